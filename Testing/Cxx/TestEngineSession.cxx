// SPDX-License-Identifier: BSD-3-Clause
// The engine's TraceSession (what a SchlierenImage runs) on 1, 2 and 3 in-process ranks with
// TraceInPieces off, each rank given a different slab of one scene's volume (with an octree whose
// piece levels must be rebuilt
// and a solid body in one slab only):
// - every rank assembles the whole volume bit for bit as one rank packs it;
// - the image on rank 0 equals the one-rank image bit for bit. Why exact: every rank holds the
//   same assembled volume and traces with rank 0's Auto choice; a pixel's photons are traced by
//   one rank only and the others add 0 to its sums; the counts and totals are whole numbers; the
//   maxima are exact. One caveat would be a photon that lands in a pixel other ranks' photons
//   also land in (sums in another order), which the focused knife edge here does not produce
//   (the test would show it);
// - progressive refinement: 1 pass and then 3 traces 2 more and equals 3 passes at once;
// - a failure on some ranks (NaN in one rank's piece, a problem or a failed read on one rank,
//   pieces that do not cover the volume) ends with an Error on every rank, with the failing
//   rank's message on all of them, and no hang.
#include "SchlierenSession.h"
#include "SchlierenTesting.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>

using namespace schlieren;

namespace
{

const int Dims[3] = { 22, 20, 18 };
const double Lo = -1.0, Hi = 1.0;

/** The scene on the whole grid: n - 1, the octree levels of the whole volume and a body. */
struct Whole
{
  std::vector<float> N1;
  std::vector<unsigned char> Levels, Solid;
  double Spacing[3];
  double Tolerance = 0;
  Whole()
  {
    const double origin[3] = { Lo, Lo, Lo };
    for (int a = 0; a < 3; ++a)
      Spacing[a] = (Hi - Lo) / (Dims[a] - 1);
    const std::size_t n = static_cast<std::size_t>(Dims[0]) * Dims[1] * Dims[2];
    N1.resize(n);
    SceneParameters p;
    p.Amplitude = 1e-4;
    p.Width = 0.35;
    p.Center[0] = 0.1;
    p.Center[1] = -0.05;
    FillScene(Scene::GaussianSphere, p, Dims, origin, Spacing, N1.data(), nullptr);
    Tolerance = 1e-6;
    Levels.resize(n);
    ComputeOctreeLevels(Dims, N1.data(), Tolerance, Levels.data(), 7);
    // a small sphere in the upper z slab only (z > 0.4): the other pieces have no body
    BodyParameters b;
    b.Shape = Body::Sphere;
    b.Radius = 0.25;
    b.Center[0] = -0.3;
    b.Center[2] = 0.65;
    Solid.resize(n);
    FillBody(b, Dims, origin, Spacing, Solid.data());
  }
};

/** Rank r's piece: a slab along `axis` (point extents; `overlap`: neighbours share a layer, as
 * VTK's extent translator splits them). */
VolumePiece Slab(int r, int n, int axis, bool overlap)
{
  VolumePiece piece;
  for (int a = 0; a < 3; ++a)
  {
    piece.WholeExtent[2 * a] = 0;
    piece.WholeExtent[2 * a + 1] = Dims[a] - 1;
    piece.Extent[2 * a] = 0;
    piece.Extent[2 * a + 1] = Dims[a] - 1;
    piece.Origin[a] = Lo;
    piece.Spacing[a] = (Hi - Lo) / (Dims[a] - 1);
  }
  const int cells = Dims[axis] - 1;
  const int lo = r * cells / n, hi = (r + 1) * cells / n;
  piece.Extent[2 * axis] = (overlap || r == 0) ? lo : lo + 1;
  piece.Extent[2 * axis + 1] = hi;
  piece.Version = 7;
  return piece;
}

/** Fills `values` from the whole arrays over the piece's extent; the levels are the piece's own
 * (as RefractionOctree computes them on a piece: they stop at its borders). */
void Cut(const Whole& w, const VolumePiece& piece, PieceValues& values, bool withLevels)
{
  const int* e = piece.Extent;
  const int pd[3] = { e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1 };
  values.NMinus1.clear();
  values.Solid.clear();
  bool anySolid = false;
  for (int k = e[4]; k <= e[5]; ++k)
    for (int j = e[2]; j <= e[3]; ++j)
      for (int i = e[0]; i <= e[1]; ++i)
      {
        const std::size_t at = (static_cast<std::size_t>(k) * Dims[1] + j) * Dims[0] + i;
        values.NMinus1.push_back(w.N1[at]);
        values.Solid.push_back(w.Solid[at]);
        anySolid = anySolid || w.Solid[at];
      }
  if (!anySolid)
    values.Solid.clear(); // as the filter gives it: no body in this piece
  if (withLevels)
  {
    values.Levels.resize(values.NMinus1.size());
    ComputeOctreeLevels(pd, values.NMinus1.data(), w.Tolerance, values.Levels.data(), 7);
    values.HasLevelTolerance = true;
    values.LevelTolerance = w.Tolerance;
    values.MaxLevel = 7;
  }
}

TraceSettings Settings(int passes, bool autoIntegrator)
{
  TraceSettings s;
  s.Resolution[0] = 30;
  s.Resolution[1] = 26;
  s.Passes = passes;
  s.Seed = 5;
  s.ViewDirection[0] = 0.2;
  s.ViewDirection[1] = -0.1;
  s.ViewDirection[2] = -1.0;
  s.Mode = Cutoff::KnifeEdge;
  s.KnifeAngle = 30.0;
  s.Method = autoIntegrator ? Integrator::Auto : Integrator::RK4;
  s.Device = Backend::CPU;
  // the whole-volume path (TraceInPieces off): every rank assembles the volume. The pieces path
  // (a body included) has its own tests: TestEngineDistributed, python.mpi_cases, solids_mpi
  s.InPieces = false;
  return s;
}

bool SameImage(const TraceResult& a, const TraceResult& b)
{
  return a.Intensity == b.Intensity && a.Deflection == b.Deflection && a.Blocked == b.Blocked &&
    a.Photons == b.Photons && a.Samples == b.Samples && a.BlockedRays == b.BlockedRays &&
    a.CutoffScaleUsed == b.CutoffScaleUsed;
}

/** What one configuration gives on rank 0: the image, and per rank the assembled volume. */
struct Run
{
  SessionImage First, Second; // Passes 1, then 3 (or one update only)
  std::vector<std::vector<float>> Fields;     // per rank: the kept packed field
  std::vector<std::vector<unsigned char>> Levels, Solids;
  std::vector<std::string> Errors;            // per rank: the error, if any
};

Run RunSession(const Whole& w, int n, int axis, bool overlap, bool autoIntegrator,
  const std::function<void(int, VolumePiece&)>& spoil = nullptr, bool twoUpdates = true,
  bool inPieces = false)
{
  Run run;
  run.Fields.resize(n);
  run.Levels.resize(n);
  run.Solids.resize(n);
  run.Errors.resize(n);
  std::mutex m;
  RunInProcessRanks(n, [&](Parallel& p) {
    const int r = p.Rank();
    VolumePiece piece = n == 1 ? Slab(0, 1, axis, true) : Slab(r, n, axis, overlap);
    piece.Load = [&w, piece](PieceValues& v) {
      Cut(w, piece, v, true);
      return std::string();
    };
    if (spoil)
      spoil(r, piece);
    TraceSession session;
    SessionImage first, second;
    std::string error;
    try
    {
      TraceSettings s = Settings(twoUpdates ? 1 : 3, autoIntegrator);
      s.InPieces = inPieces;
      session.Update(p, piece, s, first);
      if (twoUpdates)
      {
        s.Passes = 3;
        session.Update(p, piece, s, second);
      }
    }
    catch (const Error& e)
    {
      error = e.what();
    }
    const Volume& v = session.KeptVolume();
    std::lock_guard<std::mutex> lock(m);
    run.Errors[r] = error;
    if (v.Field)
    {
      run.Fields[r].assign(v.Field, v.Field + 4 * v.NumberOfPoints());
      if (v.Levels)
        run.Levels[r].assign(v.Levels, v.Levels + v.NumberOfPoints());
      if (v.Solid)
        run.Solids[r].assign(v.Solid, v.Solid + v.NumberOfPoints());
    }
    if (r == 0)
    {
      run.First = first;
      run.Second = second;
    }
  });
  return run;
}

} // namespace

