# SPDX-License-Identifier: BSD-3-Clause
"""What the filters say, checked for its text: the weak-field warning (a deflection below what a
laboratory bench resolves) with the causes and the properties to set, the automatic scale's
full-contrast deflection, Model Automatic's note in plain words (the gas, the units, PLOT3D's
non-dimensional density), the Resolution error, each said once per update (RefractiveIndex's notes once
per settings, not again at each time step), and the domains the GUI's
sliders and fields use. The reactor and the blunt fin come from ../shared/data (skipped there, with a
message, where it is absent). The process exits 0.

Run: pvpython test_messages.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import cfd_testing as ct
import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_messages")
WEAK = "below the about 1e-07 rad that a sensitive laboratory schlieren bench resolves"


def field(data, name):
    a = data.GetFieldData().GetAbstractArray(name)
    if a is None or not a.GetNumberOfValues():
        return None
    return repr(a.GetValue(0)) if a.IsNumeric() else a.GetValue(0)


def update(proxy):
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
    return sm.Fetch(proxy), out.text


# --- 1. a field a bench would see: no weak-field warning; the scale's full-contrast deflection --
sphere = RefractiveScene(Scene="GaussianSphere", Dimensions=[32, 32, 32])
image = SchlierenImage(Input=sphere, Resolution=[32, 32], Passes=1, Backend="CPU", Cutoff="KnifeEdge")
data, text = update(image)
k, full, top = (float(field(data, n)) for n in ("cutoff_scale", "full_contrast_deflection", "max_deflection"))
T.check(WEAK not in text and WEAK not in field(data, "warnings"),
        "the Gaussian sphere (largest deflection %.3g rad): no weak-field warning" % top)
T.close(full * k, 0.5, 1e-12, "knife edge: full_contrast_deflection %.4g rad = 0.5 / cutoff_scale" % full)
T.check(full <= top * (1 + 1e-6), "the knife's full-contrast deflection %.4g is at most the largest |e| %.4g" % (full, top))
image.Cutoff = "Circular"
data, _ = update(image)
T.close(float(field(data, "full_contrast_deflection")) * float(field(data, "cutoff_scale")), 1.0, 1e-12,
        "circular stop: full_contrast_deflection = 1 / cutoff_scale")
image.Cutoff = "Shadowgraph"
data, _ = update(image)
T.check(float(field(data, "full_contrast_deflection")) == 0.0, "shadowgraph: no scale, full_contrast_deflection 0")
Delete(image)
uniform = RefractiveScene(Scene="Uniform", Dimensions=[16, 16, 16], Amplitude=2.7e-4)
image = SchlierenImage(Input=uniform, Resolution=[16, 16], Passes=1, Backend="CPU")
data, text = update(image)
T.check(float(field(data, "max_deflection")) == 0.0 and WEAK not in text,
        "a uniform field bends nothing (max_deflection 0) and is not warned of as weak")

# --- 2. the Resolution error: the property, the value, the least allowed; once per update ---------
for res in ([1, 1], [1, 16], [16, 0]):
    image.Resolution = res
    data, text = update(image)
    wanted = "Resolution is %d x %d pixels: each side must be 2 to 16384 pixels (at least 2 x 2)." % tuple(res)
    T.check(text.count(wanted) == 1 and data.GetNumberOfPoints() == 0,
            "Resolution %s: the error %r, said once (%d times), no image" % (res, wanted, text.count(wanted)))
image.Resolution = [2, 2]
data, text = update(image)
T.check(data.GetNumberOfPoints() == 4 and "ERROR" not in text, "Resolution 2 x 2 traces (%d points)" % data.GetNumberOfPoints())
Delete(image)

# --- 3. the domains the GUI uses ------------------------------------------------------------------
probe = SchlierenImage(Input=uniform)
r = probe.GetProperty("Resolution").GetDomain("range")
T.check(r.GetMinimum(0) == 2 and r.GetMinimum(1) == 2, "Resolution's domain starts at 2 x 2 (%d, %d)" % (r.GetMinimum(0), r.GetMinimum(1)))
w = probe.GetProperty("Wavelength").GetDomain("range")
T.check(w.GetMinimum(0) == 100, "SchlierenImage's Wavelength slider starts at %g nm, not 0" % w.GetMinimum(0))
index_probe = RefractiveIndex(Input=uniform)
w = index_probe.GetProperty("Wavelength").GetDomain("range")
T.check(w.GetMinimum(0) == 100, "RefractiveIndex's Wavelength slider starts at %g nm, not 0" % w.GetMinimum(0))
Delete(index_probe)
Delete(probe)

# --- 3b. RefractiveIndex's notes: said once per settings, not again at every time step (issue 49) --
blast = RefractiveScene(Scene="BlastWave", Dimensions=[16, 16, 16], TimeSteps=3)
index = RefractiveIndex(Input=blast)
times = list(blast.TimestepValues)
said = []
for t in times[:2]:
    with st.CapturedOutput() as out:
        index.UpdatePipeline(t)
    said.append(out.text.count("Model Automatic chose"))
index.Wavelength = 589.0  # a new setting: the choice is said again
with st.CapturedOutput() as out:
    index.UpdatePipeline(times[2])
said.append(out.text.count("Model Automatic chose"))
T.check(len(times) == 3 and said == [1, 0, 1],
        "Model Automatic's note: said at the first time step, not at the next, again after a property "
        "changed (%s over times %s)" % (said, times))
Delete(index)
Delete(blast)

# --- 4. the reactor's Pres read as an absolute pressure in Pa (Model Automatic) -------------------
path = os.path.join(ct.data_dir(), "disk_out_ref.ex2")
if os.path.exists(path):
    reader = ExodusIIReader(FileName=path)
    reader.PointVariables = ["Temp", "Pres", "H2"]
    index = RefractiveIndex(Input=reader, AutomaticDimension=48)
    image = SchlierenImage(Input=index, ViewDirection=[1, 0, 0], ViewUp=[0, 0, 1], Resolution=[48, 64],
                           Passes=1, Backend="CPU")
    with st.CapturedOutput() as out:
        index.UpdatePipeline()
    notes = field(sm.Fetch(index), "index_notes")
    for phrase in ("Model Automatic chose IdealGas: the input has a temperature and a pressure.",
                   "Gas: air (Gas Custom, whose defaults are air's: K = 0.0002256 m^3/kg, M = 0.0289641 kg/mol; "
                   "set Gas for another gas).",
                   "Temperature 'Temp' read in K times TemperatureReference (1), pressure 'Pres' in Pa times "
                   "PressureReference (1) plus PressureOffset (0): an absolute pressure (a gauge one needs the "
                   "operating pressure as PressureOffset)."):
        T.check(phrase in notes, "the reactor's note says %r" % phrase)
    T.check("unless set otherwise" not in notes, "the old 'air unless set otherwise' is gone")
    data, text = update(image)
    top, full, k = (float(field(data, n)) for n in ("max_deflection", "full_contrast_deflection", "cutoff_scale"))
    warnings = field(data, "warnings")
    print("     reactor as absolute Pa: max_deflection %.3g rad, cutoff_scale %.3g, full contrast at %.3g rad" % (top, k, full))
    T.check(0 < top < 1e-7, "the reactor as absolute Pa: the largest deflection %.3g rad is below 1e-7" % top)
    T.check(text.count(WEAK) == 1, "the weak-field warning is said once (%d)" % text.count(WEAK))
    expected = ("The largest deflection over the film is %g rad, %s: a real bench would show nothing here, and "
                "the automatic CutoffScale (%g) stretched %g rad to full contrast." % (top, WEAK, k, full))
    T.check(warnings.startswith(expected), "the warning: %r" % warnings[:len(expected) + 20])
    for prop in ("PressureUnit", "TemperatureUnit", "PressureOffset", "DensityReference", "PressureReference",
                 "PLOT3D's rho / rho_inf", "the Gas"):
        T.check(prop in warnings, "the warning names %r" % prop)
    # the same reactor with the gauge pressure on 1 atm (Examples/reactor.py): no such warning
    index.PressureOffset = 101325.0
    data, text = update(image)
    T.check(float(field(data, "max_deflection")) > 1e-5 and WEAK not in field(data, "warnings"),
            "with PressureOffset 101325 Pa: largest deflection %s rad, no weak-field warning" % field(data, "max_deflection"))
else:
    print("SKIP the reactor: no disk_out_ref.ex2 in %s" % ct.data_dir())

# --- 5. PLOT3D's non-dimensional density under Model Automatic ------------------------------------
xyz, q = os.path.join(ct.data_dir(), "bluntfinxyz.bin"), os.path.join(ct.data_dir(), "bluntfinq.bin")
if os.path.exists(xyz) and os.path.exists(q):
    fin = PLOT3DReader(FileName=xyz, QFileName=[q])
    index = RefractiveIndex(Input=fin, AutomaticDimension=24)
    with st.CapturedOutput():
        index.UpdatePipeline()
    notes = field(sm.Fetch(index), "index_notes")
    wanted = ("Density 'Density' read in kg/m^3 times DensityReference (1): a non-dimensional density (PLOT3D's is "
              "rho / rho_inf) needs the free-stream density in kg/m^3 as DensityReference.")
    T.check("chose GladstoneDale" in notes and wanted in notes, "the blunt fin's note: %r" % notes[-260:])
else:
    print("SKIP the blunt fin: no bluntfin*.bin in %s" % ct.data_dir())
T.finish()
