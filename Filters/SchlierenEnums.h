// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenEnums.h
 * @brief Internal to the filters: an enumeration or boolean property outside its XML domain.
 *
 * The setters take any int (a clamp would turn Integrator = 99 into another integrator without a
 * word); each filter asks here, where its other range checks are, and reports the text as an
 * error naming the property, the value and the allowed entries.
 */
#ifndef SchlierenEnums_h
#define SchlierenEnums_h

#include "SchlierenLimits.h" // schlieren::EnumerationProblem: the message, the engine's

#include <initializer_list>
#include <string>

using SchlierenEntry = schlieren::PropertyEntry;

/** Empty where `value` is one of `entries` (those of the property's EnumerationDomain); else
 * "Name is V: it must be one of A (0), B (1)." */
inline std::string SchlierenEnumProblem(
  const std::string& name, int value, std::initializer_list<SchlierenEntry> entries)
{
  return schlieren::EnumerationProblem(name, value, std::vector<SchlierenEntry>(entries));
}

/** Empty where `value` is 0 or 1 (a BooleanDomain); else "Name is V: it must be 0 (off) or 1 (on)." */
inline std::string SchlierenBoolProblem(const std::string& name, int value)
{
  if (value == 0 || value == 1)
    return std::string();
  return name + " is " + std::to_string(value) + ": it must be 0 (off) or 1 (on).";
}

#endif
