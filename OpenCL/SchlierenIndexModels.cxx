// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenIndexModels.h"

#include "SchlierenEngine.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace schlieren
{
namespace
{

// K in cm^3/g and M in g/mol as tabulated; converted to SI (x 1e-3 both) on use.
struct GasRow
{
  Gas Id;
  const char* Name;
  const char* Alias;
  double KcgsPerGram;
  double GramsPerMole;
};

const GasRow GasTable[] = {
  { Gas::Air, "Air", "Air", 0.2256, 28.9641 },
  { Gas::Helium, "He", "Helium", 0.1954, 4.002602 },
  { Gas::Nitrogen, "N2", "Nitrogen", 0.2381, 28.0134 },
  { Gas::Oxygen, "O2", "Oxygen", 0.1888, 31.9988 },
  { Gas::Argon, "Ar", "Argon", 0.1576, 39.948 },
  { Gas::CarbonDioxide, "CO2", "CarbonDioxide", 0.2265, 44.0095 },
  { Gas::Hydrogen, "H2", "Hydrogen", 1.5395, 2.01588 },
  { Gas::Water, "H2O", "Water", 0.3127, 18.01528 },
  { Gas::Methane, "CH4", "Methane", 0.617, 16.0425 },
  { Gas::CarbonMonoxide, "CO", "CarbonMonoxide", 0.268, 28.0101 },
};
constexpr int NumberOfGasRows = static_cast<int>(sizeof(GasTable) / sizeof(GasTable[0]));
static_assert(NumberOfGasRows == static_cast<int>(Gas::NumberOfGases), "one row per gas");

const GasProperties* BuildProperties()
{
  static GasProperties props[NumberOfGasRows];
  for (int i = 0; i < NumberOfGasRows; ++i)
  {
    const GasRow& r = GasTable[i];
    props[i] = GasProperties{ r.Id, r.Name, r.Alias, r.KcgsPerGram * 1e-3, r.GramsPerMole * 1e-3 };
  }
  return props;
}

std::string Lower(const std::string& s)
{
  std::string out(s);
  for (char& c : out)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string Num(double v)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.7g", v); // the inputs are floats: 7 digits are all they hold
  return buf;
}

/** Counts the points where `bad(value)` holds; remembers the first. */
struct BadPoints
{
  std::size_t Count = 0;
  std::size_t First = 0;
  double FirstValue = 0.0;
  void Add(std::size_t i, double v)
  {
    if (this->Count++ == 0)
    {
      this->First = i;
      this->FirstValue = v;
    }
  }
};

template <typename Bad>
BadPoints Scan(const float* a, std::size_t n, Bad bad)
{
  BadPoints b;
  for (std::size_t i = 0; i < n; ++i)
    if (bad(static_cast<double>(a[i])))
      b.Add(i, a[i]);
  return b;
}

/** "<name>: 3 of 1000 points <problem> (first at index 5: -12). <todo>" */
[[noreturn]] void ThrowBad(const std::string& name, const BadPoints& b, std::size_t n,
  const std::string& problem, const std::string& todo, const std::string& valueLabel = "")
{
  // `problem` is worded for many points ("are ...", "have ..."); one point gets "is", "has".
  std::string what = problem;
  if (b.Count == 1 && what.compare(0, 4, "are ") == 0)
    what = "is " + what.substr(4);
  else if (b.Count == 1 && what.compare(0, 5, "have ") == 0)
    what = "has " + what.substr(5);
  throw Error(name + ": " + std::to_string(b.Count) + " of " + std::to_string(n) + " points " +
    what + " (first at index " + std::to_string(b.First) + ": " + valueLabel +
    Num(b.FirstValue) + "). " + todo);
}

void CheckPointers(const void* in, const void* out, const char* what)
{
  if (!in || !out)
    throw Error(std::string(what) + ": an input or output array is null; pass arrays of n values.");
}

bool NotPositiveFinite(double v)
{
  return !(v > 0.0) || !std::isfinite(v);
}

const char* TemperatureHint = "Temperature must be a finite, positive value in kelvin: check the "
                              "array, and convert Celsius or non-dimensional data (ToKelvin, "
                              "ScaleByReference).";
const char* PressureHint = "Pressure must be a finite, positive absolute pressure in pascal: "
                           "check the array, use absolute (not gauge) pressure, and convert other "
                           "units or non-dimensional data (ToPascal, ScaleByReference).";

void CheckTemperatureArray(const float* T, std::size_t n)
{
  BadPoints b = Scan(T, n, NotPositiveFinite);
  if (b.Count)
    ThrowBad("temperature", b, n, "are not positive or not finite", TemperatureHint);
}

void CheckPressureArray(const float* p, std::size_t n)
{
  BadPoints b = Scan(p, n, NotPositiveFinite);
  if (b.Count)
    ThrowBad("pressure", b, n, "are not positive or not finite", PressureHint);
}

constexpr double FractionTolerance = 1e-6;

bool BadFraction(double y)
{
  return !(y >= -FractionTolerance && y <= 1.0 + FractionTolerance);
}

double ClampFraction(double y)
{
  return y < 0.0 ? 0.0 : (y > 1.0 ? 1.0 : y);
}

const char* FractionHint = "Mass fractions must lie in [0, 1]: check that the array holds mass "
                           "fractions (not mole fractions, percent or a passive scalar on another "
                           "scale).";

std::string SpeciesLabel(const Gas* species, std::size_t s)
{
  return std::string("mass fraction of ") + GetGasProperties(species[s]).Name + " (species " +
    std::to_string(s) + ")";
}

//--- Ciddor -------------------------------------------------------------------------------------

// Saturation vapour pressure over water (IAPWS-IF97, NIST's Appendix A-I), T in K, Pa.
double SaturationOverWater(double T)
{
  const double K1 = 1.16705214528e3, K2 = -7.24213167032e5, K3 = -1.70738469401e1,
               K4 = 1.20208247025e4, K5 = -3.23255503223e6, K6 = 1.49151086135e1,
               K7 = -4.82326573616e3, K8 = 4.05113405421e5, K9 = -2.38555575678e-1,
               K10 = 6.50175348448e2;
  const double omega = T + K9 / (T - K10);
  const double A = omega * omega + K1 * omega + K2;
  const double B = K3 * omega * omega + K4 * omega + K5;
  const double C = K6 * omega * omega + K7 * omega + K8;
  const double X = -B + std::sqrt(B * B - 4.0 * A * C);
  const double r = 2.0 * C / X;
  return 1e6 * r * r * r * r;
}

// Sublimation pressure over ice (IAPWS), T in K, Pa.
double SaturationOverIce(double T)
{
  const double A1 = -13.928169, A2 = 34.7078238;
  const double theta = T / 273.16;
  const double Y = A1 * (1.0 - std::pow(theta, -1.5)) + A2 * (1.0 - std::pow(theta, -1.25));
  return 611.657 * std::exp(Y);
}

constexpr double CiddorR = 8.314472;      // J/(mol K), as in NIST's calculator
constexpr double CiddorMw = 0.018015;     // kg/mol, water
constexpr double CiddorRhoWs = 0.00985938; // kg/m^3, water vapour at 20 C, 1333 Pa
constexpr double WavelengthMin = 300.0, WavelengthMax = 1700.0; // nm

void CheckWavelength(double wavelength)
{
  if (!(wavelength >= WavelengthMin && wavelength <= WavelengthMax))
    throw Error("wavelength: " + Num(wavelength) +
      " nm is outside the range of the Ciddor equation, 300-1700 nm (vacuum wavelength in nm). "
      "Give the wavelength in nanometres (e.g. 632.8), or use Gladstone-Dale outside that range.");
}

// Water-vapour mole fraction from the humidity input; < 0 or >= 1 means bad.
double WaterMoleFraction(double T, double p, double humidity, HumidityMeasure measure)
{
  if (measure == HumidityMeasure::MoleFraction)
    return humidity;
  return EnhancementFactor(p, T) * humidity * SaturationVapourPressure(T) / p;
}

// n - 1 with checked inputs.
double CiddorUnchecked(double T, double p, double xw, double wavelength, double co2)
{
  const double sigma = 1000.0 / wavelength; // um^-1
  const double s2 = sigma * sigma;
  const double s4 = s2 * s2, s6 = s4 * s2;

  const double Ma = 0.0289635 + 1.2011e-8 * (co2 - 400.0);
  const double naxs =
    1e-8 * (5792105.0 / (238.0185 - s2) + 167917.0 / (57.362 - s2)) * (1.0 + 0.534e-6 * (co2 - 450.0));
  const double nws = 1.022e-8 * (295.235 + 2.6422 * s2 - 0.032380 * s4 + 0.004028 * s6);

  const double T0 = 288.15, p0 = 101325.0;
  const double Za = CiddorCompressibility(p0, T0, 0.0);
  const double rhoAxs = p0 * Ma / (Za * CiddorR * T0);

  const double Z = CiddorCompressibility(p, T, xw);
  const double rhoA = p * Ma * (1.0 - xw) / (Z * CiddorR * T);
  const double rhoW = p * CiddorMw * xw / (Z * CiddorR * T);
  return (rhoA / rhoAxs) * naxs + (rhoW / CiddorRhoWs) * nws;
}

std::string HumidityName(HumidityMeasure measure)
{
  return measure == HumidityMeasure::Relative ? "relative humidity" : "water-vapour mole fraction";
}

} // namespace

//------------------------------------------------------------------------------------------------
const GasProperties& GetGasProperties(Gas gas)
{
  static const GasProperties* props = BuildProperties();
  const int i = static_cast<int>(gas);
  if (i < 0 || i >= NumberOfGasRows)
    throw Error("gas: " + std::to_string(i) + " is not a gas of the table; valid gases are " +
      GasNames() + ".");
  return props[i];
}

double GladstoneDaleConstant(Gas gas)
{
  return GetGasProperties(gas).GladstoneDale;
}

double MolarMass(Gas gas)
{
  return GetGasProperties(gas).MolarMass;
}

Gas ParseGas(const std::string& name)
{
  const std::string key = Lower(name);
  for (const GasRow& r : GasTable)
    if (key == Lower(r.Name) || key == Lower(r.Alias))
      return r.Id;
  throw Error("gas: '" + name + "' is not a known gas. Use one of " + GasNames() +
    " (case does not matter), or give the Gladstone-Dale constant directly.");
}

std::string GasNames()
{
  std::string s;
  for (const GasRow& r : GasTable)
  {
    if (!s.empty())
      s += ", ";
    s += r.Name;
    if (std::string(r.Alias) != r.Name)
      s += std::string(" (") + r.Alias + ")";
  }
  return s;
}

//------------------------------------------------------------------------------------------------
void GladstoneDale(const float* rho, std::size_t n, double K, float* nMinus1)
{
  CheckPointers(rho, nMinus1, "Gladstone-Dale");
  if (!(K > 0.0) || !std::isfinite(K))
    throw Error("Gladstone-Dale constant: " + Num(K) +
      " m^3/kg is not a positive number. Use a value in m^3/kg (air at 632.8 nm: 2.256e-4; "
      "1 cm^3/g = 1e-3 m^3/kg).");
  BadPoints b = Scan(rho, n, [](double v) { return !(v >= 0.0) || !std::isfinite(v); });
  if (b.Count)
    ThrowBad("density", b, n, "are negative or not finite",
      "Density must be a finite value >= 0 in kg/m^3: check the array and its scaling.");
  for (std::size_t i = 0; i < n; ++i)
    nMinus1[i] = static_cast<float>(K * static_cast<double>(rho[i]));
}

void GladstoneDale(const float* rho, const float* K, std::size_t n, float* nMinus1)
{
  CheckPointers(rho, nMinus1, "Gladstone-Dale");
  CheckPointers(K, nMinus1, "Gladstone-Dale");
  BadPoints bk = Scan(K, n, NotPositiveFinite);
  if (bk.Count)
    ThrowBad("Gladstone-Dale constant", bk, n, "are not positive or not finite",
      "K must be positive, in m^3/kg (air at 632.8 nm: 2.256e-4).");
  BadPoints b = Scan(rho, n, [](double v) { return !(v >= 0.0) || !std::isfinite(v); });
  if (b.Count)
    ThrowBad("density", b, n, "are negative or not finite",
      "Density must be a finite value >= 0 in kg/m^3: check the array and its scaling.");
  for (std::size_t i = 0; i < n; ++i)
    nMinus1[i] = static_cast<float>(static_cast<double>(K[i]) * static_cast<double>(rho[i]));
}

namespace
{
// Checks scalar fractions; returns the balance fraction.
double CheckScalarFractions(const Gas* species, const double* Y, std::size_t count)
{
  if (count && (!species || !Y))
    throw Error("mass fractions: the species or fraction list is null; pass `count` of each.");
  double sum = 0.0;
  for (std::size_t s = 0; s < count; ++s)
  {
    if (BadFraction(Y[s]))
      throw Error(SpeciesLabel(species, s) + ": " + Num(Y[s]) + " is outside [0, 1]. " +
        FractionHint);
    sum += ClampFraction(Y[s]);
  }
  if (sum > 1.0 + FractionTolerance)
    throw Error("mass fractions: they sum to " + Num(sum) +
      ", above 1. The listed species must not include the balance gas and must sum to at most 1: "
      "renormalise them or leave one species out as the balance.");
  return sum >= 1.0 ? 0.0 : 1.0 - sum;
}
} // namespace

double MixtureConstant(const Gas* species, const double* Y, std::size_t count, Gas balance)
{
  const double rest = CheckScalarFractions(species, Y, count);
  double K = rest * GladstoneDaleConstant(balance);
  for (std::size_t s = 0; s < count; ++s)
    K += ClampFraction(Y[s]) * GladstoneDaleConstant(species[s]);
  return K;
}

double MixtureMolarMass(const Gas* species, const double* Y, std::size_t count, Gas balance)
{
  const double rest = CheckScalarFractions(species, Y, count);
  double invM = rest / MolarMass(balance);
  for (std::size_t s = 0; s < count; ++s)
    invM += ClampFraction(Y[s]) / MolarMass(species[s]);
  return 1.0 / invM;
}

void MixtureFractionConstant(const float* f, std::size_t n, Gas gas0, Gas gasF, float* K, float* M)
{
  CheckPointers(f, K, "mixture fraction");
  const GasProperties& g0 = GetGasProperties(gas0);
  const GasProperties& gF = GetGasProperties(gasF);
  BadPoints b = Scan(f, n, BadFraction);
  if (b.Count)
    ThrowBad("mixture fraction", b, n, "are outside [0, 1] or not finite",
      std::string("The mixture fraction is the mass fraction of ") + gF.Name + " (the rest is " +
        g0.Name + "): check the array and its scaling.");
  for (std::size_t i = 0; i < n; ++i)
  {
    const double y = ClampFraction(f[i]);
    K[i] = static_cast<float>((1.0 - y) * g0.GladstoneDale + y * gF.GladstoneDale);
    if (M)
      M[i] = static_cast<float>(1.0 / ((1.0 - y) / g0.MolarMass + y / gF.MolarMass));
  }
}

void SpeciesConstant(const float* const* Y, const Gas* species, std::size_t nSpecies,
  std::size_t n, Gas balance, float* K, float* M)
{
  // the table's gases are a case of MixtureConstants (typed gases, optional balance)
  if (nSpecies && !species)
    throw Error("species mass fractions: the array or species list is null; pass nSpecies of each.");
  std::vector<GasChoice> choices;
  for (std::size_t s = 0; s < nSpecies; ++s)
    choices.push_back(GasChoice::Table(species[s]));
  const GasChoice rest = GasChoice::Table(balance);
  MixtureConstants(Y, choices.data(), nSpecies, n, &rest, K, M);
}

//------------------------------------------------------------------------------------------------
double IdealGasDensity(double p, double T, double M)
{
  if (NotPositiveFinite(T))
    throw Error("temperature: " + Num(T) + " K is not positive. " + TemperatureHint);
  if (NotPositiveFinite(p))
    throw Error("pressure: " + Num(p) + " Pa is not positive. " + PressureHint);
  if (NotPositiveFinite(M))
    throw Error("molar mass: " + Num(M) + " kg/mol is not positive. Give it in kg/mol (air: "
      "0.0289641).");
  return p * M / (MolarGasConstant * T);
}

void IdealGasDensity(const float* p, const float* T, std::size_t n, ScalarField M, float* rho)
{
  CheckPointers(p, rho, "ideal-gas density");
  CheckPointers(T, rho, "ideal-gas density");
  CheckTemperatureArray(T, n);
  CheckPressureArray(p, n);
  if (M.Array)
  {
    BadPoints b = Scan(M.Array, n, NotPositiveFinite);
    if (b.Count)
      ThrowBad("molar mass", b, n, "are not positive or not finite",
        "Molar mass must be positive, in kg/mol (air: 0.0289641).");
  }
  else if (NotPositiveFinite(M.Value))
    throw Error("molar mass: " + Num(M.Value) +
      " kg/mol is not positive. Give it in kg/mol (air: 0.0289641).");
  for (std::size_t i = 0; i < n; ++i)
    rho[i] = static_cast<float>(
      static_cast<double>(p[i]) * M[i] / (MolarGasConstant * static_cast<double>(T[i])));
}

//------------------------------------------------------------------------------------------------
double SaturationVapourPressure(double T)
{
  if (NotPositiveFinite(T))
    throw Error("temperature: " + Num(T) + " K is not positive. " + TemperatureHint);
  return T >= 273.15 ? SaturationOverWater(T) : SaturationOverIce(T);
}

double EnhancementFactor(double p, double T)
{
  const double t = T - 273.15;
  return 1.00062 + 3.14e-8 * p + 5.6e-7 * t * t;
}

double CiddorCompressibility(double p, double T, double xw)
{
  const double a0 = 1.58123e-6, a1 = -2.9331e-8, a2 = 1.1043e-10;
  const double b0 = 5.707e-6, b1 = -2.051e-8;
  const double c0 = 1.9898e-4, c1 = -2.376e-6;
  const double d = 1.83e-11, e = -0.765e-8;
  const double t = T - 273.15;
  const double pt = p / T;
  return 1.0 - pt * (a0 + a1 * t + a2 * t * t + (b0 + b1 * t) * xw + (c0 + c1 * t) * xw * xw) +
    pt * pt * (d + e * xw * xw);
}

double CiddorIndex(
  double T, double p, double humidity, double wavelength, double co2, HumidityMeasure measure)
{
  CheckWavelength(wavelength);
  if (NotPositiveFinite(T))
    throw Error("temperature: " + Num(T) + " K is not positive. " + TemperatureHint);
  if (NotPositiveFinite(p))
    throw Error("pressure: " + Num(p) + " Pa is not positive. " + PressureHint);
  if (!(humidity >= 0.0 && humidity <= 1.0))
    throw Error("humidity: the " + HumidityName(measure) + " " + Num(humidity) +
      " is outside [0, 1]. Give it as a fraction (50 % is 0.5).");
  if (!(co2 >= 0.0) || !std::isfinite(co2))
    throw Error("CO2: " + Num(co2) + " umol/mol is not a valid concentration. Give it in umol/mol "
      "(ppm by amount; 450 is Ciddor's standard air).");
  const double xw = WaterMoleFraction(T, p, humidity, measure);
  if (!(xw < 1.0))
    throw Error("humidity: the water-vapour mole fraction would be " + Num(xw) + " at " + Num(T) +
      " K and " + Num(p) + " Pa (saturation pressure above the pressure). Lower the humidity.");
  return CiddorUnchecked(T, p, xw, wavelength, co2);
}

void CiddorIndex(const float* T, const float* p, std::size_t n, ScalarField humidity,
  double wavelength, ScalarField co2, float* nMinus1, HumidityMeasure measure)
{
  CheckPointers(T, nMinus1, "Ciddor");
  CheckPointers(p, nMinus1, "Ciddor");
  CheckWavelength(wavelength);
  CheckTemperatureArray(T, n);
  CheckPressureArray(p, n);

  auto badHumidity = [](double h) { return !(h >= 0.0 && h <= 1.0); };
  const std::string humidityTodo = "Give the " + HumidityName(measure) +
    " as a fraction in [0, 1] (50 % is 0.5).";
  if (humidity.Array)
  {
    BadPoints b = Scan(humidity.Array, n, badHumidity);
    if (b.Count)
      ThrowBad("humidity", b, n, "are outside [0, 1] or not finite", humidityTodo);
  }
  else if (badHumidity(humidity.Value))
    throw Error("humidity: the " + HumidityName(measure) + " " + Num(humidity.Value) +
      " is outside [0, 1]. " + humidityTodo);

  auto badCO2 = [](double c) { return !(c >= 0.0) || !std::isfinite(c); };
  const char* co2Todo = "Give CO2 in umol/mol (ppm by amount; 450 is Ciddor's standard air).";
  if (co2.Array)
  {
    BadPoints b = Scan(co2.Array, n, badCO2);
    if (b.Count)
      ThrowBad("CO2", b, n, "are negative or not finite", co2Todo);
  }
  else if (badCO2(co2.Value))
    throw Error("CO2: " + Num(co2.Value) + " umol/mol is not a valid concentration. " + co2Todo);

  // Mole fractions first, so that a bad point stops the run before anything is written.
  BadPoints saturated;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double xw = WaterMoleFraction(T[i], p[i], humidity[i], measure);
    if (!(xw < 1.0))
      saturated.Add(i, xw);
  }
  if (saturated.Count)
    ThrowBad("humidity", saturated, n,
      "have a water-vapour mole fraction of 1 or more (saturation pressure above the pressure)",
      "Lower the humidity there, or check the temperature and pressure units.", "x_w ");

  for (std::size_t i = 0; i < n; ++i)
  {
    const double t = T[i], pp = p[i];
    const double xw = WaterMoleFraction(t, pp, humidity[i], measure);
    nMinus1[i] = static_cast<float>(CiddorUnchecked(t, pp, xw, wavelength, co2[i]));
  }
}

