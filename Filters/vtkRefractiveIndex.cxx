// SPDX-License-Identifier: BSD-3-Clause
#include "vtkRefractiveIndex.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "SchlierenEngine.h"
#include "SchlierenIndexModels.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkRefractiveIndex);

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
}

//------------------------------------------------------------------------------
vtkRefractiveIndex::vtkRefractiveIndex()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
  // Default: the active point scalars.
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

//------------------------------------------------------------------------------
vtkRefractiveIndex::~vtkRefractiveIndex() = default;

//------------------------------------------------------------------------------
int vtkRefractiveIndex::FillInputPortInformation(int port, vtkInformation* info)
{
  // Any data set is accepted at the pipeline level so that a non-image input gets a clear error
  // from this filter rather than a generic type mismatch from the executive.
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkRefractiveIndex::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkDataObject* input = vtkDataObject::GetData(inInfo);
  if (!vtkImageData::SafeDownCast(input))
  {
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outputVector->GetInformationObject(0)->Set(
      vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    vtkErrorMacro("RefractiveIndex needs a vtkImageData input; got "
      << (input ? input->GetClassName() : "nothing")
      << ". Resample the data onto an image first (for example with Resample To Image).");
    return 0;
  }
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  // Any sub-extent can be computed (from an input one point larger on every side).
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
  int whole[6], ext[6];
  inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  outInfo->Get(SDDP::UPDATE_EXTENT(), ext);

  // With a piece request the executive splits the output's update extent into this piece (we
  // produce sub-extents) only after this call: compute the same piece here.
  const int pieces = outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES())
    : 1;
  if (pieces > 1)
  {
    const int piece = outInfo->Get(SDDP::UPDATE_PIECE_NUMBER());
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
  const bool empty = ext[1] < ext[0] || ext[3] < ext[2] || ext[5] < ext[4];
  if (!empty)
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
int vtkRefractiveIndex::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* inputObject = vtkDataObject::GetData(inInfo);
  vtkImageData* input = vtkImageData::SafeDownCast(inputObject);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  if (!input || !output)
  {
    vtkErrorMacro("RefractiveIndex needs a vtkImageData input; got "
      << (inputObject ? inputObject->GetClassName() : "nothing")
      << ". Resample the data onto an image first (for example with Resample To Image).");
    return 0;
  }

  int outExt[6], inExt[6], whole[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), outExt);
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  input->GetExtent(inExt);
  if (outExt[1] < outExt[0] || outExt[3] < outExt[2] || outExt[5] < outExt[4] ||
    input->GetNumberOfPoints() == 0)
  {
    output->Initialize();
    return 1; // an empty piece
  }
  for (int a = 0; a < 3; ++a)
  {
    if (outExt[2 * a] < inExt[2 * a] || outExt[2 * a + 1] > inExt[2 * a + 1])
    {
      vtkErrorMacro("The input's extent ("
        << inExt[0] << " " << inExt[1] << " " << inExt[2] << " " << inExt[3] << " " << inExt[4]
        << " " << inExt[5] << ") does not cover the requested extent (" << outExt[0] << " "
        << outExt[1] << " " << outExt[2] << " " << outExt[3] << " " << outExt[4] << " " << outExt[5]
        << "); the upstream filter did not honour the update request.");
      return 0;
    }
  }

  // The chosen array.
  vtkInformation* arrayInfo = this->GetInputArrayInformation(0);
  const char* chosen = arrayInfo && arrayInfo->Has(vtkDataObject::FIELD_NAME())
    ? arrayInfo->Get(vtkDataObject::FIELD_NAME())
    : nullptr;
  vtkDataArray* array = nullptr;
  if (chosen && *chosen)
  {
    array = this->GetInputArrayToProcess(0, inputVector);
  }
  else
  {
    // No name chosen (e.g. a pvpython proxy created before its input was updated): the active
    // point scalars, else the first point array.
    vtkPointData* pd = input->GetPointData();
    array = pd->GetScalars() ? pd->GetScalars() : pd->GetArray(0);
  }
  if (!array)
  {
    vtkErrorMacro("The input has no point array "
      << (chosen && *chosen ? std::string("'") + chosen + "'" : std::string("(active scalars)"))
      << " to compute the refractive index from. Point arrays present: "
      << PointArrayNames(input) << ". Choose one of them as the input array.");
    return 0;
  }
  const std::string arrayName = array->GetName() ? array->GetName() : "(unnamed)";
  if (array->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("The input array '" << arrayName << "' has " << array->GetNumberOfComponents()
                                      << " components; the refractive index needs a scalar array.");
    return 0;
  }

  // n - 1 on the (grown) input piece: the array as float, then the model (in place).
  const vtkIdType count = input->GetNumberOfPoints();
  vtkNew<vtkFloatArray> nMinus1;
  nMinus1->SetName("n_minus_1");
  nMinus1->SetNumberOfTuples(count);
  float* n1 = nMinus1->GetPointer(0);
  for (vtkIdType i = 0; i < count; ++i)
  {
    n1[i] = static_cast<float>(array->GetComponent(i, 0));
  }

  vtkNew<vtkFloatArray> gradient;
  gradient->SetName("grad_n");
  gradient->SetNumberOfComponents(3);
  gradient->SetNumberOfTuples(count);
  try
  {
    if (this->Model == GLADSTONE_DALE)
    {
      schlieren::GladstoneDale(
        n1, static_cast<std::size_t>(count), this->GladstoneDaleConstant, n1);
    }
    const std::string problem = schlieren::ValidateIndex(n1, static_cast<std::size_t>(count));
    if (!problem.empty())
    {
      vtkErrorMacro("Input array '" << arrayName << "': " << problem);
      return 0;
    }
    int dims[3];
    input->GetDimensions(dims);
    double spacing[3];
    input->GetSpacing(spacing);
    schlieren::ComputeGradient(dims, spacing, n1, gradient->GetPointer(0));
  }
  catch (const schlieren::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  this->UpdateProgress(0.9);

  // Output: the requested extent of the input, with the two new arrays.
  const bool sameExtent = std::equal(inExt, inExt + 6, outExt);
  if (sameExtent)
  {
    output->ShallowCopy(input);
    output->GetPointData()->AddArray(gradient);
    output->GetPointData()->AddArray(nMinus1);
    output->GetPointData()->SetActiveScalars("n_minus_1");
    return 1;
  }

  vtkNew<vtkPointData> pointData;
  pointData->ShallowCopy(input->GetPointData());
  pointData->AddArray(gradient);
  pointData->AddArray(nMinus1);
  pointData->SetActiveScalars("n_minus_1");

  output->Initialize();
  output->SetExtent(outExt);
  output->SetOrigin(input->GetOrigin());
  output->SetSpacing(input->GetSpacing());
  output->SetDirectionMatrix(input->GetDirectionMatrix());
  const vtkIdType outCount = output->GetNumberOfPoints();
  output->GetPointData()->CopyAllocate(pointData, outCount);
  output->GetPointData()->CopyStructuredData(pointData, inExt, outExt);

  int inCells[6], outCells[6];
  CellExtent(whole, inExt, inCells);
  CellExtent(whole, outExt, outCells);
  output->GetCellData()->CopyAllocate(input->GetCellData(), output->GetNumberOfCells());
  output->GetCellData()->CopyStructuredData(input->GetCellData(), inCells, outCells);
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
  return 1;
}

//------------------------------------------------------------------------------
void vtkRefractiveIndex::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Model: " << this->Model
     << (this->Model == GLADSTONE_DALE ? " (GladstoneDale)" : " (Passthrough)") << "\n";
  os << indent << "GladstoneDaleConstant: " << this->GladstoneDaleConstant << " m^3/kg\n";
  os << indent << "Wavelength: " << this->Wavelength << " nm\n";
}
