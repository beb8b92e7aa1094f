# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView Python plugin (SchlierenPython.py) where a user meets it, against the C++ plugin's
filters (the compiled classes of schlieren_vtk, in the same pvpython):

  1. outputs are one vtkImageData for any input: RefractiveIndex on the blunt fin (PLOT3D, a
     multiblock) gives the C++ filter's grid (extent, origin, spacing), n - 1 and grad n bit for
     bit, also over the example's SamplingBounds, with AmbientMode DomainEdgeMedian and Value, and
     with the fin as a body (BodyWallFaces: solid bit for bit, the field data's counts equal);
     its information has the grid before RequestData (a Slice of the image has points), and
     SchlierenImage and NumericalSchlieren on it give the C++ filters' images bit for bit (not
     multiblocks); SchlierenImage straight on the multiblock gives an empty image and the C++
     filter's reason; an unstructured mesh (disk_out_ref.ex2, an Exodus multiblock of
     hexahedra) gives the C++ filter's grid, valid points, n - 1, grad n, resampled arrays and
     traced image bit for bit (both resample with the engine's cell sampler);
  2. errors are VTK errors (ParaView's Output Messages), never a Python traceback; a refused value
     (Symmetry Planar on a 3D volume: the C++ filter's reason; Resolution 1 x 1) leaves an empty
     output, and a good value set after it gives the image again;
  3. NumericalSchlieren logs no update-extent error;
  4. `import schlieren_view` works after LoadPlugin, and Examples/first_light.py runs with the
     Python plugin (its PNG equals the C++ plugin's bit for bit);
  5. what the C++ SchlierenImage refuses the Python one refuses with the same reason (a direction
     matrix; an unstructured grid given straight to it), and an image whose extent does not start
     at 0 is traced to the C++ filter's film, bit for bit (intensity, origin), which is also the
     film of the same grid given with its extent from 0;
  6. RefractiveIndex's index models (Model Automatic's choice: n - 1 before a density, IdealGas
     from a temperature and a pressure, Passthrough of an array named n; GladstoneDaleMixture by
     mixture fraction and by species, IdealGas with one gas, a mixture fraction and species with
     a custom gas, Ciddor with constant and array humidity and CO2; a SolidArray) give the C++
     filter's n - 1 and grad n bit for bit on the same arrays (the engine's ComputeFieldIndex
     through schlieren_index_model);
  7. Symmetry (the engine's schlieren_symmetry_*, the same calls for both): Planar on a 2D image
     and on a 2D unstructured grid, Axisymmetric on an r-z half plane (a cone's shock layer) about
     SymmetryAxis, and on a wedge with no axis typed (one cell across, its axis along y off the
     origin: AxisFromWedge finds it) give the C++ filter's grid, n - 1, grad n and field data bit
     for bit, and SchlierenImage on each the C++ filter's film bit for bit; the wedge with
     Symmetry None warns as the C++ filter does; the C++ filter's refusals (Span 0, a 3D mesh,
     SymmetryAxis normal to the plane) are the Python one's, word for word;
  9. RefractiveIndex's parity matrix (frontend_cases.INDEX, every property value class: each
     model, Symmetry None/Planar/Axisymmetric, a wedge with no axis typed, bodies from holes and
     from walls, SamplingBounds, each AmbientMode; the table of class -> case is in
     frontend_cases.py): the inputs frontend_reference.py wrote, through the Python plugin's
     proxies, against the C++ plugin's records bit for bit (frontend_matrix.compare: the index's
     grid, point arrays and field data less the C++ filter's cache report, the film's arrays and
     field data). The same matrix runs through pip VTK in test_frontend.py (python.frontend_vtk_*);
     sections 1, 6 and 7 compare the two plugins on the same classes in one process.
  8. NumericalSchlieren (both plugins) reports its progress between blocks of film rows and stops
     at an abort: an observer aborting at the first progress event ends a LineOfSight image at 0 %
     with the engine's message and an empty output; the next update is a fresh filter's image bit
     for bit, its progress rising from 0 to 1 in several steps;
  10. an overlapping AMR (two levels, the finer one two boxes sharing a face; point data and cell
     data): the C++ filter's grid, n - 1, grad n and field data bit for bit (both read it into
     the engine's AMR sampler), SchlierenImage's film bit for bit; overlapping boxes refused with
     the C++ filter's message;
  11. the per-time-step cache: a Python source with 4 time steps (a ProgrammableSource counting
     its executions) played twice through the Python plugin: the second play executes neither
     the source nor RefractiveIndex (index_from_cache 1) and gives the first play's images bit for
     bit; the source's script or a RefractiveIndex property changed: computed again.
  12. the Body input (port 1): a sphere surface and two overlapping spheres on a Gaussian scene
     give the C++ filter's solid, n - 1, grad n and field data bit for bit, a sphere beside the
     grid the same note; an open surface and one without polygons are refused by both with the
     C++ filter's message.

    pvpython test_python_plugin_parity.py --plugin SchlierenPython.py --cxx-plugin Schlieren.so \\
        --example Examples/first_light.py --work DIR [--data ../shared/data] [--reference REF]

The blunt fin part is skipped (said so) when ../shared/data (or SCHLIEREN_DATA) has no blunt fin.
ParaView 5.11.0 under Python 3.11 needs the getargspec shim below before any Python plugin loads
(docs/PYTHON.md).
"""
import argparse
import collections
import inspect
import os
import subprocess
import sys
import time

if not hasattr(inspect, "getargspec"):  # ParaView 5.11.0 on Python >= 3.11
    _ArgSpec = collections.namedtuple("ArgSpec", "args varargs keywords defaults")
    inspect.getargspec = lambda f: _ArgSpec(*inspect.getfullargspec(f)[:4])

import numpy as np  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import Delete, LoadPlugin, PLOT3DReader, PVTrivialProducer, Slice  # noqa: E402
from vtkmodules.util import numpy_support  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True, help="SchlierenPython.py")
ap.add_argument("--cxx-plugin", required=True, help="Schlieren.so (for first_light.py's reference)")
ap.add_argument("--example", required=True, help="Examples/first_light.py")
ap.add_argument("--work", required=True)
ap.add_argument("--reference", help="frontend_reference.py's output: RefractiveIndex's matrix")
ap.add_argument("--pvpython", default="pvpython", help="to run the example")
ap.add_argument("--data", default=os.environ.get("SCHLIEREN_DATA") or
                os.path.join(HERE, "..", "..", "..", "shared", "data"))
args = ap.parse_args()
os.makedirs(args.work, exist_ok=True)

LoadPlugin(args.plugin, remote=False, ns=globals())
ns = globals()
import schlieren_vtk as cxx  # noqa: E402  the C++ plugin's filters, compiled

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


# what the process writes to its standard error while a block runs (VTK's output window, tracebacks)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from schlieren_testing import CapturedStderr as Captured  # noqa: E402


def array(data, name):
    a = data.GetPointData().GetArray(name) if data is not None else None
    return None if a is None else numpy_support.vtk_to_numpy(a)


def producer(data):
    """A pipeline source (paraview.simple) that hands out `data`."""
    p = PVTrivialProducer()
    p.GetClientSideObject().SetOutput(data)
    return p


def cxx_image(data, **settings):
    """The C++ SchlierenImage's output for `data` (a copy) and whether it succeeded."""
    f = cxx.vtkSchlierenImage()
    f.SetInputData(data)
    f.SetBackend(cxx.vtkSchlierenImage.CPU)
    f.SetResolution(*settings.get("Resolution", [48, 40]))
    f.SetPasses(settings.get("Passes", 1))
    f.SetViewDirection(*settings.get("ViewDirection", [0, 0, -1]))
    f.SetViewUp(*settings.get("ViewUp", [0, 1, 0]))
    ok = f.GetExecutive().Update()
    out = vtkImageData()
    out.DeepCopy(f.GetOutput())
    return out, ok


def py_image(data, **settings):
    """The Python plugin's SchlierenImage proxy on `data`: (output copy, stderr text)."""
    kw = dict(Resolution=[48, 40], Passes=1, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0])
    kw.update(settings)
    src = producer(data)
    img = ns["SchlierenImage"](Input=src, Backend="CPU", **kw)
    with Captured() as c:
        img.UpdatePipeline()
    out = servermanager.Fetch(img)
    return out, c.text


def same_film(a, b):
    ia, ib = array(a, "intensity"), array(b, "intensity")
    return (ia is not None and ib is not None and a.GetExtent() == b.GetExtent() and
            a.GetOrigin() == b.GetOrigin() and a.GetSpacing() == b.GetSpacing() and
            np.array_equal(ia.view(np.uint32), ib.view(np.uint32)))