//------------------------------------------------------------------------------------------------
double ToKelvin(double value, TemperatureUnit unit)
{
  switch (unit)
  {
    case TemperatureUnit::Kelvin:
      return value;
    case TemperatureUnit::Celsius:
      return value + 273.15;
  }
  throw Error("temperature unit: " + std::to_string(static_cast<int>(unit)) +
    " is not a unit; use Kelvin (0) or Celsius (1).");
}

double ToPascal(double value, PressureUnit unit)
{
  switch (unit)
  {
    case PressureUnit::Pascal:
      return value;
    case PressureUnit::Kilopascal:
      return value * 1e3;
    case PressureUnit::Atmosphere:
      return value * 101325.0;
    case PressureUnit::Bar:
      return value * 1e5;
  }
  throw Error("pressure unit: " + std::to_string(static_cast<int>(unit)) +
    " is not a unit; use Pascal (0), Kilopascal (1), Atmosphere (2) or Bar (3).");
}

void ToKelvin(const float* in, std::size_t n, TemperatureUnit unit, float* out)
{
  CheckPointers(in, out, "temperature conversion");
  ToKelvin(0.0, unit); // validates the unit
  for (std::size_t i = 0; i < n; ++i)
    out[i] = static_cast<float>(ToKelvin(static_cast<double>(in[i]), unit));
}

