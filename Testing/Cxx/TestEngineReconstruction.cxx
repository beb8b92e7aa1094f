// SPDX-License-Identifier: BSD-3-Clause
// The fourth-order reconstruction (Reconstruction Cubic, PackFieldHighOrder) against known answers:
//  - the packing (bit rows, threads) against a plain transcription of its steps, a byte per point:
//    the same smoothness bytes, packed field and smooth fraction, bit for bit;
//  - its order on the weak Gaussian sphere n = 1 + A exp(-r^2/s^2), A = 2e-4, s = 0.25 on
//    [-1, 1]^3, beam along z, rays through the centres of a 64^2 film's pixels with |x|, |y| <
//    2.2 s: the RMS deflection error against ORACLES' closed form, as a fraction of its peak, at
//    64^3, 128^3 and 256^3. Line of sight isolates the reconstruction (the closed form is the
//    straight-line integral, exact to its O(A) bending term, which line of sight leaves out);
//    RK4 is checked beside it at 128^3 against the same bound plus that term; the optical path
//    (phase) against P = sqrt(pi) A s exp(-rho^2 / s^2) is ten times closer than trilinear's;
//  - the smoothness switch at a shock: the normal shock seen edge-on (beam along its plane) gives
//    the same jump in the index, the same position and the same peak of the deflection as trilinear,
//    and no more overshoot; at 40 degrees it obeys Snell as the trilinear scheme does, for every
//    StepSize (steps from cells that are not smooth are at most a voxel, so none jumps the shock);
//  - a feature the smoothness test passes (a shock eight voxels wide) but a long step jumps is
//    still flagged;
//  - field-sized steps: samples per ray on the Gaussian at a fixed step in world units do not grow
//    with the grid;
//  - the OpenCL kernels (per item and lock step) trace the same rays as the CPU build;
//  - Reconstruction Auto: cubic where the trilinear's error is above the tolerance, trilinear where
//    it is far below, and the tolerance met against the closed form.
#include "SchlierenOracles.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <initializer_list>

using namespace schlieren;

namespace
{
using schtest::Beam;
using schtest::kPi;

const double kA = 2e-4, kS = 0.25;

// A scene packed for Reconstruction Cubic (and its smoothness bytes).
struct CubicVolume
{
  std::vector<float> N1, Field;
  std::vector<unsigned char> Smooth;
  Volume V;
  double SmoothFraction = 0;
  CubicVolume(Scene scene, const SceneParameters& p, int n)
  {
    for (int a = 0; a < 3; ++a)
    {
      V.Dimensions[a] = n;
      V.Origin[a] = -1;
      V.Spacing[a] = 2.0 / (n - 1);
    }
    N1.resize(V.NumberOfPoints());
    Field.resize(4 * N1.size());
    Smooth.resize(N1.size());
    FillScene(scene, p, V.Dimensions, V.Origin, V.Spacing, N1.data(), nullptr);
    SmoothFraction = PackFieldHighOrder(V.Dimensions, V.Spacing, N1.data(), Field.data(), Smooth.data());
    V.Field = Field.data();
    V.Smooth = Smooth.data();
  }
};

SceneParameters GaussianParameters()
{
  SceneParameters p;
  p.Amplitude = kA;
  p.Width = kS;
  return p;
}

// The centres of a 64^2 film's pixels over the box, within |x|, |y| < 2.2 s.
std::vector<float> CentreRays()
{
  std::vector<float> ab;
  const int np = 64;
  const double pix = 2.0 / np;
  for (int j = 0; j < np; ++j)
    for (int i = 0; i < np; ++i)
    {
      const double a = -1 + (i + 0.5) * pix, b = -1 + (j + 0.5) * pix;
      if (std::fabs(a) < 2.2 * kS && std::fabs(b) < 2.2 * kS)
      {
        ab.push_back(static_cast<float>(a));
        ab.push_back(static_cast<float>(b));
      }
    }
  return ab;
}

// RMS deflection error against the closed form, as a fraction of its peak.
double GaussianRms(const std::vector<RayRecord>& r, const std::vector<float>& ab)
{
  double sum = 0;
  for (std::size_t k = 0; k < r.size(); ++k)
  {
    double e[2];
    schtest::GaussianDeflection(kA, kS, ab[2 * k], ab[2 * k + 1], e);
    sum += (r[k].DeflX - e[0]) * (r[k].DeflX - e[0]) + (r[k].DeflY - e[1]) * (r[k].DeflY - e[1]);
  }
  return std::sqrt(sum / r.size()) / schtest::GaussianMaxDeflection(kA);
}

// RMS error of the optical path (the phase, for interferometry) against the closed form
// P = sqrt(pi) A s exp(-rho^2 / s^2), as a fraction of its peak sqrt(pi) A s.
double PhaseRms(const std::vector<RayRecord>& r, const std::vector<float>& ab)
{
  const double peak = std::sqrt(kPi) * kA * kS;
  double sum = 0;
  for (std::size_t k = 0; k < r.size(); ++k)
  {
    const double rho2 = double(ab[2 * k]) * ab[2 * k] + double(ab[2 * k + 1]) * ab[2 * k + 1];
    const double e = r[k].OpticalPathExcess - peak * std::exp(-rho2 / (kS * kS));
    sum += e * e;
  }
  return std::sqrt(sum / r.size()) / peak;
}

double Slope(const std::vector<double>& x, const std::vector<double>& y)
{
  double mx = 0, my = 0;
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    mx += std::log(x[i]) / n;
    my += std::log(y[i]) / n;
  }
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return sxy / sxx;
}

