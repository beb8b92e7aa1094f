# SPDX-License-Identifier: BSD-3-Clause
"""Peak host memory that a trace adds, per voxel, on each backend: prints a table.

Run: pvpython memory_per_voxel.py --plugin <Schlieren.so> [--size 256] [--pvpython pvpython]

Each row runs in a pvpython child of its own (VmHWM, the process's high-water mark of resident
memory, only grows): the child makes a RefractiveScene of size^3 points, updates it, reads VmHWM,
then traces it with SchlierenImage (a 64^2 film, one pass: the film is negligible) and reads VmHWM
again. (after - before) / voxels is what tracing holds on top of the input at its peak: the
filter's copy of n - 1, the packed field, and on an OpenCL device that keeps its buffers in host
memory, the driver's copy unless the buffer uses the field in place (CL_MEM_USE_HOST_PTR, off
with SCHLIEREN_CL_USE_HOST_PTR=0).
"""
import os
import subprocess
import sys


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


def child(plugin, size, backend):
    from paraview import simple
    from paraview import servermanager as sm
    ns = globals()
    simple.LoadPlugin(plugin, remote=False, ns=ns)
    scene = ns["RefractiveScene"](Dimensions=[size] * 3)
    scene.UpdatePipeline()
    before = hwm()
    image = ns["SchlierenImage"](Input=scene, Backend=backend, Resolution=[64, 64])
    image.UpdatePipeline()
    d = sm.Fetch(image)
    after = hwm()
    used = d.GetFieldData().GetAbstractArray("backend").GetValue(0)
    sys.stdout.write("ROW %s %d %d %s\n" % (backend, before, after, used))


def main():
    plugin = argument("--plugin", os.environ.get("SCHLIEREN_PLUGIN"))
    size = int(argument("--size", "256"))
    if argument("--child"):
        child(plugin, size, argument("--child"))
        return 0
    rows = [("CPU", {}), ("OpenCL", {}), ("OpenCL", {"SCHLIEREN_CL_USE_HOST_PTR": "0"})]
    voxels = float(size) ** 3
    print("Peak host memory a trace adds, %d^3 = %.1f M voxels, 64^2 film (VmHWM after - before)"
          % (size, voxels / 1e6))
    print("| backend | buffer | MiB added | bytes per voxel |")
    print("|---|---|---|---|")
    for backend, env in rows:
        e = dict(os.environ, **env)
        out = subprocess.run([argument("--pvpython", "pvpython"), os.path.abspath(__file__), "--plugin", plugin,
                              "--size", str(size), "--child", backend], env=e,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT).stdout.decode()
        row = [l for l in out.splitlines() if l.startswith("ROW ")]
        if not row:
            print("| %s | (failed: %s) | | |" % (backend, out.strip()[-200:]))
            continue
        _, b, before, after, used = row[0].split()
        added = int(after) - int(before)
        how = "" if backend == "CPU" else ("copied by the driver" if env else "the field in place")
        print("| %s | %s | %.0f | %.1f |" % (used, how, added / 2.0 ** 20, added / voxels))
    return 0


sys.exit(main())
