# SPDX-License-Identifier: BSD-3-Clause
"""The Python plugin (SchlierenPython.py) loaded into Debian's ParaView 5.11 GUI the way a user does
it, with real X events (xdotool) under Xvfb and openbox, and its pipeline's image and property
lists against the C++ plugin's.

    with_xvfb.sh python3 test_gui_python_plugin.py --paraview paraview --pvpython pvpython \\
        --plugin <an empty folder>/none --python-plugin SchlierenPython.py \\
        --cxx-plugin Schlieren.so --reference DIR --work DIR

paraview starts with no plugin (PV_PLUGIN_PATH an empty folder, a fresh HOME) and a session script
(gui_python_plugin_session.py) that runs the getargspec shim docs/PYTHON.md gives. Then:
  1. Alt+T, Down x3, Return opens Tools > Manage Plugins; a click on its "Load New ..." button opens
     the "Load Plugin" file dialog; the path typed there and Return load the .py: the Plugin
     Manager lists it, and ParaView knows RefractiveScene, RefractiveIndex, RefractionOctree and
     SchlierenImage and NumericalSchlieren, none of which it knew before;
  2. Quick Launch (Ctrl+Space) "Refractive Scene" Return, the Gaussian sphere case's settings
     (frontend_cases.py; set by the session, as the user would type them), Apply (Alt+A); the same
     for "Schlieren Image" on it, Backend CPU, then OpenCL where the reference has an OpenCL image;
  3. the image (intensity, deflection: every bit) and its whole field data equal the C++ plugin's
     for that case (frontend_reference.py's files), and the property lists of the GUI's proxies
     equal those the C++ plugin's proxies have in pvpython, less what the Python plugin leaves out
     by name (frontend_cases.PYTHON_PLUGIN_LEFT_OUT).
  4. the blunt fin (PLOT3D, ../shared/data; the part is skipped, said so, without it): the reader
     opened by the session (as File > Open does), Quick Launch "Refractive Index" and Apply; in
     the panel's search box "wall", the six Body Wall Faces fields typed 0 1 1 0 1 1, the mouse
     resting on one of them shows its tooltip (the XML's documentation), Apply: the index finds
     the fin a body (solid points > 0, none before); Quick Launch "Schlieren Image", Apply: dark
     where the fin is; the image shown in a 2D render view beside the 3D one (the session splits
     the layout: the Python plugin cannot add the C++ plugin's Open Image View); Follow Camera
     on, a 160-pixel drag in the 3D view: the line of sight turns, the image is traced again and
     refined, and the 2D view shows the new image.
Screenshots: plugin_manager.png (the .py listed as Loaded), image.png (the pipeline after Apply),
bluntfin_faces.png, bluntfin_tooltip.png, bluntfin_2d.png, bluntfin_follow.png.
"""
import json
import os
import subprocess
import sys
import time

import numpy as np

import gui_driver

sys.path.insert(0, gui_driver.HERE)
import frontend_cases as cases  # noqa: E402


def options(parser):
    parser.add_argument("--python-plugin", required=True)
    parser.add_argument("--cxx-plugin", required=True)
    parser.add_argument("--reference", required=True)


gd = gui_driver.Driver(__doc__, options)
args = gd.args
say, check, fatal, xdo, screenshot = gd.say, gd.check, gd.fatal, gd.xdo, gd.screenshot
home = os.path.join(args.work, "home")  # no earlier session's settings or plugin list
os.makedirs(home)
gd.launch("gui_python_plugin_session.py", env={"HOME": home})
ready = gd.read_json("ready.json", timeout=120)
PROXIES = ["RefractiveScene", "RefractiveIndex", "RefractionOctree", "SchlierenImage", "NumericalSchlieren"]
check(not any(ready["known"].values()), "before the load ParaView knows no Schlieren proxy (%s)"
      % ready["known"])
window = gd.main_window()
polls = [0]


def state():
    polls[0] += 1
    gd.send("state %d" % polls[0])
    return gd.read_json("state-%d.json" % polls[0])


def windows(name):
    return subprocess.run(["xdotool", "search", "--onlyvisible", "--name", name], stdout=subprocess.PIPE,
                          universal_newlines=True).stdout.split()


