// SPDX-License-Identifier: BSD-3-Clause
// The refractive-index models (SchlierenIndexModels.h) against ../shared/ORACLES.md, section
// "Refractive index": Ciddor (NIST form) to 1e-9 in n on every row of the table, Gladstone-Dale for
// helium/air to the digits given there, the ideal-gas density of air; and bad input (negative
// temperature, NaN pressure, mass fractions above 1) gets an Error naming the array and the count.
#include "SchlierenIndexModels.h"
#include "SchlierenTesting.h"

#include <limits>

using namespace schlieren;

namespace
{
// Runs f; passes if it throws schlieren::Error whose message contains every one of `needles`.
template <typename F>
void ExpectError(const char* what, F f, std::vector<std::string> needles)
{
  std::string msg;
  bool threw = false;
  try
  {
    f();
  }
  catch (const Error& e)
  {
    threw = true;
    msg = e.what();
  }
  bool found = threw;
  for (const std::string& n : needles)
    found = found && msg.find(n) != std::string::npos;
  std::printf("%s -> %s\n", what, threw ? msg.substr(0, 300).c_str() : "(no error)");
  CHECK(found, std::string(what) + ": expected an error mentioning the cause, got: " + msg);
}

// The tolerance to a number given to `digits` significant figures: half a unit in the last place.
double HalfUlp(double v, int digits)
{
  const double e = std::floor(std::log10(std::fabs(v)));
  return 0.5 * std::pow(10.0, e - (digits - 1));
}

void TestCiddor()
{
  struct Row
  {
    double t, pkPa, rh, lambda, n;
  };
  // ORACLES.md: t (C), p (kPa), RH (%), lambda (nm), n; CO2 450 umol/mol.
  const Row rows[] = {
    { 20, 101.325, 0, 633, 1.000271800 },
    { 20, 60, 0, 633, 1.000160924 },
    { 50, 100, 0, 633, 1.000243285 },
    { -40, 100, 0, 633, 1.000337580 },
    { 50, 120, 100, 633, 1.000287924 },
    { 40, 110, 100, 1700, 1.000270247 },
    { 40, 110, 100, 300, 1.000289000 },
    { -40, 120, 0, 300, 1.000427233 },
  };
  std::vector<float> T, p, h, out;
  for (const Row& r : rows)
  {
    const double T_K = ToKelvin(r.t, TemperatureUnit::Celsius);
    const double p_Pa = ToPascal(r.pkPa, PressureUnit::Kilopascal);
    const double n1 = CiddorIndex(T_K, p_Pa, r.rh / 100.0, r.lambda, 450.0);
    char what[160];
    std::snprintf(what, sizeof(what), "Ciddor n at %g C, %g kPa, %g %% RH, %g nm (error %+.2e)",
      r.t, r.pkPa, r.rh, r.lambda, 1.0 + n1 - r.n);
    std::printf("%s\n", what);
    CHECK_NEAR(1.0 + n1, r.n, 1e-9, what);

    // The same through the mole-fraction input: x_w = f h p_sv / p.
    const double xw = EnhancementFactor(p_Pa, T_K) * (r.rh / 100.0) *
      SaturationVapourPressure(T_K) / p_Pa;
    CHECK_NEAR(CiddorIndex(T_K, p_Pa, xw, r.lambda, 450.0, HumidityMeasure::MoleFraction), n1,
      1e-15, "Ciddor with the water mole fraction given directly");

    T.push_back(static_cast<float>(T_K));
    p.push_back(static_cast<float>(p_Pa));
    h.push_back(static_cast<float>(r.rh / 100.0));
  }

  // The array version at 633 nm for the 633 nm rows: float storage costs ~1e-7 relative of n - 1.
  out.resize(T.size());
  CiddorIndex(T.data(), p.data(), T.size(), ScalarField::PerPoint(h.data()), 633.0,
    ScalarField::Constant(450.0), out.data());
  for (std::size_t i = 0; i < T.size(); ++i)
    if (rows[i].lambda == 633)
      CHECK_NEAR(1.0 + out[i], rows[i].n, 1e-9, "Ciddor, array version, row " + std::to_string(i));

  // Standard dry air (15 C, 101325 Pa, 450 umol/mol) is n_axs itself; CO2 raises n a little.
  const double nStd = CiddorIndex(288.15, 101325.0, 0.0, 633.0);
  CHECK(CiddorIndex(288.15, 101325.0, 0.0, 633.0, 800.0) > nStd, "more CO2, higher index");
  // Saturation pressure is continuous at 0 C (water and ice agree at the triple point to 0.1 %).
  CHECK_NEAR(SaturationVapourPressure(273.15 - 1e-9) / SaturationVapourPressure(273.15), 1.0,
    1e-3, "saturation pressure over ice and water meet at 0 C");
  CHECK_NEAR(SaturationVapourPressure(373.124), 101325.0, 10.0, "water boils at 99.974 C");
}

void TestGladstoneDale()
{
  // The table, in SI.
  CHECK_NEAR(GladstoneDaleConstant(Gas::Air), 0.2256e-3, 1e-15, "K air");
  CHECK_NEAR(GladstoneDaleConstant(Gas::Helium), 0.1954e-3, 1e-15, "K He");
  CHECK_NEAR(MolarMass(Gas::Air), 28.9641e-3, 1e-15, "M air");
  CHECK_NEAR(MolarMass(Gas::Helium), 4.002602e-3, 1e-15, "M He");
  CHECK(ParseGas("helium") == Gas::Helium && ParseGas("HE") == Gas::Helium, "He by either name");
  CHECK(ParseGas("co2") == Gas::CarbonDioxide && ParseGas("Air") == Gas::Air, "CO2, air");
  ExpectError("unknown gas", [] { ParseGas("xenon"); }, { "xenon", "Air", "He (Helium)", "CO2" });

  // Ideal-gas air at 293.15 K, 101325 Pa: rho = p M / (R T).
  const double rhoAir = IdealGasDensity(101325.0, 293.15, MolarMass(Gas::Air));
  CHECK_NEAR(rhoAir, 101325.0 * 0.0289641 / (8.314462618 * 293.15), 1e-15, "air density formula");
  CHECK_NEAR(rhoAir, 1.20407, HalfUlp(1.20407, 6), "air density at 20 C, 1 atm");

  // Helium/air (paper's eq. 2), f = helium mass fraction, at 293.15 K and 101325 Pa.
  const float f[3] = { 0.0f, 0.5f, 1.0f };
  const double expected[3] = { 2.7164e-4, 6.1546e-5, 3.2513e-5 };
  float K[3], M[3], T[3], p[3], rho[3], n1[3];
  MixtureFractionConstant(f, 3, Gas::Air, Gas::Helium, K, M);
  for (int i = 0; i < 3; ++i)
  {
    T[i] = 293.15f;
    p[i] = 101325.0f;
  }
  IdealGasDensity(p, T, 3, ScalarField::PerPoint(M), rho);
  GladstoneDale(rho, K, 3, n1);
  for (int i = 0; i < 3; ++i)
    CHECK_NEAR(n1[i], expected[i], HalfUlp(expected[i], 5),
      "helium/air n - 1 at f = " + std::to_string(f[i]));
  CHECK_NEAR(M[1] * 1e3, 7.0333, HalfUlp(7.0333, 5), "helium/air M at f = 0.5 (g/mol)");
  CHECK_NEAR(rho[1], 0.29238, HalfUlp(0.29238, 5), "helium/air rho at f = 0.5 (kg/m^3)");

  // The same by the scalar and species routes, in double.
  const Gas he[1] = { Gas::Helium };
  const double half[1] = { 0.5 };
  const double Kmix = MixtureConstant(he, half, 1, Gas::Air);
  const double Mmix = MixtureMolarMass(he, half, 1, Gas::Air);
  const double n1mix = Kmix * IdealGasDensity(101325.0, 293.15, Mmix);
  CHECK_NEAR(Mmix * 1e3, 7.0333, HalfUlp(7.0333, 5), "MixtureMolarMass at Y_He = 0.5");
  CHECK_NEAR(n1mix, 6.1546e-5, HalfUlp(6.1546e-5, 5), "scalar helium/air n - 1 at Y_He = 0.5");
  const float* Y[1] = { f };
  float Ks[3], Ms[3];
  SpeciesConstant(Y, he, 1, 3, Gas::Air, Ks, Ms);
  for (int i = 0; i < 3; ++i)
  {
    CHECK_NEAR(Ks[i], K[i], 1e-12, "species route K = mixture-fraction route K");
    CHECK_NEAR(Ms[i], M[i], 1e-9, "species route M = mixture-fraction route M");
  }
  // A balance gas fills what the listed species leave: 20 % O2 in N2.
  const Gas o2[1] = { Gas::Oxygen };
  const double y20[1] = { 0.2 };
  CHECK_NEAR(MixtureConstant(o2, y20, 1, Gas::Nitrogen), (0.2 * 0.1888 + 0.8 * 0.2381) * 1e-3,
    1e-15, "O2 in balance N2");

  // Single-constant Gladstone-Dale.
  const float rho1[2] = { 1.2f, 0.0f };
  float out[2];
  GladstoneDale(rho1, 2, GladstoneDaleConstant(Gas::Air), out);
  CHECK_NEAR(out[0], 1.2 * 0.2256e-3, 1e-10, "n - 1 = K rho");
  CHECK_NEAR(out[1], 0.0, 0.0, "vacuum");

  // Units.
  CHECK_NEAR(ToPascal(1.0, PressureUnit::Atmosphere), 101325.0, 0.0, "1 atm");
  CHECK_NEAR(ToPascal(1.0, PressureUnit::Bar), 1e5, 0.0, "1 bar");
  CHECK_NEAR(ToKelvin(-273.15, TemperatureUnit::Celsius), 0.0, 0.0, "absolute zero");
  const float nd[2] = { 1.0f, 2.5f };
  float si[2];
  ScaleByReference(nd, 2, 101325.0, si);
  CHECK_NEAR(si[1], 253312.5, 0.0, "non-dimensional pressure to Pa");
}

void TestErrors()
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float T[4] = { 300.0f, -5.0f, 280.0f, -1.0f };
  const float Tok[4] = { 300.0f, 300.0f, 300.0f, 300.0f };
  const float p[4] = { 1e5f, 1e5f, 1e5f, 1e5f };
  const float pNaN[4] = { 1e5f, nan, 1e5f, 1e5f };
  float rho[4];
  ExpectError("negative temperature",
    [&] { IdealGasDensity(p, T, 4, ScalarField::Constant(0.029), rho); },
    { "temperature", "2 of 4 points", "index 1", "-5", "kelvin" });
  ExpectError("NaN pressure",
    [&] { IdealGasDensity(pNaN, Tok, 4, ScalarField::Constant(0.029), rho); },
    { "pressure", "1 of 4 points", "index 1", "nan" });
  ExpectError("negative temperature (Ciddor)",
    [&] {
      CiddorIndex(T, p, 4, ScalarField::Constant(0.5), 633.0, ScalarField::Constant(450.0), rho);
    },
    { "temperature", "2 of 4 points" });
  ExpectError("NaN pressure (Ciddor)",
    [&] {
      CiddorIndex(Tok, pNaN, 4, ScalarField::Constant(0.5), 633.0, ScalarField::Constant(450.0),
        rho);
    },
    { "pressure", "1 of 4 points" });
  ExpectError("humidity in percent",
    [&] {
      const float h[4] = { 50.0f, 0.5f, 60.0f, 70.0f };
      CiddorIndex(Tok, p, 4, ScalarField::PerPoint(h), 633.0, ScalarField::Constant(450.0), rho);
    },
    { "humidity", "3 of 4 points", "0.5" });
  ExpectError("wavelength out of range", [] { CiddorIndex(293.15, 101325.0, 0.0, 200.0); },
    { "wavelength", "300-1700 nm" });

