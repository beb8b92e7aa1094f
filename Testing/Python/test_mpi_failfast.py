# SPDX-License-Identifier: BSD-3-Clause
"""Issue 48: an upstream failure on one rank of three stops every rank at once, with an error
naming the failing rank, at SCHLIEREN_MPI_TIMEOUT's default (120 s: the guard's timeout is not
what ends it).

    mpiexec -n 3 pvbatch --mpi --symmetric test_mpi_failfast.py --plugin <Schlieren.so> --tmp DIR

Each rank reads its own 21^3 volume, or a file that is missing where it should fail (the reader
then returns failure, and the executive never calls the filter on that rank: before issue 48 the
other ranks waited at the filter's first collective for the guard's 120 s, and the failing rank
spun in the next MPI collective it met). The filters' executive has the ranks agree on their
inputs' passes first (schlieren::NewAgreeingExecutive):
a. rank 2's reader fails -> RefractiveIndex -> SchlierenImage: ranks 0 and 1 each say, once,
   "the input of RefractiveIndex failed on rank 2", and nothing from SchlierenImage; rank 2 says
   nothing of ours.
b. rank 0's reader fails -> NumericalSchlieren: ranks 1 and 2 name rank 0.
c. rank 0's reader fails -> RefractionOctree: ranks 1 and 2 name rank 0.
(A reader of a missing file returns failure where it is asked for a piece that is not empty: on
rank 1 of these 3, or where two ranks' files are missing, the reader of this ParaView returns an
empty piece without failure, and the other ranks work on their pieces: nothing the pipeline sees.)
d. right after (no barrier: the agreement keeps the ranks in step), a good pipeline gives its
   image on rank 0 and no error on any rank.
Every output of a failed case is empty. The test's TIMEOUT (60 s) is what catches a hang.
"""
import os
import sys
import tempfile

os.environ.pop("SCHLIEREN_MPI_TIMEOUT", None)  # the default wait: only the agreement is fast

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkParallelCore import vtkMultiProcessController

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_mpi_failfast")
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
ranks = controller.GetNumberOfProcesses() if controller else 1
T.check(ranks == 3, "rank %d: pvbatch --symmetric runs on 3 ranks (got %d)" % (rank, ranks))

tmp = st.argument("--tmp") or tempfile.gettempdir()
os.makedirs(tmp, exist_ok=True)
good = os.path.join(tmp, "mpi_failfast_rank%d.vti" % rank)
st.write_mpi_volume(good)


def reader(failing_ranks):
    name = os.path.join(tmp, "no_such_file.vti") if rank in failing_ranks else good
    return XMLImageDataReader(FileName=[name])


def update(proxy):
    """Updates `proxy` on this rank: (output points, errors of our filters)."""
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
    data = proxy.GetClientSideObject().GetOutputDataObject(0)
    errs = [(c, m) for c, m in st.errors_of(out.text)
            if c.startswith(("vtkRefracti", "vtkSchlieren", "vtkNumerical"))]
    return (data.GetNumberOfPoints() if data else 0), errs


def check(case, failing, filter_name, pipeline):
    proxies = pipeline(reader(failing))
    points, errs = update(proxies[-1])
    who = ("rank %d" % failing[0]) if len(failing) == 1 else \
        "ranks " + ", ".join(str(r) for r in failing)
    if rank in failing:
        ok = not errs
    else:
        expected = "the input of %s failed on %s " % (filter_name, who)
        ok = len(errs) == 1 and errs[0][0] == "vtk" + filter_name and errs[0][1].startswith(expected)
    T.check(ok and points == 0,
            "rank %d: %s: %s, empty output (%d points); errors: %s"
            % (rank, case, "silent (its reader said why)" if rank in failing else "one error naming " + who,
               points, "; ".join("%s %s" % (c, m[:160]) for c, m in errs)))
    for p in reversed(proxies):
        Delete(p)


def index_and_image(r):
    ri = RefractiveIndex(Input=r, Model="GladstoneDale")
    return [r, ri, SchlierenImage(Input=ri, Resolution=[16, 16], Backend="CPU")]


check("a", (2,), "RefractiveIndex", index_and_image)
check("b", (0,), "NumericalSchlieren",
      lambda r: [r, NumericalSchlieren(Input=r, DensityArray="density", Resolution=[16, 16])])
check("c", (0,), "RefractionOctree", lambda r: [r, RefractionOctree(Input=r)])

# d. in step again at once
proxies = index_and_image(reader(()))
points, errs = update(proxies[-1])
T.check(not errs and (rank != 0 or points == 256),
        "rank %d: d: the good pipeline right after gives the image (%d points; errors: %s)"
        % (rank, points, "; ".join(m[:150] for _, m in errs)))
T.finish()
