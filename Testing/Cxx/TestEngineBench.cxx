// SPDX-License-Identifier: BSD-3-Clause
// The bench's finite sources cut by the knife (docs/BENCH.md) against their closed forms
// (ORACLES.md, "The optical bench"). The volume is a slab n = n0 + G y of width W along the beam,
// built here (RefractiveScene's LinearGradient is n^2 = A + B y): every ray leaves it with the
// same deflection eps = G W / n0 toward +y, so each pixel's intensity is the response of the
// source's image shifted by f2 eps, and sweeping G walks it from full dark through the linear range
// to saturation. The knife normal a is the film's y (KnifeAngle 90): light bent toward -y passes,
// so the shift toward the open side is s = -f2 eps.
#include "SchlierenTesting.h"

#include "SchlierenPhysics.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace schlieren;

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kFloatEps = 1.0 / 16777216.0; // 2^-24, float32's unit roundoff

// the slab: x, y in [-H, H], z in [-W/2, W/2], n - 1 = n0m1 + G y
constexpr double H = 0.01, W = 0.1;
constexpr int NX = 9, NZ = 41;

struct Slab
{
  std::vector<float> N1, Field;
  Volume V;
  Slab(double n0m1, double G)
  {
    const int dims[3] = { NX, NX, NZ };
    const double lo[3] = { -H, -H, -0.5 * W }, hi[3] = { H, H, 0.5 * W };
    for (int a = 0; a < 3; ++a)
    {
      V.Dimensions[a] = dims[a];
      V.Origin[a] = lo[a];
      V.Spacing[a] = (hi[a] - lo[a]) / (dims[a] - 1);
    }
    N1.resize(V.NumberOfPoints());
    for (int k = 0; k < NZ; ++k)
      for (int j = 0; j < NX; ++j)
        for (int i = 0; i < NX; ++i)
          N1[(static_cast<std::size_t>(k) * NX + j) * NX + i] =
            static_cast<float>(n0m1 + G * (V.Origin[1] + j * V.Spacing[1]));
    Field.resize(4 * N1.size());
    PackField(V.Dimensions, V.Spacing, N1.data(), Field.data());
    V.Field = Field.data();
  }
};

constexpr int kFilm = 8;

TraceSettings BenchSettings(BenchSource src, double h, double f1, double f2, double cut)
{
  TraceSettings s;
  s.Device = Backend::CPU;
  s.ViewDirection[0] = 0;
  s.ViewDirection[1] = 0;
  s.ViewDirection[2] = -1;
  s.ViewUp[0] = 0;
  s.ViewUp[1] = 1;
  s.ViewUp[2] = 0;
  s.Resolution[0] = s.Resolution[1] = kFilm;
  s.Passes = 1;
  s.Jitter = false; // one photon at each pixel's centre: it cannot cross into its neighbour
  s.Mode = Cutoff::KnifeEdge;
  s.KnifeAngle = 90;
  s.Source = src;
  s.SourceSize[0] = h;
  s.SourceSize[1] = 2 * h;
  s.CollimatorFocalLength = f1;
  s.SchlierenFocalLength = f2;
  s.KnifeCut = cut;
  return s;
}

