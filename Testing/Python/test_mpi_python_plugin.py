# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView Python plugin (SchlierenPython.py) under MPI against the C++ plugin and against one
process (issue 47: the Python plugin was "one process (no MPI)": each rank saw only its piece).

    mpiexec -n 2 pvbatch --mpi --symmetric test_mpi_python_plugin.py --plugin SchlierenPython.py

Every rank runs this script (--symmetric). The reference: the same pipelines through the plugin's
own algorithms as one process runs them (their ranks left out, one piece). Then:

1. a Gaussian sphere from the Python plugin's RefractiveScene, split into two pieces (each rank
   fills its own), through RefractiveIndex (GladstoneDale), SchlierenImage (an oblique knife edge
   with the automatic scale, Backend CPU: the volume traced in pieces, rays handed between the
   ranks), NumericalSchlieren (LineOfSight), RefractionOctree (its levels and tolerance), and
   the scene with a solid sphere (its solid points through RefractiveIndex, rays blocked): the
   index's pieces tile the grid and hold the one-process n - 1 and grad n there bit for bit;
   rank 0 holds the images, rank 1 empty ones; the images (every point array) and their field
   data (less the timings and what the report says of the ranks) equal the one-process images bit
   for bit, and the C++ plugin's (its compiled filters, schlieren_vtk, run on the same pieces with
   UpdatePiece) bit for bit, the index's and the octree's pieces too; the octree's tolerance is the
   whole volume's (one process's);
   A resampled input (the blunt fin's PLOT3D multiblock, skipped where ../shared/data has none):
   read whole on every rank, resampled whole there and cut to the rank's piece: each piece one
   process's grid and arrays there, the field data and the image one process's, bit for bit;
2. a failure on rank 1 only (RefractiveIndex reading an array its input does not have there): both
   ranks end with the one agreed error, rank 1 its own, rank 0 "another rank (1) failed: <it>",
   empty outputs, no hang (the ctest TIMEOUT); a new pipeline right after gives one process's
   image on rank 0 (the ranks stayed in step).
"""
import collections
import inspect
import os
import sys
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
T = st.Checker("test_mpi_python_plugin (rank %d of %d)" % (rank, ranks))

SCENE = dict(Scene="GaussianSphere", Dimensions=[40, 36, 32], Bounds=[-1, 1, -1, 1, -1, 1],
             Amplitude=1e-4, Width=0.3, Center=[0.1, -0.05, 0.02])
KNIFE = dict(ViewDirection=[0.3, -0.2, -1.0], ViewUp=[0, 1, 0], Resolution=[48, 40], Passes=1,
             Seed=3, Cutoff="KnifeEdge", CutoffScale=0.0, KnifeAngle=30.0, Backend="CPU")
# a scene with a body (RefractiveScene's solid points, passed on by RefractiveIndex, traced in pieces)
BODY = dict(SCENE, Body="Sphere", BodyRadius=0.2, BodyCenter=[-0.3, 0.1, 0.05])
NUMERICAL = dict(Mode="LineOfSight", Resolution=[48, 40], ViewDirection=[0.3, -0.2, -1.0])
TIMINGS = ("tracing_seconds", "exchange_seconds")
# what the report says of the ranks and the session's volumes, not of the image: one process
# packs the whole volume, two ranks trace pieces
RANKS_REPORT = ("distributed_ranks", "volume_from", "volumes_packed", "held_points_max",
                "rays_handed_on", "ray_traffic_bytes", "exchange_rounds", "ghost_layers")


def local(proxy):
    """This rank's output of `proxy` (a copy)."""
    from vtkmodules.vtkCommonDataModel import vtkImageData
    out = vtkImageData()
    out.DeepCopy(proxy.GetClientSideObject().GetOutputDataObject(0))
    return out


def record(prefix, data):
    """Every point array and field data value of an image, by name."""
    r = {prefix + ":extent": np.array(data.GetExtent()),
         prefix + ":origin": np.array(data.GetOrigin()),
         prefix + ":spacing": np.array(data.GetSpacing())}
    pd = data.GetPointData()
    for i in range(pd.GetNumberOfArrays()):
        r[prefix + ":" + pd.GetArrayName(i)] = vtk_to_numpy(pd.GetArray(i)).copy()
    fd = data.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        if a.GetName() in TIMINGS:
            continue
        if a.IsA("vtkDataArray"):
            r[prefix + "@" + a.GetName()] = vtk_to_numpy(a).copy()
        else:
            r[prefix + "@" + a.GetName()] = np.array([a.GetValue(k) for k in
                                                      range(a.GetNumberOfValues())])
    return r


def same(a, b):
    """Bit for bit (floats by their bits, NaNs included)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind == "f":
        return np.array_equal(a.view(np.uint8), b.view(np.uint8))
    return np.array_equal(a, b)


def compare(mine, theirs, prefix, what, names=None, leave_out=()):
    """Every entry of `theirs` under `prefix` equal in `mine` (or only `names`), but the field
    data in `leave_out`."""
    keys = [k for k in theirs if k.startswith(prefix + ":") or (
        k.startswith(prefix + "@") and k.split("@", 1)[1] not in leave_out)]
    if names is not None:
        keys = [k for k in keys if k.split(":", 1)[-1].split("@", 1)[-1] in names]
    missing = [k for k in keys if k not in mine]
    differ = [k for k in keys if k in mine and not same(mine[k], theirs[k])]
    T.check(keys and not missing and not differ,
            "rank %d: %s: %d arrays and field data bit for bit%s%s" % (
                rank, what, len(keys), "; missing " + ", ".join(missing) if missing else "",
                "; differ " + ", ".join(differ) if differ else ""))


def filter_errors(text):
    """(filter, message) of the filters' errors ("ERROR: In <filter>: <message>"), not the
    executive's ("ERROR: In .../vtkExecutive.cxx, line ...")."""
    out = []
    for line in text.splitlines():
        if line.startswith("ERROR: In "):
            who, _, message = line[len("ERROR: In "):].partition(": ")
            if ".cxx" not in who:
                out.append((who, message))
    return out


NAMES = ("scene", "index", "knife", "numerical", "octree", "body_scene", "index_body",
         "knife_body")


def python_pipelines():
    scene = RefractiveScene(**SCENE)  # noqa: F821 (the plugin's proxies)
    index = RefractiveIndex(Input=scene, Model="GladstoneDale")  # noqa: F821
    index.InputArray = ["POINTS", "density"]
    knife = SchlierenImage(Input=index, **KNIFE)  # noqa: F821
    numerical = NumericalSchlieren(Input=index, **NUMERICAL)  # noqa: F821
    octree = RefractionOctree(Input=index)  # noqa: F821
    body_scene = RefractiveScene(**BODY)  # noqa: F821
    index_body = RefractiveIndex(Input=body_scene, Model="GladstoneDale")  # noqa: F821
    index_body.InputArray = ["POINTS", "density"]
    knife_body = SchlierenImage(Input=index_body, **KNIFE)  # noqa: F821
    return scene, index, knife, numerical, octree, body_scene, index_body, knife_body


def run_python():
    """The Python plugin's outputs on this rank: (record, error texts)."""
    proxies = python_pipelines()
    out = {}
    with st.CapturedOutput() as c:
        for name, p in zip(NAMES, proxies):
            if name.endswith("scene"):
                continue
            p.UpdatePipeline()
            out.update(record(name, local(p)))
    for p in reversed(proxies):
        simple.Delete(p)
    return out, c.text


def run_cxx():
    """The C++ plugin's compiled filters on this rank's piece (UpdatePiece(rank, ranks))."""
    import schlieren_vtk as cxx

    def index_of(body):
        scene = cxx.vtkRefractiveScene()
        scene.SetScene(cxx.vtkRefractiveScene.GAUSSIAN_SPHERE)
        scene.SetDimensions(*SCENE["Dimensions"])
        scene.SetBounds(*SCENE["Bounds"])
        scene.SetAmplitude(SCENE["Amplitude"])
        scene.SetWidth(SCENE["Width"])
        scene.SetCenter(*SCENE["Center"])
        if body:
            scene.SetBody(cxx.vtkRefractiveScene.SPHERE_BODY)
            scene.SetBodyRadius(BODY["BodyRadius"])
            scene.SetBodyCenter(*BODY["BodyCenter"])
        index = cxx.vtkRefractiveIndex()
        index.SetInputConnection(scene.GetOutputPort())
        index.SetModel(cxx.vtkRefractiveIndex.GLADSTONE_DALE)
        index.SetInputArrayToProcess(0, 0, 0, 0, "density")
        index._scene = scene  # kept alive with it
        return index
    index, index_body = index_of(False), index_of(True)

    def image(source):
        f = cxx.vtkSchlierenImage()
        f.SetInputConnection(source.GetOutputPort())
        f.SetViewDirection(*KNIFE["ViewDirection"])
        f.SetViewUp(*KNIFE["ViewUp"])
        f.SetResolution(*KNIFE["Resolution"])
        f.SetPasses(KNIFE["Passes"])
        f.SetSeed(KNIFE["Seed"])
        f.SetCutoffScale(KNIFE["CutoffScale"])
        f.SetKnifeAngle(KNIFE["KnifeAngle"])
        f.SetBackend(cxx.vtkSchlierenImage.CPU)
        return f
    knife = image(index)
    numerical = cxx.vtkNumericalSchlieren()
    numerical.SetInputConnection(index.GetOutputPort())
    numerical.SetMode(1)  # LineOfSight
    numerical.SetResolution(*NUMERICAL["Resolution"])
    numerical.SetViewDirection(*NUMERICAL["ViewDirection"])
    octree = cxx.vtkRefractionOctree()
    octree.SetInputConnection(index.GetOutputPort())
    knife_body = image(index_body)
    out = {}
    for name, f in (("index", index), ("knife", knife), ("numerical", numerical),
                    ("octree", octree), ("index_body", index_body), ("knife_body", knife_body)):
        f.UpdatePiece(rank, ranks, 0)
        out.update(record(name, f.GetOutputDataObject(0)))
    return out


def run_one_process():
    """The same pipelines through the plugin's own algorithms (the classes behind its proxies,
    module schlieren_paraview_plugin.algorithms) as one process runs them: their ranks left out
    (the module's _ranks() None while they run), updated as one piece."""
    alg = sys.modules["schlieren_paraview_plugin.algorithms"]
    ranks_of = alg._ranks
    alg._ranks = lambda: None
    try:
        scene = alg.RefractiveScene(**SCENE)
        index = alg.RefractiveIndex(Model="GladstoneDale", InputArray="density")
        index.SetInputConnection(scene.GetOutputPort())
        knife = alg.SchlierenImage(**KNIFE)
        knife.SetInputConnection(index.GetOutputPort())
        numerical = alg.NumericalSchlieren(**NUMERICAL)
        numerical.SetInputConnection(index.GetOutputPort())
        octree = alg.RefractionOctree()
        octree.SetInputConnection(index.GetOutputPort())
        body_scene = alg.RefractiveScene(**BODY)
        index_body = alg.RefractiveIndex(Model="GladstoneDale", InputArray="density")
        index_body.SetInputConnection(body_scene.GetOutputPort())
        knife_body = alg.SchlierenImage(**KNIFE)
        knife_body.SetInputConnection(index_body.GetOutputPort())
        out = {}
        with st.CapturedOutput() as c:
            for name, f in (("index", index), ("knife", knife), ("numerical", numerical),
                            ("octree", octree), ("index_body", index_body),
                            ("knife_body", knife_body)):
                f.UpdatePiece(0, 1, 0)
                out.update(record(name, f.GetOutputDataObject(0)))
    finally:
        alg._ranks = ranks_of
    return out, c.text


# ---- two ranks
T.check(ranks == 2, "rank %d: 2 ranks (got %d)" % (rank, ranks))
t0 = time.time()
one, text = run_one_process()
T.check("ERROR" not in text, "rank %d: one process (the reference): no error%s" % (
    rank, "" if "ERROR" not in text else ": " + text[:400]))
print("rank %d: one process: %.1f s" % (rank, time.time() - t0))
t0 = time.time()
mine, text = run_python()
print("rank %d: the Python plugin on 2 ranks: %.1f s" % (rank, time.time() - t0))
T.check("ERROR" not in text, "rank %d: the Python plugin: no error%s" % (
    rank, "" if "ERROR" not in text else ": " + text[:600]))

# 1a. the index in two pieces that tile the grid, each the one-process values there
e = mine["index:extent"]
whole = one["index:extent"]
T.check(any(e[2 * a] > whole[2 * a] or e[2 * a + 1] < whole[2 * a + 1] for a in range(3)),
        "rank %d: RefractiveIndex computed a piece %s of the grid %s" % (rank, list(e), list(whole)))
d = [whole[2 * a + 1] - whole[2 * a] + 1 for a in range(3)]
cut = tuple(slice(e[2 * a] - whole[2 * a], e[2 * a + 1] - whole[2 * a] + 1) for a in (2, 1, 0))
for name in ("n_minus_1", "grad_n", "density"):
    ref = one["index:" + name]
    ref = ref.reshape(d[2], d[1], d[0], -1)[cut].reshape(ref.shape[1:] and (-1,) + ref.shape[1:]
                                                         or (-1,))
    T.check(same(mine["index:" + name], ref),
            "rank %d: RefractiveIndex's piece: %s of one process bit for bit" % (rank, name))
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.vtkCommonCore import vtkDoubleArray  # noqa: E402
gathered = vtkDoubleArray()
controller.AllGather(numpy_to_vtk(np.array(e, np.float64), deep=1), gathered)
both = vtk_to_numpy(gathered).reshape(2, 6).astype(int)
tiled = np.zeros(d[::-1], int)
for p in both:
    tiled[p[4]:p[5] + 1, p[2]:p[3] + 1, p[0]:p[1] + 1] += 1
T.check(tiled.min() == 1 and tiled.max() <= 2 and (tiled == 2).sum() < tiled.size // 4,
        "rank %d: the two pieces %s tile the grid (a shared plane)" % (rank, both.tolist()))

# 1b. the images: on rank 0, one process's and the C++ plugin's bit for bit; on rank 1 none
t1 = time.time()
cxx = run_cxx()
print("rank %d: the C++ plugin on 2 ranks: %.1f s" % (rank, time.time() - t1))
for name in ("knife", "numerical", "knife_body"):
    points = int(np.prod(mine[name + ":extent"][1::2] - mine[name + ":extent"][0::2] + 1))
    if rank == 0:
        compare(mine, one, name, "%s: the Python plugin on 2 ranks against one process (the "
                "report less what it says of the ranks)" % name, leave_out=RANKS_REPORT)
        compare(mine, cxx, name, "%s: the Python plugin against the C++ plugin on 2 ranks" % name)
    else:
        T.check(name + ":intensity" not in mine,
                "rank 1: %s: no image here (rank 0 holds it)" % name)
if rank == 0:
    fd = {k.split("@", 1)[1]: v for k, v in mine.items() if k.startswith("knife@")}
    T.check(fd.get("distributed_ranks", [0])[0] == 2 and fd.get("rays_handed_on", [0])[0] > 0,
            "rank 0: knife: traced in pieces on 2 ranks (distributed_ranks %s, rays handed on %s)"
            % (fd.get("distributed_ranks"), fd.get("rays_handed_on")))
compare(mine, cxx, "index", "the index's piece against the C++ plugin's piece",
        names=("n_minus_1", "grad_n", "extent", "origin", "spacing"))
compare(mine, cxx, "index_body", "the index's piece with a body against the C++ plugin's piece",
        names=("n_minus_1", "grad_n", "solid", "extent"))
if rank == 0:
    fd = {k.split("@", 1)[1]: v for k, v in mine.items() if k.startswith("knife_body@")}
    T.check(fd.get("blocked_rays", [0])[0] > 0 and "knife_body:blocked" in mine,
            "rank 0: knife_body: the body blocks rays (%s)" % fd.get("blocked_rays"))
compare(mine, one, "octree", "RefractionOctree's tolerance: one process's (the whole range)",
        names=("octree_tolerance",))
compare(mine, cxx, "octree", "RefractionOctree's piece against the C++ plugin's piece",
        names=("octree_level", "octree_tolerance", "octree_skippable_fraction", "extent"))
print("rank %d: the pipelines on 2 ranks: %.1f s" % (rank, time.time() - t0))

# 1c. a resampled input (the blunt fin's PLOT3D multiblock): each rank resamples its piece, the
# samples summed over the ranks: the C++ plugin's grid, arrays and image bit for bit
data = st.argument("--data") or os.environ.get("SCHLIEREN_DATA") or os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared", "data")
xyz, q = os.path.join(data, "bluntfinxyz.bin"), os.path.join(data, "bluntfinq.bin")
if not (os.path.exists(xyz) and os.path.exists(q)):
    print("SKIP the blunt fin part: no bluntfinxyz.bin/bluntfinq.bin in %s (set SCHLIEREN_DATA)"
          % os.path.abspath(data))
else:
    t1 = time.time()
    FIN = dict(Model="GladstoneDale", Gas="Air", DensityReference=1.2, AutomaticDimension=24,
               BodyFromGrid=1)
    reader = simple.PLOT3DReader(FileName=xyz, QFileName=[q])
    index_fin = RefractiveIndex(Input=reader, **FIN)  # noqa: F821
    index_fin.InputArray = ["POINTS", "Density"]
    knife_fin = SchlierenImage(Input=index_fin, **KNIFE)  # noqa: F821
    with st.CapturedOutput() as c:
        knife_fin.UpdatePipeline()
    fin = record("index_fin", local(index_fin))
    fin.update(record("knife_fin", local(knife_fin)))
    T.check("ERROR" not in c.text, "rank %d: the blunt fin on 2 ranks: no error%s" % (
        rank, "" if "ERROR" not in c.text else ": " + c.text[:400]))
    # the C++ plugin's filters on the same reader's pieces (its parallel reading makes a
    # one-process reference of it in this job impossible; the C++ plugin's 2 ranks against one
    # process on the blunt fin is python.mpi_cases)
    import schlieren_vtk as cxx
    index_c = cxx.vtkRefractiveIndex()
    index_c.SetInputConnection(reader.GetClientSideObject().GetOutputPort())
    index_c.SetModel(cxx.vtkRefractiveIndex.GLADSTONE_DALE)
    index_c.SetGas(cxx.vtkRefractiveIndex.AIR)
    index_c.SetDensityReference(FIN["DensityReference"])
    index_c.SetAutomaticDimension(FIN["AutomaticDimension"])
    index_c.SetBodyFromGrid(FIN["BodyFromGrid"])
    index_c.SetInputArrayToProcess(0, 0, 0, 0, "Density")
    knife_c = cxx.vtkSchlierenImage()
    knife_c.SetInputConnection(index_c.GetOutputPort())
    knife_c.SetViewDirection(*KNIFE["ViewDirection"])
    knife_c.SetViewUp(*KNIFE["ViewUp"])
    knife_c.SetResolution(*KNIFE["Resolution"])
    knife_c.SetPasses(KNIFE["Passes"])
    knife_c.SetSeed(KNIFE["Seed"])
    knife_c.SetCutoffScale(KNIFE["CutoffScale"])
    knife_c.SetKnifeAngle(KNIFE["KnifeAngle"])
    knife_c.SetBackend(cxx.vtkSchlierenImage.CPU)
    with st.CapturedOutput() as c:
        index_c.UpdatePiece(rank, ranks, 0)
        theirs = record("index_fin", index_c.GetOutputDataObject(0))
        knife_c.UpdatePiece(rank, ranks, 0)
        theirs.update(record("knife_fin", knife_c.GetOutputDataObject(0)))
    compare(fin, theirs, "index_fin", "the blunt fin's index: this rank's piece %s against the "
            "C++ plugin's" % list(fin["index_fin:extent"]),
            names=("n_minus_1", "grad_n", "solid", "vtkValidPointMask", "extent", "origin",
                   "spacing"))
    if rank == 0:
        compare(fin, theirs, "knife_fin", "the blunt fin's image against the C++ plugin's")
    for p in (knife_fin, index_fin, reader):
        simple.Delete(p)
    print("rank %d: the blunt fin: %.1f s" % (rank, time.time() - t1))

# 1d. an overlapping AMR spread over the ranks (rank 0 holds level 0, rank 1 the two boxes of
# level 1; the metadata on both): the boxes of all ranks sampled by the engine (collective): each
# rank's piece of one process's grid (the whole AMR) bit for bit, and the C++ plugin's
import amr_cases  # noqa: E402
t1 = time.time()
whole_amr = amr_cases.two_level_amr(False, 8)
spread_amr = amr_cases.two_level_amr(False, 8)  # (DeepCopy of an AMR copies no boxes in VTK 9.2)
for level, b in ((0, 0), (1, 0), (1, 1)):
    if (level == 0) != (rank == 0):
        spread_amr.SetDataSet(level, b, None)
source = simple.PVTrivialProducer()
source.GetClientSideObject().SetOutput(spread_amr)
index_amr = RefractiveIndex(Input=source, Model="GladstoneDale")  # noqa: F821
index_amr.InputArray = ["POINTS", "density"]
knife_amr = SchlierenImage(Input=index_amr, **KNIFE)  # noqa: F821
with st.CapturedOutput() as c:
    knife_amr.UpdatePipeline()
amr = record("index_amr", local(index_amr))
amr.update(record("knife_amr", local(knife_amr)))
T.check("ERROR" not in c.text, "rank %d: the AMR spread over 2 ranks: no error%s" % (
    rank, "" if "ERROR" not in c.text else ": " + c.text[:400]))
alg = sys.modules["schlieren_paraview_plugin.algorithms"]
ranks_of, alg._ranks = alg._ranks, (lambda: None)
try:
    index_one = alg.RefractiveIndex(Model="GladstoneDale", InputArray="density")
    index_one.SetInputData(whole_amr)
    knife_one = alg.SchlierenImage(**KNIFE)
    knife_one.SetInputConnection(index_one.GetOutputPort())
    index_one.UpdatePiece(0, 1, 0)
    whole = record("index_amr", index_one.GetOutputDataObject(0))
    knife_one.UpdatePiece(0, 1, 0)
    whole.update(record("knife_amr", knife_one.GetOutputDataObject(0)))
finally:
    alg._ranks = ranks_of
e, w = amr["index_amr:extent"], whole["index_amr:extent"]
d = [w[2 * a + 1] - w[2 * a] + 1 for a in range(3)]
cut = tuple(slice(e[2 * a] - w[2 * a], e[2 * a + 1] - w[2 * a] + 1) for a in (2, 1, 0))
differ = []
for name in ("n_minus_1", "grad_n", "density"):
    ref = whole.get("index_amr:" + name)
    if ref is None or not same(amr.get("index_amr:" + name), ref.reshape(d[2], d[1], d[0], -1)[
            cut].reshape(ref.shape[1:] and (-1,) + ref.shape[1:] or (-1,))):
        differ.append(name)
T.check(list(e) != list(w) and not differ and same(amr["index_amr:origin"],
                                                   whole["index_amr:origin"]),
        "rank %d: the AMR's index: this rank's piece %s of one process's grid %s, n - 1, grad n "
        "and density there bit for bit%s" % (rank, list(e), list(w), "; differ: " +
                                             ", ".join(differ) if differ else ""))
compare(amr, whole, "index_amr", "the AMR's index: the field data one process's (less the cache's "
        "budget, of the memory free)", names=[k.split("@", 1)[1] for k in whole
                                               if k.startswith("index_amr@")],
        leave_out=("index_cache_budget",))
if rank == 0:
    compare(amr, whole, "knife_amr", "the AMR's image: one process's", leave_out=RANKS_REPORT)
import schlieren_vtk as cxx  # noqa: E402
index_c = cxx.vtkRefractiveIndex()
index_c.SetInputData(spread_amr)
index_c.SetModel(cxx.vtkRefractiveIndex.GLADSTONE_DALE)
index_c.SetInputArrayToProcess(0, 0, 0, 0, "density")
index_c.UpdatePiece(rank, ranks, 0)
compare(amr, record("index_amr", index_c.GetOutputDataObject(0)), "index_amr",
        "the AMR's index: this rank's piece against the C++ plugin's",
        names=("n_minus_1", "grad_n", "extent", "origin", "spacing"))
for p in (knife_amr, index_amr, source):
    simple.Delete(p)
print("rank %d: the AMR: %.1f s" % (rank, time.time() - t1))

# 2. a failure on rank 1 only: one agreed error, empty outputs, no hang
scene = RefractiveScene(**SCENE)  # noqa: F821
index = RefractiveIndex(Input=scene, Model="GladstoneDale")  # noqa: F821
index.InputArray = ["POINTS", "density" if rank == 0 else "no_such_array"]
knife = SchlierenImage(Input=index, **KNIFE)  # noqa: F821
with st.CapturedOutput() as c:
    knife.UpdatePipeline()
errors = filter_errors(c.text)
index_errors = [m for w, m in errors if w.endswith("RefractiveIndex")]
others = [(w, m) for w, m in errors if not w.endswith("RefractiveIndex")]
theirs = index_errors[0] if index_errors else ""
from vtkmodules.vtkCommonCore import vtkCharArray  # noqa: E402
sent = vtkCharArray()
sent.SetNumberOfTuples(600)
vtk_to_numpy(sent)[:] = 0
text1 = theirs.encode()[:599]
vtk_to_numpy(sent)[:len(text1)] = np.frombuffer(text1, np.int8)
controller.Broadcast(sent, 1)
rank1 = bytes(vtk_to_numpy(sent).astype(np.uint8)).split(b"\0", 1)[0].decode()
expected = rank1 if rank == 1 else "another rank (1) failed: " + rank1
T.check(len(index_errors) == 1 and theirs == expected and "no_such_array" in rank1 and
        not others and local(index).GetNumberOfPoints() == 0 and
        local(knife).GetNumberOfPoints() == 0,
        "rank %d: a bad array on rank 1 only: one RefractiveIndex error, the agreed one (%r), "
        "nothing from SchlierenImage (%s), empty outputs" % (rank, theirs, others))
for p in (knife, index, scene):
    simple.Delete(p)

# 3. a new pipeline right after: both ranks in step, the image on rank 0, no error
scene = RefractiveScene(**SCENE)  # noqa: F821
index = RefractiveIndex(Input=scene, Model="GladstoneDale")  # noqa: F821
index.InputArray = ["POINTS", "density"]
knife = SchlierenImage(Input=index, **KNIFE)  # noqa: F821
with st.CapturedOutput() as c:
    knife.UpdatePipeline()
T.check("ERROR" not in c.text and (local(knife).GetNumberOfPoints() > 0) == (rank == 0),
        "rank %d: a new pipeline right after: the image on rank 0 (%d points here), no error%s"
        % (rank, local(knife).GetNumberOfPoints(), "" if "ERROR" not in c.text else
           ": " + c.text[:600]))
if rank == 0:
    T.check(same(record("knife", local(knife))["knife:intensity"], one["knife:intensity"]),
            "rank 0: that image is one process's bit for bit")
T.finish()
