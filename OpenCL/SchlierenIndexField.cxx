// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenIndexField.h"

#include "SchlierenBodies.h"
#include "SchlierenEngine.h"
#include "SchlierenParallel.h"

#include <algorithm>
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

} // namespace schlieren
