// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenOpenCL.h"
#include "SchlierenEngine.h"
#include "SchlierenOptions.h"

#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <tuple>
#include <vector>

namespace schlieren
{
namespace ocl
{

const char* StatusName(cl_int s)
{
  switch (s)
  {
#define SCH_CASE(x)                                                                                \
  case x:                                                                                          \
    return #x;
    SCH_CASE(CL_SUCCESS)
    SCH_CASE(CL_DEVICE_NOT_FOUND)
    SCH_CASE(CL_DEVICE_NOT_AVAILABLE)
    SCH_CASE(CL_COMPILER_NOT_AVAILABLE)
    SCH_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    SCH_CASE(CL_OUT_OF_RESOURCES)
    SCH_CASE(CL_OUT_OF_HOST_MEMORY)
    SCH_CASE(CL_PROFILING_INFO_NOT_AVAILABLE)
    SCH_CASE(CL_MEM_COPY_OVERLAP)
    SCH_CASE(CL_IMAGE_FORMAT_MISMATCH)
    SCH_CASE(CL_IMAGE_FORMAT_NOT_SUPPORTED)
    SCH_CASE(CL_BUILD_PROGRAM_FAILURE)
    SCH_CASE(CL_MAP_FAILURE)
    SCH_CASE(CL_MISALIGNED_SUB_BUFFER_OFFSET)
    SCH_CASE(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
    SCH_CASE(CL_COMPILE_PROGRAM_FAILURE)
    SCH_CASE(CL_LINKER_NOT_AVAILABLE)
    SCH_CASE(CL_LINK_PROGRAM_FAILURE)
    SCH_CASE(CL_DEVICE_PARTITION_FAILED)
    SCH_CASE(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
    SCH_CASE(CL_INVALID_VALUE)
    SCH_CASE(CL_INVALID_DEVICE_TYPE)
    SCH_CASE(CL_INVALID_PLATFORM)
    SCH_CASE(CL_INVALID_DEVICE)
    SCH_CASE(CL_INVALID_CONTEXT)
    SCH_CASE(CL_INVALID_QUEUE_PROPERTIES)
    SCH_CASE(CL_INVALID_COMMAND_QUEUE)
    SCH_CASE(CL_INVALID_HOST_PTR)
    SCH_CASE(CL_INVALID_MEM_OBJECT)
    SCH_CASE(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
    SCH_CASE(CL_INVALID_IMAGE_SIZE)
    SCH_CASE(CL_INVALID_SAMPLER)
    SCH_CASE(CL_INVALID_BINARY)
    SCH_CASE(CL_INVALID_BUILD_OPTIONS)
    SCH_CASE(CL_INVALID_PROGRAM)
    SCH_CASE(CL_INVALID_PROGRAM_EXECUTABLE)
    SCH_CASE(CL_INVALID_KERNEL_NAME)
    SCH_CASE(CL_INVALID_KERNEL_DEFINITION)
    SCH_CASE(CL_INVALID_KERNEL)
    SCH_CASE(CL_INVALID_ARG_INDEX)
    SCH_CASE(CL_INVALID_ARG_VALUE)
    SCH_CASE(CL_INVALID_ARG_SIZE)
    SCH_CASE(CL_INVALID_KERNEL_ARGS)
    SCH_CASE(CL_INVALID_WORK_DIMENSION)
    SCH_CASE(CL_INVALID_WORK_GROUP_SIZE)
    SCH_CASE(CL_INVALID_WORK_ITEM_SIZE)
    SCH_CASE(CL_INVALID_GLOBAL_OFFSET)
    SCH_CASE(CL_INVALID_EVENT_WAIT_LIST)
    SCH_CASE(CL_INVALID_EVENT)
    SCH_CASE(CL_INVALID_OPERATION)
    SCH_CASE(CL_INVALID_GL_OBJECT)
    SCH_CASE(CL_INVALID_BUFFER_SIZE)
    SCH_CASE(CL_INVALID_MIP_LEVEL)
    SCH_CASE(CL_INVALID_GLOBAL_WORK_SIZE)
    SCH_CASE(CL_INVALID_PROPERTY)
#undef SCH_CASE
    case -1001:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return "unknown OpenCL status";
  }
}

void Check(cl_int status, const char* what)
{
  if (status != CL_SUCCESS)
  {
    std::ostringstream msg;
    msg << what << ": " << StatusName(status) << " (" << status << ")";
    throw Error(msg.str());
  }
}

namespace
{
// an OpenCL device that can build kernels
struct Candidate
{
  cl_platform_id P;
  cl_device_id D;
  cl_device_type T;
  std::string Name;
};

std::mutex gMutex;
// the devices (enumerated once; or why none can be used) and a runtime per device used
bool gEnumerated = false;
std::vector<Candidate> gDevices;
std::string gEnumerationError;
std::map<cl_device_id, std::unique_ptr<Runtime>> gRuntimes;
std::map<cl_device_id, std::string> gRuntimeErrors;

std::string DeviceString(cl_device_id d, cl_device_info what)
{
  std::size_t n = 0;
  if (clGetDeviceInfo(d, what, 0, nullptr, &n) != CL_SUCCESS || n == 0)
    return std::string();
  std::string s(n, '\0');
  clGetDeviceInfo(d, what, n, &s[0], nullptr);
  while (!s.empty() && s.back() == '\0')
    s.pop_back();
  return s;
}

std::string PlatformString(cl_platform_id p, cl_platform_info what)
{
  std::size_t n = 0;
  if (clGetPlatformInfo(p, what, 0, nullptr, &n) != CL_SUCCESS || n == 0)
    return std::string();
  std::string s(n, '\0');
  clGetPlatformInfo(p, what, n, &s[0], nullptr);
  while (!s.empty() && s.back() == '\0')
    s.pop_back();
  return s;
}

// Every available device with a compiler, on every platform.
std::vector<Candidate> EnumerateDevices()
{
  cl_uint np = 0;
  std::string noLoader;
  if (!LoadOpenCL(&noLoader))
    throw Error(noLoader);
  cl_int st = clGetPlatformIDs(0, nullptr, &np);
  if (st != CL_SUCCESS || np == 0)
  {
    std::ostringstream msg;
    msg << "No OpenCL platform found (" << StatusName(st)
        << "): install an OpenCL driver (on Debian: apt-get install pocl-opencl-icd) or choose "
           "Backend CPU.";
    throw Error(msg.str());
  }
  std::vector<cl_platform_id> platforms(np);
  Check(clGetPlatformIDs(np, platforms.data(), nullptr), "clGetPlatformIDs");

  std::vector<Candidate> all;
  for (cl_platform_id p : platforms)
  {
    cl_uint nd = 0;
    if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS || nd == 0)
      continue;
    std::vector<cl_device_id> devs(nd);
    clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, nd, devs.data(), nullptr);
    for (cl_device_id d : devs)
    {
      cl_device_type t = 0;
      clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof(t), &t, nullptr);
      cl_bool avail = CL_FALSE, comp = CL_FALSE;
      clGetDeviceInfo(d, CL_DEVICE_AVAILABLE, sizeof(avail), &avail, nullptr);
      clGetDeviceInfo(d, CL_DEVICE_COMPILER_AVAILABLE, sizeof(comp), &comp, nullptr);
      if (avail && comp)
        all.push_back({ p, d, t, DeviceString(d, CL_DEVICE_NAME) });
    }
  }
  if (all.empty())
    throw Error("OpenCL platforms exist but none has an available device with a compiler; choose "
                "Backend CPU.");
  return all;
}

// The device whose name contains `want` (from `source`, for the message), or with an empty
// `want` the first GPU, else the first device.
const Candidate& PickDevice(const std::vector<Candidate>& all, const std::string& want, const char* source)
{
  if (!want.empty())
  {
    for (const Candidate& c : all)
      if (c.Name.find(want) != std::string::npos)
        return c;
    std::ostringstream msg;
    msg << source << "='" << want << "' matches no OpenCL device; devices:";
    for (const Candidate& c : all)
      msg << " '" << c.Name << "'";
    msg << ". Give a part of one of these names, leave it empty for the default device, or choose "
           "Backend CPU.";
    throw Error(msg.str());
  }
  for (const Candidate& c : all)
    if (c.T & CL_DEVICE_TYPE_GPU)
      return c;
  return all.front();
}

std::unique_ptr<Runtime> CreateRuntime(const Candidate& pick)
{
  auto rt = std::make_unique<Runtime>();
  rt->Platform = pick.P;
  rt->Device = pick.D;
  rt->DeviceName = pick.Name;
  rt->PlatformName = PlatformString(pick.P, CL_PLATFORM_NAME);
  rt->Version = DeviceString(pick.D, CL_DEVICE_VERSION);
  cl_ulong v = 0;
  clGetDeviceInfo(pick.D, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof(v), &v, nullptr);
  rt->MaxAlloc = v;
  clGetDeviceInfo(pick.D, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof(v), &v, nullptr);
  rt->GlobalMemory = v;
  clGetDeviceInfo(pick.D, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof(rt->MaxWorkGroup), &rt->MaxWorkGroup, nullptr);
  cl_device_type type = 0;
  clGetDeviceInfo(pick.D, CL_DEVICE_TYPE, sizeof(type), &type, nullptr);
  rt->IsCPU = (type & CL_DEVICE_TYPE_CPU) != 0;
  cl_context_properties props[] = { CL_CONTEXT_PLATFORM,
    reinterpret_cast<cl_context_properties>(pick.P), 0 };
  cl_int err = CL_SUCCESS;
  rt->Context = clCreateContext(props, 1, &pick.D, nullptr, nullptr, &err);
  Check(err, "clCreateContext");
  rt->Queue = clCreateCommandQueue(rt->Context, pick.D, 0, &err);
  if (err != CL_SUCCESS)
    clReleaseContext(rt->Context);
  Check(err, "clCreateCommandQueue");
  return rt;
}

struct ProgramEntry
{
  cl_program Program = nullptr;
  std::string Error;
};
std::map<std::tuple<cl_device_id, std::string, std::size_t>, ProgramEntry> gPrograms;
std::vector<void (*)()> gReleaseHooks;

// Releases every OpenCL object the engine made when the process exits. Declared after the
// runtime and the program cache, so that it is destroyed before them (while they still exist).
struct RuntimeOwner
{
  ~RuntimeOwner() { ReleaseRuntime(); }
} gOwner;
} // namespace

void AtRelease(void (*hook)())
{
  std::lock_guard<std::mutex> lock(gMutex);
  gReleaseHooks.push_back(hook);
}

void ReleaseRuntime()
{
  std::vector<void (*)()> hooks;
  {
    std::lock_guard<std::mutex> lock(gMutex);
    hooks.swap(gReleaseHooks);
  }
  for (auto h : hooks)
    h();
  std::lock_guard<std::mutex> lock(gMutex);
  for (auto& p : gPrograms)
    if (p.second.Program)
      clReleaseProgram(p.second.Program);
  gPrograms.clear();
  for (auto& r : gRuntimes)
  {
    if (r.second->Queue)
    {
      clFinish(r.second->Queue);
      clReleaseCommandQueue(r.second->Queue);
    }
    if (r.second->Context)
      clReleaseContext(r.second->Context);
  }
  gRuntimes.clear();
}

Runtime& GetRuntime(const std::string& deviceName)
{
  const std::string want = deviceName.empty() ? GetRuntimeOptions().OpenCLDevice : deviceName;
  const char* source = deviceName.empty() ? "SCHLIEREN_OPENCL_DEVICE" : "DeviceName";
  std::lock_guard<std::mutex> lock(gMutex);
  if (!gEnumerated)
  {
    try
    {
      gDevices = EnumerateDevices();
    }
    catch (const Error& e)
    {
      gEnumerationError = e.what();
    }
    gEnumerated = true;
  }
  if (!gEnumerationError.empty())
    throw Error(gEnumerationError);
  const Candidate& pick = PickDevice(gDevices, want, source);
  auto it = gRuntimes.find(pick.D);
  if (it != gRuntimes.end())
    return *it->second;
  auto bad = gRuntimeErrors.find(pick.D);
  if (bad != gRuntimeErrors.end())
    throw Error(bad->second);
  try
  {
    return *(gRuntimes[pick.D] = CreateRuntime(pick));
  }
  catch (const Error& e)
  {
    gRuntimes.erase(pick.D);
    gRuntimeErrors[pick.D] = e.what();
    throw;
  }
}

cl_program GetProgram(const std::string& name, const std::string& source, const std::string& options)
{
  return GetProgram(GetRuntime(), name, source, options);
}

cl_program GetProgram(
  Runtime& rt, const std::string& name, const std::string& source, const std::string& options)
{
  std::lock_guard<std::mutex> lock(gMutex);
  auto key = std::make_tuple(rt.Device, options, std::hash<std::string>()(source));
  auto it = gPrograms.find(key);
  if (it != gPrograms.end())
  {
    if (!it->second.Error.empty())
      throw Error(it->second.Error);
    return it->second.Program;
  }
  ProgramEntry entry;
  const char* text = source.c_str();
  std::size_t len = source.size();
  cl_int err = CL_SUCCESS;
  cl_program prog = clCreateProgramWithSource(rt.Context, 1, &text, &len, &err);
  if (err == CL_SUCCESS)
    err = clBuildProgram(prog, 1, &rt.Device, options.c_str(), nullptr, nullptr);
  if (err != CL_SUCCESS)
  {
    std::string log;
    if (prog)
    {
      std::size_t n = 0;
      clGetProgramBuildInfo(prog, rt.Device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
      log.resize(n);
      if (n)
        clGetProgramBuildInfo(prog, rt.Device, CL_PROGRAM_BUILD_LOG, n, &log[0], nullptr);
      while (!log.empty() && log.back() == '\0')
        log.pop_back();
      clReleaseProgram(prog);
    }
    std::ostringstream msg;
    msg << "OpenCL kernel '" << name << "' failed to build on '" << rt.DeviceName
        << "': " << StatusName(err) << " (" << err << "), options '" << options
        << "'. Build log:\n"
        << (log.empty() ? std::string("(empty)") : log);
    entry.Error = msg.str();
    gPrograms[key] = entry;
    throw Error(entry.Error);
  }
  entry.Program = prog;
  gPrograms[key] = entry;
  return prog;
}

std::size_t ProgramsBuilt()
{
  std::lock_guard<std::mutex> lock(gMutex);
  return gPrograms.size();
}

} // namespace ocl
} // namespace schlieren