unsigned AllFlags(const std::vector<RayRecord>& r)
{
  unsigned f = 0;
  for (const RayRecord& x : r)
    f |= x.Flags;
  return f;
}

void TestOrder()
{
  const std::vector<float> ab = CentreRays();
  std::vector<double> hs, cubic, tri, phaseTri, phaseCubic;
  double samples128 = 0, samples256 = 0;
  for (int n : { 64, 128, 256 })
  {
    CubicVolume cv(Scene::GaussianSphere, GaussianParameters(), n);
    TraceSettings s = Beam(0, 0, -1, 0, 1, 0);
    s.Method = Integrator::Straight;
    s.StepSize = 1.0;
    s.Recon = Reconstruction::Trilinear;
    // the present scheme: PackField's central differences, trilinear
    Volume present = cv.V;
    std::vector<float> packed(cv.Field.size());
    PackField(cv.V.Dimensions, cv.V.Spacing, cv.N1.data(), packed.data());
    present.Field = packed.data();
    present.Smooth = nullptr;
    const std::vector<RayRecord> rt = TraceRays(present, s, ab);
    const double et = GaussianRms(rt, ab);
    s.Recon = Reconstruction::Cubic;
    const std::vector<RayRecord> rc = TraceRays(cv.V, s, ab);
    const double ec = GaussianRms(rc, ab);
    // a step fixed in world units (1/16 of the box: 4 s / 8), given in voxels of this grid
    s.StepSize = (n - 1) / 32.0;
    const std::vector<RayRecord> rl = TraceRays(cv.V, s, ab);
    const double el = GaussianRms(rl, ab);
    const double spr = schtest::SampleCount(rl) / rl.size();
    const double pt = PhaseRms(rt, ab), pc = PhaseRms(rc, ab);
    std::printf("  optical path (phase), RMS of its peak: trilinear %.5f %%, cubic %.6f %%\n", 100 * pt, 100 * pc);
    phaseTri.push_back(pt);
    phaseCubic.push_back(pc);
    std::printf("Gaussian A = 2e-4 at %d^3 (%.1f %% of cells smooth): RMS deflection error of peak, "
                "line of sight at 1 voxel: trilinear %.4f %%, cubic %.5f %%; cubic at 1/32 of the box "
                "(%.1f voxels) %.5f %%, %.1f samples per ray\n",
      n, 100 * cv.SmoothFraction, 100 * et, 100 * ec, s.StepSize, 100 * el, spr);
    CHECK((AllFlags(rc) & RayUnderresolved) == 0, "no ray flagged on the smooth Gaussian");
    hs.push_back(2.0 / (n - 1));
    cubic.push_back(ec);
    tri.push_back(et);
    if (n == 64)
      CHECK(ec <= 1e-3, "64^3: cubic RMS error <= 0.1 % of peak");
    if (n == 128)
    {
      CHECK(ec <= 2e-4, "128^3: cubic RMS error <= 0.02 % of peak (ten times below the best peer's 0.22 %)");
      CHECK_NEAR(el, ec, 0.2 * ec + 2e-6, "128^3: the field-sized step is as accurate as steps of a voxel");
      samples128 = spr;
      // the bent ray (RK4) sees the closed form's O(A) term on top
      TraceSettings r = s;
      r.Method = Integrator::RK4;
      r.StepSize = 1.0;
      const double er = GaussianRms(TraceRays(cv.V, r, ab), ab);
      std::printf("128^3: cubic, RK4 at 1 voxel: %.5f %% (the closed form holds to O(A) = %.3f %%)\n",
        100 * er, 100 * 1.4 * kA);
      CHECK(er <= 2e-4 + 1.4 * kA, "128^3: RK4 with cubic within 0.02 % plus the closed form's O(A)");
    }
    if (n == 256)
      samples256 = spr;
  }
  // the optical path of n - 1 itself (the phase): far closer with the tricubic n - 1, though not
  // at a clean fourth order over these grids
  const double phaseOrder = std::log(phaseCubic[0] / phaseCubic[1]) / std::log(hs[0] / hs[1]);
  std::printf("optical path: cubic order %.2f over 64 -> 128, %.2f over 128 -> 256\n", phaseOrder,
    std::log(phaseCubic[1] / phaseCubic[2]) / std::log(hs[1] / hs[2]));
  CHECK(phaseCubic[0] <= 0.1 * phaseTri[0] && phaseCubic[1] <= 0.1 * phaseTri[1],
    "64^3 and 128^3: the cubic optical path is ten times closer to the closed form than the trilinear one");
  const double order = Slope(hs, cubic), orderTri = Slope(hs, tri);
  std::printf("measured order: cubic %.2f, trilinear %.2f\n", order, orderTri);
  CHECK(order >= 3.5 && order <= 4.8, "the cubic reconstruction converges at fourth order");
  // (64^3, at eight voxels per width s, is not yet in the asymptotic range of the second order)
  CHECK(orderTri >= 1.5 && orderTri <= 2.3, "the present scheme converges at second order");
  CHECK(samples256 <= 1.3 * samples128,
    "steps sized by the field: samples per ray at 256^3 within 1.3x of 128^3 at the same world step");
}

