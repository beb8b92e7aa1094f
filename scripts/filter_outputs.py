# SPDX-License-Identifier: BSD-3-Clause
"""Every point, cell and field array of RefractiveScene, RefractiveIndex and RefractionOctree on
20 pipelines, for a bit-exact before/after comparison of a change that must not change numbers
(a refactoring): scenes with a body, every model family, an image, a clipped unstructured grid with
the three AmbientModes, SolidArray, a Body surface, Planar and Axisymmetric, the octree, and
disk_out_ref.ex2 from ../shared/data (or $SCHLIEREN_DATA; left out where absent).

    pvbatch scripts/filter_outputs.py --plugin <Schlieren.so> --output before
    mpiexec -n 2 pvbatch --mpi --symmetric scripts/filter_outputs.py --plugin <Schlieren.so> --output before2
    (build the change, the same with --output after / after2)
    /usr/bin/python3 scripts/filter_outputs.py --compare before.r0.npz after.r0.npz

Each rank writes its own piece (<output>.r<rank>.npz); --compare prints the arrays that differ in
shape, type or any bit, and exits 1 where one does.
"""
import os
import sys

import numpy as np


def argument(name):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else None


if argument("--compare"):
    a, b = np.load(argument("--compare")), np.load(sys.argv[sys.argv.index("--compare") + 2])
    bad = 0
    for k in sorted(set(a.files) | set(b.files)):
        if k not in a.files or k not in b.files:
            print("only in %s: %s" % ("the first" if k in a.files else "the second", k))
            bad += 1
            continue
        x, y = a[k], b[k]
        if x.shape != y.shape or x.dtype != y.dtype or not np.array_equal(x, y, equal_nan=x.dtype.kind == "f"):
            print("differs: %s %s %s / %s %s" % (k, x.shape, x.dtype, y.shape, y.dtype))
            bad += 1
    print("%d arrays, %d differ" % (len(a.files), bad))
    sys.exit(1 if bad else 0)

from paraview.simple import *  # noqa: E402,F401,F403
from paraview import servermanager as sm  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkParallelCore import vtkMultiProcessController  # noqa: E402

LoadPlugin(argument("--plugin") or os.environ["SCHLIEREN_PLUGIN"], remote=False, ns=globals())
out = argument("--output")
ranks = sm.ActiveConnection.GetNumberOfDataPartitions()
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
record = {}


def grab(name, proxy):
    """Every array of proxy's output on this rank, under name/p|c|f/<array>."""
    proxy.UpdatePipeline()
    d = proxy.GetClientSideObject().GetOutputDataObject(0)
    if d is None:
        record[name + "/none"] = np.array(1)
        return
    record[name + "/npts"] = np.array(d.GetNumberOfPoints())
    if hasattr(d, "GetExtent"):
        record[name + "/extent"] = np.array(d.GetExtent())
        record[name + "/origin"] = np.array(d.GetOrigin())
        record[name + "/spacing"] = np.array(d.GetSpacing())
    for attributes, tag in ((d.GetPointData(), "p"), (d.GetCellData(), "c")):
        for i in range(attributes.GetNumberOfArrays()):
            a = attributes.GetArray(i)
            if a is not None:
                record["%s/%s/%s" % (name, tag, a.GetName())] = vtk_to_numpy(a).copy()
    fd = d.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        record["%s/f/%s" % (name, a.GetName())] = np.array(
            [str(a.GetVariantValue(j).ToString()) for j in range(a.GetNumberOfValues())])


def case(name, make):
    try:
        grab(name, make())
    except Exception as e:  # recorded, so that a change of behaviour shows
        record[name + "/exception"] = np.array(str(e))


def index(source, model, array=None, **properties):
    r = RefractiveIndex(Input=source, Model=model, **properties)
    if array:
        r.InputArray = ["POINTS", array]
    return r


gs = RefractiveScene(Scene="GaussianSphere", Dimensions=[33, 29, 31], Body="Sphere", BodyRadius=0.2,
                     BodyCenter=[0.4, 0.1, 0])
gd = index(gs, "GladstoneDale", "density")
pl = RefractiveScene(Scene="HeliumPlume", Dimensions=[25, 27, 23])
wv = Wavelet(WholeExtent=[-10, 10, -9, 9, -8, 8])
cl = Clip(Input=wv)
cl.ClipType = "Sphere"
cl.ClipType.Radius = 8.0
cl.Invert = 1
flat = Wavelet(WholeExtent=[-10, 10, -9, 9, 0, 0])
body = Sphere(Radius=0.2, Center=[-0.5, -0.3, 0.1], ThetaResolution=24, PhiResolution=24)


def mixture():
    r = index(pl, "GladstoneDaleMixture", "density", MixtureComposition="MixtureFraction")
    r.MixtureFractionArray = ["POINTS", "mixture_fraction"]
    return r


case("scene_gs", lambda: gs)
case("gd", lambda: gd)
case("oct_gd", lambda: RefractionOctree(Input=gd))
case("oct_gd_tol", lambda: RefractionOctree(Input=gd, Tolerance=1e-6, MaxLevel=3))
case("pass_body", lambda: index(gs, "Passthrough", "n_minus_1", Body=body))
case("solidarray_img", lambda: index(gs, "Passthrough", "n_minus_1", SolidArray="density", BodyFromGrid=0))
case("scene_plume", lambda: pl)
case("mix", mixture)
case("auto_plume", lambda: RefractiveIndex(Input=pl))
case("scene_blast", lambda: RefractiveScene(Scene="BlastWave", Dimensions=[21, 21, 21], TimeSteps=3))
for mode in ("Extend", "DomainEdgeMedian", "Value"):
    case("clip_" + mode, lambda: index(cl, "GladstoneDale", "RTData", DensityReference=1e-3, AmbientMode=mode,
                                       AutomaticDimension=24))
case("solidarray_clip", lambda: index(cl, "GladstoneDale", "RTData", DensityReference=1e-3, AutomaticDimension=20,
                                      SolidArray="RTData"))
case("wavelet_img", lambda: index(wv, "GladstoneDale", "RTData", DensityReference=1e-3))
case("oct_wavelet", lambda: RefractionOctree(Input=index(wv, "GladstoneDale", "RTData", DensityReference=1e-3)))
case("planar", lambda: index(flat, "GladstoneDale", "RTData", DensityReference=1e-3, Symmetry="Planar", Span=0.5))
case("axi", lambda: index(flat, "GladstoneDale", "RTData", DensityReference=1e-3, Symmetry="Axisymmetric",
                          Span=0.5))
here = os.path.dirname(os.path.abspath(__file__))
data = os.environ.get("SCHLIEREN_DATA", os.path.join(here, "..", "..", "shared", "data"))
if os.path.exists(os.path.join(data, "disk_out_ref.ex2")):
    disk = OpenDataFile(os.path.join(data, "disk_out_ref.ex2"))

    def ideal_gas():
        r = RefractiveIndex(Input=disk, Model="IdealGas", AutomaticDimension=28)
        r.TemperatureArray = ["POINTS", "Temp"]
        r.PressureArray = ["POINTS", "Pres"]
        return r

    case("disk_ideal", ideal_gas)
    case("disk_auto", lambda: RefractiveIndex(Input=disk, AutomaticDimension=20))
else:
    print("no disk_out_ref.ex2 in %s: its two cases are left out" % data)
np.savez(out + ".r%d.npz" % rank, **record)
print("rank %d of %d: %d arrays written to %s.r%d.npz" % (rank, ranks, len(record), out, rank))
