# SPDX-License-Identifier: BSD-3-Clause
"""NumericalSchlieren in the GUI as SchlierenImage is: its own 2D view, following the 3D camera, by
real key and mouse events (issue 49).

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_numerical.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

The harness of test_gui_drag.py (gui_drag_session.py: the blunt fin's RefractiveIndex, or the
built-in sphere without ../shared/data, its outline in a 3D view seen from an oblique camera). A
Numerical Schlieren is made with the quick launch (the session ticks its Follow Camera) and applied
(Alt+A). Checked: the Apply opened the film in its own render view, interaction 2D, and never drew
it in the 3D view (where its film plane was edge-on, invisible from the side); the film looks along
the 3D camera; the image view shows an image (screen pixels); a drag of the 3D view turns the film
with the camera (its View Direction is the new camera's) and changes the image.
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
settings = {"filter": "NumericalSchlieren", "image": dict(Resolution=[160, 160], FollowCamera=1)}
gd.launch("gui_drag_session.py", settings)
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
events_since, send, read_json, dump = gd.events_since, gd.send, gd.read_json, gd.dump
xdo, screenshot, drag = gd.xdo, gd.screenshot, gd.drag


def image_fraction(png, box):
    """The fraction of the box's middle half that is not the views' background colour."""
    import numpy as np

    pixels = read_ppm(png)
    x, y, bw, bh = box
    mid = pixels[y + bh // 4: y + 3 * bh // 4, x + bw // 4: x + 3 * bw // 4]
    return float(np.mean(np.any(np.abs(mid - np.array(gui_driver.VIEW_BACKGROUND)) > 2, axis=2)))


ready = read_json("ready.json", timeout=120)
say("the session is ready (%s)" % ready["scene"])
window = gd.main_window()
gd.quick_launch("Numerical Schlieren")
t_apply = time.time()
xdo("key", "--clearmodifiers", "alt+a")
wait_for("Apply (Alt+A) opening the numerical schlieren's view", lambda: events_since(t_apply, "opened"), 60)
time.sleep(1.5)
send("sizes")
sizes = read_json("sizes.json")
check(sizes["image_view"] is not None and sizes["image_view_mode"] == "2D",
      "Apply opened the numerical schlieren in its own render view, interaction 2D (%s)" % sizes["image_view_mode"])
check(sizes["image_in_3d"] in ([], [0]) and sizes["shown_3d"]["film"] == 0,
      "the film is not drawn in the 3D view (%s; %d of %d renders drew it)"
      % (sizes["image_in_3d"], sizes["shown_3d"]["film"], sizes["shown_3d"]["renders"]))
import numpy as np  # noqa: E402

first = np.load(dump("first"))
shot_first = screenshot("gui_numerical_applied")
views = view_boxes(shot_first)
if len(views) < 2:
    fatal("two render views expected on the screen, found %s (%s)" % (views, shot_first))
fraction = image_fraction(shot_first, views[1])
check(fraction > 0.3, "the image view shows the film (%.0f %% of its middle is image)" % (100 * fraction))
d0 = first["direction"]
say("the film looks along %s; intensity %.3f to %.3f" % (np.round(d0, 3).tolist(), first["intensity"].min(),
                                                         first["intensity"].max()))
check(abs(d0[2] + 1) > 1e-3 and first["intensity"].std() > 0,
      "the film follows the oblique 3D camera (not the default (0, 0, -1)) and shows structure")

# a drag of the 3D view: the film turns with the camera
t_drag = time.time()
drag(views[0], 160, 12)
wait_for("the film re-made along the turned camera", lambda: events_since(t_drag, "retrace"), 60)
time.sleep(2.0)  # the rest: nothing to refine (one update is the image), the last move traced
turned = np.load(dump("turned"))
d1 = turned["direction"]
angle = np.degrees(np.arccos(np.clip(np.dot(d0, d1), -1, 1)))
change = np.abs(turned["intensity"] - first["intensity"]).max() if turned["intensity"].shape == first["intensity"].shape else 1.0
say("after the drag: View Direction %s (%.1f degrees turned), max |intensity change| %.3f"
    % (np.round(d1, 3).tolist(), angle, change))
check(angle > 5, "the film turned with the 3D camera (%.1f degrees)" % angle)
check(change > 0.05, "the image changed with the view (max |change| %.3f)" % change)
shot_turned = screenshot("gui_numerical_turned")
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    for p in (shot_first, shot_turned):
        shutil.copy(p, args.screenshots)
finish()
