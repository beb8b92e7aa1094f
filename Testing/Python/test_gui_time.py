# SPDX-License-Identifier: BSD-3-Clause
"""A time step in the GUI is traced as every other image the GUI starts: its first pass at once,
the rest in chunks up to Passes (issue 49), by real mouse events.

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_time.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

The harness of test_gui_drag.py with the built-in blast wave of 4 time steps
(SCHLIEREN_GUI_SCENE=blast; no data needed). A Schlieren Image of RK4, 32 passes is made with the
quick launch and applied; once it has its 32 passes, the VCR toolbar's Next Frame button is
clicked. Checked: the new time step's first update traced Interactive Passes (1), and chunks
brought it to 32 passes (the trace lines); the image changed with the time step.
"""
import os
import shutil
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import gui_driver  # noqa: E402

gd = gui_driver.Driver(__doc__)
args, data = gd.args, gd.data
TARGET = 32
settings = {"image": dict(Resolution=[128, 128], Passes=TARGET, Integrator="RK4", Cutoff="KnifeEdge",
                          Backend="CPU", Seed=4, InteractivePasses=1, FollowCamera=0)}
gd.launch("gui_drag_session.py", settings, env={"SCHLIEREN_GUI_SCENE": "blast"})
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
events_since, read_json, dump = gd.events_since, gd.read_json, gd.dump
xdo, screenshot = gd.xdo, gd.screenshot
events, lock = gd.events, gd.lock

ready = read_json("ready.json", timeout=120)
say("the session is ready (%s)" % ready["scene"])
window = gd.main_window()
gd.quick_launch("Schlieren Image")
t_apply = time.time()
xdo("key", "--clearmodifiers", "alt+a")
wait_for("Apply opening the schlieren view", lambda: events_since(t_apply, "opened"), 60)
wait_for("the first time step's %d passes" % TARGET, lambda: [
    e for e in events_since(t_apply, "converged") if e[2]["passes"] == str(TARGET)], 120)
time.sleep(1.0)
import numpy as np  # noqa: E402

before = np.load(dump("first-step"))
# the VCR toolbar's Next Frame (the fifth button of the Time row, left of "Time:")
shot = screenshot("gui_time_before")
t_step = time.time()
xdo("mousemove", 626, 42)
xdo("click", 1)
step = wait_for("the time step's image starting", lambda: events_since(t_step, "time"), 30)
done = wait_for("the time step's image refined to %d passes" % TARGET, lambda: [
    e for e in events_since(t_step, "converged") if e[2]["passes"] == str(TARGET)], 120)
updated = events_since(t_step, "updated")
steps = [int(e[2]["passes"]) for e in events_since(t_step, "refine")]
say("the time step: first update %s pass(es), then chunks at %s" % (
    updated[0][2]["passes"] if updated else "?", steps))
check(updated and int(updated[0][2]["passes"]) == 1 and steps and steps[-1] == TARGET,
      "the new time step traced its first pass, then chunks to %d passes" % TARGET)
time.sleep(1.0)
after = np.load(dump("next-step"))
change = np.abs(after["intensity"] - before["intensity"]).max()
check(int(after["passes"]) == TARGET and change > 0.05,
      "the image of the next time step has %d passes and differs (max |change| %.3f)" % (after["passes"], change))
shot = screenshot("gui_time_after")
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    shutil.copy(shot, args.screenshots)
finish()
