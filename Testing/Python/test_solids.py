# SPDX-License-Identifier: BSD-3-Clause
"""Solid bodies through the pipeline, with numbers:

  - RefractiveScene Body Sphere (R = 0.5) in uniform air, SchlierenImage knife edge: a dark disc of
    radius R (equivalent radius of the dark area within a pixel; pixel = spacing = 1/32), 0.5
    elsewhere; the image's `blocked` array is 1 inside and 0 outside, `blocked_rays` counts the
    rays through the disc and `failed_rays` stays 0; CPU and OpenCL stop the same rays.
  - RefractiveIndex, where the body comes from (and it keeps a body its input already has):
      * the holes of the grid (an image with vtkValidPointMask 0 in a ball in the middle, and in a
        slab on the z min face): the enclosed ball is solid, the slab on the face is not, unless
        BodyWallFaces marks that face;
      * SolidArray: a point array, non-zero = solid;
      * the Body input: a closed sphere surface (vtkSphereSource, R = 0.4): the points inside it
        within a voxel of the sphere's volume (4/3 pi R^3 / h^3 +- its surface's points), and a
        dark disc of radius R in the image; an open surface (a plane) is an error that says so.
  - The blunt fin (../shared/data; skipped where absent), resampled with BodyWallFaces 0 1 1 0 1 1:
    every point the resampling finds outside every cell of the fin's box is inside the fin's hole
    (x >= 0, y <= 0.5: the grid's fin surface, its j = 0 face), and the image's dark region is the
    projection of the solid points along the beam, to a voxel:
      * side view (beam along +y): the silhouette's leading edge on every film row at the fin's
        nose x from the grid (the smallest x of the j = 0 face), within one voxel;
      * top view (beam along -z): on every film column the dark band's width is the fin's
        half-thickness from the grid's j = 0 face at that x, within a voxel;
    with the default BodyWallFaces (all open) the fin, which touches the box, is not a body.

Run: pvpython test_solids.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

import cfd_testing as ct
import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_solids")


def fetch(proxy, expect_error=None):
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy)
    if expect_error is None:
        T.check("ERROR" not in out.text, "%s: no error%s" % (
            proxy.GetXMLName(), "" if "ERROR" not in out.text else ": " + out.text.strip()[:400]))
    return data, out.text


def blocked(data):
    nx, ny, _ = data.GetDimensions()
    return vtk_to_numpy(data.GetPointData().GetArray("blocked")).reshape(ny, nx).astype(float)


def disc_checks(img, R, label, centre=(0.0, 0.0)):
    """The dark disc of radius R under the knife edge: equivalent radius within a pixel, 0 inside
    and 0.5 outside (more than a pixel from the rim). Returns the field data."""
    X, Y, I, D, F = st.image_arrays(img)
    px = X[0, 1] - X[0, 0]
    rho = np.hypot(X - centre[0], Y - centre[1])
    radius = math.sqrt((1 - I / 0.5).sum() * px * px / math.pi)
    T.close(radius, R, px, "%s: the dark disc's radius is R = %g (equivalent radius %.4f, pixel %.4f)"
            % (label, R, radius, px))
    T.check(I[rho < R - px].max() == 0.0, "%s: no light inside the disc" % label)
    T.close(I[rho > R + px], 0.5, 1e-6, "%s: the knife edge's 0.5 outside the disc" % label)
    B = blocked(img)
    T.check(B[rho < R - px].min() == 1.0 and B[rho > R + px].max() == 0.0,
            "%s: the blocked fraction is 1 inside the disc, 0 outside" % label)
    passes = F["passes"]
    T.close(F["blocked_rays"] / passes, math.pi * R * R / px ** 2, 2 * math.pi * R / px,
            "%s: blocked rays per pass = pixels in the disc (%.0f), to its rim" % (label, F["blocked_rays"] / passes))
    T.check(F["failed_rays"] == 0, "%s: no ray failed (blocked rays are not failures)" % label)
    return F


# ================================================================ RefractiveScene with a body
scene = RefractiveScene(Scene="Uniform", Amplitude=2.7e-4, Dimensions=[65, 65, 65], Body="Sphere",
                        BodyRadius=0.5)
grid, _ = fetch(scene)
(solid,) = ct.grid_arrays(grid, "solid")
h = 2.0 / 64
x = -1 + h * np.arange(65)
Z, Yg, Xg = np.meshgrid(x, x, x, indexing="ij")
T.check(np.array_equal(solid > 0, Xg ** 2 + Yg ** 2 + Z ** 2 <= 0.25),
        "RefractiveScene: `solid` marks the grid points within the sphere (%d points)" % (solid > 0).sum())
through = RefractiveIndex(Input=scene, Model="Passthrough")
through.InputArray = ["POINTS", "n_minus_1"]
kept, _ = fetch(through)
T.check(ct.field_value(kept, "solid_points") == (solid > 0).sum(),
        "RefractiveIndex keeps the body its input carries (%d points)" % ct.field_value(kept, "solid_points"))
fields = {}
for backend in ("CPU", "OpenCL"):
    img = SchlierenImage(Input=scene, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], Resolution=[64, 64],
                         Passes=4, CutoffScale=1000.0, Cutoff="KnifeEdge", Backend=backend)
    data, _ = fetch(img)
    fields[backend] = (disc_checks(data, 0.5, "opaque sphere (%s)" % backend), blocked(data))
T.check(fields["CPU"][0]["blocked_rays"] == fields["OpenCL"][0]["blocked_rays"]
        and np.array_equal(fields["CPU"][1], fields["OpenCL"][1]),
        "CPU and OpenCL stop the same rays (%.0f)" % fields["CPU"][0]["blocked_rays"])

# ================================================================ RefractiveIndex: holes of the grid
n = 33
hh = 2.0 / (n - 1)
x = -1 + hh * np.arange(n)
Z, Yg, Xg = np.meshgrid(x, x, x, indexing="ij")
ball = Xg ** 2 + Yg ** 2 + Z ** 2 <= 0.3 ** 2
slab = (Z <= -0.8) & (abs(Xg) <= 0.3) & (abs(Yg) <= 0.3)  # on the z min face
valid = (~(ball | slab)).astype(np.float32)
image = ct.make_image((n, n, n), (-1, -1, -1), (hh, hh, hh),
                      {"n_minus_1": np.full(ball.shape, 2.7e-4), "vtkValidPointMask": valid,
                       "mask": (abs(Xg - 0.6) <= 0.15) & (abs(Yg) <= 0.15) & (abs(Z) <= 0.15)})
src = ct.producer(globals(), image)
index = RefractiveIndex(Input=src, Model="Passthrough")
index.InputArray = ["POINTS", "n_minus_1"]
out, _ = fetch(index)
(s,) = ct.grid_arrays(out, "solid")
T.check(np.array_equal(s > 0, ball), "BodyFromGrid: the enclosed hole is solid (%d points), the hole on the "
        "z min face is not (outside the flow domain)" % (s > 0).sum())
T.check(ct.field_value(out, "solid_points") == ball.sum(), "field data solid_points = %d" % ball.sum())
index.BodyWallFaces = [0, 0, 0, 0, 1, 0]
out, _ = fetch(index)
(s,) = ct.grid_arrays(out, "solid")
T.check(np.array_equal(s > 0, ball | slab), "BodyWallFaces z min: the hole on that face is a body too")
index.BodyWallFaces = [0] * 6
index.BodyFromGrid = 0
index.SolidArray = "mask"
out, _ = fetch(index)
(s,) = ct.grid_arrays(out, "solid")
T.check(np.array_equal(s > 0, image_mask := vtk_to_numpy(image.GetPointData().GetArray("mask")).reshape(n, n, n) > 0),
        "SolidArray: the mask's non-zero points are solid (%d), the grid's holes are not (BodyFromGrid off)"
        % image_mask.sum())
index.SolidArray = "no_such_array"
_, text = fetch(index, expect_error=True)
T.check("SolidArray 'no_such_array'" in text and "n_minus_1" in text,
        "a SolidArray that is not there is an error naming it and the arrays present: %s" % text.strip()[:200])
index.SolidArray = "None"
out, _ = fetch(index)
T.check(out.GetPointData().GetArray("solid") is None and ct.field_value(out, "solid_points") == 0,
        "no body: no `solid` array (SchlierenImage then costs nothing more)")

# ================================================================ the Body input: a closed surface
air = RefractiveScene(Scene="Uniform", Amplitude=2.7e-4, Dimensions=[65, 65, 65])
sphere = Sphere(Radius=0.4, ThetaResolution=64, PhiResolution=64)
withbody = RefractiveIndex(Input=air, Body=sphere, Model="Passthrough")
withbody.InputArray = ["POINTS", "n_minus_1"]
out, _ = fetch(withbody)
(s,) = ct.grid_arrays(out, "solid")
h = 2.0 / 64
x = -1 + h * np.arange(65)
Z, Yg, Xg = np.meshgrid(x, x, x, indexing="ij")
r = np.sqrt(Xg ** 2 + Yg ** 2 + Z ** 2)
# the tessellated sphere lies inside the true one by up to R (1 - cos(pi/64)) = 5e-4 R
T.check((s[r < 0.4 - 0.02] > 0).all() and not (s[r > 0.4 + 0.001] > 0).any(),
        "Body input: the grid points inside the closed sphere are solid, none outside (%d points; "
        "4/3 pi R^3 / h^3 = %.0f)" % ((s > 0).sum(), 4 / 3 * math.pi * 0.4 ** 3 / h ** 3))
T.close((s > 0).sum(), 4 / 3 * math.pi * 0.4 ** 3 / h ** 3, 4 * math.pi * 0.4 ** 2 / h ** 2,
        "Body input: the solid points fill the sphere's volume, to its surface's points")
img = SchlierenImage(Input=withbody, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], Resolution=[64, 64],
                     Passes=4, CutoffScale=1000.0, Backend="OpenCL")
data, _ = fetch(img)
disc_checks(data, 0.4, "Body surface sphere")
plane = Plane(Origin=[-0.5, -0.5, 0], Point1=[0.5, -0.5, 0], Point2=[-0.5, 0.5, 0])
openbody = RefractiveIndex(Input=air, Body=plane, Model="Passthrough")
openbody.InputArray = ["POINTS", "n_minus_1"]
_, text = fetch(openbody, expect_error=True)
T.check("not a closed surface" in text, "an open Body surface is an error that says so: %s" % text.strip()[:200])

# ================================================================ the blunt fin's silhouette
folder = ct.data_dir()
xyz, q = os.path.join(folder, "bluntfinxyz.bin"), os.path.join(folder, "bluntfinq.bin")
if not (os.path.exists(xyz) and os.path.exists(q)):
    print("SKIP the blunt fin part: no shared CFD data in %s (set SCHLIEREN_DATA)" % os.path.abspath(folder))
else:
    reader = PLOT3DReader(FileName=xyz, QFileName=[q])
    fin = RefractiveIndex(Input=reader, Model="GladstoneDale", Gas="Air", DensityReference=1.2,
                          UseSamplingBounds=1, SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7],
                          AutomaticDimension=128, BodyWallFaces=[0, 1, 1, 0, 1, 1])
    fin.InputArray = ["POINTS", "Density"]
    g, _ = fetch(fin)
    dims = g.GetDimensions()
    o, hg = np.array(g.GetOrigin()), np.array(g.GetSpacing())
    s, mask = ct.grid_arrays(g, "solid", "vtkValidPointMask")
    solid = s > 0
    gx = o[0] + hg[0] * np.arange(dims[0])
    gy = o[1] + hg[1] * np.arange(dims[1])
    gz = o[2] + hg[2] * np.arange(dims[2])
    # the fin's surface: the curvilinear grid's j = 0 face
    raw = sm.Fetch(reader).GetBlock(0)
    rp = vtk_to_numpy(raw.GetPoints().GetData()).reshape(32, 32, 40, 3)  # k, j, i
    wall = rp[:, 0, :, :].reshape(-1, 3)
    nose = wall[:, 0].min()
    T.check(np.array_equal(solid, mask == 0),
            "blunt fin: every point of the box outside every cell is in the fin (%d solid points)" % solid.sum())
    Zs, Ys, Xs = np.meshgrid(gz, gy, gx, indexing="ij")
    T.check(Xs[solid].min() >= nose - hg[0] and Ys[solid].max() <= wall[:, 1].max() + hg[1],
            "blunt fin: the solid points lie within the grid's fin surface (x >= %.3f, y <= %.3f), to a voxel"
            % (nose, wall[:, 1].max()))

    def fin_image(**view):
        img = SchlierenImage(Input=fin, Passes=2, Cutoff="KnifeEdge", Backend="OpenCL", **view)
        data, _ = fetch(img)
        X, Y, I, D, F = st.image_arrays(data)
        return X, Y, I, blocked(data), F

    # side view: film x = world x, film y = world z
    X, Y, I, B, F = fin_image(ViewDirection=[0, 1, 0], ViewUp=[0, 0, 1], Resolution=[400, 228])
    dark = B > 0.5
    proj = solid.any(axis=1)  # (z, x): some solid point along the beam
    # the projection at each pixel's nearest grid point
    ix = np.clip(np.rint((X - o[0]) / hg[0]).astype(int), 0, dims[0] - 1)
    iz = np.clip(np.rint((Y - o[2]) / hg[2]).astype(int), 0, dims[2] - 1)
    mismatch = (dark != proj[iz, ix]).mean()
    T.check(mismatch < 0.01, "blunt fin, side: the dark region is the projection of the solid points "
            "(%.2f %% of the pixels differ)" % (100 * mismatch))
    edges = [X[j][dark[j]].min() for j in range(dark.shape[0]) if dark[j].any()]
    T.check(len(edges) == dark.shape[0] and max(abs(e - nose) for e in edges) <= hg[0],
            "blunt fin, side: on every film row the silhouette starts at the fin's nose x = %.3f from the "
            "grid (leading edge at %.3f .. %.3f, voxel %.3f)" % (nose, min(edges), max(edges), hg[0]))
    # the camera images the box's centre plane y = 2.5, the fin lies at y <= 0.5: light passing
    # beside it and deflected by the flow there lands a little off its straight path, and a few
    # pixels of the shadow's rim receive some
    full = B == 1.0
    lit = (I[full] > 0).mean()
    T.check(lit < 1e-3 and F["blocked_rays"] > 0 and F["failed_rays"] == 0,
            "blunt fin, side: black where the fin is (%.0f rays stopped, none failed; %d of %d fully "
            "shadowed pixels receive deflected light)" % (F["blocked_rays"], (I[full] > 0).sum(), full.sum()))
    T.check(np.isfinite(I).all() and I[~dark].std() > 0.01, "blunt fin, side: the flow ahead of the fin shows")

    # top view: film x = world x, film y = world y
    X, Y, I, B, F = fin_image(ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], Resolution=[400, 200])
    dark = B > 0.5
    px = X[0, 1] - X[0, 0]
    # the fin's half-thickness along x: the largest y of the j = 0 face's points at each i (the
    # face's grid lines run along the fin), interpolated
    ws = rp[:, 0, :, :]
    fx, fy = ws[..., 0].mean(axis=0), ws[..., 1].max(axis=0)
    order = np.argsort(fx)
    half = lambda xv: np.interp(xv, fx[order], fy[order])  # noqa: E731
    worst = 0.0
    columns = 0
    for i in range(X.shape[1]):
        xc = X[0, i]
        if xc < nose or xc > 7.5 - hg[0]:
            continue
        # the voxelised fin may sit up to a voxel off along x too (steep at the round nose)
        around = half(xc + hg[0] * np.linspace(-1, 1, 9))
        width = dark[:, i].sum() * px
        off = max(0.0, around.min() - width, width - around.max())
        worst = max(worst, off)
        columns += 1
    T.check(columns > 250 and worst <= hg[1] + px,
            "blunt fin, top: on each of %d columns the dark band's width is the fin's half-thickness from "
            "the grid (within a voxel along x), to a voxel and a pixel (largest difference %.3f, voxel %.3f, "
            "pixel %.3f)" % (columns, worst, hg[1], px))
    open_faces = RefractiveIndex(Input=reader, Model="GladstoneDale", Gas="Air", DensityReference=1.2,
                                 UseSamplingBounds=1, SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7],
                                 AutomaticDimension=128)
    open_faces.InputArray = ["POINTS", "Density"]
    g2, _ = fetch(open_faces)
    T.check(ct.field_value(g2, "solid_points") == 0,
            "blunt fin with every face open (the default): the fin touches the box, so it is not a body")

T.finish()
