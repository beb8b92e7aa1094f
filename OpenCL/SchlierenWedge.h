// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenWedge.h
 * @brief An axisymmetric CFD case given as a wedge (OpenFOAM's way): found from its points.
 *
 * An axisymmetric OpenFOAM case is a wedge of a few degrees, one cell thick: every point of the
 * mesh lies on one of two planes through a common line, the symmetry axis. DetectWedge finds the
 * two planes (least squares on the points above and below their mid-plane), checks that they
 * hold every point, meet at a small angle along a line parallel to a coordinate axis, and that
 * the mesh lies on one side of that line; and says why where one of these fails.
 */
#ifndef SchlierenWedge_h
#define SchlierenWedge_h

#include <cstddef>
#include <string>

namespace schlieren
{

/** What DetectWedge found. Coordinates: axial, radial, thin are world axes (0 x, 1 y, 2 z). */
struct Wedge
{
  bool Found = false;
  /** Every point lies on one of two fitted planes (one cell across): a wedge in shape, found or
   * not (not where its axis is tilted, its angle too large or the mesh on both sides). */
  bool OnTwoPlanes = false;
  std::string Why;  ///< where not found: the reason, for the user
  int Axial = 0;    ///< the world axis the symmetry axis is parallel to
  int Radial = 1;   ///< the in-plane axis across it
  int Thin = 2;     ///< the axis across the wedge (its thinnest side)
  double AxisRadial = 0.0; ///< the axis's radial coordinate
  double AxisThin = 0.0;   ///< the axis's thin coordinate
  double Angle = 0.0;      ///< the angle between the two planes (radians)
  double MidTilt = 0.0;    ///< the mid-plane's angle from the radial axis towards the thin one
  double Sign = 1.0;       ///< +1: the mesh lies at radial > AxisRadial; -1: below
  double Reach = 0.0;      ///< the largest distance of a point from the axis along the mid-plane
  double Residual = 0.0;   ///< the largest distance of a point from its plane
};

/** The largest angle between the two planes taken as a wedge (degrees). */
constexpr double WedgeMaxAngleDegrees = 10.0;

/** Finds the wedge of `n` points (x, y, z interleaved); see Wedge::Why where there is none. */
Wedge DetectWedge(const double* xyz, std::size_t n);

} // namespace schlieren

#endif
