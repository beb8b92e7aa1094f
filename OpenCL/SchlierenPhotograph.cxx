// SPDX-License-Identifier: BSD-3-Clause
// A photograph beside the traced image (SchlierenPhotograph.h): registration, grey calibration,
// strong-gradient lines and their distances. Plain C++ on the CPU: the images are 2D and small.
#include "SchlierenPhotograph.h"

#include "SchlierenEngine.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <cstdio>

namespace schlieren
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

/** A grey image, x fastest. */
struct Image
{
  int W = 0, H = 0;
  std::vector<float> V;
  Image() = default;
  Image(int w, int h, float fill = 0.f)
    : W(w)
    , H(h)
    , V(static_cast<std::size_t>(w) * h, fill)
  {
  }
  float& at(int i, int j) { return V[static_cast<std::size_t>(j) * W + i]; }
  float at(int i, int j) const { return V[static_cast<std::size_t>(j) * W + i]; }
  /** Bilinear at (x, y) pixel coordinates; false outside [0, W-1] x [0, H-1]. */
  bool Sample(double x, double y, float& out) const
  {
    if (!(x >= 0 && y >= 0 && x <= W - 1 && y <= H - 1))
      return false;
    int i = std::min(static_cast<int>(x), std::max(W - 2, 0));
    int j = std::min(static_cast<int>(y), std::max(H - 2, 0));
    const double fx = x - i, fy = y - j;
    const int i1 = std::min(i + 1, W - 1), j1 = std::min(j + 1, H - 1);
    out = static_cast<float>((1 - fy) * ((1 - fx) * at(i, j) + fx * at(i1, j)) +
      fy * ((1 - fx) * at(i, j1) + fx * at(i1, j1)));
    return true;
  }
};

Image Half(const Image& a)
{
  Image b(std::max(1, a.W / 2), std::max(1, a.H / 2));
  for (int j = 0; j < b.H; ++j)
    for (int i = 0; i < b.W; ++i)
    {
      const int i0 = std::min(2 * i, a.W - 1), i1 = std::min(2 * i + 1, a.W - 1);
      const int j0 = std::min(2 * j, a.H - 1), j1 = std::min(2 * j + 1, a.H - 1);
      b.at(i, j) = 0.25f * (a.at(i0, j0) + a.at(i1, j0) + a.at(i0, j1) + a.at(i1, j1));
    }
  return b;
}

Image Gaussian(const Image& a, double sigma)
{
  const int r = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
  std::vector<double> k(2 * r + 1);
  double sum = 0;
  for (int t = -r; t <= r; ++t)
    sum += k[t + r] = std::exp(-0.5 * t * t / (sigma * sigma));
  for (double& v : k)
    v /= sum;
  Image tmp(a.W, a.H), b(a.W, a.H);
  for (int j = 0; j < a.H; ++j)
    for (int i = 0; i < a.W; ++i)
    {
      double s = 0;
      for (int t = -r; t <= r; ++t)
        s += k[t + r] * a.at(std::clamp(i + t, 0, a.W - 1), j);
      tmp.at(i, j) = static_cast<float>(s);
    }
  for (int j = 0; j < a.H; ++j)
    for (int i = 0; i < a.W; ++i)
    {
      double s = 0;
      for (int t = -r; t <= r; ++t)
        s += k[t + r] * tmp.at(i, std::clamp(j + t, 0, a.H - 1));
      b.at(i, j) = static_cast<float>(s);
    }
  return b;
}

/** The largest value within `r` pixels (a square window), for keeping away from lines. */
Image Dilate(const Image& a, int r)
{
  Image tmp(a.W, a.H), b(a.W, a.H);
  for (int j = 0; j < a.H; ++j)
    for (int i = 0; i < a.W; ++i)
    {
      float m = a.at(i, j);
      for (int t = std::max(0, i - r); t <= std::min(a.W - 1, i + r); ++t)
        m = std::max(m, a.at(t, j));
      tmp.at(i, j) = m;
    }
  for (int j = 0; j < a.H; ++j)
    for (int i = 0; i < a.W; ++i)
    {
      float m = tmp.at(i, j);
      for (int t = std::max(0, j - r); t <= std::min(a.H - 1, j + r); ++t)
        m = std::max(m, tmp.at(i, t));
      b.at(i, j) = m;
    }
  return b;
}

/** The gradient (central differences, one-sided at the borders) of a smoothed image. */
void Gradient(const Image& a, Image& gx, Image& gy, Image& mag)
{
  gx = Image(a.W, a.H);
  gy = Image(a.W, a.H);
  mag = Image(a.W, a.H);
  for (int j = 0; j < a.H; ++j)
    for (int i = 0; i < a.W; ++i)
    {
      const int il = std::max(i - 1, 0), ir = std::min(i + 1, a.W - 1);
      const int jl = std::max(j - 1, 0), jr = std::min(j + 1, a.H - 1);
      const float dx = (a.at(ir, j) - a.at(il, j)) / std::max(ir - il, 1);
      const float dy = (a.at(i, jr) - a.at(i, jl)) / std::max(jr - jl, 1);
      gx.at(i, j) = dx;
      gy.at(i, j) = dy;
      mag.at(i, j) = std::sqrt(dx * dx + dy * dy);
    }
}

Image GradientMap(const Image& a, double sigma = 1.0)
{
  Image gx, gy, m;
  Gradient(Gaussian(a, sigma), gx, gy, m);
  return m;
}

