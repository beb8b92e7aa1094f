// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenParallel.h
 * @brief The one interface to work spread over ranks (MPI processes under ParaView).
 *
 * The engine and the filters never call MPI: they call a Parallel. The filters implement it with
 * vtkMultiProcessController (Filters/SchlierenController); the engine's tests with N in-process
 * ranks on threads (RunInProcessRanks), so that distributed code is tested without MPI. Every
 * member is collective unless it says otherwise: all ranks call it, in the same order, with
 * arguments of the same shape.
 */
#ifndef SchlierenParallel_h
#define SchlierenParallel_h

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace schlieren
{

enum class ReduceOp
{
  Sum,
  Min,
  Max
};

class Parallel
{
public:
  virtual ~Parallel() = default;

  /** This rank, in [0, Size()). Not collective. */
  virtual int Rank() const = 0;
  /** The number of ranks (1: serial). Not collective. */
  virtual int Size() const = 0;

  /** Combines `count` values element-wise over the ranks, in place; every rank gets the same
   * result (sums in rank order where the implementation allows: see the implementation). */
  virtual void Reduce(double* values, std::size_t count, ReduceOp op) = 0;
  /** The root's bytes to every rank (resized on the others). */
  virtual void Broadcast(std::vector<char>& bytes, int root) = 0;
  /** Every rank's bytes, in rank order, on every rank. */
  virtual std::vector<std::vector<char>> AllGather(const std::vector<char>& mine) = 0;
  /**
   * All-to-all: outgoing[r] is what this rank sends rank r (outgoing.size() == Size(); an empty
   * message where there is nothing; outgoing[Rank()] comes back to this rank). Returns incoming,
   * incoming[r] being what rank r sent this rank.
   */
  virtual std::vector<std::vector<char>> Exchange(
    const std::vector<std::vector<char>>& outgoing) = 0;

  // Conveniences on the members above (collective as they are).
  void Sum(double* values, std::size_t count) { this->Reduce(values, count, ReduceOp::Sum); }
  void Max(double* values, std::size_t count) { this->Reduce(values, count, ReduceOp::Max); }
  void Min(double* values, std::size_t count) { this->Reduce(values, count, ReduceOp::Min); }
  double Sum(double v);
  double Max(double v);
  double Min(double v);
  /** True where `ok` holds on every rank. */
  bool AllOk(bool ok);
  /**
   * Agreement after a step that may fail on some ranks only: empty where no rank failed, else the
   * same message on every rank: the lowest failing rank's own message on that rank, and
   * "another rank (r) failed: <its message>" on the others.
   */
  std::string Failure(const std::string& mine);
  /** Every rank's string, in rank order. */
  std::vector<std::string> AllGatherStrings(const std::string& mine);
  /** The root's string on every rank. */
  std::string BroadcastString(const std::string& s, int root);
};

/** One rank: every collective returns at once with this rank's data. */
Parallel& SerialParallel();

/**
 * Runs body on `ranks` threads at once, each with its own Parallel of `ranks` in-process ranks that
 * really exchange data (for tests of distributed code without MPI). Returns when all are done.
 * If a rank throws, the others' next collective throws Error("another in-process rank failed")
 * (never a hang), and the first rank's exception is rethrown here.
 */
void RunInProcessRanks(int ranks, const std::function<void(Parallel&)>& body);

} // namespace schlieren

#endif
