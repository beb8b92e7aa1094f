# SPDX-License-Identifier: BSD-3-Clause
"""The Python front end (Python/schlieren: ctypes over libschlieren_engine, VTK algorithms) against
the C++ plugin's images of frontend_cases.py, bit for bit, on the CPU backend and on OpenCL (PoCL
here): the same engine, the same settings, the same image.

    python test_frontend.py --reference DIR     (DIR: what frontend_reference.py wrote)

Run in a venv with PyPI's vtk and NumPy, the package on PYTHONPATH and SCHLIEREN_ENGINE_LIBRARY
naming the build's libschlieren_engine.so. Also checks the keyword/attribute interface, an error
naming a bad property value, and that the library traces on the CPU with no OpenCL loader at all
(SCHLIEREN_OPENCL_LIBRARY pointing nowhere, in a child process).

RefractiveIndex's parity matrix (frontend_cases.INDEX, every property value class: each model,
Symmetry None/Planar/Axisymmetric, a wedge with no axis typed, bodies from holes and from walls,
SamplingBounds, each AmbientMode; the table is in frontend_cases.py): each case's input as the
reference run wrote it, through this package's RefractiveIndex and SchlierenImage, against the C++
plugin's index (grid, point arrays, field data) and film (arrays, field data) bit for bit
(frontend_matrix.compare). The Python plugin's leg of the same matrix is in
test_python_plugin_parity.py."""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import frontend_cases as cases  # noqa: E402

import schlieren  # noqa: E402
import vtkmodules  # noqa: E402
from vtkmodules.util import numpy_support  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--reference", required=True)
args = ap.parse_args()
print("vtk %s, numpy %s, engine %s" % (vtkmodules.__version__ if hasattr(vtkmodules, "__version__")
                                       else "?", np.__version__, schlieren.version()))
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


# 1. the interface: keywords, attributes, defaults, errors
img = schlieren.SchlierenImage(Cutoff="KnifeEdge", Resolution=[512, 512])
check(img.Cutoff == "KnifeEdge" and img.Resolution == [512, 512] and img.Passes == 4,
      "keywords and the proxy's defaults (Passes 4)")
t0 = img.GetMTime()
img.Passes = 8
check(img.GetMTime() > t0 and img.Passes == 8, "an attribute set marks the algorithm modified")
try:
    img.Cutoff = "Knife"
    check(False, "a bad enumeration is refused")
except ValueError as e:
    check("KnifeEdge" in str(e) and "Cutoff" in str(e), "a bad enumeration names the entries: %s" % e)
try:
    schlieren.SchlierenImage(Resolutoin=[4, 4])
    check(False, "a misspelt property is refused")
except AttributeError as e:
    check("Resolution" in str(e), "a misspelt property lists the properties")
bad = schlieren.SchlierenImage(StepSize=-1.0, Backend="CPU", Resolution=[8, 8])
small = schlieren.RefractiveScene(Dimensions=[8, 8, 8])  # kept: VTK's Python algorithms must be
bad.SetInputConnection(small.GetOutputPort())           # referenced while the pipeline runs
bad.Update()
check("StepSize" in bad.LastError, "an out-of-range value is the engine's error: %s" % bad.LastError)

# every engine property of SchlierenImage is away from its default in some case
varied = set()
for props in cases.IMAGES.values():
    for k, v in props.items():
        if img._defaults.get(k) != v and not (isinstance(v, list) and [float(x) for x in v] ==
                                               [float(x) for x in img._defaults.get(k, [])]):
            varied.add(k)
never = set(img._defaults) - varied - cases.SETTINGS_NOT_VARIED
check(not never, "every SchlierenImage property is set away from its default in some case "
      "(never: %s; left out by name: %s)" % (sorted(never), sorted(cases.SETTINGS_NOT_VARIED)))

# 2. the images against the C++ plugin's
sources = {}
keep = []  # VTK's Python algorithms must stay referenced while the pipeline runs
for name, props in cases.SCENES.items():
    sources[name] = schlieren.RefractiveScene(**props)
    for stage, stage_props in cases.STAGES.get(name, []):
        keep.append(sources[name])
        f = getattr(schlieren, stage)(**stage_props)
        f.SetInputConnection(sources[name].GetOutputPort())
        sources[name] = f
vti = os.path.join(args.reference, "bluntfin_index.vti")
if os.path.exists(vti):
    r = vtkXMLImageDataReader()
    r.SetFileName(vti)
    sources["bluntfin"] = r
else:
    print("skip blunt fin: no %s (the reference run found no data)" % vti)
with open(os.path.join(args.reference, "opencl.txt")) as f:
    opencl = f.read().strip()
