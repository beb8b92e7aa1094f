// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSchlierenImage.h"
#include "SchlierenEnums.h"
#include "SchlierenGuard.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkInformationInformationVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include "SchlierenArrays.h"
#include "SchlierenController.h"
#include "SchlierenEngine.h"
#include "SchlierenFilmInformation.h"
#include "SchlierenSession.h"

#include <algorithm>
#include <memory>
#include <cctype>
#include <chrono>
#include <functional>
#include <cstdint>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSchlierenImage);

namespace
{
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

/** The whole extent, origin and spacing the information describes. */
void WholeGridOf(vtkInformation* inInfo, schlieren::VolumePiece& piece)
{
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), piece.WholeExtent);
  if (inInfo->Has(vtkDataObject::ORIGIN()))
  {
    inInfo->Get(vtkDataObject::ORIGIN(), piece.Origin);
  }
  if (inInfo->Has(vtkDataObject::SPACING()))
  {
    inInfo->Get(vtkDataObject::SPACING(), piece.Spacing);
  }
}

/** The engine's grid (without its field) of the whole extent described by the information. */
schlieren::Volume WholeVolume(vtkInformation* inInfo)
{
  schlieren::VolumePiece piece;
  WholeGridOf(inInfo, piece);
  schlieren::Volume volume;
  for (int a = 0; a < 3; ++a)
  {
    volume.Dimensions[a] = std::max(piece.WholeExtent[2 * a + 1] - piece.WholeExtent[2 * a] + 1, 0);
    volume.Origin[a] = piece.Origin[a] + piece.WholeExtent[2 * a] * piece.Spacing[a];
    volume.Spacing[a] = piece.Spacing[a];
  }
  return volume;
}

/** The values of a one-component array of any type, each converted by `convert` (VTK's typed
 * dispatch for the common types, the generic vtkDataArray path for the others). */
template <typename Out, typename Convert>
void ConvertArray(vtkDataArray* array, std::vector<Out>& out, Convert convert)
{
  auto worker = [&out, &convert](auto* a) {
    const auto values = vtk::DataArrayValueRange<1>(a);
    out.resize(static_cast<std::size_t>(values.size()));
    std::transform(values.begin(), values.end(), out.begin(),
      [&convert](auto v) { return convert(static_cast<double>(v)); });
  };
  if (!vtkArrayDispatch::Dispatch::Execute(array, worker))
  {
    worker(array);
  }
}

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

/** The piece's point array `name` if it has one component and a value per point, else null. */
vtkDataArray* PointScalars(vtkImageData* input, const char* name)
{
  vtkDataArray* a = input->GetPointData()->GetArray(name);
  return a && a->GetNumberOfComponents() == 1 && a->GetNumberOfTuples() == input->GetNumberOfPoints()
    ? a
    : nullptr;
}

/**
 * Reads the input piece's values for the engine: n - 1; the octree levels (vtkRefractionOctree's
 * `octree_level` and field data) where `octree` is asked for; the solid points (non-zero: in a body).
 * Returns why it cannot, or an empty string.
 */
