"""A photograph beside the image (issue 51): a "photograph" made from a solved OpenFOAM case (Mach 5
over a 15 degree wedge, rhoCentralFoam) with a camera's transform, gamma, vignetting, blur and
photon noise, registered onto our traced film, its grey calibrated, and the distances between the
two images' shocks printed; the images written (film, photograph, checkerboard, difference, the
lines coloured by their distance).

    SCHLIEREN_ENGINE_LIBRARY=build/OpenCL/libschlieren_engine.so.1 \
    pvpython Examples/photograph.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/photograph

(the photograph is made with the Python package in Python/, which loads the engine library: a
build tree has it in build/OpenCL/, an installed wheel beside the package).

Two photographs: one of the same time as the film, registered without a start and with the bench's
magnification (the lines agree: distances of a fraction of a pixel), one of an earlier time of the
solve registered on two marks (--photo-time; by the first time written, 0.1 s, the shock has
settled: the distances say so). Without --case the
tutorial is meshed and solved next to the output with Testing/Python/openfoam_cases.py (exits 125,
skipped, where OpenFOAM is not installed).
"""
import argparse
import math
import os
import sys

from paraview.simple import LoadPlugin, OpenFOAMReader, servermanager

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Python"))
import numpy as np  # noqa: E402

from schlieren import engine  # noqa: E402
from schlieren.png import write_png  # noqa: E402


def film_at(reader, image, time):
    """The film's intensity (ny, nx), its origin and pixel at `time`."""
    from vtkmodules.util import numpy_support
    image.UpdatePipeline(time)
    out = servermanager.Fetch(image)
    nx, ny, _ = out.GetDimensions()
    a = numpy_support.vtk_to_numpy(out.GetPointData().GetArray("intensity")).reshape(ny, nx)
    e, o, s = out.GetExtent(), out.GetOrigin(), out.GetSpacing()
    return a.astype(np.float32), [o[0] + e[0] * s[0], o[1] + e[2] * s[1]], s[0]


def coloured_lines(film, r, pixel):
    """The film in grey with the film's lines coloured by their distance to the photograph's:
    green at 0, red at 4 pixels and beyond; the photograph's lines in blue."""
    rgb = np.repeat(np.clip(film, 0, 1)[..., None], 3, axis=2) * 0.7
    d = r["images"]["line_distance"]
    t = np.clip(np.nan_to_num(d / (4 * pixel)), 0, 1)
    on = ~np.isnan(d)
    rgb[on] = np.stack([t[on], 1 - t[on], np.zeros(on.sum())], axis=1)
    for line in r["lines"]:
        if line["image"] != "photograph":
            continue
        xy = np.asarray(line["points"]).reshape(-1, 2)
        i = np.clip(np.round((xy[:, 0] - r["_origin"][0]) / pixel).astype(int), 0, film.shape[1] - 1)
        j = np.clip(np.round((xy[:, 1] - r["_origin"][1]) / pixel).astype(int), 0, film.shape[0] - 1)
        rgb[j, i] = [0.2, 0.4, 1.0]
    return rgb


