// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenWalls.h
 * @brief Which boundary faces of a CFD mesh are walls, seen from the resampled grid's void.
 *
 * A body on the edge of a CFD domain (wedge15Ma5's wedge, forwardStep's step) is where the mesh
 * is not, and its void reaches the resampling box, so the enclosed-hole rule cannot tell it from
 * the outside beyond a far-field boundary. The mesh's own boundary faces can: the flow does not
 * cross a wall (slip or no-slip, |U.n| small next to it), it does cross an inlet, an outlet or a
 * far field (fluid at rest next to a face tells neither). Each invalid grid point next to a valid one takes the kind of its nearest boundary
 * face; schlieren::InvalidRegionsBesideWalls then decides per void region. Here what needs VTK:
 * the mesh's boundary faces, their normals and velocity, the nearest face; the kinds are the
 * engine's (schlieren::walls::ClassifyFaces, OpenCL/SchlierenWallFaces.h).
 */
#ifndef SchlierenWalls_h
#define SchlierenWalls_h

#include "SchlierenWallFaces.h" // the kinds of the faces, the report: the engine's

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

class vtkDataSet;

namespace schlieren
{
namespace walls
{

/**
 * Fills `rim` (one byte per grid point, x fastest) for the invalid points of the grid (dims,
 * origin, spacing; `valid`) that have a valid 6-neighbour: 1 where the nearest boundary face of
 * `mesh` is a wall, 2 where it is a face the flow crosses; 0 elsewhere. `toMesh` maps a grid
 * point to where the grid sampled the mesh (the identity for a volume, the mid-plane or the r-z
 * plane for symmetric inputs). Faces whose normal lies within 25 deg of axis `ignoreAxis` (the
 * planar case's front and back, a wedge's sides; -1: none) are left out. Returns false (rim all
 * 0) where the mesh carries no velocity (a 3-component point or cell array named U or velocity).
 */
bool ClassifyRim(vtkDataSet* mesh, const int dims[3], const double origin[3],
  const double spacing[3], const unsigned char* valid, int ignoreAxis,
  const std::function<void(const double*, double*)>& toMesh, std::vector<unsigned char>& rim,
  RimReport& report);

} // namespace walls
} // namespace schlieren

#endif
