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

struct VisitFirstComponent
{
  template <class ArrayT, class F>
  void operator()(ArrayT* array, F& f) const
  {
    vtkIdType i = 0;
    for (const auto tuple : vtk::DataArrayTupleRange(array))
    {
      f(i++, static_cast<double>(tuple[0]));
    }
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
/**
 * Calls f(i, value) for every tuple i of `array` (with at least one component), value being its
 * first component as a double (what GetComponent(i, 0) gives), without a copy of the array.
 */
template <class F>
void ForEachFirstComponent(vtkDataArray* array, F&& f)
{
  detail::VisitFirstComponent worker;
  if (!vtkArrayDispatch::Dispatch::Execute(array, worker, f))
  {
    worker(array, f);
  }
}
} // namespace values
} // namespace schlieren

#endif