// the independent closed forms, in double
double DiscF(double t)
{
  t = std::max(-1.0, std::min(1.0, t));
  return (std::acos(t) - t * std::sqrt(1 - t * t)) / kPi;
}
// x with f(x) = y for a decreasing f, by bisection on [lo, hi]
template <typename F>
double SolveDecreasing(F f, double y, double lo, double hi)
{
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > y ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The passing share at shift s for a source whose image (a0, or R', or sigma) the knife cuts to
// leave `open`, from the formulas of ORACLES.md rather than the engine's.
struct Expected
{
  BenchSource Src;
  double a0, open, d, size;
  Expected(BenchSource src, double h, double f1, double f2, double cut)
    : Src(src)
    , a0(h * 1e-3 * f2 / f1)
    , open(1 - cut)
  {
    if (src == BenchSource::Disc)
    {
      size = 0.5 * a0;
      d = size * SolveDecreasing(DiscF, open, -1, 1);
    }
    else if (src == BenchSource::Gaussian)
    {
      size = 0.25 * a0;
      d = SolveDecreasing([this](double x) { return 0.5 * std::erfc(x / (size * std::sqrt(2.0))); },
        open, -20 * size, 20 * size);
    }
    else
    {
      size = a0;
      d = 0.5 * a0 - open * a0;
    }
  }
  double I(double s) const
  {
    if (Src == BenchSource::Disc)
      return DiscF((d - s) / size);
    if (Src == BenchSource::Gaussian)
      return 0.5 * std::erfc((d - s) / (size * std::sqrt(2.0)));
    return std::max(0.0, std::min(1.0, (open * a0 + s) / a0));
  }
};

// The largest relative error of the traced deflection: the float32 sums of v over the steps
// (each step's rounding, 2^-24 relative, adds up over the ~W / (StepSize h) steps), the gradient
// from float differences of n - 1, and the normalisation; a factor 4 over that count covers the
// few roundings per step that the count treats as one.
double DeflectionTolerance()
{
  const double steps = W / (0.5 * (2 * H / (NX - 1)));
  return 4 * (steps + 16) * kFloatEps;
}

struct Pixel
{
  double Ey, Intensity;
};

// the traced image's interior pixels (the slab's border rows see one-sided gradients, which are
// exact for a linear field too; all pixels are checked)
void CheckSlab(BenchSource src, double h, double f1, double f2, double cut, double n0m1,
  const std::vector<double>& epsOpen, const char* label)
{
  const Expected X(src, h, f1, f2, cut);
  const double tolRel = DeflectionTolerance();
  double worstE = 0, worstI = 0, worstLinear = 0;
  int dark = 0, saturated = 0, linear = 0;
  for (double eo : epsOpen)
  {
    // eps toward +y is -eps_open: choose G so that the centre ray's eps is what was asked
    const double G = -eo * (1 + n0m1) / W;
    Slab slab(n0m1, G);
    TraceSettings s = BenchSettings(src, h, f1, f2, cut);
    const TraceResult r = Trace(slab.V, s);
    // n - 1 is stored as float: each grid value is off by up to 2^-24 of the largest |n - 1|, and
    // the gradient's central difference over 2 dy carries twice that, which W turns into an
    // absolute error of the deflection (twice again for the interpolation between two rows)
    const double dy = 2 * H / (NX - 1);
    const double tolAbs = 2 * W * 2 * (std::fabs(n0m1) + std::fabs(G) * H) * kFloatEps / (2 * dy);
    for (int j = 0; j < kFilm; ++j)
      for (int i = 0; i < kFilm; ++i)
      {
        const std::size_t p = static_cast<std::size_t>(j) * kFilm + i;
        const double y = r.Film.Center[1] + r.Film.Corner[1] + (j + 0.5) * r.Film.PixelSize;
        const double n = 1 + n0m1 + G * y;
        const double ey = G * W / n; // the slab's closed form, toward +y
        const double gotE = r.Deflection[2 * p + 1];
        const double errE = std::fabs(gotE - ey);
        worstE = std::max(worstE, errE / std::max(std::fabs(ey), 1e-300));
        const double tolE = tolRel * std::fabs(ey) + tolAbs;
        CHECK(errE <= tolE,
          std::string(label) + ": deflection " + std::to_string(gotE) + " against G W / n " +
            std::to_string(ey));
        const double sh = -f2 * ey;
        const double want = X.I(sh);
        // the weight is computed in float (a few roundings of values of order 1), and the
        // deflection's own error moves the shift by f2 tolRel |eps| over an image of size `size`
        // whose response has slope at most 1 / size (slit), (2 / pi) / R' (disc),
        // 1 / (sigma sqrt(2 pi)) (Gaussian)
        const double tolI = 16 * kFloatEps + f2 * tolE / X.size;
        const double got = r.Intensity[p];
        worstI = std::max(worstI, std::fabs(got - want));
        CHECK(std::fabs(got - want) <= tolI,
          std::string(label) + ": I = " + std::to_string(got) + " against the closed form " +
            std::to_string(want) + " at eps " + std::to_string(-ey));
        if (src == BenchSource::Slit || src == BenchSource::Rectangle)
        {
          // every pixel has the same deflection: the film is all saturated, all dark, or neither
          const double eOpen0 = -ey, a0open = X.open * X.a0;
          const bool allSat = eOpen0 >= (X.a0 - a0open) / f2 * (1 + 1e-3);
          const bool inside = eOpen0 < (X.a0 - a0open) / f2 * (1 - 1e-3);
          if (allSat || inside)
          {
            CHECK(r.BenchSaturated == (allSat ? 1.0 : 0.0), std::string(label) + ": share saturated");
            CHECK((r.Warnings.find("saturated") != std::string::npos) == allSat,
              std::string(label) + ": the saturation warning: " + r.Warnings);
          }
          const double eOpen = -ey, a = X.open * X.a0;
          if (eOpen <= -a / f2)
          {
            ++dark;
            CHECK(got == 0.0, std::string(label) + ": full dark beyond eps = -a / f2");
          }
          else if (eOpen >= (X.a0 - a) / f2)
          {
            ++saturated;
            CHECK(got == 1.0f, std::string(label) + ": saturated (I / I0 = a0 / a) beyond (a0 - a) / f2");
          }
          else
          {
            ++linear;
            // contrast dI / I = f2 eps / a in the linear range
            const double contrast = got / X.open - 1, lin = f2 * eOpen / a;
            worstLinear = std::max(worstLinear, std::fabs(contrast - lin));
            CHECK(std::fabs(contrast - lin) <= tolI / X.open,
              std::string(label) + ": dI/I = f2 eps / a in the linear range");
          }
        }
      }
    // the read-outs from the settings alone
    if (eo == epsOpen.front())
    {
      const BenchResponse b = ComputeBench(s);
      CHECK(b.Finite, label);
      CHECK_NEAR(r.BenchRange[0], b.Dark, 0, std::string(label) + ": TraceResult's range");
      if (src == BenchSource::Slit || src == BenchSource::Rectangle)
      {
        const double a = X.open * X.a0;
        CHECK_NEAR(r.BenchSensitivity, f2 / a, 1e-9 * f2 / a, std::string(label) + ": sensitivity f2 / a");
        CHECK_NEAR(r.BenchRange[0], -a / f2, 1e-12, std::string(label) + ": full dark at -a / f2");
        CHECK_NEAR(r.BenchRange[1], (X.a0 - a) / f2, 1e-12, std::string(label) + ": saturation at (a0 - a) / f2");
        // one grey level of 8 bits, full scale at I = 1, is a shift of a0 / 255
        CHECK_NEAR(r.BenchResolvable, X.a0 / (255 * f2), 1e-9 * X.a0 / f2, std::string(label) + ": 8-bit resolvable eps");
      }
      else
      {
        // the sensitivity is the closed form's slope at eps = 0: a centred difference
        const double ds = 1e-6 * X.size;
        const double slope = (X.I(ds) - X.I(-ds)) / (2 * ds) * f2 / X.open;
        CHECK_NEAR(r.BenchSensitivity, slope, 1e-6 * slope, std::string(label) + ": sensitivity dI/I per radian");
      }
      CHECK(!r.BenchModel.empty() && r.BenchModel.find("closed form") != std::string::npos,
        std::string(label) + ": BenchModel says closed form: " + r.BenchModel);
    }
  }
  std::printf("%-20s a0 = %.4g mm, open %.2f: max rel deflection error %.2g (tolerance %.2g + "
              "float n - 1), max |I - closed form| %.2g",
    label, X.a0 * 1e3, X.open, worstE, tolRel, worstI);
  if (src == BenchSource::Slit || src == BenchSource::Rectangle)
    std::printf(", max |dI/I - f2 eps/a| %.2g; pixels dark %d, linear %d, saturated %d", worstLinear,
      dark, linear, saturated);
  std::printf("\n");
  if (src == BenchSource::Slit)
    CHECK(dark > 0 && linear > 0 && saturated > 0, std::string(label) + ": the sweep reaches all three ranges");
}

std::vector<double> Sweep(double lo, double hi, int n)
{
  std::vector<double> v;
  for (int k = 0; k < n; ++k)
    v.push_back(lo + (hi - lo) * k / (n - 1));
  return v;
}

void TestSlit()
{
  // h = 0.6 mm, f1 = 1.5 m, f2 = 2 m: a0 = 0.8 mm; at each cut the sweep runs from 1.5 x the
  // dark limit to 1.5 x the saturation limit, through 0
  for (double cut : { 0.3, 0.5, 0.7 })
  {
    const double a0 = 0.6e-3 * 2 / 1.5, a = (1 - cut) * a0, f2 = 2;
    std::vector<double> eps = Sweep(-1.5 * a / f2, 1.5 * (a0 - a) / f2, 13);
    // just inside and just beyond each end
    for (double f : { 0.98, 1.02 })
    {
      eps.push_back(-f * a / f2);
      eps.push_back(f * (a0 - a) / f2);
    }
    char label[64];
    std::snprintf(label, sizeof(label), "slit, %.0f %% cut", 100 * cut);
    CheckSlab(BenchSource::Slit, 0.6, 1.5, 2, cut, 3e-4, eps, label);
  }
  // a rectangle is a slit for the knife (its along-knife side does not matter)
  CheckSlab(BenchSource::Rectangle, 0.6, 1.5, 2, 0.5, 3e-4, Sweep(-4e-4, 4e-4, 5), "rectangle, 50 % cut");
}

void TestDisc()
{
  // pinhole of 1 mm, f1 = 1 m, f2 = 1.5 m: R' = 0.75 mm
  const double f2 = 1.5, R = 0.5 * 1e-3 * f2 / 1;
  for (double cut : { 0.3, 0.5, 0.7 })
  {
    char label[64];
    std::snprintf(label, sizeof(label), "disc, %.0f %% cut", 100 * cut);
    CheckSlab(BenchSource::Disc, 1.0, 1.0, f2, cut, 3e-4, Sweep(-2.5 * R / f2, 2.5 * R / f2, 11), label);
  }
  // at 50 % and small eps: dI/I = (4 / pi) f2 eps / R', to O(t^2 / 6) relative, t = f2 eps / R'
  const double t = 0.01, eo = t * R / f2;
  const double G = -eo * (1 + 3e-4) / W;
  Slab slab(3e-4, G);
  const TraceResult r = Trace(slab.V, BenchSettings(BenchSource::Disc, 1.0, 1.0, f2, 0.5));
  const std::size_t p = static_cast<std::size_t>(kFilm / 2) * kFilm + kFilm / 2;
  const double y = r.Film.Center[1] + r.Film.Corner[1] + (kFilm / 2 + 0.5) * r.Film.PixelSize;
  const double eps = -G * W / (1 + 3e-4 + G * y);
  const double contrast = r.Intensity[p] / 0.5 - 1, lin = 4 / kPi * f2 * eps / R;
  const double tol = std::fabs(lin) * (t * t / 6 + DeflectionTolerance()) + 32 * kFloatEps;
  CHECK_NEAR(contrast, lin, tol, "disc at 50 % cut: dI/I = (4 / pi) f2 eps / R'");
  CHECK_NEAR(r.BenchSensitivity, 4 / kPi * f2 / R, 1e-6 * 4 / kPi * f2 / R,
    "disc at 50 % cut: sensitivity (4 / pi) f2 / R'");
  std::printf("disc, 50 %% cut, t = %.2g: dI/I = %.6g, (4/pi) f2 eps / R' = %.6g\n", t, contrast, lin);
}

void TestGaussian()
{
  // 1/e^2 diameter 2 mm, f1 = f2 = 1 m: sigma' = 0.5 mm
  for (double cut : { 0.3, 0.5, 0.7 })
  {
    char label[64];
    std::snprintf(label, sizeof(label), "Gaussian, %.0f %% cut", 100 * cut);
    CheckSlab(BenchSource::Gaussian, 2.0, 1.0, 1.0, cut, 3e-4, Sweep(-2e-3, 2e-3, 11), label);
  }
}

// every integrator hands the same deflection to the bench: a slit at 50 % in its linear range
void TestIntegrators()
{
  const double eo = 2e-4, n0m1 = 3e-4, G = -eo * (1 + n0m1) / W;
  Slab slab(n0m1, G);
  for (Integrator m :
    { Integrator::Verlet, Integrator::Midpoint, Integrator::RK4, Integrator::Straight, Integrator::Auto })
  {
    TraceSettings s = BenchSettings(BenchSource::Slit, 1.0, 1.0, 1.0, 0.5);
    s.Method = m;
    // Auto at the deflection's tolerance this test holds every integrator to (at its default, 1 %
    // of the deflection, it takes one line-of-sight step across the slab since issue 50: 2e-8 rad
    // off, within that default and not within this test's)
    if (m == Integrator::Auto)
      s.Tolerance = DeflectionTolerance() * eo;
    const TraceResult r = Trace(slab.V, s);
    double worst = 0;
    for (int j = 0; j < kFilm; ++j)
    {
      const double y = r.Film.Center[1] + r.Film.Corner[1] + (j + 0.5) * r.Film.PixelSize;
      const double want = 0.5 - 1.0 * G * W / (1 + n0m1 + G * y) / 1e-3; // (a + s) / a0, s = -f2 eps
      for (int i = 0; i < kFilm; ++i)
        worst = std::max(worst, std::fabs(r.Intensity[static_cast<std::size_t>(j) * kFilm + i] - want));
    }
    // the deflection's tolerance moved through the slit's slope f2 / a0, plus the weight's roundings
    const double tol = 16 * kFloatEps + (DeflectionTolerance() * eo + 1e-9) * 1.0 / 1e-3;
    CHECK(worst <= tol, std::string("slit at 50 % under ") + IntegratorName(m) + ": I == (a + f2 eps) / a0");
    std::printf("slit at 50 %% under %-8s max |I - closed form| %.2g (tolerance %.2g)\n", IntegratorName(m), worst, tol);
  }
}

// the physics header's closed forms at the values ORACLES.md lists
void TestWeights()
{
  const struct
  {
    double t, F;
  } disc[] = { { 0, 0.5 }, { 0.3, 0.3119 }, { 0.8, 0.0520 }, { -0.5, 0.8045 }, { 1.5, 0 }, { -1.5, 1 } };
  for (const auto& c : disc)
    CHECK_NEAR(sch_bench_weight(SCH_SOURCE_DISC, 0.0f, static_cast<float>(c.t), 1.0f), c.F, 5e-5,
      "disc F(t) (ORACLES, 4 digits)");
  // slit: a0 = 1, edge at d = 0.2 (a = 0.3 open): (a + s) / a0 clamped
  CHECK_NEAR(sch_bench_weight(SCH_SOURCE_SLIT, 0.1f, 0.2f, 1.0f), 0.4, 1e-6, "slit (a + s) / a0");
  CHECK_NEAR(sch_bench_weight(SCH_SOURCE_SLIT, -0.4f, 0.2f, 1.0f), 0, 0, "slit: dark");
  CHECK_NEAR(sch_bench_weight(SCH_SOURCE_SLIT, 0.8f, 0.2f, 1.0f), 1, 0, "slit: saturated");
  // Gaussian: erfc((d - s) / (sigma sqrt 2)) / 2
  CHECK_NEAR(sch_bench_weight(SCH_SOURCE_GAUSSIAN, 0.0f, 0.0f, 1.0f), 0.5, 1e-6, "Gaussian at its centre");
  CHECK_NEAR(sch_bench_weight(SCH_SOURCE_GAUSSIAN, 0.0f, 1.0f, 1.0f), 0.5 * std::erfc(1 / std::sqrt(2.0)),
    1e-6, "Gaussian one sigma in");
}

// Point: the bench's other settings change nothing, bit for bit, on either backend
void TestPointUnchanged(bool opencl)
{
  SceneParameters p;
  p.Amplitude = 1e-4;
  p.Width = 0.25;
  schtest::SceneVolume sv(Scene::GaussianSphere, p, 48, 1.0);
  for (Cutoff mode : { Cutoff::KnifeEdge, Cutoff::Circular, Cutoff::Shadowgraph })
  {
    TraceSettings s;
    s.Device = opencl ? Backend::OpenCL : Backend::CPU;
    s.Resolution[0] = s.Resolution[1] = 40;
    s.Passes = 2;
    s.Mode = mode;
    s.KnifeAngle = 30;
    const TraceResult ref = Trace(sv.V, s);
    s.SourceSize[0] = 3;
    s.SourceSize[1] = 7;
    s.CollimatorFocalLength = 0.5;
    s.SchlierenFocalLength = 2.5;
    s.KnifeCut = 0.8;
    const TraceResult got = Trace(sv.V, s);
    const bool same = ref.Intensity.size() == got.Intensity.size() &&
      std::memcmp(ref.Intensity.data(), got.Intensity.data(), ref.Intensity.size() * sizeof(float)) == 0;
    CHECK(same, std::string("Point source: the bench's sizes change nothing (") + CutoffName(mode) + ")");
    CHECK(got.BenchModel.empty() && got.BenchSensitivity == 0, "Point: no bench read-outs");
    // a finite source under a cutoff other than the knife is the point source's
    s.Source = BenchSource::Slit;
    if (mode != Cutoff::KnifeEdge)
    {
      const TraceResult slit = Trace(sv.V, s);
      CHECK(std::memcmp(ref.Intensity.data(), slit.Intensity.data(), ref.Intensity.size() * sizeof(float)) == 0,
        std::string("a finite source leaves ") + CutoffName(mode) + " unchanged");
    }
  }
  std::printf("Point source unchanged by the bench's settings (%s)\n", opencl ? "OpenCL" : "CPU");
}

// Circular stops in mm (StopDiameter): the share of the source's image, shifted by s = f2 |e|,
// inside a circular aperture of radius rho (Circular) or outside an opaque disc (Complement),
// against shares computed here another way: a disc's by summing its chords inside the circle, a
// Gaussian's by integrating it over the circle on a polar grid, the point source's as a step.
double DiscInsideByChords(double a, double rho, double d)
{
  const int n = 200000;
  double sum = 0;
  for (int k = 0; k < n; ++k)
  {
    const double x = d - a + 2 * a * (k + 0.5) / n; // across the source's image, centred at d
    const double ys = std::sqrt(std::max(0.0, a * a - (x - d) * (x - d)));
    const double yb = std::fabs(x) < rho ? std::sqrt(rho * rho - x * x) : 0.0;
    sum += 2 * std::min(ys, yb); // both chords are centred on y = 0
  }
  return sum * (2 * a / n) / (kPi * a * a);
}

double GaussianInsideByGrid(double sigma, double rho, double d)
{
  const int nr = 600, nt = 600;
  double sum = 0;
  for (int i = 0; i < nr; ++i)
    for (int k = 0; k < nt; ++k)
    {
      const double r = rho * (i + 0.5) / nr, t = 2 * kPi * (k + 0.5) / nt;
      const double x = r * std::cos(t) - d, y = r * std::sin(t);
      sum += std::exp(-0.5 * (x * x + y * y) / (sigma * sigma)) * r;
    }
  return sum * (rho / nr) * (2 * kPi / nt) / (2 * kPi * sigma * sigma);
}

void TestStops()
{
  const double f1 = 1.0, f2 = 1.0, n0m1 = 3e-4;
  // mm: rho = 0.8 mm, larger than the disc's image (R' = 0.5 mm), and 0.3 mm, smaller than it
  for (double diameter : { 1.6, 0.6 })
  for (BenchSource src : { BenchSource::Disc, BenchSource::Gaussian, BenchSource::Point })
    for (Cutoff mode : { Cutoff::Circular, Cutoff::ComplementCircular })
    {
      const double rho = 0.5 * diameter * 1e-3;
      const double h = 1.0; // mm: a disc's image R' = 0.5 mm, a Gaussian's sigma = 0.25 mm
      const double size = src == BenchSource::Disc ? 0.5e-3 * h : 0.25e-3 * h;
      double worst = 0;
      for (double sh : Sweep(0.0, 1.5e-3, 13)) // the image's shift in the cutoff plane, m
      {
        if (src == BenchSource::Point && std::fabs(sh - rho) < 0.05e-3)
          continue; // the step itself: the slab's own deflection error decides which side
        const double G = sh / f2 * (1 + n0m1) / W;
        Slab slab(n0m1, G);
        TraceSettings s = BenchSettings(src, h, f1, f2, 0.5);
        s.Mode = mode;
        s.StopDiameter = diameter;
        const TraceResult r = Trace(slab.V, s);
        const double dy = 2 * H / (NX - 1);
        const double tolAbs = 2 * W * 2 * (std::fabs(n0m1) + std::fabs(G) * H) * kFloatEps / (2 * dy);
        for (int j = 0; j < kFilm; ++j)
        {
          // a row's pixels share their deflection (the slab's n depends on y alone)
          const double y = r.Film.Center[1] + r.Film.Corner[1] + (j + 0.5) * r.Film.PixelSize;
          const double ey = G * W / (1 + n0m1 + G * y);
          const double d = f2 * std::fabs(ey);
          const double inside = src == BenchSource::Disc ? DiscInsideByChords(size, rho, d)
            : src == BenchSource::Gaussian               ? GaussianInsideByGrid(size, rho, d)
                                                         : (d < rho ? 1.0 : 0.0);
          for (int i = 0; i < kFilm; ++i)
          {
            const std::size_t p = static_cast<std::size_t>(j) * kFilm + i;
            const double want = mode == Cutoff::Circular ? inside : 1 - inside;
            // float weights, the deflection's error times the response's slope (at most
            // 2 / (pi R') for a disc, 1 / (sigma sqrt(2 pi)) for a Gaussian), the Gaussian's table
            const double slope = src == BenchSource::Disc ? 2 / (kPi * size) : 1 / (size * std::sqrt(2 * kPi));
            const double tolE = DeflectionTolerance() * std::fabs(ey) + tolAbs;
            const double tol = 16 * kFloatEps + (src == BenchSource::Point ? 0 : f2 * tolE * slope) +
              (src == BenchSource::Gaussian ? 1e-5 : 2e-7);
            worst = std::max(worst, std::fabs(r.Intensity[p] - want));
            CHECK(std::fabs(r.Intensity[p] - want) <= tol,
              std::string("stop: ") + CutoffName(mode) + " I = " + std::to_string(r.Intensity[p]) +
                " against " + std::to_string(want) + " at shift " + std::to_string(d * 1e3) + " mm");
          }
        }
        if (src == BenchSource::Disc && sh == 0.0 && diameter == 1.6)
        {
          // the range: the stop begins to cut the image at (rho - R') / f2, covers it at (rho + R') / f2
          const bool c = mode == Cutoff::Circular;
          CHECK(std::fabs(r.BenchRange[c ? 1 : 0] - (rho - size) / f2) < 1e-12 &&
              std::fabs(r.BenchRange[c ? 0 : 1] - (rho + size) / f2) < 1e-12,
            "stop: bench_range from rho -/+ R'");
          CHECK(r.BenchModel.find("1.6 mm") != std::string::npos, "stop: the model names the stop: " + r.BenchModel);
        }
      }
      std::printf("stop %s, %s: max |I - share| = %.3g over shifts 0..1.5 mm (rho = %g mm)\n",
        CutoffName(mode), src == BenchSource::Disc ? "disc R' 0.5 mm" : src == BenchSource::Gaussian
          ? "Gaussian sigma 0.25 mm" : "point", worst, rho * 1e3);
    }
  // the colour filter with an opaque centre of 1.6 mm: the light a disc's image leaves around it,
  // on the hue of the deflection's direction (+y here: between yellow and green, rgb (0.5, 1, 0))
  {
    const double rho = 0.8e-3, size = 0.5e-3;
    double worst = 0;
    for (double sh : Sweep(0.0, 1.5e-3, 7))
    {
      const double G = sh / f2 * (1 + n0m1) / W;
      Slab slab(n0m1, G);
      TraceSettings s = BenchSettings(BenchSource::Disc, 1.0, f1, f2, 0.5);
      s.Mode = Cutoff::ColorFilter;
      s.StopDiameter = 1.6;
      const TraceResult r = Trace(slab.V, s);
      const std::size_t p = static_cast<std::size_t>(kFilm / 2) * kFilm + kFilm / 2;
      const double y = r.Film.Center[1] + r.Film.Corner[1] + (kFilm / 2 + 0.5) * r.Film.PixelSize;
      const double ey = G * W / (1 + n0m1 + G * y);
      const double share = 1 - DiscInsideByChords(size, rho, f2 * std::fabs(ey));
      const double hue[3] = { sh > 0 ? 0.5 : 1.0, sh > 0 ? 1.0 : 0.0, 0.0 }; // no deflection: hue 0, red
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::fabs(r.RGB[3 * p + c] - share * hue[c]));
      worst = std::max(worst, std::fabs(r.Intensity[p] - share));
    }
    std::printf("colour filter with a 1.6 mm opaque centre, disc R' 0.5 mm: max |rgb - share x hue| = %.3g\n", worst);
    CHECK(worst < 1e-4, "colour filter in mm: the share outside its centre on the deflection's hue");
  }
  // StopDiameter 0 keeps the idealised stops: bit for bit
  Slab slab(n0m1, 2e-3);
  TraceSettings s = BenchSettings(BenchSource::Disc, 1.0, f1, f2, 0.5);
  s.Mode = Cutoff::Circular;
  s.CutoffScale = 500;
  const TraceResult a = Trace(slab.V, s);
  s.Source = BenchSource::Point;
  const TraceResult b = Trace(slab.V, s);
  CHECK(std::memcmp(a.Intensity.data(), b.Intensity.data(), a.Intensity.size() * sizeof(float)) == 0,
    "StopDiameter 0: the idealised circular stop whatever the source");
}

void TestErrors()
{
  Slab slab(3e-4, 1e-3);
  auto run = [&](std::function<void(TraceSettings&)> change) {
    return [&slab, change]() {
      TraceSettings s = BenchSettings(BenchSource::Slit, 1, 1, 1, 0.5);
      change(s);
      Trace(slab.V, s);
    };
  };
  schtest::ExpectError("SourceSize 0", run([](TraceSettings& s) { s.SourceSize[0] = 0; }),
    { "SourceSize[0]", "[0.001, 10000] mm" });
  schtest::ExpectError("SourceSize[1] -1", run([](TraceSettings& s) { s.SourceSize[1] = -1; }),
    { "SourceSize[1]", "-1" });
  schtest::ExpectError("SourceSize NaN", run([](TraceSettings& s) { s.SourceSize[0] = std::nan(""); }),
    { "SourceSize[0]", "nan" });
  schtest::ExpectError("CollimatorFocalLength 0", run([](TraceSettings& s) { s.CollimatorFocalLength = 0; }),
    { "CollimatorFocalLength", "[0.001, 1000] m" });
  schtest::ExpectError("SchlierenFocalLength -2", run([](TraceSettings& s) { s.SchlierenFocalLength = -2; }),
    { "SchlierenFocalLength", "-2" });
  schtest::ExpectError("KnifeCut 1", run([](TraceSettings& s) { s.KnifeCut = 1; }), { "KnifeCut", "[0, 0.999]" });
  schtest::ExpectError("KnifeCut -0.1", run([](TraceSettings& s) { s.KnifeCut = -0.1; }), { "KnifeCut", "-0.1" });
  schtest::ExpectError("BitDepth 0", run([](TraceSettings& s) { s.BitDepth = 0; }), { "BitDepth", "[1, 32]" });
  schtest::ExpectError("SaturationWarning 2", run([](TraceSettings& s) { s.SaturationWarning = 2; }),
    { "SaturationWarning", "[0, 1]" });
  schtest::ExpectError("StopDiameter -1", run([](TraceSettings& s) {
    s.Mode = Cutoff::Circular;
    s.StopDiameter = -1;
  }), { "StopDiameter", "[0, 10000] mm" });
  schtest::ExpectError("a slit with a circular stop", run([](TraceSettings& s) {
    s.Mode = Cutoff::ComplementCircular;
    s.Source = BenchSource::Slit;
    s.StopDiameter = 2;
  }), { "circular stop", "Disc" });
  schtest::ExpectError("Source 7", run([](TraceSettings& s) { s.Source = static_cast<BenchSource>(7); }),
    { "Source", "Gaussian" });
  // issue 48: a source far larger than its mirror (h/f1 = 1e4 gave a flat film and a resolvable
  // deflection of 39 rad) is outside the paraxial closed forms: refused, naming h/f1 and the limit
  schtest::ExpectError("h/f1 = 1e4", run([](TraceSettings& s) {
    s.SourceSize[0] = 1e4;
    s.SourceSize[1] = 1;
    s.CollimatorFocalLength = 1e-3;
  }), { "h/f1 = 10000", "h/f1 <= 0.2", "SourceSize", "CollimatorFocalLength" });
  schtest::ExpectError("a disc at h/f1 = 0.21 with a stop", run([](TraceSettings& s) {
    s.Source = BenchSource::Disc;
    s.Mode = Cutoff::Circular;
    s.StopDiameter = 300;
    s.SourceSize[0] = 210;
    s.SourceSize[1] = 1;
  }), { "h/f1 = 0.21", "at most 200 mm" });
  for (BenchSource src : { BenchSource::Slit, BenchSource::Disc, BenchSource::Gaussian })
  {
    // at the limit: traced, the read-outs those of the closed form (slit: a0/((2^8 - 1) f2))
    TraceSettings s = BenchSettings(src, 200, 1, 1, 0.5);
    bool traced = false;
    try
    {
      traced = !Trace(slab.V, s).Intensity.empty();
    }
    catch (const Error&)
    {
    }
    CHECK(traced, "h/f1 = 0.2 (a 200 mm source at f1 = 1 m): traced");
  }
  {
    // the point source does not use SourceSize: any h/f1 is accepted
    TraceSettings s = BenchSettings(BenchSource::Point, 5e3, 1e-3, 1, 0.5);
    CHECK(!Trace(slab.V, s).Intensity.empty(), "Point with h/f1 = 5e3 set: traced (the size is not used)");
    const BenchResponse b = ComputeBench(BenchSettings(BenchSource::Slit, 200, 1, 1, 0.5));
    CHECK_NEAR(b.Resolvable, 0.2 / 255, 1e-12, "h/f1 = 0.2: resolvable deflection a0 / (255 f2)");
  }
}
}

int main()
{
  TestWeights();
  TestSlit();
  TestDisc();
  TestGaussian();
  TestIntegrators();
  TestStops();
  TestErrors();
  TestPointUnchanged(false);
  if (schtest::HaveOpenCL())
    TestPointUnchanged(true);
  return schtest::Finish();
}
