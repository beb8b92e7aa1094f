// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenScenes.h"
#include "SchlierenEngine.h"
#include "SchlierenIndexModels.h"
#include "SchlierenPhysics.h" // sch_tanh_d: the same bits on every glibc

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace schlieren
{

ScenePointValues ScenePoint(Scene scene, const SceneParameters& p, double x, double y, double z)
{
  ScenePointValues v;
  const double rx = x - p.Center[0], ry = y - p.Center[1], rz = z - p.Center[2];
  if (scene == Scene::HeliumPlume)
  {
    // height above the nozzle, which sits at Center - Width/2 (below it: the feed pipe)
    const double rise = std::max(0.0, ry + 0.5 * p.Width);
    const double r0 = p.Radius;
    // a jet that spreads at 0.07 per unit height, with puffing bulges every 3.3 nozzle radii that
    // grow as they rise
    const double s2 = std::sin(2 * 3.14159265358979323846 * rise / (3.3 * r0));
    const double width = (r0 + 0.07 * rise) * (1 + 0.25 * (rise / p.Width) * s2 * s2);
    // mass fraction on the axis falls as the jet entrains air; the profile goes from a top hat at
    // the nozzle to a Gaussian at Width
    const double axis = p.Amplitude * std::min(1.0, std::pow(r0 / width, 1.6));
    const double shape = 4.0 - 2.0 * std::min(1.0, rise / p.Width);
    const double r = std::sqrt(rx * rx + rz * rz);
    const double f = axis * std::exp(-std::pow(r / width, shape));
    const Gas he = Gas::Helium;
    const double T = 293.15, P = 101325.0;
    const double K = MixtureConstant(&he, &f, 1, Gas::Air);
    const double M = MixtureMolarMass(&he, &f, 1, Gas::Air);
    v.MixtureFraction = f;
    v.Density = IdealGasDensity(P, T, M);
    v.NMinus1 = K * v.Density;
    return v;
  }
  if (scene == Scene::BlastWave)
  {
    const double r = std::sqrt(rx * rx + ry * ry + rz * rz);
    const double R = p.Radius * std::pow(std::max(p.Time, 1e-6), 0.4);
    // inside: 6 rho0 (r/R)^7.5 (Sedov-like), outside rho0, joined over the shock thickness
    const double inner = 6.0 * std::pow(std::min(r / R, 1.0), 7.5);
    const double sw = 0.5 * (1.0 - sch_tanh_d((r - R) / p.Width));
    v.Density = p.Density * (1.0 + (inner - 1.0) * sw);
    v.NMinus1 = GladstoneDaleAir * v.Density;
    return v;
  }
  v.NMinus1 = SceneIndex(scene, p, x, y, z);
  v.Density = v.NMinus1 / GladstoneDaleAir; // air with this index (the shock's is its real density)
  return v;
}

double SceneIndex(Scene scene, const SceneParameters& p, double x, double y, double z)
{
  if (scene == Scene::HeliumPlume || scene == Scene::BlastWave)
    return ScenePoint(scene, p, x, y, z).NMinus1;
  const double rx = x - p.Center[0], ry = y - p.Center[1], rz = z - p.Center[2];
  const double r2 = rx * rx + ry * ry + rz * rz;
  switch (scene)
  {
    case Scene::Uniform:
      return p.Amplitude;
    case Scene::GaussianSphere:
      return p.Amplitude * std::exp(-r2 / (p.Width * p.Width));
    case Scene::LuneburgLens:
    {
      const double R2 = p.Radius * p.Radius;
      return r2 < R2 ? std::sqrt(2.0 - r2 / R2) - 1.0 : 0.0;
    }
    case Scene::LinearGradient:
    {
      const double n2 = p.GradientA + p.GradientB * ry;
      return n2 > 0 ? std::sqrt(n2) - 1.0 : std::nan("");
    }
    case Scene::NormalShock:
    {
      const double r = NormalShockDensityRatio(p.Mach);
      const double rho = p.Density * (1.0 + (r - 1.0) * 0.5 * (1.0 + sch_tanh_d(rx / p.Width)));
      return GladstoneDaleAir * rho;
    }
    default:
      break;
  }
  return 0.0;
}

double NormalShockDensityRatio(double m, double g)
{
  return (g + 1) * m * m / ((g - 1) * m * m + 2);
}

void FillScene(Scene scene, const SceneParameters& p, const int dims[3], const double origin[3],
  const double spacing[3], float* nMinus1, float* density, float* mixtureFraction)
{
  if (scene == Scene::HeliumPlume &&
    (!(p.Radius > 0) || !(p.Width > 0) || !(p.Amplitude >= 0 && p.Amplitude <= 1)))
    throw Error("HeliumPlume: Radius (the nozzle's) and Width (the plume's height) must be positive "
                "and Amplitude (the helium mass fraction at the nozzle) between 0 and 1.");
  if (scene == Scene::BlastWave && (!(p.Radius > 0) || !(p.Width > 0) || !(p.Density > 0)))
    throw Error("BlastWave: Radius, Width and Density must be positive.");
  if (scene == Scene::GaussianSphere && !(p.Width > 0))
    throw Error("GaussianSphere: Width must be positive.");
  if (scene == Scene::LuneburgLens && !(p.Radius > 0))
    throw Error("LuneburgLens: Radius must be positive.");
  if (scene == Scene::NormalShock && (!(p.Width > 0) || !(p.Mach >= 1) || !(p.Density > 0)))
    throw Error("NormalShock: Width and Density must be positive and Mach at least 1.");
  std::size_t idx = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    const double z = origin[2] + k * spacing[2];
    for (int j = 0; j < dims[1]; ++j)
    {
      const double y = origin[1] + j * spacing[1];
      for (int i = 0; i < dims[0]; ++i, ++idx)
      {
        const double x = origin[0] + i * spacing[0];
        const ScenePointValues pv = ScenePoint(scene, p, x, y, z);
        const double n1 = pv.NMinus1;
        if (!std::isfinite(n1) || n1 <= -1.0)
        {
          std::ostringstream msg;
          msg << SceneName(scene) << ": the index is not physical (n^2 <= 0) at (" << x << ", " << y
              << ", " << z << "); reduce GradientB or the bounds in y.";
          throw Error(msg.str());
        }
        nMinus1[idx] = static_cast<float>(n1);
        if (density)
          density[idx] = static_cast<float>(pv.Density);
        if (mixtureFraction)
          mixtureFraction[idx] = static_cast<float>(pv.MixtureFraction);
      }
    }
  }
}

