# SPDX-License-Identifier: BSD-3-Clause
"""SchlierenPhotograph in the two plugins on one photograph (issue 51): the C++ filter
(vtkSchlierenPhotograph, the compiled class of schlieren_vtk) and the ParaView Python plugin's
proxy (SchlierenPython.py, the Python package's class) in one pvpython, on the film of one traced
image and a "photograph" of it made with a known similarity transform, gamma, vignetting and noise:

  1. a 16-bit grey PNG and an 8-bit colour JPEG: every output array (intensity, photograph,
     photograph_calibrated, difference, checkerboard, blend, line_distance), the active scalars
     Overlay names, the field data (the engine's JSON report and the numbers) and the lines
     (points, cells, image, line_distance, line_offset, line_matched, line_match) bit for bit,
     under Overlay Blend and under Checkerboard with another Blend Weight and Checker Size;
  2. the transform recovered (corner error under half a film pixel), blend = film + weight *
     difference, the distances of the lines over 16 points within two pixels (the same flow);
  3. the photograph given on the C++ filter's second input (a vtkPNGReader) equals FileName's;
  4. refused alike, with the same reason and empty outputs: a photograph of noise, a missing file,
     one point pair, a Blend Weight of 2;
  5. the blast's shock moved by a known distance (radius 0.04 larger, 2.2 film pixels), placed by
     two marks typed as Point Pairs with Refine None: bit for bit again, the blast's lines listed
     the move apart within half a film pixel, the plane shock's (over 16 points) under half a pixel.

    pvpython test_photograph_plugins.py --plugin build/lib/schlieren-python-plugin/SchlierenPython.py \\
        --work /tmp/photograph_plugins
(PYTHONPATH: the build's schlieren_vtk; SCHLIEREN_ENGINE_LIBRARY the engine). ParaView 5.11.0
under Python 3.11 needs inspect.getargspec for any Python plugin (docs/PYTHON.md): set below.
"""
import collections
import inspect
import math
import os
import re
import sys

if not hasattr(inspect, "getargspec"):  # ParaView 5.11.0 on Python >= 3.11
    _ArgSpec = collections.namedtuple("ArgSpec", "args varargs keywords defaults")
    inspect.getargspec = lambda f: _ArgSpec(*inspect.getfullargspec(f)[:4])

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np  # noqa: E402
from paraview.simple import LoadPlugin, TrivialProducer  # noqa: E402
from vtkmodules.util import numpy_support  # noqa: E402

import schlieren_testing as st  # noqa: E402
import schlieren_vtk  # noqa: E402
from test_photograph import test_volume, write  # noqa: E402

T = st.Checker("test_photograph_plugins")
work = st.argument("--work", "photograph_plugins")
os.makedirs(work, exist_ok=True)
LoadPlugin(st.argument("--plugin"), remote=False, ns=globals())
import schlieren_paraview_plugin._engine as engine  # noqa: E402 -- the Python plugin's package

OVERLAYS = ["Blend", "Checkerboard", "Difference", "Photograph", "Image"]
N = 112  # film pixels a side (at 80 the registration took 4 times longer: 16-20 s against 4 s)
# The lines whose distances are checked: more than 16 points. The engine's walk ends a line where
# the next point's direction leaves the line's chord over its last 8 points by 30 deg: where it
# meets another line (the plane shock's edge at the blast) or curves tighter than a radius of 9 to
# 12 pixels (the chord's direction is the tangent 4.5 steps back; the lump's soft edge, 8 pixels). Within those 8 points of the cut the photograph's ridge
# bends into the other feature or, where the edge is weak (1.0-1.3 times LineThreshold here), is
# lost in the photograph's noise, and a point's nearest photograph line is then the other
# feature's (docs/CFD.md: the map is the finer account there). A line of over twice 8 points, cut
# at both ends, has under half its points there: its median distance is its own. Shorter pieces
# are listed, not checked: the plane shock's edge between the lump and the blast (11 points) and
# the lump's edge (9 and 11) read 0.0006-0.0087 world units against photographs without noise,
# 0.0008-0.07 over six noise seeds of these 3000-photon photographs.
MEASURED = 2 * 8

