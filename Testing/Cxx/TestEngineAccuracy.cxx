// SPDX-License-Identifier: BSD-3-Clause
// Tracing accuracy: convergence orders, octree on/off, where methods fail (and that the
// tracer says so), line of sight against the curved trace, the step-doubling estimate, and Auto.
// CPU backend throughout: the OpenCL build of the same source is held to it in TestEngineOracles.
// The figures it gave when it was written are in docs/PERFORMANCE.md (accuracy of the tracer).
#include "SchlierenIndexModels.h"
#include "SchlierenOracles.h"

#include <algorithm>
#include <cmath>
#include <sstream>

using namespace schlieren;

namespace
{
using schtest::Beam;
using schtest::kPi;

// Largest landing distance between two sets of records.
double LandingError(const std::vector<RayRecord>& a, const std::vector<RayRecord>& b)
{
  double e = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    e = std::max(e, double(std::hypot(a[k].LandA - b[k].LandA, a[k].LandB - b[k].LandB)));
  return e;
}

unsigned AllFlags(const std::vector<RayRecord>& r)
{
  unsigned f = 0;
  for (const RayRecord& x : r)
    f |= x.Flags;
  return f;
}

// Least-squares slope of log(error) against log(step).
double Order(const std::vector<double>& steps, const std::vector<double>& errors)
{
  double mx = 0, my = 0;
  const std::size_t n = steps.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    mx += std::log(steps[i]) / n;
    my += std::log(errors[i]) / n;
  }
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    sxy += (std::log(steps[i]) - mx) * (std::log(errors[i]) - my);
    sxx += (std::log(steps[i]) - mx) * (std::log(steps[i]) - mx);
  }
  return sxy / sxx;
}

