// SPDX-License-Identifier: BSD-3-Clause
#include "vtkRefractionOctree.h"
#include "SchlierenGuard.h"

#include <sstream>

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include "SchlierenEngine.h"
#include "SchlierenLimits.h"

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

//------------------------------------------------------------------------------
int vtkRefractionOctree::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? std::max(controller->GetNumberOfProcesses(), 1) : 1;

  // 1. This rank's piece of n - 1 (an empty piece is fine under MPI).
  std::string problem;
  std::vector<float> n1;
  int dims[3] = { 0, 0, 0 };
  if (!(this->Tolerance >= 0.0 && this->Tolerance <= 1.0))
  {
    std::ostringstream msg;
    msg << "Tolerance is " << this->Tolerance
        << ": it must be in [0, 1] (a spread of n - 1, index units; 0: automatic).";
    problem = msg.str();
  }
  else if (!input || !output)
  {
    problem = "RefractionOctree needs a vtkImageData input with the point array 'n_minus_1'. "
              "Resample the data onto an image and apply RefractiveIndex first.";
  }
  else if (input->GetNumberOfPoints() > 0)
  {
    vtkDataArray* array = input->GetPointData()->GetArray("n_minus_1");
    if (!array || array->GetNumberOfComponents() != 1)
    {
      problem = "RefractionOctree needs the one-component point array 'n_minus_1' (n - 1). "
                "Apply RefractiveIndex first.";
    }
    else
    {
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
        problem = e.what();
      }
    }
    if (problem.empty() && array && array->GetNumberOfComponents() == 1)
    {
      n1.resize(static_cast<std::size_t>(array->GetNumberOfTuples()));
      for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
      {
        n1[i] = static_cast<float>(array->GetComponent(i, 0));
      }
      const std::string bad = schlieren::ValidateIndex(n1.data(), n1.size());
      if (!bad.empty())
      {
        problem = bad;
      }
    }
  }
  else if (ranks == 1)
  {
    problem = "RefractionOctree: the input image is empty.";
  }

  // 2. The tolerance: the range of n - 1 is that of the whole volume (reduced across ranks), so
  // that every rank uses the same one. Errors are reduced with it: no rank waits for another that
  // has given up.
  double lo = std::numeric_limits<double>::max(), hi = -std::numeric_limits<double>::max();
  for (float v : n1)
  {
    lo = std::min(lo, double(v));
    hi = std::max(hi, double(v));
  }
  double local[3] = { lo, -hi, problem.empty() ? 0.0 : -1.0 };
  double global[3] = { lo, -hi, local[2] };
  if (ranks > 1)
  {
    controller->AllReduce(local, global, 3, vtkCommunicator::MIN_OP);
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  if (global[2] < 0)
  {
    vtkErrorMacro("Another MPI rank failed (see its error); no octree.");
    return 0;
  }
  const double range = (-global[1]) - global[0];
  double tolerance = this->Tolerance;
  if (!(tolerance > 0))
  {
    tolerance = range > 0 ? AutomaticToleranceFraction * range : 0.0;
  }

  // 3. The levels of this piece (a piece thinner than 2 points has no cell: level 0).
  output->ShallowCopy(input);
  vtkNew<vtkUnsignedCharArray> levels;
  levels->SetName("octree_level");
  levels->SetNumberOfTuples(static_cast<vtkIdType>(n1.size()));
  levels->FillValue(0);
  double counts[2] = { 0.0, 0.0 }; // skippable cells, cells
  if (!n1.empty() && dims[0] >= 2 && dims[1] >= 2 && dims[2] >= 2)
  {
    try
    {
      const double fraction =
        schlieren::ComputeOctreeLevels(dims, n1.data(), tolerance, levels->GetPointer(0), this->MaxLevel);
      counts[1] = double(dims[0] - 1) * (dims[1] - 1) * (dims[2] - 1);
      counts[0] = fraction * counts[1];
    }
    catch (const schlieren::Error& e)
    {
      // the checks above leave nothing for the engine to refuse; report it anyway
      vtkErrorMacro(<< e.what());
    }
  }
  double totals[2] = { counts[0], counts[1] };
  if (ranks > 1)
  {
    controller->AllReduce(counts, totals, 2, vtkCommunicator::SUM_OP);
  }
  if (!n1.empty())
  {
    output->GetPointData()->AddArray(levels);
  }

  vtkFieldData* fd = output->GetFieldData();
  auto addNumber = [fd](const char* name, double value) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  addNumber("octree_tolerance", tolerance);
  addNumber("octree_max_level", this->MaxLevel);
  addNumber("octree_skippable_fraction", totals[1] > 0 ? totals[0] / totals[1] : 0.0);
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
vtkTypeBool vtkRefractionOctree::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return SchlierenGuarded(this,
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); });
}
