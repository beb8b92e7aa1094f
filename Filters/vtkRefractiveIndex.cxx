// SPDX-License-Identifier: BSD-3-Clause
#include "vtkRefractiveIndex.h"
#include "SchlierenGuard.h"

#include "vtkBoundingBox.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataProbeFilter.h"
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
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSelectEnclosedPoints.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include "SchlierenBodies.h"
#include "SchlierenEngine.h"
#include "SchlierenIndexModels.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkRefractiveIndex);

namespace
{
const char* const MaskName = "vtkValidPointMask";

/** "a, b, c" for the point arrays of a data set, or "none". */
std::string PointArrayNames(vtkDataSet* ds)
{
  vtkPointData* pd = ds->GetPointData();
  std::ostringstream names;
  int shown = 0;
  for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
  {
    const char* name = pd->GetArrayName(i);
    if (name && std::string(name) == MaskName)
    {
      continue;
    }
    names << (shown++ ? ", " : "") << (name ? name : "(unnamed)");
  }
  const std::string s = names.str();
  return s.empty() ? std::string("none") : s;
}

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

/** The rank and number of processes of the global controller (0 and 1 without one). */
void RankAndSize(int& rank, int& size)
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  rank = c ? c->GetLocalProcessId() : 0;
  size = c ? std::max(c->GetNumberOfProcesses(), 1) : 1;
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

/** A 1-component array as floats. */
std::vector<float> AsFloat(vtkDataArray* a)
{
  const vtkIdType n = a->GetNumberOfTuples();
  std::vector<float> v(static_cast<std::size_t>(n));
  if (auto* f = vtkFloatArray::SafeDownCast(a))
  {
    std::copy(f->GetPointer(0), f->GetPointer(0) + n, v.begin());
  }
  else
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      v[i] = static_cast<float>(a->GetComponent(i, 0));
    }
  }
  return v;
}

/** 1 where a point of `image` is in the flow (vtkValidPointMask != 0 and not a hidden point). */
std::vector<unsigned char> Validity(vtkImageData* image, bool& any)
{
  const vtkIdType n = image->GetNumberOfPoints();
  std::vector<unsigned char> valid(static_cast<std::size_t>(n), 1);
  any = false;
  if (vtkDataArray* mask = image->GetPointData()->GetArray(MaskName))
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (mask->GetComponent(i, 0) == 0.0)
      {
        valid[i] = 0;
        any = true;
      }
    }
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

schlieren::GasChoice GasOf(int gas, double K, double M)
{
  return gas == vtkRefractiveIndex::CUSTOM_GAS
    ? schlieren::GasChoice::Typed(K, M)
    : schlieren::GasChoice::Table(static_cast<schlieren::Gas>(gas));
}

const char* ModelLabel(int model)
{
  static const char* const names[] = { "Passthrough", "GladstoneDale", "GladstoneDaleMixture",
    "IdealGas", "Ciddor" };
  return model >= 0 && model <= 4 ? names[model] : "(unknown)";
}

/** The role of an input-array index, for messages: name, ParaView property, what it holds. */
struct Role
{
  const char* What;
  const char* Property;
};

Role RoleOf(int idx, int model)
{
  switch (idx)
  {
    case vtkRefractiveIndex::INPUT_ARRAY:
      return { model == vtkRefractiveIndex::PASSTHROUGH ? "n - 1 (or n)" : "density", "InputArray" };
    case vtkRefractiveIndex::TEMPERATURE_ARRAY:
      return { "temperature", "TemperatureArray" };
    case vtkRefractiveIndex::PRESSURE_ARRAY:
      return { "pressure", "PressureArray" };
    case vtkRefractiveIndex::MIXTURE_FRACTION_ARRAY:
      return { "mixture fraction", "MixtureFractionArray" };
    case vtkRefractiveIndex::HUMIDITY_ARRAY:
      return { "humidity", "HumidityArray" };
    case vtkRefractiveIndex::CO2_ARRAY:
      return { "CO2", "CO2Array" };
    default:
      break;
  }
  static const char* const species[] = { "Species1Array", "Species2Array", "Species3Array",
    "Species4Array" };
  const int s = idx - vtkRefractiveIndex::SPECIES_ARRAY;
  return { "species mass fraction", s >= 0 && s < 4 ? species[s] : "Species?Array" };
}
} // namespace

//------------------------------------------------------------------------------
vtkRefractiveIndex::vtkRefractiveIndex()
{
  // port 1: an optional closed surface of a solid body
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(1);
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
bool vtkRefractiveIndex::UpdatedInputBounds(vtkInformation* inInfo, double bounds[6])
{
  // The bounds of a non-image input are known only once it has executed: update it now, for the
  // same piece as RequestUpdateExtent will ask (so that the later update does not run again).
  using SDDP = vtkStreamingDemandDrivenPipeline;
  int rank, size;
  RankAndSize(rank, size);
  int producerPort = 0;
  vtkAlgorithm* producer = this->GetInputAlgorithm(0, 0, producerPort);
  if (producer)
  {
    inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), rank);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), size);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    if (inInfo->Has(SDDP::WHOLE_EXTENT()))
    {
      inInfo->Set(SDDP::UPDATE_EXTENT(), inInfo->Get(SDDP::WHOLE_EXTENT()), 6);
    }
    producer->Update(producerPort);
  }
  double local[6] = { 1, -1, 1, -1, 1, -1 };
  const bool have = LocalBounds(vtkDataObject::GetData(inInfo), local);
  if (size <= 1)
  {
    std::copy(local, local + 6, bounds);
    return have;
  }
  // All ranks: min of the minima, max of the maxima (empty ranks send +/- infinity).
  double mins[3], maxs[3], gmins[3], gmaxs[3];
  for (int a = 0; a < 3; ++a)
  {
    mins[a] = have ? local[2 * a] : VTK_DOUBLE_MAX;
    maxs[a] = have ? local[2 * a + 1] : -VTK_DOUBLE_MAX;
  }
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  c->AllReduce(mins, gmins, 3, vtkCommunicator::MIN_OP);
  c->AllReduce(maxs, gmaxs, 3, vtkCommunicator::MAX_OP);
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = gmins[a];
    bounds[2 * a + 1] = gmaxs[a];
  }
  return gmins[0] <= gmaxs[0];
}

