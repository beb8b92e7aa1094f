# SPDX-License-Identifier: BSD-3-Clause
"""RefractiveIndex's parity matrix (frontend_cases.INDEX) through the three front ends: its inputs,
what a leg records of RefractiveIndex's output and of SchlierenImage's film on it, and the
comparison with the C++ plugin's record. Plain VTK only (ParaView's in pvpython, PyPI's in a venv):

  - frontend_reference.py (pvpython, the C++ plugin's proxies) builds the inputs (make_inputs),
    writes each as a VTK XML file (write_input) and records the C++ plugin's outputs
    (DIR/index_<case>.npz);
  - test_frontend.py (a venv with PyPI's vtk, the package's algorithms) and
    test_python_plugin_parity.py (pvpython, the Python plugin's proxies) read the same files
    (read_input), run the case's pipeline and compare their record with the C++ plugin's
    (compare): the image grid, every point array (names, order, bits), the field data (names,
    order, values) and the film on it (every image array bit for bit, the whole field data).

Known differences of the Python front end's RefractiveIndex (algorithms.py), said on every case
where they show but not failed (that class is being rewritten on other branches; fixing these is
theirs, see INDEX_KNOWN):
  - its field data lacks `index_notes` where the C++ filter's notes are not the engine's yet
    (Model Automatic's choice, the wedge found; an AMR input's are); the per-time-step cache
    report (INDEX_FIELDS_LEFT_OUT) is left out of both records (its budget is the process's
    memory);
  - its point arrays end n_minus_1, grad_n where the C++ filter's end grad_n, n_minus_1 (an input
    without n_minus_1: the C++ filter adds grad_n, then sets n_minus_1 as the scalars).
Every other array, name and value is compared, and a difference fails."""
import json
import os

import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkStructuredGrid

import frontend_cases as cases

INDEX_FIELDS_LEFT_OUT = {"index_computed", "index_from_cache", "index_cache_entries",
                         "index_cache_bytes", "index_cache_budget"}
# field data the C++ RefractiveIndex writes and the Python one not yet: none since the engine
# writes both front ends' field data (schlieren_index_field)
INDEX_FIELDS_MISSING = set()
# the cases whose model reads cell data only, and the note both front ends write of it (the
# engine's CellOnlyFields)
CELL_NOTE_CASES = {"cell_data_only": "RefractiveIndex: the cell array density converted to point "
                   "data (each point the mean of the cells around it, vtkCellDataToPointData), "
                   "since n - 1 and its gradient are fields on points."}
INDEX_KNOWN = []  # the known differences met, said at the end (known_differences())

# the array-selection properties (ParaView's proxies take ["POINTS", name]; the package a name)
ARRAY_PROPERTIES = {"InputArray", "TemperatureArray", "PressureArray", "MixtureFractionArray",
                    "Species1Array", "Species2Array", "Species3Array", "Species4Array",
                    "HumidityArray", "CO2Array"}

# the file each input is written to (its extension: the data set's XML format)
EXTENSIONS = {"vtkImageData": ".vti", "vtkStructuredGrid": ".vts", "vtkUnstructuredGrid": ".vtu",
              "vtkMultiBlockDataSet": ".vtm", "vtkOverlappingAMR": ".vthb", "vtkPolyData": ".vtp"}


def proxy_properties(props, case=None):
    """A case's RefractiveIndex properties as ParaView's proxies take them: the arrays as point
    arrays, as cell arrays in the CELL_NOTE_CASES (a cell-only array asked for as POINTS would be
    converted by ParaView's vtkPVPostFilter before the C++ filter sees it, docs/CFD.md)."""
    kind = "CELLS" if case in CELL_NOTE_CASES else "POINTS"
    return {k: ([kind, v] if k in ARRAY_PROPERTIES else v) for k, v in props.items()}


def _add(data, name, values):
    a = numpy_support.numpy_to_vtk(np.ascontiguousarray(values), deep=1)
    a.SetName(name)
    data.GetPointData().AddArray(a)


def _image(dims, spacing, origin):
    g = vtkImageData()
    g.SetDimensions(*dims)
    g.SetSpacing(*spacing)
    g.SetOrigin(*origin)
    return g


def _unstructured(data):
    from vtkmodules.vtkFiltersCore import vtkAppendFilter
    a = vtkAppendFilter()
    a.SetInputData(data)
    a.Update()
    out = a.GetOutput()
    out.GetPointData().RemoveArray("vtkValidPointMask")
    return out


