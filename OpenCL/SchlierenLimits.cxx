// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenLimits.h"
#include "SchlierenOptions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>

#include <new>
#ifdef _WIN32
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <malloc.h>
#include <windows.h>
#else
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace schlieren
{

namespace
{
// A "Key: <number> kB" line of a /proc file, in bytes; 0 if absent.
std::uint64_t ProcKiB(const char* file, const char* key)
{
  std::FILE* f = std::fopen(file, "r");
  if (!f)
    return 0;
  char line[256];
  std::uint64_t value = 0;
  const std::size_t len = std::strlen(key);
  while (std::fgets(line, sizeof(line), f))
    if (std::strncmp(line, key, len) == 0 && line[len] == ':')
    {
      value = std::strtoull(line + len + 1, nullptr, 10) * 1024;
      break;
    }
  std::fclose(f);
  return value;
}

std::string Num(double v)
{
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// "<Property> is <value>: it must be <range>."
[[noreturn]] void OutOfRange(const char* property, double value, const std::string& range,
  const std::string& more = std::string())
{
  std::ostringstream msg;
  msg << property << " is " << Num(value) << ": it must be " << range << "." << more;
  throw Error(msg.str());
}

void CheckFinite(const char* property, const double* v, int n)
{
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i]))
    {
      std::ostringstream msg;
      msg << property << " has a non-finite component (" << Num(v[i]) << "): give finite numbers.";
      throw Error(msg.str());
    }
}
} // namespace

std::uint64_t PhysicalMemory()
{
#ifdef _WIN32
  MEMORYSTATUSEX m;
  m.dwLength = sizeof(m);
  return GlobalMemoryStatusEx(&m) ? std::uint64_t(m.ullTotalPhys) : 0;
#else
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  return pages > 0 && size > 0 ? std::uint64_t(pages) * std::uint64_t(size) : 0;
#endif
}

std::uint64_t AvailableMemory()
{
#ifdef _WIN32
  MEMORYSTATUSEX ms;
  ms.dwLength = sizeof(ms);
  std::uint64_t avail = GlobalMemoryStatusEx(&ms) ? std::uint64_t(ms.ullAvailPhys) : 0;
  const std::uint64_t mw = GetRuntimeOptions().MemoryLimit;
  return mw > 0 ? std::min(avail, mw) : avail;
#else
  std::uint64_t avail = ProcKiB("/proc/meminfo", "MemAvailable");
  if (avail == 0)
    avail = PhysicalMemory();
  struct rlimit lim;
  if (getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY)
  {
    const std::uint64_t used = ProcKiB("/proc/self/status", "VmSize");
    const std::uint64_t cap = std::uint64_t(lim.rlim_cur);
    avail = std::min(avail, cap > used ? cap - used : 0);
  }
  const std::uint64_t m = GetRuntimeOptions().MemoryLimit;
  if (m > 0)
    avail = std::min(avail, m);
  return avail;
#endif
}

std::string FormatBytes(double b)
{
  std::ostringstream s;
  s.precision(3);
  if (b >= 1024.0 * 1024 * 1024 * 1024)
    s << b / (1024.0 * 1024 * 1024 * 1024) << " TiB";
  else if (b >= 1024.0 * 1024 * 1024)
    s << b / (1024.0 * 1024 * 1024) << " GiB";
  else if (b >= 1024.0 * 1024)
    s << b / (1024.0 * 1024) << " MiB";
  else
    s << b / 1024.0 << " KiB";
  return s.str();
}

void CheckHostMemory(double bytes, const std::string& what, const std::string& hint)
{
  const double avail = double(AvailableMemory());
  if (std::isfinite(bytes) && bytes <= avail)
    return;
  std::ostringstream msg;
  msg << what << " needs " << FormatBytes(bytes) << " of memory; this machine has "
      << FormatBytes(avail) << " available (" << FormatBytes(double(PhysicalMemory()))
      << " installed). " << hint;
  throw Error(msg.str());
}

double FilmBytesPerPixel()
{
  // FilmSums: 12 double channels (96 B), kept by the filter for progressive passes, copied by
  // the filter and again by Finalize (which filters a copy: a 96 B channel of scratch), then the
  // image's float arrays (at most 1 + 2 + 1 + 3 + 1 + 2 = 10 floats) and the caller's copy of them
  return 3 * 96.0 + 8.0 + 2 * 40.0;
}

