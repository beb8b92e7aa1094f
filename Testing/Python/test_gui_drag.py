# SPDX-License-Identifier: BSD-3-Clause
"""The schlieren image follows the 3D view in the ParaView GUI, driven by real mouse and key events.

Run with Debian's Python under an X server with a window manager:

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_drag.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

Starts `paraview` with the plugin's folder on PV_PLUGIN_PATH (as a user's ParaView loads it) and
gui_drag_session.py as its --script (it builds the chain and records what the GUI shows), then,
with xdotool, as a user: makes a Schlieren Image with the quick launch (Ctrl+Space) and presses
Apply (Alt+A), turns Follow Camera on (Ctrl+Alt+F, the toolbar
toggle), drags the 3D view with the mouse, drags again while the image refines, and presses Stop
Refinement (Ctrl+Alt+S). It checks, from the plugin's event lines (SCHLIEREN_GUI_TRACE=1), the
session's records and screenshots (`import -window root`):
  1. Apply opened the image in its own 2D view beside the 3D view and hid it there;
  2. the image view re-rendered by itself while the mouse dragged the 3D view (its render count
     and its pixels on the screen changed with no event sent to it);
  3. after the drag the image refined in chunks to the target passes (RMS per step printed) and
     equals a pvpython trace with the same camera and passes, bit for bit (gui_drag_check.py);
  4. a drag during the refinement cancelled it (back to the interactive passes);
  5. Stop Refinement stopped the refinement before it would have ended (the latency printed, not
     asserted); the image keeps the passes done and
     equals a pvpython trace of that many passes;
  6. the image at the starting camera matches a baseline PNG (the blunt fin).
The built-in sphere stands in where ../shared/data is absent (the baseline check is then skipped,
with a note). Exit status 0 on success; every failure says what did not happen.

With --pvserver <pvserver> the same session runs in client/server mode: a `pvserver` on a free
localhost port (the plugin on its PV_PLUGIN_PATH too) runs the pipeline and the traces, and the GUI
connects to it with --server-url=cs://localhost:<port>; the session then fetches the images from
the server. The server is ended on every exit path (it also dies with this driver: PDEATHSIG).
"""
import os
import shutil
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import gui_driver  # noqa: E402
from gui_driver import view_boxes  # noqa: E402


def options(parser):
    parser.add_argument("--baseline", default=os.path.join(here, "..", "Baselines", "gui_drag_bluntfin.png"))


gd = gui_driver.Driver(__doc__, options)
args, data = gd.args, gd.data
TARGET = 96
settings = {"image": dict(Resolution=[160, 160], Passes=TARGET, Cutoff="KnifeEdge", CutoffScale=250.0,
                          Backend="CPU", Seed=4, InteractivePasses=1, InteractiveScale=0.5, FollowCamera=0)}
gd.launch("gui_drag_session.py", settings)
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
events_since, send, read_json, dump = gd.events_since, gd.send, gd.read_json, gd.dump
xdo, screenshot, drag = gd.xdo, gd.screenshot, gd.drag


# -- the GUI comes up with the pipeline built
ready = read_json("ready.json", timeout=120)
say("the session is ready (%s); paraview's 3D view %s" % (ready["scene"], ready["view3d"]))
check(ready.get("remote", False) == bool(args.pvserver),
      "the GUI runs %s (session remote: %s)" % ("on the pvserver" if args.pvserver else "builtin", ready.get("remote")))
check(ready.get("ranks") == args.ranks, "the server has %d rank(s) (the session sees %s)" % (args.ranks, ready.get("ranks")))
if ready["scene"] != "bluntfin":
    say("SKIP note: no blunt-fin data in %s: the built-in off-centre sphere instead, no baseline check"
        % os.path.abspath(data))
window = gd.main_window()

