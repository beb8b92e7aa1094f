// SPDX-License-Identifier: BSD-3-Clause
// A mesh sampled at the points of an image grid, cell by cell (SchlierenSample.h).
#include "SchlierenSample.h"

#include "SchlierenEngine.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace schlieren
{
namespace
{
enum : int
{
  EMPTY = 0,
  TRIANGLE = 5,
  PIXEL = 8,
  QUAD = 9,
  TETRA = 10,
  VOXEL = 11,
  HEXAHEDRON = 12,
  WEDGE = 13,
  PYRAMID = 14,
};

/** Points a sampled type has; 0: a type passed over (no volume); -1: refused. `faces`: the points
 * mode, where triangles, pixels and quads are sampled too (a 2D mesh in its plane) and the faces
 * it cannot sample (strips, polygons) are refused. */
int PointsOfType(int type, bool faces)
{
  if (faces)
  {
    switch (type)
    {
      case TRIANGLE:
        return 3;
      case PIXEL:
      case QUAD:
        return 4;
      case 6:
      case 7:
        return -1;
      default:
        break;
    }
  }
  switch (type)
  {
    case TETRA:
      return 4;
    case VOXEL:
    case HEXAHEDRON:
      return 8;
    case WEDGE:
      return 6;
    case PYRAMID:
      return 5;
    case EMPTY:
    case 1:
    case 2:
    case 3:
    case 4:
    case 5:
    case 6:
    case 7:
    case 8:
    case 9: // vertices to quads
    case 21:
    case 22:
    case 23: // quadratic faces
      return 0;
    default:
      return -1;
  }
}

/** The determinant of the columns c1, c2, c3 (vtkMath::Determinant3x3's order of operations). */
inline double Det(const double c1[3], const double c2[3], const double c3[3])
{
  return c1[0] * c2[1] * c3[2] + c2[0] * c3[1] * c1[2] + c3[0] * c1[1] * c2[2] -
    c1[0] * c3[1] * c2[2] - c2[0] * c1[1] * c3[2] - c3[0] * c2[1] * c1[2];
}

constexpr double Tolerance = 1e-3; // parametric: inside within it, Newton converged below it
constexpr double HexConverged = 1e-5;
constexpr double HexOutside = 1e-6;
constexpr double Diverged = 1e6;
constexpr int Iterations = 10;

/** A cell's points, copied (x, y, z each). */
struct Cell
{
  int Type = 0;
  int Count = 0;
  std::int64_t Ids[8];
  double X[8][3];
  double Flat = 0.0;   ///< a face's: how far from its plane a point may lie (1e-6 of its box)
  double Margin = 0.0; ///< a face's parametric tolerance: 0 (VTK's), then 1e-3 for the rest
};

// Interpolation functions and their derivatives (r, then s, then t: Count values each), in
// parametric coordinates p, of the cells solved by Newton's iteration.
void HexFunctions(const double p[3], double* w, double* d)
{
  const double r = p[0], s = p[1], t = p[2];
  const double rm = 1.0 - r, sm = 1.0 - s, tm = 1.0 - t;
  w[0] = rm * sm * tm;
  w[1] = r * sm * tm;
  w[2] = r * s * tm;
  w[3] = rm * s * tm;
  w[4] = rm * sm * t;
  w[5] = r * sm * t;
  w[6] = r * s * t;
  w[7] = rm * s * t;
  if (!d)
    return;
  d[0] = -sm * tm;
  d[1] = sm * tm;
  d[2] = s * tm;
  d[3] = -s * tm;
  d[4] = -sm * t;
  d[5] = sm * t;
  d[6] = s * t;
  d[7] = -s * t;
  d[8] = -rm * tm;
  d[9] = -r * tm;
  d[10] = r * tm;
  d[11] = rm * tm;
  d[12] = -rm * t;
  d[13] = -r * t;
  d[14] = r * t;
  d[15] = rm * t;
  d[16] = -rm * sm;
  d[17] = -r * sm;
  d[18] = -r * s;
  d[19] = -rm * s;
  d[20] = rm * sm;
  d[21] = r * sm;
  d[22] = r * s;
  d[23] = rm * s;
}

void WedgeFunctions(const double p[3], double* w, double* d)
{
  const double r = p[0], s = p[1], t = p[2];
  w[0] = (1.0 - r - s) * (1.0 - t);
  w[1] = r * (1.0 - t);
  w[2] = s * (1.0 - t);
  w[3] = (1.0 - r - s) * t;
  w[4] = r * t;
  w[5] = s * t;
  if (!d)
    return;
  const double dr[6] = { -1.0 + t, 1.0 - t, 0.0, -t, t, 0.0 };
  const double ds[6] = { -1.0 + t, 0.0, 1.0 - t, -t, 0.0, t };
  const double dt[6] = { -1.0 + r + s, -r, -s, 1.0 - r - s, r, s };
  std::copy(dr, dr + 6, d);
  std::copy(ds, ds + 6, d + 6);
  std::copy(dt, dt + 6, d + 12);
}

void PyramidFunctions(const double p[3], double* w, double* d)
{
  const double r = p[0], s = p[1], t = p[2];
  const double rm = 1.0 - r, sm = 1.0 - s, tm = 1.0 - t;
  w[0] = rm * sm * tm;
  w[1] = r * sm * tm;
  w[2] = r * s * tm;
  w[3] = rm * s * tm;
  w[4] = t;
  if (!d)
    return;
  const double dr[5] = { -sm * tm, sm * tm, s * tm, -s * tm, 0.0 };
  const double ds[5] = { -rm * tm, -r * tm, r * tm, rm * tm, 0.0 };
  const double dt[5] = { -rm * sm, -r * sm, -r * s, -rm * s, 1.0 };
  std::copy(dr, dr + 5, d);
  std::copy(ds, ds + 5, d + 5);
  std::copy(dt, dt + 5, d + 10);
}

inline double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/**
 * A face of a 2D mesh (the points mode): 1 where `x` lies on it, within Flat of its plane (w: its
 * weights there, those of vtkPixel, vtkTriangle and vtkQuad). A pixel's coordinates exactly, as a
 * voxel's; a triangle's from the projection onto its plane; a quad's by Gauss-Newton from
 * (0.5, 0.5) to 1e-12 (20 steps at most), in its plane where it is planar. Inside: parametric
 * coordinates within c.Margin of [0, 1].
 */
int InsideFace(const Cell& c, const double x[3], double* w)
{
  const double lo = -c.Margin, hi = 1.0 + c.Margin;
  if (c.Type == PIXEL)
  {
    // points 1 and 2 lie one step from point 0 along two axes, the third is the normal
    int a = 0, b = 0;
    for (int i = 1; i < 3; ++i)
    {
      if (std::fabs(c.X[1][i] - c.X[0][i]) > std::fabs(c.X[1][a] - c.X[0][a]))
        a = i;
      if (std::fabs(c.X[2][i] - c.X[0][i]) > std::fabs(c.X[2][b] - c.X[0][b]))
        b = i;
    }
    const double da = c.X[1][a] - c.X[0][a], db = c.X[2][b] - c.X[0][b];
    if (a == b || da == 0.0 || db == 0.0)
      return 0;
    const int normal = 3 - a - b;
    const double r = (x[a] - c.X[0][a]) / da, s = (x[b] - c.X[0][b]) / db;
    const double rm = 1.0 - r, sm = 1.0 - s;
    w[0] = rm * sm;
    w[1] = r * sm;
    w[2] = rm * s;
    w[3] = r * s;
    return r >= lo && r <= hi && s >= lo && s <= hi &&
      std::fabs(x[normal] - c.X[0][normal]) <= c.Flat;
  }
  if (c.Type == TRIANGLE)
  {
    double e1[3], e2[3], d[3];
    for (int i = 0; i < 3; ++i)
    {
      e1[i] = c.X[1][i] - c.X[0][i];
      e2[i] = c.X[2][i] - c.X[0][i];
      d[i] = x[i] - c.X[0][i];
    }
    const double a11 = Dot(e1, e1), a12 = Dot(e1, e2), a22 = Dot(e2, e2);
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 0.0))
      return 0;
    const double b1 = Dot(d, e1), b2 = Dot(d, e2);
    const double u = (a22 * b1 - a12 * b2) / det, v = (a11 * b2 - a12 * b1) / det;
    w[0] = 1.0 - u - v;
    w[1] = u;
    w[2] = v;
    double off2 = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      const double o = d[i] - u * e1[i] - v * e2[i];
      off2 += o * o;
    }
    return u >= lo && u <= hi && v >= lo && v <= hi && w[0] >= lo && w[0] <= hi &&
      off2 <= c.Flat * c.Flat;
  }
  // a quad: P(r, s) = sum of w_i X_i, bilinear; Gauss-Newton on |P - x|^2
  double r = 0.5, s = 0.5;
  bool converged = false;
  double off2 = 0.0;
  for (int iteration = 0; iteration <= 20; ++iteration) // 20 steps, then the offset
  {
    const double rm = 1.0 - r, sm = 1.0 - s;
    const double q[4] = { rm * sm, r * sm, r * s, rm * s };
    const double dr[4] = { -sm, sm, s, -s };
    const double ds[4] = { -rm, -r, r, rm };
    double f[3] = { 0, 0, 0 }, jr[3] = { 0, 0, 0 }, js[3] = { 0, 0, 0 };
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j)
      {
        f[j] += q[i] * c.X[i][j];
        jr[j] += dr[i] * c.X[i][j];
        js[j] += ds[i] * c.X[i][j];
      }
    for (int j = 0; j < 3; ++j)
      f[j] = x[j] - f[j];
    off2 = Dot(f, f);
    if (converged)
      break;
    const double a11 = Dot(jr, jr), a12 = Dot(jr, js), a22 = Dot(js, js);
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 0.0))
      return 0;
    const double b1 = Dot(f, jr), b2 = Dot(f, js);
    const double stepR = (a22 * b1 - a12 * b2) / det, stepS = (a11 * b2 - a12 * b1) / det;
    r += stepR;
    s += stepS;
    if (!(std::fabs(r) < Diverged && std::fabs(s) < Diverged))
      return 0;
    converged = std::fabs(stepR) < 1e-12 && std::fabs(stepS) < 1e-12;
  }
  if (!converged)
    return 0;
  const double rm = 1.0 - r, sm = 1.0 - s;
  w[0] = rm * sm;
  w[1] = r * sm;
  w[2] = r * s;
  w[3] = rm * s;
  return r >= lo && r <= hi && s >= lo && s <= hi && off2 <= c.Flat * c.Flat;
}

