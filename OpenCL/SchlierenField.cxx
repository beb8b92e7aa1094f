// SPDX-License-Identifier: BSD-3-Clause
// Field preparation: grid checks, ValidateIndex, the gradient, PackField and PackFieldHighOrder.
#include "SchlierenEngineInternal.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace schlieren
{

void Volume::GetBounds(double b[6]) const
{
  for (int a = 0; a < 3; ++a)
  {
    const double lo = Origin[a] + Ghost * Spacing[a], hi = Origin[a] + (Dimensions[a] - 1 - Ghost) * Spacing[a];
    b[2 * a] = std::min(lo, hi);
    b[2 * a + 1] = std::max(lo, hi);
  }
}

void CheckGrid(const int dims[3], const double spacing[3])
{
  for (int a = 0; a < 3; ++a)
  {
    if (dims[a] < 2)
    {
      std::ostringstream msg;
      msg << "The volume is " << dims[0] << " x " << dims[1] << " x " << dims[2]
          << " points: tracing needs at least 2 points along every axis (axis " << "xyz"[a]
          << " has " << dims[a]
          << "). Give the source or reader a 3D extent; a 2D result (planar or axisymmetric) goes "
             "through RefractiveIndex with Symmetry Planar or Axisymmetric.";
      throw Error(msg.str());
    }
    if (!(spacing[a] > 0) || !std::isfinite(spacing[a]))
    {
      std::ostringstream msg;
      msg << "The grid spacing along " << "xyz"[a] << " is " << spacing[a]
          << ": it must be positive and finite.";
      throw Error(msg.str());
    }
  }
}

std::string ScanIndex(const float* n1, std::size_t count, float& rangeLo, float& rangeHi)
{
  // one pass over the field on every core (a 512^3 field is 0.5 GB: one thread took ~0.12 s for
  // the check and ~0.23 s for the range)
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const unsigned nt = static_cast<unsigned>(std::min<std::size_t>(cores, count / 65536 + 1));
  struct Part
  {
    std::size_t nonfinite = 0, nonpositive = 0, first = 0;
    float lo = 0, hi = 0;
    bool any = false;
  };
  std::vector<Part> parts(nt);
  RunOnThreads(nt, [&](unsigned t) {
    const std::size_t i0 = count * t / nt, i1 = count * (t + 1) / nt;
    Part p;
    p.first = count;
    float lo = 0, hi = 0;
    bool any = false;
    for (std::size_t i = i0; i < i1; ++i)
    {
      const float v = n1[i];
      if (std::isfinite(v) && v > -1.0f)
      {
        lo = any ? std::min(lo, v) : v;
        hi = any ? std::max(hi, v) : v;
        any = true;
        continue;
      }
      ++(std::isfinite(v) ? p.nonpositive : p.nonfinite);
      p.first = std::min(p.first, i);
    }
    p.lo = lo;
    p.hi = hi;
    p.any = any;
    parts[t] = p;
  });
  std::size_t nonfinite = 0, nonpositive = 0, first = count;
  bool any = false;
  rangeLo = rangeHi = 0;
  for (const Part& p : parts)
  {
    nonfinite += p.nonfinite;
    nonpositive += p.nonpositive;
    first = std::min(first, p.first);
    if (p.any)
    {
      rangeLo = any ? std::min(rangeLo, p.lo) : p.lo;
      rangeHi = any ? std::max(rangeHi, p.hi) : p.hi;
      any = true;
    }
  }
  if (nonfinite == 0 && nonpositive == 0)
    return std::string();
  std::ostringstream msg;
  msg << "n_minus_1 is not usable: ";
  if (nonfinite)
    msg << nonfinite << " of " << count << " points are NaN or Inf";
  if (nonfinite && nonpositive)
    msg << " and ";
  if (nonpositive)
    msg << nonpositive << " of " << count << " points have n <= 0";
  msg << " (first at point " << first
      << "). Check the input arrays (density, temperature, pressure) for invalid values, or mask "
         "them before tracing.";
  return msg.str();
}

std::string ValidateIndex(const float* n1, std::size_t count)
{
  float lo, hi;
  return ScanIndex(n1, count, lo, hi);
}

// The second-order difference along axis a at point idx of n1, whose index along a is c (central
// inside, one-sided at the borders): PackField's gradient, and PackFieldHighOrder's where the data
// is not smooth.
static inline double Difference2(const int dims[3], const std::size_t strides[3], const double spacing[3],
  const float* n1, std::size_t idx, int c, int a)
{
  const std::size_t s = strides[a];
  if (c == 0)
    return (double(n1[idx + s]) - n1[idx]) / spacing[a];
  if (c == dims[a] - 1)
    return (double(n1[idx]) - n1[idx - s]) / spacing[a];
  return (double(n1[idx + s]) - n1[idx - s]) / (2.0 * spacing[a]);
}

static inline void Gradient2(const int dims[3], const std::size_t strides[3], const double spacing[3],
  const float* n1, int i, int j, int k, double g[3])
{
  const int ijk[3] = { i, j, k };
  const std::size_t idx = i * strides[0] + j * strides[1] + k * strides[2];
  for (int a = 0; a < 3; ++a)
    g[a] = Difference2(dims, strides, spacing, n1, idx, ijk[a], a);
}

template <typename Store>
static void GradientLoop(const int dims[3], const double spacing[3], const float* n1, Store store)
{
  const std::size_t sx = 1, sy = dims[0], sz = static_cast<std::size_t>(dims[0]) * dims[1];
  const std::size_t strides[3] = { sx, sy, sz };
  auto worker = [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
        {
          double g[3];
          Gradient2(dims, strides, spacing, n1, i, j, k, g);
          store(i * sx + j * sy + k * sz, g);
        }
  };
  const int nt = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
  RunOnThreads(static_cast<unsigned>(nt),
    [&](unsigned t) { worker(dims[2] * int(t) / nt, dims[2] * (int(t) + 1) / nt); });
}

void ComputeGradient(const int dims[3], const double spacing[3], const float* n1, float* grad3)
{
  CheckGrid(dims, spacing);
  GradientLoop(dims, spacing, n1, [grad3](std::size_t idx, const double g[3]) {
    grad3[3 * idx] = static_cast<float>(g[0]);
    grad3[3 * idx + 1] = static_cast<float>(g[1]);
    grad3[3 * idx + 2] = static_cast<float>(g[2]);
  });
}

void PackField(const int dims[3], const double spacing[3], const float* n1, float* out)
{
  CheckGrid(dims, spacing);
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::string bad = ValidateIndex(n1, n);
  if (!bad.empty())
    throw Error(bad);
  PackFieldOf(dims, spacing, n1, out);
}

// Runs body(k0, k1) over z ranges on up to 8 threads (the packing loops).
template <typename Body>
static void ParallelSlices(int nz, Body body)
{
  const int nt = std::max(1, std::min(std::min(8, nz), static_cast<int>(std::thread::hardware_concurrency())));
  RunOnThreads(static_cast<unsigned>(nt),
    [&](unsigned t) { body(nz * int(t) / nt, nz * (int(t) + 1) / nt); });
}

// Calls point(i, j, k, o) for every slot o of a packed field in layout L, in the order the slots
// lie in memory (the writes stream, in either layout: bricks written point by point along the
// rows of the linear field took 1.7-2x the linear packing's time at 256^3 and 512^3), on threads
// over layers along z (a layer of bricks, or a plane). The slots past the grid (the last bricks'
// padding) take the nearest point of the grid: they repeat the border points, as the copy of
// BrickedField does.
template <typename Point>
static void ForEachSlot(const int dims[3], const FieldLayout& L, float* out, Point point)
{
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  if (!L.Bricked)
  {
    ParallelSlices(nz, [&](int k0, int k1) {
      float* o = out + L.At(0, 0, k0);
      for (int k = k0; k < k1; ++k)
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i, o += 4)
            point(i, j, k, o);
    });
    return;
  }
  const BrickLayout b(dims);
  const int B = 1 << FieldBrickShift;
  ParallelSlices(static_cast<int>(b.Bricks[2]), [&](int z0, int z1) {
    float* o = out + std::size_t(z0) * b.LayerFloats();
    for (int bz = z0; bz < z1; ++bz)
      for (int by = 0; by < int(b.Bricks[1]); ++by)
        for (int bx = 0; bx < int(b.Bricks[0]); ++bx)
          for (int kk = 0; kk < B; ++kk)
          {
            const int k = std::min(bz * B + kk, nz - 1);
            for (int jj = 0; jj < B; ++jj)
            {
              const int j = std::min(by * B + jj, ny - 1);
              for (int ii = 0; ii < B; ++ii, o += 4)
                point(std::min(bx * B + ii, nx - 1), j, k, o);
            }
          }
  });
}

