# SPDX-License-Identifier: BSD-3-Clause
"""RefractiveIndex on bad CFD input: every case gives an error (or a warning) that names
the array, the number of points and what to do; the output is empty after an error, ParaView
survives, and fixing the property recovers. The process exits 0.

Run: pvpython test_cfd_errors.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import cfd_testing as ct
import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_cfd_errors")


def run(proxy):
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy)
    return data, out.text


def expect_error(proxy, case, *phrases):
    data, text = run(proxy)
    points = data.GetNumberOfPoints() if data is not None else 0
    missing = [p for p in phrases if p not in text]
    T.check("ERROR" in text and not missing,
            "%s: an error naming %s%s" % (case, ", ".join(repr(p) for p in phrases),
                                         "" if not missing else " (missing %s; got: %s)" % (missing, text.strip()[:700])))
    T.check(points == 0, "%s: the output is empty (%d points)" % (case, points))
    lines = [l for l in text.splitlines() if "vtkRefractiveIndex" in l or l.startswith("vtk")]
    print("     reported: %s" % (text[text.find("vtkRefractiveIndex"):][:400].replace("\n", " ") if "vtkRefractiveIndex" in text else "(nothing)"))


def expect_ok(proxy, case, *warnings):
    data, text = run(proxy)
    missing = [p for p in warnings if p not in text]
    T.check("ERROR" not in text and data.GetNumberOfPoints() > 0,
            "%s: no error, %d points%s" % (case, data.GetNumberOfPoints(), "" if "ERROR" not in text else ": " + text[:400]))
    if warnings:
        T.check("Warning" in text and not missing,
                "%s: a warning naming %s%s" % (case, ", ".join(repr(p) for p in warnings),
                                              "" if not missing else " (got: %s)" % text.strip()[:500]))
    return data


# A 6 x 4 x 3 image of temperature (K), pressure (Pa), density, fractions; bad values at known points.
shape = (3, 4, 6)
n = 6 * 4 * 3
good = {
    "Temp": np.full(shape, 300.0), "Pres": np.full(shape, 101325.0), "Density": np.full(shape, 1.2),
    "Y_H2": np.full(shape, 0.9), "Y_CH4": np.full(shape, 0.1), "V": None,
}


def source(**changes):
    arrays = {k: v.copy() for k, v in good.items() if v is not None}
    for name, (index, value) in changes.items():
        flat = arrays[name].reshape(-1)
        for i in np.atleast_1d(index):
            flat[i] = value
    img = ct.make_image((6, 4, 3), (0, 0, 0), (0.1, 0.1, 0.1), arrays)
    from vtkmodules.util.numpy_support import numpy_to_vtk
    v = numpy_to_vtk(np.zeros((n, 3), dtype=np.float32), deep=1)
    v.SetName("V")
    img.GetPointData().AddArray(v)
    return ct.producer(globals(), img)


def ideal_gas(src, t="Temp", p="Pres", **props):
    props.setdefault("Gas", "Air")
    f = RefractiveIndex(Input=src, Model="IdealGas", **props)
    f.TemperatureArray = ["POINTS", t]
    f.PressureArray = ["POINTS", p]
    return f


base = source()
# 1. Missing arrays: the error lists the arrays that are there.
expect_error(ideal_gas(base, t="T"), "IdealGas with no array 'T'",
             "temperature", "'T'", "TemperatureArray", "Point arrays present", "Temp", "Pres", "Density")
expect_error(ideal_gas(base, t="Pres"), "the same array for temperature and pressure",
             "temperature and pressure arrays are both 'Pres'")
vector = RefractiveIndex(Input=base, Model="GladstoneDale")
vector.InputArray = ["POINTS", "V"]
expect_error(vector, "a 3-component density", "'V'", "3 components")

# 2. NaN / Inf: the array, how many points, the first one.
expect_error(ideal_gas(source(Temp=([5, 7, 9], float("nan")))), "NaN temperature",
             "'Temp'", "3 of 72 points", "NaN or infinite", "index 5")
gd_inf = RefractiveIndex(Input=source(Density=(4, float("inf"))), Model="GladstoneDale")
gd_inf.InputArray = ["POINTS", "Density"]
expect_error(gd_inf, "Inf density", "'Density'", "1 of 72 points is NaN or infinite", "index 4")

# 3. Zero or negative temperature, pressure, density.
expect_error(ideal_gas(source(Temp=([1, 2], -10.0))), "negative temperature",
             "'Temp'", "2 of 72 points", "absolute zero", "kelvin")
expect_error(ideal_gas(source(Temp=(3, 10.0)), TemperatureUnit="Celsius", TemperatureReference=-30.0),
             "a negative reference", "reference", "positive")
expect_error(ideal_gas(source(Pres=(0, 0.0))), "zero pressure",
             "'Pres'", "1 of 72 points is not positive", "PressureOffset")
gd_neg = RefractiveIndex(Input=source(Density=([0, 1, 2, 3], -0.1)), Model="GladstoneDale")
gd_neg.InputArray = ["POINTS", "Density"]
expect_error(gd_neg, "negative density", "'Density'", "4 of 72 points are negative", "DensityReference")
gd_zero = RefractiveIndex(Input=source(Density=([0, 1], 0.0)), Model="GladstoneDale")
gd_zero.InputArray = ["POINTS", "Density"]
expect_ok(gd_zero, "zero density is a warning", "'Density'", "2 of 72 points are 0", "vacuum")

# 4. Mass fractions: not summing to 1 without a balance gas; above 1 with one.
def species(src, balance, count=2):
    f = RefractiveIndex(Input=src, Model="IdealGas", IdealGasComposition="Species", NumberOfSpecies=count,
                        SpeciesGases=[6, 8, 1, 5], BalanceGas=balance)
    f.TemperatureArray = ["POINTS", "Temp"]
    f.PressureArray = ["POINTS", "Pres"]
    f.Species1Array = ["POINTS", "Y_H2"]
    f.Species2Array = ["POINTS", "Y_CH4"]
    return f


expect_ok(species(base, "None"), "H2 0.9 + CH4 0.1 sum to 1")
expect_error(species(source(Y_CH4=([3, 8, 13], 0.05)), "None"), "species summing to 0.95, no balance gas",
             "'Y_H2'", "'Y_CH4'", "3 of 72 points", "do not sum to 1", "sum 0.95", "balance gas")
expect_error(species(source(Y_CH4=(6, 0.3)), "N2"), "species summing above 1",
             "'Y_H2'", "'Y_CH4'", "1 of 72 points", "sum above 1", "(N2)")
expect_error(species(source(Y_H2=(2, 1.5)), "N2"), "a mass fraction of 1.5",
             "'Y_H2'", "mass fraction of H2", "outside [0, 1]", "index 2")

# 5. Ciddor outside its range; a custom gas without its constants.
cid = RefractiveIndex(Input=base, Model="Ciddor", Wavelength=200.0)
cid.TemperatureArray = ["POINTS", "Temp"]
cid.PressureArray = ["POINTS", "Pres"]
expect_error(cid, "Ciddor at 200 nm", "wavelength", "300-1700 nm")
custom = ideal_gas(base, Gas="Custom", MolarMass=0.0)
expect_error(custom, "a custom gas with M = 0", "custom gas", "molar mass")

# 6. Resampling: a data set with no points; sampling bounds that miss the data.
sphere = Sphere()
nothing = Threshold(Input=Elevation(Input=sphere), Scalars=["POINTS", "Elevation"], LowerThreshold=5,
                    UpperThreshold=6)
expect_error(RefractiveIndex(Input=nothing), "an empty data set", "no points")
cells = Delaunay3D(Input=Elevation(Input=sphere))
away = RefractiveIndex(Input=cells, Model="Passthrough", UseSamplingBounds=1, SamplingBounds=[10, 11, 10, 11, 10, 11],
                       SamplingDimensions=[8, 8, 8])
away.InputArray = ["POINTS", "Elevation"]
expect_error(away, "sampling bounds away from the data", "No point of the sampling grid", "SamplingBounds")
table_like = RefractiveIndex(Input=cells, Model="IdealGas", SamplingDimensions=[16, 16, 16])
table_like.TemperatureArray = ["POINTS", "Temperature"]
table_like.PressureArray = ["POINTS", "Pressure"]
expect_error(table_like, "missing arrays after resampling", "'Temperature'", "Elevation")

# 7. Fixing the property recovers on the same proxy.
fixed = ideal_gas(source(Temp=([1, 2], -10.0)))
run(fixed)
fixed.TemperatureArray = ["POINTS", "Pres"]
fixed.PressureArray = ["POINTS", "Temp"]
expect_error(fixed, "still wrong (arrays swapped)", "'Temp'")
fixed.Input = base
fixed.TemperatureArray = ["POINTS", "Temp"]
fixed.PressureArray = ["POINTS", "Pres"]
data = expect_ok(fixed, "recovered with the right input")
v = ct.grid_arrays(data, "n_minus_1")[0]
T.close(v, ct.ideal_gas_n1(300.0, 101325.0), 1e-10, "recovered: air at 300 K, 1 atm")

T.finish()