/**
 * 1 where `x` lies in the cell (weights[] set: the cell's interpolation weights at x), 0 where it
 * does not or the cell is degenerate there: vtkCell::EvaluatePosition's answer and weights.
 */
int Inside(const Cell& c, const double x[3], double* w)
{
  const double lo = -Tolerance, hi = 1.0 + Tolerance;
  if (c.Type == TETRA)
  {
    double rhs[3], c1[3], c2[3], c3[3];
    for (int i = 0; i < 3; ++i)
    {
      rhs[i] = x[i] - c.X[0][i];
      c1[i] = c.X[1][i] - c.X[0][i];
      c2[i] = c.X[2][i] - c.X[0][i];
      c3[i] = c.X[3][i] - c.X[0][i];
    }
    const double det = Det(c1, c2, c3);
    if (det == 0.0)
      return 0;
    const double p0 = Det(rhs, c2, c3) / det;
    const double p1 = Det(c1, rhs, c3) / det;
    const double p2 = Det(c1, c2, rhs) / det;
    const double p3 = 1.0 - p0 - p1 - p2;
    w[0] = p3;
    w[1] = p0;
    w[2] = p1;
    w[3] = p2;
    return p0 >= lo && p0 <= hi && p1 >= lo && p1 <= hi && p2 >= lo && p2 <= hi && p3 >= lo &&
      p3 <= hi;
  }
  if (c.Type == VOXEL)
  {
    // points 1, 2 and 4 lie one step from point 0 along x, y and z
    double p[3];
    p[0] = (x[0] - c.X[0][0]) / (c.X[1][0] - c.X[0][0]);
    p[1] = (x[1] - c.X[0][1]) / (c.X[2][1] - c.X[0][1]);
    p[2] = (x[2] - c.X[0][2]) / (c.X[4][2] - c.X[0][2]);
    const double r = p[0], s = p[1], t = p[2];
    const double rm = 1.0 - r, sm = 1.0 - s, tm = 1.0 - t;
    w[0] = rm * sm * tm;
    w[1] = r * sm * tm;
    w[2] = rm * s * tm;
    w[3] = r * s * tm;
    w[4] = rm * sm * t;
    w[5] = r * sm * t;
    w[6] = rm * s * t;
    w[7] = r * s * t;
    return p[0] >= 0.0 && p[0] <= 1.0 && p[1] >= 0.0 && p[1] <= 1.0 && p[2] >= 0.0 && p[2] <= 1.0;
  }
  if (c.Type == PIXEL || c.Type == TRIANGLE || c.Type == QUAD)
  {
    return InsideFace(c, x, w);
  }
  void (*functions)(const double*, double*, double*) = c.Type == HEXAHEDRON ? HexFunctions
    : c.Type == WEDGE                                                       ? WedgeFunctions
                                                                            : PyramidFunctions;
  // a scale for a determinant that says the cell is degenerate at the estimate: 1e-5 of the
  // cube of its longest diagonal (hexahedron) or edge (wedge; a pyramid: of the box around it)
  auto distance2 = [&c](int a, int b)
  {
    const double dx = c.X[a][0] - c.X[b][0], dy = c.X[a][1] - c.X[b][1], dz = c.X[a][2] - c.X[b][2];
    return dx * dx + dy * dy + dz * dz;
  };
  double longest = 0.0;
  if (c.Type == HEXAHEDRON)
  {
    static const int diagonals[4][2] = { { 0, 6 }, { 1, 7 }, { 2, 4 }, { 3, 5 } };
    for (const auto& e : diagonals)
      longest = std::max(longest, distance2(e[0], e[1]));
  }
  else if (c.Type == WEDGE)
  {
    static const int edges[9][2] = {
      { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 }, { 0, 3 }, { 1, 4 }, { 2, 5 }
    };
    for (const auto& e : edges)
      longest = std::max(longest, distance2(e[0], e[1]));
  }
  else
  {
    for (int a = 0; a < 3; ++a)
    {
      double mn = c.X[0][a], mx = c.X[0][a];
      for (int i = 1; i < c.Count; ++i)
      {
        mn = std::min(mn, c.X[i][a]);
        mx = std::max(mx, c.X[i][a]);
      }
      longest += (mx - mn) * (mx - mn);
    }
  }
  const double degenerate = std::min(1e-20, 1e-5 * std::pow(longest, 1.5));
  // a hexahedron converges further and is held to its faces more tightly (VTK's own constants)
  const double converge = c.Type == HEXAHEDRON ? HexConverged : Tolerance;
  const double margin = c.Type == HEXAHEDRON ? HexOutside : Tolerance;
  const int n = c.Count;
  double d[24];
  double p[3] = { 0.5, 0.5, 0.5 }, previous[3] = { 0.5, 0.5, 0.5 };
  bool converged = false;
  for (int iteration = 0; !converged && iteration < Iterations; ++iteration)
  {
    functions(p, w, d);
    double f[3] = { 0, 0, 0 }, cr[3] = { 0, 0, 0 }, cs[3] = { 0, 0, 0 }, ct[3] = { 0, 0, 0 };
    for (int i = 0; i < n; ++i)
    {
      const double* pt = c.X[i];
      for (int j = 0; j < 3; ++j)
      {
        f[j] += pt[j] * w[i];
        cr[j] += pt[j] * d[i];
        cs[j] += pt[j] * d[i + n];
        ct[j] += pt[j] * d[i + 2 * n];
      }
    }
    for (int j = 0; j < 3; ++j)
      f[j] -= x[j];
    const double det = Det(cr, cs, ct);
    if (std::fabs(det) < degenerate)
      return 0;
    p[0] = previous[0] - Det(f, cs, ct) / det;
    p[1] = previous[1] - Det(cr, f, ct) / det;
    p[2] = previous[2] - Det(cr, cs, f) / det;
    if (std::fabs(p[0] - previous[0]) < converge && std::fabs(p[1] - previous[1]) < converge &&
      std::fabs(p[2] - previous[2]) < converge)
      converged = true;
    else if (std::fabs(p[0]) > Diverged || std::fabs(p[1]) > Diverged || std::fabs(p[2]) > Diverged)
      return 0;
    else
      std::copy(p, p + 3, previous);
  }
  if (!converged)
    return 0;
  functions(p, w, nullptr);
  const double l = -margin, h = 1.0 + margin;
  const bool box = p[0] >= l && p[0] <= h && p[1] >= l && p[1] <= h && p[2] >= l && p[2] <= h;
  return box && (c.Type != WEDGE || p[0] + p[1] <= h);
}

