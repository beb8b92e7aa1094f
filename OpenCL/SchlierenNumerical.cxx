// SPDX-License-Identifier: BSD-3-Clause
// Numerical schlieren: Quirk's grey scale of the density gradient on a plane or along the view.
#include "SchlierenNumerical.h"
#include "SchlierenEngineInternal.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

namespace schlieren
{

namespace
{
void CheckRange(const char* name, double v, double lo, double hi, const char* what)
{
  if (!(v >= lo && v <= hi))
  {
    std::ostringstream msg;
    msg << name << " is " << v << ": it must be in [" << lo << ", " << hi << "] (" << what << ").";
    throw Error(msg.str());
  }
}

TraceSettings FilmSettings(const NumericalSettings& s)
{
  TraceSettings t;
  for (int a = 0; a < 3; ++a)
  {
    t.ViewDirection[a] = s.ViewDirection[a];
    t.ViewUp[a] = s.ViewUp[a];
  }
  t.Resolution[0] = s.Resolution[0];
  t.Resolution[1] = s.Resolution[1];
  return t;
}

Volume GridOf(const ScalarGrid& g)
{
  Volume v;
  for (int a = 0; a < 3; ++a)
  {
    v.Dimensions[a] = g.Dimensions[a];
    v.Origin[a] = g.Origin[a];
    v.Spacing[a] = g.Spacing[a];
  }
  return v;
}

/**
 * The gradient at every grid point, 3 floats per point: central differences between fluid
 * neighbours, one-sided where one neighbour is solid (or excluded) or outside the box, 0 along an
 * axis one point thick, at a solid or excluded point, or where both neighbours are.
 */
std::vector<float> PointGradient(const ScalarGrid& g)
{
  const int nx = g.Dimensions[0], ny = g.Dimensions[1], nz = g.Dimensions[2];
  const std::size_t n = std::size_t(nx) * ny * nz;
  std::vector<float> grad(3 * n, 0.0f);
  const std::size_t stride[3] = { 1, std::size_t(nx), std::size_t(nx) * ny };
  auto fluid = [&](std::size_t i) {
    return (!g.Solid || g.Solid[i] == 0) && (!g.Excluded || g.Excluded[i] == 0);
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const std::size_t p = i + stride[1] * j + stride[2] * k;
        if (!fluid(p))
          continue;
        const int idx[3] = { i, j, k };
        for (int a = 0; a < 3; ++a)
        {
          const bool lo = idx[a] > 0 && fluid(p - stride[a]);
          const bool hi = idx[a] < g.Dimensions[a] - 1 && fluid(p + stride[a]);
          double d = 0.0;
          if (lo && hi)
            d = (double(g.Values[p + stride[a]]) - g.Values[p - stride[a]]) / (2 * g.Spacing[a]);
          else if (hi)
            d = (double(g.Values[p + stride[a]]) - g.Values[p]) / g.Spacing[a];
          else if (lo)
            d = (double(g.Values[p]) - g.Values[p - stride[a]]) / g.Spacing[a];
          grad[3 * p + a] = static_cast<float>(d);
        }
      }
  return grad;
}

/** Trilinear sampling of the point gradient and of the solid points at a world position. */
struct Sampler
{
  const ScalarGrid& G;
  const std::vector<float>& Grad;

