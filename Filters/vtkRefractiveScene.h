// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkRefractiveScene
 * @brief   analytic refractive-index scenes with known answers, on an image grid
 *
 * vtkRefractiveScene is a source that fills a regular grid with the refractive index of an analytic
 * scene (schlieren::FillScene): a uniform medium, a weak Gaussian sphere, a Luneburg lens, a
 * linear gradient or a plane normal shock in air. These scenes have closed-form ray paths and
 * deflections, which makes them the known answers of the tests and a quick demo of the plugin.
 *
 * The output is a vtkImageData with the point arrays `n_minus_1` (float, n - 1, the active scalars)
 * and `density` (float, kg/m^3: the density of air that has this index by Gladstone-Dale,
 * rho = (n - 1) / 2.256e-4 m^3/kg at 632.8 nm).
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
    NORMAL_SHOCK = 4
  };

  ///@{
  /**
   * The scene to fill (a SceneType). Default GAUSSIAN_SPHERE.
   */
  vtkSetClampMacro(Scene, int, UNIFORM, NORMAL_SHOCK);
  vtkGetMacro(Scene, int);
  void SetSceneToUniform() { this->SetScene(UNIFORM); }
  void SetSceneToGaussianSphere() { this->SetScene(GAUSSIAN_SPHERE); }
  void SetSceneToLuneburgLens() { this->SetScene(LUNEBURG_LENS); }
  void SetSceneToLinearGradient() { this->SetScene(LINEAR_GRADIENT); }
  void SetSceneToNormalShock() { this->SetScene(NORMAL_SHOCK); }
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
   * n - 1 of the uniform scene, or at the centre of the Gaussian sphere (dimensionless).
   * Default 1e-4.
   */
  vtkSetClampMacro(Amplitude, double, -0.9, 10.0);
  vtkGetMacro(Amplitude, double);
  ///@}

  ///@{
  /**
   * The Gaussian sphere's 1/e radius, or the normal shock's tanh thickness, world units (> 0).
   * Default 0.25.
   */
  vtkSetClampMacro(Width, double, 1e-12, VTK_DOUBLE_MAX);
  vtkGetMacro(Width, double);
  ///@}

  ///@{
  /**
   * The Luneburg lens radius, world units (> 0). Default 1.
   */
  vtkSetClampMacro(Radius, double, 1e-12, VTK_DOUBLE_MAX);
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
  vtkSetClampMacro(Mach, double, 1.0, 100.0);
  vtkGetMacro(Mach, double);
  ///@}

  ///@{
  /**
   * NORMAL_SHOCK: the upstream density, kg/m^3 (> 0; clamped to [1e-12, 1e6]). Default 1.2.
   */
  vtkSetClampMacro(Density, double, 1e-12, 1e6);
  vtkGetMacro(Density, double);
  ///@}

protected:
  vtkRefractiveScene();
  ~vtkRefractiveScene() override;

  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /** Spacing and origin of the whole grid from Dimensions and Bounds; false (with an error) if invalid. */
  bool ComputeGrid(double origin[3], double spacing[3]);

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

private:
  vtkRefractiveScene(const vtkRefractiveScene&) = delete;
  void operator=(const vtkRefractiveScene&) = delete;
};

#endif