void PackFieldOf(const int dims[3], const double spacing[3], const float* n1, float* out, bool bricked)
{
  const FieldLayout L(dims, bricked);
  const std::size_t strides[3] = { 1, std::size_t(dims[0]), std::size_t(dims[0]) * dims[1] };
  ForEachSlot(dims, L, out, [&](int i, int j, int k, float* o) {
    double g[3];
    Gradient2(dims, strides, spacing, n1, i, j, k, g);
    o[0] = n1[i + j * strides[1] + k * strides[2]];
    o[1] = static_cast<float>(g[0]);
    o[2] = static_cast<float>(g[1]);
    o[3] = static_cast<float>(g[2]);
  });
}

// The smoothness test of a row (PackFieldHighOrderOf, step 1): ok[i] &= the five-point test at i
// of row values f0..f4. Built twice (the loop vectorises with AVX2's conversions of floats to
// doubles, not with the baseline's SSE2), the CPU's clone chosen at load time: the same doubles,
// the same decisions (no FMA in either clone).
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__) && defined(__linux__) // ifunc: ELF only
__attribute__((target_clones("avx2", "default")))
#endif
static void FivePointTest(const float* f0, const float* f1, const float* f2, const float* f3,
  const float* f4, unsigned char* ok, int i0, int i1, double TH, double FL)
{
  for (int i = i0; i < i1; ++i)
  {
    const double a0 = f0[i], a1 = f1[i], a2 = f2[i], a3 = f3[i], a4 = f4[i];
    const double lo = std::min(std::min(std::min(a0, a1), std::min(a2, a3)), a4);
    const double hi = std::max(std::max(std::max(a0, a1), std::max(a2, a3)), a4);
    const double d4 = a0 - 4 * a1 + 6 * a2 - 4 * a3 + a4;
    ok[i] = ok[i] & (std::fabs(d4) <= TH * (hi - lo + FL) ? 1 : 0);
  }
}

