// SPDX-License-Identifier: BSD-3-Clause
// The runtime options (SchlierenOptions.h) and the per-trace settings that override them:
// - the environment is read once, at first use (ctest starts this test with SCHLIEREN_CPU_THREADS=3
//   and SCHLIEREN_CL_OPTIONS set), and a malformed value is an error naming the variable;
// - TraceSettings::Threads chooses the CPU backend's threads, and the film does not depend on
//   them (Threads 1, 2 and the environment's 3 give the same film, bit for bit: each ray is traced
//   alone and splatted in ray order);
// - TraceSettings::DeviceName chooses the OpenCL device: a name no device has is an Error under
//   Backend OpenCL and a CPU trace with a warning under Auto; a device's own name traces on it;
// - every build option is part of the kernel cache key: a kept volume traced again with another
//   SCHLIEREN_CL_OPTIONS builds its kernels again (an option the compiler refuses then fails,
//   where a cached kernel would have hidden it).
#include "SchlierenTesting.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

using namespace schlieren;
using schtest::ExpectError;

namespace
{
// The largest absolute difference between two films (+inf where their sizes differ).
double LargestDifference(const std::vector<float>& a, const std::vector<float>& b)
{
  if (a.size() != b.size() || a.empty())
    return INFINITY;
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    d = std::max(d, double(std::fabs(a[i] - b[i])));
  return d;
}

double LargestValue(const std::vector<float>& a)
{
  double m = 0;
  for (float v : a)
    m = std::max(m, double(std::fabs(v)));
  return m;
}
} // namespace