# a small volume with n_minus_1 from the C++ RefractiveScene (a Gaussian sphere)
scene = cxx.vtkRefractiveScene()
scene.SetDimensions(24, 20, 16)
scene.Update()
volume = vtkImageData()
volume.DeepCopy(scene.GetOutput())

# -- 1. one vtkImageData for any input: the blunt fin (a PLOT3D multiblock)
xyz, q = os.path.join(args.data, "bluntfinxyz.bin"), os.path.join(args.data, "bluntfinq.bin")
if not (os.path.exists(xyz) and os.path.exists(q)):
    print("SKIP the blunt fin part: no bluntfinxyz.bin/bluntfinq.bin in %s (set SCHLIEREN_DATA)"
          % os.path.abspath(args.data))
else:
    reader = PLOT3DReader(FileName=xyz, QFileName=[q])
    index = ns["RefractiveIndex"](Input=reader, Model="GladstoneDale", Gas="Air",
                                  DensityReference=1.2, AutomaticDimension=48, BodyFromGrid=1)
    index.InputArray = ["POINTS", "Density"]
    index.UpdatePipeline()
    mine = servermanager.Fetch(index)
    blocks = servermanager.Fetch(reader)
    ref = cxx.vtkRefractiveIndex()
    ref.SetInputData(blocks)
    ref.SetModel(cxx.vtkRefractiveIndex.GLADSTONE_DALE)
    ref.SetGas(cxx.vtkRefractiveIndex.AIR)
    ref.SetDensityReference(1.2)
    ref.SetAutomaticDimension(48)
    ref.SetBodyFromGrid(0)  # the Python front end finds no body in the grid's holes (yet)
    ref.SetInputArrayToProcess(0, 0, 0, 0, "Density")
    ref.Update()
    theirs = ref.GetOutput()
    check(mine.GetClassName() == "vtkImageData",
          "RefractiveIndex on the blunt fin's %s: one %s" % (blocks.GetClassName(),
                                                           mine.GetClassName()))
    check(mine.GetExtent() == theirs.GetExtent() and
          np.allclose(mine.GetOrigin(), theirs.GetOrigin(), rtol=0, atol=1e-12) and
          np.allclose(mine.GetSpacing(), theirs.GetSpacing(), rtol=1e-12, atol=0),
          "its grid is the C++ filter's (extent %s, origin %s, spacing %s; C++ %s %s %s)"
          % (mine.GetExtent(), mine.GetOrigin(), mine.GetSpacing(), theirs.GetExtent(),
             theirs.GetOrigin(), theirs.GetSpacing()))
    for name in ("n_minus_1", "grad_n"):
        a, b = array(mine, name), array(theirs, name)
        check(a is not None and b is not None and a.shape == b.shape and
              np.array_equal(a.view(np.uint32), b.view(np.uint32)),
              "%s bit for bit with the C++ filter's (BodyFromGrid off there: the Python front "
              "end finds no body in the grid's holes yet)" % name)
    # the box the example samples (Examples/bluntfin.py), AutomaticDimension over it
    boxed = ns["RefractiveIndex"](Input=reader, Model="GladstoneDale", Gas="Air",
                                  DensityReference=1.2, AutomaticDimension=48, UseSamplingBounds=1,
                                  SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7])
    boxed.InputArray = ["POINTS", "Density"]
    boxed.UpdatePipeline()
    mine_boxed = servermanager.Fetch(boxed)
    ref.SetUseSamplingBounds(1)
    ref.SetSamplingBounds(-2.5, 7.5, 0.0, 5.0, 0.0, 5.7)
    ref.Update()
    theirs_boxed = ref.GetOutput()
    check(mine_boxed.GetExtent() == theirs_boxed.GetExtent() and
          mine_boxed.GetOrigin() == theirs_boxed.GetOrigin() and
          mine_boxed.GetSpacing() == theirs_boxed.GetSpacing() and
          all(array(mine_boxed, n) is not None and array(theirs_boxed, n) is not None and
              np.array_equal(array(mine_boxed, n).view(np.uint32),
                             array(theirs_boxed, n).view(np.uint32))
              for n in ("n_minus_1", "grad_n")) and
          tuple(int(v) for v in boxed.GetDataInformation().DataInformation.GetExtent()) ==
          theirs_boxed.GetExtent(),
          "SamplingBounds -2.5 7.5 0 5 0 5.7: the C++ filter's grid %s, n_minus_1 and grad_n bit "
          "for bit, the same extent in the pipeline's information" % (theirs_boxed.GetExtent(),))
    # the points outside the grid (the fin's hole, the box's corners) by each AmbientMode
    for mode, number in (("DomainEdgeMedian", 1), ("Value", 2)):
        boxed.AmbientMode = mode
        boxed.AmbientValue = 2.5e-4
        boxed.UpdatePipeline()
        mine_boxed = servermanager.Fetch(boxed)
        ref.SetAmbientMode(number)
        ref.SetAmbientValue(2.5e-4)
        ref.Update()
        theirs_boxed = ref.GetOutput()
        check(all(array(mine_boxed, n) is not None and array(theirs_boxed, n) is not None and
                  np.array_equal(array(mine_boxed, n).view(np.uint32),
                                 array(theirs_boxed, n).view(np.uint32))
                  for n in ("n_minus_1", "grad_n")),
              "AmbientMode %s: n_minus_1 and grad_n bit for bit the C++ filter's" % mode)
    ref.SetAmbientMode(0)
    # the fin as a body: the grid's hole the flow encloses, through the wall faces of
    # Examples/bluntfin.py (the fin runs past x max, the plane y = 0 cuts it, it stands on z = 0
    # and reaches the top), as the example's silhouette
    boxed.AmbientMode = "Extend"
    boxed.BodyWallFaces = [0, 1, 1, 0, 1, 1]
    boxed.UpdatePipeline()
    mine_boxed = servermanager.Fetch(boxed)
    ref.SetBodyFromGrid(1)
    ref.SetBodyWallFaces(0, 1, 1, 0, 1, 1)
    ref.Update()
    theirs_boxed = ref.GetOutput()
    solid = array(theirs_boxed, "solid")
    check(all(array(mine_boxed, n) is not None and array(theirs_boxed, n) is not None and
              np.array_equal(array(mine_boxed, n).view(np.uint8),
                             array(theirs_boxed, n).view(np.uint8))
              for n in ("n_minus_1", "grad_n", "solid")) and solid is not None and
          solid.sum() > 100,
          "BodyFromGrid with BodyWallFaces 0 1 1 0 1 1: the fin's %s solid points, solid, n_minus_1 "
          "and grad_n bit for bit the C++ filter's" % (None if solid is None else int(solid.sum())))
    fields_of = (lambda d: {n: [d.GetFieldData().GetAbstractArray(n).GetVariantValue(i).ToString()
                                for i in range(d.GetFieldData().GetAbstractArray(n)
                                               .GetNumberOfValues())]
                            for n in ("index_model", "index_arrays", "valid_point_fraction",
                                      "solid_points")
                            if d.GetFieldData().GetAbstractArray(n) is not None})
    check(fields_of(mine_boxed) == fields_of(theirs_boxed) and len(fields_of(theirs_boxed)) == 4,
          "its field data index_model, index_arrays, valid_point_fraction, solid_points: the C++ "
          "filter's (%s)" % fields_of(mine_boxed))
    ref.SetBodyFromGrid(0)
    ref.SetBodyWallFaces(0, 0, 0, 0, 0, 0)
    ref.SetUseSamplingBounds(0)
    ref.Update()
    settings = dict(Resolution=[64, 48], Passes=1, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0])
    image = ns["SchlierenImage"](Input=index, Backend="CPU", **settings)
    image.UpdatePipeline()
    out = servermanager.Fetch(image)
    film, _ = cxx_image(theirs, **settings)
    check(out.GetClassName() == "vtkImageData" and out.GetNumberOfPoints() == 64 * 48 and
          same_film(out, film),
          "SchlierenImage on it: a %s, the C++ filter's film %s bit for bit (got %s)"
          % (out.GetClassName(), film.GetExtent(), out.GetExtent()))
    # what a view asks for: the pipeline's information (not Fetch, which asks for everything)
    # gives the film's extent, so a Slice (as a 2D view's slice representation) has points
    slicer = Slice(Input=image)
    slicer.SliceType.Normal = [1, 0, 0]
    slicer.UpdatePipeline()
    extent = tuple(int(v) for v in image.GetDataInformation().DataInformation.GetExtent())
    check(extent == film.GetExtent() and slicer.GetDataInformation().GetNumberOfPoints() == 48,
          "the image's data information has the film's extent %s and a Slice across it has its "
          "48 points (%d)" % (extent, slicer.GetDataInformation().GetNumberOfPoints()))
    numerical = ns["NumericalSchlieren"](Input=index, Resolution=[64, 48])
    with Captured() as c:
        numerical.UpdatePipeline()
    out = servermanager.Fetch(numerical)
    ref_numerical = cxx.vtkNumericalSchlieren()
    ref_numerical.SetInputData(theirs)
    ref_numerical.SetResolution(64, 48)
    ref_numerical.Update()
    want = ref_numerical.GetOutput()
    check(out.GetClassName() == "vtkImageData" and out.GetNumberOfPoints() > 0 and
          out.GetExtent() == want.GetExtent() and out.GetOrigin() == want.GetOrigin() and
          all(array(out, n) is not None and array(want, n) is not None and
              np.array_equal(array(out, n).view(np.uint8), array(want, n).view(np.uint8))
              for n in ("intensity", "numerical_gradient", "blocked")),
          "NumericalSchlieren on it: a %s of %d points, the C++ filter's image bit for bit"
          % (out.GetClassName(), out.GetNumberOfPoints()))
    # -- 3. no update-extent error (the film's extent is not the volume's)
    check("update extent" not in c.text.lower() and "ERR" not in c.text,
          "NumericalSchlieren logs no update-extent error (stderr: %r)" % c.text[-300:])
    direct = ns["SchlierenImage"](Input=reader, Backend="CPU", Resolution=[32, 32], Passes=1)
    with Captured() as c:
        direct.UpdatePipeline()
    out = servermanager.Fetch(direct)
    check(out.GetClassName() == "vtkImageData" and out.GetNumberOfPoints() == 0 and
          "SchlierenImage needs a vtkImageData input with the point array 'n_minus_1'; got "
          "vtkMultiBlockDataSet" in c.text and "Traceback" not in c.text,
          "SchlierenImage straight on the multiblock: an empty %s and the C++ filter's reason"
          % out.GetClassName())

