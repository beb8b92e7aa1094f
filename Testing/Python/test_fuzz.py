# SPDX-License-Identifier: BSD-3-Clause
"""Hostile input, seeded and bounded: no volume, size or setting may crash ParaView, hang it, or
draw a picture that no photon reached without a warning.

Run: python3 test_fuzz.py --pvpython <pvpython> --plugin <Schlieren.so> [--cases 300] [--seed 16]

Every case runs in a pvpython child (fuzz_worker.py) under a memory limit (RLIMIT_AS, 4 GiB) and
a time limit. The cases of the issue that filed this test (allocations sized by a property, the
spacing that ran one ray for 303 s, origins far from 0, extreme anisotropy, FilmDistance inf and
1e7, out-of-range settings, misleading messages) are fixed cases; the dangerous ones (allocation,
hang) each get a child of their own, the others share children with the random cases (40 a
child). Each case is classified as image, warned image or clear error; the test fails on a crash
(the child died of a signal), a hang (the time limit), an empty output without an error, an image
that no photon reached without a warning, non-finite output, or (fixed cases) an outcome or
message other than the one expected. A summary table is printed.

The second round's cases are fixed cases too: Threads 1000 and 4096 (an image: the 4 GiB limit
holds fewer thread stacks), -5 and 100000 (errors naming Threads and its range), BodyRadius < 0,
a 3D volume under Symmetry Planar and Axisymmetric (errors naming what was expected), two
overlapping closed shells on Body (an image), a body over the whole beam (warned: it blocked the
rays). The random part also draws Threads (in range and out), DeviceName, Reconstruction, closed
spheres on RefractiveIndex's Body (overlapping or not) and Symmetry with its axis, Span and
SamplingDimensions; SolidArray masks (a ball, all, none) and grid holes for BodyFromGrid,
BlastWave's time steps (at, between, before and after them) and repeated updates of one pipeline
with changed properties; five fixed cases cover them too. The MPI part is python.fuzz_mpi
(fuzz_mpi.py).

The random cases are sized to at most about 2e8 ray samples (a second or two): long but
legitimate traces are the benchmark's business; abort is tested by test_time_abort.py.
"""
import json
import math
import os
import random
import resource
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def argument(name, default=None):
    for i, a in enumerate(sys.argv):
        if a == name and i + 1 < len(sys.argv):
            return sys.argv[i + 1]
        if a.startswith(name + "="):
            return a[len(name) + 1:]
    return default


PVPYTHON = argument("--pvpython", "pvpython")
PLUGIN = argument("--plugin", os.environ.get("SCHLIEREN_PLUGIN"))
NCASES = int(argument("--cases", "300"))
SEED = int(argument("--seed", "16"))
MEMORY = 4 << 30          # RLIMIT_AS of every child
BATCH = 40                # random cases per child
BATCH_SECONDS = 120       # time limit of a child of BATCH cases
SOLO_SECONDS = 60         # time limit of a child of one case

GAUSS = dict(kind="image", dims=[24, 24, 24], spacing=[2 / 23.0] * 3, origin=[-1, -1, -1],
             field="gauss", amp=1e-4)


def img(**kw):
    return dict(dict(Resolution=[32, 32], Backend="CPU"), **kw)


def error_naming(*phrases, **more):
    return dict(outcome=["error"], phrases=list(phrases), **more)