void ToPascal(const float* in, std::size_t n, PressureUnit unit, float* out)
{
  CheckPointers(in, out, "pressure conversion");
  ToPascal(0.0, unit); // validates the unit
  for (std::size_t i = 0; i < n; ++i)
    out[i] = static_cast<float>(ToPascal(static_cast<double>(in[i]), unit));
}

void ScaleByReference(const float* in, std::size_t n, double reference, float* out)
{
  CheckPointers(in, out, "reference scaling");
  if (NotPositiveFinite(reference))
    throw Error("reference value: " + Num(reference) +
      " is not a positive number. Give the free-stream (reference) value in SI units: kg/m^3 for "
      "density, K for temperature, Pa for pressure.");
  for (std::size_t i = 0; i < n; ++i)
    out[i] = static_cast<float>(static_cast<double>(in[i]) * reference);
}

//------------------------------------------------------------------------------------------------
// Whole fields
//------------------------------------------------------------------------------------------------
double GasChoice::GladstoneDale() const
{
  if (!this->Custom)
    return GladstoneDaleConstant(this->Preset);
  if (NotPositiveFinite(this->K))
    throw Error("custom gas: the Gladstone-Dale constant " + Num(this->K) +
      " m^3/kg is not positive. Type it in m^3/kg (1 cm^3/g = 1e-3 m^3/kg; air at 632.8 nm: "
      "2.256e-4).");
  return this->K;
}

