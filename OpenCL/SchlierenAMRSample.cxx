// SPDX-License-Identifier: BSD-3-Clause
// Overlapping AMR sampled onto an image grid, finest level first (SchlierenAMRSample.h).
#include "SchlierenAMRSample.h"

#include "SchlierenLimits.h"
#include "SchlierenParallel.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>

namespace
{
/** One axis of a trilinear stencil: the lower index and the weight of the upper one. */
struct Stencil
{
  int Index;
  float Weight;
};

/**
 * Where `u` (a coordinate in units of the samples, 0 at the first) falls between `count`
 * samples: clamped to the first and last sample, so that a point beyond them takes the nearest.
 */
Stencil Between(double u, int count)
{
  if (count <= 1)
  {
    return { 0, 0.0f };
  }
  u = std::min(std::max(u, 0.0), double(count - 1));
  const int i = std::min(static_cast<int>(std::floor(u)), count - 2);
  return { i, static_cast<float>(u - i) };
}

/** A box's array as floats (its components kept), read in place where it is float already. */
const float* AsFloats(const schlieren::AMRArray& a, std::size_t n, std::vector<float>& copy)
{
  if (a.ValueBytes == 4)
  {
    return static_cast<const float*>(a.Values);
  }
  const double* v = static_cast<const double*>(a.Values);
  copy.resize(n);
  std::transform(v, v + n, copy.begin(), [](double x) { return static_cast<float>(x); });
  return copy.data();
}

bool EmptyExtent(const int e[6])
{
  return e[1] < e[0] || e[3] < e[2] || e[5] < e[4];
}

/** The blocks' indices by level, coarsest first, each level's in the order given. */
std::vector<std::size_t> ByLevel(const std::vector<schlieren::AMRBlock>& blocks)
{
  std::vector<std::size_t> order(blocks.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
    [&](std::size_t x, std::size_t y) { return blocks[x].Level < blocks[y].Level; });
  return order;
}
} // namespace

namespace schlieren
{

//------------------------------------------------------------------------------
std::string AMROverlapProblem(const std::vector<AMRCellBox>& all)
{
  int levels = 0;
  for (const AMRCellBox& b : all)
  {
    levels = std::max(levels, b.Level + 1);
  }
  for (int l = 0; l < levels; ++l)
  {
    // each box's cell range (an axis with no cells, a 2D box's, as one cell), swept along x
    std::vector<std::array<int, 6>> boxes;
    std::vector<unsigned int> ids;
    unsigned int index = 0;
    for (const AMRCellBox& box : all)
    {
      if (box.Level != l)
      {
        continue;
      }
      const unsigned int b = index++;
      const int* lo = box.Lo;
      const int* hi = box.Hi;
      bool invalid = false; // vtkAMRBox::IsInvalid (in 64 bits: lo - 1 of INT_MIN overflows)
      for (int a = 0; a < 3; ++a)
      {
        invalid = invalid || std::int64_t(hi[a]) < std::int64_t(lo[a]) - 1;
      }
      if (invalid)
      {
        continue;
      }
      std::array<int, 6> r;
      for (int a = 0; a < 3; ++a)
      {
        r[2 * a] = lo[a];
        r[2 * a + 1] = std::max(lo[a], hi[a]);
      }
      boxes.push_back(r);
      ids.push_back(b);
    }
    std::vector<std::size_t> order(boxes.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(),
      [&](std::size_t x, std::size_t y) { return boxes[x][0] < boxes[y][0]; });
    std::size_t pairs = 0;
    double cells = 0;
    std::ostringstream first;
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      const std::array<int, 6>& p = boxes[order[i]];
      for (std::size_t j = i + 1; j < order.size() && boxes[order[j]][0] <= p[1]; ++j)
      {
        const std::array<int, 6>& q = boxes[order[j]];
        double shared = 1;
        for (int a = 0; a < 3 && shared > 0; ++a)
        {
          shared *= std::max(0.0,
            double(std::min(p[2 * a + 1], q[2 * a + 1])) - double(std::max(p[2 * a], q[2 * a])) + 1);
        }
        if (shared <= 0)
        {
          continue;
        }
        if (pairs == 0)
        {
          const unsigned int b0 = std::min(ids[order[i]], ids[order[j]]);
          const unsigned int b1 = std::max(ids[order[i]], ids[order[j]]);
          first << "boxes " << b0 << " and " << b1 << " share " << shared << " cells (cells";
          for (int a = 0; a < 3; ++a)
          {
            first << ' ' << "ijk"[a] << ' ' << std::max(p[2 * a], q[2 * a]) << "-"
                  << std::min(p[2 * a + 1], q[2 * a + 1]);
          }
          first << ")";
        }
        ++pairs;
        cells += shared;
      }
    }
    if (pairs > 0)
    {
      std::ostringstream m;
      m << "RefractiveIndex: the AMR input's level " << l << " has boxes that overlap: " << first.str();
      if (pairs > 1)
      {
        m << ", and " << pairs - 1 << " more pairs (" << cells << " cells in all)";
      }
      m << ". A level's boxes must tile it without overlap (each cell in one box); where two "
           "overlap, which box's values to take is undefined. Fix the boxes (the writer's or "
           "reader's AMR metadata), or resample the data onto an image first.";
      return m.str();
    }
  }
  return std::string();
}

