// SPDX-License-Identifier: BSD-3-Clause
// The film: its geometry (MakeFilm), the sums (FilmSums) and the splatter that puts photons on it.
#include "SchlierenEngineInternal.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace schlieren
{

static void Normalize(double v[3])
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int a = 0; a < 3; ++a)
    v[a] /= n;
}

static void Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void FilmGeometry::GetImageOrigin(double origin[2]) const
{
  origin[0] = Dot(Center, Right) + Corner[0] + 0.5 * PixelSize;
  origin[1] = Dot(Center, Up) + Corner[1] + 0.5 * PixelSize;
}

// Half the extent of the box of grid points along each axis, from the grid itself: the bounds
// (origin + extent) lose the extent's digits when the volume sits far from the world origin.
void HalfExtent(const Volume& v, double h[3])
{
  for (int a = 0; a < 3; ++a)
    h[a] = 0.5 * (v.Dimensions[a] - 1 - 2 * v.Ghost) * v.Spacing[a];
}

FilmGeometry MakeFilm(const Volume& volume, const TraceSettings& s)
{
  CheckGrid(volume.Dimensions, volume.Spacing);
  CheckSettings(s);
  FilmGeometry f;
  const double dlen = std::sqrt(Dot(s.ViewDirection, s.ViewDirection));
  if (!(dlen > 0) || !std::isfinite(dlen))
    throw Error("ViewDirection must be a non-zero, finite vector.");
  for (int a = 0; a < 3; ++a)
    f.Direction[a] = s.ViewDirection[a] / dlen;
  double up[3] = { s.ViewUp[0], s.ViewUp[1], s.ViewUp[2] };
  const double along = Dot(up, f.Direction);
  for (int a = 0; a < 3; ++a)
    up[a] -= along * f.Direction[a];
  const double ulen = std::sqrt(Dot(up, up));
  if (!(ulen > 1e-6 * std::sqrt(Dot(s.ViewUp, s.ViewUp))) || !std::isfinite(ulen))
    throw Error("ViewUp is zero or parallel to ViewDirection: choose an up vector across the beam.");
  Normalize(up);
  Cross(f.Direction, up, f.Right);
  Normalize(f.Right);
  Cross(f.Right, f.Direction, f.Up);
  Normalize(f.Up);

  if (s.Resolution[0] < 2 || s.Resolution[1] < 2 || s.Resolution[0] > 16384 ||
    s.Resolution[1] > 16384)
  {
    std::ostringstream msg;
    msg << "Resolution is " << s.Resolution[0] << " x " << s.Resolution[1]
        << " pixels: each side must be 2 to 16384 pixels (at least 2 x 2).";
    throw Error(msg.str());
  }
  double h[3];
  HalfExtent(volume, h);
  for (int a = 0; a < 3; ++a)
    f.Center[a] = volume.Origin[a] + h[a];
  double wa = 0, wb = 0, wd = 0;
  for (int a = 0; a < 3; ++a)
  {
    wa += h[a] * std::fabs(f.Right[a]);
    wb += h[a] * std::fabs(f.Up[a]);
    wd += h[a] * std::fabs(f.Direction[a]);
  }
  f.Size[0] = s.Resolution[0];
  f.Size[1] = s.Resolution[1];
  // the box's projection, or the frame asked for (Framing Silhouette), centred on the film
  double a0 = -wa, a1 = wa, b0 = -wb, b1 = wb;
  if (HasFilmExtent(s))
  {
    a0 = s.FilmExtent[0];
    a1 = s.FilmExtent[1];
    b0 = s.FilmExtent[2];
    b1 = s.FilmExtent[3];
  }
  if (s.Frame == Framing::Silhouette && HasFilmExtent(s))
  {
    // the frame's shape with Resolution's pixel count: no film left empty beside the data
    const double pixels = double(s.Resolution[0]) * s.Resolution[1], aspect = (a1 - a0) / (b1 - b0);
    f.Size[0] = static_cast<int>(std::min(std::max(std::lround(std::sqrt(pixels * aspect)), 2L), 16384L));
    f.Size[1] = static_cast<int>(std::min(std::max(std::lround(std::sqrt(pixels / aspect)), 2L), 16384L));
  }
  f.PixelSize = std::max((a1 - a0) / f.Size[0], (b1 - b0) / f.Size[1]);
  f.Corner[0] = 0.5 * (a0 + a1) - 0.5 * f.Size[0] * f.PixelSize;
  f.Corner[1] = 0.5 * (b0 + b1) - 0.5 * f.Size[1] * f.PixelSize;
  f.FrontPlane = -wd * 1.001;
  if (!std::isfinite(s.FilmDistance))
    throw Error("FilmDistance must be finite.");
  // A shadowgraph's film is FilmDistance behind the back of the box. Every other cutoff images
  // the volume's centre plane, as a schlieren camera focused on the test section does (BOS: the
  // photons are then referred to the background, see Splatter); FilmDistance defocuses it.
  f.FilmPlane = s.Mode == Cutoff::Shadowgraph ? wd + s.FilmDistance : s.FilmDistance;
  // A camera images its focus plane whatever the cutoff (a shadowgraph is then a defocus)
  if (s.Camera != CameraModel::None)
    f.FilmPlane = s.FocusPlane;
  return f;
}

