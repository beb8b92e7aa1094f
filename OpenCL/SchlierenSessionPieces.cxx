// SPDX-License-Identifier: BSD-3-Clause
// TraceSession with the volume in pieces: each rank keeps its piece (and ghosts) and the rays are
// handed between ranks (SchlierenDistributed.h); the other path, every rank with the whole volume,
// is in SchlierenSession.cxx.
#include "SchlierenEngineInternal.h"
#include "SchlierenSession.h"
#include "SchlierenSessionInternal.h"

#include <algorithm>
#include <sstream>

namespace schlieren
{

std::string WhyNotInPieces(const TraceSettings& s)
{
  if (!s.InPieces)
    return "TraceInPieces is off";
  return std::string();
}

void TraceSession::UpdatePieces(Parallel& parallel, const VolumePiece& piece,
  const TraceSettings& settings, SessionImage& out, const ProgressFunction& progress)
{
  const int ranks = parallel.Size(), rank = parallel.Rank();

  // 1. This rank's piece with its ghosts: kept while the input, the pieces and the ghosts it
  // needs stay the same.
  Piece p;
  for (int a = 0; a < 3; ++a)
  {
    p.WholeDimensions[a] = piece.WholeExtent[2 * a + 1] - piece.WholeExtent[2 * a] + 1;
    p.Origin[a] = piece.Origin[a] + piece.WholeExtent[2 * a] * piece.Spacing[a];
    p.Spacing[a] = piece.Spacing[a];
    p.Extent[2 * a] = piece.Extent[2 * a] - piece.WholeExtent[2 * a];
    p.Extent[2 * a + 1] = piece.Extent[2 * a + 1] - piece.WholeExtent[2 * a];
  }
  const bool octreeAsked = settings.UseOctree;
  // Reconstruction Cubic or Auto: the pieces packed for Cubic, smoothness levels as deep as the
  // steps use (SmoothLevelsFor)
  const bool highOrder = settings.Recon != Reconstruction::Trilinear;
  std::ostringstream key;
  key.precision(17);
  key << piece.Version << ' ' << ranks << ' ' << octreeAsked << ' ' << highOrder;
  for (int a = 0; a < 6; ++a)
    key << ' ' << piece.Extent[a] << ' ' << piece.WholeExtent[a];
  for (int a = 0; a < 3; ++a)
    key << ' ' << piece.Origin[a] << ' ' << piece.Spacing[a];
  // kept while the ghosts are deep enough for these settings' steps
  const bool reuse = parallel.AllOk(piece.Problem.empty() && settings.Passes >= 1 &&
    this->Pieces && key.str() == this->PiecesKey &&
    this->Pieces->Ghost >= GhostPointsFor(settings, this->Pieces->Octree ? this->Pieces->LevelMax : 0) &&
    this->Pieces->SmoothLevelMax >= SmoothLevelsFor(settings));
  if (!reuse)
  {
    this->Pieces.reset();
    this->PiecesKey.clear();
    PieceValues values;
    const std::size_t count = ExtentPoints(piece.Extent);
    LoadPieceAgreed(parallel, piece, settings, values);
    // a body: its solid points travel with n - 1 (the ghosts' too)
    const bool body = values.Solid.size() == count &&
      std::any_of(values.Solid.begin(), values.Solid.end(), [](unsigned char c) { return c != 0; });
    p.Solid = body ? values.Solid.data() : nullptr;
    // the whole-volume path's volume and sums go (its film sums are not these)
    this->ClearVolume();
    this->Sums.Resize(0, 0);
    this->SumsKey.clear();
    // the octree's tolerance: the smallest any piece was built for (RefractionOctree)
    const bool present = octreeAsked && count > 0 && values.Levels.size() == count &&
      values.HasLevelTolerance && values.LevelTolerance >= 0;
    const double tol = -parallel.Max(present ? -values.LevelTolerance : -1e300);
    const bool octree = octreeAsked && tol < 1e300;
    p.NMinus1 = values.NMinus1Data();
    // its levels up to the highest any piece was built for (as the whole volume's), held up to
    // the highest the volume reaches, with the ghosts that level's blocks need
    // (held in int range before the cast: OctreeLevelReached takes 10 at most; a broken
    // transport's noise is no level)
    const double maxLevelAll = parallel.Max(present ? double(values.MaxLevel) : -1.0);
    const int maxLevel = maxLevelAll >= -1 && maxLevelAll <= 64 ? static_cast<int>(maxLevelAll) : 64;
    const int level = octree ? OctreeLevelReached(p, tol, maxLevel, parallel) : 0;
    const int ghost = GhostPointsFor(settings, level);
    // the pieces, ghosts and octree: a failure on any rank throws on every rank
    this->Pieces = std::make_shared<DistributedVolume>(p, ghost, parallel,
      octree && level > 0 ? tol : -1.0, level, highOrder ? SmoothLevelsFor(settings) : 0);
    this->PiecesKey = key.str();
  }
  if (progress)
    progress(0.05);
  const DistributedVolume& dv = *this->Pieces;

  // 2. Framing Silhouette from the pieces (each rank scans the points of its cells, the frame
  // reduced over the ranks), Auto on the pieces (every rank the same choice), then the passes
  // not yet traced.
  TraceSettings traced = settings;
  traced.RankIndex = 0;
  traced.RankCount = 1;
  this->FrameKept(dv.Stamp, parallel,
    [&dv, &traced, &parallel]() {
      SilhouetteScan scan;
      scan.Field = dv.Packed.data();
      scan.Solid = dv.HasSolid ? dv.Solid.data() : nullptr;
      for (int a = 0; a < 3; ++a)
      {
        scan.Held[a] = dv.HeldDims[a];
        scan.Offset[a] = dv.HeldLo[a];
        // the points of the owned cells: [lo, hi), and the grid's last point on its last rank
        const int lo = dv.Owned[2 * a], hi = dv.Owned[2 * a + 1];
        scan.Lo[a] = lo - dv.HeldLo[a];
        scan.Hi[a] = hi > lo ? hi - dv.HeldLo[a] + (hi == dv.WholeDimensions[a] - 1 ? 1 : 0) : scan.Lo[a];
      }
      return FrameSilhouette(dv.Whole(), traced, scan, [&parallel](double* v, std::size_t n, bool max) {
        if (max)
          parallel.Max(v, n);
        else
          parallel.Sum(v, n);
      });
    },
    traced, out, rank == 0);
  AutoChoice choice;
  const bool autoAsked = settings.Method == Integrator::Auto;
  if (autoAsked || settings.Recon == Reconstruction::Auto)
  {
    // the choice kept across seeds, passes, films and camera moves as on the whole volume
    // (issue 50); the pieces' key stands for the volume
    std::ostringstream vk;
    vk << this->PiecesKey << ' ' << dv.Octree << ' ' << dv.Ghost;
    choice = this->ResolveKept(parallel, dv.Whole(), traced, vk.str(), [&](TraceSettings& t) {
      AutoChoice c;
      t = ResolveAutoDistributed(dv, t, parallel, &c);
      return c;
    });
  }
  else
    traced = ResolveAutoDistributed(dv, traced, parallel, &choice);
  if (!autoAsked)
  {
    choice.Method = traced.Method;
    choice.StepSize = traced.StepSize;
    choice.Recon = traced.Recon;
  }
  else if (rank == 0)
  {
    out.Notes.push_back({ false, choice.Report });
    if (choice.PiecesBound && choice.StepSize >= AutoPiecesReach(traced.Recon == Reconstruction::Cubic))
      out.Notes.push_back({ false,
        "Auto on the pieces tried no step longer than " +
          std::to_string(static_cast<int>(AutoPiecesReach(traced.Recon == Reconstruction::Cubic))) +
          " voxels (the pieces' ghost layers hold no longer ones): one process (TraceInPieces off) "
          "may choose a longer, cheaper step" });
    if (!choice.Met)
      out.Notes.push_back({ true, choice.Report });
  }
  Volume grid = dv.Whole();
  // Finalize's blocked output where the volume has a body (a flag: the grid has no field)
  static const unsigned char aBody = 1;
  grid.Solid = dv.HasSolid ? &aBody : nullptr;
  std::ostringstream sk;
  sk.precision(17);
  sk << traced.PhotonKey() << " | " << this->PiecesKey << ' ' << dv.Octree;
  const std::string sumsKey = sk.str();
  const bool reuseSums = parallel.AllOk(
    sumsKey == this->SumsKey && this->Sums.Passes > 0 && settings.Passes >= this->Sums.Passes);
  if (!reuseSums)
  {
    this->Sums.Resize(0, 0);
    this->SumsKey.clear();
  }
  DistributedStats stats;
  std::string problem;
  out.PassesTraced = settings.Passes - this->Sums.Passes;
  try
  {
    if (out.PassesTraced > 0)
    {
      traced.Passes = out.PassesTraced;
      AccumulateDistributed(dv, traced, this->Sums, parallel, &stats,
        [&progress](double f) { return progress ? progress(0.05 + 0.9 * f) : true; });
    }
  }
  catch (const Error& e)
  {
    problem = e.what();
  }
  // AccumulateDistributed's errors come on every rank alike (its collectives agree)
  if (!problem.empty())
  {
    this->Sums.Resize(0, 0);
    throw Error(problem);
  }
  traced.Passes = settings.Passes;
  this->SumsKey = sumsKey;

  // 3. What it cost, over all ranks.
  double sums[3] = { stats.RaysHandedOn, stats.BytesExchanged, 0.0 };
  parallel.Sum(sums, 2);
  double maxima[3] = { static_cast<double>(dv.HeldDims[0]) * dv.HeldDims[1] * dv.HeldDims[2],
    stats.SecondsTracing, stats.SecondsExchanging };
  parallel.Max(maxima, 3);
  const double heldMax = maxima[0];
  out.SecondsTracing = maxima[1];
  out.SecondsExchanging = maxima[2];
  out.DistributedRanks = ranks;
  out.HeldPointsMax = heldMax;
  out.RaysHandedOn = sums[0];
  out.BytesExchanged = sums[1];
  out.Rounds = stats.Rounds;
  out.GhostLayers = dv.Ghost;
  if (rank != 0)
    return;

  // 4. The image (rank 0).
  if (!stats.BackendUsed.empty())
  {
    this->PiecesBackend = stats.BackendUsed;
    this->PiecesDevice = stats.DeviceName;
  }
  stats.BackendUsed = this->PiecesBackend;
  stats.DeviceName = this->PiecesDevice;
  out.Result = Finalize(grid, traced, this->Sums);
  out.BackendUsed = stats.BackendUsed;
  out.DeviceName = stats.DeviceName;
  out.Result.BackendUsed = stats.BackendUsed;
  out.Result.DeviceName = stats.DeviceName;
  if (!stats.Warnings.empty())
    out.Result.Warnings = stats.Warnings + out.Result.Warnings;
  std::ostringstream note;
  note << "Traced in pieces on " << ranks << " ranks: the most any rank holds is " << heldMax
       << " of the volume's " << double(grid.NumberOfPoints()) << " points (its piece and "
       << dv.Ghost << " ghost layers); " << sums[0] << " rays handed between ranks, " << sums[1]
       << " bytes exchanged, " << stats.Rounds << " rounds.";
  if (dv.Octree)
    note << " Octree blocks up to 2^" << dv.LevelMax << " cells (tolerance " << dv.LevelTolerance
         << ").";
  out.Notes.push_back({ false, note.str() });
  if (!out.Result.Warnings.empty())
    out.Notes.push_back({ true, out.Result.Warnings });
  out.HasImage = true;
  out.Traced = traced;
  out.Choice = choice;
  out.AutoAsked = autoAsked;
  out.Warnings = out.Result.Warnings;
  out.Passes = this->Sums.Passes;
  for (double c : this->Sums.Count)
    out.LandedPhotons += c;
  out.OctreeUsed = dv.Octree && traced.UseOctree;
  out.OctreeTolerance = dv.LevelTolerance;
}

} // namespace schlieren
