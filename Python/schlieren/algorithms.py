# SPDX-License-Identifier: BSD-3-Clause
"""The four stages as VTK algorithms (VTKPythonAlgorithmBase) over the engine's C interface.

    import schlieren
    scene = schlieren.RefractiveScene(Scene="GaussianSphere", Dimensions=[128] * 3)
    image = schlieren.SchlierenImage(Cutoff="KnifeEdge", Resolution=[512, 512])
    image.SetInputConnection(scene.GetOutputPort())
    image.Update()
    out = image.GetOutput()          # vtkImageData: intensity, deflection, ...

Property names, defaults and entries are the ParaView proxies'; they are keyword arguments and
attributes (setting one marks the algorithm modified). Inputs may be any vtkDataSet: what is not
an axis-aligned vtkImageData is resampled onto one (the engine's cell sampler) first by RefractiveIndex
(a composite data set, a PLOT3D multiblock for example, too: its blocks onto one image);
RefractionOctree, NumericalSchlieren and SchlierenImage take an axis-aligned vtkImageData and
refuse anything else with the C++ filters' reason. Every output is one vtkImageData, whatever the
input (no per-block multiblock); a failed request leaves it empty and says why (a VTK error, the
message kept in LastError), never a Python traceback.
"""
import math

import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.util.vtkAlgorithm import VTKPythonAlgorithmBase
from vtkmodules.vtkCommonDataModel import (vtkCompositeDataSet, vtkDataObject, vtkDataSet,
                                           vtkImageData, vtkOverlappingAMR, vtkPolyData)
from vtkmodules.vtkCommonExecutionModel import vtkDemandDrivenPipeline as DDP
from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as SDDP

from . import _engine
from ._engine import EngineError


def _is_number(v):
    return isinstance(v, (int, float, np.integer, np.floating, np.bool_))


def _ranks():
    """The job's ranks (pvbatch or pvserver under MPI: VTK's global controller with more than one
    process) as the engine's collectives take them (_engine.Ranks), or None: one process."""
    return _engine.controller_ranks()


def _pass_name(request):
    """"data", "information", "update extent" or "data object": the pipeline pass `request`
    asks for."""
    for name, key in (("data", DDP.REQUEST_DATA()), ("information", DDP.REQUEST_INFORMATION()),
                      ("update extent", SDDP.REQUEST_UPDATE_EXTENT()),
                      ("data object", DDP.REQUEST_DATA_OBJECT())):
        if request.Has(key):
            return name
    return "other"


def _has_grid(info):
    """Whether the input information `info` gives an image's grid (whole extent, origin, spacing):
    not where the upstream's information pass failed (on this rank)."""
    return all(info.Has(k) for k in (SDDP.WHOLE_EXTENT(), vtkImageData.ORIGIN(),
                                     vtkImageData.SPACING()))


def _empty(extent):
    return any(extent[2 * a + 1] < extent[2 * a] for a in range(3))


def _spread(ranks, data, symmetry):
    """`ranks` where RefractiveIndex resamples a mesh or an AMR under MPI from every rank's piece
    (the C++ filter's way: each rank samples its piece or its boxes, the samples combined over the
    ranks), else None: one process, an image, a 2D input made a volume (read whole on every
    rank)."""
    if ranks is None or symmetry != "None" or isinstance(data, vtkImageData):
        return None
    return ranks if isinstance(data, (vtkDataSet, vtkCompositeDataSet)) else None


def _crop(image, extent):
    """`image` cut to `extent` in place (its point arrays, its field data kept), where it holds
    more."""
    e = [int(v) for v in extent]
    have = list(image.GetExtent())
    if e == have or _empty(e) or any(e[2 * a] < have[2 * a] or e[2 * a + 1] > have[2 * a + 1]
                                      for a in range(3)):
        return
    d = [have[2 * a + 1] - have[2 * a] + 1 for a in range(3)]
    sl = tuple(slice(e[2 * a] - have[2 * a], e[2 * a + 1] - have[2 * a] + 1) for a in (2, 1, 0))
    cut = vtkImageData()
    cut.SetExtent(*e)
    cut.SetOrigin(image.GetOrigin())
    cut.SetSpacing(image.GetSpacing())
    from vtkmodules.vtkCommonCore import vtkDataArray
    pd, cpd = image.GetPointData(), cut.GetPointData()
    scalars = pd.GetScalars()
    for i in range(pd.GetNumberOfArrays()):
        a = pd.GetAbstractArray(i)
        if not isinstance(a, vtkDataArray):
            continue
        v = numpy_support.vtk_to_numpy(a)
        c = a.GetNumberOfComponents()
        v = v.reshape(d[2], d[1], d[0], c)[sl].reshape(-1, c) if c > 1 else \
            v.reshape(d[2], d[1], d[0])[sl].reshape(-1)
        b = numpy_support.numpy_to_vtk(np.ascontiguousarray(v), deep=1,
                                       array_type=a.GetDataType())
        b.SetName(a.GetName())
        for k in range(c):
            if a.GetComponentName(k):
                b.SetComponentName(k, a.GetComponentName(k))
        cpd.AddArray(b)
        if scalars is not None and a.GetName() == scalars.GetName():
            cpd.SetActiveScalars(a.GetName())
    cut.GetFieldData().ShallowCopy(image.GetFieldData())
    image.ShallowCopy(cut)


def _ask_pieces(src, out_info, ranks):
    """The input request of a filter that gathers the pieces under MPI (the C++ SchlierenImage's
    and NumericalSchlieren's): the whole extent, on one process as one piece, under MPI this
    output's piece of as many (the upstream splits the whole extent)."""
    if src.Has(SDDP.WHOLE_EXTENT()):
        src.Set(SDDP.UPDATE_EXTENT(), src.Get(SDDP.WHOLE_EXTENT()), 6)
    if ranks is None:
        return
    piece = out_info.Get(SDDP.UPDATE_PIECE_NUMBER()) if out_info.Has(
        SDDP.UPDATE_PIECE_NUMBER()) else 0
    pieces = out_info.Get(SDDP.UPDATE_NUMBER_OF_PIECES()) if out_info.Has(
        SDDP.UPDATE_NUMBER_OF_PIECES()) else 1
    src.Set(SDDP.UPDATE_PIECE_NUMBER(), piece)
    src.Set(SDDP.UPDATE_NUMBER_OF_PIECES(), max(pieces, 1))
    src.Set(SDDP.UPDATE_NUMBER_OF_GHOST_LEVELS(), 0)


def _agreed(ranks, mine, step):
    """Under MPI, before the collective `step`, the failure every rank reports after a step that
    may fail on some only: this rank's own where it failed, else the first failing rank's
    ("another rank (r) failed: ..."); "" where none did; where the ranks are not all at `step`,
    that (every rank). One process: `mine`."""
    if ranks is None:
        return mine or ""
    agreed = ranks.failure(mine or "", step)
    return agreed if agreed.startswith("the ranks are at different") else (mine or agreed)


_INDEX_STEP = "RefractiveIndex's pieces"
_TRACE_STEP = "SchlierenImage's trace"


def _closest(name, names):
    """" (the closest known name: 'X'...)" for the known name nearest to `name`, or ""."""
    import difflib
    names = list(names)
    same = [n for n in names if n.lower() == str(name).lower()]
    if same:
        return " (the closest known name: %r; names are case-sensitive)" % same[0]
    near = difflib.get_close_matches(str(name), names, n=1, cutoff=0.75) or \
        difflib.get_close_matches(str(name).lower(), [n.lower() for n in names], n=1, cutoff=0.75)
    if near:
        match = [n for n in names if n == near[0] or n.lower() == near[0]][0]
        return " (the closest known name: %r)" % match
    return ""


class _Properties(VTKPythonAlgorithmBase):
    """Proxy properties as attributes and keyword arguments."""

    _defaults = {}   # name -> default
    _entries = {}    # name -> allowed texts (enumerations)

    def __init__(self, nInputPorts, outputType="vtkImageData", nOutputPorts=1, **kwargs):
        object.__setattr__(self, "_values", dict(self._defaults))
        object.__setattr__(self, "LastError", "")  # the message of the last failed request
        # values refused by SetProperty (the ParaView plugin's setters): name -> the reason
        object.__setattr__(self, "_refused", {})
        VTKPythonAlgorithmBase.__init__(self, nInputPorts=nInputPorts, nOutputPorts=nOutputPorts,
                                        outputType=outputType)
        object.__setattr__(self, "_ready", True)
        for k, v in kwargs.items():
            setattr(self, k, v)

    def __getattr__(self, name):
        values = self.__dict__.get("_values")
        if values is not None and name in values:
            return values[name]
        raise AttributeError("%s has no attribute or property %r" % (type(self).__name__, name))

    def __setattr__(self, name, value):
        if name in self._defaults:
            try:
                self._values[name] = self._check(name, value)
            except (TypeError, ValueError) as e:
                object.__setattr__(self, "LastError", str(e))
                raise
            self.Modified()
        elif not self.__dict__.get("_ready") or hasattr(type(self), name) or \
                (not name[:1].isupper() and (name.startswith("_") or
                                             not _closest(name, self._defaults))):
            # the base class's own attributes (InputType, ...) and private state
            object.__setattr__(self, name, value)
        else:
            # a property's name mistyped or wrongly cased (cutoff=...): an error, not an
            # attribute the trace never reads
            raise AttributeError("%s has no property %r%s; its properties: %s"
                                 % (type(self).__name__, name, _closest(name, self._defaults),
                                    ", ".join(self._defaults)))

    def _check(self, name, value):
        default = self._defaults[name]
        if name in self._entries:
            if value not in self._entries[name]:
                raise ValueError("%s %r is not one of: %s%s" % (
                    name, value, ", ".join(self._entries[name]),
                    _closest(str(value), self._entries[name])))
            return value
        if isinstance(default, (list, tuple)):
            try:
                value = list(np.asarray(value).ravel().tolist())
            except Exception:
                raise ValueError("%s takes %d numbers, got %r" % (name, len(default), value))
            if len(value) != len(default):
                raise ValueError("%s takes %d values, got %d" % (name, len(default), len(value)))
            if all(_is_number(d) for d in default) and not all(_is_number(v) for v in value):
                raise ValueError("%s takes %d numbers, got %r" % (name, len(default), value))
            return value
        if _is_number(default) and not _is_number(value):
            raise ValueError("%s is %r: it takes a number" % (name, value))
        return value

    # the proxy whose property ranges the engine lists (schlieren_check_property: the C++
    # filter's check), or None
    _range_proxy = None

    def _check_ranges(self):
        """An EngineError naming the first property whose value is outside the engine's range."""
        if self._range_proxy:
            for name in self._defaults:
                _engine.check_property(self._range_proxy, name, self._values[name])

    def SetProperty(self, name, value):
        """Sets a property as ParaView's setters do: a value this front end refuses is kept as an
        error instead of raised (no traceback out of a proxy's setter). Until a good value is
        set, every request fails with that error and an empty output, so that no image shows
        that seems to use the refused value."""
        try:
            setattr(self, name, value)
        except (ValueError, TypeError, EngineError) as e:
            self._refused[name] = str(e)
            self.Modified()
            return False
        if self._refused.pop(name, None) is not None:
            self.Modified()
        return True

    def ProcessRequest(self, request, inInfo, outInfo):
        """VTKPythonAlgorithmBase's dispatch with the errors a C++ filter gives: a refused value
        or an exception of any kind becomes a VTK error (ParaView's Output Messages) and an
        empty output, never a traceback."""
        is_data = request.Has(DDP.REQUEST_DATA())
        ranks = _ranks()
        # under MPI the pass's collectives are named after it, so that the guard tells the ranks
        # that are at this pass from those elsewhere (_engine.Ranks.begin)
        kept = ranks.begin("%s's %s pass" % (type(self).__name__, _pass_name(request))) \
            if ranks is not None else None
        try:
            if is_data or request.Has(DDP.REQUEST_INFORMATION()):
                self._check_ranges()  # as the C++ filters' RequestInformation
            if self._refused and (is_data or request.Has(DDP.REQUEST_INFORMATION())):
                if not is_data:
                    # said once, by the data request; the output's extent is empty until then
                    info = outInfo.GetInformationObject(0)
                    if info.Has(SDDP.WHOLE_EXTENT()):
                        info.Set(SDDP.WHOLE_EXTENT(), 0, -1, 0, -1, 0, -1)
                    return 1
                ok = self._fail("; ".join(self._refused.values()) + " (the output stays empty "
                                "until the value is changed)")
            else:
                ok = VTKPythonAlgorithmBase.ProcessRequest(self, request, inInfo, outInfo)
        except Exception as e:  # noqa: BLE001 -- a message, not a traceback, whatever it is
            ok = self._fail(str(e) if isinstance(e, (EngineError, _engine.OutOfStep)) else
                            "%s: %s" % (type(e).__name__, e))
        finally:
            if ranks is not None:
                ranks.end(kept)
        if not ok and (is_data or request.Has(DDP.REQUEST_INFORMATION())):
            # no image from before left as if it were this request's (a failed information
            # request is not followed by a data request)
            out = outInfo.GetInformationObject(0).Get(vtkDataObject.DATA_OBJECT())
            if out is not None:
                out.Initialize()
        elif is_data:
            object.__setattr__(self, "_said", None)  # a later failure is said again
        return ok

    def GetOutput(self, port=0):
        """The output data object (vtkImageData), as vtkImageAlgorithm::GetOutput gives it."""
        return self.GetOutputDataObject(port)

    def SetInputData(self, *args):
        """SetInputData(data) or SetInputData(port, data), as on VTK's C++ algorithms."""
        self.SetInputDataObject(*args)

    def ListProperties(self):
        return list(self._defaults)

    def _fail(self, message):
        """A VTK error (the output window, as vtkErrorMacro writes) and the message kept in
        LastError for scripts; returns 0 for the pipeline (the request failed)."""
        from vtkmodules.vtkCommonCore import vtkOutputWindow
        object.__setattr__(self, "LastError", message)
        # said once, as the C++ filters do: not again for the same settings (a failed request
        # is asked again by every update and Fetch)
        key = (message, self.GetMTime())
        if self.__dict__.get("_said") != key:
            object.__setattr__(self, "_said", key)
            vtkOutputWindow.GetInstance().DisplayErrorText(
                "ERROR: In %s: %s\n" % (type(self).__name__, message))
        return 0

    def _warn(self, message):
        """A VTK warning (ParaView's Output Messages, as vtkWarningMacro writes)."""
        from vtkmodules.vtkCommonCore import vtkOutputWindow
        vtkOutputWindow.GetInstance().DisplayWarningText(
            "Warning: In %s: %s\n" % (type(self).__name__, message))


def _axis_aligned_image(data, what):
    """`data` if it is a vtkImageData without a direction matrix; else an EngineError with the
    reason the C++ SchlierenImage gives."""
    if not isinstance(data, vtkImageData):
        raise EngineError(
            "%s needs a vtkImageData input with the point array 'n_minus_1'; got %s. Resample "
            "the data onto an image and apply RefractiveIndex first."
            % (what, data.GetClassName() if data is not None else "nothing"))
    direction = getattr(data, "GetDirectionMatrix", None)
    if direction is not None and not direction().IsIdentity():
        raise EngineError("%s traces axis-aligned images only; this one has a direction matrix. "
                          "Resample it onto an axis-aligned image first." % what)
    return data