# -- 1. Tools > Manage Plugins > Load New ..., the path typed into ParaView's file dialog
xdo("key", "--clearmodifiers", "alt+t")
time.sleep(1.0)
xdo("key", "Down", "Down", "Down", "Return")  # Add Camera Link (the first enabled item) -> Manage Plugins...
dialog = gd.wait_for('a window titled "Plugin Manager"', lambda: windows("^Plugin Manager$"), 20)[0]
geometry = dict(line.split("=") for line in subprocess.run(
    ["xdotool", "getwindowgeometry", "--shell", dialog], stdout=subprocess.PIPE,
    universal_newlines=True).stdout.split())
# "Load New ..." sits at the dialog's lower left (its 800 x 600 layout, seen in the screenshots)
xdo("mousemove", int(geometry["X"]) + 65, int(geometry["Y"]) + 513)
xdo("click", 1)
gd.wait_for('the "Load Plugin" file dialog after a click on "Load New ..."', lambda: windows("^Load Plugin$"), 20)
time.sleep(0.5)
xdo("type", "--delay", "20", os.path.abspath(args.python_plugin))
xdo("key", "Return")
known = gd.wait_for("ParaView knowing SchlierenImage after the load",
                    lambda: (lambda s: s["known"] if s["known"]["SchlierenImage"] else None)(state()), 30)
check(all(known[p] for p in PROXIES), "after Load New ParaView knows %s (%s)" % (", ".join(PROXIES), known))
time.sleep(1.0)
shot = screenshot("plugin_manager")
say("the Plugin Manager after the load: %s" % shot)
xdo("key", "Escape")  # closes the Plugin Manager
gd.wait_for("the Plugin Manager closed", lambda: not windows("^Plugin Manager$"), 10)


# -- 2. the pipeline: Quick Launch, the case's settings, Apply
def quick_launch(label, registered):
    xdo("windowactivate", "--sync", window)
    xdo("key", "--clearmodifiers", "ctrl+space")
    time.sleep(1.0)
    xdo("type", "--delay", "60", label)
    time.sleep(1.0)
    xdo("key", "--clearmodifiers", "Return")
    gd.wait_for("%s in the pipeline" % registered, lambda: registered in state()["sources"], 30)


def set_active(props):
    gd.send("set " + json.dumps(props))
    gd.read_json("set-%d.json" % gd.commands)


def apply_and_wait(name):
    xdo("key", "--clearmodifiers", "alt+a")
    return gd.wait_for("%s's output after Apply" % name,
                       lambda: state()["sources"][name]["points"] > 0, 120)


name = "gaussian_sphere"
quick_launch("Refractive Scene", "RefractiveScene1")
set_active(cases.SCENES[name])
apply_and_wait("RefractiveScene1")
quick_launch("Schlieren Image", "SchlierenImage1")
with open(os.path.join(args.reference, "opencl.txt")) as f:
    opencl = f.read().strip()
compared = 0
for backend in cases.BACKENDS:
    ref = np.load(os.path.join(args.reference, "%s_%s.npz" % (name, backend)))
    if "array_intensity" not in ref:
        say("skip %s: the C++ plugin made no image there (OpenCL: %s)" % (backend, opencl))
        continue
    set_active(dict(cases.IMAGES[name], Backend=backend))
    want_backend = [e for e in json.loads(str(ref["field_data"])) if e[0] == "backend"][0]
    if compared:
        xdo("key", "--clearmodifiers", "alt+a")
    else:
        apply_and_wait("SchlierenImage1")
    end, k = time.time() + 60, 0
    while True:  # the image of this Apply: its field data names the backend asked for
        k += 1
        mine = np.load(gd.dump("image_%s_%d" % (backend, k)))
        if want_backend in json.loads(str(mine["field_data"])) or time.time() > end:
            break
        time.sleep(0.5)
    for a in ("intensity", "deflection"):
        m, t = mine.get("array_" + a), ref["array_" + a]
        check(m is not None and m.shape == t.shape and np.array_equal(m.view(np.uint32), t.view(np.uint32)),
              "%s %s: %s bit for bit the C++ plugin's (%s, mean %.6g)" % (name, backend, a, t.shape, float(t.mean())))
    check(np.array_equal(mine["extent"], ref["extent"]) and np.array_equal(mine["origin"], ref["origin"]),
          "%s %s: the film's extent and origin" % (name, backend))
    fd_mine, fd_ref = json.loads(str(mine["field_data"])), json.loads(str(ref["field_data"]))
    if compared:
        # this filter's session traced the same input before on the other backend and traces
        # its packed volume again (the C++ reference is a fresh filter per backend, which packs):
        # the volume kept, none cached beside it, one packed in all
        counters = {e[0]: e[2] for e in fd_mine if e[0] in ("volumes_cached", "volumes_packed",
                                                            "volume_from")}
        check(counters == {"volumes_cached": ["0.0"], "volumes_packed": ["1.0"], "volume_from": ["kept"]},
              "%s %s: the session keeps the first backend's volume (%s)" % (name, backend, counters))
        fd_mine = [e for e in fd_mine if e[0] not in counters]
        fd_ref = [e for e in fd_ref if e[0] not in counters]
    check(fd_mine == fd_ref, "%s %s: the field data equals the C++ plugin's (%d entries; differing: %s)"
          % (name, backend, len(fd_ref), [(a, b) for a, b in zip(fd_mine, fd_ref) if a != b][:3]))
    compared += 1
