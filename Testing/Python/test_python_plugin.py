# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView Python plugin (SchlierenPython.py, generated from Schlieren.xml and the Python
package) in Debian's ParaView 5.11, from pvpython: it loads, its proxies' property lists equal the
C++ plugin's (Schlieren.xml, less the GUI-only properties the Python plugin leaves out) with the
same defaults, and its images of frontend_cases.py equal the C++ plugin's bit for bit on the CPU
and on OpenCL.

    pvpython test_python_plugin.py --plugin SchlierenPython.py --xml Plugin/Schlieren.xml \
        --reference DIR     (DIR: what frontend_reference.py wrote)

ParaView 5.11.0's own paraview.detail.pythonalgorithm imports inspect.getargspec, which Python
3.11 (Debian 12's) no longer has: no Python plugin loads there without the two lines below run
first (docs/PYTHON.md)."""
import argparse
import collections
import inspect
import json
import os
import sys
import xml.etree.ElementTree as ET

if not hasattr(inspect, "getargspec"):  # ParaView 5.11.0 on Python >= 3.11
    _ArgSpec = collections.namedtuple("ArgSpec", "args varargs keywords defaults")
    inspect.getargspec = lambda f: _ArgSpec(*inspect.getfullargspec(f)[:4])

import numpy as np  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import LoadPlugin  # noqa: E402
from vtkmodules.util import numpy_support  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import frontend_cases as cases  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--xml", required=True)
ap.add_argument("--reference", required=True)
args = ap.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
ns = globals()
failures = []
GUI_ONLY = {"FollowCamera", "InteractivePasses", "InteractiveScale", "OpenImageView", "PassLimit"}


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


check("RefractiveScene" in ns and "SchlierenImage" in ns, "the plugin's proxies are defined")
root = ET.parse(args.xml).getroot()
for proxy, leave_out in (("SchlierenImage", GUI_ONLY), ("RefractiveScene", {"TimeSteps"})):
    xml = [p for p in root.iter("SourceProxy") if p.get("name") == proxy][0]
    props = {p.get("name"): p for p in xml if p.tag.endswith("VectorProperty")
             and p.get("information_only") != "1"}
    inputs = {p.get("name") for p in xml if p.tag == "InputProperty"}
    cxx = set(props) | inputs
    source = ns["RefractiveScene"]() if proxy == "RefractiveScene" else None
    made = source if source else ns["SchlierenImage"](Input=ns["RefractiveScene"]())
    py = set(made.ListProperties()) - {"ReloadPythonModule"}  # ParaView's, on every Python proxy
    check(py == cxx - leave_out, "%s: property list = the C++ plugin's less %s (Python only: %s; "
          "C++ only: %s)" % (proxy, sorted(leave_out), sorted(py - cxx),
                             sorted(cxx - leave_out - py)))
    for name in sorted(py & set(props)):
        want = props[name].get("default_values", "")
        have = made.GetProperty(name).GetData()
        if isinstance(have, str) or have is None:
            ok = (have or "") == want or (props[name].find(".//Entry") is not None and
                                          have == [e.get("text") for e in props[name].iter("Entry")
                                                   if e.get("value") == want][0])
        else:
            have = have if isinstance(have, list) else [have]
            ok = [float(v) for v in have] == [float(v) for v in want.split()]
        check(ok, "%s.%s: default %r (C++ %r)" % (proxy, name, have, want))

compared = 0
for backend in cases.BACKENDS:
    for name, props in cases.SCENES.items():
        tag = "%s_%s" % (name, backend)
        ref = np.load(os.path.join(args.reference, tag + ".npz"))
        if "array_intensity" not in ref:
            print("skip %s: no C++ image (no OpenCL device)" % tag)
            continue
        scene = ns["RefractiveScene"](**props)
        image = ns["SchlierenImage"](Input=scene, Backend=backend, **cases.IMAGES[name])
        image.UpdatePipeline()
        out = servermanager.Fetch(image)
        check(np.array_equal(np.array(out.GetExtent()), ref["extent"]) and
              np.array_equal(np.array(out.GetOrigin()), ref["origin"]),
              "%s: the film's extent and origin" % tag)
        for a in cases.ARRAYS:
            mine = out.GetPointData().GetArray(a)
            theirs = ref["array_" + a] if "array_" + a in ref else None
            if mine is None or theirs is None:
                check(mine is None and theirs is None, "%s: %s on both sides or neither" % (tag, a))
                continue
            m = numpy_support.vtk_to_numpy(mine)
            check(m.shape == theirs.shape and np.array_equal(m.view(np.uint32),
                                                             theirs.view(np.uint32)),
                  "%s: %s bit for bit" % (tag, a))
        fields = json.loads(str(ref["fields"]))
        fd = out.GetFieldData()
        for k, v in fields.items():
            arr = fd.GetAbstractArray(k)
            check(arr is not None and arr.GetValue(0) == v, "%s: field %s" % (tag, k))
        mine_fd = cases.field_data_list(fd)
        theirs_fd = json.loads(str(ref["field_data"]))
        check(mine_fd == theirs_fd and len(mine_fd) > 20,
              "%s: the field data equals the C++ filter's (%d entries; differing: %s)"
              % (tag, len(theirs_fd), [(a, b) for a, b in zip(mine_fd, theirs_fd) if a != b][:3]))
        compared += 1
check(compared >= 2, "images compared: %d" % compared)
print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
