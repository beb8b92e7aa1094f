// SPDX-License-Identifier: BSD-3-Clause
// The refractive-index models (SchlierenIndexModels.h) against ../shared/ORACLES.md, section
// "Refractive index": Ciddor (NIST form) to 1e-9 in n on every row of the table, Gladstone-Dale for
// helium/air to the digits given there, the ideal-gas density of air; and bad input (negative
// temperature, NaN pressure, mass fractions above 1) gets an Error naming the array and the count.
#include "SchlierenIndexModels.h"
#include "SchlierenSamplingGrid.h"
#include "SchlierenTesting.h"

#include <limits>

using namespace schlieren;
using schtest::ExpectError;

namespace
{
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

// The whole-field entry point the RefractiveIndex filter calls: each model against the ORACLES
// values above (through units, references, offsets and the validity mask), and its messages.
void TestFields()
{
  // GladstoneDale with a non-dimensional density (PLOT3D style): rho = 1.2 kg/m^3 * value.
  {
    const float rhoND[3] = { 1.0f, 0.19f, 4.98f };
    float out[3];
    FieldArrays f;
    f.Count = 3;
    f.Density = { rhoND, "Density" };
    FieldModel m;
    m.Model = IndexModel::GladstoneDale;
    m.DensityReference = 1.2;
    ComputeFieldIndex(f, m, out);
    for (int i = 0; i < 3; ++i)
      CHECK_NEAR(out[i], 0.2256e-3 * 1.2 * rhoND[i], 1e-10, "GladstoneDale, scaled density");
    m.SingleGas = GasChoice::Typed(0.5e-3, 0.01);
    ComputeFieldIndex(f, m, out);
    CHECK_NEAR(out[0], 0.5e-3 * 1.2, 1e-10, "GladstoneDale, typed K");
  }

  // Helium/air (ORACLES) through IdealGas: T in Celsius, p in kPa, by mixture fraction and by
  // species (with and without a balance gas).
  const float f3[3] = { 0.0f, 0.5f, 1.0f };
  const float air3[3] = { 1.0f, 0.5f, 0.0f };
  const float T3[3] = { 20.0f, 20.0f, 20.0f };
  const float p3[3] = { 101.325f, 101.325f, 101.325f };
  const double expected[3] = { 2.7164e-4, 6.1546e-5, 3.2513e-5 };
  {
    FieldArrays f;
    f.Count = 3;
    f.Temperature = { T3, "T" };
    f.Pressure = { p3, "p" };
    f.MixtureFraction = { f3, "f" };
    f.Species[0] = { f3, "Y_He" };
    f.Species[1] = { air3, "Y_air" };
    FieldModel m;
    m.Model = IndexModel::IdealGas;
    m.TemperatureUnits = TemperatureUnit::Celsius;
    m.PressureUnits = PressureUnit::Kilopascal;
    m.Mixture = Composition::MixtureFraction;
    float out[3];
    ComputeFieldIndex(f, m, out);
    for (int i = 0; i < 3; ++i)
      CHECK_NEAR(out[i], expected[i], HalfUlp(expected[i], 5),
        "IdealGas by mixture fraction, f = " + std::to_string(f3[i]));
    m.Mixture = Composition::Species;
    m.NumberOfSpecies = 1;
    m.Species[0] = GasChoice::Table(Gas::Helium);
    m.Balance = GasChoice::Table(Gas::Air);
    ComputeFieldIndex(f, m, out);
    for (int i = 0; i < 3; ++i)
      CHECK_NEAR(out[i], expected[i], HalfUlp(expected[i], 5), "IdealGas by species + balance");
    m.NumberOfSpecies = 2;
    m.Species[1] = GasChoice::Typed(0.2256e-3, 28.9641e-3); // air, typed
    m.HasBalance = false;
    FieldReport r = ComputeFieldIndex(f, m, out);
    for (int i = 0; i < 3; ++i)
      CHECK_NEAR(out[i], expected[i], HalfUlp(expected[i], 5), "IdealGas by two species, no balance");
    CHECK(r.Warnings.empty(), "no warning for species that sum to 1");

    // GladstoneDaleMixture from the density the ideal gas gives at f = 0.5 (0.29238 kg/m^3).
    const float rho[1] = { 0.29238f };
    const float half[1] = { 0.5f };
    FieldArrays g;
    g.Count = 1;
    g.Density = { rho, "rho" };
    g.MixtureFraction = { half, "f" };
    FieldModel gm;
    gm.Model = IndexModel::GladstoneDaleMixture;
    gm.Mixture = Composition::MixtureFraction;
    float one[1];
    ComputeFieldIndex(g, gm, one);
    CHECK_NEAR(one[0], 6.1546e-5, HalfUlp(6.1546e-5, 5), "GladstoneDaleMixture at f = 0.5");
  }

  // Pressure units and a gauge pressure with an operating-pressure offset: 1 atm three ways.
  {
    const float T[1] = { 293.15f };
    const float gauge[1] = { 0.0f }, atm[1] = { 1.0f }, bar[1] = { 1.01325f };
    float a[1], b[1], c[1];
    FieldArrays f;
    f.Count = 1;
    f.Temperature = { T, "T" };
    FieldModel m;
    m.Model = IndexModel::IdealGas;
    m.Mixture = Composition::SingleGas;
    f.Pressure = { gauge, "p_gauge" };
    m.PressureUnits = PressureUnit::Kilopascal;
    m.PressureOffset = 101.325;
    ComputeFieldIndex(f, m, a);
    f.Pressure = { atm, "p_atm" };
    m.PressureUnits = PressureUnit::Atmosphere;
    m.PressureOffset = 0.0;
    ComputeFieldIndex(f, m, b);
    f.Pressure = { bar, "p_bar" };
    m.PressureUnits = PressureUnit::Bar;
    ComputeFieldIndex(f, m, c);
    CHECK_NEAR(a[0], 2.7164e-4, HalfUlp(2.7164e-4, 5), "air at 1 atm: gauge 0 kPa + 101.325 kPa");
    CHECK_NEAR(b[0], a[0], 1e-11, "air at 1 atm: in atm");
    CHECK_NEAR(c[0], a[0], 1e-11, "air at 1 atm: in bar");
    // Non-dimensional T and p (T / 293.15 K, p / 101325 Pa).
    const float one[1] = { 1.0f };
    f.Temperature = { one, "T_nd" };
    f.Pressure = { one, "p_nd" };
    m.PressureUnits = PressureUnit::Pascal;
    m.TemperatureReference = 293.15;
    m.PressureReference = 101325.0;
    ComputeFieldIndex(f, m, b);
    CHECK_NEAR(b[0], a[0], 1e-11, "air at 1 atm from non-dimensional T and p");
  }

  // Ciddor through the field entry point: the 633 nm rows of ORACLES in C and kPa, humidity as
  // an array; CO2 constant.
  {
    const float T[5] = { 20, 20, 50, -40, 50 };
    const float p[5] = { 101.325f, 60, 100, 100, 120 };
    const float h[5] = { 0, 0, 0, 0, 1 };
    const double n[5] = { 1.000271800, 1.000160924, 1.000243285, 1.000337580, 1.000287924 };
    FieldArrays f;
    f.Count = 5;
    f.Temperature = { T, "t_C" };
    f.Pressure = { p, "p_kPa" };
    f.Humidity = { h, "RH" };
    FieldModel m;
    m.Model = IndexModel::Ciddor;
    m.TemperatureUnits = TemperatureUnit::Celsius;
    m.PressureUnits = PressureUnit::Kilopascal;
    m.Wavelength = 633.0;
    float out[5];
    ComputeFieldIndex(f, m, out);
    for (int i = 0; i < 5; ++i)
      CHECK_NEAR(1.0 + out[i], n[i], 1e-9, "Ciddor field, row " + std::to_string(i));
  }

  // Passthrough of n or n - 1; the validity mask: invalid points are skipped (even NaN there).
  {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float n1[4] = { 1e-4f, 2e-4f, nan, 3e-4f };
    const float nn[4] = { 1.0001f, 1.0002f, nan, 1.0003f };
    const unsigned char valid[4] = { 1, 1, 0, 1 };
    float out[4] = { 0, 0, -7.0f, 0 };
    FieldArrays f;
    f.Count = 4;
    f.Index = { n1, "n_minus_1" };
    f.Valid = valid;
    FieldModel m;
    FieldReport r = ComputeFieldIndex(f, m, out);
    CHECK(r.ValidPoints == 3, "three valid points");
    CHECK_NEAR(out[3], 3e-4, 1e-10, "Passthrough n - 1");
    CHECK(out[2] == -7.0f, "an invalid point is left as it was");
    f.Index = { nn, "n" };
    m.IndexIsN = true;
    ComputeFieldIndex(f, m, out);
    CHECK_NEAR(out[1], 2e-4, 1e-7, "Passthrough n (float n keeps ~1e-7 of n - 1)");
  }
}

void TestFieldErrors()
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float T[4] = { 300.0f, nan, 280.0f, inf };
  const float Tc[4] = { 20.0f, -300.0f, 20.0f, 20.0f };
  const float p[4] = { 1e5f, 1e5f, 1e5f, 1e5f };
  const float zero[4] = { 1e5f, 0.0f, 1e5f, 1e5f };
  float out[4];
  FieldArrays f;
  f.Count = 4;
  FieldModel m;
  m.Model = IndexModel::IdealGas;
  m.Mixture = Composition::SingleGas;
  f.Pressure = { p, "Pres" };
  ExpectError("IdealGas without a temperature array",
    [&] { ComputeFieldIndex(f, m, out); }, { "IdealGas", "temperature array" });
  f.Temperature = { T, "Temp" };
  ExpectError("NaN and Inf temperature", [&] { ComputeFieldIndex(f, m, out); },
    { "'Temp'", "temperature", "2 of 4 points", "NaN or infinite", "index 1" });
  f.Temperature = { Tc, "Temp" };
  m.TemperatureUnits = TemperatureUnit::Celsius;
  ExpectError("temperature below absolute zero after the unit",
    [&] { ComputeFieldIndex(f, m, out); }, { "'Temp'", "1 of 4 points", "absolute zero", "-26.85" });
  m.TemperatureUnits = TemperatureUnit::Kelvin;
  f.Temperature = { p, "Temp" };
  f.Pressure = { zero, "Pres" };
  ExpectError("zero pressure", [&] { ComputeFieldIndex(f, m, out); },
    { "'Pres'", "pressure", "1 of 4 points", "PressureOffset" });