void CheckFilmMemory(const int size[2])
{
  std::ostringstream what;
  what << "A film of " << size[0] << " x " << size[1] << " pixels";
  CheckHostMemory(double(size[0]) * size[1] * FilmBytesPerPixel(), what.str(),
    "Lower Resolution (the film costs about " + std::to_string(int(FilmBytesPerPixel())) +
      " bytes per pixel).");
}

double VolumeBytesPerPoint()
{
  // the packed field (n - 1 and grad n as 4 floats), the octree levels, the filter's copy of n - 1
  return 16.0 + 1.0 + 4.0;
}

void* AllocatePages(std::size_t bytes)
{
  const std::size_t page = 4096, huge = std::size_t(2) << 20;
  const std::size_t align = bytes >= 2 * huge ? huge : page;
  const std::size_t size = (std::max(bytes, page) + align - 1) / align * align;
#ifdef _WIN32
  void* p = _aligned_malloc(size, align); // freed with FreePages (_aligned_free)
#else
  void* p = std::aligned_alloc(align, size);
#endif
  if (!p)
    throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // advice only: where the kernel has huge pages off (or none free) the pages stay 4 KiB; Linux
  // asks for this advice by default (transparent_hugepage/enabled = madvise)
  if (align == huge)
    madvise(p, size, MADV_HUGEPAGE);
#endif
  return p;
}

double MaxSourceOverF1()
{
  return 0.2; // docs/BENCH.md "Where the closed forms hold"
}

void FreePages(void* p)
{
#ifdef _WIN32
  _aligned_free(p);
#else
  std::free(p);
#endif
}

double MaxStepsAcross()
{
  return 4194304.0; // 2^22
}

namespace
{
struct Range
{
  const char* Proxy;
  const char* Name;
  double Min, Max;
  bool Boolean;
  const char* Note; // said after the range
};
const double inf = std::numeric_limits<double>::infinity();
const char* const reference = " (a reference value is positive: 1 for dimensional data)";
const Range Ranges[] = {
  { "RefractiveIndex", "GladstoneDaleConstant", 0, 1, false, "" },
  { "RefractiveIndex", "MolarMass", 0, 10, false, "" },
  { "RefractiveIndex", "NumberOfSpecies", 0, 4, false, "" },
  { "RefractiveIndex", "SpeciesGases", -1, 9, false, "" },
  { "RefractiveIndex", "SpeciesGladstoneDale", 0, inf, false, "" },
  { "RefractiveIndex", "SpeciesMolarMass", 0, inf, false, "" },
  { "RefractiveIndex", "BalanceGladstoneDale", 0, inf, false, "" },
  { "RefractiveIndex", "BalanceMolarMass", 0, inf, false, "" },
  { "RefractiveIndex", "DensityReference", 1e-12, inf, false, reference },
  { "RefractiveIndex", "TemperatureReference", 1e-12, inf, false, reference },
  { "RefractiveIndex", "PressureReference", 1e-12, inf, false, reference },
  { "RefractiveIndex", "PressureOffset", -inf, inf, false, "" },
  { "RefractiveIndex", "Humidity", 0, 1, false, "" },
  { "RefractiveIndex", "CO2", 0, 1e6, false, "" },
  { "RefractiveIndex", "Wavelength", 100, 20000, false, "" },
  { "RefractiveIndex", "Span", 0, inf, false, "" },
  { "RefractiveIndex", "SamplingDimensions", 0, 65536, false, "" },
  { "RefractiveIndex", "AutomaticDimension", 2, 4096, false, "" },
  { "RefractiveIndex", "BodyWallFaces", 0, 1, false, "" },
  { "RefractiveIndex", "PassthroughHoldsN", 0, 1, true, "" },
  { "RefractiveIndex", "HumidityFromArray", 0, 1, true, "" },
  { "RefractiveIndex", "CO2FromArray", 0, 1, true, "" },
  { "RefractiveIndex", "AxisFromWedge", 0, 1, true, "" },
  { "RefractiveIndex", "UseSamplingBounds", 0, 1, true, "" },
  { "RefractiveIndex", "BodyFromGrid", 0, 1, true, "" },
  { "RefractionOctree", "Tolerance", 0, 1, false,
    ": the largest spread of n - 1 (dimensionless) that a block may hold and still be skipped "
    "(air's n - 1 is about 3e-4, so useful values are far below 1; 0: automatic, 1e-4 of the "
    "field's range)" },
  { "RefractionOctree", "MaxLevel", 0, 10, false, "" },
};
} // namespace

