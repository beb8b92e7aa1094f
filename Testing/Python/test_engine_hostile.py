# SPDX-License-Identifier: BSD-3-Clause
"""Issue 48: the C interface and the Python front end as hostile users meet them.

Run: python3 test_engine_hostile.py   (Debian's Python with NumPy and ParaView's vtkmodules;
PYTHONPATH=<source>/Python and SCHLIEREN_ENGINE_LIBRARY=<build>/OpenCL/libschlieren_engine.so)

Each case is one that crashed or answered wrongly without a word before (issue 48), with what it
must give now. The crashers run in a child process each, so that a crash is a failure of its case
and not of the run. The C interface's own fuzz is engine.TestCApiFuzz (Testing/Cxx/TestCApiFuzz.c).
"""
import os
import subprocess
import sys
import threading

import numpy as np

failures = []


def check(ok, name, detail=""):
    print("%s %s%s" % ("ok  " if ok else "FAIL", name, (": " + detail) if detail else ""))
    if not ok:
        failures.append(name)


def raises(f, kinds=Exception):
    """The exception `f` raises (None if none)."""
    try:
        f()
    except kinds as e:
        return e
    return None


def child(code):
    """Runs `code` in a child Python; (return code, stdout + stderr)."""
    p = subprocess.run([sys.executable, "-c", "import numpy as np\nfrom schlieren import _engine as e\n"
                        + code], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
    return p.returncode, p.stdout.decode("utf-8", "replace")


# ---- crashers: array lengths (each in a child; a segfault before) ----
CRASHERS = {
    "gradient of 400^3 given 10 values": (
        "e.gradient([400] * 3, [1, 1, 1], np.zeros(10, np.float32))",
        ["n_minus_1 holds 10 values", "400 x 400 x 400", "64000000"]),
    "octree_levels given 10 values for 40^3": (
        "e.octree_levels([40] * 3, np.zeros(10, np.float32), 1e-6)",
        ["n_minus_1 holds 10 values", "64000"]),
    "extend_into_invalid given 10 valid flags for 40^3": (
        "e.extend_into_invalid([40] * 3, np.zeros(10, np.uint8), np.zeros(64000, np.float32))",
        ["valid holds 10 values", "64000"]),
    "numerical given 10 values for 40^3": (
        "e.numerical({}, [40] * 3, [0] * 3, [1] * 3, np.zeros(10, np.float32))",
        ["values holds 10 values", "64000"]),
    "Session.set_volume with a solid mask of 10 for 40^3": (
        "e.Session().set_volume([40] * 3, [0] * 3, [1] * 3, np.zeros(64000, np.float32), "
        "solid=np.zeros(10, np.uint8))", ["solid holds 10 values", "64000"]),
    "Session.set_volume with levels one short (heap garbage traced before)": (
        "e.Session().set_volume([40] * 3, [0] * 3, [1] * 3, np.zeros(64000, np.float32), "
        "levels=np.zeros(63999, np.uint8))", ["levels holds 63999 values", "64000"]),
    "fill_scene with negative dims (uninitialised memory as n - 1 before)": (
        "e.fill_scene({}, [-5, 4, 4], [0] * 3, [1] * 3)", ["dims", "-5", "at least 1"]),
    "Session.trace() after free() (JSONDecodeError before)": (
        "s = e.Session(); s.free(); s.trace()", ["Session.trace", "freed"]),
    "Session.film() after free() ('no image traced yet' before)": (
        "s = e.Session(); s.free(); s.film()", ["Session.film", "freed"]),
}
for name, (code, phrases) in CRASHERS.items():
    rc, out = child(code + "\n")
    last = out.strip().splitlines()[-1] if out.strip() else "(no output, rc %d)" % rc
    check(rc == 1 and ("EngineError" in last or "ArgumentError" in last) and
          all(p in last for p in phrases), "crasher: " + name, last)

from schlieren import _engine as e  # noqa: E402

# ---- the C interface from ctypes: counts, handles, names, numbers ----
e._lib.schlieren_field_index(b"Passthrough", None, -1, 0, 1.0, None, None, None)
msg = e._text(e._lib.schlieren_last_error())
check("count is -1" in msg, "field_index with count -1 says what is wrong", msg)
h = e._lib.schlieren_session_new()
e._lib.schlieren_session_free(h)
rc = e._lib.schlieren_session_trace(h)
report = e._text(e._lib.schlieren_session_report(h))
check(rc != 0 and "freed" in e._text(e._lib.schlieren_session_error(h)) and '"error"' in report,
      "C: a freed handle refused (its report is JSON with the error)", report[:120])

s = e.Session()


def refused(name, value):
    err = raises(lambda: s.set(name, value), e.EngineError)
    return str(err) if err else ""


m = refused("cutoff", "Shadowgraph")
check("closest known name: 'Cutoff'" in m, "C: a wrongly cased property names the closest", m[:90])
m = refused("Cutoff", "shadowgraph")
check("closest known name: 'Shadowgraph'" in m, "C: a wrongly cased entry names the closest", m[-80:])
m = refused("Passes", 3000000000)
check("Passes is 3000000000" in m and "-2147483648" not in m, "C: Passes 3e9 reported as given", m)
m = refused("Seed", 2 ** 32)
check("Seed is 4294967296" in m and "4294967295" in m, "C: a seed past 2^32 named with its range", m)
check(refused("Seed", 2 ** 32 - 1) == "" and s.get("Seed") == "4294967295", "C: seed 2^32 - 1 taken")
s.set("Seed", 0)
m = refused("UseOctree", 2)
check("0 or 1" in m, "C: a boolean 2 refused as the C++ plugin refuses it", m)

# KnifeAngle: the engine's range, the C++ plugin's
dims, origin, spacing = [24, 24, 24], [-1.0] * 3, [2 / 23.0] * 3
scene = e.fill_scene(dict(Scene="GaussianSphere", Amplitude=1e-4, Width=0.25), dims, origin,
                     spacing)
s.set_volume(dims, origin, spacing, scene["n_minus_1"])
for k, v in dict(Resolution=[32, 32], Passes=2, Backend="CPU").items():
    s.set(k, v)
s.set("KnifeAngle", 1e300)
err = raises(s.trace, e.EngineError)
check(err is not None and "KnifeAngle is 1e+300" in str(err) and "[-180, 180]" in str(err),
      "KnifeAngle 1e300 refused by the trace (traced before)", str(err))
s.set("KnifeAngle", 0.0)

# BodyCenter NaN: refused (the body dropped before)
err = raises(lambda: e.fill_scene(dict(Body="Sphere", BodyCenter=[float("nan"), 0, 0]), [8] * 3,
                                  [0] * 3, [1] * 3), e.EngineError)
check(err is not None and "BodyCenter" in str(err), "a BodyCenter with NaN refused", str(err))
err = raises(lambda: e.fill_scene(dict(Amplitude=100), [8] * 3, [0] * 3, [1] * 3), e.EngineError)
check(err is not None and "Amplitude is 100" in str(err) and "[-0.9, 10]" in str(err),
      "fill_scene checks RefractiveScene's ranges (the C++ filter's)", str(err))

# ---- shapes and orders: (nz, ny, nx) or refused, named ----
dims2 = [20, 16, 12]
o2, h2 = [-1.0, -0.8, -0.6], [0.1, 0.1, 0.1]
n1 = e.fill_scene(dict(Scene="GaussianSphere", Amplitude=1e-4, Width=0.3), dims2, o2, h2)["n_minus_1"]
s.set_volume(dims2, o2, h2, n1)
s.trace()
reference = s.array("intensity")
cube = n1.reshape(12, 16, 20)
err = raises(lambda: s.set_volume(dims2, o2, h2, np.ascontiguousarray(cube.transpose(2, 1, 0))),
             e.EngineError)
check(isinstance(err, ValueError) and "n_minus_1 has shape (20, 16, 12)" in str(err) and
      "(12, 16, 20)" in str(err), "an array shaped (nx, ny, nz) refused, naming the argument",
      str(err)[:140])
s.set_volume(dims2, o2, h2, np.asfortranarray(cube))
s.trace()
check(np.array_equal(s.array("intensity"), reference),
      "a Fortran-ordered (nz, ny, nx) array traced as its C-ordered copy")
err = raises(lambda: s.set_volume(dims2, o2, h2, n1.astype(np.complex64)), e.EngineError)
check(isinstance(err, TypeError) and "n_minus_1 has dtype complex64" in str(err),
      "a complex n_minus_1 refused by dtype", str(err))
err = raises(lambda: s.set_volume(dims2, o2, h2, n1.reshape(-1, 2)), e.EngineError)
check(err is not None and "n_minus_1 has shape" in str(err), "a 2D n_minus_1 refused", str(err)[:90])

# ---- two threads tracing one session: serialised, the single thread's image ----
s.set("Resolution", [96, 96])
s.set("Passes", 6)
s.set_volume(dims2, o2, h2, n1)
s.trace()
single = s.array("intensity")
worst = 0.0
for attempt in range(3):
    s.set_volume(dims2, o2, h2, n1)   # a new volume: both threads trace from the start
    results = []
    threads = [threading.Thread(target=lambda: results.append(s.trace())) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    worst = max(worst, float(np.abs(s.array("intensity") - single).max()))
check(len(results) == 2 and worst == 0.0,
      "two threads tracing one Session give the single thread's image (torn before)",
      "largest |dI| %g over 3 tries" % worst)
s.free()

# ---- the VTK front end ----
try:
    import schlieren
    from vtkmodules.vtkCommonCore import vtkOutputWindow
    from vtkmodules.vtkFiltersCore import vtkAppendFilter
    from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
except ImportError as x:
    print("skipped the VTK front end's cases: %s" % x)
else:
    vtkOutputWindow.GetInstance().SetDisplayModeToNever() if hasattr(
        vtkOutputWindow.GetInstance(), "SetDisplayModeToNever") else None
    err = raises(lambda: schlieren.RefractiveScene(Amplitude="big"), ValueError)
    check(err is not None and "Amplitude" in str(err), "RefractiveScene(Amplitude='big') names "
          "the property (a traceback without its name before)", str(err))
    scene_alg = schlieren.RefractiveScene(Dimensions=[2000] * 3)
    scene_alg.Update()
    check("2000 x 2000 x 2000" in scene_alg.LastError and "needs" in scene_alg.LastError and
          "GiB" in scene_alg.LastError, "RefractiveScene(Dimensions=[2000]*3): 'needs N GiB' "
          "before allocating (NumPy's MemoryError before)", scene_alg.LastError)
    wide = schlieren.RefractiveScene(Dimensions=[3000000000, 4, 4])
    wide.Update()
    check("3000000000" in wide.LastError and "Dimensions" in wide.LastError,
          "RefractiveScene(Dimensions=[3e9, 4, 4]) named as given", wide.LastError)
    err = raises(lambda: schlieren.SchlierenImage(cutoff="Shadowgraph"), AttributeError)
    check(err is not None and "'Cutoff'" in str(err),
          "SchlierenImage(cutoff=...) names Cutoff (silently KnifeEdge before)", str(err)[:100])
    err = raises(lambda: schlieren.SchlierenImage(Cutoff="shadowgraph"), ValueError)
    check(err is not None and "'Shadowgraph'" in str(err), "Cutoff='shadowgraph' names the "
          "closest entry", str(err)[-60:])
    flat = schlieren.RefractiveScene(Dimensions=[16, 16, 1])
    flat_image = schlieren.SchlierenImage(Resolution=[16, 16], Backend="CPU")
    flat_image.SetInputConnection(flat.GetOutputPort())
    flat_image.Update()
    check("RefractiveIndex with Symmetry Planar or Axisymmetric" in flat_image.LastError and
          "None only" not in
          flat_image.LastError, "a 2D volume: the advice sends the user to Symmetry Planar, which "
          "the Python front end's RefractiveIndex has (as the C++ plugin's)",
          flat_image.LastError[-110:])
    # a cell type the sampler does not take: an error naming it (the C++ filter's words)
    from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
    prism = vtkUnstructuredGrid()
    corners = vtkPoints()
    for z in (0.0, 1.0):
        for k in range(5):
            corners.InsertNextPoint(np.cos(2 * np.pi * k / 5), np.sin(2 * np.pi * k / 5), z)
    prism.SetPoints(corners)
    prism.InsertNextCell(15, 10, list(range(10)))  # VTK_PENTAGONAL_PRISM
    rho = vtkFloatArray()
    rho.SetName("density")
    for _ in range(10):
        rho.InsertNextValue(1.2)
    prism.GetPointData().AddArray(rho)
    prism_index = schlieren.RefractiveIndex(Model="GladstoneDale", InputArray="density",
                                            SamplingDimensions=[8, 8, 4])
    prism_index.SetInputData(prism)
    prism_index.Update()
    check("pentagonal prism" in prism_index.LastError and
          prism_index.GetOutput().GetNumberOfPoints() == 0,
          "RefractiveIndex on a pentagonal prism: the sampler's error naming the cell type, an "
          "empty output", prism_index.LastError[-160:])
    wavelet = vtkRTAnalyticSource()
    wavelet.SetWholeExtent(-5, 5, -5, 5, -5, 5)
    grid = vtkAppendFilter()   # an unstructured grid: resampled by RefractiveIndex
    grid.SetInputConnection(wavelet.GetOutputPort())
    index = schlieren.RefractiveIndex(Model="GladstoneDale", InputArray="RTData",
                                      AutomaticDimension=4096)
    index.SetInputConnection(grid.GetOutputPort())
    index.Update()
    check("4096 x 4096 x 4096" in index.LastError and "needs" in index.LastError and
          "AutomaticDimension" in index.LastError, "RefractiveIndex(AutomaticDimension=4096) on "
          "an unstructured grid: 'needs N GiB' (std::bad_alloc, abort before)", index.LastError)

# ---- the cell sampler (schlieren_sample_cells, issue 47): every array checked, by name ----
cube = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1],
                 [0, 1, 1]], float)
