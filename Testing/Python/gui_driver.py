# SPDX-License-Identifier: BSD-3-Clause
"""The harness the GUI tests share: a real `paraview` under an X server with a window manager, driven
by real key and mouse events (xdotool), watched through screenshots (ImageMagick's `import`) and the
plugin's event lines on paraview's stderr (SCHLIEREN_GUI_TRACE=1).

A test makes one Driver, which parses the common options (--paraview --pvpython --plugin --work
[--screenshots] [--pvserver], plus the test's own), empties the work folder and checks the tools;
`launch` starts paraview with a session script (its --script: it builds the pipeline and answers the
driver's commands, see gui_drag_session.py) and, with --pvserver, a pvserver on a free localhost port
that the GUI connects to. Every child dies with the driver (PDEATHSIG) and on every exit path.

    gd = gui_driver.Driver(__doc__)
    gd.launch("gui_drag_session.py", settings={"image": dict(Resolution=[160, 160])})
    ready = gd.read_json("ready.json", timeout=120)
    window = gd.main_window()
    ...
    gd.check(condition, "what must hold")
    gd.finish()          # quits paraview, prints the session's log, exits 0 or 1

The session script and the driver talk through files in the work folder: the driver writes
cmd-<k>.txt (`send`), the session writes <name>.json (`read_json`) and dumps images (`dump`).
"""
import argparse
import atexit
import ctypes
import json
import os
import random
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from urllib.parse import unquote

HERE = os.path.dirname(os.path.abspath(__file__))
# ParaView's render-view background (0.32, 0.34, 0.43) in 8 bits: how views are found on the screen
VIEW_BACKGROUND = (82, 87, 110)


def read_ppm(png):
    """A screenshot's pixels as a (h, w, 3) int array (through ImageMagick's convert)."""
    import numpy as np

    ppm = subprocess.run(["convert", png, "ppm:-"], stdout=subprocess.PIPE, check=True, timeout=60).stdout
    header = ppm.split(b"\n", 3)  # P6, "w h", maxval, then the pixels
    w, h = map(int, header[1].split())
    return np.frombuffer(header[3], dtype=np.uint8)[: w * h * 3].reshape(h, w, 3).astype(int)


def view_boxes(png):
    """The render views on the screen, left to right, as (x, y, w, h): the blocks of ParaView's
    background colour in a screenshot (the views are not X windows of their own)."""
    import numpy as np

    pixels = read_ppm(png)
    h, w = pixels.shape[:2]
    bg = np.all(np.abs(pixels - np.array(VIEW_BACKGROUND)) <= 2, axis=2)
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


def field_boxes(png):
    """The centres of the white line edits of the Properties panel below its search box, in reading
    order (rows of two: x min, x max; y min, y max; z min, z max), from a screenshot."""
    import numpy as np

    pixels = read_ppm(png)
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


def die_with_parent():
    """Runs in the child before exec: SIGKILL it when the driver dies, however it dies."""
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


