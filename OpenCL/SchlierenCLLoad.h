// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenCLLoad.h
 * @brief Internal: the OpenCL entry points the engine uses, taken from libOpenCL.so.1 at run time.
 *
 * The engine does not link an OpenCL loader: a library or program built from it loads and runs on
 * the CPU backend on a machine with no OpenCL at all. The first OpenCL call dlopen()s the ICD loader
 * (SCHLIEREN_OPENCL_LIBRARY if set, else libOpenCL.so.1, else libOpenCL.so) and resolves the
 * functions below; where that fails, every entry point returns CL_PLATFORM_NOT_FOUND_KHR and
 * LoadOpenCL says why. Included by SchlierenOpenCL.h after <CL/cl.h>: the macros send the engine's
 * cl* calls through the table, so the host code keeps the names of the OpenCL API.
 */
#ifndef SchlierenCLLoad_h
#define SchlierenCLLoad_h

#include <string>

namespace schlieren
{
namespace ocl
{

#define SCH_CL_FUNCTIONS(X)                                                                        \
  X(clBuildProgram)                                                                                \
  X(clCreateBuffer)                                                                                \
  X(clCreateCommandQueue)                                                                          \
  X(clCreateContext)                                                                               \
  X(clCreateKernel)                                                                                \
  X(clCreateProgramWithSource)                                                                     \
  X(clEnqueueNDRangeKernel)                                                                        \
  X(clEnqueueReadBuffer)                                                                           \
  X(clFinish)                                                                                      \
  X(clGetDeviceIDs)                                                                                \
  X(clGetDeviceInfo)                                                                               \
  X(clGetPlatformIDs)                                                                              \
  X(clGetPlatformInfo)                                                                             \
  X(clGetProgramBuildInfo)                                                                         \
  X(clReleaseCommandQueue)                                                                         \
  X(clReleaseContext)                                                                              \
  X(clReleaseKernel)                                                                               \
  X(clReleaseMemObject)                                                                            \
  X(clReleaseProgram)                                                                              \
  X(clSetKernelArg)

/** The entry points, resolved (or stubs that fail) on first use. */
struct Functions
{
#define SCH_CL_MEMBER(name) decltype(&::name) name##_;
  SCH_CL_FUNCTIONS(SCH_CL_MEMBER)
#undef SCH_CL_MEMBER
};

/** The table (loaded on the first call; thread-safe). */
const Functions& Api();

/**
 * Loads the OpenCL loader if it is not loaded yet. Returns false, with the reason in `why`
 * (the library tried and dlerror's text), where no OpenCL can be used.
 */
bool LoadOpenCL(std::string* why = nullptr);

} // namespace ocl
} // namespace schlieren

#ifndef SCH_CL_NO_REDIRECT
#define clBuildProgram (schlieren::ocl::Api().clBuildProgram_)
#define clCreateBuffer (schlieren::ocl::Api().clCreateBuffer_)
#define clCreateCommandQueue (schlieren::ocl::Api().clCreateCommandQueue_)
#define clCreateContext (schlieren::ocl::Api().clCreateContext_)
#define clCreateKernel (schlieren::ocl::Api().clCreateKernel_)
#define clCreateProgramWithSource (schlieren::ocl::Api().clCreateProgramWithSource_)
#define clEnqueueNDRangeKernel (schlieren::ocl::Api().clEnqueueNDRangeKernel_)
#define clEnqueueReadBuffer (schlieren::ocl::Api().clEnqueueReadBuffer_)
#define clFinish (schlieren::ocl::Api().clFinish_)
#define clGetDeviceIDs (schlieren::ocl::Api().clGetDeviceIDs_)
#define clGetDeviceInfo (schlieren::ocl::Api().clGetDeviceInfo_)
#define clGetPlatformIDs (schlieren::ocl::Api().clGetPlatformIDs_)
#define clGetPlatformInfo (schlieren::ocl::Api().clGetPlatformInfo_)
#define clGetProgramBuildInfo (schlieren::ocl::Api().clGetProgramBuildInfo_)
#define clReleaseCommandQueue (schlieren::ocl::Api().clReleaseCommandQueue_)
#define clReleaseContext (schlieren::ocl::Api().clReleaseContext_)
#define clReleaseKernel (schlieren::ocl::Api().clReleaseKernel_)
#define clReleaseMemObject (schlieren::ocl::Api().clReleaseMemObject_)
#define clReleaseProgram (schlieren::ocl::Api().clReleaseProgram_)
#define clSetKernelArg (schlieren::ocl::Api().clSetKernelArg_)
#endif

#endif
