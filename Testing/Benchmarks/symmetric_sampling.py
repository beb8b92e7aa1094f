"""RefractiveIndex's symmetric sampling: the engine's points mode (schlieren_sample_cells_at, what
both front ends run now) against the vtkCompositeDataProbeFilter with a vtkStaticCellLocator that
both ran before, on the suite's symmetric inputs, in whichever VTK runs it:

    pvpython Testing/Benchmarks/symmetric_sampling.py [--openfoam build/openfoam]
    build/python-venvs/vtk-newest/bin/python Testing/Benchmarks/symmetric_sampling.py ...

(SCHLIEREN_ENGINE_LIBRARY=build/OpenCL/libschlieren_engine.so where the package does not find
it.) The inputs: the parity matrix's 2D image, its unstructured copy, the cone's r-z half plane
and the structured 5 degree wedge (Testing/Python/frontend_matrix.py), test_symmetry.py's quads
and triangles, and the OpenFOAM wedge and forward step (openfoam_cases.py's, where solved), each
at the points the engine's plan samples (schlieren_symmetry_samples) for the matrix's settings;
and blocks of images (two halves of a Gaussian) on an image grid, the engine's grid mode against
the probe on that grid (Symmetry None: the other path the probe had).
Per case: the samples, those found by one sampler only, the seconds each took (one run; the
blocks of images: both together), and for every array both give the
largest difference where both found the point (absolute, and relative to the array's range) and
how many points differ at all. A point found by one only is said with its distance (in the
nearest cell's parametric coordinates) from the cells' faces.
"""
import argparse
import os
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "Python"))
sys.path.insert(0, os.path.join(here, "..", "..", "Python"))

import numpy as np  # noqa: E402
from vtkmodules.util import numpy_support  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints, vtkVersion  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkStaticCellLocator  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkCompositeDataProbeFilter  # noqa: E402

import frontend_matrix as matrix  # noqa: E402
from schlieren import _engine, algorithms  # noqa: E402


def probe(data, points):
    """The old sampler (both front ends' before): the arrays {name: values} and the mask."""
    p = vtkPoints()
    p.SetDataTypeToDouble()
    p.SetData(numpy_support.numpy_to_vtk(np.ascontiguousarray(points, np.float64), deep=1))
    samples = vtkPolyData()
    samples.SetPoints(p)
    f = vtkCompositeDataProbeFilter()
    f.SetInputData(samples)
    f.SetSourceData(data)
    f.SetValidPointMaskArrayName("vtkValidPointMask")
    (f.SetCellLocator if hasattr(f, "SetCellLocator") else f.SetCellLocatorPrototype)(
        vtkStaticCellLocator())
    f.Update()
    pd = f.GetOutput().GetPointData()
    out = {pd.GetArrayName(i): numpy_support.vtk_to_numpy(pd.GetArray(i))
           for i in range(pd.GetNumberOfArrays()) if pd.GetArray(i) is not None}
    return out, out.pop("vtkValidPointMask") != 0


def openfoam(folder, case, time_value):
    from vtkmodules.vtkIOGeometry import vtkOpenFOAMReader
    foam = os.path.join(folder, case, "case.foam")
    if not os.path.exists(foam):
        return None
    r = vtkOpenFOAMReader()
    r.SetFileName(foam)
    r.SkipZeroTimeOff()
    if hasattr(r, "DecomposePolyhedraOn"):  # (VTK 9.7 has no switch: it decomposes)
        r.DecomposePolyhedraOn()
    r.UpdateInformation()
    r.DisableAllCellArrays()
    for name in ("T", "p"):
        r.SetCellArrayStatus(name, 1)
    r.UpdateTimeStep(time_value)
    return r.GetOutput()


def planes():
    """test_symmetry.py's quads (an r-x half plane) and triangles (a plane at z = 0.3)."""
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter
    from vtkmodules.vtkFiltersSources import vtkPlaneSource
    out = {}
    for name, origin, p1, p2, res, tri in (
            ("quads", (-1.0, 0.0, 0.0), (1.0, 0.0, 0.0), (-1.0, 0.6, 0.0), (200, 60), False),
            ("triangles", (-0.48, -0.36, 0.3), (0.48, -0.36, 0.3), (-0.48, 0.36, 0.3), (96, 72),
             True)):
        s = vtkPlaneSource()
        s.SetOrigin(*origin)
        s.SetPoint1(*p1)
        s.SetPoint2(*p2)
        s.SetResolution(*res)
        s.Update()
        data = s.GetOutput()
        if tri:
            t = vtkTriangleFilter()
            t.SetInputData(data)
            t.Update()
            data = t.GetOutput()
        x = numpy_support.vtk_to_numpy(data.GetPoints().GetData())
        v = numpy_support.numpy_to_vtk(np.exp(-(x[:, 0] ** 2 + 4 * x[:, 1] ** 2)) * 1e-4, deep=1)
        v.SetName("n_minus_1")
        d = vtkPolyData()
        d.ShallowCopy(data)
        d.GetPointData().Initialize()
        d.GetPointData().AddArray(v)
        out[name] = d
    return out


def image_blocks():
    """Blocks of images (Symmetry None: the engine's grid mode, where the probe ran before): a
    Gaussian on 33 x 25 x 17 points cut into two images that share the plane x = 0, sampled onto
    RefractiveIndex's automatic grid over them (every grid point off the blocks' points)."""
    from vtkmodules.vtkCommonDataModel import vtkImageData, vtkMultiBlockDataSet
    blocks = vtkMultiBlockDataSet()
    for b, (i0, i1) in enumerate(((-16, 0), (0, 16))):
        g = vtkImageData()
        g.SetExtent(i0, i1, -12, 12, -8, 8)
        g.SetSpacing(0.03, 0.03, 0.03)
        x = np.array([g.GetPoint(k) for k in range(g.GetNumberOfPoints())])
        v = numpy_support.numpy_to_vtk(np.exp(-(x ** 2).sum(axis=1) / 0.04).astype(np.float32),
                                       deep=1)
        v.SetName("density")
        g.GetPointData().AddArray(v)
        blocks.SetBlock(b, g)
    return blocks


