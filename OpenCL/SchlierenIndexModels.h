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
#include <vector>

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

//------------------------------------------------------------------------------------------------
// Whole fields: what the RefractiveIndex filter hands over (named arrays, a model, units)
//------------------------------------------------------------------------------------------------

/** The model that turns CFD fields into n - 1 (the filter's `Model`). */
enum class IndexModel : int
{
  Passthrough = 0,          ///< the array is n - 1 (or n, see FieldModel::IndexIsN)
  GladstoneDale = 1,        ///< n - 1 = K rho, one gas
  GladstoneDaleMixture = 2, ///< n - 1 = K(Y) rho, K weighted by mass fraction
  IdealGas = 3,             ///< rho = p M / (R T), then Gladstone-Dale
  Ciddor = 4                ///< moist air from T, p, humidity, CO2 and wavelength
};

/** What the gas is made of (GladstoneDaleMixture and IdealGas). */
enum class Composition : int
{
  SingleGas = 0,       ///< one gas (FieldModel::SingleGas)
  MixtureFraction = 1, ///< a mixture-fraction array: the mass fraction of GasF, the rest Gas0
  Species = 2          ///< up to MaxSpecies mass-fraction arrays, plus an optional balance gas
};

/** The most species mass-fraction arrays a field can have. */
constexpr int MaxSpecies = 4;

/** A gas: a row of the table, or constants typed by the user (for a gas the table lacks). */
struct GasChoice
{
  bool Custom = false;
  Gas Preset = Gas::Air;
  double K = 0.0; ///< Custom only: Gladstone-Dale constant, m^3/kg
  double M = 0.0; ///< Custom only: molar mass, kg/mol

  static GasChoice Table(Gas g)
  {
    GasChoice c;
    c.Preset = g;
    return c;
  }
  static GasChoice Typed(double k, double m)
  {
    GasChoice c;
    c.Custom = true;
    c.K = k;
    c.M = m;
    return c;
  }
  /** K, m^3/kg. Throws Error if a typed K is not positive and finite. */
  double GladstoneDale() const;
  /** M, kg/mol. Throws Error if a typed M is not positive and finite. */
  double MolarMass() const;
  /** "He", or "custom gas (K = ... m^3/kg, M = ... kg/mol)". */
  std::string Label() const;
};

/**
 * The model and its parameters. Units of the input arrays, to SI:
 *   density  rho = DensityReference * value                       (kg/m^3)
 *   T        = ToKelvin(TemperatureReference * value, TemperatureUnits)
 *   p        = ToPascal(PressureReference * value + PressureOffset, PressureUnits)
 * The references are 1 for dimensional data; for non-dimensional CFD output they are the
 * free-stream (reference) values the solver divided by, in the unit chosen (PLOT3D: rho_inf for
 * density, T_inf for temperature and rho_inf a_inf^2 = gamma p_inf for pressure). PressureOffset
 * turns a gauge pressure into an absolute one (the solver's operating pressure, in PressureUnits).
 */
struct FieldModel
{
  IndexModel Model = IndexModel::Passthrough;
  bool IndexIsN = false; ///< Passthrough: the array holds n (n - 1 = value - 1), not n - 1

  GasChoice SingleGas = GasChoice::Table(Gas::Air); ///< GladstoneDale; IdealGas with SingleGas
  Composition Mixture = Composition::MixtureFraction; ///< GladstoneDaleMixture, IdealGas
  Gas Gas0 = Gas::Air;    ///< the gas at mixture fraction 0
  Gas GasF = Gas::Helium; ///< the gas at mixture fraction 1
  int NumberOfSpecies = 0;
  GasChoice Species[MaxSpecies];
  bool HasBalance = true; ///< false: the species must sum to 1 (within 1e-3; renormalised)
  GasChoice Balance = GasChoice::Table(Gas::Air);

  double DensityReference = 1.0;
  double TemperatureReference = 1.0;
  TemperatureUnit TemperatureUnits = TemperatureUnit::Kelvin;
  double PressureReference = 1.0;
  double PressureOffset = 0.0;
  PressureUnit PressureUnits = PressureUnit::Pascal;

  double Humidity = 0.0; ///< Ciddor, used where FieldArrays::Humidity has no array
  HumidityMeasure HumidityKind = HumidityMeasure::Relative;
  double CO2 = 450.0;        ///< Ciddor, umol/mol, used where FieldArrays::CO2 has no array
  double Wavelength = 632.8; ///< Ciddor, nm
};

/** One input array, float, one value per point; its name is for messages. */
struct NamedArray
{
  const float* Data = nullptr;
  std::string Name;
};

/**
 * The arrays of a field, each `Count` points long; only those the model needs must be set.
 * Points with Valid[i] == 0 (outside the flow domain, blanked) are neither checked nor computed:
 * their n - 1 is left as it was, for FillInvalid.
 */
