// SPDX-License-Identifier: BSD-3-Clause
// Finalising the film: the film filters, sums to image per cutoff, and the photon warnings.
#include "SchlierenEngineInternal.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace schlieren
{

// The smallest deflection a sensitive laboratory schlieren bench resolves, rad (a long-focus
// system with a sharp knife edge; ordinary benches need about ten times more).
static double BenchResolvableDeflection()
{
  return 1e-7;
}

// A field that bends light less than a laboratory bench can see: the image is contrast made by the
// automatic scale, not a picture of anything a real schlieren system would show. Such a field is
// nearly always an input read in the wrong units. An exactly uniform field (no deflection at all)
// is not warned of: its image is honest (uniform, or a body's shadow).
static std::string WeakFieldWarning(const TraceSettings& s, const TraceResult& r)
{
  if (s.Mode == Cutoff::Interferometry || !(r.MaxDeflection > 0) ||
    !(r.MaxDeflection < BenchResolvableDeflection()))
    return std::string();
  std::ostringstream msg;
  msg << "The largest deflection over the film is " << r.MaxDeflection << " rad, below the about "
      << BenchResolvableDeflection()
      << " rad that a sensitive laboratory schlieren bench resolves: a real bench would show "
         "nothing here";
  if (!(s.CutoffScale > 0) && r.CutoffScaleUsed > 0)
    msg << ", and the automatic CutoffScale (" << r.CutoffScaleUsed << ") stretched "
        << r.FullContrastDeflection << " rad to full contrast";
  msg << ". n - 1 is likely far too small for the flow: check RefractiveIndex's units "
         "(PressureUnit, TemperatureUnit), an absolute pressure against a gauge one (PressureOffset "
         "is the operating pressure a gauge pressure is added to), a non-dimensional density such "
         "as PLOT3D's rho / rho_inf (DensityReference: the free-stream density in kg/m^3) or "
         "pressure (PressureReference), and the Gas (its Gladstone-Dale constant).\n";
  return msg.str();
}

// What the user must be told when the photons did not make a picture: no ray entered the volume
// (a uniform image), or the photons that did landed off the film (a blank image). Uses the raw
// (unfiltered) sums: a landed photon is counted once there.
static std::string PhotonWarnings(const Volume& volume, const FilmGeometry& film, const FilmSums& raw)
{
  if (!(raw.Photons > 0))
    return std::string();
  double landed = 0;
  for (double c : raw.Count)
    landed += c;
  const double entered = raw.Photons - raw.MissedRays;
  const double kept = raw.Photons - raw.FailedRays;
  // a ray a body stopped is dark on the film, not off it
  const double blocked = std::min(kept, std::max(0.0, raw.BlockedRays));
  const double left = kept - blocked;
  const double off = std::max(0.0, left - landed);
  std::ostringstream msg;
  if (!(entered > 0))
  {
    double h[3];
    for (int a = 0; a < 3; ++a)
      h[a] = (volume.Dimensions[a] - 1) * volume.Spacing[a];
    msg << "No ray entered the volume (" << h[0] << " x " << h[1] << " x " << h[2]
        << " world units) of " << raw.Photons << " traced: the image is uniform and shows nothing "
        << "of the field. The film's pixels are " << film.PixelSize << " world units wide; a "
        << "volume thinner than that across the beam is missed by the rays through the pixel "
        << "centres. Raise Resolution, view the volume face-on, or resample it thicker.\n";
  }
  else if (!(landed > 0) && blocked > 0 && !(left >= 1))
    msg << "A solid body blocked " << blocked << " of " << kept << " rays: it covers the whole "
        << "beam, so no light passed it and the image is dark. View it along a direction where it "
        << "does not fill the film, or give the volume room around the body.\n";
  else if (!(landed > 0))
    msg << "No photon reached the film: all " << left << " photons that left the volume landed "
        << "off the film (it is " << film.Size[0] * film.PixelSize << " world units wide and "
        << "images the plane " << film.FilmPlane << " from the volume's centre). The image is "
        << "blank: lower FilmDistance (or CutoffScale) so that the deflected light stays on the "
        << "film.\n";
  else if (off > 0.5 * left)
    msg << off << " of " << left << " photons landed off the film (the film images the plane "
        << film.FilmPlane << " from the volume's centre): the image shows only the rest. Lower "
        << "FilmDistance to keep more of the light on the film.\n";
  return msg.str();
}

// Film filters (paper section 6): every per-pixel sum is convolved with the same kernel, so that
// ratios (mean deflection, BOS pattern) stay consistent; the total stays the same.
static void FilterChannel(std::vector<double>& c, int nx, int ny, const std::vector<double>& kernel,
  int radius, bool separable)
{
  std::vector<double> tmp(c.size(), 0.0);
  if (separable)
  {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const double v = c[static_cast<std::size_t>(j) * nx + i];
        if (v == 0)
          continue;
        for (int d = -radius; d <= radius; ++d)
          if (i + d >= 0 && i + d < nx)
            tmp[static_cast<std::size_t>(j) * nx + i + d] += v * kernel[d + radius];
      }
    std::fill(c.begin(), c.end(), 0.0);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const double v = tmp[static_cast<std::size_t>(j) * nx + i];
        if (v == 0)
          continue;
        for (int d = -radius; d <= radius; ++d)
          if (j + d >= 0 && j + d < ny)
            c[static_cast<std::size_t>(j + d) * nx + i] += v * kernel[d + radius];
      }
    return;
  }
  const int w = 2 * radius + 1;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const double v = c[static_cast<std::size_t>(j) * nx + i];
      if (v == 0)
        continue;
      for (int dj = -radius; dj <= radius; ++dj)
        for (int di = -radius; di <= radius; ++di)
          if (i + di >= 0 && i + di < nx && j + dj >= 0 && j + dj < ny)
            tmp[static_cast<std::size_t>(j + dj) * nx + i + di] += v * kernel[(dj + radius) * w + di + radius];
    }
  c.swap(tmp);
}

