// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenAMRSample.h
 * @brief Overlapping AMR (levels of boxes) sampled onto RefractiveIndex's image grid, on plain
 * arrays: the engine's part of an AMR input, which every front end reads into these arrays (the
 * C++ filter in Filters/SchlierenAMR.cxx, the Python one in algorithms.py, through
 * schlieren_amr_sample and its neighbours in schlieren_c.h).
 *
 * The levels' order rule: every grid point takes its value from the finest level whose boxes
 * cover it, never from a coarser level under a refined patch (the boxes are written level by
 * level, coarsest first, so that a finer level overwrites what lies under it). Point arrays are
 * interpolated trilinearly between a box's points; cell arrays trilinearly between its cell
 * centres (constant over the outer half cell of a box, where no centre lies beyond), in float,
 * without converting them to point data first (which would average across each box's edge from
 * one side). Blanking is not needed: the level order decides. Under MPI each rank samples its own
 * boxes and the finest level found on any rank wins (the mean where two ranks hold it).
 */
#ifndef SchlierenAMRSample_h
#define SchlierenAMRSample_h

#include <string>
#include <vector>

namespace schlieren
{
class Parallel;

/** One array of one box: float (ValueBytes 4) or double (8) values, Components a point or cell. */
struct AMRArray
{
  const void* Values = nullptr; ///< null: the box has no array of this name
  int ValueBytes = 4;
  int Components = 0;
  bool Cells = false; ///< a cell array (one tuple per cell), else a point array
};

/** One box of a level as loaded: its image's extent, origin and spacing (point i along an axis
 * lies at Origin + i Spacing, i from Extent's low to high end), one AMRArray per name asked for. */
struct AMRBlock
{
  int Level = 0;
  int Extent[6] = { 0, -1, 0, -1, 0, -1 };
  double Origin[3] = { 0.0, 0.0, 0.0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
  std::vector<AMRArray> Arrays;
};

/** One box of the AMR's metadata: its level and cell range (vtkAMRBox's corners, as given). */
struct AMRCellBox
{
  int Level = 0;
  int Lo[3] = { 0, 0, 0 };
  int Hi[3] = { -1, -1, -1 };
};

/**
 * "" or the error where two boxes of one level overlap in cells (a level's boxes tile it: which
 * box's values to take there is undefined; issue 48: one box's values were dropped without a
 * word). Boxes that share a face share points, not cells, and are fine. A box is named by its
 * index among its level's boxes in the order given; an invalid box (a high corner below its low
 * corner less one, vtkAMRBox::IsInvalid) is passed over; an axis with no cells (a 2D box's) counts
 * as one cell. Read from the metadata, which every rank holds, so every rank finds the same.
 */
std::string AMROverlapProblem(const std::vector<AMRCellBox>& boxes);

/**
 * The spacing of the finest level that holds a box on any rank (`blocks`: this rank's loaded
 * boxes); false where no rank holds any. `level` receives that level's index, `levels` the most
 * levels any rank lists (`listed`: this rank's). Collective.
 */
bool AMRFinestSpacing(Parallel& parallel, const std::vector<AMRBlock>& blocks, int listed,
  double spacing[3], int& level, int& levels);

/**
 * The automatic grid of an AMR input: dimensions over `bounds` at the finest level's spacing
 * (`finest`), capped so that the grid, `bytesPerPoint` each, takes at most half the memory this
 * process can allocate (the least over the ranks; SCHLIEREN_MEMORY_LIMIT lowers it). False where
 * no rank holds a box. `capped` says whether the cap acted; `note` says what was chosen and, where
 * capped, why. Collective.
 */
bool AMRDimensions(Parallel& parallel, const std::vector<AMRBlock>& blocks, int listed,
  const double bounds[6], double bytesPerPoint, int dims[3], double finest[3], bool& capped,
  std::string& note);

/** What AMRResample gives: per name its values (grid points x Components, float; empty where no
 * box on any rank has it: Components 0), whether any box held it as cells, the valid mask (1 where
 * a box covers the point), the same on every rank, and the notes for the user. */
struct AMRSampled
{
  std::vector<std::vector<float>> Values;
  std::vector<int> Components;
  std::vector<int> FromCells;
  std::vector<unsigned char> Valid;
  std::vector<std::string> Notes;
};

/**
 * The boxes sampled at the points of the grid `dims`, `origin`, `spacing` (`names`: the arrays
 * asked for, one AMRArray each in every block, for the messages). A box whose array has other
 * components than the first box's is not read for it. `listed`: the levels the AMR lists (a note
 * names those no rank holds). Collective.
 */
AMRSampled AMRResample(Parallel& parallel, const std::vector<AMRBlock>& blocks, int listed,
  const int dims[3], const double origin[3], const double spacing[3],
  const std::vector<std::string>& names);
} // namespace schlieren

#endif
