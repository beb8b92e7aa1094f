# SPDX-License-Identifier: BSD-3-Clause
"""An abort within a single pass ends the work and keeps the image the filter had.

Run: pvpython test_abort_pass.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so

A 64^2 image of a Gaussian sphere is traced (1 pass); then the view turns and the film grows to
512^2, RK4, still 1 pass (one long pass). A progress observer sets AbortExecute once about a
quarter of the pass is traced. Asserted, whatever the machine's load: the update returns with the trace
unfinished (the warning says how far it got: well below 100 %), the output is the image of before
(64^2, its intensity bit for bit, its `passes` 1) and not an empty one, the warning says so, and the
next update (no abort) traces the new view afresh (512^2, 1 pass) when the filter is updated again. The time the abort took is
printed, not asserted.
"""
import os
import re
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_abort_pass")

scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[96] * 3, Amplitude=1e-3, Width=0.25)
image = SchlierenImage(Input=scene, Resolution=[64, 64], Passes=1, Backend="CPU", CutoffScale=500.0)
before = st.image_arrays(sm.Fetch(image))
algo = image.GetClientSideObject()
requested = []


def on_progress(caller, event):
    if not requested and caller.GetProgress() > 0.3:  # a quarter of the pass traced
        requested.append(time.perf_counter())
        caller.SetAbortExecute(1)


image.ViewDirection = [0.2, 0.1, -1.0]
image.Resolution = [512, 512]
image.Integrator = "RK4"
tag = algo.AddObserver("ProgressEvent", on_progress)
with st.CapturedOutput() as out:
    image.UpdatePipeline()
returned = time.perf_counter()
algo.RemoveObserver(tag)
kept = algo.GetOutputDataObject(0)
dims = kept.GetDimensions()
m = re.search(r"aborted at (\d+) % of the trace", out.text)
T.check(len(requested) == 1 and m is not None and int(m.group(1)) < 60,
        "the abort ended the single pass early (%s %% of the trace done)" % (m.group(1) if m else "?"))
if requested:
    print("time: the abort returned %.3f s after the request (load %.2f)"
          % (returned - requested[0], os.getloadavg()[0]))
after = st.image_arrays(kept) if kept.GetNumberOfPoints() else None
T.check(after is not None and tuple(dims[:2]) == (64, 64) and np.array_equal(after[2], before[2])
        and after[4]["passes"] == 1,
        "the image of before is kept (%s, its intensity bit for bit, 1 pass)" % (dims,))
T.check("previous one" in out.text, "the warning says the image shown is the previous one")
with st.CapturedOutput() as out2:
    # the filter's own update: the server manager sees no property changed (the GUI's Apply is
    # offered again by the plugin, a camera move changes the view)
    algo.Update()
again = algo.GetOutputDataObject(0)
fresh = st.image_arrays(again)
T.check(tuple(again.GetDimensions()[:2]) == (512, 512) and fresh[4]["passes"] == 1
        and fresh[4]["passes_traced"] == 1 and "aborted" not in out2.text,
        "the next update traces the new view afresh (%s, %d pass)" % (again.GetDimensions(), fresh[4]["passes"]))
T.finish()