std::string ReadPiece(vtkImageData* input, bool octree, schlieren::PieceValues& values)
{
  namespace arrays = schlieren::arrays;
  vtkDataArray* array = input->GetPointData()->GetArray(arrays::NMinus1);
  if (!array)
  {
    return std::string("SchlierenImage needs the point array 'n_minus_1' (n - 1); the input "
                       "has the point arrays: ") +
      PointArrayNames(input) + ". Apply RefractiveIndex first.";
  }
  if (array->GetNumberOfComponents() != 1)
  {
    return "The point array 'n_minus_1' must have one component.";
  }
  // floats are read in place: the input lives, unchanged, through the Update that loads them
  // (at 512³ the copy was 1.2 s of the first update and 512 MB)
  if (vtkFloatArray* floats = vtkFloatArray::SafeDownCast(array))
  {
    values.NMinus1InPlace = floats->GetPointer(0);
    values.NMinus1InPlaceCount = static_cast<std::size_t>(floats->GetNumberOfTuples());
  }
  else
  {
    ConvertArray(array, values.NMinus1, [](double v) { return static_cast<float>(v); });
  }
  vtkDataArray* levels = octree ? PointScalars(input, arrays::OctreeLevel) : nullptr;
  if (levels)
  {
    ConvertArray(levels, values.Levels,
      [](double v) { return static_cast<unsigned char>(std::max(0.0, std::min(10.0, v))); });
    values.LevelTolerance =
      FieldNumber(input, arrays::OctreeTolerance, 0.0, &values.HasLevelTolerance);
    values.MaxLevel = static_cast<int>(FieldNumber(input, arrays::OctreeMaxLevel, 7.0));
  }
  if (vtkDataArray* solid = PointScalars(input, arrays::Solid))
  {
    ConvertArray(solid, values.Solid, [](double v) -> unsigned char { return v != 0.0 ? 1 : 0; });
  }
  return std::string();
}

/** This rank's piece of the input, as the engine takes it (its values are read when needed). */
schlieren::VolumePiece PieceOf(
  vtkImageData* input, vtkImageData* output, vtkInformation* inInfo, bool octree)
{
  schlieren::VolumePiece piece;
  if (!input || !output)
  {
    piece.Problem = NotAnImage(vtkDataObject::GetData(inInfo));
    return piece;
  }
  if (!input->GetDirectionMatrix()->IsIdentity())
  {
    piece.Problem = "SchlierenImage traces axis-aligned images only; this one has a direction "
                    "matrix. Resample it onto an axis-aligned image first.";
    return piece;
  }
  WholeGridOf(inInfo, piece);
  if (input->GetNumberOfPoints() > 0)
  {
    input->GetExtent(piece.Extent);
  }
  piece.Version = input->GetMTime();
  piece.Load = [input, octree](schlieren::PieceValues& v) { return ReadPiece(input, octree, v); };
  return piece;
}

/** Versions handed out to time steps (by every SchlierenImage: none is handed out twice). */
std::uint64_t& Counter()
{
  static std::uint64_t n = 0;
  return n;
}

/**
 * A time step's input named by its time and the upstream pipeline's MTime rather than by the data
 * object's MTime (new whenever the upstream executes, even for a time it gave before), so that
 * the session finds the volume it packed for that time (TraceSession's earlier volumes).
 */
