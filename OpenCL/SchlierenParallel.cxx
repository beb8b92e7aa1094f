// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenParallel.h"

#include "SchlierenEngine.h"

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

namespace schlieren
{

// ------------------------------------------------------------------ conveniences

namespace
{
/** A reduction whose result cannot come from this rank's value `mine` (a broken transport: the
 * engine checks what comes back before it relies on it). */
[[noreturn]] void ImpossibleReduction(const Parallel& p, const char* op, double mine, double got)
{
  throw Error("Parallel: the ranks' " + std::string(op) + " came back as " + std::to_string(got) +
    " on rank " + std::to_string(p.Rank()) + " of " + std::to_string(p.Size()) + ", whose own value is " +
    std::to_string(mine) + ": that cannot be (the ranks' messages were changed on the way: a broken transport).");
}
}

double Parallel::Sum(double v)
{
  this->Reduce(&v, 1, ReduceOp::Sum);
  return v;
}

double Parallel::Max(double v)
{
  const double mine = v;
  this->Reduce(&v, 1, ReduceOp::Max);
  if (v < mine)
    ImpossibleReduction(*this, "maximum", mine, v);
  return v;
}

double Parallel::Min(double v)
{
  const double mine = v;
  this->Reduce(&v, 1, ReduceOp::Min);
  if (v > mine)
    ImpossibleReduction(*this, "minimum", mine, v);
  return v;
}

bool Parallel::AllOk(bool ok)
{
  // the minimum of 0s and 1s: 0 or 1, and 0 where this rank's is
  const double all = this->Min(ok ? 1.0 : 0.0);
  if (!(all == 0.0 || all == 1.0))
    ImpossibleReduction(*this, "minimum of 0s and 1s", ok ? 1.0 : 0.0, all);
  return all > 0.5;
}

std::vector<std::string> Parallel::AllGatherStrings(const std::string& mine)
{
  std::vector<std::vector<char>> all = this->AllGather(std::vector<char>(mine.begin(), mine.end()));
  std::vector<std::string> out;
  out.reserve(all.size());
  for (const std::vector<char>& b : all)
    out.emplace_back(b.begin(), b.end());
  return out;
}

std::string Parallel::BroadcastString(const std::string& s, int root)
{
  std::vector<char> bytes(s.begin(), s.end());
  this->Broadcast(bytes, root);
  return std::string(bytes.begin(), bytes.end());
}

std::string Parallel::Failure(const std::string& mine)
{
  if (this->Size() == 1)
    return mine;
  // the lowest failing rank's message, so that every rank reports the same
  const double first = this->Min(mine.empty() ? static_cast<double>(this->Size()) : this->Rank());
  if (!(first >= 0 && first <= this->Size() && first == static_cast<int>(first)))
    ImpossibleReduction(*this, "lowest failing rank", mine.empty() ? this->Size() : this->Rank(), first);
  if (first >= this->Size())
    return std::string();
  const int root = static_cast<int>(first);
  const std::string message = this->BroadcastString(mine, root);
  if (root == this->Rank())
    return message;
  return "another rank (" + std::to_string(root) + ") failed: " + message;
}

// ------------------------------------------------------------------ one rank

namespace
{

class Serial final : public Parallel
{
public:
  int Rank() const override { return 0; }
  int Size() const override { return 1; }
  void Reduce(double*, std::size_t, ReduceOp) override {}
  void Broadcast(std::vector<char>&, int) override {}
  std::vector<std::vector<char>> AllGather(const std::vector<char>& mine) override
  {
    return { mine };
  }
  std::vector<std::vector<char>> Exchange(const std::vector<std::vector<char>>& outgoing) override
  {
    if (outgoing.size() != 1)
      throw Error("Parallel::Exchange: one message per rank expected");
    return outgoing;
  }
};

// ------------------------------------------------------------------ in-process ranks

/** What the threads of RunInProcessRanks share: a slot per rank and a reusable barrier. */
struct Shared
{
  explicit Shared(int n)
    : Ranks(n)
    , Slots(n)
  {
  }
  int Ranks;
  std::mutex Mutex;
  std::condition_variable Changed;
  int Arrived = 0;
  unsigned long Generation = 0;
  bool Aborted = false;
  std::string Reason;
  /** Slots[r]: rank r's messages for the collective under way, one per destination. */
  std::vector<std::vector<std::vector<char>>> Slots;

