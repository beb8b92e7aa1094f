// SPDX-License-Identifier: BSD-3-Clause
#include "vtkRefractiveScene.h"
#include "SchlierenEnums.h"
#include "SchlierenGuard.h"
#include "SchlierenLimits.h"

#include <sstream>

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "SchlierenArrays.h"
#include "SchlierenEngine.h"
#include "SchlierenScenes.h"

vtkStandardNewMacro(vtkRefractiveScene);

//------------------------------------------------------------------------------
vtkRefractiveScene::vtkRefractiveScene()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkRefractiveScene::~vtkRefractiveScene() = default;

//------------------------------------------------------------------------------
void vtkRefractiveScene::EngineParameters(
  schlieren::SceneParameters& p, schlieren::BodyParameters& b) const
{
  p.Amplitude = this->Amplitude;
  p.Width = this->Width;
  p.Radius = this->Radius;
  std::copy(this->Center, this->Center + 3, p.Center);
  p.GradientA = this->GradientA;
  p.GradientB = this->GradientB;
  p.Mach = this->Mach;
  p.Density = this->Density;
  p.Time = this->Time;
  b.Shape = static_cast<schlieren::Body>(this->Body);
  b.Radius = this->BodyRadius;
  std::copy(this->BodyCenter, this->BodyCenter + 3, b.Center);
  std::copy(this->BodyAxis, this->BodyAxis + 3, b.Axis);
}

