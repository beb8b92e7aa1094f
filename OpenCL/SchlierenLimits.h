// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenLimits.h
 * @brief What the machine and the float tracer can honour, checked before any work is done.
 *
 * Every allocation that a user's setting sizes (the packed volume, a resampling grid, a scene, the
 * film and its sums, device buffers) is checked here against the memory the machine can give
 * before it is made, and refused with a schlieren::Error that says how much it needs, how much is
 * available and what to change. The settings of a trace are checked against their documented
 * ranges (the message names the property, the value and the range), and the volume against the
 * resolution of the float tracer (a step that would not move a float position, an axis thinner
 * than float can tell apart). No VTK here.
 */
#ifndef SchlierenLimits_h
#define SchlierenLimits_h

#include "SchlierenEngine.h"

#include <cstdint>
#include <cstdlib>
#include <functional>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace schlieren
{

/** Bytes of RAM installed (sysconf(_SC_PHYS_PAGES) * page size). */
std::uint64_t PhysicalMemory();

/**
 * Bytes this process can still allocate: the smaller of MemAvailable (/proc/meminfo; the physical
 * memory where that is missing) and what the address-space limit (RLIMIT_AS, `ulimit -v`) leaves
 * above the process's current size. SCHLIEREN_MEMORY_LIMIT (bytes) lowers it further, for tests.
 */
std::uint64_t AvailableMemory();

/** "1.5 GiB", "340 MiB", "12 KiB": for messages. */
std::string FormatBytes(double bytes);

/**
 * Throws Error if `bytes` exceed AvailableMemory(): "<what> needs <bytes>; this machine has
 * <available> available (<physical> installed). <hint>". `bytes` is a double so that a product of
 * user-sized factors cannot overflow before it is checked.
 */
void CheckHostMemory(double bytes, const std::string& what, const std::string& hint);

/** Host bytes per film pixel that a trace and its image hold at their peak (the sums, their
 * filtered copy, the image arrays and the caller's copy of them). */
double FilmBytesPerPixel();

/** Throws Error if a film of size[0] x size[1] pixels (FilmBytesPerPixel each) does not fit. */
void CheckFilmMemory(const int size[2]);

/** Bytes per grid point that tracing holds on the host besides the caller's n - 1: the packed
 * field (4 floats), the octree levels and the index copy the filter makes. */
double VolumeBytesPerPoint();

/**
 * Checks every setting against its range; throws Error naming the property (the ParaView name),
 * the value and the valid range. Documented special values pass: CutoffScale 0 and Tolerance 0
 * (automatic), BackgroundPeriod 0 (6 pixels), MaxSteps 0 (automatic).
 */
void CheckSettings(const TraceSettings& settings);

/**
 * The ranges of the filters' numeric and boolean properties that every front end checks alike
 * (Plugin/Schlieren.xml's domains of RefractiveIndex and RefractionOctree; SchlierenImage's are
 * CheckSettings'): "" where each of the `count` values of `property` of `proxy` lies in its range,
 * or where no range is listed for it; else "Name is V: it must be in [min, max]." (an element's
 * index after the name where the property has several: "SamplingDimensions[1] is -1: ..."; a
 * boolean: "Name is V: it must be 0 (off) or 1 (on)."). NaN and infinities are out of every range.
 */
std::string PropertyRangeProblem(
  const std::string& proxy, const std::string& property, const double* values, int count);

/** An entry of an enumeration property (Schlieren.xml's EnumerationDomain): its value and text. */
struct PropertyEntry
{
  int Value;
  const char* Text;
};

/** "" where `value` is one of `entries`; else "Name is V: it must be one of A (0), B (1)." */
std::string EnumerationProblem(
  const std::string& name, int value, const std::vector<PropertyEntry>& entries);

/** The entries of the enumeration property `property` of the filter `proxy` ("RefractiveIndex"),
 * in the XML's order; empty where it is not an enumeration the engine lists. */
const std::vector<PropertyEntry>& PropertyEntries(
  const std::string& proxy, const std::string& property);

/**
 * The first problem of the filter `proxy`'s properties, the C++ filter's check before each request:
 * every numeric and boolean property of PropertyRangeProblem's table in its order, then every
 * enumeration of PropertyEntries in its order; `value(name)` gives the property's numbers (an
 * enumeration's: its value; none: not checked). "" where all are in range.
 */
std::string PropertiesProblem(const std::string& proxy,
  const std::function<std::vector<double>(const std::string&)>& value);

/**
 * Checks that the float tracer can honour the volume and settings: a base step that moves a float
 * position at the volume's scale, no more steps across the volume than a ray can take in
 * reasonable time, every axis resolvable next to the longest one (spacing ratios), and a film
 * plane at a finite, sane distance. Throws Error with the reason and what to change.
 */
void CheckPrecision(const Volume& volume, const TraceSettings& settings);

/**
 * Page-aligned memory for `bytes` (at least a page), freed with FreePages. Buffers of 4 MiB and
 * more are aligned to 2 MiB and asked for in transparent huge pages where Linux offers them on
 * request (madvise): a long step lands on a new 4 KiB page of the field at nearly every sample,
 * and each such page costs a walk of the page tables (in a VM, of two sets). Throws
 * std::bad_alloc.
 */
void* AllocatePages(std::size_t bytes);
/** Frees what AllocatePages returned (std::free; _aligned_free on Windows). */
void FreePages(void* p);

/**
 * Page-aligned storage (AllocatePages): a packed field held in it is used in place by a CPU
 * OpenCL device (CL_MEM_USE_HOST_PTR needs the device's base-address alignment) instead of being
 * copied.
 */
template <typename T>
struct PageAlignedAllocator
{
  using value_type = T;
  PageAlignedAllocator() = default;
  template <typename U>
  PageAlignedAllocator(const PageAlignedAllocator<U>&)
  {
  }
  T* allocate(std::size_t n) { return static_cast<T*>(AllocatePages(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) { FreePages(p); }
  // resize() leaves the new elements uninitialised: the packings write every one, and a zero
  // fill first would touch the memory twice, the first time (its page faults) on one thread
  template <typename U>
  void construct(U* p) noexcept
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  bool operator==(const PageAlignedAllocator<U>&) const
  {
    return true;
  }
  template <typename U>
  bool operator!=(const PageAlignedAllocator<U>&) const
  {
    return false;
  }
};
using AlignedFloats = std::vector<float, PageAlignedAllocator<float>>;
using AlignedBytes = std::vector<unsigned char, PageAlignedAllocator<unsigned char>>;

/** The most base steps a ray may need across the volume's diagonal (CheckPrecision refuses more). */
double MaxStepsAcross();

/** The largest source size over collimator focal length, h / f1, that the bench's paraxial closed
 * forms take (CheckSettings refuses more for a finite source in use; docs/BENCH.md). */
double MaxSourceOverF1();

} // namespace schlieren

#endif
