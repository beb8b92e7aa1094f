// SPDX-License-Identifier: BSD-3-Clause
#include "vtkRefractiveIndex.h"
#include "SchlierenGuard.h"

#include "vtkBoundingBox.h"
#include "vtkCellData.h"
#include "vtkCellTypes.h"
#include "vtkCharArray.h"
#include "vtkCompositeDataIterator.h"
#include "vtkOverlappingAMR.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkSelectEnclosedPoints.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include "SchlierenAMR.h"
#include "SchlierenArrays.h"
#include "SchlierenBodies.h"
#include "SchlierenController.h"
#include "SchlierenEnums.h"
#include "SchlierenEngine.h"
#include "SchlierenIndexField.h"
#include "SchlierenIndexModels.h"
#include "SchlierenLimits.h"
#include "SchlierenResample.h"
#include "SchlierenSamplingGrid.h"
#include "SchlierenTimeCache.h"
#include "SchlierenValues.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkRefractiveIndex);

namespace
{
const char* const MaskName = "vtkValidPointMask";

std::string NotAVolume(vtkDataObject* input)
{
  return std::string("RefractiveIndex needs a volume to sample: a vtkImageData, or any volumetric "
                     "grid (structured, rectilinear, unstructured, or a multiblock of them) to "
                     "resample onto an image; got ") +
    (input ? input->GetClassName() : "nothing") +
    (vtkPolyData::SafeDownCast(input)
        ? " (surfaces, lines and points have no inside; a 2D flow on a mesh in a plane: set "
          "Symmetry to Planar or Axisymmetric)."
        : ".");
}
/** The names of the point and cell arrays of a data set or of the leaves of a composite one. */
std::vector<std::string> InputArrayNames(vtkDataObject* data)
{
  std::vector<std::string> names;
  auto add = [&names](vtkDataSet* ds) {
    for (vtkFieldData* fd : { static_cast<vtkFieldData*>(ds->GetPointData()),
           static_cast<vtkFieldData*>(ds->GetCellData()) })
    {
      for (int i = 0; i < fd->GetNumberOfArrays(); ++i)
      {
        const char* n = fd->GetArrayName(i);
        if (n && std::find(names.begin(), names.end(), n) == names.end())
        {
          names.emplace_back(n);
        }
      }
    }
  };
  if (auto* ds = vtkDataSet::SafeDownCast(data))
  {
    add(ds);
  }
  else if (auto* cd = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(cd->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (auto* leaf = vtkDataSet::SafeDownCast(it->GetCurrentDataObject()))
      {
        add(leaf);
      }
    }
  }
  return names;
}

/** The cell extent of a point extent of an image whose whole point extent is `whole`. */
void CellExtent(const int whole[6], const int pointExt[6], int cellExt[6])
{
  for (int a = 0; a < 3; ++a)
  {
    cellExt[2 * a] = pointExt[2 * a];
    cellExt[2 * a + 1] =
      whole[2 * a + 1] > whole[2 * a] ? pointExt[2 * a + 1] - 1 : pointExt[2 * a + 1];
  }
}

bool IsEmpty(const int ext[6])
{
  return ext[1] < ext[0] || ext[3] < ext[2] || ext[5] < ext[4];
}

/** Bounds of the points of a data set or of the leaves of a composite data set. */
bool LocalBounds(vtkDataObject* data, double bounds[6])
{
  vtkBoundingBox box;
  if (auto* ds = vtkDataSet::SafeDownCast(data))
  {
    if (ds->GetNumberOfPoints() > 0)
    {
      box.AddBounds(ds->GetBounds());
    }
  }
  else if (auto* cd = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(cd->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      auto* leaf = vtkDataSet::SafeDownCast(it->GetCurrentDataObject());
      if (leaf && leaf->GetNumberOfPoints() > 0)
      {
        box.AddBounds(leaf->GetBounds());
      }
    }
  }
  if (!box.IsValid())
  {
    return false;
  }
  box.GetBounds(bounds);
  return true;
}

/** The bounds of `data`'s points over every rank (min of the minima, max of the maxima; empty
 * ranks send +/- infinity): false where no rank has a point. Collective under MPI. */
bool GlobalBounds(schlieren::Parallel& parallel, vtkDataObject* data, double bounds[6])
{
  double local[6] = { 1, -1, 1, -1, 1, -1 };
  const bool have = LocalBounds(data, local);
  if (parallel.Size() <= 1)
  {
    std::copy(local, local + 6, bounds);
    return have;
  }
  double mins[3], maxs[3];
  for (int a = 0; a < 3; ++a)
  {
    mins[a] = have ? local[2 * a] : VTK_DOUBLE_MAX;
    maxs[a] = have ? local[2 * a + 1] : -VTK_DOUBLE_MAX;
  }
  parallel.Min(mins, 3);
  parallel.Max(maxs, 3);
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = mins[a];
    bounds[2 * a + 1] = maxs[a];
  }
  return mins[0] <= maxs[0];
}

/** 1 where a point of `image` is in the flow (vtkValidPointMask != 0 and not a hidden point). */
std::vector<unsigned char> Validity(vtkImageData* image, bool& any)
{
  const vtkIdType n = image->GetNumberOfPoints();
  std::vector<unsigned char> valid(static_cast<std::size_t>(n), 1);
  any = false;
  if (vtkDataArray* mask = image->GetPointData()->GetArray(MaskName))
  {
    schlieren::values::ForEachFirstComponent(mask, [&](vtkIdType i, double v) {
      if (i < n && v == 0.0)
      {
        valid[i] = 0;
        any = true;
      }
    });
  }
  if (vtkUnsignedCharArray* ghosts = image->GetPointGhostArray())
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (ghosts->GetValue(i) & vtkDataSetAttributes::HIDDENPOINT)
      {
        valid[i] = 0;
        any = true;
      }
    }
  }
  return valid;
}

/** The input's arrays, bytes per point, as the probe copies them (a composite input: a few double
 * arrays): the engine adds the mask, n - 1 and grad n (schlieren::SamplingBytesPerPoint). */
double ArrayBytesPerPoint(vtkDataObject* input)
{
  auto* ds = vtkDataSet::SafeDownCast(input);
  if (!ds)
  {
    return 64.0;
  }
  double bytes = 0.0;
  for (vtkDataSetAttributes* attributes : { static_cast<vtkDataSetAttributes*>(ds->GetPointData()),
         static_cast<vtkDataSetAttributes*>(ds->GetCellData()) })
  {
    for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
    {
      if (vtkDataArray* a = attributes->GetArray(i))
      {
        bytes += a->GetNumberOfComponents() * a->GetDataTypeSize();
      }
    }
  }
  return bytes;
}

/** The engine's request of the input (schlieren::RequestInput) in the pipeline's keys. */
void SetRequest(vtkInformation* inInfo, const schlieren::InputRequest& r)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (!r.WholeExtent)
  {
    inInfo->Set(SDDP::UPDATE_EXTENT(), r.Extent, 6);
  }
  else if (inInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    inInfo->Set(SDDP::UPDATE_EXTENT(), inInfo->Get(SDDP::WHOLE_EXTENT()), 6);
  }
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), r.Piece);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), r.Pieces);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
}

/** The sampling properties, for the engine. */
schlieren::SamplingSettings SamplingOf(vtkRefractiveIndex* self)
{
  schlieren::SamplingSettings s;
  std::copy(self->GetSamplingDimensions(), self->GetSamplingDimensions() + 3, s.SamplingDimensions);
  s.AutomaticDimension = self->GetAutomaticDimension();
  s.UseSamplingBounds = self->GetUseSamplingBounds() != 0;
  std::copy(self->GetSamplingBounds(), self->GetSamplingBounds() + 6, s.SamplingBounds);
  return s;
}

