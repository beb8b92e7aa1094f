# SPDX-License-Identifier: BSD-3-Clause
"""Every trace the GUI starts is chunked and stoppable, and the image never has fewer passes than the
panel says: Apply with Follow Camera on, a Stop, a larger Passes after it, Save and Load State, by
real key and mouse events (issue 49).

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_refine.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

The harness of test_gui_apply_stop.py (paraview with PV_PLUGIN_PATH, gui_drag_session.py as its
--script: the blunt fin, or the built-in sphere without ../shared/data). A Schlieren Image of RK4,
64 passes, Follow Camera on, is made with the quick launch and applied (Alt+A). Checked:
  1. the first Apply comes in chunks; Stop Refinement (Ctrl+Alt+S) keeps the passes traced and the
     panel says them: the Passes property, the Passes field and the image's field data `passes`
     agree;
  2. 64 typed into the Passes field and applied refines that image to 64 (field data `passes` 64),
     from the passes it had;
  3. an Apply of another setting (Knife Angle, through the panel's search box) while the image
     follows the camera is chunked too (it was one blocking trace of every pass): the File menu
     opens by a key while it refines, Stop ends it (no pass after it) and the panel and the image
     agree again; the key-to-stop latency is printed; Undo (Ctrl+Z) of that Apply (ParaView restores the proxy as it
     was before it: Knife Angle 0, Passes 64) is a new image traced the same way (its first pass,
     then chunks), stopped again;
  4. the session saved (File > Save State) and loaded (File > Load State): the layout of two views
     is back while the image refines, in chunks, to the passes saved (the panel's Passes).
Stop Refinement is enabled while the loaded image refines and greyed once it is done (the toolbar's
trace lines).
"""
import os
import shutil
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import gui_driver  # noqa: E402
from gui_driver import field_boxes, read_ppm, view_boxes  # noqa: E402

gd = gui_driver.Driver(__doc__)
args, data = gd.args, gd.data
TARGET = 64
# a long trace: RK4, 64 passes; the film sized so that one pass takes a fraction of a second here
settings = {"image": dict(Resolution=[128, 128], Passes=TARGET, Integrator="RK4", Cutoff="KnifeEdge",
                          CutoffScale=250.0, Backend="CPU", Seed=4, InteractivePasses=1,
                          InteractiveScale=1.0, FollowCamera=1)}
gd.launch("gui_drag_session.py", settings)
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
events_since, read_json, dump = gd.events_since, gd.read_json, gd.dump
xdo, screenshot = gd.xdo, gd.screenshot
events, lock = gd.events, gd.lock
shots = []


def chunks(t, n, target):
    """Waits for n refinement chunks after t towards `target` passes; returns them."""
    return wait_for("%d refinement chunks towards %d passes" % (n, target), lambda: (lambda r: r if len(r) >= n else None)(
        [e for e in events_since(t, "refine") if e[2]["target"] == str(target)]), 120)


def stop(what):
    """Ctrl+Alt+S; the stop event, its latency, and the check that no pass came after it."""
    t_stop = time.time()
    xdo("key", "--clearmodifiers", "ctrl+alt+s")
    stopped = wait_for("Stop Refinement (Ctrl+Alt+S) %s" % what, lambda: events_since(t_stop, "stopped"), 60)
    latency = stopped[0][0] - t_stop
    time.sleep(1.5)
    late = [e for e in events_since(stopped[0][0]) if e[1] in ("refine", "retrace")]
    fields = stopped[0][2]
    say("%s: the stop took effect %.3f s after the key (not asserted; load %.1f); passes %s, property %s, field %s"
        % (what, latency, os.getloadavg()[0], fields["passes"], fields["passes_property"], fields["passes_field"]))
    check(not late, "%s: no pass traced after the stop (%d updates)" % (what, len(late)))
    return int(fields["passes"]), fields, latency


def agree(what, fields, name):
    """The panel's Passes (property and field) and the image's field data `passes` are one number."""
    got = read_json("dumped-%s.json" % name) if dump(name) else None
    n = got["passes"]
    check(fields["passes_property"] == str(n) and fields["passes_field"] == str(n),
          "%s: the panel says %s passes (field %s) and the image's field data %d" %
          (what, fields["passes_property"], fields["passes_field"], n))
    return n