def fixed_cases():
    """The cases listed in the issue, with what each must give."""
    c = []

    def add(name, case, expect=None, solo=False):
        case = dict(case, id="fixed:" + name, group="fixed", solo=solo)
        if expect:
            case["expect"] = expect
        c.append(case)

    # allocations a property sizes: a clear error before the allocation (each in its own child)
    add("AutomaticDimension 4096 on an unstructured grid",
        dict(source=dict(kind="unstructured"),
             index=dict(Model="GladstoneDale", InputArray=["POINTS", "RTData"], AutomaticDimension=4096)),
        error_naming("4096 x 4096 x 4096", "needs", "available", "AutomaticDimension"), solo=True)
    add("RefractiveScene 2000^3",
        dict(source=dict(kind="scene", properties=dict(Dimensions=[2000] * 3))),
        error_naming("2000 x 2000 x 2000", "needs", "available", "Dimensions"), solo=True)
    add("trace of 1000^3",
        dict(source=dict(kind="scene", properties=dict(Dimensions=[1000] * 3)), image=img()),
        error_naming("1000 x 1000 x 1000", "needs", "available"), solo=True)
    add("trace of 400^3 with 1 GB left (the packed field refused)",
        dict(source=dict(kind="scene", properties=dict(Dimensions=[400] * 3)), image=img(),
             env=dict(SCHLIEREN_MEMORY_LIMIT="1000000000")),
        error_naming("Tracing the 400 x 400 x 400 volume", "needs", "available", "Resample"), solo=True)
    add("film 8000^2",
        dict(source=GAUSS, image=img(Resolution=[8000, 8000])),
        error_naming("8000 x 8000 pixels", "needs", "available", "Lower Resolution"), solo=True)
    add("film 16384^2",
        dict(source=GAUSS, image=img(Resolution=[16384, 16384])),
        error_naming("16384 x 16384 pixels", "needs", "available", "Lower Resolution"), solo=True)
    add("film 16384^2 on OpenCL",
        dict(source=GAUSS, image=img(Resolution=[16384, 16384], Backend="OpenCL")),
        error_naming("16384 x 16384 pixels", "Lower Resolution"), solo=True)
    # the hang: the step below float resolution
    add("spacing (1e-40, 0.0092, 0.44)",
        dict(source=dict(kind="image", dims=[13, 35, 31], spacing=[1e-40, 0.0092, 0.44],
                         origin=[0, 0, 0], field="gauss"), image=img()),
        error_naming("float tracer"), solo=True)
    add("spacing (1e-40, 0.0092, 0.44) on OpenCL",
        dict(source=dict(kind="image", dims=[13, 35, 31], spacing=[1e-40, 0.0092, 0.44],
                         origin=[0, 0, 0], field="gauss"), image=img(Backend="OpenCL")),
        error_naming("float tracer"), solo=True)
    # far from the origin: the image of the volume at the origin
    for shift in (1e6, 1e14, 1e18):
        for backend in ("CPU", "OpenCL"):
            add("origin %g %s" % (shift, backend),
                dict(source=dict(GAUSS, origin=[shift - 1] * 3), image=img(Backend=backend)),
                dict(outcome=["image"]))
    # extreme anisotropy
    thin = dict(kind="image", dims=[24, 24, 24], spacing=[2 / 23.0, 2 / 23.0, 6e-5 / 23],
                origin=[-1, -1, -3e-5], field="gauss")
    add("spacing ratio 3e4 seen along a long axis",
        dict(source=thin, image=img(ViewDirection=[1, 0, 0], ViewUp=[0, 0, 1])),
        error_naming("StepSize", "float position"))
    # traced (no float-precision refusal); the sheet is thin along the beam, so its bending
    # (about 4e-9 rad) is below what a bench resolves and says so
    add("spacing ratio 3e4 seen along the thin axis",
        dict(source=thin, image=img()),
        dict(outcome=["warned"], phrases=["The largest deflection over the film is", "below the about 1e-07 rad"]))
    add("spacing ratio 3e4 oblique",
        dict(source=thin, image=img(ViewDirection=[1, 1, 1], ViewUp=[0, 0, 1])),
        dict(outcome=["image", "warned"]))  # the beam advances along z by many float units
    add("film pixels wider than the thin axis",
        dict(source=dict(thin, dims=[24, 24, 4], spacing=[2 / 23.0, 2 / 23.0, 2e-5 / 3],
                         origin=[-1, -1, -1e-5]),
             image=img(ViewDirection=[1, 0, 0], ViewUp=[0, 0, 1], StepSize=64)),
        dict(outcome=["warned"], phrases=["No ray entered the volume"]))
    # the film
    add("FilmDistance inf", dict(source=GAUSS, image=img(FilmDistance=float("inf"))),
        error_naming("FilmDistance", "finite"))
    add("FilmDistance inf, BOS", dict(source=GAUSS, image=img(FilmDistance=float("inf"), Cutoff="BOS")),
        error_naming("FilmDistance"))
    for cutoff in ("KnifeEdge", "Shadowgraph", "Interferometry"):
        add("FilmDistance 1e7 %s" % cutoff, dict(source=GAUSS, image=img(FilmDistance=1e7, Cutoff=cutoff)),
            error_naming("FilmDistance", "1e6 times"))
        add("FilmDistance 3e6 %s (strong field)" % cutoff,
            dict(source=dict(GAUSS, amp=1e-2), image=img(FilmDistance=3e6, Cutoff=cutoff)),
            dict(outcome=["warned"], phrases=["No photon reached the film", "FilmDistance"]))
    # out-of-range settings: errors naming the property and its range
    for prop, value, rng in (("StepSize", -1, "[0.01, 1000]"), ("StepSize", 1e4, "[0.01, 1000]"),
                             ("FilmDistance", -5, ">= 0"), ("BackgroundDistance", -1, ">= 0"),
                             ("CutoffScale", -10, "[0, 1e12]"), ("Wavelength", 0, "[100, 100000]"),
                             ("Wavelength", -500, "[100, 100000]"), ("FilterWidth", -2, "[0.01, 64]"),
                             ("Tolerance", -1, "[0, 1]")):
        add("%s %g" % (prop, value), dict(source=GAUSS, image=img(**{prop: value})),
            error_naming(prop, rng))
    add("RefractionOctree Tolerance 10",
        dict(source=GAUSS, octree=dict(Tolerance=10.0), image=img()),
        error_naming("Tolerance is 10", "[0, 1]"))
    # the special values keep working
    add("CutoffScale 0 and Tolerance 0 (automatic)",
        dict(source=GAUSS, image=img(CutoffScale=0.0, Integrator="Auto", Tolerance=0.0)),
        dict(outcome=["image", "warned"]))
    # messages that misled
    add("Ciddor without a temperature array",
        dict(source=dict(kind="scene", properties=dict(Dimensions=[16] * 3)), index=dict(Model="Ciddor")),
        error_naming("temperature", "none is chosen", "TemperatureArray", not_phrases=["'1'"]))
    add("cell-only input, InputArray CELLS",
        dict(source=dict(GAUSS, array="density", cells=True),
             index=dict(Model="GladstoneDale", InputArray=["CELLS", "density"])),
        # density 1e-4 kg/m^3 bends light by about 1e-9 rad: the weak-field warning is right
        dict(outcome=["error", "image", "warned"], not_phrases=["no point array of that name"]))
    # the second round: threads, bodies, symmetry (each child has a 4 GiB address space: 1000
    # threads' stacks do not fit, and must not abort)
    for threads in (1000, 4096):
        add("Threads %d" % threads, dict(source=GAUSS, image=img(Threads=threads)),
            dict(outcome=["image"]), solo=True)
    for threads in (100000, -5):
        add("Threads %d" % threads, dict(source=GAUSS, image=img(Threads=threads)),
            error_naming("Threads is %d" % threads, "[0, 4096]"))
    add("BodyRadius -0.1",
        dict(source=dict(kind="scene", properties=dict(Dimensions=[16] * 3, Body="Sphere",
                                                       BodyRadius=-0.1)), image=img()),
        error_naming("BodyRadius is -0.1"))
    for sym, phrase in (("Planar", "expects a 2D plane"), ("Axisymmetric", "an r-x half plane")):
        add("3D volume under Symmetry %s" % sym,
            dict(source=dict(kind="scene", properties=dict(Dimensions=[16] * 3)),
                 index=dict(Model="Passthrough", Symmetry=sym, SymmetryAxis="X", Span=1.0),
                 image=img()),
            error_naming(phrase, "a 3D volume"))
    add("two overlapping closed shells on Body",
        dict(source=dict(kind="scene", properties=dict(Dimensions=[24] * 3, Scene="GaussianSphere")),
             index=dict(Model="Passthrough"), body=[[-0.15, 0, 0, 0.4], [0.15, 0, 0, 0.4]],
             image=img()),
        dict(outcome=["image", "warned"]))
    add("a body over the whole beam",
        dict(source=dict(kind="scene", properties=dict(Dimensions=[24] * 3, Body="Sphere",
                                                       BodyRadius=2.0)), image=img()),
        dict(outcome=["warned"], phrases=["A solid body blocked"], not_phrases=["off the film"]))
    # bodies from masks and grid holes, time steps, one pipeline updated again
    add("a SolidArray mask over the whole volume",
        dict(source=dict(GAUSS, mask="all"), index=dict(Model="Passthrough", SolidArray="solid"),
             image=img()),
        dict(outcome=["warned"], phrases=["A solid body blocked"]))
    add("a SolidArray ball in the middle",
        dict(source=dict(GAUSS, mask=[0, 0, 0, 0.4]),
             index=dict(Model="Passthrough", SolidArray="solid"), image=img()),
        dict(outcome=["image", "warned"]))
    add("a grid hole enclosed in the volume, BodyFromGrid",
        dict(source=dict(GAUSS, kind="holes", box=[-0.3, 0.3] * 3),
             index=dict(Model="Passthrough", SamplingDimensions=[16, 16, 16]), image=img()),
        dict(outcome=["image", "warned"]))
    add("BlastWave at a time between its steps",
        dict(source=dict(kind="scene", properties=dict(Scene="BlastWave", Dimensions=[16] * 3,
                                                       TimeSteps=4)),
             time=0.4, image=img()),
        dict(outcome=["image", "warned"]))
    add("one pipeline updated four times with changed properties",
        dict(source=GAUSS, image=img(),
             repeat=[dict(Resolution=[16, 24]), dict(Cutoff="Shadowgraph"), dict(Passes=2)]),
        dict(outcome=["image", "warned"]))
    return c