SilhouetteFrame FrameSilhouette(const Volume& volume, const TraceSettings& s)
{
  SilhouetteScan scan;
  scan.Field = volume.Field;
  scan.Solid = volume.Solid;
  scan.FieldInBricks = volume.FieldInBricks;
  for (int a = 0; a < 3; ++a)
  {
    scan.Held[a] = volume.Dimensions[a];
    scan.Hi[a] = volume.Dimensions[a];
  }
  return FrameSilhouette(volume, s, scan, [](double*, std::size_t, bool) {});
}

SilhouetteFrame FrameSilhouette(const Volume& grid, const TraceSettings& s, const SilhouetteScan& scan,
  const std::function<void(double* values, std::size_t count, bool max)>& reduce)
{
  TraceSettings plain = s;
  for (double& e : plain.FilmExtent)
    e = 0;
  Volume box = grid;
  box.Field = nullptr;
  const FilmGeometry f = MakeFilm(box, plain);
  double h[3];
  HalfExtent(grid, h);
  SilhouetteFrame out;
  double wa = 0, wb = 0;
  for (int a = 0; a < 3; ++a)
  {
    wa += h[a] * std::fabs(f.Right[a]);
    wb += h[a] * std::fabs(f.Up[a]);
  }
  out.Extent[0] = -wa;
  out.Extent[1] = wa;
  out.Extent[2] = -wb;
  out.Extent[3] = wb;
  if (!scan.Field)
    return out;
  const float* F = scan.Field;
  auto at = [&scan](int i, int j, int k) {
    return (static_cast<std::size_t>(k) * scan.Held[1] + j) * scan.Held[0] + i;
  };
  const FieldLayout layout(scan.Held, scan.FieldInBricks);
  auto grad2 = [F, &layout](int i, int j, int k) {
    const float* f = F + layout.At(i, j, k);
    return double(f[1]) * f[1] + double(f[2]) * f[2] + double(f[3]) * f[3];
  };
  // the largest |grad n|^2 (the packed gradient, world units), over every piece
  double g2max = 0;
  for (int k = scan.Lo[2]; k < scan.Hi[2]; ++k)
    for (int j = scan.Lo[1]; j < scan.Hi[1]; ++j)
      for (int i = scan.Lo[0]; i < scan.Hi[0]; ++i)
        g2max = std::max(g2max, grad2(i, j, k));
  reduce(&g2max, 1, true);
  const double threshold = 1e-6 * g2max; // (1e-3 of the largest |grad n|)^2
  auto inside = [&](int i, int j, int k) {
    if (scan.Solid && scan.Solid[at(i, j, k)])
      return true;
    return g2max > 0 && grad2(i, j, k) > threshold;
  };
  // a point's film coordinates are linear along a row: its first and last silhouette points
  // bound the row's projection (whole-grid indices: scan.Offset + held)
  double lo[2] = { 1e300, 1e300 }, hi[2] = { -1e300, -1e300 };
  auto project = [&](int i, int j, int k) {
    const double p[3] = { (i + scan.Offset[0]) * grid.Spacing[0] - h[0],
      (j + scan.Offset[1]) * grid.Spacing[1] - h[1], (k + scan.Offset[2]) * grid.Spacing[2] - h[2] };
    const double c[2] = { Dot(p, f.Right), Dot(p, f.Up) };
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], c[a]);
      hi[a] = std::max(hi[a], c[a]);
    }
  };
  double points = 0;
  for (int k = scan.Lo[2]; k < scan.Hi[2]; ++k)
    for (int j = scan.Lo[1]; j < scan.Hi[1]; ++j)
    {
      int first = -1, last = -1;
      for (int i = scan.Lo[0]; i < scan.Hi[0]; ++i)
        if (inside(i, j, k))
        {
          if (first < 0)
            first = i;
          last = i;
          points += 1;
        }
      if (first >= 0)
      {
        project(first, j, k);
        project(last, j, k);
      }
    }
  // over every piece: the extremes (as maxima of the negated lows) and the count
  double extremes[4] = { -lo[0], -lo[1], hi[0], hi[1] };
  reduce(extremes, 4, true);
  reduce(&points, 1, false);
  lo[0] = -extremes[0];
  lo[1] = -extremes[1];
  hi[0] = extremes[2];
  hi[1] = extremes[3];
  out.Points = points;
  if (out.Points == 0)
    return out;
  out.Found = true;
  // the data reaches half a cell past its last points; 2 % more keeps the edge off the border
  const double spacing = std::max({ grid.Spacing[0], grid.Spacing[1], grid.Spacing[2] });
  for (int a = 0; a < 2; ++a)
  {
    const double pad = spacing + 0.02 * (hi[a] - lo[a]);
    const double w = a == 0 ? wa : wb;
    out.Extent[2 * a] = std::max(lo[a] - pad, -w);
    out.Extent[2 * a + 1] = std::min(hi[a] + pad, w);
  }
  out.Fraction =
    (out.Extent[1] - out.Extent[0]) * (out.Extent[3] - out.Extent[2]) / (4 * wa * wb);
  return out;
}

