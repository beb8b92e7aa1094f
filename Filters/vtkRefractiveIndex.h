// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkRefractiveIndex
 * @brief   refractive index n - 1 and its gradient from CFD fields, on an image grid
 *
 * vtkRefractiveIndex turns what a CFD code writes (density, or temperature and pressure, or
 * species) into the refractive index that the schlieren tracer needs, by a Model (the physics is
 * schlieren::ComputeFieldIndex, SchlierenIndexModels.h; units SI):
 *
 * - PASSTHROUGH (0): the input array is n - 1, or n itself with PassthroughHoldsN on;
 * - GLADSTONE_DALE (1): the input array is the density rho; n - 1 = K rho, K of Gas (a row of the
 *   table at 632.8 nm, or CUSTOM_GAS: GladstoneDaleConstant);
 * - GLADSTONE_DALE_MIXTURE (2): the input array is the density; K = sum_i Y_i K_i by mass fraction,
 *   from a mixture-fraction array between MixtureGas0 and MixtureGas1 (default air and helium, the
 *   paper's eq. 2) or from up to 4 species mass-fraction arrays plus a BalanceGas
 *   (MixtureComposition);
 * - IDEAL_GAS (3): temperature and pressure arrays, rho = p M / (R T) with M (and K) of Gas, of a
 *   mixture fraction or of the species (IdealGasComposition), then Gladstone-Dale;
 * - CIDDOR (4): moist air from temperature and pressure, relative humidity (or water mole
 *   fraction; constant or an array), CO2 (constant or an array, umol/mol) and Wavelength (nm,
 *   300-1700), Ciddor (1996) in NIST's form.
 *
 * Units: density = DensityReference x value (kg/m^3); temperature = TemperatureReference x value in
 * TemperatureUnit; pressure = PressureReference x value + PressureOffset in PressureUnit. The
 * references are 1 for dimensional data and the free-stream values for non-dimensional data
 * (PLOT3D: rho_inf, T_inf and rho_inf a_inf^2 = gamma p_inf); PressureOffset makes a gauge
 * pressure absolute.
 *
 * Arrays are chosen with SetInputArrayToProcess (point data), by index: 0 the input array (n - 1
 * or n for Passthrough, the density for the Gladstone-Dale models; default the active scalars),
 * 1 temperature, 2 pressure, 3 mixture fraction, 4-7 the species 1-4, 8 humidity, 9 CO2. A model
 * reads only the arrays it needs; a missing one is an error that lists the arrays present.
 *
 * Input: a vtkImageData is used on its own grid. Any other data set or composite data set
 * (unstructured, curvilinear, multiblock such as PLOT3D's, blocks of images) is resampled onto an
 * image grid by the engine's cell sampler (SchlierenResample.h): SamplingDimensions points (0 0 0, the default: AutomaticDimension
 * points along the longest side of the bounds and the same spacing along the others) over
 * SamplingBounds (with UseSamplingBounds) or the input's bounds. That grid is set when the
 * pipeline information is updated (the filter then updates its input once to learn its bounds,
 * unless both the dimensions and the bounds are given) and stays fixed across time steps.
 *
 * Points outside the flow domain (where the sampler found no cell, or an image's
 * vtkValidPointMask is 0, or hidden points) get an ambient n - 1, never 0, since a jump to vacuum
 * would draw a false shock at the domain's edge. AmbientMode EXTEND (default): the flow's n - 1 is
 * carried outward from the domain's edge, layer by layer (schlieren::ExtendIntoInvalid: a
 * zero-gradient extension, as at a CFD outflow boundary), so that no ray sees a jump where the
 * domain ends, even where the flow varies along the edge (an inflow boundary layer, a shock
 * leaving the domain); it needs no reference conditions and works for every model.
 * DOMAIN_EDGE_MEDIAN: one value, the median n - 1 over the valid points next to an invalid one.
 * AMBIENT_VALUE: AmbientValue as typed (e.g. K rho_inf). A constant leaves a jump wherever the
 * edge's values differ from it: where a boundary layer lies along the grid's outer boundary (the
 * blunt fin's inflow, docs/CFD.md), it draws that boundary as a false edge. The constant used is
 * in the field data `ambient_n_minus_1`.
 *
 * Solid bodies (see BodyFromGrid): the output's point array `solid` (unsigned char) marks the
 * points in a body, from the grid's enclosed holes, a SolidArray or a closed surface on input
 * port 1; SchlierenImage stops the light there.
 *
 * The output is always a vtkImageData with the point arrays `n_minus_1` (float, the active
 * scalars) and `grad_n` (float, 3 components, per world unit: central differences, one-sided at
 * the borders; schlieren::ComputeGradient), the input's (or the resampled) point arrays and, where
 * points were invalid, `vtkValidPointMask`. Field data: `ambient_n_minus_1`,
 * `valid_point_fraction`. NaN/Inf, temperature or pressure <= 0, negative density, mass fractions
 * outside [0, 1] or not summing to 1, or n <= 0 anywhere in the flow is an error that names the
 * array, the number of points and what to do; zero density is a warning.
 *
 * Under MPI an image input is computed piecewise (each rank asks its input for one more point on
 * every side of its piece, so that the central differences at the piece borders are those of the
 * whole volume). A resampled input is probed on every rank against its own piece; the arrays the
 * model reads (and the mask) are summed over the ranks, and each rank keeps its piece of the grid.
 *
 * @warning Under MPI a resampled output carries only the arrays the model reads, not every input
 * array. The grid of a resampled input ignores the input's direction and time-varying bounds.
 *
 * @sa vtkRefractiveScene vtkSchlierenImage vtkResampleToImage
 */
#ifndef vtkRefractiveIndex_h
#define vtkRefractiveIndex_h

#include "SchlierenFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include "vtkSmartPointer.h" // for vtkSmartPointer

#include <memory> // for std::shared_ptr
#include <set>    // for std::set
#include <string> // for std::string
#include <vector> // for std::vector

class vtkFieldData;
class vtkImageData;
namespace schlieren
{
class Parallel; // OpenCL/SchlierenParallel.h: the one interface to the ranks
struct SymmetryPlan; // OpenCL/SchlierenSymmetry.h: a symmetric input's grid and samples
class TimeStepCache; // SchlierenTimeCache.h: outputs kept per time step
}

class SCHLIERENFILTERS_EXPORT vtkRefractiveIndex : public vtkImageAlgorithm
{
public:
  static vtkRefractiveIndex* New();
  vtkTypeMacro(vtkRefractiveIndex, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** How the input arrays become n - 1. */
  enum ModelType
  {
    AUTOMATIC = -1,             ///< chosen in RequestData from the arrays present (see SetModel)
    PASSTHROUGH = 0,            ///< the array is n - 1 (or n)
    GLADSTONE_DALE = 1,         ///< the array is the density; n - 1 = K rho
    GLADSTONE_DALE_MIXTURE = 2, ///< the density, K by mass fraction
    IDEAL_GAS = 3,              ///< temperature and pressure; rho = p M / (R T)
    CIDDOR = 4                  ///< moist air from temperature, pressure, humidity, CO2
  };

  /** The input arrays, by their SetInputArrayToProcess index. */
  enum InputArrayIndex
  {
    INPUT_ARRAY = 0, ///< n - 1 or n (Passthrough); density (Gladstone-Dale models)
    TEMPERATURE_ARRAY = 1,
    PRESSURE_ARRAY = 2,
    MIXTURE_FRACTION_ARRAY = 3,
    SPECIES_ARRAY = 4, ///< 4, 5, 6, 7: species 1-4
    HUMIDITY_ARRAY = 8,
    CO2_ARRAY = 9
  };

  /** Gases: the table of SchlierenIndexModels.h (632.8 nm), or typed constants. */
  enum GasType
  {
    NO_GAS = -2,     ///< BalanceGas only: no balance, the species sum to 1
    CUSTOM_GAS = -1, ///< the typed Gladstone-Dale constant and molar mass
    AIR = 0,
    HELIUM,
    NITROGEN,
    OXYGEN,
    ARGON,
    CARBON_DIOXIDE,
    HYDROGEN,
    WATER,
    METHANE,
    CARBON_MONOXIDE
  };

  /** What the gas is made of (GladstoneDaleMixture, IdealGas). */
  enum CompositionType
  {
    SINGLE_GAS = 0,
    MIXTURE_FRACTION = 1,
    SPECIES = 2
  };

  enum TemperatureUnitType
  {
    KELVIN = 0,
    CELSIUS = 1
  };

  enum PressureUnitType
  {
    PASCAL = 0,
    KILOPASCAL = 1,
    ATMOSPHERE = 2,
    BAR = 3
  };

  enum HumidityMeasureType
  {
    RELATIVE_HUMIDITY = 0,
    WATER_MOLE_FRACTION = 1
  };

  enum AmbientModeType
  {
    EXTEND = 0,             ///< the flow's n - 1 carried outward from the domain's edge
    DOMAIN_EDGE_MEDIAN = 1, ///< one value: the median n - 1 of the valid points next to invalid ones
    AMBIENT_VALUE = 2       ///< one value: AmbientValue
  };

  /** How a 2D result is made into the 3D volume that is traced. */
  enum SymmetryType
  {
    NO_SYMMETRY = 0, ///< the input is a volume (a 2D input is an error that names the others)
    PLANAR = 1,      ///< a 2D flow extruded across its plane over Span
    AXISYMMETRIC = 2 ///< an r-z half plane revolved about SymmetryAxis
  };

  ///@{
  /**
   * The model (a ModelType). Default AUTOMATIC: resolved in RequestData from the arrays' names
   * (case-insensitive). An InputArray chosen by name decides: a name of n - 1 (n_minus_1,
   * refractivity) gives PASSTHROUGH, of n (n, refractive_index) PASSTHROUGH with
   * PassthroughHoldsN, of a density (density, rho, dens) GLADSTONE_DALE, of a temperature or a
   * pressure IDEAL_GAS; any other chosen name PASSTHROUGH (whose range check then stops a field
   * that is not n - 1). With InputArray left automatic, the first of: an n - 1 array
   * (PASSTHROUGH), a density (GLADSTONE_DALE with Gas, air by default), a temperature
   * (temperature, temp, t) and a pressure (pressure, pres, p) (IDEAL_GAS), an n array; none of
   * them is an error that lists the arrays. The choice is reported as text and in the field data
   * `index_model` (see GetModelInUse).
   */
  vtkSetMacro(Model, int);
  vtkGetMacro(Model, int);
  void SetModelToAutomatic() { this->SetModel(AUTOMATIC); }
  void SetModelToPassthrough() { this->SetModel(PASSTHROUGH); }
  void SetModelToGladstoneDale() { this->SetModel(GLADSTONE_DALE); }
  void SetModelToGladstoneDaleMixture() { this->SetModel(GLADSTONE_DALE_MIXTURE); }
  void SetModelToIdealGas() { this->SetModel(IDEAL_GAS); }
  void SetModelToCiddor() { this->SetModel(CIDDOR); }
  ///@}

  /** The model the last RequestData used: Model, or what AUTOMATIC resolved to. */
  int GetModelInUse() const;
  /**
   * The array name the last RequestData used for input-array index `idx`: the one chosen, or the
   * one found by name where the choice was left automatic ("" if none).
   */
  std::string GetArrayInUse(int idx) const;
  /** PassthroughHoldsN, or what AUTOMATIC chose (on for an array named n). */
  bool GetPassthroughHoldsNInUse() const;

  /**
   * The array name that stands for "not chosen: find it by name" (the GUI's default entry):
   * "(automatic)". An unset array (no name) means the same.
   */
  static const char* AutomaticArrayName() { return "(automatic)"; }

  ///@{
  /**
   * How the input becomes a volume (a SymmetryType). NO_SYMMETRY (default): the input is a
   * volume; a 2D input (an image one point thick, or bounds of no thickness) is an error that
   * says to choose one of the others. PLANAR: a 2D flow (a 2D data set, or the mid-plane of a
   * thin 3D one: the plane is normal to the input's thinnest axis) is extruded across its plane
   * over Span (the test section's width), the field uniform across it, onto an image grid with
   * the plane's points (an image's own in-plane grid, else AutomaticDimension or
   * SamplingDimensions) and SamplingDimensions' count across (3 when automatic). View it along
   * the plane's normal. AXISYMMETRIC: the input is the r-z half plane of an axisymmetric flow
   * lying in a coordinate plane; it is revolved about SymmetryAxis (the line through the origin
   * of the plane's other in-plane axis; r = |that coordinate|) onto an image grid of
   * SamplingDimensions (or AutomaticDimension along the longest side) over the revolved bounds
   * (or SamplingBounds): each grid point takes the 2D field's value at (its axial coordinate, its
   * distance to the axis), probed in the 2D input, so that memory and time follow the 3D grid
   * and no 3D copy of the input is made. Any view direction works.
   */
  vtkSetMacro(Symmetry, int);
  vtkGetMacro(Symmetry, int);
  ///@}

  ///@{
  /** PLANAR: the extent across the plane (the test section's width), world units. Default 1. */
  vtkSetMacro(Span, double);
  vtkGetMacro(Span, double);
  ///@}

  ///@{
  /**
   * AXISYMMETRIC: the world axis (0 x, 1 y, 2 z) that is the symmetry axis; it must lie in the
   * input's plane, and r is measured along the plane's other axis. Default 0 (x: r along y for
   * data in the x-y plane).
   */
  vtkSetMacro(SymmetryAxis, int);
  vtkGetMacro(SymmetryAxis, int);
  ///@}

  ///@{
  /**
   * AXISYMMETRIC: on (default), an input that is a wedge (one cell across, every point on one of
   * two planes through a common line parallel to a coordinate axis, at most
   * schlieren::WedgeMaxAngleDegrees apart: OpenFOAM's axisymmetric cases) is revolved about
   * that line, found from its points (schlieren::DetectWedge), and SymmetryAxis is ignored; the
   * note says what was found, or why a 3D input was not taken as a wedge. Off: SymmetryAxis.
   */
  vtkSetMacro(AxisFromWedge, int);
  vtkGetMacro(AxisFromWedge, int);
  vtkBooleanMacro(AxisFromWedge, int);
  ///@}

  ///@{
  /** Passthrough: on, the input array holds n (n - 1 = value - 1); off (default), n - 1. */
  vtkSetMacro(PassthroughHoldsN, int);
  vtkGetMacro(PassthroughHoldsN, int);
  vtkBooleanMacro(PassthroughHoldsN, int);
  ///@}

  ///@{
  /**
   * The gas of GladstoneDale (and of IdealGas with SINGLE_GAS): a GasType from AIR to
   * CARBON_MONOXIDE, or CUSTOM_GAS (the default) for GladstoneDaleConstant and MolarMass, whose
   * defaults are air's.
   */
  vtkSetMacro(Gas, int);
  vtkGetMacro(Gas, int);
  ///@}

  ///@{
  /**
   * The typed Gladstone-Dale constant K, m^3/kg (1 cm^3/g = 1e-3 m^3/kg), used with CUSTOM_GAS.
   * Default 2.256e-4 (air at 632.8 nm). Outside [0, 1] an error naming it.
   */
  vtkSetMacro(GladstoneDaleConstant, double);
  vtkGetMacro(GladstoneDaleConstant, double);
  ///@}

  ///@{
  /** The typed molar mass, kg/mol, used with CUSTOM_GAS. Default 0.0289641 (air). */
  vtkSetMacro(MolarMass, double);
  vtkGetMacro(MolarMass, double);
  ///@}

  ///@{
  /** GladstoneDaleMixture: MIXTURE_FRACTION (default) or SPECIES. */
  vtkSetMacro(MixtureComposition, int);
  vtkGetMacro(MixtureComposition, int);
  ///@}

  ///@{
  /** IdealGas: SINGLE_GAS (Gas; the default), MIXTURE_FRACTION or SPECIES. */
  vtkSetMacro(IdealGasComposition, int);
  vtkGetMacro(IdealGasComposition, int);
  ///@}

  ///@{
  /**
   * The gases at mixture fraction 0 and 1 (GasType, table rows only). Defaults AIR and HELIUM: the
   * paper's eq. 2, K = (1 - f) K_air + f K_He.
   */
  vtkSetMacro(MixtureGas0, int);
  vtkGetMacro(MixtureGas0, int);
  vtkSetMacro(MixtureGas1, int);
  vtkGetMacro(MixtureGas1, int);
  ///@}

  ///@{
  /** How many species mass-fraction arrays (indices 4 to 3 + NumberOfSpecies) are read: 0-4. Default 1. */
  vtkSetMacro(NumberOfSpecies, int);
  vtkGetMacro(NumberOfSpecies, int);
  ///@}

  ///@{
  /**
   * The gas of each species array (GasType, CUSTOM_GAS for the typed constants below). Default
   * HYDROGEN, METHANE, HELIUM, CARBON_DIOXIDE.
   */
  vtkSetVector4Macro(SpeciesGases, int);
  vtkGetVector4Macro(SpeciesGases, int);
  ///@}

  ///@{
  /** Typed Gladstone-Dale constants (m^3/kg) and molar masses (kg/mol) of CUSTOM_GAS species. */
  vtkSetVector4Macro(SpeciesGladstoneDale, double);
  vtkGetVector4Macro(SpeciesGladstoneDale, double);
  vtkSetVector4Macro(SpeciesMolarMass, double);
  vtkGetVector4Macro(SpeciesMolarMass, double);
  ///@}

  ///@{
  /**
   * The gas that takes 1 - sum Y (GasType; CUSTOM_GAS: BalanceGladstoneDale and BalanceMolarMass;
   * NO_GAS: none, the species must sum to 1 within 1e-3). Default AIR.
   */
  vtkSetMacro(BalanceGas, int);
  vtkGetMacro(BalanceGas, int);
  vtkSetMacro(BalanceGladstoneDale, double);
  vtkGetMacro(BalanceGladstoneDale, double);
  vtkSetMacro(BalanceMolarMass, double);
  vtkGetMacro(BalanceMolarMass, double);
  ///@}

  ///@{
  /** The unit of the temperature array (after TemperatureReference): KELVIN (default) or CELSIUS. */
  vtkSetMacro(TemperatureUnit, int);
  vtkGetMacro(TemperatureUnit, int);
  ///@}

  ///@{
  /** The unit of the pressure array: PASCAL (default), KILOPASCAL, ATMOSPHERE or BAR. */
  vtkSetMacro(PressureUnit, int);
  vtkGetMacro(PressureUnit, int);
  ///@}

  ///@{
  /**
   * Reference (free-stream) values that non-dimensional arrays are multiplied by: density in
   * kg/m^3, temperature in TemperatureUnit, pressure in PressureUnit. Default 1 (dimensional
   * data). Must be positive.
   */
  vtkSetMacro(DensityReference, double);
  vtkGetMacro(DensityReference, double);
  vtkSetMacro(TemperatureReference, double);
  vtkGetMacro(TemperatureReference, double);
  vtkSetMacro(PressureReference, double);
  vtkGetMacro(PressureReference, double);
  ///@}

  ///@{
  /** Added to the (scaled) pressure, in PressureUnit: the operating pressure of a gauge pressure. Default 0. */
  vtkSetMacro(PressureOffset, double);
  vtkGetMacro(PressureOffset, double);
  ///@}

  ///@{
  /** Ciddor: the humidity where no array is read, a fraction in [0, 1]. Default 0 (dry air). */
  vtkSetMacro(Humidity, double);
  vtkGetMacro(Humidity, double);
  /** Ciddor: read the humidity from the array of index 8. Default off. */
  vtkSetMacro(HumidityFromArray, int);
  vtkGetMacro(HumidityFromArray, int);
  vtkBooleanMacro(HumidityFromArray, int);
  /** Ciddor: RELATIVE_HUMIDITY (default) or WATER_MOLE_FRACTION. */
  vtkSetMacro(HumidityMeasure, int);
  vtkGetMacro(HumidityMeasure, int);
  ///@}

  ///@{
  /** Ciddor: CO2 in umol/mol where no array is read. Default 450 (Ciddor's standard air). */
  vtkSetMacro(CO2, double);
  vtkGetMacro(CO2, double);
  /** Ciddor: read CO2 (umol/mol) from the array of index 9. Default off. */
  vtkSetMacro(CO2FromArray, int);
  vtkGetMacro(CO2FromArray, int);
  vtkBooleanMacro(CO2FromArray, int);
  ///@}

  ///@{
  /**
   * The light's vacuum wavelength, nm. Default 632.8 (HeNe). Used by Ciddor (300-1700 nm); the
   * Gladstone-Dale constants of the table are those at 632.8 nm.
   */
  vtkSetMacro(Wavelength, double); // checked by the model that uses it (never clamped)
  vtkGetMacro(Wavelength, double);
  ///@}

  ///@{
  /**
   * Resampling: grid points along each axis. 0 0 0 (the default): automatic, AutomaticDimension
   * points along the longest side of the bounds, about the same spacing along the others. Not
   * used for image inputs.
   */
  vtkSetVector3Macro(SamplingDimensions, int);
  vtkGetVector3Macro(SamplingDimensions, int);
  ///@}

  ///@{
  /** Resampling: points along the longest side when SamplingDimensions is automatic. Default 128. */
  vtkSetMacro(AutomaticDimension, int);
  vtkGetMacro(AutomaticDimension, int);
  ///@}

  ///@{
  /** Resampling: use SamplingBounds (world units) instead of the input's bounds. Default off. */
  vtkSetMacro(UseSamplingBounds, int);
  vtkGetMacro(UseSamplingBounds, int);
  vtkBooleanMacro(UseSamplingBounds, int);
  vtkSetVector6Macro(SamplingBounds, double);
  vtkGetVector6Macro(SamplingBounds, double);
  ///@}

  ///@{
  /** n - 1 outside the flow domain: EXTEND (default), DOMAIN_EDGE_MEDIAN or AMBIENT_VALUE. */
  vtkSetMacro(AmbientMode, int);
  vtkGetMacro(AmbientMode, int);
  /** The ambient n - 1 of AMBIENT_VALUE. Default 2.7164e-4 (air at 20 C and 1 atm, 632.8 nm). */
  vtkSetMacro(AmbientValue, double);
  vtkGetMacro(AmbientValue, double);
  ///@}

  ///@{
  /**
   * Solid bodies, output as the point array `solid` (unsigned char, 1 in a body) that
   * SchlierenImage reads: rays that meet a body stop, so its shadow is dark (field data
   * `solid_points` counts them). A body is the union of what these give:
   *  - BodyFromGrid (default on): points outside every cell of the input (vtkValidPointMask 0)
   *    that the flow encloses: their connected region of such points does not reach the grid's
   *    boundary, except through the faces marked in BodyWallFaces (schlieren::EnclosedInvalidPoints).
   *    Points beyond the CFD grid's outer boundary reach an open face and stay transparent.
   *  - BodyWallFaces (xmin, xmax, ymin, ymax, zmin, zmax; default all 0): the faces of the grid a
   *    body may touch and the outside may not: a wall the body stands on, a symmetry plane that
   *    cuts it, a face where the sampling box cuts through it. The blunt fin: 0 1 1 0 1 1 (it
   *    runs past x max, is cut by the symmetry plane y = 0, stands on the plate z = 0 and
   *    reaches the top).
   *  - SolidArray (default none): a point array of the input, solid where non-zero (where
   *    resampled, where its interpolated value is at least 0.5).
   *  - The second input (port 1, optional): a closed surface (vtkPolyData, e.g. an STL of the
   *    model, in the data's coordinates); the grid points inside it are solid. A surface that is
   *    not closed is an error.
   */
  vtkSetMacro(BodyFromGrid, int);
  vtkGetMacro(BodyFromGrid, int);
  vtkBooleanMacro(BodyFromGrid, int);
  vtkSetVector6Macro(BodyWallFaces, int);
  vtkGetVector6Macro(BodyWallFaces, int);
  void SetSolidArray(const char* name)
  {
    // "None" (the GUI's entry for no array) and "" mean no mask array
    std::string v = name ? name : "";
    if (v == "None")
    {
      v.clear();
    }
    if (v != this->SolidArray)
    {
      this->SolidArray = v;
      this->Modified();
    }
  }
  const char* GetSolidArray() { return this->SolidArray.c_str(); }
  /** The body surface on port 1 (ParaView: the Body input). */
  void SetBodyConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  ///@}

protected:
  vtkRefractiveIndex();
  ~vtkRefractiveIndex() override;

public:
  /** Every request, with any exception turned into an error and a failed request. */
  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

protected:
  /** ParaView's executive that, under MPI, stops the filter on every rank at once where its
   * input failed on some (schlieren::NewAgreeingExecutive). */
  vtkExecutive* CreateDefaultExecutive() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int Model = AUTOMATIC;
  int Symmetry = NO_SYMMETRY;
  double Span = 1.0;
  int SymmetryAxis = 0;
  int AxisFromWedge = 1;
  int PassthroughHoldsN = 0;
  int Gas = CUSTOM_GAS;
  double GladstoneDaleConstant = 2.256e-4;
  double MolarMass = 0.0289641;
  int MixtureComposition = MIXTURE_FRACTION;
  int IdealGasComposition = SINGLE_GAS;
  int MixtureGas0 = AIR;
  int MixtureGas1 = HELIUM;
  int NumberOfSpecies = 1;
  int SpeciesGases[4] = { HYDROGEN, METHANE, HELIUM, CARBON_DIOXIDE };
  double SpeciesGladstoneDale[4] = { 2.256e-4, 2.256e-4, 2.256e-4, 2.256e-4 };
  double SpeciesMolarMass[4] = { 0.0289641, 0.0289641, 0.0289641, 0.0289641 };
  int BalanceGas = AIR;
  double BalanceGladstoneDale = 2.256e-4;
  double BalanceMolarMass = 0.0289641;
  int TemperatureUnit = KELVIN;
  int PressureUnit = PASCAL;
  double DensityReference = 1.0;
  double TemperatureReference = 1.0;
  double PressureReference = 1.0;
  double PressureOffset = 0.0;
  double Humidity = 0.0;
  int HumidityFromArray = 0;
  int HumidityMeasure = RELATIVE_HUMIDITY;
  double CO2 = 450.0;
  int CO2FromArray = 0;
  double Wavelength = 632.8;
  int SamplingDimensions[3] = { 0, 0, 0 };
  int AutomaticDimension = 128;
  int UseSamplingBounds = 0;
  double SamplingBounds[6] = { 0, 1, 0, 1, 0, 1 };
  int AmbientMode = EXTEND;
  double AmbientValue = 2.7164e-4;
  int BodyFromGrid = 1;
  int BodyWallFaces[6] = { 0, 0, 0, 0, 0, 0 };
  std::string SolidArray;

private:
  vtkRefractiveIndex(const vtkRefractiveIndex&) = delete;
  void operator=(const vtkRefractiveIndex&) = delete;

  /** The resampling grid of a non-image input (RequestInformation); false after an error. */
  bool SamplingGrid(schlieren::Parallel& parallel, vtkInformation* inInfo, int whole[6],
    double origin[3], double spacing[3]);
  /** Updates the input once and returns its bounds (all ranks); false if it has no points. */
  bool UpdatedInputBounds(schlieren::Parallel& parallel, vtkInformation* inInfo, double bounds[6]);

  // The steps of RequestData, in order (vtkRefractiveIndex.cxx). Each returns "" or the error
  // for the user; Work carries what they pass each other.
  struct Work;
  /** What to read: the 2D check, the automatic choices, cell arrays made point arrays. */
  std::string ReadInputs(Work& w);
  /** The grid the model runs on: the input image's (grown) piece, or the resampled grid. */
  std::string MakeGrid(Work& w);
  /** A resampled input whose bounds moved since RequestInformation (a moving mesh over time): the
   * grid's origin and spacing in the output information follow them (collective under MPI). */
  void FollowMovingBounds(Work& w);
  /** The engine's work on the grid (schlieren::ComputeIndexField): n - 1, grad n, the bodies
   * and the field data; collective where an image is split over ranks. */
  std::string ComputeOnGrid(Work& w);
  /**
   * Marks in `solid` the void regions of the resampled `grid` that lie beside the walls of
   * `mesh` (schlieren::walls; vtkRefractiveIndexInputs.cxx); `note` says what was found.
   */
  bool BodiesBesideWalls(vtkDataSet* mesh, vtkImageData* grid, const unsigned char* valid,
    unsigned char* solid, std::string& note);
  /** The requested extent of the grid, with the new arrays and the field data. */
  void WriteOutput(Work& w);
  /**
   * Shows an information note in the Output Messages once until a property changes: a new time
   * step (or any update of the same settings) repeats none of the notes said.
   */
  void SayNote(const std::string& note);
  std::set<std::string> SaidNotes;
  vtkMTimeType SaidNotesTime = 0;
  /** Why the last RequestInformation could not set up the resampling grid (for RequestData). */
  std::string SamplingError;
  // the automatic grid of an AMR input: what it was chosen from, and whether memory capped it
  std::string SamplingNote;
  bool SamplingCapped = false;
  // outputs kept per time step (SchlierenTimeCache.h)
  std::shared_ptr<schlieren::TimeStepCache> TimeCache;

  // Planar and axisymmetric inputs, automatic choices and the checks of the arrays read: defined
  // in vtkRefractiveIndexInputs.cxx.
  /** The 3D grid of a PLANAR or AXISYMMETRIC input (RequestInformation); false after an error. */
  bool SymmetricGrid(vtkInformation* inInfo, int whole[6], double origin[3], double spacing[3]);
  /** The 2D input sampled onto the 3D grid `structure`: the arrays `names` and the valid mask. */
  vtkSmartPointer<vtkImageData> SymmetricResample(
    vtkDataObject* input, vtkImageData* structure, const std::vector<std::string>& names);
  /**
   * Resolves AUTOMATIC and the arrays left automatic (the *InUse state); returns "" or an error
   * for the user; `notes` gets what was chosen.
   */
  std::string ResolveChoices(
    schlieren::Parallel& parallel, vtkDataObject* input, std::vector<std::string>& notes);
  /**
   * Checks the arrays `names` on the input (no integer or id arrays) and converts those that are
   * cell data only to point data; returns the input to use (itself or a converted copy), or null
   * after an error (in `error`).
   */
  vtkSmartPointer<vtkDataObject> PointFields(schlieren::Parallel& parallel, vtkDataObject* input,
    const std::vector<std::string>& names, std::vector<std::string>& notes, std::string& error);
  /**
   * NO_SYMMETRY: "" or the warning that the (non-image) input is an axisymmetric wedge, which
   * traced as it is would be a slab of gas a few degrees thick (issue 48), and what to set.
   */
  std::string WedgeWithoutSymmetry(vtkDataObject* input);
  /** "" or the error of a NO_SYMMETRY input that is 2D (one message, naming Symmetry). */
  std::string FlatInputError(schlieren::Parallel& parallel, vtkDataObject* input);
  /**
   * An OpenFOAM reader's multiblock (a top-level block named internalMesh): that block, the
   * cells; the patches and zones beside it are ignored (`note`, if given, says so). Any other
   * input as it is.
   */
  static vtkDataObject* InternalMesh(vtkDataObject* input, std::string* note);

  int ResolvedModel = PASSTHROUGH;
  bool ResolvedHoldsN = false;
  std::vector<std::string> ResolvedArrays;
  // The symmetric grid's plan (SymmetricGrid, the engine's PlanSymmetry): the plane, the axis in
  // use, the wedge's tilt, the grid; where each grid point samples the 2D input
  std::shared_ptr<schlieren::SymmetryPlan> SymmetryGeometry;
  std::string WedgeNote; // what the wedge detection found, for the log
};

#endif
