// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenSample.h
 * @brief A mesh sampled at the points of an image grid, cell by cell, on plain arrays.
 *
 * RefractiveIndex's resampling of any mesh, for every front end (the C++ filter through
 * Filters/SchlierenResample.cxx, Python through schlieren_sample_cells). Each cell is visited
 * once: the grid points within its bounding box are tested against it and, where one lies inside,
 * the point arrays are interpolated there with the cell's own weights and the cell arrays take
 * the cell's value. The point-in-cell test and the weights are VTK's (vtkCell::EvaluatePosition,
 * vtkDataArray::InterpolateTuple), in the same arithmetic, so a front end gets VTK's sampler's
 * values, bit for bit on the suite's meshes (the blunt fin, the combustor, disk_out_ref and the
 * four OpenFOAM cases: Testing/Benchmarks/resampling.py --compare): the parametric coordinates of
 * a tetrahedron and a voxel in closed form, those of a hexahedron, a wedge and a pyramid by
 * Newton's iteration from (0.5, 0.5, 0.5) (10 steps at most; converged at 1e-5 for a hexahedron,
 * 1e-3 for the others), a point inside where every parametric coordinate lies within 1e-6 of a
 * hexahedron, 1e-3 of a tetrahedron, wedge or pyramid, and exactly in a voxel. A point on a face
 * shared by two cells takes the first cell's (the lowest id). No VTK here.
 *
 * Cells: VTK's numbering. Tetrahedra (10), voxels (11), hexahedra (12), wedges (13) and pyramids
 * (14) are sampled; vertices, lines and faces (types 1-9, 21-23, 0) hold no volume and are passed
 * over; any other type (a polyhedron, a pentagonal prism, a quadratic cell) is refused by name.
 * A structured grid comes as its point dimensions instead of the connectivity: its cells are the
 * hexahedra of vtkStructuredGrid, numbered x fastest.
 *
 * The points mode (SamplePoints) samples the same way at any points (RefractiveIndex's symmetric
 * plan's, OpenCL/SchlierenSymmetry.h), each cell looking only at the points in the bins its box
 * meets; there a 2D mesh's faces are sampled in their plane too (within 1e-6 of a face's size
 * of it): pixels (8) exactly, triangles (5) by projection, quads (9) by Gauss-Newton to 1e-12;
 * strips and polygons (6, 7) are refused. The cell that holds a point is again the lowest id.
 * Both modes visit the cells in the same order with the same test and weights.
 */
#ifndef SchlierenSample_h
#define SchlierenSample_h

#include <cstdint>
#include <string>
#include <vector>

namespace schlieren
{

/** The cells of a mesh: explicit (CellTypes, Offsets, Connectivity) or structured (Dims). */
struct SampleMesh
{
  const double* Points = nullptr; ///< x, y, z of each point
  std::int64_t NumberOfPoints = 0;
  /// Explicit cells: cell c has type CellTypes[c] and the points
  /// Connectivity[Offsets[c]] .. Connectivity[Offsets[c + 1] - 1] (VTK's order).
  const unsigned char* CellTypes = nullptr;
  const std::int64_t* Offsets = nullptr; ///< NumberOfCells + 1 values, Offsets[0] = 0
  const std::int64_t* Connectivity = nullptr;
  std::int64_t ConnectivityLength = 0;
  std::int64_t NumberOfCells = 0;
  /// A structured grid instead: its points' dimensions (all > 0; then the explicit cells are
  /// not read and NumberOfCells is the grid's count of cells).
  int StructuredDims[3] = { 0, 0, 0 };
  /// Optional, one byte per cell: non-zero cells are passed over (hidden ghost cells).
  const unsigned char* SkipCells = nullptr;
};

/** One array to sample: a point array (interpolated) or a cell array (the holding cell's). */
struct SampleArray
{
  std::string Name; ///< for messages
  bool Cells = false;
  int Components = 1;
  /// Point arrays: 4 (float) or 8 (double), interpolated in double and rounded to that type.
  /// Cell arrays: the bytes of one component, of any type (copied).
  int ValueBytes = 4;
  const void* In = nullptr;
  std::int64_t InValues = 0; ///< values in In: (points or cells) x Components
  void* Out = nullptr;       ///< grid points x Components values; points not found left as given
};

/** The image grid: Dims points from Origin, Spacing apart. */
struct SampleGrid
{
  int Dims[3] = { 1, 1, 1 };
  double Origin[3] = { 0.0, 0.0, 0.0 };
  double Spacing[3] = { 1.0, 1.0, 1.0 };
};

/** "hexahedron", "polyhedron", "cell type 77": for messages. */
std::string SampleCellTypeName(int type);

/**
 * Checks the mesh, the grid and every array before anything is read: lengths (each array named),
 * offsets, point ids, each cell's count of points for its type, the types themselves. Throws
 * schlieren::Error with the reason. The cells counted by a structured grid are returned by
 * SampleCellCount.
 */
void CheckSample(const SampleMesh& mesh,
  const SampleGrid& grid,
  const std::vector<SampleArray>& arrays);

/** The cells a mesh has (a structured grid's: the product of dims - 1 over dims above 1). */
std::int64_t SampleCellCount(const SampleMesh& mesh);

/**
 * Samples `mesh` at the points of `grid` (CheckSample first). `found` holds a byte per grid
 * point: a point already non-zero is left alone (found in an earlier block of a composite data
 * set), a point found here is set to 1. Returns the points found here.
 */
std::int64_t SampleCells(const SampleMesh& mesh,
  const SampleGrid& grid,
  const std::vector<SampleArray>& arrays,
  unsigned char* found);

/**
 * Checks as CheckSample does, for `count` points at `at` (x, y, z each) instead of a grid: every
 * output array holds count x Components values.
 */
void CheckSamplePoints(const SampleMesh& mesh,
  const double* at,
  std::int64_t count,
  const std::vector<SampleArray>& arrays);

/**
 * Samples `mesh` at the `count` points `at` (x, y, z each; a point not finite is in no cell), as
 * SampleCells samples a grid's: `found` a byte per point (non-zero left alone, found here set to
 * 1), the arrays' outputs a value per point. Returns the points found here.
 */
std::int64_t SamplePoints(const SampleMesh& mesh,
  const double* at,
  std::int64_t count,
  const std::vector<SampleArray>& arrays,
  unsigned char* found);

} // namespace schlieren

#endif
