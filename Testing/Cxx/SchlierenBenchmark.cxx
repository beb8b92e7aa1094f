// SPDX-License-Identifier: BSD-3-Clause
// Benchmark (not a test): photons/s, samples/s and ms per pass of each backend side by side, with
// the error of the traced deflection against a known answer, so that no speed is quoted without
// the accuracy it was bought at. Three cases:
//   gaussian  the 256^3 Gaussian sphere; error against the closed form
//   plume     a 480 x 720 x 100 helium jet (combustion-like: a sharp, strongly refracting
//             interface); error against RK4 at 1/8 voxel on the same grid
//   bluntfin  the NASA blunt fin resampled to 256^3 (--raw, written by
//             Testing/Benchmarks/bluntfin_volume.py); error against RK4 at 1/8 voxel
// Rows per case and backend: fixed Euler steps, the same with the octree, and Auto (tolerance 1 %
// of the largest deflection) with the octree; the CPU path once more on one thread, so that each
// run shows how its second core scaled.
//   grids     the weak Gaussian (A = 2e-4, s = 0.25 on [-1, 1]^3) on each grid of --grids (64^3 to
//             512^3), packed for both reconstructions: Integrator and Reconstruction Auto at a fixed
//             tolerance (--tolerance, of the peak deflection), beside the present scheme
//             (Reconstruction Trilinear, Integrator Auto, the same tolerance); rays/s with the RMS
//             and largest deflection error against the closed form over the film's pixel centres
//             within |x|, |y| < 2.2 s
//   autostep  issue 50's table: the same Gaussian on each grid of --grids, Auto (Integrator and
//             Reconstruction) at its default tolerance and at 3e-8 rad beside Straight at a step of
//             the feature's width and the cheapest swept setting that meets Auto's default
//             tolerance: samples/ray, RMS and largest error against the closed form, rays/s, the
//             pilot's ms; then the scaling table (each setting's rays/s over its 64^3 rate)
//   moves     issue 50's first image after a camera move: the same Gaussian on each grid of --grids
//             in a TraceSession (what SchlierenImage runs), Auto at its default tolerance and Auto +
//             Cubic at 3e-8 rad: the first update (packing, pilot, one pass of the film), camera
//             moves on axis and oblique (half film, one pass, as the GUI's follower traces) and the
//             camera at rest (the pilot again, the full film): wall ms of each update split into
//             the pilot, the trace and the rest (packing, set-up, the image)
//   cubicrate issue 50: Auto at --tolerance (rad here) on the same Gaussian on each grid of --grids, its
//             choice and the same step on the other reconstruction, the field linear and in bricks,
//             alternated --rounds times: median rays/s, samples/s, the tricubic sample's time over
//             the trilinear's, the pilot's ms and its reference check's
//   oblique   the same Gaussian on each grid of --grids seen along -z and along (1, 0.7, -0.4), Euler
//             at --step voxels, Trilinear and Cubic, the field linear and in bricks, alternated
//             --rounds times: median samples/s and rays/s, oblique over axis time per sample, errors
//             against the closed form
//   sources   the bench's sources (Point, Slit, Disc, Gaussian) on the Gaussian sphere: rays/s, the
//             passes for an RMS of 1 %, a camera move
//   raycost   the Gaussian sphere (--size) traced as a camera move traces it at steps of 0.3 to 30
//             voxels: what a ray costs besides its samples (issue 24's per-ray overhead)
//
//   SchlierenBenchmark [--cases gaussian,plume,bluntfin] [--size N] [--film N] [--passes N]
//     [--step voxels] [--backends OpenCL,CPU] [--rays-per-item N] [--raw bluntfin_256 (no suffix)]
//     [--grids 64,128,256,512] [--tolerance 1e-3] [--rounds 5 --steps 0.3,1,3,10,30 (raycost)]
#include "SchlierenEngine.h"
#include "SchlierenLimits.h"
#include "SchlierenOptions.h"
#include "SchlierenOracles.h"
#include "SchlierenScenes.h"
#include "SchlierenSession.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace schlieren;