  /** False where x is outside the box (an axis one point thick takes any coordinate). */
  bool Sample(const double x[3], double out[3], bool& solid) const
  {
    int i0[3];
    double w[3];
    for (int a = 0; a < 3; ++a)
    {
      const int n = G.Dimensions[a];
      if (n == 1)
      {
        i0[a] = 0;
        w[a] = 0.0;
        continue;
      }
      const double u = (x[a] - G.Origin[a]) / G.Spacing[a];
      const double tol = 1e-9 * (n - 1);
      if (!(u >= -tol && u <= (n - 1) + tol))
        return false;
      const double c = std::min(std::max(u, 0.0), double(n - 1));
      int f = static_cast<int>(std::floor(c));
      if (f >= n - 1)
        f = n - 2;
      i0[a] = f;
      w[a] = c - f;
    }
    const std::size_t sy = G.Dimensions[0], sz = std::size_t(G.Dimensions[0]) * G.Dimensions[1];
    out[0] = out[1] = out[2] = 0.0;
    double s = 0.0;
    for (int c = 0; c < 8; ++c)
    {
      const int d[3] = { c & 1, (c >> 1) & 1, (c >> 2) & 1 };
      double wt = 1.0;
      std::size_t p = 0;
      bool skip = false;
      for (int a = 0; a < 3; ++a)
      {
        const double wa = d[a] ? w[a] : 1.0 - w[a];
        if (d[a] && G.Dimensions[a] == 1)
          skip = true;
        wt *= wa;
      }
      if (skip || wt == 0.0)
        continue;
      p = std::size_t(i0[0] + d[0]) + sy * (i0[1] + d[1]) + sz * (i0[2] + d[2]);
      for (int a = 0; a < 3; ++a)
        out[a] += wt * Grad[3 * p + a];
      if (G.Solid && G.Solid[p])
        s += wt;
    }
    solid = s >= 0.5;
    return true;
  }
};

/**
 * Refuses a field with NaN or Inf at a point of the flow (not solid, not excluded), as
 * SchlierenImage refuses such an n - 1 (ValidateIndex): the differences beside it would be NaN,
 * the automatic maximum ignores NaN, and the image would come out white or NaN without a word.
 */
void CheckFiniteField(const ScalarGrid& g)
{
  const std::size_t n = std::size_t(g.Dimensions[0]) * g.Dimensions[1] * g.Dimensions[2];
  std::size_t bad = 0, first = n;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (std::isfinite(g.Values[i]) || (g.Solid && g.Solid[i]) || (g.Excluded && g.Excluded[i]))
      continue;
    ++bad;
    first = std::min(first, i);
  }
  if (bad == 0)
    return;
  const std::size_t nx = g.Dimensions[0], ny = g.Dimensions[1];
  std::ostringstream msg;
  msg << "NumericalSchlieren: the field is not usable: " << bad << " of " << n
      << " points of the flow are NaN or Inf (first at point " << first << ", i j k = "
      << first % nx << " " << (first / nx) % ny << " " << first / (nx * ny)
      << "). Check the density array (and the filters before it) for invalid values, or mask "
         "them (vtkValidPointMask 0, or a solid) before imaging.";
  throw Error(msg.str());
}

template <typename F>
void ParallelRows(int rows, F&& f)
{
  const int threads =
    std::max(1, std::min<int>(rows, int(std::max(1u, std::thread::hardware_concurrency()))));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (int r = t; r < rows; r += threads)
        f(r);
    });
  for (auto& th : pool)
    th.join();
}
} // namespace

void CheckNumericalSettings(const NumericalSettings& s)
{
  CheckRange("C0", s.C0, -1.0, 0.0, "the scale's low end, a fraction of the largest gradient");
  CheckRange("C1", s.C1, 0.001, 1.0, "the scale's high end, a fraction of the largest gradient");
  CheckRange("K", s.K, 0.001, 100.0, "the grey scale exp(-K S)");
  CheckRange("StepSize", s.StepSize, 0.05, 8.0, "voxels between the line of sight's samples");
  CheckRange("KnifeAngle", s.KnifeAngle, -180.0, 180.0, "degrees in the film plane");
  if (!(s.Maximum >= 0.0) || !std::isfinite(s.Maximum))
  {
    std::ostringstream msg;
    msg << "GradientMaximum is " << s.Maximum
        << ": it must be 0 (automatic: the largest over the image) or a positive, finite gradient.";
    throw Error(msg.str());
  }
  if (!std::isfinite(s.SliceOffset))
    throw Error("SliceOffset must be finite (world units along the view from the volume's centre).");
  if (s.Mode != NumericalMode::Slice && s.Mode != NumericalMode::LineOfSight)
    throw Error("Mode must be Slice (0) or LineOfSight (1).");
  if (s.Quantity != NumericalQuantity::Magnitude && s.Quantity != NumericalQuantity::KnifeComponent)
    throw Error("Gradient must be Magnitude (0) or KnifeComponent (1).");
}

