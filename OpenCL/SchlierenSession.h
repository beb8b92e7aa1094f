// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenSession.h
 * @brief One image traced again and again: what a SchlierenImage keeps between updates, and every
 * step of an update that involves more than one rank. VTK-free.
 *
 * A TraceSession takes this rank's piece of the input volume (its point extent within the whole
 * extent, n - 1 and the optional octree levels and solid points) and the trace settings, and
 * returns the image on rank 0. Between calls it keeps
 * - the packed volume of the whole extent (n - 1 and gradient, octree levels, solid points,
 *   smoothness) and its stamp, while the input's version, the pieces and the settings that shape
 *   the packing stay the same: a new camera, other optics or more passes do not pack it again, and
 *   the engine keeps its device copy (Volume::Stamp);
 * - the packed volumes of earlier inputs (the time steps of an animation: VolumePiece::Version
 *   names the input's time and pipeline), newest last, while they take at most a quarter of the
 *   memory the process could have (AvailableMemory() plus what they hold), the oldest evicted
 *   first: an animation played again traces its frames without packing them again;
 * - this rank's film sums of the passes traced so far (progressive refinement): with the same
 *   photons (TraceSettings::PhotonKey) and volume, raising Passes traces only the new passes.
 *
 * Every collective step goes through the Parallel passed in (all ranks call Update together):
 * assembling the whole volume from the pieces, the octree levels of the whole volume, Auto's choice
 * (made on rank 0 and broadcast), the trace of this rank's pixels (p % ranks == rank), the
 * reduction of the film sums, and after every step that can fail on some ranks only, one agreement
 * (so that no rank waits in a collective another one has left). A failure throws Error on every
 * rank: on a rank that failed, its own message; on the others the lowest failing rank's, as
 * Parallel::Failure words it.
 */
#ifndef SchlierenSession_h
#define SchlierenSession_h

#include "SchlierenDistributed.h"
#include "SchlierenEngine.h"
#include "SchlierenLimits.h"
#include "SchlierenParallel.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace schlieren
{

/** The values of a piece (what VolumePiece::Load fills). */
struct PieceValues
{
  std::vector<float> NMinus1; ///< n - 1 at the piece's points, x fastest
  /**
   * Or n - 1 read in place, without a copy (NMinus1 then empty): an input that already holds
   * floats, x fastest, that lives and does not change until the Update that loads it returns.
   */
  const float* NMinus1InPlace = nullptr;
  std::size_t NMinus1InPlaceCount = 0;
  /** n - 1 at the piece's points, from either; null where there are none. */
  const float* NMinus1Data() const
  {
    return this->NMinus1InPlace ? this->NMinus1InPlace
                                : this->NMinus1.empty() ? nullptr : this->NMinus1.data();
  }
  std::size_t NMinus1Size() const
  {
    return this->NMinus1InPlace ? this->NMinus1InPlaceCount : this->NMinus1.size();
  }
  /** Octree levels per point (RefractionOctree); empty: none. Used only with UseOctree. */
  std::vector<unsigned char> Levels;
  bool HasLevelTolerance = false; ///< the tolerance the levels were built for is known
  double LevelTolerance = 0.0;
  int MaxLevel = 7;
  /** Non-zero at points in a solid body; empty: no body in this piece. */
  std::vector<unsigned char> Solid;
};

/** This rank's piece of the input volume. */
struct VolumePiece
{
  int WholeExtent[6] = { 0, -1, 0, -1, 0, -1 }; ///< point indices of the whole volume
  int Extent[6] = { 0, -1, 0, -1, 0, -1 };      ///< this piece's (empty: no points on this rank)
  double Origin[3] = { 0, 0, 0 };  ///< world position of point index (0, 0, 0)
  double Spacing[3] = { 1, 1, 1 };
  /** Changes whenever the input's values may have changed (the filter: the input's MTime). */
  std::uint64_t Version = 0;
  /** Why this rank's input cannot be traced (a message for the user); empty: it can. */
  std::string Problem;
  /**
   * Fills the piece's values, or returns why they cannot be read (a message for the user).
   * Called only where the session needs the volume again and the piece has points.
   */
  std::function<std::string(PieceValues&)> Load;
};

/** What a SchlierenImage writes besides the image itself. */
struct SessionImage
{
  bool HasImage = false; ///< true on rank 0 (the others return no image)
  TraceResult Result;    ///< the image (rank 0)
  TraceSettings Traced;  ///< the settings traced with (Auto resolved; all passes)
  bool AutoAsked = false; ///< Integrator or Reconstruction was Auto: Choice says what it chose
  AutoChoice Choice;     ///< what was traced with (for Auto: what it chose, and its report)
  std::string Warnings;  ///< this rank's engine warnings, then Finalize's where they differ
  std::string BackendUsed, DeviceName;
  /** Distributed tracing (the volume in pieces, rays handed between ranks): the ranks it ran on;
   * 0 where every rank traced the whole volume. */
  int DistributedRanks = 0;
  double HeldPointsMax = 0;   ///< the most grid points any rank held (its piece and ghosts)
  double RaysHandedOn = 0;    ///< over all ranks and passes of this update
  double BytesExchanged = 0;  ///< ray states and records sent between ranks, all ranks
  double Rounds = 0;          ///< trace-and-exchange rounds of this update
  int GhostLayers = 0;        ///< ghost points around each rank's owned cells
  double SecondsTracing = 0;    ///< the longest any rank spent stepping rays (this update; the whole volume: the trace of its passes)
  double SecondsExchanging = 0; ///< the longest any rank spent in the exchanges, waiting included
  int Passes = 0;        ///< passes in the image
  int PassesTraced = 0;  ///< passes traced by this update (the others were kept)
  /** Where the packed volume came from: "packed" (by this update), "kept" (the last update's),
   * "cache" (an earlier input's, e.g. a time step traced before); VolumesCached: how many the
   * session holds besides the current one, VolumesPacked: how many it has packed in all. */
  std::string VolumeFrom;
  int VolumesCached = 0;
  int VolumesPacked = 0;
  /** Framing Silhouette: the frame traced with (Traced.FilmExtent), and whether it was kept
   * from an earlier update (only the view, Resolution or Passes changed since it was found). */
  bool Framed = false;
  bool FrameKept = false;
  SilhouetteFrame Frame;
  double LandedPhotons = 0; ///< photons that reached the film (0: a blank image)
  bool OctreeUsed = false;
  double OctreeTolerance = 0.0;
  /** What to tell the user, in order: Warning (vtkWarning) or not (an info line for the log). */
  struct Note
  {
    bool Warning;
    std::string Text;
  };
  std::vector<Note> Notes;
};

/**
 * One entry of an image's report: what SchlierenImage writes as the output's field data (the C++
 * filter, a vtkDoubleArray of Numbers or a vtkStringArray of Text) and what the C interface
 * returns as schlieren_session_report's "field_data" (the Python front end's field data). Made in
 * one place, ImageReport, so that the front ends list the same names and values in one order.
 */
struct ReportEntry
{
  std::string Name;
  bool IsText = false;
  std::vector<double> Numbers; ///< one value, or more (bench_range: two)
  std::string Text;
};

/** The report of a traced image (empty where `image` holds none), in vtkSchlierenImage's order. */
std::vector<ReportEntry> ImageReport(const SessionImage& image);

/**
 * The time left of an update, from the progress TraceSession::Update reports (its tracing runs
 * from 0.05 to 0.95 of it), for a front end's progress text. Started at construction.
 */
class TraceClock
{
public:
  explicit TraceClock(int passes);
  /** The text at `progress` (called with each report): once about one pass's share of the
   * tracing is done (at least 1 %) and a tenth of a second has passed, "SchlierenImage: 40 %
   * traced, about 3.2 s left"; empty before and from 0.95 on. */
  std::string Text(double progress);
  /** The share of the tracing done at the last report, in percent. */
  int Percent() const;

private:
  std::chrono::steady_clock::time_point Start;
  int Passes;
  double StartProgress = -1;
  double Reached = 0;
};

/** JSON text of a string (quoted, escaped) and of a number (%.17g; NaN and the infinities as
 * Python's json reads them): the C interface's and the BOS side file's. */
std::string JsonString(const std::string& s);
std::string JsonNumber(double v);
/** ImageReport as a JSON object {"name": value, ...} (numbers, [numbers] or text). */
std::string ImageReportJson(const SessionImage& image);

/**
 * BOS for the laboratory's software (docs/BENCH.md "BOS image pairs"): where and how WriteBOSPair
 * writes the pair.
 */
struct BOSPairRequest
{
  std::string Folder;         ///< an existing folder
  int Bits = 8;               ///< 8 or 16 bits per grey level
  std::string Format = "png"; ///< "png" or "tiff" ("tif")
  std::string Prefix = "bos"; ///< <Prefix>_background.<ext>, <Prefix>_recording.<ext>, <Prefix>.json
};

/** The paths WriteBOSPair wrote. */
struct BOSPairFiles
{
  std::string Background, Recording, SideFile;
};

/** The undistorted background of a BOS trace (nx*ny, film order): the pattern at the trace's own
 * emission points (Seed, Jitter, its `passes`), each landing where it left, through the same film
 * filter: the recording of the same film without the flow. */
std::vector<float> BOSBackground(const TraceSettings& traced, const FilmGeometry& film, int passes);

/** Writes a BOS image's recording (its intensity) and undistorted background (BOSBackground) as
 * grey images, and a JSON side file: the film's pixel size and axes, the bench (Z_D, the pattern,
 * the camera and its magnification), the displacement's units and sign, the trace's report.
 * Throws Error (one line) for an image that is not BOS, a folder that does not exist, a bit depth
 * other than 8 or 16, an unknown format, a prefix with a folder in it, or a file that cannot be
 * written. */
BOSPairFiles WriteBOSPair(const SessionImage& image, const BOSPairRequest& request);

class TraceSession
{
public:
  TraceSession() = default;
  /** Frees the engine's device copy of this session's volume. */
  ~TraceSession();
  TraceSession(const TraceSession&) = delete;
  TraceSession& operator=(const TraceSession&) = delete;

  /**
   * Traces `settings` (Passes in all; RankIndex/RankCount are set here) through the volume of the
   * pieces, continuing the kept sums where it can. Collective. `progress` (may be empty) gets the
   * fraction done; returning false aborts (Error "aborted"). Throws Error on every rank where any
   * rank failed; `out` then still holds the notes made before the failure.
   */
  void Update(Parallel& parallel, const VolumePiece& piece, const TraceSettings& settings,
    SessionImage& out, const ProgressFunction& progress = nullptr);

  /** The packed volume of the last update (Field null before one). */
  const Volume& KeptVolume() const { return this->Kept; }
  /** Drops what is kept (the next update packs and traces afresh). Not collective. */
  void Clear();
  /** Framing Silhouette: the frame of the last update (TraceSettings::FilmExtent); false where
   * there is none. */
  bool KeptFrame(double extent[4]) const
  {
    if (this->FrameKey.empty())
      return false;
    std::copy(this->Frame.Extent, this->Frame.Extent + 4, extent);
    return true;
  }
  /** How many times an update of this session has run Auto's pilot (the others kept a choice). */
  int Pilots() const { return this->PilotsRun; }

private:
  void ClearVolume();
  /** Moves the current volume among the earlier ones (evicting the oldest beyond the budget). */
  void StashVolume();
  /** Makes the earlier volume of `key` the current one; false where there is none. */
  bool RestoreVolume(const std::string& key, bool restore);
  /** Update with the volume in pieces (SchlierenSessionPieces.cxx): no rank holds the whole. */
  void UpdatePieces(Parallel& parallel, const VolumePiece& piece, const TraceSettings& settings,
    SessionImage& out, const ProgressFunction& progress);

  // the whole volume and what it was built from
  std::string VolumeKey;
  AlignedFloats Packed; // page-aligned: a CPU OpenCL device traces it in place
  std::vector<unsigned char> Levels, Solid;
  AlignedBytes Smooth; // written whole by PackFieldHighOrder: no zero fill first
  Volume Kept;
  struct EarlierVolume
  {
    std::string Key;
    AlignedFloats Packed;
    std::vector<unsigned char> Levels, Solid;
    AlignedBytes Smooth;
    Volume Kept;
    double Bytes = 0.0;
  };
  std::deque<EarlierVolume> Earlier; // oldest first
  int PacksRun = 0;
  bool Stamped = false; // a volume of this session has been stamped (the engine may keep it)
  // this rank's film sums and the photons and volume they were traced from
  std::string SumsKey;
  FilmSums Sums;
  // distributed tracing: this rank's piece with its ghosts, and what it was built from
  std::shared_ptr<DistributedVolume> Pieces;
  std::string PiecesKey;
  std::string PiecesBackend, PiecesDevice; // what the kept sums were traced on
  /**
   * Auto's choice kept between camera moves (the whole-volume path). An update whose volume and
   * settings other than ViewDirection, ViewUp, Resolution, Passes, Seed and the jitter are the
   * last pilot's keeps its choice: a camera move costs the trace, not the pilot, and so do
   * another seed, more passes and another film size (issue 50), where the choice's landing error
   * (the pilot's, in world units) stays within half a pixel of the new film. The pilot runs again
   * where the camera has come to rest (an update with the same view as the last one, which kept
   * a choice: the refinement's passes), where a film is so much finer that the landing is not
   * within half its pixel, and for any other change (the volume, the tolerance, the cutoff...).
   */
  AutoChoice ResolveKept(Parallel& parallel, const Volume& volume, TraceSettings& settings);
  /** The same for a volume whose version is `volumeKey` (not volume.Stamp: the pieces' key),
   * resolved by `resolve` (the pieces' pilot, collective) where a pilot runs. */
  AutoChoice ResolveKept(Parallel& parallel, const Volume& volume, TraceSettings& settings,
    const std::string& volumeKey, const std::function<AutoChoice(TraceSettings&)>& resolve);
  /** Framing Silhouette: sets settings.FilmExtent from the frame kept or found now (see
   * TraceSettings::Frame); out says which; `say`: add the note (rank 0). The frame is found by
   * `find` (FrameSilhouette of the volume, or of the pieces: collective), again where any rank
   * lost its key; `stamp`: the volume's. */
  void FrameKept(std::uint64_t stamp, Parallel& parallel, const std::function<SilhouetteFrame()>& find,
    TraceSettings& settings, SessionImage& out, bool say);
  std::string FrameKey; // empty: no frame kept
  SilhouetteFrame Frame;
  std::string AutoKey; // empty: no choice kept
  TraceSettings AutoTraced;
  AutoChoice AutoKept;
  double AutoView[6] = { 0, 0, 0, 0, 0, 0 }; // the last pilot's view
  double LastView[6] = { 0, 0, 0, 0, 0, 0 }; // the last update's
  int AutoResolution[2] = { 0, 0 };
  double AutoLanding = 0; // the kept choice's landing error, world units (on the pilot's film)
  const AutoChoice* PilotStart = nullptr; // while a pilot runs: the last one's choice, its start
  bool AutoChoiceKept = false; // the last update kept the choice for another view
  int PilotsRun = 0;
};

/**
 * The film an update of `settings` on the grid of `volume` (its values are not needed) is
 * expected to give, for a front end's output information before the trace: for Framing
 * Silhouette the session's last frame, before any the box's projection in the frame's shape (the
 * trace may then find another frame: the output's information follows the image).
 */
FilmGeometry PlannedFilm(const Volume& volume, TraceSettings settings, const TraceSession& session);

/**
 * Why an update of `settings` on more than one rank cannot trace the volume in pieces (empty:
 * it can): what distributed tracing does not take yet. The same on every rank.
 */
std::string WhyNotInPieces(const TraceSettings& settings);

/**
 * The whole volume from every rank's piece, on every rank (collective): returns n - 1 at its
 * points, in `field` or, for one rank's whole volume read in place, in that input (no copy); and
 * where any piece has a body, the solid points into `solid` (else it comes back empty). `values`
 * is this rank's; its vectors may be taken. Throws Error where the pieces do not cover the whole
 * extent (on every rank alike).
 */
const float* AssembleVolume(Parallel& parallel, const VolumePiece& piece, PieceValues& values,
  std::vector<float>& field, std::vector<unsigned char>& solid);

} // namespace schlieren

#endif
