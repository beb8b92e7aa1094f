# SPDX-License-Identifier: BSD-3-Clause
"""The Python plugin (SchlierenPython.py) under MPI when a filter upstream of ours fails on one
rank only: no hang (the C++ plugin's collective guard, docs/PARALLEL.md, in _engine._MpiGuard).

    SCHLIEREN_MPI_TIMEOUT=5 mpiexec -n 2 pvbatch --mpi --symmetric test_mpi_python_deadline.py \
        --plugin SchlierenPython.py --tmp DIR

Every rank runs this script (--symmetric).
1. A reader whose file is missing on rank 1 only (it returns failure there, and ParaView's
   executive then never calls our filters there; a ProgrammableSource that raises returns
   success: our filters run on an empty piece and agree on the failure as before) -> RefractiveIndex -> SchlierenImage: before, rank 0 waited in RefractiveIndex's
   first collective for ever (pvbatch never returned: the ctest TIMEOUT). Now rank 0's
   RefractiveIndex fails within SCHLIEREN_MPI_TIMEOUT (5 s here; checked: 4 to 12 s) with the C++
   guard's words, "rank 1 did not reach RefractiveIndex's collective 1 (... its data pass) within
   5 s: its upstream probably failed (see its error). SCHLIEREN_MPI_TIMEOUT sets the wait.", and
   nothing from SchlierenImage; rank 1 says nothing of ours; every output is empty. Then rank 0's
   file missing: rank 1 names rank 0 after the timeout and twice a grace (7.5 s). Then rank 1's
   file missing straight in front of SchlierenImage, NumericalSchlieren and RefractionOctree: they
   run on rank 1 on an input without a grid, say so, and both ranks fail at once with the agreed
   error (before, a TypeError on rank 1 left rank 0 waiting for ever; RefractionOctree gave rank
   0's piece with the tolerance of rank 0's range alone, and no error).
2. Right after, a good pipeline (RefractiveScene -> RefractiveIndex -> SchlierenImage, traced in
   pieces) on both ranks: no error, and rank 0's image is one process's (the plugin's own
   algorithms as one piece) bit for bit: the failed step left no message that the next one takes
   for its own.
"""
import collections
import inspect
import os
import sys
import tempfile
import time

if not hasattr(inspect, "getargspec"):  # ParaView 5.11.0 on Python >= 3.11 (docs/PYTHON.md)
    _ArgSpec = collections.namedtuple("ArgSpec", "args varargs keywords defaults")
    inspect.getargspec = lambda f: _ArgSpec(*inspect.getfullargspec(f)[:4])

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

import schlieren_testing as st  # noqa: E402

simple.LoadPlugin(st.argument("--plugin"), remote=False, ns=globals())
controller = vtkMultiProcessController.GetGlobalController()
ranks = controller.GetNumberOfProcesses() if controller else 1
rank = controller.GetLocalProcessId() if controller else 0
T = st.Checker("test_mpi_python_deadline (rank %d of %d)" % (rank, ranks))
T.check(ranks == 2, "rank %d: 2 ranks (got %d)" % (rank, ranks))
TIMEOUT = float(os.environ.get("SCHLIEREN_MPI_TIMEOUT", "0"))
T.check(TIMEOUT == 5.0, "rank %d: SCHLIEREN_MPI_TIMEOUT=5 (got %r)" % (rank, TIMEOUT))
# the guard needs mpi4py (python3-mpi4py, scripts/common.sh): without it this test would hang
guard = sys.modules["schlieren_paraview_plugin._engine"].controller_ranks()._guard
if not T.check(guard is not None, "rank %d: the collective guard is on (mpi4py importable)" % rank):
    T.finish()

SCENE = dict(Scene="GaussianSphere", Dimensions=[24, 22, 20], Bounds=[-1, 1, -1, 1, -1, 1],
             Amplitude=1e-4, Width=0.3, Center=[0.1, -0.05, 0.02])
KNIFE = dict(ViewDirection=[0.3, -0.2, -1.0], ViewUp=[0, 1, 0], Resolution=[32, 28], Passes=1,
             Seed=3, Cutoff="KnifeEdge", CutoffScale=0.0, KnifeAngle=30.0, Backend="CPU")
TMP = st.argument("--tmp") or tempfile.gettempdir()
os.makedirs(TMP, exist_ok=True)
GOOD_FILE = os.path.join(TMP, "mpi_python_deadline_rank%d.vti" % rank)
st.write_mpi_volume(GOOD_FILE)  # a 21^3 image with density


def our_errors(text):
    """(filter, message) of the plugin's errors ("ERROR: In <filter>: <message>")."""
    out = []
    for line in text.splitlines():
        if line.startswith("ERROR: In "):
            who, _, message = line[len("ERROR: In "):].partition(": ")
            if ".cxx" not in who:
                out.append((who, message))
    return out


def points(proxy):
    data = proxy.GetClientSideObject().GetOutputDataObject(0)
    return data.GetNumberOfPoints() if data is not None else 0


