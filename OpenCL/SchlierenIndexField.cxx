// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenIndexField.h"

#include "SchlierenBodies.h"
#include "SchlierenEngine.h"
#include "SchlierenParallel.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

namespace schlieren
{
namespace
{
/** The role of an array, for messages: what it holds and its ParaView property. */
struct Role
{
  const char* What;
  const char* Property;
};

Role RoleOf(int role, IndexModel model)
{
  switch (role)
  {
    case RoleInput:
      return { model == IndexModel::Passthrough ? "n - 1 (or n)" : "density", "InputArray" };
    case RoleTemperature:
      return { "temperature", "TemperatureArray" };
    case RolePressure:
      return { "pressure", "PressureArray" };
    case RoleMixtureFraction:
      return { "mixture fraction", "MixtureFractionArray" };
    case RoleHumidity:
      return { "humidity", "HumidityArray" };
    case RoleCO2:
      return { "CO2", "CO2Array" };
    default:
      break;
  }
  static const char* const species[] = { "Species1Array", "Species2Array", "Species3Array",
    "Species4Array" };
  const int s = role - RoleSpecies;
  return { "species mass fraction", s >= 0 && s < 4 ? species[s] : "Species?Array" };
}

/** "a, b, c" for the grid's point arrays, or "none". */
std::string PointArrayNames(const IndexFieldInput& in)
{
  std::ostringstream names;
  int shown = 0;
  for (const GridArray& a : in.PointArrays)
  {
    names << (shown++ ? ", " : "") << (a.Name.empty() ? "(unnamed)" : a.Name);
  }
  const std::string s = names.str();
  return s.empty() ? std::string("none") : s;
}

const GridArray* Named(const IndexFieldInput& in, const std::string& name)
{
  for (const GridArray& a : in.PointArrays)
  {
    if (a.Name == name)
    {
      return &a;
    }
  }
  return nullptr;
}

/** The values of a scalar array as floats (converted as a vtkDataArray's, through double). */
std::vector<float> FloatValues(const GridArray& a, std::size_t count)
{
  if (a.Float)
  {
    return std::vector<float>(a.Float, a.Float + count);
  }
  if (!a.Double)
  {
    throw Error("The array '" + a.Name + "' was given without its values.");
  }
  std::vector<float> v(count, 0.0f);
  for (std::size_t i = 0; i < count; ++i)
  {
    v[i] = static_cast<float>(a.Double[i]);
  }
  return v;
}

/** Marks `solid` where the scalar array says solid: non-zero, or at least one half on a
 * resampled grid (where the sampling interpolates the mask). True where it marked any point. */
bool MarkSolid(const GridArray& a, std::size_t count, bool resampled, std::vector<unsigned char>& solid)
{
  bool any = false;
  for (std::size_t i = 0; i < count && i < solid.size(); ++i)
  {
    const double v = a.Float ? static_cast<double>(a.Float[i]) : a.Double ? a.Double[i] : 0.0;
    if (resampled ? v >= 0.5 : v != 0.0)
    {
      solid[i] = 1;
      any = true;
    }
  }
  return any;
}

/** The arrays the model reads into `fields` (copies in `storage`): "" or the user's message. */
std::string GatherFields(const IndexFieldInput& in, const std::vector<int>& needed,
  std::size_t count, FieldArrays& fields, std::vector<std::vector<float>>& storage)
{
  const IndexModel model = in.Model.Model;
  storage.assign(needed.size(), std::vector<float>());
  std::vector<std::pair<std::string, int>> chosen; // name, role
  for (std::size_t k = 0; k < needed.size(); ++k)
  {
    const int idx = needed[k];
    const Role role = RoleOf(idx, model);
    std::string name = in.ArrayNames[idx];
    const GridArray* a = nullptr;
    if (!name.empty())
    {
      a = Named(in, name);
    }
    else if (idx == RoleInput && !in.PointArrays.empty())
    {
      // No name chosen (e.g. a pvpython proxy made before its input was updated): the active
      // point scalars, else the first point array.
      a = in.ActiveScalars >= 0 && in.ActiveScalars < static_cast<int>(in.PointArrays.size())
        ? &in.PointArrays[in.ActiveScalars]
        : &in.PointArrays[0];
      name = a->Name;
    }
    std::ostringstream m;
    if (!a)
    {
      m << IndexModelLabel(model) << " needs a " << role.What << " array ";
      if (name.empty())
      {
        m << "and none is chosen: choose one with " << role.Property
          << " (SetInputArrayToProcess index " << idx << ").";
      }
      else
      {
        m << "('" << name << "', " << role.Property << ") but ";
        if (std::find(in.CellArrayNames.begin(), in.CellArrayNames.end(), name) !=
          in.CellArrayNames.end())
        {
          m << "'" << name << "' is a cell array, and the model reads point arrays: convert it "
            << "first (Cell Data to Point Data).";
        }
        else
        {
          m << "the input has no point array of that name.";
        }
      }
      m << " Point arrays present: " << PointArrayNames(in) << ".";
      return m.str();
    }
    if (a->Components != 1)
    {
      m << "The " << role.What << " array '" << name << "' has " << a->Components
        << " components; " << role.Property << " needs a scalar array.";
      return m.str();
    }
    for (const auto& other : chosen)
    {
      if (other.first == name)
      {
        const Role first = RoleOf(other.second, model);
        m << "The " << first.What << " and " << role.What << " arrays are both '" << name
          << "': choose the right array for each (" << first.Property << ", " << role.Property
          << "). Point arrays present: " << PointArrayNames(in) << ".";
        return m.str();
      }
    }
    chosen.emplace_back(name, idx);
    storage[k] = FloatValues(*a, count);
    const NamedArray named{ storage[k].data(), name };
    switch (idx)
    {
      case RoleInput:
        fields.Index = named;
        fields.Density = named;
        break;
      case RoleTemperature:
        fields.Temperature = named;
        break;
      case RolePressure:
        fields.Pressure = named;
        break;
      case RoleMixtureFraction:
        fields.MixtureFraction = named;
        break;
      case RoleHumidity:
        fields.Humidity = named;
        break;
      case RoleCO2:
        fields.CO2 = named;
        break;
      default:
        fields.Species[idx - RoleSpecies] = named;
        break;
    }
  }
  return std::string();
}

/**
 * "" or the error of Passthrough on values that no gas has as n - 1 (|n - 1| > 0.1: a density, a
 * temperature or a pressure taken for n - 1), naming the array, its range and the models to use.
 */
std::string PassthroughRangeError(
  const float* n1, std::size_t count, const std::string& name, bool holdsN)
{
  const double limit = 0.1;
  float lo = 0.0f, hi = 0.0f;
  if (count > 0)
  {
    const auto range = std::minmax_element(n1, n1 + count);
    lo = *range.first;
    hi = *range.second;
  }
  if (hi <= limit && lo >= -limit)
  {
    return std::string();
  }
  std::ostringstream m;
  m << "Passthrough takes '" << name << "' as " << (holdsN ? "n" : "n - 1")
    << ", but it gives n - 1 from " << lo << " to " << hi << ": no gas has |n - 1| above "
    << limit << " (air at 1 atm: 2.7e-4). If '" << name
    << "' is a density, choose Model GladstoneDale (with DensityReference for non-dimensional "
       "data); a temperature and a pressure: IdealGas; if it holds n itself, turn on "
       "PassthroughHoldsN. A lens or a liquid (not a gas) goes to SchlierenImage directly as an "
       "image carrying n_minus_1.";
  return m.str();
}

/** The message where no point of the grid is in the flow. */
std::string NoValidPoint(const IndexFieldInput& in)
{
  if (!in.Resampled)
  {
    return "No point of the input is valid (vtkValidPointMask is 0 everywhere): check the "
           "filter that made the mask.";
  }
  if (in.UseSamplingBounds)
  {
    return "No point of the sampling grid lies inside the input's cells: SamplingBounds "
           "(UseSamplingBounds on) lies outside the input's mesh; check SamplingBounds and "
           "the input.";
  }
  // the grid is over the input's own bounds: its cells hold no volume to sample (issue 48:
  // "check SamplingBounds" was said with SamplingBounds off)
  return "No point of the sampling grid lies inside the input's cells, though the grid spans "
         "the input's own bounds: its cells enclose no volume (" +
    (in.DescribeCells ? in.DescribeCells() : std::string("its cells")) +
    "). A volume mesh is needed: an OpenFOAM case's internalMesh rather than its patches, a "
    "wedge with an angle, cells with a thickness; a 2D result takes Symmetry Planar or "
    "Axisymmetric.";
}
} // namespace

namespace
{
/** What a field's name says it holds. */
enum class Kind
{
  NMinus1,
  N,
  Density,
  Temperature,
  Pressure,
  MixtureFraction,
  Unknown
};

/** The names (lower case) taken for each kind, in order of preference. */
const std::vector<std::string>& NamesOf(Kind kind)
{
  static const std::vector<std::string> n1{ "n_minus_1", "nminus1", "n-1", "refractivity" };
  static const std::vector<std::string> n{ "n", "refractive_index", "refractiveindex",
    "index_of_refraction" };
  static const std::vector<std::string> rho{ "density", "rho", "dens", "mass_density" };
  static const std::vector<std::string> t{ "temperature", "temp", "t", "static_temperature",
    "t_static" };
  static const std::vector<std::string> p{ "pressure", "pres", "press", "p", "static_pressure",
    "p_static" };
  static const std::vector<std::string> f{ "mixture_fraction", "mixturefraction", "f", "z" };
  static const std::vector<std::string> none;
  switch (kind)
  {
    case Kind::NMinus1:
      return n1;
    case Kind::N:
      return n;
    case Kind::Density:
      return rho;
    case Kind::Temperature:
      return t;
    case Kind::Pressure:
      return p;
    case Kind::MixtureFraction:
      return f;
    default:
      return none;
  }
}

Kind KindOf(const std::string& name)
{
  const std::string l = LowerCase(name);
  for (Kind k : { Kind::NMinus1, Kind::N, Kind::Density, Kind::Temperature, Kind::Pressure })
  {
    const auto& names = NamesOf(k);
    if (std::find(names.begin(), names.end(), l) != names.end())
    {
      return k;
    }
  }
  return Kind::Unknown;
}

/** The first present array whose name is one of `kind`'s (by the order of preference), or "". */
std::string Find(const std::vector<std::string>& present, Kind kind)
{
  for (const std::string& want : NamesOf(kind))
  {
    for (const std::string& name : present)
    {
      if (LowerCase(name) == want)
      {
        return name;
      }
    }
  }
  return std::string();
}

const int ModelPassthrough = 0, ModelGladstoneDale = 1, ModelGladstoneDaleMixture = 2,
          ModelIdealGas = 3, ModelCiddor = 4;

/**
 * Model Automatic: the model (and whether ModelPassthrough's array holds n) from the name of the chosen
 * input array, else from the names `present`; fills the arrays it implies. `why` gets the reason
 * for the note; returns "" or the error where no name says anything.
 */
std::string ChooseModel(const std::vector<std::string>& present, std::string* arrays, int& model,
  bool& holdsN, std::ostringstream& why)
{
  const std::string chosen = arrays[RoleInput];
  if (!chosen.empty())
  {
    switch (KindOf(chosen))
    {
      case Kind::N:
        model = ModelPassthrough;
        holdsN = true;
        why << "Input Array '" << chosen << "' is named as n";
        break;
      case Kind::Density:
        model = ModelGladstoneDale;
        why << "Input Array '" << chosen << "' is named as a density";
        break;
      case Kind::Temperature:
      case Kind::Pressure:
      {
        const bool isT = KindOf(chosen) == Kind::Temperature;
        std::string& slot = arrays[isT ? RoleTemperature : RolePressure];
        if (slot.empty())
        {
          slot = chosen;
        }
        model = ModelIdealGas;
        why << "Input Array '" << chosen << "' is named as a "
            << (isT ? "temperature" : "pressure");
        break;
      }
      case Kind::NMinus1:
        model = ModelPassthrough;
        holdsN = false;
        why << "Input Array '" << chosen << "' is named as n - 1";
        break;
      default:
        model = ModelPassthrough;
        holdsN = false;
        why << "Input Array '" << chosen
            << "' has no name it knows, so it is taken as n - 1 (choose Model if it is not)";
        break;
    }
  }
  else if (!Find(present, Kind::NMinus1).empty())
  {
    model = ModelPassthrough;
    holdsN = false;
    arrays[RoleInput] = Find(present, Kind::NMinus1);
    why << "the input carries n - 1 ('" << arrays[RoleInput] << "')";
  }
  else if (!Find(present, Kind::Density).empty())
  {
    model = ModelGladstoneDale;
    arrays[RoleInput] = Find(present, Kind::Density);
    why << "the input has a density ('" << arrays[RoleInput] << "')";
  }
  else if (!Find(present, Kind::Temperature).empty() && !Find(present, Kind::Pressure).empty())
  {
    model = ModelIdealGas;
    why << "the input has a temperature and a pressure";
  }
  else if (!Find(present, Kind::N).empty())
  {
    model = ModelPassthrough;
    holdsN = true;
    arrays[RoleInput] = Find(present, Kind::N);
    why << "the input carries n ('" << arrays[RoleInput] << "')";
  }
  else
  {
    return "Model Automatic found no array named as a refractive index (n_minus_1, n), a "
           "density (density, rho) or a temperature and a pressure (temperature, Temp, T; "
           "pressure, Pres, p) among the input's arrays: " +
      NameList(present) + ". Choose the Model and its arrays.";
  }
  return std::string();
}

const char* PressureUnitLabel(PressureUnit unit)
{
  static const char* const names[] = { "Pa", "kPa", "atm", "bar" };
  const int u = static_cast<int>(unit);
  return u >= 0 && u <= 3 ? names[u] : "Pa";
}

/** The gas the chosen model takes, in words: "air (the default Custom gas: ...)", "He (the table)". */
std::string GasWords(const IndexChoiceInput& in, int model)
{
  std::ostringstream g;
  if (model == ModelIdealGas && in.IdealGasComposition != Composition::SingleGas)
  {
    g << (in.IdealGasComposition == Composition::MixtureFraction
        ? "a mixture fraction between Mixture Gas 0 and 1"
        : "species mass fractions");
    return g.str();
  }
  if (in.Gas >= 0)
  {
    const GasProperties& p = GetGasProperties(static_cast<Gas>(in.Gas));
    g << p.Name << " from the gas table (K = " << p.GladstoneDale << " m^3/kg)";
    return g.str();
  }
  const GasProperties& air = GetGasProperties(Gas::Air);
  const double K = in.GladstoneDale, M = in.MolarMass;
  const bool isAir = K == air.GladstoneDale && (model != ModelIdealGas || M == air.MolarMass);
  if (isAir)
  {
    g << "air (Gas Custom, whose defaults are air's: K = " << K << " m^3/kg";
    if (model == ModelIdealGas)
    {
      g << ", M = " << M << " kg/mol";
    }
    g << "; set Gas for another gas)";
  }
  else
  {
    g << "the Custom gas, K = " << K << " m^3/kg";
    if (model == ModelIdealGas)
    {
      g << ", M = " << M << " kg/mol";
    }
  }
  return g.str();
}

/** The note that says what Model Automatic chose, and why. */
std::string ChoiceNote(const IndexChoiceInput& in, int model, bool holdsN, const std::string& why)
{
  std::ostringstream note;
  note << "RefractiveIndex: Model Automatic chose "
       << IndexModelLabel(static_cast<IndexModel>(model));
  if (model == ModelPassthrough && holdsN)
  {
    note << " of n";
  }
  note << ": " << why << ".";
  if (model == ModelGladstoneDale || model == ModelIdealGas)
  {
    note << " Gas: " << GasWords(in, model) << ".";
  }
  return note.str();
}
} // namespace

//------------------------------------------------------------------------------
std::string ResolveIndexChoices(const IndexChoiceInput& in, IndexChoice& out)
{
  out = IndexChoice();
  std::string* arrays = out.Arrays;
  std::copy(in.Arrays, in.Arrays + NumberOfRoles, arrays);
  std::vector<std::string>& notes = out.Notes;
  const bool automatic = in.Model < 0;
  int model = in.Model;
  bool holdsN = in.HoldsN;
  if (automatic)
  {
    std::ostringstream why;
    const std::string problem = ChooseModel(in.Present, arrays, model, holdsN, why);
    if (!problem.empty())
    {
      return problem;
    }
    notes.push_back(ChoiceNote(in, model, holdsN, why.str()));
  }
  out.Model = static_cast<IndexModel>(model);
  out.HoldsN = holdsN;

  // The arrays left automatic, found by name for what the model reads there.
  auto fill = [&](int idx, Kind kind, const char* property) {
    if (arrays[idx].empty())
    {
      arrays[idx] = Find(in.Present, kind);
      if (!arrays[idx].empty() && !automatic)
      {
        notes.push_back(std::string("RefractiveIndex: ") + property + " '" + arrays[idx] +
          "', found by name.");
      }
    }
  };
  if (model == ModelPassthrough)
  {
    fill(RoleInput, holdsN ? Kind::N : Kind::NMinus1, "InputArray");
  }
  else if (model == ModelGladstoneDale || model == ModelGladstoneDaleMixture)
  {
    fill(RoleInput, Kind::Density, "InputArray");
  }
  if (arrays[RoleInput].empty() && model != ModelIdealGas && model != ModelCiddor && in.FallbackInput)
  {
    // Nothing chosen and no name known: the active point scalars, else the first point array
    // (as before there was an automatic choice).
    arrays[RoleInput] = in.FallbackInput();
  }
  if (model == ModelIdealGas || model == ModelCiddor)
  {
    fill(RoleTemperature, Kind::Temperature, "TemperatureArray");
    fill(RolePressure, Kind::Pressure, "PressureArray");
  }
  if ((model == ModelGladstoneDaleMixture && in.MixtureComposition == Composition::MixtureFraction) ||
    (model == ModelIdealGas && in.IdealGasComposition == Composition::MixtureFraction))
  {
    fill(RoleMixtureFraction, Kind::MixtureFraction, "MixtureFractionArray");
  }
  if (automatic && model == ModelIdealGas)
  {
    std::ostringstream units;
    units << " Temperature '" << arrays[RoleTemperature] << "' read in "
          << (in.TemperatureUnits == TemperatureUnit::Celsius ? "C" : "K")
          << " times TemperatureReference (" << in.TemperatureReference << "), pressure '"
          << arrays[RolePressure] << "' in " << PressureUnitLabel(in.PressureUnits)
          << " times PressureReference (" << in.PressureReference << ") plus PressureOffset ("
          << in.PressureOffset
          << "): an absolute pressure (a gauge one needs the operating pressure as PressureOffset).";
    notes.back() += units.str();
  }
  if (automatic && model == ModelGladstoneDale)
  {
    std::ostringstream units;
    units << " Density '" << arrays[RoleInput] << "' read in kg/m^3 times DensityReference ("
          << in.DensityReference
          << "): a non-dimensional density (PLOT3D's is rho / rho_inf) needs the free-stream "
             "density in kg/m^3 as DensityReference.";
    notes.back() += units.str();
  }
  return std::string();
}

//------------------------------------------------------------------------------
std::string NameList(const std::vector<std::string>& names)
{
  std::ostringstream s;
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    s << (i ? ", " : "") << names[i];
  }
  return names.empty() ? std::string("none") : s.str();
}