// The normal shock (Mach 2, tanh profile) seen edge-on: beam along z in the shock plane x = 0. A
// row of rays across it gives the deflection peak and, integrated across x, the index step.
struct Profile
{
  double Jump = 0, Peak = 0, PeakX = 0, Under = 0, Over = 0;
};

Profile ShockProfile(const Volume& v, Reconstruction rc, int n)
{
  TraceSettings s = Beam(0, 0, -1, 0, 1, 0);
  s.Method = Integrator::Straight;
  s.StepSize = 0.5;
  s.Recon = rc;
  std::vector<float> ab;
  const double h = 2.0 / (n - 1);
  for (int i = -120; i <= 120; ++i)
  {
    ab.push_back(static_cast<float>(0.05 * h * i + 0.013 * h));
    ab.push_back(0.1f);
  }
  const std::vector<RayRecord> r = TraceRays(v, s, ab);
  // the deflection is the path (2) times dn/dx: its running integral across x is the index
  // profile (times 2), whose plateaus give the jump and whose excursions beyond them the overshoot
  Profile p;
  std::vector<double> cum(r.size(), 0.0);
  for (std::size_t k = 1; k < r.size(); ++k)
    cum[k] = cum[k - 1] + 0.5 * (r[k].DeflX + r[k - 1].DeflX) * (ab[2 * k] - ab[2 * k - 2]);
  p.Jump = cum.back();
  for (std::size_t k = 0; k < r.size(); ++k)
  {
    const double d = r[k].DeflX;
    if (std::fabs(d) > std::fabs(p.Peak))
    {
      p.Peak = d;
      p.PeakX = ab[2 * k];
    }
    const double sg = p.Jump > 0 ? 1.0 : -1.0;
    p.Over = std::max(p.Over, std::max(sg * (cum[k] - p.Jump), -sg * cum[k]));
  }
  for (const RayRecord& x : r)
    p.Under = std::max(p.Under, -double(x.DeflX) * (p.Peak > 0 ? 1 : -1));
  return p;
}

