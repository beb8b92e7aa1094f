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
import argparse
import atexit
import ctypes
import json
import os
import random
import re
import signal
import socket
import shutil
import subprocess
import sys
import threading
import time

here = os.path.dirname(os.path.abspath(__file__))
parser = argparse.ArgumentParser()
parser.add_argument("--paraview", required=True)
parser.add_argument("--pvpython", required=True)
parser.add_argument("--plugin", required=True)
parser.add_argument("--work", required=True, help="a folder for the session's files (emptied)")
parser.add_argument("--screenshots", default=None, help="also copy the screenshots here")
parser.add_argument("--pvserver", default=None,
                    help="client/server mode: run the pipeline on this pvserver (a free localhost port)")
args = parser.parse_args()

T0 = time.time()
failures = []


def say(text):
    print("[%6.1f s] %s" % (time.time() - T0, text))
    sys.stdout.flush()


def check(condition, message):
    say(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)
    return condition


def fatal(message):
    check(False, message)
    try:
        say("the screen at the failure: %s" % screenshot("failure"))
    except Exception as e:  # the screenshot is a help, not a check
        say("no screenshot: %s" % e)
    finish()


if os.path.isdir(args.work):
    shutil.rmtree(args.work)
os.makedirs(args.work)
for tool in ("xdotool", "xwininfo", "import"):
    if shutil.which(tool) is None:
        print("FAIL: %s is needed (apt-get install xdotool x11-utils imagemagick)" % tool)
        sys.exit(1)
if not os.environ.get("DISPLAY"):
    print("FAIL: no DISPLAY (run under Testing/with_xvfb.sh with SCHLIEREN_XVFB_WM=openbox)")
    sys.exit(1)

data = os.environ.get("SCHLIEREN_DATA", os.path.join(here, "..", "..", "..", "shared", "data"))
TARGET = 64  # typed into the Passes field
# the first Apply at 4 passes; the film small enough that the refinement to 64 is a few seconds here
settings = {"image": dict(Resolution=[160, 160], Passes=4, Cutoff="KnifeEdge", CutoffScale=250.0,
                          Backend="CPU", Seed=4, InteractivePasses=1, InteractiveScale=0.5, FollowCamera=0)}
with open(os.path.join(args.work, "settings.json"), "w") as f:
    json.dump(settings, f)

env = dict(os.environ, PV_PLUGIN_PATH=os.path.dirname(os.path.abspath(args.plugin)),
           SCHLIEREN_GUI_TRACE="1", SCHLIEREN_GUI_WORK=args.work, SCHLIEREN_DATA=data,
           SCHLIEREN_GUI_HERE=here)
env.pop("SCHLIEREN_PLUGIN", None)  # the session must not load the plugin itself


def die_with_parent():
    """Runs in the child before exec: SIGKILL it when this driver dies, however it dies."""
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


server = None


def stop_server():
    if server is not None and server.poll() is None:
        server.terminate()
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()


def start_server():
    """A pvserver on a free localhost port (tried until one binds); returns its port."""
    global server
    for attempt in range(8):
        port = random.randint(20000, 40000)
        with socket.socket() as probe:
            try:
                probe.bind(("127.0.0.1", port))
            except OSError:
                continue
        log = open(os.path.join(args.work, "pvserver-%d.log" % attempt), "w")
        server = subprocess.Popen([args.pvserver, "--server-port=%d" % port, "--hostname=localhost"], env=env,
                                  stdout=log, stderr=subprocess.STDOUT, preexec_fn=die_with_parent)
        end = time.time() + 60
        while time.time() < end and server.poll() is None:
            if "Accepting connection" in open(log.name).read():
                say("pvserver (pid %d) listens on localhost:%d" % (server.pid, port))
                return port
            time.sleep(0.1)
        say("pvserver on port %d did not start: %s" % (port, open(log.name).read().strip()[-300:]))
        stop_server()
    print("FAIL: no pvserver could be started (%s)" % args.pvserver)
    sys.exit(1)


command = [args.paraview, "--dr", "--script=" + os.path.join(here, "gui_drag_session.py")]
if args.pvserver:
    command.insert(1, "--server-url=cs://localhost:%d" % start_server())
say(" ".join(command))
process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           universal_newlines=True, bufsize=1, preexec_fn=die_with_parent)


def on_term(signum, frame):
    # ctest's timeout or with_xvfb.sh's cleanup: end the GUI and the server before going
    for p in (process, server):
        if p is not None and p.poll() is None:
            p.kill()
    sys.exit(1)


def kill_children():
    # an exception anywhere in the driver: no GUI or server left behind
    for p in (process, server):
        if p is not None and p.poll() is None:
            p.kill()
            p.wait()


atexit.register(kill_children)
signal.signal(signal.SIGTERM, on_term)
signal.signal(signal.SIGINT, on_term)
events = []  # (time, event, fields) from the plugin's SCHLIEREN_GUI_TRACE lines
stderr_tail = []
lock = threading.Lock()


