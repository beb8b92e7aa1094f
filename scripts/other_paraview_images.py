"""The images scripts/other-paraview.sh holds against Debian 12's: the first-light Gaussian sphere
(Examples/first_light.py's scene, 128^2, 2 passes) and the blunt fin (Examples/bluntfin.py's top
view, 2 passes), each on the CPU and on OpenCL, written as raw float32 arrays (.npy) with a SHA-256
of their bytes; or, with --compare, two such folders compared (bit for bit, else the largest
difference in units in the last place and how many values differ).

    pvpython scripts/other_paraview_images.py --plugin <Schlieren.so> --output <folder>
    /usr/bin/python3 scripts/other_paraview_images.py --compare <folder A> <folder B>
"""
import argparse
import glob
import hashlib
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ARRAYS = ("intensity", "deflection")


def trace(args):
    from paraview.simple import LoadPlugin, servermanager
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy as np

    sys.path.insert(0, os.path.join(HERE, "..", "Examples"))
    ns = globals()  # LoadPlugin fills the namespace given (an empty dict counts as none)
    LoadPlugin(args.plugin, remote=False, ns=ns)
    os.makedirs(args.output, exist_ok=True)
    cases = []
    scene = ns["RefractiveScene"](Scene="GaussianSphere", Dimensions=[128, 128, 128],
                                  Bounds=[-1, 1, -1, 1, -1, 1], Amplitude=1e-4, Width=0.25)
    index = ns["RefractiveIndex"](Input=scene, Model="Passthrough")
    index.InputArray = ["POINTS", "n_minus_1"]
    cases.append(("first_light", index, dict(KnifeAngle=0.0, Resolution=[128, 128])))
    from bluntfin import blunt_fin_index
    fin = blunt_fin_index(ns, args.data, AutomaticDimension=160)
    if fin is None:
        print("no blunt fin data in %s: the first-light image only" % args.data)
    else:
        cases.append(("bluntfin", fin, dict(ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], Resolution=[800, 400],
                                            KnifeAngle=0.0, CutoffScale=40.0)))
    for name, source, view in cases:
        for backend in ("CPU", "OpenCL"):
            image = ns["SchlierenImage"](Input=source, Cutoff="KnifeEdge", Passes=2, Backend=backend, **view)
            image.UpdatePipeline()
            out = servermanager.Fetch(image)
            used = out.GetFieldData().GetAbstractArray("backend")
            if used is None or used.GetValue(0) != backend:
                sys.exit("%s: asked for %s, traced on %s" % (name, backend, used.GetValue(0) if used else "?"))
            for a in ARRAYS:
                arr = out.GetPointData().GetArray(a)
                if arr is None:
                    continue
                v = np.ascontiguousarray(vtk_to_numpy(arr))
                path = os.path.join(args.output, "%s_%s_%s.npy" % (name, backend, a))
                np.save(path, v)
                print("%-40s %s %s %s" % (os.path.basename(path), v.dtype, v.shape,
                                          hashlib.sha256(v.tobytes()).hexdigest()[:16]))


def compare(a, b):
    import numpy as np
    names = sorted(os.path.basename(p) for p in glob.glob(os.path.join(a, "*.npy")))
    if not names:
        sys.exit("no .npy files in %s" % a)
    same = True
    for n in names:
        x = np.load(os.path.join(a, n))
        pb = os.path.join(b, n)
        if not os.path.exists(pb):
            print("%-40s missing in %s" % (n, b))
            same = False
            continue
        y = np.load(pb)
        if x.shape == y.shape and x.dtype == y.dtype and x.tobytes() == y.tobytes():
            print("%-40s bit for bit" % n)
            continue
        same = False
        if x.shape != y.shape or x.dtype != y.dtype:
            print("%-40s differs in shape or type: %s %s / %s %s" % (n, x.shape, x.dtype, y.shape, y.dtype))
            continue
        xi = x.astype(np.float32).view(np.int32).astype(np.int64)
        yi = y.astype(np.float32).view(np.int32).astype(np.int64)
        ulp = np.abs(xi - yi)
        print("%-40s %d of %d values differ, at most %d ulp (largest |difference| %.3g)"
              % (n, int(np.count_nonzero(ulp)), ulp.size, int(ulp.max()),
                 float(np.max(np.abs(x.astype(np.float64) - y.astype(np.float64))))))
    return same


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin")
    ap.add_argument("--output")
    ap.add_argument("--data", default=os.environ.get("SCHLIEREN_DATA") or
                    os.path.join(HERE, "..", "..", "shared", "data"))
    ap.add_argument("--compare", nargs=2, metavar="FOLDER")
    args = ap.parse_args()
    if args.compare:
        sys.exit(0 if compare(*args.compare) else 1)
    if not (args.plugin and args.output):
        ap.error("--plugin and --output, or --compare A B")
    trace(args)


if __name__ == "__main__":
    main()
