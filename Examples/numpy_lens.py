# SPDX-License-Identifier: BSD-3-Clause
# %% [markdown]
# # Schlieren from NumPy arrays (Jupyter-friendly: each `# %%` is a cell)
#
# The engine needs no VTK: a NumPy array of n - 1 on a regular grid goes in, NumPy images come
# out. Here a Gaussian lens of denser air, traced three ways (knife edge, shadowgraph,
# interferometry) and checked against the closed form of the line-of-sight deflection.
#
#     pip install .          # or the wheel
#     python Examples/numpy_lens.py --output lens.png

# %%
import argparse
import sys

import numpy as np

from schlieren import engine
from schlieren.png import write_png

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

# %% one session, three optics: the volume is packed once
session = engine.Session()
session.set_volume(dims, origin, spacing, n_minus_1.ravel())
images = {}
for cutoff in ("KnifeEdge", "Shadowgraph", "Interferometry"):
    for k, v in dict(Cutoff=cutoff, Resolution=[128, 128], Passes=4, Backend=args.backend,
                     FilmDistance=0.5 if cutoff == "Shadowgraph" else 0.0).items():
        session.set(k, v)
    report = session.trace()
    size, film_origin, pixel = session.film()
    images[cutoff] = session.array("intensity").reshape(size[1], size[0])
    deflection = session.array("deflection").reshape(size[1], size[0], 2)
    print("%-14s intensity %.3f..%.3f on %s" % (cutoff, images[cutoff].min(),
                                                 images[cutoff].max(),
                                                 report["field_data"]["backend"]))

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

# %% the three images side by side (in a notebook: plt.imshow(strip, origin="lower"))
strip = np.concatenate([np.clip(images[c] / max(1.0, images[c].max()), 0, 1) for c in images],
                       axis=1)
write_png(strip, args.output)
print("wrote %s (%d x %d): knife edge | shadowgraph | interferometry" % (args.output,
                                                                        strip.shape[1],
                                                                        strip.shape[0]))
