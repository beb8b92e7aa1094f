// SPDX-License-Identifier: BSD-3-Clause
// A photograph beside the image (issue 51), against known answers: synthetic photographs made from
// our own traced images with a known similarity transform, vignetting, a camera gamma, a blur and
// Poisson noise, at the ends of the ranges, and the stated uncertainty against the error;
// the same flow with its shock moved a known distance; two lines that cross or meet, one moved;
// photographs of something else, of noise, and blank ones refused.
// `TestEnginePhotograph coverage N [first]` prints the stated uncertainty against the error over N
// random cameras instead (docs/CFD.md's table).
#include "SchlierenEngine.h"
#include "SchlierenPhotograph.h"
#include "SchlierenScenes.h"
#include "SchlierenTesting.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace schlieren;

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr int Film = 128; // film pixels a side

/** A blast wave off the centre beside a Gaussian lump (no symmetry leaves a transform unseen),
 * traced on the CPU with the knife normal along x and a fixed cutoff scale. */
struct Traced
{
  std::vector<float> I;
  double Origin[2], Pixel;
};

Traced TraceFlow(double blastTime, bool lump = true, double cutoff = 0, bool plume = false)
{
  const int n = 56;
  const int dims[3] = { n, n, n };
  const double origin[3] = { -1, -1, -1 }, spacing[3] = { 2.0 / (n - 1), 2.0 / (n - 1), 2.0 / (n - 1) };
  std::vector<float> n1(n * n * n), other(n * n * n), field(4 * n1.size());
  SceneParameters blast;
  blast.Center[0] = 0.2;
  blast.Center[1] = 0.15;
  blast.Radius = 0.4;
  blast.Width = 0.04;
  blast.Time = blastTime;
  if (plume)
  {
    // something else: a helium plume rising through the film
    SceneParameters p;
    p.Radius = 0.15;
    p.Width = 1.6;
    p.Amplitude = 1.0;
    p.Center[0] = -0.1;
    FillScene(Scene::HeliumPlume, p, dims, origin, spacing, n1.data(), nullptr);
  }
  else
    FillScene(Scene::BlastWave, blast, dims, origin, spacing, n1.data(), nullptr);
  if (lump && !plume)
  {
    SceneParameters g;
    g.Amplitude = 3e-3;
    g.Width = 0.2;
    g.Center[0] = -0.45;
    g.Center[1] = -0.4;
    FillScene(Scene::GaussianSphere, g, dims, origin, spacing, other.data(), nullptr);
    for (std::size_t q = 0; q < n1.size(); ++q)
      n1[q] += other[q];
    // and a plane shock across the film, at an angle to both film axes
    SceneParameters shock;
    shock.Center[0] = -0.25;
    shock.Width = 0.03;
    shock.Mach = 1.3;
    const int d2[3] = { n, n, n };
    FillScene(Scene::NormalShock, shock, d2, origin, spacing, other.data(), nullptr);
    const double ambient = other[0];
    for (std::size_t q = 0; q < n1.size(); ++q)
      n1[q] += other[q] - static_cast<float>(ambient);
  }
  PackField(dims, spacing, n1.data(), field.data());
  Volume v;
  for (int a = 0; a < 3; ++a)
  {
    v.Dimensions[a] = dims[a];
    v.Origin[a] = origin[a];
    v.Spacing[a] = spacing[a];
  }
  v.Field = field.data();
  TraceSettings s;
  s.Device = Backend::CPU;
  s.Resolution[0] = s.Resolution[1] = Film;
  s.Passes = 4;
  s.CutoffScale = cutoff;
  TraceResult r = Trace(v, s);
  Traced t;
  t.I = r.Intensity;
  r.Film.GetImageOrigin(t.Origin);
  t.Pixel = r.Film.PixelSize;
  return t;
}

struct Camera
{
  double Scale = 1, RotationDeg = 0, Shift[2] = { 0, 0 };
  int W = 200, H = 180;
  double Gamma = 1, Vignetting = 0, Blur = 0, Photons = 0, Gain = 0.8;
};

