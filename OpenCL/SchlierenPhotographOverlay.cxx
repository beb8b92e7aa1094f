// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenPhotographOverlay.h"

#include "SchlierenEngine.h"

#include <cmath>
#include <sstream>
#include <string>

namespace schlieren
{

void PhotographGrey(const double* values, std::size_t count, int components, float* grey)
{
  if (components < 1 || components > 4)
    throw Error("The photograph has " + std::to_string(components) +
      " components a pixel: grey (1), grey and alpha (2), RGB (3) or RGBA (4) are taken.");
  const std::size_t c = static_cast<std::size_t>(components);
  for (std::size_t q = 0; q < count; ++q)
  {
    const double* p = values + q * c;
    // three products summed left to right, in double, as written (no fused multiply-add)
    const double r = p[0] * 0.2126;
    const double g = components >= 3 ? p[1] * 0.7152 : 0.0;
    const double b = components >= 3 ? p[2] * 0.0722 : 0.0;
    grey[q] = static_cast<float>(components >= 3 ? (r + g) + b : p[0]);
  }
}

void PhotographBlend(double weight, const float* film, const float* difference, std::size_t count, float* blend)
{
  if (!(weight >= 0 && weight <= 1))
  {
    std::ostringstream msg;
    msg << "BlendWeight is " << weight << ": it must be in [0, 1] (the photograph's share of the blend).";
    throw Error(msg.str());
  }
  const float w = static_cast<float>(weight);
  for (std::size_t q = 0; q < count; ++q)
  {
    const float d = w * difference[q];
    blend[q] = film[q] + d;
  }
}

} // namespace schlieren
