// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenWedge.h"
#include "SchlierenPhysics.h" // sch_atan_d: the same bits on every glibc

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace schlieren
{
namespace
{
const char* const Names = "xyz";

/** Least squares t = c0 + c1 r + c2 a over the points selected; false if singular. */
bool FitPlane(const double* xyz, std::size_t n, int a, int r, int t, const std::vector<char>& use,
  double c[3])
{
  double m[3][4] = {};
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!use[i])
    {
      continue;
    }
    const double v[3] = { 1.0, xyz[3 * i + r], xyz[3 * i + a] };
    for (int p = 0; p < 3; ++p)
    {
      for (int q = 0; q < 3; ++q)
      {
        m[p][q] += v[p] * v[q];
      }
      m[p][3] += v[p] * xyz[3 * i + t];
    }
  }
  // Gaussian elimination with partial pivoting
  for (int col = 0; col < 3; ++col)
  {
    int piv = col;
    for (int row = col + 1; row < 3; ++row)
    {
      if (std::abs(m[row][col]) > std::abs(m[piv][col]))
      {
        piv = row;
      }
    }
    if (!(std::abs(m[piv][col]) > 0))
    {
      return false;
    }
    std::swap(m[col], m[piv]);
    for (int row = 0; row < 3; ++row)
    {
      if (row != col)
      {
        const double f = m[row][col] / m[col][col];
        for (int k = col; k < 4; ++k)
        {
          m[row][k] -= f * m[col][k];
        }
      }
    }
  }
  for (int p = 0; p < 3; ++p)
  {
    c[p] = m[p][3] / m[p][p];
  }
  return true;
}
} // namespace

