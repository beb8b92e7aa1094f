// SPDX-License-Identifier: BSD-3-Clause
// A mesh sampled onto an image grid cell by cell (SchlierenResample.h): VTK's data turned into the
// engine's arrays (OpenCL/SchlierenSample.h), which does the sampling.
#include "SchlierenResample.h"

#include "SchlierenEngine.h"
#include "SchlierenLimits.h"
#include "SchlierenSample.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkStructuredGrid.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace
{
/** A leaf's mesh as the engine's arrays (copies only where VTK's layout is not the engine's). */
struct MeshArrays
{
  schlieren::SampleMesh Mesh;
  std::vector<double> Points;
  std::vector<unsigned char> Types, Skip;
  std::vector<std::int64_t> Offsets, Connectivity;
};

void ToMesh(vtkDataSet* ds, MeshArrays& m)
{
  const vtkIdType np = ds->GetNumberOfPoints();
  const vtkIdType nc = ds->GetNumberOfCells();
  auto* pointSet = vtkPointSet::SafeDownCast(ds);
  auto* coordinates = pointSet && pointSet->GetPoints()
    ? vtkDoubleArray::SafeDownCast(pointSet->GetPoints()->GetData())
    : nullptr;
  // the copies made below where VTK's layout is not the engine's: points in double, a byte per
  // cell where some are hidden, the cells in 64 bits (8 ids per cell at most where they are read
  // one by one)
  auto* ug = vtkUnstructuredGrid::SafeDownCast(ds);
  const bool cellsCopied = !vtkStructuredGrid::SafeDownCast(ds) &&
    !(ug && ug->GetCells() && ug->GetCells()->IsStorage64Bit());
  const double idBytes =
    ug && ug->GetCells() ? 8.0 * ug->GetCells()->GetNumberOfConnectivityIds() : 64.0 * nc;
  schlieren::CheckHostMemory((coordinates ? 0.0 : 24.0 * np) +
      (ds->GetCellGhostArray() ? 1.0 * nc : 0.0) +
      (cellsCopied ? (ug ? 8.0 : 9.0) * nc + idBytes : 0.0),
    "The cell sampler's copy of a mesh of " + std::to_string(np) + " points and " +
      std::to_string(nc) + " cells",
    "Give the mesh in fewer pieces or with fewer cells.");
  if (coordinates && coordinates->GetNumberOfComponents() == 3)
  {
    m.Mesh.Points = coordinates->GetPointer(0);
  }
  else
  {
    m.Points.resize(3 * static_cast<std::size_t>(np));
    for (vtkIdType i = 0; i < np; ++i)
    {
      ds->GetPoint(i, m.Points.data() + 3 * i);
    }
    m.Mesh.Points = m.Points.data();
  }
  m.Mesh.NumberOfPoints = np;

  auto* sg = vtkStructuredGrid::SafeDownCast(ds);
  if (sg)
  {
    sg->GetDimensions(m.Mesh.StructuredDims);
    if (sg->HasAnyBlankCells() || sg->HasAnyBlankPoints())
    {
      // a cell is hidden by its own ghost flag or by one of its points' (IsCellVisible)
      m.Skip.resize(static_cast<std::size_t>(nc));
      for (vtkIdType c = 0; c < nc; ++c)
      {
        m.Skip[c] = sg->IsCellVisible(c) ? 0 : 1;
      }
    }
  }
  else if (ug)
  {
    vtkUnsignedCharArray* types = ug->GetCellTypesArray();
    m.Mesh.CellTypes = types ? types->GetPointer(0) : nullptr;
    vtkCellArray* cells = ug->GetCells();
    if (cells && cells->IsStorage64Bit())
    {
      m.Mesh.Offsets =
        reinterpret_cast<const std::int64_t*>(cells->GetOffsetsArray64()->GetPointer(0));
      m.Mesh.Connectivity =
        reinterpret_cast<const std::int64_t*>(cells->GetConnectivityArray64()->GetPointer(0));
    }
    else if (cells)
    {
      auto* offsets = cells->GetOffsetsArray32();
      auto* connectivity = cells->GetConnectivityArray32();
      m.Offsets.assign(
        offsets->GetPointer(0), offsets->GetPointer(0) + offsets->GetNumberOfValues());
      m.Connectivity.assign(connectivity->GetPointer(0),
        connectivity->GetPointer(0) + connectivity->GetNumberOfValues());
      m.Mesh.Offsets = m.Offsets.data();
      m.Mesh.Connectivity = m.Connectivity.data();
    }
    m.Mesh.ConnectivityLength = cells ? cells->GetNumberOfConnectivityIds() : 0;
    m.Mesh.NumberOfCells = nc;
  }
  else
  {
    // any other data set (a rectilinear grid's voxels, a poly data's faces): cell by cell
    vtkNew<vtkIdList> ids;
    m.Types.resize(static_cast<std::size_t>(nc));
    m.Offsets.assign(1, 0);
    for (vtkIdType c = 0; c < nc; ++c)
    {
      m.Types[c] = static_cast<unsigned char>(ds->GetCellType(c));
      ds->GetCellPoints(c, ids);
      for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      {
        m.Connectivity.push_back(ids->GetId(i));
      }
      m.Offsets.push_back(static_cast<std::int64_t>(m.Connectivity.size()));
    }
    m.Mesh.CellTypes = m.Types.data();
    m.Mesh.Offsets = m.Offsets.data();
    m.Mesh.Connectivity = m.Connectivity.data();
    m.Mesh.ConnectivityLength = static_cast<std::int64_t>(m.Connectivity.size());
    m.Mesh.NumberOfCells = nc;
  }
  if (!sg && ds->GetCellGhostArray())
  {
    vtkUnsignedCharArray* ghosts = ds->GetCellGhostArray();
    m.Skip.resize(static_cast<std::size_t>(nc));
    for (vtkIdType c = 0; c < nc; ++c)
    {
      m.Skip[c] = (ghosts->GetValue(c) & vtkDataSetAttributes::HIDDENCELL) ? 1 : 0;
    }
  }
  m.Mesh.SkipCells = m.Skip.empty() ? nullptr : m.Skip.data();
}

/** An output array and what the engine reads and writes for it. */
struct Field
{
  std::string Name;
  bool Cells;
  int Type, Components;
  vtkSmartPointer<vtkDataArray> Out;
  std::vector<double> Wide; // a point array of another type than float or double: in double
};

/** The leaves of `input` (itself where it is a data set) that hold cells. */
std::vector<vtkDataSet*> Leaves(vtkDataObject* input)
{
  std::vector<vtkDataSet*> leaves;
  if (auto* ds = vtkDataSet::SafeDownCast(input))
  {
    leaves.push_back(ds);
  }
  else if (auto* cd = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(cd->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      auto* leaf = vtkDataSet::SafeDownCast(it->GetCurrentDataObject());
      if (leaf && leaf->GetNumberOfCells() > 0)
      {
        leaves.push_back(leaf);
      }
    }
  }
  return leaves;
}

/** Point (cells = false) or cell array `name` of `ds` if it has `type` and `components`. */
vtkDataArray* Matching(vtkDataSet* ds, const Field& f)
{
  vtkDataSetAttributes* attributes = f.Cells
    ? static_cast<vtkDataSetAttributes*>(ds->GetCellData())
    : static_cast<vtkDataSetAttributes*>(ds->GetPointData());
  vtkDataArray* a = attributes->GetArray(f.Name.c_str());
  return a && a->GetDataType() == f.Type && a->GetNumberOfComponents() == f.Components ? a
                                                                                       : nullptr;
}
} // namespace