std::string Text(std::int64_t v)
{
  return std::to_string(v);
}

bool Structured(const SampleMesh& m)
{
  return m.StructuredDims[0] > 0 && m.StructuredDims[1] > 0 && m.StructuredDims[2] > 0;
}

/** Writes the value of a point array at grid point `p`: Σ weight x value in double, as
 * vtkDataArray::InterpolateTuple. */
template<typename T>
void Interpolate(const SampleArray& a, const Cell& c, const double* w, std::int64_t p)
{
  const T* in = static_cast<const T*>(a.In);
  T* out = static_cast<T*>(a.Out);
  const int nc = a.Components;
  for (int k = 0; k < nc; ++k)
  {
    double v = 0.0;
    for (int i = 0; i < c.Count; ++i)
      v += w[i] * static_cast<double>(in[c.Ids[i] * nc + k]);
    out[p * nc + k] = static_cast<T>(v);
  }
}
} // namespace

std::string SampleCellTypeName(int type)
{
  switch (type)
  {
    case 0:
      return "an empty cell";
    case 1:
      return "vertex";
    case 2:
      return "poly-vertex";
    case 3:
      return "line";
    case 4:
      return "poly-line";
    case 5:
      return "triangle";
    case 6:
      return "triangle strip";
    case 7:
      return "polygon";
    case 8:
      return "pixel";
    case 9:
      return "quad";
    case TETRA:
      return "tetrahedron";
    case VOXEL:
      return "voxel";
    case HEXAHEDRON:
      return "hexahedron";
    case WEDGE:
      return "wedge";
    case PYRAMID:
      return "pyramid";
    case 15:
      return "pentagonal prism";
    case 16:
      return "hexagonal prism";
    case 24:
      return "quadratic tetrahedron";
    case 25:
      return "quadratic hexahedron";
    case 26:
      return "quadratic wedge";
    case 27:
      return "quadratic pyramid";
    case 42:
      return "polyhedron";
    default:
      return "cell type " + std::to_string(type);
  }
}

