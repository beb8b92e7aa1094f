// SPDX-License-Identifier: BSD-3-Clause
// The C interface (schlieren_c.h) over the engine: a TraceSession per handle on one process, the
// SchlierenImage properties by name, and the report as JSON. Every entry point catches what the
// engine throws and turns it into a message.
#define SCHLIEREN_C_BUILDING
#include "schlieren_c.h"

#include "SchlierenAMRSample.h"
#include "SchlierenBodies.h"
#include "SchlierenEngine.h"
#include "SchlierenLimits.h"
#include "SchlierenIndexField.h"
#include "SchlierenWallFaces.h"
#include "SchlierenIndexModels.h"
#include "SchlierenNumerical.h"
#include "SchlierenOptions.h"
#include "SchlierenParallel.h"
#include "SchlierenPhotograph.h"
#include "SchlierenPhotographOverlay.h"
#include "SchlierenSample.h"
#include "SchlierenSamplingGrid.h"
#include "SchlierenScenes.h"
#include "SchlierenSession.h"
#include "SchlierenSymmetry.h"
#include "SchlierenTimeStore.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

namespace
{
using schlieren::TraceSettings;

thread_local std::string LastError;
thread_local std::string Returned;

std::string Json(const std::string& s)
{
  return schlieren::JsonString(s);
}

std::string Number(double v)
{
  return schlieren::JsonNumber(v);
}

/** The numbers of a text value ("0 0 -1", "512,512") and, where `tokens` is given, their text as
 * typed (for messages: a value is reported as given); false where one does not parse. */
bool ParseNumbers(const char* text, std::vector<double>& out, std::vector<std::string>* tokens = nullptr)
{
  out.clear();
  if (tokens)
    tokens->clear();
  const char* p = text;
  while (*p)
  {
    while (*p == ' ' || *p == ',' || *p == '\t' || *p == '\n' || *p == '\r' || *p == '[' || *p == ']' || *p == '(' || *p == ')')
      ++p;
    if (!*p)
      break;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p)
      return false;
    out.push_back(v);
    if (tokens)
      tokens->push_back(std::string(p, static_cast<std::size_t>(end - p)));
    p = end;
  }
  return true;
}

/** Levenshtein distance of two names, letters compared without case. */
std::size_t Distance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({ row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1) });
      diagonal = up;
    }
  }
  return row[b.size()];
}

/** " (the closest known name: 'X'; names are case-sensitive)" for the known name nearest to
 * `given`, empty where none is near (more than half its letters differ). */
template <typename Names>
std::string Closest(const std::string& given, const Names& names)
{
  std::string best;
  std::size_t bestDistance = std::string::npos;
  for (const auto& n : names)
  {
    const std::string name(n);
    const std::size_t d = Distance(given, name);
    if (d < bestDistance)
    {
      best = name;
      bestDistance = d;
    }
  }
  if (best.empty() || bestDistance > std::max<std::size_t>(2, best.size() / 2))
    return std::string();
  return " (the closest known name: '" + best + "'" +
    (bestDistance == 0 ? "; names are case-sensitive)" : ")");
}

/** A property of SchlierenImage as the interface takes it. */
struct Property
{
  const char* Name;
  const char* Kind; // int, double, bool, enum, string
  int Size;
  std::vector<const char*> Entries; // enum: the entry texts, value = index
  std::function<void(TraceSettings&, const std::vector<double>&)> SetNumbers;
  std::function<std::vector<double>(const TraceSettings&)> GetNumbers;
  std::function<void(TraceSettings&, const std::string&)> SetText; // string kind
  std::function<std::string(const TraceSettings&)> GetText;
};

#define SCH_NUM(name, kind, field, type)                                                           \
  Property{ #name, kind, 1, {},                                                                    \
    [](TraceSettings& s, const std::vector<double>& v) { s.field = static_cast<type>(v[0]); },     \
    [](const TraceSettings& s) { return std::vector<double>{ static_cast<double>(s.field) }; },    \
    nullptr, nullptr }
#define SCH_ENUM(name, field, type, ...)                                                           \
  Property{ #name, "enum", 1, { __VA_ARGS__ },                                                     \
    [](TraceSettings& s, const std::vector<double>& v) { s.field = static_cast<type>(int(v[0])); }, \
    [](const TraceSettings& s) { return std::vector<double>{ static_cast<double>(int(s.field)) }; }, \
    nullptr, nullptr }

/** The SchlierenImage properties the engine takes (the GUI's Follow group is not the engine's). */
const std::vector<Property>& Properties()
{
  static const std::vector<Property> properties = {
    Property{ "ViewDirection", "double", 3, {},
      [](TraceSettings& s, const std::vector<double>& v) { std::copy(v.begin(), v.end(), s.ViewDirection); },
      [](const TraceSettings& s) { return std::vector<double>(s.ViewDirection, s.ViewDirection + 3); },
      nullptr, nullptr },
    Property{ "ViewUp", "double", 3, {},
      [](TraceSettings& s, const std::vector<double>& v) { std::copy(v.begin(), v.end(), s.ViewUp); },
      [](const TraceSettings& s) { return std::vector<double>(s.ViewUp, s.ViewUp + 3); }, nullptr,
      nullptr },
    Property{ "Resolution", "int", 2, {},
      [](TraceSettings& s, const std::vector<double>& v) {
        s.Resolution[0] = static_cast<int>(v[0]);
        s.Resolution[1] = static_cast<int>(v[1]);
      },
      [](const TraceSettings& s) { return std::vector<double>{ double(s.Resolution[0]), double(s.Resolution[1]) }; },
      nullptr, nullptr },
    SCH_ENUM(Framing, Frame, schlieren::Framing, "Volume", "Silhouette"),
    SCH_NUM(Passes, "int", Passes, int),
    SCH_NUM(StepSize, "double", StepSize, double),
    SCH_ENUM(Integrator, Method, schlieren::Integrator, "Euler", "Midpoint", "RK4", "Straight", "Auto",
      "Verlet"),
    SCH_ENUM(Reconstruction, Recon, schlieren::Reconstruction, "Trilinear", "Cubic", "Auto"),
    SCH_NUM(Tolerance, "double", Tolerance, double),
    SCH_NUM(KeepInvariant, "bool", KeepInvariant, bool),
    SCH_NUM(EstimateError, "bool", EstimateError, bool),
    SCH_NUM(UseOctree, "bool", UseOctree, bool),
    SCH_ENUM(Cutoff, Mode, schlieren::Cutoff, "KnifeEdge", "Shadowgraph", "Circular",
      "ComplementCircular", "ColorFilter", "Interferometry", "BOS"),
    SCH_NUM(KnifeAngle, "double", KnifeAngle, double),
    SCH_NUM(CutoffScale, "double", CutoffScale, double),
    SCH_NUM(FilmDistance, "double", FilmDistance, double),
    SCH_NUM(Wavelength, "double", Wavelength, double),
    SCH_NUM(ReferenceTilt, "double", ReferenceTilt, double),
    Property{ "WavelengthRange", "double", 2, {},
      [](TraceSettings& s, const std::vector<double>& v) { std::copy(v.begin(), v.end(), s.WavelengthRange); },
      [](const TraceSettings& s) { return std::vector<double>(s.WavelengthRange, s.WavelengthRange + 2); },
      nullptr, nullptr },
    SCH_NUM(WavelengthBins, "int", WavelengthBins, int),
    SCH_ENUM(Dispersion, Disperse, schlieren::Dispersion, "Air", "None"),
    SCH_NUM(BackgroundDistance, "double", BackgroundDistance, double),
    SCH_ENUM(BackgroundPattern, BackgroundPattern, int, "Dots", "Stripes"),
    SCH_NUM(BackgroundPeriod, "double", BackgroundPeriod, double),
    SCH_ENUM(Filter, Filter, schlieren::FilmFilter, "None", "Gaussian", "Cone"),
    SCH_NUM(FilterWidth, "double", FilterWidth, double),
    SCH_NUM(RussianRoulette, "bool", RussianRoulette, bool),
    SCH_NUM(Jitter, "bool", Jitter, bool),
    SCH_ENUM(JitterPattern, Pattern, schlieren::JitterPattern, "Random", "Lattice"),
    SCH_NUM(Seed, "int", Seed, std::uint32_t),
    SCH_ENUM(Backend, Device, schlieren::Backend, "Auto", "OpenCL", "CPU"),
    Property{ "DeviceName", "string", 1, {}, nullptr, nullptr,
      [](TraceSettings& s, const std::string& t) { s.DeviceName = t; },
      [](const TraceSettings& s) { return s.DeviceName; } },
    SCH_NUM(Threads, "int", Threads, int),
    SCH_NUM(TraceInPieces, "bool", InPieces, bool),
    SCH_ENUM(Source, Source, schlieren::BenchSource, "Point", "Slit", "Rectangle", "Disc", "Gaussian"),
    Property{ "SourceSize", "double", 2, {},
      [](TraceSettings& s, const std::vector<double>& v) { std::copy(v.begin(), v.end(), s.SourceSize); },
      [](const TraceSettings& s) { return std::vector<double>(s.SourceSize, s.SourceSize + 2); },
      nullptr, nullptr },
    SCH_NUM(CollimatorFocalLength, "double", CollimatorFocalLength, double),
    SCH_NUM(SchlierenFocalLength, "double", SchlierenFocalLength, double),
    SCH_NUM(KnifeCut, "double", KnifeCut, double),
    SCH_NUM(StopDiameter, "double", StopDiameter, double),
    SCH_NUM(BitDepth, "int", BitDepth, int),
    SCH_NUM(SaturationWarning, "double", SaturationWarning, double),
    SCH_ENUM(Camera, Camera, schlieren::CameraModel, "None", "Ideal", "Lens"),
    SCH_NUM(CameraFocalLength, "double", CameraFocalLength, double),
    SCH_NUM(FNumber, "double", FNumber, double),
    SCH_NUM(CameraDistance, "double", CameraDistance, double),
    SCH_NUM(FocusPlane, "double", FocusPlane, double),
    SCH_NUM(SourceGridDistance, "double", SourceGridDistance, double),
  };
  return properties;
}

/** SchlierenImage's defaults where they differ from TraceSettings' (vtkSchlierenImage.h). */
TraceSettings Defaults()
{
  TraceSettings s;
  s.Passes = 4;
  return s;
}

const Property* FindProperty(const char* name)
{
  if (!name)
    return nullptr;
  for (const Property& p : Properties())
    if (std::strcmp(p.Name, name) == 0)
      return &p;
  return nullptr;
}

std::string ValueText(const Property& p, const TraceSettings& s)
{
  if (p.GetText)
    return p.GetText(s);
  const std::vector<double> v = p.GetNumbers(s);
  if (std::strcmp(p.Kind, "enum") == 0)
  {
    const int i = static_cast<int>(v[0]);
    return i >= 0 && i < static_cast<int>(p.Entries.size()) ? p.Entries[i] : std::to_string(i);
  }
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i)
    out += (i ? " " : "") + Number(v[i]);
  return out;
}

/** The storage range of an integer property (Seed: unsigned 32 bits; bool 0/1; else int). */
void IntegerRange(const Property& p, double& lo, double& hi)
{
  if (std::strcmp(p.Kind, "bool") == 0)
  {
    lo = 0;
    hi = 1;
  }
  else if (std::strcmp(p.Name, "Seed") == 0)
  {
    lo = 0;
    hi = 4294967295.0;
  }
  else
  {
    lo = std::numeric_limits<int>::min();
    hi = std::numeric_limits<int>::max();
  }
}

/** Sets `p` from text; returns an empty string or why not. */
std::string SetProperty(const Property& p, TraceSettings& s, const char* text)
{
  if (!text)
    return std::string(p.Name) + ": no value given (NULL).";
  if (p.SetText)
  {
    p.SetText(s, text);
    return std::string();
  }
  if (std::strcmp(p.Kind, "enum") == 0)
  {
    for (std::size_t i = 0; i < p.Entries.size(); ++i)
      if (std::strcmp(p.Entries[i], text) == 0)
      {
        p.SetNumbers(s, { double(i) });
        return std::string();
      }
    std::vector<double> v;
    if (ParseNumbers(text, v) && v.size() == 1 && v[0] == std::floor(v[0]) && v[0] >= 0 &&
      v[0] < p.Entries.size())
    {
      p.SetNumbers(s, v);
      return std::string();
    }
    std::string list;
    for (const char* e : p.Entries)
      list += std::string(list.empty() ? "" : ", ") + e;
    return std::string(p.Name) + " '" + text + "' is not one of: " + list + Closest(text, p.Entries) + ".";
  }
  std::vector<double> v;
  std::vector<std::string> typed;
  if (!ParseNumbers(text, v, &typed) || static_cast<int>(v.size()) != p.Size)
    return std::string(p.Name) + " '" + text + "': expected " + std::to_string(p.Size) + " " +
      (std::strcmp(p.Kind, "double") == 0 ? "" : "integer ") + (p.Size == 1 ? "number" : "numbers") + ".";
  if (std::strcmp(p.Kind, "double") == 0)
  {
    p.SetNumbers(s, v);
    return std::string();
  }
  double lo = 0, hi = 0;
  IntegerRange(p, lo, hi);
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    const double x = v[i];
    if (!std::isfinite(x) || x != std::floor(x))
      return std::string(p.Name) + " is " + typed[i] + ": " +
        (std::strcmp(p.Kind, "bool") == 0 ? "it must be 0 or 1 (a boolean)." : "expected an integer.");
    if (x >= lo && x <= hi)
      continue;
    if (std::strcmp(p.Kind, "bool") == 0)
      return std::string(p.Name) + " is " + typed[i] + ": it must be 0 or 1 (a boolean).";
    // out of the storage type: the engine's range for the property, with the value as given
    // (not as the 32-bit integer it would have wrapped to)
    std::vector<double> clamped = v;
    for (double& c : clamped)
      c = std::min(std::max(c, lo), hi);
    TraceSettings trial = s;
    p.SetNumbers(trial, clamped);
    std::string message;
    try
    {
      schlieren::CheckSettings(trial);
    }
    catch (const std::exception& e)
    {
      message = e.what();
    }
    std::ostringstream c;
    c.precision(17);
    c << clamped[i];
    const std::size_t at = message.find(c.str());
    if (message.compare(0, std::strlen(p.Name), p.Name) == 0 && at != std::string::npos)
      return message.replace(at, c.str().size(), typed[i]);
    std::ostringstream range;
    range.precision(17);
    range << p.Name << " is " << typed[i] << ": it must be an integer in [" << lo << ", " << hi << "].";
    return range.str();
  }
  p.SetNumbers(s, v);
  return std::string();
}

} // namespace

struct schlieren_session
{
  /** One call at a time: every entry point that takes the session holds this for its call (a
   * second thread waits; the header says so). */
  std::mutex Mutex;
  schlieren::TraceSession Session;
  TraceSettings Settings = Defaults();
  schlieren::VolumePiece Piece;
  std::vector<float> NMinus1;
  std::vector<unsigned char> Solid, Levels;
  double LevelTolerance = -1;
  int MaxLevel = 7;
  bool HasVolume = false;
  std::uint64_t Version = 0;
  schlieren::SessionImage Image;
  bool HasImage = false;
  std::string Error, Report, Text;
};

namespace
{
/** The live sessions: a handle not in it (freed, or not made here) is refused, not followed. The
 * registry holds a reference, and each call holds its own for the call: a free from another
 * thread during a call frees the session when that call ends. Never destroyed (calls may come
 * from other threads' destructors at exit). */
std::mutex& RegistryMutex()
{
  static std::mutex* m = new std::mutex;
  return *m;
}
std::unordered_map<const schlieren_session*, std::shared_ptr<schlieren_session>>& Registry()
{
  static auto* r = new std::unordered_map<const schlieren_session*, std::shared_ptr<schlieren_session>>;
  return *r;
}

std::shared_ptr<schlieren_session> Live(const schlieren_session* s)
{
  if (!s)
    return nullptr;
  std::lock_guard<std::mutex> lock(RegistryMutex());
  const auto it = Registry().find(s);
  return it == Registry().end() ? nullptr : it->second;
}

const char* NotLive(const schlieren_session* s)
{
  return s ? "not a live session: the handle was freed (schlieren_session_free) or was not made "
             "by schlieren_session_new"
           : "no session (NULL)";
}

/** A session held for one call (its mutex locked), or, where the handle is not live, nothing and
 * the reason in schlieren_last_error(). */
struct Held
{
  std::shared_ptr<schlieren_session> Session;
  std::unique_lock<std::mutex> Lock;
  Held(const schlieren_session* s, const char* function)
    : Session(Live(s))
  {
    if (Session)
      Lock = std::unique_lock<std::mutex>(Session->Mutex);
    else
      LastError = std::string(function) + ": " + NotLive(s) + ".";
  }
  explicit operator bool() const { return static_cast<bool>(Session); }
  schlieren_session* operator->() const { return Session.get(); }
  schlieren_session* get() const { return Session.get(); }
};

/** The points of a grid, refusing dimensions below 1 and products past 2^40 (before any
 * allocation or loop sized by them). */
std::int64_t GridPoints(const char* function, const int dims[3])
{
  if (!dims)
    throw schlieren::Error(std::string(function) + ": dims is NULL.");
  std::int64_t n = 1;
  for (int a = 0; a < 3; ++a)
  {
    if (dims[a] < 1)
      throw schlieren::Error(std::string(function) + ": dims are " + std::to_string(dims[0]) + " " +
        std::to_string(dims[1]) + " " + std::to_string(dims[2]) +
        ": each must be at least 1 (points along x, y, z).");
    // checked before the product (2^40 x 2^31 would overflow 64 bits)
    if (n > (std::int64_t(1) << 40) / dims[a])
      throw schlieren::Error(std::string(function) + ": dims " + std::to_string(dims[0]) + " x " +
        std::to_string(dims[1]) + " x " + std::to_string(dims[2]) +
        " make more than 2^40 points: no array of the engine can hold them.");
    n *= dims[a];
  }
  return n;
}

bool EmptyExtent(const int extent[6])
{
  return extent[1] < extent[0] || extent[3] < extent[2] || extent[5] < extent[4];
}

std::string GridText(const int dims[3])
{
  return std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " + std::to_string(dims[2]);
}

/** An array and its length: NULL with length 0 is "not given" where `optional`; else the length
 * must be `needed` (in `unit`s) and the pointer not NULL. */
void CheckArray(const char* function, const char* array, const void* data, std::int64_t given,
  std::int64_t needed, const std::string& per, bool optional, const char* unit = "values")
{
  if (given < 0)
    throw schlieren::Error(std::string(function) + ": the length of " + array + " is " +
      std::to_string(given) + ": a length is a count of " + unit + " (>= 0).");
  if (!data)
  {
    if (optional && given == 0)
      return;
    throw schlieren::Error(std::string(function) + ": " + array + " is NULL" +
      (optional ? " with a length of " + std::to_string(given) + " (give both, or NULL and 0)."
                : ": it must be given (" + std::to_string(needed) + " " + unit + ")."));
  }
  if (given != needed)
    throw schlieren::Error(std::string(function) + ": " + array + " holds " + std::to_string(given) +
      " " + unit + "; " + per + " needs " + std::to_string(needed) + ".");
}

void CheckFinite3(const char* function, const char* name, const double* v)
{
  if (!v)
    throw schlieren::Error(std::string(function) + ": " + name + " is NULL.");
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(v[a]))
    {
      std::ostringstream msg;
      msg << function << ": " << name << " is " << v[0] << " " << v[1] << " " << v[2]
          << ": give finite numbers.";
      throw schlieren::Error(msg.str());
    }
}

} // namespace