check(compared >= 1, "images compared: %d" % compared)
shot = screenshot("image")
say("the pipeline after Apply: %s" % shot)

# -- 2b. Follow Camera from the panel's property (no Python typed): a mouse drag in the 3D view
# turns the image's line of sight with the camera; when the camera rests the passes come back
polls2 = [0]


def image_state(name="SchlierenImage1"):
    polls2[0] += 1
    gd.send("image %d %s" % (polls2[0], name))
    return gd.read_json("image-%d.json" % polls2[0])


set_active({"FollowCamera": 1, "Passes": 4, "Backend": "CPU"})
xdo("key", "--clearmodifiers", "alt+a")
before = gd.wait_for("the follower to start", lambda: (lambda s: s if s["following"] else None)(
    image_state()), 30)
boxes = gui_driver.view_boxes(shot)
check(len(boxes) >= 1, "the 3D view found on the screen (%s)" % boxes)
if boxes:
    gd.drag(max(boxes, key=lambda b: b[2] * b[3]), 160, 8)
    after = gd.wait_for("the image to follow the drag and refine back to 4 passes", lambda: (
        lambda s: s if s["moved"] > 0 and s["Passes"] == 4 and s["passes_done"] == [4.0] else
        None)(image_state()), 60)
    turn = np.degrees(np.arccos(np.clip(np.dot(before["ViewDirection"], after["ViewDirection"]) /
                                        np.linalg.norm(before["ViewDirection"]) /
                                        np.linalg.norm(after["ViewDirection"]), -1, 1)))
    check(turn > 5 and after["intensity_sha"] != before["intensity_sha"],
          "Follow Camera: a drag of 160 pixels turned the line of sight by %.1f degrees (%s -> %s, "
          "%d camera changes seen), the image was traced again and refined to %s passes"
          % (turn, [round(v, 3) for v in before["ViewDirection"]],
             [round(v, 3) for v in after["ViewDirection"]], after["moved"], after["passes_done"]))
    say("after the drag: %s" % screenshot("follow"))

# -- 3. the property lists: the GUI's proxies against the C++ plugin's in pvpython
gui = state()["sources"]
code = ("import json, sys\n"
        "from paraview.simple import *\n"
        "LoadPlugin(sys.argv[1], remote=False, ns=globals())\n"
        "s = RefractiveScene()\n"
        "out = {'RefractiveScene': s.ListProperties(),\n"
        "       'SchlierenImage': SchlierenImage(Input=s).ListProperties()}\n"
        "print('PROPS ' + json.dumps(out))\n")
p = subprocess.run([args.pvpython, "-c", code, os.path.abspath(args.cxx_plugin)], stdout=subprocess.PIPE,
                   stderr=subprocess.STDOUT, universal_newlines=True, timeout=120,
                   env=dict(os.environ, HOME=home))
lines = [l for l in p.stdout.splitlines() if l.startswith("PROPS ")]
if not lines:
    fatal("pvpython with the C++ plugin listed no properties: %s" % p.stdout[-500:])
