// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenSamplingGrid.h
 * @brief RefractiveIndex's pipeline rules on plain numbers: the grid a mesh is resampled onto
 * (SamplingBounds, SamplingDimensions, AutomaticDimension, the memory it costs), that grid
 * following a mesh that moves over time, and the piece of its input an update asks for.
 *
 * Every front end reads its input's bounds and arrays (VTK's business) and its pipeline keys, and
 * calls these for the rule, so that the C++ filter, the Python algorithm and the Python plugin set
 * up the same grid and ask for the same extent, with the C++ filter's messages. No VTK here.
 */
#ifndef SchlierenSamplingGrid_h
#define SchlierenSamplingGrid_h

#include <functional>
#include <string>
#include <vector>

namespace schlieren
{
class Parallel;

/** The sampling properties of RefractiveIndex (the proxy's names and defaults). */
struct SamplingSettings
{
  int SamplingDimensions[3] = { 0, 0, 0 }; // any <= 0: automatic
  int AutomaticDimension = 128;            // points along the longest side when automatic
  bool UseSamplingBounds = false;
  double SamplingBounds[6] = { 0, 1, 0, 1, 0, 1 };
  /** Whether the dimensions are automatic (any of SamplingDimensions <= 0). */
  bool Automatic() const;
};

/** The grid a mesh is resampled onto: the whole extent (0 .. dims - 1), origin and spacing. */
struct SamplingGrid
{
  int Dims[3] = { 1, 1, 1 };
  int Whole[6] = { 0, 0, 0, 0, 0, 0 };
  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
};

/**
 * The box `bounds` pulled in about its centre by a factor 1 - 1e-6 (as vtkBoundingBox's
 * ScaleAboutCenter), so that the grid's outermost points lie inside the outermost cells despite
 * round-off (as vtkResampleToImage does).
 */
void PullIn(const double bounds[6], double box[6]);

/**
 * The box RefractiveIndex resamples over: SamplingBounds where UseSamplingBounds is on, else the
 * input's bounds (`inputBounds`, nullptr where the input has no points) pulled in (PullIn). Throws
 * Error with the C++ filter's messages: "The input has no points to resample onto an image grid.",
 * or the box's problem (AutomaticDimensions' check) followed by " (SamplingBounds: xmin xmax ymin
 * ymax zmin zmax)" where the box was typed.
 */
void SamplingBox(const SamplingSettings& s, const double* inputBounds, double box[6]);

/** Bytes a resampled grid point costs the front end before the engine's share: the probe's copy of
 * the input's arrays (`arrayBytes` per point; a composite input: 64), its mask, n - 1, grad n. */
double SamplingBytesPerPoint(double arrayBytes);

/** Where the dimensions are automatic, the input's own (an AMR input's finest level, capped):
 * true with `dims` written, or false (AutomaticDimension then). May throw Error. */
using AutomaticGrid = std::function<bool(const double box[6], int dims[3])>;

/**
 * The grid over `box` (SamplingBox's): SamplingDimensions, or where automatic the input's own
 * (`own`, may be empty) or AutomaticDimension points along the longest side; checked against the
 * memory this process may use
 * (SamplingBytesPerPoint(arrayBytes) a point: "Resampling onto X x Y x Z points needs ..."). Throws
 * Error with the C++ filter's messages (the SamplingBounds suffix where the box was typed).
 */
SamplingGrid PlanSamplingGrid(const SamplingSettings& s, const double box[6], double arrayBytes,
  const AutomaticGrid& own = AutomaticGrid());

/**
 * A mesh that moves over time: `grid` (origin, spacing, whole extent as set up over an earlier
 * step's bounds) made to span `inputBounds` (this step's, pulled in as SamplingBox does) with the
 * same points. Returns false where the bounds are those of the grid (to 1e-9 of its size) or
 * empty; else writes `moved` and, where `note` is non-null, the note the C++ filter says ("...
 * the grid follows them, the same points over [x0, x1] x [y0, y1] x [z0, z1].").
 */
bool FollowBounds(
  const SamplingGrid& grid, const double inputBounds[6], SamplingGrid& moved, std::string* note);

/** What RefractiveIndex asks of its input for one update. */
struct InputRequest
{
  int Piece = 0;            // the input's piece number ...
  int Pieces = 1;           // ... of this many
  bool WholeExtent = true;  // the input's whole extent (else Extent)
  int Extent[6] = { 0, -1, 0, -1, 0, -1 };
};

/**
 * The split of `updateExtent` into piece `piece` of `pieces` with `ghosts` ghost levels, as VTK's
 * pipeline splits an image's extent (vtkExtentTranslator by cells: the larger axis halved in
 * block mode, `splitMode` 0, 1, 2 an X, Y or Z slab first, 3 block), the ghost levels clamped
 * to `updateExtent` (the translator's whole extent, as the pipeline asks it). Writes an
 * empty extent (0 -1 0 -1 0 -1) where the piece gets nothing. Returns false for a piece outside
 * 0 .. pieces - 1.
 */
bool SplitExtent(
  int piece, int pieces, int ghosts, int splitMode, const int updateExtent[6], int extent[6]);

/**
 * What RefractiveIndex asks of its input. A resampled input (a mesh, a composite, or any input
 * made a volume by Symmetry: `resampled`) is read whole: piece `rank` of `ranks` (every rank
 * probes the whole grid against its own piece), or on one piece where `symmetric` (a 2D input is
 * read whole on every rank). An image is read over the piece of the output's update extent
 * (SplitExtent of `piece`, `pieces`, `ghosts`, `splitMode`) grown by one point on every side for
 * the central differences and clamped to `whole`, as one piece.
 */
InputRequest RequestInput(bool resampled, bool symmetric, int rank, int ranks, int piece,
  int pieces, int ghosts, int splitMode, const int updateExtent[6], const int whole[6]);

/** "" where `extent` (the input's, grown) covers `requested` (the output's update extent); else
 * "The input's extent (...) does not cover the requested extent (...); the upstream filter did
 * not honour the update request." */
std::string ExtentCoverProblem(const int extent[6], const int requested[6]);

/** "" where every one of `names` (the arrays the model reads) is among `present` (the input's
 * point and cell arrays); else "<model> reads the array 'X', which the input does not have.
 * Arrays present: a, b. Choose one of them." (said before a mesh is resampled). */
std::string MissingArrayProblem(const std::vector<std::string>& names,
  const std::vector<std::string>& present, const std::string& model);

/**
 * A piece of the input refused on one rank (a cell type the sampler does not take) fails every
 * rank, so that none waits for it in the collective steps that follow: throws Error with
 * `refused` where this rank refused (non-empty), with "Another rank's piece of the input could
 * not be resampled (its message says why)." where another did. Collective.
 */
void AgreeOnRefusal(Parallel& parallel, const std::string& refused);

/** One rank's probe of its piece of the input at the grid's points (MergeProbedPieces). */
struct ProbedArray
{
  std::string Name;
  bool Have = false;           // this rank's piece has it, one component
  std::vector<double> Values;  // at the grid's points, where Have
};

/** An array of the merged grid: float, a value a grid point. */
struct MergedArray
{
  std::string Name;
  std::vector<float> Values;
};

/**
 * The grid probed in pieces (each rank its own piece of the input, MPI) made one on every rank:
 * `found` (a byte a grid point, non-zero where this rank's piece holds the point) and each of
 * `arrays` (the same names in the same order on every rank) summed over the ranks. `valid` gets 1
 * where any rank found the point; `merged` each array some rank has, in order, the mean of the
 * values of the ranks that found the point (0 where none did). Collective.
 */
void MergeProbedPieces(Parallel& parallel, const std::vector<unsigned char>& found,
  const std::vector<ProbedArray>& arrays, std::vector<unsigned char>& valid,
  std::vector<MergedArray>& merged);

} // namespace schlieren

#endif
