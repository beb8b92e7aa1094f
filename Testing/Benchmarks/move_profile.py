# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark (not a test): what a camera move costs through the pipeline, split into the update
(SchlierenImage's RequestData: pilot, ray set-up, tracing, splatting, finalize, the image arrays)
and the Fetch that brings the image to the client, at the panel's default integrator and at Auto.

    pvpython move_profile.py --plugin Schlieren.so [--size 256] [--film 512] [--moves 4]
        [--backend OpenCL|CPU] [--tolerance 3e-8]

Prints one row per setting: the first update (volume packing and, for Auto, the pilot), the mean
camera move (update, Fetch), samples per ray and the whole update's samples per second. Run it
under `perf record -e cpu-clock -g` for where the time goes inside an update; with
`perf record -D -1 --control fifo:CTL,ACK` and PERF_CTL=CTL PERF_ACK=ACK in the environment the
profile holds the camera moves only (perf is enabled around them).
"""
import argparse
import os
import time

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--size", type=int, default=256)
ap.add_argument("--film", type=int, default=512)
ap.add_argument("--moves", type=int, default=4)
ap.add_argument("--backend", default="OpenCL")
ap.add_argument("--tolerance", type=float, default=3e-8)
ap.add_argument("--only", default="", help="settings to run, comma-separated: euler, euler16, "
                "euler03, euler10, euler16cubic, auto (default: all)")
args = ap.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())

scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[args.size] * 3, Amplitude=2e-4, Width=0.25)
index = RefractiveIndex(Input=scene, Model="Passthrough")
index.UpdatePipeline()
settings = [("euler", "Euler 0.5 voxel, trilinear", dict(Integrator="Euler", StepSize=0.5)),
            ("euler16", "Euler 16 voxel, trilinear", dict(Integrator="Euler", StepSize=16.0)),
            # issue 24's per-ray overhead: the rate at 16 samples per ray against 500 (256^3)
            ("euler03", "Euler 0.3 voxel, trilinear", dict(Integrator="Euler", StepSize=0.3)),
            ("euler10", "Euler 10 voxel, trilinear", dict(Integrator="Euler", StepSize=10.0)),
            ("euler16cubic", "Euler 16 voxel, Cubic", dict(Integrator="Euler", StepSize=16.0,
                                                           Reconstruction="Cubic")),
            ("auto", "Auto + Cubic, %g rad" % args.tolerance,
             dict(Integrator="Auto", Reconstruction="Cubic", Tolerance=args.tolerance))]
# views off the axis, as a drag gives them (each differs from the last: a move, not a rest)
views = [[np.cos(a), 0.3 * np.sin(3 * a), np.sin(a)] for a in np.linspace(0.3, 2.8, args.moves)]


def perf(command):
    """Enables or disables a `perf record --control` session (PERF_CTL, PERF_ACK fifos)."""
    if os.environ.get("PERF_CTL"):
        with open(os.environ["PERF_CTL"], "w") as ctl:
            ctl.write(command + "\n")
        with open(os.environ["PERF_ACK"]) as ack:
            ack.readline()


def number(data, name):
    a = data.GetFieldData().GetArray(name)
    return a.GetValue(0) if a is not None else float("nan")


print("| %d^3 Gaussian, %d^2 film, 1 pass, %s | first update s | move: update s | move: Fetch s "
      "| move: CPU s (all threads) | samples/ray | M samples/s (update) | M samples/s (update + Fetch) "
      "| M samples per CPU s | choice |" % (args.size, args.film, args.backend))
print("|---|---|---|---|---|---|---|---|---|---|")
for key, name, kw in settings:
    if args.only and key not in args.only.split(","):
        continue
    image = SchlierenImage(Input=index, Resolution=[args.film] * 2, Passes=1, Backend=args.backend,
                           Cutoff="KnifeEdge", CutoffScale=1000.0, ViewDirection=[0, 0, -1],
                           ViewUp=[0, 1, 0], **kw)
    t0 = time.perf_counter()
    image.UpdatePipeline()
    first = time.perf_counter() - t0
    sm.Fetch(image)
    up, fe, cpu, spr, upRate, rate, cpuRate = [], [], [], [], [], [], []
    choice = ""
    perf("enable")
    for v in views:
        image.ViewDirection = list(v)
        c0 = time.process_time()  # this process's CPU time, every thread (PoCL's too)
        t0 = time.perf_counter()
        image.UpdatePipeline()
        t1 = time.perf_counter()
        data = sm.Fetch(image)
        t2 = time.perf_counter()
        c2 = time.process_time()
        up.append(t1 - t0)
        fe.append(t2 - t1)
        cpu.append(c2 - c0)
        spr.append(number(data, "samples_per_ray"))
        upRate.append(number(data, "samples") / (t1 - t0) / 1e6)
        rate.append(number(data, "samples") / (t2 - t0) / 1e6)
        cpuRate.append(number(data, "samples") / (c2 - c0) / 1e6)
        r = data.GetFieldData().GetAbstractArray("auto_report")
        choice = r.GetValue(0)[:60] if r is not None else name
    perf("disable")
    print("| %s | %.2f | %.3f | %.3f | %.3f | %.1f | %.1f | %.1f | %.1f | %s |" % (
        name, first, np.mean(up), np.mean(fe), np.mean(cpu), np.mean(spr), np.mean(upRate),
        np.mean(rate), np.mean(cpuRate), choice))
    Delete(image)
