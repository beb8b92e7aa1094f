"""The helium plume under a Z-type schlieren bench: a slit cut 30, 50 and 70 %, a pinhole, and stops in mm.

    pvpython Examples/bench_gallery.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/bench

The bench (docs/BENCH.md): two 1 m focal-length mirrors (f1 = f2 = 1 m), a slit 1.5 mm high (its
image a0 = 1.5 mm at the knife), the knife normal along the film's x. The knife leaves
a = (1 - cut) a0: full dark at eps = -a / f2, saturation at (a0 - a) / f2, sensitivity f2 / a. The
plume's largest deflection (7.2e-4 rad at the nozzle's rim) lies inside the range at 50 % cut
(+-7.5e-4 rad), beyond saturation at 30 % (4.5e-4 rad: the rim bent toward the open side clips to
white) and beyond full dark at 70 % (-4.5e-4 rad: the other rim clips to black): more cut, more
contrast and a darker background. The pinhole of 1.5 mm at 50 % has the disc's response, steeper
at the centre ((4 / pi) f2 / R' against the slit's 2 f2 / a0) and rounded toward its ends.

The second row: a 0.5 mm pinhole (its image R' = 0.25 mm) through an iris of 1 mm (Circular with
StopDiameter: light lost where the deflection moves the image past the iris, from 2.5e-4 rad, all
of it beyond 7.5e-4 rad), onto an opaque disc of 0.6 mm (dark field: light from 5e-5 rad), and a
0.3 mm pinhole around a colour filter's opaque centre of 0.6 mm (the light that passes takes the
hue of its deflection's direction).

Writes bench_cut30.png, bench_cut50.png, bench_cut70.png, bench_disc50.png, bench_iris.png,
bench_darkfield.png, bench_colour.png, bench.txt (each image's read-outs) and, if matplotlib
imports, bench.png, a contact sheet with titles.
"""
import argparse
import os
import sys

import numpy as np
from paraview.simple import Delete, LoadPlugin, servermanager


def fetch(proxy):
    data = servermanager.Fetch(proxy)
    if data is None or data.GetPointData().GetArray("intensity") is None:
        sys.exit("bench_gallery: a trace produced no image (see the errors above)")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    nx, ny, _ = data.GetDimensions()
    intensity = vtk_to_numpy(data.GetPointData().GetArray("intensity")).astype(float).reshape(ny, nx)
    rgb = data.GetPointData().GetArray("rgb")
    if rgb is not None and data.GetPointData().GetArray("intensity").GetRange()[1] > 0:
        intensity = vtk_to_numpy(rgb).astype(float).reshape(ny, nx, 3)  # the colour filter's picture
    fd = data.GetFieldData()
    fields = {}
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        fields[a.GetName()] = [a.GetValue(k) for k in range(a.GetNumberOfValues())]
    return intensity, fields


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True, help="path to Schlieren.so")
    ap.add_argument("--output", required=True, help="folder for the PNGs")
    ap.add_argument("--resolution", type=int, default=256)
    ap.add_argument("--grid", type=int, default=128)
    ap.add_argument("--passes", type=int, default=4)
    ap.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    ns = globals()
    LoadPlugin(args.plugin, remote=False, ns=ns)
    from schlieren_view import write_png  # beside the plugin, importable after LoadPlugin
    half = 0.02
    plume = ns["RefractiveScene"](Scene="HeliumPlume", Dimensions=[args.grid] * 3, Bounds=[-half, half] * 3,
                                  Center=[0, 0, 0], Radius=0.003, Width=2 * half, Amplitude=1.0)
    octree = ns["RefractionOctree"](Input=plume)
    bench = dict(Cutoff="KnifeEdge", KnifeAngle=0.0, CollimatorFocalLength=1.0, SchlierenFocalLength=1.0,
                 Resolution=[args.resolution] * 2, Passes=args.passes, Backend=args.backend, Seed=11,
                 Integrator="Midpoint", StepSize=1.0, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0])
    shots = [("bench_cut30", "Slit 1.5 mm, 30 % cut", dict(Source="Slit", SourceSize=[1.5, 10], KnifeCut=0.3)),
             ("bench_cut50", "Slit 1.5 mm, 50 % cut", dict(Source="Slit", SourceSize=[1.5, 10], KnifeCut=0.5)),
             ("bench_cut70", "Slit 1.5 mm, 70 % cut", dict(Source="Slit", SourceSize=[1.5, 10], KnifeCut=0.7)),
             ("bench_disc50", "Pinhole 1.5 mm, 50 % cut", dict(Source="Disc", SourceSize=[1.5, 1.5], KnifeCut=0.5)),
             ("bench_iris", "Pinhole 0.5 mm, iris 1 mm", dict(Cutoff="Circular", Source="Disc", SourceSize=[0.5, 0.5],
                                                            StopDiameter=1.0)),
             ("bench_darkfield", "Pinhole 0.5 mm, disc 0.6 mm", dict(Cutoff="ComplementCircular", Source="Disc",
                                                                   SourceSize=[0.5, 0.5], StopDiameter=0.6)),
             ("bench_colour", "Pinhole 0.3 mm, colour filter 0.6 mm", dict(Cutoff="ColorFilter", Source="Disc",
                                                                         SourceSize=[0.3, 0.3], StopDiameter=0.6))]
    log, panels = [], []
    for name, title, props in shots:
        settings = dict(bench)
        settings.update(props)
        image = ns["SchlierenImage"](Input=octree, **settings)
        intensity, f = fetch(image)
        Delete(image)
        write_png(intensity, os.path.join(args.output, name + ".png"))
        panels.append((title, intensity))
        line = ("%-18s %-26s sensitivity %.0f /rad, dark at %.3g rad, saturation at %.3g rad, 8-bit step %.2g rad, "
                "film saturated %.1f %%, dark %.1f %%, background %.3f"
                % (name + ".png", title, f["bench_sensitivity"][0], f["bench_range"][0], f["bench_range"][1],
                   f["bench_resolvable_deflection"][0], 100 * f["bench_saturated_share"][0],
                   100 * f["bench_dark_share"][0], np.median(intensity)))
        if "StopDiameter" in props:
            # a stop's range: where it begins to cut the source's image and where it covers it
            line += "\n    " + f["bench_model"][0]
        print(line)
        log.append(line)
    flat = [t for t, p in panels if np.ptp(p) < 0.2]
    if flat:
        sys.exit("bench_gallery: these images have no contrast: %s" % ", ".join(flat))
    with open(os.path.join(args.output, "bench.txt"), "w") as out:
        out.write("\n".join(log) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not available: no contact sheet")
        return
    cols = 4
    rows = (len(panels) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.0 * cols, 3.3 * rows))
    for ax in axes.ravel():
        ax.axis("off")
    for ax, (title, picture) in zip(axes.ravel(), panels):
        ax.imshow(np.clip(picture, 0, 1), cmap="gray", vmin=0, vmax=1, origin="lower", interpolation="nearest")
        ax.set_title(title, fontsize=10)
        ax.axis("off")
    fig.suptitle("Helium jet, Z-type bench f1 = f2 = 1 m (intensity: share of the uncut source image)", fontsize=11)
    fig.tight_layout()
    fig.savefig(os.path.join(args.output, "bench.png"), dpi=80)
    print("wrote %s" % os.path.join(os.path.abspath(args.output), "bench.png"))


if __name__ == "__main__":
    main()
