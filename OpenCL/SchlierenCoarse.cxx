// SPDX-License-Identifier: BSD-3-Clause
// Auto's coarse copy (issue 50): a large smooth field traced from a copy of it at 2 or 4 times
// its spacing, where the copy's reconstruction is within a certified bound of the full grid's.
#include "SchlierenEngineInternal.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <new>

namespace schlieren
{

namespace
{
inline double Sq(double x)
{
  return x * x;
}

// The weights of 4-point Lagrange interpolation at x (an index of a line of n points; outside
// [0, n - 1] extrapolation from its 4 end points) on the points s0 .. s0 + 3.
void LagrangeAt(int n, double x, int& s0, double w[4])
{
  s0 = std::max(0, std::min(n - 4, static_cast<int>(std::floor(x)) - 1));
  for (int q = 0; q < 4; ++q)
  {
    w[q] = 1;
    for (int r = 0; r < 4; ++r)
      if (r != q)
        w[q] *= (x - (s0 + r)) / double(q - r);
  }
}

// the copies of the last stamped volume, by stride
std::mutex CoarseMutex;
VolumeIdentity CoarseOwner;
std::map<int, std::shared_ptr<const CoarseCopy>> CoarseCopies;

std::shared_ptr<const CoarseCopy> MakeCoarseCopy(const Volume& v, int r)
{
  auto c = std::make_shared<CoarseCopy>();
  c->Stride = r;
  // M = ceil((N - 1) / r) + 1 points over the box, and one more beyond each face (Volume::Ghost),
  // extrapolated from the field's last four points: every cell inside the box then has the
  // 4 x 4 x 4 points of a tricubic sample (without them the outermost cells would be trilinear at
  // the copy's spacing, and a ray grazing a face would meet that error along its whole length)
  int dims[3], inner[3];
  double step[3]; // the copy's spacing in the field's points
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = v.Dimensions[a];
    inner[a] = (dims[a] - 1 + r - 1) / r + 1;
    if (inner[a] < CoarseMinPoints)
      return nullptr;
  }
  // in one device buffer (the kernels' slabs keep their first and last cells trilinear, which the
  // certificate below does not see)
  if (16.0 * (inner[0] + 2) * (inner[1] + 2) * (inner[2] + 2) > CoarseMaxBytes)
    return nullptr;
  for (int a = 0; a < 3; ++a)
  {
    step[a] = double(dims[a] - 1) / (inner[a] - 1);
    c->V.Dimensions[a] = inner[a] + 2;
    c->V.Spacing[a] = v.Spacing[a] * step[a];
    c->V.Origin[a] = v.Origin[a] - c->V.Spacing[a];
  }
  c->V.Ghost = 1;
  // only a field smooth everywhere inside (PackFieldHighOrder's verdict on every cell it judges,
  // two points and more from the faces): a jump stays the field's own
  if (!v.Smooth)
    return nullptr;
  for (int k = 3; k <= dims[2] - 5; ++k)
    for (int j = 3; j <= dims[1] - 5; ++j)
    {
      const unsigned char* row = v.Smooth + (std::size_t(k) * dims[1] + j) * dims[0];
      for (int i = 3; i <= dims[0] - 5; ++i)
        if (!(row[i] & SCH_SMOOTH_CELL))
          return nullptr;
    }
  // The field's four values (n - 1 and the gradient) at the copy's points, one copy plane at a
  // time: each of the field's planes resampled along x, then y, once (a thread keeps the last
  // four it made: the planes a copy plane's z stencil reads only move forward), then the four
  // blended along z into the copy. No intermediate of the field's size: a plane of 1 to 4 MiB.
  const FieldLayout layout(dims, v.FieldInBricks);
  const int* M = c->V.Dimensions;
  struct AxisWeights
  {
    std::vector<int> First;
    std::vector<float> W;
  } ax[3];
  for (int a = 0; a < 3; ++a)
  {
    ax[a].First.resize(M[a]);
    ax[a].W.resize(4 * std::size_t(M[a]));
    for (int q = 0; q < M[a]; ++q)
    {
      double wd[4];
      LagrangeAt(dims[a], (q - 1) * step[a], ax[a].First[q], wd);
      for (int u = 0; u < 4; ++u)
        ax[a].W[4 * std::size_t(q) + u] = static_cast<float>(wd[u]);
    }
  }
  const std::size_t planeFloats = 4 * std::size_t(M[0]) * M[1];
  c->Packed.resize(planeFloats * M[2]);
  const unsigned threads = CpuThreads();
  RunOnThreads(threads, [&](unsigned t) {
    // this thread's copy planes: a contiguous share
    const int q0 = static_cast<int>(std::size_t(M[2]) * t / threads);
    const int q1 = static_cast<int>(std::size_t(M[2]) * (t + 1) / threads);
    std::vector<float> xr(4 * std::size_t(M[0]) * dims[1]);
    std::vector<std::vector<float>> ring(4, std::vector<float>(planeFloats));
    int ringK[4] = { -1, -1, -1, -1 };
    // In bricks: a layer of bricks (2^FieldBrickShift planes, contiguous in memory) read once, in
    // its order, into its planes' linear rows (a brick's row of points is contiguous; the last
    // brick is whole: the points past the grid repeat its border)
    const int b = 1 << FieldBrickShift;
    const std::size_t rowPts = std::size_t(dims[0] + b) / b * b;
    std::vector<float> layer(v.FieldInBricks ? 4 * rowPts * dims[1] * b : 0);
    int layerAt = -1;
    auto loadLayer = [&](int L) {
      for (int by = 0; by < dims[1]; by += b)
        for (int bx = 0; bx < dims[0]; bx += b)
          for (int kz = 0; kz < b && L * b + kz < dims[2]; ++kz)
            for (int jy = 0; jy < b && by + jy < dims[1]; ++jy)
            {
              const float* f = v.Field + layout.At(bx, by + jy, L * b + kz);
              std::copy(f, f + 4 * b, &layer[4 * (rowPts * (std::size_t(kz) * dims[1] + by + jy) + bx)]);
            }
      layerAt = L;
    };
    // plane k of the field resampled along x and y into out
    auto plane = [&](int k, float* out) {
      if (v.FieldInBricks && k / b != layerAt)
        loadLayer(k / b);
      for (int j = 0; j < dims[1]; ++j)
      {
        const float* row = v.FieldInBricks ? &layer[4 * rowPts * (std::size_t(k % b) * dims[1] + j)]
                                           : v.Field + layout.At(0, j, k);
        float* dst = &xr[4 * std::size_t(M[0]) * j];
        for (int q = 0; q < M[0]; ++q)
        {
          const float* wq = &ax[0].W[4 * std::size_t(q)];
          const float* src = row + 4 * std::size_t(ax[0].First[q]);
          for (int comp = 0; comp < 4; ++comp)
            dst[4 * q + comp] =
              wq[0] * src[comp] + wq[1] * src[4 + comp] + wq[2] * src[8 + comp] + wq[3] * src[12 + comp];
        }
      }
      const std::size_t rowFloats = 4 * std::size_t(M[0]);
      for (int q = 0; q < M[1]; ++q)
      {
        const float* wq = &ax[1].W[4 * std::size_t(q)];
        const float* s0 = &xr[rowFloats * ax[1].First[q]];
        float* dst = out + rowFloats * q;
        for (std::size_t e = 0; e < rowFloats; ++e)
          dst[e] = wq[0] * s0[e] + wq[1] * s0[rowFloats + e] + wq[2] * s0[2 * rowFloats + e] +
            wq[3] * s0[3 * rowFloats + e];
      }
    };
    for (int q = q0; q < q1; ++q)
    {
      const int f0 = ax[2].First[q];
      const float* src[4];
      for (int u = 0; u < 4; ++u)
      {
        const int k = f0 + u;
        int slot = -1;
        for (int e = 0; e < 4; ++e)
          if (ringK[e] == k)
            slot = e;
        if (slot < 0)
        {
          // the slot of the oldest plane (the smallest k, or an empty one)
          slot = 0;
          for (int e = 1; e < 4; ++e)
            if (ringK[e] < ringK[slot])
              slot = e;
          plane(k, ring[slot].data());
          ringK[slot] = k;
        }
        src[u] = ring[slot].data();
      }
      const float* wq = &ax[2].W[4 * std::size_t(q)];
      float* dst = c->Packed.data() + planeFloats * q;
      for (std::size_t e = 0; e < planeFloats; ++e)
        dst[e] = wq[0] * src[0][e] + wq[1] * src[1][e] + wq[2] * src[2][e] + wq[3] * src[3][e];
    }
  });
  const int* D = c->V.Dimensions;
  // The ghost layer's cells (outside the box) take no tricubic sample (no SCH_SMOOTH_CELL: their
  // stencils would leave the copy), but the smoothness level of the field's own rule there
  // (PackFieldHighOrder: beyond the grid no step goes): a ray enters on the box's face, which
  // the sampler puts in the ghost cell beyond it, and a level of 0 there capped its first step at
  // a cell, one sample a ray more (issue 50: 12 samples a ray at 512^3 where 11 reach the exit).
  c->Smooth.assign(c->V.NumberOfPoints(), static_cast<unsigned char>(7 << SCH_SMOOTH_SHIFT));
  const unsigned char inside = static_cast<unsigned char>(SCH_SMOOTH_CELL | (7 << SCH_SMOOTH_SHIFT));
  for (int k = 1; k <= D[2] - 3; ++k)
    for (int j = 1; j <= D[1] - 3; ++j)
      std::fill_n(&c->Smooth[(std::size_t(k) * D[1] + j) * D[0] + 1], D[0] - 3, inside);
  c->V.Field = c->Packed.data();
  c->V.Smooth = c->Smooth.data();
  c->V.Stamp = NewVolumeStamp();

