// SPDX-License-Identifier: BSD-3-Clause
// Distributed tracing on in-process ranks: a volume split into pieces (slabs, blocks, uneven), each
// rank holding only its piece and ghosts, rays handed from rank to rank. The known answer is one
// process tracing the whole volume on the CPU backend: every ray record and every film sum must be
// equal bit for bit (the same steps with the same arithmetic, splatted in the same order), for the
// Gaussian sphere seen obliquely, the Luneburg lens (rays that curve across pieces and back) and a
// shadowgraph with caustics. Bad decompositions and bad pieces give one error on every rank.
#include "SchlierenBodies.h"
#include "SchlierenDistributed.h"
#include "SchlierenOptions.h"
#include "SchlierenTesting.h"

#include <cstring>
#include <mutex>

using namespace schlieren;

namespace
{

/** A decomposition: per rank, its point extent (inclusive) of a grid of n points per side. */
using Decomposition = std::vector<std::array<int, 6>>;

/** Splits points 0..n-1 into `parts` ranges sharing their end points, at the given fractions. */
std::vector<std::array<int, 2>> Split(int n, const std::vector<double>& cuts)
{
  std::vector<std::array<int, 2>> out;
  int lo = 0;
  for (double c : cuts)
  {
    const int hi = static_cast<int>(c * (n - 1));
    out.push_back({ lo, hi });
    lo = hi;
  }
  out.push_back({ lo, n - 1 });
  return out;
}

Decomposition Blocks(int n, const std::vector<double>& cx, const std::vector<double>& cy,
  const std::vector<double>& cz)
{
  Decomposition d;
  for (auto z : Split(n, cz))
    for (auto y : Split(n, cy))
      for (auto x : Split(n, cx))
        d.push_back({ x[0], x[1], y[0], y[1], z[0], z[1] });
  return d;
}

/** The piece of `extent` cut from values on the whole grid of `sv`. */
template <typename T>
std::vector<T> CutOf(const schtest::SceneVolume& sv, const std::vector<T>& whole, const std::array<int, 6>& e)
{
  const int* d = sv.V.Dimensions;
  std::vector<T> out;
  for (int z = e[4]; z <= e[5]; ++z)
    for (int y = e[2]; y <= e[3]; ++y)
      for (int x = e[0]; x <= e[1]; ++x)
        out.push_back(whole[(static_cast<std::size_t>(z) * d[1] + y) * d[0] + x]);
  return out;
}

/** The piece of `extent` cut from the whole grid's n - 1. */
std::vector<float> Cut(const schtest::SceneVolume& sv, const std::array<int, 6>& e)
{
  return CutOf(sv, sv.N1, e);
}

Piece PieceOf(const schtest::SceneVolume& sv, const std::array<int, 6>& e, const std::vector<float>& values)
{
  Piece p;
  std::copy(sv.V.Dimensions, sv.V.Dimensions + 3, p.WholeDimensions);
  std::copy(sv.V.Origin, sv.V.Origin + 3, p.Origin);
  std::copy(sv.V.Spacing, sv.V.Spacing + 3, p.Spacing);
  std::copy(e.begin(), e.end(), p.Extent);
  p.NMinus1 = values.data();
  return p;
}

/** One process's volume of `sv`, with the whole grid's octree (levels up to the distributed
 * maximum, into `levels`) where tol >= 0, packed for Reconstruction Cubic (into `cubic`, the
 * smoothness into `smooth`) where `highOrder`. */
Volume WholeVolume(const schtest::SceneVolume& sv, double tol, std::vector<unsigned char>& levels,
  bool highOrder, std::vector<float>& cubic, std::vector<unsigned char>& smooth,
  int maxLevel = DistributedOctreeMaxLevel)
{
  Volume whole = sv.V;
  if (highOrder)
  {
    cubic.resize(4 * whole.NumberOfPoints());
    smooth.resize(whole.NumberOfPoints());
    const double fraction =
      PackFieldHighOrder(whole.Dimensions, whole.Spacing, sv.N1.data(), cubic.data(), smooth.data());
    std::printf("  (packed for Cubic: %.2f of the cells smooth)\n", fraction);
    whole.Field = cubic.data();
    whole.Smooth = smooth.data();
  }
  if (tol >= 0)
  {
    levels.resize(whole.NumberOfPoints());
    ComputeOctreeLevels(whole.Dimensions, sv.N1.data(), tol, levels.data(), maxLevel);
    whole.Levels = levels.data();
    whole.LevelTolerance = tol;
  }
  return whole;
}

bool SameRecords(const std::vector<RayRecord>& a, const std::vector<RayRecord>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(RayRecord)) == 0;
}

bool SameSums(FilmSums& a, FilmSums& b)
{
  std::vector<double> aa, am, ba, bm;
  a.ToArrays(aa, am);
  b.ToArrays(ba, bm);
  return aa.size() == ba.size() && am.size() == bm.size() &&
    std::memcmp(aa.data(), ba.data(), aa.size() * sizeof(double)) == 0 &&
    std::memcmp(am.data(), bm.data(), am.size() * sizeof(double)) == 0;
}

struct Case
{
  const char* Name;
  schtest::SceneVolume* Volume;
  TraceSettings Settings;
  double OctreeTolerance = -1; ///< >= 0: with the min-max octree (levels up to 3)
  bool OnDevice = true;        ///< also traced on OpenCL in pieces
  const std::vector<unsigned char>* Solid = nullptr; ///< a body's points (whole grid), or none
  int OctreeLevels = DistributedOctreeMaxLevel;      ///< one process's octree MaxLevel
};