  void Wait()
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    if (this->Aborted)
      throw Error(this->Reason);
    const unsigned long generation = this->Generation;
    if (++this->Arrived == this->Ranks)
    {
      this->Arrived = 0;
      ++this->Generation;
      this->Changed.notify_all();
      return;
    }
    this->Changed.wait(lock, [&] { return this->Generation != generation || this->Aborted; });
    if (this->Generation == generation)
      throw Error(this->Reason);
  }

  /** No collective can complete any more: a rank failed, or one returned while others wait
   * (collectives out of step). Waiting ranks throw Error(reason) instead of hanging. */
  void Abort(const char* reason)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (!this->Aborted)
      this->Reason = reason;
    this->Aborted = true;
    this->Changed.notify_all();
  }
};

class InProcess final : public Parallel
{
public:
  InProcess(std::shared_ptr<Shared> shared, int rank)
    : S(std::move(shared))
    , Me(rank)
  {
  }
  int Rank() const override { return this->Me; }
  int Size() const override { return this->S->Ranks; }

  std::vector<std::vector<char>> Exchange(const std::vector<std::vector<char>>& outgoing) override
  {
    if (static_cast<int>(outgoing.size()) != this->S->Ranks)
      throw Error("Parallel::Exchange: one message per rank expected");
    // deposit, wait for all, read what is addressed to this rank, wait until all have read
    this->S->Slots[this->Me] = outgoing;
    this->S->Wait();
    std::vector<std::vector<char>> incoming(this->S->Ranks);
    for (int r = 0; r < this->S->Ranks; ++r)
      incoming[r] = this->S->Slots[r][this->Me];
    this->S->Wait();
    return incoming;
  }

  std::vector<std::vector<char>> AllGather(const std::vector<char>& mine) override
  {
    return this->Exchange(std::vector<std::vector<char>>(this->S->Ranks, mine));
  }

  void Broadcast(std::vector<char>& bytes, int root) override
  {
    std::vector<std::vector<char>> all =
      this->AllGather(this->Me == root ? bytes : std::vector<char>());
    bytes = all.at(root);
  }

  void Reduce(double* values, std::size_t count, ReduceOp op) override
  {
    std::vector<char> mine(count * sizeof(double));
    if (count)
      std::memcpy(mine.data(), values, mine.size());
    std::vector<std::vector<char>> all = this->AllGather(mine);
    // in rank order on every rank: the same result everywhere
    for (std::size_t i = 0; i < count; ++i)
    {
      double acc = 0.0;
      for (int r = 0; r < this->S->Ranks; ++r)
      {
        if (all[r].size() != mine.size())
          throw Error("Parallel::Reduce: ranks reduce different counts");
        double v;
        std::memcpy(&v, all[r].data() + i * sizeof(double), sizeof(double));
        if (r == 0)
          acc = v;
        else if (op == ReduceOp::Sum)
          acc += v;
        else if (op == ReduceOp::Min)
          acc = std::min(acc, v);
        else
          acc = std::max(acc, v);
      }
      values[i] = acc;
    }
  }

private:
  std::shared_ptr<Shared> S;
  int Me;
};

} // namespace

Parallel& SerialParallel()
{
  static Serial serial;
  return serial;
}

namespace
{
const char* const OtherFailed = "another in-process rank failed";
const char* const LeftEarly = "an in-process rank returned while this one waits in a collective";
}

void RunInProcessRanks(int ranks, const std::function<void(Parallel&)>& body)
{
  if (ranks < 1)
    throw Error("RunInProcessRanks: at least one rank");
  auto shared = std::make_shared<Shared>(ranks);
  std::vector<std::exception_ptr> errors(ranks);
  std::vector<std::thread> threads;
  threads.reserve(ranks);
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      InProcess p(shared, r);
      try
      {
        body(p);
        shared->Abort(LeftEarly);
      }
      catch (...)
      {
        errors[r] = std::current_exception();
        shared->Abort(OtherFailed);
      }
    });
  for (std::thread& t : threads)
    t.join();
  // the first failure that is not a consequence of another rank's
  std::exception_ptr first;
  for (const std::exception_ptr& e : errors)
  {
    if (!e)
      continue;
    try
    {
      std::rethrow_exception(e);
    }
    catch (const Error& err)
    {
      if (std::string(err.what()) == OtherFailed)
      {
        if (!first)
          first = e;
        continue;
      }
      std::rethrow_exception(e);
    }
    catch (...)
    {
      std::rethrow_exception(e);
    }
  }
  if (first)
    std::rethrow_exception(first);
}

} // namespace schlieren
