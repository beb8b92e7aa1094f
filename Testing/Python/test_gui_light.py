# SPDX-License-Identifier: BSD-3-Clause
"""White light from the Properties panel, by real key and mouse events: the image in colour, and grey again.

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_light.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

The harness of test_gui_drag.py (gui_drag_session.py builds the blunt fin's RefractiveIndex, or
the built-in sphere without ../shared/data, and a 3D view). As a user: makes a Schlieren Image
(quick launch; the session sets an interferometer with a tilted reference) and applies it at one
wavelength; types "wavelength range" in the panel's search box, 400 and 700 into the two fields
it shows, applies; then 0 and 0 (one wavelength again), applies. Checked: the first image is shown
as intensity in a grey map; the panel set WavelengthRange 400 700; the image's field data says how
the band was sampled (400-700 nm); the image view switched to the film's rgb as colours (not
through a colour map), and the screenshot of that view holds colours (pixels whose channels
differ), where a one-wavelength interferogram is grey; back at one wavelength the view shows
intensity in grey again, with no "Failed to locate selected scalars".
"""
import os
import shutil
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import gui_driver  # noqa: E402
from gui_driver import field_boxes, read_ppm, view_boxes  # noqa: E402

gd = gui_driver.Driver(__doc__)
args, data = gd.args, gd.data
TARGET = 16
# a tilted reference: 2 fringes of 632.8 nm per world unit, 1.3 um of path at the sphere's edge (the blunt
# fin's flow adds its own), where a 400-700 nm band's fringes fade in colour
settings = {"image": dict(Resolution=[160, 160], Passes=TARGET, Cutoff="Interferometry",
                          Backend="CPU", Seed=4, InteractivePasses=1, InteractiveScale=0.5,
                          FollowCamera=0, WavelengthBins=16, ReferenceTilt=2.0)}
gd.launch("gui_drag_session.py", settings)
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
events_since, send, read_json = gd.events_since, gd.send, gd.read_json
xdo, screenshot = gd.xdo, gd.screenshot


def fields(name):
    send("fields")
    got = read_json("fields.json", timeout=60)
    os.remove(os.path.join(args.work, "fields.json"))
    say("%s: WavelengthRange %s, spectrum %s, image view colours %s"
        % (name, got["wavelength_range"], got["spectrum"], got["image_colour"]))
    return got


ready = read_json("ready.json", timeout=120)
window = gd.main_window()

gd.quick_launch("Schlieren Image")
# the first Apply at one wavelength: a grey interferogram
t = time.time()
xdo("key", "--clearmodifiers", "alt+a")
wait_for("Apply opening the schlieren view", lambda: events_since(t, "opened"), 120)
wait_for("the applied trace reaching its %d passes" % TARGET,
         lambda: [e for e in events_since(t, "converged") if int(e[2]["passes"]) == TARGET], 300)
time.sleep(1.0)  # the views' deferred renders
got = fields("one wavelength")
check(got["image_colour"] == ["intensity", 1],
      "one wavelength: the image view shows intensity through the grey map (%s)" % got["image_colour"])


def wavelength_range(low, high):
    """The panel's search box (below Apply/Reset/Delete): "wavelength range" leaves its two fields;
    low and high typed into them, applied; waits for the refinement to the passes asked for."""
    xdo("mousemove", 130, 539)
    xdo("click", 1)
    time.sleep(0.3)
    xdo("key", "--clearmodifiers", "ctrl+a")
    xdo("type", "--delay", "60", "wavelength range")
    time.sleep(0.8)
    shot_search = screenshot("panel_wavelength_range")
    boxes = field_boxes(shot_search)
    if len(boxes) < 2:
        fatal("the panel shows %d line edits after the search, not WavelengthRange's two (%s)" % (len(boxes), shot_search))
    for (x, y), value in zip(boxes[:2], (low, high)):
        xdo("mousemove", x, y)
        xdo("click", 1)
        xdo("key", "--clearmodifiers", "ctrl+a")
        xdo("type", "--delay", "40", str(value))
        time.sleep(0.2)
    screenshot("panel_typed-%d" % low)
    t = time.time()
    xdo("key", "--clearmodifiers", "alt+a")
    wait_for("the applied trace reaching its %d passes" % TARGET,
             lambda: [e for e in events_since(t, "converged") if int(e[2]["passes"]) == TARGET], 300)
    time.sleep(1.5)  # the views' deferred renders
    return t


# the band applied to the same image: its view switches to the colours
wavelength_range(400, 700)
got = fields("after Apply")
check(got["wavelength_range"] == [400.0, 700.0],
      "the panel's fields set WavelengthRange to %s" % got["wavelength_range"])
check(got["spectrum"] is not None and got["spectrum"].startswith("400-700 nm") and "16 of them traced" in got["spectrum"],
      "the image's field data says how the band was sampled (%s)" % got["spectrum"])
check(got["image_colour"] == ["rgb", 0],
      "the image view switched to rgb as colours, not through a colour map (%s)" % got["image_colour"])
shot = screenshot("gui_light_applied")
views = view_boxes(shot)
if len(views) < 2:
    fatal("the screenshot %s does not show two render views side by side (%s)" % (shot, views))
x, y, w, h = views[1]
import numpy as np
px = read_ppm(shot)[y + h // 4:y + 3 * h // 4, x + w // 4:x + 3 * w // 4]
spread = px.max(axis=2) - px.min(axis=2)
coloured = float(np.mean(spread > 40))
say("the image view's middle: %.0f %% of its pixels coloured (channels more than 40 apart)" % (100 * coloured))
check(coloured > 0.05, "the image view shows colours (%.1f %% of its middle's pixels)" % (100 * coloured))

# back to one wavelength: grey again, and no complaint about the rgb array gone
t_back = wavelength_range(0, 0)
got = fields("one wavelength again")
check(got["image_colour"] == ["intensity", 1],
      "back to one wavelength: the image view shows intensity in grey again (%s)" % got["image_colour"])
failed = [m for m in gd.messages_since(t_back) if "Failed to locate" in m[3]]
check(not failed, "no 'Failed to locate selected scalars' after the switch (%s)" % [m[3][:80] for m in failed])
shot_grey = screenshot("gui_light_grey")
x, y, w, h = view_boxes(shot_grey)[1]
px = read_ppm(shot_grey)[y + h // 4:y + 3 * h // 4, x + w // 4:x + 3 * w // 4]
grey = float(np.mean((px.max(axis=2) - px.min(axis=2)) > 40))
check(grey < 0.01, "the image view is grey again (%.1f %% of its middle's pixels coloured)" % (100 * grey))
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    shutil.copy(shot, args.screenshots)
    shutil.copy(shot_grey, args.screenshots)
finish()