/** The octree level the pieces hold for the case (OctreeLevelReached on the whole grid as one
 * piece: the same on any pieces), 0 without the octree. */
int LevelFor(const Case& c)
{
  if (c.OctreeTolerance < 0)
    return 0;
  int level = 0;
  const std::vector<float>& n1 = c.Volume->N1;
  RunInProcessRanks(1, [&](Parallel& p) {
    Piece whole;
    std::copy(c.Volume->V.Dimensions, c.Volume->V.Dimensions + 3, whole.WholeDimensions);
    for (int a = 0; a < 3; ++a)
    {
      whole.Extent[2 * a] = 0;
      whole.Extent[2 * a + 1] = c.Volume->V.Dimensions[a] - 1;
    }
    whole.NMinus1 = n1.data();
    level = OctreeLevelReached(whole, c.OctreeTolerance, c.OctreeLevels, p);
  });
  return level;
}

/** Whether the case needs the pieces packed for Cubic (Reconstruction Cubic or Auto). */
bool HighOrder(const TraceSettings& s)
{
  return s.Recon != Reconstruction::Trilinear;
}

/** A rank's distributed volume for the case: its piece with the ghosts that `s` needs, the octree
 * where the case has one, packed for Cubic where `s` asks for it. */
DistributedVolume PiecesFor(const Case& c, const TraceSettings& s, Piece piece, Parallel& p,
  const std::vector<unsigned char>& solid)
{
  piece.Solid = c.Solid ? solid.data() : nullptr;
  // the level reached, from the pieces (every rank the same)
  const int level = c.OctreeTolerance >= 0 ? OctreeLevelReached(piece, c.OctreeTolerance, c.OctreeLevels, p) : 0;
  const int ghost = GhostPointsFor(s, level);
  return DistributedVolume(piece, ghost, p, level > 0 ? c.OctreeTolerance : -1.0, level,
    HighOrder(s) ? SmoothLevelsFor(s) : 0);
}

/** Settings with Auto resolved as one process resolves it on `whole` (unchanged without Auto),
 * with the steps the pieces allow (issue 50: beyond 8 voxels trilinear, 64 tricubic, the whole
 * volume's Auto may go further than the pieces' ghost layers hold). */
TraceSettings Resolved(const Volume& whole, const TraceSettings& s)
{
  if (s.Method != Integrator::Auto && s.Recon != Reconstruction::Auto)
    return s;
  AutoChoice choice;
  const TraceSettings out = ResolveAuto(whole, s, &choice, true);
  std::printf("  (one process's Auto: %s)\n", choice.Report.c_str());
  return out;
}

bool SameChoice(const TraceSettings& a, const TraceSettings& b)
{
  return a.Method == b.Method && a.StepSize == b.StepSize && a.Recon == b.Recon;
}

/** Traces `c` on the decomposition and compares with one process; returns the rays handed on. */
double CheckCase(Case& c, const char* decoName, const Decomposition& deco)
{
  const schtest::SceneVolume& sv = *c.Volume;
  TraceSettings s = c.Settings;
  s.Device = Backend::CPU;
  // one process's volume, with the whole grid's octree where the case has one
  std::vector<unsigned char> levels, smooth;
  std::vector<float> cubic;
  Volume whole = WholeVolume(sv, c.OctreeTolerance, levels, HighOrder(s), cubic, smooth, c.OctreeLevels);
  if (c.Solid)
    whole.Solid = c.Solid->data();
  if (c.OctreeTolerance >= 0)
    s.UseOctree = true;
  const int ghost = GhostPointsFor(s, LevelFor(c));
  // Auto: the pieces must make one process's choice; both trace it
  const TraceSettings asked = s;
  s = Resolved(whole, asked);
  // the known answer: one process, the whole volume, the CPU backend
  std::vector<float> ab;
  const FilmGeometry film = MakeFilm(whole, s);
  for (int j = 0; j < s.Resolution[1]; ++j)
    for (int i = 0; i < s.Resolution[0]; ++i)
    {
      ab.push_back(static_cast<float>(film.Corner[0] + (i + 0.5) * film.PixelSize));
      ab.push_back(static_cast<float>(film.Corner[1] + (j + 0.5) * film.PixelSize));
    }
  const std::vector<RayRecord> expected = TraceRays(whole, s, ab);
  FilmSums expectedSums;
  Accumulate(whole, s, expectedSums);
  if (s.EstimateError)
  {
    // the records compared carry an estimate: not all zero
    double largest = 0;
    for (const RayRecord& r : expected)
      largest = std::max(largest, double(r.Error));
    CHECK(largest > 0, std::string(c.Name) + ": one process's estimate is not zero (" + std::to_string(largest) + ")");
  }

  const int ranks = static_cast<int>(deco.size());
  std::vector<std::vector<float>> values(ranks);
  std::vector<std::vector<unsigned char>> solids(ranks);
  for (int r = 0; r < ranks; ++r)
  {
    values[r] = Cut(sv, deco[r]);
    if (c.Solid)
      solids[r] = CutOf(sv, *c.Solid, deco[r]);
  }
  if (c.Solid)
  {
    double blocked = 0;
    for (const RayRecord& r : expected)
      blocked += (r.Flags & RayBlocked) ? 1 : 0;
    CHECK(blocked > 0, std::string(c.Name) + ": the body stops rays (" + std::to_string(blocked) + ")");
  }
  std::mutex m;
  bool recordsEqual = true, sumsEqual = true, smaller = true, sameChoice = true;
  double handed = 0, rounds = 0;
  RunInProcessRanks(ranks, [&](Parallel& p) {
    const int r = p.Rank();
    DistributedVolume dv = PiecesFor(c, asked, PieceOf(sv, deco[r], values[r]), p, solids[r]);
    const TraceSettings mine = asked.Method == Integrator::Auto || asked.Recon == Reconstruction::Auto
      ? ResolveAutoDistributed(dv, asked, p)
      : asked;
    DistributedStats st;
    const std::vector<RayRecord> got = TraceRaysDistributed(dv, s, ab, p, true, &st);
    FilmSums sums;
    AccumulateDistributed(dv, s, sums, p, &st);
    std::lock_guard<std::mutex> lock(m);
    sameChoice = sameChoice && SameChoice(mine, s);
    recordsEqual = recordsEqual && SameRecords(got, expected);
    if (r == 0)
      sumsEqual = SameSums(sums, expectedSums);
    // a rank holds its owned cells' points and the ghosts around them, within the grid: no more
    std::size_t held = 4;
    for (int d = 0; d < 3; ++d)
      held *= std::min(sv.V.Dimensions[d] - 1, deco[r][2 * d + 1] + ghost) -
        std::max(0, deco[r][2 * d] - ghost) + 1;
    smaller = smaller && dv.Packed.size() == held;
    handed += st.RaysHandedOn;
    rounds = std::max(rounds, st.Rounds);
  });
  const std::string what = std::string(c.Name) + ", " + decoName + " (" + std::to_string(ranks) +
    " ranks)";
  CHECK(sameChoice, what + ": Auto on the pieces chose what one process chose");
  CHECK(recordsEqual, what + ": every ray record equals one process's, bit for bit");
  CHECK(sumsEqual, what + ": the film sums equal one process's, bit for bit");
  CHECK(smaller, what + ": each rank holds its piece and " + std::to_string(ghost) +
      " ghost points, no more");
  if (c.OctreeTolerance >= 0)
  {
    // the octree skips: fewer steps than fixed steps through the same volume
    TraceSettings fixed = s;
    fixed.UseOctree = false;
    double skipping = 0, plain = 0;
    for (const RayRecord& r : expected)
      skipping += r.Steps;
    for (const RayRecord& r : TraceRays(whole, fixed, ab))
      plain += r.Steps;
    CHECK(skipping < 0.7 * plain, what + ": the octree skips (steps " + std::to_string(skipping) +
        " against " + std::to_string(plain) + " fixed)");
  }
  std::printf("%-34s %-22s ranks %d: %8.0f rays handed on, %3.0f rounds (both traces)\n", c.Name,
    decoName, ranks, handed, rounds);
  return handed;
}

