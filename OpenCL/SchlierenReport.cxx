// SPDX-License-Identifier: BSD-3-Clause
// The report of a traced image: the one list of names and values that vtkSchlierenImage writes as
// field data and the C interface returns as JSON (SchlierenSession.h, ImageReport).
#include "SchlierenSession.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace schlieren
{

std::vector<ReportEntry> ImageReport(const SessionImage& image)
{
  std::vector<ReportEntry> out;
  if (!image.HasImage)
  {
    return out;
  }
  auto number = [&out](const char* name, double value) {
    ReportEntry e;
    e.Name = name;
    e.Numbers.push_back(value);
    out.push_back(std::move(e));
  };
  auto text = [&out](const char* name, const std::string& value) {
    ReportEntry e;
    e.Name = name;
    e.IsText = true;
    e.Text = value;
    out.push_back(std::move(e));
  };
  const TraceResult& result = image.Result;
  number("cutoff_scale", result.CutoffScaleUsed);
  if (!result.BenchModel.empty())
  {
    // what a finite source implies (docs/BENCH.md): dI/I per radian, eps at full dark and at
    // saturation, eps of one grey level, the film's shares at either end, how it was computed
    number("bench_sensitivity", result.BenchSensitivity);
    ReportEntry range;
    range.Name = "bench_range";
    range.Numbers = { result.BenchRange[0], result.BenchRange[1] };
    out.push_back(std::move(range));
    number("bench_resolvable_deflection", result.BenchResolvable);
    number("bench_saturated_share", result.BenchSaturated);
    number("bench_dark_share", result.BenchDark);
    text("bench_model", result.BenchModel);
  }
  if (!result.Spectrum.empty())
  {
    // a band of wavelengths: how it was sampled, and n - 1's scale at its long and short ends
    text("spectrum", result.Spectrum);
    ReportEntry scale;
    scale.Name = "spectrum_index_scale";
    scale.Numbers = { result.SpectrumScale[0], result.SpectrumScale[1] };
    out.push_back(std::move(scale));
  }
  const TraceResult::CameraReadouts& cam = result.Camera;
  if (cam.Active)
  {
    // what the camera implies (docs/BENCH.md "Camera"), each in closed form
    number("camera_magnification", cam.Magnification);
    if (cam.Aperture > 0)
    {
      number("camera_aperture", cam.Aperture);
      number("camera_blur_per_depth", cam.BlurPerDepth);
      number("camera_depth_of_field", cam.DepthOfField);
      number("camera_aperture_samples", cam.ApertureSamples);
    }
    if (cam.BOSMagnification > 0)
    {
      number("bos_magnification", cam.BOSMagnification);
      number("bos_displacement_per_radian", cam.BOSDisplacementPerRadian);
      number("bos_pixels_per_radian", cam.BOSPixelsPerRadian);
      number("bos_blur", cam.BOSBlur);
      number("bos_blur_pixels", cam.BOSBlurPixels);
    }
    if (cam.FocusingEffectiveF2 > 0)
    {
      number("focusing_effective_f2", cam.FocusingEffectiveF2);
    }
    text("camera_model", cam.Model);
  }
  // the deflection (rad) the scale maps to full contrast, and the largest one traced
  number("full_contrast_deflection", result.FullContrastDeflection);
  number("max_deflection", result.MaxDeflection);
  // what the user was warned of (empty: nothing), for scripts that check an image is usable
  text("warnings", image.Warnings);
  text("backend", image.BackendUsed);
  text("device", image.DeviceName);
  number("photons", result.Photons);
  number("passes", image.Passes);
  number("passes_traced", image.PassesTraced);
  text("volume_from", image.VolumeFrom);
  number("volumes_cached", image.VolumesCached);
  number("volumes_packed", image.VolumesPacked);
  number("samples", result.Samples);
  number("samples_per_ray", result.Photons > 0 ? result.Samples / result.Photons : 0.0);
  number("failed_rays", result.FailedRays);
  number("missed_rays", result.MissedRays);
  // photons that reached the film (0: a blank image, which the warnings explain)
  number("landed_photons", image.LandedPhotons);
  number("underresolved_rays", result.UnderresolvedRays);
  number("side_rays", result.SideRays);
  number("blocked_rays", result.BlockedRays);
  number("max_drift", result.MaxDrift);
  number("max_error", result.MaxError);
  text("integrator", IntegratorName(image.Traced.Method));
  text("reconstruction", ReconstructionName(image.Traced.Recon));
  number("step_size", image.Traced.StepSize);
  // Auto may have found that the octree does not pay (traced without it)
  number("octree", image.OctreeUsed ? 1.0 : 0.0);
  if (image.OctreeUsed)
  {
    number("octree_tolerance", image.OctreeTolerance);
  }
  // traced in pieces over ranks (0: every rank had the whole volume, or one process)
  number("distributed_ranks", image.DistributedRanks);
  if (image.DistributedRanks > 0)
  {
    number("held_points_max", image.HeldPointsMax);
    number("rays_handed_on", image.RaysHandedOn);
    number("ray_traffic_bytes", image.BytesExchanged);
    number("exchange_rounds", image.Rounds);
    number("ghost_layers", image.GhostLayers);
    // where the time went (the slowest rank's): for benchmarks, not for tests
    number("tracing_seconds", image.SecondsTracing);
    number("exchange_seconds", image.SecondsExchanging);
  }
  if (image.Framed)
  {
    // Framing Silhouette: the film's frame (a0, a1, b0, b1, film coordinates from the volume's
    // centre), its share of the box's projection, and 1 where it was kept from the last Apply
    ReportEntry e;
    e.Name = "film_extent";
    e.Numbers.assign(image.Traced.FilmExtent, image.Traced.FilmExtent + 4);
    out.push_back(std::move(e));
    number("film_frame_share", image.Frame.Fraction);
    number("film_frame_kept", image.FrameKept ? 1.0 : 0.0);
  }
  if (image.AutoAsked)
  {
    text("auto_report", image.Choice.Report);
    number("expected_error", image.Choice.ExpectedError);
    number("auto_tolerance", image.Choice.Tolerance);
    number("auto_met", image.Choice.Met ? 1.0 : 0.0);
    // the tolerance was below what the volume allows: the floor the choice was made at (radians)
    number("auto_floor", image.Choice.AtFloor ? image.Choice.Floor : 0.0);
    // the tricubic reference's own estimated error, radians (0: not measured: the tolerance
    // was not within its reach)
    number("auto_reference_error", image.Choice.ReferenceError);
    // 1: a camera move kept the previous view's choice (no pilot this update)
    number("auto_reused", image.Choice.Reused ? 1.0 : 0.0);
  }
  return out;
}

TraceClock::TraceClock(int passes)
  : Start(std::chrono::steady_clock::now())
  , Passes(passes)
{
}

std::string TraceClock::Text(double progress)
{
  this->Reached = progress;
  const double now =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  if (this->StartProgress < 0 && progress >= 0.05)
    this->StartProgress = progress;
  const double done = progress - this->StartProgress;
  // after about one pass's share of the tracing (at least 1 %) and a tenth of a second
  const double share = std::max(0.01, 0.9 / std::max(1, this->Passes));
  if (!(this->StartProgress >= 0 && done >= share && now > 0.1 && progress < 0.95))
    return std::string();
  std::ostringstream t;
  const double left = now * (0.95 - progress) / done;
  t << "SchlierenImage: " << static_cast<int>(100 * (progress - 0.05) / 0.9) << " % traced, about "
    << (left < 10 ? std::round(left * 10) / 10 : std::round(left)) << " s left";
  return t.str();
}

int TraceClock::Percent() const
{
  return static_cast<int>(100 * std::max(0.0, this->Reached - 0.05) / 0.9);
}

std::string JsonString(const std::string& s)
{
  std::string out = "\"";
  for (unsigned char c : s)
  {
    switch (c)
    {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (c < 0x20)
        {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out += buf;
        }
        else
          out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

std::string JsonNumber(double v)
{
  if (!std::isfinite(v))
    return v != v ? "NaN" : (v > 0 ? "Infinity" : "-Infinity"); // Python's json reads these
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

std::string ImageReportJson(const SessionImage& image)
{
  std::ostringstream o;
  o << "{";
  bool first = true;
  for (const ReportEntry& e : ImageReport(image))
  {
    o << (first ? "" : ", ") << JsonString(e.Name) << ": ";
    first = false;
    if (e.IsText)
      o << JsonString(e.Text);
    else if (e.Numbers.size() == 1)
      o << JsonNumber(e.Numbers[0]);
    else
    {
      o << "[";
      for (std::size_t i = 0; i < e.Numbers.size(); ++i)
        o << (i ? ", " : "") << JsonNumber(e.Numbers[i]);
      o << "]";
    }
  }
  o << "}";
  return o.str();
}

} // namespace schlieren