cxx = json.loads(lines[-1][6:])
for proxy, registered in (("RefractiveScene", "RefractiveScene1"), ("SchlierenImage", "SchlierenImage1")):
    py = set(gui[registered]["properties"]) - {"ReloadPythonModule"}
    want = set(cxx[proxy]) - cases.PYTHON_PLUGIN_LEFT_OUT.get(proxy, set())
    check(py == want, "%s in the GUI: its %d properties are the C++ plugin's less %s (Python only: %s; "
          "C++ only: %s)" % (proxy, len(py), sorted(cases.PYTHON_PLUGIN_LEFT_OUT.get(proxy, ())),
                             sorted(py - want), sorted(want - py)))

# -- 4. the blunt fin (PLOT3D) with its silhouette, by the panel: Refractive Index by Quick Launch,
# Body Wall Faces typed into the panel's six fields, Schlieren Image, the image in a 2D view, Follow
# Camera with a drag in the 3D view
def ask(command, reply):
    """Sends `command <k> ...` with a fresh tag k, returns the session's <reply>-<k>.json."""
    polls[0] += 1
    gd.send(command.replace("<k>", str(polls[0])))
    return gd.read_json("%s-%d.json" % (reply, polls[0]), timeout=120)


gd.send("setin SchlierenImage1 " + json.dumps({"FollowCamera": 0}))
gd.read_json("set-%d.json" % gd.commands)
if not ask("bluntfin <k>", "bluntfin")["found"]:
    say("SKIP the blunt fin part: no bluntfinxyz.bin and bluntfinq.bin in %s" % os.path.abspath(gd.data))
    gd.finish()
quick_launch("Refractive Index", "RefractiveIndex1")
# the settings of gui_drag_scene.py (the C++ plugin's GUI tests): the fin's density at 64 voxels
set_active(dict(Model="GladstoneDale", Gas="Air", DensityReference=1.2, UseSamplingBounds=1,
                SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7], AutomaticDimension=64,
                InputArray=["POINTS", "Density"]))
apply_and_wait("RefractiveIndex1")
before = ask("index <k>", "index")
check(before["faces"] == [0] * 6 and before["solid_points"] == 0,
      "the blunt fin's index before: Body Wall Faces %s, %d solid points of %d"
      % (before["faces"], before["solid_points"], before["points"]))
# the panel's search box (below Apply/Reset/Delete), "wall", the six fields typed
xdo("mousemove", 130, 539)
xdo("click", 1)
time.sleep(0.3)
xdo("type", "--delay", "60", "wall")
time.sleep(0.8)
fields = gui_driver.field_boxes(screenshot("bluntfin_search"))
say("the Body Wall Faces fields on the screen (x, y): %s" % fields)
if len(fields) != 6:
    fatal("the Python plugin's panel does not show Body Wall Faces as six fields (%d found)" % len(fields))
for (x, y), value in zip(fields, (0, 1, 1, 0, 1, 1)):
    xdo("mousemove", x, y)
    xdo("click", 1)
    xdo("key", "--clearmodifiers", "ctrl+a")
    xdo("type", "--delay", "40", str(value))
    time.sleep(0.2)
time.sleep(0.5)
shot_faces = screenshot("bluntfin_faces")
say("the panel with the faces typed: %s" % shot_faces)
# the property's tooltip (its documentation in Schlieren.xml, which the generated plugin carries):
# the mouse rests on the property's middle row of fields
hover = (fields[3][0], fields[3][1])
xdo("mousemove", hover[0] + 5, hover[1] + 30)
time.sleep(0.5)
xdo("mousemove", *hover)
time.sleep(2.5)
shot_tip = screenshot("bluntfin_tooltip")
tip = np.abs(gui_driver.read_ppm(shot_tip) - gui_driver.read_ppm(shot_faces)).sum(axis=2) > 0
tip = tip[hover[1] + 8:hover[1] + 300, max(0, hover[0] - 300):hover[0] + 600]
check(int(tip.sum()) > 2000, "a tooltip shows where the mouse rests on Body Wall Faces (%d pixels "
      "changed below it): %s" % (int(tip.sum()), shot_tip))