schlieren::GasChoice GasOf(int gas, double K, double M)
{
  return gas == vtkRefractiveIndex::CUSTOM_GAS
    ? schlieren::GasChoice::Typed(K, M)
    : schlieren::GasChoice::Table(static_cast<schlieren::Gas>(gas));
}

} // namespace

//------------------------------------------------------------------------------
vtkRefractiveIndex::vtkRefractiveIndex()
{
  // port 1: an optional closed surface of a solid body
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(1);
  this->TimeCache = std::make_shared<schlieren::TimeStepCache>();
  // Default: the active point scalars.
  this->SetInputArrayToProcess(
    INPUT_ARRAY, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

//------------------------------------------------------------------------------
vtkRefractiveIndex::~vtkRefractiveIndex() = default;

//------------------------------------------------------------------------------
int vtkRefractiveIndex::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  // Any data set or composite data set: images are used as they are, the rest is resampled. The
  // composite type keeps the executive from running the filter block by block.
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

//------------------------------------------------------------------------------
bool vtkRefractiveIndex::UpdatedInputBounds(
  schlieren::Parallel& parallel, vtkInformation* inInfo, double bounds[6])
{
  // The bounds of a non-image input are known only once it has executed: update it now, for the
  // same piece as RequestUpdateExtent will ask (so that the later update does not run again).
  int producerPort = 0;
  vtkAlgorithm* producer = this->GetInputAlgorithm(0, 0, producerPort);
  if (producer)
  {
    const int none[6] = { 0, -1, 0, -1, 0, -1 };
    SetRequest(inInfo, schlieren::RequestInput(
                         true, false, parallel.Rank(), parallel.Size(), 0, 1, 0, 3, none, none));
    producer->Update(producerPort);
  }
  return GlobalBounds(parallel, vtkDataObject::GetData(inInfo), bounds);
}

//------------------------------------------------------------------------------
bool vtkRefractiveIndex::SamplingGrid(schlieren::Parallel& parallel, vtkInformation* inInfo,
  int whole[6], double origin[3], double spacing[3])
{
  // the rule is the engine's (SchlierenSamplingGrid.h); here the input's bounds, arrays and AMR
  this->SamplingError.clear();
  this->SamplingNote.clear();
  const schlieren::SamplingSettings s = SamplingOf(this);
  schlieren::SamplingGrid grid;
  try
  {
    double bounds[6];
    const bool have = !s.UseSamplingBounds && this->UpdatedInputBounds(parallel, inInfo, bounds);
    double box[6];
    schlieren::SamplingBox(s, have ? bounds : nullptr, box);
    vtkDataObject* input = vtkDataObject::GetData(inInfo);
    const double arrayBytes = ArrayBytesPerPoint(input);
    grid = schlieren::PlanSamplingGrid(s, box, arrayBytes, [&](const double b[6], int dims[3]) {
      double finest[3]; // an AMR input: its finest level's spacing rather than AutomaticDimension
      return schlieren::amr::Dimensions(parallel, input, b,
        schlieren::SamplingBytesPerPoint(arrayBytes) + schlieren::VolumeBytesPerPoint(), dims,
        finest, this->SamplingCapped, this->SamplingNote);
    });
  }
  catch (const schlieren::Error& e)
  {
    this->SamplingError = e.what();
    vtkErrorMacro(<< this->SamplingError);
    return false;
  }
  std::copy(grid.Whole, grid.Whole + 6, whole);
  std::copy(grid.Origin, grid.Origin + 3, origin);
  std::copy(grid.Spacing, grid.Spacing + 3, spacing);
  return true;
}

namespace
{
/**
 * The numeric properties outside their ranges, those of their domains in Schlieren.xml: an error
 * naming the property, the value and the range (empty where all are in range). Checked whatever
 * the model, so that a value is never clamped or taken silently.
 */
std::string PropertyProblem(vtkRefractiveIndex* self)
{
  // the values, read here; their ranges, entries and order are the engine's
  // (schlieren::PropertiesProblem; the Python front end has the same through the C interface)
  auto v = [](std::initializer_list<double> x) { return std::vector<double>(x); };
  const int* species = self->GetSpeciesGases();
  const double* speciesK = self->GetSpeciesGladstoneDale();
  const double* speciesM = self->GetSpeciesMolarMass();
  const int* sampling = self->GetSamplingDimensions();
  const int* walls = self->GetBodyWallFaces();
  const std::map<std::string, std::vector<double>> values = {
    { "GladstoneDaleConstant", v({ self->GetGladstoneDaleConstant() }) },
    { "MolarMass", v({ self->GetMolarMass() }) },
    { "NumberOfSpecies", v({ double(self->GetNumberOfSpecies()) }) },
    { "SpeciesGases",
      v({ double(species[0]), double(species[1]), double(species[2]), double(species[3]) }) },
    { "SpeciesGladstoneDale", std::vector<double>(speciesK, speciesK + 4) },
    { "SpeciesMolarMass", std::vector<double>(speciesM, speciesM + 4) },
    { "BalanceGladstoneDale", v({ self->GetBalanceGladstoneDale() }) },
    { "BalanceMolarMass", v({ self->GetBalanceMolarMass() }) },
    { "DensityReference", v({ self->GetDensityReference() }) },
    { "TemperatureReference", v({ self->GetTemperatureReference() }) },
    { "PressureReference", v({ self->GetPressureReference() }) },
    { "PressureOffset", v({ self->GetPressureOffset() }) },
    { "Humidity", v({ self->GetHumidity() }) }, { "CO2", v({ self->GetCO2() }) },
    { "Wavelength", v({ self->GetWavelength() }) }, { "Span", v({ self->GetSpan() }) },
    { "AutomaticDimension", v({ double(self->GetAutomaticDimension()) }) },
    { "SamplingDimensions", v({ double(sampling[0]), double(sampling[1]), double(sampling[2]) }) },
    { "BodyWallFaces", std::vector<double>(walls, walls + 6) },
    { "PassthroughHoldsN", v({ double(self->GetPassthroughHoldsN()) }) },
    { "HumidityFromArray", v({ double(self->GetHumidityFromArray()) }) },
    { "CO2FromArray", v({ double(self->GetCO2FromArray()) }) },
    { "AxisFromWedge", v({ double(self->GetAxisFromWedge()) }) },
    { "UseSamplingBounds", v({ double(self->GetUseSamplingBounds()) }) },
    { "BodyFromGrid", v({ double(self->GetBodyFromGrid()) }) },
    { "Model", v({ double(self->GetModel()) }) }, { "Gas", v({ double(self->GetGas()) }) },
    { "MixtureComposition", v({ double(self->GetMixtureComposition()) }) },
    { "IdealGasComposition", v({ double(self->GetIdealGasComposition()) }) },
    { "MixtureGas0", v({ double(self->GetMixtureGas0()) }) },
    { "MixtureGas1", v({ double(self->GetMixtureGas1()) }) },
    { "BalanceGas", v({ double(self->GetBalanceGas()) }) },
    { "TemperatureUnit", v({ double(self->GetTemperatureUnit()) }) },
    { "PressureUnit", v({ double(self->GetPressureUnit()) }) },
    { "HumidityMeasure", v({ double(self->GetHumidityMeasure()) }) },
    { "Symmetry", v({ double(self->GetSymmetry()) }) },
    { "SymmetryAxis", v({ double(self->GetSymmetryAxis()) }) },
    { "AmbientMode", v({ double(self->GetAmbientMode()) }) } };
  return schlieren::PropertiesProblem("RefractiveIndex", [&values](const std::string& name) {
    const auto it = values.find(name);
    return it == values.end() ? std::vector<double>() : it->second;
  });
}
} // namespace

//------------------------------------------------------------------------------
int vtkRefractiveIndex::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* input = vtkDataObject::GetData(inInfo);
  const int empty[6] = { 0, -1, 0, -1, 0, -1 };
  const std::string badValue = PropertyProblem(this);
  if (!badValue.empty())
  {
    vtkErrorMacro(<< badValue);
    return 0;
  }
  schlieren::ControllerParallel parallel("RefractiveIndex");
  if (this->Symmetry != NO_SYMMETRY &&
    (vtkDataSet::SafeDownCast(input) || vtkCompositeDataSet::SafeDownCast(input)))
  {
    // A 2D input made into a volume on this filter's grid (vtkRefractiveIndexInputs.cxx).
    int whole[6];
    double origin[3], spacing[3];
    if (!this->SymmetricGrid(inInfo, whole, origin, spacing))
    {
      outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
      return 0;
    }
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
    outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
    outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  }
  else if (vtkImageData::SafeDownCast(input))
  {
    // A 2D image without Symmetry: said here, so that nothing downstream adds its own message.
    const std::string flat = this->FlatInputError(parallel, input);
    if (!flat.empty())
    {
      outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
      vtkErrorMacro(<< flat);
      return 0;
    }
    if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
    {
      return 0;
    }
  }
  else if ((vtkDataSet::SafeDownCast(input) && !vtkPolyData::SafeDownCast(input)) ||
    vtkCompositeDataSet::SafeDownCast(input))
  {
    // Resampled: the grid is this filter's, whatever the input's structure.
    int whole[6];
    double origin[3], spacing[3];
    if (!this->SamplingGrid(parallel, inInfo, whole, origin, spacing))
    {
      outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
      return 0;
    }
    const std::string flat = this->FlatInputError(parallel, vtkDataObject::GetData(inInfo));
    if (!flat.empty())
    {
      this->SamplingError = flat; // repeated by RequestData
      outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
      vtkErrorMacro(<< flat);
      return 0;
    }
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
    outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
    outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  }
  else
  {
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    vtkErrorMacro(<< NotAVolume(input));
    return 0;
  }
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  // Any sub-extent can be computed (from an input one point larger on every side, or from the
  // whole resampled grid).
  outInfo->Set(CAN_PRODUCE_SUB_EXTENT(), 1);
  return 1;
}

//------------------------------------------------------------------------------
namespace
{
/**
 * The key of this update in the per-time-step cache: false where the output is not cached (the
 * input has no time steps, no time is asked for, or more than one process runs).
 */
bool CacheKey(vtkRefractiveIndex* self, vtkInformation* inInfo, vtkInformation* outInfo,
  schlieren::TimeStepCache::Key& key)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  auto* executive = vtkDemandDrivenPipeline::SafeDownCast(self->GetExecutive());
  if (!executive || !inInfo || !outInfo || !inInfo->Has(SDDP::TIME_STEPS()) ||
    !outInfo->Has(SDDP::UPDATE_TIME_STEP()) || schlieren::ControllerParallel().Size() > 1)
  {
    return false;
  }
  key.Time = outInfo->Get(SDDP::UPDATE_TIME_STEP());
  key.Pipeline = executive->GetPipelineMTime();
  if (outInfo->Has(SDDP::UPDATE_EXTENT()))
  {
    outInfo->Get(SDDP::UPDATE_EXTENT(), key.Extent);
  }
  return true;
}

/** The cache's counters in the output's field data (its own copy: the kept entry shares it). */
void CacheFields(vtkDataObject* output, const schlieren::TimeStepCache& cache, bool served)
{
  vtkNew<vtkFieldData> fd;
  if (output->GetFieldData())
  {
    fd->ShallowCopy(output->GetFieldData());
  }
  const std::pair<const char*, double> numbers[] = { { "index_computed", cache.Computed },
    { "index_from_cache", served ? 1.0 : 0.0 }, { "index_cache_entries", double(cache.Size()) },
    { "index_cache_bytes", cache.Held() }, { "index_cache_budget", cache.Budget() } };
  for (const auto& n : numbers)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(n.first);
    a->InsertNextValue(n.second);
    fd->AddArray(a);
  }
  output->SetFieldData(fd);
}
} // namespace

