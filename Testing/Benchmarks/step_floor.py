#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The fewest samples a ray that any step gives on issue 50's Gaussian at a tolerance: a model.

Velocity Verlet (the engine's Integrator Verlet: half a kick, the move, half a kick with the
gradient where the step ends, one sample a step and one where the ray leaves) on the analytic
index n = 1 + A exp(-r^2/s^2), A = 2e-4, s = 0.25, rays along -z through [-1, 1]^3, against the
same integrator at 1e-4 of the box's half width (its own error ~1e-15 rad). No grid: the steps'
own error alone, as on a tricubic field that resolves the Gaussian (the 512^3 field, or Auto's
copy of it). Prints, per step in voxels of an N^3 grid over the box (--grid, default 512):

  - uniform steps: samples a ray and the largest deflection error over 246 rays;
  - steps that lengthen where the Gaussian is weak: a step of h0 * 2^(k/2) (up to hmax) wherever
    the field at the closest point that step can reach is weak enough (exp(-rc^2/s^2)^(p/3) times
    the step within h0), swept over p, h0 and hmax: the cheapest that meet the tolerance.

So it bounds what Auto can reach on this scene with any step rule, adaptive or not: the issue's
0.7 (512^3's rays/s over 64^3's, where Auto takes 8 samples a ray) is at most 8 over these
samples at the same time a sample. Run: /usr/bin/python3 Testing/Benchmarks/step_floor.py
"""
import argparse

import numpy as np

A, S = 2e-4, 0.25


def index_and_gradient(p):
    r2 = (p ** 2).sum(-1)
    e = A * np.exp(-r2 / S ** 2)
    return 1 + e, (-2 / S ** 2) * e[..., None] * p


def verlet(b, step_of):
    """Deflections (m, 2) and samples a ray of rays entering at z = 1 at points b (m, 2); the
    step of each ray at its position from step_of(positions)."""
    m = len(b)
    x = np.zeros((m, 3))
    x[:, :2] = b
    x[:, 2] = 1.0
    n, g = index_and_gradient(x)
    w = np.zeros((m, 3))
    w[:, 2] = -n  # n times the direction
    samples = np.ones(m)
    alive = np.ones(m, bool)
    while alive.any():
        h = step_of(x)
        # the last step ends where the ray leaves the box at z = -1
        rest = (x[:, 2] + 1) / np.maximum(1e-30, -w[:, 2] / n)
        last = alive & (h >= 0.999999 * rest)
        h = np.where(last, rest, h)
        h = np.where(alive, h, 0.0)
        w = w + 0.5 * h[:, None] * g
        x = x + h[:, None] * w / n[:, None]
        n, g = index_and_gradient(x)
        w = w + 0.5 * h[:, None] * g
        samples += alive
        alive &= ~last
    return w[:, :2] / n[:, None], samples


def lengthening(h0, hmax, p):
    ladder = h0 * 2 ** (np.arange(0, 16) / 2.0)
    ladder = ladder[ladder <= hmax * (1 + 1e-9)]

    def step_of(x):
        r = np.sqrt((x ** 2).sum(-1))
        h = np.full(len(x), h0)
        for hl in ladder:
            rc = np.maximum(0.0, r - hl)  # the closest to the centre this step can come
            weak = np.exp(-rc ** 2 / S ** 2) ** (-p / 3.0)
            h = np.where(hl <= h0 * weak, hl, h)
        return h

    return step_of


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grid", type=int, default=512, help="points a side: the voxel the steps are counted in")
    ap.add_argument("--tolerance", type=float, default=3e-8, help="radians (default 3e-8)")
    a = ap.parse_args()
    vox = 2.0 / (a.grid - 1)
    rng = np.random.default_rng(1)
    b = np.concatenate([np.c_[np.linspace(0, 0.9, 46), np.zeros(46)], rng.uniform(-0.9, 0.9, (200, 2))])
    exact = verlet(b, lambda x: np.full(len(x), 1e-4))[0]
    check = verlet(b, lambda x: np.full(len(x), 2e-4))[0]
    print("Verlet on the analytic Gaussian (A = %g, s = %g), %d rays; the reference's own error %.1e rad"
          % (A, S, len(b), np.abs(exact - check).max()))
    print("\n| step (voxels of %d^3) | samples a ray | largest error (rad) | meets %g |" % (a.grid, a.tolerance))
    print("|---|---|---|---|")
    fewest = None
    for k in range(12, 30):
        hv = 2 ** (k / 4.0)
        d, s = verlet(b, lambda x, h=hv * vox: np.full(len(x), h))
        e = np.hypot(*(d - exact).T).max()
        ok = e <= a.tolerance
        if ok and (fewest is None or s.mean() < fewest[0]):
            fewest = (s.mean(), "uniform %.1f voxels" % hv, e)
        print("| %.1f | %.1f | %.2e | %s |" % (hv, s.mean(), e, "yes" if ok else "no"))
    found = []
    for p in (0.5, 1.0, 1.5, 3.0):
        for h0 in (16, 22.6, 32, 38.1, 45.3, 53.8):
            for hmax in (64, 90.5, 128, 256, 512):
                if hmax <= h0:
                    continue
                d, s = verlet(b, lengthening(h0 * vox, hmax * vox, p))
                e = np.hypot(*(d - exact).T).max()
                if e <= a.tolerance:
                    found.append((s.mean(), e, p, h0, hmax))
    found.sort()
    print("\nSteps that lengthen where the Gaussian is weak, the cheapest %d of %d that meet %g rad:"
          % (min(5, len(found)), len(found), a.tolerance))
    print("\n| p | h0 (voxels) | hmax (voxels) | samples a ray | largest error (rad) |")
    print("|---|---|---|---|---|")
    for s, e, p, h0, hmax in found[:5]:
        print("| %.1f | %.1f | %.1f | %.2f | %.2e |" % (p, h0, hmax, s, e))
    if found and (fewest is None or found[0][0] < fewest[0]):
        fewest = (found[0][0], "lengthening p %.1f from %.1f to %.1f voxels" % found[0][2:], found[0][1])
    if fewest:
        print("\nFewest samples a ray that meet %g rad: %.2f (%s, %.2e rad). Against 8 a ray (Auto at 64^3): "
              "rays/s at most %.2f of 64^3's at the same time a sample."
              % (a.tolerance, fewest[0], fewest[1], fewest[2], 8 / fewest[0]))


if __name__ == "__main__":
    main()
