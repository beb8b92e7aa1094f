# SPDX-License-Identifier: BSD-3-Clause
"""A schlieren session saved with File > Save State and loaded again with File > Load State, by real
key events (the harness of test_gui_drag.py; gui_drag_session.py builds the chain).

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_state.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

A Schlieren Image is made (quick launch) and applied: the 3D view and the image's 2D view side by
side. The state is saved (File menu, Save State..., the file name typed) and loaded (File menu,
Load State..., the file name, the options dialog accepted). Checked: after the load the screen shows
the layout as saved, two render views side by side (not four), the plugin opened no new view (it
adopted the loaded 2D view as the image view), and the image view shows the image again (its
middle is not the empty background).
"""
import os
import shutil
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import gui_driver  # noqa: E402
from gui_driver import read_ppm, view_boxes  # noqa: E402

gd = gui_driver.Driver(__doc__)
args, data = gd.args, gd.data
settings = {"image": dict(Resolution=[160, 160], InteractivePasses=2, Passes=2, Cutoff="KnifeEdge",
                          CutoffScale=250.0, Backend="CPU", Seed=4, FollowCamera=0)}
gd.launch("gui_drag_session.py", settings)
say, check, finish, wait_for = gd.say, gd.check, gd.finish, gd.wait_for
events_since, read_json = gd.events_since, gd.read_json
xdo, screenshot = gd.xdo, gd.screenshot



def image_fraction(png, box):
    """The fraction of the box's middle half that is not the views' background colour."""
    import numpy as np

    pixels = read_ppm(png)
    x, y, bw, bh = box
    mid = pixels[y + bh // 4: y + 3 * bh // 4, x + bw // 4: x + 3 * bw // 4]
    return float(np.mean(np.any(np.abs(mid - np.array([82, 87, 110])) > 2, axis=2)))


def menu(item_downs, path, accept_options=False):
    """File menu (Alt+F), Down item_downs times, Return; the file dialog: the path, Return."""
    xdo("key", "--clearmodifiers", "alt+f")
    time.sleep(0.8)
    for _ in range(item_downs):
        xdo("key", "--clearmodifiers", "Down")
        time.sleep(0.15)
    shot = screenshot("menu-%d" % item_downs)
    xdo("key", "--clearmodifiers", "Return")
    time.sleep(2.0)
    screenshot("dialog-%d" % item_downs)
    xdo("key", "--clearmodifiers", "ctrl+a")
    xdo("type", "--delay", "30", path)
    time.sleep(0.3)
    xdo("key", "--clearmodifiers", "Return")
    if accept_options:
        time.sleep(2.0)
        screenshot("options-%d" % item_downs)
        xdo("key", "--clearmodifiers", "Return")
    return shot


# -- the GUI comes up with the pipeline built
ready = read_json("ready.json", timeout=120)
window = gd.main_window()
gd.quick_launch("Schlieren Image")
t = time.time()
xdo("key", "--clearmodifiers", "alt+a")
wait_for("Apply opening the schlieren view", lambda: events_since(t, "opened"), 120)
time.sleep(2.0)
shot_saved = screenshot("gui_state_saved")
saved = view_boxes(shot_saved)
check(len(saved) == 2, "before saving: two render views side by side (%s)" % saved)

state = os.path.join(os.path.abspath(args.work), "session.pvsm")
menu(3, state)  # (the first Down highlights Open) Recent Files, (Reload Files, greyed) Load State, Save State
wait_for("the state file %s" % state, lambda: os.path.exists(state) and os.path.getsize(state) > 1000, 30)
say("saved %s (%d bytes)" % (state, os.path.getsize(state)))
time.sleep(1.0)
t_load = time.time()
menu(2, state, accept_options=True)
time.sleep(3.0)
loaded, shot_loaded = None, None
end = time.time() + 90
while time.time() < end:
    shot_loaded = screenshot("gui_state_loaded")
    loaded = view_boxes(shot_loaded)
    if len(loaded) == 2 and image_fraction(shot_loaded, loaded[-1]) > 0.3:
        break
    time.sleep(2.0)
say("after Load State: render views %s, %.2f s after the load was asked for" % (loaded, time.time() - t_load))
check(len(loaded) == 2, "after Load State: the layout as saved, two render views (%d)" % len(loaded))
check(not events_since(t_load, "opened"), "the plugin opened no new view after the load")
check(events_since(t_load, "adopted"), "the loaded 2D view is the image view again (adopted)")
if loaded:
    fraction = image_fraction(shot_loaded, loaded[-1])
    check(fraction > 0.3, "the image view shows the image again (%.0f %% of its middle is image)" % (100 * fraction))
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    for p in (shot_saved, shot_loaded):
        shutil.copy(p, args.screenshots)
finish()
