# SPDX-License-Identifier: BSD-3-Clause
"""The Python front end's inputs and errors in plain VTK (PyPI's vtk, no ParaView): what
python.python_plugin_parity checks against the C++ plugin in pvpython, here in a venv.

  - a composite input (a vtkMultiBlockDataSet holding a curvilinear grid) to RefractiveIndex gives
    one vtkImageData, bit for bit the image of the bare grid; SchlierenImage, RefractionOctree and
    NumericalSchlieren on the multiblock give an empty vtkImageData and the C++ filter's reason;
  - SchlierenImage refuses a direction matrix and an unstructured grid (the C++ filter's words);
  - an image whose extent does not start at 0 gives the film of the same points given with their
    extent from 0 (python.python_plugin_parity: that film is the C++ filter's bit for bit);
  - a failed request leaves the output empty (no image from before) and LastError says why;
  - an exception of any kind inside a request is an error message, not a traceback;
  - RefractiveIndex's IdealGas (the engine's index models) against rho = p M / (R T);
  - Symmetry Planar on a 2D image (the field extruded unchanged), Axisymmetric on a wedge with no
    axis typed (revolved about its own axis), the wedge's warning at Symmetry None.

    python test_frontend_inputs.py      (the package on PYTHONPATH, SCHLIEREN_ENGINE_LIBRARY set)
"""
import atexit
import os
import sys
import tempfile

import numpy as np

import schlieren  # noqa: E402
from vtkmodules.util import numpy_support  # noqa: E402
from vtkmodules.vtkCommonCore import vtkFileOutputWindow, vtkOutputWindow, vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import (vtkImageData, vtkMultiBlockDataSet,  # noqa: E402
                                           vtkStructuredGrid)
from vtkmodules.vtkFiltersCore import vtkAppendFilter  # noqa: E402

failures = []
_fd, log = tempfile.mkstemp(prefix="frontend_inputs_", suffix=".txt")
os.close(_fd)
atexit.register(os.remove, log)
window = vtkFileOutputWindow()  # VTK's errors and warnings into a file the test reads
window.SetFileName(log)
window.SetFlush(1)
vtkOutputWindow.SetInstance(window)


def messages():
    if not os.path.exists(log):
        return ""
    with open(log) as f:
        return f.read()


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def run(algorithm, data):
    """`algorithm` on `data`: (output copy, messages written meanwhile)."""
    start = len(messages())
    algorithm.SetInputData(data)
    algorithm.Update()
    out = vtkImageData()
    if algorithm.GetOutputDataObject(0).IsA("vtkImageData"):
        out.DeepCopy(algorithm.GetOutputDataObject(0))
    return algorithm.GetOutputDataObject(0), out, messages()[start:]


def intensity(image):
    a = image.GetPointData().GetArray("intensity")
    return None if a is None else numpy_support.vtk_to_numpy(a)


def image_settings():
    return dict(Backend="CPU", Resolution=[40, 32], Passes=1)


scene = schlieren.RefractiveScene(Dimensions=[24, 20, 16])
scene.Update()
volume = vtkImageData()
volume.DeepCopy(scene.GetOutput())

# a curvilinear grid (the volume's points, slightly sheared) with a density, in a multiblock
dims = volume.GetDimensions()
points = vtkPoints()
for k in range(dims[2]):
    for j in range(dims[1]):
        for i in range(dims[0]):
            x, y, z = volume.GetPoint(i + dims[0] * (j + dims[1] * k))
            points.InsertNextPoint(x + 0.05 * y, y, z)
grid = vtkStructuredGrid()
grid.SetDimensions(dims)
grid.SetPoints(points)
density = numpy_support.numpy_to_vtk(
    1.2 + 1000.0 * numpy_support.vtk_to_numpy(volume.GetPointData().GetArray("n_minus_1")), deep=1)
density.SetName("density")
grid.GetPointData().AddArray(density)
blocks = vtkMultiBlockDataSet()
blocks.SetNumberOfBlocks(1)
blocks.SetBlock(0, grid)

index_settings = dict(Model="GladstoneDale", InputArray="density", AutomaticDimension=32,
                      BodyFromGrid=0)
