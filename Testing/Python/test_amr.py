# SPDX-License-Identifier: BSD-3-Clause
"""RefractiveIndex on overlapping AMR input (vtkOverlappingAMR): every grid point from the finest
level that covers it, the automatic grid at the finest level's spacing, capped by memory.

Run: pvpython test_amr.py --plugin <Schlieren.so>

The case, made here: n - 1 = A exp(-r^2/s^2) (A = 1e-4, s = 0.25) on [-1, 1]^3, level 0 of 32
cells (h0 = 1/16), level 1 a patch [-0.5, 0.5]^3 refined by 2 (h1 = 1/32), the analytic field on
both levels; against the same field on a uniform grid at h1 (65^3 points).

Known answers:
- The automatic grid is the finest level's: spacing h1, 65^3 points (field data amr_finest_spacing,
  sampling_spacing).
- Inside the patch the grid points are the fine level's points: n - 1 equals the uniform fine
  grid's to float rounding. Outside it a grid point lies in a coarse cell and takes its trilinear
  interpolant, whose error is at most (h0^2 / 8) (|f_xx| + |f_yy| + |f_zz|), the second
  derivatives' largest values outside the patch (each axis's linear interpolation errs by at most
  h^2/8 |f''|, and the trilinear interpolant is three of them in turn).
- The deflection: the filter's grad n is a central difference over 2 h1 of n - 1, so an error e
  of n - 1 changes it by at most max|e| / h1; a ray along z crosses at most L = 1 of coarse cells
  (|z| > 0.5), so each deflection component differs from the uniform grid's by at most
  L max|e| / h1 (plus the tracer's float rounding, 1e-9 here).
- A field that differs on purpose between the levels (level 1 = level 0 + 1e-5): every grid point
  in the patch carries the offset, none outside it (the coarse level under the patch unused).
- Cell data (the same field at the cell centres): sampled as cells, trilinear between centres and
  constant over a box's outer half cell: within (h^2/8) sum|f_aa| inside each level plus
  (h1/2) |grad f| at the patch's faces (the half cell where no fine centre lies beyond).
- SCHLIEREN_MEMORY_LIMIT below the fine grid's needs: the grid is capped (sampling_capped = 1,
  the note says so) and still covers the whole input.
- Read through ParaView's AMReX plotfile reader (AMReXBoxLibGridReader), a plotfile of the same
  two levels (cell data) written here: the same n - 1 as the in-memory AMR with cell data, to
  float rounding; with the reader's Level = 0 the grid follows level 0 and a note names the level
  not loaded.
"""
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import (vtkAMRBox, vtkAMRUtilities, vtkOverlappingAMR,
                                           vtkUniformGrid)

import cfd_testing as cfd
import schlieren_testing as st

st.load_plugin(globals())

A, S = 1e-4, 0.25
N0 = 32                      # level 0 cells per axis over [-1, 1]
H0 = 2.0 / N0
H1 = H0 / 2
PATCH = 0.5                  # level 1 covers [-PATCH, PATCH]^3
N1 = int(round(2 * PATCH / H1))


def f(X, Y, Z):
    return A * np.exp(-(X ** 2 + Y ** 2 + Z ** 2) / S ** 2)


def block(lo, h, n, offset, cells):
    """A vtkUniformGrid of n^3 cells from corner lo, spacing h: f + offset at its points (or at
    its cell centres)."""
    g = vtkUniformGrid()
    g.SetOrigin(lo, lo, lo)
    g.SetSpacing(h, h, h)
    g.SetDimensions(n + 1, n + 1, n + 1)
    x = lo + h * (np.arange(n) + 0.5) if cells else lo + h * np.arange(n + 1)
    Z, Y, X = np.meshgrid(x, x, x, indexing="ij")
    a = numpy_to_vtk((f(X, Y, Z) + offset).ravel().astype(np.float32), deep=1)
    a.SetName("n_minus_1")
    (g.GetCellData() if cells else g.GetPointData()).AddArray(a)
    return g


def make_amr(fine_offset=0.0, cells=False):
    amr = vtkOverlappingAMR()
    amr.Initialize(2, [1, 1])
    amr.SetOrigin([-1.0, -1.0, -1.0])
    amr.SetSpacing(0, [H0] * 3)
    amr.SetAMRBox(0, 0, vtkAMRBox([-1.0] * 3, [N0 + 1] * 3, [H0] * 3, [-1.0] * 3, 8))
    amr.SetDataSet(0, 0, block(-1.0, H0, N0, 0.0, cells))
    amr.SetSpacing(1, [H1] * 3)
    amr.SetAMRBox(1, 0, vtkAMRBox([-PATCH] * 3, [N1 + 1] * 3, [H1] * 3, [-1.0] * 3, 8))
    amr.SetDataSet(1, 0, block(-PATCH, H1, N1, fine_offset, cells))
    amr.SetRefinementRatio(0, 2)
    vtkAMRUtilities.BlankCells(amr)
    return amr


