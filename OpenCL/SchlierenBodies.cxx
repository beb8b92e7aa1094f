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

std::size_t InvalidRegionsBesideWalls(
  const int dims[3], const unsigned char* valid, const unsigned char* rim, unsigned char* solid)
{
  const std::int64_t nx = dims[0], ny = dims[1], nz = dims[2];
  const std::size_t n = static_cast<std::size_t>(nx * ny * nz);
  std::vector<std::int64_t> region(n, -1);
  std::vector<unsigned char> kind(n, 0); // a shared void's points: the nearest rim's kind
  std::vector<std::int64_t> stack, members;
  std::size_t count = 0;
  std::int64_t label = 0;
  for (std::size_t start = 0; start < n; ++start)
  {
    if (valid[start] || region[start] >= 0)
    {
      continue;
    }
    // flood fill one region, counting its wall and flow rim points
    std::size_t walls = 0, flows = 0;
    members.clear();
    region[start] = label;
    stack.push_back(static_cast<std::int64_t>(start));
    while (!stack.empty())
    {
      const std::int64_t p = stack.back();
      stack.pop_back();
      members.push_back(p);
      walls += rim[p] == 1;
      flows += rim[p] == 2;
      const std::int64_t i = p % nx, j = (p / nx) % ny, k = p / (nx * ny);
      const std::int64_t next[6][3] = { { i - 1, j, k }, { i + 1, j, k }, { i, j - 1, k },
        { i, j + 1, k }, { i, j, k - 1 }, { i, j, k + 1 } };
      for (const auto& q : next)
      {
        if (q[0] < 0 || q[0] >= nx || q[1] < 0 || q[1] >= ny || q[2] < 0 || q[2] >= nz)
        {
          continue;
        }
        const std::int64_t r = (q[2] * ny + q[1]) * nx + q[0];
        if (!valid[r] && region[r] < 0)
        {
          region[r] = label;
          stack.push_back(r);
        }
      }
    }
    ++label;
    if (walls > flows)
    {
      for (std::int64_t p : members)
      {
        count += solid[p] == 0;
        solid[p] = 1;
      }
    }
    else if (walls > 0)
    {
      // A void that walls and flow faces share (the inside of a cone joined to the far field
      // beyond a thin body-fitted mesh, past its outlet): each point goes with the rim nearest
      // to it, by a breadth-first front from every wall and flow rim point at once; the points
      // the walls' front reaches first are the body.
      std::vector<std::int64_t> front;
      for (std::int64_t p : members)
      {
        if (rim[p] == 1 || rim[p] == 2)
        {
          kind[p] = rim[p];
          front.push_back(p);
        }
      }
      for (std::size_t head = 0; head < front.size(); ++head)
      {
        const std::int64_t p = front[head];
        const std::int64_t i = p % nx, j = (p / nx) % ny, k = p / (nx * ny);
        const std::int64_t next[6][3] = { { i - 1, j, k }, { i + 1, j, k }, { i, j - 1, k },
          { i, j + 1, k }, { i, j, k - 1 }, { i, j, k + 1 } };
        for (const auto& q : next)
        {
          if (q[0] < 0 || q[0] >= nx || q[1] < 0 || q[1] >= ny || q[2] < 0 || q[2] >= nz)
          {
            continue;
          }
          const std::int64_t r = (q[2] * ny + q[1]) * nx + q[0];
          if (!valid[r] && kind[r] == 0)
          {
            kind[r] = kind[p];
            front.push_back(r);
          }
        }
      }
      for (std::int64_t p : members)
      {
        if (kind[p] == 1)
        {
          count += solid[p] == 0;
          solid[p] = 1;
        }
      }
    }
  }
  return count;
}

} // namespace schlieren