void CheckOrder(const char* scene, schtest::SceneVolume& sv, TraceSettings s,
  const std::vector<float>& ab, Integrator m, const std::vector<double>& steps, double lo, double hi)
{
  s.Method = Integrator::RK4;
  s.StepSize = 1.0 / 32;
  const std::vector<RayRecord> ref = TraceRays(sv.V, s, ab);
  std::vector<double> errs;
  unsigned flags = 0;
  for (double st : steps)
  {
    s.Method = m;
    s.StepSize = st;
    const std::vector<RayRecord> r = TraceRays(sv.V, s, ab);
    errs.push_back(LandingError(r, ref));
    flags |= AllFlags(r);
  }
  const double order = Order(steps, errs);
  std::printf("%s, %s: landing errors", scene, IntegratorName(m));
  for (std::size_t i = 0; i < steps.size(); ++i)
    std::printf(" %.3g (%g vox)", errs[i], steps[i]);
  std::printf(" -> order %.2f\n", order);
  CHECK(flags == 0, std::string(scene) + ": no ray flagged at these steps");
  CHECK(order >= lo && order <= hi,
    std::string(scene) + " " + IntegratorName(m) + ": measured order " + std::to_string(order) +
      " within [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

void TestConvergence()
{
  {
    SceneParameters p;
    p.GradientA = 1.0;
    p.GradientB = 0.2;
    schtest::SceneVolume sv(Scene::LinearGradient, p, 64, 1.0);
    std::vector<float> ab;
    for (int i = -6; i <= 4; ++i)
    {
      ab.push_back(0.3f);
      ab.push_back(0.1f * i);
    }
    TraceSettings s = Beam(1, 0, 0, 0, 1, 0);
    // the closed form (ORACLES): y(x) = y0 + b (x - x0)^2 / (4 C^2), C = n(y0), over x0 = -1 .. 1
    s.Method = Integrator::RK4;
    s.StepSize = 0.25;
    const std::vector<RayRecord> r = TraceRays(sv.V, s, ab);
    double err = 0;
    for (std::size_t k = 0; k < r.size(); ++k)
    {
      const double y0 = ab[2 * k + 1], C2 = 1.0 + 0.2 * y0;
      err = std::max(err, std::fabs(r[k].LandB - (y0 + 0.2 * 4.0 / (4 * C2))));
    }
    std::printf("linear gradient: RK4 landing against the parabola of ORACLES: %.3g\n", err);
    CHECK_NEAR(err, 0.0, 1e-5, "linear medium: the traced ray is the analytic parabola");
    CheckOrder("linear gradient", sv, s, ab, Integrator::Euler, { 4, 2, 1, 0.5 }, 0.9, 1.1);
    CheckOrder("linear gradient", sv, s, ab, Integrator::Midpoint, { 16, 8, 4 }, 1.6, 2.4);
    // Verlet: second order at Euler's one sample a step
    CheckOrder("linear gradient", sv, s, ab, Integrator::Verlet, { 16, 8, 4 }, 1.6, 2.4);
  }
  {
    SceneParameters p;
    p.Radius = 1.0;
    schtest::SceneVolume sv(Scene::LuneburgLens, p, 64, 1.0);
    std::vector<float> ab;
    for (int i = 1; i <= 7; ++i)
    {
      ab.push_back(0.1f * i);
      ab.push_back(0.05f * i);
    }
    TraceSettings s = Beam(1, 0, 0, 0, 0, 1);
    CheckOrder("Luneburg lens", sv, s, ab, Integrator::Euler, { 1, 0.5, 0.25 }, 0.9, 1.1);
    CheckOrder("Luneburg lens", sv, s, ab, Integrator::Midpoint, { 1, 0.5, 0.25 }, 1.8, 2.6);
    CheckOrder("Luneburg lens", sv, s, ab, Integrator::Verlet, { 1, 0.5, 0.25 }, 1.8, 2.6);
  }
}

void TestOctree()
{
  const double A = 1e-4;
  SceneParameters p;
  p.Amplitude = A;
  p.Width = 0.1; // a small sphere in a large, mostly uniform box
  schtest::SceneVolume sv(Scene::GaussianSphere, p, 128, 1.0);
  const double emax = schtest::GaussianMaxDeflection(A);
  TraceSettings s;
  s.Device = Backend::CPU;
  s.Resolution[0] = s.Resolution[1] = 96;
  s.Jitter = false;
  s.CutoffScale = 1000;
  const TraceResult off = Trace(sv.V, s);
  std::vector<unsigned char> levels(sv.V.NumberOfPoints());
  const double tol = 1e-4 * A;
  const double frac = ComputeOctreeLevels(sv.V.Dimensions, sv.N1.data(), tol, levels.data());
  Volume v = sv.V;
  v.Levels = levels.data();
  v.LevelTolerance = tol;
  const TraceResult on = Trace(v, s);
  double d = 0;
  for (std::size_t i = 0; i < on.Deflection.size(); ++i)
    d = std::max(d, double(std::fabs(on.Deflection[i] - off.Deflection[i])));
  std::printf("octree at %.0e: %.1f %% of cells skippable; %.1f samples/ray against %.1f (%.1fx "
              "fewer); deflection differs by %.3g of max eps\n",
    tol, 100 * frac, on.Samples / on.Photons, off.Samples / off.Photons, off.Samples / on.Samples, d / emax);
  CHECK(off.Samples / on.Samples > 10, "the octree takes at least 10x fewer samples here");
  CHECK_NEAR(d / emax, 0.0, 1e-4, "octree on and off give the same deflections within 1e-4 of max eps");
  CHECK(on.UnderresolvedRays == 0, "octree skips are not flagged as jumps over structure");
  // levels are right: a uniform field is one big block, a field with no uniform block has none
  std::vector<float> flat(sv.N1.size(), 3e-4f);
  CHECK(ComputeOctreeLevels(sv.V.Dimensions, flat.data(), 0.0, levels.data(), 7) == 1.0,
    "a uniform field is skippable everywhere");
  CHECK(levels[0] == 7, "a uniform 128^3 field reaches the top level (128-cell blocks)");
  std::vector<float> noise(sv.N1.size());
  for (std::size_t i = 0; i < noise.size(); ++i)
    noise[i] = 1e-4f * static_cast<float>(i % 2);
  CHECK(ComputeOctreeLevels(sv.V.Dimensions, noise.data(), 1e-6, levels.data()) == 0.0,
    "a field that alternates by more than the tolerance has no skippable block");
  // Auto keeps the octree where it skips most of the samples (the small sphere) and drops it where
  // it skips none (a linear gradient: no uniform block), saying so
  ComputeOctreeLevels(sv.V.Dimensions, sv.N1.data(), tol, levels.data());
  s.Method = Integrator::Auto;
  AutoChoice sphere;
  const TraceSettings kept = ResolveAuto(v, s, &sphere);
  std::printf("Auto on the small sphere: %s\n", sphere.Report.c_str());
  CHECK(kept.UseOctree && sphere.OctreeSaving > 0.5,
    "Auto keeps the octree where it skips more than half of the samples");
  SceneParameters lp;
  lp.GradientA = 1.0;
  lp.GradientB = 0.2;
  schtest::SceneVolume lin(Scene::LinearGradient, lp, 64, 1.0);
  std::vector<unsigned char> linLevels(lin.V.NumberOfPoints());
  const auto mm = std::minmax_element(lin.N1.begin(), lin.N1.end());
  const double linTol = 1e-4 * (*mm.second - *mm.first);
  CHECK(ComputeOctreeLevels(lin.V.Dimensions, lin.N1.data(), linTol, linLevels.data()) == 0.0,
    "a linear gradient has no skippable block");
  Volume lv = lin.V;
  lv.Levels = linLevels.data();
  lv.LevelTolerance = linTol;
  AutoChoice gradient;
  const TraceSettings dropped = ResolveAuto(lv, s, &gradient);
  std::printf("Auto on the linear gradient: %s\n", gradient.Report.c_str());
  CHECK(!dropped.UseOctree && gradient.Report.find("octree off") != std::string::npos,
    "Auto drops the octree where it skips nothing, and says so");
}

// Snell across a plane normal shock (two voxels thick) on 128^3: the tangential part of v = n d is
// conserved. Steps longer than the shock are wrong and flagged; steps of a voxel are right.
void TestShock()
{
  schtest::OracleCase c = schtest::ShockCase(128, 2.0);
  for (double st : { 8.0, 4.0, 2.0, 1.0, 0.5 })
  {
    for (Integrator m : { Integrator::Euler, Integrator::Verlet, Integrator::Midpoint, Integrator::RK4 })
    {
      TraceSettings s = c.S;
      s.Method = m;
      s.StepSize = st;
      const std::vector<RayRecord> r = TraceRays(c.SV->V, s, c.AB);
      const double err = c.Error(r) / c.Magnitude;
      const bool flagged = (AllFlags(r) & RayUnderresolved) != 0;
      std::printf("shock, %s at %g voxel: %.1f %% off Snell, %s\n", IntegratorName(m), st, 100 * err,
        flagged ? "flagged" : "not flagged");
      if (st >= 2)
        CHECK(flagged, "a step longer than the shock is flagged (" + std::to_string(st) + " voxel)");
      else
      {
        CHECK(!flagged, "steps of a voxel or less are not flagged");
        CHECK_NEAR(err, 0.0, 0.01, "steps of a voxel or less cross the shock within 1 % of Snell");
      }
      if (st >= 8)
        CHECK(err > 0.14, "a step four times the shock's width is badly wrong (ORACLES: 14-42 %)");
    }
  }
  // the image says so too
  TraceSettings t = c.S;
  t.Resolution[0] = t.Resolution[1] = 32;
  t.StepSize = 8;
  const TraceResult img = Trace(c.SV->V, t);
  CHECK(img.UnderresolvedRays > 0 && img.Warnings.find("longer than a feature") != std::string::npos,
    "the image reports rays that stepped over the shock, and says what to do");
}

// A strong gradient along a tilted beam turns rays back (a mirage); a weak one does not.
// A steep helium/air interface: a plane where the helium mass fraction falls from 1 to 0 over
// about two voxels (tanh), n - 1 from the mixture Gladstone-Dale at the ideal-gas density (the
// engine's index models: 3.25e-5 in helium, 2.72e-4 in air). The beam crosses it at 40 degrees:
// by Snell the tangential part of v = n d is conserved. Long steps are wrong and flagged.
void TestHeliumInterface()
{
  const int n = 96;
  const double h = 2.0 / (n - 1), delta = h;
  schtest::SceneVolume sv(Scene::Uniform, SceneParameters(), n, 1.0);
  auto mixture = [](double f) {
    const Gas he = Gas::Helium;
    const double M = MixtureMolarMass(&he, &f, 1, Gas::Air);
    return MixtureConstant(&he, &f, 1, Gas::Air) * IdealGasDensity(101325.0, 293.15, M);
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double x = -1 + i * h;
        sv.N1[(static_cast<std::size_t>(k) * n + j) * n + i] =
          static_cast<float>(mixture(0.5 * (1 - std::tanh(x / delta))));
      }
  PackField(sv.V.Dimensions, sv.V.Spacing, sv.N1.data(), sv.Field.data());
  const double n1 = 1 + mixture(1.0), n2 = 1 + mixture(0.0);
  const double al = 40 * kPi / 180;
  const double vz = -n1 * std::cos(al), vx = std::sqrt(n2 * n2 - vz * vz);
  const double exact = (vx / n2) * std::cos(al) + (vz / n2) * std::sin(al);
  std::vector<float> ab;
  for (int i = -3; i <= 3; ++i)
  {
    ab.push_back(0.08f * i);
    ab.push_back(0.1f * i);
  }
  for (double st : { 8.0, 4.0, 1.0, 0.5 })
  {
    TraceSettings s = Beam(std::sin(al), 0, -std::cos(al), 0, 1, 0);
    s.Method = Integrator::Midpoint;
    s.StepSize = st;
    const std::vector<RayRecord> r = TraceRays(sv.V, s, ab);
    double err = 0;
    for (const RayRecord& x : r)
      err = std::max(err, std::fabs(x.DeflX - exact) / std::fabs(exact));
    const bool flagged = (AllFlags(r) & RayUnderresolved) != 0;
    std::printf("helium/air interface (n - 1 %.3g | %.3g), Midpoint at %g voxel: %.1f %% off Snell, %s\n",
      n1 - 1, n2 - 1, st, 100 * err, flagged ? "flagged" : "not flagged");
    if (st >= 4)
      CHECK(flagged, "a step longer than the interface is flagged");
    else
    {
      CHECK(!flagged, "steps of a voxel or less are not flagged at the interface");
      CHECK_NEAR(err, 0.0, 0.01, "steps of a voxel or less cross the interface within 1 % of Snell");
    }
    if (st >= 8)
      CHECK(err > 0.1, "an 8-voxel step across a 2-voxel interface is more than 10 % wrong");
  }
}

void TestTurnBackAndGrazing()
{
  // n^2 = a + b y with a = 2.6, b = -2.5: a ray entering the bottom at 15 deg from the vertical has
  // C = n sin 15 deg, turns where n = C (y = 0.90, ORACLES' parabola) and heads back against the beam
  // right after; with b = -0.1 (a = 1.5) n never falls to C and no ray turns
  for (double b : { -2.5, -0.1 })
  {
    SceneParameters p;
    p.GradientA = b < -1 ? 2.6 : 1.5;
    p.GradientB = b;
    schtest::SceneVolume sv(Scene::LinearGradient, p, 64, 1.0);
    const double al = 15 * kPi / 180;
    TraceSettings s = Beam(std::sin(al), std::cos(al), 0, 0, 0, 1);
    s.Resolution[0] = s.Resolution[1] = 48;
    s.StepSize = 0.5;
    s.Method = Integrator::Midpoint;
    const TraceResult r = Trace(sv.V, s);
    std::printf("linear gradient b = %g along a beam at 15 deg: %.0f of %.0f rays turned back or "
                "failed\n", b, r.FailedRays, r.Photons);
    if (b < -0.5)
      CHECK(r.FailedRays > 0 && r.Warnings.find("turned back") != std::string::npos,
        "rays that turn back are detected, dropped and reported");
    else
      CHECK(r.FailedRays == 0, "no ray turns back in the weak gradient");
  }
  // grazing rays along the top face of a box with a gradient that bends them upward leave through
  // the side: flagged, still on the film
  SceneParameters p;
  p.GradientA = 1.0;
  p.GradientB = 0.2;
  schtest::SceneVolume sv(Scene::LinearGradient, p, 64, 1.0);
  TraceSettings s = Beam(0, 0, -1, 0, 1, 0);
  std::vector<float> ab = { 0.0f, 0.999f, 0.0f, 0.0f };
  const std::vector<RayRecord> r = TraceRays(sv.V, s, ab);
  std::printf("grazing ray at y = 0.999: flags %u, path %.3f; central ray: flags %u, path %.3f\n",
    r[0].Flags, r[0].Path, r[1].Flags, r[1].Path);
  CHECK((r[0].Flags & RaySide) != 0, "a grazing ray that leaves through the top face is flagged");
  CHECK((r[1].Flags & RaySide) == 0, "a central ray leaves through the back");
  CHECK((r[0].Flags & (RayMaxSteps | RayTurned | RayNonFinite | RayOffFilm)) == 0,
    "the grazing ray still reaches the film");
  // line of sight steps along the beam even where the gradient tilts v towards the face: a ray
  // 1e-6 below the top face crosses in the central ray's number of steps (aimed along v / n, its
  // steps shrank towards the face and it stopped at the step limit, 10 % of the way through)
  s.Method = Integrator::Straight;
  const std::vector<RayRecord> los = TraceRays(sv.V, s, { 0.0f, 0.999999f, 0.0f, 0.0f });
  std::printf("line of sight, grazing ray at y = 0.999999: flags %u, %g steps (central ray %g)\n",
    los[0].Flags, los[0].Steps, los[1].Steps);
  CHECK(los[0].Flags == 0 && los[0].Steps == los[1].Steps,
    "line of sight: a ray grazing a face crosses like any other");
}

// Line of sight (no bending) against the curved trace.
void TestStraightLine()
{
  {
    const double A = 1e-4;
    SceneParameters p;
    p.Amplitude = A;
    p.Width = 0.25;
    schtest::SceneVolume sv(Scene::GaussianSphere, p, 96, 1.0);
    TraceSettings s = Beam(0, 0, -1, 0, 1, 0);
    std::vector<float> ab;
    for (int i = -10; i <= 10; ++i)
    {
      ab.push_back(0.05f * i);
      ab.push_back(0.02f * i);
    }
    s.Method = Integrator::RK4;
    const std::vector<RayRecord> curved = TraceRays(sv.V, s, ab);
    s.Method = Integrator::Straight;
    const std::vector<RayRecord> straight = TraceRays(sv.V, s, ab);
    double d = 0;
    for (std::size_t k = 0; k < ab.size() / 2; ++k)
      d = std::max(d, double(std::hypot(curved[k].DeflX - straight[k].DeflX, curved[k].DeflY - straight[k].DeflY)));
    const double emax = schtest::GaussianMaxDeflection(A);
    std::printf("weak Gaussian (A = 1e-4): line of sight differs from the curved trace by %.3g of max eps\n", d / emax);
    CHECK_NEAR(d / emax, 0.0, 2e-3, "line of sight is the weak-field limit of the curved trace");
  }
  {
    SceneParameters p;
    p.Radius = 1;
    schtest::SceneVolume sv(Scene::LuneburgLens, p, 64, 1.0);
    TraceSettings s = Beam(1, 0, 0, 0, 0, 1);
    std::vector<float> ab;
    for (int i = 1; i <= 7; ++i)
    {
      ab.push_back(0.1f * i);
      ab.push_back(0.0f);
    }
    s.Method = Integrator::Midpoint;
    const std::vector<RayRecord> curved = TraceRays(sv.V, s, ab);
    s.Method = Integrator::Straight;
    const std::vector<RayRecord> straight = TraceRays(sv.V, s, ab);
    double land = 0, dir = 0;
    for (std::size_t k = 0; k < curved.size(); ++k)
    {
      land = std::max(land, double(std::hypot(curved[k].LandA - straight[k].LandA, curved[k].LandB - straight[k].LandB)));
      dir = std::max(dir, double(std::fabs(curved[k].DeflX - straight[k].DeflX)));
    }
    std::printf("Luneburg lens: line of sight lands up to %.3f R from the curved trace, its direction "
                "off by up to %.3f\n", land, dir);
    // measured: landing up to 0.095 R off, exit direction up to 0.115 rad off (for h = 0.7 R the
    // deflection is 0.7 rad): the weak-field approximation fails in strong refraction
    CHECK(dir > 0.05 && land > 0.05, "line of sight departs from the curved trace in the Luneburg lens");
  }
}

// The step-doubling estimate tracks the real error of Euler steps.
void TestErrorEstimate()
{
  SceneParameters p;
  p.Radius = 1;
  schtest::SceneVolume sv(Scene::LuneburgLens, p, 64, 1.0);
  TraceSettings s = Beam(1, 0, 0, 0, 0, 1);
  std::vector<float> ab;
  for (int i = 1; i <= 6; ++i)
  {
    ab.push_back(0.1f * i);
    ab.push_back(0.05f * i);
  }
  s.Method = Integrator::RK4;
  s.StepSize = 1.0 / 32;
  const std::vector<RayRecord> ref = TraceRays(sv.V, s, ab);
  s.Method = Integrator::Euler;
  s.StepSize = 0.5;
  s.EstimateError = true;
  const std::vector<RayRecord> r = TraceRays(sv.V, s, ab);
  double worst = 0, best = 1e9;
  for (std::size_t k = 0; k < r.size(); ++k)
  {
    const double real = std::hypot(r[k].DeflX - ref[k].DeflX, r[k].DeflY - ref[k].DeflY);
    const double ratio = r[k].Error / real;
    worst = std::max(worst, ratio);
    best = std::min(best, ratio);
  }
  std::printf("Euler at 0.5 voxel on the Luneburg lens: estimate / real error in [%.2f, %.2f]\n", best, worst);
  CHECK(best > 0.5 && worst < 2.0, "the step-doubling estimate is within a factor 2 of the real error");
}

// Auto meets its tolerance against the known answers, at no more cost than the cheapest fixed
// setting that also does. Each scene is judged on Auto's own pilot rays, over the whole film, so
// that both sides answer for the same rays. (The normal shock is not among them: its known answer
// fails within a few voxels of the box's faces, where the data's one-sided differences, not the
// tracer, set the error; TestShock covers it.)
void TestAuto()
{
  // every case is judged on Auto's own pilot rays (16 x 16 over the film), against the known answer
  std::vector<schtest::OracleCase> cases = { schtest::GaussianCase(96), schtest::LuneburgCase(96),
    schtest::LinearCase(96) };
  for (schtest::OracleCase& c : cases)
  {
    TraceSettings s = c.S;
    s.Method = Integrator::Auto;
    s.Tolerance = c.Tolerance;
    AutoChoice choice;
    const TraceSettings chosen = ResolveAuto(c.SV->V, s, &choice);
    std::printf("%s: %s\n", c.Name.c_str(), choice.Report.c_str());
    const std::vector<RayRecord> r = TraceRays(c.SV->V, chosen, c.AB);
    const double err = c.Error(r);
    const double samples = schtest::SampleCount(r);
    // the cheapest fixed setting that meets the tolerance against the known answer
    double cheapest = 1e300;
    std::string cheapestName = "none";
    for (Integrator m : { Integrator::Straight, Integrator::Euler, Integrator::Verlet, Integrator::Midpoint,
           Integrator::RK4 })
      for (double st : { 8.0, 4.0, 2.0, 1.0, 0.5, 0.25 })
      {
        TraceSettings t = c.S;
        t.Method = m;
        t.StepSize = st;
        const std::vector<RayRecord> q = TraceRays(c.SV->V, t, c.AB);
        const double qs = schtest::SampleCount(q);
        if (c.Error(q) <= c.Tolerance && qs < cheapest)
        {
          cheapest = qs;
          cheapestName = std::string(IntegratorName(m)) + " at " + std::to_string(st);
        }
      }
    std::printf("%s: Auto's error against the known answer %.3g (tolerance %.3g), %.0f samples; the "
                "cheapest fixed setting that meets it: %s, %.0f samples\n",
      c.Name.c_str(), err, c.Tolerance, samples, cheapestName.c_str(), cheapest);
    CHECK(choice.Met, c.Name + ": Auto found a setting");
    CHECK_NEAR(err, 0.0, c.Tolerance, c.Name + ": Auto meets its tolerance against the known answer");
    // within issue 50's 1.5 x: since the pilot's rays left the centres of its pattern (which lay
    // on grid lines of 32 k + 1 point grids) the Luneburg lens's pilot meets rays nearer its rim
    // and takes Verlet at 1.41 voxel where 2 meets on these rays (19114 samples against 13626)
    CHECK(samples <= 1.5 * cheapest, c.Name + ": Auto costs at most 1.5 x the cheapest fixed setting that meets the tolerance");
  }
}
} // namespace

// Auto on oblique views, and where the tolerance is below what the pilot can measure. The walk
// keeps a ray's position as entry + along d0 + dev, so that seen obliquely a position is not
// rounded anew at every step across the beam: the pilot's reference (RK4 at 1/8 voxel, over a
// thousand steps) must then differ from itself at 1/4 voxel by no more than on axis, the floor
// must be about the axis view's, and the sphere, which looks the same from every side, must cost
// what the axis view costs at the tolerances users ask for. A tolerance below the floor must still
// be reported with the floor, and the estimate must hold against the closed form on rays the
// pilot did not trace.
void TestAutoFloor()
{
  const double A = 2e-4, w = 0.25;
  SceneParameters p;
  p.Amplitude = A;
  p.Width = w;
  // a box of +-4 s: the field at its faces (e^-16) leaves the closed form exact for every view
  schtest::SceneVolume sv(Scene::GaussianSphere, p, 128, 1.0);
  std::vector<unsigned char> smooth(sv.N1.size());
  PackFieldHighOrder(sv.V.Dimensions, sv.V.Spacing, sv.N1.data(), sv.Field.data(), smooth.data());
  sv.V.Smooth = smooth.data();
  // rays off the pilot's 16 x 16 grid, within the sphere's deflection
  std::vector<float> ab;
  for (int j = -15; j <= 15; ++j)
    for (int i = -15; i <= 15; ++i)
    {
      ab.push_back(static_cast<float>(0.041 * i + 0.003));
      ab.push_back(static_cast<float>(0.041 * j - 0.002));
    }
  auto closedError = [&](const std::vector<RayRecord>& r) {
    double e = 0;
    for (std::size_t k = 0; k < r.size(); ++k)
    {
      double g[2];
      schtest::GaussianDeflection(A, w, ab[2 * k], ab[2 * k + 1], g);
      e = std::max(e, std::hypot(r[k].DeflX - g[0], r[k].DeflY - g[1]));
    }
    return e;
  };
  const double views[3][6] = { { 0, 0, -1, 0, 1, 0 }, { 1, 0.7, -0.4, 0, 0, 1 }, { 0.3, 0, -1, 0, 1, 0 } };
  const char* names[3] = { "axis", "oblique (1, 0.7, -0.4)", "oblique (0.3, 0, -1)" };
  auto settings = [&](int v, double tol) {
    TraceSettings s = Beam(views[v][0], views[v][1], views[v][2], views[v][3], views[v][4], views[v][5]);
    s.Resolution[0] = s.Resolution[1] = 256;
    s.Passes = 1;
    s.Method = Integrator::Auto;
    s.Recon = Reconstruction::Cubic;
    s.Tolerance = tol;
    return s;
  };
  double eRef[3];
  for (int v = 0; v < 3; ++v)
  {
    TraceSettings ref = settings(v, 0);
    ref.Method = Integrator::RK4;
    ref.StepSize = 0.125;
    eRef[v] = closedError(TraceRays(sv.V, ref, ab));
    std::printf("%s: the pilot's reference (RK4 at 1/8 voxel) against the closed form %.3g rad\n",
      names[v], eRef[v]);
    // the reference the estimate is measured against is as right seen obliquely as on axis
    if (v > 0)
      CHECK(eRef[v] <= 1.5 * eRef[0], std::string(names[v]) + ": the reference holds to the closed form as on axis");
  }
  // the tolerances users ask for: every view's choice meets it, and the oblique views cost no
  // more samples per ray than the axis view (within 1.5 x). Not 1e-8 rad (asked here before
  // issue 50's reference check): on this 128^3 grid the tricubic data itself is about 1e-8 rad
  // off the exact ray (engine.TestEngineAutoStep: the smallest error of any swept setting 1.04e-8
  // on axis; the pilot's estimate of its reference's error 6.2e-9 on axis, 7.6e-9 and 1.1e-8
  // seen obliquely), and Auto now reports it below the floor
  for (double tol : { 3e-8, 2e-8 })
  {
    double sprAxis = 0;
    for (int v = 0; v < 3; ++v)
    {
      TraceSettings s = settings(v, tol);
      AutoChoice c;
      const TraceSettings chosen = ResolveAuto(sv.V, s, &c);
      const double eChosen = closedError(TraceRays(sv.V, chosen, ab));
      std::printf("Auto at %.3g rad, %s: %s at %g voxel, %.1f samples per ray, estimate %.3g, floor "
                  "%.3g%s; against the closed form: chosen %.3g, reference %.3g rad\n",
        tol, names[v], IntegratorName(c.Method), c.StepSize, c.SamplesPerRay, c.ExpectedError,
        c.Floor, c.AtFloor ? " (at the floor)" : "", eChosen, eRef[v]);
      CHECK(c.Met && !c.AtFloor && c.Floor < tol,
        std::string(names[v]) + ": the floor is below the tolerance, which is met");
      if (v == 0)
        sprAxis = c.SamplesPerRay;
      else
        CHECK(c.SamplesPerRay <= 1.5 * sprAxis,
          std::string(names[v]) + ": Auto's choice costs no more than 1.5 x the axis view's samples per ray");
      // the estimate carries over to rays the pilot did not trace: the chosen setting is off the
      // closed form by at most the reference's own error (the grid's) and twice what was applied
      CHECK(eChosen <= eRef[v] + 2 * std::max(tol, c.Floor),
        std::string(names[v]) + ": the chosen setting against the closed form within its estimate");
    }
  }
  // a tolerance below every view's floor: the floor is reported, named in a warning, and seen
  // obliquely it is about the axis view's (float rounding no longer summed across the beam)
  const double tiny = 1e-12;
  double floorAxis = 0;
  for (int v = 0; v < 3; ++v)
  {
    TraceSettings s = settings(v, tiny);
    AutoChoice c;
    const TraceSettings chosen = ResolveAuto(sv.V, s, &c);
    const double eChosen = closedError(TraceRays(sv.V, chosen, ab));
    std::printf("Auto at %.3g rad, %s: %s at %g voxel, %.1f samples per ray, floor %.3g%s; against "
                "the closed form %.3g rad; %s\n",
      tiny, names[v], IntegratorName(c.Method), c.StepSize, c.SamplesPerRay, c.Floor,
      c.AtFloor ? " (at the floor)" : "", eChosen, c.Report.c_str());
    CHECK(c.AtFloor && !c.Met && c.Floor > tiny, std::string(names[v]) + ": the tolerance is below the floor, and reported so");
    std::ostringstream floorText;
    floorText << "a floor of " << c.Floor << " rad";
    CHECK(c.Report.find("below what this volume allows") != std::string::npos &&
        c.Report.find(floorText.str()) != std::string::npos,
      std::string(names[v]) + ": the report names the floor in radians: " + c.Report);
    if (v == 0)
      floorAxis = c.Floor;
    else
      CHECK(c.Floor <= 3 * floorAxis,
        std::string(names[v]) + ": the floor seen obliquely is within 3 x the axis view's");
    if (v == 1)
    {
      const TraceResult r = Trace(sv.V, s);
      CHECK(r.Warnings.find(floorText.str()) != std::string::npos, "oblique: a warning names the floor");
      CHECK(r.Choice.AtFloor && r.Choice.Floor == c.Floor, "oblique: the result's choice is at the floor");
      // at a tolerance above the floor the tolerance is met as asked
      s.Tolerance = 2 * c.Floor;
      AutoChoice above;
      ResolveAuto(sv.V, s, &above);
      CHECK(above.Met && !above.AtFloor, "oblique: a tolerance above the floor is met");
    }
  }
}

int main()
{
  TestConvergence();
  TestOctree();
  TestShock();
  TestHeliumInterface();
  TestTurnBackAndGrazing();
  TestStraightLine();
  TestErrorEstimate();
  TestAuto();
  TestAutoFloor();
  return schtest::Finish();
}