/** The photograph a camera takes of `film`: the film's pixel (i, j) lands at
 * s R (i - c) + c' + shift; grey = Gain * vignetting * I^gamma, blurred, Poisson noise. */
std::vector<float> Photograph(const std::vector<float>& film, const Camera& c, unsigned seed = 7)
{
  const double th = c.RotationDeg * Pi / 180, cs = std::cos(th), sn = std::sin(th);
  std::vector<float> p(static_cast<std::size_t>(c.W) * c.H);
  const double fc = 0.5 * (Film - 1);
  for (int v = 0; v < c.H; ++v)
    for (int u = 0; u < c.W; ++u)
    {
      const double a = u - 0.5 * (c.W - 1) - c.Shift[0], b = v - 0.5 * (c.H - 1) - c.Shift[1];
      const double x = (cs * a + sn * b) / c.Scale + fc, y = (-sn * a + cs * b) / c.Scale + fc;
      double I = 0.5; // outside the film: the free stream
      if (x >= 0 && y >= 0 && x <= Film - 1 && y <= Film - 1)
      {
        const int i = std::min(static_cast<int>(x), Film - 2), j = std::min(static_cast<int>(y), Film - 2);
        const double fx = x - i, fy = y - j;
        auto at = [&](int ii, int jj) { return film[static_cast<std::size_t>(jj) * Film + ii]; };
        I = (1 - fy) * ((1 - fx) * at(i, j) + fx * at(i + 1, j)) + fy * ((1 - fx) * at(i, j + 1) + fx * at(i + 1, j + 1));
      }
      const double r2 = (std::pow(u - 0.5 * c.W, 2) + std::pow(v - 0.5 * c.H, 2)) / (0.25 * (c.W * c.W + c.H * c.H));
      p[static_cast<std::size_t>(v) * c.W + u] =
        static_cast<float>(c.Gain * (1 - c.Vignetting * r2) * std::pow(std::max(I, 0.0), c.Gamma));
    }
  if (c.Blur > 0)
  {
    const int r = static_cast<int>(std::ceil(3 * c.Blur));
    std::vector<double> k(2 * r + 1);
    double sum = 0;
    for (int t = -r; t <= r; ++t)
      sum += k[t + r] = std::exp(-0.5 * t * t / (c.Blur * c.Blur));
    for (int pass = 0; pass < 2; ++pass)
    {
      std::vector<float> q(p.size());
      for (int v = 0; v < c.H; ++v)
        for (int u = 0; u < c.W; ++u)
        {
          double s = 0;
          for (int t = -r; t <= r; ++t)
          {
            const int uu = pass ? u : std::clamp(u + t, 0, c.W - 1), vv = pass ? std::clamp(v + t, 0, c.H - 1) : v;
            s += k[t + r] / sum * p[static_cast<std::size_t>(vv) * c.W + uu];
          }
          q[static_cast<std::size_t>(v) * c.W + u] = static_cast<float>(s);
        }
      p.swap(q);
    }
  }
  if (c.Photons > 0)
  {
    std::mt19937 rng(seed);
    for (float& x : p)
    {
      std::poisson_distribution<int> d(std::max(0.0, x * c.Photons));
      x = static_cast<float>(d(rng) / c.Photons);
    }
  }
  return p;
}

/** The error of a found transform at the film's corners (film pixels) and in rotation (degrees). */
void TransformError(const PhotographResult& r, const Camera& c, double& edge, double& rotation)
{
  edge = 0;
  const double fc = 0.5 * (Film - 1);
  for (int corner = 0; corner < 4; ++corner)
  {
    const double x = (corner & 1 ? Film - 1 : 0) - fc, y = (corner & 2 ? Film - 1 : 0) - fc;
    auto map = [&](double s, double deg, double tx, double ty, double& u, double& v) {
      const double th = deg * Pi / 180;
      u = s * (std::cos(th) * x - std::sin(th) * y) + tx;
      v = s * (std::sin(th) * x + std::cos(th) * y) + ty;
    };
    double u0, v0, u1, v1;
    map(c.Scale, c.RotationDeg, c.Shift[0], c.Shift[1], u0, v0);
    map(r.Scale, r.Rotation, r.Shift[0], r.Shift[1], u1, v1);
    edge = std::max(edge, std::hypot(u1 - u0, v1 - v0) / c.Scale); // in film pixels
  }
  rotation = std::fabs(r.Rotation - c.RotationDeg);
}