FilmGeometry NumericalFilm(const ScalarGrid& grid, const NumericalSettings& s)
{
  CheckNumericalSettings(s);
  return MakeFilm(GridOf(grid), FilmSettings(s));
}

double QuirkGrey(double q, double qmax, double c0, double c1, double k)
{
  if (!(qmax > 0))
    return 1.0;
  const double S = (q - c0 * qmax) / ((c1 - c0) * qmax);
  return std::exp(-k * std::min(std::max(S, 0.0), 1.0));
}

NumericalImage NumericalSchlieren(
  const ScalarGrid& grid, const NumericalSettings& s, const ProgressFunction& progress)
{
  NumericalImage out;
  out.Film = NumericalFilm(grid, s);
  const FilmGeometry& f = out.Film;
  if (!grid.Values)
    throw Error("NumericalSchlieren needs the field's values.");
  CheckFiniteField(grid);
  const double points = double(grid.Dimensions[0]) * grid.Dimensions[1] * grid.Dimensions[2];
  const double pixels = double(f.Size[0]) * f.Size[1];
  CheckHostMemory(points * 12.0 + pixels * 9.0, "NumericalSchlieren's gradient and image",
    "Resample the volume to fewer points or lower the Resolution.");

  // The plane's (or the line's) depth along the view, from the volume's centre.
  double h[3];
  for (int a = 0; a < 3; ++a)
    h[a] = 0.5 * (grid.Dimensions[a] - 1) * grid.Spacing[a];
  double depth = 0.0, smallest = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    depth += h[a] * std::fabs(f.Direction[a]);
    if (grid.Dimensions[a] > 1)
      smallest = smallest > 0 ? std::min(smallest, grid.Spacing[a]) : grid.Spacing[a];
  }
  if (s.Mode == NumericalMode::Slice && std::fabs(s.SliceOffset) > depth * (1 + 1e-9))
  {
    std::ostringstream msg;
    msg << "SliceOffset is " << s.SliceOffset << ": the plane must cross the volume, within ["
        << -depth << ", " << depth << "] (world units along the view from its centre).";
    throw Error(msg.str());
  }
  const double step = s.StepSize * (smallest > 0 ? smallest : 1.0);
  const int samples = s.Mode == NumericalMode::Slice
    ? 1
    : std::max(1, static_cast<int>(std::floor(2 * depth / step)) + 1);
  const double first = s.Mode == NumericalMode::Slice ? s.SliceOffset
                                                      : -0.5 * (samples - 1) * step;

  const double angle = s.KnifeAngle * 3.14159265358979323846 / 180.0;
  double knife[3];
  for (int a = 0; a < 3; ++a)
    knife[a] = std::cos(angle) * f.Right[a] + std::sin(angle) * f.Up[a];

  const std::vector<float> grad = PointGradient(grid);
  const Sampler sampler{ grid, grad };
  const std::size_t n = static_cast<std::size_t>(f.Size[0]) * f.Size[1];
  out.Gradient.assign(n, 0.0f);
  out.Blocked.assign(n, 0);
  out.Intensity.assign(n, 1.0f);
  std::vector<double> rowMax(f.Size[1], 0.0);
  // Blocks of rows, each about NumericalBlockSamples samples (at least one row per thread), with
  // the progress between them on this thread; every pixel is its own, so the blocks change no bit.
  const int threads = std::max(1, int(std::thread::hardware_concurrency()));
  const double perRow = std::max(1.0, double(f.Size[0]) * samples);
  const int block = std::max(threads,
    static_cast<int>(std::min<double>(f.Size[1], std::ceil(NumericalBlockSamples / perRow))));
  for (int start = 0; start < f.Size[1]; start += block)
  {
    if (progress && !progress(double(start) / f.Size[1]))
    {
      throw Error("aborted at " + std::to_string(static_cast<int>(100.0 * start / f.Size[1])) +
        " % of the image: no image");
    }
    const int rows = std::min(block, f.Size[1] - start);
    ParallelRows(rows, [&](int r) {
      const int j = start + r;
      for (int i = 0; i < f.Size[0]; ++i)
      {
        const double u = f.Corner[0] + (i + 0.5) * f.PixelSize;
        const double v = f.Corner[1] + (j + 0.5) * f.PixelSize;
        double sum = 0.0;
        int count = 0;
        bool blocked = false;
        for (int t = 0; t < samples && !blocked; ++t)
        {
          const double w = first + t * step;
          double x[3], g[3];
          for (int a = 0; a < 3; ++a)
            x[a] = f.Center[a] + u * f.Right[a] + v * f.Up[a] + w * f.Direction[a];
          bool solid = false;
          if (!sampler.Sample(x, g, solid))
            continue;
          if (solid)
          {
            blocked = true;
            break;
          }
          sum += s.Quantity == NumericalQuantity::Magnitude
            ? std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2])
            : g[0] * knife[0] + g[1] * knife[1] + g[2] * knife[2];
          ++count;
        }
        const std::size_t p = std::size_t(i) + std::size_t(f.Size[0]) * j;
        if (blocked)
        {
          out.Blocked[p] = 1;
          continue;
        }
        const double q = count > 0 ? sum / count : 0.0;
        out.Gradient[p] = static_cast<float>(q);
        rowMax[j] = std::max(rowMax[j], std::fabs(q));
      }
    });
  }
  if (progress)
    progress(1.0);
  for (double m : rowMax)
    out.Largest = std::max(out.Largest, m);
  out.Maximum = s.Maximum > 0 ? s.Maximum : out.Largest;
  for (std::size_t p = 0; p < n; ++p)
    out.Intensity[p] = out.Blocked[p]
      ? 0.0f
      : static_cast<float>(QuirkGrey(std::fabs(out.Gradient[p]), out.Maximum, s.C0, s.C1, s.K));
  return out;
}

