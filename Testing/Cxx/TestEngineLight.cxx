// SPDX-License-Identifier: BSD-3-Clause
// A band of wavelengths (docs/BENCH.md "Light") against its closed forms (ORACLES.md):
// - white-light fringes of a tilted reference through a uniform medium: a path difference
//   D = ReferenceTilt Wavelength a across the film, a band flat in wavenumber s1..s2 gives
//   I = 1/2 (1 + sinc(pi D (s2 - s1)) cos(2 pi s D)), s the band's mean wavenumber: the first
//   zero of the visibility at D = 1 / (s2 - s1), 0.933 um for 400-700 nm; the zero-order fringe
//   white, the first dark ones coloured;
// - dispersion: with the density fixed, eps(l) / eps(l0) = (n(l) - 1) / (n(l0) - 1) from Ciddor
//   (about +2.5 % at 400 nm against 700 nm); Dispersion None leaves eps alone;
// - one wavelength of the band equal to Wavelength: the monochromatic image bit for bit;
// - CPU and OpenCL agree; bad bands are refused with the cause.
#include "SchlierenOracles.h"
#include "SchlierenTesting.h"

#include "SchlierenIndexModels.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace schlieren;

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr int kFilm = 65; // odd: a pixel centred on a = 0, the zero-order fringe

TraceSettings Base()
{
  TraceSettings s = schtest::Beam(0, 0, -1, 0, 1, 0);
  s.Resolution[0] = s.Resolution[1] = kFilm;
  s.Device = Backend::CPU;
  s.Jitter = false;
  return s;
}

double PixelA(const TraceResult& r, int i)
{
  return r.Film.Corner[0] + (i + 0.5) * r.Film.PixelSize;
}

double Sinc(double x)
{
  return std::fabs(x) < 1e-12 ? 1.0 : std::sin(x) / x;
}

// white-light fringes: the tilted reference through a uniform medium (its phase is 0: every ray
// keeps the index it entered with), so the fringes are the reference's alone
void TestVisibility()
{
  SceneParameters p;
  p.Amplitude = 2.7e-4;
  schtest::SceneVolume uv(Scene::Uniform, p, 16, 1.0);
  TraceSettings s = Base();
  s.Mode = Cutoff::Interferometry;
  s.Wavelength = 632.8;
  s.WavelengthRange[0] = 400;
  s.WavelengthRange[1] = 700;
  const int bins = 32;
  s.WavelengthBins = bins;
  s.Passes = bins;
  // D = 2 um at the film's edge (a = 1): past the visibility's second zero
  s.ReferenceTilt = 2000.0 / s.Wavelength;
  const TraceResult r = Trace(uv.V, s);
  const double s1 = 1.0 / 700, s2 = 1.0 / 400, sm = 0.5 * (s1 + s2); // 1/nm
  // the bins' centres: the midpoint rule on [s1, s2] in N bins errs by at most
  // (s2 - s1)^2 / (24 N^2) max |f''| for f = cos(2 pi s D): (2 pi D (s2 - s1))^2 / (24 N^2) in
  // <cos>, half that in I; float32 phases of up to 2 pi s D ~ 30 rad add ~1e-5
  const double dmax = s.ReferenceTilt * s.Wavelength * 1.0;
  const double bound = 0.5 * std::pow(2 * kPi * dmax * (s2 - s1), 2) / (24.0 * bins * bins) + 1e-5;
  double err = 0, whiteSpread = 1, darkSpread = 0;
  const int row = kFilm / 2;
  for (int i = 0; i < kFilm; ++i)
  {
    const double a = PixelA(r, i);
    const double D = s.ReferenceTilt * s.Wavelength * a; // nm
    const double expect = 0.5 * (1 + Sinc(kPi * D * (s2 - s1)) * std::cos(2 * kPi * sm * D));
    const std::size_t px = static_cast<std::size_t>(row) * kFilm + i;
    err = std::max(err, std::fabs(r.Intensity[px] - expect));
    const float* c = &r.RGB[3 * px];
    const double spread = std::max({ c[0], c[1], c[2] }) - std::min({ c[0], c[1], c[2] });
    if (std::fabs(D) < 0.5 * s.ReferenceTilt * s.Wavelength * r.Film.PixelSize + 1e-9)
      whiteSpread = spread; // the zero-order fringe (D within half a pixel of 0)
    if (std::fabs(D) > 150 && std::fabs(D) < 450)
      darkSpread = std::max(darkSpread, spread); // the first dark fringes, D ~ 300 nm
  }
  std::printf("white-light fringes, 400-700 nm in %d bins: max |I - closed form| = %.3g (bound %.3g); "
              "rgb spread %.3g at the zero-order fringe, %.3g at the first dark ones\n",
    bins, err, bound, whiteSpread, darkSpread);
  CHECK(err <= bound, "white-light fringes: I within the midpoint rule's bound of the band's closed form");
  CHECK(r.RGB.size() == 3 * r.Intensity.size(), "a band gives rgb");
  CHECK(whiteSpread < 1e-3, "the zero-order fringe is white (its channels within 1e-3)");
  CHECK(darkSpread > 0.1, "the first dark fringes are coloured (channels apart by more than 0.1)");
  // the visibility's first zero at D = 1 / (s2 - s1): 933 nm for 400-700 nm
  CHECK_NEAR(1.0 / (s2 - s1), 933.3, 0.1, "the first zero of the visibility (nm), as ORACLES.md says");
  CHECK(r.Spectrum.find("400-700 nm") != std::string::npos && r.Spectrum.find("32 bins") != std::string::npos,
    "the report says how the band was sampled: " + r.Spectrum);

  // a monochromatic reference: the same tilt at one wavelength keeps full visibility
  TraceSettings m = s;
  m.WavelengthRange[0] = m.WavelengthRange[1] = 0;
  m.Passes = 1;
  const TraceResult mono = Trace(uv.V, m);
  double lo = 1, hi = 0;
  for (int i = 0; i < kFilm; ++i)
  {
    lo = std::min(lo, double(mono.Intensity[row * kFilm + i]));
    hi = std::max(hi, double(mono.Intensity[row * kFilm + i]));
  }
  CHECK(lo < 0.01 && hi > 0.99 && mono.RGB.empty(), "one wavelength: fringes of full visibility, no rgb");
}