/** SCHLIEREN_PHOTOGRAPH_DUMP=folder: raw float images to look at. */
void Dump(const std::string& name, const std::vector<float>& v, int w, int h)
{
  const char* dir = std::getenv("SCHLIEREN_PHOTOGRAPH_DUMP");
  if (!dir || v.empty())
    return;
  const std::string path = std::string(dir) + "/" + name + "_" + std::to_string(w) + "x" + std::to_string(h) + ".f32";
  if (FILE* f = std::fopen(path.c_str(), "wb"))
  {
    std::fwrite(v.data(), sizeof(float), v.size(), f);
    std::fclose(f);
  }
}

PhotographResult Register(const Traced& f, const std::vector<float>& photo, const Camera& c, const std::string& settings)
{
  const int fs[2] = { Film, Film }, ps[2] = { c.W, c.H };
  return RegisterPhotograph(fs, f.Origin, f.Pixel, f.I.data(), ps, photo.data(), ParsePhotographSettings(settings));
}

/** Two step edges in grey (0.5 +- 0.15 tanh(d / 1.2 px) each, d the distance to the line) through
 * the film's centre, along `a1` and `a2` degrees, the second moved `move` pixels along its normal;
 * `touching`: the second only on one side of the first (a reflected shock meeting the incident
 * one), else they cross. */
std::vector<float> TwoLines(double a1, double a2, double move, bool touching)
{
  std::vector<float> v(static_cast<std::size_t>(Film) * Film);
  const double c = 0.5 * (Film - 1), w = 1.2;
  const double n1[2] = { -std::sin(a1 * Pi / 180), std::cos(a1 * Pi / 180) };
  const double n2[2] = { -std::sin(a2 * Pi / 180), std::cos(a2 * Pi / 180) };
  for (int j = 0; j < Film; ++j)
    for (int i = 0; i < Film; ++i)
    {
      const double d1 = (i - c) * n1[0] + (j - c) * n1[1], d2 = (i - c) * n2[0] + (j - c) * n2[1] - move;
      const double side = touching ? 0.5 * (1 + std::tanh(d1 / w)) : 1.0;
      v[static_cast<std::size_t>(j) * Film + i] = static_cast<float>(0.5 + 0.15 * std::tanh(d1 / w) + 0.15 * side * std::tanh(d2 / w));
    }
  return v;
}

/** A camera drawn at random over the ranges: scale 0.7-1.4 (log-uniform), rotation +-10 deg,
 * shift up to a quarter of the film (in the film's pixels), gamma 0.5-2 (log-uniform), vignetting
 * 0-0.3, blur 1-2 px, 500-3000 photons a unit of grey; the photograph 1.15-1.35 times the film's
 * extent. */
Camera RandomCamera(unsigned seed)
{
  std::mt19937 rng(1000 + seed);
  std::uniform_real_distribution<double> u(0, 1);
  Camera c;
  c.Scale = std::exp(std::log(0.7) + u(rng) * std::log(2.0));
  c.RotationDeg = -10 + 20 * u(rng);
  const double r = 0.25 * Film * std::sqrt(u(rng)), a = 2 * Pi * u(rng);
  c.Shift[0] = c.Scale * r * std::cos(a);
  c.Shift[1] = c.Scale * r * std::sin(a);
  c.Gamma = std::exp(std::log(0.5) + u(rng) * std::log(4.0));
  c.Vignetting = 0.3 * u(rng);
  c.Blur = 1 + u(rng);
  c.Photons = 500 + 2500 * u(rng);
  c.W = static_cast<int>(c.Scale * Film * (1.15 + 0.2 * u(rng)));
  c.H = static_cast<int>(c.Scale * Film * (1.15 + 0.2 * u(rng)));
  return c;
}