void TestShock()
{
  const int n = 96;
  for (double thickness : { 1.0, 2.0 })
  {
    SceneParameters ps;
    ps.Mach = 2;
    ps.Density = 1.2;
    ps.Width = 0.5 * thickness * 2.0 / (n - 1);
    CubicVolume cv(Scene::NormalShock, ps, n);
    const Profile t = ShockProfile(cv.V, Reconstruction::Trilinear, n);
    const Profile c = ShockProfile(cv.V, Reconstruction::Cubic, n);
    const double h = 2.0 / (n - 1);
    std::printf("normal shock %.0f voxel(s) thick, edge-on: index jump x 2 %.6g / %.6g (trilinear / "
                "cubic), deflection peak %.6g / %.6g at x = %.4f / %.4f, undershoot %.3g / %.3g of the "
                "peak, index overshoot %.3g / %.3g of the jump\n",
      2 * thickness, t.Jump, c.Jump, t.Peak, c.Peak, t.PeakX, c.PeakX, t.Under / std::fabs(t.Peak),
      c.Under / std::fabs(c.Peak), t.Over / std::fabs(t.Jump), c.Over / std::fabs(c.Jump));
    CHECK_NEAR(c.Jump, t.Jump, 1e-3 * std::fabs(t.Jump), "shock: the same jump in the index (0.1 %)");
    CHECK_NEAR(c.PeakX, t.PeakX, 0.1 * h, "shock: the deflection peaks at the same place (0.1 voxel)");
    CHECK_NEAR(c.Peak, t.Peak, 0.01 * std::fabs(t.Peak), "shock: the same peak deflection (1 %)");
    CHECK(c.Under <= t.Under + 0.005 * std::fabs(t.Peak),
      "shock: no new undershoot of the deflection (0.5 % of its peak)");
    CHECK(c.Over <= t.Over + 0.005 * std::fabs(t.Jump),
      "shock: no new overshoot of the index (0.5 % of the jump)");
  }
  // Snell at 40 degrees (ORACLES' case, 2 voxels thick on 128^3), every StepSize: the steps from
  // cells near the shock are a voxel at most, so none jumps it, and none is flagged
  schtest::OracleCase oc = schtest::ShockCase(128, 2.0);
  std::vector<unsigned char> smooth(oc.SV->N1.size());
  PackFieldHighOrder(oc.SV->V.Dimensions, oc.SV->V.Spacing, oc.SV->N1.data(), oc.SV->Field.data(), smooth.data());
  Volume v = oc.SV->V;
  v.Smooth = smooth.data();
  for (double st : { 16.0, 8.0, 2.0, 1.0 })
    for (Integrator m : { Integrator::Euler, Integrator::Verlet, Integrator::Midpoint })
    {
      TraceSettings s = oc.S;
      s.Method = m;
      s.StepSize = st;
      s.Recon = Reconstruction::Cubic;
      const std::vector<RayRecord> r = TraceRays(v, s, oc.AB);
      const double err = oc.Error(r) / oc.Magnitude;
      const bool flagged = (AllFlags(r) & RayUnderresolved) != 0;
      std::printf("shock at 40 deg, cubic, %s at %g voxel: %.2f %% off Snell, %s, %.1f samples per ray\n",
        IntegratorName(m), st, 100 * err, flagged ? "flagged" : "not flagged", schtest::SampleCount(r) / r.size());
      CHECK(err <= 0.01, "cubic: every StepSize crosses the shock within 1 % of Snell");
      CHECK(!flagged, "cubic: no step jumps the shock");
    }
  // a shock eight voxels wide passes the smoothness test (cubic there): a 32-voxel step jumps it,
  // and is flagged, as trilinear's long steps are
  {
    SceneParameters ps;
    ps.Mach = 2;
    ps.Density = 1.2;
    ps.Width = 4.0 * 2.0 / (128 - 1);
    CubicVolume cv(Scene::NormalShock, ps, 128);
    const double al = 40 * kPi / 180;
    TraceSettings s = Beam(std::sin(al), 0, -std::cos(al), 0, 1, 0);
    s.Method = Integrator::Euler;
    s.StepSize = 32;
    s.Recon = Reconstruction::Cubic;
    std::vector<float> ab;
    for (int i = -4; i <= 4; ++i)
      ab.insert(ab.end(), { 0.1f * i, 0.05f * i });
    const std::vector<RayRecord> r = TraceRays(cv.V, s, ab);
    std::printf("shock 8 voxels wide (%.1f %% of cells smooth), cubic, Euler at 32 voxels: %s\n",
      100 * cv.SmoothFraction, (AllFlags(r) & RayUnderresolved) ? "flagged" : "not flagged");
    // (the cells within three of the faces are never smooth: 11 % of a 128^3 grid)
    CHECK(cv.SmoothFraction > 0.85, "a shock 8 voxels wide is smooth to the test");
    CHECK((AllFlags(r) & RayUnderresolved) != 0, "a long step over it is flagged");
  }
}

