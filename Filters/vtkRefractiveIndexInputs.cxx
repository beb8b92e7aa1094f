// SPDX-License-Identifier: BSD-3-Clause
// vtkRefractiveIndex, the parts that decide what the filter reads: planar and axisymmetric 2D
// inputs made into a volume, the automatic choice of the model and of the arrays left unchosen,
// and the checks of the arrays a model reads (no integer or id arrays; cell data converted to
// point data). The resampling of volumes stays in vtkRefractiveIndex.cxx.
#include "vtkRefractiveIndex.h"

#include "vtkBoundingBox.h"
#include "vtkCellData.h"
#include "vtkCellDataToPointData.h"
#include "vtkCharArray.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkOverlappingAMR.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "SchlierenArrays.h"
#include "SchlierenBodies.h"
#include "SchlierenController.h"
#include "SchlierenWalls.h"
#include "SchlierenEngine.h"
#include "SchlierenParallel.h"
#include "SchlierenResample.h"
#include "SchlierenValues.h"
#include "SchlierenSymmetry.h"
#include "SchlierenIndexField.h"
#include "SchlierenIndexModels.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* const ValidMask = "vtkValidPointMask";
const char* const AxisNames = "xyz";

/** Calls f(vtkDataSet*) for a data set or for every leaf of a composite data set. */
template <class F>
void ForEachLeaf(vtkDataObject* data, F f)
{
  if (auto* ds = vtkDataSet::SafeDownCast(data))
  {
    f(ds);
  }
  else if (auto* cd = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(cd->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (auto* leaf = vtkDataSet::SafeDownCast(it->GetCurrentDataObject()))
      {
        f(leaf);
      }
    }
  }
}

/** The names of the point arrays, then of the cell arrays, of every leaf (each name once). */
std::vector<std::string> ArrayNames(vtkDataObject* data)
{
  std::vector<std::string> names;
  for (int cells = 0; cells < 2; ++cells)
  {
    ForEachLeaf(data, [&](vtkDataSet* ds) {
      vtkFieldData* fd = cells ? static_cast<vtkFieldData*>(ds->GetCellData())
                               : static_cast<vtkFieldData*>(ds->GetPointData());
      for (int i = 0; i < fd->GetNumberOfArrays(); ++i)
      {
        const char* n = fd->GetArrayName(i);
        if (n && std::string(n) != ValidMask &&
          std::find(names.begin(), names.end(), n) == names.end())
        {
          names.emplace_back(n);
        }
      }
    });
  }
  return names;
}

/** Every rank's `names`, in rank order, each name once (the local list on one process). */
std::vector<std::string> GatherNames(
  schlieren::Parallel& parallel, const std::vector<std::string>& names)
{
  if (parallel.Size() <= 1)
  {
    return names;
  }
  std::string mine;
  for (const std::string& n : names)
  {
    mine += n + '\n';
  }
  std::vector<std::string> global;
  for (const std::string& theirs : parallel.AllGatherStrings(mine))
  {
    std::string current;
    for (char c : theirs)
    {
      if (c != '\n')
      {
        current += c;
        continue;
      }
      if (std::find(global.begin(), global.end(), current) == global.end())
      {
        global.push_back(current);
      }
      current.clear();
    }
  }
  return global;
}

/**
 * ArrayNames over every rank's piece, in rank order, so that every rank makes the same choices and
 * the same errors (a rank's piece may be empty).
 */
std::vector<std::string> GlobalArrayNames(schlieren::Parallel& parallel, vtkDataObject* data)
{
  return GatherNames(parallel, ArrayNames(data));
}

/** True where `value` holds on any rank. */
bool AnyRank(schlieren::Parallel& parallel, bool value)
{
  return parallel.Max(value ? 1.0 : 0.0) > 0.5;
}

/** Bounds of the points of a data set or of the leaves of a composite one; false if none. */
bool BoundsOf(vtkDataObject* data, double bounds[6])
{
  vtkBoundingBox box;
  ForEachLeaf(data, [&](vtkDataSet* ds) {
    if (ds->GetNumberOfPoints() > 0)
    {
      box.AddBounds(ds->GetBounds());
    }
  });
  if (!box.IsValid())
  {
    return false;
  }
  box.GetBounds(bounds);
  return true;
}

std::string Flat2DAdvice(int thin)
{
  std::ostringstream m;
  m << " Set Symmetry to Planar (a 2D flow seen across its plane, as through a test section: "
       "Span is its width; view along "
    << AxisNames[thin]
    << ") or Axisymmetric (an r-z half plane revolved about SymmetryAxis; any view).";
  return m.str();
}
} // namespace

