// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenDistributed.h
 * @brief Tracing a volume spread over ranks: each rank holds its piece (with ghost points), traces
 * the rays that are in it and hands a ray that leaves it to the rank that owns where it went.
 *
 * The cells of the whole grid are shared out by the pieces' point extents (a piece with points
 * x0..x1 owns cells x0..x1-1 along x, as VTK's structured pieces share their face points). A ray
 * belongs to the rank that owns the cell it is in; after every step that ends in a cell another
 * rank owns, its whole state (the march, where it started, its pixel) goes to that rank; rounds of
 * tracing and exchange continue until no ray is in flight. Samples are taken with the whole grid's
 * coordinates on ghost points that are copies of the neighbours' (sch_params ox, oy, oz), so a ray
 * takes the same steps with the same arithmetic whichever ranks it crosses: records are bit for bit
 * those of one process with the whole volume, and the films too (they are splatted on rank 0 in
 * pixel order, as one process does).
 *
 * On the CPU backend or an OpenCL device (the kernel sch_walk_pieces steps a batch of rays until
 * each leaves the volume or the rank's cells); trilinear reconstruction, fixed steps or the octree
 * up to DistributedOctreeMaxLevel, solid bodies (their bits on the held points); Reconstruction Cubic (and Auto's choice between
 * the two) on pieces packed for it (smoothLevels), the smoothness test on the whole grid's range
 * and every owned cell's bytes the whole grid's; the step-doubling estimate as a second trace
 * at twice the step on the pieces (TraceAllEstimated); other settings are refused with an Error
 * that says so.
 */
#ifndef SchlierenDistributed_h
#define SchlierenDistributed_h

#include "SchlierenEngine.h"
#include "SchlierenLimits.h"
#include "SchlierenParallel.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace schlieren
{

/** A rank's piece of the whole volume, as a reader or ParaView's redistribution gives it. */
struct Piece
{
  int WholeDimensions[3] = { 0, 0, 0 };
  double Origin[3] = { 0, 0, 0 }; ///< of the whole grid's first point
  double Spacing[3] = { 1, 1, 1 };
  /** Points held, inclusive whole-grid indices: x0, x1, y0, y1, z0, z1 (empty: x1 < x0). */
  int Extent[6] = { 0, -1, 0, -1, 0, -1 };
  const float* NMinus1 = nullptr; ///< n - 1 at the Extent's points, x fastest
  const unsigned char* Solid = nullptr; ///< non-zero at points in a solid body (null: none here)
};

/** What ray passing cost in a trace (this rank's share, then summed over ranks by the caller). */
struct DistributedStats
{
  double Rounds = 0;          ///< trace-and-exchange rounds (the same on every rank)
  double RaysHandedOn = 0;    ///< rays this rank sent to another
  double BytesExchanged = 0;  ///< bytes this rank sent (ray states and the records to rank 0)
  double SecondsTracing = 0;  ///< this rank's time stepping rays
  double SecondsExchanging = 0; ///< this rank's time in the exchanges (waiting for others included)
  std::string BackendUsed;    ///< this rank's: "OpenCL" or "CPU"
  std::string DeviceName;     ///< this rank's device
  std::string Warnings;       ///< what this rank's user should know (an OpenCL fallback)
};

/** The octree levels pieces hold at least where the octree asks for them (blocks of 2^3 cells, 10
 * ghost layers): every level a rank holds must be the one the whole grid gives, which takes
 * ghosts as deep as a block; higher levels where the volume reaches them (OctreeLevelReached). */
constexpr int DistributedOctreeMaxLevel = 3;

/**
 * The highest octree level (up to maxLevel) that some block of the whole grid passes at tolerance
 * `tol`, found from the pieces' own points (no ghosts: per block the minimum and maximum of n - 1
 * over its points and halo, reduced over the ranks) for the levels above
 * DistributedOctreeMaxLevel; at least min(maxLevel, DistributedOctreeMaxLevel). The pieces then
 * hold levels up to it with ghosts of 2^level + 2 points (GhostPointsFor), and every cell's level
 * is one process's at that maxLevel. Collective.
 */
int OctreeLevelReached(const Piece& piece, double tol, int maxLevel, Parallel& parallel);

/**
 * The ghost points a trace with settings `s` needs around the owned cells: the longest step's reach
 * in cells (an octree skip crosses at most a block of 2^octreeLevel cells), the trilinear cell and
 * the gradient's central differences, and one to spare; with the octree, also the block and halo
 * that an owned cell's level is computed from.
 */
int GhostPointsFor(const TraceSettings& s, int octreeLevel = 0);

/**
 * The smoothness levels (Volume::Smooth bits 4-6) a trace with settings `s` can tell apart: 0 for
 * Trilinear; else the least level q whose step room, 2^q - 1 cells, is a cell longer than the
 * longest base step (Auto's candidates included), past which no step is longer. Pieces hold levels
 * up to it, not to 7: an owned cell's level q needs ghosts of 2^q + 5 points (GhostPointsFor).
 */
int SmoothLevelsFor(const TraceSettings& s);

/** This rank's share of a distributed volume. Construction is collective. */
class DistributedVolume
{
public:
  /**
   * Gathers every rank's extent, checks that the pieces share out the whole grid's cells (no gap,
   * no overlap), copies the ghost points from the ranks that hold them, validates and packs n - 1
   * and its gradient. Throws the same Error on every rank where any rank's piece is bad.
   */
  DistributedVolume(const Piece& piece, int ghostPoints, Parallel& parallel);
  /**
   * The same, with the min-max octree of the whole grid (levels up to `octreeMaxLevel`: ghosts of
   * 2^octreeMaxLevel + 2 points at least) for `octreeTolerance` (>= 0): each rank computes the levels of the
   * cells it holds on the whole grid's blocks, which for its owned cells are the whole grid's.
   */
  DistributedVolume(const Piece& piece, int ghostPoints, Parallel& parallel, double octreeTolerance,
    int octreeMaxLevel = DistributedOctreeMaxLevel, int smoothLevels = 0);
  /* octreeTolerance < 0: no octree. smoothLevels > 0: packed for Reconstruction Cubic
   * (PackFieldHighOrder on the whole grid's range), smoothness levels up to it (SmoothLevelsFor). */

  /** The whole grid (no field): for the film and the parameters. */
  Volume Whole() const;
  /** The points this rank holds (owned cells' points and ghosts), packed. */
  Volume Held() const;
  /** The rank that owns cell (i, j, k) of the whole grid. */
  int OwnerOfCell(int i, int j, int k) const;
  bool OwnsCell(int i, int j, int k) const;

  int WholeDimensions[3];
  double Origin[3], Spacing[3];
  int Ghost;
  int HeldLo[3], HeldDims[3]; ///< first held point (whole-grid index) and held dimensions
  int Owned[6];               ///< owned cells: [lo, hi) per axis (x, y, z)
  std::vector<std::array<int, 6>> AllOwned; ///< every rank's owned cells
  AlignedFloats Packed;       ///< 4 floats per held point (Volume::Field layout), page-aligned: a
                              ///< CPU OpenCL device traces it in place
  std::uint64_t Stamp = NewVolumeStamp(); ///< the held points' (a device keeps its copy)
  std::vector<unsigned char> Levels; ///< the kernels' byte per held cell: octree level (Octree),
                                     ///< smoothness (HighOrder); empty: neither
  bool Octree = false;               ///< Levels holds the octree levels
  bool HighOrder = false;            ///< packed for Cubic: Levels holds the smoothness bits
  int SmoothLevelMax = 0;            ///< the smoothness levels held go up to this
  bool HasSolid = false;             ///< some rank's piece has a body: Solid holds the held points
  std::vector<unsigned char> Solid;  ///< 1 at held points in a body (HasSolid)
  /**
   * The kernels' bytes for a trace with P on the held points: Levels without a body; with one,
   * the solid, near and lowered-level bits of one process's (MakeCellBytes) for steps of up to
   * `reach` world units, every owned cell's the whole grid's (the ghosts reach the step and the
   * octree blocks). Kept for the last reach.
   */
  std::shared_ptr<const std::vector<unsigned char>> CellBytes(double reach) const;
  /** The bytes the tracing reads: with a body, those of the last CellBytes call (each trace
   * makes it first), else Levels (or null). */
  const unsigned char* TraceBytes() const
  {
    if (this->HasSolid && this->KeptBytes)
      return this->KeptBytes->data();
    return this->Levels.empty() ? nullptr : this->Levels.data();
  }
  double LevelTolerance = 0;         ///< the tolerance the levels were built for
  int LevelMax = 0;                  ///< the largest level they may hold
  float RangeLo = 0, RangeHi = 0; ///< n - 1 over the whole grid
  mutable std::shared_ptr<const std::vector<unsigned char>> KeptBytes; ///< CellBytes' last
  mutable double KeptReach = -1;
  double HeldBytes() const { return double(sizeof(float)) * Packed.size() + Levels.size(); }
};

/**
 * Line of sight (Integrator Straight, without the octree, Cubic or KeepInvariant) needs no ray passing:
 * every rank integrates the steps that start in its cells (walking every ray's positions with the
 * same arithmetic as one process, sampling only its own), and rank 0 adds each ray's runs in
 * order. The sums are reassociated, so these records equal one process's within float rounding
 * (docs/PARALLEL.md has the measured differences), not bit for bit; with
 * lineOfSightSums false such rays are handed on like the others (bit for bit).
 *
 * Traces rays that start at the film points ab (pairs; the same on every rank) through the
 * distributed volume; returns every record, in the order of ab, on every rank (`everywhere`) or
 * on rank 0 only (the others get an empty vector).
 */
std::vector<RayRecord> TraceRaysDistributed(const DistributedVolume& volume,
  const TraceSettings& settings, const std::vector<float>& ab, Parallel& parallel,
  bool everywhere = true, DistributedStats* stats = nullptr, bool lineOfSightSums = true);

/**
 * ResolveAuto on a distributed volume: the pilot rays traced on the pieces (every rank gets every
 * record), so every rank makes the same choice, and it is the choice one process makes with the
 * whole volume (and the same octree). Collective.
 */
TraceSettings ResolveAutoDistributed(const DistributedVolume& volume, const TraceSettings& settings,
  Parallel& parallel, AutoChoice* choice = nullptr);

/**
 * Accumulate on a distributed volume: settings.Passes passes of the whole film; the sums are
 * complete on rank 0 (the other ranks' `sums` are left with their size and no photons).
 * RankIndex/RankCount must be 0/1 (every rank traces the rays in its piece, not a pixel share).
 */
void AccumulateDistributed(const DistributedVolume& volume, const TraceSettings& settings,
  FilmSums& sums, Parallel& parallel, DistributedStats* stats = nullptr,
  const ProgressFunction& progress = nullptr);

} // namespace schlieren

#endif
