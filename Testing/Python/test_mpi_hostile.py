# SPDX-License-Identifier: BSD-3-Clause
"""Failures on one rank of three, upstream of our filters or inside them: every rank finishes, and
each says one error (no second one from a filter downstream).

    mpiexec -n 3 pvbatch --mpi --symmetric test_mpi_hostile.py --plugin <Schlieren.so>

1. RefractionOctree fails on rank 0 only (n_minus_1 = -2 where y < -0.5, in rank 0's piece of a
   9 x 24 x 9 LinearGradient split along y) and feeds SchlierenImage: rank 0 says its own error,
   ranks 1 and 2 "another rank (0) failed: ...", and no rank has an error from SchlierenImage.
2. A PythonCalculator that raises on rank 0 only feeds SchlierenImage; its sources are deleted; a
   second pipeline, PythonCalculator (raising on rank 0) -> RefractiveIndex -> SchlierenImage, is
   updated: every rank returns (the ctest timeout catches a hang), rank 0 with the image or an
   error.
"""
import os
import sys

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


def errors_of(text):
    """(class, message) of every error in `text` but the executive's 'returned failure'."""
    lines = text.splitlines()
    out = []
    for i, line in enumerate(lines):
        if "ERR|" in line:
            body = line.split("ERR|", 1)[1].strip()
        elif line.startswith("ERROR: In") and i + 1 < len(lines):
            body = lines[i + 1].strip()
        else:
            continue
        if "returned failure" in body:
            continue
        out.append((body.split(" ", 1)[0], body.split("): ", 1)[-1]))
    return out


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
controller.Barrier()
T.finish()