double Percentile(std::vector<float> v, double q)
{
  if (v.empty())
    return 0;
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

/** The similarity transform, full-resolution pixels. */
struct Transform
{
  double S = 1, Theta = 0, Tx = 0, Ty = 0; // Theta in radians
};

/** A pyramid of gradient maps (level k: the image halved k times, then its gradient map). */
struct Pyramid
{
  std::vector<Image> Maps;
  explicit Pyramid(const Image& a, int levels)
  {
    Image cur = a;
    for (int k = 0; k < levels; ++k)
    {
      Maps.push_back(GradientMap(cur));
      if (cur.W < 4 || cur.H < 4)
        break;
      cur = Half(cur);
    }
  }
};

/** Registration state: film and photograph pyramids and the centres. */
struct Registrar
{
  int FW, FH, PW, PH;
  Pyramid Film, Photo;
  std::vector<unsigned char> Keep; // level-0 film pixels in the correlation (all, or a jackknife's)
  /** The final refinement's photograph map (level -1): the full photograph smoothed by a film
   * pixel (Scale photograph pixels), as the film's map is, where UseFine. */
  Image Fine;
  bool UseFine = false;

  Registrar(const Image& film, const Image& photo, int levels)
    : FW(film.W)
    , FH(film.H)
    , PW(photo.W)
    , PH(photo.H)
    , Film(film, levels)
    , Photo(photo, levels + 8)
  {
  }

  /** The photograph level whose pixel best matches a film level-k pixel at scale s. */
  int PhotoLevel(int k, double s) const
  {
    const double f = std::ldexp(s, k);
    if (k == 0 && UseFine)
      return -1;
    int L = f >= 1 ? static_cast<int>(std::floor(std::log2(f) + 1e-9)) : 0;
    return std::clamp(L, 0, static_cast<int>(Photo.Maps.size()) - 1);
  }

  /** The photograph's level-L map under `t`, sampled at film points. */
  struct Mapping
  {
    const Image* P;
    double A, B, U0, V0, G;
    Mapping(const Registrar& R, int L, const Transform& t)
      : P(L < 0 ? &R.Fine : &R.Photo.Maps[L])
      , A(std::cos(t.Theta) * t.S)
      , B(std::sin(t.Theta) * t.S)
      , U0(0.5 * (R.PW - 1) + t.Tx)
      , V0(0.5 * (R.PH - 1) + t.Ty)
      , G(L < 0 ? 1.0 : std::ldexp(1.0, L))
    {
    }
    /** At the film's point (x, y) (full-resolution film pixels from the film's centre); false
     * outside the photograph. */
    bool At(double x, double y, float& p) const
    {
      const double u = A * x - B * y + U0, v = B * x + A * y + V0;
      return P->Sample((u - 0.5 * (G - 1)) / G, (v - 0.5 * (G - 1)) / G, p);
    }
  };

  /** Normalised correlation of the film's level-k map with the photograph's under `t`; the
   * covered fraction of the film in `overlap`. */
  double Score(int k, const Transform& t, double* overlap = nullptr) const
  {
    const Image& F = Film.Maps[k];
    const Mapping M(*this, PhotoLevel(k, t.S), t);
    const double f = std::ldexp(1.0, k);
    const double fcx = 0.5 * (FW - 1), fcy = 0.5 * (FH - 1);
    double n = 0, sf = 0, sp = 0, sff = 0, spp = 0, sfp = 0;
    for (int j = 0; j < F.H; ++j)
    {
      const double y = f * j + 0.5 * (f - 1) - fcy;
      for (int i = 0; i < F.W; ++i)
      {
        if (k == 0 && !Keep.empty() && !Keep[static_cast<std::size_t>(j) * F.W + i])
          continue;
        const double x = f * i + 0.5 * (f - 1) - fcx;
        float p;
        if (!M.At(x, y, p))
          continue;
        const double a = F.at(i, j);
        n += 1;
        sf += a;
        sp += p;
        sff += a * a;
        spp += p * p;
        sfp += a * p;
      }
    }
    if (overlap)
      *overlap = n / (static_cast<double>(F.W) * F.H);
    // a transform that leaves half the film uncovered is not taken: a correlation over few pixels
    // reaches high values by chance
    if (n < 0.5 * F.W * F.H)
      return -1;
    const double vf = sff - sf * sf / n, vp = spp - sp * sp / n;
    if (!(vf > 0 && vp > 0))
      return -1;
    return (sfp - sf * sp / n) / std::sqrt(vf * vp);
  }

  /** Pattern search from `t` at level k over the free parameters (shift always; rotation and
   * scale: the first `free` of shift x, shift y, rotation, scale), steps in level pixels at the
   * film's corner from `step` to `stop`. */
  double Refine(int k, Transform& t, int free, double step, double stop) const
  {
    const double f = std::ldexp(1.0, k);
    const double r = 0.5 * std::hypot(FW, FH) / f; // corner radius, level pixels
    double best = Score(k, t);
    int evaluations = 0;
    while (step >= stop && evaluations < 4000)
    {
      bool moved = false;
      for (int p = 0; p < free; ++p)
        for (int sgn = -1; sgn <= 1; sgn += 2)
        {
          Transform trial = t;
          const double d = sgn * step;
          if (p == 0)
            trial.Tx += d * f * t.S;
          else if (p == 1)
            trial.Ty += d * f * t.S;
          else if (p == 2)
            trial.Theta += d / r;
          else
            trial.S *= std::exp(d / r);
          const double sc = Score(k, trial);
          ++evaluations;
          if (sc > best)
          {
            best = sc;
            t = trial;
            moved = true;
            break;
          }
        }
      if (!moved)
        step *= 0.5;
    }
    return best;
  }
};

struct Candidate
{
  double Score;
  Transform T;
};

/** The coarse search at level k: every scale and rotation of the grids, every integer shift of
 * the film's level pixels within `maxShift` of `center`; the best `keep` distinct candidates. */
std::vector<Candidate> CoarseSearch(const Registrar& R, int k, const std::vector<double>& scales,
  const std::vector<double>& angles, const Transform& center, int maxShift, int keep)
{
  std::vector<Candidate> all;
  const double f = std::ldexp(1.0, k);
  for (double s : scales)
    for (double th : angles)
    {
      Candidate best{ -2, {} };
      for (int dy = -maxShift; dy <= maxShift; ++dy)
        for (int dx = -maxShift; dx <= maxShift; ++dx)
        {
          Transform t{ s, th, 0, 0 };
          // a film shift d (level px) is a photograph shift s R d
          const double ddx = dx * f, ddy = dy * f;
          t.Tx = center.Tx + s * (std::cos(th) * ddx - std::sin(th) * ddy);
          t.Ty = center.Ty + s * (std::sin(th) * ddx + std::cos(th) * ddy);
          const double sc = R.Score(k, t);
          if (sc > best.Score)
            best = { sc, t };
        }
      all.push_back(best);
    }
  std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) { return a.Score > b.Score; });
  std::vector<Candidate> out;
  for (const Candidate& c : all)
  {
    bool distinct = true;
    for (const Candidate& o : out)
      if (std::fabs(std::log(c.T.S / o.T.S)) < 0.08 && std::fabs(c.T.Theta - o.T.Theta) < 0.06)
        distinct = false;
    if (distinct)
      out.push_back(c);
    if (static_cast<int>(out.size()) >= keep)
      break;
  }
  return out;
}

/** The photograph cut in blocks, shuffled and flipped: the same grey statistics, no picture. */
Image Scramble(const Image& a, unsigned seed)
{
  // 8 x 8 blocks (of at least 2 pixels a side: the photograph has 16 or more)
  const int bx = std::max(2, a.W / 8), by = std::max(2, a.H / 8);
  const int nx = a.W / bx, ny = a.H / by;
  std::vector<int> order(nx * ny);
  for (int i = 0; i < nx * ny; ++i)
    order[i] = i;
  std::mt19937 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  Image out = a;
  for (int q = 0; q < nx * ny; ++q)
  {
    const int src = order[q];
    const int si = (src % nx) * bx, sj = (src / nx) * by, di = (q % nx) * bx, dj = (q / nx) * by;
    const bool fx = rng() & 1, fy = rng() & 1;
    for (int j = 0; j < by; ++j)
      for (int i = 0; i < bx; ++i)
        out.at(di + i, dj + j) = a.at(si + (fx ? bx - 1 - i : i), sj + (fy ? by - 1 - j : j));
  }
  return out;
}

/** Similarity from point pairs (least squares, complex form photo = a film + b). */
Transform FromPairs(const std::vector<double>& pairs, int FW, int FH, int PW, int PH,
  const double origin[2], double px)
{
  using C = std::complex<double>;
  const std::size_t n = pairs.size() / 4;
  std::vector<C> z, w;
  for (std::size_t q = 0; q < n; ++q)
  {
    w.emplace_back(pairs[4 * q] - 0.5 * (PW - 1), pairs[4 * q + 1] - 0.5 * (PH - 1));
    z.emplace_back((pairs[4 * q + 2] - origin[0]) / px - 0.5 * (FW - 1),
      (pairs[4 * q + 3] - origin[1]) / px - 0.5 * (FH - 1));
  }
  C mz = 0, mw = 0;
  for (std::size_t q = 0; q < n; ++q)
  {
    mz += z[q];
    mw += w[q];
  }
  mz /= double(n);
  mw /= double(n);
  C num = 0;
  double den = 0;
  for (std::size_t q = 0; q < n; ++q)
  {
    num += std::conj(z[q] - mz) * (w[q] - mw);
    den += std::norm(z[q] - mz);
  }
  if (!(den > 0))
    throw Error("SchlierenPhotograph: the PointPairs' film points coincide: give 2 to 4 distinct points.");
  const C a = num / den, b = mw - a * mz;
  Transform t;
  t.S = std::abs(a);
  t.Theta = std::arg(a);
  t.Tx = b.real();
  t.Ty = b.imag();
  if (!(t.S > 0) || !std::isfinite(t.S))
    throw Error("SchlierenPhotograph: the PointPairs give no scale: give distinct points.");
  return t;
}

/** Solves the normal equations A x = b (n x n, symmetric) by Gaussian elimination, with A's
 * inverse where asked; false if singular. */
bool Solve(std::vector<double> A, std::vector<double> b, int n, std::vector<double>& x, std::vector<double>* inverse)
{
  std::vector<double> inv(n * n, 0);
  for (int i = 0; i < n; ++i)
    inv[i * n + i] = 1;
  for (int c = 0; c < n; ++c)
  {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::fabs(A[r * n + c]) > std::fabs(A[p * n + c]))
        p = r;
    if (!(std::fabs(A[p * n + c]) > 1e-300))
      return false;
    for (int q = 0; q < n; ++q)
    {
      std::swap(A[c * n + q], A[p * n + q]);
      std::swap(inv[c * n + q], inv[p * n + q]);
    }
    std::swap(b[c], b[p]);
    for (int r = 0; r < n; ++r)
      if (r != c)
      {
        const double m = A[r * n + c] / A[c * n + c];
        for (int q = 0; q < n; ++q)
        {
          A[r * n + q] -= m * A[c * n + q];
          inv[r * n + q] -= m * inv[c * n + q];
        }
        b[r] -= m * b[c];
      }
  }
  x.assign(n, 0);
  for (int i = 0; i < n; ++i)
    x[i] = b[i] / A[i * n + i];
  if (inverse)
  {
    inverse->assign(n * n, 0);
    for (int i = 0; i < n; ++i)
      for (int q = 0; q < n; ++q)
        (*inverse)[i * n + q] = inv[i * n + q] / A[i * n + i];
  }
  return true;
}