namespace
{

/** Runs `f`, turning every exception into a message; returns 0 or 1. */
template <typename F>
int Guard(std::string& error, F&& f)
{
  try
  {
    error.clear();
    f();
    return 0;
  }
  catch (const std::bad_alloc&)
  {
    error = "Out of memory.";
  }
  catch (const std::exception& e)
  {
    error = e.what();
    if (error.empty())
      error = "Unknown engine error.";
  }
  catch (...)
  {
    error = "Unknown engine error.";
  }
  return 1;
}

void MakeReport(schlieren_session* s, const std::string& error)
{
  const schlieren::SessionImage& image = s->Image;
  std::ostringstream o;
  o << "{\"field_data\": ";
  // the engine's one list (vtkSchlierenImage writes the same as its field data)
  o << (error.empty() ? schlieren::ImageReportJson(image) : std::string("{}"));
  o << ", \"notes\": [";
  for (std::size_t i = 0; i < image.Notes.size(); ++i)
    o << (i ? ", " : "") << "{\"warning\": " << (image.Notes[i].Warning ? "true" : "false")
      << ", \"text\": " << Json(image.Notes[i].Text) << "}";
  o << "], \"error\": " << Json(error) << "}";
  s->Report = o.str();
}

} // namespace

namespace
{
/** schlieren_parallel's callbacks as the engine's Parallel (docs/PARALLEL.md): lengths are
 * exchanged first so that every callback moves the same count on every rank; what the callbacks
 * give back is checked before it is used. */
class CallbackParallel final : public schlieren::Parallel
{
public:
  CallbackParallel(const schlieren_parallel& p, const char* function)
    : P(p)
    , Function(function)
  {
  }
  int Rank() const override { return this->P.rank; }
  int Size() const override { return this->P.size; }

  void Reduce(double* values, std::size_t count, schlieren::ReduceOp op) override
  {
    if (count == 0)
      return;
    std::vector<double> in(values, values + count);
    const int code = op == schlieren::ReduceOp::Sum ? 0 : op == schlieren::ReduceOp::Min ? 1 : 2;
    this->Check("reduce", this->P.reduce(in.data(), values, static_cast<int64_t>(count), code, this->P.user));
    const bool finiteIn = std::all_of(in.begin(), in.end(), [](double v) { return std::isfinite(v); });
    if (finiteIn && !std::all_of(values, values + count, [](double v) { return std::isfinite(v); }))
      this->Bad("reduce", "a value that is not finite from finite ones");
  }

  void Broadcast(std::vector<char>& bytes, int root) override
  {
    if (root < 0 || root >= this->P.size)
      this->Bad("broadcast", "a root outside the ranks (" + std::to_string(root) + ")");
    std::int64_t length = static_cast<std::int64_t>(bytes.size());
    char head[sizeof(length)];
    std::memcpy(head, &length, sizeof(length));
    this->Check("broadcast", this->P.broadcast(head, sizeof(head), root, this->P.user));
    std::memcpy(&length, head, sizeof(length));
    this->Length("broadcast", length);
    if (this->P.rank != root)
      bytes.assign(static_cast<std::size_t>(length), 0);
    else if (length != static_cast<std::int64_t>(bytes.size()))
      this->Bad("broadcast", "the root another length than its own");
    if (length > 0)
      this->Check("broadcast", this->P.broadcast(bytes.data(), length, root, this->P.user));
  }

  std::vector<std::vector<char>> AllGather(const std::vector<char>& mine) override
  {
    const int n = this->P.size;
    const std::int64_t length = static_cast<std::int64_t>(mine.size());
    std::vector<std::int64_t> lengths(static_cast<std::size_t>(n), 0);
    this->Check("allgather", this->P.allgather(reinterpret_cast<const char*>(&length),
                               sizeof(length), reinterpret_cast<char*>(lengths.data()), this->P.user));
    std::int64_t most = 0;
    for (std::int64_t l : lengths)
    {
      this->Length("allgather", l);
      most = std::max(most, l);
    }
    if (lengths[static_cast<std::size_t>(this->P.rank)] != length)
      this->Bad("allgather", "this rank another length than its own");
    std::vector<std::vector<char>> out(static_cast<std::size_t>(n));
    if (most == 0)
      return out;
    schlieren::CheckHostMemory(double(most) * n, "Gathering the ranks' messages",
      "Use fewer ranks or a smaller volume.");
    // every rank sends the longest message's count: padded
    std::vector<char> padded(static_cast<std::size_t>(most), 0), all(static_cast<std::size_t>(most) * n);
    std::copy(mine.begin(), mine.end(), padded.begin());
    this->Check("allgather", this->P.allgather(padded.data(), most, all.data(), this->P.user));
    for (int r = 0; r < n; ++r)
    {
      const char* from = all.data() + static_cast<std::size_t>(r) * static_cast<std::size_t>(most);
      out[static_cast<std::size_t>(r)].assign(from, from + lengths[static_cast<std::size_t>(r)]);
    }
    return out;
  }

  std::vector<std::vector<char>> Exchange(const std::vector<std::vector<char>>& outgoing) override
  {
    const int n = this->P.size;
    if (static_cast<int>(outgoing.size()) != n)
      throw schlieren::Error("Parallel::Exchange: one message per rank expected");
    // on the all-gather: every rank's messages to every rank, each rank keeps those to it
    std::vector<char> mine;
    for (const std::vector<char>& m : outgoing)
    {
      const std::int64_t l = static_cast<std::int64_t>(m.size());
      const char* b = reinterpret_cast<const char*>(&l);
      mine.insert(mine.end(), b, b + sizeof(l));
      mine.insert(mine.end(), m.begin(), m.end());
    }
    const std::vector<std::vector<char>> all = this->AllGather(mine);
    std::vector<std::vector<char>> incoming(static_cast<std::size_t>(n));
    for (int r = 0; r < n; ++r)
    {
      const std::vector<char>& theirs = all[static_cast<std::size_t>(r)];
      std::size_t at = 0;
      for (int to = 0; to < n; ++to)
      {
        std::int64_t l = -1;
        if (at > theirs.size() || theirs.size() - at < sizeof(l))
          this->Bad("allgather", "a message cut short");
        std::memcpy(&l, theirs.data() + at, sizeof(l));
        at += sizeof(l);
        if (l < 0 || static_cast<std::uint64_t>(l) > theirs.size() - at)
          this->Bad("allgather", "a message cut short");
        if (to == this->P.rank)
          incoming[static_cast<std::size_t>(r)].assign(
            theirs.begin() + static_cast<std::ptrdiff_t>(at), theirs.begin() + static_cast<std::ptrdiff_t>(at + l));
        at += static_cast<std::size_t>(l);
      }
    }
    return incoming;
  }

private:
  void Check(const char* callback, int status) const
  {
    if (status != 0)
      throw schlieren::Error(std::string(this->Function) + ": the caller's " + callback +
        " callback failed (returned " + std::to_string(status) + ") on rank " +
        std::to_string(this->P.rank) + " of " + std::to_string(this->P.size) + ".");
  }
  [[noreturn]] void Bad(const char* callback, const std::string& what) const
  {
    throw schlieren::Error(std::string(this->Function) + ": the caller's " + callback +
      " callback gave " + what + " on rank " + std::to_string(this->P.rank) + " of " +
      std::to_string(this->P.size) + ".");
  }
  void Length(const char* callback, std::int64_t l) const
  {
    if (l < 0 || l > (std::int64_t(1) << 40))
      this->Bad(callback, "a length of " + std::to_string(l) + " bytes (0 to 2^40)");
  }
  schlieren_parallel P;
  const char* Function;
};

/** The ranks `p` describes, checked: one process for NULL or a size of 1; `own` keeps the
 * callbacks' Parallel for the call. */
schlieren::Parallel& RanksOf(
  const char* f, const schlieren_parallel* p, std::unique_ptr<CallbackParallel>& own)
{
  if (!p)
    return schlieren::SerialParallel();
  if (p->size < 1)
    throw schlieren::Error(std::string(f) + ": parallel->size is " + std::to_string(p->size) +
      ": the number of ranks, at least 1.");
  if (p->rank < 0 || p->rank >= p->size)
    throw schlieren::Error(std::string(f) + ": parallel->rank is " + std::to_string(p->rank) +
      ": it must be in [0, " + std::to_string(p->size) + ") (parallel->size " +
      std::to_string(p->size) + ").");
  if (p->size == 1)
    return schlieren::SerialParallel();
  if (!p->reduce || !p->broadcast || !p->allgather)
    throw schlieren::Error(std::string(f) + ": parallel->size is " + std::to_string(p->size) +
      " but its " + (!p->reduce ? "reduce" : !p->broadcast ? "broadcast" : "allgather") +
      " callback is NULL: give reduce, broadcast and allgather.");
  own = std::make_unique<CallbackParallel>(*p, f);
  return *own;
}
} // namespace

int schlieren_parallel_failure(const schlieren_parallel* parallel, const char* mine, const char** agreed)
{
  if (agreed)
    *agreed = "";
  return Guard(LastError, [&] {
    if (!agreed)
      throw schlieren::Error("schlieren_parallel_failure: agreed must be given.");
    std::unique_ptr<CallbackParallel> own;
    schlieren::Parallel& ranks = RanksOf("schlieren_parallel_failure", parallel, own);
    Returned = ranks.Failure(mine ? mine : "");
    *agreed = Returned.c_str();
  });
}

namespace
{
const std::string& PropertiesJson();
const std::string& DeviceJson(const char* device_name);
}

extern "C"
{

int schlieren_api_version(void)
{
  return SCHLIEREN_C_API_VERSION;
}

const char* schlieren_version(void)
{
  return "0.1.0";
}

const char* schlieren_last_error(void)
{
  return LastError.c_str();
}

const char* schlieren_properties(void)
{
  try
  {
    return PropertiesJson().c_str();
  }
  catch (...)
  {
    LastError = "Out of memory.";
    return "[]";
  }
}

const char* schlieren_opencl_device(const char* device_name)
{
  try
  {
    return DeviceJson(device_name).c_str();
  }
  catch (...)
  {
    LastError = "Out of memory.";
    return "{}";
  }
}

} // extern "C"

namespace
{
const std::string& PropertiesJson()
{
  static const std::string text = [] {
    const TraceSettings d = Defaults();
    std::ostringstream o;
    o << "[";
    bool first = true;
    for (const Property& p : Properties())
    {
      o << (first ? "" : ", ") << "{\"name\": " << Json(p.Name) << ", \"kind\": " << Json(p.Kind)
        << ", \"size\": " << p.Size << ", \"default\": ";
      first = false;
      if (p.GetText)
        o << Json(p.GetText(d));
      else if (std::strcmp(p.Kind, "enum") == 0)
        o << Json(ValueText(p, d));
      else
      {
        const std::vector<double> v = p.GetNumbers(d);
        if (p.Size > 1)
          o << "[";
        for (std::size_t i = 0; i < v.size(); ++i)
          o << (i ? ", " : "") << Number(v[i]);
        if (p.Size > 1)
          o << "]";
      }
      o << ", \"entries\": [";
      for (std::size_t i = 0; i < p.Entries.size(); ++i)
        o << (i ? ", " : "") << Json(p.Entries[i]);
      o << "]}";
    }
    o << "]";
    return o.str();
  }();
  return text;
}

const std::string& DeviceJson(const char* device_name)
{
  schlieren::DeviceInfo info;
  if (Guard(LastError, [&] { info = schlieren::QueryOpenCLDevice(device_name ? device_name : ""); }))
    info.Reason = LastError;
  std::ostringstream o;
  o << "{\"available\": " << (info.Available ? "true" : "false") << ", \"name\": " << Json(info.Name)
    << ", \"platform\": " << Json(info.Platform) << ", \"version\": " << Json(info.Version)
    << ", \"reason\": " << Json(info.Reason) << "}";
  Returned = o.str();
  return Returned;
}
} // namespace

