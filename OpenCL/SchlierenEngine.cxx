// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenEngine.h"
#include "SchlierenLimits.h"
#include "SchlierenOpenCL.h"

// The physics, compiled as C++ for the CPU backend and for the host-side film. The CPU path
// advances 64 rays in turn per packet (sch_trace_packet): more rays' steps in flight. 4 -> 16
// (session 2, 256^3 Gaussian, 512^2 film): Euler 75.8/70.8 -> 83.2/81.2 M samples/s; 16 -> 64
// (session 3, two runs): Gaussian Euler 111 -> 118/120 M, blunt fin Auto (midpoint) 1.40 ->
// 1.75/1.79 M photons/s; 32 was in between.
#define SCH_PACKET 64
#include "SchlierenPhysics.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

namespace schlieren
{

static_assert(sizeof(sch_params) % 4 == 0, "sch_params must hold only 4-byte members");
static_assert(sizeof(RayRecord) == SCH_RECORD * sizeof(float), "RayRecord mirrors SCH_RECORD");

// ------------------------------------------------------------------ field preparation

void Volume::GetBounds(double b[6]) const
{
  for (int a = 0; a < 3; ++a)
  {
    const double lo = Origin[a], hi = Origin[a] + (Dimensions[a] - 1) * Spacing[a];
    b[2 * a] = std::min(lo, hi);
    b[2 * a + 1] = std::max(lo, hi);
  }
}

static void CheckGrid(const int dims[3], const double spacing[3])
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

std::string ValidateIndex(const float* n1, std::size_t count)
{
  std::size_t nonfinite = 0, nonpositive = 0, first = count;
  for (std::size_t i = 0; i < count; ++i)
  {
    const float v = n1[i];
    if (!std::isfinite(v))
    {
      ++nonfinite;
      first = std::min(first, i);
    }
    else if (v <= -1.0f)
    {
      ++nonpositive;
      first = std::min(first, i);
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
          const int ijk[3] = { i, j, k };
          const std::size_t idx = i * sx + j * sy + k * sz;
          double g[3];
          for (int a = 0; a < 3; ++a)
          {
            const std::size_t s = strides[a];
            if (ijk[a] == 0)
              g[a] = (double(n1[idx + s]) - n1[idx]) / spacing[a];
            else if (ijk[a] == dims[a] - 1)
              g[a] = (double(n1[idx]) - n1[idx - s]) / spacing[a];
            else
              g[a] = (double(n1[idx + s]) - n1[idx - s]) / (2.0 * spacing[a]);
          }
          store(idx, g);
        }
  };
  const int nt = std::max(1u, std::min(8u, std::thread::hardware_concurrency()));
  std::vector<std::thread> threads;
  for (int t = 0; t < nt; ++t)
  {
    const int k0 = dims[2] * t / nt, k1 = dims[2] * (t + 1) / nt;
    threads.emplace_back(worker, k0, k1);
  }
  for (auto& th : threads)
    th.join();
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
  GradientLoop(dims, spacing, n1, [out, n1](std::size_t idx, const double g[3]) {
    out[4 * idx] = n1[idx];
    out[4 * idx + 1] = static_cast<float>(g[0]);
    out[4 * idx + 2] = static_cast<float>(g[1]);
    out[4 * idx + 3] = static_cast<float>(g[2]);
  });
}

// Runs body(k0, k1) over z ranges on up to 8 threads (the packing loops).
template <typename Body>
static void ParallelSlices(int nz, Body body)
{
  const int nt = std::max(1, std::min(std::min(8, nz), static_cast<int>(std::thread::hardware_concurrency())));
  std::vector<std::thread> threads;
  for (int t = 1; t < nt; ++t)
    threads.emplace_back(body, nz * t / nt, nz * (t + 1) / nt);
  body(0, nz / nt);
  for (auto& th : threads)
    th.join();
}

double PackFieldHighOrder(const int dims[3], const double spacing[3], const float* n1, float* out,
  unsigned char* smooth, double threshold)
{
  CheckGrid(dims, spacing);
  if (!(threshold > 0) || !std::isfinite(threshold))
    throw Error("PackFieldHighOrder: the smoothness threshold must be positive and finite.");
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::string bad = ValidateIndex(n1, n);
  if (!bad.empty())
    throw Error(bad);
  const std::size_t strides[3] = { 1, static_cast<std::size_t>(dims[0]),
    static_cast<std::size_t>(dims[0]) * dims[1] };
  // structure below this part of the field's range is left to the smooth scheme: its overshoot
  // there is far below what the tracer resolves (steps are flagged for 1 % of the range)
  const auto mm = std::minmax_element(n1, n1 + n);
  const double floor = 1e-4 * (double(*mm.second) - *mm.first) + 1e-30;
  // 1. the smooth points: two or more points from every border, and along every axis a fourth
  // difference small against the range of the five points (a jump or a kink makes it of the
  // order of the range; smooth data makes it O(h^2) smaller)
  // (near a border the five points are the five nearest inside: jumpFree, what the step length
  // needs; point adds the two points of margin that the fourth-order stencils need)
  std::vector<unsigned char> point(n, 0), jumpFree(n, 0);
  // the loops read the grid's sizes from locals (captured by value): byte and float stores could
  // alias captured references, which the compiler must then reload at every point
  const int G[3] = { dims[0], dims[1], dims[2] };
  const std::size_t St[3] = { strides[0], strides[1], strides[2] };
  const double H[3] = { spacing[0], spacing[1], spacing[2] };
  unsigned char* const PT = point.data();
  unsigned char* const JF = jumpFree.data();
  ParallelSlices(dims[2], [=](int k0, int k1) {
    const int dims[3] = { G[0], G[1], G[2] };
    const std::size_t strides[3] = { St[0], St[1], St[2] };
    for (int k = k0; k < k1; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
        {
          const int ijk[3] = { i, j, k };
          const std::size_t idx = i + j * strides[1] + k * strides[2];
          bool ok = true, inner = true;
          for (int a = 0; a < 3 && ok; ++a)
          {
            if (dims[a] < 5)
            {
              ok = false;
              break;
            }
            inner = inner && ijk[a] >= 2 && ijk[a] <= dims[a] - 3;
            const int c = std::min(std::max(ijk[a], 2), dims[a] - 3);
            const std::size_t s = strides[a];
            const std::size_t m = idx + (static_cast<std::ptrdiff_t>(c) - ijk[a]) * static_cast<std::ptrdiff_t>(s);
            const double f[5] = { n1[m - 2 * s], n1[m - s], n1[m], n1[m + s], n1[m + 2 * s] };
            const double lo = std::min({ f[0], f[1], f[2], f[3], f[4] });
            const double hi = std::max({ f[0], f[1], f[2], f[3], f[4] });
            const double d4 = f[0] - 4 * f[1] + 6 * f[2] - 4 * f[3] + f[4];
            ok = std::fabs(d4) <= threshold * (hi - lo + floor);
          }
          JF[idx] = ok ? 1 : 0;
          PT[idx] = ok && inner ? 1 : 0;
        }
  });
  // 2. n - 1 and the gradient: along each axis, fourth order where the five points of the
  // difference are all smooth (a point beside a jump may pass the test on its own), PackField's
  // second order elsewhere
  ParallelSlices(dims[2], [=](int k0, int k1) {
    const int dims[3] = { G[0], G[1], G[2] };
    const std::size_t strides[3] = { St[0], St[1], St[2] };
    const double spacing[3] = { H[0], H[1], H[2] };
    const unsigned char* const point = PT;
    for (int k = k0; k < k1; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
        {
          const int ijk[3] = { i, j, k };
          const std::size_t idx = i + j * strides[1] + k * strides[2];
          out[4 * idx] = n1[idx];
          for (int a = 0; a < 3; ++a)
          {
            const std::size_t s = strides[a];
            double g;
            if (point[idx] && point[idx - s] && point[idx + s] && point[idx - 2 * s] && point[idx + 2 * s])
              g = (double(n1[idx - 2 * s]) - 8.0 * n1[idx - s] + 8.0 * n1[idx + s] - n1[idx + 2 * s]) /
                (12.0 * spacing[a]);
            else if (ijk[a] == 0)
              g = (double(n1[idx + s]) - n1[idx]) / spacing[a];
            else if (ijk[a] == dims[a] - 1)
              g = (double(n1[idx]) - n1[idx - s]) / spacing[a];
            else
              g = (double(n1[idx + s]) - n1[idx - s]) / (2.0 * spacing[a]);
            out[4 * idx + 1 + a] = static_cast<float>(g);
          }
        }
  });
  // 3. the smooth cells, and 4. their levels, by minima along one axis at a time: dst(i) = the
  // least src(i + d) over the offsets d; beyond the grid, 0 (cells) or the border's value (levels)
  auto minPass = [&](const std::vector<unsigned char>& src, std::vector<unsigned char>& dst, int a,
                   std::initializer_list<int> offsets, bool clamp) {
    // everything the loops read in locals: byte stores may alias any captured value, which kept
    // the compiler from vectorising (and reloaded the bounds every iteration)
    int off[4] = { 0, 0, 0, 0 }, no = 0, dlo = 0, dhi = 0;
    for (int d : offsets)
    {
      off[no++] = d;
      dlo = std::min(dlo, d);
      dhi = std::max(dhi, d);
    }
    const int nx = dims[0], ny = dims[1], na = dims[a];
    const std::size_t sy = strides[1], sz = strides[2];
    const unsigned char* const S = src.data();
    unsigned char* const D = dst.data();
    ParallelSlices(dims[2], [=](int k0, int k1) {
      for (int k = k0; k < k1; ++k)
        for (int j = 0; j < ny; ++j)
        {
          unsigned char* __restrict out = D + j * sy + k * sz;
          if (a == 0)
          {
            const unsigned char* __restrict in = S + j * sy + k * sz;
            // inside the row no offset reaches past it: one sweep per offset (vectorised)
            const int i0 = std::max(0, -dlo), i1 = nx - std::max(0, dhi);
            if (i1 > i0)
            {
              std::fill(out + i0, out + i1, static_cast<unsigned char>(1));
              for (int o = 0; o < no; ++o)
              {
                const int d = off[o];
                for (int i = i0; i < i1; ++i)
                  out[i] = std::min(out[i], in[i + d]);
              }
            }
            for (int i = 0; i < nx; ++i)
            {
              if (i >= i0 && i < i1)
                continue;
              unsigned char m = 1;
              for (int o = 0; o < no; ++o)
              {
                int c = i + off[o];
                if (c < 0 || c > nx - 1)
                {
                  if (!clamp)
                  {
                    m = 0;
                    break;
                  }
                  c = c < 0 ? 0 : nx - 1;
                }
                m = std::min(m, in[c]);
              }
              out[i] = m;
            }
            continue;
          }
          std::fill(out, out + nx, static_cast<unsigned char>(1));
          for (int o = 0; o < no; ++o)
          {
            int c = (a == 1 ? j : k) + off[o];
            if (c < 0 || c > na - 1)
            {
              if (!clamp)
              {
                std::fill(out, out + nx, static_cast<unsigned char>(0));
                break;
              }
              c = c < 0 ? 0 : na - 1;
            }
            const unsigned char* __restrict in = S + (a == 1 ? c : j) * sy + (a == 2 ? c : k) * sz;
            for (int i = 0; i < nx; ++i)
              out[i] = std::min(out[i], in[i]);
          }
        }
    });
  };
  // cell c (points c .. c + 1) is smooth where the points c - 1 .. c + 2 are, along every axis
  std::vector<unsigned char> cell = point, next(n, 0);
  for (int a = 0; a < 3; ++a)
  {
    minPass(cell, next, a, { -1, 0, 1, 2 }, false);
    cell.swap(next);
  }
  std::vector<unsigned char>().swap(point);
  // level q (1 .. 7) of a cell: every cell within 2^q cells (Chebyshev distance) is free of jumps
  // (its points c - 1 .. c + 2 inside the grid are jumpFree; beyond the grid no step goes). A
  // cube erosion of radius 1 (offsets -1, 0, 1), then radius r -> 2 r by offsets -r, r.
  std::vector<unsigned char> ero = jumpFree;
  for (int a = 0; a < 3; ++a)
  {
    minPass(ero, next, a, { -1, 0, 1, 2 }, true);
    ero.swap(next);
  }
  std::vector<unsigned char>().swap(jumpFree);
  std::vector<unsigned char> level(n, 0);
  for (int a = 0; a < 3; ++a)
  {
    minPass(ero, next, a, { -1, 0, 1 }, true);
    ero.swap(next);
  }
  for (int q = 1, r = 1; q <= 7; ++q, r *= 2)
  {
    for (int a = 0; a < 3; ++a)
    {
      minPass(ero, next, a, { -r, r }, true);
      ero.swap(next);
    }
    std::atomic<bool> any(false);
    ParallelSlices(dims[2], [&, q](int k0, int k1) {
      bool found = false;
      for (std::size_t i = k0 * strides[2]; i < k1 * strides[2]; ++i)
        if (ero[i])
        {
          level[i] = static_cast<unsigned char>(q);
          found = true;
        }
      if (found)
        any = true;
    });
    if (!any)
      break;
  }
  std::size_t count = 0, total = 0;
  for (int k = 0; k + 1 < dims[2]; ++k)
    for (int j = 0; j + 1 < dims[1]; ++j)
      for (int i = 0; i + 1 < dims[0]; ++i, ++total)
        count += cell[i + j * strides[1] + k * strides[2]];
  for (std::size_t i = 0; i < n; ++i)
    smooth[i] = static_cast<unsigned char>((cell[i] ? SCH_SMOOTH_CELL : 0) | (level[i] << SCH_SMOOTH_SHIFT));
  return total ? double(count) / total : 0.0;
}

// ------------------------------------------------------------------ octree

double ComputeOctreeLevels(const int dims[3], const float* n1, double tol, unsigned char* levels,
  int maxLevel)
{
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 2)
      throw Error("ComputeOctreeLevels: every dimension needs at least 2 points.");
  if (!(tol >= 0) || !std::isfinite(tol))
    throw Error("The octree tolerance must be a finite value >= 0.");
  maxLevel = std::max(0, std::min(maxLevel, 10));
  const std::size_t N = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::memset(levels, 0, N);
  const int cells[3] = { dims[0] - 1, dims[1] - 1, dims[2] - 1 };
  std::vector<float> lo, hi, lo2, hi2;
  for (int L = 1; L <= maxLevel; ++L)
  {
    const int B = 1 << L;
    int nb[3];
    for (int a = 0; a < 3; ++a)
      nb[a] = (cells[a] + B - 1) / B;
    // separable min/max of the points that the block's cells touch, grown by one: block b along an
    // axis covers points [b B - 1, b B + B + 1], clamped to the grid
    auto window = [&](int a, int b, int& p0, int& p1) {
      p0 = std::max(0, b * B - 1);
      p1 = std::min(dims[a] - 1, b * B + B + 1);
    };
    // x
    lo.assign(static_cast<std::size_t>(nb[0]) * dims[1] * dims[2], 0.f);
    hi.assign(lo.size(), 0.f);
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int b = 0; b < nb[0]; ++b)
        {
          int p0, p1;
          window(0, b, p0, p1);
          const float* row = n1 + (static_cast<std::size_t>(k) * dims[1] + j) * dims[0];
          float mn = row[p0], mx = row[p0];
          for (int i = p0 + 1; i <= p1; ++i)
          {
            mn = std::min(mn, row[i]);
            mx = std::max(mx, row[i]);
          }
          const std::size_t o = (static_cast<std::size_t>(k) * dims[1] + j) * nb[0] + b;
          lo[o] = mn;
          hi[o] = mx;
        }
    // y
    lo2.assign(static_cast<std::size_t>(nb[0]) * nb[1] * dims[2], 0.f);
    hi2.assign(lo2.size(), 0.f);
    for (int k = 0; k < dims[2]; ++k)
      for (int b = 0; b < nb[1]; ++b)
      {
        int p0, p1;
        window(1, b, p0, p1);
        for (int bx = 0; bx < nb[0]; ++bx)
        {
          float mn = 1e30f, mx = -1e30f;
          for (int j = p0; j <= p1; ++j)
          {
            const std::size_t o = (static_cast<std::size_t>(k) * dims[1] + j) * nb[0] + bx;
            mn = std::min(mn, lo[o]);
            mx = std::max(mx, hi[o]);
          }
          const std::size_t o2 = (static_cast<std::size_t>(k) * nb[1] + b) * nb[0] + bx;
          lo2[o2] = mn;
          hi2[o2] = mx;
        }
      }
    // z, and the level of every cell of blocks that pass
    bool any = false;
    for (int bz = 0; bz < nb[2]; ++bz)
    {
      int p0, p1;
      window(2, bz, p0, p1);
      for (int by = 0; by < nb[1]; ++by)
        for (int bx = 0; bx < nb[0]; ++bx)
        {
          float mn = 1e30f, mx = -1e30f;
          for (int k = p0; k <= p1; ++k)
          {
            const std::size_t o = (static_cast<std::size_t>(k) * nb[1] + by) * nb[0] + bx;
            mn = std::min(mn, lo2[o]);
            mx = std::max(mx, hi2[o]);
          }
          if (double(mx) - double(mn) > tol)
            continue;
          any = true;
          for (int k = bz * B; k < std::min(cells[2], bz * B + B); ++k)
            for (int j = by * B; j < std::min(cells[1], by * B + B); ++j)
            {
              unsigned char* row = levels + (static_cast<std::size_t>(k) * dims[1] + j) * dims[0];
              for (int i = bx * B; i < std::min(cells[0], bx * B + B); ++i)
                row[i] = static_cast<unsigned char>(L);
            }
        }
    }
    if (!any)
      break;
  }
  std::size_t skip = 0, total = 0;
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i, ++total)
        skip += levels[(static_cast<std::size_t>(k) * dims[1] + j) * dims[0] + i] > 0;
  return total ? double(skip) / total : 0.0;
}