def _first_point(image):
    """The world position of an image's first point (its extent may not start at 0)."""
    e, o, s = image.GetExtent(), image.GetOrigin(), image.GetSpacing()
    return [o[a] + e[2 * a] * s[a] for a in range(3)]


def _array_bytes(data):
    """The input's arrays, bytes per grid point, as the C++ filter counts what the probe copies
    (every point and cell array; a composite input: 64): the engine adds the rest."""
    if not isinstance(data, vtkDataSet):
        return 64.0
    return float(sum(a.GetNumberOfComponents() * a.GetDataTypeSize()
                     for attributes in (data.GetPointData(), data.GetCellData())
                     for a in (attributes.GetArray(i) for i in range(attributes.GetNumberOfArrays()))
                     if a is not None))


def _bounds_everywhere(data, ranks=None):
    """The bounds of the leaves that have points (None: no points, _leaf_bounds); with `ranks`
    (MPI, collective) of every rank's piece, an empty piece counting for nothing, as the C++
    filter's UpdatedInputBounds."""
    local = _leaf_bounds(data)
    if ranks is None:
        return local
    have = local is not None
    lows = np.array([local[2 * a] if have else np.inf for a in range(3)] +
                    [-local[2 * a + 1] if have else np.inf for a in range(3)], np.float64)
    lows = ranks.comm.allreduce(lows, "min")
    if not np.isfinite(lows).all():
        return None  # no rank has a point
    return [lows[0], -lows[3], lows[1], -lows[4], lows[2], -lows[5]]


def _internal_mesh(data):
    """An OpenFOAM reader's multiblock: its block named internalMesh (the cells; the patches are
    surfaces of it), as the C++ filter reads it; any other input as it is."""
    from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet
    if not isinstance(data, vtkMultiBlockDataSet):
        return data
    for b in range(data.GetNumberOfBlocks()):
        meta = data.GetMetaData(b) if data.HasMetaData(b) else None
        block = data.GetBlock(b)
        if meta is not None and meta.Get(vtkCompositeDataSet.NAME()) == "internalMesh" and \
                isinstance(block, vtkDataSet):
            return block
    return data


def _internal_mesh_note(data):
    """The C++ filter's note where `data` is an OpenFOAM reader's multiblock with an internalMesh
    ("" otherwise): the block read and the others ignored."""
    mesh = _internal_mesh(data)
    if mesh is data:
        return ""
    others = []
    for b in range(data.GetNumberOfBlocks()):
        meta = data.GetMetaData(b) if data.HasMetaData(b) else None
        name = meta.Get(vtkCompositeDataSet.NAME()) if meta is not None else None
        if data.GetBlock(b) is not None and data.GetBlock(b) is not mesh:
            others.append(name if name else "block %d" % b)
    note = "RefractiveIndex: the OpenFOAM case's internalMesh is read (%d cells)" % \
        mesh.GetNumberOfCells()
    if others:
        note += ("; the other blocks (%s: patches, zones) are ignored, since the field lives in "
                 "the cells" % ", ".join(others))
    return note + "."


def _leaves(data):
    """The data sets of a data set (itself) or of a composite data set, in its iterator's order."""
    if isinstance(data, vtkDataSet):
        return [data]
    leaves = []
    if isinstance(data, vtkCompositeDataSet):
        it = data.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            if isinstance(it.GetCurrentDataObject(), vtkDataSet):
                leaves.append(it.GetCurrentDataObject())
            it.GoToNextItem()
    return leaves


def _input_arrays(data):
    """The input's array names (point arrays, then cell arrays, each once; the C++ filter's
    ArrayNames) and where each is found: (name, "point" or "cell", VTK type name) a leaf."""
    names, places = [], []
    for cells in (0, 1):
        for leaf in _leaves(data):
            fd = leaf.GetCellData() if cells else leaf.GetPointData()
            for i in range(fd.GetNumberOfArrays()):
                a, n = fd.GetAbstractArray(i), fd.GetArrayName(i)
                if a is None or not n or n == "vtkValidPointMask":
                    continue
                if n not in names:
                    names.append(n)
                places.append("%s\t%s\t%s" % (n, "cell" if cells else "point",
                                                a.GetDataTypeAsString()))
    return names, places


def _point_fields(data, chosen, names, places):
    """The C++ RefractiveIndex's PointFields: the arrays the model reads (`chosen`: the model as
    resolved, schlieren_cell_fields' settings) where the input has them as cell data only, turned
    into point data by vtkCellDataToPointData with the C++ filter's settings (only those arrays,
    cell data not passed; an AMR kept as it is); ids and integer arrays refused (EngineError),
    the rule and the note the engine's. `names`, `places`: _input_arrays' (every rank's under
    MPI). Returns (the data to sample, the note or "")."""
    found = _engine.cell_fields(chosen, [p.split("\t") for p in places], names)
    if not found["from_cells"] or isinstance(data, vtkOverlappingAMR):
        return data, ""  # (an AMR's cell data is sampled as cells, as the C++ filter's)
    from vtkmodules.vtkFiltersCore import vtkCellDataToPointData
    to_points = vtkCellDataToPointData()
    to_points.SetInputData(data)
    to_points.SetProcessAllArrays(False)
    for name in found["from_cells"]:
        to_points.AddCellDataArray(name)
    to_points.PassCellDataOff()
    to_points.Update()
    converted = to_points.GetOutputDataObject(0)
    copy = converted.NewInstance()
    copy.ShallowCopy(converted)
    return copy, found["note"]


def _leaf_bounds(data):
    """The bounds of the leaves that have points (None: no points), as the C++ filter's."""
    from vtkmodules.vtkCommonDataModel import vtkBoundingBox
    box = vtkBoundingBox()
    for leaf in _leaves(data):
        if leaf.GetNumberOfPoints() > 0:
            box.AddBounds(leaf.GetBounds())
    if not box.IsValid():
        return None
    b = [0.0] * 6
    box.GetBounds(b)
    return b


def _cell_leaves(data):
    """The data sets with cells of `data` (itself, or a composite data set's blocks in order)."""
    return [leaf for leaf in _leaves(data) if leaf.GetNumberOfCells() > 0]


def _wall_rim(mesh, dims, origin, spacing, valid, ignore_axis, plan=None):
    """BodyFromGrid's voids beside a mesh's walls, the front end's part (as the C++ filter's
    schlieren::walls::ClassifyRim): the mesh's boundary faces with their normals and the velocity
    beside them (VTK's surface filter), their kinds (the engine's, schlieren_wall_faces), and for
    every invalid grid point next to a valid one the kind of its nearest face (VTK's static cell
    locator, at the point where the grid sampled the mesh: the engine's SymmetryToMesh for a
    symmetric `plan`). Returns (rim uint8 a grid point, the faces' report), or None where the mesh
    has no velocity (a 3-component point or cell array named U or velocity) or no face."""
    from vtkmodules.vtkCommonCore import vtkIdList, reference
    from vtkmodules.vtkCommonDataModel import (vtkCellArray, vtkGenericCell, vtkPolyData,
                                               vtkPolygon, vtkStaticCellLocator)
    from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter
    if not isinstance(mesh, vtkDataSet) or mesh.GetNumberOfCells() == 0:
        return None

    def velocity(fd):
        for i in range(fd.GetNumberOfArrays()):
            a = fd.GetArray(i)
            if a is not None and a.GetName() and a.GetNumberOfComponents() == 3 and \
                    a.GetName().lower() in ("u", "velocity"):
                return a
        return None
    cell_u = velocity(mesh.GetCellData())  # the cell's own value beside a face, before points'
    point_u = None if cell_u is not None else velocity(mesh.GetPointData())
    U = cell_u if cell_u is not None else point_u
    if U is None or U.GetNumberOfTuples() == 0:
        return None
    u3 = numpy_support.vtk_to_numpy(U).astype(np.float64).reshape(-1, 3)
    largest = float(np.sqrt(u3[:, 0] * u3[:, 0] + u3[:, 1] * u3[:, 1] + u3[:, 2] * u3[:, 2]).max())
    if not largest > 0:
        return None
    surface = vtkDataSetSurfaceFilter()
    surface.SetInputData(mesh)
    surface.PassThroughCellIdsOn()
    surface.PassThroughPointIdsOn()
    surface.Update()
    faces = surface.GetOutput()
    cell_ids = faces.GetCellData().GetArray(surface.GetOriginalCellIdsName())
    point_ids = faces.GetPointData().GetArray(surface.GetOriginalPointIdsName())
    cell_ids = None if cell_ids is None else numpy_support.vtk_to_numpy(cell_ids)
    point_ids = None if point_ids is None else numpy_support.vtk_to_numpy(point_ids)
    count, points, ids = faces.GetNumberOfCells(), faces.GetPoints(), vtkIdList()
    offsets, connectivity = [0], []
    normals, speeds = np.zeros((count, 3)), np.zeros((count, 3))
    for c in range(count):
        faces.GetCellPoints(c, ids)
        m = ids.GetNumberOfIds()
        face = [ids.GetId(k) for k in range(m)]
        connectivity.extend(face)
        offsets.append(len(connectivity))
        if m < 3:
            continue
        n = [0.0, 0.0, 0.0]
        vtkPolygon.ComputeNormal(points, m, face, n)
        normals[c] = n
        if cell_u is not None and cell_ids is not None:
            speeds[c] = u3[cell_ids[c]]
        elif point_u is not None and point_ids is not None:
            u = [0.0, 0.0, 0.0]
            for q in face:
                v = u3[point_ids[q]]
                for a in range(3):
                    u[a] += float(v[a]) / m
            speeds[c] = u
    kinds, report = _engine.wall_faces(offsets, connectivity, faces.GetNumberOfPoints(), normals,
                                       speeds, largest, ignore_axis, U.GetName())
    kept, polys, kind = vtkPolyData(), vtkCellArray(), []
    kept.SetPoints(points)
    for c in range(count):
        if kinds[c] != 255:
            faces.GetCellPoints(c, ids)
            polys.InsertNextCell(ids)
            kind.append(int(kinds[c]))
    if not kind:
        return None
    kept.SetPolys(polys)
    locator = vtkStaticCellLocator()
    locator.SetDataSet(kept)
    locator.BuildLocator()
    # the invalid points next to a valid one (6 neighbours), x fastest
    nx, ny, nz = dims
    ok = np.asarray(valid).reshape(nz, ny, nx) != 0
    beside = np.zeros_like(ok)
    beside[:, :, 1:] |= ok[:, :, :-1]
    beside[:, :, :-1] |= ok[:, :, 1:]
    beside[:, 1:, :] |= ok[:, :-1, :]
    beside[:, :-1, :] |= ok[:, 1:, :]
    beside[1:, :, :] |= ok[:-1, :, :]
    beside[:-1, :, :] |= ok[1:, :, :]
    where = np.flatnonzero(~ok & beside)
    k, j, i = np.unravel_index(where, (nz, ny, nx))
    x = np.stack([origin[0] + i * spacing[0], origin[1] + j * spacing[1],
                  origin[2] + k * spacing[2]], axis=1)
    at = x if plan is None else _engine.symmetry_to_mesh(plan, x)
    rim = np.zeros(nx * ny * nz, np.uint8)
    cell, closest = vtkGenericCell(), [0.0, 0.0, 0.0]
    found, sub, d2 = reference(-1), reference(0), reference(0.0)
    for p, point in zip(where, at):
        found.set(-1)
        locator.FindClosestPoint(point.tolist(), closest, cell, found, sub, d2)
        if found.get() >= 0:
            rim[p] = kind[found.get()]
    return rim, report


def _describe_cells(data):
    """"N cells: a 3D, b 2D (faces), c 1D or 0D" of a data set or a composite one's leaves (the
    C++ filter's words, for the message where no grid point lies in a cell)."""
    from vtkmodules.vtkCommonDataModel import vtkCellTypes
    counts = [0, 0, 0, 0]
    for leaf in _leaves(data):
        for c in range(leaf.GetNumberOfCells()):
            counts[max(0, min(3, vtkCellTypes.GetDimension(leaf.GetCellType(c))))] += 1
    return "%d cells: %d 3D, %d 2D (faces), %d 1D or 0D" % (
        sum(counts), counts[3], counts[2], counts[0] + counts[1])


def _values(a):
    """A VTK array's values as NumPy's (a copy where VTK's layout is not a plain array: the
    implicit arrays newer VTKs keep offsets and cell types in)."""
    try:
        return numpy_support.vtk_to_numpy(a)
    except Exception:
        from vtkmodules.vtkCommonCore import vtkTypeInt64Array
        plain = vtkTypeInt64Array()
        plain.DeepCopy(a)
        return numpy_support.vtk_to_numpy(plain)


def _mesh_of(ds):
    """A data set's mesh as schlieren_sample_cells takes it (keyword arguments)."""
    from vtkmodules.vtkCommonDataModel import (vtkDataSetAttributes, vtkStructuredGrid,
                                               vtkUnstructuredGrid)
    n2n = numpy_support.vtk_to_numpy
    if not isinstance(ds, (vtkStructuredGrid, vtkUnstructuredGrid)):
        # an image's or a rectilinear grid's voxels, a poly data's faces: as an unstructured grid,
        # its points in double as the C++ adapter reads them (vtkDataSet::GetPoint; the append
        # filter's default makes an image's points float)
        from vtkmodules.vtkCommonExecutionModel import vtkAlgorithm
        from vtkmodules.vtkFiltersCore import vtkAppendFilter
        append = vtkAppendFilter()
        append.SetOutputPointsPrecision(vtkAlgorithm.DOUBLE_PRECISION)
        append.AddInputData(ds)
        append.Update()
        ds = append.GetOutput()
    points = ds.GetPoints()
    mesh = dict(points=np.zeros((0, 3)) if points is None else n2n(points.GetData()))
    cell_ghosts = ds.GetCellData().GetArray("vtkGhostType")
    skip = None
    if cell_ghosts is not None:
        skip = (n2n(cell_ghosts) & vtkDataSetAttributes.HIDDENCELL) != 0
    if isinstance(ds, vtkStructuredGrid):
        d = [0, 0, 0]
        ds.GetDimensions(d)  # (VTK 9.6 and later have no GetDimensions() that returns them)
        mesh["structured_dims"] = d
        point_ghosts = ds.GetPointData().GetArray("vtkGhostType")
        if point_ghosts is not None and min(d) > 1:
            # a cell is hidden by one of its points too (vtkStructuredGrid::IsCellVisible)
            hidden = ((n2n(point_ghosts) & vtkDataSetAttributes.HIDDENPOINT) != 0).reshape(
                d[2], d[1], d[0])
            corners = np.zeros((d[2] - 1, d[1] - 1, d[0] - 1), bool)
            for dz in (0, 1):
                for dy in (0, 1):
                    for dx in (0, 1):
                        corners |= hidden[dz:d[2] - 1 + dz, dy:d[1] - 1 + dy, dx:d[0] - 1 + dx]
            skip = corners.reshape(-1) if skip is None else (skip | corners.reshape(-1))
    else:
        cells = ds.GetCells()
        mesh["cell_types"] = _values(getattr(ds, "GetCellTypesArray", ds.GetCellTypes)())
        mesh["offsets"] = _values(cells.GetOffsetsArray())
        mesh["connectivity"] = _values(cells.GetConnectivityArray())
    mesh["skip_cells"] = None if skip is None or not skip.any() else skip.astype(np.uint8)
    return mesh


