# SPDX-License-Identifier: BSD-3-Clause
"""The installed plugin in ParaView's Plugin Manager, opened by a user's keys.

Run with Debian's Python under an X server with a window manager, after test_install.py has
installed into <prefix> (ctest: the fixture schlieren_install):

    SCHLIEREN_XVFB_WM=openbox Testing/with_xvfb.sh /usr/bin/python3 test_install_gui.py \\
        --paraview paraview --prefix <prefix> --libdir lib --work <folder>

Starts `paraview` as a user of the installed prefix starts it (PV_PLUGIN_CONFIG_FILE=<prefix>/
<libdir>/paraview-X.Y/plugins/Schlieren.plugins, nothing of the build tree in the environment, a
fresh HOME so that no earlier session's settings list the plugin), then with xdotool's X key events:
Alt+T opens the Tools menu, Down x3 + Return opens "Manage Plugins..."; in the dialog the user types
"vtkPV" (the tree's keyboard search selects ParaView's own vtkPVInitializerPlugin),
then "Schl", then Right (expands the row). It checks:
  1. a window titled "Plugin Manager" appeared after the keys (xdotool search --name);
  2. the selection moved by whole rows when "Schl" was typed: a row whose name starts with
     "Schl" is listed (the tree's keyboard search selects nothing else; the row band is found in
     screenshots by the selection colour; how far it moves depends on the other plugins listed:
     none in 5.11, every plugin ParaView ships in 5.13, sorted by name);
  3. the plugin's GUI part ran: its toolbar printed "toolbar created" (SCHLIEREN_GUI_TRACE=1), so
     ParaView loaded the Schlieren.so it found from the name in the list;
  4. after Ctrl+Q, the settings file ParaView writes lists Schlieren with the installed
     Schlieren.so as its file (the Plugin Manager's list, saved by the GUI itself).
Screenshots (`import -window root`) go to <work>: plugin_manager.png shows the expanded row
(Loaded, Location in the prefix). Exit status 0 on success; each failure says what did not happen.
"""
import argparse
import ctypes
import glob
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import numpy as np

parser = argparse.ArgumentParser()
parser.add_argument("--paraview", required=True)
parser.add_argument("--prefix", required=True, help="the prefix test_install.py installed into")
parser.add_argument("--libdir", required=True, help="CMAKE_INSTALL_LIBDIR, relative to the prefix")
parser.add_argument("--paraview-subdir", required=True,
                    help="paraview-<major>.<minor> of the ParaView built against (CMake's SCHLIEREN_PARAVIEW_SUBDIR)")
parser.add_argument("--work", required=True, help="a folder for the session's files (emptied)")
args = parser.parse_args()

T0 = time.time()
failures = []
prefix = os.path.abspath(args.prefix)
plugins_file = os.path.join(prefix, args.libdir, args.paraview_subdir, "plugins", "Schlieren.plugins")
plugin_so = os.path.join(prefix, args.libdir, args.paraview_subdir, "plugins", "Schlieren", "Schlieren.so")
SELECTION = np.array([48, 140, 198])  # Qt's Fusion selection colour for the current row


def say(text):
    print("[%6.1f s] %s" % (time.time() - T0, text))
    sys.stdout.flush()


def check(condition, message):
    say(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)
    return condition


for tool in ("xdotool", "import", "convert"):
    if shutil.which(tool) is None:
        print("FAIL: %s is needed (apt-get install xdotool imagemagick)" % tool)
        sys.exit(1)
if not os.environ.get("DISPLAY"):
    print("FAIL: no DISPLAY (run under Testing/with_xvfb.sh with SCHLIEREN_XVFB_WM=openbox)")
    sys.exit(1)
if not os.path.exists(plugins_file) or not os.path.exists(plugin_so):
    print("FAIL: %s or %s is missing: run test_install.py first (ctest fixture schlieren_install)"
          % (plugins_file, plugin_so))
    sys.exit(1)
if os.path.isdir(args.work):
    shutil.rmtree(args.work)
home = os.path.join(args.work, "home")
os.makedirs(home)

env = dict(os.environ, HOME=home, XDG_CONFIG_HOME=os.path.join(home, ".config"),
           PV_PLUGIN_CONFIG_FILE=plugins_file, SCHLIEREN_GUI_TRACE="1")
for name in ("SCHLIEREN_PLUGIN", "PV_PLUGIN_PATH", "PYTHONPATH"):
    env.pop(name, None)


def die_with_parent():
    """Runs in the child before exec: SIGKILL it when this driver dies, however it dies."""
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


log = open(os.path.join(args.work, "paraview.log"), "w")
process = subprocess.Popen([args.paraview, "--dr"], env=env, stdout=log, stderr=subprocess.STDOUT,
                           preexec_fn=die_with_parent)


def on_term(signum, frame):
    if process.poll() is None:
        process.kill()
    sys.exit(1)


signal.signal(signal.SIGTERM, on_term)
signal.signal(signal.SIGINT, on_term)


def finish():
    if process.poll() is None:
        process.kill()
        process.wait()
    if failures:
        log.flush()
        print("--- paraview's output (last lines)\n" + "".join(open(log.name).readlines()[-20:]))
        print("FAIL: %d check(s) failed: %s" % (len(failures), "; ".join(failures)))
        sys.exit(1)
    print("PASS")
    sys.exit(0)


def fatal(message):
    check(False, message)
    try:
        say("the screen at the failure: %s" % screenshot("failure"))
    except Exception as e:  # the screenshot is a help, not a check
        say("no screenshot: %s" % e)
    finish()


def xdo(*words):
    return subprocess.run(["xdotool"] + [str(w) for w in words], check=True, timeout=30,
                          stdout=subprocess.PIPE, universal_newlines=True).stdout