// ------------------------------------------------------------------ names

Backend ParseBackend(const std::string& name)
{
  if (name == "Auto" || name == "auto")
    return Backend::Auto;
  if (name == "OpenCL" || name == "opencl")
    return Backend::OpenCL;
  if (name == "CPU" || name == "cpu")
    return Backend::CPU;
  throw Error("Unknown backend '" + name + "': use Auto, OpenCL or CPU.");
}

const char* BackendName(Backend b)
{
  switch (b)
  {
    case Backend::Auto:
      return "Auto";
    case Backend::OpenCL:
      return "OpenCL";
    case Backend::CPU:
      return "CPU";
  }
  return "?";
}

// ------------------------------------------------------------------ film

static void Normalize(double v[3])
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int a = 0; a < 3; ++a)
    v[a] /= n;
}

static void Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void FilmGeometry::GetImageOrigin(double origin[2]) const
{
  origin[0] = Dot(Center, Right) + Corner[0] + 0.5 * PixelSize;
  origin[1] = Dot(Center, Up) + Corner[1] + 0.5 * PixelSize;
}

// Half the extent of the box of grid points along each axis, from the grid itself: the bounds
// (origin + extent) lose the extent's digits when the volume sits far from the world origin.
static void HalfExtent(const Volume& v, double h[3])
{
  for (int a = 0; a < 3; ++a)
    h[a] = 0.5 * (v.Dimensions[a] - 1) * v.Spacing[a];
}

FilmGeometry MakeFilm(const Volume& volume, const TraceSettings& s)
{
  CheckGrid(volume.Dimensions, volume.Spacing);
  CheckSettings(s);
  FilmGeometry f;
  const double dlen = std::sqrt(Dot(s.ViewDirection, s.ViewDirection));
  if (!(dlen > 0) || !std::isfinite(dlen))
    throw Error("ViewDirection must be a non-zero, finite vector.");
  for (int a = 0; a < 3; ++a)
    f.Direction[a] = s.ViewDirection[a] / dlen;
  double up[3] = { s.ViewUp[0], s.ViewUp[1], s.ViewUp[2] };
  const double along = Dot(up, f.Direction);
  for (int a = 0; a < 3; ++a)
    up[a] -= along * f.Direction[a];
  const double ulen = std::sqrt(Dot(up, up));
  if (!(ulen > 1e-6 * std::sqrt(Dot(s.ViewUp, s.ViewUp))) || !std::isfinite(ulen))
    throw Error("ViewUp is zero or parallel to ViewDirection: choose an up vector across the beam.");
  Normalize(up);
  Cross(f.Direction, up, f.Right);
  Normalize(f.Right);
  Cross(f.Right, f.Direction, f.Up);
  Normalize(f.Up);

  if (s.Resolution[0] < 1 || s.Resolution[1] < 1 || s.Resolution[0] > 16384 ||
    s.Resolution[1] > 16384)
  {
    std::ostringstream msg;
    msg << "Resolution " << s.Resolution[0] << " x " << s.Resolution[1]
        << " is out of range: each side must be 1 to 16384 pixels.";
    throw Error(msg.str());
  }
  double h[3];
  HalfExtent(volume, h);
  for (int a = 0; a < 3; ++a)
    f.Center[a] = volume.Origin[a] + h[a];
  double wa = 0, wb = 0, wd = 0;
  for (int a = 0; a < 3; ++a)
  {
    wa += h[a] * std::fabs(f.Right[a]);
    wb += h[a] * std::fabs(f.Up[a]);
    wd += h[a] * std::fabs(f.Direction[a]);
  }
  f.Size[0] = s.Resolution[0];
  f.Size[1] = s.Resolution[1];
  f.PixelSize = std::max(2 * wa / f.Size[0], 2 * wb / f.Size[1]);
  f.Corner[0] = -0.5 * f.Size[0] * f.PixelSize;
  f.Corner[1] = -0.5 * f.Size[1] * f.PixelSize;
  f.FrontPlane = -wd * 1.001;
  if (!std::isfinite(s.FilmDistance))
    throw Error("FilmDistance must be finite.");
  // A shadowgraph's film is FilmDistance behind the back of the box. Every other cutoff images
  // the volume's centre plane, as a schlieren camera focused on the test section does (BOS: the
  // photons are then referred to the background, see Splatter); FilmDistance defocuses it.
  f.FilmPlane = s.Mode == Cutoff::Shadowgraph ? wd + s.FilmDistance : s.FilmDistance;
  return f;
}

static double MinSpacing(const Volume& v)
{
  return std::min(v.Spacing[0], std::min(v.Spacing[1], v.Spacing[2]));
}