// The same source on both backends: OpenCL (lock step and per item) against the CPU build.
void TestBackends()
{
  if (!schtest::HaveOpenCL())
    return;
  SceneParameters p = GaussianParameters();
  CubicVolume cv(Scene::GaussianSphere, p, 48);
  for (Integrator m : { Integrator::Straight, Integrator::Euler, Integrator::RK4 })
    for (double st : { 0.5, 8.0 })
    {
      TraceSettings s;
      s.Method = m;
      s.StepSize = st;
      s.Recon = Reconstruction::Cubic;
      s.Resolution[0] = 40;
      s.Resolution[1] = 32;
      s.CutoffScale = 1000;
      s.Device = Backend::CPU;
      const TraceResult cpu = Trace(cv.V, s);
      s.Device = Backend::OpenCL;
      double diff[2] = { 0, 0 };
      double samples[2] = { 0, 0 };
      for (int lock = 0; lock < 2; ++lock)
      {
        const schtest::ScopedOptions kernel([lock](RuntimeOptions& o) { o.Lockstep = lock; });
        const TraceResult cl = Trace(cv.V, s);
        for (std::size_t i = 0; i < cl.Deflection.size(); ++i)
          diff[lock] = std::max(diff[lock], double(std::fabs(cl.Deflection[i] - cpu.Deflection[i])));
        samples[lock] = cl.Samples;
      }
      const double emax = schtest::GaussianMaxDeflection(kA);
      std::printf("cubic, %s at %g voxel: OpenCL per item / lock step against the CPU: %.3g / %.3g of "
                  "max eps; samples %.0f / %.0f / %.0f\n",
        IntegratorName(m), st, diff[0] / emax, diff[1] / emax, samples[0], samples[1], cpu.Samples);
      CHECK(diff[0] == diff[1] && samples[0] == samples[1],
        "cubic: the lock-step and per-item kernels trace the same rays, bit for bit");
      // (rounding may put a step's end in another cell, whose smoothness allows another step:
      // a few samples of a pass differ)
      CHECK(diff[0] <= 1e-5 * emax && std::fabs(samples[0] - cpu.Samples) <= 1e-3 * cpu.Samples,
        "cubic: OpenCL and the CPU build of the same source agree (1e-5 of max eps, samples 0.1 %)");
    }
}

