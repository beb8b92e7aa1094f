// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenScenes.h"
#include "SchlierenEngine.h"

#include <cmath>
#include <sstream>

namespace schlieren
{

double SceneIndex(Scene scene, const SceneParameters& p, double x, double y, double z)
{
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
      const double rho = p.Density * (1.0 + (r - 1.0) * 0.5 * (1.0 + std::tanh(rx / p.Width)));
      return GladstoneDaleAir * rho;
    }
  }
  return 0.0;
}

double NormalShockDensityRatio(double m, double g)
{
  return (g + 1) * m * m / ((g - 1) * m * m + 2);
}

double NormalShockPressureRatio(double m, double g)
{
  return 1 + 2 * g * (m * m - 1) / (g + 1);
}

void FillScene(Scene scene, const SceneParameters& p, const int dims[3], const double origin[3],
  const double spacing[3], float* nMinus1, float* density)
{
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
        const double n1 = SceneIndex(scene, p, x, y, z);
        if (!std::isfinite(n1) || n1 <= -1.0)
        {
          std::ostringstream msg;
          msg << SceneName(scene) << ": the index is not physical (n^2 <= 0) at (" << x << ", " << y
              << ", " << z << "); reduce GradientB or the bounds in y.";
          throw Error(msg.str());
        }
        nMinus1[idx] = static_cast<float>(n1);
        if (density)
          density[idx] = static_cast<float>(n1 / GladstoneDaleAir);
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
  }
  return "?";
}

} // namespace schlieren
