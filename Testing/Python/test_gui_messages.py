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
with the automatic scale's full-contrast deflection), deletes the image with the panel's Delete
(its view goes, the layout back to one view, the 3D view active), selects the
PLOT3D reader (the greyed Schlieren Image entry's tip says to apply RefractiveIndex first).
Skipped (exit 0, a message) without ../shared/data.
"""
import os
import shutil
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import gui_driver  # noqa: E402
from gui_driver import field_boxes  # noqa: E402

gd = gui_driver.Driver(__doc__)
args, data = gd.args, gd.data
settings = {}
gd.launch("gui_messages_session.py", settings)
say, check, fatal, finish, wait_for = gd.say, gd.check, gd.fatal, gd.finish, gd.wait_for
events_since, send, read_json = gd.events_since, gd.send, gd.read_json
xdo, screenshot = gd.xdo, gd.screenshot
events, messages, lock = gd.events, gd.messages, gd.lock
messages_since = gd.messages_since





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
window = gd.main_window()
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
check(gone["active_view"], "after the image is deleted a view is active (the 3D view), not none")
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
