# SPDX-License-Identifier: BSD-3-Clause
"""BodyFromGrid's body beside a mesh's walls through both plugins (issue 47).

A channel of hexahedra 2 x 1 x 0.2 with a step cut out of its floor (x >= 1, y < 0.3: the void
reaches the sampling box's faces, so no hole encloses it), the cell velocity U = (1, 0, 0): the
step's top and the channel's walls are walls (|U.n| = 0), its front face is crossed by the flow
but is a group of 6 faces between walls (a stagnation: taken as wall), the inlet and the outlet
are crossed. The C++ RefractiveIndex (schlieren_vtk) and the Python plugin's (SchlierenPython.py:
the engine's schlieren_wall_faces and schlieren_index_field with VTK's surface filter and locator
in the front end) give the same `solid` (the step's void, bit for bit), n_minus_1, grad_n, the
same note word for word in the output window and in index_notes, and solid_points > 0.
"""
import argparse
import collections
import inspect
import sys

if not hasattr(inspect, "getargspec"):  # ParaView 5.11.0 on Python >= 3.11 (docs/PYTHON.md)
    _ArgSpec = collections.namedtuple("ArgSpec", "args varargs keywords defaults")
    inspect.getargspec = lambda f: _ArgSpec(*inspect.getfullargspec(f)[:4])

import numpy as np  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import LoadPlugin, PVTrivialProducer  # noqa: E402
from vtkmodules.util import numpy_support  # noqa: E402
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkFloatArray, vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid, VTK_HEXAHEDRON  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True, help="SchlierenPython.py")
args = ap.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())
ns = globals()
import schlieren_vtk as cxx  # noqa: E402  the C++ plugin's filters, compiled

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def channel_with_step():
    nx, ny, nz = 21, 11, 3
    pts = vtkPoints()
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                pts.InsertNextPoint(0.1 * i, 0.1 * j, 0.1 * k)
    grid = vtkUnstructuredGrid()
    grid.SetPoints(pts)
    pid = (lambda i, j, k: (k * ny + j) * nx + i)
    for k in range(nz - 1):
        for j in range(ny - 1):
            for i in range(nx - 1):
                if i >= 10 and j < 3:
                    continue  # the step
                grid.InsertNextCell(VTK_HEXAHEDRON, 8, [
                    pid(i, j, k), pid(i + 1, j, k), pid(i + 1, j + 1, k), pid(i, j + 1, k),
                    pid(i, j, k + 1), pid(i + 1, j, k + 1), pid(i + 1, j + 1, k + 1),
                    pid(i, j + 1, k + 1)])
    u = vtkDoubleArray()
    u.SetName("U")
    u.SetNumberOfComponents(3)
    for c in range(grid.GetNumberOfCells()):
        u.InsertNextTuple3(1.0, 0.0, 0.0)
    grid.GetCellData().AddArray(u)
    x = numpy_support.vtk_to_numpy(pts.GetData())
    rho = numpy_support.numpy_to_vtk((1.2 + 0.1 * x[:, 0] + 0.05 * x[:, 1]).astype(np.float32),
                                     deep=1, array_type=vtkFloatArray().GetDataType())
    rho.SetName("density")
    grid.GetPointData().AddArray(rho)
    return grid


def values(data, name):
    a = data.GetPointData().GetArray(name)
    return None if a is None else numpy_support.vtk_to_numpy(a)


def strings(data, name):
    a = data.GetFieldData().GetAbstractArray(name)
    return None if a is None else [a.GetValue(i) for i in range(a.GetNumberOfValues())]


mesh = channel_with_step()
f = cxx.vtkRefractiveIndex()
f.SetInputData(mesh)
f.SetModel(cxx.vtkRefractiveIndex.GLADSTONE_DALE)
f.SetInputArrayToProcess(0, 0, 0, 0, "density")
f.SetAutomaticDimension(48)
f.Update()
theirs = f.GetOutput()

producer = PVTrivialProducer()
producer.GetClientSideObject().SetOutput(mesh)
index = ns["RefractiveIndex"](Input=producer, Model="GladstoneDale",
                              InputArray=["POINTS", "density"], AutomaticDimension=48)
index.UpdatePipeline()
mine = servermanager.Fetch(index)

solid_c, solid_p = values(theirs, "solid"), values(mine, "solid")
notes_c, notes_p = strings(theirs, "index_notes"), strings(mine, "index_notes")
check(solid_c is not None and solid_c.sum() > 0,
      "the C++ filter finds the step's void a body (%s solid points)"
      % (None if solid_c is None else int(solid_c.sum())))
check(solid_p is not None and solid_c is not None and np.array_equal(solid_c, solid_p),
      "the Python plugin's solid is the C++ filter's, bit for bit (%s points)"
      % (None if solid_p is None else int(solid_p.sum())))
for name in ("n_minus_1", "grad_n"):
    a, b = values(theirs, name), values(mine, name)
    check(a is not None and b is not None and a.dtype == b.dtype and np.array_equal(a, b),
          "%s bit for bit" % name)
check(notes_c is not None and notes_c == notes_p and len(notes_c) == 1 and
      "taken as a body" in notes_c[0] and " 0 grid points" not in notes_c[0],
      "index_notes: the C++ filter's note, word for word (%s; Python: %s)" % (notes_c, notes_p))
for name in ("solid_points", "valid_point_fraction"):
    a = theirs.GetFieldData().GetArray(name).GetValue(0)
    b = mine.GetFieldData().GetArray(name).GetValue(0) if mine.GetFieldData().GetArray(name) \
        else None
    check(a == b, "%s the same (%s, %s)" % (name, a, b))
print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