  // Density: negative is an error, zero a warning.
  const float rho[4] = { 1.0f, -0.5f, 0.0f, 1.0f };
  const float rho0[4] = { 1.0f, 0.0f, 0.0f, 1.0f };
  FieldArrays g;
  g.Count = 4;
  g.Density = { rho, "Density" };
  FieldModel gd;
  gd.Model = IndexModel::GladstoneDale;
  ExpectError("negative density", [&] { ComputeFieldIndex(g, gd, out); },
    { "'Density'", "1 of 4 points", "negative" });
  g.Density = { rho0, "Density" };
  FieldReport r = ComputeFieldIndex(g, gd, out);
  CHECK(r.Warnings.size() == 1 && r.Warnings[0].find("2 of 4 points are 0") != std::string::npos,
    "zero density is a warning: " + (r.Warnings.empty() ? std::string("(none)") : r.Warnings[0]));

  // Mass fractions: above 1 with a balance gas; not summing to 1 without one.
  const float yH2[4] = { 0.9f, 0.8f, 0.7f, 0.5f };
  const float yX[4] = { 0.1f, 0.3f, 0.2f, 0.5f };
  FieldArrays s;
  s.Count = 4;
  s.Density = { rho, "rho" };
  s.Density.Data = rho0;
  s.Species[0] = { yH2, "H2" };
  s.Species[1] = { yX, "AsH3" };
  FieldModel sm;
  sm.Model = IndexModel::GladstoneDaleMixture;
  sm.Mixture = Composition::Species;
  sm.NumberOfSpecies = 2;
  sm.Species[0] = GasChoice::Table(Gas::Hydrogen);
  sm.Species[1] = GasChoice::Typed(0.3e-3, 77.9454e-3);
  ExpectError("species summing above 1", [&] { ComputeFieldIndex(s, sm, out); },
    { "'H2'", "'AsH3'", "1 of 4 points", "sum 1.1", "balance gas (Air)" });
  sm.HasBalance = false;
  ExpectError("species not summing to 1 without a balance gas",
    [&] { ComputeFieldIndex(s, sm, out); },
    { "'H2'", "'AsH3'", "2 of 4 points", "do not sum to 1", "index 1" });
  sm.NumberOfSpecies = 1;
  ExpectError("a typed gas without a molar mass",
    [&] {
      FieldModel bad = sm;
      bad.Model = IndexModel::IdealGas;
      bad.Species[0] = GasChoice::Typed(0.3e-3, 0.0);
      FieldArrays a = s;
      a.Temperature = { p, "T" };
      a.Pressure = { p, "p" };
      ComputeFieldIndex(a, bad, out);
    },
    { "custom gas", "molar mass" });
  ExpectError("a reference of 0", [&] {
    FieldModel bad = gd;
    bad.DensityReference = 0.0;
    ComputeFieldIndex(g, bad, out);
  }, { "reference", "positive" });
}

