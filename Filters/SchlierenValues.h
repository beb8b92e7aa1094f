// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenValues.h
 * @brief The values of a vtkDataArray of any value type, read through VTK's typed dispatch
 * (vtkArrayDispatch and vtk::DataArrayValueRange) rather than a virtual GetComponent per value.
 */
#ifndef SchlierenValues_h
#define SchlierenValues_h

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"

#include <algorithm>
#include <vector>

namespace schlieren
{
namespace values
{
namespace detail
{
struct CopyValues
{
  template <class ArrayT, class T>
  void operator()(ArrayT* array, std::vector<T>& out) const
  {
    const auto range = vtk::DataArrayValueRange(array);
    out.resize(static_cast<std::size_t>(range.size()));
    // through double, as GetComponent gives them, so that every value type converts as before
    std::transform(range.cbegin(), range.cend(), out.begin(),
      [](const auto v) { return static_cast<T>(static_cast<double>(v)); });
  }
};
} // namespace detail

/**
 * Every value of `array` (tuple after tuple, the components of a tuple in order) as a T, converted
 * through double. Arrays the dispatch does not know (implicit or other non-standard layouts) are
 * read through vtkDataArray's generic API.
 */
template <class T>
std::vector<T> Values(vtkDataArray* array)
{
  std::vector<T> out;
  detail::CopyValues worker;
  if (!vtkArrayDispatch::Dispatch::Execute(array, worker, out))
  {
    worker(array, out);
  }
  return out;
}
} // namespace values
} // namespace schlieren

#endif
