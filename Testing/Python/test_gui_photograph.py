# SPDX-License-Identifier: BSD-3-Clause
"""A photograph beside the image in the GUI, by real key and mouse events (issue 51).

    SCHLIEREN_XVFB_WM=openbox PYTHONPATH=Python SCHLIEREN_ENGINE_LIBRARY=<libschlieren_engine.so> \\
        Testing/with_xvfb.sh /usr/bin/python3 test_gui_photograph.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

gui_photograph_session.py builds python.photograph's scene, its Schlieren Image in a 2D view beside
the 3D view, and a 16-bit PNG "photograph" of the film with a known similarity transform, gamma,
vignetting and noise. Here, as a user: the image selected, ParaView's quick launch makes a Schlieren
Photograph on it, the File Name typed into the Properties panel (found by its search box), Apply
(Alt+A); then the Overlay combobox (found by the search box) stepped to Checkerboard and to
Difference, Apply each time. Checked: the overlay is shown in the image's 2D view (a slice coloured
by the Overlay's array, the image hidden under it) and not in the 3D view, the lines over it
coloured by line_distance; each overlay changes the view's pixels (counted on the screenshots) and
the active array, without registering again; the transform recovered within half a film pixel at
the corners; the lines' list in a spreadsheet view, the film's matched lines within two pixels of
the photograph's (the same flow: the known move is 0).
"""
import math
import os
import shutil
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import gui_driver  # noqa: E402
from gui_driver import field_boxes, read_ppm, view_boxes  # noqa: E402

gd = gui_driver.Driver(__doc__)
args = gd.args
gd.launch("gui_photograph_session.py", {})
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
send, read_json, xdo, screenshot = gd.send, gd.read_json, gd.xdo, gd.screenshot


def state(command="state"):
    n = gd.commands
    send(command)
    return read_json("state-%d.json" % n, timeout=60)


def search_panel(text):
    """Types `text` into the Properties panel's search box (it shows only the matching
    properties); returns a screenshot's path."""
    xdo("mousemove", 130, 539)
    xdo("click", 1)
    xdo("key", "--clearmodifiers", "ctrl+a")
    xdo("type", "--delay", "60", text)
    time.sleep(1.0)
    return screenshot("search_" + text.replace(" ", "_"))


def apply_and_wait(before, what):
    """Alt+A, then waits until the photograph's output is newer than `before` (its MTime)."""
    xdo("key", "--clearmodifiers", "alt+a")
    return wait_for(what, lambda: (lambda s: s if s.get("points") and s["mtime"] != before else None)(
        state()), 90)


ready = read_json("ready.json", timeout=180)
truth = ready["truth"]
say("the session is ready: a film of %s pixels, the photograph %s" % (ready["film"], ready["photo"]))
window = gd.main_window()
gd.quick_launch("Schlieren Photograph", configured=False)
wait_for("the Schlieren Photograph made by the quick launch", lambda: state()["photograph"], 30)
shot = search_panel("file name")
boxes = field_boxes(shot)
if not boxes:
    fatal("no line edit for File Name in the Properties panel (%s)" % shot)
xdo("mousemove", *boxes[0])
xdo("click", 1)
xdo("key", "--clearmodifiers", "ctrl+a")
xdo("type", "--delay", "20", ready["photo"])
time.sleep(0.5)
s = apply_and_wait(None, "Apply (Alt+A) registering the photograph")
check(s["file_name"] == ready["photo"], "the typed File Name reached the filter (%s)" % s["file_name"])
shots = {"Blend": screenshot("overlay_blend")}
states = {"Blend": s}
for overlay in ("Checkerboard", "Difference"):
    found = field_boxes(search_panel("overlay"))
    if len(found) < 2:
        fatal("the Overlay group's fields were not found in the Properties panel")
    # the group's rows: Overlay (a combobox), Blend Weight and Checker Size (line edits): the
    # combobox is a row above the first line edit. A click opens its list at the entry shown;
    # Down and Return pick the next one (Blend, Checkerboard, Difference, ...)
    combo = (found[0][0], found[0][1] - (found[1][1] - found[0][1]))
    xdo("mousemove", *combo)
    xdo("click", 1)
    time.sleep(0.8)
    xdo("key", "--clearmodifiers", "Down")
    time.sleep(0.3)
    xdo("key", "--clearmodifiers", "Return")
    time.sleep(0.5)
    states[overlay] = apply_and_wait(states["Blend" if overlay == "Checkerboard" else "Checkerboard"]["mtime"],
                                     "Apply (Alt+A) of Overlay %s" % overlay)
    shots[overlay] = screenshot("overlay_" + overlay.lower())