//------------------------------------------------------------------------------
int vtkRefractiveIndex::GetModelInUse() const
{
  return this->Model == AUTOMATIC ? this->ResolvedModel : this->Model;
}

//------------------------------------------------------------------------------
bool vtkRefractiveIndex::GetPassthroughHoldsNInUse() const
{
  return this->Model == AUTOMATIC ? this->ResolvedHoldsN : this->PassthroughHoldsN;
}

//------------------------------------------------------------------------------
std::string vtkRefractiveIndex::GetArrayInUse(int idx) const
{
  if (idx >= 0 && static_cast<std::size_t>(idx) < this->ResolvedArrays.size())
  {
    return this->ResolvedArrays[idx];
  }
  return std::string();
}

//------------------------------------------------------------------------------
std::string vtkRefractiveIndex::ResolveChoices(
  schlieren::Parallel& parallel, vtkDataObject* input, std::vector<std::string>& notes)
{
  const std::vector<std::string> present = GlobalArrayNames(parallel, input);
  this->ResolvedArrays.assign(CO2_ARRAY + 1, std::string());
  for (int idx = 0; idx <= CO2_ARRAY; ++idx)
  {
    vtkInformation* info = this->GetInputArrayInformation(idx);
    const char* name = info && info->Has(vtkDataObject::FIELD_NAME())
      ? info->Get(vtkDataObject::FIELD_NAME())
      : nullptr;
    if (name && std::string(name) != AutomaticArrayName())
    {
      this->ResolvedArrays[idx] = name;
    }
  }
  // the choice is the engine's (schlieren::ResolveIndexChoices, which the Python front end calls
  // too); the active scalars where nothing is chosen are read here
  schlieren::IndexChoiceInput in;
  in.Present = present;
  in.Model = this->Model;
  in.HoldsN = this->PassthroughHoldsN != 0;
  std::copy(this->ResolvedArrays.begin(), this->ResolvedArrays.end(), in.Arrays);
  in.Gas = this->Gas;
  in.GladstoneDale = this->GladstoneDaleConstant;
  in.MolarMass = this->MolarMass;
  in.MixtureComposition = static_cast<schlieren::Composition>(this->MixtureComposition);
  in.IdealGasComposition = static_cast<schlieren::Composition>(this->IdealGasComposition);
  in.TemperatureUnits = static_cast<schlieren::TemperatureUnit>(this->TemperatureUnit);
  in.PressureUnits = static_cast<schlieren::PressureUnit>(this->PressureUnit);
  in.TemperatureReference = this->TemperatureReference;
  in.PressureReference = this->PressureReference;
  in.PressureOffset = this->PressureOffset;
  in.DensityReference = this->DensityReference;
  in.FallbackInput = [&parallel, input] {
    std::string name;
    ForEachLeaf(input, [&](vtkDataSet* ds) {
      vtkPointData* pd = ds->GetPointData();
      vtkDataArray* a = pd->GetScalars();
      for (int i = 0; !a && i < pd->GetNumberOfArrays(); ++i)
      {
        const char* n = pd->GetArrayName(i);
        if (n && std::string(n) != ValidMask)
        {
          a = pd->GetArray(i);
        }
      }
      if (name.empty() && a && a->GetName())
      {
        name = a->GetName();
      }
    });
    // the same on every rank: the first rank's that has one
    for (const std::string& c : GatherNames(parallel, std::vector<std::string>{ name }))
    {
      if (!c.empty())
      {
        return c;
      }
    }
    return std::string();
  };
  schlieren::IndexChoice chosen;
  const std::string problem = schlieren::ResolveIndexChoices(in, chosen);
  if (!problem.empty())
  {
    return problem;
  }
  this->ResolvedModel = static_cast<int>(chosen.Model);
  this->ResolvedHoldsN = chosen.HoldsN;
  this->ResolvedArrays.assign(chosen.Arrays, chosen.Arrays + schlieren::NumberOfRoles);
  notes.insert(notes.end(), chosen.Notes.begin(), chosen.Notes.end());
  return std::string();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDataObject> vtkRefractiveIndex::PointFields(schlieren::Parallel& parallel,
  vtkDataObject* input, const std::vector<std::string>& names, std::vector<std::string>& notes,
  std::string& error)
{
  // where each array the model reads is, over every rank's piece; the rule (ids and integer
  // arrays refused, which are cell data only, the note) is the engine's, the Python filter's too
  std::vector<schlieren::ArrayPlace> read(names.size());
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    schlieren::ArrayPlace& place = read[i];
    place.Name = names[i];
    ForEachLeaf(input, [&](vtkDataSet* ds) {
      for (int cells = 0; cells < 2; ++cells)
      {
        vtkFieldData* fd = cells ? static_cast<vtkFieldData*>(ds->GetCellData())
                                 : static_cast<vtkFieldData*>(ds->GetPointData());
        vtkAbstractArray* a = fd->GetAbstractArray(place.Name.c_str());
        if (!a)
        {
          continue;
        }
        (cells ? place.InCells : place.InPoints) = true;
        if (a->GetDataType() != VTK_FLOAT && a->GetDataType() != VTK_DOUBLE)
        {
          place.Integral = true;
          place.Type = a->GetDataTypeAsString();
        }
      }
    });
    place.Integral = AnyRank(parallel, place.Integral);
    place.InPoints = AnyRank(parallel, place.InPoints);
    place.InCells = AnyRank(parallel, place.InCells);
  }
  std::vector<std::string> fromCells;
  std::string note;
  error = schlieren::CellOnlyFields(read, GlobalArrayNames(parallel, input), fromCells, note);
  if (!error.empty())
  {
    return nullptr;
  }
  if (fromCells.empty() || vtkOverlappingAMR::SafeDownCast(input))
  {
    return input; // (AMR cell data is sampled as cells: SchlierenAMR.h)
  }
  vtkNew<vtkCellDataToPointData> toPoints;
  toPoints->SetInputData(input);
  toPoints->SetProcessAllArrays(false);
  for (const std::string& name : fromCells)
  {
    toPoints->AddCellDataArray(name.c_str());
  }
  toPoints->PassCellDataOff();
  toPoints->Update();
  vtkDataObject* converted = toPoints->GetOutputDataObject(0);
  if (!converted)
  {
    error = "The cell arrays " + schlieren::NameList(fromCells) + " could not be converted to point data.";
    return nullptr;
  }
  vtkSmartPointer<vtkDataObject> copy;
  copy.TakeReference(converted->NewInstance());
  copy->ShallowCopy(converted);
  notes.push_back(note);
  return copy;
}