//------------------------------------------------------------------------------
int vtkRefractiveIndex::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  using SDDP = vtkStreamingDemandDrivenPipeline;
  schlieren::TimeStepCache::Key key;
  vtkDataObject* held = vtkDataObject::GetData(inInfo);
  if (CacheKey(this, inInfo, outInfo, key) && this->TimeCache->Find(key) && held &&
    held->GetInformation()->Has(vtkDataObject::DATA_TIME_STEP()))
  {
    // a time step kept: the input stays at the time it holds (it does not execute again)
    inInfo->Set(SDDP::UPDATE_TIME_STEP(), held->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()));
  }
  if (vtkInformation* bodyInfo = inputVector[1]->GetInformationObject(0))
  {
    // the whole body surface on every rank: the inside test needs all of it
    bodyInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
    bodyInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
    bodyInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
  // the engine's rule (schlieren::RequestInput): a resampled or symmetric input whole, an image
  // over the piece the executive will split from the output's update extent (after this call),
  // grown by one point for the central differences
  auto number = [outInfo](vtkInformationIntegerKey* key, int fallback) {
    return outInfo->Has(key) ? outInfo->Get(key) : fallback;
  };
  const bool image = vtkImageData::SafeDownCast(vtkDataObject::GetData(inInfo)) != nullptr;
  int whole[6] = { 0, -1, 0, -1, 0, -1 }, ext[6] = { 0, -1, 0, -1, 0, -1 };
  if (image)
  {
    inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
    outInfo->Get(SDDP::UPDATE_EXTENT(), ext);
  }
  const schlieren::ControllerParallel parallel;
  SetRequest(inInfo,
    schlieren::RequestInput(!image, this->Symmetry != NO_SYMMETRY, parallel.Rank(),
      parallel.Size(), number(SDDP::UPDATE_PIECE_NUMBER(), 0),
      number(SDDP::UPDATE_NUMBER_OF_PIECES(), 1), number(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0),
      number(vtkExtentTranslator::UPDATE_SPLIT_MODE(), vtkExtentTranslator::BLOCK_MODE), ext,
      whole));
  return 1;
}

