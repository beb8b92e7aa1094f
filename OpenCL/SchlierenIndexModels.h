// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenIndexModels.h
 * @brief Refractive index n - 1 from CFD fields (the paper's section 4.1), VTK-free.
 *
 * Plain arrays in (float, one value per point), n - 1 out. Arithmetic is done in double; only the
 * stored result is rounded to float. Every function checks its inputs and throws schlieren::Error
 * (SchlierenEngine.h) with a message that names the input, how many points are bad, the first bad
 * index and value, and what to do. Reference values: ../shared/ORACLES.md, section "Refractive index".
 *
 * Units: SI throughout (kg/m^3, Pa, K, kg/mol, m^3/kg) except where a name says otherwise
 * (wavelength in nm, CO2 in umol/mol). The unit helpers at the end convert CFD output to SI.
 *
 * The models:
 *  - Gladstone-Dale: n - 1 = K rho. K depends on the gas and (weakly) on the wavelength; the table
 *    below is for 632.8 nm (He-Ne). For a mixture, K = sum_i Y_i K_i (mass fractions Y_i): the
 *    paper's eq. 2 for air/helium with mixture fraction f is K = (1 - f) K_air + f K_He.
 *  - Ideal gas, where the data has temperature and pressure but no density: rho = p M / (R T),
 *    1/M = sum_i Y_i / M_i, R = 8.314462618 J/(mol K).
 *  - Ciddor (1996) for (moist) air from temperature, pressure, humidity, CO2 and wavelength, in the
 *    form of NIST's Engineering Metrology Toolbox "Refractive Index of Air" calculator (Stone and
 *    Zimmerman, Appendix A): dry-air and water-vapour refractivities are added linearly,
 *    n - 1 = (rho_a / rho_axs)(n_axs - 1) + (rho_w / rho_ws)(n_ws - 1).
 *    Valid 300-1700 nm (outside: Error). NIST quotes an uncertainty of a few parts in 1e8 in n
 *    for -40..100 C, 10..140 kPa, 0..100 % relative humidity and 0..2000 umol/mol CO2; outside
 *    that range the result is an extrapolation (no error is raised for it).
 */
#ifndef SchlierenIndexModels_h
#define SchlierenIndexModels_h

#include <cstddef>
#include <string>

