# SPDX-License-Identifier: BSD-3-Clause
"""The blunt fin's film framed to its silhouette from the Properties panel, kept while the camera
follows, by real key and mouse events.

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_framing.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

The harness of test_gui_drag.py (gui_drag_session.py builds the blunt fin's RefractiveIndex and a
3D view looking at it obliquely). As a user: makes a Schlieren Image (quick launch), types
"framing" in the panel's search box, clicks the Framing combo box and picks Silhouette with the
keys, applies; turns Follow Camera on and drags the 3D view. Checked: the panel set Framing
Silhouette; the applied film has the silhouette's shape (here the bounding rectangle of the box's
oblique projection: the fin's flow fills its box) with Resolution's pixel count (160 x 160:
25600); every image shown while the mouse dragged and after has that film's shape
(film_frame_kept 1, the same film_extent): the frame chosen by the Apply stays while the camera
follows. Skipped (exit 0, a message) without ../shared/data.
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
TARGET = 16
settings = {"image": dict(Resolution=[160, 160], Passes=TARGET, Cutoff="KnifeEdge", CutoffScale=250.0,
                          Backend="CPU", Seed=4, InteractivePasses=1, InteractiveScale=0.5,
                          FollowCamera=0)}
gd.launch("gui_drag_session.py", settings)
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
events_since, send, read_json, dump = gd.events_since, gd.send, gd.read_json, gd.dump
xdo, screenshot, drag = gd.xdo, gd.screenshot, gd.drag


def fields(name):
    send("fields")
    got = read_json("fields.json", timeout=60)
    os.remove(os.path.join(args.work, "fields.json"))
    say("%s: Framing %s, film %s, film_extent %s, kept %s, missed %s of %s rays"
        % (name, got["framing"], got["size"], got["film_extent"], got["film_frame_kept"],
           got["missed_rays"], got["photons"]))
    return got


ready = read_json("ready.json", timeout=120)
if ready["scene"] != "bluntfin":
    say("SKIP: no blunt-fin data in %s" % os.path.abspath(data))
    send("quit")
    sys.exit(0)
window = gd.main_window()

# the image: quick launch, then the panel (before Apply)
gd.quick_launch("Schlieren Image")
# the panel's search box (below Apply/Reset/Delete), "framing": the one row left is Framing's
xdo("mousemove", 130, 539)
xdo("click", 1)
time.sleep(0.3)
xdo("type", "--delay", "60", "framing")
time.sleep(0.8)
shot_search = screenshot("panel_framing")
# its combo box: the row under the group's title, right of the label
xdo("mousemove", int(os.environ.get("FRAMING_X", 190)), int(os.environ.get("FRAMING_Y", 632)))
xdo("click", 1)
time.sleep(0.6)
screenshot("framing_popup")
xdo("key", "--clearmodifiers", "Down")
time.sleep(0.2)
xdo("key", "--clearmodifiers", "Return")
time.sleep(0.5)
shot_chosen = screenshot("framing_chosen")
t = time.time()
xdo("key", "--clearmodifiers", "alt+a")
wait_for("Apply opening the schlieren view", lambda: events_since(t, "opened"), 120)
wait_for("the applied trace reaching its %d passes" % TARGET,
         lambda: [e for e in events_since(t, "converged") if int(e[2]["passes"]) == TARGET], 240)
applied = fields("after Apply")
check(applied["framing"] == "Silhouette", "the panel's combo box set Framing to %s" % applied["framing"])
nx, ny = applied["size"]
check(nx != ny and abs(nx * ny - 25600) <= 0.01 * 25600,
      "the film has the silhouette's shape with Resolution's 25600 pixels (%d x %d)" % (nx, ny))
ext = applied["film_extent"]
check(ext is not None and len(ext) == 4 and abs(nx / ny - (ext[1] - ext[0]) / (ext[3] - ext[2])) <= 1.0 / min(nx, ny) * nx / ny + 1e-9,
      "its shape is the frame's (%s)" % ext)
time.sleep(1.0)
shot_apply = screenshot("gui_framing_applied")

# Follow Camera, a drag
t = time.time()
xdo("key", "--clearmodifiers", "ctrl+alt+f")
wait_for("Follow Camera (Ctrl+Alt+F)", lambda: events_since(t, "follow"), 30)
boxes = view_boxes(shot_apply)
if len(boxes) < 2:
    fatal("the screenshot %s does not show two render views side by side (%s)" % (shot_apply, boxes))
box3d = boxes[0]
dump("before_drag")
t_drag = time.time()
drag(box3d, 90, 14)
t_release = time.time()
moved = events_since(t_drag, "retrace")
check(len(moved) >= 1, "the drag re-traced the image (%d coarse traces)" % len(moved))
wait_for("the refinement to %d passes after the drag" % TARGET,
         lambda: [e for e in events_since(t_release, "converged") if int(e[2]["passes"]) == TARGET], 240)
time.sleep(1.0)
after = fields("after the drag")
check(after["film_frame_kept"] == [1.0] and after["film_extent"] == ext and after["size"] == [nx, ny],
      "after the drag the film is the Apply's frame, kept (%s, %s)" % (after["film_extent"], after["size"]))
import numpy as np
d = np.load(dump("after_drag"))
shapes = sorted(set(tuple(s.shape) for s in d["step_images"]))
say("images shown since the drag: %d, shapes %s" % (len(d["step_images"]), shapes))
half = (round(ny / 2.0), round(nx / 2.0))
check(all(abs(s[0] * nx - s[1] * ny) <= nx + ny for s in shapes),
      "every image shown had the frame's shape (%s, the full film %d x %d)" % (shapes, ny, nx))
shot_drag = screenshot("gui_framing_after_drag")
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    for p in (shot_chosen, shot_drag):
        shutil.copy(p, args.screenshots)
finish()