//------------------------------------------------------------------------------
namespace
{
/** The name chosen for input-array index `idx` ("" if none). */
std::string ChosenName(vtkRefractiveIndex* self, int idx)
{
  // As chosen, or found by name where the choice was left automatic (ResolveChoices).
  return self->GetArrayInUse(idx);
}

/** The composition the model uses (SINGLE_GAS for the models without one). */
int CompositionOf(vtkRefractiveIndex* self)
{
  switch (self->GetModelInUse())
  {
    case vtkRefractiveIndex::GLADSTONE_DALE_MIXTURE:
      return self->GetMixtureComposition();
    case vtkRefractiveIndex::IDEAL_GAS:
      return self->GetIdealGasComposition();
    default:
      return vtkRefractiveIndex::SINGLE_GAS;
  }
}

/** The engine's description of the model, from the filter's properties. */
schlieren::FieldModel ModelOf(vtkRefractiveIndex* self)
{
  schlieren::FieldModel m;
  m.Model = static_cast<schlieren::IndexModel>(self->GetModelInUse());
  m.IndexIsN = self->GetPassthroughHoldsNInUse();
  m.SingleGas = GasOf(self->GetGas(), self->GetGladstoneDaleConstant(), self->GetMolarMass());
  m.Mixture = static_cast<schlieren::Composition>(CompositionOf(self));
  m.Gas0 = static_cast<schlieren::Gas>(self->GetMixtureGas0());
  m.GasF = static_cast<schlieren::Gas>(self->GetMixtureGas1());
  m.NumberOfSpecies = self->GetNumberOfSpecies();
  const int* gases = self->GetSpeciesGases();
  const double* K = self->GetSpeciesGladstoneDale();
  const double* M = self->GetSpeciesMolarMass();
  for (int s = 0; s < 4; ++s)
  {
    m.Species[s] = GasOf(gases[s], K[s], M[s]);
  }
  m.HasBalance = self->GetBalanceGas() != vtkRefractiveIndex::NO_GAS;
  m.Balance = GasOf(std::max(self->GetBalanceGas(), static_cast<int>(vtkRefractiveIndex::CUSTOM_GAS)),
    self->GetBalanceGladstoneDale(), self->GetBalanceMolarMass());
  m.DensityReference = self->GetDensityReference();
  m.TemperatureReference = self->GetTemperatureReference();
  m.TemperatureUnits = static_cast<schlieren::TemperatureUnit>(self->GetTemperatureUnit());
  m.PressureReference = self->GetPressureReference();
  m.PressureOffset = self->GetPressureOffset();
  m.PressureUnits = static_cast<schlieren::PressureUnit>(self->GetPressureUnit());
  m.Humidity = self->GetHumidity();
  m.HumidityKind = static_cast<schlieren::HumidityMeasure>(self->GetHumidityMeasure());
  m.CO2 = self->GetCO2();
  m.Wavelength = self->GetWavelength();
  return m;
}

/** The input-array indices the model reads (the engine's roles are the filter's indices). */
std::vector<int> NeededArrays(vtkRefractiveIndex* self)
{
  return schlieren::NeededRoles(ModelOf(self), self->GetHumidityFromArray() != 0,
    self->GetCO2FromArray() != 0);
}

/**
 * The input probed at the points of `structure` (vtkValidPointMask: 1 where a cell was found).
 * Under MPI each rank probes its own piece; the arrays named in `names` and the mask are summed
 * over the ranks (value x found, found), so that every rank holds them on the whole grid.
 */
vtkSmartPointer<vtkImageData> Resample(schlieren::Parallel& parallel, vtkDataObject* input,
  vtkImageData* structure, const std::vector<std::string>& names)
{
  vtkSmartPointer<vtkImageData> grid;
  std::string refused;
  try
  {
    grid = schlieren::SampleCells(input, structure); // cell by cell (blocks of images too)
  }
  catch (const schlieren::Error& e)
  {
    refused = e.what(); // a cell type the sampler does not take (a polyhedron)
  }
  // a piece refused fails every rank, so that none waits for it in the sums below
  schlieren::AgreeOnRefusal(parallel, refused);
  if (!grid || grid->GetNumberOfPoints() != structure->GetNumberOfPoints())
  {
    // An empty piece of the input (MPI): nothing found here.
    grid = vtkSmartPointer<vtkImageData>::New();
    grid->CopyStructure(structure);
  }
  if (parallel.Size() <= 1)
  {
    return grid;
  }
  // the pieces summed over the ranks by the engine (value x found, found): here their reading
  const vtkIdType n = grid->GetNumberOfPoints();
  std::vector<unsigned char> found(static_cast<std::size_t>(n), 0);
  if (vtkDataArray* mask = grid->GetPointData()->GetArray(MaskName))
  {
    schlieren::values::ForEachFirstComponent(mask, [&](vtkIdType i, double v) {
      if (i < n)
      {
        found[i] = v != 0.0 ? 1 : 0;
      }
    });
  }
  std::vector<schlieren::ProbedArray> probed(names.size());
  for (std::size_t k = 0; k < names.size(); ++k)
  {
    probed[k].Name = names[k];
    vtkDataArray* a = grid->GetPointData()->GetArray(names[k].c_str());
    probed[k].Have = a && a->GetNumberOfComponents() == 1;
    if (probed[k].Have)
    {
      probed[k].Values.assign(static_cast<std::size_t>(n), 0.0);
      schlieren::values::ForEachFirstComponent(a, [&](vtkIdType i, double v) {
        if (i < n)
        {
          probed[k].Values[i] = v;
        }
      });
    }
  }
  std::vector<unsigned char> valid;
  std::vector<schlieren::MergedArray> merged;
  schlieren::MergeProbedPieces(parallel, found, probed, valid, merged);
  vtkNew<vtkImageData> reduced;
  reduced->CopyStructure(structure);
  vtkNew<vtkCharArray> validMask;
  validMask->SetName(MaskName);
  validMask->SetNumberOfTuples(n);
  std::copy(valid.begin(), valid.end(), validMask->GetPointer(0));
  reduced->GetPointData()->AddArray(validMask);
  for (const schlieren::MergedArray& m : merged)
  {
    vtkNew<vtkFloatArray> r;
    r->SetName(m.Name.c_str());
    r->SetNumberOfTuples(n);
    std::copy(m.Values.begin(), m.Values.end(), r->GetPointer(0));
    reduced->GetPointData()->AddArray(r);
  }
  return reduced;
}


} // namespace

//------------------------------------------------------------------------------
/** What the steps of RequestData pass each other. */
struct vtkRefractiveIndex::Work
{
  Work(schlieren::Parallel& parallel, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector, bool symmetric)
    : Ranks(parallel)
    , InputVector(inputVector)
    , InInfo(inputVector[0]->GetInformationObject(0))
    , OutInfo(outputVector->GetInformationObject(0))
    , Input(vtkDataObject::GetData(InInfo))
    , InputImage(vtkImageData::SafeDownCast(Input))
    , Output(vtkImageData::GetData(OutInfo))
    , Symmetric(symmetric)
    , Resampled(InputImage == nullptr || symmetric)
  {
  }
  /** Where `cache` holds this time step (computed before, with the same pipeline): the output is
   * that image, not resampled again (true). */
  bool ServeKept(schlieren::TimeStepCache& cache, const schlieren::TimeStepCache::Key& key)
  {
    vtkDataObject* kept = cache.Find(key);
    if (!kept)
      return false;
    this->Output->ShallowCopy(kept);
    this->Output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), key.Time);
    if (this->Resampled)
    {
      // the grid of that step (FollowMovingBounds may have moved it since): what SchlierenImage
      // reads from the information must be the kept image's
      this->OutInfo->Set(vtkDataObject::ORIGIN(), this->Output->GetOrigin(), 3);
      this->OutInfo->Set(vtkDataObject::SPACING(), this->Output->GetSpacing(), 3);
    }
    ++cache.Served;
    CacheFields(this->Output, cache, true);
    return true;
  }
  schlieren::Parallel& Ranks;
  vtkInformationVector** InputVector = nullptr;
  vtkInformation* InInfo = nullptr;
  vtkInformation* OutInfo = nullptr;
  vtkDataObject* Input = nullptr; // the input, or its copy with cell arrays made point arrays
  vtkImageData* InputImage = nullptr;
  vtkSmartPointer<vtkDataObject> PointInput;
  vtkDataSet* Mesh = nullptr; // the input mesh as read (its velocity tells its walls)
  vtkImageData* Output = nullptr;
  bool Symmetric = false;
  bool Resampled = false; // the grid is this filter's (a non-image or a symmetric input)
  std::vector<std::string> Notes;
  std::vector<int> Needed;
  int OutExt[6], Whole[6], GridExt[6];
  vtkSmartPointer<vtkImageData> Grid; // the input image's (grown) piece, or the resampled grid
  vtkIdType Count = 0;
  bool EmptyPiece = false;
  // the engine's inputs and results on the grid (schlieren::ComputeIndexField)
  std::vector<unsigned char> Valid;
  bool AnyInvalid = false;
  std::vector<std::string> Warnings;
  vtkNew<vtkFloatArray> NMinus1;
  vtkNew<vtkFloatArray> Gradient;
  schlieren::IndexFieldOutput Field;
  std::vector<std::pair<std::string, double>> Numbers; // more field data (an AMR input's levels)
};

