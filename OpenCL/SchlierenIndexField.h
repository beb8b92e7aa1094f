// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenIndexField.h
 * @brief RefractiveIndex's work once the input is on a grid: the arrays the model reads chosen by
 * role, the model, the points outside the flow domain, the checks of n, the gradient, the solid
 * bodies and the output's field data. One implementation for every front end: the C++ filter
 * (vtkRefractiveIndex) and, through schlieren_index_field, the Python one call it on plain arrays.
 *
 * What needs VTK stays in the front end and comes in through this interface: the point arrays of
 * the grid (read or resampled), the validity mask, the inside test of a body surface, and the
 * voids beside a mesh's walls (schlieren::walls::ClassifyRim needs the mesh's boundary faces).
 * MPI pieces of an image go through schlieren::Parallel.
 */
#ifndef SchlierenIndexField_h
#define SchlierenIndexField_h

#include "SchlierenIndexModels.h"

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace schlieren
{
class Parallel;

/** The roles of the arrays a model reads (vtkRefractiveIndex's input-array indices). */
enum IndexRole : int
{
  RoleInput = 0, ///< n - 1 or n (Passthrough); density (Gladstone-Dale models)
  RoleTemperature = 1,
  RolePressure = 2,
  RoleMixtureFraction = 3,
  RoleSpecies = 4, ///< 4 to 7: species 1 to 4
  RoleHumidity = 8,
  RoleCO2 = 9,
  NumberOfRoles = 10
};

/** RefractiveIndex's AmbientMode. */
enum class AmbientFill : int
{
  Extend = 0,
  DomainEdgeMedian = 1,
  Value = 2
};

/**
 * A point array of the grid as the front end holds it: its name and components, and where the
 * engine may read it (a scalar array it may need: the model's, "solid", SolidArray) its values,
 * float or double (any other type converted to double), `Count` tuples.
 */
struct GridArray
{
  std::string Name;
  int Components = 1;
  const float* Float = nullptr;
  const double* Double = nullptr;
};

/** What ComputeIndexField takes. */
struct IndexFieldInput
{
  int Dims[3] = { 1, 1, 1 };
  double Spacing[3] = { 1, 1, 1 };
  /** The grid's point arrays, in their order (their names are listed in messages); the mask
   * vtkValidPointMask left out. */
  std::vector<GridArray> PointArrays;
  /** The names of the grid's cell arrays (a chosen cell array gets its own message). */
  std::vector<std::string> CellArrayNames;
  /** The index in PointArrays of the active scalars (-1: none): the input array where none is
   * chosen (else the first point array). */
  int ActiveScalars = -1;
  /** Non-zero: the point is in the flow; null: every point is. */
  const unsigned char* Valid = nullptr;

  /** The model as resolved (Model Automatic already chosen) and its settings. */
  FieldModel Model;
  bool HumidityFromArray = false, CO2FromArray = false;
  /** The array chosen for each role ("" none; the input array: see ActiveScalars). */
  std::string ArrayNames[NumberOfRoles];

  /** The grid is the front end's resampling of the input (not the input image itself). */
  bool Resampled = false;
  bool UseSamplingBounds = false;
  /** "N cells: a 3D, ..." of the input (for the message where no point was found); may be empty. */
  std::function<std::string()> DescribeCells;
  /** A failure the front end found on its piece before (checked with the other ranks). */
  std::string PieceFailure;
  /** Extents (inclusive point indices) of the grid this rank holds, of the part it outputs, and
   * of the whole grid: where an image is split over ranks (else all three the grid's). */
  int GridExtent[6] = { 0, 0, 0, 0, 0, 0 };
  int OutExtent[6] = { 0, 0, 0, 0, 0, 0 };
  int WholeExtent[6] = { 0, 0, 0, 0, 0, 0 };
  /** This rank holds no point of an image split over ranks. */
  bool EmptyPiece = false;

  AmbientFill Ambient = AmbientFill::Extend;
  double AmbientValue = 2.7164e-4;

  bool BodyFromGrid = true;
  int WallFaces[6] = { 0, 0, 0, 0, 0, 0 };
  /** BodyFromGrid on a resampled grid of one process: marks in `solid` the voids beside the
   * mesh's walls (valid: the grid's validity); true where it marked one; `note` for the log.
   * Empty: the front end cannot tell (no mesh, no velocity). */
  std::function<bool(const unsigned char* valid, unsigned char* solid, std::string& note)>
    BesideWalls;
  /** The point array whose non-zero values are solid ("" none). */
  std::string SolidArray;
  /** A body surface: marks in `solid` the points inside it and sets `any` where it marked one;
   * returns "" or the error; `note` gets a surface that encloses no point. Empty: none. */
  std::function<std::string(unsigned char* solid, bool& any, std::string& note)> Surface;

  /** Where n - 1 (a float per point) and grad n (3 a point) are written: the caller's. */
  float* NMinus1 = nullptr;
  float* Gradient = nullptr;

  /** The notes said so far (for index_notes) and more numbers for the field data (AMR). */
  std::vector<std::string> Notes;
  std::vector<std::pair<std::string, double>> Numbers;
};

/** A field data value: a number, or strings. */
struct IndexFieldValue
{
  std::string Name;
  bool IsText = false;
  double Number = 0.0;
  std::vector<std::string> Texts;
};

/** What ComputeIndexField gives. */
struct IndexFieldOutput
{
  std::vector<unsigned char> Solid; ///< a byte per point, empty: no body
  bool AnyInvalid = false;
  /** The model ran on every rank without a failure: its Warnings are said, whatever comes after. */
  bool ModelDone = false;
  /** Warnings of the model (said where ModelDone, before any later failure). */
  std::vector<std::string> Warnings;
  /** A warning for the log (rank 0): a body surface that encloses no point. */
  std::string SolidNote;
  /** Notes to say now (the voids beside walls); they are in the field data's index_notes too. */
  std::vector<std::string> NewNotes;
  /** The grid's point arrays the model read, by role, and the output's field data. */
  std::vector<std::string> ArraysRead;
  std::vector<IndexFieldValue> FieldData;
  /** This rank holds no point of the image (nothing to output, no failure). */
  bool EmptyPiece = false;
};

/** What ResolveIndexChoices takes: the filter's settings as the user left them. */
struct IndexChoiceInput
{
  /** The input's array names (point, then cell arrays; each once; every rank's under MPI). */
  std::vector<std::string> Present;
  int Model = -1; ///< -1 Automatic, else an IndexModel
  bool HoldsN = false; ///< PassthroughHoldsN
  std::string Arrays[NumberOfRoles]; ///< as chosen ("": left automatic)
  // what the notes of Model Automatic's choice say of the gas and the units
  int Gas = -1; ///< -1 Custom, else a Gas
  double GladstoneDale = 2.256e-4, MolarMass = 0.0289641;
  Composition MixtureComposition = Composition::MixtureFraction;
  Composition IdealGasComposition = Composition::SingleGas;
  TemperatureUnit TemperatureUnits = TemperatureUnit::Kelvin;
  PressureUnit PressureUnits = PressureUnit::Pascal;
  double TemperatureReference = 1.0, PressureReference = 1.0, PressureOffset = 0.0,
         DensityReference = 1.0;
  /** The input array where nothing chosen and no name says it: the active point scalars, else
   * the first point array ("" none); asked only then (collective under MPI in the C++ filter). */
  std::function<std::string()> FallbackInput;
};

/** The model and the arrays RefractiveIndex reads, and the notes that say what was chosen. */
struct IndexChoice
{
  IndexModel Model = IndexModel::Passthrough;
  bool HoldsN = false;
  std::string Arrays[NumberOfRoles];
  std::vector<std::string> Notes;
};

/**
 * Model Automatic's choice (from the chosen input array's name, else from the names present: n - 1,
 * a density, a temperature and a pressure, n) and the arrays left automatic found by name (the
 * candidate names: n_minus_1, nminus1, ...; density, rho, ...; temperature, temp, t, ...;
 * pressure, pres, press, p, ...; mixture_fraction, mixturefraction, f, z). Returns "" or the
 * message where no name says anything (the C++ filter's, word for word).
 */
std::string ResolveIndexChoices(const IndexChoiceInput& in, IndexChoice& out);

/** Where a front end found an array the model reads (over every rank's piece under MPI). */
struct ArrayPlace
{
  std::string Name;
  bool InPoints = false, InCells = false;
  bool Integral = false; ///< not float or double somewhere (an integer, bit or string array)
  std::string Type;      ///< that type as VTK names it ("int", "bit", "string"; "" not known)
};

/**
 * RefractiveIndex's rule for the arrays the model reads (`read`, in the model's order): an id or
 * an array of an integer type is refused (returns the message; `present`, the input's array
 * names, listed in it); those found as cell data only go to `fromCells`, which the front end
 * converts with vtkCellDataToPointData (ProcessAllArrays off, only those arrays, PassCellData
 * off; not for an AMR, whose cells are sampled as they are), and `note` (else "") says so.
 */
std::string CellOnlyFields(const std::vector<ArrayPlace>& read,
  const std::vector<std::string>& present, std::vector<std::string>& fromCells,
  std::string& note);

/** "a, b, c", or "none" for no names (the filter's messages list the arrays present so). */
std::string NameList(const std::vector<std::string>& names);

/** `s` in lower case (ASCII), as the candidate names are compared. */
std::string LowerCase(std::string s);

/** The arrays a model reads, as roles in order. */
std::vector<int> NeededRoles(const FieldModel& model, bool humidityFromArray, bool co2FromArray);

/** "Passthrough", "GladstoneDale", ... */
const char* IndexModelLabel(IndexModel model);

/**
 * n - 1, grad n, the solid bodies and the field data of RefractiveIndex from the grid's arrays.
 * Returns "" or the message for the user (the C++ filter's, word for word). Collective where an
 * image is split over ranks (every rank calls it, an empty piece too).
 */
std::string ComputeIndexField(Parallel& ranks, const IndexFieldInput& in, IndexFieldOutput& out);

/** What a front end's test of RefractiveIndex's Body surface (its VTK part) found. */
enum class BodySurface
{
  Inside,      ///< closed: the grid points inside it were found
  NoPolygons,  ///< no polygons or strips
  NotClosed,   ///< boundary or non-manifold edges once triangulated
  NoInsideTest ///< vtkSelectEnclosedPoints gave no result
};

/** The message for the user of a Body surface refused ("" for Inside): the front ends'. */
std::string BodySurfaceProblem(BodySurface found);

/**
 * The Body surface's hook's work once the front end found the points inside it: marks in `solid`
 * (a byte a point, `count`) the points with inside[i] != 0, sets `any` where it marked one, and
 * adds to `note` that the surface encloses no point where none of its shells' boxes overlaps the
 * grid (`overlaps` false) or no point is solid (`any` false after). The C++ filter's and, through
 * schlieren_index_field, the Python one's.
 */
void MarkBodySurface(const unsigned char* inside, std::size_t count, bool overlaps,
  unsigned char* solid, bool& any, std::string& note);

} // namespace schlieren

#endif