// Reconstruction Auto with Integrator Auto, judged against the closed form on its own pilot rays.
void TestAuto()
{
  for (int n : { 64, 128 })
  {
    CubicVolume cv(Scene::GaussianSphere, GaussianParameters(), n);
    const double emax = schtest::GaussianMaxDeflection(kA);
    for (double tolFrac : { 1e-3, 3e-2 })
    {
      TraceSettings s = Beam(0, 0, -1, 0, 1, 0);
      s.Resolution[0] = s.Resolution[1] = 64;
      s.Method = Integrator::Auto;
      s.Recon = Reconstruction::Auto;
      s.Tolerance = tolFrac * emax;
      AutoChoice choice;
      const TraceSettings chosen = ResolveAuto(cv.V, s, &choice);
      const std::vector<float> ab = PilotRays(cv.V, s);
      const std::vector<RayRecord> r = TraceRays(cv.V, chosen, ab);
      double err = 0;
      for (std::size_t k = 0; k < r.size(); ++k)
      {
        double e[2];
        schtest::GaussianDeflection(kA, kS, ab[2 * k], ab[2 * k + 1], e);
        err = std::max(err, std::hypot(r[k].DeflX - e[0], r[k].DeflY - e[1]));
      }
      std::printf("%d^3, tolerance %.3g of max eps: %s; error against the closed form %.3g of max eps\n",
        n, tolFrac, choice.Report.c_str(), err / emax);
      CHECK(choice.Met, "Auto found a setting");
      CHECK(err <= s.Tolerance, "Auto meets its tolerance against the closed form");
      if (n == 64 && tolFrac < 0.01)
        CHECK(chosen.Recon == Reconstruction::Cubic,
          "Auto takes the cubic reconstruction where the trilinear's own error is above the tolerance");
    }
  }
  // no smoothness bytes (PackField): Auto stays trilinear
  schtest::SceneVolume plain(Scene::GaussianSphere, GaussianParameters(), 48, 1.0);
  TraceSettings s = Beam(0, 0, -1, 0, 1, 0);
  s.Method = Integrator::Auto;
  s.Recon = Reconstruction::Auto;
  CHECK(ResolveAuto(plain.V, s).Recon == Reconstruction::Trilinear,
    "Auto without smoothness bytes keeps the trilinear reconstruction");
  s.Method = Integrator::Euler;
  s.Recon = Reconstruction::Cubic;
  schtest::ExpectError("Cubic without PackFieldHighOrder", [&]() { TraceRays(plain.V, s, { 0.f, 0.f }); },
    { "PackFieldHighOrder" });
}

// PackFieldHighOrder against a plain transcription of its steps (a byte per point, one thread, no
// bit rows): the smoothness bytes, the packed field and the smooth fraction equal bit for bit, on
// volumes with a shock, noise and a jump, in sizes that are not multiples of the 64-point words.
struct Grid
{
  int n[3];
  std::size_t At(int i, int j, int k) const { return i + std::size_t(n[0]) * (j + std::size_t(n[1]) * k); }
  std::size_t Size() const { return std::size_t(n[0]) * n[1] * n[2]; }
  // dst = the AND over the offsets d of src at p + d along axis a; beyond the grid the border's
  // value (clamp) or 0
  void Erode(const std::vector<unsigned char>& src, std::vector<unsigned char>& dst, int a,
    std::initializer_list<int> offsets, bool clamp) const
  {
    dst.assign(Size(), 0);
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
        {
          unsigned char v = 1;
          for (int d : offsets)
          {
            int q[3] = { i, j, k };
            q[a] += d;
            if (q[a] < 0 || q[a] > n[a] - 1)
            {
              if (!clamp)
              {
                v = 0;
                break;
              }
              q[a] = q[a] < 0 ? 0 : n[a] - 1;
            }
            v &= src[At(q[0], q[1], q[2])];
          }
          dst[At(i, j, k)] = v;
        }
  }
};