// dispersion: a linear gradient's deflection at one wavelength of a band against Wavelength's
void TestDispersion(bool opencl)
{
  SceneParameters p;
  p.GradientA = 1.0006;
  p.GradientB = 2e-4;
  schtest::SceneVolume gv(Scene::LinearGradient, p, 24, 1.0);
  TraceSettings s = Base();
  s.Device = opencl ? Backend::OpenCL : Backend::CPU;
  s.Resolution[0] = s.Resolution[1] = 16;
  s.Mode = Cutoff::KnifeEdge;
  s.KnifeAngle = 90;
  s.Wavelength = 632.8;
  const TraceResult mono = Trace(gv.V, s);
  auto at = [&](double nm, Dispersion d) {
    TraceSettings b = s;
    b.WavelengthRange[0] = b.WavelengthRange[1] = nm;
    b.Disperse = d;
    return Trace(gv.V, b);
  };
  // the band's one wavelength equal to Wavelength: the same photons, bit for bit
  const TraceResult same = at(632.8, Dispersion::Air);
  CHECK(std::memcmp(same.Intensity.data(), mono.Intensity.data(), mono.Intensity.size() * sizeof(float)) == 0 &&
      std::memcmp(same.Deflection.data(), mono.Deflection.data(), mono.Deflection.size() * sizeof(float)) == 0,
    "a band of Wavelength alone: the monochromatic image bit for bit");
  const TraceResult blue = at(400, Dispersion::Air), red = at(700, Dispersion::Air);
  const TraceResult flat = at(400, Dispersion::None);
  const double want = CiddorIndex(288.15, 101325, 0, 400) / CiddorIndex(288.15, 101325, 0, 700);
  double worst = 0, worstFlat = 0;
  const std::size_t centre = (8 * 16 + 8) * 2 + 1; // the y deflection at the film's centre
  for (std::size_t k = 1; k < mono.Deflection.size(); k += 2)
  {
    if (std::fabs(mono.Deflection[k]) < 0.5 * std::fabs(mono.Deflection[centre]))
      continue; // the box's border pixels (one-sided gradients)
    worst = std::max(worst, std::fabs(double(blue.Deflection[k]) / red.Deflection[k] / want - 1));
    worstFlat = std::max(worstFlat, std::fabs(double(flat.Deflection[k]) / mono.Deflection[k] - 1));
  }
  // n - 1 ~ 3e-4 scaled by ~2.5 % changes 1/n by ~1e-5; float32 deflections add ~1e-6
  std::printf("dispersion (%s): eps(400)/eps(700) = %.6f, Ciddor's (n-1) ratio %.6f, worst relative "
              "difference %.2g; Dispersion None: %.2g\n",
    opencl ? "OpenCL" : "CPU", blue.Deflection[centre] / red.Deflection[centre], want, worst, worstFlat);
  CHECK(want > 1.02 && want < 1.03, "Ciddor: n - 1 about 2.5 % more at 400 nm than at 700 nm");
  CHECK(worst < 5e-5, "eps(400) / eps(700) is Ciddor's (n(400) - 1) / (n(700) - 1)");
  CHECK(worstFlat < 5e-6, "Dispersion None: the deflection of every wavelength is Wavelength's");
  CHECK(blue.SpectrumScale[0] == blue.SpectrumScale[1] && std::fabs(blue.SpectrumScale[0] -
      CiddorIndex(288.15, 101325, 0, 400) / CiddorIndex(288.15, 101325, 0, 632.8)) < 1e-12,
    "the report's n - 1 scale at 400 nm");
}

