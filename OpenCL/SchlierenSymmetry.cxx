// SPDX-License-Identifier: BSD-3-Clause
// RefractiveIndex's Symmetry Planar/Axisymmetric and wedges, on plain arrays (SchlierenSymmetry.h).
// Moved from the C++ filter (vtkRefractiveIndexInputs.cxx) with its messages word for word.
#include "SchlierenSymmetry.h"

#include "SchlierenEngine.h"       // schlieren::Error
#include "SchlierenIndexModels.h"  // AutomaticDimensions
#include "SchlierenWedge.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace schlieren
{
namespace
{
const char* const AxisNames = "xyz";
constexpr double Degrees = 180.0 / 3.14159265358979323846;

// Whether every point has one of at most two coordinates along `axis` (within `tol`).
bool OnTwoPlanes(const double* xyz, std::size_t n, int axis, double tol)
{
  if (!xyz || n == 0)
  {
    return false;
  }
  double planes[2];
  int found = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double x = xyz[3 * i + axis];
    bool known = false;
    for (int k = 0; k < found && !known; ++k)
    {
      known = std::abs(x - planes[k]) <= tol;
    }
    if (!known)
    {
      if (found == 2)
      {
        return false;
      }
      planes[found++] = x;
    }
  }
  return true;
}

/** The wedge (AxisFromWedge, Axisymmetric, a mesh): sets the plan's axis, crossing, tilt and note. */
Wedge FindWedge(const SymmetrySettings& s, const SymmetryInput& input, bool look, SymmetryPlan& plan)
{
  plan.AxisInUse = s.SymmetryAxis;
  plan.AxisRadial = 0.0;
  plan.MidTilt = 0.0;
  plan.WedgeNote.clear();
  Wedge wedge;
  if (!look || !s.AxisFromWedge)
  {
    return wedge;
  }
  wedge = DetectWedge(input.Points, input.Points ? input.Count : 0);
  std::ostringstream m;
  if (wedge.Found)
  {
    plan.AxisInUse = wedge.Axial;
    plan.AxisRadial = wedge.AxisRadial;
    plan.MidTilt = wedge.MidTilt;
    m << "RefractiveIndex: the input is an axisymmetric wedge (AxisFromWedge): two planes "
      << wedge.Angle * Degrees << " deg apart through the line along " << AxisNames[wedge.Axial]
      << " at " << AxisNames[wedge.Radial] << " = " << wedge.AxisRadial << ", "
      << AxisNames[wedge.Thin] << " = " << wedge.AxisThin
      << "; its mid-plane is revolved about that line (SymmetryAxis is not used).";
  }
  else if (wedge.Why.find("flat") == std::string::npos)
  {
    m << "RefractiveIndex: the input is not taken as a wedge (AxisFromWedge): " << wedge.Why
      << ". It is revolved about SymmetryAxis " << AxisNames[s.SymmetryAxis]
      << ", its mid-plane taken as the r-z plane.";
  }
  plan.WedgeNote = m.str();
  return wedge;
}
} // namespace

void SymmetryPlan::Geometry(double g[8]) const
{
  g[0] = this->Symmetry;
  g[1] = this->PlaneAxis;
  g[2] = this->PlaneCoordinate;
  g[3] = this->RadialSign;
  g[4] = this->RadialExtent;
  g[5] = this->AxisInUse;
  g[6] = this->AxisRadial;
  g[7] = this->MidTilt;
}

