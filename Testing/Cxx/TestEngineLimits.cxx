// SPDX-License-Identifier: BSD-3-Clause
// What the engine refuses, and what it must not get wrong in silence:
//  - a volume anywhere in space traces as it does at the origin (the tracer works relative to the
//    volume: the origin enters only the output image's place),
//  - out-of-range settings are errors that name the property, the value and the range (never
//    clamped), and the documented special values (0 = automatic) still work,
//  - volumes and steps the float tracer cannot honour are refused at once (the spacing that made a
//    ray run to a billion steps),
//  - films larger than the memory the machine can give are refused before they are allocated,
//  - an image that no photon reached comes with a warning,
//  - on a CPU OpenCL device a page-aligned field is traced in place, with the same records.
#include "SchlierenLimits.h"
#include "SchlierenTesting.h"

#include <chrono>
#include <cstdint>
#include <sstream>
#include <cstring>
#include <limits>
#include <memory>

using namespace schlieren;
using schtest::ExpectError;

namespace
{
TraceSettings Small(Backend b)
{
  TraceSettings s;
  s.Device = b;
  s.Resolution[0] = s.Resolution[1] = 48;
  s.Passes = 1;
  s.Jitter = false;
  s.ViewDirection[0] = 0.3; // oblique: every axis of the position moves
  s.ViewDirection[1] = -0.2;
  s.ViewDirection[2] = -1.0;
  s.CutoffScale = 1000;
  return s;
}

double MaxDiff(const std::vector<float>& a, const std::vector<float>& b)
{
  if (a.size() != b.size())
    return 1e300;
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    m = std::max(m, std::fabs(double(a[i]) - b[i]));
  return m;
}
} // namespace