// a band on both backends: one image to float rounding
void TestBackends()
{
  SceneParameters p;
  p.Amplitude = 2e-6;
  p.Width = 0.3;
  schtest::SceneVolume sv(Scene::GaussianSphere, p, 48, 1.0);
  TraceSettings s = Base();
  s.Mode = Cutoff::Interferometry;
  s.WavelengthRange[0] = 450;
  s.WavelengthRange[1] = 650;
  s.WavelengthBins = 8;
  s.Passes = 8;
  s.Jitter = true;
  const TraceResult cpu = Trace(sv.V, s);
  s.Device = Backend::OpenCL;
  const TraceResult cl = Trace(sv.V, s);
  double d = 0;
  for (std::size_t k = 0; k < cpu.RGB.size(); ++k)
    d = std::max(d, double(std::fabs(cpu.RGB[k] - cl.RGB[k])));
  std::printf("a band on CPU and OpenCL: max |rgb difference| %.3g\n", d);
  CHECK(cl.BackendUsed == "OpenCL" && d < 1e-3, "a band: CPU and OpenCL agree to float rounding");
}

void TestErrors()
{
  SceneParameters p;
  schtest::SceneVolume uv(Scene::Uniform, p, 8, 1.0);
  auto run = [&](std::function<void(TraceSettings&)> change) {
    return [&uv, change]() {
      TraceSettings s = Base();
      s.Resolution[0] = s.Resolution[1] = 8;
      change(s);
      Trace(uv.V, s);
    };
  };
  schtest::ExpectError("WavelengthRange 200 700", run([](TraceSettings& s) {
    s.WavelengthRange[0] = 200;
    s.WavelengthRange[1] = 700;
  }), { "WavelengthRange is 200 700", "Ciddor" });
  schtest::ExpectError("WavelengthRange 700 400", run([](TraceSettings& s) {
    s.WavelengthRange[0] = 700;
    s.WavelengthRange[1] = 400;
  }), { "WavelengthRange", "l0 <= l1" });
  schtest::ExpectError("WavelengthRange NaN", run([](TraceSettings& s) {
    s.WavelengthRange[0] = 400;
    s.WavelengthRange[1] = std::nan("");
  }), { "WavelengthRange", "nan" });
  schtest::ExpectError("WavelengthBins 0", run([](TraceSettings& s) { s.WavelengthBins = 0; }),
    { "WavelengthBins", "[1, 4096]" });
  schtest::ExpectError("band with Wavelength 200", run([](TraceSettings& s) {
    s.WavelengthRange[0] = 400;
    s.WavelengthRange[1] = 700;
    s.Wavelength = 200;
  }), { "Wavelength is 200", "Ciddor" });
}
}

int main()
{
  TestVisibility();
  TestDispersion(false);
  TestErrors();
  if (schtest::HaveOpenCL())
  {
    TestDispersion(true);
    TestBackends();
  }
  return schtest::Finish();
}
