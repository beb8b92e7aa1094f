// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenSession.h"
#include "SchlierenEngineInternal.h"
#include "SchlierenSessionInternal.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <new>
#include <sstream>

namespace schlieren
{

namespace
{
bool IsEmpty(const int ext[6])
{
  return ext[1] < ext[0] || ext[3] < ext[2] || ext[5] < ext[4];
}
} // namespace

std::size_t ExtentPoints(const int ext[6])
{
  return IsEmpty(ext) ? 0
                      : static_cast<std::size_t>(ext[1] - ext[0] + 1) * (ext[3] - ext[2] + 1) *
      (ext[5] - ext[4] + 1);
}

void AgreeOrThrow(Parallel& parallel, const std::string& mine)
{
  const std::string failure = parallel.Failure(mine);
  if (!failure.empty())
    throw Error(mine.empty() ? failure : mine);
}

std::string LoadPiece(
  const VolumePiece& piece, const TraceSettings& settings, int ranks, PieceValues& values)
{
  std::string problem = piece.Problem;
  const std::size_t count = ExtentPoints(piece.Extent);
  if (problem.empty() && settings.Passes < 1)
    problem = "Passes is " + std::to_string(settings.Passes) +
      "; it must be at least 1 (one photon per pixel per pass).";
  else if (problem.empty() && count > 0)
  {
    try
    {
      problem = piece.Load ? piece.Load(values) : std::string("no values for the input piece");
      if (problem.empty() && values.NMinus1Size() != count)
        problem = "The input piece has " + std::to_string(values.NMinus1Size()) +
          " values of n - 1 for its " + std::to_string(count) + " points.";
    }
    catch (const std::bad_alloc&)
    {
      problem = "Out of memory while reading the input (std::bad_alloc): resample it to fewer "
                "points.";
    }
  }
  else if (problem.empty() && ranks == 1)
    problem = "SchlierenImage: the input image is empty.";
  return problem;
}

void LoadPieceAgreed(Parallel& parallel, const VolumePiece& piece, const TraceSettings& settings,
  PieceValues& values)
{
  const int ranks = parallel.Size();
  // no whole grid on this rank: its input's information failed here (a reader of a file missing
  // on this rank alone: fuzz_mpi), while the others have theirs
  const bool noGrid = ranks > 1 && piece.Problem.empty() && ExtentPoints(piece.WholeExtent) == 0;
  AgreeOrThrow(parallel, noGrid ? "The input volume is empty on rank " + std::to_string(parallel.Rank()) +
        ": nothing to trace. If a filter upstream reported an error there, that is the cause; "
        "fix it there."
                                : LoadPiece(piece, settings, ranks, values));
  if (ranks <= 1)
    return;
  // each rank's grid against the largest and smallest of every rank's (one all-reduce)
  double grid[12];
  for (int a = 0; a < 6; ++a)
    grid[a] = piece.WholeExtent[a];
  for (int a = 0; a < 3; ++a)
  {
    grid[6 + a] = piece.Origin[a] + piece.WholeExtent[2 * a] * piece.Spacing[a];
    grid[9 + a] = piece.Spacing[a];
  }
  double range[24];
  for (int k = 0; k < 12; ++k)
  {
    range[k] = grid[k];
    range[12 + k] = -grid[k];
  }
  parallel.Max(range, 24);
  double scale = 0;
  for (int a = 0; a < 3; ++a)
    scale = std::max(scale, std::fabs(range[9 + a]));
  for (int k = 0; k < 12; ++k)
  {
    const double hi = range[k], lo = -range[12 + k];
    // extents exactly; origins and spacings to rounding of the spacing
    const double allowed = k < 6 ? 0.0 : 1e-9 * scale;
    if (!(hi - lo <= allowed))
    {
      std::ostringstream msg;
      msg.precision(10);
      msg << "Distributed volume: the ranks' pieces are not of one grid: "
          << (k < 6 ? "whole extent" : k < 9 ? "origin" : "spacing") << " component "
          << (k < 6 ? k : (k - 6) % 3) << " is " << lo << " on some rank and " << hi
          << " on another (each rank must hold a piece of the same image data; this rank's: "
          << "whole extent " << piece.WholeExtent[0] << ' ' << piece.WholeExtent[1] << ' '
          << piece.WholeExtent[2] << ' ' << piece.WholeExtent[3] << ' ' << piece.WholeExtent[4]
          << ' ' << piece.WholeExtent[5] << ").";
      throw Error(msg.str());
    }
  }
}

namespace
{

/** The grid (without its field) of the whole extent. */
Volume WholeGrid(const VolumePiece& piece)
{
  Volume volume;
  for (int a = 0; a < 3; ++a)
  {
    volume.Dimensions[a] = std::max(piece.WholeExtent[2 * a + 1] - piece.WholeExtent[2 * a] + 1, 0);
    volume.Origin[a] = piece.Origin[a] + piece.WholeExtent[2 * a] * piece.Spacing[a];
    volume.Spacing[a] = piece.Spacing[a];
  }
  return volume;
}

/** Copies a piece (its extent and x-fastest values) into the whole grid; marks what it covers. */
template <typename T>
void Insert(const int whole[6], const int ext[6], const T* values, T* grid, unsigned char* covered)
{
  if (IsEmpty(ext))
    return;
  const std::size_t nx = whole[1] - whole[0] + 1, ny = whole[3] - whole[2] + 1;
  const int len = ext[1] - ext[0] + 1;
  std::size_t src = 0;
  for (int k = ext[4]; k <= ext[5]; ++k)
    for (int j = ext[2]; j <= ext[3]; ++j)
    {
      const std::size_t row = ((k - whole[4]) * ny + (j - whole[2])) * nx + (ext[0] - whole[0]);
      std::copy(values + src, values + src + len, grid + row);
      if (covered)
        std::fill(covered + row, covered + row + len, 1);
      src += len;
    }
}

bool InsideWhole(const int whole[6], const int ext[6])
{
  for (int a = 0; a < 3; ++a)
    if (ext[2 * a] < whole[2 * a] || ext[2 * a + 1] > whole[2 * a + 1])
      return false;
  return true;
}

/** The numbers of Auto's choice, in the order rank 0 broadcasts them. */
std::vector<double> ChoiceNumbers(const TraceSettings& chosen, const AutoChoice& c)
{
  return { double(static_cast<int>(chosen.Method)), chosen.StepSize, chosen.AutoMeasuredError,
    c.ExpectedError, c.ExpectedLandingError, c.SamplesPerRay, c.Tolerance, c.Met ? 1.0 : 0.0,
    chosen.UseOctree ? 1.0 : 0.0, double(static_cast<int>(chosen.Recon)), c.TrilinearError,
    c.Floor, c.AtFloor ? 1.0 : 0.0, c.ReferenceError, double(chosen.FieldStride), c.CoarseBound };
}

/**
 * Resolves Integrator and Reconstruction Auto on rank 0 (its pilot traces the rays every rank
 * would; resolving once and broadcasting makes every rank trace with the same setting even where
 * backends round differently) and adopts the choice on every rank. Other settings come back as
 * they are. Collective.
 */
AutoChoice ResolveOnRankZero(Parallel& parallel, const Volume& volume, TraceSettings& settings,
  const AutoChoice* start)
{
  AutoChoice choice;
  if (settings.Method != Integrator::Auto && settings.Recon != Reconstruction::Auto)
  {
    choice.Method = settings.Method;
    choice.StepSize = settings.StepSize;
    choice.Recon = settings.Recon;
    return choice;
  }
  std::string problem;
  std::vector<double> numbers(16, 0.0);
  if (parallel.Rank() == 0)
  {
    try
    {
      TraceSettings pilot = settings;
      pilot.RankIndex = 0;
      pilot.RankCount = 1;
      const TraceSettings chosen = ResolveAuto(volume, pilot, &choice, false, start);
      numbers = ChoiceNumbers(chosen, choice);
    }
    catch (const Error& e)
    {
      problem = e.what();
    }
  }
  AgreeOrThrow(parallel, problem);
  std::vector<char> bytes(numbers.size() * sizeof(double));
  std::memcpy(bytes.data(), numbers.data(), bytes.size());
  parallel.Broadcast(bytes, 0);
  std::memcpy(numbers.data(), bytes.data(), std::min(bytes.size(), numbers.size() * sizeof(double)));
  choice.Report = parallel.BroadcastString(choice.Report, 0);
  settings.Method = static_cast<Integrator>(static_cast<int>(numbers[0]));
  settings.StepSize = numbers[1];
  settings.AutoMeasuredError = numbers[2];
  settings.UseOctree = numbers[8] == 1.0;
  settings.Recon = static_cast<Reconstruction>(static_cast<int>(numbers[9]));
  choice.Method = settings.Method;
  choice.StepSize = settings.StepSize;
  choice.ExpectedError = numbers[3];
  choice.ExpectedLandingError = numbers[4];
  choice.SamplesPerRay = numbers[5];
  choice.Tolerance = numbers[6];
  choice.Met = numbers[7] == 1.0;
  choice.UseOctree = settings.UseOctree;
  choice.Recon = settings.Recon;
  choice.TrilinearError = numbers[10];
  choice.Floor = numbers[11];
  choice.AtFloor = numbers[12] == 1.0;
  choice.ReferenceError = numbers[13];
  settings.FieldStride = static_cast<int>(numbers[14]);
  choice.FieldStride = settings.FieldStride;
  choice.CoarseBound = numbers[15];
  return choice;
}

/** This rank's piece as one message: extent, whether it has a body, n - 1, the solid points. */
std::vector<char> PieceMessage(const int ext[6], const PieceValues& values, bool hasSolid)
{
  const std::size_t n = values.NMinus1Size();
  std::vector<char> m(6 * sizeof(int) + 1 + n * sizeof(float) + (hasSolid ? n : 0));
  char* p = m.data();
  std::memcpy(p, ext, 6 * sizeof(int));
  p += 6 * sizeof(int);
  *p++ = hasSolid ? 1 : 0;
  if (n)
    std::memcpy(p, values.NMinus1Data(), n * sizeof(float));
  p += n * sizeof(float);
  if (hasSolid)
    std::memcpy(p, values.Solid.data(), n);
  return m;
}

} // namespace

//------------------------------------------------------------------------------
const float* AssembleVolume(Parallel& parallel, const VolumePiece& piece, PieceValues& values,
  std::vector<float>& field, std::vector<unsigned char>& solid)
{
  const int* whole = piece.WholeExtent;
  const std::size_t total = ExtentPoints(whole);
  const std::size_t count = ExtentPoints(piece.Extent);
  // the solid points, as 0 or 1; a piece without a non-zero one has no body
  bool hasSolid = values.Solid.size() == count && count > 0 &&
    std::any_of(values.Solid.begin(), values.Solid.end(), [](unsigned char s) { return s != 0; });
  if (hasSolid)
    for (unsigned char& s : values.Solid)
      s = s != 0 ? 1 : 0;
  field.clear();
  solid.clear();
  if (parallel.Size() == 1 && std::equal(piece.Extent, piece.Extent + 6, whole))
  {
    // the whole volume in one piece: taken as it is (read in place where the input allows)
    if (hasSolid)
      solid.swap(values.Solid);
    if (values.NMinus1InPlace)
      return values.NMinus1InPlace;
    field.swap(values.NMinus1);
    return field.data();
  }
  std::vector<std::vector<char>> all = parallel.AllGather(PieceMessage(piece.Extent, values, hasSolid));
  std::vector<float>().swap(values.NMinus1);
  field.assign(total, 0.0f);
  std::vector<unsigned char> covered(total, 0);
  bool anySolid = false;
  bool fits = true;
  for (const std::vector<char>& m : all)
  {
    int ext[6];
    // (a message too short for its head cannot be: the pieces are then taken as not fitting)
    if (m.size() < 6 * sizeof(int) + 1)
    {
      fits = false;
      break;
    }
    std::memcpy(ext, m.data(), 6 * sizeof(int));
    const std::size_t n = ExtentPoints(ext);
    const bool withSolid = m[6 * sizeof(int)] != 0;
    anySolid = anySolid || withSolid;
    fits = fits && (n == 0 || InsideWhole(whole, ext)) &&
      m.size() == 6 * sizeof(int) + 1 + n * sizeof(float) + (withSolid ? n : 0);
  }
  if (fits)
  {
    if (anySolid)
      solid.assign(total, 0);
    for (const std::vector<char>& m : all)
    {
      int ext[6];
      std::memcpy(ext, m.data(), 6 * sizeof(int));
      const std::size_t n = ExtentPoints(ext);
      const char* p = m.data() + 6 * sizeof(int) + 1;
      std::vector<float> v(n);
      if (n)
        std::memcpy(v.data(), p, n * sizeof(float));
      Insert(whole, ext, v.data(), field.data(), covered.data());
      if (m[6 * sizeof(int)] != 0)
        Insert(whole, ext, reinterpret_cast<const unsigned char*>(p + n * sizeof(float)),
          solid.data(), nullptr);
    }
  }
  // the same answer on every rank: no agreement needed
  if (!fits || std::find(covered.begin(), covered.end(), 0) != covered.end())
  {
    field.clear();
    solid.clear();
    throw Error("The input pieces do not cover the input's whole extent; the tracer needs the "
                "whole volume.");
  }
  return field.data();
}

//------------------------------------------------------------------------------
TraceSession::~TraceSession()
{
  // the engine's device copy may be this session's volume: free it with the session
  if (this->Stamped)
    ReleaseKeptVolume();
}

void TraceSession::Clear()
{
  this->FrameKey.clear();
  this->ClearVolume();
  this->SumsKey.clear();
  this->Sums.Resize(0, 0);
  this->Pieces.reset();
  this->PiecesKey.clear();
}

void TraceSession::StashVolume()
{
  if (this->Kept.Field && !this->VolumeKey.empty())
  {
    EarlierVolume e;
    e.Key = this->VolumeKey;
    e.Packed.swap(this->Packed);
    e.Levels.swap(this->Levels);
    e.Solid.swap(this->Solid);
    e.Smooth.swap(this->Smooth);
    e.Kept = this->Kept;
    e.Bytes = 4.0 * e.Packed.size() + e.Levels.size() + e.Solid.size() + e.Smooth.size();
    double held = 0.0;
    for (const EarlierVolume& v : this->Earlier)
      held += v.Bytes;
    const double budget = 0.25 * (double(AvailableMemory()) + held);
    while (!this->Earlier.empty() && held + e.Bytes > budget)
    {
      held -= this->Earlier.front().Bytes;
      this->Earlier.pop_front();
    }
    if (held + e.Bytes <= budget)
      this->Earlier.push_back(std::move(e));
  }
  this->ClearVolume();
}

bool TraceSession::RestoreVolume(const std::string& key, bool restore)
{
  for (auto it = this->Earlier.begin(); it != this->Earlier.end(); ++it)
  {
    if (it->Key != key)
      continue;
    if (restore)
    {
      this->ClearVolume();
      this->Packed.swap(it->Packed);
      this->Levels.swap(it->Levels);
      this->Solid.swap(it->Solid);
      this->Smooth.swap(it->Smooth);
      this->Kept = it->Kept;
      this->VolumeKey = key;
      this->Earlier.erase(it);
    }
    return true;
  }
  return false;
}

void TraceSession::ClearVolume()
{
  this->AutoKey.clear();
  this->VolumeKey.clear();
  this->Packed.clear();
  this->Levels.clear();
  this->Solid.clear();
  this->Smooth.clear();
  this->Kept = Volume();
}

//------------------------------------------------------------------------------
AutoChoice TraceSession::ResolveKept(Parallel& parallel, const Volume& volume, TraceSettings& settings)
{
  std::ostringstream stamp;
  stamp << volume.Stamp;
  return this->ResolveKept(parallel, volume, settings, stamp.str(),
    [this, &parallel, &volume](TraceSettings& s) { return ResolveOnRankZero(parallel, volume, s, this->PilotStart); });
}

AutoChoice TraceSession::ResolveKept(Parallel& parallel, const Volume& volume, TraceSettings& settings,
  const std::string& volumeKey, const std::function<AutoChoice(TraceSettings&)>& resolve)
{
  if (settings.Method != Integrator::Auto && settings.Recon != Reconstruction::Auto)
    return resolve(settings);
  // what the choice depends on besides the view and the film's size: the volume and every other
  // setting
  TraceSettings k = settings;
  for (int a = 0; a < 3; ++a)
    k.ViewDirection[a] = k.ViewUp[a] = 0;
  k.Resolution[0] = k.Resolution[1] = 0;
  k.RankIndex = k.RankCount = 0;
  // the pilot traces its rays through fixed film points: where the photons start in their pixels
  // (the seed, the jitter) is not its business (issue 50: kept across seeds, passes, films)
  k.Seed = 0;
  k.Jitter = false;
  k.Pattern = JitterPattern::Random;
  std::ostringstream key;
  key << k.PhotonKey() << " | " << volumeKey;
  // the view of the last pilot, and of the last update
  bool pilotView = true, lastView = true;
  for (int a = 0; a < 3; ++a)
  {
    pilotView = pilotView && settings.ViewDirection[a] == this->AutoView[a] &&
      settings.ViewUp[a] == this->AutoView[3 + a];
    lastView = lastView && settings.ViewDirection[a] == this->LastView[a] &&
      settings.ViewUp[a] == this->LastView[3 + a];
  }
  for (int a = 0; a < 3; ++a)
  {
    this->LastView[a] = settings.ViewDirection[a];
    this->LastView[3 + a] = settings.ViewUp[a];
  }
  // another film size: the choice holds where its landing error (measured on the pilot's film,
  // world units) is still within half a pixel of this film; a film so much finer that it is not
  // asks for a tighter landing: pilot again
  double pixel = 0;
  bool finer = false, otherFilm = false;
  if (settings.Resolution[0] != this->AutoResolution[0] ||
    settings.Resolution[1] != this->AutoResolution[1])
  {
    otherFilm = true;
    try
    {
      pixel = MakeFilm(volume, settings).PixelSize;
    }
    catch (const Error&)
    {
      pixel = 0; // the pilot will say what is wrong
    }
    finer = !(pixel > 0) || this->AutoLanding > 0.5 * pixel;
  }
  // the camera moved: keep the choice. It came to rest (the same view again after a kept
  // choice) or the film got finer (the refinement at full resolution): pilot again, for this view
  const bool keep = parallel.AllOk(!this->AutoKey.empty() && key.str() == this->AutoKey && !finer &&
    !(lastView && this->AutoChoiceKept));
  if (keep)
  {
    settings.Method = this->AutoTraced.Method;
    settings.StepSize = this->AutoTraced.StepSize;
    settings.Recon = this->AutoTraced.Recon;
    settings.FieldStride = this->AutoTraced.FieldStride;
    settings.UseOctree = this->AutoTraced.UseOctree;
    settings.AutoMeasuredError = this->AutoTraced.AutoMeasuredError;
    AutoChoice c = this->AutoKept;
    if (otherFilm && pixel > 0)
    {
      std::ostringstream note;
      note.precision(3);
      note << "; kept for a " << settings.Resolution[0] << " x " << settings.Resolution[1]
           << " film (the pilot's was " << this->AutoResolution[0] << " x " << this->AutoResolution[1]
           << "; its landing error is " << this->AutoLanding / pixel << " pixel of this film)";
      c.ExpectedLandingError = this->AutoLanding / pixel;
      c.Report += note.str();
    }
    // the same view and film as the pilot's: the choice is what the pilot would make again
    if (!pilotView)
    {
      c.Reused = true;
      c.Report += "; kept from the previous update (only the view changed): the pilot runs again "
                  "when the camera rests";
    }
    this->AutoChoiceKept = c.Reused;
    return c;
  }
  const TraceSettings asked = settings;
  // the same volume and tolerance, another view (the camera at rest after a move) or a finer
  // film: the last pilot's choice is the new one's start (issue 50)
  const AutoChoice before = this->AutoKept;
  this->PilotStart = !this->AutoKey.empty() && key.str() == this->AutoKey ? &before : nullptr;
  AutoChoice c;
  try
  {
    c = resolve(settings);
  }
  catch (...)
  {
    this->PilotStart = nullptr;
    throw;
  }
  this->PilotStart = nullptr;
  ++this->PilotsRun;
  this->AutoKey = key.str();
  this->AutoTraced = settings;
  this->AutoKept = c;
  this->AutoChoiceKept = false;
  for (int a = 0; a < 3; ++a)
  {
    this->AutoView[a] = asked.ViewDirection[a];
    this->AutoView[3 + a] = asked.ViewUp[a];
  }
  this->AutoResolution[0] = asked.Resolution[0];
  this->AutoResolution[1] = asked.Resolution[1];
  this->AutoLanding = 0;
  try
  {
    this->AutoLanding = c.ExpectedLandingError * MakeFilm(volume, asked).PixelSize;
  }
  catch (const Error&)
  {
    this->AutoLanding = 1e300; // no film to measure it on: any other film pilots again
  }
  return c;
}

FilmGeometry PlannedFilm(const Volume& volume, TraceSettings s, const TraceSession& session)
{
  if (s.Frame == Framing::Silhouette && !HasFilmExtent(s) && !session.KeptFrame(s.FilmExtent))
  {
    Volume grid = volume;
    grid.Field = nullptr; // the box's projection
    grid.Solid = nullptr;
    const SilhouetteFrame box = FrameSilhouette(grid, s);
    std::copy(box.Extent, box.Extent + 4, s.FilmExtent);
  }
  return MakeFilm(volume, s);
}

void TraceSession::FrameKept(std::uint64_t stamp, Parallel& parallel,
  const std::function<SilhouetteFrame()>& find, TraceSettings& settings, SessionImage& out, bool say)
{
  if (settings.Frame != Framing::Silhouette || HasFilmExtent(settings))
    return;
  // what the frame depends on besides the view: the volume; and any other setting changed (an
  // Apply) frames again. Resolution and Passes do not (the interactive films of a camera that
  // follows, the refinement).
  TraceSettings k = settings;
  for (int a = 0; a < 3; ++a)
    k.ViewDirection[a] = k.ViewUp[a] = 0;
  k.Resolution[0] = k.Resolution[1] = 0;
  k.Passes = 0;
  std::ostringstream key;
  key << k.PhotonKey() << " | " << stamp;
  out.FrameKept = parallel.AllOk(!this->FrameKey.empty() && key.str() == this->FrameKey);
  if (!out.FrameKept)
  {
    this->Frame = find();
    this->FrameKey = key.str();
  }
  std::copy(this->Frame.Extent, this->Frame.Extent + 4, settings.FilmExtent);
  out.Framed = true;
  out.Frame = this->Frame;
  std::ostringstream note;
  note.precision(3);
  if (!this->Frame.Found)
    note << "Framing Silhouette: no point of the volume refracts; the film frames the whole box.";
  else
    note << "Framing Silhouette: the film frames the data's silhouette, "
         << 100 * this->Frame.Fraction << " % of the box's projection ("
         << this->Frame.Points << " points refract or are solid); kept while only the view, "
            "Resolution or Passes change.";
  if (say && !out.FrameKept) // said when found, not at every step of a camera that follows
    out.Notes.push_back({ false, note.str() });
}

//------------------------------------------------------------------------------
void TraceSession::Update(Parallel& parallel, const VolumePiece& piece,
  const TraceSettings& settings, SessionImage& out, const ProgressFunction& progress)
{
  const int ranks = parallel.Size(), rank = parallel.Rank();
  auto report = [&](double fraction) {
    if (progress)
      progress(fraction);
  };
  out = SessionImage();
  // on more than one rank, the volume in pieces where the settings allow (SchlierenSessionPieces)
  if (ranks > 1)
  {
    std::string why = WhyNotInPieces(settings);
    if (why.empty())
    {
      // every mode traces in pieces (UpdatePieces traces or throws on every rank)
      this->UpdatePieces(parallel, piece, settings, out, progress);
      return;
    }
    if (rank == 0)
      out.Notes.push_back({ false, "Tracing the whole volume on every rank: " + why + "." });
  }
  // the pieces go
  if (this->Pieces)
  {
    this->Pieces.reset();
    this->PiecesKey.clear();
  }

  // 0. The packed volume of the last update, where the input and the pieces have not changed
  // since (a new camera, other optics, more passes): steps 1-3 are skipped.
  std::ostringstream vk;
  vk.precision(17);
  vk << piece.Version << ' ' << settings.UseOctree << ' ' << ranks << ' '
     << (settings.Recon != Reconstruction::Trilinear);
  for (int a = 0; a < 6; ++a)
    vk << ' ' << piece.Extent[a] << ' ' << piece.WholeExtent[a];
  for (int a = 0; a < 3; ++a)
    vk << ' ' << piece.Origin[a] << ' ' << piece.Spacing[a];
  // the field in bricks where they pay (PackInBricks: the options may change between updates)
  const int wholeDims[3] = { piece.WholeExtent[1] - piece.WholeExtent[0] + 1,
    piece.WholeExtent[3] - piece.WholeExtent[2] + 1, piece.WholeExtent[5] - piece.WholeExtent[4] + 1 };
  const bool inBricks = PackInBricks(wholeDims);
  vk << ' ' << inBricks;
  const std::string volumeKey = vk.str();
  const bool reuseVolume = parallel.AllOk(piece.Problem.empty() && settings.Passes >= 1 &&
    this->Kept.Field && volumeKey == this->VolumeKey);
  // 0b. An earlier input's packed volume (a time step traced before), where every rank has it.
  bool fromEarlier = false;
  if (!reuseVolume)
  {
    this->StashVolume();
    fromEarlier = parallel.AllOk(piece.Problem.empty() && settings.Passes >= 1 &&
      this->RestoreVolume(volumeKey, false));
    if (fromEarlier)
      this->RestoreVolume(volumeKey, true);
  }
  out.VolumeFrom = reuseVolume ? "kept" : fromEarlier ? "cache" : "packed";
  if (!reuseVolume && !fromEarlier)
  {
    ++this->PacksRun;
    this->ClearVolume();
    // 1. This rank's piece.
    PieceValues values;
    const std::size_t count = ExtentPoints(piece.Extent);
    LoadPieceAgreed(parallel, piece, settings, values);

    // 2. The whole volume on every rank.
    Volume volume = WholeGrid(piece);
    const std::size_t total = volume.NumberOfPoints();
    const bool wholePiece = ranks == 1 && std::equal(piece.Extent, piece.Extent + 6, piece.WholeExtent);
    // what this piece says of its octree (vtkRefractionOctree: the levels and their tolerance)
    bool present = settings.UseOctree && count > 0 && values.Levels.size() == count;
    bool hasTolerance = present && values.HasLevelTolerance && values.LevelTolerance >= 0;
    double tolerance = hasTolerance ? values.LevelTolerance : 0.0;
    int maxLevel = present ? values.MaxLevel : 7;
    std::vector<float> field;
    const float* nMinus1 = AssembleVolume(parallel, piece, values, field, this->Solid);

    // 2b. The octree levels of the whole volume. One rank with the whole volume: the piece's
    // levels as they are. Otherwise (pieces, whose levels stop at the piece borders): the levels
    // of the assembled volume, recomputed at the tolerance the octree was built for.
    if (ranks > 1)
    {
      // every rank the same: the octree if any piece has one, the smallest tolerance, the highest
      // level
      double octree[3] = { present ? 1.0 : 0.0, hasTolerance ? -tolerance : -1e300,
        present ? double(maxLevel) : -1.0 };
      parallel.Max(octree, 3);
      present = octree[0] > 0;
      hasTolerance = octree[1] > -1e300;
      tolerance = hasTolerance ? -octree[1] : 0.0;
      maxLevel = static_cast<int>(octree[2]);
    }
    if (settings.UseOctree && present)
    {
      if (wholePiece && values.Levels.size() == total)
        this->Levels.swap(values.Levels);
      else if (hasTolerance && volume.Dimensions[0] >= 2 && volume.Dimensions[1] >= 2 &&
        volume.Dimensions[2] >= 2)
      {
        this->Levels.resize(total);
        // ValidateIndex runs in PackField below; ComputeOctreeLevels itself only reads values
        ComputeOctreeLevels(
          volume.Dimensions, nMinus1, tolerance, this->Levels.data(), maxLevel);
      }
      else if (rank == 0)
        out.Notes.push_back({ true,
          "The input has the point array 'octree_level' but not the field data "
          "'octree_tolerance' it was built for, and the levels of its pieces cannot be joined: "
          "tracing without the octree. Apply RefractionOctree right before SchlierenImage." });
    }
    report(0.05);

    // 3. n - 1 and its gradient, packed.
    std::string problem;
    float rangeLo = 0, rangeHi = 0;
    try
    {
      std::ostringstream what;
      what << "Tracing the " << volume.Dimensions[0] << " x " << volume.Dimensions[1] << " x "
           << volume.Dimensions[2] << " volume";
      CheckHostMemory(double(total) * (VolumeBytesPerPoint() - 4.0), what.str(),
        "Resample the data to fewer points (RefractiveIndex SamplingDimensions or "
        "AutomaticDimension), or trace a subset (ExtractSubset).");
      // checked, and its range found, in one pass (the tracer's feature tolerance needs the range
      // too: kept below, with the volume's stamp)
      CheckGrid(volume.Dimensions, volume.Spacing);
      const std::string bad = ScanIndex(nMinus1, total, rangeLo, rangeHi);
      if (!bad.empty())
        throw Error(bad);
      // (in bricks: written in place, no linear copy first)
      const bool bricked = inBricks && std::equal(volume.Dimensions, volume.Dimensions + 3, wholeDims);
      this->Packed.resize(FieldLayout(volume.Dimensions, bricked).Floats);
      if (settings.Recon == Reconstruction::Trilinear)
        PackFieldOf(volume.Dimensions, volume.Spacing, nMinus1, this->Packed.data(), bricked);
      else
      {
        // fourth-order gradients where the data is smooth, and the smoothness per cell
        this->Smooth.resize(total);
        PackFieldHighOrderOf(volume.Dimensions, volume.Spacing, nMinus1, this->Packed.data(),
          this->Smooth.data(), DefaultSmoothnessThreshold, rangeLo, rangeHi, 7, bricked);
      }
      volume.FieldInBricks = bricked;
    }
    catch (const Error& e)
    {
      problem = e.what();
    }
    catch (const std::bad_alloc&)
    {
      problem = "Out of memory while packing the volume (std::bad_alloc): resample it to fewer "
                "points.";
    }
    std::vector<float>().swap(field);
    if (!problem.empty())
      this->ClearVolume();
    AgreeOrThrow(parallel, problem);
    volume.Field = this->Packed.data();
    if (!this->Levels.empty())
    {
      volume.Levels = this->Levels.data();
      volume.LevelTolerance = hasTolerance ? tolerance : 0.0;
    }
    volume.Solid = this->Solid.empty() ? nullptr : this->Solid.data();
    volume.Smooth = this->Smooth.empty() ? nullptr : this->Smooth.data();
    volume.Stamp = NewVolumeStamp();
    KeepIndexRange(volume, rangeLo, rangeHi);
    this->Stamped = true;
    this->Kept = volume;
    this->VolumeKey = volumeKey;
  }
  else
    report(0.05);
  out.VolumesCached = static_cast<int>(this->Earlier.size());
  out.VolumesPacked = this->PacksRun;
  const Volume& volume = this->Kept;

  // 4. Auto resolved on rank 0, then this rank's share of the photons. Progressive refinement:
  // where only Passes grew since the last trace of the same volume with the same photons, the
  // kept sums go on with the new passes (the jitter sequence goes on where it stopped, so the
  // image equals a trace of all passes at once).
  TraceSettings traced = settings;
  this->FrameKept(volume.Stamp, parallel, [&volume, &traced]() { return FrameSilhouette(volume, traced); },
    traced, out, rank == 0);
  const AutoChoice choice = this->ResolveKept(parallel, volume, traced);
  if (rank == 0 && (settings.Method == Integrator::Auto || settings.Recon == Reconstruction::Auto))
  {
    out.Notes.push_back({ false, choice.Report });
    if (!choice.Met)
      out.Notes.push_back({ true, choice.Report });
  }
  traced.RankIndex = rank;
  traced.RankCount = ranks;
  std::ostringstream keyStream;
  keyStream.precision(17);
  keyStream << traced.PhotonKey() << " | " << piece.Version << ' ' << volume.Dimensions[0] << ' '
            << volume.Dimensions[1] << ' ' << volume.Dimensions[2] << ' ' << volume.Origin[0]
            << ' ' << volume.Origin[1] << ' ' << volume.Origin[2] << ' ' << volume.Spacing[0]
            << ' ' << volume.Spacing[1] << ' ' << volume.Spacing[2] << ' '
            << (volume.Levels ? 1 : 0) << ' ' << volume.LevelTolerance << ' '
            << (volume.Solid ? 1 : 0);
  const std::string key = keyStream.str();
  const bool reuseSums = parallel.AllOk(
    key == this->SumsKey && this->Sums.Passes > 0 && settings.Passes >= this->Sums.Passes);
  FilmSums reduced; // on more than one rank: the sums of all ranks (one rank reads this->Sums)
  std::string problem, warnings;
  try
  {
    const FilmGeometry film = MakeFilm(volume, traced);
    if (!reuseSums)
    {
      this->Sums.Resize(0, 0); // the old film goes before the new one is checked and made
      CheckFilmMemory(film.Size);
      this->Sums.Resize(film.Size[0], film.Size[1]);
    }
    this->SumsKey.clear(); // valid again only once the passes below are all in
    out.PassesTraced = settings.Passes - this->Sums.Passes;
    if (out.PassesTraced > 0)
    {
      traced.Passes = out.PassesTraced;
      const auto t0 = std::chrono::steady_clock::now();
      Accumulate(volume, traced, this->Sums, &out.BackendUsed, &out.DeviceName, &warnings,
        [&progress](double p) { return progress ? progress(0.05 + 0.9 * p) : true; });
      out.SecondsTracing = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    traced.Passes = settings.Passes;
    this->SumsKey = key;
  }
  catch (const Error& e)
  {
    this->Sums.Resize(0, 0);
    problem = e.what();
  }
  catch (const std::bad_alloc&)
  {
    this->Sums.Resize(0, 0);
    problem = "Out of memory while tracing (std::bad_alloc): lower Resolution or resample the "
              "volume to fewer points.";
  }
  AgreeOrThrow(parallel, problem);
  if (!warnings.empty())
    out.Notes.push_back({ true, ranks > 1 ? "rank " + std::to_string(rank) + ": " + warnings : warnings });

  // 5. The film sums of all ranks: every additive part in one sum, the maxima in one max (the
  // engine lists them, so a new channel needs no change here).
  if (ranks > 1)
  {
    reduced = this->Sums;
    std::vector<double> additive, maxima;
    reduced.ToArrays(additive, maxima);
    parallel.Sum(additive.data(), additive.size());
    parallel.Max(maxima.data(), maxima.size());
    if (rank != 0)
      return; // rank 0 holds the image
    reduced.FromArrays(additive, maxima);
  }
  const FilmSums& sums = ranks > 1 ? reduced : this->Sums;

  // 6. The image (rank 0; nothing collective from here on).
  out.Result = Finalize(volume, traced, sums);
  if (!out.Result.Warnings.empty() && out.Result.Warnings != warnings)
    out.Notes.push_back({ true, out.Result.Warnings });
  out.HasImage = true;
  out.Traced = traced;
  out.Choice = choice;
  out.AutoAsked = settings.Method == Integrator::Auto || settings.Recon == Reconstruction::Auto;
  out.Warnings = warnings + (out.Result.Warnings != warnings ? out.Result.Warnings : std::string());
  if (!out.Result.BackendUsed.empty())
    out.BackendUsed = out.Result.BackendUsed;
  if (!out.Result.DeviceName.empty())
    out.DeviceName = out.Result.DeviceName;
  out.Passes = sums.Passes;
  for (double c : sums.Count)
    out.LandedPhotons += c;
  out.OctreeUsed = volume.Levels && traced.UseOctree;
  out.OctreeTolerance = volume.LevelTolerance;
}

} // namespace schlieren