// One bit per point, rows of W words along x (row r = j + k ny): the smoothness passes' masks.
// The erosions of a mask (dst = the AND of src shifted by offsets along one axis) read and write an
// eighth of what byte rows took, and the masks' scratch is a sixteenth of the packed field's.
// Bits past a row's last point (nx - 1) are never read: the shifts stop at the row's ends.
using Words = std::vector<std::uint64_t, PageAlignedAllocator<std::uint64_t>>;

namespace
{
struct BitGrid
{
  int nx, ny, nz, W;
  std::size_t Words() const { return static_cast<std::size_t>(ny) * nz * W; }
  // bits s .. s + 63 of a row; positions before 0 or past nx - 1 read the row's end bit (clamp)
  // or 0
  std::uint64_t At(const std::uint64_t* in, long s, bool clamp) const
  {
    const long lo = std::max(s, 0L), hi = std::min(s + 63, long(nx) - 1);
    std::uint64_t v = 0;
    if (lo <= hi)
    {
      const int len = int(hi - lo + 1), off = int(lo & 63);
      const long w = lo >> 6;
      std::uint64_t chunk = in[w] >> off;
      if (off && off + len > 64)
        chunk |= in[w + 1] << (64 - off);
      if (len < 64)
        chunk &= (std::uint64_t(1) << len) - 1;
      v = chunk << (lo - s);
    }
    if (!clamp)
      return v;
    if (s < 0 && (in[0] & 1))
    {
      const long below = std::min(-s, 64L); // bits 0 .. below - 1 lie before the row
      v |= below >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << below) - 1;
    }
    if (s + 63 > long(nx) - 1 && ((in[(nx - 1) >> 6] >> ((nx - 1) & 63)) & 1))
    {
      const long first = std::max(0L, long(nx) - s); // bits first .. 63 lie past the row
      v |= first >= 64 ? 0 : ~std::uint64_t(0) << first;
    }
    return v;
  }
  // dst = the AND over the offsets d of src at (point + d along axis a); beyond the grid the
  // border's bit (clamp) or 0
  void Erode(const std::uint64_t* S, std::uint64_t* D, int a, std::initializer_list<int> offsets,
    bool clamp) const
  {
    int off[5] = { 0, 0, 0, 0, 0 }, no = 0;
    for (int d : offsets)
      off[no++] = d;
    const BitGrid g = *this;
    ParallelSlices(nz, [=](int k0, int k1) {
      for (int k = k0; k < k1; ++k)
        for (int j = 0; j < g.ny; ++j)
        {
          const std::size_t row = (std::size_t(k) * g.ny + j) * g.W;
          std::uint64_t* out = D + row;
          if (a == 0)
          {
            for (int w = 0; w < g.W; ++w)
            {
              std::uint64_t v = ~std::uint64_t(0);
              for (int o = 0; o < no; ++o)
                v &= g.At(S + row, long(w) * 64 + off[o], clamp);
              out[w] = v;
            }
            continue;
          }
          for (int w = 0; w < g.W; ++w)
            out[w] = ~std::uint64_t(0);
          for (int o = 0; o < no; ++o)
          {
            int c = (a == 1 ? j : k) + off[o];
            const int na = a == 1 ? g.ny : g.nz;
            if (c < 0 || c > na - 1)
            {
              if (!clamp)
              {
                for (int w = 0; w < g.W; ++w)
                  out[w] = 0;
                break;
              }
              c = c < 0 ? 0 : na - 1;
            }
            const std::uint64_t* in =
              S + ((a == 1 ? std::size_t(k) * g.ny + c : std::size_t(c) * g.ny + j) * g.W);
            for (int w = 0; w < g.W; ++w)
              out[w] &= in[w];
          }
        }
    });
  }
};
} // namespace

