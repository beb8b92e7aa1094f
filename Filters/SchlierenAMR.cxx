// SPDX-License-Identifier: BSD-3-Clause
// Overlapping AMR read into the engine's arrays and sampled there (SchlierenAMR.h,
// OpenCL/SchlierenAMRSample.h).
#include "SchlierenAMR.h"

#include "vtkAMRBox.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkUniformGrid.h"
#include "vtkVersionMacros.h"

#include "SchlierenAMRSample.h"
#include "SchlierenParallel.h"

#include <algorithm>

namespace
{
const char* const MaskName = "vtkValidPointMask";

// A level's blocks. VTK 9.6 deprecates GetNumberOfDataSets(level) and GetDataSet(level, index)
// for GetNumberOfBlocks(level) and GetDataSetAsImageData(level, index), which VTK 9.2
// (ParaView 5.11) and 9.3/9.4 (ParaView 5.13) do not have.
unsigned int BlocksOf(vtkOverlappingAMR* amr, unsigned int level)
{
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 6, 0)
  return amr->GetNumberOfBlocks(level);
#else
  return amr->GetNumberOfDataSets(level);
#endif
}

vtkImageData* BlockOf(vtkOverlappingAMR* amr, unsigned int level, unsigned int index)
{
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 6, 0)
  return amr->GetDataSetAsImageData(level, index);
#else
  return amr->GetDataSet(level, index);
#endif
}

/**
 * The boxes of `amr` that this process holds, as the engine reads them (SchlierenAMRSample.h):
 * per box, the point array of each of `names`, else its cell array (float and double read in
 * place, any other type copied into `storage` as floats).
 */
std::vector<schlieren::AMRBlock> BlocksFor(vtkOverlappingAMR* amr,
  const std::vector<std::string>& names, std::vector<std::vector<float>>& storage)
{
  std::vector<schlieren::AMRBlock> blocks;
  const unsigned int levels = amr ? amr->GetNumberOfLevels() : 0;
  for (unsigned int l = 0; l < levels; ++l)
  {
    for (unsigned int b = 0; b < BlocksOf(amr, l); ++b)
    {
      vtkImageData* g = BlockOf(amr, l, b);
      if (!g)
      {
        continue;
      }
      schlieren::AMRBlock block;
      block.Level = static_cast<int>(l);
      g->GetExtent(block.Extent);
      g->GetOrigin(block.Origin);
      g->GetSpacing(block.Spacing);
      if (g->GetNumberOfPoints() == 0)
      {
        block.Extent[1] = block.Extent[0] - 1; // nothing to sample
      }
      for (const std::string& name : names)
      {
        schlieren::AMRArray array;
        vtkDataArray* a = g->GetPointData()->GetArray(name.c_str());
        array.Cells = a == nullptr;
        if (!a)
        {
          a = g->GetCellData()->GetArray(name.c_str());
        }
        if (a)
        {
          array.Components = a->GetNumberOfComponents();
          if (vtkFloatArray::SafeDownCast(a) || vtkDoubleArray::SafeDownCast(a))
          {
            array.Values = a->GetVoidPointer(0);
            array.ValueBytes = a->GetDataTypeSize();
          }
          else
          {
            const vtkIdType n = a->GetNumberOfValues();
            const int nc = array.Components;
            storage.emplace_back(static_cast<std::size_t>(n));
            for (vtkIdType i = 0; i < n; ++i)
            {
              storage.back()[i] = static_cast<float>(a->GetComponent(i / nc, static_cast<int>(i % nc)));
            }
            array.Values = storage.back().data();
          }
        }
        block.Arrays.push_back(array);
      }
      blocks.push_back(std::move(block));
    }
  }
  return blocks;
}
} // namespace

namespace schlieren
{
namespace amr
{

//------------------------------------------------------------------------------
bool FinestSpacing(
  schlieren::Parallel& parallel, vtkDataObject* data, double spacing[3], int& level, int& levels)
{
  auto* amr = vtkOverlappingAMR::SafeDownCast(data);
  std::vector<std::vector<float>> storage;
  return schlieren::AMRFinestSpacing(parallel, BlocksFor(amr, {}, storage),
    amr ? static_cast<int>(amr->GetNumberOfLevels()) : 0, spacing, level, levels);
}

//------------------------------------------------------------------------------
bool Dimensions(schlieren::Parallel& parallel, vtkDataObject* data, const double bounds[6],
  double bytesPerPoint, int dims[3], double finest[3], bool& capped, std::string& note)
{
  auto* amr = vtkOverlappingAMR::SafeDownCast(data);
  std::vector<std::vector<float>> storage;
  return schlieren::AMRDimensions(parallel, BlocksFor(amr, {}, storage),
    amr ? static_cast<int>(amr->GetNumberOfLevels()) : 0, bounds, bytesPerPoint, dims, finest,
    capped, note);
}

//------------------------------------------------------------------------------
std::string OverlapProblem(vtkOverlappingAMR* data)
{
  std::vector<schlieren::AMRCellBox> boxes;
  for (unsigned int l = 0; data && l < data->GetNumberOfLevels(); ++l)
  {
    for (unsigned int b = 0; b < BlocksOf(data, l); ++b)
    {
      const vtkAMRBox& box = data->GetAMRBox(l, b);
      schlieren::AMRCellBox cells;
      cells.Level = static_cast<int>(l);
      std::copy(box.GetLoCorner(), box.GetLoCorner() + 3, cells.Lo);
      std::copy(box.GetHiCorner(), box.GetHiCorner() + 3, cells.Hi);
      boxes.push_back(cells);
    }
  }
  return schlieren::AMROverlapProblem(boxes);
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> Resample(schlieren::Parallel& parallel, vtkOverlappingAMR* data,
  vtkImageData* structure, const std::vector<std::string>& names, std::vector<std::string>& notes)
{
  int D[3];
  double O[3], H[3];
  structure->GetDimensions(D);
  structure->GetOrigin(O);
  structure->GetSpacing(H);
  std::vector<std::vector<float>> storage;
  schlieren::AMRSampled r = schlieren::AMRResample(parallel, BlocksFor(data, names, storage),
    data ? static_cast<int>(data->GetNumberOfLevels()) : 0, D, O, H, names);
  const vtkIdType count = structure->GetNumberOfPoints();
  vtkNew<vtkImageData> grid;
  grid->CopyStructure(structure);
  vtkNew<vtkCharArray> mask;
  mask->SetName(MaskName);
  mask->SetNumberOfTuples(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    mask->SetValue(i, static_cast<char>(r.Valid[i]));
  }
  grid->GetPointData()->AddArray(mask);
  for (std::size_t k = 0; k < names.size(); ++k)
  {
    if (r.Components[k] == 0)
    {
      continue; // reported as missing by the caller
    }
    vtkNew<vtkFloatArray> a;
    a->SetName(names[k].c_str());
    a->SetNumberOfComponents(r.Components[k]);
    a->SetNumberOfTuples(count);
    if (!r.Values[k].empty())
    {
      std::copy(r.Values[k].begin(), r.Values[k].end(), a->GetPointer(0));
    }
    else
    {
      a->FillValue(0.0f);
    }
    grid->GetPointData()->AddArray(a);
  }
  notes.insert(notes.end(), r.Notes.begin(), r.Notes.end());
  return grid;
}
} // namespace amr
} // namespace schlieren
