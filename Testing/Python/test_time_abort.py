# SPDX-License-Identifier: BSD-3-Clause
"""Time series and abort, in pvpython.

1. RefractiveScene's BlastWave is a ParaView time series: it offers TimeSteps times, and the
   schlieren image of each time shows the shock where the Sedov-Taylor law puts it,
   R = Radius t^(2/5): the ring of largest deflection is measured on the film and compared.
2. Abort: a long trace (40 passes, about 20 s uninterrupted on 2 idle cores) is aborted from a
   progress observer; the filter must return well before the trace would have ended: sooner than a
   quarter of 40 times the time of one uninterrupted pass of the same trace, measured in the same run
   (a ratio, so a loaded machine slows both sides). The latency itself is printed, not asserted (the
   engine checks between chunks of about 8 M samples).
3. Progressive refinement: raising Passes traces only the new passes.
"""
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_time_abort")

# 1. time series
R0, W = 0.6, 0.01
scene = RefractiveScene(Scene="BlastWave", Dimensions=[96, 96, 96], Bounds=[-1, 1] * 3, Radius=R0,
                        Width=W, Time=1.0, TimeSteps=5)
scene.UpdatePipelineInformation()
times = list(scene.TimestepValues)
T.close(times, [0.2, 0.4, 0.6, 0.8, 1.0], 1e-12, "BlastWave offers 5 time steps up to Time")
image = SchlierenImage(Input=scene, Resolution=[160, 160], Passes=1, Jitter=0, Cutoff="KnifeEdge",
                       CutoffScale=1000.0, Backend="CPU")
radii = []
for t in (0.2, 0.6, 1.0):
    image.UpdatePipeline(t)
    X, Y, I, D, F = st.image_arrays(sm.Fetch(image))
    rho = np.hypot(X, Y)
    mag = np.hypot(D[..., 0], D[..., 1])
    # the ring of largest deflection: the radius of the brightest bins of |eps| against rho
    bins = np.linspace(0, 1, 101)
    idx = np.digitize(rho.ravel(), bins)
    prof = np.array([mag.ravel()[idx == i].mean() if np.any(idx == i) else 0 for i in range(1, 101)])
    ring = 0.5 * (bins[np.argmax(prof)] + bins[np.argmax(prof) + 1])
    expected = R0 * t ** 0.4
    radii.append(ring)
    # the sharpest bending is where the ray grazes the shell, just inside the front: within 3
    # voxels (0.0625) of R(t)
    T.check(abs(ring - expected) < 0.0625,
            "t = %.1f: the shock ring at rho = %.3f, Sedov-Taylor R = Radius t^(2/5) = %.3f" % (t, ring, expected))
T.check(radii[0] < radii[1] < radii[2], "the blast grows with time (%s)" % radii)

# 2. abort within a second
big = RefractiveScene(Scene="GaussianSphere", Dimensions=[160, 160, 160], Amplitude=1e-4, Width=0.25)
long_trace = SchlierenImage(Input=big, Resolution=[512, 512], Passes=40, Backend="CPU",
                            CutoffScale=1000.0)
vtk_filter = long_trace.GetClientSideObject()
requested = []


def on_progress(caller, event):
    if not requested and caller.GetProgress() > 0.0:
        requested.append(time.perf_counter())
        caller.SetAbortExecute(1)


big.UpdatePipeline()  # the scene itself is not what is timed
# one uninterrupted pass of the same trace: the yardstick of "well before it would have ended"
one_pass = SchlierenImage(Input=big, Resolution=[512, 512], Passes=1, Backend="CPU", CutoffScale=1000.0)
one_pass.UpdatePipeline()  # the volume packed once, as for the long trace
one_pass.ViewDirection = [0.0, 0.1, -1.0]  # a new view: the pass traced again, the volume kept
t_one = time.perf_counter()
one_pass.UpdatePipeline()
seconds_per_pass = time.perf_counter() - t_one
Delete(one_pass)
tag = vtk_filter.AddObserver("ProgressEvent", on_progress)
with st.CapturedOutput() as out:
    long_trace.UpdatePipeline()
stopped = time.perf_counter()
vtk_filter.RemoveObserver(tag)
T.check(len(requested) == 1, "the trace reported progress")
if requested:
    latency = stopped - requested[0]
    whole = 40 * seconds_per_pass
    print("time: the abort returned %.3f s after the request; one pass %.3f s, the whole trace ~%.1f s "
          "(load %.2f)" % (latency, seconds_per_pass, whole, os.getloadavg()[0]))
    T.check(latency < 0.25 * whole,
            "the abort ended the trace well before it would have (%.3f s < a quarter of ~%.1f s)"
            % (latency, whole))
T.check("aborted" in out.text, "the abort is reported")

# 3. Progressive refinement: raising Passes traces only the new passes, and the image equals a
# trace of all of them at once (the jitter sequence continues), bit for bit.
small = RefractiveScene(Scene="GaussianSphere", Dimensions=[48, 48, 48], Amplitude=1e-4, Width=0.25)
grow = SchlierenImage(Input=small, Resolution=[64, 64], Passes=3, Cutoff="Shadowgraph", FilmDistance=5.0,
                      Backend="CPU")
first = st.image_arrays(sm.Fetch(grow))
grow.Passes = 7
X, Y, I7, D7, F7 = st.image_arrays(sm.Fetch(grow))
once = SchlierenImage(Input=small, Resolution=[64, 64], Passes=7, Cutoff="Shadowgraph", FilmDistance=5.0,
                      Backend="CPU")
X, Y, Io, Do, Fo = st.image_arrays(sm.Fetch(once))
T.check(first[4]["passes_traced"] == 3 and F7["passes_traced"] == 4 and F7["passes"] == 7,
        "Passes 3 -> 7 traced the 4 new passes only (%d, then %d of %d)"
        % (first[4]["passes_traced"], F7["passes_traced"], F7["passes"]))
T.check(np.array_equal(I7, Io) and np.array_equal(D7, Do),
        "3 passes then 4 more give the image of 7 at once, bit for bit")
grow.FilmDistance = 4.0
F = st.image_arrays(sm.Fetch(grow))[4]
T.check(F["passes_traced"] == 7, "another photon setting (FilmDistance) traces all passes again")
T.finish()
