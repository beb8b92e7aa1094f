# SPDX-License-Identifier: BSD-3-Clause
"""python -m schlieren demo [--output schlieren.png] [--backend Auto|OpenCL|CPU] [--resolution N]
python -m schlieren bos --folder DIR [--bits 8|16] [--format png|tiff] [--prefix bos] ...
python -m schlieren info

demo: the project's demo image (README): a knife-edge schlieren of a Gaussian sphere of denser
air, n = 1 + 1e-4 exp(-r^2/s^2), s = 0.25, on a 128^3 grid; engine and NumPy only (no VTK).
bos: the same sphere (--amplitude, default 1e-3) seen by background-oriented schlieren
(--background-distance), written as the image pair PIV codes read (OpenPIV and others): the
undistorted background, the recording and the side file <prefix>.json (docs/BENCH.md "BOS image
pairs").
info: the version, the library loaded and the OpenCL device the engine would use.

Errors are one line on stderr: exit code 2 for bad arguments (a resolution or a number of passes
the engine refuses, an output folder that does not exist, an output that is a folder, a bit depth
not 8 or 16), 1 for a failure of the engine or of writing the image."""
import argparse
import os
import sys

from . import _engine
from .png import write_png


class UsageError(Exception):
    """A bad argument: one line on stderr, exit code 2."""


def _sphere_session(args, settings, amplitude):
    """A session that has traced the Gaussian sphere (128^3, s = 0.25, n - 1 = amplitude at its
    centre) with the common arguments and `settings` (proxy names); returns (session, report)."""
    dims, origin = [128, 128, 128], [-1.0, -1.0, -1.0]
    spacing = [2.0 / 127] * 3
    s = _engine.Session()
    # the arguments the engine refuses (its ranges, as every front end's): before any work
    for k, v, arg in (("Resolution", [args.resolution] * 2, "--resolution %d" % args.resolution),
                      ("Passes", args.passes, "--passes %d" % args.passes),
                      ("Backend", args.backend, "--backend %s" % args.backend)):
        try:
            s.set(k, v)
        except _engine.EngineError as e:
            raise UsageError("%s: %s" % (arg, e))
    for k, v in settings:
        s.set(k, v)
    try:
        s.plan_film(dims, origin, spacing)
    except _engine.EngineError as e:
        which = "--resolution" if "Resolution" in str(e) else \
            "--passes" if "Passes" in str(e) else \
            "--background-distance" if "BackgroundDistance" in str(e) else "an argument"
        raise UsageError("%s: %s" % (which, e))
    scene = _engine.fill_scene(dict(Scene="GaussianSphere", Amplitude=amplitude, Width=0.25), dims,
                               origin, spacing)
    s.set_volume(dims, origin, spacing, scene["n_minus_1"])
    report = s.trace()
    for note in report["notes"]:
        if note["warning"]:
            print("warning: " + note["text"], file=sys.stderr)
    return s, report


def demo(args):
    out = os.path.abspath(args.output)
    if os.path.isdir(out):
        raise UsageError("--output %s is a folder: give a file name (e.g. %s)"
                         % (args.output, os.path.join(args.output, "schlieren.png")))
    if not os.path.isdir(os.path.dirname(out)):
        raise UsageError("--output %s: the folder %s does not exist"
                         % (args.output, os.path.dirname(out)))
    s, report = _sphere_session(args, [("Cutoff", "KnifeEdge"), ("KnifeAngle", 0.0)], 1e-4)
    size, _, _ = s.film()
    intensity = s.array("intensity").reshape(size[1], size[0])
    write_png(intensity, args.output)
    f = report["field_data"]
    print("wrote %s: %dx%d knife-edge schlieren of a Gaussian sphere, intensity %.3f..%.3f, "
          "k = %.4g, traced on %s (%s)" % (os.path.abspath(args.output), size[0], size[1],
                                           intensity.min(), intensity.max(), f["cutoff_scale"],
                                           f["backend"], f["device"] or "all cores"))
    return 0


def bos(args):
    folder = os.path.abspath(args.folder)
    if not os.path.isdir(folder):
        raise UsageError("--folder %s: the folder does not exist (make it first)" % args.folder)
    if args.bits not in (8, 16):
        raise UsageError("--bits %d: PIV codes read 8 or 16 bits" % args.bits)
    s, report = _sphere_session(args, [("Cutoff", "BOS"),
                                       ("BackgroundDistance", args.background_distance)],
                                args.amplitude)
    try:
        files = s.write_bos_pair(folder, args.bits, args.format, args.prefix)
    except _engine.EngineError as e:
        raise UsageError(str(e))
    size, _, pixel = s.film()
    shift = s.array("bos_displacement")
    peak = float((shift ** 2).sum(axis=1).max() ** 0.5 / pixel)
    print("wrote %s, %s and %s: %dx%d BOS of a Gaussian sphere (n - 1 = %g), largest "
          "displacement %.3f px, traced on %s" % (files["background"], files["recording"],
                                                  files["side_file"], size[0], size[1],
                                                  args.amplitude, peak,
                                                  report["field_data"]["backend"]))
    return 0


def info(args):
    print("schlieren %s (C API %d) from %s" % (_engine.version(), _engine.API_VERSION,
                                               _engine._lib._name))
    d = _engine.opencl_device()
    print("OpenCL: " + (d["name"] + " (" + d["platform"] + ")" if d["available"]
                        else "none: " + d["reason"]))
    return 0


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        # one line, not the usage block (python -m schlieren --help shows that)
        raise UsageError(message)


def main(argv=None):
    try:
        return _main(argv)
    except UsageError as e:
        print("python -m schlieren: error: %s" % " ".join(str(e).split()), file=sys.stderr)
        return 2
    except (_engine.EngineError, OSError, MemoryError) as e:
        print("python -m schlieren: %s" % " ".join(str(e).split()), file=sys.stderr)
        return 1


def _main(argv):
    ap = _Parser(prog="python -m schlieren", description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="command", required=True, parser_class=_Parser)
    d = sub.add_parser("demo", help="write the demo image")
    d.add_argument("--output", default="schlieren.png")
    d.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    d.add_argument("--resolution", type=int, default=512)
    d.add_argument("--passes", type=int, default=8)
    b = sub.add_parser("bos", help="write a BOS image pair for PIV codes (OpenPIV)")
    b.add_argument("--folder", required=True, help="an existing folder for the pair")
    b.add_argument("--bits", type=int, default=8, help="8 or 16 bits per grey level")
    b.add_argument("--format", default="png", choices=["png", "tiff"])
    b.add_argument("--prefix", default="bos")
    b.add_argument("--amplitude", type=float, default=1e-3, help="n - 1 at the sphere's centre")
    b.add_argument("--background-distance", type=float, default=10.0,
                   help="world units from the volume's box to the background")
    b.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    b.add_argument("--resolution", type=int, default=512)
    b.add_argument("--passes", type=int, default=8)
    sub.add_parser("info", help="the library and the OpenCL device")
    args = ap.parse_args(argv)
    return {"demo": demo, "bos": bos, "info": info}[args.command](args)


if __name__ == "__main__":
    sys.exit(main())