def fields(data):
    fd = data.GetFieldData()
    out = {}
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        out[a.GetName()] = [a.GetVariantValue(j).ToString() for j in range(a.GetNumberOfValues())]
    return out


def index_of(source, **kw):
    with st.CapturedOutput() as log:
        ri = RefractiveIndex(Input=source, Model="Passthrough", **kw)
        out = sm.Fetch(ri)
    return ri, out, log.text


def n1_and_points(out):
    (n1,) = cfd.grid_arrays(out, "n_minus_1")
    nx, ny, nz = out.GetDimensions()
    o, h = out.GetOrigin(), out.GetSpacing()
    x = [o[a] + h[a] * np.arange((nx, ny, nz)[a]) for a in range(3)]
    Z, Y, X = np.meshgrid(x[2], x[1], x[0], indexing="ij")
    return n1, X, Y, Z


def second_derivative_sum(X, Y, Z):
    e = np.exp(-(X ** 2 + Y ** 2 + Z ** 2) / S ** 2)
    return sum(np.abs(A * (4 * c ** 2 / S ** 4 - 2 / S ** 2) * e) for c in (X, Y, Z))


def gradient_norm(X, Y, Z):
    return 2 * np.sqrt(X ** 2 + Y ** 2 + Z ** 2) / S ** 2 * f(X, Y, Z)


if st.argument("--cap-child"):
    # run with SCHLIEREN_MEMORY_LIMIT set: the automatic grid is capped and said to be
    T = st.Checker("test_amr (memory cap)")
    tp = cfd.producer(globals(), make_amr())
    _, out, log = index_of(tp)
    fd = fields(out)
    dims = out.GetDimensions()
    print("capped grid %s; note: %s" % (dims, [n for n in fd.get("index_notes", []) if "AMR" in n]))
    T.check(fd.get("sampling_capped") == ["1"], "the memory limit caps the automatic grid "
            "(sampling_capped = %s)" % fd.get("sampling_capped"))
    T.check(max(dims) < 65 and min(dims) >= 2, "the capped grid is coarser than the finest "
            "level's 65^3 (%s)" % (dims,))
    T.check("capped to" in log and "memory budget" in log, "the log says the grid was capped by "
            "the memory budget")
    b = out.GetBounds()
    T.check(b[0] < -0.99 and b[1] > 0.99, "the capped grid still spans the input (%s)" % (b,))
    T.finish()
    sys.exit(0)

T = st.Checker("test_amr")

# the uniform fine reference: f at h1 over [-1, 1]^3
nf = int(round(2 / H1)) + 1
x = -1 + H1 * np.arange(nf)
Zf, Yf, Xf = np.meshgrid(x, x, x, indexing="ij")
uniform = cfd.producer(globals(), cfd.make_image([nf] * 3, [-1] * 3, [H1] * 3,
                                                 {"n_minus_1": f(Xf, Yf, Zf)}))

amr_source = cfd.producer(globals(), make_amr())
amr_index, amr_out, amr_log = index_of(amr_source)
fd = fields(amr_out)
print("AMR grid %s, spacing %s; notes: %s" % (amr_out.GetDimensions(), amr_out.GetSpacing(),
                                             fd.get("index_notes")))
T.check(fd.get("amr_levels") == ["2"] and fd.get("amr_finest_level") == ["1"],
        "field data: 2 levels, the finest level 1 (%s, %s)" % (fd.get("amr_levels"),
                                                           fd.get("amr_finest_level")))
T.check(abs(float(fd["amr_finest_spacing"][0]) - H1) < 1e-12, "amr_finest_spacing = h1")
T.check(tuple(amr_out.GetDimensions()) == (nf, nf, nf) and
        abs(amr_out.GetSpacing()[0] - H1) < 1e-5 * H1,
        "the automatic grid is the finest level's: %d^3 at h1 (got %s at %.6g)"
        % (nf, amr_out.GetDimensions(), amr_out.GetSpacing()[0]))
T.check("finest level covering it" in amr_log, "the log says each point takes the finest level")