def random_case(rng, k):
    """A random volume and settings; out-of-range values on purpose, about one case in six."""
    def pick(*choices):
        return rng.choice(choices)

    def lograng(a, b):
        return 10 ** rng.uniform(a, b)

    dims = [rng.randint(2, 24) for _ in range(3)]
    if rng.random() < 0.05:
        dims[rng.randrange(3)] = 1
    base = lograng(-3, 1)
    spacing = [base * lograng(-0.5, 0.5) for _ in range(3)]
    r = rng.random()
    if r < 0.08:
        spacing[rng.randrange(3)] *= lograng(-40, -4)
    elif r < 0.12:
        spacing[rng.randrange(3)] *= lograng(3, 12)
    origin = pick([0.0, 0.0, 0.0], [rng.uniform(-10, 10) for _ in range(3)],
                  [pick(1, -1) * lograng(0, 20) for _ in range(3)])
    src = dict(kind="image", dims=dims, spacing=spacing, origin=origin,
               field=pick(*(["gauss"] * 8 + ["noise", "uniform", "linear", "shock"] * 2 + ["nan", "negative"])),
               amp=lograng(-7, -1), seed=k)
    if rng.random() < 0.1:
        src["array"] = "density"  # not n_minus_1: SchlierenImage must say so

    view = pick([0, 0, -1], [1, 0, 0], [0, 1, 0],
                [rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)])
    up = [rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)]
    if rng.random() < 0.05:
        up = list(view)  # parallel to the beam: an error
    bad = rng.random() < 0.15
    image = dict(
        ViewDirection=view, ViewUp=up,
        Resolution=[rng.randint(2, 48), rng.randint(2, 48)],
        Passes=rng.randint(1, 3),
        StepSize=lograng(-2, 1.8),
        Integrator=pick("Euler", "Verlet", "Midpoint", "RK4", "Straight", "Auto"),
        Cutoff=pick("KnifeEdge", "Circular", "ComplementCircular", "ColorFilter", "Shadowgraph",
                    "Interferometry", "BOS"),
        KnifeAngle=rng.uniform(-180, 180),
        CutoffScale=pick(0.0, lograng(0, 5)),
        FilmDistance=pick(0.0, lograng(-2, 4), lograng(4, 8)),
        Wavelength=pick(632.8, rng.uniform(100, 1e5)),
        BackgroundDistance=pick(1.0, lograng(-2, 3)),
        Filter=pick("None", "Gaussian", "Cone"),
        FilterWidth=pick(1.0, rng.uniform(0.01, 64)),
        Tolerance=pick(0.0, lograng(-7, -2)),
        EstimateError=rng.random() < 0.2,
        KeepInvariant=rng.random() < 0.2,
        Jitter=rng.random() < 0.8,
        Seed=rng.randint(0, 1000),
        Backend=pick("CPU", "OpenCL", "Auto"))
    if bad:
        prop, value = pick(("StepSize", pick(-1.0, 0.0, 1e4, float("nan"))),
                           ("FilmDistance", pick(-5.0, float("inf"), 1e300)),
                           ("BackgroundDistance", -1.0), ("CutoffScale", -10.0),
                           ("Wavelength", pick(0.0, -500.0)), ("FilterWidth", -2.0),
                           ("Tolerance", -1.0), ("Resolution", [0, 16]), ("Passes", 0))
        image[prop] = value
    # keep the work bounded (see the module's doc): about 2e8 samples at most
    hmax = max((d - 1) * s for d, s in zip(dims, spacing)) / 2
    smin = min(spacing)
    for _ in range(40):
        across = 3.5 * hmax / (image["StepSize"] * smin) if image["StepSize"] > 0 else 0
        per_step = {"RK4": 4, "Midpoint": 2}.get(image["Integrator"], 1) * (2 if image["EstimateError"] else 1)
        work = across * per_step * image["Resolution"][0] * image["Resolution"][1] * image["Passes"]
        if image["Integrator"] == "Auto":
            work += across * 256 * 60  # the pilot: 256 rays, about 60 candidate steps per ray
        if not (work > 2e8) or not math.isfinite(work):
            break
        if image["StepSize"] < 64:
            image["StepSize"] = min(64.0, image["StepSize"] * 2)
        else:
            image["Resolution"] = [max(2, n // 2) for n in image["Resolution"]]
    # threads and device names (out of range about one in six), reconstruction
    if rng.random() < 0.3:
        image["Threads"] = pick(0, 1, 3, 64, 1000, 4096, -1, 5000)
    if rng.random() < 0.15:
        image["DeviceName"] = pick("", "no-such-device", "cpu", "pthread", "\u00e9\u00e8 ;")
    if rng.random() < 0.3:
        image["Reconstruction"] = pick("Trilinear", "Cubic", "Auto")
    case = dict(id="random:%d" % k, group="random", source=src, image=image, solo=False)
    if rng.random() < 0.25:
        case["octree"] = dict(Tolerance=pick(0.0, lograng(-8, -2)), MaxLevel=rng.randint(0, 10))
    # bodies (closed spheres, overlapping or not, a SolidArray mask, grid holes are the CFD tests')
    # and symmetry with its parameters, through RefractiveIndex
    r = rng.random()
    if r < 0.15:
        case["index"] = dict(Model="Passthrough", InputArray=["POINTS", src.get("array", "n_minus_1")])
        centre = [o + (d - 1) * sp / 2 for o, d, sp in zip(origin, dims, spacing)]
        case["body"] = [[c0 + rng.uniform(-1, 1) * hmax for c0 in centre] + [lograng(-1.5, 0.3) * hmax]
                        for _ in range(rng.randint(1, 3))]
    elif r < 0.25:
        case["index"] = dict(Model="Passthrough", InputArray=["POINTS", src.get("array", "n_minus_1")],
                             Symmetry=pick("Planar", "Axisymmetric"), SymmetryAxis=pick("X", "Y", "Z"),
                             Span=pick(1.0, lograng(-3, 2), 0.0, -1.0),
                             SamplingDimensions=pick([0, 0, 0], [16, 16, 16], [24, 8, 1]))
    elif r < 0.32:
        # a SolidArray mask: a ball (anywhere, any size), the whole volume or nothing
        src["mask"] = pick("all", "none", [rng.uniform(-1, 1) for _ in range(3)] +
                           [rng.uniform(0.05, 1.2)])
        case["index"] = dict(Model="Passthrough", InputArray=["POINTS", src.get("array", "n_minus_1")],
                             SolidArray="solid")
    elif r < 0.39:
        # grid holes: the cells in a box removed (enclosed, or reaching the boundary)
        lo = [rng.uniform(-1.2, 0.6) for _ in range(3)]
        src.update(kind="holes", box=sum(([a, a + rng.uniform(0.1, 1.0)] for a in lo), []))
        case["index"] = dict(Model="Passthrough", InputArray=["POINTS", src.get("array", "n_minus_1")],
                             BodyFromGrid=rng.random() < 0.8,
                             SamplingDimensions=pick([0, 0, 0], [16, 16, 16]))
    # time steps: BlastWave's, at a step, between, before or after them
    if rng.random() < 0.06:
        case["source"] = dict(kind="scene", properties=dict(
            Scene="BlastWave", Dimensions=[rng.randint(8, 24)] * 3, TimeSteps=rng.randint(0, 5),
            Time=pick(1.0, lograng(-1, 1))))
        case.pop("index", None)
        case.pop("body", None)
        case["time"] = pick(0.0, 0.25, 0.5, 1.0, 3.0, -1.0, 1e9)
        image["Resolution"] = [min(n, 32) for n in image["Resolution"]]
        image["StepSize"] = max(image["StepSize"], 0.5)
        image.pop("ViewDirection", None)
        image.pop("ViewUp", None)
    # the same pipeline updated again with changed properties
    if rng.random() < 0.1:
        case["repeat"] = [pick(dict(Resolution=[rng.randint(1, 32), rng.randint(1, 32)]),
                               dict(Passes=rng.randint(1, 3)),
                               dict(Cutoff=pick("KnifeEdge", "Shadowgraph", "BOS")),
                               dict(KnifeAngle=rng.uniform(-180, 180)),
                               dict(Integrator=pick("Euler", "RK4", "Straight")),
                               dict(StepSize=pick(-1.0, image["StepSize"] * 2)))
                          for _ in range(rng.randint(1, 3))]
    return case


def limits():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def run_child(cases, seconds):
    """Runs the cases in one child; returns {id: result}. A case the child died in (a signal or
    the time limit) is a FAIL-crash or FAIL-hang; the cases after it get a child of their own."""
    results = {}
    pending = list(cases)
    while pending:
        env = dict(os.environ)
        for c in pending[:1]:
            env.update(c.get("env", {}))
        # per-case environments only in solo children
        batch = pending if not any(c.get("env") for c in pending) else pending[:1]
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
            json.dump(batch, f)
            path = f.name
        start = time.time()
        status = None
        try:
            p = subprocess.run([PVPYTHON, os.path.join(HERE, "fuzz_worker.py"), "--plugin", PLUGIN,
                                "--cases", path], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               timeout=seconds, preexec_fn=limits, env=env)
            out, status = p.stdout.decode("utf-8", "replace"), p.returncode
        except subprocess.TimeoutExpired as e:
            out = (e.stdout or b"").decode("utf-8", "replace")
            status = "timeout"
        os.unlink(path)
        current = None
        for line in out.splitlines():
            if line.startswith("BEGIN "):
                current = line[6:].strip()
            elif line.startswith("RESULT "):
                r = json.loads(line[7:])
                r["seconds"] = time.time() - start
                results[r["id"]] = r
                current = None
        done = {c["id"] for c in batch if c["id"] in results}
        if current is not None and current not in results:
            tail = " | ".join(out.strip().splitlines()[-3:])[-300:]
            if status == "timeout":
                results[current] = dict(id=current, outcome="FAIL-hang",
                                        detail="no result within %d s" % seconds)
            else:
                results[current] = dict(id=current, outcome="FAIL-crash",
                                        detail="child exited with %s: %s" % (status, tail))
            done.add(current)
        elif len(done) < len(batch) and current is None:
            # died before the first case (or between cases): the first pending case carries it
            first = next(c["id"] for c in batch if c["id"] not in done)
            results[first] = dict(id=first, outcome="FAIL-crash",
                                  detail="child exited with %s before a result: %s"
                                  % (status, out.strip()[-300:]))
            done.add(first)
        pending = [c for c in pending if c["id"] not in done]
    return results


def main():
    if not PLUGIN or not os.path.exists(PLUGIN):
        print("the plugin was not found: pass --plugin")
        return 2
    rng = random.Random(SEED)
    fixed = fixed_cases()
    randoms = [random_case(rng, k) for k in range(NCASES)]
    groups = [[c] for c in fixed if c["solo"]]
    shared = [c for c in fixed if not c["solo"]] + randoms
    for i in range(0, len(shared), BATCH):
        groups.append(shared[i:i + BATCH])
    results = {}
    lock = threading.Lock()
    queue = list(groups)
    t0 = time.time()

    def worker():
        while True:
            with lock:
                if not queue:
                    return
                g = queue.pop(0)
            r = run_child(g, SOLO_SECONDS if len(g) == 1 else BATCH_SECONDS)
            with lock:
                results.update(r)

    threads = [threading.Thread(target=worker) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    seconds = time.time() - t0

    everything = fixed + randoms
    table = {}
    failures = []
    for c in everything:
        r = results.get(c["id"], dict(id=c["id"], outcome="FAIL-no-result", detail=""))
        key = (c["group"], r["outcome"])
        table[key] = table.get(key, 0) + 1
        if r["outcome"].startswith("FAIL"):
            failures.append((c, r))
    print("fuzz: %d fixed + %d random cases (seed %d) in %.0f s, children limited to %d GiB"
          % (len(fixed), len(randoms), SEED, seconds, MEMORY >> 30))
    for c in fixed:
        r = results.get(c["id"], {})
        print("  %-60s %-10s %s" % (c["id"][6:][:60], r.get("outcome", "?"), r.get("detail", "")[:150]))
    print("\n  %-8s %-28s %6s" % ("group", "outcome", "cases"))
    for (g, o), n in sorted(table.items()):
        print("  %-8s %-28s %6d" % (g, o, n))
    reasons = {}
    for c in randoms:
        r = results.get(c["id"], {})
        if r.get("outcome") in ("error", "warned"):
            words = " ".join(r.get("detail", "").replace(":", " ").split()[:3])
            key = (r["outcome"], words)
            reasons[key] = reasons.get(key, 0) + 1
    print("\n  random cases by what the message begins with:")
    for (o, w), n in sorted(reasons.items(), key=lambda kv: -kv[1]):
        print("  %-7s %-40s %5d" % (o, w, n))
    examples = {}
    for c in randoms:
        r = results.get(c["id"], {})
        o = r.get("outcome", "?")
        if o in ("error", "warned") and len(examples.setdefault(o, [])) < 4:
            examples[o].append(r.get("detail", "")[:160])
    for o, ex in examples.items():
        print("\n  random %s, e.g.:" % o)
        for e in ex:
            print("    " + e)
    if failures:
        print("\nFAILED cases:")
        for c, r in failures:
            print("  %s: %s: %s" % (c["id"], r["outcome"], r.get("detail", "")))
            print("    case: %s" % json.dumps({k: v for k, v in c.items() if k not in ("id", "group")})[:600])
        return 1
    print("\nno crash, no hang, no unwarned blank image")
    return 0


sys.exit(main())
