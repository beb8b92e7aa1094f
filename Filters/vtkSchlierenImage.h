// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSchlierenImage
 * @brief   traces curved light rays through a refractive-index volume into a schlieren image
 *
 * vtkSchlierenImage takes a vtkImageData with the point array `n_minus_1` (n - 1, dimensionless)
 * and traces a collimated beam through it with the schlieren engine (OpenCL, or the C++ build of
 * the same physics). Where the input has the point array `solid` (vtkRefractiveIndex,
 * vtkRefractiveScene: non-zero in a solid body), rays stop where they meet a body: its shadow is
 * dark under every cutoff, and those rays are counted, not failed. The output is a 2D vtkImageData, the film: its spacing is the pixel size and
 * its origin the centre of pixel (0, 0), both in world units of the film plane (measured from the
 * volume's centre along the film's x = ViewDirection x ViewUp and y = ViewUp axes).
 *
 * Point arrays of the output:
 * - `intensity` (float, the active scalars): the image the cutoff forms;
 * - `deflection` (float, 2 components): the mean exit-direction change along film x and y, radians;
 * - `rgb` (float, 3 components in [0, 1]; ColorFilter: hue from the direction of the
 *   deflection, value k|e|; a WavelengthRange: the colour of the light that reached the pixel);
 * - `phase` (float, radians; Interferometry only): 2 pi / Wavelength times the optical path
 *   excess against the index where the ray entered;
 * - `bos_displacement` (float, 2 components, world units; BOS only): the apparent shift of the
 *   background, about -Z eps for a background Z behind the object;
 * - `error_estimate` (float, radians; EstimateError only): the step-doubling estimate of the
 *   deflection error per pixel;
 * - `blocked` (float in [0, 1]; where the input has a body): the fraction of the photons emitted
 *   through the pixel that a body stopped.
 *
 * Field data: `cutoff_scale` (the k used), `backend` and `device` (strings), `photons`,
 * `samples`, `samples_per_ray`, `failed_rays`, `missed_rays`, `underresolved_rays` (rays whose
 * steps jumped over a feature), `side_rays` (rays that left through a side of the box), `blocked_rays` (rays a solid body stopped),
 * `max_drift` (largest | |v| - n | at exit), `max_error` (EstimateError: the largest estimate),
 * `integrator` (string: the integrator traced with) and `step_size` (voxels: the step traced with),
 * `reconstruction` (string: Trilinear or Cubic, as traced),
 * `octree` (1 if the octree levels were used, else 0) and, for Integrator AUTO_INTEGRATOR (or
 * Reconstruction AUTO_RECONSTRUCTION),
 * `auto_report` (string: what Auto chose and why), `expected_error` (radians: the chosen setting's
 * error on the pilot rays), `auto_tolerance` (radians, as applied), `auto_met` (1 if a
 * candidate met it) and `auto_floor` (radians: where the tolerance was below the smallest error the
 * pilot can tell apart, that floor, at which the cheapest candidate was taken; else 0),
 * `auto_reference_error` (radians: the tricubic reference's own error, measured against the field
 * sampled at twice the spacing where the tolerance may be within its reach; else 0; 1.5 times it is a
 * floor, and a tolerance below it is reported not reachable on this grid) and
 * `auto_reused` (1: only the view changed since the last pilot, whose choice was kept).
 * With a finite Source under KnifeEdge (docs/BENCH.md): `bench_sensitivity` (dI/I per radian),
 * `bench_range` (2 values, radians: full dark, saturation), `bench_resolvable_deflection` (radians
 * per grey level of BitDepth), `bench_saturated_share`, `bench_dark_share` and `bench_model`.
 * With a Camera (docs/BENCH.md "Camera"): `camera_magnification`, `camera_model`, and with Lens
 * `camera_aperture` (m), `camera_blur_per_depth`, `camera_depth_of_field` (world units: the blur
 * within one film pixel), `camera_aperture_samples`; under BOS `bos_magnification`,
 * `bos_displacement_per_radian` (m on the sensor), `bos_pixels_per_radian`, `bos_blur` (m on the
 * sensor), `bos_blur_pixels`; with Lens and KnifeEdge `focusing_effective_f2` (m).
 * What the user should know (fallbacks, failed or under-resolved rays, Auto that found no setting
 * within its tolerance) is reported with vtkWarningMacro; Auto's choice is logged (vtkLog INFO).
 *
 * Settings and defaults:
 * - ViewDirection (0 0 -1): the beam's direction, world vector; ViewUp (0 1 0): film "up".
 * - Resolution (512 512): film pixels.
 * - Passes (4, at least 1): progressive passes, one jittered photon per pixel each.
 * - StepSize (0.5 voxels, in [0.01, 1000]): the base integration step.
 * - Integrator (EULER): EULER (the paper's), VERLET (velocity Verlet: second order at Euler's one
 *   sample a step), MIDPOINT, RK4, STRAIGHT (line of sight: grad n
 *   integrated along the unbent ray) or AUTO_INTEGRATOR (the cheapest of those, and a step, that
 *   meets Tolerance on a pilot of 16 x 16 rays; StepSize is then ignored).
 * - Reconstruction (TRILINEAR): TRILINEAR (central differences, trilinear: second order), CUBIC
 *   (fourth-order differences and tricubic sampling where the data is smooth, the trilinear scheme
 *   beside jumps; StepSize only through smooth data, a voxel at most from cells near a jump) or
 *   AUTO_RECONSTRUCTION (CUBIC where the trilinear scheme's error, estimated on the pilot rays,
 *   exceeds half the Tolerance, or where it is cheaper at it).
 * - Tolerance (radians, default 0 = 1 % of the largest deflection of the pilot rays): Auto's error
 *   allowance on the deflection.
 * - KeepInvariant (off): hold |v| = n after every step. EstimateError (off): trace each ray again
 *   at twice the step and output `error_estimate`.
 * - UseOctree (on): where the input has the point array `octree_level` (vtkRefractionOctree),
 *   step across uniform blocks; the tolerance it was built for comes from the field data
 *   `octree_tolerance`.
 * - Cutoff (KNIFE_EDGE): KNIFE_EDGE (I = 0.5 - k e.a), SHADOWGRAPH (photon density on a film
 *   FilmDistance world units behind the volume's box), CIRCULAR (I = 1 - k|e|),
 *   COMPLEMENT_CIRCULAR (I = k|e|), COLOR_FILTER (`rgb`), INTERFEROMETRY (I = (1 + cos(phase -
 *   reference)) / 2, `phase`) or BOS (a background pattern seen through the flow,
 *   `bos_displacement`).
 * - KnifeAngle (0 degrees: knife normal along film x); CutoffScale (k, 0 = automatic: the largest
 *   deflection maps to full contrast).
 * - Wavelength (632.8 nm) and ReferenceTilt (0 fringes per world unit along film x) for
 *   INTERFEROMETRY; world units are taken as metres for the phase.
 * - BackgroundDistance (1 world unit from the front of the volume's box), BackgroundPattern (DOTS or
 *   STRIPES) and BackgroundPeriod (0 = 6 pixels) for BOS.
 * - Filter (NO_FILTER, GAUSSIAN of standard deviation FilterWidth pixels, or CONE of radius
 *   FilterWidth / sqrt(passes) pixels) and FilterWidth (1 pixel).
 * - RussianRoulette (off): photon killing instead of energy weighting (needs a CutoffScale for the
 *   knife and circular cutoffs): the same mean, more noise.
 * - Jitter (on: photons start at random points of their pixels; off: at the centres),
 *   JitterPattern (LATTICE: one offset per pass, the pixel grid shifted; RANDOM: one per pixel) and
 *   Seed (1) for the jitter; Backend (AUTO: OpenCL if a device works, else the CPU with a warning;
 *   OPENCL: OpenCL or an error; CPU).
 * - DeviceName (empty): a substring of the OpenCL device's name; empty: SCHLIEREN_OPENCL_DEVICE,
 *   else the first GPU, else the first device. Threads (0): threads of the CPU backend; 0:
 *   SCHLIEREN_CPU_THREADS, else all cores.
 *
 * On one process it asks for the whole input extent. Under MPI (the global controller has N > 1
 * processes) each rank asks for its own piece and, with TraceInPieces (the default), keeps it:
 * with a few ghost layers from its neighbours it traces the rays in its piece and hands a ray that
 * leaves it to the rank that owns where it went; rank 0 puts the photons on the film and outputs
 * the whole image (the others an empty one): the image of a single process (docs/PARALLEL.md).
 * Where that is not available (Reconstruction CUBIC or AUTO_RECONSTRUCTION, EstimateError, a solid
 * body) or TraceInPieces is off, the pieces are gathered on every rank, each rank traces the pixels
 * p with p % N == rank, and the film sums are added across the ranks. The octree levels of the
 * pieces stop at the pieces' borders: under MPI the levels are recomputed from the field data
 * `octree_tolerance` and `octree_max_level` (see vtkRefractionOctree); in pieces up to level 3.
 *
 * The filter only adapts (reads the properties and the piece's arrays, writes the image and its
 * field data): the engine's schlieren::TraceSession does the work and keeps the packed volume and
 * the film sums between updates, and its collective steps go through
 * schlieren::ControllerParallel.
 *
 * @sa vtkRefractiveIndex vtkRefractiveScene vtkRefractionOctree
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
  /** Newer than any output while the image shown is one an aborted update left (traced again). */
  vtkMTimeType GetMTime() override;

  /** Reconstructions of the field between grid points; the values are those of
   * schlieren::Reconstruction. */
  enum ReconstructionType
  {
    TRILINEAR = 0,
    CUBIC = 1,
    AUTO_RECONSTRUCTION = 2
  };

  /** Integrators; the values are those of schlieren::Integrator. */
  enum IntegratorType
  {
    EULER = 0,
    MIDPOINT = 1,
    RK4 = 2,
    STRAIGHT = 3,
    AUTO_INTEGRATOR = 4,
    VERLET = 5
  };

  /** Cutoffs; the values are those of schlieren::Cutoff. */
  enum CutoffType
  {
    KNIFE_EDGE = 0,
    SHADOWGRAPH = 1,
    CIRCULAR = 2,
    COMPLEMENT_CIRCULAR = 3,
    COLOR_FILTER = 4,
    INTERFEROMETRY = 5,
    BOS = 6
  };

  /** BOS background patterns (TraceSettings::BackgroundPattern). */
  enum BackgroundPatternType
  {
    DOTS = 0,
    STRIPES = 1
  };

  /** Film filters; the values are those of schlieren::FilmFilter. */
  enum FilterType
  {
    NO_FILTER = 0,
    GAUSSIAN = 1,
    CONE = 2
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
   * What the film frames: VOLUME_FRAME (0, the default) the projection of the volume's box;
   * SILHOUETTE_FRAME (1) the data's silhouette seen along the view (the points that refract or lie
   * in a body), Resolution and square pixels kept. The frame is found once per change of the
   * input or of any property but the view, Resolution and Passes, and kept while the camera
   * follows. Field data: film_extent, film_frame_share, film_frame_kept.
   */
  enum
  {
    VOLUME_FRAME = 0,
    SILHOUETTE_FRAME = 1
  };
  vtkSetMacro(Framing, int);
  vtkGetMacro(Framing, int);
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
   * At most this many of Passes are traced (0: no limit, the default). The GUI's refinement
   * raises it in steps up to Passes, so that Passes stays the user's target.
   */
  vtkSetMacro(PassLimit, int);
  vtkGetMacro(PassLimit, int);
  ///@}

  ///@{
  /**
   * The base integration step, in voxels (of the smallest spacing). Valid range [0.01, 1000]:
   * a value outside it is an error when the filter runs (never clamped). Default 0.5.
   */
  vtkSetMacro(StepSize, double);
  vtkGetMacro(StepSize, double);
  ///@}

  ///@{
  /**
   * The ray integrator (an IntegratorType). Default EULER. AUTO_INTEGRATOR picks the cheapest
   * integrator and step that meet Tolerance (StepSize is then ignored).
   */
  vtkSetMacro(Integrator, int);
  vtkGetMacro(Integrator, int);
  ///@}

  ///@{
  /**
   * How n - 1 and grad n are reconstructed between grid points (a ReconstructionType). Default
   * TRILINEAR: central differences and trilinear interpolation (second order in the spacing).
   * CUBIC: fourth-order differences and tricubic interpolation where the data is smooth, the
   * trilinear scheme beside jumps (shocks, interfaces), so that nothing overshoots there; steps of
   * StepSize only through smooth data, at most a voxel from cells near a jump. AUTO_RECONSTRUCTION:
   * CUBIC where the trilinear scheme's error, estimated on Auto's pilot rays, would exceed half the
   * tolerance, or where it is cheaper at the tolerance (with Integrator AUTO_INTEGRATOR).
   */
  vtkSetMacro(Reconstruction, int);
  vtkGetMacro(Reconstruction, int);
  ///@}

  ///@{
  /**
   * Integrator AUTO_INTEGRATOR: the deflection error allowed, radians; 0 (the default) means 1 % of the
   * largest deflection of the pilot rays. Valid range [0, 1] (an error outside it).
   */
  vtkSetMacro(Tolerance, double);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * Rescale v = n dx/ds to |v| = n after every step (the ray invariant). Default off. It holds
   * the invariant (field data max_drift) but does not make the deflection more accurate: on a
   * linear medium Euler's deflection error grew from 4.4e-6 to 2.1e-4 rad with it (2-voxel steps);
   * Midpoint and RK4 were unchanged.
   */
  vtkSetMacro(KeepInvariant, int);
  vtkGetMacro(KeepInvariant, int);
  vtkBooleanMacro(KeepInvariant, int);
  ///@}

  ///@{
  /**
   * Trace every ray a second time at twice the step and output the per-pixel difference
   * (scaled by the integrator's order) as the point array `error_estimate`, radians. Default off.
   */
  vtkSetMacro(EstimateError, int);
  vtkGetMacro(EstimateError, int);
  vtkBooleanMacro(EstimateError, int);
  ///@}

  ///@{
  /**
   * Use the input's point array `octree_level` (vtkRefractionOctree), when there is one, to step
   * across uniform blocks. Default on.
   */
  vtkSetMacro(UseOctree, int);
  vtkGetMacro(UseOctree, int);
  vtkBooleanMacro(UseOctree, int);
  ///@}

  ///@{
  /**
   * The cutoff that forms the image (a CutoffType). Default KNIFE_EDGE.
   */
  vtkSetMacro(Cutoff, int);
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
   * to full contrast. Valid range [0, 1e12] (an error outside it). Default 0.
   */
  vtkSetMacro(CutoffScale, double);
  vtkGetMacro(CutoffScale, double);
  ///@}

  ///@{
  /**
   * The bench (KnifeEdge; docs/BENCH.md): the light source whose image the knife cuts. Source
   * POINT_SOURCE (default: the idealised knife, CutoffScale's I = 0.5 - k e.a), SLIT, RECTANGLE, DISC,
   * GAUSSIAN_SPOT. SourceSize (mm, [0.001, 10000]): across the knife (a disc's diameter, a Gaussian's
   * 1/e^2 diameter) and along it. CollimatorFocalLength and SchlierenFocalLength (f1, f2; m,
   * [0.001, 1000]). KnifeCut: the share of the source's image the knife covers, [0, 0.999].
   * BitDepth ([1, 32]) and SaturationWarning ([0, 1]) only shape the read-outs. Out of range: an error.
   */
  enum SourceType
  {
    POINT_SOURCE = 0,
    SLIT = 1,
    RECTANGLE = 2,
    DISC = 3,
    GAUSSIAN_SPOT = 4
  };
  vtkSetMacro(Source, int);
  vtkGetMacro(Source, int);
  /**
   * CIRCULAR and COMPLEMENT_CIRCULAR: the stop's diameter in the cutoff plane, mm ([0, 10000]; 0,
   * the default: the idealised stops of CutoffScale). With a diameter the weight is the share of
   * the source's image (POINT, DISC or GAUSSIAN_SPOT, shifted by f2 |e|) the stop lets through.
   */
  vtkSetMacro(StopDiameter, double);
  vtkGetMacro(StopDiameter, double);
  vtkSetVector2Macro(SourceSize, double);
  vtkGetVector2Macro(SourceSize, double);
  vtkSetMacro(CollimatorFocalLength, double);
  vtkGetMacro(CollimatorFocalLength, double);
  vtkSetMacro(SchlierenFocalLength, double);
  vtkGetMacro(SchlierenFocalLength, double);
  vtkSetMacro(KnifeCut, double);
  vtkGetMacro(KnifeCut, double);
  vtkSetMacro(BitDepth, int);
  vtkGetMacro(BitDepth, int);
  vtkSetMacro(SaturationWarning, double);
  vtkGetMacro(SaturationWarning, double);
  ///@}

  ///@{
  /**
   * The camera (docs/BENCH.md "Camera"; world units taken as metres). Camera NO_CAMERA (default:
   * the film where FilmDistance puts it, as before), IDEAL_LENS (a thin lens imaging FocusPlane,
   * no aperture blur) or FINITE_APERTURE (its aperture CameraFocalLength / FNumber sampled, one
   * lens point per pass). CameraFocalLength (m, [0.001, 1000]), FNumber ([0.5, 1000]),
   * CameraDistance (m, [0.001, 1e6]: the lens to the volume's centre), FocusPlane (world units
   * along the beam from the volume's centre, positive toward the camera, [-1e6, 1e6]),
   * SourceGridDistance (m, [0.001, 1e6]: a focusing schlieren's source grid to the lens; a
   * read-out only). Out of range, or the focus plane within the focal length: an error.
   */
  enum CameraType
  {
    NO_CAMERA = 0,
    IDEAL_LENS = 1,
    FINITE_APERTURE = 2
  };
  vtkSetMacro(Camera, int);
  vtkGetMacro(Camera, int);
  vtkSetMacro(CameraFocalLength, double);
  vtkGetMacro(CameraFocalLength, double);
  vtkSetMacro(FNumber, double);
  vtkGetMacro(FNumber, double);
  vtkSetMacro(CameraDistance, double);
  vtkGetMacro(CameraDistance, double);
  vtkSetMacro(FocusPlane, double);
  vtkGetMacro(FocusPlane, double);
  vtkSetMacro(SourceGridDistance, double);
  vtkGetMacro(SourceGridDistance, double);
  ///@}

  ///@{
  /**
   * Distance of the film behind the back of the volume's box, world units (>= 0 and finite,
   * else an error). Default 0.
   */
  vtkSetMacro(FilmDistance, double);
  vtkGetMacro(FilmDistance, double);
  ///@}

  ///@{
  /**
   * INTERFEROMETRY: the light's vacuum wavelength, nm (world units are taken as metres for the
   * phase 2 pi / lambda * integral (n - n_entry) ds). Valid range [100, 100000] (an error outside it). Default 632.8.
   * The index itself is computed upstream (vtkRefractiveIndex has its own Wavelength).
   */
  vtkSetMacro(Wavelength, double);
  vtkGetMacro(Wavelength, double);
  ///@}

  ///@{
  /**
   * INTERFEROMETRY: the reference beam's tilt, fringes per world unit along film x (0: an
   * infinite-fringe interferogram). Default 0.
   */
  vtkSetMacro(ReferenceTilt, double);
  vtkGetMacro(ReferenceTilt, double);
  ///@}

  ///@{
  /**
   * White light (docs/BENCH.md "Light"): a band of vacuum wavelengths, nm, flat in wavenumber
   * (0 0, the default: the one Wavelength, which is then the wavelength the input's n - 1 holds);
   * WavelengthBins (16, [1, 4096]) bins traced one per pass; Dispersion AIR (n - 1 scaled by
   * air's Ciddor index) or NO_DISPERSION. The output gets `rgb`, the colour of the light.
   */
  vtkSetVector2Macro(WavelengthRange, double);
  vtkGetVector2Macro(WavelengthRange, double);
  vtkSetMacro(WavelengthBins, int);
  vtkGetMacro(WavelengthBins, int);
  enum DispersionModel
  {
    AIR = 0,
    NO_DISPERSION = 1
  };
  vtkSetMacro(Dispersion, int);
  vtkGetMacro(Dispersion, int);
  ///@}

  ///@{
  /**
   * BOS: distance from the front of the volume's box (where the beam enters) to the background,
   * world units (>= 0 and finite, else an error). Default 1.
   */
  vtkSetMacro(BackgroundDistance, double);
  vtkGetMacro(BackgroundDistance, double);
  ///@}

  ///@{
  /**
   * BOS: the background (a BackgroundPatternType): DOTS (random dots, one per period cell,
   * seeded) or STRIPES (a cosine along film x). Default DOTS.
   */
  vtkSetMacro(BackgroundPattern, int);
  vtkGetMacro(BackgroundPattern, int);
  ///@}

  ///@{
  /**
   * BOS: the dot spacing or stripe period, world units; 0 (the default) means 6 pixels.
   */
  vtkSetMacro(BackgroundPeriod, double);
  vtkGetMacro(BackgroundPeriod, double);
  ///@}

  /**
   * BOS for the laboratory's software (docs/BENCH.md "BOS image pairs"): writes the last image
   * this filter made (Cutoff BOS) as the image pair that OpenPIV and other cross-correlation codes
   * read: `<prefix>_background` (the same film without the flow) and `<prefix>_recording` (the
   * intensity), grey, `bits` 8 or 16, `format` "png" or "tiff", and the side file `<prefix>.json`
   * (the pixel size, the bench, the displacement's units and sign), in the existing `folder`.
   * The engine writes them (schlieren::WriteBOSPair), as the Python front end's
   * SchlierenImage.WriteBOSPair and schlieren_session_write_bos_pair do. pvpython:
   * `img.GetClientSideObject().WriteBOSPair("/tmp/pair", 16, "png", "bos")` after an update (on
   * the process that holds the image: builtin, or rank 0 of pvbatch). Returns 1, or 0 with a
   * one-line error (vtkErrorMacro; GetBOSPairMessage() says it, or on success the files).
   */
  int WriteBOSPair(const char* folder, int bits, const char* format, const char* prefix);
  int WriteBOSPair(const char* folder, int bits, const char* format)
  {
    return this->WriteBOSPair(folder, bits, format, "bos");
  }
  const char* GetBOSPairMessage();

  ///@{
  /**
   * The film filter (a FilterType). Default NO_FILTER.
   */
  vtkSetMacro(Filter, int);
  vtkGetMacro(Filter, int);
  ///@}

  ///@{
  /**
   * The filter's width in pixels: the Gaussian's standard deviation, or the cone's radius at one
   * pass (it shrinks as 1 / sqrt(passes), to at least 1 pixel). Valid range [0.01, 64] (an error
   * outside it). Default 1.
   */
  vtkSetMacro(FilterWidth, double);
  vtkGetMacro(FilterWidth, double);
  ///@}

  ///@{
  /**
   * Photon killing (Russian roulette) instead of energy weighting: each photon passes the cutoff
   * whole or not at all, with the probability of its weight. Same mean, more noise; the knife and
   * circular cutoffs then need a CutoffScale. Default off.
   */
  vtkSetMacro(RussianRoulette, int);
  vtkGetMacro(RussianRoulette, int);
  vtkBooleanMacro(RussianRoulette, int);
  ///@}

  ///@{
  /**
   * Whether photons start at random points inside their pixels (on, the default: passes then
   * sample the pixel's area) or at the pixel centres (off: every pass is the same; for tests and
   * pixel-exact comparisons).
   */
  vtkSetMacro(Jitter, int);
  vtkGetMacro(Jitter, int);
  vtkBooleanMacro(Jitter, int);
  ///@}

  ///@{
  /**
   * With Jitter on, where a pass's photons start: LATTICE (1, the default) one offset for every
   * pixel of a pass, the pixel grid shifted as a whole (smooth fields and shocks converge in a
   * fraction of the passes, without the first passes' speckle; near caustics the first passes
   * show moire that fades as passes add); RANDOM (0) every pixel its own random offset (a pass's
   * image is noisy, never patterned).
   */
  enum JitterPatternType
  {
    RANDOM = 0,
    LATTICE = 1
  };
  vtkSetMacro(JitterPattern, int);
  vtkGetMacro(JitterPattern, int);
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
  vtkSetMacro(Backend, int);
  vtkGetMacro(Backend, int);
  ///@}

  ///@{
  /**
   * The OpenCL device: a substring of its name. Default empty: the environment variable
   * SCHLIEREN_OPENCL_DEVICE, else the first GPU, else the first device. A name no device has is
   * an error with Backend OPENCL, and the CPU with a warning with AUTO.
   */
  vtkSetStringMacro(DeviceName);
  vtkGetStringMacro(DeviceName);
  ///@}

  ///@{
  /**
   * Threads of the CPU backend. Default 0: the environment variable SCHLIEREN_CPU_THREADS, else
   * all cores.
   */
  // not clamped: a value outside 0..4096 is refused by the engine with the range
  vtkSetMacro(Threads, int);
  vtkGetMacro(Threads, int);
  ///@}

  ///@{
  /**
   * Under MPI, keep the volume in pieces and hand rays between ranks (default on): no rank holds
   * the whole volume. Off: every rank gathers the whole volume (more memory per rank).
   */
  vtkSetMacro(TraceInPieces, vtkTypeBool);
  vtkGetMacro(TraceInPieces, vtkTypeBool);
  vtkBooleanMacro(TraceInPieces, vtkTypeBool);
  ///@}

protected:
  vtkSchlierenImage();
  ~vtkSchlierenImage() override;

public:
  /** Every request, with any exception turned into an error and a failed request. */
  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

protected:
  /** ParaView's executive that, under MPI, stops the filter on every rank at once where its
   * input failed on some (schlieren::NewAgreeingExecutive). */
  vtkExecutive* CreateDefaultExecutive() override;

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
  int Framing = VOLUME_FRAME;
  int Passes = 4;
  int PassLimit = 0;
  double StepSize = 0.5;
  int Integrator = EULER;
  int Reconstruction = TRILINEAR;
  double Tolerance = 0.0;
  int KeepInvariant = 0;
  int EstimateError = 0;
  int UseOctree = 1;
  int Cutoff = KNIFE_EDGE;
  double KnifeAngle = 0.0;
  double CutoffScale = 0.0;
  int Source = POINT_SOURCE;
  double SourceSize[2] = { 1.0, 1.0 };
  double StopDiameter = 0.0;
  double CollimatorFocalLength = 1.0;
  double SchlierenFocalLength = 1.0;
  double KnifeCut = 0.5;
  int BitDepth = 8;
  double SaturationWarning = 0.01;
  int Camera = NO_CAMERA;
  double CameraFocalLength = 0.1;
  double FNumber = 8.0;
  double CameraDistance = 1.0;
  double FocusPlane = 0.0;
  double SourceGridDistance = 2.0;
  double FilmDistance = 0.0;
  double Wavelength = 632.8;
  double ReferenceTilt = 0.0;
  double WavelengthRange[2] = { 0.0, 0.0 };
  int WavelengthBins = 16;
  int Dispersion = AIR;
  double BackgroundDistance = 1.0;
  int BackgroundPattern = DOTS;
  double BackgroundPeriod = 0.0;
  int Filter = NO_FILTER;
  double FilterWidth = 1.0;
  int RussianRoulette = 0;
  int Jitter = 1;
  int JitterPattern = LATTICE;
  int Seed = 1;
  int Backend = AUTO;
  char* DeviceName = nullptr;
  int Threads = 0;
  vtkTypeBool TraceInPieces = 1;

private:
  // what is kept between updates: the packed volume, and this rank's film sums of the passes
  // traced so far (raising Passes traces only the new passes)
  struct vtkInternals;
  vtkInternals* Internals;

  vtkSchlierenImage(const vtkSchlierenImage&) = delete;
  void operator=(const vtkSchlierenImage&) = delete;
};

#endif