def _sample_leaves(data, n, run):
    """The leaves of `data` with cells sampled at `n` points by `run(found, point_arrays,
    cell_arrays, mesh)` (the engine's grid or points mode), as the C++ RefractiveIndex samples
    them: every point array of the first block that every block has, interpolated (float32 and
    float64 kept, integers rounded back), every cell array the holding cell's value. Returns
    ([(name, vtk array of n tuples)] in that order, found: a uint8 per point)."""
    leaves = _cell_leaves(data)
    found = np.zeros(n, np.uint8)
    wanted = []  # (cells, name, vtk type, components), the first block's, kept where all have them
    for cells in (0, 1):
        attributes = (leaves[0].GetCellData() if cells else leaves[0].GetPointData()) if leaves \
            else None
        for i in range(attributes.GetNumberOfArrays() if attributes else 0):
            a = attributes.GetArray(i)
            if a is None or not a.GetName() or a.GetName() == "vtkGhostType" or \
                    a.GetDataType() == 1 or \
                    (cells and any(w[1] == a.GetName() and not w[0] for w in wanted)):
                continue  # (1: VTK_BIT)
            key = (cells, a.GetName(), a.GetDataType(), a.GetNumberOfComponents())

            def has(leaf, key=key):
                b = (leaf.GetCellData() if key[0] else leaf.GetPointData()).GetArray(key[1])
                return b is not None and b.GetDataType() == key[2] and \
                    b.GetNumberOfComponents() == key[3]
            if all(has(leaf) for leaf in leaves):
                wanted.append(key)
    sampled = {}
    for leaf in leaves:
        arrays = [[], []]
        for cells, name, _, _ in wanted:
            a = (leaf.GetCellData() if cells else leaf.GetPointData()).GetArray(name)
            arrays[cells].append((name, numpy_support.vtk_to_numpy(a)))
        before = found.copy()
        _, values = run(found, arrays[0], arrays[1], _mesh_of(leaf))
        here = (found != 0) & (before == 0)  # a later block wrote only the points it found
        for key in wanted:
            if key[1] in sampled:
                sampled[key[1]][here] = values[key[1]][here]
            else:
                sampled[key[1]] = values[key[1]]
    from vtkmodules.vtkCommonCore import vtkDataArray
    out = []
    for cells, name, vtk_type, components in wanted:
        v = sampled[name]
        a = vtkDataArray.CreateDataArray(vtk_type)
        a.SetName(name)
        a.SetNumberOfComponents(components)
        a.SetNumberOfTuples(n)
        target = numpy_support.vtk_to_numpy(a)
        if not cells and target.dtype.kind in "iub":
            # rounded as vtkDataArray::InterpolateTuple rounds (half away from zero)
            v = np.where(v >= 0, np.floor(v + 0.5), np.ceil(v - 0.5))
        target[...] = v.reshape(target.shape)
        out.append((name, a))
    return out, found


def _sample_cells(data, dims, origin, spacing):
    """`data` (a data set or a composite data set: meshes, blocks of images) sampled cell by cell
    onto `dims` points at `origin`, `spacing` by the engine (schlieren_sample_cells), as the C++
    RefractiveIndex samples it (_sample_leaves): (image, the valid-point mask)."""
    d = [int(x) for x in dims]
    out = vtkImageData()
    out.SetDimensions(*d)
    out.SetOrigin(*origin)
    out.SetSpacing(*spacing)
    arrays, found = _sample_leaves(data, d[0] * d[1] * d[2], lambda found, pa, ca, mesh:
                                   _engine.sample_cells(found=found, dims=d, origin=origin,
                                                        spacing=spacing, point_arrays=pa,
                                                        cell_arrays=ca, **mesh))
    for _, a in arrays:
        out.GetPointData().AddArray(a)
    return out, found


def _sample_cells_at(data, points):
    """`data` sampled at `points` ((m, 3) float64) by the engine's points mode
    (schlieren_sample_cells_at), as the C++ filter samples a 2D input under Symmetry:
    ([(name, vtk array of m tuples)], found: a uint8 per point)."""
    at = np.ascontiguousarray(points, np.float64).reshape(-1, 3)
    return _sample_leaves(data, len(at), lambda found, pa, ca, mesh: _engine.sample_cells_at(
        at=at, found=found, point_arrays=pa, cell_arrays=ca, **mesh))


def _all_points(data):
    """x, y, z (float64, (n, 3)) of every point of every leaf, in order."""
    parts = []
    for leaf in _leaves(data):
        n = leaf.GetNumberOfPoints()
        points = leaf.GetPoints() if hasattr(leaf, "GetPoints") else None
        if points is not None and points.GetData() is not None:
            parts.append(numpy_support.vtk_to_numpy(points.GetData()).astype(np.float64)
                         .reshape(-1, 3))
        elif n:
            parts.append(np.array([leaf.GetPoint(i) for i in range(n)], np.float64))
    return np.concatenate(parts) if parts else np.zeros((0, 3))


def _image_input(data, grid=None, ranks=None):
    """`data` as an axis-aligned vtkImageData and its valid-point mask (None: all valid): itself,
    or resampled cell by cell by the engine (the C++ RefractiveIndex's sampler) onto `grid`
    (dims, origin, spacing: the engine's sampling grid). With `ranks` (MPI, collective) each
    rank samples its piece of a mesh and the samples are summed over the ranks (_summed)."""
    if isinstance(data, vtkImageData) and ranks is None:
        return data, None
    if ranks is not None:
        try:
            out, mask, refused = None, None, ""
            out, mask = _image_input(data, grid)
            if mask is None:
                mask = np.ones(out.GetNumberOfPoints(), np.uint8)
        except EngineError as e:
            refused = str(e)  # a cell type the sampler does not take
        agreed = ranks.failure(refused, "RefractiveIndex's resampled pieces")
        if agreed:
            raise EngineError(refused or agreed)
        return _summed(ranks, out, mask)
    dims, origin, spacing = grid
    out, mask = _sample_cells(data, dims, origin, spacing)  # meshes and blocks of images alike
    if not mask.all():
        # kept where it says something, as the C++ filter does: NumericalSchlieren leaves the
        # points outside the input's cells out of its gradients
        from vtkmodules.vtkCommonCore import vtkCharArray
        m = vtkCharArray()
        m.SetName("vtkValidPointMask")
        m.SetNumberOfTuples(mask.size)
        numpy_support.vtk_to_numpy(m)[:] = mask
        out.GetPointData().AddArray(m)
    return out, (None if mask.all() else mask)


def _names_everywhere(ranks, mine):
    """Every rank's names (`mine`: this rank's), each once, in rank order (collective)."""
    text = "\n".join(mine).encode()
    longest = int(ranks.comm.allreduce(np.array([len(text)], np.float64), "max")[0])
    names = []
    if longest:
        everyone = ranks.comm.allgather(np.frombuffer(text.ljust(longest, b"\0"), np.uint8))
        for theirs in everyone:
            for name in bytes(np.asarray(theirs, np.uint8)).rstrip(b"\0").decode().split("\n"):
                if name and name not in names:
                    names.append(name)
    return names


def _summed(ranks, grid, mask):
    """Under MPI, the resampled grid of every rank's piece on every rank (collective): the C++
    filter's Resample: per one-component point array any rank holds, value x found summed over
    the ranks and divided by the times found (in double, then float), the mask where any rank
    found the point. Arrays of more components are left out (as the C++ filter does)."""
    n = grid.GetNumberOfPoints()
    pd = grid.GetPointData()
    mine = [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())
            if pd.GetArray(i) is not None and pd.GetArray(i).GetNumberOfComponents() == 1 and
            pd.GetArrayName(i) != "vtkValidPointMask"]
    names = _names_everywhere(ranks, mine)
    found = (mask != 0).astype(np.float64)
    total = ranks.comm.allreduce(found, "sum")
    out = vtkImageData()
    out.CopyStructure(grid)
    for name in names:  # the same list, in the same order, on every rank
        a = pd.GetArray(name)
        values = np.zeros(n, np.float64)
        if a is not None and a.GetNumberOfComponents() == 1:
            v = numpy_support.vtk_to_numpy(a).astype(np.float64)
            values[found != 0] = v[found != 0]
        values = ranks.comm.allreduce(values, "sum")
        _add(out, name, np.where(total > 0, values / np.where(total > 0, total, 1.0), 0.0)
             .astype(np.float32))
    valid = (total > 0).astype(np.uint8)
    if not valid.all():
        from vtkmodules.vtkCommonCore import vtkCharArray
        m = vtkCharArray()
        m.SetName("vtkValidPointMask")
        m.SetNumberOfTuples(n)
        numpy_support.vtk_to_numpy(m)[:] = valid
        out.GetPointData().AddArray(m)
    return out, (None if valid.all() else valid)


def _amr_boxes(amr):
    """(level, index) of every box an overlapping AMR lists, level by level (VTK 9.6 renames
    GetNumberOfDataSets(level) GetNumberOfBlocks(level); the old name is used where it exists)."""
    count = getattr(amr, "GetNumberOfDataSets", None) or amr.GetNumberOfBlocks
    return [(level, b) for level in range(amr.GetNumberOfLevels()) for b in range(count(level))]


def _amr_block_list(amr, names=()):
    """The boxes an overlapping AMR holds as the engine takes them (schlieren_amr_*), as the C++
    filter reads them (Filters/SchlierenAMR.cxx): dicts of level, extent, origin, spacing and
    arrays {name: (values, is_cell)}, for each of `names` the box's point array of that name, else
    its cell array (float32 and float64 as they are, any other type as float64)."""
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    blocks = []
    for level, b in _amr_boxes(amr):
        g = (amr.GetDataSet if hasattr(amr, "GetDataSet") else amr.GetDataSetAsImageData)(level, b)
        if g is not None:
            extent = list(g.GetExtent())
            if g.GetNumberOfPoints() == 0:
                extent[1] = extent[0] - 1  # nothing to sample
            arrays = {}
            for name in names:
                a = g.GetPointData().GetArray(name)
                cells = a is None
                if cells:
                    a = g.GetCellData().GetArray(name)
                if a is None:
                    continue
                if a.GetDataType() not in (10, 11):  # VTK_FLOAT, VTK_DOUBLE
                    d = vtkDoubleArray()
                    d.DeepCopy(a)
                    a = d
                arrays[name] = (numpy_support.vtk_to_numpy(a), cells)
            blocks.append(dict(level=level, extent=extent, origin=g.GetOrigin(),
                               spacing=g.GetSpacing(), arrays=arrays))
    return blocks


def _amr_grid(amr, box, bytes_per_point, ranks=None):
    """The engine's automatic grid of an AMR over `box` (schlieren_amr_grid: the finest loaded
    level's spacing, capped by memory), as the C++ filter's; with `ranks` (MPI, collective) over
    the boxes every rank holds."""
    return _engine.amr_grid(amr.GetNumberOfLevels(), _amr_block_list(amr), box, bytes_per_point,
                            ranks)


def _amr_input(amr, dims, origin, spacing, ranks=None):
    """An overlapping AMR sampled onto `dims` points at `origin`, `spacing` by the engine
    (schlieren_amr_sample), as the C++ RefractiveIndex samples it: (image with every array any box
    holds as float32 and vtkValidPointMask where some point lies outside every box, valid mask or
    None where all are valid, notes). The boxes of a level that overlap are refused first, with
    the C++ filter's message."""
    boxes = []
    for level, b in _amr_boxes(amr):
        lo, hi = [0] * 3, [0] * 3
        amr.GetAMRBox(level, b).GetDimensions(lo, hi)  # its corners
        boxes.append((level, lo, hi))
    _engine.amr_overlap(boxes)
    names = []
    for leaf in _leaves(amr):
        for attributes in (leaf.GetPointData(), leaf.GetCellData()):
            for i in range(attributes.GetNumberOfArrays()):
                n = attributes.GetArrayName(i)
                if n and n not in names and n not in ("vtkGhostType", "vtkValidPointMask"):
                    names.append(n)
    if ranks is not None:
        names = _names_everywhere(ranks, names)  # every rank's boxes' arrays (MPI)
    d = [int(x) for x in dims]
    image = vtkImageData()
    image.SetDimensions(*d)
    image.SetOrigin(*origin)
    image.SetSpacing(*spacing)
    # the C++ filter's structure: its spacing and origin as it sets them, read back
    mask, sampled, notes = _engine.amr_sample(amr.GetNumberOfLevels(), _amr_block_list(amr, names),
                                              names, d, image.GetOrigin(), image.GetSpacing(),
                                              ranks)
    for name in names:
        if name in sampled:
            _add(image, name, sampled[name])
    if not mask.all():
        from vtkmodules.vtkCommonCore import vtkCharArray
        m = vtkCharArray()
        m.SetName("vtkValidPointMask")
        m.SetNumberOfTuples(mask.size)
        numpy_support.vtk_to_numpy(m)[:] = mask
        image.GetPointData().AddArray(m)
    return image, (None if mask.all() else mask), notes


def _image_validity(image):
    """The flow's points of an image input as the C++ filter's Validity reads them (a uint8 array,
    1 in the flow), or None where all are: vtkValidPointMask 0 and hidden points (ghost array)
    are outside it."""
    n = image.GetNumberOfPoints()
    valid = np.ones(n, np.uint8)
    mask = _point_array(image, "vtkValidPointMask")
    if mask is not None and mask.ndim == 1:
        valid[mask == 0] = 0
    ghosts = image.GetPointData().GetArray("vtkGhostType")
    if ghosts is not None:
        from vtkmodules.vtkCommonDataModel import vtkDataSetAttributes
        g = numpy_support.vtk_to_numpy(ghosts)
        valid[(g.astype(np.int64) & vtkDataSetAttributes.HIDDENPOINT) != 0] = 0
    return None if valid.all() else valid


def _point_array(image, name):
    a = image.GetPointData().GetArray(name)
    return None if a is None else numpy_support.vtk_to_numpy(a)


def _add(image, name, values, components=None):
    a = numpy_support.numpy_to_vtk(np.ascontiguousarray(values), deep=1)
    a.SetName(name)
    image.GetPointData().AddArray(a)
    return a


def _field_number(image, name, value):
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    a = vtkDoubleArray()
    a.SetName(name)
    for v in (value if isinstance(value, (list, tuple)) else [value]):  # bench_range: two
        a.InsertNextValue(v)
    image.GetFieldData().AddArray(a)


def _field_string(image, name, value):
    from vtkmodules.vtkCommonCore import vtkStringArray
    a = vtkStringArray()
    a.SetName(name)
    a.InsertNextValue(value)
    image.GetFieldData().AddArray(a)