static sch_params MakeParams(const Volume& volume, const TraceSettings& s, const FilmGeometry& f)
{
  if (!(s.StepSize > 0) || !std::isfinite(s.StepSize) || s.StepSize > 1e3)
  {
    std::ostringstream msg;
    msg << "StepSize " << s.StepSize << " voxels is out of range: use a value in (0, 1000].";
    throw Error(msg.str());
  }
  CheckPrecision(volume, s);
  sch_params P;
  std::memset(&P, 0, sizeof(P));
  P.nx = volume.Dimensions[0];
  P.ny = volume.Dimensions[1];
  P.nz = volume.Dimensions[2];
  // the tracer works relative to the volume's centre: only the extent enters, never the origin
  double h[3];
  HalfExtent(volume, h);
  P.isx = static_cast<float>(1.0 / volume.Spacing[0]);
  P.isy = static_cast<float>(1.0 / volume.Spacing[1]);
  P.isz = static_cast<float>(1.0 / volume.Spacing[2]);
  P.hx = static_cast<float>(h[0]);
  P.hy = static_cast<float>(h[1]);
  P.hz = static_cast<float>(h[2]);
  P.dx = static_cast<float>(f.Direction[0]);
  P.dy = static_cast<float>(f.Direction[1]);
  P.dz = static_cast<float>(f.Direction[2]);
  P.rx = static_cast<float>(f.Right[0]);
  P.ry = static_cast<float>(f.Right[1]);
  P.rz = static_cast<float>(f.Right[2]);
  P.tx = static_cast<float>(f.Up[0]);
  P.ty = static_cast<float>(f.Up[1]);
  P.tz = static_cast<float>(f.Up[2]);
  P.sFront = static_cast<float>(f.FrontPlane);
  P.sFilm = static_cast<float>(f.FilmPlane);
  P.filmA0 = static_cast<float>(f.Corner[0]);
  P.filmB0 = static_cast<float>(f.Corner[1]);
  P.pixel = static_cast<float>(f.PixelSize);
  P.filmNx = f.Size[0];
  P.filmNy = f.Size[1];
  const double step = s.StepSize * MinSpacing(volume);
  P.step = static_cast<float>(step);
  const double diag = 2 * std::sqrt(double(P.hx) * P.hx + double(P.hy) * P.hy + double(P.hz) * P.hz);
  // near a body steps are cut to a cell: the default limit allows for a whole path of them
  const double shortest = volume.Solid ? std::min(step, MinSpacing(volume)) : step;
  double maxSteps = s.MaxSteps > 0 ? s.MaxSteps : 8.0 * diag / shortest + 16;
  P.maxSteps = static_cast<int>(std::min(maxSteps, 1e9));
  P.seed = s.Seed;
  P.pass = 0;
  P.integrator = static_cast<int>(s.Method);
  P.jitter = s.Jitter ? 1 : 0;
  if (s.RankCount < 1 || s.RankIndex < 0 || s.RankIndex >= s.RankCount)
    throw Error("RankIndex must be in [0, RankCount).");
  P.rayOffset = s.RankIndex;
  P.rayStride = s.RankCount;
  P.useLevels = (s.UseOctree && volume.Levels) ? 1 : 0;
  P.useSolid = volume.Solid ? 1 : 0;
  P.keepInvariant = s.KeepInvariant ? 1 : 0;
  P.estimate = s.EstimateError ? 1 : 0;
  P.featureTol = 0.0f; // see SetFeatureTolerance
  // steps no longer than the smallest spacing cannot jump over a cell: no need to check them
  P.cellStep = static_cast<float>(MinSpacing(volume));
  P.gxMax = std::nextafter(static_cast<float>(P.nx - 1), 0.0f);
  P.gyMax = std::nextafter(static_cast<float>(P.ny - 1), 0.0f);
  P.gzMax = std::nextafter(static_cast<float>(P.nz - 1), 0.0f);
  // the grid coordinate of the centre, (origin - centre) / spacing, exactly
  P.gx0 = static_cast<float>(0.5 * (P.nx - 1));
  P.gy0 = static_cast<float>(0.5 * (P.ny - 1));
  P.gz0 = static_cast<float>(0.5 * (P.nz - 1));
  if (4.0 * P.nx * P.ny > 2147483647.0)
    throw Error("A slice of the volume has more than 2^29 points: not supported.");
  P.rowFloats = 4 * P.nx;
  P.sliceFloats = 4 * P.nx * P.ny;
  if (s.Recon == Reconstruction::Auto)
    throw Error("Reconstruction Auto must be resolved first (ResolveAuto).");
  if (s.Recon == Reconstruction::Cubic && !volume.Smooth)
    throw Error("Reconstruction Cubic needs the volume's smoothness (Volume::Smooth): pack the field "
                "with PackFieldHighOrder, or use Reconstruction Trilinear.");
  // with a body the levels byte carries its bits where Cubic keeps the smoothness: trilinear
  P.recon = s.Recon == Reconstruction::Cubic && !volume.Solid ? SCH_CUBIC : SCH_TRILINEAR;
  // from cells that are not smooth, steps of at most a cell: they cannot jump over a feature
  P.roughStep = P.recon == SCH_CUBIC ? P.cellStep : 0.0f;
  return P;
}

// A step that leaves more than 1 % of the field's index range unexplained by the gradient (or more
// than the octree tolerance) has jumped over structure. Reads the whole field: call it once the
// backend has accepted the volume.
// What identifies a stamped volume's contents (Volume::Stamp).
struct VolumeIdentity
{
  const float* Field = nullptr;
  const unsigned char* Levels = nullptr;
  const unsigned char* Solid = nullptr;
  int Dimensions[3] = { 0, 0, 0 };
  std::uint64_t Stamp = 0;

  explicit VolumeIdentity(const Volume& v)
    : Field(v.Field)
    , Levels(v.Levels)
    , Solid(v.Solid)
    , Stamp(v.Stamp)
  {
    std::copy(v.Dimensions, v.Dimensions + 3, Dimensions);
  }
  VolumeIdentity() = default;
  bool operator==(const VolumeIdentity& o) const
  {
    return Stamp != 0 && Stamp == o.Stamp && Field == o.Field && Levels == o.Levels &&
      Solid == o.Solid && std::equal(Dimensions, Dimensions + 3, o.Dimensions);
  }
};

static std::mutex KeptMutex;

static void SetFeatureTolerance(sch_params& P, const Volume& volume)
{
  // the index range of the last stamped volume (a pass over the whole field: ~40 ms at 256^3)
  static VolumeIdentity rangeOf;
  static float rangeLo = 0, rangeHi = 0;
  float lo = volume.Field[0], hi = volume.Field[0];
  bool known = false;
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    if (rangeOf == VolumeIdentity(volume))
    {
      lo = rangeLo;
      hi = rangeHi;
      known = true;
    }
  }
  const std::size_t n = volume.NumberOfPoints();
  for (std::size_t i = 0; !known && i < n; ++i)
  {
    lo = std::min(lo, volume.Field[4 * i]);
    hi = std::max(hi, volume.Field[4 * i]);
  }
  if (!known && volume.Stamp != 0)
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    rangeOf = VolumeIdentity(volume);
    rangeLo = lo;
    rangeHi = hi;
  }
  P.featureTol = static_cast<float>(std::max(volume.LevelTolerance, 0.01 * (double(hi) - lo)));
  if (!(P.featureTol > 0))
    P.featureTol = 1e-30f;
}

// The byte per grid point that the kernels read (SCH_OCTREE_BITS, SCH_NEAR_BIT, SCH_SOLID_BIT):
// with a body, the solid bit; the near bit where a solid point lies within `reach` (world units:
// the longest step) of the cell, so that steps there are cut to a cell; and the volume's levels
// lowered until no block (with its one-point halo) holds a solid point, so that no skip crosses a
// body.
static std::vector<unsigned char> MakeCellBytes(const Volume& v, double reach)
{
  const std::size_t N = v.NumberOfPoints();
  const int nx = v.Dimensions[0], ny = v.Dimensions[1], nz = v.Dimensions[2];
  std::vector<unsigned char> bytes(N, 0);
  bool anyLevel = false;
  for (std::size_t i = 0; i < N; ++i)
  {
    const unsigned char lvl = v.Levels ? static_cast<unsigned char>(v.Levels[i] & SCH_OCTREE_BITS) : 0;
    bytes[i] = static_cast<unsigned char>(lvl | (v.Solid[i] ? SCH_SOLID_BIT : 0));
    anyLevel = anyLevel || lvl > 0;
  }
  // solid points in any box of points by a summed-volume table
  const std::size_t sx = 1, sy = nx + 1, sz = static_cast<std::size_t>(nx + 1) * (ny + 1);
  std::vector<std::uint32_t> S(sz * (nz + 1), 0);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const std::size_t o = (k + 1) * sz + (j + 1) * sy + (i + 1) * sx;
        const std::uint32_t here = v.Solid[(static_cast<std::size_t>(k) * ny + j) * nx + i] ? 1u : 0u;
        S[o] = here + S[o - sx] + S[o - sy] + S[o - sz] - S[o - sx - sy] - S[o - sx - sz] -
          S[o - sy - sz] + S[o - sx - sy - sz];
      }
  auto solidIn = [&](const int lo[3], const int hi[3]) {
    // points lo..hi inclusive
    const std::size_t i0 = lo[0], i1 = hi[0] + 1, j0 = lo[1], j1 = hi[1] + 1, k0 = lo[2], k1 = hi[2] + 1;
    const std::int64_t c = std::int64_t(S[k1 * sz + j1 * sy + i1]) - S[k1 * sz + j1 * sy + i0] -
      S[k1 * sz + j0 * sy + i1] - S[k0 * sz + j1 * sy + i1] + S[k1 * sz + j0 * sy + i0] +
      S[k0 * sz + j1 * sy + i0] + S[k0 * sz + j0 * sy + i1] - S[k0 * sz + j0 * sy + i0];
    return c > 0;
  };
  // a step of length `reach` from inside cell c stays within the cells c - r .. c + r, and the
  // points nearest to it within c - r .. c + 1 + r, r = ceil(reach / spacing) along each axis
  int r[3];
  for (int a = 0; a < 3; ++a)
    r[a] = static_cast<int>(std::ceil(reach / v.Spacing[a])) + 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        unsigned char& b = bytes[(static_cast<std::size_t>(k) * ny + j) * nx + i];
        int L = b & SCH_OCTREE_BITS;
        const int c[3] = { i, j, k };
        int nlo[3], nhi[3];
        for (int a = 0; a < 3; ++a)
        {
          nlo[a] = std::max(0, c[a] - r[a]);
          nhi[a] = std::min(v.Dimensions[a] - 1, c[a] + 1 + r[a]);
        }
        const bool near = solidIn(nlo, nhi);
        while (L > 0)
        {
          // the points the block's cells touch, grown by one (as ComputeOctreeLevels)
          int lo[3], hi[3];
          for (int a = 0; a < 3; ++a)
          {
            const int b0 = (c[a] >> L) << L;
            lo[a] = std::max(0, b0 - 1);
            hi[a] = std::min(v.Dimensions[a] - 1, b0 + (1 << L) + 1);
          }
          if (!solidIn(lo, hi))
            break;
          --L;
        }
        b = static_cast<unsigned char>((b & SCH_SOLID_BIT) | (near ? SCH_NEAR_BIT : 0) | L);
      }
  return bytes;
}

// The cell bytes for a trace with steps of up to `reach` world units: the volume's levels (or
// null) without a body; with one, the bytes of MakeCellBytes, kept for the last stamped volume
// and reach.
static std::shared_ptr<const std::vector<unsigned char>> CellBytesOf(const Volume& v, double reach)
{
  if (!v.Solid)
    return nullptr;
  static VolumeIdentity bytesOf;
  static double reachOf = 0;
  static std::shared_ptr<const std::vector<unsigned char>> kept;
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    if (kept && bytesOf == VolumeIdentity(v) && reachOf == reach)
      return kept;
  }
  auto bytes = std::make_shared<const std::vector<unsigned char>>(MakeCellBytes(v, reach));
  if (v.Stamp != 0)
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    bytesOf = VolumeIdentity(v);
    reachOf = reach;
    kept = bytes;
  }
  return bytes;
}

// The longest step a trace with parameters P takes (the step-doubling estimate doubles it).
static double StepReach(const sch_params& P)
{
  return double(P.step) * (P.estimate ? 2.0 : 1.0);
}

// ------------------------------------------------------------------ film sums

std::vector<std::vector<double>*> FilmSums::PixelChannels()
{
  return { &Count, &Weight, &DeflectionX, &DeflectionY, &AbsDeflection, &Red, &Green, &Blue, &Phase,
    &ShiftX, &ShiftY, &ErrorSum, &Blocked };
}

std::vector<double*> FilmSums::Totals()
{
  return { &Photons, &Samples, &FailedRays, &MissedRays, &UnderresolvedRays, &SideRays, &Steps,
    &BlockedRays };
}

std::vector<double*> FilmSums::Maxima()
{
  return { &MaxAbsKnife, &MaxAbsDeflection, &MaxDrift, &MaxError };
}

void FilmSums::Resize(int nx, int ny)
{
  Size[0] = nx;
  Size[1] = ny;
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  for (std::vector<double>* c : PixelChannels())
    c->assign(n, 0.0);
  for (double* t : Totals())
    *t = 0.0;
  for (double* m : Maxima())
    *m = 0.0;
  Passes = 0;
}

void FilmSums::Merge(const FilmSums& o)
{
  if (o.Size[0] != Size[0] || o.Size[1] != Size[1])
    throw schlieren::Error("FilmSums::Merge: films of different sizes.");
  FilmSums& other = const_cast<FilmSums&>(o);
  const auto mine = PixelChannels(), theirs = other.PixelChannels();
  for (std::size_t c = 0; c < mine.size(); ++c)
    for (std::size_t i = 0; i < mine[c]->size(); ++i)
      (*mine[c])[i] += (*theirs[c])[i];
  const auto t0 = Totals(), t1 = other.Totals();
  for (std::size_t i = 0; i < t0.size(); ++i)
    *t0[i] += *t1[i];
  const auto m0 = Maxima(), m1 = other.Maxima();
  for (std::size_t i = 0; i < m0.size(); ++i)
    *m0[i] = std::max(*m0[i], *m1[i]);
}

void FilmSums::ToArrays(std::vector<double>& additive, std::vector<double>& maxima)
{
  additive.clear();
  for (std::vector<double>* c : PixelChannels())
    additive.insert(additive.end(), c->begin(), c->end());
  for (double* t : Totals())
    additive.push_back(*t);
  maxima.clear();
  for (double* m : Maxima())
    maxima.push_back(*m);
}

