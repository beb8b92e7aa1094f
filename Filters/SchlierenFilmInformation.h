// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenFilmInformation.h
 * @brief The output information of a filter whose output is a film (SchlierenImage,
 * NumericalSchlieren): its whole extent, spacing and origin.
 */
#ifndef SchlierenFilmInformation_h
#define SchlierenFilmInformation_h

#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "SchlierenEngine.h"

namespace schlieren
{
/** Sets outInfo's WHOLE_EXTENT, SPACING and ORIGIN to those of the film (a 2D image, one layer). */
inline void SetFilmInformation(vtkInformation* outInfo, const FilmGeometry& film)
{
  double origin[2];
  film.GetImageOrigin(origin);
  const int whole[6] = { 0, film.Size[0] - 1, 0, film.Size[1] - 1, 0, 0 };
  const double spacing[3] = { film.PixelSize, film.PixelSize, 1.0 };
  const double origin3[3] = { origin[0], origin[1], 0.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin3, 3);
}
} // namespace schlieren

#endif