struct FieldArrays
{
  std::size_t Count = 0;
  NamedArray Index;       ///< Passthrough
  NamedArray Density;     ///< GladstoneDale, GladstoneDaleMixture
  NamedArray Temperature; ///< IdealGas, Ciddor
  NamedArray Pressure;    ///< IdealGas, Ciddor
  NamedArray MixtureFraction;
  NamedArray Species[MaxSpecies];
  NamedArray Humidity; ///< Ciddor, optional (else FieldModel::Humidity)
  NamedArray CO2;      ///< Ciddor, optional (else FieldModel::CO2)
  const unsigned char* Valid = nullptr;
};

/** What ComputeFieldIndex found besides errors. */
struct FieldReport
{
  std::size_t ValidPoints = 0;
  std::vector<std::string> Warnings; ///< e.g. points of zero density, renormalised mass fractions
};

/**
 * n - 1 of a whole field by `model`: unit conversion, the model, and checks whose messages name
 * the input array (its name and role), the count of bad points (of the valid ones), the first bad
 * point and value, and what to do: a missing array the model needs; NaN/Inf; temperature or
 * pressure <= 0; density < 0; mass fractions outside [0, 1] or summing above 1 (or, without a
 * balance gas, away from 1 by more than 1e-3). Density 0 (vacuum) and renormalised mass fractions
 * give warnings. Writes the valid points of `nMinus1` (Count floats). Throws Error.
 */
FieldReport ComputeFieldIndex(const FieldArrays& arrays, const FieldModel& model, float* nMinus1);

/**
 * Gladstone-Dale constant (m^3/kg) and molar mass (kg/mol) per point of a mixture given by
 * species mass fractions (Y[s][i] for the gas species[s]) and an optional balance gas that takes
 * 1 - sum Y (null: none; the species must then sum to 1 within 1e-3 and are renormalised).
 * Fractions outside [0, 1] (beyond 1e-6) or summing above 1 + 1e-6 throw Error; `names[s]` names
 * the arrays in messages (null: "mass fraction of <gas>"). `M` may be null. `renormalised`
 * (optional) receives the number of points whose sum differed from 1 by more than 1e-6.
 */
void MixtureConstants(const float* const* Y, const GasChoice* species, std::size_t nSpecies,
  std::size_t n, const GasChoice* balance, float* K, float* M, const std::string* names = nullptr,
  std::size_t* renormalised = nullptr);

//------------------------------------------------------------------------------------------------
// Points outside the flow domain, and the sampling grid
//------------------------------------------------------------------------------------------------

/**
 * Values of n - 1 at the edge of the flow domain: the valid points of a grid (`dims`, x fastest)
 * that have an invalid neighbour along x, y or z. Only points inside `owned` (index ranges
 * i0 i1 j0 j1 k0 k1 into the grid, inclusive; null: all) are collected, so that pieces that
 * overlap can share the work exactly. Appends to `values`.
 */
void CollectDomainEdge(const int dims[3], const unsigned char* valid, const float* nMinus1,
  const int owned[6], std::vector<float>& values);

/** The median of `values` (reordered; the mean of the two middle ones if even); NaN if empty. */
double Median(std::vector<float>& values);

/**
 * Sets n - 1 = ambient at every point with valid[i] == 0; returns how many. Throws Error if the
 * ambient value is not finite or n would be <= 0. (The ambient is never 0 by default: a jump from
 * the flow to vacuum at the domain's edge would draw a false shock there.)
 */
std::size_t FillInvalid(std::size_t n, const unsigned char* valid, double ambient, float* nMinus1);

/**
 * Fills every invalid point of a grid (`dims`, x fastest) with a smooth continuation of the flow.
 * First the flow is carried outward layer by layer (each newly reached point the mean of its
 * neighbours filled before it: a zero-gradient extension normal to the domain's edge). Then the
 * inside of the void (off the grid's faces, which keep that extension) is made harmonic: n - 1
 * solves Laplace's equation there with the flow's values at the void's edge (the valid points are
 * not changed), by successive over-relaxation (red-black, to 1e-5 of the field's range). Along any
 * ray the index then continues across the domain's edge without a jump, whatever the flow does
 * there (a boundary layer, a shock leaving the domain), and a body enclosed by flow gets no ridge
 * inside. Returns the number of points filled. Throws Error if no point is valid.
 */
std::size_t ExtendIntoInvalid(const int dims[3], const unsigned char* valid, float* nMinus1);

/**
 * Sampling dimensions for a box (`bounds`: xmin xmax ymin ymax zmin zmax): `longest` points along
 * its longest side and about the same spacing along the others (rounded, at least 2 along a side
 * of non-zero length, 1 along a flat one). Throws Error for empty or non-finite bounds, a box of
 * zero size, or longest < 2.
 */
void AutomaticDimensions(const double bounds[6], int longest, int dims[3]);

} // namespace schlieren

#endif
