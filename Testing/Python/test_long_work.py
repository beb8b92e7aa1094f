# SPDX-License-Identifier: BSD-3-Clause
"""Long work says how long it will take and stops on abort.

Run: pvpython test_long_work.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so

Passes = 100000 on a 16 x 16 film of a 16^3 Gaussian sphere (Backend CPU: tens of seconds). A
ProgressEvent observer reads the progress text and, half a second after the first estimate,
sets AbortExecute. Asserted (whatever the machine's load, which slows the estimate and the work
alike): the text gives an estimate ("... % traced, about N s left") once some tracing is done;
the update returns after the abort with an empty output and the error "aborted", and it ran for
less than a fifth of the time the estimate said the whole would take. The abort's latency is
printed, not asserted (docs/PERFORMANCE.md).
"""
import os
import re
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: F401,F403

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_long_work")

scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[16] * 3)
image = SchlierenImage(Input=scene, Resolution=[16, 16], Passes=100000, Backend="CPU")
algo = image.GetClientSideObject()
state = dict(start=None, first=None, estimate=None, abort_at=None, texts=0)


def on_progress(obj, event):
    now = time.time() - state["start"]
    text = obj.GetProgressText() or ""
    m = re.search(r"(\d+) % traced, about ([0-9.]+) s left", text)
    if m:
        state["texts"] += 1
        if state["first"] is None:
            state["first"] = now
            state["estimate"] = now + float(m.group(2))
            state["text"] = text
    if state["first"] is not None and now > state["first"] + 0.5 and state["abort_at"] is None:
        state["abort_at"] = now
        obj.SetAbortExecute(1)


algo.AddObserver("ProgressEvent", on_progress)
state["start"] = time.time()
with st.CapturedOutput() as out:
    image.UpdatePipeline()
elapsed = time.time() - state["start"]
data = algo.GetOutputDataObject(0)
T.check(state["estimate"] is not None,
        "the progress text gives a time estimate once tracing is under way (%r)" % state.get("text"))
T.check(state["abort_at"] is not None and data.GetNumberOfPoints() == 0 and "aborted" in out.text,
        "the abort stops the trace: an empty output and the error 'aborted'")
if state["estimate"] and state["abort_at"] is not None:
    T.check(elapsed < 0.2 * state["estimate"],
            "it stopped well before the whole would have finished: %.2f s of an estimated %.1f s"
            % (elapsed, state["estimate"]))
    print("test_long_work: first estimate at %.2f s (%s), abort at %.2f s, returned at %.2f s "
          "(latency %.3f s)" % (state["first"], state.get("text"), state["abort_at"], elapsed,
                                elapsed - state["abort_at"]))
sys.exit(T.finish())