int main()
{
  // 1. The environment, read once. ctest sets the variables; run by hand, the test sets them
  // before the engine's first use.
  if (!std::getenv("SCHLIEREN_CPU_THREADS"))
    setenv("SCHLIEREN_CPU_THREADS", "3", 1);
  if (!std::getenv("SCHLIEREN_CL_OPTIONS"))
    setenv("SCHLIEREN_CL_OPTIONS", "-DSCHLIEREN_TEST_OPTION=1", 1);
  const RuntimeOptions first = GetRuntimeOptions();
  CHECK(first.CpuThreads == 3, "SCHLIEREN_CPU_THREADS=3 is read into CpuThreads");
  CHECK(first.BuildOptions == "-DSCHLIEREN_TEST_OPTION=1", "SCHLIEREN_CL_OPTIONS is read into BuildOptions");
  CHECK(first.Lockstep == -1 && first.UseHostPtr && first.Specialise && first.MaxAlloc == 0 &&
      first.MemoryLimit == 0 && first.OpenCLDevice.empty(),
    "unset variables leave the defaults");
  setenv("SCHLIEREN_CPU_THREADS", "5", 1);
  CHECK(GetRuntimeOptions().CpuThreads == 3, "the environment is read once: a later change is not seen");
  setenv("SCHLIEREN_CPU_THREADS", "three", 1);
  ExpectError("SCHLIEREN_CPU_THREADS=three", [] { RuntimeOptions::FromEnvironment(); },
    { "SCHLIEREN_CPU_THREADS", "'three'", "whole number" });
  setenv("SCHLIEREN_CL_LOCKSTEP", "yes", 1);
  setenv("SCHLIEREN_CPU_THREADS", "3", 1);
  ExpectError("SCHLIEREN_CL_LOCKSTEP=yes", [] { RuntimeOptions::FromEnvironment(); },
    { "SCHLIEREN_CL_LOCKSTEP", "0 or 1" });
  unsetenv("SCHLIEREN_CL_LOCKSTEP");
  CHECK(RuntimeOptions::FromEnvironment().LocalSize == -1, "SCHLIEREN_CL_LOCAL_SIZE unset: -1 (16 on CPUs)");
  setenv("SCHLIEREN_CL_LOCAL_SIZE", "0", 1);
  CHECK(RuntimeOptions::FromEnvironment().LocalSize == 0, "SCHLIEREN_CL_LOCAL_SIZE=0 is read");
  setenv("SCHLIEREN_CL_LOCAL_SIZE", "-16", 1);
  ExpectError("SCHLIEREN_CL_LOCAL_SIZE=-16", [] { RuntimeOptions::FromEnvironment(); },
    { "SCHLIEREN_CL_LOCAL_SIZE", "'-16'", "whole number" });
  unsetenv("SCHLIEREN_CL_LOCAL_SIZE");
  CHECK(RuntimeOptions::FromEnvironment().MpiTimeout == 120.0, "SCHLIEREN_MPI_TIMEOUT: 120 s unset");
  setenv("SCHLIEREN_MPI_TIMEOUT", "2.5", 1);
  CHECK(RuntimeOptions::FromEnvironment().MpiTimeout == 2.5, "SCHLIEREN_MPI_TIMEOUT=2.5 is read");
  setenv("SCHLIEREN_MPI_TIMEOUT", "0", 1);
  ExpectError("SCHLIEREN_MPI_TIMEOUT=0", [] { RuntimeOptions::FromEnvironment(); },
    { "SCHLIEREN_MPI_TIMEOUT", "'0'", "seconds in (0, 1e7]" });
  unsetenv("SCHLIEREN_MPI_TIMEOUT");
  CHECK(!RuntimeOptions::FromEnvironment().MpiAbort, "SCHLIEREN_MPI_ABORT: off unset");
  setenv("SCHLIEREN_MPI_ABORT", "1", 1);
  CHECK(RuntimeOptions::FromEnvironment().MpiAbort, "SCHLIEREN_MPI_ABORT=1 is read");
  setenv("SCHLIEREN_MPI_ABORT", "yes", 1);
  ExpectError("SCHLIEREN_MPI_ABORT=yes", [] { RuntimeOptions::FromEnvironment(); },
    { "SCHLIEREN_MPI_ABORT", "'yes'", "0 or 1" });
  unsetenv("SCHLIEREN_MPI_ABORT");
  CHECK(RuntimeOptions::FromEnvironment().CoarseCopies, "SCHLIEREN_COARSE: on unset");
  setenv("SCHLIEREN_COARSE", "0", 1);
  CHECK(!RuntimeOptions::FromEnvironment().CoarseCopies, "SCHLIEREN_COARSE=0 is read");
  setenv("SCHLIEREN_COARSE", "off", 1);
  ExpectError("SCHLIEREN_COARSE=off", [] { RuntimeOptions::FromEnvironment(); },
    { "SCHLIEREN_COARSE", "'off'", "0 or 1" });
  unsetenv("SCHLIEREN_COARSE");

  const bool haveCL = schtest::HaveOpenCL();
  SceneParameters p;
  schtest::SceneVolume sphere(Scene::GaussianSphere, p, 24, 1.0);
  sphere.V.Stamp = NewVolumeStamp();
  TraceSettings s;
  s.Resolution[0] = 48;
  s.Resolution[1] = 40;
  s.Passes = 2;
  s.CutoffScale = 1000;
  s.Method = Integrator::RK4;
  s.StepSize = 0.5;

  // 2. Threads: the CPU backend's thread count, per trace; the film does not depend on it.
  {
    TraceSettings c = s;
    c.Device = Backend::CPU;
    const TraceResult env = Trace(sphere.V, c);
    c.Threads = 1;
    const TraceResult one = Trace(sphere.V, c);
    c.Threads = 2;
    const TraceResult two = Trace(sphere.V, c);
    std::printf("CPU: %s / %s / %s\n", env.DeviceName.c_str(), one.DeviceName.c_str(), two.DeviceName.c_str());
    CHECK(env.DeviceName == "CPU (3 threads)" && one.DeviceName == "CPU (1 threads)" &&
        two.DeviceName == "CPU (2 threads)",
      "Threads chooses the CPU backend's threads; 0 takes SCHLIEREN_CPU_THREADS");
    CHECK(LargestDifference(one.Intensity, two.Intensity) == 0 &&
        LargestDifference(one.Deflection, two.Deflection) == 0 &&
        LargestDifference(one.Intensity, env.Intensity) == 0 && one.Samples == two.Samples &&
        one.Photons == two.Photons && LargestValue(one.Deflection) > 0,
      "Threads 1, 2 and 3 give the same film, bit for bit");
    c.Threads = -1;
    ExpectError("Threads -1", [&] { Trace(sphere.V, c); }, { "Threads", "0, 4096" });
  }

  // 3. DeviceName: a name no device has.
  {
    TraceSettings c = s;
    c.DeviceName = "no such device 1234";
    c.Device = Backend::OpenCL;
    ExpectError("DeviceName that matches nothing, Backend OpenCL", [&] { Trace(sphere.V, c); },
      haveCL ? std::vector<std::string>{ "DeviceName='no such device 1234'", "matches no OpenCL device",
                 "Backend CPU" }
             : std::vector<std::string>{});
    c.Device = Backend::Auto;
    const TraceResult r = Trace(sphere.V, c);
    std::printf("Auto with a bogus device: %s; %s", r.BackendUsed.c_str(), r.Warnings.c_str());
    // without any OpenCL device the warning says that instead
    CHECK(r.BackendUsed == "CPU" && r.Warnings.find("tracing on the CPU instead") != std::string::npos &&
        (!haveCL || r.Warnings.find("no such device 1234") != std::string::npos),
      "Backend Auto with a device name no device has traces on the CPU and says why");
    // the same name from the options (SCHLIEREN_OPENCL_DEVICE) when DeviceName is empty
    {
      const schtest::ScopedOptions env([](RuntimeOptions& o) { o.OpenCLDevice = "no such device 1234"; });
      TraceSettings e = s;
      e.Device = Backend::OpenCL;
      ExpectError("SCHLIEREN_OPENCL_DEVICE that matches nothing", [&] { Trace(sphere.V, e); },
        haveCL ? std::vector<std::string>{ "SCHLIEREN_OPENCL_DEVICE='no such device 1234'" }
               : std::vector<std::string>{});
    }
    const DeviceInfo none = QueryOpenCLDevice("no such device 1234");
    CHECK(!none.Available && (!haveCL || none.Reason.find("matches no OpenCL device") != std::string::npos),
      "QueryOpenCLDevice says that no device has the name");
  }
  if (!haveCL)
    return schtest::Finish();

  // 4. DeviceName: the device's own name (a part of it) traces there, as the default does; CPU and
  // OpenCL agree to float rounding.
  const DeviceInfo dev = QueryOpenCLDevice();
  {
    TraceSettings c = s;
    c.Device = Backend::OpenCL;
    const TraceResult byDefault = Trace(sphere.V, c);
    c.DeviceName = dev.Name.substr(0, std::min<std::size_t>(6, dev.Name.size()));
    const TraceResult named = Trace(sphere.V, c);
    CHECK(named.BackendUsed == "OpenCL" && named.DeviceName.find(dev.Name) == 0,
      "DeviceName '" + c.DeviceName + "' traces on '" + dev.Name + "'");
    CHECK(LargestDifference(named.Deflection, byDefault.Deflection) == 0,
      "the same device by name and by default gives the same film");
    TraceSettings cpu = s;
    cpu.Device = Backend::CPU;
    const TraceResult onCPU = Trace(sphere.V, cpu);
    const double d = LargestDifference(onCPU.Deflection, named.Deflection);
    const double m = LargestValue(onCPU.Deflection);
    std::printf("CPU against OpenCL: largest deflection difference %.3g rad of %.3g (%.3g); "
                "intensity %.3g\n",
      d, m, d / m, LargestDifference(onCPU.Intensity, named.Intensity));
    // a few hundred float steps: each rounds at 2^-24 of the deflection, so 1e-4 of it is far
    // above rounding and far below any difference in physics
    CHECK(d <= 1e-4 * m, "CPU and OpenCL agree to float rounding");
  }

  // 5. Build options are part of the kernel cache key: the kept volume, traced again with an
  // option the compiler refuses, builds again and fails, saying which option; back to the
  // environment's options, it traces again.
  {
    TraceSettings c = s;
    c.Device = Backend::OpenCL;
    const TraceResult before = Trace(sphere.V, c);
    {
      const schtest::ScopedOptions bad([](RuntimeOptions& o) { o.BuildOptions = "-Dsch_params=1"; });
      ExpectError("SCHLIEREN_CL_OPTIONS that breaks the build", [&] { Trace(sphere.V, c); },
        { "failed to build", "-Dsch_params=1" });
    }
    const TraceResult after = Trace(sphere.V, c);
    CHECK(LargestDifference(before.Deflection, after.Deflection) == 0,
      "with the first options again the kept volume traces as before");
  }
  ReleaseKeptVolume();
  return schtest::Finish();
}
