"""First light: a knife-edge schlieren image of a built-in scene, written to a PNG.

    pvpython Examples/first_light.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/schlieren.png

The scene is a Gaussian sphere of denser air, n = 1 + A exp(-r^2/s^2) with A = 1e-4, s = 0.25 m on a
128^3 grid over [-1, 1]^3 m; the beam runs along -z and a vertical knife edge (normal along the
film's x) cuts the deflected light, so one side of the sphere is bright and the other dark. Runs
without a display: the image is written from the filter's output array, no render view is needed.
"""
import argparse
import os
import sys

from paraview.simple import LoadPlugin, servermanager


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True, help="path to Schlieren.so")
    ap.add_argument("--output", default="schlieren.png")
    ap.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    ap.add_argument("--resolution", type=int, default=512)
    ap.add_argument("--passes", type=int, default=8)
    args = ap.parse_args()

    LoadPlugin(args.plugin, remote=False, ns=globals())
    scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[128, 128, 128],  # noqa: F821
                            Bounds=[-1, 1, -1, 1, -1, 1], Amplitude=1e-4, Width=0.25)
    index = RefractiveIndex(Input=scene, Model="Passthrough")  # noqa: F821
    index.InputArray = ["POINTS", "n_minus_1"]
    image = SchlierenImage(Input=index, Cutoff="KnifeEdge", KnifeAngle=0.0,  # noqa: F821
                           Resolution=[args.resolution, args.resolution], Passes=args.passes,
                           Backend=args.backend)
    image.UpdatePipeline()
    out = servermanager.Fetch(image)
    if out is None or out.GetPointData().GetArray("intensity") is None:
        sys.exit("first_light: the trace produced no image (see the errors above)")
    fd = out.GetFieldData()
    backend = fd.GetAbstractArray("backend")
    device = fd.GetAbstractArray("device")
    k = fd.GetArray("cutoff_scale")

    import schlieren_view  # beside the plugin, importable after LoadPlugin

    schlieren_view.write_png(schlieren_view.film_array(out, "intensity"), args.output)
    rng = out.GetPointData().GetArray("intensity").GetRange()
    print("wrote %s: %dx%d knife-edge schlieren of a Gaussian sphere, intensity %.3f..%.3f, k = %.4g, "
          "traced on %s (%s)" % (os.path.abspath(args.output), args.resolution, args.resolution,
                                 rng[0], rng[1], k.GetValue(0) if k else float("nan"),
                                 backend.GetValue(0) if backend else "?",
                                 device.GetValue(0) if device else "?"))


if __name__ == "__main__":
    main()