void FilterSums(FilmSums& f, const TraceSettings& s)
{
  if (s.Filter == FilmFilter::None)
    return;
  if (!(s.FilterWidth > 0) || s.FilterWidth > 64)
    throw Error("FilterWidth must be in (0, 64] pixels.");
  std::vector<double> kernel;
  int radius = 0;
  bool separable = false;
  if (s.Filter == FilmFilter::Gaussian)
  {
    const double sigma = s.FilterWidth;
    radius = static_cast<int>(std::ceil(3 * sigma));
    double sum = 0;
    for (int d = -radius; d <= radius; ++d)
    {
      kernel.push_back(std::exp(-0.5 * d * d / (sigma * sigma)));
      sum += kernel.back();
    }
    for (double& k : kernel)
      k /= sum;
    separable = true;
  }
  else
  {
    // cone of radius FilterWidth / sqrt(passes): wide while few photons, sharp as they add up
    const double r = std::max(1.0, s.FilterWidth / std::sqrt(double(std::max(1, f.Passes))));
    radius = static_cast<int>(std::floor(r));
    double sum = 0;
    for (int dj = -radius; dj <= radius; ++dj)
      for (int di = -radius; di <= radius; ++di)
      {
        kernel.push_back(std::max(0.0, 1.0 - sch_hypot_d(di, dj) / (r + 0.5)));
        sum += kernel.back();
      }
    for (double& k : kernel)
      k /= sum;
  }
  for (std::vector<double>* c : f.PixelChannels())
    FilterChannel(*c, f.Size[0], f.Size[1], kernel, radius, separable);
}