namespace schlieren
{
namespace
{
/**
 * The leaves of `input` sampled at `count` points into `out` (the arrays, then the mask
 * vtkValidPointMask) by `run(mesh, arrays, found)`, the engine's grid or points mode: every array
 * of the first leaf that every leaf has (with its type and components), as the probe gives them:
 * point arrays interpolated, cell arrays copied (a cell array named as a point array is left
 * out), each of its own type.
 */
template<typename Run>
void SampleLeaves(vtkDataObject* input, vtkIdType count, vtkPointData* out, Run run)
{
  const std::vector<vtkDataSet*> leaves = Leaves(input);
  vtkNew<vtkCharArray> mask;
  mask->SetName("vtkValidPointMask");
  mask->SetNumberOfTuples(count);
  mask->FillValue(0);
  auto* found = reinterpret_cast<unsigned char*>(mask->GetPointer(0));

  std::vector<Field> fields;
  for (int cells = 0; cells < 2 && !leaves.empty(); ++cells)
  {
    vtkDataSetAttributes* attributes = cells
      ? static_cast<vtkDataSetAttributes*>(leaves[0]->GetCellData())
      : static_cast<vtkDataSetAttributes*>(leaves[0]->GetPointData());
    for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* a = attributes->GetArray(i);
      if (!a || !a->GetName() || std::string(a->GetName()) == "vtkGhostType" ||
        a->GetDataType() == VTK_BIT || (cells && out->GetArray(a->GetName())))
      {
        continue;
      }
      Field f{
        a->GetName(), cells != 0, a->GetDataType(), a->GetNumberOfComponents(), nullptr, {}
      };
      if (!std::all_of(leaves.begin(), leaves.end(), [&](vtkDataSet* l) { return Matching(l, f); }))
      {
        continue;
      }
      f.Out = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(f.Type));
      f.Out->SetName(f.Name.c_str());
      f.Out->SetNumberOfComponents(f.Components);
      f.Out->SetNumberOfTuples(count);
      f.Out->Fill(0.0);
      if (!f.Cells && f.Type != VTK_FLOAT && f.Type != VTK_DOUBLE)
      {
        f.Wide.assign(static_cast<std::size_t>(count) * f.Components, 0.0);
      }
      out->AddArray(f.Out);
      fields.push_back(std::move(f));
    }
  }
  out->AddArray(mask);