double ReferencePack(const Grid& g, const double h[3], const std::vector<float>& f, std::vector<float>& out,
  std::vector<unsigned char>& bytes)
{
  const std::size_t N = g.Size();
  const float lo = *std::min_element(f.begin(), f.end()), hi = *std::max_element(f.begin(), f.end());
  const double floor = 1e-4 * (double(hi) - lo) + 1e-30, threshold = 0.25;
  const bool thin = g.n[0] < 5 || g.n[1] < 5 || g.n[2] < 5;
  std::vector<unsigned char> jumpFree(N, 0), point(N, 0);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
      {
        if (thin)
          continue;
        const int p[3] = { i, j, k };
        bool ok = true, inner = true;
        for (int a = 0; a < 3; ++a)
        {
          int q[3] = { i, j, k };
          q[a] = std::min(std::max(p[a], 2), g.n[a] - 3);
          double v[5];
          for (int d = -2; d <= 2; ++d)
          {
            int r[3] = { q[0], q[1], q[2] };
            r[a] += d;
            v[d + 2] = f[g.At(r[0], r[1], r[2])];
          }
          const double vlo = *std::min_element(v, v + 5), vhi = *std::max_element(v, v + 5);
          const double d4 = v[0] - 4 * v[1] + 6 * v[2] - 4 * v[3] + v[4];
          ok = ok && std::fabs(d4) <= threshold * (vhi - vlo + floor);
          inner = inner && p[a] >= 2 && p[a] <= g.n[a] - 3;
        }
        jumpFree[g.At(i, j, k)] = ok;
        point[g.At(i, j, k)] = ok && inner;
      }
  std::vector<unsigned char> fourth[3], cell, spare, A, B;
  for (int a = 0; a < 3; ++a)
    g.Erode(point, fourth[a], a, { -2, -1, 0, 1, 2 }, false);
  out.assign(4 * N, 0.0f);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
      {
        const int p[3] = { i, j, k };
        const std::size_t idx = g.At(i, j, k), st[3] = { 1, g.At(0, 1, 0), g.At(0, 0, 1) };
        out[4 * idx] = f[idx];
        for (int a = 0; a < 3; ++a)
        {
          const std::size_t s = st[a];
          double grad;
          if (fourth[a][idx])
            grad = (double(f[idx - 2 * s]) - 8.0 * f[idx - s] + 8.0 * f[idx + s] - f[idx + 2 * s]) / (12.0 * h[a]);
          else if (p[a] == 0)
            grad = (double(f[idx + s]) - f[idx]) / h[a];
          else if (p[a] == g.n[a] - 1)
            grad = (double(f[idx]) - f[idx - s]) / h[a];
          else
            grad = (double(f[idx + s]) - f[idx - s]) / (2.0 * h[a]);
          out[4 * idx + 1 + a] = static_cast<float>(grad);
        }
      }
  g.Erode(point, spare, 0, { -1, 0, 1, 2 }, false);
  g.Erode(spare, cell, 1, { -1, 0, 1, 2 }, false);
  g.Erode(cell, spare, 2, { -1, 0, 1, 2 }, false);
  cell.swap(spare);
  g.Erode(jumpFree, A, 0, { -1, 0, 1, 2 }, true);
  g.Erode(A, B, 1, { -1, 0, 1, 2 }, true);
  g.Erode(B, A, 2, { -1, 0, 1, 2 }, true);
  g.Erode(A, B, 0, { -1, 0, 1 }, true);
  g.Erode(B, A, 1, { -1, 0, 1 }, true);
  g.Erode(A, B, 2, { -1, 0, 1 }, true);
  std::vector<int> level(N, 0);
  for (int q = 1, r = 1; q <= 7; ++q, r *= 2)
  {
    g.Erode(B, A, 0, { -r, r }, true);
    g.Erode(A, B, 1, { -r, r }, true);
    g.Erode(B, A, 2, { -r, r }, true);
    A.swap(B);
    bool any = false;
    for (std::size_t x = 0; x < N; ++x)
      if (B[x])
      {
        level[x] = q;
        any = true;
      }
    if (!any)
      break;
  }
  bytes.assign(N, 0);
  std::size_t smooth = 0;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
      {
        const std::size_t x = g.At(i, j, k);
        bytes[x] = static_cast<unsigned char>((cell[x] ? 128 : 0) | (level[x] << 4));
        if (cell[x] && i + 1 < g.n[0] && j + 1 < g.n[1] && k + 1 < g.n[2])
          ++smooth;
      }
  const std::size_t cells = std::size_t(g.n[0] - 1) * (g.n[1] - 1) * (g.n[2] - 1);
  return cells ? double(smooth) / cells : 0.0;
}