const char* SceneName(Scene scene)
{
  switch (scene)
  {
    case Scene::Uniform:
      return "Uniform";
    case Scene::GaussianSphere:
      return "GaussianSphere";
    case Scene::LuneburgLens:
      return "LuneburgLens";
    case Scene::LinearGradient:
      return "LinearGradient";
    case Scene::NormalShock:
      return "NormalShock";
    case Scene::HeliumPlume:
      return "HeliumPlume";
    case Scene::BlastWave:
      return "BlastWave";
  }
  return "?";
}

std::size_t FillBody(const BodyParameters& b, const int dims[3], const double origin[3],
  const double spacing[3], unsigned char* solid)
{
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::fill(solid, solid + n, static_cast<unsigned char>(0));
  if (b.Shape == Body::None)
    return 0;
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(b.Center[a]))
    {
      // a NaN centre compares false everywhere: the body would vanish without a word
      std::ostringstream msg;
      msg << "BodyCenter has a non-finite component (" << b.Center[a] << "): give finite numbers.";
      throw Error(msg.str());
    }
  if (!(b.Radius > 0) || !std::isfinite(b.Radius))
  {
    std::ostringstream msg;
    msg << "BodyRadius is " << b.Radius << ": the body's radius must be positive and finite "
        << "(world units, > 0).";
    throw Error(msg.str());
  }
  double axis[3] = { b.Axis[0], b.Axis[1], b.Axis[2] };
  const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (b.Shape == Body::Cylinder && !(len > 0 && std::isfinite(len)))
    throw Error("The cylinder's axis must be a non-zero, finite vector.");
  for (double& a : axis)
    a = len > 0 ? a / len : 0.0;
  const double r2 = b.Radius * b.Radius;
  std::size_t count = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        double d[3] = { origin[0] + i * spacing[0] - b.Center[0],
          origin[1] + j * spacing[1] - b.Center[1], origin[2] + k * spacing[2] - b.Center[2] };
        if (b.Shape == Body::Cylinder)
        {
          const double along = d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2];
          for (int a = 0; a < 3; ++a)
            d[a] -= along * axis[a];
        }
        const bool in = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= r2;
        solid[(static_cast<std::size_t>(k) * dims[1] + j) * dims[0] + i] = in ? 1 : 0;
        count += in;
      }
  return count;
}

const char* BodyName(Body body)
{
  switch (body)
  {
    case Body::None:
      return "None";
    case Body::Sphere:
      return "Sphere";
    case Body::Cylinder:
      return "Cylinder";
  }
  return "?";
}

void CheckSceneParameters(const SceneParameters& p, const BodyParameters& b)
{
  const double inf = std::numeric_limits<double>::infinity();
  const struct
  {
    const char* Name;
    double Value, Min, Max;
  } ranges[] = { { "Amplitude", p.Amplitude, -0.9, 10.0 }, { "Width", p.Width, 1e-12, inf },
    { "Radius", p.Radius, 1e-12, inf }, { "Mach", p.Mach, 1.0, 100.0 },
    { "Density", p.Density, 1e-12, 1e6 }, { "Time", p.Time, 1e-6, 1e6 },
    { "BodyRadius", b.Radius, 1e-12, inf } };
  for (const auto& r : ranges)
    if (!(r.Value >= r.Min && r.Value <= r.Max) || std::isinf(r.Value))
    {
      std::ostringstream msg;
      msg << r.Name << " is " << r.Value << ": it must be in [" << r.Min << ", ";
      if (std::isinf(r.Max))
        msg << "a finite value]";
      else
        msg << r.Max << "]";
      msg << ".";
      throw Error(msg.str());
    }
  const struct
  {
    const char* Name;
    const double* Values;
    int Count;
  } vectors[] = { { "Center", p.Center, 3 }, { "GradientA", &p.GradientA, 1 },
    { "GradientB", &p.GradientB, 1 }, { "BodyCenter", b.Center, 3 }, { "BodyAxis", b.Axis, 3 } };
  for (const auto& v : vectors)
    for (int i = 0; i < v.Count; ++i)
      if (!std::isfinite(v.Values[i]))
      {
        std::ostringstream msg;
        msg << v.Name << (v.Count > 1 ? " has a non-finite component (" : " is not finite (")
            << v.Values[i] << "): give finite numbers.";
        throw Error(msg.str());
      }
}

} // namespace schlieren