# -- 1. The Schlieren Image from the GUI's quick launch (Ctrl+Space), then Apply (Alt+A); the image
# opens in its own 2D view
gd.quick_launch("Schlieren Image")
screenshot("configured")
t = time.time()
xdo("key", "--clearmodifiers", "alt+a")
opened = wait_for("Apply (Alt+A) opening the schlieren view", lambda: events_since(t, "opened"), 40)
# Follow Camera off, the Apply traces the interactive passes and the plugin adds the rest in chunks
wait_for("the applied trace reaching its %d passes" % TARGET,
         lambda: [e for e in events_since(t, "converged") if int(e[2]["passes"]) == TARGET], 240)
send("sizes")
sizes = read_json("sizes.json")
say("after Apply: 3D view %s, image view %s" % (sizes["view3d"], sizes["image_view"]))
check(sizes["image_view"] is not None and sizes["image_view_mode"] == "2D",
      "Apply opened the image in its own render view, interaction 2D (%s)" % sizes["image_view_mode"])
check(sizes["distributed_ranks"] == (args.ranks if args.ranks > 1 else 0),
      "the trace ran in pieces on the server's %d rank(s) (field data distributed_ranks = %s)"
      % (args.ranks, sizes["distributed_ranks"]))
check(sizes["image_in_3d"] in ([], [0]), "the film is hidden in the 3D view (%s)" % sizes["image_in_3d"])
shown = sizes["shown_3d"]
check(shown["renders"] > 0 and shown["film"] == 0 and shown["legend"] == 0,
      "no render of the 3D view drew the film or a colour legend (%d renders: the film in %d, a legend "
      "in %d)" % (shown["renders"], shown["film"], shown["legend"]))
wait_for("the first image", lambda: os.path.exists(dump("initial")), 60)
initial = os.path.join(args.work, "initial.npz")
time.sleep(1.0)  # the views' deferred renders
shot_apply = screenshot("gui_applied")

# -- Follow Camera from the toolbar's shortcut
t = time.time()
xdo("key", "--clearmodifiers", "ctrl+alt+f")
wait_for("Follow Camera (Ctrl+Alt+F)", lambda: events_since(t, "follow"), 30)
send("sizes")
os.remove(os.path.join(args.work, "sizes.json"))
check(read_json("sizes.json")["follow"] == 1, "the toolbar toggle set the image's FollowCamera property")
time.sleep(1.0)
check(not [e for e in events_since(t) if e[1] in ("retrace", "refine")],
      "turning Follow Camera on kept the image it had (no trace before the camera moves)")

# where the two views are on the screen
boxes = view_boxes(shot_apply)
if len(boxes) < 2:
    fatal("the screenshot %s does not show two render views side by side (%s)" % (shot_apply, boxes))
box3d, boxim = boxes[0], boxes[-1]
say("3D view at %s, image view at %s (screen pixels: x, y, w, h)" % (box3d, boxim))
check(boxim[0] >= box3d[0] + box3d[2] - 8, "the image view is beside the 3D view, on its right")

# -- 2, 3. Drag the 3D view: the image view follows by itself, then refines to the target
before = dump("before_drag")
t_drag = time.time()
drag(box3d, 80, 16)
t_release = time.time()
moved = events_since(t_drag, "retrace")
check(len(moved) >= 1, "the drag re-traced the image (%d coarse traces during the drag)" % len(moved))
check(all(int(e[2]["passes"]) == 1 and e[2]["resolution"] == "80x80" for e in moved),
      "while the mouse moved, 1 pass each on a half-resolution film (InteractiveScale 0.5: %s)"
      % sorted(set(e[2]["resolution"] for e in moved)))
converged = wait_for("the refinement to %d passes after the drag" % TARGET,
                     lambda: [e for e in events_since(t_release, "converged") if int(e[2]["passes"]) == TARGET],
                     240)
refines = events_since(t_release, "refine")
say("refinement after the drag: %d chunks, passes %s, first %.2f s after the release, converged %.2f s after"
    % (len(refines), [int(e[2]["passes"]) for e in refines], refines[0][0] - t_release if refines else -1,
       converged[0][0] - t_release))
