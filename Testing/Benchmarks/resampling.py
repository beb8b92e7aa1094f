"""RefractiveIndex's resampling of a large unstructured grid beside ParaView's ResampleToImage.

    pvpython Testing/Benchmarks/resampling.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        [--extent 25] [--dims 100] [--repeats 2] [--no-probe]

(--extent 63: 1.0e7 tetrahedra, the size of the issue's large unstructured results; --no-probe
leaves out the old probe's row, which at that size only repeats what the smaller grids show.)

The grid: vtkRTAnalyticSource (the Wavelet) over [-e, e]^3 cells, tetrahedralized (vtkDataSetTriangleFilter:
5 tetrahedra per hexahedron), with density = RTData / 200. Both filters resample it onto the same
dims^3 image over its bounds; the table gives the seconds (best of --repeats) and input cells per
second, and checks that the two resampled densities agree (the largest difference, relative to
the range). RefractiveIndex's time includes n - 1 and its gradient (what a user waits for); the probe row is
the vtkCompositeDataProbeFilter RefractiveIndex ran before it sampled cell by cell, alone.

    pvpython Testing/Benchmarks/resampling.py --plugin ... --cases [--data ../shared/data]
        [--openfoam build/openfoam] [--dims 96 64 48] [--repeats 3]

--cases: the suite's meshes as the readers give them (the blunt fin's PLOT3D multiblock, the
combustor's, disk_out_ref.ex2's Exodus multiblock, the OpenFOAM cases' multiblocks when
openfoam_cases.py has made them), each sampled onto the grid RefractiveIndex makes for them by what
each front end ran before (the C++ filter: vtkCompositeDataProbeFilter for a multiblock; the Python
front end: vtkResampleToImage) and by the engine's cell sampler that both run now
(schlieren_sample_cells, through the Python front end's adapter; the C++ adapter gives the same
bits). Seconds are the best of --repeats, the three taken in turn; the differences are the largest
of every sampled point array where both found the point, relative to the array's range, and the
points found by one and not the other.
"""
import argparse
import os
import time

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy


def best(proxy, repeats, touch):
    times = []
    for _ in range(repeats):
        touch()
        t0 = time.perf_counter()
        proxy.UpdatePipeline()
        times.append(time.perf_counter() - t0)
    return min(times)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plugin", required=True)
    ap.add_argument("--extent", type=int, default=25)
    ap.add_argument("--dims", type=int, default=100)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--no-probe", action="store_true", help="leave out the probe's row")
    a = ap.parse_args()
    LoadPlugin(a.plugin, remote=False, ns=globals())
    e = a.extent
    wavelet = Wavelet(WholeExtent=[-e, e] * 3)
    tets = Tetrahedralize(Input=wavelet)
    dens = Calculator(Input=tets, ResultArrayName="density", Function="RTData/200")
    t0 = time.perf_counter()
    dens.UpdatePipeline()
    t_make = time.perf_counter() - t0
    cells = dens.GetDataInformation().GetNumberOfCells()
    d = [a.dims] * 3
    ours = RefractiveIndex(Input=dens, Model="GladstoneDale", SamplingDimensions=d)
    theirs = ResampleToImage(Input=dens, SamplingDimensions=d, UseInputBounds=1)

    def touch(proxy):
        def again():  # execute again, input unchanged (the proxy too must be told: else its
            proxy.GetClientSideObject().Modified()  # UpdatePipeline does nothing, 0.00 s)
            proxy.SMProxy.MarkModified(proxy.SMProxy)
        return again

    # the probe RefractiveIndex ran before it sampled cell by cell (vtkCompositeDataProbeFilter)
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkFiltersCore import vtkCompositeDataProbeFilter
    mesh = dens.GetClientSideObject().GetOutputDataObject(0)
    b = mesh.GetBounds()
    structure = vtkImageData()
    structure.SetDimensions(*d)
    structure.SetOrigin(*[b[2 * i] + 0.5e-6 * (b[2 * i + 1] - b[2 * i]) for i in range(3)])
    structure.SetSpacing(*[(b[2 * i + 1] - b[2 * i]) * (1 - 1e-6) / (a.dims - 1) for i in range(3)])
    probe = vtkCompositeDataProbeFilter()
    probe.SetInputData(structure)
    probe.SetSourceData(mesh)
    t_probe = []
    for _ in range(0 if a.no_probe else a.repeats):
        probe.Modified()
        t0 = time.perf_counter()
        probe.Update()
        t_probe.append(time.perf_counter() - t0)
    t_probe = min(t_probe) if t_probe else None
    t_theirs = best(theirs, a.repeats, touch(theirs))
    t_ours = best(ours, a.repeats, touch(ours))
    r = theirs.GetClientSideObject().GetOutputDataObject(0)
    rho_theirs = vtk_to_numpy(r.GetPointData().GetArray("density")).astype(float)
    mask = vtk_to_numpy(r.GetPointData().GetArray("vtkValidPointMask")) != 0
    o = ours.GetClientSideObject().GetOutputDataObject(0)
    n1 = vtk_to_numpy(o.GetPointData().GetArray("n_minus_1")).astype(float)
    # n - 1 = K rho (Gladstone-Dale): compare rho via the ratio on valid points
    K = np.median(n1[mask] / rho_theirs[mask])
    diff = np.abs(n1[mask] / K - rho_theirs[mask]).max() / np.ptp(rho_theirs[mask])
    load = os.getloadavg()
    import resource
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0 ** 2
    print("grid: %d tetrahedra (Wavelet %d^3 cells, made in %.1f s), output %d^3 points; load %.1f %.1f %.1f "
          "(shared machine); peak memory of the process %.1f GiB"
          % (cells, 2 * e, t_make, a.dims, load[0], load[1], load[2], peak))
    print("| filter | seconds | input cells/s | output points/s |")
    print("|---|---|---|---|")
    for name, t in (("ResampleToImage (ParaView)", t_theirs),
                    ("vtkCompositeDataProbeFilter (RefractiveIndex's resampling before)", t_probe),
                    ("RefractiveIndex (cell by cell, with n - 1 and grad n)", t_ours)):
        if t is None:
            continue
        print("| %s | %.2f | %.3g | %.3g |" % (name, t, cells / t, a.dims ** 3 / t))
    print("RefractiveIndex / ResampleToImage time: %.2f; largest density difference %.2g of its range"
          % (t_ours / t_theirs, diff))


