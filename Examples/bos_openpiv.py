# SPDX-License-Identifier: BSD-3-Clause
"""Our BOS recording through the laboratory's software: OpenPIV's cross-correlation against the
traced bos_displacement (docs/BENCH.md "BOS image pairs").

    pip install openpiv          # with the schlieren package (pip install .), or a build tree's
    python Examples/bos_openpiv.py --output bos_openpiv

1. A Gaussian sphere of denser air (n - 1 = A exp(-r^2/s^2), s = 0.25, on a grid over [-1, 1]^3)
   seen by BOS (a random-dot background BackgroundDistance behind the volume's box) is traced, and
   the engine writes the pair PIV codes read: the undistorted background, the recording (grey PNG
   or TIFF, 8 or 16 bits) and the side file bos.json (pixel size, bench, the displacement's units
   and sign).
2. OpenPIV reads the two files back and cross-correlates them, frame A the background, frame B the
   recording: windows of 32 px (the dots' period is 6 px: about 28 dots a window, well above the
   ~10 that a reliable correlation peak needs, and the largest shift, about 5 px, stays under a
   quarter of the window, the usual rule), 75 % overlap (a vector every 8 px, 61 x 61 on a 512^2
   film), no search-area extension (the shifts are small), the three-point Gaussian fit of the
   correlation peak (the dots are Gaussian, 1.5 px in 1/e radius: the fit suits them and avoids
   peak locking).
3. The vectors are compared with bos_displacement at the windows' centres (bilinear): OpenPIV's
   rows run down, the film's y up, so v_openpiv = -d_y; d is in film pixels (bos_displacement /
   pixel_size), and the sign is the side file's: recording(p) = background(p - d).
   It prints the median and the 95th percentile of |difference| (px) and writes compare.png:
   |d| traced, |d| from OpenPIV (the same grey scale), |difference| (white = 0.5 px).

--max-median and --max-p95 make it fail (exit 1) above those (the test's known answer).
"""
import argparse
import json
import os
import sys
import time

import numpy as np

from schlieren import engine
from schlieren.png import write_png

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--output", default="bos_openpiv", help="a folder (made if missing)")
ap.add_argument("--resolution", type=int, default=512)
ap.add_argument("--grid", type=int, default=128, help="grid points along each axis")
ap.add_argument("--passes", type=int, default=8)
ap.add_argument("--amplitude", type=float, default=1e-3, help="n - 1 at the sphere's centre")
ap.add_argument("--background-distance", type=float, default=10.0,
                help="world units from the volume's box to the background")
ap.add_argument("--bits", type=int, default=8)
ap.add_argument("--format", default="png", choices=["png", "tiff"])
ap.add_argument("--window", type=int, default=32)
ap.add_argument("--overlap", type=int, default=24)
ap.add_argument("--backend", default="Auto")
ap.add_argument("--max-median", type=float, default=None)
ap.add_argument("--max-p95", type=float, default=None)
args = ap.parse_args()

try:
    from openpiv import pyprocess
except ImportError as e:
    sys.exit("bos_openpiv: OpenPIV is not installed (pip install openpiv): %s" % e)

# 1. the trace and the pair
t0 = time.time()
n = args.grid
dims, origin, spacing = [n, n, n], [-1.0] * 3, [2.0 / (n - 1)] * 3
scene = engine.fill_scene(dict(Scene="GaussianSphere", Amplitude=args.amplitude, Width=0.25), dims,
                          origin, spacing)
session = engine.Session()
session.set_volume(dims, origin, spacing, scene["n_minus_1"])
for k, v in dict(Cutoff="BOS", BackgroundDistance=args.background_distance,
                 Resolution=[args.resolution] * 2, Passes=args.passes,
                 Backend=args.backend).items():
    session.set(k, v)
report = session.trace()
os.makedirs(args.output, exist_ok=True)
files = session.write_bos_pair(args.output, args.bits, args.format)
side = json.load(open(files["side_file"]))
(nx, ny), _, pixel = session.film()
shift = session.array("bos_displacement").reshape(ny, nx, 2) / pixel  # film pixels, row 0 bottom
t1 = time.time()
print("traced %dx%d BOS (%s, %d passes, Z_D %.3g, dots every %.3g px), largest shift %.3f px; "
      "wrote %s and %s (%d bit) in %.1f s"
      % (nx, ny, report["field_data"]["backend"], args.passes,
         side["bench"]["background_distance"], side["bench"]["background_period_pixels"],
         side["displacement"]["max_pixels"], files["background"], files["recording"], args.bits,
         t1 - t0))