std::int64_t SampleCellCount(const SampleMesh& m)
{
  if (!Structured(m))
    return m.NumberOfCells;
  std::int64_t n = 1;
  for (int a = 0; a < 3; ++a)
    if (m.StructuredDims[a] > 1)
      n *= m.StructuredDims[a] - 1;
  return n;
}

namespace
{
/** The mesh and the arrays, for `outputs` points sampled (CheckSample's, CheckSamplePoints'). */
void CheckMesh(const SampleMesh& m,
  std::int64_t outputs,
  const std::vector<SampleArray>& arrays,
  bool faces)
{
  const std::string f = "The cell sampler: ";
  if (m.NumberOfPoints < 0 || (m.NumberOfPoints > 0 && !m.Points))
    throw Error(f + "points: " + Text(m.NumberOfPoints) + " points and " +
      (m.Points ? "an array" : "no array") + ".");
  std::int64_t cells = 0;
  if (Structured(m))
  {
    std::int64_t n = 1;
    for (int a = 0; a < 3; ++a)
    {
      if (n > (std::int64_t(1) << 40) / m.StructuredDims[a])
        throw Error(f + "the structured grid has more than 2^40 points.");
      n *= m.StructuredDims[a];
    }
    if (n != m.NumberOfPoints)
      throw Error(f + "points holds " + Text(m.NumberOfPoints) + " points; a structured grid of " +
        Text(m.StructuredDims[0]) + " x " + Text(m.StructuredDims[1]) + " x " +
        Text(m.StructuredDims[2]) + " needs " + Text(n) + ".");
    cells = SampleCellCount(m);
  }
  else
  {
    cells = m.NumberOfCells;
    if (cells < 0)
      throw Error(f + "the number of cells is " + Text(cells) + ".");
    if (cells > 0 && (!m.CellTypes || !m.Offsets))
      throw Error(f + "cell_types and offsets must be given for " + Text(cells) + " cells.");
    if (m.ConnectivityLength < 0 || (m.ConnectivityLength > 0 && !m.Connectivity))
      throw Error(f + "connectivity is missing or its length (" + Text(m.ConnectivityLength) +
        ") is negative.");
    if (cells > 0 && m.Offsets[0] != 0)
      throw Error(f + "offsets[0] is " + Text(m.Offsets[0]) + "; it must be 0.");
    if (cells > 0 && m.Offsets[cells] != m.ConnectivityLength)
      throw Error(f + "offsets[" + Text(cells) + "] (the last of the " + Text(cells + 1) +
        " offsets) is " + Text(m.Offsets[cells]) + "; connectivity holds " +
        Text(m.ConnectivityLength) + " ids.");
    for (std::int64_t c = 0; c < cells; ++c)
    {
      const std::int64_t size = m.Offsets[c + 1] - m.Offsets[c];
      if (size < 0)
        throw Error(f + "offsets decrease at cell " + Text(c) + ".");
      const int type = m.CellTypes[c];
      const int wanted = PointsOfType(type, faces);
      if (wanted < 0)
        throw Error(f + "cell " + Text(c) + " is a " + SampleCellTypeName(type) + " (VTK type " +
          Text(type) +
          "), which the sampler does not handle (tetrahedra, voxels, hexahedra, "
          "wedges and pyramids" +
          std::string(faces ? "; triangles, pixels and quads of a 2D mesh"
                            : "; faces and lines are passed over") +
          "). Split the cells first (Tetrahedralize" + (faces ? ", Triangulate" : "") +
          ", or the OpenFOAM reader's Decompose polyhedra).");
      if (wanted > 0 && size != wanted)
        throw Error(f + "cell " + Text(c) + " is a " + SampleCellTypeName(type) + " with " +
          Text(size) + " points; a " + SampleCellTypeName(type) + " has " + Text(wanted) + ".");
    }
    for (std::int64_t i = 0; i < m.ConnectivityLength; ++i)
      if (m.Connectivity[i] < 0 || m.Connectivity[i] >= m.NumberOfPoints)
        throw Error(f + "connectivity[" + Text(i) + "] is point " + Text(m.Connectivity[i]) +
          "; the mesh has " + Text(m.NumberOfPoints) + " points.");
  }
  for (const SampleArray& a : arrays)
  {
    const std::string name = "array '" + a.Name + "'";
    if (a.Components < 1)
      throw Error(f + name + " has " + Text(a.Components) + " components.");
    if (!a.Cells && a.ValueBytes != 4 && a.ValueBytes != 8)
      throw Error(f + name +
        ": a point array is interpolated as float (4 bytes) or double (8), "
        "not " +
        Text(a.ValueBytes) + "-byte values.");
    if (a.Cells && (a.ValueBytes < 1 || a.ValueBytes > 16))
      throw Error(f + name + ": " + Text(a.ValueBytes) + "-byte values.");
    const std::int64_t tuples = a.Cells ? cells : m.NumberOfPoints;
    const std::int64_t needed = tuples * a.Components;
    if (a.InValues != needed || (needed > 0 && !a.In))
      throw Error(f + name + " holds " + Text(a.In ? a.InValues : 0) + " values; " + Text(tuples) +
        (a.Cells ? " cells" : " points") + " x " + Text(a.Components) + " components need " +
        Text(needed) + ".");
    if (!a.Out)
      throw Error(f + name + ": no output array (" + Text(outputs) + " x " + Text(a.Components) +
        " values).");
  }
}
} // namespace

