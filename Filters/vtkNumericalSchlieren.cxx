// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNumericalSchlieren.h"
#include "SchlierenGuard.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "SchlierenArrays.h"
#include "SchlierenController.h"
#include "SchlierenFilmInformation.h"
#include "SchlierenNumerical.h"
#include "SchlierenValues.h"

#include <algorithm>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkNumericalSchlieren);

vtkNumericalSchlieren::vtkNumericalSchlieren()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

vtkNumericalSchlieren::~vtkNumericalSchlieren() = default;

namespace
{
/** The engine's settings of the filter's properties; throws schlieren::Error naming a bad one. */
schlieren::NumericalSettings SettingsOf(vtkNumericalSchlieren* f)
{
  schlieren::NumericalSettings s;
  for (int a = 0; a < 3; ++a)
  {
    s.ViewDirection[a] = f->GetViewDirection()[a];
    s.ViewUp[a] = f->GetViewUp()[a];
  }
  s.Resolution[0] = f->GetResolution()[0];
  s.Resolution[1] = f->GetResolution()[1];
  if (f->GetMode() != 0 && f->GetMode() != 1)
    throw schlieren::Error(
      "Mode is " + std::to_string(f->GetMode()) + ": it must be 0 (Slice) or 1 (LineOfSight).");
  if (f->GetGradient() != 0 && f->GetGradient() != 1)
    throw schlieren::Error("Gradient is " + std::to_string(f->GetGradient()) +
      ": it must be 0 (Magnitude) or 1 (KnifeComponent).");
  s.Mode = static_cast<schlieren::NumericalMode>(f->GetMode());
  s.Quantity = static_cast<schlieren::NumericalQuantity>(f->GetGradient());
  s.KnifeAngle = f->GetKnifeAngle();
  s.SliceOffset = f->GetSliceOffset();
  s.StepSize = f->GetStepSize();
  s.C0 = f->GetC0();
  s.C1 = f->GetC1();
  s.K = f->GetK();
  s.Maximum = f->GetGradientMaximum();
  schlieren::CheckNumericalSettings(s);
  return s;
}

/** The grid (without values) the input's whole extent describes. */
schlieren::ScalarGrid WholeGrid(vtkInformation* inInfo)
{
  schlieren::ScalarGrid g;
  int whole[6] = { 0, -1, 0, -1, 0, -1 };
  double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  if (inInfo->Has(vtkDataObject::ORIGIN()))
    inInfo->Get(vtkDataObject::ORIGIN(), origin);
  if (inInfo->Has(vtkDataObject::SPACING()))
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  for (int a = 0; a < 3; ++a)
  {
    g.Dimensions[a] = std::max(whole[2 * a + 1] - whole[2 * a] + 1, 0);
    g.Origin[a] = origin[a] + whole[2 * a] * spacing[a];
    g.Spacing[a] = spacing[a];
  }
  return g;
}

vtkDataArray* Scalars(vtkImageData* input, const std::string& name)
{
  vtkDataArray* a = input->GetPointData()->GetArray(name.c_str());
  return a && a->GetNumberOfComponents() == 1 && a->GetNumberOfTuples() == input->GetNumberOfPoints()
    ? a
    : nullptr;
}

/**
 * The density of a piece that is not empty: the array named (`named`), else the first
 * density-like array, else n - 1; `name` and `values` set. Returns the error where there is none.
 */
std::string DensityOf(
  vtkImageData* input, const std::string& named, std::string& name, vtkDataArray*& values)
{
  name = named;
  if (!name.empty())
  {
    values = Scalars(input, name);
    return values ? std::string()
                  : "DensityArray is '" + name +
        "': the input has no one-component point array of that name.";
  }
  for (const char* candidate : { "density", "rho", "Density", schlieren::arrays::NMinus1 })
  {
    if ((values = Scalars(input, candidate)))
    {
      name = candidate;
      return std::string();
    }
  }
  return "NumericalSchlieren needs a density (point array 'density', 'rho' or 'Density', or one "
         "named in DensityArray) or 'n_minus_1'; the input has none.";
}

/** This rank's piece as the engine's grid: its values, solid and excluded points as copies the
 * grid points to (empty where the piece is: `input` null). */
struct PieceOfGrid
{
  PieceOfGrid(vtkImageData* input, vtkDataArray* values)
  {
    if (!input)
      return;
    this->Field = schlieren::values::Values<float>(values);
    if (vtkDataArray* so = Scalars(input, schlieren::arrays::Solid))
      this->Solid = schlieren::values::Values<unsigned char>(so);
    if (vtkDataArray* m = Scalars(input, "vtkValidPointMask"))
    {
      this->Excluded = schlieren::values::Values<unsigned char>(m);
      for (unsigned char& e : this->Excluded)
        e = e ? 0 : 1;
    }
    input->GetDimensions(this->Grid.Dimensions);
    input->GetOrigin(this->Grid.Origin);
    input->GetSpacing(this->Grid.Spacing);
    const int* ext = input->GetExtent();
    for (int a = 0; a < 3; ++a)
      this->Grid.Origin[a] += ext[2 * a] * this->Grid.Spacing[a];
    this->Grid.Values = this->Field.data();
    this->Grid.Solid = this->Solid.empty() ? nullptr : this->Solid.data();
    this->Grid.Excluded = this->Excluded.empty() ? nullptr : this->Excluded.data();
  }
  std::vector<float> Field;
  std::vector<unsigned char> Solid, Excluded;
  schlieren::ScalarGrid Grid;
};

/**
 * Under MPI: the whole volume's grid (no values), on the same origin and spacing as this rank's
 * piece (`input`; null where it is empty: the pipeline's), so that rank 0 computes the sample
 * points as one process does; `offset` is the piece's first point in it.
 */
schlieren::ScalarGrid WholeGridOfPieces(vtkInformation* inInfo, vtkImageData* input, int offset[3])
{
  int wholeExt[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExt);
  // an empty piece: the pipeline's origin and spacing of the whole volume
  const schlieren::ScalarGrid info = WholeGrid(inInfo);
  double o[3], h[3];
  for (int a = 0; a < 3; ++a)
  {
    o[a] = info.Origin[a] - wholeExt[2 * a] * info.Spacing[a];
    h[a] = info.Spacing[a];
  }
  if (input)
  {
    input->GetOrigin(o);
    input->GetSpacing(h);
    const int* ext = input->GetExtent();
    for (int a = 0; a < 3; ++a)
      offset[a] = ext[2 * a] - wholeExt[2 * a];
  }
  schlieren::ScalarGrid whole;
  for (int a = 0; a < 3; ++a)
  {
    whole.Dimensions[a] = wholeExt[2 * a + 1] - wholeExt[2 * a] + 1;
    whole.Origin[a] = o[a] + wholeExt[2 * a] * h[a];
    whole.Spacing[a] = h[a];
  }
  return whole;
}

/** The image's film and arrays into `output`. */
void WriteImage(vtkImageData* output, const schlieren::NumericalImage& image)
{
  const int nx = image.Film.Size[0], ny = image.Film.Size[1];
  double origin[2];
  image.Film.GetImageOrigin(origin);
  output->SetExtent(0, nx - 1, 0, ny - 1, 0, 0);
  output->SetSpacing(image.Film.PixelSize, image.Film.PixelSize, 1.0);
  output->SetOrigin(origin[0], origin[1], 0.0);
  const vtkIdType n = static_cast<vtkIdType>(nx) * ny;
  vtkNew<vtkFloatArray> intensity, gradient;
  vtkNew<vtkUnsignedCharArray> blocked;
  intensity->SetName("intensity");
  gradient->SetName("numerical_gradient");
  blocked->SetName("blocked");
  intensity->SetNumberOfTuples(n);
  gradient->SetNumberOfTuples(n);
  blocked->SetNumberOfTuples(n);
  std::copy(image.Intensity.begin(), image.Intensity.end(), intensity->GetPointer(0));
  std::copy(image.Gradient.begin(), image.Gradient.end(), gradient->GetPointer(0));
  std::copy(image.Blocked.begin(), image.Blocked.end(), blocked->GetPointer(0));
  output->GetPointData()->SetScalars(intensity);
  output->GetPointData()->AddArray(gradient);
  output->GetPointData()->AddArray(blocked);
}

void AddNumber(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

void AddString(vtkFieldData* fd, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
} // namespace

int vtkNumericalSchlieren::FillInputPortInformation(int port, vtkInformation* info)
{
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkNumericalSchlieren::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int empty[6] = { 0, -1, 0, -1, 0, -1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
  const schlieren::ScalarGrid grid = WholeGrid(inInfo);
  if (grid.Dimensions[0] < 1 || grid.Dimensions[1] < 1 || grid.Dimensions[2] < 1)
  {
    vtkErrorMacro(<< "The input volume is empty: nothing to image. If a filter upstream reported "
                     "an error, that is the cause; fix it there.");
    return 0;
  }
  try
  {
    schlieren::SetFilmInformation(outInfo, schlieren::NumericalFilm(grid, SettingsOf(this)));
  }
  catch (const schlieren::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  // Every rank executes (the pieces are gathered under MPI); rank 0 produces the image.
  outInfo->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

int vtkNumericalSchlieren::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The film's extent is no extent of the input: ask for the whole volume; under MPI each rank
  // for its piece of it (the upstream splits the whole extent), gathered in RequestData.
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int whole[6];
  inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  inInfo->Set(SDDP::UPDATE_EXTENT(), whole, 6);
  int piece = 0, pieces = 1;
  if (schlieren::ControllerParallel().Size() > 1)
  {
    piece = outInfo->Has(SDDP::UPDATE_PIECE_NUMBER()) ? outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()) : 0;
    pieces = outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES())
      ? std::max(outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()), 1)
      : 1;
  }
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), piece);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), pieces);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  return 1;
}

