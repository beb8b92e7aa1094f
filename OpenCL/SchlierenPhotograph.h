// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenPhotograph.h
 * @brief A laboratory photograph beside a traced image (issue 51): registration by a similarity
 * transform, grey calibration, the images on the film's grid, and the distance between the two
 * images' strong-gradient lines. VTK-free; every front end calls RegisterPhotograph.
 *
 * Pixel conventions: both images x fastest, row 0 first in memory (VTK's order: row 0 at the
 * film's origin). The transform maps a film pixel (i, j) to photograph pixel coordinates
 *   (u, v) = Scale R(Rotation) ((i, j) - film centre) + photograph centre + Shift,
 * centres ((n - 1) / 2), Scale in photograph pixels per film pixel, Rotation in degrees
 * (counter-clockwise), Shift in photograph pixels. A mirrored photograph is not a similarity: flip
 * it before.
 */
#ifndef SchlierenPhotograph_h
#define SchlierenPhotograph_h

#include <string>
#include <vector>

namespace schlieren
{

/** The filter's settings ("Name=value" lines through the C interface: ParsePhotographSettings). */
struct PhotographSettings
{
  /** The start from the bench: the photograph's pixel on the test section in world units (camera
   * pixel / magnification); 0: unknown (the scale is searched over ScaleRange about the scale at
   * which the two images' areas agree). */
  double PhotoPixelSize = 0;
  /** 2 to 4 point pairs the user typed: groups of 4 numbers, photograph pixel (u, v) and world
   * (x, y) on the film plane. Empty: none. */
  std::vector<double> PointPairs;
  /** What the correlation refines: "Similarity" (scale, rotation, shift; the scale stays the
   * bench's where PhotoPixelSize is given), "Rigid" (rotation, shift), "Shift", "None" (the start
   * as given: needs PointPairs). */
  std::string Refine = "Similarity";
  /** Factors about the start scale searched where the scale is not known (PhotoPixelSize 0). */
  double ScaleRange[2] = { 0.6, 1.6 };
  /** Rotation searched, +- degrees (where PointPairs do not give it). */
  double MaxRotation = 12.0;
  /** Shift searched, as a fraction of the film's larger side (where PointPairs do not give it). */
  double MaxShift = 0.3;
  /** A strong-gradient line: a ridge of the gradient magnitude above this fraction of the film's
   * strongest gradients (its 99.9th percentile). */
  double LineThreshold = 0.25;
  /** Lines shorter than this (film pixels) are dropped. */
  int MinLineLength = 8;
  /** Lines farther apart than this (world units) do not match; 0: a tenth of the film's size. */
  double MaxLineDistance = 0;
  /** Squares of the checkerboard, film pixels. */
  int CheckerSize = 16;
  /** Refuse below the threshold (1), or report without refusing (0: for studies of the score). */
  bool Refuse = true;
};

/** A strong-gradient line: a polyline in world units on the film plane. */
struct PhotographLine
{
  int Image = 0;              ///< 0: the film's line, 1: the photograph's
  std::vector<double> Points; ///< x y pairs, world units
  int Match = -1;             ///< the other image's line that most of its points are nearest to
  double Distance = -1;       ///< median distance of its matched points to the other image's lines (world); -1: none matched
  double Offset[2] = { 0, 0 };///< mean vector from its matched points to their nearest points (world)
  double Matched = 0;         ///< fraction of its points within MaxLineDistance of the other image's lines
};

struct PhotographResult
{
  bool Match = false;      ///< registered and above the threshold
  std::string Reason;      ///< why not (empty when Match)
  double Scale = 1, Rotation = 0, Shift[2] = { 0, 0 };
  double PhotoPixelSize = 0;       ///< world units per photograph pixel found (film pixel / Scale)
  double Sigma[4] = { 0, 0, 0, 0 };///< standard errors: shift x, y (photo px), rotation (deg), scale (relative)
  double EdgeUncertainty = 0;      ///< the position's standard error at the film's worst corner, film pixels (docs/CFD.md)
  double EdgeNoise = 0;            ///< EdgeUncertainty's part from the maps' residuals (their noise, correlated over pixels)
  double EdgeSpread = 0;           ///< EdgeUncertainty's part from the spread between parts of the film (a jackknife over tiles)
  int UncertaintyWindow = 0;       ///< the residuals' correlation window (film pixels) the uncertainty counted
  double WeakDirection = 0;        ///< the film direction (deg) along which a shift costs the correlation least
  double WeakRatio = 0;            ///< its cost against the costliest direction's (near 0: the shift is not held along it)
  std::string Warnings;            ///< what the user should know (a direction not held)
  double Score = 0;        ///< normalised correlation of the gradient maps on the film's grid
  double Threshold = 0;    ///< the score a match must reach: above what scrambled copies reach (docs/CFD.md)
  double NullScore = 0;    ///< the best score of scrambled photographs (searched and refined alike)
  double CoarseScore = 0;  ///< the correlation at the coarse search's level
  double Overlap = 0;      ///< fraction of the film the photograph covers
  std::string Start;       ///< where the search started
  // grey calibration
  bool GreyFitted = false;
  std::string GreyReason;
  double Gamma = 1, GammaError = 0, Background = 0, Vignetting = 1, GreyResidual = 0;
  double FilmBackground = 0; ///< the film's free-stream level
  int GreyPixels = 0;
  // images on the film's grid (Width x Height)
  int Width = 0, Height = 0;
  std::vector<float> Registered, Calibrated, Difference, Checkerboard, LineDistance;
  std::vector<unsigned char> Valid;
  std::vector<PhotographLine> Lines;
  double Seconds = 0;
  /** The report as JSON (everything above but the images). */
  std::string Json() const;
};

/** Reads "Name=value" lines (the names of PhotographSettings); unknown names and bad values are
 * refused with a message. */
PhotographSettings ParsePhotographSettings(const std::string& text);

/**
 * Registers `photo` (photo_size[0] x photo_size[1] grey values) onto the film (film_size pixels of
 * traced intensity, `film_origin` the world position of pixel (0, 0)'s centre, `pixel_size` world
 * units a pixel) and compares them. Throws schlieren::Error for input it cannot take (sizes,
 * non-finite values); a photograph that does not match is a result with Match false and Reason.
 */
PhotographResult RegisterPhotograph(const int film_size[2], const double film_origin[2],
  double pixel_size, const float* film, const int photo_size[2], const float* photo,
  const PhotographSettings& settings);

} // namespace schlieren

#endif