void CheckSample(const SampleMesh& m, const SampleGrid& g, const std::vector<SampleArray>& arrays)
{
  const std::string f = "The cell sampler: ";
  std::int64_t gridPoints = 1;
  for (int a = 0; a < 3; ++a)
  {
    if (g.Dims[a] < 1)
      throw Error(f + "the image grid's dimensions must be at least 1 (" + Text(g.Dims[0]) + " " +
        Text(g.Dims[1]) + " " + Text(g.Dims[2]) + ").");
    if (!std::isfinite(g.Origin[a]) || !std::isfinite(g.Spacing[a]) || !(g.Spacing[a] > 0.0))
      throw Error(f + "the image grid's origin must be finite and its spacing above 0.");
    if (gridPoints > (std::int64_t(1) << 40) / g.Dims[a])
      throw Error(f + "the image grid has more than 2^40 points.");
    gridPoints *= g.Dims[a];
  }
  CheckMesh(m, gridPoints, arrays, false);
}

void CheckSamplePoints(const SampleMesh& m,
  const double* at,
  std::int64_t count,
  const std::vector<SampleArray>& arrays)
{
  if (count < 0 || (count > 0 && !at))
    throw Error("The cell sampler: " + Text(count) + " points to sample and " +
      (at ? "an array" : "no array") + ".");
  CheckMesh(m, count, arrays, true);
}