//------------------------------------------------------------------------------
bool vtkRefractiveIndex::SamplingGrid(
  vtkInformation* inInfo, int whole[6], double origin[3], double spacing[3])
{
  this->SamplingError.clear();
  double bounds[6];
  if (this->UseSamplingBounds)
  {
    std::copy(this->SamplingBounds, this->SamplingBounds + 6, bounds);
  }
  else
  {
    if (!this->UpdatedInputBounds(inInfo, bounds))
    {
      this->SamplingError = "The input has no points to resample onto an image grid.";
      vtkErrorMacro(<< this->SamplingError);
      return false;
    }
    // Pull the box in by a hair, so that the grid's outermost points are found inside the
    // outermost cells despite round-off (as vtkResampleToImage does).
    vtkBoundingBox box(bounds);
    box.ScaleAboutCenter(1.0 - 1e-6);
    box.GetBounds(bounds);
  }
  int dims[3];
  const bool automatic = this->SamplingDimensions[0] <= 0 || this->SamplingDimensions[1] <= 0 ||
    this->SamplingDimensions[2] <= 0;
  try
  {
    if (automatic)
    {
      schlieren::AutomaticDimensions(bounds, this->AutomaticDimension, dims);
    }
    else
    {
      std::copy(this->SamplingDimensions, this->SamplingDimensions + 3, dims);
      int ignored[3];
      schlieren::AutomaticDimensions(bounds, 2, ignored); // checks the bounds
    }
    // the resampled grid (the probe's copy of every input array, its mask, then n - 1 and
    // grad n), checked before the probe allocates it
    double perPoint = 1.0 + 16.0;
    if (vtkDataSet* ds = vtkDataSet::SafeDownCast(vtkDataObject::GetData(inInfo)))
    {
      for (vtkDataSetAttributes* attributes :
        { static_cast<vtkDataSetAttributes*>(ds->GetPointData()),
          static_cast<vtkDataSetAttributes*>(ds->GetCellData()) })
      {
        for (int i = 0; i < attributes->GetNumberOfArrays(); ++i)
        {
          if (vtkDataArray* a = attributes->GetArray(i))
          {
            perPoint += a->GetNumberOfComponents() * a->GetDataTypeSize();
          }
        }
      }
    }
    else
    {
      perPoint += 64.0; // a composite input: a few double arrays
    }
    std::ostringstream what;
    what << "Resampling onto " << dims[0] << " x " << dims[1] << " x " << dims[2] << " points";
    schlieren::CheckHostMemory(double(dims[0]) * dims[1] * dims[2] * perPoint, what.str(),
      automatic ? "Lower AutomaticDimension (points along the longest side)."
                : "Lower SamplingDimensions.");
  }
  catch (const schlieren::Error& e)
  {
    this->SamplingError = std::string(e.what()) +
      (this->UseSamplingBounds ? " (SamplingBounds: xmin xmax ymin ymax zmin zmax)" : "");
    vtkErrorMacro(<< this->SamplingError);
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    whole[2 * a] = 0;
    whole[2 * a + 1] = dims[a] - 1;
    origin[a] = bounds[2 * a];
    spacing[a] = dims[a] > 1 ? (bounds[2 * a + 1] - bounds[2 * a]) / (dims[a] - 1) : 1.0;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkRefractiveIndex::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* input = vtkDataObject::GetData(inInfo);
  const int empty[6] = { 0, -1, 0, -1, 0, -1 };
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
    const std::string flat = this->FlatInputError(input);
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
    if (!this->SamplingGrid(inInfo, whole, origin, spacing))
    {
      outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
      return 0;
    }
    const std::string flat = this->FlatInputError(vtkDataObject::GetData(inInfo));
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
int vtkRefractiveIndex::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (vtkInformation* bodyInfo = inputVector[1]->GetInformationObject(0))
  {
    // the whole body surface on every rank: the inside test needs all of it
    bodyInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
    bodyInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
    bodyInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
  const int pieces = outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES())
    : 1;
  const int piece = outInfo->Has(SDDP::UPDATE_PIECE_NUMBER())
    ? outInfo->Get(SDDP::UPDATE_PIECE_NUMBER())
    : 0;

  if (!vtkImageData::SafeDownCast(vtkDataObject::GetData(inInfo)) || this->Symmetry != NO_SYMMETRY)
  {
    // Resampled: every rank probes the whole grid against its own piece of the input (or the
    // whole input on one process); a 2D input made into a volume is read whole on every rank.
    int rank, size;
    RankAndSize(rank, size);
    if (this->Symmetry != NO_SYMMETRY)
    {
      rank = 0;
      size = 1;
    }
    inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), size > 1 ? rank : 0);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), size);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    if (inInfo->Has(SDDP::WHOLE_EXTENT()))
    {
      inInfo->Set(SDDP::UPDATE_EXTENT(), inInfo->Get(SDDP::WHOLE_EXTENT()), 6);
    }
    return 1;
  }

  int whole[6], ext[6];
  inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  outInfo->Get(SDDP::UPDATE_EXTENT(), ext);
  // With a piece request the executive splits the output's update extent into this piece (we
  // produce sub-extents) only after this call: compute the same piece here.
  if (pieces > 1)
  {
    const int ghosts = outInfo->Has(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS())
      ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS())
      : 0;
    const int mode = outInfo->Has(vtkExtentTranslator::UPDATE_SPLIT_MODE())
      ? outInfo->Get(vtkExtentTranslator::UPDATE_SPLIT_MODE())
      : vtkExtentTranslator::BLOCK_MODE;
    const int all[6] = { ext[0], ext[1], ext[2], ext[3], ext[4], ext[5] };
    vtkNew<vtkExtentTranslator> translator;
    translator->PieceToExtentThreadSafe(piece, pieces, ghosts, const_cast<int*>(all), ext, mode, 0);
  }
  if (!IsEmpty(ext))
  {
    // One more point on every side, so that central differences at the piece's borders use the
    // neighbours' values; clamped to the whole extent (where the engine goes one-sided).
    for (int a = 0; a < 3; ++a)
    {
      ext[2 * a] = std::max(ext[2 * a] - 1, whole[2 * a]);
      ext[2 * a + 1] = std::min(ext[2 * a + 1] + 1, whole[2 * a + 1]);
    }
  }
  // Exactly this extent from the input: one piece, not to be split again upstream.
  inInfo->Set(SDDP::UPDATE_EXTENT(), ext, 6);
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
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

