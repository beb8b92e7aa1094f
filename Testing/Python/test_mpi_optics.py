# SPDX-License-Identifier: BSD-3-Clause
"""RefractionOctree, Integrator Auto and the optics arrays under MPI equal one process.

Two runs of this script, one pipeline:
  mpiexec -n 2 pvbatch --mpi test_mpi_optics.py --plugin <Schlieren.so> --output <dir>/optics.npz
  pvpython test_mpi_optics.py --plugin <Schlieren.so> --input <dir>/optics.npz

The 2-rank run checks that the octree filter ran on both pieces with one tolerance (the automatic
tolerance reduces the range of n - 1 across ranks) and writes the images; the one-process run
traces the same pipeline and compares. Under MPI SchlierenImage traces "color" and "bos" in pieces
(the CPU backend; each rank computes the whole grid's octree levels of its cells at the filter's
tolerance, at the filter's default MaxLevel (7), up to the level the volume reaches, found from the
pieces, with ghosts as deep as such a block, and Auto is
resolved on the pieces with every rank the same choice; Auto's line of sight is then traced
without ray passing, its partial integrals added in another order: k within 1e-6), and "fringes"
(the error estimate: each ray traced again at twice the step on the pieces; the CPU backend too,
where the pieces' arithmetic is one process's: on an OpenCL device the pieces' kernel rounds
otherwise, and an estimate, a difference of two close deflections, shows it). The images must be those of one
process: every point array within 1e-6 (of its largest value), the same integrator, step,
expected error and samples per ray, and the same Auto report (less its timing).
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview import simple  # noqa: F401
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

import schlieren_testing as st

st.load_plugin(globals())
ranks = sm.ActiveConnection.GetNumberOfDataPartitions()
T = st.Checker("test_mpi_optics (%d rank%s)" % (ranks, "s" if ranks > 1 else ""))

scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[64, 64, 64], Bounds=[-1, 1, -1, 1, -1, 1],  # noqa: F821
                        Amplitude=1e-4, Width=0.2, Center=[0.1, -0.05, 0.02])
octree = RefractionOctree(Input=scene)  # noqa: F821
images = {
    # Auto with the octree, colour filter (rgb), automatic k (reduced across ranks)
    "color": SchlierenImage(Input=octree, Integrator="Auto", Cutoff="ColorFilter",  # noqa: F821
                            Resolution=[64, 48], Passes=2, Seed=3, ViewDirection=[0.3, -0.2, -1.0],
                            Backend="CPU"),
    # interferometry with the error estimate and a Gaussian film filter
    "fringes": SchlierenImage(Input=octree, Integrator="Midpoint", StepSize=1.0, Cutoff="Interferometry",  # noqa: F821
                              EstimateError=1, Filter="Gaussian", FilterWidth=0.7, Resolution=[48, 48],
                              Passes=2, Seed=5, ReferenceTilt=3.0, Backend="CPU"),
    # BOS with RK4 over the octree
    "bos": SchlierenImage(Input=octree, Integrator="RK4", StepSize=1.0, Cutoff="BOS",  # noqa: F821
                          BackgroundDistance=3.0, Resolution=[48, 48], Passes=1, Jitter=0, Backend="CPU"),
}
ARRAYS = {"color": ["intensity", "deflection", "rgb"], "fringes": ["intensity", "deflection", "phase", "error_estimate"],
          "bos": ["intensity", "deflection", "bos_displacement"]}
NUMBERS = ["photons", "samples", "samples_per_ray", "step_size", "octree", "octree_tolerance", "cutoff_scale",
           "underresolved_rays", "failed_rays", "max_error"]


def record(name, data):
    out = {}
    pd = data.GetPointData()
    for a in ARRAYS[name]:
        arr = pd.GetArray(a)
        out[name + "/" + a] = vtk_to_numpy(arr).copy() if arr is not None else np.array([])
    fd = data.GetFieldData()
    for key in NUMBERS + ["expected_error", "auto_tolerance"]:
        arr = fd.GetArray(key)
        out[name + "/" + key] = np.array(arr.GetValue(0) if arr is not None else np.nan)
    for key in ("integrator", "auto_report"):
        arr = fd.GetAbstractArray(key)
        text = arr.GetValue(0) if arr is not None else ""
        out[name + "/" + key] = np.array(re.sub(r", \d+ ms\)", ")", text))
    return out


if ranks > 1:
    output = st.argument("--output")
    if not output:
        raise RuntimeError("pass --output FILE.npz")
    if os.path.exists(output):
        os.remove(output)  # a failed run must not leave an older result for the comparison
    T.check(ranks == 2, "pvbatch runs on 2 ranks (got %d)" % ranks)
    tolerances = []
    for r in range(ranks):
        piece = sm.Fetch(octree, r)
        levels = piece.GetPointData().GetArray("octree_level")
        tolerances.append(piece.GetFieldData().GetArray("octree_tolerance").GetValue(0))
        T.check(levels is not None and levels.GetNumberOfTuples() < 64 ** 3,
                "rank %d: the octree filter ran on its piece (%d points)" % (r, piece.GetNumberOfPoints()))
    T.check(tolerances[0] == tolerances[1] and tolerances[0] > 0,
            "both ranks use one octree tolerance (%s)" % tolerances)
    saved = {}
    for name, proxy in images.items():
        with st.CapturedOutput() as out:
            image = sm.Fetch(proxy, 0)
            empty = sm.Fetch(proxy, 1)
        T.check("ERROR" not in out.text, "%s: no error%s" % (name, "" if "ERROR" not in out.text else ": " + out.text[:400]))
        T.check(image.GetNumberOfPoints() > 0 and empty.GetNumberOfPoints() == 0,
                "%s: rank 0 holds the image, rank 1 an empty one" % name)
        saved.update(record(name, image))
    T.check(str(saved["color/auto_report"]).startswith("Auto chose"), "color: Auto reports its choice: %s" % saved["color/auto_report"])
    np.savez(output, **saved)
    print("wrote %s" % output)
else:
    path = st.argument("--input")
    if not path or not os.path.exists(path):
        raise RuntimeError("the 2-rank result %r is missing: run this script under MPI first" % path)
    mpi = np.load(path)
    for name, proxy in images.items():
        serial = record(name, sm.Fetch(proxy))
        for a in ARRAYS[name]:
            key = name + "/" + a
            scale = max(float(np.abs(serial[key]).max()), 1e-30) if serial[key].size else 1.0
            T.check(serial[key].size > 0 and mpi[key].shape == serial[key].shape,
                    "%s: %s present, %s values" % (name, a, serial[key].shape))
            if mpi[key].shape == serial[key].shape:
                T.close(mpi[key] / scale, serial[key] / scale, 1e-6, "%s: %s, 2 ranks vs 1 (relative to its largest)" % (name, a))
        for key in NUMBERS + ["expected_error", "auto_tolerance"]:
            a, b = float(mpi[name + "/" + key]), float(serial[name + "/" + key])
            # Auto's line of sight is traced in pieces without ray passing: each ray's partial
            # integrals add up in another order, so the largest deflection (hence k) agrees to
            # float rounding; every count and every choice stays exact
            rel = 1e-6 if key == "cutoff_scale" else 1e-9
            T.check((np.isnan(a) and np.isnan(b)) or abs(a - b) <= rel * max(abs(b), 1e-30),
                    "%s: field data %s, 2 ranks %.10g vs 1 %.10g" % (name, key, a, b))
        for key in ("integrator", "auto_report"):
            T.check(str(mpi[name + "/" + key]) == str(serial[name + "/" + key]),
                    "%s: %s the same: %r" % (name, key, str(serial[name + "/" + key])[:90]))
    # (Auto may find that blocks of up to 2^3 cells do not pay for "color": it says so, the same
    # on both sides; "bos" asks for the octree and uses it)
    T.check(float(mpi["bos/octree"]) == 1.0, "the octree was used under MPI (bos)")

T.finish()
