// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenOpenCL.h
 * @brief Internal: the OpenCL device, context, queue and program cache of the engine.
 *
 * A runtime (context and queue) per device used, made on first use and kept for the life of the
 * process. Programs are cached per device, build options and source hash; a failed build is
 * cached too and reports the kernel name, status, options and the full build log.
 */
#ifndef SchlierenOpenCL_h
#define SchlierenOpenCL_h

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>
// the cl* entry points through the run-time loaded table
#include "SchlierenCLLoad.h"

#include <cstdint>
#include <string>

namespace schlieren
{
namespace ocl
{

/** The name of an OpenCL status code (CL_OUT_OF_RESOURCES, ...). */
const char* StatusName(cl_int status);

/** Throws schlieren::Error("<what>: <status name> (<code>)") if status is not CL_SUCCESS. */
void Check(cl_int status, const char* what);

struct Runtime
{
  cl_platform_id Platform = nullptr;
  cl_device_id Device = nullptr;
  cl_context Context = nullptr;
  cl_command_queue Queue = nullptr;
  std::string DeviceName, PlatformName, Version;
  std::uint64_t MaxAlloc = 0, GlobalMemory = 0;
  std::size_t MaxWorkGroup = 1;
  bool IsCPU = false; ///< CL_DEVICE_TYPE_CPU (PoCL here): lock-step rays vectorise there
};

/**
 * The runtime of the device whose name contains `deviceName`; empty: the runtime options' device
 * (SCHLIEREN_OPENCL_DEVICE), else the first GPU, else the first device. Created on first use;
 * throws schlieren::Error if no device can be used or none matches (listing the devices).
 */
Runtime& GetRuntime(const std::string& deviceName = std::string());

/** A built program (cached) on rt's device; throws schlieren::Error with the build log on failure. */
cl_program GetProgram(
  Runtime& rt, const std::string& name, const std::string& source, const std::string& options);
/** GetProgram on the default device (GetRuntime()). */
cl_program GetProgram(const std::string& name, const std::string& source, const std::string& options);
/** The programs GetProgram has built (or failed to build) in this process, on every device. */
std::size_t ProgramsBuilt();

/**
 * Registers a function that releases what its caller holds on the runtime's context (kernels,
 * buffers). At process exit the hooks run, then the cached programs, the queue and the context
 * are released (before the OpenCL driver's own teardown, which runs after every exit handler).
 */
void AtRelease(void (*hook)());

/** Runs the hooks and releases programs, queue and context now (process exit calls it). */
void ReleaseRuntime();

} // namespace ocl
} // namespace schlieren

#endif
