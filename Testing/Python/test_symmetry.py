# SPDX-License-Identifier: BSD-3-Clause
"""2D results as a laboratory sees them (RefractiveIndex Symmetry Planar and Axisymmetric), against
closed forms, in pvpython; the 2D inputs are built here with VTK (the test carries no data).

1. Planar: a 2D Gaussian n - 1 = A exp(-((x-a)^2 + (y-b)^2)/s^2) on an image one point thick in z,
   extruded over Span L, seen along z. For a weak field the ray hardly moves sideways inside the
   span, so the deflection is L grad(n - 1) / n (first order in the deflection: the sideways
   displacement L^2 |grad n| / 2 = 2.5e-5 m here changes grad n by a relative 2.5e-5 / s = 3e-4)
   (the phase, measured by the tracer against the index where a ray enters, is then ~0: shown
   here, documented as a limit). What remains is the grid's: central differences of the
   Gaussian at h = s / 12 (O(h^2 f'''/6): 0.4 % of the largest gradient) and trilinear
   interpolation of grad n between grid points (O(h^2 f''/8): 0.9 %); asserted 2 % of the
   largest deflection.
   The same field as a one-cell-thick 3D image (2 points in z) gives the same volume.
2. Axisymmetric: n - 1 = A exp(-r^2/s^2) g(x), g(x) = exp(-x^2/w^2), given as an r-x half plane
   (a vtkPolyData of quads in the x-y plane, r along y), revolved about x. Across the axis (beam
   along -z) the projected index is the Abel transform sqrt(pi) A s exp(-y^2/s^2) g(x); the
   phase is 2 pi / lambda times it and the deflection its gradient. Along the axis (beam along
   -x) it is sqrt(pi) w A exp(-r^2/s^2). Errors: the 2D mesh's bilinear interpolation (h2 = s/20:
   (h2/s)^2/4 = 0.06 % of A), the 3D grid's trilinear interpolation (h = s/8: 0.4 %) and its
   central differences (O(h^2): about 1.5 % of the largest gradient); the revolved box ends at
   r = 3 s (the integral beyond it is erfc(3) = 2e-5 of the whole). Asserted: phase 1.5 % of its
   peak across the axis, deflection 3 % of its largest. Along the axis every sample of a ray is
   at the same r, so the transverse bilinear error (up to 2 x (h/s)^2/4 = 0.8 % of A) does not
   average out along the ray: 2 %.
3. Errors: Planar with Span 0; Axisymmetric with the axis normal to the data's plane; a 2D input
   with Symmetry None gives one message that names Symmetry (and not a second one about n).

Run: pvpython test_symmetry.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so
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
T = st.Checker("test_symmetry")
LAMBDA = 632.8e-9


def fetch(proxy):
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy)
    T.check("ERROR" not in out.text, "%s: no error%s" % (proxy.GetXMLName(), "" if "ERROR" not in out.text
                                                          else ": " + out.text.strip()[:600]))
    return data, out.text


def expect_error(make, case, *phrases):
    """Creates (make()) and updates a proxy; checks that RefractiveIndex's error names the phrases,
    that it says one thing (the same message at information and data time) and nothing about n."""
    with st.CapturedOutput() as out:
        proxy = make()
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy)
    text = out.text
    lines = text.splitlines()
    errors = set(lines[i + 1] for i, l in enumerate(lines[:-1])
                 if l.startswith("ERROR: In") and "vtkRefractiveIndex" in l)
    errors = set(e.split("): ", 1)[-1] for e in errors)
    missing = [p for p in phrases if p not in text]
    T.check(not missing and errors, "%s: the error names %s%s" % (case, ", ".join(repr(p) for p in phrases),
                                                                  "" if not missing else " (got: %s)" % text.strip()[:500]))
    T.check(len(errors) == 1 and "n <= 0" not in text,
            "%s: one message from RefractiveIndex (%d distinct), none about n <= 0: %s"
            % (case, len(errors), "; ".join(e[:160] for e in errors)))
    T.check(data is None or data.GetNumberOfPoints() == 0, "%s: empty output" % case)
    Delete(proxy)


def extra(data, name):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    nx, ny, _ = data.GetDimensions()
    a = data.GetPointData().GetArray(name)
    return None if a is None else vtk_to_numpy(a).reshape(ny, nx).astype(float)


# --- 1. Planar ----------------------------------------------------------------------------------
A, S, L = 1e-4, 0.12, 0.5
CA, CB = 0.05, -0.03
H = S / 12
nx, ny = 97, 73
ox, oy = -48 * H, -36 * H
x = ox + H * np.arange(nx)
y = oy + H * np.arange(ny)
Y2, X2 = np.meshgrid(y, x, indexing="ij")
field = A * np.exp(-((X2 - CA) ** 2 + (Y2 - CB) ** 2) / S ** 2)
flat = ct.producer(globals(), ct.make_image((nx, ny, 1), (ox, oy, 0.3), (H, H, 1.0),
                                            {"n_minus_1": field[np.newaxis]}))
planar = RefractiveIndex(Input=flat, Symmetry="Planar", Span=L)
vol, text = fetch(planar)
dims = vol.GetDimensions()
T.check(list(dims) == [nx, ny, 3], "Planar: the image's own grid in its plane and 3 points across: %s" % (dims,))
T.close(vol.GetBounds()[4:6], [0.3 - L / 2, 0.3 + L / 2], 1e-12, "Planar: the span is centred on the data's plane")
T.check("Passthrough" in text, "Planar: Model Automatic says it chose Passthrough on n_minus_1")
n1, g = ct.grid_arrays(vol, "n_minus_1", "grad_n")
T.close(n1, np.repeat(field[np.newaxis], 3, axis=0), 1e-7 * A, "Planar: n - 1 uniform across the span, equal to the 2D field")
T.close(g[..., 2], 0.0, 1e-12, "Planar: no gradient across the span")

film = dict(Resolution=[80, 60], Passes=1, Jitter=0, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0])
knife = SchlierenImage(Input=planar, Cutoff="KnifeEdge", **film)
data, _ = fetch(knife)
X, Y, I, D, F = st.image_arrays(data)
common = np.exp(-((X - CA) ** 2 + (Y - CB) ** 2) / S ** 2)
exact = np.stack([-2 * (X - CA) / S ** 2, -2 * (Y - CB) / S ** 2], axis=-1) * (A * common)[..., None] * L
exact /= (1.0 + A * common)[..., None]
emax = np.abs(exact).max()
err = np.abs(D - exact).max() / emax
T.check(err <= 0.02, "Planar: deflection == Span grad(n-1)/n in the plane: max error %.3g %% of max %.3g rad (tolerance 2 %%)"
        % (100 * err, emax))
fringes = SchlierenImage(Input=planar, Cutoff="Interferometry", Wavelength=632.8, **film)
data, _ = fetch(fringes)
phase = extra(data, "phase")
X, Y = st.image_arrays(data)[:2]
pexact = 2 * math.pi / LAMBDA * L * A * np.exp(-((X - CA) ** 2 + (Y - CB) ** 2) / S ** 2)
# The tracer's phase is the optical path against the index where each ray enters: across a
# uniform span that is the field itself, so a Planar volume's phase is about 0 (a known limit,
# documented in docs/CFD.md: the fringe order of a 2D flow is 2 pi/lambda Span (n - 1 - n_ref)).
T.check(phase is not None and np.abs(phase).max() < 1e-3 * pexact.max(),
        "Planar: the phase, measured against the entry index, is ~0 (max %.3g rad; Span (n - 1) would give %.1f)"
        % (np.abs(phase).max(), pexact.max()))
# One cell thick: the same field on 2 points in z (a 3D result of one cell) makes the same volume.
thick = ct.producer(globals(), ct.make_image((nx, ny, 2), (ox, oy, 0.2), (H, H, 0.2),
                                             {"n_minus_1": np.repeat(field[np.newaxis], 2, axis=0)}))
planar2 = RefractiveIndex(Input=thick, Symmetry="Planar", Span=L)
vol2, _ = fetch(planar2)
T.check(list(vol2.GetDimensions()) == [nx, ny, 3], "Planar, one cell thick: the same grid")
T.close(ct.grid_arrays(vol2, "n_minus_1")[0], n1, 1e-12, "Planar, one cell thick: the same n - 1 (its mid-plane)")
# The same 2D field on triangles in the plane z = 0.3 (a vtkPolyData, as a 2D solver writes it):
# resampled in the plane (AutomaticDimension 97 along x gives the image's spacing, so the grid's
# points sit on the mesh's nodes, moved by the 1e-6 pull-in of the box): n - 1 equals the nodes'
# values to 1e-4 of A (a grid off the nodes would see the triangles' linear interpolation, up to
# (h/s)^2/4 = 0.17 % of A).
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

tplane = vtkPlaneSource()
tplane.SetOrigin(ox, oy, 0.3)
tplane.SetPoint1(ox + (nx - 1) * H, oy, 0.3)
tplane.SetPoint2(ox, oy + (ny - 1) * H, 0.3)
tplane.SetResolution(nx - 1, ny - 1)
tri = vtkTriangleFilter()
tri.SetInputConnection(tplane.GetOutputPort())
tri.Update()
tris = tri.GetOutput()
tp = vtk_to_numpy(tris.GetPoints().GetData())
tv = numpy_to_vtk(A * np.exp(-((tp[:, 0] - CA) ** 2 + (tp[:, 1] - CB) ** 2) / S ** 2), deep=1)
tv.SetName("n_minus_1")
tris.GetPointData().AddArray(tv)
planar3 = RefractiveIndex(Input=ct.producer(globals(), tris), Symmetry="Planar", Span=L, AutomaticDimension=nx)
vol3, _ = fetch(planar3)
T.check(list(vol3.GetDimensions()) == [nx, ny, 3], "Planar on triangles: %s points (%d along x)" % (vol3.GetDimensions(), nx))
n3 = ct.grid_arrays(vol3, "n_minus_1")[0]
T.close(n3 / A, np.repeat(field[np.newaxis], 3, axis=0) / A, 1e-4,
        "Planar on triangles: n - 1 = the 2D field at the nodes, uniform across (of A)")
for p in (knife, fringes, planar2, planar3):
    Delete(p)

# --- 2. Axisymmetric ----------------------------------------------------------------------------
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

A, S, W = 2e-6, 0.2, 0.4  # A small enough that the fringes are resolved on the film
R = 3 * S
plane = vtkPlaneSource()
plane.SetOrigin(-1.0, 0.0, 0.0)
plane.SetPoint1(1.0, 0.0, 0.0)
plane.SetPoint2(-1.0, R, 0.0)
plane.SetXResolution(200)
plane.SetYResolution(60)  # h2 = 0.01 = s / 20
plane.Update()
half = plane.GetOutput()
pts = vtk_to_numpy(half.GetPoints().GetData())
values = A * np.exp(-pts[:, 1] ** 2 / S ** 2) * np.exp(-pts[:, 0] ** 2 / W ** 2)
arr = numpy_to_vtk(values.astype(np.float64), deep=1)
arr.SetName("n_minus_1")
half.GetPointData().AddArray(arr)
half.GetPointData().RemoveArray("Normals")
half.GetPointData().RemoveArray("TextureCoordinates")
source = ct.producer(globals(), half)
axi = RefractiveIndex(Input=source, Symmetry="Axisymmetric", SymmetryAxis="X", SamplingDimensions=[81, 49, 49])
vol, _ = fetch(axi)
b = vol.GetBounds()
T.close([b[2], b[3], b[4], b[5]], [-R, R, -R, R], 1e-6, "Axisymmetric: revolved box y, z in [-R, R] (R = %.2f)" % R)
T.close([b[0], b[1]], [-1, 1], 1e-5, "Axisymmetric: the axial extent of the data")
n1 = ct.grid_arrays(vol, "n_minus_1")[0]
o, h = np.array(vol.GetOrigin()), np.array(vol.GetSpacing())
zz, yy, xx = np.meshgrid(o[2] + h[2] * np.arange(49), o[1] + h[1] * np.arange(49), o[0] + h[0] * np.arange(81), indexing="ij")
rr = np.sqrt(yy ** 2 + zz ** 2)
inside = rr <= R * (1 - 1e-9)
n3 = A * np.exp(-rr ** 2 / S ** 2) * np.exp(-xx ** 2 / W ** 2)
T.close(n1[inside] / A, n3[inside] / A, 2e-3, "Axisymmetric: n - 1 at each grid point = the 2D field at (x, r) (of A)")

film = dict(Resolution=[96, 40], Passes=1, Jitter=0)
across = SchlierenImage(Input=axi, Cutoff="Interferometry", Wavelength=632.8, ViewDirection=[0, 0, -1],
                        ViewUp=[0, 1, 0], **film)
data, _ = fetch(across)
X, Y, I, D, F = st.image_arrays(data)
phase = extra(data, "phase")
P = math.sqrt(math.pi) * A * S * np.exp(-Y ** 2 / S ** 2) * np.exp(-X ** 2 / W ** 2)
pexact = 2 * math.pi / LAMBDA * P
perr = np.abs(phase - pexact).max() / pexact.max()
T.check(perr <= 0.015, "Axisymmetric across the axis: phase == 2 pi/lambda sqrt(pi) A s exp(-y^2/s^2) g(x): "
        "max error %.3g %% of its %.2f rad peak (tolerance 1.5 %%)" % (100 * perr, pexact.max()))
eps = np.stack([-2 * X / W ** 2 * P, -2 * Y / S ** 2 * P], axis=-1)
emax = np.abs(eps).max()
derr = np.abs(D - eps).max() / emax
T.check(derr <= 0.03, "Axisymmetric across the axis: deflection == grad of the Abel transform: max error %.3g %% "
        "of max %.3g rad (tolerance 3 %%)" % (100 * derr, emax))
along = SchlierenImage(Input=axi, Cutoff="Interferometry", Wavelength=632.8, ViewDirection=[-1, 0, 0],
                       ViewUp=[0, 1, 0], Resolution=[48, 48], Passes=1, Jitter=0)
data, _ = fetch(along)
X, Y = st.image_arrays(data)[:2]
phase = extra(data, "phase")
r2 = X ** 2 + Y ** 2
# Along the axis the beam crosses x in [-1, 1] (the data's extent): sqrt(pi) w erf(1/w) A exp(-r^2/s^2).
aexact = 2 * math.pi / LAMBDA * math.sqrt(math.pi) * W * math.erf(1.0 / W) * A * np.exp(-r2 / S ** 2)
inner = r2 <= (0.9 * R) ** 2
aerr = np.abs(phase - aexact)[inner].max() / aexact.max()
T.check(aerr <= 0.02, "Axisymmetric along the axis: phase == 2 pi/lambda sqrt(pi) w erf(1/w) A exp(-r^2/s^2): "
        "max error %.3g %% of its %.2f rad peak (r < 0.9 R; tolerance 2 %%)" % (100 * aerr, aexact.max()))
for p in (across, along):
    Delete(p)

# --- 3. Errors ----------------------------------------------------------------------------------
expect_error(lambda: RefractiveIndex(Input=flat, Symmetry="Planar", Span=0.0), "Planar with Span 0", "Span")
expect_error(lambda: RefractiveIndex(Input=source, Symmetry="Axisymmetric", SymmetryAxis="Z"),
             "axis normal to the plane", "SymmetryAxis z")
expect_error(lambda: RefractiveIndex(Input=flat), "a 2D image with Symmetry None", "2D", "Symmetry", "Planar")
expect_error(lambda: RefractiveIndex(Input=source), "a 2D polydata with Symmetry None", "Symmetry", "Planar")

# The chain on a 2D image: RefractiveIndex names Symmetry; SchlierenImage says only that its input is
# empty because of the error upstream (not a second, misleading reason about the grid or n).
with st.CapturedOutput() as out:
    chain_index = RefractiveIndex(Input=flat)
    chain = SchlierenImage(Input=chain_index, Resolution=[16, 16], Passes=1)
    chain.UpdatePipeline()
text = out.text
T.check("Symmetry" in text and "n <= 0" not in text and "tracing needs" not in text
        and ("volume is empty" in text or "vtkSchlierenImage" not in text),
        "a 2D image into RefractiveIndex into SchlierenImage: the cause once (Symmetry), no misleading "
        "second message")

T.finish()