void FilmSums::FromArrays(const std::vector<double>& additive, const std::vector<double>& maxima)
{
  std::size_t pos = 0;
  for (std::vector<double>* c : PixelChannels())
  {
    if (pos + c->size() > additive.size())
      throw schlieren::Error("FilmSums::FromArrays: the arrays do not match this film.");
    std::copy(additive.begin() + pos, additive.begin() + pos + c->size(), c->begin());
    pos += c->size();
  }
  for (double* t : Totals())
    *t = additive.at(pos++);
  std::size_t m = 0;
  for (double* x : Maxima())
    *x = maxima.at(m++);
}

namespace
{
// Puts photons on the film. Runs on the host, in ray order, for both backends: the image does not
// depend on the order threads finish in, and both backends share this code.
struct Splatter
{
  const sch_params& P;
  const TraceSettings& S;
  FilmSums& F;
  float ca, sa, k;
  bool manual;
  double twoPiOverLambda, tilt, bgPlane, period;

  Splatter(const sch_params& p, const TraceSettings& s, FilmSums& f)
    : P(p)
    , S(s)
    , F(f)
  {
    const double ang = s.KnifeAngle * 3.14159265358979323846 / 180.0;
    ca = static_cast<float>(std::cos(ang));
    sa = static_cast<float>(std::sin(ang));
    k = static_cast<float>(s.CutoffScale);
    manual = s.CutoffScale > 0;
    twoPiOverLambda = 2 * 3.14159265358979323846 / (s.Wavelength * 1e-9);
    tilt = 2 * 3.14159265358979323846 * s.ReferenceTilt;
    bgPlane = P.sFront - s.BackgroundDistance;
    period = s.BackgroundPeriod > 0 ? s.BackgroundPeriod : 6.0 * P.pixel;
  }

  // the photon's weight under the cutoff, with energy weighting or (optionally) photon killing
  float CutoffWeight(float ex, float ey, float landA, double phase, sch_uint pix) const
  {
    float w = 1.0f;
    switch (S.Mode)
    {
      case Cutoff::KnifeEdge:
        w = sch_knife_weight(ex, ey, ca, sa, k);
        break;
      case Cutoff::Circular:
        w = sch_circular_weight(ex, ey, k, 0);
        break;
      case Cutoff::ComplementCircular:
        w = sch_circular_weight(ex, ey, k, 1);
        break;
      case Cutoff::Interferometry:
        w = sch_fringe_weight(static_cast<float>(phase), static_cast<float>(tilt * landA));
        break;
      default:
        w = 1.0f;
    }
    if (S.RussianRoulette)
    {
      // the photon survives with probability w and then carries all its energy: same mean
      const sch_uint h = sch_hash(P.seed * 747796405u ^ sch_hash(pix * 2891336453u + static_cast<sch_uint>(P.pass)));
      w = sch_unit(h) < w ? 1.0f : 0.0f;
    }
    return w;
  }

