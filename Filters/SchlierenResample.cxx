// SPDX-License-Identifier: BSD-3-Clause
// A mesh sampled onto an image grid cell by cell (SchlierenResample.h).
#include "SchlierenResample.h"

#include "vtkCell.h"
#include "vtkCellType.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkFloatArray.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace schlieren
{
vtkSmartPointer<vtkImageData> SampleCells(vtkDataSet* mesh, vtkImageData* structure)
{
  int D[3];
  double O[3], H[3];
  structure->GetDimensions(D);
  structure->GetOrigin(O);
  structure->GetSpacing(H);
  const vtkIdType count = structure->GetNumberOfPoints();
  auto grid = vtkSmartPointer<vtkImageData>::New();
  grid->CopyStructure(structure);
  vtkNew<vtkCharArray> mask;
  mask->SetName("vtkValidPointMask");
  mask->SetNumberOfTuples(count);
  mask->FillValue(0);
  char* found = mask->GetPointer(0);

  // every array, as the probe gives them: point arrays interpolated, cell arrays copied (a cell
  // array named as a point array is left out), each of its own type
  struct Field
  {
    vtkDataArray* In;
    bool Cells;
    vtkSmartPointer<vtkDataArray> Out;
  };
  std::vector<Field> fields;
  for (int cells = 0; cells < 2; ++cells)
  {
    vtkDataSetAttributes* attributes = cells
      ? static_cast<vtkDataSetAttributes*>(mesh->GetCellData())
      : static_cast<vtkDataSetAttributes*>(mesh->GetPointData());
    for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* a = attributes->GetArray(i);
      if (!a || !a->GetName() || std::string(a->GetName()) == "vtkGhostType" ||
        (cells && grid->GetPointData()->GetArray(a->GetName())))
      {
        continue;
      }
      Field f{ a, cells != 0, vtk::TakeSmartPointer(a->NewInstance()) };
      f.Out->SetName(a->GetName());
      f.Out->SetNumberOfComponents(a->GetNumberOfComponents());
      f.Out->SetNumberOfTuples(count);
      f.Out->Fill(0.0);
      grid->GetPointData()->AddArray(f.Out);
      fields.push_back(f);
    }
  }
  grid->GetPointData()->AddArray(mask);

  vtkUnsignedCharArray* ghosts = mesh->GetCellGhostArray();
  vtkNew<vtkGenericCell> cell;
  std::vector<double> weights(static_cast<std::size_t>(std::max(mesh->GetMaxCellSize(), 8)));
  std::vector<double> tuple(16);
  const vtkIdType cells = mesh->GetNumberOfCells();
  for (vtkIdType c = 0; c < cells; ++c)
  {
    if (ghosts && (ghosts->GetValue(c) & vtkDataSetAttributes::HIDDENCELL))
    {
      continue;
    }
    double b[6];
    mesh->GetCellBounds(c, b);
    int lo[3], hi[3];
    bool empty = false;
    for (int a = 0; a < 3; ++a)
    {
      if (D[a] == 1)
      {
        lo[a] = hi[a] = 0;
        empty = empty || O[a] < b[2 * a] || O[a] > b[2 * a + 1];
        continue;
      }
      const double eps = 1e-9;
      lo[a] = std::max(0, static_cast<int>(std::ceil((b[2 * a] - O[a]) / H[a] - eps)));
      hi[a] = std::min(D[a] - 1, static_cast<int>(std::floor((b[2 * a + 1] - O[a]) / H[a] + eps)));
      empty = empty || hi[a] < lo[a];
    }
    if (empty)
    {
      continue;
    }
    mesh->GetCell(c, cell);
    if (cell->GetCellDimension() < 3)
    {
      continue; // a face or a line holds no volume
    }
    if (static_cast<std::size_t>(cell->GetNumberOfPoints()) > weights.size())
    {
      weights.resize(static_cast<std::size_t>(cell->GetNumberOfPoints()));
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
    {
      for (int y = lo[1]; y <= hi[1]; ++y)
      {
        for (int x = lo[0]; x <= hi[0]; ++x)
        {
          const vtkIdType p = (vtkIdType(z) * D[1] + y) * D[0] + x;
          if (found[p])
          {
            continue;
          }
          double point[3] = { O[0] + x * H[0], O[1] + y * H[1], O[2] + z * H[2] };
          // the closest point is not needed (and costs most where the point is outside); a
          // polyhedron gets a buffer all the same
          double pcoords[3], dist2, closest[3];
          int subId = 0;
          double* wanted = cell->GetCellType() == VTK_POLYHEDRON ? closest : nullptr;
          if (cell->EvaluatePosition(point, wanted, subId, pcoords, dist2, weights.data()) != 1)
          {
            continue;
          }
          found[p] = 1;
          for (Field& f : fields)
          {
            if (f.Cells)
            {
              f.Out->SetTuple(p, c, f.In);
            }
            else
            {
              f.Out->InterpolateTuple(p, cell->GetPointIds(), f.In, weights.data());
            }
          }
        }
      }
    }
  }
  return grid;
}
} // namespace schlieren
