// SPDX-License-Identifier: BSD-3-Clause
#include "vtkRefractionOctree.h"
#include "SchlierenGuard.h"

#include <sstream>

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include "SchlierenArrays.h"
#include "SchlierenController.h"
#include "SchlierenEngine.h"
#include "SchlierenLimits.h"
#include "SchlierenValues.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkRefractionOctree);

//------------------------------------------------------------------------------
vtkRefractionOctree::vtkRefractionOctree()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkRefractionOctree::~vtkRefractionOctree() = default;

namespace
{
/**
 * This rank's piece of n - 1 as floats (an empty piece is fine under MPI) and its dimensions;
 * returns "" or the problem for the user.
 */
std::string ReadPiece(double tolerance, int maxLevel, vtkImageData* input, vtkImageData* output,
  int ranks, std::vector<float>& n1, int dims[3])
{
  // the ranges are the engine's (the Python front end checks the same)
  const double level = maxLevel;
  std::string range = schlieren::PropertyRangeProblem("RefractionOctree", "MaxLevel", &level, 1);
  if (range.empty())
    range = schlieren::PropertyRangeProblem("RefractionOctree", "Tolerance", &tolerance, 1);
  if (!range.empty())
    return range;
  if (!input || !output)
  {
    return std::string("RefractionOctree needs a vtkImageData input with the point array '") +
      schlieren::arrays::NMinus1 +
      "'. Resample the data onto an image and apply RefractiveIndex first.";
  }
  if (input->GetNumberOfPoints() == 0)
  {
    return ranks == 1 ? "RefractionOctree: the input image is empty." : "";
  }
  vtkDataArray* array = input->GetPointData()->GetArray(schlieren::arrays::NMinus1);
  if (!array || array->GetNumberOfComponents() != 1)
  {
    return std::string("RefractionOctree needs the one-component point array '") +
      schlieren::arrays::NMinus1 + "' (n - 1). Apply RefractiveIndex first.";
  }
  input->GetDimensions(dims);
  try
  {
    // the float copy of n - 1, the levels, and the min/max scratch of the first level
    std::ostringstream what;
    what << "RefractionOctree on " << dims[0] << " x " << dims[1] << " x " << dims[2] << " points";
    schlieren::CheckHostMemory(double(array->GetNumberOfTuples()) * (4.0 + 1.0 + 4.0), what.str(),
      "Resample the volume to fewer points (RefractiveIndex SamplingDimensions).");
  }
  catch (const schlieren::Error& e)
  {
    return e.what();
  }
  n1 = schlieren::values::Values<float>(array);
  return schlieren::ValidateIndex(n1.data(), n1.size());
}

/**
 * The levels of this piece into `levels` (a piece thinner than 2 points has no cell: level 0);
 * counts gets its skippable cells and its cells. Returns "" or the engine's error.
 */
std::string PieceLevels(const std::vector<float>& n1, const int dims[3], double tolerance,
  int maxLevel, vtkUnsignedCharArray* levels, double counts[2])
{
  levels->SetName(schlieren::arrays::OctreeLevel);
  levels->SetNumberOfTuples(static_cast<vtkIdType>(n1.size()));
  levels->FillValue(0);
  counts[0] = counts[1] = 0.0;
  if (n1.empty() || dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    return std::string();
  }
  try
  {
    const double fraction =
      schlieren::ComputeOctreeLevels(dims, n1.data(), tolerance, levels->GetPointer(0), maxLevel);
    counts[1] = double(dims[0] - 1) * (dims[1] - 1) * (dims[2] - 1);
    counts[0] = fraction * counts[1];
  }
  catch (const schlieren::Error& e)
  {
    // the checks of ReadPiece leave nothing for the engine to refuse; reported anyway
    return e.what();
  }
  return std::string();
}

void AddNumber(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
} // namespace

//------------------------------------------------------------------------------
int vtkRefractionOctree::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  schlieren::ControllerParallel parallel("RefractionOctree");

  // 1. This rank's piece of n - 1; every rank learns whether one failed, so that no rank waits
  // for another that has given up.
  std::vector<float> n1;
  int dims[3] = { 0, 0, 0 };
  // (a range's problem is the same on every rank: still agreed below, like any other failure)
  const std::string problem =
    ReadPiece(this->Tolerance, this->MaxLevel, input, output, parallel.Size(), n1, dims);
  const std::string failure = parallel.Failure(problem);
  if (!failure.empty())
  {
    vtkErrorMacro(<< (problem.empty() ? failure : problem));
    return 0;
  }

  // 2. The tolerance: the range of n - 1 is that of the whole volume, so that every rank uses
  // the same one.
  double lowest[2] = { std::numeric_limits<double>::max(), std::numeric_limits<double>::max() };
  for (float v : n1)
  {
    lowest[0] = std::min(lowest[0], double(v));
    lowest[1] = std::min(lowest[1], -double(v));
  }
  parallel.Min(lowest, 2);
  const double range = (-lowest[1]) - lowest[0];
  double tolerance = this->Tolerance;
  if (!(tolerance > 0))
  {
    tolerance = range > 0 ? AutomaticToleranceFraction * range : 0.0;
  }

  // 3. The levels of this piece, and the skippable fraction of the whole volume.
  output->ShallowCopy(input);
  vtkNew<vtkUnsignedCharArray> levels;
  double counts[2];
  const std::string engineError =
    PieceLevels(n1, dims, tolerance, this->MaxLevel, levels, counts);
  if (!engineError.empty())
  {
    vtkErrorMacro(<< engineError);
  }
  parallel.Sum(counts, 2);
  if (!n1.empty())
  {
    output->GetPointData()->AddArray(levels);
  }
  vtkFieldData* fd = output->GetFieldData();
  AddNumber(fd, schlieren::arrays::OctreeTolerance, tolerance);
  AddNumber(fd, schlieren::arrays::OctreeMaxLevel, this->MaxLevel);
  AddNumber(fd, schlieren::arrays::OctreeSkippableFraction,
    counts[1] > 0 ? counts[0] / counts[1] : 0.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkRefractionOctree::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tolerance: " << this->Tolerance
     << (this->Tolerance > 0 ? "" : " (automatic: a fraction of the range of n - 1)") << "\n";
  os << indent << "MaxLevel: " << this->MaxLevel << "\n";
}

//------------------------------------------------------------------------------
vtkExecutive* vtkRefractionOctree::CreateDefaultExecutive()
{
  return schlieren::NewAgreeingExecutive();
}

vtkTypeBool vtkRefractionOctree::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return SchlierenGuarded(this,
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); });
}
