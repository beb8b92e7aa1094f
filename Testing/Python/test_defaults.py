# SPDX-License-Identifier: BSD-3-Clause
"""RefractiveIndex's defaults and its handling of arrays, the same on every input type, in pvpython:

1. the GUI/pvpython default of every array property is '(automatic)', also for a RefractiveIndex
   created after a SchlierenImage (whose `intensity` array used to become the default of a filter
   on another input) and before its input was updated;
2. Model Automatic: a density gives GladstoneDale (n - 1 = K_air rho), temperature and pressure
   IdealGas (K p M / (R T), air), n_minus_1 Passthrough, n Passthrough of n; it says so (text and
   the field data index_model); an input with none of those names is an error listing its arrays;
3. Passthrough on a density (values far above 0.1) is an error naming the array, its range and
   GladstoneDale;
4. cell arrays become point arrays (vtkCellDataToPointData) on images and on unstructured grids
   alike, and the filter says so; integer arrays and ids (ObjectId) are refused with their name.

Run: pvpython test_defaults.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so
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
T = st.Checker("test_defaults")
K_AIR, M_AIR = ct.GASES["Air"]
AUTO = "(automatic)"


def run(proxy):
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy)
    return data, out.text


def field_string(data, name):
    a = data.GetFieldData().GetAbstractArray(name)
    return a.GetValue(0) if a is not None else None


def ok(proxy, case):
    data, text = run(proxy)
    T.check("ERROR" not in text, "%s: no error%s" % (case, "" if "ERROR" not in text else ": " + text.strip()[:500]))
    return data, text


def refused(proxy, case, *phrases):
    data, text = run(proxy)
    missing = [p for p in phrases if p not in text]
    T.check("ERROR" in text and not missing, "%s: an error naming %s%s" % (
        case, ", ".join(repr(p) for p in phrases), "" if not missing else " (got: %s)" % text.strip()[:600]))
    T.check(data is None or data.GetNumberOfPoints() == 0, "%s: empty output" % case)
    lines = [l for l in text.splitlines() if l.startswith("vtkRefractiveIndex (")]
    print("     said: %s" % (lines[0].split("): ", 1)[-1][:300] if lines else "(nothing)"))


DIMS = (12, 10, 8)
rng = np.random.default_rng(7)
shape = DIMS[::-1]
rho = (1.0 + 0.3 * rng.random(shape)).astype(np.float32)
temp = (280.0 + 40.0 * rng.random(shape)).astype(np.float32)
pres = (9e4 + 2e4 * rng.random(shape)).astype(np.float32)

# --- 1. the array defaults, after a SchlierenImage in the same session -----------------------------
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[24, 24, 24])
first = RefractiveIndex(Input=scene)
image = SchlierenImage(Input=first, Resolution=[16, 16], Passes=1)
image.UpdatePipeline()
density_src = ct.producer(globals(), ct.make_image(DIMS, (0, 0, 0), (0.1, 0.1, 0.1), {"Density": rho}))
SetActiveSource(image)  # the GUI's and pvpython's active source is the image
second = RefractiveIndex(Input=density_src)
upstream = ["Density", AUTO]
for prop in ("InputArray", "TemperatureArray", "PressureArray", "MixtureFractionArray"):
    value = getattr(second, prop)
    T.check(value[1] in upstream, "second RefractiveIndex after a SchlierenImage: %s defaults to %s (an upstream "
            "array or (automatic), not intensity)" % (prop, list(value)))
fresh = RefractiveIndex(Input=RefractiveScene(Scene="GaussianSphere", Dimensions=[8, 8, 8]))
T.check(fresh.InputArray[1] == AUTO and fresh.Model == "Automatic",
        "a RefractiveIndex on a not yet updated input: InputArray %s, Model %s" % (list(fresh.InputArray), fresh.Model))
data, text = ok(second, "second RefractiveIndex")
n1 = ct.grid_arrays(data, "n_minus_1")[0]
T.close(n1, K_AIR * rho, 1e-9, "Automatic on Density: GladstoneDale, n - 1 = K_air rho")
T.check(field_string(data, "index_model") == "GladstoneDale" and "GladstoneDale" in text and "Density" in text,
        "Automatic says it chose GladstoneDale on Density (field data index_model %r)" % field_string(data, "index_model"))
for p in (second, fresh, image, first):
    Delete(p)

# --- 2. the other automatic choices ---------------------------------------------------------------
tp = ct.producer(globals(), ct.make_image(DIMS, (0, 0, 0), (0.1, 0.1, 0.1), {"Temp": temp, "Pres": pres, "V": rho}))
index = RefractiveIndex(Input=tp)
data, text = ok(index, "Automatic on Temp, Pres")
n1 = ct.grid_arrays(data, "n_minus_1")[0]
expected = K_AIR * pres.astype(float) * M_AIR / (ct.R * temp.astype(float))
T.close(n1 / expected.max(), expected / expected.max(), 1e-6, "Automatic on Temp and Pres: IdealGas, n - 1 = K p M / (R T)")
T.check(field_string(data, "index_model") == "IdealGas" and "'Temp'" in text and "'Pres'" in text,
        "Automatic says IdealGas with Temp and Pres")
Delete(index)

n_src = ct.producer(globals(), ct.make_image(DIMS, (0, 0, 0), (0.1, 0.1, 0.1), {"n": 1.0 + K_AIR * rho}))
index = RefractiveIndex(Input=n_src)
data, text = ok(index, "Automatic on n")
T.close(ct.grid_arrays(data, "n_minus_1")[0], K_AIR * rho, 2e-7, "Automatic on an array named n: Passthrough of n")
Delete(index)

nothing = ct.producer(globals(), ct.make_image(DIMS, (0, 0, 0), (0.1, 0.1, 0.1), {"q": rho, "w": temp}))
index = RefractiveIndex(Input=nothing)
refused(index, "Automatic without a known name", "Automatic", "q, w", "Choose the Model")
Delete(index)

# --- 3. Passthrough on a density ------------------------------------------------------------------
index = RefractiveIndex(Input=density_src, Model="Passthrough")
index.InputArray = ["POINTS", "Density"]
refused(index, "Passthrough on a density", "'Density'", "GladstoneDale", "%.6g" % rho.max())
Delete(index)

# --- 4. cell arrays and ids, on an image and on an unstructured grid -----------------------------
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersCore import vtkCellDataToPointData
from vtkmodules.util.numpy_support import numpy_to_vtk

cells = vtkImageData()
cells.SetDimensions(*DIMS)
cells.SetSpacing(0.1, 0.1, 0.1)
ncell = cells.GetNumberOfCells()
crho = numpy_to_vtk((1.0 + 0.3 * rng.random(ncell)).astype(np.float32), deep=1)
crho.SetName("density")
cells.GetCellData().AddArray(crho)
ids = numpy_to_vtk(np.arange(ncell, dtype=np.int32), deep=1)
ids.SetName("ObjectId")
cells.GetCellData().AddArray(ids)
fake = numpy_to_vtk(np.ones(ncell, dtype=np.float32), deep=1)
fake.SetName("GlobalElementId")
cells.GetCellData().AddArray(fake)
c2p = vtkCellDataToPointData()
c2p.SetInputData(cells)
c2p.Update()
averaged = dsa.WrapDataObject(c2p.GetOutput()).PointData["density"]
expected = K_AIR * np.asarray(averaged, dtype=float).reshape(shape)
cell_image = ct.producer(globals(), cells)
unstructured = MergeBlocks(Input=cell_image)
for src, kind in ((cell_image, "image"), (unstructured, "unstructured grid")):
    index = RefractiveIndex(Input=src, Model="GladstoneDale", SamplingDimensions=list(DIMS))
    index.InputArray = ["CELLS", "density"]
    data, text = ok(index, "cell density on an %s" % kind)
    T.check("converted to point data" in text and "density" in text,
            "%s: says the cell array density was converted to point data" % kind)
    n1 = ct.grid_arrays(data, "n_minus_1")[0]
    # (the unstructured grid is resampled over its bounds pulled in by 1e-6: 1e-5 of the values)
    T.close(n1, expected, 1e-5 * expected.max(), "%s: n - 1 = K x the cell density averaged to the points "
            "(vtkCellDataToPointData)" % kind)
    Delete(index)
    for name in ("ObjectId", "GlobalElementId"):
        index = RefractiveIndex(Input=src, Model="GladstoneDale", SamplingDimensions=list(DIMS))
        index.InputArray = ["CELLS", name]
        refused(index, "%s as density on an %s" % (name, kind), "'%s'" % name, "id")
        Delete(index)

T.finish()
