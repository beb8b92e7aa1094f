// SPDX-License-Identifier: BSD-3-Clause
// Solid bodies (Volume::Solid) against closed-form shadows:
//  - an opaque sphere of radius R in uniform air: a dark disc of radius R (to a pixel), 0.5
//    elsewhere under the knife edge, and 0 inside the disc for every cutoff;
//  - a cylinder across the beam: a dark band of its diameter;
//  - a sphere beside the Gaussian sphere: only its disc darkens, the deflection elsewhere is the
//    one without it;
//  - shadowgraph: the shadow's edge is sharp (one partial pixel on each side);
//  - a plate one grid point thick is not jumped over by the octree's skips or by long steps;
//  - the CPU and OpenCL backends, and the lock-step and per-item kernels, agree.
// The body is the half-level surface of the interpolated solid points, within about half a
// spacing of the exact one: "to a pixel" with pixel = spacing.
#include "SchlierenTesting.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

using namespace schlieren;

namespace
{
// A uniform or Gaussian field on [-1, 1]^3 with n points per axis, and a body.
struct BodyVolume
{
  schtest::SceneVolume SV;
  std::vector<unsigned char> Solid, Levels;
  Volume V;
  std::size_t SolidPoints = 0;
  BodyVolume(Scene scene, const SceneParameters& p, int n, const BodyParameters& b)
    : SV(scene, p, n, 1.0)
  {
    Solid.resize(SV.V.NumberOfPoints());
    SolidPoints = FillBody(b, SV.V.Dimensions, SV.V.Origin, SV.V.Spacing, Solid.data());
    V = SV.V;
    V.Solid = Solid.data();
  }
  Volume Without() const { return SV.V; }
  Volume WithOctree(double tol)
  {
    Levels.resize(SV.V.NumberOfPoints());
    ComputeOctreeLevels(SV.V.Dimensions, SV.N1.data(), tol, Levels.data());
    Volume v = V;
    v.Levels = Levels.data();
    v.LevelTolerance = tol;
    return v;
  }
};

SceneParameters Air()
{
  SceneParameters p;
  p.Amplitude = 2.7e-4; // n - 1 of air
  return p;
}

TraceSettings Film(int pixels, Backend b)
{
  TraceSettings s;
  s.Device = b;
  s.Resolution[0] = s.Resolution[1] = pixels;
  s.Passes = 4;
  s.CutoffScale = 1000; // a fixed scale: uniform air has no deflection for the automatic one
  s.StepSize = 0.5;
  return s;
}

// film coordinate (from the volume centre) of pixel i's centre
double PixelCentre(const TraceResult& r, int i, int axis)
{
  return r.Film.Corner[axis] + (i + 0.5) * r.Film.PixelSize;
}

void TestSphere(Backend backend, const char* name)
{
  const double R = 0.5;
  BodyParameters b;
  b.Shape = Body::Sphere;
  b.Radius = R;
  BodyVolume bv(Scene::Uniform, Air(), 65, b); // spacing 1/32
  TraceSettings s = Film(64, backend);        // pixel 1/32
  const TraceResult r = Trace(bv.V, s);
  const int nx = r.Film.Size[0], ny = r.Film.Size[1];
  const double px = r.Film.PixelSize;
  double dark = 0, worstIn = 0, worstOut = 0, blockedIn = 1;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const double rho = std::hypot(PixelCentre(r, i, 0), PixelCentre(r, j, 1));
      const double I = r.Intensity[k];
      dark += 1.0 - I / 0.5;
      if (rho < R - px)
      {
        worstIn = std::max(worstIn, I);
        blockedIn = std::min(blockedIn, double(r.Blocked[k]));
      }
      if (rho > R + px)
        worstOut = std::max(worstOut, std::fabs(I - 0.5));
    }
  const double radius = std::sqrt(dark * px * px / 3.14159265358979);
  std::printf("%s sphere R = %g: dark-area radius %.5f (%.3f pixels off), largest I inside %.3g, "
              "largest |I - 0.5| outside %.3g, blocked rays %.0f of %.0f\n",
    name, R, radius, (radius - R) / px, worstIn, worstOut, r.BlockedRays, r.Photons);
  CHECK_NEAR(radius, R, px, std::string(name) + ": the dark disc has the sphere's radius, to a pixel");
  CHECK(worstIn == 0.0 && blockedIn == 1.0, std::string(name) + ": inside the disc no light arrives");
  CHECK(worstOut < 1e-6, std::string(name) + ": outside the disc the knife edge's 0.5");
  CHECK(r.FailedRays == 0 && r.BlockedRays > 0, std::string(name) + ": blocked rays are counted, not failed");
  // the blocked count: the rays through the disc, about pi R^2 / px^2 per pass
  CHECK_NEAR(r.BlockedRays / s.Passes, 3.14159265358979 * R * R / (px * px),
    2 * 3.14159265358979 * R / px, std::string(name) + ": blocked rays per pass = pixels in the disc, to its rim");