/**
 * The refined transform's covariance, from the level-0 correlation's residuals. The photograph's
 * map at the transform is modelled as a F + b (F the film's map) plus the change a move of the
 * transform makes (its Jacobian J, by central differences of half a film pixel at the corner):
 * least squares, whose covariance is the sandwich (J'J)^-1 S (J'J)^-1. S sums the products of
 * the pixels' scores J e over every lag within a Bartlett window (Newey-West in two dimensions):
 * the residuals e are correlated over several pixels (the maps' smoothing, the camera's blur, the
 * interpolation), and counting them as independent states an uncertainty several times too small.
 * The window reaches twice the lag at which the residuals' correlation falls under 0.05 (3 to 20
 * pixels). Parameters: shift x, y (photograph pixels), rotation (radians), log scale; the first
 * `free` of them. Returns false where the system is singular.
 */
bool Covariance(const Registrar& R, const Transform& t, int free, std::vector<double>& cov, int& window)
{
  const Image& F = R.Film.Maps[0];
  const int W = F.W, H = F.H, n = free;
  const std::size_t N = static_cast<std::size_t>(W) * H;
  const int L = R.PhotoLevel(0, t.S);
  const double r = 0.5 * std::hypot(W, H);
  const double step[4] = { 0.5 * t.S, 0.5 * t.S, 0.5 / r, 0.5 / r };
  std::vector<Registrar::Mapping> plus, minus;
  const Registrar::Mapping M(R, L, t);
  for (int a = 0; a < n; ++a)
    for (int sgn = -1; sgn <= 1; sgn += 2)
    {
      Transform u = t;
      const double d = sgn * step[a];
      if (a == 0)
        u.Tx += d;
      else if (a == 1)
        u.Ty += d;
      else if (a == 2)
        u.Theta += d;
      else
        u.S *= std::exp(d);
      (sgn > 0 ? plus : minus).emplace_back(R, L, u);
    }
  std::vector<unsigned char> ok(N, 0);
  std::vector<double> p0(N, 0), J(N * n, 0);
  const double fcx = 0.5 * (W - 1), fcy = 0.5 * (H - 1);
  std::size_t count = 0;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i)
    {
      const std::size_t q = static_cast<std::size_t>(j) * W + i;
      const double x = i - fcx, y = j - fcy;
      float p, hi, lo;
      if (!M.At(x, y, p))
        continue;
      bool inside = true;
      for (int a = 0; a < n && inside; ++a)
      {
        inside = plus[a].At(x, y, hi) && minus[a].At(x, y, lo);
        J[q * n + a] = (hi - lo) / (2 * step[a]);
      }
      if (!inside)
        continue;
      ok[q] = 1;
      p0[q] = p;
      ++count;
    }
  if (count < 16)
    return false;
  // the nuisance a F + b projected out of p0 and of J's columns
  auto project = [&](auto get, auto set) {
    double sf = 0, sy = 0, sff = 0, sfy = 0, m = 0;
    for (std::size_t q = 0; q < N; ++q)
      if (ok[q])
      {
        const double f = F.V[q], y = get(q);
        m += 1;
        sf += f;
        sy += y;
        sff += f * f;
        sfy += f * y;
      }
    const double vf = sff - sf * sf / m;
    const double a = vf > 0 ? (sfy - sf * sy / m) / vf : 0, b = (sy - a * sf) / m;
    for (std::size_t q = 0; q < N; ++q)
      if (ok[q])
        set(q, get(q) - a * F.V[q] - b);
  };
  project([&](std::size_t q) { return p0[q]; }, [&](std::size_t q, double v) { p0[q] = v; });
  for (int a = 0; a < n; ++a)
    project([&](std::size_t q) { return J[q * n + a]; }, [&](std::size_t q, double v) { J[q * n + a] = v; });
  const std::vector<double>& e = p0;
  // the window: where the residuals' correlation (along x and y) falls under 0.05
  double e2 = 0;
  for (std::size_t q = 0; q < N; ++q)
    if (ok[q])
      e2 += e[q] * e[q];
  int fall = 10;
  for (int d = 1; d <= 10; ++d)
  {
    double c = 0;
    for (int j = 0; j < H; ++j)
      for (int i = 0; i < W; ++i)
      {
        const std::size_t q = static_cast<std::size_t>(j) * W + i;
        if (!ok[q])
          continue;
        if (i + d < W && ok[q + d])
          c += 0.5 * e[q] * e[q + d];
        if (j + d < H && ok[q + static_cast<std::size_t>(d) * W])
          c += 0.5 * e[q] * e[q + static_cast<std::size_t>(d) * W];
      }
    if (!(e2 > 0) || c < 0.05 * e2)
    {
      fall = d;
      break;
    }
  }
  window = std::clamp(2 * fall, 3, 20);
  // the scores and the sandwich
  std::vector<double> g(N * n, 0), A(n * n, 0), S(n * n, 0);
  for (std::size_t q = 0; q < N; ++q)
    if (ok[q])
      for (int a = 0; a < n; ++a)
      {
        g[q * n + a] = J[q * n + a] * e[q];
        for (int b = 0; b < n; ++b)
          A[a * n + b] += J[q * n + a] * J[q * n + b];
      }
  // the Bartlett window is separable, (1 - |dx| / (L + 1)) (1 - |dy| / (L + 1)): S = sum over q of
  // g_q (w * g)_q', w * g the triangle filter along x, then along y (g is 0 off the valid pixels)
  const int Lw = window;
  std::vector<double> wx(N * n, 0), wg(N * n, 0);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i)
    {
      const std::size_t q = static_cast<std::size_t>(j) * W + i;
      for (int d = std::max(-Lw, -i); d <= std::min(Lw, W - 1 - i); ++d)
      {
        const double w = 1 - std::abs(d) / (Lw + 1.0);
        for (int a = 0; a < n; ++a)
          wx[q * n + a] += w * g[(q + d) * n + a];
      }
    }
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i)
    {
      const std::size_t q = static_cast<std::size_t>(j) * W + i;
      for (int d = std::max(-Lw, -j); d <= std::min(Lw, H - 1 - j); ++d)
      {
        const double w = 1 - std::abs(d) / (Lw + 1.0);
        const std::size_t o = q + static_cast<std::ptrdiff_t>(d) * W;
        for (int a = 0; a < n; ++a)
          wg[q * n + a] += w * wx[o * n + a];
      }
    }
  for (std::size_t q = 0; q < N; ++q)
    if (ok[q])
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
          S[a * n + b] += 0.5 * (g[q * n + a] * wg[q * n + b] + g[q * n + b] * wg[q * n + a]);
  std::vector<double> x, inv;
  if (!Solve(A, std::vector<double>(n, 0), n, x, &inv))
    return false;
  cov.assign(n * n, 0);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
    {
      double v = 0;
      for (int c = 0; c < n; ++c)
        for (int d = 0; d < n; ++d)
          v += inv[a * n + c] * S[c * n + d] * inv[d * n + b];
      cov[a * n + b] = v;
    }
  return true;
}

/** A ridge pixel of a gradient map with its sub-pixel position. */
struct Ridge
{
  double X, Y;
  double Tx, Ty; ///< the line's direction there (across the gradient), unit
};

/** Strong-gradient ridges (non-maximum suppression across the gradient, sub-pixel by a parabola),
 * linked into polylines: a walk steps to the 8-connected neighbour that lies most nearly along
 * the line's direction (within 60 degrees of it) and whose own direction differs by under 30
 * degrees, so that lines meeting at an angle (a reflected shock on the incident one, a shock on
 * a body) end at the junction, each its own line; lines shorter than `minLength` dropped. */