def grid_mode(blocks):
    """The engine's grid mode against the probe on the structure: (new, old) as main's rows."""
    grid = algorithms.RefractiveIndex(AutomaticDimension=61)._sampling_grid(blocks)
    image, found = algorithms._sample_cells(blocks, grid["dims"], grid["origin"], grid["spacing"])
    from vtkmodules.vtkCommonDataModel import vtkImageData
    structure = vtkImageData()
    structure.CopyStructure(image)
    f = vtkCompositeDataProbeFilter()
    f.SetInputData(structure)
    f.SetSourceData(blocks)
    f.SetValidPointMaskArrayName("vtkValidPointMask")
    f.Update()
    pd = f.GetOutput().GetPointData()
    old = {pd.GetArrayName(i): numpy_support.vtk_to_numpy(pd.GetArray(i))
           for i in range(pd.GetNumberOfArrays())}
    new = [(n, image.GetPointData().GetArray(n)) for n in ("density",)]
    return structure.GetNumberOfPoints(), new, found, old, old.pop("vtkValidPointMask") != 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--openfoam", default="build/openfoam")
    a = ap.parse_args()
    inputs = {"plane": (matrix._plane((0, 16, 0, 12, 0, 0), False), dict(Symmetry="Planar",
                                                                         Span=0.6)),
              "plane_unstructured": (matrix._unstructured(matrix._plane((0, 16, 0, 12, 0, 0),
                                                                        False)),
                                     dict(Symmetry="Planar", Span=0.6, AutomaticDimension=32)),
              "cone": (matrix._unstructured(matrix._plane((0, 20, 0, 10, 0, 0), True)),
                       dict(Symmetry="Axisymmetric", SymmetryAxis="X", AutomaticDimension=32)),
              "wedge": (matrix._wedge(), dict(Symmetry="Axisymmetric", AutomaticDimension=28))}
    p = planes()
    inputs["quads"] = (p["quads"], dict(Symmetry="Axisymmetric", SymmetryAxis="X",
                                        SamplingDimensions=[81, 49, 49]))
    inputs["triangles"] = (p["triangles"], dict(Symmetry="Planar", Span=0.5,
                                                AutomaticDimension=97))
    for name, case, t, props in (
            ("openfoam_wedge", "LadenburgJet60psi", 0.0,
             dict(Symmetry="Axisymmetric", SamplingDimensions=[64, 24, 24])),
            ("openfoam_forward_step", "forwardStep", 2.0,
             dict(Symmetry="Planar", Span=0.1, SamplingDimensions=[96, 32, 3])),
            ("openfoam_biconic", "biconic25-55Run35", 0.0,
             dict(Symmetry="Axisymmetric", SamplingDimensions=[200, 100, 100]))):
        data = openfoam(a.openfoam, case, t)
        if data is None:
            print("%s: no %s in %s (run openfoam_cases.py)" % (name, case, a.openfoam))
        else:
            inputs[name] = (data, props)
    print("VTK %s; the engine's points mode against vtkCompositeDataProbeFilter (static cell "
          "locator)" % vtkVersion.GetVTKVersion())
    print("%-22s %7s %9s %9s %8s %8s  %s" % (
        "case", "samples", "new only", "old only", "probe s", "engine s",
        "array: max |diff| (of its range), points differing"))
    inputs["image_blocks"] = (image_blocks(), None)
    for name, (data, props) in inputs.items():
        if props is None:
            t0 = time.perf_counter()
            count, arrays, found, old, old_found = grid_mode(data)
            seconds = (float("nan"), time.perf_counter() - t0)  # (both, together)
            points = np.zeros((count, 3))
        else:
            ri = algorithms.RefractiveIndex(**props)
            plan = ri._symmetry_plan(data)
            mesh = algorithms._internal_mesh(data)
            points, _ = _engine.symmetry_samples(plan)
            t0 = time.perf_counter()
            old, old_found = probe(mesh, points)
            t1 = time.perf_counter()
            arrays, found = algorithms._sample_cells_at(mesh, points)
            seconds = (t1 - t0, time.perf_counter() - t1)
        new_found = found != 0
        both = new_found & old_found
        parts = []
        for array_name, arr in arrays:
            if array_name not in old:
                parts.append("%s: not in the probe's" % array_name)
                continue
            n = numpy_support.vtk_to_numpy(arr).astype(np.float64).reshape(len(points), -1)
            o = old[array_name].astype(np.float64).reshape(len(points), -1)
            d = np.abs(n - o)[both]
            span = float(np.ptp(o[both])) if both.any() else 0.0
            worst = float(d.max()) if d.size else 0.0
            parts.append("%s: %.3g (%.3g), %d" % (array_name, worst, worst / span if span else 0.0,
                                                   int((d.max(axis=1) > 0).sum()) if d.size else 0))
        print("%-22s %7d %9d %9d %8.3f %8.3f  %s" % (
            name, len(points), int((new_found & ~old_found).sum()),
            int((old_found & ~new_found).sum()), seconds[0], seconds[1], "; ".join(parts)))
        for k in np.nonzero(new_found != old_found)[0][:3]:
            print("    sample %d at %s: found by the %s sampler only" % (
                k, np.array2string(points[k], precision=9),
                "new" if new_found[k] else "old"))


if __name__ == "__main__":
    main()