namespace
{

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string CpuName()
{
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0)
      return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

// One benchmark case: a volume, its octree, the probe rays and their known deflections.
struct Case
{
  std::string Name, Reference;
  Volume V;
  std::vector<float> N1;
  AlignedFloats Field; // page-aligned, as the filters' session keeps it: a CPU device traces it in place
  std::vector<unsigned char> Levels;
  double OctreeTolerance = 0, Skippable = 0, LevelMs = 0, PackMs = 0;
  std::vector<float> Probe;          // film coordinates (a, b) of the probe rays
  std::vector<double> RefX, RefY;    // their known deflections
  double RefMax = 0;                 // the largest known deflection
};

void SetUp(Case& c)
{
  const auto t0 = Clock::now();
  c.Field.resize(4 * c.N1.size());
  PackField(c.V.Dimensions, c.V.Spacing, c.N1.data(), c.Field.data());
  c.PackMs = Since(t0) * 1e3;
  c.V.Field = c.Field.data();
  // the same contents from trace to trace: the OpenCL device keeps its copy (as in a view that
  // traces again after each camera move); the first-trace column pays the upload
  c.V.Stamp = NewVolumeStamp();
  const auto mm = std::minmax_element(c.N1.begin(), c.N1.end());
  c.OctreeTolerance = 1e-4 * (*mm.second - *mm.first);
  c.Levels.resize(c.N1.size());
  const auto t1 = Clock::now();
  c.Skippable = ComputeOctreeLevels(c.V.Dimensions, c.N1.data(), c.OctreeTolerance, c.Levels.data());
  c.LevelMs = Since(t1) * 1e3;
  // 25 x 25 probe rays over the middle 60 % of the film (the volume's projection along -z)
  double b[6];
  c.V.GetBounds(b);
  const double hx = 0.5 * (b[1] - b[0]), hy = 0.5 * (b[3] - b[2]);
  for (int j = -12; j <= 12; ++j)
    for (int i = -12; i <= 12; ++i)
    {
      c.Probe.push_back(static_cast<float>(0.05 * i * hx));
      c.Probe.push_back(static_cast<float>(0.05 * j * hy));
    }
}

// The reference of a case without a closed form: RK4 at 1/8 voxel on the CPU, same grid.
void ReferenceByRK4(Case& c)
{
  TraceSettings s;
  s.Device = Backend::CPU;
  s.Method = Integrator::RK4;
  s.StepSize = 0.125;
  const std::vector<RayRecord> rec = TraceRays(c.V, s, c.Probe);
  for (const RayRecord& r : rec)
  {
    c.RefX.push_back(r.DeflX);
    c.RefY.push_back(r.DeflY);
    c.RefMax = std::max(c.RefMax, std::hypot(double(r.DeflX), double(r.DeflY)));
  }
  c.Reference = "RK4 at 1/8 voxel, same grid";
}

bool Gaussian(Case& c, int size)
{
  const double A = 1e-4, w = 0.25;
  SceneParameters p;
  p.Amplitude = A;
  p.Width = w;
  for (int a = 0; a < 3; ++a)
  {
    c.V.Dimensions[a] = size;
    c.V.Origin[a] = -1;
    c.V.Spacing[a] = 2.0 / (size - 1);
  }
  c.N1.resize(c.V.NumberOfPoints());
  FillScene(Scene::GaussianSphere, p, c.V.Dimensions, c.V.Origin, c.V.Spacing, c.N1.data(), nullptr);
  c.Name = "Gaussian sphere A = 1e-4, s = 0.25, " + std::to_string(size) + "^3";
  SetUp(c);
  for (std::size_t k = 0; k < c.Probe.size() / 2; ++k)
  {
    double e[2];
    schtest::GaussianDeflection(A, w, c.Probe[2 * k], c.Probe[2 * k + 1], e);
    c.RefX.push_back(e[0]);
    c.RefY.push_back(e[1]);
  }
  c.RefMax = schtest::GaussianMaxDeflection(A);
  c.Reference = "closed form eps = -(2 sqrt(pi) A / s) (x, y) exp(-rho^2 / s^2)";
  return true;
}

bool Plume(Case& c)
{
  // 480 x 720 x 100 points, 0.1 mm apart: a 3 mm helium nozzle at the bottom, the jet rising 72 mm
  const int dims[3] = { 480, 720, 100 };
  const double h = 1e-4;
  for (int a = 0; a < 3; ++a)
  {
    c.V.Dimensions[a] = dims[a];
    c.V.Spacing[a] = h;
    c.V.Origin[a] = -0.5 * (dims[a] - 1) * h;
  }
  SceneParameters p;
  p.Amplitude = 1.0; // pure helium at the nozzle
  p.Radius = 0.003;
  p.Width = (dims[1] - 1) * h;
  c.N1.resize(c.V.NumberOfPoints());
  FillScene(Scene::HeliumPlume, p, c.V.Dimensions, c.V.Origin, c.V.Spacing, c.N1.data(), nullptr);
  c.Name = "helium plume 480 x 720 x 100 (nozzle 3 mm, 0.1 mm spacing)";
  SetUp(c);
  ReferenceByRK4(c);
  return true;
}

bool BluntFin(Case& c, const std::string& raw)
{
  std::ifstream hdr(raw + ".txt");
  std::ifstream data(raw + ".raw", std::ios::binary);
  if (!hdr || !data)
  {
    std::printf("bluntfin: SKIP, no %s.raw/.txt (scripts/benchmark.sh writes them with "
                "Testing/Benchmarks/bluntfin_volume.py when ../shared/data has the blunt fin)\n\n",
      raw.c_str());
    return false;
  }
  std::string key;
  hdr >> key >> c.V.Dimensions[0] >> c.V.Dimensions[1] >> c.V.Dimensions[2];
  hdr >> key >> c.V.Origin[0] >> c.V.Origin[1] >> c.V.Origin[2];
  hdr >> key >> c.V.Spacing[0] >> c.V.Spacing[1] >> c.V.Spacing[2];
  c.N1.resize(c.V.NumberOfPoints());
  data.read(reinterpret_cast<char*>(c.N1.data()), static_cast<std::streamsize>(c.N1.size() * sizeof(float)));
  if (!hdr || data.gcount() != static_cast<std::streamsize>(c.N1.size() * sizeof(float)))
  {
    std::printf("bluntfin: SKIP, %s.raw/.txt do not match\n\n", raw.c_str());
    return false;
  }
  c.Name = "NASA blunt fin (Mach 2.95) resampled to " + std::to_string(c.V.Dimensions[0]) + " x " +
    std::to_string(c.V.Dimensions[1]) + " x " + std::to_string(c.V.Dimensions[2]);
  SetUp(c);
  ReferenceByRK4(c);
  return true;
}

void Run(Case& c, const std::string& backends, const std::string& only, int film, int passes,
  double step, int rpi)
{
  std::printf("## %s\n\n", c.Name.c_str());
  std::printf("error: the largest over 625 probe rays of |deflection - reference|, as a fraction of the "
              "largest reference deflection (%.3g rad); reference: %s\n\n",
    c.RefMax, c.Reference.c_str());
  std::printf("| backend, setting | photons/s | samples/s | ms/pass | samples/ray | error | first-trace ms |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  struct Row
  {
    const char* Key;
    const char* Name;
    Integrator Method;
    bool Octree;
    bool OneThread;
  };
  const Row rows[] = { { "euler", "Euler", Integrator::Euler, false, false },
    { "octree", "Euler + octree", Integrator::Euler, true, false },
    { "auto", "Auto (1 % of max eps) + octree", Integrator::Auto, true, false },
    { "onethread", "Euler, 1 thread", Integrator::Euler, false, true } };
  std::stringstream ss(backends);
  std::string name;
  while (std::getline(ss, name, ','))
  {
    for (const Row& row : rows)
    {
      const Backend device = ParseBackend(name);
      if (row.OneThread && device != Backend::CPU)
        continue;
      if (!only.empty() && ("," + only + ",").find(std::string(",") + row.Key + ",") == std::string::npos)
        continue;
      TraceSettings s;
      s.Device = device;
      s.Resolution[0] = s.Resolution[1] = film;
      s.StepSize = step;
      s.Passes = 1;
      s.CutoffScale = 1000;
      s.Method = row.Method;
      s.Tolerance = 0.01 * c.RefMax;
      if (rpi > 0)
        s.RaysPerWorkItem = rpi;
      Volume vv = c.V;
      if (row.Octree)
      {
        vv.Levels = c.Levels.data();
        vv.LevelTolerance = c.OctreeTolerance;
      }
      if (row.OneThread)
        s.Threads = 1;
      try
      {
        // Auto chooses once (its pilot is not part of the pass time)
        s = ResolveAuto(vv, s);
        // first trace: includes the program build (cached after) and the upload
        const auto t0 = Clock::now();
        TraceResult warm = Trace(vv, s);
        const double first = Since(t0);
        (void)warm;
        s.Passes = passes;
        TraceResult r = Trace(vv, s);
        const std::vector<RayRecord> rec = TraceRays(vv, s, c.Probe);
        double err = 0;
        for (std::size_t k = 0; k < rec.size(); ++k)
          err = std::max(err, std::hypot(rec[k].DeflX - c.RefX[k], rec[k].DeflY - c.RefY[k]));
        std::string label = std::string(r.BackendUsed) + ", " + row.Name;
        if (row.Method == Integrator::Auto)
        {
          char chosen[64];
          std::snprintf(chosen, sizeof(chosen), " -> %s %.3g vox%s", IntegratorName(s.Method),
            s.StepSize, s.UseOctree ? "" : ", octree off");
          label += chosen;
        }
        std::printf("| %s | %.3g M | %.3g M | %.1f | %.1f | %.3g | %.0f |\n", label.c_str(),
          r.Photons / r.Seconds / 1e6, r.Samples / r.Seconds / 1e6, r.Seconds / passes * 1e3,
          r.Samples / r.Photons, err / c.RefMax, first * 1e3);
      }
      catch (const Error& e)
      {
        std::printf("| %s, %s | failed: %s | | | | | |\n", name.c_str(), row.Name, e.what());
      }
      std::fflush(stdout);
    }
  }
  std::printf("\nn - 1 packed with its gradient in %.0f ms; octree: tolerance %.3g (1e-4 of the index "
              "range), %.1f %% of cells skippable, built in %.0f ms\n\n",
    c.PackMs, c.OctreeTolerance, 100 * c.Skippable, c.LevelMs);
}

// The raycost case (issue 24's per-ray overhead): what a ray costs besides its samples. The
// Gaussian sphere traced as a camera move traces it (a whole update of the engine: the film sums
// zeroed in place, Accumulate, Finalize; an oblique view per round, the same for every row) at
// the base steps of --steps (0.3 to 30 voxels), and once with every ray stopped after its first
// step (MaxSteps 1: the ray's set-up, its entry sample, one step and its record). Steps are taken
// in turn, round after round, so that the machine's drift falls on every row alike; each row's
// time is the median over the rounds. A fit of time = rays x fixed + samples x per-sample
// through the 10 and 30 voxel rows says what a ray costs that does not depend on its length, in
// samples' worth; the rate against the first row's (0.3 voxel by default) is issue 24's ratio
// (target >= 0.5 at about 16 samples per ray). Each row's error is that of its step against the
// closed form (625 probe rays, on axis).
void RayCost(Case& c, const std::string& backends, int film, int rounds, std::vector<double> steps)
{
  std::printf("## ray cost: %s, film %d^2, 1 pass, oblique views, median of %d rounds\n\n",
    c.Name.c_str(), film, rounds);
  std::printf("| backend | base step (voxels) | samples/ray | ms per update | M samples/s | "
              "rate / the first row's rate | error (of max eps) |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  steps.push_back(10); // the last row: 10 voxels with MaxSteps 1
  const int kinds = static_cast<int>(steps.size());
  std::stringstream bs(backends);
  std::string name;
  while (std::getline(bs, name, ','))
  {
    try
    {
      // per row, per round: ms and samples; every row sees the same views (one per round)
      std::vector<std::vector<double>> ms(kinds);
      std::vector<double> samples(kinds), time(kinds), err(kinds);
      double rays = 0;
      FilmSums sums;
      for (int r = 0; r <= rounds; ++r)
        for (int k = 0; k < kinds; ++k)
        {
          TraceSettings s;
          s.Device = ParseBackend(name);
          s.Resolution[0] = s.Resolution[1] = film;
          s.CutoffScale = 1000;
          s.StepSize = steps[k];
          if (k == kinds - 1)
            s.MaxSteps = 1;
          const double a = 0.3 + 0.37 * r;
          s.ViewDirection[0] = std::cos(a);
          s.ViewDirection[1] = 0.3 * std::sin(3 * a);
          s.ViewDirection[2] = std::sin(a);
          const auto t0 = Clock::now();
          sums.Resize(film, film);
          Accumulate(c.V, s, sums);
          const TraceResult res = Finalize(c.V, s, sums);
          const double t = Since(t0);
          if (r == 0)
          {
            // the first round builds the programs and uploads: not timed; the errors, on axis
            TraceSettings axis = s;
            axis.ViewDirection[0] = axis.ViewDirection[1] = 0;
            axis.ViewDirection[2] = -1;
            const std::vector<RayRecord> rec = TraceRays(c.V, axis, c.Probe);
            for (std::size_t q = 0; q < rec.size(); ++q)
              err[k] = std::max(err[k], std::hypot(rec[q].DeflX - c.RefX[q], rec[q].DeflY - c.RefY[q]));
            continue;
          }
          ms[k].push_back(t * 1e3);
          samples[k] += res.Samples;
          time[k] += t;
          rays += k == 0 ? res.Photons : 0;
        }
      rays /= rounds; // per update
      std::vector<double> med(kinds), spr(kinds), rate(kinds);
      for (int k = 0; k < kinds; ++k)
      {
        std::sort(ms[k].begin(), ms[k].end());
        med[k] = ms[k][ms[k].size() / 2];
        spr[k] = samples[k] / rounds / rays;
        rate[k] = samples[k] / time[k];
      }
      for (int k = 0; k < kinds; ++k)
      {
        char e[32] = "-"; // rays stopped after a step have no deflection to compare
        if (k < kinds - 1)
          std::snprintf(e, sizeof(e), "%.3g", err[k] / c.RefMax);
        std::printf("| %s | %g%s | %.1f | %.1f | %.1f | %.2f | %s |\n", name.c_str(), steps[k],
          k == kinds - 1 ? ", MaxSteps 1" : "", spr[k], med[k], rate[k] / 1e6, rate[k] / rate[0], e);
      }
      // time per ray = fixed + per-sample x samples per ray through the 10 and 30 voxel rows
      // (the same views, the same kind of step: long, prefetched, checked for features)
      const auto p10 = std::find(steps.begin(), steps.end() - 1, 10.0) - steps.begin();
      const auto p30 = std::find(steps.begin(), steps.end() - 1, 30.0) - steps.begin();
      if (p10 < kinds - 1 && p30 < kinds - 1)
      {
        const double per = (time[p10] - time[p30]) / (samples[p10] - samples[p30]);
        const double fixed = (time[p10] - per * samples[p10]) / (rounds * rays);
        std::printf("\n%s: at long steps a ray costs %.0f ns besides its samples (%.1f samples' "
                    "worth) and %.1f ns a sample; at %g voxels %.1f ns a sample (wall, every "
                    "thread)\n",
          name.c_str(), fixed * 1e9, fixed / per, per * 1e9, steps[0], 1e9 / rate[0]);
      }
      std::printf("\n");
    }
    catch (const Error& e)
    {
      std::printf("| %s | failed: %s | | | | | |\n", name.c_str(), e.what());
    }
    std::fflush(stdout);
  }
}

// The rays through a film of film^2 pixels over [-1, 1]^2 whose centres lie within |a|, |b| < half:
// (a, b) pairs, where the Gaussian cases compare deflections with the closed form.
std::vector<float> CentreRays(int film, double half)
{
  std::vector<float> ab;
  const double pix = 2.0 / film;
  for (int j = 0; j < film; ++j)
    for (int i = 0; i < film; ++i)
    {
      const double a = -1 + (i + 0.5) * pix, b = -1 + (j + 0.5) * pix;
      if (std::fabs(a) < half && std::fabs(b) < half)
      {
        ab.push_back(static_cast<float>(a));
        ab.push_back(static_cast<float>(b));
      }
    }
  return ab;
}

// The weak Gaussian (A, s = w) on n^3 points over [-1, 1]^3 packed for both reconstructions
// (PackFieldHighOrder) into `packed` and `smooth`, `v` set to trace it (a new stamp, the kept
// volume released); false, with the table's row saying why, where it cannot be allocated.
bool PackedGaussian(int n, double A, double w, Volume& v, AlignedFloats& packed,
  std::vector<unsigned char>& smooth)
{
  for (int a = 0; a < 3; ++a)
  {
    v.Dimensions[a] = n;
    v.Origin[a] = -1;
    v.Spacing[a] = 2.0 / (n - 1);
  }
  try
  {
    std::vector<float> n1(v.NumberOfPoints());
    SceneParameters p;
    p.Amplitude = A;
    p.Width = w;
    FillScene(Scene::GaussianSphere, p, v.Dimensions, v.Origin, v.Spacing, n1.data(), nullptr);
    packed.resize(4 * n1.size());
    smooth.resize(n1.size());
    PackFieldHighOrder(v.Dimensions, v.Spacing, n1.data(), packed.data(), smooth.data());
  }
  catch (const std::exception& e)
  {
    std::printf("| %d^3 | could not allocate or fill: %s | | | | | | | | |\n", n, e.what());
    return false;
  }
  v.Field = packed.data();
  v.Smooth = smooth.data();
  ReleaseKeptVolume();
  v.Stamp = NewVolumeStamp();
  return true;
}

double Median(std::vector<double> x)
{
  std::sort(x.begin(), x.end());
  return x.empty() ? 0.0 : x.size() % 2 ? x[x.size() / 2] : 0.5 * (x[x.size() / 2 - 1] + x[x.size() / 2]);
}

// The grids case: one row per grid, reconstruction and backend.
void Grids(const std::string& grids, const std::string& backends, int film, int passes, double tolFrac)
{
  const double A = 2e-4, w = 0.25;
  const double peak = schtest::GaussianMaxDeflection(A);
  std::printf("## Weak Gaussian A = 2e-4, s = 0.25 on [-1, 1]^3, beam along -z, Auto at a tolerance of "
              "%.3g of the peak deflection (%.3g rad)\n\n", tolFrac, tolFrac * peak);
  std::printf("error: RMS and largest over the film's pixel centres within |x|, |y| < 2.2 s of "
              "|deflection - closed form|, as a fraction of the peak; rays/s of %d passes of a %d^2 film "
              "(Auto's pilot not included: its time is the last column)\n\n", passes, film);
  std::printf("| grid | backend, setting | chosen | rays/s | samples/ray | RMS error | max error | "
              "pack ms | pilot ms |\n|---|---|---|---|---|---|---|---|---|\n");
  std::stringstream gs(grids);
  std::string g;
  while (std::getline(gs, g, ','))
  {
    const int n = std::atoi(g.c_str());
    Volume v;
    for (int a = 0; a < 3; ++a)
    {
      v.Dimensions[a] = n;
      v.Origin[a] = -1;
      v.Spacing[a] = 2.0 / (n - 1);
    }
    std::vector<float> n1, packed, present;
    std::vector<unsigned char> smooth;
    try
    {
      n1.resize(v.NumberOfPoints());
      SceneParameters p;
      p.Amplitude = A;
      p.Width = w;
      FillScene(Scene::GaussianSphere, p, v.Dimensions, v.Origin, v.Spacing, n1.data(), nullptr);
      packed.resize(4 * n1.size());
      smooth.resize(n1.size());
    }
    catch (const std::exception& e)
    {
      std::printf("| %d^3 | could not allocate or fill: %s | | | | | | | |\n", n, e.what());
      continue;
    }
    v.Field = packed.data();
    // the rays through the film's pixel centres within |x|, |y| < 2.2 s (the film covers the box)
    const std::vector<float> ab = CentreRays(film, 2.2 * w);
    std::stringstream bs(backends);
    std::string name;
    while (std::getline(bs, name, ','))
      for (Reconstruction rc : { Reconstruction::Auto, Reconstruction::Trilinear })
      {
        // Auto: the field packed for both (PackFieldHighOrder); the present scheme: PackField
        const auto t0 = Clock::now();
        if (rc == Reconstruction::Auto)
          PackFieldHighOrder(v.Dimensions, v.Spacing, n1.data(), packed.data(), smooth.data());
        else
          PackField(v.Dimensions, v.Spacing, n1.data(), packed.data());
        const double packMs = Since(t0) * 1e3;
        v.Smooth = rc == Reconstruction::Auto ? smooth.data() : nullptr;
        ReleaseKeptVolume();
        v.Stamp = NewVolumeStamp();
        TraceSettings s;
        s.Device = ParseBackend(name);
        s.Resolution[0] = s.Resolution[1] = film;
        s.Passes = 1;
        s.CutoffScale = 1000;
        s.Jitter = false;
        s.Method = Integrator::Auto;
        s.Recon = rc;
        s.Tolerance = tolFrac * peak;
        try
        {
          const auto tp = Clock::now();
          AutoChoice choice;
          s = ResolveAuto(v, s, &choice);
          const double pilotMs = Since(tp) * 1e3;
          Trace(v, s); // the first trace builds the program and uploads
          s.Passes = passes;
          const TraceResult r = Trace(v, s);
          const std::vector<RayRecord> rec = TraceRays(v, s, ab);
          double sum = 0, worst = 0;
          for (std::size_t k = 0; k < rec.size(); ++k)
          {
            double e[2];
            schtest::GaussianDeflection(A, w, ab[2 * k], ab[2 * k + 1], e);
            const double d2 = (rec[k].DeflX - e[0]) * (rec[k].DeflX - e[0]) + (rec[k].DeflY - e[1]) * (rec[k].DeflY - e[1]);
            sum += d2;
            worst = std::max(worst, std::sqrt(d2));
          }
          char chosen[96];
          std::snprintf(chosen, sizeof(chosen), "%s %s %.3g vox%s", ReconstructionName(s.Recon),
            IntegratorName(s.Method), s.StepSize, choice.Met ? "" : " (tolerance not met)");
          std::printf("| %d^3 | %s, %s | %s | %.3g M | %.1f | %.3g %% | %.3g %% | %.0f | %.0f |\n", n,
            r.BackendUsed.c_str(), rc == Reconstruction::Auto ? "Auto / Auto" : "Auto / Trilinear (present)",
            chosen, r.Photons / r.Seconds / 1e6, r.Samples / r.Photons,
            100 * std::sqrt(sum / rec.size()) / peak, 100 * worst / peak, packMs, pilotMs);
        }
        catch (const Error& e)
        {
          std::printf("| %d^3 | %s | failed: %s | | | | | | |\n", n, name.c_str(), e.what());
        }
        std::fflush(stdout);
      }
    ReleaseKeptVolume();
  }
  std::printf("\n");
}

// The autostep case (issue 50): the weak Gaussian of the grids case on each grid, Auto (Integrator
// and Reconstruction) at its default tolerance and at 3e-8 rad beside the setting the issue names
// (Straight, trilinear, step = the feature's width s) and the cheapest setting of a sweep that
// meets Auto's default tolerance (the sweep of TestEngineAutoStep: 4 integrators x 2
// reconstructions x steps 2^(k/2) voxels, 1-128, max error over 24 x 24 rays within 2.2 s against
// the closed form, a tricubic sample counted as 3). Errors: RMS and largest over the film's pixel
// centres within 2.2 s, against the closed form, of the peak. Speed: rays/s of a film of --passes
// passes after a first trace (the program and the upload), the pilot apart; then each setting's
// rays/s on each grid over its 64^3 rate (the scaling table).
void AutoStep(const std::string& grids, const std::string& backends, int film, int passes)
{
  const double A = 2e-4, w = 0.25;
  const double peak = schtest::GaussianMaxDeflection(A);
  std::printf("## Auto's step (issue 50): weak Gaussian A = 2e-4, s = 0.25 on [-1, 1]^3, beam along -z, "
              "film %d^2, %d passes\n\n", film, passes);
  std::printf("error: RMS / largest |deflection - closed form| over the film's pixel centres within "
              "|x|, |y| < 2.2 s, of the peak (%.4g rad); rays/s: the trace without the pilot; pilot ms: "
              "a pilot once the programs are built and the field uploaded (a session's first, which "
              "does both, in brackets); rays/s with the pilot: an update of the passes that runs it; cost: samples per ray, a tricubic sample counted as 3. The peers' columns of the "
              "issue (jdhare/turbulence_tracing, cfdtools SHADOWGRAPH) need their code, not kept here.\n\n",
    peak);
  struct Row
  {
    std::string Name;
    double Rate = 0, Rms = 0;
  };
  std::printf("| grid | backend | setting | chosen | samples/ray | RMS error | max error | rays/s | pilot ms | rays/s with the pilot |\n"
              "|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::pair<int, std::vector<Row>>> scaling;
  std::stringstream gs(grids);
  std::string g;
  while (std::getline(gs, g, ','))
  {
    const int n = std::atoi(g.c_str());
    Volume v;
    AlignedFloats packed;
    std::vector<unsigned char> smooth;
    if (!PackedGaussian(n, A, w, v, packed, smooth))
      continue;
    // the film's pixel centres within 2.2 s, and 24 x 24 rays for the sweep
    const std::vector<float> ab = CentreRays(film, 2.2 * w);
    std::vector<float> sweepAb;
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i)
      {
        sweepAb.push_back(static_cast<float>(-2.2 * w + 4.4 * w * (i + 0.5) / 24));
        sweepAb.push_back(static_cast<float>(-2.2 * w + 4.4 * w * (j + 0.5) / 24));
      }
    auto errors = [&](const std::vector<float>& rays, const std::vector<RayRecord>& rec, double* rms) {
      double sum = 0, worst = 0;
      for (std::size_t k = 0; k < rec.size(); ++k)
      {
        double e[2];
        schtest::GaussianDeflection(A, w, rays[2 * k], rays[2 * k + 1], e);
        double d = std::hypot(rec[k].DeflX - e[0], rec[k].DeflY - e[1]);
        if (rec[k].Flags & (RayMaxSteps | RayTurned | RayNonFinite | RayOffFilm | RayUnderresolved))
          d = 1.0;
        sum += d * d;
        worst = std::max(worst, d);
      }
      if (rms)
        *rms = std::sqrt(sum / std::max<std::size_t>(1, rec.size()));
      return worst;
    };
    std::vector<Row> rows;
    std::stringstream bs(backends);
    std::string bname;
    bool first = true;
    while (std::getline(bs, bname, ','))
    {
      TraceSettings base;
      base.Device = ParseBackend(bname);
      base.Resolution[0] = base.Resolution[1] = film;
      base.Passes = 1;
      base.CutoffScale = 1000;
      base.UseOctree = false;
      double defaultTol = 0.01 * peak;
      // the rows: Auto at its default and at 3e-8 rad, the setting, the sweep's cheapest,
      // Euler at a voxel (the scaling table's first row)
      std::vector<std::pair<std::string, TraceSettings>> settings;
      std::vector<double> pilotMs, pilotFirstMs;
      for (double tol : { 0.0, 3e-8 })
      {
        TraceSettings s = base;
        s.Method = Integrator::Auto;
        s.Recon = Reconstruction::Auto;
        s.Tolerance = tol;
        AutoChoice choice;
        // the pilot twice: the first builds the programs and uploads the field (a session's
        // first update), the second is what a pilot costs once they are there (a camera at rest)
        double first = 0;
        try
        {
          auto tp = Clock::now();
          ResolveAuto(v, s, &choice);
          first = Since(tp) * 1e3;
          tp = Clock::now();
          s = ResolveAuto(v, s, &choice);
          pilotMs.push_back(Since(tp) * 1e3);
        }
        catch (const Error& e)
        {
          std::printf("| %d^3 | %s | Auto %g | failed: %s | | | | | | |\n", n, bname.c_str(), tol, e.what());
          continue;
        }
        pilotFirstMs.push_back(first);
        if (tol == 0)
          defaultTol = choice.Tolerance;
        settings.push_back({ tol == 0 ? "Auto, default tolerance" : "Auto, 3e-8 rad", s });
      }
      {
        TraceSettings s = base;
        s.Method = Integrator::Straight;
        s.StepSize = w / v.Spacing[0];
        settings.push_back({ "Straight, trilinear, step = s", s });
      }
      {
        // the sweep's cheapest setting that meets Auto's default tolerance
        double best = 1e300;
        TraceSettings bestS = base;
        for (Reconstruction rc : { Reconstruction::Trilinear, Reconstruction::Cubic })
          for (Integrator m : { Integrator::Straight, Integrator::Euler, Integrator::Verlet, Integrator::Midpoint,
           Integrator::RK4 })
            for (int k = 14; k >= 0; --k)
            {
              TraceSettings t = base;
              t.Method = m;
              t.Recon = rc;
              t.StepSize = std::pow(2.0, 0.5 * k);
              std::vector<RayRecord> rec;
              try
              {
                rec = TraceRays(v, t, sweepAb);
              }
              catch (const Error&)
              {
                continue;
              }
              if (errors(sweepAb, rec, nullptr) > defaultTol)
                continue;
              double spr = 0;
              for (const RayRecord& r : rec)
                spr += r.Samples / rec.size();
              const double cost = spr * (rc == Reconstruction::Cubic ? 3.0 : 1.0);
              if (cost < best)
              {
                best = cost;
                bestS = t;
              }
              break; // the longest step of this group that meets it
            }
        settings.push_back({ "cheapest swept at Auto's default", bestS });
      }
      {
        TraceSettings s = base;
        s.Method = Integrator::Euler;
        s.StepSize = 1.0;
        settings.push_back({ "Euler 1 voxel", s });
      }
      for (std::size_t k = 0; k < settings.size(); ++k)
      {
        TraceSettings s = settings[k].second;
        try
        {
          Trace(v, s); // the program and the upload
          s.Passes = passes;
          const TraceResult r = Trace(v, s);
          double rms = 0;
          const double worst = errors(ab, TraceRays(v, s, ab), &rms);
          char chosen[96];
          std::snprintf(chosen, sizeof(chosen), "%s %s %.3g vox", ReconstructionName(s.Recon),
            IntegratorName(s.Method), s.StepSize);
          char pilot[48] = "-", withPilot[32] = "-";
          const double rate = r.Photons / r.Seconds;
          // an update of --passes passes that runs the pilot (warm): its rays over pilot + trace
          double rateWithPilot = 0;
          if (k < pilotMs.size())
          {
            std::snprintf(pilot, sizeof(pilot), "%.0f (first %.0f)", pilotMs[k], pilotFirstMs[k]);
            rateWithPilot = r.Photons / (r.Seconds + 1e-3 * pilotMs[k]);
            std::snprintf(withPilot, sizeof(withPilot), "%.3g M", rateWithPilot / 1e6);
          }
          std::printf("| %d^3 | %s | %s | %s | %.1f | %.3g %% | %.3g %% | %.3g M | %s | %s |\n", n,
            r.BackendUsed.c_str(), settings[k].first.c_str(), chosen, r.Samples / r.Photons,
            100 * rms / peak, 100 * worst / peak, rate / 1e6, pilot, withPilot);
          if (first)
          {
            rows.push_back({ settings[k].first, settings[k].first == "Euler 1 voxel" ? r.Samples / r.Seconds : rate,
              rms / peak });
            if (rateWithPilot > 0)
              rows.push_back({ settings[k].first + ", with its pilot", rateWithPilot, rms / peak });
          }
        }
        catch (const Error& e)
        {
          std::printf("| %d^3 | %s | %s | failed: %s | | | | | | |\n", n, bname.c_str(),
            settings[k].first.c_str(), e.what());
        }
        std::fflush(stdout);
      }
      first = false;
    }
    scaling.push_back({ n, rows });
    ReleaseKeptVolume();
  }
  // the scaling table: each setting's rate on each grid over its rate on the first grid (first backend)
  if (scaling.empty() || scaling[0].second.empty())
    return;
  std::printf("\nrays/s (Euler 1 voxel: samples/s) over the %d^3 rate, first backend; RMS error of the peak "
              "in brackets\n\n| setting |", scaling[0].first);
  for (const auto& sc : scaling)
    std::printf(" %d^3 |", sc.first);
  std::printf("\n|---|");
  for (std::size_t k = 0; k < scaling.size(); ++k)
    std::printf("---|");
  std::printf("\n");
  for (std::size_t r = 0; r < scaling[0].second.size(); ++r)
  {
    std::printf("| %s |", scaling[0].second[r].Name.c_str());
    for (const auto& sc : scaling)
    {
      if (r < sc.second.size() && sc.second[r].Name == scaling[0].second[r].Name)
        std::printf(" %.2f (%.2g %%) |", sc.second[r].Rate / scaling[0].second[r].Rate, 100 * sc.second[r].Rms);
      else
        std::printf(" - |");
    }
    std::printf("\n");
  }
  std::printf("\n");
}

// The oblique case (issue 50): the weak Gaussian of the grids case on each grid of --grids, traced
// along the axis (beam along -z) and obliquely (beam along (1, 0.7, -0.4)), Euler at a fixed step
// (--step voxels, no octree, no Auto: the samples per unit length are the same), Trilinear and
// Cubic (one field packed for both by PackFieldHighOrder), each with the field in its linear layout
// and in bricks (SCHLIEREN_FIELD_BRICKS), the four alternated --rounds times in one run: medians of
// samples/s and rays/s, the cost per sample over the axis view's, and the RMS and largest deflection error against the closed form (the sphere is round:
// the closed form holds in any view's film coordinates) over the film's pixel centres within 2.2 s.
void Oblique(const std::string& grids, const std::string& backends, int film, int passes, double step,
  int rounds)
{
  const double A = 2e-4, w = 0.25;
  const double peak = schtest::GaussianMaxDeflection(A);
  std::printf("## Oblique views (issue 50): weak Gaussian A = 2e-4, s = 0.25 on [-1, 1]^3, Euler at %g voxel, "
              "no octree, film %d^2, %d passes, axis (0, 0, -1) and oblique (1, 0.7, -0.4) alternated %d times "
              "(medians)\n\n", step, film, passes, rounds);
  std::printf("time per sample: over the same layout's axis view, and over the linear layout's axis view; "
              "the two layouts' records compared bit for bit\n\n");
  std::printf("| grid | backend | reconstruction | layout | view | samples/ray | M samples/s | M rays/s | time per "
              "sample / axis | / linear axis | RMS error | max error |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const auto median = Median;
  std::stringstream gs(grids);
  std::string g;
  while (std::getline(gs, g, ','))
  {
    const int n = std::atoi(g.c_str());
    Volume v;
    AlignedFloats packed;
    std::vector<unsigned char> smooth;
    if (!PackedGaussian(n, A, w, v, packed, smooth))
      continue;
    const std::vector<float> ab = CentreRays(film, 2.2 * w);
    const RuntimeOptions options = GetRuntimeOptions();
    std::stringstream bs(backends);
    std::string bname;
    while (std::getline(bs, bname, ','))
      for (Reconstruction rc : { Reconstruction::Trilinear, Reconstruction::Cubic })
      {
        // [layout][view]: layout 0 the linear field (SCHLIEREN_FIELD_BRICKS=0), 1 the bricks
        TraceSettings s[2];
        for (int view = 0; view < 2; ++view)
        {
          s[view].Device = ParseBackend(bname);
          s[view].Resolution[0] = s[view].Resolution[1] = film;
          s[view].CutoffScale = 1000;
          s[view].UseOctree = false;
          s[view].Method = Integrator::Euler;
          s[view].Recon = rc;
          s[view].StepSize = step;
          s[view].Passes = passes;
        }
        s[1].ViewDirection[0] = 1;
        s[1].ViewDirection[1] = 0.7;
        s[1].ViewDirection[2] = -0.4;
        auto useLayout = [&](int layout) {
          RuntimeOptions o = options;
          o.Bricks = layout == 1 ? 1 : 0;
          SetRuntimeOptions(o);
        };
        std::vector<double> perSample[2][2], perRay[2][2];
        double samplesPerRay[2] = { 0, 0 }, rms[2] = { 0, 0 }, worst[2] = { 0, 0 };
        bool same = true;
        try
        {
          std::vector<RayRecord> first[2];
          for (int layout = 0; layout < 2; ++layout)
          {
            useLayout(layout);
            for (int view = 0; view < 2; ++view)
            {
              const std::vector<RayRecord> rec = TraceRays(v, s[view], ab);
              if (layout == 0)
                first[view] = rec;
              else
                same = same && std::memcmp(rec.data(), first[view].data(), rec.size() * sizeof(RayRecord)) == 0;
              double sum = 0;
              for (std::size_t k = 0; k < rec.size(); ++k)
              {
                double e[2];
                schtest::GaussianDeflection(A, w, ab[2 * k], ab[2 * k + 1], e);
                double d = std::hypot(rec[k].DeflX - e[0], rec[k].DeflY - e[1]);
                if (rec[k].Flags & (RayMaxSteps | RayTurned | RayNonFinite | RayOffFilm | RayUnderresolved))
                  d = 1.0;
                sum += d * d;
                worst[view] = std::max(worst[view], d);
              }
              rms[view] = std::sqrt(sum / std::max<std::size_t>(1, rec.size()));
            }
          }
          // each round: both layouts, both views; after a change of layout a small trace takes
          // the device's buffers and kernels (not timed)
          for (int r = 0; r < rounds; ++r)
            for (int layout = 0; layout < 2; ++layout)
            {
              useLayout(layout);
              TraceSettings warm = s[0];
              warm.Resolution[0] = warm.Resolution[1] = 8;
              warm.Passes = 1;
              Trace(v, warm);
              for (int view = 0; view < 2; ++view)
              {
                const TraceResult t = Trace(v, s[view]);
                perSample[layout][view].push_back(t.Seconds / t.Samples);
                perRay[layout][view].push_back(t.Seconds / t.Photons);
                samplesPerRay[view] = t.Samples / t.Photons;
              }
            }
        }
        catch (const Error& e)
        {
          SetRuntimeOptions(options);
          std::printf("| %d^3 | %s | %s | failed: %s | | | | | | | |\n", n, bname.c_str(), ReconstructionName(rc),
            e.what());
          continue;
        }
        SetRuntimeOptions(options);
        const double axis0 = median(perSample[0][0]);
        for (int layout = 0; layout < 2; ++layout)
          for (int view = 0; view < 2; ++view)
          {
            const double ps = median(perSample[layout][view]);
            std::printf("| %d^3 | %s | %s | %s | %s | %.1f | %.3g | %.3g | %.2f | %.2f | %.3g %% | %.3g %%%s |\n", n,
              bname.c_str(), ReconstructionName(rc), layout ? "bricks" : "linear", view ? "oblique" : "axis",
              samplesPerRay[view], 1e-6 / ps, 1e-6 / median(perRay[layout][view]),
              ps / median(perSample[layout][0]), ps / axis0, 100 * rms[view] / peak, 100 * worst[view] / peak,
              layout && !same ? " (records differ from linear!)" : "");
          }
        std::fflush(stdout);
      }
    ReleaseKeptVolume();
  }
  std::printf("\n");
}

// The cubicrate case (issue 50): Auto (Integrator and Reconstruction) at --tolerance rad on each
// grid, its choice traced beside the same integrator and step on the trilinear field, in the
// linear and the bricked layout, alternated --rounds times: median rays/s and samples/s, so that
// the grids' ratio splits into samples a ray and the rate of a sample, and the tricubic sample's
// cost over the trilinear one's is read at the step Auto takes (not at a voxel).
void CubicRate(const std::string& grids, const std::string& backends, int film, int passes, double tol, int rounds)
{
  const double A = 2e-4, w = 0.25;
  std::printf("## Auto at %g rad across grids (issue 50): weak Gaussian A = 2e-4, s = 0.25, beam along -z, film %d^2, "
              "%d passes, medians of %d alternations (the first trace of each grid and layout, which uploads, left out)\n\n",
    tol, film, passes, rounds);
  std::printf("| grid | backend | layout | setting | samples/ray | M rays/s | M samples/s | tricubic / trilinear time per sample | pilot ms | reference check ms |\n"
              "|---|---|---|---|---|---|---|---|---|---|\n");
  const RuntimeOptions options = GetRuntimeOptions();
  std::stringstream gs(grids);
  std::string g;
  while (std::getline(gs, g, ','))
  {
    const int n = std::atoi(g.c_str());
    Volume v;
    AlignedFloats packed;
    std::vector<unsigned char> smooth;
    if (!PackedGaussian(n, A, w, v, packed, smooth))
      continue;
    std::stringstream bs(backends);
    std::string bname;
    while (std::getline(bs, bname, ','))
    {
      TraceSettings s;
      s.Device = ParseBackend(bname);
      s.Resolution[0] = s.Resolution[1] = film;
      s.Passes = passes;
      s.CutoffScale = 1000;
      s.UseOctree = false;
      s.Method = Integrator::Auto;
      s.Recon = Reconstruction::Auto;
      s.Tolerance = tol;
      AutoChoice choice;
      TraceSettings chosen;
      double pilotMs = 0, copyMs = 0;
      try
      {
        ResolveAuto(v, s, &choice); // builds the programs, uploads the field (and a copy's)
        copyMs = choice.CoarseMs;
        const auto tp = Clock::now();
        chosen = ResolveAuto(v, s, &choice);
        pilotMs = Since(tp) * 1e3;
      }
      catch (const Error& e)
      {
        std::printf("| %d^3 | %s | failed: %s | | | | | | | |\n", n, bname.c_str(), e.what());
        continue;
      }
      TraceSettings twin = chosen;
      twin.Recon = chosen.Recon == Reconstruction::Cubic ? Reconstruction::Trilinear : Reconstruction::Cubic;
      const TraceSettings* set[2] = { &chosen, &twin };
      // [layout][setting]
      std::vector<double> rays[2][2], samples[2][2];
      double perRay[2] = { 0, 0 };
      for (int round = 0; round <= rounds; ++round)
        for (int layout = 0; layout < 2; ++layout)
        {
          RuntimeOptions o = options;
          o.Bricks = layout == 1;
          SetRuntimeOptions(o);
          for (int k = 0; k < 2; ++k)
          {
            const TraceResult r = Trace(v, *set[k]);
            perRay[k] = r.Photons > 0 ? r.Samples / r.Photons : 0;
            if (round == 0)
              continue; // the upload of this layout
            rays[layout][k].push_back(r.Photons / r.Seconds * 1e-6);
            samples[layout][k].push_back(r.Samples / r.Seconds * 1e-6);
          }
        }
      SetRuntimeOptions(options);
      auto median = [](std::vector<double> x) {
        std::sort(x.begin(), x.end());
        return x.empty() ? 0.0 : x[x.size() / 2];
      };
      for (int layout = 0; layout < 2; ++layout)
        for (int k = 0; k < 2; ++k)
        {
          const TraceSettings& t = *set[k];
          // the time of a tricubic sample over a trilinear one's (the same on both rows)
          const int cubicAt = chosen.Recon == Reconstruction::Cubic ? 0 : 1;
          const double cubicOverTri = median(samples[layout][1 - cubicAt]) / median(samples[layout][cubicAt]);
          // a coarse copy (issue 50): "on 1/r", the field at r times its spacing
          const std::string copy = t.FieldStride > 1 ? " on 1/" + std::to_string(t.FieldStride) : "";
          std::printf("| %d^3 | %s | %s | %s%s %s %.3g vox%s | %.1f | %.3g | %.3g | %.2f | %s | %s |\n", n, bname.c_str(),
            layout ? "bricks" : "linear", k == 0 ? "Auto: " : "", ReconstructionName(t.Recon), IntegratorName(t.Method),
            t.StepSize, copy.c_str(), perRay[k], median(rays[layout][k]), median(samples[layout][k]), cubicOverTri,
            k == 0 ? (std::to_string(static_cast<int>(pilotMs)) +
                       (copyMs > 0 ? " (copies " + std::to_string(static_cast<int>(copyMs)) + " once)" : "")).c_str()
                   : "-",
            k == 0 && choice.ReferenceError > 0 ? std::to_string(static_cast<int>(choice.ReferenceCheckMs)).c_str() : "-");
        }
      if (!choice.Met)
        std::printf("| %d^3 | %s | | Auto: %s | | | | | | |\n", n, bname.c_str(), choice.Report.c_str());
      std::fflush(stdout);
    }
    ReleaseKeptVolume();
  }
  std::printf("\n");
}

// The moves case (issue 50): per update of a TraceSession, the wall time split into the pilot
// (from Auto's report), the trace (TraceResult::Seconds) and the rest (packing the volume, the
// rays' set-up, the image).
void Moves(const std::string& grids, int film)
{
  const double A = 2e-4, w = 0.25;
  std::printf("## The first image after a camera move (issue 50): weak Gaussian A = 2e-4, s = 0.25 on "
              "[-1, 1]^3 in a TraceSession, film %d^2 at rest, %d^2 while moving (1 pass)\n\n",
    film, film / 2);
  std::printf("| grid | setting | update | film | wall ms | pilot ms | trace ms | rest ms | volume | chosen | samples/ray |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::stringstream gs(grids);
  std::string g;
  while (std::getline(gs, g, ','))
  {
    const int n = std::atoi(g.c_str());
    std::vector<float> n1;
    VolumePiece piece;
    try
    {
      n1.resize(static_cast<std::size_t>(n) * n * n);
      int dims[3] = { n, n, n };
      double origin[3] = { -1, -1, -1 }, spacing[3];
      for (int a = 0; a < 3; ++a)
        spacing[a] = 2.0 / (n - 1);
      SceneParameters p;
      p.Amplitude = A;
      p.Width = w;
      FillScene(Scene::GaussianSphere, p, dims, origin, spacing, n1.data(), nullptr);
      for (int a = 0; a < 3; ++a)
      {
        piece.WholeExtent[2 * a] = piece.Extent[2 * a] = 0;
        piece.WholeExtent[2 * a + 1] = piece.Extent[2 * a + 1] = n - 1;
        piece.Origin[a] = origin[a];
        piece.Spacing[a] = spacing[a];
      }
      piece.Version = 1;
      piece.Load = [&n1](PieceValues& v) {
        v.NMinus1InPlace = n1.data();
        v.NMinus1InPlaceCount = n1.size();
        return std::string();
      };
    }
    catch (const std::exception& e)
    {
      std::printf("| %d^3 | could not allocate or fill: %s | | | | | | | | | |\n", n, e.what());
      continue;
    }
    for (int setting = 0; setting < 2; ++setting)
    {
      TraceSession session;
      TraceSettings s;
      s.Method = Integrator::Auto;
      s.Recon = setting == 0 ? Reconstruction::Auto : Reconstruction::Cubic;
      s.Tolerance = setting == 0 ? 0.0 : 3e-8;
      s.CutoffScale = 1000;
      s.UseOctree = false;
      const char* name = setting == 0 ? "Auto, default tolerance" : "Auto + Cubic, 3e-8 rad";
      // at rest on axis, then moves: oblique, near the axis, oblique, and at rest again
      struct Step
      {
        const char* What;
        double Dir[3];
        bool Moving;
      };
      const Step steps[] = { { "first update, axis", { 0, 0, -1 }, false },
        { "move, oblique (1, 0.7, -0.4)", { 1, 0.7, -0.4 }, true },
        { "move, near the axis (0.05, 0.03, -1)", { 0.05, 0.03, -1 }, true },
        { "move, oblique (-0.6, 0.5, -0.6)", { -0.6, 0.5, -0.6 }, true },
        { "at rest, oblique (-0.6, 0.5, -0.6)", { -0.6, 0.5, -0.6 }, false },
        { "move, axis (0, 0, -1)", { 0, 0, -1 }, true } };
      for (const Step& st : steps)
      {
        TraceSettings t = s;
        for (int a = 0; a < 3; ++a)
          t.ViewDirection[a] = st.Dir[a];
        const bool alongY = std::fabs(st.Dir[1]) > 0.9 * std::sqrt(st.Dir[0] * st.Dir[0] + st.Dir[1] * st.Dir[1] + st.Dir[2] * st.Dir[2]);
        t.ViewUp[0] = 0;
        t.ViewUp[1] = alongY ? 0 : 1;
        t.ViewUp[2] = alongY ? 1 : 0;
        t.Resolution[0] = t.Resolution[1] = st.Moving ? film / 2 : film;
        t.Passes = 1;
        SessionImage out;
        const auto t0 = Clock::now();
        try
        {
          session.Update(SerialParallel(), piece, t, out);
        }
        catch (const Error& e)
        {
          std::printf("| %d^3 | %s | %s | failed: %s | | | | | | | |\n", n, name, st.What, e.what());
          break;
        }
        const double wall = Since(t0) * 1e3;
        double pilot = 0;
        const std::string& rep = out.Choice.Report;
        const std::size_t at = rep.find(" rays, ");
        if (!out.Choice.Reused && at != std::string::npos)
          pilot = std::atof(rep.c_str() + at + 7);
        const double trace = out.SecondsTracing * 1e3;
        char chosen[96];
        std::snprintf(chosen, sizeof(chosen), "%s %s %.3g vox%s", ReconstructionName(out.Traced.Recon),
          IntegratorName(out.Traced.Method), out.Traced.StepSize, out.Choice.Reused ? " (kept)" : "");
        std::printf("| %d^3 | %s | %s | %d^2 | %.0f | %.0f | %.0f | %.0f | %s | %s | %.1f |\n", n, name, st.What,
          t.Resolution[0], wall, pilot, trace, wall - pilot - trace, out.VolumeFrom.c_str(), chosen,
          out.Result.Photons > 0 ? out.Result.Samples / out.Result.Photons : 0.0);
        std::fflush(stdout);
      }
    }
  }
  std::printf("\n");
}

} // namespace

// The bench's sources on one case (the Gaussian sphere, size^3), and a camera aperture: rays/s of each, the passes each
// needs for an RMS of 1 % of the image's contrast against its own 32-pass image, and a camera
// move (8 views, 1 pass on a half-size film) per source. Slit, disc and Gaussian of 0.5 mm with
// f1 = f2 = 1 m at 50 % cut keep the sphere's deflections in their linear range.
void Sources(const std::string& backends, int film, int size)
{
  Case c;
  Gaussian(c, size);
  std::printf("## bench sources: %s, film %d^2\n\n", c.Name.c_str(), film);
  std::printf("| backend | source | rays/s (8 passes) | RMS at 1, 4, 16 passes (of contrast) | passes for 1 %% | camera move ms/view |\n");
  std::printf("|---|---|---|---|---|---|\n");
  std::stringstream bs(backends);
  std::string b;
  while (std::getline(bs, b, ','))
  {
    const Backend dev = b == "CPU" ? Backend::CPU : Backend::OpenCL;
    if (dev == Backend::OpenCL && !QueryOpenCLDevice().Available)
      continue;
    // the last row: the point source seen by a lens of f = 0.1 m at f/0.5 (D = 0.2) focused 0.5
    // in front of the sphere's centre, 1 from the focus plane: the sphere blurred by about 0.1
    // (6 pixels of a 128 film), the aperture sampled one lens point per pass (docs/BENCH.md "Camera")
    // and the point source under a white band, 400-700 nm in 16 bins (one wavelength per pass,
    // n - 1 scaled by air's dispersion: docs/BENCH.md "Light")
    for (int row = 0; row < 6; ++row)
    {
      const BenchSource src = row == 1 ? BenchSource::Slit
        : row == 2                     ? BenchSource::Disc
        : row == 3                     ? BenchSource::Gaussian
                                       : BenchSource::Point;
      TraceSettings s;
      s.Device = dev;
      s.Mode = Cutoff::KnifeEdge;
      s.Resolution[0] = s.Resolution[1] = film;
      if (row == 4)
      {
        s.Camera = CameraModel::Lens;
        s.CameraFocalLength = 0.1;
        s.FNumber = 0.5;
        s.FocusPlane = 0.5;
        s.CameraDistance = 1.5;
      }
      if (row == 5)
      {
        s.WavelengthRange[0] = 400;
        s.WavelengthRange[1] = 700;
        s.WavelengthBins = 16;
      }
      s.Source = src;
      s.SourceSize[0] = s.SourceSize[1] = 0.5;
      s.Passes = 32;
      const TraceResult ref = Trace(c.V, s);
      double lo = 1e30, hi = -1e30;
      for (float v : ref.Intensity)
        lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
      double rms[5];
      int need = 0;
      const int counts[5] = { 1, 2, 4, 8, 16 };
      double rate = 0;
      for (int q = 0; q < 5; ++q)
      {
        s.Passes = counts[q];
        s.Seed = 7; // not the reference's passes
        const auto t0 = Clock::now();
        const TraceResult r = Trace(c.V, s);
        if (counts[q] == 8)
          rate = r.Photons / Since(t0);
        double sum = 0;
        for (std::size_t i = 0; i < r.Intensity.size(); ++i)
          sum += (double(r.Intensity[i]) - ref.Intensity[i]) * (double(r.Intensity[i]) - ref.Intensity[i]);
        rms[q] = std::sqrt(sum / r.Intensity.size()) / std::max(hi - lo, 1e-30);
        if (!need && rms[q] < 0.01)
          need = counts[q];
      }
      // a camera move: 8 views 2 degrees apart, 1 pass on half the film, as Follow Camera does
      s.Passes = 1;
      s.Resolution[0] = s.Resolution[1] = film / 2;
      const auto t1 = Clock::now();
      for (int v = 0; v < 8; ++v)
      {
        const double ang = v * 2 * 3.14159265358979 / 180;
        s.ViewDirection[0] = std::sin(ang);
        s.ViewDirection[2] = -std::cos(ang);
        Trace(c.V, s);
      }
      const double msView = 1e3 * Since(t1) / 8;
      const char* names[] = { "Point", "Slit", "Rectangle", "Disc", "Gaussian" };
      std::printf("| %s | %s | %.3g | %.3g, %.3g, %.3g | %s | %.1f |\n", b.c_str(),
        row == 4 ? "Point, Lens f/0.5 defocused" : row == 5 ? "Point, white 400-700 nm" : names[static_cast<int>(src)],
        rate, rms[0], rms[2], rms[4], need ? std::to_string(need).c_str() : "> 16", msView);
      std::fflush(stdout);
    }
  }
  std::printf("\n");
}

int main(int argc, char** argv)
{
  int size = 256, film = 512, passes = 3, rpi = 0;
  double step = 0.5;
  std::string backends = "OpenCL,CPU", cases = "gaussian,plume,bluntfin", raw = "bluntfin_256";
  std::string rows; // empty: all rows (euler,octree,auto,onethread)
  std::string grids = "64,128,256,512";
  double tolFrac = 1e-3;
  int rounds = 5;
  std::vector<double> raySteps = { 0.3, 1, 3, 10, 30 };
  for (int i = 1; i + 1 < argc; i += 2)
  {
    if (!std::strcmp(argv[i], "--size"))
      size = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--film"))
      film = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--passes"))
      passes = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--step"))
      step = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--backends"))
      backends = argv[i + 1];
    else if (!std::strcmp(argv[i], "--rays-per-item"))
      rpi = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--cases"))
      cases = argv[i + 1];
    else if (!std::strcmp(argv[i], "--raw"))
      raw = argv[i + 1];
    else if (!std::strcmp(argv[i], "--rows"))
      rows = argv[i + 1];
    else if (!std::strcmp(argv[i], "--grids"))
      grids = argv[i + 1];
    else if (!std::strcmp(argv[i], "--tolerance"))
      tolFrac = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--rounds"))
      rounds = std::max(1, std::atoi(argv[i + 1]));
    else if (!std::strcmp(argv[i], "--steps"))
    {
      raySteps.clear();
      std::stringstream st(argv[i + 1]);
      std::string v;
      while (std::getline(st, v, ','))
        raySteps.push_back(std::atof(v.c_str()));
      if (raySteps.empty())
        raySteps.push_back(0.3);
    }
  }
  DeviceInfo dev = QueryOpenCLDevice();
  std::printf("# Schlieren benchmark: film %d^2, %d passes, Euler step %.2f voxel\n\n", film, passes, step);
  std::printf("machine: %s, %u hardware threads; OpenCL device: %s\n\n", CpuName().c_str(),
    std::thread::hardware_concurrency(),
    dev.Available ? (dev.Name + " (" + dev.Platform + ")").c_str() : dev.Reason.c_str());
  std::stringstream ss(cases);
  std::string name;
  while (std::getline(ss, name, ','))
  {
    Case c;
    bool ok = false;
    try
    {
      if (name == "grids")
        Grids(grids, backends, film, passes, tolFrac);
      else if (name == "autostep")
        AutoStep(grids, backends, film, passes);
      else if (name == "sources")
        Sources(backends, film, size);
      else if (name == "oblique")
        Oblique(grids, backends, film, passes, step, rounds);
      else if (name == "moves")
        Moves(grids, film);
      else if (name == "cubicrate")
        CubicRate(grids, backends, film, passes, tolFrac, rounds);
      else if (name == "raycost")
      {
        if (Gaussian(c, size))
          RayCost(c, backends, film, rounds, raySteps);
      }
      else if (name == "gaussian")
        ok = Gaussian(c, size);
      else if (name == "plume")
        ok = Plume(c);
      else if (name == "bluntfin")
        ok = BluntFin(c, raw);
      else
        std::printf("unknown case '%s' (gaussian, plume, bluntfin, grids, autostep, moves, cubicrate, oblique, sources, raycost)\n", name.c_str());
    }
    catch (const Error& e)
    {
      std::printf("%s: could not set up: %s\n", name.c_str(), e.what());
    }
    if (ok)
      Run(c, backends, rows, film, passes, step, rpi);
  }
  return 0;
}