double GasChoice::MolarMass() const
{
  if (!this->Custom)
    return schlieren::MolarMass(this->Preset);
  if (NotPositiveFinite(this->M))
    throw Error("custom gas: the molar mass " + Num(this->M) +
      " kg/mol is not positive. Type it in kg/mol (air: 0.0289641).");
  return this->M;
}

std::string GasChoice::Label() const
{
  if (!this->Custom)
    return GetGasProperties(this->Preset).Name;
  return "custom gas (K = " + Num(this->K) + " m^3/kg, M = " + Num(this->M) + " kg/mol)";
}

void MixtureConstants(const float* const* Y, const GasChoice* species, std::size_t nSpecies,
  std::size_t n, const GasChoice* balance, float* K, float* M, const std::string* names,
  std::size_t* renormalised)
{
  if (!K)
    throw Error("species mass fractions: the output array K is null; pass an array of n values.");
  if (nSpecies && (!Y || !species))
    throw Error("species mass fractions: the array or species list is null; pass nSpecies of each.");
  if (!balance && nSpecies == 0)
    throw Error("species mass fractions: no species and no balance gas. List at least one species "
                "mass-fraction array, or choose a balance gas.");
  std::vector<double> k(nSpecies), invM(nSpecies);
  std::string list;
  for (std::size_t s = 0; s < nSpecies; ++s)
  {
    const std::string label = names && !names[s].empty()
      ? "'" + names[s] + "' (mass fraction of " + species[s].Label() + ")"
      : "mass fraction of " + species[s].Label() + " (species " + std::to_string(s) + ")";
    list += (s ? ", " : "") + (names && !names[s].empty() ? "'" + names[s] + "'" : species[s].Label());
    if (!Y[s])
      throw Error(label + ": the array is null; pass an array of n values.");
    BadPoints b = Scan(Y[s], n, BadFraction);
    if (b.Count)
      ThrowBad(label, b, n, "are outside [0, 1] or not finite", FractionHint);
    k[s] = species[s].GladstoneDale();
    invM[s] = 1.0 / species[s].MolarMass();
  }
  const double kb = balance ? balance->GladstoneDale() : 0.0;
  const double invMb = balance ? 1.0 / balance->MolarMass() : 0.0;

  constexpr double SumTolerance = 1e-3; // without a balance gas: |sum - 1| allowed, renormalised
  BadPoints above, away;
  std::size_t renorm = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    double sum = 0.0;
    for (std::size_t s = 0; s < nSpecies; ++s)
      sum += ClampFraction(Y[s][i]);
    if (balance && sum > 1.0 + FractionTolerance)
      above.Add(i, sum);
    if (!balance && std::fabs(sum - 1.0) > SumTolerance)
      away.Add(i, sum);
  }
  if (above.Count)
    ThrowBad("mass fractions (" + list + ")", above, n, "have fractions that sum above 1",
      "The listed species must not include the balance gas (" + balance->Label() +
        ") and must sum to at most 1 at every point: renormalise them, or leave one species out "
        "as the balance.",
      "sum ");
  if (away.Count)
    ThrowBad("mass fractions (" + list + ")", away, n,
      "have fractions that do not sum to 1 (within 1e-3)",
      "Without a balance gas the listed species must make up the whole gas: list every species, "
      "or choose a balance gas that takes the rest (1 - sum).",
      "sum ");
  for (std::size_t i = 0; i < n; ++i)
  {
    double sum = 0.0, kk = 0.0, im = 0.0;
    for (std::size_t s = 0; s < nSpecies; ++s)
    {
      const double y = ClampFraction(Y[s][i]);
      sum += y;
      kk += y * k[s];
      im += y * invM[s];
    }
    if (balance)
    {
      const double rest = sum >= 1.0 ? 0.0 : 1.0 - sum;
      kk += rest * kb;
      im += rest * invMb;
    }
    else
    {
      if (std::fabs(sum - 1.0) > FractionTolerance)
        ++renorm;
      kk /= sum;
      im /= sum;
    }
    K[i] = static_cast<float>(kk);
    if (M)
      M[i] = static_cast<float>(1.0 / im);
  }
  if (renormalised)
    *renormalised = renorm;
}

