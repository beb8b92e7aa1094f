// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenResample.h
 * @brief A mesh (any vtkDataSet with 3D cells) sampled at the points of an image grid, cell by
 * cell.
 *
 * The probe (vtkProbeFilter) asks, for every grid point, which cell holds it: a point-locator
 * search and a walk through neighbouring cells. Here each cell is visited once instead, by the
 * engine (OpenCL/SchlierenSample.h, the same sampler every front end calls): the grid points
 * within its bounding box are tested against it with VTK's own point-in-cell test and weights
 * (vtkCell::EvaluatePosition, vtkDataArray::InterpolateTuple), so the values are the probe's.
 * This file only turns VTK's data into the engine's arrays: the points, the cells (a structured
 * grid as its dimensions, an unstructured grid's own offsets and connectivity, any other data set
 * cell by cell), the hidden cells (vtkGhostType HIDDENCELL; in a structured grid also the cells
 * of hidden points), the point and cell arrays. A point on a face shared by two cells takes the
 * first cell's (the lowest id; of a composite data set, the first block's).
 *
 * Every RefractiveIndex input goes through here (no vtkProbeFilter is left in its paths): meshes
 * and blocks of images onto the grid (an image's cells are voxels, sampled exactly), and a 2D
 * input under Symmetry at the points the engine's plan gives (SampleCellsAt: the engine's points
 * mode, which samples a 2D mesh's triangles, pixels and quads in their plane too).
 */
#ifndef SchlierenResample_h
#define SchlierenResample_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

class vtkDataObject;
class vtkImageData;
class vtkPointData;

namespace schlieren
{
/**
 * `mesh` (a data set, or a composite data set's blocks in turn) sampled at the points of
 * `structure`, as vtkProbeFilter gives it: every point array interpolated, every cell array the
 * holding cell's value (each of its own type; of a composite data set, the arrays every block
 * with cells has), and vtkValidPointMask (1 where a cell holds the point). Throws schlieren::Error
 * for a cell type the engine does not sample (a polyhedron: the message names it).
 */
vtkSmartPointer<vtkImageData> SampleCells(vtkDataObject* mesh, vtkImageData* structure);

/**
 * `mesh` sampled at `count` points `at` (x, y, z each) as SampleCells samples a grid's: the arrays
 * and vtkValidPointMask, a value per point, in the returned point data. Throws schlieren::Error
 * as SampleCells does (and for a 2D mesh's strips and polygons: Triangulate first).
 */
vtkSmartPointer<vtkPointData> SampleCellsAt(vtkDataObject* mesh, const double* at, vtkIdType count);
} // namespace schlieren

#endif