class Driver:
    def __init__(self, description=None, add_arguments=None):
        """Parses the options (add_arguments(parser) adds the test's own), empties --work and checks
        that the X tools and a DISPLAY are there (a failure says which package to install)."""
        parser = argparse.ArgumentParser(description=description,
                                         formatter_class=argparse.RawDescriptionHelpFormatter)
        parser.add_argument("--paraview", required=True)
        parser.add_argument("--pvpython", required=True)
        parser.add_argument("--plugin", required=True)
        parser.add_argument("--work", required=True, help="a folder for the session's files (emptied)")
        parser.add_argument("--screenshots", default=None, help="also copy the screenshots here")
        parser.add_argument("--pvserver", default=None,
                            help="client/server mode: run the pipeline on this pvserver (a free localhost port)")
        parser.add_argument("--ranks", type=int, default=1,
                            help="with --pvserver: start it under --mpiexec with this many ranks")
        parser.add_argument("--mpiexec", default="mpiexec", help="the MPI launcher for --ranks > 1")
        if add_arguments:
            add_arguments(parser)
        self.args = parser.parse_args()
        self.T0 = time.time()
        self.failures = []
        self.process = None
        self.server = None
        self.events = []  # (time, event, fields) from the plugin's SCHLIEREN_GUI_TRACE lines
        self.messages = []  # (time, "message"/"hint", type or action, text)
        self.stderr_tail = []
        self.lock = threading.Lock()
        self.commands = 0
        work = self.args.work
        if os.path.isdir(work):
            shutil.rmtree(work)
        os.makedirs(work)
        for tool in ("xdotool", "xwininfo", "import"):
            if shutil.which(tool) is None:
                print("FAIL: %s is needed (apt-get install xdotool x11-utils imagemagick)" % tool)
                sys.exit(1)
        if not os.environ.get("DISPLAY"):
            print("FAIL: no DISPLAY (run under Testing/with_xvfb.sh with SCHLIEREN_XVFB_WM=openbox)")
            sys.exit(1)
        self.data = os.environ.get("SCHLIEREN_DATA", os.path.join(HERE, "..", "..", "..", "shared", "data"))

    # -- reporting
    def say(self, text):
        print("[%6.1f s] %s" % (time.time() - self.T0, text))
        sys.stdout.flush()

    def check(self, condition, message):
        self.say(("ok   " if condition else "FAIL ") + message)
        if not condition:
            self.failures.append(message)
        return condition

    def fatal(self, message):
        self.check(False, message)
        try:
            self.say("the screen at the failure: %s" % self.screenshot("failure"))
        except Exception as e:  # the screenshot is a help, not a check
            self.say("no screenshot: %s" % e)
        self.finish()

    # -- the processes
    def launch(self, session_script, settings=None, env=None, paraview_args=()):
        """Starts paraview (and with --pvserver the server) with session_script as its --script;
        settings go to the session as settings.json, env is added to the environment of both."""
        with open(os.path.join(self.args.work, "settings.json"), "w") as f:
            json.dump(settings or {}, f)
        self.env = dict(os.environ, PV_PLUGIN_PATH=os.path.dirname(os.path.abspath(self.args.plugin)),
                        SCHLIEREN_GUI_TRACE="1", SCHLIEREN_GUI_WORK=self.args.work, SCHLIEREN_DATA=self.data,
                        SCHLIEREN_GUI_HERE=HERE, **(env or {}))
        self.env.pop("SCHLIEREN_PLUGIN", None)  # the session must not load the plugin itself
        command = [self.args.paraview, "--dr", "--script=" + os.path.join(HERE, session_script)]
        command[1:1] = list(paraview_args)
        if self.args.pvserver:
            command.insert(1, "--server-url=cs://localhost:%d" % self._start_server())
        self.say(" ".join(command))
        self.process = subprocess.Popen(command, env=self.env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                        universal_newlines=True, bufsize=1, preexec_fn=die_with_parent)
        atexit.register(self._kill_children)
        signal.signal(signal.SIGTERM, self._on_term)
        signal.signal(signal.SIGINT, self._on_term)
        threading.Thread(target=self._read_stderr, daemon=True).start()
        return self.process

    def _start_server(self):
        """A pvserver on a free localhost port (tried until one binds); returns its port."""
        for attempt in range(8):
            port = random.randint(20000, 40000)
            with socket.socket() as probe:
                try:
                    probe.bind(("127.0.0.1", port))
                except OSError:
                    continue
            log = open(os.path.join(self.args.work, "pvserver-%d.log" % attempt), "w")
            command = [self.args.pvserver, "--server-port=%d" % port, "--hostname=localhost"]
            if self.args.ranks > 1:
                # root needs --allow-run-as-root; past the cores, ranks share them (--oversubscribe)
                launcher = [self.args.mpiexec, "-n", str(self.args.ranks), "--oversubscribe"]
                if os.getuid() == 0:
                    launcher.insert(1, "--allow-run-as-root")
                command = launcher + command
            self.say(" ".join(command))
            self.server = subprocess.Popen(command, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                                           preexec_fn=die_with_parent)
            end = time.time() + 60
            while time.time() < end and self.server.poll() is None:
                if "Accepting connection" in open(log.name).read():
                    self.say("pvserver (pid %d) listens on localhost:%d" % (self.server.pid, port))
                    return port
                time.sleep(0.1)
            self.say("pvserver on port %d did not start: %s" % (port, open(log.name).read().strip()[-300:]))
            self.stop_server()
        print("FAIL: no pvserver could be started (%s)" % self.args.pvserver)
        sys.exit(1)

    def stop_server(self):
        if self.server is not None and self.server.poll() is None:
            self.server.terminate()
            try:
                self.server.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.server.kill()
                self.server.wait()

    def _on_term(self, signum, frame):
        # ctest's timeout or with_xvfb.sh's cleanup: end the GUI and the server before going
        for p in (self.process, self.server):
            if p is not None and p.poll() is None:
                p.kill()
        sys.exit(1)

    def _kill_children(self):
        # an exception anywhere in the driver: no GUI or server left behind
        for p in (self.process, self.server):
            if p is not None and p.poll() is None:
                p.kill()
                p.wait()

    def _read_stderr(self):
        for line in self.process.stderr:
            parts = line.split()
            traced = len(parts) > 2 and parts[0] == "schlieren-gui"
            if traced:
                try:
                    float(parts[1])
                except ValueError:  # not the trace format: kept as stderr, never the reader's end
                    traced = False
            if traced:
                if parts[2] in ("message", "hint"):
                    with self.lock:
                        self.messages.append((float(parts[1]), parts[2], parts[3],
                                              unquote(parts[4]) if len(parts) > 4 else ""))
                else:
                    fields = dict(p.split("=", 1) for p in parts[4:] if "=" in p)
                    with self.lock:
                        self.events.append((float(parts[1]), parts[2], fields))
            else:
                self.stderr_tail.append(line.rstrip())
                del self.stderr_tail[:-40]

    def finish(self):
        """Quits paraview and the server, prints the session's log; exits 0, or 1 with the failures."""
        if self.process is not None and self.process.poll() is None:
            self.send("quit")
            try:
                self.process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.stop_server()
        log = os.path.join(self.args.work, "session.log")
        if os.path.exists(log):
            print("--- session log\n" + open(log).read().rstrip())
        if self.failures:
            with self.lock:
                print("--- the plugin's events\n" + "\n".join(
                    "%.3f %s %s" % (e[0] - self.T0, e[1], e[2].get("passes")) for e in self.events[-40:]))
            print("--- paraview's stderr (last lines)\n" + "\n".join(self.stderr_tail[-20:]))
            print("FAIL: %d check(s) failed: %s" % (len(self.failures), "; ".join(self.failures)))
            sys.exit(1)
        print("PASS")
        sys.exit(0)

    # -- waiting and talking to the session
    def wait_for(self, what, condition, timeout):
        """Polls condition() until it returns a true value; fails with `what` after timeout s."""
        end = time.time() + timeout
        while time.time() < end:
            value = condition()
            if value:
                return value
            if self.process.poll() is not None:
                self.fatal("paraview exited (status %s) while waiting for %s" % (self.process.returncode, what))
            time.sleep(0.05)
        self.fatal("%s did not happen within %g s" % (what, timeout))

    def events_since(self, t, name=None):
        with self.lock:
            return [e for e in self.events if e[0] >= t and (name is None or e[1] == name)]

    def messages_since(self, t, kind="message"):
        with self.lock:
            return [m for m in self.messages if m[0] >= t and m[1] == kind]

    def quick_launch(self, label="Schlieren Image", configured=True):
        """As a user makes a filter: Ctrl+Space (ParaView's quick launch), the label typed, Return;
        it applies to the active source. With `configured`, waits until the session has set the
        test's settings on the new image (gui_drag_session.py writes configured.json)."""
        self.xdo("key", "--clearmodifiers", "ctrl+space")
        time.sleep(1.0)
        self.xdo("type", "--delay", "60", label)
        time.sleep(1.0)
        self.xdo("key", "--clearmodifiers", "Return")
        if configured:
            self.read_json("configured.json", timeout=60)
            time.sleep(0.5)

    def send(self, text):
        path = os.path.join(self.args.work, "cmd-%d.txt" % self.commands)
        with open(path + ".tmp", "w") as f:
            f.write(text)
        os.replace(path + ".tmp", path)
        self.commands += 1

    def read_json(self, name, timeout=30):
        path = os.path.join(self.args.work, name)
        self.wait_for("the session's %s" % name, lambda: os.path.exists(path), timeout)
        return json.load(open(path))

    def dump(self, name):
        self.send("dump " + name)
        self.read_json("dumped-%s.json" % name)
        return os.path.join(self.args.work, name + ".npz")

    # -- the X events and the screen
    def xdo(self, *words):
        subprocess.run(["xdotool"] + [str(w) for w in words], check=True, timeout=30)

    def screenshot(self, name):
        path = os.path.join(self.args.work, name + ".png")
        subprocess.run(["import", "-window", "root", path], check=True, timeout=60)
        return path

    def drag(self, box, dx, steps, pause=0.04):
        """A left-button drag through the middle of `box` (x, y, w, h), dx pixels to the right."""
        x0, y0 = box[0] + box[2] // 2 - dx // 2, box[1] + box[3] // 2
        self.xdo("mousemove", x0, y0)
        time.sleep(0.2)
        self.xdo("mousedown", 1)
        for i in range(1, steps + 1):
            self.xdo("mousemove", x0 + dx * i // steps, y0)
            time.sleep(pause)
        self.xdo("mouseup", 1)

    def main_window(self, width=1280, height=1000):
        """The ParaView main window, moved to the top left, sized and activated; its X id."""
        window = self.wait_for("the ParaView main window", lambda: subprocess.run(
            ["xdotool", "search", "--onlyvisible", "--name", "ParaView"], stdout=subprocess.PIPE,
            universal_newlines=True).stdout.split(), 60)[0]
        self.xdo("windowmove", "--sync", window, 0, 0)
        self.xdo("windowsize", "--sync", window, width, height)
        self.xdo("windowactivate", "--sync", window)
        time.sleep(1.0)
        return window