void TimeVersion(vtkAlgorithm* self, vtkImageData* input, vtkInformation* inInfo,
  schlieren::VolumePiece& piece, std::map<std::pair<vtkMTimeType, double>, std::uint64_t>& versions)
{
  auto* upstream = vtkDemandDrivenPipeline::SafeDownCast(self->GetInputExecutive(0, 0));
  if (!input || !upstream || !inInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) ||
    !input->GetInformation()->Has(vtkDataObject::DATA_TIME_STEP()))
  {
    return;
  }
  const std::pair<vtkMTimeType, double> key(upstream->GetPipelineMTime(),
    input->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()));
  for (auto it = versions.begin(); it != versions.end();)
  {
    it = it->first.first != key.first ? versions.erase(it) : std::next(it); // another pipeline
  }
  auto found = versions.find(key);
  if (found == versions.end())
  {
    // a number of its own, apart from any data object's MTime (the top bit)
    const std::uint64_t next = (std::uint64_t(1) << 63) + 1 + Counter()++;
    found = versions.emplace(key, next).first;
  }
  piece.Version = found->second;
}

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
  s.Frame = static_cast<schlieren::Framing>(self->GetFraming());
  s.Passes = self->GetPasses();
  if (self->GetPassLimit() > 0)
  {
    s.Passes = std::min(s.Passes, self->GetPassLimit());
  }
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
  s.Source = static_cast<schlieren::BenchSource>(self->GetSource());
  s.SourceSize[0] = self->GetSourceSize()[0];
  s.SourceSize[1] = self->GetSourceSize()[1];
  s.StopDiameter = self->GetStopDiameter();
  s.CollimatorFocalLength = self->GetCollimatorFocalLength();
  s.SchlierenFocalLength = self->GetSchlierenFocalLength();
  s.KnifeCut = self->GetKnifeCut();
  s.BitDepth = self->GetBitDepth();
  s.SaturationWarning = self->GetSaturationWarning();
  s.Camera = static_cast<schlieren::CameraModel>(self->GetCamera());
  s.CameraFocalLength = self->GetCameraFocalLength();
  s.FNumber = self->GetFNumber();
  s.CameraDistance = self->GetCameraDistance();
  s.FocusPlane = self->GetFocusPlane();
  s.SourceGridDistance = self->GetSourceGridDistance();
  s.FilmDistance = self->GetFilmDistance();
  s.Wavelength = self->GetWavelength();
  s.ReferenceTilt = self->GetReferenceTilt();
  s.WavelengthRange[0] = self->GetWavelengthRange()[0];
  s.WavelengthRange[1] = self->GetWavelengthRange()[1];
  s.WavelengthBins = self->GetWavelengthBins();
  s.Disperse = static_cast<schlieren::Dispersion>(self->GetDispersion());
  s.BackgroundDistance = self->GetBackgroundDistance();
  s.BackgroundPattern = self->GetBackgroundPattern();
  s.BackgroundPeriod = self->GetBackgroundPeriod();
  s.Filter = static_cast<schlieren::FilmFilter>(self->GetFilter());
  s.FilterWidth = self->GetFilterWidth();
  s.RussianRoulette = self->GetRussianRoulette();
  s.Jitter = self->GetJitter();
  s.Pattern = static_cast<schlieren::JitterPattern>(self->GetJitterPattern());
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
  s.DeviceName = self->GetDeviceName() ? self->GetDeviceName() : "";
  s.Threads = self->GetThreads();
  s.InPieces = self->GetTraceInPieces() != 0;
  return s;
}

/** The settings an error is said again for when they change (all but the GUI's PassLimit). */
std::string ErrorKey(vtkSchlierenImage* self)
{
  return SettingsOf(self).PhotonKey() + " | passes " + std::to_string(self->GetPasses()) +
    " | filter " + std::to_string(self->GetFilter());
}

/**
 * Fills the range cache of a float array whose values are all finite: every component's range and,
 * for more than one component, the range of the tuples' L2 norm, as vtkDataArray computes them
 * (double minima and maxima; the norm's from the sums of squares in component order), for all
 * values and for the finite ones (the same here). ParaView's data information asks each of these
 * after every update and would otherwise compute them on one thread, twice (docs/PERFORMANCE.md
 * has what that cost a camera move). An array with a NaN or an infinity is left to VTK.
 */
void SeedRanges(vtkFloatArray* a, vtkIdType tuples)
{
  const int nc = a->GetNumberOfComponents();
  if (tuples < 1 || nc < 1 || nc > 3)
  {
    return;
  }
  const float* v = a->GetPointer(0);
  double lo[3], hi[3], n2lo = 0, n2hi = 0;
  for (int c = 0; c < nc; ++c)
  {
    lo[c] = hi[c] = v[c];
  }
  bool finite = true;
  for (vtkIdType t = 0; t < tuples; ++t)
  {
    double n2 = 0;
    for (int c = 0; c < nc; ++c)
    {
      const double x = v[t * nc + c];
      finite = finite && std::isfinite(x);
      lo[c] = std::min(lo[c], x);
      hi[c] = std::max(hi[c], x);
      n2 += x * x;
    }
    n2lo = t == 0 ? n2 : std::min(n2lo, n2);
    n2hi = t == 0 ? n2 : std::max(n2hi, n2);
  }
  if (!finite)
  {
    return;
  }
  vtkInformation* info = a->GetInformation();
  for (vtkInformationInformationVectorKey* key :
    { vtkAbstractArray::PER_COMPONENT(), vtkAbstractArray::PER_FINITE_COMPONENT() })
  {
    vtkNew<vtkInformationVector> ranges;
    ranges->SetNumberOfInformationObjects(nc);
    for (int c = 0; c < nc; ++c)
    {
      const double r[2] = { lo[c], hi[c] };
      ranges->GetInformationObject(c)->Set(vtkDataArray::COMPONENT_RANGE(), r, 2);
    }
    info->Set(key, ranges);
  }
  if (nc > 1)
  {
    const double r[2] = { std::sqrt(n2lo), std::sqrt(n2hi) };
    info->Set(vtkDataArray::L2_NORM_RANGE(), r, 2);
    info->Set(vtkDataArray::L2_NORM_FINITE_RANGE(), r, 2);
  }
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
  SeedRanges(a, pixels);
  return a;
}

