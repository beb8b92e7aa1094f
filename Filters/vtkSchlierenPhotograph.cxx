// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSchlierenPhotograph.h"
#include "SchlierenGuard.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageReader2Factory.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtksys/SystemTools.hxx"

#include "vtk_nlohmannjson.h"
#include VTK_NLOHMANN_JSON(json.hpp)

#include "SchlierenController.h"
#include "SchlierenEngine.h"
#include "SchlierenPhotograph.h"
#include "SchlierenPhotographOverlay.h"
#include "SchlierenValues.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSchlierenPhotograph);

class vtkSchlierenPhotograph::vtkInternals
{
public:
  std::string Key; ///< what the result was registered from ("" none)
  schlieren::PhotographResult Result;
};

vtkSchlierenPhotograph::vtkSchlierenPhotograph()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

vtkSchlierenPhotograph::~vtkSchlierenPhotograph()
{
  delete this->Internals;
}

namespace
{
const char* const RefineNames[] = { "Similarity", "Rigid", "Shift", "None" };
// Overlay's entries' arrays (the Python package's PHOTOGRAPH_OVERLAYS)
const char* const OverlayArrays[] = { "blend", "checkerboard", "difference", "photograph_calibrated",
  "intensity" };

std::string Number(double v)
{
  char text[40];
  std::snprintf(text, sizeof(text), "%.17g", v);
  return text;
}

/** The engine's settings text ("Name=value" lines) of the filter's properties; throws
 * schlieren::Error for an enumeration out of range (the engine checks the values). */
std::string SettingsText(vtkSchlierenPhotograph* f)
{
  if (f->GetRefine() < 0 || f->GetRefine() > 3)
    throw schlieren::Error("Refine is " + std::to_string(f->GetRefine()) +
      ": it must be 0 (Similarity), 1 (Rigid), 2 (Shift) or 3 (None).");
  std::string pairs = f->GetPointPairs() ? f->GetPointPairs() : "";
  const std::size_t first = pairs.find_first_not_of(" \t\r\n");
  pairs = first == std::string::npos ? std::string()
                                     : pairs.substr(first, pairs.find_last_not_of(" \t\r\n") - first + 1);
  std::string s = "PhotoPixelSize=" + Number(f->GetPhotoPixelSize()) + "\n";
  if (!pairs.empty())
    s += "PointPairs=" + pairs + "\n";
  s += std::string("Refine=") + RefineNames[f->GetRefine()] + "\n";
  s += "ScaleRange=" + Number(f->GetScaleRange()[0]) + " " + Number(f->GetScaleRange()[1]) + "\n";
  s += "MaxRotation=" + Number(f->GetMaxRotation()) + "\n";
  s += "MaxShift=" + Number(f->GetMaxShift()) + "\n";
  s += "LineThreshold=" + Number(f->GetLineThreshold()) + "\n";
  s += "MinLineLength=" + std::to_string(f->GetMinLineLength()) + "\n";
  s += "MaxLineDistance=" + Number(f->GetMaxLineDistance()) + "\n";
  s += "CheckerSize=" + std::to_string(f->GetCheckerSize()) + "\n";
  return s;
}

/** Grey values of an image's scalars (`what` names it in errors): `size` its first layer's. */
std::vector<float> GreyOf(vtkImageData* image, const std::string& what, int size[2])
{
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  int dims[3] = { 0, 0, 0 };
  if (image)
    image->GetDimensions(dims);
  if (!scalars || dims[0] * dims[1] == 0)
    throw schlieren::Error(what + " holds no image.");
  size[0] = dims[0];
  size[1] = dims[1];
  const std::vector<double> values = schlieren::values::Values<double>(scalars);
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1];
  std::vector<float> grey(n);
  schlieren::PhotographGrey(values.data(), n, scalars->GetNumberOfComponents(), grey.data());
  return grey;
}

/** The photograph file read with VTK's readers, as grey. */
std::vector<float> ReadPhotograph(const std::string& name, int size[2])
{
  if (!vtksys::SystemTools::FileExists(name, true))
    throw schlieren::Error("The photograph '" + name + "' was not found.");
  vtkSmartPointer<vtkImageReader2> reader;
  reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(name.c_str()));
  if (!reader)
    throw schlieren::Error(
      "The photograph '" + name + "' is not an image VTK reads (PNG, JPEG, TIFF, BMP, PNM).");
  reader->SetFileName(name.c_str());
  reader->Update();
  return GreyOf(reader->GetOutput(), "The photograph '" + name + "'", size);
}

vtkSmartPointer<vtkFloatArray> FloatArray(const char* name, const float* values, vtkIdType n)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(name);
  a->SetNumberOfTuples(n);
  std::copy(values, values + n, a->GetPointer(0));
  return a;
}

void AddNumbers(vtkFieldData* fd, const char* name, std::initializer_list<double> values)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  for (double v : values)
    a->InsertNextValue(v);
  fd->AddArray(a);
}

