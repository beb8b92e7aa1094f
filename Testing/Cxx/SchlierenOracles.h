// SPDX-License-Identifier: BSD-3-Clause
// Known-answer scenes (../shared/ORACLES.md) as ready-made cases: a volume, a view, rays (Auto's
// pilot rays: a 16 x 16 grid over the film, so that a whole image is judged) and the error of a set
// of traced records against the closed form. Shared by the accuracy test and the accuracy chart,
// so that both hold the tracer to one definition of each answer.
#ifndef SchlierenOracles_h
#define SchlierenOracles_h

#include "SchlierenTesting.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

namespace schtest
{
constexpr double kPi = 3.14159265358979323846;

/** ORACLES, weak Gaussian sphere n = 1 + A exp(-r^2/s^2) seen along an axis: the deflection at film
 * point (a, b) from the centre, eps = -(2 sqrt(pi) A / s) (a, b) exp(-rho^2 / s^2). */
inline void GaussianDeflection(double A, double s, double a, double b, double e[2])
{
  const double f = -(2 * std::sqrt(kPi) * A / s) * std::exp(-(a * a + b * b) / (s * s));
  e[0] = f * a;
  e[1] = f * b;
}

/** Its largest magnitude, sqrt(2 pi) A e^(-1/2) (at rho = s / sqrt(2); ORACLES: 1.5203 A). */
inline double GaussianMaxDeflection(double A)
{
  return std::sqrt(2 * kPi) * A * std::exp(-0.5);
}

inline schlieren::TraceSettings Beam(double dx, double dy, double dz, double ux, double uy, double uz)
{
  schlieren::TraceSettings s;
  s.Device = schlieren::Backend::CPU;
  // a film behind the volume (not a camera focused inside it): landing positions are where the
  // rays really go, which the known answers describe
  s.Mode = schlieren::Cutoff::Shadowgraph;
  s.ViewDirection[0] = dx;
  s.ViewDirection[1] = dy;
  s.ViewDirection[2] = dz;
  s.ViewUp[0] = ux;
  s.ViewUp[1] = uy;
  s.ViewUp[2] = uz;
  return s;
}

struct OracleCase
{
  std::string Name;
  std::shared_ptr<SceneVolume> SV;
  schlieren::TraceSettings S;
  std::vector<float> AB;
  /** Largest deflection error (radians) against the known answer; 1e9 where a photon lands more
   * than half a pixel from where the known answer puts it (where that is known). */
  std::function<double(const std::vector<schlieren::RayRecord>&)> Error;
  double Tolerance; ///< what "accurate" means for this scene
  double Magnitude = 0; ///< the largest deflection of the known answer, radians
};

/** Gaussian sphere A = 1e-4, s = 0.25, beam along -z: eps = -(2 sqrt(pi) A / s) (x, y) e^(-rho^2/s^2). */
inline OracleCase GaussianCase(int n)
{
  using namespace schlieren;
  SceneParameters pg;
  pg.Amplitude = 1e-4;
  pg.Width = 0.25;
  OracleCase c{ "Gaussian sphere", std::make_shared<SceneVolume>(Scene::GaussianSphere, pg, n, 1.0),
    Beam(0, 0, -1, 0, 1, 0), {}, nullptr, 0 };
  c.S.Resolution[0] = c.S.Resolution[1] = 64;
  c.AB = PilotRays(c.SV->V, c.S);
  const std::vector<float> ab = c.AB;
  c.Error = [ab](const std::vector<RayRecord>& r) {
    double e = 0;
    for (std::size_t k = 0; k < r.size(); ++k)
    {
      double g[2];
      GaussianDeflection(1e-4, 0.25, ab[2 * k], ab[2 * k + 1], g);
      e = std::max(e, std::hypot(r[k].DeflX - g[0], r[k].DeflY - g[1]));
    }
    return e;
  };
  c.Magnitude = GaussianMaxDeflection(1e-4);
  c.Tolerance = 0.03 * c.Magnitude; // 3 % of max eps: above the grid's own error
  return c;
}

/** Luneburg lens R = 1, beam along x: rays through the lens leave at the far pole with direction
 * (sqrt(1 - h^2), -h); rays beside it go straight. */
inline OracleCase LuneburgCase(int n)
{
  using namespace schlieren;
  SceneParameters pl;
  OracleCase c{ "Luneburg lens", std::make_shared<SceneVolume>(Scene::LuneburgLens, pl, n, 1.0),
    Beam(1, 0, 0, 0, 0, 1), {}, nullptr, 0 };
  c.S.Resolution[0] = c.S.Resolution[1] = 64;
  c.AB = PilotRays(c.SV->V, c.S);
  const std::vector<float> ab = c.AB;
  // the rim (0.97 R < h < 1.03 R), where rays leave almost across the beam, has no usable answer
  c.Error = [ab](const std::vector<RayRecord>& r) {
    double e = 0;
    for (std::size_t k = 0; k < r.size(); ++k)
    {
      const double a = ab[2 * k], b = ab[2 * k + 1], h = std::hypot(a, b);
      if (h > 0.97 && h < 1.03)
        continue;
      const double ex = h < 1 ? -a : 0.0, ey = h < 1 ? -b : 0.0;
      e = std::max(e, double(std::hypot(r[k].DeflX - ex, r[k].DeflY - ey)));
      // and the image must be right: rays through the lens land on the pole (within half a
      // pixel, Auto's own landing criterion), the others where they started
      const double la = h < 1 ? 0.0 : a, lb = h < 1 ? 0.0 : b;
      if (std::hypot(r[k].LandA - la, r[k].LandB - lb) > 0.5 * (2.0 / 64))
        e = 1e9;
    }
    return e;
  };
  c.Tolerance = 0.01;
  c.Magnitude = 0.97; // the largest |h / R| judged
  return c;
}

/** The linear medium n^2 = 1 + 0.2 y, beam along x: y(x) = y0 + b (x - x0)^2 / (4 C^2) with
 * C^2 = 1 + 0.2 y0, for every ray: through the back face (x = 1) or, near the top, through the top
 * face where the parabola reaches y = 1. */
inline OracleCase LinearCase(int n)
{
  using namespace schlieren;
  SceneParameters pr;
  pr.GradientA = 1.0;
  pr.GradientB = 0.2;
  OracleCase c{ "linear gradient", std::make_shared<SceneVolume>(Scene::LinearGradient, pr, n, 1.0),
    Beam(1, 0, 0, 0, 1, 0), {}, nullptr, 0 };
  c.S.Resolution[0] = c.S.Resolution[1] = 64;
  c.AB = PilotRays(c.SV->V, c.S);
  const std::vector<float> ab = c.AB;
  c.Error = [ab](const std::vector<RayRecord>& r) {
    const double B = 0.2;
    double e = 0;
    for (std::size_t k = 0; k < r.size(); ++k)
    {
      const double y0 = ab[2 * k + 1], C2 = 1 + B * y0;
      double run = 2.0; // x - x0 at the exit
      if (y0 + B * run * run / (4 * C2) > 1)
        run = std::sqrt((1 - y0) * 4 * C2 / B); // leaves through the top
      const double slope = B * run / (2 * C2);
      const double ey = slope / std::sqrt(1 + slope * slope);
      const double yl = y0 + B * run * run / (4 * C2) + slope * (2.0 - run); // straight on to x = 1
      e = std::max(e, double(std::hypot(r[k].DeflX, r[k].DeflY - ey)));
      if (std::fabs(r[k].LandB - yl) > 0.5 * (2.0 / 64))
        e = 1e9;
    }
    return e;
  };
  c.Magnitude = 0.2;
  c.Tolerance = 1e-3; // 0.5 % of the largest deflection
  return c;
}

/** A Mach 2 normal shock about `thickness` voxels thick, beam at 40 degrees to it: by Snell the
 * tangential part of v = n d is conserved. Rays crossing within three voxels of the box's faces
 * are left out: there the data's one-sided differences, not the tracer, set the error. */
inline OracleCase ShockCase(int n, double thicknessVoxels = 2.0)
{
  using namespace schlieren;
  SceneParameters ps;
  ps.Mach = 2;
  ps.Density = 1.2;
  ps.Width = 0.5 * thicknessVoxels * 2.0 / (n - 1);
  const double al = 40 * kPi / 180;
  OracleCase c{ "normal shock", std::make_shared<SceneVolume>(Scene::NormalShock, ps, n, 1.0),
    Beam(std::sin(al), 0, -std::cos(al), 0, 1, 0), {}, nullptr, 0 };
  c.S.Resolution[0] = c.S.Resolution[1] = 64;
  c.AB = PilotRays(c.SV->V, c.S);
  const std::vector<float> ab = c.AB;
  const double n1 = 1 + GladstoneDaleAir * ps.Density;
  const double n2 = 1 + GladstoneDaleAir * ps.Density * NormalShockDensityRatio(ps.Mach);
  const double vz = -n1 * std::cos(al), vx = std::sqrt(n2 * n2 - vz * vz);
  // film right axis r = d0 x up = (cos al, 0, sin al); e = d . r
  const double exact = (vx / n2) * std::cos(al) + (vz / n2) * std::sin(al);
  // a ray at film coordinate a meets the shock plane x = 0 at z = a / sin al: inside the box it
  // crosses, outside it does not, nor do rays beside the box (|b| > 1)
  const double band = 3 * 2.0 / (n - 1);
  c.Error = [ab, exact, al, band](const std::vector<RayRecord>& r) {
    double e = 0;
    for (std::size_t k = 0; k < r.size(); ++k)
    {
      const double z = std::fabs(ab[2 * k] / std::sin(al)), y = std::fabs(ab[2 * k + 1]);
      if (std::fabs(z - 1) < band / std::sin(al) || std::fabs(y - 1) < band)
        continue;
      e = std::max(e, double(std::fabs(r[k].DeflX - (z < 1 && y < 1 ? exact : 0.0))));
    }
    return e;
  };
  c.Magnitude = exact;
  c.Tolerance = 0.02 * exact;
  return c;
}

/** Total samples of a set of records. */
inline double SampleCount(const std::vector<schlieren::RayRecord>& r)
{
  double s = 0;
  for (const schlieren::RayRecord& x : r)
    s += x.Samples;
  return s;
}
} // namespace schtest

#endif
