# SPDX-License-Identifier: BSD-3-Clause
"""Issue 48: cases outside the physics' assumptions are refused (or handled) with the reason,
never imaged silently with a model outside its validity. Each of these gave a silent wrong image
on the main branch before issue 48.

1. NumericalSchlieren with NaN and Inf in the density (the C++ filter, and the Python front end's
   engine call): an error saying how many points are NaN or Inf, no image (it gave NaN pixels or a
   white image with gradient_maximum 0). NaN where vtkValidPointMask is 0 is accepted.
2. The bench outside its closed forms: a slit of 10 m at f1 = 1 mm (h/f1 = 1e4: a flat film and a
   resolvable deflection of 39 rad) refused naming h/f1 and the limit 0.2; a slit at h/f1 = 0.2
   accepted. A camera lens inside the test section (CameraDistance 0.05 m in a 2 m box) refused;
   BOS with the volume's centre within the focal length (M_A = f / (Z_A - f) < 0) refused.
3. SchlierenImage with KnifeAngle 400: an error and no image (it output an image traced at 400).
4. Wedges (RefractiveIndex): an OpenFOAM-style 5 degree wedge (one cell across, prisms on the
   axis, cell data, in a multiblock) at the defaults (Symmetry None) gets a warning naming it and
   what to set (it was traced as a 5 degree slab of gas without a word), and under Axisymmetric
   is revolved; a wedge whose axis is tilted 20 degrees (turned about its radial axis) is refused
   with the reason (it was revolved about x); a 30 degree wedge's error names the 10 degree limit
   (it was called a 3D volume).
5. AMR with two boxes that overlap on one level (one box's values were dropped without a word):
   refused naming the level, the boxes and the cells they share; two boxes sharing a face are
   resampled as before.
6. A time series whose mesh moves (two unstructured steps, the second moved by 0.5 along x): the
   second step's sampling box follows its bounds, and its image is that step's traced alone (the
   first step's box was kept: |dI| 0.2 to 0.5).
7. Messages: a mesh of patches with no internal mesh (SamplingBounds off) is told that its cells
   enclose no volume, with its cells counted by dimension (it was told to "check
   SamplingBounds"); with SamplingBounds on and outside the mesh, "check SamplingBounds".
   RefractionOctree's Tolerance out of range says what the tolerance is (it spoke of units).

Run: pvpython test_physics_sense.py --plugin <Schlieren.so> --engine <libschlieren_engine.so.1>
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_physics_sense")


def fetch(proxy):
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy)
    return data, out.text


def field(data, name):
    a = data.GetFieldData().GetAbstractArray(name)
    return None if a is None else a.GetVariantValue(0).ToString()


# ------------------------------------------------------------------ 1. NumericalSchlieren NaN
scene = RefractiveScene(Scene="Uniform", Dimensions=[17, 13, 9], Bounds=[-1, 1, -0.5, 0.5, -0.4, 0.4])
ramp = Calculator(Input=scene, ResultArrayName="ramp", Function="1.2 + 0.3 * coordsX")
# NaN on the plane x = 0.5 (13 x 9 = 117 points)
nan_ramp = PythonCalculator(Input=ramp, ArrayName="ramp",
                            Expression="where(abs(ramp - 1.35) < 0.01, float('nan'), ramp)")
ns = NumericalSchlieren(Input=nan_ramp, DensityArray="ramp", Resolution=[40, 20])
data, text = fetch(ns)
T.check("ERROR" in text and "117 of 1989 points of the flow are NaN or Inf" in text,
        "NumericalSchlieren of a density with NaN: an error counting them")
T.check(data.GetNumberOfPoints() == 0, "NumericalSchlieren of a density with NaN: no image")
# the same NaN where vtkValidPointMask says there is no data: accepted, the ramp's gradient
masked = PythonCalculator(Input=nan_ramp, ArrayName="vtkValidPointMask",
                          Expression="where(ramp != ramp, 0, 1)")
ns_masked = NumericalSchlieren(Input=masked, DensityArray="ramp", Resolution=[40, 20])
data, text = fetch(ns_masked)
T.check(data.GetNumberOfPoints() == 800 and "ERROR" not in text,
        "NaN only where vtkValidPointMask is 0: an image, no error")
if data.GetNumberOfPoints():
    T.close(float(field(data, "gradient_maximum")), 0.3, 1e-5,
            "NaN masked out: the ramp's gradient 0.3 as the maximum")

# the Python front end: the engine's C interface refuses the same field
engine_path = st.argument("--engine")
if engine_path:
    os.environ["SCHLIEREN_ENGINE_LIBRARY"] = engine_path
    sys.path.insert(0, os.path.join(HERE, "..", "..", "Python"))
    from schlieren import _engine

    values = np.full(17 * 13 * 9, 1.2, np.float32)
    values[100] = np.nan
    values[101] = np.inf
    try:
        _engine.numerical({"Resolution": [40, 20]}, [17, 13, 9], [-1, -0.5, -0.4], [0.125, 1 / 12, 0.1], values)
        said = ""
    except _engine.EngineError as e:
        said = str(e)
    T.check("2 of 1989 points of the flow are NaN or Inf" in said,
            "Python front end (schlieren._engine.numerical): NaN and Inf refused (%s)" % said[:160])
else:
    T.check(False, "--engine <libschlieren_engine.so.1> was not given")


# ------------------------------------------------------------------ 2. the bench and the camera
sphere = RefractiveScene(Scene="GaussianSphere", Dimensions=[24, 24, 24], Amplitude=1e-4, Width=0.25)
def image(**props):
    im = SchlierenImage(Input=sphere, Resolution=[24, 24], Passes=1, Backend="CPU", **props)
    data, text = fetch(im)
    Delete(im)
    return data, text


data, text = image(Source="Slit", SourceSize=[10000, 1], CollimatorFocalLength=0.001)
T.check("ERROR" in text and "h/f1 = 10000" in text and "h/f1 <= 0.2" in text and data.GetNumberOfPoints() == 0,
        "a 10 m slit at f1 = 1 mm (h/f1 = 1e4): refused naming h/f1 and the limit, no image")
data, text = image(Source="Slit", SourceSize=[200, 1], CollimatorFocalLength=1.0)
T.check("ERROR" not in text and data.GetNumberOfPoints() == 24 * 24,
        "a 200 mm slit at f1 = 1 m (h/f1 = 0.2, the limit): traced")
if data.GetNumberOfPoints():
    T.close(float(field(data, "bench_resolvable_deflection")), 0.2 / 255, 1e-9,
            "h/f1 = 0.2: resolvable deflection a0 / (255 f2) = 7.8e-4 rad")
# the scene's box is [-1, 1]^3: a lens 0.05 m from its centre is inside it
data, text = image(Camera="Ideal", CameraFocalLength=0.01, CameraDistance=0.05)
T.check("ERROR" in text and "inside the volume" in text and data.GetNumberOfPoints() == 0,
        "CameraDistance 0.05 m in a 2 m box: refused (the lens inside the volume), no image")
data, text = image(Cutoff="BOS", Camera="Ideal", CameraFocalLength=2.0, CameraDistance=1.5, FocusPlane=-2.0)
T.check("ERROR" in text and "M_A = f / (Z_A - f) = -4" in text and data.GetNumberOfPoints() == 0,
        "BOS with the volume's centre within the focal length (Z_A 1.5 m, f 2 m): refused, no image")
data, text = image(Cutoff="BOS", Camera="Ideal", CameraFocalLength=0.5, CameraDistance=1.5, FocusPlane=-2.0)
T.check("ERROR" not in text and float(field(data, "bos_pixels_per_radian") or 0) > 0,
        "BOS with Z_A 1.5 m beyond f 0.5 m: traced, bos_pixels_per_radian > 0")

# ------------------------------------------------------------------ 3. KnifeAngle out of range
im = SchlierenImage(Input=sphere, Resolution=[24, 24], Passes=1, Backend="CPU")
data, text = fetch(im)
T.check(data.GetNumberOfPoints() == 24 * 24, "KnifeAngle 0: an image")
im.KnifeAngle = 400
data, text = fetch(im)
T.check("ERROR" in text and "KnifeAngle is 400" in text, "KnifeAngle 400: an error naming it")
T.check(data.GetNumberOfPoints() == 0, "KnifeAngle 400: no image (was an image traced at 400 degrees)")
Delete(im)

# ------------------------------------------------------------------ 4. wedges
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_HEXAHEDRON, VTK_WEDGE, vtkMultiBlockDataSet, vtkUnstructuredGrid
import cfd_testing as cfd


def wedge_mesh(angle_deg, tilt_deg=0.0, nx=21, nr=11, length=1.0, radius=0.5):
    """An OpenFOAM-style axisymmetric wedge: the axis along x (turned by tilt_deg about y), the
    mesh at y >= 0 between the planes z = +-y tan(angle / 2), one cell across, prisms on the axis,
    the density as cell data, in a multiblock."""
    t = math.tan(math.radians(angle_deg) / 2)
    c, s_ = math.cos(math.radians(tilt_deg)), math.sin(math.radians(tilt_deg))
    pts = vtkPoints()
    index = {}

    def point(i, j, side):
        key = (i, 0, 0) if j == 0 else (i, j, side)
        if key not in index:
            x, y = length * i / (nx - 1), radius * j / (nr - 1)
            z = side * y * t
            index[key] = pts.InsertNextPoint(c * x + s_ * z, y, -s_ * x + c * z)
        return index[key]

    ug = vtkUnstructuredGrid()
    rho = vtkDoubleArray()
    rho.SetName("density")
    cells = []
    for i in range(nx - 1):
        for j in range(nr - 1):
            if j == 0:
                ids = [point(i, 0, 0), point(i, 1, -1), point(i, 1, 1),
                       point(i + 1, 0, 0), point(i + 1, 1, -1), point(i + 1, 1, 1)]
                cells.append((VTK_WEDGE, ids))
            else:
                ids = [point(i, j, -1), point(i, j + 1, -1), point(i, j + 1, 1), point(i, j, 1),
                       point(i + 1, j, -1), point(i + 1, j + 1, -1), point(i + 1, j + 1, 1), point(i + 1, j, 1)]
                cells.append((VTK_HEXAHEDRON, ids))
            xc, rc = length * (i + 0.5) / (nx - 1), radius * (j + 0.5) / (nr - 1)
            rho.InsertNextValue(1.2 + 0.5 * math.exp(-((xc - 0.5) ** 2 + rc ** 2) / 0.04))
    ug.SetPoints(pts)
    for kind, ids in cells:
        ug.InsertNextCell(kind, len(ids), ids)
    ug.GetCellData().AddArray(rho)
    mb = vtkMultiBlockDataSet()
    mb.SetBlock(0, ug)
    return mb


wedge5 = cfd.producer(globals(), wedge_mesh(5.0))
ri = RefractiveIndex(Input=wedge5, AutomaticDimension=32)
data, text = fetch(ri)
T.check("axisymmetric wedge" in text and "5 deg slab of gas" in text and "Set Symmetry to Axisymmetric" in text,
        "a 5 deg wedge at the defaults (Symmetry None): a warning naming the wedge and what to set")
ri.Symmetry = "Axisymmetric"
data, text = fetch(ri)
T.check("ERROR" not in text and "deg slab" not in text and data.GetNumberOfPoints() > 0 and
        "is an axisymmetric wedge (AxisFromWedge)" in text,
        "the same wedge under Symmetry Axisymmetric: revolved about the axis it found, no warning")
Delete(ri)

tilted = cfd.producer(globals(), wedge_mesh(5.0, tilt_deg=20.0))
ri = RefractiveIndex(Input=tilted, Symmetry="Axisymmetric", AutomaticDimension=32)
data, text = fetch(ri)
T.check("ERROR" in text and "tilted 20 deg from x (direction -0.94, 0, 0.342)" in text and data.GetNumberOfPoints() == 0,
        "a wedge whose axis is tilted 20 deg: refused with the reason (was revolved about x, 10 % valid)")
Delete(ri)

wide = cfd.producer(globals(), wedge_mesh(30.0))
ri = RefractiveIndex(Input=wide, Symmetry="Axisymmetric", AutomaticDimension=32)
data, text = fetch(ri)
T.check("ERROR" in text and "30 deg apart, more than the 10 deg" in text and "3D volume" not in text,
        "a 30 deg wedge: the error names the 10 deg limit (was called a 3D volume)")
Delete(ri)

# ------------------------------------------------------------------ 5. AMR boxes that overlap
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import vtkAMRBox, vtkAMRUtilities, vtkOverlappingAMR, vtkUniformGrid


def amr_block(lo, h, n, offset):
    """A vtkUniformGrid of n[0] x n[1] x n[2] cells from corner lo, spacing h, a Gaussian n - 1
    (+ offset) at its points."""
    g = vtkUniformGrid()
    g.SetOrigin(*lo)
    g.SetSpacing(h, h, h)
    g.SetDimensions(n[0] + 1, n[1] + 1, n[2] + 1)
    x = [lo[a] + h * np.arange(n[a] + 1) for a in range(3)]
    Z, Y, X = np.meshgrid(x[2], x[1], x[0], indexing="ij")
    a = numpy_to_vtk((1e-4 * np.exp(-(X ** 2 + Y ** 2 + Z ** 2) / 0.0625) + offset).ravel().astype(np.float32), deep=1)
    a.SetName("n_minus_1")
    g.GetPointData().AddArray(a)
    return g


def make_amr(x_ranges):
    """Level 0: [-1, 1]^3 in 8 cells a side; level 1 (spacing 0.125): a box over each x range,
    [-0.5, 0.5] in y and z, the second 1e-5 above the first."""
    h0, h1 = 0.25, 0.125
    amr = vtkOverlappingAMR()
    amr.Initialize(2, [1, len(x_ranges)])
    amr.SetOrigin([-1.0, -1.0, -1.0])
    amr.SetSpacing(0, [h0] * 3)
    amr.SetAMRBox(0, 0, vtkAMRBox([-1.0] * 3, [9] * 3, [h0] * 3, [-1.0] * 3, 8))
    amr.SetDataSet(0, 0, amr_block([-1.0] * 3, h0, [8] * 3, 0.0))
    amr.SetSpacing(1, [h1] * 3)
    for b, (x0, x1) in enumerate(x_ranges):
        n = [int(round((x1 - x0) / h1)), 8, 8]
        lo = [x0, -0.5, -0.5]
        amr.SetAMRBox(1, b, vtkAMRBox(lo, [n[0] + 1, 9, 9], [h1] * 3, [-1.0] * 3, 8))
        amr.SetDataSet(1, b, amr_block(lo, h1, n, 1e-5 * b))
    amr.SetRefinementRatio(0, 2)
    vtkAMRUtilities.BlankCells(amr)
    return amr


overlapping = cfd.producer(globals(), make_amr([(-0.5, 0.25), (-0.25, 0.5)]))
ri = RefractiveIndex(Input=overlapping, Model="Passthrough")
data, text = fetch(ri)
T.check("ERROR" in text and "level 1 has boxes that overlap: boxes 0 and 1 share 256 cells" in text
        and data.GetNumberOfPoints() == 0,
        "AMR with two boxes overlapping on level 1 (4 x 8 x 8 cells): refused naming them (one box's "
        "values were dropped)")
Delete(ri)
touching = cfd.producer(globals(), make_amr([(-0.5, 0.0), (0.0, 0.5)]))
ri = RefractiveIndex(Input=touching, Model="Passthrough")
data, text = fetch(ri)
T.check("ERROR" not in text and data.GetNumberOfPoints() == 17 ** 3,
        "AMR with two boxes sharing a face on level 1: resampled (17^3 points at the finest spacing)")
Delete(ri)

# ------------------------------------------------------------------ 6. a mesh that moves
import tempfile


def traced(reader, time=None):
    ri = RefractiveIndex(Input=reader, AutomaticDimension=20)
    im = SchlierenImage(Input=ri, Resolution=[20, 20], Passes=1, Backend="CPU", CutoffScale=100.0,
                        Jitter=0)
    with st.CapturedOutput() as out:
        if time is None:
            im.UpdatePipeline()
            ri.UpdatePipeline()
        else:
            im.UpdatePipeline(time)
            ri.UpdatePipeline(time)
        image = sm.Fetch(im)
        volume = sm.Fetch(ri)
    I = vtk_to_numpy(image.GetPointData().GetArray("intensity")).astype(float) if image.GetNumberOfPoints() else None
    result = (I, volume.GetBounds(), out.text)
    Delete(im)
    Delete(ri)
    return result


folder = tempfile.mkdtemp(prefix="physics_sense_")
steps = [os.path.join(folder, "mesh_%d.vtu" % i) for i in range(2)]
st.moving_mesh(steps[0], 0.0)
st.moving_mesh(steps[1], 0.5)
series = XMLUnstructuredGridReader(FileName=steps)
series.UpdatePipelineInformation()
alone = XMLUnstructuredGridReader(FileName=[steps[1]])
I_alone, b_alone, _ = traced(alone)
ri_series = RefractiveIndex(Input=series, AutomaticDimension=20)
im_series = SchlierenImage(Input=ri_series, Resolution=[20, 20], Passes=1, Backend="CPU", CutoffScale=100.0,
                           Jitter=0)
def intensity_now():
    return vtk_to_numpy(sm.Fetch(im_series).GetPointData().GetArray("intensity")).astype(float)


with st.CapturedOutput() as out:
    im_series.UpdatePipeline(0.0)
    I_first = intensity_now()
    im_series.UpdatePipeline(1.0)
    ri_series.UpdatePipeline(1.0)
    image = sm.Fetch(im_series)
    volume = sm.Fetch(ri_series)
    I_series = vtk_to_numpy(image.GetPointData().GetArray("intensity")).astype(float)
    # back to the first step: RefractiveIndex serves it from its time cache, on its own grid
    im_series.UpdatePipeline(0.0)
    I_again = intensity_now()
    ri_series.UpdatePipeline(0.0)
    b_again = sm.Fetch(ri_series).GetBounds()
    from vtkmodules.vtkCommonDataModel import vtkDataObject
    info_origin = ri_series.GetClientSideObject().GetOutputInformation(0).Get(vtkDataObject.ORIGIN())
    data_origin = ri_series.GetClientSideObject().GetOutputDataObject(0).GetOrigin()
T.close(volume.GetBounds()[0:2], b_alone[0:2], 1e-9,
        "a mesh moved by 0.5 along x at its second step: the sampling box follows it (x from %.4g to %.4g)"
        % volume.GetBounds()[0:2])
T.check("the grid follows them" in out.text, "the moved bounds are said in the log")
if I_alone is not None:
    T.close(I_series, I_alone, 1e-6, "the second step traced in the series against that step alone")
T.close(I_again, I_first, 0.0, "the first step again (from the time cache) against its first trace")
T.close(b_again[0:2], [-1.0, 1.0], 1e-5, "the first step again: its own box (x from %.4g to %.4g)" % b_again[0:2])
T.close(info_origin, data_origin, 1e-12, "the first step again: the grid in the pipeline information "
        "(what SchlierenImage reads) is the kept image's, not the moved step's")
Delete(im_series)
Delete(ri_series)
for f in steps:
    os.remove(f)
os.rmdir(folder)

# ------------------------------------------------------------------ 7. what the messages say
from vtkmodules.vtkCommonDataModel import VTK_QUAD


def box_patches():
    """The six faces of [-1, 1]^3 as quads (an OpenFOAM case's patches without its internal
    mesh), in a multiblock: no cell holds any volume."""
    pts = vtkPoints()
    for z in (-1, 1):
        for y in (-1, 1):
            for x in (-1, 1):
                pts.InsertNextPoint(x, y, z)
    ug = vtkUnstructuredGrid()
    ug.SetPoints(pts)
    for quad in ((0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)):
        ug.InsertNextCell(VTK_QUAD, 4, quad)
    rho = vtkDoubleArray()
    rho.SetName("density")
    for i in range(8):
        rho.InsertNextValue(1.2)
    ug.GetPointData().AddArray(rho)
    mb = vtkMultiBlockDataSet()
    mb.SetBlock(0, ug)
    return mb


patches = cfd.producer(globals(), box_patches())
ri = RefractiveIndex(Input=patches, AutomaticDimension=16)
data, text = fetch(ri)
T.check("ERROR" in text and "enclose no volume" in text and "6 cells: 0 3D, 6 2D" in text
        and "check SamplingBounds" not in text,
        "patches with no internal mesh, SamplingBounds off: the error says the cells enclose no "
        "volume (it said 'check SamplingBounds')")
ri.UseSamplingBounds = 1
ri.SamplingBounds = [5, 6, 5, 6, 5, 6]
data, text = fetch(ri)
T.check("ERROR" in text and "check SamplingBounds" in text,
        "the same with SamplingBounds on and outside the mesh: 'check SamplingBounds'")
Delete(ri)
octree = RefractionOctree(Input=sphere, Tolerance=2.0)
data, text = fetch(octree)
T.check("ERROR" in text and "Tolerance is 2" in text and "air's n - 1 is about 3e-4" in text
        and "units" not in text, "RefractionOctree Tolerance 2: the range and what the value means, "
        "not a word about units")
Delete(octree)

T.finish()