std::string PropertyRangeProblem(
  const std::string& proxy, const std::string& property, const double* values, int count)
{
  for (const Range& r : Ranges)
  {
    if (proxy != r.Proxy || property != r.Name)
      continue;
    for (int i = 0; i < count; ++i)
    {
      const double v = values[i];
      if (v >= r.Min && v <= r.Max && std::isfinite(v))
        continue;
      std::ostringstream msg;
      msg << r.Name;
      if (count > 1)
        msg << "[" << i << "]";
      msg << " is " << v;
      if (r.Boolean)
        msg << ": it must be 0 (off) or 1 (on).";
      else
      {
        msg << ": it must be ";
        if (std::isinf(r.Min) && std::isinf(r.Max))
          msg << "a finite value";
        else
        {
          msg << "in [" << r.Min << ", ";
          if (std::isinf(r.Max))
            msg << "a finite value]";
          else
            msg << r.Max << "]";
        }
        msg << r.Note << ".";
      }
      return msg.str();
    }
    return std::string();
  }
  return std::string();
}

namespace
{
struct Enumeration
{
  const char* Proxy;
  const char* Name;
  std::vector<PropertyEntry> Entries;
};
/** RefractiveIndex's enumerations, their EnumerationDomains in Schlieren.xml, in the order the C++
 * filter checks them. */
const std::vector<Enumeration>& Enumerations()
{
  static const std::vector<PropertyEntry> gases = { { 0, "Air" }, { 1, "He" }, { 2, "N2" },
    { 3, "O2" }, { 4, "Ar" }, { 5, "CO2" }, { 6, "H2" }, { 7, "H2O" }, { 8, "CH4" }, { 9, "CO" } };
  auto with = [](std::vector<PropertyEntry> first, const std::vector<PropertyEntry>& rest) {
    first.insert(first.end(), rest.begin(), rest.end());
    return first;
  };
  static const std::vector<Enumeration> all = {
    { "RefractiveIndex", "Model",
      { { -1, "Automatic" }, { 0, "Passthrough" }, { 1, "GladstoneDale" },
        { 2, "GladstoneDaleMixture" }, { 3, "IdealGas" }, { 4, "Ciddor" } } },
    { "RefractiveIndex", "Gas", with({ { -1, "Custom" } }, gases) },
    { "RefractiveIndex", "MixtureComposition", { { 1, "MixtureFraction" }, { 2, "Species" } } },
    { "RefractiveIndex", "IdealGasComposition",
      { { 0, "Gas" }, { 1, "MixtureFraction" }, { 2, "Species" } } },
    { "RefractiveIndex", "MixtureGas0", gases },
    { "RefractiveIndex", "MixtureGas1", gases },
    { "RefractiveIndex", "BalanceGas", with({ { -2, "None" }, { -1, "Custom" } }, gases) },
    { "RefractiveIndex", "TemperatureUnit", { { 0, "Kelvin" }, { 1, "Celsius" } } },
    { "RefractiveIndex", "PressureUnit", { { 0, "Pa" }, { 1, "kPa" }, { 2, "atm" }, { 3, "bar" } } },
    { "RefractiveIndex", "HumidityMeasure",
      { { 0, "RelativeHumidity" }, { 1, "WaterMoleFraction" } } },
    { "RefractiveIndex", "Symmetry", { { 0, "None" }, { 1, "Planar" }, { 2, "Axisymmetric" } } },
    { "RefractiveIndex", "SymmetryAxis", { { 0, "X" }, { 1, "Y" }, { 2, "Z" } } },
    { "RefractiveIndex", "AmbientMode",
      { { 0, "Extend" }, { 1, "DomainEdgeMedian" }, { 2, "Value" } } },
  };
  return all;
}
} // namespace

