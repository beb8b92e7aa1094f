"""The gallery: one helium plume seen the ways a laboratory sees it.

    pvpython Examples/gallery.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/gallery

Writes into the --output folder one PNG per image, from the SchlierenImage arrays (no render view,
no display needed): knife-edge schlieren (curved rays), the same with the line-of-sight
approximation (straight rays) and their difference, circular stop, dark field (complement
circular), colour filter, shadowgraph, an infinite- and a finite-fringe interferogram, a white-light
one, a synthetic
background-oriented schlieren (BOS) recording and its displacement field; plus gallery.png, a
contact sheet with titles (if matplotlib imports), and gallery.txt, what each image took.

The scene is RefractiveScene's HeliumPlume: a round jet of pure helium rising from a nozzle of
radius 3 mm into still air at 293.15 K and 101325 Pa, in a 4 cm cube (world units are metres). Its
helium mass fraction falls and its width grows with height, with the bulges of the puffing
instability growing as they rise; n - 1 is the Gladstone-Dale mixture of ORACLES.md at the
ideal-gas density (the engine's index models), from 2.72e-4 in the air to 3.25e-5 in the helium
at the nozzle. RefractionOctree lets the tracer cross the still air in long steps.
"""
import argparse
import math
import os
import sys
import time

import numpy as np
from paraview.simple import Delete, LoadPlugin, servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy

def fetch(proxy):
    """The image's point arrays as (ny, nx[, c]) numpy arrays, and its field data as a dict."""
    data = servermanager.Fetch(proxy)
    if data is None or data.GetPointData().GetArray("intensity") is None:
        sys.exit("gallery: a trace produced no image (see the errors above)")
    nx, ny, _ = data.GetDimensions()
    arrays = {}
    pd = data.GetPointData()
    for i in range(pd.GetNumberOfArrays()):
        a = pd.GetArray(i)
        c = a.GetNumberOfComponents()
        arrays[a.GetName()] = vtk_to_numpy(a).astype(float).reshape((ny, nx) + ((c,) if c > 1 else ()))
    fields = {}
    fd = data.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        fields[a.GetName()] = a.GetValue(0)
    return arrays, fields


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True, help="path to Schlieren.so")
    ap.add_argument("--output", required=True, help="folder for the PNGs")
    ap.add_argument("--resolution", type=int, default=256, help="film pixels per side (default 256)")
    ap.add_argument("--grid", type=int, default=128, help="grid points per side (default 128)")
    ap.add_argument("--passes", type=int, default=8, help="passes per image (default 8)")
    ap.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)

    ns = globals()
    LoadPlugin(args.plugin, remote=False, ns=ns)
    from schlieren_view import write_png  # beside the plugin, importable after LoadPlugin
    half, nozzle = 0.02, 0.003
    plume = ns["RefractiveScene"](Scene="HeliumPlume", Dimensions=[args.grid] * 3,
                                  Bounds=[-half, half] * 3, Center=[0, 0, 0], Radius=nozzle,
                                  Width=2 * half, Amplitude=1.0)
    octree = ns["RefractionOctree"](Input=plume)

    res = [args.resolution, args.resolution]
    common = dict(Resolution=res, Passes=args.passes, Backend=args.backend, Seed=11,
                  ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0])
    # The stops' sensitivity k: a deflection of 1e-3 rad (a little above the largest, 7.2e-4 rad at
    # the nozzle's rim) gives full contrast, as one sets a laboratory knife so that the plume neither
    # washes out nor saturates.
    k = 1000.0
    tilt = 300.0  # reference fringes per metre for the finite-fringe interferogram
    # The knife-edge pair traces one photon through each pixel centre (no jitter), so that the two
    # images and their difference compare ray for ray.
    pair = dict(Cutoff="KnifeEdge", KnifeAngle=0.0, CutoffScale=k, StepSize=1.0, Jitter=0, Passes=1)
    # Images whose intensity is a sum over photons (the stops, the interferograms) are traced with
    # curved rays: line of sight leaves its photons where the exit ray points back to, up to a
    # tenth of a pixel off here, and that shows as photon-count noise at few passes. The
    # shadowgraph and BOS let Auto choose (it picks line of sight for this weak object).
    stop = dict(CutoffScale=k, Integrator="Midpoint", StepSize=1.0)
    shots = [
        ("knife_edge", "Knife edge (curved rays)", dict(pair, Integrator="RK4")),
        ("knife_edge_straight", "Knife edge (line of sight)", dict(pair, Integrator="Straight")),
        ("circular", "Circular stop", dict(stop, Cutoff="Circular")),
        ("dark_field", "Dark field (complement)", dict(stop, Cutoff="ComplementCircular")),
        ("color", "Colour filter", dict(stop, Cutoff="ColorFilter")),
        ("shadowgraph", "Shadowgraph, film 1.5 m behind", dict(Cutoff="Shadowgraph", FilmDistance=1.5, Integrator="Auto",
                                                             Filter="Gaussian", FilterWidth=0.7, Passes=2 * args.passes)),
        ("interferogram", "Interferogram", dict(Cutoff="Interferometry", Integrator="Midpoint", StepSize=1.0)),
        ("interferogram_tilted", "Interferogram, tilted reference", dict(Cutoff="Interferometry", ReferenceTilt=tilt,
                                                                         Integrator="Midpoint", StepSize=1.0)),
        # white light (400-700 nm, 16 bins, one per pass): the fringes of a tilted reference
        # fade within a micrometre of path from the zero-order fringe, which the jet bends
        ("interferogram_white", "White-light interferogram, 400-700 nm",
         dict(Cutoff="Interferometry", ReferenceTilt=tilt, WavelengthRange=[400.0, 700.0], WavelengthBins=16,
              Passes=max(16, args.passes), Integrator="Midpoint", StepSize=1.0)),
        ("bos", "BOS: background 1 m behind", dict(Cutoff="BOS", BackgroundDistance=1.0, Integrator="Auto")),
    ]
    log = []
    panels = []
    curved = straight = None
    t_all = time.time()
    for name, title, props in shots:
        settings = dict(common)
        settings.update(props)
        image = ns["SchlierenImage"](Input=octree, **settings)
        t0 = time.time()
        arrays, fields = fetch(image)
        seconds = time.time() - t0
        Delete(image)
        if "rgb" in arrays:
            picture = arrays["rgb"]
        else:
            picture = arrays["intensity"]
        if name == "shadowgraph":
            picture = 0.5 * picture  # photon density 1 (undisturbed) as mid grey
        write_png(picture, os.path.join(args.output, name + ".png"))
        panels.append((name, title, picture))
        line = "%-26s %-33s %s at %g voxel, %.1f samples/ray, %.2f s (%s)" % (
            name + ".png", title, fields["integrator"], fields["step_size"], fields["samples_per_ray"],
            seconds, fields["backend"])
        if "auto_report" in fields:
            line += "\n    " + fields["auto_report"]
        if name == "knife_edge":
            curved = arrays["deflection"]
        if name == "knife_edge_straight":
            straight = arrays["deflection"]
        if name == "interferogram":
            peak = np.abs(arrays["phase"]).max()
            line += "; largest phase %.1f rad (%.1f fringes)" % (peak, peak / (2 * math.pi))
        if name == "bos":
            shift = np.sqrt(np.sum(arrays["bos_displacement"] ** 2, axis=-1))
            pixel = 2 * half / args.resolution
            line += "; largest displacement %.2f mm (%.1f pixels)" % (1e3 * shift.max(), shift.max() / pixel)
            write_png(shift / np.maximum(shift.max(), 1e-30), os.path.join(args.output, "bos_displacement.png"))
            panels.append(("bos_displacement", "BOS displacement |d|", shift / np.maximum(shift.max(), 1e-30)))
        print(line)
        log.append(line)

    # line of sight against the curved trace: where and how much they differ
    gap = np.sqrt(np.sum((curved - straight) ** 2, axis=-1))
    emax = np.sqrt(np.sum(curved ** 2, axis=-1)).max()
    line = ("line of sight vs curved trace: deflections differ by up to %.3g rad (%.2g %% of the largest, "
            "%.3g rad)" % (gap.max(), 100 * gap.max() / emax, emax))
    print(line)
    log.append(line)
    # the knife-edge difference, amplified so that the largest maps to full contrast
    gain = 0.5 / np.maximum(np.abs(curved[..., 0] - straight[..., 0]).max(), 1e-30)
    difference = 0.5 + (curved[..., 0] - straight[..., 0]) * gain
    write_png(difference, os.path.join(args.output, "knife_edge_difference.png"))
    panels.insert(2, ("knife_edge_difference", "Curved - line of sight (x%.0f)" % (gain / k), difference))
    log.append("total %.1f s" % (time.time() - t_all))
    # every panel must show something: a flat image means the trace or the scene went wrong
    flat = [name for name, title, picture in panels if np.ptp(picture) < 0.2]
    if flat:
        sys.exit("gallery: these images have no contrast: %s" % ", ".join(flat))
    with open(os.path.join(args.output, "gallery.txt"), "w") as f:
        f.write("\n".join(log) + "\n")

    # the contact sheet, with titles
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not available: no contact sheet")
        return
    cols = 4
    rows = (len(panels) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.0 * cols, 3.2 * rows))
    for ax in axes.ravel():
        ax.axis("off")
    for ax, (name, title, picture) in zip(axes.ravel(), panels):
        ax.imshow(np.clip(picture, 0, 1), cmap="gray", vmin=0, vmax=1, origin="lower", interpolation="nearest")
        ax.set_title(title, fontsize=10)
    fig.suptitle("A helium jet rising into air (4 cm box, 632.8 nm): one scene, every cutoff", fontsize=12)
    fig.tight_layout()
    fig.savefig(os.path.join(args.output, "gallery.png"), dpi=80)
    print("wrote %s" % os.path.join(os.path.abspath(args.output), "gallery.png"))


if __name__ == "__main__":
    main()