//------------------------------------------------------------------------------
void vtkRefractiveIndex::SayNote(const std::string& note)
{
  // the notes said belong to the settings they were said for (time steps repeat none: issue 49
  // saw the three lines of Model Automatic's choice added again at every step)
  if (this->GetMTime() != this->SaidNotesTime)
  {
    this->SaidNotes.clear();
    this->SaidNotesTime = this->GetMTime();
  }
  if (this->SaidNotes.insert(note).second)
  {
    vtkOutputWindowDisplayText((note + "\n").c_str());
  }
}

//------------------------------------------------------------------------------
int vtkRefractiveIndex::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const std::string badValue = PropertyProblem(this);
  if (!badValue.empty())
  {
    vtkErrorMacro(<< badValue);
    return 0;
  }
  schlieren::ControllerParallel parallel("RefractiveIndex");
  Work w(parallel, inputVector, outputVector, this->Symmetry != NO_SYMMETRY);
  if (!w.Output || (vtkPolyData::SafeDownCast(w.Input) && !w.Symmetric) ||
    (!vtkDataSet::SafeDownCast(w.Input) && !vtkCompositeDataSet::SafeDownCast(w.Input)))
  {
    vtkErrorMacro(<< NotAVolume(w.Input));
    return 0;
  }
  schlieren::TimeStepCache::Key key;
  const bool cached = CacheKey(this, w.InInfo, w.OutInfo, key);
  if (cached && w.ServeKept(*this->TimeCache, key))
  {
    return 1;
  }
  // 0. What to read; 1. the grid the model runs on; 2. the engine's work on it: the model, under
  // MPI the agreement of the ranks, the points outside the flow, the gradient, the bodies.
  std::string problem = this->ReadInputs(w);
  problem = problem.empty() ? this->MakeGrid(w) : problem;
  problem = problem.empty() ? this->ComputeOnGrid(w) : problem;
  if (problem.empty() || w.Field.ModelDone)
  {
    for (const std::string& warning : w.Warnings)
    {
      vtkWarningMacro(<< warning);
    }
    for (const std::string& warning : w.Field.Warnings)
    {
      vtkWarningMacro(<< warning);
    }
  }
  if (problem.empty() && w.Field.EmptyPiece)
  {
    w.Output->Initialize();
    return 1;
  }
  for (const std::string& note : w.Field.NewNotes)
  {
    this->SayNote(note);
  }
  if (!problem.empty())
  {
    w.Output->Initialize();
    vtkErrorMacro(<< problem);
    return 0;
  }
  if (!w.Field.SolidNote.empty() && parallel.Rank() == 0)
  {
    vtkWarningMacro(<< w.Field.SolidNote);
  }
  this->UpdateProgress(0.9);
  // 5. The output: the requested extent of the grid, with the new arrays.
  this->WriteOutput(w);
  ++this->TimeCache->Computed;
  if (cached)
  {
    this->TimeCache->Insert(key, w.Output);
  }
  CacheFields(w.Output, *this->TimeCache, false);
  return 1;
}

//------------------------------------------------------------------------------
std::string vtkRefractiveIndex::ReadInputs(Work& w)
{
  // A 2D input without Symmetry is one clear error (vtkRefractiveIndexInputs.cxx); the model and
  // the arrays left automatic are resolved by name; ids and integer arrays are refused; cell
  // arrays become point arrays.
  // an OpenFOAM case: its internal mesh (the patches are surfaces of it, with no volume to probe)
  std::string meshNote;
  w.Input = InternalMesh(w.Input, &meshNote);
  w.Mesh = vtkDataSet::SafeDownCast(w.Input);
  if (w.Symmetric && !this->WedgeNote.empty())
  {
    w.Notes.push_back(this->WedgeNote);
  }
  if (!w.Symmetric && w.Ranks.Rank() == 0)
  {
    const std::string wedge = this->WedgeWithoutSymmetry(w.Input);
    if (!wedge.empty())
    {
      w.Warnings.push_back(wedge);
    }
  }
  if (!meshNote.empty())
  {
    w.Notes.push_back(meshNote);
  }
  int outWhole[6];
  w.OutInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), outWhole);
  if (!w.Resampled || (!IsEmpty(outWhole) && w.OutInfo->Has(vtkDataObject::ORIGIN())))
  {
    // (without a resampling grid, RequestInformation's error is repeated by MakeGrid instead)
    std::string problem = this->FlatInputError(w.Ranks, w.Input);
    if (problem.empty())
    {
      problem = this->ResolveChoices(w.Ranks, w.Input, w.Notes);
    }
    std::vector<std::string> readNames;
    for (int idx : NeededArrays(this))
    {
      const std::string name = ChosenName(this, idx);
      if (!name.empty())
      {
        readNames.push_back(name);
      }
    }
    if (problem.empty())
    {
      w.PointInput = this->PointFields(w.Ranks, w.Input, readNames, w.Notes, problem);
    }
    if (!problem.empty())
    {
      return problem;
    }
    for (const std::string& note : w.Notes)
    {
      if (w.Ranks.Rank() == 0) // the same on every rank: said once
      {
        this->SayNote(note);
      }
    }
    if (w.PointInput != w.Input)
    {
      w.Input = w.PointInput;
      w.InputImage = vtkImageData::SafeDownCast(w.Input);
    }
  }
  w.Needed = NeededArrays(this);
  return std::string();
}


//------------------------------------------------------------------------------
namespace
{
/** "N cells: a of them 3D, b 2D, c 1D or 0D" of a data set or the leaves of a composite one. */
std::string DescribeCells(vtkDataObject* data)
{
  vtkIdType counts[4] = { 0, 0, 0, 0 };
  auto count = [&](vtkDataSet* ds) {
    for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c)
    {
      const int d = vtkCellTypes::GetDimension(static_cast<unsigned char>(ds->GetCellType(c)));
      ++counts[std::max(0, std::min(3, d))];
    }
  };
  if (auto* ds = vtkDataSet::SafeDownCast(data))
  {
    count(ds);
  }
  else if (auto* cds = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkCompositeDataIterator* iter = cds->NewIterator();
    for (iter->InitTraversal(); !iter->IsDoneWithTraversal(); iter->GoToNextItem())
    {
      if (auto* leaf = vtkDataSet::SafeDownCast(iter->GetCurrentDataObject()))
      {
        count(leaf);
      }
    }
    iter->Delete();
  }
  std::ostringstream m;
  m << counts[0] + counts[1] + counts[2] + counts[3] << " cells: " << counts[3] << " 3D, "
    << counts[2] << " 2D (faces), " << counts[0] + counts[1] << " 1D or 0D";
  return m.str();
}
} // namespace