# -- 1b. an unstructured mesh (disk_out_ref.ex2: an Exodus multiblock of hexahedra): both
# plugins resample it with the engine's cell sampler (schlieren_sample_cells), so the grid, the
# valid points, n - 1, grad n and the traced image are bit for bit the C++ filter's
exo = os.path.join(args.data, "disk_out_ref.ex2")
if not os.path.exists(exo):
    print("SKIP the unstructured part: no disk_out_ref.ex2 in %s (set SCHLIEREN_DATA)"
          % os.path.abspath(args.data))
else:
    from paraview.simple import ExodusIIReader
    disk = ExodusIIReader(FileName=exo)
    disk.PointVariables = ["Temp", "V"]
    disk_index = ns["RefractiveIndex"](Input=disk, Model="GladstoneDale", Gas="Air",
                                       DensityReference=1e-3, AutomaticDimension=40)
    disk_index.InputArray = ["POINTS", "Temp"]
    with Captured() as c:
        disk_index.UpdatePipeline()
    mine = servermanager.Fetch(disk_index)
    ref = cxx.vtkRefractiveIndex()
    ref.SetInputData(servermanager.Fetch(disk))
    ref.SetModel(cxx.vtkRefractiveIndex.GLADSTONE_DALE)
    ref.SetGas(cxx.vtkRefractiveIndex.AIR)
    ref.SetDensityReference(1e-3)
    ref.SetAutomaticDimension(40)
    ref.SetInputArrayToProcess(0, 0, 0, 0, "Temp")
    ref.Update()
    theirs = ref.GetOutput()
    fraction = [d.GetFieldData().GetArray("valid_point_fraction").GetValue(0)
                if d.GetFieldData().GetArray("valid_point_fraction") else None
                for d in (mine, theirs)]
    check(mine.GetClassName() == "vtkImageData" and mine.GetExtent() == theirs.GetExtent() and
          mine.GetOrigin() == theirs.GetOrigin() and mine.GetSpacing() == theirs.GetSpacing() and
          fraction[0] == fraction[1] and fraction[0] is not None and 0.3 < fraction[0] < 1.0 and
          "Traceback" not in c.text,
          "disk_out_ref.ex2 (%s of hexahedra): the C++ filter's grid %s and valid points "
          "(valid_point_fraction %s)" % (servermanager.Fetch(disk).GetClassName(),
                                         theirs.GetExtent(), fraction))
    for name in ("n_minus_1", "grad_n", "Temp", "V"):
        a, b = array(mine, name), array(theirs, name)
        check(a is not None and b is not None and a.shape == b.shape and
              np.array_equal(a.view(np.uint8), b.view(np.uint8)),
              "disk_out_ref.ex2: %s bit for bit the C++ filter's" % name)
    settings = dict(Resolution=[48, 40], Passes=1, ViewDirection=[1, 0, 0], ViewUp=[0, 0, 1])
    image = ns["SchlierenImage"](Input=disk_index, Backend="CPU", **settings)
    image.UpdatePipeline()
    out = servermanager.Fetch(image)
    film, _ = cxx_image(theirs, **settings)
    intensity = array(film, "intensity")
    check(same_film(out, film) and intensity is not None and np.ptp(intensity) > 0.05,
          "disk_out_ref.ex2: SchlierenImage's film bit for bit the C++ filter's (intensity "
          "%.3f to %.3f)" % ((intensity.min(), intensity.max()) if intensity is not None
                             else (0, 0)))
    for p in (image, disk_index, disk):
        Delete(p)

# -- 2. errors: VTK errors, no traceback; a refused value leaves an empty output
src = producer(volume)
index = ns["RefractiveIndex"](Input=src, Model="Passthrough")
index.UpdatePipeline()
check(servermanager.Fetch(index).GetNumberOfPoints() == 24 * 20 * 16, "RefractiveIndex runs")
with Captured() as c:
    index.Symmetry = "Planar"  # a 3D volume: refused with the C++ filter's reason
    index.UpdatePipeline()
out = servermanager.Fetch(index)
check("Traceback" not in c.text and "ERROR: In RefractiveIndex" in c.text and
      "Symmetry Planar expects a 2D plane normal to x, y or z" in c.text and
      out.GetNumberOfPoints() == 0,
      "Symmetry Planar on a 3D volume: the C++ filter's reason, no traceback, an empty output "
      "(%d points; %r)" % (out.GetNumberOfPoints(), c.text.strip().splitlines()[:1]))
with Captured() as c:
    index.Symmetry = "None"
    index.UpdatePipeline()
check("ERR" not in c.text and servermanager.Fetch(index).GetNumberOfPoints() == 24 * 20 * 16,
      "Symmetry None again: the output is back, no error")
image = ns["SchlierenImage"](Input=index, Backend="CPU", Resolution=[32, 32], Passes=1)
image.UpdatePipeline()
good = servermanager.Fetch(image).GetNumberOfPoints()
with Captured() as c:
    image.Resolution = [1, 1]
    image.UpdatePipeline()
out = servermanager.Fetch(image)
check(good == 32 * 32 and out.GetNumberOfPoints() == 0 and "Traceback" not in c.text and
      "Resolution is 1 x 1 pixels" in c.text,
      "SchlierenImage Resolution 1 x 1: the engine's error, no traceback, no image left from "
      "before (%d points after, %d before)" % (out.GetNumberOfPoints(), good))

# -- 5. the C++ filter's refusals, and an extent that does not start at 0
turned = vtkImageData()
turned.DeepCopy(volume)
turned.SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1)
out, text = py_image(turned)
_, ok = cxx_image(turned)
check(not ok and out.GetNumberOfPoints() == 0 and "has a direction matrix" in text and
      "Traceback" not in text,
      "a direction matrix: refused by both, with the C++ filter's reason, an empty output")
shifted = vtkImageData()
shifted.DeepCopy(volume)
shifted.SetExtent(5, 28, -3, 16, 2, 17)
mine, text = py_image(shifted)
theirs, ok = cxx_image(shifted)
check(ok and same_film(mine, theirs),
      "extent %s: the C++ filter's film bit for bit (origin %s, C++ %s)"
      % (shifted.GetExtent(), mine.GetOrigin(), theirs.GetOrigin()))
moved = vtkImageData()
moved.DeepCopy(volume)
moved.SetOrigin([volume.GetOrigin()[a] + e * volume.GetSpacing()[a]
                 for a, e in enumerate((5, -3, 2))])