  // The certificate: the copy's reconstruction against the field's values at the field's
  // points, every second one along each axis (which the field's own reconstruction takes at its
  // points). A feature between the checked points shows in their gradients, which the field's
  // differences take from their neighbours. The copy's reconstruction is the kernels' own: the
  // grid coordinate of sch_grid_coord, the cell's Lagrange weights of SCH_CUBIC_WEIGHTS (every
  // cell inside the box is tricubic), and the trilinear's 1 - t, t beside it. Evaluated a
  // checked plane, then row, at a time (z, y, then x), a point costs 2 x 16 multiply-adds, not a
  // full sample's 2 x 64 (at 512^3: 16.8 M points).
  TraceSettings t;
  t.Recon = Reconstruction::Cubic;
  t.Method = Integrator::Euler;
  t.StepSize = 1;
  t.Device = Backend::CPU;
  const sch_params P = MakeParams(c->V, t, MakeFilm(c->V, t));
  double h[3];
  HalfExtent(v, h);
  const int* fd = v.Dimensions;
  // per axis, for every checked index (even): the copy's cell and the cubic and linear weights
  struct AxisStencil
  {
    std::vector<int> Cell;
    std::vector<float> Cubic, Linear;
  } st[3];
  const float is[3] = { P.isx, P.isy, P.isz }, g0[3] = { P.gx0, P.gy0, P.gz0 },
              gmax[3] = { P.gxMax, P.gyMax, P.gzMax };
  for (int a = 0; a < 3; ++a)
  {
    const int n = (fd[a] + 1) / 2;
    st[a].Cell.resize(n);
    st[a].Cubic.resize(4 * std::size_t(n));
    st[a].Linear.resize(2 * std::size_t(n));
    for (int q = 0; q < n; ++q)
    {
      int cell;
      const float g = sch_grid_coord(static_cast<float>(2 * q * v.Spacing[a] - h[a]), is[a], g0[a], gmax[a], &cell);
      // the cells inside the box: 1 .. M - 3 (a point on the far face is the last cell's end)
      cell = std::max(1, std::min(M[a] - 3, cell));
      const float tt = g - static_cast<float>(cell);
      SCH_CUBIC_WEIGHTS(tt, w0, w1, w2, w3);
      st[a].Cell[q] = cell;
      float* wc = &st[a].Cubic[4 * std::size_t(q)];
      wc[0] = w0;
      wc[1] = w1;
      wc[2] = w2;
      wc[3] = w3;
      st[a].Linear[2 * std::size_t(q)] = 1.0f - tt;
      st[a].Linear[2 * std::size_t(q) + 1] = tt;
    }
  }
  // the checked points' lattice, and along its lines of x, y and z the sums of |g_copy - g|
  // (the certificate) and of the copy's |g_trilinear - g_tricubic| (what its trilinear would add)
  const int cx = (fd[0] + 1) / 2, cy = (fd[1] + 1) / 2, cz = (fd[2] + 1) / 2;
  struct LineSums
  {
    std::vector<double> X, Y;
    std::vector<std::vector<double>> Z; // a plane per thread (the threads share its lines)
  };
  LineSums sums[2];
  for (LineSums& ls : sums)
  {
    ls.X.assign(std::size_t(cy) * cz, 0.0);
    ls.Y.assign(std::size_t(cx) * cz, 0.0);
    ls.Z.assign(threads, std::vector<double>(std::size_t(cx) * cy, 0.0));
  }
  std::vector<double> gap(threads, 0.0), lowest(threads, 0.0);
  const float* C = c->Packed.data();
  const std::size_t rowF = 4 * std::size_t(M[0]);
  RunOnThreads(threads, [&](unsigned th) {
    double g = 0, lo = 0;
    // a checked plane blended along z (cubic, linear), then a checked row along y
    std::vector<float> pc(planeFloats), pl(planeFloats), rc(rowF), rl(rowF);
    // the field's values at the plane's checked points, gathered in the field's memory order (in
    // bricks: two of a brick's rows of four points at a time, the bricks in turn)
    std::vector<float> fv(4 * std::size_t(cx) * cy);
    for (int kk = static_cast<int>(th); kk < cz; kk += static_cast<int>(threads))
    {
      const int b = v.FieldInBricks ? 1 << FieldBrickShift : 2;
      for (int by = 0; by < fd[1]; by += b)
        for (int bx = 0; bx < fd[0]; bx += b)
          for (int jy = 0; jy < b && by + jy < fd[1]; jy += 2)
          {
            const float* f = v.Field + layout.At(bx, by + jy, 2 * kk);
            for (int ix = 0; ix < b && bx + ix < fd[0]; ix += 2)
              std::copy(f + 4 * ix, f + 4 * ix + 4,
                &fv[4 * (std::size_t((by + jy) / 2) * cx + (bx + ix) / 2)]);
          }
      {
        const int kc = st[2].Cell[kk];
        const float* wc = &st[2].Cubic[4 * std::size_t(kk)];
        const float* wl = &st[2].Linear[2 * std::size_t(kk)];
        const float* q0 = C + planeFloats * (kc - 1);
        const float* q1 = q0 + planeFloats;
        const float* q2 = q1 + planeFloats;
        const float* q3 = q2 + planeFloats;
        for (std::size_t e = 0; e < planeFloats; ++e)
        {
          pc[e] = wc[0] * q0[e] + wc[1] * q1[e] + wc[2] * q2[e] + wc[3] * q3[e];
          pl[e] = wl[0] * q1[e] + wl[1] * q2[e];
        }
      }
      for (int jj = 0; jj < cy; ++jj)
      {
        const int jc = st[1].Cell[jj];
        const float* wc = &st[1].Cubic[4 * std::size_t(jj)];
        const float* wl = &st[1].Linear[2 * std::size_t(jj)];
        const float* r0 = pc.data() + rowF * (jc - 1);
        const float* l1 = pl.data() + rowF * jc;
        for (std::size_t e = 0; e < rowF; ++e)
        {
          rc[e] = wc[0] * r0[e] + wc[1] * r0[rowF + e] + wc[2] * r0[2 * rowF + e] + wc[3] * r0[3 * rowF + e];
          rl[e] = wl[0] * l1[e] + wl[1] * l1[rowF + e];
        }
        for (int ii = 0; ii < cx; ++ii)
        {
          const int ic = st[0].Cell[ii];
          const float* wc = &st[0].Cubic[4 * std::size_t(ii)];
          const float* wl = &st[0].Linear[2 * std::size_t(ii)];
          const float* x0 = rc.data() + 4 * std::size_t(ic - 1);
          const float* y1 = rl.data() + 4 * std::size_t(ic);
          float sc[4], sl[4];
          for (int comp = 1; comp < 4; ++comp)
          {
            sc[comp] = wc[0] * x0[comp] + wc[1] * x0[4 + comp] + wc[2] * x0[8 + comp] + wc[3] * x0[12 + comp];
            sl[comp] = wl[0] * y1[comp] + wl[1] * y1[4 + comp];
          }
          const float* f = &fv[4 * (std::size_t(jj) * cx + ii)];
          const double d[2] = { std::sqrt(Sq(double(sc[1]) - f[1]) + Sq(double(sc[2]) - f[2]) + Sq(double(sc[3]) - f[3])),
            std::sqrt(Sq(double(sl[1]) - sc[1]) + Sq(double(sl[2]) - sc[2]) + Sq(double(sl[3]) - sc[3])) };
          g = std::max(g, d[0]);
          for (int q = 0; q < 2; ++q)
          {
            sums[q].X[std::size_t(kk) * cy + jj] += d[q];
            sums[q].Y[std::size_t(kk) * cx + ii] += d[q];
            sums[q].Z[th][std::size_t(jj) * cx + ii] += d[q];
          }
          lo = std::min(lo, double(f[0]));
        }
      }
    }
    gap[th] = g;
    lowest[th] = lo;
  });
  c->GradientGap = *std::max_element(gap.begin(), gap.end());
  const double n1min = *std::min_element(lowest.begin(), lowest.end());
  // A ray's deflection is the integral of the gradient across it over n. Along a line of the
  // grid the copy's error adds up to at most the sum of |g_copy - g| over the line (the checked
  // points stand for two spacings each); a line across the grid's lines meets the same cells'
  // errors over at most sqrt 3 times their length. The largest line's sum, times sqrt 3, over
  // the lowest n.
  double bound[2];
  for (int q = 0; q < 2; ++q)
  {
    LineSums& ls = sums[q];
    for (unsigned th = 1; th < threads; ++th)
      for (std::size_t e = 0; e < ls.Z[0].size(); ++e)
        ls.Z[0][e] += ls.Z[th][e];
    const double lx = *std::max_element(ls.X.begin(), ls.X.end()) * 2 * v.Spacing[0];
    const double ly = *std::max_element(ls.Y.begin(), ls.Y.end()) * 2 * v.Spacing[1];
    const double lz = *std::max_element(ls.Z[0].begin(), ls.Z[0].end()) * 2 * v.Spacing[2];
    bound[q] = std::sqrt(3.0) * std::max({ lx, ly, lz }) / std::max(1e-3, 1.0 + n1min);
  }
  c->Bound = bound[0];
  c->TrilinearBound = bound[1];
  return c;
}
} // namespace

