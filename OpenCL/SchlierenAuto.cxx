// SPDX-License-Identifier: BSD-3-Clause
// Integrator and Reconstruction Auto: the pilot rays, the candidates, the choice (ResolveAuto).
#include "SchlierenEngineInternal.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace schlieren
{

namespace
{
std::string ToText(double v)
{
  std::ostringstream o;
  o.precision(3);
  o << v;
  return o.str();
}

// What a tricubic sample costs against a trilinear one when Auto weighs the two reconstructions:
// it reads 64 points instead of 8, mostly from the same cache lines (docs/PERFORMANCE.md has the
// measured ratio).
constexpr double CubicSampleCost = 3.0;

// The rays of a pilot that a comparison can use: neither lost.
bool Comparable(const RayRecord& a, const RayRecord& b)
{
  const std::uint32_t bad = RayMaxSteps | RayTurned | RayNonFinite | RayOffFilm;
  return !(a.Flags & bad) && !(b.Flags & bad);
}
} // namespace

TraceSettings ResolveAuto(const Volume& volume, const TraceSettings& in, AutoChoice* choice)
{
  if (in.Method == Integrator::Auto || in.Recon == Reconstruction::Auto)
    CheckVolume(volume);
  AutoVolume grid;
  grid.Grid = volume;
  grid.HasLevels = volume.Levels != nullptr;
  grid.HasSmooth = volume.Smooth != nullptr;
  grid.HasSolid = volume.Solid != nullptr;
  return ResolveAutoWith(grid, in, choice,
    [&volume](const TraceSettings& t, const std::vector<float>& ab) { return TraceRays(volume, t, ab); });
}

TraceSettings ResolveAutoWith(const AutoVolume& grid, const TraceSettings& in, AutoChoice* choice,
  const PilotTracer& traceRays)
{
  const Volume& volume = grid.Grid;
  AutoChoice c;
  c.Method = in.Method;
  c.StepSize = in.StepSize;
  c.Recon = in.Recon;
  c.Met = true;
  const bool autoRecon = in.Recon == Reconstruction::Auto;
  if (in.Method != Integrator::Auto && !autoRecon)
  {
    c.Report = std::string(IntegratorName(in.Method)) + " at " + std::to_string(in.StepSize) + " voxel";
    if (in.Recon != Reconstruction::Trilinear)
      c.Report += std::string(", reconstruction ") + ReconstructionName(in.Recon);
    if (choice)
      *choice = c;
    return in;
  }
  const FilmGeometry film = MakeFilm(volume, in);
  const std::vector<float> ab = PilotRays(volume, in);
  TraceSettings ref = in;
  ref.Method = Integrator::RK4;
  ref.StepSize = 0.125;
  ref.UseOctree = false;
  ref.EstimateError = false;
  const auto t0 = std::chrono::steady_clock::now();
  // the reference's step (and the candidates') is Auto's, not the user's StepSize: say so when
  // the volume cannot be traced at it
  try
  {
    CheckPrecision(volume, ref);
  }
  catch (const Error& e)
  {
    throw Error(std::string("Integrator Auto measures its candidates against RK4 at 0.125 voxel, "
                            "which this volume does not allow: ") + e.what() +
      " Or choose a fixed Integrator and StepSize.");
  }
  // the reference of each reconstruction that may be chosen. Reconstruction Auto: the difference
  // between the two references is the second-order reconstruction's error (the fourth-order one's
  // is far smaller where the data is smooth, and both are the same trilinear code elsewhere), an
  // error that a reference on the same grid with the same reconstruction cannot see
  // (with a body the levels byte holds its bits instead of the smoothness: trilinear only)
  bool tryTri = in.Recon == Reconstruction::Trilinear || (autoRecon) || grid.HasSolid;
  bool tryCubic = !grid.HasSolid && (in.Recon == Reconstruction::Cubic || (autoRecon && grid.HasSmooth));
  std::vector<RayRecord> refTri, refCubic;
  if (tryTri)
  {
    ref.Recon = Reconstruction::Trilinear;
    refTri = traceRays(ref, ab);
  }
  if (tryCubic)
  {
    ref.Recon = Reconstruction::Cubic;
    refCubic = traceRays(ref, ab);
  }
  const std::vector<RayRecord>& R0 = tryCubic ? refCubic : refTri;
  double emax = 0;
  for (const RayRecord& r : R0)
    if (!(r.Flags & RayBlocked))
      emax = std::max(emax, double(sch_hypot_d(r.DeflX, r.DeflY)));
  const double tol = in.Tolerance > 0 ? in.Tolerance : 0.01 * emax;
  double triError = 0;
  if (tryTri && tryCubic)
  {
    for (std::size_t k = 0; k < refTri.size(); ++k)
      if (Comparable(refTri[k], refCubic[k]))
        triError = std::max(triError,
          double(sch_hypot_d(refTri[k].DeflX - refCubic[k].DeflX, refTri[k].DeflY - refCubic[k].DeflY)));
    c.TrilinearError = triError;
    // trilinear only where its own error leaves at least half the tolerance to the integrator
    if (triError > 0.5 * tol)
      tryTri = false;
  }
  if (in.Method != Integrator::Auto)
  {
    // Reconstruction Auto with a fixed integrator: trilinear where it is accurate enough
    c.Recon = tryTri ? Reconstruction::Trilinear : Reconstruction::Cubic;
    c.Tolerance = tol;
    std::ostringstream rep;
    rep << IntegratorName(in.Method) << " at " << in.StepSize << " voxel, reconstruction "
        << ReconstructionName(c.Recon) << " (the trilinear's estimated error " << triError
        << " rad against the tolerance " << tol << " rad)";
    c.Report = rep.str();
    if (choice)
      *choice = c;
    TraceSettings out = in;
    out.Recon = c.Recon;
    return out;
  }
  struct Candidate
  {
    Integrator M;
    double Step;
    Reconstruction Rc;
  };
  std::vector<Candidate> candidates;
  for (Reconstruction rc : { Reconstruction::Trilinear, Reconstruction::Cubic })
  {
    if ((rc == Reconstruction::Trilinear && !tryTri) || (rc == Reconstruction::Cubic && !tryCubic))
      continue;
    // tricubic: steps sized by the field, up to 64 voxels where the data is smooth (a voxel
    // elsewhere, see sch_walk_step)
    std::vector<double> longSteps;
    if (rc == Reconstruction::Cubic)
      longSteps = { 64.0, 32.0, 16.0 };
    for (double st : longSteps)
      candidates.push_back({ Integrator::Straight, st, rc });
    for (double st : { 8.0, 4.0, 2.0, 1.0 })
      candidates.push_back({ Integrator::Straight, st, rc });
    for (Integrator m : { Integrator::Euler, Integrator::Midpoint, Integrator::RK4 })
    {
      for (double st : longSteps)
        candidates.push_back({ m, st, rc });
      for (double st : { 8.0, 4.0, 2.0, 1.0, 0.5, 0.25 })
        candidates.push_back({ m, st, rc });
    }
  }
  // The floor: the smallest error the pilot can tell apart. The reference traced again at twice
  // its step (RK4 at 1/4 voxel, also a candidate) differs from it by what the reference itself is
  // uncertain by; a candidate within 1.5 times that is as accurate as the pilot can tell, and a
  // finer step only costs more. Where the tolerance is below the floor, the floor is the
  // tolerance applied: the cheapest candidate within it is taken, and the report says that the
  // tolerance asked is below what this volume allows, and why.
  const bool reuseFloorTrace = !(in.UseOctree && grid.HasLevels); // candidates skip, the floor not
  std::map<int, std::vector<RayRecord>> floorTrace;
  std::map<int, double> floorOf, floorDiff;
  for (Reconstruction rc : { Reconstruction::Trilinear, Reconstruction::Cubic })
  {
    if ((rc == Reconstruction::Trilinear && !tryTri) || (rc == Reconstruction::Cubic && !tryCubic))
      continue;
    TraceSettings t = ref;
    t.StepSize = 0.25;
    t.Recon = rc;
    std::vector<RayRecord>& F = floorTrace[static_cast<int>(rc)];
    F = traceRays(t, ab);
    const std::vector<RayRecord>& R = rc == Reconstruction::Cubic ? refCubic : refTri;
    double d = 0;
    for (std::size_t k = 0; k < F.size(); ++k)
      if (Comparable(F[k], R[k]) && !((F[k].Flags | R[k].Flags) & RayBlocked))
        d = std::max(d, double(sch_hypot_d(F[k].DeflX - R[k].DeflX, F[k].DeflY - R[k].DeflY)));
    floorDiff[static_cast<int>(rc)] = d;
    floorOf[static_cast<int>(rc)] = 1.5 * d;
  }
  bool found = false;
  double bestCost = 1e300, bestErr = 1e300;
  AutoChoice fallback;
  // the smallest error of an RK4 candidate at a step of a voxel or more, per reconstruction: if
  // it is about the floor, the floor does not fall with the step
  std::map<int, double> coarseRK4;
  // each integrator's steps come longest first: once one meets the tolerance, the shorter ones of
  // that integrator and reconstruction only cost more
  std::map<int, bool> met;
  for (const Candidate& cand : candidates)
  {
    const int group = static_cast<int>(cand.Rc) * 8 + static_cast<int>(cand.M);
    if (met[group])
      continue;
    TraceSettings t = in;
    t.Method = cand.M;
    t.StepSize = cand.Step;
    t.Recon = cand.Rc;
    t.EstimateError = false;
    const bool isFloorTrace = reuseFloorTrace && cand.M == Integrator::RK4 && cand.Step == 0.25;
    const std::vector<RayRecord> T =
      isFloorTrace ? floorTrace[static_cast<int>(cand.Rc)] : traceRays(t, ab);
    const std::vector<RayRecord>& R = cand.Rc == Reconstruction::Cubic ? refCubic : refTri;
    // a trilinear candidate answers for the trilinear's own error too (Reconstruction Auto)
    const double base = cand.Rc == Reconstruction::Trilinear && tryCubic ? triError : 0.0;
    const double allowed = std::max(tol, floorOf[static_cast<int>(cand.Rc)]);
    double err = 0, land = 0, samples = 0;
    bool lost = false;
    // rays the candidate loses where the reference does not disqualify it; steps over structure
    // do not by themselves: their effect is in the measured error
    const std::uint32_t bad = RayMaxSteps | RayTurned | RayNonFinite | RayOffFilm;
    for (std::size_t k = 0; k < T.size(); ++k)
    {
      samples += T[k].Samples;
      if (R[k].Flags & bad)
        continue; // the reference itself cannot be trusted here: nothing to compare
      // a body stopped it (in either trace: a grazing ray may stop at a body's corner with one
      // step and pass it with another): dark, no deflection to compare
      if ((R[k].Flags | T[k].Flags) & RayBlocked)
        continue;
      if (T[k].Flags & bad)
        lost = true; // it fails (or steps over structure) where the reference does not
      err = std::max(err, double(sch_hypot_d(T[k].DeflX - R[k].DeflX, T[k].DeflY - R[k].DeflY)));
      land = std::max(land, double(sch_hypot_d(T[k].LandA - R[k].LandA, T[k].LandB - R[k].LandB)));
    }
    land /= film.PixelSize;
    if (lost)
      continue;
    if (cand.M == Integrator::RK4 && cand.Step >= 1.0)
    {
      auto it = coarseRK4.find(static_cast<int>(cand.Rc));
      if (it == coarseRK4.end() || err < it->second)
        coarseRK4[static_cast<int>(cand.Rc)] = err;
    }
    const double cost = samples * (cand.Rc == Reconstruction::Cubic ? CubicSampleCost : 1.0);
    if (err + base <= allowed && land <= 0.5)
      met[group] = true;
    if (err + base <= allowed && land <= 0.5 && cost < bestCost)
    {
      found = true;
      bestCost = cost;
      c.Method = cand.M;
      c.StepSize = cand.Step;
      c.Recon = cand.Rc;
      c.ExpectedError = err + base;
      c.ExpectedLandingError = land;
      c.SamplesPerRay = samples / T.size();
    }
    if (!found && err + base < bestErr)
    {
      bestErr = err + base;
      fallback.Method = cand.M;
      fallback.StepSize = cand.Step;
      fallback.Recon = cand.Rc;
      fallback.ExpectedError = err + base;
      fallback.ExpectedLandingError = land;
      fallback.SamplesPerRay = samples / T.size();
    }
  }
  if (!found)
  {
    const double keep = c.TrilinearError;
    c = fallback;
    c.TrilinearError = keep;
    c.Met = false;
  }
  c.Floor = floorOf[static_cast<int>(c.Recon)];
  c.AtFloor = found && tol < c.Floor;
  if (c.AtFloor)
    c.Met = false;
  std::string floorWhy;
  if (c.AtFloor)
  {
    const double d = floorDiff[static_cast<int>(c.Recon)];
    auto it = coarseRK4.find(static_cast<int>(c.Recon));
    // RK4 at 4 times the step would be 256 times worse if the difference were its truncation
    // error: an error that does not fall with the step is rounding
    floorWhy = "the reference (RK4 at 1/8 voxel) and RK4 at 1/4 voxel differ by " + ToText(d) + " rad";
    if (it != coarseRK4.end() && it->second <= 2 * d)
      floorWhy += ", RK4 at a voxel or more by " + ToText(it->second) +
        " rad: an error that does not fall with the step, float rounding (each sample's position "
        "and the sums along the ray are single precision; it grows as the steps get shorter)";
    else
      floorWhy += ": the reference itself is still converging (structure finer than its step, "
                  "or data the grid does not resolve for this tolerance)";
  }
  c.Tolerance = tol;
  // the octree is a cost too: a skipping step costs more than a plain one. Kept
  // when it saves at least 10 % of the chosen setting's samples on the pilot; without it the
  // error can only stay or shrink (fixed steps through the blocks it would have skipped).
  c.UseOctree = in.UseOctree && grid.HasLevels;
  if (c.UseOctree)
  {
    TraceSettings t = in;
    t.Method = c.Method;
    t.StepSize = c.StepSize;
    t.Recon = c.Recon;
    t.EstimateError = false;
    t.UseOctree = false;
    double plain = 0;
    for (const RayRecord& r : traceRays(t, ab))
      plain += r.Samples;
    c.OctreeSaving = plain > 0 ? 1.0 - c.SamplesPerRay * (ab.size() / 2) / plain : 0.0;
    c.UseOctree = c.OctreeSaving >= 0.1;
  }
  const double ms = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() * 1e3;
  std::ostringstream rep;
  rep << "Auto chose " << IntegratorName(c.Method) << " at " << c.StepSize << " voxel: expected "
      << "deflection error " << c.ExpectedError << " rad (tolerance " << tol << " rad), landing error "
      << c.ExpectedLandingError << " pixel, " << c.SamplesPerRay << " samples per ray (pilot of "
      << ab.size() / 2 << " rays, " << static_cast<int>(ms) << " ms)";
  if (c.Recon != Reconstruction::Trilinear || autoRecon)
    rep << "; reconstruction " << ReconstructionName(c.Recon);
  if (autoRecon && tryCubic)
    rep << " (the trilinear's estimated error " << c.TrilinearError << " rad)";
  if (c.AtFloor)
    rep << "; no candidate met the tolerance: it is below what this volume allows, a floor of "
        << c.Floor << " rad (" << floorWhy
        << "); using the cheapest candidate within the floor (a Tolerance of at least " << c.Floor
        << " rad asks no more than the pilot can measure)";
  else if (!c.Met)
    rep << "; no candidate met the tolerance: using the most accurate one";
  if (in.UseOctree && grid.HasLevels)
    rep << "; octree " << (c.UseOctree ? "on" : "off") << ": it skips "
        << static_cast<int>(std::lround(100 * c.OctreeSaving)) << " % of the samples"
        << (c.UseOctree ? "" : " (less than 10 %)");
  c.Report = rep.str();
  if (choice)
    *choice = c;
  TraceSettings out = in;
  out.Method = c.Method;
  out.StepSize = c.StepSize;
  out.Recon = c.Recon;
  out.AutoMeasuredError = c.Met ? c.ExpectedError : -1.0;
  out.UseOctree = in.UseOctree && c.UseOctree;
  return out;
}

std::vector<float> PilotRays(const Volume& volume, const TraceSettings& s)
{
  const FilmGeometry film = MakeFilm(volume, s);
  std::vector<float> ab;
  const int np = 16;
  const double w = film.Size[0] * film.PixelSize, h = film.Size[1] * film.PixelSize;
  for (int j = 0; j < np; ++j)
    for (int i = 0; i < np; ++i)
    {
      ab.push_back(static_cast<float>(film.Corner[0] + (i + 0.5) * w / np));
      ab.push_back(static_cast<float>(film.Corner[1] + (j + 0.5) * h / np));
    }
  return ab;
}

} // namespace schlieren
