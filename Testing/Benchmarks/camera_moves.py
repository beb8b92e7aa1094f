# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark (not a test): the time SchlierenImage takes per camera move, as an interactive view
re-traces, against a filter that builds the volume from scratch for every view (what every update
cost before the volume was kept between traces).

    pvpython camera_moves.py --plugin Schlieren.so [--size 256] [--film 256] [--passes 1]
        [--backend OpenCL|CPU] [--moves 5]

Prints a table: setting, seconds per update (mean over the moves), and the largest difference
between the two images of each view (they must be equal: the same photons from the same volume).
"""
import argparse
import time

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--size", type=int, default=256)
ap.add_argument("--film", type=int, default=256)
ap.add_argument("--passes", type=int, default=1)
ap.add_argument("--backend", default="OpenCL")
ap.add_argument("--moves", type=int, default=5)
args = ap.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())

scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[args.size] * 3, Amplitude=1e-4, Width=0.25)
index = RefractiveIndex(Input=scene, Model="Passthrough")
octree = RefractionOctree(Input=index)
octree.UpdatePipeline()
common = dict(Cutoff="KnifeEdge", CutoffScale=1000.0, Resolution=[args.film] * 2, Passes=args.passes,
              Backend=args.backend, ViewUp=[0, 1, 0])
views = [[np.cos(a), 0.3 * np.sin(3 * a), np.sin(a)] for a in np.linspace(0.3, 2.8, args.moves)]


def trace(proxy):
    t0 = time.perf_counter()
    proxy.UpdatePipeline()
    dt = time.perf_counter() - t0
    data = sm.Fetch(proxy)
    return dt, vtk_to_numpy(data.GetPointData().GetArray("deflection")).astype(np.float64)


kept = SchlierenImage(Input=octree, ViewDirection=[0, 0, -1], **common)
trace(kept)  # the first trace builds and uploads
t_kept, t_fresh, worst = [], [], 0.0
for v in views:
    kept.ViewDirection = list(v)
    dt, dk = trace(kept)
    t_kept.append(dt)
    fresh = SchlierenImage(Input=octree, ViewDirection=list(v), **common)
    dt, df = trace(fresh)
    t_fresh.append(dt)
    worst = max(worst, float(np.abs(dk - df).max()))
    Delete(fresh)
    # a deleted filter frees the engine's kept copy (one volume at a time): re-prime the view's
    kept.ViewDirection = [0, 0, -1]
    trace(kept)

print("| %d^3 Gaussian, %d^2 film, %d pass(es), %s | s per camera move |" % (args.size, args.film, args.passes, args.backend))
print("|---|---|")
print("| volume built for every view (gather, pack, octree, upload, trace) | %.3f |" % np.mean(t_fresh))
print("| volume kept between views (trace only) | %.3f |" % np.mean(t_kept))
print("\nspeed-up %.1fx; largest difference between the two images of a view: %g rad"
      % (np.mean(t_fresh) / np.mean(t_kept), worst))
