# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView GUI loads the plugin, builds the chain, shows the image; run by run_gui_test.py.

The GUI runs this with `paraview --dr --script=test_gui.py --exit`, which does not pass arguments
and exits 0 even when the script raises: so the plugin path comes from the environment
(SCHLIEREN_PLUGIN), success is written to the file SCHLIEREN_GUI_RESULT ("PASS" and the checks),
and a failure ends the process at once with status 1.
"""
import os
import sys
import traceback

result_path = os.environ.get("SCHLIEREN_GUI_RESULT")
lines = []


def check(condition, message):
    lines.append("%s %s" % ("ok  " if condition else "FAIL", message))
    if not condition:
        raise AssertionError(message)


try:
    import math

    from paraview.simple import *  # noqa: F401,F403
    from paraview import servermanager as sm

    plugin = os.environ["SCHLIEREN_PLUGIN"]
    LoadPlugin(plugin, remote=False, ns=globals())

    A = 1e-4
    k = 1000.0
    scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[48, 48, 48], Amplitude=A, Width=0.25)
    index = RefractiveIndex(Input=scene, Model="Passthrough")
    image = SchlierenImage(Input=index, Resolution=[128, 128], Passes=1, Jitter=0,
                           Cutoff="KnifeEdge", CutoffScale=k)
    view = GetActiveViewOrCreate("RenderView")
    display = Show(image, view)
    ColorBy(display, ("POINTS", "intensity"))
    Render(view)

    names = [key[0] for key in GetSources().keys()]
    check(all(n in names for n in ("RefractiveScene1", "RefractiveIndex1", "SchlierenImage1")),
          "the pipeline browser holds the chain (%s)" % sorted(names))
    check(view.GetXMLName() == "RenderView", "the image is shown in a render view")
    check(display.Representation in ("Slice", "Surface", "Outline"),
          "the image has a representation (%s)" % display.Representation)

    # I = 0.5 - k eps_x at pixel centres: the range is 0.5 -/+ k max|eps_x|, max|eps| =
    # sqrt(2 pi) A e^-1/2 = 1.52e-4, less the grid's 2-3 % at 48^3 (tolerance 0.01 in intensity).
    lo, hi = image.PointData["intensity"].GetRange()
    half = k * math.sqrt(2 * math.pi) * A * math.exp(-0.5)
    check(abs(lo - (0.5 - half)) < 0.01 and abs(hi - (0.5 + half)) < 0.01,
          "intensity range [%.4f, %.4f], expected about [%.4f, %.4f]" % (lo, hi, 0.5 - half, 0.5 + half))
    check(image.GetDataInformation().GetNumberOfPoints() == 128 * 128, "a 128 x 128 film")
    lines.append("PASS")
except BaseException:
    lines.append("FAIL " + traceback.format_exc())
    if result_path:
        with open(result_path, "w") as f:
            f.write("\n".join(lines) + "\n")
    sys.stderr.write("\n".join(lines) + "\n")
    sys.stderr.flush()
    os._exit(1)

if result_path:
    with open(result_path, "w") as f:
        f.write("\n".join(lines) + "\n")