/**
 * BodyFromGrid across pieces (EnclosedInvalidPointsOfPiece): random holes (about 45 % of the
 * points invalid, so regions wind across the pieces) on a 20 x 18 x 16 grid, split into pieces
 * that share their face points and pieces that only touch; every piece's solid points must be
 * the whole grid's (EnclosedInvalidPoints), with and without wall faces.
 */
void TestEnclosedInPieces()
{
  const int dims[3] = { 20, 18, 16 };
  const int whole[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::vector<unsigned char> valid(n);
  unsigned state = 12345u;
  for (std::size_t i = 0; i < n; ++i)
  {
    state = state * 1664525u + 1013904223u;
    valid[i] = (state >> 8) % 100 >= 45 ? 1 : 0;
  }
  const int walls[6] = { 0, 0, 0, 0, 1, 0 };
  for (const int* wallFaces : { static_cast<const int*>(nullptr), walls })
  {
    std::vector<unsigned char> expected(n);
    const std::size_t count = EnclosedInvalidPoints(dims, valid.data(), wallFaces, expected.data());
    // pieces: {x0, x1, ...} per rank; "touching" ones leave no shared layer
    const std::vector<std::pair<const char*, std::vector<std::array<int, 6>>>> decos = {
      { "2 slabs sharing a layer", { { 0, 19, 0, 17, 0, 8 }, { 0, 19, 0, 17, 8, 15 } } },
      { "3 touching slabs along x", { { 0, 5, 0, 17, 0, 15 }, { 6, 12, 0, 17, 0, 15 }, { 13, 19, 0, 17, 0, 15 } } },
      { "2 x 2 blocks sharing layers, an empty rank",
        { { 0, 10, 0, 9, 0, 15 }, { 10, 19, 0, 9, 0, 15 }, { 0, 10, 9, 17, 0, 15 }, { 10, 19, 9, 17, 0, 15 },
          { 0, -1, 0, -1, 0, -1 } } },
    };
    for (const auto& d : decos)
    {
      const int ranks = static_cast<int>(d.second.size());
      std::mutex m;
      bool same = true;
      double solid = 0;
      RunInProcessRanks(ranks, [&](Parallel& p) {
        const std::array<int, 6>& e = d.second[p.Rank()];
        std::vector<unsigned char> v, got;
        for (int z = e[4]; z <= e[5]; ++z)
          for (int y = e[2]; y <= e[3]; ++y)
            for (int x = e[0]; x <= e[1]; ++x)
              v.push_back(valid[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x]);
        got.resize(v.size());
        EnclosedInvalidPointsOfPiece(p, e.data(), whole, v.data(), wallFaces, got.data());
        std::lock_guard<std::mutex> lock(m);
        std::size_t k = 0;
        for (int z = e[4]; z <= e[5]; ++z)
          for (int y = e[2]; y <= e[3]; ++y)
            for (int x = e[0]; x <= e[1]; ++x, ++k)
            {
              same = same && got[k] == expected[(static_cast<std::size_t>(z) * dims[1] + y) * dims[0] + x];
              solid += got[k];
            }
      });
      CHECK(same && count > 0,
        std::string("BodyFromGrid in pieces, ") + d.first + (wallFaces ? ", z min a wall" : "") +
          ": every piece's solid points are the whole grid's (" + std::to_string(count) + " of " +
          std::to_string(n) + ")");
    }
  }
}

} // namespace

