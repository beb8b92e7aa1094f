// SPDX-License-Identifier: BSD-3-Clause
// The OpenCL loader opened at run time (see SchlierenCLLoad.h).
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>
#define SCH_CL_NO_REDIRECT
#include "SchlierenCLLoad.h"

#ifdef _WIN32
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
#else
#include <dlfcn.h>
#endif

#include <cstdlib>
#include <mutex>
#include <string>
#include <type_traits>

namespace schlieren
{
namespace ocl
{
namespace
{

constexpr cl_int NoPlatform = -1001; // CL_PLATFORM_NOT_FOUND_KHR

// Stubs for a process without OpenCL: each fails as a driver with no platform would. The
// functions that return an object set the error code argument where there is one.
cl_int StubPlatforms(cl_uint, cl_platform_id*, cl_uint* n)
{
  if (n)
    *n = 0;
  return NoPlatform;
}

template <typename F>
struct Stub;
template <typename R, typename... A>
struct Stub<R (*)(A...)>
{
  static R Call(A...)
  {
    if constexpr (std::is_pointer<R>::value)
      return nullptr;
    else
      return NoPlatform;
  }
};

void* SymbolOf(void* handle, const char* name)
{
#ifdef _WIN32
  return reinterpret_cast<void*>(GetProcAddress(static_cast<HMODULE>(handle), name));
#else
  return dlsym(handle, name);
#endif
}

struct Loaded
{
  Functions Table;
  std::string Why;
  bool Ok = false;
};

Loaded& Load()
{
  static Loaded loaded;
  static std::once_flag once;
  std::call_once(once, [] {
#define SCH_CL_STUB(name) loaded.Table.name##_ = &Stub<decltype(&::name)>::Call;
    SCH_CL_FUNCTIONS(SCH_CL_STUB)
#undef SCH_CL_STUB
    loaded.Table.clGetPlatformIDs_ = &StubPlatforms;
    const char* env = std::getenv("SCHLIEREN_OPENCL_LIBRARY");
#ifdef _WIN32
    // the ICD loader every Windows OpenCL driver installs in System32
    const char* names[] = { env && *env ? env : "OpenCL.dll", "OpenCL.dll" };
#else
    const char* names[] = { env && *env ? env : "libOpenCL.so.1", "libOpenCL.so" };
#endif
    void* handle = nullptr;
    std::string tried;
    for (const char* name : names)
    {
#ifdef _WIN32
      handle = reinterpret_cast<void*>(LoadLibraryA(name)); // stays loaded until the process ends
      if (handle)
        break;
      tried += std::string(tried.empty() ? "" : "; ") + name + ": Windows error " +
        std::to_string(static_cast<unsigned long>(GetLastError()));
#else
      // RTLD_NODELETE: the driver stays mapped until the process ends (its own exit handlers
      // run after the engine's, see ReleaseRuntime)
      handle = dlopen(name, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
      if (handle)
        break;
      const char* e = dlerror();
      tried += std::string(tried.empty() ? "" : "; ") + (e ? e : name);
#endif
      if (env && *env)
        break; // an explicit library: no fallback to another
    }
    if (!handle)
    {
      loaded.Why = "The OpenCL loader could not be opened (" + tried +
#ifdef _WIN32
        "): install your GPU's driver (it brings OpenCL.dll), set "
#else
        "): install one (on Debian: apt-get install ocl-icd-libopencl1 pocl-opencl-icd), set "
#endif
        "SCHLIEREN_OPENCL_LIBRARY to its path, or choose Backend CPU.";
      return;
    }
    Functions t = loaded.Table;
    std::string missing;
#define SCH_CL_RESOLVE(name)                                                                       \
  if (void* f = SymbolOf(handle, #name))                                                           \
    t.name##_ = reinterpret_cast<decltype(&::name)>(f);                                            \
  else                                                                                             \
    missing += std::string(missing.empty() ? "" : ", ") + #name;
    SCH_CL_FUNCTIONS(SCH_CL_RESOLVE)
#undef SCH_CL_RESOLVE
    if (!missing.empty())
    {
      loaded.Why = "The OpenCL loader " + std::string(names[0]) + " lacks " + missing +
        " (OpenCL 1.2 is needed): choose Backend CPU.";
      return; // the stubs stay: no half-loaded table
    }
    loaded.Table = t;
    loaded.Ok = true;
  });
  return loaded;
}

} // namespace

const Functions& Api()
{
  return Load().Table;
}

bool LoadOpenCL(std::string* why)
{
  Loaded& l = Load();
  if (why)
    *why = l.Why;
  return l.Ok;
}

} // namespace ocl
} // namespace schlieren
