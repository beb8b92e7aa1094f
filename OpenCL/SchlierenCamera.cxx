// SPDX-License-Identifier: BSD-3-Clause
// The camera (docs/BENCH.md "Camera"): a thin lens focused on FocusPlane. Ideal: the film is the
// image of the focus plane (a ray lands where its exit line crosses that plane). Lens: its
// aperture's cone of rays is sampled, one lens point per pass: the beam of the pass is tilted
// toward that point, so that the rays that reach one film point cross the volume along a cone
// whose apex is the point's object in the focus plane, and a plane Dz from focus is blurred by a
// disc of diameter D Dz / Z_F in its own plane. Also the read-outs (depth of field, BOS
// displacement and blur, focusing schlieren's effective f2), each in closed form.
#include "SchlierenEngineInternal.h"

#include <cmath>
#include <sstream>

namespace schlieren
{

void CameraLensSample(std::uint32_t seed, int pass, double* u, double* v)
{
  // the seed's offset, then the R2 sequence (as the pixel jitter, sch_emit) over the passes
  const sch_uint h = sch_hash(seed * 2246822519u ^ 0x27d4eb2fu);
  double x = sch_unit(h) + pass * 0.7548776662466927, y = sch_unit(sch_hash(h ^ 0x165667b1u)) + pass * 0.5698402909980532;
  x = 2 * (x - std::floor(x)) - 1;
  y = 2 * (y - std::floor(y)) - 1;
  // Shirley and Chiu's concentric map of the square [-1, 1]^2 to the unit disc (area-preserving)
  const double quarter = 0.78539816339744831;
  double r, phi;
  if (x == 0 && y == 0)
  {
    r = 0;
    phi = 0;
  }
  else if (std::fabs(x) > std::fabs(y))
  {
    r = x;
    phi = quarter * (y / x);
  }
  else
  {
    r = y;
    phi = 2 * quarter - quarter * (x / y);
  }
  *u = r * std::cos(phi);
  *v = r * std::sin(phi);
}

namespace
{
// the lens to the focus plane, m
double FocusDistance(const TraceSettings& s)
{
  return s.CameraDistance - s.FocusPlane;
}
}

bool CameraPass(const TraceSettings& s, sch_params& P, int pass, double tilt[2])
{
  tilt[0] = tilt[1] = 0;
  if (s.Camera != CameraModel::Lens)
    return false;
  double u, v;
  CameraLensSample(s.Seed, pass, &u, &v);
  // the ray toward lens point L = (D/2)(u, v) from the axis point of the focus plane: its slope
  // is L / Z_F (the field's chief-ray tilt, the perspective, is left out: the film is a parallel
  // projection; the blur of a plane Dz from focus in that plane's own scale is the same)
  const double half = 0.5 * s.CameraFocalLength / s.FNumber / FocusDistance(s);
  const double ta = half * u, tb = half * v;
  const double d0x = P.dx, d0y = P.dy, d0z = P.dz;
  double d[3] = { P.dx + ta * P.rx + tb * P.tx, P.dy + ta * P.ry + tb * P.ty, P.dz + ta * P.rz + tb * P.tz };
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  P.dx = static_cast<float>(d[0] / len);
  P.dy = static_cast<float>(d[1] / len);
  P.dz = static_cast<float>(d[2] / len);
  // the slopes of the direction as the kernels hold it (across over along the beam): a ray
  // emitted at film coordinate a is at a + slope s at depth s, so that the emission's move and the
  // landing's correction cancel exactly for an undisturbed ray
  const double along = double(P.dx) * d0x + double(P.dy) * d0y + double(P.dz) * d0z;
  tilt[0] = (double(P.dx) * P.rx + double(P.dy) * P.ry + double(P.dz) * P.rz) / along;
  tilt[1] = (double(P.dx) * P.tx + double(P.dy) * P.ty + double(P.dz) * P.tz) / along;
  P.filmA0 = static_cast<float>(P.filmA0 - tilt[0] * P.sFilm);
  P.filmB0 = static_cast<float>(P.filmB0 - tilt[1] * P.sFilm);
  return true;
}

TraceResult::CameraReadouts ComputeCamera(const TraceSettings& s, const FilmGeometry& film)
{
  TraceResult::CameraReadouts c;
  if (s.Camera == CameraModel::None)
    return c;
  c.Active = true;
  const double f = s.CameraFocalLength, zf = FocusDistance(s), pixel = film.PixelSize;
  c.Magnification = f / (zf - f);
  std::ostringstream m;
  m.precision(4);
  if (s.Camera == CameraModel::Lens)
  {
    c.Aperture = f / s.FNumber;
    c.BlurPerDepth = c.Aperture / zf;
    c.DepthOfField = 2 * pixel / c.BlurPerDepth;
    c.ApertureSamples = s.Passes;
    m << "Lens: f = " << f << " m, f/" << s.FNumber << " (D = " << c.Aperture * 1e3
      << " mm), focused " << zf << " m away (FocusPlane " << s.FocusPlane
      << "); the aperture sampled, one lens point per pass (stratified, R2 on the disc); the "
         "film the image of the focus plane";
  }
  else
    m << "Ideal: f = " << f << " m, focused " << zf << " m away (FocusPlane " << s.FocusPlane
      << "), no aperture blur; the film the image of the focus plane";
  if (s.Mode == Cutoff::BOS)
  {
    // Z_A: the lens to the object (the volume's centre); Z_D: the object to the background, as
    // the tracer places it (BackgroundDistance in front of the emission plane)
    const double za = s.CameraDistance, zd = s.BackgroundDistance - film.FrontPlane;
    const double d = f / s.FNumber;
    c.BOSMagnification = f / (za + zd - f);
    c.BOSDisplacementPerRadian = c.BOSMagnification * zd;
    const double ma = f / (za - f); // the object plane's magnification: a film pixel on the sensor
    c.BOSPixelsPerRadian = c.BOSDisplacementPerRadian / (ma * pixel);
    c.BOSBlur = d * f * zd / (za * (za + zd - f));
    c.BOSBlurPixels = c.BOSBlur / (ma * pixel);
    m << "; BOS: Z_A = " << za << " m, Z_D = " << zd << " m, the background in focus (closed form)";
  }
  if (s.Camera == CameraModel::Lens && s.Mode == Cutoff::KnifeEdge)
  {
    const double L = s.SourceGridDistance;
    if (L > zf && L > f)
    {
      const double image = L * f / (L - f);
      c.FocusingEffectiveF2 = (L - zf) * image / L;
      m << "; focusing schlieren: L = " << L << " m, L' = " << image << " m, f2_eff = "
        << c.FocusingEffectiveF2 << " m (closed form)";
    }
  }
  c.Model = m.str();
  return c;
}

} // namespace schlieren
