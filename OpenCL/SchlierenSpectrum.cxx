// SPDX-License-Identifier: BSD-3-Clause
// Light (docs/BENCH.md "Light"): a band of wavelengths, flat in wavenumber, one wavelength per
// pass. The band is split into WavelengthBins bins of equal width in wavenumber; pass p takes
// bin (p mod B) g mod B, g coprime to B near 0.618 B, so that any run of passes spreads over the
// band and B passes take every bin once; inside its bin the wavenumber is the centre (Jitter off)
// or a hashed point (Jitter on: stratified, converging to the band's integral). The pass traces
// n - 1 scaled to its wavelength (Dispersion Air: standard air's Ciddor index relative to
// Wavelength's), its phase is 2 pi / lambda of its path, and its photons carry the tristimulus
// values of lambda (CIE 1931 X, Y, Z: every weight positive, as a camera's channels); Finalize
// divides each pixel's sums by the band's (so that its light is white, D65) and converts to sRGB.
#include "SchlierenEngineInternal.h"
#include "SchlierenIndexModels.h"

#include <cmath>
#include <numeric>
#include <sstream>

namespace schlieren
{

namespace
{
int BinStep(int bins)
{
  int g = std::max(1, static_cast<int>(std::lround(0.6180339887498949 * bins)));
  while (std::gcd(g, bins) != 1)
    ++g;
  return g;
}

// standard air's n - 1 (15 C, 101325 Pa, dry, 450 ppm CO2): only its ratios are used
double AirIndex(double nm)
{
  return CiddorIndex(288.15, 101325.0, 0.0, nm);
}

// one lobe of the CIE 1931 fit of Wyman, Sloan and Shirley (2013): a Gaussian with different
// widths on either side of its peak
double Lobe(double nm, double mu, double left, double right)
{
  const double t = (nm - mu) / (nm < mu ? left : right);
  return std::exp(-0.5 * t * t);
}
}

double SpectralWavelength(const TraceSettings& s, int pass)
{
  const int bins = std::max(1, s.WavelengthBins);
  const int bin = static_cast<int>((static_cast<long long>(pass % bins) * BinStep(bins)) % bins);
  double u = 0.5;
  if (s.Jitter)
    u = sch_unit(sch_hash(s.Seed * 3266489917u ^ sch_hash(static_cast<sch_uint>(pass) * 668265263u + 0x85ebca6bu)));
  // wavenumbers 1/nm: from the long end of the band (the smallest) to the short one
  const double lo = 1.0 / s.WavelengthRange[1], hi = 1.0 / s.WavelengthRange[0];
  return 1.0 / (lo + (hi - lo) * (bin + u) / bins);
}

double DispersionScale(const TraceSettings& s, double nm)
{
  if (s.Disperse == Dispersion::None || nm == s.Wavelength)
    return 1.0;
  return AirIndex(nm) / AirIndex(s.Wavelength);
}

void SpectralXYZ(double nm, double xyz[3])
{
  const double X = 1.056 * Lobe(nm, 599.8, 37.9, 31.0) + 0.362 * Lobe(nm, 442.0, 16.0, 26.7) -
    0.065 * Lobe(nm, 501.1, 20.4, 26.2);
  const double Y = 0.821 * Lobe(nm, 568.8, 46.9, 40.5) + 0.286 * Lobe(nm, 530.9, 16.3, 31.1);
  const double Z = 1.217 * Lobe(nm, 437.0, 11.8, 36.0) + 0.681 * Lobe(nm, 459.0, 26.0, 13.8);
  xyz[0] = X;
  xyz[1] = Y;
  xyz[2] = Z;
}

void SpectrumMeanXYZ(const TraceSettings& s, int passes, double xyz[3])
{
  xyz[0] = xyz[1] = xyz[2] = 0;
  for (int p = 0; p < passes; ++p)
  {
    double c[3];
    SpectralXYZ(SpectralWavelength(s, p), c);
    for (int a = 0; a < 3; ++a)
      xyz[a] += c[a] / passes;
  }
}

void BandColour(const double share[3], float rgb[3])
{
  // the band's white as D65 (a von Kries scaling in XYZ), then XYZ to linear sRGB (IEC
  // 61966-2-1), which takes D65 to (1, 1, 1); clamped to [0, 1] where a colour is out of gamut
  const double X = 0.95047 * share[0], Y = share[1], Z = 1.08883 * share[2];
  const double c[3] = { 3.2406 * X - 1.5372 * Y - 0.4986 * Z, -0.9689 * X + 1.8758 * Y + 0.0415 * Z,
    0.0557 * X - 0.2040 * Y + 1.0570 * Z };
  for (int a = 0; a < 3; ++a)
    rgb[a] = static_cast<float>(std::min(1.0, std::max(0.0, c[a])));
}

std::string SpectrumText(const TraceSettings& s, int passes, double scale[2])
{
  const int bins = std::max(1, s.WavelengthBins);
  scale[0] = DispersionScale(s, s.WavelengthRange[1]);
  scale[1] = DispersionScale(s, s.WavelengthRange[0]);
  std::ostringstream t;
  t << s.WavelengthRange[0] << "-" << s.WavelengthRange[1] << " nm flat in wavenumber, one "
    << "wavelength per pass in " << bins << " bins (" << std::min(passes, bins) << " of them "
    << "traced" << (s.Jitter ? ", jittered inside each" : ", at their centres") << "); n - 1 ";
  if (s.Disperse == Dispersion::Air)
    t << "scaled from " << s.Wavelength << " nm by air's dispersion (Ciddor), x" << scale[0]
      << " to x" << scale[1];
  else
    t << "the same at every wavelength (Dispersion None)";
  return t.str();
}

void Splatter::BeginPass(sch_params& Pk, int pass)
{
  CameraPass(S, Pk, pass, lensTilt);
  if (!white)
    return;
  const double nm = SpectralWavelength(S, pass);
  Pk.indexScale = static_cast<float>(DispersionScale(S, nm));
  twoPiOverLambda = 2 * 3.14159265358979323846 / (nm * 1e-9);
  tiltScale = S.Wavelength / nm;
  SpectralXYZ(nm, passColour);
}

} // namespace schlieren