  void Add(const float* rec, std::size_t first, std::size_t count)
  {
    for (std::size_t r = 0; r < count; ++r, rec += SCH_RECORD)
    {
      const unsigned flags = static_cast<unsigned>(rec[SCH_REC_FLAGS]);
      F.Photons += 1;
      F.Samples += rec[SCH_REC_SAMPLES];
      F.Steps += rec[SCH_REC_STEPS];
      if (flags & SCH_RAY_MISSED)
        F.MissedRays += 1;
      if (flags & SCH_RAY_UNDERRESOLVED)
        F.UnderresolvedRays += 1;
      if (flags & SCH_RAY_SIDE)
        F.SideRays += 1;
      if (flags & SCH_RAY_BLOCKED)
      {
        // stopped by a body: no light; counted in the pixel it was emitted through (the shadow)
        F.BlockedRays += 1;
        F.Blocked[static_cast<std::size_t>(P.rayOffset + (first + r) * P.rayStride)] += 1;
        continue;
      }
      if (flags & SCH_RAY_LOST)
      {
        F.FailedRays += 1;
        continue;
      }
      F.MaxDrift = std::max(F.MaxDrift, double(std::fabs(rec[SCH_REC_DRIFT])));
      F.MaxError = std::max(F.MaxError, double(rec[SCH_REC_ERROR]));
      const float ex = rec[SCH_REC_EX], ey = rec[SCH_REC_EY];
      const double absE = std::hypot(double(ex), double(ey));
      F.MaxAbsKnife = std::max(F.MaxAbsKnife, double(std::fabs(ex * ca + ey * sa)));
      F.MaxAbsDeflection = std::max(F.MaxAbsDeflection, absE);
      const int pix = static_cast<int>(P.rayOffset + (first + r) * P.rayStride);
      double la = rec[SCH_REC_A], lb = rec[SCH_REC_B];
      double bosWeight = 0, shiftX = 0, shiftY = 0;
      if (S.Mode == Cutoff::BOS)
      {
        // the camera sees the background point the photon left from, where the exit ray seems
        // to come from: back along the exit direction to the background plane
        float a0, b0;
        sch_emit(&P, pix, &a0, &b0);
        bosWeight = sch_bos_pattern(a0, b0, static_cast<float>(period), S.BackgroundPattern, P.seed);
        la -= (P.sFilm - bgPlane) * ex;
        lb -= (P.sFilm - bgPlane) * ey;
        shiftX = la - a0;
        shiftY = lb - b0;
      }
      const double fi = std::floor((la - P.filmA0) / P.pixel);
      const double fj = std::floor((lb - P.filmB0) / P.pixel);
      if (fi < 0 || fj < 0 || fi >= P.filmNx || fj >= P.filmNy)
        continue; // landed off the film
      const std::size_t idx = static_cast<std::size_t>(fj) * P.filmNx + static_cast<std::size_t>(fi);
      const double phase = twoPiOverLambda * rec[SCH_REC_OPL];
      F.Count[idx] += 1;
      F.DeflectionX[idx] += ex;
      F.DeflectionY[idx] += ey;
      F.AbsDeflection[idx] += absE;
      F.ErrorSum[idx] += rec[SCH_REC_ERROR];
      F.Phase[idx] += phase;
      if (S.Mode == Cutoff::ColorFilter)
      {
        float cr, cg, cb;
        sch_hue_rgb(ex, ey, &cr, &cg, &cb);
        // value k|e| (manual k, clamped) or |e| (automatic: k applied in Finalize)
        const double v = manual ? std::min(1.0, k * absE) : absE;
        F.Red[idx] += v * cr;
        F.Green[idx] += v * cg;
        F.Blue[idx] += v * cb;
      }
      else if (S.Mode == Cutoff::BOS)
      {
        F.Weight[idx] += bosWeight;
        F.ShiftX[idx] += shiftX;
        F.ShiftY[idx] += shiftY;
      }
      else if (manual || S.Mode == Cutoff::Interferometry || S.RussianRoulette)
        F.Weight[idx] += CutoffWeight(ex, ey, static_cast<float>(la), phase, static_cast<sch_uint>(pix));
    }
  }
};

std::size_t RaysForRank(const sch_params& P)
{
  const std::size_t pixels = static_cast<std::size_t>(P.filmNx) * P.filmNy;
  if (pixels <= static_cast<std::size_t>(P.rayOffset))
    return 0;
  return (pixels - P.rayOffset + P.rayStride - 1) / P.rayStride;
}

// Threads of the CPU backend: SCHLIEREN_CPU_THREADS when set (for instance 1 per MPI rank, or to
// measure scaling), else every hardware thread.
unsigned CpuThreads()
{
  if (const char* env = std::getenv("SCHLIEREN_CPU_THREADS"))
  {
    const int n = std::atoi(env);
    if (n > 0)
      return static_cast<unsigned>(n);
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

// The CPU backend: the C++ build of SchlierenPhysics.h on std::thread.
void TraceChunkCPU(const float* field, const unsigned char* levels, const sch_params& P,
  std::size_t first, std::size_t count, float* out)
{
  const unsigned nt = CpuThreads();
  std::atomic<std::size_t> next(0);
  // blocks of 256 rays, smaller where a chunk has fewer rays than that for each thread
  const std::size_t block = std::max<std::size_t>(1, std::min<std::size_t>(256, (count + nt - 1) / nt));
  auto worker = [&]() {
    // each thread reads its own copy of the parameters: the caller's sits on the main thread's
    // stack, next to what that thread writes every step, and the other thread's reads of it
    // missed the cache on every step (false sharing: 2 threads ran no faster than 1)
    const sch_params Pw = P;
    for (;;)
    {
      const std::size_t b0 = next.fetch_add(block);
      if (b0 >= count)
        break;
      const std::size_t b1 = std::min(count, b0 + block);
      for (std::size_t k = b0; k < b1; k += SCH_PACKET)
      {
        const int pix = static_cast<int>(Pw.rayOffset + (first + k) * Pw.rayStride);
        const int n = static_cast<int>(std::min<std::size_t>(SCH_PACKET, b1 - k));
        sch_trace_packet(field, levels, &Pw, pix, Pw.rayStride, n, out + k * SCH_RECORD);
      }
    }
  };
  std::vector<std::thread> threads;
  for (unsigned t = 0; t + 1 < nt; ++t)
    threads.emplace_back(worker);
  worker();
  for (auto& th : threads)
    th.join();
}

// The OpenCL backend: holds the device buffers for one Accumulate call.
class OpenCLTracer
{
public:
  // bytes: the cell bytes (octree levels, solid points) or null
  OpenCLTracer(const Volume& volume, const unsigned char* cellBytes, std::size_t chunk, int raysPerItem)
    : RT(ocl::GetRuntime())
    , RaysPerItem(raysPerItem > 0 ? raysPerItem : (RT.IsCPU ? 4 : 1))
  {
    // over one buffer's limit, the field goes in slabs along z, up to MaxSlabs buffers: slab q
    // holds planes q K .. q K + K (K cells; the shared plane keeps every cell in one slab)
    const std::uint64_t maxAlloc = MaxAllocation();
    const std::uint64_t planeFloats = std::uint64_t(volume.Dimensions[0]) * volume.Dimensions[1] * 4;
    const std::uint64_t bytes = volume.NumberOfPoints() * 4 * sizeof(float);
    const int nz = volume.Dimensions[2];
    SlabCells = nz - 1;
    Slabs = 1;
    std::uint64_t total = bytes;
    if (bytes > maxAlloc)
    {
      const std::int64_t cells = std::int64_t(maxAlloc / (planeFloats * sizeof(float))) - 1;
      Slabs = cells >= 1 ? static_cast<int>((nz - 1 + cells - 1) / cells) : MaxSlabs + 1;
      SlabCells = static_cast<int>(std::max<std::int64_t>(cells, 1));
      total = bytes + std::uint64_t(Slabs - 1) * planeFloats * sizeof(float);
    }
    const std::uint64_t levelBytes = cellBytes ? volume.NumberOfPoints() : 1;
    if (Slabs > MaxSlabs || total + levelBytes > RT.GlobalMemory)
    {
      std::ostringstream msg;
      msg << "The volume needs " << total / (1 << 20) << " MiB on the OpenCL device '"
          << RT.DeviceName << "', which allows " << maxAlloc / (1 << 20) << " MiB per buffer (split "
          << "in at most " << MaxSlabs << " buffers) and " << RT.GlobalMemory / (1 << 20)
          << " MiB in all. Resample the data to fewer points, or choose Backend CPU.";
      throw Error(msg.str());
    }
    // A CPU device's buffers live in host memory: there the buffer uses the caller's field where
    // its address has the device's alignment (no second copy of the volume), else the driver
    // keeps a copy, which must fit in what the machine has left.
    cl_uint alignBits = 0;
    clGetDeviceInfo(RT.Device, CL_DEVICE_MEM_BASE_ADDR_ALIGN, sizeof(alignBits), &alignBits, nullptr);
    const std::uintptr_t align = std::max<std::uintptr_t>(alignBits / 8, 64);
    const char* useHost = std::getenv("SCHLIEREN_CL_USE_HOST_PTR");
    const bool shareHost = RT.IsCPU && !(useHost && std::string(useHost) == "0");
    auto slabStart = [&](int q) {
      return volume.Field + std::uint64_t(q) * SlabCells * planeFloats;
    };
    double copied = 0;
    for (int q = 0; q < Slabs; ++q)
    {
      Shared[q] = shareHost && reinterpret_cast<std::uintptr_t>(slabStart(q)) % align == 0;
      if (!Shared[q] && RT.IsCPU)
        copied += double(total) / Slabs;
    }
    if (copied > 0)
      CheckHostMemory(copied + levelBytes,
        "The OpenCL device '" + RT.DeviceName + "' keeps its copy of the volume in host memory; it",
        "Choose Backend CPU (which traces the field in place), or resample the data to fewer points.");
    try
    {
      cl_int err = CL_SUCCESS;
      for (int q = 0; q < Slabs; ++q)
      {
        const std::uint64_t first = std::uint64_t(q) * SlabCells;
        const std::uint64_t planes = std::min<std::uint64_t>(SlabCells, nz - 1 - first) + 1;
        const cl_mem_flags flags = CL_MEM_READ_ONLY | (Shared[q] ? CL_MEM_USE_HOST_PTR : CL_MEM_COPY_HOST_PTR);
        Fields[q] = clCreateBuffer(RT.Context, flags, planes * planeFloats * sizeof(float),
          const_cast<float*>(slabStart(q)), &err);
        ocl::Check(err, "clCreateBuffer(field)");
      }
      // the cell bytes (octree levels, solid points), or one byte that no kernel reads when
      // there are none
      static unsigned char none = 0;
      Levels = clCreateBuffer(RT.Context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
        cellBytes ? volume.NumberOfPoints() : 1, const_cast<unsigned char*>(cellBytes ? cellBytes : &none), &err);
      ocl::Check(err, "clCreateBuffer(levels)");
      EnsureOut(chunk);
    }
    catch (...)
    {
      // a failed allocation leaves nothing behind on the device (no destructor runs here)
      Release();
      throw;
    }
  }
  // the records buffer holds at least `chunk` rays
  void EnsureOut(std::size_t chunk)
  {
    if (Out && chunk <= Chunk)
      return;
    if (Out)
      clReleaseMemObject(Out);
    Out = nullptr;
    cl_int err = CL_SUCCESS;
    Chunk = std::max<std::size_t>(1, chunk);
    Out = clCreateBuffer(RT.Context, CL_MEM_WRITE_ONLY, Chunk * SCH_RECORD * sizeof(float), nullptr, &err);
    ocl::Check(err, "clCreateBuffer(records)");
  }
  ~OpenCLTracer() { Release(); }
  void Release()
  {
    if (Out)
      clReleaseMemObject(Out);
    for (cl_mem& f : Fields)
      if (f)
        clReleaseMemObject(f);
    if (Levels)
      clReleaseMemObject(Levels);
    for (auto& k : Kernels)
      clReleaseKernel(k.second);
    Out = Levels = nullptr;
    for (cl_mem& f : Fields)
      f = nullptr;
    Kernels.clear();
  }
  OpenCLTracer(const OpenCLTracer&) = delete;
  OpenCLTracer& operator=(const OpenCLTracer&) = delete;

  // The kernels for P's integrator, octree use and invariant rescaling: built with them as
  // constants (-DSCH_FIXED_*), so that the step has no branches on them (+10-28 % on PoCL, Euler,
  // 192^3). Two programs per setting: the per-item one (sch_trace_rays, sch_trace_points) and the
  // lock-step one (sch_trace_lockstep, -DSCH_LOCKSTEP_GROUP: its walks in local memory). Each is
  // built on first use and kept; SCHLIEREN_CL_SPECIALISE=0 builds one generic program of each.
  enum class Entry
  {
    Rays,
    Points,
    Lockstep
  };
  cl_kernel KernelFor(const sch_params& P, Entry entry)
  {
    const char* spec = std::getenv("SCHLIEREN_CL_SPECIALISE");
    const bool specialise = !(spec && std::string(spec) == "0");
    const int setting = specialise
      ? 1 + P.integrator * 8 + (P.useSolid ? 4 : 0) + (P.useLevels ? 2 : 0) + (P.keepInvariant ? 1 : 0) +
        64 * P.recon
      : 0;
    const int key = setting * 3 + static_cast<int>(entry);
    auto it = Kernels.find(key);
    if (it != Kernels.end())
      return it->second;
    std::ostringstream opts;
    opts << "-cl-std=CL1.2";
    if (entry == Entry::Lockstep)
      opts << " -DSCH_LOCKSTEP_GROUP=" << LockstepGroup;
    else
      opts << " -DSCH_RAYS_PER_ITEM=" << RaysPerItem;
    if (Slabs > 1)
      opts << " -DSCH_SLABS=" << Slabs;
    if (specialise)
      opts << " -DSCH_FIXED_INTEGRATOR=" << P.integrator << " -DSCH_FIXED_LEVELS=" << (P.useLevels ? 1 : 0)
           << " -DSCH_FIXED_KEEP=" << (P.keepInvariant ? 1 : 0) << " -DSCH_FIXED_RECON=" << P.recon
           << " -DSCH_FIXED_SOLID=" << (P.useSolid ? 1 : 0);
    // extra OpenCL build options, for experiments (e.g. -cl-mad-enable)
    if (const char* extra = std::getenv("SCHLIEREN_CL_OPTIONS"))
      opts << " " << extra;
    cl_program prog = ocl::GetProgram("SchlierenTrace.cl", EmbeddedKernelSource(), opts.str());
    const char* name = entry == Entry::Rays ? "sch_trace_rays"
      : entry == Entry::Points              ? "sch_trace_points"
                                            : "sch_trace_lockstep";
    cl_int err = CL_SUCCESS;
    cl_kernel k = clCreateKernel(prog, name, &err);
    ocl::Check(err, (std::string("clCreateKernel(") + name + ")").c_str());
    return Kernels[key] = k;
  }
  // The kernel that Trace (points false) or TracePoints (true) runs for P.
  cl_kernel KernelFor(const sch_params& P, bool points)
  {
    return KernelFor(P, points ? Entry::Points : UseLockstep(P) ? Entry::Lockstep : Entry::Rays);
  }

  void Trace(const sch_params& P, std::size_t first, std::size_t count, float* out)
  {
    const bool lockstep = UseLockstep(P);
    cl_kernel Kernel = KernelFor(P, false);
    const int f = static_cast<int>(first), c = static_cast<int>(count);
    const sch_params Q = WithSlabs(P);
    SetFieldArgs(Kernel);
    ocl::Check(clSetKernelArg(Kernel, 5, sizeof(sch_params), &Q), "clSetKernelArg(params)");
    ocl::Check(clSetKernelArg(Kernel, 6, sizeof(int), &f), "clSetKernelArg(first)");
    ocl::Check(clSetKernelArg(Kernel, 7, sizeof(int), &c), "clSetKernelArg(count)");
    ocl::Check(clSetKernelArg(Kernel, 8, sizeof(cl_mem), &Out), "clSetKernelArg(out)");
    if (lockstep)
    {
      // a ray per work-item, groups of LockstepGroup (the global size rounded up to them)
      const std::size_t local = LockstepGroup;
      const std::size_t global = (count + local - 1) / local * local;
      ocl::Check(clEnqueueNDRangeKernel(RT.Queue, Kernel, 1, nullptr, &global, &local, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel(sch_trace_lockstep)");
    }
    else
    {
      const std::size_t global = (count + RaysPerItem - 1) / RaysPerItem;
      ocl::Check(clEnqueueNDRangeKernel(RT.Queue, Kernel, 1, nullptr, &global, nullptr, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel(sch_trace_rays)");
    }
    ocl::Check(clEnqueueReadBuffer(RT.Queue, Out, CL_TRUE, 0, count * SCH_RECORD * sizeof(float), out,
                 0, nullptr, nullptr),
      "clEnqueueReadBuffer(records)");
  }

  void TracePoints(const sch_params& P, const float* ab, std::size_t count, float* out)
  {
    cl_kernel PointsKernel = KernelFor(P, true);
    cl_int err = CL_SUCCESS;
    cl_mem abBuf = clCreateBuffer(RT.Context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
      std::max<std::size_t>(1, count) * 2 * sizeof(float), const_cast<float*>(ab), &err);
    ocl::Check(err, "clCreateBuffer(points)");
    const int c = static_cast<int>(count);
    const sch_params Q = WithSlabs(P);
    SetFieldArgs(PointsKernel);
    clSetKernelArg(PointsKernel, 5, sizeof(sch_params), &Q);
    clSetKernelArg(PointsKernel, 6, sizeof(cl_mem), &abBuf);
    clSetKernelArg(PointsKernel, 7, sizeof(int), &c);
    clSetKernelArg(PointsKernel, 8, sizeof(cl_mem), &Out);
    const std::size_t global = count;
    cl_int st = clEnqueueNDRangeKernel(RT.Queue, PointsKernel, 1, nullptr, &global, nullptr, 0, nullptr, nullptr);
    if (st == CL_SUCCESS)
      st = clEnqueueReadBuffer(RT.Queue, Out, CL_TRUE, 0, count * SCH_RECORD * sizeof(float), out, 0,
        nullptr, nullptr);
    clReleaseMemObject(abBuf);
    ocl::Check(st, "sch_trace_points");
  }

  // Arguments 0-4 of every kernel: the field's buffers (the first bound again where there are
  // fewer than four slabs; those are not read) and the octree levels.
  void SetFieldArgs(cl_kernel k)
  {
    for (int q = 0; q < MaxSlabs; ++q)
      ocl::Check(clSetKernelArg(k, q, sizeof(cl_mem), &Fields[q < Slabs ? q : 0]), "clSetKernelArg(field)");
    ocl::Check(clSetKernelArg(k, 4, sizeof(cl_mem), &Levels), "clSetKernelArg(levels)");
  }
  sch_params WithSlabs(const sch_params& P) const
  {
    sch_params Q = P;
    Q.slabCells = SlabCells;
    return Q;
  }
  // The device's largest buffer, or less where SCHLIEREN_CL_MAX_ALLOC (bytes) says so: the split
  // into slabs is tested on small volumes that way.
  std::uint64_t MaxAllocation() const
  {
    std::uint64_t m = RT.MaxAlloc;
    if (const char* e = std::getenv("SCHLIEREN_CL_MAX_ALLOC"))
      m = std::min<std::uint64_t>(m, std::strtoull(e, nullptr, 10));
    return m;
  }

  // Lock-step rays (sch_trace_lockstep) on CPU devices: PoCL then runs each step over the whole
  // group of rays, whose memory reads overlap (line of sight + octree too, since session 3:
  // 2.7-3.2 -> 4.3 M photons/s on the plume). Other devices take the per-item kernel, and so does
  // the step-doubling estimate (the lock-step program has no private walks to march the second
  // ray with). SCHLIEREN_CL_LOCKSTEP=0/1 overrides (for measurements).
  bool UseLockstep(const sch_params& P) const
  {
    if (P.estimate)
      return false;
    if (const char* e = std::getenv("SCHLIEREN_CL_LOCKSTEP"))
      return std::string(e) != "0";
    return RT.IsCPU;
  }
  static constexpr std::size_t LockstepGroup = 64;

  ocl::Runtime& RT;
  int RaysPerItem;
  std::size_t Chunk = 0;
  std::map<int, cl_kernel> Kernels;
  // the field: one buffer, or Slabs buffers of SlabCells cells along z (see the constructor)
  static constexpr int MaxSlabs = 4;
  cl_mem Fields[MaxSlabs] = { nullptr, nullptr, nullptr, nullptr };
  bool Shared[MaxSlabs] = { false, false, false, false }; // uses the caller's memory (CPU device)
  int Slabs = 1, SlabCells = 0;
  cl_mem Levels = nullptr, Out = nullptr;
};

// Chooses the backend; returns the OpenCL tracer or null for the CPU.
// The device copy of the last stamped volume, kept for the next call (an interactive view traces
// the same volume again and again, so the upload is paid once). Allocated once; its
// device objects are released by the runtime's exit hook (ocl::AtRelease), before the context.
struct KeptTracer
{
  VolumeIdentity Identity;
  int RaysPerItem = 0;
  // the cell bytes the device copy was made from, held so that no other allocation can take
  // their address while the copy is kept: with a body they change with the step's reach
  const unsigned char* Bytes = nullptr;
  std::shared_ptr<const void> BytesOwner;
  std::shared_ptr<OpenCLTracer> Tracer;
};
void ReleaseKeptAtExit();
KeptTracer& Kept()
{
  static KeptTracer* kept = [] {
    ocl::AtRelease(&ReleaseKeptAtExit);
    return new KeptTracer;
  }();
  return *kept;
}
void ReleaseKeptAtExit()
{
  std::lock_guard<std::mutex> lock(KeptMutex);
  Kept().Tracer.reset();
  Kept().Identity = VolumeIdentity();
}

std::shared_ptr<OpenCLTracer> AcquireTracer(const Volume& volume, const unsigned char* bytes,
  const std::shared_ptr<const void>& bytesOwner, std::size_t chunk, int raysPerItem)
{
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    KeptTracer& k = Kept();
    // in use by another call (use_count > 1): that call keeps it; this one makes its own
    if (k.Tracer && k.Identity == VolumeIdentity(volume) && k.RaysPerItem == raysPerItem &&
      k.Bytes == bytes && k.Tracer.use_count() == 1)
    {
      std::shared_ptr<OpenCLTracer> t = k.Tracer;
      t->EnsureOut(chunk);
      return t;
    }
    // one volume on the device at a time: the old copy goes before the new one is made
    k.Tracer.reset();
    k.Identity = VolumeIdentity();
    k.Bytes = nullptr;
    k.BytesOwner.reset();
  }
  auto t = std::make_shared<OpenCLTracer>(volume, bytes, chunk, raysPerItem);
  if (volume.Stamp != 0)
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    Kept().Identity = VolumeIdentity(volume);
    Kept().RaysPerItem = raysPerItem;
    Kept().Bytes = bytes;
    Kept().BytesOwner = bytesOwner;
    Kept().Tracer = t;
  }
  return t;
}

// The OpenCL tracer for this trace, or null for the CPU (asked for, or OpenCL unusable under Auto,
// with a warning). points: the caller traces explicit film points (TracePoints) rather than passes
// (Trace); the kernel it will run is built here, so that a build failure falls back too.
std::shared_ptr<OpenCLTracer> OpenBackend(const Volume& volume, const unsigned char* bytes,
  const std::shared_ptr<const void>& bytesOwner, const TraceSettings& s,
  const sch_params& P, std::size_t chunk, bool points, std::string& used, std::string& device,
  std::string& warnings)
{
  if (s.Device == Backend::CPU)
  {
    used = "CPU";
    device = "CPU (" + std::to_string(CpuThreads()) + " threads)";
    return nullptr;
  }
  try
  {
    auto t = AcquireTracer(volume, bytes, bytesOwner, chunk, s.RaysPerWorkItem);
    t->KernelFor(P, points); // built here, so that a build failure falls back like a missing device
    used = "OpenCL";
    device = t->RT.DeviceName;
    if (t->Slabs > 1)
      device += " (the field split in " + std::to_string(t->Slabs) + " buffers)";
    return t;
  }
  catch (const Error& e)
  {
    if (s.Device == Backend::OpenCL)
      throw;
    used = "CPU";
    device = "CPU (" + std::to_string(CpuThreads()) + " threads)";
    warnings += std::string("OpenCL is not usable, tracing on the CPU instead: ") + e.what() + "\n";
    return nullptr;
  }
}

// The volume as the kernels see it: with Volume::Smooth, its levels buffer holds the smoothness
// bits (Reconstruction Cubic) above the octree levels (SCH_OCTREE_BITS), for either
// reconstruction, so that switching between them (Auto's pilot) keeps the device copy. The merged
// bytes of a stamped volume are kept for its next trace; `own` holds those of this call.
Volume TraceVolume(const Volume& v, std::shared_ptr<std::vector<unsigned char>>& own)
{
  if (!v.Smooth)
    return v;
  Volume out = v;
  if (!v.Levels)
  {
    out.Levels = v.Smooth;
    return out;
  }
  struct Merged
  {
    const unsigned char* Levels = nullptr;
    const unsigned char* Smooth = nullptr;
    std::uint64_t Stamp = 0;
    std::size_t Points = 0;
    std::shared_ptr<std::vector<unsigned char>> Bytes;
  };
  static Merged kept;
  const std::size_t n = v.NumberOfPoints();
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    if (v.Stamp != 0 && kept.Stamp == v.Stamp && kept.Levels == v.Levels && kept.Smooth == v.Smooth &&
      kept.Points == n && kept.Bytes)
      own = kept.Bytes;
  }
  if (!own)
  {
    own = std::make_shared<std::vector<unsigned char>>(n);
    for (std::size_t i = 0; i < n; ++i)
      (*own)[i] = static_cast<unsigned char>((v.Levels[i] & SCH_OCTREE_BITS) | (v.Smooth[i] & ~SCH_OCTREE_BITS));
    if (v.Stamp != 0)
    {
      std::lock_guard<std::mutex> lock(KeptMutex);
      kept.Levels = v.Levels;
      kept.Smooth = v.Smooth;
      kept.Stamp = v.Stamp;
      kept.Points = n;
      kept.Bytes = own;
    }
  }
  out.Levels = own->data();
  return out;
}

void CheckVolume(const Volume& v)
{
  CheckGrid(v.Dimensions, v.Spacing);
  if (!v.Field)
    throw Error("The volume has no field data.");
}
} // namespace

void Accumulate(const Volume& volume, const TraceSettings& s, FilmSums& sums,
  std::string* backendUsed, std::string* deviceName, std::string* warnings,
  const ProgressFunction& progress)
{
  CheckVolume(volume);
  CheckSettings(s);
  if (s.Method == Integrator::Auto)
    throw Error("Accumulate: resolve Integrator Auto first (ResolveAuto).");
  if (s.RussianRoulette && !(s.CutoffScale > 0) &&
    (s.Mode == Cutoff::KnifeEdge || s.Mode == Cutoff::Circular || s.Mode == Cutoff::ComplementCircular))
    throw Error("Photon killing (RussianRoulette) needs a fixed CutoffScale: the automatic scale is "
                "known only after the trace.");
  const FilmGeometry film = MakeFilm(volume, s);
  sch_params P = MakeParams(volume, s, film);
  std::shared_ptr<std::vector<unsigned char>> levelBytes;
  const Volume tv = TraceVolume(volume, levelBytes);
  if (sums.Size[0] != film.Size[0] || sums.Size[1] != film.Size[1] || sums.Count.empty())
  {
    CheckFilmMemory(film.Size);
    sums.Resize(film.Size[0], film.Size[1]);
  }

  const std::size_t rays = RaysForRank(P);
  // chunks of about 8 M samples (~0.1-0.2 s on a CPU): progress and abort are checked between
  // chunks, so an abort stops the trace within one chunk; long rays make small chunks
  const double samplesPerRay = std::max(1.0, 2.0 * std::sqrt(double(P.hx) * P.hx + double(P.hy) * P.hy +
                                                 double(P.hz) * P.hz) / P.step *
      (s.Method == Integrator::RK4 ? 4 : (s.Method == Integrator::Midpoint ? 2 : 1)) *
      (s.EstimateError ? 1.5 : 1.0));
  std::size_t chunk = 64;
  while (chunk < (1u << 16) && (2 * chunk) * samplesPerRay <= 8e6)
    chunk *= 2;
  chunk = std::min<std::size_t>(std::max<std::size_t>(rays, 1), chunk);
  std::string used, device, warn;
  // with a body the kernels read its solid and near bits in the levels byte (no Cubic then)
  const auto solidBytes = CellBytesOf(volume, StepReach(P));
  const unsigned char* bytes = solidBytes ? solidBytes->data() : tv.Levels;
  std::shared_ptr<OpenCLTracer> cl =
    OpenBackend(tv, bytes, solidBytes, s, P, chunk, false, used, device, warn);
  SetFeatureTolerance(P, tv);
  if (volume.Solid && s.Recon == Reconstruction::Cubic && sums.Passes == 0)
    warn += "Reconstruction Cubic is not available with a solid body (the byte per point that "
            "carries the body holds the smoothness it needs): traced trilinear.\n";
  std::vector<float> records(chunk * SCH_RECORD);
  Splatter splat(P, s, sums);
  const double total = double(s.Passes) * std::max<std::size_t>(rays, 1);
  double done = 0;
  for (int pass = 0; pass < s.Passes; ++pass)
  {
    P.pass = sums.Passes + pass;
    for (std::size_t first = 0; first < rays; first += chunk)
    {
      const std::size_t count = std::min(chunk, rays - first);
      if (cl)
        cl->Trace(P, first, count, records.data());
      else
        TraceChunkCPU(tv.Field, bytes, P, first, count, records.data());
      splat.Add(records.data(), first, count);
      done += count;
      if (progress && !progress(done / total))
        throw Error("aborted");
    }
  }
  sums.Passes += s.Passes;
  if (backendUsed)
    *backendUsed = used;
  if (deviceName)
    *deviceName = device;
  if (warnings)
    *warnings += warn;
}

// What the user must be told when the photons did not make a picture: no ray entered the volume
// (a uniform image), or the photons that did landed off the film (a blank image). Uses the raw
// (unfiltered) sums: a landed photon is counted once there.
static std::string PhotonWarnings(const Volume& volume, const FilmGeometry& film, const FilmSums& raw)
{
  if (!(raw.Photons > 0))
    return std::string();
  double landed = 0;
  for (double c : raw.Count)
    landed += c;
  const double entered = raw.Photons - raw.MissedRays;
  const double kept = raw.Photons - raw.FailedRays;
  const double off = std::max(0.0, kept - landed);
  std::ostringstream msg;
  if (!(entered > 0))
  {
    double h[3];
    for (int a = 0; a < 3; ++a)
      h[a] = (volume.Dimensions[a] - 1) * volume.Spacing[a];
    msg << "No ray entered the volume (" << h[0] << " x " << h[1] << " x " << h[2]
        << " world units) of " << raw.Photons << " traced: the image is uniform and shows nothing "
        << "of the field. The film's pixels are " << film.PixelSize << " world units wide; a "
        << "volume thinner than that across the beam is missed by the rays through the pixel "
        << "centres. Raise Resolution, view the volume face-on, or resample it thicker.\n";
  }
  else if (!(landed > 0))
    msg << "No photon reached the film: all " << kept << " photons that left the volume landed "
        << "off the film (it is " << film.Size[0] * film.PixelSize << " world units wide and "
        << "images the plane " << film.FilmPlane << " from the volume's centre). The image is "
        << "blank: lower FilmDistance (or CutoffScale) so that the deflected light stays on the "
        << "film.\n";
  else if (off > 0.5 * kept)
    msg << off << " of " << kept << " photons landed off the film (the film images the plane "
        << film.FilmPlane << " from the volume's centre): the image shows only the rest. Lower "
        << "FilmDistance to keep more of the light on the film.\n";
  return msg.str();
}

// Film filters (paper section 6): every per-pixel sum is convolved with the same kernel, so that
// ratios (mean deflection, BOS pattern) stay consistent; the total stays the same.
static void FilterChannel(std::vector<double>& c, int nx, int ny, const std::vector<double>& kernel,
  int radius, bool separable)
{
  std::vector<double> tmp(c.size(), 0.0);
  if (separable)
  {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const double v = c[static_cast<std::size_t>(j) * nx + i];
        if (v == 0)
          continue;
        for (int d = -radius; d <= radius; ++d)
          if (i + d >= 0 && i + d < nx)
            tmp[static_cast<std::size_t>(j) * nx + i + d] += v * kernel[d + radius];
      }
    std::fill(c.begin(), c.end(), 0.0);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const double v = tmp[static_cast<std::size_t>(j) * nx + i];
        if (v == 0)
          continue;
        for (int d = -radius; d <= radius; ++d)
          if (j + d >= 0 && j + d < ny)
            c[static_cast<std::size_t>(j + d) * nx + i] += v * kernel[d + radius];
      }
    return;
  }
  const int w = 2 * radius + 1;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const double v = c[static_cast<std::size_t>(j) * nx + i];
      if (v == 0)
        continue;
      for (int dj = -radius; dj <= radius; ++dj)
        for (int di = -radius; di <= radius; ++di)
          if (i + di >= 0 && i + di < nx && j + dj >= 0 && j + dj < ny)
            tmp[static_cast<std::size_t>(j + dj) * nx + i + di] += v * kernel[(dj + radius) * w + di + radius];
    }
  c.swap(tmp);
}