namespace
{
/** "array 'Temp' (temperature)" */
std::string ArrayLabel(const NamedArray& a, const char* role)
{
  return "array '" + (a.Name.empty() ? std::string("(unnamed)") : a.Name) + "' (" + role + ")";
}

const char* ModelName(IndexModel m)
{
  switch (m)
  {
    case IndexModel::Passthrough:
      return "Passthrough";
    case IndexModel::GladstoneDale:
      return "GladstoneDale";
    case IndexModel::GladstoneDaleMixture:
      return "GladstoneDaleMixture";
    case IndexModel::IdealGas:
      return "IdealGas";
    case IndexModel::Ciddor:
      return "Ciddor";
  }
  return "(unknown model)";
}

/**
 * The valid points of `a` converted by `convert` (raw float -> SI double), the invalid ones set to
 * `benign`. Throws if the array is missing or a valid point is NaN/Inf.
 */
template <typename Convert>
std::vector<float> Prepare(const FieldArrays& f, const NamedArray& a, const char* role,
  IndexModel model, Convert convert, float benign)
{
  if (!a.Data)
    throw Error(std::string(ModelName(model)) + " needs a " + role +
      " array, and none was given: choose one among the input's point arrays.");
  const std::size_t n = f.Count;
  BadPoints b;
  for (std::size_t i = 0; i < n; ++i)
    if ((!f.Valid || f.Valid[i]) && !std::isfinite(a.Data[i]))
      b.Add(i, a.Data[i]);
  if (b.Count)
    ThrowBad(ArrayLabel(a, role), b, n, "are NaN or infinite",
      "Fix the data upstream (or remove those points, e.g. with a Threshold filter): the "
      "refractive index needs a finite value everywhere in the flow.");
  std::vector<float> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = (!f.Valid || f.Valid[i]) ? static_cast<float>(convert(static_cast<double>(a.Data[i])))
                                      : benign;
  return out;
}

/** Throws for valid points where `bad` holds (after conversion to SI). */
template <typename Bad>
void CheckSI(const FieldArrays& f, const NamedArray& a, const char* role,
  const std::vector<float>& si, Bad bad, const std::string& problem, const std::string& todo,
  const std::string& unitLabel)
{
  BadPoints b;
  for (std::size_t i = 0; i < f.Count; ++i)
    if ((!f.Valid || f.Valid[i]) && bad(static_cast<double>(si[i])))
      b.Add(i, si[i]);
  if (b.Count)
    ThrowBad(ArrayLabel(a, role), b, f.Count, problem, todo, unitLabel);
}

/** Runs `f`, prefixing the message of an Error with `prefix`. */
template <typename F>
void Prefixed(const std::string& prefix, F f)
{
  try
  {
    f();
  }
  catch (const Error& e)
  {
    throw Error(prefix + e.what());
  }
}
} // namespace