/** The corner error's parts: the scale's and rotation's (at the film's corner radius) and the
 * shift's, film pixels, signed. */
void ErrorParts(const PhotographResult& r, const Camera& c, double parts[4])
{
  const double rc = 0.5 * std::hypot(Film, Film);
  parts[0] = std::log(r.Scale / c.Scale) * rc;
  parts[1] = (r.Rotation - c.RotationDeg) * Pi / 180 * rc;
  parts[2] = (r.Shift[0] - c.Shift[0]) / c.Scale;
  parts[3] = (r.Shift[1] - c.Shift[1]) / c.Scale;
}

/** `TestEnginePhotograph coverage N [first]`: the stated corner uncertainty against the error found
 * over N random cameras (a table, not a test). */
int Coverage(const Traced& flow, int n, int first)
{
  std::printf("seed scale   rot  shift  gamma blur photons | found  stated ratio (noise spread) | dlogS*rc dtheta*rc dx dy (film px) | gamma found +- ratio | s\n");
  std::vector<double> ratios, gammaRatios;
  int refused = 0;
  for (int seed = first; seed < first + n; ++seed)
  {
    const Camera c = RandomCamera(static_cast<unsigned>(seed));
    const std::vector<float> photo = Photograph(flow.I, c, static_cast<unsigned>(seed));
    const PhotographResult r = Register(flow, photo, c, "");
    double edge, rot, parts[4];
    TransformError(r, c, edge, rot);
    ErrorParts(r, c, parts);
    std::printf("%4d %5.3f %5.1f %5.1f %5.2f %4.2f %5.0f | %6.3f %6.3f %5.2f (%5.3f %5.3f) | %7.3f %7.3f %6.3f %6.3f | %5.3f %5.3f +- %5.3f %5.2f | %4.1f%s\n",
      seed, c.Scale, c.RotationDeg, std::hypot(c.Shift[0], c.Shift[1]) / c.Scale, c.Gamma, c.Blur, c.Photons, edge,
      r.EdgeUncertainty, edge / r.EdgeUncertainty, r.EdgeNoise, r.EdgeSpread, parts[0], parts[1], parts[2], parts[3],
      c.Gamma, r.Gamma, r.GammaError, std::fabs(r.Gamma - c.Gamma) / r.GammaError, r.Seconds, r.Match ? "" : "  REFUSED");
    std::fflush(stdout);
    if (!r.Match)
    {
      ++refused;
      continue;
    }
    ratios.push_back(edge / r.EdgeUncertainty);
    gammaRatios.push_back(std::fabs(r.Gamma - c.Gamma) / r.GammaError);
  }
  std::sort(ratios.begin(), ratios.end());
  auto q = [&](double f) { return ratios.empty() ? 0.0 : ratios[std::min(ratios.size() - 1, static_cast<std::size_t>(f * ratios.size()))]; };
  int within1 = 0, within2 = 0, within3 = 0;
  for (double x : ratios)
  {
    within1 += x <= 1;
    within2 += x <= 2;
    within3 += x <= 3;
  }
  std::printf("%zu registered (%d refused): found/stated median %.2f, 68th %.2f, 95th %.2f, min %.2f, max %.2f; "
              "within 1x %d, 2x %d, 3x %d\n", ratios.size(), refused, q(0.5), q(0.68), q(0.95),
    ratios.empty() ? 0 : ratios.front(), ratios.empty() ? 0 : ratios.back(), within1, within2, within3);
  std::sort(gammaRatios.begin(), gammaRatios.end());
  if (!gammaRatios.empty())
    std::printf("gamma: |found - true| / stated median %.2f, max %.2f\n", gammaRatios[gammaRatios.size() / 2], gammaRatios.back());
  return 0;
}
} // namespace

