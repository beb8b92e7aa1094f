// SPDX-License-Identifier: BSD-3-Clause
// Integrator and Reconstruction Auto: the pilot rays, the candidates, the choice (ResolveAuto).
#include "SchlierenEngineInternal.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <map>
#include <tuple>
#include <sstream>
#include <string>
#include <vector>

namespace schlieren
{

namespace
{
std::string ToText(double v)
{
  std::ostringstream o;
  o.precision(3);
  o << v;
  return o.str();
}

// What a tricubic sample costs against a trilinear one when Auto weighs the two reconstructions:
// it reads 64 points instead of 8, mostly from the same cache lines (docs/PERFORMANCE.md has the
// measured ratio).
constexpr double CubicSampleCost = 3.0;

// The longest step Auto tries, voxels: StepSize's own limit (SchlierenLimits.cxx). The volume's
// diagonal bounds it before this does.
constexpr double MaxAutoStep = 1000.0;

// The share of the tolerance a step longer than 8 voxels may use on the pilot (see evaluate).
constexpr double LongStepMargin = 0.75;

// A step longer than 8 voxels meets only where no pilot ray missed more than this share of what a
// step saw (the kernel flags RayUnderresolved at 0.5, SchlierenPhysics.h): the image's rays lie
// between the pilot's, and the share grows smoothly with the step (on the Gaussian of width s,
// along an axis: 0.40 at 0.84 s, 0.51 at s; over all the steps' phases, 0.45 and 0.55), so the
// margin keeps them unflagged (issue 50: at 0.5 the 384^3 Gaussian at 1e-7 rad took 45.1 voxels,
// and 12 of 576 rays between the pilot's flagged).
constexpr double PilotFeatureShare = 0.45;

// Reconstruction and Integrator Auto: the trilinear's candidates are tried where its reference is
// within this many times the tolerance of the tricubic's (see ResolveAutoWith). Its long steps
// were measured at most 1.5 times closer to the tricubic reference than its own reference is
// (the 64^3 Gaussian: 2.14e-6 against 3.24e-6 rad); beyond that the trilinear's candidates only
// cost the pilot time (at 512^3 and 3e-8 rad, 5.1e-8 rad apart: 16 more traces, none met).
constexpr double TrilinearReach = 1.5;

// The pilot's references (RK4): the first step of their ladder, voxels, the finest, and the
// share of the tolerance that two successive steps may differ by for the finer to be the
// reference (see ResolveAutoWith).
constexpr double RefFirstStep = 2.0;
constexpr double RefFinestStep = 0.125;
constexpr double RefShare = 0.05;

// The tricubic reference's own error (issue 50): the reference is traced again on the field
// sampled at about twice the spacing (MakeCoarseField); a fourth-order reconstruction's error
// grows r^4 times with the spacing, so the difference of the two traces over r^4 - 1 is the
// reference's error at the grid's own spacing (on the Gaussian at 64^3, 128^3 and 256^3 the
// estimates were 9.5e-8, 6.2e-9 and 3.9e-10 rad: 15.2 and 16.0 times apart, the fourth order).
// Building the coarse field reads the whole volume (0.6-0.8 s at 256^3 on a loaded machine), so
// it is measured only where the tolerance may be within its reach: the trilinear's error E2
// (the two references' difference) is about (h/s)^2 of the largest deflection D for features s
// wide, the tricubic's E4 about (h/s)^2 E2, so E4 ~ E2^2 / D (on the Gaussian E4 = 2.8-3.0
// E2^2 / D at 64^3-256^3); checked where the tolerance is below RefCheckReach E2^2 / D, ten
// times the Gaussian's ratio.
constexpr double RefCheckReach = 30.0;
constexpr double RefFloorMargin = 1.5;
constexpr double RefCheckOrder = 4.0;
// the coarse field's smoothness threshold (PackFieldHighOrder's 0.25 at the grid's spacing): a
// feature's fourth difference relative to its range grows as h^2, 4 times at twice the spacing,
// so that the same cells are tricubic in both traces
constexpr double RefCheckSmoothness = 1.0;

// n - 1 of `v` on M = ceil((N - 1) / 2) + 1 points per axis over the same box (the fine points
// i (N - 1) / (M - 1)), by 4-point Lagrange interpolation along each axis in turn: exact where a
// coarse point is a fine one (N odd), fourth order elsewhere (its error is the fine
// reconstruction's, 1/16 of the coarse one's). `ratio`: the smallest coarse / fine spacing.
struct CoarseField
{
  int Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 0, 0, 0 };
  double Ratio = 2;
  std::vector<float> Packed;
  std::vector<unsigned char> Smooth;
};

bool MakeCoarseField(const Volume& v, CoarseField& c)
{
  int dims[3] = { v.Dimensions[0], v.Dimensions[1], v.Dimensions[2] };
  for (int a = 0; a < 3; ++a)
  {
    c.Dims[a] = dims[a] / 2 + 1; // ceil((N - 1) / 2) + 1
    if (dims[a] < 9)
      return false; // too few points for a tricubic stencil at twice the spacing
    c.Spacing[a] = v.Spacing[a] * (dims[a] - 1) / (c.Dims[a] - 1);
  }
  c.Ratio = std::min({ c.Spacing[0] / v.Spacing[0], c.Spacing[1] / v.Spacing[1], c.Spacing[2] / v.Spacing[2] });
  std::vector<double> cur(v.NumberOfPoints());
  for (std::size_t i = 0; i < cur.size(); ++i)
    cur[i] = v.Field[4 * i];
  for (int a = 0; a < 3; ++a)
  {
    const int n = dims[a], m = c.Dims[a];
    int out[3] = { dims[0], dims[1], dims[2] };
    out[a] = m;
    std::vector<double> next(static_cast<std::size_t>(out[0]) * out[1] * out[2]);
    const std::size_t stride = a == 0 ? 1 : (a == 1 ? std::size_t(dims[0]) : std::size_t(dims[0]) * dims[1]);
    const std::size_t ostride = a == 0 ? 1 : (a == 1 ? std::size_t(out[0]) : std::size_t(out[0]) * out[1]);
    for (int j = 0; j < m; ++j)
    {
      const double x = double(j) * (n - 1) / (m - 1);
      const int s0 = std::max(0, std::min(n - 4, static_cast<int>(std::floor(x)) - 1));
      double w[4];
      for (int q = 0; q < 4; ++q)
      {
        w[q] = 1;
        for (int r = 0; r < 4; ++r)
          if (r != q)
            w[q] *= (x - (s0 + r)) / double(q - r);
      }
      // every line along axis a: the other two indices
      const int o1 = a == 0 ? 1 : 0, o2 = a == 2 ? 1 : 2;
      for (int k2 = 0; k2 < dims[o2]; ++k2)
        for (int k1 = 0; k1 < dims[o1]; ++k1)
        {
          const std::size_t base = (o1 == 0 ? std::size_t(k1) : std::size_t(k1) * dims[0]) +
            (o2 == 1 ? std::size_t(k2) * dims[0] : std::size_t(k2) * dims[0] * dims[1]);
          const std::size_t obase = (o1 == 0 ? std::size_t(k1) : std::size_t(k1) * out[0]) +
            (o2 == 1 ? std::size_t(k2) * out[0] : std::size_t(k2) * out[0] * out[1]);
          double sum = 0;
          for (int q = 0; q < 4; ++q)
            sum += w[q] * cur[base + (s0 + q) * stride];
          next[obase + j * ostride] = sum;
        }
    }
    cur.swap(next);
    dims[a] = m;
  }
  std::vector<float> n1(cur.begin(), cur.end());
  c.Packed.resize(4 * n1.size());
  c.Smooth.resize(n1.size());
  PackFieldHighOrder(c.Dims, c.Spacing, n1.data(), c.Packed.data(), c.Smooth.data(), RefCheckSmoothness);
  return true;
}

// One reconstruction's reference: RK4 at Step (Fine) and at CoarseStep = 2 Step (Coarse), and
// the largest difference between the two over the pilot's rays, radians.
struct RefLadder
{
  std::vector<RayRecord> Fine, Coarse;
  double Step = 0, CoarseStep = 0, Diff = 0;
};


// Samples an integrator takes a step.
double Evaluations(Integrator m)
{
  return m == Integrator::RK4 ? 4.0 : (m == Integrator::Midpoint ? 2.0 : 1.0);
}

// A ray the pilot cannot compare: lost.
constexpr std::uint32_t LostFlags = RayMaxSteps | RayTurned | RayNonFinite | RayOffFilm;

// A ladder's last two traces agree on every ray's fate: none lost or stopped at one step and not
// at the other, and none where the finer step is still longer than a feature (the kernel's
// RayUnderresolved: two steps that both step over a feature may agree and both be wrong).
bool Converged(const RefLadder& L)
{
  for (std::size_t k = 0; k < L.Fine.size(); ++k)
    if (((L.Fine[k].Flags ^ L.Coarse[k].Flags) & (LostFlags | RayBlocked)) || (L.Fine[k].Flags & RayUnderresolved))
      return false;
  return true;
}

// Whether a trace has a ray that took a step longer than a feature, or within PilotFeatureShare of
// one (RayRecord::Mismatch), of those neither lost nor blocked.
bool SteppedOverFeature(const std::vector<RayRecord>& T)
{
  for (const RayRecord& r : T)
    if (!(r.Flags & (LostFlags | RayBlocked)) && ((r.Flags & RayUnderresolved) || r.Mismatch > PilotFeatureShare))
      return true;
  return false;
}

// The rays of a pilot that a comparison can use: neither lost.
bool Comparable(const RayRecord& a, const RayRecord& b)
{
  return !(a.Flags & LostFlags) && !(b.Flags & LostFlags);
}
} // namespace