hexa = dict(cell_types=[12], offsets=[0, 8], connectivity=np.arange(8))
grid3 = dict(dims=[3, 3, 3], origin=[0, 0, 0], spacing=[0.5, 0.5, 0.5])
found, values = e.sample_cells(cube, point_arrays=[("x", cube[:, 0].astype(np.float32))],
                               cell_arrays=[("id", np.array([7], np.int32))], **hexa, **grid3)
xs = np.tile([0, 0.5, 1], 9).astype(np.float32)
check(found.all() and np.array_equal(values["x"], xs) and values["x"].dtype == np.float32 and
      (values["id"] == 7).all() and values["id"].dtype == np.int32,
      "sample_cells: a unit hexahedron on a 3 x 3 x 3 grid: every point found, x exact (float32 "
      "kept), the cell array's int32 value copied")
for what, kw, kinds, words in (
        ("points shaped (8, 2)", dict(points=cube[:, :2]), e.ArgumentError, ["points", "(n, 3)"]),
        ("connectivity of floats", dict(connectivity=np.arange(8.0)), e.ArgumentTypeError,
         ["connectivity", "integers"]),
        ("offsets of 3 values for 1 cell", dict(offsets=[0, 8, 8]), e.EngineError,
         ["offsets", "2"]),
        ("a point id past the mesh", dict(connectivity=[0, 1, 2, 3, 4, 5, 6, 8]), e.EngineError,
         ["connectivity[7]", "8 points"]),
        ("a polyhedron", dict(cell_types=[42]), e.EngineError, ["polyhedron", "Tetrahedralize"]),
        ("a hexahedron of 6 points", dict(offsets=[0, 6], connectivity=np.arange(6)),
         e.EngineError, ["hexahedron with 6 points"]),
        ("skip_cells of 2 bytes for 1 cell", dict(skip_cells=[0, 0]), e.EngineError,
         ["skip_cells"]),
        ("a point array of 7 tuples", dict(point_arrays=[("x", np.zeros(7))]), e.EngineError,
         ["'x'", "8 points"]),
        ("spacing 0", dict(spacing=[0.5, 0, 0.5]), e.EngineError, ["spacing"])):
    args = dict(points=cube, **hexa, **grid3)
    args.update(kw)
    err = raises(lambda: e.sample_cells(**args), Exception)
    check(isinstance(err, kinds) and all(w in str(err) for w in words),
          "sample_cells with %s: %s naming it" % (what, kinds.__name__), str(err)[:160])

