// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenTimeStore.h
 * @brief RefractiveIndex's per-time-step cache, on plain keys: outputs kept per time step, so that
 * an animation played again does not resample (and its upstream does not execute) a time it has
 * computed already. The front ends hold the outputs (VTK objects); the engine holds the rule.
 *
 * An entry is keyed by the requested time, a change token the caller gives (what it says changed:
 * the C++ filter its pipeline's modified time, the Python one its own and its upstream's; any other
 * token invalidates every entry, which cannot be asked for again) and the output's update extent.
 * The entries together hold at most a quarter of the memory this process could have (what
 * AvailableMemory() reports plus what the cache holds; SCHLIEREN_MEMORY_LIMIT lowers it); a new
 * entry evicts the oldest ones until it fits, and one larger than the budget is not kept.
 * The rule is stateless (FindTimeStep, PlanTimeStepInsert: the C interface's
 * schlieren_time_cache_find and _insert); TimeStepStore keeps the keys for a C++ front end.
 */
#ifndef SchlierenTimeStore_h
#define SchlierenTimeStore_h

#include <cstdint>
#include <deque>
#include <vector>

namespace schlieren
{
struct TimeStepKey
{
  double Time = 0.0;
  std::uint64_t Token = 0;
  int Extent[6] = { 0, -1, 0, -1, 0, -1 };
  bool operator==(const TimeStepKey& o) const;
};

/** The index of `key` among `held`, or -1. */
std::int64_t FindTimeStep(const std::vector<TimeStepKey>& held, const TimeStepKey& key);

/** A quarter of the memory available to this process, counting `heldBytes` the cache holds. */
double TimeStepBudget(double heldBytes);

/**
 * Which entries stay when `key` (`bytes`) is kept: `held` (oldest first, `heldBytes` each) loses
 * the entries of another token and the one of the same key, then the oldest until the new one
 * fits the budget (TimeStepBudget of what stays before the oldest go). `keep` gets a flag per held
 * entry; returns whether the new one is kept (not where it is larger than the budget). `budget`
 * (may be null) gets the budget it was measured against.
 */
bool PlanTimeStepInsert(const std::vector<TimeStepKey>& held, const std::vector<double>& heldBytes,
  const TimeStepKey& key, double bytes, std::vector<unsigned char>& keep, double* budget = nullptr);

/** The rule with its keys kept: entries named by ids the front end maps to its outputs. */
class TimeStepStore
{
public:
  /** The id of the entry kept for `key`, or -1. */
  std::int64_t Find(const TimeStepKey& key) const;
  /** Keeps an entry of `bytes` for `key` (PlanTimeStepInsert); returns its id, or -1 where it is
   * not kept. `dropped` gets the ids of the entries that went (the front end releases them). */
  std::int64_t Insert(const TimeStepKey& key, double bytes, std::vector<std::int64_t>& dropped);
  /** Bytes the entries hold. */
  double Held() const;
  /** TimeStepBudget(Held()). */
  double Budget() const;
  std::size_t Size() const { return this->Entries.size(); }
  void Clear() { this->Entries.clear(); }

private:
  struct Entry
  {
    TimeStepKey Key;
    double Bytes = 0.0;
    std::int64_t Id = 0;
  };
  std::deque<Entry> Entries; // oldest first
  std::int64_t NextId = 0;
};
} // namespace schlieren

#endif
