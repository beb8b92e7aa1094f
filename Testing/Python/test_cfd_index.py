# SPDX-License-Identifier: BSD-3-Clause
"""RefractiveIndex on synthetic fields with known answers, in pvpython:

1. grad n of a Gaussian on an anisotropic grid with a non-zero origin: equal to the central
   differences of n - 1 in world units (one-sided at the borders) to float precision, and to the
   analytic gradient within the O(h^2) bound of central differences;
2. the same Gaussian as an unstructured grid, resampled onto an image: the values, the automatic
   dimensions, sampling bounds larger than the data and the three ambient modes;
3. every model through the filter against ../../../shared/ORACLES.md: Ciddor (the 633 nm rows, to
   1e-9 in n, T in Celsius and p in kPa), ideal-gas helium/air by mixture fraction and by species,
   Gladstone-Dale mixtures, non-dimensional and gauge inputs, Passthrough of n;
4. time: a time-varying input (image and unstructured) passes its time steps and each update
   computes that step.

Run: pvpython test_cfd_index.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import cfd_testing as ct
import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_cfd_index")


def fetch(proxy, time=None):
    with st.CapturedOutput() as out:
        if time is None:
            proxy.UpdatePipeline()
        else:
            proxy.UpdatePipeline(time)
        data = sm.Fetch(proxy)
    T.check("ERROR" not in out.text, "%s: no error%s" % (proxy.GetXMLName(), "" if "ERROR" not in out.text
                                                          else ": " + out.text.strip()[:400]))
    return data


# --- 1. grad n of a Gaussian, anisotropic spacing, non-zero origin --------------------------------
A, S = 1e-4, 0.25
C = np.array([0.83, 0.07, 1.31])
BOUNDS = [0.2, 1.4, -0.5, 0.4, 1.0, 1.6]
DIMS = [61, 31, 13]  # spacing 0.02, 0.03, 0.05
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=DIMS, Bounds=BOUNDS, Amplitude=A,
                        Width=S, Center=list(C))
index = RefractiveIndex(Input=scene, Model="Passthrough")
index.InputArray = ["POINTS", "n_minus_1"]
out = fetch(index)
h = np.array(out.GetSpacing())
o = np.array(out.GetOrigin())
T.close(h, [0.02, 0.03, 0.05], 1e-12, "anisotropic spacing 0.02, 0.03, 0.05")
T.close(o, [0.2, -0.5, 1.0], 1e-12, "origin (0.2, -0.5, 1.0)")
n1, g = ct.grid_arrays(out, "n_minus_1", "grad_n")
nz, ny, nx = n1.shape
z, y, x = np.meshgrid(o[2] + h[2] * np.arange(nz), o[1] + h[1] * np.arange(ny),
                      o[0] + h[0] * np.arange(nx), indexing="ij")
r2 = (x - C[0]) ** 2 + (y - C[1]) ** 2 + (z - C[2]) ** 2
exact = A * np.exp(-r2 / S ** 2)
T.close(n1, exact, 1e-10, "n - 1 of the scene is the Gaussian at the grid points")

# (a) The discrete formula, axis by axis (numpy.gradient: central inside, one-sided at the edges).
for a, axis in ((0, 2), (1, 1), (2, 0)):
    numeric = np.gradient(n1, h[a], axis=axis, edge_order=1)
    T.close(g[..., a], numeric, 1e-7 * 2 * A / S,
            "grad_n[%d] = central differences in world units (spacing %.2f)" % (a, h[a]))
# (b) The analytic gradient, inside: |error| <= h^2/6 max|d3n/dx3| = h^2/6 * A * 3.59 / s^3 ...
# (max |d3/du3 exp(-u^2)| = 3.587 at u = 0 +- ... for the 1D Gaussian; the other factors are <= 1).
analytic = [-2.0 * (x - C[0]) / S ** 2 * exact, -2.0 * (y - C[1]) / S ** 2 * exact,
            -2.0 * (z - C[2]) / S ** 2 * exact]
u = np.linspace(-4, 4, 80001)
d3max = np.max(np.abs((-8 * u ** 3 + 12 * u) * np.exp(-u ** 2)))
inner = (slice(1, -1), slice(1, -1), slice(1, -1))
gmax = math.sqrt(2.0) * A / S * math.exp(-0.5)  # the largest |grad n|
for a in range(3):
    err = np.max(np.abs(g[..., a][inner] - analytic[a][inner]))
    bound = h[a] ** 2 / 6.0 * A * d3max / S ** 3
    T.check(err <= bound * 1.05 + 1e-6 * gmax,
            "grad_n[%d] against the analytic gradient: max error %.3g = %.2f %% of max|grad n| "
            "(O(h^2) bound %.3g)" % (a, err, 100 * err / gmax, bound))
# (c) Positions: the steepest point along x through the centre is at C_x - s / sqrt(2).
j = int(round((C[1] - o[1]) / h[1]))
k = int(round((C[2] - o[2]) / h[2]))
xs = o[0] + h[0] * np.argmax(g[k, j, :, 0])
T.check(abs(xs - (C[0] - S / math.sqrt(2))) <= h[0],
        "largest grad_n_x at x = %.3f, analytic %.3f (one voxel %.2f)" % (xs, C[0] - S / math.sqrt(2), h[0]))

# --- 2. The Gaussian as an unstructured grid, resampled ------------------------------------------
background = PythonCalculator(Input=scene, Expression="n_minus_1 + 2.7e-4", ArrayName="n1_bg")
unstructured = MergeBlocks(Input=background)
data = fetch(unstructured)
T.check(data.GetClassName() == "vtkUnstructuredGrid", "the input is a %s" % data.GetClassName())
same = RefractiveIndex(Input=unstructured, Model="Passthrough", SamplingDimensions=DIMS)
same.InputArray = ["POINTS", "n1_bg"]
rs = fetch(same)
T.check(rs.GetClassName() == "vtkImageData" and list(rs.GetDimensions()) == DIMS,
        "resampled: a vtkImageData of %s points" % (rs.GetDimensions(),))
T.close(rs.GetOrigin(), o, 1e-5, "resampled: origin at the data's bounds (pulled in by 1e-6)")
rn1, rg = ct.grid_arrays(rs, "n_minus_1", "grad_n")
T.close(rn1, exact + 2.7e-4, 1e-3 * A, "resampled n - 1 = the Gaussian + 2.7e-4 (1e-3 A)")
T.close(rg, g, 2e-3 * gmax, "resampled grad_n = the image's (2e-3 of max|grad n|)")
T.check(ct.field_value(rs, "valid_point_fraction") == 1.0, "every point found inside the cells")

auto = RefractiveIndex(Input=unstructured, Model="Passthrough", AutomaticDimension=61)
auto.InputArray = ["POINTS", "n1_bg"]
ra = fetch(auto)
T.check(list(ra.GetDimensions()) == [61, 46, 31],
        "automatic dimensions of a 1.2 x 0.9 x 0.6 box, 61 along x: %s (expected 61 46 31)" % (ra.GetDimensions(),))
T.close(ra.GetSpacing(), [0.02, 0.02, 0.02], 1e-6, "automatic spacing isotropic (0.02)")

# Sampling bounds larger than the data: points outside get the ambient index, never 0.
big = [0.0, 1.6, -0.7, 0.6, 0.8, 1.8]
gmax_bg = gmax
for mode in ("Extend", "DomainEdgeMedian", "Value"):
    p = RefractiveIndex(Input=unstructured, Model="Passthrough", UseSamplingBounds=1, SamplingBounds=big,
                        SamplingDimensions=[65, 53, 41], AmbientMode=mode, AmbientValue=2.5e-4)
    p.InputArray = ["POINTS", "n1_bg"]
    r = fetch(p)
    n, gr, mask = ct.grid_arrays(r, "n_minus_1", "grad_n", "vtkValidPointMask")
    valid = mask > 0
    frac = ct.field_value(r, "valid_point_fraction")
    T.check(0.2 < frac < 0.9 and abs(frac - valid.mean()) < 1e-12,
            "%s: %.0f %% of the points inside the data" % (mode, 100 * frac))
    T.check(np.isfinite(n).all() and n.min() > 2.0e-4,
            "%s: n - 1 everywhere in [%.3g, %.3g], never 0" % (mode, n.min(), n.max()))
    inv = ~valid
    if mode == "Extend":
        T.check(ct.field_value(r, "ambient_n_minus_1") is None, "Extend: no single ambient value")
        gm = np.abs(gr).max()
        T.check(gm <= 1.1 * gmax_bg, "Extend: no false edge, max|grad_n| %.3g <= 1.1 x the flow's %.3g" % (gm, gmax_bg))
    else:
        amb = ct.field_value(r, "ambient_n_minus_1")
        if mode == "Value":
            expected = 2.5e-4
        else:
            # The valid points with an invalid neighbour along x, y or z.
            pad = np.pad(inv, 1, constant_values=False)
            touch = np.zeros_like(inv)
            for ax in range(3):
                for sh in (-1, 1):
                    touch |= np.roll(pad, sh, axis=ax)[1:-1, 1:-1, 1:-1]
            expected = float(np.median(n[valid & touch].astype(np.float32)))
        T.close(amb, expected, 1e-12, "%s: ambient n - 1 = %.6g" % (mode, expected))
        T.close(n[inv], amb, 1e-10, "%s: every outside point holds it" % mode)

# --- 3. The models against ORACLES.md ------------------------------------------------------------
def image(columns, **extra):
    """An n x 2 x 2 image whose x columns hold the given values (each array a list of n)."""
    n = len(next(iter(columns.values())))
    arrays = {k: np.tile(np.asarray(v, dtype=np.float32), (2, 2, 1)) for k, v in columns.items()}
    return ct.producer(globals(), ct.make_image((n, 2, 2), (0, 0, 0), (1, 1, 1), arrays))


def index_of(src, **props):
    arrays = props.pop("arrays", {})
    p = RefractiveIndex(Input=src, **props)
    for prop, name in arrays.items():
        setattr(p, prop, ["POINTS", name])
    return ct.grid_arrays(fetch(p), "n_minus_1")[0][0, 0]


rows = [(20, 101.325, 0, 1.000271800), (20, 60, 0, 1.000160924), (50, 100, 0, 1.000243285),
        (-40, 100, 0, 1.000337580), (50, 120, 100, 1.000287924)]
ciddor_src = image({"t_C": [r[0] for r in rows], "p_kPa": [r[1] for r in rows],
                    "RH": [r[2] / 100.0 for r in rows]})
n = index_of(ciddor_src, Model="Ciddor", TemperatureUnit="Celsius", PressureUnit="kPa",
             HumidityFromArray=1, Wavelength=633.0,
             arrays={"TemperatureArray": "t_C", "PressureArray": "p_kPa", "HumidityArray": "RH"})
T.close(1.0 + n, [r[3] for r in rows], 1e-9, "Ciddor, ORACLES rows at 633 nm (C, kPa, RH array)")
n = index_of(ciddor_src, Model="Ciddor", TemperatureUnit="Celsius", PressureUnit="kPa", Humidity=0.0,
             Wavelength=633.0, arrays={"TemperatureArray": "t_C", "PressureArray": "p_kPa"})
T.close(1.0 + n[:4], [r[3] for r in rows[:4]], 1e-9, "Ciddor, dry rows with the constant humidity 0")

he_src = image({"T": [293.15] * 3, "p": [101325.0] * 3, "f": [0.0, 0.5, 1.0], "rho": [1.20407, 0.29238, 0.166454],
                "Y_He": [0.0, 0.5, 1.0], "Y_air": [1.0, 0.5, 0.0]})
oracle = np.array([2.7164e-4, 6.1546e-5, 3.2513e-5])
n = index_of(he_src, Model="IdealGas", IdealGasComposition="MixtureFraction",
             arrays={"TemperatureArray": "T", "PressureArray": "p", "MixtureFractionArray": "f"})
T.close(n, oracle, 0.5e-8, "IdealGas helium/air by mixture fraction: %s (ORACLES %s)" % (n, oracle))
n = index_of(he_src, Model="IdealGas", IdealGasComposition="Species", NumberOfSpecies=1,
             SpeciesGases=[1, 8, 1, 5], BalanceGas="Air",
             arrays={"TemperatureArray": "T", "PressureArray": "p", "Species1Array": "Y_He"})
T.close(n, oracle, 0.5e-8, "IdealGas helium + balance air by species")
n = index_of(he_src, Model="IdealGas", IdealGasComposition="Species", NumberOfSpecies=2,
             SpeciesGases=[1, -1, 1, 5], SpeciesGladstoneDale=[0, 0.2256e-3, 0, 0],
             SpeciesMolarMass=[0, 28.9641e-3, 0, 0], BalanceGas="None",
             arrays={"TemperatureArray": "T", "PressureArray": "p", "Species1Array": "Y_He",
                     "Species2Array": "Y_air"})
T.close(n, oracle, 0.5e-8, "IdealGas helium + typed air, no balance gas")
n = index_of(he_src, Model="GladstoneDaleMixture", MixtureComposition="MixtureFraction",
             arrays={"InputArray": "rho", "MixtureFractionArray": "f"})
T.close(n[1], 6.1546e-5, 0.5e-8, "GladstoneDaleMixture at rho = 0.29238 kg/m^3, f = 0.5")
n = index_of(he_src, Model="GladstoneDale", Gas="He", arrays={"InputArray": "rho"})
T.close(n, 0.1954e-3 * np.array([1.20407, 0.29238, 0.166454]), 1e-10, "GladstoneDale with He from the table")

nd_src = image({"T_nd": [1.0, 1.0], "p_nd": [1.0, 1.0], "p_gauge_atm": [0.0, 0.0], "T_K": [293.15, 293.15],
                "n": [1.0002716, 1.0002716]})
n = index_of(nd_src, Model="IdealGas", Gas="Air", TemperatureReference=293.15, PressureReference=101325.0,
             arrays={"TemperatureArray": "T_nd", "PressureArray": "p_nd"})
T.close(n, 2.7164e-4, 0.5e-8, "IdealGas air from non-dimensional T and p (references 293.15 K, 101325 Pa)")
n = index_of(nd_src, Model="IdealGas", Gas="Air", PressureUnit="atm", PressureOffset=1.0,
             arrays={"TemperatureArray": "T_K", "PressureArray": "p_gauge_atm"})
T.close(n, 2.7164e-4, 0.5e-8, "IdealGas air from a gauge pressure 0 atm + offset 1 atm")
n = index_of(nd_src, Model="Passthrough", PassthroughHoldsN=1, arrays={"InputArray": "n"})
T.close(n, 2.716e-4, 1e-7, "Passthrough of n (float n keeps ~1e-7 of n - 1)")

# --- 4. Time ---------------------------------------------------------------------------------------
INFO = """
executive = self.GetExecutive()
info = executive.GetOutputInformation(0)
info.Set(executive.WHOLE_EXTENT(), 0, 7, 0, 5, 0, 4)
info.Remove(executive.TIME_STEPS())
for t in (0.0, 1.0, 2.0):
    info.Append(executive.TIME_STEPS(), t)
