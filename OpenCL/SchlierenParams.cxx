// SPDX-License-Identifier: BSD-3-Clause
// Parameters: the settings and the volume as the kernels see them (sch_params), the feature tolerance.
#include "SchlierenEngineInternal.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

namespace schlieren
{

// Whether each step asks for its next sample's lines (sch_prefetch_at; SCHLIEREN_PREFETCH 0 or 1
// overrides). Where it paid in this machine's measurements (2 cores, PoCL and the CPU path;
// docs/PERFORMANCE.md, "The prefetch"): oblique views (no direction cosine of the beam over 0.9) of
// a packed field over 128 MiB (about 200^3 points), and views along an axis of a field over 432 MiB
// (past 300^3) in bricks. 512^3 in bricks: moves in 10-45 % less time, oblique views at 1-voxel steps
// 1.1-2.8x; 256^3 oblique moves with Cubic 1.3-1.9x. Not elsewhere: a field within the caches'
// reach only pays the prefetch's instructions (64^3, 128^3: 30-38 % slower), and along an axis of
// a linear field the rays of a group read neighbouring lines that the hardware fetches itself
// (512^3, a 512^2 film: 24 % slower with it; 256^3: 20-25 %).
bool PrefetchPays(const sch_params& P)
{
  const int asked = GetRuntimeOptions().Prefetch;
  if (asked >= 0)
    return asked == 1;
  const double bytes = 16.0 * P.nx * double(P.ny) * P.nz;
  const bool axis = std::max({ std::fabs(P.dx), std::fabs(P.dy), std::fabs(P.dz) }) > 0.9f;
  const bool linear = P.fieldShift == 31;
  if (bytes <= 128.0 * (1 << 20))
    return false;
  return !axis || (!linear && bytes > 432.0 * (1 << 20));
}

sch_params MakeParams(const Volume& volume, const TraceSettings& s, const FilmGeometry& f)
{
  if (!(s.StepSize > 0) || !std::isfinite(s.StepSize) || s.StepSize > 1e3)
  {
    std::ostringstream msg;
    msg << "StepSize " << s.StepSize << " voxels is out of range: use a value in (0, 1000].";
    throw Error(msg.str());
  }
  CheckPrecision(volume, s);
  sch_params P;
  std::memset(&P, 0, sizeof(P));
  P.nx = volume.Dimensions[0];
  P.ny = volume.Dimensions[1];
  P.nz = volume.Dimensions[2];
  // the tracer works relative to the volume's centre: only the extent enters, never the origin
  double h[3];
  HalfExtent(volume, h);
  P.isx = static_cast<float>(1.0 / volume.Spacing[0]);
  P.isy = static_cast<float>(1.0 / volume.Spacing[1]);
  P.isz = static_cast<float>(1.0 / volume.Spacing[2]);
  P.hx = static_cast<float>(h[0]);
  P.hy = static_cast<float>(h[1]);
  P.hz = static_cast<float>(h[2]);
  P.dx = static_cast<float>(f.Direction[0]);
  P.dy = static_cast<float>(f.Direction[1]);
  P.dz = static_cast<float>(f.Direction[2]);
  P.rx = static_cast<float>(f.Right[0]);
  P.ry = static_cast<float>(f.Right[1]);
  P.rz = static_cast<float>(f.Right[2]);
  P.tx = static_cast<float>(f.Up[0]);
  P.ty = static_cast<float>(f.Up[1]);
  P.tz = static_cast<float>(f.Up[2]);
  P.sFront = static_cast<float>(f.FrontPlane);
  P.sFilm = static_cast<float>(f.FilmPlane);
  P.filmA0 = static_cast<float>(f.Corner[0]);
  P.filmB0 = static_cast<float>(f.Corner[1]);
  P.pixel = static_cast<float>(f.PixelSize);
  P.filmNx = f.Size[0];
  P.filmNy = f.Size[1];
  const double step = s.StepSize * MinSpacing(volume);
  P.step = static_cast<float>(step);
  const double diag = 2 * std::sqrt(double(P.hx) * P.hx + double(P.hy) * P.hy + double(P.hz) * P.hz);
  // near a body steps are cut to a cell: the default limit allows for a whole path of them
  const double shortest = volume.Solid ? std::min(step, MinSpacing(volume)) : step;
  double maxSteps = s.MaxSteps > 0 ? s.MaxSteps : 8.0 * diag / shortest + 16;
  P.maxSteps = static_cast<int>(std::min(maxSteps, 1e9));
  P.seed = s.Seed;
  P.pass = 0;
  P.indexScale = 1.0f; // SpectralPass sets a band's
  P.integrator = static_cast<int>(s.Method);
  P.jitter = s.Jitter ? (s.Pattern == JitterPattern::Lattice ? 2 : 1) : 0;
  if (s.RankCount < 1 || s.RankIndex < 0 || s.RankIndex >= s.RankCount)
    throw Error("RankIndex must be in [0, RankCount).");
  P.rayOffset = s.RankIndex;
  P.rayStride = s.RankCount;
  P.useLevels = (s.UseOctree && volume.Levels) ? 1 : 0;
  P.useSolid = volume.Solid ? 1 : 0;
  P.keepInvariant = s.KeepInvariant ? 1 : 0;
  P.estimate = s.EstimateError ? 1 : 0;
  P.featureTol = 0.0f; // see SetFeatureTolerance
  // steps no longer than the smallest spacing cannot jump over a cell: no need to check them
  P.cellStep = static_cast<float>(MinSpacing(volume));
  P.gxMax = std::nextafter(static_cast<float>(P.nx - 1), 0.0f);
  P.gyMax = std::nextafter(static_cast<float>(P.ny - 1), 0.0f);
  P.gzMax = std::nextafter(static_cast<float>(P.nz - 1), 0.0f);
  // the grid coordinate of the centre, (origin - centre) / spacing, exactly
  P.gx0 = static_cast<float>(0.5 * (P.nx - 1));
  P.gy0 = static_cast<float>(0.5 * (P.ny - 1));
  P.gz0 = static_cast<float>(0.5 * (P.nz - 1));
  if (4.0 * P.nx * P.ny > 2147483647.0)
    throw Error("A slice of the volume has more than 2^29 points: not supported.");
  // the field in bricks where it is packed so (Volume::FieldInBricks) or the options ask for a copy
  // in bricks (BrickedField, SCHLIEREN_FIELD_BRICKS=1): a ray in any direction then reads the
  // pages its neighbours read; else linear
  SetFieldLayout(P, volume.FieldInBricks || GetRuntimeOptions().Bricks == 1);
  if (volume.FieldInBricks && P.fieldShift != FieldBrickShift)
    throw Error("The volume's field is in bricks, which a grid of this size cannot be read in "
                "(a layer of bricks past 2^31 floats): pack it linear.");
  if (s.Recon == Reconstruction::Auto)
    throw Error("Reconstruction Auto must be resolved first (ResolveAuto).");
  if (s.Recon == Reconstruction::Cubic && !volume.Smooth)
    throw Error("Reconstruction Cubic needs the volume's smoothness (Volume::Smooth): pack the field "
                "with PackFieldHighOrder, or use Reconstruction Trilinear.");
  // with a body the levels byte carries its bits where Cubic keeps the smoothness: trilinear
  P.recon = s.Recon == Reconstruction::Cubic && !volume.Solid ? SCH_CUBIC : SCH_TRILINEAR;
  P.prefetch = PrefetchPays(P) ? 1 : 0;
  // from cells that are not smooth, steps of at most a cell: they cannot jump over a feature
  P.roughStep = P.recon == SCH_CUBIC ? P.cellStep : 0.0f;
  return P;
}

std::mutex KeptMutex;

namespace
{
// The index ranges of the last stamped volumes (finding one is a pass over the whole field),
// newest first, under KeptMutex. More than one: Auto's pilot on a certified copy traces the copy
// and the field in turn (issue 50), and with one range kept each trace found the other's range
// again: 120 of a 200 ms pilot at 512^3 and 3e-8 rad went into passes over the 2 GiB field.
struct KeptRange
{
  VolumeIdentity Of;
  float Lo = 0, Hi = 0;
};
constexpr std::size_t KeptRanges = 4;
std::vector<KeptRange> kept;
std::size_t scans = 0; // passes over a field to find its range (IndexRangeScans)

// the range is the field's alone: the tracer's view of a volume (TraceVolume) may carry other
// level bytes, yet the same range
VolumeIdentity FieldIdentity(const Volume& volume)
{
  VolumeIdentity id(volume);
  id.Levels = nullptr;
  id.Solid = nullptr;
  return id;
}
}

void KeepIndexRange(const Volume& volume, float lo, float hi)
{
  if (volume.Stamp == 0)
    return;
  const VolumeIdentity id = FieldIdentity(volume);
  std::lock_guard<std::mutex> lock(KeptMutex);
  auto it = std::find_if(kept.begin(), kept.end(), [&id](const KeptRange& k) { return k.Of == id; });
  if (it != kept.end())
    kept.erase(it);
  else if (kept.size() == KeptRanges)
    kept.pop_back();
  kept.insert(kept.begin(), KeptRange{ id, lo, hi });
}

void SetFeatureTolerance(sch_params& P, const Volume& volume)
{
  float lo = volume.Field[0], hi = volume.Field[0];
  bool known = false;
  {
    const VolumeIdentity id = FieldIdentity(volume);
    std::lock_guard<std::mutex> lock(KeptMutex);
    for (const KeptRange& k : kept)
      if (k.Of == id)
      {
        lo = k.Lo;
        hi = k.Hi;
        known = true;
        break;
      }
  }
  // (in bricks, the padding repeats points of the grid: the same range)
  const std::size_t n = FieldLayout(volume.Dimensions, volume.FieldInBricks).Floats / 4;
  for (std::size_t i = 0; !known && i < n; ++i)
  {
    lo = std::min(lo, volume.Field[4 * i]);
    hi = std::max(hi, volume.Field[4 * i]);
  }
  if (!known)
  {
    KeepIndexRange(volume, lo, hi);
    std::lock_guard<std::mutex> lock(KeptMutex);
    ++scans;
  }
  P.featureTol = FeatureTolerance(lo, hi, volume.LevelTolerance);
}

std::size_t IndexRangeScans()
{
  std::lock_guard<std::mutex> lock(KeptMutex);
  return scans;
}

float FeatureTolerance(float lo, float hi, double levelTolerance)
{
  const float tol = static_cast<float>(std::max(levelTolerance, 0.01 * (double(hi) - lo)));
  return tol > 0 ? tol : 1e-30f;
}

std::size_t RaysForRank(const sch_params& P)
{
  const std::size_t pixels = static_cast<std::size_t>(P.filmNx) * P.filmNy;
  if (pixels <= static_cast<std::size_t>(P.rayOffset))
    return 0;
  return (pixels - P.rayOffset + P.rayStride - 1) / P.rayStride;
}

} // namespace schlieren
