# SPDX-License-Identifier: BSD-3-Clause
"""The blunt fin made a solid body from the Properties panel alone, by real key and mouse events.

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_body_faces.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

The harness of test_gui_drag.py (gui_drag_session.py builds the blunt fin's RefractiveIndex with the
default Body Wall Faces, all 0: no body). As a user: selects RefractiveIndex1 in the pipeline
browser, types "wall" in the panel's search box, tabs into Body Wall Faces (six fields, labelled
x min ... z max) and types 0 1 1 0 1 1, applies; then makes a Schlieren Image (quick launch) and
applies. Checked: the panel's fields set the property (0 1 1 0 1 1), the index then finds
solid_points > 0 (none before), and the image is dark where the fin is (the solid mask's rays).
Skipped (exit 0, a message) without ../shared/data.
"""
import os
import shutil
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import gui_driver  # noqa: E402
from gui_driver import field_boxes  # noqa: E402

gd = gui_driver.Driver(__doc__)
args, data = gd.args, gd.data
settings = {"image": dict(Resolution=[160, 160], Passes=1, Cutoff="KnifeEdge", CutoffScale=250.0,
                          Backend="CPU", Seed=4, InteractivePasses=1, FollowCamera=0)}
gd.launch("gui_drag_session.py", settings)
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
events_since, send, read_json, dump = gd.events_since, gd.send, gd.read_json, gd.dump
xdo, screenshot = gd.xdo, gd.screenshot




# -- the GUI comes up with the pipeline built
ready = read_json("ready.json", timeout=120)
if ready["scene"] != "bluntfin":
    say("SKIP: no blunt-fin data in %s" % os.path.abspath(data))
    send("quit")
    sys.exit(0)
window = gd.main_window()
send("index")
before = read_json("index.json")
os.remove(os.path.join(args.work, "index.json"))
check(before["faces"] == [0] * 6 and not before["solid_points"],
      "before: Body Wall Faces %s, solid_points %s (no body)" % (before["faces"], before["solid_points"]))

# the panel's search box (below Apply/Reset/Delete), "wall", then Tab into the six fields
xdo("mousemove", 130, 539)
xdo("click", 1)
time.sleep(0.3)
xdo("type", "--delay", "60", "wall")
time.sleep(0.8)
fields = field_boxes(screenshot("panel_search"))
say("the Body Wall Faces fields on the screen (x, y): %s" % fields)
if len(fields) != 6:
    fatal("the panel does not show Body Wall Faces as six fields (%d found)" % len(fields))
for (x, y), value in zip(fields, (0, 1, 1, 0, 1, 1)):
    xdo("mousemove", x, y)
    xdo("click", 1)
    xdo("key", "--clearmodifiers", "ctrl+a")
    xdo("type", "--delay", "40", str(value))
    time.sleep(0.2)
time.sleep(0.5)
shot_panel = screenshot("panel_faces")
xdo("key", "--clearmodifiers", "alt+a")
time.sleep(3.0)
send("index")
after = read_json("index.json", timeout=120)
check(after["faces"] == [0, 1, 1, 0, 1, 1], "the panel's six fields set Body Wall Faces to %s" % after["faces"])
check(after["solid_points"] and after["solid_points"] > 0,
      "the index finds the fin a body: solid_points %s" % after["solid_points"])

# the image: quick launch, Apply
gd.quick_launch("Schlieren Image")
t = time.time()
xdo("key", "--clearmodifiers", "alt+a")
wait_for("Apply opening the schlieren view", lambda: events_since(t, "opened"), 120)
time.sleep(1.0)
dump("image")
import numpy as np
d = np.load(os.path.join(args.work, "image.npz"))
I = d["intensity"]
dark = float((I < 0.05).mean())
say("the image: %d passes, intensity mean %.3f, %.1f %% of the pixels below 0.05" % (int(d["passes"]), I.mean(), 100 * dark))
check(dark > 0.02, "the image is dark where the fin is (%.1f %% of the film black)" % (100 * dark))
time.sleep(1.0)
shot = screenshot("gui_body_faces")
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    for p in (shot_panel, shot):
        shutil.copy(p, args.screenshots)
finish()