/** The film and its point arrays; false where the engine's image has the wrong size. */
bool WriteImage(vtkImageData* output, const schlieren::TraceResult& result)
{
  const int nx = result.Film.Size[0], ny = result.Film.Size[1];
  double origin[2];
  result.Film.GetImageOrigin(origin);
  output->SetExtent(0, nx - 1, 0, ny - 1, 0, 0);
  output->SetSpacing(result.Film.PixelSize, result.Film.PixelSize, 1.0);
  output->SetOrigin(origin[0], origin[1], 0.0);
  const vtkIdType pixels = static_cast<vtkIdType>(nx) * ny;
  if (result.Intensity.size() != static_cast<std::size_t>(pixels) ||
    result.Deflection.size() != 2 * static_cast<std::size_t>(pixels))
  {
    return false;
  }
  vtkPointData* pd = output->GetPointData();
  pd->SetScalars(FloatArray("intensity", result.Intensity, 1, pixels));
  pd->AddArray(FloatArray("deflection", result.Deflection, 2, pixels, "x", "y"));
  // the optional images, where the engine made them
  const struct
  {
    const char* Name;
    const std::vector<float>& Values;
    int Components;
    const char *C0, *C1, *C2;
  } optional[] = { { "rgb", result.RGB, 3, "r", "g", "b" },
    { "phase", result.Phase, 1, nullptr, nullptr, nullptr },
    { "bos_displacement", result.Displacement, 2, "x", "y", nullptr },
    { "error_estimate", result.ErrorEstimate, 1, nullptr, nullptr, nullptr },
    { "blocked", result.Blocked, 1, nullptr, nullptr, nullptr } };
  for (const auto& o : optional)
  {
    if (!o.Values.empty())
    {
      pd->AddArray(FloatArray(o.Name, o.Values, o.Components, pixels, o.C0, o.C1, o.C2));
    }
  }
  return true;
}

/** The field data of the image: the engine's report (schlieren::ImageReport, which the C
 * interface returns too), one array per entry. */
void WriteFieldData(vtkFieldData* fd, const schlieren::SessionImage& image)
{
  for (const schlieren::ReportEntry& e : schlieren::ImageReport(image))
  {
    if (e.IsText)
    {
      vtkNew<vtkStringArray> a;
      a->SetName(e.Name.c_str());
      a->InsertNextValue(e.Text);
      fd->AddArray(a);
    }
    else
    {
      vtkNew<vtkDoubleArray> a;
      a->SetName(e.Name.c_str());
      for (double v : e.Numbers)
      {
        a->InsertNextValue(v);
      }
      fd->AddArray(a);
    }
  }
}
}