int main()
{
  const Whole w;
  std::size_t solidPoints = 0;
  for (unsigned char s : w.Solid)
    solidPoints += s;
  CHECK(solidPoints > 0, "the scene has a body");

  // the single-rank reference (the whole volume in one piece: its levels taken as they are)
  const Run one = RunSession(w, 1, 2, true, false);
  CHECK(one.Errors[0].empty(), "one rank traces: " + one.Errors[0]);
  CHECK(one.First.HasImage && one.Second.HasImage, "rank 0 has the image");
  CHECK(one.Second.PassesTraced == 2 && one.Second.Passes == 3,
    "raising Passes from 1 to 3 traces the 2 new passes only (traced " +
      std::to_string(one.Second.PassesTraced) + ")");
  CHECK(one.Second.OctreeUsed && one.Second.OctreeTolerance == w.Tolerance,
    "the octree is used at its tolerance");
  CHECK(one.Second.Result.BlockedRays > 0, "the body stops rays");
  CHECK(one.Levels[0] == w.Levels, "one rank: the piece's levels are the volume's");
  CHECK(one.Solids[0] == w.Solid, "one rank: the solid points are the body's");
  {
    // 3 passes at once on a fresh session: the same image as 1 + 2
    const Run once = RunSession(w, 1, 2, true, false, nullptr, false);
    CHECK(once.First.PassesTraced == 3 && SameImage(once.First.Result, one.Second.Result),
      "1 pass then 2 more equals 3 passes at once, bit for bit");
  }

  struct Config
  {
    int Ranks, Axis;
    bool Overlap, Auto;
  } configs[] = { { 2, 2, true, false }, { 3, 1, false, false }, { 3, 2, true, false } };
  for (const Config& c : configs)
  {
    const std::string name = std::to_string(c.Ranks) + " ranks, slabs along " + "xyz"[c.Axis] +
      (c.Overlap ? " sharing a layer" : "");
    const Run run = RunSession(w, c.Ranks, c.Axis, c.Overlap, c.Auto);
    bool ok = true;
    for (int r = 0; r < c.Ranks; ++r)
      ok = ok && run.Errors[r].empty();
    CHECK(ok, name + ": every rank traces");
    bool sameVolume = true;
    for (int r = 0; r < c.Ranks; ++r)
      sameVolume = sameVolume && run.Fields[r] == one.Fields[0] && run.Levels[r] == w.Levels &&
        run.Solids[r] == w.Solid;
    CHECK(sameVolume,
      name + ": every rank assembles the one-rank volume bit for bit (field, rebuilt levels, body)");
    CHECK(run.First.HasImage && SameImage(run.First.Result, one.First.Result),
      name + ": 1 pass: the one-rank image bit for bit");
    CHECK(run.Second.HasImage && SameImage(run.Second.Result, one.Second.Result) &&
        run.Second.PassesTraced == 2,
      name + ": then 3 passes (2 traced): the one-rank image bit for bit");
  }

  // Integrator Auto: chosen on rank 0, the same image on 3 ranks as on one
  {
    const Run a1 = RunSession(w, 1, 2, true, true, nullptr, false);
    const Run a3 = RunSession(w, 3, 2, true, true, nullptr, false);
    CHECK(a1.Errors[0].empty() && a3.Errors[0].empty() && a3.Errors[2].empty(),
      "Auto traces on 1 and 3 ranks");
    // (the reports differ only in the pilot's time)
    CHECK(a1.First.AutoAsked && a3.First.AutoAsked && !a3.First.Choice.Report.empty() &&
        a3.First.Traced.Method == a1.First.Traced.Method &&
        a3.First.Traced.StepSize == a1.First.Traced.StepSize,
      std::string("Auto chooses the same on 3 ranks (") + IntegratorName(a3.First.Traced.Method) +
        " at " + std::to_string(a3.First.Traced.StepSize) + " voxel) as on one (" +
        IntegratorName(a1.First.Traced.Method) + ")");
    CHECK(SameImage(a3.First.Result, a1.First.Result), "Auto on 3 ranks: the one-rank image bit for bit");
  }

  // failures: the failing rank's message on every rank, no hang
  auto agreed = [](const Run& run, const std::string& message, int failing) {
    bool ok = true;
    for (int r = 0; r < static_cast<int>(run.Errors.size()); ++r)
    {
      const std::string& e = run.Errors[r];
      const std::string expected =
        r == failing ? message : "another rank (" + std::to_string(failing) + ") failed: " + message;
      if (e != expected)
      {
        std::printf("  rank %d: '%s'\n  expected '%s'\n", r, e.c_str(), expected.c_str());
        ok = false;
      }
    }
    return ok;
  };
  {
    // NaN in rank 1's piece: every rank assembles it and finds it (the same message everywhere)
    const Run run = RunSession(w, 3, 2, true, false, [&w](int r, VolumePiece& piece) {
      if (r == 1)
        piece.Load = [&w, piece](PieceValues& v) {
          Cut(w, piece, v, true);
          v.NMinus1[v.NMinus1.size() / 2] = std::numeric_limits<float>::quiet_NaN();
          return std::string();
        };
    });
    bool same = !run.Errors[0].empty() && run.Errors[0].find("NaN") != std::string::npos;
    for (const std::string& e : run.Errors)
      same = same && e == run.Errors[0];
    CHECK(same, "NaN in rank 1's piece: the same error on every rank: " + run.Errors[0]);
  }
  {
    const std::string problem = "SchlierenImage traces axis-aligned images only (test)";
    const Run run = RunSession(w, 3, 1, false, false, [&problem](int r, VolumePiece& piece) {
      if (r == 2)
        piece.Problem = problem;
    });
    CHECK(agreed(run, problem, 2), "a problem on rank 2: its message on every rank");
  }
  {
    const std::string unreadable = "SchlierenImage needs the point array 'n_minus_1' (test)";
    const Run run = RunSession(w, 2, 2, true, false, [&unreadable](int r, VolumePiece& piece) {
      if (r == 1)
        piece.Load = [&unreadable](PieceValues&) { return unreadable; };
    });
    CHECK(agreed(run, unreadable, 1), "a piece that cannot be read on rank 1: its message on every rank");
  }
  {
    // rank 1 holds nothing: a gap in the whole extent, the same error on every rank
    const Run run = RunSession(w, 3, 2, false, false, [](int r, VolumePiece& piece) {
      if (r == 1)
      {
        const int empty[6] = { 0, -1, 0, -1, 0, -1 };
        std::memcpy(piece.Extent, empty, sizeof empty);
      }
    });
    bool same = run.Errors[0].find("do not cover") != std::string::npos;
    for (const std::string& e : run.Errors)
      same = same && e == run.Errors[0];
    CHECK(same, "pieces with a gap: the same error on every rank: " + run.Errors[0]);
  }
  for (bool inPieces : { false, true })
  {
    const std::string path = inPieces ? " (in pieces)" : " (the whole volume on every rank)";
    // rank 1 has no grid at all: its input's information failed there alone (a reader of a file
    // missing on that rank, as fuzz_mpi draws it). Before, the collectives sized by the whole
    // grid then differed between the ranks: MPI_ERR_TRUNCATE, and the job aborted
    const Run none = RunSession(w, 3, 2, false, false, [](int r, VolumePiece& piece) {
      if (r == 1)
      {
        const int empty[6] = { 0, -1, 0, -1, 0, -1 };
        std::memcpy(piece.Extent, empty, sizeof empty);
        std::memcpy(piece.WholeExtent, empty, sizeof empty);
      }
    }, true, inPieces);
    CHECK(agreed(none, "The input volume is empty on rank 1: nothing to trace. If a filter upstream "
                       "reported an error there, that is the cause; fix it there.", 1),
      "no grid on rank 1: its message on every rank" + path);
    // rank 2's piece of another grid (its whole extent one point longer)
    const Run other = RunSession(w, 3, 2, false, false, [](int r, VolumePiece& piece) {
      if (r == 2)
        piece.WholeExtent[1] += 1;
    }, true, inPieces);
    bool said = true;
    for (const std::string& e : other.Errors)
      said = said && e.find("the ranks' pieces are not of one grid: whole extent component 1 is") != std::string::npos;
    CHECK(said, "rank 2's piece of another grid: refused on every rank" + path + ": " + other.Errors[0]);
  }
  {
    // one rank: an empty input is an error; Passes below 1 too
    const Run empty = RunSession(w, 1, 2, true, false, [](int, VolumePiece& piece) {
      const int none[6] = { 0, -1, 0, -1, 0, -1 };
      std::memcpy(piece.Extent, none, sizeof none);
    });
    CHECK(empty.Errors[0] == "SchlierenImage: the input image is empty.",
      "one rank, no points: " + empty.Errors[0]);
  }
  // Auto's choice kept across a camera move: only the view changed, so the pilot does not run and
  // the image is that of the kept setting traced for the new view; at rest (the same view again)
  // it runs again
  {
    VolumePiece piece = Slab(0, 1, 2, true);
    piece.Load = [&w, piece](PieceValues& v) {
      Cut(w, piece, v, true);
      return std::string();
    };
    Parallel& p = SerialParallel();
    TraceSession session;
    TraceSettings s = Settings(1, true);
    SessionImage a, b, c, d, e;
    session.Update(p, piece, s, a);
    CHECK(session.Pilots() == 1 && !a.Choice.Reused, "Auto: the first update runs the pilot");
    s.ViewDirection[0] = -0.3;
    s.ViewDirection[1] = 0.25;
    session.Update(p, piece, s, b);
    CHECK(session.Pilots() == 1 && b.Choice.Reused &&
        b.Choice.Report.find("kept from the previous update") != std::string::npos,
      "Auto: a camera move keeps the choice, no pilot: " + b.Choice.Report);
    CHECK(b.Traced.Method == a.Traced.Method && b.Traced.StepSize == a.Traced.StepSize,
      "Auto: the kept choice is traced");
    TraceSettings fixed = s;
    fixed.Method = b.Traced.Method;
    fixed.StepSize = b.Traced.StepSize;
    fixed.Recon = b.Traced.Recon;
    fixed.UseOctree = b.Traced.UseOctree;
    TraceSession fresh;
    SessionImage f;
    fresh.Update(p, piece, fixed, f);
    CHECK(SameImage(b.Result, f.Result), "Auto, kept choice: the image of the same fixed settings, bit for bit");
    // at rest: the refinement's passes at the same view pilot again, for this view
    s.Passes = 3;
    session.Update(p, piece, s, c);
    CHECK(session.Pilots() == 2 && !c.Choice.Reused, "Auto: the camera at rest pilots again");
    // the same view and film as that pilot's: kept (a pilot would choose the same)
    s.Passes = 4;
    session.Update(p, piece, s, d);
    CHECK(session.Pilots() == 2 && !d.Choice.Reused && d.PassesTraced == 1,
      "Auto: more passes at rest keep the choice and the passes");
    // issue 50: the pilot depends on the volume, the view and the tolerance, not on the seed or
    // the film's size: another seed, a finer film (its landing error, a few thousandths of a
    // pixel here, is still within half a pixel of it) and a coarser one keep the choice
    std::printf("Auto's kept choice: landing error %.3g pixel on the pilot's film\n",
      d.Choice.ExpectedLandingError);
    s.Seed = 11;
    session.Update(p, piece, s, e);
    CHECK(session.Pilots() == 2 && e.Traced.Method == c.Traced.Method &&
        e.Traced.StepSize == c.Traced.StepSize, "Auto: another seed keeps the choice: " + e.Choice.Report);
    s.Resolution[0] *= 2;
    s.Resolution[1] *= 2;
    session.Update(p, piece, s, e);
    CHECK(session.Pilots() == 2 && e.Choice.Report.find("kept for a 60 x 52 film") != std::string::npos,
      "Auto: a finer film keeps the choice where it lands within half a pixel: " + e.Choice.Report);
    s.Resolution[0] = 20;
    s.Resolution[1] = 16;
    session.Update(p, piece, s, e);
    CHECK(session.Pilots() == 2, "Auto: a coarser film keeps the choice");
    // another tolerance and another view (once the camera rests) pilot again
    s.Tolerance = 1e-5;
    session.Update(p, piece, s, e);
    CHECK(session.Pilots() == 3, "Auto: another tolerance pilots again");
    s.ViewDirection[0] = 0.4;
    session.Update(p, piece, s, e);
    CHECK(session.Pilots() == 3 && e.Choice.Reused, "Auto: a camera move keeps it");
    session.Update(p, piece, s, e);
    CHECK(session.Pilots() == 4, "Auto: another view pilots again at rest");
  }
  // the same on the pieces (2 in-process ranks, TraceInPieces): the pilot, traced on the pieces
  // with rays handed on, is kept across a seed and a film size and runs again for a tolerance
  {
    std::vector<int> pilots(2, -1), kept(2, -1), again(2, -1);
    std::vector<std::string> errors(2), reports(2);
    RunInProcessRanks(2, [&](Parallel& p) {
      const int r = p.Rank();
      VolumePiece piece = Slab(r, 2, 2, true);
      piece.Load = [&w, piece](PieceValues& v) {
        Cut(w, piece, v, true);
        return std::string();
      };
      TraceSession session;
      TraceSettings s = Settings(1, true);
      s.InPieces = true;
      SessionImage a, b;
      try
      {
        session.Update(p, piece, s, a);
        pilots[r] = session.Pilots();
        s.Seed = 12;
        s.Resolution[0] = 20;
        s.Resolution[1] = 16;
        session.Update(p, piece, s, b);
        kept[r] = session.Pilots();
        reports[r] = b.Choice.Report;
        s.Tolerance = 1e-5;
        session.Update(p, piece, s, b);
        again[r] = session.Pilots();
      }
      catch (const Error& e)
      {
        errors[r] = e.what();
      }
    });
    for (int r = 0; r < 2; ++r)
    {
      CHECK(errors[r].empty(), "pieces, Auto: no error: " + errors[r]);
      CHECK(pilots[r] == 1 && kept[r] == 1 && again[r] == 2,
        "pieces, Auto: a seed and a film keep the pilot, a tolerance runs it (rank " +
          std::to_string(r) + ": " + std::to_string(pilots[r]) + ", " + std::to_string(kept[r]) +
          ", " + std::to_string(again[r]) + "): " + reports[r]);
    }
  }
  return schtest::Finish();
}
