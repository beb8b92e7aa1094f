"""An axisymmetric OpenFOAM case, opened as it is (a `.foam` file), to a schlieren image with no
axis typed: OpenFOAM gives an axisymmetric flow as a wedge one cell thick between two `wedge`
patches; RefractiveIndex finds the wedge and its axis from the mesh and revolves its mid-plane.

    pvpython Examples/openfoam_wedge.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --case path/to/case.foam --output out/jet.png

Without --case it meshes Debian's rhoCentralFoam/LadenburgJet60psi tutorial (openfoam,
openfoam-examples; an under-expanded jet whose time-0 fields are the converged solution) next to
the output, with Testing/Python/openfoam_cases.py, and exits 125 (skipped) where OpenFOAM is not
installed.

    OpenFOAMReader -> RefractiveIndex (Symmetry Axisymmetric; the wedge found, AxisFromWedge)
        -> SchlierenImage (knife edge across the axis, knife normal along it; _radial: knife normal
           across it; _along: seen along the axis)
        -> NumericalSchlieren (_numerical: |grad rho| on the plane through the axis, the same film)
"""
import argparse
import os
import sys

from paraview.simple import LoadPlugin, OpenFOAMReader, servermanager

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True, help="path to Schlieren.so")
    ap.add_argument("--case", default=None, help="an OpenFOAM case's .foam file (default: LadenburgJet60psi)")
    ap.add_argument("--time", type=float, default=None, help="the time to read (default: the last; 0 included)")
    ap.add_argument("--output", default="openfoam_wedge.png")
    # 8: the photon-counting speckle of 1-2 passes on a film finer than the grid is gone (docs/GUI.md)
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--dimensions", type=int, nargs=3, default=[240, 80, 80])
    args = ap.parse_args()

    case = args.case
    if case is None:
        sys.path.insert(0, os.path.join(HERE, "..", "Testing", "Python"))
        import openfoam_cases

        why = openfoam_cases.available()
        if why:
            print("SKIP: %s" % why)
            sys.exit(125)
        folder = os.path.join(os.path.dirname(os.path.abspath(args.output)), "openfoam")
        os.makedirs(folder, exist_ok=True)
        if not openfoam_cases.run_case(folder, "LadenburgJet60psi"):
            sys.exit("openfoam_wedge: the tutorial case could not be prepared")
        case = os.path.join(folder, "LadenburgJet60psi", "case.foam")
    if not os.path.exists(case):
        print("SKIP: the case %s is not there (is OpenFOAM installed? see Testing/Python/openfoam_cases.py)" % case)
        sys.exit(125)
    LoadPlugin(args.plugin, remote=False, ns=globals())
    import schlieren_view  # beside the plugin, importable after LoadPlugin

    reader = OpenFOAMReader(FileName=case)
    reader.SkipZeroTime = 0  # a converged solution given as time 0 is read too
    reader.Refresh()
    reader.UpdatePipelineInformation()
    reader.CellArrays = list(reader.CellArrays.Available)
    times = list(reader.TimestepValues) or [0.0]
    time = args.time if args.time is not None else max(times)
    index = RefractiveIndex(Input=reader, Symmetry="Axisymmetric",  # noqa: F821
                            SamplingDimensions=args.dimensions)
    root, ext = os.path.splitext(args.output)
    # across the axis with the knife normal along it (the Mach disc, the expansion) and across it
    # (the barrel shocks and the jet's boundary, which bend light away from the axis); along it
    for path, view, res, knife in ((args.output, [0, 0, -1], args.dimensions[:2], 0.0),
                                   (root + "_radial" + (ext or ".png"), [0, 0, -1], args.dimensions[:2], 90.0),
                                   (root + "_along" + (ext or ".png"), [-1, 0, 0], args.dimensions[1:], 0.0)):
        image = SchlierenImage(Input=index, ViewDirection=view, ViewUp=[0, 1, 0],  # noqa: F821
                               Resolution=[2 * r for r in res], Passes=args.passes, Cutoff="KnifeEdge",
                               KnifeAngle=knife)
        image.UpdatePipeline(time)
        out = servermanager.Fetch(image)
        if out is None or out.GetPointData().GetArray("intensity") is None:
            sys.exit("openfoam_wedge: the trace produced no image (see the errors above)")
        schlieren_view.write_png(schlieren_view.film_array(out, "intensity"), path)
        print("wrote %s" % path)
    # the numerical schlieren CFD papers print, on the across view's film: |grad rho| on the plane
    # through the axis (Quirk's grey scale, C0 -0.001, C1 0.05, K 5), no light traced
    path = root + "_numerical" + (ext or ".png")
    numerical = NumericalSchlieren(Input=index, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0],  # noqa: F821
                                   Resolution=[2 * r for r in args.dimensions[:2]])
    numerical.UpdatePipeline(time)
    out = servermanager.Fetch(numerical)
    if out is None or out.GetPointData().GetArray("intensity") is None:
        sys.exit("openfoam_wedge: the numerical schlieren produced no image (see the errors above)")
    schlieren_view.write_png(schlieren_view.film_array(out, "intensity"), path)
    print("wrote %s" % path)


if __name__ == "__main__":
    main()