/** The array chosen for input-array index `idx` among the point arrays of `data`, or null. */
vtkDataArray* ChosenArray(vtkRefractiveIndex* self, int idx, vtkImageData* data, std::string& name)
{
  name = ChosenName(self, idx);
  vtkPointData* pd = data->GetPointData();
  if (!name.empty())
  {
    return pd->GetArray(name.c_str());
  }
  if (idx != vtkRefractiveIndex::INPUT_ARRAY)
  {
    return nullptr;
  }
  // No name chosen (e.g. a pvpython proxy created before its input was updated): the active
  // point scalars, else the first point array that is not the mask.
  vtkDataArray* a = pd->GetScalars();
  for (int i = 0; !a && i < pd->GetNumberOfArrays(); ++i)
  {
    const char* n = pd->GetArrayName(i);
    if (!n || std::string(n) != MaskName)
    {
      a = pd->GetArray(i);
    }
  }
  if (a && a->GetName())
  {
    name = a->GetName();
  }
  return a;
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

/** The input-array indices the model reads. */
std::vector<int> NeededArrays(vtkRefractiveIndex* self)
{
  std::vector<int> needed;
  const int model = self->GetModelInUse();
  if (model == vtkRefractiveIndex::IDEAL_GAS || model == vtkRefractiveIndex::CIDDOR)
  {
    needed = { vtkRefractiveIndex::TEMPERATURE_ARRAY, vtkRefractiveIndex::PRESSURE_ARRAY };
  }
  else
  {
    needed = { vtkRefractiveIndex::INPUT_ARRAY };
  }
  const int composition = CompositionOf(self);
  if (composition == vtkRefractiveIndex::MIXTURE_FRACTION)
  {
    needed.push_back(vtkRefractiveIndex::MIXTURE_FRACTION_ARRAY);
  }
  else if (composition == vtkRefractiveIndex::SPECIES)
  {
    for (int s = 0; s < self->GetNumberOfSpecies(); ++s)
    {
      needed.push_back(vtkRefractiveIndex::SPECIES_ARRAY + s);
    }
  }
  if (model == vtkRefractiveIndex::CIDDOR && self->GetHumidityFromArray())
  {
    needed.push_back(vtkRefractiveIndex::HUMIDITY_ARRAY);
  }
  if (model == vtkRefractiveIndex::CIDDOR && self->GetCO2FromArray())
  {
    needed.push_back(vtkRefractiveIndex::CO2_ARRAY);
  }
  return needed;
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

/**
 * The input probed at the points of `structure` (vtkValidPointMask: 1 where a cell was found).
 * Under MPI each rank probes its own piece; the arrays named in `names` and the mask are summed
 * over the ranks (value x found, found), so that every rank holds them on the whole grid.
 */
vtkSmartPointer<vtkImageData> Resample(
  vtkDataObject* input, vtkImageData* structure, const std::vector<std::string>& names)
{
  vtkNew<vtkCompositeDataProbeFilter> probe;
  probe->SetInputData(structure);
  probe->SetSourceData(input);
  probe->SetValidPointMaskArrayName(MaskName);
  probe->Update();
  vtkSmartPointer<vtkImageData> grid = vtkImageData::SafeDownCast(probe->GetOutputDataObject(0));
  if (!grid || grid->GetNumberOfPoints() != structure->GetNumberOfPoints())
  {
    // An empty piece of the input (MPI): nothing found here.
    grid = vtkSmartPointer<vtkImageData>::New();
    grid->CopyStructure(structure);
  }
  int rank, ranks;
  RankAndSize(rank, ranks);
  if (ranks <= 1)
  {
    return grid;
  }
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const vtkIdType n = grid->GetNumberOfPoints();
  vtkDataArray* mask = grid->GetPointData()->GetArray(MaskName);
  std::vector<double> found(n, 0.0), total(n, 0.0);
  for (vtkIdType i = 0; mask && i < n; ++i)
  {
    found[i] = mask->GetComponent(i, 0) != 0.0 ? 1.0 : 0.0;
  }
  controller->AllReduce(found.data(), total.data(), n, vtkCommunicator::SUM_OP);
  vtkNew<vtkImageData> reduced;
  reduced->CopyStructure(structure);
  vtkNew<vtkCharArray> validMask;
  validMask->SetName(MaskName);
  validMask->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    validMask->SetValue(i, total[i] > 0.0 ? 1 : 0);
  }
  reduced->GetPointData()->AddArray(validMask);
  for (const std::string& name : names) // the same list, in the same order, on every rank
  {
    vtkDataArray* a = grid->GetPointData()->GetArray(name.c_str());
    int have = (a && a->GetNumberOfComponents() == 1) ? 1 : 0, haveAny = 0;
    controller->AllReduce(&have, &haveAny, 1, vtkCommunicator::MAX_OP);
    if (!haveAny)
    {
      continue; // reported as missing by the caller, the same on every rank
    }
    std::vector<double> sum(n, 0.0), all(n, 0.0);
    for (vtkIdType i = 0; have && i < n; ++i)
    {
      sum[i] = found[i] != 0.0 ? a->GetComponent(i, 0) : 0.0;
    }
    controller->AllReduce(sum.data(), all.data(), n, vtkCommunicator::SUM_OP);
    vtkNew<vtkFloatArray> r;
    r->SetName(name.c_str());
    r->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      r->SetValue(i, total[i] > 0.0 ? static_cast<float>(all[i] / total[i]) : 0.0f);
    }
    reduced->GetPointData()->AddArray(r);
  }
  return reduced;
}

