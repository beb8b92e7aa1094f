// SPDX-License-Identifier: BSD-3-Clause
// Names: the enums' names and parsing, and TraceSettings::PhotonKey.
#include "SchlierenEngineInternal.h"

#include <sstream>
#include <string>

namespace schlieren
{

Backend ParseBackend(const std::string& name)
{
  if (name == "Auto" || name == "auto")
    return Backend::Auto;
  if (name == "OpenCL" || name == "opencl")
    return Backend::OpenCL;
  if (name == "CPU" || name == "cpu")
    return Backend::CPU;
  throw Error("Unknown backend '" + name + "': use Auto, OpenCL or CPU.");
}

const char* BackendName(Backend b)
{
  switch (b)
  {
    case Backend::Auto:
      return "Auto";
    case Backend::OpenCL:
      return "OpenCL";
    case Backend::CPU:
      return "CPU";
  }
  return "?";
}

const char* CutoffName(Cutoff c)
{
  switch (c)
  {
    case Cutoff::KnifeEdge:
      return "KnifeEdge";
    case Cutoff::Shadowgraph:
      return "Shadowgraph";
    case Cutoff::Circular:
      return "Circular";
    case Cutoff::ComplementCircular:
      return "ComplementCircular";
    case Cutoff::ColorFilter:
      return "ColorFilter";
    case Cutoff::Interferometry:
      return "Interferometry";
    case Cutoff::BOS:
      return "BOS";
  }
  return "?";
}

std::string TraceSettings::PhotonKey() const
{
  std::ostringstream k;
  k.precision(17);
  k << ViewDirection[0] << ' ' << ViewDirection[1] << ' ' << ViewDirection[2] << ' ' << ViewUp[0]
    << ' ' << ViewUp[1] << ' ' << ViewUp[2] << ' ' << Resolution[0] << ' ' << Resolution[1] << ' '
    << static_cast<int>(Frame) << ' ' << FilmExtent[0] << ' ' << FilmExtent[1] << ' '
    << FilmExtent[2] << ' ' << FilmExtent[3] << ' ' << StepSize << ' ' << static_cast<int>(Method) << ' ' << KeepInvariant << ' ' << EstimateError
    << ' ' << UseOctree << ' ' << static_cast<int>(Recon) << ' ' << Tolerance << ' ' << AutoMeasuredError << ' ' << FieldStride << ' '
    << static_cast<int>(Mode) << ' ' << KnifeAngle << ' ' << CutoffScale << ' ' << FilmDistance
    << ' ' << Wavelength << ' ' << ReferenceTilt << ' ' << BackgroundDistance << ' '
    << BackgroundPattern << ' ' << BackgroundPeriod << ' ' << RussianRoulette << ' ' << Jitter
    << ' ' << static_cast<int>(Pattern)
    << ' ' << Seed << ' ' << MaxSteps << ' ' << static_cast<int>(Device) << ' ' << DeviceName.size()
    << ':' << DeviceName << ' ' << RaysPerWorkItem
    << ' ' << RankIndex << ' ' << RankCount
    << ' ' << static_cast<int>(Source) << ' ' << SourceSize[0] << ' ' << SourceSize[1] << ' '
    << CollimatorFocalLength << ' ' << SchlierenFocalLength << ' ' << KnifeCut << ' ' << StopDiameter;
  // the camera (SourceGridDistance is a read-out only)
  k << ' ' << static_cast<int>(Camera) << ' ' << CameraFocalLength << ' ' << FNumber << ' '
    << CameraDistance << ' ' << FocusPlane;
  k << ' ' << WavelengthRange[0] << ' ' << WavelengthRange[1] << ' ' << WavelengthBins << ' '
    << static_cast<int>(Disperse);
  return k.str();
}

const char* IntegratorName(Integrator m)
{
  switch (m)
  {
    case Integrator::Euler:
      return "Euler";
    case Integrator::Midpoint:
      return "Midpoint";
    case Integrator::RK4:
      return "RK4";
    case Integrator::Straight:
      return "Straight";
    case Integrator::Auto:
      return "Auto";
    case Integrator::Verlet:
      return "Verlet";
  }
  return "?";
}

const char* ReconstructionName(Reconstruction r)
{
  switch (r)
  {
    case Reconstruction::Trilinear:
      return "Trilinear";
    case Reconstruction::Cubic:
      return "Cubic";
    case Reconstruction::Auto:
      return "Auto";
  }
  return "?";
}

} // namespace schlieren
