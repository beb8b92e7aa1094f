// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkRefractiveScene
 * @brief   analytic refractive-index scenes with known answers, on an image grid
 *
 * vtkRefractiveScene is a source that fills a regular grid with the refractive index of an analytic
 * scene (schlieren::FillScene): a uniform medium, a weak Gaussian sphere, a Luneburg lens, a
 * linear gradient, a plane normal shock in air, a helium jet rising into air or a spherical blast
 * wave. The first five have closed-form ray paths and deflections, which makes them the known
 * answers of the tests; the plume and the blast are physical scenes for demonstrations.
 *
 * The output is a vtkImageData with the point arrays `n_minus_1` (float, n - 1, the active scalars)
 * and `density` (float, kg/m^3: the gas density the scene models: for the analytic index scenes,
 * the density of air that has this index by Gladstone-Dale, rho = (n - 1) / 2.256e-4 m^3/kg at
 * 632.8 nm; for the shock and the blast, the air's density; for the plume, the mixture's ideal-gas
 * density), and for HELIUM_PLUME `mixture_fraction` (float: the helium mass fraction).
 *
 * The grid has Dimensions points (default 64 x 64 x 64) spread over Bounds (world units, default
 * [-1, 1] in each direction): spacing = (max - min) / (dimension - 1). The scene parameters are
 * Amplitude (n - 1 at the centre of a Gaussian sphere, or everywhere for the uniform scene; default
 * 1e-4), Width (the Gaussian's 1/e radius, world units, default 0.25), Radius (of the Luneburg lens,
 * default 1), Center (default 0 0 0), GradientA and GradientB (the linear medium
 * n^2 = GradientA + GradientB (y - Center_y); defaults 1 and 0.01 per world unit), Mach (default
 * 2) and Density (kg/m^3, default 1.2) for the normal shock: a plane shock at x = Center_x with its
 * normal along x, upstream density Density (x < Center_x) and downstream Density rho2/rho1,
 * rho2/rho1 = (g + 1) M^2 / ((g - 1) M^2 + 2) with g = 1.4 (2.667 at Mach 2), joined by
 * 0.5 (1 + tanh((x - Center_x) / Width)); n - 1 = 2.256e-4 m^3/kg rho.
 *
 * HELIUM_PLUME: a round jet rising along +y from a nozzle at y = Center_y - Radius into still air
 * at 293.15 K and 101325 Pa; Amplitude is the helium mass fraction on the axis at the nozzle (0 to
 * 1), Radius the nozzle's Gaussian half-width (world units, metres for a physical size); the jet
 * widens and dilutes with height, with a puffing ripple, and n - 1 is the mass-weighted
 * Gladstone-Dale mixture at the ideal-gas density. BLAST_WAVE: a spherical blast in air about
 * Center, Sedov-Taylor radius Radius Time^(2/5), a density jump to 6 Density of thickness Width
 * behind which the density falls as (r/R)^7.5; Time (default 1) in units of the time the shock
 * takes to reach Radius.
 *
 * The source produces sub-extents: under MPI each rank fills only its own piece.
 *
 * @warning A dimension of 1 gives a flat grid (spacing along it is then the width of the bounds,
 * or 1); such a grid cannot be traced.
 *
 * @sa vtkRefractiveIndex vtkSchlierenImage
 */
#ifndef vtkRefractiveScene_h
#define vtkRefractiveScene_h

#include "SchlierenFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <string>

namespace schlieren
{
struct SceneParameters;
struct BodyParameters;
}

