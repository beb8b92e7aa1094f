# SPDX-License-Identifier: BSD-3-Clause
"""Writes the NASA blunt fin (../shared/data, PLOT3D) resampled to an N^3 image of n - 1, for
SchlierenBenchmark --raw: the real-data case of the speed benchmark.

    pvpython bluntfin_volume.py --plugin Schlieren.so --output DIR [--size 256] [--data DIR]

Writes DIR/bluntfin_<N>.raw (float32 n - 1, x fastest, little-endian) and DIR/bluntfin_<N>.txt
("dims nx ny nz", "origin x y z", "spacing x y z"). The chain is Examples/bluntfin.py's (blunt_fin_index):
PLOT3DReader -> RefractiveIndex (Gladstone-Dale, air, density x 1.2 kg/m^3, Extend ambient).
Exit status 125 (and a SKIP line) when the data is absent.
"""
import argparse
import os
import sys

from paraview.simple import LoadPlugin, servermanager

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples"))
from bluntfin import blunt_fin_index  # noqa: E402  (the example's chain: one recipe for both)
DEFAULT_DATA = os.environ.get("SCHLIEREN_DATA") or os.path.join(HERE, "..", "..", "..", "shared", "data")

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--plugin", required=True)
ap.add_argument("--output", required=True)
ap.add_argument("--size", type=int, default=256)
ap.add_argument("--data", default=DEFAULT_DATA)
args = ap.parse_args()

xyz = os.path.join(args.data, "bluntfinxyz.bin")
q = os.path.join(args.data, "bluntfinq.bin")
if not (os.path.exists(xyz) and os.path.exists(q)):
    print("bluntfin_volume: SKIP, no blunt-fin data in %s (set SCHLIEREN_DATA)" % os.path.abspath(args.data))
    sys.exit(125)
os.makedirs(args.output, exist_ok=True)
base = os.path.join(args.output, "bluntfin_%d" % args.size)
if os.path.exists(base + ".raw") and os.path.exists(base + ".txt"):
    print("bluntfin_volume: %s.raw exists" % base)
    sys.exit(0)

LoadPlugin(args.plugin, remote=False, ns=globals())
index = blunt_fin_index(globals(), args.data, SamplingDimensions=[args.size] * 3)
index.UpdatePipeline()
grid = servermanager.Fetch(index)
n1 = grid.GetPointData().GetArray("n_minus_1")
if n1 is None or n1.GetNumberOfTuples() != args.size ** 3:
    sys.exit("bluntfin_volume: no n_minus_1 on a %d^3 grid" % args.size)
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

vtk_to_numpy(n1).astype("<f4").tofile(base + ".raw")
with open(base + ".txt", "w") as f:
    f.write("dims %d %d %d\n" % grid.GetDimensions())
    f.write("origin %.17g %.17g %.17g\n" % grid.GetOrigin())
    f.write("spacing %.17g %.17g %.17g\n" % grid.GetSpacing())
print("bluntfin_volume: wrote %s.raw (%d^3, n - 1 %.4g..%.4g)" % (base, args.size, *n1.GetRange()))
