# SPDX-License-Identifier: BSD-3-Clause
"""Inputs a hostile user gives that used to make silent wrong pictures: each is now a clear error
naming what was expected, with an empty output.

- RefractiveScene BodyRadius < 0 (it was clamped to 1e-12: no body, no message): an error naming
  BodyRadius and the value; a NaN BodyCenter (the body dropped) an error naming BodyCenter.
- A full 3D volume (an image 16 x 16 x 16) given Symmetry Planar or Axisymmetric (it was cut to one
  plane and extruded or revolved): an error saying a 2D plane normal to x, y or z was expected
  (for Axisymmetric an r-x half plane) and that this is a 3D volume.
- A tilted 2D plane (a quad mesh in a plane at 30 degrees to z) under Planar (it blamed
  SamplingBounds): an error saying the plane must be axis-aligned.
- Two overlapping closed spheres on RefractiveIndex's Body (the overlap was left transparent:
  an even-odd inside rule over both): every point inside either is solid, none outside.
- A body over the whole beam: the warning says it blocked N of M rays (it spoke of photons off
  the film, with advice about FilmDistance).
- Axisymmetric data crossing the axis (different values on its two sides): a warning naming the
  side revolved (it lost the other without a word).
Controls: BodyRadius 0.25 makes solid points; a 2D image (16 x 16 x 1) under Planar and a
one-cell-thick image (16 x 16 x 2) make a volume with no error.

Run: pvpython test_hostile.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_hostile")


def fetch(proxy):
    with st.CapturedOutput() as out:
        data = sm.Fetch(proxy)
    points = data.GetNumberOfPoints() if data is not None else 0
    return data, points, out.text


# 1. BodyRadius
for radius in (-0.1, 0.0):
    scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[16] * 3, Body="Sphere",
                            BodyRadius=radius)
    _, points, text = fetch(scene)
    T.check(points == 0 and "BodyRadius is %g" % radius in text,
            "BodyRadius %g: an error naming BodyRadius and the value, no output (%d points; %s)"
            % (radius, points, text.strip()[-300:]))
    Delete(scene)
# a NaN BodyCenter (issue 48: the body was dropped without a word): the engine's check, the one the
# C interface makes
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[16] * 3, Body="Sphere",
                        BodyCenter=[float("nan"), 0, 0])
_, points, text = fetch(scene)
T.check(points == 0 and "BodyCenter has a non-finite component" in text,
        "BodyCenter NaN: an error naming BodyCenter, no output (%d points; %s)"
        % (points, text.strip()[-200:]))
Delete(scene)
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[16] * 3, Body="Sphere", BodyRadius=0.25)
data, points, text = fetch(scene)
solid = data.GetPointData().GetArray("solid") if points else None
T.check(solid is not None and solid.GetRange()[1] == 1 and "ERROR" not in text,
        "control: BodyRadius 0.25 makes solid points")

# 2. A 3D volume under Symmetry Planar and Axisymmetric
volume = RefractiveScene(Scene="GaussianSphere", Dimensions=[16] * 3)
for sym, expected in (("Planar", "expects a 2D plane normal to x, y or z"),
                      ("Axisymmetric", "(an r-x half plane holding SymmetryAxis)")):
    index = RefractiveIndex(Input=volume, Symmetry=sym, SymmetryAxis="X", Model="Passthrough")
    _, points, text = fetch(index)
    T.check(points == 0 and expected in text and "a 3D volume" in text,
            "3D volume under Symmetry %s: refused naming what was expected (%d points; %s)"
            % (sym, points, text.strip()[-400:]))
    Delete(index)

# controls: a 2D image and a one-cell-thick one
for dims in ([16, 16, 1], [16, 16, 2]):
    flat = RefractiveScene(Scene="GaussianSphere", Dimensions=dims,
                           Bounds=[-1, 1, -1, 1, 0, 0.05 if dims[2] > 1 else 0])
    index = RefractiveIndex(Input=flat, Symmetry="Planar", Span=1.0, Model="Passthrough")
    _, points, text = fetch(index)
    T.check(points > 0 and "ERROR" not in text,
            "control: a %s image under Planar makes a volume (%d points; %s)"
            % ("x".join(map(str, dims)), points, text.strip()[-300:]))
    Delete(index)
    Delete(flat)

# 3. A tilted plane under Planar: a quad mesh in the x-y plane turned 30 degrees about x
plane = Plane(XResolution=16, YResolution=16)
calc = Calculator(Input=plane, ResultArrayName="n_minus_1", Function="1e-4*exp(-(coordsX^2+coordsY^2)/0.04)")
tilted = Transform(Input=calc)
tilted.Transform.Rotate = [30, 0, 0]
index = RefractiveIndex(Input=tilted, Symmetry="Planar", Span=1.0, Model="Passthrough")
_, points, text = fetch(index)
T.check(points == 0 and "not axis-aligned" in text and "SamplingBounds" not in text,
        "tilted plane under Planar: says the plane must be axis-aligned, does not blame "
        "SamplingBounds (%d points; %s)" % (points, text.strip()[-400:]))
# the same plane untilted: a volume
index2 = RefractiveIndex(Input=calc, Symmetry="Planar", Span=1.0, Model="Passthrough")
_, points, text = fetch(index2)
T.check(points > 0 and "ERROR" not in text,
        "control: the plane untilted makes a volume (%d points; %s)" % (points, text.strip()[-300:]))

# 4. Two overlapping closed spheres on Body: their union is solid (the overlap too), by the grid
# points' distances to the two centres (the tessellation lies inside by up to 5e-4 R)
import numpy as np  # noqa: E402
from vtkmodules.numpy_interface import dataset_adapter as dsa  # noqa: E402

air = RefractiveScene(Scene="Uniform", Amplitude=2.7e-4, Dimensions=[41, 41, 41])
a_ = Sphere(Radius=0.4, Center=[-0.15, 0, 0], ThetaResolution=48, PhiResolution=48)
b_ = Sphere(Radius=0.4, Center=[0.15, 0, 0], ThetaResolution=48, PhiResolution=48)
both = AppendGeometry(Input=[a_, b_])
index = RefractiveIndex(Input=air, Body=both, Model="Passthrough")
data, points, text = fetch(index)
solid = dsa.WrapDataObject(data).PointData["solid"] if points else None
if solid is None:
    T.check(False, "two overlapping shells: no solid array (%s)" % text.strip()[-300:])
else:
    pts = np.array([data.GetPoint(i) for i in range(data.GetNumberOfPoints())])
    ra = np.linalg.norm(pts - [-0.15, 0, 0], axis=1)
    rb = np.linalg.norm(pts - [0.15, 0, 0], axis=1)
    overlap = (ra < 0.39) & (rb < 0.39)
    union = (ra < 0.39) | (rb < 0.39)
    outside = (ra > 0.401) & (rb > 0.401)
    s_ = np.asarray(solid) > 0
    T.check(overlap.sum() > 50 and s_[overlap].all() and s_[union].all() and not s_[outside].any(),
            "two overlapping shells: the overlap is solid (%d of %d overlap points), the union "
            "too (%d of %d), nothing outside (%d)" % (s_[overlap].sum(), overlap.sum(),
                                                      s_[union].sum(), union.sum(), s_[outside].sum()))

# 5. A body that blocks the whole beam: the warning says the body blocked the rays (all of them),
# not that photons landed off the film, and gives no advice about FilmDistance or CutoffScale
wall = RefractiveScene(Scene="GaussianSphere", Dimensions=[24] * 3, Body="Sphere", BodyRadius=2.0)
image = SchlierenImage(Input=wall, Resolution=[16, 16], Passes=1, Backend="CPU")
data, points, text = fetch(image)
F = st.image_arrays(data)[4] if points else {}
warn = F.get("warnings", "")
T.check(points > 0 and "A solid body blocked 256 of 256 rays" in warn and "off the film" not in warn
        and "FilmDistance" not in warn,
        "a body over the whole beam: 'blocked 256 of 256 rays', no word of the film (%r)" % warn[:300])

# 6. Axisymmetric data crossing the axis, with different values on its two sides: a warning that
# says which side is revolved; a half plane (r >= 0) gives none
def half_plane(y0):
    plane = Plane(Origin=[-1, y0, 0], Point1=[1, y0, 0], Point2=[-1, 1, 0], XResolution=16,
                  YResolution=16)
    return Calculator(Input=plane, ResultArrayName="n_minus_1",
                      Function="1e-4*exp(-(coordsX^2+coordsY^2)/0.1)*(1+(coordsY<0))")


for y0, crosses in ((-0.5, True), (0.0, False)):
    src = half_plane(y0)
    # the grid, and so the warning, is made when the proxy's information is first updated
    with st.CapturedOutput() as made:
        index = RefractiveIndex(Input=src, Symmetry="Axisymmetric", SymmetryAxis="X",
                                SamplingDimensions=[16, 16, 16], Model="Passthrough")
    _, points, text = fetch(index)
    text = made.text + text
    said = "crosses the axis" in text and "only the side y > 0" in text
    T.check(points > 0 and said == crosses,
            "axisymmetric data from y = %g: %s (%d points; %s)"
            % (y0, "a warning naming the side revolved" if crosses else "no axis warning", points,
               text.strip()[-300:]))
    Delete(index)
sys.exit(T.finish())