class RefractiveScene(_Properties):
    """Analytic scenes with known answers (the RefractiveScene proxy), as vtkImageData."""

    _defaults = dict(Scene="GaussianSphere", Dimensions=[64, 64, 64],
                     Bounds=[-1.0, 1.0, -1.0, 1.0, -1.0, 1.0], Amplitude=1e-4, Width=0.25,
                     Radius=1.0, Center=[0.0, 0.0, 0.0], GradientA=1.0, GradientB=0.01, Mach=2.0,
                     Density=1.2, Time=1.0, Body="None", BodyRadius=0.25,
                     BodyCenter=[0.0, 0.0, 0.0], BodyAxis=[1.0, 0.0, 0.0])
    _entries = dict(Scene=["Uniform", "GaussianSphere", "LuneburgLens", "LinearGradient",
                           "NormalShock", "HeliumPlume", "BlastWave"],
                    Body=["None", "Sphere", "Cylinder"])
    _ranges = dict(Amplitude=(-0.9, 10.0), Width=(1e-12, np.inf), Radius=(1e-12, np.inf),
                   Mach=(1.0, 100.0), Density=(1e-12, 1e6), Time=(1e-6, 1e6),
                   BodyRadius=(1e-12, np.inf))

    def __init__(self, **kwargs):
        _Properties.__init__(self, 0, **kwargs)

    def _grid(self):
        for name, (lo, hi) in self._ranges.items():
            v = float(getattr(self, name))
            if not (lo <= v <= hi) or np.isinf(v):
                raise EngineError("%s is %g: it must be in [%g, %s]." % (
                    name, v, lo, "a finite value" if np.isinf(hi) else "%g" % hi))
        dims = [int(d) for d in self.Dimensions]
        origin, spacing = [0.0] * 3, [0.0] * 3
        for a in range(3):
            lo, hi = float(self.Bounds[2 * a]), float(self.Bounds[2 * a + 1])
            if dims[a] < 1 or dims[a] > 2 ** 31 - 1:
                raise EngineError("Dimensions must be at least 1 along each axis (and fit a "
                                  "32-bit integer); got %s." % dims)
            if dims[a] > 1 and not hi > lo:
                raise EngineError("Bounds along axis %d are [%g, %g]: the max must exceed the "
                                  "min." % (a, lo, hi))
            origin[a] = lo
            spacing[a] = (hi - lo) / (dims[a] - 1) if dims[a] > 1 else (hi - lo if hi > lo
                                                                       else 1.0)
        return dims, origin, spacing

    def RequestInformation(self, request, inInfo, outInfo):
        try:
            dims, origin, spacing = self._grid()
        except EngineError as e:
            return self._fail(str(e))
        info = outInfo.GetInformationObject(0)
        info.Set(SDDP.WHOLE_EXTENT(), 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1)
        info.Set(vtkImageData.ORIGIN(), *origin)
        info.Set(vtkImageData.SPACING(), *spacing)
        # any piece (under MPI each rank fills its own, as the C++ source does)
        info.Set(self.CAN_PRODUCE_SUB_EXTENT(), 1)
        return 1

    def RequestData(self, request, inInfo, outInfo):
        out = vtkImageData.GetData(outInfo)
        info = outInfo.GetInformationObject(0)
        try:
            dims, origin, spacing = self._grid()
            ext = list(info.Get(SDDP.UPDATE_EXTENT())) if info.Has(SDDP.UPDATE_EXTENT()) else \
                [0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1]
            if _empty(ext):
                out.Initialize()
                out.SetExtent(*ext)
                return 1  # an empty piece
            settings = {k: self._values[k] for k in self._defaults
                        if k not in ("Dimensions", "Bounds")}
            # the requested piece as a grid of its own whose first point is its extent's (the
            # C++ source's arithmetic: the whole grid where the piece is the whole)
            arrays = _engine.fill_scene(
                settings, [ext[2 * a + 1] - ext[2 * a] + 1 for a in range(3)],
                [origin[a] + ext[2 * a] * spacing[a] for a in range(3)], spacing)
        except EngineError as e:
            return self._fail(str(e))
        out.SetExtent(*ext)
        out.SetOrigin(*origin)
        out.SetSpacing(*spacing)
        n1 = _add(out, "n_minus_1", arrays["n_minus_1"])
        out.GetPointData().SetScalars(n1)
        _add(out, "density", arrays["density"])
        if "mixture_fraction" in arrays:
            _add(out, "mixture_fraction", arrays["mixture_fraction"])
        if "solid" in arrays:
            _add(out, "solid", arrays["solid"])
        return 1


class _TimeStepCache:
    """RefractiveIndex's outputs kept per time step, so that an animation played again neither
    resamples nor executes its upstream again: the engine's rule (schlieren_time_cache_find and
    _insert, OpenCL/SchlierenTimeStore.h, as the C++ filter's SchlierenTimeCache.h): keys of time,
    change token and extent, a quarter of the memory available, the oldest out first. The entries
    (time, token, extent, bytes, image) oldest first, the images shallow copies."""

    def __init__(self):
        self.entries, self.computed, self.served = [], 0, 0

    def find(self, key):
        i, _ = _engine.time_cache_find([e[:4] for e in self.entries], *key)
        return None if i < 0 else self.entries[i][4]

    def insert(self, key, image):
        nbytes = 1024.0 * image.GetActualMemorySize()
        keep, kept, _ = _engine.time_cache_insert([e[:4] for e in self.entries], *key,
                                                  nbytes=nbytes)
        self.entries = [e for e, k in zip(self.entries, keep) if k]
        if kept:
            copy = type(image)()
            copy.ShallowCopy(image)
            self.entries.append((key[0], key[1], key[2], nbytes, copy))

    def fields(self, out, served):
        """The cache's counters in the output's field data (its own copy: the kept entry shares
        it), as the C++ filter's CacheFields."""
        from vtkmodules.vtkCommonDataModel import vtkFieldData
        held = sum(e[3] for e in self.entries)
        _, budget = _engine.time_cache_find([e[:4] for e in self.entries], 0.0, 0,
                                            (0, -1, 0, -1, 0, -1))
        fd = vtkFieldData()
        if out.GetFieldData() is not None:
            fd.ShallowCopy(out.GetFieldData())
        out.SetFieldData(fd)
        for name, value in (("index_computed", self.computed),
                            ("index_from_cache", 1 if served else 0),
                            ("index_cache_entries", len(self.entries)),
                            ("index_cache_bytes", held), ("index_cache_budget", budget)):
            _field_number(out, name, value)


def _inside_shell(shell, image, inside, dims):
    """Marks `inside` (a byte a point of `image`) at the points inside the one closed `shell`,
    tested only within its bounds (vtkSelectEnclosedPoints, as the C++ filter's MarkInsideShell).
    Returns whether its bounds overlap the grid, None where the inside test gave no result."""
    from vtkmodules.vtkFiltersModeling import vtkSelectEnclosedPoints
    b = shell.GetBounds()
    origin, spacing, ext = image.GetOrigin(), image.GetSpacing(), image.GetExtent()
    sub = [0] * 6
    for a in range(3):
        sub[2 * a] = max(ext[2 * a], int(math.floor((b[2 * a] - origin[a]) / spacing[a])))
        sub[2 * a + 1] = min(ext[2 * a + 1],
                             int(math.ceil((b[2 * a + 1] - origin[a]) / spacing[a])))
    if not all(sub[2 * a] <= sub[2 * a + 1] for a in range(3)):
        return False
    box = vtkImageData()
    box.SetExtent(sub)
    box.SetOrigin(origin)
    box.SetSpacing(spacing)
    select = vtkSelectEnclosedPoints()
    select.SetInputData(box)
    select.SetSurfaceData(shell)
    select.CheckSurfaceOff()  # checked before, with the engine's message
    select.Update()
    selected = select.GetOutput().GetPointData().GetArray("SelectedPoints")
    if selected is None:
        return None
    enclosed = numpy_support.vtk_to_numpy(selected).reshape(selected.GetNumberOfTuples(), -1)
    enclosed = (enclosed[:, 0] != 0).reshape(sub[5] - sub[4] + 1, sub[3] - sub[2] + 1,
                                             sub[1] - sub[0] + 1)
    grid = inside.reshape(dims[2], dims[1], dims[0])
    grid[sub[4] - ext[4]:sub[5] - ext[4] + 1, sub[2] - ext[2]:sub[3] - ext[2] + 1,
         sub[0] - ext[0]:sub[1] - ext[0] + 1] |= enclosed.astype(np.uint8)
    return True


def _body_inside(surface, image):
    """RefractiveIndex's Body input, the front end's part (the C++ filter's SurfaceSolid): the
    closed `surface` triangulated, each connected shell tested alone within its bounds and the
    results ORed. Returns (what was found: schlieren_index_field's BodySurface, the points inside
    (a byte a point of `image`, None where refused), whether a shell's bounds overlap the grid)."""
    from vtkmodules.vtkFiltersCore import vtkPolyDataConnectivityFilter, vtkTriangleFilter
    from vtkmodules.vtkFiltersModeling import vtkSelectEnclosedPoints
    if surface.GetNumberOfPolys() == 0 and surface.GetNumberOfStrips() == 0:
        return "NoPolygons", None, False
    triangles = vtkTriangleFilter()
    triangles.SetInputData(surface)
    triangles.PassLinesOff()
    triangles.PassVertsOff()
    triangles.Update()
    closed = triangles.GetOutput()
    if not vtkSelectEnclosedPoints.IsSurfaceClosed(closed):
        return "NotClosed", None, False
    shells = vtkPolyDataConnectivityFilter()
    shells.SetInputData(closed)
    shells.SetExtractionModeToAllRegions()
    shells.Update()
    regions = shells.GetNumberOfExtractedRegions()
    dims = image.GetDimensions()
    inside = np.zeros(int(dims[0]) * dims[1] * dims[2], np.uint8)
    pieces = [closed] if regions <= 1 else []
    for r in range(regions if regions > 1 else 0):
        one = vtkPolyDataConnectivityFilter()
        one.SetInputData(closed)
        one.SetExtractionModeToSpecifiedRegions()
        one.AddSpecifiedRegion(r)
        one.Update()
        pieces.append(one.GetOutput())
    overlaps = False
    for shell in pieces:
        found = _inside_shell(shell, image, inside, dims)
        if found is None:
            return "NoInsideTest", None, False
        overlaps = overlaps or found
    return "Inside", inside, overlaps