//------------------------------------------------------------------------------
struct vtkSchlierenImage::vtkInternals
{
  // the packed volume and this rank's film sums, kept between updates
  schlieren::TraceSession Session;
  // the Version of each time step of the input (its time and upstream pipeline MTime)
  std::map<std::pair<vtkMTimeType, double>, std::uint64_t> TimeVersions;
  // The last error reported. ParaView (the GUI's refinement too) asks again for the data of a
  // filter that failed: an error is reported once until an update succeeds, the error changes or
  // a setting does (a new update with changed settings is told again why it fails). The GUI's own
  // PassLimit is not a setting here: its refinement steps do not repeat an error.
  std::string LastError;
  std::string LastErrorKey;
  bool Fresh(const std::string& error, const std::string& key)
  {
    const bool fresh = error != this->LastError || key != this->LastErrorKey;
    this->LastError = error;
    this->LastErrorKey = key;
    return fresh;
  }
  // The warnings of the last update without their numbers: passes added to the same image
  // (the GUI's refinement, chunk by chunk) repeat a warning only when it changes in words.
  std::string LastWarnings;
  bool FreshWarnings(const std::string& warnings, bool addedPasses)
  {
    std::string words;
    for (char c : warnings)
    {
      if (!std::isdigit(static_cast<unsigned char>(c)))
      {
        words += c;
      }
    }
    const bool fresh = !addedPasses || words != this->LastWarnings;
    this->LastWarnings = words;
    return fresh;
  }
  // the last image written: what an update aborted within a pass leaves in the output
  vtkSmartPointer<vtkImageData> Shown;
  // the last image when it was traced with Cutoff BOS (WriteBOSPair), else null
  std::shared_ptr<schlieren::SessionImage> LastBOS;
  std::string BOSPairMessage;
  // the output is that previous image: the next update must trace, whatever changed
  bool Stale = false;
  vtkTimeStamp StaleTime;

  /** What an update that wrote `output` from `image` leaves: the image shown (what an abort
   * keeps), and a BOS image for WriteBOSPair. */
  void Keep(vtkImageData* output, schlieren::SessionImage&& image)
  {
    if (image.Traced.Mode == schlieren::Cutoff::BOS)
    {
      this->LastBOS = std::make_shared<schlieren::SessionImage>(std::move(image));
    }
    if (!this->Shown)
    {
      this->Shown = vtkSmartPointer<vtkImageData>::New();
    }
    this->Shown->ShallowCopy(output);
  }

  /** `error` as the filter's error, once (Fresh). */
  void SayError(vtkSchlierenImage* self, const std::string& error)
  {
    if (this->Fresh(error, ErrorKey(self)))
    {
      vtkErrorWithObjectMacro(self, << error);
    }
  }

  /** The engine's notes of an update: warnings (once, FreshWarnings) and the log's lines. */
  void SayNotes(vtkSchlierenImage* self, const schlieren::SessionImage& image)
  {
    const bool freshWarnings = this->FreshWarnings(image.Warnings, image.PassesTraced < image.Passes);
    for (const schlieren::SessionImage::Note& note : image.Notes)
    {
      if (note.Warning)
      {
        if (freshWarnings)
        {
          vtkWarningWithObjectMacro(self, << note.Text);
        }
      }
      else
      {
        vtkLog(INFO, << "SchlierenImage: " << note.Text);
      }
    }
  }

  /** An update that failed with `error` (`percent` of the trace done): where the pipeline aborted
   * it and an earlier image exists, that image stays (1); else the error, said once (0). */
  int Failed(vtkSchlierenImage* self, vtkImageData* output, std::string error, int percent)
  {
    const bool aborted = self->GetAbortExecute();
    if (aborted)
    {
      self->SetAbortExecute(0); // the abort is spent: the next update traces
    }
    if (aborted && this->Shown)
    {
      // aborted, within a pass or between passes: the previous image stays (the kept passes are
      // dropped with the unfinished one, so the next update traces afresh)
      output->ShallowCopy(this->Shown);
      this->Stale = true;
      vtkWarningWithObjectMacro(self, << "aborted at " << percent
                                      << " % of the trace: the image shown is the previous one; "
                                         "the next update traces all its passes again");
      return 1;
    }
    if (aborted)
    {
      error = "aborted at " + std::to_string(percent) + " % of the trace: no image yet";
    }
    this->SayError(self, error);
    return 0;
  }
};