std::string EnumerationProblem(
  const std::string& name, int value, const std::vector<PropertyEntry>& entries)
{
  std::string list;
  for (const PropertyEntry& e : entries)
  {
    if (e.Value == value)
      return std::string();
    list += (list.empty() ? "" : ", ") + std::string(e.Text) + " (" + std::to_string(e.Value) + ")";
  }
  return name + " is " + std::to_string(value) + ": it must be one of " + list + ".";
}

const std::vector<PropertyEntry>& PropertyEntries(
  const std::string& proxy, const std::string& property)
{
  static const std::vector<PropertyEntry> none;
  for (const Enumeration& e : Enumerations())
    if (proxy == e.Proxy && property == e.Name)
      return e.Entries;
  return none;
}

std::string PropertiesProblem(const std::string& proxy,
  const std::function<std::vector<double>(const std::string&)>& value)
{
  for (const Range& r : Ranges)
  {
    if (proxy != r.Proxy)
      continue;
    const std::vector<double> v = value(r.Name);
    const std::string problem =
      PropertyRangeProblem(proxy, r.Name, v.data(), static_cast<int>(v.size()));
    if (!problem.empty())
      return problem;
  }
  for (const Enumeration& e : Enumerations())
  {
    if (proxy != e.Proxy)
      continue;
    const std::vector<double> v = value(e.Name);
    if (v.empty())
      continue; // not given
    const std::string problem = EnumerationProblem(e.Name, static_cast<int>(v[0]), e.Entries);
    if (!problem.empty())
      return problem;
  }
  return std::string();
}

