# SPDX-License-Identifier: BSD-3-Clause
"""Every output of SchlierenImage over a dozen settings, saved to compare two builds bit for bit
(a refactoring must not change a number). Not a test: a tool for "the same numbers before and
after".

Write (one process, or rank 0 under MPI):
  pvpython snapshot_images.py --plugin <Schlieren.so> --out A.npz
  mpiexec -n 2 pvbatch --mpi snapshot_images.py --plugin <Schlieren.so> --out B.npz
Compare (any Python 3 with NumPy):
  /usr/bin/python3 snapshot_images.py --compare A.npz B.npz
prints every array or field datum that differs (Auto's report carries the pilot's time in ms,
which differs from run to run) and exits 1 if any other does.

The settings: knife edge at an angle (then Passes 2 -> 5, then a camera move), Integrator Auto,
Reconstruction Auto and Cubic, colour filter with a Gaussian filter, interferometry, BOS,
shadowgraph with the error estimate and a cone filter, Backend CPU, no octree, a solid body.
"""
import os
import sys


def compare(path_a, path_b):
    import numpy as np
    a = np.load(path_a)
    b = np.load(path_b)
    ka, kb = set(a.files), set(b.files)
    bad = 0
    for k in sorted(ka ^ kb):
        print("only in", path_a if k in ka else path_b, k)
        bad += 1
    for k in sorted(ka & kb):
        x, y = a[k], b[k]
        if x.dtype.kind in "fiu":
            if x.shape != y.shape or not np.array_equal(x, y, equal_nan=True):
                d = np.max(np.abs(x.astype(float) - y.astype(float))) if x.shape == y.shape else "shape"
                print("DIFF", k, "max |difference|", d)
                bad += 1
        elif str(x) != str(y):
            print("DIFF", k, repr(str(x))[:300], "|", repr(str(y))[:300])
            if not k.endswith("/@auto_report"):
                bad += 1
    print("%d keys compared; %d differ (not counting Auto's report)" % (len(ka & kb), bad))
    return 1 if bad else 0


if "--compare" in sys.argv:
    i = sys.argv.index("--compare")
    sys.exit(compare(sys.argv[i + 1], sys.argv[i + 2]))

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402
from paraview.simple import *  # noqa: F401,F403,E402
from paraview import servermanager as sm  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

import schlieren_testing as st  # noqa: E402

st.load_plugin(globals())
out = st.argument("--out", "schlieren_snapshot.npz")
res = {}


def grab(tag, proxy):
    """Every point array and field datum of the proxy's output, under `tag/`."""
    d = sm.Fetch(proxy)
    pd = d.GetPointData()
    for i in range(pd.GetNumberOfArrays()):
        a = pd.GetArray(i)
        res[tag + "/" + a.GetName()] = vtk_to_numpy(a).copy()
    fd = d.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        v = a.GetValue(0)
        res[tag + "/@" + a.GetName()] = np.array(str(v) if isinstance(v, str) else float(v))


scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[40, 36, 32], Amplitude=1e-4, Width=0.3,
                        Center=[0.1, -0.05, 0.02])
index = RefractiveIndex(Input=scene, Model="Passthrough")
octree = RefractionOctree(Input=index)
common = dict(Resolution=[40, 32], Passes=2, Seed=3, ViewDirection=[0.3, -0.2, -1.0])
cfgs = {
    "knife": dict(Cutoff="KnifeEdge", KnifeAngle=30.0),
    "auto": dict(Integrator="Auto"),
    "reconauto": dict(Reconstruction="Auto", Tolerance=1e-6),
    "cubic": dict(Reconstruction="Cubic", Integrator="RK4", StepSize=2.0),
    "color": dict(Cutoff="ColorFilter", Filter="Gaussian"),
    "interf": dict(Cutoff="Interferometry", ReferenceTilt=3.0),
    "bos": dict(Cutoff="BOS"),
    "shadow": dict(Cutoff="Shadowgraph", FilmDistance=2.0, EstimateError=1, Filter="Cone"),
    "cpu": dict(Backend="CPU", Integrator="Midpoint"),
}
for tag, kw in cfgs.items():
    kw2 = dict(common, **kw)
    img = SchlierenImage(Input=octree, **kw2)
    grab(tag, img)
    if tag == "knife":
        img.Passes = 5
        grab("knife_more", img)
        img.ViewDirection = [0, 0, -1]
        grab("knife_view", img)
    Delete(img)
noct = SchlierenImage(Input=index, **common)
grab("nooctree", noct)
body = RefractiveScene(Scene="GaussianSphere", Dimensions=[40, 36, 32], Amplitude=1e-4, Width=0.3,
                       Body="Sphere", BodyRadius=0.2)
bimg = SchlierenImage(Input=body, **common)
grab("solid", bimg)
if sm.vtkProcessModule.GetProcessModule().GetPartitionId() == 0:
    np.savez(out, **res)
    print("wrote", out, len(res))