def windows(name):
    return subprocess.run(["xdotool", "search", "--onlyvisible", "--name", name], stdout=subprocess.PIPE,
                          universal_newlines=True, timeout=30).stdout.split()


def wait_for(what, condition, timeout):
    end = time.time() + timeout
    while time.time() < end:
        value = condition()
        if value:
            return value
        if process.poll() is not None:
            fatal("paraview exited (status %s) while waiting for %s" % (process.returncode, what))
        time.sleep(0.1)
    fatal("%s did not happen within %g s" % (what, timeout))


def screenshot(name):
    path = os.path.join(args.work, name + ".png")
    subprocess.run(["import", "-window", "root", path], check=True, timeout=60)
    return path


def selection_rows(png, box):
    """The rows (y) inside box (x, y, w, h) that the selection colour fills for 100+ pixels."""
    ppm = subprocess.run(["convert", png, "ppm:-"], stdout=subprocess.PIPE, check=True, timeout=60).stdout
    header = ppm.split(b"\n", 3)  # P6, "w h", maxval, then the pixels
    w, h = map(int, header[1].split())
    pixels = np.frombuffer(header[3], dtype=np.uint8)[: w * h * 3].reshape(h, w, 3).astype(int)
    x, y, bw, bh = box
    inside = pixels[y:y + bh, x:x + bw]
    hit = np.all(np.abs(inside - SELECTION) <= 2, axis=2).sum(axis=1) >= 100
    return [y + int(r) for r in np.nonzero(hit)[0]]


# -- the main window
main = wait_for("the ParaView main window", lambda: windows("^ParaView"), 90)[0]
xdo("windowmove", "--sync", main, 0, 0)
xdo("windowsize", "--sync", main, 1200, 900)
xdo("windowactivate", "--sync", main)
time.sleep(2.0)  # the GUI finishes building its menus and toolbars

# -- 1. Tools > Manage Plugins... with the keyboard
xdo("key", "--clearmodifiers", "alt+t")
time.sleep(1.0)
say("Tools menu: %s" % screenshot("tools_menu"))
xdo("key", "Down", "Down", "Down", "Return")  # Add Camera Link (the first enabled item) -> Manage Plugins...
dialog = wait_for('a window titled "Plugin Manager" after Alt+T, Down x3, Return',
                  lambda: windows("^Plugin Manager$"), 20)[0]
check(True, 'the keys opened a window titled "Plugin Manager" (X window %s)' % dialog)
geometry = dict(line.split("=") for line in xdo("getwindowgeometry", "--shell", dialog).split())
box = tuple(int(geometry[k]) for k in ("X", "Y", "WIDTH", "HEIGHT"))
say("the dialog is at %s" % (box,))
time.sleep(1.0)

# -- 2. the tree's keyboard search: "vtkPV" selects vtkPVInitializerPlugin, "Schl" the row named Schl...
xdo("type", "--delay", "80", "vtkPV")
time.sleep(1.0)  # longer than Qt's keyboard-search interval: the next letters start a new search
first = selection_rows(screenshot("select_first"), box)
xdo("type", "--delay", "80", "Schl")
time.sleep(1.0)
second = selection_rows(screenshot("select_schlieren"), box)
xdo("key", "Right")
time.sleep(1.0)
say("the Plugin Manager with Schlieren expanded: %s" % screenshot("plugin_manager"))
say("selected rows: after 'vtkPV' y = %s..%s, after 'Schl' y = %s..%s"
    % (first[:1], first[-1:], second[:1], second[-1:]))
if check(first and second, "a row is selected after each search (the selection colour in the dialog)"):
    # where the row lies depends on what else the Plugin Manager lists: 5.11 lists Schlieren
    # and vtkPVInitializerPlugin alone (Schlieren one row above ... below), 5.13 every plugin
    # ParaView ships, sorted by name (Schlieren six rows above vtkPVInitializerPlugin). The
    # search selects only a row whose name starts with what was typed: a move by whole rows
    height = first[-1] - first[0] + 1
    moved = second[0] - first[0]
    rows = round(moved / float(height))
    check(rows != 0 and abs(moved - rows * height) <= 2 * max(1, abs(rows)),
          "typing 'Schl' moved the selection by %d row(s) (%d px, a row is %d px): the Plugin "
          "Manager lists a plugin whose name starts with Schl" % (rows, moved, height))

# -- 3, 4. close the dialog and quit; the GUI saves its plugin list
xdo("key", "Escape")
wait_for("the Plugin Manager closing on Escape", lambda: not windows("^Plugin Manager$"), 10)
xdo("windowactivate", "--sync", main)
xdo("key", "--clearmodifiers", "ctrl+q")
try:
    process.wait(timeout=30)
except subprocess.TimeoutExpired:
    fatal("paraview did not quit within 30 s of Ctrl+Q")
check(process.returncode == 0, "paraview quit on Ctrl+Q (exit status %d)" % process.returncode)
log.flush()
check(re.search(r"^schlieren-gui \S+ toolbar created$", open(log.name).read(), re.M) is not None,
      "the plugin's toolbar was created in the GUI (its 'toolbar created' trace line)")
settings = glob.glob(os.path.join(home, ".config", "ParaView", "*.ini"))
text = "".join(open(f, errors="replace").read() for f in settings)
listed = re.findall(r'name=\\"Schlieren\\" filename=\\"([^"\\]*)\\"', text)
check(os.path.realpath(plugin_so) in [os.path.realpath(p) for p in listed],
      "the settings ParaView wrote (%s) list Schlieren at the installed %s (listed: %s)"
      % (", ".join(os.path.basename(f) for f in settings) or "none", plugin_so, listed))
finish()