# the film: the C++ SchlierenImage on the test volume
volume = test_volume(engine)
tracer = schlieren_vtk.vtkSchlierenImage()
tracer.SetInputData(volume)
tracer.SetResolution(N, N)
tracer.SetPasses(4)
tracer.SetBackend(schlieren_vtk.vtkSchlierenImage.CPU)
tracer.Update()
film = tracer.GetOutput()
pixel = film.GetSpacing()[0]
values = numpy_support.vtk_to_numpy(film.GetPointData().GetArray("intensity")).reshape(N, N)
truth = dict(scale=1.2, degrees=7.0, shift=(-10.0, 6.0))
photo = engine.synthetic_photograph(values, truth["scale"], truth["degrees"], truth["shift"],
                                    (140, 160), gamma=1.4, vignetting=0.2, photons=3000, seed=11)
png, jpg = os.path.join(work, "photo16.png"), os.path.join(work, "photo8.jpg")
write(photo, png, 16)
write(photo, jpg, 8, colour=True)

producer = TrivialProducer(registrationName="film")
producer.GetClientSideObject().SetOutput(film)
producer.UpdatePipeline()


def cxx_filter(**props):
    f = schlieren_vtk.vtkSchlierenPhotograph()
    f.SetInputData(film)
    for name, value in props.items():
        if name == "Overlay":
            value = OVERLAYS.index(value)
        elif name == "Refine":
            value = ["Similarity", "Rigid", "Shift", "None"].index(value)
        getattr(f, "Set" + name)(*(value if isinstance(value, list) else [value]))
    return f


def run_both(**props):
    """The C++ filter and the Python plugin's proxy with `props`: (outputs, error text) each, the
    Python class (its Report), the C++ filter and the proxy."""
    f = cxx_filter(**props)
    with st.CapturedStderr() as c:
        f.Update()
    py = SchlierenPhotograph(Input=producer, **props)  # noqa: F821 -- the plugin's
    with st.CapturedStderr() as p:
        py.UpdatePipeline()
    alg = py.GetClientSideObject()
    return ((f.GetOutputDataObject(0), f.GetOutputDataObject(1)), c.text,
            (alg.GetOutputDataObject(0), alg.GetOutputDataObject(1)), p.text, alg, f, py)


def arrays(attributes):
    return {attributes.GetAbstractArray(k).GetName(): attributes.GetAbstractArray(k)
            for k in range(attributes.GetNumberOfArrays())}


def same_attributes(a, b, what):
    """The arrays of two vtkFieldData/vtkDataSetAttributes: the same names, types and bits."""
    x, y = arrays(a), arrays(b)
    T.check(sorted(x) == sorted(y), "%s: the same arrays %s (C++ only %s, Python only %s)"
            % (what, sorted(x), sorted(set(x) - set(y)), sorted(set(y) - set(x))))
    differ = []
    for name in sorted(set(x) & set(y)):
        u, v = x[name], y[name]
        if name == "photograph_report":
            # the engine's JSON, but for the seconds each registration took
            timeless = lambda a: re.sub(r'"seconds": [^,]*,', "", a.GetValue(0))  # noqa: E731
            ok = timeless(u) == timeless(v)
        elif u.IsA("vtkStringArray") or v.IsA("vtkStringArray"):
            ok = u.IsA("vtkStringArray") and v.IsA("vtkStringArray") and \
                [u.GetValue(i) for i in range(u.GetNumberOfValues())] == \
                [v.GetValue(i) for i in range(v.GetNumberOfValues())]
        else:
            p, q = numpy_support.vtk_to_numpy(u), numpy_support.vtk_to_numpy(v)
            ok = p.dtype == q.dtype and p.shape == q.shape and p.tobytes() == q.tobytes()
        if not ok:
            differ.append(name)
    T.check(not differ, "%s: every array bit for bit (differ: %s)" % (what, differ))