# ---- its points mode (schlieren_sample_cells_at, RefractiveIndex's symmetric sampling) ----
# known answers: a linear field is interpolated exactly by every cell type; the first cell (the
# lowest id) holds a point on a shared face; a point off a face's plane or outside, or not finite,
# is in no cell
at = np.array([[0.25, 0.5, 0.75], [1.0, 1.0, 1.0], [1.5, 0.5, 0.5], [np.nan, 0.5, 0.5]])
found, values = e.sample_cells_at(cube, at, point_arrays=[("f", cube @ [1.0, 2.0, 4.0])],
                                  cell_arrays=[("id", np.array([7], np.int32))], **hexa)
check(found.tolist() == [1, 1, 0, 0] and np.allclose(values["f"][:2], [4.25, 7.0], rtol=0,
                                                     atol=1e-12) and
      values["id"].tolist() == [7, 7, 0, 0] and values["f"][2:].tolist() == [0, 0],
      "sample_cells_at: a unit hexahedron: inside and on a corner found, f = x + 2y + 4z exact; "
      "outside and NaN not found (left 0)", str((found, values)))
# a 2D mesh in the plane z = 0.3: a pixel (x 0..1), a quad (x 1..2, sheared), two triangles
# (x 2..3); g = 3x - y + 0.5 at its nodes
flat = np.array([[0, 0], [1, 0], [0, 1], [1, 1], [2, 0], [2.2, 1], [3, 0], [3, 1]], float)
nodes = np.column_stack([flat, np.full(len(flat), 0.3)])
faces = dict(cell_types=[8, 9, 5, 5], offsets=[0, 4, 8, 11, 14],
             connectivity=[0, 1, 2, 3, 1, 4, 5, 3, 4, 6, 7, 4, 7, 5])
