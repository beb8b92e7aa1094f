// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSchlierenImage.h"

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include "SchlierenEngine.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSchlierenImage);

namespace
{
const char* const IndexArrayName = "n_minus_1";

/** "a, b, c" for the point arrays of a data set, or "none". */
std::string PointArrayNames(vtkDataSet* ds)
{
  vtkPointData* pd = ds->GetPointData();
  std::ostringstream names;
  for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
  {
    const char* name = pd->GetArrayName(i);
    names << (i ? ", " : "") << (name ? name : "(unnamed)");
  }
  const std::string s = names.str();
  return s.empty() ? std::string("none") : s;
}

std::string NotAnImage(vtkDataObject* input)
{
  return std::string("SchlierenImage needs a vtkImageData input with the point array 'n_minus_1'; "
                     "got ") +
    (input ? input->GetClassName() : "nothing") +
    ". Resample the data onto an image and apply RefractiveIndex first.";
}

bool IsEmpty(const int ext[6])
{
  return ext[1] < ext[0] || ext[3] < ext[2] || ext[5] < ext[4];
}

vtkIdType ExtentPoints(const int ext[6])
{
  return IsEmpty(ext) ? 0
                      : static_cast<vtkIdType>(ext[1] - ext[0] + 1) * (ext[3] - ext[2] + 1) *
      (ext[5] - ext[4] + 1);
}

/** The engine's grid (without its field) of the whole extent described by the information. */
schlieren::Volume WholeVolume(vtkInformation* inInfo)
{
  int whole[6];
  double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  if (inInfo->Has(vtkDataObject::ORIGIN()))
  {
    inInfo->Get(vtkDataObject::ORIGIN(), origin);
  }
  if (inInfo->Has(vtkDataObject::SPACING()))
  {
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  }
  schlieren::Volume volume;
  for (int a = 0; a < 3; ++a)
  {
    volume.Dimensions[a] = std::max(whole[2 * a + 1] - whole[2 * a] + 1, 0);
    volume.Origin[a] = origin[a] + whole[2 * a] * spacing[a];
    volume.Spacing[a] = spacing[a];
  }
  return volume;
}

/** Copies a piece (its extent and x-fastest values) into the whole grid and marks what it covers. */
void Insert(const int whole[6], const int ext[6], const float* values, std::vector<float>& field,
  std::vector<unsigned char>& covered)
{
  if (IsEmpty(ext))
  {
    return;
  }
  const vtkIdType nx = whole[1] - whole[0] + 1, ny = whole[3] - whole[2] + 1;
  std::size_t src = 0;
  for (int k = ext[4]; k <= ext[5]; ++k)
  {
    for (int j = ext[2]; j <= ext[3]; ++j)
    {
      const vtkIdType row = ((k - whole[4]) * ny + (j - whole[2])) * nx + (ext[0] - whole[0]);
      const int len = ext[1] - ext[0] + 1;
      std::copy(values + src, values + src + len, field.begin() + row);
      std::fill(covered.begin() + row, covered.begin() + row + len, 1);
      src += len;
    }
  }
}
}

//------------------------------------------------------------------------------
vtkSchlierenImage::vtkSchlierenImage()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkSchlierenImage::~vtkSchlierenImage() = default;