namespace schlieren
{

/** Molar gas constant, J/(mol K) (CODATA 2018, exact). Used by the ideal-gas density. */
constexpr double MolarGasConstant = 8.314462618;

//------------------------------------------------------------------------------------------------
// Gases
//------------------------------------------------------------------------------------------------

/** The gases with a tabulated Gladstone-Dale constant. */
enum class Gas : int
{
  Air = 0,
  Helium,
  Nitrogen,
  Oxygen,
  Argon,
  CarbonDioxide,
  Hydrogen,
  Water, ///< water vapour
  Methane,
  CarbonMonoxide,
  NumberOfGases
};

/** Properties of one gas. */
struct GasProperties
{
  Gas Id;
  const char* Name;    ///< the name ParseGas prints ("Air", "He", "N2", ...)
  const char* Alias;   ///< a second accepted name ("Helium", "Nitrogen", ...)
  double GladstoneDale; ///< K at 632.8 nm, m^3/kg (table value in cm^3/g times 1e-3)
  double MolarMass;     ///< kg/mol
};

/**
 * The table: K at 632.8 nm in cm^3/g (x 1e-3 for m^3/kg) and molar mass in g/mol (x 1e-3 for kg/mol):
 * Air 0.2256 / 28.9641, He 0.1954 / 4.002602, N2 0.2381 / 28.0134, O2 0.1888 / 31.9988,
 * Ar 0.1576 / 39.948, CO2 0.2265 / 44.0095, H2 1.5395 / 2.01588, H2O (vapour) 0.3127 / 18.01528,
 * CH4 0.617 / 16.0425, CO 0.268 / 28.0101 (the K of CH4 and CO are known to about 1 %).
 * Throws Error for Gas::NumberOfGases or an out-of-range value.
 */
const GasProperties& GetGasProperties(Gas gas);

/** Gladstone-Dale constant of `gas` at 632.8 nm, m^3/kg. */
double GladstoneDaleConstant(Gas gas);

/** Molar mass of `gas`, kg/mol. */
double MolarMass(Gas gas);

/**
 * The gas with this name, case-insensitive: the short name or the alias of the table ("Air",
 * "He"/"Helium", "N2"/"Nitrogen", "O2"/"Oxygen", "Ar"/"Argon", "CO2"/"CarbonDioxide",
 * "H2"/"Hydrogen", "H2O"/"Water", "CH4"/"Methane", "CO"/"CarbonMonoxide").
 * Throws Error listing the valid names if there is none.
 */
Gas ParseGas(const std::string& name);

/** The valid gas names, for messages and UIs: "Air, He (Helium), N2 (Nitrogen), ...". */
std::string GasNames();

//------------------------------------------------------------------------------------------------
// Gladstone-Dale and mixtures
//------------------------------------------------------------------------------------------------

/**
 * n - 1 = K rho at each of `n` points. `rho` in kg/m^3, `K` in m^3/kg (e.g. GladstoneDaleConstant).
 * `nMinus1` may alias `rho`. Throws Error if K is not finite or not positive, or if any density is
 * negative or not finite (message: "density", count, first index and value).
 */
void GladstoneDale(const float* rho, std::size_t n, double K, float* nMinus1);

/** The same with a K per point (e.g. from MixtureFractionConstant or SpeciesConstant). */
void GladstoneDale(const float* rho, const float* K, std::size_t n, float* nMinus1);

/**
 * Mass-fraction-weighted Gladstone-Dale constant of a mixture, m^3/kg:
 * K = sum_i Y_i K_i + (1 - sum_i Y_i) K_balance.
 * `species[i]` has mass fraction `Y[i]` (i < count); the balance gas takes the rest.
 * Each Y must be in [0, 1] and their sum at most 1 (tolerance 1e-6), else Error.
 */
double MixtureConstant(const Gas* species, const double* Y, std::size_t count, Gas balance);

/** Molar mass of the same mixture, kg/mol: 1/M = sum_i Y_i / M_i + (1 - sum_i Y_i) / M_balance. */
double MixtureMolarMass(const Gas* species, const double* Y, std::size_t count, Gas balance);

/**
 * Two-gas mixture by a mixture fraction (the paper's eq. 2): `f` is the mass fraction of `gasF`,
 * the rest is `gas0`; for the paper's air/helium case gas0 = Air, gasF = Helium.
 * Writes K = (1 - f) K_0 + f K_F (m^3/kg) into `K` and, if `M` is not null, the molar mass
 * 1/M = (1 - f)/M_0 + f/M_F (kg/mol) into `M`. Values within 1e-6 outside [0, 1] are clamped;
 * others (and NaN) throw Error ("mixture fraction", count, first index and value).
 */
void MixtureFractionConstant(
  const float* f, std::size_t n, Gas gas0, Gas gasF, float* K, float* M = nullptr);

/**
 * N species by mass-fraction arrays plus a balance gas that fills 1 - sum Y (e.g. N2 or air).
 * `Y[s]` is the array of species `species[s]` (s < nSpecies), each `n` points long.
 * Writes K (m^3/kg) and, if `M` is not null, the molar mass (kg/mol) per point.
 * A fraction outside [0, 1] or a sum above 1 (tolerance 1e-6) throws Error naming the species,
 * the count and the first bad point; a sum below 1 is filled by the balance gas.
 */
void SpeciesConstant(const float* const* Y, const Gas* species, std::size_t nSpecies,
  std::size_t n, Gas balance, float* K, float* M = nullptr);

//------------------------------------------------------------------------------------------------
// Ideal gas
//------------------------------------------------------------------------------------------------

/** rho = p M / (R T): p in Pa, T in K, M in kg/mol, rho in kg/m^3. Throws Error if any is <= 0. */
double IdealGasDensity(double p, double T, double M);

/**
 * An input that is either one value for all points (Array == nullptr) or one value per point.
 * Used where a CFD file may or may not carry a field (humidity, CO2, molar mass).
 */
struct ScalarField
{
  const float* Array = nullptr;
  double Value = 0.0;

