// SPDX-License-Identifier: BSD-3-Clause
// The camera (docs/BENCH.md "Camera") against its known answers (ORACLES.md, the bench):
//  - Camera None with every camera setting changed, and Ideal focused where FilmDistance put the
//    film, give the images of before bit for bit (CPU and OpenCL);
//  - shadowgraph as defocus: a thin sheet whose deflection grows linearly across the film,
//    eps = kappa x, imaged by a camera focused on it has no contrast; refocused by g the
//    photon density is 1 / (1 + g kappa) (exact in 1D);
//  - depth of field: a thin sinusoidal phase sheet of period Lambda, Dz from the focus of a lens
//    of aperture D at Z_F, keeps 2 J1(x) / x of its contrast, x = pi d / Lambda, d = D Dz / Z_F;
//  - BOS: the background's displacement M Z_D eps, M = f / (Z_A + Z_D - f), and the object's
//    blur c = D f Z_D / [Z_A (Z_A + Z_D - f)] (1.03 mm at f/4, 0.26 mm at f/16 for f = 105 mm,
//    Z_A = 0.75 m, Z_D = 0.25 m); focusing schlieren's f2_eff = (L - l) L' / L;
//  - each bad value's error names the property.
#include "SchlierenTesting.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <functional>

using namespace schlieren;

namespace
{
constexpr double kPi = 3.14159265358979323846;

// A volume on [-hx, hx] x [-hy, hy] x [-hz, hz] with n - 1 = fn(x, y, z).
struct Grid
{
  std::vector<float> N1, Field;
  std::vector<unsigned char> Smooth;
  Volume V;
  Grid(const int dims[3], const double half[3], const std::function<double(double, double, double)>& fn,
    bool cubic = false)
  {
    for (int a = 0; a < 3; ++a)
    {
      V.Dimensions[a] = dims[a];
      V.Origin[a] = -half[a];
      V.Spacing[a] = 2 * half[a] / (dims[a] - 1);
    }
    N1.resize(V.NumberOfPoints());
    std::size_t p = 0;
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
          N1[p++] = static_cast<float>(fn(V.Origin[0] + i * V.Spacing[0], V.Origin[1] + j * V.Spacing[1],
            V.Origin[2] + k * V.Spacing[2]));
    Field.resize(4 * N1.size());
    if (cubic)
    {
      Smooth.resize(N1.size());
      PackFieldHighOrder(V.Dimensions, V.Spacing, N1.data(), Field.data(), Smooth.data());
      V.Smooth = Smooth.data();
    }
    else
      PackField(V.Dimensions, V.Spacing, N1.data(), Field.data());
    V.Field = Field.data();
  }
};

TraceSettings Base(int nx, int ny)
{
  TraceSettings s;
  s.Device = Backend::CPU;
  s.ViewDirection[0] = 0;
  s.ViewDirection[1] = 0;
  s.ViewDirection[2] = -1; // the beam along -z: s = -z, film x = world x, film y = world y
  s.ViewUp[0] = 0;
  s.ViewUp[1] = 1;
  s.ViewUp[2] = 0;
  s.Resolution[0] = nx;
  s.Resolution[1] = ny;
  s.Passes = 1;
  s.Jitter = false;
  s.UseOctree = false;
  s.Method = Integrator::RK4;
  return s;
}

bool SameImage(const TraceResult& a, const TraceResult& b)
{
  auto same = [](const std::vector<float>& x, const std::vector<float>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) == 0;
  };
  return same(a.Intensity, b.Intensity) && same(a.Deflection, b.Deflection) && same(a.RGB, b.RGB) &&
    same(a.Phase, b.Phase) && same(a.Displacement, b.Displacement);
}

// A small Gaussian sphere of index: every cutoff has something to show.
Grid& Sphere()
{
  static const int dims[3] = { 24, 24, 24 };
  static const double half[3] = { 0.01, 0.01, 0.01 };
  static Grid g(dims, half, [](double x, double y, double z) {
    return 3e-4 * std::exp(-(x * x + y * y + z * z) / (2 * 0.003 * 0.003));
  });
  return g;
}