compared = 0
for backend in cases.BACKENDS:
    for name, source in sources.items():
        tag = "%s_%s" % (name, backend)
        ref = np.load(os.path.join(args.reference, tag + ".npz"))
        if "array_intensity" not in ref:
            print("skip %s: the C++ plugin made no image there (OpenCL: %s)" % (tag, opencl))
            continue
        image = schlieren.SchlierenImage(Backend=backend, **cases.IMAGES[name])
        image.SetInputConnection(source.GetOutputPort())
        image.Update()
        out = image.GetOutput()
        check(np.array_equal(np.array(out.GetExtent()), ref["extent"]) and
              np.array_equal(np.array(out.GetOrigin()), ref["origin"]) and
              np.array_equal(np.array(out.GetSpacing()), ref["spacing"]),
              "%s: the film's extent, origin and spacing" % tag)
        for a in cases.ARRAYS:
            mine = out.GetPointData().GetArray(a)
            theirs = ref["array_" + a] if "array_" + a in ref else None
            if mine is None or theirs is None:
                check(mine is None and theirs is None, "%s: %s on both sides or neither" % (tag, a))
                continue
            m = numpy_support.vtk_to_numpy(mine)
            same = m.shape == theirs.shape and m.dtype == theirs.dtype and \
                np.array_equal(m.view(np.uint32), theirs.view(np.uint32))
            check(same, "%s: %s bit for bit (%s, mean %.6g)" % (tag, a, theirs.shape,
                                                                 float(theirs.mean())))
        fields = json.loads(str(ref["fields"]))
        report = image.LastReport["field_data"]
        for k, v in fields.items():
            check(report.get(k) == v, "%s: field %s = %r (C++: %r)" % (tag, k, report.get(k), v))
        # the whole field data, names, order and values: both written from the engine's one
        # report (schlieren::ImageReport), the C++ filter's directly, this one's through the C API
        mine_fd = cases.field_data_list(out.GetFieldData())
        theirs_fd = json.loads(str(ref["field_data"]))
        diff = [(a, b) for a, b in zip(mine_fd, theirs_fd) if a != b]
        check(mine_fd == theirs_fd and len(mine_fd) > 20,
              "%s: the field data equals the C++ filter's: %d entries (%s; Python only: %s; C++ "
              "only: %s)" % (tag, len(theirs_fd), diff[:3],
                             sorted({e[0] for e in mine_fd} - {e[0] for e in theirs_fd}),
                             sorted({e[0] for e in theirs_fd} - {e[0] for e in mine_fd})))
        if name == "solid_sphere":
            check(fields["blocked_rays"] > 0, "%s: the body blocks rays (%d)" %
                  (tag, fields["blocked_rays"]))
        compared += 1
want = len(sources) * (2 if opencl == "OpenCL" else 1)  # every case, on OpenCL where it traced
check(compared == want, "images compared: %d of %d" % (compared, want))

# NumericalSchlieren: the engine's code through the C interface, the C++ filter's image
for name, (scene, props) in cases.NUMERICAL.items():
    ref = np.load(os.path.join(args.reference, name + ".npz"))
    src = schlieren.RefractiveScene(**cases.SCENES[scene])
    image = schlieren.NumericalSchlieren(**props)
    image.SetInputConnection(src.GetOutputPort())
    image.Update()
    out = image.GetOutput()
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

# RefractiveIndex's parity matrix (frontend_cases.INDEX: every property value class): the inputs
# the reference run wrote, through this package's RefractiveIndex and SchlierenImage, against the
# C++ plugin's records bit for bit (the Python plugin's leg: python.python_plugin_parity)
import frontend_matrix as matrix  # noqa: E402
matrix_compared, matrix_started = 0, time.time()
for case, (which, props, image_props) in cases.INDEX.items():
    path = os.path.join(args.reference, "index_%s.npz" % case)
    if not os.path.exists(path):
        print("skip %s: the reference run left it out (no %s data)" % (case, which))
        continue
    data = matrix.read_input(args.reference, which)
    index = schlieren.RefractiveIndex(**props)
    index.SetInputData(data)
    if case in cases.INDEX_BODY:  # the Body input (port 1)
        body = matrix.read_input(args.reference, cases.INDEX_BODY[case])
        index.SetInputData(1, body)
    image = schlieren.SchlierenImage(**dict(cases.INDEX_IMAGE, **image_props))
    image.SetInputConnection(index.GetOutputPort())
    image.Update()
    matrix.compare(case, matrix.record(index.GetOutput(), image.GetOutput()), np.load(path),
                   check, "pip vtk %s" % vtkmodules.__version__)
    matrix_compared += 1
matrix.known_differences()
print("RefractiveIndex's matrix in %.1f s" % (time.time() - matrix_started))
check(matrix_compared >= len([c for c in cases.INDEX.values()
                               if c[0] not in cases.INDEX_OPTIONAL_INPUTS]),
      "RefractiveIndex's matrix: %d of %d cases compared (the others need ../shared/data or the "
      "suite's OpenFOAM cases)" % (matrix_compared, len(cases.INDEX)))

# 3. no OpenCL loader at all: Backend Auto traces on the CPU with a warning naming why
code = ("import schlieren\n"
        "s = schlieren.RefractiveScene(Dimensions=[16, 16, 16], Amplitude=1e-3)\n"
        "i = schlieren.SchlierenImage(Resolution=[16, 16], Passes=1)\n"
        "i.SetInputConnection(s.GetOutputPort()); i.Update()\n"
        "f = i.LastReport['field_data']\n"
        "print(f['backend'] + '|' + f['warnings'])\n")
env = dict(os.environ, SCHLIEREN_OPENCL_LIBRARY="/nonexistent/libOpenCL.so.1")
p = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
line = p.stdout.strip().splitlines()[-1] if p.stdout.strip() else ""
check(p.returncode == 0 and line.startswith("CPU|") and "OpenCL loader" in line,
      "no OpenCL loader: CPU with a warning (%s)" % (line or p.stderr[-300:]))

print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
