// SPDX-License-Identifier: BSD-3-Clause
// The min-max octree: ComputeOctreeLevels (a level per cell).
#include "SchlierenEngineInternal.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace schlieren
{

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

} // namespace schlieren