void CheckSettings(const TraceSettings& s)
{
  if (s.FieldStride != 1 && s.FieldStride != 2 && s.FieldStride != 4)
    throw Error("FieldStride is " + std::to_string(s.FieldStride) +
      ": it is 1 (the volume's points), 2 or 4 (Auto's certified copy); ResolveAuto sets it.");
  CheckFinite("ViewDirection", s.ViewDirection, 3);
  CheckFinite("ViewUp", s.ViewUp, 3);
  // a film one pixel wide is a line or a point, which ParaView cannot show as an image
  if (s.Resolution[0] < 2 || s.Resolution[1] < 2 || s.Resolution[0] > 16384 ||
    s.Resolution[1] > 16384)
  {
    std::ostringstream msg;
    msg << "Resolution is " << s.Resolution[0] << " x " << s.Resolution[1]
        << " pixels: each side must be 2 to 16384 pixels (at least 2 x 2).";
    throw Error(msg.str());
  }
  if (s.Passes < 1 || s.Passes > 1000000)
  {
    std::ostringstream msg;
    msg << "Passes is " << s.Passes << ": it must be at least 1 (and at most 1000000).";
    throw Error(msg.str());
  }
  if (!(s.StepSize >= 0.01 && s.StepSize <= 1000))
    OutOfRange("StepSize", s.StepSize, "in [0.01, 1000] voxels (of the smallest spacing)");
  if (!(s.Tolerance >= 0 && s.Tolerance <= 1))
    OutOfRange("Tolerance", s.Tolerance, "in [0, 1] radians (0: automatic, 1 % of the largest deflection)");
  if (!(s.CutoffScale >= 0 && s.CutoffScale <= 1e12))
    OutOfRange("CutoffScale", s.CutoffScale, "in [0, 1e12] (0: automatic)");
  // the SchlierenImage proxy's domain (Schlieren.xml), for every front end: outside it an
  // error, not a wrap
  if (!(s.KnifeAngle >= -180 && s.KnifeAngle <= 180))
    OutOfRange("KnifeAngle", s.KnifeAngle, "in [-180, 180] degrees");
  const int frame = static_cast<int>(s.Frame);
  if (frame < 0 || frame > static_cast<int>(Framing::Silhouette))
    OutOfRange("Framing", frame, "0 (Volume) or 1 (Silhouette)");
  for (double e : s.FilmExtent)
    if (!std::isfinite(e))
      OutOfRange("FilmExtent", e, "finite film coordinates (world units)");
  // the bench (checked whatever the source: a typed value is kept for when it is used)
  const int source = static_cast<int>(s.Source);
  if (source < 0 || source > static_cast<int>(BenchSource::Gaussian))
    OutOfRange("Source", source, "0 (Point), 1 (Slit), 2 (Rectangle), 3 (Disc) or 4 (Gaussian)");
  for (int i = 0; i < 2; ++i)
    if (!(s.SourceSize[i] >= 1e-3 && s.SourceSize[i] <= 1e4))
      OutOfRange(i == 0 ? "SourceSize[0] (across the knife)" : "SourceSize[1] (along the knife)",
        s.SourceSize[i], "in [0.001, 10000] mm");
  if (!(s.CollimatorFocalLength >= 1e-3 && s.CollimatorFocalLength <= 1e3))
    OutOfRange("CollimatorFocalLength", s.CollimatorFocalLength, "in [0.001, 1000] m");
  if (!(s.SchlierenFocalLength >= 1e-3 && s.SchlierenFocalLength <= 1e3))
    OutOfRange("SchlierenFocalLength", s.SchlierenFocalLength, "in [0.001, 1000] m");
  if (!(s.KnifeCut >= 0 && s.KnifeCut <= 0.999))
    OutOfRange("KnifeCut", s.KnifeCut, "in [0, 0.999]: the share of the source's image the knife "
      "covers (all of it would leave no light)");
  if (!(s.StopDiameter >= 0 && s.StopDiameter <= 1e4))
    OutOfRange("StopDiameter", s.StopDiameter, "in [0, 10000] mm (0: the idealised stops of Cutoff Scale)");
  if (s.StopDiameter > 0 &&
    (s.Mode == Cutoff::Circular || s.Mode == Cutoff::ComplementCircular || s.Mode == Cutoff::ColorFilter) &&
    (s.Source == BenchSource::Slit || s.Source == BenchSource::Rectangle))
    throw Error(std::string("A circular stop (StopDiameter ") + Num(s.StopDiameter) + " mm) takes a Point, "
      "Disc or Gaussian source, not a " + (s.Source == BenchSource::Slit ? "Slit" : "Rectangle") +
      ": a slit's image is cut by a knife (Cutoff KnifeEdge). Choose Source Disc (a pinhole) or set "
      "StopDiameter to 0.");
  // The bench's closed forms are paraxial: the source (height h at the collimator's focus)
  // subtends h / f1 rad, its image a0 = h f2 / f1 in the cutoff plane spans a0 / f2 = h / f1 rad
  // of deflection. They hold where tan(x) ~ x over half that angle: h / f1 <= 0.2 (a half-angle of
  // 0.1 rad, tan's relative error x^2 / 3 = 0.33 %); past it the film, the range and the
  // resolvable deflection are read outside the model (h / f1 = 1e4 gave a flat film and a
  // resolvable deflection of 39 rad). Checked only where the finite source is used.
  const bool stop = s.StopDiameter > 0 &&
    (s.Mode == Cutoff::Circular || s.Mode == Cutoff::ComplementCircular || s.Mode == Cutoff::ColorFilter);
  if (s.Source != BenchSource::Point && (s.Mode == Cutoff::KnifeEdge || stop) &&
    s.CollimatorFocalLength > 0 && !(s.SourceSize[0] * 1e-3 / s.CollimatorFocalLength <= MaxSourceOverF1()))
  {
    std::ostringstream msg;
    msg << "SourceSize " << Num(s.SourceSize[0]) << " mm (across the knife) at a CollimatorFocalLength of "
        << Num(s.CollimatorFocalLength) << " m subtends h/f1 = " << Num(s.SourceSize[0] * 1e-3 / s.CollimatorFocalLength)
        << " rad: the bench's closed forms assume a source small beside its mirror's focal length "
        << "(paraxial, h/f1 <= " << Num(MaxSourceOverF1()) << "; tan's error 0.33 % at its edge). "
        << "Give the source's size in mm and the focal length in m, or a smaller source (at most "
        << Num(MaxSourceOverF1() * s.CollimatorFocalLength * 1e3) << " mm here).";
    throw Error(msg.str());
  }
  if (s.BitDepth < 1 || s.BitDepth > 32)
    OutOfRange("BitDepth", s.BitDepth, "in [1, 32] bits");
  if (!(s.SaturationWarning >= 0 && s.SaturationWarning <= 1))
    OutOfRange("SaturationWarning", s.SaturationWarning, "in [0, 1] (a share of the lit film)");
  if (!(s.FilmDistance >= 0 && std::isfinite(s.FilmDistance)))
    OutOfRange("FilmDistance", s.FilmDistance, "a finite distance >= 0 (world units behind the volume)");
  if (!(s.Wavelength >= 100 && s.Wavelength <= 100000))
    OutOfRange("Wavelength", s.Wavelength, "in [100, 100000] nm");
  if (!(s.WavelengthRange[0] == 0 && s.WavelengthRange[1] == 0))
  {
    // a band: Ciddor's range where it is scaled by air's dispersion
    const bool air = s.Disperse == Dispersion::Air;
    const double lo = air ? 300 : 100, hi = air ? 1700 : 100000;
    if (!(s.WavelengthRange[0] >= lo && s.WavelengthRange[0] <= s.WavelengthRange[1] &&
          s.WavelengthRange[1] <= hi))
      throw Error("WavelengthRange is " + Num(s.WavelengthRange[0]) + " " + Num(s.WavelengthRange[1]) +
        ": it must be 0 0 (one wavelength) or a band l0 <= l1 in [" + Num(lo) + ", " + Num(hi) +
        "] nm" + (air ? " (Ciddor's range: Dispersion Air)" : "") + ".");
    if (air && !(s.Wavelength >= 300 && s.Wavelength <= 1700))
      OutOfRange("Wavelength", s.Wavelength, "in [300, 1700] nm with a band under Dispersion Air "
        "(n - 1 is scaled from it by Ciddor's index of air)");
  }
  if (s.WavelengthBins < 1 || s.WavelengthBins > 4096)
    OutOfRange("WavelengthBins", s.WavelengthBins, "in [1, 4096]");
  const int dispersion = static_cast<int>(s.Disperse);
  if (dispersion < 0 || dispersion > static_cast<int>(Dispersion::None))
    OutOfRange("Dispersion", dispersion, "0 (Air) or 1 (None)");
  if (!std::isfinite(s.ReferenceTilt))
    OutOfRange("ReferenceTilt", s.ReferenceTilt, "finite (fringes per world unit)");
  if (!(s.BackgroundDistance >= 0 && std::isfinite(s.BackgroundDistance)))
    OutOfRange("BackgroundDistance", s.BackgroundDistance, "a finite distance >= 0 (world units)");
  if (s.BackgroundPattern != 0 && s.BackgroundPattern != 1)
    OutOfRange("BackgroundPattern", s.BackgroundPattern, "0 (dots) or 1 (stripes)");
  const int pattern = static_cast<int>(s.Pattern);
  if (pattern < 0 || pattern > static_cast<int>(JitterPattern::Lattice))
    OutOfRange("JitterPattern", pattern, "0 (Random) or 1 (Lattice)");
  if (!(s.BackgroundPeriod >= 0 && std::isfinite(s.BackgroundPeriod)))
    OutOfRange("BackgroundPeriod", s.BackgroundPeriod, "a finite length >= 0 (0: 6 pixels)");
  // the camera (checked whatever Camera is: a typed value is kept for when it is used)
  const int camera = static_cast<int>(s.Camera);
  if (camera < 0 || camera > static_cast<int>(CameraModel::Lens))
    OutOfRange("Camera", camera, "0 (None), 1 (Ideal) or 2 (Lens)");
  if (!(s.CameraFocalLength >= 1e-3 && s.CameraFocalLength <= 1e3))
    OutOfRange("CameraFocalLength", s.CameraFocalLength, "in [0.001, 1000] m");
  if (!(s.FNumber >= 0.5 && s.FNumber <= 1000))
    OutOfRange("FNumber", s.FNumber, "in [0.5, 1000]");
  if (!(s.CameraDistance >= 1e-3 && s.CameraDistance <= 1e6))
    OutOfRange("CameraDistance", s.CameraDistance, "in [0.001, 1e6] m (the lens to the volume's centre)");
  if (!(s.FocusPlane >= -1e6 && s.FocusPlane <= 1e6))
    OutOfRange("FocusPlane", s.FocusPlane, "in [-1e6, 1e6] world units along the beam from the volume's centre");
  if (!(s.SourceGridDistance >= 1e-3 && s.SourceGridDistance <= 1e6))
    OutOfRange("SourceGridDistance", s.SourceGridDistance, "in [0.001, 1e6] m");
  if (s.Camera != CameraModel::None && !(s.CameraDistance - s.FocusPlane > s.CameraFocalLength))
  {
    std::ostringstream msg;
    msg << "CameraDistance " << s.CameraDistance << " m less FocusPlane " << s.FocusPlane
        << " (the lens to the plane it focuses on) must be more than CameraFocalLength "
        << s.CameraFocalLength << " m: a lens forms no real image of a plane within its focal length.";
    throw Error(msg.str());
  }
  if (!(s.FilterWidth >= 0.01 && s.FilterWidth <= 64))
    OutOfRange("FilterWidth", s.FilterWidth, "in [0.01, 64] pixels");
  if (s.MaxSteps < 0)
    OutOfRange("MaxSteps", s.MaxSteps, ">= 0 (0: automatic)");
  if (s.RaysPerWorkItem < 0 || s.RaysPerWorkItem > 64)
    OutOfRange("RaysPerWorkItem", s.RaysPerWorkItem, "in [0, 64] (0: automatic)");
  if (s.Threads < 0 || s.Threads > 4096)
    OutOfRange("Threads", s.Threads, "in [0, 4096] (0: the runtime options' choice, else every core)");
}