double PackFieldHighOrder(const int dims[3], const double spacing[3], const float* n1, float* out,
  unsigned char* smooth, double threshold)
{
  CheckGrid(dims, spacing);
  if (!(threshold > 0) || !std::isfinite(threshold))
    throw Error("PackFieldHighOrder: the smoothness threshold must be positive and finite.");
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  float lo, hi;
  std::string bad = ScanIndex(n1, n, lo, hi);
  if (!bad.empty())
    throw Error(bad);
  return PackFieldHighOrderOf(dims, spacing, n1, out, smooth, threshold, lo, hi, 7);
}

double PackFieldHighOrderOf(const int dims[3], const double spacing[3], const float* n1, float* out,
  unsigned char* smooth, double threshold, float rangeLo, float rangeHi, int levelMax, bool bricked)
{
  const FieldLayout layout(dims, bricked);
  const std::size_t strides[3] = { 1, static_cast<std::size_t>(dims[0]),
    static_cast<std::size_t>(dims[0]) * dims[1] };
  // structure below this part of the field's range is left to the smooth scheme: its overshoot
  // there is far below what the tracer resolves (steps are flagged for 1 % of the range)
  const double floor = 1e-4 * (double(rangeHi) - rangeLo) + 1e-30;
  const BitGrid grid{ dims[0], dims[1], dims[2], (dims[0] + 63) / 64 };
  const int nx = dims[0], ny = dims[1], nz = dims[2], W = grid.W;
  // (every mask is written whole before it is read: no zero fill, whose first touch of the memory
  // would run on one thread)
  Words point(grid.Words()), jumpFree(grid.Words());
  // 1. the smooth points: two or more points from every border, and along every axis a fourth
  // difference small against the range of the five points (a jump or a kink makes it of the
  // order of the range; smooth data makes it O(h^2) smaller)
  // (near a border the five points are the five nearest inside: jumpFree, what the step length
  // needs; point adds the two points of margin that the fourth-order stencils need)
  {
    // the loops read the grid's sizes from locals (captured by value): stores could alias
    // captured references, which the compiler must then reload at every point
    const std::size_t sy = strides[1], sz = strides[2];
    std::uint64_t* const PT = point.data();
    std::uint64_t* const JF = jumpFree.data();
    const double TH = threshold, FL = floor;
    ParallelSlices(nz, [=](int k0, int k1) {
      // bytes b[0 .. nx - 1] (0 or 1) as the row's bits
      auto toBits = [nx, W](const unsigned char* b, std::uint64_t* bits) {
        for (int w = 0; w < W; ++w)
        {
          std::uint64_t v = 0;
          const int n = std::min(64, nx - 64 * w);
          for (int i = 0; i < n; ++i)
            v |= std::uint64_t(b[64 * w + i]) << i;
          bits[w] = v;
        }
      };
      std::vector<unsigned char> ok(static_cast<std::size_t>(nx)), pt(static_cast<std::size_t>(nx));
      const bool tooThin = nx < 5 || ny < 5 || nz < 5;
      for (int k = k0; k < k1; ++k)
        for (int j = 0; j < ny; ++j)
        {
          const std::size_t row = (std::size_t(k) * ny + j) * W;
          if (tooThin)
          {
            std::fill(JF + row, JF + row + W, std::uint64_t(0));
            std::fill(PT + row, PT + row + W, std::uint64_t(0));
            continue;
          }
          std::fill(ok.begin(), ok.end(), static_cast<unsigned char>(1));
          // along x: the five points around i, those around 2 (or nx - 3) near the ends
          const float* r = n1 + j * sy + k * sz;
          FivePointTest(r - 2, r - 1, r, r + 1, r + 2, ok.data(), 2, nx - 2, TH, FL);
          for (int i = 0; i < 2; ++i)
            ok[i] = ok[2];
          for (int i = nx - 2; i < nx; ++i)
            ok[i] = ok[nx - 3];
          // along y and z: the five rows around j (k), those around 2 (or n - 3) near the ends
          const int jc = std::min(std::max(j, 2), ny - 3), kc = std::min(std::max(k, 2), nz - 3);
          const float* ry = n1 + jc * sy + k * sz;
          FivePointTest(ry - 2 * sy, ry - sy, ry, ry + sy, ry + 2 * sy, ok.data(), 0, nx, TH, FL);
          const float* rz = n1 + j * sy + kc * sz;
          FivePointTest(rz - 2 * sz, rz - sz, rz, rz + sz, rz + 2 * sz, ok.data(), 0, nx, TH, FL);
          const bool innerRow = j >= 2 && j <= ny - 3 && k >= 2 && k <= nz - 3;
          for (int i = 0; i < nx; ++i)
            pt[i] = (innerRow && i >= 2 && i <= nx - 3) ? ok[i] : 0;
          toBits(ok.data(), JF + row);
          toBits(pt.data(), PT + row);
        }
    });
  }
  // 2. n - 1 and the gradient: along each axis, fourth order where the five points of the
  // difference are all smooth (a point beside a jump may pass the test on its own), PackField's
  // second order elsewhere. fourth[a]: those points along axis a (point is 0 two points from the
  // borders, so beyond the grid reads 0).
  Words fourth[3] = { Words(grid.Words()), Words(grid.Words()), Words(grid.Words()) };
  for (int a = 0; a < 3; ++a)
    grid.Erode(point.data(), fourth[a].data(), a, { -2, -1, 0, 1, 2 }, false);
  {
    const double H[3] = { spacing[0], spacing[1], spacing[2] };
    const std::uint64_t* const F[3] = { fourth[0].data(), fourth[1].data(), fourth[2].data() };
    ForEachSlot(dims, layout, out, [&](int i, int j, int k, float* o) {
      const int ijk[3] = { i, j, k };
      const std::size_t idx = i + j * strides[1] + k * strides[2];
      const std::size_t row = (std::size_t(k) * ny + j) * W;
      o[0] = n1[idx];
      for (int a = 0; a < 3; ++a)
      {
        const std::size_t s = strides[a];
        double g;
        if ((F[a][row + (i >> 6)] >> (i & 63)) & 1)
          g = (double(n1[idx - 2 * s]) - 8.0 * n1[idx - s] + 8.0 * n1[idx + s] - n1[idx + 2 * s]) /
            (12.0 * H[a]);
        else
          g = Difference2(dims, strides, spacing, n1, idx, ijk[a], a);
        o[1 + a] = static_cast<float>(g);
      }
    });
  }
  // 3. the smooth cells: cell c (points c .. c + 1) is smooth where the points c - 1 .. c + 2 are,
  // along every axis (beyond the grid: not smooth)
  Words& cell = fourth[0];
  Words& spare = fourth[1];
  grid.Erode(point.data(), spare.data(), 0, { -1, 0, 1, 2 }, false);
  grid.Erode(spare.data(), cell.data(), 1, { -1, 0, 1, 2 }, false);
  grid.Erode(cell.data(), spare.data(), 2, { -1, 0, 1, 2 }, false);
  cell.swap(spare);
  // 4. level q (1 .. 7) of a cell: every cell within 2^q cells (Chebyshev distance) is free of
  // jumps (its points c - 1 .. c + 2 inside the grid are jumpFree; beyond the grid no step goes).
  // A cube erosion of radius 1 (offsets -1, 0, 1), then radius r -> 2 r by offsets -r, r.
  Words& A = point; // free now
  Words& B = fourth[2];
  grid.Erode(jumpFree.data(), A.data(), 0, { -1, 0, 1, 2 }, true);
  grid.Erode(A.data(), B.data(), 1, { -1, 0, 1, 2 }, true);
  grid.Erode(B.data(), A.data(), 2, { -1, 0, 1, 2 }, true);
  grid.Erode(A.data(), B.data(), 0, { -1, 0, 1 }, true);
  grid.Erode(B.data(), A.data(), 1, { -1, 0, 1 }, true);
  grid.Erode(A.data(), B.data(), 2, { -1, 0, 1 }, true);
  // each cell's level as three bit planes, level = L0 + 2 L1 + 4 L2: for each level q the cells
  // of its set take q (a bit row per plane, not a byte per cell per level); the bytes are written
  // once, below
  Words& L0 = spare; // free now, as jumpFree is
  Words& L1 = jumpFree;
  Words L2(grid.Words());
  {
    std::uint64_t* const P0 = L0.data();
    std::uint64_t* const P1 = L1.data();
    std::uint64_t* const P2 = L2.data();
    ParallelSlices(nz, [=](int k0, int k1) {
      const std::size_t w0 = std::size_t(k0) * ny * W, w1 = std::size_t(k1) * ny * W;
      std::fill(P0 + w0, P0 + w1, std::uint64_t(0));
      std::fill(P1 + w0, P1 + w1, std::uint64_t(0));
      std::fill(P2 + w0, P2 + w1, std::uint64_t(0));
    });
  }
  for (int q = 1, r = 1; q <= std::min(levelMax, 7); ++q, r *= 2)
  {
    // B holds level q - 1's cells (q = 1: the radius-1 erosion): x, y, z by offsets -r, r
    grid.Erode(B.data(), A.data(), 0, { -r, r }, true);
    grid.Erode(A.data(), B.data(), 1, { -r, r }, true);
    grid.Erode(B.data(), A.data(), 2, { -r, r }, true);
    A.swap(B);
    // B holds this level's cells: their level is q (a subset of the last level's)
    std::atomic<bool> any(false);
    const std::uint64_t* const L = B.data();
    std::uint64_t* const P[3] = { L0.data(), L1.data(), L2.data() };
    ParallelSlices(nz, [=, &any](int k0, int k1) {
      std::uint64_t found = 0;
      for (std::size_t row = std::size_t(k0) * ny; row < std::size_t(k1) * ny; ++row)
        for (int w = 0; w < W; ++w)
        {
          std::uint64_t v = L[row * W + w];
          if (w == W - 1 && (nx & 63))
            v &= (std::uint64_t(1) << (nx & 63)) - 1;
          found |= v;
          for (int b = 0; b < 3; ++b)
          {
            std::uint64_t& plane = P[b][row * W + w];
            plane = ((q >> b) & 1) ? (plane | v) : (plane & ~v);
          }
        }
      if (found)
        any = true;
    });
    if (!any)
      break;
  }
  // the smoothness bytes (the smooth cell bit and the level), and the smooth share of the cells
  // (c .. c + 1 inside the grid)
  std::atomic<std::size_t> count(0);
  {
    const std::uint64_t* const C = cell.data();
    const std::uint64_t* const P[3] = { L0.data(), L1.data(), L2.data() };
    ParallelSlices(nz, [=, &count](int k0, int k1) {
      std::size_t c = 0;
      for (int k = k0; k < k1; ++k)
        for (int j = 0; j < ny; ++j)
        {
          const std::size_t row = (std::size_t(k) * ny + j) * W;
          const std::uint64_t* bits = C + row;
          unsigned char* s = smooth + (std::size_t(k) * ny + j) * nx;
          for (int w = 0; w < W; ++w)
          {
            const std::uint64_t cw = bits[w], p0 = P[0][row + w], p1 = P[1][row + w],
                                p2 = P[2][row + w];
            const int n = std::min(64, nx - 64 * w);
            for (int i = 0; i < n; ++i)
            {
              const unsigned level = unsigned((p0 >> i) & 1) | unsigned((p1 >> i) & 1) << 1 |
                unsigned((p2 >> i) & 1) << 2;
              s[64 * w + i] = static_cast<unsigned char>(
                (((cw >> i) & 1) ? SCH_SMOOTH_CELL : 0) | (level << SCH_SMOOTH_SHIFT));
            }
          }
          if (k + 1 < nz && j + 1 < ny)
            for (int w = 0; w < W; ++w)
            {
              const int last = std::min(64, nx - 1 - 64 * w); // cells i < nx - 1
              if (last > 0)
                c += __builtin_popcountll(last >= 64 ? bits[w] : bits[w] & ((std::uint64_t(1) << last) - 1));
            }
        }
      count += c;
    });
  }
  const std::size_t total = std::size_t(nx - 1) * (ny - 1) * (nz - 1);
  return total ? double(count.load()) / total : 0.0;
}

