// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenBodies.h
 * @brief Solid bodies from a CFD grid's resampling: which points outside every cell are a body.
 *
 * A CFD grid leaves out the solid it flows around (the blunt fin's fin, a cylinder, a wing): when
 * it is resampled onto an image, the points inside the body find no cell, as do the points beyond
 * the grid's outer boundary. Only the former should stop light. The rule (see docs/CFD.md):
 * invalid points are a body when the flow encloses them, that is, when their connected region of
 * invalid points (6 neighbours) does not reach the image's boundary; except through the faces
 * the user marks as walls (a plate the body stands on, a symmetry plane that cuts it, a face where
 * the sampling box cuts through it), which no outside region is meant to reach.
 */
#ifndef SchlierenBodies_h
#define SchlierenBodies_h

#include <cstddef>

namespace schlieren
{

/**
 * Marks in `solid` (one byte per point, x fastest: 1 body, 0 not) the points with valid[i] == 0
 * whose region of invalid points does not reach a face of the grid except those with
 * wallFaces[f] != 0 (f: xmin, xmax, ymin, ymax, zmin, zmax); valid points are never solid.
 * Returns the number of solid points. `wallFaces` may be null (no walls: only enclosed holes).
 */
std::size_t EnclosedInvalidPoints(
  const int dims[3], const unsigned char* valid, const int* wallFaces, unsigned char* solid);

class Parallel;

/**
 * EnclosedInvalidPoints on a grid split over ranks: this rank holds the points `extent` (inclusive
 * indices of the whole grid `whole`, both x0, x1, y0, y1, z0, z1; empty: x1 < x0) with their
 * validity. The outside is flooded from the whole grid's open faces on every piece, and the
 * pieces hand on, round after round, the outside points next to or shared with another's piece,
 * until no piece finds a new one: every rank's `solid` (over its extent) is then the part of the
 * one-process answer on the whole grid. Collective: every rank calls it. Returns this rank's
 * solid points.
 */
std::size_t EnclosedInvalidPointsOfPiece(Parallel& parallel, const int extent[6], const int whole[6],
  const unsigned char* valid, const int* wallFaces, unsigned char* solid);

/**
 * The bodies a CFD mesh leaves out beside its walls (a wedge or a step on the domain's edge,
 * which reach the grid's boundary and so are not enclosed). `rim` holds, for the invalid points
 * next to a valid one, which boundary face of the mesh is nearest: 1 a wall (a face the flow
 * does not cross), 2 a face the flow crosses (an inlet, an outlet, a far field); 0 elsewhere.
 * Every connected region of invalid points (6 neighbours) whose rim has more wall points than
 * flow points is marked in `solid` (added to what is there); in a region with wall points but no
 * more of them than flow points, the points nearer (in steps between neighbours) to a wall rim
 * point than to a flow rim point are marked. Returns the number of points marked.
 */
std::size_t InvalidRegionsBesideWalls(
  const int dims[3], const unsigned char* valid, const unsigned char* rim, unsigned char* solid);

} // namespace schlieren

#endif
