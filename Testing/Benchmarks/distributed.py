# SPDX-License-Identifier: BSD-3-Clause
"""Tracing in pieces under MPI: peak memory per rank, ray traffic and time per pass at 1, 2 and 4
ranks; prints a table.

Run: /usr/bin/python3 distributed.py --plugin <Schlieren.so> [--size 384] [--resolution 256]
         [--passes 2] [--ranks 1,2,4] [--integrator Euler] [--step 0.5] [--reconstruction Trilinear]
         [--body 0] [--modes pieces,whole] [--backend CPU] [--pvbatch pvbatch] [--mpiexec mpiexec]

Each row is one `mpiexec -n N pvbatch --mpi --symmetric` run of this script (--worker): every rank
makes its piece of a RefractiveScene of size^3 points (the Gaussian sphere), reads its high-water
mark of resident memory (VmHWM), traces it with SchlierenImage (Euler, 0.5 voxel, knife edge) and
reads VmHWM again. --reconstruction Cubic packs the pieces for tricubic samples (deeper ghosts);
--body 1 puts RefractiveScene's solid sphere (radius 0.2 of the box, off centre) in the volume. "pieces" is the default under MPI (the volume stays in pieces, rays are handed
between ranks); "whole" turns TraceInPieces off: every rank gathers the whole volume (the path
every rank took before tracing in pieces). Both on --backend (CPU by default). Columns: the largest VmHWM of
any rank and the most the trace added on any rank (after - before), the points the busiest rank
held (its piece and ghosts), ray traffic per pass, and the time per pass with where the slowest
rank spent it (stepping rays, exchanging: waiting for the other ranks included). Each rank runs
max(1, cores / N) CPU threads (SCHLIEREN_CPU_THREADS): with more ranks than cores the ranks share
them (oversubscribed), so times at 4 ranks on a 2-core machine show the cost of the exchange, not a
speed-up.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time


def argument(name, default=None):
    for i, a in enumerate(sys.argv):
        if a == name and i + 1 < len(sys.argv):
            return sys.argv[i + 1]
    return default


def hwm():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
    return 0


def worker():
    from paraview import simple
    from paraview.modules.vtkRemotingCore import vtkProcessModule
    ns = globals()
    simple.LoadPlugin(argument("--plugin"), remote=False, ns=ns)
    controller = vtkProcessModule.GetProcessModule().GetGlobalController()
    rank = controller.GetLocalProcessId()
    size = int(argument("--size"))
    scene = ns["RefractiveScene"](Dimensions=[size] * 3, Amplitude=1e-4, Width=0.3)
    if argument("--body", "0") == "1":
        scene.Body = "Sphere"
        scene.BodyRadius = 0.2
        scene.BodyCenter = [-0.25, 0.1, 0.0]
    scene.UpdatePipeline()
    before = hwm()
    image = ns["SchlierenImage"](Input=scene, Resolution=[int(argument("--resolution"))] * 2,
                                 Passes=int(argument("--passes")), Backend=argument("--backend"),
                                 TraceInPieces=int(argument("--pieces")),
                                 Integrator=argument("--integrator", "Euler"),
                                 StepSize=float(argument("--step", "0.5")),
                                 Reconstruction=argument("--reconstruction", "Trilinear"))
    t0 = time.time()
    image.UpdatePipeline()
    seconds = time.time() - t0
    after = hwm()
    # each rank's numbers in a file of its own (the ranks' standard outputs interleave)
    numbers = {"hwm_before": before, "hwm_after": after}
    if rank == 0:
        numbers["seconds"] = seconds
        fd = image.GetClientSideObject().GetOutputDataObject(0).GetFieldData()
        for i in range(fd.GetNumberOfArrays()):
            a = fd.GetArray(i)
            if a is not None and a.GetNumberOfTuples() == 1 and a.GetNumberOfComponents() == 1:
                numbers[fd.GetArrayName(i)] = a.GetValue(0)
    with open(os.path.join(argument("--outdir"), "rank%d.json" % rank), "w") as f:
        json.dump(numbers, f)


def main():
    plugin = argument("--plugin")
    if not plugin:
        raise SystemExit("pass --plugin <Schlieren.so>")
    size = argument("--size", "384")
    resolution = argument("--resolution", "256")
    passes = argument("--passes", "2")
    pvbatch = argument("--pvbatch", "pvbatch")
    mpiexec = argument("--mpiexec", "mpiexec")
    ranks = [int(r) for r in argument("--ranks", "1,2,4").split(",")]
    cores = os.cpu_count() or 1
    points = int(size) ** 3
    print("%s^3 points (%.0f MB of n - 1 as floats, %.0f MB packed), film %s^2, %s passes, %s at %s voxel, %s%s, %d cores"
          % (size, points * 4 / 1e6, points * 16 / 1e6, resolution, passes, argument("--integrator", "Euler"),
             argument("--step", "0.5"), argument("--reconstruction", "Trilinear"),
             ", a solid sphere" if argument("--body", "0") == "1" else "", cores))
    print("%5s %6s %11s %11s %13s %12s %10s %10s %10s %6s %7s %9s %9s" % (
        "ranks", "mode", "peak MB", "trace MB", "held points", "MB/pass", "s/pass", "tracing", "exchange", "ghosts",
        "rounds", "handed M", "samples M"))
    modes = argument("--modes", "pieces,whole").split(",")
    for n in ranks:
        backend = argument("--backend", "CPU")
        for mode, pieces in (("pieces", "1"), ("whole", "0")):
            if (n == 1 and mode == "whole") or (n > 1 and mode not in modes):
                continue  # one rank always has the whole volume (its row says "one")
            env = dict(os.environ, SCHLIEREN_CPU_THREADS=str(max(1, cores // n)))
            cmd = [mpiexec, "-n", str(n), "--allow-run-as-root", "--oversubscribe", pvbatch, "--mpi",
                   "--symmetric", os.path.abspath(__file__), "--worker", "--plugin", plugin, "--size", size,
                   "--resolution", resolution, "--passes", passes, "--backend", backend, "--pieces", pieces,
                   "--integrator", argument("--integrator", "Euler"), "--step", argument("--step", "0.5"),
                   "--reconstruction", argument("--reconstruction", "Trilinear"), "--body", argument("--body", "0")]
            outdir = tempfile.mkdtemp(prefix="schlieren_distributed_")
            run = subprocess.run(cmd + ["--outdir", outdir], env=env, stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, text=True)
            ranks_numbers = []
            for r in range(n):
                path = os.path.join(outdir, "rank%d.json" % r)
                if os.path.exists(path):
                    with open(path) as f:
                        ranks_numbers.append(json.load(f))
            shutil.rmtree(outdir, ignore_errors=True)
            if run.returncode != 0 or len(ranks_numbers) != n:
                print("%5d %6s failed (status %d): %s" % (n, mode, run.returncode, run.stdout[-800:]))
                continue
            rows = [(x["hwm_before"], x["hwm_after"]) for x in ranks_numbers]
            numbers = ranks_numbers[0]
            peak = max(after for before, after in rows) / 1e6
            added = max(after - before for before, after in rows) / 1e6
            held = numbers.get("held_points_max", points)
            p = float(passes)
            mode = "one" if n == 1 else mode
            print("%5d %6s %11.0f %11.0f %13.0f %12.2f %10.2f %10.2f %10.2f %6.0f %7.0f %9.3f %9.2f" % (
                n, mode, peak, added, held, numbers.get("ray_traffic_bytes", 0) / 1e6 / p,
                numbers["seconds"] / p, numbers.get("tracing_seconds", float("nan")) / p,
                numbers.get("exchange_seconds", float("nan")) / p, numbers.get("ghost_layers", 0),
                numbers.get("exchange_rounds", 0) / p, numbers.get("rays_handed_on", 0) / 1e6 / p,
                numbers.get("samples", 0) / 1e6 / p))


if __name__ == "__main__":
    if "--worker" in sys.argv:
        worker()
    else:
        main()