BrickLayout::BrickLayout(const int dims[3])
{
  for (int a = 0; a < 3; ++a)
    Bricks[a] = (std::uint64_t(dims[a]) + (1u << FieldBrickShift) - 1) >> FieldBrickShift;
}

bool BricksFit(const int dims[3])
{
  // the kernels' strides are ints: a layer of bricks past that reads the field linear
  return BrickLayout(dims).LayerFloats() <= 2147483647u;
}

FieldLayout::FieldLayout(const int dims[3], bool bricked)
{
  const BrickLayout b(dims);
  Bricked = bricked && BricksFit(dims);
  if (!Bricked)
  {
    Inner[0] = 4;
    Inner[1] = 4 * dims[0];
    Inner[2] = static_cast<int>(std::min<std::uint64_t>(std::uint64_t(4) * dims[0] * dims[1], 2147483647u));
    Floats = std::uint64_t(4) * dims[0] * dims[1] * dims[2];
    Row = std::size_t(4) * dims[0];
    Plane = Row * dims[1];
    return;
  }
  const int B = 1 << FieldBrickShift;
  Shift = FieldBrickShift;
  Mask = B - 1;
  Inner[0] = 4;
  Inner[1] = 4 * B;
  Inner[2] = 4 * B * B;
  Outer[0] = static_cast<int>(BrickLayout::BrickFloats());
  Outer[1] = static_cast<int>(BrickLayout::BrickFloats() * b.Bricks[0]);
  Outer[2] = static_cast<int>(b.LayerFloats());
  Floats = b.Floats();
}