std::vector<std::vector<Ridge>> Lines(const Image& img, const std::vector<unsigned char>& valid,
  double threshold, int minLength)
{
  Image gx, gy, m;
  Gradient(Gaussian(img, 1.0), gx, gy, m);
  const int W = img.W, H = img.H;
  std::vector<int> id(static_cast<std::size_t>(W) * H, -1);
  std::vector<Ridge> pts;
  for (int j = 1; j < H - 1; ++j)
    for (int i = 1; i < W - 1; ++i)
    {
      const std::size_t q = static_cast<std::size_t>(j) * W + i;
      const float g = m.at(i, j);
      if (!(g > threshold) || !valid[q])
        continue;
      // every neighbour valid (no edge of the photograph's cover taken for a line)
      bool inside = true;
      for (int b = -1; b <= 1; ++b)
        for (int a = -1; a <= 1; ++a)
          inside = inside && valid[q + b * W + a];
      if (!inside)
        continue;
      const double ux = gx.at(i, j) / g, uy = gy.at(i, j) / g;
      const int sx = static_cast<int>(std::lround(ux)), sy = static_cast<int>(std::lround(uy));
      const float g1 = m.at(i + sx, j + sy), g0 = m.at(i - sx, j - sy);
      if (!(g >= g1 && g > g0))
        continue;
      const double den = g0 - 2.0 * g + g1;
      double off = den < 0 ? 0.5 * (g0 - g1) / den : 0;
      off = std::clamp(off, -0.5, 0.5);
      const double len = std::hypot(sx, sy);
      id[q] = static_cast<int>(pts.size());
      pts.push_back({ i + off * sx / len, j + off * sy / len, -uy, ux });
    }
  std::vector<std::vector<Ridge>> lines;
  std::vector<int> px(pts.size()), py(pts.size());
  for (int j = 0, c = 0; j < H; ++j)
    for (int i = 0; i < W; ++i)
      if (id[static_cast<std::size_t>(j) * W + i] >= 0)
      {
        px[c] = i;
        py[c] = j;
        ++c;
      }
  std::vector<unsigned char> used(pts.size(), 0);
  const double sameDirection = std::cos(30 * Pi / 180), along = std::cos(60 * Pi / 180);
  // the next point from p walking along (dx, dy) (the sign of the line's direction taken), -1 at
  // an end or a junction; its direction also within 30 degrees of (rx, ry), the line's chord over
  // its last 8 points (a junction smoothed by the maps' blur turns the direction by degrees a pixel)
  auto step = [&](int p, double& dx, double& dy, double rx, double ry) {
    int next = -1;
    double bestAlong = along;
    for (int b = -1; b <= 1; ++b)
      for (int a = -1; a <= 1; ++a)
      {
        const int i = px[p] + a, j = py[p] + b;
        if ((!a && !b) || i < 0 || j < 0 || i >= W || j >= H)
          continue;
        const int c = id[static_cast<std::size_t>(j) * W + i];
        if (c < 0 || used[c])
          continue;
        const double len = std::hypot(a, b), ox = a / len, oy = b / len;
        const double cosine = ox * dx + oy * dy;
        if (cosine < bestAlong)
          continue;
        if (std::fabs(pts[c].Tx * pts[p].Tx + pts[c].Ty * pts[p].Ty) < sameDirection ||
          std::fabs(pts[c].Tx * rx + pts[c].Ty * ry) < sameDirection)
          continue;
        bestAlong = cosine;
        next = c;
      }
    if (next >= 0)
    {
      // the direction there, signed as the walk goes
      const double sgn = pts[next].Tx * dx + pts[next].Ty * dy >= 0 ? 1 : -1;
      dx = sgn * pts[next].Tx;
      dy = sgn * pts[next].Ty;
    }
    return next;
  };
  for (std::size_t s = 0; s < pts.size(); ++s)
  {
    if (used[s])
      continue;
    used[s] = 1;
    std::vector<Ridge> halves[2];
    for (int half = 0; half < 2; ++half)
    {
      double dx = half ? -pts[s].Tx : pts[s].Tx, dy = half ? -pts[s].Ty : pts[s].Ty;
      std::vector<Ridge>& h = halves[half];
      for (int p = static_cast<int>(s);;)
      {
        double rx = dx, ry = dy;
        if (h.size() >= 8)
        {
          const Ridge& back = h[h.size() - 8];
          const double l = std::hypot(h.back().X - back.X, h.back().Y - back.Y);
          if (l > 0)
          {
            rx = (h.back().X - back.X) / l;
            ry = (h.back().Y - back.Y) / l;
          }
        }
        p = step(p, dx, dy, rx, ry);
        if (p < 0)
          break;
        used[p] = 1;
        h.push_back(pts[p]);
      }
    }
    std::vector<Ridge> line(halves[1].rbegin(), halves[1].rend());
    line.push_back(pts[s]);
    line.insert(line.end(), halves[0].begin(), halves[0].end());
    if (static_cast<int>(line.size()) >= minLength)
      lines.push_back(std::move(line));
  }
  return lines;
}

/** A number in JSON: null where it is not finite. */
struct J
{
  double V;
};
std::ostream& operator<<(std::ostream& o, J j)
{
  if (std::isfinite(j.V))
    o << j.V;
  else
    o << "null";
  return o;
}

} // namespace

PhotographSettings ParsePhotographSettings(const std::string& text)
{
  PhotographSettings s;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line))
  {
    if (line.find_first_not_of(" \t\r") == std::string::npos)
      continue;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos)
      throw Error("SchlierenPhotograph setting '" + line + "': expected Name=value.");
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    std::vector<double> v;
    {
      std::istringstream in(value);
      std::string word;
      while (in >> word)
      {
        char* end = nullptr;
        const double d = std::strtod(word.c_str(), &end);
        if (key != "Refine" && (end == word.c_str() || *end || !std::isfinite(d)))
          throw Error("SchlierenPhotograph " + key + " '" + value + "': expected finite numbers.");
        v.push_back(d);
      }
    }
    auto one = [&](double lo, double hi) {
      if (v.size() != 1 || !(v[0] >= lo && v[0] <= hi))
      {
        std::ostringstream msg;
        msg << "SchlierenPhotograph " << key << " '" << value << "': expected one number in [" << lo
            << ", " << hi << "].";
        throw Error(msg.str());
      }
      return v[0];
    };
    if (key == "PhotoPixelSize")
      s.PhotoPixelSize = one(0, 1e30);
    else if (key == "PointPairs")
    {
      if (!(v.empty() || (v.size() % 4 == 0 && v.size() >= 8 && v.size() <= 16)))
        throw Error("SchlierenPhotograph PointPairs '" + value + "': expected 2 to 4 pairs of 4 numbers "
          "(photograph pixel u v, world x y), " + std::to_string(v.size()) + " numbers given.");
      s.PointPairs = v;
    }
    else if (key == "Refine")
    {
      const std::string r = value.substr(0, value.find_last_not_of(" \t\r") + 1);
      if (r != "Similarity" && r != "Rigid" && r != "Shift" && r != "None")
        throw Error("SchlierenPhotograph Refine '" + value + "' is not one of: Similarity, Rigid, Shift, None.");
      s.Refine = r;
    }
    else if (key == "ScaleRange")
    {
      if (v.size() != 2 || !(v[0] > 0 && v[0] <= 1 && v[1] >= 1 && v[1] <= 100))
        throw Error("SchlierenPhotograph ScaleRange '" + value + "': expected 2 numbers, 0 < low <= 1 <= high <= 100.");
      s.ScaleRange[0] = v[0];
      s.ScaleRange[1] = v[1];
    }
    else if (key == "MaxRotation")
      s.MaxRotation = one(0, 180);
    else if (key == "MaxShift")
      s.MaxShift = one(0, 1);
    else if (key == "LineThreshold")
      s.LineThreshold = one(1e-6, 1);
    else if (key == "MinLineLength")
      s.MinLineLength = static_cast<int>(one(2, 100000));
    else if (key == "MaxLineDistance")
      s.MaxLineDistance = one(0, 1e30);
    else if (key == "CheckerSize")
      s.CheckerSize = static_cast<int>(one(1, 100000));
    else if (key == "Refuse")
      s.Refuse = one(0, 1) != 0;
    else
      throw Error("SchlierenPhotograph: unknown setting '" + key + "' (known: PhotoPixelSize, PointPairs, "
        "Refine, ScaleRange, MaxRotation, MaxShift, LineThreshold, MinLineLength, MaxLineDistance, "
        "CheckerSize, Refuse).");
  }
  if (s.Refine == "None" && s.PointPairs.empty())
    throw Error("SchlierenPhotograph: Refine None takes the transform from PointPairs: give 2 to 4 pairs.");
  return s;
}