check(same_film(mine, py_image(moved)[0]),
      "and the film of the same grid with its extent from 0 (placed where the points are)")
from vtkmodules.vtkFiltersCore import vtkAppendFilter  # noqa: E402
append = vtkAppendFilter()
append.SetInputData(volume)
append.Update()
grid = append.GetOutput()
out, text = py_image(grid)
_, ok = cxx_image(grid)
check(not ok and out.GetNumberOfPoints() == 0 and
      "needs a vtkImageData input with the point array 'n_minus_1'; got vtkUnstructuredGrid" in
      text and "Traceback" not in text,
      "an unstructured grid straight to SchlierenImage: refused by both with the reason "
      "(RefractiveIndex resamples it), an empty output")

# -- 6. RefractiveIndex's index models: the engine's (schlieren_index_model), bit for bit the C++
# filter's n - 1 and grad n on the same arrays
fields = vtkImageData()
fields.SetDimensions(14, 11, 9)
fields.SetSpacing(0.01, 0.012, 0.015)
fields.SetOrigin(-0.07, -0.06, -0.06)
count = fields.GetNumberOfPoints()
x = np.linspace(0.0, 1.0, count)
wave = np.sin(7.0 * x) * np.cos(3.0 * x)
for field, values in (("density", 1.2 + 0.3 * wave), ("T", 300.0 - 40.0 * wave),
                      ("p", 101.325 * (1.0 + 0.2 * wave)), ("mix", 0.5 + 0.4 * wave),
                      ("Y1", 0.05 + 0.04 * wave), ("Y2", 0.2 - 0.1 * wave),
                      ("rh", 0.5 + 0.3 * wave), ("co2", 450.0 + 100.0 * wave),
                      ("blk", (wave > 0.3).astype(float))):
    a = numpy_support.numpy_to_vtk(values.astype(np.float32), deep=1)
    a.SetName(field)
    fields.GetPointData().AddArray(a)
RI = cxx.vtkRefractiveIndex
ARRAY_INDEX = dict(InputArray=0, TemperatureArray=1, PressureArray=2, MixtureFractionArray=3,
                   Species1Array=4, Species2Array=5, HumidityArray=8, CO2Array=9)
ENUMS = dict(AmbientMode=["Extend", "DomainEdgeMedian", "Value"],
             Model={"Automatic": -1, "Passthrough": 0, "GladstoneDale": 1,
                    "GladstoneDaleMixture": 2, "IdealGas": 3, "Ciddor": 4},
             MixtureComposition={"MixtureFraction": 1, "Species": 2},
             IdealGasComposition={"Gas": 0, "MixtureFraction": 1, "Species": 2},
             PressureUnit=["Pa", "kPa", "atm", "bar"], TemperatureUnit=["Kelvin", "Celsius"],
             HumidityMeasure=["RelativeHumidity", "WaterMoleFraction"])
GASES = ["Air", "He", "N2", "O2", "Ar", "CO2", "H2", "H2O", "CH4", "CO"]
MODELS = {
    "mixture_fraction": dict(Model="GladstoneDaleMixture", InputArray="density",
                             MixtureComposition="MixtureFraction", MixtureFractionArray="mix",
                             MixtureGas0="Air", MixtureGas1="He"),
    "mixture_species": dict(Model="GladstoneDaleMixture", InputArray="density",
                            MixtureComposition="Species", NumberOfSpecies=2,
                            SpeciesGases=[6, 8, 1, 5], Species1Array="Y1", Species2Array="Y2",
                            BalanceGas="N2"),
    "ideal_gas": dict(Model="IdealGas", Gas="CO2", TemperatureArray="T", PressureArray="p",
                      PressureUnit="kPa"),
    "ideal_gas_mixture": dict(Model="IdealGas", IdealGasComposition="MixtureFraction",
                              TemperatureArray="T", PressureArray="p", PressureUnit="kPa",
                              MixtureFractionArray="mix", MixtureGas0="N2", MixtureGas1="Ar"),
    "ideal_gas_species": dict(Model="IdealGas", IdealGasComposition="Species", NumberOfSpecies=2,
                              SpeciesGases=[-1, 8, 1, 5], SpeciesGladstoneDale=[3e-4, 2.2e-4,
                                                                                 2e-4, 2e-4],
                              SpeciesMolarMass=[0.04, 0.03, 0.004, 0.044],
                              Species1Array="Y1", Species2Array="Y2", TemperatureArray="T",
                              PressureArray="p", PressureUnit="kPa", TemperatureReference=1.1),
    "ciddor": dict(Model="Ciddor", TemperatureArray="T", PressureArray="p", PressureUnit="kPa",
                   Humidity=0.4, CO2=500.0, Wavelength=550.0),
    "ciddor_arrays": dict(Model="Ciddor", TemperatureArray="T", PressureArray="p",
                          PressureUnit="kPa", HumidityFromArray=1, HumidityArray="rh",
                          CO2FromArray=1, CO2Array="co2", TemperatureUnit="Kelvin"),
    # Model Automatic: n - 1 before a density (a scene has both), a temperature and a pressure
    # (IdealGas, arrays found by name), an array named n (Passthrough of n)
    "automatic_n_minus_1": dict(Model="Automatic", _input="scene"),
    "automatic_ideal_gas": dict(Model="Automatic", PressureUnit="kPa", Gas="Ar", _input="tp"),
    "automatic_n": dict(Model="Automatic", _input="n"),
    "automatic_named_temperature": dict(Model="Automatic", InputArray="T", PressureUnit="kPa",
                                        _input="tp"),
    # a solid mask array (SolidArray): its non-zero points are the output's solid
    "solid_array": dict(Model="GladstoneDale", InputArray="density", SolidArray="blk"),
    # an image with points outside the flow (vtkValidPointMask 0: a hole the flow encloses, a
    # notch open to a face): filled by AmbientMode, the hole a body (BodyFromGrid)
    "image_mask_extend": dict(Model="Passthrough", InputArray="n_minus_1", _input="masked"),
    "image_mask_median": dict(Model="Passthrough", InputArray="n_minus_1",
                              AmbientMode="DomainEdgeMedian", _input="masked"),
}
inputs = dict(fields=fields, scene=volume)
inputs["masked"] = vtkImageData()
inputs["masked"].DeepCopy(volume)
flow = np.ones((16, 20, 24), np.int8)  # z, y, x
flow[6:10, 8:12, 9:14] = 0  # enclosed
flow[0:3, 0:4, 0:5] = 0  # open to the faces
mask = numpy_support.numpy_to_vtk(flow.ravel(), deep=1, array_type=numpy_support.get_vtk_array_type(
    np.int8))
mask.SetName("vtkValidPointMask")
inputs["masked"].GetPointData().AddArray(mask)
for which, keep in (("tp", ("T", "p")), ("n", ())):
    inputs[which] = vtkImageData()
    inputs[which].CopyStructure(fields)
    for field in keep:
        inputs[which].GetPointData().AddArray(fields.GetPointData().GetArray(field))
n_array = numpy_support.numpy_to_vtk((1.0 + 3e-4 * (1 + wave)).astype(np.float32), deep=1)
n_array.SetName("n")
inputs["n"].GetPointData().AddArray(n_array)
sources = {k: producer(v) for k, v in inputs.items()}
for case, props in MODELS.items():
    props = dict(props)
    which = props.pop("_input", "fields")
    source = sources[which]
    ref = RI()
    ref.SetInputData(inputs[which])
    if which == "masked":
        ref.SetBodyFromGrid(1)
    for k, v in props.items():
        if k in ARRAY_INDEX:
            ref.SetInputArrayToProcess(ARRAY_INDEX[k], 0, 0, 0, v)
        elif k in ENUMS:
            e = ENUMS[k]
            getattr(ref, "Set" + k)(e[v] if isinstance(e, dict) else e.index(v))
        elif k in ("Gas", "MixtureGas0", "MixtureGas1", "BalanceGas"):
            getattr(ref, "Set" + k)(GASES.index(v))
        elif isinstance(v, list):
            getattr(ref, "Set" + k)(*v)
        else:
            getattr(ref, "Set" + k)(v)
    ok = ref.GetExecutive().Update()
    theirs = ref.GetOutput()
    index = ns["RefractiveIndex"](Input=source)
    for k, v in props.items():
        index.GetProperty(k).SetData(["POINTS", v] if k in ARRAY_INDEX else v)
    with Captured() as c:
        index.UpdatePipeline()
    mine = servermanager.Fetch(index)
    same = ok and all(
        array(mine, n) is not None and array(theirs, n) is not None and
        np.array_equal(array(mine, n).view(np.uint32), array(theirs, n).view(np.uint32))
        for n in ("n_minus_1", "grad_n")) and (
        array(theirs, "solid") is None if "SolidArray" not in props and which != "masked" else (
            array(mine, "solid") is not None and array(theirs, "solid") is not None and
            np.array_equal(array(mine, "solid"), array(theirs, "solid"))))
    b = array(theirs, "n_minus_1")
    model = mine.GetFieldData().GetAbstractArray("index_model")
    check(same and "ERR" not in c.text,
          "RefractiveIndex %s: n_minus_1 and grad_n bit for bit the C++ filter's (model %s, n - 1 "
          "%.6g..%.6g%s)" % (case, model.GetValue(0) if model else None,
                             b.min() if b is not None else float("nan"),
                   b.max() if b is not None else float("nan"),
                   "" if "ERR" not in c.text else "; " + c.text.strip().splitlines()[0][:200]))
    Delete(index)