# 2. OpenPIV on the files, as a laboratory reads them
def read_grey(path):
    try:
        from imageio.v3 import imread
    except ImportError:
        from PIL import Image

        def imread(p):
            return np.asarray(Image.open(p))
    return np.asarray(imread(path), dtype=np.float64)


frame_a, frame_b = read_grey(files["background"]), read_grey(files["recording"])
if frame_a.shape != (ny, nx) or frame_b.shape != (ny, nx):
    sys.exit("bos_openpiv: the images read back are %s and %s, not %dx%d"
             % (frame_a.shape, frame_b.shape, ny, nx))
u, v, s2n = pyprocess.extended_search_area_piv(
    frame_a, frame_b, window_size=args.window, overlap=args.overlap,
    search_area_size=args.window, subpixel_method="gaussian", sig2noise_method="peak2peak")
t2 = time.time()

# 3. against bos_displacement at the windows' centres: window k spans rows (columns) k step ..
# k step + window - 1, its centre at k step + (window - 1) / 2 in pixel indices; file row r is
# film row ny - 1 - r
step = args.window - args.overlap
rows = np.arange(u.shape[0]) * step + (args.window - 1) / 2.0
cols = np.arange(u.shape[1]) * step + (args.window - 1) / 2.0
R, C = np.meshgrid(rows, cols, indexing="ij")
J = ny - 1 - R


def bilinear(a, j, i):
    j0, i0 = np.floor(j).astype(int), np.floor(i).astype(int)
    j1, i1 = np.minimum(j0 + 1, a.shape[0] - 1), np.minimum(i0 + 1, a.shape[1] - 1)
    fj, fi = (j - j0)[..., None], (i - i0)[..., None]
    return ((1 - fj) * ((1 - fi) * a[j0, i0] + fi * a[j0, i1])
            + fj * ((1 - fi) * a[j1, i0] + fi * a[j1, i1]))


traced = bilinear(shift, J, C)                      # (d_x, d_y), film axes, px
piv = np.stack([u, -v], axis=-1)                    # OpenPIV's v runs down the rows
diff = np.hypot(*(piv - traced).transpose(2, 0, 1))
median, p95 = float(np.median(diff)), float(np.percentile(diff, 95))
over = float(np.mean(diff > 1.0))
print("OpenPIV: %d windows of %d px, overlap %d, Gaussian peak fit, in %.1f s: |OpenPIV - "
      "bos_displacement| median %.4f px, 95th percentile %.3f px, %.2f %% over 1 px "
      "(largest traced shift at the centres %.3f px)"
      % (diff.size, args.window, args.overlap, t2 - t1, median, p95, 100 * over,
         np.hypot(*traced.transpose(2, 0, 1)).max()))

# compare.png: |d| traced, |d| OpenPIV (one scale), |difference| (white = 0.5 px); windows as
# blocks of `step` pixels, row 0 at the bottom as the film
mag_t = np.hypot(*traced.transpose(2, 0, 1))[::-1]
mag_p = np.hypot(*piv.transpose(2, 0, 1))[::-1]
top = max(mag_t.max(), 1e-30)
panels = [mag_t / top, mag_p / top, diff[::-1] / 0.5]
gap = np.ones((mag_t.shape[0], 1))
strip = np.concatenate(sum(([p, gap] for p in panels), [])[:-1], axis=1)
write_png(np.kron(strip, np.ones((step, step))), os.path.join(args.output, "compare.png"))
print("wrote %s" % os.path.join(args.output, "compare.png"))

with open(os.path.join(args.output, "openpiv.json"), "w") as f:
    json.dump(dict(windows=int(diff.size), window=args.window, overlap=args.overlap,
                   median_px=median, p95_px=p95, share_over_1px=over,
                   largest_shift_px=float(side["displacement"]["max_pixels"])), f, indent=1)

bad = []
if args.max_median is not None and not median <= args.max_median:
    bad.append("median %.4f px > %g" % (median, args.max_median))
if args.max_p95 is not None and not p95 <= args.max_p95:
    bad.append("95th percentile %.3f px > %g" % (p95, args.max_p95))
if bad:
    sys.exit("bos_openpiv: OpenPIV disagrees with bos_displacement: " + "; ".join(bad))
