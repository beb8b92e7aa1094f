# SPDX-License-Identifier: BSD-3-Clause
"""Failures on one rank of three, upstream of our filters or inside them: every rank finishes, and
each says one error (no second one from a filter downstream).

    mpiexec -n 3 pvbatch --mpi --symmetric test_mpi_hostile.py --plugin <Schlieren.so>

1. RefractionOctree fails on rank 0 only (n_minus_1 = -2 where y < -0.5, in rank 0's piece of a
   9 x 24 x 9 LinearGradient split along y) and feeds SchlierenImage: rank 0 says its own error,
   ranks 1 and 2 "another rank (0) failed: ...", and no rank has an error from SchlierenImage.
2. A PythonCalculator that raises on rank 0 only feeds SchlierenImage; its sources are deleted; a
   second pipeline, PythonCalculator (raising on rank 0) -> RefractiveIndex -> SchlierenImage, is
   updated: every rank returns, rank 0 with the image or an error. (A PythonCalculator that
   raises passes its input on: every rank still reaches our filters.)
3. A rank that never comes: an upstream that fails where the pipeline cannot see it (here the
   script itself does not update on rank 2, as a rank held in another collective would not; an
   upstream failure the pipeline sees is agreed on at once: test_mpi_failfast.py). Ranks 0 and 1
   update reader -> RefractiveIndex -> SchlierenImage and each return with the guard's error
   naming rank 2 and the step it did not reach, after SCHLIEREN_MPI_TIMEOUT = 2 s here. Then the
   ranks meet (a barrier: the script is in step again) and a good pipeline gives its image on
   every rank with no error: a stale guard message of the failed update does not pair with a
   later one.
"""
import os
import sys
import tempfile
import time

# the guard's wait, read on the plugin's first collective (before that: no collective yet)
os.environ["SCHLIEREN_MPI_TIMEOUT"] = "2"

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkParallelCore import vtkMultiProcessController

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_mpi_hostile")
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
ranks = controller.GetNumberOfProcesses() if controller else 1
T.check(ranks == 3, "rank %d: pvbatch --symmetric runs on 3 ranks (got %d)" % (rank, ranks))


errors_of = st.errors_of


# 1. RefractionOctree failing on rank 0, SchlierenImage downstream
scene = RefractiveScene(Scene="LinearGradient", Dimensions=[9, 24, 9], GradientA=1.0,
                        GradientB=0.01, Center=[0, -0.5, 0])
calc = Calculator(Input=scene, ResultArrayName="n_minus_1", Function="-2*(coordsY<-0.5)+1e-4")
octree = RefractionOctree(Input=calc)
image = SchlierenImage(Input=octree, Resolution=[16, 16], Backend="CPU")
with st.CapturedOutput() as out:
    image.UpdatePipeline()
errs = errors_of(out.text)
own = [m for c, m in errs if c.startswith("vtkRefractionOctree")]
others = [(c, m) for c, m in errs if not c.startswith("vtkRefractionOctree")]
if rank == 0:
    ok = len(own) == 1 and "have n <= 0" in own[0] and "another rank" not in own[0]
else:
    ok = len(own) == 1 and own[0].startswith("another rank (0) failed: ")
T.check(ok and not others,
        "rank %d: one error, RefractionOctree's (%s), none downstream (%s)"
        % (rank, "; ".join(m[:100] for m in own), "; ".join("%s %s" % (c, m[:100]) for c, m in others)))
for p in (image, octree, calc, scene):
    Delete(p)

# 2. The failing PythonCalculator upstream, twice
BAD = "n_minus_1 if inputs[0].VTKObject.GetBounds()[2] > -0.45 else no_such_name"
s1 = RefractiveScene(Scene="GaussianSphere", Dimensions=[16, 24, 16])
p1 = PythonCalculator(Input=s1, Expression=BAD, ArrayName="n_minus_1")
i1 = SchlierenImage(Input=p1, Resolution=[16, 16], Backend="CPU")
with st.CapturedOutput():
    i1.UpdatePipeline()
for p in (i1, p1, s1):
    Delete(p)
s2 = RefractiveScene(Scene="GaussianSphere", Dimensions=[16, 24, 16])
p2 = PythonCalculator(Input=s2, Expression=BAD.replace("n_minus_1 if", "density if"),
                      ArrayName="density")
r2 = RefractiveIndex(Input=p2)
i2 = SchlierenImage(Input=r2, Resolution=[16, 16], Backend="CPU")
with st.CapturedOutput() as out:
    i2.UpdatePipeline()
points = i2.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
# the image is gathered on rank 0 (the other ranks' outputs are empty by design)
T.check(rank != 0 or points > 0 or errors_of(out.text),
        "rank %d: the second pipeline after a failing first one returned an image or an error "
        "(%d points; %s)" % (rank, points, "; ".join(m[:120] for _, m in errors_of(out.text))))

# 3. An upstream that fails on some ranks only: a reader of a file that is missing there
tmp = st.argument("--tmp") or tempfile.gettempdir()  # this rank's files, rank in their names
os.makedirs(tmp, exist_ok=True)
good = os.path.join(tmp, "mpi_hostile_rank%d.vti" % rank)
st.write_mpi_volume(good)


def reader(failing_ranks):
    name = os.path.join(tmp, "no_such_file.vti") if rank in failing_ranks else good
    return XMLImageDataReader(FileName=[name])


def update(proxy):
    """Updates `proxy`; (seconds, errors) on this rank."""
    t0 = time.time()
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
    return time.time() - t0, errors_of(out.text)


def guard_errors(errs):
    return [m for _, m in errs if "did not reach" in m or "different collectives" in m]


def good_pipeline(label):
    """After the ranks meet again, every rank traces, rank 0 gets the image, nobody errs."""
    controller.Barrier()
    r = reader(())
    ri = RefractiveIndex(Input=r, Model="GladstoneDale")
    im = SchlierenImage(Input=ri, Resolution=[16, 16], Backend="CPU")
    _, errs = update(im)
    pts = im.GetClientSideObject().GetOutputDataObject(0).GetNumberOfPoints()
    T.check(not errs and (rank != 0 or pts == 256),
            "rank %d: %s: the good pipeline after it gives the image (%d points; errors: %s)"
            % (rank, label, pts, "; ".join(m[:150] for _, m in errs)))
    for p in (im, ri, r):
        Delete(p)


# rank 2 never updates; ranks 0 and 1 wait at RefractiveIndex's agreement on its inputs
ra = reader(())
ria = RefractiveIndex(Input=ra, Model="GladstoneDale")
ia = SchlierenImage(Input=ria, Resolution=[16, 16], Backend="CPU")
ta, errs_a = update(ia) if rank != 2 else (0.0, [])
for p in (ia, ria, ra):
    Delete(p)
ga = guard_errors(errs_a)
ok = rank == 2 or (len(ga) == 1 and ga[0].startswith(
    "rank 2 did not reach RefractiveIndex's inputs (its data) within 2 s: its upstream probably "
    "failed"))
T.check(ok, "rank %d: 3: rank 2 never comes: %.1f s; %s"
        % (rank, ta, "; ".join(m[:160] for _, m in errs_a)))
good_pipeline("3")

controller.Barrier()
T.finish()