  for (vtkDataSet* leaf : leaves)
  {
    MeshArrays m;
    ToMesh(leaf, m);
    std::vector<schlieren::SampleArray> arrays;
    std::vector<vtkSmartPointer<vtkDataArray>> copies; // inputs in the engine's layout
    for (Field& f : fields)
    {
      vtkDataArray* a = Matching(leaf, f);
      schlieren::SampleArray s;
      s.Name = f.Name;
      s.Cells = f.Cells;
      s.Components = f.Components;
      if (!f.Wide.empty())
      {
        auto wide = vtkSmartPointer<vtkDoubleArray>::New();
        wide->DeepCopy(a);
        copies.push_back(wide);
        s.ValueBytes = 8;
        s.In = wide->GetVoidPointer(0);
        s.Out = f.Wide.data();
      }
      else
      {
        if (!a->HasStandardMemoryLayout())
        {
          auto copy = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(f.Type));
          copy->DeepCopy(a);
          copies.push_back(copy);
          a = copy;
        }
        s.ValueBytes = a->GetDataTypeSize();
        s.In = a->GetVoidPointer(0);
        s.Out = f.Out->GetVoidPointer(0);
      }
      s.InValues = a->GetNumberOfValues();
      arrays.push_back(s);
    }
    run(m.Mesh, arrays, found);
  }
  for (Field& f : fields)
  {
    // integers interpolated in double, rounded as vtkDataArray::InterpolateTuple rounds them
    for (std::size_t i = 0; i < f.Wide.size(); ++i)
    {
      f.Out->SetComponent(static_cast<vtkIdType>(i) / f.Components,
        static_cast<int>(i % f.Components),
        std::round(f.Wide[i]));
    }
  }
}
} // namespace

vtkSmartPointer<vtkImageData> SampleCells(vtkDataObject* input, vtkImageData* structure)
{
  SampleGrid grid;
  structure->GetDimensions(grid.Dims);
  structure->GetOrigin(grid.Origin);
  structure->GetSpacing(grid.Spacing);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->CopyStructure(structure);
  SampleLeaves(input,
    structure->GetNumberOfPoints(),
    image->GetPointData(),
    [&](const SampleMesh& mesh, const std::vector<SampleArray>& arrays, unsigned char* found)
    { schlieren::SampleCells(mesh, grid, arrays, found); });
  return image;
}

vtkSmartPointer<vtkPointData> SampleCellsAt(vtkDataObject* input, const double* at, vtkIdType count)
{
  auto sampled = vtkSmartPointer<vtkPointData>::New();
  SampleLeaves(input,
    count,
    sampled,
    [&](const SampleMesh& mesh, const std::vector<SampleArray>& arrays, unsigned char* found)
    { schlieren::SamplePoints(mesh, at, count, arrays, found); });
  return sampled;
}
} // namespace schlieren
