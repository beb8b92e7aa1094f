// SPDX-License-Identifier: BSD-3-Clause
// Runtime options: the environment variables the engine reads, read once into one object.
#include "SchlierenOptions.h"
#include "SchlierenEngine.h"

#include <cerrno>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <sstream>

namespace schlieren
{

namespace
{
std::mutex gOptionsMutex;
std::unique_ptr<RuntimeOptions> gOptions;

// The variable's value, or null where it is unset or empty.
const char* Value(const char* name)
{
  const char* v = std::getenv(name);
  return v && *v ? v : nullptr;
}

[[noreturn]] void Bad(const char* name, const char* value, const char* what)
{
  std::ostringstream msg;
  msg << "The environment variable " << name << "='" << value << "' is not " << what
      << ": set it to such a value, or unset it for the default.";
  throw Error(msg.str());
}

std::uint64_t Unsigned(const char* name, const char* v, std::uint64_t max)
{
  char* end = nullptr;
  errno = 0;
  const unsigned long long n = std::strtoull(v, &end, 10);
  if (errno != 0 || end == v || *end != '\0' || v[0] == '-' || n > max)
    Bad(name, v, "a whole number of at least 0 in range");
  return n;
}

double Seconds(const char* name, const char* v)
{
  char* end = nullptr;
  errno = 0;
  const double s = std::strtod(v, &end);
  if (errno != 0 || end == v || *end != '\0' || !(s > 0.0) || !(s <= 1e7))
    Bad(name, v, "a number of seconds in (0, 1e7]");
  return s;
}

bool Flag(const char* name, const char* v)
{
  const std::string s(v);
  if (s == "0")
    return false;
  if (s == "1")
    return true;
  Bad(name, v, "0 or 1");
}
} // namespace

RuntimeOptions RuntimeOptions::FromEnvironment()
{
  RuntimeOptions o;
  if (const char* v = Value("SCHLIEREN_OPENCL_DEVICE"))
    o.OpenCLDevice = v;
  if (const char* v = Value("SCHLIEREN_CPU_THREADS"))
    o.CpuThreads = static_cast<int>(Unsigned("SCHLIEREN_CPU_THREADS", v, 4096));
  if (const char* v = Value("SCHLIEREN_CL_USE_HOST_PTR"))
    o.UseHostPtr = Flag("SCHLIEREN_CL_USE_HOST_PTR", v);
  if (const char* v = Value("SCHLIEREN_CL_SPECIALISE"))
    o.Specialise = Flag("SCHLIEREN_CL_SPECIALISE", v);
  if (const char* v = Value("SCHLIEREN_CL_OPTIONS"))
    o.BuildOptions = v;
  if (const char* v = Value("SCHLIEREN_CL_MAX_ALLOC"))
    o.MaxAlloc = Unsigned("SCHLIEREN_CL_MAX_ALLOC", v, ~std::uint64_t(0));
  if (const char* v = Value("SCHLIEREN_CL_LOCKSTEP"))
    o.Lockstep = Flag("SCHLIEREN_CL_LOCKSTEP", v) ? 1 : 0;
  if (const char* v = Value("SCHLIEREN_CL_LOCAL_SIZE"))
    o.LocalSize = static_cast<int>(Unsigned("SCHLIEREN_CL_LOCAL_SIZE", v, 4096));
  if (const char* v = Value("SCHLIEREN_FIELD_BRICKS"))
    o.Bricks = Flag("SCHLIEREN_FIELD_BRICKS", v) ? 1 : 0;
  if (const char* v = Value("SCHLIEREN_PREFETCH"))
    o.Prefetch = Flag("SCHLIEREN_PREFETCH", v) ? 1 : 0;
  if (const char* v = Value("SCHLIEREN_MEMORY_LIMIT"))
    o.MemoryLimit = Unsigned("SCHLIEREN_MEMORY_LIMIT", v, ~std::uint64_t(0));
  if (const char* v = Value("SCHLIEREN_MPI_TIMEOUT"))
    o.MpiTimeout = Seconds("SCHLIEREN_MPI_TIMEOUT", v);
  if (const char* v = Value("SCHLIEREN_MPI_ABORT"))
    o.MpiAbort = Flag("SCHLIEREN_MPI_ABORT", v);
  if (const char* v = Value("SCHLIEREN_COARSE"))
    o.CoarseCopies = Flag("SCHLIEREN_COARSE", v);
  return o;
}

std::string RuntimeOptions::OpenCLKey() const
{
  std::ostringstream k;
  k << OpenCLDevice << '\n' << UseHostPtr << ' ' << Specialise << ' ' << MaxAlloc << ' ' << Lockstep
    << ' ' << LocalSize << '\n' << BuildOptions;
  return k.str();
}

RuntimeOptions GetRuntimeOptions()
{
  std::lock_guard<std::mutex> lock(gOptionsMutex);
  if (!gOptions)
    gOptions = std::make_unique<RuntimeOptions>(RuntimeOptions::FromEnvironment());
  return *gOptions;
}

void SetRuntimeOptions(const RuntimeOptions& options)
{
  std::lock_guard<std::mutex> lock(gOptionsMutex);
  gOptions = std::make_unique<RuntimeOptions>(options);
}

void ResetRuntimeOptions()
{
  RuntimeOptions o = RuntimeOptions::FromEnvironment();
  std::lock_guard<std::mutex> lock(gOptionsMutex);
  gOptions = std::make_unique<RuntimeOptions>(o);
}

} // namespace schlieren
