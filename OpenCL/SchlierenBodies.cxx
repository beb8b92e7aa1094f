// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenBodies.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace schlieren
{

std::size_t EnclosedInvalidPoints(
  const int dims[3], const unsigned char* valid, const int* wallFaces, unsigned char* solid)
{
  const std::int64_t nx = dims[0], ny = dims[1], nz = dims[2];
  const std::size_t n = static_cast<std::size_t>(nx * ny * nz);
  // outside: invalid points reached from an open face through invalid points (a flood fill)
  std::vector<unsigned char> outside(n, 0);
  std::vector<std::int64_t> stack;
  auto open = [&](int f) { return !(wallFaces && wallFaces[f]); };
  auto seed = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    const std::int64_t p = (k * ny + j) * nx + i;
    if (!valid[p] && !outside[p])
    {
      outside[p] = 1;
      stack.push_back(p);
    }
  };
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i)
      {
        const bool onOpenFace = (i == 0 && open(0)) || (i == nx - 1 && open(1)) ||
          (j == 0 && open(2)) || (j == ny - 1 && open(3)) || (k == 0 && open(4)) ||
          (k == nz - 1 && open(5));
        if (onOpenFace)
          seed(i, j, k);
      }
  while (!stack.empty())
  {
    const std::int64_t p = stack.back();
    stack.pop_back();
    const std::int64_t i = p % nx, j = (p / nx) % ny, k = p / (nx * ny);
    if (i > 0)
      seed(i - 1, j, k);
    if (i + 1 < nx)
      seed(i + 1, j, k);
    if (j > 0)
      seed(i, j - 1, k);
    if (j + 1 < ny)
      seed(i, j + 1, k);
    if (k > 0)
      seed(i, j, k - 1);
    if (k + 1 < nz)
      seed(i, j, k + 1);
  }
  std::size_t count = 0;
  for (std::size_t p = 0; p < n; ++p)
  {
    solid[p] = (!valid[p] && !outside[p]) ? 1 : 0;
    count += solid[p];
  }
  return count;
}

} // namespace schlieren