def same_outputs(cxx, py, what):
    (c0, c1), (p0, p1) = cxx, py
    T.check(c0.GetDimensions() == p0.GetDimensions() == (N, N, 1) and
            c0.GetOrigin() == p0.GetOrigin() and c0.GetSpacing() == p0.GetSpacing(),
            "%s: the film's grid (%s, origin %s)" % (what, c0.GetDimensions(), c0.GetOrigin()))
    same_attributes(c0.GetPointData(), p0.GetPointData(), what + ", point data")
    active = (c0.GetPointData().GetScalars(), p0.GetPointData().GetScalars())
    T.check(None not in active and active[0].GetName() == active[1].GetName(),
            "%s: the active scalars %s" % (what, [a.GetName() if a else None for a in active]))
    same_attributes(c0.GetFieldData(), p0.GetFieldData(), what + ", field data")
    T.check(c1.GetNumberOfCells() == p1.GetNumberOfCells() > 0 and
            numpy_support.vtk_to_numpy(c1.GetPoints().GetData()).tobytes() ==
            numpy_support.vtk_to_numpy(p1.GetPoints().GetData()).tobytes() and
            numpy_support.vtk_to_numpy(c1.GetLines().GetConnectivityArray()).tobytes() ==
            numpy_support.vtk_to_numpy(p1.GetLines().GetConnectivityArray()).tobytes(),
            "%s: %d lines, their points and cells bit for bit" % (what, c1.GetNumberOfCells()))
    same_attributes(c1.GetCellData(), p1.GetCellData(), what + ", the lines' cell data")


def corner_error(report):
    """The largest distance at the film's corners between the true and the found transform,
    film pixels (the convention of schlieren_photograph: film centre to photograph centre)."""
    worst = 0.0
    for cx in (0, N - 1):
        for cy in (0, N - 1):
            x, y = cx - 0.5 * (N - 1), cy - 0.5 * (N - 1)

            def place(s, deg, t):
                th = math.radians(deg)
                return (s * (math.cos(th) * x - math.sin(th) * y) + t[0],
                        s * (math.sin(th) * x + math.cos(th) * y) + t[1])
            u0 = place(truth["scale"], truth["degrees"], truth["shift"])
            u1 = place(report["scale"], report["rotation"], report["shift"])
            worst = max(worst, math.hypot(u1[0] - u0[0], u1[1] - u0[1]) / truth["scale"])
    return worst


