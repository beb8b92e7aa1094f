// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenAMR.h
 * @brief Overlapping AMR input (vtkOverlappingAMR) read into the engine's arrays
 * (OpenCL/SchlierenAMRSample.h, which samples it) for RefractiveIndex's image grid.
 *
 * Every grid point takes its value from the finest level whose boxes cover it, never from a
 * coarser level under a refined patch: the boxes are written level by level, coarsest first, so
 * that a finer level overwrites what lies under it. Point arrays are interpolated trilinearly
 * between a box's points; cell arrays trilinearly between its cell centres (constant over the
 * outer half cell of a box, where no centre lies beyond), without converting them to point data
 * first (which would average across each box's edge from one side). Blanking (vtkGhostType) is
 * not needed and not read: the level order decides. Under MPI each rank samples its own boxes and
 * the finest level found on any rank wins.
 */
#ifndef SchlierenAMR_h
#define SchlierenAMR_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkDataObject;
class vtkImageData;
class vtkOverlappingAMR;

namespace schlieren
{
class Parallel;

namespace amr
{
/**
 * The spacing of the finest level that holds data on any rank (levels with metadata but no loaded
 * boxes are skipped); false where `data` is not an overlapping AMR with data. `level` receives
 * that level's index, `levels` the number of levels the metadata lists.
 */
bool FinestSpacing(schlieren::Parallel& parallel, vtkDataObject* data, double spacing[3],
  int& level, int& levels);

/**
 * The automatic grid of an AMR input: dimensions over `bounds` at the finest level's spacing
 * (`finest`), capped so that the grid, `bytesPerPoint` each, takes at most half the memory this
 * process can allocate (the least over the ranks; SCHLIEREN_MEMORY_LIMIT lowers it). False where
 * `data` is not an AMR with data. `capped` says whether the cap acted; `note` says what was chosen
 * and, where capped, why.
 */
bool Dimensions(schlieren::Parallel& parallel, vtkDataObject* data, const double bounds[6],
  double bytesPerPoint, int dims[3], double finest[3], bool& capped, std::string& note);

/**
 * "" or the error where two boxes of one level overlap in cells (a level's boxes tile it: which
 * box's values to take there is undefined; issue 48: one box's values were dropped without a
 * word). Boxes that share a face share points, not cells, and are fine. Read from the AMR's
 * metadata, which every rank holds, so every rank finds the same.
 */
std::string OverlapProblem(vtkOverlappingAMR* data);

/**
 * The AMR `data` sampled at the points of `structure`: the arrays named in `names` (float, their
 * components kept) and vtkValidPointMask (1 where a box covers the point), the same on every
 * rank. `notes` receives what the user should know (levels used, cell data sampled as cells,
 * levels listed but not loaded).
 */
vtkSmartPointer<vtkImageData> Resample(schlieren::Parallel& parallel, vtkOverlappingAMR* data,
  vtkImageData* structure, const std::vector<std::string>& names, std::vector<std::string>& notes);
} // namespace amr
} // namespace schlieren

#endif