PhotographResult RegisterPhotograph(const int film_size[2], const double film_origin[2],
  double pixel_size, const float* film, const int photo_size[2], const float* photo,
  const PhotographSettings& settings)
{
  const auto t0 = std::chrono::steady_clock::now();
  const int FW = film_size[0], FH = film_size[1], PW = photo_size[0], PH = photo_size[1];
  if (FW < 16 || FH < 16 || FW > 16384 || FH > 16384)
    throw Error("SchlierenPhotograph: the film is " + std::to_string(FW) + " x " + std::to_string(FH) +
      " pixels: 16 to 16384 a side are taken.");
  if (PW < 16 || PH < 16 || PW > 32768 || PH > 32768)
    throw Error("SchlierenPhotograph: the photograph is " + std::to_string(PW) + " x " + std::to_string(PH) +
      " pixels: 16 to 32768 a side are taken.");
  if (!(pixel_size > 0) || !std::isfinite(pixel_size) || !std::isfinite(film_origin[0]) || !std::isfinite(film_origin[1]))
    throw Error("SchlierenPhotograph: the film's pixel size and origin must be finite (pixel size > 0).");
  // the images, their pyramids of gradient maps and the scrambled copies': about 12 floats a
  // pixel of each
  CheckHostMemory(48.0 * (double(FW) * FH + double(PW) * PH), "Registering a photograph of " +
      std::to_string(PW) + " x " + std::to_string(PH) + " pixels onto a film of " + std::to_string(FW) +
      " x " + std::to_string(FH), "Give a smaller photograph (or film).");
  Image F(FW, FH), P(PW, PH);
  for (std::size_t q = 0; q < F.V.size(); ++q)
  {
    if (!std::isfinite(film[q]))
      throw Error("SchlierenPhotograph: the film's intensity is not finite at pixel " + std::to_string(q) + ".");
    F.V[q] = film[q];
  }
  for (std::size_t q = 0; q < P.V.size(); ++q)
  {
    if (!std::isfinite(photo[q]))
      throw Error("SchlierenPhotograph: the photograph is not finite at pixel " + std::to_string(q) +
        ": give grey levels (NaN and infinities are not).");
    P.V[q] = photo[q];
  }
  const double px = pixel_size;
  PhotographResult res;
  res.Width = FW;
  res.Height = FH;
  const std::size_t N = F.V.size();

  // the film or the photograph without contrast: nothing to register
  auto spread = [](const Image& a) {
    double lo = a.V[0], hi = a.V[0];
    for (float v : a.V)
    {
      lo = std::min<double>(lo, v);
      hi = std::max<double>(hi, v);
    }
    return std::make_pair(lo, hi);
  };
  const auto fs = spread(F), ps = spread(P);
  auto refuse = [&](const std::string& why) {
    res.Match = false;
    res.Reason = why;
  };

  // the pyramid: the coarse level has 24 to 48 pixels along the film's larger side
  int coarse = 0;
  while ((std::max(FW, FH) >> (coarse + 1)) >= 24 && std::min(FW, FH) >> (coarse + 1) >= 12)
    ++coarse;
  Registrar R(F, P, coarse + 1);
  coarse = std::min(coarse, static_cast<int>(R.Film.Maps.size()) - 1);

  // the start
  Transform start;
  const bool pairs = !settings.PointPairs.empty();
  const double area_scale = std::sqrt(double(PW) * PH / (double(FW) * FH));
  if (pairs)
  {
    start = FromPairs(settings.PointPairs, FW, FH, PW, PH, film_origin, px);
    res.Start = "point pairs";
  }
  else if (settings.PhotoPixelSize > 0)
  {
    start.S = px / settings.PhotoPixelSize;
    res.Start = "the bench's photograph pixel size";
  }
  else
  {
    start.S = area_scale;
    res.Start = "the images' areas (scale searched)";
  }

  Transform best = start;
  const bool similarity = settings.Refine == "Similarity";
  // the parameters refined: Similarity 4 (the scale only where the bench does not give it:
  // PhotoPixelSize fixes it), Rigid 3 (shift and rotation), Shift 2
  const int free = settings.Refine == "Shift" ? 2 : (settings.Refine == "Rigid" || (similarity && settings.PhotoPixelSize > 0 && !pairs)) ? 3 : 4;
  const bool rotate = free >= 3;
  bool blank = false;
  if (!(fs.second - fs.first > 1e-6 * std::max(1.0, std::fabs(fs.second))))
  {
    refuse("the film is blank (one grey level): nothing to register against.");
    blank = true;
  }
  else if (!(ps.second - ps.first > 1e-6 * std::max(1.0, std::fabs(ps.second))))
  {
    refuse("the photograph is blank (one grey level " + std::to_string(ps.first) + "): nothing to register.");
    blank = true;
  }

  if (!blank && settings.Refine != "None")
  {
    const int maxShift = pairs ? 2 : std::max(1, static_cast<int>(std::ceil(settings.MaxShift *
      std::max(R.Film.Maps[coarse].W, R.Film.Maps[coarse].H))));
    std::vector<double> scales, angles;
    const double r = 0.5 * std::hypot(R.Film.Maps[coarse].W, R.Film.Maps[coarse].H);
    {
      // the coarse search's work, bounded before it starts: scales x angles x shifts correlations
      // of the coarse level's pixels, three times (the photograph and two scrambled copies). Its
      // grids grow with the coarse level's size r (scales and angles as r, shifts as r^2), and
      // the pyramid stops coarsening where the film's shorter side would go under 12 pixels: a
      // 300 x 16 film searched at 300 x 16 took 4.4e12 pixel visits (hours; the C
      // interface's fuzz, seeds 3 and 11). Square films up to 16384 a side with the default
      // settings stay under 3e9.
      const double w = R.Film.Maps[coarse].W, h = R.Film.Maps[coarse].H;
      const double nScales = (pairs || settings.PhotoPixelSize > 0 || !similarity) ? 1 :
        std::floor((std::log(settings.ScaleRange[1]) - std::log(settings.ScaleRange[0]) + 1e-9) * r) + 1;
      const double nAngles = (pairs || !rotate) ? 1 : std::floor(2 * settings.MaxRotation * Pi / 180 * r + 1e-9) + 1;
      const double work = 3 * nScales * nAngles * (2.0 * maxShift + 1) * (2.0 * maxShift + 1) * w * h;
      const double bound = 2e10;
      if (!(work <= bound))
      {
        std::ostringstream msg;
        msg.precision(3);
        msg << "SchlierenPhotograph: the registration's coarse search would visit " << work
            << " pixels (" << nScales << " scales x " << nAngles << " rotations x " << (2 * maxShift + 1)
            << "^2 shifts on the film's coarse level of " << w << " x " << h << " pixels, three times), over the "
            << bound << " taken: give PointPairs or PhotoPixelSize, narrow ScaleRange, MaxRotation or MaxShift"
            << (std::max(FW, FH) > 4 * std::min(FW, FH) ? ", or a film less elongated (the pyramid stops "
                "coarsening where its shorter side would go under 12 pixels)" : "") << ".";
        throw Error(msg.str());
      }
    }
    if (pairs || settings.PhotoPixelSize > 0 || !similarity)
      scales.push_back(start.S);
    else
    {
      const double step = 1.0 / r; // about a coarse pixel at the corner
      for (double l = std::log(settings.ScaleRange[0]); l <= std::log(settings.ScaleRange[1]) + 1e-9; l += step)
        scales.push_back(start.S * std::exp(l));
    }
    if (pairs || !rotate)
      angles.push_back(start.Theta);
    else
    {
      const double step = 1.0 / r, m = settings.MaxRotation * Pi / 180;
      for (double a = -m; a <= m + 1e-9; a += step)
        angles.push_back(start.Theta + a);
    }
    Transform center = start;
    auto candidates = CoarseSearch(R, coarse, scales, angles, center, maxShift, 4);
    // refine the candidates, level after level
    double bestScore = -2;
    for (Candidate c : candidates)
    {
      Transform t = c.T;
      for (int k = coarse; k >= 0; --k)
        R.Refine(k, t, free, k == coarse ? 0.5 : 1.0, k == 0 ? 0.005 : 0.1);
      const double sc = R.Score(0, t);
      if (sc > bestScore)
      {
        bestScore = sc;
        best = t;
      }
    }
    res.CoarseScore = R.Score(coarse, best);
    res.Score = bestScore;
    // what noise gives: the same search and refinement with the photograph scrambled (cut in
    // blocks, shuffled and flipped: its grey statistics, no picture), two seeds
    double null = -1;
    for (unsigned seed = 1; seed <= 2; ++seed)
    {
      Registrar Rn(F, Scramble(P, seed), coarse + 1);
      auto c = CoarseSearch(Rn, coarse, scales, angles, center, maxShift, 1);
      if (c.empty())
        continue;
      Transform t = c[0].T;
      for (int k = coarse; k >= 0; --k)
        Rn.Refine(k, t, free, k == coarse ? 0.5 : 1.0, k == 0 ? 0.02 : 0.1);
      null = std::max(null, Rn.Score(0, t));
    }
    res.NullScore = null;
    // a match stands clear of the scrambled photographs' best: its correlation on the film's
    // grid exceeds theirs by half the room left above them
    res.Threshold = null + 0.5 * (1 - null);
    if (res.Score < res.Threshold)
    {
      std::ostringstream msg;
      msg.precision(3);
      msg << "the photograph does not match the film: its best correlation " << res.Score
          << " is below the threshold " << res.Threshold << " (scrambled copies of the photograph reach "
          << null << "): a photograph of another flow, of noise, or a start too far off.";
      refuse(msg.str());
    }
    else
      res.Match = true;
    if (res.Match)
    {
      // the last refinement on a photograph map smoothed by exactly a film pixel, as the film's
      // is (the pyramid's levels are smoothed by a level pixel: 1 / Scale film pixels on level 0,
      // under 1 where the photograph is finer, over 1 where coarser): a difference of smoothing
      // moves the gradient's ridge of a curved line, which the similarity takes up as a scale
      R.Fine = GradientMap(P, best.S);
      R.UseFine = true;
      R.Refine(0, best, free, 0.25, 0.005);
      // the uncertainty: two estimates, added (their covariances summed), since each sees what the
      // other does not (docs/CFD.md: measured over 30 random cameras, neither alone covers the
      // error as a standard error does)
      // (a) the residuals' sandwich (Covariance): the noise of both maps, correlated over pixels
      std::vector<double> cov;
      int window = 0;
      if (!Covariance(R, best, free, cov, window))
        cov.assign(free * free, 0);
      res.UncertaintyWindow = window;
      // the photograph point's move for each parameter's, at the film's corners
      const double cb = std::cos(best.Theta) * best.S, sb = std::sin(best.Theta) * best.S;
      double Gc[4][2][4];
      for (int k = 0; k < 4; ++k)
      {
        const double x = (k & 1 ? 0.5 : -0.5) * (FW - 1), y = (k & 2 ? 0.5 : -0.5) * (FH - 1);
        const double g[2][4] = { { 1, 0, -sb * x - cb * y, cb * x - sb * y }, { 0, 1, cb * x - sb * y, sb * x + cb * y } };
        std::copy(&g[0][0], &g[0][0] + 8, &Gc[k][0][0]);
      }
      // (b) a jackknife over 8 groups of tiles of the film (4 x 4 tiles, two in a group, each
      // group left out in turn and the transform refined again): the spread between parts of the
      // film, where the two images differ by more than noise (the camera's blur and response,
      // interpolation, a flow that is not quite the film's). (Capping a group's move at 2.5 times
      // the median group's was tried: it halved an over-statement of 7 times but let an error of 3.2
      // times the stated through, the test's first camera.)
      std::vector<double> jackknife(free * free, 0);
      {
        const int groups = 8, tiles = 4;
        std::vector<std::vector<double>> p;
        for (int gidx = 0; gidx < groups; ++gidx)
        {
          R.Keep.assign(N, 1);
          for (int j = 0; j < FH; ++j)
            for (int i = 0; i < FW; ++i)
            {
              const int tile = (j * tiles / FH) * tiles + (i * tiles / FW);
              if (tile % groups == gidx)
                R.Keep[static_cast<std::size_t>(j) * FW + i] = 0;
            }
          Transform t = best;
          R.Refine(0, t, free, 0.25, 0.005);
          p.push_back({ t.Tx, t.Ty, t.Theta, std::log(t.S) });
        }
        R.Keep.clear();
        double mean[4] = { 0, 0, 0, 0 };
        for (const auto& v : p)
          for (int a = 0; a < 4; ++a)
            mean[a] += v[a] / groups;
        for (const auto& v : p)
          for (int a = 0; a < free; ++a)
            for (int b = 0; b < free; ++b)
              jackknife[a * free + b] += (v[a] - mean[a]) * (v[b] - mean[b]) * (groups - 1.0) / groups;
      }
      // the position's standard error at the film's worst corner, film pixels
      auto corner = [&](const std::vector<double>& cv) {
        double worst = 0;
        for (int k = 0; k < 4; ++k)
        {
          double v = 0;
          for (int row = 0; row < 2; ++row)
            for (int a = 0; a < free; ++a)
              for (int b = 0; b < free; ++b)
                v += Gc[k][row][a] * cv[a * free + b] * Gc[k][row][b];
          worst = std::max(worst, std::sqrt(std::max(0.0, v)) / best.S);
        }
        return worst;
      };
      res.EdgeNoise = corner(cov);
      res.EdgeSpread = corner(jackknife);
      for (int a = 0; a < free * free; ++a)
        cov[a] += jackknife[a];
      res.EdgeUncertainty = corner(cov);
      double var[4] = { 0, 0, 0, 0 };
      for (int a = 0; a < free; ++a)
        var[a] = std::max(0.0, cov[a * free + a]);
      res.Sigma[0] = std::sqrt(var[0]);
      res.Sigma[1] = std::sqrt(var[1]);
      res.Sigma[2] = std::sqrt(var[2]) * 180 / Pi;
      res.Sigma[3] = std::sqrt(var[3]);
      R.UseFine = false;
      res.Score = R.Score(0, best);
      // a direction along which the correlation is flat (lines all parallel to it, a self-similar
      // flow) is said in words too: the score's fall for a shift of a film pixel in each
      // direction, the weakest against the strongest
      const double s0 = R.Score(0, best);
      double weakest = 1e300, strongest = 0, weakAngle = 0;
      for (int a = 0; a < 8; ++a)
      {
        const double phi = a * Pi / 8;
        double fall = 0;
        for (int sgn = -1; sgn <= 1; sgn += 2)
        {
          Transform t = best;
          const double dx = sgn * std::cos(phi), dy = sgn * std::sin(phi);
          t.Tx += best.S * (std::cos(best.Theta) * dx - std::sin(best.Theta) * dy);
          t.Ty += best.S * (std::sin(best.Theta) * dx + std::cos(best.Theta) * dy);
          fall += 0.5 * (s0 - R.Score(0, t));
        }
        if (fall < weakest)
        {
          weakest = fall;
          weakAngle = phi * 180 / Pi;
        }
        strongest = std::max(strongest, fall);
      }
      res.WeakDirection = weakAngle;
      res.WeakRatio = strongest > 0 ? weakest / strongest : 0;
      if (res.WeakRatio < 0.15)
      {
        std::ostringstream msg;
        msg.precision(2);
        msg << "the correlation hardly changes along the film's direction " << weakAngle
            << " deg (a shift there costs " << res.WeakRatio << " of what it costs across): the lines "
            << "are nearly parallel to it, or the flow is self-similar, and the registration is not held "
            << "along it beyond its uncertainty: give PointPairs (two or more marks).";
        res.Warnings = msg.str();
      }
    }
  }
  else if (!blank)
  {
    res.Match = true;
    res.Start += " (not refined)";
    res.CoarseScore = R.Score(coarse, best);
    res.Score = R.Score(0, best);
    // the transform is the user's: not refused, but said where scrambled copies of the photograph
    // correlate about as well at it
    double null = -1;
    for (unsigned seed = 1; seed <= 2; ++seed)
    {
      Registrar Rn(F, Scramble(P, seed), 1);
      null = std::max(null, Rn.Score(0, best));
    }
    res.NullScore = null;
    res.Threshold = null + 0.5 * (1 - null);
    if (res.Score < res.Threshold)
    {
      std::ostringstream msg;
      msg.precision(3);
      double covered = 0;
      R.Score(0, best, &covered);
      if (covered < 0.5)
        msg << "at the PointPairs' transform the photograph covers " << 100 * covered
            << " % of the film, below the half a correlation needs: check the pairs.";
      else
        msg << "at the PointPairs' transform the photograph correlates " << res.Score << " with the film, "
            << "below the " << res.Threshold << " a match reaches (scrambled copies: " << null
            << "): check the pairs, and that the photograph is of this flow.";
      res.Warnings = msg.str();
    }
  }
  res.Scale = best.S;
  res.Rotation = best.Theta * 180 / Pi;
  res.Shift[0] = best.Tx;
  res.Shift[1] = best.Ty;
  res.PhotoPixelSize = px / best.S;

  // the photograph on the film's grid (from the pyramid level of its scale: no aliasing)
  res.Registered.assign(N, 0.f);
  res.Valid.assign(N, 0);
  {
    int L = 0;
    while (std::ldexp(1.0, L + 1) <= best.S + 1e-9 && std::min(PW, PH) >> (L + 1) >= 4)
      ++L;
    Image level = P;
    for (int l = 0; l < L; ++l)
      level = Half(level);
    const double g = std::ldexp(1.0, L);
    const double c = std::cos(best.Theta) * best.S, sn = std::sin(best.Theta) * best.S;
    for (int j = 0; j < FH; ++j)
      for (int i = 0; i < FW; ++i)
      {
        const double x = i - 0.5 * (FW - 1), y = j - 0.5 * (FH - 1);
        const double u = c * x - sn * y + 0.5 * (PW - 1) + best.Tx, v = sn * x + c * y + 0.5 * (PH - 1) + best.Ty;
        float p;
        const std::size_t q = static_cast<std::size_t>(j) * FW + i;
        if (level.Sample((u - 0.5 * (g - 1)) / g, (v - 0.5 * (g - 1)) / g, p))
        {
          res.Registered[q] = p;
          res.Valid[q] = 1;
        }
      }
  }
  std::size_t covered = 0;
  for (unsigned char v : res.Valid)
    covered += v;
  res.Overlap = double(covered) / N;

  // grey calibration: log P = vignetting (a quadratic in x, y) + log c + gamma log F, fitted over the
  // covered pixels away from strong gradients (where blur and registration errors dominate)
  Image fgx, fgy, fmag;
  Gradient(Gaussian(F, 1.0), fgx, fgy, fmag);
  const double strong = Percentile(fmag.V, 0.999);
  const double lineThreshold = settings.LineThreshold * strong;
  {
    std::vector<float> quiet;
    for (std::size_t q = 0; q < N; ++q)
      if (fmag.V[q] < 0.05 * strong)
        quiet.push_back(F.V[q]);
    res.FilmBackground = quiet.empty() ? Percentile(F.V, 0.5) : Percentile(quiet, 0.5);
  }
  const double fmax = fs.second;
  std::vector<int> use;
  double pmax = 0;
  for (std::size_t q = 0; q < N; ++q)
    if (res.Valid[q])
      pmax = std::max<double>(pmax, res.Registered[q]);
  // a camera's blur (a pixel or two) mixes the two sides of a line: only the pixels whose grey a
  // blur of 2 pixels would change by less than 1 % of the film's range, and 2 pixels beyond them
  const Image blurred = Gaussian(F, 2.0);
  Image change(FW, FH);
  for (std::size_t q = 0; q < N; ++q)
    change.V[q] = std::fabs(blurred.V[q] - F.V[q]);
  const Image nearLine = Dilate(change, 2);
  const double range = Percentile(F.V, 0.99) - Percentile(F.V, 0.01);
  for (std::size_t q = 0; q < N; ++q)
    if (res.Valid[q] && nearLine.V[q] < 0.01 * range + 1e-30 && F.V[q] > 0.02 * fmax &&
      res.Registered[q] > 0.01 * pmax)
      use.push_back(static_cast<int>(q));
  auto basis = [&](int q, double* b) {
    const double x = 2.0 * (q % FW) / (FW - 1) - 1, y = 2.0 * (q / FW) / (FH - 1) - 1;
    b[0] = 1;
    b[1] = x;
    b[2] = y;
    b[3] = x * x;
    b[4] = x * y;
    b[5] = y * y;
  };
  double gamma = 1;
  std::vector<double> coef(7, 0);
  if (blank || !res.Match)
    res.GreyReason = "no registration to calibrate on.";
  else if (pmax <= 0)
    res.GreyReason = "the photograph has no positive grey levels where it covers the film.";
  else if (use.size() < 200)
    res.GreyReason = "fewer than 200 pixels of the film away from strong gradients are covered by the photograph.";
  else
  {
    // does the film show a range of grey there (else only the level and vignetting are fitted)?
    // at least 100 of those pixels 10 % or more off the free stream's level
    int away = 0;
    for (int q : use)
      away += std::fabs(std::log(F.V[q] / res.FilmBackground)) > 0.1;
    const bool fitGamma = res.FilmBackground > 0 && away >= 100;
    const int n = fitGamma ? 7 : 6;
    std::vector<int> kept = use;
    std::vector<double> x, inverse;
    double rms = 0, gammaError = 0;
    for (int iteration = 0; iteration < 3; ++iteration)
    {
      std::vector<double> A(n * n, 0), b(n, 0);
      for (int q : kept)
      {
        double row[7];
        basis(q, row);
        row[6] = std::log(F.V[q]);
        const double yv = std::log(res.Registered[q]) - (fitGamma ? 0 : row[6]);
        for (int a = 0; a < n; ++a)
        {
          b[a] += row[a] * yv;
          for (int c = 0; c < n; ++c)
            A[a * n + c] += row[a] * row[c];
        }
      }
      if (!Solve(A, b, n, x, &inverse))
        break;
      std::vector<double> resid;
      for (int q : kept)
      {
        double row[7];
        basis(q, row);
        row[6] = std::log(F.V[q]);
        double pred = fitGamma ? 0 : row[6];
        for (int a = 0; a < n; ++a)
          pred += x[a] * row[a];
        resid.push_back(std::log(res.Registered[q]) - pred);
      }
      double ss = 0;
      for (double r : resid)
        ss += r * r;
      rms = std::sqrt(ss / std::max<std::size_t>(1, resid.size() - n));
      // gamma's standard error: the residuals are correlated over the film (the blur, a vignetting
      // that is not quite a quadratic in log, the film's own noise smoothed), so they are summed in
      // 4 x 4 tiles of the film and the tiles counted as the independent samples (a
      // cluster-robust sandwich: inverse(X'X) (sum over tiles of u u') inverse(X'X), u = X'r of a
      // tile, times G / (G - 1))
      {
        const int G = 16;
        std::vector<double> u(static_cast<std::size_t>(G) * n, 0), S(n * n, 0);
        for (std::size_t a = 0; a < kept.size(); ++a)
        {
          const int q = kept[a];
          const int tile = ((q / FW) * 4 / FH) * 4 + (q % FW) * 4 / FW;
          double row[7];
          basis(q, row);
          row[6] = std::log(F.V[q]);
          for (int e = 0; e < n; ++e)
            u[tile * n + e] += row[e] * resid[a];
        }
        for (int t = 0; t < G; ++t)
          for (int a = 0; a < n; ++a)
            for (int e = 0; e < n; ++e)
              S[a * n + e] += u[t * n + a] * u[t * n + e] * G / (G - 1.0);
        double v = 0;
        for (int a = 0; a < n; ++a)
          for (int e = 0; e < n; ++e)
            v += inverse[(n - 1) * n + a] * S[a * n + e] * inverse[e * n + n - 1];
        gammaError = fitGamma ? std::sqrt(std::max(0.0, v)) : 0;
      }
      std::vector<float> absr(resid.size());
      for (std::size_t a = 0; a < resid.size(); ++a)
        absr[a] = static_cast<float>(std::fabs(resid[a]));
      const double mad = 1.4826 * Percentile(absr, 0.5);
      std::vector<int> next;
      for (std::size_t a = 0; a < kept.size(); ++a)
        if (std::fabs(resid[a]) <= 3 * mad + 1e-12)
          next.push_back(kept[a]);
      if (next.size() < 100 || next.size() == kept.size())
        break;
      kept.swap(next);
    }
    if (x.size() == static_cast<std::size_t>(n))
    {
      res.GreyFitted = true;
      for (int a = 0; a < 6; ++a)
        coef[a] = x[a];
      gamma = fitGamma ? x[6] : 1.0;
      res.Gamma = gamma;
      res.GammaError = gammaError;
      res.GreyResidual = rms;
      res.GreyPixels = static_cast<int>(kept.size());
      res.Background = std::exp(x[0]) * std::pow(res.FilmBackground, gamma);
      double corner[6];
      basis(0, corner);
      double v = 0;
      for (int a = 1; a < 6; ++a)
        v += x[a] * corner[a];
      res.Vignetting = std::exp(v);
      if (!fitGamma)
        res.GreyReason = "the film shows too narrow a range of grey away from its lines to fit a response: gamma 1 assumed, the level and vignetting fitted.";
      else if (!(gamma > 0.05 && gamma < 20))
      {
        res.GreyReason = "the fitted response (gamma " + std::to_string(gamma) + ") is not a camera's: not applied.";
        res.GreyFitted = false;
      }
    }
    else
      res.GreyReason = "the grey levels' fit is singular.";
  }
  // the calibrated photograph in the film's grey, the difference and the checkerboard
  res.Calibrated.assign(N, 0.f);
  res.Difference.assign(N, 0.f);
  res.Checkerboard.assign(N, 0.f);
  const int cs = std::max(1, settings.CheckerSize);
  for (std::size_t q = 0; q < N; ++q)
  {
    float cal = 0;
    if (res.Valid[q])
    {
      if (res.GreyFitted)
      {
        double b[6];
        basis(static_cast<int>(q), b);
        double l = 0;
        for (int a = 0; a < 6; ++a)
          l += coef[a] * b[a];
        cal = res.Registered[q] > 0 ? static_cast<float>(std::pow(res.Registered[q] / std::exp(l), 1.0 / gamma)) : 0.f;
      }
      else
        cal = res.Registered[q];
      res.Difference[q] = cal - F.V[q];
    }
    res.Calibrated[q] = cal;
    const int i = static_cast<int>(q % FW) / cs, j = static_cast<int>(q / FW) / cs;
    res.Checkerboard[q] = ((i + j) % 2 && res.Valid[q]) ? cal : F.V[q];
  }

  // the strong-gradient lines and their distances
  res.LineDistance.assign(N, std::numeric_limits<float>::quiet_NaN());
  if (!blank && res.Match)
  {
    std::vector<unsigned char> all(N, 1);
    Image C(FW, FH);
    C.V = res.Calibrated;
    // the photograph's threshold: the film's, or above its own noise (5 times the median gradient)
    Image cgx, cgy, cmag;
    Gradient(Gaussian(C, 1.0), cgx, cgy, cmag);
    std::vector<float> cm;
    for (std::size_t q = 0; q < N; ++q)
      if (res.Valid[q])
        cm.push_back(cmag.V[q]);
    const double photoThreshold = std::max(lineThreshold, 5 * Percentile(cm, 0.5));
    auto fl = Lines(F, all, lineThreshold, settings.MinLineLength);
    auto pl = Lines(C, res.Valid, photoThreshold, settings.MinLineLength);
    const double maxd = (settings.MaxLineDistance > 0 ? settings.MaxLineDistance / px : 0.1 * std::max(FW, FH));
    // a bucket grid of the photograph's ridge points
    const int cell = std::max(1, static_cast<int>(std::ceil(maxd)));
    const int gw = FW / cell + 1, gh = FH / cell + 1;
    std::vector<std::vector<std::pair<int, int>>> grid(static_cast<std::size_t>(gw) * gh);
    for (std::size_t l = 0; l < pl.size(); ++l)
      for (std::size_t a = 0; a < pl[l].size(); ++a)
      {
        const int gi = std::clamp(static_cast<int>(pl[l][a].X) / cell, 0, gw - 1);
        const int gj = std::clamp(static_cast<int>(pl[l][a].Y) / cell, 0, gh - 1);
        grid[static_cast<std::size_t>(gj) * gw + gi].push_back({ static_cast<int>(l), static_cast<int>(a) });
      }
    auto toWorld = [&](const std::vector<Ridge>& line, int image) {
      PhotographLine out;
      out.Image = image;
      for (const Ridge& r : line)
      {
        out.Points.push_back(film_origin[0] + px * r.X);
        out.Points.push_back(film_origin[1] + px * r.Y);
      }
      return out;
    };
    for (std::size_t l = 0; l < fl.size(); ++l)
    {
      PhotographLine out = toWorld(fl[l], 0);
      std::vector<double> dist;
      std::map<int, int> votes;
      double ox = 0, oy = 0;
      for (const Ridge& r : fl[l])
      {
        const int gi = std::clamp(static_cast<int>(r.X) / cell, 0, gw - 1);
        const int gj = std::clamp(static_cast<int>(r.Y) / cell, 0, gh - 1);
        double bd = std::numeric_limits<double>::infinity();
        int bl = -1;
        double bx = 0, by = 0;
        for (int b = std::max(0, gj - 1); b <= std::min(gh - 1, gj + 1); ++b)
          for (int a = std::max(0, gi - 1); a <= std::min(gw - 1, gi + 1); ++a)
            for (const auto& e : grid[static_cast<std::size_t>(b) * gw + a])
            {
              const Ridge& o = pl[e.first][e.second];
              const double d = std::hypot(o.X - r.X, o.Y - r.Y);
              if (d < bd)
              {
                bd = d;
                bl = e.first;
                bx = o.X - r.X;
                by = o.Y - r.Y;
              }
            }
        if (bd <= maxd)
        {
          dist.push_back(bd);
          ++votes[bl];
          ox += bx;
          oy += by;
          const int i = std::clamp(static_cast<int>(std::lround(r.X)), 0, FW - 1);
          const int j = std::clamp(static_cast<int>(std::lround(r.Y)), 0, FH - 1);
          res.LineDistance[static_cast<std::size_t>(j) * FW + i] = static_cast<float>(bd * px);
        }
      }
      out.Matched = double(dist.size()) / fl[l].size();
      if (!dist.empty())
      {
        std::vector<float> d(dist.begin(), dist.end());
        out.Distance = Percentile(d, 0.5) * px;
        out.Offset[0] = ox / dist.size() * px;
        out.Offset[1] = oy / dist.size() * px;
        int most = 0;
        for (const auto& v : votes)
          if (v.second > most)
          {
            most = v.second;
            out.Match = static_cast<int>(fl.size()) + v.first;
          }
      }
      res.Lines.push_back(std::move(out));
    }
    for (const auto& l : pl)
      res.Lines.push_back(toWorld(l, 1));
  }
  res.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

std::string PhotographResult::Json() const
{
  std::ostringstream o;
  o.precision(9);
  auto text = [](const std::string& s) {
    std::string out = "\"";
    for (char c : s)
    {
      if (c == '"' || c == '\\')
        out += '\\';
      out += c;
    }
    return out + "\"";
  };
  o << "{\"match\": " << (Match ? "true" : "false") << ", \"reason\": " << text(Reason)
    << ", \"start\": " << text(Start) << ", \"scale\": " << J{Scale} << ", \"rotation\": " << J{Rotation}
    << ", \"shift\": [" << J{Shift[0]} << ", " << J{Shift[1]} << "], \"photo_pixel_size\": " << J{PhotoPixelSize}
    << ", \"sigma_shift\": [" << J{Sigma[0]} << ", " << J{Sigma[1]} << "], \"sigma_rotation\": " << J{Sigma[2]}
    << ", \"sigma_scale\": " << J{Sigma[3]} << ", \"edge_uncertainty\": " << J{EdgeUncertainty}
    << ", \"edge_noise\": " << J{EdgeNoise} << ", \"edge_spread\": " << J{EdgeSpread}
    << ", \"uncertainty_window\": " << UncertaintyWindow << ", \"weak_direction\": " << J{WeakDirection} << ", \"weak_ratio\": " << J{WeakRatio}
    << ", \"warnings\": " << text(Warnings)
    << ", \"score\": " << J{Score} << ", \"threshold\": " << J{Threshold} << ", \"null_score\": " << J{NullScore}
    << ", \"coarse_score\": " << J{CoarseScore} << ", \"overlap\": " << J{Overlap}
    << ", \"grey_fitted\": " << (GreyFitted ? "true" : "false") << ", \"grey_reason\": " << text(GreyReason)
    << ", \"gamma\": " << J{Gamma} << ", \"gamma_error\": " << J{GammaError} << ", \"background\": " << J{Background}
    << ", \"film_background\": " << J{FilmBackground} << ", \"vignetting\": " << J{Vignetting}
    << ", \"grey_residual\": " << J{GreyResidual} << ", \"grey_pixels\": " << GreyPixels
    << ", \"seconds\": " << J{Seconds} << ", \"lines\": [";
  for (std::size_t l = 0; l < Lines.size(); ++l)
  {
    const PhotographLine& L = Lines[l];
    o << (l ? ", " : "") << "{\"image\": " << (L.Image ? "\"photograph\"" : "\"film\"")
      << ", \"match\": " << L.Match << ", \"distance\": " << J{L.Distance} << ", \"offset\": [" << J{L.Offset[0]}
      << ", " << J{L.Offset[1]} << "], \"matched\": " << J{L.Matched} << ", \"points\": [";
    for (std::size_t a = 0; a < L.Points.size(); ++a)
      o << (a ? ", " : "") << J{L.Points[a]};
    o << "]}";
  }
  o << "]}";
  return o.str();
}

} // namespace schlieren
