# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark (not a test): issue 50's first table, our settings beside two peers where their code is
present, on the weak Gaussian sphere of the issue (n - 1 = A exp(-r^2/s^2), A = 2e-4, s = 0.25 on
[-1, 1]^3, N^3 points):

  jdhare/turbulence_tracing  Python, scipy's solve_ivp RK45 over all rays at once, the gradient by
                             np.gradient and RegularGridInterpolator (trilinear); --rays rays in
                             |x|, |y| < 2.2 s along the axis. Its electron-density form is given
                             ne/nc = -2 (n - 1), so that its dv/dt = -grad(c^2 ne / 2 nc) is the
                             ray equation of n.
  nasa/cfdtools SHADOWGRAPH  Fortran, lines of sight (no bending), trapezoids between the cell faces
                             a pixel's ray crosses, the gradient from its own least squares; each
                             view a whole run (reads the grid, differentiates, integrates). Given
                             the density (n - 1) / GDair as a PLOT3D grid and function file; a
                             --film^2 image of 1.99 x 1.99 off the centre by (0.00123, 0.00234),
                             viewed along y (its default): its own default, the box edge to edge,
                             puts pixel rows on grid planes, where a ray is counted once per cell
                             that it touches (2 or 4 times: 4x the deflection at 64^3 with a 64^2
                             film).

