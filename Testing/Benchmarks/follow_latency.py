# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark (not a test): the follow-the-camera loop's latency, as the GUI's follower runs it.

    pvpython Testing/Benchmarks/follow_latency.py --plugin <Schlieren.so> [--moves 3] [--target 16]

For each case and backend, after a warm-up trace: the camera turns (ViewDirection/ViewUp set, as the
GUI's follower does on a camera change), then
  first   = the time to the first updated image (InteractivePasses = 1 pass traced),
  converged = the time from the camera change to the target-pass image, refined in the GUI's
            chunks (about 0.25 s of passes each, sized from the last measured pass time),
each the median of --moves camera moves. Cases: the NASA blunt fin (../shared/data or
$SCHLIEREN_DATA, resampled to 128 voxels along its longest side; skipped where absent) and a 256^3
Gaussian sphere, both on a 512^2 film, Euler at --step voxels (1) with the octree off. Prints a
table.
The GUI adds its renders (a few ms for a 512^2 image) and the 300 ms it waits for the camera to rest
before refining; python.gui_drag measures those in the real GUI.
"""
import argparse
import os
import statistics
import sys
import time

import numpy as np

parser = argparse.ArgumentParser()
parser.add_argument("--plugin", required=True)
parser.add_argument("--moves", type=int, default=2)
parser.add_argument("--target", type=int, default=8)
parser.add_argument("--step", type=float, default=1.0, help="Euler step, voxels")
parser.add_argument("--chunk-seconds", type=float, default=0.25)
args = parser.parse_args()

from paraview.simple import *  # noqa: E402,F401,F403

LoadPlugin(args.plugin, remote=False, ns=globals())

here = os.path.dirname(os.path.abspath(__file__))
data = os.environ.get("SCHLIEREN_DATA", os.path.join(here, "..", "..", "..", "shared", "data"))
cases = []
xyz, q = os.path.join(data, "bluntfinxyz.bin"), os.path.join(data, "bluntfinq.bin")
if os.path.exists(xyz) and os.path.exists(q):
    reader = PLOT3DReader(FileName=xyz, QFileName=[q])
    fin = RefractiveIndex(Input=reader, Model="GladstoneDale", Gas="Air", DensityReference=1.2, UseSamplingBounds=1,
                          SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7], AutomaticDimension=128, AmbientMode="Extend")
    fin.InputArray = ["POINTS", "Density"]
    fin.UpdatePipeline()
    cases.append(("blunt fin, 128 x 64 x 73", fin))
else:
    print("SKIP the blunt fin: no data in %s" % os.path.abspath(data))
sphere = RefractiveScene(Scene="GaussianSphere", Dimensions=[256] * 3, Amplitude=1e-4, Width=0.25)
sphere.UpdatePipeline()
cases.append(("Gaussian sphere, 256^3", sphere))


def camera(k):
    """The k-th camera: turned 20 degrees about y and 10 about x each move."""
    a, b = np.radians(20.0 * (k + 1)), np.radians(10.0 * (k + 1))
    d = np.array([np.sin(a) * np.cos(b), np.sin(b), -np.cos(a) * np.cos(b)])
    up = np.array([0.0, 1.0, 0.0])
    up = up - d * np.dot(up, d)
    return d.tolist(), (up / np.linalg.norm(up)).tolist()


rows = []
for name, volume in cases:
    for backend in ("OpenCL", "CPU"):
        image = SchlierenImage(Input=volume, Resolution=[512, 512], Passes=1, Integrator="Euler", StepSize=args.step,
                               UseOctree=0, Cutoff="KnifeEdge", Backend=backend)
        image.UpdatePipeline()  # the volume packed and uploaded once, as in the GUI after Apply
        firsts, converged, chunks = [], [], []
        for k in range(args.moves):
            d, up = camera(k)
            t0 = time.perf_counter()
            image.ViewDirection, image.ViewUp, image.Passes = d, up, 1
            image.UpdatePipeline()
            t1 = time.perf_counter()
            per_pass, passes, n = t1 - t0, 1, 0
            while passes < args.target:
                step = max(1, int(args.chunk_seconds / per_pass))
                new = min(args.target, passes + step)
                ta = time.perf_counter()
                image.Passes = new
                image.UpdatePipeline()
                per_pass = (time.perf_counter() - ta) / (new - passes)
                passes, n = new, n + 1
            t2 = time.perf_counter()
            firsts.append(t1 - t0)
            converged.append(t2 - t0)
            chunks.append(n)
        rows.append((name, backend, statistics.median(firsts), statistics.median(converged),
                     statistics.median(chunks)))
        Delete(image)
        print("%-26s %-7s first image %.3f s, %d passes %.2f s (%d chunks)" % (name, backend, rows[-1][2],
              args.target, rows[-1][3], rows[-1][4]))
        sys.stdout.flush()

print()
print("| case (512^2 film, Euler %g voxel) | backend | camera change -> first image (1 pass) | "
      "-> converged (%d passes) | refinement chunks |" % (args.step, args.target))
print("|---|---|---|---|---|")
for name, backend, first, conv, n in rows:
    print("| %s | %s | %.3f s | %.2f s | %d |" % (name, "OpenCL (PoCL)" if backend == "OpenCL" else backend,
                                                first, conv, n))