def _plane(extent, shock):
    """A 2D image (z = 0) with a density: a Gaussian blob, or (shock) a cone's conical shock layer
    seen in its r-z plane (x axial, y = r >= 0): denser between the cone and the shock."""
    g = vtkImageData()
    g.SetExtent(*extent)
    g.SetSpacing(0.05, 0.05, 1.0)
    g.SetOrigin(-0.4, 0.0 if shock else -0.3, 0.0)
    x = np.array([g.GetPoint(i) for i in range(g.GetNumberOfPoints())])
    if shock:
        cone, front = np.tan(np.radians(15.0)), np.tan(np.radians(28.0))
        s = x[:, 0] + 0.4
        rho = 1.2 + 0.6 * ((x[:, 1] < front * s) & (x[:, 1] > cone * s))
    else:
        rho = 1.2 + 0.5 * np.exp(-((x[:, 0] - 0.1) ** 2 + (x[:, 1] - 0.05) ** 2) / 0.02)
    _add(g, "density", rho.astype(np.float32))
    return g


def _wedge():
    """A 5 deg wedge one cell across (OpenFOAM's axisymmetric case) about the line along y at
    x = 0.3, z = 0.1: SymmetryAxis left at X, AxisFromWedge finds y."""
    g = vtkStructuredGrid()
    nr, na = 14, 17
    g.SetDimensions(nr, na, 2)
    p, values, half = vtkPoints(), [], np.radians(2.5)
    for side in (-1, 1):
        for j in range(na):
            for i in range(nr):
                r, y = 0.05 * i, 0.05 * j
                p.InsertNextPoint(0.3 + r * np.cos(half), y, 0.1 + side * r * np.sin(half))
                values.append(1.2 + 0.4 * np.exp(-((r - 0.3) ** 2 + (y - 0.4) ** 2) / 0.02))
    g.SetPoints(p)
    _add(g, "density", np.array(values, np.float32))
    return g


def _sheared(scene):
    """The scene's points, sheared in x by 0.05 y (a curvilinear grid), with its density."""
    dims = scene.GetDimensions()
    points = vtkPoints()
    for k in range(dims[2]):
        for j in range(dims[1]):
            for i in range(dims[0]):
                x, y, z = scene.GetPoint(i + dims[0] * (j + dims[1] * k))
                points.InsertNextPoint(x + 0.05 * y, y, z)
    g = vtkStructuredGrid()
    g.SetDimensions(dims)
    g.SetPoints(points)
    g.GetPointData().AddArray(scene.GetPointData().GetArray("density"))
    return g


