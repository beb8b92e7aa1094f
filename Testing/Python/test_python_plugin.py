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
from paraview.simple import Delete, LoadPlugin  # noqa: E402
from vtkmodules.util import numpy_support  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import frontend_cases as cases  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--xml", required=True)
ap.add_argument("--reference", required=True)
ap.add_argument("--package", help="the folder holding the Python front end's package `schlieren`")
args = ap.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
ns = globals()
failures = []
PROXIES_LEFT_OUT = cases.PYTHON_PLUGIN_PROXIES_LEFT_OUT  # a proxy or property missing from (or
LEFT_OUT = cases.PYTHON_PLUGIN_LEFT_OUT                 # added to) either side fails the diff


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


root = ET.parse(args.xml).getroot()
cxx_proxies = {p.get("name"): p for p in root.iter("SourceProxy")}
py_proxies = {n for n in cxx_proxies if n in ns and callable(ns[n])}
check(py_proxies == set(cxx_proxies) - PROXIES_LEFT_OUT,
      "the proxies are the C++ plugin's less %s (Python: %s)" % (sorted(PROXIES_LEFT_OUT),
                                                                 sorted(py_proxies)))
scene = ns["RefractiveScene"]()
for proxy in sorted(py_proxies):
    xml = cxx_proxies[proxy]
    leave_out = LEFT_OUT.get(proxy, set())
    # the names paraview.simple gives: the labels, as ParaView makes them valid names
    props = {servermanager._make_name_valid(p.get("label") or p.get("name")): p for p in xml
             if p.tag.endswith("VectorProperty") and p.get("information_only") != "1"
             and p.get("name") not in leave_out}
    inputs = {p.get("name") for p in xml if p.tag == "InputProperty"} - leave_out
    made = scene if proxy == "RefractiveScene" else ns[proxy](Input=scene)
    py = set(made.ListProperties()) - {"ReloadPythonModule"}  # ParaView's, on every Python proxy
    cxx = set(props) | inputs
    check(py == cxx, "%s: property list = the C++ plugin's less %s (%d; Python only: %s; C++ "
          "only: %s)" % (proxy, sorted(leave_out), len(py), sorted(py - cxx), sorted(cxx - py)))
    for name in sorted(py & set(props)):
        want = props[name].get("default_values", "")
        have = made.GetProperty(name).GetData()
        entries = {e.get("value"): e.get("text") for e in props[name].iter("Entry")}
        if props[name].tag == "StringVectorProperty" and \
                int(props[name].get("number_of_elements", "1")) == 5:
            ok = want.split(";")[-1] == "(automatic)" and have[-1] in ("", "(automatic)")
        elif isinstance(have, str) or have is None:
            ok = (have or "") == want or have == entries.get(want)
        else:
            have = have if isinstance(have, list) else [have]
            ok = [float(v) for v in have] == [float(v) for v in want.split()]
        check(ok, "%s.%s: default %r (C++ %r)" % (proxy, name, have, want))
    # the domains and documentation: the same XML (the generator copies it; here it is read back)
    for name in sorted(py & set(props)):
        p = made.GetProperty(name)
        doc = props[name].find("Documentation")
        want_doc = " ".join((doc.text or "").split()) if doc is not None else ""
        have_doc = " ".join((p.GetDocumentation().GetDescription() or "").split()) \
            if p.GetDocumentation() else ""
        check(have_doc == want_doc, "%s.%s: documentation is the C++ plugin's" % (proxy, name))
        if entries := [e.get("text") for e in props[name].iter("Entry")]:
            check(list(p.Available) == entries if hasattr(p, "Available") else True,
                  "%s.%s: entries %s" % (proxy, name, entries))
        rng = props[name].find("IntRangeDomain")
        rng = rng if rng is not None else props[name].find("DoubleRangeDomain")
        if rng is not None:
            d = p.SMProperty.GetDomain(rng.get("name"))
            want_lo = [float(v) for v in (rng.get("min") or "").split()]
            lo = [float(d.GetMinimum(i)) for i in range(len(want_lo)) if d.GetMinimumExists(i)]
            check(lo == want_lo,
                  "%s.%s: range minimum %s (C++ %s)" % (proxy, name, lo, want_lo))
    if made is not scene:
        Delete(made)

compared = 0
for backend in cases.BACKENDS:
    for name, props in cases.SCENES.items():
        tag = "%s_%s" % (name, backend)
        ref = np.load(os.path.join(args.reference, tag + ".npz"))
        if "array_intensity" not in ref:
            print("skip %s: no C++ image (no OpenCL device)" % tag)
            continue
        source = ns["RefractiveScene"](**props)
        for stage, stage_props in cases.STAGES.get(name, []):
            source = ns[stage](Input=source, **stage_props)
        image = ns["SchlierenImage"](Input=source, Backend=backend, **cases.IMAGES[name])
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
with open(os.path.join(args.reference, "opencl.txt")) as f:
    want = len(cases.SCENES) * (2 if f.read().strip() == "OpenCL" else 1)
check(compared == want, "images compared: %d of %d" % (compared, want))