def cases_main(a):
    import sys
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.join(here, "..", "..", "Python"))
    from paraview import servermanager as sm
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkFiltersCore import vtkCompositeDataProbeFilter, vtkResampleToImage
    from schlieren import algorithms
    LoadPlugin(a.plugin, remote=False, ns=globals())
    D, F = a.data, a.openfoam
    readers = [("blunt fin (PLOT3D)", lambda: PLOT3DReader(FileName=D + "/bluntfinxyz.bin",
                                                           QFileName=[D + "/bluntfinq.bin"])),
               ("combustor (PLOT3D)", lambda: PLOT3DReader(FileName=D + "/combxyz.bin",
                                                           QFileName=[D + "/combq.bin"])),
               ("disk_out_ref.ex2", lambda: ExodusIIReader(FileName=D + "/disk_out_ref.ex2"))]
    for c in ("wedge15Ma5", "forwardStep"):
        if os.path.exists(os.path.join(F, c, "case.foam")):
            readers.append(("OpenFOAM " + c, lambda c=c: OpenFOAMReader(
                FileName=os.path.join(F, c, "case.foam"))))
    load = os.getloadavg()
    print("grid %s points; best of %d, taken in turn; load %.1f %.1f %.1f (shared machine)"
          % ("x".join(str(d) for d in a.grid), a.repeats, load[0], load[1], load[2]))
    print("| mesh | cells | probe (C++ before) s | ResampleToImage (Python before) s | engine s | "
          "probe / engine | ResampleToImage / engine | largest difference vs probe | vs "
          "ResampleToImage |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label, make in readers:
        if not os.path.exists(D) and "OpenFOAM" not in label:
            continue
        r = make()
        times = r.TimestepValues
        t = max(times) if isinstance(times, (list, tuple)) and times else 0.0
        r.UpdatePipeline(t)
        mesh = sm.Fetch(r)
        box = algorithms._engine.sampling_box({"UseSamplingBounds": 0},
                                              algorithms._leaf_bounds(mesh))
        d = list(a.grid)
        structure = vtkImageData()
        structure.SetDimensions(*d)
        structure.SetOrigin(box[0], box[2], box[4])
        structure.SetSpacing(*[(box[2 * i + 1] - box[2 * i]) / (d[i] - 1) for i in range(3)])
        probe = vtkCompositeDataProbeFilter()
        probe.SetInputData(structure)
        probe.SetSourceData(mesh)
        rti = vtkResampleToImage()
        rti.SetInputDataObject(mesh)
        rti.SetUseInputBounds(0)
        rti.SetSamplingBounds(*box)
        rti.SetSamplingDimensions(*d)
        best = {"probe": 1e30, "rti": 1e30, "engine": 1e30}
        for _ in range(a.repeats):
            for key in ("probe", "rti", "engine"):
                t0 = time.perf_counter()
                if key == "probe":
                    probe.Modified()
                    probe.Update()
                elif key == "rti":
                    rti.Modified()
                    rti.Update()
                else:
                    ours, found = algorithms._sample_cells(
                        mesh, d, [box[0], box[2], box[4]],
                        [(box[2 * i + 1] - box[2 * i]) / (d[i] - 1) for i in range(3)])
                best[key] = min(best[key], time.perf_counter() - t0)
        diffs = []
        for theirs in (probe.GetOutput(), rti.GetOutput()):
            pd = theirs.GetPointData()
            mask = vtk_to_numpy(pd.GetArray("vtkValidPointMask")) != 0
            worst, worst_name = 0.0, ""
            for i in range(ours.GetPointData().GetNumberOfArrays()):
                name = ours.GetPointData().GetArrayName(i)
                b = pd.GetArray(name)
                if b is None:
                    continue
                x = vtk_to_numpy(ours.GetPointData().GetArray(i)).astype(float)
                y = vtk_to_numpy(b).astype(float)
                both = mask & (found != 0)
                if x.shape != y.shape or not both.any():
                    continue
                span = np.ptp(y[both]) or 1.0
                dd = np.abs(x[both] - y[both]).max() / span
                if dd >= worst:
                    worst, worst_name = dd, name
            diffs.append("%.2g (%s); %d points found by one only"
                         % (worst, worst_name, int(np.count_nonzero(mask != (found != 0)))))
        print("| %s | %d | %.3f | %.3f | %.3f | %.1f | %.1f | %s | %s |"
              % (label, mesh.GetNumberOfCells(), best["probe"], best["rti"], best["engine"],
                 best["probe"] / best["engine"], best["rti"] / best["engine"], diffs[0], diffs[1]))
        Delete(r)


if __name__ == "__main__":
    import sys
    if "--cases" in sys.argv:
        ap = argparse.ArgumentParser()
        ap.add_argument("--plugin", required=True)
        ap.add_argument("--cases", action="store_true")
        ap.add_argument("--data", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                       "..", "..", "..", "shared", "data"))
        ap.add_argument("--openfoam", default="build/openfoam")
        ap.add_argument("--grid", type=int, nargs=3, default=[96, 64, 48])
        ap.add_argument("--repeats", type=int, default=3)
        cases_main(ap.parse_args())
    else:
        main()
