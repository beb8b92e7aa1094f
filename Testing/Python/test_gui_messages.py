# SPDX-License-Identifier: BSD-3-Clause
"""What the GUI says, by real key and mouse events: honest contrast, the model's units, one message
per error, no view left behind.

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_gui_messages.py \\
        --paraview paraview --pvpython pvpython --plugin <Schlieren.so> --work <folder>

The harness of test_gui_body_faces.py; gui_messages_session.py builds the Exodus reactor with
its Pres read as an absolute pressure in Pa under Model Automatic (n - 1 about 1e-11) and the
blunt fin's PLOT3D reader. As a user: searches the Properties panel of RefractiveIndex1 for
"pressure offset" and "density reference" (shown under Model Automatic), makes a Schlieren Image
by quick launch, types Resolution 1 1 and applies (one error naming Resolution, 1 x 1 and the
least allowed 2 x 2; none of the pipeline's "returned failure" lines; no image view opened),
types 96 96 and applies (the view opens; one warning: the largest deflection below 1e-7 rad,
with the automatic scale's full-contrast deflection), deletes the image with the
panel's Delete (its view goes, the layout back to one view), selects the
PLOT3D reader (the greyed Schlieren Image entry's tip says to apply RefractiveIndex first).
Skipped (exit 0, a message) without ../shared/data.
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
settings = {}
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


command = [args.paraview, "--dr", "--script=" + os.path.join(here, "gui_messages_session.py")]
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
messages = []  # (time, "message"/"hint", type or action, text)
events = []  # (time, event, fields) from the plugin's SCHLIEREN_GUI_TRACE lines
stderr_tail = []
lock = threading.Lock()


def read_stderr():
    for line in process.stderr:
        if line.startswith("schlieren-gui ") and line.split()[2] in ("message", "hint"):
            parts = line.split()
            from urllib.parse import unquote
            with lock:
                messages.append((float(parts[1]), parts[2], parts[3],
                                 unquote(parts[4]) if len(parts) > 4 else ""))
        elif line.startswith("schlieren-gui "):
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


def field_boxes(png):
    """The centres of the white line edits of the Properties panel below its search box, in reading
    order (rows of two: x min, x max; y min, y max; z min, z max), from a screenshot."""
    import numpy as np

    ppm = subprocess.run(["convert", png, "ppm:-"], stdout=subprocess.PIPE, check=True, timeout=60).stdout
    header = ppm.split(b"\n", 3)
    w, h = map(int, header[1].split())
    pixels = np.frombuffer(header[3], dtype=np.uint8)[: w * h * 3].reshape(h, w, 3)
    white = np.all(pixels[:, :300] == 255, axis=2)
    boxes = []
    y = 560  # below the search box
    while y < 900:
        runs = white[y]
        if runs.sum() > 40:
            y1 = y
            while y1 < 900 and white[y1].sum() > 40:
                y1 += 1
            if y1 - y >= 10:
                row = white[(y + y1) // 2]
                x = 0
                while x < 300:
                    if row[x]:
                        x1 = x
                        while x1 < 300 and row[x1]:
                            x1 += 1
                        if x1 - x > 30:
                            boxes.append(((x + x1) // 2, (y + y1) // 2))
                        x = x1
                    x += 1
            y = y1
        y += 1
    return boxes


def messages_since(t, kind="message"):
    with lock:
        return [m for m in messages if m[0] >= t and m[1] == kind]


def state(tag):
    send("state " + tag)
    return read_json("state-%s.json" % tag, timeout=60)


def search_panel(text):
    """Types `text` into the Properties panel's search box; returns the line edits it shows."""
    xdo("mousemove", 130, 539)
    xdo("click", 1)
    xdo("key", "--clearmodifiers", "ctrl+a")
    xdo("type", "--delay", "50", text)
    time.sleep(0.8)
    return field_boxes(screenshot("search-" + text.replace(" ", "_")))


def type_fields(fields, values):
    for (x, y), value in zip(fields, values):
        xdo("mousemove", x, y)
        xdo("click", 1)
        xdo("key", "--clearmodifiers", "ctrl+a")
        xdo("type", "--delay", "40", str(value))
        time.sleep(0.2)


# -- the GUI comes up with the reactor's RefractiveIndex (Model Automatic) built
ready = read_json("ready.json", timeout=120)
if not ready.get("scene"):
    say("SKIP: no reactor data (disk_out_ref.ex2) in %s" % os.path.abspath(data))
    sys.exit(0)
window = wait_for("the ParaView main window", lambda: subprocess.run(
    ["xdotool", "search", "--onlyvisible", "--name", "ParaView"], stdout=subprocess.PIPE,
    universal_newlines=True).stdout.split(), 60)[0]
xdo("windowmove", "--sync", window, 0, 0)
xdo("windowsize", "--sync", window, 1280, 1000)
xdo("windowactivate", "--sync", window)
time.sleep(1.0)
first = state("start")
with lock:
    shown = [e for e in events if e[1] == "output-shown"]
check(len(shown) == 1, "Model Automatic's choice opened the Output Messages (%d time(s))" % len(shown))
screenshot("gui_messages_choice")
check(first["index_model"] == "Automatic", "RefractiveIndex1's Model is Automatic (%s)" % first["index_model"])
notes = first["index_notes"] or ""
check("Gas: air (Gas Custom, whose defaults are air's" in notes and "unless set otherwise" not in notes
      and "PressureOffset (0): an absolute pressure" in notes,
      "the model's note says the gas and the units plainly: %r" % notes)