namespace
{
/** The output's whole extent, spacing and origin: the film the settings give on `volume` (the
 * input's grid), as schlieren::PlannedFilm expects it. */
void SetFilmInformation(vtkInformation* outInfo, const schlieren::Volume& volume,
  const schlieren::TraceSettings& s, const schlieren::TraceSession& session)
{
  schlieren::SetFilmInformation(outInfo, schlieren::PlannedFilm(volume, s, session));
}
}

//------------------------------------------------------------------------------
vtkMTimeType vtkSchlierenImage::GetMTime()
{
  if (this->Internals && this->Internals->Stale)
  {
    this->Internals->StaleTime.Modified();
    return this->Internals->StaleTime.GetMTime();
  }
  return this->Superclass::GetMTime();
}

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
  this->SetDeviceName(nullptr);
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

//------------------------------------------------------------------------------
namespace
{
std::string EnumerationProblem(vtkSchlierenImage* f)
{
  // The enumerations' and booleans' entries, those of their domains in Schlieren.xml: another
  // value is an error, not a clamp to another choice (empty where all are entries).
  for (const std::string& problem :
    { SchlierenEnumProblem("Integrator", f->GetIntegrator(),
        { { 0, "Euler" }, { 1, "Midpoint" }, { 2, "RK4" }, { 3, "Straight" }, { 4, "Auto" },
          { 5, "Verlet" } }),
      SchlierenEnumProblem("Reconstruction", f->GetReconstruction(),
        { { 0, "Trilinear" }, { 1, "Cubic" }, { 2, "Auto" } }),
      SchlierenEnumProblem("Cutoff", f->GetCutoff(),
        { { 0, "KnifeEdge" }, { 1, "Shadowgraph" }, { 2, "Circular" },
          { 3, "ComplementCircular" }, { 4, "ColorFilter" }, { 5, "Interferometry" },
          { 6, "BOS" } }),
      SchlierenEnumProblem("Source", f->GetSource(),
        { { 0, "Point" }, { 1, "Slit" }, { 2, "Rectangle" }, { 3, "Disc" }, { 4, "Gaussian" } }),
      SchlierenEnumProblem("Camera", f->GetCamera(), { { 0, "None" }, { 1, "Ideal" }, { 2, "Lens" } }),
      SchlierenEnumProblem("Framing", f->GetFraming(), { { 0, "Volume" }, { 1, "Silhouette" } }),
      SchlierenEnumProblem(
        "BackgroundPattern", f->GetBackgroundPattern(), { { 0, "Dots" }, { 1, "Stripes" } }),
      SchlierenEnumProblem(
        "JitterPattern", f->GetJitterPattern(), { { 0, "Random" }, { 1, "Lattice" } }),
      SchlierenEnumProblem(
        "Filter", f->GetFilter(), { { 0, "None" }, { 1, "Gaussian" }, { 2, "Cone" } }),
      SchlierenEnumProblem(
        "Backend", f->GetBackend(), { { 0, "Auto" }, { 1, "OpenCL" }, { 2, "CPU" } }),
      SchlierenBoolProblem("UseOctree", f->GetUseOctree()),
      SchlierenBoolProblem("KeepInvariant", f->GetKeepInvariant()),
      SchlierenBoolProblem("EstimateError", f->GetEstimateError()),
      SchlierenBoolProblem("Jitter", f->GetJitter()),
      SchlierenBoolProblem("RussianRoulette", f->GetRussianRoulette()),
      SchlierenBoolProblem("TraceInPieces", f->GetTraceInPieces()) })
  {
    if (!problem.empty())
      return problem;
  }
  // The XML domain's range (the engine takes any finite angle): outside it, an error, not a wrap;
  // found here so that RequestData refuses it too (issue 48: it traced at that angle).
  if (!(f->GetKnifeAngle() >= -180 && f->GetKnifeAngle() <= 180))
  {
    std::ostringstream msg;
    msg << "KnifeAngle is " << f->GetKnifeAngle() << ": it must be in [-180, 180] degrees.";
    return msg.str();
  }
  return std::string();
}
} // namespace

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
  // The errors found here are RequestData's to report (it finds them again): ParaView asks for
  // the information more often than for the data, and each error is said once.
  if (!EnumerationProblem(this).empty())
  {
    const std::string problem = EnumerationProblem(this);
    if (this->Internals->Fresh(problem, ErrorKey(this)))
    {
      vtkErrorMacro(<< problem);
    }
    return 0;
  }
  if (!vtkImageData::SafeDownCast(input))
  {
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
    const std::string empty = "The input volume is empty: nothing to trace. If a filter upstream "
                              "reported an error, that is the cause; fix it there.";
    if (this->Internals->Fresh(empty, ErrorKey(this)))
    {
      vtkErrorMacro(<< empty);
    }
    return 0;
  }
  try
  {
    SetFilmInformation(outInfo, WholeVolume(inInfo), SettingsOf(this), this->Internals->Session);
  }
  catch (const schlieren::Error&)
  {
    return 0; // RequestData reports it
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
  const int ranks = schlieren::ControllerParallel().Size();
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
namespace
{
/** The pipeline's progress of a trace, its text the engine's TraceClock. Returns false once the
 * pipeline asks to abort. */
struct TraceProgress
{
  explicit TraceProgress(vtkSchlierenImage* self)
    : Self(self)
    , Clock(self->GetPasses())
  {
  }
  bool operator()(double progress)
  {
    const std::string text = this->Clock.Text(progress);
    if (!text.empty())
    {
      this->Text = text;
      this->Self->SetProgressText(this->Text.c_str());
    }
    this->Self->UpdateProgress(progress);
    return !this->Self->GetAbortExecute();
  }
  /** The text cleared; the share of the trace done, in percent. */
  int Done()
  {
    if (!this->Text.empty())
      this->Self->SetProgressText(nullptr);
    return this->Clock.Percent();
  }
  vtkSchlierenImage* Self;
  schlieren::TraceClock Clock;
  std::string Text;
};
} // namespace

int vtkSchlierenImage::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outputVector->GetInformationObject(0));
  vtkImageData* input = vtkImageData::GetData(inInfo);
  // found again, said once (RequestInformation said it): the same on every rank
  const std::string badChoice = EnumerationProblem(this);
  if (!badChoice.empty())
  {
    this->Internals->SayError(this, badChoice);
    output->Initialize();
    return 0;
  }
  schlieren::ControllerParallel parallel("SchlierenImage");
  schlieren::SessionImage image;
  std::string error;
  this->Internals->Stale = false;
  TraceProgress progress(this);
  try
  {
    schlieren::VolumePiece piece = PieceOf(input, output, inInfo, this->UseOctree);
    TimeVersion(this, input, inInfo, piece, this->Internals->TimeVersions);
    this->Internals->LastBOS.reset();
    this->Internals->Session.Update(parallel, piece, SettingsOf(this), image, std::ref(progress));
    // a frame found by this update (Framing Silhouette) may give the film another shape than
    // RequestInformation could know: the output's information follows the image
    if (this->Framing == SILHOUETTE_FRAME)
    {
      SetFilmInformation(outputVector->GetInformationObject(0), WholeVolume(inInfo),
        SettingsOf(this), this->Internals->Session);
    }
  }
  catch (const schlieren::Error& e)
  {
    error = e.what();
  }
  const int percent = progress.Done();
  this->Internals->SayNotes(this, image);
  if (!error.empty())
  {
    return this->Internals->Failed(this, output, error, percent);
  }
  this->Internals->Fresh(std::string(), std::string());
  output->Initialize();
  if (!image.HasImage)
  {
    return 1; // rank 0 holds the image
  }
  if (!WriteImage(output, image.Result))
  {
    vtkErrorMacro("The engine returned an image of the wrong size.");
    output->Initialize();
    return 0;
  }
  WriteFieldData(output->GetFieldData(), image);
  this->Internals->Keep(output, std::move(image));
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkSchlierenImage::WriteBOSPair(const char* folder, int bits, const char* format, const char* prefix)
{
  std::string& message = this->Internals->BOSPairMessage;
  try
  {
    if (!this->Internals->LastBOS)
    {
      const schlieren::Cutoff mode = SettingsOf(this).Mode;
      if (mode != schlieren::Cutoff::BOS)
      {
        throw schlieren::Error(std::string("Writing the BOS pair: this SchlierenImage's Cutoff is ") +
          schlieren::CutoffName(mode) + ", not BOS: set Cutoff to BOS (and BackgroundDistance) and update it.");
      }
      throw schlieren::Error("Writing the BOS pair: this SchlierenImage holds no BOS image: update "
                             "it first (on the process that holds the image).");
    }
    schlieren::BOSPairRequest request;
    request.Folder = folder ? folder : "";
    request.Bits = bits;
    request.Format = format ? format : "png";
    request.Prefix = prefix ? prefix : "bos";
    const schlieren::BOSPairFiles files = schlieren::WriteBOSPair(*this->Internals->LastBOS, request);
    message = "wrote " + files.Background + ", " + files.Recording + " and " + files.SideFile;
    return 1;
  }
  catch (const std::exception& e)
  {
    message = e.what();
  }
  vtkErrorMacro(<< message);
  return 0;
}

