// SPDX-License-Identifier: BSD-3-Clause
// Framing Silhouette (FrameSilhouette, MakeFilm with FilmExtent, TraceSession's kept frame):
//  - a small Gaussian blob, n - 1 = A exp(-r^2 / s^2), off the centre of a large box: the frame
//    is the blob's disc where |grad n| exceeds 1e-3 of its largest, r_t from the closed form
//    r exp(-r^2 / s^2) = 1e-3 (s / sqrt 2) exp(-1/2), padded by a spacing and 2 %, within a spacing;
//  - a uniform field frames the whole box (nothing refracts), and so does a field that fills it:
//    then the film is the Framing Volume film bit for bit;
//  - a body in uniform air is framed by its own projection;
//  - the film keeps Resolution's pixel count in the frame's shape, with square pixels;
//  - a session frames once and keeps the frame while only the view, Resolution or Passes change,
//    and frames again for any other change; the image of a framed trace puts every photon of the
//    blob's disc on the film and fills it;
//  - a bad Framing value is refused by name.
#include "SchlierenSession.h"
#include "SchlierenParallel.h"

#include <mutex>
#include "SchlierenTesting.h"

#include <algorithm>
#include <cmath>

using namespace schlieren;

namespace
{

/** The radius outside which |grad| of exp(-r^2 / s^2) is below 1e-3 of its largest. */
double ThresholdRadius(double s)
{
  const double target = 1e-3 * (s / std::sqrt(2.0)) * std::exp(-0.5);
  double lo = s / std::sqrt(2.0), hi = 10 * s;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (mid * std::exp(-mid * mid / (s * s)) > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TraceSettings View(double dx, double dy, double dz, double ux, double uy, double uz)
{
  TraceSettings s;
  s.ViewDirection[0] = dx;
  s.ViewDirection[1] = dy;
  s.ViewDirection[2] = dz;
  s.ViewUp[0] = ux;
  s.ViewUp[1] = uy;
  s.ViewUp[2] = uz;
  s.Frame = Framing::Silhouette;
  s.Device = Backend::CPU;
  return s;
}

/** One rank's piece: the whole volume of `n1`. */
VolumePiece WholePiece(const Volume& v, const std::vector<float>& n1, std::uint64_t version)
{
  VolumePiece piece;
  for (int a = 0; a < 3; ++a)
  {
    piece.WholeExtent[2 * a] = piece.Extent[2 * a] = 0;
    piece.WholeExtent[2 * a + 1] = piece.Extent[2 * a + 1] = v.Dimensions[a] - 1;
    piece.Origin[a] = v.Origin[a];
    piece.Spacing[a] = v.Spacing[a];
  }
  piece.Version = version;
  piece.Load = [&n1](PieceValues& values) {
    values.NMinus1 = n1;
    return std::string();
  };
  return piece;
}

} // namespace

int main()
{
  // the blob: s = 0.1 at (0.3, -0.2, 0.1) in [-1, 1]^3 on 81^3 points (spacing 0.025)
  SceneParameters p;
  p.Amplitude = 1e-4;
  p.Width = 0.1;
  p.Center[0] = 0.3;
  p.Center[1] = -0.2;
  p.Center[2] = 0.1;
  schtest::SceneVolume blob(Scene::GaussianSphere, p, 81, 81, 81, -1.0, 1.0);
  const double h = blob.V.Spacing[0];
  const double rt = ThresholdRadius(p.Width);
  std::printf("threshold radius %.4f (s = %.2f, spacing %.4f)\n", rt, p.Width, h);

  // along -z, up y: film x is -x... (Right = Direction x Up = (0,0,-1) x (0,1,0) = (1,0,0))
  {
    const TraceSettings s = View(0, 0, -1, 0, 1, 0);
    const SilhouetteFrame f = FrameSilhouette(blob.V, s);
    CHECK(f.Found, "the blob refracts");
    const double expect[4] = { p.Center[0] - rt, p.Center[0] + rt, p.Center[1] - rt, p.Center[1] + rt };
    for (int i = 0; i < 4; ++i)
    {
      const double pad = h + 0.02 * 2 * rt;
      const double e = expect[i] + (i % 2 ? pad : -pad);
      CHECK_NEAR(f.Extent[i], e, h, "along z: frame edge " + std::to_string(i) + " at the closed form's disc, padded");
    }
    const double share = (2 * rt + 2 * (h + 0.04 * rt)) * (2 * rt + 2 * (h + 0.04 * rt)) / 4.0;
    CHECK_NEAR(f.Fraction, share, 0.15 * share, "along z: the frame's share of the box's projection");
    // the film on it: a square frame keeps 64 x 48 = 3072 pixels as about 55 x 55
    TraceSettings framed = s;
    framed.Resolution[0] = 64;
    framed.Resolution[1] = 48;
    std::copy(f.Extent, f.Extent + 4, framed.FilmExtent);
    const FilmGeometry film = MakeFilm(blob.V, framed);
    const double pixels = double(film.Size[0]) * film.Size[1];
    CHECK(std::fabs(pixels - 3072) < 0.03 * 3072, "the framed film keeps Resolution's pixel count (" +
        std::to_string(film.Size[0]) + " x " + std::to_string(film.Size[1]) + ")");
    CHECK(film.PixelSize * film.Size[0] >= f.Extent[1] - f.Extent[0] - 1e-12 &&
        film.PixelSize * film.Size[1] >= f.Extent[3] - f.Extent[2] - 1e-12,
      "the framed film holds the frame");
    CHECK(std::max(film.PixelSize * film.Size[0] / (f.Extent[1] - f.Extent[0]),
            film.PixelSize * film.Size[1] / (f.Extent[3] - f.Extent[2])) < 1.05,
      "and wastes under 5 % of a side");
    // Framing Volume with the same extent: Resolution's pixels as they are
    framed.Frame = Framing::Volume;
    const FilmGeometry plain = MakeFilm(blob.V, framed);
    CHECK(plain.Size[0] == 64 && plain.Size[1] == 48, "Framing Volume with a FilmExtent keeps Resolution");
  }
  // an oblique view: the frame is the disc of radius r_t about the centre's projection
  {
    const double d[3] = { 0.6, -0.5, -0.62 };
    const TraceSettings s = View(d[0], d[1], d[2], 0, 0, 1);
    const SilhouetteFrame f = FrameSilhouette(blob.V, s);
    const FilmGeometry film = MakeFilm(blob.V, s);
    const double ca = p.Center[0] * film.Right[0] + p.Center[1] * film.Right[1] + p.Center[2] * film.Right[2];
    const double cb = p.Center[0] * film.Up[0] + p.Center[1] * film.Up[1] + p.Center[2] * film.Up[2];
    const double pad = h + 0.04 * rt;
    // the grid's points are up to sqrt(3)/2 h off the disc's edge along an oblique axis
    CHECK_NEAR(0.5 * (f.Extent[0] + f.Extent[1]), ca, h, "oblique: the frame is centred on the blob (film x)");
    CHECK_NEAR(0.5 * (f.Extent[2] + f.Extent[3]), cb, h, "oblique: the frame is centred on the blob (film y)");
    CHECK_NEAR(f.Extent[1] - f.Extent[0], 2 * (rt + pad), 2 * h, "oblique: the frame's width");
    CHECK_NEAR(f.Extent[3] - f.Extent[2], 2 * (rt + pad), 2 * h, "oblique: the frame's height");
  }
  // a uniform field: nothing refracts, the whole box; a field that fills the box: the box, and
  // the film of Framing Volume bit for bit
  {
    SceneParameters u;
    u.Amplitude = 2e-4;
    schtest::SceneVolume uniform(Scene::Uniform, u, 21, 17, 13, -1.0, 1.0);
    const TraceSettings s = View(0.2, 0.1, -1, 0, 1, 0);
    const SilhouetteFrame f = FrameSilhouette(uniform.V, s);
    CHECK(!f.Found && f.Points == 0, "a uniform field has no silhouette");
    SceneParameters wide;
    wide.Width = 0.8;
    schtest::SceneVolume full(Scene::GaussianSphere, wide, 33, 29, 25, -1.0, 1.0);
    const SilhouetteFrame g = FrameSilhouette(full.V, s);
    TraceSettings framed = s;
    std::copy(g.Extent, g.Extent + 4, framed.FilmExtent);
    framed.Frame = Framing::Volume;
    TraceSettings box = s;
    box.Frame = Framing::Volume;
    const FilmGeometry a = MakeFilm(full.V, framed), b = MakeFilm(full.V, box);
    CHECK(g.Found && g.Fraction == 1.0 && a.PixelSize == b.PixelSize && a.Corner[0] == b.Corner[0] &&
        a.Corner[1] == b.Corner[1] && a.Size[0] == b.Size[0],
      "a field that fills the box: its frame is the box, the film bit for bit Framing Volume's");
  }
  // a body in uniform air: framed by the body's projection (a sphere of radius 0.2 at -0.4, 0, 0)
  {
    SceneParameters u;
    schtest::SceneVolume air(Scene::Uniform, u, 41, 41, 41, -1.0, 1.0);
    BodyParameters b;
    b.Shape = Body::Sphere;
    b.Radius = 0.2;
    b.Center[0] = -0.4;
    std::vector<unsigned char> solid(air.V.NumberOfPoints());
    FillBody(b, air.V.Dimensions, air.V.Origin, air.V.Spacing, solid.data());
    air.V.Solid = solid.data();
    const SilhouetteFrame f = FrameSilhouette(air.V, View(0, 0, -1, 0, 1, 0));
    const double hb = air.V.Spacing[0], pad = hb + 0.02 * 0.4;
    CHECK(f.Found, "the body is the silhouette");
    // the solid points lie inside the surface (FillBody); the frame holds the body, with at
    // most its padding and a spacing more
    CHECK(f.Extent[0] <= -0.6 && f.Extent[0] >= -0.6 - pad - hb, "the body's frame: left");
    CHECK(f.Extent[1] >= -0.2 && f.Extent[1] <= -0.2 + pad + hb, "the body's frame: right");
    CHECK(f.Extent[2] <= -0.2 && f.Extent[3] >= 0.2 && f.Extent[3] - f.Extent[2] <= 0.4 + 2 * (pad + hb),
      "the body's frame: bottom and top");
  }
  // the session: frames once, keeps it while the camera moves, frames again on another change
  {
    TraceSession session;
    TraceSettings s = View(0, 0, -1, 0, 1, 0);
    s.Resolution[0] = s.Resolution[1] = 48;
    s.Passes = 2;
    s.Method = Integrator::RK4;
    const VolumePiece piece = WholePiece(blob.V, blob.N1, 7);
    SessionImage first, moved, other;
    session.Update(SerialParallel(), piece, s, first);
    CHECK(first.HasImage && first.Framed && !first.FrameKept, "the first update frames");
    const SilhouetteFrame direct = FrameSilhouette(session.KeptVolume(), s);
    CHECK(std::equal(direct.Extent, direct.Extent + 4, first.Traced.FilmExtent),
      "the session's frame is FrameSilhouette's");
    // the blob's whole disc is on the film, which it fills: no photon misses the film, and
    // the film's border pixels are those of the frame's padding
    CHECK(first.Result.Film.Size[0] == 48 && first.Result.Film.Size[1] == 48,
      "a square frame: a square film of Resolution's pixels");
    CHECK(first.Result.MissedRays == 0 && first.Result.FailedRays == 0,
      "every ray of the framed film crosses the volume");
    double edge = 0, centre = 0;
    const int n = first.Result.Film.Size[0];
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double e = std::fabs(first.Result.Intensity[j * n + i] - 0.5);
        if (i == 0 || j == 0 || i == n - 1 || j == n - 1)
          edge = std::max(edge, e);
        else
          centre = std::max(centre, e);
      }
    std::printf("framed: largest |I - 0.5| at the border %.4f, inside %.4f\n", edge, centre);
    CHECK(centre > 0.3 && edge < 0.02 * centre + 0.01,
      "the blob's image fills the film: full contrast inside, grey at the border");
    TraceSettings m = s;
    m.ViewDirection[0] = 0.3;
    m.ViewUp[2] = 0.2;
    m.Resolution[0] = m.Resolution[1] = 24; // an interactive half film
    m.Passes = 1;
    session.Update(SerialParallel(), piece, m, moved);
    CHECK(moved.Framed && moved.FrameKept &&
        std::equal(first.Traced.FilmExtent, first.Traced.FilmExtent + 4, moved.Traced.FilmExtent),
      "a camera move (view, half film, fewer passes) keeps the frame");
    TraceSettings c = m;
    c.Mode = Cutoff::Shadowgraph;
    session.Update(SerialParallel(), piece, c, other);
    CHECK(other.Framed && !other.FrameKept, "another change (the cutoff) frames again");
    // the report says it
    bool named = false;
    for (const ReportEntry& e : ImageReport(first))
      named = named || (e.Name == "film_extent" && e.Numbers.size() == 4 && e.Numbers[0] == first.Traced.FilmExtent[0]);
    CHECK(named, "the report has film_extent");
  }
  // in pieces: 3 ranks, slabs along x (the blob across two of them) and an oblique view; each
  // rank scans its cells' points, the frame is reduced over the ranks: the one-process frame and
  // image, bit for bit (the CPU backend), traced in pieces
  {
    TraceSettings s = View(0.3, -0.2, -1, 0, 1, 0);
    s.Resolution[0] = 40;
    s.Resolution[1] = 30;
    s.Passes = 2;
    s.Method = Integrator::RK4;
    SessionImage whole;
    {
      TraceSession session;
      session.Update(SerialParallel(), WholePiece(blob.V, blob.N1, 9), s, whole);
    }
    const int n = blob.V.Dimensions[0];
    SessionImage pieces;
    std::mutex m;
    RunInProcessRanks(3, [&](Parallel& p) {
      const int r = p.Rank();
      VolumePiece piece = WholePiece(blob.V, blob.N1, 9);
      const int cut[4] = { 0, n / 3, 2 * n / 3 + 5, n - 1 };
      piece.Extent[0] = cut[r];
      piece.Extent[1] = cut[r + 1];
      const int e0 = piece.Extent[0], e1 = piece.Extent[1];
      piece.Load = [&blob, e0, e1, n](PieceValues& values) {
        for (int k = 0; k < n; ++k)
          for (int j = 0; j < n; ++j)
            for (int i = e0; i <= e1; ++i)
              values.NMinus1.push_back(blob.N1[(static_cast<std::size_t>(k) * n + j) * n + i]);
        return std::string();
      };
      TraceSession session;
      SessionImage out;
      session.Update(p, piece, s, out);
      std::lock_guard<std::mutex> lock(m);
      if (r == 0)
        pieces = out;
    });
    std::printf("framed in pieces: film_extent %.6f %.6f %.6f %.6f (one process %.6f %.6f %.6f %.6f), %d ranks\n",
      pieces.Traced.FilmExtent[0], pieces.Traced.FilmExtent[1], pieces.Traced.FilmExtent[2],
      pieces.Traced.FilmExtent[3], whole.Traced.FilmExtent[0], whole.Traced.FilmExtent[1],
      whole.Traced.FilmExtent[2], whole.Traced.FilmExtent[3], pieces.DistributedRanks);
    CHECK(pieces.DistributedRanks == 3, "Framing Silhouette is traced in pieces on 3 ranks");
    CHECK(pieces.Framed && std::equal(whole.Traced.FilmExtent, whole.Traced.FilmExtent + 4, pieces.Traced.FilmExtent) &&
        pieces.Frame.Points == whole.Frame.Points,
      "the pieces' frame is one process's (extent and points)");
    CHECK(pieces.Result.Intensity == whole.Result.Intensity && pieces.Result.Deflection == whole.Result.Deflection,
      "the framed image in pieces is one process's, bit for bit");
  }
  // errors
  {
    TraceSettings s = View(0, 0, -1, 0, 1, 0);
    s.Frame = static_cast<Framing>(5);
    schtest::ExpectError("Framing 5", [&]() { MakeFilm(blob.V, s); }, { "Framing", "Silhouette" });
    s.Frame = Framing::Silhouette;
    s.FilmExtent[0] = std::nan("");
    schtest::ExpectError("FilmExtent NaN", [&]() { MakeFilm(blob.V, s); }, { "FilmExtent" });
  }
  return schtest::Finish();
}