//------------------------------------------------------------------------------
vtkDataObject* vtkRefractiveIndex::InternalMesh(vtkDataObject* input, std::string* note)
{
  auto* blocks = vtkMultiBlockDataSet::SafeDownCast(input);
  if (!blocks)
  {
    return input;
  }
  vtkDataSet* mesh = nullptr;
  std::vector<std::string> others;
  for (unsigned int b = 0; b < blocks->GetNumberOfBlocks(); ++b)
  {
    const char* name = blocks->HasMetaData(b)
      ? blocks->GetMetaData(b)->Get(vtkCompositeDataSet::NAME())
      : nullptr;
    auto* ds = vtkDataSet::SafeDownCast(blocks->GetBlock(b));
    if (!mesh && ds && name && std::string(name) == "internalMesh")
    {
      mesh = ds;
    }
    else if (blocks->GetBlock(b))
    {
      others.emplace_back(name ? name : "block " + std::to_string(b));
    }
  }
  if (!mesh)
  {
    return input;
  }
  if (note)
  {
    std::ostringstream m;
    m << "RefractiveIndex: the OpenFOAM case's internalMesh is read (" << mesh->GetNumberOfCells()
      << " cells)";
    if (!others.empty())
    {
      m << "; the other blocks (" << schlieren::NameList(others)
        << ": patches, zones) are ignored, since the field lives in the cells";
    }
    m << ".";
    *note = m.str();
  }
  return mesh;
}

//------------------------------------------------------------------------------
std::string vtkRefractiveIndex::FlatInputError(schlieren::Parallel& parallel, vtkDataObject* input)
{
  if (this->Symmetry != NO_SYMMETRY)
  {
    return std::string();
  }
  std::ostringstream m;
  if (auto* image = vtkImageData::SafeDownCast(input))
  {
    int ext[6];
    vtkInformation* info = this->GetInputInformation(0, 0);
    if (info && info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), ext);
    }
    else
    {
      image->GetExtent(ext);
    }
    int dims[3] = { ext[1] - ext[0] + 1, ext[3] - ext[2] + 1, ext[5] - ext[4] + 1 };
    for (int a = 2; a >= 0; --a)
    {
      if (dims[a] == 1 && dims[(a + 1) % 3] >= 1 && dims[(a + 2) % 3] >= 1)
      {
        m << "The input image is 2D (" << dims[0] << " x " << dims[1] << " x " << dims[2]
          << " points, one along " << AxisNames[a] << "): there is no volume to trace through."
          << Flat2DAdvice(a);
        return m.str();
      }
    }
    return std::string();
  }
  double b[6] = { 0, -1, 0, -1, 0, -1 };
  const bool have = BoundsOf(input, b);
  if (parallel.Size() > 1)
  {
    // every rank decides on the whole input's bounds (a piece may be empty)
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = have ? b[2 * a] : VTK_DOUBLE_MAX;
      hi[a] = have ? b[2 * a + 1] : -VTK_DOUBLE_MAX;
    }
    parallel.Min(lo, 3);
    parallel.Max(hi, 3);
    for (int a = 0; a < 3; ++a)
    {
      b[2 * a] = lo[a];
      b[2 * a + 1] = hi[a];
    }
  }
  if (!(b[0] <= b[1]))
  {
    return std::string();
  }
  const double largest = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  for (int a = 2; a >= 0; --a)
  {
    if (largest > 0 && b[2 * a + 1] - b[2 * a] <= 1e-9 * largest)
    {
      m << "The input is 2D (its bounds have no thickness along " << AxisNames[a]
        << "): there is no volume to trace through." << Flat2DAdvice(a);
      return m.str();
    }
  }
  return std::string();
}