std::shared_ptr<const CoarseCopy> CoarseCopyOf(const Volume& v, int stride)
{
  if (v.Stamp == 0 || !v.Field)
    return nullptr;
  std::lock_guard<std::mutex> lock(CoarseMutex);
  const VolumeIdentity id(v);
  if (!(id == CoarseOwner))
  {
    CoarseCopies.clear();
    CoarseOwner = id;
  }
  auto it = CoarseCopies.find(stride);
  if (it != CoarseCopies.end())
    return it->second;
  std::shared_ptr<const CoarseCopy> c;
  try
  {
    c = MakeCoarseCopy(v, stride);
  }
  catch (const std::bad_alloc&)
  {
    c = nullptr; // no room for a copy: the field is traced itself
  }
  CoarseCopies[stride] = c;
  return c;
}

void ReleaseCoarseCopies()
{
  std::lock_guard<std::mutex> lock(CoarseMutex);
  CoarseCopies.clear();
  CoarseOwner = VolumeIdentity();
}

bool CoarseEligible(const Volume& v, const TraceSettings& in, bool piecesBound)
{
  return in.Method == Integrator::Auto &&
    (in.Recon == Reconstruction::Cubic || in.Recon == Reconstruction::Auto) && in.Tolerance > 0 &&
    !piecesBound && v.Stamp != 0 && v.Field && v.Smooth && !v.Solid &&
    double(v.NumberOfPoints()) >= CoarseFromPoints && in.Mode != Cutoff::Interferometry &&
    !in.WhiteLight() && !in.EstimateError && GetRuntimeOptions().CoarseCopies;
}

} // namespace schlieren
