// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenEngineInternal.h
 * @brief Internal (not installed): what the engine's stage files share.
 *
 * The stages of a trace, one file each: SchlierenField.cxx (grid checks, gradient, packing),
 * SchlierenOctree.cxx (the min-max octree), SchlierenCellBytes.cxx (the byte per cell the kernels
 * read: levels, smoothness, solid bits), SchlierenParams.cxx (settings to sch_params),
 * SchlierenFilm.cxx (film geometry, sums, the splatter), SchlierenFinalize.cxx (film filters,
 * sums to image, photon warnings), SchlierenAuto.cxx (Auto's pilot), SchlierenCpuBackend.cxx,
 * SchlierenOpenCLBackend.cxx, SchlierenTrace.cxx (Accumulate, Trace, TraceRays, the backend
 * choice) and SchlierenNames.cxx (enum names, the photon key). The runtime options (the
 * environment, read once) are in SchlierenOptions.h; the OpenCL context and program cache in
 * SchlierenOpenCL.h.
 */
#ifndef SchlierenEngineInternal_h
#define SchlierenEngineInternal_h

#include "SchlierenEngine.h"
#include "SchlierenLimits.h"
#include "SchlierenOptions.h"

// The physics, compiled as C++ for the CPU backend and for the host-side film. The CPU path
// advances SCH_PACKET rays in turn per packet (sch_trace_packet): more rays' steps in flight
// (docs/PERFORMANCE.md has the measurements behind the packet size).
#define SCH_PACKET 64
#include "SchlierenPhysics.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace schlieren
{

static_assert(sizeof(sch_params) % 4 == 0, "sch_params must hold only 4-byte members");
static_assert(sizeof(RayRecord) == SCH_RECORD * sizeof(float), "RayRecord mirrors SCH_RECORD");

// ------------------------------------------------------------------ field (SchlierenField.cxx)

/** Throws Error unless every dimension has at least 2 points and every spacing is positive, finite. */
void CheckGrid(const int dims[3], const double spacing[3]);
/** CheckGrid, and a field to trace. */
void CheckVolume(const Volume& v);

inline double MinSpacing(const Volume& v)
{
  return std::min(v.Spacing[0], std::min(v.Spacing[1], v.Spacing[2]));
}

// ------------------------------------------------------------------ octree (SchlierenOctree.cxx)

/**
 * ComputeOctreeLevels on a piece of a larger grid: `dims` points held, the first at grid index
 * `offset` of a grid of `whole` points. The blocks are the whole grid's (aligned on its index 0,
 * windows clamped to its borders), so a held cell gets the level the whole grid would give it
 * wherever its block's points are all held, and a lower one where they are not. With offset 0 and
 * whole == dims it is ComputeOctreeLevels. Returns the fraction of held cells at level >= 1.
 */
double ComputeOctreeLevelsOfPiece(const int dims[3], const int offset[3], const int whole[3],
  const float* n1, double tol, unsigned char* levels, int maxLevel);

// ------------------------------------------------------------------ field (SchlierenField.cxx)

/**
 * ValidateIndex, and the range [rangeLo, rangeHi] of the valid values (0, 0 where none is), in one
 * pass on every core. Empty where every value is usable, else the message ValidateIndex gives.
 */
std::string ScanIndex(const float* n1, std::size_t count, float& rangeLo, float& rangeHi);

/** The smoothness threshold the engine packs with (PackFieldHighOrder's default). */
constexpr double DefaultSmoothnessThreshold = 0.25;

/** PackField without its checks (CheckGrid, ValidateIndex): the caller's. bricked: `out` in
 * bricks (FieldLayout's floats, the padding repeating the border points), else linear. */
void PackFieldOf(const int dims[3], const double spacing[3], const float* n1, float* out,
  bool bricked = false);

/**
 * PackFieldHighOrder with the range of n - 1 given (the whole grid's, where `n1` is a piece of it:
 * the smoothness test's floor is a part of that range) and the smoothness levels (bits 4-6) stopped
 * at `levelMax` (1..7). On a piece held with ghosts, every value at least the stencils' reach from
 * the piece's faces is the one the whole grid gives (docs/PARALLEL.md). No validation: the caller's.
 */
double PackFieldHighOrderOf(const int dims[3], const double spacing[3], const float* n1, float* out,
  unsigned char* smooth, double threshold, float rangeLo, float rangeHi, int levelMax,
  bool bricked = false);

// ------------------------------------------------------------------ Auto (SchlierenAuto.cxx)

/** What ResolveAuto needs of a volume: its grid (no field needed) and which data it has. */
struct AutoVolume
{
  Volume Grid;
  bool HasLevels = false, HasSmooth = false, HasSolid = false;
  /** The candidates' steps stay within AutoPiecesReach (the pieces' ghost layers hold no
   * longer ones); false: up to the volume's diagonal. */
  bool PiecesBound = false;
  /** The report's steps are in voxels of the grid times this (a coarse copy's: the field's). */
  double ReportScale = 1.0;
};
/** Auto's coarse copy of a field (issue 50, SchlierenCoarse.cxx): the field's four values
 * resampled (4-point Lagrange along each axis) at Stride times its spacing over the same box,
 * its smoothness its own; certified against the field at every second point along each axis. */
struct CoarseCopy
{
  int Stride = 1;
  Volume V; ///< the copy (linear, stamped), pointing into Packed and Smooth
  AlignedFloats Packed; ///< page-aligned: a CPU OpenCL device traces it in place
  std::vector<unsigned char> Smooth;
  /** The largest difference of a gradient component between the copy's reconstruction (the
   * kernels' sampling) and the field's values at the checked points, per world unit. */
  double GradientGap = 0;
  /** GradientGap as a deflection, radians: sqrt 3 times it along the box's diagonal, over the
   * lowest n. No ray's deflection differs by more between the copy and the field. */
  double Bound = 0;
  /** The same sum for the copy's trilinear against its tricubic, radians: the trilinear's own
   * error on the copy, r^2 times the field's (second order). */
  double TrilinearBound = 0;
};
/** A copy has at least this many points along every axis. */
constexpr int CoarseMinPoints = 32;
/** Auto tries a copy for grids of at least this many points (the field past the caches). */
constexpr double CoarseFromPoints = 256.0 * 256.0 * 256.0;
/** A copy's field is at most this many bytes (one device buffer, PoCL's limit half of it). */
constexpr double CoarseMaxBytes = 512.0 * 1024 * 1024;
/** The share of the tolerance a copy's Bound may take. */
constexpr double CoarseShare = 0.25;
/** The copy of stamped volume v at `stride` (2 or 4), kept for the last stamped volume (every
 * stride asked); null where the volume is not stamped or the copy would have fewer than
 * CoarseMinPoints along an axis. */
std::shared_ptr<const CoarseCopy> CoarseCopyOf(const Volume& v, int stride);
/** Lets go of the copies CoarseCopyOf keeps. */
void ReleaseCoarseCopies();
/** Whether Auto may trace `in` on v from a coarse copy: Integrator Auto with Cubic or Auto
 * reconstruction and a Tolerance given, one process's stamped volume of CoarseFromPoints or
 * more, high-order packed, no body, no phase (Interferometry), one wavelength, no error
 * estimate, and the runtime options' CoarseCopies. */
bool CoarseEligible(const Volume& v, const TraceSettings& in, bool piecesBound);

/** The longest step Auto's candidates take on the pieces of a distributed volume, voxels:
 * 8 trilinear, 64 tricubic (the ghost layers are sized for them, GhostPointsFor). */
double AutoPiecesReach(bool cubic);
/** The device Auto's pilot traces on for settings `in`: the CPU where `in` asks for it or where
 * its OpenCL device is itself a CPU (the C++ build, nothing to compile), else `in`'s. */
Backend PilotDevice(const TraceSettings& in);
/** Traces the pilot's rays (film points, pairs) with settings t: TraceRays, or a distributed trace
 * that returns the same records on every rank (so that every rank makes the same choice). */
using PilotTracer =
  std::function<std::vector<RayRecord>(const TraceSettings& t, const std::vector<float>& ab)>;
/** ResolveAuto with the pilot traced by `traceRays`. */
TraceSettings ResolveAutoWith(const AutoVolume& grid, const TraceSettings& in, AutoChoice* choice,
  const PilotTracer& traceRays, const AutoChoice* start = nullptr);

// ------------------------------------------------------------------ film (SchlierenFilm.cxx)

/** Half the extent of the box of grid points along each axis, from the grid itself. */
void HalfExtent(const Volume& v, double h[3]);

/**
 * Puts photons on the film. Runs on the host, in ray order, for both backends: the image does not
 * depend on the order threads finish in, and both backends share this code.
 */
struct Splatter
{
  const sch_params& P;
  const TraceSettings& S;
  FilmSums& F;
  float ca, sa, k;
  bool manual;
  BenchResponse Bench; ///< a finite source's closed-form knife (Finite false: the point source)
  double twoPiOverLambda, tilt, bgPlane, period;
  /// Camera Lens: this pass's tilt (CameraPass); camera: a camera images the focus plane
  double lensTilt[2] = { 0, 0 };
  bool camera = false;
  /// A band of wavelengths (SpectralWavelength): this pass's X, Y, Z (summed in the film's
  /// Red, Green and Blue channels), and Wavelength / its wavelength
  /// (ReferenceTilt is a path difference counted in Wavelength's fringes)
  bool white = false;
  double passColour[3] = { 1, 1, 1 };
  double tiltScale = 1.0;

  Splatter(const sch_params& p, const TraceSettings& s, FilmSums& f);
  /** Pass `pass`'s kernel parameters Pk (from the trace's P) and this splatter's state for it:
   * the camera's tilt (CameraPass) and a band's wavelength (SpectralWavelength). */
  void BeginPass(sch_params& Pk, int pass);
  /** The photon's weight under the cutoff, with energy weighting or (optionally) photon killing. */
  float CutoffWeight(float ex, float ey, float landA, double phase, sch_uint pix) const;
  /** Adds `count` records (SCH_RECORD floats each) of the rays first, first + 1, ... of this rank:
   * on two threads where the trace may use two (CpuThreads), each adding the photons that land
   * in its film rows, so that every pixel takes its photons in the records' order (the sums of
   * one thread, bit for bit). */
  void Add(const float* rec, std::size_t first, std::size_t count);
  /** Add's work for the photons that land in rows [rowLo, rowHi) (and the rays blocked there);
   * the totals and maxima of all the records where `totals`. */
  void AddRows(const float* rec, std::size_t first, std::size_t count, int rowLo, int rowHi,
    bool totals);
  unsigned Threads = 1;
};

// ------------------------------------------------------------------ camera (SchlierenCamera.cxx)

/** The camera's view of pass `pass` (Camera Lens): P's beam direction tilted toward the pass's
 * lens point and its emission moved by -tilt FocusPlane, so that an undisturbed ray crosses the
 * focus plane at its pixel. tilt: the tilted direction's slopes along the film's right and top
 * axes (across over along the beam); the ray's film coordinate is its coordinate in the tilted
 * frame plus tilt times its depth (the splatter adds tilt sFilm to a landing). Returns false (P untouched, tilt 0) for None
 * and Ideal. */
bool CameraPass(const TraceSettings& s, sch_params& P, int pass, double tilt[2]);

/** The camera's read-outs (TraceResult::Camera) for a trace onto film f. */
TraceResult::CameraReadouts ComputeCamera(const TraceSettings& s, const FilmGeometry& f);

// ------------------------------------------------------------------ light (SchlierenSpectrum.cxx)

/** A band's wavelength (nm) for pass `pass` (TraceSettings::WavelengthRange set). */
double SpectralWavelength(const TraceSettings& s, int pass);
/** (n(nm) - 1) / (n(Wavelength) - 1) under s.Disperse. */
double DispersionScale(const TraceSettings& s, double nm);
/** The CIE 1931 tristimulus values of light of wavelength nm (an analytic fit, Wyman et al. 2013). */
void SpectralXYZ(double nm, double xyz[3]);
/** The mean SpectralXYZ of passes 0 .. passes - 1: the band's white. */
void SpectrumMeanXYZ(const TraceSettings& s, int passes, double xyz[3]);
/** Linear sRGB in [0, 1] of a pixel's X, Y, Z as shares of the band's white's (1, 1, 1: white). */
void BandColour(const double share[3], float rgb[3]);
/** The field data's account of the band after `passes` passes; scale: n - 1's at its ends. */
std::string SpectrumText(const TraceSettings& s, int passes, double scale[2]);

/** The film filter (settings.Filter, FilterWidth) applied to every per-pixel sum of `f` alike, as
 * Finalize does (SchlierenFinalize.cxx); the BOS pair's background (SchlierenBOSPair.cxx) too. */
void FilterSums(FilmSums& f, const TraceSettings& s);

// ------------------------------------------------------------------ parameters (SchlierenParams.cxx)

/** The kernels' parameters for a trace of `volume` with settings `s` onto film `f`; throws Error on
 * settings the tracer cannot take. featureTol is left 0: see SetFeatureTolerance. */
sch_params MakeParams(const Volume& volume, const TraceSettings& s, const FilmGeometry& f);
/// Whether the steps of a trace with these parameters ask for their next sample's cache lines
/// (sch_prefetch_at): SCHLIEREN_PREFETCH where set, else where it pays (large fields, oblique views)
bool PrefetchPays(const sch_params& P);

/** What identifies a stamped volume's contents (Volume::Stamp). */
struct VolumeIdentity
{
  const float* Field = nullptr;
  const unsigned char* Levels = nullptr;
  const unsigned char* Solid = nullptr;
  int Dimensions[3] = { 0, 0, 0 };
  std::uint64_t Stamp = 0;

  explicit VolumeIdentity(const Volume& v)
    : Field(v.Field)
    , Levels(v.Levels)
    , Solid(v.Solid)
    , Stamp(v.Stamp)
  {
    std::copy(v.Dimensions, v.Dimensions + 3, Dimensions);
  }
  VolumeIdentity() = default;
  bool operator==(const VolumeIdentity& o) const
  {
    return Stamp != 0 && Stamp == o.Stamp && Field == o.Field && Levels == o.Levels &&
      Solid == o.Solid && std::equal(Dimensions, Dimensions + 3, o.Dimensions);
  }
};

/** Guards everything the engine keeps from one call to the next (kept tracer, cell bytes, range). */
extern std::mutex KeptMutex;

/**
 * Sets P.featureTol: a step that leaves more than 1 % of the field's index range unexplained by the
 * gradient (or more than the octree tolerance) has jumped over structure. Reads the whole field
 * where its range is not kept (KeepIndexRange): call it once the backend has accepted the volume.
 */
void SetFeatureTolerance(sch_params& P, const Volume& volume);
/**
 * Tells SetFeatureTolerance the range of a stamped volume's n - 1, found while packing it, so that
 * the first trace does not read the whole field again. Ignored for a volume without a stamp. The
 * last few volumes' ranges are kept (a field and its certified copies, which Auto's pilot traces
 * in turn); SetFeatureTolerance keeps the ranges it finds too.
 */
void KeepIndexRange(const Volume& volume, float lo, float hi);
/** How many times SetFeatureTolerance read a whole field for its range (for tests). */
std::size_t IndexRangeScans();
/** The feature tolerance for a field whose n - 1 spans [lo, hi] (SetFeatureTolerance's rule). */
float FeatureTolerance(float lo, float hi, double levelTolerance);

/** The longest step a trace with parameters P takes (the step-doubling estimate doubles it). */
inline double StepReach(const sch_params& P)
{
  return double(P.step) * (P.estimate ? 2.0 : 1.0);
}

/** The rays this rank traces per pass (pixels p with p % rayStride == rayOffset). */
std::size_t RaysForRank(const sch_params& P);

// ------------------------------------------------------------------ cell bytes (SchlierenCellBytes.cxx)

/**
 * The cell bytes for a trace with steps of up to `reach` world units: the volume's levels (or
 * null) without a body; with one, the solid, near and lowered-level bits, kept for the last
 * stamped volume and reach.
 */
std::shared_ptr<const std::vector<unsigned char>> CellBytesOf(const Volume& v, double reach);

/** The bytes CellBytesOf keeps: for a volume with Solid (and Levels, or null), steps of `reach`. */
std::vector<unsigned char> MakeCellBytes(const Volume& v, double reach);

/**
 * The volume as the kernels see it: with Volume::Smooth, its levels buffer holds the smoothness
 * bits above the octree levels; `own` holds the merged bytes of this call.
 */
Volume TraceVolume(const Volume& v, std::shared_ptr<std::vector<unsigned char>>& own);

// ------------------------------------------------------------------ the field's layout (SchlierenField.cxx)

/** The kernels' layout of the packed field (sch_params' fieldShift): bricks of 2^FieldBrickShift
 * points a side, so that a ray in any direction reads lines and pages its neighbours and its last
 * samples read (a 4^3 brick is 1 KiB: Cubic's 4^3 footprint, a trilinear cell in one to eight). */
constexpr int FieldBrickShift = 2;

/** Bricks of a field of dims points: the grid rounded up to whole bricks along each axis. */
struct BrickLayout
{
  std::uint64_t Bricks[3] = { 0, 0, 0 };
  explicit BrickLayout(const int dims[3]);
  /** floats of a brick, of one layer of bricks along z (2^FieldBrickShift planes), of the field */
  static std::uint64_t BrickFloats() { return std::uint64_t(4) << (3 * FieldBrickShift); }
  std::uint64_t LayerFloats() const { return BrickFloats() * Bricks[0] * Bricks[1]; }
  std::uint64_t Floats() const { return LayerFloats() * Bricks[2]; }
};

/** Whether a field of dims points can be laid out in bricks: the kernels' strides are ints, and
 * a layer of bricks must fit in one. */
bool BricksFit(const int dims[3]);

/** Where point (i, j, k) of a packed field sits (its first float), in bricks (BrickLayout) or
 * linear: the kernels' addressing (sch_axis_offset), for the host. */
struct FieldLayout
{
  int Shift = 31, Mask = -1;
  int Inner[3] = { 4, 0, 0 }, Outer[3] = { 0, 0, 0 };
  std::uint64_t Floats = 0; ///< the field's floats (bricks: the grid rounded up to whole bricks)
  bool Bricked = false;
  /** bricked where BricksFit(dims), else linear */
  FieldLayout(const int dims[3], bool bricked);
  std::size_t Row = 0, Plane = 0; ///< linear: floats a row of x, a plane (size_t: any grid)
  std::size_t At(int i, int j, int k) const
  {
    if (!Bricked)
      return 4 * std::size_t(i) + Row * j + Plane * k;
    return static_cast<std::size_t>(sch_axis_offset(i, Shift, Mask, Outer[0], Inner[0]) +
      sch_axis_offset(j, Shift, Mask, Outer[1], Inner[1]) +
      sch_axis_offset(k, Shift, Mask, Outer[2], Inner[2]));
  }
};

/** Sets P's field layout for its held points (P.nx, P.ny): bricks (BrickLayout) where `bricked`
 * and BricksFit, else the linear layout of Volume::Field. */
void SetFieldLayout(sch_params& P, bool bricked);

/** Whether a TraceSession packs a volume of dims points in bricks (Volume::FieldInBricks): where
 * the options say (SCHLIEREN_FIELD_BRICKS 0 or 1) or, unset, where they pay (docs/PERFORMANCE.md:
 * grids past BricksFromPoints, on every backend and reconstruction, where the padding to whole
 * bricks adds at most a tenth); never where they do not fit (BricksFit). */
bool PackInBricks(const int dims[3]);
/** PackInBricks's threshold, unset: bricks for grids of more points than this. */
constexpr double BricksFromPoints = 300.0 * 300.0 * 300.0;

/** Volume::Field (linear) rearranged in bricks (BrickLayout; the points past the grid repeat its border
 * points), kept for the last stamped volume (ReleaseKeptVolume lets it go). Throws std::bad_alloc
 * where the copy would take more than half the memory left (AvailableMemory). */
std::shared_ptr<const AlignedFloats> BrickedField(const Volume& v);
/** Lets go of the bricks BrickedField keeps. */
void ReleaseBrickedField();

// ------------------------------------------------------------------ CPU backend (SchlierenCpuBackend.cxx)

/** Threads the CPU backend runs on: `requested` (TraceSettings::Threads) where positive, else the
 * runtime options' CpuThreads where positive, else every hardware thread; at most
 * MaxCpuThreads(). */
unsigned CpuThreads(int requested = 0);

/** The most threads the CPU backend starts: 16 per hardware thread (more only share the cores
 * and each reserves a stack of address space). Threads up to 4096 are accepted and capped here. */
unsigned MaxCpuThreads();

/**
 * Runs work(0) .. work(n - 1), each index on its own thread where the system gives one (work(0)
 * on the calling thread). Where it refuses a thread (the address-space limit, the process limit),
 * the indices left run on the calling thread after work(0): the result is the same, only slower.
 * An exception thrown by any work(t) is rethrown here after every thread has been joined.
 */
void RunOnThreads(unsigned n, const std::function<void(unsigned)>& work);

/** Traces rays first .. first + count - 1 of this rank's pass P.pass into `out` (SCH_RECORD each),
 * on `threadCount` threads (0: CpuThreads()). The records do not depend on the thread count. */
void TraceChunkCPU(const float* field, const unsigned char* levels, const sch_params& P,
  std::size_t first, std::size_t count, float* out, unsigned threadCount = 0);

// ------------------------------------------------------------------ OpenCL backend (SchlierenOpenCLBackend.cxx)

/** The OpenCL tracer: the device's copy of a volume, its kernels and records buffer. */
class OpenCLTracer;

/**
 * The OpenCL tracer for `volume` with cell bytes `bytes` (held alive by `bytesOwner`), its records
 * buffer for at least `chunk` rays, on the device whose name contains `deviceName` (empty: the
 * options' device) with the OpenCL options of `options`: the kept one where all of these match,
 * else a new one (kept where the volume is stamped). Throws Error where the device cannot take
 * the volume or none matches. bricked: volume.Field is in bricks (BrickedField), else linear.
 */
std::shared_ptr<OpenCLTracer> AcquireTracer(const Volume& volume, const unsigned char* bytes,
  const std::shared_ptr<const void>& bytesOwner, std::size_t chunk, int raysPerItem,
  const RuntimeOptions& options, const std::string& deviceName, bool bricked = false);

/** Builds (or finds) the kernel that TraceOpenCL (points false) or TracePointsOpenCL (true) runs
 * for P; throws Error on a build failure. */
void PrepareKernel(OpenCLTracer& t, const sch_params& P, bool points);

/** The device's name, and how the field is split on it, for TraceResult::DeviceName. */
std::string TracerDeviceName(const OpenCLTracer& t);

/** Whether the OpenCL device a trace with this DeviceName would take (empty: the runtime options')
 * is a CPU (CL_DEVICE_TYPE_CPU: PoCL here); false where no such device can be used. */
bool OpenCLDeviceIsCPU(const std::string& deviceName);
/** The OpenCL programs built (or failed) in this process so far (ocl::ProgramsBuilt; for tests). */
std::size_t OpenCLProgramsBuilt();

/** TraceChunkCPU on the device. */
void TraceOpenCL(OpenCLTracer& t, const sch_params& P, std::size_t first, std::size_t count, float* out);

/** Builds (or finds) the kernel WalkPiecesOpenCL runs for P; throws Error on a build failure. */
void PreparePiecesKernel(OpenCLTracer& t, const sch_params& P);

/** Distributed tracing on the device: advances `count` rays in place until each leaves the volume
 * (status 0, its record in out) or the cells P.own* (status 1). */
void WalkPiecesOpenCL(OpenCLTracer& t, const sch_params& P, sch_piece_ray* rays, std::size_t count,
  float* out, int* status);

/** Traces rays that start at the film points ab (pairs) into `out` (SCH_RECORD each). */
void TracePointsOpenCL(
  OpenCLTracer& t, const sch_params& P, const float* ab, std::size_t count, float* out);

// ------------------------------------------------------------------ backend choice (SchlierenTrace.cxx)

/**
 * The OpenCL tracer for this trace, or null for the CPU (asked for, or OpenCL unusable under Auto,
 * with a warning). points: the caller traces explicit film points (TracePoints) rather than passes
 * (Trace); the kernel it will run is built here, so that a build failure falls back too.
 */
std::shared_ptr<OpenCLTracer> OpenBackend(const Volume& volume, const unsigned char* bytes,
  const std::shared_ptr<const void>& bytesOwner, const TraceSettings& s, const sch_params& P,
  std::size_t chunk, bool points, std::string& used, std::string& device, std::string& warnings);

} // namespace schlieren

#endif