Wedge DetectWedge(const double* xyz, std::size_t n)
{
  Wedge w;
  if (n < 6)
  {
    w.Why = "the mesh has fewer than 6 points";
    return w;
  }
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k)
  {
    lo[k] = std::numeric_limits<double>::max();
    hi[k] = -lo[k];
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], xyz[3 * i + k]);
      hi[k] = std::max(hi[k], xyz[3 * i + k]);
    }
  }
  const double size[3] = { hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] };
  int thin = 2;
  for (int k = 1; k >= 0; --k)
  {
    if (size[k] < size[thin])
    {
      thin = k;
    }
  }
  const double largest = std::max({ size[0], size[1], size[2] });
  std::ostringstream why;
  if (!(size[thin] > 1e-9 * largest))
  {
    why << "the mesh is flat (no thickness along " << Names[thin] << "): a 2D r-z plane, not a wedge";
    w.Why = why.str();
    return w;
  }
  struct Candidate
  {
    int a, r;
    double lower[3], upper[3];
    double residual;
  };
  std::vector<Candidate> found;
  for (int a : { (thin + 1) % 3, (thin + 2) % 3 })
  {
    const int r = 3 - a - thin;
    Candidate c{ a, r, {}, {}, std::numeric_limits<double>::max() };
    std::vector<char> all(n, 1), up(n, 0), down(n, 0);
    double mid[3];
    if (!FitPlane(xyz, n, a, r, thin, all, mid))
    {
      continue;
    }
    const double eps = 1e-6 * largest;
    std::size_t nu = 0, nd = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double d = xyz[3 * i + thin] - (mid[0] + mid[1] * xyz[3 * i + r] + mid[2] * xyz[3 * i + a]);
      up[i] = d >= -eps;
      down[i] = d <= eps;
      nu += up[i];
      nd += down[i];
    }
    if (nu < 3 || nd < 3 || !FitPlane(xyz, n, a, r, thin, up, c.upper) ||
      !FitPlane(xyz, n, a, r, thin, down, c.lower))
    {
      continue;
    }
    double res = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double* p = xyz + 3 * i;
      const double du = std::abs(p[thin] - (c.upper[0] + c.upper[1] * p[r] + c.upper[2] * p[a]));
      const double dd = std::abs(p[thin] - (c.lower[0] + c.lower[1] * p[r] + c.lower[2] * p[a]));
      res = std::max(res, std::min(du, dd));
    }
    c.residual = res;
    found.push_back(c);
  }
  if (found.empty())
  {
    w.Why = "no two planes could be fitted to the mesh's points";
    return w;
  }
  const Candidate* best = &*std::min_element(found.begin(), found.end(),
    [](const Candidate& x, const Candidate& y) { return x.residual < y.residual; });
  // the line where the two planes meet, from their normals (t - c1 r - c2 a = c0): both
  // candidates fit the same two planes, so the one whose axial axis is along that line is taken
  double line[3] = { 0, 0, 0 }, length = 0;
  {
    double nu[3], nl[3];
    nu[best->r] = -best->upper[1];
    nu[best->a] = -best->upper[2];
    nu[thin] = 1;
    nl[best->r] = -best->lower[1];
    nl[best->a] = -best->lower[2];
    nl[thin] = 1;
    line[0] = nu[1] * nl[2] - nu[2] * nl[1];
    line[1] = nu[2] * nl[0] - nu[0] * nl[2];
    line[2] = nu[0] * nl[1] - nu[1] * nl[0];
    length = std::sqrt(line[0] * line[0] + line[1] * line[1] + line[2] * line[2]);
  }
  int along = best->a;
  if (length > 1e-12)
  {
    for (int k = 0; k < 3; ++k)
      if (std::abs(line[k]) > std::abs(line[along]))
        along = k;
    for (const Candidate& other : found)
      if (other.a == along && other.residual <= best->residual + 1e-9 * largest)
        best = &other;
  }
  const Candidate& c = *best;
  w.Axial = c.a;
  w.Radial = c.r;
  w.Thin = thin;
  w.Residual = c.residual;
  const double tolerance = 1e-3 * size[thin] + 1e-9 * largest;
  if (c.residual > tolerance)
  {
    why << "its points do not lie on two planes (one is " << c.residual << " from the nearer, "
        << 100 * c.residual / size[thin] << " % of the thickness along " << Names[thin]
        << "): more than one cell across, or curved sides";
    w.Why = why.str();
    return w;
  }
  w.OnTwoPlanes = true;
  const double axialRun = size[c.a];
  // the planes' common line must run along the axial axis: sloped alike along it (the line
  // tilted toward the thin axis: a wedge turned about its radial axis) or differently (tilted
  // within the mid-plane), measured as the drift across the axial run against the tolerance
  // (issue 48: a wedge turned 20 deg about its radial axis was revolved about x, 10 % valid)
  const double common = 0.5 * (c.upper[2] + c.lower[2]), apart = c.upper[2] - c.lower[2];
  if (along == thin || std::abs(common) * axialRun > tolerance || std::abs(apart) * axialRun > tolerance)
  {
    const double cosine = length > 0 ? std::min(1.0, std::abs(line[along]) / length) : 1.0;
    why.precision(3);
    why << "its two planes meet along a line tilted " << std::acos(cosine) * 180.0 / 3.14159265358979323846
        << " deg from " << Names[along];
    if (length > 0)
    {
      auto component = [&](int k) { return std::abs(line[k]) < 1e-6 * length ? 0.0 : line[k] / length; };
      why << " (direction " << component(0) << ", " << component(1) << ", " << component(2) << ")";
    }
    why << ": its axis is not along x, y or z; rotate the mesh so that its axis lies along a "
        << "coordinate axis (Transform), or give the r-z plane";
    w.Why = why.str();
    return w;
  }
  const double phiU = sch_atan_d(c.upper[1]), phiL = sch_atan_d(c.lower[1]);
  w.Angle = std::abs(phiU - phiL);
  if (w.Angle < 1e-9)
  {
    why << "its two sides are parallel (a slab of constant thickness along " << Names[thin]
        << ", not a wedge): a planar 2D case, for Symmetry Planar";
    w.Why = why.str();
    return w;
  }
  if (w.Angle > WedgeMaxAngleDegrees * 3.14159265358979323846 / 180.0)
  {
    why << "its two planes are " << w.Angle * 180.0 / 3.14159265358979323846
        << " deg apart, more than the " << WedgeMaxAngleDegrees << " deg of a small-angle wedge "
        << "(the largest taken as one: a wedge's cells are revolved from its mid-plane, which "
        << "holds for a few degrees); give the r-z plane (a Slice through the axis) instead";
    w.Why = why.str();
    return w;
  }
  // the common line: upper and lower meet where their thin coordinates agree
  w.AxisRadial = (c.lower[0] - c.upper[0]) / (c.upper[1] - c.lower[1]);
  w.AxisThin = c.upper[0] + c.upper[1] * w.AxisRadial;
  w.MidTilt = 0.5 * (phiU + phiL);
  double below = 0.0, above = 0.0, reach = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double dr = xyz[3 * i + c.r] - w.AxisRadial, dt = xyz[3 * i + thin] - w.AxisThin;
    below = std::min(below, dr);
    above = std::max(above, dr);
    // along the mid-plane, the half plane that is sampled (the sides' corners lie a hair beyond)
    reach = std::max(reach, std::abs(dr * std::cos(w.MidTilt) + dt * std::sin(w.MidTilt)));
  }
  const double side = 1e-6 * largest + 1e-3 * size[c.r];
  if (below < -side && above > side)
  {
    why << "the mesh lies on both sides of the planes' common line (" << Names[c.r] << " from "
        << w.AxisRadial + below << " to " << w.AxisRadial + above << " about " << w.AxisRadial
        << "): not a wedge about an axis";
    w.Why = why.str();
    return w;
  }
  w.Sign = above > side ? 1.0 : -1.0;
  w.Reach = reach;
  w.Found = true;
  return w;
}

} // namespace schlieren