//------------------------------------------------------------------------------
bool vtkRefractiveScene::ComputeGrid(double origin[3], double spacing[3])
{
  // the numeric properties' ranges, those of their domains in Schlieren.xml, and finite vectors:
  // the engine's check (schlieren::CheckSceneParameters), the same for every front end; outside,
  // an error naming the property, the value and the range (a clamp would change the scene
  // silently). TimeSteps is this filter's alone (the engine's scenes take one time).
  schlieren::SceneParameters p;
  schlieren::BodyParameters b;
  this->EngineParameters(p, b);
  try
  {
    schlieren::CheckSceneParameters(p, b);
  }
  catch (const schlieren::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  if (!(this->TimeSteps >= 0 && this->TimeSteps <= 10000))
  {
    vtkErrorMacro(<< "TimeSteps is " << this->TimeSteps << ": it must be in [0, 10000].");
    return false;
  }
  // the enumerations' entries, those of their domains in Schlieren.xml
  for (const std::string& problem : { SchlierenEnumProblem("Scene", this->Scene,
                                        { { 0, "Uniform" }, { 1, "GaussianSphere" },
                                          { 2, "LuneburgLens" }, { 3, "LinearGradient" },
                                          { 4, "NormalShock" }, { 5, "HeliumPlume" },
                                          { 6, "BlastWave" } }),
         SchlierenEnumProblem(
           "Body", this->Body, { { 0, "None" }, { 1, "Sphere" }, { 2, "Cylinder" } }) })
  {
    if (!problem.empty())
    {
      vtkErrorMacro(<< problem);
      return false;
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    const double lo = this->Bounds[2 * a], hi = this->Bounds[2 * a + 1];
    if (this->Dimensions[a] < 1)
    {
      vtkErrorMacro("Dimensions must be at least 1 along each axis; got " << this->Dimensions[0]
                                                                          << " " << this->Dimensions[1]
                                                                          << " " << this->Dimensions[2]
                                                                          << ".");
      return false;
    }
    if (this->Dimensions[a] > 1 && !(hi > lo))
    {
      vtkErrorMacro("Bounds along axis " << a << " are [" << lo << ", " << hi
                                         << "]: the max must exceed the min.");
      return false;
    }
    origin[a] = lo;
    spacing[a] = this->Dimensions[a] > 1 ? (hi - lo) / (this->Dimensions[a] - 1)
                                         : (hi > lo ? hi - lo : 1.0);
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkRefractiveScene::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  double origin[3], spacing[3];
  if (!this->ComputeGrid(origin, spacing))
  {
    return 0;
  }
  int whole[6] = { 0, this->Dimensions[0] - 1, 0, this->Dimensions[1] - 1, 0,
    this->Dimensions[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  // the blast wave is a time series: TimeSteps steps up to Time, which ParaView's animation plays
  if (this->Scene == BLAST_WAVE && this->TimeSteps > 0)
  {
    std::vector<double> times(this->TimeSteps);
    for (int i = 0; i < this->TimeSteps; ++i)
    {
      times[i] = this->Time * (i + 1) / this->TimeSteps;
    }
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), this->TimeSteps);
    const double range[2] = { times.front(), times.back() };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  else
  {
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkRefractiveScene::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  double origin[3], spacing[3];
  if (!output || !this->ComputeGrid(origin, spacing))
  {
    return 0;
  }

  int ext[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  output->SetOrigin(origin);
  output->SetSpacing(spacing);
  output->SetExtent(ext);
  if (ext[1] < ext[0] || ext[3] < ext[2] || ext[5] < ext[4])
  {
    return 1; // an empty piece
  }

  // The requested piece is a grid of its own whose first point is (ext[0], ext[2], ext[4]).
  const int dims[3] = { ext[1] - ext[0] + 1, ext[3] - ext[2] + 1, ext[5] - ext[4] + 1 };
  const double pieceOrigin[3] = { origin[0] + ext[0] * spacing[0], origin[1] + ext[2] * spacing[1],
    origin[2] + ext[4] * spacing[2] };
  const std::string problem = this->FillPiece(outInfo, output, dims, pieceOrigin, spacing);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    output->Initialize();
    return 0;
  }
  return 1;
}

//------------------------------------------------------------------------------
namespace
{
vtkSmartPointer<vtkFloatArray> NewFloats(const char* name, vtkIdType count)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(name);
  a->SetNumberOfTuples(count);
  return a;
}
} // namespace

//------------------------------------------------------------------------------
std::string vtkRefractiveScene::FillPiece(vtkInformation* outInfo, vtkImageData* output,
  const int dims[3], const double pieceOrigin[3], const double spacing[3])
{
  const vtkIdType count = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  const bool plume = this->Scene == HELIUM_PLUME;
  schlieren::SceneParameters p;
  schlieren::BodyParameters b;
  this->EngineParameters(p, b);
  if (this->Scene == BLAST_WAVE && this->TimeSteps > 0 &&
    outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    // the time the pipeline asks for (ParaView's animation time)
    p.Time = std::max(1e-6, outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()));
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), p.Time);
  }

  vtkSmartPointer<vtkFloatArray> nMinus1, density, mixture;
  vtkNew<vtkUnsignedCharArray> solid;
  try
  {
    std::ostringstream what;
    what << "RefractiveScene's grid of " << dims[0] << " x " << dims[1] << " x " << dims[2]
         << " points (" << (plume ? 3 : 2) << " float arrays)";
    schlieren::CheckHostMemory(double(dims[0]) * dims[1] * dims[2] * 4.0 * (plume ? 3 : 2),
      what.str(), "Lower Dimensions.");
    nMinus1 = NewFloats(schlieren::arrays::NMinus1, count);
    density = NewFloats("density", count);
    mixture = plume ? NewFloats("mixture_fraction", count) : nullptr;
    schlieren::FillScene(static_cast<schlieren::Scene>(this->Scene), p, dims, pieceOrigin, spacing,
      nMinus1->GetPointer(0), density->GetPointer(0), plume ? mixture->GetPointer(0) : nullptr);
    if (this->Body != NO_BODY)
    {
      solid->SetName(schlieren::arrays::Solid);
      solid->SetNumberOfTuples(count);
      schlieren::FillBody(b, dims, pieceOrigin, spacing, solid->GetPointer(0));
    }
  }
  catch (const schlieren::Error& e)
  {
    return e.what();
  }
  if (this->Body != NO_BODY)
  {
    output->GetPointData()->AddArray(solid);
  }
  output->GetPointData()->SetScalars(nMinus1);
  output->GetPointData()->AddArray(density);
  if (plume)
  {
    output->GetPointData()->AddArray(mixture);
  }
  return std::string();
}

//------------------------------------------------------------------------------
void vtkRefractiveScene::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scene: " << this->Scene << " ("
     << schlieren::SceneName(static_cast<schlieren::Scene>(this->Scene)) << ")\n";
  os << indent << "Dimensions: " << this->Dimensions[0] << " " << this->Dimensions[1] << " "
     << this->Dimensions[2] << "\n";
  os << indent << "Bounds: " << this->Bounds[0] << " " << this->Bounds[1] << " " << this->Bounds[2]
     << " " << this->Bounds[3] << " " << this->Bounds[4] << " " << this->Bounds[5] << "\n";
  os << indent << "Amplitude: " << this->Amplitude << "\n";
  os << indent << "Width: " << this->Width << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "Center: " << this->Center[0] << " " << this->Center[1] << " " << this->Center[2]
     << "\n";
  os << indent << "GradientA: " << this->GradientA << "\n";
  os << indent << "GradientB: " << this->GradientB << "\n";
  os << indent << "Mach: " << this->Mach << "\n";
  os << indent << "Density: " << this->Density << " kg/m^3\n";
  os << indent << "Time: " << this->Time << "\n";
  os << indent << "TimeSteps: " << this->TimeSteps << "\n";
  os << indent << "Body: " << schlieren::BodyName(static_cast<schlieren::Body>(this->Body))
     << ", radius " << this->BodyRadius << ", centre " << this->BodyCenter[0] << " "
     << this->BodyCenter[1] << " " << this->BodyCenter[2] << ", axis " << this->BodyAxis[0] << " "
     << this->BodyAxis[1] << " " << this->BodyAxis[2] << "\n";
}

//------------------------------------------------------------------------------
vtkTypeBool vtkRefractiveScene::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return SchlierenGuarded(this,
    [&] { return this->Superclass::ProcessRequest(request, inputVector, outputVector); });
}