void TestDefaultsUnchanged(bool opencl)
{
  Grid& g = Sphere();
  for (Cutoff mode : { Cutoff::KnifeEdge, Cutoff::Shadowgraph, Cutoff::ColorFilter, Cutoff::Interferometry,
         Cutoff::BOS })
  {
    TraceSettings s = Base(32, 32);
    s.Device = opencl ? Backend::OpenCL : Backend::CPU;
    s.Passes = 2;
    s.Jitter = true;
    s.Mode = mode;
    s.FilmDistance = mode == Cutoff::Shadowgraph ? 0.5 : 0.0;
    const TraceResult ref = Trace(g.V, s);
    TraceSettings c = s;
    c.CameraFocalLength = 0.05;
    c.FNumber = 2;
    c.CameraDistance = 3;
    c.FocusPlane = 0.3;
    c.SourceGridDistance = 7;
    const TraceResult got = Trace(g.V, c);
    CHECK(SameImage(ref, got), std::string("Camera None: the camera's settings change nothing (") + CutoffName(mode) + ")");
    CHECK(!got.Camera.Active && got.Camera.Model.empty(), "Camera None: no camera read-outs");
    if (mode != Cutoff::Shadowgraph && mode != Cutoff::BOS)
    {
      // (BOS with a camera sees the focus plane, not the background of the film: TestReadouts)
      // Ideal focused where FilmDistance put the film is that film, bit for bit
      TraceSettings d = s;
      d.FilmDistance = 0.004;
      TraceSettings e = s;
      e.Camera = CameraModel::Ideal;
      e.FocusPlane = 0.004;
      CHECK(SameImage(Trace(g.V, d), Trace(g.V, e)),
        std::string("Camera Ideal at FocusPlane = FilmDistance is the film of before (") + CutoffName(mode) + ")");
    }
  }
  std::printf("defaults unchanged (%s)\n", opencl ? "OpenCL" : "CPU");
}

// A thin sheet at z = 0 whose deflection grows linearly across x: n - 1 = c x^2 G(z), G a
// Gaussian of width sigma, so d n/dx = 2 c x G and eps = kappa x, kappa = 2 c Int G dz.
void TestShadowgraphDefocus()
{
  const int dims[3] = { 129, 3, 41 };
  const double half[3] = { 0.064, 0.001, 0.02 }, sigma = 0.003, c = 6.65;
  Grid g(dims, half, [=](double x, double, double z) { return c * x * x * std::exp(-z * z / (2 * sigma * sigma)); });
  // the trace integrates the trilinear interpolant of d n/dx exactly (RK4 is Simpson's rule on
  // each half-voxel step, which does not straddle a grid plane): the trapezoid sum of G
  double sumG = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    const double z = -half[2] + k * g.V.Spacing[2];
    sumG += std::exp(-z * z / (2 * sigma * sigma));
  }
  const double kappaSum = 2 * c * sumG * g.V.Spacing[2];
  const int nx = 256, ny = 4, i0 = 48, i1 = 208; // the block |X| < 40 mm (0.5 mm pixels)
  auto trace = [&](CameraModel cam, double focus) {
    TraceSettings s = Base(nx, ny);
    s.Mode = Cutoff::Shadowgraph;
    s.Camera = cam;
    s.CameraDistance = 5;
    s.FocusPlane = focus;
    return Trace(g.V, s);
  };
  const TraceResult focused = trace(CameraModel::Ideal, 0.0);
  // kappa from the traced deflections (least squares over the block), and against the sum
  double sx = 0, sxx = 0, se = 0, sxe = 0, n = 0;
  double origin[2];
  focused.Film.GetImageOrigin(origin);
  const double pixel = focused.Film.PixelSize;
  double maxDev = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = i0; i < i1; ++i)
    {
      const std::size_t p = static_cast<std::size_t>(j) * nx + i;
      const double X = origin[0] + i * pixel, e = focused.Deflection[2 * p];
      sx += X;
      sxx += X * X;
      se += e;
      sxe += X * e;
      n += 1;
      maxDev = std::max(maxDev, std::fabs(focused.Intensity[p] - 1.0));
    }
  const double kappa = (n * sxe - sx * se) / (n * sxx - sx * sx);
  // the rays move across the sheet by about eps sigma: a second-order change of kappa sigma
  CHECK_NEAR(kappa / kappaSum, 1.0, 2 * kappaSum * sigma + 1e-4, "the sheet's dEps/dx against its trapezoid sum");
  // focused on the sheet's plane: every photon stays in its pixel (it moves by eps times the
  // sheet's half-width at most, far below half a pixel): no contrast at all
  CHECK(maxDev == 0, "shadowgraph focused on a thin object: contrast 0");
  for (double gap : { 2.0, -2.0 })
  {
    const TraceResult r = trace(CameraModel::Ideal, gap);
    double mean = 0;
    for (int j = 0; j < ny; ++j)
      for (int i = i0; i < i1; ++i)
        mean += r.Intensity[static_cast<std::size_t>(j) * nx + i];
    mean /= n;
    // photons land at a (1 + g kappa): the block of 160 pixels takes the emission points of
    // 160 / (1 + g kappa) pixels, a lattice of pixel centres: that count is exact to less than one
    // photon a row, 1 / 160 of the block's mean
    const double expected = 1 / (1 + gap * kappa);
    std::printf("refocused by g = %g m: I/I0 %.6f, 1/(1 + g dEps/dx) %.6f (g kappa = %.4f)\n", gap, mean,
      expected, gap * kappa);
    CHECK_NEAR(mean, expected, 1.0 / (i1 - i0), "shadowgraph refocused by g: I/I0 = 1/(1 + g dEps/dx)");
  }
}

