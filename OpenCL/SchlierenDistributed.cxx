// SPDX-License-Identifier: BSD-3-Clause
// Distributed tracing: pieces with ghost points, rays handed from rank to rank (see the header).
#include "SchlierenDistributed.h"

#include "SchlierenEngineInternal.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>
#include <thread>

namespace schlieren
{

namespace
{

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/** Everything a ray carries from rank to rank: which ray (into the caller's film points, or the
 * pixel of a pass), where it started, its march; the devices read the same layout. */
using RayState = sch_piece_ray;

/** A finished ray's record and which ray it is. */
struct Finished
{
  std::uint32_t Index;
  float Rec[SCH_RECORD];
};

template <typename T>
void Append(std::vector<char>& bytes, const T& value)
{
  const std::size_t at = bytes.size();
  bytes.resize(at + sizeof(T));
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

/** What rank r sent (`what`) that cannot be, `why`: a broken transport (what arrives from the
 * other ranks is checked before it is used: sizes, counts, boxes, indices, finite numbers). */
[[noreturn]] void Impossible(int r, const std::string& what, const std::string& why)
{
  throw Error("Distributed tracing: rank " + std::to_string(r) + " sent " + what +
    " that cannot be: " + why + " (the ranks' messages were changed on the way: a broken transport).");
}

template <typename T>
std::vector<T> Unpack(const std::vector<char>& bytes, int from, const char* what)
{
  if (bytes.size() % sizeof(T))
    Impossible(from, what, std::to_string(bytes.size()) + " bytes, not a whole number of " +
      std::to_string(sizeof(T)) + "-byte entries");
  std::vector<T> out(bytes.size() / sizeof(T));
  if (!out.empty())
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

bool Empty(const int box[6])
{
  return box[1] < box[0] || box[3] < box[2] || box[5] < box[4];
}

/** The intersection of two inclusive point boxes. */
void Intersect(const int a[6], const int b[6], int out[6])
{
  for (int d = 0; d < 3; ++d)
  {
    out[2 * d] = std::max(a[2 * d], b[2 * d]);
    out[2 * d + 1] = std::min(a[2 * d + 1], b[2 * d + 1]);
  }
}

std::size_t BoxPoints(const int box[6])
{
  if (Empty(box))
    return 0;
  return static_cast<std::size_t>(box[1] - box[0] + 1) * (box[3] - box[2] + 1) *
    (box[5] - box[4] + 1);
}

std::string BoxText(const int b[6])
{
  std::ostringstream s;
  s << "[" << b[0] << ", " << b[1] << "] x [" << b[2] << ", " << b[3] << "] x [" << b[4] << ", "
    << b[5] << "]";
  return s.str();
}

/** The point box rank r sent (`what`) at the start of `m`, checked: `m` holds it (and `rest`
 * bytes more where rest >= 0) and it is empty or inside `within`. */
std::array<int, 6> BoxFrom(const std::vector<char>& m, int r, const char* what, const int within[6],
  long long rest = 0)
{
  std::array<int, 6> b{};
  if (m.size() < sizeof(b) || (rest >= 0 && m.size() != sizeof(b) + static_cast<std::size_t>(rest)))
    Impossible(r, what, std::to_string(m.size()) + " bytes where " +
      (rest >= 0 ? std::to_string(sizeof(b) + rest) : "at least " + std::to_string(sizeof(b))) +
      " are expected");
  std::memcpy(b.data(), m.data(), sizeof(b));
  if (!Empty(b.data()))
    for (int d = 0; d < 3; ++d)
      if (b[2 * d] < within[2 * d] || b[2 * d + 1] > within[2 * d + 1])
        Impossible(r, what, "the box " + BoxText(b.data()) + " leaves " + BoxText(within));
  return b;
}

/**
 * The values (T per point, x fastest) of the box `held` from the ranks whose pieces (`e` this
 * rank's, of `values`) have them: one all-to-all. heldAll: every rank's held box. Collective.
 * Returns false where some held point came from no rank.
 */
template <typename T>
bool HeldValues(const int e[6], const T* values, const int held[6],
  const std::vector<std::array<int, 6>>& heldAll, int me, Parallel& parallel, std::vector<T>& out)
{
  const int ranks = parallel.Size();
  std::vector<std::vector<char>> send(ranks);
  const int ex = e[1] - e[0] + 1, ey = e[3] - e[2] + 1;
  for (int r = 0; r < ranks; ++r)
  {
    int part[6];
    // this rank's own points are copied in place below, not through a message
    if (r == me || Empty(e) || Empty(heldAll[r].data()))
      continue;
    Intersect(e, heldAll[r].data(), part);
    if (Empty(part))
      continue;
    // the box, then its values in x-fastest order
    for (int k = 0; k < 6; ++k)
      Append(send[r], part[k]);
    for (int z = part[4]; z <= part[5]; ++z)
      for (int y = part[2]; y <= part[3]; ++y)
      {
        const T* row = values + (static_cast<std::size_t>(z - e[4]) * ey + (y - e[2])) * ex + (part[0] - e[0]);
        const std::size_t at = send[r].size();
        send[r].resize(at + sizeof(T) * (part[1] - part[0] + 1));
        std::memcpy(send[r].data() + at, row, sizeof(T) * (part[1] - part[0] + 1));
      }
  }
  std::vector<std::vector<char>> in = parallel.Exchange(send);
  send.clear();
  out.assign(BoxPoints(held), T());
  std::vector<unsigned char> have(out.size(), 0);
  const int hx = held[1] - held[0] + 1, hy = held[3] - held[2] + 1;
  {
    int part[6];
    Intersect(e, held, part);
    if (!Empty(e) && !Empty(part))
      for (int z = part[4]; z <= part[5]; ++z)
        for (int y = part[2]; y <= part[3]; ++y)
        {
          const std::size_t at =
            (static_cast<std::size_t>(z - held[4]) * hy + (y - held[2])) * hx + (part[0] - held[0]);
          const T* row = values + (static_cast<std::size_t>(z - e[4]) * ey + (y - e[2])) * ex + (part[0] - e[0]);
          std::memcpy(out.data() + at, row, sizeof(T) * (part[1] - part[0] + 1));
          std::memset(have.data() + at, 1, part[1] - part[0] + 1);
        }
  }
  for (int r = 0; r < ranks; ++r)
  {
    if (in[r].empty())
      continue;
    const std::array<int, 6> box = BoxFrom(in[r], r, "the points of this rank's ghosts", held, -1);
    const int* part = box.data();
    if (Empty(part) || in[r].size() != 6 * sizeof(int) + BoxPoints(part) * sizeof(T))
      Impossible(r, "the points of this rank's ghosts", std::to_string(in[r].size()) +
        " bytes for the box " + BoxText(part));
    const char* v = in[r].data() + 6 * sizeof(int);
    const int len = part[1] - part[0] + 1;
    for (int z = part[4]; z <= part[5]; ++z)
      for (int y = part[2]; y <= part[3]; ++y, v += sizeof(T) * len)
      {
        const std::size_t at =
          (static_cast<std::size_t>(z - held[4]) * hy + (y - held[2])) * hx + (part[0] - held[0]);
        std::memcpy(out.data() + at, v, sizeof(T) * len);
        std::memset(have.data() + at, 1, len);
      }
    std::vector<char>().swap(in[r]);
  }
  return std::find(have.begin(), have.end(), 0) == have.end();
}

// The longest base step (voxels of the smallest spacing) a trace with settings s takes: Auto's
// candidates reach 8 voxels trilinear and 64 tricubic on the pieces (AutoPiecesReach: the whole
// volume's Auto goes on to its diagonal since issue 50; the pieces' ghost layers stay those of
// 8 and 64 voxels); the step-doubling estimate twice the step.
double LongestStep(const TraceSettings& s)
{
  const bool cubic = s.Recon != Reconstruction::Trilinear;
  const double step =
    s.Method == Integrator::Auto ? std::max(s.StepSize, AutoPiecesReach(cubic)) : s.StepSize;
  return step * (s.EstimateError ? 2.0 : 1.0);
}
} // namespace

int SmoothLevelsFor(const TraceSettings& s)
{
  if (s.Recon == Reconstruction::Trilinear)
    return 0;
  // level q lets a step of (2^q - 1) cells (sch_walk_step): a level whose room is a cell longer
  // than the longest base step leaves every step at the base step, as every higher level does
  const double step = LongestStep(s);
  int q = 1;
  while (q < 7 && double((1 << q) - 1) < step + 1.0)
    ++q;
  return q;
}

int GhostPointsFor(const TraceSettings& s, int octreeLevel)
{
  // a step of StepSize voxels of the smallest spacing moves at most that many cells along any
  // axis; the midpoint and Runge-Kutta stages stay within a step of its start. An octree skip
  // ends a hair past the face of its block: at most a block and a cell along any axis. Then the
  // cell of a trilinear sample (1), the gradient's central difference (1) and one to spare.
  const int block = (s.UseOctree && octreeLevel > 0) ? (1 << octreeLevel) : 0;
  const int reach =
    std::max(static_cast<int>(std::ceil(LongestStep(s))), block ? block + 1 : 0);
  // an owned cell's level: its block and the block's one-point halo
  int ghost = std::max(reach + 3, block ? block + 2 : 0);
  if (s.Recon != Reconstruction::Trilinear)
  {
    // tricubic where a step may end: the cell's 4 x 4 x 4 points (-1 .. 2), their fourth-order
    // gradients (+-2) and the smoothness test of those points (+-2), and one to spare; an owned
    // cell's smoothness level q: the cells within 2^q cells (points -(2^q + 1) .. 2^q + 2) free of
    // jumps by the five-point test (+-2), and one to spare
    ghost = std::max(ghost, reach + 7);
    ghost = std::max(ghost, (1 << SmoothLevelsFor(s)) + 5);
  }
  return ghost;
}

// ------------------------------------------------------------------ the distributed volume

DistributedVolume::DistributedVolume(const Piece& piece, int ghostPoints, Parallel& parallel)
  : DistributedVolume(piece, ghostPoints, parallel, -1.0, 0)
{
}

DistributedVolume::DistributedVolume(const Piece& piece, int ghostPoints, Parallel& parallel,
  double octreeTolerance, int octreeMaxLevel, int smoothLevels)
{
  std::copy(piece.WholeDimensions, piece.WholeDimensions + 3, this->WholeDimensions);
  std::copy(piece.Origin, piece.Origin + 3, this->Origin);
  std::copy(piece.Spacing, piece.Spacing + 3, this->Spacing);
  this->Ghost = std::max(ghostPoints, 2);
  const int ranks = parallel.Size(), me = parallel.Rank();

  // 1. Every rank's extent, and the cells it owns.
  std::string failure;
  const int* e = piece.Extent;
  if (!Empty(e))
  {
    for (int d = 0; d < 3 && failure.empty(); ++d)
      if (e[2 * d] < 0 || e[2 * d + 1] >= this->WholeDimensions[d])
        failure = "this rank's piece " + BoxText(e) + " lies outside the whole grid";
    if (failure.empty() && !piece.NMinus1)
      failure = "this rank's piece has no n - 1 values";
  }
  failure = parallel.Failure(failure);
  if (!failure.empty())
    throw Error("Distributed volume: " + failure + ".");
  std::vector<char> mine;
  for (int k = 0; k < 6; ++k)
    Append(mine, e[k]);
  std::vector<std::vector<char>> all = parallel.AllGather(mine);
  std::vector<std::array<int, 6>> extents(ranks);
  const int wholeBox[6] = { 0, this->WholeDimensions[0] - 1, 0, this->WholeDimensions[1] - 1, 0,
    this->WholeDimensions[2] - 1 };
  for (int r = 0; r < ranks; ++r)
    extents[r] = BoxFrom(all[r], r, "its piece's extent", wholeBox);
  this->AllOwned.assign(ranks, { 0, 0, 0, 0, 0, 0 });
  double ownedCells = 0;
  for (int r = 0; r < ranks; ++r)
  {
    if (Empty(extents[r].data()))
      continue;
    for (int d = 0; d < 3; ++d)
    {
      this->AllOwned[r][2 * d] = extents[r][2 * d];
      this->AllOwned[r][2 * d + 1] = extents[r][2 * d + 1]; // cells lo .. hi-1: [lo, hi)
    }
    double c = 1;
    for (int d = 0; d < 3; ++d)
      c *= std::max(0, this->AllOwned[r][2 * d + 1] - this->AllOwned[r][2 * d]);
    ownedCells += c;
  }
  std::copy(this->AllOwned[me].begin(), this->AllOwned[me].end(), this->Owned);
  // the pieces must share out the cells: no two own one, none is left over
  double wholeCells = 1;
  for (int d = 0; d < 3; ++d)
    wholeCells *= std::max(0, this->WholeDimensions[d] - 1);
  for (int r = 0; r < ranks && failure.empty(); ++r)
    for (int q = r + 1; q < ranks && failure.empty(); ++q)
    {
      bool overlap = true;
      for (int d = 0; d < 3; ++d)
        overlap = overlap &&
          std::max(this->AllOwned[r][2 * d], this->AllOwned[q][2 * d]) <
            std::min(this->AllOwned[r][2 * d + 1], this->AllOwned[q][2 * d + 1]);
      if (overlap)
        failure = "the pieces of ranks " + std::to_string(r) + " and " + std::to_string(q) +
          " overlap in cells (" + BoxText(extents[r].data()) + ", " + BoxText(extents[q].data()) +
          "): pieces must share only their face points";
    }
  if (failure.empty() && ownedCells != wholeCells)
  {
    // a rank whose piece is empty where the grid needs it: most often its upstream failed there
    // without saying so to the pipeline (a Python source that raised); name it
    std::string empty;
    for (int r = 0; r < ranks; ++r)
      if (Empty(extents[r].data()))
        empty += (empty.empty() ? "" : ", ") + std::to_string(r);
    failure = "the pieces leave cells of the whole grid uncovered: pieces must tile it";
    if (!empty.empty())
      failure += " (empty on rank" + std::string(empty.find(',') != std::string::npos ? "s " : " ") + empty +
        ": if a filter upstream reported an error there, that is the cause)";
  }
  // every rank found the same from the same extents
  if (!failure.empty())
    throw Error("Distributed volume: " + failure + ".");

  // 2. The points held: the owned cells' points and the ghosts around them, within the grid.
  int held[6] = { 0, -1, 0, -1, 0, -1 };
  if (!Empty(e))
    for (int d = 0; d < 3; ++d)
    {
      held[2 * d] = std::max(0, this->Owned[2 * d] - this->Ghost);
      held[2 * d + 1] = std::min(this->WholeDimensions[d] - 1, this->Owned[2 * d + 1] + this->Ghost);
    }
  for (int d = 0; d < 3; ++d)
  {
    this->HeldLo[d] = held[2 * d];
    this->HeldDims[d] = std::max(0, held[2 * d + 1] - held[2 * d] + 1);
  }

  // What this rank will hold at the peak of building its share: the packed field (16 bytes a
  // point), n - 1 of the held points (4) and their bookkeeping (1), and the octree levels (1).
  {
    std::string tooBig;
    try
    {
      std::ostringstream what;
      what << "This rank's share of the volume (" << this->HeldDims[0] << " x " << this->HeldDims[1]
           << " x " << this->HeldDims[2] << " points with its ghosts)";
      // (Reconstruction Cubic: the smoothness, a byte, and its working bytes, 5 more)
      CheckHostMemory((smoothLevels > 0 ? 28.0 : 22.0) * BoxPoints(held), what.str(),
        "Run on more ranks (or nodes), or resample the data to fewer points.");
    }
    catch (const Error& err)
    {
      tooBig = err.what();
    }
    tooBig = parallel.Failure(tooBig);
    if (!tooBig.empty())
      throw Error("Distributed volume: " + tooBig);
  }

  // 3. The held points from whichever ranks have them (its own piece included): n - 1, and the
  // solid points where any rank's piece has a body.
  std::vector<char> heldBox;
  for (int k = 0; k < 6; ++k)
    Append(heldBox, held[k]);
  all = parallel.AllGather(heldBox);
  std::vector<std::array<int, 6>> heldAll(ranks);
  for (int r = 0; r < ranks; ++r)
    heldAll[r] = BoxFrom(all[r], r, "the box of points it holds", wholeBox);
  all.clear();
  const std::size_t heldPoints = BoxPoints(held);
  std::vector<float> n1;
  if (!HeldValues(e, piece.NMinus1, held, heldAll, me, parallel, n1))
    failure = "no rank holds some of the points this rank needs: pieces must tile the grid";
  const bool body = parallel.Max(piece.Solid && !Empty(e) ? 1.0 : 0.0) > 0;
  if (body)
  {
    // a piece without solid points of its own sends zeros
    std::vector<unsigned char> none;
    if (!piece.Solid)
      none.assign(BoxPoints(e), 0);
    HeldValues(e, piece.Solid ? piece.Solid : none.data(), held, heldAll, me, parallel, this->Solid);
    for (unsigned char& c : this->Solid)
      c = c ? 1 : 0;
    this->HasSolid = true;
  }

  // 4. Validated; the index range of the whole grid (for the step-quality checks and the
  // smoothness test's floor), from the held points, which together are the whole grid's.
  double lo = 1e300, hi = -1e300;
  if (failure.empty() && heldPoints)
  {
    float heldLo, heldHi;
    failure = ScanIndex(n1.data(), heldPoints, heldLo, heldHi);
    lo = heldLo;
    hi = heldHi;
  }
  failure = parallel.Failure(failure);
  if (!failure.empty())
    throw Error("Distributed volume: " + failure);
  {
    lo = parallel.Min(lo);
    hi = parallel.Max(hi);
    this->RangeLo = static_cast<float>(lo);
    this->RangeHi = static_cast<float>(hi);
  }

  // 5. Packed as one process packs the whole: the gradient is wrong only on the outermost ghost
  // layer (one-sided there), which no sample of an owned cell's step reads. Reconstruction Cubic:
  // the fourth-order gradient and the smoothness of every held point, right wherever a step from
  // an owned cell samples and, for the smoothness levels, on the owned cells (GhostPointsFor).
  std::vector<unsigned char> smooth;
  if (heldPoints)
  {
    try
    {
      this->Packed.resize(4 * heldPoints);
      if (smoothLevels > 0)
      {
        this->HighOrder = true;
        this->SmoothLevelMax = std::min(smoothLevels, 7);
        smooth.resize(heldPoints);
        PackFieldHighOrderOf(this->HeldDims, this->Spacing, n1.data(), this->Packed.data(),
          smooth.data(), DefaultSmoothnessThreshold, this->RangeLo, this->RangeHi,
          this->SmoothLevelMax);
      }
      else
      {
        CheckGrid(this->HeldDims, this->Spacing); // (validated above)
        PackFieldOf(this->HeldDims, this->Spacing, n1.data(), this->Packed.data());
      }
    }
    catch (const Error& err)
    {
      failure = err.what();
    }
  }
  // 6. The octree levels of the held cells, on the whole grid's blocks.
  if (failure.empty() && heldPoints && octreeTolerance >= 0 && octreeMaxLevel > 0)
  {
    this->LevelMax = std::min(octreeMaxLevel, 10);
    this->LevelTolerance = octreeTolerance;
    if ((1 << this->LevelMax) + 2 > this->Ghost)
      failure = "octree levels up to " + std::to_string(this->LevelMax) + " need " +
        std::to_string((1 << this->LevelMax) + 2) + " ghost points, not " +
        std::to_string(this->Ghost);
    else
    {
      try
      {
        this->Levels.resize(heldPoints);
        ComputeOctreeLevelsOfPiece(this->HeldDims, this->HeldLo, this->WholeDimensions, n1.data(),
          octreeTolerance, this->Levels.data(), this->LevelMax);
        this->Octree = true;
      }
      catch (const Error& err)
      {
        failure = err.what();
      }
    }
  }
  // the kernels' cell bytes: the octree level in the low bits, the smoothness above (as
  // TraceVolume merges them for one process)
  if (failure.empty() && this->HighOrder)
  {
    if (this->Levels.empty())
      this->Levels.swap(smooth);
    else
      for (std::size_t i = 0; i < heldPoints; ++i)
        this->Levels[i] = static_cast<unsigned char>(
          (this->Levels[i] & SCH_OCTREE_BITS) | (smooth[i] & ~SCH_OCTREE_BITS));
  }
  failure = parallel.Failure(failure);
  if (!failure.empty())
    throw Error("Distributed volume: " + failure);
}

int OctreeLevelReached(const Piece& piece, double tol, int maxLevel, Parallel& parallel)
{
  maxLevel = std::max(0, std::min(maxLevel, 10));
  int reached = std::min(maxLevel, DistributedOctreeMaxLevel);
  const int* e = piece.Extent;
  const bool empty = Empty(e) || !piece.NMinus1;
  const int ex = e[1] - e[0] + 1, ey = e[3] - e[2] + 1;
  for (int L = DistributedOctreeMaxLevel + 1; L <= maxLevel; ++L)
  {
    // the whole grid's blocks of 2^L cells, aligned on its index 0 (as ComputeOctreeLevels); per
    // block -min and max of its points [b B - 1, b B + B + 1] that this piece holds
    const int B = 1 << L;
    int nb[3];
    for (int a = 0; a < 3; ++a)
      nb[a] = std::max(1, (piece.WholeDimensions[a] - 2) / B + 1);
    const std::size_t blocks = static_cast<std::size_t>(nb[0]) * nb[1] * nb[2];
    std::vector<double> v(2 * blocks, -1e300);
    if (!empty)
    {
      int lo[3], hi[3];
      for (int a = 0; a < 3; ++a)
      {
        // the blocks whose windows meet this piece's points
        lo[a] = std::max(0, (e[2 * a] - 1) / B - 1);
        hi[a] = std::min(nb[a] - 1, (e[2 * a + 1] + 1) / B);
      }
      for (int bz = lo[2]; bz <= hi[2]; ++bz)
        for (int by = lo[1]; by <= hi[1]; ++by)
          for (int bx = lo[0]; bx <= hi[0]; ++bx)
          {
            const int b[3] = { bx, by, bz };
            int p0[3], p1[3];
            bool meets = true;
            for (int a = 0; a < 3; ++a)
            {
              p0[a] = std::max({ 0, b[a] * B - 1, e[2 * a] });
              p1[a] = std::min({ piece.WholeDimensions[a] - 1, b[a] * B + B + 1, e[2 * a + 1] });
              meets = meets && p0[a] <= p1[a];
            }
            if (!meets)
              continue;
            float mn = 1e30f, mx = -1e30f;
            for (int z = p0[2]; z <= p1[2]; ++z)
              for (int y = p0[1]; y <= p1[1]; ++y)
              {
                const float* row =
                  piece.NMinus1 + (static_cast<std::size_t>(z - e[4]) * ey + (y - e[2])) * ex;
                for (int x = p0[0]; x <= p1[0]; ++x)
                {
                  mn = std::min(mn, row[x - e[0]]);
                  mx = std::max(mx, row[x - e[0]]);
                }
              }
            const std::size_t o = (static_cast<std::size_t>(bz) * nb[1] + by) * nb[0] + bx;
            v[2 * o] = std::max(v[2 * o], -double(mn));
            v[2 * o + 1] = std::max(v[2 * o + 1], double(mx));
          }
    }
    parallel.Max(v.data(), v.size());
    // ComputeOctreeLevels' test on the floats: exact in doubles
    bool any = false;
    for (std::size_t o = 0; o < blocks && !any; ++o)
      any = v[2 * o + 1] - (-v[2 * o]) <= tol;
    if (!any)
      break;
    reached = L;
  }
  return reached;
}

Volume DistributedVolume::Whole() const
{
  Volume v;
  std::copy(this->WholeDimensions, this->WholeDimensions + 3, v.Dimensions);
  std::copy(this->Origin, this->Origin + 3, v.Origin);
  std::copy(this->Spacing, this->Spacing + 3, v.Spacing);
  return v;
}

std::shared_ptr<const std::vector<unsigned char>> DistributedVolume::CellBytes(double reach) const
{
  if (!this->HasSolid)
    return nullptr;
  if (this->KeptBytes && this->KeptReach == reach)
    return this->KeptBytes;
  // the held box as a volume of its own: MakeCellBytes' windows (a step's reach, an octree block
  // and its halo) stop at its faces, which are the whole grid's or at least that far from every
  // owned cell (GhostPointsFor)
  Volume v = this->Held();
  v.Levels = this->Octree ? this->Levels.data() : nullptr;
  v.Solid = this->Solid.empty() ? nullptr : this->Solid.data();
  this->KeptBytes.reset();
  auto bytes = std::make_shared<std::vector<unsigned char>>();
  if (v.Solid && v.NumberOfPoints() > 0)
    *bytes = MakeCellBytes(v, reach);
  this->KeptBytes = bytes;
  this->KeptReach = reach;
  return this->KeptBytes;
}

Volume DistributedVolume::Held() const
{
  Volume v;
  std::copy(this->HeldDims, this->HeldDims + 3, v.Dimensions);
  for (int d = 0; d < 3; ++d)
    v.Origin[d] = this->Origin[d] + this->HeldLo[d] * this->Spacing[d];
  std::copy(this->Spacing, this->Spacing + 3, v.Spacing);
  v.Field = this->Packed.empty() ? nullptr : this->Packed.data();
  v.Levels = this->Octree ? this->Levels.data() : nullptr;
  // with Reconstruction Cubic the cell bytes (Levels) carry the smoothness too
  v.Smooth = this->HighOrder ? this->Levels.data() : nullptr;
  v.LevelTolerance = this->LevelTolerance;
  v.Stamp = this->Stamp;
  return v;
}

bool DistributedVolume::OwnsCell(int i, int j, int k) const
{
  return i >= this->Owned[0] && i < this->Owned[1] && j >= this->Owned[2] && j < this->Owned[3] &&
    k >= this->Owned[4] && k < this->Owned[5];
}

int DistributedVolume::OwnerOfCell(int i, int j, int k) const
{
  for (std::size_t r = 0; r < this->AllOwned.size(); ++r)
  {
    const std::array<int, 6>& o = this->AllOwned[r];
    if (i >= o[0] && i < o[1] && j >= o[2] && j < o[3] && k >= o[4] && k < o[5])
      return static_cast<int>(r);
  }
  return 0; // unreachable: the pieces tile the cells (checked on construction)
}

// ------------------------------------------------------------------ tracing

namespace
{

/** The parameters of a trace on this rank's held points: the whole grid's, addressing the held. */
sch_params PieceParams(const DistributedVolume& dv, const TraceSettings& s, const FilmGeometry& film)
{
  if (s.Method == Integrator::Auto || s.Recon == Reconstruction::Auto)
    throw Error("Distributed tracing: resolve Auto first (ResolveAuto).");
  if (s.Recon == Reconstruction::Cubic && !dv.HighOrder)
    throw Error("Distributed tracing: Reconstruction Cubic needs the pieces packed for it "
                "(DistributedVolume's smoothLevels).");
  if (s.RankCount != 1 || s.RankIndex != 0)
    throw Error("Distributed tracing: RankIndex/RankCount must be 0/1 (every rank traces its piece).");
  const int need = GhostPointsFor(s, dv.Octree ? dv.LevelMax : 0);
  if (dv.Ghost < need)
    throw Error("Distributed tracing: StepSize " + std::to_string(s.StepSize) + " needs " +
      std::to_string(need) + " ghost points; the volume holds " + std::to_string(dv.Ghost) + ".");
  if (s.Recon == Reconstruction::Cubic && dv.SmoothLevelMax < SmoothLevelsFor(s))
    throw Error("Distributed tracing: StepSize " + std::to_string(s.StepSize) +
      " with Reconstruction Cubic needs smoothness levels up to " +
      std::to_string(SmoothLevelsFor(s)) + "; the pieces hold " + std::to_string(dv.SmoothLevelMax) + ".");
  Volume whole = dv.Whole();
  whole.LevelTolerance = dv.LevelTolerance;
  // (MakeParams checks that Cubic has the smoothness: the pieces' cell bytes)
  whole.Smooth = dv.HighOrder ? dv.Levels.data() : nullptr;
  // a body: its bits in the cell bytes (MakeParams then traces trilinear, as one process does)
  static const unsigned char aBody = 1;
  whole.Solid = dv.HasSolid ? &aBody : nullptr;
  sch_params P = MakeParams(whole, s, film);
  P.useLevels = (s.UseOctree && dv.Octree) ? 1 : 0;
  P.nx = dv.HeldDims[0];
  P.ny = dv.HeldDims[1];
  P.nz = dv.HeldDims[2];
  P.ox = dv.HeldLo[0];
  P.oy = dv.HeldLo[1];
  P.oz = dv.HeldLo[2];
  SetFieldLayout(P, false); // a piece's field is packed linear (DistributedVolume::Packed)
  P.featureTol = FeatureTolerance(dv.RangeLo, dv.RangeHi, whole.LevelTolerance);
  P.ownX0 = dv.Owned[0];
  P.ownX1 = dv.Owned[1];
  P.ownY0 = dv.Owned[2];
  P.ownY1 = dv.Owned[3];
  P.ownZ0 = dv.Owned[4];
  P.ownZ1 = dv.Owned[5];
  return P;
}

/** The cell of x (relative to the centre) in the whole grid, as the sampler finds it. */
void CellOf(const sch_params& P, sch_v3 x, int c[3])
{
  sch_grid_coord(x.x, P.isx, P.gx0, P.gxMax, &c[0]);
  sch_grid_coord(x.y, P.isy, P.gy0, P.gyMax, &c[1]);
  sch_grid_coord(x.z, P.isz, P.gz0, P.gzMax, &c[2]);
}

/** Advances the rays in `live` until each has left the volume (finished) or this rank's cells
 * (handed on, by owner). Rays are split over threads; each ray's steps are its own. */
void Advance(const DistributedVolume& dv, const sch_params& P, std::vector<RayState>& live,
  std::vector<Finished>& finished, std::vector<std::vector<RayState>>& handOn, int threadCount,
  OpenCLTracer* cl)
{
  if (cl)
  {
    // on the device: every ray until it leaves the volume or this rank's cells
    std::vector<float> rec(live.size() * SCH_RECORD);
    std::vector<int> status(live.size());
    WalkPiecesOpenCL(*cl, P, live.data(), live.size(), rec.data(), status.data());
    for (std::size_t r = 0; r < live.size(); ++r)
    {
      if (status[r] == 1)
      {
        int c[3];
        CellOf(P, live[r].w.x, c);
        handOn[dv.OwnerOfCell(c[0], c[1], c[2])].push_back(live[r]);
        continue;
      }
      Finished f;
      f.Index = live[r].index;
      std::memcpy(f.Rec, rec.data() + r * SCH_RECORD, sizeof(f.Rec));
      finished.push_back(f);
    }
    live.clear();
    return;
  }
  const float* field = dv.Packed.data();
  const unsigned char* levels = dv.TraceBytes();
  const unsigned nt = std::max(1u, std::min<unsigned>(CpuThreads(threadCount),
                                     static_cast<unsigned>((live.size() + 63) / 64)));
  std::vector<std::vector<Finished>> fin(nt);
  std::vector<std::vector<std::vector<RayState>>> out(nt, std::vector<std::vector<RayState>>(handOn.size()));
  auto work = [&](unsigned t) {
    const sch_params Pw = P;
    for (std::size_t r = t; r < live.size(); r += nt)
    {
      RayState st = live[r];
      bool left = false;
      if (Pw.useLevels || Pw.recon == SCH_CUBIC || Pw.useSolid)
      {
        // the byte of the cell it is in, as its owner knows it (a sender's ghost cell may differ:
        // its octree block, its smoothness window or a body's reach lies past the sender's ghosts)
        long cell;
        sch_sample_cell(field, &Pw, st.w.x, &cell);
        if (Pw.useLevels || Pw.recon == SCH_CUBIC)
          st.w.level = levels[cell];
        if (Pw.useSolid)
          st.w.nearSolid = levels[cell] & SCH_NEAR_BIT;
      }
      while (sch_walk_step(field, levels, &Pw, &st.w))
      {
        int c[3];
        CellOf(Pw, st.w.x, c);
        if (!dv.OwnsCell(c[0], c[1], c[2]))
        {
          out[t][dv.OwnerOfCell(c[0], c[1], c[2])].push_back(st);
          left = true;
          break;
        }
      }
      if (left)
        continue;
      sch_ray R;
      sch_walk_end(field, &Pw, &st.w, &R);
      Finished f;
      f.Index = st.index;
      sch_record(field, levels, &Pw, st.a, st.b, st.o, st.entry, st.s1, &R, f.Rec);
      fin[t].push_back(f);
    }
  };
  RunOnThreads(nt, work);
  for (unsigned t = 0; t < nt; ++t)
  {
    finished.insert(finished.end(), fin[t].begin(), fin[t].end());
    for (std::size_t q = 0; q < handOn.size(); ++q)
      handOn[q].insert(handOn[q].end(), out[t][q].begin(), out[t][q].end());
  }
  live.clear();
}

/**
 * A run of consecutive steps of one line-of-sight ray in one rank's cells: its partial integrals.
 * Along the unbent line w is a plain sum of the pieces' parts, and the sideways displacement
 * (the sum of w ds / n) is the run's own part plus the w of the runs before it times the run's
 * sum of ds / n, so the runs add up in the order of their first step.
 */
struct StraightRun
{
  std::uint32_t Index;  // the ray
  std::uint32_t First;  // its first step
  float W[3];           // sum of grad n ds over the run
  float Dev[3];         // sum of w ds / n with w counted from the run's start
  float InvN;           // sum of ds / n
  float NDs;            // sum of (n - n_entry) ds: the optical path excess
  float Ds;             // sum of ds
  float N1;             // n - 1 at the run's first point (at the entry: the background index)
  float ExitN1;         // n - 1 where the ray left the box (the run that ends there), else 0
  std::uint32_t Last;   // 1: the run ends where the ray leaves the box
  float X[3];           // (Last) where the ray left the box
  std::uint32_t Steps;  // (Last) the ray's steps, as sch_walk_step counts them
};

/** Line of sight without ray passing: every rank walks every ray's positions (the same float
 * arithmetic as sch_walk_step, no sample) and integrates the steps that start in its cells; the
 * runs go to rank 0 (or everyone), which adds them in order and makes the records. */
template <typename PointOf>
std::vector<float> TraceStraightSums(const DistributedVolume& dv, const sch_params& P,
  std::size_t count, PointOf pointOf, Parallel& parallel, bool everywhere, DistributedStats* stats)
{
  const int ranks = parallel.Size(), me = parallel.Rank();
  const float* field = dv.Packed.data();
  Clock::time_point ta = Clock::now();
  const sch_v3 d0 = sch_make(P.dx, P.dy, P.dz);
  std::vector<StraightRun> runs;
  std::vector<float> A(count), B(count), S1(count);
  std::vector<sch_v3> O(count), E(count);
  std::vector<int> hit(count);
  // the index where each ray enters, from the rank that owns that cell, on every rank: the optical
  // path is summed against it step by step, as one process sums it
  std::vector<double> entryN1(count, 0.0);
  for (std::size_t k = 0; k < count; ++k)
  {
    pointOf(k, &A[k], &B[k]);
    S1[k] = 0.0f;
    hit[k] = sch_entry(&P, A[k], B[k], &O[k], &E[k], &S1[k]);
    int c[3];
    CellOf(P, E[k], c);
    if (hit[k] && dv.OwnsCell(c[0], c[1], c[2]))
      entryN1[k] = sch_sample_field(field, &P, E[k]).n1;
  }
  parallel.Sum(entryN1.data(), entryN1.size());
  for (std::size_t k = 0; k < count; ++k)
  {
    if (!hit[k])
      continue;
    const float ne1 = static_cast<float>(entryN1[k]);
    sch_v3 x = E[k];
    float along = 0.0f; // x as sch_walk_step keeps it: E[k] + along d0
    const float base = P.step;
    bool open = false; // a run of this rank is open
    StraightRun run;
    sch_sample smp;
    float invn = 0.0f;
    int it = 0;
    for (;; ++it)
    {
      int c[3];
      CellOf(P, x, c);
      const bool mine = dv.OwnsCell(c[0], c[1], c[2]);
      if (mine)
      {
        smp = sch_sample_field(field, &P, x);
        invn = 1.0f / (1.0f + smp.n1);
        if (!open)
        {
          run = StraightRun();
          run.Index = static_cast<std::uint32_t>(k);
          run.First = static_cast<std::uint32_t>(it);
          run.N1 = smp.n1;
          open = true;
        }
      }
      else if (open)
      {
        runs.push_back(run);
        open = false;
      }
      if (it >= P.maxSteps)
        break;
      // the step of sch_walk_step along the unbent line
      float ds = base;
      const int fit = sch_box_step(&P, x, d0, it, base, &ds);
      if (!fit)
        break;
      if (mine)
      {
        // ddev = w ds / n with the run's own w (the runs before add theirs in the sum)
        for (int a = 0; a < 3; ++a)
          run.Dev[a] += run.W[a] * (ds * invn);
        run.W[0] += smp.gx * ds;
        run.W[1] += smp.gy * ds;
        run.W[2] += smp.gz * ds;
        run.InvN += ds * invn;
        run.NDs += ds * (smp.n1 - ne1);
        run.Ds += ds;
      }
      along += ds;
      x = sch_walk_at(E[k], along, d0, sch_make(0.0f, 0.0f, 0.0f));
      if (fit == 2)
        break;
    }
    // where it left: the owner of that (clamped) cell samples the index there, and says where
    // and after how many steps
    int c[3];
    CellOf(P, x, c);
    if (dv.OwnsCell(c[0], c[1], c[2]))
    {
      if (!open)
      {
        run = StraightRun();
        run.Index = static_cast<std::uint32_t>(k);
        run.First = static_cast<std::uint32_t>(it + 1);
        open = true;
      }
      run.Last = 1;
      run.ExitN1 = sch_sample_field(field, &P, x).n1;
      run.X[0] = x.x;
      run.X[1] = x.y;
      run.X[2] = x.z;
      run.Steps = static_cast<std::uint32_t>(it);
    }
    if (open)
      runs.push_back(run);
  }
  const double tracing = SecondsSince(ta);
  Clock::time_point tb = Clock::now();
  std::vector<char> mine(runs.size() * sizeof(StraightRun));
  if (!runs.empty())
    std::memcpy(mine.data(), runs.data(), mine.size());
  double bytes = 0;
  std::vector<std::vector<char>> got;
  if (everywhere)
  {
    got = parallel.AllGather(mine);
    bytes += mine.size() * (ranks - 1);
  }
  else
  {
    std::vector<std::vector<char>> out(ranks);
    if (me != 0)
      bytes += mine.size();
    out[0] = std::move(mine);
    got = parallel.Exchange(out);
  }
  std::vector<float> records;
  if (everywhere || me == 0)
  {
    std::vector<StraightRun> all;
    for (int from = 0; from < static_cast<int>(got.size()); ++from)
    {
      std::vector<StraightRun> r = Unpack<StraightRun>(got[from], from, "runs of its rays");
      // (numbers that are not finite are the march's to flag, as on one rank)
      for (const StraightRun& u : r)
        if (u.Index >= count || u.Last > 1 || u.Steps > static_cast<std::uint32_t>(P.maxSteps))
          Impossible(from, "a run of a ray",
            "ray " + std::to_string(u.Index) + " of " + std::to_string(count) + ", last " +
              std::to_string(u.Last) + ", steps " + std::to_string(u.Steps) + " of at most " +
              std::to_string(P.maxSteps));
      all.insert(all.end(), r.begin(), r.end());
    }
    std::sort(all.begin(), all.end(), [](const StraightRun& a, const StraightRun& b) {
      return a.Index != b.Index ? a.Index < b.Index : a.First < b.First;
    });
    records.assign(count * SCH_RECORD, 0.0f);
    std::size_t at = 0;
    for (std::size_t k = 0; k < count; ++k)
    {
      sch_ray R;
      if (!hit[k])
        sch_missed(O[k], &R);
      else
      {
        // the runs of ray k, in the order of their first step
        float w[3] = { 0, 0, 0 }, dev[3] = { 0, 0, 0 }, nds = 0, len = 0, ne1 = 0, exitN1 = 0;
        sch_v3 x = E[k];
        std::uint32_t steps = 0;
        bool first = true;
        for (; at < all.size() && all[at].Index == k; ++at)
        {
          const StraightRun& r = all[at];
          if (first)
            ne1 = r.N1;
          first = false;
          for (int a = 0; a < 3; ++a)
          {
            dev[a] += r.Dev[a] + w[a] * r.InvN;
            w[a] += r.W[a];
          }
          nds += r.NDs;
          len += r.Ds;
          if (r.Last)
          {
            exitN1 = r.ExitN1;
            x = sch_make(r.X[0], r.X[1], r.X[2]);
            steps = r.Steps;
          }
        }
        R.x = x;
        R.w = sch_make(w[0], w[1], w[2]);
        R.dev = sch_make(dev[0], dev[1], dev[2]);
        R.ne1 = ne1;
        R.n1 = exitN1;
        R.opl = nds;
        R.path = len;
        R.samples = 1.0f + static_cast<float>(steps);
        R.steps = static_cast<float>(steps);
        R.mismatch = 0.0f;
        R.flags = 0u;
        if (!(sch_isfinite(x.x) && sch_isfinite(x.y) && sch_isfinite(x.z) && sch_isfinite(w[0]) &&
              sch_isfinite(w[1]) && sch_isfinite(w[2])))
          R.flags |= SCH_RAY_NONFINITE;
        if (static_cast<int>(steps) >= P.maxSteps)
          R.flags |= SCH_RAY_MAXSTEPS;
        else if (!(R.flags & SCH_RAY_NONFINITE) && (1.0f + ne1) + sch_dot(d0, R.w) <= 0.0f)
          R.flags |= SCH_RAY_TURNED;
      }
      sch_record(field, nullptr, &P, A[k], B[k], O[k], E[k], S1[k], &R,
        records.data() + k * SCH_RECORD);
    }
  }
  if (stats)
  {
    stats->Rounds += 1;
    stats->BytesExchanged += bytes;
    stats->SecondsTracing += tracing;
    stats->SecondsExchanging += SecondsSince(tb);
  }
  return records;
}

/** Whether a trace with P takes the line-of-sight partial integrals (no ray passing): not with
 * Cubic or a body, whose steps are sized by cell bytes (smoothness, near a body) that only the
 * cell's owner knows. */
bool StraightSums(const sch_params& P)
{
  return P.integrator == SCH_STRAIGHT && !P.useLevels && !P.keepInvariant && !P.estimate &&
    P.recon != SCH_CUBIC && !P.useSolid;
}

/**
 * The records of rays 0 .. count-1 whose film points `pointOf(k, &a, &b)` gives, traced on the
 * pieces (on the device of `cl`, else the CPU); in ray order on rank 0 (and every rank with
 * `everywhere`).
 */
template <typename PointOf>
std::vector<float> TraceAll(const DistributedVolume& dv, const sch_params& P, std::size_t count,
  PointOf pointOf, Parallel& parallel, bool everywhere, DistributedStats* stats, int threads,
  OpenCLTracer* cl, bool sums = true)
{
  if (sums && StraightSums(P))
    return TraceStraightSums(dv, P, count, pointOf, parallel, everywhere, stats);
  const int ranks = parallel.Size(), me = parallel.Rank();
  if (count > 0xffffffffu)
    throw Error("Distributed tracing: too many rays in one pass.");
  Clock::time_point t0 = Clock::now();
  // every rank finds where each ray enters; the owner of that cell starts it, rank 0 keeps misses
  std::vector<RayState> fresh, live;
  std::vector<Finished> finished;
  for (std::size_t k = 0; k < count; ++k)
  {
    RayState st;
    st.index = static_cast<std::uint32_t>(k);
    pointOf(k, &st.a, &st.b);
    st.s1 = 0.0f;
    const int hit = sch_entry(&P, st.a, st.b, &st.o, &st.entry, &st.s1);
    if (!hit)
    {
      if (me == 0)
      {
        sch_ray R;
        sch_missed(st.o, &R);
        Finished f;
        f.Index = st.index;
        sch_record(dv.Packed.data(), nullptr, &P, st.a, st.b, st.o, st.entry, st.s1, &R, f.Rec);
        finished.push_back(f);
      }
      continue;
    }
    int c[3];
    CellOf(P, st.entry, c);
    if (!dv.OwnsCell(c[0], c[1], c[2]))
      continue;
    sch_walk_begin(dv.Packed.data(), dv.TraceBytes(), &P, st.entry,
      P.step, &st.w);
    fresh.push_back(st);
  }
  // the rays that start here go in batches, a batch a round: while the next rank along the beam
  // traces the first batch on, this one traces the second (a pipeline; all at once, the ranks
  // behind would wait for the whole pass)
  const std::size_t batch = ranks == 1
    ? fresh.size()
    : std::max<std::size_t>(64, (fresh.size() + 4 * ranks - 1) / (4 * ranks));
  std::size_t next = 0;
  double tracing = 0, exchanging = 0, rounds = 0, handed = 0, bytes = 0;
  for (;;)
  {
    Clock::time_point ta = Clock::now();
    const std::size_t take = std::min(batch, fresh.size() - next);
    live.insert(live.end(), fresh.begin() + next, fresh.begin() + next + take);
    next += take;
    std::vector<std::vector<RayState>> handOn(ranks);
    Advance(dv, P, live, finished, handOn, threads, cl);
    tracing += SecondsSince(ta);
    Clock::time_point tb = Clock::now();
    std::vector<std::vector<char>> out(ranks);
    double sent = 0;
    for (int q = 0; q < ranks; ++q)
    {
      out[q].resize(handOn[q].size() * sizeof(RayState));
      if (!handOn[q].empty())
        std::memcpy(out[q].data(), handOn[q].data(), out[q].size());
      sent += handOn[q].size();
      if (q != me)
        bytes += out[q].size();
    }
    handed += sent;
    rounds += 1;
    // every rank learns whether any ray is still in flight or to start (the same answer everywhere)
    const double own = sent + double(fresh.size() - next);
    const double inFlight = parallel.Sum(own);
    // counts summed: a whole number, at least this rank's (else the loop would never end)
    if (!(inFlight >= own && inFlight == std::floor(inFlight) && inFlight <= 1e15))
    {
      std::ostringstream msg;
      msg << "Distributed tracing: the ranks' sum of the rays in flight came back as " << inFlight
          << " where this rank alone has " << own
          << ": that cannot be (the ranks' messages were changed on the way: a broken transport).";
      throw Error(msg.str());
    }
    if (inFlight == 0)
    {
      exchanging += SecondsSince(tb);
      break;
    }
    std::vector<std::vector<char>> in = parallel.Exchange(out);
    for (int from = 0; from < ranks; ++from)
    {
      std::vector<RayState> got = Unpack<RayState>(in[from], from, "rays handed on");
      for (const RayState& st : got)
      {
        // a ray handed on is one of the pass's, in a cell of this rank, within its steps (numbers
        // that are not finite are the march's to flag, as on one rank)
        if (st.index >= count)
          Impossible(from, "a ray handed on", "ray " + std::to_string(st.index) + " of " +
            std::to_string(count));
        int c[3];
        CellOf(P, st.w.x, c);
        if (!dv.OwnsCell(c[0], c[1], c[2]) || st.w.it < 0 || st.w.it > P.maxSteps || st.w.level < 0 ||
          st.w.level > 255)
          Impossible(from, "a ray handed on", "ray " + std::to_string(st.index) + " at cell (" +
            std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
            ") of rank " + std::to_string(dv.OwnerOfCell(c[0], c[1], c[2])) + ", not this rank (" +
            std::to_string(me) + "), or its steps " + std::to_string(st.w.it) + " or octree level " +
            std::to_string(st.w.level) + " out of range");
      }
      live.insert(live.end(), got.begin(), got.end());
    }
    exchanging += SecondsSince(tb);
  }
  // the records to rank 0 (or everyone), put in ray order
  Clock::time_point tc = Clock::now();
  std::vector<char> mine(finished.size() * sizeof(Finished));
  if (!finished.empty())
    std::memcpy(mine.data(), finished.data(), mine.size());
  std::vector<std::vector<char>> got;
  if (everywhere)
  {
    got = parallel.AllGather(mine);
    bytes += mine.size() * (ranks - 1);
  }
  else
  {
    std::vector<std::vector<char>> out(ranks);
    out[0] = std::move(mine);
    if (me != 0)
      bytes += out[0].size();
    got = parallel.Exchange(out);
  }
  std::vector<float> records;
  if (everywhere || me == 0)
  {
    records.assign(count * SCH_RECORD, 0.0f);
    std::size_t n = 0;
    std::vector<unsigned char> seen(count, 0);
    for (int from = 0; from < static_cast<int>(got.size()); ++from)
      for (const Finished& f : Unpack<Finished>(got[from], from, "records of finished rays"))
      {
        if (f.Index >= count || seen[f.Index])
          Impossible(from, "the record of a finished ray", "ray " + std::to_string(f.Index) +
            (f.Index >= count ? " of " + std::to_string(count) : ", whose record came already"));
        seen[f.Index] = 1;
        std::memcpy(records.data() + static_cast<std::size_t>(f.Index) * SCH_RECORD, f.Rec,
          sizeof(f.Rec));
        ++n;
      }
    if (n != count)
      throw Error("Distributed tracing lost rays (" + std::to_string(count - n) + " of " +
        std::to_string(count) + "): a bug; please report it.");
  }
  exchanging += SecondsSince(tc);
  (void)t0;
  if (stats)
  {
    stats->Rounds += rounds;
    stats->RaysHandedOn += handed;
    stats->BytesExchanged += bytes;
    stats->SecondsTracing += tracing;
    stats->SecondsExchanging += exchanging;
  }
  return records;
}

} // namespace

namespace
{
/**
 * The device tracer for this rank's held points, or null for the CPU (asked for, an empty piece,
 * or OpenCL unusable under Backend Auto, with a warning in stats). Line of sight in sums runs on
 * the host. Collective: under Backend OpenCL a failure on any rank throws on every rank.
 */
std::shared_ptr<OpenCLTracer> PieceBackend(const DistributedVolume& dv, const TraceSettings& s,
  const sch_params& P, bool sums, Parallel& parallel, DistributedStats* stats)
{
  std::shared_ptr<OpenCLTracer> cl;
  std::string used = "CPU", device = "CPU (" + std::to_string(CpuThreads(s.Threads)) + " threads)";
  std::string problem, warning;
  if (s.Device != Backend::CPU && !(sums && StraightSums(P)) && !dv.Packed.empty())
  {
    try
    {
      cl = AcquireTracer(dv.Held(), dv.TraceBytes(), dv.HasSolid ? dv.KeptBytes : nullptr, 1,
        s.RaysPerWorkItem, GetRuntimeOptions(), s.DeviceName);
      PreparePiecesKernel(*cl, P);
      used = "OpenCL";
      device = TracerDeviceName(*cl);
    }
    catch (const Error& e)
    {
      cl.reset();
      if (s.Device == Backend::OpenCL)
        problem = e.what();
      else
        warning = std::string("OpenCL is not usable, tracing on the CPU instead: ") + e.what() + "\n";
    }
  }
  problem = parallel.Failure(problem);
  if (!problem.empty())
    throw Error(problem);
  if (stats)
  {
    stats->BackendUsed = used;
    stats->DeviceName = device;
    if (stats->Warnings.find(warning) == std::string::npos)
      stats->Warnings += warning;
  }
  return cl;
}
} // namespace

namespace
{
/**
 * TraceAll, with the step-doubling estimate where P asks for it. A walk on the pieces cannot march
 * a second, private ray across ranks as one process does (sch_record): the rays are traced on the
 * pieces at the base step and again at twice it, and rank 0 (every rank with `everywhere`) puts the
 * estimate and the second trace's samples into each record with the arithmetic of sch_record, so
 * the records equal one process's bit for bit. Both traces march (no line-of-sight sums: one
 * process marches both).
 */
template <typename PointOf>
std::vector<float> TraceAllEstimated(const DistributedVolume& dv, const sch_params& P, std::size_t count,
  PointOf pointOf, Parallel& parallel, bool everywhere, DistributedStats* stats, int threads,
  OpenCLTracer* cl, bool sums = true)
{
  if (!P.estimate)
    return TraceAll(dv, P, count, pointOf, parallel, everywhere, stats, threads, cl, sums);
  sch_params base = P;
  base.estimate = 0;
  sch_params doubled = base;
  doubled.step = 2.0f * P.step;
  std::vector<float> rec = TraceAll(dv, base, count, pointOf, parallel, everywhere, stats, threads, cl, false);
  const std::vector<float> rec2 =
    TraceAll(dv, doubled, count, pointOf, parallel, everywhere, stats, threads, cl, false);
  if (rec.empty())
    return rec;
  for (std::size_t k = 0; k < count; ++k)
  {
    float* r = &rec[k * SCH_RECORD];
    const float* r2 = &rec2[k * SCH_RECORD];
    const unsigned f1 = static_cast<unsigned>(r[SCH_REC_FLAGS]), f2 = static_cast<unsigned>(r2[SCH_REC_FLAGS]);
    if ((f1 & SCH_RAY_MISSED) || (f1 & SCH_RAY_BLOCKED))
      continue;
    r[SCH_REC_ERROR] = (f2 & SCH_RAY_BLOCKED)
      ? 0.0f
      : sch_doubling_error(P.integrator, r[SCH_REC_EX], r[SCH_REC_EY], r2[SCH_REC_EX], r2[SCH_REC_EY]);
    r[SCH_REC_SAMPLES] += r2[SCH_REC_SAMPLES];
  }
  return rec;
}
} // namespace

std::vector<RayRecord> TraceRaysDistributed(const DistributedVolume& dv, const TraceSettings& s,
  const std::vector<float>& ab, Parallel& parallel, bool everywhere, DistributedStats* stats,
  bool lineOfSightSums)
{
  const FilmGeometry film = MakeFilm(dv.Whole(), s);
  const sch_params P = PieceParams(dv, s, film);
  const std::size_t count = ab.size() / 2;
  // a body's bits for this trace's reach (the estimate's doubled step included, as one process)
  dv.CellBytes(StepReach(P));
  const std::shared_ptr<OpenCLTracer> cl = PieceBackend(dv, s, P, lineOfSightSums, parallel, stats);
  std::vector<float> rec = TraceAllEstimated(
    dv, P, count,
    [&](std::size_t k, float* a, float* b) {
      *a = ab[2 * k];
      *b = ab[2 * k + 1];
    },
    parallel, everywhere, stats, s.Threads, cl.get(), lineOfSightSums);
  std::vector<RayRecord> out;
  if (rec.empty())
    return out;
  out.resize(count);
  std::memcpy(out.data(), rec.data(), rec.size() * sizeof(float));
  // the flags travel as floats in the record; turn them into integers
  for (RayRecord& r : out)
  {
    float f;
    std::memcpy(&f, &r.Flags, sizeof(f));
    r.Flags = static_cast<std::uint32_t>(f);
  }
  return out;
}

TraceSettings ResolveAutoDistributed(const DistributedVolume& dv, const TraceSettings& s,
  Parallel& parallel, AutoChoice* choice)
{
  if (s.Recon != Reconstruction::Trilinear && !dv.HighOrder)
    throw Error("Distributed tracing: Reconstruction " + std::string(ReconstructionName(s.Recon)) +
      " needs the pieces packed for Cubic (DistributedVolume's smoothLevels).");
  AutoVolume grid;
  grid.Grid = dv.Whole();
  grid.HasLevels = dv.Octree;
  grid.HasSmooth = dv.HighOrder;
  grid.HasSolid = dv.HasSolid;
  // the candidates' steps stay within what the pieces' ghost layers hold (AutoPiecesReach)
  grid.PiecesBound = true;
  return ResolveAutoWith(grid, s, choice,
    [&](const TraceSettings& t, const std::vector<float>& ab) {
      // the pilot's line-of-sight rays handed on like the others: its records, hence its
      // choice, are one process's bit for bit
      return TraceRaysDistributed(dv, t, ab, parallel, true, nullptr, false);
    });
}

void AccumulateDistributed(const DistributedVolume& dv, const TraceSettings& s, FilmSums& sums,
  Parallel& parallel, DistributedStats* stats, const ProgressFunction& progress)
{
  CheckSettings(s);
  if (s.RussianRoulette && !(s.CutoffScale > 0) &&
    (s.Mode == Cutoff::KnifeEdge || s.Mode == Cutoff::Circular || s.Mode == Cutoff::ComplementCircular))
    throw Error("Photon killing (RussianRoulette) needs a fixed CutoffScale: the automatic scale is "
                "known only after the trace.");
  const FilmGeometry film = MakeFilm(dv.Whole(), s);
  sch_params P = PieceParams(dv, s, film);
  if (sums.Size[0] != film.Size[0] || sums.Size[1] != film.Size[1] || sums.Count.empty())
  {
    CheckFilmMemory(film.Size);
    sums.Resize(film.Size[0], film.Size[1]);
  }
  const std::size_t pixels = static_cast<std::size_t>(film.Size[0]) * film.Size[1];
  Splatter splat(P, s, sums);
  dv.CellBytes(StepReach(P));
  if (dv.HasSolid && s.Recon == Reconstruction::Cubic && sums.Passes == 0 && stats &&
    parallel.Rank() == 0)
    stats->Warnings += "Reconstruction Cubic is not available with a solid body (the byte per "
                       "point that carries the body holds the smoothness it needs): traced "
                       "trilinear.\n";
  const std::shared_ptr<OpenCLTracer> cl = PieceBackend(dv, s, P, true, parallel, stats);
  for (int pass = 0; pass < s.Passes; ++pass)
  {
    P.pass = sums.Passes + pass;
    // Camera Lens: the pieces trace this pass's tilted beam (Pk), a band this pass's wavelength;
    // the splatter bins on P's film
    sch_params Pk = P;
    splat.BeginPass(Pk, P.pass);
    std::vector<float> rec = TraceAllEstimated(
      dv, Pk, pixels,
      [&](std::size_t k, float* a, float* b) { sch_emit(&Pk, static_cast<int>(k), a, b); },
      parallel, false, stats, s.Threads, cl.get());
    // in pixel order on rank 0, as one process splats them: the same sums, bit for bit
    if (parallel.Rank() == 0)
      splat.Add(rec.data(), 0, pixels);
    // every rank stops together: rank 0's answer
    bool go = true;
    if (progress)
      go = progress(double(pass + 1) / s.Passes);
    if (!parallel.AllOk(go))
      throw Error("aborted");
  }
  sums.Passes += s.Passes;
}

} // namespace schlieren