namespace
{
/**
 * Cell `c` of `m` into `cell` and its box into b (xmin, xmax, ...); false where it is passed over
 * (hidden, or a type with nothing to sample: `faces` as PointsOfType's).
 */
bool LoadCell(const SampleMesh& m, std::int64_t c, bool faces, Cell& cell, double b[6])
{
  if (m.SkipCells && m.SkipCells[c])
    return false;
  if (Structured(m))
  {
    const int* S = m.StructuredDims;
    const std::int64_t i = c % (S[0] - 1), j = (c / (S[0] - 1)) % (S[1] - 1),
                       k = c / ((S[0] - 1) * std::int64_t(S[1] - 1));
    const std::int64_t p0 = i + S[0] * (j + std::int64_t(S[1]) * k);
    const std::int64_t plane = std::int64_t(S[0]) * S[1];
    const std::int64_t ids[8] = { p0,
      p0 + 1,
      p0 + 1 + S[0],
      p0 + S[0],
      p0 + plane,
      p0 + plane + 1,
      p0 + plane + 1 + S[0],
      p0 + plane + S[0] };
    cell.Type = HEXAHEDRON;
    cell.Count = 8;
    std::copy(ids, ids + 8, cell.Ids);
  }
  else
  {
    cell.Type = m.CellTypes[c];
    cell.Count = PointsOfType(cell.Type, faces);
    if (cell.Count <= 0)
      return false; // no volume
    std::copy(m.Connectivity + m.Offsets[c], m.Connectivity + m.Offsets[c + 1], cell.Ids);
  }
  b[0] = b[2] = b[4] = 0.0;
  b[1] = b[3] = b[5] = -1.0;
  for (int i = 0; i < cell.Count; ++i)
  {
    const double* x = m.Points + 3 * cell.Ids[i];
    for (int a = 0; a < 3; ++a)
    {
      cell.X[i][a] = x[a];
      if (i == 0 || x[a] < b[2 * a])
        b[2 * a] = x[a];
      if (i == 0 || x[a] > b[2 * a + 1])
        b[2 * a + 1] = x[a];
    }
  }
  return true;
}

/** Every array's value at output point `p`, in `cell` (number `c`) with the weights `w`. */
void Store(const std::vector<SampleArray>& arrays,
  const Cell& cell,
  std::int64_t c,
  const double* w,
  std::int64_t p)
{
  for (const SampleArray& a : arrays)
  {
    if (a.Cells)
    {
      const std::size_t bytes = static_cast<std::size_t>(a.ValueBytes) * a.Components;
      std::memcpy(
        static_cast<char*>(a.Out) + p * bytes, static_cast<const char*>(a.In) + c * bytes, bytes);
    }
    else if (a.ValueBytes == 4)
      Interpolate<float>(a, cell, w, p);
    else
      Interpolate<double>(a, cell, w, p);
  }
}
} // namespace

