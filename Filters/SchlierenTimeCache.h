// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenTimeCache.h
 * @brief RefractiveIndex's outputs kept per time step, so that an animation played again does not
 * resample (and its upstream does not execute) a time it has computed already.
 *
 * An entry is keyed by the requested time, the pipeline's modified time (the filter's and every
 * upstream algorithm's MTime: any property change invalidates every entry) and the output's
 * update extent. The entries together hold at most a quarter of the memory this process could
 * have (what AvailableMemory() reports plus what the cache holds; SCHLIEREN_MEMORY_LIMIT lowers
 * it); a new entry evicts the oldest ones until it fits, and one larger than the budget is not
 * kept. One process only: under MPI a rank whose budget differs would skip a collective step the
 * others run, so the cache is off there.
 */
#ifndef SchlierenTimeCache_h
#define SchlierenTimeCache_h

#include "vtkDataObject.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "SchlierenLimits.h"

#include <algorithm>
#include <deque>

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
    bool operator==(const Key& o) const
    {
      return this->Time == o.Time && this->Pipeline == o.Pipeline &&
        std::equal(this->Extent, this->Extent + 6, o.Extent);
    }
  };

  /** The output kept for `key`, or null. */
  vtkDataObject* Find(const Key& key) const
  {
    for (const Entry& e : this->Entries)
    {
      if (e.K == key)
      {
        return e.Data;
      }
    }
    return nullptr;
  }

  /** Keeps a shallow copy of `data` for `key`: entries of another pipeline MTime go (they cannot
   * be asked for again), then the oldest until it fits the budget. */
  void Insert(const Key& key, vtkDataObject* data)
  {
    this->Entries.erase(std::remove_if(this->Entries.begin(), this->Entries.end(),
                          [&](const Entry& e) { return e.K.Pipeline != key.Pipeline || e.K == key; }),
      this->Entries.end());
    Entry e;
    e.K = key;
    e.Data.TakeReference(data->NewInstance());
    e.Data->ShallowCopy(data);
    e.Bytes = 1024.0 * static_cast<double>(data->GetActualMemorySize());
    const double budget = this->Budget();
    while (!this->Entries.empty() && this->Held() + e.Bytes > budget)
    {
      this->Entries.pop_front();
    }
    if (e.Bytes <= budget)
    {
      this->Entries.push_back(e);
    }
  }

  /** Bytes the entries hold (their arrays' sizes; shared with the outputs while those live). */
  double Held() const
  {
    double b = 0.0;
    for (const Entry& e : this->Entries)
    {
      b += e.Bytes;
    }
    return b;
  }
  /** A quarter of the memory available to this process, counting what the entries hold. */
  double Budget() const
  {
    return 0.25 * (static_cast<double>(schlieren::AvailableMemory()) + this->Held());
  }
  std::size_t Size() const { return this->Entries.size(); }
  void Clear() { this->Entries.clear(); }

  int Computed = 0; ///< outputs computed (resampled) by this filter
  int Served = 0;   ///< outputs served from the cache

private:
  struct Entry
  {
    Key K;
    vtkSmartPointer<vtkDataObject> Data;
    double Bytes = 0.0;
  };
  std::deque<Entry> Entries; // oldest first
};
} // namespace schlieren

#endif