// The sampler: lens points fill the unit disc (a known integral over it).
void TestLensSampler()
{
  const int count = 1024;
  double sr2 = 0, mx = 0;
  for (int p = 0; p < count; ++p)
  {
    double u, v;
    CameraLensSample(1, p, &u, &v);
    CHECK(u * u + v * v <= 1 + 1e-12, "lens points lie in the disc");
    sr2 += u * u + v * v;
    mx = std::max(mx, u * u + v * v);
  }
  // E[r^2] = 1/2 over the disc; r^2 is uniform on [0, 1] (variance 1/12): 3 sigma of iid points
  CHECK_NEAR(sr2 / count, 0.5, 3 * std::sqrt(1.0 / 12 / count), "lens points: mean r^2 of the unit disc");
  CHECK(mx > 0.99, "lens points reach the rim");
}

// Depth of field: the sheet n - 1 = A sin(k x) G(z).
void TestDepthOfField()
{
  const double lambda = 0.016, k = 2 * kPi / lambda, sigma = 0.003;
  const double e0 = 1e-4; // the deflection's amplitude, rad
  const double A = e0 / (k * sigma * std::sqrt(2 * kPi));
  const int dims[3] = { 161, 33, 61 };
  const double half[3] = { 0.04, 0.008, 0.015 };
  Grid g(dims, half, [=](double x, double, double z) { return A * std::sin(k * x) * std::exp(-z * z / (2 * sigma * sigma)); },
    true);
  const double f = 0.1, N = 2, D = f / N, zf = 1.0;
  const int nx = 80, ny = 16, passes = 128;
  auto trace = [&](double focus) {
    TraceSettings s = Base(nx, ny);
    s.Mode = Cutoff::KnifeEdge;
    s.CutoffScale = 1000;
    s.Recon = Reconstruction::Cubic;
    s.StepSize = 2;
    s.Passes = passes;
    s.Camera = CameraModel::Lens;
    s.CameraFocalLength = f;
    s.FNumber = N;
    s.FocusPlane = focus;
    s.CameraDistance = zf + focus; // the lens Z_F = 1 m from the focus plane
    return Trace(g.V, s);
  };
  // the sheet's Fourier coefficient at k over |X| < 32 mm (4 periods) and |Y| < 2 mm
  auto coefficient = [&](const TraceResult& r) {
    double origin[2];
    r.Film.GetImageOrigin(origin);
    std::complex<double> C = 0;
    for (int j = 0; j < ny; ++j)
    {
      const double Y = origin[1] + j * r.Film.PixelSize;
      if (std::fabs(Y) > 0.002)
        continue;
      for (int i = 0; i < nx; ++i)
      {
        const double X = origin[0] + i * r.Film.PixelSize;
        if (std::fabs(X) < 0.032)
          C += double(r.Deflection[2 * (static_cast<std::size_t>(j) * nx + i)]) * std::polar(1.0, -k * X);
      }
    }
    return C;
  };
  const TraceResult ref = trace(0.0);
  const std::complex<double> c0 = coefficient(ref);
  CHECK(ref.Camera.Active && ref.Camera.ApertureSamples == passes, "Lens: aperture samples reported");
  CHECK_NEAR(ref.Camera.BlurPerDepth, D / zf, 1e-15, "camera_blur_per_depth = D / Z_F");
  CHECK_NEAR(ref.Camera.DepthOfField, 2 * ref.Film.PixelSize * zf / D, 1e-15, "camera_depth_of_field = 2 p Z_F / D");
  for (double x : { 1.0, 2.0, -2.0 })
  {
    const double dz = x * lambda * zf / (kPi * D); // d = D |Dz| / Z_F = x Lambda / pi
    const std::complex<double> c = coefficient(trace(dz));
    // the lens points this trace took: the ray toward point p crosses the sheet (s = 0) at
    // X - t_p Dz, t_p = (D / 2) u_p / Z_F; a tilted path through the Gaussian layer smears it by
    // exp(-(k t sigma)^2 / 2) and is longer by 1 / cos = sqrt(1 + t^2 + t_v^2), in the focused
    // reference as well
    std::complex<double> sampled = 0, smear = 0;
    double sumCos = 0;
    for (int p = 0; p < passes; ++p)
    {
      double u, v;
      CameraLensSample(1, p, &u, &v);
      const double t = 0.5 * D * u / zf, tv = 0.5 * D * v / zf;
      const double w = std::sqrt(1 + t * t + tv * tv) * std::exp(-0.5 * (k * t * sigma) * (k * t * sigma));
      sampled += w * std::polar(1.0, -k * t * dz);
      smear += w;
      sumCos += std::cos(k * t * dz);
    }
    const std::complex<double> predicted = sampled / smear, measured = c / c0;
    const double mtf = 2 * std::cyl_bessel_j(1.0, std::fabs(x)) / std::fabs(x);
    // tolerance: cubic Lagrange interpolation of a sinusoid at 32 points a period, at most
    // (9/16) (k h)^4 / 4! of its amplitude, twice (both traces); float32 deflections, 1e-5
    const double h = g.V.Spacing[0], interp = 9.0 / 16 * std::pow(k * h, 4) / 24;
    std::printf("x = %g (Dz = %.4f m): contrast %.5f, the %d lens points' %.5f, 2 J1(x)/x %.5f\n", x, dz,
      std::abs(measured), passes, std::abs(predicted), mtf);
    CHECK_NEAR(std::abs(measured - predicted), 0.0, 2 * interp + 1e-5,
      "defocused sheet: the contrast the sampled aperture gives");
    // the sampled aperture against the disc's transfer function: within 3 standard errors of
    // independent points (the R2 points are stratified, no worse); var cos = (1 + m(2x)) / 2 - m(x)^2
    const double m2 = 2 * std::cyl_bessel_j(1.0, 2 * std::fabs(x)) / (2 * std::fabs(x));
    const double sd = std::sqrt(std::max(0.0, (1 + m2) / 2 - mtf * mtf));
    CHECK_NEAR(sumCos / passes, mtf, 3 * sd / std::sqrt(double(passes)), "the aperture's blur: 2 J1(x)/x");
    CHECK_NEAR(std::abs(measured), mtf, 3 * sd / std::sqrt(double(passes)) + 2 * interp + 1e-3,
      "defocused sheet keeps 2 J1(x)/x of its contrast");
  }
}