int main()
{
  const bool haveCL = schtest::HaveOpenCL();
  SceneParameters p; // Gaussian sphere A = 1e-4, s = 0.25
  schtest::SceneVolume g(Scene::GaussianSphere, p, 40, 1.0);

  // 1. Far from the origin: the same image, bit for bit (tolerance 0: the tracer never sees the
  // origin, so any difference is a bug), and the image's origin follows the volume.
  for (Backend b : { Backend::CPU, Backend::OpenCL })
  {
    if (b == Backend::OpenCL && !haveCL)
      continue;
    const TraceSettings s = Small(b);
    const TraceResult ref = Trace(g.V, s);
    CHECK(ref.Samples > 0 && ref.Warnings.empty(), "the reference trace samples the volume, no warning");
    double refOrigin[2];
    ref.Film.GetImageOrigin(refOrigin);
    for (double shift : { 1e6, 1e14, 1e18 })
    {
      Volume v = g.V;
      for (int a = 0; a < 3; ++a)
        v.Origin[a] += shift;
      const TraceResult r = Trace(v, s);
      const double dI = MaxDiff(r.Intensity, ref.Intensity), dE = MaxDiff(r.Deflection, ref.Deflection);
      std::printf("%s, origin + %g: samples %g (at the origin %g), max |dI| %g, max |d deflection| %g rad\n",
        BackendName(b), shift, r.Samples, ref.Samples, dI, dE);
      CHECK(r.Samples == ref.Samples && dI == 0 && dE == 0,
        "a volume moved by " + std::to_string(shift) + " traces the same image");
      double o[2];
      r.Film.GetImageOrigin(o);
      // the film's place: shifted by the projection of (shift, shift, shift) on its axes
      const double along[2] = { shift * (r.Film.Right[0] + r.Film.Right[1] + r.Film.Right[2]),
        shift * (r.Film.Up[0] + r.Film.Up[1] + r.Film.Up[2]) };
      for (int k = 0; k < 2; ++k)
        CHECK_NEAR(o[k], refOrigin[k] + along[k], 1e-12 * shift, "the image origin moves with the volume");
    }
  }

  // 2. Out-of-range settings: errors naming the property, the value and the range.
  {
    const double inf = std::numeric_limits<double>::infinity();
    struct Case
    {
      const char* Name;
      void (*Set)(TraceSettings&, double);
      double Value;
      const char* Expect;
    };
    const Case cases[] = {
      { "StepSize", [](TraceSettings& t, double v) { t.StepSize = v; }, -1, "[0.01, 1000]" },
      { "StepSize", [](TraceSettings& t, double v) { t.StepSize = v; }, 1e4, "[0.01, 1000]" },
      { "FilmDistance", [](TraceSettings& t, double v) { t.FilmDistance = v; }, -5, ">= 0" },
      { "FilmDistance", [](TraceSettings& t, double v) { t.FilmDistance = v; }, inf, "finite" },
      { "FilmDistance", [](TraceSettings& t, double v) { t.FilmDistance = v; },
        std::numeric_limits<double>::max(), "1e6 times the volume's size" },
      { "BackgroundDistance", [](TraceSettings& t, double v) { t.BackgroundDistance = v; }, -1, ">= 0" },
      { "CutoffScale", [](TraceSettings& t, double v) { t.CutoffScale = v; }, -10, "[0, 1e12]" },
      { "Wavelength", [](TraceSettings& t, double v) { t.Wavelength = v; }, 0, "[100, 100000]" },
      { "Wavelength", [](TraceSettings& t, double v) { t.Wavelength = v; }, -500, "[100, 100000]" },
      { "FilterWidth", [](TraceSettings& t, double v) { t.FilterWidth = v; }, -2, "[0.01, 64]" },
      { "Tolerance", [](TraceSettings& t, double v) { t.Tolerance = v; }, -1, "[0, 1]" },
    };
    for (const Case& c : cases)
    {
      TraceSettings t = Small(Backend::CPU);
      c.Set(t, c.Value);
      std::ostringstream value;
      value << c.Value;
      ExpectError(c.Name, [&] { Trace(g.V, t); }, { c.Name, c.Expect });
    }
    // the special values still work: automatic cutoff scale and Auto's automatic tolerance
    TraceSettings t = Small(Backend::CPU);
    t.CutoffScale = 0;
    t.Method = Integrator::Auto;
    t.Tolerance = 0;
    bool ok = true;
    try
    {
      const TraceResult r = Trace(g.V, t);
      ok = r.CutoffScaleUsed > 0 && r.Choice.Tolerance > 0;
    }
    catch (const Error& e)
    {
      ok = false;
      std::printf("%s\n", e.what());
    }
    CHECK(ok, "CutoffScale 0 and Tolerance 0 mean automatic");
  }

  // 3. The float tracer's limits: refused at once, with the reason.
  {
    // the volume that ran one ray for 303 s: 13 x 35 x 31 points, spacing (1e-40, 0.0092, 0.44)
    std::vector<float> n1(13 * 35 * 31, 1e-4f), f(4 * n1.size());
    Volume v;
    v.Dimensions[0] = 13;
    v.Dimensions[1] = 35;
    v.Dimensions[2] = 31;
    v.Spacing[0] = 1e-40;
    v.Spacing[1] = 0.0092;
    v.Spacing[2] = 0.44;
    PackField(v.Dimensions, v.Spacing, n1.data(), f.data());
    v.Field = f.data();
    for (Backend b : { Backend::CPU, Backend::OpenCL })
    {
      TraceSettings s = Small(b);
      s.Resolution[0] = s.Resolution[1] = 16;
      const auto t0 = std::chrono::steady_clock::now();
      ExpectError("spacing (1e-40, 0.0092, 0.44)", [&] { Trace(v, s); }, { "float tracer", "spacing" });
      const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      CHECK(sec < 1.0, "refused within a second, not traced (" + std::to_string(sec) + " s)");
    }
    // a spacing ratio of 3e4 seen along the long axes: the step moves a position by 8 float units
    schtest::SceneVolume thin(Scene::GaussianSphere, p, 32, 32, 32, -1.0, 1.0);
    thin.V.Spacing[2] = 2 * 3e-5 / 31;
    TraceSettings s = Small(Backend::CPU);
    s.ViewDirection[0] = 1;
    s.ViewDirection[1] = 0;
    s.ViewDirection[2] = 0;
    s.ViewUp[0] = 0;
    s.ViewUp[1] = 0;
    s.ViewUp[2] = 1;
    ExpectError("spacing ratio 3e4, viewed along a long axis", [&] { Trace(thin.V, s); },
      { "StepSize", "float position", "spacing ratio" });
    // seen along the thin axis, the same volume traces (the step moves z by many float units)
    s.ViewDirection[0] = 0;
    s.ViewDirection[2] = -1;
    s.ViewUp[1] = 1;
    s.ViewUp[2] = 0;
    bool ok = true;
    try
    {
      ok = Trace(thin.V, s).Samples > 0;
    }
    catch (const Error& e)
    {
      ok = false;
      std::printf("%s\n", e.what());
    }
    CHECK(ok, "the thin volume seen along its thin axis traces");
  }

  // 4. Memory: a film larger than the machine can give is refused before it is allocated, with
  // what it needs, what is available and what to change (the limit set low for the test, so
  // that it does not depend on this machine's RAM).
  {
    auto limit = std::make_unique<schtest::ScopedOptions>([](RuntimeOptions& o) { o.MemoryLimit = 100000000; });
    TraceSettings s = Small(Backend::CPU);
    s.Resolution[0] = s.Resolution[1] = 16384;
    ExpectError("16384^2 film, 100 MB available", [&] { Trace(g.V, s); },
      { "16384 x 16384 pixels", "needs 94", "GiB", "available", "Lower Resolution" });
    s.Resolution[0] = s.Resolution[1] = 8000;
    ExpectError("8000^2 film", [&] { Trace(g.V, s); }, { "8000 x 8000", "Lower Resolution" });
    limit.reset();
    CHECK(AvailableMemory() > 0 && AvailableMemory() <= PhysicalMemory(),
      "available memory is positive and at most the installed memory");
  }

  // 5. Images no photon reached come with a warning.
  {
    // a sheet 2e-5 thick seen edge-on through 48 pixels 0.04 wide: no ray enters it
    schtest::SceneVolume sheet(Scene::GaussianSphere, p, 32, 32, 4, -1.0, 1.0);
    sheet.V.Spacing[2] = 2e-5 / 3;
    TraceSettings s = Small(Backend::CPU);
    s.ViewDirection[0] = 1;
    s.ViewDirection[1] = 0;
    s.ViewDirection[2] = 0;
    s.ViewUp[0] = 0;
    s.ViewUp[1] = 0;
    s.ViewUp[2] = 1;
    s.StepSize = 64;
    TraceResult r = Trace(sheet.V, s);
    std::printf("edge-on sheet: samples %g, warnings: %s", r.Samples, r.Warnings.c_str());
    CHECK(r.Samples == 0 && r.Warnings.find("No ray entered the volume") != std::string::npos,
      "a volume no ray entered is reported");
    // a shadowgraph film 3e6 behind a 3.5-unit volume of a wide, strong sphere (A = 1e-3, s = 1): the
    // photons through the sphere (deflected by more than 1e-6 rad) land off the film
    SceneParameters strong;
    strong.Amplitude = 1e-3;
    strong.Width = 1.0;
    schtest::SceneVolume g3(Scene::GaussianSphere, strong, 40, 1.0);
    TraceSettings t = Small(Backend::CPU);
    t.Mode = Cutoff::Shadowgraph;
    t.FilmDistance = 3e6;
    r = Trace(g3.V, t);
    double sum = 0;
    for (float x : r.Intensity)
      sum += x;
    std::printf("film 3e6 behind: samples %g, image sum %g, warnings: %s", r.Samples, sum, r.Warnings.c_str());
    CHECK(r.Samples > 0 && r.Warnings.find("off the film") != std::string::npos,
      "photons landing off the film are reported");
  }

  // 5b. Abort within a fraction of a second when every ray is long: 3^3 points spaced
  // (5e4, 1, 1), seen along x: 2e5 steps a ray, 8e8 samples for the 64^2 film. Progress (and
  // abort) comes between chunks, which are sized by the rays' length (64 rays here, 1.3e7
  // samples), not a fixed 4096 rays (the whole film: one report at the end, seconds later).
  {
    std::vector<float> n1(27, 1e-4f), f(4 * 27);
    Volume v;
    for (int a = 0; a < 3; ++a)
      v.Dimensions[a] = 3;
    v.Spacing[0] = 5e4;
    PackField(v.Dimensions, v.Spacing, n1.data(), f.data());
    v.Field = f.data();
    TraceSettings s = Small(Backend::CPU);
    s.Resolution[0] = s.Resolution[1] = 64;
    s.ViewDirection[0] = 1;
    s.ViewDirection[1] = 0;
    s.ViewDirection[2] = 0;
    s.ViewUp[0] = 0;
    s.ViewUp[1] = 0;
    s.ViewUp[2] = 1;
    int calls = 0;
    const auto t0 = std::chrono::steady_clock::now();
    double first = -1;
    ExpectError("abort a trace of long rays", [&] {
      Trace(v, s, [&](double) {
        if (first < 0)
          first = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return ++calls < 2;
      });
    }, { "aborted" });
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("long rays: first progress report after %.3f s, aborted after %.3f s\n", first, sec);
    // the abort comes one chunk after the first report (the machine's speed cancels out); with
    // the whole film in one chunk there is no second report and no abort at all
    CHECK(sec < 3 * first + 0.5, "the trace of long rays stops one chunk after the request (" +
        std::to_string(sec) + " s, first report " + std::to_string(first) + " s)");
  }

  // 6. A CPU OpenCL device traces a page-aligned field in place: the same records as a copy.
  if (haveCL)
  {
    AlignedFloats aligned(g.Field.begin(), g.Field.end());
    Volume v = g.V;
    v.Field = aligned.data();
    CHECK(reinterpret_cast<std::uintptr_t>(aligned.data()) % 4096 == 0, "AlignedFloats is page-aligned");
    const TraceSettings s = Small(Backend::OpenCL);
    const TraceResult a = Trace(g.V, s), b = Trace(v, s);
    CHECK(MaxDiff(a.Intensity, b.Intensity) == 0 && MaxDiff(a.Deflection, b.Deflection) == 0,
      "in place and copied fields give the same image");
  }
  return schtest::Finish();
}