# 1-2. both files, two overlays
for path, props in ((png, dict(Overlay="Blend")),
                    (jpg, dict(Overlay="Checkerboard", BlendWeight=0.3, CheckerSize=8))):
    what = "%s, Overlay %s" % (os.path.basename(path), props["Overlay"])
    cxx, cxx_text, py, py_text, alg, f, proxy = run_both(FileName=path, **props)
    r = alg.Report
    T.check(r is not None and r["match"], "%s: registered (score %.3f, threshold %.3f, %.2f s)"
            % (what, r["score"] if r else -1, r["threshold"] if r else -1, r["seconds"] if r else -1))
    same_outputs(cxx, py, what)
    out = cxx[0]
    want = {"Blend": "blend", "Checkerboard": "checkerboard"}[props["Overlay"]]
    T.check(out.GetPointData().GetScalars().GetName() == want,
            "%s: the active scalars are %s" % (what, want))
    err = corner_error(r)
    T.check(err < 0.5, "%s: the transform within %.3f film pixels at the corners (< 0.5; scale "
            "%.4f, rotation %.3f deg, shift %.2f %.2f)" % (what, err, r["scale"], r["rotation"],
                                                         r["shift"][0], r["shift"][1]))
    get = lambda name: numpy_support.vtk_to_numpy(out.GetPointData().GetArray(name))  # noqa: E731
    weight = props.get("BlendWeight", 0.5)
    T.close(get("blend"), get("intensity") + weight * get("difference"), 1e-6,
            "%s: blend = film + %.1f difference" % (what, weight))
    distance = numpy_support.vtk_to_numpy(cxx[1].GetCellData().GetArray("line_distance"))
    image = numpy_support.vtk_to_numpy(cxx[1].GetCellData().GetArray("image"))
    points = np.array([cxx[1].GetCell(k).GetNumberOfPoints() for k in range(cxx[1].GetNumberOfCells())])
    film_lines = (image == 0) & ~np.isnan(distance)
    matched = distance[film_lines & (points > MEASURED)]
    print("%s: the film's lines over %d points %s, shorter %s (a pixel %.4f)"
          % (what, MEASURED, ["%.4f" % d for d in matched],
             ["%.4f" % d for d in distance[film_lines & (points <= MEASURED)]], pixel))
    T.check(matched.size >= 6 and matched.max() < 2 * pixel,
            "%s: the film's %d matched lines over %d points within 2 pixels of the photograph's "
            "(largest %.4g, a pixel %.4g)" % (what, matched.size, MEASURED,
                                               matched.max() if matched.size else -1, pixel))
    if path == png:
        by_name = f
        # Overlay Difference on both: the same registration (not done again), another view
        f.SetOverlay(OVERLAYS.index("Difference"))
        f.Update()
        proxy.Overlay = "Difference"
        proxy.UpdatePipeline()
        T.check(alg.Report is r, "%s: Overlay Difference keeps the registration" % what)
        same_outputs((f.GetOutputDataObject(0), f.GetOutputDataObject(1)),
                     (alg.GetOutputDataObject(0), alg.GetOutputDataObject(1)), what + " then Difference")
        T.check(f.GetOutput().GetPointData().GetScalars().GetName() == "difference",
                "%s then Difference: the active scalars are difference" % what)

# 3. the photograph on the C++ filter's second input: FileName's bits
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402
reader = vtkPNGReader()
reader.SetFileName(png)
by_port = cxx_filter()
by_port.SetInputConnection(1, reader.GetOutputPort())
by_port.Update()
same_attributes(by_port.GetOutput().GetPointData(), by_name.GetOutput().GetPointData(),
                "the C++ filter's second input against its FileName")

# 5. the blast's shock moved by a known distance (its radius 0.04 larger: 2.2 film pixels), the
# photograph placed by two marks typed as Point Pairs with Refine None (a correlation would pull
# toward the moved shock): the blast's lines listed that far apart, the plane shock's not moved
move = 0.04
moved_volume = test_volume(engine, 0.4 + move)
moved_tracer = schlieren_vtk.vtkSchlierenImage()
moved_tracer.SetInputData(moved_volume)
moved_tracer.SetResolution(N, N)
moved_tracer.SetPasses(4)
moved_tracer.SetBackend(schlieren_vtk.vtkSchlierenImage.CPU)
moved_tracer.Update()
moved_values = numpy_support.vtk_to_numpy(
    moved_tracer.GetOutput().GetPointData().GetArray("intensity")).reshape(N, N)
moved_photo = engine.synthetic_photograph(moved_values, truth["scale"], truth["degrees"], truth["shift"],
                                          (140, 160), gamma=1.4, vignetting=0.2, photons=3000, seed=12)
moved_png = os.path.join(work, "moved16.png")
write(moved_photo, moved_png, 16)
origin = film.GetOrigin()
pairs = []
for i, j in ((12, 10), (N - 15, N - 12)):  # film pixels of two marks, their photograph pixels
    x, y = i - 0.5 * (N - 1), j - 0.5 * (N - 1)
    t = math.radians(truth["degrees"])
    pairs += [truth["scale"] * (math.cos(t) * x - math.sin(t) * y) + 0.5 * (160 - 1) + truth["shift"][0],
              truth["scale"] * (math.sin(t) * x + math.cos(t) * y) + 0.5 * (140 - 1) + truth["shift"][1],
              origin[0] + i * pixel, origin[1] + j * pixel]
