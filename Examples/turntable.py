"""A turntable: the knife-edge schlieren of a helium jet seen from all around, one PNG per angle.

    pvpython Examples/turntable.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/turntable

The beam turns about the jet's axis (y); each frame sets SchlierenImage's ViewDirection. (In the
GUI, `import schlieren_view; schlieren_view.follow_camera(view, image)` does the same from the 3D
view's camera as you rotate it.) Written from the image arrays, no display needed.
"""
import argparse
import math
import os

from paraview.simple import LoadPlugin, servermanager


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True)
    ap.add_argument("--output", required=True)
    ap.add_argument("--frames", type=int, default=12)
    ap.add_argument("--resolution", type=int, default=192)
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    ns = globals()
    LoadPlugin(args.plugin, remote=False, ns=ns)
    import schlieren_view  # beside the plugin, importable after LoadPlugin: film_array, write_png
    jet = ns["RefractiveScene"](Scene="HeliumPlume", Dimensions=[96] * 3, Bounds=[-0.02, 0.02] * 3,
                                Radius=0.003, Width=0.04, Amplitude=1.0)
    image = ns["SchlierenImage"](Input=ns["RefractionOctree"](Input=jet), Cutoff="KnifeEdge",
                                 CutoffScale=1000.0, Resolution=[args.resolution] * 2, Passes=2,
                                 ViewUp=[0, 1, 0])
    for i in range(args.frames):
        a = 2 * math.pi * i / args.frames
        image.ViewDirection = [math.sin(a), 0.0, -math.cos(a)]
        data = servermanager.Fetch(image)
        I = schlieren_view.film_array(data, "intensity")
        path = os.path.join(args.output, "turntable_%03d.png" % i)
        schlieren_view.write_png(I, path)
        print("%5.1f deg: %s (intensity %.2f..%.2f)" % (math.degrees(a), path, I.min(), I.max()))


if __name__ == "__main__":
    main()
