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
        return lambda: proxy.GetClientSideObject().Modified()  # execute again, input unchanged

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


if __name__ == "__main__":
    main()