void AddString(vtkFieldData* fd, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

/** A report's number (null: NaN), as Python's json reads the engine's text. */
double NumberOf(const nlohmann::json& v)
{
  return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
}

/** The report's field data on the film's output (the numbers as the engine's JSON gives them, so
 * that the Python front end, which reads only that, has the same bits). */
void WriteReport(vtkImageData* output, const std::string& text, const nlohmann::json& r)
{
  vtkFieldData* fd = output->GetFieldData();
  AddString(fd, "photograph_report", text);
  for (const char* k : { "score", "threshold", "scale", "rotation", "photo_pixel_size",
         "edge_uncertainty", "gamma", "gamma_error", "background", "vignetting" })
  {
    if (r.contains(k) && !r[k].is_null())
      AddNumbers(fd, (std::string("photograph_") + k).c_str(), { r[k].get<double>() });
  }
  AddNumbers(fd, "photograph_shift", { NumberOf(r["shift"][0]), NumberOf(r["shift"][1]) });
  if (!r["grey_reason"].get<std::string>().empty())
    AddString(fd, "photograph_grey_reason", r["grey_reason"].get<std::string>());
  if (r.contains("warnings") && !r["warnings"].get<std::string>().empty())
    AddString(fd, "warnings", r["warnings"].get<std::string>());
}

/** The report's lines as polylines at height z (the Python package's _photograph_lines). */
void WriteLines(vtkPolyData* output, const nlohmann::json& lines, double z)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkIntArray> image, match;
  vtkNew<vtkFloatArray> distance, offset, matched;
  offset->SetNumberOfComponents(2);
  image->SetName("image");
  distance->SetName("line_distance");
  offset->SetName("line_offset");
  matched->SetName("line_matched");
  match->SetName("line_match");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& line : lines)
  {
    const auto& xy = line["points"];
    cells->InsertNextCell(static_cast<int>(xy.size() / 2));
    for (std::size_t a = 0; a + 1 < xy.size(); a += 2)
      cells->InsertCellPoint(points->InsertNextPoint(NumberOf(xy[a]), NumberOf(xy[a + 1]), z));
    image->InsertNextValue(line["image"].get<std::string>() == "film" ? 0 : 1);
    const double d = NumberOf(line["distance"]);
    distance->InsertNextValue(static_cast<float>(std::isnan(d) || d < 0 ? nan : d));
    offset->InsertNextTuple2(NumberOf(line["offset"][0]), NumberOf(line["offset"][1]));
    matched->InsertNextValue(static_cast<float>(NumberOf(line["matched"])));
    match->InsertNextValue(line["match"].get<int>());
  }
  output->SetPoints(points);
  output->SetLines(cells);
  for (vtkDataArray* a : std::initializer_list<vtkDataArray*>{ image, distance, offset, matched, match })
    output->GetCellData()->AddArray(a);
  output->GetCellData()->SetActiveScalars("line_distance"); // the lines coloured by it
}
} // namespace

int vtkSchlierenPhotograph::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  if (port == 1)
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkSchlierenPhotograph::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 1 ? "vtkPolyData" : "vtkImageData");
  return 1;
}

int vtkSchlierenPhotograph::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // the film's grid (the executive copied the input's extent, spacing and origin)
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(),
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

int vtkSchlierenPhotograph::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // the whole film and the whole photograph
  for (int port = 0; port < 2; ++port)
  {
    for (int c = 0; c < inputVector[port]->GetNumberOfInformationObjects(); ++c)
    {
      vtkInformation* in = inputVector[port]->GetInformationObject(c);
      if (in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
        in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
          in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
    }
  }
  return 1;
}