def failing(missing):
    """A reader whose file is missing on rank `missing` (it returns failure there, and the
    executive never calls our filters there) -> RefractiveIndex -> SchlierenImage."""
    source = simple.XMLImageDataReader(FileName=[
        os.path.join(TMP, "no_such_file.vti") if rank == missing else GOOD_FILE])
    index = RefractiveIndex(Input=source, Model="GladstoneDale")  # noqa: F821
    index.InputArray = ["POINTS", "density"]
    knife = SchlierenImage(Input=index, **KNIFE)  # noqa: F821
    t0 = time.time()
    with st.CapturedOutput() as c:
        knife.UpdatePipeline()
    waited = time.time() - t0
    errors = our_errors(c.text)
    print("rank %d: the update with rank %d's upstream failing took %.1f s" % (rank, missing, waited))
    if rank == missing:
        T.check(not errors and "no_such_file.vti" in c.text,
                "rank %d: its upstream's error, nothing of ours: %s" % (rank, errors))
    else:
        T.check(len(errors) == 1 and errors[0][0] == "RefractiveIndex" and errors[0][1] == (
                "rank %d did not reach RefractiveIndex's collective 1 (an all-gather, its data "
                "pass) within 5 s: its upstream probably failed (see its error). "
                "SCHLIEREN_MPI_TIMEOUT sets the wait." % missing),
                "rank %d: one error, RefractiveIndex's, naming rank %d in the C++ guard's words: "
                "%s" % (rank, missing, errors))
        # rank 0 gives up at the timeout; another rank waits for rank 0's word twice a grace
        # (a quarter of the timeout) longer
        T.check(4.0 <= waited <= (12.0 if rank == 0 else 15.0),
                "rank %d: the error came after the 5 s timeout, not much more (%.1f s)"
                % (rank, waited))
    T.check(points(index) == 0 and points(knife) == 0,
            "rank %d: empty outputs (%d, %d points)" % (rank, points(index), points(knife)))
    for p in (knife, index, source):
        simple.Delete(p)
    # in step again before the next update (the guard's own words: a rank that failed fast would
    # meet the others at the next pipeline's first collective, of the same name)
    controller.Barrier()


def failing_image(name, make, nothing):
    """A reader whose file is missing on rank 1 straight in front of SchlierenImage,
    NumericalSchlieren or RefractionOctree: these filters run there on an input without a grid, say so and agree on
    it with rank 0 at once (before, a TypeError on rank 1 left rank 0 waiting)."""
    source = simple.XMLImageDataReader(FileName=[
        os.path.join(TMP, "no_such_file.vti") if rank == 1 else GOOD_FILE])
    f = make(source)
    t0 = time.time()
    with st.CapturedOutput() as c:
        f.UpdatePipeline()
    waited = time.time() - t0
    said = "The input volume is empty: nothing to %s. If a filter upstream reported an error, " \
        "that is the cause; fix it there." % nothing
    expected = said if rank == 1 else "another rank (1) failed: " + said
    T.check(our_errors(c.text) == [(name, expected)] and waited < 4.0 and points(f) == 0,
            "rank %d: %s on rank 1's failed reader: the agreed error at once (%.1f s, not the "
            "guard's 5), empty output (%d points): %s" % (rank, name, waited, points(f),
                                                         our_errors(c.text)))
    for p in (f, source):
        simple.Delete(p)


# 1. the upstream fails on rank 1 only, then on rank 0 only
failing(1)
failing(0)
failing_image("SchlierenImage", lambda src: SchlierenImage(Input=src, **KNIFE),  # noqa: F821
              "trace")
failing_image("NumericalSchlieren", lambda src: NumericalSchlieren(  # noqa: F821
    Input=src, Resolution=[32, 28]), "image")
failing_image("RefractionOctree", lambda src: RefractionOctree(Input=src),  # noqa: F821
              "build an octree of")
controller.Barrier()

# 2. a good pipeline after them: rank 0's image one process's bit for bit
good_scene = RefractiveScene(**SCENE)  # noqa: F821
good_index = RefractiveIndex(Input=good_scene, Model="GladstoneDale")  # noqa: F821
good_index.InputArray = ["POINTS", "density"]
good_knife = SchlierenImage(Input=good_index, **KNIFE)  # noqa: F821
with st.CapturedOutput() as c:
    good_knife.UpdatePipeline()
T.check(not our_errors(c.text), "rank %d: the good pipeline: no error %s"
        % (rank, our_errors(c.text)))
if rank == 0:
    alg = sys.modules["schlieren_paraview_plugin.algorithms"]
    ranks_of = alg._ranks
    alg._ranks = lambda: None  # the plugin's algorithms as one process runs them
    try:
        one_scene = alg.RefractiveScene(**SCENE)
        one_index = alg.RefractiveIndex(Model="GladstoneDale", InputArray="density")
        one_index.SetInputConnection(one_scene.GetOutputPort())
        one_knife = alg.SchlierenImage(**KNIFE)
        one_knife.SetInputConnection(one_index.GetOutputPort())
        one_knife.UpdatePiece(0, 1, 0)
        one = vtk_to_numpy(one_knife.GetOutputDataObject(0).GetPointData()
                           .GetArray("intensity")).copy()
    finally:
        alg._ranks = ranks_of
    out = good_knife.GetClientSideObject().GetOutputDataObject(0)
    mine = out.GetPointData().GetArray("intensity")
    mine = vtk_to_numpy(mine).copy() if mine is not None else np.zeros(0, np.float32)
    T.check(mine.shape == one.shape and np.array_equal(mine.view(np.uint8), one.view(np.uint8))
            and float(np.ptp(one)) > 0.05,
            "rank 0: the image on 2 ranks is one process's bit for bit (%d pixels, intensity "
            "%.4f to %.4f)" % (one.size, one.min(), one.max()))
    distributed = out.GetFieldData().GetArray("distributed_ranks")
    T.check(distributed is not None and distributed.GetValue(0) == 2,
            "rank 0: traced in pieces on 2 ranks")
T.finish()
