"""An animation over time: the shadowgraph of a spherical blast wave, one PNG per time step.

    pvpython Examples/blast_animation.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/blast

RefractiveScene's BlastWave is a time series (TimeSteps times up to Time, the Sedov-Taylor radius
growing as t^(2/5)); SchlierenImage follows the pipeline's time like any ParaView filter, so
stepping through the time steps and fetching the image at each gives the frames. Written from the
image arrays (no display needed).
"""
import argparse
import os

from paraview.simple import LoadPlugin, servermanager


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True)
    ap.add_argument("--output", required=True)
    ap.add_argument("--steps", type=int, default=8)
    ap.add_argument("--resolution", type=int, default=192)
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    ns = globals()
    LoadPlugin(args.plugin, remote=False, ns=ns)
    import schlieren_view  # beside the plugin, importable after LoadPlugin: film_array, write_png
    scene = ns["RefractiveScene"](Scene="BlastWave", Dimensions=[96, 96, 96], Bounds=[-1, 1] * 3,
                                  Radius=0.7, Width=0.015, Time=1.0, TimeSteps=args.steps)
    scene.UpdatePipelineInformation()
    image = ns["SchlierenImage"](Input=scene, Resolution=[args.resolution] * 2, Passes=4,
                                 Cutoff="Shadowgraph", FilmDistance=1.0, Filter="Gaussian",
                                 FilterWidth=0.7)
    for i, t in enumerate(scene.TimestepValues):
        image.UpdatePipeline(t)
        data = servermanager.Fetch(image)
        I = schlieren_view.film_array(data, "intensity")
        path = os.path.join(args.output, "blast_%03d.png" % i)
        schlieren_view.write_png(0.5 * I, path)  # undisturbed light (1) as mid grey
        print("t = %.3f: %s (intensity %.2f..%.2f)" % (t, path, I.min(), I.max()))


if __name__ == "__main__":
    main()