// The pilot traces a few hundred rays in a dozen settings, and on OpenCL each setting is a program
// of its own (the kernel built with the integrator and reconstruction fixed, SCH_FIXED_*): on
// PoCL, each compiled for 0.4-1.8 s where its cache is cold (a new install, a new PoCL or a new
// kernel source), 12.4 s of the first update of the 512^3 Gaussian at the default tolerance and
// 4.3 s at its first oblique view. Where the OpenCL device is the CPU, the C++ build of the same
// physics runs on the same cores with nothing to compile: the pilot runs there (issue 50). A GPU
// keeps it: there the rays are cheap and the driver's compiler fast.
Backend PilotDevice(const TraceSettings& in)
{
  if (in.Device == Backend::CPU || OpenCLDeviceIsCPU(in.DeviceName))
    return Backend::CPU;
  return in.Device;
}

double AutoPiecesReach(bool cubic)
{
  return cubic ? 64.0 : 8.0;
}

TraceSettings ResolveAuto(const Volume& volume, const TraceSettings& in, AutoChoice* choice,
  bool piecesBound, const AutoChoice* start)
{
  if (in.Method == Integrator::Auto || in.Recon == Reconstruction::Auto)
    CheckVolume(volume);
  AutoVolume grid;
  grid.Grid = volume;
  grid.HasLevels = volume.Levels != nullptr;
  grid.HasSmooth = volume.Smooth != nullptr;
  grid.HasSolid = volume.Solid != nullptr;
  grid.PiecesBound = piecesBound;
  // A large smooth field traced from its copy at 4 or 2 times the spacing, where the copy is
  // certified within CoarseShare of the tolerance at every point (issue 50: a tricubic sample of
  // a 2 GiB field costs 2.2 times one of a field in the caches; the Gaussian at 512^3 holds no
  // more than a 128^3 copy carries). The pilot then runs on the copy, against the rest of the
  // tolerance, and so does the image: the device holds the copy, not the field.
  std::shared_ptr<const CoarseCopy> copy;
  double coarseMs = 0;
  if (CoarseEligible(volume, in, piecesBound))
  {
    const auto c0 = std::chrono::steady_clock::now();
    // 4 first; 2 where 4 was not smooth, or its bound is within 16 times the share (a fourth-order
    // reconstruction's error falls 16-fold at half the spacing: the Gaussian at 512^3, 1.1e-8 and
    // 1.7e-9 rad)
    const std::shared_ptr<const CoarseCopy> c4 = CoarseCopyOf(volume, 4);
    // Reconstruction Auto: where the field's own trilinear may meet the tolerance (the copy's
    // trilinear error over the spacings' ratio squared within TrilinearReach of it), a trilinear
    // sample of the field may be the cheapest: the field's own pilot decides, and no copy is
    // traced (issue 50: the 256^3 Gaussian at 1e-6 rad, Cubic Straight on the copy at 4 times the
    // spacing, 7 samples a ray, where Trilinear Straight on the field met with 8)
    const double r4 = c4 ? MinSpacing(c4->V) / MinSpacing(volume) : 4.0;
    const bool fieldTrilinear =
      in.Recon == Reconstruction::Auto && c4 && c4->TrilinearBound / (r4 * r4) <= TrilinearReach * in.Tolerance;
    if (fieldTrilinear)
      ;
    else if (c4 && c4->Bound <= CoarseShare * in.Tolerance)
      copy = c4;
    else if (!c4 || c4->Bound <= 16 * CoarseShare * in.Tolerance)
    {
      const std::shared_ptr<const CoarseCopy> c2 = CoarseCopyOf(volume, 2);
      if (c2 && c2->Bound <= CoarseShare * in.Tolerance)
        copy = c2;
    }
    coarseMs = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count() * 1e3;
  }
  if (!copy)
  {
    TraceSettings out = ResolveAutoWith(grid, in, choice,
      [&volume](const TraceSettings& t, const std::vector<float>& ab) { return TraceRays(volume, t, ab); },
      start);
    if (choice)
      choice->CoarseMs = coarseMs;
    return out;
  }
  const Volume& cv = copy->V;
  const double scale = MinSpacing(cv) / MinSpacing(volume); // the copy's voxel in the field's
  AutoVolume cg = grid;
  cg.Grid = cv;
  cg.HasLevels = false;
  cg.ReportScale = scale;
  TraceSettings cin = in;
  cin.Tolerance = in.Tolerance - copy->Bound;
  cin.UseOctree = false;
  // an earlier pilot's choice on the same copy: its steps in the copy's voxels (the field's
  // trilinear measured against the copy: FieldStride 1 and the copy's certificate)
  AutoChoice cstart;
  const AutoChoice* cs = nullptr;
  if (start && (start->FieldStride == copy->Stride || (start->FieldStride == 1 && start->CoarseBound == copy->Bound)))
  {
    cstart = *start;
    cstart.StepSize /= scale;
    for (double& st : cstart.ReferenceSteps)
      st /= scale;
    cs = &cstart;
  }
  // The copy stands for the field through its tricubic reconstruction, which the certificate
  // covers; its trilinear, twice as coarse or more, is not (the pilot's rays alone would answer
  // for it, and they miss what lies between them). With Reconstruction Auto the trilinear
  // candidates are the field's own: traced on the field (steps in the copy's voxels, as the pilot
  // counts them) and measured against the copy's tricubic reference, which is within the
  // certificate of the field's; the image then traces the field (issue 50: the 384^3 Gaussian at
  // 1e-7 rad, Cubic Straight on the copy, 10 samples a ray, where Trilinear Straight on the field
  // met with 9: 3.3 times the cost). On the CPU: the device keeps the copy the pilot traces, and
  // the field is not uploaded for 256 rays. Where the last pilot on this copy at this tolerance
  // found the field's trilinear too far off to try (TrilinearReach), it is not traced again: its
  // reference on the field (RK4 to a quarter of the field's voxel, through the trilinear's kinks)
  // took 230 of a 256 ms pilot at rest at 512^3 and 3e-8 rad, against 19 on the copy alone.
  const bool triRejected = cs && start->Tolerance == in.Tolerance && start->Recon == Reconstruction::Cubic &&
    start->TrilinearError > TrilinearReach * cin.Tolerance;
  const bool fieldTrilinearToo = in.Recon == Reconstruction::Auto && !triRejected;
  cin.Recon = fieldTrilinearToo ? Reconstruction::Auto : Reconstruction::Cubic;
  const PilotTracer onCopy = [&cv, &volume, scale](const TraceSettings& t, const std::vector<float>& ab) {
    if (t.Recon != Reconstruction::Trilinear)
      return TraceRays(cv, t, ab);
    TraceSettings f = t;
    f.StepSize = t.StepSize * scale;
    f.Device = Backend::CPU;
    return TraceRays(volume, f, ab);
  };
  AutoChoice c;
  TraceSettings out = ResolveAutoWith(cg, cin, &c, onCopy, cs);
  // where nothing met the rest of the tolerance on the copy: the field, with all of it, may
  if (!c.Met)
  {
    TraceSettings field = ResolveAutoWith(grid, in, choice,
      [&volume](const TraceSettings& t, const std::vector<float>& ab) { return TraceRays(volume, t, ab); },
      start && start->FieldStride == 1 ? start : nullptr);
    if (choice)
      choice->CoarseMs = coarseMs;
    return field;
  }
  if (triRejected && in.Recon == Reconstruction::Auto)
  {
    c.TrilinearError = start->TrilinearError; // the next pilot skips it too
    std::ostringstream tri;
    tri << " (the field's trilinear, " << start->TrilinearError
        << " rad off at the last pilot of this volume, not tried again)";
    c.Report += tri.str();
  }
  const bool onField = c.Recon == Reconstruction::Trilinear; // the field's trilinear was chosen
  out.Tolerance = in.Tolerance;
  out.UseOctree = in.UseOctree && out.UseOctree;
  out.StepSize *= scale;
  out.FieldStride = onField ? 1 : copy->Stride;
  c.StepSize *= scale;
  for (double& st : c.ReferenceSteps)
    st *= scale;
  c.FieldStride = out.FieldStride;
  c.CoarseBound = copy->Bound;
  c.Tolerance = in.Tolerance; // the whole: the copy's certificate and the pilot's share
  c.CoarseMs = coarseMs;
  std::ostringstream rep;
  // (not the word "spacing": VTK's legacy reader, which carries the image between ranks and to
  // the client, takes it in a string of field data for its keyword, and says "Error reading
  // spacing!")
  if (onField)
    rep << "; traced on the field itself, measured against the tricubic of a copy of the field";
  else
    rep << "; traced on a copy of the field";
  rep << " with 1 point in " << copy->Stride << " along each axis (" << cv.Dimensions[0] << " x "
      << cv.Dimensions[1] << " x " << cv.Dimensions[2] << " points, certified within " << copy->Bound
      << " rad of the field for every ray; the pilot's tolerance the rest, " << cin.Tolerance << " rad)";
  c.Report += rep.str();
  if (choice)
    *choice = c;
  return out;
}

