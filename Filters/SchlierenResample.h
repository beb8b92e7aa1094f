// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenResample.h
 * @brief A mesh (any vtkDataSet with 3D cells) sampled at the points of an image grid, cell by cell.
 *
 * The probe (vtkProbeFilter) asks, for every grid point, which cell holds it: a point-locator
 * search and a walk through neighbouring cells, each tested with a closest-point computation.
 * Here each cell is visited once instead: the grid points within its bounding box are tested
 * against it (vtkCell::EvaluatePosition, without the closest point), and where one lies inside,
 * the arrays are interpolated there with the cell's own weights as the probe does
 * (vtkDataArray::InterpolateTuple): the same values. A point on a face shared by two cells takes
 * the first cell's (the lowest id; both give the same value to rounding). Cells blanked
 * (vtkGhostType HIDDENCELL) are skipped.
 */
#ifndef SchlierenResample_h
#define SchlierenResample_h

#include "vtkSmartPointer.h"

class vtkDataSet;
class vtkImageData;

namespace schlieren
{
/**
 * `mesh` sampled at the points of `structure`, as vtkProbeFilter gives it: every point array
 * interpolated, every cell array the holding cell's value (each of its own type), and
 * vtkValidPointMask (1 where a cell holds the point).
 */
vtkSmartPointer<vtkImageData> SampleCells(vtkDataSet* mesh, vtkImageData* structure);
} // namespace schlieren

#endif