FieldReport ComputeFieldIndex(const FieldArrays& f, const FieldModel& m, float* nMinus1)
{
  if (!nMinus1 && f.Count)
    throw Error("ComputeFieldIndex: the output array is null; pass an array of Count values.");
  const std::size_t n = f.Count;
  FieldReport report;
  for (std::size_t i = 0; i < n; ++i)
    report.ValidPoints += (!f.Valid || f.Valid[i]) ? 1 : 0;
  const IndexModel model = m.Model;
  auto isValid = [&f](std::size_t i) { return !f.Valid || f.Valid[i]; };

  // Unit conversions to SI.
  if (NotPositiveFinite(m.DensityReference) || NotPositiveFinite(m.TemperatureReference) ||
    NotPositiveFinite(m.PressureReference))
    throw Error("reference values: density " + Num(m.DensityReference) + ", temperature " +
      Num(m.TemperatureReference) + ", pressure " + Num(m.PressureReference) +
      "; each must be a positive number (1 for dimensional data; the free-stream value the "
      "solver divided by for non-dimensional data).");
  if (!std::isfinite(m.PressureOffset))
    throw Error("pressure offset: " + Num(m.PressureOffset) + " is not a finite number.");
  const double rhoRef = m.DensityReference, TRef = m.TemperatureReference,
               pRef = m.PressureReference, pOffset = m.PressureOffset;
  const TemperatureUnit TUnit = m.TemperatureUnits;
  const PressureUnit pUnit = m.PressureUnits;
  ToKelvin(0.0, TUnit); // validate the units
  ToPascal(0.0, pUnit);
  auto density = [&](const NamedArray& a) {
    std::vector<float> rho = Prepare(
      f, a, "density", model, [rhoRef](double v) { return rhoRef * v; }, 0.0f);
    CheckSI(f, a, "density", rho, [](double v) { return v < 0.0; }, "are negative",
      "Density must be >= 0 in kg/m^3 after scaling by DensityReference: check the array and "
      "its scaling.",
      "");
    BadPoints zero;
    for (std::size_t i = 0; i < n; ++i)
      if (isValid(i) && rho[i] == 0.0f)
        zero.Add(i, 0.0);
    if (zero.Count)
      report.Warnings.push_back(ArrayLabel(a, "density") + ": " + std::to_string(zero.Count) +
        " of " + std::to_string(n) + " points are 0 (first at index " + std::to_string(zero.First) +
        "), a vacuum where n - 1 = 0. If the flow has no vacuum there, check the array.");
    return rho;
  };
  auto temperature = [&]() {
    std::vector<float> T = Prepare(
      f, f.Temperature, "temperature", model,
      [TRef, TUnit](double v) { return ToKelvin(TRef * v, TUnit); }, 293.15f);
    CheckSI(f, f.Temperature, "temperature", T, NotPositiveFinite,
      "are at or below absolute zero (in K after the unit and reference)",
      std::string(TemperatureHint) + " The filter's TemperatureUnit and TemperatureReference "
                                     "set the conversion.",
      "");
    return T;
  };
  auto pressure = [&]() {
    std::vector<float> p = Prepare(
      f, f.Pressure, "pressure", model,
      [pRef, pOffset, pUnit](double v) { return ToPascal(pRef * v + pOffset, pUnit); }, 101325.0f);
    CheckSI(f, f.Pressure, "pressure", p, NotPositiveFinite,
      "are not positive (in Pa after the unit, reference and offset)",
      std::string(PressureHint) + " For a gauge pressure, set PressureOffset to the operating "
                                  "pressure.",
      "");
    return p;
  };
  // Gladstone-Dale constant (and molar mass) per point from the composition.
  auto composition = [&](std::vector<float>& K, std::vector<float>* M) {
    K.assign(n, 0.0f);
    if (M)
      M->assign(n, 0.0f);
    switch (m.Mixture)
    {
      case Composition::SingleGas:
      {
        const double k = m.SingleGas.GladstoneDale();
        const double mm = m.SingleGas.MolarMass();
        std::fill(K.begin(), K.end(), static_cast<float>(k));
        if (M)
          std::fill(M->begin(), M->end(), static_cast<float>(mm));
        return;
      }
      case Composition::MixtureFraction:
      {
        std::vector<float> frac = Prepare(
          f, f.MixtureFraction, "mixture fraction", model, [](double v) { return v; }, 0.0f);
        Prefixed(ArrayLabel(f.MixtureFraction, "mixture fraction") + ", ", [&] {
          MixtureFractionConstant(
            frac.data(), n, m.Gas0, m.GasF, K.data(), M ? M->data() : nullptr);
        });
        return;
      }
      case Composition::Species:
      {
        const int ns = m.NumberOfSpecies;
        if (ns < 0 || ns > MaxSpecies)
          throw Error("number of species: " + std::to_string(ns) + " is outside 0-" +
            std::to_string(MaxSpecies) + ".");
        std::vector<std::vector<float>> Y(ns);
        std::vector<const float*> ptr(ns);
        std::vector<std::string> names(ns);
        for (int s = 0; s < ns; ++s)
        {
          const std::string role = "mass fraction of " + m.Species[s].Label();
          // Benign value at invalid points: the first species alone (sums to 1 with or without
          // a balance gas).
          Y[s] = Prepare(
            f, f.Species[s], role.c_str(), model, [](double v) { return v; }, s == 0 ? 1.0f : 0.0f);
          ptr[s] = Y[s].data();
          names[s] = f.Species[s].Name.empty() ? "(unnamed)" : f.Species[s].Name;
        }
        std::size_t renormalised = 0;
        MixtureConstants(ptr.data(), m.Species, static_cast<std::size_t>(ns), n,
          m.HasBalance ? &m.Balance : nullptr, K.data(), M ? M->data() : nullptr, names.data(),
          &renormalised);
        if (renormalised)
          report.Warnings.push_back("mass fractions: at " + std::to_string(renormalised) + " of " +
            std::to_string(n) +
            " points they sum to 1 only within 1e-3 and were renormalised (no balance gas).");
        return;
      }
    }
    throw Error("composition: " + std::to_string(static_cast<int>(m.Mixture)) +
      " is not one of SingleGas (0), MixtureFraction (1), Species (2).");
  };

  switch (model)
  {
    case IndexModel::Passthrough:
    {
      const bool isN = m.IndexIsN;
      std::vector<float> v = Prepare(
        f, f.Index, isN ? "refractive index n" : "n - 1", model,
        [isN](double x) { return isN ? x - 1.0 : x; }, 0.0f);
      CheckSI(f, f.Index, isN ? "refractive index n" : "n - 1", v,
        [](double x) { return x <= -1.0; }, "give n <= 0",
        isN ? "The array should hold n (about 1.0003 in air); if it holds n - 1, turn "
              "PassthroughHoldsN off."
            : "The array should hold n - 1 (about 2.7e-4 in air); if it holds n itself, turn "
              "PassthroughHoldsN on.",
        "");
      for (std::size_t i = 0; i < n; ++i)
        if (isValid(i))
          nMinus1[i] = v[i];
      return report;
    }
    case IndexModel::GladstoneDale:
    case IndexModel::GladstoneDaleMixture:
    {
      std::vector<float> rho = density(f.Density);
      std::vector<float> K;
      if (model == IndexModel::GladstoneDale)
        K.assign(n, static_cast<float>(m.SingleGas.GladstoneDale()));
      else
        composition(K, nullptr);
      for (std::size_t i = 0; i < n; ++i)
        if (isValid(i))
          nMinus1[i] = static_cast<float>(static_cast<double>(K[i]) * rho[i]);
      return report;
    }
    case IndexModel::IdealGas:
    {
      std::vector<float> T = temperature();
      std::vector<float> p = pressure();
      std::vector<float> K, M;
      composition(K, &M);
      for (std::size_t i = 0; i < n; ++i)
        if (isValid(i))
        {
          const double rho =
            static_cast<double>(p[i]) * M[i] / (MolarGasConstant * static_cast<double>(T[i]));
          nMinus1[i] = static_cast<float>(static_cast<double>(K[i]) * rho);
        }
      return report;
    }
    case IndexModel::Ciddor:
    {
      std::vector<float> T = temperature();
      std::vector<float> p = pressure();
      std::vector<float> h, c;
      ScalarField humidity = ScalarField::Constant(m.Humidity);
      ScalarField co2 = ScalarField::Constant(m.CO2);
      const char* hRole =
        m.HumidityKind == HumidityMeasure::Relative ? "relative humidity" : "water mole fraction";
      if (f.Humidity.Data)
      {
        h = Prepare(f, f.Humidity, hRole, model, [](double v) { return v; }, 0.0f);
        CheckSI(f, f.Humidity, hRole, h, [](double v) { return !(v >= 0.0 && v <= 1.0); },
          "are outside [0, 1]", "Give the humidity as a fraction in [0, 1] (50 % is 0.5).", "");
        humidity = ScalarField::PerPoint(h.data());
      }
      if (f.CO2.Data)
      {
        c = Prepare(f, f.CO2, "CO2", model, [](double v) { return v; }, 450.0f);
        CheckSI(f, f.CO2, "CO2", c, [](double v) { return v < 0.0; }, "are negative",
          "Give CO2 in umol/mol (ppm by amount; 450 is Ciddor's standard air).", "");
        co2 = ScalarField::PerPoint(c.data());
      }
      std::vector<float> out(n);
      Prefixed("Ciddor (temperature " + ArrayLabel(f.Temperature, "temperature") + ", pressure " +
          ArrayLabel(f.Pressure, "pressure") + "): ",
        [&] {
          CiddorIndex(T.data(), p.data(), n, humidity, m.Wavelength, co2, out.data(),
            m.HumidityKind);
        });
      for (std::size_t i = 0; i < n; ++i)
        if (isValid(i))
          nMinus1[i] = out[i];
      return report;
    }
  }
  throw Error("model: " + std::to_string(static_cast<int>(model)) +
    " is not a model; use Passthrough (0), GladstoneDale (1), GladstoneDaleMixture (2), IdealGas "
    "(3) or Ciddor (4).");
}