extern "C"
{

schlieren_session* schlieren_session_new(void)
{
  try
  {
    auto session = std::make_shared<schlieren_session>();
    std::lock_guard<std::mutex> lock(RegistryMutex());
    Registry()[session.get()] = session;
    return session.get();
  }
  catch (...)
  {
    LastError = "schlieren_session_new: out of memory.";
    return nullptr;
  }
}

void schlieren_session_free(schlieren_session* s)
{
  if (!s)
    return;
  try
  {
    std::shared_ptr<schlieren_session> gone;
    {
      std::lock_guard<std::mutex> lock(RegistryMutex());
      const auto it = Registry().find(s);
      if (it == Registry().end())
      {
        // a second free, or a foreign pointer: refused (not deleted twice)
        LastError = std::string("schlieren_session_free: ") + NotLive(s) + ".";
        return;
      }
      gone = std::move(it->second);
      Registry().erase(it);
    }
    // freed here, or when a call still running on another thread ends
  }
  catch (...)
  {
  }
}

const char* schlieren_session_error(const schlieren_session* s)
{
  Held h(s, "schlieren_session_error");
  if (!h)
    return NotLive(s);
  return h->Error.c_str();
}

int schlieren_session_set(schlieren_session* s, const char* name, const char* value)
{
  Held h(s, "schlieren_session_set");
  if (!h)
    return 1;
  return Guard(h->Error, [&] {
    const Property* p = FindProperty(name);
    if (!p)
    {
      std::string list;
      std::vector<const char*> names;
      for (const Property& q : Properties())
      {
        list += std::string(list.empty() ? "" : ", ") + q.Name;
        names.push_back(q.Name);
      }
      throw schlieren::Error(std::string("SchlierenImage has no property '") + (name ? name : "(NULL)") +
        "'" + (name ? Closest(name, names) : std::string()) + "; it has: " + list + ".");
    }
    const std::string why = SetProperty(*p, h->Settings, value);
    if (!why.empty())
      throw schlieren::Error(why);
  });
}

const char* schlieren_session_get(schlieren_session* s, const char* name)
{
  Held h(s, "schlieren_session_get");
  if (!h)
    return nullptr;
  const Property* p = FindProperty(name);
  if (!p)
  {
    std::vector<const char*> names;
    for (const Property& q : Properties())
      names.push_back(q.Name);
    h->Error = std::string("SchlierenImage has no property '") + (name ? name : "(NULL)") + "'" +
      (name ? Closest(name, names) : std::string()) + ".";
    return nullptr;
  }
  if (Guard(h->Error, [&] { h->Text = ValueText(*p, h->Settings); }))
    return nullptr;
  return h->Text.c_str();
}

namespace
{
/** The session's volume: this rank's piece `extent` of `whole` (both the whole where one process
 * holds it), checked. */
int SetPiece(schlieren_session* handle, const char* f, const int whole[6], const int extent[6],
  const double origin[3], const double spacing[3], const float* n_minus_1,
  int64_t n_minus_1_count, const unsigned char* solid, int64_t solid_count,
  const unsigned char* levels, int64_t levels_count, double level_tolerance, int max_level)
{
  Held h(handle, f);
  if (!h)
    return 1;
  schlieren_session* s = h.get();
  return Guard(s->Error, [&] {
    if (!whole || !extent)
      throw schlieren::Error(std::string(f) + ": whole_extent and extent must be given.");
    int wholeDims[3], dims[3] = { 0, 0, 0 };
    for (int a = 0; a < 3; ++a)
      wholeDims[a] = whole[2 * a + 1] >= whole[2 * a] &&
          std::int64_t(whole[2 * a + 1]) - whole[2 * a] < (std::int64_t(1) << 31) - 1
        ? whole[2 * a + 1] - whole[2 * a] + 1
        : 0;
    GridPoints(f, wholeDims); // the whole volume's points: refused as a grid's dims are
    const bool empty = EmptyExtent(extent);
    if (!empty)
    {
      for (int a = 0; a < 3; ++a)
      {
        if (extent[2 * a] < whole[2 * a] || extent[2 * a + 1] > whole[2 * a + 1])
          throw schlieren::Error(std::string(f) + ": extent " + std::to_string(extent[0]) + " " +
            std::to_string(extent[1]) + " " + std::to_string(extent[2]) + " " +
            std::to_string(extent[3]) + " " + std::to_string(extent[4]) + " " +
            std::to_string(extent[5]) + " does not lie inside whole_extent " +
            std::to_string(whole[0]) + " " + std::to_string(whole[1]) + " " +
            std::to_string(whole[2]) + " " + std::to_string(whole[3]) + " " +
            std::to_string(whole[4]) + " " + std::to_string(whole[5]) + ".");
        dims[a] = extent[2 * a + 1] - extent[2 * a] + 1;
      }
    }
    const std::int64_t n = empty ? 0 : GridPoints(f, dims);
    const std::string per = empty ? std::string("an empty piece")
                                  : (std::equal(whole, whole + 6, extent) ? "a grid of " : "a piece of ") +
        GridText(dims) + " points";
    CheckFinite3(f, "origin", origin);
    CheckFinite3(f, "spacing", spacing);
    CheckArray(f, "n_minus_1", n_minus_1, n_minus_1_count, n, per, empty);
    CheckArray(f, "solid", solid, solid_count, n, per, true);
    CheckArray(f, "levels", levels, levels_count, n, per, true);
    if (!(max_level >= 0 && max_level <= 10))
      throw schlieren::Error(std::string(f) + ": max_level is " + std::to_string(max_level) +
        ": it must be in [0, 10] (RefractionOctree's MaxLevel).");
    if (std::isnan(level_tolerance))
      throw schlieren::Error(std::string(f) + ": level_tolerance is NaN (< 0: unknown).");
    // the copies, refused before they are made where they do not fit
    schlieren::CheckHostMemory(double(n) * (4.0 + (solid ? 1 : 0) + (levels ? 1 : 0)),
      "The session's copy of a volume of " + GridText(dims) + " points",
      "Give a smaller volume (resample it).");
    s->HasVolume = false;
    s->NMinus1.assign(n_minus_1, n_minus_1 + n);
    if (solid)
      s->Solid.assign(solid, solid + n);
    else
      s->Solid.clear();
    if (levels)
      s->Levels.assign(levels, levels + n);
    else
      s->Levels.clear();
    s->LevelTolerance = level_tolerance;
    s->MaxLevel = max_level;
    schlieren::VolumePiece& piece = s->Piece;
    for (int a = 0; a < 3; ++a)
    {
      piece.WholeExtent[2 * a] = whole[2 * a];
      piece.WholeExtent[2 * a + 1] = whole[2 * a + 1];
      piece.Extent[2 * a] = empty ? 0 : extent[2 * a];
      piece.Extent[2 * a + 1] = empty ? -1 : extent[2 * a + 1];
      piece.Origin[a] = origin[a];
      piece.Spacing[a] = spacing[a];
    }
    piece.Version = ++s->Version;
    piece.Problem.clear();
    piece.Load = [s](schlieren::PieceValues& v) {
      // read in place: the session's copy lives, unchanged, through the Update
      v.NMinus1InPlace = s->NMinus1.data();
      v.NMinus1InPlaceCount = s->NMinus1.size();
      v.Solid = s->Solid;
      if (s->Settings.UseOctree && !s->Levels.empty())
      {
        v.Levels = s->Levels;
        v.HasLevelTolerance = s->LevelTolerance >= 0;
        v.LevelTolerance = s->LevelTolerance >= 0 ? s->LevelTolerance : 0.0;
        v.MaxLevel = s->MaxLevel;
      }
      return std::string();
    };
    s->HasVolume = true;
  });
}
} // namespace

int schlieren_session_set_volume(schlieren_session* handle, const int dims[3],
  const double origin[3], const double spacing[3], const float* n_minus_1,
  int64_t n_minus_1_count, const unsigned char* solid, int64_t solid_count,
  const unsigned char* levels, int64_t levels_count, double level_tolerance, int max_level)
{
  const char* f = "schlieren_session_set_volume";
  int whole[6] = { 0, -1, 0, -1, 0, -1 };
  for (int a = 0; a < 3; ++a)
    {
      if (!dims || dims[a] < 1)
      {
        // the grid's message, as before
        Held h(handle, f);
        if (!h)
          return 1;
        return Guard(h->Error, [&] { GridPoints(f, dims); });
      }
      whole[2 * a + 1] = dims[a] - 1;
    }
  return SetPiece(handle, f, whole, whole, origin, spacing,
    n_minus_1, n_minus_1_count, solid, solid_count, levels, levels_count, level_tolerance,
    max_level);
}

int schlieren_session_set_piece(schlieren_session* handle, const int whole_extent[6],
  const int extent[6], const double origin[3], const double spacing[3], const float* n_minus_1,
  int64_t n_minus_1_count, const unsigned char* solid, int64_t solid_count,
  const unsigned char* levels, int64_t levels_count, double level_tolerance, int max_level)
{
  return SetPiece(handle, "schlieren_session_set_piece", whole_extent, extent, origin, spacing,
    n_minus_1, n_minus_1_count, solid, solid_count, levels, levels_count, level_tolerance,
    max_level);
}

namespace
{
int TraceWith(schlieren_session* handle, const char* name,
  schlieren_progress_callback callback, void* user, const schlieren_parallel* parallel = nullptr)
{
  Held h(handle, name);
  if (!h)
    return 1;
  schlieren_session* s = h.get();
  s->Image = schlieren::SessionImage();
  s->HasImage = false;
  bool stopped = false;
  int percent = 0;
  const int rc = Guard(s->Error, [&] {
    if (!s->HasVolume)
      throw schlieren::Error("No volume: call schlieren_session_set_volume before tracing.");
    // the octree levels take part only with UseOctree (the filter reads them only then): a
    // change of UseOctree is a new volume for the session
    s->Piece.Version = s->Version * 2 + (s->Settings.UseOctree ? 1 : 0);
    // the C++ filter's TraceProgress: its text and, on a stop, its message
    schlieren::TraceClock clock(s->Settings.Passes);
    schlieren::ProgressFunction progress;
    if (callback)
      progress = [&](double fraction) {
        const std::string text = clock.Text(fraction);
        // once stopped, stopped: the engine asks again at points where it cannot stop
        stopped = stopped || callback(fraction, text.c_str(), user) == 0;
        percent = clock.Percent();
        return !stopped;
      };
    std::unique_ptr<CallbackParallel> own;
    schlieren::Parallel& ranks = RanksOf(name, parallel, own);
    s->Session.Update(ranks, s->Piece, s->Settings, s->Image, progress);
    s->HasImage = s->Image.HasImage;
  });
  if (rc != 0 && stopped)
    s->Error = "aborted at " + std::to_string(percent) + " % of the trace: no image yet";
  try
  {
    MakeReport(s, s->Error);
  }
  catch (...)
  {
    s->Report = "{\"field_data\": {}, \"notes\": [], \"error\": \"Out of memory.\"}";
  }
  return rc;
}
} // namespace

int schlieren_session_trace(schlieren_session* handle)
{
  return TraceWith(handle, "schlieren_session_trace", nullptr, nullptr);
}

int schlieren_session_trace_progress(
  schlieren_session* handle, schlieren_progress_callback progress, void* user)
{
  return TraceWith(handle, "schlieren_session_trace_progress", progress, user);
}

int schlieren_session_trace_parallel(schlieren_session* handle,
  const schlieren_parallel* parallel, schlieren_progress_callback progress, void* user)
{
  return TraceWith(handle, "schlieren_session_trace_parallel", progress, user, parallel);
}

int schlieren_session_write_bos_pair(schlieren_session* handle, const char* folder, int bits,
  const char* format, const char* prefix, const char** written)
{
  Held h(handle, "schlieren_session_write_bos_pair");
  if (!h)
    return 1;
  schlieren_session* s = h.get();
  if (written)
    *written = nullptr;
  if (!s->HasImage)
  {
    s->Error = "schlieren_session_write_bos_pair: no image: trace one with Cutoff BOS first.";
    return 1;
  }
  return Guard(s->Error, [&] {
    schlieren::BOSPairRequest request;
    request.Folder = folder ? folder : "";
    request.Bits = bits;
    request.Format = format ? format : "png";
    request.Prefix = prefix ? prefix : "bos";
    const schlieren::BOSPairFiles files = schlieren::WriteBOSPair(s->Image, request);
    s->Text = "{\"background\": " + Json(files.Background) + ", \"recording\": " +
      Json(files.Recording) + ", \"side_file\": " + Json(files.SideFile) + "}";
    if (written)
      *written = s->Text.c_str();
  });
}

const float* schlieren_session_array(
  const schlieren_session* handle, const char* name, int* components, int64_t* pixels)
{
  Held h(handle, "schlieren_session_array");
  if (!h || !h->HasImage || !name)
    return nullptr;
  const schlieren::TraceResult& r = h->Image.Result;
  const struct
  {
    const char* Name;
    const std::vector<float>* Values;
    int Components;
  } arrays[] = { { "intensity", &r.Intensity, 1 }, { "deflection", &r.Deflection, 2 },
    { "rgb", &r.RGB, 3 }, { "phase", &r.Phase, 1 }, { "bos_displacement", &r.Displacement, 2 },
    { "error_estimate", &r.ErrorEstimate, 1 }, { "blocked", &r.Blocked, 1 } };
  const std::int64_t count = static_cast<std::int64_t>(r.Film.Size[0]) * r.Film.Size[1];
  for (const auto& a : arrays)
  {
    if (std::strcmp(a.Name, name) == 0)
    {
      if (a.Values->empty() || static_cast<std::int64_t>(a.Values->size()) != count * a.Components)
        return nullptr;
      if (components)
        *components = a.Components;
      if (pixels)
        *pixels = count;
      return a.Values->data();
    }
  }
  return nullptr;
}

int schlieren_session_film(
  const schlieren_session* handle, int size[2], double origin[2], double* pixel_size)
{
  Held h(handle, "schlieren_session_film");
  if (!h)
    return 1;
  if (!h->HasImage)
  {
    h->Error = "schlieren_session_film: no image: the session has not traced one yet, or its last "
               "trace failed (" + (h->Error.empty() ? std::string("no trace yet") : h->Error) + ").";
    return 1;
  }
  const schlieren::FilmGeometry& f = h->Image.Result.Film;
  if (size)
  {
    size[0] = f.Size[0];
    size[1] = f.Size[1];
  }
  if (origin)
    f.GetImageOrigin(origin);
  if (pixel_size)
    *pixel_size = f.PixelSize;
  return 0;
}

int schlieren_session_plan_film(schlieren_session* handle, const int dims[3], const double origin[3],
  const double spacing[3], int size[2], double film_origin[2], double* pixel_size)
{
  Held h(handle, "schlieren_session_plan_film");
  if (!h)
    return 1;
  schlieren_session* s = h.get();
  return Guard(s->Error, [&] {
    const char* f = "schlieren_session_plan_film";
    GridPoints(f, dims);
    CheckFinite3(f, "origin", origin);
    CheckFinite3(f, "spacing", spacing);
    schlieren::Volume v;
    for (int a = 0; a < 3; ++a)
    {
      v.Dimensions[a] = dims[a];
      v.Origin[a] = origin[a];
      v.Spacing[a] = spacing[a];
    }
    const schlieren::FilmGeometry film = schlieren::PlannedFilm(v, s->Settings, s->Session);
    if (size)
    {
      size[0] = film.Size[0];
      size[1] = film.Size[1];
    }
    if (film_origin)
      film.GetImageOrigin(film_origin);
    if (pixel_size)
      *pixel_size = film.PixelSize;
  });
}

const char* schlieren_session_report(const schlieren_session* handle)
{
  Held h(handle, "schlieren_session_report");
  if (!h)
  {
    Returned = "{\"field_data\": {}, \"notes\": [], \"error\": " +
      Json(std::string("schlieren_session_report: ") + NotLive(handle) + ".") + "}";
    return Returned.c_str();
  }
  return h->Report.c_str();
}

int schlieren_fill_scene(const char* settings, const int dims[3], const double origin[3],
  const double spacing[3], int64_t count, float* n_minus_1, float* density, float* mixture_fraction,
  unsigned char* solid)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_fill_scene";
    const std::int64_t n = GridPoints(f, dims);
    CheckFinite3(f, "origin", origin);
    CheckFinite3(f, "spacing", spacing);
    CheckArray(f, "n_minus_1 (and each array given)", n_minus_1, count, n,
      "a grid of " + GridText(dims) + " points", false);
    static const char* scenes[] = { "Uniform", "GaussianSphere", "LuneburgLens", "LinearGradient",
      "NormalShock", "HeliumPlume", "BlastWave" };
    static const char* bodies[] = { "None", "Sphere", "Cylinder" };
    schlieren::Scene scene = schlieren::Scene::GaussianSphere;
    schlieren::SceneParameters p;
    schlieren::BodyParameters b;
    std::istringstream lines(settings ? settings : "");
    std::string line;
    while (std::getline(lines, line))
    {
      if (line.find_first_not_of(" \t\r") == std::string::npos)
        continue;
      const std::size_t eq = line.find('=');
      if (eq == std::string::npos)
        throw schlieren::Error("RefractiveScene setting '" + line + "': expected Name=value.");
      const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
      auto pick = [&](const char* const* names, int entries) {
        for (int i = 0; i < entries; ++i)
          if (value == names[i])
            return i;
        std::string list;
        for (int i = 0; i < entries; ++i)
          list += std::string(i ? ", " : "") + names[i];
        throw schlieren::Error(key + " '" + value + "' is not one of: " + list +
          Closest(value, std::vector<const char*>(names, names + entries)) + ".");
      };
      std::vector<double> v;
      auto numbers = [&](int n) {
        if (!ParseNumbers(value.c_str(), v) || static_cast<int>(v.size()) != n)
          throw schlieren::Error(key + " '" + value + "': expected " + std::to_string(n) +
            (n == 1 ? " number." : " numbers."));
      };
      if (key == "Scene")
        scene = static_cast<schlieren::Scene>(pick(scenes, 7));
      else if (key == "Body")
        b.Shape = static_cast<schlieren::Body>(pick(bodies, 3));
      else if (key == "Center" || key == "BodyCenter" || key == "BodyAxis")
      {
        numbers(3);
        double* to = key == "Center" ? p.Center : (key == "BodyCenter" ? b.Center : b.Axis);
        std::copy(v.begin(), v.end(), to);
      }
      else
      {
        double* to = key == "Amplitude" ? &p.Amplitude
          : key == "Width"               ? &p.Width
          : key == "Radius"              ? &p.Radius
          : key == "GradientA"           ? &p.GradientA
          : key == "GradientB"           ? &p.GradientB
          : key == "Mach"                ? &p.Mach
          : key == "Density"             ? &p.Density
          : key == "Time"                ? &p.Time
          : key == "BodyRadius"          ? &b.Radius
                                         : nullptr;
        if (!to)
        {
          static const char* known[] = { "Scene", "Amplitude", "Width", "Radius", "Center",
            "GradientA", "GradientB", "Mach", "Density", "Time", "Body", "BodyRadius", "BodyCenter",
            "BodyAxis" };
          throw schlieren::Error("RefractiveScene has no engine setting '" + key + "'" +
            Closest(key, known) + ".");
        }
        numbers(1);
        *to = v[0];
      }
    }
    // the ranges of RefractiveScene's properties, as the C++ filter checks them
    schlieren::CheckSceneParameters(p, b);
    schlieren::FillScene(scene, p, dims, origin, spacing, n_minus_1, density, mixture_fraction);
    if (solid && b.Shape != schlieren::Body::None)
      schlieren::FillBody(b, dims, origin, spacing, solid);
  });
}

namespace
{
int NumericalWith(const char* f, const char* settings, const int dims[3], const double origin[3],
  const double spacing[3], const float* values, int64_t values_count, const unsigned char* solid,
  int64_t solid_count, const unsigned char* excluded, int64_t excluded_count, int size[2],
  double film_origin[2], double* pixel_size, int64_t capacity, float* intensity, float* gradient,
  unsigned char* blocked, double maximum_largest[2], schlieren_progress_callback callback,
  void* user, const int* offset = nullptr, const int* piece_dims = nullptr,
  const schlieren_parallel* parallel = nullptr, int* has_image = nullptr)
{
  if (has_image)
    *has_image = 0;
  return Guard(LastError, [&] {
    std::unique_ptr<CallbackParallel> own;
    schlieren::Parallel& ranks = RanksOf(f, parallel, own);
    GridPoints(f, dims);
    // this rank's piece: its points (0 where it holds none) and their index in the whole grid
    int pieceDims[3] = { dims[0], dims[1], dims[2] }, pieceOffset[3] = { 0, 0, 0 };
    bool emptyPiece = false;
    if (piece_dims)
    {
      if (!offset)
        throw schlieren::Error(std::string(f) + ": offset must be given with piece_dims.");
      for (int a = 0; a < 3; ++a)
      {
        emptyPiece = emptyPiece || piece_dims[a] == 0;
        if (piece_dims[a] < 0 || offset[a] < 0 || offset[a] > dims[a] ||
          piece_dims[a] > dims[a] - offset[a])
          throw schlieren::Error(std::string(f) + ": the piece (offset " + std::to_string(offset[0]) +
            " " + std::to_string(offset[1]) + " " + std::to_string(offset[2]) + ", piece_dims " +
            std::to_string(piece_dims[0]) + " " + std::to_string(piece_dims[1]) + " " +
            std::to_string(piece_dims[2]) + ") does not lie inside whole_dims " + GridText(dims) + ".");
        pieceDims[a] = piece_dims[a];
        pieceOffset[a] = offset[a];
      }
    }
    const std::int64_t points = emptyPiece ? 0 : GridPoints(f, pieceDims);
    CheckFinite3(f, "origin", origin);
    CheckFinite3(f, "spacing", spacing);
    if (capacity < 0)
      throw schlieren::Error("schlieren_numerical: capacity is " + std::to_string(capacity) +
        ": a count of pixels (>= 0).");
    schlieren::NumericalSettings ns;
    std::istringstream lines(settings ? settings : "");
    std::string line;
    while (std::getline(lines, line))
    {
      if (line.find_first_not_of(" \t\r") == std::string::npos)
        continue;
      const std::size_t eq = line.find('=');
      if (eq == std::string::npos)
        throw schlieren::Error("NumericalSchlieren setting '" + line + "': expected Name=value.");
      const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
      std::vector<double> v;
      auto numbers = [&](std::size_t n) {
        if (!ParseNumbers(value.c_str(), v) || v.size() != n)
          throw schlieren::Error(key + " '" + value + "': expected " + std::to_string(n) +
            (n == 1 ? " number." : " numbers."));
      };
      if (key == "Mode" || key == "Gradient")
      {
        const bool mode = key == "Mode";
        const char* a = mode ? "Slice" : "Magnitude";
        const char* b = mode ? "LineOfSight" : "KnifeComponent";
        if (value != a && value != b)
          throw schlieren::Error(key + " '" + value + "' is not one of: " + a + ", " + b +
            Closest(value, std::vector<const char*>{ a, b }) + ".");
        if (mode)
          ns.Mode = value == a ? schlieren::NumericalMode::Slice : schlieren::NumericalMode::LineOfSight;
        else
          ns.Quantity = value == a ? schlieren::NumericalQuantity::Magnitude
                                   : schlieren::NumericalQuantity::KnifeComponent;
      }
      else if (key == "ViewDirection" || key == "ViewUp")
      {
        numbers(3);
        std::copy(v.begin(), v.end(), key == "ViewDirection" ? ns.ViewDirection : ns.ViewUp);
      }
      else if (key == "Resolution")
      {
        numbers(2);
        for (int i = 0; i < 2; ++i)
        {
          if (v[i] != std::floor(v[i]) || std::fabs(v[i]) > 1e9)
            throw schlieren::Error("Resolution '" + value + "': expected two integers.");
          ns.Resolution[i] = static_cast<int>(v[i]);
        }
      }
      else
      {
        double* to = key == "KnifeAngle"    ? &ns.KnifeAngle
          : key == "SliceOffset"            ? &ns.SliceOffset
          : key == "StepSize"               ? &ns.StepSize
          : key == "C0"                     ? &ns.C0
          : key == "C1"                     ? &ns.C1
          : key == "K"                      ? &ns.K
          : key == "GradientMaximum"        ? &ns.Maximum
                                            : nullptr;
        if (!to)
        {
          static const char* known[] = { "Mode", "Gradient", "ViewDirection", "ViewUp",
            "Resolution", "KnifeAngle", "SliceOffset", "StepSize", "C0", "C1", "K",
            "GradientMaximum" };
          throw schlieren::Error("NumericalSchlieren has no engine setting '" + key + "'" +
            Closest(key, known) + ".");
        }
        numbers(1);
        *to = v[0];
      }
    }
    schlieren::CheckNumericalSettings(ns);
    schlieren::ScalarGrid grid;
    for (int a = 0; a < 3; ++a)
    {
      grid.Dimensions[a] = dims[a];
      grid.Origin[a] = origin[a];
      grid.Spacing[a] = spacing[a];
    }
    if (!intensity)
    {
      // the film only (RequestInformation's extent)
      const schlieren::FilmGeometry f = schlieren::NumericalFilm(grid, ns);
      if (size)
      {
        size[0] = f.Size[0];
        size[1] = f.Size[1];
      }
      if (film_origin)
        f.GetImageOrigin(film_origin);
      if (pixel_size)
        *pixel_size = f.PixelSize;
      return;
    }
    if (!gradient || !blocked)
      throw schlieren::Error("schlieren_numerical: intensity, gradient and blocked must be given "
                             "together (each of `capacity` pixels).");
    const std::string per = emptyPiece ? std::string("an empty piece")
                                       : (piece_dims ? "a piece of " : "a grid of ") + GridText(pieceDims) + " points";
    CheckArray(f, "values", values, values_count, points, per, emptyPiece);
    CheckArray(f, "solid", solid, solid_count, points, per, true);
    CheckArray(f, "excluded", excluded, excluded_count, points, per, true);
    schlieren::ScalarGrid piece = grid;
    for (int a = 0; a < 3; ++a)
    {
      piece.Dimensions[a] = emptyPiece ? 0 : pieceDims[a];
      piece.Origin[a] = origin[a] + pieceOffset[a] * spacing[a];
    }
    piece.Values = values;
    piece.Solid = solid;
    piece.Excluded = excluded;
    grid.Values = values;
    grid.Solid = solid;
    grid.Excluded = excluded;
    // the callback's progress; once it says stop, stopped (the engine's last report ignores it)
    bool stopped = false;
    schlieren::ProgressFunction progress;
    if (callback)
      progress = [&](double fraction) {
        const std::string text = "NumericalSchlieren: " +
          std::to_string(static_cast<int>(100.0 * fraction)) + " % of the image";
        stopped = stopped || callback(fraction, text.c_str(), user) == 0;
        return !stopped;
      };
    schlieren::NumericalImage image;
    if (!piece_dims)
      image = schlieren::NumericalSchlieren(grid, ns, progress);
    else
    {
      grid.Values = nullptr;
      grid.Solid = grid.Excluded = nullptr;
      if (!schlieren::NumericalSchlierenOfPieces(ranks, piece, pieceOffset, grid, ns, image, progress))
        return; // rank 0 holds the image
    }
    if (has_image)
      *has_image = 1;
    const std::int64_t n = static_cast<std::int64_t>(image.Film.Size[0]) * image.Film.Size[1];
    if (n > capacity)
      throw schlieren::Error("schlieren_numerical: the film has " + std::to_string(n) +
        " pixels; the buffers hold " + std::to_string(capacity) + ".");
    std::copy(image.Intensity.begin(), image.Intensity.end(), intensity);
    std::copy(image.Gradient.begin(), image.Gradient.end(), gradient);
    std::copy(image.Blocked.begin(), image.Blocked.end(), blocked);
    if (size)
    {
      size[0] = image.Film.Size[0];
      size[1] = image.Film.Size[1];
    }
    if (film_origin)
      image.Film.GetImageOrigin(film_origin);
    if (pixel_size)
      *pixel_size = image.Film.PixelSize;
    if (maximum_largest)
    {
      maximum_largest[0] = image.Maximum;
      maximum_largest[1] = image.Largest;
    }
  });
}
} // namespace

