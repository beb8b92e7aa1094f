// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenSymmetry.h
 * @brief RefractiveIndex's Symmetry Planar and Axisymmetric (and an OpenFOAM wedge revolved about
 * its own axis), VTK-free: every front end calls these and samples its mesh where they say.
 *
 * A 2D input (a plane normal to x, y or z; an r-z half plane; a wedge one cell across) becomes a
 * volume in three steps:
 *  1. PlanSymmetry: the checks (the messages users see), the wedge, and the 3D grid to make;
 *  2. SymmetrySamples: the in-plane points where the front end samples its 2D mesh (the
 *     mid-plane for Planar; (axial coordinate, distance to the axis) for Axisymmetric, each
 *     distinct distance once per axial position), and for every grid point the sample it takes;
 *  3. ExpandSamples / ExpandValidity: the sampled arrays and their validity onto the grid.
 * The sampling itself (finding the mesh's cell of each sample) stays the front end's.
 */
#ifndef SchlierenSymmetry_h
#define SchlierenSymmetry_h

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace schlieren
{

/** RefractiveIndex's Symmetry (the proxy's entries, in order). */
enum SymmetryKind
{
  SymmetryNone = 0,
  SymmetryPlanar = 1,
  SymmetryAxisymmetric = 2
};

/** The RefractiveIndex properties that shape a symmetric grid. */
struct SymmetrySettings
{
  int Symmetry = SymmetryNone;
  int SymmetryAxis = 0; ///< 0 x, 1 y, 2 z
  double Span = 1.0;
  bool AxisFromWedge = true;
  int SamplingDimensions[3] = { 0, 0, 0 }; ///< any <= 0: automatic
  int AutomaticDimension = 128;
  bool UseSamplingBounds = false;
  double SamplingBounds[6] = { 0, 1, 0, 1, 0, 1 };
};

/** What the front end knows of its 2D input. */
struct SymmetryInput
{
  bool HasPoints = false;  ///< the input has points (Bounds are set)
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 };
  /** x, y, z of every point of a mesh (all its blocks), for the wedge and the one-cell-across
   * checks; may be null for an image. */
  const double* Points = nullptr;
  std::size_t Count = 0;
  /** The points are one data set (a mesh one cell across is a plane); false: a composite's. */
  bool OneDataSet = true;
  bool Image = false;       ///< an image: its extent, origin and spacing below
  int ImageExtent[6] = { 0, -1, 0, -1, 0, -1 };
  double ImageOrigin[3] = { 0, 0, 0 };
  double ImageSpacing[3] = { 1, 1, 1 };
};

/** The symmetric grid and where it samples the plane. */
struct SymmetryPlan
{
  int Symmetry = SymmetryPlanar;
  int PlaneAxis = 2;           ///< the axis normal to the input's plane (a wedge: its thin axis)
  double PlaneCoordinate = 0;  ///< the plane's coordinate along it (a wedge: its axis's)
  double RadialSign = 1.0;     ///< the side of the axis revolved
  double RadialExtent = 0.0;   ///< the input's largest r
  int AxisInUse = 0;           ///< the symmetry axis (SymmetryAxis, or the wedge's)
  double AxisRadial = 0.0;     ///< where the axis crosses the radial axis (a wedge's)
  double MidTilt = 0.0;        ///< the sampled half plane's tilt (a wedge's mid-plane)
  int Dims[3] = { 0, 0, 0 };
  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  std::string WedgeNote;             ///< what the wedge detection found, for the log
  std::vector<std::string> Warnings; ///< for rank 0 to say (the input crossing the axis)

  /** The 8 numbers that SymmetrySamples and SymmetryToMesh need (the C interface's geometry):
   * Symmetry, PlaneAxis, PlaneCoordinate, RadialSign, RadialExtent, AxisInUse, AxisRadial,
   * MidTilt. */
  void Geometry(double g[8]) const;
  /** The plan from Geometry's numbers and a grid; throws schlieren::Error where they are not
   * one (an axis outside 0..2, the two the same, a number not finite). */
  static SymmetryPlan FromGeometry(const double g[8], const int dims[3], const double origin[3],
    const double spacing[3]);
};

/** The checks and the grid: "" and `plan` filled, or the message for the user. */
std::string PlanSymmetry(const SymmetrySettings& settings, const SymmetryInput& input,
  SymmetryPlan& plan);

/** The in-plane points to sample (x, y, z each) and, for every grid point (x fastest), the index
 * of the sample it takes. */
void SymmetrySamples(const SymmetryPlan& plan, std::vector<double>& points,
  std::vector<std::int64_t>& sampleOf);

/** out[id] = samples[sampleOf[id]] for `components` floats each, `count` grid points. */
void ExpandSamples(const std::int64_t* sampleOf, std::size_t count, const float* samples,
  int components, float* out);

/** valid[id] = sampleValid[sampleOf[id]] != 0 (sampleValid null: none valid). */
void ExpandValidity(const std::int64_t* sampleOf, std::size_t count,
  const unsigned char* sampleValid, unsigned char* valid);

/** Where the grid point `x` sampled the mesh: `x` itself (Symmetry None), on the mid-plane
 * (Planar), or at its axial coordinate and distance to the axis on the sampled half plane. */
void SymmetryToMesh(const SymmetryPlan& plan, const double x[3], double at[3]);

/** Whether an input of these bounds is thin enough to be a wedge (worth gathering its points
 * for WedgeWithoutSymmetry). */
bool MayBeWedge(const double bounds[6]);

/** The warning for an axisymmetric wedge traced with Symmetry None (AxisFromWedge on), or "". */
std::string WedgeWithoutSymmetry(const double* xyz, std::size_t n);

} // namespace schlieren

#endif