//------------------------------------------------------------------------------------------------
void CollectDomainEdge(const int dims[3], const unsigned char* valid, const float* nMinus1,
  const int owned[6], std::vector<float>& values)
{
  if (!valid || !nMinus1)
    return;
  int r[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  if (owned)
    for (int a = 0; a < 3; ++a)
    {
      r[2 * a] = std::max(r[2 * a], owned[2 * a]);
      r[2 * a + 1] = std::min(r[2 * a + 1], owned[2 * a + 1]);
    }
  const std::size_t sy = static_cast<std::size_t>(dims[0]);
  const std::size_t sz = sy * static_cast<std::size_t>(dims[1]);
  for (int k = r[4]; k <= r[5]; ++k)
    for (int j = r[2]; j <= r[3]; ++j)
      for (int i = r[0]; i <= r[1]; ++i)
      {
        const std::size_t id = i + j * sy + k * sz;
        if (!valid[id])
          continue;
        const bool edge = (i > 0 && !valid[id - 1]) || (i + 1 < dims[0] && !valid[id + 1]) ||
          (j > 0 && !valid[id - sy]) || (j + 1 < dims[1] && !valid[id + sy]) ||
          (k > 0 && !valid[id - sz]) || (k + 1 < dims[2] && !valid[id + sz]);
        if (edge)
          values.push_back(nMinus1[id]);
      }
}

double Median(std::vector<float>& values)
{
  if (values.empty())
    return std::numeric_limits<double>::quiet_NaN();
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  const double upper = values[mid];
  if (values.size() % 2)
    return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + mid);
  return 0.5 * (lower + upper);
}

std::size_t FillInvalid(std::size_t n, const unsigned char* valid, double ambient, float* nMinus1)
{
  if (!valid)
    return 0;
  if (!std::isfinite(ambient) || ambient <= -1.0)
    throw Error("ambient n - 1: " + Num(ambient) +
      " is not usable outside the flow domain (it must be finite and above -1). Set the ambient "
      "value to the free stream's n - 1 (air at 20 C, 1 atm: 2.7e-4).");
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (!valid[i])
    {
      nMinus1[i] = static_cast<float>(ambient);
      ++count;
    }
  return count;
}