void TestReadouts()
{
  Grid& g = Sphere();
  TraceSettings s = Base(8, 8);
  s.Mode = Cutoff::BOS;
  s.Camera = CameraModel::Ideal;
  s.CameraFocalLength = 0.105;
  s.CameraDistance = 0.75;
  const FilmGeometry film = MakeFilm(g.V, s);
  s.BackgroundDistance = 0.25 + film.FrontPlane; // Z_D = 0.25 m from the volume's centre
  const double f = 0.105, za = 0.75, zd = 0.25;
  for (double N : { 4.0, 16.0 })
  {
    s.FNumber = N;
    const TraceResult r = Trace(g.V, s);
    const double M = f / (za + zd - f), c = f / N * f * zd / (za * (za + zd - f));
    std::printf("BOS f/%g: blur %.4f mm, M Z_D %.4f mm/rad, %.1f film pixels/rad\n", N, r.Camera.BOSBlur * 1e3,
      r.Camera.BOSDisplacementPerRadian * 1e3, r.Camera.BOSPixelsPerRadian);
    CHECK_NEAR(r.Camera.BOSMagnification, M, 1e-12, "BOS: M = f / (Z_A + Z_D - f)");
    CHECK_NEAR(r.Camera.BOSDisplacementPerRadian, M * zd, 1e-12, "BOS: displacement M Z_D per radian");
    CHECK_NEAR(r.Camera.BOSBlur, c, 1e-12, "BOS: blur D f Z_D / [Z_A (Z_A + Z_D - f)]");
    // the figures, to their two digits
    CHECK_NEAR(r.Camera.BOSBlur * 1e3, N == 4 ? 1.03 : 0.26, 0.005, "BOS blur: 1.03 mm at f/4, 0.26 mm at f/16");
    const double ma = f / (za - f);
    CHECK_NEAR(r.Camera.BOSPixelsPerRadian, M * zd / (ma * r.Film.PixelSize), 1e-9, "BOS: film pixels per radian");
    CHECK_NEAR(r.Camera.BOSBlurPixels, c / (ma * r.Film.PixelSize), 1e-9, "BOS: blur in film pixels");
  }
  // focusing schlieren: f2_eff = (L - l) L' / L
  TraceSettings k = Base(8, 8);
  k.Camera = CameraModel::Lens;
  k.CameraFocalLength = 0.3;
  k.FNumber = 2;
  k.CameraDistance = 1.0;
  k.SourceGridDistance = 2.0;
  const TraceResult r = Trace(g.V, k);
  const double L = 2.0, l = 1.0, Lp = L * 0.3 / (L - 0.3);
  CHECK_NEAR(r.Camera.FocusingEffectiveF2, (L - l) * Lp / L, 1e-12, "focusing schlieren: f2_eff = (L - l) L'/L");
  CHECK_NEAR(r.Camera.Magnification, 0.3 / (l - 0.3), 1e-12, "camera magnification f / (Z_F - f)");
  // the BOS displacement traced with a camera focused on the background is the film's of before
  TraceSettings b = Base(16, 16);
  b.Mode = Cutoff::BOS;
  b.BackgroundDistance = 0.2;
  const TraceResult none = Trace(g.V, b);
  b.Camera = CameraModel::Ideal;
  b.FocusPlane = MakeFilm(g.V, b).FrontPlane - 0.2;
  const TraceResult ideal = Trace(g.V, b);
  double worst = 0, largest = 0;
  for (std::size_t i = 0; i < none.Displacement.size(); ++i)
  {
    worst = std::max(worst, double(std::fabs(none.Displacement[i] - ideal.Displacement[i])));
    largest = std::max(largest, double(std::fabs(none.Displacement[i])));
  }
  // float32 landings of about 0.01 world units: a few of their roundings
  CHECK(largest > 1e-6 && worst <= 8 * 0.01 * 6e-8, "BOS: the camera focused on the background sees the displacement of before");
}

