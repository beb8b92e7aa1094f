"""ParaView's CVD reactor (disk_out_ref.ex2): a knife-edge schlieren of the hot hydrogen over the
heated disk, to a PNG.

    pvpython Examples/reactor.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/reactor.png [--data ../shared/data]

The data is the ParaView tutorial's reactor (Exodus II, 8499 points, unstructured): gas flows
through a cylinder (radius 5.75, z from -10 to 10) past a spinning disk heated to 913 K on a shaft;
the gas is mostly hydrogen (mass fraction 0.81-0.92, the rest arsine and trimethylgallium). The
file's temperature `Temp` is in kelvin (293-913 K). Its `Pres` (0.0068-0.029) rises and falls
along the cylinder by a factor of 4, which no absolute pressure in a slow flow does: it is read
here as a gauge pressure in pascal on top of an assumed operating pressure of 1 atm
(PressureOffset), which makes it negligible; the density then follows the temperature.

    ExodusIIReader -> RefractiveIndex (IdealGas, H2: rho = p M / (R T), n - 1 = K rho)
                   -> SchlierenImage (knife edge, looking across the cylinder)

The gas is taken as pure hydrogen (the table has no Gladstone-Dale constant for arsine or
trimethylgallium; with their constants, the Species composition and Custom gases take them into
account). RefractiveIndex resamples the unstructured grid onto an image grid; the points outside
the cylinder and inside the disk and its shaft get a smooth continuation of the flow (AmbientMode
Extend).
"""
import argparse
import os
import sys

from paraview.simple import ExodusIIReader, LoadPlugin, servermanager

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_DATA = os.environ.get("SCHLIEREN_DATA") or os.path.join(HERE, "..", "..", "shared", "data")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True, help="path to Schlieren.so")
    ap.add_argument("--output", default="reactor.png")
    ap.add_argument("--data", default=DEFAULT_DATA, help="folder with disk_out_ref.ex2")
    ap.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    ap.add_argument("--passes", type=int, default=8)
    args = ap.parse_args()

    path = os.path.join(args.data, "disk_out_ref.ex2")
    if not os.path.exists(path):
        print("reactor: SKIP, no data in %s (pass --data or set SCHLIEREN_DATA)" % os.path.abspath(args.data))
        sys.exit(125)

    LoadPlugin(args.plugin, remote=False, ns=globals())
    reader = ExodusIIReader(FileName=path)
    reader.PointVariables = ["Temp", "Pres", "H2"]
    index = RefractiveIndex(Input=reader, Model="IdealGas", IdealGasComposition="Gas", Gas="H2",  # noqa: F821
                            TemperatureUnit="Kelvin", PressureUnit="Pa",
                            PressureOffset=101325.0,  # Pres is a gauge pressure (see above)
                            AutomaticDimension=128, AmbientMode="Extend")
    index.TemperatureArray = ["POINTS", "Temp"]
    index.PressureArray = ["POINTS", "Pres"]
    # Across the cylinder (the beam along x), the cylinder's axis up the film, the knife normal
    # along the film's x: the light is bent sideways by the hot (thinner) gas over the disk.
    image = SchlierenImage(Input=index, ViewDirection=[1, 0, 0], ViewUp=[0, 0, 1],  # noqa: F821
                           Resolution=[384, 512], Passes=args.passes, Cutoff="KnifeEdge",
                           KnifeAngle=0.0, Backend=args.backend)
    image.UpdatePipeline()
    out = servermanager.Fetch(image)
    if out is None or out.GetPointData().GetArray("intensity") is None:
        sys.exit("reactor: the trace produced no image (see the errors above)")
    import schlieren_view  # beside the plugin, importable after LoadPlugin

    schlieren_view.write_png(schlieren_view.film_array(out, "intensity"), args.output)
    grid = servermanager.Fetch(index)
    fd = out.GetFieldData()
    k = fd.GetArray("cutoff_scale")
    backend = fd.GetAbstractArray("backend")
    rng = out.GetPointData().GetArray("intensity").GetRange()
    print("wrote %s: %d x %d knife-edge schlieren of the reactor from a %d x %d x %d resampled grid "
          "(%.0f %% inside the CFD grid), n - 1 %.4g..%.4g, intensity %.3f..%.3f, k = %.4g, traced on %s"
          % (os.path.abspath(args.output), out.GetDimensions()[0], out.GetDimensions()[1],
             *grid.GetDimensions(), 100 * grid.GetFieldData().GetArray("valid_point_fraction").GetValue(0),
             *grid.GetPointData().GetArray("n_minus_1").GetRange(), rng[0], rng[1],
             k.GetValue(0) if k else float("nan"), backend.GetValue(0) if backend else "?"))


if __name__ == "__main__":
    main()