sheet = state("spreadsheet")
time.sleep(1.5)
shots["list"] = screenshot("lines_list")
for overlay, s in states.items():
    say("%s: %s" % (overlay, {k: v for k, v in s.items() if k not in ("report", "lines")}))

# the overlay where the image is, as the Overlay says, the lines over it
for overlay, s in states.items():
    want = {"Blend": "blend", "Checkerboard": "checkerboard", "Difference": "difference"}[overlay]
    check(s["overlay"] == overlay and s["active"] == want and s["port0"] is not None and
          s["port0"]["visible"] and s["port0"]["type"] == "Slice" and s["port0"]["colour"] == ["POINTS", want],
          "Overlay %s: the image view shows output 0 as a slice coloured by %s (%s)" % (overlay, want, s["port0"]))
    check(s["port1"] is not None and s["port1"]["visible"] and s["port1"]["type"] == "Surface" and
          s["port1"]["colour"] == ["CELLS", "line_distance"],
          "Overlay %s: the lines drawn over it, coloured by line_distance (%s)" % (overlay, s["port1"]))
    check(s["image_shown"] == 0 and s["in_3d"] == [None, None],
          "Overlay %s: the film under it hidden, nothing of it in the 3D view" % overlay)
check(states["Difference"]["port0"]["range"][0] == -states["Difference"]["port0"]["range"][1],
      "the difference's map centred on 0 (agreement): %s" % states["Difference"]["port0"]["range"])
check(states["Checkerboard"]["report"]["seconds"] == states["Difference"]["report"]["seconds"] ==
      states["Blend"]["report"]["seconds"],
      "the Overlay changed the view, not the registration (one registration of %.2f s)"
      % states["Blend"]["report"]["seconds"])

# the screen: each overlay changes the image view's pixels
import numpy as np  # noqa: E402
pixels = {k: read_ppm(v) for k, v in shots.items() if k != "list"}
box = max(view_boxes(shots["Blend"]), key=lambda b: b[2] * b[3])  # the image view
x, y, w, h = box
inner = lambda a: a[y + h // 8: y + 7 * h // 8, x + w // 8: x + 5 * w // 8]  # noqa: E731 -- the film, not the legends
# (blend and checkerboard differ by half the calibrated photograph's difference from the film,
# its noise: 2-3 grey levels; the difference is another map)
for a, b, least in (("Blend", "Checkerboard", 0.3), ("Checkerboard", "Difference", 0.5)):
    changed = float(np.mean(np.any(inner(pixels[a]) != inner(pixels[b]), axis=2)))
    check(changed > least, "%s to %s: %.1f %% of the image view's pixels changed (> %.0f %%)"
          % (a, b, 100 * changed, 100 * least))

# the numbers: the transform, the lines' distances (the same flow: the known move is 0)
r, pixel = states["Blend"]["report"], ready["pixel"]
n = ready["film"][0]
worst = 0.0
for cx in (0, n - 1):
    for cy in (0, n - 1):
        px, py = cx - 0.5 * (n - 1), cy - 0.5 * (n - 1)

        def place(scale, degrees, shift):
            t = math.radians(degrees)
            return (scale * (math.cos(t) * px - math.sin(t) * py) + shift[0],
                    scale * (math.sin(t) * px + math.cos(t) * py) + shift[1])
        u0, u1 = place(truth["scale"], truth["degrees"], truth["shift"]), place(r["scale"], r["rotation"], r["shift"])
        worst = max(worst, math.hypot(u1[0] - u0[0], u1[1] - u0[1]) / truth["scale"])
check(r["match"] and worst < 0.5, "registered in the GUI: the transform within %.3f film pixels at the "
      "corners (< 0.5; scale %.4f, rotation %.3f deg, score %.3f over %.3f)"
      % (worst, r["scale"], r["rotation"], r["score"], r["threshold"]))
film_lines = [l["distance"] for l in sheet["lines"] if l["image"] == 0 and l["distance"] == l["distance"]]
check(len(film_lines) >= 3 and max(film_lines) < 2 * pixel,
      "the film's %d matched lines within 2 pixels of the photograph's: largest %.4g (a pixel %.4g; "
      "the same flow, moved 0)" % (len(film_lines), max(film_lines) if film_lines else -1, pixel))
lists = sheet["spreadsheets"]
check(len(lists) == 1 and lists[0]["rows"] == len(sheet["lines"]) and lists[0]["attribute"] == "Cell Data"
      and "line_distance" in lists[0]["columns"],
      "the lines listed in a spreadsheet view: %s" % ({k: v for k, v in lists[0].items() if k != "columns"}
                                                       if lists else None))
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    for name, path in shots.items():
        shutil.copy(path, args.screenshots)
finish()