g = nodes @ [3.0, -1.0, 0.0] + 0.5
probe = np.array([[0.3, 0.6, 0.3], [1.5, 0.4, 0.3], [2.7, 0.2, 0.3], [2.5, 0.5, 0.3],
                  [1.0, 0.5, 0.3], [0.3, 0.6, 0.3 + 1e-3], [3.5, 0.5, 0.3]])
found, values = e.sample_cells_at(nodes, probe, point_arrays=[("g", g)],
                                  cell_arrays=[("cell", np.arange(4, dtype=np.int64))], **faces)
exact = probe @ [3.0, -1.0, 0.0] + 0.5
check(found.tolist() == [1, 1, 1, 1, 1, 0, 0] and
      np.allclose(values["g"][:5], exact[:5], rtol=0, atol=1e-12) and
      values["cell"][:5].tolist() == [0, 1, 2, 2, 0],
      "sample_cells_at: a pixel, a sheared quad and two triangles in z = 0.3: g = 3x - y + 0.5 "
      "exact in each, a point on the pixel-quad edge and on the triangles' diagonal the lower "
      "cell's, 1e-3 off the plane and past the mesh not found",
      str((found.tolist(), values["g"].tolist(), values["cell"].tolist())))
for what, kw, kinds, words in (
        ("at shaped (4, 2)", dict(at=np.zeros((4, 2))), e.ArgumentError, ["at", "(n, 3)"]),
        ("a polygon", dict(cell_types=[8, 9, 7, 5]), e.EngineError, ["polygon", "Triangulate"]),
        ("an output for 3 of 7 points", dict(found=np.zeros(3, np.uint8)), e.EngineError,
         ["found", "7 points to sample"])):
    args = dict(points=nodes, at=probe, point_arrays=[("g", g)], **faces)
    args.update(kw)
    err = raises(lambda: e.sample_cells_at(**args), Exception)
    check(isinstance(err, kinds) and all(w in str(err) for w in words),
          "sample_cells_at with %s: %s naming it" % (what, kinds.__name__), str(err)[:160])

