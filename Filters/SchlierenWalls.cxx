// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenWalls.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "vtkStaticCellLocator.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>

namespace schlieren
{
namespace walls
{
namespace
{
vtkDataArray* Velocity(vtkFieldData* fd)
{
  for (int i = 0; i < fd->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* a = fd->GetArray(i);
    if (!a || !a->GetName() || a->GetNumberOfComponents() != 3)
    {
      continue;
    }
    std::string n = a->GetName();
    std::transform(n.begin(), n.end(), n.begin(),
      [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (n == "u" || n == "velocity")
    {
      return a;
    }
  }
  return nullptr;
}
} // namespace

bool ClassifyRim(vtkDataSet* mesh, const int dims[3], const double origin[3],
  const double spacing[3], const unsigned char* valid, int ignoreAxis,
  const std::function<void(const double*, double*)>& toMesh, std::vector<unsigned char>& rim,
  RimReport& report)
{
  const std::int64_t nx = dims[0], ny = dims[1], nz = dims[2];
  rim.assign(static_cast<std::size_t>(nx * ny * nz), 0);
  if (!mesh || mesh->GetNumberOfCells() == 0)
  {
    return false;
  }
  // the velocity: cell data (next to the face, the cell's own value) before point data
  vtkDataArray* cellU = Velocity(mesh->GetCellData());
  vtkDataArray* pointU = cellU ? nullptr : Velocity(mesh->GetPointData());
  vtkDataArray* U = cellU ? cellU : pointU;
  if (!U)
  {
    return false;
  }
  report.Velocity = U->GetName();
  double umax = 0.0;
  for (vtkIdType t = 0; t < U->GetNumberOfTuples(); ++t)
  {
    const double* u = U->GetTuple3(t);
    umax = std::max(umax, std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
  }
  if (!(umax > 0))
  {
    return false;
  }

  // the mesh's boundary faces, each with the cell it bounds
  vtkNew<vtkDataSetSurfaceFilter> surface;
  surface->SetInputData(mesh);
  surface->PassThroughCellIdsOn();
  surface->PassThroughPointIdsOn();
  surface->Update();
  vtkPolyData* faces = surface->GetOutput();
  auto* cellIds = vtkIdTypeArray::SafeDownCast(
    faces->GetCellData()->GetArray(surface->GetOriginalCellIdsName()));
  auto* pointIds = vtkIdTypeArray::SafeDownCast(
    faces->GetPointData()->GetArray(surface->GetOriginalPointIdsName()));
  // every face's points, normal and the velocity beside it: the engine decides their kinds
  const vtkIdType count = faces->GetNumberOfCells();
  std::vector<std::int64_t> offsets(1, 0), connectivity;
  std::vector<double> normals(3 * static_cast<std::size_t>(count), 0.0);
  std::vector<double> velocity(3 * static_cast<std::size_t>(count), 0.0);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < count; ++c)
  {
    faces->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      connectivity.push_back(ids->GetId(k));
    }
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    if (ids->GetNumberOfIds() < 3)
    {
      continue;
    }
    double* n = normals.data() + 3 * c;
    vtkPolygon::ComputeNormal(faces->GetPoints(), static_cast<int>(ids->GetNumberOfIds()),
      ids->GetPointer(0), n);
    double* u = velocity.data() + 3 * c;
    if (cellU && cellIds)
    {
      cellU->GetTuple(cellIds->GetValue(c), u);
    }
    else if (pointU && pointIds)
    {
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        const double* v = pointU->GetTuple3(pointIds->GetValue(ids->GetId(k)));
        for (int a = 0; a < 3; ++a)
        {
          u[a] += v[a] / ids->GetNumberOfIds();
        }
      }
    }
  }
  const std::vector<unsigned char> all = ClassifyFaces(static_cast<std::size_t>(count),
    offsets.data(), connectivity.data(), static_cast<std::size_t>(faces->GetNumberOfPoints()),
    normals.data(), velocity.data(), umax, ignoreAxis, report);
  // the faces kept, for the nearest-face search
  vtkNew<vtkPolyData> kept;
  kept->SetPoints(faces->GetPoints());
  vtkNew<vtkCellArray> polys;
  std::vector<unsigned char> kind;
  for (vtkIdType c = 0; c < count; ++c)
  {
    if (all[c] != LeftOut)
    {
      faces->GetCellPoints(c, ids);
      polys->InsertNextCell(ids);
      kind.push_back(all[c]);
    }
  }
  if (kind.empty())
  {
    return false;
  }
  kept->SetPolys(polys);
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(kept);
  locator->BuildLocator();
  vtkNew<vtkGenericCell> cell;
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i)
      {
        const std::int64_t p = (k * ny + j) * nx + i;
        if (valid[p])
        {
          continue;
        }
        const bool besideValid = (i > 0 && valid[p - 1]) || (i + 1 < nx && valid[p + 1]) ||
          (j > 0 && valid[p - nx]) || (j + 1 < ny && valid[p + nx]) ||
          (k > 0 && valid[p - nx * ny]) || (k + 1 < nz && valid[p + nx * ny]);
        if (!besideValid)
        {
          continue;
        }
        const double x[3] = { origin[0] + i * spacing[0], origin[1] + j * spacing[1],
          origin[2] + k * spacing[2] };
        double at[3], closest[3], d2;
        toMesh(x, at);
        vtkIdType found = -1;
        int subId;
        locator->FindClosestPoint(at, closest, cell, found, subId, d2);
        if (found >= 0)
        {
          rim[p] = kind[found];
          ++report.RimPoints;
        }
      }
  return true;
}

} // namespace walls
} // namespace schlieren
