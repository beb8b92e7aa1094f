// SPDX-License-Identifier: BSD-3-Clause
// A few checks for the engine tests: each failed check prints where and why; main returns the
// number of failures, and the run ends with the plain line "N passed, N failed".
#ifndef SchlierenTesting_h
#define SchlierenTesting_h

#include "SchlierenEngine.h"
#include "SchlierenOptions.h"
#include "SchlierenScenes.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

namespace schtest
{
inline int& Failures()
{
  static int n = 0;
  return n;
}
inline int& Passes()
{
  static int n = 0;
  return n;
}
inline void Report(bool ok, const char* file, int line, const std::string& what)
{
  if (ok)
    ++Passes();
  else
  {
    ++Failures();
    std::printf("FAIL %s:%d: %s\n", file, line, what.c_str());
  }
}
inline int Finish()
{
  std::printf("%d passed, %d failed\n", Passes(), Failures());
  return Failures() ? 1 : 0;
}

/** A scene on a grid, packed for the engine; owns its arrays. */
struct SceneVolume
{
  std::vector<float> N1, Field;
  schlieren::Volume V;
  SceneVolume(schlieren::Scene scene, const schlieren::SceneParameters& p, int n, double half)
    : SceneVolume(scene, p, n, n, n, -half, half)
  {
  }
  SceneVolume(schlieren::Scene scene, const schlieren::SceneParameters& p, int nx, int ny, int nz,
    double lo, double hi)
  {
    const int dims[3] = { nx, ny, nz };
    for (int a = 0; a < 3; ++a)
    {
      V.Dimensions[a] = dims[a];
      V.Origin[a] = lo;
      V.Spacing[a] = (hi - lo) / (dims[a] - 1);
    }
    N1.resize(V.NumberOfPoints());
    Field.resize(4 * N1.size());
    schlieren::FillScene(scene, p, V.Dimensions, V.Origin, V.Spacing, N1.data(), nullptr);
    schlieren::PackField(V.Dimensions, V.Spacing, N1.data(), Field.data());
    V.Field = Field.data();
  }
};

/** Changes the engine's runtime options for the life of this object (what a test would otherwise
 * do with setenv, which the engine reads only once), then puts the previous ones back. */
struct ScopedOptions
{
  schlieren::RuntimeOptions Saved = schlieren::GetRuntimeOptions();
  explicit ScopedOptions(const std::function<void(schlieren::RuntimeOptions&)>& change)
  {
    schlieren::RuntimeOptions o = Saved;
    change(o);
    schlieren::SetRuntimeOptions(o);
  }
  ~ScopedOptions() { schlieren::SetRuntimeOptions(Saved); }
  ScopedOptions(const ScopedOptions&) = delete;
  ScopedOptions& operator=(const ScopedOptions&) = delete;
};

/** True if OpenCL can run here; tests that need it say so and skip otherwise. */
inline bool HaveOpenCL()
{
  schlieren::DeviceInfo d = schlieren::QueryOpenCLDevice();
  if (!d.Available)
  {
    // CI sets SCHLIEREN_REQUIRE_OPENCL=1: there a missing device is a failure, not a skip
    const char* req = std::getenv("SCHLIEREN_REQUIRE_OPENCL");
    Report(!(req && *req == '1'), __FILE__, __LINE__, "OpenCL is required here: " + d.Reason);
    std::printf("SKIP OpenCL parts: %s\n", d.Reason.c_str());
  }
  else
    std::printf("OpenCL device: %s (%s)\n", d.Name.c_str(), d.Version.c_str());
  return d.Available;
}
} // namespace schtest

#define CHECK(cond, msg)                                                                           \
  schtest::Report((cond), __FILE__, __LINE__, std::string(#cond) + ": " + (msg))

namespace schtest
{
/** Runs f; passes if it throws schlieren::Error whose message contains every one of `needles`. */
template <typename F>
void ExpectError(const char* what, F f, std::vector<std::string> needles)
{
  std::string msg;
  bool threw = false;
  try
  {
    f();
  }
  catch (const schlieren::Error& e)
  {
    threw = true;
    msg = e.what();
  }
  bool found = threw;
  for (const std::string& n : needles)
    found = found && msg.find(n) != std::string::npos;
  std::printf("%s -> %s\n", what, threw ? msg.substr(0, 300).c_str() : "(no error)");
  CHECK(found, std::string(what) + ": expected an error mentioning the cause, got: " + msg);
}
} // namespace schtest

#define CHECK_NEAR(a, b, tol, msg)                                                                 \
  do                                                                                               \
  {                                                                                                \
    const double _a = (a), _b = (b), _t = (tol);                                                   \
    char _buf[256];                                                                                \
    std::snprintf(_buf, sizeof(_buf), " (got %.9g, expected %.9g, tolerance %.3g)", _a, _b, _t);   \
    schtest::Report(std::fabs(_a - _b) <= _t, __FILE__, __LINE__, std::string(msg) + _buf);       \
  } while (0)

#endif