SymmetryPlan SymmetryPlan::FromGeometry(
  const double g[8], const int dims[3], const double origin[3], const double spacing[3])
{
  for (int k = 0; k < 8; ++k)
  {
    if (!std::isfinite(g[k]))
    {
      throw Error("geometry[" + std::to_string(k) + "] is not finite: give the 8 numbers that "
                  "schlieren_symmetry_plan wrote.");
    }
  }
  auto whole = [](double v) { return v == std::floor(v); };
  if (!whole(g[0]) || (g[0] != SymmetryPlanar && g[0] != SymmetryAxisymmetric) || !whole(g[1]) ||
    g[1] < 0 || g[1] > 2 || !whole(g[5]) || g[5] < 0 || g[5] > 2 ||
    (g[0] == SymmetryAxisymmetric && g[1] == g[5]))
  {
    std::ostringstream m;
    m << "geometry is " << g[0] << " " << g[1] << " ... " << g[5]
      << ": its Symmetry must be 1 (Planar) or 2 (Axisymmetric), its plane axis and symmetry axis "
         "0, 1 or 2 (different where Axisymmetric): give the 8 numbers that "
         "schlieren_symmetry_plan wrote.";
    throw Error(m.str());
  }
  SymmetryPlan p;
  p.Symmetry = static_cast<int>(g[0]);
  p.PlaneAxis = static_cast<int>(g[1]);
  p.PlaneCoordinate = g[2];
  p.RadialSign = g[3];
  p.RadialExtent = g[4];
  p.AxisInUse = static_cast<int>(g[5]);
  p.AxisRadial = g[6];
  p.MidTilt = g[7];
  for (int a = 0; a < 3; ++a)
  {
    if (dims[a] < 1 || !std::isfinite(origin[a]) || !std::isfinite(spacing[a]) || !(spacing[a] > 0))
    {
      throw Error("the grid's dims must be at least 1, its origin finite and its spacing "
                  "positive (the grid schlieren_symmetry_plan wrote).");
    }
    p.Dims[a] = dims[a];
    p.Origin[a] = origin[a];
    p.Spacing[a] = spacing[a];
  }
  return p;
}