namespace
{
template <typename T>
void Put(std::vector<char>& b, const T* v, std::size_t n)
{
  const char* c = reinterpret_cast<const char*>(v);
  b.insert(b.end(), c, c + n * sizeof(T));
}

template <typename T>
void Take(const std::vector<char>& b, std::size_t& at, T* v, std::size_t n)
{
  if (at + n * sizeof(T) > b.size())
    throw Error("NumericalSchlieren: a rank's piece arrived short (an internal error).");
  std::copy(b.begin() + at, b.begin() + at + n * sizeof(T), reinterpret_cast<char*>(v));
  at += n * sizeof(T);
}
} // namespace

std::string AgreedFieldName(Parallel& parallel, const std::string& error, const std::string& mine)
{
  const std::string failure = parallel.Failure(error);
  if (!failure.empty())
    throw Error(failure);
  if (parallel.Size() <= 1)
    return mine;
  // the same array on every rank that holds a piece (the first such rank's name is used)
  std::string agreed, problem;
  for (const std::string& other : parallel.AllGatherStrings(mine))
  {
    if (!other.empty() && agreed.empty())
      agreed = other;
    else if (!other.empty() && other != agreed)
      problem = "NumericalSchlieren: the ranks' pieces carry different density arrays ('" + agreed +
        "', '" + other + "'): name one in DensityArray.";
  }
  if (agreed.empty())
    problem = "NumericalSchlieren needs a non-empty image (vtkImageData): every rank's piece of "
              "the input is empty.";
  if (!problem.empty())
    throw Error(problem);
  return agreed;
}

