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

// x with erfc(x) = y, y in (0, 2), by bisection (erfc is decreasing); clamped to [-10, 10]
double InverseErfc(double y)
{
  double lo = -10, hi = 10;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    if (std::erfc(mid) > y)
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
  return (std::acos(t) - t * std::sqrt(1 - t * t)) / kPi;
}
}

BenchResponse ComputeBench(const TraceSettings& s)
{
  BenchResponse b;
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