# -- 12. the Body input (port 1, a closed surface): the C++ filter's inside test in both (the
# front end's VTK part with the same classes and settings, the engine's MarkBodySurface through
# schlieren_index_field), on the Gaussian scene: a sphere and two overlapping spheres (one surface
# of two shells, ORed) give solid, n - 1, grad n and field data bit for bit; a sphere beside the
# grid the same note; an open surface (a plane) and one without polygons refused word for word
from vtkmodules.vtkFiltersCore import vtkAppendPolyData  # noqa: E402
from vtkmodules.vtkFiltersSources import vtkPlaneSource  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402
from frontend_matrix import sphere  # noqa: E402  (one definition, the matrix's Body too)


def field_data(d):
    """The field data, exactly (numbers as float64), less the filters' cache reports (the cache
    budget is the process's memory: frontend_matrix.INDEX_FIELDS_LEFT_OUT)."""
    from frontend_matrix import INDEX_FIELDS_LEFT_OUT
    fd, out = d.GetFieldData(), []
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        if a.GetName() in INDEX_FIELDS_LEFT_OUT:
            continue
        values = [a.GetValue(j) for j in range(a.GetNumberOfValues())] if \
            a.IsA("vtkStringArray") else numpy_support.vtk_to_numpy(a).astype(np.float64).tolist()
        out.append((a.GetName(), values))
    return out


vb = volume.GetBounds()
mid = [(vb[0] + vb[1]) / 2, (vb[2] + vb[3]) / 2, (vb[4] + vb[5]) / 2]
size = min(vb[1] - vb[0], vb[3] - vb[2], vb[5] - vb[4])
two = vtkAppendPolyData()
two.AddInputData(sphere([mid[0] - 0.1 * size, mid[1], mid[2]], 0.25 * size))
two.AddInputData(sphere([mid[0] + 0.15 * size, mid[1], mid[2]], 0.2 * size))
two.Update()
plane = vtkPlaneSource()
plane.SetCenter(mid)
plane.Update()
no_polys = vtkPolyData()
no_polys.SetPoints(sphere(mid, 0.3 * size).GetPoints())
NOTE = "The Body surface encloses no point of the grid"
OPEN = ("The Body input is not a closed surface (it has boundary or non-manifold edges), so its "
        "inside is not defined.")
NO_POLYS = "The Body input has no polygons: it must be a closed surface (vtkPolyData)"
BODIES = {"sphere": (sphere(mid, 0.3 * size), None),
          "two overlapping spheres": (two.GetOutput(), None),
          "a sphere beside the grid": (sphere([vb[1] + size, mid[1], mid[2]], 0.2 * size), NOTE),
          "an open surface (a plane)": (plane.GetOutput(), OPEN),
          "points without polygons": (no_polys, NO_POLYS)}
for case, (surface, said) in BODIES.items():
    ref = RI()
    ref.SetInputData(volume)
    ref.SetInputData(1, surface)
    ref.SetModel(0)
    ref.SetInputArrayToProcess(0, 0, 0, 0, "n_minus_1")
    with Captured() as c_cxx:
        ok = ref.GetExecutive().Update()
    theirs = ref.GetOutput()
    index = ns["RefractiveIndex"](Input=producer(volume), Body=producer(surface),
                                  Model="Passthrough", InputArray=["POINTS", "n_minus_1"])
    with Captured() as c:
        index.UpdatePipeline()
    mine = servermanager.Fetch(index)
    refused = said is not None and said != NOTE
    if refused:
        check(not ok and said in c.text and said in c_cxx.text and "Traceback" not in c.text and
              mine.GetNumberOfPoints() == 0,
              "Body %s: refused by both with the C++ filter's message, an empty output (%s...)"
              % (case, said))
    else:
        arrays = ("n_minus_1", "grad_n") + (("solid",) if said is None else ())
        same = ok and all(
            array(mine, n) is not None and array(theirs, n) is not None and
            np.array_equal(array(mine, n).view(np.uint8), array(theirs, n).view(np.uint8))
            for n in arrays) and (said is None or (array(mine, "solid") is None and
                                                    array(theirs, "solid") is None))
        solid = array(theirs, "solid")
        check(same and field_data(mine) == field_data(theirs) and "ERR" not in c.text and
              (said is None or (said in c.text and said in c_cxx.text)) and
              (said is not None or int(solid.sum()) > 0),
              "Body %s: %s, n_minus_1, grad_n and field data bit for bit the C++ filter's (%s "
              "solid points%s)" % (case, "solid" if said is None else "no solid",
                                   0 if solid is None else int(solid.sum()),
                                   "" if said is None else "; both note: " + said))
    Delete(index)

# -- 7. Symmetry Planar and Axisymmetric, a wedge with no axis typed: the engine's plan, samples and
# expansion through both front ends
# the 2D inputs the matrix of frontend_matrix.py uses too (one definition)
from frontend_matrix import _plane as plane, _wedge as wedge  # noqa: E402


def unstructured(data):
    a = vtkAppendFilter()
    a.SetInputData(data)
    a.Update()
    return a.GetOutput()


FIELDS = ("index_model", "index_arrays", "valid_point_fraction", "solid_points")


def field_values(d):
    out = {}
    for n in FIELDS:
        a = d.GetFieldData().GetAbstractArray(n)
        if a is not None:
            out[n] = [a.GetVariantValue(i).ToString() for i in range(a.GetNumberOfValues())]
    return out


SYMMETRY = {
    "planar_image": (plane((0, 16, 0, 12, 0, 0), False), dict(Symmetry="Planar", Span=0.6)),
    "planar_unstructured": (unstructured(plane((0, 16, 0, 12, 0, 0), False)),
                            dict(Symmetry="Planar", Span=0.6, AutomaticDimension=40)),
    "axisymmetric_cone": (unstructured(plane((0, 20, 0, 10, 0, 0), True)),
                          dict(Symmetry="Axisymmetric", SymmetryAxis="X",
                               AutomaticDimension=36)),
    "wedge_no_axis_typed": (wedge(), dict(Symmetry="Axisymmetric", AutomaticDimension=30)),
}
for case, (data, props) in SYMMETRY.items():
    ref = RI()
    ref.SetInputData(data)
    ref.SetModel(ENUMS["Model"]["GladstoneDale"])
    ref.SetInputArrayToProcess(0, 0, 0, 0, "density")
    ref.SetSymmetry(["None", "Planar", "Axisymmetric"].index(props["Symmetry"]))
    ref.SetSymmetryAxis("XYZ".index(props.get("SymmetryAxis", "X")))
    ref.SetSpan(props.get("Span", 1.0))
    ref.SetAutomaticDimension(props.get("AutomaticDimension", 128))
    ok = ref.GetExecutive().Update()
    theirs = vtkImageData()
    theirs.DeepCopy(ref.GetOutput())
    source = producer(data)
    index = ns["RefractiveIndex"](Input=source, Model="GladstoneDale", **props)
    index.InputArray = ["POINTS", "density"]
    with Captured() as c:
        index.UpdatePipeline()
    mine = servermanager.Fetch(index)
    info = tuple(int(v) for v in index.GetDataInformation().DataInformation.GetExtent())
    same = ok and mine.GetExtent() == theirs.GetExtent() and info == theirs.GetExtent() and \
        mine.GetOrigin() == theirs.GetOrigin() and mine.GetSpacing() == theirs.GetSpacing() and \
        all(array(mine, n) is not None and array(theirs, n) is not None and
            np.array_equal(array(mine, n).view(np.uint32), array(theirs, n).view(np.uint32))
            for n in ("n_minus_1", "grad_n")) and \
        field_values(mine) == field_values(theirs) and len(field_values(theirs)) == 4
    valid = field_values(theirs).get("valid_point_fraction")
    check(same and "ERR" not in c.text and "Traceback" not in c.text,
          "Symmetry %s: the C++ filter's grid %s (also in the pipeline's information), n_minus_1, "
          "grad_n and field data bit for bit (valid_point_fraction %s)%s"
          % (case, theirs.GetDimensions(), valid, "" if "ERR" not in c.text else
             "; " + c.text.strip().splitlines()[0][:200]))
    view = dict(ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0]) if props["Symmetry"] == "Planar" else \
        dict(ViewDirection=[0, 0, -1] if case != "wedge_no_axis_typed" else [1, 0, 0],
             ViewUp=[0, 1, 0] if case != "wedge_no_axis_typed" else [0, 1, 0])
    settings = dict(Resolution=[48, 40], Passes=1, **view)
    image = ns["SchlierenImage"](Input=index, Backend="CPU", **settings)
    image.UpdatePipeline()
    out = servermanager.Fetch(image)
    film, film_ok = cxx_image(theirs, **settings)
    intensity = array(film, "intensity")
    check(film_ok and same_film(out, film) and intensity is not None and
          float(intensity.max() - intensity.min()) > 0.05,
          "SchlierenImage on it: the C++ filter's film bit for bit (intensity %.3f..%.3f)"
          % ((intensity.min(), intensity.max()) if intensity is not None else (0, 0)))
    Delete(image)
    Delete(index)
