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

#include <cstddef>

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
  NormalShock = 4,    ///< a plane normal shock in air at x = Center[0], normal along x: upstream
                      ///< density Density (x < Center[0]), downstream Density * rho2/rho1 for Mach
                      ///< (gamma = 1.4), a tanh profile of thickness Width; n - 1 = K_air rho
  HeliumPlume = 5,    ///< a round helium jet rising along +y into still air at 293.15 K, 1 atm (the
                      ///< paper's air/helium case): nozzle of radius Radius at y = Center[1] -
                      ///< Width/2, helium mass fraction Amplitude there; the jet spreads at 0.07 per
                      ///< unit height with puffing bulges every 3.3 nozzle radii, its axis fraction
                      ///< falls as (Radius / width)^1.6 and its profile goes from a top hat to a
                      ///< Gaussian over the height Width; n - 1 by the mass-weighted Gladstone-Dale
                      ///< mixture at the ideal-gas density (SchlierenIndexModels)
  BlastWave = 6       ///< a spherical blast in air about Center: Sedov-Taylor radius
                      ///< R = Radius (Time)^(2/5), a strong-shock density jump (6 rho0 for
                      ///< gamma = 1.4) of thickness Width behind which the density falls as
                      ///< (r/R)^7.5; rho0 = Density; for time series (Time > 0)
};

/** Normal-shock density ratio rho2/rho1 = (g+1) M^2 / ((g-1) M^2 + 2). */
double NormalShockDensityRatio(double mach, double gamma = 1.4);

struct SceneParameters
{
  double Amplitude = 1e-4;
  double Width = 0.25;
  double Radius = 1.0;
  double Center[3] = { 0, 0, 0 };
  double GradientA = 1.0;
  double GradientB = 0.01;
  double Mach = 2.0;      ///< NormalShock
  double Density = 1.2;   ///< NormalShock, BlastWave: ambient density, kg/m^3
  double Time = 1.0;      ///< BlastWave: time in units of the time the shock takes to reach Radius
};

/** Everything a scene models at one point. */
struct ScenePointValues
{
  double NMinus1 = 0;
  double Density = 0;          ///< kg/m^3 (for analytic index scenes: air with that index)
  double MixtureFraction = 0;  ///< helium mass fraction (HeliumPlume), else 0
};

/** The fields of a scene at one world point. */
ScenePointValues ScenePoint(Scene scene, const SceneParameters& p, double x, double y, double z);

/** The index n - 1 of a scene at one world point. */
double SceneIndex(Scene scene, const SceneParameters& p, double x, double y, double z);

/** Fills n - 1 (and, where not null, density and helium mass fraction) on a grid.
 * Throws schlieren::Error on invalid parameters (e.g. n^2 <= 0 somewhere for LinearGradient). */
void FillScene(Scene scene, const SceneParameters& p, const int dims[3], const double origin[3],
  const double spacing[3], float* nMinus1, float* density, float* mixtureFraction = nullptr);

const char* SceneName(Scene scene);

/** Opaque bodies a scene may hold (the solid mask of Volume::Solid). */
enum class Body
{
  None = 0,
  Sphere = 1,  ///< the points within Radius of Center
  Cylinder = 2 ///< the points within Radius of the line through Center along Axis (unit)
};

struct BodyParameters
{
  Body Shape = Body::None;
  double Radius = 0.25;
  double Center[3] = { 0, 0, 0 };
  double Axis[3] = { 1, 0, 0 };
};

/** Fills `solid` (one byte per grid point, x fastest) with 1 inside the body, 0 elsewhere;
 * returns the number of solid points. Throws schlieren::Error on a radius <= 0 or a zero axis. */
std::size_t FillBody(const BodyParameters& b, const int dims[3], const double origin[3],
  const double spacing[3], unsigned char* solid);

const char* BodyName(Body body);

/** RefractiveScene's property ranges (its domains in Schlieren.xml, the C++ filter's table):
 * Amplitude [-0.9, 10], Width, Radius, BodyRadius > 0 and finite, Mach [1, 100], Density
 * [1e-12, 1e6], Time [1e-6, 1e6], and finite Center, GradientA, GradientB, BodyCenter and BodyAxis.
 * Throws schlieren::Error naming the property, the value and the range (every front end's check). */
void CheckSceneParameters(const SceneParameters& p, const BodyParameters& b);

} // namespace schlieren

#endif
