// SPDX-License-Identifier: BSD-3-Clause
// Benchmark (not a test): photons/s, samples/s and ms per pass of each backend side by side, on a
// Gaussian sphere (default 256^3, 512^2 film), with the error of the traced deflection against the
// closed form so that no speed is quoted without the accuracy it was bought at.
//
//   SchlierenBenchmark [--size N] [--film N] [--passes N] [--step voxels] [--backends CPU,OpenCL]
#include "SchlierenEngine.h"
#include "SchlierenScenes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace schlieren;

static std::string CpuName()
{
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0)
      return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

int main(int argc, char** argv)
{
  int size = 256, film = 512, passes = 3;
  double step = 0.5;
  int rpi = 0;
  std::string backends = "CPU,OpenCL";
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
  }
  const double A = 1e-4, w = 0.25;
  SceneParameters p;
  p.Amplitude = A;
  p.Width = w;
  Volume v;
  for (int a = 0; a < 3; ++a)
  {
    v.Dimensions[a] = size;
    v.Origin[a] = -1;
    v.Spacing[a] = 2.0 / (size - 1);
  }
  std::vector<float> n1(v.NumberOfPoints()), field(4 * n1.size());
  FillScene(Scene::GaussianSphere, p, v.Dimensions, v.Origin, v.Spacing, n1.data(), nullptr);
  const auto tp0 = std::chrono::steady_clock::now();
  PackField(v.Dimensions, v.Spacing, n1.data(), field.data());
  const double packSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tp0).count();
  v.Field = field.data();

  DeviceInfo dev = QueryOpenCLDevice();
  std::printf("Schlieren benchmark: Gaussian sphere A=%g s=%g on %d^3, film %d^2, %d passes, Euler "
              "step %.2f voxel\n",
    A, w, size, film, passes, step);
  std::printf("machine: %s, %u hardware threads; OpenCL device: %s\n", CpuName().c_str(),
    std::thread::hardware_concurrency(), dev.Available ? (dev.Name + " (" + dev.Platform + ")").c_str() : dev.Reason.c_str());
  std::printf("gradient precomputation (PackField): %.0f ms\n\n", packSeconds * 1e3);
  std::printf("| backend, setting | photons/s | samples/s | ms/pass | samples/ray | max deflection error (of max eps) | first-trace ms |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const double emax = std::sqrt(2 * M_PI) * A * std::exp(-0.5);
  // the octree for the "octree" rows: tolerance 1e-4 A (the accuracy test holds this to 1e-4 of
  // max eps against fixed steps)
  std::vector<unsigned char> levels(v.NumberOfPoints());
  const double octreeTol = 1e-4 * A;
  const auto tl0 = std::chrono::steady_clock::now();
  const double skippable = ComputeOctreeLevels(v.Dimensions, n1.data(), octreeTol, levels.data());
  const double levelMs = std::chrono::duration<double>(std::chrono::steady_clock::now() - tl0).count() * 1e3;
  std::vector<float> ab;
  for (int j = -12; j <= 12; ++j)
    for (int i = -12; i <= 12; ++i)
    {
      ab.push_back(static_cast<float>(0.05 * i));
      ab.push_back(static_cast<float>(0.05 * j));
    }
  struct Row
  {
    const char* Name;
    Integrator Method;
    bool Octree;
  };
  const Row rows[] = { { "Euler", Integrator::Euler, false }, { "Euler + octree", Integrator::Euler, true },
    { "Auto (1 % of max eps) + octree", Integrator::Auto, true } };
  std::stringstream ss(backends);
  std::string name;
  while (std::getline(ss, name, ','))
  {
    for (const Row& row : rows)
    {
      TraceSettings s;
      s.Device = ParseBackend(name);
      s.Resolution[0] = s.Resolution[1] = film;
      s.StepSize = step;
      s.Passes = 1;
      s.CutoffScale = 1000;
      s.Method = row.Method;
      s.Tolerance = 0.01 * std::sqrt(2 * M_PI) * A * std::exp(-0.5);
      if (rpi > 0)
        s.RaysPerWorkItem = rpi;
      Volume vv = v;
      if (row.Octree)
      {
        vv.Levels = levels.data();
        vv.LevelTolerance = octreeTol;
      }
      try
      {
        // Auto chooses once (its pilot is not part of the pass time)
        AutoChoice choice;
        s = ResolveAuto(vv, s, &choice);
        // first trace: includes the program build (cached after) and the upload
        const auto t0 = std::chrono::steady_clock::now();
        TraceResult warm = Trace(vv, s);
        const double first = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        s.Passes = passes;
        TraceResult r = Trace(vv, s);
        // accuracy: 25 x 25 rays through the sphere on this backend and setting, against the closed form
        std::vector<RayRecord> rec = TraceRays(vv, s, ab);
        double err = 0;
        for (std::size_t k = 0; k < rec.size(); ++k)
        {
          const double a = ab[2 * k], b = ab[2 * k + 1];
          const double f = -(2 * std::sqrt(M_PI) * A / w) * std::exp(-(a * a + b * b) / (w * w));
          err = std::max(err, std::hypot(rec[k].DeflX - f * a, rec[k].DeflY - f * b));
        }
        std::string label = std::string(r.BackendUsed) + ", " + row.Name;
        if (row.Method == Integrator::Auto)
          label += std::string(" -> ") + IntegratorName(s.Method) + " " + std::to_string(s.StepSize).substr(0, 4) + " vox";
        std::printf("| %s | %.3g M | %.3g M | %.1f | %.1f | %.3g | %.0f |\n", label.c_str(),
          r.Photons / r.Seconds / 1e6, r.Samples / r.Seconds / 1e6, r.Seconds / passes * 1e3,
          r.Samples / r.Photons, err / emax, first * 1e3);
        (void)warm;
      }
      catch (const Error& e)
      {
        std::printf("| %s, %s | failed: %s | | | | | |\n", name.c_str(), row.Name, e.what());
      }
    }
  }
  std::printf("\noctree: tolerance %.3g (1e-4 A), %.1f %% of cells skippable, built in %.0f ms\n",
    octreeTol, 100 * skippable, levelMs);
  std::printf("\n(deflection error: the largest over 625 rays at |x|, |y| <= 0.6, traced on the same "
              "backend and step, against eps = -(2 sqrt(pi) A / s) (x, y) exp(-rho^2 / s^2))\n");
  return 0;
}