static void FilterSums(FilmSums& f, const TraceSettings& s)
{
  if (s.Filter == FilmFilter::None)
    return;
  if (!(s.FilterWidth > 0) || s.FilterWidth > 64)
    throw Error("FilterWidth must be in (0, 64] pixels.");
  std::vector<double> kernel;
  int radius = 0;
  bool separable = false;
  if (s.Filter == FilmFilter::Gaussian)
  {
    const double sigma = s.FilterWidth;
    radius = static_cast<int>(std::ceil(3 * sigma));
    double sum = 0;
    for (int d = -radius; d <= radius; ++d)
    {
      kernel.push_back(std::exp(-0.5 * d * d / (sigma * sigma)));
      sum += kernel.back();
    }
    for (double& k : kernel)
      k /= sum;
    separable = true;
  }
  else
  {
    // cone of radius FilterWidth / sqrt(passes): wide while few photons, sharp as they add up
    const double r = std::max(1.0, s.FilterWidth / std::sqrt(double(std::max(1, f.Passes))));
    radius = static_cast<int>(std::floor(r));
    double sum = 0;
    for (int dj = -radius; dj <= radius; ++dj)
      for (int di = -radius; di <= radius; ++di)
      {
        kernel.push_back(std::max(0.0, 1.0 - std::hypot(di, dj) / (r + 0.5)));
        sum += kernel.back();
      }
    for (double& k : kernel)
      k /= sum;
  }
  for (std::vector<double>* c : f.PixelChannels())
    FilterChannel(*c, f.Size[0], f.Size[1], kernel, radius, separable);
}