typed = " ".join("%.6f" % v for v in pairs)
cxx, cxx_text, py, py_text, alg, f, proxy = run_both(FileName=moved_png, PointPairs=typed, Refine="None")
same_outputs(cxx, py, "the moved blast on two marks")
cd = cxx[1].GetCellData()
lines = [(int(cd.GetArray("image").GetValue(k)), float(cd.GetArray("line_distance").GetValue(k)),
          cxx[1].GetCell(k).GetBounds(), cxx[1].GetCell(k).GetNumberOfPoints())
         for k in range(cxx[1].GetNumberOfCells())]
# the blast's lines: the film's lines right of the plane shock (x > -0.1); the plane shock's: near x
# -0.25 (x bounds in -0.35 to -0.15); over MEASURED points (above)
blast = [d for image, d, b, n in lines if image == 0 and d == d and b[0] > -0.1 and n > MEASURED]
plane = [d for image, d, b, n in lines if image == 0 and d == d and b[1] < -0.15 and b[0] > -0.35 and n > MEASURED]
print("moved blast: the blast's lines %s, the plane shock's %s, the plane shock's pieces of %d points "
      "or fewer %s (moved %g, a pixel %.4g)"
      % (["%.4f" % d for d in blast], ["%.4f" % d for d in plane], MEASURED,
         ["%.4f" % d for image, d, b, n in lines if image == 0 and d == d and b[1] < -0.15 and
          b[0] > -0.35 and n <= MEASURED], move, pixel))
T.check(alg.Report is not None and alg.Report["match"] and blast and
        abs(float(np.median(blast)) - move) < 0.5 * pixel,
        "the moved blast: its lines' median distance %.4f for a move of %g (within half a film pixel, %.4f)"
        % (float(np.median(blast)) if blast else -1, move, 0.5 * pixel))
T.check(len(plane) >= 3 and max(plane) < 0.5 * pixel,
        "the plane shock did not move: %s (under half a film pixel)" % ["%.4f" % d for d in plane])

# 4. refused alike
noise = np.random.default_rng(3).poisson(400, (64, 72)).astype(np.float32)  # small: quick to refuse
noise_png = os.path.join(work, "noise.png")
write(noise, noise_png, 16)
for what, props, needle in (
        ("a photograph of noise", dict(FileName=noise_png), "The photograph was not registered: "),
        ("a missing file", dict(FileName=os.path.join(work, "none.png")), "was not found"),
        ("one point pair", dict(FileName=png, PointPairs="1 2 3 4"), "PointPairs"),
        ("Blend Weight 2", dict(FileName=png, BlendWeight=2.0), "BlendWeight")):
    cxx, cxx_text, py, py_text, alg, f, proxy = run_both(**props)
    plain = lambda text: re.sub(r"\x1b\[[0-9;]*m", "", text)  # noqa: E731 -- no colours
    cxx_text, py_text = plain(cxx_text), plain(py_text)
    reason = lambda text: re.findall(r"(?:ERR\||ERROR:).*?(\S*" + needle + r".*)", text)  # noqa: E731
    c, p = reason(cxx_text), reason(py_text)
    message = lambda text: re.sub(r"^.*?In \w+: ", "", text[0]).strip() if text else ""  # noqa: E731
    T.check(c and p, "%s refused by both: C++ %r, Python %r" % (what, c[:1], p[:1]))
    T.check(all(o.GetNumberOfPoints() == 0 for o in cxx + py),
            "%s: both outputs empty" % what)
    if what == "a photograph of noise":
        tail = lambda text: text[text.find(needle):].strip() if needle in text else ""  # noqa: E731
        T.check(tail(message(c)) == tail(message(p)) and "below the threshold" in tail(message(c)),
                "%s: the same reason: %s" % (what, tail(message(c))[:160]))
T.finish()