n1, X, Y, Z = n1_and_points(amr_out)
exact = f(X, Y, Z)
inside = (np.abs(X) <= PATCH + 1e-9) & (np.abs(Y) <= PATCH + 1e-9) & (np.abs(Z) <= PATCH + 1e-9)
err = np.abs(n1 - exact)
bound_n1 = H0 ** 2 / 8 * second_derivative_sum(X, Y, Z)[~inside].max() + 1e-6 * A
print("n-1: max error inside the patch %.3g, outside %.3g (bound h0^2/8 sum|f''| = %.3g)"
      % (err[inside].max(), err[~inside].max(), bound_n1))
T.check(err[inside].max() <= 1e-6 * A, "inside the patch n - 1 is the fine level's to float "
        "rounding (%.3g)" % err[inside].max())
T.check(err[~inside].max() <= bound_n1, "outside the patch within the coarse level's "
        "interpolation error (%.3g <= %.3g)" % (err[~inside].max(), bound_n1))

# the schlieren images: AMR against the uniform fine grid
common = dict(Cutoff="KnifeEdge", CutoffScale=st.KNIFE_SCALE, Resolution=[64, 64], Passes=1,
              ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], Integrator="RK4")
uni_index = RefractiveIndex(Input=uniform, Model="Passthrough")
_, _, _, D_uni, _ = st.image_arrays(sm.Fetch(SchlierenImage(Input=uni_index, **common)))
Xi, Yi, _, D_amr, _ = st.image_arrays(sm.Fetch(SchlierenImage(Input=amr_index, **common)))
bound_eps = 1.0 * bound_n1 / H1 + 1e-9
d_eps = np.abs(D_amr - D_uni).max()
eps_max = st.gaussian_max_deflection(A)
print("deflection: max |AMR - uniform| %.3g rad (bound L max|e| / h1 = %.3g; max |eps| %.3g)"
      % (d_eps, bound_eps, eps_max))
T.check(np.abs(D_uni).max() > 0.5 * eps_max, "the uniform grid's image deflects (max %.3g)"
        % np.abs(D_uni).max())
T.check(d_eps <= bound_eps, "the AMR image's deflection equals the uniform grid's within the "
        "coarse level's error (%.3g <= %.3g)" % (d_eps, bound_eps))

# a field that differs on purpose between the levels: the patch's values are the fine level's
tagged_source = cfd.producer(globals(), make_amr(fine_offset=1e-5))
_, tagged_out, _ = index_of(tagged_source)
t1, _, _, _ = n1_and_points(tagged_out)
offset = t1 - exact
T.check(np.all(np.abs(offset[inside] - 1e-5) < 1e-3 * 1e-5), "every grid point in the patch "
        "carries the fine level's offset (%d points)" % inside.sum())
T.check(np.all(np.abs(offset[~inside]) <= bound_n1), "no point outside the patch does")

# cell data: sampled between cell centres, not converted to points
cell_source = cfd.producer(globals(), make_amr(cells=True))
_, cell_out, cell_log = index_of(cell_source)
c1, _, _, _ = n1_and_points(cell_out)
cerr = np.abs(c1 - exact)
patch_face = inside & ((np.abs(X) > PATCH - H1 / 2 - 1e-9) | (np.abs(Y) > PATCH - H1 / 2 - 1e-9) |
                       (np.abs(Z) > PATCH - H1 / 2 - 1e-9))
d2 = second_derivative_sum(X, Y, Z)
ROUND = 1e-6 * A  # float32 rounding of the stored and sampled values
bound_in = H1 ** 2 / 8 * d2[inside].max() + ROUND
bound_face = bound_in + H1 / 2 * 1.01 * gradient_norm(X, Y, Z)[patch_face].max()
# outside the patch: coarse interpolation between centres, and its half cell at the domain's edge
edge = (np.abs(X) > 1 - H0 / 2 - 1e-9) | (np.abs(Y) > 1 - H0 / 2 - 1e-9) | (np.abs(Z) > 1 - H0 / 2 - 1e-9)
bound_out = H0 ** 2 / 8 * d2[~inside].max() + H0 / 2 * gradient_norm(X, Y, Z)[edge].max() + ROUND
print("cell data: max error inside %.6g (bound %.6g), at the patch's faces %.3g (bound %.3g), "
      "outside %.3g (bound %.3g)" % (cerr[inside & ~patch_face].max(), bound_in,
                                     cerr[patch_face].max(), bound_face, cerr[~inside].max(),
                                     bound_out))
T.check("sampled as cells" in cell_log, "the log says the cell data was sampled as cells")
T.check(cerr[inside & ~patch_face].max() <= bound_in, "cell data inside the patch within "
        "h1^2/8 sum|f''|")