# NumericalSchlieren: the engine's code in both, the same image and field data
for name, (scene, props) in cases.NUMERICAL.items():
    ref = np.load(os.path.join(args.reference, name + ".npz"))
    image = ns["NumericalSchlieren"](Input=ns["RefractiveScene"](**cases.SCENES[scene]), **props)
    image.UpdatePipeline()
    out = servermanager.Fetch(image)
    check(np.array_equal(np.array(out.GetExtent()), ref["extent"]) and
          np.array_equal(np.array(out.GetOrigin()), ref["origin"]) and
          np.array_equal(np.array(out.GetSpacing()), ref["spacing"]), "%s: the film" % name)
    for a in ("intensity", "numerical_gradient", "blocked"):
        mine = out.GetPointData().GetArray(a)
        m = numpy_support.vtk_to_numpy(mine) if mine is not None else None
        t = ref["array_" + a]
        check(m is not None and m.dtype == t.dtype and m.shape == t.shape and
              np.array_equal(m.view(np.uint8), t.view(np.uint8)),
              "%s: %s bit for bit (%s, mean %.6g)" % (name, a, t.shape, float(t.mean())))
    mine_fd = cases.field_data_list(out.GetFieldData())
    check(mine_fd == json.loads(str(ref["field_data"])),
          "%s: the field data equals the C++ filter's (%s)" % (name, mine_fd))
# a trace the pipeline stops (issue 47, "never a hang"): Passes 1000000 (250 s before) with an
# observer that asks to abort at the first progress event ends at once with the C++ filter's
# message and no image; with an earlier image that image stays, with the C++ filter's warning;
# the next update traces, and its image is bit for bit a fresh filter's (python.python_plugin's
# TIMEOUT guards the hang)
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402


def stop_at_first_progress(alg, proxy):
    """Updates `proxy` with an observer on `alg` that asks to abort at the first progress event;
    returns (the progress values seen, the output, the warnings and errors written). The output
    is the algorithm's (a Fetch would update a failed request again, without the observer)."""
    seen = []

    def abort(obj, _event):
        if not seen:
            obj.SetAbortExecute(1)
        seen.append(obj.GetProgress())
    tag = alg.AddObserver("ProgressEvent", abort)
    said, window = vtkStringOutputWindow(), vtkOutputWindow.GetInstance()
    vtkOutputWindow.SetInstance(said)
    try:
        proxy.UpdatePipeline()
    finally:
        vtkOutputWindow.SetInstance(window)
        alg.RemoveObserver(tag)
    out = vtkImageData()
    out.ShallowCopy(alg.GetOutputDataObject(0))
    return seen, out, said.GetOutput()


def intensity(out):
    a = out.GetPointData().GetArray("intensity")
    return numpy_support.vtk_to_numpy(a).copy() if a is not None else None


def passes(out):
    a = out.GetFieldData().GetArray("passes")
    return a.GetValue(0) if a is not None else None


small = ns["RefractiveScene"](**cases.SCENES["gaussian_sphere"])
stopped = ns["SchlierenImage"](Input=small, Backend="CPU", Resolution=[48, 40], Passes=1000000)
alg = stopped.GetClientSideObject()
seen, out, said = stop_at_first_progress(alg, stopped)
check(len(seen) >= 1 and alg.LastError.startswith("aborted at 0 % of the trace: no image yet") and
      out.GetNumberOfPoints() == 0 and "no image yet" in said,
      "Passes 1000000, aborted at the first progress event: '%s', %d points out, progress seen %s"
      % (alg.LastError, out.GetNumberOfPoints(), seen[:4]))
stopped.Passes = 3
stopped.UpdatePipeline()
first = alg.GetOutputDataObject(0)
fresh = ns["SchlierenImage"](Input=small, Backend="CPU", Resolution=[48, 40], Passes=3)
fresh.UpdatePipeline()
want = intensity(servermanager.Fetch(fresh))
got = intensity(first)
check(got is not None and want is not None and np.array_equal(got.view(np.uint32),
                                                              want.view(np.uint32)) and
      passes(first) == 3 and alg.LastError == "",
      "the update after the abort traces: Passes 3 bit for bit a fresh filter's (passes %s)"
      % passes(first))
stopped.Passes = 1000000
seen, out, said = stop_at_first_progress(alg, stopped)
got = intensity(out)
check(got is not None and np.array_equal(got.view(np.uint32), want.view(np.uint32)) and
      passes(out) == 3 and "the image shown is the previous one" in said and alg.LastError == "",
      "aborted with an earlier image: that image (passes %s) stays, with the warning '%s'"
      % (passes(out), said.strip()[-120:]))
for q in (fresh, stopped, small):
    Delete(q)

# the two packages in one ParaView Python session: the C++ plugin's compiled classes
# (schlieren_vtk, from the build's dist-packages) and the Python front end (schlieren), neither
# shadowing the other; the front end hands out the compiled classes under their old name
if args.package:
    sys.path.insert(0, args.package)
    import schlieren_vtk  # noqa: E402
    import schlieren  # noqa: E402
    check(os.path.dirname(schlieren.__file__) == os.path.join(args.package, "schlieren") and
          hasattr(schlieren, "SchlierenImage") and hasattr(schlieren_vtk, "vtkSchlierenImage") and
          schlieren.vtkSchlierenImage is schlieren_vtk.vtkSchlierenImage,
          "schlieren (%s) and schlieren_vtk (%s) import in one session; schlieren.vtkSchlierenImage "
          "is the compiled class" % (schlieren.__file__, schlieren_vtk.__file__))
    f = schlieren.RefractiveScene(Dimensions=[8, 8, 8])
    f.Update()
    g = schlieren_vtk.vtkRefractiveScene()
    g.SetDimensions(8, 8, 8)
    g.Update()
    check(f.GetOutput().GetDimensions() == g.GetOutput().GetDimensions() == (8, 8, 8),
          "both packages' RefractiveScene run in that session")
print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