int main(int argc, char** argv)
{
  const Traced flow = TraceFlow(1.0, true, 0);
  if (argc >= 3 && std::string(argv[1]) == "coverage")
    return Coverage(flow, std::atoi(argv[2]), argc >= 4 ? std::atoi(argv[3]) : 1);
  std::printf("film %d x %d, pixel %.4g world units\n", Film, Film, flow.Pixel);

  // 1. known transforms, camera defects and noise at the ends of the ranges (scale 0.7 and
  // 1.4, rotation -10 and +10 deg, a shift of a quarter of the film, gamma 0.5 and 2, blur 1 and 2
  // photograph pixels, vignetting 0.2-0.3, 1000-2000 photons a unit of grey): the transform within
  // 0.5 px at the film's corners and 0.2 deg; the stated corner uncertainty covering the error as
  // the coverage table (`TestEnginePhotograph coverage 30`, docs/CFD.md) says it does over 30
  // random cameras: found / stated 0.17 to 2.43, geometric mean 0.52; here each under 3 and over
  // 0.1 (the third camera, the hardest, states 7 times its error: leaving out parts of its film
  // moves the transform by 2 px), their geometric mean within 0.25 to 2; gamma within 5 % (the
  // table's worst: 4.1 %, a bias, median +2 %, that gamma_error does not include)
  struct Case
  {
    const char* Name;
    Camera C;
  };
  std::vector<Case> cases;
  {
    const double q = 0.25 * Film; // a quarter of the film, film pixels
    auto camera = [&](double scale, double deg, double shiftAngle, double gamma, double blur, double vignetting,
                    double photons, int w, int h) {
      Camera c;
      c.Scale = scale;
      c.RotationDeg = deg;
      c.Shift[0] = scale * q * std::cos(shiftAngle * Pi / 180);
      c.Shift[1] = scale * q * std::sin(shiftAngle * Pi / 180);
      c.Gamma = gamma;
      c.Blur = blur;
      c.Vignetting = vignetting;
      c.Photons = photons;
      c.W = w;
      c.H = h;
      return c;
    };
    cases.push_back({ "scale 1.4, 10 deg, shift a quarter film at -45 deg, gamma 0.5, blur 2", camera(1.4, 10, -45, 0.5, 2, 0.3, 1000, 230, 220) });
    cases.push_back({ "scale 0.7, -10 deg, shift a quarter film at 135 deg, gamma 2, blur 1", camera(0.7, -10, 135, 2, 1, 0.2, 2000, 125, 115) });
    cases.push_back({ "scale 0.7, 10 deg, shift a quarter film at 180 deg, gamma 0.5, blur 2", camera(0.7, 10, 180, 0.5, 2, 0.3, 1500, 150, 140) });
    cases.push_back({ "scale 1.4, -10 deg, shift a quarter film at 90 deg, gamma 2, blur 1", camera(1.4, -10, 90, 2, 1, 0.2, 1500, 220, 230) });
  }
  double logRatio = 0; // the geometric mean of found / stated over the cases
  for (const Case& k : cases)
  {
    const std::vector<float> photo = Photograph(flow.I, k.C);
    const PhotographResult r = Register(flow, photo, k.C, "");
    const std::string tag = std::to_string(&k - cases.data());
    Dump("film", flow.I, Film, Film);
    Dump("photo" + tag, photo, k.C.W, k.C.H);
    Dump("calibrated" + tag, r.Calibrated, Film, Film);
    Dump("difference" + tag, r.Difference, Film, Film);
    double edge, rot;
    TransformError(r, k.C, edge, rot);
    std::printf("%s: match %d score %.3f (threshold %.3f, scrambled %.3f, coarse %.3f) scale %.4f rot %.3f "
                "shift %.2f %.2f; corner error %.3f px (sigma %.3f), rotation error %.4f deg (sigma %.4f); "
                "(noise %.3f, spread %.3f); gamma %.3f +- %.3f (true %.2f), vignetting %.3f, %.2f s\n  %s\n",
      k.Name, r.Match, r.Score, r.Threshold, r.NullScore, r.CoarseScore, r.Scale, r.Rotation, r.Shift[0],
      r.Shift[1], edge, r.EdgeUncertainty, rot, r.Sigma[2], r.EdgeNoise, r.EdgeSpread, r.Gamma, r.GammaError, k.C.Gamma, r.Vignetting,
      r.Seconds, r.Reason.c_str());
    CHECK(r.Match, std::string(k.Name) + ": registered");
    CHECK(edge < 0.5, std::string(k.Name) + ": corner error " + std::to_string(edge) + " px");
    CHECK(rot < 0.2, std::string(k.Name) + ": rotation error " + std::to_string(rot) + " deg");
    CHECK(std::fabs(r.Gamma - k.C.Gamma) < 0.05 * k.C.Gamma, std::string(k.Name) + ": gamma " + std::to_string(r.Gamma));
    CHECK(edge <= 3 * r.EdgeUncertainty && r.EdgeUncertainty <= 10 * edge,
      std::string(k.Name) + ": the corner error " + std::to_string(edge) + " px against the stated " +
        std::to_string(r.EdgeUncertainty));
    logRatio += std::log(edge / r.EdgeUncertainty) / cases.size();
  }
  std::printf("found / stated: geometric mean %.2f over the %zu cameras\n", std::exp(logRatio), cases.size());
  CHECK(std::exp(logRatio) > 0.25 && std::exp(logRatio) < 2,
    "the stated corner uncertainty neither far above nor far below the errors: found / stated " +
      std::to_string(std::exp(logRatio)) + " (geometric mean; 0.52 over the coverage table's 30 cameras)");
  // 2. the same flow with its blast wave later (radius 0.4 t^0.4 from t = 1 to 1.3: 0.0442 world
  // units, 2.8 film pixels), photographed at a known magnification: the blast's lines are that far
  // apart within a cell of the volume (2/55), the plane shock's within half a cell
  {
    const double cutoff = 4000; // the same knife for both times
    const Traced early = TraceFlow(1.0, true, cutoff), late = TraceFlow(1.3, true, cutoff);
    Camera c;
    c.Scale = 1.2;
    c.Shift[0] = 6;
    c.Shift[1] = -4;
    c.Gamma = 0.8;
    c.Vignetting = 0.2;
    c.Blur = 1.0;
    c.Photons = 2000;
    const std::vector<float> photo = Photograph(late.I, c);
    // two fiducial marks whose places the user knows on the model and sees on the photograph (a
    // moved shock would pull a correlation: the lines are compared on the marks' registration)
    std::string pairs = "PointPairs=";
    for (const double* w : { (const double[]){ -0.8, -0.7 }, (const double[]){ 0.75, 0.8 } })
    {
      const double i = (w[0] - early.Origin[0]) / early.Pixel - 0.5 * (Film - 1);
      const double j = (w[1] - early.Origin[1]) / early.Pixel - 0.5 * (Film - 1);
      pairs += std::to_string(c.Scale * i + 0.5 * (c.W - 1) + c.Shift[0]) + " " +
        std::to_string(c.Scale * j + 0.5 * (c.H - 1) + c.Shift[1]) + " " + std::to_string(w[0]) + " " +
        std::to_string(w[1]) + " ";
    }
    const PhotographResult r = Register(early, photo, c, pairs + "\nRefine=None");
    const double move = 0.4 * (std::pow(1.3, 0.4) - 1), cell = 2.0 / 55;
    double edge, rot;
    TransformError(r, c, edge, rot);
    std::printf("moved blast: match %d score %.3f (threshold %.3f) corner error %.3f px; %zu lines %s\n", r.Match, r.Score, r.Threshold, edge, r.Lines.size(), r.Warnings.c_str());
    CHECK(r.Warnings.empty() && r.Score > r.Threshold, "the moved blast's photograph correlates above the threshold at its marks");
    CHECK(r.Match && edge < 0.05, "the moved blast's photograph placed by its marks (corner error " + std::to_string(edge) + " px)");
    Dump("moved_distance", r.LineDistance, Film, Film);
    Dump("moved_calibrated", r.Calibrated, Film, Film);
    // the distance map: along the blast's right side, and along the plane shock far from the blast
    std::vector<float> blast, shock;
    for (int j = 0; j < Film; ++j)
      for (int i = 0; i < Film; ++i)
      {
        const float d = r.LineDistance[static_cast<std::size_t>(j) * Film + i];
        if (std::isnan(d))
          continue;
        const double x = early.Origin[0] + i * early.Pixel, y = early.Origin[1] + j * early.Pixel;
        const double rb = std::hypot(x - 0.2, y - 0.15);
        if (rb > 0.3 && rb < 0.55 && x > 0.3)
          blast.push_back(d);
        else if (std::fabs(x + 0.25) < 0.05 && std::fabs(y - 0.15) > 0.5)
          shock.push_back(d);
      }
    auto median = [](std::vector<float> v) {
      std::sort(v.begin(), v.end());
      return v.empty() ? -1.0 : double(v[v.size() / 2]);
    };
    std::printf("  the blast's right side: %zu line pixels, median distance %.4f (moved %.4f, a cell %.4f); "
                "the plane shock: %zu, median %.4f\n", blast.size(), median(blast), move, cell, shock.size(), median(shock));
    CHECK(blast.size() >= 20 && std::fabs(median(blast) - move) < cell,
      "the blast's lines moved " + std::to_string(median(blast)) + " (true " + std::to_string(move) + ")");
    CHECK(shock.size() >= 10 && median(shock) < 0.5 * cell, "the plane shock did not move: " + std::to_string(median(shock)));
    int near = 0;
    for (const PhotographLine& l : r.Lines)
      if (l.Image == 0 && l.Distance >= 0 && std::fabs(l.Distance - move) < cell)
        ++near;
    CHECK(near >= 1, "a line of the film is reported about the move apart");
  }

  // 3. lines that meet: two straight edges crossing (an X) or touching (a Y: the second on one
  // side of the first only), the second moved 3 pixels along its normal in the photograph (the
  // same grid, placed by two marks). Each film line is one of the two (not a walk that turns from
  // one onto the other at the junction: 85 % of its points or more nearer to one of them, the
  // junction's 4 pixels aside), the first's lines 0 apart and the second's 3, within 0.25 pixel
  // (the ridges' sub-pixel positions on noise-free edges are good to about 0.1 pixel); each edge
  // found over at least 60 % of its length.
  for (const bool touching : { false, true })
  {
    const double a1 = 80, a2 = 25, move = 3;
    Traced f;
    f.I = TwoLines(a1, a2, 0, touching);
    f.Origin[0] = f.Origin[1] = 0;
    f.Pixel = 1;
    Camera c;
    c.W = c.H = Film;
    const std::vector<float> photo = TwoLines(a1, a2, move, touching);
    const PhotographResult r = Register(f, photo, c, "PointPairs=0 0 0 0 127 127 127 127\nRefine=None");
    const char* name = touching ? "touching lines" : "crossing lines";
    Dump(std::string(touching ? "touching" : "crossing") + "_distance", r.LineDistance, Film, Film);
    const double cc = 0.5 * (Film - 1);
    const double n1[2] = { -std::sin(a1 * Pi / 180), std::cos(a1 * Pi / 180) };
    const double n2[2] = { -std::sin(a2 * Pi / 180), std::cos(a2 * Pi / 180) };
    double length[2] = { 0, 0 };
    int mixed = 0, wrong = 0, lines = 0;
    for (const PhotographLine& l : r.Lines)
    {
      if (l.Image != 0 || l.Points.size() < 2 * 16)
        continue;
      int near[2] = { 0, 0 };
      for (std::size_t a = 0; a + 1 < l.Points.size(); a += 2)
      {
        const double x = l.Points[a] - cc, y = l.Points[a + 1] - cc;
        if (std::hypot(x, y) < 4)
          continue;
        const double d1 = std::fabs(x * n1[0] + y * n1[1]), d2 = std::fabs(x * n2[0] + y * n2[1]);
        ++near[d2 < d1];
      }
      const int which = near[1] > near[0];
      const double purity = double(near[which]) / std::max(1, near[0] + near[1]);
      const double expected = which ? move : 0;
      ++lines;
      length[which] += l.Points.size() / 2;
      mixed += purity < 0.85;
      wrong += !(std::fabs(l.Distance - expected) < 0.25);
      std::printf("  %s: film line of %zu points, %.0f %% along edge %d, distance %.3f px (expected %.0f), "
                  "matched %.2f\n", name, l.Points.size() / 2, 100 * purity, which + 1, l.Distance, expected, l.Matched);
    }
    // the edges' lengths inside the film (the first crosses it; the second crosses or half does)
    const double full1 = Film / std::fabs(std::sin(a1 * Pi / 180)), full2 = Film / std::fabs(std::cos(a2 * Pi / 180));
    const double want[2] = { 0.6 * full1, 0.6 * (touching ? 0.5 : 1.0) * full2 };
    std::printf("%s: %d film lines, edge 1 %.0f points (want %.0f), edge 2 %.0f (want %.0f)\n", name, lines,
      length[0], want[0], length[1], want[1]);
    CHECK(r.Match, std::string(name) + ": placed by the marks");
    CHECK(mixed == 0, std::string(name) + ": " + std::to_string(mixed) + " film lines run along both edges");
    CHECK(wrong == 0, std::string(name) + ": " + std::to_string(wrong) + " film lines at a distance other than their edge's move");
    CHECK(length[0] >= want[0] && length[1] >= want[1], std::string(name) + ": both edges found over 60 % of their length");
  }

  // 4. refused: a photograph of something else, of noise, a blank one
  {
    Camera c;
    c.Scale = 1.1;
    c.RotationDeg = 3;
    c.Photons = 2000;
    c.Blur = 1;
    const Traced plume = TraceFlow(1.0, false, 0, true);
    const std::vector<float> other = Photograph(plume.I, c);
    std::vector<float> noise(static_cast<std::size_t>(c.W) * c.H), blank(noise.size(), 0.4f);
    std::mt19937 rng(3);
    std::poisson_distribution<int> d(1000);
    for (float& v : noise)
      v = d(rng) / 2000.f;
    struct Bad
    {
      const char* Name;
      const std::vector<float>* Photo;
      const char* Needle;
    };
    Dump("plume", plume.I, Film, Film);
    for (const Bad& b : { Bad{ "another flow", &other, "does not match" }, Bad{ "noise", &noise, "does not match" },
           Bad{ "blank", &blank, "blank" } })
    {
      const PhotographResult r = Register(flow, *b.Photo, c, "");
      std::printf("%s: match %d score %.3f threshold %.3f (scrambled %.3f): %s\n", b.Name, r.Match, r.Score,
        r.Threshold, r.NullScore, r.Reason.c_str());
      CHECK(!r.Match && r.Reason.find(b.Needle) != std::string::npos, std::string(b.Name) + " refused: " + r.Reason);
      CHECK(r.Score < r.Threshold || r.Reason.find("blank") != std::string::npos, std::string(b.Name) + ": the score is below the threshold");
    }
    // noise placed by PointPairs with Refine None: the user's transform is kept, and the warning says
    // that the photograph does not correlate there
    const PhotographResult r = Register(flow, noise, c, "PointPairs=10 10 -0.9 -0.9 190 170 0.9 0.9\nRefine=None");
    std::printf("noise at the user's pairs: match %d score %.3f threshold %.3f: %s\n", r.Match, r.Score, r.Threshold, r.Warnings.c_str());
    CHECK(r.Match && r.Warnings.find("below the") != std::string::npos, "noise at the user's pairs: warned");
  }
  return schtest::Finish();
}