  // every cutoff is dark inside the disc; outside, each shows undisturbed air
  for (Cutoff c : { Cutoff::Circular, Cutoff::ComplementCircular, Cutoff::ColorFilter,
         Cutoff::Interferometry, Cutoff::BOS, Cutoff::Shadowgraph })
  {
    TraceSettings t = s;
    t.Mode = c;
    const TraceResult q = Trace(bv.V, t);
    double in = 0, out = 0, rgbIn = 0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const std::size_t k = static_cast<std::size_t>(j) * nx + i;
        const double rho = std::hypot(PixelCentre(q, i, 0), PixelCentre(q, j, 1));
        if (rho < R - px)
        {
          in = std::max(in, double(q.Intensity[k]));
          if (!q.RGB.empty())
            rgbIn = std::max(rgbIn, double(std::max(q.RGB[3 * k], std::max(q.RGB[3 * k + 1], q.RGB[3 * k + 2]))));
        }
        else if (rho > R + px)
          out = std::max(out, double(q.Intensity[k]));
      }
    std::printf("  %s: largest I inside %.3g, outside %.3g, blocked %.0f\n", CutoffName(c), in, out,
      q.BlockedRays);
    CHECK(in == 0.0 && rgbIn == 0.0, std::string(name) + " " + CutoffName(c) + ": dark inside the disc");
    CHECK(q.BlockedRays == r.BlockedRays, std::string(name) + " " + CutoffName(c) + ": the same rays blocked");
    if (c != Cutoff::ComplementCircular && c != Cutoff::ColorFilter) // those are dark without deflection
      CHECK(out > 0.3, std::string(name) + " " + CutoffName(c) + ": light outside the disc");
  }

  // line of sight blocks the same rays (it steps along the unbent beam)
  TraceSettings ls = s;
  ls.Method = Integrator::Straight;
  const TraceResult st = Trace(bv.V, ls);
  CHECK(st.BlockedRays == r.BlockedRays, std::string(name) + ": line of sight blocks the same rays in uniform air");
}

void TestCylinder()
{
  const double R = 0.3;
  BodyParameters b;
  b.Shape = Body::Cylinder;
  b.Radius = R;
  b.Axis[0] = 1; // along x, across the beam (which travels along -z)
  b.Axis[1] = b.Axis[2] = 0;
  BodyVolume bv(Scene::Uniform, Air(), 65, b);
  const TraceResult r = Trace(bv.V, Film(64, Backend::CPU));
  const int nx = r.Film.Size[0], ny = r.Film.Size[1];
  const double px = r.Film.PixelSize;
  double worst = 0;
  for (int i = 0; i < nx; ++i)
  {
    double dark = 0;
    for (int j = 0; j < ny; ++j)
      dark += 1.0 - r.Intensity[static_cast<std::size_t>(j) * nx + i] / 0.5;
    worst = std::max(worst, std::fabs(dark * px - 2 * R));
  }
  std::printf("cylinder of diameter %g across the beam: dark band width within %.3f pixels of it in "
              "every column\n", 2 * R, worst / px);
  CHECK(worst <= px, "a cylinder across the beam casts a dark band of its diameter, to a pixel");
}