// The domain edge, its median and the fill; the automatic sampling dimensions.
void TestDomainEdge()
{
  // A 6 x 5 x 4 grid, valid where i < 4; n - 1 = 1e-4 (i + 1).
  const int dims[3] = { 6, 5, 4 };
  const std::size_t N = 6 * 5 * 4;
  std::vector<unsigned char> valid(N);
  std::vector<float> n1(N);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 6; ++i)
      {
        const std::size_t id = i + 6 * (j + 5 * k);
        valid[id] = i < 4;
        n1[id] = i < 4 ? 1e-4f * (i + 1) : 0.0f;
      }
  std::vector<float> edge;
  CollectDomainEdge(dims, valid.data(), n1.data(), nullptr, edge);
  CHECK(edge.size() == 20, "the edge is the plane i = 3: 20 points (got " +
      std::to_string(edge.size()) + ")");
  CHECK_NEAR(Median(edge), 4e-4, 1e-10, "median of the edge");
  // Two overlapping pieces (k 0-2 and k 2-3) that own k 0-1 and k 2-3 find the same points.
  std::vector<float> a, b;
  const int ownA[6] = { 0, 5, 0, 4, 0, 1 }, ownB[6] = { 0, 5, 0, 4, 2, 3 };
  CollectDomainEdge(dims, valid.data(), n1.data(), ownA, a);
  CollectDomainEdge(dims, valid.data(), n1.data(), ownB, b);
  CHECK(a.size() + b.size() == 20, "owned pieces split the edge exactly");
  std::vector<float> even = { 1.0f, 4.0f, 2.0f, 3.0f };
  CHECK_NEAR(Median(even), 2.5, 0.0, "median of an even count");
  CHECK(FillInvalid(N, valid.data(), 4e-4, n1.data()) == 2 * 5 * 4, "40 points filled");
  CHECK_NEAR(n1[5], 4e-4, 1e-10, "an invalid point gets the ambient value");
  ExpectError("ambient NaN", [&] { FillInvalid(N, valid.data(), std::nan(""), n1.data()); },
    { "ambient" });

  // Extension: a field that varies along z (like a boundary layer) continues across the edge
  // i = 3 unchanged along x, so a ray along z sees no jump there.
  std::vector<float> ext(N);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 6; ++i)
      {
        const std::size_t id = i + 6 * (j + 5 * k);
        ext[id] = i < 4 ? 1e-4f * (1 + k) : 0.0f;
      }
  CHECK(ExtendIntoInvalid(dims, valid.data(), ext.data()) == 40, "40 points extended");
  double worst = 0.0;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 4; i < 6; ++i)
        worst = std::max(worst,
          std::fabs(double(ext[i + 6 * (j + 5 * k)]) - ext[3 + 6 * (j + 5 * k)]));
  CHECK_NEAR(worst, 0.0, 1e-12, "the extension is the edge value, row by row");
  // A body enclosed by flow (a ball of radius 5 in a 24^3 grid) in a linear field: the fill is the
  // same linear field (harmonic), with no ridge where the fronts from its sides meet.
  const int bd[3] = { 24, 24, 24 };
  const std::size_t BN = 24 * 24 * 24;
  std::vector<unsigned char> bv(BN);
  std::vector<float> bf(BN), truth(BN);
  for (int k = 0; k < 24; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i)
      {
        const std::size_t id = i + 24 * (j + 24 * k);
        truth[id] = 2.7e-4f + 1e-6f * i - 2e-6f * j + 0.5e-6f * k;
        bv[id] = (i - 11.5) * (i - 11.5) + (j - 11.5) * (j - 11.5) + (k - 11.5) * (k - 11.5) > 25.0;
        bf[id] = bv[id] ? truth[id] : 0.0f;
      }
  ExtendIntoInvalid(bd, bv.data(), bf.data());
  double worstBall = 0.0;
  for (std::size_t id = 0; id < BN; ++id)
    worstBall = std::max(worstBall, std::fabs(double(bf[id]) - truth[id]));
  std::printf("harmonic fill of a ball in a linear field: max error %.3g (field range 7e-5)\n",
    worstBall);
  CHECK(worstBall < 1e-9, "the fill inside an enclosed body continues a linear field");
  std::vector<unsigned char> none(N, 0);
  ExpectError("nothing valid to extend", [&] { ExtendIntoInvalid(dims, none.data(), ext.data()); },
    { "no point" });

  // The blunt fin's box: 128 points along x, the same spacing (within rounding) along y and z.
  const double fin[6] = { -7.8157, 14.3622, 0.0, 8.32756, 0.0, 5.72425 };
  int d[3];
  AutomaticDimensions(fin, 128, d);
  std::printf("blunt fin box -> %d x %d x %d\n", d[0], d[1], d[2]);
  CHECK(d[0] == 128 && d[1] == 49 && d[2] == 34, "automatic dimensions of the blunt fin's box");
  for (int a2 = 1; a2 < 3; ++a2)
  {
    const double h = (fin[2 * a2 + 1] - fin[2 * a2]) / (d[a2] - 1);
    CHECK_NEAR(h / ((fin[1] - fin[0]) / 127.0), 1.0, 0.03, "spacing nearly isotropic");
  }
  const double flat[6] = { 0, 1, 0, 1, 2, 2 };
  AutomaticDimensions(flat, 64, d);
  CHECK(d[0] == 64 && d[1] == 64 && d[2] == 1, "a flat box keeps one layer");
  ExpectError("empty bounds", [&] {
    const double e[6] = { 1, -1, 1, -1, 1, -1 };
    AutomaticDimensions(e, 128, d);
  }, { "empty" });
}

