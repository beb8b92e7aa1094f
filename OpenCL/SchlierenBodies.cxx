// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenBodies.h"
#include "SchlierenParallel.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
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

std::size_t EnclosedInvalidPointsOfPiece(Parallel& parallel, const int extent[6], const int whole[6],
  const unsigned char* valid, const int* wallFaces, unsigned char* solid)
{
  const int ranks = parallel.Size(), me = parallel.Rank();
  const bool empty = extent[1] < extent[0] || extent[3] < extent[2] || extent[5] < extent[4];
  const std::int64_t nx = empty ? 0 : extent[1] - extent[0] + 1, ny = empty ? 0 : extent[3] - extent[2] + 1,
                     nz = empty ? 0 : extent[5] - extent[4] + 1;
  const std::size_t n = static_cast<std::size_t>(nx * ny * nz);
  // every rank's extent
  std::vector<char> mine(6 * sizeof(int));
  std::memcpy(mine.data(), extent, 6 * sizeof(int));
  const std::vector<std::vector<char>> all = parallel.AllGather(mine);
  std::vector<std::array<int, 6>> ext(ranks);
  for (int r = 0; r < ranks; ++r)
    std::memcpy(ext[r].data(), all[r].data(), 6 * sizeof(int));
  std::vector<unsigned char> outside(n, 0);
  std::vector<std::int64_t> stack;
  auto at = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return ((k - extent[4]) * ny + (j - extent[2])) * nx + (i - extent[0]);
  };
  auto inside = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return !empty && i >= extent[0] && i <= extent[1] && j >= extent[2] && j <= extent[3] &&
      k >= extent[4] && k <= extent[5];
  };
  auto seed = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    if (!inside(i, j, k))
      return;
    const std::int64_t p = at(i, j, k);
    if (!valid[p] && !outside[p])
    {
      outside[p] = 1;
      stack.push_back(p);
    }
  };
  // the whole grid's open faces (as EnclosedInvalidPoints)
  auto open = [&](int f) { return !(wallFaces && wallFaces[f]); };
  for (std::int64_t k = extent[4]; k <= extent[5] && !empty; ++k)
    for (std::int64_t j = extent[2]; j <= extent[3]; ++j)
      for (std::int64_t i = extent[0]; i <= extent[1]; ++i)
        if ((i == whole[0] && open(0)) || (i == whole[1] && open(1)) || (j == whole[2] && open(2)) ||
          (j == whole[3] && open(3)) || (k == whole[4] && open(4)) || (k == whole[5] && open(5)))
          seed(i, j, k);
  // the six neighbours of point (i, j, k) (of the whole grid), those in this piece
  auto seedAround = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    seed(i - 1, j, k);
    seed(i + 1, j, k);
    seed(i, j - 1, k);
    seed(i, j + 1, k);
    seed(i, j, k - 1);
    seed(i, j, k + 1);
  };
  auto flood = [&]() {
    while (!stack.empty())
    {
      const std::int64_t p = stack.back();
      stack.pop_back();
      seedAround(extent[0] + p % nx, extent[2] + (p / nx) % ny, extent[4] + p / (nx * ny));
    }
  };
  // what each other rank needs of this piece: its points shared with, or next to, that rank's
  // piece (the other's extent grown by one)
  std::vector<std::array<int, 6>> boxes(ranks);
  for (int r = 0; r < ranks; ++r)
  {
    std::array<int, 6>& b = boxes[r];
    const std::array<int, 6>& o = ext[r];
    const bool theirsEmpty = o[1] < o[0] || o[3] < o[2] || o[5] < o[4];
    for (int a = 0; a < 3; ++a)
    {
      b[2 * a] = std::max(extent[2 * a], o[2 * a] - 1);
      b[2 * a + 1] = std::min(extent[2 * a + 1], o[2 * a + 1] + 1);
    }
    if (r == me || empty || theirsEmpty)
      b = { 0, -1, 0, -1, 0, -1 };
  }
  flood();
  for (;;)
  {
    // this piece's outside points in each box (a byte each), to the box's rank
    std::vector<std::vector<char>> send(ranks);
    for (int r = 0; r < ranks; ++r)
    {
      const std::array<int, 6>& b = boxes[r];
      if (b[1] < b[0] || b[3] < b[2] || b[5] < b[4])
        continue;
      send[r].resize(6 * sizeof(int));
      std::memcpy(send[r].data(), b.data(), 6 * sizeof(int));
      for (std::int64_t k = b[4]; k <= b[5]; ++k)
        for (std::int64_t j = b[2]; j <= b[3]; ++j)
          for (std::int64_t i = b[0]; i <= b[1]; ++i)
            send[r].push_back(static_cast<char>(outside[at(i, j, k)]));
    }
    const std::vector<std::vector<char>> got = parallel.Exchange(send);
    // an outside point of another piece makes its invalid neighbours here (and itself, where
    // shared) outside
    for (int r = 0; r < ranks; ++r)
    {
      if (got[r].size() < 6 * sizeof(int))
        continue;
      int b[6];
      std::memcpy(b, got[r].data(), 6 * sizeof(int));
      const char* f = got[r].data() + 6 * sizeof(int);
      for (std::int64_t k = b[4]; k <= b[5]; ++k)
        for (std::int64_t j = b[2]; j <= b[3]; ++j)
          for (std::int64_t i = b[0]; i <= b[1]; ++i, ++f)
            if (*f)
            {
              seed(i, j, k);
              seedAround(i, j, k);
            }
    }
    // every rank stops together, once no piece found a new outside point
    if (parallel.Max(stack.empty() ? 0.0 : 1.0) == 0.0)
      break;
    flood();
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