int schlieren_numerical(const char* settings, const int dims[3], const double origin[3],
  const double spacing[3], const float* values, int64_t values_count, const unsigned char* solid,
  int64_t solid_count, const unsigned char* excluded, int64_t excluded_count, int size[2],
  double film_origin[2], double* pixel_size, int64_t capacity, float* intensity, float* gradient,
  unsigned char* blocked, double maximum_largest[2])
{
  return NumericalWith("schlieren_numerical", settings, dims, origin, spacing, values,
    values_count, solid, solid_count, excluded, excluded_count, size, film_origin, pixel_size,
    capacity, intensity, gradient, blocked, maximum_largest, nullptr, nullptr);
}

int schlieren_numerical_progress(const char* settings, const int dims[3], const double origin[3],
  const double spacing[3], const float* values, int64_t values_count, const unsigned char* solid,
  int64_t solid_count, const unsigned char* excluded, int64_t excluded_count, int size[2],
  double film_origin[2], double* pixel_size, int64_t capacity, float* intensity, float* gradient,
  unsigned char* blocked, double maximum_largest[2], schlieren_progress_callback progress,
  void* user)
{
  return NumericalWith("schlieren_numerical_progress", settings, dims, origin, spacing, values,
    values_count, solid, solid_count, excluded, excluded_count, size, film_origin, pixel_size,
    capacity, intensity, gradient, blocked, maximum_largest, progress, user);
}

int schlieren_numerical_pieces(const char* settings, const int whole_dims[3],
  const double origin[3], const double spacing[3], const int offset[3], const int piece_dims[3],
  const float* values, int64_t values_count, const unsigned char* solid, int64_t solid_count,
  const unsigned char* excluded, int64_t excluded_count, int size[2], double film_origin[2],
  double* pixel_size, int64_t capacity, float* intensity, float* gradient, unsigned char* blocked,
  double maximum_largest[2], schlieren_progress_callback progress, void* user,
  const schlieren_parallel* parallel, int* has_image)
{
  const char* f = "schlieren_numerical_pieces";
  if (!offset || !piece_dims || !intensity)
  {
    if (has_image)
      *has_image = 0;
    LastError = std::string(f) + ": offset, piece_dims and intensity (with gradient and blocked) "
                                 "must be given (schlieren_numerical plans the film).";
    return 1;
  }
  return NumericalWith(f, settings, whole_dims, origin, spacing, values, values_count, solid,
    solid_count, excluded, excluded_count, size, film_origin, pixel_size, capacity, intensity,
    gradient, blocked, maximum_largest, progress, user, offset, piece_dims, parallel, has_image);
}

int schlieren_octree_levels(const int dims[3], const float* n_minus_1, int64_t count,
  double tolerance, int max_level, unsigned char* levels, double* fraction)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_octree_levels";
    const std::int64_t n = GridPoints(f, dims);
    const std::string per = "a grid of " + GridText(dims) + " points";
    CheckArray(f, "n_minus_1 (and levels)", n_minus_1, count, n, per, false);
    if (!levels)
      throw schlieren::Error("schlieren_octree_levels: levels is NULL: it must hold `count` bytes.");
    if (!(max_level >= 0 && max_level <= 10))
      throw schlieren::Error("schlieren_octree_levels: max_level is " + std::to_string(max_level) +
        ": it must be in [0, 10] (RefractionOctree's MaxLevel).");
    if (!(tolerance >= 0) || !std::isfinite(tolerance))
    {
      std::ostringstream msg;
      msg << "schlieren_octree_levels: tolerance is " << tolerance
          << ": it must be a finite n - 1 difference >= 0.";
      throw schlieren::Error(msg.str());
    }
    const double share = schlieren::ComputeOctreeLevels(dims, n_minus_1, tolerance, levels, max_level);
    if (fraction)
      *fraction = share;
  });
}

int schlieren_gradient(const int dims[3], const double spacing[3], const float* n_minus_1,
  int64_t count, float* grad3, int64_t grad3_count)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_gradient";
    const std::int64_t n = GridPoints(f, dims);
    const std::string per = "a grid of " + GridText(dims) + " points";
    CheckFinite3(f, "spacing", spacing);
    CheckArray(f, "n_minus_1", n_minus_1, count, n, per, false);
    CheckArray(f, "grad3", grad3, grad3_count, 3 * n, per + " (3 floats a point)", false, "floats");
    schlieren::ComputeGradient(dims, spacing, n_minus_1, grad3);
  });
}

int schlieren_field_index(const char* model, const float* input, int64_t count, int index_is_n,
  double density_reference, const char* gas, float* n_minus_1, const char** report)
{
  if (report)
    *report = "";
  return Guard(LastError, [&] {
    if (count < 0)
      throw schlieren::Error("schlieren_field_index: count is " + std::to_string(count) +
        ": the number of points in input and n_minus_1 (>= 0).");
    if (!model)
      throw schlieren::Error("schlieren_field_index: model is NULL: give Passthrough or GladstoneDale.");
    if (count > 0 && (!input || !n_minus_1))
      throw schlieren::Error(std::string("schlieren_field_index: ") + (!input ? "input" : "n_minus_1") +
        " is NULL with a count of " + std::to_string(count) + ".");
    schlieren::FieldModel m;
    schlieren::FieldArrays a;
    a.Count = static_cast<std::size_t>(count);
    const std::string name = model;
    if (name == "Passthrough")
    {
      m.Model = schlieren::IndexModel::Passthrough;
      m.IndexIsN = index_is_n != 0;
      a.Index.Data = input;
      a.Index.Name = index_is_n ? "n" : "n_minus_1";
    }
    else if (name == "GladstoneDale")
    {
      m.Model = schlieren::IndexModel::GladstoneDale;
      m.DensityReference = density_reference;
      std::vector<double> km;
      if (gas && std::strncmp(gas, "Custom", 6) == 0)
      {
        // the proxy's Gas Custom: GladstoneDaleConstant and MolarMass typed in
        if (!ParseNumbers(gas + 6, km) || km.size() != 2)
          throw schlieren::Error(std::string("Gas '") + gas +
            "': Custom takes the Gladstone-Dale constant (m^3/kg) and the molar mass (kg/mol).");
        m.SingleGas = schlieren::GasChoice::Typed(km[0], km[1]);
      }
      else if (gas && *gas)
        m.SingleGas = schlieren::GasChoice::Table(schlieren::ParseGas(gas));
      a.Density.Data = input;
      a.Density.Name = "density";
    }
    else
      throw schlieren::Error("Model '" + name + "': this interface takes Passthrough or GladstoneDale" +
        Closest(name, std::vector<const char*>{ "Passthrough", "GladstoneDale" }) + ".");
    const schlieren::FieldReport r = schlieren::ComputeFieldIndex(a, m, n_minus_1);
    Returned.clear();
    for (const std::string& w : r.Warnings)
      Returned += w + "\n";
    if (report)
      *report = Returned.c_str();
  });
}

namespace
{
/** An entry's text among `names` (its index), else an Error naming the property and the entries. */
int EntryOf(const std::string& property, const std::string& text, std::vector<std::string> names)
{
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == text)
      return static_cast<int>(i);
  std::string all;
  for (const std::string& n : names)
    all += (all.empty() ? "" : ", ") + n;
  throw schlieren::Error(property + " '" + text + "' is not one of: " + all + ".");
}

/** `count` numbers of a property's text, else an Error naming it. */
std::vector<double> NumbersOf(const std::string& property, const std::string& text, std::size_t count)
{
  std::vector<double> v;
  if (!ParseNumbers(text.c_str(), v) || v.size() != count)
    throw schlieren::Error(property + " '" + text + "': " + std::to_string(count) +
      (count == 1 ? " number" : " numbers") + " expected.");
  return v;
}

/** A proxy's properties given as "Name=value" lines (entries by their text), each name among
 * `known`; else an Error naming the function and the line or name. */
std::map<std::string, std::string> SettingLines(
  const char* function, const char* settings, const std::vector<std::string>& known)
{
  std::map<std::string, std::string> p;
  std::istringstream lines(settings ? settings : "");
  for (std::string line; std::getline(lines, line);)
  {
    const std::size_t eq = line.find('=');
    if (line.empty())
      continue;
    if (eq == std::string::npos)
      throw schlieren::Error(std::string(function) + ": '" + line + "' is not Name=value.");
    p[line.substr(0, eq)] = line.substr(eq + 1);
  }
  for (const auto& kv : p)
    if (std::find(known.begin(), known.end(), kv.first) == known.end())
      throw schlieren::Error(std::string(function) + ": unknown setting '" + kv.first + "'" +
        " (the closest known: " + Closest(kv.first, known) + ").");
  return p;
}

/** RefractiveIndex's sampling settings (SamplingDimensions, AutomaticDimension, UseSamplingBounds,
 * SamplingBounds) from the settings `p` (absent: the proxy's defaults); an Error names one that does
 * not parse. */
schlieren::SamplingSettings SamplingSettingsOf(
  const char* f, const std::map<std::string, std::string>& p)
{
  auto text = [&](const char* name, const char* fallback) {
    const auto it = p.find(name);
    return it == p.end() ? std::string(fallback) : it->second;
  };
  schlieren::SamplingSettings s;
  const std::vector<double> sd = NumbersOf("SamplingDimensions", text("SamplingDimensions", "0 0 0"), 3);
  const double automaticDimension = NumbersOf("AutomaticDimension", text("AutomaticDimension", "128"), 1)[0];
  for (double v : sd)
    if (!(std::abs(v) < 1e9) || v != std::floor(v))
      throw schlieren::Error(std::string(f) + ": SamplingDimensions '" +
        text("SamplingDimensions", "") + "': whole numbers of points expected.");
  if (!(std::abs(automaticDimension) < 1e9) || automaticDimension != std::floor(automaticDimension))
    throw schlieren::Error(std::string(f) + ": AutomaticDimension '" +
      text("AutomaticDimension", "") + "': a whole number of points expected.");
  for (int a = 0; a < 3; ++a)
    s.SamplingDimensions[a] = static_cast<int>(sd[a]);
  s.AutomaticDimension = static_cast<int>(automaticDimension);
  s.UseSamplingBounds = NumbersOf("UseSamplingBounds", text("UseSamplingBounds", "0"), 1)[0] != 0;
  const std::vector<double> sb = NumbersOf("SamplingBounds", text("SamplingBounds", "0 1 0 1 0 1"), 6);
  std::copy(sb.begin(), sb.end(), s.SamplingBounds);
  return s;
}

/** A gas by the proxy's number (-1 Custom with K and M, 0 Air, 1 He, ...: SpeciesGases). */
schlieren::GasChoice GasByNumber(const std::string& property, double number, double K, double M)
{
  const int g = static_cast<int>(number);
  if (g != number || g < -1 || g >= static_cast<int>(schlieren::Gas::NumberOfGases))
    throw schlieren::Error(property + ": " + std::to_string(number) + " is not a gas number (-1 "
      "Custom, 0 to " + std::to_string(static_cast<int>(schlieren::Gas::NumberOfGases) - 1) + ").");
  return g < 0 ? schlieren::GasChoice::Typed(K, M)
               : schlieren::GasChoice::Table(static_cast<schlieren::Gas>(g));
}
/** The index models' settings (schlieren_index_model, schlieren_index_field). */
std::vector<std::string> ModelSettingNames()
{
  return { "Model", "PassthroughHoldsN", "Gas", "GladstoneDaleConstant", "MolarMass",
    "MixtureComposition", "IdealGasComposition", "MixtureGas0", "MixtureGas1", "NumberOfSpecies",
    "SpeciesGases", "SpeciesGladstoneDale", "SpeciesMolarMass", "BalanceGas",
    "BalanceGladstoneDale", "BalanceMolarMass", "DensityReference", "TemperatureUnit",
    "TemperatureReference", "PressureUnit", "PressureReference", "PressureOffset", "Humidity",
    "HumidityMeasure", "CO2", "Wavelength" };
}

/** The engine's model from the settings `p` (absent: the proxy's defaults); an Error names a
 * setting that does not parse. */
schlieren::FieldModel ModelOfSettings(const std::map<std::string, std::string>& p)
{
  auto text = [&](const char* name, const char* fallback) {
    const auto it = p.find(name);
    return it == p.end() ? std::string(fallback) : it->second;
  };
  auto number = [&](const char* name, double fallback) {
    const auto it = p.find(name);
    return it == p.end() ? fallback : NumbersOf(name, it->second, 1)[0];
  };
  auto gas = [&](const char* name, const std::string& value, double K, double M) {
    if (value == "Custom")
      return schlieren::GasChoice::Typed(K, M);
    try
    {
      return schlieren::GasChoice::Table(schlieren::ParseGas(value));
    }
    catch (const schlieren::Error& e)
    {
      throw schlieren::Error(std::string(name) + ": " + e.what());
    }
  };
  schlieren::FieldModel m;
  m.Model = static_cast<schlieren::IndexModel>(EntryOf("Model", text("Model", "Passthrough"),
    { "Passthrough", "GladstoneDale", "GladstoneDaleMixture", "IdealGas", "Ciddor" }));
  m.IndexIsN = number("PassthroughHoldsN", 0) != 0;
  m.SingleGas = gas("Gas", text("Gas", "Air"), number("GladstoneDaleConstant", 2.256e-4),
    number("MolarMass", 0.0289641));
  if (m.Model == schlieren::IndexModel::GladstoneDaleMixture)
    m.Mixture = static_cast<schlieren::Composition>(1 +
      EntryOf("MixtureComposition", text("MixtureComposition", "MixtureFraction"),
        { "MixtureFraction", "Species" }));
  else if (m.Model == schlieren::IndexModel::IdealGas)
    m.Mixture = static_cast<schlieren::Composition>(EntryOf("IdealGasComposition",
      text("IdealGasComposition", "Gas"), { "Gas", "MixtureFraction", "Species" }));
  else
    m.Mixture = schlieren::Composition::SingleGas;
  m.Gas0 = gas("MixtureGas0", text("MixtureGas0", "Air"), 0, 0).Preset;
  m.GasF = gas("MixtureGas1", text("MixtureGas1", "He"), 0, 0).Preset;
  m.NumberOfSpecies = static_cast<int>(number("NumberOfSpecies", 1));
  const std::vector<double> gases = NumbersOf("SpeciesGases", text("SpeciesGases", "6 8 1 5"), 4);
  const std::vector<double> K =
    NumbersOf("SpeciesGladstoneDale", text("SpeciesGladstoneDale", "2.256e-4 2.256e-4 2.256e-4 2.256e-4"), 4);
  const std::vector<double> M =
    NumbersOf("SpeciesMolarMass", text("SpeciesMolarMass", "0.0289641 0.0289641 0.0289641 0.0289641"), 4);
  for (int s = 0; s < schlieren::MaxSpecies; ++s)
    m.Species[s] = GasByNumber("SpeciesGases", gases[s], K[s], M[s]);
  const std::string balance = text("BalanceGas", "Air");
  m.HasBalance = balance != "None";
  m.Balance = m.HasBalance ? gas("BalanceGas", balance, number("BalanceGladstoneDale", 2.256e-4),
                               number("BalanceMolarMass", 0.0289641))
                           : schlieren::GasChoice::Table(schlieren::Gas::Air);
  m.DensityReference = number("DensityReference", 1.0);
  m.TemperatureReference = number("TemperatureReference", 1.0);
  m.TemperatureUnits = static_cast<schlieren::TemperatureUnit>(
    EntryOf("TemperatureUnit", text("TemperatureUnit", "Kelvin"), { "Kelvin", "Celsius" }));
  m.PressureReference = number("PressureReference", 1.0);
  m.PressureOffset = number("PressureOffset", 0.0);
  m.PressureUnits = static_cast<schlieren::PressureUnit>(
    EntryOf("PressureUnit", text("PressureUnit", "Pa"), { "Pa", "kPa", "atm", "bar" }));
  m.Humidity = number("Humidity", 0.0);
  m.HumidityKind = static_cast<schlieren::HumidityMeasure>(EntryOf("HumidityMeasure",
    text("HumidityMeasure", "RelativeHumidity"), { "RelativeHumidity", "WaterMoleFraction" }));
  m.CO2 = number("CO2", 450.0);
  m.Wavelength = number("Wavelength", 632.8);
  return m;
}
} // namespace