# ---- python -m schlieren: one line, exit code 2 ----
env = dict(os.environ)
for args in (["--resolution", "0"], ["--resolution", "1"], ["--resolution", "-5"],
             ["--resolution", "100000"], ["--passes", "0"],
             ["--output", "/nonexistent/folder/x.png"], ["--output", "."]):
    p = subprocess.run([sys.executable, "-m", "schlieren", "demo"] + args, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, env=env, timeout=120)
    err_text = p.stderr.decode()
    check(p.returncode == 2 and len(err_text.strip().splitlines()) == 1 and
          "Traceback" not in err_text, "python -m schlieren demo %s: exit 2, one line"
          % " ".join(args), "rc %d: %s" % (p.returncode, err_text.strip()[:150]))

# ---- RefractiveIndex's symmetry through ctypes: shapes, dtypes and lengths named ----
plan = e.symmetry_plan({"Symmetry": "Planar", "Span": 0.5, "SamplingDimensions": [4, 3, 3]},
                       [0, 1, 0, 1, 0, 0])
points, sample_of = e.symmetry_samples(plan)
check(plan["dims"] == [4, 3, 3] and points.shape == (12, 3) and sample_of.dtype == np.int64 and
      sample_of.size == 36, "symmetry_plan and symmetry_samples: 4 x 3 x 3 from 12 samples",
      str(plan["dims"]))