//------------------------------------------------------------------------------
int vtkSchlierenImage::FillInputPortInformation(int port, vtkInformation* info)
{
  // Any data set at the pipeline level, so that a wrong input gets this filter's clear error.
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

namespace
{
/** The engine's settings from the filter's properties. */
schlieren::TraceSettings SettingsOf(vtkSchlierenImage* self)
{
  schlieren::TraceSettings s;
  for (int a = 0; a < 3; ++a)
  {
    s.ViewDirection[a] = self->GetViewDirection()[a];
    s.ViewUp[a] = self->GetViewUp()[a];
  }
  s.Resolution[0] = self->GetResolution()[0];
  s.Resolution[1] = self->GetResolution()[1];
  s.Passes = self->GetPasses();
  s.StepSize = self->GetStepSize();
  s.Method = static_cast<schlieren::Integrator>(self->GetIntegrator());
  s.Mode = static_cast<schlieren::Cutoff>(self->GetCutoff());
  s.KnifeAngle = self->GetKnifeAngle();
  s.CutoffScale = self->GetCutoffScale();
  s.FilmDistance = self->GetFilmDistance();
  s.Jitter = self->GetJitter();
  s.Seed = static_cast<std::uint32_t>(self->GetSeed());
  switch (self->GetBackend())
  {
    case vtkSchlierenImage::OPENCL:
      s.Device = schlieren::Backend::OpenCL;
      break;
    case vtkSchlierenImage::CPU:
      s.Device = schlieren::Backend::CPU;
      break;
    default:
      s.Device = schlieren::Backend::Auto;
      break;
  }
  return s;
}
}

//------------------------------------------------------------------------------
int vtkSchlierenImage::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* input = vtkDataObject::GetData(inInfo);
  // Until the film is known the output is empty: a failure below must not leave the input's
  // extent (copied here by the executive) as the film's.
  const int empty[6] = { 0, -1, 0, -1, 0, -1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
  if (!vtkImageData::SafeDownCast(input))
  {
    vtkErrorMacro(<< NotAnImage(input));
    return 0;
  }
  try
  {
    const schlieren::Volume volume = WholeVolume(inInfo);
    const schlieren::FilmGeometry film = schlieren::MakeFilm(volume, SettingsOf(this));
    double origin[2];
    film.GetImageOrigin(origin);
    const int whole[6] = { 0, film.Size[0] - 1, 0, film.Size[1] - 1, 0, 0 };
    const double spacing[3] = { film.PixelSize, film.PixelSize, 1.0 };
    const double origin3[3] = { origin[0], origin[1], 0.0 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
    outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
    outInfo->Set(vtkDataObject::ORIGIN(), origin3, 3);
  }
  catch (const schlieren::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  // Every rank must execute (the tracing is collective under MPI); rank 0 produces the image.
  outInfo->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkSchlierenImage::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int whole[6];
  inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  // The tracer needs the whole volume: ask for the whole extent. On one process that is one
  // piece. Under MPI each rank asks for its piece of it (this output's piece of as many pieces:
  // the upstream splits the whole extent with its extent translator), and RequestData gathers
  // the pieces of all ranks.
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  inInfo->Set(SDDP::UPDATE_EXTENT(), whole, 6);
  if (ranks <= 1)
  {
    inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
  }
  else
  {
    const int piece =
      outInfo->Has(SDDP::UPDATE_PIECE_NUMBER()) ? outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()) : 0;
    const int pieces = outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES())
      ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES())
      : 1;
    inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), piece);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), std::max(pieces, 1));
  }
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkSchlierenImage::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  vtkImageData* input = vtkImageData::GetData(inInfo);

  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? std::max(controller->GetNumberOfProcesses(), 1) : 1;
  const int rank = ranks > 1 ? controller->GetLocalProcessId() : 0;

  // Under MPI every step below that can fail on some ranks only is followed by an agreement,
  // so that no rank waits forever in a collective that another one has left.
  auto agree = [&](const std::string& localError) -> bool {
    int ok = localError.empty() ? 1 : 0;
    if (ranks > 1)
    {
      int allOk = 0;
      controller->AllReduce(&ok, &allOk, 1, vtkCommunicator::MIN_OP);
      if (allOk == 0 && ok == 1)
      {
        vtkErrorMacro("Another MPI rank failed (see its error); no image.");
      }
      ok = allOk;
    }
    if (!localError.empty())
    {
      vtkErrorMacro(<< localError);
    }
    return ok == 1;
  };

  // 1. This rank's piece of n - 1.
  std::string problem;
  int ext[6] = { 0, -1, 0, -1, 0, -1 };
  std::vector<float> values;
  if (!input || !output)
  {
    problem = NotAnImage(vtkDataObject::GetData(inInfo));
  }
  else if (!input->GetDirectionMatrix()->IsIdentity())
  {
    problem = "SchlierenImage traces axis-aligned images only; this one has a direction matrix. "
              "Resample it onto an axis-aligned image first.";
  }
  else if (this->Passes < 1)
  {
    std::ostringstream msg;
    msg << "Passes is " << this->Passes << "; it must be at least 1 (one photon per pixel per pass).";
    problem = msg.str();
  }
  else if (input->GetNumberOfPoints() > 0)
  {
    vtkDataArray* array = input->GetPointData()->GetArray(IndexArrayName);
    if (!array)
    {
      problem = std::string("SchlierenImage needs the point array 'n_minus_1' (n - 1); the input "
                            "has the point arrays: ") +
        PointArrayNames(input) + ". Apply RefractiveIndex first.";
    }
    else if (array->GetNumberOfComponents() != 1)
    {
      problem = "The point array 'n_minus_1' must have one component.";
    }
    else
    {
      input->GetExtent(ext);
      const vtkIdType count = array->GetNumberOfTuples();
      values.resize(static_cast<std::size_t>(count));
      for (vtkIdType i = 0; i < count; ++i)
      {
        values[i] = static_cast<float>(array->GetComponent(i, 0));
      }
    }
  }
  else if (ranks == 1)
  {
    problem = "SchlierenImage: the input image is empty.";
  }
  if (!agree(problem))
  {
    return 0;
  }

  // 2. The whole volume on every rank.
  schlieren::Volume volume = WholeVolume(inInfo);
  int whole[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  const std::size_t total = volume.NumberOfPoints();
  std::vector<float> field;
  if (ranks == 1 && std::equal(ext, ext + 6, whole))
  {
    field.swap(values);
  }
  else
  {
    field.assign(total, 0.0f);
    std::vector<unsigned char> covered(total, 0);
    if (ranks == 1)
    {
      Insert(whole, ext, values.data(), field, covered);
    }
    else
    {
      std::vector<int> extents(6 * static_cast<std::size_t>(ranks));
      controller->AllGather(ext, extents.data(), 6);
      std::vector<vtkIdType> counts(ranks), offsets(ranks);
      vtkIdType sum = 0;
      for (int r = 0; r < ranks; ++r)
      {
        counts[r] = ExtentPoints(&extents[6 * r]);
        offsets[r] = sum;
        sum += counts[r];
      }
      std::vector<float> all(static_cast<std::size_t>(std::max<vtkIdType>(sum, 1)));
      controller->AllGatherV(values.data(), all.data(), static_cast<vtkIdType>(values.size()),
        counts.data(), offsets.data());
      for (int r = 0; r < ranks; ++r)
      {
        Insert(whole, &extents[6 * r], all.data() + offsets[r], field, covered);
      }
    }
    // The same answer on every rank: no agreement needed.
    if (std::find(covered.begin(), covered.end(), 0) != covered.end())
    {
      vtkErrorMacro("The input pieces do not cover the input's whole extent; the tracer needs "
                    "the whole volume.");
      return 0;
    }
  }
  this->UpdateProgress(0.05);

  // 3. n - 1 and its gradient, packed; then this rank's share of the photons.
  schlieren::TraceSettings settings = SettingsOf(this);
  settings.RankIndex = rank;
  settings.RankCount = ranks;
  std::vector<float> packed;
  schlieren::FilmSums sums;
  std::string backendUsed, deviceName, warnings;
  try
  {
    packed.resize(4 * total);
    schlieren::PackField(volume.Dimensions, volume.Spacing, field.data(), packed.data());
    std::vector<float>().swap(field);
    volume.Field = packed.data();
    const schlieren::FilmGeometry film = schlieren::MakeFilm(volume, settings);
    sums.Resize(film.Size[0], film.Size[1]);
    schlieren::Accumulate(volume, settings, sums, &backendUsed, &deviceName, &warnings,
      [this](double progress) {
        this->UpdateProgress(0.05 + 0.9 * progress);
        return !this->GetAbortExecute();
      });
    problem.clear();
  }
  catch (const schlieren::Error& e)
  {
    problem = e.what();
  }
  if (!agree(problem))
  {
    return 0;
  }
  if (!warnings.empty())
  {
    if (ranks > 1)
    {
      vtkWarningMacro("rank " << rank << ": " << warnings);
    }
    else
    {
      vtkWarningMacro(<< warnings);
    }
  }

  // 4. The film sums of all ranks, on rank 0.
  if (ranks > 1)
  {
    // every additive part of the sums (all channels and totals) in one reduce, the maxima in
    // another: the engine lists them, so a new channel needs no change here
    std::vector<double> additive, maxima;
    sums.ToArrays(additive, maxima);
    std::vector<double> summed(additive.size()), maxed(maxima.size());
    controller->Reduce(additive.data(), summed.data(), static_cast<vtkIdType>(additive.size()),
      vtkCommunicator::SUM_OP, 0);
    controller->Reduce(maxima.data(), maxed.data(), static_cast<vtkIdType>(maxima.size()),
      vtkCommunicator::MAX_OP, 0);
    if (rank != 0)
    {
      output->Initialize(); // rank 0 holds the image
      return 1;
    }
    sums.FromArrays(summed, maxed);
  }

  // 5. The image (rank 0).
  schlieren::TraceResult result;
  try
  {
    result = schlieren::Finalize(volume, settings, sums);
  }
  catch (const schlieren::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  if (!result.Warnings.empty() && result.Warnings != warnings)
  {
    vtkWarningMacro(<< result.Warnings);
  }

  const int nx = result.Film.Size[0], ny = result.Film.Size[1];
  double origin[2];
  result.Film.GetImageOrigin(origin);
  output->Initialize();
  output->SetExtent(0, nx - 1, 0, ny - 1, 0, 0);
  output->SetSpacing(result.Film.PixelSize, result.Film.PixelSize, 1.0);
  output->SetOrigin(origin[0], origin[1], 0.0);

  const vtkIdType pixels = static_cast<vtkIdType>(nx) * ny;
  vtkNew<vtkFloatArray> intensity;
  intensity->SetName("intensity");
  intensity->SetNumberOfTuples(pixels);
  vtkNew<vtkFloatArray> deflection;
  deflection->SetName("deflection");
  deflection->SetNumberOfComponents(2);
  deflection->SetComponentName(0, "x");
  deflection->SetComponentName(1, "y");
  deflection->SetNumberOfTuples(pixels);
  if (result.Intensity.size() != static_cast<std::size_t>(pixels) ||
    result.Deflection.size() != 2 * static_cast<std::size_t>(pixels))
  {
    vtkErrorMacro("The engine returned an image of the wrong size.");
    output->Initialize();
    return 0;
  }
  std::copy(result.Intensity.begin(), result.Intensity.end(), intensity->GetPointer(0));
  std::copy(result.Deflection.begin(), result.Deflection.end(), deflection->GetPointer(0));
  output->GetPointData()->SetScalars(intensity);
  output->GetPointData()->AddArray(deflection);

  vtkFieldData* fd = output->GetFieldData();
  auto addNumber = [fd](const char* name, double value) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  auto addString = [fd](const char* name, const std::string& value) {
    vtkNew<vtkStringArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  addNumber("cutoff_scale", result.CutoffScaleUsed);
  addString("backend", result.BackendUsed.empty() ? backendUsed : result.BackendUsed);
  addString("device", result.DeviceName.empty() ? deviceName : result.DeviceName);
  addNumber("photons", result.Photons);
  addNumber("samples", result.Samples);
  addNumber("failed_rays", result.FailedRays);
  addNumber("missed_rays", result.MissedRays);
  addNumber("max_drift", result.MaxDrift);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSchlierenImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ViewDirection: " << this->ViewDirection[0] << " " << this->ViewDirection[1]
     << " " << this->ViewDirection[2] << "\n";
  os << indent << "ViewUp: " << this->ViewUp[0] << " " << this->ViewUp[1] << " " << this->ViewUp[2]
     << "\n";
  os << indent << "Resolution: " << this->Resolution[0] << " " << this->Resolution[1] << "\n";
  os << indent << "Passes: " << this->Passes << "\n";
  os << indent << "StepSize: " << this->StepSize << " voxels\n";
  os << indent << "Integrator: " << (this->Integrator == MIDPOINT ? "Midpoint" : "Euler") << "\n";
  os << indent << "Cutoff: " << (this->Cutoff == SHADOWGRAPH ? "Shadowgraph" : "KnifeEdge") << "\n";
  os << indent << "KnifeAngle: " << this->KnifeAngle << " degrees\n";
  os << indent << "CutoffScale: " << this->CutoffScale << (this->CutoffScale == 0 ? " (automatic)" : "")
     << "\n";
  os << indent << "FilmDistance: " << this->FilmDistance << "\n";
  os << indent << "Jitter: " << (this->Jitter ? "On" : "Off") << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Backend: "
     << (this->Backend == OPENCL ? "OpenCL" : (this->Backend == CPU ? "CPU" : "Auto")) << "\n";
}