def menu(item_downs, path, accept_options=False):
    """File menu (Alt+F), Down item_downs times, Return; the file dialog: the path, Return."""
    xdo("key", "--clearmodifiers", "alt+f")
    time.sleep(0.8)
    for _ in range(item_downs):
        xdo("key", "--clearmodifiers", "Down")
        time.sleep(0.15)
    xdo("key", "--clearmodifiers", "Return")
    time.sleep(2.0)
    xdo("key", "--clearmodifiers", "ctrl+a")
    xdo("type", "--delay", "30", path)
    time.sleep(0.3)
    xdo("key", "--clearmodifiers", "Return")
    if accept_options:
        time.sleep(2.0)
        xdo("key", "--clearmodifiers", "Return")


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

# -- 1. the first Apply, following the camera: chunks, then a stop
gd.quick_launch("Schlieren Image")
t_apply = time.time()
xdo("key", "--clearmodifiers", "alt+a")
wait_for("Apply (Alt+A) opening the schlieren view", lambda: events_since(t_apply, "opened"), 60)
first = chunks(t_apply, 2, TARGET)
stopped_a, fields_a, _ = stop("the first Apply")
check(0 < stopped_a < TARGET, "the first Apply was stopped mid-way (%d of %d passes)" % (stopped_a, TARGET))
agree("after the stop", fields_a, "stop1")

# -- 2. 64 typed into the Passes field and applied: the image refines to 64 from its passes
with lock:
    at = [e[2].get("field_at") for e in events if e[2].get("field_at", "-1,-1") != "-1,-1"]
if not at:
    fatal("the plugin never saw the Passes field on the screen")
fx, fy = map(int, at[-1].split(","))
xdo("mousemove", fx, fy)
time.sleep(0.2)
xdo("click", 1)
time.sleep(0.3)
xdo("key", "--clearmodifiers", "ctrl+a")
xdo("type", "--delay", "100", str(TARGET))
time.sleep(0.4)
t_typed = time.time()
xdo("key", "--clearmodifiers", "alt+a")
converged = wait_for("the refinement to %d passes" % TARGET, lambda: [
    e for e in events_since(t_typed, "converged") if e[2]["passes"] == str(TARGET)], 180)
steps = [int(e[2]["passes"]) for e in events_since(t_typed, "refine")]
say("Passes %d applied after the stop at %d: chunks at %s" % (TARGET, stopped_a, steps))
check(steps and steps[0] > stopped_a, "the refinement went on from the %d passes kept (first chunk %s)"
      % (stopped_a, steps[:1]))
time.sleep(1.0)
check(agree("after Passes %d" % TARGET, converged[0][2], "converged") == TARGET,
      "Passes %d after a stop at %d: the image has %d passes" % (TARGET, stopped_a, TARGET))

# -- 3. another setting applied while following: chunked, the menus answer, Stop ends it
xdo("mousemove", 130, 539)  # the panel's search box
xdo("click", 1)
time.sleep(0.3)
xdo("type", "--delay", "60", "knife angle")
time.sleep(0.8)
boxes = field_boxes(screenshot("panel_knife_angle"))
if not boxes:
    fatal("the panel shows no line edit after searching for Knife Angle")
xdo("mousemove", *boxes[0])
xdo("click", 1)
xdo("key", "--clearmodifiers", "ctrl+a")
xdo("type", "--delay", "60", "30")
time.sleep(0.3)
t_knife = time.time()
xdo("key", "--clearmodifiers", "alt+a")
refines = chunks(t_knife, 2, TARGET)
check(int(refines[0][2]["passes"]) < TARGET,
      "the Apply of Knife Angle while following came in chunks (first %s passes of %d)"
      % (refines[0][2]["passes"], TARGET))
xdo("key", "--clearmodifiers", "alt+f")
time.sleep(0.8)
shots.append(screenshot("gui_refine_menu"))
windows = subprocess.run(["xdotool", "search", "--onlyvisible", "--class", "paraview"], stdout=subprocess.PIPE,
                         universal_newlines=True).stdout.split()
xdo("key", "--clearmodifiers", "Escape")
time.sleep(0.3)
still = [e for e in events_since(t_knife, "converged")]
check(len(windows) >= 2 and not still, "a key opened the File menu while the Apply refined (%d paraview windows)"
      % len(windows))
stopped_c, fields_c, latency = stop("the Knife Angle Apply")
check(0 < stopped_c < TARGET, "the Apply while following was stopped mid-way (%d of %d passes)"
      % (stopped_c, TARGET))
saved_passes = agree("after the second stop", fields_c, "stop2")
shots.append(screenshot("gui_refine_stopped"))

# -- Undo (Ctrl+Z, the focus first on the image view, away from the panel's line edit, which has an
# undo of its own) of the Knife Angle: a new image, chunked to the Passes the panel says
time.sleep(0.5)
views = view_boxes(screenshot("gui_refine_before_undo"))
if len(views) < 2:
    fatal("two render views expected on the screen, found %s" % views)
