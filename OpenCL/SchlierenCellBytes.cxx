// SPDX-License-Identifier: BSD-3-Clause
// The byte per cell the kernels read: octree levels, smoothness bits, solid and near bits.
#include "SchlierenEngineInternal.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace schlieren
{

// The byte per grid point that the kernels read (SCH_OCTREE_BITS, SCH_NEAR_BIT, SCH_SOLID_BIT):
// with a body, the solid bit; the near bit where a solid point lies within `reach` (world units:
// the longest step) of the cell, so that steps there are cut to a cell; and the volume's levels
// lowered until no block (with its one-point halo) holds a solid point, so that no skip crosses a
// body.
std::vector<unsigned char> MakeCellBytes(const Volume& v, double reach)
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
std::shared_ptr<const std::vector<unsigned char>> CellBytesOf(const Volume& v, double reach)
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

} // namespace schlieren