std::int64_t SampleCells(const SampleMesh& m,
  const SampleGrid& g,
  const std::vector<SampleArray>& arrays,
  unsigned char* found)
{
  CheckSample(m, g, arrays);
  const int* D = g.Dims;
  const double* O = g.Origin;
  const double* H = g.Spacing;
  const int* S = m.StructuredDims;
  if (Structured(m) && (S[0] < 2 || S[1] < 2 || S[2] < 2))
    return 0; // a surface or a line of points: faces and edges, no volume
  const std::int64_t cells = SampleCellCount(m);
  std::int64_t count = 0;
  Cell cell;
  double w[8];
  for (std::int64_t c = 0; c < cells; ++c)
  {
    double b[6];
    if (!LoadCell(m, c, false, cell, b))
      continue;
    // the grid points in the cell's box (a hair wider: a point on a face is in it)
    int lo[3], hi[3];
    bool empty = false;
    for (int a = 0; a < 3 && !empty; ++a)
    {
      if (D[a] == 1)
      {
        lo[a] = hi[a] = 0;
        empty = O[a] < b[2 * a] || O[a] > b[2 * a + 1];
        continue;
      }
      const double eps = 1e-9;
      const double l = std::ceil((b[2 * a] - O[a]) / H[a] - eps);
      const double h = std::floor((b[2 * a + 1] - O[a]) / H[a] + eps);
      if (!(l <= h) || h < 0.0 || l > D[a] - 1)
      {
        empty = true;
        continue;
      }
      lo[a] = static_cast<int>(std::max(0.0, l));
      hi[a] = static_cast<int>(std::min(static_cast<double>(D[a] - 1), h));
    }
    if (empty)
      continue;
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
        {
          const std::int64_t p = (std::int64_t(z) * D[1] + y) * D[0] + x;
          if (found[p])
            continue;
          const double point[3] = { O[0] + x * H[0], O[1] + y * H[1], O[2] + z * H[2] };
          if (Inside(cell, point, w) != 1)
            continue;
          found[p] = 1;
          ++count;
          Store(arrays, cell, c, w, p);
        }
  }
  return count;
}

