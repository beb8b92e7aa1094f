# SPDX-License-Identifier: BSD-3-Clause
# %% [markdown]
# # Schlieren from NumPy arrays (Jupyter-friendly: each `# %%` is a cell)
#
# The engine needs no VTK: a NumPy array of n - 1 on a regular grid goes in, NumPy images come
# out. Here a Gaussian lens of denser air, traced three ways (knife edge, shadowgraph,
# interferometry) and checked against the closed form of the line-of-sight deflection. In a
# notebook, show(image) as a cell's last line displays it (schlieren.png: no package beyond NumPy).
#
#     pip install .          # or the wheel
#     python Examples/numpy_lens.py --output lens.png

# %%
import argparse
import sys

import numpy as np

from schlieren import engine
from schlieren.png import show

ap = argparse.ArgumentParser(description="schlieren from NumPy arrays")
ap.add_argument("--output", default="lens.png")
ap.add_argument("--backend", default="Auto")
args, _ = ap.parse_known_args()  # parse_known_args: Jupyter passes its own arguments

# %% the volume: n - 1 = A exp(-r^2 / s^2) on a 64^3 grid over [-1, 1]^3, x fastest
n = 64
x = np.linspace(-1.0, 1.0, n)
Z, Y, X = np.meshgrid(x, x, x, indexing="ij")   # C order (z, y, x): x varies fastest
A, s = 1e-4, 0.3
n_minus_1 = (A * np.exp(-(X ** 2 + Y ** 2 + Z ** 2) / s ** 2)).astype(np.float32)
dims, origin, spacing = [n, n, n], [-1.0] * 3, [2.0 / (n - 1)] * 3

# %% one session, three optics: the volume is packed once. The shadowgraph's film lies 100 units
# behind the volume (50 times its width): its contrast is about FilmDistance * laplacian of the
# phase, 2.4e-3 per unit at the centre here, so at 0.5 units it would be 1e-3 -- the photons move
# a two-hundredth of a pixel, none leaves its pixel, and every pixel reads exactly 1.0. It counts
# photons, so it takes more passes and a Gaussian filter over the noise.
session = engine.Session()
session.set_volume(dims, origin, spacing, n_minus_1.ravel())
images = {}
optics = {"KnifeEdge": dict(Passes=4, FilmDistance=0.0, Filter="None"),
          "Shadowgraph": dict(Passes=16, FilmDistance=100.0, Filter="Gaussian", FilterWidth=1.5),
          "Interferometry": dict(Passes=4, FilmDistance=0.0, Filter="None")}
for cutoff, settings in optics.items():
    for k, v in dict(settings, Cutoff=cutoff, Resolution=[128, 128], Backend=args.backend).items():
        session.set(k, v)
    report = session.trace()
    size, film_origin, pixel = session.film()
    images[cutoff] = session.array("intensity").reshape(size[1], size[0])
    deflection = session.array("deflection").reshape(size[1], size[0], 2)
    print("%-14s intensity %.3f..%.3f on %s" % (cutoff, images[cutoff].min(),
                                                 images[cutoff].max(),
                                                 report["field_data"]["backend"]))
# the lens focuses: I = 1 - L lap(P) for a weak lens, with lap(P) = 4 sqrt(pi) A s (r^2/s^2 - 1)
# exp(-r^2/s^2) / s^2: bright at the centre (1 + 2.4e-3 L), darkest at r = s sqrt(2) (1 - 3.2e-4 L)
L = optics["Shadowgraph"]["FilmDistance"]
yy, xx = np.meshgrid(film_origin[1] + pixel * np.arange(size[1]),
                     film_origin[0] + pixel * np.arange(size[0]), indexing="ij")
r = np.hypot(xx, yy)
centre = images["Shadowgraph"][r < 0.05].mean()
ring = images["Shadowgraph"][(r > 0.36) & (r < 0.48)].mean()
print("shadowgraph: %.3f at the centre (weak-lens closed form %.3f), %.3f at r = 0.36..0.48 (%.3f)"
      % (centre, 1 + L * 4 * np.sqrt(np.pi) * A / s, ring,
         1 - L * 4 * np.sqrt(np.pi) * A / s * np.exp(-2)))
if not (centre > 1.15 and ring < 0.985):
    sys.exit("numpy_lens: the shadowgraph shows no lens (centre %.3f, ring %.3f)" % (centre, ring))
show(0.5 + 2 * (images["Shadowgraph"] - 1))  # in a notebook: the shadowgraph, 1.0 mid grey

# %% the deflection against the closed form: along the beam (z), a ray at height y is bent by
# d(y) = -sqrt(pi) A (2 y / s) exp(-y^2 / s^2) towards the centre (small-angle, unbent path)
ys = film_origin[1] + pixel * np.arange(size[1])
row = deflection[:, size[0] // 2, 1]
closed = -np.sqrt(np.pi) * A * (2 * ys / s) * np.exp(-ys ** 2 / s ** 2)
err = np.max(np.abs(row - closed)) / np.max(np.abs(closed))
print("largest deflection %.4g rad (closed form %.4g), relative error %.2g"
      % (np.max(np.abs(row)), np.max(np.abs(closed)), err))
if not err < 0.05:
    sys.exit("numpy_lens: the deflection is off the closed form by %.2g" % err)

# %% the three images side by side (the shadowgraph about mid grey, its contrast doubled)
shown = dict(images, Shadowgraph=0.5 + 2 * (images["Shadowgraph"] - 1))
strip = np.concatenate([np.clip(shown[c], 0, 1) for c in images], axis=1)
picture = show(strip)
picture.save(args.output)
print("wrote %s (%d x %d): knife edge | shadowgraph | interferometry" % (args.output,
                                                                        strip.shape[1],
                                                                        strip.shape[0]))
picture  # a notebook shows it
