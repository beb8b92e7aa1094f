// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenWallFaces.h
 * @brief Which boundary faces of a CFD mesh are walls, from the velocity beside them (plain
 * arrays): the engine's part of BodyFromGrid's bodies beside walls.
 *
 * A body on the edge of a CFD domain (wedge15Ma5's wedge, forwardStep's step) is where the mesh
 * is not, and its void reaches the resampling box, so the enclosed-hole rule cannot tell it from
 * the outside beyond a far-field boundary. The mesh's own boundary faces can: the flow does not
 * cross a wall (slip or no-slip, |U.n| small next to it), it does cross an inlet, an outlet or a
 * far field (fluid at rest next to a face tells neither). The front end extracts the boundary
 * faces with their normals and the velocity beside them (VTK's surface filter) and finds the
 * nearest face of each rim point (VTK's locator, Filters/SchlierenWalls); the kinds, the groups
 * of a few flow faces between walls, and the note are decided here.
 */
#ifndef SchlierenWallFaces_h
#define SchlierenWallFaces_h

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace schlieren
{
namespace walls
{

/** The fraction of the speed |U| next to a boundary face under which |U.n| makes it a wall. */
constexpr double WallFlux = 0.05;
/** Under this fraction of the largest |U| the fluid next to a face is at rest: neither kind. */
constexpr double MovingFluid = 0.01;
/**
 * A connected group of at most this many faces the flow crosses, with walls beside it and
 * nothing else but fluid at rest, is taken as walls: the flow turning onto a wall (a
 * reattachment, a stagnation point), where the velocity of the cell beside the face is not
 * along it.
 */
constexpr std::size_t FewFaces = 8;

/** What ClassifyFaces found (for the log). */
struct RimReport
{
  std::string Velocity; // the velocity array's name ("" if the mesh has none)
  std::size_t WallFaces = 0, FlowFaces = 0, StillFaces = 0, RimPoints = 0;
  std::size_t TurnedFaces = 0; // of WallFaces: few flow faces between walls (see FewFaces)
};

/** A face's kind: at rest beside it, a wall, crossed by the flow; left out (see ClassifyFaces). */
enum FaceKind : unsigned char
{
  StillFace = 0,
  WallFace = 1,
  FlowFace = 2,
  LeftOut = 255
};

/**
 * The kind of each of `faces` boundary faces: face f has the points
 * connectivity[offsets[f]] .. connectivity[offsets[f + 1] - 1] (indices of the surface's
 * points, below `points`; they tell which faces touch), the unit normal normals[3f..3f+2] and
 * the velocity beside it velocity[3f..3f+2]; `largestSpeed` is the largest |U| of the mesh.
 * Faces of fewer than 3 points, and faces whose normal lies within 25 deg of axis `ignoreAxis`
 * (the planar case's front and back, a wedge's sides; -1: none) are LeftOut. `report` gets the
 * counts.
 */
std::vector<unsigned char> ClassifyFaces(std::size_t faces, const std::int64_t* offsets,
  const std::int64_t* connectivity, std::size_t points, const double* normals,
  const double* velocity, double largestSpeed, int ignoreAxis, RimReport& report);

/** The log's note: the faces of each kind, and `marked` grid points taken as a body. */
std::string BesideWallsNote(const RimReport& report, std::size_t marked);

} // namespace walls
} // namespace schlieren

#endif