def report(name, r, truth, pixel):
    print("\n%s: %s" % (name, "registered" if r["match"] else "REFUSED: " + r["reason"]))
    print("  score %.3f (threshold %.3f from scrambled copies reaching %.3f), start: %s"
          % (r["score"], r["threshold"], r["null_score"], r["start"]))
    if truth:
        print("  scale %.4f (true %.4f), rotation %.3f deg (true %.3f), shift %.2f %.2f px (true %.2f %.2f); "
              "uncertainty at the film's corner %.3f px"
              % (r["scale"], truth[0], r["rotation"], truth[1], r["shift"][0], r["shift"][1], truth[2][0],
                 truth[2][1], r["edge_uncertainty"]))
    if r.get("warnings"):
        print("  warning: " + r["warnings"])
    print("  grey: %s gamma %.3f +- %.3f, background %.3f, vignetting at the corner %.3f, residual %.3f (log)%s"
          % ("fitted" if r["grey_fitted"] else "not fitted:", r["gamma"], r["gamma_error"], r["background"],
             r["vignetting"], r["grey_residual"], (" - " + r["grey_reason"]) if r["grey_reason"] else ""))
    film_lines = [l for l in r["lines"] if l["image"] == "film"]
    print("  %d lines of the film, %d of the photograph; the film's, longest first:"
          % (len(film_lines), len(r["lines"]) - len(film_lines)))
    for l in sorted(film_lines, key=lambda l: -len(l["points"]))[:6]:
        xy = np.asarray(l["points"]).reshape(-1, 2)
        d = l["distance"]
        print("    %3d points from (%.4f, %.4f) to (%.4f, %.4f) m: %s" % (
            len(xy), xy[0, 0], xy[0, 1], xy[-1, 0], xy[-1, 1],
            "distance %.2f mm (%.2f px), offset (%.2f, %.2f) mm, %.0f %% matched" % (
                1e3 * d, d / pixel, 1e3 * l["offset"][0], 1e3 * l["offset"][1], 100 * l["matched"])
            if d is not None and d >= 0 else "no line of the photograph within reach"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True, help="path to Schlieren.so")
    ap.add_argument("--case", default=None, help="the wedge15Ma5 case's .foam file (default: solved here)")
    ap.add_argument("--photo-time", type=float, default=None,
                    help="the time of the second photograph (default: the first time written after 0)")
    ap.add_argument("--output", default="photograph", help="folder of the images")
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    case = args.case
    if case is None:
        sys.path.insert(0, os.path.join(HERE, "..", "Testing", "Python"))
        import openfoam_cases
        why = openfoam_cases.available()
        if why:
            print("SKIP: %s" % why)
            sys.exit(125)
        folder = os.path.join(os.path.abspath(args.output), "openfoam")
        if not openfoam_cases.run_case(folder, "wedge15Ma5"):
            sys.exit("photograph: the tutorial case could not be solved")
        case = os.path.join(folder, "wedge15Ma5", "case.foam")
    LoadPlugin(args.plugin, remote=False, ns=globals())
    reader = OpenFOAMReader(FileName=case)
    reader.UpdatePipelineInformation()
    times = [t for t in reader.TimestepValues if t > 0]
    index = RefractiveIndex(Input=reader, Symmetry="Planar", Span=0.1,  # noqa: F821
                            SamplingDimensions=[458, 153, 3])
    image = SchlierenImage(Input=index, Cutoff="KnifeEdge", Resolution=[458, 153], Passes=4,  # noqa: F821
                           ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], CutoffScale=400.0)
    film, origin, pixel = film_at(reader, image, times[-1])
    print("film %d x %d pixels of %.3f mm at t = %g s (the solve's last time)" % (film.shape[1], film.shape[0],
                                                                             1e3 * pixel, times[-1]))
    write_png(film, os.path.join(args.output, "film.png"))

    # 1. the same time: a camera at 1.15 photograph pixels a film pixel, turned 4 degrees
    truth = (1.15, 4.0, (10.0, -6.0))
    cam = dict(size=(200, 560), gamma=0.6, vignetting=0.25, blur=1.2, photons=2000)
    photo = engine.synthetic_photograph(film, *truth, **cam)
    write_png(photo / photo.max(), os.path.join(args.output, "photograph.png"))
    # without a start the scale is searched: a wedge's flow is conical (the shock from the apex is
    # its own image under a scale about the apex), so the scale is held by the lines' ends alone and
    # the uncertainty says so; the bench's magnification (PhotoPixelSize) fixes it
    r0 = engine.photograph(film, origin, pixel, photo)
    r0["_origin"] = origin
    report("the same time, no start (scale searched)", r0, truth, pixel)
    r = engine.photograph(film, origin, pixel, photo, {"PhotoPixelSize": pixel / truth[0]})
    r["_origin"] = origin
    report("the same time, the bench's magnification given", r, truth, pixel)
    if r["match"]:
        write_png(r["images"]["checkerboard"], os.path.join(args.output, "checkerboard.png"))
        write_png(0.5 + r["images"]["difference"], os.path.join(args.output, "difference.png"))
        write_png(coloured_lines(film, r, pixel), os.path.join(args.output, "lines.png"))
        # the gallery's panel (docs/gallery/photograph.png), top to bottom: the film, the
        # checkerboard, the difference, the lines (rows stack bottom first: the film last)
        grey = lambda a: np.repeat(np.clip(a, 0, 1)[..., None], 3, axis=2)  # noqa: E731
        gap = np.ones((4,) + film.shape[1:] + (3,))
        write_png(np.concatenate([coloured_lines(film, r, pixel), gap, grey(0.5 + r["images"]["difference"]),
                                  gap, grey(r["images"]["checkerboard"]), gap, grey(film)]),
                  os.path.join(args.output, "photograph_gallery.png"))

    # 2. an earlier time, registered on two marks whose places are known on the model and in the
    # photograph (a correlation would pull the registration toward the moved shock)
    t2 = args.photo_time if args.photo_time is not None else times[0]
    early, _, _ = film_at(reader, image, t2)
    photo2 = engine.synthetic_photograph(early, *truth, **cam)
    write_png(photo2 / photo2.max(), os.path.join(args.output, "photograph_early.png"))
    ny, nx = film.shape
    pairs = []
    for (i, j) in ((20, 15), (nx - 30, ny - 20)):  # film pixels of the marks
        x, y = i - 0.5 * (nx - 1), j - 0.5 * (ny - 1)
        th = math.radians(truth[1])
        u = truth[0] * (math.cos(th) * x - math.sin(th) * y) + 0.5 * (cam["size"][1] - 1) + truth[2][0]
        v = truth[0] * (math.sin(th) * x + math.cos(th) * y) + 0.5 * (cam["size"][0] - 1) + truth[2][1]
        pairs += [u, v, origin[0] + i * pixel, origin[1] + j * pixel]
    r2 = engine.photograph(film, origin, pixel, photo2, {"PointPairs": pairs, "Refine": "None"})
    r2["_origin"] = origin
    report("t = %g s against t = %g s (two marks)" % (t2, times[-1]), r2, truth, pixel)
    if r2["match"]:
        write_png(coloured_lines(film, r2, pixel), os.path.join(args.output, "lines_early.png"))
        write_png(0.5 + r2["images"]["difference"], os.path.join(args.output, "difference_early.png"))
    print("\nimages in %s" % os.path.abspath(args.output))
    return 0 if r["match"] else 1


if __name__ == "__main__":
    sys.exit(main())