TraceSettings ResolveAutoWith(const AutoVolume& grid, const TraceSettings& in, AutoChoice* choice,
  const PilotTracer& tracer, const AutoChoice* start)
{
  const Volume& volume = grid.Grid;
  // The pilot's rays on the device PilotDevice picks; the image keeps the one asked for.
  const Backend pilotDevice = PilotDevice(in);
  const PilotTracer traceRays = [&tracer, pilotDevice](const TraceSettings& t, const std::vector<float>& ab) {
    TraceSettings u = t;
    u.Device = pilotDevice;
    return tracer(u, ab);
  };
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
  bool tryTri = in.Recon == Reconstruction::Trilinear || (autoRecon) || grid.HasSolid;
  bool tryCubic = !grid.HasSolid && (in.Recon == Reconstruction::Cubic || (autoRecon && grid.HasSmooth));
  // Each reference only as fine as it needs to be (issue 50: at 1/8 voxel both references took
  // 1.7 s of a 2.2 s pilot at 512^3, on a field whose features are 64 voxels wide): RK4 from
  // RefFirstStep, halved while two successive traces differ by more than RefShare of the
  // tolerance (the default tolerance from the first trace), down to RefFinestStep. The finer of
  // the last two is the reference; their difference bounds its own error (RK4's falls 16-fold a
  // halving on smooth data, 4-fold through the trilinear's kinks) and is the floor's measure.
  std::map<int, RefLadder> refs;
  double tolGuess = in.Tolerance;
  // one rung down a ladder: the fine trace becomes the coarse one, RK4 at half its step the fine
  auto halve = [&](RefLadder& L, Reconstruction rc) {
    if (!L.Fine.empty())
    {
      L.Coarse.swap(L.Fine);
      L.CoarseStep = L.Step;
    }
    ref.Recon = rc;
    ref.StepSize = 0.5 * L.CoarseStep;
    L.Fine = traceRays(ref, ab);
    L.Step = ref.StepSize;
    L.Diff = 0;
    for (std::size_t k = 0; k < L.Fine.size(); ++k)
      if (Comparable(L.Fine[k], L.Coarse[k]) && !((L.Fine[k].Flags | L.Coarse[k].Flags) & RayBlocked))
        L.Diff = std::max(L.Diff,
          double(sch_hypot_d(L.Fine[k].DeflX - L.Coarse[k].DeflX, L.Fine[k].DeflY - L.Coarse[k].DeflY)));
  };
  for (Reconstruction rc : { Reconstruction::Cubic, Reconstruction::Trilinear })
  {
    if ((rc == Reconstruction::Trilinear && !tryTri) || (rc == Reconstruction::Cubic && !tryCubic))
      continue;
    RefLadder& L = refs[static_cast<int>(rc)];
    ref.Recon = rc;
    ref.StepSize = RefFirstStep;
    // an earlier pilot's ladder (another view of the same volume): from twice where it stopped
    const double before = start ? start->ReferenceSteps[rc == Reconstruction::Cubic ? 1 : 0] : 0.0;
    if (before >= RefFinestStep && before < RefFirstStep)
      ref.StepSize = 2 * before;
    L.Coarse = traceRays(ref, ab);
    L.CoarseStep = ref.StepSize;
    if (!(tolGuess > 0))
    {
      double e = 0;
      for (const RayRecord& r : L.Coarse)
        if (!(r.Flags & RayBlocked))
          e = std::max(e, double(sch_hypot_d(r.DeflX, r.DeflY)));
      tolGuess = 0.01 * e;
    }
    for (;;)
    {
      halve(L, rc);
      if (L.Step <= RefFinestStep || (Converged(L) && L.Diff <= RefShare * tolGuess))
        break;
    }
  }
  // Both references at one step: their difference is the trilinear's own error only where they
  // integrate alike (the normal shock at 96^3: the trilinear's ladder went to 1/8 voxel, the
  // tricubic's stopped at 1 voxel, where RK4 at 2 and 1 voxel agreed and both were 1.4e-6 rad off;
  // the trilinear then looked 1e3 times worse than it is, and Cubic RK4 at 32 voxels was chosen at
  // 1e-3 of the deflection with an error of 1.3e-3 against the closed form)
  if (refs.size() == 2)
  {
    RefLadder& T = refs[static_cast<int>(Reconstruction::Trilinear)];
    RefLadder& C = refs[static_cast<int>(Reconstruction::Cubic)];
    const double step = std::min(T.Step, C.Step);
    while (T.Step > step)
      halve(T, Reconstruction::Trilinear);
    while (C.Step > step)
      halve(C, Reconstruction::Cubic);
  }
  static const std::vector<RayRecord> none;
  const std::vector<RayRecord>& refTri = tryTri ? refs[static_cast<int>(Reconstruction::Trilinear)].Fine : none;
  const std::vector<RayRecord>& refCubic = tryCubic ? refs[static_cast<int>(Reconstruction::Cubic)].Fine : none;
  const std::vector<RayRecord>& R0 = tryCubic ? refCubic : refTri;
  // the rays a long step about to be chosen is checked on for steps longer than a feature (see
  // evaluateOnce); none where a reference itself flags one (a body, the octree's levels): there
  // the pilot's own rays decide, as they did
  std::vector<float> denseAb;
  {
    bool clean = true;
    for (const std::vector<RayRecord>* r : { &refTri, &refCubic })
      for (const RayRecord& x : *r)
        clean = clean && !(x.Flags & RayUnderresolved);
    if (clean)
      denseAb = PilotRays(volume, in, 32);
  }
  double emax = 0;
  for (const RayRecord& r : R0)
    if (!(r.Flags & RayBlocked))
      emax = std::max(emax, double(sch_hypot_d(r.DeflX, r.DeflY)));
  const double tol = in.Tolerance > 0 ? in.Tolerance : 0.01 * emax;
  double triError = 0;
  if (tryTri && tryCubic)
  {
    for (std::size_t k = 0; k < refTri.size(); ++k)
      if (Comparable(refTri[k], refCubic[k]))
        triError = std::max(triError,
          double(sch_hypot_d(refTri[k].DeflX - refCubic[k].DeflX, refTri[k].DeflY - refCubic[k].DeflY)));
    c.TrilinearError = triError;
    // Integrator Auto: a trilinear candidate is measured against the tricubic reference itself
    // (see evaluateOnce), so the trilinear is tried unless its reference is off by more than
    // TrilinearReach times the tolerance. The difference of the two references is the integral
    // of the trilinear's error along the ray; a candidate that samples the trilinear field at
    // long steps may be closer to the truth than that (issue 50: on the 64^3 Gaussian at the
    // default tolerance, 3.0e-6 rad, the references differed by 3.24e-6 rad and Straight at
    // 11.3 voxels on the trilinear was 2.1e-6 rad from the exact ray; when candidates answered
    // for err + triError, the trilinear was left out and Cubic taken at 3 times the cost). A
    // fixed integrator, whose error is not measured: where the trilinear's own leaves at least
    // half the tolerance to it.
    if (triError > (in.Method == Integrator::Auto ? TrilinearReach : 0.5) * tol)
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
  // The floor: the smallest error the pilot can tell apart. The reference traced again at twice
  // its step (RK4, also a candidate) differs from it by what the reference itself is uncertain
  // by; a candidate within 1.5 times that is as accurate as the pilot can tell, and a finer step
  // only costs more. The ladder stops refining once that difference is within RefShare of the
  // tolerance, so the floor is above the tolerance only where the reference reached its finest
  // step (1/8 voxel, against 1/4). Where the tolerance is below the floor, the floor is the
  // tolerance applied: the cheapest candidate within it is taken, and the report says that the
  // tolerance asked is below what this volume allows, and why.
  const bool reuseRefTrace = !(in.UseOctree && grid.HasLevels); // candidates skip, the references not
  std::map<int, double> floorOf, floorDiff;
  for (const auto& L : refs)
  {
    floorDiff[L.first] = L.second.Diff;
    floorOf[L.first] = 1.5 * L.second.Diff;
  }
  double refErr = 0;
  // The tricubic reference's own error, where the tolerance may be within its reach (issue 50:
  // at 64^3 the tricubic data is 4e-8 to 1.2e-7 rad off the exact ray, and a pilot that measured
  // against it alone reported 1e-7 and 3e-8 rad met). It is part of the floor: no candidate is
  // closer to the truth than the reference it is measured against can tell.
  double reach = triError;
  if (tryCubic && !(reach > 0) && volume.Field && volume.Smooth && !grid.PiecesBound && volume.Ghost == 0 && emax > 0)
  {
    // Reconstruction Cubic (no trilinear reference): the trilinear's error from one trace at
    // the tricubic reference's step
    TraceSettings t = ref;
    t.Recon = Reconstruction::Trilinear;
    t.StepSize = refs[static_cast<int>(Reconstruction::Cubic)].Step;
    const std::vector<RayRecord> tri = traceRays(t, ab);
    for (std::size_t k = 0; k < tri.size(); ++k)
      if (Comparable(tri[k], refCubic[k]) && !((tri[k].Flags | refCubic[k].Flags) & RayBlocked))
        reach = std::max(reach, double(sch_hypot_d(tri[k].DeflX - refCubic[k].DeflX, tri[k].DeflY - refCubic[k].DeflY)));
  }
  // (not on a coarse copy, Volume::Ghost: its field at twice the spacing would not have the box's
  // faces; the copy is certified against the field instead, CoarseCopy::Bound)
  if (tryCubic && volume.Field && volume.Smooth && !grid.PiecesBound && volume.Ghost == 0 && emax > 0 &&
    tol < RefCheckReach * reach * reach / emax)
  {
    const auto r0 = std::chrono::steady_clock::now();
    CoarseField cf;
    if (MakeCoarseField(volume, cf))
    {
      Volume coarse;
      std::copy(cf.Dims, cf.Dims + 3, coarse.Dimensions);
      std::copy(volume.Origin, volume.Origin + 3, coarse.Origin);
      std::copy(cf.Spacing, cf.Spacing + 3, coarse.Spacing);
      coarse.Field = cf.Packed.data();
      coarse.Smooth = cf.Smooth.data();
      const RefLadder& L = refs[static_cast<int>(Reconstruction::Cubic)];
      TraceSettings t = ref;
      t.Recon = Reconstruction::Cubic;
      t.Method = Integrator::RK4;
      // the same step in world units: the integration's error is the same in both traces
      t.StepSize = L.Step * MinSpacing(volume) / MinSpacing(coarse);
      // on the CPU: the device keeps the volume traced, not this one
      t.Device = Backend::CPU;
      const std::vector<RayRecord> rc = TraceRays(coarse, t, ab);
      double d = 0;
      for (std::size_t k = 0; k < rc.size(); ++k)
        if (Comparable(rc[k], refCubic[k]) && !((rc[k].Flags | refCubic[k].Flags) & RayBlocked))
          d = std::max(d, double(sch_hypot_d(rc[k].DeflX - refCubic[k].DeflX, rc[k].DeflY - refCubic[k].DeflY)));
      c.ReferenceError = d / (std::pow(cf.Ratio, RefCheckOrder) - 1);
      c.ReferenceCheckMs = std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count() * 1e3;
      // a candidate's error against the truth is within its error against the reference plus
      // the reference's: nothing is known to be closer to the truth than the reference's own
      // error, taken with the margin of the ladder's floor (1.5: the estimate was 0.8 of the
      // smallest error any setting reaches at 64^3, whose coarse grid, 32^3, is not yet in the
      // fourth order's range). Above it the candidates are measured against the reference as
      // before (at 128^3 and 3e-8 rad, the reference 6.2e-9 rad off, counting the two together
      // took Cubic Euler at 6.73 voxels, 1.58 times the cheapest swept setting that meets it)
      refErr = c.ReferenceError;
      const int k = static_cast<int>(Reconstruction::Cubic);
      floorOf[k] = std::max(floorOf[k], RefFloorMargin * refErr);
    }
  }
  // The longest step the field allows: no fixed list. The steps a group (an integrator and a
  // reconstruction) tries are found from the pilot itself: from 8 voxels, doubled while the
  // candidate meets the tolerance (up to the volume's diagonal: a step never needs to be longer
  // than the box), halved until one does where 8 does not; then the interval between the longest
  // step that met and the shortest that did not is halved twice in log(step) (2^(1/2), 2^(1/4)),
  // so that the step taken is within 2^(1/4) (19 %) of the longest that meets. A step longer than
  // 8 voxels that is longer than a feature (the kernel's check, RayUnderresolved, on a ray the
  // reference traced without it) does not meet, whatever its error on the pilot: the pilot's rays
  // may miss where it matters.
  double maxStep = 0;
  {
    double d2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double side = (volume.Dimensions[a] - 1) * volume.Spacing[a];
      d2 += side * side;
    }
    maxStep = std::min(MaxAutoStep, std::max(1.0, std::sqrt(d2) / MinSpacing(volume)));
  }
  bool found = false;
  double bestCost = 1e300, bestErr = 1e300;
  AutoChoice fallback;
  // the smallest error of an RK4 candidate at a step of a voxel or more, per reconstruction: if
  // it is about the floor, the floor does not fall with the step
  std::map<int, double> coarseRK4;
  int tried = 0;
  bool boundByPieces = false; // a step was longer than the pieces' ghost layers hold
  // traces one candidate; true where it meets the tolerance (and landing within half a pixel)
  // the fewest samples per voxel of a sample point per step (samples / ray x step / the
  // integrator's evaluations per step) of the candidates traced, per reconstruction
  std::map<int, double> perVoxel;
  // err (if not null): the candidate's measured error, radians (1e300 where it lost a ray);
  // stepErr (if not null): its error against its own reconstruction's reference, the step's part
  auto evaluateOnce = [&](Integrator m, double step, Reconstruction rc, double* errOut, double* stepErrOut) -> bool
  {
    if (errOut)
      *errOut = 1e300;
    if (stepErrOut)
      *stepErrOut = 1e300;
    TraceSettings t = in;
    t.Method = m;
    t.StepSize = step;
    t.Recon = rc;
    t.EstimateError = false;
    if (grid.PiecesBound && step > AutoPiecesReach(rc == Reconstruction::Cubic))
    {
      boundByPieces = true;
      return false;
    }
    ++tried;
    // RK4 at a step of the reference's ladder: its trace is at hand
    const RefLadder& L = refs[static_cast<int>(rc)];
    const bool atLadder = reuseRefTrace && m == Integrator::RK4 && (step == L.Step || step == L.CoarseStep);
    const std::vector<RayRecord> T =
      atLadder ? (step == L.Step ? L.Fine : L.Coarse) : traceRays(t, ab);
    // the most accurate reference at hand: the tricubic's where it was traced. A trilinear
    // candidate measured against it answers for the trilinear's own error (Reconstruction Auto)
    // as it is on its own samples, not as the bound err + triError, which counted it twice where
    // the candidate's samples fall where the trilinear is exact (issue 50, see TrilinearReach)
    const Reconstruction refRc = tryCubic ? Reconstruction::Cubic : rc;
    const std::vector<RayRecord>& R = refRc == Reconstruction::Cubic ? refCubic : refTri;
    const std::vector<RayRecord>& own = rc == Reconstruction::Cubic ? refCubic : refTri;
    // below the floor of the reference's own error: the candidates within that error of the
    // reference (their error against the truth within about twice it)
    const double refFloorOf = floorOf[static_cast<int>(refRc)];
    const double allowed =
      refRc == Reconstruction::Cubic && tol < refFloorOf && RefFloorMargin * refErr >= refFloorOf
      ? refErr
      : std::max(tol, refFloorOf);
    double err = 0, stepErr = 0, land = 0, samples = 0;
    bool lost = false, over = false;
    // rays the candidate loses where the reference does not disqualify it
    const std::uint32_t bad = RayMaxSteps | RayTurned | RayNonFinite | RayOffFilm;
    for (std::size_t k = 0; k < T.size(); ++k)
    {
      samples += T[k].Samples;
      if ((R[k].Flags | own[k].Flags) & bad)
        continue; // the reference itself cannot be trusted here: nothing to compare
      // a body stopped it (in either trace: a grazing ray may stop at a body's corner with one
      // step and pass it with another): dark, no deflection to compare
      if ((R[k].Flags | own[k].Flags | T[k].Flags) & RayBlocked)
        continue;
      if (T[k].Flags & bad)
        lost = true; // it fails where the reference does not
      if (((T[k].Flags & RayUnderresolved) || T[k].Mismatch > PilotFeatureShare) && !(own[k].Flags & RayUnderresolved))
        over = true; // a step longer than a feature (or near it), where the reference's are not
      err = std::max(err, double(sch_hypot_d(T[k].DeflX - R[k].DeflX, T[k].DeflY - R[k].DeflY)));
      stepErr = std::max(stepErr, double(sch_hypot_d(T[k].DeflX - own[k].DeflX, T[k].DeflY - own[k].DeflY)));
      land = std::max(land, double(sch_hypot_d(T[k].LandA - R[k].LandA, T[k].LandB - R[k].LandB)));
    }
    land /= film.PixelSize;
    {
      const double pv = samples / T.size() * step / Evaluations(m);
      auto it = perVoxel.find(static_cast<int>(rc));
      if (it == perVoxel.end() || pv < it->second)
        perVoxel[static_cast<int>(rc)] = pv;
    }
    if (lost)
      return false;
    if (errOut)
      *errOut = err;
    if (stepErrOut)
      *stepErrOut = stepErr;
    if (m == Integrator::RK4 && step >= 1.0)
    {
      auto it = coarseRK4.find(static_cast<int>(rc));
      if (it == coarseRK4.end() || err < it->second)
        coarseRK4[static_cast<int>(rc)] = err;
    }
    // the kernel's check bounds the steps beyond the classic ones (8 voxels and less): there the
    // pilot's measured error decides, as it did before issue 50 (the Luneburg lens's edge flags
    // Midpoint at 2 voxels and it meets the tolerance all the same)
    if (over && step > 8.0)
      return false;
    const double cost = samples * (rc == Reconstruction::Cubic ? CubicSampleCost : 1.0);
    // Beyond the classic steps (more than 8 voxels) a step is taken with a margin: the error
    // of a long step grows steeply with it (a line of sight's sum over a Gaussian of width s,
    // like exp(-pi^2 s^2 / h^2)), and the pilot does not see the reference's own error (the
    // tricubic's). Measured: Straight at 9.51 voxels on the 64^3 Gaussian (A = 1e-4) was 2.8e-7
    // rad from the reference, 3.9e-7 from the closed form; with the margin every choice of
    // TestEngineAutoStep and TestEngineReconstruction is within its tolerance of the known answer.
    // The margin bounds the step's part of the error (against the candidate's own
    // reconstruction's reference); the whole error, against the most accurate reference, must
    // be within the tolerance (the trilinear's own part does not grow with the step).
    const double margin = step > 8.0 ? LongStepMargin : 1.0;
    const bool meets = err <= allowed && stepErr <= margin * allowed && land <= 0.5;
    // a long step about to be chosen: its check for steps longer than a feature on rays between
    // the pilot's, 32 x 32 of them (no reference needed: the candidate alone, a few ms). The
    // pilot's 16 x 16 rays lie half a width apart on the Gaussian at 384^3: Trilinear
    // Euler at 45.1 voxels had a share of 0.45 or less on them, and 12 of 576 rays between them
    // over 0.5, flagged.
    if (meets && cost < bestCost && step > 8.0 && m != Integrator::Straight && !denseAb.empty() &&
      SteppedOverFeature(traceRays(t, denseAb)))
      return false;
    if (meets && cost < bestCost)
    {
      found = true;
      bestCost = cost;
      c.Method = m;
      c.StepSize = step;
      c.Recon = rc;
      c.ExpectedError = err;
      c.ExpectedLandingError = land;
      c.SamplesPerRay = samples / T.size();
    }
    if (!found && err < bestErr)
    {
      bestErr = err;
      fallback.Method = m;
      fallback.StepSize = step;
      fallback.Recon = rc;
      fallback.ExpectedError = err;
      fallback.ExpectedLandingError = land;
      fallback.SamplesPerRay = samples / T.size();
    }
    return meets;
  };
  // the same, each candidate traced once
  // what each candidate traced gave (an earlier pilot's choice, traced first, comes up again in
  // its group): met, its error and its step's error (1e300: lost)
  struct Outcome
  {
    bool Met;
    double Err, StepErr;
  };
  std::map<std::tuple<int, double, int>, Outcome> done;
  auto evaluate = [&](Integrator m, double step, Reconstruction rc, double* errOut,
                    double* stepErrOut = nullptr) -> bool
  {
    const auto memo = std::make_tuple(static_cast<int>(m), step, static_cast<int>(rc));
    auto seen = done.find(memo);
    if (seen == done.end())
    {
      Outcome o{ false, 1e300, 1e300 };
      o.Met = evaluateOnce(m, step, rc, &o.Err, &o.StepErr);
      seen = done.emplace(memo, o).first;
    }
    if (errOut)
      *errOut = seen->second.Err;
    if (stepErrOut)
      *stepErrOut = seen->second.StepErr;
    return seen->second.Met;
  };
  // The search skips what cannot be chosen (issue 50: the candidates took half of a pilot at
  // 512^3 once the references were cheap): a candidate whose cost, predicted from the samples
  // per voxel of the candidates traced so far (a lower bound: the fewest), is not below the
  // cheapest that met. A group whose 8 voxels are too dear starts at the shortest step of its
  // doubling ladder that is not, and bisects below it where that one does not meet; where none
  // is, it is skipped. Errors grow with the step (the search's own premise), so nothing cheaper
  // than the choice is left out. And a line of sight stops halving where its error does not fall
  // with the step (by a quarter a halving): what is left is the bending it does not follow.
  auto predicted = [&](Integrator m, double step, Reconstruction rc) {
    auto it = perVoxel.find(static_cast<int>(rc));
    if (it == perVoxel.end())
      it = perVoxel.begin();
    if (it == perVoxel.end())
      return 0.0;
    // the pilot's cost: samples of all its rays, as evaluate counts them
    return it->second * Evaluations(m) / step * (rc == Reconstruction::Cubic ? CubicSampleCost : 1.0) *
      static_cast<double>(ab.size() / 2);
  };
  auto useless = [&](Integrator m, double step, Reconstruction rc) {
    return found && predicted(m, step, rc) >= bestCost;
  };
  // an earlier pilot's choice first: where it meets again, what is dearer is skipped from the start
  if (start && start->Met && start->StepSize > 0 && start->StepSize <= maxStep &&
    ((start->Recon == Reconstruction::Trilinear && tryTri) || (start->Recon == Reconstruction::Cubic && tryCubic)) &&
    start->Method != Integrator::Auto)
    evaluate(start->Method, start->StepSize, start->Recon, nullptr);
  for (Reconstruction rc : { Reconstruction::Trilinear, Reconstruction::Cubic })
  {
    if ((rc == Reconstruction::Trilinear && !tryTri) || (rc == Reconstruction::Cubic && !tryCubic))
      continue;
    for (Integrator m :
      { Integrator::Straight, Integrator::Euler, Integrator::Verlet, Integrator::Midpoint, Integrator::RK4 })
    {
      // line of sight is not refined below a voxel (its error there is the data's, not the step's)
      const double shortest = m == Integrator::Straight ? 1.0 : 0.25;
      double lo = 0, hi = 0; // the longest step that met, the shortest longer one that did not
      double first = std::min(8.0, maxStep);
      double dear = 0; // a step known too dear to be chosen (the bisection's lower end), or 0
      while (useless(m, first, rc) && first < maxStep)
      {
        dear = first;
        first = std::min(2 * first, maxStep);
      }
      if (useless(m, first, rc))
        continue; // even its longest step costs more than the choice
      double err = 0, stepErr = 0;
      bool met = evaluate(m, first, rc, &err, &stepErr);
      // A trilinear candidate that fails on the trilinear's own error (its step's part, against
      // the trilinear's reference, within the tolerance) may meet at a longer step: there its
      // samples fall at other places in the voxels, and the step's error may offset the
      // trilinear's; the error does not grow with the step until the step's part dominates.
      // So the group climbs by 2^(1/4) to twice its first step while the step's part stays
      // within the tolerance's margin (issue 50: on the 64^3 Gaussian at the default tolerance,
      // 3.0e-6 rad, the trilinear line of sight was 3.2e-6 rad off at 8 voxels and 3.8e-6 at
      // 9.51 on the pilot, 2.1e-6 at 11.3: the cheapest setting of a sweep against the exact
      // ray, where Auto took Cubic at the same samples, 3 times the cost).
      const double allowedTri = std::max(tol, floorOf[static_cast<int>(Reconstruction::Cubic)]);
      const double climbLimit = LongStepMargin * allowedTri;
      if (!met && rc == Reconstruction::Trilinear && tryCubic && stepErr <= climbLimit)
        for (double st = first;;)
        {
          const double next = std::min(std::stod(ToText(st * std::pow(2.0, 0.25))), maxStep);
          if (!(next > st) || next > 2 * first || useless(m, next, rc))
            break;
          st = next;
          double se = 0;
          if (evaluate(m, st, rc, nullptr, &se))
          {
            met = true;
            first = st; // the doubling goes on from there
            break;
          }
          if (!(se <= climbLimit))
            break;
        }
      if (met)
      {
        lo = first;
        while (lo < maxStep)
        {
          const double st = std::min(2 * lo, maxStep);
          if (!evaluate(m, st, rc, nullptr))
          {
            hi = st;
            break;
          }
          lo = st;
        }
      }
      else if (dear > 0)
      {
        // the steps between the dear one and the first: bisected as below, from the dear end
        hi = first;
        lo = dear;
        for (int r = 0; r < 2; ++r)
        {
          const double mid = std::stod(ToText(std::sqrt(lo * hi)));
          if (!(mid > lo && mid < hi) || useless(m, mid, rc))
            break;
          if (evaluate(m, mid, rc, nullptr))
            lo = mid;
          else
            hi = mid;
        }
        continue;
      }
      else
      {
        hi = first;
        // Shorter steps tend to the trilinear's reference: where that is off by more than the
        // tolerance, halving does not meet (issue 50: at 512^3 and 3e-8 rad the trilinear
        // groups were halved to 1/4 voxel, 5.0e-8 rad off at every step, and the pilot took
        // 1.96 s instead of 0.53 s)
        const bool halves = !(rc == Reconstruction::Trilinear && tryCubic && triError > allowedTri);
        for (double st = first / 2; halves && st >= shortest && !useless(m, st, rc); st /= 2)
        {
          double e = 0;
          if (evaluate(m, st, rc, &e))
          {
            lo = st;
            break;
          }
          hi = st;
          if (m == Integrator::Straight && e < 1e300 && err < 1e300 && e > 0.75 * err)
            break; // the error is the bending's, not the step's
          err = e;
        }
      }
      for (int r = 0; r < 2 && lo > 0 && hi > lo; ++r)
      {
        // the geometric middle, to 3 digits (a step the report can print as it is)
        const double mid = std::stod(ToText(std::sqrt(lo * hi)));
        if (!(mid > lo && mid < hi))
          break;
        if (evaluate(m, mid, rc, nullptr))
          lo = mid;
        else
          hi = mid;
      }
    }
  }
  if (!found)
  {
    const double keep = c.TrilinearError;
    c = fallback;
    c.TrilinearError = keep;
    c.Met = false;
  }
  // the floor of the reference the choice was measured against
  const int floorRc = static_cast<int>(tryCubic ? Reconstruction::Cubic : c.Recon);
  c.Floor = floorOf[floorRc];
  c.AtFloor = found && tol < c.Floor;
  if (c.AtFloor)
    c.Met = false;
  std::string floorWhy;
  // the floor is the tricubic reference's own error: the tolerance is below what this grid's
  // data holds, whatever the step
  const bool refFloor = c.AtFloor && c.ReferenceError > 0 && RefFloorMargin * c.ReferenceError >= 1.5 * floorDiff[floorRc];
  if (c.AtFloor && !refFloor)
  {
    const double d = floorDiff[floorRc];
    auto it = coarseRK4.find(floorRc);
    // RK4 at 4 times the step would be 256 times worse if the difference were its truncation
    // error: an error that does not fall with the step is rounding
    const RefLadder& L = refs[floorRc];
    floorWhy = "the reference (RK4 at " + ToText(L.Step * grid.ReportScale) + " voxel) and RK4 at " +
      ToText(L.CoarseStep * grid.ReportScale) +
      " voxel differ by " + ToText(d) + " rad";
    if (it != coarseRK4.end() && it->second <= 2 * d)
      floorWhy += ", RK4 at a voxel or more by " + ToText(it->second) +
        " rad: an error that does not fall with the step, float rounding (each sample's position "
        "and the sums along the ray are single precision; it grows as the steps get shorter)";
    else
      floorWhy += ": the reference itself is still converging (structure finer than its step, "
                  "or data the grid does not resolve for this tolerance)";
  }
  c.Tolerance = tol;
  // the octree is a cost too: a skipping step costs more than a plain one. Kept
  // when it saves at least 10 % of the chosen setting's samples on the pilot; without it the
  // error can only stay or shrink (fixed steps through the blocks it would have skipped).
  c.UseOctree = in.UseOctree && grid.HasLevels;
  if (c.UseOctree)
  {
    TraceSettings t = in;
    t.Method = c.Method;
    t.StepSize = c.StepSize;
    t.Recon = c.Recon;
    t.EstimateError = false;
    t.UseOctree = false;
    double plain = 0;
    for (const RayRecord& r : traceRays(t, ab))
      plain += r.Samples;
    c.OctreeSaving = plain > 0 ? 1.0 - c.SamplesPerRay * (ab.size() / 2) / plain : 0.0;
    c.UseOctree = c.OctreeSaving >= 0.1;
  }
  const double ms = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() * 1e3;
  std::ostringstream rep;
  rep << "Auto chose " << IntegratorName(c.Method) << " at " << c.StepSize * grid.ReportScale << " voxel: expected "
      << "deflection error " << c.ExpectedError << " rad (tolerance " << tol << " rad), landing error "
      << c.ExpectedLandingError << " pixel, " << c.SamplesPerRay << " samples per ray (pilot of "
      << ab.size() / 2 << " rays, " << static_cast<int>(ms) << " ms)";
  if (c.Recon != Reconstruction::Trilinear || autoRecon)
    rep << "; reconstruction " << ReconstructionName(c.Recon);
  if (autoRecon && tryCubic)
    rep << " (the trilinear's estimated error " << c.TrilinearError << " rad)";
  // Only two reconstructions tell the trilinear's own error (the data's, between its points)
  // apart: a reference on the trilinear data alone converges to the trilinear field, not to the
  // one the data samples (the 64^3 Gaussian, GaussianCase: Auto expected 7.2e-7 rad, the closed
  // form was 2.9e-6 away). Said where the estimate lacks it.
  if (c.Recon == Reconstruction::Trilinear && !tryCubic)
    rep << "; the trilinear data's own error between its points is not in this estimate ("
        << (grid.HasSolid ? "with a body in the volume only the trilinear reconstruction is traced"
              : !autoRecon ? "Reconstruction Auto measures it"
                           : "the volume has no smoothness bytes, which PackFieldHighOrder writes: only the trilinear "
                             "reconstruction is traced")
        << ")";
  if (c.ReferenceError > 0 && !refFloor)
    rep << "; the tricubic reference's own estimated error " << c.ReferenceError << " rad";
  if (refFloor)
  {
    std::ostringstream best;
    best << ReconstructionName(c.Recon) << " " << IntegratorName(c.Method) << " at " << c.StepSize * grid.ReportScale << " voxel";
    rep << "; no candidate met the tolerance: it is below what this volume allows, a floor of " << c.Floor
        << " rad (" << RefFloorMargin << " times the tricubic reference's own error, " << c.ReferenceError
        << " rad, measured against the field resampled with half its points along each axis: the data does not resolve the "
           "field finely enough for this tolerance): tolerance "
        << tol << " rad not reachable on this grid: best estimated " << c.ExpectedError + c.Floor
        << " rad with " << best.str() << " (its " << c.ExpectedError
        << " rad from the reference and the floor; a finer grid, or a Tolerance of at least "
        << c.ExpectedError + c.Floor << " rad)";
  }
  else if (c.AtFloor)
    rep << "; no candidate met the tolerance: it is below what this volume allows, a floor of "
        << c.Floor << " rad (" << floorWhy
        << "); using the cheapest candidate within the floor (a Tolerance of at least " << c.Floor
        << " rad asks no more than the pilot can measure)";
  else if (!c.Met)
    rep << "; no candidate met the tolerance: using the most accurate one";
  // (the pieces' bound is not in the report, which is one process's where the choice is: the
  // session says it apart, AutoChoice::PiecesBound)
  c.PiecesBound = boundByPieces;
  c.Candidates = tried;
  for (const auto& L : refs)
    c.ReferenceSteps[L.first == static_cast<int>(Reconstruction::Cubic) ? 1 : 0] = L.second.Step;
  if (in.UseOctree && grid.HasLevels)
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

std::vector<float> PilotRays(const Volume& volume, const TraceSettings& s, int np)
{
  const FilmGeometry film = MakeFilm(volume, s);
  std::vector<float> ab;
  const double w = film.Size[0] * film.PixelSize, h = film.Size[1] * film.PixelSize;
  // Each ray off the centre of its cell of the np x np pattern, by the R2 sequence (in the cell's
  // middle half). At the centres, an axis view of a grid of 32 k + 1 points a side (33, 65, 129,
  // 257, 513) put every pilot ray on a grid line, where the trilinear interpolation across the
  // ray is exact: the pilot saw none of the trilinear's error (the 129^3 Gaussian at 3e-8 rad:
  // Trilinear Verlet chosen, 8.8e-7 rad off the exact ray; at 1e-7 rad, 8.3e-7).
  const double r1 = 0.7548776662466927, r2 = 0.5698402909980532; // 1 / g, 1 / g^2 (g^3 = g + 1)
  for (int j = 0; j < np; ++j)
    for (int i = 0; i < np; ++i)
    {
      const int k = j * np + i + 1;
      const double u = 0.25 + 0.5 * std::fmod(0.5 + k * r1, 1.0);
      const double v = 0.25 + 0.5 * std::fmod(0.5 + k * r2, 1.0);
      ab.push_back(static_cast<float>(film.Corner[0] + (i + u) * w / np));
      ab.push_back(static_cast<float>(film.Corner[1] + (j + v) * h / np));
    }
  return ab;
}

} // namespace schlieren