def read_stderr():
    for line in process.stderr:
        if line.startswith("schlieren-gui "):
            parts = line.split()
            fields = dict(p.split("=", 1) for p in parts[4:] if "=" in p)
            with lock:
                events.append((float(parts[1]), parts[2], fields))
        else:
            stderr_tail.append(line.rstrip())
            del stderr_tail[:-40]


reader_thread = threading.Thread(target=read_stderr, daemon=True)
reader_thread.start()


def finish():
    if process.poll() is None:
        send("quit")
        try:
            process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
    stop_server()
    log = os.path.join(args.work, "session.log")
    if os.path.exists(log):
        print("--- session log\n" + open(log).read().rstrip())
    if failures:
        with lock:
            print("--- the plugin's events\n" + "\n".join("%.3f %s %s" % (e[0] - T0, e[1], e[2].get("passes"))
                                                         for e in events[-40:]))
        print("--- paraview's stderr (last lines)\n" + "\n".join(stderr_tail[-20:]))
        print("FAIL: %d check(s) failed: %s" % (len(failures), "; ".join(failures)))
        sys.exit(1)
    print("PASS")
    sys.exit(0)


def wait_for(what, condition, timeout):
    """Polls condition() until it returns a true value; fails with `what` after timeout s."""
    end = time.time() + timeout
    while time.time() < end:
        value = condition()
        if value:
            return value
        if process.poll() is not None:
            fatal("paraview exited (status %s) while waiting for %s" % (process.returncode, what))
        time.sleep(0.05)
    fatal("%s did not happen within %g s" % (what, timeout))


def events_since(t, name=None):
    with lock:
        return [e for e in events if e[0] >= t and (name is None or e[1] == name)]


commands = [0]


def send(text):
    path = os.path.join(args.work, "cmd-%d.txt" % commands[0])
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)
    commands[0] += 1


def read_json(name, timeout=30):
    path = os.path.join(args.work, name)
    wait_for("the session's %s" % name, lambda: os.path.exists(path), timeout)
    return json.load(open(path))


def dump(name):
    send("dump " + name)
    read_json("dumped-%s.json" % name)
    return os.path.join(args.work, name + ".npz")


def xdo(*words):
    subprocess.run(["xdotool"] + [str(w) for w in words], check=True, timeout=30)


def screenshot(name):
    path = os.path.join(args.work, name + ".png")
    subprocess.run(["import", "-window", "root", path], check=True, timeout=60)
    return path


def view_boxes(png):
    """The render views on the screen, left to right, as (x, y, w, h): the blocks of ParaView's
    background colour (0.32, 0.34, 0.43) in a screenshot (the views are not X windows of their own)."""
    import numpy as np

    ppm = subprocess.run(["convert", png, "ppm:-"], stdout=subprocess.PIPE, check=True, timeout=60).stdout
    header = ppm.split(b"\n", 3)  # P6, "w h", maxval, then the pixels
    w, h = map(int, header[1].split())
    pixels = np.frombuffer(header[3], dtype=np.uint8)[: w * h * 3].reshape(h, w, 3).astype(int)
    bg = np.all(np.abs(pixels - np.array([82, 87, 110])) <= 2, axis=2)
    columns = bg.sum(axis=0) > 150
    boxes, x = [], 0
    while x < w:
        if columns[x]:
            x1 = x
            while x1 < w and columns[x1]:
                x1 += 1
            if x1 - x > 100:
                rows = np.nonzero(bg[:, x:x1].sum(axis=1) > 0.3 * (x1 - x))[0]
                boxes.append((x, int(rows.min()), x1 - x, int(rows.max() - rows.min() + 1)))
            x = x1
        else:
            x += 1
    return boxes


def drag(box, dx, steps, pause=0.04):
    """A left-button drag through the middle of `box` (x, y, w, h), dx pixels to the right."""
    x0, y0 = box[0] + box[2] // 2 - dx // 2, box[1] + box[3] // 2
    xdo("mousemove", x0, y0)
    time.sleep(0.2)
    xdo("mousedown", 1)
    for i in range(1, steps + 1):
        xdo("mousemove", x0 + dx * i // steps, y0)
        time.sleep(pause)
    xdo("mouseup", 1)


# -- the GUI comes up with the pipeline built
ready = read_json("ready.json", timeout=120)
say("the session is ready (%s)" % ready["scene"])
window = wait_for("the ParaView main window", lambda: subprocess.run(
    ["xdotool", "search", "--onlyvisible", "--name", "ParaView"], stdout=subprocess.PIPE,
    universal_newlines=True).stdout.split(), 60)[0]
xdo("windowmove", "--sync", window, 0, 0)
xdo("windowsize", "--sync", window, 1280, 1000)
xdo("windowactivate", "--sync", window)
time.sleep(1.0)

xdo("key", "--clearmodifiers", "ctrl+space")
time.sleep(1.0)
xdo("type", "--delay", "60", "Schlieren Image")
time.sleep(1.0)
xdo("key", "--clearmodifiers", "Return")
read_json("configured.json", timeout=60)
time.sleep(0.5)
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