# the wedge traced with Symmetry None: the C++ filter's warning, word for word
wedge_data = SYMMETRY["wedge_no_axis_typed"][0]
ref = RI()
ref.SetInputData(wedge_data)
ref.SetModel(ENUMS["Model"]["GladstoneDale"])
ref.SetInputArrayToProcess(0, 0, 0, 0, "density")
ref.SetAutomaticDimension(24)
with Captured() as c_cxx:
    ref.Update()
index = ns["RefractiveIndex"](Input=producer(wedge_data), Model="GladstoneDale",
                              AutomaticDimension=24)
index.InputArray = ["POINTS", "density"]
with Captured() as c:
    index.UpdatePipeline()
said = "The input is an axisymmetric wedge (OpenFOAM's way: two planes 5 deg apart through the " \
    "line along y at x = 0.3, z = 0.1, one cell across). With Symmetry None it is traced as it " \
    "is: a 5 deg slab of gas"
check(said in c.text and said in c_cxx.text and "Traceback" not in c.text,
      "the wedge with Symmetry None: the C++ filter's warning, word for word (%r)"
      % c.text.strip()[-160:])
Delete(index)
# refusals: the C++ filter's messages, word for word, and an empty output
REFUSED = {
    "Span 0": (plane((0, 16, 0, 12, 0, 0), False), dict(Symmetry="Planar", Span=0.0),
               "Span is 0.000000: it must be positive"),
    "a 3D mesh": (unstructured(volume), dict(Symmetry="Planar"),
                  "Symmetry Planar expects a 2D plane normal to x, y or z; the input spans"),
    "SymmetryAxis Z, normal to the plane": (
        unstructured(plane((0, 20, 0, 10, 0, 0), True)),
        dict(Symmetry="Axisymmetric", SymmetryAxis="Z"),
        "SymmetryAxis z is normal to the input's plane"),
}
for case, (data, props, message) in REFUSED.items():
    ref = RI()
    ref.SetInputData(data)
    ref.SetModel(ENUMS["Model"]["GladstoneDale"])
    ref.SetInputArrayToProcess(0, 0, 0, 0, "density" if case != "a 3D mesh" else "n_minus_1")
    ref.SetSymmetry(["None", "Planar", "Axisymmetric"].index(props["Symmetry"]))
    ref.SetSymmetryAxis("XYZ".index(props.get("SymmetryAxis", "X")))
    ref.SetSpan(props.get("Span", 1.0))
    with Captured() as c_cxx:
        ref.GetExecutive().Update()
    index = ns["RefractiveIndex"](Input=producer(data), Model="GladstoneDale", **props)
    index.InputArray = ["POINTS", "density" if case != "a 3D mesh" else "n_minus_1"]
    with Captured() as c:
        index.UpdatePipeline()
    out = servermanager.Fetch(index)
    check(message in c.text and message in c_cxx.text and "Traceback" not in c.text and
          out.GetNumberOfPoints() == 0,
          "Symmetry refused (%s): the C++ filter's message, an empty output (%r)"
          % (case, c.text.strip().splitlines()[0][-120:] if c.text.strip() else ""))
    Delete(index)

# -- 10. an overlapping AMR (vtkOverlappingAMR): both read it into the engine's AMR sampler
# (schlieren_amr_sample, OpenCL/SchlierenAMRSample.h): level 0 of 16^3 cells over [-1, 1]^3, level
# 1 two boxes side by side (sharing a face) over [-0.5, 0.5]^3 at half the spacing, a Gaussian
# density a little higher on level 1 (so that the finest level's choice shows), as point data and
# as cell data
sys.path.insert(0, HERE)
from amr_cases import two_level_amr as amr_case  # noqa: E402


AMR_FIELDS = FIELDS + ("index_notes", "amr_levels", "amr_finest_level", "amr_finest_spacing",
                       "sampling_spacing", "sampling_capped")


def amr_fields(d):
    out = {}
    for n in AMR_FIELDS:
        a = d.GetFieldData().GetAbstractArray(n)
        if a is not None:
            out[n] = [a.GetVariantValue(i).ToString() for i in range(a.GetNumberOfValues())]
    return out


for kind in ("point", "cell"):
    data = amr_case(kind == "cell")
    ref = RI()
    ref.SetInputData(data)
    ref.SetModel(ENUMS["Model"]["GladstoneDale"])
    ref.SetInputArrayToProcess(0, 0, 0, 0, "density")
    ok = ref.GetExecutive().Update()
    theirs = vtkImageData()
    theirs.DeepCopy(ref.GetOutput())
    index = ns["RefractiveIndex"](Input=producer(data), Model="GladstoneDale")
    index.InputArray = ["POINTS", "density"]
    with Captured() as c:
        index.UpdatePipeline()
    mine = servermanager.Fetch(index)
    info = tuple(int(v) for v in index.GetDataInformation().DataInformation.GetExtent())
    mf, tf = amr_fields(mine), amr_fields(theirs)
    same = ok and mine.GetExtent() == theirs.GetExtent() and info == theirs.GetExtent() and \
        mine.GetOrigin() == theirs.GetOrigin() and mine.GetSpacing() == theirs.GetSpacing() and \
        all(array(mine, n) is not None and array(theirs, n) is not None and
            np.array_equal(array(mine, n).view(np.uint32), array(theirs, n).view(np.uint32))
            for n in ("n_minus_1", "grad_n")) and mf == tf and len(tf) == len(AMR_FIELDS)
    check(same and theirs.GetDimensions() == (33, 33, 33) and "ERR" not in c.text and
          "Traceback" not in c.text,
          "AMR with %s data (two levels, level 1 two boxes): the C++ filter's grid %s (the finest "
          "level's spacing, also in the pipeline's information), n_minus_1, grad_n and field data "
          "(index_notes, amr_*, sampling_*) bit for bit%s"
          % (kind, theirs.GetDimensions(), "" if mf == tf else "; fields %s vs %s" % (mf, tf)))
    settings = dict(Resolution=[48, 40], Passes=1, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0])
    image = ns["SchlierenImage"](Input=index, Backend="CPU", **settings)
    image.UpdatePipeline()
    out = servermanager.Fetch(image)
    film, film_ok = cxx_image(theirs, **settings)
    intensity = array(film, "intensity")
    check(film_ok and same_film(out, film) and intensity is not None and
          float(intensity.max() - intensity.min()) > 0.05,
          "SchlierenImage on it: the C++ filter's film bit for bit (intensity %.3f..%.3f)"
          % ((intensity.min(), intensity.max()) if intensity is not None else (0, 0)))
    Delete(image)
    Delete(index)