xdo("key", "--clearmodifiers", "alt+a")
after = gd.wait_for("the index with the fin as a body", lambda: (
    lambda r: r if r["faces"] == [0, 1, 1, 0, 1, 1] and r["solid_points"] > 0 else None)(
    ask("index <k>", "index")), 60)
check(after["solid_points"] > 0, "the panel's six fields set Body Wall Faces to %s: %d solid points "
      "of %d" % (after["faces"], after["solid_points"], after["points"]))
quick_launch("Schlieren Image", "SchlierenImage2")
set_active(dict(Resolution=[160, 160], Passes=1, Cutoff="KnifeEdge", CutoffScale=250.0, Backend="CPU",
                Seed=4, InteractivePasses=1))
apply_and_wait("SchlierenImage2")
ask("view2d <k> SchlierenImage2", "view2d")
time.sleep(1.5)
shot = screenshot("bluntfin_2d")
say("the blunt fin's image in its 2D view: %s" % shot)
gd.send("dump bluntfin SchlierenImage2")
gd.read_json("dumped-bluntfin.json", timeout=60)
fin = np.load(os.path.join(args.work, "bluntfin.npz"))
dark = float((fin["array_intensity"] < 0.05).mean())
check(dark > 0.02, "the blunt fin's image is dark where the fin is (%.1f %% of the film below 0.05; "
      "mean %.3f)" % (100 * dark, float(fin["array_intensity"].mean())))
boxes = gui_driver.view_boxes(shot)
check(len(boxes) == 2, "two views on the screen, the 3D view and the image's 2D view (%s)" % boxes)
gd.send("setin SchlierenImage2 " + json.dumps({"FollowCamera": 1, "Passes": 2}))
gd.read_json("set-%d.json" % gd.commands)
xdo("key", "--clearmodifiers", "alt+a")
before = gd.wait_for("the blunt fin's follower to start", lambda: (
    lambda r: r if r["following"] else None)(image_state("SchlierenImage2")), 30)
if boxes:
    gd.drag(boxes[0], 160, 8)  # the left view: the 3D one
    after = gd.wait_for("the blunt fin's image to follow the drag and refine to 2 passes", lambda: (
        lambda r: r if r["moved"] > 0 and r["passes_done"] == [2.0] else None)(
        image_state("SchlierenImage2")), 90)
    turn = np.degrees(np.arccos(np.clip(np.dot(before["ViewDirection"], after["ViewDirection"]) /
                                        np.linalg.norm(before["ViewDirection"]) /
                                        np.linalg.norm(after["ViewDirection"]), -1, 1)))
    check(turn > 5 and after["intensity_sha"] != before["intensity_sha"],
          "the blunt fin's Follow Camera: the drag turned the line of sight by %.1f degrees, the "
          "image was traced again (%d camera changes seen) and refined to %s passes"
          % (turn, after["moved"], after["passes_done"]))
    time.sleep(1.0)
    shot_after = screenshot("bluntfin_follow")
    say("the blunt fin after the drag: %s" % shot_after)
    # the 2D view shows the refined image of the new line of sight (rendered by the follower
    # after its last chunk: before the fix in schlieren_view it kept the image of before the drag)
    x, y, w, h = boxes[1]
    changed = int((np.abs(gui_driver.read_ppm(shot)[y:y + h, x:x + w] -
                          gui_driver.read_ppm(shot_after)[y:y + h, x:x + w]).sum(axis=2) > 0).sum())
    check(changed > 1000, "the image's 2D view shows the image after the drag (%d of its %d pixels "
          "changed)" % (changed, w * h))
# the panel's "?" (right of Delete): ParaView's help window, which has a page for a proxy only where
# a registered Qt help collection holds <group>.<name>.html (a Python plugin can register none)
xdo("mousemove", 270, 508)
xdo("click", 1)
helpw = gd.wait_for('a help window after a click on the panel\'s "?"', lambda: windows("Online Help"), 30)
time.sleep(2.0)
say("the help window the '?' opened for the Python plugin's SchlierenImage: %s" % screenshot("help"))
check(bool(helpw), "the panel's '?' opens ParaView's help window (%s)" % helpw)
gd.finish()