//------------------------------------------------------------------------------
bool AMRFinestSpacing(Parallel& parallel, const std::vector<AMRBlock>& blocks, int listed,
  double spacing[3], int& level, int& levels)
{
  double found[2] = { -1.0, double(listed) }; // level, then levels listed
  double h[3] = { DBL_MAX, DBL_MAX, DBL_MAX };
  for (std::size_t i : ByLevel(blocks))
  {
    // the finest level's first box (by level, then in the order given)
    if (blocks[i].Level > found[0])
    {
      found[0] = blocks[i].Level;
      std::copy(blocks[i].Spacing, blocks[i].Spacing + 3, h);
    }
  }
  double any[2] = { found[0], found[1] };
  parallel.Max(any, 2);
  if (any[0] < 0.0)
  {
    return false;
  }
  if (found[0] != any[0])
  {
    h[0] = h[1] = h[2] = DBL_MAX; // a coarser level here: the finest rank's spacing decides
  }
  parallel.Min(h, 3);
  std::copy(h, h + 3, spacing);
  level = static_cast<int>(any[0]);
  levels = static_cast<int>(any[1]);
  return true;
}

//------------------------------------------------------------------------------
bool AMRDimensions(Parallel& parallel, const std::vector<AMRBlock>& blocks, int listed,
  const double bounds[6], double bytesPerPoint, int dims[3], double finest[3], bool& capped,
  std::string& note)
{
  int level = 0, levels = 0;
  if (!AMRFinestSpacing(parallel, blocks, listed, finest, level, levels))
  {
    return false;
  }
  double wanted = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    const double cells = (bounds[2 * a + 1] - bounds[2 * a]) / finest[a];
    dims[a] = std::max(1, static_cast<int>(std::min(std::floor(cells + 0.5), 1e6)) + 1);
    wanted *= dims[a];
  }
  const double budget = parallel.Min(0.5 * static_cast<double>(schlieren::AvailableMemory()));
  const int full[3] = { dims[0], dims[1], dims[2] };
  capped = false;
  double scale = std::cbrt(wanted * bytesPerPoint / budget);
  while (double(dims[0]) * dims[1] * dims[2] * bytesPerPoint > budget)
  {
    capped = true;
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = full[a] > 1 ? std::max(2, static_cast<int>((full[a] - 1) / scale) + 1) : 1;
    }
    if (double(dims[0]) * dims[1] * dims[2] <= 8)
    {
      break; // nothing smaller: CheckHostMemory refuses it with its message
    }
    scale *= 1.01;
  }
  std::ostringstream m;
  m << "RefractiveIndex: AMR input: the grid's spacing from its finest level (level " << level
    << " of " << levels << ", spacing " << finest[0] << ")";
  if (capped)
  {
    m << " would need " << full[0] << " x " << full[1] << " x " << full[2] << " points ("
      << schlieren::FormatBytes(wanted * bytesPerPoint) << "); capped to " << dims[0] << " x "
      << dims[1] << " x " << dims[2] << " by the memory budget (half the memory available, "
      << schlieren::FormatBytes(budget) << "). Set SamplingDimensions to choose another grid.";
  }
  else
  {
    m << ": " << dims[0] << " x " << dims[1] << " x " << dims[2] << " points.";
  }
  note = m.str();
  return true;
}