void SetFieldLayout(sch_params& P, bool bricked)
{
  const int dims[3] = { P.nx, P.ny, P.nz };
  const FieldLayout L(dims, bricked);
  P.fieldShift = L.Shift;
  P.fieldMask = L.Mask;
  P.innerX = L.Inner[0];
  P.innerY = L.Inner[1];
  P.innerZ = L.Inner[2];
  P.outerX = L.Outer[0];
  P.outerY = L.Outer[1];
  P.outerZ = L.Outer[2];
}

bool PackInBricks(const int dims[3])
{
  const int forced = GetRuntimeOptions().Bricks;
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || !BricksFit(dims) || forced == 0)
    return false;
  if (forced == 1)
    return true;
  // unset: where they pay (docs/PERFORMANCE.md, "the field packed in bricks"): large grids, on every
  // backend and reconstruction (the CPU backend's Cubic, linear until 2026-12-08: its oblique view
  // 1.6-1.9x its axis view's time a sample at 512^3 there, 1.06-1.27x in bricks, where the oblique
  // view is 1.05-1.44x faster and the axis view 1.2-1.5x slower, as on PoCL), but not where the
  // padding to whole bricks would add more than a tenth (a thin grid: 9 planes
  // take 12)
  const double points = double(dims[0]) * dims[1] * dims[2];
  return points > BricksFromPoints && double(FieldLayout(dims, true).Floats) <= 1.1 * 4.0 * points;
}

