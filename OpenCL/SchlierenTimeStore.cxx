// SPDX-License-Identifier: BSD-3-Clause
// RefractiveIndex's per-time-step cache: the rule and its keys (SchlierenTimeStore.h).
#include "SchlierenTimeStore.h"

#include "SchlierenLimits.h"

#include <algorithm>

namespace schlieren
{

bool TimeStepKey::operator==(const TimeStepKey& o) const
{
  return this->Time == o.Time && this->Token == o.Token &&
    std::equal(this->Extent, this->Extent + 6, o.Extent);
}

std::int64_t FindTimeStep(const std::vector<TimeStepKey>& held, const TimeStepKey& key)
{
  for (std::size_t i = 0; i < held.size(); ++i)
  {
    if (held[i] == key)
    {
      return static_cast<std::int64_t>(i);
    }
  }
  return -1;
}

double TimeStepBudget(double heldBytes)
{
  return 0.25 * (static_cast<double>(AvailableMemory()) + heldBytes);
}

bool PlanTimeStepInsert(const std::vector<TimeStepKey>& held, const std::vector<double>& heldBytes,
  const TimeStepKey& key, double bytes, std::vector<unsigned char>& keep, double* budgetOut)
{
  keep.assign(held.size(), 0);
  double stays = 0.0;
  for (std::size_t i = 0; i < held.size(); ++i)
  {
    // another token: it cannot be asked for again; the same key: replaced
    keep[i] = held[i].Token == key.Token && !(held[i] == key) ? 1 : 0;
    stays += keep[i] ? heldBytes[i] : 0.0;
  }
  const double budget = TimeStepBudget(stays);
  for (std::size_t i = 0; i < held.size() && stays + bytes > budget; ++i)
  {
    if (keep[i])
    {
      keep[i] = 0; // the oldest first
      stays -= heldBytes[i];
    }
  }
  if (budgetOut)
  {
    *budgetOut = budget;
  }
  return bytes <= budget;
}

std::int64_t TimeStepStore::Find(const TimeStepKey& key) const
{
  for (const Entry& e : this->Entries)
  {
    if (e.Key == key)
    {
      return e.Id;
    }
  }
  return -1;
}

std::int64_t TimeStepStore::Insert(
  const TimeStepKey& key, double bytes, std::vector<std::int64_t>& dropped)
{
  std::vector<TimeStepKey> keys;
  std::vector<double> sizes;
  for (const Entry& e : this->Entries)
  {
    keys.push_back(e.Key);
    sizes.push_back(e.Bytes);
  }
  std::vector<unsigned char> keep;
  const bool kept = PlanTimeStepInsert(keys, sizes, key, bytes, keep);
  std::deque<Entry> stay;
  for (std::size_t i = 0; i < this->Entries.size(); ++i)
  {
    if (keep[i])
    {
      stay.push_back(this->Entries[i]);
    }
    else
    {
      dropped.push_back(this->Entries[i].Id);
    }
  }
  this->Entries.swap(stay);
  if (!kept)
  {
    return -1;
  }
  Entry e;
  e.Key = key;
  e.Bytes = bytes;
  e.Id = this->NextId++;
  this->Entries.push_back(e);
  return e.Id;
}

double TimeStepStore::Held() const
{
  double b = 0.0;
  for (const Entry& e : this->Entries)
  {
    b += e.Bytes;
  }
  return b;
}

double TimeStepStore::Budget() const
{
  return TimeStepBudget(this->Held());
}
} // namespace schlieren
