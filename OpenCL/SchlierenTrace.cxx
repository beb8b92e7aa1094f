// SPDX-License-Identifier: BSD-3-Clause
// Tracing: Accumulate, Trace and TraceRays, and the choice of backend (with the CPU fallback).
#include "SchlierenEngineInternal.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace schlieren
{

namespace
{
// The volume as the kernels read it in P's layout (MakeParams): its field in bricks
// (BrickedField) or as it is, and what a device that uses host memory in place must keep alive,
// the bricks and the cell bytes. The bricks are a second copy of the field: where there is no room
// for it (BrickedField), P goes back to the linear layout (the same images, slower oblique views).
struct FieldForKernels
{
  std::shared_ptr<const AlignedFloats> Bricks;
  Volume Bricked;
  std::shared_ptr<const void> Owner;
  FieldForKernels(const Volume& tv, sch_params& P, const std::shared_ptr<const void>& bytesOwner)
    : Bricked(tv)
    , Owner(bytesOwner)
  {
    if (P.fieldShift != FieldBrickShift || tv.FieldInBricks)
      return;
    try
    {
      Bricks = BrickedField(tv);
    }
    catch (const std::bad_alloc&)
    {
      SetFieldLayout(P, false);
      return;
    }
    Bricked.Field = Bricks->data();
    Bricked.FieldInBricks = true;
    Owner = std::make_shared<std::pair<std::shared_ptr<const void>, std::shared_ptr<const void>>>(
      bytesOwner, Bricks);
  }
};
} // namespace

// (volume.Field in P's layout: the bricks of BrickedField, which bytesOwner then holds too)
std::shared_ptr<OpenCLTracer> OpenBackend(const Volume& volume, const unsigned char* bytes,
  const std::shared_ptr<const void>& bytesOwner, const TraceSettings& s,
  const sch_params& P, std::size_t chunk, bool points, std::string& used, std::string& device,
  std::string& warnings)
{
  if (s.Device == Backend::CPU)
  {
    used = "CPU";
    device = "CPU (" + std::to_string(CpuThreads(s.Threads)) + " threads)";
    return nullptr;
  }
  try
  {
    auto t = AcquireTracer(
      volume, bytes, bytesOwner, chunk, s.RaysPerWorkItem, GetRuntimeOptions(), s.DeviceName,
      P.fieldShift == FieldBrickShift);
    PrepareKernel(*t, P, points); // built here, so that a build failure falls back like a missing device
    used = "OpenCL";
    device = TracerDeviceName(*t);
    return t;
  }
  catch (const Error& e)
  {
    if (s.Device == Backend::OpenCL)
      throw;
    used = "CPU";
    device = "CPU (" + std::to_string(CpuThreads(s.Threads)) + " threads)";
    warnings += std::string("OpenCL is not usable, tracing on the CPU instead: ") + e.what() + "\n";
    return nullptr;
  }
}

namespace
{
// The copy a trace with FieldStride traces (ResolveAuto's choice; the caller holds it for the
// trace) and its settings `t`: the step in the copy's voxels, no octree (the copy has no levels).
std::shared_ptr<const CoarseCopy> CoarseOf(const Volume& volume, const TraceSettings& s, TraceSettings& t)
{
  std::shared_ptr<const CoarseCopy> held = CoarseCopyOf(volume, s.FieldStride);
  if (!held)
    throw Error("FieldStride " + std::to_string(s.FieldStride) +
      " asks for a copy of the field that this volume does not have (a stamped volume of at least " +
      std::to_string(CoarseMinPoints) + " points a side at that stride); trace with FieldStride 1.");
  t = s;
  t.FieldStride = 1;
  t.StepSize = s.StepSize * MinSpacing(volume) / MinSpacing(held->V);
  t.UseOctree = false;
  return held;
}
} // namespace

void Accumulate(const Volume& volume, const TraceSettings& s, FilmSums& sums,
  std::string* backendUsed, std::string* deviceName, std::string* warnings,
  const ProgressFunction& progress)
{
  CheckVolume(volume);
  CheckSettings(s);
  if (s.Method == Integrator::Auto)
    throw Error("Accumulate: resolve Integrator Auto first (ResolveAuto).");
  if (s.FieldStride != 1)
  {
    TraceSettings t;
    const std::shared_ptr<const CoarseCopy> copy = CoarseOf(volume, s, t);
    Accumulate(copy->V, t, sums, backendUsed, deviceName, warnings, progress);
    return;
  }
  if (s.RussianRoulette && !(s.CutoffScale > 0) &&
    (s.Mode == Cutoff::KnifeEdge || s.Mode == Cutoff::Circular || s.Mode == Cutoff::ComplementCircular))
    throw Error("Photon killing (RussianRoulette) needs a fixed CutoffScale: the automatic scale is "
                "known only after the trace.");
  const FilmGeometry film = MakeFilm(volume, s);
  sch_params P = MakeParams(volume, s, film);
  std::shared_ptr<std::vector<unsigned char>> levelBytes;
  const Volume tv = TraceVolume(volume, levelBytes);
  if (sums.Size[0] != film.Size[0] || sums.Size[1] != film.Size[1] || sums.Count.empty())
  {
    CheckFilmMemory(film.Size);
    sums.Resize(film.Size[0], film.Size[1]);
  }

  const std::size_t rays = RaysForRank(P);
  // chunks of about 8 M samples (a fraction of a second): progress and abort are checked between
  // chunks, so an abort stops the trace within one chunk; long rays make small chunks
  const double samplesPerRay = std::max(1.0, 2.0 * std::sqrt(double(P.hx) * P.hx + double(P.hy) * P.hy +
                                                 double(P.hz) * P.hz) / P.step *
      (s.Method == Integrator::RK4 ? 4 : (s.Method == Integrator::Midpoint ? 2 : 1)) *
      (s.EstimateError ? 1.5 : 1.0));
  std::size_t chunk = 64;
  while (chunk < (1u << 16) && (2 * chunk) * samplesPerRay <= 8e6)
    chunk *= 2;
  // whole bands of film rows where this rank traces every pixel: the lock-step kernel then
  // traces them in tiles (sch_tile_order)
  const std::size_t band = std::size_t(SCH_TILE_ROWS) * std::size_t(P.filmNx);
  if (P.rayStride == 1 && chunk % band != 0)
    chunk = std::max(band, chunk / band * band);
  chunk = std::min<std::size_t>(std::max<std::size_t>(rays, 1), chunk);
  std::string used, device, warn;
  // with a body the kernels read its solid and near bits in the levels byte (no Cubic then)
  const auto solidBytes = CellBytesOf(volume, StepReach(P));
  const unsigned char* bytes = solidBytes ? solidBytes->data() : tv.Levels;
  const FieldForKernels kf(tv, P, solidBytes ? std::shared_ptr<const void>(solidBytes) : levelBytes);
  std::shared_ptr<OpenCLTracer> cl =
    OpenBackend(kf.Bricked, bytes, kf.Owner, s, P, chunk, false, used, device, warn);
  SetFeatureTolerance(P, tv);
  if (volume.Solid && s.Recon == Reconstruction::Cubic && sums.Passes == 0)
    warn += "Reconstruction Cubic is not available with a solid body (the byte per point that "
            "carries the body holds the smoothness it needs): traced trilinear.\n";
  std::vector<float> records(chunk * SCH_RECORD);
  const unsigned threads = CpuThreads(s.Threads);
  Splatter splat(P, s, sums);
  const double total = double(s.Passes) * std::max<std::size_t>(rays, 1);
  double done = 0;
  for (int pass = 0; pass < s.Passes; ++pass)
  {
    P.pass = sums.Passes + pass;
    // Camera Lens: the kernels trace this pass's tilted beam (Pk), a band this pass's wavelength;
    // the splatter bins on P's film
    sch_params Pk = P;
    splat.BeginPass(Pk, P.pass);
    for (std::size_t first = 0; first < rays; first += chunk)
    {
      const std::size_t count = std::min(chunk, rays - first);
      if (cl)
        TraceOpenCL(*cl, Pk, first, count, records.data());
      else
        TraceChunkCPU(kf.Bricked.Field, bytes, Pk, first, count, records.data(), threads);
      splat.Add(records.data(), first, count);
      done += count;
      if (progress && !progress(done / total))
        throw Error("aborted");
    }
  }
  sums.Passes += s.Passes;
  if (backendUsed)
    *backendUsed = used;
  if (deviceName)
    *deviceName = device;
  if (warnings)
    *warnings += warn;
}

std::uint64_t NewVolumeStamp()
{
  static std::atomic<std::uint64_t> next(1);
  return next.fetch_add(1);
}

TraceResult Trace(const Volume& volume, const TraceSettings& requested, const ProgressFunction& progress)
{
  FilmSums sums;
  std::string used, device, warn;
  AutoChoice choice;
  const TraceSettings s = ResolveAuto(volume, requested, &choice);
  if (!choice.Met)
    warn += choice.Report + "\n";
  const auto t0 = std::chrono::steady_clock::now();
  Accumulate(volume, s, sums, &used, &device, &warn, progress);
  const auto t1 = std::chrono::steady_clock::now();
  TraceResult r = Finalize(volume, s, sums);
  r.Choice = choice;
  r.BackendUsed = used;
  r.DeviceName = device;
  r.Warnings = warn + r.Warnings;
  r.Seconds = std::chrono::duration<double>(t1 - t0).count();
  return r;
}

std::vector<RayRecord> TraceRays(const Volume& volume, const TraceSettings& s,
  const std::vector<float>& ab, std::string* backendUsed)
{
  CheckVolume(volume);
  if (s.Method == Integrator::Auto)
    throw Error("TraceRays: resolve Integrator Auto first (ResolveAuto).");
  if (s.FieldStride != 1)
  {
    CheckSettings(s);
    TraceSettings t;
    const std::shared_ptr<const CoarseCopy> copy = CoarseOf(volume, s, t);
    return TraceRays(copy->V, t, ab, backendUsed);
  }
  const FilmGeometry film = MakeFilm(volume, s);
  sch_params P = MakeParams(volume, s, film);
  const std::size_t count = ab.size() / 2;
  std::vector<RayRecord> out(count);
  std::string used, device, warn;
  std::shared_ptr<std::vector<unsigned char>> levelBytes;
  const Volume tv = TraceVolume(volume, levelBytes);
  const auto solidBytes = CellBytesOf(volume, StepReach(P));
  const unsigned char* bytes = solidBytes ? solidBytes->data() : tv.Levels;
  const FieldForKernels kf(tv, P, solidBytes ? std::shared_ptr<const void>(solidBytes) : levelBytes);
  std::shared_ptr<OpenCLTracer> cl = OpenBackend(
    kf.Bricked, bytes, kf.Owner, s, P, std::max<std::size_t>(count, 1), true, used, device, warn);
  SetFeatureTolerance(P, tv);
  float* rec = reinterpret_cast<float*>(out.data());
  if (cl)
    TracePointsOpenCL(*cl, P, ab.data(), count, rec);
  else
  {
    // on the CPU backend's threads, in blocks of 8 rays taken in turn (Auto's pilot traces here;
    // packets of rays as TraceChunkCPU's gained nothing there), each thread with its own copy of
    // the parameters (as TraceChunkCPU: not beside what the calling thread writes as it steps)
    constexpr std::size_t block = 8;
    std::atomic<std::size_t> next{ 0 };
    const unsigned threads = static_cast<unsigned>(
      std::min<std::size_t>(CpuThreads(s.Threads), (count + block - 1) / block));
    RunOnThreads(threads, [&](unsigned) {
      const sch_params Pw = P;
      for (std::size_t b; (b = next.fetch_add(block)) < count;)
        for (std::size_t k = b; k < std::min(count, b + block); ++k)
          sch_trace(kf.Bricked.Field, bytes, &Pw, ab[2 * k], ab[2 * k + 1], rec + k * SCH_RECORD);
    });
  }
  // the flags travel as floats in the record; turn them into integers
  for (RayRecord& r : out)
  {
    float f;
    std::memcpy(&f, &r.Flags, sizeof(f));
    r.Flags = static_cast<std::uint32_t>(f);
  }
  if (backendUsed)
    *backendUsed = used;
  return out;
}

} // namespace schlieren
