// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenNumerical.h
 * @brief "Numerical schlieren", the image CFD users know: a grey scale of the density gradient.
 *
 * Quirk's grey scale (Quirk 1994; the form most CFD papers print): I = exp(-k S), with
 * S = (q - c0 qmax) / ((c1 - c0) qmax) clamped to [0, 1], q the gradient's magnitude |grad rho|
 * (or the magnitude of its component normal to a knife edge), qmax its largest value over the
 * image. Nothing here traces light: q is read on a plane through the volume normal to the view
 * (Slice) or averaged along the view (LineOfSight), on the film SchlierenImage would make for the
 * same view and resolution (MakeFilm), so the two images line up pixel for pixel.
 *
 * The gradient is taken at the grid points by central differences in world units (one-sided
 * beside a solid point or the box's faces, 0 along an axis one point thick) and interpolated
 * trilinearly at the sample points. Solid points (Solid non-zero) are no part of the flow: a
 * pixel whose plane point (Slice) or any of whose line's samples (LineOfSight) falls in a body
 * (interpolated solid at least one half, as the tracer's test) is black and marked blocked.
 */
#ifndef SchlierenNumerical_h
#define SchlierenNumerical_h

#include "SchlierenEngine.h"
#include "SchlierenParallel.h"

#include <string>
#include <vector>

namespace schlieren
{

/** Where the gradient is read. */
enum class NumericalMode
{
  Slice = 0,      ///< on the plane normal to the view at SliceOffset from the volume's centre
  LineOfSight = 1 ///< averaged over the samples along each pixel's line through the volume
};

/** Which gradient the grey scale shows. */
enum class NumericalQuantity
{
  Magnitude = 0,     ///< |grad rho| (all three components)
  KnifeComponent = 1 ///< grad rho . a, a the knife normal in the film plane (grey from |.|)
};

struct NumericalSettings
{
  double ViewDirection[3] = { 0, 0, -1 };
  double ViewUp[3] = { 0, 1, 0 };
  int Resolution[2] = { 512, 512 };
  NumericalMode Mode = NumericalMode::Slice;
  NumericalQuantity Quantity = NumericalQuantity::Magnitude;
  double KnifeAngle = 0.0;  ///< degrees; 0: knife normal along film x (as SchlierenImage)
  double SliceOffset = 0.0; ///< world units along ViewDirection from the volume's centre
  double StepSize = 0.5;    ///< LineOfSight: samples this many voxels (smallest spacing) apart
  double C0 = -0.001;       ///< low end of the scale, a fraction of qmax, in [-1, 0]
  double C1 = 0.05;         ///< high end (full dark), a fraction of qmax, in [0.001, 1]
  double K = 5.0;           ///< the exponent's scale, in [0.001, 100]
  double Maximum = 0.0;     ///< qmax; 0: automatic, the largest q over the image's flow pixels
};

/** A scalar field on a regular grid (non-owning), x fastest, and its optional solid points. */
struct ScalarGrid
{
  int Dimensions[3] = { 0, 0, 0 };
  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  const float* Values = nullptr;
  const unsigned char* Solid = nullptr;
  /** Optional: non-zero at points without data (outside the CFD mesh, not a body): no part of
   * the differences, as solid points, but they block nothing. */
  const unsigned char* Excluded = nullptr;
};

struct NumericalImage
{
  FilmGeometry Film;
  std::vector<float> Intensity;     ///< exp(-k S); 0 where blocked
  std::vector<float> Gradient;      ///< q (Magnitude) or the signed component (KnifeComponent),
                                    ///< field units per world unit; 0 where blocked
  std::vector<unsigned char> Blocked; ///< 1 where a body is on the plane or the line
  double Maximum = 0.0;             ///< the qmax used
  double Largest = 0.0;             ///< the largest q over the flow pixels
};

/** Throws Error naming the setting where one is out of its range (the XML domains' ranges). */
void CheckNumericalSettings(const NumericalSettings& s);

/** The film SchlierenImage makes for this grid, view and resolution. */
FilmGeometry NumericalFilm(const ScalarGrid& grid, const NumericalSettings& s);

/**
 * The numerical-schlieren image of `grid` (see the file's comment). `progress` (may be empty) gets
 * the share of the image done, on the calling thread, between blocks of film rows (each block
 * about NumericalBlockSamples samples: a fraction of a second; a LineOfSight image of a 256^3
 * volume on a 1024^2 film takes about a minute on two cores); once it returns false the image
 * stops there and Error "aborted at P % of the image: no image" is thrown. The image is bit for
 * bit the same with or without it.
 */
NumericalImage NumericalSchlieren(
  const ScalarGrid& grid, const NumericalSettings& s, const ProgressFunction& progress = nullptr);

/** About this many samples (pixels times samples along each pixel's line) between two progress
 * reports of NumericalSchlieren. */
constexpr double NumericalBlockSamples = 4.0e6;

/**
 * The same image from a volume split over ranks (collective): `piece` is this rank's part of the
 * grid, `offset` its first point's index in the whole grid (`whole`: dimensions, origin and
 * spacing, no values). The pieces (values, solid and excluded points) are gathered on rank 0,
 * which makes the image from the whole grid exactly as one process does; the other ranks return
 * false and an empty image. A piece with no points sends nothing. Points no piece holds, or an
 * error on any rank, throw Error on every rank (the same message: Parallel::Failure). With one
 * rank this is NumericalSchlieren(piece, s, progress). `progress` is called on rank 0 (which makes
 * the image); its abort is every rank's Error.
 */
bool NumericalSchlierenOfPieces(Parallel& parallel, const ScalarGrid& piece, const int offset[3],
  const ScalarGrid& whole, const NumericalSettings& s, NumericalImage& image,
  const ProgressFunction& progress = nullptr);

/**
 * The field's name that every rank images (collective): first every rank's `error` is agreed on
 * (Parallel::Failure; a failure throws Error, the same on every rank), then the name `mine` of
 * the first rank whose piece is not empty ("" where this rank's is). Throws Error on every rank
 * where two ranks' pieces carry different names or every piece is empty. With one rank: `mine`.
 */
std::string AgreedFieldName(Parallel& parallel, const std::string& error, const std::string& mine);

/** Quirk's grey of q for the largest qmax: exp(-k clamp((q - c0 qmax) / ((c1 - c0) qmax), 0, 1)). */
double QuirkGrey(double q, double qmax, double c0, double c1, double k);

const char* NumericalModeName(NumericalMode m);
const char* NumericalQuantityName(NumericalQuantity q);

} // namespace schlieren

#endif