//------------------------------------------------------------------------------
namespace
{
/** Names of ids and index arrays that VTK readers and filters add. */
bool IsIdName(const std::string& name)
{
  static const char* const ids[] = { "objectid", "globalelementid", "globalnodeid", "pedigreeid",
    "pedigreeids", "vtkoriginalcellids", "vtkoriginalpointids", "vtkoriginalindices",
    "vtkcompositeindex", "vtkblockcolors", "blockid", "processid", "vtkprocessid", "element_id",
    "node_id", "cellid", "pointid", "ids" };
  const std::string l = LowerCase(name);
  return std::find(std::begin(ids), std::end(ids), l) != std::end(ids);
}
} // anonymous namespace

//------------------------------------------------------------------------------
std::string CellOnlyFields(const std::vector<ArrayPlace>& read,
  const std::vector<std::string>& present, std::vector<std::string>& fromCells,
  std::string& note)
{
  fromCells.clear();
  note.clear();
  for (const ArrayPlace& a : read)
  {
    if (a.Integral || ((a.InPoints || a.InCells) && IsIdName(a.Name)))
    {
      std::ostringstream m;
      m << "The array '" << a.Name << "' is "
        << (a.Integral ? "of an integer type" + (a.Type.empty() ? std::string() : " (" + a.Type + ")")
                       : std::string("named as an id"))
        << ": ids and index arrays (ObjectId, GlobalElementId, vtkOriginalCellIds, ...) are not "
           "a density, temperature, pressure or index field. Choose the field itself (Model "
           "and its arrays); arrays present: "
        << NameList(present) << ".";
      fromCells.clear();
      return m.str();
    }
    if (a.InCells && !a.InPoints &&
      std::find(fromCells.begin(), fromCells.end(), a.Name) == fromCells.end())
    {
      fromCells.push_back(a.Name);
    }
  }
  if (!fromCells.empty())
  {
    note = "RefractiveIndex: the cell array" + std::string(fromCells.size() > 1 ? "s " : " ") +
      NameList(fromCells) +
      " converted to point data (each point the mean of the cells around it, "
      "vtkCellDataToPointData), since n - 1 and its gradient are fields on points.";
  }
  return std::string();
}

