// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenScenes.h
 * @brief Analytic refractive scenes with known answers (see ../shared/ORACLES.md), VTK-free.
 *
 * Each scene fills n-1 at the points of a regular grid (x fastest). Where asked, it also writes the
 * density of air that has that index by Gladstone-Dale (rho = (n-1) / K_air, K_air = 2.256e-4 m^3/kg
 * at 632.8 nm), so that density-based models can be tested on the same scenes.
 */
#ifndef SchlierenScenes_h
#define SchlierenScenes_h

namespace schlieren
{

/** Gladstone-Dale constant of air at 632.8 nm, m^3/kg (0.2256 cm^3/g). */
constexpr double GladstoneDaleAir = 0.2256e-3;

enum class Scene
{
  Uniform = 0,        ///< n - 1 = Amplitude everywhere
  GaussianSphere = 1, ///< n = 1 + Amplitude exp(-r^2 / Width^2), r from Center
  LuneburgLens = 2,   ///< n = sqrt(2 - r^2 / Radius^2) for r < Radius, 1 outside
  LinearGradient = 3, ///< n^2 = GradientA + GradientB (y - Center[1])
  NormalShock = 4     ///< a plane normal shock in air at x = Center[0], normal along x: upstream
                      ///< density Density (x < Center[0]), downstream Density * rho2/rho1 for Mach
                      ///< (gamma = 1.4), a tanh profile of thickness Width; n - 1 = K_air rho
};

/** Normal-shock density ratio rho2/rho1 = (g+1) M^2 / ((g-1) M^2 + 2). */
double NormalShockDensityRatio(double mach, double gamma = 1.4);
/** Normal-shock pressure ratio p2/p1 = 1 + 2 g (M^2 - 1) / (g + 1). */
double NormalShockPressureRatio(double mach, double gamma = 1.4);

struct SceneParameters
{
  double Amplitude = 1e-4;
  double Width = 0.25;
  double Radius = 1.0;
  double Center[3] = { 0, 0, 0 };
  double GradientA = 1.0;
  double GradientB = 0.01;
  double Mach = 2.0;      ///< NormalShock
  double Density = 1.2;   ///< NormalShock: upstream density, kg/m^3
};

/** The index n - 1 of a scene at one world point. */
double SceneIndex(Scene scene, const SceneParameters& p, double x, double y, double z);

/** Fills n - 1 (and, if `density` is not null, the Gladstone-Dale air density) on a grid.
 * Throws schlieren::Error on invalid parameters (e.g. n^2 <= 0 somewhere for LinearGradient). */
void FillScene(Scene scene, const SceneParameters& p, const int dims[3], const double origin[3],
  const double spacing[3], float* nMinus1, float* density);

const char* SceneName(Scene scene);

} // namespace schlieren

#endif