check(len(refines) >= 2 and all(e[2]["resolution"] == "160x160" for e in refines),
      "the refinement came in chunks (%d), on the full 160 x 160 film" % len(refines))
time.sleep(1.0)
after = dump("after_drag")
shot_drag = screenshot("gui_after_drag")

# -- 4. A new drag while refining cancels the refinement
t = time.time()
drag(box3d, -120, 10)
t2 = time.time()
first = wait_for("the refinement after the second drag", lambda: events_since(t2, "refine"), 60)
t3 = time.time()
drag(box3d, 60, 6, pause=0.03)
cancel = wait_for("the cancel of the refinement by the third drag", lambda: events_since(t3, "cancelled"), 30)
check(int(first[0][2]["passes"]) < TARGET, "the third drag came during the refinement (%s of %d passes)"
      % (first[0][2]["passes"], TARGET))
retraced = wait_for("the coarse trace after the cancel", lambda: events_since(cancel[0][0], "retrace"), 30)
check(int(retraced[0][2]["passes"]) == 1, "a new drag mid-refinement cancels it: back to 1 pass")

# -- 5. Stop Refinement during the refinement: stops within a second, keeps the passes done
t4 = time.time()
wait_for("the refinement after the third drag", lambda: events_since(t4, "refine"), 60)
t_stop = time.time()
xdo("key", "--clearmodifiers", "ctrl+alt+s")
stopped = wait_for("Stop Refinement (Ctrl+Alt+S)", lambda: events_since(t_stop, "stopped"), 30)
latency = stopped[0][0] - t_stop
time.sleep(1.5)
late = [e for e in events_since(stopped[0][0]) if e[1] in ("refine", "retrace")]
passes_stopped = int(stopped[0][2]["passes"])
# the latency is printed, not asserted (a loaded machine stretches it); what must hold whatever the
# load: the stop came sooner than the rest of the refinement would have taken
remaining = (TARGET - passes_stopped) * float(stopped[0][2]["seconds_per_pass"])
say("Stop took effect %.3f s after the key press (load %.2f)" % (latency, os.getloadavg()[0]))
check(latency < remaining, "Stop came sooner than the rest of the refinement would have (%.3f s < %.1f s)"
      % (latency, remaining))
check(not late and passes_stopped < TARGET,
      "no pass was added after Stop; the image keeps %d of %d passes" % (passes_stopped, TARGET))
stop_dump = dump("stopped")
shot_stop = screenshot("gui_stopped")

# -- the numbers: pvpython traces with the same cameras and passes, the baseline
check_cmd = [args.pvpython, os.path.join(here, "gui_drag_check.py"), "--plugin", args.plugin,
             "--work", args.work, "--scene", ready["scene"], "--baseline", args.baseline]
say(" ".join(check_cmd))
rc = subprocess.call(check_cmd, env=dict(os.environ, SCHLIEREN_DATA=data), timeout=600)
check(rc == 0, "gui_drag_check.py: the GUI's images against pvpython traces and the baseline")

# the image view's pixels on the screen changed with the drag (it re-rendered by itself)
region = "[%dx%d+%d+%d]" % (boxim[2], boxim[3], boxim[0], boxim[1])
cmp = subprocess.run(["compare", "-metric", "AE", "-fuzz", "2%", shot_apply + region, shot_drag + region,
                      os.path.join(args.work, "image_view_diff.png")],
                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=120)
changed = cmp.stdout.strip().split()[0] if cmp.stdout.strip() else "?"
check(changed.replace(".", "").isdigit() and float(changed) > 500,
      "the image view's pixels on the screen changed after the drag (%s pixels differ)" % changed)
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    for p in (shot_apply, shot_drag, shot_stop):
        shutil.copy(p, args.screenshots)
finish()