Ours: SchlierenBenchmark --cases autostep on the same grids (its rows: Auto + Cubic at 3e-8 rad, line
of sight on the trilinear at a step of the feature's width s, Auto at its default tolerance, Euler at
one voxel), rays/s of the trace (the pilot apart: its ms are in that case's own table).

Errors: RMS of |deflection - closed form| over the peer's rays (turbulence_tracing) or the pixel
centres within 2.2 s (SHADOWGRAPH, ours), of the peak deflection (the closed form of ORACLES.md).
Speed-ups: our rays/s over the peer's (turbulence_tracing: rays over solve_ivp's time; SHADOWGRAPH:
pixels over the whole run's wall time).

Where the peers go (they are not part of this repository; put them there yourself):

  SCHLIEREN_PEERS (default: ../peers beside the repository, as ../shared is)
    turbulence_tracing/particle_tracking/particle_tracker.py   (git clone jdhare/turbulence_tracing)
    cfdtools/build/shadowgraph   (nasa/cfdtools app/shadowgraph built with gfortran; see --help-build)

    /usr/bin/python3 Testing/Benchmarks/peers.py [--benchmark build/bin/SchlierenBenchmark]
        [--grids 64,128,256] [--peer-grids 64,128,256] [--rays 20000] [--film 512] [--passes 3]

A peer that is absent gets "not present: put it at ..." in its columns; the rest still runs.
--peer-grids bounds the peers' grids (512^3 takes turbulence_tracing about 8 GiB of float64 arrays,
and SHADOWGRAPH's PLOT3D records would pass gfortran's 2 GiB record); --grids bounds ours.
"""
import argparse
import os
import platform
import re
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np

A, S = 2e-4, 0.25
GDAIR = 0.000292 / 1.293  # SHADOWGRAPH's Gladstone-Dale constant for air, m^3/kg (n - 1 = GDair rho)
HELP_BUILD = """Building SHADOWGRAPH (gfortran; not a dependency of this project):
  D=$SCHLIEREN_PEERS/cfdtools; mkdir -p $D/build && cd $D/build
  F="-O2 -fdefault-real-8 -fdefault-double-8 -ffixed-line-length-none -ffree-line-length-none -fallow-argument-mismatch -w"
  S=../app/shadowgraph
  for f in ../lib/{interp3d,intrinsics,numodules,progtools}/*.f*; do gfortran $F -c $f -o lib_$(basename $f).o || true; done
  for f in $S/grid_block_structure.f90 ../lib/xyzq_io/xyzq_io.f90 ../lib/grid_block_utilities/grid_block_utilities.f90 \\
      $S/FieldView_Data.f90 $S/VTK_Data.f90 $S/flow_gradients.f90 $S/triangulate_quad_face.f90 $S/process_tet_cell.f90 \\
      $S/process_pyramid.f90 $S/process_prism.f90 $S/process_hex_cell.f90 $S/read_fieldview.f90 $S/shadowgraph.f90 \\
      ../lib/geomlib/rotate3d.f ../lib/linsys/lusolve.f90; do gfortran $F -c $f; done
  ar rcs libpeer.a lib_*.o && gfortran -o shadowgraph $(ls *.o | grep -v '^lib_') libpeer.a
(the libraries first: the program's files use their modules, trigd among them; the libraries' files
 that do not compile alone are not needed)
"""


def closed_form(a, b):
    """The deflection of the weak Gaussian (first order in A), beam along an axis; (a, b) across it."""
    f = -(2 * np.sqrt(np.pi) * A / S) * np.exp(-(a * a + b * b) / (S * S))
    return f * a, f * b


PEAK = np.sqrt(2 * np.pi) * A * np.exp(-0.5)


def field(n):
    ax = np.linspace(-1.0, 1.0, n)
    r2 = ax[:, None, None] ** 2 + ax[None, :, None] ** 2 + ax[None, None, :] ** 2  # [i, j, k]: x, y, z
    r2 *= -1.0 / (S * S)
    return ax, A * np.exp(r2, out=r2)


def run_turbulence_tracing(folder, n, rays, seed=50):
    sys.path.insert(0, os.path.join(folder, "particle_tracking"))
    import particle_tracker as pt  # the peer's module, from where the user put it

    ax, dn = field(n)
    cube = pt.ElectronCube(ax, ax, ax)
    lwl = 1053e-9
    omega = 2 * np.pi * (pt.c / lwl)
    nc = 3.14207787e-4 * omega ** 2  # its critical density (calc_dndr)
    cube.external_ne(-2.0 * dn * nc)
    del dn
    t0 = time.perf_counter()
    cube.calc_dndr(lwl=lwl)
    setup = time.perf_counter() - t0
    rng = np.random.default_rng(seed)
    s0 = np.zeros((6, rays))
    s0[0] = rng.uniform(-2.2 * S, 2.2 * S, rays)
    s0[1] = rng.uniform(-2.2 * S, 2.2 * S, rays)
    s0[2] = -cube.extent_z
    s0[5] = pt.c
    cube.extent = cube.extent_z
    cube.s0 = s0
    t0 = time.perf_counter()
    rf = cube.solve()
    solve = time.perf_counter() - t0
    ex, ey = closed_form(s0[0], s0[1])
    err = np.hypot(rf[1] - ex, rf[3] - ey)
    sys.path.pop(0)
    return dict(rms=float(np.sqrt(np.mean(err ** 2))) / PEAK, max=float(err.max()) / PEAK,
                rate=rays / solve, seconds=solve, setup=setup)


def fortran_record(f, data):
    b = data.tobytes(order="F") if isinstance(data, np.ndarray) else data
    if len(b) > 2 ** 31 - 9:
        raise ValueError("a PLOT3D record over 2 GiB (gfortran's subrecords are not written here)")
    f.write(struct.pack("<i", len(b)) + b + struct.pack("<i", len(b)))


def read_records(path):
    out = []
    with open(path, "rb") as f:
        while True:
            head = f.read(4)
            if len(head) < 4:
                break
            size = struct.unpack("<i", head)[0]
            out.append(f.read(size))
            f.read(4)
    return out


def run_shadowgraph(exe, n, film):
    ax, dn = field(n)
    with tempfile.TemporaryDirectory(prefix="peer_shadowgraph_") as d:
        x, y, z = np.meshgrid(ax, ax, ax, indexing="ij")
        with open(os.path.join(d, "grid.gu"), "wb") as f:
            fortran_record(f, np.array([1], np.int32))
            fortran_record(f, np.array([n, n, n], np.int32))
            fortran_record(f, np.concatenate([x.ravel(order="F"), y.ravel(order="F"), z.ravel(order="F")]))
        del x, y, z
        with open(os.path.join(d, "flow.fu"), "wb") as f:
            fortran_record(f, np.array([1], np.int32))
            fortran_record(f, np.array([n, n, n, 1], np.int32))
            fortran_record(f, (dn / GDAIR).ravel(order="F"))
        del dn
        control = "\n".join([
            "SHADOWGRAPH Control File", "1", "1", "3", "grid.gu", "F", "flow.fu", "F", "F",
            "0. 1. 0.", "%d %d" % (film, film), "1.99 1.99", "0.00123 0. 0.00234", "10.", "999999.", ""])
        t0 = time.perf_counter()
        with open(os.path.join(d, "control.inp"), "w") as f:
            f.write(control)
        with open(os.path.join(d, "control.inp")) as inp:
            r = subprocess.run([exe], stdin=inp, cwd=d, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if r.returncode != 0 or not os.path.exists(os.path.join(d, "quadratures.fu")):
            log = open(os.path.join(d, "shadowgraph.log")).read()[-2000:] if os.path.exists(
                os.path.join(d, "shadowgraph.log")) else r.stdout[-2000:]
            raise RuntimeError("SHADOWGRAPH failed (%d): %s" % (r.returncode, log))
        pix = read_records(os.path.join(d, "pixels.gu"))
        ni, nj = struct.unpack("<2i", pix[1])
        xz = np.frombuffer(pix[2], np.float64)
        xi = xz[:ni * nj].reshape((ni, nj), order="F")
        zi = xz[ni * nj:].reshape((ni, nj), order="F")
        q = np.frombuffer(read_records(os.path.join(d, "quadratures.fu"))[2], np.float64)
        # quadratures(1, :, :), (2, :, :), (3, :, :): n - 1, (1/n) dn/dx, (1/n) dn/dz along y
        qx = q[ni * nj:2 * ni * nj].reshape((ni, nj), order="F")
        qz = q[2 * ni * nj:].reshape((ni, nj), order="F")
    inside = (abs(xi) < 2.2 * S) & (abs(zi) < 2.2 * S)
    ex, ez = closed_form(xi[inside], zi[inside])
    err = np.hypot(qx[inside] - ex, qz[inside] - ez)
    return dict(rms=float(np.sqrt(np.mean(err ** 2))) / PEAK, max=float(err.max()) / PEAK,
                rate=ni * nj / wall, seconds=wall)


def run_ours(bench, grids, film, passes):
    cmd = [bench, "--cases", "autostep", "--grids", ",".join(str(g) for g in grids), "--backends", "OpenCL",
           "--film", str(film), "--passes", str(passes)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s failed (%d): %s" % (" ".join(cmd), r.returncode, r.stdout[-2000:] + r.stderr[-2000:]))
    rows = {}
    for line in r.stdout.splitlines():
        m = re.match(r"\|\s*(\d+)\^3\s*\|\s*OpenCL\s*\|([^|]+)\|([^|]+)\|([^|]+)\|\s*([\d.e+-]+) %\s*\|\s*([\d.e+-]+) %"
                     r"\s*\|\s*([\d.e+-]+) M\s*\|", line)
        if m:
            rows[(int(m.group(1)), m.group(2).strip())] = dict(
                chosen=m.group(3).strip(), samples=float(m.group(4)), rms=float(m.group(5)) / 100,
                max=float(m.group(6)) / 100, rate=float(m.group(7)) * 1e6)
    return rows, r.stdout


def pct(v):
    return "%.3g %%" % (100 * v)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    ap.add_argument("--benchmark", default=None, help="SchlierenBenchmark (default: the first of build/bin, "
                    "build/Testing/Cxx, build-eng/Testing/Cxx that exists)")
    ap.add_argument("--grids", default="64,128,256,512")
    ap.add_argument("--peer-grids", default="64,128,256")
    ap.add_argument("--rays", type=int, default=20000)
    ap.add_argument("--film", type=int, default=512)
    ap.add_argument("--passes", type=int, default=3)
    ap.add_argument("--help-build", action="store_true", help="how to build SHADOWGRAPH")
    args = ap.parse_args()
    if args.help_build:
        print(HELP_BUILD)
        return 0
    peers = os.environ.get("SCHLIEREN_PEERS", os.path.join(os.path.dirname(root), "peers"))
    tt = os.path.join(peers, "turbulence_tracing")
    tt_file = os.path.join(tt, "particle_tracking", "particle_tracker.py")
    sg = os.path.join(peers, "cfdtools", "build", "shadowgraph")
    bench = args.benchmark
    if bench is None:
        for c in ("build/bin", "build/Testing/Cxx", "build-eng/Testing/Cxx"):
            if os.path.exists(os.path.join(root, c, "SchlierenBenchmark")):
                bench = os.path.join(root, c, "SchlierenBenchmark")
                break
    if bench is None or not os.path.exists(bench):
        print("SchlierenBenchmark not found: build it (cmake --build build --target SchlierenBenchmark) or "
              "give --benchmark")
        return 1
    grids = [int(g) for g in args.grids.split(",")]
    peer_grids = [int(g) for g in args.peer_grids.split(",")]
    try:
        load = os.getloadavg()
    except OSError:
        load = (float("nan"),) * 3
    print("# issue 50's table: ours beside the peers\n")
    print("machine: %s, %d hardware threads, load average %.1f %.1f %.1f at the start" % (
        platform.processor() or platform.machine(), os.cpu_count(), *load))
    print("weak Gaussian A = %g, s = %g on [-1, 1]^3, peak deflection %.4g rad; ours: %s\n" % (A, S, PEAK, bench))

    peer = {}
    have_tt, have_sg = os.path.exists(tt_file), os.access(sg, os.X_OK)
    for n in peer_grids:
        if have_tt:
            r = run_turbulence_tracing(tt, n, args.rays)
            peer[("tt", n)] = r
            print("turbulence_tracing %d^3: %d rays in %.2f s (RK45; np.gradient and interpolators %.2f s), "
                  "RMS %s, max %s" % (n, args.rays, r["seconds"], r["setup"], pct(r["rms"]), pct(r["max"])))
        if have_sg and 3 * 8 * n ** 3 > 2 ** 31 - 9:
            peer[("sg", n)] = None
            print("SHADOWGRAPH %d^3: not run: its PLOT3D grid would be one record over 2 GiB "
                  "(gfortran's subrecords are not written here)" % n)
        elif have_sg:
            r = run_shadowgraph(sg, n, args.film)
            peer[("sg", n)] = r
            print("SHADOWGRAPH %d^3: %d^2 pixels in %.2f s (the whole run), RMS %s, max %s" % (
                n, args.film, r["seconds"], pct(r["rms"]), pct(r["max"])))
    if not have_tt:
        print("turbulence_tracing: not present: put it at %s (git clone https://github.com/jdhare/turbulence_tracing; "
              "or set SCHLIEREN_PEERS)" % tt)
    if not have_sg:
        print("SHADOWGRAPH: not present: put the built program at %s (nasa/cfdtools, app/shadowgraph; "
              "--help-build says how; or set SCHLIEREN_PEERS)" % sg)
    sys.stdout.flush()

    t0 = time.perf_counter()
    ours, text = run_ours(bench, grids, args.film, args.passes)
    print("ours: %s --cases autostep --grids %s --backends OpenCL --film %d --passes %d (%.0f s)\n" % (
        bench, ",".join(map(str, grids)), args.film, args.passes, time.perf_counter() - t0))
    cubic, straight, default, euler = ("Auto, 3e-8 rad", "Straight, trilinear, step = s", "Auto, default tolerance",
                                       "Euler 1 voxel")

    def speed(n, key, who):
        p = peer.get((who, n))
        o = ours.get((n, key))
        if p is None or o is None:
            return "-"
        return "%.3g x" % (o["rate"] / p["rate"])

    absent = {"tt": "not present" if not have_tt else "not run (--peer-grids)",
              "sg": "not present" if not have_sg else "not run (--peer-grids)"}
    print("| grid | turbulence_tracing: RMS error, rays/s | ours Auto + Cubic 3e-8 rad: RMS error, speed-up | "
          "line of sight, trilinear, step = s: RMS error, speed-up | Auto at its default tolerance: RMS error, "
          "speed-up | SHADOWGRAPH: RMS error, rays/s | Euler 1 voxel (one sample a voxel, as SHADOWGRAPH): RMS error, "
          "speed-up over SHADOWGRAPH | line of sight, step = s: speed-up over SHADOWGRAPH |")
    print("|---|---|---|---|---|---|---|---|")
    for n in grids:
        cells = ["%d^3" % n]
        p = peer.get(("tt", n))
        cells.append("%s, %.3g" % (pct(p["rms"]), p["rate"]) if p else absent["tt"])
        for key in (cubic, straight, default):
            o = ours.get((n, key))
            cells.append("%s, %s" % (pct(o["rms"]), speed(n, key, "tt")) if o else "-")
        p = peer.get(("sg", n))
        cells.append("%s, %.3g" % (pct(p["rms"]), p["rate"]) if p else
                     "not run (a record over 2 GiB)" if ("sg", n) in peer else absent["sg"])
        o = ours.get((n, euler))
        cells.append("%s, %s" % (pct(o["rms"]), speed(n, euler, "sg")) if o else "-")
        cells.append(speed(n, straight, "sg"))
        print("| " + " | ".join(cells) + " |")
    print("\nours, as SchlierenBenchmark printed it:\n")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