bool NumericalSchlierenOfPieces(Parallel& parallel, const ScalarGrid& piece, const int offset[3],
  const ScalarGrid& whole, const NumericalSettings& s, NumericalImage& image,
  const ProgressFunction& progress)
{
  image = NumericalImage();
  if (parallel.Size() <= 1)
  {
    image = NumericalSchlieren(piece, s, progress);
    return true;
  }
  // This rank's piece for rank 0: its index range, flags, values, solid and excluded points.
  const std::size_t mine =
    std::size_t(piece.Dimensions[0]) * piece.Dimensions[1] * piece.Dimensions[2];
  std::vector<std::vector<char>> out(parallel.Size());
  if (mine > 0 && piece.Values)
  {
    std::vector<char>& b = out[0];
    const int head[8] = { offset[0], offset[1], offset[2], piece.Dimensions[0],
      piece.Dimensions[1], piece.Dimensions[2], piece.Solid ? 1 : 0, piece.Excluded ? 1 : 0 };
    Put(b, head, 8);
    Put(b, piece.Values, mine);
    if (piece.Solid)
      Put(b, piece.Solid, mine);
    if (piece.Excluded)
      Put(b, piece.Excluded, mine);
  }
  const std::vector<std::vector<char>> in = parallel.Exchange(out);

  std::string error;
  if (parallel.Rank() == 0)
  {
    try
    {
      const int* D = whole.Dimensions;
      const std::size_t n = std::size_t(D[0]) * D[1] * D[2];
      std::vector<float> values(n, 0.0f);
      std::vector<unsigned char> solid, excluded, held(n, 0);
      for (const std::vector<char>& b : in)
      {
        if (b.empty())
          continue;
        std::size_t at = 0;
        int head[8];
        Take(b, at, head, 8);
        for (int a = 0; a < 3; ++a)
          if (head[a] < 0 || head[3 + a] < 0 || head[a] + head[3 + a] > D[a])
            throw Error("NumericalSchlieren: a rank's piece lies outside the whole extent.");
        const std::size_t m = std::size_t(head[3]) * head[4] * head[5];
        std::vector<float> v(m);
        std::vector<unsigned char> so, ex;
        Take(b, at, v.data(), m);
        if (head[6])
        {
          so.resize(m);
          Take(b, at, so.data(), m);
          solid.resize(n, 0);
        }
        if (head[7])
        {
          ex.resize(m);
          Take(b, at, ex.data(), m);
          excluded.resize(n, 0);
        }
        std::size_t k = 0;
        for (int z = 0; z < head[5]; ++z)
          for (int y = 0; y < head[4]; ++y)
            for (int x = 0; x < head[3]; ++x, ++k)
            {
              const std::size_t p =
                (std::size_t(z + head[2]) * D[1] + (y + head[1])) * D[0] + (x + head[0]);
              values[p] = v[k];
              held[p] = 1;
              if (head[6])
                solid[p] = so[k];
              if (head[7])
                excluded[p] = ex[k];
            }
      }
      const std::size_t missing = n - std::size_t(std::count(held.begin(), held.end(), 1));
      if (missing > 0)
      {
        std::ostringstream msg;
        msg << "NumericalSchlieren: the ranks' pieces leave " << missing << " of the volume's "
            << n << " points out (the input's pieces must cover its whole extent).";
        throw Error(msg.str());
      }
      ScalarGrid g = whole;
      g.Values = values.data();
      g.Solid = solid.empty() ? nullptr : solid.data();
      g.Excluded = excluded.empty() ? nullptr : excluded.data();
      image = NumericalSchlieren(g, s, progress);
    }
    catch (const Error& e)
    {
      error = e.what();
    }
  }
  error = parallel.Failure(error);
  if (!error.empty())
    throw Error(error);
  return parallel.Rank() == 0;
}

const char* NumericalModeName(NumericalMode m)
{
  return m == NumericalMode::Slice ? "Slice" : "LineOfSight";
}

const char* NumericalQuantityName(NumericalQuantity q)
{
  return q == NumericalQuantity::Magnitude ? "Magnitude" : "KnifeComponent";
}

} // namespace schlieren