class SCHLIERENFILTERS_EXPORT vtkRefractiveScene : public vtkImageAlgorithm
{
public:
  static vtkRefractiveScene* New();
  vtkTypeMacro(vtkRefractiveScene, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The scenes; the values are those of schlieren::Scene. */
  enum SceneType
  {
    UNIFORM = 0,
    GAUSSIAN_SPHERE = 1,
    LUNEBURG_LENS = 2,
    LINEAR_GRADIENT = 3,
    NORMAL_SHOCK = 4,
    HELIUM_PLUME = 5,
    BLAST_WAVE = 6
  };

  ///@{
  /**
   * The scene to fill (a SceneType). Default GAUSSIAN_SPHERE.
   */
  vtkSetMacro(Scene, int);
  vtkGetMacro(Scene, int);
  void SetSceneToUniform() { this->SetScene(UNIFORM); }
  void SetSceneToGaussianSphere() { this->SetScene(GAUSSIAN_SPHERE); }
  void SetSceneToLuneburgLens() { this->SetScene(LUNEBURG_LENS); }
  void SetSceneToLinearGradient() { this->SetScene(LINEAR_GRADIENT); }
  void SetSceneToNormalShock() { this->SetScene(NORMAL_SHOCK); }
  void SetSceneToHeliumPlume() { this->SetScene(HELIUM_PLUME); }
  void SetSceneToBlastWave() { this->SetScene(BLAST_WAVE); }
  ///@}

  ///@{
  /**
   * Number of grid points along x, y and z. Each must be at least 1. Default 64 64 64.
   */
  vtkSetVector3Macro(Dimensions, int);
  vtkGetVector3Macro(Dimensions, int);
  ///@}

  ///@{
  /**
   * World bounds of the grid's points: xmin, xmax, ymin, ymax, zmin, zmax. Each max must exceed
   * its min where the dimension is above 1. Default -1 1 -1 1 -1 1.
   */
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /**
   * n - 1 of the uniform scene, or at the centre of the Gaussian sphere (dimensionless); for
   * HELIUM_PLUME the helium mass fraction at the nozzle (0 to 1). Default 1e-4.
   */
  vtkSetMacro(Amplitude, double); // outside the range: an error naming it (ComputeGrid)
  vtkGetMacro(Amplitude, double);
  ///@}

  ///@{
  /**
   * The Gaussian sphere's 1/e radius, or the tanh thickness of the normal shock and of the blast
   * wave's front, world units (> 0). Default 0.25.
   */
  vtkSetMacro(Width, double); // outside the range: an error naming it (ComputeGrid)
  vtkGetMacro(Width, double);
  ///@}

  ///@{
  /**
   * The Luneburg lens radius, the helium plume's nozzle half-width, or the blast wave's radius at
   * Time 1; world units (> 0). Default 1.
   */
  vtkSetMacro(Radius, double); // outside the range: an error naming it (ComputeGrid)
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /**
   * Centre of the sphere and lens; the gradient's y reference. World units. Default 0 0 0.
   */
  vtkSetVector3Macro(Center, double);
  vtkGetVector3Macro(Center, double);
  ///@}

  ///@{
  /**
   * The linear medium n^2 = GradientA + GradientB (y - Center_y): GradientA (dimensionless,
   * default 1) and GradientB (per world unit, default 0.01). n^2 must stay positive on the grid.
   */
  vtkSetMacro(GradientA, double);
  vtkGetMacro(GradientA, double);
  vtkSetMacro(GradientB, double);
  vtkGetMacro(GradientB, double);
  ///@}

  ///@{
  /**
   * NORMAL_SHOCK: the upstream Mach number (>= 1; clamped to [1, 100]). Default 2.
   */
  vtkSetMacro(Mach, double); // outside the range: an error naming it (ComputeGrid)
  vtkGetMacro(Mach, double);
  ///@}

  ///@{
  /**
   * NORMAL_SHOCK: the upstream density; BLAST_WAVE: the ambient density; kg/m^3 (> 0; clamped to
   * [1e-12, 1e6]). Default 1.2.
   */
  vtkSetMacro(Density, double); // outside the range: an error naming it (ComputeGrid)
  vtkGetMacro(Density, double);
  ///@}

  ///@{
  /**
   * BLAST_WAVE: the time, in units of the time the shock takes to reach Radius (> 0; clamped to
   * [1e-6, 1e6]). Default 1.
   */
  vtkSetMacro(Time, double); // outside the range: an error naming it (ComputeGrid)
  vtkGetMacro(Time, double);
  ///@}

  ///@{
  /**
   * BlastWave only: the number of time steps the source offers, evenly spaced up to Time (so that
   * ParaView's animation plays the blast growing); 0 makes it a single, static scene at Time.
   * Default 10.
   */
  vtkSetMacro(TimeSteps, int); // outside the range: an error naming it (ComputeGrid)
  vtkGetMacro(TimeSteps, int);
  ///@}

  /** Opaque bodies the scene may hold; the values are those of schlieren::Body. */
  enum BodyType
  {
    NO_BODY = 0,
    SPHERE_BODY = 1,
    CYLINDER_BODY = 2
  };

  ///@{
  /**
   * An opaque body in the scene (a BodyType): the grid points inside it get 1 in the point array
   * `solid` (unsigned char, 0 elsewhere), which SchlierenImage reads: rays that meet it stop, and
   * its shadow is dark under every cutoff. The index field is left as the scene makes it (the
   * body does not change the flow). Default NO_BODY (no `solid` array).
   */
  vtkSetMacro(Body, int);
  vtkGetMacro(Body, int);
  ///@}

  ///@{
  /** The body's radius, world units (> 0). Default 0.25. */
  // not clamped: a radius <= 0 is refused with its value (a clamp made an invisible body)
  vtkSetMacro(BodyRadius, double);
  vtkGetMacro(BodyRadius, double);
  ///@}

  ///@{
  /** The sphere's centre, or a point on the cylinder's axis; world units. Default 0 0 0. */
  vtkSetVector3Macro(BodyCenter, double);
  vtkGetVector3Macro(BodyCenter, double);
  ///@}

  ///@{
  /** The cylinder's axis direction (non-zero). Default 1 0 0. */
  vtkSetVector3Macro(BodyAxis, double);
  vtkGetVector3Macro(BodyAxis, double);
  ///@}

protected:
  vtkRefractiveScene();
  ~vtkRefractiveScene() override;

public:
  /** Every request, with any exception turned into an error and a failed request. */
  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

protected:

  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /** Spacing and origin of the whole grid from Dimensions and Bounds; false (with an error) if invalid. */
  bool ComputeGrid(double origin[3], double spacing[3]);

  /** The properties as the engine's scene and body parameters (one place for the check and the fill). */
  void EngineParameters(schlieren::SceneParameters& p, schlieren::BodyParameters& b) const;

  int Scene = GAUSSIAN_SPHERE;
  int Dimensions[3] = { 64, 64, 64 };
  double Bounds[6] = { -1, 1, -1, 1, -1, 1 };
  double Amplitude = 1e-4;
  double Width = 0.25;
  double Radius = 1.0;
  double Center[3] = { 0, 0, 0 };
  double GradientA = 1.0;
  double GradientB = 0.01;
  double Mach = 2.0;
  double Density = 1.2;
  double Time = 1.0;
  int TimeSteps = 10;
  int Body = NO_BODY;
  double BodyRadius = 0.25;
  double BodyCenter[3] = { 0, 0, 0 };
  double BodyAxis[3] = { 1, 0, 0 };

private:
  vtkRefractiveScene(const vtkRefractiveScene&) = delete;
  void operator=(const vtkRefractiveScene&) = delete;

  /**
   * The scene's arrays (n - 1, density, the plume's mixture fraction, the body's `solid`) on the
   * piece of `dims` points from `pieceOrigin`, added to `output`; "" or the error for the user.
   */
  std::string FillPiece(vtkInformation* outInfo, vtkImageData* output, const int dims[3],
    const double pieceOrigin[3], const double spacing[3]);
};

#endif