void CheckPrecision(const Volume& volume, const TraceSettings& s)
{
  // the box, from the grid itself (not from bounds, which lose the extent far from the origin)
  double h[3], hmax = 0, hmin = std::numeric_limits<double>::max(), smin = hmin;
  for (int a = 0; a < 3; ++a)
  {
    h[a] = 0.5 * (volume.Dimensions[a] - 1) * volume.Spacing[a];
    hmax = std::max(hmax, h[a]);
    hmin = std::min(hmin, h[a]);
    smin = std::min(smin, volume.Spacing[a]);
  }
  // positions in the tracer are floats relative to the volume's centre, of magnitude up to hmax:
  // an axis thinner than a few float steps at that magnitude cannot be told apart from a plane,
  // and 1 / spacing must be a float
  const double eps = std::numeric_limits<float>::epsilon(); // 2^-23
  const double ratio = hmax / hmin;
  if (!(hmin >= 8 * eps * hmax) || !(1.0 / smin < 1e30) || !(hmax < 1e30))
  {
    std::ostringstream msg;
    msg << "The volume is " << Num(2 * h[0]) << " x " << Num(2 * h[1]) << " x " << Num(2 * h[2])
        << " world units (spacing " << Num(volume.Spacing[0]) << ", " << Num(volume.Spacing[1])
        << ", " << Num(volume.Spacing[2]) << "): its longest side is " << Num(ratio)
        << " times its shortest, more than the float tracer can resolve (at most "
        << Num(1.0 / (8 * eps)) << "). Resample it with less extreme spacing, or scale the "
        << "thin axis (the physics of a sheet that thin is that of a plane).";
    throw Error(msg.str());
  }
  // the base step must move a float position by many of its units along the axis the beam
  // advances along fastest (positions are relative to the centre, at most the half-size there),
  // and a ray must cross the volume in a bounded number of steps
  const double step = s.StepSize * smin;
  const double across = 2 * std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]) / step;
  const double dlen = std::sqrt(s.ViewDirection[0] * s.ViewDirection[0] +
    s.ViewDirection[1] * s.ViewDirection[1] + s.ViewDirection[2] * s.ViewDirection[2]);
  double units = 0; // float units at the position's scale that one step moves it by, at most
  for (int a = 0; a < 3; ++a)
    if (dlen > 0)
      units = std::max(units, step * std::fabs(s.ViewDirection[a]) / dlen / (eps * h[a]));
  if (!(units >= 16) || !(across <= MaxStepsAcross()))
  {
    std::ostringstream msg;
    msg << "StepSize " << Num(s.StepSize) << " voxels is a step of " << Num(step)
        << " world units (of the smallest spacing, " << Num(smin) << ") in a volume of "
        << Num(2 * h[0]) << " x " << Num(2 * h[1]) << " x " << Num(2 * h[2]) << " world units";
    if (!(units >= 16))
      msg << ": along the beam that moves a float position by only " << Num(units)
          << " of its last-digit units (at least 16 are needed; below 1 the ray never advances)";
    else
      msg << ": a ray would need " << Num(across) << " steps to cross it (at most "
          << Num(MaxStepsAcross()) << ")";
    msg << ". Raise StepSize, view the volume along its thin axis, or resample it with a less "
        << "extreme spacing ratio (largest / smallest spacing here "
        << Num(std::max(volume.Spacing[0], std::max(volume.Spacing[1], volume.Spacing[2])) / smin)
        << ").";
    throw Error(msg.str());
  }
  // the film plane: beyond a million volume sizes a photon deflected by a micro-radian (far
  // weaker than any flow a schlieren system shows) moves by more than the film's width
  const double diag = 2 * std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  if (!(s.FilmDistance <= 1e6 * diag))
  {
    std::ostringstream msg;
    msg << "FilmDistance " << Num(s.FilmDistance) << " is more than 1e6 times the volume's size ("
        << Num(diag) << " world units): there a deflection of a micro-radian moves a photon by "
        << "more than the film's width, and the image would be blank. Use a distance of at most "
        << Num(1e6 * diag) << ".";
    throw Error(msg.str());
  }
  if (s.Mode == Cutoff::BOS && !(s.BackgroundDistance <= 1e6 * diag))
  {
    std::ostringstream msg;
    msg << "BackgroundDistance " << Num(s.BackgroundDistance)
        << " is more than 1e6 times the volume's size (" << Num(diag)
        << " world units). Use a distance of at most " << Num(1e6 * diag) << ".";
    throw Error(msg.str());
  }
  // the camera's focus plane is the film plane: the same reach as FilmDistance's
  if (s.Camera != CameraModel::None && !(std::fabs(s.FocusPlane) <= 1e6 * diag))
  {
    std::ostringstream msg;
    msg << "FocusPlane " << Num(s.FocusPlane) << " is more than 1e6 times the volume's size ("
        << Num(diag) << " world units) from its centre: there a deflection of a micro-radian moves a "
        << "photon by more than the film's width. Use a focus plane within " << Num(1e6 * diag) << ".";
    throw Error(msg.str());
  }
  if (s.Camera != CameraModel::None)
  {
    // the lens must be outside the test section: the volume's half-depth along the beam (its
    // box projected on ViewDirection) is where its last point toward the camera lies (issue 48:
    // CameraDistance 0.05 m in a 2 m box was traced)
    double depth = 0;
    for (int a = 0; a < 3; ++a)
      if (dlen > 0)
        depth += h[a] * std::fabs(s.ViewDirection[a]) / dlen;
    if (!(s.CameraDistance >= depth * (1 - 1e-6))) // at the box's face (the default camera of a unit box): outside
    {
      std::ostringstream msg;
      msg << "CameraDistance " << Num(s.CameraDistance) << " m puts the lens inside the volume: "
          << "the lens is that far from the volume's centre, and the volume reaches " << Num(depth)
          << " world units (m) toward it along the beam. The thin-lens camera is outside the test "
          << "section: set CameraDistance to at least " << Num(depth) << " m.";
      throw Error(msg.str());
    }
    // BOS's read-outs refer the background's shift to the volume's centre plane, imaged with
    // M_A = f / (Z_A - f): a centre at or within the focal length has no real image
    if (s.Mode == Cutoff::BOS && !(s.CameraDistance > s.CameraFocalLength))
    {
      std::ostringstream msg;
      msg << "Cutoff BOS with a camera: CameraDistance (Z_A, the lens to the volume's centre) "
          << Num(s.CameraDistance) << " m is not more than CameraFocalLength " << Num(s.CameraFocalLength)
          << " m. A volume at or within the focal length has no real image (M_A = f / (Z_A - f) = "
          << (s.CameraDistance == s.CameraFocalLength ? std::string("inf")
                                                       : Num(s.CameraFocalLength / (s.CameraDistance - s.CameraFocalLength)))
          << "), so the displacement and blur on the sensor (bos_pixels_per_radian, bos_blur_pixels) "
          << "would be meaningless. Move the camera beyond its focal length (CameraDistance > "
          << Num(s.CameraFocalLength) << " m) or use a shorter CameraFocalLength.";
      throw Error(msg.str());
    }
  }
}

} // namespace schlieren
