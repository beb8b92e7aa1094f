// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSchlierenImage
 * @brief   traces curved light rays through a refractive-index volume into a schlieren image
 *
 * vtkSchlierenImage takes a vtkImageData with the point array `n_minus_1` (n - 1, dimensionless)
 * and traces a collimated beam through it with the schlieren engine (OpenCL, or the C++ build of
 * the same physics). The output is a 2D vtkImageData, the film: its spacing is the pixel size and
 * its origin the centre of pixel (0, 0), both in world units of the film plane (measured from the
 * volume's centre along the film's x = ViewDirection x ViewUp and y = ViewUp axes), with the point
 * arrays `intensity` (float, the active scalars) and `deflection` (float, 2 components: the mean
 * exit-direction change along film x and y, radians), and the field data `cutoff_scale` (the k
 * used), `backend` and `device` (strings), `photons`, `samples` and `failed_rays`.
 *
 * Settings and defaults:
 * - ViewDirection (0 0 -1): the beam's direction, world vector; ViewUp (0 1 0): film "up".
 * - Resolution (512 512): film pixels.
 * - Passes (4, at least 1): progressive passes, one jittered photon per pixel each.
 * - StepSize (0.5 voxels, in (0.01, 64]): the base integration step.
 * - Integrator (EULER): EULER or MIDPOINT.
 * - Cutoff (KNIFE_EDGE): KNIFE_EDGE (I = 0.5 - k e.a) or SHADOWGRAPH (photon density on a film
 *   FilmDistance world units behind the volume's box).
 * - KnifeAngle (0 degrees: knife normal along film x); CutoffScale (k, 0 = automatic: the largest
 *   deflection maps to full contrast).
 * - Jitter (on: photons start at random points of their pixels; off: at the centres) and
 *   Seed (1) for the jitter; Backend (AUTO: OpenCL if a device works, else the CPU with a warning;
 *   OPENCL: OpenCL or an error; CPU).
 *
 * The tracer needs the whole volume. On one process it asks for the whole input extent. Under MPI
 * (the global controller has N > 1 processes) each rank asks for its own piece; the pieces are
 * gathered on every rank, each rank traces the pixels p with p % N == rank, the film sums are
 * reduced to rank 0, and rank 0 outputs the whole image (the others an empty one). The image is
 * that of a single process.
 *
 * @sa vtkRefractiveIndex vtkRefractiveScene
 */
#ifndef vtkSchlierenImage_h
#define vtkSchlierenImage_h

#include "SchlierenFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class SCHLIERENFILTERS_EXPORT vtkSchlierenImage : public vtkImageAlgorithm
{
public:
  static vtkSchlierenImage* New();
  vtkTypeMacro(vtkSchlierenImage, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Integrators; the values are those of schlieren::Integrator. */
  enum IntegratorType
  {
    EULER = 0,
    MIDPOINT = 1
  };

  /** Cutoffs; the values are those of schlieren::Cutoff. */
  enum CutoffType
  {
    KNIFE_EDGE = 0,
    SHADOWGRAPH = 1
  };

  /** Backends; the values are those of schlieren::Backend. */
  enum BackendType
  {
    AUTO = 0,
    OPENCL = 1,
    CPU = 2
  };

  ///@{
  /**
   * The direction the beam travels, a world vector (need not be unit). Default 0 0 -1.
   */
  vtkSetVector3Macro(ViewDirection, double);
  vtkGetVector3Macro(ViewDirection, double);
  ///@}

  ///@{
  /**
   * The film's "up", a world vector (made orthogonal to ViewDirection). Default 0 1 0.
   */
  vtkSetVector3Macro(ViewUp, double);
  vtkGetVector3Macro(ViewUp, double);
  ///@}

  ///@{
  /**
   * Film pixels along x and y. Default 512 512.
   */
  vtkSetVector2Macro(Resolution, int);
  vtkGetVector2Macro(Resolution, int);
  ///@}

  ///@{
  /**
   * Progressive passes, each one jittered photon per pixel. Must be at least 1 (0 is reported as
   * an error, not clamped). Default 4.
   */
  vtkSetMacro(Passes, int);
  vtkGetMacro(Passes, int);
  ///@}

  ///@{
  /**
   * The base integration step, in voxels (of the smallest spacing). Clamped to [0.01, 64].
   * Default 0.5.
   */
  vtkSetClampMacro(StepSize, double, 0.01, 64.0);
  vtkGetMacro(StepSize, double);
  ///@}

  ///@{
  /**
   * The ray integrator (an IntegratorType). Default EULER.
   */
  vtkSetClampMacro(Integrator, int, EULER, MIDPOINT);
  vtkGetMacro(Integrator, int);
  ///@}

  ///@{
  /**
   * The cutoff that forms the image (a CutoffType). Default KNIFE_EDGE.
   */
  vtkSetClampMacro(Cutoff, int, KNIFE_EDGE, SHADOWGRAPH);
  vtkGetMacro(Cutoff, int);
  ///@}

  ///@{
  /**
   * The knife's normal in the film plane, degrees from the film's x axis. Default 0.
   */
  vtkSetMacro(KnifeAngle, double);
  vtkGetMacro(KnifeAngle, double);
  ///@}

  ///@{
  /**
   * The cutoff scale k (per radian of deflection); 0 means automatic: the largest deflection maps
   * to full contrast. Clamped to [0, 1e12]. Default 0.
   */
  vtkSetClampMacro(CutoffScale, double, 0.0, 1e12);
  vtkGetMacro(CutoffScale, double);
  ///@}

  ///@{
  /**
   * Distance of the film behind the back of the volume's box, world units (>= 0). Default 0.
   */
  vtkSetClampMacro(FilmDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(FilmDistance, double);
  ///@}

  ///@{
  /**
   * Whether photons start at random points inside their pixels (on, the default: passes then
   * sample the pixel's area) or at the pixel centres (off: every pass is the same; for tests and
   * pixel-exact comparisons).
   */
  vtkSetMacro(Jitter, bool);
  vtkGetMacro(Jitter, bool);
  vtkBooleanMacro(Jitter, bool);
  ///@}

  ///@{
  /**
   * Seed of the photons' jitter. Default 1.
   */
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /**
   * Where to trace (a BackendType). Default AUTO.
   */
  vtkSetClampMacro(Backend, int, AUTO, CPU);
  vtkGetMacro(Backend, int);
  ///@}

protected:
  vtkSchlierenImage();
  ~vtkSchlierenImage() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double ViewDirection[3] = { 0, 0, -1 };
  double ViewUp[3] = { 0, 1, 0 };
  int Resolution[2] = { 512, 512 };
  int Passes = 4;
  double StepSize = 0.5;
  int Integrator = EULER;
  int Cutoff = KNIFE_EDGE;
  double KnifeAngle = 0.0;
  double CutoffScale = 0.0;
  double FilmDistance = 0.0;
  bool Jitter = true;
  int Seed = 1;
  int Backend = AUTO;

private:
  vtkSchlierenImage(const vtkSchlierenImage&) = delete;
  void operator=(const vtkSchlierenImage&) = delete;
};

#endif