// A sphere beside the Gaussian sphere: its disc goes dark; elsewhere the deflection is the one
// traced without the body (the same rays, steps and samples: it is the same arithmetic).
void TestGaussianWithBody(bool haveCL)
{
  SceneParameters p;
  p.Amplitude = 1e-4;
  p.Width = 0.25;
  BodyParameters b;
  b.Shape = Body::Sphere;
  b.Radius = 0.15;
  b.Center[0] = 0.45;
  BodyVolume bv(Scene::GaussianSphere, p, 65, b);
  TraceSettings s = Film(64, Backend::CPU);
  s.Method = Integrator::Midpoint;
  const TraceResult with = Trace(bv.V, s);
  const TraceResult without = Trace(bv.Without(), s);
  const int nx = with.Film.Size[0], ny = with.Film.Size[1];
  const double px = with.Film.PixelSize;
  double diff = 0, emax = 0, in = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const double rho = std::hypot(PixelCentre(with, i, 0) - b.Center[0], PixelCentre(with, j, 1));
      if (rho > b.Radius + 1.5 * px)
        for (int c = 0; c < 2; ++c)
        {
          diff = std::max(diff, double(std::fabs(with.Deflection[2 * k + c] - without.Deflection[2 * k + c])));
          emax = std::max(emax, double(std::fabs(without.Deflection[2 * k + c])));
        }
      if (rho < b.Radius - px)
        in = std::max(in, double(with.Intensity[k]));
    }
  std::printf("Gaussian + sphere: deflection outside the disc differs from the trace without the "
              "body by %.3g rad (largest deflection %.3g rad); largest I inside the disc %.3g\n",
    diff, emax, in);
  CHECK(diff <= 1e-6 * emax, "the body leaves the deflection outside its disc as without it");
  CHECK(in == 0.0, "the body's disc is dark in the Gaussian field");

  // the octree: blocks next to the body are not skipped, the same rays stop
  BodyVolume bo(Scene::GaussianSphere, p, 65, b);
  const Volume vo = bo.WithOctree(1e-4 * p.Amplitude);
  const TraceResult oct = Trace(vo, s);
  std::printf("  with the octree: blocked %.0f, without %.0f\n", oct.BlockedRays, with.BlockedRays);
  CHECK(oct.BlockedRays == with.BlockedRays, "the octree's skips do not change which rays a body stops");

  // Auto: the pilot ignores blocked rays and the image is still dark in the disc
  TraceSettings a = s;
  a.Method = Integrator::Auto;
  const TraceResult au = Trace(bv.V, a);
  std::printf("  Auto: %s; blocked %.0f\n", au.Choice.Report.c_str(), au.BlockedRays);
  CHECK(au.Choice.Met, "Auto meets its tolerance with a body");
  CHECK(au.BlockedRays > 0 && au.FailedRays == 0, "Auto's trace stops rays at the body, none fails");

  if (!haveCL)
    return;
  // CPU and OpenCL agree; the lock-step and per-item kernels are identical
  TraceSettings c = s;
  c.Device = Backend::OpenCL;
  TraceResult lock, item;
  {
    const schtest::ScopedOptions on([](RuntimeOptions& o) { o.Lockstep = 1; });
    lock = Trace(bv.V, c);
  }
  {
    const schtest::ScopedOptions off([](RuntimeOptions& o) { o.Lockstep = 0; });
    item = Trace(bv.V, c);
  }
  double dcl = 0, dki = 0;
  for (std::size_t k = 0; k < with.Deflection.size(); ++k)
  {
    dcl = std::max(dcl, double(std::fabs(with.Deflection[k] - lock.Deflection[k])));
    dki = std::max(dki, double(std::fabs(item.Deflection[k] - lock.Deflection[k])));
  }
  std::printf("  OpenCL against CPU: deflection difference %.3g rad, blocked %.0f and %.0f; lock-step "
              "against per-item: %.3g rad, blocked %.0f and %.0f\n",
    dcl, lock.BlockedRays, with.BlockedRays, dki, lock.BlockedRays, item.BlockedRays);
  CHECK(lock.BlockedRays == with.BlockedRays && lock.Blocked == with.Blocked,
    "OpenCL and CPU stop the same rays at the body");
  CHECK(dcl <= 1e-4 * emax, "OpenCL and CPU deflections agree with a body (float rounding only)");
  CHECK(dki == 0.0 && item.BlockedRays == lock.BlockedRays && item.Samples == lock.Samples,
    "the lock-step and per-item kernels trace the same rays with a body, bit for bit");
}