err = raises(lambda: e.symmetry_expand(sample_of.astype(np.int32), 12, values=np.zeros(12)),
             e.ArgumentTypeError)
check(err is not None and "int64" in str(err), "symmetry_expand: int32 sample_of refused by dtype",
      str(err))
err = raises(lambda: e.symmetry_expand(sample_of, 12, values=np.zeros(11)), e.ArgumentError)
check(err is not None and "12 samples" in str(err), "symmetry_expand: 11 values for 12 samples "
      "refused", str(err))
bad = sample_of.copy()
bad[5] = 12
err = raises(lambda: e.symmetry_expand(bad, 12, values=np.zeros(12)), e.EngineError)
check(err is not None and "sample_of[5] is 12" in str(err), "symmetry_expand: an index past the "
      "samples refused by the engine (no read past them)", str(err))
err = raises(lambda: e.symmetry_plan({"Symmetry": "Axisymmetric"}, [0, 1, 0, 1, 0, 0.1],
                                     points=np.zeros((5, 2))), e.ArgumentError)
check(err is not None and "(n, 3)" in str(err), "symmetry_plan: points of shape (5, 2) refused",
      str(err))
err = raises(lambda: e.symmetry_plan({"Symmetry": "planar"}, [0, 1, 0, 1, 0, 0]), e.EngineError)
check(err is not None and "Symmetry 'planar' is not one of: None, Planar, Axisymmetric" in str(err),
      "symmetry_plan: a wrongly cased entry names the entries", str(err))
values, valid = e.symmetry_expand(sample_of, 12, values=np.arange(24.0).reshape(12, 2),
                                  sample_valid=np.arange(12) != 3)
check(values.shape == (36, 2) and values.dtype == np.float32 and values[35, 1] == 23.0 and
      valid.sum() == 33, "symmetry_expand: 2 components a sample, onto 36 points (%d valid)"
      % valid.sum())

print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