int vtkNumericalSchlieren::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  output->Initialize();
  schlieren::ControllerParallel parallel("NumericalSchlieren");
  // Under MPI a rank's piece may be empty (more ranks than the upstream splits the volume into);
  // it sends nothing. Every rank's failure is agreed on before the pieces are gathered.
  const bool empty = !input || input->GetNumberOfPoints() == 0;
  std::string name;
  vtkDataArray* values = nullptr;
  const std::string error = empty
    ? (parallel.Size() > 1 ? std::string()
                           : "NumericalSchlieren needs a non-empty image (vtkImageData), for "
                             "example the output of RefractiveIndex or RefractiveScene.")
    : DensityOf(input, this->DensityArray, name, values);
  schlieren::NumericalImage image;
  try
  {
    name = schlieren::AgreedFieldName(parallel, error, empty ? std::string() : name);
    PieceOfGrid piece(empty ? nullptr : input, values);
    int offset[3] = { 0, 0, 0 };
    const schlieren::ScalarGrid whole = parallel.Size() > 1
      ? WholeGridOfPieces(inputVector[0]->GetInformationObject(0), empty ? nullptr : input, offset)
      : piece.Grid;
    // the pipeline's progress between blocks of rows; an abort (ParaView's, an observer's
    // SetAbortExecute) stops the image there, with no image, and is spent
    const schlieren::ProgressFunction progress = [this](double fraction) {
      this->UpdateProgress(fraction);
      return !this->GetAbortExecute();
    };
    if (!schlieren::NumericalSchlierenOfPieces(
          parallel, piece.Grid, offset, whole, SettingsOf(this), image, progress))
    {
      return 1; // rank 0 holds the image
    }
  }
  catch (const schlieren::Error& e)
  {
    this->SetAbortExecute(0);
    vtkErrorMacro(<< e.what());
    return 0;
  }
  WriteImage(output, image);
  vtkFieldData* fd = output->GetFieldData();
  AddString(fd, "numerical_field", name);
  AddString(fd, "numerical_mode", schlieren::NumericalModeName(static_cast<schlieren::NumericalMode>(this->Mode)));
  AddString(fd, "numerical_gradient_kind",
    schlieren::NumericalQuantityName(static_cast<schlieren::NumericalQuantity>(this->Gradient)));
  AddNumber(fd, "gradient_maximum", image.Maximum);
  AddNumber(fd, "gradient_largest", image.Largest);
  return 1;
}

void vtkNumericalSchlieren::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << this->Mode << "\n";
  os << indent << "Gradient: " << this->Gradient << "\n";
  os << indent << "C0, C1, K: " << this->C0 << ", " << this->C1 << ", " << this->K << "\n";
  os << indent << "GradientMaximum: " << this->GradientMaximum << "\n";
  os << indent << "DensityArray: " << this->DensityArray << "\n";
}

vtkExecutive* vtkNumericalSchlieren::CreateDefaultExecutive()
{
  return schlieren::NewAgreeingExecutive();
}

vtkTypeBool vtkNumericalSchlieren::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return SchlierenGuarded(this,
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); });
}