// Volume::Field (linear) copied into bricks, in the bricks' memory order (ForEachSlot).
static void MakeBricks(const Volume& v, float* out)
{
  const std::size_t sy = std::size_t(v.Dimensions[0]), sz = sy * v.Dimensions[1];
  const float* in = v.Field;
  ForEachSlot(v.Dimensions, FieldLayout(v.Dimensions, true), out, [&](int i, int j, int k, float* o) {
    std::memcpy(o, in + 4 * (i + j * sy + k * sz), 4 * sizeof(float));
  });
}

namespace
{
struct KeptBricks
{
  VolumeIdentity Of;
  std::shared_ptr<const AlignedFloats> Bricks;
};
// Never destroyed (as the kept tracer): a TraceSession that a front end destroys after the exit
// handlers ran (ParaView's session at pvpython's exit) still releases the bricks through it; a
// static object here was destroyed first, and that release freed its shared_ptr a second time
// (glibc: "corrupted double-linked list", an abort at exit).
KeptBricks& Kept()
{
  static KeptBricks* kept = new KeptBricks;
  return *kept;
}
} // namespace

std::shared_ptr<const AlignedFloats> BrickedField(const Volume& v)
{
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    if (Kept().Bricks && Kept().Of == VolumeIdentity(v))
      return Kept().Bricks;
  }
  // the last volume's bricks go before this one's are made
  if (v.Stamp != 0)
    ReleaseBrickedField();
  // a second copy of the field: made where it takes at most half the memory left
  const double bytes = double(BrickLayout(v.Dimensions).Floats()) * sizeof(float);
  if (bytes > 0.5 * double(AvailableMemory()))
    throw std::bad_alloc();
  auto bricks = std::make_shared<AlignedFloats>(BrickLayout(v.Dimensions).Floats());
  MakeBricks(v, bricks->data());
  if (v.Stamp != 0)
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    Kept().Of = VolumeIdentity(v);
    Kept().Bricks = bricks;
  }
  return bricks;
}

void ReleaseBrickedField()
{
  std::shared_ptr<const AlignedFloats> gone;
  std::lock_guard<std::mutex> lock(KeptMutex);
  gone.swap(Kept().Bricks);
  Kept().Of = VolumeIdentity();
}

void CheckVolume(const Volume& v)
{
  CheckGrid(v.Dimensions, v.Spacing);
  if (!v.Field)
    throw Error("The volume has no field data.");
  for (int a = 0; a < 3; ++a)
    if (v.Ghost < 0 || v.Dimensions[a] < 2 * v.Ghost + 2)
      throw Error("The volume's Ghost layers (" + std::to_string(v.Ghost) +
        ") leave no box inside its points: 0 for a volume of the caller's.");
}

} // namespace schlieren