//------------------------------------------------------------------------------
AMRSampled AMRResample(Parallel& parallel, const std::vector<AMRBlock>& blocks, int listed,
  const int D[3], const double O[3], const double H[3], const std::vector<std::string>& names)
{
  const std::int64_t count = std::int64_t(D[0]) * D[1] * D[2];
  std::vector<int> levelOf(static_cast<std::size_t>(count), -1);
  AMRSampled r;
  std::vector<std::vector<float>>& values = r.Values;
  std::vector<int>& components = r.Components;
  std::vector<int>& fromCells = r.FromCells;
  values.resize(names.size());
  components.assign(names.size(), 0);
  fromCells.assign(names.size(), 0);
  const int levels = std::max(listed, 0);
  std::vector<int> loaded(static_cast<std::size_t>(levels), 0);
  std::vector<float> copy;
  for (std::size_t bi : ByLevel(blocks))
  {
    const AMRBlock& g = blocks[bi];
    const int l = g.Level;
    if (EmptyExtent(g.Extent))
    {
      continue;
    }
    if (l >= 0 && l < levels)
    {
      loaded[l] = 1;
    }
    const int* ext = g.Extent;
    const double* o = g.Origin;
    const double* h = g.Spacing;
    int np[3];
    double lo[3];
    // the grid points this box covers, and the stencils along each axis
    int first[3], last[3];
    std::vector<Stencil> atPoints[3], atCells[3];
    bool empty = false;
    for (int a = 0; a < 3; ++a)
    {
      np[a] = ext[2 * a + 1] - ext[2 * a] + 1;
      lo[a] = o[a] + ext[2 * a] * h[a];
      const double hi = o[a] + ext[2 * a + 1] * h[a];
      const double eps = 1e-9 * std::max(std::fabs(H[a]), std::fabs(hi - lo[a]));
      // (clamped in double first: a box far off the grid must not overflow an int)
      auto index = [&](double i) { return static_cast<int>(std::min(std::max(i, -1.0), double(D[a]))); };
      first[a] = std::max(0, index(std::ceil((lo[a] - eps - O[a]) / H[a])));
      last[a] = std::min(D[a] - 1, index(std::floor((hi + eps - O[a]) / H[a])));
      if (D[a] == 1)
      {
        // the grid's one plane: covered or not (not: first past last; the filter's code before
        // the engine set both to 1 there and wrote one plane past the grid)
        first[a] = (O[a] >= lo[a] - eps && O[a] <= hi + eps) ? 0 : 1;
        last[a] = 0;
      }
      empty = empty || last[a] < first[a];
      for (int i = first[a]; i <= last[a] && !empty; ++i)
      {
        const double u = (O[a] + i * H[a] - lo[a]) / h[a];
        atPoints[a].push_back(Between(u, np[a]));
        atCells[a].push_back(Between(u - 0.5, std::max(np[a] - 1, 1)));
      }
    }
    if (empty)
    {
      continue;
    }
    for (std::size_t k = 0; k < names.size() && k < g.Arrays.size(); ++k)
    {
      const AMRArray& a = g.Arrays[k];
      if (!a.Values || a.Components < 1)
      {
        continue;
      }
      const bool cells = a.Cells;
      const int nc = a.Components;
      if (components[k] == 0)
      {
        components[k] = nc;
        values[k].assign(static_cast<std::size_t>(count) * nc, 0.0f);
      }
      if (components[k] != nc)
      {
        continue; // a box that disagrees on the components: not read
      }
      fromCells[k] = fromCells[k] || cells;
      const std::vector<Stencil>* s = cells ? atCells : atPoints;
      std::int64_t n[3] = { np[0], np[1], np[2] };
      if (cells)
      {
        for (int ax = 0; ax < 3; ++ax)
        {
          n[ax] = std::max(np[ax] - 1, 1);
        }
      }
      const float* v = AsFloats(a, static_cast<std::size_t>(n[0] * n[1] * n[2] * nc), copy);
      const std::int64_t sx = n[0] > 1 ? 1 : 0, sy = n[1] > 1 ? n[0] : 0,
                         sz = n[2] > 1 ? n[0] * n[1] : 0;
      float* out = values[k].data();
      for (int z = first[2]; z <= last[2]; ++z)
      {
        const Stencil& cz = s[2][z - first[2]];
        for (int y = first[1]; y <= last[1]; ++y)
        {
          const Stencil& cy = s[1][y - first[1]];
          const std::int64_t row = (std::int64_t(z) * D[1] + y) * D[0];
          for (int x = first[0]; x <= last[0]; ++x)
          {
            const Stencil& cx = s[0][x - first[0]];
            const std::int64_t base = (std::int64_t(cz.Index) * n[1] + cy.Index) * n[0] + cx.Index;
            const float wx = cx.Weight, wy = cy.Weight, wz = cz.Weight;
            for (int c = 0; c < nc; ++c)
            {
              auto at = [&](std::int64_t offset) { return v[(base + offset) * nc + c]; };
              const float c00 = at(0) + wx * (at(sx) - at(0));
              const float c10 = at(sy) + wx * (at(sy + sx) - at(sy));
              const float c01 = at(sz) + wx * (at(sz + sx) - at(sz));
              const float c11 = at(sz + sy) + wx * (at(sz + sy + sx) - at(sz + sy));
              const float c0 = c00 + wy * (c10 - c00), c1 = c01 + wy * (c11 - c01);
              out[(row + x) * nc + c] = c0 + wz * (c1 - c0);
            }
          }
        }
      }
    }
    for (int z = first[2]; z <= last[2]; ++z)
    {
      for (int y = first[1]; y <= last[1]; ++y)
      {
        const std::int64_t row = (std::int64_t(z) * D[1] + y) * D[0];
        std::fill(levelOf.begin() + row + first[0], levelOf.begin() + row + last[0] + 1, l);
      }
    }
  }

  // under MPI: the finest level found on any rank wins (the mean where two ranks hold it)
  if (parallel.Size() > 1)
  {
    std::vector<double> finest(levelOf.begin(), levelOf.end());
    parallel.Max(finest.data(), finest.size());
    std::vector<char> mine(levelOf.size(), 0); // this rank holds the winning level there
    std::vector<double> hits(levelOf.size(), 0.0);
    for (std::size_t i = 0; i < finest.size(); ++i)
    {
      mine[i] = levelOf[i] >= 0 && levelOf[i] == static_cast<int>(finest[i]) ? 1 : 0;
      hits[i] = mine[i];
      levelOf[i] = static_cast<int>(finest[i]);
    }
    parallel.Sum(hits.data(), hits.size());
    for (std::size_t k = 0; k < names.size(); ++k)
    {
      components[k] = static_cast<int>(parallel.Max(double(components[k])));
      fromCells[k] = static_cast<int>(parallel.Max(double(fromCells[k])));
      if (components[k] == 0)
      {
        continue;
      }
      const int nc = components[k];
      std::vector<double> sum(static_cast<std::size_t>(count) * nc, 0.0);
      if (!values[k].empty())
      {
        for (std::size_t i = 0; i < sum.size(); ++i)
        {
          sum[i] = mine[i / nc] ? values[k][i] : 0.0;
        }
      }
      parallel.Sum(sum.data(), sum.size());
      values[k].assign(sum.size(), 0.0f);
      for (std::size_t i = 0; i < sum.size(); ++i)
      {
        const double hh = hits[i / nc];
        values[k][i] = hh > 0.0 ? static_cast<float>(sum[i] / hh) : 0.0f;
      }
    }
  }

  r.Valid.assign(static_cast<std::size_t>(count), 0);
  std::vector<std::int64_t> perLevel(static_cast<std::size_t>(std::max(levels, 1)), 0);
  for (std::int64_t i = 0; i < count; ++i)
  {
    r.Valid[i] = levelOf[i] >= 0 ? 1 : 0;
    if (levelOf[i] >= 0 && levelOf[i] < static_cast<int>(perLevel.size()))
    {
      ++perLevel[levelOf[i]];
    }
  }
  std::vector<std::string> asCells;
  for (std::size_t k = 0; k < names.size(); ++k)
  {
    if (components[k] != 0 && fromCells[k])
    {
      asCells.push_back(names[k]);
    }
  }
  std::ostringstream m;
  m << "RefractiveIndex: AMR input (" << levels << " level" << (levels == 1 ? "" : "s")
    << "): each grid point sampled from the finest level covering it (points per level:";
  for (std::size_t l = 0; l < perLevel.size(); ++l)
  {
    m << (l ? ", " : " ") << "L" << l << " " << perLevel[l];
  }
  m << ").";
  if (!asCells.empty())
  {
    m << " Cell data (";
    for (std::size_t i = 0; i < asCells.size(); ++i)
    {
      m << (i ? ", " : "") << asCells[i];
    }
    m << ") sampled as cells: trilinear between each box's cell centres, not converted to points.";
  }
  r.Notes.push_back(m.str());
  // levels the metadata lists but no rank holds (a reader's MaxLevel)
  if (parallel.Size() > 1 && !loaded.empty())
  {
    std::vector<double> any(loaded.begin(), loaded.end());
    parallel.Max(any.data(), any.size());
    for (std::size_t l = 0; l < any.size(); ++l)
    {
      loaded[l] = any[l] > 0.5 ? 1 : 0;
    }
  }
  int unloaded = 0;
  for (int l = 0; l < levels; ++l)
  {
    unloaded += loaded[l] ? 0 : 1;
  }
  if (unloaded > 0)
  {
    std::ostringstream u;
    u << "RefractiveIndex: the AMR input lists " << levels << " levels but only "
      << (levels - unloaded)
      << " hold data: the finer ones were not loaded (an AMR reader loads the levels up to its "
         "MaxLevel, the Level property of ParaView's AMR readers: raise it to sample them).";
    r.Notes.push_back(u.str());
  }
  return r;
}
} // namespace schlieren