info.Remove(executive.TIME_RANGE())
info.Append(executive.TIME_RANGE(), 0.0)
info.Append(executive.TIME_RANGE(), 2.0)
"""
SCRIPT = """
import numpy as np
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersCore import vtkAppendFilter
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as SDDP
from vtkmodules.util.numpy_support import numpy_to_vtk
info = self.GetOutputInformation(0)
t = info.Get(SDDP.UPDATE_TIME_STEP()) if info.Has(SDDP.UPDATE_TIME_STEP()) else 0.0
img = vtkImageData()
img.SetExtent(0, 7, 0, 5, 0, 4)
img.SetSpacing(0.1, 0.1, 0.1)
x = 0.1 * np.tile(np.arange(8), 6 * 5)
a = numpy_to_vtk((1e-4 * (1.0 + t) * (1.0 + x)).astype(np.float32), deep=1)
a.SetName("n1")
img.GetPointData().AddArray(a)
out = self.GetOutput()
if out.IsA("vtkImageData"):
    out.ShallowCopy(img)
else:
    app = vtkAppendFilter()
    app.AddInputData(img)
    app.Update()
    out.ShallowCopy(app.GetOutput())
"""
for kind in ("vtkImageData", "vtkUnstructuredGrid"):
    src = ProgrammableSource(OutputDataSetType=kind, Script=SCRIPT, ScriptRequestInformation=INFO)
    p = RefractiveIndex(Input=src, Model="Passthrough", SamplingDimensions=[8, 6, 5])
    p.InputArray = ["POINTS", "n1"]
    p.UpdatePipelineInformation()
    from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as SDDP
    steps = p.GetClientSideObject().GetOutputInformation(0).Get(SDDP.TIME_STEPS())
    T.check(steps is not None and list(steps) == [0.0, 1.0, 2.0],
            "%s: RefractiveIndex passes the time steps %s" % (kind, steps))
    for t in (0.0, 2.0, 1.0):
        v = ct.grid_arrays(fetch(p, t), "n_minus_1")[0]
        T.close(v[0, 0, 0], 1e-4 * (1.0 + t), 1e-9, "%s at t = %g: n - 1 at x = 0 is 1e-4 (1 + t)" % (kind, t))
        T.close(v[0, 0, -1], 1e-4 * (1.0 + t) * 1.7, 1e-9, "%s at t = %g: n - 1 at x = 0.7" % (kind, t))

T.finish()
