# SPDX-License-Identifier: BSD-3-Clause
"""What a solid body costs: the blunt fin traced with and without its fin as a body (a table).

    pvpython bodies.py --plugin Schlieren.so [--data DIR] [--passes 4]

The chain is Examples/bluntfin.py's (blunt_fin_index, 160 points along x, BodyWallFaces 0 1 1 0 1 1),
looking down on the plate (800 x 400 film); each row is traced once to warm up (kernel build,
Auto's pilot) and once more with another seed, timed. Prints seconds, samples, the rays the fin
stopped and what Auto chose. Exit status 125 (and a SKIP line) when the data is absent.
"""
import argparse
import os
import sys
import time

from paraview.simple import Delete, LoadPlugin, servermanager

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples"))
from bluntfin import blunt_fin_index  # noqa: E402
DEFAULT_DATA = os.environ.get("SCHLIEREN_DATA") or os.path.join(HERE, "..", "..", "..", "shared", "data")

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--plugin", required=True)
ap.add_argument("--data", default=DEFAULT_DATA)
ap.add_argument("--passes", type=int, default=4)
args = ap.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
rows = []
for body in (1, 0):
    index = blunt_fin_index(globals(), args.data, AutomaticDimension=160)
    if index is None:
        print("bodies: SKIP, no blunt-fin data in %s (set SCHLIEREN_DATA)" % os.path.abspath(args.data))
        sys.exit(125)
    index.BodyFromGrid = body
    index.UpdatePipeline()
    for backend in ("OpenCL", "CPU"):
        for integrator in ("Midpoint", "Auto"):
            image = SchlierenImage(Input=index, Cutoff="KnifeEdge", Passes=args.passes,  # noqa: F821
                                   ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], Resolution=[800, 400],
                                   Backend=backend, Integrator=integrator, StepSize=1.0)
            image.UpdatePipeline()
            image.Seed = 2
            t0 = time.time()
            image.UpdatePipeline()
            seconds = time.time() - t0
            fd = servermanager.Fetch(image).GetFieldData()
            rows.append((body, backend, integrator, seconds, fd.GetArray("samples").GetValue(0),
                         fd.GetArray("blocked_rays").GetValue(0), fd.GetAbstractArray("integrator").GetValue(0),
                         fd.GetArray("step_size").GetValue(0)))
            Delete(image)
print("| body | backend | integrator | seconds | samples | rays stopped | traced with |")
print("|---|---|---|---|---|---|---|")
for r in rows:
    print("| %s | %s | %s | %.3f | %.4g | %.0f | %s at %g voxel |" % (("yes" if r[0] else "no",) + r[1:]))