void TestPackingReference()
{
  const int sizes[][3] = { { 67, 33, 45 }, { 70, 9, 64 }, { 130, 12, 20 }, { 6, 5, 7 } };
  for (const auto& n : sizes)
    for (int scene = 0; scene < 4; ++scene)
    {
      const Grid g{ { n[0], n[1], n[2] } };
      std::vector<float> f(g.Size());
      std::uint32_t seed = 12345;
      for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
          for (int i = 0; i < n[0]; ++i)
          {
            const double x = 2.0 * i / (n[0] - 1) - 1, y = 2.0 * j / (n[1] - 1) - 1,
                         z = 2.0 * k / (n[2] - 1) - 1, r2 = x * x + y * y + z * z;
            double v = kA * std::exp(-r2 / (2 * kS * kS));
            if (scene == 1)
              v += x + 0.3 * y > 0.1 ? 1e-4 : 0.0; // a plane shock, oblique to the grid
            if (scene == 2 && std::fabs(z) < 0.3 && y > 0)
            {
              seed = seed * 1664525u + 1013904223u; // noise in a slab
              v += 1e-6 * (seed >> 8) / 16777216.0;
            }
            if (scene == 3)
              v = r2 < 0.25 ? 3e-4 : 1e-5 * x; // a sphere with a jump at its surface
            f[g.At(i, j, k)] = static_cast<float>(v);
          }
      const double h[3] = { 2.0 / (n[0] - 1), 2.0 / (n[1] - 1), 2.0 / (n[2] - 1) };
      std::vector<float> out(4 * g.Size()), refOut;
      std::vector<unsigned char> bytes(g.Size()), refBytes;
      const double fraction = PackFieldHighOrder(n, h, f.data(), out.data(), bytes.data());
      const double refFraction = ReferencePack(g, h, f, refOut, refBytes);
      int levels = 0;
      for (unsigned char b : refBytes)
        levels = std::max(levels, b >> 4 & 7);
      std::printf("packing %d x %d x %d, scene %d: %.4f of the cells smooth, levels up to %d\n", n[0],
        n[1], n[2], scene, refFraction, levels);
      CHECK(bytes == refBytes, "the smoothness bytes equal the plain transcription's");
      CHECK(std::memcmp(out.data(), refOut.data(), out.size() * sizeof(float)) == 0,
        "the packed field equals the plain transcription's");
      CHECK(fraction == refFraction, "the smooth fraction equals the plain transcription's");
    }
}
} // namespace

int main()
{
  TestPackingReference();
  TestOrder();
  TestShock();
  TestBackends();
  TestAuto();
  return schtest::Finish();
}
