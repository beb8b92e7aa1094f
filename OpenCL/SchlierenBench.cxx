// SPDX-License-Identifier: BSD-3-Clause
// The bench: what a finite source cut by the knife implies (docs/BENCH.md). The per-photon weight
// itself is sch_bench_weight in SchlierenPhysics.h; this places the edge for the requested cut and
// derives the read-outs (sensitivity, measuring range) from the same closed forms.
#include "SchlierenEngineInternal.h"

#include <cmath>
#include <sstream>

namespace schlieren
{

namespace
{
const double kPi = 3.14159265358979323846;

// x with erfc(x) = y, y in (0, 2), by bisection (erfc is decreasing); clamped to [-10, 10]. The
// engine's own erfc (SchlierenPhysics.h), the one the weights use: the C library's moved in its last
// bit at glibc 2.43, and with it the edge.
double InverseErfc(double y)
{
  double lo = -10, hi = 10;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    if (double(sch_erfc(static_cast<float>(mid))) > y)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

// the disc's uncovered share beyond a chord at t R' from its centre
double DiscShare(double t)
{
  t = std::max(-1.0, std::min(1.0, t));
  return (sch_acos_d(t) - t * std::sqrt(1 - t * t)) / kPi;
}
}

namespace
{
// the share of a disc of radius a (the source's image) inside a circle of radius b whose centre
// is d from the disc's: the lens where they overlap, over pi a^2
double DiscInCircle(double a, double b, double d)
{
  if (d >= a + b)
    return 0;
  if (d <= std::fabs(a - b))
    return a <= b ? 1.0 : (b * b) / (a * a);
  const double ca = std::max(-1.0, std::min(1.0, (d * d + a * a - b * b) / (2 * d * a)));
  const double cb = std::max(-1.0, std::min(1.0, (d * d + b * b - a * a) / (2 * d * b)));
  const double k = std::sqrt(std::max(0.0, (-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b)));
  return (a * a * sch_acos_d(ca) + b * b * sch_acos_d(cb) - 0.5 * k) / (kPi * a * a);
}

// the share of an isotropic Gaussian spot (sigma) centred s from the centre of a circle of radius
// rho that falls inside it, as an integral over the directions from the spot's centre: along a
// direction the Gaussian's mass between distances L1 and L2 is exp(-L1^2/2s^2) - exp(-L2^2/2s^2)
double GaussianInCircle(double sigma, double rho, double s)
{
  const int n = 256; // Gauss-free midpoint rule on a smooth, periodic (or substituted) integrand
  auto mass = [sigma](double l) { return std::exp(-0.5 * l * l / (sigma * sigma)); };
  double sum = 0;
  if (s < rho)
  {
    // every direction leaves the circle once, at L = -s cos t + sqrt(rho^2 - s^2 sin^2 t)
    for (int i = 0; i < n; ++i)
    {
      const double t = kPi * (i + 0.5) / n; // symmetric: [0, pi] twice
      const double st = std::sin(t), ct = std::cos(t);
      const double l = -s * ct + std::sqrt(std::max(0.0, rho * rho - s * s * st * st));
      sum += 1 - mass(l);
    }
    return sum / n;
  }
  // outside: the directions toward the circle, sin t = (rho / s) sin u for u in [0, pi/2] (the
  // substitution takes away the square root's infinite slope at the tangents), cross it between
  // L1,2 = s cos t -/+ rho cos u; dt = (rho / s) cos u / cos t du
  for (int i = 0; i < n; ++i)
  {
    const double u = 0.5 * kPi * (i + 0.5) / n;
    const double st = rho / s * std::sin(u), ct = std::sqrt(std::max(0.0, 1 - st * st));
    if (ct <= 0)
      continue;
    const double cu = std::cos(u);
    sum += (mass(s * ct - rho * cu) - mass(s * ct + rho * cu)) * (rho / s) * cu / ct;
  }
  // the cone of directions is 2 x [0, asin(rho / s)] of the full turn 2 pi
  return 2 * sum * (0.5 * kPi / n) / (2 * kPi);
}
}

double StopWeight(const BenchResponse& b, double s)
{
  double inside;
  if (b.Source == static_cast<int>(BenchSource::Disc))
    inside = DiscInCircle(b.Size, b.StopRadius, s);
  else if (b.Source == static_cast<int>(BenchSource::Gaussian))
  {
    const double x = s / b.StopStep;
    const std::size_t i = static_cast<std::size_t>(x);
    if (i + 1 >= b.StopTable.size())
      inside = b.StopTable.empty() ? 0.0 : b.StopTable.back();
    else
      inside = b.StopTable[i] + (x - i) * (b.StopTable[i + 1] - b.StopTable[i]);
  }
  else
    inside = s < b.StopRadius ? 1.0 : 0.0;
  return b.Complement ? 1 - inside : inside;
}

namespace
{
BenchResponse ComputeStop(const TraceSettings& s)
{
  BenchResponse b;
  b.Finite = b.Stop = true;
  // the colour filter's opaque centre passes the light it does not cover, as a dark-field disc
  b.Complement = s.Mode == Cutoff::ComplementCircular || s.Mode == Cutoff::ColorFilter;
  b.Source = static_cast<int>(s.Source);
  const double f2 = s.SchlierenFocalLength;
  b.ImageHeight = s.Source == BenchSource::Point ? 0 : s.SourceSize[0] * 1e-3 * f2 / s.CollimatorFocalLength;
  b.StopRadius = 0.5 * s.StopDiameter * 1e-3;
  b.Open = 1;
  const double rho = b.StopRadius;
  std::ostringstream m;
  m.precision(4);
  m << (s.Mode == Cutoff::ColorFilter ? "a colour filter with an opaque centre"
          : b.Complement               ? "an opaque disc"
                                       : "a circular aperture")
    << " of " << s.StopDiameter << " mm in the cutoff plane";
  if (s.Mode == Cutoff::ColorFilter)
    m << " (the hue of the shift's direction: the image's spread in azimuth is not integrated)";
  m << "; ";
  double reach = 0; // the image's half width
  if (s.Source == BenchSource::Disc)
  {
    b.Size = reach = 0.5 * b.ImageHeight;
    m << "Disc: closed form (the overlap of the source's image, R' = " << b.Size * 1e3
      << " mm, with the stop, per photon; not sampled)";
  }
  else if (s.Source == BenchSource::Gaussian)
  {
    b.Size = 0.25 * b.ImageHeight;
    reach = 4 * b.Size;
    // the share inside the stop over the shift, 2048 steps out to rho + 8 sigma
    const int n = 2048;
    b.StopStep = (rho + 8 * b.Size) / n;
    b.StopTable.resize(n + 1);
    for (int i = 0; i <= n; ++i)
      b.StopTable[i] = GaussianInCircle(b.Size, rho, i * b.StopStep);
    m << "Gaussian: its share inside the stop integrated once (sigma = " << b.Size * 1e3
      << " mm) and interpolated per photon; not sampled";
  }
  else
    m << "Point: the photon passes while f2 |e| is inside the stop (a step)";
  // the measuring range: where the stop begins to cut the source's image and where it covers it
  const double a = std::max(0.0, rho - reach) / f2, c = (rho + reach) / f2;
  b.Dark = b.Complement ? a : c;
  b.Saturation = b.Complement ? c : a;
  if (s.Source == BenchSource::Gaussian)
  {
    b.DarkWeight = 0.001;
    b.SaturatedWeight = 0.999;
  }
  // the steepest slope of the response, per radian (a point source's step has none to give)
  if (s.Source != BenchSource::Point)
  {
    const int n = 400;
    double prev = StopWeight(b, 0), steepest = 0;
    const double ds = (rho + 2 * reach) / n;
    for (int i = 1; i <= n; ++i)
    {
      const double w = StopWeight(b, i * ds);
      steepest = std::max(steepest, std::fabs(w - prev) / ds);
      prev = w;
    }
    b.Sensitivity = steepest * f2;
  }
  const double levels = std::ldexp(1.0, std::max(1, std::min(32, s.BitDepth))) - 1;
  b.Resolvable = b.Sensitivity > 0 ? 1 / (levels * b.Sensitivity) : 0;
  b.Model = m.str();
  return b;
}
}

BenchResponse ComputeBench(const TraceSettings& s)
{
  BenchResponse b;
  if ((s.Mode == Cutoff::Circular || s.Mode == Cutoff::ComplementCircular ||
        s.Mode == Cutoff::ColorFilter) && s.StopDiameter > 0)
    return ComputeStop(s);
  if (s.Source == BenchSource::Point || s.Mode != Cutoff::KnifeEdge)
    return b;
  b.Finite = true;
  b.Source = static_cast<int>(s.Source);
  const double f1 = s.CollimatorFocalLength, f2 = s.SchlierenFocalLength;
  b.ImageHeight = s.SourceSize[0] * 1e-3 * f2 / f1;
  b.Open = 1 - s.KnifeCut;
  const double a0 = b.ImageHeight;
  std::ostringstream m;
  m.precision(4);
  switch (s.Source)
  {
    case BenchSource::Disc:
    {
      const double R = 0.5 * a0;
      double lo = -1, hi = 1; // DiscShare falls from 1 to 0
      for (int i = 0; i < 200; ++i)
      {
        const double mid = 0.5 * (lo + hi);
        if (DiscShare(mid) > b.Open)
          lo = mid;
        else
          hi = mid;
      }
      const double t0 = 0.5 * (lo + hi);
      b.Size = R;
      b.Edge = t0 * R;
      b.Sensitivity = b.Open > 0 ? 2 / kPi * std::sqrt(1 - t0 * t0) * f2 / (R * b.Open) : 0;
      b.Dark = (b.Edge - R) / f2;
      b.Saturation = (b.Edge + R) / f2;
      m << "Disc: closed form (the uncovered share of the source's image, [acos t - t sqrt(1 - t^2)] / pi, "
           "per photon; not sampled); image radius R' = "
        << R * 1e3 << " mm";
      break;
    }
    case BenchSource::Gaussian:
    {
      const double sigma = 0.25 * a0, r2 = std::sqrt(2.0);
      b.Size = sigma;
      b.Edge = sigma * r2 * InverseErfc(2 * b.Open);
      const double pdf = std::exp(-0.5 * b.Edge * b.Edge / (sigma * sigma)) / (sigma * std::sqrt(2 * kPi));
      b.Sensitivity = b.Open > 0 ? f2 * pdf / b.Open : 0;
      // no finite edge: full dark and saturation where the passing share is 0.1 % and 99.9 %
      b.Dark = (b.Edge - sigma * r2 * InverseErfc(0.002)) / f2;
      b.Saturation = (b.Edge - sigma * r2 * InverseErfc(1.998)) / f2;
      b.DarkWeight = 0.001;
      b.SaturatedWeight = 0.999;
      m << "Gaussian: closed form (erfc((d - s) / (sigma sqrt 2)) / 2 per photon; not sampled); image "
           "sigma = "
        << sigma * 1e3 << " mm (1/e^2 diameter " << a0 * 1e3 << " mm); range at 0.1 % and 99.9 %";
      break;
    }
    default:
    {
      const double a = b.Open * a0;
      b.Size = a0;
      b.Edge = 0.5 * a0 - a;
      b.Sensitivity = a > 0 ? f2 / a : 0;
      b.Dark = -a / f2;
      b.Saturation = (a0 - a) / f2;
      m << (s.Source == BenchSource::Slit ? "Slit" : "Rectangle")
        << ": closed form (clamp((a + s) / a0) per photon; not sampled); image height a0 = " << a0 * 1e3
        << " mm, uncovered a = " << a * 1e3 << " mm";
    }
  }
  // one grey level of the film, full scale at the uncut source image (I = 1), is 1 / (2^bits - 1)
  // of I; the response's slope at eps = 0 is Open * Sensitivity per radian
  const double levels = std::ldexp(1.0, std::max(1, std::min(32, s.BitDepth))) - 1;
  b.Resolvable = b.Sensitivity > 0 ? 1 / (levels * b.Open * b.Sensitivity) : 0;
  b.Model = m.str();
  return b;
}

} // namespace schlieren