class RefractiveIndex(_Properties):
    """n - 1 from CFD fields by every index model of the engine (Passthrough, GladstoneDale,
    GladstoneDaleMixture, IdealGas, Ciddor), resampled onto an image as needed.

    Model Automatic chooses as the C++ filter does, by the same engine function
    (schlieren_index_choices): Passthrough on an array named as n - 1, else GladstoneDale on one
    named as a density, else IdealGas on a temperature and a pressure, else Passthrough of n; a
    named InputArray decides by its name. An empty array property takes the first array named as
    what it holds (the C++ filter's names). The work on the grid (the model, the ambient fill, the
    gradient, the bodies, the field data) is the engine's schlieren_index_field, the C++
    filter's.

    Every property of the RefractiveIndex proxy is here with the proxy's default (the ParaView
    names: SelectInputArray is InputArray). Symmetry Planar (a 2D plane extruded over Span) and
    Axisymmetric (an r-z half plane revolved about SymmetryAxis, or an OpenFOAM wedge about its
    own axis: AxisFromWedge) are the engine's (schlieren_symmetry_plan, _samples, _expand, as the
    C++ filter's): this front end samples the mesh where the engine says. Bodies: from the grid's holes (BodyFromGrid, BodyWallFaces), from the
    voids beside a mesh's walls where it has a velocity (the engine's kinds of its faces), a solid
    array (SolidArray, an upstream `solid`), and a closed body surface on the optional input
    port 1 (Body, vtkPolyData: the grid points inside it, found as the C++ filter finds them)."""

    _defaults = dict(
        Model="Automatic", InputArray="", TemperatureArray="", PressureArray="",
        MixtureFractionArray="", Species1Array="", Species2Array="", Species3Array="",
        Species4Array="", HumidityArray="", CO2Array="", PassthroughHoldsN=0, Gas="Custom",
        GladstoneDaleConstant=2.256e-4, MolarMass=0.0289641, MixtureComposition="MixtureFraction",
        IdealGasComposition="Gas", MixtureGas0="Air", MixtureGas1="He", NumberOfSpecies=1,
        SpeciesGases=[6, 8, 1, 5], SpeciesGladstoneDale=[2.256e-4] * 4,
        SpeciesMolarMass=[0.0289641] * 4, BalanceGas="Air", BalanceGladstoneDale=2.256e-4,
        BalanceMolarMass=0.0289641, DensityReference=1.0, TemperatureUnit="Kelvin",
        TemperatureReference=1.0, PressureUnit="Pa", PressureReference=1.0, PressureOffset=0.0,
        Humidity=0.0, HumidityFromArray=0, HumidityMeasure="RelativeHumidity", CO2=450.0,
        CO2FromArray=0, Wavelength=632.8, Symmetry="None", Span=1.0, SymmetryAxis="X",
        AxisFromWedge=1, SamplingDimensions=[0, 0, 0], AutomaticDimension=128,
        UseSamplingBounds=0, SamplingBounds=[0.0, 1.0, 0.0, 1.0, 0.0, 1.0], AmbientMode="Extend",
        AmbientValue=2.7164e-4, BodyFromGrid=1, BodyWallFaces=[0, 0, 0, 0, 0, 0],
        SolidArray="None")
    _range_proxy = "RefractiveIndex"
    # the enumerations' entries: the engine's (schlieren_property_entries, the C++ filter's check)
    _entries = {name: [text for _, text in _engine.property_entries("RefractiveIndex", name)]
                for name in _defaults}
    _entries = {name: texts for name, texts in _entries.items() if texts}
    # implemented here: the properties in _implemented (the others are held at their defaults)
    # the index models' settings, handed to the engine by name (schlieren_index_model)
    _model_settings = ("PassthroughHoldsN", "Gas", "GladstoneDaleConstant", "MolarMass",
                       "MixtureComposition", "IdealGasComposition", "MixtureGas0", "MixtureGas1",
                       "NumberOfSpecies", "SpeciesGases", "SpeciesGladstoneDale",
                       "SpeciesMolarMass", "BalanceGas", "BalanceGladstoneDale",
                       "BalanceMolarMass", "DensityReference", "TemperatureUnit",
                       "TemperatureReference", "PressureUnit", "PressureReference",
                       "PressureOffset", "Humidity", "HumidityMeasure", "CO2", "Wavelength")
    _implemented = {"Model", "InputArray", "Symmetry", "Span", "SymmetryAxis", "AxisFromWedge",
                    "SamplingDimensions", "AutomaticDimension",
                    "UseSamplingBounds", "SamplingBounds", "BodyWallFaces", "SolidArray",
                    "AmbientMode", "AmbientValue", "BodyFromGrid", "TemperatureArray",
                    "PressureArray",
                    "MixtureFractionArray", "Species1Array", "Species2Array", "Species3Array",
                    "Species4Array", "HumidityArray", "CO2Array", "HumidityFromArray",
                    "CO2FromArray"} | set(_model_settings)
    _implemented_entries = {}
    def _check(self, name, value):
        value = _Properties._check(self, name, value)
        if name.endswith("Array") and isinstance(value, (list, tuple)):
            value = value[-1]  # ParaView's ["POINTS", name]
        if name in self._implemented_entries and value not in self._implemented_entries[name]:
            raise ValueError("RefractiveIndex: %s %r is not available in the Python front end "
                             "(it has: %s); the C++ plugin has it"
                             % (name, value, ", ".join(self._implemented_entries[name])))
        if name not in self._implemented and value != self._defaults[name] and not (
                isinstance(value, list) and [float(v) for v in value] ==
                [float(v) for v in self._defaults[name]]):
            raise ValueError("RefractiveIndex: %s is not available in the Python front end: it "
                             "takes only its default %r (got %r); the C++ plugin has it"
                             % (name, self._defaults[name], value))
        return value

    def __init__(self, **kwargs):
        _Properties.__init__(self, 2, **kwargs)
        object.__setattr__(self, "_time_cache", _TimeStepCache())

    def FillInputPortInformation(self, port, info):
        if port == 1:
            # the optional Body: a closed surface whose inside is solid (the C++ filter's port 1)
            info.Set(self.INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData")
            info.Set(self.INPUT_IS_OPTIONAL(), 1)
            return 1
        # a data set or a composite data set as one input (the C++ filter's types): the blocks
        # are resampled onto one image, not executed one by one into a multiblock of images
        info.Set(self.INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet")
        info.Append(self.INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet")
        return 1

    def RequestInformation(self, request, inInfo, outInfo):
        # an image's grid is the input's (the executive copied it); a resampled input's grid is
        # known from its bounds, known once it has executed: it is updated now, as the C++ filter
        # does, and the grid the cell sampler will fill is given downstream (SchlierenImage
        # plans its film from it; without it a view asks for an empty extent and shows nothing)
        src = inInfo[0].GetInformationObject(0)
        info = outInfo.GetInformationObject(0)
        ranks = _ranks()
        if ranks is not None:
            # under MPI any piece of the grid (the C++ filter's): computed from the input's piece
            # grown by a point, or cut from the whole resampled grid
            info.Set(self.CAN_PRODUCE_SUB_EXTENT(), 1)
        if isinstance(vtkDataObject.GetData(src), vtkImageData) and self.Symmetry == "None":
            return 1  # (the data object exists, empty, before the input executes)
        connection = self.GetInputConnection(0, 0) if self.GetNumberOfInputConnections(0) else None
        if connection is not None and src.Has(SDDP.WHOLE_EXTENT()):
            src.Set(SDDP.UPDATE_EXTENT(), src.Get(SDDP.WHOLE_EXTENT()), 6)
        spread = _spread(ranks, vtkDataObject.GetData(src), self.Symmetry)
        if connection is not None and ranks is not None:
            # a mesh: this rank's piece (resampled here, the samples summed over the ranks); made
            # a volume or an AMR: the whole input on every rank (docs/PARALLEL.md)
            src.Set(SDDP.UPDATE_PIECE_NUMBER(), ranks.rank if spread else 0)
            src.Set(SDDP.UPDATE_NUMBER_OF_PIECES(), ranks.size if spread else 1)
            src.Set(SDDP.UPDATE_NUMBER_OF_GHOST_LEVELS(), 0)
        if connection is not None:
            connection.GetProducer().Update(connection.GetIndex())
        data = vtkDataObject.GetData(src)
        info.Set(SDDP.WHOLE_EXTENT(), 0, -1, 0, -1, 0, -1)
        if not isinstance(data, (vtkDataSet, vtkCompositeDataSet)) or \
                (data.GetNumberOfPoints() == 0 and spread is None):
            return 1  # RequestData says why
        if self.Symmetry != "None":
            # the engine's grid for the 2D input (RequestData says why where there is none)
            try:
                plan = self._symmetry_plan(data)
            except (EngineError, ValueError):
                return 1
            d, o, h = plan["dims"], plan["origin"], plan["spacing"]
            info.Set(SDDP.WHOLE_EXTENT(), 0, d[0] - 1, 0, d[1] - 1, 0, d[2] - 1)
            info.Set(vtkImageData.ORIGIN(), *o)
            info.Set(vtkImageData.SPACING(), *h)
            return 1
        # the grid the cell sampler fills: the engine's (the C++ filter's); under MPI over every
        # rank's piece
        try:
            grid = self._sampling_grid(data, spread)
        except EngineError:
            if spread is None:
                raise
            return 1  # no rank has a point, or too many: RequestData says why on every rank
        dims = grid["dims"]
        info.Set(SDDP.WHOLE_EXTENT(), 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1)
        info.Set(vtkImageData.ORIGIN(), *grid["origin"])
        info.Set(vtkImageData.SPACING(), *grid["spacing"])
        return 1

    def _cache_key(self, src, info):
        """The key of this update in the per-time-step cache (time, change token, extent), as the
        C++ filter's: None where the output is not cached (the input has no time steps or no time
        is asked for). The token is the pipeline's modified time (this algorithm's and every
        upstream one's)."""
        pipeline_mtime = getattr(self.GetExecutive(), "GetPipelineMTime", None)
        if _ranks() is not None:
            return None  # not under MPI (the C++ filter's rule)
        if src is None or info is None or not src.Has(SDDP.TIME_STEPS()) or \
                not info.Has(SDDP.UPDATE_TIME_STEP()) or pipeline_mtime is None:
            return None
        extent = info.Get(SDDP.UPDATE_EXTENT()) if info.Has(SDDP.UPDATE_EXTENT()) else \
            (0, -1, 0, -1, 0, -1)
        return info.Get(SDDP.UPDATE_TIME_STEP()), pipeline_mtime(), tuple(extent)

    def RequestUpdateExtent(self, request, inInfo, outInfo):
        src = inInfo[0].GetInformationObject(0)
        key = self._cache_key(src, outInfo.GetInformationObject(0))
        held = vtkDataObject.GetData(src)
        if key is not None and self._time_cache.find(key) is not None and held is not None and \
                held.GetInformation().Has(vtkDataObject.DATA_TIME_STEP()):
            # a time step kept: the input stays at the time it holds (it does not execute again)
            src.Set(SDDP.UPDATE_TIME_STEP(),
                    held.GetInformation().Get(vtkDataObject.DATA_TIME_STEP()))
        # the engine's rule (schlieren_input_request, the C++ filter's): a resampled input whole
        # (under MPI this rank's piece of a mesh), a symmetric one whole on every rank, an image
        # over this output's piece of the update extent grown by one point for the central
        # differences
        info = outInfo.GetInformationObject(0)
        ranks = _ranks()
        image = isinstance(held, vtkImageData) and src.Has(SDDP.WHOLE_EXTENT()) and \
            info.Has(SDDP.UPDATE_EXTENT())
        resampled = not image
        spread = _spread(ranks, held, self.Symmetry) if resampled else None

        def asked(key, default):
            return info.Get(key) if ranks is not None and info.Has(key) else default
        piece, pieces, extent = _engine.input_request(
            resampled, self.Symmetry != "None",
            rank=ranks.rank if spread else 0, ranks=ranks.size if spread else 1,
            piece=asked(SDDP.UPDATE_PIECE_NUMBER(), 0),
            pieces=asked(SDDP.UPDATE_NUMBER_OF_PIECES(), 1),
            ghosts=asked(SDDP.UPDATE_NUMBER_OF_GHOST_LEVELS(), 0),
            split_mode=asked(vtkExtentTranslator.UPDATE_SPLIT_MODE(), 3),
            update_extent=info.Get(SDDP.UPDATE_EXTENT()) if image else (0, -1, 0, -1, 0, -1),
            whole_extent=src.Get(SDDP.WHOLE_EXTENT()) if image else (0, -1, 0, -1, 0, -1))
        if (extent is None or (ranks is None and _empty(extent))) and \
                src.Has(SDDP.WHOLE_EXTENT()):
            # whole (in one process an empty update extent too: it makes no empty piece)
            extent = src.Get(SDDP.WHOLE_EXTENT())
        if extent is not None:
            src.Set(SDDP.UPDATE_EXTENT(), extent, 6)
        src.Set(SDDP.UPDATE_PIECE_NUMBER(), piece)
        src.Set(SDDP.UPDATE_NUMBER_OF_PIECES(), pieces)
        if ranks is not None:
            src.Set(SDDP.UPDATE_NUMBER_OF_GHOST_LEVELS(), 0)
        return 1

    # the array properties by role, in the engine's order (schlieren_index_field)
    _role_properties = ("InputArray", "TemperatureArray", "PressureArray", "MixtureFractionArray",
                        "Species1Array", "Species2Array", "Species3Array", "Species4Array",
                        "HumidityArray", "CO2Array")

    def _note(self, note):
        """A note for the user, said once for the settings it was said for (the C++ filter's
        SayNote: ParaView's Output Messages as plain text); under MPI by rank 0."""
        from vtkmodules.vtkCommonCore import vtkOutputWindow
        ranks = _ranks()
        if ranks is not None and ranks.rank != 0:
            return
        said = self.__dict__.get("_notes_said")
        if said is None or said[0] != self.GetMTime():
            said = (self.GetMTime(), set())
            object.__setattr__(self, "_notes_said", said)
        if note not in said[1]:
            said[1].add(note)
            vtkOutputWindow.GetInstance().DisplayText(note + "\n")

    _sampling_names = ("SamplingDimensions", "AutomaticDimension", "UseSamplingBounds",
                       "SamplingBounds")

    def _sampling_grid(self, data, ranks=None):
        """The grid a resampled input is sampled onto, the engine's (schlieren_sampling_box and
        _grid: the C++ filter's rule, with its messages): dict(dims, origin, spacing, amr: an AMR
        input's automatic grid where it set the dimensions, else None)."""
        settings = {k: self._values[k] for k in self._sampling_names}
        box = _engine.sampling_box(
            settings, None if self.UseSamplingBounds else _bounds_everywhere(data, ranks))
        array_bytes = _array_bytes(data)
        amr = None
        if min(int(d) for d in self.SamplingDimensions) <= 0 and \
                isinstance(data, vtkOverlappingAMR) and (data.GetNumberOfPoints() or
                                                          ranks is not None):
            # an AMR: its finest level's spacing, capped by memory (with the engine's share;
            # under MPI over every rank's boxes)
            amr = _amr_grid(data, box, 1.0 + 16.0 + array_bytes + 21.0, ranks)
        dims, origin, spacing = _engine.sampling_grid(settings, box, array_bytes,
                                                      amr["dims"] if amr else None)
        return dict(dims=dims, origin=origin, spacing=spacing, box=box, amr=amr)

    def _followed_grid(self, data, info, ranks=None):
        """RequestInformation's grid (`info`), made to follow a mesh that moves over time (the
        engine's schlieren_follow_bounds, the C++ filter's): (dims, origin, spacing), note or
        None."""
        if not info.Has(vtkImageData.ORIGIN()) or not info.Has(SDDP.WHOLE_EXTENT()):
            grid = self._sampling_grid(data, ranks)
            return (grid["dims"], grid["origin"], grid["spacing"]), None
        whole = info.Get(SDDP.WHOLE_EXTENT())
        dims = [whole[2 * a + 1] - whole[2 * a] + 1 for a in range(3)]
        origin, spacing = list(info.Get(vtkImageData.ORIGIN())), list(info.Get(vtkImageData.SPACING()))
        bounds = None if self.UseSamplingBounds else _bounds_everywhere(_internal_mesh(data), ranks)
        moved = None if bounds is None else \
            _engine.follow_bounds(whole, origin, spacing, bounds)
        if moved is None:
            return (dims, origin, spacing), None
        info.Set(vtkImageData.ORIGIN(), *moved[0])
        info.Set(vtkImageData.SPACING(), *moved[1])
        return (dims, moved[0], moved[1]), moved[2]

    def _symmetry_plan(self, data):
        """The engine's plan (schlieren_symmetry_plan) for the 2D input `data`: its checks (the C++
        filter's messages), its wedge, its grid."""
        mesh = _internal_mesh(data)
        settings = {k: self._values[k] for k in (
            "Symmetry", "SymmetryAxis", "Span", "AxisFromWedge", "SamplingDimensions",
            "AutomaticDimension", "UseSamplingBounds", "SamplingBounds")}
        bounds = _leaf_bounds(mesh)
        if isinstance(mesh, vtkImageData):
            return _engine.symmetry_plan(settings, bounds, image=(
                mesh.GetExtent(), mesh.GetOrigin(), mesh.GetSpacing()))
        return _engine.symmetry_plan(settings, bounds,
                                     None if bounds is None else _all_points(mesh),
                                     one_data_set=isinstance(mesh, vtkDataSet))

    def _symmetric_input(self, data):
        """The 2D input made a volume on the engine's grid: (image with every point array of the
        input sampled there as float32, valid mask or None where all are valid, the plan)."""
        plan = self._symmetry_plan(data)
        mesh = _internal_mesh(data)
        count = int(np.prod(plan["dims"]))
        _engine.check_memory(count * (8.0 + 1.0 + 22.0), "Resampling onto %d x %d x %d points"
                             % tuple(plan["dims"]), "Lower SamplingDimensions or "
                             "AutomaticDimension.")
        points, sample_of = _engine.symmetry_samples(plan)
        # the engine's cell sampler at the plan's points (its points mode: the C++ filter's)
        arrays, found = _sample_cells_at(mesh, points)
        _, valid = _engine.symmetry_expand(sample_of, len(points), sample_valid=found)
        image = vtkImageData()
        image.SetDimensions(*plan["dims"])
        image.SetOrigin(*plan["origin"])
        image.SetSpacing(*plan["spacing"])
        if not valid.all():  # the mask first, as the C++ filter's grid has it
            from vtkmodules.vtkCommonCore import VTK_CHAR
            mask = numpy_support.numpy_to_vtk(valid.astype(np.int8), deep=1, array_type=VTK_CHAR)
            mask.SetName("vtkValidPointMask")
            image.GetPointData().AddArray(mask)
        for name, a in arrays:
            values, _ = _engine.symmetry_expand(sample_of, len(points),
                                                values=numpy_support.vtk_to_numpy(a))
            _add(image, name, values)
        return image, (None if valid.all() else valid), plan

    def _point_fields(self, data, ranks):
        """The input with the arrays the model reads that it has as cell data only turned into
        point data, and the note (_point_fields): the model and arrays resolved on the input's
        names as the C++ filter's ResolveChoices (a choice that fails here fails again below,
        on the sampled grid, with its message)."""
        names, places = _input_arrays(data)
        fallback = ""
        for leaf in _leaves(data):
            pd = leaf.GetPointData()
            a = pd.GetScalars()
            for i in range(pd.GetNumberOfArrays()):
                if a is None and pd.GetArrayName(i) and pd.GetArrayName(i) != "vtkValidPointMask":
                    a = pd.GetArray(i)
            if a is not None and a.GetName():
                fallback = a.GetName()
                break
        if ranks is not None:  # every rank's (collective)
            names = _names_everywhere(ranks, names)
            places = _names_everywhere(ranks, places)
            fallback = ([n for n in _names_everywhere(ranks, [fallback]) if n] or [""])[0]
        settings = {k: self._values[k] for k in self._model_settings}
        settings.update({k: self._values[k] or "" for k in self._role_properties})
        settings["Model"] = self.Model
        try:
            choice = _engine.index_choices(settings, names, fallback)
        except EngineError:
            return data, ""
        settings.update(choice["arrays"])
        settings.update(Model=choice["model"], PassthroughHoldsN=int(choice["holds_n"]),
                        HumidityFromArray=int(self.HumidityFromArray),
                        CO2FromArray=int(self.CO2FromArray))
        return _point_fields(data, settings, names, places)

    def RequestData(self, request, inInfo, outInfo):
        data = vtkDataObject.GetData(inInfo[0])
        out = vtkImageData.GetData(outInfo)
        ranks = _ranks()
        # under MPI an image is computed piece by piece (the engine's collective
        # schlieren_index_field_piece); a failure before it is agreed on with the other ranks
        pieces = ranks is not None and isinstance(data, vtkImageData) and \
            self.Symmetry == "None"
        collective = [False]
        try:
            if pieces:
                whole = list(inInfo[0].GetInformationObject(0).Get(SDDP.WHOLE_EXTENT()))
                out_ext = list(outInfo.GetInformationObject(0).Get(SDDP.UPDATE_EXTENT()))
                grid_ext = list(data.GetExtent()) if data.GetNumberOfPoints() else \
                    [0, -1, 0, -1, 0, -1]
                if _empty(out_ext) or _empty(grid_ext):
                    collective[0] = True
                    agreed = _agreed(ranks, "", _INDEX_STEP)
                    if agreed:
                        return self._fail(agreed)
                    _engine.index_field_piece({"Model": "Passthrough"}, [0, -1, 0, -1, 0, -1],
                                              out_ext, whole, [1.0] * 3, {}, ranks=ranks)
                    out.Initialize()
                    return 1  # this rank holds no point of the image
                if any(out_ext[2 * a] < grid_ext[2 * a] or out_ext[2 * a + 1] >
                       grid_ext[2 * a + 1] for a in range(3)):
                    raise EngineError("The input's extent (%s) does not cover the requested "
                                      "extent (%s); the upstream filter did not honour the "
                                      "update request." % (" ".join(map(str, grid_ext)),
                                                           " ".join(map(str, out_ext))))
            if data is None or not isinstance(data, (vtkDataSet, vtkCompositeDataSet)):
                raise EngineError("RefractiveIndex needs a data set or a composite data set; "
                                  "got %s." % (data.GetClassName() if data else "nothing"))
            if isinstance(data, vtkCompositeDataSet) and \
                    data.GetNumberOfPoints() == 0 and _spread(ranks, data, self.Symmetry) is None:
                raise EngineError("RefractiveIndex: the input (%s) has no points."
                                  % data.GetClassName())
            key = self._cache_key(inInfo[0].GetInformationObject(0),
                                  outInfo.GetInformationObject(0))
            kept = None if key is None else self._time_cache.find(key)
            if kept is not None:
                # this time step, computed before with the same pipeline: that image again
                out.ShallowCopy(kept)
                out.GetInformation().Set(vtkDataObject.DATA_TIME_STEP(), key[0])
                self._time_cache.served += 1
                self._time_cache.fields(out, True)
                return 1
            data, cell_note = self._point_fields(data, None if pieces else ranks)
            symmetric = self.Symmetry != "None"
            resampled = symmetric or not isinstance(data, vtkImageData)
            notes, amr_numbers, plan = [], [], None
            if symmetric:
                image, valid, plan = self._symmetric_input(data)
                for w in plan["warnings"]:
                    self._warn(w)
            elif isinstance(data, vtkOverlappingAMR):
                # the engine's AMR sampler (the C++ filter's), and its numbers and notes
                # (under MPI over the boxes every rank holds, collective: the C++ filter's)
                spread = _spread(ranks, data, self.Symmetry)
                sampling = self._sampling_grid(data, spread)
                grid = sampling["amr"] or _amr_grid(data, sampling["box"], 1.0 + 16.0 + 64.0 + 21.0,
                                                    spread)
                automatic = min(int(v) for v in self.SamplingDimensions) <= 0
                image, valid, notes = _amr_input(data, sampling["dims"], sampling["origin"],
                                                 sampling["spacing"], spread)
                notes = ([grid["note"]] if automatic else []) + notes
                amr_numbers = [("amr_levels", data.GetNumberOfLevels()),
                               ("amr_finest_level", grid["finest_level"]),
                               ("amr_finest_spacing", grid["finest_spacing"][0]),
                               ("sampling_spacing", image.GetSpacing()[0]),
                               ("sampling_capped", 1 if automatic and grid["capped"] else 0)]
                for note in notes:
                    self._note(note)
            else:
                grid = None
                spread = _spread(ranks, data, self.Symmetry)
                if resampled:
                    grid, moved = self._followed_grid(data, outInfo.GetInformationObject(0),
                                                      spread)
                    if moved:
                        notes.append(moved)
                        self._note(moved)
                image, valid = _image_input(data, grid, spread)
                if not isinstance(data, vtkImageData) and self.AxisFromWedge:
                    # a wedge traced as it is: a slab of gas a few degrees thick (said as the
                    # C++ filter says it)
                    mesh = _internal_mesh(data)
                    bounds = _leaf_bounds(mesh)
                    wedge = "" if bounds is None else \
                        _engine.wedge_warning(bounds, lambda: _all_points(mesh))
                    if wedge:
                        self._warn(wedge)
            if not resampled:
                valid = _image_validity(image)
            # the wedge found and the OpenFOAM mesh read: the first notes (the C++ filter's order)
            read_notes = [] if plan is None else list(plan["notes"])
            read_notes += [n for n in [_internal_mesh_note(data)] if n]
            for note in read_notes:
                self._note(note)
            pd = image.GetPointData()
            names = [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())]
            names = [n for n in names if n and n != "vtkValidPointMask"]
            # the model and the arrays left automatic: the engine's choice (the C++ filter's),
            # from the names present (point arrays, then cell arrays)
            cd = image.GetCellData()
            cells = [cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())
                     if cd.GetArray(i) is not None and cd.GetArrayName(i)]
            scalars = pd.GetScalars()
            fallback = scalars.GetName() if scalars is not None and scalars.GetName() else \
                (names[0] if names else "")
            settings = {k: self._values[k] for k in self._model_settings}
            settings.update({k: self._values[k] or "" for k in self._role_properties})
            settings["Model"] = self.Model
            choice = _engine.index_choices(settings, names + [c for c in cells if c not in names],
                                           fallback)
            cell_notes = [cell_note] if cell_note else []
            for note in choice["notes"] + cell_notes:
                self._note(note)
            # the engine's work on the grid (schlieren_index_field, the C++ filter's): the
            # arrays by role, the model, the points outside the flow, the gradient, the bodies,
            # the field data
            settings.update(choice["arrays"])
            settings.update(
                Model=choice["model"], PassthroughHoldsN=int(choice["holds_n"]),
                HumidityFromArray=int(self.HumidityFromArray), CO2FromArray=int(self.CO2FromArray),
                AmbientMode=self.AmbientMode, AmbientValue=float(self.AmbientValue),
                BodyFromGrid=int(self.BodyFromGrid), BodyWallFaces=self.BodyWallFaces,
                SolidArray=self.SolidArray or "", Resampled=int(resampled),
                UseSamplingBounds=int(self.UseSamplingBounds))
            if resampled and valid is not None and not valid.any():
                settings["CellsDescription"] = _describe_cells(_internal_mesh(data))
            rim = None
            if self.BodyFromGrid and resampled and valid is not None and not valid.all() and \
                    ranks is None:
                # the voids beside the mesh's walls, where it has a velocity (the C++ filter's)
                found = _wall_rim(_internal_mesh(data), list(image.GetDimensions()),
                                  image.GetOrigin(), image.GetSpacing(), valid,
                                  -1 if plan is None else int(plan["geometry"][1]), plan)
                if found is not None:
                    rim, faces = found
                    settings["WallVelocity"] = faces["velocity"]
                    settings["WallFaceCounts"] = [faces["wall_faces"], faces["flow_faces"],
                                                  faces["still_faces"], faces["turned_faces"]]
            arrays, active = {}, -1
            for i in range(pd.GetNumberOfArrays()):
                a = pd.GetArray(i)
                if a is None or a.GetName() == "vtkValidPointMask" or a.GetName() in arrays:
                    continue
                if scalars is not None and a is scalars:
                    active = len(arrays)
                arrays[a.GetName() or ""] = numpy_support.vtk_to_numpy(a)
            dims = list(image.GetDimensions())
            body = None
            surface = vtkPolyData.GetData(inInfo[1]) if len(inInfo) > 1 and \
                inInfo[1].GetNumberOfInformationObjects() else None
            if surface is not None:
                # the Body surface's inside, the C++ filter's test; the engine marks it solid
                # and says what the C++ filter's hook says (a refusal, the note)
                found, body, overlaps = _body_inside(surface, image)
                settings.update(BodySurface=found, BodyOverlaps=int(overlaps))
            try:
                if pieces:
                    collective[0] = True
                    agreed = _agreed(ranks, "", _INDEX_STEP)
                    if agreed:
                        return self._fail(agreed)
                    n1, grad, solid, report = _engine.index_field_piece(
                        settings, grid_ext, out_ext, whole, image.GetSpacing(), arrays, valid,
                        active, cells, read_notes + choice["notes"] + cell_notes + notes,
                        ranks=ranks,
                        body=body)
                else:
                    n1, grad, solid, report = _engine.index_field(
                        settings, dims, image.GetSpacing(), arrays, valid, active, cells,
                        read_notes + choice["notes"] + cell_notes + notes, rim, body)
            except EngineError as e:
                report = getattr(e, "report", {})
                if report.get("model_done"):
                    for w in report.get("warnings", []):
                        self._warn(w)
                raise
        except EngineError as e:
            if pieces and not collective[0]:
                return self._fail(_agreed(ranks, str(e), _INDEX_STEP))
            return self._fail(str(e))
        for w in report["warnings"]:
            self._warn(w)
        for note in report["notes"]:
            self._note(note)
        if report["solid_note"]:
            self._warn(report["solid_note"])
        out.ShallowCopy(image)
        if resampled:
            e = out.GetExtent()  # the resampled grid's, known only now
            outInfo.GetInformationObject(0).Set(SDDP.WHOLE_EXTENT(), e, 6)
        _add(out, "grad_n", grad)  # before n - 1, as the C++ filter writes them
        a = _add(out, "n_minus_1", n1)
        # active, not SetScalars: that would drop the input's active scalars (the blunt fin's
        # Density), which the C++ filter keeps (and NumericalSchlieren prefers a density)
        out.GetPointData().SetActiveScalars(a.GetName())
        if solid is not None:
            out.GetPointData().RemoveArray("solid")
            _add(out, "solid", solid)
        # the engine's field data, in the C++ filter's order
        from vtkmodules.vtkCommonCore import vtkStringArray
        for field, value in report["field_data"]:
            if isinstance(value, list):
                strings = vtkStringArray()
                strings.SetName(field)
                for v in value:
                    strings.InsertNextValue(v)
                out.GetFieldData().AddArray(strings)
            else:
                _field_number(out, field, value)
        for name, value in amr_numbers:  # the AMR's levels, last (the C++ filter's order)
            _field_number(out, name, value)
        if ranks is not None:
            # this rank's piece of the grid (the requested extent), as the C++ filter writes it
            _crop(out, outInfo.GetInformationObject(0).Get(SDDP.UPDATE_EXTENT()))
        self._time_cache.computed += 1
        if key is not None:
            self._time_cache.insert(key, out)
        self._time_cache.fields(out, False)
        return 1


class RefractionOctree(_Properties):
    """The paper's min-max octree as a level per point (`octree_level`) for a tolerance."""

    _defaults = dict(Tolerance=0.0, MaxLevel=7)
    _range_proxy = "RefractionOctree"
    AutomaticToleranceFraction = 1e-4

    def __init__(self, **kwargs):
        _Properties.__init__(self, 1, **kwargs)

    def FillInputPortInformation(self, port, info):
        # any data object, refused below unless an image: a multiblock must not be executed
        # block by block into a multiblock output (the output is one image or empty)
        info.Set(self.INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject")
        return 1

    def RequestData(self, request, inInfo, outInfo):
        image = vtkDataObject.GetData(inInfo[0])
        out = vtkImageData.GetData(outInfo)
        ranks = _ranks()
        problem, n1 = "", None
        if not isinstance(image, vtkImageData):
            problem = ("RefractionOctree needs a vtkImageData input with the point array "
                       "'n_minus_1' (the output of RefractiveIndex); got %s."
                       % (image.GetClassName() if image is not None else "nothing"))
        elif not 0 <= int(self.MaxLevel) <= 10:
            problem = "MaxLevel is %d: it must be in [0, 10]." % int(self.MaxLevel)
        elif ranks is not None and not _has_grid(inInfo[0].GetInformationObject(0)):
            # the upstream's information failed on this rank: agreed on (below), not an empty
            # piece whose range the others would take for the volume's
            problem = ("The input volume is empty: nothing to build an octree of. If a filter "
                       "upstream reported an error, that is the cause; fix it there.")
        elif ranks is not None and image.GetNumberOfPoints() == 0:
            n1 = np.zeros(0, np.float32)  # an empty piece under MPI
        else:
            n1 = _point_array(image, "n_minus_1")
            if n1 is None:
                problem = "RefractionOctree needs the point array 'n_minus_1'."
        # under MPI every rank learns whether one failed (no rank waits for one that gave up)
        problem = _agreed(ranks, problem, "RefractionOctree's range")
        if problem:
            return self._fail(problem)
        n1 = np.ascontiguousarray(n1, np.float32)
        lowest = [float(n1.min()), -float(n1.max())] if n1.size else [np.inf, np.inf]
        if ranks is not None:
            # under MPI (the C++ filter's): the range of the whole volume, so that every rank
            # uses the same tolerance
            lowest = list(ranks.comm.allreduce(np.array(lowest, np.float64), "min"))
        rng = -lowest[1] - lowest[0] if np.isfinite(lowest).all() else 0.0
        tol = float(self.Tolerance)
        if not tol > 0:
            tol = self.AutomaticToleranceFraction * rng if rng > 0 else 0.0
        dims = list(image.GetDimensions())
        out.ShallowCopy(image)
        fraction, counts = 0.0, np.zeros(2)
        if min(dims) >= 2:
            try:
                levels, fraction = _engine.octree_levels(dims, n1, tol, int(self.MaxLevel))
            except EngineError as e:
                return self._fail(str(e))
            _add(out, "octree_level", levels)
            cells = float(dims[0] - 1) * (dims[1] - 1) * (dims[2] - 1)
            counts = np.array([fraction * cells, cells])
        if ranks is not None:
            # the skippable fraction of the whole volume
            counts = ranks.comm.allreduce(counts, "sum")
            fraction = counts[0] / counts[1] if counts[1] > 0 else 0.0
        _field_number(out, "octree_tolerance", tol)
        _field_number(out, "octree_max_level", int(self.MaxLevel))
        _field_number(out, "octree_skippable_fraction", fraction)
        return 1


class NumericalSchlieren(_Properties):
    """The textbook schlieren image computed from the gradient of a scalar (density or n - 1) on
    a plane (Slice) or averaged along each pixel's line (LineOfSight): the NumericalSchlieren
    proxy, the engine's code. Input: vtkImageData."""

    _defaults = dict(Mode="Slice", Gradient="Magnitude", KnifeAngle=0.0, C0=-0.001, C1=0.05, K=5.0,
                     GradientMaximum=0.0, SliceOffset=0.0, StepSize=0.5,
                     ViewDirection=[0.0, 0.0, -1.0], ViewUp=[0.0, 1.0, 0.0], Resolution=[512, 512],
                     DensityArray="")
    _entries = dict(Mode=["Slice", "LineOfSight"], Gradient=["Magnitude", "KnifeComponent"])

    def __init__(self, **kwargs):
        _Properties.__init__(self, 1, **kwargs)

    def FillInputPortInformation(self, port, info):
        info.Set(self.INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject")  # one image out, see above
        return 1

    def RequestUpdateExtent(self, request, inInfo, outInfo):
        # the whole volume (not the film's extent, which the pipeline would copy upstream and
        # then report as outside the input's whole extent); under MPI each rank's piece of it,
        # gathered in RequestData (the C++ filter's)
        _ask_pieces(inInfo[0].GetInformationObject(0), outInfo.GetInformationObject(0),
                    _ranks())
        return 1

    def _settings(self):
        return {k: self._values[k] for k in self._defaults if k != "DensityArray"}

    @staticmethod
    def _grid(info_or_image):
        if isinstance(info_or_image, vtkImageData):
            e = info_or_image.GetExtent()
            spacing = info_or_image.GetSpacing()
            origin = info_or_image.GetOrigin()
        else:
            e = info_or_image.Get(SDDP.WHOLE_EXTENT())
            spacing = info_or_image.Get(vtkImageData.SPACING())
            origin = info_or_image.Get(vtkImageData.ORIGIN())
        dims = [e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1]
        # the grid's first point (the extent may not start at 0)
        return dims, [origin[a] + e[2 * a] * spacing[a] for a in range(3)], list(spacing)

    def RequestInformation(self, request, inInfo, outInfo):
        src = inInfo[0].GetInformationObject(0)
        if not (src.Has(SDDP.WHOLE_EXTENT()) and src.Has(vtkImageData.SPACING())):
            return 1
        try:
            dims, origin, spacing = self._grid(src)
            size, film_origin, pixel = _engine.numerical(self._settings(), dims, origin, spacing)
        except EngineError as e:
            return self._fail(str(e))
        info = outInfo.GetInformationObject(0)
        info.Set(SDDP.WHOLE_EXTENT(), 0, size[0] - 1, 0, size[1] - 1, 0, 0)
        info.Set(vtkImageData.SPACING(), pixel, pixel, 1.0)
        info.Set(vtkImageData.ORIGIN(), film_origin[0], film_origin[1], 0.0)
        # every rank executes (the pieces are gathered under MPI); rank 0 makes the image
        info.Set(self.CAN_HANDLE_PIECE_REQUEST(), 1)
        return 1

    def RequestData(self, request, inInfo, outInfo):
        ranks = _ranks()
        if ranks is not None:
            return self._pieces(ranks, inInfo, outInfo)
        image = vtkDataObject.GetData(inInfo[0])
        out = vtkImageData.GetData(outInfo)
        if image is not None and not isinstance(image, vtkImageData):
            return self._fail("NumericalSchlieren needs a vtkImageData input (for example the "
                              "output of RefractiveIndex or RefractiveScene); got %s. Resample "
                              "the data onto an image with RefractiveIndex first."
                              % image.GetClassName())
        try:
            _axis_aligned_image(image, "NumericalSchlieren")
        except EngineError as e:
            if image is not None:
                return self._fail(str(e))
        if image is None or image.GetNumberOfPoints() == 0:
            return self._fail("NumericalSchlieren needs a non-empty image (vtkImageData), for "
                              "example the output of RefractiveIndex or RefractiveScene.")

        def scalars(name):
            a = image.GetPointData().GetArray(name)
            return None if a is None or a.GetNumberOfComponents() != 1 else \
                numpy_support.vtk_to_numpy(a)
        try:
            name, values = self._field(image)
        except EngineError as e:
            return self._fail(str(e))
        solid = scalars("solid")
        mask = scalars("vtkValidPointMask")
        try:
            dims, origin, spacing = self._grid(image)
            r = _engine.numerical(self._settings(), dims, origin, spacing, values,
                                  None if solid is None else (solid != 0).astype(np.uint8),
                                  None if mask is None else (mask == 0).astype(np.uint8),
                                  progress=self._progress)
        except EngineError as e:
            self.SetAbortExecute(0)  # an abort is spent: the next update images again
            out.Initialize()
            return self._fail(str(e))
        self._write(out, r, name)
        return 1

    def _write(self, out, r, name):
        out.Initialize()
        out.SetExtent(0, r["size"][0] - 1, 0, r["size"][1] - 1, 0, 0)
        out.SetSpacing(r["pixel"], r["pixel"], 1.0)
        out.SetOrigin(r["origin"][0], r["origin"][1], 0.0)
        out.GetPointData().SetScalars(_add(out, "intensity", r["intensity"]))
        _add(out, "numerical_gradient", r["numerical_gradient"])
        _add(out, "blocked", r["blocked"])
        _field_string(out, "numerical_field", name)
        _field_string(out, "numerical_mode", self.Mode)
        _field_string(out, "numerical_gradient_kind", self.Gradient)
        _field_number(out, "gradient_maximum", r["maximum"])
        _field_number(out, "gradient_largest", r["largest"])

    def _pieces(self, ranks, inInfo, outInfo):
        """RequestData under MPI (the C++ filter's): each rank's piece of the volume gathered on
        rank 0, which makes the image of the whole; a failure on any rank is every rank's (the
        engine's agreement), an empty piece sends nothing."""
        image = vtkDataObject.GetData(inInfo[0])
        out = vtkImageData.GetData(outInfo)
        out.Initialize()
        src = inInfo[0].GetInformationObject(0)
        empty = not isinstance(image, vtkImageData) or image.GetNumberOfPoints() == 0
        error, name, values, solid, mask = "", "", None, None, None
        if image is not None and not isinstance(image, vtkImageData):
            error = ("NumericalSchlieren needs a vtkImageData input (for example the output of "
                     "RefractiveIndex or RefractiveScene); got %s. Resample the data onto an "
                     "image with RefractiveIndex first." % image.GetClassName())
        elif not empty:
            try:
                _axis_aligned_image(image, "NumericalSchlieren")
                name, values = self._field(image)
            except EngineError as e:
                error = str(e)
            solid, mask = _point_array(image, "solid"), _point_array(image, "vtkValidPointMask")
        if not error and not _has_grid(src):
            # the upstream's information failed on this rank: agreed on, not a TypeError that
            # leaves the other ranks waiting
            error = ("The input volume is empty: nothing to image. If a filter upstream reported "
                     "an error, that is the cause; fix it there.")
        try:
            agreed = _agreed(ranks, error, "NumericalSchlieren's pieces")
            if agreed:
                return self._fail(agreed)
            whole, origin, spacing = self._grid(src)
            e = src.Get(SDDP.WHOLE_EXTENT())
            if empty:
                offset, piece = [0, 0, 0], [0, 0, 0]
            else:
                pe = image.GetExtent()
                offset = [pe[2 * a] - e[2 * a] for a in range(3)]
                piece = list(image.GetDimensions())
            r = _engine.numerical_pieces(
                self._settings(), whole, origin, spacing, offset, piece, values,
                None if solid is None else (solid != 0).astype(np.uint8),
                None if mask is None else (mask == 0).astype(np.uint8), ranks=ranks,
                progress=self._progress)
        except EngineError as err:
            self.SetAbortExecute(0)
            out.Initialize()
            return self._fail(str(err))
        if r is not None:
            self._write(out, r, name)
        return 1

    def _field(self, image):
        """(name, values) of the field imaged: DensityArray, else the first of density, rho,
        Density, n_minus_1 (one-component point arrays); EngineError where none is."""
        def scalars(name):
            a = image.GetPointData().GetArray(name)
            return None if a is None or a.GetNumberOfComponents() != 1 else \
                numpy_support.vtk_to_numpy(a)
        if self.DensityArray:
            values = scalars(self.DensityArray)
            if values is None:
                raise EngineError("DensityArray is '%s': the input has no one-component point "
                                  "array of that name." % self.DensityArray)
            return self.DensityArray, values
        for name in ("density", "rho", "Density", "n_minus_1"):
            values = scalars(name)
            if values is not None:
                return name, values
        raise EngineError("NumericalSchlieren needs a density (point array 'density', 'rho' or "
                          "'Density', or one named in DensityArray) or 'n_minus_1'; the input "
                          "has none.")

    def _progress(self, fraction, _text):
        """The image's progress, as the C++ filter reports it; False once the pipeline asks to
        abort (ParaView's abort, an observer's SetAbortExecute)."""
        self.UpdateProgress(fraction)
        return not self.GetAbortExecute()


def _image_properties():
    props = _engine.properties()
    return ({p["name"]: p["default"] for p in props},
            {p["name"]: p["entries"] for p in props if p["kind"] == "enum"})


class SchlierenImage(_Properties):
    """Traces a collimated beam through n - 1 and forms the film image (vtkImageData).

    The properties are the SchlierenImage proxy's engine properties (schlieren.properties()).
    The last trace's report is `LastReport` (field_data, notes, error); the field data is also
    on the output, as the C++ filter writes it."""

    _defaults, _entries = _image_properties()

    def __init__(self, **kwargs):
        object.__setattr__(self, "_session", _engine.Session())
        object.__setattr__(self, "_volume_key", None)
        object.__setattr__(self, "LastReport", None)
        object.__setattr__(self, "LastError", "")
        _Properties.__init__(self, 1, **kwargs)

    def FillInputPortInformation(self, port, info):
        info.Set(self.INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject")  # one image out, see above
        return 1

    def RequestData(self, request, inInfo, outInfo):
        data = vtkDataObject.GetData(inInfo[0])
        out = vtkImageData.GetData(outInfo)
        s = self._session
        ranks = _ranks()
        # under MPI (the C++ filter's): each rank's piece, traced together by the engine
        # (collective); a failure before is agreed on, an empty piece sends nothing
        empty = ranks is not None and isinstance(data, vtkImageData) and \
            data.GetNumberOfPoints() == 0
        collective = False
        try:
            # the C++ filter's refusals: not an image (an unstructured grid traced as vacuum
            # outside its cells would be a wrong image: RefractiveIndex resamples it with the
            # validity mask and fills those points), or a turned one
            image = _axis_aligned_image(data, "SchlierenImage")
            n1 = None if empty else _point_array(image, "n_minus_1")
            if n1 is None and not empty:
                pd = image.GetPointData()
                raise EngineError(
                    "SchlierenImage needs the point array 'n_minus_1' (n - 1); the input has "
                    "the point arrays: %s. Apply RefractiveIndex first." % ", ".join(
                        pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())))
            if n1 is not None and n1.ndim != 1:
                raise EngineError("The point array 'n_minus_1' must have one component.")
            # the input by its C++ object and modification time: id() of the Python wrapper is
            # not stable (a wrapper freed after RequestData may come back at another address),
            # and a resampled image is new each time while its source is unchanged
            key = (data.GetMTime(), data.__this__)
            if key != self._volume_key:
                object.__setattr__(self, "_volume_key", None)
                solid = None if empty else _point_array(image, "solid")
                levels = None if empty else _point_array(image, "octree_level")
                fd = image.GetFieldData()
                tol = fd.GetArray("octree_tolerance")
                maxl = fd.GetArray("octree_max_level")
                volume = (n1, None if solid is None else (solid != 0).astype(np.uint8),
                          None if levels is None else np.clip(levels, 0, 10).astype(np.uint8),
                          tol.GetValue(0) if tol is not None else -1.0,
                          int(maxl.GetValue(0)) if maxl is not None else 7)
                if ranks is None:
                    s.set_volume(image.GetDimensions(), _first_point(image), image.GetSpacing(),
                                 *volume)
                else:
                    src = inInfo[0].GetInformationObject(0)
                    if not _has_grid(src):
                        # the upstream's information failed on this rank: said, and agreed on
                        # with the other ranks (below), not a TypeError that leaves them waiting
                        raise EngineError("The input volume is empty: nothing to trace. If a "
                                          "filter upstream reported an error, that is the "
                                          "cause; fix it there.")
                    s.set_piece(src.Get(SDDP.WHOLE_EXTENT()),
                                [0, -1, 0, -1, 0, -1] if empty else image.GetExtent(),
                                src.Get(vtkImageData.ORIGIN()), src.Get(vtkImageData.SPACING()),
                                *volume)
                object.__setattr__(self, "_volume_key", key)
            for name, value in self._values.items():
                s.set(name, value)
            if ranks is None:
                report = s.trace(self._progress)
            else:
                collective = True
                agreed = _agreed(ranks, "", _TRACE_STEP)
                if agreed:
                    raise EngineError(agreed)
                report = s.trace_parallel(ranks, self._progress)
        except EngineError as e:
            object.__setattr__(self, "LastReport", getattr(e, "report", None))
            message = str(e)
            if ranks is not None and not collective:
                message = _agreed(ranks, message, _TRACE_STEP)
            return self._stopped(out, message)
        object.__setattr__(self, "LastReport", report)
        object.__setattr__(self, "LastError", "")
        for note in report["notes"]:
            if note["warning"]:
                self._warn(note["text"])
        if ranks is not None and not s.has_image():
            out.Initialize()
            return 1  # rank 0 holds the image
        size, origin, pixel = s.film()
        # only the image and the report, as the C++ filter's output (the pipeline passed the
        # input's field data on: RefractiveIndex's index_* are not this image's)
        out.Initialize()
        out.SetExtent(0, size[0] - 1, 0, size[1] - 1, 0, 0)
        out.SetSpacing(pixel, pixel, 1.0)
        out.SetOrigin(origin[0], origin[1], 0.0)
        # a frame found by this trace (Framing Silhouette) may give the film another shape than
        # RequestInformation could know: the output's information follows the image
        info = outInfo.GetInformationObject(0)
        info.Set(SDDP.WHOLE_EXTENT(), 0, size[0] - 1, 0, size[1] - 1, 0, 0)
        info.Set(vtkImageData.SPACING(), pixel, pixel, 1.0)
        info.Set(vtkImageData.ORIGIN(), origin[0], origin[1], 0.0)
        out.GetPointData().SetScalars(_add(out, "intensity", s.array("intensity")))
        for name, comps in (("deflection", ("x", "y")), ("rgb", ("r", "g", "b")),
                            ("phase", ()), ("bos_displacement", ("x", "y")),
                            ("error_estimate", ()), ("blocked", ())):
            a = s.array(name)
            if a is not None:
                arr = _add(out, name, a)
                for i, c in enumerate(comps):
                    arr.SetComponentName(i, c)
        for k, v in report["field_data"].items():
            (_field_string if isinstance(v, str) else _field_number)(out, k, v)
        shown = vtkImageData()
        shown.ShallowCopy(out)
        object.__setattr__(self, "_shown", shown)
        self.UpdateProgress(1.0)
        return 1

    def _progress(self, fraction, text):
        """The trace's progress (the engine's text, as the C++ filter shows it); False once the
        pipeline asks to abort (GetAbortExecute: ParaView's abort, an observer's SetAbortExecute)."""
        if text:
            self.SetProgressText(text)
        self.UpdateProgress(fraction)
        return not self.GetAbortExecute()

    def _stopped(self, out, message):
        """A failed trace as the C++ filter ends it: where the pipeline aborted it and an earlier
        image exists, that image stays, with a warning (1); else the error (0). The abort is
        spent: the next update traces."""
        aborted = self.GetAbortExecute()
        if aborted:
            self.SetAbortExecute(0)
        self.SetProgressText(None)
        shown = self.__dict__.get("_shown")
        if aborted and shown is not None and message.endswith(": no image yet"):
            out.ShallowCopy(shown)
            self._warn(message[:-len("no image yet")] + "the image shown is the previous one; "
                       "the next update traces all its passes again")
            return 1
        return self._fail(message)

    def WriteBOSPair(self, folder, bits=8, format="png", prefix="bos"):
        """The last image (Cutoff BOS) as an image pair for PIV codes, OpenPIV and others: the
        undistorted background and the recording (grey PNG or TIFF, 8 or 16 bits) and a JSON side
        file (pixel size, bench, the displacement's units and sign) in the existing `folder`
        (docs/BENCH.md "BOS image pairs"). Returns the paths {"background", "recording",
        "side_file"}; raises EngineError (one line) on bad input. The C++ filter's
        WriteBOSPair writes the same files."""
        return self._session.write_bos_pair(folder, bits, format, prefix)

    def RequestInformation(self, request, inInfo, outInfo):
        # the film's extent, as the C++ filter gives it: from the input's grid and the settings
        # (a non-image input is resampled in RequestData; its film is known only then)
        src = inInfo[0].GetInformationObject(0)
        info = outInfo.GetInformationObject(0)
        # empty until the film is known (not the input's extent, which the executive copied)
        info.Set(SDDP.WHOLE_EXTENT(), 0, -1, 0, -1, 0, -1)
        if not _has_grid(src):
            return 1
        e = src.Get(SDDP.WHOLE_EXTENT())
        dims = [e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1]
        if min(dims) < 1:
            return self._fail("The input volume is empty: nothing to trace. If a filter upstream "
                              "reported an error, that is the cause; fix it there.")
        spacing = src.Get(vtkImageData.SPACING())
        first = [src.Get(vtkImageData.ORIGIN())[a] + e[2 * a] * spacing[a] for a in range(3)]
        try:
            for name, value in self._values.items():
                self._session.set(name, value)
            size, origin, pixel = self._session.plan_film(dims, first, spacing)
        except EngineError as err:
            return self._fail(str(err))
        info.Set(SDDP.WHOLE_EXTENT(), 0, size[0] - 1, 0, size[1] - 1, 0, 0)
        info.Set(vtkImageData.SPACING(), pixel, pixel, 1.0)
        info.Set(vtkImageData.ORIGIN(), origin[0], origin[1], 0.0)
        # every rank executes (the tracing is collective under MPI); rank 0 makes the image
        info.Set(self.CAN_HANDLE_PIECE_REQUEST(), 1)
        return 1

    def RequestUpdateExtent(self, request, inInfo, outInfo):
        # the tracer needs the whole volume; under MPI each rank its piece of it (the C++
        # filter's), traced together in RequestData
        _ask_pieces(inInfo[0].GetInformationObject(0), outInfo.GetInformationObject(0),
                    _ranks())
        return 1


def read_photograph(path):
    """A photograph file (PNG, JPEG, TIFF; 8 or 16 bit; grey or colour) read with VTK's readers, as
    grey float32 (rows, columns), row 0 at the bottom (VTK's order, as the film's). Colour is
    converted by its luminance (Rec. 709) in the engine (schlieren_photograph_grey), as the C++
    filter converts it."""
    import os
    from vtkmodules.vtkIOImage import vtkImageReader2Factory
    if not os.path.isfile(path):
        raise EngineError("The photograph %r was not found." % path)
    reader = vtkImageReader2Factory.CreateImageReader2(path)
    if reader is None:
        raise EngineError("The photograph %r is not an image VTK reads (PNG, JPEG, TIFF, BMP, PNM)."
                          % path)
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    nx, ny, nz = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    if scalars is None or nx * ny == 0:
        raise EngineError("The photograph %r holds no image." % path)
    a = numpy_support.vtk_to_numpy(scalars)
    return _engine.grey(a.reshape((nz, ny, nx, -1))[0], "the photograph %r" % path)


# SchlierenPhotograph's Overlay: the output array each entry makes the active scalars
PHOTOGRAPH_OVERLAYS = dict(Blend="blend", Checkerboard="checkerboard", Difference="difference",
                           Photograph="photograph_calibrated", Image="intensity")
# the engine's images (schlieren_photograph) and their output arrays
PHOTOGRAPH_ARRAYS = dict(registered="photograph", calibrated="photograph_calibrated",
                         difference="difference", checkerboard="checkerboard",
                         line_distance="line_distance")


class SchlierenPhotograph(_Properties):
    """A photograph beside the image (issue 51; docs/CFD.md), the C++ plugin's
    vtkSchlierenPhotograph: input 0 a SchlierenImage output (its `intensity`), input 1 (optional)
    the photograph as a vtkImageData, else FileName (PNG, JPEG, TIFF, 8 or 16 bit, read with VTK's
    readers). Output 0: the film's grid with `intensity`, `photograph` (registered),
    `photograph_calibrated`, `difference`, `checkerboard`, `blend`, `line_distance` (world units
    at the film's line pixels, NaN elsewhere), the array Overlay names active; field data
    `photograph_report` (the engine's JSON) and the numbers. Output 1: the lines as polylines (cell
    data `image` 0 film / 1 photograph, `line_distance`, `line_offset`, `line_matched`,
    `line_match`). A photograph that does not match fails the request with the reason (no
    registration presented as a match)."""

    _defaults = dict(FileName="", PhotoPixelSize=0.0, PointPairs="", Refine="Similarity",
                     ScaleRange=[0.6, 1.6], MaxRotation=12.0, MaxShift=0.3, LineThreshold=0.25,
                     MinLineLength=8, MaxLineDistance=0.0, Overlay="Blend", BlendWeight=0.5,
                     CheckerSize=16)
    _entries = dict(Refine=["Similarity", "Rigid", "Shift", "None"],
                    Overlay=list(PHOTOGRAPH_OVERLAYS))

    def __init__(self, **kwargs):
        _Properties.__init__(self, 2, nOutputPorts=2, **kwargs)
        object.__setattr__(self, "Report", None)

    def _check(self, name, value):
        if name == "PointPairs":
            # the engine's text: numbers separated by spaces (a list is written so)
            if isinstance(value, str):
                return value.strip()
            v = list(np.asarray(value, dtype=float).ravel().tolist())
            if len(v) not in (0, 8, 12, 16):
                raise ValueError("PointPairs takes 2 to 4 pairs of 4 numbers (photograph pixel u v, "
                                 "world x y), got %d numbers" % len(v))
            return " ".join(repr(x) for x in v)
        return _Properties._check(self, name, value)

    def FillInputPortInformation(self, port, info):
        info.Set(self.INPUT_REQUIRED_DATA_TYPE(), "vtkImageData")
        if port == 1:
            info.Set(self.INPUT_IS_OPTIONAL(), 1)
        return 1

    def FillOutputPortInformation(self, port, info):
        info.Set(vtkDataObject.DATA_TYPE_NAME(), "vtkPolyData" if port == 1 else "vtkImageData")
        return 1

    def _photograph(self, inInfo):
        """The photograph as grey (rows, columns): the second input's scalars, else FileName's."""
        photo_in = vtkImageData.GetData(inInfo[1]) if self.GetNumberOfInputConnections(1) else None
        if photo_in is not None:
            scalars = photo_in.GetPointData().GetScalars()
            if scalars is None:
                raise EngineError("SchlierenPhotograph's photograph input has no scalars.")
            px, py, _ = photo_in.GetDimensions()
            return _engine.grey(numpy_support.vtk_to_numpy(scalars).reshape((py, px, -1)),
                                "the photograph input")
        if self.FileName:
            return read_photograph(self.FileName)
        raise EngineError("SchlierenPhotograph needs a photograph: set FileName (a PNG, JPEG or "
                          "TIFF file) or connect an image to its second input.")

    def _registration_key(self, film, inInfo, settings):
        """What a registration depends on: the film, the photograph (its input, or its file as it
        is on disk) and the engine's settings (not Overlay or BlendWeight: they change the view
        without registering again, as in the C++ filter)."""
        import os
        photo_in = vtkImageData.GetData(inInfo[1]) if self.GetNumberOfInputConnections(1) else None
        if photo_in is not None:
            photo = ("input", photo_in.__this__, photo_in.GetMTime())
        elif self.FileName and os.path.isfile(self.FileName):
            st = os.stat(self.FileName)
            photo = ("file", self.FileName, st.st_mtime_ns, st.st_size)
        else:
            photo = None
        return (sorted((k, str(v)) for k, v in settings.items()), film.__this__, film.GetMTime(), photo)

    def RequestData(self, request, inInfo, outInfo):
        from vtkmodules.vtkCommonDataModel import vtkPolyData
        film = vtkImageData.GetData(inInfo[0])
        out = vtkImageData.GetData(outInfo, 0)
        lines_out = vtkPolyData.GetData(outInfo, 1)
        out.Initialize()
        lines_out.Initialize()
        object.__setattr__(self, "Report", None)
        if film is None or _point_array(film, "intensity") is None:
            return self._fail("SchlierenPhotograph needs the output of SchlierenImage (a 2D image "
                              "with the point array 'intensity') on its first input.")
        nx, ny, nz = film.GetDimensions()
        if nz != 1:
            return self._fail("SchlierenPhotograph needs a 2D film (one layer); got %d x %d x %d."
                              % (nx, ny, nz))
        sx, sy, _ = film.GetSpacing()
        if abs(sx - sy) > 1e-6 * max(abs(sx), abs(sy)):
            return self._fail("SchlierenPhotograph needs square film pixels; got %g x %g." % (sx, sy))
        intensity = _point_array(film, "intensity").reshape((ny, nx))
        origin = _first_point(film)
        settings = {k: self._values[k] for k in self._defaults
                    if k not in ("FileName", "Overlay", "BlendWeight")}
        if not settings["PointPairs"]:
            del settings["PointPairs"]
        try:
            _engine.photograph_blend(np.empty(0), np.empty(0), self.BlendWeight)  # its range
            key = self._registration_key(film, inInfo, settings)
            cached = self.__dict__.get("_registered")
            if cached is not None and cached[0] == key:
                r = cached[1]
            else:
                object.__setattr__(self, "_registered", None)
                photo = self._photograph(inInfo)
                r = _engine.photograph(intensity, origin[:2], sx, photo, settings)
                object.__setattr__(self, "_registered", (key, r))
            blend = _engine.photograph_blend(intensity, r["images"]["difference"], self.BlendWeight)
        except EngineError as err:
            return self._fail(str(err))
        object.__setattr__(self, "Report", r)
        if not r["match"]:
            return self._fail("The photograph was not registered: " + r["reason"])
        out.SetExtent(0, nx - 1, 0, ny - 1, 0, 0)
        out.SetSpacing(sx, sy, 1.0)
        out.SetOrigin(origin[0], origin[1], origin[2])
        _add(out, "intensity", intensity.ravel())
        for k, name in PHOTOGRAPH_ARRAYS.items():
            _add(out, name, r["images"][k].ravel())
        _add(out, "blend", blend.ravel())
        out.GetPointData().SetActiveScalars(PHOTOGRAPH_OVERLAYS[self.Overlay])
        _field_string(out, "photograph_report", r["json"])
        for k in ("score", "threshold", "scale", "rotation", "photo_pixel_size", "edge_uncertainty",
                  "gamma", "gamma_error", "background", "vignetting"):
            if r.get(k) is not None:
                _field_number(out, "photograph_" + k, r[k])
        _field_number(out, "photograph_shift", list(r["shift"]))
        if r["grey_reason"]:
            _field_string(out, "photograph_grey_reason", r["grey_reason"])
        if r.get("warnings"):
            _field_string(out, "warnings", r["warnings"])
            self._warn(r["warnings"])
        _photograph_lines(lines_out, r["lines"], origin[2])
        return 1


def _photograph_lines(output, lines, z):
    """The report's strong-gradient lines as polylines at height `z`, one cell a line, with the cell
    arrays image (0 the film's, 1 the photograph's), line_distance (world; NaN: none matched),
    line_offset (2: the mean vector to the other image's lines), line_matched (the fraction of its
    points matched) and line_match (the other image's line it is nearest to, -1: none)."""
    from vtkmodules.vtkCommonCore import vtkFloatArray, vtkIntArray, vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray
    points, cells = vtkPoints(), vtkCellArray()
    image, match = vtkIntArray(), vtkIntArray()
    distance, offset, matched = vtkFloatArray(), vtkFloatArray(), vtkFloatArray()
    offset.SetNumberOfComponents(2)
    for a, name in ((image, "image"), (distance, "line_distance"), (offset, "line_offset"),
                    (matched, "line_matched"), (match, "line_match")):
        a.SetName(name)
    nan = float("nan")
    number = lambda v: nan if v is None else v  # noqa: E731 -- the report's null: not a number
    for line in lines:
        xy = line["points"]
        cells.InsertNextCell(len(xy) // 2)
        for a in range(0, len(xy), 2):
            cells.InsertCellPoint(points.InsertNextPoint(xy[a], xy[a + 1], z))
        image.InsertNextValue(0 if line["image"] == "film" else 1)
        d = line["distance"]
        distance.InsertNextValue(nan if d is None or d < 0 else d)
        offset.InsertNextTuple2(number(line["offset"][0]), number(line["offset"][1]))
        matched.InsertNextValue(number(line["matched"]))
        match.InsertNextValue(int(line["match"]))
    output.SetPoints(points)
    output.SetLines(cells)
    for a in (image, distance, offset, matched, match):
        output.GetCellData().AddArray(a)
    output.GetCellData().SetActiveScalars("line_distance")  # the lines coloured by it


def image_to_numpy(image, name="intensity"):
    """A point array of a 2D vtkImageData as a NumPy array of shape (ny, nx[, components])."""
    a = _point_array(image, name)
    nx, ny, _ = image.GetDimensions()
    return a.reshape((ny, nx) + a.shape[1:])