/**
 * Points `fields` at float copies (kept in `storage`) of the arrays the model reads; returns ""
 * or a message for the user (a missing array, with the arrays present; a vector; one array chosen
 * for two roles).
 */
std::string GatherFields(vtkRefractiveIndex* self, vtkImageData* grid, const std::vector<int>& needed,
  schlieren::FieldArrays& fields, std::vector<std::vector<float>>& storage)
{
  const int model = self->GetModelInUse();
  storage.assign(needed.size(), std::vector<float>());
  std::vector<std::pair<std::string, int>> chosen; // name, index
  for (std::size_t k = 0; k < needed.size(); ++k)
  {
    const int idx = needed[k];
    const Role role = RoleOf(idx, model);
    std::string name;
    vtkDataArray* a = ChosenArray(self, idx, grid, name);
    std::ostringstream m;
    if (!a)
    {
      m << ModelLabel(model) << " needs a " << role.What << " array ";
      if (name.empty())
      {
        m << "and none is chosen: choose one with " << role.Property
          << " (SetInputArrayToProcess index " << idx << ").";
      }
      else
      {
        m << "('" << name << "', " << role.Property << ") but ";
        if (grid->GetCellData()->GetArray(name.c_str()))
        {
          m << "'" << name << "' is a cell array, and the model reads point arrays: convert it "
            << "first (Cell Data to Point Data).";
        }
        else
        {
          m << "the input has no point array of that name.";
        }
      }
      m << " Point arrays present: " << PointArrayNames(grid) << ".";
      return m.str();
    }
    if (a->GetNumberOfComponents() != 1)
    {
      m << "The " << role.What << " array '" << name << "' has " << a->GetNumberOfComponents()
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
          << "). Point arrays present: " << PointArrayNames(grid) << ".";
        return m.str();
      }
    }
    chosen.emplace_back(name, idx);
    storage[k] = AsFloat(a);
    const schlieren::NamedArray named{ storage[k].data(), name };
    switch (idx)
    {
      case vtkRefractiveIndex::INPUT_ARRAY:
        fields.Index = named;
        fields.Density = named;
        break;
      case vtkRefractiveIndex::TEMPERATURE_ARRAY:
        fields.Temperature = named;
        break;
      case vtkRefractiveIndex::PRESSURE_ARRAY:
        fields.Pressure = named;
        break;
      case vtkRefractiveIndex::MIXTURE_FRACTION_ARRAY:
        fields.MixtureFraction = named;
        break;
      case vtkRefractiveIndex::HUMIDITY_ARRAY:
        fields.Humidity = named;
        break;
      case vtkRefractiveIndex::CO2_ARRAY:
        fields.CO2 = named;
        break;
      default:
        fields.Species[idx - vtkRefractiveIndex::SPECIES_ARRAY] = named;
        break;
    }
  }
  return std::string();
}

/**
 * "" or the error of Passthrough on values that no gas has as n - 1 (|n - 1| > 0.1: a density, a
 * temperature or a pressure taken for n - 1), naming the array, its range and the models to use.
 */
std::string PassthroughRangeError(const float* n1, vtkIdType count, const std::string& name, bool holdsN)
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
  m << "Passthrough takes '" << name << "' as " << (holdsN ? "n" : "n - 1") << ", but it gives n - 1 from "
    << lo << " to " << hi << ": no gas has |n - 1| above " << limit
    << " (air at 1 atm: 2.7e-4). If '" << name
    << "' is a density, choose Model GladstoneDale (with DensityReference for non-dimensional "
       "data); a temperature and a pressure: IdealGas; if it holds n itself, turn on "
       "PassthroughHoldsN. A lens or a liquid (not a gas) goes to SchlierenImage directly as an "
       "image carrying n_minus_1.";
  return m.str();
}