# 1. under Model Automatic the panel shows the controls that fix the units
for text in ("pressure offset", "density reference", "pressure unit"):
    fields = search_panel(text)
    check(len(fields) >= 1, "the panel's search for %r shows %d field(s) under Model Automatic" % (text, len(fields)))
xdo("key", "--clearmodifiers", "ctrl+a")
xdo("key", "--clearmodifiers", "BackSpace")

# 2. a Schlieren Image with Resolution 1 x 1: one error, naming the property, the value, the least
xdo("key", "--clearmodifiers", "ctrl+space")
time.sleep(1.0)
xdo("type", "--delay", "60", "Schlieren Image")
time.sleep(1.0)
xdo("key", "--clearmodifiers", "Return")
wait_for("the Schlieren Image in the pipeline", lambda: state("made-%d" % len(messages))["image"], 30)
# the first row: Resolution's two fields (Interactive Scale's documentation matches too, below)
fields = search_panel("resolution")[:2]
if len(fields) != 2:
    fatal("the panel does not show Resolution as two fields (%d found)" % len(fields))
type_fields(fields, (1, 1))
t = time.time()
xdo("key", "--clearmodifiers", "alt+a")
time.sleep(6.0)
errors = [m for m in messages_since(t) if m[2] == "2"]
say("messages after the Apply: %s" % [m[3][:160] for m in messages_since(t)])
wanted = "Resolution is 1 x 1 pixels: each side must be 2 to 16384 pixels (at least 2 x 2)."
check(len(errors) == 1 and wanted in errors[0][3],
      "one error in the Output Messages, %r (%d errors)" % (wanted, len(errors)))
check(not [m for m in messages_since(t) if "returned failure" in m[3]],
      "none of the pipeline's 'returned failure for request' lines")
failed = state("failed")
check(failed["views"] == 1 and not failed["image_points"],
      "the failed image opens no view: %d view(s), %s points" % (failed["views"], failed["image_points"]))
shot_error = screenshot("gui_messages_error")

# 3. Resolution 96 x 96: the image in its view, and one warning says the contrast is not real
fields = search_panel("resolution")[:2]
type_fields(fields, (96, 96))
t = time.time()
xdo("key", "--clearmodifiers", "alt+a")
end, n = time.time() + 90, 0
while time.time() < end and not state("wait-%d" % n)["image_points"]:
    n += 1
    time.sleep(0.5)
time.sleep(4.0)
traced = state("traced")
f = traced["field"]
say("the image: max_deflection %s rad, full_contrast_deflection %s rad, cutoff_scale %s, passes %s"
    % (f.get("max_deflection"), f.get("full_contrast_deflection"), f.get("cutoff_scale"), f.get("passes")))
check(traced["views"] == 2 and events_since(t, "opened"),
      "the Apply that made an image opened its view: %d views" % traced["views"])
check(0 < float(f["max_deflection"]) < 1e-7, "the largest deflection %s rad is below 1e-7 rad" % f["max_deflection"])
check(abs(float(f["full_contrast_deflection"]) * float(f["cutoff_scale"]) - 0.5) < 1e-4,
      "full_contrast_deflection = 0.5 / cutoff_scale (knife edge)")
weak = [m for m in messages_since(t) if "below the about 1e-07 rad that a sensitive laboratory" in m[3]]
check(len(weak) == 1 and weak[0][2] == "1", "the Output Messages warn of the weak field once (%d time(s))" % len(weak))
if weak:
    w = weak[-1][3]
    check(all(s in w for s in ("PressureUnit", "PressureOffset", "DensityReference", "PLOT3D", "Gas",
                               "stretched %s rad to full contrast" % "")) or
          all(s in w for s in ("PressureUnit", "PressureOffset", "DensityReference", "PLOT3D", "Gas", "to full contrast")),
          "the warning names the causes and the properties: %r" % w[:400])
check(traced["field"].get("warnings", "").startswith("The largest deflection over the film is"),
      "field data warnings holds it")
time.sleep(1.0)
shot_weak = screenshot("gui_messages_weak")

# 4. Delete the image (Edit > Delete, the Delete key in the pipeline browser): its view goes too
xdo("mousemove", 214, 508)  # the Properties panel's Delete button (SchlierenImage1 is active)
xdo("click", 1)
time.sleep(3.0)
gone = state("deleted")
check(not gone["image"] and gone["views"] == 1,
      "after the image is deleted: image %s, %d view(s)" % (gone["image"], gone["views"]))
screenshot("gui_messages_deleted")

# 5. the PLOT3D reader selected: the greyed Schlieren Image entry says what to do
if ready.get("plot3d"):
    t = time.time()
    send("select bluntfin")
    read_json("selected-bluntfin.json")
    time.sleep(1.0)
    # ParaView sets the entries' state and tips when the menu opens: Filters, by a click
    xdo("mousemove", 216, 10)
    xdo("click", 1)
    time.sleep(1.5)
    screenshot("gui_messages_filters_menu")
    xdo("key", "Escape")
    time.sleep(0.5)
    hints = [m for m in messages_since(t, "hint")]
    say("menu hints: %s" % [(h[2], h[3]) for h in hints])
    check(any("apply RefractiveIndex first" in h[3] and h[3].startswith("Input must be") for h in hints),
          "the greyed Schlieren Image entry's tip says to apply RefractiveIndex first")
if args.screenshots:
    os.makedirs(args.screenshots, exist_ok=True)
    for p in (shot_error, shot_weak):
        shutil.copy(p, args.screenshots)
finish()