  // Mass fractions above 1, one array at a time and in sum.
  const float f[4] = { 0.2f, 1.5f, 1.2f, 0.3f };
  float K[4];
  ExpectError("mixture fraction above 1",
    [&] { MixtureFractionConstant(f, 4, Gas::Air, Gas::Helium, K); },
    { "mixture fraction", "2 of 4 points", "index 1", "1.5" });
  const float yHe[4] = { 0.6f, 0.5f, 0.7f, 0.1f };
  const float yCO2[4] = { 0.6f, 0.4f, 0.2f, 0.1f };
  const float* Y[2] = { yHe, yCO2 };
  const Gas species[2] = { Gas::Helium, Gas::CarbonDioxide };
  ExpectError("mass fractions summing above 1",
    [&] { SpeciesConstant(Y, species, 2, 4, Gas::Nitrogen, K); },
    { "mass fractions", "1 of 4 points", "index 0", "sum 1.2", "N2" });
  const float* Ybad[2] = { yHe, f };
  ExpectError("a species mass fraction above 1",
    [&] { SpeciesConstant(Ybad, species, 2, 4, Gas::Nitrogen, K); },
    { "mass fraction of CO2", "2 of 4 points", "index 1" });
  const double yScalar[2] = { 0.7, 0.6 };
  ExpectError("scalar mass fractions summing above 1",
    [&] { MixtureConstant(species, yScalar, 2, Gas::Air); }, { "mass fractions", "1.3" });
  ExpectError("negative density",
    [&] {
      const float r[4] = { 1.0f, -1.0f, 1.0f, 1.0f };
      GladstoneDale(r, 4, 2.256e-4, K);
    },
    { "density", "1 of 4 points" });
}
} // namespace

int main()
{
  TestCiddor();
  TestGladstoneDale();
  TestErrors();
  return schtest::Finish();
}
