# SPDX-License-Identifier: BSD-3-Clause
"""With Follow Camera, the Passes field keeps the target the user typed while the image refines.

Run with Debian's Python under an X server with a window manager:

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_target.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

The same harness as test_gui_apply_stop.py (paraview with PV_PLUGIN_PATH, gui_drag_session.py as
its --script, xdotool for every user action). A Schlieren Image is made with the quick launch and
applied at 4 passes, Follow Camera is turned on (Ctrl+Alt+F), 64 is typed into the Properties
panel's Passes field (a click on it, Ctrl+A, the keys 6 4) and applied (Alt+A), the 3D view is
dragged and left to rest. Checked, from the plugin's trace lines (each gives the passes traced, the
Passes property and the text of the panel's Passes field):
  1. while the image refines (passes traced below 64), both the property and the field say 64;
  2. the refinement reaches 64 passes and the field still says 64; the image kept says 64 passes;
  3. the status bar said the passes done ("N of 64 passes"), seen in a screenshot (printed).
"""
import os
import shutil
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import gui_driver  # noqa: E402
from gui_driver import view_boxes  # noqa: E402

gd = gui_driver.Driver(__doc__)
args, data = gd.args, gd.data
TARGET = 64  # typed into the Passes field
# the first Apply at 4 passes; the film small enough that the refinement to 64 is a few seconds here
settings = {"image": dict(Resolution=[160, 160], Passes=4, Cutoff="KnifeEdge", CutoffScale=250.0,
                          Backend="CPU", Seed=4, InteractivePasses=1, InteractiveScale=0.5, FollowCamera=0)}
gd.launch("gui_drag_session.py", settings)
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
events_since, read_json, dump = gd.events_since, gd.read_json, gd.dump
xdo, screenshot, drag = gd.xdo, gd.screenshot, gd.drag
events, lock = gd.events, gd.lock


# -- the GUI comes up with the pipeline built
ready = read_json("ready.json", timeout=120)
say("the session is ready (%s)" % ready["scene"])
window = gd.main_window()

gd.quick_launch("Schlieren Image")
t_apply = time.time()
xdo("key", "--clearmodifiers", "alt+a")
wait_for("Apply (Alt+A) opening the schlieren view", lambda: events_since(t_apply, "opened"), 60)
time.sleep(1.0)
t_follow = time.time()
xdo("key", "--clearmodifiers", "ctrl+alt+f")
wait_for("Follow Camera (Ctrl+Alt+F)", lambda: events_since(t_follow, "follow"), 30)
time.sleep(1.5)
with lock:
    at = [e[2].get("field_at") for e in events if e[2].get("field_at", "-1,-1") != "-1,-1"]
if not at:
    fatal("the plugin never saw the Passes field on the screen")
fx, fy = map(int, at[-1].split(","))
say("the Passes field is at (%d, %d) on the screen" % (fx, fy))

# the user types the target into the field and applies it
xdo("mousemove", fx, fy)
time.sleep(0.2)
xdo("click", 1)
time.sleep(0.3)
xdo("key", "--clearmodifiers", "ctrl+a")
xdo("type", "--delay", "120", str(TARGET))
time.sleep(0.5)
t_typed = time.time()
xdo("key", "--clearmodifiers", "alt+a")
wait_for("a refinement towards the typed %d passes" % TARGET,
         lambda: [e for e in events_since(t_typed, "refine") if e[2].get("target") == str(TARGET)], 60)

# a drag of the 3D view, then the rest: the refinement starts again from 1 pass
boxes = view_boxes(screenshot("views"))
if len(boxes) < 2:
    fatal("two render views expected on the screen, found %s" % boxes)
time.sleep(0.5)
t_drag = time.time()
drag(boxes[0], 120, 12)
t_release = time.time()
refines = wait_for("three refinement chunks after the drag",
                   lambda: (lambda r: r if len(r) >= 3 else None)(events_since(t_release, "refine")), 90)
shot_refining = screenshot("gui_target_refining")
converged = wait_for("the refinement to %d passes" % TARGET, lambda: events_since(t_release, "converged"), 240)
time.sleep(1.0)
during = [e for e in events_since(t_release) if e[1] == "refine" and int(e[2]["passes"]) < TARGET]
say("while refining: passes traced %s; Passes property %s; the field %s" % (
    [int(e[2]["passes"]) for e in during], sorted(set(e[2]["passes_property"] for e in during)),
    sorted(set(e[2]["passes_field"] for e in during))))
check(len(during) >= 2, "the image refined in chunks after the drag (%d chunks below %d passes)"
      % (len(during), TARGET))
check(all(e[2]["passes_property"] == str(TARGET) for e in during),
      "the Passes property keeps the target %d while the image refines" % TARGET)
check(all(e[2]["passes_field"] == str(TARGET) for e in during),
      "the Passes field shows the target %d while the image refines" % TARGET)
last = converged[0][2]
check(last["passes"] == str(TARGET) and last["passes_property"] == str(TARGET)
      and last["passes_field"] == str(TARGET),
      "refined to %s passes, the property %s and the field %s after it"
      % (last["passes"], last["passes_property"], last["passes_field"]))
got = read_json("dumped-converged.json") if dump("converged") else None
check(got["passes"] == TARGET, "the image kept says %d passes" % got["passes"])
say("the screen while refining (the panel's Passes field and the status bar): %s" % shot_refining)
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    shutil.copy(shot_refining, args.screenshots)
finish()
