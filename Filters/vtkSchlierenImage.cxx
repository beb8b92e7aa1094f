// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSchlierenImage.h"
#include "SchlierenGuard.h"

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include "SchlierenEngine.h"
#include "SchlierenLimits.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSchlierenImage);

namespace
{
const char* const IndexArrayName = "n_minus_1";
const char* const SolidArrayName = "solid";

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
struct vtkSchlierenImage::vtkInternals
{
  schlieren::FilmSums Sums; // this rank's sums of the passes traced so far
  std::string Key;          // the photons' settings and the input they were traced from
  // the whole volume of the last trace (n - 1 and gradient, octree levels) and the input it came
  // from: kept while only the view, optics or passes change
  std::string VolumeKey;
  schlieren::AlignedFloats Packed; // page-aligned: a CPU OpenCL device traces it in place
  std::vector<unsigned char> Levels;
  std::vector<unsigned char> Solid; // the input's `solid` points (empty: no body)
  std::vector<unsigned char> Smooth; // PackFieldHighOrder's smoothness (Reconstruction not trilinear)
  schlieren::Volume Volume;
};

//------------------------------------------------------------------------------
vtkSchlierenImage::vtkSchlierenImage()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkSchlierenImage::~vtkSchlierenImage()
{
  // the engine's device copy may be this filter's volume: free it with the filter
  if (this->Internals->Volume.Stamp != 0)
  {
    schlieren::ReleaseKeptVolume();
  }
  delete this->Internals;
}

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
  s.Recon = static_cast<schlieren::Reconstruction>(self->GetReconstruction());
  s.Tolerance = self->GetTolerance();
  s.KeepInvariant = self->GetKeepInvariant();
  s.EstimateError = self->GetEstimateError();
  s.UseOctree = self->GetUseOctree();
  s.Mode = static_cast<schlieren::Cutoff>(self->GetCutoff());
  s.KnifeAngle = self->GetKnifeAngle();
  s.CutoffScale = self->GetCutoffScale();
  s.FilmDistance = self->GetFilmDistance();
  s.Wavelength = self->GetWavelength();
  s.ReferenceTilt = self->GetReferenceTilt();
  s.BackgroundDistance = self->GetBackgroundDistance();
  s.BackgroundPattern = self->GetBackgroundPattern();
  s.BackgroundPeriod = self->GetBackgroundPeriod();
  s.Filter = static_cast<schlieren::FilmFilter>(self->GetFilter());
  s.FilterWidth = self->GetFilterWidth();
  s.RussianRoulette = self->GetRussianRoulette();
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

/** What the input says about its octree (vtkRefractionOctree's array and field data). */
struct OctreeInfo
{
  bool Present = false;      ///< the point array `octree_level` is there
  bool HasTolerance = false; ///< and the field data `octree_tolerance`
  double Tolerance = 0.0;
  int MaxLevel = 7;
};

/** A number of the field data, or `fallback`. */
double FieldNumber(vtkDataSet* ds, const char* name, double fallback, bool* found = nullptr)
{
  vtkDataArray* a = ds->GetFieldData() ? ds->GetFieldData()->GetArray(name) : nullptr;
  const bool ok = a && a->GetNumberOfTuples() > 0 && a->GetNumberOfComponents() == 1 &&
    std::isfinite(a->GetComponent(0, 0));
  if (found)
  {
    *found = ok;
  }
  return ok ? a->GetComponent(0, 0) : fallback;
}

/** The piece's octree levels (as bytes) and what its field data says about them. */
OctreeInfo ReadOctree(vtkImageData* input, std::vector<unsigned char>& levels)
{
  OctreeInfo info;
  vtkDataArray* array = input->GetPointData()->GetArray("octree_level");
  if (!array || array->GetNumberOfComponents() != 1 ||
    array->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    return info;
  }
  info.Present = true;
  levels.resize(static_cast<std::size_t>(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    const double v = array->GetComponent(i, 0);
    levels[i] = static_cast<unsigned char>(std::max(0.0, std::min(10.0, v)));
  }
  info.Tolerance = FieldNumber(input, "octree_tolerance", 0.0, &info.HasTolerance);
  info.HasTolerance = info.HasTolerance && info.Tolerance >= 0;
  info.MaxLevel = static_cast<int>(FieldNumber(input, "octree_max_level", 7.0));
  return info;
}

/** A float point array of `pixels` tuples from an engine image, with component names. */
vtkSmartPointer<vtkFloatArray> FloatArray(const char* name, const std::vector<float>& values,
  int components, vtkIdType pixels, const char* c0 = nullptr, const char* c1 = nullptr,
  const char* c2 = nullptr)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  const char* names[3] = { c0, c1, c2 };
  for (int c = 0; c < components && c < 3; ++c)
  {
    if (names[c])
    {
      a->SetComponentName(c, names[c]);
    }
  }
  a->SetNumberOfTuples(pixels);
  std::copy(values.begin(), values.begin() + static_cast<std::size_t>(components) * pixels,
    a->GetPointer(0));
  return a;
}

/**
 * Resolves Integrator Auto (settings.Method) into the integrator and step it chooses, and whether
 * the octree pays for it (settings.UseOctree); other integrators come back unchanged. Rank 0 resolves (its pilot traces the same rays as every other
 * rank would; doing it once and broadcasting the choice makes every rank trace with the same
 * setting even if their backends were to round differently) and every rank adopts its choice.
 * Collective under MPI. Returns false (with an error reported) if Auto failed.
 */
bool ResolveIntegrator(vtkSchlierenImage* self, const schlieren::Volume& volume,
  schlieren::TraceSettings& settings, schlieren::AutoChoice& choice,
  vtkMultiProcessController* controller, int ranks, int rank)
{
  if (settings.Method != schlieren::Integrator::Auto &&
    settings.Recon != schlieren::Reconstruction::Auto)
  {
    choice = schlieren::AutoChoice();
    choice.Method = settings.Method;
    choice.StepSize = settings.StepSize;
    choice.Recon = settings.Recon;
    return true;
  }
  std::string error;
  // ok, method, step, measured error, expected error, landing error, samples per ray,
  // tolerance, met, octree, reconstruction, the trilinear's estimated error
  std::vector<double> numbers(12, 0.0);
  if (rank == 0)
  {
    try
    {
      schlieren::TraceSettings pilot = settings;
      pilot.RankIndex = 0;
      pilot.RankCount = 1;
      const schlieren::TraceSettings chosen = schlieren::ResolveAuto(volume, pilot, &choice);
      numbers = { 1.0, double(static_cast<int>(chosen.Method)), chosen.StepSize,
        chosen.AutoMeasuredError, choice.ExpectedError, choice.ExpectedLandingError,
        choice.SamplesPerRay, choice.Tolerance, choice.Met ? 1.0 : 0.0,
        chosen.UseOctree ? 1.0 : 0.0, double(static_cast<int>(chosen.Recon)), choice.TrilinearError };
    }
    catch (const schlieren::Error& e)
    {
      error = e.what();
      numbers.assign(12, 0.0);
    }
  }
  std::string text = error.empty() ? choice.Report : error;
  if (ranks > 1)
  {
    controller->Broadcast(numbers.data(), static_cast<vtkIdType>(numbers.size()), 0);
    vtkIdType length = static_cast<vtkIdType>(text.size());
    controller->Broadcast(&length, 1, 0);
    std::vector<char> chars(text.begin(), text.end());
    chars.resize(static_cast<std::size_t>(length) + 1, '\0');
    controller->Broadcast(chars.data(), length + 1, 0);
    text.assign(chars.data(), static_cast<std::size_t>(length));
  }
  if (numbers[0] != 1.0)
  {
    if (rank == 0)
    {
      vtkErrorWithObjectMacro(self, << text);
    }
    else
    {
      vtkErrorWithObjectMacro(self, "Integrator Auto failed on rank 0 (see its error); no image.");
    }
    return false;
  }
  settings.Method = static_cast<schlieren::Integrator>(static_cast<int>(numbers[1]));
  settings.StepSize = numbers[2];
  settings.AutoMeasuredError = numbers[3];
  settings.UseOctree = numbers[9] == 1.0;
  settings.Recon = static_cast<schlieren::Reconstruction>(static_cast<int>(numbers[10]));
  choice.Recon = settings.Recon;
  choice.TrilinearError = numbers[11];
  choice.Method = settings.Method;
  choice.StepSize = settings.StepSize;
  choice.ExpectedError = numbers[4];
  choice.ExpectedLandingError = numbers[5];
  choice.SamplesPerRay = numbers[6];
  choice.Tolerance = numbers[7];
  choice.Met = numbers[8] == 1.0;
  choice.UseOctree = settings.UseOctree;
  choice.Report = text;
  if (rank == 0)
  {
    vtkLog(INFO, << "SchlierenImage: " << choice.Report);
    if (!choice.Met)
    {
      vtkWarningWithObjectMacro(self, << choice.Report);
    }
  }
  return true;
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
  int inWhole[6] = { 0, -1, 0, -1, 0, -1 };
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), inWhole);
  }
  if (inWhole[1] < inWhole[0] || inWhole[3] < inWhole[2] || inWhole[5] < inWhole[4])
  {
    // Not a grid with too few points: nothing came (a filter upstream that failed said why).
    vtkErrorMacro(<< "The input volume is empty: nothing to trace. If a filter upstream reported "
                     "an error, that is the cause; fix it there.");
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

  // 0. The packed volume of the last trace, if the input has not changed since (a new camera,
  // other optics, more passes): steps 1-3 below are skipped, and the engine keeps its device copy
  // of the volume (Volume::Stamp), so that an interactive view re-traces without re-uploading.
  vtkInternals& cache = *this->Internals;
  std::string volumeKey;
  if (input && output)
  {
    int pieceExtent[6], wholeExtent[6];
    input->GetExtent(pieceExtent);
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent);
    std::ostringstream vk;
    vk << input->GetMTime() << " " << this->UseOctree << " " << ranks << " "
       << (this->Reconstruction != TRILINEAR);
    for (int a = 0; a < 6; ++a)
    {
      vk << " " << pieceExtent[a] << " " << wholeExtent[a];
    }
    volumeKey = vk.str();
  }
  int reuseVolume =
    (!volumeKey.empty() && volumeKey == cache.VolumeKey && this->Passes >= 1) ? 1 : 0;
  if (ranks > 1)
  {
    int all = 0;
    controller->AllReduce(&reuseVolume, &all, 1, vtkCommunicator::MIN_OP);
    reuseVolume = all;
  }
  std::string problem;
  schlieren::Volume volume;
  schlieren::AlignedFloats packed;
  std::vector<unsigned char> levels, smooth;
  std::vector<unsigned char> solid;
  // steps 1-3: the volume from the input; 0 when it failed (reported, agreed by all ranks)
  auto buildVolume = [&]() -> int {
    // 1. This rank's piece of n - 1 (and of the octree levels, where asked for and present).
    int ext[6] = { 0, -1, 0, -1, 0, -1 };
    std::vector<float> values;
    std::vector<float> solidValues; // the piece's `solid` array (1 solid, 0 not), if any
    std::vector<unsigned char> pieceLevels;
    OctreeInfo octree;
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
        if (this->UseOctree)
        {
          octree = ReadOctree(input, pieceLevels);
        }
        // solid bodies (RefractiveIndex, RefractiveScene): non-zero points stop the rays
        vtkDataArray* solidArray = input->GetPointData()->GetArray(SolidArrayName);
        if (solidArray && solidArray->GetNumberOfComponents() == 1 &&
          solidArray->GetNumberOfTuples() == count)
        {
          solidValues.resize(static_cast<std::size_t>(count));
          bool any = false;
          for (vtkIdType i = 0; i < count; ++i)
          {
            solidValues[i] = solidArray->GetComponent(i, 0) != 0.0 ? 1.0f : 0.0f;
            any = any || solidValues[i] != 0.0f;
          }
          if (!any)
          {
            solidValues.clear();
          }
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
    volume = WholeVolume(inInfo);
    int whole[6];
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    const std::size_t total = volume.NumberOfPoints();
    std::vector<float> field;
    const bool wholePiece = ranks == 1 && std::equal(ext, ext + 6, whole);
    // the solid points: every rank learns whether any piece has a body, and gathers them as the
    // field below
    int hasSolid = solidValues.empty() ? 0 : 1;
    if (ranks > 1)
    {
      int anySolid = 0;
      controller->AllReduce(&hasSolid, &anySolid, 1, vtkCommunicator::MAX_OP);
      hasSolid = anySolid;
      if (hasSolid && solidValues.empty())
      {
        solidValues.assign(values.size(), 0.0f);
      }
    }
    // pass 0: n - 1 into `field`; pass 1 (with a body): the solid points into `solid`
    for (int pass = 0; pass < (hasSolid ? 2 : 1); ++pass)
    {
      std::vector<float>& source = pass == 0 ? values : solidValues;
      std::vector<float> gathered;
      if (wholePiece)
      {
        gathered.swap(source);
      }
      else
      {
        gathered.assign(total, 0.0f);
        std::vector<unsigned char> covered(total, 0);
        if (ranks == 1)
        {
          Insert(whole, ext, source.data(), gathered, covered);
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
          controller->AllGatherV(source.data(), all.data(), static_cast<vtkIdType>(source.size()),
            counts.data(), offsets.data());
          for (int r = 0; r < ranks; ++r)
          {
            Insert(whole, &extents[6 * r], all.data() + offsets[r], gathered, covered);
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
      if (pass == 0)
      {
        field.swap(gathered);
      }
      else
      {
        solid.resize(total);
        for (std::size_t i = 0; i < total; ++i)
        {
          solid[i] = gathered[i] != 0.0f ? 1 : 0;
        }
      }
    }
    std::vector<float>().swap(values);

    // 2b. The octree levels of the whole volume. One process with the whole volume: the input's
    // `octree_level` as it is. Otherwise (MPI pieces, whose levels stop at the piece borders): the
    // levels of the gathered volume, recomputed at the tolerance the octree filter used.
    if (ranks > 1)
    {
      // every rank the same: the octree if any piece has one, the smallest tolerance, the highest level
      double local[3] = { octree.Present ? 1.0 : 0.0,
        octree.Present && octree.HasTolerance ? -octree.Tolerance : -VTK_DOUBLE_MAX,
        octree.Present ? double(octree.MaxLevel) : -1.0 };
      double global[3];
      controller->AllReduce(local, global, 3, vtkCommunicator::MAX_OP);
      octree.Present = global[0] > 0;
      octree.HasTolerance = global[1] > -VTK_DOUBLE_MAX;
      octree.Tolerance = octree.HasTolerance ? -global[1] : 0.0;
      octree.MaxLevel = static_cast<int>(global[2]);
    }
    std::string octreeNote;
    if (this->UseOctree && octree.Present)
    {
      if (wholePiece && pieceLevels.size() == total)
      {
        levels.swap(pieceLevels);
      }
      else if (octree.HasTolerance && volume.Dimensions[0] >= 2 && volume.Dimensions[1] >= 2 &&
        volume.Dimensions[2] >= 2)
      {
        levels.resize(total);
        // ValidateIndex runs in PackField below; ComputeOctreeLevels itself only reads values
        schlieren::ComputeOctreeLevels(
          volume.Dimensions, field.data(), octree.Tolerance, levels.data(), octree.MaxLevel);
      }
      else
      {
        octreeNote = "The input has the point array 'octree_level' but not the field data "
                     "'octree_tolerance' it was built for, and the levels of its pieces cannot be "
                     "joined: tracing without the octree. Apply RefractionOctree right before "
                     "SchlierenImage.";
      }
    }
    if (!octreeNote.empty() && rank == 0)
    {
      vtkWarningMacro(<< octreeNote);
    }
    this->UpdateProgress(0.05);

    // 3. n - 1 and its gradient, packed; Auto resolved (on rank 0, broadcast); then this rank's
    // share of the photons.
    try
    {
      std::ostringstream what;
      what << "Tracing the " << volume.Dimensions[0] << " x " << volume.Dimensions[1] << " x "
           << volume.Dimensions[2] << " volume";
      schlieren::CheckHostMemory(double(total) * (schlieren::VolumeBytesPerPoint() - 4.0),
        what.str(),
        "Resample the data to fewer points (RefractiveIndex SamplingDimensions or "
        "AutomaticDimension), or trace a subset (ExtractSubset).");
      packed.resize(4 * total);
      if (this->Reconstruction == TRILINEAR)
      {
        schlieren::PackField(volume.Dimensions, volume.Spacing, field.data(), packed.data());
      }
      else
      {
        // fourth-order gradients where the data is smooth, and the smoothness per cell
        smooth.resize(total);
        schlieren::PackFieldHighOrder(
          volume.Dimensions, volume.Spacing, field.data(), packed.data(), smooth.data());
      }
      std::vector<float>().swap(field);
      volume.Field = packed.data();
      if (!levels.empty())
      {
        volume.Levels = levels.data();
        volume.LevelTolerance = octree.HasTolerance ? octree.Tolerance : 0.0;
      }
      problem.clear();
    }
    catch (const schlieren::Error& e)
    {
      problem = e.what();
    }
    catch (const std::bad_alloc&)
    {
      problem = "Out of memory while packing the volume (std::bad_alloc): resample it to fewer "
                "points.";
    }
    if (!agree(problem))
    {
      return 0;
    }
    return 1;
  };
  if (reuseVolume)
  {
    volume = cache.Volume;
    this->UpdateProgress(0.05);
  }
  else
  {
    cache.VolumeKey.clear();
    cache.Packed.clear();
    cache.Levels.clear();
    cache.Solid.clear();
    cache.Smooth.clear();
    if (!buildVolume())
    {
      return 0;
    }
    cache.Packed.swap(packed);
    cache.Levels.swap(levels);
    cache.Solid.swap(solid);
    volume.Solid = cache.Solid.empty() ? nullptr : cache.Solid.data();
    cache.Smooth.swap(smooth);
    volume.Field = cache.Packed.data();
    volume.Levels = cache.Levels.empty() ? nullptr : cache.Levels.data();
    volume.Smooth = cache.Smooth.empty() ? nullptr : cache.Smooth.data();
    volume.Stamp = schlieren::NewVolumeStamp();
    cache.Volume = volume;
    cache.VolumeKey = volumeKey;
  }
  schlieren::TraceSettings settings = SettingsOf(this);
  schlieren::AutoChoice choice;
  schlieren::FilmSums sums;
  std::string backendUsed, deviceName, warnings;
  if (!ResolveIntegrator(this, volume, settings, choice, controller, ranks, rank))
  {
    return 0;
  }
  settings.RankIndex = rank;
  settings.RankCount = ranks;
  // Progressive refinement: if only Passes grew since the last trace of the same input with the
  // same photon settings, continue the cached sums with the new passes (the jitter sequence goes on
  // where it stopped, so the image equals a trace of all passes at once).
  std::ostringstream keyStream;
  keyStream.precision(17);
  keyStream << settings.PhotonKey() << " | " << input->GetMTime() << ' ' << volume.Dimensions[0]
            << ' ' << volume.Dimensions[1] << ' ' << volume.Dimensions[2] << ' '
            << volume.Origin[0] << ' ' << volume.Origin[1] << ' ' << volume.Origin[2] << ' '
            << volume.Spacing[0] << ' ' << volume.Spacing[1] << ' ' << volume.Spacing[2] << ' '
            << (volume.Levels ? 1 : 0) << ' ' << volume.LevelTolerance << ' '
            << (volume.Solid ? 1 : 0);
  const std::string key = keyStream.str();
  int reuse = (key == cache.Key && cache.Sums.Passes > 0 && this->Passes >= cache.Sums.Passes) ? 1 : 0;
  if (ranks > 1)
  {
    int all = 0;
    controller->AllReduce(&reuse, &all, 1, vtkCommunicator::MIN_OP);
    reuse = all;
  }
  int passesTraced = 0;
  try
  {
    const schlieren::FilmGeometry film = schlieren::MakeFilm(volume, settings);
    if (!reuse)
    {
      cache.Sums.Resize(0, 0); // the old film goes before the new one is checked and made
      schlieren::CheckFilmMemory(film.Size);
      cache.Sums.Resize(film.Size[0], film.Size[1]);
    }
    cache.Key.clear(); // valid again only once the passes below are all in
    passesTraced = this->Passes - cache.Sums.Passes;
    if (passesTraced > 0)
    {
      settings.Passes = passesTraced;
      schlieren::Accumulate(volume, settings, cache.Sums, &backendUsed, &deviceName, &warnings,
        [this](double progress) {
          this->UpdateProgress(0.05 + 0.9 * progress);
          return !this->GetAbortExecute();
        });
    }
    settings.Passes = this->Passes;
    cache.Key = key;
    sums = cache.Sums;
    problem.clear();
  }
  catch (const schlieren::Error& e)
  {
    cache.Sums.Resize(0, 0);
    problem = e.what();
  }
  catch (const std::bad_alloc&)
  {
    // here, not in ProcessRequest's guard: under MPI the other ranks wait in agree() below
    cache.Sums.Resize(0, 0);
    problem = "Out of memory while tracing (std::bad_alloc): lower Resolution or resample the "
              "volume to fewer points.";
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
  if (result.Intensity.size() != static_cast<std::size_t>(pixels) ||
    result.Deflection.size() != 2 * static_cast<std::size_t>(pixels))
  {
    vtkErrorMacro("The engine returned an image of the wrong size.");
    output->Initialize();
    return 0;
  }
  vtkPointData* pd = output->GetPointData();
  pd->SetScalars(FloatArray("intensity", result.Intensity, 1, pixels));
  pd->AddArray(FloatArray("deflection", result.Deflection, 2, pixels, "x", "y"));
  if (!result.RGB.empty())
  {
    pd->AddArray(FloatArray("rgb", result.RGB, 3, pixels, "r", "g", "b"));
  }
  if (!result.Phase.empty())
  {
    pd->AddArray(FloatArray("phase", result.Phase, 1, pixels));
  }
  if (!result.Displacement.empty())
  {
    pd->AddArray(FloatArray("bos_displacement", result.Displacement, 2, pixels, "x", "y"));
  }
  if (!result.ErrorEstimate.empty())
  {
    pd->AddArray(FloatArray("error_estimate", result.ErrorEstimate, 1, pixels));
  }
  if (!result.Blocked.empty())
  {
    pd->AddArray(FloatArray("blocked", result.Blocked, 1, pixels));
  }

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
  // what the user was warned of (empty: nothing), for scripts that check an image is usable
  addString("warnings", warnings + (result.Warnings != warnings ? result.Warnings : std::string()));
  addString("backend", result.BackendUsed.empty() ? backendUsed : result.BackendUsed);
  addString("device", result.DeviceName.empty() ? deviceName : result.DeviceName);
  addNumber("photons", result.Photons);
  addNumber("passes", sums.Passes);
  addNumber("passes_traced", passesTraced);
  addNumber("samples", result.Samples);
  addNumber("samples_per_ray", result.Photons > 0 ? result.Samples / result.Photons : 0.0);
  addNumber("failed_rays", result.FailedRays);
  addNumber("missed_rays", result.MissedRays);
  double landed = 0; // photons that reached the film (0: a blank image, which the warnings explain)
  for (double c : sums.Count)
  {
    landed += c;
  }
  addNumber("landed_photons", landed);
  addNumber("underresolved_rays", result.UnderresolvedRays);
  addNumber("side_rays", result.SideRays);
  addNumber("blocked_rays", result.BlockedRays);
  addNumber("max_drift", result.MaxDrift);
  addNumber("max_error", result.MaxError);
  addString("integrator", schlieren::IntegratorName(settings.Method));
  addString("reconstruction", schlieren::ReconstructionName(settings.Recon));
  addNumber("step_size", settings.StepSize);
  // Auto may have found that the octree does not pay (settings.UseOctree off)
  const bool octreeUsed = volume.Levels && settings.UseOctree;
  addNumber("octree", octreeUsed ? 1.0 : 0.0);
  if (octreeUsed)
  {
    addNumber("octree_tolerance", volume.LevelTolerance);
  }
  if (this->Integrator == AUTO_INTEGRATOR || this->Reconstruction == AUTO_RECONSTRUCTION)
  {
    addString("auto_report", choice.Report);
    addNumber("expected_error", choice.ExpectedError);
    addNumber("auto_tolerance", choice.Tolerance);
    addNumber("auto_met", choice.Met ? 1.0 : 0.0);
  }
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
  os << indent << "Integrator: "
     << schlieren::IntegratorName(static_cast<schlieren::Integrator>(this->Integrator)) << "\n";
  os << indent << "Reconstruction: "
     << schlieren::ReconstructionName(static_cast<schlieren::Reconstruction>(this->Reconstruction))
     << "\n";
  os << indent << "Tolerance: " << this->Tolerance
     << (this->Tolerance > 0 ? " rad" : " (automatic: 1 % of the largest deflection)") << "\n";
  os << indent << "KeepInvariant: " << (this->KeepInvariant ? "On" : "Off") << "\n";
  os << indent << "EstimateError: " << (this->EstimateError ? "On" : "Off") << "\n";
  os << indent << "UseOctree: " << (this->UseOctree ? "On" : "Off") << "\n";
  os << indent << "Cutoff: " << schlieren::CutoffName(static_cast<schlieren::Cutoff>(this->Cutoff))
     << "\n";
  os << indent << "KnifeAngle: " << this->KnifeAngle << " degrees\n";
  os << indent << "CutoffScale: " << this->CutoffScale << (this->CutoffScale == 0 ? " (automatic)" : "")
     << "\n";
  os << indent << "FilmDistance: " << this->FilmDistance << "\n";
  os << indent << "Wavelength: " << this->Wavelength << " nm\n";
  os << indent << "ReferenceTilt: " << this->ReferenceTilt << " fringes per world unit\n";
  os << indent << "BackgroundDistance: " << this->BackgroundDistance << "\n";
  os << indent << "BackgroundPattern: " << (this->BackgroundPattern == STRIPES ? "Stripes" : "Dots")
     << "\n";
  os << indent << "BackgroundPeriod: " << this->BackgroundPeriod
     << (this->BackgroundPeriod > 0 ? "" : " (6 pixels)") << "\n";
  os << indent << "Filter: "
     << (this->Filter == GAUSSIAN ? "Gaussian" : (this->Filter == CONE ? "Cone" : "None")) << "\n";
  os << indent << "FilterWidth: " << this->FilterWidth << " pixels\n";
  os << indent << "RussianRoulette: " << (this->RussianRoulette ? "On" : "Off") << "\n";
  os << indent << "Jitter: " << (this->Jitter ? "On" : "Off") << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Backend: "
     << (this->Backend == OPENCL ? "OpenCL" : (this->Backend == CPU ? "CPU" : "Auto")) << "\n";
}

//------------------------------------------------------------------------------
vtkTypeBool vtkSchlierenImage::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return SchlierenGuarded(this,
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); });
}
