"""A straightforward NumPy implementation of the same Euler tracer, for the benchmark's comparison.

    /usr/bin/python3 Testing/Benchmarks/numpy_tracer.py --size 256 --film 512 [--rows 64]

The same scene and settings as SchlierenBenchmark (Gaussian sphere A = 1e-4, s = 0.25 on size^3
over [-1, 1]^3, gradient by central differences, beam along -z, Euler steps of 0.5 voxel, the
paper's x += ds v/n, v += ds grad n), vectorised over all rays of a film, trilinear sampling by
hand. `--rows` traces only that many film rows (the rate is per sample, so a slice of the film
measures it without waiting minutes). Prints photons/s, samples/s and the deflection error against
the closed form on the traced rays, as one line of the benchmark's table.
"""
import argparse
import math
import platform
import time

import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--film", type=int, default=512)
    ap.add_argument("--rows", type=int, default=64)
    ap.add_argument("--step", type=float, default=0.5)
    args = ap.parse_args()
    A, s = 1e-4, 0.25
    n = args.size
    h = 2.0 / (n - 1)
    ax = np.linspace(-1.0, 1.0, n, dtype=np.float64)
    z, y, x = np.meshgrid(ax, ax, ax, indexing="ij")  # [k, j, i]
    n1 = (A * np.exp(-(x * x + y * y + z * z) / (s * s))).astype(np.float32)
    del x, y, z
    gz, gy, gx = np.gradient(n1.astype(np.float64), h, h, h, edge_order=1)
    # one array of 4 floats per point, as the engine packs it
    field = np.stack([n1, gx.astype(np.float32), gy.astype(np.float32), gz.astype(np.float32)], axis=-1)
    field = field.reshape(-1, 4)
    del gx, gy, gz

    film = args.film
    pixel = 2.0 / film
    rows = min(args.rows, film)
    j0 = (film - rows) // 2
    ii, jj = np.meshgrid(np.arange(film), np.arange(j0, j0 + rows))
    a = (-1.0 + (ii.ravel() + 0.5) * pixel).astype(np.float32)
    b = (-1.0 + (jj.ravel() + 0.5) * pixel).astype(np.float32)
    rays = a.size

    # rays enter at z = +1 travelling along -z
    px, py, pz = a.copy(), b.copy(), np.full(rays, 1.0, np.float32)
    ds = np.float32(args.step * h)
    inv = np.float32(1.0 / h)

    def sample(px, py, pz):
        fx = np.clip((px + 1.0) * inv, 0, n - 1)
        fy = np.clip((py + 1.0) * inv, 0, n - 1)
        fz = np.clip((pz + 1.0) * inv, 0, n - 1)
        i = np.minimum(fx.astype(np.int64), n - 2)
        j = np.minimum(fy.astype(np.int64), n - 2)
        k = np.minimum(fz.astype(np.int64), n - 2)
        tx, ty, tz = (fx - i)[:, None], (fy - j)[:, None], (fz - k)[:, None]
        base = (k * n + j) * n + i
        out = np.zeros((px.size, 4), np.float32)
        for dk in (0, 1):
            wz = tz if dk else 1 - tz
            for dj in (0, 1):
                wy = ty if dj else 1 - ty
                for di in (0, 1):
                    wx = tx if di else 1 - tx
                    out += (wx * wy * wz) * field[base + (dk * n + dj) * n + di]
        return out

    smp = sample(px, py, pz)
    ne = 1.0 + smp[:, 0]
    wx = np.zeros(rays, np.float32)
    wy = np.zeros(rays, np.float32)
    wz = np.zeros(rays, np.float32)
    samples = rays
    active = np.arange(rays)
    t0 = time.perf_counter()
    while active.size:
        s_ = smp[active]
        nn = 1.0 + s_[:, 0]
        vx, vy, vz = wx[active], wy[active], -ne[active] + wz[active]
        px[active] += ds * vx / nn
        py[active] += ds * vy / nn
        pz[active] += ds * vz / nn
        wx[active] += ds * s_[:, 1]
        wy[active] += ds * s_[:, 2]
        wz[active] += ds * s_[:, 3]
        inside = (np.abs(px[active]) <= 1) & (np.abs(py[active]) <= 1) & (np.abs(pz[active]) <= 1)
        active = active[inside]
        if active.size:
            smp_new = sample(px[active], py[active], pz[active])
            smp[active] = smp_new
            samples += active.size
    seconds = time.perf_counter() - t0
    vnorm = np.sqrt(wx * wx + wy * wy + (wz - ne) ** 2)
    # film axes for the beam along -z with up +y: x right, y up
    ex, ey = wx / vnorm, wy / vnorm
    rho2 = a.astype(np.float64) ** 2 + b.astype(np.float64) ** 2
    f = -(2 * math.sqrt(math.pi) * A / s) * np.exp(-rho2 / (s * s))
    err = np.max(np.hypot(ex - f * a, ey - f * b))
    emax = math.sqrt(2 * math.pi) * A * math.exp(-0.5)
    print("| NumPy %s (%s, 1 thread) | %.3g M | %.3g M | %.1f (%d of %d rows) | %.1f | %.3g | |" % (
        np.__version__, platform.python_version(), rays / seconds / 1e6, samples / seconds / 1e6,
        seconds * 1e3 * film / rows, rows, film, samples / rays, err / emax))


if __name__ == "__main__":
    main()