bare = schlieren.RefractiveIndex(**index_settings)
raw, out_bare, _ = run(bare, grid)
multi = schlieren.RefractiveIndex(**index_settings)
raw, out_multi, text = run(multi, blocks)
a, b = out_multi.GetPointData().GetArray("n_minus_1"), out_bare.GetPointData().GetArray("n_minus_1")
check(raw.GetClassName() == "vtkImageData" and a is not None and b is not None and
      out_multi.GetExtent() == out_bare.GetExtent() and
      np.array_equal(numpy_support.vtk_to_numpy(a), numpy_support.vtk_to_numpy(b)),
      "RefractiveIndex on a multiblock: one %s, the bare grid's image bit for bit (extent %s)"
      % (raw.GetClassName(), out_multi.GetExtent()))
for name, algorithm in (("SchlierenImage", schlieren.SchlierenImage(**image_settings())),
                        ("RefractionOctree", schlieren.RefractionOctree()),
                        ("NumericalSchlieren", schlieren.NumericalSchlieren(Resolution=[40, 32]))):
    raw, out, text = run(algorithm, blocks)
    check(raw.GetClassName() == "vtkImageData" and out.GetNumberOfPoints() == 0 and
          "needs a vtkImageData input" in text and "got vtkMultiBlockDataSet" in text and
          "Traceback" not in text and "got vtkMultiBlockDataSet" in algorithm.LastError,
          "%s on a multiblock: an empty vtkImageData and the reason (%r)"
          % (name, algorithm.LastError[:90]))

# SchlierenImage: a direction matrix, an unstructured grid, an extent not starting at 0
turned = vtkImageData()
turned.DeepCopy(volume)
turned.SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1)
image = schlieren.SchlierenImage(**image_settings())
_, out, text = run(image, turned)
check(out.GetNumberOfPoints() == 0 and "this one has a direction matrix" in text,
      "a direction matrix: refused with the C++ filter's reason")
append = vtkAppendFilter()
append.SetInputData(volume)
append.Update()
_, out, text = run(schlieren.SchlierenImage(**image_settings()), append.GetOutput())
check(out.GetNumberOfPoints() == 0 and "got vtkUnstructuredGrid" in text and
      "apply RefractiveIndex first" in text,
      "an unstructured grid straight to SchlierenImage: refused, RefractiveIndex named")
shifted = vtkImageData()
shifted.DeepCopy(volume)
shifted.SetExtent(5, 28, -3, 16, 2, 17)
moved = vtkImageData()
moved.DeepCopy(volume)
moved.SetOrigin([volume.GetOrigin()[a] + e * volume.GetSpacing()[a]
                 for a, e in enumerate((5, -3, 2))])
_, one, _ = run(schlieren.SchlierenImage(**image_settings()), shifted)
_, two, _ = run(schlieren.SchlierenImage(**image_settings()), moved)
check(one.GetNumberOfPoints() == 40 * 32 and one.GetOrigin() == two.GetOrigin() and
      np.array_equal(intensity(one), intensity(two)),
      "extent %s: the film of the same points with their extent from 0 (origin %s)"
      % (shifted.GetExtent(), one.GetOrigin()))

# the index models in plain VTK: IdealGas air from T and p against rho = p M / (R T), n - 1 = K rho
# (K 0.2256 cm^3/g, M 28.9641 g/mol, R 8.314462618 J/(mol K): the engine's table, ORACLES.md)
tp = vtkImageData()
tp.SetDimensions(6, 5, 4)
t_values = np.linspace(250.0, 350.0, 120)
p_values = np.linspace(0.9e5, 1.1e5, 120)
for field, values in (("Temperature", t_values), ("Pressure", p_values)):
    a = numpy_support.numpy_to_vtk(values.astype(np.float32), deep=1)
    a.SetName(field)
    tp.GetPointData().AddArray(a)
ideal = schlieren.RefractiveIndex(Model="IdealGas", Gas="Air")
_, out, text = run(ideal, tp)
got = out.GetPointData().GetArray("n_minus_1")
want = 0.2256e-3 * p_values.astype(np.float32) * 28.9641e-3 / (8.314462618 *
                                                               t_values.astype(np.float32))
err = np.max(np.abs(numpy_support.vtk_to_numpy(got) / want - 1.0)) if got is not None else 1.0
check(got is not None and err < 1e-6 and "ERROR" not in text,
      "IdealGas air (arrays Temperature, Pressure found by name): n - 1 = K p M / (R T) within "
      "%.1e relative (float32)" % err)