const char* CutoffName(Cutoff c)
{
  switch (c)
  {
    case Cutoff::KnifeEdge:
      return "KnifeEdge";
    case Cutoff::Shadowgraph:
      return "Shadowgraph";
    case Cutoff::Circular:
      return "Circular";
    case Cutoff::ComplementCircular:
      return "ComplementCircular";
    case Cutoff::ColorFilter:
      return "ColorFilter";
    case Cutoff::Interferometry:
      return "Interferometry";
    case Cutoff::BOS:
      return "BOS";
  }
  return "?";
}

TraceResult Finalize(const Volume& volume, const TraceSettings& s, const FilmSums& raw)
{
  TraceResult r;
  r.Film = MakeFilm(volume, s);
  const std::size_t n = static_cast<std::size_t>(r.Film.Size[0]) * r.Film.Size[1];
  if (raw.Count.size() != n || raw.Passes < 1)
    throw Error("Finalize: the sums do not belong to this film, or hold no pass.");
  FilmSums sums = raw;
  FilterSums(sums, s);
  r.Intensity.assign(n, 0.f);
  r.Deflection.assign(2 * n, 0.f);
  if (s.EstimateError)
    r.ErrorEstimate.assign(n, 0.f);
  if (s.Mode == Cutoff::ColorFilter)
    r.RGB.assign(3 * n, 0.f);
  if (s.Mode == Cutoff::Interferometry)
    r.Phase.assign(n, 0.f);
  if (s.Mode == Cutoff::BOS)
    r.Displacement.assign(2 * n, 0.f);
  if (volume.Solid)
    r.Blocked.assign(n, 0.f);
  const double passes = sums.Passes;
  const double ang = s.KnifeAngle * 3.14159265358979323846 / 180.0;
  const double ca = std::cos(ang), sa = std::sin(ang);
  const bool manual = s.CutoffScale > 0;
  // the automatic scale maps the largest deflection to full contrast
  double k = s.CutoffScale;
  if (!manual)
  {
    if (s.Mode == Cutoff::KnifeEdge)
      k = sums.MaxAbsKnife > 0 ? 0.5 / sums.MaxAbsKnife : 0.0;
    else
      k = sums.MaxAbsDeflection > 0 ? 1.0 / sums.MaxAbsDeflection : 0.0;
  }
  const bool weighted = manual || s.RussianRoulette;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double c = sums.Count[i];
    if (c > 0)
    {
      r.Deflection[2 * i] = static_cast<float>(sums.DeflectionX[i] / c);
      r.Deflection[2 * i + 1] = static_cast<float>(sums.DeflectionY[i] / c);
      if (s.EstimateError)
        r.ErrorEstimate[i] = static_cast<float>(sums.ErrorSum[i] / c);
      if (s.Mode == Cutoff::Interferometry)
        r.Phase[i] = static_cast<float>(sums.Phase[i] / c);
      if (s.Mode == Cutoff::BOS)
      {
        r.Displacement[2 * i] = static_cast<float>(sums.ShiftX[i] / c);
        r.Displacement[2 * i + 1] = static_cast<float>(sums.ShiftY[i] / c);
      }
    }
    double I = 0;
    // with the automatic k no photon reaches a clamp, so the sums of the linear weights are exact
    switch (s.Mode)
    {
      case Cutoff::KnifeEdge:
        I = weighted ? sums.Weight[i] / passes
                     : (0.5 * c - k * (sums.DeflectionX[i] * ca + sums.DeflectionY[i] * sa)) / passes;
        break;
      case Cutoff::Circular:
        I = weighted ? sums.Weight[i] / passes : (c - k * sums.AbsDeflection[i]) / passes;
        break;
      case Cutoff::ComplementCircular:
        I = weighted ? sums.Weight[i] / passes : k * sums.AbsDeflection[i] / passes;
        break;
      case Cutoff::ColorFilter:
      {
        const double scale = (manual ? 1.0 : k) / passes;
        r.RGB[3 * i] = static_cast<float>(sums.Red[i] * scale);
        r.RGB[3 * i + 1] = static_cast<float>(sums.Green[i] * scale);
        r.RGB[3 * i + 2] = static_cast<float>(sums.Blue[i] * scale);
        I = (manual ? 0.0 : k * sums.AbsDeflection[i]) / passes;
        if (manual)
          I = std::max(r.RGB[3 * i], std::max(r.RGB[3 * i + 1], r.RGB[3 * i + 2]));
        break;
      }
      case Cutoff::Shadowgraph:
        I = c / passes;
        break;
      case Cutoff::Interferometry:
        I = sums.Weight[i] / passes;
        break;
      case Cutoff::BOS:
        // the background as seen through the flow; a body hides it (its photons count, dark)
        I = c + sums.Blocked[i] > 0 ? sums.Weight[i] / (c + sums.Blocked[i]) : 0.0;
        break;
    }
    if (volume.Solid)
      r.Blocked[i] = static_cast<float>(sums.Blocked[i] / passes);
    r.Intensity[i] = static_cast<float>(I);
  }
  r.CutoffScaleUsed = (s.Mode == Cutoff::Shadowgraph || s.Mode == Cutoff::Interferometry || s.Mode == Cutoff::BOS) ? 0.0 : k;
  r.Photons = sums.Photons;
  r.Samples = sums.Samples;
  r.FailedRays = sums.FailedRays;
  r.MissedRays = sums.MissedRays;
  r.MaxDrift = sums.MaxDrift;
  r.MaxError = sums.MaxError;
  r.UnderresolvedRays = sums.UnderresolvedRays;
  r.SideRays = sums.SideRays;
  r.Steps = sums.Steps;
  r.BlockedRays = sums.BlockedRays;
  if (sums.UnderresolvedRays > 0 && s.AutoMeasuredError >= 0)
  {
    std::ostringstream msg;
    msg << sums.UnderresolvedRays << " of " << sums.Photons
        << " rays took steps longer than a feature of the field; Auto measured the error of this "
           "setting on its pilot rays at "
        << s.AutoMeasuredError << " rad, within the tolerance " << s.Tolerance << " rad.\n";
    r.Warnings += msg.str();
  }
  else if (sums.UnderresolvedRays > 0)
  {
    std::ostringstream msg;
    msg << sums.UnderresolvedRays << " of " << sums.Photons
        << " rays took steps longer than a feature of the field (a shock or an interface crossed in "
           "one step): their deflection may be badly wrong. Lower StepSize (or the octree "
           "tolerance) until this warning goes.\n";
    r.Warnings += msg.str();
  }
  if (sums.FailedRays > 0)
  {
    std::ostringstream msg;
    msg << sums.FailedRays << " of " << sums.Photons
        << " rays failed (turned back, hit the step limit or went non-finite) and were dropped "
           "from the image.\n";
    r.Warnings += msg.str();
  }
  r.Warnings += PhotonWarnings(volume, r.Film, raw);
  return r;
}

std::string TraceSettings::PhotonKey() const
{
  std::ostringstream k;
  k.precision(17);
  k << ViewDirection[0] << ' ' << ViewDirection[1] << ' ' << ViewDirection[2] << ' ' << ViewUp[0]
    << ' ' << ViewUp[1] << ' ' << ViewUp[2] << ' ' << Resolution[0] << ' ' << Resolution[1] << ' '
    << StepSize << ' ' << static_cast<int>(Method) << ' ' << KeepInvariant << ' ' << EstimateError
    << ' ' << UseOctree << ' ' << static_cast<int>(Recon) << ' ' << Tolerance << ' ' << AutoMeasuredError << ' '
    << static_cast<int>(Mode) << ' ' << KnifeAngle << ' ' << CutoffScale << ' ' << FilmDistance
    << ' ' << Wavelength << ' ' << ReferenceTilt << ' ' << BackgroundDistance << ' '
    << BackgroundPattern << ' ' << BackgroundPeriod << ' ' << RussianRoulette << ' ' << Jitter
    << ' ' << Seed << ' ' << MaxSteps << ' ' << static_cast<int>(Device) << ' ' << RaysPerWorkItem
    << ' ' << RankIndex << ' ' << RankCount;
  return k.str();
}

const char* IntegratorName(Integrator m)
{
  switch (m)
  {
    case Integrator::Euler:
      return "Euler";
    case Integrator::Midpoint:
      return "Midpoint";
    case Integrator::RK4:
      return "RK4";
    case Integrator::Straight:
      return "Straight";
    case Integrator::Auto:
      return "Auto";
  }
  return "?";
}

const char* ReconstructionName(Reconstruction r)
{
  switch (r)
  {
    case Reconstruction::Trilinear:
      return "Trilinear";
    case Reconstruction::Cubic:
      return "Cubic";
    case Reconstruction::Auto:
      return "Auto";
  }
  return "?";
}

namespace
{
// What a tricubic sample costs against a trilinear one when Auto weighs the two reconstructions:
// it reads 64 points instead of 8, mostly from the same cache lines (docs/PERFORMANCE.md has the
// measured ratio).
constexpr double CubicSampleCost = 3.0;

// The rays of a pilot that a comparison can use: neither lost.
bool Comparable(const RayRecord& a, const RayRecord& b)
{
  const std::uint32_t bad = RayMaxSteps | RayTurned | RayNonFinite | RayOffFilm;
  return !(a.Flags & bad) && !(b.Flags & bad);
}
} // namespace