// Shadowgraph: the photons that pass the sphere land undeflected (uniform air), those that meet
// it never arrive: along the rows through the centre, the light goes from none to all within two
// pixels at each edge (a Gaussian blur or a deflected fringe would spread it wider).
void TestShadowEdge(Backend backend)
{
  BodyParameters b;
  b.Shape = Body::Sphere;
  b.Radius = 0.5;
  BodyVolume bv(Scene::Uniform, Air(), 65, b);
  TraceSettings s = Film(64, backend);
  s.Mode = Cutoff::Shadowgraph;
  s.FilmDistance = 2.0;
  s.Passes = 16;
  const TraceResult r = Trace(bv.V, s);
  const int nx = r.Film.Size[0];
  int partial = 0, dark = 0, lit = 0;
  for (int row : { nx / 2 - 1, nx / 2 })
    for (int i = 0; i < nx; ++i)
    {
      const double I = r.Intensity[static_cast<std::size_t>(row) * nx + i];
      partial += I > 0.0 && I < 1.0;
      dark += I == 0.0;
      lit += I == 1.0;
    }
  std::printf("shadowgraph (%s): rows through the centre: %d dark, %d partial, %d fully lit pixels\n",
    BackendName(backend), dark, partial, lit);
  // the pixel edges lie on grid points, the body's surface along a grid line half-way between:
  // an edge of the shadow falls inside a pixel and may half-cover it and its neighbour
  CHECK(partial <= 8 && dark + partial + lit == 2 * nx,
    "the shadow's edge is sharp: at most two partial pixels at each edge of each row");
  CHECK(std::abs(dark + partial / 2 - 2 * 32) <= 4, "the shadow is the sphere's diameter wide (32 pixels), to a pixel each side");
}