x, y, w, h = views[1]
xdo("mousemove", x + w // 2, y + h // 2)
xdo("click", 1)
time.sleep(0.5)
t_undo = time.time()
xdo("key", "--clearmodifiers", "ctrl+z")
# ParaView's Undo returns the proxy to its state before that Apply: Knife Angle 0 and Passes 64
first = wait_for("the Undo's refinement", lambda: events_since(t_undo, "refine"), 60)
undone_target = int(first[0][2]["target"])
refines = chunks(t_undo, 2, undone_target)
updated = events_since(t_undo, "updated")
with lock:
    say("Undo: events %s" % ["%.2f %s %s/%s" % (e[0] - t_undo, e[1], e[2].get("passes"), e[2].get("target"))
                             for e in events if e[0] >= t_undo][:8])
check(updated and int(updated[0][2]["passes"]) < undone_target and undone_target == TARGET,
      "Undo of the Knife Angle Apply (back to Passes %d) traced %s pass(es) first, then chunks"
      % (undone_target, updated[0][2]["passes"] if updated else "?"))
wait_for("the Undo's refinement past 12 passes", lambda: [
    e for e in events_since(t_undo, "refine") if int(e[2]["passes"]) >= 12], 60)
stopped_u, fields_u, _ = stop("the Undo's refinement")
saved_passes = agree("after the stop of the Undo's refinement", fields_u, "stop3")

# -- 4. Save State, Load State: the layout at once, the image refined to the passes saved
state = os.path.join(os.path.abspath(args.work), "refine.pvsm")
menu(3, state)  # (the first Down highlights Open) Recent Files, (Reload Files, greyed) Load State, Save State
wait_for("the state file %s" % state, lambda: os.path.exists(state) and os.path.getsize(state) > 1000, 30)
time.sleep(1.0)
t_load = time.time()
menu(2, state, accept_options=True)
t_asked = time.time()
# the state's image made (its first pass not traced yet), then the layout on the screen
loading = wait_for("the loaded state's image", lambda: events_since(t_load, "loading"), 90)
shown, shot_loaded = None, None
while time.time() < loading[0][0] + 60:
    shot_loaded = screenshot("gui_refine_loaded-%d" % len(shots))
    shots.append(shot_loaded)
    views = view_boxes(shot_loaded)
    if len(views) == 2 and image_fraction(shot_loaded, views[-1]) > 0.3:
        shown = time.time()
        break
    time.sleep(0.3)
if shown is None:
    fatal("after Load State the two views with the image did not come back (%s)" % shot_loaded)
shots.append(shot_loaded)
first = events_since(t_load, "updated")
say("Load State: the first image (%s passes) %.1f s and the layout with the image on the screen %.1f s after "
    "the state's image was made (%.1f s after the options were accepted)"
    % (first[0][2]["passes"] if first else "?", first[0][0] - loading[0][0] if first else -1,
       shown - loading[0][0], shown - t_asked))
with lock:
    say("events since the load: %s" % ["%.2f %s %s" % (e[0] - loading[0][0], e[1], e[2].get("passes"))
                                       for e in events if e[0] >= t_load])
check(int(loading[0][2]["passes"]) < saved_passes,
      "the loaded image starts from %s passes, not all %d at once" % (loading[0][2]["passes"], saved_passes))
done = wait_for("the loaded image refined to the %d passes saved" % saved_passes, lambda: [
    e for e in events_since(t_load, "converged") if e[2]["passes"] == str(saved_passes)], 120)
steps = [int(e[2]["passes"]) for e in events_since(t_load, "refine")]
say("after Load State: chunks at %s" % steps)
load_refines = events_since(t_load, "refine")
check(load_refines and all(e[2]["view_shown"] == "1" for e in load_refines),
      "the loaded image refined with its view on the screen (every chunk after the layout showed)")
check(len(steps) >= 1 and done[0][2]["passes_property"] == str(saved_passes),
      "the loaded image refined in chunks to the %d passes saved (the panel says %s)"
      % (saved_passes, done[0][2]["passes_property"]))
time.sleep(1.0)
actions = events_since(t_load, "actions")
check(actions and actions[-1][2]["stop"] == "0" and any(a[2]["stop"] == "1" for a in actions),
      "Stop Refinement enabled while the loaded image refined, greyed after (%s)"
      % [a[2]["stop"] for a in actions])
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    for p in shots:
        shutil.copy(p, args.screenshots)
finish()
