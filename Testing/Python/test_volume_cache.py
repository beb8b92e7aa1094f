# SPDX-License-Identifier: BSD-3-Clause
"""SchlierenImage keeps its packed volume (and the engine its device copy) while only the view,
the optics or the passes change, and rebuilds it when the input changes.

Run: pvpython test_volume_cache.py --plugin <Schlieren.so>

Checked against a fresh filter (no cache) on the same input and camera: equal images, bit for bit,
after a camera move; after the scene's amplitude doubles, the deflection doubles (A enters the
closed form linearly: eps = -(2 sqrt(pi) A / s) (x, y) exp(-rho^2/s^2)). The time per camera move
is printed (not asserted: timings belong in benchmarks).
"""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_volume_cache")

A = 1e-4
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[96, 96, 96], Amplitude=A, Width=0.25)
index = RefractiveIndex(Input=scene, Model="Passthrough")
octree = RefractionOctree(Input=index)
common = dict(Cutoff="KnifeEdge", CutoffScale=st.KNIFE_SCALE, Resolution=[64, 64], Passes=2)
image = SchlierenImage(Input=octree, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], **common)


def deflection(proxy):
    _, _, _, D, _ = st.image_arrays(sm.Fetch(proxy))
    return np.array(D, dtype=np.float64)


t0 = time.perf_counter()
first = deflection(image)
t_first = time.perf_counter() - t0

# camera moves: the kept volume against a new filter that builds everything
times = []
for view in ([1, 0.2, -1], [0.3, -1, -0.4], [0, 0, -1]):
    image.ViewDirection = view
    t0 = time.perf_counter()
    kept = deflection(image)
    times.append(time.perf_counter() - t0)
    fresh_filter = SchlierenImage(Input=octree, ViewDirection=view, ViewUp=[0, 1, 0], **common)
    fresh = deflection(fresh_filter)
    Delete(fresh_filter)
    T.check(np.array_equal(kept, fresh),
            "view %s: the kept volume gives the fresh filter's image bit for bit" % (view,))
T.check(np.array_equal(kept, first), "back to the first view: the first image again")

# the input changes: the volume is rebuilt (twice the amplitude, twice the deflection)
scene.Amplitude = 2 * A
doubled = deflection(image)
ratio = np.abs(doubled).sum() / np.abs(first).sum()
T.close(ratio, 2.0, 0.01, "input changed (A doubled): the deflection doubled (ratio %.4f)" % ratio)

print("time: first trace %.3f s (build, pack, octree, upload, trace); camera moves %s s"
      % (t_first, ", ".join("%.3f" % t for t in times)))
sys.exit(T.finish())
