// SPDX-License-Identifier: BSD-3-Clause
// Filters/SchlierenValues.h: Values<T> and ForEachFirstComponent read the values of a vtkDataArray
// through VTK's typed dispatch, and must give exactly what the per-value virtual GetComponent they
// replaced gave (static_cast<T>(GetComponent(i, c))): for every value type, for several
// components, and for arrays the dispatch does not know (vtkBitArray, a structure-of-arrays
// layout), which go through vtkDataArray's generic API. Exact equality is the known answer: the
// filters' outputs must not change by a bit (a 64-bit integer converted straight to float, not
// through double, rounds differently: the case below shows it).
#include "SchlierenValues.h"

#include "vtkBitArray.h"
#include "vtkCharArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkSOADataArrayTemplate.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
int failures = 0, passes = 0;

void Check(bool ok, const std::string& what)
{
  ++(ok ? passes : failures);
  if (!ok)
  {
    std::printf("FAIL %s\n", what.c_str());
  }
}

/** Values<T>(a) against static_cast<T>(a->GetComponent(i, c)), value by value. */
template <class T>
void Compare(vtkDataArray* a, const std::string& name)
{
  const std::vector<T> values = schlieren::values::Values<T>(a);
  const int nc = a->GetNumberOfComponents();
  const vtkIdType n = a->GetNumberOfTuples();
  bool same = values.size() == static_cast<std::size_t>(n * nc);
  for (vtkIdType i = 0; same && i < n; ++i)
  {
    for (int c = 0; c < nc; ++c)
    {
      same = same && values[i * nc + c] == static_cast<T>(a->GetComponent(i, c));
    }
  }
  Check(same,
    name + (sizeof(T) == 4 ? " as float" : " as double") + ": the values GetComponent gives");
}

/** ForEachFirstComponent(a) against GetComponent(i, 0), tuple by tuple, each tuple once. */
void CompareFirst(vtkDataArray* a, const std::string& name)
{
  vtkIdType next = 0;
  bool same = true;
  schlieren::values::ForEachFirstComponent(a, [&](vtkIdType i, double v) {
    same = same && i == next++ && v == a->GetComponent(i, 0);
  });
  Check(same && next == a->GetNumberOfTuples(),
    name + ": ForEachFirstComponent visits every tuple's first component in order");
}

void CompareBoth(vtkDataArray* a, const std::string& name)
{
  Compare<float>(a, name);
  Compare<double>(a, name);
  CompareFirst(a, name);
}
} // namespace

int main()
{
  vtkNew<vtkFloatArray> f;
  for (float v : { 0.0f, -1.5f, 3.0e-38f, 2.7e-4f, 1.0e30f })
  {
    f->InsertNextValue(v);
  }
  CompareBoth(f, "vtkFloatArray");

  vtkNew<vtkDoubleArray> d;
  d->SetNumberOfComponents(3);
  for (int i = 0; i < 7; ++i)
  {
    const double t[3] = { 0.1 * i, -1e300 * i, 1.0 / (i + 3) };
    d->InsertNextTuple(t);
  }
  CompareBoth(d, "vtkDoubleArray, 3 components");

  // 2^60 + 2^36 + 1: through double it becomes 2^60 + 2^36, a tie that float rounds to 2^60;
  // straight to float it would round up to 2^60 + 2^37
  const std::int64_t big = (std::int64_t(1) << 60) + (std::int64_t(1) << 36) + 1;
  vtkNew<vtkTypeInt64Array> i64;
  for (std::int64_t v : { std::int64_t(0), std::int64_t(-7), big, -big })
  {
    i64->InsertNextValue(v);
  }
  CompareBoth(i64, "vtkTypeInt64Array");
  Check(schlieren::values::Values<float>(i64)[2] == static_cast<float>(static_cast<double>(big)) &&
      static_cast<float>(static_cast<double>(big)) != static_cast<float>(big),
    "a 64-bit integer converts to float through double, as GetComponent did");

  vtkNew<vtkIntArray> ints;
  vtkNew<vtkUnsignedCharArray> bytes;
  vtkNew<vtkCharArray> chars;
  for (int v : { 0, 1, 2, 127, 255 })
  {
    ints->InsertNextValue(-v * 1000003);
    bytes->InsertNextValue(static_cast<unsigned char>(v));
    chars->InsertNextValue(static_cast<char>(v & 0x7f));
  }
  CompareBoth(ints, "vtkIntArray");
  CompareBoth(bytes, "vtkUnsignedCharArray");
  CompareBoth(chars, "vtkCharArray");

  // not in the dispatch's list: read through vtkDataArray's generic API
  vtkNew<vtkBitArray> bits;
  for (int v : { 1, 0, 0, 1, 1, 1, 0, 1, 0 })
  {
    bits->InsertNextValue(v);
  }
  CompareBoth(bits, "vtkBitArray");
  vtkNew<vtkSOADataArrayTemplate<double>> soa;
  soa->SetNumberOfComponents(2);
  soa->SetNumberOfTuples(4);
  for (vtkIdType i = 0; i < 4; ++i)
  {
    soa->SetTypedComponent(i, 0, 0.3 * i);
    soa->SetTypedComponent(i, 1, -1.0 / (i + 7));
  }
  CompareBoth(soa, "vtkSOADataArrayTemplate<double>, 2 components");

  vtkNew<vtkFloatArray> empty;
  Check(schlieren::values::Values<float>(empty).empty(), "an empty array: no values");

  std::printf("%d passed, %d failed\n", passes, failures);
  return failures ? 1 : 0;
}