// A plate one grid point thick across the beam, in uniform air whose octree would skip the whole
// box; and steps of 4 voxels asked for: no ray passes through it (steps are cut to a cell near
// it, and no octree block around it is skipped), while away from it the steps stay long.
void TestThinPlate()
{
  schtest::SceneVolume sv(Scene::Uniform, Air(), 33, 1.0);
  std::vector<unsigned char> solid(sv.V.NumberOfPoints(), 0), levels(sv.V.NumberOfPoints());
  const int n = 33;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      solid[(static_cast<std::size_t>(17) * n + j) * n + i] = 1; // the plane z = 1/16
  const double frac = ComputeOctreeLevels(sv.V.Dimensions, sv.N1.data(), 1e-9, levels.data());
  for (bool octree : { false, true })
    for (Integrator m : { Integrator::Straight, Integrator::Euler, Integrator::RK4 })
    {
      Volume v = sv.V;
      v.Solid = solid.data();
      if (octree)
        v.Levels = levels.data();
      TraceSettings s = Film(32, Backend::CPU);
      s.Method = m;
      s.StepSize = 4.0;
      s.Passes = 2;
      s.ViewDirection[0] = 0.3; // oblique: the rays cross the plate between grid points
      s.ViewDirection[1] = 0.2;
      s.ViewDirection[2] = -1;
      const TraceResult r = Trace(v, s);
      // every ray that crosses the box's z extent meets the plate: those are the rays that
      // did not miss and did not leave through a side before reaching z = 1/16
      std::vector<float> ab;
      for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 32; ++i)
          ab.insert(ab.end(), { static_cast<float>(PixelCentre(r, i, 0)), static_cast<float>(PixelCentre(r, j, 1)) });
      const std::vector<RayRecord> rays = TraceRays(v, s, ab);
      // uniform air: straight rays; those whose line meets the plane z = 1/16 inside the box
      // (with a margin of a spacing from its sides) must stop there
      int through = 0, crossing = 0;
      const double* d = r.Film.Direction;
      for (std::size_t q = 0; q < rays.size(); ++q)
      {
        double o[3];
        for (int c = 0; c < 3; ++c)
          o[c] = ab[2 * q] * r.Film.Right[c] + ab[2 * q + 1] * r.Film.Up[c] + r.Film.FrontPlane * d[c];
        const double t = (0.0625 - o[2]) / d[2];
        const double x = o[0] + t * d[0], y = o[1] + t * d[1];
        if (std::fabs(x) < 1 - 1.0 / 16 && std::fabs(y) < 1 - 1.0 / 16)
        {
          ++crossing;
          through += !(rays[q].Flags & RayBlocked);
        }
      }
      std::printf("thin plate, %s%s, StepSize 4: %d of the %d rays that cross it "
                  "passed (octree skips %.0f %% of the cells without the body)\n",
        IntegratorName(m), octree ? " + octree" : "", through, crossing, 100 * frac);
      CHECK(through == 0 && crossing > 500, std::string("no ray passes through a plate one point thick (") +
          IntegratorName(m) + (octree ? " + octree)" : ")"));
      // away from the plate the steps are as long as asked
      TraceSettings one = s;
      one.StepSize = 1.0;
      const TraceResult r1 = Trace(v, one);
      std::printf("  steps taken: %.0f at StepSize 4, %.0f at StepSize 1\n", r.Steps, r1.Steps);
      CHECK(octree || r.Steps < 0.6 * r1.Steps,
        "steps are cut to a cell only near the body: StepSize 4 takes fewer steps than 1");
    }
}

// A ray that enters the box inside a body touching the box face is stopped there; rays that leave
// through the box's faces beside the body are not blocked.
void TestBodyOnTheBoundary()
{
  BodyParameters b;
  b.Shape = Body::Sphere;
  b.Radius = 0.4;
  b.Center[2] = 1.0; // on the front face z = 1 (the beam travels along -z)
  BodyVolume bv(Scene::Uniform, Air(), 33, b);
  TraceSettings s = Film(32, Backend::CPU);
  const std::vector<float> ab = { 0.0f, 0.0f, 0.9f, 0.0f };
  const std::vector<RayRecord> r = TraceRays(bv.V, s, ab);
  std::printf("body on the front face: centre ray flags %u, steps %.0f; ray beside it flags %u\n",
    r[0].Flags, r[0].Steps, r[1].Flags);
  CHECK((r[0].Flags & RayBlocked) && r[0].Steps == 0, "a ray entering inside a body is stopped where it enters");
  CHECK(!(r[1].Flags & RayBlocked), "a ray beside the body crosses the box and is not blocked");
}
} // namespace

int main()
{
  const bool haveCL = schtest::HaveOpenCL();
  TestSphere(Backend::CPU, "CPU");
  if (haveCL)
    TestSphere(Backend::OpenCL, "OpenCL");
  TestCylinder();
  TestGaussianWithBody(haveCL);
  TestShadowEdge(Backend::CPU);
  if (haveCL)
    TestShadowEdge(Backend::OpenCL);
  TestThinPlate();
  TestBodyOnTheBoundary();
  return schtest::Finish();
}
