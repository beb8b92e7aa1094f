# SPDX-License-Identifier: BSD-3-Clause
"""NumericalSchlieren and AMR input under MPI: 2 ranks of pvbatch give the one-process images.

    mpiexec -n 2 pvbatch --mpi --symmetric test_mpi_numerical_amr.py --plugin <Schlieren.so> --output <dir>/x.npz
    pvpython test_mpi_numerical_amr.py --plugin <Schlieren.so> --compare <dir>/x.npz

--symmetric: every rank runs this script (each makes its own share of the AMR); rank 0 records.

1. NumericalSchlieren on volumes split over the ranks (each rank holds a piece of the volume; the
   pieces are gathered on rank 0, which makes the image from the whole grid as one process does):
   - RefractiveScene GaussianSphere with a sphere Body (the pieces' solid points gathered too),
     Slice of |grad rho| and LineOfSight of the knife component, of the scene's `density`;
   - an unstructured input (a Wavelet tetrahedralized, density = RTData / 100) resampled by
     RefractiveIndex (GladstoneDale), read as `density`.
   Known answer: the one-process image of the same pipeline, bit for bit: the gathered grid is the
   one process's grid point for point (the scene's pieces are computed as one process computes
   them; the resampled grid on 2 ranks is the one-process grid, python.cfd_mpi), and the image is
   then computed by the same code on the same numbers. Also: the scene's 2 pieces are proper
   pieces (each rank's holds fewer points than the whole), so the gather is exercised, and only
   rank 0 holds the image. (engine.TestEngineNumericalPieces: uneven pieces, an empty rank.)
2. AMR (the two-level Gaussian of python.amr: n - 1 = 1e-4 exp(-r^2 / 0.25^2) on [-1, 1]^3, level
   0 at h0 = 1/16, a patch [-0.5, 0.5]^3 at h1 = h0 / 2), each level split in two boxes along x,
   rank 0 holding level 0's x < 0 box and level 1's x > 0 box, rank 1 the other two (so each
   rank's fine box lies over the other rank's coarse one): RefractiveIndex takes each point from
   the finest level on any rank. Known answer: the one-process grid (all four boxes on one rank)
   and its knife-edge image, bit for bit (a point the finest level covers is held at that level
   by one rank, or by two with the same value on the boxes' shared face: the sum over ranks
   divided by the count is then that value exactly); and the one-process grid is the right one:
   inside the patch n - 1 is the analytic field to float rounding (python.amr's check).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkAMRBox, vtkAMRUtilities, vtkOverlappingAMR, vtkUniformGrid
from vtkmodules.vtkParallelCore import vtkMultiProcessController

import schlieren_testing as st

st.load_plugin(globals())
output = st.argument("--output")
compare = st.argument("--compare")
if not output and not compare:
    raise RuntimeError("pass --output FILE.npz (under MPI) or --compare FILE.npz (one process)")
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
ranks = controller.GetNumberOfProcesses() if controller else 1
T = st.Checker("test_mpi_numerical_amr (rank %d of %d)" % (rank, ranks))
if output and rank == 0 and os.path.exists(output):
    os.remove(output)  # a failed run must not leave an older result for the comparison


def update(proxy):
    """Updates `proxy` on this rank: its output here and what VTK said."""
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
    T.check("ERROR" not in out.text, "rank %d, %s: no error%s" % (
        rank, proxy.GetXMLName(), "" if "ERROR" not in out.text else ": " + out.text.strip()[:600]))
    return proxy.GetClientSideObject().GetOutputDataObject(0), out.text


def arrays(data, *names):
    return [vtk_to_numpy(data.GetPointData().GetArray(n)).copy() for n in names]


record = {}

# 1. NumericalSchlieren on split volumes
DIMS = [48, 40, 36]
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=DIMS, Body="Sphere", BodyRadius=0.2,
                        BodyCenter=[0.35, 0.1, 0.0])
wavelet = Wavelet(WholeExtent=[-12, 12, -10, 10, -8, 8])
density = Calculator(Input=Tetrahedralize(Input=wavelet), ResultArrayName="density", Function="RTData/100")
resampled = RefractiveIndex(Input=density, SamplingDimensions=[33, 29, 25])
cases = {
    "scene_slice": dict(Input=scene, Mode="Slice", Resolution=[64, 56], ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0]),
    "scene_los": dict(Input=scene, Mode="LineOfSight", Gradient="KnifeComponent", KnifeAngle=30,
                      Resolution=[56, 48], ViewDirection=[-1, 0, 0], ViewUp=[0, 0, 1]),
    "resampled_los": dict(Input=resampled, Mode="LineOfSight", Resolution=[50, 44], ViewDirection=[0, 0, -1],
                          ViewUp=[0, 1, 0]),
}
scene_piece, _ = update(scene)
points = DIMS[0] * DIMS[1] * DIMS[2]
if ranks > 1:
    T.check(0 < scene_piece.GetNumberOfPoints() < points, "rank %d: the scene's piece holds %d of the %d points" % (
        rank, scene_piece.GetNumberOfPoints(), points))
for name, kw in sorted(cases.items()):
    ns = NumericalSchlieren(**kw)
    film, text = update(ns)
    nx, ny = kw["Resolution"]
    if rank == 0:
        T.check(film.GetNumberOfPoints() == nx * ny, "%s: rank 0 holds the %d-pixel image (%d)" % (
            name, nx * ny, film.GetNumberOfPoints()))
        record[name + "_intensity"], record[name + "_gradient"], record[name + "_blocked"] = arrays(
            film, "intensity", "numerical_gradient", "blocked")
        field = film.GetFieldData().GetAbstractArray("numerical_field").GetValue(0)
        record[name + "_field"] = np.array(field)
        T.check(field == "density",
                "%s: the field read is %s" % (name, field))
    else:
        T.check(film.GetNumberOfPoints() == 0, "%s: rank %d holds no image (%d points)" % (
            name, rank, film.GetNumberOfPoints()))
    Delete(ns)
if rank == 0:
    T.check(record["scene_slice_blocked"].sum() > 50, "the body is blocked on %d pixels of the slice"
            % record["scene_slice_blocked"].sum())

# 2. AMR: the two-level Gaussian, each level in two boxes along x, shared out over the ranks
A, S = 1e-4, 0.25
N0 = 32
H0 = 2.0 / N0
H1 = H0 / 2
PATCH = 0.5
N1 = int(round(2 * PATCH / H1))


def f(X, Y, Z):
    return A * np.exp(-(X ** 2 + Y ** 2 + Z ** 2) / S ** 2)


def box_grid(lo, h, n):
    g = vtkUniformGrid()
    g.SetOrigin(lo)
    g.SetSpacing(h, h, h)
    g.SetDimensions([c + 1 for c in n])
    x = [lo[a] + h * np.arange(n[a] + 1) for a in range(3)]
    Z, Y, X = np.meshgrid(x[2], x[1], x[0], indexing="ij")
    v = numpy_to_vtk(f(X, Y, Z).ravel().astype(np.float32), deep=1)
    v.SetName("n_minus_1")
    g.GetPointData().AddArray(v)
    return g


def make_amr(owner):
    """The AMR's metadata on every rank; box (level, b) only where owner(level, b) is this rank."""
    amr = vtkOverlappingAMR()
    amr.Initialize(2, [2, 2])
    amr.SetOrigin([-1.0, -1.0, -1.0])
    for level, (lo, h, n) in enumerate(((-1.0, H0, N0), (-PATCH, H1, N1))):
        amr.SetSpacing(level, [h] * 3)
        for b in range(2):
            corner = [lo + b * h * (n // 2), lo, lo]
            cells = [n // 2, n, n]
            amr.SetAMRBox(level, b, vtkAMRBox(corner, [c + 1 for c in cells], [h] * 3, [-1.0] * 3, 8))
            if owner(level, b) == rank:
                amr.SetDataSet(level, b, box_grid(corner, h, cells))
    amr.SetRefinementRatio(0, 2)
    vtkAMRUtilities.BlankCells(amr)
    return amr


# rank 0: level 0's x < 0 box and level 1's x > 0 box; rank 1 the others; one process all four
amr = make_amr((lambda level, b: (b + level) % 2) if ranks > 1 else (lambda level, b: 0))
producer = TrivialProducer()
producer.GetClientSideObject().SetOutput(amr)
amr_index = RefractiveIndex(Input=producer, Model="Passthrough")
amr_image = SchlierenImage(Input=amr_index, Backend="CPU", Cutoff="KnifeEdge", CutoffScale=st.KNIFE_SCALE, Resolution=[48, 48],
                           Passes=1, Jitter=0, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0])
piece, text = update(amr_index)
film, _ = update(amr_image)
e = np.array(piece.GetExtent())
n1, = arrays(piece, "n_minus_1")
if ranks > 1:
    # every rank's piece of n - 1, gathered on rank 0 by the controller (numpy bytes)
    from vtkmodules.vtkCommonCore import vtkFloatArray, vtkIntArray
    ext = vtkIntArray()
    ext.SetNumberOfValues(6)
    for i in range(6):
        ext.SetValue(i, int(e[i]))
    all_ext = vtkIntArray()
    controller.AllGather(ext, all_ext)
    vals = vtkFloatArray()
    vals.DeepCopy(piece.GetPointData().GetArray("n_minus_1"))
    all_vals = vtkFloatArray()
    controller.AllGatherV(vals, all_vals)
    if rank == 0:
        record["amr_extents"] = vtk_to_numpy(all_ext).reshape(ranks, 6).copy()
        record["amr_values"] = vtk_to_numpy(all_vals).copy()
else:
    record["amr_extents"] = e.reshape(1, 6)
    record["amr_values"] = n1.astype(np.float32)
if rank == 0:
    T.check("finest level covering it" in text, "AMR: the note says each point takes the finest level")
    T.check(film.GetNumberOfPoints() == 48 * 48, "AMR: rank 0 holds the image")
    record["amr_intensity"], record["amr_deflection"] = arrays(film, "intensity", "deflection")

if rank == 0:
    if output:
        T.check(ranks == 2, "pvbatch runs on 2 ranks (got %d)" % ranks)
        ex = record["amr_extents"]
        T.check(all(ex[r][5] - ex[r][4] < 64 or ex[r][3] - ex[r][2] < 64 or ex[r][1] - ex[r][0] < 64
                    for r in range(ranks)), "AMR: each rank's grid is a piece of the 65^3 grid %s" % ex.tolist())
        T.check(record["amr_values"].size == sum(int(np.prod(ex[r][1::2] - ex[r][::2] + 1)) for r in range(ranks)),
                "AMR: every rank's piece gathered")
        np.savez(output, ranks=ranks, **record)
        print("wrote %s" % output)
    else:
        mpi = np.load(compare)
        for name in sorted(cases):
            for what in ("intensity", "gradient", "blocked"):
                a, b = mpi[name + "_" + what], record[name + "_" + what]
                T.check(a.shape == b.shape and np.array_equal(a, b), "%s: the %s on %d ranks = on one process, bit "
                        "for bit (largest difference %s)" % (name, what, int(mpi["ranks"]),
                                                               np.abs(a - b).max() if a.shape == b.shape else "shape"))
        # the AMR grid: every rank's piece equals the one-process grid there, bit for bit
        whole = record["amr_extents"][0]
        full = record["amr_values"].reshape(whole[5] + 1, whole[3] + 1, whole[1] + 1)
        at = 0
        for r, ex in enumerate(mpi["amr_extents"]):
            count = int(np.prod(ex[1::2] - ex[::2] + 1))
            theirs = mpi["amr_values"][at:at + count]
            at += count
            mine = full[ex[4]:ex[5] + 1, ex[2]:ex[3] + 1, ex[0]:ex[1] + 1].ravel()
            T.check(np.array_equal(theirs, mine), "AMR: rank %d's piece %s of n - 1 = the one-process grid, bit for "
                    "bit (largest difference %.3g)" % (r, ex.tolist(), np.abs(theirs - mine).max()))
        for what in ("intensity", "deflection"):
            a, b = mpi["amr_" + what], record["amr_" + what]
            T.check(np.array_equal(a, b), "AMR: the knife-edge %s on 2 ranks = on one process, bit for bit (largest "
                    "difference %.3g)" % (what, np.abs(a - b).max()))
        # the one-process grid is the two-level Gaussian's: the fine level's values inside the patch
        h = H1
        x = -1 + h * np.arange(whole[1] + 1)
        Z, Y, X = np.meshgrid(x, x, x, indexing="ij")
        inside = (np.abs(X) <= PATCH + 1e-9) & (np.abs(Y) <= PATCH + 1e-9) & (np.abs(Z) <= PATCH + 1e-9)
        err = np.abs(full - f(X, Y, Z))[inside].max()
        T.check(full.shape == (65, 65, 65) and err <= 1e-6 * A, "AMR (one process): the 65^3 grid at h1, the fine "
                "level's n - 1 inside the patch (largest error %.3g)" % err)
T.finish()