def _amr(scene):
    """A two-level vtkOverlappingAMR of the scene's density: level 0 its 24 x 20 x 16 points, level
    1 the middle half of it at twice the resolution (the scene's density at the nearest point)."""
    from vtkmodules.vtkCommonDataModel import (vtkAMRBox, vtkAMRUtilities, vtkOverlappingAMR,
                                               vtkUniformGrid)
    dims, h, o = scene.GetDimensions(), scene.GetSpacing(), scene.GetOrigin()
    rho = numpy_support.vtk_to_numpy(scene.GetPointData().GetArray("density")).reshape(
        dims[2], dims[1], dims[0])
    amr = vtkOverlappingAMR()
    amr.Initialize(2, [1, 1])
    amr.SetOrigin(o)
    lo = [dims[a] // 4 for a in range(3)]  # the patch: points lo .. lo + dims / 2 of level 0
    for level, (first, count, step) in enumerate((([0, 0, 0], [d - 1 for d in dims], 1),
                                                  (lo, [d // 2 for d in dims], 2))):
        spacing = [h[a] / step for a in range(3)]
        corner = [o[a] + first[a] * h[a] for a in range(3)]
        g = vtkUniformGrid()
        g.SetOrigin(corner)
        g.SetSpacing(spacing)
        g.SetDimensions([c * step + 1 for c in count])
        k, j, i = np.meshgrid(*[np.clip(np.rint(first[a] + np.arange(count[a] * step + 1) / step)
                                        .astype(int), 0, dims[a] - 1) for a in (2, 1, 0)],
                              indexing="ij")
        _add(g, "density", rho[k, j, i].astype(np.float32).ravel())
        amr.SetSpacing(level, spacing)
        amr.SetAMRBox(level, 0, vtkAMRBox(corner, [c * step + 1 for c in count], spacing, o, 8))
        amr.SetDataSet(level, 0, g)
    amr.SetRefinementRatio(0, 2)
    vtkAMRUtilities.BlankCells(amr)
    return amr


def _image_blocks(scene):
    """The scene's density as a multiblock of two images, its halves in x sharing the plane
    between them (blocks of images: the engine's cell sampler on their voxels, as meshes)."""
    from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet
    dims = scene.GetDimensions()
    rho = numpy_support.vtk_to_numpy(scene.GetPointData().GetArray("density")).reshape(
        dims[2], dims[1], dims[0])
    out, half = vtkMultiBlockDataSet(), dims[0] // 2
    for b, (i0, i1) in enumerate(((0, half), (half, dims[0] - 1))):
        g = vtkImageData()
        g.SetExtent(i0, i1, 0, dims[1] - 1, 0, dims[2] - 1)
        g.SetSpacing(scene.GetSpacing())
        g.SetOrigin(scene.GetOrigin())
        _add(g, "density", np.ascontiguousarray(rho[:, :, i0:i1 + 1]).ravel())
        out.SetBlock(b, g)
    return out


def sphere(center, radius, res=24):
    """A closed sphere surface (a Body input: frontend_cases.INDEX_BODY's, and
    test_python_plugin_parity.py's section 12)."""
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    from vtkmodules.vtkFiltersSources import vtkSphereSource
    s = vtkSphereSource()
    s.SetCenter(center)
    s.SetRadius(radius)
    s.SetThetaResolution(res)
    s.SetPhiResolution(res)
    s.Update()
    out = vtkPolyData()
    out.DeepCopy(s.GetOutput())
    return out


def _cells_only():
    """A tetrahedralized Wavelet (vtkRTAnalyticSource, 13^3 points, 8640 tetrahedra) with its
    field as cell data only: `density` = RTData / 200 (0.19 .. 1.35), the cells' means of the
    points' values; no point arrays (a reader's cell arrays with no point copies)."""
    from vtkmodules.vtkFiltersCore import vtkPointDataToCellData
    from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
    from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
    wave = vtkRTAnalyticSource()
    wave.SetWholeExtent(-6, 6, -6, 6, -6, 6)
    tets = vtkDataSetTriangleFilter()
    tets.SetInputConnection(wave.GetOutputPort())
    cells = vtkPointDataToCellData()
    cells.SetInputConnection(tets.GetOutputPort())
    cells.Update()
    out = cells.GetOutput().NewInstance()
    out.DeepCopy(cells.GetOutput())
    rt = numpy_support.vtk_to_numpy(out.GetCellData().GetArray("RTData"))
    density = numpy_support.numpy_to_vtk((rt / 200.0).astype(np.float32), deep=1)
    density.SetName("density")
    out.GetCellData().Initialize()
    out.GetPointData().Initialize()
    out.GetCellData().AddArray(density)
    return out


def make_inputs(scene, readers):
    """The matrix's inputs: {name: data set}. `scene` is a RefractiveScene's output (a Gaussian
    sphere on 24 x 20 x 16 points, n_minus_1 and density); `readers` {name: data object} the real
    data read where present (bluntfin: the PLOT3D multiblock; disk: disk_out_ref.ex2). Also the
    Body input of frontend_cases.INDEX_BODY (sphere: a closed vtkPolyData)."""
    out = dict(readers)
    fields = _image((14, 11, 9), (0.01, 0.012, 0.015), (-0.07, -0.06, -0.06))
    count = fields.GetNumberOfPoints()
    wave = np.sin(7.0 * np.linspace(0.0, 1.0, count)) * np.cos(3.0 * np.linspace(0.0, 1.0, count))
    for field, values in (("density", 1.2 + 0.3 * wave), ("T", 300.0 - 40.0 * wave),
                          ("p", 101.325 * (1.0 + 0.2 * wave)), ("mix", 0.5 + 0.4 * wave),
                          ("Y1", 0.05 + 0.04 * wave), ("Y2", 0.2 - 0.1 * wave),
                          ("rh", 0.5 + 0.3 * wave), ("co2", 450.0 + 100.0 * wave),
                          ("blk", (wave > 0.3).astype(float))):
        _add(fields, field, values.astype(np.float32))
    out["fields"] = fields
    for which, keep in (("tp", ("T", "p")), ("n", ())):
        out[which] = vtkImageData()
        out[which].CopyStructure(fields)
        for field in keep:
            out[which].GetPointData().AddArray(fields.GetPointData().GetArray(field))
    _add(out["n"], "n", (1.0 + 3e-4 * (1 + wave)).astype(np.float32))
    out["scene"] = vtkImageData()
    out["scene"].DeepCopy(scene)
    # points outside the flow (vtkValidPointMask 0): a hole the flow encloses, a notch open to
    # the faces
    out["masked"] = vtkImageData()
    out["masked"].DeepCopy(scene)
    flow = np.ones((16, 20, 24), np.int8)  # z, y, x
    flow[6:10, 8:12, 9:14] = 0
    flow[0:3, 0:4, 0:5] = 0
    _add(out["masked"], "vtkValidPointMask", flow.ravel())
    out["sheared"] = _sheared(scene)
    out["plane"] = _plane((0, 16, 0, 12, 0, 0), False)
    out["plane_unstructured"] = _unstructured(_plane((0, 16, 0, 12, 0, 0), False))
    out["cone"] = _unstructured(_plane((0, 20, 0, 10, 0, 0), True))
    out["wedge"] = _wedge()
    out["amr"] = _amr(scene)
    out["image_blocks"] = _image_blocks(scene)
    out["cells_only"] = _cells_only()
    b = scene.GetBounds()  # the Body: about the scene's centre, 0.3 its shortest side
    out["sphere"] = sphere([(b[2 * a] + b[2 * a + 1]) / 2 for a in range(3)],
                           0.3 * min(b[2 * a + 1] - b[2 * a] for a in range(3)))
    return out


def write_input(folder, name, data):
    from vtkmodules.vtkIOXML import (vtkXMLImageDataWriter, vtkXMLMultiBlockDataWriter,
                                     vtkXMLPolyDataWriter, vtkXMLStructuredGridWriter,
                                     vtkXMLUniformGridAMRWriter, vtkXMLUnstructuredGridWriter)
    kind = data.GetClassName()
    writer = {"vtkImageData": vtkXMLImageDataWriter, "vtkStructuredGrid": vtkXMLStructuredGridWriter,
              "vtkUnstructuredGrid": vtkXMLUnstructuredGridWriter,
              "vtkMultiBlockDataSet": vtkXMLMultiBlockDataWriter,
              "vtkOverlappingAMR": vtkXMLUniformGridAMRWriter,
              "vtkPolyData": vtkXMLPolyDataWriter}[kind]()
    writer.SetInputData(data)
    writer.SetFileName(os.path.join(folder, "input_" + name + EXTENSIONS[kind]))
    if not writer.Write():
        raise RuntimeError("could not write %s" % writer.GetFileName())


def read_input(folder, name):
    """The input `name` as the reference run wrote it, or None where it wrote none."""
    from vtkmodules.vtkIOXML import vtkXMLGenericDataObjectReader, vtkXMLUniformGridAMRReader
    for ext in EXTENSIONS.values():
        path = os.path.join(folder, "input_" + name + ext)
        if os.path.exists(path):
            # (the generic reader gives an AMR's boxes without their data; an AMR's DeepCopy into
            # a NewInstance has no points: the reader's own output is handed on)
            r = vtkXMLUniformGridAMRReader() if ext == ".vthb" else vtkXMLGenericDataObjectReader()
            r.SetFileName(path)
            if ext == ".vthb":
                r.SetMaximumLevelsToReadByDefault(0)  # every level (the default reads level 0)
            r.Update()
            if ext == ".vthb":
                return r.GetOutputDataObject(0)
            data = r.GetOutputDataObject(0).NewInstance()
            data.DeepCopy(r.GetOutputDataObject(0))
            return data
    return None


def record(index, film):
    """What a leg compares: RefractiveIndex's output `index` and the film on it, as arrays."""
    out = {"index_geometry": np.array(index.GetExtent() + index.GetOrigin() + index.GetSpacing(),
                                      np.float64),
           "film_geometry": np.array(film.GetExtent() + film.GetOrigin() + film.GetSpacing(),
                                     np.float64)}
    pd = index.GetPointData()
    names = [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())]
    out["index_arrays"] = np.array(json.dumps(names))
    for i, n in enumerate(names):
        out["index_array_" + n] = numpy_support.vtk_to_numpy(pd.GetArray(i)).copy()
    fields = [f for f in cases.field_data_list(index.GetFieldData())
              if f[0] not in INDEX_FIELDS_LEFT_OUT]
    out["index_fields"] = np.array(json.dumps(fields))
    for a in cases.ARRAYS:
        arr = film.GetPointData().GetArray(a)
        if arr is not None:
            out["film_array_" + a] = numpy_support.vtk_to_numpy(arr).copy()
    out["film_fields"] = np.array(json.dumps(cases.field_data_list(film.GetFieldData())))
    return out


def _same(a, b):
    return a.shape == b.shape and a.dtype == b.dtype and \
        np.array_equal(a.view(np.uint8), b.view(np.uint8))


def compare(case, mine, theirs, check, leg):
    """`mine` (record) against the C++ plugin's record `theirs` (a loaded npz), bit for bit."""
    check(_same(mine["index_geometry"], theirs["index_geometry"]),
          "%s (%s): RefractiveIndex's grid is the C++ filter's (extent, origin, spacing %s)"
          % (case, leg, theirs["index_geometry"].tolist()))
    names = json.loads(str(theirs["index_arrays"]))
    mine_names = json.loads(str(mine["index_arrays"]))
    differing = [n for n in names if n in mine_names and
                 not _same(mine["index_array_" + n], theirs["index_array_" + n])]
    solid = theirs["index_array_solid"] if "solid" in names else None
    check(mine_names == names and not differing,
          "%s (%s): its point arrays %s bit for bit the C++ filter's (differing: %s%s)%s"
          % (case, leg, names, differing, "" if mine_names == names else
             "; the Python front end's: %s" % mine_names,
             "" if solid is None else ", %d solid points" % int(solid.astype(bool).sum())))
    f_mine = {f[0]: f for f in json.loads(str(mine["index_fields"]))}
    f_theirs = {f[0]: f for f in json.loads(str(theirs["index_fields"]))}
    missing = sorted(set(f_theirs) - set(f_mine))
    unknown = [n for n in missing if n not in INDEX_FIELDS_MISSING]
    extra = sorted(set(f_mine) - set(f_theirs))
    wrong = [n for n in f_theirs if n in f_mine and f_mine[n] != f_theirs[n]]
    check(not unknown and not extra and not wrong and len(f_mine) >= 4,
          "%s (%s): its field data %s the C++ filter's (less its cache report; differing: %s, "
          "C++ only: %s, Python only: %s)" % (case, leg, sorted(f_mine), [
              (f_mine[n], f_theirs[n]) for n in wrong][:2], unknown, extra))
    if case in CELL_NOTE_CASES:
        notes = [f for f in f_mine.get("index_notes", [None, None, []])[2]
                 if "converted to point data" in f]
        check(notes == [CELL_NOTE_CASES[case]],
              "%s (%s): the note of the cell arrays converted to point data: %s"
              % (case, leg, notes))
    if missing and not unknown:
        INDEX_KNOWN.append("%s: no %s in the field data (C++: %r)" % (
            case, ", ".join(missing), [f_theirs[n][2] for n in missing]))
    check(_same(mine["film_geometry"], theirs["film_geometry"]),
          "%s (%s): SchlierenImage's film the C++ filter's (%s)"
          % (case, leg, theirs["film_geometry"].tolist()))
    arrays = [a for a in cases.ARRAYS if "film_array_" + a in theirs]
    intensity = theirs["film_array_intensity"]
    check(all("film_array_" + a in mine and _same(mine["film_array_" + a],
                                                  theirs["film_array_" + a]) for a in arrays) and
          not [a for a in cases.ARRAYS if "film_array_" + a in mine and a not in arrays] and
          float(np.ptp(intensity)) > 0.02,
          "%s (%s): the film's %s bit for bit (intensity %.3f..%.3f)"
          % (case, leg, arrays, float(intensity.min()), float(intensity.max())))
    f_mine, f_theirs = json.loads(str(mine["film_fields"])), json.loads(str(theirs["film_fields"]))
    check(f_mine == f_theirs and len(f_theirs) > 20,
          "%s (%s): the film's field data the C++ filter's (%d entries%s)"
          % (case, leg, len(f_theirs), "" if f_mine == f_theirs else
             "; differing: %s" % [(a, b) for a, b in zip(f_mine, f_theirs) if a != b][:3]))


def known_differences():
    """Says the known differences met (INDEX_KNOWN), one line each."""
    for line in INDEX_KNOWN:
        print("known (Python RefractiveIndex) " + line)