  static ScalarField Constant(double v)
  {
    ScalarField s;
    s.Value = v;
    return s;
  }
  static ScalarField PerPoint(const float* a)
  {
    ScalarField s;
    s.Array = a;
    return s;
  }
  double operator[](std::size_t i) const { return this->Array ? this->Array[i] : this->Value; }
};

/**
 * Ideal-gas density at each of `n` points: rho = p M / (R T). `p` in Pa, `T` in K, molar mass `M`
 * in kg/mol (constant, e.g. MolarMass(Gas::Air), or per point, e.g. from SpeciesConstant).
 * Throws Error naming "temperature", "pressure" or "molar mass" with the count of points that are
 * <= 0 or not finite, the first index and value, and a hint about units.
 */
void IdealGasDensity(
  const float* p, const float* T, std::size_t n, ScalarField M, float* rho);

//------------------------------------------------------------------------------------------------
// Ciddor (1996), NIST form
//------------------------------------------------------------------------------------------------

/** How a humidity input is given. */
enum class HumidityMeasure : int
{
  Relative = 0,     ///< relative humidity h in [0, 1] (not percent): x_w = f h p_sv / p
  MoleFraction = 1  ///< water-vapour mole fraction x_w in [0, 1)
};

/**
 * Saturation vapour pressure, Pa, at temperature T (K). At or above 273.15 K: the IAPWS-IF97
 * saturation equation (Wagner and Pruss form, as used by NIST); below: IAPWS sublimation
 * pressure over ice, 611.657 exp(A1 (1 - theta^-1.5) + A2 (1 - theta^-1.25)), theta = T/273.16.
 */
double SaturationVapourPressure(double T);

/** Enhancement factor of water vapour in air: f = 1.00062 + 3.14e-8 p + 5.6e-7 t^2 (p Pa, t C). */
double EnhancementFactor(double p, double T);

/**
 * Compressibility of moist air (Ciddor 1996 / BIPM 1981-91): p Pa, T K, x_w mole fraction:
 * Z = 1 - (p/T)[a0 + a1 t + a2 t^2 + (b0 + b1 t) x_w + (c0 + c1 t) x_w^2] + (p/T)^2 (d + e x_w^2).
 */
double CiddorCompressibility(double p, double T, double xw);

/**
 * n - 1 of moist air by Ciddor (1996), NIST form. T in K, p in Pa, `humidity` as `measure` says
 * (relative humidity 0-1 by default), `co2` in umol/mol (450 is Ciddor's standard air),
 * `wavelength` the vacuum wavelength in nm, 300-1700.
 *
 * Steps: sigma = 1/lambda (um^-1); x_w = f h p_sv / p; M_a = 0.0289635 + 1.2011e-8 (x_c - 400);
 * n_axs - 1 = 1e-8 [5792105/(238.0185 - sigma^2) + 167917/(57.362 - sigma^2)] [1 + 0.534e-6 (x_c - 450)];
 * n_ws - 1 = 1.022e-8 (295.235 + 2.6422 sigma^2 - 0.032380 sigma^4 + 0.004028 sigma^6);
 * rho_axs = p0 M_a / (Z_a R' T0) at 15 C, 101325 Pa, dry (Z_a from the same formula);
 * rho_ws = 0.00985938 kg/m^3 (pure vapour at 20 C, 1333 Pa, NIST's value);
 * rho_a = p M_a (1 - x_w) / (Z R' T), rho_w = p M_w x_w / (Z R' T), M_w = 0.018015 kg/mol,
 * R' = 8.314472 J/(mol K) as in NIST's calculator (it cancels in the dry term).
 *
 * Throws Error if T or p is not positive, humidity is outside [0, 1] (or x_w >= 1), CO2 is
 * negative, or the wavelength is outside 300-1700 nm.
 */
double CiddorIndex(double T, double p, double humidity, double wavelength, double co2 = 450.0,
  HumidityMeasure measure = HumidityMeasure::Relative);

/**
 * CiddorIndex at each of `n` points (T K, p Pa per point; humidity and CO2 constant or per point),
 * into `nMinus1`. Throws Error naming the array ("temperature", "pressure", "humidity", "CO2"),
 * the count of bad points, the first index and value.
 */
void CiddorIndex(const float* T, const float* p, std::size_t n, ScalarField humidity,
  double wavelength, ScalarField co2, float* nMinus1,
  HumidityMeasure measure = HumidityMeasure::Relative);

//------------------------------------------------------------------------------------------------
// Units of CFD data
//------------------------------------------------------------------------------------------------

enum class TemperatureUnit : int
{
  Kelvin = 0,
  Celsius = 1 ///< K = C + 273.15
};

enum class PressureUnit : int
{
  Pascal = 0,
  Kilopascal = 1, ///< 1 kPa = 1000 Pa
  Atmosphere = 2, ///< 1 atm = 101325 Pa
  Bar = 3         ///< 1 bar = 100000 Pa
};

/** One temperature in `unit` to kelvin. */
double ToKelvin(double value, TemperatureUnit unit);

/** One pressure in `unit` to pascal. */
double ToPascal(double value, PressureUnit unit);

/** Converts `n` temperatures in `unit` to kelvin, `out` may alias `in`. */
void ToKelvin(const float* in, std::size_t n, TemperatureUnit unit, float* out);

/** Converts `n` pressures in `unit` to pascal, `out` may alias `in`. */
void ToPascal(const float* in, std::size_t n, PressureUnit unit, float* out);

/**
 * Non-dimensional CFD output to SI by its reference value: out = in * reference. For a solver that
 * writes rho/rho_inf, T/T_inf or p/p_inf, pass rho_inf (kg/m^3), T_inf (K) or p_inf (Pa); for a
 * pressure scaled by rho_inf U_inf^2, pass rho_inf U_inf^2 (Pa). `out` may alias `in`.
 * Throws Error if the reference is not finite or not positive.
 */
void ScaleByReference(const float* in, std::size_t n, double reference, float* out);

} // namespace schlieren

#endif