int vtkSchlierenPhotograph::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* film = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkPolyData* lines = vtkPolyData::GetData(outputVector, 1);
  output->Initialize();
  lines->Initialize();
  // under MPI the film is rank 0's (SchlierenImage's other ranks hold nothing)
  if ((!film || film->GetNumberOfPoints() == 0) && schlieren::ControllerParallel().Size() > 1)
    return 1;
  vtkDataArray* intensity = film ? film->GetPointData()->GetArray("intensity") : nullptr;
  if (!intensity || intensity->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("SchlierenPhotograph needs the output of SchlierenImage (a 2D image with the "
                  "point array 'intensity') on its first input.");
    return 0;
  }
  int dims[3];
  double spacing[3], origin[3];
  film->GetDimensions(dims);
  film->GetSpacing(spacing);
  film->GetOrigin(origin);
  if (dims[2] != 1)
  {
    vtkErrorMacro("SchlierenPhotograph needs a 2D film (one layer); got "
      << dims[0] << " x " << dims[1] << " x " << dims[2] << ".");
    return 0;
  }
  if (std::abs(spacing[0] - spacing[1]) > 1e-6 * std::max(std::abs(spacing[0]), std::abs(spacing[1])))
  {
    vtkErrorMacro("SchlierenPhotograph needs square film pixels; got " << spacing[0] << " x "
                                                                        << spacing[1] << ".");
    return 0;
  }
  const int* ext = film->GetExtent();
  for (int a = 0; a < 3; ++a)
    origin[a] += ext[2 * a] * spacing[a];
  const int filmSize[2] = { dims[0], dims[1] };
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1];
  const std::vector<float> filmValues = schlieren::values::Values<float>(intensity);
  std::vector<float> blend(static_cast<std::size_t>(n));
  vtkInternals& cache = *this->Internals;
  try
  {
    if (this->Overlay < BLEND || this->Overlay > IMAGE)
      throw schlieren::Error("Overlay is " + std::to_string(this->Overlay) +
        ": it must be 0 (Blend), 1 (Checkerboard), 2 (Difference), 3 (Photograph) or 4 (Image).");
    schlieren::PhotographBlend(this->BlendWeight, nullptr, nullptr, 0, nullptr); // its range
    const std::string settingsText = SettingsText(this);
    vtkImageData* photoInput =
      this->GetNumberOfInputConnections(1) ? vtkImageData::GetData(inputVector[1]) : nullptr;
    // the film, the photograph (its input, or its file as it is on disk) and the settings
    std::string key = settingsText + "film " + std::to_string(reinterpret_cast<std::uintptr_t>(film)) +
      " " + std::to_string(film->GetMTime()) + "\n";
    if (photoInput)
      key += "input " + std::to_string(reinterpret_cast<std::uintptr_t>(photoInput)) + " " +
        std::to_string(photoInput->GetMTime());
    else if (!this->FileName.empty() && vtksys::SystemTools::FileExists(this->FileName, true))
      key += "file " + this->FileName + " " +
        std::to_string(vtksys::SystemTools::ModifiedTime(this->FileName)) + " " +
        std::to_string(vtksys::SystemTools::FileLength(this->FileName));
    if (key != cache.Key)
    {
      cache.Key.clear();
      int photoSize[2] = { 0, 0 };
      std::vector<float> photo;
      if (photoInput)
      {
        if (!photoInput->GetPointData()->GetScalars())
          throw schlieren::Error("SchlierenPhotograph's photograph input has no scalars.");
        photo = GreyOf(photoInput, "The photograph input", photoSize);
      }
      else if (!this->FileName.empty())
        photo = ReadPhotograph(this->FileName, photoSize);
      else
        throw schlieren::Error("SchlierenPhotograph needs a photograph: set FileName (a PNG, JPEG "
                               "or TIFF file) or connect an image to its second input.");
      const schlieren::PhotographSettings settings = schlieren::ParsePhotographSettings(settingsText);
      cache.Result = schlieren::RegisterPhotograph(
        filmSize, origin, spacing[0], filmValues.data(), photoSize, photo.data(), settings);
      cache.Key = key;
    }
    if (!cache.Result.Match)
      throw schlieren::Error("The photograph was not registered: " + cache.Result.Reason);
    schlieren::PhotographBlend(
      this->BlendWeight, filmValues.data(), cache.Result.Difference.data(), blend.size(), blend.data());
  }
  catch (const schlieren::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  const schlieren::PhotographResult& r = cache.Result;
  const std::string text = r.Json();
  output->SetExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, 0);
  output->SetSpacing(spacing[0], spacing[1], 1.0);
  output->SetOrigin(origin);
  vtkSmartPointer<vtkDataArray> film0;
  film0.TakeReference(intensity->NewInstance());
  film0->DeepCopy(intensity);
  film0->SetName("intensity");
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(film0);
  pd->AddArray(FloatArray("photograph", r.Registered.data(), n));
  pd->AddArray(FloatArray("photograph_calibrated", r.Calibrated.data(), n));
  pd->AddArray(FloatArray("difference", r.Difference.data(), n));
  pd->AddArray(FloatArray("checkerboard", r.Checkerboard.data(), n));
  pd->AddArray(FloatArray("line_distance", r.LineDistance.data(), n));
  pd->AddArray(FloatArray("blend", blend.data(), n));
  pd->SetActiveScalars(OverlayArrays[this->Overlay]);
  const nlohmann::json report = nlohmann::json::parse(text);
  WriteReport(output, text, report);
  if (!r.Warnings.empty())
    vtkWarningMacro(<< r.Warnings);
  WriteLines(lines, report["lines"], origin[2]);
  return 1;
}

void vtkSchlierenPhotograph::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "PhotoPixelSize: " << this->PhotoPixelSize << "\n";
  os << indent << "PointPairs: " << this->PointPairs << "\n";
  os << indent << "Refine: " << this->Refine << "\n";
  os << indent << "ScaleRange: " << this->ScaleRange[0] << ", " << this->ScaleRange[1] << "\n";
  os << indent << "MaxRotation: " << this->MaxRotation << "\n";
  os << indent << "MaxShift: " << this->MaxShift << "\n";
  os << indent << "LineThreshold: " << this->LineThreshold << "\n";
  os << indent << "MinLineLength: " << this->MinLineLength << "\n";
  os << indent << "MaxLineDistance: " << this->MaxLineDistance << "\n";
  os << indent << "Overlay: " << this->Overlay << "\n";
  os << indent << "BlendWeight: " << this->BlendWeight << "\n";
  os << indent << "CheckerSize: " << this->CheckerSize << "\n";
}

vtkTypeBool vtkSchlierenPhotograph::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return SchlierenGuarded(this,
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); });
}