int schlieren_index_model(const char* settings, int64_t count, int number_of_arrays,
  const char* const* roles, const float* const* arrays, const unsigned char* valid,
  float* n_minus_1, const char** report)
{
  if (report)
    *report = "";
  return Guard(LastError, [&] {
    if (count < 0)
      throw schlieren::Error("schlieren_index_model: count is " + std::to_string(count) +
        ": the number of points in every array and n_minus_1 (>= 0).");
    if (!settings || (count > 0 && !n_minus_1) || number_of_arrays < 0 ||
      (number_of_arrays > 0 && (!roles || !arrays)))
      throw schlieren::Error("schlieren_index_model: settings, the arrays and n_minus_1 must be "
                             "given.");
    const std::map<std::string, std::string> p =
      SettingLines("schlieren_index_model", settings, ModelSettingNames());
    const schlieren::FieldModel m = ModelOfSettings(p);
    // the arrays, by role
    schlieren::FieldArrays a;
    a.Count = static_cast<std::size_t>(count);
    a.Valid = valid;
    for (int i = 0; i < number_of_arrays; ++i)
    {
      if (!roles[i] || !arrays[i])
        throw schlieren::Error("schlieren_index_model: array " + std::to_string(i) +
          " has no role or no values.");
      const std::string role = roles[i];
      // "role:name": the name is the input array's, for messages
      const std::size_t colon = role.find(':');
      const std::string kind = role.substr(0, colon);
      const std::string name = colon == std::string::npos ? kind : role.substr(colon + 1);
      schlieren::NamedArray* slot = nullptr;
      if (kind == "index")
        slot = &a.Index;
      else if (kind == "density")
        slot = &a.Density;
      else if (kind == "temperature")
        slot = &a.Temperature;
      else if (kind == "pressure")
        slot = &a.Pressure;
      else if (kind == "mixture_fraction")
        slot = &a.MixtureFraction;
      else if (kind.size() == 8 && kind.compare(0, 7, "species") == 0 && kind[7] >= '1' &&
        kind[7] <= '4')
        slot = &a.Species[kind[7] - '1'];
      else if (kind == "humidity")
        slot = &a.Humidity;
      else if (kind == "co2")
        slot = &a.CO2;
      else
        throw schlieren::Error("schlieren_index_model: unknown array role '" + kind + "' (index, "
          "density, temperature, pressure, mixture_fraction, species1-4, humidity, co2).");
      slot->Data = arrays[i];
      slot->Name = name;
    }
    const schlieren::FieldReport r = schlieren::ComputeFieldIndex(a, m, n_minus_1);
    Returned.clear();
    for (const std::string& w : r.Warnings)
      Returned += w + "\n";
    if (report)
      *report = Returned.c_str();
  });
}

namespace
{
std::string JsonList(const std::vector<std::string>& values)
{
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i)
    out += (i ? ", " : "") + Json(values[i]);
  return out + "]";
}

/** The lines of `text` (NULL: none), empty lines left out. */
std::vector<std::string> Lines(const char* text)
{
  std::vector<std::string> out;
  std::istringstream lines(text ? text : "");
  for (std::string line; std::getline(lines, line);)
    if (!line.empty())
      out.push_back(line);
  return out;
}

/** schlieren_index_field's report (JSON; see schlieren_c.h). */
std::string IndexFieldReport(const schlieren::IndexFieldOutput& out, const std::string& error)
{
  std::string r = "{\"model_done\": " + std::string(out.ModelDone ? "true" : "false") +
    ", \"warnings\": " + JsonList(out.Warnings) + ", \"notes\": " + JsonList(out.NewNotes) +
    ", \"solid_note\": " + Json(out.SolidNote) +
    ", \"solid\": " + (out.Solid.empty() ? "false" : "true") +
    ", \"arrays_read\": " + JsonList(out.ArraysRead) + ", \"field_data\": [";
  for (std::size_t i = 0; i < out.FieldData.size(); ++i)
  {
    const schlieren::IndexFieldValue& v = out.FieldData[i];
    r += (i ? ", [" : "[") + Json(v.Name) + ", " + (v.IsText ? JsonList(v.Texts) : Number(v.Number)) + "]";
  }
  return r + "], \"error\": " + Json(error) + "}";
}
} // namespace

namespace
{
/** schlieren_index_field on `dims_in` (one process), or on a piece (`extents`: grid, out and whole
 * extents, 18 values; dims from the grid's) over `parallel`. */
int IndexFieldWith(const char* f, const char* settings, const int dims_in[3],
  const int* extents, const double spacing[3],
  int number_of_arrays, const char* const* names, const int* components, const int* value_bytes,
  const void* const* values, const int64_t* value_counts, int active_scalars,
  const char* cell_arrays, const char* notes, const unsigned char* valid, int64_t valid_count,
  const unsigned char* rim, int64_t rim_count, const unsigned char* body, int64_t body_count,
  float* n_minus_1, int64_t n_minus_1_count, float* grad3, int64_t grad3_count,
  unsigned char* solid, int64_t solid_count, const schlieren_parallel* parallel,
  const char** report)
{
  if (report)
    *report = "";
  schlieren::IndexFieldOutput out;
  std::string failure;
  int dims[3] = { 0, 0, 0 };
  bool emptyPiece = false;
  const int status = Guard(LastError, [&] {
    std::unique_ptr<CallbackParallel> own;
    schlieren::Parallel& ranks = RanksOf(f, parallel, own);
    if (extents)
    {
      const int* whole = extents + 12;
      int wholeDims[3];
      for (int a = 0; a < 3; ++a)
        wholeDims[a] = whole[2 * a + 1] >= whole[2 * a] &&
            std::int64_t(whole[2 * a + 1]) - whole[2 * a] < (std::int64_t(1) << 31) - 1
          ? whole[2 * a + 1] - whole[2 * a] + 1
          : 0;
      GridPoints(f, wholeDims);
      emptyPiece = EmptyExtent(extents) || EmptyExtent(extents + 6);
      for (int e = 0; e < 2 && !emptyPiece; ++e)
        for (int a = 0; a < 3; ++a)
          if (extents[6 * e + 2 * a] < whole[2 * a] || extents[6 * e + 2 * a + 1] > whole[2 * a + 1] ||
            (e == 1 && (extents[6 + 2 * a] < extents[2 * a] || extents[6 + 2 * a + 1] > extents[2 * a + 1])))
            throw schlieren::Error(std::string(f) + ": the extents are not nested: out_extent must "
                                                    "lie inside grid_extent, and both inside whole_extent.");
      for (int a = 0; a < 3 && !emptyPiece; ++a)
        dims[a] = extents[2 * a + 1] - extents[2 * a] + 1;
    }
    else if (dims_in)
      std::copy(dims_in, dims_in + 3, dims);
    const std::int64_t points = emptyPiece ? 0 : GridPoints(f, extents ? dims : dims_in);
    CheckFinite3(f, "spacing", spacing);
    const std::string per = emptyPiece ? std::string("an empty piece") : "a grid of " + GridText(dims) + " points";
    CheckArray(f, "valid", valid, valid_count, points, per, true, "bytes");
    CheckArray(f, "rim", rim, rim_count, points, per, true, "bytes");
    CheckArray(f, "body", body, body_count, points, per, true, "bytes");
    CheckArray(f, "n_minus_1", n_minus_1, n_minus_1_count, points, per, emptyPiece);
    CheckArray(f, "grad3", grad3, grad3_count, 3 * points, per + " (3 a point)", emptyPiece);
    CheckArray(f, "solid", solid, solid_count, points, per, emptyPiece, "bytes");
    if (number_of_arrays < 0 ||
      (number_of_arrays > 0 && (!names || !components || !value_bytes || !values || !value_counts)))
      throw schlieren::Error(std::string(f) + ": number_of_arrays is " +
        std::to_string(number_of_arrays) + ": names, components, value_bytes, values and "
        "value_counts must hold that many entries.");
    std::vector<std::string> known = ModelSettingNames();
    for (const char* extra : { "InputArray", "TemperatureArray", "PressureArray",
           "MixtureFractionArray", "Species1Array", "Species2Array", "Species3Array",
           "Species4Array", "HumidityArray", "CO2Array", "HumidityFromArray", "CO2FromArray",
           "AmbientMode", "AmbientValue", "BodyFromGrid", "BodyWallFaces", "SolidArray",
           "Resampled", "UseSamplingBounds", "CellsDescription", "WallVelocity",
           "WallFaceCounts", "BodySurface", "BodyOverlaps" })
      known.emplace_back(extra);
    const std::map<std::string, std::string> p = SettingLines(f, settings, known);
    auto text = [&](const char* name, const char* fallback) {
      const auto it = p.find(name);
      return it == p.end() ? std::string(fallback) : it->second;
    };
    auto flag = [&](const char* name, double fallback) {
      const auto it = p.find(name);
      const double v = it == p.end() ? fallback : NumbersOf(name, it->second, 1)[0];
      if (v != 0.0 && v != 1.0)
        throw schlieren::Error(std::string(name) + " '" + it->second + "': 0 or 1 expected.");
      return v != 0.0;
    };
    schlieren::IndexFieldInput in;
    std::copy(dims, dims + 3, in.Dims);
    std::copy(spacing, spacing + 3, in.Spacing);
    in.Model = ModelOfSettings(p);
    static const char* const roles[] = { "InputArray", "TemperatureArray", "PressureArray",
      "MixtureFractionArray", "Species1Array", "Species2Array", "Species3Array", "Species4Array",
      "HumidityArray", "CO2Array" };
    for (int r = 0; r < schlieren::NumberOfRoles; ++r)
      in.ArrayNames[r] = text(roles[r], "");
    in.HumidityFromArray = flag("HumidityFromArray", 0);
    in.CO2FromArray = flag("CO2FromArray", 0);
    in.Ambient = static_cast<schlieren::AmbientFill>(EntryOf("AmbientMode",
      text("AmbientMode", "Extend"), { "Extend", "DomainEdgeMedian", "Value" }));
    in.AmbientValue = NumbersOf("AmbientValue", text("AmbientValue", "2.7164e-4"), 1)[0];
    in.BodyFromGrid = flag("BodyFromGrid", 1);
    const std::vector<double> walls =
      NumbersOf("BodyWallFaces", text("BodyWallFaces", "0 0 0 0 0 0"), 6);
    for (int w = 0; w < 6; ++w)
      in.WallFaces[w] = walls[w] != 0.0 ? 1 : 0;
    in.SolidArray = text("SolidArray", "");
    if (in.SolidArray == "None")
      in.SolidArray.clear(); // the proxy's entry for no array
    in.Resampled = flag("Resampled", 0);
    in.UseSamplingBounds = flag("UseSamplingBounds", 0);
    const std::string cells = text("CellsDescription", "");
    if (!cells.empty())
      in.DescribeCells = [cells] { return cells; };
    for (int i = 0; i < number_of_arrays; ++i)
    {
      const std::string which = "array " + std::to_string(i);
      if (!names[i])
        throw schlieren::Error(std::string(f) + ": " + which + " has no name (NULL).");
      if (components[i] < 1)
        throw schlieren::Error(std::string(f) + ": " + which + " ('" + names[i] + "') has " +
          std::to_string(components[i]) + " components: at least 1.");
      schlieren::GridArray g;
      g.Name = names[i];
      g.Components = components[i];
      if (components[i] == 1 || values[i] || value_counts[i] != 0)
      {
        if (value_bytes[i] != 4 && value_bytes[i] != 8)
          throw schlieren::Error(std::string(f) + ": " + which + " ('" + names[i] +
            "') has value_bytes " + std::to_string(value_bytes[i]) + ": 4 (float) or 8 (double).");
        const std::string label = which + " ('" + g.Name + "')";
        CheckArray(f, label.c_str(), values[i], value_counts[i],
          points * components[i], per + " x " + std::to_string(components[i]) + " components",
          false);
        if (value_bytes[i] == 4)
          g.Float = static_cast<const float*>(values[i]);
        else
          g.Double = static_cast<const double*>(values[i]);
      }
      in.PointArrays.push_back(g);
    }
    if (rim)
    {
      // the voids beside the mesh's walls: the rim's kinds the front end found (its nearest
      // boundary faces' kinds, schlieren_wall_faces)
      schlieren::walls::RimReport r;
      r.Velocity = text("WallVelocity", "U");
      const std::vector<double> c = NumbersOf("WallFaceCounts", text("WallFaceCounts", "0 0 0 0"), 4);
      for (double v : c)
        if (!(v >= 0) || v != std::floor(v) || v > 1e15)
          throw schlieren::Error(std::string(f) + ": WallFaceCounts takes 4 counts (walls, "
                                                  "crossed by the flow, at rest, turned).");
      r.WallFaces = static_cast<std::size_t>(c[0]);
      r.FlowFaces = static_cast<std::size_t>(c[1]);
      r.StillFaces = static_cast<std::size_t>(c[2]);
      r.TurnedFaces = static_cast<std::size_t>(c[3]);
      const int* d = dims;
      in.BesideWalls = [r, rim, d](const unsigned char* v, unsigned char* solidOut, std::string& note) {
        const std::size_t marked = schlieren::InvalidRegionsBesideWalls(d, v, rim, solidOut);
        note = schlieren::walls::BesideWallsNote(r, marked);
        return marked > 0;
      };
    }
    // the Body surface: what the front end's test of it found (the C++ filter's hook's result)
    const int surface = EntryOf("BodySurface", text("BodySurface", body ? "Inside" : "None"),
      { "Inside", "NoPolygons", "NotClosed", "NoInsideTest", "None" });
    if (surface < 4)
    {
      const auto found = static_cast<schlieren::BodySurface>(surface);
      if (found == schlieren::BodySurface::Inside && !body)
        throw schlieren::Error(std::string(f) + ": BodySurface Inside needs `body`, a byte a "
                                                "point (non-zero inside the surface).");
      const bool overlaps = flag("BodyOverlaps", 1);
      const std::size_t count = static_cast<std::size_t>(points);
      in.Surface = [found, body, count, overlaps](unsigned char* solidOut, bool& any,
                     std::string& note) {
        if (found != schlieren::BodySurface::Inside)
          return schlieren::BodySurfaceProblem(found);
        schlieren::MarkBodySurface(body, count, overlaps, solidOut, any, note);
        return std::string();
      };
    }
    in.ActiveScalars = active_scalars >= 0 && active_scalars < number_of_arrays ? active_scalars : -1;
    in.CellArrayNames = Lines(cell_arrays);
    in.Notes = Lines(notes);
    in.Valid = valid;
    in.NMinus1 = n_minus_1;
    in.Gradient = grad3;
    if (extents)
    {
      std::copy(extents, extents + 6, in.GridExtent);
      std::copy(extents + 6, extents + 12, in.OutExtent);
      std::copy(extents + 12, extents + 18, in.WholeExtent);
      in.EmptyPiece = emptyPiece;
    }
    else
      for (int a = 0; a < 3; ++a)
      {
        in.GridExtent[2 * a + 1] = in.OutExtent[2 * a + 1] = in.WholeExtent[2 * a + 1] = dims[a] - 1;
      }
    failure = schlieren::ComputeIndexField(ranks, in, out);
    if (solid)
    {
      std::fill(solid, solid + points, static_cast<unsigned char>(0));
      std::copy(out.Solid.begin(), out.Solid.begin() + std::min<std::ptrdiff_t>(
        static_cast<std::ptrdiff_t>(out.Solid.size()), static_cast<std::ptrdiff_t>(points)), solid);
    }
    if (!failure.empty())
      throw schlieren::Error(failure);
  });
  Returned = IndexFieldReport(out, status ? LastError : std::string());
  if (report)
    *report = Returned.c_str();
  return status;
}
} // namespace

int schlieren_index_field(const char* settings, const int dims[3], const double spacing[3],
  int number_of_arrays, const char* const* names, const int* components, const int* value_bytes,
  const void* const* values, const int64_t* value_counts, int active_scalars,
  const char* cell_arrays, const char* notes, const unsigned char* valid, int64_t valid_count,
  const unsigned char* rim, int64_t rim_count, const unsigned char* body, int64_t body_count,
  float* n_minus_1, int64_t n_minus_1_count, float* grad3, int64_t grad3_count,
  unsigned char* solid, int64_t solid_count, const char** report)
{
  return IndexFieldWith("schlieren_index_field", settings, dims, nullptr, spacing,
    number_of_arrays, names, components, value_bytes, values, value_counts, active_scalars,
    cell_arrays, notes, valid, valid_count, rim, rim_count, body, body_count, n_minus_1,
    n_minus_1_count, grad3, grad3_count, solid, solid_count, nullptr, report);
}

int schlieren_index_field_piece(const char* settings, const int grid_extent[6],
  const int out_extent[6], const int whole_extent[6], const double spacing[3],
  int number_of_arrays, const char* const* names, const int* components, const int* value_bytes,
  const void* const* values, const int64_t* value_counts, int active_scalars,
  const char* cell_arrays, const char* notes, const unsigned char* valid, int64_t valid_count,
  const unsigned char* rim, int64_t rim_count, const unsigned char* body, int64_t body_count,
  float* n_minus_1, int64_t n_minus_1_count, float* grad3, int64_t grad3_count,
  unsigned char* solid, int64_t solid_count, const schlieren_parallel* parallel,
  const char** report)
{
  const char* f = "schlieren_index_field_piece";
  if (!grid_extent || !out_extent || !whole_extent)
  {
    LastError = std::string(f) + ": grid_extent, out_extent and whole_extent must be given.";
    if (report)
      *report = "";
    return 1;
  }
  int extents[18];
  std::copy(grid_extent, grid_extent + 6, extents);
  std::copy(out_extent, out_extent + 6, extents + 6);
  std::copy(whole_extent, whole_extent + 6, extents + 12);
  return IndexFieldWith(f, settings, nullptr, extents, spacing, number_of_arrays, names,
    components, value_bytes, values, value_counts, active_scalars, cell_arrays, notes, valid,
    valid_count, rim, rim_count, body, body_count, n_minus_1, n_minus_1_count, grad3, grad3_count,
    solid, solid_count, parallel, report);
}

int schlieren_index_choices(
  const char* settings, const char* present, const char* fallback_input, const char** report)
{
  if (report)
    *report = "";
  return Guard(LastError, [&] {
    const char* f = "schlieren_index_choices";
    static const char* const roles[] = { "InputArray", "TemperatureArray", "PressureArray",
      "MixtureFractionArray", "Species1Array", "Species2Array", "Species3Array", "Species4Array",
      "HumidityArray", "CO2Array" };
    std::vector<std::string> known = ModelSettingNames();
    known.insert(known.end(), std::begin(roles), std::end(roles));
    const std::map<std::string, std::string> p = SettingLines(f, settings, known);
    auto text = [&](const char* name, const char* fallback) {
      const auto it = p.find(name);
      return it == p.end() ? std::string(fallback) : it->second;
    };
    auto number = [&](const char* name, double fallback) {
      const auto it = p.find(name);
      return it == p.end() ? fallback : NumbersOf(name, it->second, 1)[0];
    };
    schlieren::IndexChoiceInput in;
    in.Present = Lines(present);
    in.Model = EntryOf("Model", text("Model", "Automatic"),
                 { "Automatic", "Passthrough", "GladstoneDale", "GladstoneDaleMixture",
                   "IdealGas", "Ciddor" }) - 1;
    in.HoldsN = number("PassthroughHoldsN", 0) != 0;
    for (int r = 0; r < schlieren::NumberOfRoles; ++r)
      in.Arrays[r] = text(roles[r], "");
    const std::string gas = text("Gas", "Custom");
    in.Gas = gas == "Custom" ? -1 : static_cast<int>(schlieren::ParseGas(gas));
    in.GladstoneDale = number("GladstoneDaleConstant", 2.256e-4);
    in.MolarMass = number("MolarMass", 0.0289641);
    in.MixtureComposition = static_cast<schlieren::Composition>(1 +
      EntryOf("MixtureComposition", text("MixtureComposition", "MixtureFraction"),
        { "MixtureFraction", "Species" }));
    in.IdealGasComposition = static_cast<schlieren::Composition>(EntryOf("IdealGasComposition",
      text("IdealGasComposition", "Gas"), { "Gas", "MixtureFraction", "Species" }));
    in.TemperatureUnits = static_cast<schlieren::TemperatureUnit>(
      EntryOf("TemperatureUnit", text("TemperatureUnit", "Kelvin"), { "Kelvin", "Celsius" }));
    in.PressureUnits = static_cast<schlieren::PressureUnit>(
      EntryOf("PressureUnit", text("PressureUnit", "Pa"), { "Pa", "kPa", "atm", "bar" }));
    in.TemperatureReference = number("TemperatureReference", 1.0);
    in.PressureReference = number("PressureReference", 1.0);
    in.PressureOffset = number("PressureOffset", 0.0);
    in.DensityReference = number("DensityReference", 1.0);
    const std::string fallback = fallback_input ? fallback_input : "";
    in.FallbackInput = [fallback] { return fallback; };
    schlieren::IndexChoice out;
    const std::string problem = schlieren::ResolveIndexChoices(in, out);
    if (!problem.empty())
      throw schlieren::Error(problem);
    Returned = "{\"model\": " + Json(schlieren::IndexModelLabel(out.Model)) +
      ", \"holds_n\": " + (out.HoldsN ? "true" : "false") + ", \"arrays\": {";
    for (int r = 0; r < schlieren::NumberOfRoles; ++r)
      Returned += std::string(r ? ", " : "") + Json(roles[r]) + ": " + Json(out.Arrays[r]);
    Returned += "}, \"notes\": " + JsonList(out.Notes) + "}";
    if (report)
      *report = Returned.c_str();
  });
}

