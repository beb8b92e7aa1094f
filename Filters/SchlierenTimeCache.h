// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenTimeCache.h
 * @brief RefractiveIndex's outputs kept per time step, so that an animation played again does not
 * resample (and its upstream does not execute) a time it has computed already: the VTK objects
 * held by the entries of the engine's store (OpenCL/SchlierenTimeStore.h, whose rule the Python
 * front end calls too).
 *
 * An entry is keyed by the requested time, the pipeline's modified time (the filter's and every
 * upstream algorithm's MTime: any property change invalidates every entry; the engine's change
 * token) and the output's update extent. The engine's budget: a quarter of the memory this process
 * could have, the oldest entries evicted first. One process only: under MPI a rank whose budget
 * differs would skip a collective step the others run, so the cache is off there.
 */
#ifndef SchlierenTimeCache_h
#define SchlierenTimeCache_h

#include "vtkDataObject.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "SchlierenTimeStore.h"

#include <algorithm>
#include <map>

namespace schlieren
{
class TimeStepCache
{
public:
  struct Key
  {
    double Time = 0.0;
    vtkMTimeType Pipeline = 0;
    int Extent[6] = { 0, -1, 0, -1, 0, -1 };
    TimeStepKey Engine() const
    {
      TimeStepKey k;
      k.Time = this->Time;
      k.Token = static_cast<std::uint64_t>(this->Pipeline);
      std::copy(this->Extent, this->Extent + 6, k.Extent);
      return k;
    }
  };

  /** The output kept for `key`, or null. */
  vtkDataObject* Find(const Key& key) const
  {
    const auto it = this->Data.find(this->Store.Find(key.Engine()));
    return it == this->Data.end() ? nullptr : it->second.GetPointer();
  }

  /** Keeps a shallow copy of `data` for `key` (its arrays' bytes), as the engine's store says. */
  void Insert(const Key& key, vtkDataObject* data)
  {
    std::vector<std::int64_t> dropped;
    const std::int64_t id = this->Store.Insert(
      key.Engine(), 1024.0 * static_cast<double>(data->GetActualMemorySize()), dropped);
    for (std::int64_t gone : dropped)
    {
      this->Data.erase(gone);
    }
    if (id >= 0)
    {
      vtkSmartPointer<vtkDataObject> copy;
      copy.TakeReference(data->NewInstance());
      copy->ShallowCopy(data);
      this->Data[id] = copy;
    }
  }

  /** Bytes the entries hold (their arrays' sizes; shared with the outputs while those live). */
  double Held() const { return this->Store.Held(); }
  /** A quarter of the memory available to this process, counting what the entries hold. */
  double Budget() const { return this->Store.Budget(); }
  std::size_t Size() const { return this->Store.Size(); }
  void Clear()
  {
    this->Store.Clear();
    this->Data.clear();
  }

  int Computed = 0; ///< outputs computed (resampled) by this filter
  int Served = 0;   ///< outputs served from the cache

private:
  TimeStepStore Store;
  std::map<std::int64_t, vtkSmartPointer<vtkDataObject>> Data;
};
} // namespace schlieren

#endif