std::vector<std::vector<double>*> FilmSums::PixelChannels()
{
  return { &Count, &Weight, &DeflectionX, &DeflectionY, &AbsDeflection, &Red, &Green, &Blue, &Phase,
    &ShiftX, &ShiftY, &ErrorSum, &Blocked };
}

std::vector<double*> FilmSums::Totals()
{
  return { &Photons, &Samples, &FailedRays, &MissedRays, &UnderresolvedRays, &SideRays, &Steps,
    &BlockedRays };
}

std::vector<double*> FilmSums::Maxima()
{
  return { &MaxAbsKnife, &MaxAbsDeflection, &MaxDrift, &MaxError };
}

void FilmSums::Resize(int nx, int ny)
{
  Size[0] = nx;
  Size[1] = ny;
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  for (std::vector<double>* c : PixelChannels())
    c->assign(n, 0.0);
  for (double* t : Totals())
    *t = 0.0;
  for (double* m : Maxima())
    *m = 0.0;
  Passes = 0;
}

void FilmSums::ToArrays(std::vector<double>& additive, std::vector<double>& maxima)
{
  additive.clear();
  for (std::vector<double>* c : PixelChannels())
    additive.insert(additive.end(), c->begin(), c->end());
  for (double* t : Totals())
    additive.push_back(*t);
  maxima.clear();
  for (double* m : Maxima())
    maxima.push_back(*m);
}