//------------------------------------------------------------------------------
void vtkRefractiveIndex::FollowMovingBounds(Work& w)
{
  // RequestInformation set the grid over the input's bounds then (the first time step it saw);
  // a mesh that moves over time has other bounds now: the grid follows them, with the same
  // points (the extent downstream asked for), so that each step is sampled over its own box
  // (issue 48: the first step's box was kept, |dI| 0.2-0.5 against each step alone). Collective
  // under MPI, as UpdatedInputBounds.
  double bounds[6];
  if (!GlobalBounds(w.Ranks, w.Input, bounds))
  {
    return;
  }
  schlieren::SamplingGrid grid, moved;
  std::copy(w.Whole, w.Whole + 6, grid.Whole);
  w.OutInfo->Get(vtkDataObject::ORIGIN(), grid.Origin);
  w.OutInfo->Get(vtkDataObject::SPACING(), grid.Spacing);
  std::string note;
  if (!schlieren::FollowBounds(grid, bounds, moved, &note)) // the engine's rule
  {
    return;
  }
  w.OutInfo->Set(vtkDataObject::ORIGIN(), moved.Origin, 3);
  w.OutInfo->Set(vtkDataObject::SPACING(), moved.Spacing, 3);
  w.Notes.push_back(note);
  if (w.Ranks.Rank() == 0)
  {
    vtkOutputWindowDisplayText((note + "\n").c_str());
  }
}

//------------------------------------------------------------------------------
std::string vtkRefractiveIndex::MakeGrid(Work& w)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  w.OutInfo->Get(SDDP::UPDATE_EXTENT(), w.OutExt);
  if (!w.Resampled)
  {
    w.InInfo->Get(SDDP::WHOLE_EXTENT(), w.Whole);
    w.Grid = w.InputImage;
  }
  else
  {
    // the whole resampling grid, on every rank
    w.OutInfo->Get(SDDP::WHOLE_EXTENT(), w.Whole);
    if (IsEmpty(w.Whole) || !w.OutInfo->Has(vtkDataObject::ORIGIN()))
    {
      // RequestInformation could not set up the grid (and said why then): say it again.
      return this->SamplingError.empty()
        ? std::string("No resampling grid: the pipeline information was not updated.")
        : this->SamplingError;
    }
    if (!w.Symmetric && !this->UseSamplingBounds && !vtkOverlappingAMR::SafeDownCast(w.Input))
    {
      this->FollowMovingBounds(w);
    }
    vtkNew<vtkImageData> structure;
    structure->SetExtent(w.Whole);
    structure->SetOrigin(w.OutInfo->Get(vtkDataObject::ORIGIN()));
    structure->SetSpacing(w.OutInfo->Get(vtkDataObject::SPACING()));
    std::vector<std::string> names;
    for (int idx : w.Needed)
    {
      const std::string name = ChosenName(this, idx);
      if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end())
      {
        names.push_back(name);
      }
    }
    if (!this->SolidArray.empty() &&
      std::find(names.begin(), names.end(), this->SolidArray) == names.end())
    {
      names.push_back(this->SolidArray); // probed with the fields
    }
    if (w.Ranks.Size() <= 1)
    {
      // under MPI a missing array is reported after the probing, since a rank's piece may be empty
      // reported before the (costly) probing
      const std::string missing = schlieren::MissingArrayProblem(names, InputArrayNames(w.Input),
        schlieren::IndexModelLabel(static_cast<schlieren::IndexModel>(this->GetModelInUse())));
      if (!missing.empty())
      {
        return missing;
      }
    }
    auto* amr = vtkOverlappingAMR::SafeDownCast(w.Input);
    if (amr && !w.Symmetric)
    {
      std::vector<std::string> notes;
      if (!this->SamplingNote.empty())
      {
        notes.push_back(this->SamplingNote);
      }
      const std::string overlap = schlieren::amr::OverlapProblem(amr);
      if (!overlap.empty())
      {
        return overlap; // the same on every rank (from the metadata): before the collective steps
      }
      w.Grid = schlieren::amr::Resample(w.Ranks, amr, structure, names, notes);
      double finest[3];
      int level = 0, levels = 0;
      schlieren::amr::FinestSpacing(w.Ranks, amr, finest, level, levels);
      w.Numbers = { { "amr_levels", levels }, { "amr_finest_level", level },
        { "amr_finest_spacing", finest[0] }, { "sampling_spacing", structure->GetSpacing()[0] },
        { "sampling_capped", this->SamplingCapped && !this->SamplingNote.empty() ? 1 : 0 } };
      for (const std::string& note : notes)
      {
        if (w.Ranks.Rank() == 0)
        {
          this->SayNote(note);
        }
        w.Notes.push_back(note);
      }
    }
    else
    {
      w.Grid = w.Symmetric ? this->SymmetricResample(w.Input, structure, names)
                           : Resample(w.Ranks, w.Input, structure, names);
    }
    this->UpdateProgress(0.4);
  }
  w.Count = w.Grid->GetNumberOfPoints();
  w.EmptyPiece = !w.Resampled && (IsEmpty(w.OutExt) || w.Count == 0);
  w.Grid->GetExtent(w.GridExt);
  return std::string();
}

//------------------------------------------------------------------------------
//------------------------------------------------------------------------------
void vtkRefractiveIndex::WriteOutput(Work& w)
{
  vtkNew<vtkPointData> pointData;
  pointData->ShallowCopy(w.Grid->GetPointData());
  if (!w.AnyInvalid && w.Resampled)
  {
    pointData->RemoveArray(MaskName); // every point was found: the mask says nothing
  }
  pointData->AddArray(w.Gradient);
  pointData->AddArray(w.NMinus1);
  if (!w.Field.Solid.empty())
  {
    vtkNew<vtkUnsignedCharArray> solid;
    solid->SetName(schlieren::arrays::Solid);
    solid->SetNumberOfTuples(w.Count);
    std::copy(w.Field.Solid.begin(), w.Field.Solid.end(), solid->GetPointer(0));
    pointData->AddArray(solid);
  }
  pointData->SetActiveScalars(schlieren::arrays::NMinus1);

  vtkImageData* output = w.Output;
  output->Initialize();
  if (std::equal(w.GridExt, w.GridExt + 6, w.OutExt))
  {
    output->CopyStructure(w.Grid);
    output->GetPointData()->ShallowCopy(pointData);
    if (!w.Resampled)
    {
      output->GetCellData()->ShallowCopy(w.Grid->GetCellData());
    }
  }
  else
  {
    output->SetExtent(w.OutExt);
    output->SetOrigin(w.Grid->GetOrigin());
    output->SetSpacing(w.Grid->GetSpacing());
    output->SetDirectionMatrix(w.Grid->GetDirectionMatrix());
    output->GetPointData()->CopyAllocate(pointData, output->GetNumberOfPoints());
    output->GetPointData()->CopyStructuredData(pointData, w.GridExt, w.OutExt);
    if (!w.Resampled)
    {
      int inCells[6], outCells[6];
      CellExtent(w.Whole, w.GridExt, inCells);
      CellExtent(w.Whole, w.OutExt, outCells);
      output->GetCellData()->CopyAllocate(w.Grid->GetCellData(), output->GetNumberOfCells());
      output->GetCellData()->CopyStructuredData(w.Grid->GetCellData(), inCells, outCells);
    }
  }
  output->GetPointData()->SetActiveScalars(schlieren::arrays::NMinus1);
  // the field data: the input image's, then the engine's (what was read, for scripts and for the
  // GUI's information panel)
  vtkNew<vtkFieldData> fieldData;
  if (!w.Resampled && w.InputImage->GetFieldData())
  {
    fieldData->ShallowCopy(w.InputImage->GetFieldData());
  }
  for (const schlieren::IndexFieldValue& v : w.Field.FieldData)
  {
    if (v.IsText)
    {
      vtkNew<vtkStringArray> a;
      a->SetName(v.Name.c_str());
      for (const std::string& t : v.Texts)
      {
        a->InsertNextValue(t);
      }
      fieldData->AddArray(a);
    }
    else
    {
      vtkNew<vtkDoubleArray> a;
      a->SetName(v.Name.c_str());
      a->InsertNextValue(v.Number);
      fieldData->AddArray(a);
    }
  }
  output->GetFieldData()->ShallowCopy(fieldData);
}