# Symmetry in plain VTK (the engine's plan, samples and fill; python.python_plugin_parity compares
# them with the C++ filter in pvpython): Planar on a 2D image keeps its own in-plane points, the
# field extruded unchanged over Span; a wedge one cell across is revolved about its own axis (along
# y at x = 0.3, z = 0.1, SymmetryAxis left at X), and with Symmetry None it is said to be a wedge
flat = vtkImageData()
flat.SetDimensions(9, 7, 1)
flat.SetSpacing(0.1, 0.1, 1.0)
flat.SetOrigin(-0.4, -0.3, 0.0)
rho = (1.2 + 0.1 * np.arange(63) % 0.7).astype(np.float32)
a = numpy_support.numpy_to_vtk(rho, deep=1)
a.SetName("density")
flat.GetPointData().AddArray(a)
planar = schlieren.RefractiveIndex(Model="GladstoneDale", InputArray="density", Symmetry="Planar",
                                   Span=0.4)
_, out, text = run(planar, flat)
got = out.GetPointData().GetArray("n_minus_1")
got = None if got is None else numpy_support.vtk_to_numpy(got).reshape(-1, 63)
check(out.GetDimensions() == (9, 7, 3) and np.allclose(out.GetOrigin(), (-0.4, -0.3, -0.2)) and
      got is not None and all(np.array_equal(got[k], got[0]) for k in range(3)) and
      np.max(np.abs(got[0] / (2.256e-4 * rho) - 1)) < 1e-6 and "ERROR" not in text,
      "Symmetry Planar on a 9 x 7 image: 9 x 7 x 3 points, z from -Span/2, n - 1 = K rho at the "
      "image's points on every plane across the span (%s)" % (text.strip()[:120],))
wedge = vtkStructuredGrid()
wedge.SetDimensions(10, 12, 2)
points, values, half = vtkPoints(), [], np.radians(2.5)
for side in (-1, 1):
    for j in range(12):
        for i in range(10):
            r, y = 0.05 * i, 0.05 * j
            points.InsertNextPoint(0.3 + r * np.cos(half), y, 0.1 + side * r * np.sin(half))
            values.append(1.2 + 0.4 * np.exp(-((r - 0.2) ** 2 + (y - 0.3) ** 2) / 0.02))
wedge.SetPoints(points)
a = numpy_support.numpy_to_vtk(np.array(values, np.float32), deep=1)
a.SetName("density")
wedge.GetPointData().AddArray(a)
revolved = schlieren.RefractiveIndex(Model="GladstoneDale", InputArray="density",
                                     Symmetry="Axisymmetric", AutomaticDimension=24)
_, out, text = run(revolved, wedge)
d, o, h = out.GetDimensions(), out.GetOrigin(), out.GetSpacing()
centre = [o[a] + 0.5 * (d[a] - 1) * h[a] for a in range(3)]
check(out.GetNumberOfPoints() > 0 and d[0] == d[2] and abs(centre[0] - 0.3) < 1e-6 and
      abs(centre[2] - 0.1) < 1e-6 and "ERROR" not in text,
      "Symmetry Axisymmetric on a wedge about y (no axis typed): revolved about x = 0.3, z = 0.1 "
      "(grid %s, centre %s, the fitted axis)" % (d, [round(c, 9) for c in centre]))
_, out, text = run(schlieren.RefractiveIndex(Model="GladstoneDale", InputArray="density",
                                             AutomaticDimension=16), wedge)
check(out.GetNumberOfPoints() > 0 and "The input is an axisymmetric wedge (OpenFOAM's way: two "
      "planes 5 deg apart through the line along y at x = 0.3, z = 0.1, one cell across)" in text,
      "the wedge with Symmetry None: the C++ filter's warning (%r)" % text.strip()[-120:])

# a failed request leaves no image from before
image = schlieren.SchlierenImage(**image_settings())
_, good, _ = run(image, volume)
image.Resolution = [1, 1]
raw, _, text = run(image, volume)
check(good.GetNumberOfPoints() == 40 * 32 and raw.GetNumberOfPoints() == 0 and
      "Resolution is 1 x 1 pixels" in image.LastError and text.count("Resolution is 1 x 1") == 1,
      "Resolution 1 x 1 after a good image: the output is empty, the error said once (%r)"
      % image.LastError)
# an exception of any kind in a request: a message, no traceback
broken = schlieren.RefractionOctree()
broken.RequestData = lambda *a: 1 / 0
raw, _, text = run(broken, volume)
check(raw.GetNumberOfPoints() == 0 and "ZeroDivisionError" in text and "Traceback" not in text,
      "an exception in a request: an error naming it, not a traceback (%r)" % broken.LastError)
print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