void FilmSums::FromArrays(const std::vector<double>& additive, const std::vector<double>& maxima)
{
  std::size_t pos = 0;
  for (std::vector<double>* c : PixelChannels())
  {
    if (pos + c->size() > additive.size())
      throw schlieren::Error("FilmSums::FromArrays: the arrays do not match this film.");
    std::copy(additive.begin() + pos, additive.begin() + pos + c->size(), c->begin());
    pos += c->size();
  }
  for (double* t : Totals())
    *t = additive.at(pos++);
  std::size_t m = 0;
  for (double* x : Maxima())
    *x = maxima.at(m++);
}

Splatter::Splatter(const sch_params& p, const TraceSettings& s, FilmSums& f)
  : P(p)
  , S(s)
  , F(f)
{
  const double ang = s.KnifeAngle * 3.14159265358979323846 / 180.0;
  ca = static_cast<float>(std::cos(ang));
  sa = static_cast<float>(std::sin(ang));
  k = static_cast<float>(s.CutoffScale);
  manual = s.CutoffScale > 0;
  Bench = ComputeBench(s);
  twoPiOverLambda = 2 * 3.14159265358979323846 / (s.Wavelength * 1e-9);
  tilt = 2 * 3.14159265358979323846 * s.ReferenceTilt;
  bgPlane = P.sFront - s.BackgroundDistance;
  period = s.BackgroundPeriod > 0 ? s.BackgroundPeriod : 6.0 * P.pixel;
  camera = s.Camera != CameraModel::None;
  white = s.WhiteLight();
  Threads = std::min(2u, CpuThreads(s.Threads));
}

float Splatter::CutoffWeight(float ex, float ey, float landA, double phase, sch_uint pix) const
{
  float w = 1.0f;
  switch (S.Mode)
  {
    case Cutoff::KnifeEdge:
      // a finite source: its image shifted by f2 eps toward the open side, eps = -(e . a)
      w = Bench.Finite ? sch_bench_weight(Bench.Source, static_cast<float>(-S.SchlierenFocalLength * (ex * ca + ey * sa)),
                           static_cast<float>(Bench.Edge), static_cast<float>(Bench.Size))
                       : sch_knife_weight(ex, ey, ca, sa, k);
      break;
    case Cutoff::Circular:
    case Cutoff::ComplementCircular:
      // a stop in mm: the share of the source's image, shifted by f2 |e|, it lets through
      w = Bench.Stop ? static_cast<float>(StopWeight(Bench, S.SchlierenFocalLength * sch_hypot_d(double(ex), double(ey))))
                     : sch_circular_weight(ex, ey, k, S.Mode == Cutoff::ComplementCircular ? 1 : 0);
      break;
    case Cutoff::Interferometry:
      w = sch_fringe_weight(static_cast<float>(phase), static_cast<float>(tilt * tiltScale * landA));
      break;
    default:
      w = 1.0f;
  }
  if (S.RussianRoulette)
  {
    // the photon survives with probability w and then carries all its energy: same mean
    const sch_uint h = sch_hash(P.seed * 747796405u ^ sch_hash(pix * 2891336453u + static_cast<sch_uint>(P.pass)));
    w = sch_unit(h) < w ? 1.0f : 0.0f;
  }
  return w;
}

void Splatter::Add(const float* rec, std::size_t first, std::size_t count)
{
  // the rows split at the chunk's middle ray: photons land near where they were emitted, so
  // each thread gets about half; the totals and maxima on the first, in the records' order.
  // Small chunks on one thread: a thread's start costs more than it saves there.
  const long W = std::max(1, P.filmNx);
  const long mid = (P.rayOffset + (long(first) + long(count) / 2) * P.rayStride) / W;
  const int split = static_cast<int>(std::min<long>(std::max<long>(mid, 1), P.filmNy - 1));
  if (Threads < 2 || count < 8192 || P.filmNy < 2)
  {
    AddRows(rec, first, count, 0, P.filmNy, true);
    return;
  }
  RunOnThreads(2, [&](unsigned t) {
    if (t == 0)
      AddRows(rec, first, count, 0, split, true);
    else
      AddRows(rec, first, count, split, P.filmNy, false);
  });
}