std::size_t ExtendIntoInvalid(const int dims[3], const unsigned char* valid, float* nMinus1)
{
  if (!valid)
    return 0;
  const std::size_t sy = static_cast<std::size_t>(dims[0]);
  const std::size_t sz = sy * static_cast<std::size_t>(dims[1]);
  const std::size_t n = sz * static_cast<std::size_t>(dims[2]);
  // 2: filled (valid, or an earlier layer), 1: in the current front, 0: not reached yet.
  std::vector<unsigned char> state(n);
  std::size_t nValid = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    state[i] = valid[i] ? 2 : 0;
    nValid += valid[i] ? 1 : 0;
  }
  if (nValid == 0)
    throw Error("no point of the grid lies in the flow domain: there is nothing to extend. Check "
                "the sampling bounds and the input.");
  auto neighbours = [&](std::size_t id, auto visit) {
    const int i = static_cast<int>(id % sy);
    const int j = static_cast<int>((id / sy) % dims[1]);
    const int k = static_cast<int>(id / sz);
    if (i > 0)
      visit(id - 1);
    if (i + 1 < dims[0])
      visit(id + 1);
    if (j > 0)
      visit(id - sy);
    if (j + 1 < dims[1])
      visit(id + sy);
    if (k > 0)
      visit(id - sz);
    if (k + 1 < dims[2])
      visit(id + sz);
  };
  std::vector<std::size_t> front, next;
  for (std::size_t id = 0; id < n; ++id)
    if (state[id] == 0)
    {
      bool touches = false;
      neighbours(id, [&](std::size_t o) { touches = touches || state[o] == 2; });
      if (touches)
      {
        state[id] = 1;
        front.push_back(id);
      }
    }
  std::size_t filled = 0;
  std::vector<float> values;
  while (!front.empty())
  {
    // Values first (from the points filled before this layer), then mark the layer filled.
    values.resize(front.size());
    for (std::size_t f = 0; f < front.size(); ++f)
    {
      double sum = 0.0;
      int count = 0;
      neighbours(front[f], [&](std::size_t o) {
        if (state[o] == 2)
        {
          sum += nMinus1[o];
          ++count;
        }
      });
      values[f] = static_cast<float>(sum / count);
    }
    for (std::size_t f = 0; f < front.size(); ++f)
    {
      nMinus1[front[f]] = values[f];
      state[front[f]] = 2;
    }
    filled += front.size();
    next.clear();
    for (std::size_t id : front)
      neighbours(id, [&](std::size_t o) {
        if (state[o] == 0)
        {
          state[o] = 1;
          next.push_back(o);
        }
      });
    front.swap(next);
  }

  // Smooth the fill into a harmonic continuation: inside the void n - 1 solves Laplace's equation
  // with the flow's values at its edge (the valid points are fixed) and, on the grid's faces, the
  // values of the layer extension (so that a profile along a face, such as a boundary layer
  // against a wall, is carried out unchanged). The layer extension alone leaves ridges where fronts
  // from different parts of the edge meet (inside a body enclosed by flow); the harmonic fill has
  // none. Successive over-relaxation, red-black order (deterministic).
  auto onFace = [&](std::size_t id) {
    const int i = static_cast<int>(id % sy);
    const int j = static_cast<int>((id / sy) % dims[1]);
    const int k = static_cast<int>(id / sz);
    return (dims[0] > 1 && (i == 0 || i == dims[0] - 1)) ||
      (dims[1] > 1 && (j == 0 || j == dims[1] - 1)) || (dims[2] > 1 && (k == 0 || k == dims[2] - 1));
  };
  std::vector<std::size_t> voids;
  voids.reserve(filled);
  float lo = std::numeric_limits<float>::max(), hi = -lo;
  for (std::size_t id = 0; id < n; ++id)
  {
    if (!valid[id] && !onFace(id))
      voids.push_back(id);
    lo = std::min(lo, nMinus1[id]);
    hi = std::max(hi, nMinus1[id]);
  }
  const int longest = std::max(dims[0], std::max(dims[1], dims[2]));
  const double pi = 3.14159265358979323846;
  const double omega = 2.0 / (1.0 + std::sin(pi / std::max(longest, 2)));
  const double tolerance = 1e-5 * std::max(static_cast<double>(hi - lo), 1e-30);
  const int maxSweeps = 4 * longest + 50;
  for (int sweep = 0; sweep < maxSweeps; ++sweep)
  {
    double largest = 0.0;
    for (int colour = 0; colour < 2; ++colour)
      for (std::size_t id : voids)
      {
        const std::size_t i = id % sy, j = (id / sy) % dims[1], k = id / sz;
        if (static_cast<int>((i + j + k) % 2) != colour)
          continue;
        // A point off the faces: both neighbours exist along every axis the grid extends along.
        // An axis one point thick has none (a 2D grid is smoothed in its plane; reading across it
        // read outside the array: issue 48's fuzz, under AddressSanitizer). The sum in the order
        // it had (a 3D grid's fill is unchanged, bit for bit).
        double sum = 0.0;
        int terms = 0;
        if (dims[0] > 1)
        {
          sum += nMinus1[id - 1];
          sum += nMinus1[id + 1];
          terms += 2;
        }
        if (dims[1] > 1)
        {
          sum += nMinus1[id - sy];
          sum += nMinus1[id + sy];
          terms += 2;
        }
        if (dims[2] > 1)
        {
          sum += nMinus1[id - sz];
          sum += nMinus1[id + sz];
          terms += 2;
        }
        if (terms == 0)
          continue;
        const double change = omega * (sum / terms - nMinus1[id]);
        nMinus1[id] = static_cast<float>(nMinus1[id] + change);
        largest = std::max(largest, std::fabs(change));
      }
    if (largest < tolerance)
      break;
  }
  return filled;
}

void AutomaticDimensions(const double bounds[6], int longest, int dims[3])
{
  if (longest < 2)
    throw Error("sampling: " + std::to_string(longest) +
      " points along the longest side is too few; use at least 2 (128 is the default).");
  double size[3], largest = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    size[a] = bounds[2 * a + 1] - bounds[2 * a];
    if (!std::isfinite(size[a]) || size[a] < 0.0)
      throw Error("sampling: the input's bounds (" + Num(bounds[0]) + " " + Num(bounds[1]) + " " +
        Num(bounds[2]) + " " + Num(bounds[3]) + " " + Num(bounds[4]) + " " + Num(bounds[5]) +
        ") are empty or not finite; the input has no points to resample.");
    largest = std::max(largest, size[a]);
  }
  if (!(largest > 0.0))
    throw Error("sampling: the input's bounds have zero size (a single point); nothing to resample.");
  const double h = largest / (longest - 1);
  for (int a = 0; a < 3; ++a)
  {
    if (size[a] <= 1e-12 * largest)
      dims[a] = 1;
    else
      dims[a] = std::max(2, static_cast<int>(std::lround(size[a] / h)) + 1);
  }
}

} // namespace schlieren
