// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenPhotographOverlay.h
 * @brief What the photograph filter's front ends show beside RegisterPhotograph's images (issue 51):
 * a photograph's values made grey, and the blend of the calibrated photograph over the film. One
 * source for the C++ filter (vtkSchlierenPhotograph) and the Python front end (through the C
 * interface: schlieren_photograph_grey, schlieren_photograph_blend), so both give the same bits.
 */
#ifndef SchlierenPhotographOverlay_h
#define SchlierenPhotographOverlay_h

#include <cstddef>

namespace schlieren
{

/**
 * A photograph's pixels (`count` pixels of `components` values each, as a reader gives them) as
 * grey: 1 component as it is, 2 (grey and alpha) the first, 3 or 4 (RGB, RGBA) the luminance
 * 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709; alpha ignored), in double, then float. Throws Error for
 * another number of components.
 */
void PhotographGrey(const double* values, std::size_t count, int components, float* grey);

/**
 * The blend shown over the film: film + weight * difference (float arithmetic), that is
 * (1 - weight) film + weight calibrated where the photograph covers the film and the film elsewhere
 * (RegisterPhotograph's difference is 0 there). `weight` in [0, 1] (the photograph's share); Error
 * otherwise.
 */
void PhotographBlend(double weight, const float* film, const float* difference, std::size_t count, float* blend);

} // namespace schlieren

#endif
