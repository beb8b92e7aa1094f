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
  vtkNew<vtkPolyData> kept;
  kept->SetPoints(faces->GetPoints());
  vtkNew<vtkCellArray> polys;
  std::vector<unsigned char> kind;
  std::vector<std::vector<vtkIdType>> facePoints; // each kept face's points (of `faces`)
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < faces->GetNumberOfCells(); ++c)
  {
    faces->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() < 3)
    {
      continue;
    }
    double n[3];
    vtkPolygon::ComputeNormal(faces->GetPoints(), static_cast<int>(ids->GetNumberOfIds()),
      ids->GetPointer(0), n);
    if (ignoreAxis >= 0 && std::abs(n[ignoreAxis]) > std::cos(25.0 * 3.14159265358979 / 180.0))
    {
      continue;
    }
    double u[3] = { 0, 0, 0 };
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
    // fluid at rest says nothing (a quiescent far field as much as a wall): neither
    const double speed = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const bool moving = speed >= MovingFluid * umax;
    const bool wall = moving && std::abs(u[0] * n[0] + u[1] * n[1] + u[2] * n[2]) < WallFlux * speed;
    (wall ? report.WallFaces : moving ? report.FlowFaces : report.StillFaces) += 1;
    kind.push_back(wall ? 1 : moving ? 2 : 0);
    facePoints.emplace_back(ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfIds());
    polys->InsertNextCell(ids);
  }
  if (kind.empty())
  {
    return false;
  }
  // A few faces the flow crosses with only walls (or fluid at rest) beside them are a wall
  // where the flow turns onto it (a reattachment, a stagnation point): the velocity of the cell
  // beside the face is not along the face there. An inlet or an outlet is a patch of its own.
  {
    std::vector<std::vector<std::size_t>> facesOf(static_cast<std::size_t>(faces->GetNumberOfPoints()));
    for (std::size_t f = 0; f < facePoints.size(); ++f)
      for (vtkIdType q : facePoints[f])
        facesOf[static_cast<std::size_t>(q)].push_back(f);
    std::vector<char> seen(kind.size(), 0);
    std::vector<std::size_t> cluster;
    for (std::size_t f0 = 0; f0 < kind.size(); ++f0)
    {
      if (kind[f0] != 2 || seen[f0])
        continue;
      cluster.assign(1, f0);
      seen[f0] = 1;
      bool besideWall = false;
      for (std::size_t c = 0; c < cluster.size(); ++c)
        for (vtkIdType q : facePoints[cluster[c]])
          for (std::size_t g : facesOf[static_cast<std::size_t>(q)])
          {
            if (kind[g] == 2 && !seen[g])
            {
              seen[g] = 1;
              cluster.push_back(g);
            }
            besideWall = besideWall || kind[g] == 1;
          }
      if (besideWall && cluster.size() <= FewFaces)
      {
        for (std::size_t g : cluster)
          kind[g] = 1;
        report.FlowFaces -= cluster.size();
        report.WallFaces += cluster.size();
        report.TurnedFaces += cluster.size();
      }
    }
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