TraceResult Finalize(const Volume& volume, const TraceSettings& s, const FilmSums& raw)
{
  TraceResult r;
  r.Film = MakeFilm(volume, s);
  const std::size_t n = static_cast<std::size_t>(r.Film.Size[0]) * r.Film.Size[1];
  if (raw.Count.size() != n || raw.Passes < 1)
    throw Error("Finalize: the sums do not belong to this film, or hold no pass.");
  // the sums are copied only to be filtered: unfiltered, the image reads them where they are (a
  // copy of every channel is the largest part of Finalize on a large film)
  FilmSums filtered;
  if (s.Filter != FilmFilter::None)
  {
    filtered = raw;
    FilterSums(filtered, s);
  }
  const FilmSums& sums = s.Filter != FilmFilter::None ? filtered : raw;
  r.Intensity.assign(n, 0.f);
  r.Deflection.assign(2 * n, 0.f);
  if (s.EstimateError)
    r.ErrorEstimate.assign(n, 0.f);
  const bool white = s.WhiteLight() && s.Mode != Cutoff::ColorFilter;
  if (s.Mode == Cutoff::ColorFilter || white)
    r.RGB.assign(3 * n, 0.f);
  // a band: X, Y, Z (summed in Red, Green, Blue) over the band's white, the mean of the passes'
  double bandWhite[3] = { 1, 1, 1 };
  if (s.WhiteLight())
  {
    SpectrumMeanXYZ(s, sums.Passes, bandWhite);
    r.Spectrum = SpectrumText(s, sums.Passes, r.SpectrumScale);
  }
  if (s.Mode == Cutoff::Interferometry)
    r.Phase.assign(n, 0.f);
  if (s.Mode == Cutoff::BOS)
    r.Displacement.assign(2 * n, 0.f);
  if (volume.Solid)
    r.Blocked.assign(n, 0.f);
  const double passes = sums.Passes;
  const double ang = s.KnifeAngle * 3.14159265358979323846 / 180.0;
  const double ca = std::cos(ang), sa = std::sin(ang);
  const bool manual = s.CutoffScale > 0;
  // the automatic scale maps the largest deflection to full contrast
  double k = s.CutoffScale;
  if (!manual)
  {
    if (s.Mode == Cutoff::KnifeEdge)
      k = sums.MaxAbsKnife > 0 ? 0.5 / sums.MaxAbsKnife : 0.0;
    else
      k = sums.MaxAbsDeflection > 0 ? 1.0 / sums.MaxAbsDeflection : 0.0;
  }
  const BenchResponse bench = ComputeBench(s);
  const bool weighted = manual || s.RussianRoulette || bench.Finite;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double c = sums.Count[i];
    if (c > 0)
    {
      r.Deflection[2 * i] = static_cast<float>(sums.DeflectionX[i] / c);
      r.Deflection[2 * i + 1] = static_cast<float>(sums.DeflectionY[i] / c);
      if (s.EstimateError)
        r.ErrorEstimate[i] = static_cast<float>(sums.ErrorSum[i] / c);
      if (s.Mode == Cutoff::Interferometry)
        r.Phase[i] = static_cast<float>(sums.Phase[i] / c);
      if (s.Mode == Cutoff::BOS)
      {
        r.Displacement[2 * i] = static_cast<float>(sums.ShiftX[i] / c);
        r.Displacement[2 * i + 1] = static_cast<float>(sums.ShiftY[i] / c);
      }
    }
    double I = 0;
    // with the automatic k no photon reaches a clamp, so the sums of the linear weights are exact
    switch (s.Mode)
    {
      case Cutoff::KnifeEdge:
        I = weighted ? sums.Weight[i] / passes
                     : (0.5 * c - k * (sums.DeflectionX[i] * ca + sums.DeflectionY[i] * sa)) / passes;
        break;
      case Cutoff::Circular:
        I = weighted ? sums.Weight[i] / passes : (c - k * sums.AbsDeflection[i]) / passes;
        break;
      case Cutoff::ComplementCircular:
        I = weighted ? sums.Weight[i] / passes : k * sums.AbsDeflection[i] / passes;
        break;
      case Cutoff::ColorFilter:
      {
        // the values are final where k was applied per photon or a stop in mm weighed them
        const bool direct = manual || bench.Stop;
        const double scale = (direct ? 1.0 : k) / passes;
        r.RGB[3 * i] = static_cast<float>(sums.Red[i] * scale);
        r.RGB[3 * i + 1] = static_cast<float>(sums.Green[i] * scale);
        r.RGB[3 * i + 2] = static_cast<float>(sums.Blue[i] * scale);
        I = (direct ? 0.0 : k * sums.AbsDeflection[i]) / passes;
        if (direct)
          I = std::max(r.RGB[3 * i], std::max(r.RGB[3 * i + 1], r.RGB[3 * i + 2]));
        break;
      }
      case Cutoff::Shadowgraph:
        I = c / passes;
        break;
      case Cutoff::Interferometry:
        I = sums.Weight[i] / passes;
        break;
      case Cutoff::BOS:
        // the background as seen through the flow; a body hides it (its photons count, dark)
        I = c + sums.Blocked[i] > 0 ? sums.Weight[i] / (c + sums.Blocked[i]) : 0.0;
        break;
    }
    if (volume.Solid)
      r.Blocked[i] = static_cast<float>(sums.Blocked[i] / passes);
    r.Intensity[i] = static_cast<float>(I);
    if (white)
    {
      // where each photon's weight is known (Splatter) the sums are of the light let through;
      // elsewhere they are of the light that landed, its share of each colour times I
      const bool perPhoton = weighted || s.Mode == Cutoff::Interferometry || s.Mode == Cutoff::Shadowgraph;
      const double sum[3] = { sums.Red[i], sums.Green[i], sums.Blue[i] };
      double share[3];
      for (int a = 0; a < 3; ++a)
        share[a] = perPhoton ? sum[a] / (passes * bandWhite[a]) : (c > 0 ? I * sum[a] / (c * bandWhite[a]) : 0.0);
      BandColour(share, &r.RGB[3 * i]);
    }
  }
  r.CutoffScaleUsed = (s.Mode == Cutoff::Shadowgraph || s.Mode == Cutoff::Interferometry || s.Mode == Cutoff::BOS) ? 0.0 : k;
  if (bench.Finite)
  {
    r.BenchSensitivity = bench.Sensitivity;
    r.BenchRange[0] = bench.Dark;
    r.BenchRange[1] = bench.Saturation;
    r.BenchResolvable = bench.Resolvable;
    r.BenchModel = bench.Model;
    // a pixel is saturated (dark) where every photon's share reached the end of the response; the
    // float weights are compared with a margin of a few roundings
    double lit = 0, saturated = 0, dark = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (sums.Count[i] > 0)
      {
        const double w = sums.Weight[i] / sums.Count[i];
        lit += 1;
        saturated += w >= bench.SaturatedWeight - 1e-6;
        dark += w <= bench.DarkWeight + 1e-6;
      }
    r.BenchSaturated = lit > 0 ? saturated / lit : 0;
    r.BenchDark = lit > 0 ? dark / lit : 0;
    // a knife's saturation is the end of its measuring range; a stop's "saturated" pixels (the
    // whole image passed) are its undisturbed background: no warning
    if (!bench.Stop && r.BenchSaturated > s.SaturationWarning)
    {
      std::ostringstream msg;
      msg.precision(3);
      msg << 100 * r.BenchSaturated << " % of the lit film is saturated (more than SaturationWarning, "
          << 100 * s.SaturationWarning << " %): deflections beyond " << bench.Saturation
          << " rad toward the open side pass the whole source image. Cut more of the source's image "
             "(KnifeCut), or use a larger source or a shorter SchlierenFocalLength, for a wider "
             "range on that side.\n";
      r.Warnings += msg.str();
    }
  }
  r.FullContrastDeflection =
    r.CutoffScaleUsed > 0 ? (s.Mode == Cutoff::KnifeEdge ? 0.5 : 1.0) / r.CutoffScaleUsed : 0.0;
  r.MaxDeflection = sums.MaxAbsDeflection;
  r.Photons = sums.Photons;
  r.Samples = sums.Samples;
  r.FailedRays = sums.FailedRays;
  r.MissedRays = sums.MissedRays;
  r.MaxDrift = sums.MaxDrift;
  r.MaxError = sums.MaxError;
  r.UnderresolvedRays = sums.UnderresolvedRays;
  r.SideRays = sums.SideRays;
  r.Steps = sums.Steps;
  r.BlockedRays = sums.BlockedRays;
  if (sums.UnderresolvedRays > 0 && s.AutoMeasuredError >= 0)
  {
    std::ostringstream msg;
    msg << sums.UnderresolvedRays << " of " << sums.Photons
        << " rays took steps longer than a feature of the field; Auto measured the error of this "
           "setting on its pilot rays at "
        << s.AutoMeasuredError << " rad, within the tolerance " << s.Tolerance << " rad.\n";
    r.Warnings += msg.str();
  }
  else if (sums.UnderresolvedRays > 0)
  {
    std::ostringstream msg;
    msg << sums.UnderresolvedRays << " of " << sums.Photons
        << " rays took steps longer than a feature of the field (a shock or an interface crossed in "
           "one step): their deflection may be badly wrong. Lower StepSize (or the octree "
           "tolerance) until this warning goes.\n";
    r.Warnings += msg.str();
  }
  if (sums.FailedRays > 0)
  {
    std::ostringstream msg;
    msg << sums.FailedRays << " of " << sums.Photons
        << " rays failed (turned back, hit the step limit or went non-finite) and were dropped "
           "from the image.\n";
    r.Warnings += msg.str();
  }
  r.Camera = ComputeCamera(s, r.Film);
  r.Warnings += PhotonWarnings(volume, r.Film, raw);
  r.Warnings += WeakFieldWarning(s, r);
  return r;
}

} // namespace schlieren
