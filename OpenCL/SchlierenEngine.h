// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenEngine.h
 * @brief The VTK-free tracing engine: plain arrays in, plain images out.
 *
 * The engine takes a volume of n-1 on a regular grid (with its gradient, packed 4 floats per point)
 * and traces a collimated beam through it on one of two backends built from one physics source
 * (SchlierenPhysics.h): OpenCL (any device; PoCL on a CPU) or the CPU (std::thread). It returns the
 * film image. Every failure is reported by throwing schlieren::Error with a message for the user.
 *
 * Units: SI; world units for lengths, radians for deflections.
 */
#ifndef SchlierenEngine_h
#define SchlierenEngine_h

#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace schlieren
{

/** Every error the engine reports. The message says what went wrong and what to do. */
class Error : public std::runtime_error
{
public:
  explicit Error(const std::string& what)
    : std::runtime_error(what)
  {
  }
};

/** A regular grid (non-owning). `field` holds 4 floats per point: n-1, dn/dx, dn/dy, dn/dz, x fastest. */
struct Volume
{
  int Dimensions[3] = { 0, 0, 0 };
  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  const float* Field = nullptr;
  /** Optional min-max octree level per cell (see ComputeOctreeLevels); null: fixed steps. */
  const unsigned char* Levels = nullptr;
  /** The index tolerance the levels were built for (for the step-quality checks). */
  double LevelTolerance = 0.0;
  /**
   * Optional solid bodies: one byte per grid point, non-zero where the point lies in a body
   * (null: no body, and no cost). A ray stops where a step ends in a body, where the trilinear
   * interpolation of the solid points (1 solid, 0 not) is at least one half: its light
   * never reaches the film, and it is counted (RayBlocked, TraceResult::BlockedRays). With a
   * body no step near it is longer than a cell and no octree skip crosses one, so that no step
   * passes over a body one point thick. Rays that leave through the box's faces are not blocked.
   * With a body the trace is trilinear (Reconstruction Cubic needs the bits it uses).
   */
  const unsigned char* Solid = nullptr;
  /**
   * Optional smoothness of the data per cell (byte per grid point, the cell whose lower corner it
   * is), written by PackFieldHighOrder together with Field: what Reconstruction Cubic needs. Bit 7:
   * the 4 x 4 x 4 points around the cell are smooth (tricubic there, trilinear elsewhere); bits
   * 4-6, q: every cell within 2^q cells is smooth (steps may be as long as 2^q - 1 cells).
   */
  const unsigned char* Smooth = nullptr;
  /**
   * The caller's version of Field, Levels, Smooth and Solid. Equal non-zero stamps with the same pointers and
   * dimensions promise unchanged contents: the engine then keeps what it derived from them (the
   * OpenCL device's copy, the index range) from one call to the next, so that a new camera or
   * a few more passes do not upload the volume again. 0 (the default): nothing is kept.
   */
  std::uint64_t Stamp = 0;
  /**
   * Field's layout: false (the default), the linear layout above (x fastest); true, the points in
   * bricks of 4^3 (what PackFieldOf and PackFieldHighOrderOf write with `bricked`, and a
   * TraceSession packs where they pay: BrickLayout in SchlierenEngineInternal.h). Levels, Smooth
   * and Solid stay linear either way. The images are the same, bit for bit.
   */
  bool FieldInBricks = false;
  /**
   * Layers of points beyond every face of the box (0, the default: none). The box, where rays
   * enter and leave and the film is framed, is the bounds of the points Ghost in from each face;
   * the outer ones only give the reconstruction its stencils there (Auto's coarse copy, issue 50).
   */
  int Ghost = 0;

  std::size_t NumberOfPoints() const
  {
    return static_cast<std::size_t>(Dimensions[0]) * Dimensions[1] * Dimensions[2];
  }
  /** The box (the point bounds, less Ghost layers): xmin, xmax, ymin, ymax, zmin, zmax. */
  void GetBounds(double bounds[6]) const;
};

/** A stamp no other volume of this process has had (for Volume::Stamp). */
std::uint64_t NewVolumeStamp();

/** Frees what the engine keeps between calls (the device copy of the last stamped volume). */
void ReleaseKeptVolume();

/**
 * Packs n-1 and its gradient (central differences in world units, one-sided at the borders) into
 * the 4-float layout of Volume::Field. `out` must hold 4 * number of points floats.
 * Throws Error if a dimension is below 2, a spacing is not positive, or n-1 is NaN/Inf or <= -1.
 */
void PackField(const int dims[3], const double spacing[3], const float* nMinus1, float* out);

/**
 * PackField for Reconstruction Cubic: the gradient by fourth-order central differences,
 * (f[-2] - 8 f[-1] + 8 f[1] - f[2]) / 12h, where the five points of the difference are all smooth,
 * by PackField's second-order differences elsewhere; and the smoothness of every cell in `smooth`
 * (a byte per point, see Volume::Smooth). A point is smooth where, along each axis, the fourth
 * difference of its five points is below `threshold` times their range (a jump or a kink gives 1
 * to 3, a Gaussian of width s sampled at h about 6 (h/s)^2; structure below 1e-4 of the field's
 * range counts as smooth) and it is at least two points from the border; a cell is smooth where the 4 x 4 x 4 points around it are. Returns the fraction of
 * cells that are smooth. Throws what PackField throws.
 */
double PackFieldHighOrder(const int dims[3], const double spacing[3], const float* nMinus1,
  float* out, unsigned char* smooth, double threshold = 0.25);

/** The same gradient written into a 3-component array (for the `grad_n` output of filters). */
void ComputeGradient(const int dims[3], const double spacing[3], const float* nMinus1, float* grad3);

/**
 * The min-max octree of the paper (section 4.2), stored as a level per cell: level j means that the
 * aligned block of 2^j cells holding the cell, grown by a one-cell halo, spans no more than
 * `tolerance` in n-1, so a ray may cross the block in one straight step. `levels` holds one byte per
 * grid point (the cell whose lower corner it is; the last layer is unused). Returns the fraction of
 * cells at level >= 1. Levels stop at maxLevel (2^maxLevel cells).
 */
double ComputeOctreeLevels(const int dims[3], const float* nMinus1, double tolerance,
  unsigned char* levels, int maxLevel = 7);

/**
 * Checks n-1 for NaN/Inf and for n <= 0; returns an empty string if fine, else a message that
 * gives how many points are bad and the first one.
 */
std::string ValidateIndex(const float* nMinus1, std::size_t count);

enum class Backend
{
  Auto,   ///< OpenCL if a device works, else CPU with a warning
  OpenCL, ///< OpenCL or an error
  CPU     ///< the C++ build of the same physics, on std::thread
};

enum class Integrator
{
  Euler = 0,    ///< the paper's explicit Euler (first order, 1 sample per step)
  Midpoint = 1, ///< explicit midpoint (second order, 2 samples per step)
  RK4 = 2,      ///< classical Runge-Kutta (fourth order, 4 samples per step)
  Straight = 3, ///< line of sight: grad n integrated along the unbent ray (no refraction)
  Auto = 4,     ///< the cheapest of the others (and step) that meets TraceSettings::Tolerance
  Verlet = 5    ///< velocity Verlet (second order, 1 sample per step: Euler's cost)
};

/** How the packed field is reconstructed between grid points. */
enum class Reconstruction
{
  Trilinear = 0, ///< trilinear (second order): the paper's; needs nothing beyond PackField
  Cubic = 1,     ///< tricubic where the data is smooth, trilinear near jumps (fourth order where
                 ///< smooth); steps of StepSize only in smooth data, at most a voxel elsewhere.
                 ///< Needs Volume::Smooth (PackFieldHighOrder)
  Auto = 2       ///< Cubic where the second-order reconstruction's error (estimated on the pilot
                 ///< rays) would exceed the tolerance (with the candidate's own error) or where
                 ///< Cubic is cheaper at it, else Trilinear; Trilinear without Smooth
};

enum class Cutoff
{
  KnifeEdge = 0,          ///< I = 0.5 - k e.a, per photon, clamped to [0, 1]
  Shadowgraph = 1,        ///< no cutoff: density of photons arriving on the film
  Circular = 2,           ///< a pinhole stop: I = 1 - k|e|
  ComplementCircular = 3, ///< a dot stop (dark field): I = k|e|
  ColorFilter = 4,        ///< hue from the direction of e in the film plane, value k|e| (rgb)
  Interferometry = 5,     ///< fringes of the optical phase against a reference beam
  BOS = 6                 ///< background-oriented schlieren: a dot/stripe background seen through the flow
};

/** The bench's light source (docs/BENCH.md); values match SCH_SOURCE_* in SchlierenPhysics.h. */
enum class BenchSource
{
  Point = 0,     ///< the idealised point source: clamp(0.5 - k e.a), k automatic or CutoffScale
  Slit = 1,      ///< a slit of height SourceSize[0] across the knife (along it: no effect)
  Rectangle = 2, ///< a rectangle SourceSize[0] x SourceSize[1], sides along the knife
  Disc = 3,      ///< a pinhole of diameter SourceSize[0]
  Gaussian = 4   ///< a Gaussian spot of 1/e^2 diameter SourceSize[0] (sigma = diameter / 4)
};

/** The camera that images the beam (docs/BENCH.md "Camera"). */
enum class CameraModel
{
  None = 0,  ///< no lens: the film where FilmDistance puts it (today's images)
  Ideal = 1, ///< a thin lens focused on FocusPlane with no aperture blur (collimated light passes its focus)
  Lens = 2   ///< a thin lens of aperture CameraFocalLength / FNumber filled with light: its cone of rays sampled
};

/** How the index of a band's wavelengths follows from the input's (docs/BENCH.md "Light"). */
enum class Dispersion
{
  Air = 0, ///< n - 1 scaled by standard air's (Ciddor): (n(l) - 1) / (n(Wavelength) - 1)
  None = 1 ///< n - 1 the same at every wavelength (only the phase's 2 pi / l changes)
};

/** What the film covers (docs/GUI.md "Framing"). */
enum class Framing
{
  Volume = 0,    ///< the projection of the volume's box (the images before Framing existed)
  Silhouette = 1 ///< the data's silhouette seen along the view (FrameSilhouette), in its shape
};

/** Where a pass's photons start inside their pixels, with Jitter on (docs/GUI.md "Jitter"). */
enum class JitterPattern
{
  Random = 0, ///< each pixel its own random offset (then R2 over the passes): noise, never a pattern
  Lattice = 1 ///< one offset for every pixel of a pass (R2 over the passes): the pixel grid shifted;
              ///< smooth fields and shocks converge in fewer passes, caustics show moire that fades
};

enum class FilmFilter
{
  None = 0,     ///< each photon in the pixel it lands in
  Gaussian = 1, ///< Gaussian of standard deviation FilterWidth pixels
  Cone = 2      ///< cone of radius FilterWidth / sqrt(passes) pixels (at least 1): sharpens as passes add up
};

/** Everything that defines a trace besides the volume. */
struct TraceSettings
{
  double ViewDirection[3] = { 0, 0, -1 }; ///< the beam travels along this world vector
  double ViewUp[3] = { 0, 1, 0 };         ///< film "up" (made orthogonal to ViewDirection)
  int Resolution[2] = { 512, 512 };       ///< film pixels
  /** Framing Silhouette: TraceSession frames the film to the data (FrameSilhouette) once and keeps
   * the frame while only the view, Resolution or Passes change (a camera that follows). */
  Framing Frame = Framing::Volume;
  /** The film's frame, film coordinates from the volume's centre (world units): a0, a1, b0, b1.
   * Where a1 > a0 and b1 > b0 the film holds it, centred on it, with square pixels: Framing
   * Volume on Resolution's pixels, Framing Silhouette on as many pixels as Resolution has, in the
   * frame's shape (each side 2 to 16384). Otherwise (the default, zeros) the box's projection on
   * Resolution's pixels. TraceSession sets it for Framing Silhouette; a caller may set it. */
  double FilmExtent[4] = { 0, 0, 0, 0 };
  int Passes = 1;                         ///< progressive passes, one jittered photon per pixel each
  double StepSize = 0.5;                  ///< base step, in voxels (of the smallest spacing)
  Integrator Method = Integrator::Euler;
  bool KeepInvariant = false; ///< rescale v = n dx/ds to |v| = n after every step
  bool EstimateError = false; ///< trace each ray again at twice the step: per-pixel error estimate
  bool UseOctree = true;      ///< skip through uniform blocks when the volume has Levels
  Reconstruction Recon = Reconstruction::Trilinear; ///< between grid points (see Reconstruction)
  /** Integrator Auto: the deflection error allowed, radians; <= 0 means 1 % of the largest
   * deflection of the pilot rays. */
  double Tolerance = 0.0;
  /** Set by ResolveAuto: the pilot's measured error of the chosen setting (radians); -1 otherwise. */
  double AutoMeasuredError = -1.0;
  /** Set by ResolveAuto (issue 50): 1, the volume's own points are traced; 2 or 4, a copy of the
   * field at that many times its spacing over the same box, certified within a quarter of the
   * Tolerance of the field at every point (CoarseCopyOf). StepSize stays in the volume's voxels. */
  int FieldStride = 1;
  Cutoff Mode = Cutoff::KnifeEdge;
  double KnifeAngle = 0.0;  ///< degrees in the film plane; 0: knife normal along film x
  double CutoffScale = 0.0; ///< k; 0 means automatic: the largest deflection maps to full contrast
  /** Shadowgraph: world units from the back of the volume's box to the film. Other cutoffs: the
   * camera images the volume's centre plane (a focused schlieren system) and FilmDistance moves
   * the imaged plane along the beam (defocus). */
  double FilmDistance = 0.0;
  double Wavelength = 632.8; ///< nm (Interferometry; world units are taken as metres)
  double ReferenceTilt = 0.0; ///< Interferometry: reference-beam fringes per world unit along film x
  /// Light (docs/BENCH.md "Light"): a band of vacuum wavelengths, nm, flat in wavenumber; both 0
  /// (the default): the one Wavelength, as before. With a band, Wavelength is the one the input's
  /// n - 1 holds (RefractiveIndex's) and the one ReferenceTilt's fringes are counted at (a path
  /// difference of ReferenceTilt Wavelength per world unit); each pass traces one wavelength of
  /// the band, WavelengthBins bins in a well-spread order (SpectralPass), n - 1 scaled by
  /// Dispersion, and the film gets rgb, the colour of the light that reached it.
  double WavelengthRange[2] = { 0.0, 0.0 };
  int WavelengthBins = 16;
  schlieren::Dispersion Disperse = schlieren::Dispersion::Air;
  /// A band of wavelengths (WavelengthRange set)
  bool WhiteLight() const { return WavelengthRange[1] > 0; }
  double BackgroundDistance = 1.0; ///< BOS: world units from the front of the volume's box to the background
  int BackgroundPattern = 0;       ///< BOS: 0 dots, 1 stripes (along film x)
  double BackgroundPeriod = 0.0;   ///< BOS: dot spacing or stripe period, world units; 0: 6 pixels
  FilmFilter Filter = FilmFilter::None;
  double FilterWidth = 1.0;  ///< pixels
  bool RussianRoulette = false; ///< photon killing instead of energy weighting (manual CutoffScale)
  bool Jitter = true;        ///< jitter photons inside their pixel (false: pixel centres)
  JitterPattern Pattern = JitterPattern::Lattice; ///< with Jitter: an offset per pass or per pixel
  std::uint32_t Seed = 1;
  int MaxSteps = 0;          ///< per ray; 0: 8 times the box diagonal over the step
  Backend Device = Backend::Auto;
  /// OpenCL device: a substring of the device name; empty: the runtime options' choice
  /// (SCHLIEREN_OPENCL_DEVICE, else the first GPU, else the first device)
  std::string DeviceName;
  /// CPU backend threads; 0: the runtime options' choice (SCHLIEREN_CPU_THREADS, else all cores)
  int Threads = 0;
  /// On more than one rank (TraceSession): keep the volume in pieces and hand rays between ranks;
  /// false: every rank gathers the whole volume
  bool InPieces = true;
  /// OpenCL per-item kernel: rays each work-item advances in turn; 0: 4 on CPU devices, 1 on
  /// others (GPUs: a ray per work-item). CPU devices trace passes in lock step, which ignores it.
  int RaysPerWorkItem = 0;
  int RankIndex = 0;         ///< trace only pixels p with p % RankCount == RankIndex (MPI split)
  int RankCount = 1;
  /// The bench (KnifeEdge only; docs/BENCH.md): the light source whose image the knife cuts.
  /// Point: today's idealised knife, I = clamp(0.5 - k e.a); the others give the closed-form
  /// response of their image and ignore CutoffScale.
  BenchSource Source = BenchSource::Point;
  double SourceSize[2] = { 1.0, 1.0 };  ///< mm: across the knife, along it (Gaussian: 1/e^2 diameter)
  double CollimatorFocalLength = 1.0;   ///< f1, m
  double SchlierenFocalLength = 1.0;    ///< f2, m
  double KnifeCut = 0.5;                ///< fraction of the source image's light the knife covers, [0, 0.999]
  /// Circular, ComplementCircular and ColorFilter: the stop's diameter in the cutoff plane, mm (an
  /// aperture the light passes through, an opaque disc, the colour filter's opaque centre); 0 (the
  /// default): the idealised stops, I = 1 - k|e|, k|e| and value k|e|. With a diameter the response
  /// is the share of the source's image (Point, Disc or Gaussian, shifted by f2 |e|) inside the
  /// aperture or outside the disc, in closed form (the colour filter: on the shift's hue).
  double StopDiameter = 0.0;
  /// Read-outs only (applied in Finalize): the camera's bit depth, for the smallest deflection one
  /// grey level resolves, and the share of lit pixels at saturation above which a warning is given.
  int BitDepth = 8;
  double SaturationWarning = 0.01;
  /// The camera (docs/BENCH.md "Camera"; world units are taken as metres). None: the film where
  /// FilmDistance puts it, as before the camera existed. Ideal and Lens: the film is the image of
  /// the plane FocusPlane (every cutoff, Shadowgraph included; FilmDistance is not used). Lens:
  /// an aperture of diameter D = CameraFocalLength / FNumber, CameraDistance from the volume's
  /// centre, sends each point of the focus plane a cone of rays of angular diameter D / Z_F
  /// (Z_F = CameraDistance - FocusPlane, the lens to the focus plane): one lens point per pass,
  /// stratified over the passes (CameraLensSample).
  CameraModel Camera = CameraModel::None;
  double CameraFocalLength = 0.1; ///< f, m
  double FNumber = 8.0;           ///< N (Lens), [0.5, 1000]
  double CameraDistance = 1.0;    ///< Z_A, m: the lens to the volume's centre, along the beam
  /// world units along ViewDirection from the volume's centre (positive: toward the camera) of
  /// the plane the camera focuses on; 0: the centre
  double FocusPlane = 0.0;
  /// Focusing schlieren read-out (Camera Lens): the source grid to the lens, m (L)
  double SourceGridDistance = 2.0;

  /** Every setting that changes which photons are traced or how they land and weigh: all but
   * Passes and the film filter (applied in Finalize). Equal keys, same volume: FilmSums of the
   * first passes can be continued with more (progressive refinement). Keep it in step with the
   * fields above. Device and DeviceName are in it (backends and devices agree to float rounding,
   * not bit for bit); Threads is not (the film does not depend on the thread count). */
  std::string PhotonKey() const;
};

/** The film's place in the world. */
struct FilmGeometry
{
  double Direction[3]; ///< unit beam direction
  double Right[3];     ///< film x axis (unit), Direction x Up
  double Up[3];        ///< film y axis (unit)
  double Center[3];    ///< centre of the volume's point bounds; film coordinates are measured from it
  double PixelSize;    ///< world units
  int Size[2];         ///< pixels
  double Corner[2];    ///< film coordinate (from Center) of the lower-left corner of pixel (0, 0)
  double FrontPlane;   ///< emission plane: (x - Center) . Direction
  double FilmPlane;    ///< the plane the film images: (x - Center) . Direction
  /** World-projected coordinate of the centre of pixel (0, 0): Center.Right + Corner + half a pixel. */
  void GetImageOrigin(double origin[2]) const;
};

/** Computes the film that covers the volume's projection (or settings.FilmExtent) with square
 * pixels. */
FilmGeometry MakeFilm(const Volume& volume, const TraceSettings& settings);

/** settings.FilmExtent is a frame (a1 > a0 and b1 > b0): MakeFilm covers it. */
inline bool HasFilmExtent(const TraceSettings& s)
{
  return s.FilmExtent[1] > s.FilmExtent[0] && s.FilmExtent[3] > s.FilmExtent[2];
}

/** What FrameSilhouette found. */
struct SilhouetteFrame
{
  double Extent[4] = { 0, 0, 0, 0 }; ///< a0, a1, b0, b1 (TraceSettings::FilmExtent)
  bool Found = false;  ///< false: no point refracts (a uniform field): Extent is the box's projection
  double Points = 0;   ///< grid points in the silhouette (refracting or solid)
  double Fraction = 0; ///< the frame's area over the box projection's
};

/**
 * The data's silhouette seen along settings.ViewDirection/ViewUp: the film-coordinate rectangle
 * around the grid points that refract, |grad n| above 1e-3 of the volume's largest (the packed
 * gradient), or lie in a body, padded by a grid spacing and 2 % of its size, and no larger than
 * the box's projection. Points of uniform air (a free stream around the flow, a resampled grid's
 * points outside the data) are left out. One pass over the volume.
 */
SilhouetteFrame FrameSilhouette(const Volume& volume, const TraceSettings& settings);

/** The points a FrameSilhouette scans: a block [Lo, Hi) of a held array of Held points (the
 * Volume::Field layout), whose point (0, 0, 0) is the whole grid's point Offset. */
struct SilhouetteScan
{
  const float* Field = nullptr;
  const unsigned char* Solid = nullptr;
  int Held[3] = { 0, 0, 0 };
  int Lo[3] = { 0, 0, 0 }, Hi[3] = { 0, 0, 0 };
  int Offset[3] = { 0, 0, 0 };
  bool FieldInBricks = false; ///< Field in bricks of Held points (Volume::FieldInBricks)
};
/** FrameSilhouette of the whole grid `grid` (its geometry) from the points `scan` holds, the
 * largest gradient, the extremes and the count combined over the pieces by `reduce` (max: true
 * for a maximum, false for a sum; a no-op for a whole volume), so that every piece's rank gets
 * the whole volume's frame. */
SilhouetteFrame FrameSilhouette(const Volume& grid, const TraceSettings& settings,
  const SilhouetteScan& scan, const std::function<void(double* values, std::size_t count, bool max)>& reduce);

/** Per-pixel sums over photons; these add across passes and across MPI ranks. */
struct FilmSums
{
  int Size[2] = { 0, 0 };
  std::vector<double> Count;   ///< photons landed
  std::vector<double> Weight;  ///< summed per-photon weights of the cutoff (manual CutoffScale,
                               ///< Interferometry, BOS; see Finalize)
  std::vector<double> DeflectionX, DeflectionY; ///< summed deflections
  std::vector<double> AbsDeflection; ///< summed |e|
  std::vector<double> Red, Green, Blue; ///< ColorFilter: summed value x hue colour
  std::vector<double> Phase;   ///< summed optical phase against the entry index, radians
  std::vector<double> ShiftX, ShiftY; ///< BOS: summed apparent displacement of the background
  std::vector<double> ErrorSum; ///< summed step-doubling error estimates (EstimateError only)
  double MaxAbsKnife = 0.0;    ///< max over photons of |e . a| (for the automatic scale)
  double MaxAbsDeflection = 0.0; ///< max over photons of |e|
  double MaxDrift = 0.0;       ///< max over rays of | |v| - n |
  double MaxError = 0.0;       ///< max over rays of the step-doubling estimate
  double Photons = 0.0, Samples = 0.0, FailedRays = 0.0, MissedRays = 0.0;
  double UnderresolvedRays = 0.0, SideRays = 0.0, Steps = 0.0;
  double BlockedRays = 0.0;   ///< rays stopped by a solid body (Volume::Solid)
  std::vector<double> Blocked; ///< per pixel: photons emitted there that a body stopped
  int Passes = 0;

  void Resize(int nx, int ny);
  /** Every per-pixel channel, every additive total, every maximum: for generic loops and MPI. */
  std::vector<std::vector<double>*> PixelChannels();
  std::vector<double*> Totals();
  std::vector<double*> Maxima();
  /** Flattens the additive parts (channels, then totals) and the maxima, for a sum-reduce and a
   * max-reduce across ranks; FromArrays puts reduced arrays back. */
  void ToArrays(std::vector<double>& additive, std::vector<double>& maxima);
  void FromArrays(const std::vector<double>& additive, const std::vector<double>& maxima);
};

/** What Integrator::Auto chose, and why. */
struct AutoChoice
{
  Integrator Method = Integrator::Euler;
  double StepSize = 0.5;        ///< voxels
  double Tolerance = 0;         ///< radians, as applied
  double ExpectedError = 0;     ///< radians: the largest pilot deflection error of the choice
  double ExpectedLandingError = 0; ///< film pixels
  double SamplesPerRay = 0;
  bool Met = false;             ///< false: no candidate met the tolerance; the most accurate is used
  bool UseOctree = false;       ///< the octree pays for the choice (asked for, and skips >= 10 %)
  double OctreeSaving = 0;      ///< fraction of the pilot's samples the octree skips
  Reconstruction Recon = Reconstruction::Trilinear; ///< the reconstruction traced with
  /** Reconstruction Auto: the largest pilot difference between the trilinear and the tricubic
   * reference traces, radians: the second-order reconstruction's estimated error (-1: not measured). */
  double TrilinearError = -1;
  std::string Report;           ///< one line for the user
  /** The smallest error the pilot can tell apart for the chosen reconstruction, radians (0: not
   * measured; it is only where no candidate met the tolerance): 1.5 times the largest pilot
   * difference between the reference (RK4 at the finest step of its ladder) and RK4 at twice
   * that step; above the tolerance only where the ladder reached 1/8 voxel. Below it a
   * candidate's measured error says nothing about its real one. */
  double Floor = 0;
  /** The tolerance was below Floor: the cheapest candidate within the floor was taken (Met is
   * false, the report and a warning say so). */
  bool AtFloor = false;
  /** The tricubic reference's own error, radians (0: not measured): the pilot's reference traced
   * again on the field sampled at about r = 2 times the spacing, their difference over r^4 - 1.
   * Measured where the tolerance may be within its reach; 1.5 times it is part of Floor (a
   * tolerance below: not reachable on this grid, said in Report). */
  double ReferenceError = 0;
  /** What measuring ReferenceError took, milliseconds (0: not measured). */
  double ReferenceCheckMs = 0;
  /** The pilot was not traced for this choice: it is the previous update's (a camera move of a
   * TraceSession, see TraceSession::Update). */
  bool Reused = false;
  /** Candidates the pilot traced (besides its references). */
  int Candidates = 0;
  /** The pilot's references: the step of RK4 each reconstruction's ladder stopped at, voxels
   * (Trilinear, Cubic; 0: not traced). A later pilot given this choice as its start begins its
   * ladders at twice these. */
  double ReferenceSteps[2] = { 0, 0 };
  /** Traced in pieces: steps longer than the pieces' ghost layers hold (8 voxels trilinear, 64
   * tricubic) were not tried; one process may choose a longer one. */
  bool PiecesBound = false;
  /** 1: the volume's own points traced; 2 or 4: its certified copy at that many times its
   * spacing (TraceSettings::FieldStride), the pilot traced on it too. */
  int FieldStride = 1;
  /** The copy's certificate, radians: no ray's deflection differs by more between the copy and
   * the field (0 with FieldStride 1). The pilot's tolerance was the rest of Tolerance. */
  double CoarseBound = 0;
  /** What building and certifying the copies took, milliseconds (0: kept from before). */
  double CoarseMs = 0;
};

/** The finished image. */
struct TraceResult
{
  FilmGeometry Film;
  std::vector<float> Intensity;  ///< nx*ny
  std::vector<float> Deflection; ///< 2*nx*ny, radians along film x and y (mean of the photons)
  std::vector<float> ErrorEstimate; ///< nx*ny, radians (EstimateError only, else empty)
  std::vector<float> RGB;        ///< 3*nx*ny (ColorFilter, or a band of wavelengths; else empty)
  std::vector<float> Phase;      ///< nx*ny, radians (Interferometry only, else empty)
  std::vector<float> Displacement; ///< 2*nx*ny, world units (BOS only, else empty)
  /// nx*ny: the fraction of the photons emitted at a pixel that a solid body stopped (the
  /// body's shadow, as the beam sees it before any deflection); only when the volume has Solid
  std::vector<float> Blocked;
  double CutoffScaleUsed = 0.0;
  /// the deflection (rad) that CutoffScaleUsed maps to full contrast: of the knife's component
  /// for KnifeEdge (0.5 / k), of |e| for the other stops (1 / k); 0 where no scale applies
  double FullContrastDeflection = 0.0;
  /// the largest |e| of any photon (rad)
  double MaxDeflection = 0.0;
  std::string BackendUsed;  ///< "OpenCL" or "CPU"
  std::string DeviceName;
  std::string Warnings;     ///< what the user should know (fallbacks, failed rays)
  double Photons = 0, Samples = 0, FailedRays = 0, MissedRays = 0, MaxDrift = 0;
  double UnderresolvedRays = 0, SideRays = 0, Steps = 0, MaxError = 0;
  double BlockedRays = 0; ///< stopped by a solid body: dark on the film, not failed
  AutoChoice Choice; ///< what was traced with (for Auto: what it chose)
  double Seconds = 0; ///< tracing time
  /// The bench (finite Source only): dI/I per radian of deflection toward the open side at eps = 0
  /// (f2/a for a slit), and the deflections (radians) at full dark and at saturation
  double BenchSensitivity = 0, BenchRange[2] = { 0, 0 };
  /// the deflection (radians) that moves I by one grey level of BitDepth, full scale at I = 1
  double BenchResolvable = 0;
  /// shares of the lit pixels at saturation and at full dark (the weights at BenchRange's ends)
  double BenchSaturated = 0, BenchDark = 0;
  std::string BenchModel; ///< how the response was computed; empty for Point
  /// A band of wavelengths: how it was sampled and the dispersion's scales of n - 1 at its ends
  std::string Spectrum;
  double SpectrumScale[2] = { 1, 1 };
  /// The camera (Camera not None; docs/BENCH.md "Camera"): what it implies, for the field data.
  struct CameraReadouts
  {
    bool Active = false;
    double Magnification = 0;  ///< of the focus plane on the sensor, f / (Z_F - f)
    double Aperture = 0;       ///< D = f / N, m (Lens; 0 for Ideal)
    double BlurPerDepth = 0;   ///< blur diameter in the object's plane per unit of defocus, D / Z_F
    double DepthOfField = 0;   ///< world units: the depth over which the blur stays within one film pixel, 2 p Z_F / D
    int ApertureSamples = 0;   ///< lens points sampled (one per pass; 0 for Ideal)
    /// BOS (Cutoff BOS): the background Z_D = BackgroundDistance + the box's front half-depth
    /// behind the volume's centre, the background in focus
    double BOSMagnification = 0; ///< M = f / (Z_A + Z_D - f)
    double BOSDisplacementPerRadian = 0; ///< on the sensor, m per radian: M Z_D
    double BOSPixelsPerRadian = 0;       ///< film pixels per radian: M Z_D / (M_A pixel), M_A = f / (Z_A - f)
    double BOSBlur = 0;                  ///< the object plane's blur on the sensor, m: D f Z_D / [Z_A (Z_A + Z_D - f)]
    double BOSBlurPixels = 0;            ///< the same in film pixels
    /// focusing schlieren (Lens with KnifeEdge): f2_eff = (L - l) L' / L, L' = L f / (L - f),
    /// l = Z_F; 0 where L <= max(l, f)
    double FocusingEffectiveF2 = 0;
    std::string Model;
  } Camera;
};

/** Lens point `pass` of a camera with seed `seed`, on the unit disc (u^2 + v^2 <= 1): the R2
 * low-discrepancy sequence from a seed's offset, mapped to the disc by the concentric map
 * (area-preserving, so the passes stay stratified). */
void CameraLensSample(std::uint32_t seed, int pass, double* u, double* v);


/**
 * Resolves Integrator::Auto: traces a pilot of 16 x 16 rays across the film with each candidate
 * (line of sight; Euler, midpoint, RK4) and against a reference (RK4, no octree) on the same
 * grid, and returns the settings of the cheapest candidate (fewest samples) whose
 * deflection error is within the tolerance and whose landing error is within half a pixel.
 * The reference shares the grid, so this measures integration error, not the grid's own. Its
 * step is only as fine as it needs to be: RK4 from 2 voxels, halved while two successive traces
 * differ by more than 5 % of the tolerance, down to 1/8 voxel. Candidates that cannot be cheaper
 * than the best one found (their cost predicted from the samples per voxel traced so far) are
 * not traced.
 * The steps are found from the pilot (issue 50): each integrator and reconstruction starts at 8
 * voxels, doubles while the candidate meets the tolerance (up to the volume's diagonal), halves
 * until one does where 8 does not, and bisects the last interval twice in log(step); a step
 * beyond 8 voxels meets only with 0.75 of the tolerance (after the trilinear's own error) and
 * without the kernel's step-longer-than-a-feature flag where the reference has none.
 * With UseOctree and volume.Levels, the octree is kept only if it skips at least 10 % of the
 * chosen setting's pilot samples (a skipping step costs more than a plain one).
 * Reconstruction Cubic's long steps are taken only through smooth data. Reconstruction Auto (with
 * Volume::Smooth) traces both references: their difference
 * is the trilinear scheme's own error, which a reference with the same reconstruction cannot see;
 * trilinear candidates are kept only where that error is within the tolerance and answer for
 * it on top of their own, and a tricubic sample is counted as three trilinear ones, so
 * that the cheaper reconstruction at the tolerance is chosen. With Reconstruction Auto and a fixed
 * integrator only the reconstruction is chosen.
 * Settings whose Method is not Auto (and whose Recon is not Auto) come back unchanged.
 * piecesBound: the steps stay within what tracing in pieces allows (8 voxels trilinear, 64
 * tricubic: the pieces' ghost layers), as ResolveAutoDistributed's do; one process then makes the
 * choice the pieces make (beyond those steps the two differ: the pieces' auto_report says so).
 * start (may be null): an earlier pilot's choice on the same volume and tolerance (another view):
 * its setting is traced first, so that candidates dearer than it are skipped from the start, and
 * the references' ladders begin at twice the steps it stopped at. The choice is the one the
 * search makes without it wherever the errors grow with the step (the search's premise).
 */
TraceSettings ResolveAuto(const Volume& volume, const TraceSettings& settings, AutoChoice* choice = nullptr,
  bool piecesBound = false, const AutoChoice* start = nullptr);

/** The film coordinates of Auto's pilot rays: one in each cell of an np x np grid over the film
 * (off its centre: an R2 sequence in the cell's middle half). The pilot traces 16 x 16. */
std::vector<float> PilotRays(const Volume& volume, const TraceSettings& settings, int np = 16);

const char* IntegratorName(Integrator m);
const char* ReconstructionName(Reconstruction r);
const char* CutoffName(Cutoff c);

/** Called with progress in [0, 1]; return false to abort (Trace then throws Error("aborted")). */
using ProgressFunction = std::function<bool(double)>;

/**
 * Traces and accumulates `settings.Passes` passes into `sums` (which may already hold earlier passes
 * of the same film). Does not normalise; see Finalize. Reports the backend used.
 */
void Accumulate(const Volume& volume, const TraceSettings& settings, FilmSums& sums,
  std::string* backendUsed = nullptr, std::string* deviceName = nullptr,
  std::string* warnings = nullptr, const ProgressFunction& progress = nullptr);

/** What a finite source implies (docs/BENCH.md), from the settings alone. */
struct BenchResponse
{
  bool Finite = false; ///< a finite source with KnifeEdge: the closed-form weights apply
  int Source = 0;      ///< SCH_SOURCE_*
  double ImageHeight = 0; ///< a0 = h f2 / f1, m
  double Size = 0;     ///< sch_bench_weight's size: a0 (slit, rectangle), R' (disc), sigma (Gaussian)
  double Edge = 0;     ///< d: the knife edge from the image's centre, m
  double Open = 0;     ///< 1 - KnifeCut: the share of the undisturbed beam that passes
  double Sensitivity = 0; ///< dI/I per radian at eps = 0
  double Dark = 0, Saturation = 0; ///< eps (radians) at full dark and at saturation
  double DarkWeight = 0, SaturatedWeight = 1; ///< the passing share at those ends
  double Resolvable = 0; ///< eps of one grey level of BitDepth: 1 / ((2^bits - 1) Open Sensitivity)
  std::string Model;
  /// A circular stop of StopDiameter (Circular, ComplementCircular): Size is the source image's
  /// R' (Disc) or sigma (Gaussian), 0 for Point; the Gaussian's share inside the stop is tabulated
  /// over the shift (StopTable, StopStep apart, from 0)
  bool Stop = false;
  bool Complement = false;
  double StopRadius = 0;
  std::vector<double> StopTable;
  double StopStep = 0;
};
BenchResponse ComputeBench(const TraceSettings& settings);
/** A circular stop's weight for a source image shifted by s (m, >= 0) in the cutoff plane: the
 * share of the image inside the stop (Circular) or outside it (ComplementCircular). */
double StopWeight(const BenchResponse& b, double s);

/** Turns sums into the image: intensity per the cutoff, mean deflection. */
TraceResult Finalize(const Volume& volume, const TraceSettings& settings, const FilmSums& sums);

/** Accumulate + Finalize. */
TraceResult Trace(const Volume& volume, const TraceSettings& settings,
  const ProgressFunction& progress = nullptr);

/** One ray's record, as the kernels write it (see SchlierenPhysics.h, SCH_REC_*). */
struct RayRecord
{
  float LandA, LandB;     ///< film coordinates where it lands
  float DeflX, DeflY;     ///< radians along film x, y
  float OpticalPathExcess;///< integral of (n-1) ds in the volume
  std::uint32_t Flags;    ///< RayFlags bits
  float Samples;
  float Drift;            ///< |v| - n at exit
  float Error;            ///< step-doubling estimate (EstimateError only)
  float Path;             ///< geometric path length in the volume
  float Mismatch;         ///< largest share of a step's index change its end gradients missed (> 0.5: RayUnderresolved)
  float Steps;
};

/** RayRecord::Flags bits (the same as SCH_RAY_* in SchlierenPhysics.h). */
enum RayFlags : std::uint32_t
{
  RayMissed = 1,
  RayMaxSteps = 2,
  RayTurned = 4,
  RayNonFinite = 8,
  RayOffFilm = 16,
  RayUnderresolved = 32,
  RaySide = 64,
  RayBlocked = 128 ///< stopped by a solid body (Volume::Solid)
};

/**
 * Traces rays that start on the emission plane at the given film coordinates (a, b pairs, relative
 * to the volume centre) and returns their records. For tests and probes.
 */
std::vector<RayRecord> TraceRays(const Volume& volume, const TraceSettings& settings,
  const std::vector<float>& filmAB, std::string* backendUsed = nullptr);

/** OpenCL facts. */
struct DeviceInfo
{
  bool Available = false;
  std::string Name, Platform, Version, Reason;
  std::uint64_t MaxAlloc = 0, GlobalMemory = 0;
};
/** The device the OpenCL backend would use for TraceSettings::DeviceName `deviceName` (a substring
 * of the device name; empty: the runtime options' device, SCHLIEREN_OPENCL_DEVICE, else the first
 * GPU, else the first device). Reason says why where none can be used. */
DeviceInfo QueryOpenCLDevice(const std::string& deviceName = std::string());

/** Builds OpenCL source on the engine's device; throws Error with the build log on failure.
 * The program is cached per device, options and source. */
void BuildOpenCLProgram(const std::string& name, const std::string& source, const std::string& options);

/** The embedded kernel text (physics header + kernels), as the OpenCL backend compiles it. */
const char* EmbeddedKernelSource();

Backend ParseBackend(const std::string& name);
const char* BackendName(Backend b);

} // namespace schlieren

#endif
