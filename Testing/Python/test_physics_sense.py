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

T.finish()