/** RefractiveIndex's messages that the engine gives the C++ filter before resampling and for an
 * upstream that did not honour the extent asked (SchlierenSamplingGrid.h), word for word. */
void TestRequestMessages()
{
  const int grown[6] = { 0, 10, 0, 10, 4, 10 }, inside[6] = { 0, 10, 0, 10, 5, 10 },
            past[6] = { 0, 10, 0, 10, 3, 10 };
  CHECK(ExtentCoverProblem(grown, inside).empty(), "an input extent that covers the request");
  CHECK(ExtentCoverProblem(grown, past) ==
      "The input's extent (0 10 0 10 4 10) does not cover the requested extent (0 10 0 10 3 10); "
      "the upstream filter did not honour the update request.",
    "an input extent short of the request: the C++ filter's message");
  CHECK(MissingArrayProblem({ "density" }, { "Density", "Momentum" }, "GladstoneDale") ==
      "GladstoneDale reads the array 'density', which the input does not have. Arrays present: "
      "Density, Momentum. Choose one of them.",
    "a missing array named with the arrays present");
  CHECK(MissingArrayProblem({ "T" }, {}, "IdealGas") ==
      "IdealGas reads the array 'T', which the input does not have. Arrays present: none. Choose "
      "one of them.",
    "a missing array where the input has none");
  CHECK(MissingArrayProblem({ "T", "p" }, { "p", "T" }, "IdealGas").empty(), "all present");
}
} // namespace

int main()
{
  TestRequestMessages();
  TestCiddor();
  TestGladstoneDale();
  TestErrors();
  TestFields();
  TestFieldErrors();
  TestDomainEdge();
  return schtest::Finish();
}