TraceSettings ResolveAuto(const Volume& volume, const TraceSettings& in, AutoChoice* choice)
{
  AutoChoice c;
  c.Method = in.Method;
  c.StepSize = in.StepSize;
  c.Recon = in.Recon;
  c.Met = true;
  const bool autoRecon = in.Recon == Reconstruction::Auto;
  if (in.Method != Integrator::Auto && !autoRecon)
  {
    c.Report = std::string(IntegratorName(in.Method)) + " at " + std::to_string(in.StepSize) + " voxel";
    if (in.Recon != Reconstruction::Trilinear)
      c.Report += std::string(", reconstruction ") + ReconstructionName(in.Recon);
    if (choice)
      *choice = c;
    return in;
  }
  CheckVolume(volume);
  const FilmGeometry film = MakeFilm(volume, in);
  const std::vector<float> ab = PilotRays(volume, in);
  TraceSettings ref = in;
  ref.Method = Integrator::RK4;
  ref.StepSize = 0.125;
  ref.UseOctree = false;
  ref.EstimateError = false;
  const auto t0 = std::chrono::steady_clock::now();
  // the reference's step (and the candidates') is Auto's, not the user's StepSize: say so when
  // the volume cannot be traced at it
  try
  {
    CheckPrecision(volume, ref);
  }
  catch (const Error& e)
  {
    throw Error(std::string("Integrator Auto measures its candidates against RK4 at 0.125 voxel, "
                            "which this volume does not allow: ") + e.what() +
      " Or choose a fixed Integrator and StepSize.");
  }
  // the reference of each reconstruction that may be chosen. Reconstruction Auto: the difference
  // between the two references is the second-order reconstruction's error (the fourth-order one's
  // is far smaller where the data is smooth, and both are the same trilinear code elsewhere), an
  // error that a reference on the same grid with the same reconstruction cannot see
  // (with a body the levels byte holds its bits instead of the smoothness: trilinear only)
  bool tryTri = in.Recon == Reconstruction::Trilinear || (autoRecon) || volume.Solid;
  bool tryCubic = !volume.Solid && (in.Recon == Reconstruction::Cubic || (autoRecon && volume.Smooth));
  std::vector<RayRecord> refTri, refCubic;
  if (tryTri)
  {
    ref.Recon = Reconstruction::Trilinear;
    refTri = TraceRays(volume, ref, ab);
  }
  if (tryCubic)
  {
    ref.Recon = Reconstruction::Cubic;
    refCubic = TraceRays(volume, ref, ab);
  }
  const std::vector<RayRecord>& R0 = tryCubic ? refCubic : refTri;
  double emax = 0;
  for (const RayRecord& r : R0)
    if (!(r.Flags & RayBlocked))
      emax = std::max(emax, double(std::hypot(r.DeflX, r.DeflY)));
  const double tol = in.Tolerance > 0 ? in.Tolerance : 0.01 * emax;
  double triError = 0;
  if (tryTri && tryCubic)
  {
    for (std::size_t k = 0; k < refTri.size(); ++k)
      if (Comparable(refTri[k], refCubic[k]))
        triError = std::max(triError,
          double(std::hypot(refTri[k].DeflX - refCubic[k].DeflX, refTri[k].DeflY - refCubic[k].DeflY)));
    c.TrilinearError = triError;
    // trilinear only where its own error leaves at least half the tolerance to the integrator
    if (triError > 0.5 * tol)
      tryTri = false;
  }
  if (in.Method != Integrator::Auto)
  {
    // Reconstruction Auto with a fixed integrator: trilinear where it is accurate enough
    c.Recon = tryTri ? Reconstruction::Trilinear : Reconstruction::Cubic;
    c.Tolerance = tol;
    std::ostringstream rep;
    rep << IntegratorName(in.Method) << " at " << in.StepSize << " voxel, reconstruction "
        << ReconstructionName(c.Recon) << " (the trilinear's estimated error " << triError
        << " rad against the tolerance " << tol << " rad)";
    c.Report = rep.str();
    if (choice)
      *choice = c;
    TraceSettings out = in;
    out.Recon = c.Recon;
    return out;
  }
  struct Candidate
  {
    Integrator M;
    double Step;
    Reconstruction Rc;
  };
  std::vector<Candidate> candidates;
  for (Reconstruction rc : { Reconstruction::Trilinear, Reconstruction::Cubic })
  {
    if ((rc == Reconstruction::Trilinear && !tryTri) || (rc == Reconstruction::Cubic && !tryCubic))
      continue;
    // tricubic: steps sized by the field, up to 64 voxels where the data is smooth (a voxel
    // elsewhere, see sch_walk_step)
    std::vector<double> longSteps;
    if (rc == Reconstruction::Cubic)
      longSteps = { 64.0, 32.0, 16.0 };
    for (double st : longSteps)
      candidates.push_back({ Integrator::Straight, st, rc });
    for (double st : { 8.0, 4.0, 2.0, 1.0 })
      candidates.push_back({ Integrator::Straight, st, rc });
    for (Integrator m : { Integrator::Euler, Integrator::Midpoint, Integrator::RK4 })
    {
      for (double st : longSteps)
        candidates.push_back({ m, st, rc });
      for (double st : { 8.0, 4.0, 2.0, 1.0, 0.5, 0.25 })
        candidates.push_back({ m, st, rc });
    }
  }
  bool found = false;
  double bestCost = 1e300, bestErr = 1e300;
  AutoChoice fallback;
  // each integrator's steps come longest first: once one meets the tolerance, the shorter ones of
  // that integrator and reconstruction only cost more
  std::map<int, bool> met;
  for (const Candidate& cand : candidates)
  {
    const int group = static_cast<int>(cand.Rc) * 8 + static_cast<int>(cand.M);
    if (met[group])
      continue;
    TraceSettings t = in;
    t.Method = cand.M;
    t.StepSize = cand.Step;
    t.Recon = cand.Rc;
    t.EstimateError = false;
    const std::vector<RayRecord> T = TraceRays(volume, t, ab);
    const std::vector<RayRecord>& R = cand.Rc == Reconstruction::Cubic ? refCubic : refTri;
    // a trilinear candidate answers for the trilinear's own error too (Reconstruction Auto)
    const double base = cand.Rc == Reconstruction::Trilinear && tryCubic ? triError : 0.0;
    double err = 0, land = 0, samples = 0;
    bool lost = false;
    // rays the candidate loses where the reference does not disqualify it; steps over structure
    // do not by themselves: their effect is in the measured error
    const std::uint32_t bad = RayMaxSteps | RayTurned | RayNonFinite | RayOffFilm;
    for (std::size_t k = 0; k < T.size(); ++k)
    {
      samples += T[k].Samples;
      if (R[k].Flags & bad)
        continue; // the reference itself cannot be trusted here: nothing to compare
      // a body stopped it (in either trace: a grazing ray may stop at a body's corner with one
      // step and pass it with another): dark, no deflection to compare
      if ((R[k].Flags | T[k].Flags) & RayBlocked)
        continue;
      if (T[k].Flags & bad)
        lost = true; // it fails (or steps over structure) where the reference does not
      err = std::max(err, double(std::hypot(T[k].DeflX - R[k].DeflX, T[k].DeflY - R[k].DeflY)));
      land = std::max(land, double(std::hypot(T[k].LandA - R[k].LandA, T[k].LandB - R[k].LandB)));
    }
    land /= film.PixelSize;
    if (lost)
      continue;
    const double cost = samples * (cand.Rc == Reconstruction::Cubic ? CubicSampleCost : 1.0);
    if (err + base <= tol && land <= 0.5)
      met[group] = true;
    if (err + base <= tol && land <= 0.5 && cost < bestCost)
    {
      found = true;
      bestCost = cost;
      c.Method = cand.M;
      c.StepSize = cand.Step;
      c.Recon = cand.Rc;
      c.ExpectedError = err + base;
      c.ExpectedLandingError = land;
      c.SamplesPerRay = samples / T.size();
    }
    if (!found && err + base < bestErr)
    {
      bestErr = err + base;
      fallback.Method = cand.M;
      fallback.StepSize = cand.Step;
      fallback.Recon = cand.Rc;
      fallback.ExpectedError = err + base;
      fallback.ExpectedLandingError = land;
      fallback.SamplesPerRay = samples / T.size();
    }
  }
  if (!found)
  {
    const double keep = c.TrilinearError;
    c = fallback;
    c.TrilinearError = keep;
    c.Met = false;
  }
  c.Tolerance = tol;
  // the octree is a cost too: a skipping step costs more than a plain one (1.2-1.9x here). Kept
  // when it saves at least 10 % of the chosen setting's samples on the pilot; without it the
  // error can only stay or shrink (fixed steps through the blocks it would have skipped).
  c.UseOctree = in.UseOctree && volume.Levels != nullptr;
  if (c.UseOctree)
  {
    TraceSettings t = in;
    t.Method = c.Method;
    t.StepSize = c.StepSize;
    t.Recon = c.Recon;
    t.EstimateError = false;
    t.UseOctree = false;
    double plain = 0;
    for (const RayRecord& r : TraceRays(volume, t, ab))
      plain += r.Samples;
    c.OctreeSaving = plain > 0 ? 1.0 - c.SamplesPerRay * (ab.size() / 2) / plain : 0.0;
    c.UseOctree = c.OctreeSaving >= 0.1;
  }
  const double ms = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() * 1e3;
  std::ostringstream rep;
  rep << "Auto chose " << IntegratorName(c.Method) << " at " << c.StepSize << " voxel: expected "
      << "deflection error " << c.ExpectedError << " rad (tolerance " << tol << " rad), landing error "
      << c.ExpectedLandingError << " pixel, " << c.SamplesPerRay << " samples per ray (pilot of "
      << ab.size() / 2 << " rays, " << static_cast<int>(ms) << " ms)";
  if (c.Recon != Reconstruction::Trilinear || autoRecon)
    rep << "; reconstruction " << ReconstructionName(c.Recon);
  if (autoRecon && tryCubic)
    rep << " (the trilinear's estimated error " << c.TrilinearError << " rad)";
  if (!c.Met)
    rep << "; no candidate met the tolerance: using the most accurate one";
  if (in.UseOctree && volume.Levels)
    rep << "; octree " << (c.UseOctree ? "on" : "off") << ": it skips "
        << static_cast<int>(std::lround(100 * c.OctreeSaving)) << " % of the samples"
        << (c.UseOctree ? "" : " (less than 10 %)");
  c.Report = rep.str();
  if (choice)
    *choice = c;
  TraceSettings out = in;
  out.Method = c.Method;
  out.StepSize = c.StepSize;
  out.Recon = c.Recon;
  out.AutoMeasuredError = c.Met ? c.ExpectedError : -1.0;
  out.UseOctree = in.UseOctree && c.UseOctree;
  return out;
}

std::vector<float> PilotRays(const Volume& volume, const TraceSettings& s)
{
  const FilmGeometry film = MakeFilm(volume, s);
  std::vector<float> ab;
  const int np = 16;
  const double w = film.Size[0] * film.PixelSize, h = film.Size[1] * film.PixelSize;
  for (int j = 0; j < np; ++j)
    for (int i = 0; i < np; ++i)
    {
      ab.push_back(static_cast<float>(film.Corner[0] + (i + 0.5) * w / np));
      ab.push_back(static_cast<float>(film.Corner[1] + (j + 0.5) * h / np));
    }
  return ab;
}

std::uint64_t NewVolumeStamp()
{
  static std::atomic<std::uint64_t> next(1);
  return next.fetch_add(1);
}

void ReleaseKeptVolume()
{
  std::lock_guard<std::mutex> lock(KeptMutex);
  Kept().Tracer.reset();
  Kept().Identity = VolumeIdentity();
}

TraceResult Trace(const Volume& volume, const TraceSettings& requested, const ProgressFunction& progress)
{
  FilmSums sums;
  std::string used, device, warn;
  AutoChoice choice;
  const TraceSettings s = ResolveAuto(volume, requested, &choice);
  if (!choice.Met)
    warn += choice.Report + "\n";
  const auto t0 = std::chrono::steady_clock::now();
  Accumulate(volume, s, sums, &used, &device, &warn, progress);
  const auto t1 = std::chrono::steady_clock::now();
  TraceResult r = Finalize(volume, s, sums);
  r.Choice = choice;
  r.BackendUsed = used;
  r.DeviceName = device;
  r.Warnings = warn + r.Warnings;
  r.Seconds = std::chrono::duration<double>(t1 - t0).count();
  return r;
}

std::vector<RayRecord> TraceRays(const Volume& volume, const TraceSettings& s,
  const std::vector<float>& ab, std::string* backendUsed)
{
  CheckVolume(volume);
  if (s.Method == Integrator::Auto)
    throw Error("TraceRays: resolve Integrator Auto first (ResolveAuto).");
  const FilmGeometry film = MakeFilm(volume, s);
  sch_params P = MakeParams(volume, s, film);
  const std::size_t count = ab.size() / 2;
  std::vector<RayRecord> out(count);
  std::string used, device, warn;
  std::shared_ptr<std::vector<unsigned char>> levelBytes;
  const Volume tv = TraceVolume(volume, levelBytes);
  const auto solidBytes = CellBytesOf(volume, StepReach(P));
  const unsigned char* bytes = solidBytes ? solidBytes->data() : tv.Levels;
  std::shared_ptr<OpenCLTracer> cl = OpenBackend(
    tv, bytes, solidBytes, s, P, std::max<std::size_t>(count, 1), true, used, device, warn);
  SetFeatureTolerance(P, tv);
  float* rec = reinterpret_cast<float*>(out.data());
  if (cl)
    cl->TracePoints(P, ab.data(), count, rec);
  else
    for (std::size_t k = 0; k < count; ++k)
      sch_trace(tv.Field, bytes, &P, ab[2 * k], ab[2 * k + 1], rec + k * SCH_RECORD);
  // the flags travel as floats in the record; turn them into integers
  for (RayRecord& r : out)
  {
    float f;
    std::memcpy(&f, &r.Flags, sizeof(f));
    r.Flags = static_cast<std::uint32_t>(f);
  }
  if (backendUsed)
    *backendUsed = used;
  return out;
}

DeviceInfo QueryOpenCLDevice()
{
  DeviceInfo info;
  try
  {
    ocl::Runtime& rt = ocl::GetRuntime();
    info.Available = true;
    info.Name = rt.DeviceName;
    info.Platform = rt.PlatformName;
    info.Version = rt.Version;
    info.MaxAlloc = rt.MaxAlloc;
    info.GlobalMemory = rt.GlobalMemory;
  }
  catch (const Error& e)
  {
    info.Reason = e.what();
  }
  return info;
}

void BuildOpenCLProgram(const std::string& name, const std::string& source, const std::string& options)
{
  ocl::GetProgram(name, source, options);
}

} // namespace schlieren