int schlieren_cell_fields(
  const char* settings, const char* arrays, const char* present, const char** report)
{
  if (report)
    *report = "";
  return Guard(LastError, [&] {
    const char* f = "schlieren_cell_fields";
    static const char* const roles[] = { "InputArray", "TemperatureArray", "PressureArray",
      "MixtureFractionArray", "Species1Array", "Species2Array", "Species3Array", "Species4Array",
      "HumidityArray", "CO2Array" };
    std::vector<std::string> known = ModelSettingNames();
    known.insert(known.end(), std::begin(roles), std::end(roles));
    known.emplace_back("HumidityFromArray");
    known.emplace_back("CO2FromArray");
    const std::map<std::string, std::string> p = SettingLines(f, settings, known);
    auto flag = [&](const char* name) {
      const auto it = p.find(name);
      return it != p.end() && NumbersOf(name, it->second, 1)[0] != 0.0;
    };
    std::vector<std::string> names;
    for (int r : schlieren::NeededRoles(ModelOfSettings(p), flag("HumidityFromArray"),
           flag("CO2FromArray")))
    {
      const auto it = p.find(roles[r]);
      if (it != p.end() && !it->second.empty())
        names.push_back(it->second);
    }
    std::vector<schlieren::ArrayPlace> read(names.size());
    for (std::size_t i = 0; i < names.size(); ++i)
      read[i].Name = names[i];
    for (const std::string& line : Lines(arrays))
    {
      const std::size_t a = line.find('\t'), b = line.find('\t', a == std::string::npos ? a : a + 1);
      const std::string where = a == std::string::npos ? std::string() :
        line.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1);
      if (where != "point" && where != "cell")
        throw schlieren::Error(std::string(f) + ": the arrays line '" + line +
          "' is not \"name<TAB>point|cell<TAB>type\".");
      const std::string name = line.substr(0, a);
      const std::string type = b == std::string::npos ? std::string() : line.substr(b + 1);
      for (schlieren::ArrayPlace& r : read)
      {
        if (r.Name != name)
          continue;
        (where == "cell" ? r.InCells : r.InPoints) = true;
        if (type != "float" && type != "double")
        {
          r.Integral = true;
          r.Type = type;
        }
      }
    }
    std::vector<std::string> fromCells;
    std::string note;
    const std::string problem = schlieren::CellOnlyFields(read, Lines(present), fromCells, note);
    if (!problem.empty())
      throw schlieren::Error(problem);
    Returned = "{\"from_cells\": " + JsonList(fromCells) + ", \"note\": " + Json(note) + "}";
    if (report)
      *report = Returned.c_str();
  });
}

int schlieren_wall_faces(int64_t faces, const int64_t* offsets, int64_t offsets_count,
  const int64_t* connectivity, int64_t connectivity_count, int64_t points, const double* normals,
  int64_t normals_count, const double* velocity, int64_t velocity_count, double largest_speed,
  int ignore_axis, const char* velocity_name, unsigned char* kinds, int64_t kinds_count,
  const char** report)
{
  if (report)
    *report = "";
  return Guard(LastError, [&] {
    const char* f = "schlieren_wall_faces";
    if (faces < 0 || points < 0)
      throw schlieren::Error(std::string(f) + ": faces is " + std::to_string(faces) +
        " and points " + std::to_string(points) + ": counts (>= 0).");
    const std::string per = std::to_string(faces) + " faces";
    CheckArray(f, "offsets", offsets, offsets_count, faces + 1, per + " (one more than the faces)", false);
    CheckArray(f, "normals", normals, normals_count, 3 * faces, per + " (3 a face)", false);
    CheckArray(f, "velocity", velocity, velocity_count, 3 * faces, per + " (3 a face)", false);
    CheckArray(f, "kinds", kinds, kinds_count, faces, per, false, "bytes");
    if (offsets[0] != 0)
      throw schlieren::Error(std::string(f) + ": offsets[0] is " + std::to_string(offsets[0]) + ": 0.");
    for (int64_t i = 0; i < faces; ++i)
      if (offsets[i + 1] < offsets[i])
        throw schlieren::Error(std::string(f) + ": offsets decrease at face " + std::to_string(i) + ".");
    CheckArray(f, "connectivity", connectivity, connectivity_count, offsets[faces],
      "offsets[faces]", offsets[faces] == 0);
    for (int64_t k = 0; k < connectivity_count; ++k)
      if (connectivity[k] < 0 || connectivity[k] >= points)
        throw schlieren::Error(std::string(f) + ": connectivity[" + std::to_string(k) + "] is " +
          std::to_string(connectivity[k]) + ": a point index below " + std::to_string(points) + ".");
    if (!std::isfinite(largest_speed) || ignore_axis < -1 || ignore_axis > 2)
      throw schlieren::Error(std::string(f) + ": largest_speed must be finite and ignore_axis -1, "
                                              "0, 1 or 2.");
    schlieren::walls::RimReport r;
    r.Velocity = velocity_name ? velocity_name : "U";
    const std::vector<unsigned char> k = schlieren::walls::ClassifyFaces(
      static_cast<std::size_t>(faces), offsets, connectivity, static_cast<std::size_t>(points),
      normals, velocity, largest_speed, ignore_axis, r);
    std::copy(k.begin(), k.end(), kinds);
    Returned = "{\"velocity\": " + Json(r.Velocity) + ", \"wall_faces\": " +
      std::to_string(r.WallFaces) + ", \"flow_faces\": " + std::to_string(r.FlowFaces) +
      ", \"still_faces\": " + std::to_string(r.StillFaces) + ", \"turned_faces\": " +
      std::to_string(r.TurnedFaces) + "}";
    if (report)
      *report = Returned.c_str();
  });
}

int schlieren_extend_into_invalid(const int dims[3], const unsigned char* valid, int64_t count,
  float* n_minus_1, int64_t* filled)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_extend_into_invalid";
    const std::int64_t n = GridPoints(f, dims);
    CheckArray(f, "valid (and n_minus_1)", valid, count, n, "a grid of " + GridText(dims) + " points", false);
    if (!n_minus_1)
      throw schlieren::Error("schlieren_extend_into_invalid: n_minus_1 is NULL: it must hold `count` floats.");
    const std::size_t done = schlieren::ExtendIntoInvalid(dims, valid, n_minus_1);
    if (filled)
      *filled = static_cast<int64_t>(done);
  });
}

int schlieren_fill_ambient(const int dims[3], const unsigned char* valid, int64_t count_given,
  float* n_minus_1, const char* mode, double value, double* ambient, int64_t* filled)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_fill_ambient";
    const std::int64_t points = GridPoints(f, dims);
    CheckArray(f, "valid (and n_minus_1)", valid, count_given, points,
      "a grid of " + GridText(dims) + " points", false);
    if (!n_minus_1 || !mode)
      throw schlieren::Error("schlieren_fill_ambient: n_minus_1 and mode must be given.");
    const std::string m = mode;
    const std::size_t count = static_cast<std::size_t>(points);
    double used = std::numeric_limits<double>::quiet_NaN();
    std::size_t n = 0;
    if (m == "Extend")
      n = schlieren::ExtendIntoInvalid(dims, valid, n_minus_1);
    else if (m == "DomainEdgeMedian" || m == "Value")
    {
      used = value;
      if (m == "DomainEdgeMedian")
      {
        // the RefractiveIndex filter's: the median of n - 1 at the flow domain's edge, else (no
        // valid point touches an invalid one) of every valid point
        std::vector<float> edge;
        schlieren::CollectDomainEdge(dims, valid, n_minus_1, nullptr, edge);
        used = schlieren::Median(edge);
        if (!std::isfinite(used))
        {
          std::vector<float> values;
          for (std::size_t i = 0; i < count; ++i)
            if (valid[i])
              values.push_back(n_minus_1[i]);
          used = schlieren::Median(values);
        }
      }
      n = schlieren::FillInvalid(count, valid, used, n_minus_1);
    }
    else
      throw schlieren::Error("AmbientMode '" + m + "' is not one of: Extend, DomainEdgeMedian, Value.");
    if (ambient)
      *ambient = used;
    if (filled)
      *filled = static_cast<int64_t>(n);
  });
}

int schlieren_enclosed_invalid(const int dims[3], const unsigned char* valid, int64_t count,
  const int wall_faces[6], unsigned char* solid, int64_t* solid_points)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_enclosed_invalid";
    const std::int64_t points = GridPoints(f, dims);
    CheckArray(f, "valid (and solid)", valid, count, points,
      "a grid of " + GridText(dims) + " points", false);
    if (!solid)
      throw schlieren::Error("schlieren_enclosed_invalid: solid is NULL: it must hold `count` bytes.");
    const std::size_t n = schlieren::EnclosedInvalidPoints(dims, valid, wall_faces, solid);
    if (solid_points)
      *solid_points = static_cast<int64_t>(n);
  });
}

int schlieren_automatic_dimensions(const double bounds[6], int longest, int dims[3])
{
  return Guard(LastError, [&] {
    if (!bounds || !dims)
      throw schlieren::Error("schlieren_automatic_dimensions: no argument may be NULL.");
    schlieren::AutomaticDimensions(bounds, longest, dims);
  });
}

namespace
{
/** schlieren_sample_cells' mesh and arrays (its checks, by argument), for `count` points each
 * output array holds (`what`: "a grid of ..." or "N points to sample"). */
struct SampleCall
{
  schlieren::SampleMesh Mesh;
  std::vector<schlieren::SampleArray> Arrays;
};

SampleCall SampleArguments(const char* f, const double* points, int64_t points_length,
  const int structured_dims[3], const unsigned char* cell_types, int64_t cell_types_length,
  const int64_t* offsets, int64_t offsets_length, const int64_t* connectivity,
  int64_t connectivity_length, const unsigned char* skip_cells, int64_t skip_cells_length,
  int number_of_arrays, const char* const* names, const int* is_cell, const int* components,
  const int* value_bytes, const void* const* inputs, const int64_t* input_lengths,
  void* const* outputs, const int64_t* output_lengths, std::int64_t count, const std::string& what)
{
  SampleCall call;
  schlieren::SampleMesh& mesh = call.Mesh;
  if (points_length < 0 || points_length % 3 != 0)
    throw schlieren::Error(std::string(f) + ": points holds " + std::to_string(points_length) +
      " values: give 3 per point (x, y, z).");
  CheckArray(f, "points", points, points_length, points_length, "the mesh", true);
  mesh.Points = points;
  mesh.NumberOfPoints = points_length / 3;
  if (structured_dims)
  {
    GridPoints(f, structured_dims);
    std::copy(structured_dims, structured_dims + 3, mesh.StructuredDims);
    CheckArray(f, "points", points, points_length, 3 * GridPoints(f, structured_dims),
      "a structured grid of " + GridText(structured_dims) + " points (3 each)", false);
    CheckArray(f, "cell_types", cell_types, cell_types_length, 0, "a structured grid", true);
    CheckArray(f, "offsets", offsets, offsets_length, 0, "a structured grid", true);
    CheckArray(f, "connectivity", connectivity, connectivity_length, 0, "a structured grid", true);
  }
  else
  {
    CheckArray(f, "cell_types", cell_types, cell_types_length, cell_types_length, "the mesh", true);
    CheckArray(f, "offsets", offsets, offsets_length, cell_types_length + 1,
      std::to_string(cell_types_length) + " cells", false);
    CheckArray(f, "connectivity", connectivity, connectivity_length, connectivity_length,
      "the mesh", true);
    mesh.CellTypes = cell_types;
    mesh.Offsets = offsets;
    mesh.Connectivity = connectivity;
    mesh.ConnectivityLength = connectivity_length;
    mesh.NumberOfCells = cell_types_length;
  }
  const std::int64_t cells = schlieren::SampleCellCount(mesh);
  CheckArray(f, "skip_cells", skip_cells, skip_cells_length, cells,
    "a mesh of " + std::to_string(cells) + " cells", true, "bytes");
  mesh.SkipCells = skip_cells;
  if (number_of_arrays < 0 || (number_of_arrays > 0 &&
      (!names || !is_cell || !components || !value_bytes || !inputs || !input_lengths ||
        !outputs || !output_lengths)))
    throw schlieren::Error(std::string(f) + ": number_of_arrays is " +
      std::to_string(number_of_arrays) + ": give names, is_cell, components, value_bytes, "
      "inputs, input_lengths, outputs and output_lengths, one entry per array.");
  std::vector<schlieren::SampleArray>& arrays = call.Arrays;
  arrays.resize(static_cast<std::size_t>(number_of_arrays));
  for (int i = 0; i < number_of_arrays; ++i)
  {
    schlieren::SampleArray& a = arrays[static_cast<std::size_t>(i)];
    a.Name = names[i] ? names[i] : "array " + std::to_string(i);
    a.Cells = is_cell[i] != 0;
    a.Components = components[i];
    a.ValueBytes = value_bytes[i];
    if (a.Components < 1 || a.Components > 1024)
      throw schlieren::Error(std::string(f) + ": array '" + a.Name + "' has " +
        std::to_string(a.Components) + " components (1 to 1024).");
    a.In = inputs[i];
    a.InValues = input_lengths[i];
    const std::string input = "array '" + a.Name + "' (input)";
    CheckArray(f, input.c_str(), a.In, a.InValues, (a.Cells ? cells : mesh.NumberOfPoints) * a.Components,
      std::to_string(a.Cells ? cells : mesh.NumberOfPoints) + (a.Cells ? " cells" : " points") +
        " x " + std::to_string(a.Components) + " components", false);
    const std::string out = "array '" + a.Name + "' (output)";
    CheckArray(f, out.c_str(), outputs[i], output_lengths[i], count * a.Components,
      what + " x " + std::to_string(a.Components) + " components", false);
    a.Out = outputs[i];
  }
  return call;
}
} // namespace

int schlieren_sample_cells(const double* points, int64_t points_length,
  const int structured_dims[3], const unsigned char* cell_types, int64_t cell_types_length,
  const int64_t* offsets, int64_t offsets_length, const int64_t* connectivity,
  int64_t connectivity_length, const unsigned char* skip_cells, int64_t skip_cells_length,
  int number_of_arrays, const char* const* names, const int* is_cell, const int* components,
  const int* value_bytes, const void* const* inputs, const int64_t* input_lengths,
  void* const* outputs, const int64_t* output_lengths, const int dims[3], const double origin[3],
  const double spacing[3], unsigned char* found, int64_t found_length, int64_t* found_here)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_sample_cells";
    const std::int64_t gridPoints = GridPoints(f, dims);
    CheckFinite3(f, "origin", origin);
    CheckFinite3(f, "spacing", spacing);
    CheckArray(f, "found", found, found_length, gridPoints, "a grid of " + GridText(dims) + " points",
      false, "bytes");
    const SampleCall call = SampleArguments(f, points, points_length, structured_dims, cell_types,
      cell_types_length, offsets, offsets_length, connectivity, connectivity_length, skip_cells,
      skip_cells_length, number_of_arrays, names, is_cell, components, value_bytes, inputs,
      input_lengths, outputs, output_lengths, gridPoints, "a grid of " + GridText(dims) + " points");
    schlieren::SampleGrid grid;
    std::copy(dims, dims + 3, grid.Dims);
    std::copy(origin, origin + 3, grid.Origin);
    std::copy(spacing, spacing + 3, grid.Spacing);
    const std::int64_t n = schlieren::SampleCells(call.Mesh, grid, call.Arrays, found);
    if (found_here)
      *found_here = static_cast<int64_t>(n);
  });
}

int schlieren_sample_cells_at(const double* points, int64_t points_length,
  const int structured_dims[3], const unsigned char* cell_types, int64_t cell_types_length,
  const int64_t* offsets, int64_t offsets_length, const int64_t* connectivity,
  int64_t connectivity_length, const unsigned char* skip_cells, int64_t skip_cells_length,
  int number_of_arrays, const char* const* names, const int* is_cell, const int* components,
  const int* value_bytes, const void* const* inputs, const int64_t* input_lengths,
  void* const* outputs, const int64_t* output_lengths, const double* at, int64_t at_length,
  unsigned char* found, int64_t found_length, int64_t* found_here)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_sample_cells_at";
    if (at_length < 0 || at_length % 3 != 0)
      throw schlieren::Error(std::string(f) + ": at holds " + std::to_string(at_length) +
        " values: give 3 per point to sample (x, y, z).");
    CheckArray(f, "at", at, at_length, at_length, "the points to sample", true);
    const std::int64_t count = at_length / 3;
    const std::string what = std::to_string(count) + " points to sample";
    CheckArray(f, "found", found, found_length, count, what, false, "bytes");
    const SampleCall call = SampleArguments(f, points, points_length, structured_dims, cell_types,
      cell_types_length, offsets, offsets_length, connectivity, connectivity_length, skip_cells,
      skip_cells_length, number_of_arrays, names, is_cell, components, value_bytes, inputs,
      input_lengths, outputs, output_lengths, count, what);
    const std::int64_t n = schlieren::SamplePoints(call.Mesh, at, count, call.Arrays, found);
    if (found_here)
      *found_here = static_cast<int64_t>(n);
  });
}

int schlieren_check_property(
  const char* proxy, const char* property, const double* values, int count)
{
  return Guard(LastError, [&] {
    if (!proxy || !property || (count > 0 && !values) || count < 0)
      throw schlieren::Error("schlieren_check_property: proxy and property must be names and "
                             "values must hold `count` (>= 0) numbers.");
    const std::string problem = schlieren::PropertyRangeProblem(proxy, property, values, count);
    if (!problem.empty())
      throw schlieren::Error(problem);
  });
}