# boxes of one level that share cells: the C++ filter's refusal, word for word, an empty output
data = amr_case(False)
from vtkmodules.vtkCommonDataModel import vtkAMRBox  # noqa: E402
data.SetAMRBox(1, 1, vtkAMRBox([-0.25, -0.5, -0.5], [9, 17, 17], [0.0625] * 3, [-1.0] * 3, 8))
ref = RI()
ref.SetInputData(data)
ref.SetModel(ENUMS["Model"]["GladstoneDale"])
ref.SetInputArrayToProcess(0, 0, 0, 0, "density")
with Captured() as c_cxx:
    ref.GetExecutive().Update()
index = ns["RefractiveIndex"](Input=producer(data), Model="GladstoneDale")
index.InputArray = ["POINTS", "density"]
with Captured() as c:
    index.UpdatePipeline()
out = servermanager.Fetch(index)
said = "the AMR input's level 1 has boxes that overlap: boxes 0 and 1 share 1024 cells"
check(said in c.text and said in c_cxx.text and "Traceback" not in c.text and
      out.GetNumberOfPoints() == 0,
      "AMR boxes of one level that overlap: the C++ filter's message, an empty output (%r)"
      % (c.text.strip().splitlines()[0][-160:] if c.text.strip() else ""))
Delete(index)

# -- 9. RefractiveIndex's parity matrix (frontend_cases.INDEX): the inputs the reference run wrote,
# through the Python plugin's RefractiveIndex and SchlierenImage proxies, against the C++ plugin's
# records bit for bit (the pip VTK leg: test_frontend.py)
if args.reference is None:
    print("SKIP the matrix: no --reference (frontend_reference.py's output)")
else:
    sys.path.insert(0, HERE)
    import frontend_cases as cases  # noqa: E402
    import frontend_matrix as matrix  # noqa: E402
    compared, matrix_started = 0, time.time()
    for case, (which, props, image_props) in cases.INDEX.items():
        path = os.path.join(args.reference, "index_%s.npz" % case)
        if not os.path.exists(path):
            print("SKIP %s: the reference run left it out (no %s data)" % (case, which))
            continue
        source = producer(matrix.read_input(args.reference, which))
        body = {} if case not in cases.INDEX_BODY else {  # the Body input (port 1)
            "Body": producer(matrix.read_input(args.reference, cases.INDEX_BODY[case]))}
        index = ns["RefractiveIndex"](Input=source, **body, **matrix.proxy_properties(props, case))
        image = ns["SchlierenImage"](Input=index, **dict(cases.INDEX_IMAGE, **image_props))
        with Captured() as c:
            image.UpdatePipeline()
        matrix.compare(case, matrix.record(servermanager.Fetch(index), servermanager.Fetch(image)),
                       np.load(path), check, "Python plugin")
        check("Traceback" not in c.text and "ERR" not in c.text,
              "%s (Python plugin): no error%s" % (case, "" if "ERR" not in c.text else
                                                   ": " + c.text.strip()[-200:]))
        compared += 1
        for proxy in [image, index, source] + list(body.values()):
            Delete(proxy)
    matrix.known_differences()
    print("RefractiveIndex's matrix in %.1f s" % (time.time() - matrix_started))
    check(compared >= len([c for c in cases.INDEX.values()
                           if c[0] not in cases.INDEX_OPTIONAL_INPUTS]),
          "RefractiveIndex's matrix: %d of %d cases compared (the others need ../shared/data or "
          "the suite's OpenFOAM cases)" % (compared, len(cases.INDEX)))

# -- 8. NumericalSchlieren's progress and abort, in both plugins: a LineOfSight image of a 48^3
# volume on a 384 x 384 film (14 M samples: about a second here, four blocks of rows with the
# progress between them) reports progress from 0 to 1 in several steps, an observer that aborts at
# the first progress event stops it there (the engine's "aborted at 0 % of the image: no image", an
# empty output, the abort spent), and the next update gives the image of a fresh filter bit for bit
big_scene = cxx.vtkRefractiveScene()
big_scene.SetDimensions(48, 48, 48)
big_scene.Update()
big = vtkImageData()
big.DeepCopy(big_scene.GetOutput())
numerical_settings = dict(Mode="LineOfSight", Resolution=[384, 384], ViewDirection=[0.2, 0.1, -1])


def cxx_numerical():
    f = cxx.vtkNumericalSchlieren()
    f.SetInputData(big)
    f.SetMode(1)
    f.SetResolution(384, 384)
    f.SetViewDirection(0.2, 0.1, -1)
    return f, f


def py_numerical():
    p = ns["NumericalSchlieren"](Input=producer(big), **numerical_settings)
    return p, p.GetClientSideObject()


fresh, _ = cxx_numerical()
fresh.Update()
want = fresh.GetOutput()
for which, make in (("C++", cxx_numerical), ("Python", py_numerical)):
    runner, algorithm = make()
    seen = []

    def abort_at_once(obj, _event):  # as ParaView's abort: once
        seen.append(obj.GetProgress())
        if len(seen) == 1:
            obj.SetAbortExecute(1)
    tag = algorithm.AddObserver("ProgressEvent", abort_at_once)
    started = time.time()
    with Captured() as c:
        (runner.UpdatePipeline if which == "Python" else runner.Update)()
    aborted_s = time.time() - started
    out = algorithm.GetOutputDataObject(0)  # (a Fetch would update it again)
    check(out.GetNumberOfPoints() == 0 and "aborted at 0 % of the image: no image" in c.text and
          "Traceback" not in c.text and len(seen) <= 3 and not algorithm.GetAbortExecute(),
          "%s NumericalSchlieren with an observer aborting at the first progress event: stopped "
          "there (%.2f s, progress %s), an empty output, the engine's message, the abort spent"
          % (which, aborted_s, seen))
    algorithm.RemoveObserver(tag)
    del seen[:]
    algorithm.AddObserver("ProgressEvent", lambda obj, _e: seen.append(obj.GetProgress()))
    algorithm.Modified()  # (a proxy's UpdatePipeline would see no property changed)
    started = time.time()
    with Captured() as c:
        algorithm.Update()
    whole_s = time.time() - started
    out = algorithm.GetOutputDataObject(0)
    check(out.GetNumberOfPoints() == 384 * 384 and "ERR" not in c.text and
          all(array(out, n) is not None and
              np.array_equal(array(out, n).view(np.uint8), array(want, n).view(np.uint8))
              for n in ("intensity", "numerical_gradient", "blocked")) and
          len(seen) >= 4 and seen == sorted(seen) and seen[-1] == 1.0,
          "%s NumericalSchlieren updated again: the image of a fresh filter bit for bit (%.2f s), "
          "progress in %d steps from %s to %s" % (which, whole_s, len(seen), seen[:1], seen[-1:]))
    if which == "Python":
        Delete(runner)

# -- 4. schlieren_view embedded; Examples/first_light.py with the Python plugin
try:
    import schlieren_view
    check(hasattr(schlieren_view, "follow_camera"), "import schlieren_view after LoadPlugin")
except ImportError as e:
    check(False, "import schlieren_view after LoadPlugin (%s)" % e)
shim = os.path.join(args.work, "first_light_shim.py")
with open(shim, "w") as f:
    f.write("import collections, inspect, runpy, sys\n"
            "if not hasattr(inspect, 'getargspec'):\n"
            "    A = collections.namedtuple('ArgSpec', 'args varargs keywords defaults')\n"
            "    inspect.getargspec = lambda f: A(*inspect.getfullargspec(f)[:4])\n"
            "sys.argv = sys.argv[1:]\n"
            "runpy.run_path(sys.argv[0], run_name='__main__')\n")