int main()
{
  TestEnclosedInPieces();
  const int n = 40;
  SceneParameters gp;
  gp.Amplitude = 2e-3;
  gp.Width = 0.3;
  gp.Center[0] = 0.1;
  schtest::SceneVolume gauss(Scene::GaussianSphere, gp, n, 1.0);
  SceneParameters lp;
  lp.Radius = 0.8;
  schtest::SceneVolume luneburg(Scene::LuneburgLens, lp, n, 1.0);
  SceneParameters bp;
  bp.Radius = 0.6;
  bp.Width = 0.04;
  schtest::SceneVolume blast(Scene::BlastWave, bp, n, 1.0);

  std::vector<Case> cases;
  {
    Case c{ "Gaussian sphere, oblique, RK4", &gauss, TraceSettings() };
    c.Settings.ViewDirection[0] = 0.6;
    c.Settings.ViewDirection[1] = -0.5;
    c.Settings.ViewDirection[2] = -0.62;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Method = Integrator::RK4;
    c.Settings.StepSize = 1.0;
    cases.push_back(c);
  }
  {
    Case c{ "Luneburg lens, midpoint", &luneburg, TraceSettings() };
    c.Settings.ViewDirection[0] = 0.3;
    c.Settings.ViewDirection[2] = -1;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Method = Integrator::Midpoint;
    c.Settings.StepSize = 0.5;
    c.Settings.Mode = Cutoff::Shadowgraph;
    cases.push_back(c);
  }
  {
    // Verlet's two half kicks a step: a ray handed on between two steps carries no half of one,
    // and its last half kick (where it leaves the box) is taken on the rank it leaves from
    Case c{ "Luneburg lens, Verlet", &luneburg, TraceSettings() };
    c.Settings.ViewDirection[0] = -0.4;
    c.Settings.ViewDirection[1] = 0.3;
    c.Settings.ViewDirection[2] = -1;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Method = Integrator::Verlet;
    c.Settings.StepSize = 1.5;
    cases.push_back(c);
  }
  {
    // the octree at one process's default MaxLevel (7): blocks up to the level the volume reaches
    // (OctreeLevelReached, from the pieces' own points), ghosts as deep as such a block (issue 23)
    Case c{ "Gaussian sphere, octree to level 7, RK4", &gauss, TraceSettings(), 2e-6 };
    c.OctreeLevels = 7;
    c.Settings.ViewDirection[0] = -0.3;
    c.Settings.ViewDirection[1] = 0.2;
    c.Settings.ViewDirection[2] = -1;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Method = Integrator::RK4;
    c.Settings.StepSize = 0.5;
    c.OnDevice = false;
    std::printf("octree to level 7 on the Gaussian: the pieces hold levels up to %d\n", LevelFor(c));
    CHECK(LevelFor(c) > DistributedOctreeMaxLevel, "the Gaussian's octree reaches past level 3 (" +
        std::to_string(LevelFor(c)) + ")");
    cases.push_back(c);
  }
  {
    // the octree skips the uniform air around the sphere (tolerance: 1e-3 of the peak)
    Case c{ "Gaussian sphere, octree, Euler", &gauss, TraceSettings(), 2e-6 };
    c.Settings.ViewDirection[0] = 0.2;
    c.Settings.ViewDirection[1] = 0.3;
    c.Settings.ViewDirection[2] = -1;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.StepSize = 0.5;
    cases.push_back(c);
  }
  {
    Case c{ "Gaussian shadowgraph, caustics", &gauss, TraceSettings() };
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Mode = Cutoff::Shadowgraph;
    c.Settings.FilmDistance = 40.0; // far behind: the focused rays cross (caustics)
    c.Settings.Passes = 2;
    cases.push_back(c);
  }

  {
    // a camera's aperture (docs/BENCH.md "Camera"): each pass's beam tilted toward its lens point,
    // defocused, so that the tilted rays cross the pieces
    Case c{ "Gaussian sphere, camera lens f/1", &gauss, TraceSettings() };
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Passes = 3;
    c.Settings.Camera = CameraModel::Lens;
    c.Settings.CameraFocalLength = 1.0;
    c.Settings.FNumber = 1.0;
    c.Settings.FocusPlane = 0.5;
    c.Settings.CameraDistance = 3.0;
    cases.push_back(c);
  }

  {
    // the step-doubling estimate: every ray traced again at twice the step on the pieces, the
    // estimate put into its record on rank 0 as one process's private second march does
    Case c{ "Gaussian sphere, RK4, error estimate", &gauss, TraceSettings() };
    c.Settings.ViewDirection[0] = -0.4;
    c.Settings.ViewDirection[1] = 0.5;
    c.Settings.ViewDirection[2] = -0.8;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Method = Integrator::RK4;
    c.Settings.StepSize = 1.0;
    c.Settings.EstimateError = true;
    c.Settings.Passes = 1;
    cases.push_back(c);
  }
  {
    // white light (docs/BENCH.md "Light"): each pass a wavelength of the band (2 bins, one a
    // pass), n - 1 scaled in
    // every piece's kernels, the colours summed on rank 0
    Case c{ "Gaussian interferogram, 400-700 nm", &gauss, TraceSettings() };
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.ViewDirection[0] = 0.3;
    c.Settings.ViewDirection[2] = -1;
    c.Settings.Mode = Cutoff::Interferometry;
    c.Settings.ReferenceTilt = 3;
    c.Settings.WavelengthRange[0] = 400;
    c.Settings.WavelengthRange[1] = 700;
    c.Settings.WavelengthBins = 2;
    c.Settings.Passes = 2;
    cases.push_back(c);
  }

  {
    // Reconstruction Cubic (issue 23): tricubic samples where the data is smooth, trilinear
    // beside the shock, steps sized by the smoothness levels; the pieces' smoothness tested on the
    // whole grid's range, every owned cell's bytes the whole grid's
    Case c{ "Blast wave, oblique, Cubic RK4", &blast, TraceSettings() };
    c.Settings.ViewDirection[0] = 0.5;
    c.Settings.ViewDirection[1] = 0.4;
    c.Settings.ViewDirection[2] = -0.8;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Method = Integrator::RK4;
    c.Settings.StepSize = 4.0;
    c.Settings.Recon = Reconstruction::Cubic;
    cases.push_back(c);
  }
  {
    // Auto with Reconstruction Auto: the pilot on the pieces, both reconstructions' candidates
    // (tricubic ones up to 64 voxels: every piece's ghosts reach across this small grid)
    Case c{ "Gaussian sphere, Auto + Recon Auto", &gauss, TraceSettings() };
    c.Settings.ViewDirection[0] = 0.3;
    c.Settings.ViewDirection[1] = -0.2;
    c.Settings.ViewDirection[2] = -1;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Method = Integrator::Auto;
    c.Settings.Recon = Reconstruction::Auto;
    c.Settings.Tolerance = 1e-6;
    // (on the CPU only: the blast wave runs Cubic on the device; one process's pilot there compiles
    // every candidate's kernel, 9 s cold)
    c.OnDevice = false;
    cases.push_back(c);
  }

  // a solid sphere beside the Gaussian (issue 23): its points travel with the pieces' ghosts,
  // every owned cell's solid and near bits are one process's; with the octree (levels up to 3)
  // lowered around it, and the error estimate's doubled reach
  std::vector<unsigned char> body(gauss.N1.size(), 0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double x = -1 + 2.0 * i / (n - 1) + 0.35, y = -1 + 2.0 * j / (n - 1) - 0.1,
                     z = -1 + 2.0 * k / (n - 1);
        body[(static_cast<std::size_t>(k) * n + j) * n + i] = x * x + y * y + z * z < 0.25 * 0.25;
      }
  {
    Case c{ "Gaussian and a body, octree, RK4 estimate", &gauss, TraceSettings(), 2e-6 };
    c.Solid = &body;
    c.Settings.ViewDirection[0] = 0.4;
    c.Settings.ViewDirection[1] = 0.3;
    c.Settings.ViewDirection[2] = -0.9;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Method = Integrator::RK4;
    c.Settings.StepSize = 1.0;
    c.Settings.EstimateError = true;
    cases.push_back(c);
  }
  {
    Case c{ "Gaussian and a body, Auto", &gauss, TraceSettings() };
    c.Solid = &body;
    c.Settings.ViewDirection[0] = -0.3;
    c.Settings.ViewDirection[2] = -1;
    c.Settings.Resolution[0] = c.Settings.Resolution[1] = 24;
    c.Settings.Method = Integrator::Auto;
    c.OnDevice = false;
    cases.push_back(c);
  }

  const std::vector<std::pair<const char*, Decomposition>> decos = {
    { "whole", Blocks(n, {}, {}, {}) },
    { "2 slabs along z", Blocks(n, {}, {}, { 0.5 }) },
    { "3 uneven slabs along x", Blocks(n, { 0.2, 0.7 }, {}, {}) },
    { "2 x 2 blocks", Blocks(n, { 0.5 }, { 0.5 }, {}) },
    { "2 x 2 uneven blocks", Blocks(n, { 0.3 }, {}, { 0.6 }) },
  };
  for (Case& c : cases)
  {
    double handedLens = 0;
    for (const auto& d : decos)
      handedLens += CheckCase(c, d.first, d.second);
    CHECK(handedLens > 0, std::string(c.Name) + ": rays were handed from rank to rank");
  }

  // on an OpenCL device (the kernel sch_walk_pieces): every rank runs the same kernel, so 2 and 4
  // ranks give the same film bit for bit; one process traces with another kernel build of the
  // same physics (the lock-step kernel), whose float rounding may differ: within 1e-5 of the
  // largest deflection sum, the same photons in all
  if (schtest::HaveOpenCL())
  {
    for (Case& c : cases)
    {
      if (!c.OnDevice)
        continue;
      const schtest::SceneVolume& sv = *c.Volume;
      TraceSettings s = c.Settings;
      s.Device = Backend::OpenCL;
      std::vector<unsigned char> levels, smooth;
      std::vector<float> cubic;
      Volume whole = WholeVolume(sv, c.OctreeTolerance, levels, HighOrder(s), cubic, smooth, c.OctreeLevels);
      if (c.Solid)
        whole.Solid = c.Solid->data();
      if (c.OctreeTolerance >= 0)
        s.UseOctree = true;
      const TraceSettings asked = s;
      s = Resolved(whole, asked);
      FilmSums expected;
      Accumulate(whole, s, expected);
      FilmSums got[2];
      bool onDevice = true;
      const Decomposition decos2[2] = { Blocks(n, {}, {}, { 0.5 }), Blocks(n, { 0.4 }, {}, { 0.6 }) };
      for (int which = 0; which < 2; ++which)
      {
        const Decomposition& d = decos2[which];
        const int ranks = static_cast<int>(d.size());
        std::vector<std::vector<float>> values(ranks);
        std::vector<std::vector<unsigned char>> solids(ranks);
        for (int r = 0; r < ranks; ++r)
        {
          values[r] = Cut(sv, d[r]);
          if (c.Solid)
            solids[r] = CutOf(sv, *c.Solid, d[r]);
        }
        std::mutex m;
        RunInProcessRanks(ranks, [&](Parallel& p) {
          DistributedVolume dv =
            PiecesFor(c, asked, PieceOf(sv, d[p.Rank()], values[p.Rank()]), p, solids[p.Rank()]);
          DistributedStats st;
          FilmSums sums;
          AccumulateDistributed(dv, s, sums, p, &st);
          std::lock_guard<std::mutex> lock(m);
          onDevice = onDevice && st.BackendUsed == "OpenCL";
          if (p.Rank() == 0)
            got[which] = sums;
        });
      }
      double dmax = 0, scale = 0;
      for (std::size_t k = 0; k < expected.Count.size(); ++k)
      {
        dmax = std::max(dmax, std::hypot(got[1].DeflectionX[k] - expected.DeflectionX[k],
                                got[1].DeflectionY[k] - expected.DeflectionY[k]));
        scale = std::max(scale, std::hypot(expected.DeflectionX[k], expected.DeflectionY[k]));
      }
      const std::string what = std::string(c.Name) + ", OpenCL in pieces";
      CHECK(onDevice, what + ": every rank traced on the device");
      CHECK(SameSums(got[0], got[1]), what + ": 2 slabs and 4 uneven blocks give the same film, bit for bit");
      CHECK(got[1].Photons == expected.Photons && dmax <= 1e-5 * scale,
        what + ": one process on the device within float rounding (deflection sums " +
          std::to_string(dmax / scale) + " of the largest)");
      std::printf("%-50s vs one process on the device: %.2e of the largest deflection sum\n",
        what.c_str(), dmax / scale);
    }
  }

  // line of sight needs no ray passing: each rank integrates the steps in its cells and the runs
  // add up on rank 0. The sums are reassociated (a ray's w is a sum of a few partial sums instead
  // of one running sum), so the records equal one process's within float rounding, not bit for
  // bit: deflections and landing points within 1e-5 of the largest deflection and of a pixel
  {
    TraceSettings s;
    s.Method = Integrator::Straight;
    s.StepSize = 1.0;
    s.Device = Backend::CPU;
    s.Resolution[0] = s.Resolution[1] = 24;
    s.ViewDirection[0] = 0.4;
    s.ViewDirection[1] = 0.3;
    s.ViewDirection[2] = -1;
    s.Mode = Cutoff::Interferometry;
    std::vector<float> ab;
    const FilmGeometry film = MakeFilm(gauss.V, s);
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i)
      {
        ab.push_back(static_cast<float>(film.Corner[0] + (i + 0.5) * film.PixelSize));
        ab.push_back(static_cast<float>(film.Corner[1] + (j + 0.5) * film.PixelSize));
      }
    const std::vector<RayRecord> expected = TraceRays(gauss.V, s, ab);
    double emax = 0;
    for (const RayRecord& r : expected)
      emax = std::max(emax, std::hypot(double(r.DeflX), double(r.DeflY)));
    for (const auto& d : decos)
    {
      const int ranks = static_cast<int>(d.second.size());
      std::vector<std::vector<float>> values(ranks);
      for (int r = 0; r < ranks; ++r)
        values[r] = Cut(gauss, d.second[r]);
      std::mutex m;
      double de = 0, dl = 0, dopl = 0, handed = 0, rounds = 0;
      bool flags = true, counts = true;
      RunInProcessRanks(ranks, [&](Parallel& p) {
        DistributedVolume dv(PieceOf(gauss, d.second[p.Rank()], values[p.Rank()]), GhostPointsFor(s), p);
        DistributedStats st;
        const std::vector<RayRecord> got = TraceRaysDistributed(dv, s, ab, p, true, &st);
        std::lock_guard<std::mutex> lock(m);
        handed += st.RaysHandedOn;
        rounds = std::max(rounds, st.Rounds);
        for (std::size_t k = 0; k < got.size(); ++k)
        {
          const RayRecord &a = got[k], &b = expected[k];
          de = std::max(de, std::hypot(double(a.DeflX - b.DeflX), double(a.DeflY - b.DeflY)));
          dl = std::max(dl, std::hypot(double(a.LandA - b.LandA), double(a.LandB - b.LandB)));
          dopl = std::max(dopl, std::fabs(double(a.OpticalPathExcess - b.OpticalPathExcess)) /
              std::max(1e-30, std::fabs(double(b.OpticalPathExcess))));
          flags = flags && a.Flags == b.Flags;
          counts = counts && a.Samples == b.Samples && a.Steps == b.Steps &&
            std::fabs(a.Path - b.Path) <= 1e-6f * b.Path;
        }
      });
      const std::string what = std::string("line of sight in pieces, ") + d.first;
      CHECK(de <= 1e-5 * emax, what + ": deflections within 1e-5 of the largest (" +
          std::to_string(de / emax) + ")");
      CHECK(dl <= 1e-5 * film.PixelSize, what + ": landing within 1e-5 pixel (" +
          std::to_string(dl / film.PixelSize) + ")");
      CHECK(dopl <= 1e-5, what + ": optical path within 1e-5 (" + std::to_string(dopl) + ")");
      CHECK(flags && counts, what + ": the same flags, samples and steps as one process, the path within 1e-6");
      std::printf("%-50s deflection %.2e of the largest, landing %.2e pixel, optical path %.2e\n",
        what.c_str(), de / emax, dl / film.PixelSize, dopl);
      CHECK(handed == 0 && rounds <= 1, what + ": no ray passed between ranks, one exchange");
    }
  }

  // the shadowgraph has caustics: photons pile up (a pixel with several times the mean count)
  {
    TraceSettings s;
    for (const Case& c : cases)
      if (std::string(c.Name) == "Gaussian shadowgraph, caustics")
        s = c.Settings;
    s.Device = Backend::CPU;
    FilmSums f;
    Accumulate(gauss.V, s, f);
    double peak = 0, mean = 0;
    for (double c : f.Count)
    {
      peak = std::max(peak, c);
      mean += c / f.Count.size();
    }
    CHECK(peak > 4 * mean, "the shadowgraph case has caustics (peak count over 4 x the mean)");
  }

  // a ray that crosses a piece several times: the Luneburg lens in 4 blocks across the beam
  {
    Case& c = cases[1];
    const Decomposition d = Blocks(n, { 0.5 }, { 0.5 }, {});
    std::vector<std::vector<float>> values(4);
    for (int r = 0; r < 4; ++r)
      values[r] = Cut(luneburg, d[r]);
    std::vector<float> ab;
    TraceSettings s = c.Settings;
    s.Device = Backend::CPU;
    // rays that pass close to the lens axis: they bend through the centre, across block faces
    for (int k = 0; k < 64; ++k)
    {
      ab.push_back(static_cast<float>(-0.05 + 0.1 * (k % 8) / 7.0));
      ab.push_back(static_cast<float>(-0.05 + 0.1 * (k / 8) / 7.0));
    }
    double handed = 0;
    std::mutex m;
    RunInProcessRanks(4, [&](Parallel& p) {
      DistributedVolume dv(PieceOf(luneburg, d[p.Rank()], values[p.Rank()]),
        GhostPointsFor(s), p);
      DistributedStats st;
      TraceRaysDistributed(dv, s, ab, p, true, &st);
      std::lock_guard<std::mutex> lock(m);
      handed += st.RaysHandedOn;
    });
    std::printf("Luneburg near-axis rays: %.0f hand-offs for 64 rays\n", handed);
    CHECK(handed > 64, "near-axis rays through the lens cross block faces more than once each on average");
  }

  // Auto on pieces: every rank makes one process's choice (with the octree: it may keep it)
  for (double tol : { -1.0, 2e-6 })
  {
    TraceSettings s;
    s.Method = Integrator::Auto;
    s.Device = Backend::CPU;
    s.Resolution[0] = s.Resolution[1] = 24;
    s.ViewDirection[0] = 0.6;
    s.ViewDirection[2] = -0.8;
    std::vector<unsigned char> levels, smooth;
    std::vector<float> cubic;
    const Volume whole = WholeVolume(gauss, tol, levels, false, cubic, smooth);
    AutoChoice one;
    const TraceSettings expected = ResolveAuto(whole, s, &one);
    const Decomposition d = Blocks(n, { 0.4 }, {}, { 0.6 });
    std::vector<std::vector<float>> values(4);
    for (int r = 0; r < 4; ++r)
      values[r] = Cut(gauss, d[r]);
    std::mutex m;
    bool same = true;
    RunInProcessRanks(4, [&](Parallel& p) {
      const int ghost = GhostPointsFor(s, tol >= 0 ? DistributedOctreeMaxLevel : 0);
      const Piece piece = PieceOf(gauss, d[p.Rank()], values[p.Rank()]);
      DistributedVolume dv = tol >= 0 ? DistributedVolume(piece, ghost, p, tol)
                                      : DistributedVolume(piece, ghost, p);
      AutoChoice c;
      const TraceSettings got = ResolveAutoDistributed(dv, s, p, &c);
      std::lock_guard<std::mutex> lock(m);
      same = same && got.Method == expected.Method && got.StepSize == expected.StepSize &&
        got.UseOctree == expected.UseOctree && c.ExpectedError == one.ExpectedError &&
        c.SamplesPerRay == one.SamplesPerRay;
    });
    CHECK(same, std::string("Auto on 4 ranks makes one process's choice") +
        (tol >= 0 ? " (with the octree)" : "") + ": " + one.Report);
  }

  // bad pieces: the same error on every rank, no hang
  {
    const Decomposition d = Blocks(n, {}, {}, { 0.5 });
    std::vector<std::vector<float>> values = { Cut(gauss, d[0]), Cut(gauss, d[1]) };
    values[1].back() = std::nanf(""); // far from rank 0's ghosts
    std::vector<std::string> messages(2);
    RunInProcessRanks(2, [&](Parallel& p) {
      try
      {
        DistributedVolume dv(PieceOf(gauss, d[p.Rank()], values[p.Rank()]), 4, p);
      }
      catch (const Error& e)
      {
        messages[p.Rank()] = e.what();
      }
    });
    CHECK(messages[1].find("NaN") != std::string::npos || messages[1].find("not finite") != std::string::npos ||
        messages[1].find("nan") != std::string::npos,
      "a NaN in rank 1's piece is named: " + messages[1]);
    CHECK(messages[0].find("another rank (1) failed") != std::string::npos,
      "rank 0 reports rank 1's failure: " + messages[0]);
  }
  {
    // overlapping pieces, and a gap
    const Decomposition overlap = { { 0, n - 1, 0, n - 1, 0, 25 }, { 0, n - 1, 0, n - 1, 20, n - 1 } };
    const Decomposition gap = { { 0, n - 1, 0, n - 1, 0, 15 }, { 0, n - 1, 0, n - 1, 20, n - 1 } };
    for (int which = 0; which < 2; ++which)
    {
      const Decomposition& d = which ? gap : overlap;
      std::vector<std::vector<float>> values = { Cut(gauss, d[0]), Cut(gauss, d[1]) };
      std::vector<std::string> messages(2);
      RunInProcessRanks(2, [&](Parallel& p) {
        try
        {
          DistributedVolume dv(PieceOf(gauss, d[p.Rank()], values[p.Rank()]), 4, p);
        }
        catch (const Error& e)
        {
          messages[p.Rank()] = e.what();
        }
      });
      const char* word = which ? "uncovered" : "overlap";
      CHECK(messages[0] == messages[1] && messages[0].find(word) != std::string::npos &&
          messages[0].find("empty on rank") == std::string::npos,
        std::string("pieces that ") + (which ? "leave a gap" : "overlap") + " are refused on both ranks: " +
          messages[0]);
    }
    // a gap where a rank's piece is empty (its upstream failed without the pipeline knowing: a
    // Python source that raised): the rank is named
    const Decomposition half = { { 0, n - 1, 0, n - 1, 0, 20 }, { 0, -1, 0, -1, 0, -1 } };
    std::vector<std::vector<float>> values = { Cut(gauss, half[0]), {} };
    std::vector<std::string> messages(2);
    RunInProcessRanks(2, [&](Parallel& p) {
      try
      {
        Piece piece = PieceOf(gauss, half[p.Rank()], values[p.Rank()]);
        if (p.Rank() == 1)
          piece.NMinus1 = nullptr;
        DistributedVolume dv(piece, 4, p);
      }
      catch (const Error& e)
      {
        messages[p.Rank()] = e.what();
      }
    });
    CHECK(messages[0] == messages[1] &&
        messages[0].find("uncovered: pieces must tile it (empty on rank 1: if a filter upstream reported an "
                         "error there, that is the cause)") != std::string::npos,
      "a gap left by rank 1's empty piece names rank 1 on both ranks: " + messages[0]);
  }
  // a rank with an empty piece (more ranks than a reader splits into): it owns nothing, holds
  // nothing, and the image is still one process's
  {
    const Decomposition d = { { 0, n - 1, 0, n - 1, 0, 20 }, { 0, -1, 0, -1, 0, -1 },
      { 0, n - 1, 0, n - 1, 20, n - 1 } };
    std::vector<std::vector<float>> values = { Cut(gauss, d[0]), {}, Cut(gauss, d[2]) };
    TraceSettings s = cases[0].Settings;
    s.Device = Backend::CPU;
    FilmSums expected;
    Accumulate(gauss.V, s, expected);
    bool same = false, empty = false;
    std::mutex m;
    RunInProcessRanks(3, [&](Parallel& p) {
      Piece piece = PieceOf(gauss, d[p.Rank()], values[p.Rank()]);
      if (p.Rank() == 1)
        piece.NMinus1 = nullptr;
      DistributedVolume dv(piece, GhostPointsFor(s), p);
      FilmSums sums;
      AccumulateDistributed(dv, s, sums, p);
      std::lock_guard<std::mutex> lock(m);
      if (p.Rank() == 0)
        same = SameSums(sums, expected);
      if (p.Rank() == 1)
        empty = dv.Packed.empty();
    });
    CHECK(same && empty, "a rank with an empty piece holds nothing; the film is one process's");
  }
  // a share that does not fit in memory is refused on every rank (SCHLIEREN_MEMORY_LIMIT's option)
  {
    const Decomposition d = Blocks(n, {}, {}, { 0.5 });
    std::vector<std::vector<float>> values = { Cut(gauss, d[0]), Cut(gauss, d[1]) };
    std::vector<std::string> messages(2);
    {
      schtest::ScopedOptions small([](RuntimeOptions& o) { o.MemoryLimit = 100000; });
      RunInProcessRanks(2, [&](Parallel& p) {
        try
        {
          DistributedVolume dv(PieceOf(gauss, d[p.Rank()], values[p.Rank()]), 4, p);
        }
        catch (const Error& e)
        {
          messages[p.Rank()] = e.what();
        }
      });
    }
    CHECK(messages[0].find("share of the volume") != std::string::npos &&
        messages[1].find("share of the volume") != std::string::npos &&
        messages[0].find("more ranks") != std::string::npos,
      "a share too large for memory is refused on both ranks: " + messages[0]);
  }
  // a step longer than the ghosts allow is refused, not traced wrong
  {
    const Decomposition d = Blocks(n, {}, {}, { 0.5 });
    std::vector<std::vector<float>> values = { Cut(gauss, d[0]), Cut(gauss, d[1]) };
    std::vector<std::string> messages(2);
    RunInProcessRanks(2, [&](Parallel& p) {
      DistributedVolume dv(PieceOf(gauss, d[p.Rank()], values[p.Rank()]), 3, p);
      TraceSettings s;
      s.Resolution[0] = s.Resolution[1] = 8;
      s.StepSize = 4.0;
      try
      {
        FilmSums f;
        AccumulateDistributed(dv, s, f, p);
      }
      catch (const Error& e)
      {
        messages[p.Rank()] = e.what();
      }
    });
    CHECK(messages[0].find("ghost points") != std::string::npos && messages[0] == messages[1],
      "a step longer than the ghosts is refused: " + messages[0]);
  }
  return schtest::Finish();
}
