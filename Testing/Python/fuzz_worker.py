# SPDX-License-Identifier: BSD-3-Clause
"""One child of the fuzz test (test_fuzz.py): runs the cases of a JSON file in this pvpython and
prints one JSON line per case ("BEGIN <id>" before it, so that the parent knows which case a
crash or hang belongs to).

Run: pvpython fuzz_worker.py --plugin <Schlieren.so> --cases cases.json

A case is a dict: `source` (a volume made here with numpy: dims, spacing, origin, field; or a
RefractiveScene; or an unstructured grid for RefractiveIndex), optional `index` (RefractiveIndex
properties) and `octree` (RefractionOctree properties), `image` (SchlierenImage properties;
absent: the last filter's output is the result). A source may carry a `mask` (a
point array 'solid' for RefractiveIndex's SolidArray: a ball, all or none) or be `holes` (an
unstructured grid with the cells in a box removed, for BodyFromGrid); `time` updates at that
time (BlastWave's steps); `repeat` is a list of property changes to the last filter, each
updated and classified in turn on the same pipeline (the first failure is the case's outcome).
Outcomes:
  image    an image, no warning
  warned   an image with a warning (output window or field data 'warnings')
  error    no output and an error message that says more than "returned failure"
  FAIL-*   anything else: an empty output without a clear error, an image that no photon
           reached (samples 0 or landed_photons 0) without a warning, non-finite values, an
           exception in Python, an expected phrase missing from the message
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData

import schlieren_testing as st

st.load_plugin(globals())


def make_field(src):
    nx, ny, nz = src["dims"]
    kind = src.get("field", "gauss")
    amp = src.get("amp", 1e-4)
    rng = np.random.default_rng(src.get("seed", 0))
    z, y, x = np.meshgrid(np.linspace(-1, 1, max(nz, 1)), np.linspace(-1, 1, max(ny, 1)),
                          np.linspace(-1, 1, max(nx, 1)), indexing="ij")
    if kind == "gauss":
        f = amp * np.exp(-(x * x + y * y + z * z) / 0.25)
    elif kind == "noise":
        f = amp * rng.random((nz, ny, nx))
    elif kind == "uniform":
        f = np.full((nz, ny, nx), amp)
    elif kind == "linear":
        f = amp * (1 + x)
    elif kind == "shock":
        f = np.where(x > 0.1, 2 * amp, amp)
    elif kind == "nan":
        f = amp * np.exp(-(x * x + y * y + z * z) / 0.25)
        f.flat[rng.integers(0, f.size)] = np.nan
    elif kind == "negative":
        f = np.full((nz, ny, nx), -2.0)
    else:
        raise ValueError(kind)
    return f.astype(np.float32)


def image_source(src):
    img = vtkImageData()
    img.SetDimensions(*src["dims"])
    img.SetSpacing(*src["spacing"])
    img.SetOrigin(*src["origin"])
    a = numpy_to_vtk(np.ascontiguousarray(make_field(src)).ravel(), deep=1)
    a.SetName(src.get("array", "n_minus_1"))
    if src.get("cells"):
        # a cell-only input: the values on the cells (one fewer along each axis)
        nx, ny, nz = src["dims"]
        cells = np.ascontiguousarray(make_field(dict(src, dims=[max(nx - 1, 1), max(ny - 1, 1),
                                                                 max(nz - 1, 1)]))).ravel()
        c = numpy_to_vtk(cells, deep=1)
        c.SetName(src.get("array", "n_minus_1"))
        img.GetCellData().AddArray(c)
    else:
        img.GetPointData().AddArray(a)
    mask = src.get("mask")
    if mask:
        nx, ny, nz = src["dims"]
        z, y, x = np.meshgrid(np.linspace(-1, 1, max(nz, 1)), np.linspace(-1, 1, max(ny, 1)),
                              np.linspace(-1, 1, max(nx, 1)), indexing="ij")
        if mask == "all":
            solid = np.ones_like(x)
        elif mask == "none":
            solid = np.zeros_like(x)
        else:  # a ball: [cx, cy, cz, r] in the volume's [-1, 1] coordinates
            cx, cy, cz, r = mask
            solid = ((x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2 < r * r).astype(float)
        m = numpy_to_vtk(np.ascontiguousarray(solid.astype(np.uint8)).ravel(), deep=1)
        m.SetName("solid")
        img.GetPointData().AddArray(m)
    if src.get("holes"):
        # a cell array 'keep': 0 in the box [x0, x1, y0, y1, z0, z1] (of [-1, 1]), else 1
        nx, ny, nz = src["dims"]
        b = src["holes"]
        cz, cy, cx = np.meshgrid(*(np.linspace(-1, 1, max(n - 1, 1)) for n in (nz, ny, nx)),
                                 indexing="ij")
        inside = ((cx > b[0]) & (cx < b[1]) & (cy > b[2]) & (cy < b[3]) & (cz > b[4]) &
                  (cz < b[5]))
        k = numpy_to_vtk(np.ascontiguousarray((~inside).astype(np.float32)).ravel(), deep=1)
        k.SetName("keep")
        img.GetCellData().AddArray(k)
    tp = TrivialProducer()
    tp.GetClientSideObject().SetOutput(img)
    return tp, img


def build(case):
    """The pipeline of a case: (the proxy to update, every proxy made, data to keep alive)."""
    src = case["source"]
    keep = []
    made = []
    if src["kind"] in ("image", "holes"):
        p, img = image_source(dict(src, holes=src.get("box")) if src["kind"] == "holes" else src)
        keep.append(img)
        if src["kind"] == "holes":
            made.append(p)
            p = Threshold(Input=p, Scalars=["CELLS", "keep"], LowerThreshold=0.5,
                          UpperThreshold=2.0)
    elif src["kind"] == "scene":
        p = RefractiveScene(**src["properties"])
    elif src["kind"] == "unstructured":
        w = Wavelet(WholeExtent=[-8, 8, -8, 8, -8, 8])
        made.append(w)
        p = Tetrahedralize(Input=w)
    else:
        raise ValueError(src["kind"])
    made.append(p)
    if "index" in case:
        props = dict(case["index"])
        arrays = {k: props.pop(k) for k in list(props) if k.endswith("Array")}
        body = None
        if case.get("body"):
            # closed spheres (x, y, z, radius), overlapping where they do, as one surface
            spheres = [Sphere(Center=b[:3], Radius=b[3], ThetaResolution=16, PhiResolution=16)
                       for b in case["body"]]
            made.extend(spheres)
            body = AppendGeometry(Input=spheres)
            made.append(body)
        p = RefractiveIndex(Input=p, **props) if body is None else RefractiveIndex(Input=p, Body=body, **props)
        for k, v in arrays.items():
            setattr(p, k, v)
        made.append(p)
    if "octree" in case:
        p = RefractionOctree(Input=p, **case["octree"])
        made.append(p)
    if "image" in case:
        p = SchlierenImage(Input=p, **case["image"])
        made.append(p)
    return p, made, keep


def classify(case, data, text, pyerror):
    # the output window's blocks: "ERROR: In <file>, line <n>" (or "Warning: In ...") and then
    # "<class> (<address>): <message>"
    errors, warns = [], []
    kind = None
    for line in text.splitlines():
        line = line.strip()
        if line.startswith("ERROR: In ") or "ERR|" in line:
            kind = errors
            if "ERR|" not in line:
                continue
        elif line.startswith("Warning: In ") or "WARN|" in line:
            kind = warns
            if "WARN|" not in line:
                continue
        if kind is not None and line:
            if "returned failure" not in line:
                kind.append(line)
            kind = None
    points = data.GetNumberOfPoints() if data is not None else 0
    r = {"id": case["id"], "group": case.get("group", "random")}
    if pyerror:
        r.update(outcome="FAIL-python", detail=pyerror[:300])
        return r
    if points == 0:
        if errors:
            r.update(outcome="error", detail=errors[0][errors[0].find("): ") + 3:][:300]
                     if "): " in errors[0] else errors[0][:300])
        else:
            r.update(outcome="FAIL-empty-without-error", detail=text.strip()[:300])
    else:
        fd = data.GetFieldData()
        warned = bool(warns)
        w = fd.GetAbstractArray("warnings")
        if w is not None and w.GetNumberOfValues() > 0 and w.GetValue(0).strip():
            warned = True
        pd = data.GetPointData()
        nonfinite = []
        for i in range(pd.GetNumberOfArrays()):
            a = pd.GetArray(i)
            if a is not None and not np.all(np.isfinite(vtk_to_numpy(a))):
                nonfinite.append(a.GetName())
        samples = fd.GetArray("samples")
        landed = fd.GetArray("landed_photons")
        blank = False
        if "image" in case and samples is not None and landed is not None:
            blank = samples.GetValue(0) == 0 or landed.GetValue(0) == 0
            r["samples"] = samples.GetValue(0)
        if nonfinite:
            r.update(outcome="FAIL-nonfinite", detail=",".join(nonfinite))
        elif blank and not warned:
            r.update(outcome="FAIL-blank-without-warning",
                     detail="samples %g, landed %g" % (samples.GetValue(0), landed.GetValue(0)))
        else:
            r.update(outcome="warned" if warned else "image",
                     detail=(warns[0][warns[0].find("): ") + 3:][:300] if warns else ""))
    exp = case.get("expect")
    if exp and not r["outcome"].startswith("FAIL"):
        allowed = exp.get("outcome")
        if allowed and r["outcome"] not in allowed:
            r.update(outcome="FAIL-expected-" + "/".join(allowed), detail=r.get("detail", ""))
        message = r.get("detail", "") if r["outcome"] == "error" else text
        missing = [ph for ph in exp.get("phrases", []) if ph not in message]
        absent = [ph for ph in exp.get("not_phrases", []) if ph in message]
        if missing or absent:
            r.update(outcome="FAIL-message", detail="missing %s, unwanted %s: %s"
                     % (missing, absent, r.get("detail", "")[:250]))
    return r


def update(proxy, case):
    """The proxy's output: fetched, or at the case's time."""
    if "time" in case:
        proxy.UpdatePipeline(case["time"])
        out = proxy.GetClientSideObject().GetOutputDataObject(0)
        copy = out.NewInstance()
        copy.ShallowCopy(out)
        return copy
    return sm.Fetch(proxy)


def run(case):
    pyerror = None
    data = None
    made = []
    with st.CapturedOutput() as out:
        try:
            proxy, made, keep = build(case)
            data = update(proxy, case)
        except Exception as e:  # reported, never swallowed
            pyerror = "%s: %s" % (type(e).__name__, e)
    r = classify(case, data, out.text, pyerror)
    # the same pipeline updated again with changed properties: each update classified
    for i, change in enumerate(case.get("repeat", [])):
        if r["outcome"].startswith("FAIL") or not made:
            break
        pyerror, data = None, None
        with st.CapturedOutput() as out:
            try:
                for k, v in change.items():
                    setattr(made[-1], k, v)
                data = update(made[-1], case)
            except Exception as e:
                pyerror = "%s: %s" % (type(e).__name__, e)
        r2 = classify(dict(case, expect=None), data, out.text, pyerror)
        r2["detail"] = "update %d (%s): %s" % (i + 2, json.dumps(change), r2.get("detail", ""))
        r = r2 if r2["outcome"].startswith("FAIL") or i == len(case["repeat"]) - 1 else r
    for p in reversed(made):
        Delete(p)
    return r


def main():
    path = st.argument("--cases")
    with open(path) as f:
        cases = json.load(f)
    for case in cases:
        sys.stdout.write("BEGIN %s\n" % case["id"])
        sys.stdout.flush()
        r = run(case)
        sys.stdout.write("RESULT " + json.dumps(r) + "\n")
        sys.stdout.flush()


main()