//------------------------------------------------------------------------------
namespace
{
/**
 * Marks `inside` at the points of `grid` inside the one closed shell `shell` (tested only within
 * its bounds); `overlapsAny` is set where its bounds overlap the grid. False where the inside test
 * gave no result.
 */
bool MarkInsideShell(vtkPolyData* shell, vtkImageData* grid, const int dims[3],
  std::vector<unsigned char>& inside, bool& overlapsAny)
{
  double b[6];
  shell->GetBounds(b);
  const double* origin = grid->GetOrigin();
  const double* spacing = grid->GetSpacing();
  int ext[6];
  grid->GetExtent(ext);
  int sub[6];
  bool overlaps = true;
  for (int a = 0; a < 3; ++a)
  {
    sub[2 * a] =
      std::max(ext[2 * a], static_cast<int>(std::floor((b[2 * a] - origin[a]) / spacing[a])));
    sub[2 * a + 1] = std::min(
      ext[2 * a + 1], static_cast<int>(std::ceil((b[2 * a + 1] - origin[a]) / spacing[a])));
    overlaps = overlaps && sub[2 * a] <= sub[2 * a + 1];
  }
  if (overlaps)
  {
    vtkNew<vtkImageData> box;
    box->SetExtent(sub);
    box->SetOrigin(grid->GetOrigin());
    box->SetSpacing(grid->GetSpacing());
    vtkNew<vtkSelectEnclosedPoints> select;
    select->SetInputData(box);
    select->SetSurfaceData(shell);
    select->CheckSurfaceOff(); // checked above, with a message of our own
    select->Update();
    vtkDataArray* selected =
      select->GetOutput()->GetPointData()->GetArray("SelectedPoints");
    if (!selected)
    {
      return false;
    }
    std::vector<unsigned char> enclosed(static_cast<std::size_t>(selected->GetNumberOfTuples()));
    schlieren::values::ForEachFirstComponent(
      selected, [&](vtkIdType i, double v) { enclosed[i] = v != 0.0 ? 1 : 0; });
    vtkIdType p = 0;
    for (int k = sub[4]; k <= sub[5]; ++k)
    {
      for (int j = sub[2]; j <= sub[3]; ++j)
      {
        for (int i = sub[0]; i <= sub[1]; ++i, ++p)
        {
          if (enclosed[p])
          {
            const vtkIdType g =
              (static_cast<vtkIdType>(k - ext[4]) * dims[1] + (j - ext[2])) * dims[0] +
              (i - ext[0]);
            inside[g] = 1;
          }
        }
      }
    }
  }
  overlapsAny = overlapsAny || overlaps;
  return true;
}

/**
 * Marks `solid` at the points of `grid` inside the closed `surface` (tested only within the
 * surface's bounds); `any` is set where it marked one. "" or the error for the user; `note` gets
 * a surface that encloses no point (the engine's MarkBodySurface, which the Python front end's
 * test of the surface reaches through schlieren_index_field).
 */
std::string SurfaceSolid(vtkPolyData* surface, vtkImageData* grid, unsigned char* solid,
  bool& any, std::string& note)
{
  int dims[3];
  grid->GetDimensions(dims);
  if (surface->GetNumberOfPolys() == 0 && surface->GetNumberOfStrips() == 0)
  {
    return schlieren::BodySurfaceProblem(schlieren::BodySurface::NoPolygons);
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(surface);
  triangles->PassLinesOff();
  triangles->PassVertsOff();
  triangles->Update();
  vtkPolyData* closed = triangles->GetOutput();
  if (!vtkSelectEnclosedPoints::IsSurfaceClosed(closed))
  {
    return schlieren::BodySurfaceProblem(schlieren::BodySurface::NotClosed);
  }
  // Each connected shell is tested alone and the results are ORed: one inside test over
  // overlapping shells counts crossings of both (even-odd) and leaves their overlap empty. (A
  // sealed cavity inside a body is filled: no light reaches it either way.)
  vtkNew<vtkPolyDataConnectivityFilter> shells;
  shells->SetInputData(closed);
  shells->SetExtractionModeToAllRegions();
  shells->Update();
  const int regions = shells->GetNumberOfExtractedRegions();
  const std::size_t count = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::vector<unsigned char> inside(count, 0);
  bool overlaps = false;
  if (regions <= 1)
  {
    if (!MarkInsideShell(closed, grid, dims, inside, overlaps))
      return schlieren::BodySurfaceProblem(schlieren::BodySurface::NoInsideTest);
  }
  else
  {
    for (int r = 0; r < regions; ++r)
    {
      vtkNew<vtkPolyDataConnectivityFilter> one;
      one->SetInputData(closed);
      one->SetExtractionModeToSpecifiedRegions();
      one->AddSpecifiedRegion(r);
      one->Update();
      if (!MarkInsideShell(one->GetOutput(), grid, dims, inside, overlaps))
        return schlieren::BodySurfaceProblem(schlieren::BodySurface::NoInsideTest);
    }
  }
  schlieren::MarkBodySurface(inside.data(), count, overlaps, solid, any, note);
  return std::string();
}

} // namespace

//------------------------------------------------------------------------------
std::string vtkRefractiveIndex::ComputeOnGrid(Work& w)
{
  static_assert(int(schlieren::RoleInput) == int(INPUT_ARRAY) &&
      int(schlieren::RoleSpecies) == int(SPECIES_ARRAY) && int(schlieren::RoleCO2) == int(CO2_ARRAY),
    "the engine's roles are the filter's input-array indices");
  w.NMinus1->SetName(schlieren::arrays::NMinus1);
  w.NMinus1->SetNumberOfTuples(w.Count);
  w.Gradient->SetName(schlieren::arrays::GradN);
  w.Gradient->SetNumberOfComponents(3);
  w.Gradient->SetNumberOfTuples(w.Count);
  schlieren::IndexFieldInput in;
  in.NMinus1 = w.NMinus1->GetPointer(0);
  in.Gradient = w.Gradient->GetPointer(0);
  in.EmptyPiece = w.EmptyPiece;
  if (!w.EmptyPiece)
  {
    w.Grid->GetDimensions(in.Dims);
    w.Grid->GetSpacing(in.Spacing);
    in.PieceFailure = schlieren::ExtentCoverProblem(w.GridExt, w.OutExt);
    w.Valid = Validity(w.Grid, w.AnyInvalid);
    in.Valid = w.AnyInvalid ? w.Valid.data() : nullptr;
  }
  else
  {
    in.Dims[0] = in.Dims[1] = in.Dims[2] = 0;
  }
  std::copy(w.GridExt, w.GridExt + 6, in.GridExtent);
  std::copy(w.OutExt, w.OutExt + 6, in.OutExtent);
  std::copy(w.Whole, w.Whole + 6, in.WholeExtent);
  for (int idx = 0; idx < schlieren::NumberOfRoles; ++idx)
  {
    in.ArrayNames[idx] = ChosenName(this, idx);
  }
  // the grid's point arrays: every name (for messages), the values of those the engine may read
  std::vector<std::string> read = { schlieren::arrays::Solid, this->SolidArray };
  for (int idx : w.Needed)
  {
    read.push_back(in.ArrayNames[idx]);
  }
  vtkPointData* pd = w.Grid->GetPointData();
  if (in.ArrayNames[INPUT_ARRAY].empty())
  {
    // none chosen: the engine takes the active scalars, else the first point array
    vtkDataArray* a = pd->GetScalars();
    for (int i = 0; !a && i < pd->GetNumberOfArrays(); ++i)
    {
      const char* n = pd->GetArrayName(i);
      a = n && std::string(n) == MaskName ? nullptr : pd->GetArray(i);
    }
    if (a && a->GetName())
    {
      read.emplace_back(a->GetName());
    }
  }
  std::vector<std::vector<double>> converted;
  for (int i = 0; !w.EmptyPiece && i < pd->GetNumberOfArrays(); ++i)
  {
    const char* name = pd->GetArrayName(i);
    if (name && std::string(name) == MaskName)
    {
      continue;
    }
    vtkDataArray* a = pd->GetArray(i);
    schlieren::GridArray g;
    g.Name = name ? name : "";
    g.Components = a ? a->GetNumberOfComponents() : 0;
    const bool first = in.PointArrays.empty() ||
      std::none_of(in.PointArrays.begin(), in.PointArrays.end(),
        [&g](const schlieren::GridArray& o) { return o.Name == g.Name; });
    if (a && a->GetNumberOfComponents() == 1 && name && first &&
      std::find(read.begin(), read.end(), g.Name) != read.end())
    {
      if (auto* f = vtkFloatArray::FastDownCast(a))
      {
        g.Float = f->GetPointer(0);
      }
      else
      {
        converted.push_back(schlieren::values::Values<double>(a));
        g.Double = converted.back().data();
      }
    }
    if (a && a == pd->GetScalars())
    {
      in.ActiveScalars = static_cast<int>(in.PointArrays.size());
    }
    if (a)
    {
      in.PointArrays.push_back(g);
    }
  }
  vtkCellData* cd = w.Grid->GetCellData();
  for (int i = 0; !w.EmptyPiece && i < cd->GetNumberOfArrays(); ++i)
  {
    if (cd->GetArray(i) && cd->GetArrayName(i))
    {
      in.CellArrayNames.emplace_back(cd->GetArrayName(i));
    }
  }
  in.Model = ModelOf(this);
  in.HumidityFromArray = this->HumidityFromArray != 0;
  in.CO2FromArray = this->CO2FromArray != 0;
  in.Resampled = w.Resampled;
  in.UseSamplingBounds = this->UseSamplingBounds != 0;
  vtkDataObject* input = w.Input;
  in.DescribeCells = [input] { return DescribeCells(input); };
  in.Ambient = static_cast<schlieren::AmbientFill>(this->AmbientMode);
  in.AmbientValue = this->AmbientValue;
  in.BodyFromGrid = this->BodyFromGrid != 0;
  std::copy(this->BodyWallFaces, this->BodyWallFaces + 6, in.WallFaces);
  if (w.Mesh)
  {
    in.BesideWalls = [this, &w](const unsigned char* valid, unsigned char* solid, std::string& note) {
      return this->BodiesBesideWalls(w.Mesh, w.Grid, valid, solid, note);
    };
  }
  in.SolidArray = this->SolidArray;
  vtkPolyData* surface = w.InputVector[1] && w.InputVector[1]->GetInformationObject(0)
    ? vtkPolyData::GetData(w.InputVector[1]->GetInformationObject(0))
    : nullptr;
  if (surface)
  {
    in.Surface = [surface, &w](unsigned char* solid, bool& any, std::string& note) {
      return SurfaceSolid(surface, w.Grid, solid, any, note);
    };
  }
  in.Notes = w.Notes;
  in.Numbers = w.Numbers;
  return schlieren::ComputeIndexField(w.Ranks, in, w.Field);
}

//------------------------------------------------------------------------------
void vtkRefractiveIndex::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Model: " << this->Model << " (" << schlieren::IndexModelLabel(static_cast<schlieren::IndexModel>(this->GetModelInUse())) << ")\n";
  os << indent << "PassthroughHoldsN: " << this->PassthroughHoldsN << "\n";
  os << indent << "Gas: " << this->Gas << "\n";
  os << indent << "GladstoneDaleConstant: " << this->GladstoneDaleConstant << " m^3/kg\n";
  os << indent << "MolarMass: " << this->MolarMass << " kg/mol\n";
  os << indent << "MixtureComposition: " << this->MixtureComposition << "\n";
  os << indent << "IdealGasComposition: " << this->IdealGasComposition << "\n";
  os << indent << "MixtureGas0: " << this->MixtureGas0 << "\n";
  os << indent << "MixtureGas1: " << this->MixtureGas1 << "\n";
  os << indent << "NumberOfSpecies: " << this->NumberOfSpecies << "\n";
  for (int s = 0; s < 4; ++s)
  {
    os << indent << "Species " << s + 1 << ": gas " << this->SpeciesGases[s] << ", K "
       << this->SpeciesGladstoneDale[s] << " m^3/kg, M " << this->SpeciesMolarMass[s]
       << " kg/mol\n";
  }
  os << indent << "BalanceGas: " << this->BalanceGas << " (K " << this->BalanceGladstoneDale
     << " m^3/kg, M " << this->BalanceMolarMass << " kg/mol)\n";
  os << indent << "TemperatureUnit: " << this->TemperatureUnit << "\n";
  os << indent << "PressureUnit: " << this->PressureUnit << "\n";
  os << indent << "DensityReference: " << this->DensityReference << "\n";
  os << indent << "TemperatureReference: " << this->TemperatureReference << "\n";
  os << indent << "PressureReference: " << this->PressureReference << "\n";
  os << indent << "PressureOffset: " << this->PressureOffset << "\n";
  os << indent << "Humidity: " << this->Humidity << " (from array: " << this->HumidityFromArray
     << ", measure " << this->HumidityMeasure << ")\n";
  os << indent << "CO2: " << this->CO2 << " umol/mol (from array: " << this->CO2FromArray << ")\n";
  os << indent << "Wavelength: " << this->Wavelength << " nm\n";
  os << indent << "SamplingDimensions: " << this->SamplingDimensions[0] << " "
     << this->SamplingDimensions[1] << " " << this->SamplingDimensions[2] << "\n";
  os << indent << "AutomaticDimension: " << this->AutomaticDimension << "\n";
  os << indent << "UseSamplingBounds: " << this->UseSamplingBounds << "\n";
  os << indent << "SamplingBounds:";
  for (double b : this->SamplingBounds)
  {
    os << " " << b;
  }
  os << "\n";
  os << indent << "AmbientMode: " << this->AmbientMode << "\n";
  os << indent << "AmbientValue: " << this->AmbientValue << "\n";
  os << indent << "BodyFromGrid: " << (this->BodyFromGrid ? "On" : "Off") << ", BodyWallFaces: "
     << this->BodyWallFaces[0] << " " << this->BodyWallFaces[1] << " " << this->BodyWallFaces[2]
     << " " << this->BodyWallFaces[3] << " " << this->BodyWallFaces[4] << " "
     << this->BodyWallFaces[5] << ", SolidArray: "
     << (this->SolidArray.empty() ? std::string("(none)") : this->SolidArray) << "\n";
}

//------------------------------------------------------------------------------
vtkExecutive* vtkRefractiveIndex::CreateDefaultExecutive()
{
  return schlieren::NewAgreeingExecutive();
}

vtkTypeBool vtkRefractiveIndex::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return SchlierenGuarded(this,
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); });
}