int schlieren_check_memory(double bytes, const char* what, const char* hint)
{
  return Guard(LastError, [&] {
    if (!(bytes >= 0))
    {
      std::ostringstream msg;
      msg << "schlieren_check_memory: bytes is " << bytes << ": give a count of bytes (>= 0).";
      throw schlieren::Error(msg.str());
    }
    schlieren::CheckHostMemory(bytes, what ? what : "This", hint ? hint : "");
  });
}

int schlieren_mpi_options(double* timeout, int* abort_job)
{
  return Guard(LastError, [&] {
    const schlieren::RuntimeOptions options = schlieren::GetRuntimeOptions();
    if (timeout)
      *timeout = options.MpiTimeout;
    if (abort_job)
      *abort_job = options.MpiAbort ? 1 : 0;
  });
}

namespace
{
const std::vector<std::string> SamplingSettingNames = { "SamplingDimensions", "AutomaticDimension",
  "UseSamplingBounds", "SamplingBounds" };

void CheckExtent(const char* f, const char* name, const int* e)
{
  if (!e)
    throw schlieren::Error(std::string(f) + ": " + name + " is NULL: give 6 integers.");
}
} // namespace

int schlieren_sampling_box(const char* settings, const double input_bounds[6], double box[6])
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_sampling_box";
    if (!box)
      throw schlieren::Error(std::string(f) + ": box is NULL: give 6 doubles.");
    const schlieren::SamplingSettings s =
      SamplingSettingsOf(f, SettingLines(f, settings, SamplingSettingNames));
    schlieren::SamplingBox(s, input_bounds, box);
  });
}

int schlieren_sampling_grid(const char* settings, const double box[6], double array_bytes,
  const int amr_dims[3], int dims[3], double origin[3], double spacing[3])
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_sampling_grid";
    if (!box || !dims || !origin || !spacing)
      throw schlieren::Error(std::string(f) + ": box, dims, origin and spacing must be given.");
    if (!(array_bytes >= 0) || !std::isfinite(array_bytes))
      throw schlieren::Error(std::string(f) + ": array_bytes is " + Number(array_bytes) +
        ": give the bytes of the input's arrays per point (>= 0).");
    const schlieren::SamplingSettings s =
      SamplingSettingsOf(f, SettingLines(f, settings, SamplingSettingNames));
    if (amr_dims)
      GridPoints(f, amr_dims);
    const schlieren::SamplingGrid g = schlieren::PlanSamplingGrid(s, box, array_bytes,
      [amr_dims](const double*, int d[3]) {
        if (amr_dims)
          std::copy(amr_dims, amr_dims + 3, d);
        return amr_dims != nullptr;
      });
    GridPoints(f, g.Dims);
    std::copy(g.Dims, g.Dims + 3, dims);
    std::copy(g.Origin, g.Origin + 3, origin);
    std::copy(g.Spacing, g.Spacing + 3, spacing);
  });
}

int schlieren_follow_bounds(const int whole_extent[6], const double origin[3],
  const double spacing[3], const double input_bounds[6], int* moved, double new_origin[3],
  double new_spacing[3], const char** note)
{
  if (note)
    *note = "";
  return Guard(LastError, [&] {
    const char* f = "schlieren_follow_bounds";
    CheckExtent(f, "whole_extent", whole_extent);
    if (!input_bounds || !moved || !new_origin || !new_spacing)
      throw schlieren::Error(std::string(f) + ": input_bounds, moved, new_origin and new_spacing "
                                              "must be given.");
    CheckFinite3(f, "origin", origin);
    CheckFinite3(f, "spacing", spacing);
    for (int a = 0; a < 3; ++a)
      if (whole_extent[2 * a + 1] < whole_extent[2 * a])
        throw schlieren::Error(std::string(f) + ": whole_extent is empty along " +
          std::string(1, "xyz"[a]) + ".");
    for (int k = 0; k < 6; ++k)
      if (std::isnan(input_bounds[k]))
        throw schlieren::Error(std::string(f) + ": input_bounds[" + std::to_string(k) + "] is NaN.");
    schlieren::SamplingGrid g;
    std::copy(whole_extent, whole_extent + 6, g.Whole);
    std::copy(origin, origin + 3, g.Origin);
    std::copy(spacing, spacing + 3, g.Spacing);
    schlieren::SamplingGrid m;
    Returned.clear();
    *moved = schlieren::FollowBounds(g, input_bounds, m, &Returned) ? 1 : 0;
    std::copy(*moved ? m.Origin : origin, (*moved ? m.Origin : origin) + 3, new_origin);
    std::copy(*moved ? m.Spacing : spacing, (*moved ? m.Spacing : spacing) + 3, new_spacing);
    if (!*moved)
      Returned.clear();
    if (note)
      *note = Returned.c_str();
  });
}

int schlieren_input_request(int resampled, int symmetric, int rank, int ranks, int piece,
  int pieces, int ghosts, int split_mode, const int update_extent[6], const int whole_extent[6],
  int request[3], int extent[6])
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_input_request";
    if (!request || !extent)
      throw schlieren::Error(std::string(f) + ": request and extent must be given.");
    if (ranks < 1 || rank < 0 || rank >= ranks)
      throw schlieren::Error(std::string(f) + ": rank " + std::to_string(rank) + " of " +
        std::to_string(ranks) + ": give 0 <= rank < ranks.");
    if (pieces < 1 || piece < 0 || piece >= pieces)
      throw schlieren::Error(std::string(f) + ": piece " + std::to_string(piece) + " of " +
        std::to_string(pieces) + ": give 0 <= piece < pieces.");
    if (ghosts < 0 || split_mode < 0 || split_mode > 3)
      throw schlieren::Error(std::string(f) + ": ghosts " + std::to_string(ghosts) +
        ", split_mode " + std::to_string(split_mode) + ": give ghosts >= 0 and a split mode 0 "
        "(X slab), 1 (Y slab), 2 (Z slab) or 3 (block).");
    const int none[6] = { 0, -1, 0, -1, 0, -1 };
    const bool image = !resampled && !symmetric;
    if (image)
    {
      CheckExtent(f, "update_extent", update_extent);
      CheckExtent(f, "whole_extent", whole_extent);
      for (int k = 0; k < 6; ++k)
        if (update_extent[k] < -1000000000 || update_extent[k] > 1000000000 ||
          whole_extent[k] < -1000000000 || whole_extent[k] > 1000000000)
          throw schlieren::Error(std::string(f) + ": extents are within +/- 1e9.");
    }
    const schlieren::InputRequest r = schlieren::RequestInput(resampled != 0, symmetric != 0,
      rank, ranks, piece, pieces, ghosts, split_mode, image ? update_extent : none,
      image ? whole_extent : none);
    request[0] = r.Piece;
    request[1] = r.Pieces;
    request[2] = r.WholeExtent ? 1 : 0;
    std::copy(r.Extent, r.Extent + 6, extent);
  });
}

const char* schlieren_property_entries(const char* proxy, const char* property)
{
  static thread_local std::string entries;
  entries = "[";
  if (proxy && property)
    for (const schlieren::PropertyEntry& e : schlieren::PropertyEntries(proxy, property))
      entries += (entries.size() > 1 ? ", [" : "[") + std::to_string(e.Value) + ", " +
        Json(e.Text) + "]";
  entries += "]";
  return entries.c_str();
}

int schlieren_symmetry_plan(const char* settings, const double bounds[6], const double* points,
  int64_t points_count, int one_data_set, const int image_extent[6], const double image_origin[3],
  const double image_spacing[3], int dims[3], double origin[3], double spacing[3],
  double geometry[8], const char** report)
{
  if (report)
    *report = "";
  return Guard(LastError, [&] {
    const char* f = "schlieren_symmetry_plan";
    if (!settings || !dims || !origin || !spacing || !geometry)
      throw schlieren::Error(std::string(f) + ": settings, dims, origin, spacing and geometry "
                                              "must be given.");
    const auto p = SettingLines(f, settings, { "Symmetry", "SymmetryAxis", "Span",
      "AxisFromWedge", "SamplingDimensions", "AutomaticDimension", "UseSamplingBounds",
      "SamplingBounds" });
    auto text = [&](const char* name, const char* fallback) {
      const auto it = p.find(name);
      return it == p.end() ? std::string(fallback) : it->second;
    };
    schlieren::SymmetrySettings s;
    s.Symmetry = EntryOf("Symmetry", text("Symmetry", "None"), { "None", "Planar", "Axisymmetric" });
    s.SymmetryAxis = EntryOf("SymmetryAxis", text("SymmetryAxis", "X"), { "X", "Y", "Z" });
    s.Span = NumbersOf("Span", text("Span", "1"), 1)[0];
    s.AxisFromWedge = NumbersOf("AxisFromWedge", text("AxisFromWedge", "1"), 1)[0] != 0;
    const schlieren::SamplingSettings sampling = SamplingSettingsOf(f, p);
    std::copy(sampling.SamplingDimensions, sampling.SamplingDimensions + 3, s.SamplingDimensions);
    s.AutomaticDimension = sampling.AutomaticDimension;
    s.UseSamplingBounds = sampling.UseSamplingBounds;
    std::copy(sampling.SamplingBounds, sampling.SamplingBounds + 6, s.SamplingBounds);
    if (s.Symmetry == schlieren::SymmetryNone)
      throw schlieren::Error(std::string(f) + ": Symmetry is None: there is no symmetric grid to "
                                              "make (give Planar or Axisymmetric).");
    schlieren::SymmetryInput in;
    in.HasPoints = bounds != nullptr;
    if (bounds)
    {
      for (int k = 0; k < 6; ++k)
        if (!std::isfinite(bounds[k]))
          throw schlieren::Error(std::string(f) + ": bounds are not finite.");
      for (int a = 0; a < 3; ++a)
        if (!(bounds[2 * a] <= bounds[2 * a + 1]))
          throw schlieren::Error(std::string(f) + ": bounds " + Number(bounds[2 * a]) + " " +
            Number(bounds[2 * a + 1]) + ": each max must be at least its min.");
      std::copy(bounds, bounds + 6, in.Bounds);
    }
    if (points_count < 0 || points_count % 3 != 0 || (points_count > 0 && !points))
      throw schlieren::Error(std::string(f) + ": points holds " + std::to_string(points_count) +
        " values: give x, y, z for each point (a multiple of 3), or NULL and 0.");
    for (int64_t k = 0; k < points_count; ++k)
      if (!std::isfinite(points[k]))
        throw schlieren::Error(std::string(f) + ": points[" + std::to_string(k) + "] is not finite.");
    in.Points = points;
    in.Count = static_cast<std::size_t>(points_count / 3);
    in.OneDataSet = one_data_set != 0;
    in.Image = image_extent != nullptr;
    if (in.Image)
    {
      if (!image_origin || !image_spacing)
        throw schlieren::Error(std::string(f) + ": an image's extent needs its origin and spacing.");
      CheckFinite3(f, "image_origin", image_origin);
      CheckFinite3(f, "image_spacing", image_spacing);
      for (int a = 0; a < 3; ++a)
        if (image_extent[2 * a + 1] < image_extent[2 * a])
          throw schlieren::Error(std::string(f) + ": image_extent is empty along " +
            std::string(1, "xyz"[a]) + ".");
      std::copy(image_extent, image_extent + 6, in.ImageExtent);
      std::copy(image_origin, image_origin + 3, in.ImageOrigin);
      std::copy(image_spacing, image_spacing + 3, in.ImageSpacing);
    }
    schlieren::SymmetryPlan plan;
    const std::string problem = schlieren::PlanSymmetry(s, in, plan);
    if (!problem.empty())
      throw schlieren::Error(problem);
    GridPoints(f, plan.Dims);
    std::copy(plan.Dims, plan.Dims + 3, dims);
    std::copy(plan.Origin, plan.Origin + 3, origin);
    std::copy(plan.Spacing, plan.Spacing + 3, spacing);
    plan.Geometry(geometry);
    Returned.clear();
    if (!plan.WedgeNote.empty())
      Returned += "note: " + plan.WedgeNote + "\n";
    for (const std::string& w : plan.Warnings)
      Returned += "warning: " + w + "\n";
    if (report)
      *report = Returned.c_str();
  });
}

int schlieren_symmetry_to_mesh(const double geometry[8], const int dims[3],
  const double origin[3], const double spacing[3], const double* points, int64_t points_count,
  double* at, int64_t at_count)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_symmetry_to_mesh";
    if (!geometry)
      throw schlieren::Error(std::string(f) + ": geometry must be given.");
    GridPoints(f, dims);
    CheckFinite3(f, "origin", origin);
    CheckFinite3(f, "spacing", spacing);
    if (points_count < 0 || points_count % 3 != 0)
      throw schlieren::Error(std::string(f) + ": points holds " + std::to_string(points_count) +
        " values: give 3 per point (x, y, z).");
    CheckArray(f, "points", points, points_count, points_count, "the points", true);
    CheckArray(f, "at", at, at_count, points_count, "the points (3 a point)", points_count == 0);
    schlieren::SymmetryPlan plan;
    try
    {
      plan = schlieren::SymmetryPlan::FromGeometry(geometry, dims, origin, spacing);
    }
    catch (const schlieren::Error& e)
    {
      throw schlieren::Error(std::string(f) + ": " + e.what());
    }
    for (int64_t i = 0; i < points_count / 3; ++i)
      schlieren::SymmetryToMesh(plan, points + 3 * i, at + 3 * i);
  });
}

int schlieren_symmetry_samples(const double geometry[8], const int dims[3], const double origin[3],
  const double spacing[3], int64_t* samples, double* points, int64_t points_count,
  int64_t* sample_of, int64_t sample_of_count)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_symmetry_samples";
    if (!geometry || !samples)
      throw schlieren::Error(std::string(f) + ": geometry and samples must be given.");
    const std::int64_t n = GridPoints(f, dims);
    CheckFinite3(f, "origin", origin);
    CheckFinite3(f, "spacing", spacing);
    schlieren::SymmetryPlan plan;
    try
    {
      plan = schlieren::SymmetryPlan::FromGeometry(geometry, dims, origin, spacing);
    }
    catch (const schlieren::Error& e)
    {
      throw schlieren::Error(std::string(f) + ": " + e.what());
    }
    if (points)
      CheckArray(f, "sample_of", sample_of, sample_of_count, n, "a grid of " + GridText(dims) +
        " points", false);
    schlieren::CheckHostMemory(8.0 * n * (points ? 2 : 1), "Planning the symmetric samples",
      "Lower SamplingDimensions or AutomaticDimension.");
    std::vector<double> xyz;
    std::vector<std::int64_t> of;
    schlieren::SymmetrySamples(plan, xyz, of);
    *samples = static_cast<int64_t>(xyz.size() / 3);
    if (!points)
      return;
    CheckArray(f, "points", points, points_count, static_cast<std::int64_t>(xyz.size()),
      std::to_string(xyz.size() / 3) + " samples (3 values each)", false);
    std::copy(xyz.begin(), xyz.end(), points);
    std::copy(of.begin(), of.end(), sample_of);
  });
}

int schlieren_symmetry_expand(const int64_t* sample_of, int64_t count, int64_t samples,
  const float* values, int64_t values_count, int components, float* out, int64_t out_count,
  const unsigned char* sample_valid, int64_t sample_valid_count, unsigned char* valid,
  int64_t valid_count)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_symmetry_expand";
    if (count < 0 || samples < 0)
      throw schlieren::Error(std::string(f) + ": count and samples must be >= 0.");
    CheckArray(f, "sample_of", sample_of, count, count, "the grid", false);
    for (int64_t i = 0; i < count; ++i)
      if (sample_of[i] < 0 || sample_of[i] >= samples)
        throw schlieren::Error(std::string(f) + ": sample_of[" + std::to_string(i) + "] is " +
          std::to_string(sample_of[i]) + ": a sample's index (0 to " + std::to_string(samples - 1) +
          ") expected.");
    if (values || out || values_count || out_count)
    {
      if (components < 1 || components > 64)
        throw schlieren::Error(std::string(f) + ": components is " + std::to_string(components) +
          ": 1 to 64 floats a point.");
      if (samples > std::numeric_limits<int64_t>::max() / components ||
        count > std::numeric_limits<int64_t>::max() / components)
        throw schlieren::Error(std::string(f) + ": too many values.");
      CheckArray(f, "values", values, values_count, samples * components,
        std::to_string(samples) + " samples of " + std::to_string(components) + " components", false);
      CheckArray(f, "out", out, out_count, count * components,
        std::to_string(count) + " grid points of " + std::to_string(components) + " components", false);
      schlieren::ExpandSamples(sample_of, static_cast<std::size_t>(count), values, components, out);
    }
    if (sample_valid || valid || sample_valid_count || valid_count)
    {
      CheckArray(f, "sample_valid", sample_valid, sample_valid_count, samples,
        std::to_string(samples) + " samples", false);
      CheckArray(f, "valid", valid, valid_count, count, "the grid", false);
      schlieren::ExpandValidity(sample_of, static_cast<std::size_t>(count), sample_valid, valid);
    }
  });
}

int schlieren_wedge_warning(const double bounds[6], const double* points, int64_t points_count,
  int* thin, const char** warning)
{
  if (warning)
    *warning = "";
  if (thin)
    *thin = 0;
  return Guard(LastError, [&] {
    const char* f = "schlieren_wedge_warning";
    if (!bounds || !warning)
      throw schlieren::Error(std::string(f) + ": bounds and warning must be given.");
    for (int k = 0; k < 6; ++k)
      if (!std::isfinite(bounds[k]))
        throw schlieren::Error(std::string(f) + ": bounds are not finite.");
    if (points_count < 0 || points_count % 3 != 0 || (points_count > 0 && !points))
      throw schlieren::Error(std::string(f) + ": points holds " + std::to_string(points_count) +
        " values: give x, y, z for each point (a multiple of 3), or NULL and 0.");
    for (int64_t k = 0; k < points_count; ++k)
      if (!std::isfinite(points[k]))
        throw schlieren::Error(std::string(f) + ": points[" + std::to_string(k) + "] is not finite.");
    const bool may = schlieren::MayBeWedge(bounds);
    if (thin)
      *thin = may ? 1 : 0;
    Returned = may
      ? schlieren::WedgeWithoutSymmetry(points, static_cast<std::size_t>(points_count / 3))
      : std::string();
    *warning = Returned.c_str();
  });
}