std::string PlanSymmetry(const SymmetrySettings& s, const SymmetryInput& input, SymmetryPlan& plan)
{
  plan = SymmetryPlan();
  plan.Symmetry = s.Symmetry;
  const bool axisym = s.Symmetry == SymmetryAxisymmetric;
  if (s.Symmetry != SymmetryPlanar && !axisym)
  {
    return "PlanSymmetry: Symmetry is None: there is no symmetric grid to make.";
  }
  if (s.SymmetryAxis < 0 || s.SymmetryAxis > 2)
  {
    return "SymmetryAxis is " + std::to_string(s.SymmetryAxis) + ": it must be 0 (X), 1 (Y) or 2 (Z).";
  }
  if (!input.HasPoints)
  {
    return "The input has no points to make a volume of (Symmetry " +
      std::string(s.Symmetry == SymmetryPlanar ? "Planar" : "Axisymmetric") + ").";
  }
  const double* b = input.Bounds;
  const bool image = input.Image;
  int imageDims[3] = { 0, 0, 0 };
  if (image)
  {
    for (int a = 0; a < 3; ++a)
    {
      imageDims[a] = input.ImageExtent[2 * a + 1] - input.ImageExtent[2 * a] + 1;
    }
  }
  // The axis normal to the input's plane: an image's axis of fewest points, else the thinnest
  // side of the bounds (ties: the later axis, z before y before x).
  const Wedge wedge = FindWedge(s, input, axisym && !image, plan);
  int thin = wedge.Found ? wedge.Thin : -1;
  for (int a = 2; a >= 0 && !wedge.Found; --a)
  {
    if (axisym && a == plan.AxisInUse)
    {
      continue;
    }
    const double size = image ? imageDims[a] : b[2 * a + 1] - b[2 * a];
    const double best = thin < 0 ? 0 : (image ? imageDims[thin] : b[2 * thin + 1] - b[2 * thin]);
    if (thin < 0 || size < best)
    {
      thin = a;
    }
  }
  const double largest = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  if (!(largest > 0))
  {
    return "The input's bounds have zero size (a single point): nothing to make a volume of.";
  }
  if (axisym)
  {
    // The axis must lie in the input's plane: the thinnest side overall must not be along it.
    const double axisSize = b[2 * plan.AxisInUse + 1] - b[2 * plan.AxisInUse];
    const double thinSize = b[2 * thin + 1] - b[2 * thin];
    if (axisSize < thinSize || axisSize <= 1e-9 * largest)
    {
      std::ostringstream m;
      m << "SymmetryAxis " << AxisNames[s.SymmetryAxis]
        << " is normal to the input's plane (its bounds have no extent along it): choose an "
           "axis that lies in the plane of the r-z data.";
      return m.str();
    }
  }
  {
    // A plane normal to an axis: one point (an image: at most two, a one-cell-thick 2D mesh)
    // across it, or bounds thin next to the plane's own sides. Anything thicker is a 3D volume
    // or a tilted plane, which cutting at one plane would quietly turn into a wrong volume.
    double sides[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
    double inPlane = largest;
    for (int a = 0; a < 3; ++a)
      if (a != thin)
        inPlane = std::min(inPlane, sides[a]);
    bool thick = image ? imageDims[thin] > 2 : sides[thin] > 0.05 * inPlane;
    if (thick && !image)
    {
      // A mesh one cell thick (OpenFOAM's 2D cases: every point on one of two planes) is a
      // plane whatever its thickness next to its sides.
      thick = !(input.OneDataSet && OnTwoPlanes(input.Points, input.Count, thin, 1e-6 * largest));
    }
    if (thick && !wedge.Found && wedge.OnTwoPlanes)
    {
      // a wedge in shape (one cell across between two planes) that cannot be revolved as one:
      // its own reason (a tilted axis, an angle past the limit), not "a 3D volume"
      return "Symmetry Axisymmetric: the input is one cell across between two planes, as an "
             "axisymmetric wedge, but it cannot be revolved as one: " + wedge.Why + ".";
    }
    if (thick && !wedge.Found)
    {
      std::ostringstream m;
      m << "Symmetry " << (axisym ? "Axisymmetric" : "Planar") << " expects a 2D plane normal to "
        << "x, y or z" << (axisym ? " (an r-" + std::string(1, AxisNames[s.SymmetryAxis]) +
                                      " half plane holding SymmetryAxis)"
                                  : "")
        << "; the input spans " << sides[0] << " x " << sides[1] << " x " << sides[2];
      if (image)
        m << " world units with " << imageDims[0] << " x " << imageDims[1] << " x " << imageDims[2]
          << " points: a 3D volume. Use Symmetry None for a volume.";
      else
        m << " world units along all three axes: a 3D volume, or a plane that is not "
          << "axis-aligned. Use Symmetry None for a volume; rotate a tilted plane onto an axis "
          << "plane (Transform) first.";
      return m.str();
    }
  }
  plan.PlaneAxis = thin;
  plan.PlaneCoordinate = wedge.Found ? wedge.AxisThin : 0.5 * (b[2 * thin] + b[2 * thin + 1]);
  const bool automatic =
    s.SamplingDimensions[0] <= 0 || s.SamplingDimensions[1] <= 0 || s.SamplingDimensions[2] <= 0;
  int* dims = plan.Dims;
  double* origin = plan.Origin;
  double* spacing = plan.Spacing;
  double box[6];
  if (!axisym)
  {
    if (!(s.Span > 0) || !std::isfinite(s.Span))
    {
      return "Span is " + std::to_string(s.Span) +
        ": it must be positive (the width of the test section across the 2D flow, world units).";
    }
    const int p = (thin + 1) % 3, q = (thin + 2) % 3;
    if (image && automatic && !s.UseSamplingBounds)
    {
      // The image's own grid in its plane: no interpolation.
      for (int a : { p, q })
      {
        dims[a] = imageDims[a];
        origin[a] = input.ImageOrigin[a] + input.ImageExtent[2 * a] * input.ImageSpacing[a];
        spacing[a] = input.ImageSpacing[a];
      }
    }
    else
    {
      std::copy(b, b + 6, box);
      if (s.UseSamplingBounds)
      {
        for (int a : { p, q })
        {
          box[2 * a] = s.SamplingBounds[2 * a];
          box[2 * a + 1] = s.SamplingBounds[2 * a + 1];
        }
      }
      else
      {
        // A hair inside, so that the outermost points are found in the outermost cells.
        for (int a : { p, q })
        {
          const double c = 0.5 * (box[2 * a] + box[2 * a + 1]), r = 0.5 * (box[2 * a + 1] - box[2 * a]);
          box[2 * a] = c - r * (1.0 - 1e-6);
          box[2 * a + 1] = c + r * (1.0 - 1e-6);
        }
      }
      box[2 * thin] = box[2 * thin + 1] = plan.PlaneCoordinate;
      try
      {
        AutomaticDimensions(box, s.AutomaticDimension, dims);
      }
      catch (const Error& e)
      {
        return e.what();
      }
      for (int a : { p, q })
      {
        if (!automatic)
        {
          dims[a] = s.SamplingDimensions[a];
        }
        origin[a] = box[2 * a];
        spacing[a] = dims[a] > 1 ? (box[2 * a + 1] - box[2 * a]) / (dims[a] - 1) : 1.0;
      }
    }
    if (dims[p] < 2 || dims[q] < 2)
    {
      std::ostringstream m;
      m << "Symmetry Planar: the input's plane has " << dims[p] << " x " << dims[q]
        << " points along " << AxisNames[p] << " and " << AxisNames[q]
        << "; a 2D flow needs at least 2 along each (the input is a line or a point).";
      return m.str();
    }
    // Across the plane: the field is uniform, a few points carry it.
    dims[thin] = automatic ? 3 : std::max(2, s.SamplingDimensions[thin]);
    origin[thin] = plan.PlaneCoordinate - 0.5 * s.Span;
    spacing[thin] = s.Span / (dims[thin] - 1);
  }
  else
  {
    const int axial = plan.AxisInUse;
    const int radial = 3 - axial - thin;
    const double rmax = b[2 * radial + 1], rmin = b[2 * radial];
    plan.RadialSign = wedge.Found ? wedge.Sign : (rmax >= -rmin ? 1.0 : -1.0);
    const double R = wedge.Found ? wedge.Reach : (plan.RadialSign > 0 ? rmax : -rmin);
    plan.RadialExtent = R;
    if (rmin < -0.01 * R && rmax > 0.01 * R)
    {
      // data on both sides of the axis: one side is revolved, the other would vanish unsaid
      std::ostringstream m;
      m << "Symmetry Axisymmetric: the input crosses the axis (" << AxisNames[radial] << " from "
        << rmin << " to " << rmax << "); only the side " << AxisNames[radial]
        << (plan.RadialSign > 0 ? " > 0" : " < 0")
        << " (the wider) is revolved and the other is not used. Clip the input at "
        << AxisNames[radial] << " = 0 to choose the side.";
      plan.Warnings.push_back(m.str());
    }
    if (!(R > 0))
    {
      std::ostringstream m;
      m << "Symmetry Axisymmetric: the input has no extent in r (along " << AxisNames[radial]
        << ", measured from " << AxisNames[radial] << " = 0, the axis): its bounds along "
        << AxisNames[radial] << " are " << rmin << " to " << rmax << ".";
      return m.str();
    }
    if (s.UseSamplingBounds)
    {
      std::copy(s.SamplingBounds, s.SamplingBounds + 6, box);
    }
    else
    {
      const double c = 0.5 * (b[2 * axial] + b[2 * axial + 1]);
      const double half = 0.5 * (b[2 * axial + 1] - b[2 * axial]) * (1.0 - 1e-6);
      box[2 * axial] = c - half;
      box[2 * axial + 1] = c + half;
      box[2 * radial] = plan.AxisRadial - R;
      box[2 * radial + 1] = plan.AxisRadial + R;
      box[2 * thin] = plan.PlaneCoordinate - R;
      box[2 * thin + 1] = plan.PlaneCoordinate + R;
    }
    try
    {
      if (automatic)
      {
        AutomaticDimensions(box, s.AutomaticDimension, dims);
      }
      else
      {
        std::copy(s.SamplingDimensions, s.SamplingDimensions + 3, dims);
      }
    }
    catch (const Error& e)
    {
      return e.what();
    }
    for (int a = 0; a < 3; ++a)
    {
      if (dims[a] < 2)
      {
        return "Symmetry Axisymmetric: the revolved grid would have " + std::to_string(dims[a]) +
          " point(s) along " + AxisNames[a] +
          "; give SamplingDimensions (or SamplingBounds) at least 2 along every axis.";
      }
      origin[a] = box[2 * a];
      spacing[a] = (box[2 * a + 1] - box[2 * a]) / (dims[a] - 1);
    }
  }
  return std::string();
}

void SymmetrySamples(
  const SymmetryPlan& plan, std::vector<double>& points, std::vector<std::int64_t>& sampleOf)
{
  const int* dims = plan.Dims;
  const double* o = plan.Origin;
  const double* h = plan.Spacing;
  const int thin = plan.PlaneAxis;
  const std::size_t count = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  sampleOf.assign(count, 0);
  points.clear();
  if (plan.Symmetry != SymmetryAxisymmetric)
  {
    // Planar: one sample per in-plane point, the same across the span.
    const int p = (thin + 1) % 3, q = (thin + 2) % 3;
    points.resize(3 * static_cast<std::size_t>(dims[p]) * dims[q]);
    for (int iq = 0; iq < dims[q]; ++iq)
    {
      for (int ip = 0; ip < dims[p]; ++ip)
      {
        double* x = &points[3 * (ip + static_cast<std::size_t>(dims[p]) * iq)];
        x[p] = o[p] + ip * h[p];
        x[q] = o[q] + iq * h[q];
        x[thin] = plan.PlaneCoordinate;
      }
    }
    int i[3];
    std::size_t id = 0;
    for (i[2] = 0; i[2] < dims[2]; ++i[2])
      for (i[1] = 0; i[1] < dims[1]; ++i[1])
        for (i[0] = 0; i[0] < dims[0]; ++i[0], ++id)
        {
          sampleOf[id] = i[p] + static_cast<std::int64_t>(dims[p]) * i[q];
        }
    return;
  }
  // Axisymmetric: a grid point at axial coordinate x_a and distance r from the axis takes the
  // 2D value at (x_a, r). The distances repeat over the transverse plane (its symmetries), so
  // each distinct r is probed once per axial position.
  const int axial = plan.AxisInUse;
  const int radial = 3 - axial - thin;
  const double hmin = std::min(h[radial], h[thin]);
  const double outer = plan.RadialExtent * (1.0 - 1e-6); // a hair inside the outermost cells
  std::map<long long, int> index; // quantised r -> distinct radius
  std::vector<double> radii;
  std::vector<int> radiusOf(static_cast<std::size_t>(dims[radial]) * dims[thin]);
  for (int it = 0; it < dims[thin]; ++it)
  {
    for (int ir = 0; ir < dims[radial]; ++ir)
    {
      const double dr = o[radial] + ir * h[radial] - plan.AxisRadial;
      const double dt = o[thin] + it * h[thin] - plan.PlaneCoordinate;
      // Beyond the input's largest radius (the box's corners) the field is carried outward
      // at its value there (zero gradient in r, as at a CFD outflow boundary), rather than
      // left to AmbientMode: no void to fill where the revolution, not the flow, ends.
      const double r = std::min(std::sqrt(dr * dr + dt * dt), outer);
      const long long key = std::llround(r / (1e-9 * hmin));
      auto found = index.find(key);
      int u;
      if (found == index.end())
      {
        u = static_cast<int>(radii.size());
        index.emplace(key, u);
        radii.push_back(r);
      }
      else
      {
        u = found->second;
      }
      radiusOf[ir + static_cast<std::size_t>(dims[radial]) * it] = u;
    }
  }
  const std::size_t U = radii.size();
  points.resize(3 * static_cast<std::size_t>(dims[axial]) * U);
  for (int ia = 0; ia < dims[axial]; ++ia)
  {
    for (std::size_t u = 0; u < U; ++u)
    {
      double* x = &points[3 * (ia * U + u)];
      x[axial] = o[axial] + ia * h[axial];
      // on the half plane sampled: the radial axis, or a wedge's mid-plane
      x[radial] = plan.AxisRadial + plan.RadialSign * radii[u] * std::cos(plan.MidTilt);
      x[thin] = plan.PlaneCoordinate + plan.RadialSign * radii[u] * std::sin(plan.MidTilt);
    }
  }
  int i[3];
  std::size_t id = 0;
  for (i[2] = 0; i[2] < dims[2]; ++i[2])
    for (i[1] = 0; i[1] < dims[1]; ++i[1])
      for (i[0] = 0; i[0] < dims[0]; ++i[0], ++id)
      {
        sampleOf[id] = static_cast<std::int64_t>(i[axial] * U) +
          radiusOf[i[radial] + static_cast<std::size_t>(dims[radial]) * i[thin]];
      }
}

void ExpandSamples(const std::int64_t* sampleOf, std::size_t count, const float* samples,
  int components, float* out)
{
  for (std::size_t id = 0; id < count; ++id)
  {
    std::copy_n(samples + sampleOf[id] * components, components, out + id * components);
  }
}

void ExpandValidity(const std::int64_t* sampleOf, std::size_t count,
  const unsigned char* sampleValid, unsigned char* valid)
{
  for (std::size_t id = 0; id < count; ++id)
  {
    valid[id] = sampleValid && sampleValid[sampleOf[id]] != 0 ? 1 : 0;
  }
}

void SymmetryToMesh(const SymmetryPlan& plan, const double x[3], double at[3])
{
  std::copy(x, x + 3, at);
  const int thin = plan.PlaneAxis;
  if (plan.Symmetry == SymmetryPlanar)
  {
    at[thin] = plan.PlaneCoordinate;
  }
  else if (plan.Symmetry == SymmetryAxisymmetric)
  {
    const int radial = 3 - plan.AxisInUse - thin;
    const double dr = x[radial] - plan.AxisRadial, dt = x[thin] - plan.PlaneCoordinate;
    const double r = std::sqrt(dr * dr + dt * dt);
    at[radial] = plan.AxisRadial + plan.RadialSign * r * std::cos(plan.MidTilt);
    at[thin] = plan.PlaneCoordinate + plan.RadialSign * r * std::sin(plan.MidTilt);
  }
}

bool MayBeWedge(const double bounds[6])
{
  // only a thin input can be a wedge (one of 10 deg is 0.18 of its radius across): a 3D mesh
  // costs one look at its bounds
  double sides[3] = { bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] };
  std::sort(sides, sides + 3);
  return sides[0] > 0 && !(sides[0] > 0.25 * sides[1]);
}

std::string WedgeWithoutSymmetry(const double* xyz, std::size_t n)
{
  const Wedge wedge = DetectWedge(xyz, xyz ? n : 0);
  if (!wedge.Found)
  {
    return std::string();
  }
  std::ostringstream m;
  m << "The input is an axisymmetric wedge (OpenFOAM's way: two planes " << wedge.Angle * Degrees
    << " deg apart through the line along " << AxisNames[wedge.Axial] << " at "
    << AxisNames[wedge.Radial] << " = " << wedge.AxisRadial << ", " << AxisNames[wedge.Thin]
    << " = " << wedge.AxisThin << ", one cell across). With Symmetry None it is traced as it is: a "
    << wedge.Angle * Degrees << " deg slab of gas, not the revolved flow. Set Symmetry to "
    << "Axisymmetric (AxisFromWedge on) to revolve it about its axis.";
  return m.str();
}

} // namespace schlieren
