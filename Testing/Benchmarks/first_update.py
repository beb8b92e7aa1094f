# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark (not a test): issue 24's first update, each in a fresh process, as a user meets it
after Apply. The scene and RefractiveIndex are updated first (not timed); the time is
SchlierenImage's first UpdatePipeline (the volume's packing, Cubic's smoothness levels, the
upload, Auto's pilot and one pass on a 512^2 film), on a Gaussian sphere A = 2e-4, s = 0.25.

    pvpython first_update.py --plugin Schlieren.so [--size 512] [--runs 8] [--film 512]
        [--setting autocubic|auto|default] [--tolerance 3e-8] [--backend OpenCL|CPU]

Prints one row per run (first update s, the process's peak memory, the sum of |deflection| over
the image: the same in every run) and the median. Runs are interleaved with nothing else: on this
VM the first touch of memory that the guest never backed before costs several times a warm page
(docs/PERFORMANCE.md), so a run right after boot is slower than the same run later.
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import time

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--size", type=int, default=512)
ap.add_argument("--film", type=int, default=512)
ap.add_argument("--runs", type=int, default=8)
ap.add_argument("--setting", default="autocubic", choices=["autocubic", "auto", "default"])
ap.add_argument("--tolerance", type=float, default=3e-8)
ap.add_argument("--backend", default="OpenCL")
ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
args = ap.parse_args()

if args.child:
    import numpy as np
    from paraview.simple import *  # noqa: F401,F403
    from paraview import servermanager as sm
    from vtkmodules.util.numpy_support import vtk_to_numpy

    LoadPlugin(args.plugin, remote=False, ns=globals())
    scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[args.size] * 3, Amplitude=2e-4, Width=0.25)
    index = RefractiveIndex(Input=scene, Model="Passthrough")
    index.UpdatePipeline()
    kw = {"autocubic": dict(Integrator="Auto", Reconstruction="Cubic", Tolerance=args.tolerance),
          "auto": dict(Integrator="Auto", Tolerance=0.0),
          "default": dict(Integrator="Euler", StepSize=0.5)}[args.setting]
    image = SchlierenImage(Input=index, Resolution=[args.film] * 2, Passes=1, Backend=args.backend,
                           Cutoff="KnifeEdge", ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], **kw)
    t0 = time.perf_counter()
    image.UpdatePipeline()
    seconds = time.perf_counter() - t0
    data = sm.Fetch(image)
    d = vtk_to_numpy(data.GetPointData().GetArray("deflection"))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20
    print("RESULT %.3f %.2f %.9e" % (seconds, peak, float(np.abs(d).sum())))
    sys.exit(0)

pvpython = sys.executable if "pvpython" in os.path.basename(sys.executable) else "pvpython"
print("| run | first update s, %d^3, %s, %s | peak memory GiB | sum of |deflection| |"
      % (args.size, args.setting, args.backend))
print("|---|---|---|---|")
times = []
for run in range(args.runs):
    out = subprocess.run([pvpython, os.path.abspath(__file__), "--child", "--plugin", args.plugin,
                          "--size", str(args.size), "--film", str(args.film), "--setting", args.setting,
                          "--tolerance", str(args.tolerance), "--backend", args.backend],
                         capture_output=True, text=True)
    line = [s for s in out.stdout.splitlines() if s.startswith("RESULT")]
    if not line:
        sys.exit("run %d failed:\n%s\n%s" % (run, out.stdout, out.stderr))
    seconds, peak, total = line[0].split()[1:]
    times.append(float(seconds))
    print("| %d | %s | %s | %s |" % (run + 1, seconds, peak, total), flush=True)
print("| median | %.2f | | |" % statistics.median(times))