namespace
{
/** The AMR boxes of schlieren_amr_grid and schlieren_amr_sample, checked (schlieren_c.h). */
std::vector<schlieren::AMRBlock> AMRBlocks(const char* f, int levels, int number_of_blocks,
  const int* block_levels, const int* block_extents, const double* block_origins,
  const double* block_spacings)
{
  if (levels < 0 || levels > 1024)
    throw schlieren::Error(std::string(f) + ": levels is " + std::to_string(levels) +
      ": an AMR lists 0 to 1024 levels.");
  if (number_of_blocks < 0 || (number_of_blocks > 0 &&
      (!block_levels || !block_extents || !block_origins || !block_spacings)))
    throw schlieren::Error(std::string(f) + ": number_of_blocks is " +
      std::to_string(number_of_blocks) + ": give block_levels, block_extents, block_origins and "
      "block_spacings for each (or 0).");
  std::vector<schlieren::AMRBlock> blocks(static_cast<std::size_t>(number_of_blocks));
  for (int b = 0; b < number_of_blocks; ++b)
  {
    schlieren::AMRBlock& block = blocks[static_cast<std::size_t>(b)];
    const std::string which = std::string(f) + ": block " + std::to_string(b);
    block.Level = block_levels[b];
    if (block.Level < 0 || block.Level >= levels)
      throw schlieren::Error(which + " is on level " + std::to_string(block.Level) +
        ": the levels are 0 to " + std::to_string(levels - 1) + ".");
    std::copy(block_extents + 6 * b, block_extents + 6 * b + 6, block.Extent);
    std::copy(block_origins + 3 * b, block_origins + 3 * b + 3, block.Origin);
    std::copy(block_spacings + 3 * b, block_spacings + 3 * b + 3, block.Spacing);
    CheckFinite3(f, (which + "'s origin").c_str(), block.Origin);
    CheckFinite3(f, (which + "'s spacing").c_str(), block.Spacing);
    for (int a = 0; a < 3; ++a)
    {
      if (!(block.Spacing[a] > 0.0))
        throw schlieren::Error(which + "'s spacing is not positive.");
      const double points = double(block.Extent[2 * a + 1]) - double(block.Extent[2 * a]) + 1.0;
      if (points > double(1 << 30) || std::fabs(double(block.Extent[2 * a])) > double(1 << 30) ||
        std::fabs(double(block.Extent[2 * a + 1])) > double(1 << 30))
        throw schlieren::Error(which + "'s extent reaches past 2^30 points along an axis.");
    }
  }
  return blocks;
}
} // namespace

int schlieren_amr_overlap(int number_of_boxes, const int* box_levels, const int* box_corners)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_amr_overlap";
    if (number_of_boxes < 0 || (number_of_boxes > 0 && (!box_levels || !box_corners)))
      throw schlieren::Error(std::string(f) + ": number_of_boxes is " +
        std::to_string(number_of_boxes) + ": give box_levels and box_corners for each (or 0).");
    std::vector<schlieren::AMRCellBox> boxes(static_cast<std::size_t>(number_of_boxes));
    for (int i = 0; i < number_of_boxes; ++i)
    {
      schlieren::AMRCellBox& box = boxes[static_cast<std::size_t>(i)];
      box.Level = box_levels[i];
      if (box.Level < 0 || box.Level > 1023)
        throw schlieren::Error(std::string(f) + ": box " + std::to_string(i) + " is on level " +
          std::to_string(box.Level) + ": the levels are 0 to 1023.");
      std::copy(box_corners + 6 * i, box_corners + 6 * i + 3, box.Lo);
      std::copy(box_corners + 6 * i + 3, box_corners + 6 * i + 6, box.Hi);
    }
    const std::string problem = schlieren::AMROverlapProblem(boxes);
    if (!problem.empty())
      throw schlieren::Error(problem);
  });
}

int schlieren_amr_grid(int levels, int number_of_blocks, const int* block_levels,
  const int* block_extents, const double* block_origins, const double* block_spacings,
  const double bounds[6], double bytes_per_point, int dims[3], double finest_spacing[3],
  int* finest_level, int* capped, const char** note)
{
  return schlieren_amr_grid_parallel(levels, number_of_blocks, block_levels, block_extents,
    block_origins, block_spacings, bounds, bytes_per_point, dims, finest_spacing, finest_level,
    capped, note, nullptr);
}

int schlieren_amr_grid_parallel(int levels, int number_of_blocks, const int* block_levels,
  const int* block_extents, const double* block_origins, const double* block_spacings,
  const double bounds[6], double bytes_per_point, int dims[3], double finest_spacing[3],
  int* finest_level, int* capped, const char** note, const schlieren_parallel* parallel)
{
  if (note)
    *note = "";
  return Guard(LastError, [&] {
    const char* f = parallel ? "schlieren_amr_grid_parallel" : "schlieren_amr_grid";
    std::unique_ptr<CallbackParallel> own;
    schlieren::Parallel& ranks = RanksOf(f, parallel, own);
    if (!bounds || !dims || !finest_spacing || !finest_level || !capped || !note)
      throw schlieren::Error(std::string(f) + ": bounds, dims, finest_spacing, finest_level, "
                                              "capped and note must be given.");
    const std::vector<schlieren::AMRBlock> blocks = AMRBlocks(
      f, levels, number_of_blocks, block_levels, block_extents, block_origins, block_spacings);
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(bounds[2 * a]) || !std::isfinite(bounds[2 * a + 1]) ||
        bounds[2 * a + 1] < bounds[2 * a])
        throw schlieren::Error(std::string(f) + ": bounds must be finite, each max at least its min.");
    if (!std::isfinite(bytes_per_point) || !(bytes_per_point > 0.0))
      throw schlieren::Error(std::string(f) + ": bytes_per_point must be positive.");
    bool cap = false;
    int levelsListed = 0;
    if (!schlieren::AMRDimensions(ranks, blocks, levels, bounds,
          bytes_per_point, dims, finest_spacing, cap, Returned))
      throw schlieren::Error(std::string(f) + ": no box holds data: the AMR input has nothing "
                                              "to sample.");
    schlieren::AMRFinestSpacing(ranks, blocks, levels, finest_spacing, *finest_level, levelsListed);
    *capped = cap ? 1 : 0;
    *note = Returned.c_str();
  });
}

namespace
{
thread_local schlieren::AMRSampled AMRReturned;
thread_local std::string AMRReport;
}

int schlieren_amr_sample(int levels, int number_of_blocks, const int* block_levels,
  const int* block_extents, const double* block_origins, const double* block_spacings,
  int number_of_arrays, const char* const* names, const int* is_cell, const int* components,
  const int* value_bytes, const void* const* inputs, const int64_t* input_lengths,
  const int dims[3], const double origin[3], const double spacing[3], int* out_components,
  const float** outputs, const unsigned char** valid, const char** report)
{
  return schlieren_amr_sample_parallel(levels, number_of_blocks, block_levels, block_extents,
    block_origins, block_spacings, number_of_arrays, names, is_cell, components, value_bytes,
    inputs, input_lengths, dims, origin, spacing, out_components, outputs, valid, report, nullptr);
}

int schlieren_amr_sample_parallel(int levels, int number_of_blocks, const int* block_levels,
  const int* block_extents, const double* block_origins, const double* block_spacings,
  int number_of_arrays, const char* const* names, const int* is_cell, const int* components,
  const int* value_bytes, const void* const* inputs, const int64_t* input_lengths,
  const int dims[3], const double origin[3], const double spacing[3], int* out_components,
  const float** outputs, const unsigned char** valid, const char** report,
  const schlieren_parallel* parallel)
{
  if (report)
    *report = "";
  if (valid)
    *valid = nullptr;
  return Guard(LastError, [&] {
    const char* f = parallel ? "schlieren_amr_sample_parallel" : "schlieren_amr_sample";
    std::unique_ptr<CallbackParallel> own;
    schlieren::Parallel& ranks = RanksOf(f, parallel, own);
    AMRReturned = schlieren::AMRSampled();
    std::vector<schlieren::AMRBlock> blocks = AMRBlocks(
      f, levels, number_of_blocks, block_levels, block_extents, block_origins, block_spacings);
    const std::int64_t gridPoints = GridPoints(f, dims);
    CheckFinite3(f, "origin", origin);
    CheckFinite3(f, "spacing", spacing);
    for (int a = 0; a < 3; ++a)
      if (!(spacing[a] > 0.0))
        throw schlieren::Error(std::string(f) + ": spacing must be positive.");
    if (!valid || !report || (number_of_arrays > 0 && (!out_components || !outputs)))
      throw schlieren::Error(std::string(f) + ": valid, report, out_components and outputs "
                                              "must be given.");
    if (number_of_arrays < 0 || number_of_arrays > 1024 || (number_of_arrays > 0 &&
        (!names || (number_of_blocks > 0 && (!is_cell || !components || !value_bytes ||
          !inputs || !input_lengths)))))
      throw schlieren::Error(std::string(f) + ": number_of_arrays is " +
        std::to_string(number_of_arrays) + ": give names (one per array) and is_cell, "
        "components, value_bytes, inputs and input_lengths (one per block and array), up to 1024 "
        "arrays.");
    std::vector<std::string> arrayNames;
    for (int k = 0; k < number_of_arrays; ++k)
      arrayNames.push_back(names[k] ? names[k] : "array " + std::to_string(k));
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
      schlieren::AMRBlock& block = blocks[b];
      for (int k = 0; k < number_of_arrays; ++k)
      {
        const std::size_t i = b * static_cast<std::size_t>(number_of_arrays) + k;
        schlieren::AMRArray a;
        const std::string what =
          "block " + std::to_string(b) + "'s array '" + arrayNames[static_cast<std::size_t>(k)] + "'";
        if (inputs[i] || input_lengths[i] != 0)
        {
          a.Cells = is_cell[i] != 0;
          a.Components = components[i];
          a.ValueBytes = value_bytes[i];
          if (a.Components < 1 || a.Components > 1024)
            throw schlieren::Error(std::string(f) + ": " + what + " has " +
              std::to_string(a.Components) + " components (1 to 1024).");
          if (a.ValueBytes != 4 && a.ValueBytes != 8)
            throw schlieren::Error(std::string(f) + ": " + what + " has " +
              std::to_string(a.ValueBytes) + " bytes a value: 4 (float) or 8 (double).");
          std::int64_t tuples = 1;
          for (int ax = 0; ax < 3; ++ax)
          {
            const std::int64_t np =
              std::max<std::int64_t>(0, std::int64_t(block.Extent[2 * ax + 1]) - block.Extent[2 * ax] + 1);
            tuples *= a.Cells ? std::max<std::int64_t>(np - 1, 1) : np;
            if (tuples > (std::int64_t(1) << 40))
              throw schlieren::Error(std::string(f) + ": " + what + ": the block has more than "
                                                                    "2^40 tuples.");
          }
          if (EmptyExtent(block.Extent))
            tuples = 0;
          CheckArray(f, what.c_str(), inputs[i], input_lengths[i], tuples * a.Components,
            std::to_string(tuples) + (a.Cells ? " cells" : " points") + " x " +
              std::to_string(a.Components) + " components",
            false);
          a.Values = inputs[i];
        }
        block.Arrays.push_back(a);
      }
    }
    double perPoint = 5.0; // the level of each point and its valid byte
    for (int k = 0; k < number_of_arrays; ++k)
    {
      int most = 0;
      for (std::size_t b = 0; b < blocks.size(); ++b)
        most = std::max(most, blocks[b].Arrays[static_cast<std::size_t>(k)].Components);
      perPoint += 4.0 * most;
    }
    schlieren::CheckHostMemory(double(gridPoints) * perPoint,
      "Sampling the AMR input onto " + GridText(dims) + " points", "Lower SamplingDimensions.");
    AMRReturned = schlieren::AMRResample(ranks, blocks, levels, dims,
      origin, spacing, arrayNames);
    for (int k = 0; k < number_of_arrays; ++k)
    {
      const std::size_t kk = static_cast<std::size_t>(k);
      out_components[k] = AMRReturned.Components[kk];
      outputs[k] = AMRReturned.Components[kk] ? AMRReturned.Values[kk].data() : nullptr;
    }
    *valid = AMRReturned.Valid.data();
    std::string lines;
    for (const std::string& n : AMRReturned.Notes)
      lines += "note: " + n + "\n";
    AMRReport = lines;
    *report = AMRReport.c_str();
  });
}

namespace
{
/** The entries of schlieren_time_cache_find and _insert, checked (schlieren_c.h). */
std::vector<schlieren::TimeStepKey> TimeCacheKeys(const char* f, int64_t count, const double* times,
  const uint64_t* tokens, const int* extents, const double* bytes, bool needBytes,
  std::vector<double>& sizes)
{
  if (count < 0 || count > (int64_t(1) << 20))
    throw schlieren::Error(std::string(f) + ": count is " + std::to_string(count) +
      ": the entries held (0 to 2^20).");
  if (count > 0 && (!times || !tokens || !extents || (needBytes && !bytes)))
    throw schlieren::Error(std::string(f) + ": count is " + std::to_string(count) +
      ": give times, tokens, extents" + (needBytes ? " and bytes" : "") + " for each entry.");
  std::vector<schlieren::TimeStepKey> keys(static_cast<std::size_t>(count));
  sizes.assign(static_cast<std::size_t>(count), 0.0);
  for (int64_t i = 0; i < count; ++i)
  {
    schlieren::TimeStepKey& k = keys[static_cast<std::size_t>(i)];
    k.Time = times[i];
    k.Token = tokens[i];
    std::copy(extents + 6 * i, extents + 6 * i + 6, k.Extent);
    if (!std::isfinite(k.Time))
      throw schlieren::Error(std::string(f) + ": times[" + std::to_string(i) + "] is not finite.");
    if (bytes)
    {
      sizes[static_cast<std::size_t>(i)] = bytes[i];
      if (!std::isfinite(bytes[i]) || bytes[i] < 0)
        throw schlieren::Error(std::string(f) + ": bytes[" + std::to_string(i) +
          "] is not a finite count >= 0.");
    }
  }
  return keys;
}

schlieren::TimeStepKey TimeCacheKey(const char* f, double time, uint64_t token, const int extent[6])
{
  if (!extent || !std::isfinite(time))
    throw schlieren::Error(std::string(f) + ": the key's time must be finite and its extent given.");
  schlieren::TimeStepKey k;
  k.Time = time;
  k.Token = token;
  std::copy(extent, extent + 6, k.Extent);
  return k;
}
} // namespace

int schlieren_time_cache_find(int64_t count, const double* times, const uint64_t* tokens,
  const int* extents, const double* bytes, double time, uint64_t token, const int extent[6],
  int64_t* index, double* budget)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_time_cache_find";
    if (!index)
      throw schlieren::Error(std::string(f) + ": index must be given.");
    std::vector<double> sizes;
    const auto keys = TimeCacheKeys(f, count, times, tokens, extents, bytes, false, sizes);
    *index = schlieren::FindTimeStep(keys, TimeCacheKey(f, time, token, extent));
    double held = 0.0;
    for (double b : sizes)
      held += b;
    if (budget)
      *budget = schlieren::TimeStepBudget(held);
  });
}

int schlieren_time_cache_insert(int64_t count, const double* times, const uint64_t* tokens,
  const int* extents, const double* bytes, double time, uint64_t token, const int extent[6],
  double new_bytes, unsigned char* keep, int* keep_new, double* budget)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_time_cache_insert";
    if (!keep_new || (count > 0 && !keep))
      throw schlieren::Error(std::string(f) + ": keep (count bytes) and keep_new must be given.");
    if (!std::isfinite(new_bytes) || new_bytes < 0)
      throw schlieren::Error(std::string(f) + ": new_bytes is not a finite count >= 0.");
    std::vector<double> sizes;
    const auto keys = TimeCacheKeys(f, count, times, tokens, extents, bytes, true, sizes);
    std::vector<unsigned char> flags;
    const bool kept = schlieren::PlanTimeStepInsert(
      keys, sizes, TimeCacheKey(f, time, token, extent), new_bytes, flags, budget);
    std::copy(flags.begin(), flags.end(), keep);
    *keep_new = kept ? 1 : 0;
  });
}

int schlieren_photograph(const char* settings, const int film_size[2], const double film_origin[2],
  double pixel_size, const float* film, int64_t film_count, const int photo_size[2], const float* photo,
  int64_t photo_count, int64_t capacity, float* registered, float* calibrated, float* difference,
  float* checkerboard, float* line_distance, const char** report)
{
  if (report)
    *report = "";
  return Guard(LastError, [&] {
    const char* f = "schlieren_photograph";
    if (!film_size || !photo_size || !film_origin)
      throw schlieren::Error(std::string(f) + ": " + (!film_size ? "film_size" : !photo_size ? "photo_size" : "film_origin") +
        " is NULL.");
    auto pixels = [&](const char* what, const int size[2]) {
      if (size[0] < 16 || size[1] < 16 || size[0] > 32768 || size[1] > 32768)
        throw schlieren::Error(std::string(f) + ": " + what + " is " + std::to_string(size[0]) + " x " +
          std::to_string(size[1]) + " pixels: 16 to 32768 a side are taken.");
      return static_cast<std::int64_t>(size[0]) * size[1];
    };
    const std::int64_t nf = pixels("the film", film_size), np = pixels("the photograph", photo_size);
    const std::string perf = "a film of " + std::to_string(film_size[0]) + " x " + std::to_string(film_size[1]) + " pixels";
    CheckArray(f, "film", film, film_count, nf, perf, false);
    CheckArray(f, "photo", photo, photo_count, np,
      "a photograph of " + std::to_string(photo_size[0]) + " x " + std::to_string(photo_size[1]) + " pixels", false);
    float* outs[5] = { registered, calibrated, difference, checkerboard, line_distance };
    bool any = false;
    for (float* o : outs)
      any = any || o;
    if (any)
      CheckArray(f, "capacity (the outputs' length)", outs[0] ? outs[0] : outs[1] ? outs[1] : outs[2] ? outs[2] : outs[3] ? outs[3] : outs[4],
        capacity, nf, perf, false, "floats");
    const schlieren::PhotographSettings ps = schlieren::ParsePhotographSettings(settings ? settings : "");
    const schlieren::PhotographResult r =
      schlieren::RegisterPhotograph(film_size, film_origin, pixel_size, film, photo_size, photo, ps);
    const std::vector<float>* from[5] = { &r.Registered, &r.Calibrated, &r.Difference, &r.Checkerboard, &r.LineDistance };
    for (int a = 0; a < 5; ++a)
      if (outs[a])
        std::copy(from[a]->begin(), from[a]->end(), outs[a]);
    Returned = r.Json();
    if (report)
      *report = Returned.c_str();
  });
}

int schlieren_photograph_grey(const double* values, int64_t count, int components, float* grey)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_photograph_grey";
    if (count < 0)
      throw schlieren::Error(std::string(f) + ": count is " + std::to_string(count) + ": a count of pixels (>= 0).");
    if (components < 1 || components > 4)
      throw schlieren::Error(std::string(f) + ": components is " + std::to_string(components) +
        ": 1 (grey), 2 (grey and alpha), 3 (RGB) or 4 (RGBA).");
    if (count > 0 && (!values || !grey))
      throw schlieren::Error(std::string(f) + ": " + (!values ? "values" : "grey") + " is NULL.");
    schlieren::PhotographGrey(values, static_cast<std::size_t>(count), components, grey);
  });
}

int schlieren_photograph_blend(double weight, const float* film, const float* difference, int64_t count, float* blend)
{
  return Guard(LastError, [&] {
    const char* f = "schlieren_photograph_blend";
    if (count < 0)
      throw schlieren::Error(std::string(f) + ": count is " + std::to_string(count) + ": a count of pixels (>= 0).");
    if (count > 0 && (!film || !difference || !blend))
      throw schlieren::Error(std::string(f) + ": " + (!film ? "film" : !difference ? "difference" : "blend") + " is NULL.");
    schlieren::PhotographBlend(weight, film, difference, static_cast<std::size_t>(count), blend);
  });
}

} // extern "C"