void TestErrors()
{
  Grid& g = Sphere();
  auto run = [&](std::function<void(TraceSettings&)> change) {
    return [&g, change]() {
      TraceSettings s = Base(8, 8);
      change(s);
      Trace(g.V, s);
    };
  };
  schtest::ExpectError("Camera 3", run([](TraceSettings& s) { s.Camera = static_cast<CameraModel>(3); }), { "Camera", "Lens" });
  schtest::ExpectError("CameraFocalLength 0", run([](TraceSettings& s) { s.CameraFocalLength = 0; }),
    { "CameraFocalLength", "[0.001, 1000] m" });
  schtest::ExpectError("FNumber 0.1", run([](TraceSettings& s) { s.FNumber = 0.1; }), { "FNumber", "[0.5, 1000]" });
  schtest::ExpectError("CameraDistance -1", run([](TraceSettings& s) { s.CameraDistance = -1; }), { "CameraDistance", "-1" });
  schtest::ExpectError("FocusPlane NaN", run([](TraceSettings& s) { s.FocusPlane = std::nan(""); }), { "FocusPlane", "nan" });
  schtest::ExpectError("SourceGridDistance 0", run([](TraceSettings& s) { s.SourceGridDistance = 0; }),
    { "SourceGridDistance", "[0.001, 1e6] m" });
  schtest::ExpectError("FocusPlane 1e6 volumes away", run([](TraceSettings& s) {
    s.Camera = CameraModel::Ideal;
    s.FocusPlane = -9e5;
    s.CameraDistance = 1e5;
  }), { "FocusPlane", "1e6 times the volume's size" });
  schtest::ExpectError("focus within the focal length", run([](TraceSettings& s) {
    s.Camera = CameraModel::Lens;
    s.CameraDistance = 0.5;
    s.FocusPlane = 0.45;
  }), { "CameraDistance", "FocusPlane", "CameraFocalLength" });
  // issue 48: a lens inside the test section (the sphere's box reaches 0.01 m toward the camera)
  // and BOS read-outs with the volume's centre within the focal length (M_A = f / (Z_A - f) < 0)
  for (CameraModel m : { CameraModel::Ideal, CameraModel::Lens })
    schtest::ExpectError("the lens inside the volume", run([m](TraceSettings& s) {
      s.Camera = m;
      s.CameraFocalLength = 0.002;
      s.CameraDistance = 0.005;
      s.FocusPlane = 0.0;
    }), { "CameraDistance 0.005 m puts the lens inside the volume", "at least 0.01 m" });
  {
    // just outside the box: traced
    TraceSettings s = Base(8, 8);
    s.Camera = CameraModel::Ideal;
    s.CameraFocalLength = 0.002;
    s.CameraDistance = 0.01;
    CHECK(!Trace(g.V, s).Intensity.empty(), "the lens at the face of a box of half-depth 0.01 m: traced");
  }
  schtest::ExpectError("BOS within the focal length", run([](TraceSettings& s) {
    s.Mode = Cutoff::BOS;
    s.Camera = CameraModel::Ideal;
    s.CameraFocalLength = 0.1;
    s.CameraDistance = 0.05;
    s.FocusPlane = -0.2; // focused on a background: Z_F = 0.25 m > f
  }), { "Cutoff BOS", "CameraDistance", "0.05 m is not more than CameraFocalLength 0.1 m", "M_A = f / (Z_A - f) = -2" });
  schtest::ExpectError("BOS at the focal length", run([](TraceSettings& s) {
    s.Mode = Cutoff::BOS;
    s.Camera = CameraModel::Lens;
    s.CameraFocalLength = 0.1;
    s.CameraDistance = 0.1;
    s.FocusPlane = -0.2;
  }), { "M_A = f / (Z_A - f) = inf" });
}
}

int main()
{
  TestLensSampler();
  TestErrors();
  TestReadouts();
  TestShadowgraphDefocus();
  TestDepthOfField();
  TestDefaultsUnchanged(false);
  if (schtest::HaveOpenCL())
    TestDefaultsUnchanged(true);
  return schtest::Finish();
}