pngs, runs = {}, {}
for which, plugin in (("python", args.plugin), ("cxx", args.cxx_plugin)):  # the two at once
    pngs[which] = os.path.join(args.work, "first_light_%s.png" % which)
    if os.path.exists(pngs[which]):
        os.remove(pngs[which])
    runs[which] = subprocess.Popen(
        [args.pvpython, shim, args.example, "--plugin", plugin, "--output", pngs[which],
         "--backend", "CPU", "--resolution", "64", "--passes", "1"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
for which, p in runs.items():
    output = p.communicate(timeout=300)[0]
    check(p.returncode == 0 and os.path.exists(pngs[which]),
          "Examples/first_light.py with the %s plugin (rc %d%s)"
          % (which, p.returncode, "" if p.returncode == 0 else ": " + output[-400:]))
if all(os.path.exists(p) for p in pngs.values()):
    with open(pngs["python"], "rb") as f, open(pngs["cxx"], "rb") as g:
        check(f.read() == g.read(), "its PNG equals the C++ plugin's bit for bit")
# -- 11. the per-time-step cache (the engine's rule, schlieren_time_cache_*, as the C++ filter's):
# a Python source with 4 time steps (a ProgrammableSource counting its executions) through the
# Python plugin's RefractiveIndex and SchlierenImage, the animation played twice. Last: a
# ProgrammableSource's script runs in __main__'s namespace, which it leaves with NumPy-interface
# functions named all, array... (hence builtins.all below)
import builtins  # noqa: E402
from paraview.simple import ProgrammableSource  # noqa: E402

TIMES = (0.0, 1.0, 2.0, 3.0)
SOURCE_INFO = """
executive = self.GetExecutive()
info = executive.GetOutputInformation(0)
info.Remove(executive.TIME_STEPS())
for t in %r:
    info.Append(executive.TIME_STEPS(), t)
info.Set(executive.TIME_RANGE(), [%r, %r], 2)
info.Set(executive.WHOLE_EXTENT(), 0, 19, 0, 17, 0, 15)
""" % (TIMES, TIMES[0], TIMES[-1])
SOURCE = """
import builtins
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
builtins.schlieren_source_runs = getattr(builtins, "schlieren_source_runs", 0) + 1
info = self.GetOutputInformation(0)
key = self.GetExecutive().UPDATE_TIME_STEP()
t = info.Get(key) if info.Has(key) else 0.0
out = self.GetOutput()
out.SetExtent(0, 19, 0, 17, 0, 15)
out.SetSpacing(0.1, 0.1, 0.1)
z, y, x = np.meshgrid(0.1 * np.arange(16), 0.1 * np.arange(18), 0.1 * np.arange(20), indexing="ij")
r = 0.3 + 0.1 * t
rho = 1.2 + 0.5 * np.exp(-((x - 1.0) ** 2 + (y - 0.85) ** 2 + (z - 0.75) ** 2) / (r * r))
a = numpy_to_vtk(rho.ravel().astype(np.float32), deep=1)
a.SetName("density")
out.GetPointData().AddArray(a)
"""
builtins.schlieren_source_runs = 0
timed = ProgrammableSource(OutputDataSetType="vtkImageData", Script=SOURCE,
                           ScriptRequestInformation=SOURCE_INFO)
timed_index = ns["RefractiveIndex"](Input=timed, Model="GladstoneDale")
timed_index.InputArray = ["POINTS", "density"]
timed_image = ns["SchlierenImage"](Input=timed_index, Backend="CPU", Resolution=[32, 32], Passes=1)
timed.UpdatePipelineInformation()


def cache_fields():
    fd = timed_index.GetClientSideObject().GetOutputDataObject(0).GetFieldData()
    return {n: (fd.GetArray(n).GetValue(0) if fd.GetArray(n) else None)
            for n in ("index_computed", "index_from_cache", "index_cache_entries")}


def timed_frame(t):
    with Captured():
        timed_image.UpdatePipeline(t)
    out = timed_image.GetClientSideObject().GetOutputDataObject(0)
    intensity = numpy_support.vtk_to_numpy(out.GetPointData().GetArray("intensity")).copy()
    return intensity, builtins.schlieren_source_runs, cache_fields()


plays = [[timed_frame(t) for t in TIMES] for _ in range(2)]
first, second = plays
check([f[1] for f in first] == [1, 2, 3, 4] and
      [f[2]["index_computed"] for f in first] == [1, 2, 3, 4] and
      builtins.all(f[2]["index_from_cache"] == 0 for f in first) and
      builtins.all(not np.array_equal(first[k][0], first[k - 1][0]) for k in range(1, 4)),
      "time cache, first play of 4 steps: the Python source ran %s times, RefractiveIndex "
      "computed %s, each frame differs from the one before"
      % ([f[1] for f in first], [f[2]["index_computed"] for f in first]))
check([f[1] for f in second] == [4] * 4 and
      builtins.all(f[2]["index_computed"] == 4 and f[2]["index_from_cache"] == 1 and
          f[2]["index_cache_entries"] == 4 for f in second) and
      builtins.all(np.array_equal(second[k][0].view(np.uint32), first[k][0].view(np.uint32))
          for k in range(4)),
      "time cache, second play: the Python source not executed again (runs %s), every step from "
      "the cache (%s), the first play's images bit for bit"
      % ([f[1] for f in second], [f[2] for f in second]))
timed.Script = SOURCE.replace("r = 0.3 +", "r = 0.35 +")  # upstream changed: nothing kept applies
changed = timed_frame(TIMES[1])
check(changed[1] == 5 and changed[2]["index_computed"] == 5 and
      changed[2]["index_from_cache"] == 0 and changed[2]["index_cache_entries"] == 1 and
      not np.array_equal(changed[0], first[1][0]),
      "time cache, the source's script changed: executed and computed again, the old entries "
      "dropped, another image (runs %d, %s)" % (changed[1], changed[2]))
timed_index.DensityReference = 1.1  # RefractiveIndex's own property: its token changes too
again = timed_frame(TIMES[1])
check(again[1] == 5 and again[2]["index_computed"] == 6 and again[2]["index_from_cache"] == 0,
      "time cache, DensityReference changed: computed again without executing the source (runs "
      "%d, %s)" % (again[1], again[2]))
for proxy in (timed_image, timed_index, timed):
    Delete(proxy)

# -- 12. a mesh that moves and stretches over time (issue 47: the engine's FollowBounds in both):
# the second step, x stretched by 1.5 and moved by 0.5, on the grid set over the first step's
# bounds with the same points; the C++ filter and the Python plugin give the same grid, n - 1 and
# note (before issue 47 the Python front end set a new grid from AutomaticDimension: 11 x 8 x 8
# points where the C++ filter kept 11 x 11 x 11)
import tempfile  # noqa: E402
from paraview.simple import XMLUnstructuredGridReader  # noqa: E402
import schlieren_testing as st  # noqa: E402

steps = [os.path.join(tempfile.mkdtemp(prefix="parity_moving_"), "mesh_%d.vtu" % i) for i in (0, 1)]
st.moving_mesh(steps[0], 0.0)
st.moving_mesh(steps[1], 0.5, 1.5)
series, series_cxx = XMLUnstructuredGridReader(FileName=steps), XMLUnstructuredGridReader(FileName=steps)
series.UpdatePipelineInformation()
series_cxx.UpdatePipelineInformation()  # its own reader: each pipeline sets its grid on step 0
moving_py = ns["RefractiveIndex"](Input=series, Model="GladstoneDale", AutomaticDimension=11)
moving_py.InputArray = ["POINTS", "density"]
moving_cxx = cxx.vtkRefractiveIndex()
moving_cxx.SetInputConnection(series_cxx.GetClientSideObject().GetOutputPort())
moving_cxx.SetModel(RI.GLADSTONE_DALE)
moving_cxx.SetAutomaticDimension(11)
moving_cxx.SetInputArrayToProcess(0, 0, 0, 0, "density")
with Captured():
    moving_py.UpdatePipeline(0.0)
    moving_py.UpdatePipeline(1.0)
    moving_cxx.UpdateTimeStep(0.0)
    moving_cxx.UpdateTimeStep(1.0)
mp = moving_py.GetClientSideObject().GetOutputDataObject(0)
mc = moving_cxx.GetOutputDataObject(0)
said = "the grid follows them, the same points over"
n1 = [numpy_support.vtk_to_numpy(d.GetPointData().GetArray("n_minus_1")).view(np.uint32)
      for d in (mp, mc)]  # (`array` is the ProgrammableSource's NumPy interface's by now)
check(mp.GetExtent() == mc.GetExtent() == (0, 10, 0, 10, 0, 10) and
      mp.GetOrigin() == mc.GetOrigin() and mp.GetSpacing() == mc.GetSpacing() and
      np.array_equal(n1[0], n1[1]),
      "a mesh stretched and moved at its second step: the C++ filter's grid (%s %s %s; C++ %s %s "
      "%s) and n - 1 bit for bit" % (mp.GetExtent(), mp.GetOrigin(), mp.GetSpacing(),
                                     mc.GetExtent(), mc.GetOrigin(), mc.GetSpacing()))


def notes_of(d):
    a = d.GetFieldData().GetAbstractArray("index_notes")
    return [a.GetValue(i) for i in range(a.GetNumberOfValues())] if a is not None else []


moved_notes = [[n for n in notes_of(d) if said in n] for d in (mp, mc)]
check(len(moved_notes[0]) == 1 and moved_notes[0] == moved_notes[1],
      "... and the same note in index_notes of both (%s; C++ %s)" % tuple(moved_notes))
Delete(moving_py)
Delete(series)
Delete(series_cxx)

print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
