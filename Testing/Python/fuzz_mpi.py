# SPDX-License-Identifier: BSD-3-Clause
"""The fuzz's MPI part: seeded random pipelines on 3 ranks, most with a failure on one rank
somewhere upstream of our filters or inside them; no rank may hang, and the ranks must agree.

    mpiexec -n 3 pvbatch --mpi --symmetric fuzz_mpi.py --plugin <Schlieren.so> [--cases 24]
        [--seed 25]

Every rank draws the same cases (one seed). A case: a reader of a 21^3 volume (n_minus_1 and
density, written by each rank for itself) -> RefractiveIndex (Passthrough or GladstoneDale; or none) -> maybe
RefractionOctree -> SchlierenImage with random settings (film, integrator, cutoff, passes). The
failure, on one rank drawn at random, in that rank's file (every rank runs the same filters):
none; the file missing there (the executive then never calls our filters on that rank: the
others meet the collective guard, SCHLIEREN_MPI_TIMEOUT = 2 s here); n - 1 = -2 there; NaN where
x > 4 there; the arrays renamed there. Each update is timed. Asserted on every rank, per case:
- it returned within 30 s (a hang is a failure, not a CI stall; the ctest timeout is the backstop);
- rank 0 has an image or an error, and an image is finite, and not blank without a warning;
- the ranks agree: where rank 0 has an image no rank has an error, and where any rank has an
  error every rank has one (none returns an empty output silently);
- a case with no failure gives an image and no error.
After each case the ranks meet (a barrier), as a script re-synchronises after a failure.
"""
import os
import random
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
os.environ["SCHLIEREN_MPI_TIMEOUT"] = "2"

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkCommonCore import vtkIntArray
from vtkmodules.vtkParallelCore import vtkMultiProcessController

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("fuzz_mpi")
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
ranks = controller.GetNumberOfProcesses() if controller else 1
T.check(ranks == 3, "rank %d: pvbatch --symmetric runs on 3 ranks (got %d)" % (rank, ranks))
NCASES = int(st.argument("--cases", "24"))
SEED = int(st.argument("--seed", "25"))
tmp = st.argument("--tmp") or tempfile.gettempdir()  # this rank's files, rank in their names
os.makedirs(tmp, exist_ok=True)


def write_volume(path, amp, failure):
    """A 21^3 volume on [-10, 10]^3 with n_minus_1 and density, spoilt as `failure` says: n - 1
    = -2 everywhere (negative), NaN where x > 4 (nan), no such arrays (noarray). Rank-local: no
    MPI in this writer, and every rank runs the same filters (only the data differ)."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

    img = vtkImageData()
    img.SetExtent(-10, 10, -10, 10, -10, 10)
    z, y, x = np.meshgrid(*(np.arange(-10, 11.0),) * 3, indexing="ij")
    n1 = amp * np.exp(-(x * x + y * y + z * z) / 30.0)
    if failure == "negative":
        n1[:] = -2
    elif failure == "nan":
        n1[x > 4] = np.nan
    for name, v in (("n_minus_1", n1), ("density", n1 / 2.256e-4 * (1 if failure != "negative" else 1e9))):
        arr = numpy_to_vtk(np.ascontiguousarray(v.ravel(), dtype=np.float32), deep=1)
        arr.SetName(name if failure != "noarray" else "renamed_" + name)
        img.GetPointData().AddArray(arr)
    w = vtkXMLImageDataWriter()
    w.SetInputData(img)
    w.SetFileName(path)
    w.Write()


def errors_of(text):
    """Every error message in `text` but the executive's 'returned failure'."""
    lines = text.splitlines()
    out = []
    for i, line in enumerate(lines):
        if "ERR|" in line:
            body = line.split("ERR|", 1)[1].strip()
        elif line.startswith("ERROR: In") and i + 1 < len(lines):
            body = lines[i + 1].strip()
        else:
            continue
        if "returned failure" not in body:
            out.append(body.split("): ", 1)[-1])
    return out


def warned(text, data):
    if "WARN|" in text or "Warning: In" in text:
        return True
    w = data.GetFieldData().GetAbstractArray("warnings") if data is not None else None
    return w is not None and w.GetNumberOfValues() > 0 and bool(w.GetValue(0).strip())


def all_gather(value):
    send, recv = vtkIntArray(), vtkIntArray()
    send.InsertNextValue(value)
    controller.AllGather(send, recv)
    return [recv.GetValue(i) for i in range(recv.GetNumberOfTuples())]