T.check(cerr[patch_face].max() <= bound_face, "cell data at the patch's faces within the half "
        "cell's h1/2 |grad f|")
T.check(cerr[~inside].max() <= bound_out, "cell data outside the patch within the coarse level's "
        "error")

# an AMReX plotfile of the same two levels (cell data), read through ParaView's reader
def write_plotfile(path, name="n_minus_1"):
    """Level 0: 32^3 cells on [-1, 1]^3; level 1: the patch refined by 2; f at the cell centres
    (little-endian doubles, AMReX's FAB layout: x fastest)."""
    levels = [(-1.0, H0, N0, (0, 0, 0)), (-PATCH, H1, N1, (N1 // 2,) * 3)]
    domains = [((0, 0, 0), (N0 - 1,) * 3), ((0, 0, 0), (2 * N0 - 1,) * 3)]
    os.makedirs(path, exist_ok=True)
    h = ["HyperCLaw-V1.1", "1", name, "3", "0.0", "1", "-1 -1 -1", "1 1 1", "2",
         " ".join("((%d,%d,%d) (%d,%d,%d) (0,0,0))" % (lo + hi) for lo, hi in domains), "0 0",
         "%r %r %r" % ((H0,) * 3), "%r %r %r" % ((H1,) * 3), "0", "0"]
    for level, (lo, h_cell, n, start) in enumerate(levels):
        h += ["%d 1 0.0" % level, "0"] + ["%r %r" % (lo, lo + n * h_cell)] * 3
        h.append("Level_%d/Cell" % level)
        d = os.path.join(path, "Level_%d" % level)
        os.makedirs(d, exist_ok=True)
        xc = lo + h_cell * (np.arange(n) + 0.5)
        Zc, Yc, Xc = np.meshgrid(xc, xc, xc, indexing="ij")
        v = f(Xc, Yc, Zc).astype("<f8")
        box = "((%d,%d,%d) (%d,%d,%d) (0,0,0))" % (start + tuple(s + n - 1 for s in start))
        with open(os.path.join(d, "Cell_D_00000"), "wb") as fab:
            fab.write(("FAB ((8, (64 11 52 0 1 12 0 1023)),(8, (8 7 6 5 4 3 2 1)))%s 1\n"
                       % box).encode())
            fab.write(v.tobytes())
        with open(os.path.join(d, "Cell_H"), "w") as ch:
            ch.write("1\n0\n1\n0\n(1 0\n%s\n)\n1\nFabOnDisk: Cell_D_00000 0\n\n1,1\n%r,\n\n"
                     "1,1\n%r,\n" % (box, float(v.min()), float(v.max())))
    with open(os.path.join(path, "Header"), "w") as hf:
        hf.write("\n".join(h) + "\n")


with tempfile.TemporaryDirectory() as tmp:
    plotfile = os.path.join(tmp, "plt00000")
    write_plotfile(plotfile)
    reader = AMReXBoxLibGridReader(FileNames=[plotfile])
    reader.UpdatePipelineInformation()
    reader.CellArrayStatus = ["n_minus_1"]
    _, read_out, _ = index_of(reader)
    r1, _, _, _ = n1_and_points(read_out)
    d_read = np.abs(r1 - c1).max()
    T.check(read_out.GetDimensions() == cell_out.GetDimensions() and d_read <= 1e-6 * A,
            "the plotfile through AMReXBoxLibGridReader: the in-memory AMR's n - 1 (largest "
            "difference %.2g, float rounding)" % d_read)
    reader.Level = 0
    with st.CapturedOutput() as log0:
        ri0 = RefractiveIndex(Input=reader, Model="Passthrough")
        out0 = sm.Fetch(ri0)
    T.check(out0.GetDimensions() == (N0 + 1,) * 3 and "were not loaded" in log0.text,
            "the reader's Level = 0: the grid follows level 0 (%s) and the note names the level "
            "not loaded" % (out0.GetDimensions(),))
    Delete(ri0)
    Delete(reader)

# the memory cap, in a child process with SCHLIEREN_MEMORY_LIMIT below the fine grid's needs
env = dict(os.environ, SCHLIEREN_MEMORY_LIMIT=str(30 * 1024 * 1024))
pvpython = st.argument("--pvpython", shutil.which("pvpython") or "pvpython")
child = subprocess.run([pvpython, os.path.abspath(__file__), "--plugin", st.plugin_path(),
                        "--cap-child", "1"], env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True, timeout=300)
print(child.stdout.strip())
T.check(child.returncode == 0, "the memory-capped run passes its checks (exit %d)"
        % child.returncode)

T.finish()
