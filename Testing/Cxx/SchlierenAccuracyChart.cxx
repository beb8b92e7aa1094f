// SPDX-License-Identifier: BSD-3-Clause
// The speed-versus-accuracy chart's data (a benchmark, not a test): every method x step x octree
// tolerance on four known-answer scenes, and every method x step (up to 32 voxels) with
// Reconstruction Cubic (PackFieldHighOrder, octree off), and Auto (Integrator and Reconstruction)
// at tolerances from 1e-1 to 1e-5 of the largest deflection (its line). For each: the time per pass of a full film and the error
// of the same setting against the scene's closed form (SchlierenOracles.h, on Auto's pilot rays),
// relative to the answer's largest deflection. Prints a table and the Pareto front, writes a CSV
// for Testing/Benchmarks/accuracy_chart.py.
//
//   SchlierenAccuracyChart [--size N] [--film N] [--backend CPU|OpenCL] [--csv file]
//
// The CSV goes to --csv, else to accuracy_chart.csv in the build folder (never the working
// directory, which is often the source tree).
#include "SchlierenOracles.h"

#include <chrono>
#include <cstring>
#include <fstream>

using namespace schlieren;

int main(int argc, char** argv)
{
  int size = 96, filmSize = 128;
  std::string backend = "CPU", csv = SCHLIEREN_BINARY_DIR "/accuracy_chart.csv";
  for (int i = 1; i + 1 < argc; i += 2)
  {
    if (!std::strcmp(argv[i], "--size"))
      size = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--film"))
      filmSize = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--backend"))
      backend = argv[i + 1];
    else if (!std::strcmp(argv[i], "--csv"))
      csv = argv[i + 1];
  }
  std::ofstream out(csv);
  if (!out)
  {
    std::fprintf(stderr, "SchlierenAccuracyChart: cannot write the CSV file %s: give a writable path with --csv\n",
      csv.c_str());
    return 1;
  }
  out << "scene,method,step,octree_tolerance,ms_per_pass,samples_per_ray,relative_error,flagged,reconstruction,tolerance\n";
  std::vector<schtest::OracleCase> cases = { schtest::GaussianCase(size), schtest::LuneburgCase(size),
    schtest::ShockCase(size, 2.0), schtest::LinearCase(size) };
  std::printf("Speed against accuracy, %d^3 grids, %d^2 film, backend %s\n\n", size, filmSize, backend.c_str());
  std::printf("| scene | reconstruction | method | step (voxel) | octree tol (of range) | ms/pass | samples/ray | error (of max deflection) | flagged |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (schtest::OracleCase& c : cases)
  {
    const Volume base = c.SV->V;
    float lo = 1e30f, hi = -1e30f;
    for (float v : c.SV->N1)
    {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    struct Row
    {
      std::string Method;
      double Step, Tol, Ms, Err;
    };
    std::vector<Row> rows;
    std::vector<unsigned char> levels(base.NumberOfPoints()), smooth(base.NumberOfPoints());
    std::vector<float> high(c.SV->Field.size());
    PackFieldHighOrder(base.Dimensions, base.Spacing, c.SV->N1.data(), high.data(), smooth.data());
    // -1: Reconstruction Cubic (octree off)
    for (double rel : { 0.0, 1e-4, 1e-2, -1.0 })
    {
      Volume v = base;
      const bool cubic = rel < 0;
      const double shown = cubic ? 0.0 : rel;
      if (rel > 0)
      {
        v.LevelTolerance = rel * (double(hi) - lo);
        ComputeOctreeLevels(v.Dimensions, c.SV->N1.data(), v.LevelTolerance, levels.data());
        v.Levels = levels.data();
      }
      if (cubic)
      {
        v.Field = high.data();
        v.Smooth = smooth.data();
      }
      const std::vector<double> steps = cubic ? std::vector<double>{ 32, 16, 8, 4, 2, 1, 0.5, 0.25 }
                                              : std::vector<double>{ 8, 4, 2, 1, 0.5, 0.25 };
      for (Integrator m : { Integrator::Straight, Integrator::Euler, Integrator::Verlet, Integrator::Midpoint,
           Integrator::RK4 })
        for (double st : steps)
        {
          TraceSettings s = c.S;
          s.Device = ParseBackend(backend);
          s.Method = m;
          s.StepSize = st;
          s.Recon = cubic ? Reconstruction::Cubic : Reconstruction::Trilinear;
          const std::vector<RayRecord> r = TraceRays(v, s, c.AB);
          const double err = std::min(c.Error(r) / c.Magnitude, 1e3);
          bool flagged = false;
          for (const RayRecord& x : r)
            flagged = flagged || (x.Flags & RayUnderresolved);
          s.Resolution[0] = s.Resolution[1] = filmSize;
          s.Passes = 1;
          TraceResult img = Trace(v, s); // warm-up: program build, upload
          img = Trace(v, s);
          const double ms = img.Seconds * 1e3;
          const double spr = img.Samples / img.Photons;
          std::printf("| %s | %s | %s | %g | %g | %.1f | %.0f | %.3g | %s |\n", c.Name.c_str(),
            ReconstructionName(s.Recon), IntegratorName(m), st, shown, ms, spr, err, flagged ? "yes" : "");
          out << c.Name << "," << IntegratorName(m) << "," << st << "," << shown << "," << ms << "," << spr
              << "," << err << "," << (flagged ? 1 : 0) << "," << ReconstructionName(s.Recon) << ",\n";
          rows.push_back({ std::string(cubic ? "Cubic " : "") + IntegratorName(m), st, shown, ms, err });
        }
    }
    // Integrator Auto at the panel's default tolerance (0: 1 % of the pilot's largest deflection),
    // trilinear and with Reconstruction Auto, against the panel's default setting (Euler 0.5 voxel,
    // trilinear, no octree): whether Auto could be the default. The pilot's time is printed apart
    // (a camera move reuses it); ms/pass is the chosen setting's trace.
    // a copy: rows grows below
    Row panel{ "", 0, 0, 0, -1 };
    for (const Row& r : rows)
      if (r.Method == "Euler" && r.Step == 0.5 && r.Tol == 0.0)
        panel = r;
    // Also at a tenth of that (1e-3 of the known answer's largest deflection): what a tighter
    // default would buy.
    for (const double fraction : { 0.0, 1e-3 })
    for (const Reconstruction asked : { Reconstruction::Trilinear, Reconstruction::Auto })
    {
      Volume v = base;
      if (asked == Reconstruction::Auto)
      {
        v.Field = high.data();
        v.Smooth = smooth.data();
      }
      TraceSettings s = c.S;
      s.Device = ParseBackend(backend);
      s.Method = Integrator::Auto;
      s.Tolerance = fraction * c.Magnitude;
      s.Recon = asked;
      AutoChoice choice;
      const auto p0 = std::chrono::steady_clock::now();
      const TraceSettings chosen = ResolveAuto(v, s, &choice);
      const double pilotMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - p0).count();
      const std::vector<RayRecord> r = TraceRays(v, chosen, c.AB);
      const double err = std::min(c.Error(r) / c.Magnitude, 1e3);
      TraceSettings f = chosen;
      f.Resolution[0] = f.Resolution[1] = filmSize;
      f.Passes = 1;
      TraceResult img = Trace(v, f);
      img = Trace(v, f);
      const double ms = img.Seconds * 1e3;
      const double spr = img.Samples / img.Photons;
      const std::string name = std::string("Auto ") + (fraction > 0 ? "1e-3 of max" : "default tol") + " (" +
        IntegratorName(chosen.Method) + (choice.Met ? "" : ", not met") + ")";
      std::printf("| %s | %s -> %s | %s | %g | 0 | %.1f | %.0f | %.3g | pilot %.0f ms |\n", c.Name.c_str(),
        ReconstructionName(asked), ReconstructionName(chosen.Recon), name.c_str(), chosen.StepSize, ms, spr, err,
        pilotMs);
      out << c.Name << (fraction > 0 ? ",Auto 1e-3," : ",Auto,") << chosen.StepSize << ",0," << ms << "," << spr << "," << err << ",0,"
          << ReconstructionName(chosen.Recon) << "," << fraction << "\n";
      // "no worse": within 5 % of the default's error (the runs differ in rounding only below that)
      if (panel.Err >= 0)
        std::printf("\nAuto (%s, %s asked) against the panel's default (Euler 0.5 voxel, trilinear) on %s: error %.3g "
                    "against %.3g (%s), %.1f ms against %.1f ms per pass (%.2fx the time)\n\n",
          fraction > 0 ? "tolerance 1e-3 of the largest deflection" : "default tolerance", ReconstructionName(asked),
          c.Name.c_str(), err, panel.Err,
          err <= panel.Err * 1.05 ? "no worse" : "WORSE", ms, panel.Ms, ms / panel.Ms);
      rows.push_back({ "Auto " + std::string(ReconstructionName(chosen.Recon)), chosen.StepSize, 0.0, ms, err });
    }
    // Auto's line (issue 50): Integrator and Reconstruction Auto at tolerances from 10 % to 1e-5
    // of the known answer's largest deflection, each its chosen setting's time per pass and error:
    // where Auto's choices lie against the sweep (near its Pareto front if the choice is right)
    for (const double fraction : { 1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5 })
    {
      Volume v = base;
      v.Field = high.data();
      v.Smooth = smooth.data();
      TraceSettings s = c.S;
      s.Device = ParseBackend(backend);
      s.Method = Integrator::Auto;
      s.Recon = Reconstruction::Auto;
      s.Tolerance = fraction * c.Magnitude;
      AutoChoice choice;
      const TraceSettings chosen = ResolveAuto(v, s, &choice);
      const double err = std::min(c.Error(TraceRays(v, chosen, c.AB)) / c.Magnitude, 1e3);
      TraceSettings f = chosen;
      f.Resolution[0] = f.Resolution[1] = filmSize;
      f.Passes = 1;
      TraceResult img = Trace(v, f);
      img = Trace(v, f);
      const double ms = img.Seconds * 1e3;
      const double spr = img.Samples / img.Photons;
      std::printf("| %s | Auto -> %s | Auto line, tolerance %g of max (%s%s) | %g | 0 | %.1f | %.0f | %.3g | %s |\n",
        c.Name.c_str(), ReconstructionName(chosen.Recon), fraction, IntegratorName(chosen.Method),
        choice.Met ? "" : choice.AtFloor ? ", at the floor" : ", not met", chosen.StepSize, ms, spr, err,
        err <= fraction ? "" : "over its tolerance");
      out << c.Name << ",Auto line," << chosen.StepSize << ",0," << ms << "," << spr << "," << err << ",0,"
          << ReconstructionName(chosen.Recon) << "," << fraction << "\n";
    }
    // Pareto front: no other setting is both faster and more accurate
    std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.Ms < b.Ms; });
    std::printf("\nPareto front for %s (fastest first):", c.Name.c_str());
    double best = 1e300;
    for (const Row& r : rows)
      if (r.Err < best)
      {
        best = r.Err;
        std::printf(" [%s %g vox, octree %g: %.1f ms, %.2g]", r.Method.c_str(), r.Step, r.Tol, r.Ms, r.Err);
      }
    std::printf("\n\n");
  }
  std::printf("CSV written to %s\n", csv.c_str());
  return 0;
}