//------------------------------------------------------------------------------
std::string LowerCase(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

//------------------------------------------------------------------------------
const char* IndexModelLabel(IndexModel model)
{
  static const char* const names[] = { "Passthrough", "GladstoneDale", "GladstoneDaleMixture",
    "IdealGas", "Ciddor" };
  const int m = static_cast<int>(model);
  return m >= 0 && m <= 4 ? names[m] : "(unknown)";
}

//------------------------------------------------------------------------------
std::vector<int> NeededRoles(const FieldModel& model, bool humidityFromArray, bool co2FromArray)
{
  std::vector<int> needed;
  const bool gasLaw = model.Model == IndexModel::IdealGas || model.Model == IndexModel::Ciddor;
  if (gasLaw)
  {
    needed = { RoleTemperature, RolePressure };
  }
  else
  {
    needed = { RoleInput };
  }
  const bool composed =
    model.Model == IndexModel::GladstoneDaleMixture || model.Model == IndexModel::IdealGas;
  if (composed && model.Mixture == Composition::MixtureFraction)
  {
    needed.push_back(RoleMixtureFraction);
  }
  else if (composed && model.Mixture == Composition::Species)
  {
    for (int s = 0; s < model.NumberOfSpecies; ++s)
    {
      needed.push_back(RoleSpecies + s);
    }
  }
  if (model.Model == IndexModel::Ciddor && humidityFromArray)
  {
    needed.push_back(RoleHumidity);
  }
  if (model.Model == IndexModel::Ciddor && co2FromArray)
  {
    needed.push_back(RoleCO2);
  }
  return needed;
}

//------------------------------------------------------------------------------
std::string ComputeIndexField(Parallel& ranks, const IndexFieldInput& in, IndexFieldOutput& out)
{
  const std::size_t count =
    static_cast<std::size_t>(in.Dims[0]) * static_cast<std::size_t>(in.Dims[1]) *
    static_cast<std::size_t>(in.Dims[2]);
  const IndexModel model = in.Model.Model;
  const std::vector<int> needed = NeededRoles(in.Model, in.HumidityFromArray, in.CO2FromArray);
  const bool pieceOfImage = ranks.Size() > 1 && !in.Resampled;
  out = IndexFieldOutput();
  if (count > 0 && (!in.NMinus1 || !in.Gradient))
  {
    throw Error("ComputeIndexField: no n - 1 or gradient to write.");
  }
  out.EmptyPiece = in.EmptyPiece;
  for (int idx : needed)
  {
    out.ArraysRead.push_back(in.ArrayNames[idx]);
  }

  // 1. The model on the grid. Failures are kept, not returned, so that under MPI every rank
  // reaches the agreement below.
  std::vector<unsigned char> valid;
  std::vector<float> edge; // n - 1 at the edge of the flow domain (DomainEdgeMedian)
  std::string failure;
  if (!in.EmptyPiece)
  {
    failure = in.PieceFailure;
    valid.assign(count, 1);
    if (in.Valid)
    {
      for (std::size_t i = 0; i < count; ++i)
      {
        if (!in.Valid[i])
        {
          valid[i] = 0;
          out.AnyInvalid = true;
        }
      }
    }
    FieldArrays fields;
    fields.Count = count;
    fields.Valid = out.AnyInvalid ? valid.data() : nullptr;
    std::vector<std::vector<float>> storage;
    if (failure.empty())
    {
      failure = GatherFields(in, needed, count, fields, storage);
    }
    std::fill(in.NMinus1, in.NMinus1 + count, 0.0f);
    if (failure.empty())
    {
      try
      {
        const FieldReport report = ComputeFieldIndex(fields, in.Model, in.NMinus1);
        out.Warnings = report.Warnings;
        if (out.AnyInvalid && report.ValidPoints == 0)
        {
          failure = NoValidPoint(in);
        }
      }
      catch (const Error& e)
      {
        failure = std::string(e.what()) +
          (in.Resampled ? " (Counted on the image grid the input was resampled onto.)" : "");
      }
    }
    // The values at the edge of the flow domain, for DomainEdgeMedian (and for Extend on an
    // image piece under MPI, which cannot extend across pieces), over the points this piece
    // owns: its output extent less the upper plane that the next piece also holds. A resampled
    // grid is whole on every rank: all of it.
    if (failure.empty() && out.AnyInvalid &&
      (in.Ambient == AmbientFill::DomainEdgeMedian ||
        (in.Ambient == AmbientFill::Extend && pieceOfImage)))
    {
      int owned[6];
      for (int a = 0; a < 3; ++a)
      {
        owned[2 * a] = in.Resampled ? 0 : in.OutExtent[2 * a] - in.GridExtent[2 * a];
        owned[2 * a + 1] = in.Resampled ? in.Dims[a] - 1
                                        : in.OutExtent[2 * a + 1] - in.GridExtent[2 * a] -
            (in.OutExtent[2 * a + 1] < in.WholeExtent[2 * a + 1] ? 1 : 0);
      }
      CollectDomainEdge(in.Dims, valid.data(), in.NMinus1, owned, edge);
    }
  }

  // 2. Under MPI (an image split over ranks), every rank learns whether any failed, and gets the
  // domain edge of all pieces; BodyFromGrid's flood goes across the pieces.
  std::vector<unsigned char> enclosed;
  bool enclosedFound = false;
  if (pieceOfImage)
  {
    // every failing rank reports its own failure, the others the first failing rank's
    const std::string agreed = ranks.Failure(failure);
    if (!agreed.empty())
    {
      return failure.empty() ? agreed : failure;
    }
    const bool anyInvalid = ranks.Max(out.AnyInvalid ? 1.0 : 0.0) > 0.5;
    if (anyInvalid && in.Ambient != AmbientFill::Value)
    {
      const char* mine = reinterpret_cast<const char*>(edge.data());
      const std::vector<std::vector<char>> all =
        ranks.AllGather(std::vector<char>(mine, mine + edge.size() * sizeof(float)));
      edge.clear();
      for (const std::vector<char>& theirs : all)
      {
        const std::size_t n = theirs.size() / sizeof(float);
        edge.resize(edge.size() + n);
        char* to = reinterpret_cast<char*>(edge.data() + edge.size() - n);
        std::copy(theirs.begin(), theirs.end(), to);
      }
    }
    // collective: every rank, an empty piece too, before an empty one leaves
    if (in.BodyFromGrid && ranks.Max(out.AnyInvalid ? 1.0 : 0.0) > 0.5)
    {
      int extent[6] = { 0, -1, 0, -1, 0, -1 };
      if (!in.EmptyPiece && valid.size() == count)
      {
        std::copy(in.GridExtent, in.GridExtent + 6, extent);
      }
      enclosed.assign(valid.size(), 0);
      EnclosedInvalidPointsOfPiece(
        ranks, extent, in.WholeExtent, valid.data(), in.WallFaces, enclosed.data());
      enclosedFound = true;
    }
  }
  else if (!failure.empty())
  {
    return failure;
  }
  out.ModelDone = true;
  if (in.EmptyPiece)
  {
    return std::string();
  }

  // 3. The points outside the flow domain, the check of n, the gradient.
  AmbientFill mode = in.Ambient;
  if (out.AnyInvalid && mode == AmbientFill::Extend && pieceOfImage)
  {
    mode = AmbientFill::DomainEdgeMedian; // extending needs the whole grid
  }
  double ambient =
    mode == AmbientFill::Value ? in.AmbientValue : std::numeric_limits<double>::quiet_NaN();
  std::size_t invalidPoints = 0;
  float* n1 = in.NMinus1;
  try
  {
    if (out.AnyInvalid && mode == AmbientFill::Extend)
    {
      invalidPoints = ExtendIntoInvalid(in.Dims, valid.data(), n1);
    }
    else if (out.AnyInvalid)
    {
      if (mode == AmbientFill::DomainEdgeMedian)
      {
        ambient = Median(edge);
        if (!std::isfinite(ambient))
        {
          // No valid point touches an invalid one here: the median of the valid points.
          std::vector<float> values;
          for (std::size_t i = 0; i < count; ++i)
          {
            if (valid[i])
            {
              values.push_back(n1[i]);
            }
          }
          ambient = Median(values);
        }
      }
      invalidPoints = FillInvalid(count, valid.data(), ambient, n1);
    }
    const std::string problem = ValidateIndex(n1, count);
    if (!problem.empty())
    {
      return problem + " (model " + IndexModelLabel(model) + ").";
    }
    if (model == IndexModel::Passthrough)
    {
      const std::string notGas =
        PassthroughRangeError(n1, count, in.ArrayNames[RoleInput], in.Model.IndexIsN);
      if (!notGas.empty())
      {
        return notGas;
      }
    }
    ComputeGradient(in.Dims, in.Spacing, n1, in.Gradient);
  }
  catch (const Error& e)
  {
    return e.what();
  }

  // 4. The solid bodies.
  std::vector<unsigned char>& solid = out.Solid;
  solid.assign(count, 0);
  bool any = false;
  std::vector<std::string> notes = in.Notes;
  // the holes the grid leaves that the flow encloses (the whole grid: resampled, or one process)
  if (in.BodyFromGrid && out.AnyInvalid)
  {
    if (in.Resampled || ranks.Size() == 1)
    {
      any = EnclosedInvalidPoints(in.Dims, valid.data(), in.WallFaces, solid.data()) > 0;
    }
    else if (enclosedFound && enclosed.size() == solid.size())
    {
      for (std::size_t i = 0; i < solid.size(); ++i)
      {
        solid[i] = enclosed[i];
        any = any || solid[i];
      }
    }
  }
  // the voids beside the mesh's walls (a body on the domain's edge), where the mesh has a velocity
  if (in.BodyFromGrid && out.AnyInvalid && in.Resampled && ranks.Size() == 1 && in.BesideWalls)
  {
    std::string wallNote;
    any = in.BesideWalls(valid.data(), solid.data(), wallNote) || any;
    if (!wallNote.empty())
    {
      out.NewNotes.push_back(wallNote);
      notes.push_back(wallNote);
    }
  }
  // a body the input already carries (RefractiveScene's Body, an upstream RefractiveIndex's): kept
  const GridArray* upstream = Named(in, "solid");
  if (upstream && upstream->Components == 1)
  {
    any = MarkSolid(*upstream, count, in.Resampled, solid) || any;
  }
  // the mask array
  if (!in.SolidArray.empty())
  {
    const GridArray* mask = Named(in, in.SolidArray);
    if (!mask)
    {
      return "SolidArray '" + in.SolidArray + "' is not a point array of the input. Point " +
        "arrays present: " + PointArrayNames(in) + ".";
    }
    if (mask->Components != 1)
    {
      return "SolidArray '" + in.SolidArray + "' has " + std::to_string(mask->Components) +
        " components; it must be a scalar (non-zero: solid).";
    }
    any = MarkSolid(*mask, count, in.Resampled, solid) || any;
  }
  // the body surface: the grid points inside it
  if (in.Surface)
  {
    const std::string problem = in.Surface(solid.data(), any, out.SolidNote);
    if (!problem.empty())
    {
      return problem;
    }
  }
  if (!any)
  {
    solid.clear();
  }

  // 5. The field data: what was read, for scripts and for the GUI's information panel.
  auto number = [&out](const char* name, double value) {
    IndexFieldValue v;
    v.Name = name;
    v.Number = value;
    out.FieldData.push_back(v);
  };
  auto texts = [&out](const char* name, const std::vector<std::string>& values) {
    IndexFieldValue v;
    v.Name = name;
    v.IsText = true;
    v.Texts = values;
    out.FieldData.push_back(v);
  };
  if (out.AnyInvalid && mode != AmbientFill::Extend)
  {
    number("ambient_n_minus_1", ambient);
  }
  texts("index_model", { IndexModelLabel(model) });
  texts("index_arrays", out.ArraysRead);
  if (!notes.empty())
  {
    texts("index_notes", notes);
  }
  number("valid_point_fraction",
    count ? 1.0 - static_cast<double>(invalidPoints) / static_cast<double>(count) : 0.0);
  number("solid_points", static_cast<double>(std::count(solid.begin(), solid.end(), 1)));
  for (const auto& extra : in.Numbers)
  {
    number(extra.first.c_str(), extra.second);
  }
  return std::string();
}

//------------------------------------------------------------------------------
std::string BodySurfaceProblem(BodySurface found)
{
  switch (found)
  {
    case BodySurface::NoPolygons:
      return "The Body input has no polygons: it must be a closed surface (vtkPolyData), such as "
             "an STL of the model.";
    case BodySurface::NotClosed:
      return "The Body input is not a closed surface (it has boundary or non-manifold edges), so "
             "its inside is not defined. Close it (e.g. Fill Holes, or export the model as a "
             "watertight STL).";
    case BodySurface::NoInsideTest:
      return "The inside test of the Body surface failed (vtkSelectEnclosedPoints gave no "
             "result).";
    case BodySurface::Inside:
      break;
  }
  return std::string();
}

//------------------------------------------------------------------------------
void MarkBodySurface(const unsigned char* inside, std::size_t count, bool overlaps,
  unsigned char* solid, bool& any, std::string& note)
{
  for (std::size_t i = 0; inside && i < count; ++i)
  {
    if (inside[i])
    {
      solid[i] = 1;
      any = true;
    }
  }
  if (!overlaps || !any)
  {
    note += std::string(note.empty() ? "" : " ") +
      "The Body surface encloses no point of the grid: check that it is in the data's "
      "coordinates and inside the sampling bounds.";
  }
}

} // namespace schlieren