void Splatter::AddRows(const float* rec, std::size_t first, std::size_t count, int rowLo,
  int rowHi, bool totals)
{
  // the channels' addresses read once: F's vectors sit beside the totals the first thread
  // writes, and a read of them at every photon would share that cache line
  double* const cCount = F.Count.data();
  double* const cWeight = F.Weight.data();
  double* const cDeflectionX = F.DeflectionX.data();
  double* const cDeflectionY = F.DeflectionY.data();
  double* const cAbsDeflection = F.AbsDeflection.data();
  double* const cRed = F.Red.data();
  double* const cGreen = F.Green.data();
  double* const cBlue = F.Blue.data();
  double* const cPhase = F.Phase.data();
  double* const cShiftX = F.ShiftX.data();
  double* const cShiftY = F.ShiftY.data();
  double* const cErrorSum = F.ErrorSum.data();
  double* const cBlocked = F.Blocked.data();
  for (std::size_t r = 0; r < count; ++r, rec += SCH_RECORD)
  {
    const unsigned flags = static_cast<unsigned>(rec[SCH_REC_FLAGS]);
    if (totals)
    {
      F.Photons += 1;
      F.Samples += rec[SCH_REC_SAMPLES];
      F.Steps += rec[SCH_REC_STEPS];
      if (flags & SCH_RAY_MISSED)
        F.MissedRays += 1;
      if (flags & SCH_RAY_UNDERRESOLVED)
        F.UnderresolvedRays += 1;
      if (flags & SCH_RAY_SIDE)
        F.SideRays += 1;
    }
    if (flags & SCH_RAY_BLOCKED)
    {
      // stopped by a body: no light; counted in the pixel it was emitted through (the shadow)
      if (totals)
        F.BlockedRays += 1;
      const std::size_t at = static_cast<std::size_t>(P.rayOffset + (first + r) * P.rayStride);
      const long row = static_cast<long>(at / static_cast<std::size_t>(std::max(1, P.filmNx)));
      if (row >= rowLo && row < rowHi)
        cBlocked[at] += 1;
      continue;
    }
    if (flags & SCH_RAY_LOST)
    {
      if (totals)
        F.FailedRays += 1;
      continue;
    }
    const float ex = rec[SCH_REC_EX], ey = rec[SCH_REC_EY];
    // the squares of floats are exact in double and cannot overflow: one rounding in the sum and
    // one in the root, as std::hypot gives, at a fraction of its cost (it was 0.9 % of a move)
    const double absE = std::sqrt(double(ex) * ex + double(ey) * ey);
    if (totals)
    {
      F.MaxDrift = std::max(F.MaxDrift, double(std::fabs(rec[SCH_REC_DRIFT])));
      F.MaxError = std::max(F.MaxError, double(rec[SCH_REC_ERROR]));
      F.MaxAbsKnife = std::max(F.MaxAbsKnife, double(std::fabs(ex * ca + ey * sa)));
      F.MaxAbsDeflection = std::max(F.MaxAbsDeflection, absE);
    }
    const int pix = static_cast<int>(P.rayOffset + (first + r) * P.rayStride);
    double la = rec[SCH_REC_A], lb = rec[SCH_REC_B];
    double bosWeight = 0, shiftX = 0, shiftY = 0;
    if (camera)
    {
      // Lens: from the tilted frame of the pass to the film's (zero tilt for Ideal: unchanged)
      la += lensTilt[0] * P.sFilm;
      lb += lensTilt[1] * P.sFilm;
    }
    if (S.Mode == Cutoff::BOS && camera)
    {
      // a camera sees the ray where its exit line crosses the focus plane (the background's
      // plane for the usual BOS focus); the pattern is that of the background point the ray
      // left from, tilt times the depth from its pixel's emission point
      float a0, b0;
      sch_emit(&P, pix, &a0, &b0);
      const double ba = a0 - lensTilt[0] * (P.sFilm - bgPlane), bb = b0 - lensTilt[1] * (P.sFilm - bgPlane);
      bosWeight = sch_bos_pattern(static_cast<float>(ba), static_cast<float>(bb), static_cast<float>(period),
        S.BackgroundPattern, P.seed);
      shiftX = la - a0;
      shiftY = lb - b0;
    }
    else if (S.Mode == Cutoff::BOS)
    {
      // the camera sees the background point the photon left from, where the exit ray seems
      // to come from: back along the exit direction to the background plane
      float a0, b0;
      sch_emit(&P, pix, &a0, &b0);
      bosWeight = sch_bos_pattern(a0, b0, static_cast<float>(period), S.BackgroundPattern, P.seed);
      la -= (P.sFilm - bgPlane) * ex;
      lb -= (P.sFilm - bgPlane) * ey;
      shiftX = la - a0;
      shiftY = lb - b0;
    }
    const double fi = std::floor((la - P.filmA0) / P.pixel);
    const double fj = std::floor((lb - P.filmB0) / P.pixel);
    if (fi < 0 || fj < 0 || fi >= P.filmNx || fj >= P.filmNy)
      continue; // landed off the film
    if (fj < rowLo || fj >= rowHi)
      continue; // another thread's rows
    const std::size_t idx = static_cast<std::size_t>(fj) * P.filmNx + static_cast<std::size_t>(fi);
    const double phase = twoPiOverLambda * rec[SCH_REC_OPL];
    cCount[idx] += 1;
    cDeflectionX[idx] += ex;
    cDeflectionY[idx] += ey;
    cAbsDeflection[idx] += absE;
    cErrorSum[idx] += rec[SCH_REC_ERROR];
    cPhase[idx] += phase;
    if (S.Mode == Cutoff::ColorFilter)
    {
      float cr, cg, cb;
      sch_hue_rgb(ex, ey, &cr, &cg, &cb);
      // value k|e| (manual k, clamped) or |e| (automatic: k applied in Finalize); a stop in mm:
      // the share of the source's image the filter's opaque centre leaves, on the hue of the
      // shift's direction
      const double v = Bench.Stop ? StopWeight(Bench, S.SchlierenFocalLength * absE)
        : manual                  ? std::min(1.0, k * absE)
                                  : absE;
      cRed[idx] += v * cr;
      cGreen[idx] += v * cg;
      cBlue[idx] += v * cb;
      if (Bench.Stop)
        cWeight[idx] += v; // the share passed: the read-outs' dark and full shares
    }
    else if (S.Mode == Cutoff::BOS)
    {
      cWeight[idx] += bosWeight;
      cShiftX[idx] += shiftX;
      cShiftY[idx] += shiftY;
    }
    else if (manual || Bench.Finite || S.Mode == Cutoff::Interferometry || S.RussianRoulette)
    {
      const float w = CutoffWeight(ex, ey, static_cast<float>(la), phase, static_cast<sch_uint>(pix));
      cWeight[idx] += w;
      if (white)
      {
        // the colour of the light the cutoff lets through
        cRed[idx] += w * passColour[0];
        cGreen[idx] += w * passColour[1];
        cBlue[idx] += w * passColour[2];
      }
      continue;
    }
    if (white && S.Mode != Cutoff::ColorFilter)
    {
      // the colour of the light that landed (Finalize scales it by the pixel's intensity)
      cRed[idx] += passColour[0];
      cGreen[idx] += passColour[1];
      cBlue[idx] += passColour[2];
    }
  }
}

} // namespace schlieren
