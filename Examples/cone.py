"""An axisymmetric result as a laboratory sees it: the Mach 2 flow over a 15 degree cone, given as
an r-x half plane, revolved about its axis and imaged across it (knife edge) and along it, to PNGs.

    pvpython Examples/cone.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/cone.png

The data (cone_m2_15deg.vtu, 67731 points, 1 MB, written next to the output by
Examples/make_cone_flow.py where --data is not given or missing) is not a CFD run: it is the closed-form Taylor-Maccoll solution a CFD code converges to, on an
unstructured mesh of quads in the x-y plane (r along y) with a hole where the cone is. The conical
shock leaves the tip at 33.9 degrees; between it and the cone the density rises from 0.947 kg/m^3
behind the shock to 1.090 on the surface, over a free stream of 0.792.

    XMLUnstructuredGridReader -> RefractiveIndex (Model Automatic: GladstoneDale on `density`;
        Symmetry Axisymmetric about x) -> SchlierenImage (knife edge across the axis; along it)

The filter revolves the half plane onto a 3D grid (SamplingDimensions) by probing the 2D mesh at
(x, r) for each grid point; the cone itself (no cells) is filled by AmbientMode Extend (with
--body it is opaque instead: a black silhouette, see docs/CFD.md, Solid bodies). Across the
axis the shock shows as two straight lines from the tip at +-33.9 degrees, which the script
checks on the image (the largest |deflection| along columns behind the tip).
"""
import argparse
import math
import os
import sys

from paraview.simple import LoadPlugin, XMLUnstructuredGridReader, servermanager

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True, help="path to Schlieren.so")
    ap.add_argument("--output", default="cone.png", help="the knife-edge image across the axis; "
                    "the view along the axis goes beside it with _along before the extension")
    ap.add_argument("--data", default=None, help="the half plane (.vtu); default: written next to --output")
    ap.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    ap.add_argument("--passes", type=int, default=4)
    ap.add_argument("--dimensions", type=int, nargs=3, default=[256, 160, 160])
    ap.add_argument("--body", action="store_true",
                    help="make the cone opaque: the grid's hole, which runs out through the box's x max "
                         "face, as a solid body (BodyWallFaces 0 1 0 0 0 0)")
    args = ap.parse_args()

    data = args.data or os.path.join(os.path.dirname(os.path.abspath(args.output)), "cone_m2_15deg.vtu")
    if not os.path.exists(data):
        sys.path.insert(0, HERE)
        import make_cone_flow

        os.makedirs(os.path.dirname(os.path.abspath(data)), exist_ok=True)
        make_cone_flow.write(data)
    LoadPlugin(args.plugin, remote=False, ns=globals())
    import numpy as np
    import schlieren_view  # beside the plugin, importable after LoadPlugin
    from vtkmodules.util.numpy_support import vtk_to_numpy

    reader = XMLUnstructuredGridReader(FileName=[data])
    index = RefractiveIndex(Input=reader, Symmetry="Axisymmetric", SymmetryAxis="X",  # noqa: F821
                            SamplingDimensions=args.dimensions)
    if args.body:
        index.BodyWallFaces = [0, 1, 0, 0, 0, 0]
    across = SchlierenImage(Input=index, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0],  # noqa: F821
                            Resolution=[512, 384], Passes=args.passes, Cutoff="KnifeEdge",
                            KnifeAngle=0.0, Backend=args.backend)
    across.UpdatePipeline()
    out = servermanager.Fetch(across)
    if out is None or out.GetPointData().GetArray("intensity") is None:
        sys.exit("cone: the trace produced no image (see the errors above)")
    schlieren_view.write_png(schlieren_view.film_array(out, "intensity"), args.output)

    along = SchlierenImage(Input=index, ViewDirection=[1, 0, 0], ViewUp=[0, 1, 0],  # noqa: F821
                           Resolution=[256, 256], Passes=args.passes, Cutoff="KnifeEdge",
                           KnifeAngle=0.0, Backend=args.backend)
    along.UpdatePipeline()
    out2 = servermanager.Fetch(along)
    root, ext = os.path.splitext(args.output)
    along_path = root + "_along" + (ext or ".png")
    schlieren_view.write_png(schlieren_view.film_array(out2, "intensity"), along_path)

    grid = servermanager.Fetch(index)
    model = grid.GetFieldData().GetAbstractArray("index_model").GetValue(0)
    # The shock on the film: along columns x (world) behind the tip, the largest |deflection|
    # above the axis lies at y = x tan(beta), beta = 33.9 degrees (Taylor-Maccoll).
    nx, ny, _ = out.GetDimensions()
    ox, oy, _ = out.GetOrigin()
    hx, hy, _ = out.GetSpacing()
    d = vtk_to_numpy(out.GetPointData().GetArray("deflection")).reshape(ny, nx, 2)
    mag = np.hypot(d[..., 0], d[..., 1])
    beta = math.radians(33.91)
    hgrid = grid.GetSpacing()[1]
    worst = 0.0
    for xw in (0.04, 0.06, 0.08):
        i = int(round((xw - ox) / hx))
        ys = oy + hy * np.arange(ny)
        above = ys > 0.25 * xw * math.tan(beta)  # away from the axis and the cone's tip
        j = np.argmax(np.where(above, mag[:, i], 0.0))
        err = abs(ys[j] - xw * math.tan(beta))
        worst = max(worst, err / hgrid)
        print("  x = %.2f m: largest |deflection| at y = %.4f m, shock (33.9 deg) at %.4f m" %
              (xw, ys[j], xw * math.tan(beta)))
    print("wrote %s and %s: Model Automatic chose %s; %d x %d x %d revolved grid; the shock within "
          "%.2f grid spacings of Taylor-Maccoll's angle" % (os.path.abspath(args.output), os.path.abspath(along_path),
                                                         model, *grid.GetDimensions(), worst))
    # the projected shock's edge is smeared inwards by the grid: within 1.5 spacings
    if model != "GladstoneDale" or worst > 1.5:
        sys.exit("cone: the shock is not where Taylor-Maccoll puts it (or the model is not GladstoneDale)")


if __name__ == "__main__":
    main()