std::int64_t SamplePoints(const SampleMesh& m,
  const double* at,
  std::int64_t n,
  const std::vector<SampleArray>& arrays,
  unsigned char* found)
{
  CheckSamplePoints(m, at, n, arrays);
  const int* S = m.StructuredDims;
  if (n == 0 || (Structured(m) && (S[0] < 2 || S[1] < 2 || S[2] < 2)))
    return 0; // nothing to sample, or a structured surface (its faces are not given as cells)
  // The points in bins (a uniform grid over their box, about one point a bin; a flat axis one
  // bin), each bin's points in increasing order: a cell looks only at the bins its box meets.
  double lo[3], hi[3];
  bool any = false;
  for (std::int64_t i = 0; i < n; ++i)
  {
    const double* x = at + 3 * i;
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      continue; // never in a cell
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = any ? std::min(lo[a], x[a]) : x[a];
      hi[a] = any ? std::max(hi[a], x[a]) : x[a];
    }
    any = true;
  }
  if (!any)
    return 0;
  double volume = 1.0;
  int spread = 0;
  for (int a = 0; a < 3; ++a)
    if (hi[a] > lo[a])
    {
      volume *= hi[a] - lo[a];
      ++spread;
    }
  const double side = spread ? std::pow(volume / static_cast<double>(n), 1.0 / spread) : 1.0;
  int bins[3];
  double scale[3];
  for (int a = 0; a < 3; ++a)
  {
    const double count = hi[a] > lo[a] ? std::ceil((hi[a] - lo[a]) / side) : 1.0;
    bins[a] = static_cast<int>(std::max(1.0, std::min(1024.0, count)));
    scale[a] = hi[a] > lo[a] ? bins[a] / (hi[a] - lo[a]) : 0.0;
  }
  // at most about two bins a point (an extent that underflowed or overflowed the volume above
  // would ask for 1024^3): the axis with the most bins halved until they fit
  while (static_cast<double>(bins[0]) * bins[1] * bins[2] > 2.0 * static_cast<double>(n) + 8.0)
  {
    const int a = bins[0] >= bins[1] && bins[0] >= bins[2] ? 0 : (bins[1] >= bins[2] ? 1 : 2);
    bins[a] = (bins[a] + 1) / 2;
    scale[a] = hi[a] > lo[a] ? bins[a] / (hi[a] - lo[a]) : 0.0;
  }
  auto binOf = [&](int a, double v)
  {
    const double f = std::floor((v - lo[a]) * scale[a]);
    return static_cast<int>(std::max(0.0, std::min(static_cast<double>(bins[a] - 1), f)));
  };
  const std::size_t nb = static_cast<std::size_t>(bins[0]) * bins[1] * bins[2];
  std::vector<std::int64_t> start(nb + 1, 0), order;
  std::vector<std::size_t> binOfPoint(static_cast<std::size_t>(n), nb);
  for (std::int64_t i = 0; i < n; ++i)
  {
    const double* x = at + 3 * i;
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      continue;
    const std::size_t k =
      (static_cast<std::size_t>(binOf(2, x[2])) * bins[1] + binOf(1, x[1])) * bins[0] +
      binOf(0, x[0]);
    binOfPoint[i] = k;
    ++start[k + 1];
  }
  for (std::size_t k = 0; k < nb; ++k)
    start[k + 1] += start[k];
  order.resize(static_cast<std::size_t>(start[nb]));
  {
    std::vector<std::int64_t> next(start.begin(), start.end() - 1);
    for (std::int64_t i = 0; i < n; ++i)
      if (binOfPoint[i] < nb)
        order[next[binOfPoint[i]]++] = i;
  }

  const std::int64_t cells = SampleCellCount(m);
  std::int64_t count = 0;
  Cell cell;
  double w[8];
  // Faces are tested as VTK tests them (inside exactly: the probe's cell, bit for bit on the
  // suite's 2D meshes), then, for the points that no cell held, again with 3D cells' tolerance
  // (1e-3): a point on an edge that round-off put outside both faces beside it is not lost.
  bool faces = false;
  for (int pass = 0; pass < 2 && (pass == 0 || (faces && count < n)); ++pass)
  {
    for (std::int64_t c = 0; c < cells; ++c)
    {
      double b[6];
      if (!LoadCell(m, c, true, cell, b))
        continue;
      // the box a hair wider (1e-9 of its longest side; a face: 1e-6 of it, off its plane too)
      const double longest = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
      const bool face = cell.Type == PIXEL || cell.Type == TRIANGLE || cell.Type == QUAD;
      faces = faces || face;
      if (pass == 1 && !face)
        continue;
      cell.Margin = pass == 0 ? 0.0 : Tolerance;
      cell.Flat = 1e-6 * longest;
      const double hair = face ? cell.Flat : 1e-9 * longest;
      int first[3], last[3];
      bool empty = false;
      for (int a = 0; a < 3; ++a)
      {
        b[2 * a] -= hair;
        b[2 * a + 1] += hair;
        empty = empty || b[2 * a + 1] < lo[a] || b[2 * a] > hi[a];
        first[a] = binOf(a, b[2 * a]);
        last[a] = binOf(a, b[2 * a + 1]);
      }
      if (empty)
        continue;
      for (int z = first[2]; z <= last[2]; ++z)
        for (int y = first[1]; y <= last[1]; ++y)
          for (int x = first[0]; x <= last[0]; ++x)
          {
            const std::size_t k = (static_cast<std::size_t>(z) * bins[1] + y) * bins[0] + x;
            for (std::int64_t q = start[k]; q < start[k + 1]; ++q)
            {
              const std::int64_t p = order[static_cast<std::size_t>(q)];
              if (found[p])
                continue;
              const double* point = at + 3 * p;
              if (point[0] < b[0] || point[0] > b[1] || point[1] < b[2] || point[1] > b[3] ||
                point[2] < b[4] || point[2] > b[5] || Inside(cell, point, w) != 1)
                continue;
              found[p] = 1;
              ++count;
              Store(arrays, cell, c, w, p);
            }
          }
    }
  }
  return count;
}

} // namespace schlieren