/** "The input's extent (...) does not cover the requested extent (...)", or "". */
std::string CheckCovers(const int gridExt[6], const int outExt[6])
{
  for (int a = 0; a < 3; ++a)
  {
    if (outExt[2 * a] < gridExt[2 * a] || outExt[2 * a + 1] > gridExt[2 * a + 1])
    {
      std::ostringstream m;
      m << "The input's extent (" << gridExt[0] << " " << gridExt[1] << " " << gridExt[2] << " "
        << gridExt[3] << " " << gridExt[4] << " " << gridExt[5]
        << ") does not cover the requested extent (" << outExt[0] << " " << outExt[1] << " "
        << outExt[2] << " " << outExt[3] << " " << outExt[4] << " " << outExt[5]
        << "); the upstream filter did not honour the update request.";
      return m.str();
    }
  }
  return std::string();
}

} // namespace

//------------------------------------------------------------------------------
int vtkRefractiveIndex::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* inputObject = vtkDataObject::GetData(inInfo);
  vtkImageData* inputImage = vtkImageData::SafeDownCast(inputObject);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  const bool symmetric = this->Symmetry != NO_SYMMETRY;
  if (!output || (vtkPolyData::SafeDownCast(inputObject) && !symmetric) ||
    (!vtkDataSet::SafeDownCast(inputObject) && !vtkCompositeDataSet::SafeDownCast(inputObject)))
  {
    vtkErrorMacro(<< NotAVolume(inputObject));
    return 0;
  }
  int rank, ranks;
  RankAndSize(rank, ranks);
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const bool resampled = inputImage == nullptr || symmetric;

  // 0. What to read (vtkRefractiveIndexInputs.cxx): a 2D input without Symmetry is one clear
  // error; the model and the arrays left automatic are resolved by name; ids and integer arrays
  // are refused; cell arrays become point arrays.
  std::vector<std::string> notes;
  vtkSmartPointer<vtkDataObject> pointInput; // the input with cell arrays made point arrays
  int outWhole[6];
  outInfo->Get(SDDP::WHOLE_EXTENT(), outWhole);
  if (!resampled || (!IsEmpty(outWhole) && outInfo->Has(vtkDataObject::ORIGIN())))
  {
    // (without a resampling grid, RequestInformation's error is repeated below instead)
    std::string problem = this->FlatInputError(inputObject);
    if (problem.empty())
    {
      problem = this->ResolveChoices(inputObject, notes);
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
      pointInput = this->PointFields(inputObject, readNames, notes, problem);
    }
    if (!problem.empty())
    {
      output->Initialize();
      vtkErrorMacro(<< problem);
      return 0;
    }
    for (const std::string& note : notes)
    {
      if (rank == 0) // the same on every rank: said once
      {
        vtkOutputWindowDisplayText((note + "\n").c_str());
      }
    }
    if (pointInput != inputObject)
    {
      inputObject = pointInput;
      inputImage = vtkImageData::SafeDownCast(inputObject);
    }
  }
  const std::vector<int> needed = NeededArrays(this);

  // 1. The grid the model runs on: the input image's (grown) piece, or the whole resampling grid
  // (on every rank).
  int outExt[6], whole[6];
  outInfo->Get(SDDP::UPDATE_EXTENT(), outExt);
  vtkSmartPointer<vtkImageData> grid;
  if (!resampled)
  {
    inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
    grid = inputImage;
  }
  else
  {
    outInfo->Get(SDDP::WHOLE_EXTENT(), whole);
    if (IsEmpty(whole) || !outInfo->Has(vtkDataObject::ORIGIN()))
    {
      // RequestInformation could not set up the grid (and said why then): say it again.
      output->Initialize();
      vtkErrorMacro(<< (this->SamplingError.empty()
          ? std::string("No resampling grid: the pipeline information was not updated.")
          : this->SamplingError));
      return 0;
    }
    vtkNew<vtkImageData> structure;
    structure->SetExtent(whole);
    structure->SetOrigin(outInfo->Get(vtkDataObject::ORIGIN()));
    structure->SetSpacing(outInfo->Get(vtkDataObject::SPACING()));
    std::vector<std::string> names;
    for (int idx : needed)
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
    if (ranks <= 1)
    {
      // A missing array is reported before the (costly) probing; under MPI after it, since a
      // rank's piece may be empty.
      const std::vector<std::string> present = InputArrayNames(inputObject);
      for (const std::string& name : names)
      {
        if (std::find(present.begin(), present.end(), name) == present.end())
        {
          std::ostringstream list;
          for (std::size_t i = 0; i < present.size(); ++i)
          {
            list << (i ? ", " : "") << present[i];
          }
          output->Initialize();
          vtkErrorMacro(<< ModelLabel(this->GetModelInUse()) << " reads the array '" << name
                        << "', which the input does not have. Arrays present: "
                        << (present.empty() ? std::string("none") : list.str())
                        << ". Choose one of them.");
          return 0;
        }
      }
    }
    grid = symmetric ? this->SymmetricResample(inputObject, structure, names)
                     : Resample(inputObject, structure, names);
    this->UpdateProgress(0.4);
  }

  // 2. The model on the grid. Failures are collected so that, under MPI, every rank reaches the
  // collective step below.
  std::string failure;
  std::vector<std::string> warnings;
  const vtkIdType count = grid->GetNumberOfPoints();
  const bool emptyPiece = !resampled && (IsEmpty(outExt) || count == 0);
  bool anyInvalid = false;
  std::vector<unsigned char> valid;
  vtkNew<vtkFloatArray> nMinus1;
  nMinus1->SetName("n_minus_1");
  std::vector<float> edge;
  int gridExt[6];
  grid->GetExtent(gridExt);
  if (!emptyPiece)
  {
    failure = CheckCovers(gridExt, outExt);
    valid = Validity(grid, anyInvalid);
    schlieren::FieldArrays fields;
    fields.Count = static_cast<std::size_t>(count);
    fields.Valid = anyInvalid ? valid.data() : nullptr;
    std::vector<std::vector<float>> storage;
    if (failure.empty())
    {
      failure = GatherFields(this, grid, needed, fields, storage);
    }
    nMinus1->SetNumberOfTuples(count);
    std::fill(nMinus1->GetPointer(0), nMinus1->GetPointer(0) + count, 0.0f);
    if (failure.empty())
    {
      try
      {
        const schlieren::FieldReport report =
          schlieren::ComputeFieldIndex(fields, ModelOf(this), nMinus1->GetPointer(0));
        warnings = report.Warnings;
        if (anyInvalid && report.ValidPoints == 0)
        {
          failure = "No point of the " +
            std::string(resampled ? "sampling grid lies inside the input's cells"
                                  : "input is valid (vtkValidPointMask is 0 everywhere)") +
            ": check SamplingBounds and the input.";
        }
      }
      catch (const schlieren::Error& e)
      {
        failure = e.what();
        if (resampled)
        {
          failure += " (Counted on the image grid the input was resampled onto.)";
        }
      }
    }
    // The values at the edge of the flow domain, for DomainEdgeMedian (and for Extend on an image
    // piece under MPI, which cannot extend across pieces), over the points this piece owns: its
    // output extent less the upper plane that the next piece also holds. A resampled grid is
    // whole on every rank: all of it.
    const bool pieceOfImage = ranks > 1 && !resampled;
    if (failure.empty() && anyInvalid &&
      (this->AmbientMode == DOMAIN_EDGE_MEDIAN || (this->AmbientMode == EXTEND && pieceOfImage)))
    {
      int dims[3], owned[6];
      grid->GetDimensions(dims);
      for (int a = 0; a < 3; ++a)
      {
        owned[2 * a] = resampled ? 0 : outExt[2 * a] - gridExt[2 * a];
        owned[2 * a + 1] = resampled
          ? dims[a] - 1
          : outExt[2 * a + 1] - gridExt[2 * a] - (outExt[2 * a + 1] < whole[2 * a + 1] ? 1 : 0);
      }
      schlieren::CollectDomainEdge(dims, valid.data(), nMinus1->GetPointer(0), owned, edge);
    }
  }

  // 3. Under MPI, every rank learns whether any failed and, for an image input with invalid
  // points, the domain edge of all pieces.
  if (ranks > 1 && !resampled)
  {
    int localState[2] = { failure.empty() ? 0 : 1, anyInvalid ? 1 : 0 };
    int globalState[2] = { 0, 0 };
    controller->AllReduce(localState, globalState, 2, vtkCommunicator::MAX_OP);
    if (globalState[0] && failure.empty())
    {
      failure = "Another rank failed (see its error); no output.";
    }
    if (!globalState[0] && globalState[1] && this->AmbientMode != AMBIENT_VALUE)
    {
      vtkIdType mine = static_cast<vtkIdType>(edge.size());
      std::vector<vtkIdType> lengths(ranks), offsets(ranks, 0);
      controller->AllGather(&mine, lengths.data(), 1);
      for (int r = 1; r < ranks; ++r)
      {
        offsets[r] = offsets[r - 1] + lengths[r - 1];
      }
      std::vector<float> all(static_cast<std::size_t>(offsets[ranks - 1] + lengths[ranks - 1]));
      controller->AllGatherV(edge.data(), all.data(), mine, lengths.data(), offsets.data());
      edge.swap(all);
    }
  }
  if (!failure.empty())
  {
    output->Initialize();
    vtkErrorMacro(<< failure);
    return 0;
  }
  for (const std::string& w : warnings)
  {
    vtkWarningMacro(<< w);
  }
  if (emptyPiece)
  {
    output->Initialize();
    return 1;
  }

  // 4. The points outside the flow domain, the check of n, the gradient.
  int ambientMode = this->AmbientMode;
  if (anyInvalid && ambientMode == EXTEND && ranks > 1 && !resampled)
  {
    ambientMode = DOMAIN_EDGE_MEDIAN; // extending needs the whole grid
  }
  double ambient = ambientMode == AMBIENT_VALUE ? this->AmbientValue
                                                : std::numeric_limits<double>::quiet_NaN();
  vtkIdType invalidPoints = 0;
  vtkNew<vtkFloatArray> gradient;
  gradient->SetName("grad_n");
  gradient->SetNumberOfComponents(3);
  gradient->SetNumberOfTuples(count);
  int dims[3];
  grid->GetDimensions(dims);
  try
  {
    if (anyInvalid && ambientMode == EXTEND)
    {
      invalidPoints = static_cast<vtkIdType>(
        schlieren::ExtendIntoInvalid(dims, valid.data(), nMinus1->GetPointer(0)));
    }
    else if (anyInvalid)
    {
      if (ambientMode == DOMAIN_EDGE_MEDIAN)
      {
        ambient = schlieren::Median(edge);
        if (!std::isfinite(ambient))
        {
          // No valid point touches an invalid one here: the median of the valid points.
          std::vector<float> values;
          for (vtkIdType i = 0; i < count; ++i)
          {
            if (valid[i])
            {
              values.push_back(nMinus1->GetValue(i));
            }
          }
          ambient = schlieren::Median(values);
        }
      }
      invalidPoints = static_cast<vtkIdType>(schlieren::FillInvalid(
        static_cast<std::size_t>(count), valid.data(), ambient, nMinus1->GetPointer(0)));
    }
    const std::string problem =
      schlieren::ValidateIndex(nMinus1->GetPointer(0), static_cast<std::size_t>(count));
    if (!problem.empty())
    {
      throw schlieren::Error(problem + " (model " + ModelLabel(this->GetModelInUse()) + ").");
    }
    if (this->GetModelInUse() == PASSTHROUGH)
    {
      const std::string notGas = PassthroughRangeError(
        nMinus1->GetPointer(0), count, ChosenName(this, INPUT_ARRAY), this->GetPassthroughHoldsNInUse());
      if (!notGas.empty())
      {
        throw schlieren::Error(notGas);
      }
    }
    schlieren::ComputeGradient(dims, grid->GetSpacing(), nMinus1->GetPointer(0), gradient->GetPointer(0));
  }
  catch (const schlieren::Error& e)
  {
    output->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  // 4b. Solid bodies: enclosed holes of the grid, the mask array, the body surface.
  std::vector<unsigned char> solid;
  std::string solidNote;
  const std::string solidProblem =
    this->ComputeSolid(inputVector, grid, valid, anyInvalid, resampled, solid, solidNote);
  if (!solidProblem.empty())
  {
    output->Initialize();
    vtkErrorMacro(<< solidProblem);
    return 0;
  }
  if (!solidNote.empty() && rank == 0)
  {
    vtkWarningMacro(<< solidNote);
  }
  this->UpdateProgress(0.9);

  // 5. The output: the requested extent of the grid, with the new arrays.
  vtkNew<vtkPointData> pointData;
  pointData->ShallowCopy(grid->GetPointData());
  if (!anyInvalid && resampled)
  {
    pointData->RemoveArray(MaskName); // every point was found: the mask says nothing
  }
  pointData->AddArray(gradient);
  pointData->AddArray(nMinus1);
  vtkIdType solidPoints = 0;
  if (!solid.empty())
  {
    vtkNew<vtkUnsignedCharArray> solidArray;
    solidArray->SetName("solid");
    solidArray->SetNumberOfTuples(count);
    std::copy(solid.begin(), solid.end(), solidArray->GetPointer(0));
    solidPoints = static_cast<vtkIdType>(std::count(solid.begin(), solid.end(), 1));
    pointData->AddArray(solidArray);
  }
  pointData->SetActiveScalars("n_minus_1");

  vtkNew<vtkFieldData> fieldData;
  if (!resampled && inputImage->GetFieldData())
  {
    fieldData->ShallowCopy(inputImage->GetFieldData());
  }
  if (anyInvalid && ambientMode != EXTEND)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName("ambient_n_minus_1");
    a->InsertNextValue(ambient);
    fieldData->AddArray(a);
  }
  {
    // What was read, for scripts and for the GUI's information panel.
    vtkNew<vtkStringArray> model;
    model->SetName("index_model");
    model->InsertNextValue(ModelLabel(this->GetModelInUse()));
    fieldData->AddArray(model);
    vtkNew<vtkStringArray> read;
    read->SetName("index_arrays");
    for (int idx : needed)
    {
      read->InsertNextValue(ChosenName(this, idx));
    }
    fieldData->AddArray(read);
    if (!notes.empty())
    {
      vtkNew<vtkStringArray> said;
      said->SetName("index_notes");
      for (const std::string& note : notes)
      {
        said->InsertNextValue(note);
      }
      fieldData->AddArray(said);
    }
  }
  vtkNew<vtkDoubleArray> fraction;
  fraction->SetName("valid_point_fraction");
  fraction->InsertNextValue(count ? 1.0 - static_cast<double>(invalidPoints) / count : 0.0);
  fieldData->AddArray(fraction);
  vtkNew<vtkDoubleArray> solidCount;
  solidCount->SetName("solid_points");
  solidCount->InsertNextValue(static_cast<double>(solidPoints));
  fieldData->AddArray(solidCount);

  output->Initialize();
  if (std::equal(gridExt, gridExt + 6, outExt))
  {
    output->CopyStructure(grid);
    output->GetPointData()->ShallowCopy(pointData);
    if (!resampled)
    {
      output->GetCellData()->ShallowCopy(grid->GetCellData());
    }
  }
  else
  {
    output->SetExtent(outExt);
    output->SetOrigin(grid->GetOrigin());
    output->SetSpacing(grid->GetSpacing());
    output->SetDirectionMatrix(grid->GetDirectionMatrix());
    const vtkIdType outCount = output->GetNumberOfPoints();
    output->GetPointData()->CopyAllocate(pointData, outCount);
    output->GetPointData()->CopyStructuredData(pointData, gridExt, outExt);
    if (!resampled)
    {
      int inCells[6], outCells[6];
      CellExtent(whole, gridExt, inCells);
      CellExtent(whole, outExt, outCells);
      output->GetCellData()->CopyAllocate(grid->GetCellData(), output->GetNumberOfCells());
      output->GetCellData()->CopyStructuredData(grid->GetCellData(), inCells, outCells);
    }
  }
  output->GetPointData()->SetActiveScalars("n_minus_1");
  output->GetFieldData()->ShallowCopy(fieldData);
  return 1;
}