//------------------------------------------------------------------------------
const char* vtkSchlierenImage::GetBOSPairMessage()
{
  return this->Internals->BOSPairMessage.c_str();
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
  os << indent << "Framing: " << this->Framing << "\n";
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
  os << indent << "Source: " << this->Source << ", SourceSize: " << this->SourceSize[0] << " x "
     << this->SourceSize[1] << " mm, f1: " << this->CollimatorFocalLength
     << " m, f2: " << this->SchlierenFocalLength << " m, KnifeCut: " << this->KnifeCut
     << ", BitDepth: " << this->BitDepth << ", SaturationWarning: " << this->SaturationWarning << "\n";
  os << indent << "CutoffScale: " << this->CutoffScale << (this->CutoffScale == 0 ? " (automatic)" : "")
     << "\n";
  os << indent << "Camera: " << this->Camera << ", CameraFocalLength: " << this->CameraFocalLength
     << " m, FNumber: " << this->FNumber << ", CameraDistance: " << this->CameraDistance
     << " m, FocusPlane: " << this->FocusPlane << ", SourceGridDistance: " << this->SourceGridDistance
     << " m\n";
  os << indent << "FilmDistance: " << this->FilmDistance << "\n";
  os << indent << "Wavelength: " << this->Wavelength << " nm\n";
  os << indent << "ReferenceTilt: " << this->ReferenceTilt << " fringes per world unit\n";
  os << indent << "WavelengthRange: " << this->WavelengthRange[0] << " " << this->WavelengthRange[1]
     << " nm, WavelengthBins: " << this->WavelengthBins << ", Dispersion: " << this->Dispersion << "\n";
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
  os << indent << "JitterPattern: " << (this->JitterPattern == LATTICE ? "Lattice" : "Random") << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Backend: "
     << (this->Backend == OPENCL ? "OpenCL" : (this->Backend == CPU ? "CPU" : "Auto")) << "\n";
  os << indent << "DeviceName: "
     << (this->DeviceName && *this->DeviceName ? this->DeviceName : "(default)") << "\n";
  os << indent << "Threads: " << this->Threads << (this->Threads > 0 ? "" : " (default)") << "\n";
  os << indent << "TraceInPieces: " << (this->TraceInPieces ? "on" : "off") << "\n";
}

//------------------------------------------------------------------------------
vtkExecutive* vtkSchlierenImage::CreateDefaultExecutive()
{
  return schlieren::NewAgreeingExecutive();
}

vtkTypeBool vtkSchlierenImage::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return SchlierenGuarded(this,
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); });
}
