"""The NASA blunt fin (Hung and Buning, Mach 2.95): a knife-edge schlieren of its bow shock, to a PNG.

    pvpython Examples/bluntfin.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/bluntfin.png [--data ../shared/data] [--view top|side]

The data (bluntfinxyz.bin, bluntfinq.bin; PLOT3D, from the VTK data collection) is a curvilinear
40 x 32 x 32 grid around a fin standing on a flat plate (the plate is z = 0, the fin's leading edge
at x = 0, the symmetry plane y = 0), with the density non-dimensional (free stream 1). The
pipeline:

    PLOT3DReader -> RefractiveIndex (GladstoneDale, air, Density x 1.2 kg/m^3)
                 -> SchlierenImage (knife edge)

RefractiveIndex resamples the curvilinear grid onto an image grid around the fin (SamplingBounds),
and fills the points outside the CFD grid (beyond its outer boundary and inside the fin) with a
smooth continuation of the flow (AmbientMode Extend), so that the grid's edge draws no false line.
The fin itself is the grid's hole: with BodyWallFaces 0 1 1 0 1 1 (the fin runs past the box's
x max, the symmetry plane y = 0 cuts it, it stands on the plate z = 0 and reaches the top) those
points become the point array `solid`, and the fin stops the light: a black silhouette, as in a
wind tunnel's photograph (--no-body traces through it, as before bodies were known).
--view top looks down on the plate (the bow shock wraps around the fin's nose and sweeps
outward); side looks across the flow (the shock stands ahead of the fin, with its foot
on the plate where the boundary layer separates). Runs without a display: the PNG is written from
the filter's output array.
"""
import argparse
import os
import sys

from paraview.simple import LoadPlugin, PLOT3DReader, servermanager

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_DATA = os.environ.get("SCHLIEREN_DATA") or os.path.join(HERE, "..", "..", "shared", "data")


# The faces of the sampling box the fin touches (x min, x max, y min, y max, z min, z max).
FIN_WALL_FACES = [0, 1, 1, 0, 1, 1]


def blunt_fin_index(ns, data, **resampling):
    """PLOT3DReader -> RefractiveIndex for the blunt fin in folder `data`, with the plugin's proxies
    from namespace `ns` (the one LoadPlugin filled); `resampling` adds RefractiveIndex properties
    (AutomaticDimension or SamplingDimensions). None when the files are not there."""
    xyz = os.path.join(data, "bluntfinxyz.bin")
    q = os.path.join(data, "bluntfinq.bin")
    if not (os.path.exists(xyz) and os.path.exists(q)):
        return None
    # The reader detects the format: binary, big-endian, single grid, 3D, single precision, no
    # IBlank array (the grid file is 12 + 3 x 4 x 40960 bytes), whatever ../shared/data/README.md
    # says (little-endian, IBlanking on: both fail to read).
    reader = PLOT3DReader(FileName=xyz, QFileName=[q])
    index = ns["RefractiveIndex"](Input=reader, Model="GladstoneDale", Gas="Air",
                                  DensityReference=1.2,  # rho_inf, kg/m^3: the density is rho / rho_inf
                                  UseSamplingBounds=1, SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7],
                                  AmbientMode="Extend", BodyWallFaces=FIN_WALL_FACES, **resampling)
    index.InputArray = ["POINTS", "Density"]
    return index


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True, help="path to Schlieren.so")
    ap.add_argument("--output", default="bluntfin.png")
    ap.add_argument("--data", default=DEFAULT_DATA, help="folder with bluntfinxyz.bin and bluntfinq.bin")
    ap.add_argument("--view", default="top", choices=["top", "side"])
    ap.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--no-body", action="store_true", help="let the light through the fin")
    args = ap.parse_args()

    LoadPlugin(args.plugin, remote=False, ns=globals())
    index = blunt_fin_index(globals(), args.data, AutomaticDimension=160)
    if index is not None and args.no_body:
        index.BodyFromGrid = 0
    if index is None:
        print("bluntfin: SKIP, no data in %s (pass --data or set SCHLIEREN_DATA)" % os.path.abspath(args.data))
        sys.exit(125)
    if args.view == "top":
        # k = 40 per radian saturates the nose (|e| up to 0.04) to show the weaker shock further out.
        view = dict(ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], Resolution=[800, 400], KnifeAngle=0.0,
                    CutoffScale=40.0)
    else:
        view = dict(ViewDirection=[0, 1, 0], ViewUp=[0, 0, 1], Resolution=[800, 456], KnifeAngle=0.0,
                    CutoffScale=0.0)
    image = SchlierenImage(Input=index, Cutoff="KnifeEdge", Passes=args.passes,  # noqa: F821
                           Backend=args.backend, **view)
    image.UpdatePipeline()
    out = servermanager.Fetch(image)
    if out is None or out.GetPointData().GetArray("intensity") is None:
        sys.exit("bluntfin: the trace produced no image (see the errors above)")
    import schlieren_view  # beside the plugin, importable after LoadPlugin

    schlieren_view.write_png(schlieren_view.film_array(out, "intensity"), args.output)
    grid = servermanager.Fetch(index)
    fd = out.GetFieldData()
    k = fd.GetArray("cutoff_scale")
    backend = fd.GetAbstractArray("backend")
    rng = out.GetPointData().GetArray("intensity").GetRange()
    print("wrote %s: %d x %d knife-edge schlieren of the blunt fin (%s view) from a %d x %d x %d "
          "resampled grid (%.0f %% inside the CFD grid), n - 1 %.3g..%.3g, intensity %.3f..%.3f, "
          "k = %.4g, traced on %s; %d solid points, %d of %d rays stopped by the fin"
          % (os.path.abspath(args.output), out.GetDimensions()[0], out.GetDimensions()[1], args.view,
             *grid.GetDimensions(), 100 * grid.GetFieldData().GetArray("valid_point_fraction").GetValue(0),
             *grid.GetPointData().GetArray("n_minus_1").GetRange(), rng[0], rng[1],
             k.GetValue(0) if k else float("nan"), backend.GetValue(0) if backend else "?",
             grid.GetFieldData().GetArray("solid_points").GetValue(0),
             fd.GetArray("blocked_rays").GetValue(0), fd.GetArray("photons").GetValue(0)))


if __name__ == "__main__":
    main()
