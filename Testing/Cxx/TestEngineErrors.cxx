// SPDX-License-Identifier: BSD-3-Clause
// Bad input gets a clear error (schlieren::Error with a message that says what to do), never a
// crash or a hang: one-slice volumes, NaN, n <= 0, zero passes, absurd properties, a kernel that
// fails to build (its log must come back), a volume larger than the device allows, abort.
#include "SchlierenTesting.h"

#include <cstring>
#include <limits>

using namespace schlieren;
using schtest::ExpectError;

namespace
{
} // namespace

int main()
{
  const bool haveCL = schtest::HaveOpenCL();
  SceneParameters p;
  schtest::SceneVolume good(Scene::GaussianSphere, p, 16, 1.0);

  // one-voxel-thick volume
  {
    const int dims[3] = { 16, 16, 1 };
    const double sp[3] = { 0.1, 0.1, 0.1 };
    std::vector<float> n1(256, 1e-4f), f(1024);
    ExpectError("one slice", [&] { PackField(dims, sp, n1.data(), f.data()); },
      { "at least 2 points", "axis z" });
  }
  // NaN and n <= 0
  {
    std::vector<float> n1 = good.N1, f(good.Field.size());
    n1[100] = std::numeric_limits<float>::quiet_NaN();
    n1[200] = std::numeric_limits<float>::infinity();
    ExpectError("NaN in the field",
      [&] { PackField(good.V.Dimensions, good.V.Spacing, n1.data(), f.data()); },
      { "2 of 4096 points are NaN or Inf", "first at point 100" });
    n1 = good.N1;
    n1[7] = -1.5f;
    ExpectError("n <= 0", [&] { PackField(good.V.Dimensions, good.V.Spacing, n1.data(), f.data()); },
      { "n <= 0" });
    const double badSpacing[3] = { 0.1, 0.0, 0.1 };
    ExpectError("zero spacing", [&] { PackField(good.V.Dimensions, badSpacing, good.N1.data(), f.data()); },
      { "spacing" });
  }
  // absurd properties
  {
    TraceSettings s;
    s.Device = Backend::CPU;
    s.Resolution[0] = s.Resolution[1] = 8;
    s.Passes = 0;
    ExpectError("Passes = 0", [&] { Trace(good.V, s); }, { "Passes", "at least 1" });
    s.Passes = 1;
    s.ViewUp[0] = 0;
    s.ViewUp[1] = 0;
    s.ViewUp[2] = 2;
    ExpectError("ViewUp parallel to ViewDirection", [&] { Trace(good.V, s); }, { "ViewUp" });
    s.ViewUp[2] = 0;
    s.ViewUp[1] = 1;
    s.ViewDirection[2] = 0;
    ExpectError("zero ViewDirection", [&] { Trace(good.V, s); }, { "ViewDirection" });
    s.ViewDirection[2] = -1;
    s.Resolution[0] = 0;
    ExpectError("Resolution 0", [&] { Trace(good.V, s); }, { "Resolution" });
    s.Resolution[0] = 8;
    for (double step : { 0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), 1e9 })
      ExpectError("absurd StepSize", [&] {
        TraceSettings t = s;
        t.StepSize = step;
        Trace(good.V, t);
      }, { "StepSize" });
    ExpectError("unknown backend", [&] { ParseBackend("CUDA"); }, { "Auto, OpenCL or CPU" });
    ExpectError("no field", [&] {
      Volume v = good.V;
      v.Field = nullptr;
      Trace(v, s);
    }, { "no field" });
  }
  // abort from the progress callback stops the trace
  {
    TraceSettings s;
    s.Device = Backend::CPU;
    s.Resolution[0] = s.Resolution[1] = 300;
    s.Passes = 50;
    int calls = 0;
    ExpectError("abort", [&] { Trace(good.V, s, [&](double) { return ++calls < 2; }); }, { "aborted" });
    CHECK(calls == 2, "the trace stops at the first progress report after the abort");
  }
  if (haveCL)
  {
    // a kernel that fails to build reports the status, options and the compiler's log
    ExpectError("broken kernel",
      [&] { BuildOpenCLProgram("broken.cl", "__kernel void f(__global float* x) { x[0] = y; }", "-DTEST=1"); },
      { "broken.cl", "CL_BUILD_PROGRAM_FAILURE", "-DTEST=1", "Build log", "y" });
    // the failure is cached: asking again gives the same error at once
    ExpectError("broken kernel, cached",
      [&] { BuildOpenCLProgram("broken.cl", "__kernel void f(__global float* x) { x[0] = y; }", "-DTEST=1"); },
      { "Build log" });
    // the embedded kernels build
    bool ok = true;
    try
    {
      BuildOpenCLProgram("SchlierenTrace.cl", EmbeddedKernelSource(), "-DSCH_RAYS_PER_ITEM=1");
    }
    catch (const Error& e)
    {
      ok = false;
      std::printf("%s\n", e.what());
    }
    CHECK(ok, "the embedded kernels build");
    // a volume larger than four device buffers (the most it is split into): a clear error before
    // any memory is touched
    DeviceInfo d = QueryOpenCLDevice();
    Volume big;
    big.Dimensions[0] = big.Dimensions[1] = 1024;
    big.Dimensions[2] = 4 * static_cast<int>(d.MaxAlloc / (16.0 * 1024 * 1024)) + 2;
    big.Field = good.Field.data(); // never read: the size check comes first
    TraceSettings s;
    s.Device = Backend::OpenCL;
    s.Resolution[0] = s.Resolution[1] = 4;
    ExpectError("volume over four of the device's buffers", [&] { Trace(big, s); },
      { "MiB per buffer", "Backend CPU" });
  }
  return schtest::Finish();
}