//------------------------------------------------------------------------------
namespace
{
// x, y, z of every point of `data` (all its blocks), for the engine's wedge and plane checks.
std::vector<double> AllPoints(vtkDataObject* data)
{
  std::vector<double> xyz;
  ForEachLeaf(data, [&](vtkDataSet* ds) {
    for (vtkIdType i = 0; i < ds->GetNumberOfPoints(); ++i)
    {
      double p[3];
      ds->GetPoint(i, p);
      xyz.insert(xyz.end(), p, p + 3);
    }
  });
  return xyz;
}
}

//------------------------------------------------------------------------------
bool vtkRefractiveIndex::SymmetricGrid(
  vtkInformation* inInfo, int whole[6], double origin[3], double spacing[3])
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  this->SamplingError.clear();
  this->SymmetryGeometry.reset();
  // Every rank samples the whole 2D input (it is small): ask for all of it, as
  // RequestUpdateExtent will.
  int producerPort = 0;
  if (vtkAlgorithm* producer = this->GetInputAlgorithm(0, 0, producerPort))
  {
    inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    if (inInfo->Has(SDDP::WHOLE_EXTENT()))
    {
      inInfo->Set(SDDP::UPDATE_EXTENT(), inInfo->Get(SDDP::WHOLE_EXTENT()), 6);
    }
    producer->Update(producerPort);
  }
  // the engine checks the plane, finds a wedge and plans the grid (SchlierenSymmetry.h)
  vtkDataObject* input = InternalMesh(vtkDataObject::GetData(inInfo), nullptr);
  schlieren::SymmetrySettings s;
  s.Symmetry = this->Symmetry;
  s.SymmetryAxis = this->SymmetryAxis;
  s.Span = this->Span;
  s.AxisFromWedge = this->AxisFromWedge != 0;
  std::copy(this->SamplingDimensions, this->SamplingDimensions + 3, s.SamplingDimensions);
  s.AutomaticDimension = this->AutomaticDimension;
  s.UseSamplingBounds = this->UseSamplingBounds != 0;
  std::copy(this->SamplingBounds, this->SamplingBounds + 6, s.SamplingBounds);
  schlieren::SymmetryInput in;
  in.HasPoints = BoundsOf(input, in.Bounds);
  std::vector<double> xyz;
  if (auto* image = vtkImageData::SafeDownCast(input))
  {
    in.Image = true;
    image->GetExtent(in.ImageExtent);
    image->GetOrigin(in.ImageOrigin);
    image->GetSpacing(in.ImageSpacing);
  }
  else if (in.HasPoints)
  {
    xyz = AllPoints(input);
    in.Points = xyz.data();
    in.Count = xyz.size() / 3;
    in.OneDataSet = vtkDataSet::SafeDownCast(input) != nullptr;
  }
  auto plan = std::make_shared<schlieren::SymmetryPlan>();
  const std::string problem = schlieren::PlanSymmetry(s, in, *plan);
  this->WedgeNote = plan->WedgeNote;
  if (!problem.empty())
  {
    this->SamplingError = problem;
    vtkErrorMacro(<< problem);
    return false;
  }
  if (schlieren::ControllerParallel().Rank() == 0)
  {
    for (const std::string& warning : plan->Warnings)
    {
      vtkWarningMacro(<< warning);
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    whole[2 * a] = 0;
    whole[2 * a + 1] = plan->Dims[a] - 1;
    origin[a] = plan->Origin[a];
    spacing[a] = plan->Spacing[a];
  }
  this->SymmetryGeometry = plan;
  return true;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> vtkRefractiveIndex::SymmetricResample(
  vtkDataObject* input, vtkImageData* structure, const std::vector<std::string>& names)
{
  vtkSmartPointer<vtkImageData> grid = vtkSmartPointer<vtkImageData>::New();
  grid->CopyStructure(structure);
  if (!this->SymmetryGeometry)
  {
    return grid; // no plan: RequestInformation failed and said why
  }
  // the engine's plan on this grid: where each grid point samples the 2D input
  schlieren::SymmetryPlan plan = *this->SymmetryGeometry;
  structure->GetDimensions(plan.Dims);
  structure->GetOrigin(plan.Origin);
  structure->GetSpacing(plan.Spacing);
  std::vector<double> xyz;
  std::vector<std::int64_t> sampleOf;
  schlieren::SymmetrySamples(plan, xyz, sampleOf);
  const vtkIdType count = structure->GetNumberOfPoints();
  const vtkIdType samplesCount = static_cast<vtkIdType>(xyz.size() / 3);
  // the engine's cell sampler at the plan's points (the grid mode's cells, test and weights)
  // (a cell type it does not take throws schlieren::Error, which RequestData reports)
  vtkSmartPointer<vtkPointData> probed =
    schlieren::SampleCellsAt(input, xyz.data(), samplesCount);
  vtkDataArray* found = probed->GetArray(ValidMask);
  std::vector<unsigned char> sampleValid(static_cast<std::size_t>(samplesCount), 0);
  if (found)
  {
    const std::vector<double> foundValues = schlieren::values::Values<double>(found);
    const int foundComponents = found->GetNumberOfComponents();
    for (vtkIdType k = 0; k < samplesCount; ++k)
    {
      sampleValid[k] = foundValues[k * foundComponents] != 0.0 ? 1 : 0;
    }
  }
  vtkNew<vtkCharArray> mask;
  mask->SetName(ValidMask);
  mask->SetNumberOfTuples(count);
  schlieren::ExpandValidity(sampleOf.data(), static_cast<std::size_t>(count), sampleValid.data(),
    reinterpret_cast<unsigned char*>(mask->GetPointer(0)));
  grid->GetPointData()->AddArray(mask);
  for (const std::string& name : names)
  {
    vtkDataArray* a = probed->GetArray(name.c_str());
    if (!a)
    {
      continue; // reported as missing by the caller
    }
    const int nc = a->GetNumberOfComponents();
    vtkNew<vtkFloatArray> copy;
    copy->SetName(name.c_str());
    copy->SetNumberOfComponents(nc);
    copy->SetNumberOfTuples(count);
    const std::vector<float> values = schlieren::values::Values<float>(a);
    schlieren::ExpandSamples(
      sampleOf.data(), static_cast<std::size_t>(count), values.data(), nc, copy->GetPointer(0));
    grid->GetPointData()->AddArray(copy);
  }
  return grid;
}


//------------------------------------------------------------------------------
bool vtkRefractiveIndex::BodiesBesideWalls(vtkDataSet* mesh, vtkImageData* grid,
  const unsigned char* valid, unsigned char* solid, std::string& note)
{
  int dims[3];
  grid->GetDimensions(dims);
  const bool symmetric = this->Symmetry != NO_SYMMETRY && this->SymmetryGeometry;
  const int thin = symmetric ? this->SymmetryGeometry->PlaneAxis : -1;
  // where the grid sampled the mesh: the point itself, or where the engine's plan says
  auto toMesh = [&](const double* x, double* at) {
    if (symmetric)
    {
      schlieren::SymmetryToMesh(*this->SymmetryGeometry, x, at);
    }
    else
    {
      std::copy(x, x + 3, at);
    }
  };
  std::vector<unsigned char> rim;
  schlieren::walls::RimReport report;
  if (!schlieren::walls::ClassifyRim(mesh, dims, grid->GetOrigin(), grid->GetSpacing(), valid,
        thin, toMesh, rim, report))
  {
    return false;
  }
  const std::size_t marked = schlieren::InvalidRegionsBesideWalls(dims, valid, rim.data(), solid);
  note = schlieren::walls::BesideWallsNote(report, marked);
  return marked > 0;
}

//------------------------------------------------------------------------------
std::string vtkRefractiveIndex::WedgeWithoutSymmetry(vtkDataObject* input)
{
  double b[6];
  if (!input || vtkImageData::SafeDownCast(input) || !this->AxisFromWedge || !BoundsOf(input, b) ||
    !schlieren::MayBeWedge(b))
  {
    return std::string();
  }
  const std::vector<double> xyz = AllPoints(input);
  return schlieren::WedgeWithoutSymmetry(xyz.data(), xyz.size() / 3);
}
