"""The camera: the helium plume seen by a lens focused in front of, on and behind the flow, a
shadowgraph as defocus, and a focusing-schlieren slice sweep through three spheres at three depths.

    pvpython Examples/camera_gallery.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        --output out/camera

The camera (docs/BENCH.md "Camera"): a thin lens CameraDistance from the volume's centre, focused
on FocusPlane (world units along the beam from the centre, + toward the camera); its film is the
image of that plane. Lens: its aperture D = f / N is filled with light and sampled, one lens
point per pass, so a plane Dz from focus is blurred by d = D Dz / Z_F.

Row 1, the helium jet (40 mm box), knife edge, f = 0.1 m at f/2 (D = 50 mm), 1 m away: focused on
the centre, 60 mm in front of it (toward the camera) and 60 mm behind it: a blur of 3 mm either
side. Then shadowgraphs with the Ideal lens: focused on the centre (almost no contrast: the jet is
thin next to the refocus) and refocused 0.5 m downstream.

Row 2, focusing schlieren: three Gaussian spheres of index (sigma 1.2 mm) at depths -12, 0 and
+12 mm along the beam, 10 mm apart across it; a lens of D = 200 mm (f = 0.2 m at f/1) 1 m away,
knife edge on each ray (the cutoff grid), swept through FocusPlane -12, 0, +12 mm: the sphere in
the focus plane is sharp, the others blurred by 2.4 mm (12 mm off) or 4.8 mm (24 mm off); the depth
of sharp focus 2 w l / A is a few mm (printed, w = a film pixel).

Writes camera_*.png, camera.txt (each image's read-outs) and, if matplotlib imports, camera.png.
"""
import argparse
import os
import sys

import numpy as np
from paraview.simple import Delete, LoadPlugin, ProgrammableSource, servermanager


def fetch(proxy):
    data = servermanager.Fetch(proxy)
    if data is None or data.GetPointData().GetArray("intensity") is None:
        sys.exit("camera_gallery: a trace produced no image (see the errors above)")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    nx, ny, _ = data.GetDimensions()
    intensity = vtk_to_numpy(data.GetPointData().GetArray("intensity")).astype(float).reshape(ny, nx)
    fd = data.GetFieldData()
    fields = {}
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        fields[a.GetName()] = [a.GetValue(k) for k in range(a.GetNumberOfValues())]
    return intensity, fields


SPHERES = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
n, half = {grid}, 0.02
out = self.GetOutput()
out.SetDimensions(n, n, n)
out.SetSpacing(2 * half / (n - 1), 2 * half / (n - 1), 2 * half / (n - 1))
out.SetOrigin(-half, -half, -half)
c = np.linspace(-half, half, n)
z, y, x = np.meshgrid(c, c, c, indexing="ij")
f = np.zeros_like(x)
# depth s = -z along the beam (ViewDirection 0 0 -1): spheres at s = -12, 0, +12 mm
for cx, cz in ((-0.010, 0.012), (0.0, 0.0), (0.010, -0.012)):
    f += 3e-4 * np.exp(-((x - cx) ** 2 + y ** 2 + (z - cz) ** 2) / (2 * 0.0012 ** 2))
