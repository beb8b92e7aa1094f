# SPDX-License-Identifier: BSD-3-Clause
"""PyVista: a knife-edge schlieren of a warm jet given on a curvilinear (cylindrical) grid.

    pip install "schlieren[pyvista]"       # or: pip install . pyvista
    python Examples/pyvista_jet.py --output jet.png [--show]

The flow is made here in NumPy on a pyvista.StructuredGrid (a cylinder of r, theta, z points):
air whose density falls by up to 10 % in a round jet along z that spreads and wobbles. The
pipeline is the plugin's, as VTK algorithms:

    StructuredGrid -> schlieren.RefractiveIndex (GladstoneDale on `density`, resampled to an image)
                   -> schlieren.SchlierenImage (knife edge, view across the jet)

and the film comes back as a vtkImageData that pyvista wraps (pv.wrap). --show opens a PyVista
window with the grid and the film; without it only the PNG is written (no display needed)."""
import argparse
import sys

import numpy as np
import pyvista as pv

import schlieren
from schlieren.png import write_png


def jet_grid(nr=24, nt=48, nz=40):
    r = np.linspace(0.0, 1.0, nr)
    t = np.linspace(0.0, 2 * np.pi, nt)
    z = np.linspace(0.0, 3.0, nz)
    R, T, Z = np.meshgrid(r, t, z, indexing="ij")
    grid = pv.StructuredGrid(R * np.cos(T), R * np.sin(T), Z)
    x, y, zz = grid.points.T
    width = 0.15 + 0.08 * zz
    axis_x = 0.05 * np.sin(3.0 * zz)
    rho = 1.2 * (1.0 - 0.1 * np.exp(-((x - axis_x) ** 2 + y ** 2) / width ** 2))
    grid.point_data["density"] = rho.astype(np.float32)
    return grid


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default="jet.png")
    ap.add_argument("--resolution", type=int, default=256)
    ap.add_argument("--backend", default="Auto", choices=["Auto", "OpenCL", "CPU"])
    ap.add_argument("--show", action="store_true")
    args = ap.parse_args()

    grid = jet_grid()
    index = schlieren.RefractiveIndex(Model="GladstoneDale", InputArray="density",
                                      SamplingDimensions=[64, 64, 96])
    index.SetInputData(grid)
    image = schlieren.SchlierenImage(Cutoff="KnifeEdge", KnifeAngle=0.0, ViewDirection=[0, 1, 0],
                                     ViewUp=[0, 0, 1], Passes=4, Backend=args.backend,
                                     Resolution=[args.resolution, args.resolution])
    image.SetInputConnection(index.GetOutputPort())
    image.Update()
    film = pv.wrap(image.GetOutput())
    if film.n_points == 0:
        sys.exit("pyvista_jet: no image: " + image.LastError)
    intensity = schlieren.image_to_numpy(film)
    write_png(intensity, args.output)
    f = image.LastReport["field_data"]
    print("wrote %s: %dx%d, intensity %.3f..%.3f (mean %.3f), %d photons landed, traced on %s"
          % (args.output, film.dimensions[0], film.dimensions[1], intensity.min(),
             intensity.max(), intensity.mean(), f["landed_photons"], f["backend"]))
    # the jet bends light: the film is not uniform grey
    if not intensity.max() - intensity.min() > 0.2:
        sys.exit("pyvista_jet: the film shows no jet (contrast %.3f)"
                 % (intensity.max() - intensity.min()))
    if args.show:
        p = pv.Plotter(shape=(1, 2))
        p.add_mesh(grid.outline(), color="k")
        p.add_mesh(grid.slice("y"), scalars="density")
        p.subplot(0, 1)
        p.add_mesh(film, scalars="intensity", cmap="gray")
        p.view_xy()
        p.show()


if __name__ == "__main__":
    main()