def draw(rng, k):
    return dict(
        k=k,
        amp=10 ** rng.uniform(-6, -3),
        failure=rng.choice(["none", "missing", "missing", "negative", "nan", "noarray"]),
        bad=rng.randrange(3),
        index=rng.choice(["none", "Passthrough", "GladstoneDale"]),
        octree=rng.random() < 0.3,
        image=dict(Resolution=[rng.randint(4, 32), rng.randint(4, 32)],
                   Passes=rng.randint(1, 2),
                   Integrator=rng.choice(["Euler", "Verlet", "RK4", "Straight", "Auto"]),
                   Cutoff=rng.choice(["KnifeEdge", "Shadowgraph", "Interferometry", "Circular"]),
                   ViewDirection=rng.choice([[0, 0, -1], [1, 0, 0], [0.3, -0.5, 0.8]]),
                   ViewUp=[0, 1, 0.2], Backend="CPU", Threads=1))


rng = random.Random(SEED)
cases = [draw(rng, k) for k in range(NCASES)]
summary = {}
t_all = time.time()
for c in cases:
    path = os.path.join(tmp, "fuzz_mpi_%d_rank%d.vti" % (c["k"], rank))
    mine = rank == c["bad"]
    write_volume(path, c["amp"], c["failure"] if mine else "none")
    fname = os.path.join(tmp, "no_such_file.vti") if mine and c["failure"] == "missing" else path
    made = [XMLImageDataReader(FileName=[fname])]
    if c["index"] != "none":
        made.append(RefractiveIndex(Input=made[-1], Model=c["index"]))
    if c["octree"]:
        made.append(RefractionOctree(Input=made[-1]))
    image = SchlierenImage(Input=made[-1], **c["image"])
    made.append(image)
    t0 = time.time()
    pyerror = ""
    with st.CapturedOutput() as out:
        try:
            image.UpdatePipeline()
        except Exception as e:  # reported below, never swallowed
            pyerror = "%s: %s" % (type(e).__name__, e)
    seconds = time.time() - t0
    data = image.GetClientSideObject().GetOutputDataObject(0)
    errs = errors_of(out.text)
    points = data.GetNumberOfPoints() if data is not None else 0
    finite = True
    blank = False
    if points:
        from vtkmodules.util.numpy_support import vtk_to_numpy
        import numpy as np

        pd = data.GetPointData()
        finite = all(np.all(np.isfinite(vtk_to_numpy(pd.GetArray(i))))
                     for i in range(pd.GetNumberOfArrays()) if pd.GetArray(i) is not None)
        landed = data.GetFieldData().GetArray("landed_photons")
        blank = landed is not None and landed.GetValue(0) == 0 and not warned(out.text, data)
    states = all_gather(2 if points else (1 if errs else 0))  # 2 image, 1 error, 0 empty
    label = "case %d (%s on rank %d, %s%s, %s)" % (
        c["k"], c["failure"], c["bad"], c["index"], " + octree" if c["octree"] else "",
        c["image"]["Integrator"])
    problems = []
    if pyerror:
        problems.append("Python: " + pyerror[:200])
    if seconds > 30:
        problems.append("the update took %.0f s" % seconds)
    if states[0] == 0:
        problems.append("rank 0 has neither an image nor an error")
    if states[0] == 2 and 1 in states:
        problems.append("rank 0 has an image while some rank has an error")
    if 1 in states and 0 in states:
        problems.append("some rank has an error while another returned an empty output silently")
    if not finite:
        problems.append("non-finite values in the image")
    if blank:
        problems.append("a blank image without a warning")
    if c["failure"] == "none" and (errs or states[0] != 2):
        problems.append("no failure drawn, yet no image")
    T.check(not problems, "rank %d: %s: %.1f s, states %s%s%s" % (
        rank, label, seconds, states, "; " + "; ".join(problems) if problems else "",
        " (" + errs[0][:140] + ")" if errs else ""))
    outcome = "image" if states[0] == 2 else "error"
    summary[(c["failure"], outcome)] = summary.get((c["failure"], outcome), 0) + 1
    for p in reversed(made):
        Delete(p)
    os.remove(path)
    controller.Barrier()

if rank == 0:
    print("fuzz_mpi: %d cases (seed %d) on 3 ranks in %.0f s" % (NCASES, SEED, time.time() - t_all))
    for (f, o), n in sorted(summary.items()):
        print("  %-10s %-6s %3d" % (f, o, n))
controller.Barrier()
T.finish()