a = numpy_to_vtk(f.ravel(), deep=1)
a.SetName("n_minus_1")
out.GetPointData().AddArray(a)
"""
INFO = """
n, half = {grid}, 0.02
from paraview import util
from vtkmodules.vtkCommonDataModel import vtkDataObject
util.SetOutputWholeExtent(self, [0, n - 1, 0, n - 1, 0, n - 1])
info = self.GetOutputInformation(0)
h = 2 * half / (n - 1)
info.Set(vtkDataObject.SPACING(), h, h, h)
info.Set(vtkDataObject.ORIGIN(), -half, -half, -half)
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plugin", required=True, help="path to Schlieren.so")
    ap.add_argument("--output", required=True, help="folder for the PNGs")
    ap.add_argument("--resolution", type=int, default=160)
    ap.add_argument("--grid", type=int, default=96)
    ap.add_argument("--passes", type=int, default=24)
    ap.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    ns = globals()
    LoadPlugin(args.plugin, remote=False, ns=ns)
    from schlieren_view import write_png  # beside the plugin, importable after LoadPlugin
    half = 0.02
    plume = ns["RefractiveScene"](Scene="HeliumPlume", Dimensions=[args.grid] * 3, Bounds=[-half, half] * 3,
                                  Center=[0, 0, 0], Radius=0.003, Width=2 * half, Amplitude=1.0)
    spheres = ProgrammableSource(OutputDataSetType="vtkImageData", Script=SPHERES.format(grid=args.grid),
                                 ScriptRequestInformation=INFO.format(grid=args.grid))
    common = dict(Resolution=[args.resolution] * 2, Passes=args.passes, Backend=args.backend, Seed=5,
                  Integrator="Midpoint", StepSize=1.0, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0])
    jet = dict(Cutoff="KnifeEdge", KnifeAngle=0.0, Camera="Lens", CameraFocalLength=0.1, FNumber=2.0)
    fs = dict(Cutoff="KnifeEdge", KnifeAngle=0.0, Camera="Lens", CameraFocalLength=0.2, FNumber=1.0,
              SourceGridDistance=2.0, CutoffScale=800.0)
    shots = [
        (plume, "camera_jet_focus0", "Jet, lens focused on it", dict(jet, FocusPlane=0.0, CameraDistance=1.0)),
        (plume, "camera_jet_front", "Focused 60 mm in front", dict(jet, FocusPlane=0.06, CameraDistance=1.06)),
        (plume, "camera_jet_behind", "Focused 60 mm behind", dict(jet, FocusPlane=-0.06, CameraDistance=0.94)),
        (plume, "camera_shadow_focus0", "Shadowgraph, focused", dict(Cutoff="Shadowgraph", Camera="Ideal",
                                                                      FocusPlane=0.0, CameraDistance=1.0)),
        (plume, "camera_shadow_refocus", "Shadowgraph, refocused 0.5 m", dict(Cutoff="Shadowgraph", Camera="Ideal",
                                                                              FocusPlane=0.5, CameraDistance=1.5)),
        (spheres, "camera_fs_m12", "Focusing schlieren, s = -12 mm", dict(fs, FocusPlane=-0.012, CameraDistance=0.988)),
        (spheres, "camera_fs_0", "Focusing schlieren, s = 0", dict(fs, FocusPlane=0.0, CameraDistance=1.0)),
        (spheres, "camera_fs_p12", "Focusing schlieren, s = +12 mm", dict(fs, FocusPlane=0.012, CameraDistance=1.012)),
    ]
    log, panels = [], []
    for source, name, title, props in shots:
        settings = dict(common)
        settings.update(props)
        image = ns["SchlierenImage"](Input=source, **settings)
        intensity, f = fetch(image)
        Delete(image)
        write_png(np.clip(0.5 * intensity, 0, 1)
                  if props["Cutoff"] == "Shadowgraph" else intensity, os.path.join(args.output, name + ".png"))
        panels.append((title, intensity, props["Cutoff"] == "Shadowgraph"))
        line = "%-26s %-34s contrast (std) %.4f" % (name + ".png", title, np.std(intensity))
        if "camera_depth_of_field" in f:
            line += ", depth of field %.2f mm, blur %.1f mm per 10 mm of defocus" % (
                1e3 * f["camera_depth_of_field"][0], 1e3 * 0.01 * f["camera_blur_per_depth"][0])
        if "focusing_effective_f2" in f:
            line += ", f2_eff %.3f m" % f["focusing_effective_f2"][0]
        print(line)
        log.append(line)
    # what the pictures must show: the shadowgraph focused on the jet has next to no contrast
    # against the refocused one; in each slice the sphere in the focus plane has the most
    images = {name: p for (_, name, _, _), (_, p, _) in zip(shots, panels)}
    if not np.std(images["camera_shadow_focus0"]) < 0.1 * np.std(images["camera_shadow_refocus"]):
        sys.exit("camera_gallery: the focused shadowgraph has contrast")
    n = images["camera_fs_0"].shape[0]
    c = (np.arange(n) + 0.5) / n * 2 * half - half
    X, Y = np.meshgrid(c, c)
    for name, sharp in (("camera_fs_m12", 0), ("camera_fs_0", 1), ("camera_fs_p12", 2)):
        spread = [np.ptp(images[name][(np.abs(X - cx) < 0.004) & (np.abs(Y) < 0.004)]) for cx in (-0.010, 0.0, 0.010)]
        line = "%s: contrast at the three spheres %.3f %.3f %.3f" % (name, spread[0], spread[1], spread[2])
        print(line)
        log.append(line)
        if int(np.argmax(spread)) != sharp:
            sys.exit("camera_gallery: %s: the sphere in focus is not the sharpest" % name)
    with open(os.path.join(args.output, "camera.txt"), "w") as out:
        out.write("\n".join(log) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not available: no contact sheet")
        return
    fig, axes = plt.subplots(2, 5, figsize=(15, 6.6))
    cells = list(axes[0]) + [axes[1][1], axes[1][2], axes[1][3]]
    for ax, (title, picture, shadow) in zip(cells, panels):
        top = 2.0 if shadow else 1.0  # shadowgraph: I / I0 from 0 to 2, undisturbed mid-grey
        ax.imshow(np.clip(picture, 0, top), cmap="gray", vmin=0, vmax=top, origin="lower", interpolation="nearest")
        ax.set_title(title, fontsize=10)
        ax.axis("off")
    axes[1][0].axis("off")
    axes[1][4].axis("off")
    fig.suptitle("Camera: lens f = 0.1 m at f/2, 1 m away (row 1); focusing schlieren, D = 200 mm, 1 m away (row 2)",
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(os.path.join(args.output, "camera.png"), dpi=72)
    print("wrote %s" % os.path.join(os.path.abspath(args.output), "camera.png"))


if __name__ == "__main__":
    main()