//------------------------------------------------------------------------------
std::string vtkRefractiveIndex::ComputeSolid(vtkInformationVector** inputVector, vtkImageData* grid,
  const std::vector<unsigned char>& valid, bool anyInvalid, bool resampled,
  std::vector<unsigned char>& solid, std::string& note)
{
  const vtkIdType count = grid->GetNumberOfPoints();
  int dims[3];
  grid->GetDimensions(dims);
  int rank, ranks;
  RankAndSize(rank, ranks);
  solid.assign(static_cast<std::size_t>(count), 0);
  bool any = false;
  // the holes the grid leaves that the flow encloses (the whole grid: resampled, or one process)
  if (this->BodyFromGrid && anyInvalid)
  {
    if (resampled || ranks == 1)
    {
      any = schlieren::EnclosedInvalidPoints(dims, valid.data(), this->BodyWallFaces, solid.data()) > 0;
    }
    else
    {
      note = "BodyFromGrid: the invalid points of an image split over MPI ranks cannot be told "
             "apart (body or outside) piece by piece; no body is taken from them. Give the body "
             "as a SolidArray or a surface instead.";
    }
  }
  // a body the input already carries (RefractiveScene's Body, an upstream RefractiveIndex's): kept
  if (vtkDataArray* upstream = grid->GetPointData()->GetArray("solid"))
  {
    for (vtkIdType i = 0; upstream->GetNumberOfComponents() == 1 && i < count; ++i)
    {
      const double v = upstream->GetComponent(i, 0);
      if (resampled ? v >= 0.5 : v != 0.0)
      {
        solid[i] = 1;
        any = true;
      }
    }
  }
  // the mask array
  if (!this->SolidArray.empty())
  {
    vtkDataArray* mask = grid->GetPointData()->GetArray(this->SolidArray.c_str());
    if (!mask)
    {
      return "SolidArray '" + this->SolidArray + "' is not a point array of the input. Point " +
        "arrays present: " + PointArrayNames(grid) + ".";
    }
    if (mask->GetNumberOfComponents() != 1)
    {
      return "SolidArray '" + this->SolidArray + "' has " +
        std::to_string(mask->GetNumberOfComponents()) + " components; it must be a scalar (non-zero: solid).";
    }
    for (vtkIdType i = 0; i < count; ++i)
    {
      const double v = mask->GetComponent(i, 0);
      if (resampled ? v >= 0.5 : v != 0.0)
      {
        solid[i] = 1;
        any = true;
      }
    }
  }
  // the body surface: the grid points inside it (tested only within the surface's bounds)
  vtkPolyData* surface = inputVector[1] && inputVector[1]->GetInformationObject(0)
    ? vtkPolyData::GetData(inputVector[1]->GetInformationObject(0))
    : nullptr;
  if (surface)
  {
    if (surface->GetNumberOfPolys() == 0 && surface->GetNumberOfStrips() == 0)
    {
      return "The Body input has no polygons: it must be a closed surface (vtkPolyData), such as "
             "an STL of the model.";
    }
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputData(surface);
    triangles->PassLinesOff();
    triangles->PassVertsOff();
    triangles->Update();
    vtkPolyData* closed = triangles->GetOutput();
    if (!vtkSelectEnclosedPoints::IsSurfaceClosed(closed))
    {
      return "The Body input is not a closed surface (it has boundary or non-manifold edges), so "
             "its inside is not defined. Close it (e.g. Fill Holes, or export the model as a "
             "watertight STL).";
    }
    double b[6];
    closed->GetBounds(b);
    const double* origin = grid->GetOrigin();
    const double* spacing = grid->GetSpacing();
    int ext[6];
    grid->GetExtent(ext);
    int sub[6];
    bool overlaps = true;
    for (int a = 0; a < 3; ++a)
    {
      sub[2 * a] = std::max(ext[2 * a], static_cast<int>(std::floor((b[2 * a] - origin[a]) / spacing[a])));
      sub[2 * a + 1] =
        std::min(ext[2 * a + 1], static_cast<int>(std::ceil((b[2 * a + 1] - origin[a]) / spacing[a])));
      overlaps = overlaps && sub[2 * a] <= sub[2 * a + 1];
    }
    if (overlaps)
    {
      vtkNew<vtkImageData> box;
      box->SetExtent(sub);
      box->SetOrigin(grid->GetOrigin());
      box->SetSpacing(grid->GetSpacing());
      vtkNew<vtkSelectEnclosedPoints> inside;
      inside->SetInputData(box);
      inside->SetSurfaceData(closed);
      inside->CheckSurfaceOff(); // checked above, with a message of our own
      inside->Update();
      vtkDataArray* selected =
        inside->GetOutput()->GetPointData()->GetArray("SelectedPoints");
      if (!selected)
      {
        return "The inside test of the Body surface failed (vtkSelectEnclosedPoints gave no "
               "result).";
      }
      vtkIdType p = 0;
      for (int k = sub[4]; k <= sub[5]; ++k)
      {
        for (int j = sub[2]; j <= sub[3]; ++j)
        {
          for (int i = sub[0]; i <= sub[1]; ++i, ++p)
          {
            if (selected->GetComponent(p, 0) != 0.0)
            {
              const vtkIdType g = (static_cast<vtkIdType>(k - ext[4]) * dims[1] + (j - ext[2])) * dims[0] + (i - ext[0]);
              solid[g] = 1;
              any = true;
            }
          }
        }
      }
    }
    if (!overlaps || !any)
    {
      note += std::string(note.empty() ? "" : " ") +
        "The Body surface encloses no point of the grid: check that it is in the data's "
        "coordinates and inside the sampling bounds.";
    }
  }
  if (!any)
  {
    solid.clear();
  }
  return std::string();
}

//------------------------------------------------------------------------------
void vtkRefractiveIndex::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Model: " << this->Model << " (" << ModelLabel(this->GetModelInUse()) << ")\n";
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
vtkTypeBool vtkRefractiveIndex::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return SchlierenGuarded(this,
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); });
}
