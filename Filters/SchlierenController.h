// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenController.h
 * @brief The engine's Parallel (OpenCL/SchlierenParallel.h) on VTK's vtkMultiProcessController.
 *
 * The one place in the filters where ranks talk to each other: every MPI collective of the plugin
 * goes through schlieren::Parallel, and this is its implementation under ParaView (pvbatch,
 * pvserver, vtkMPIController). Without a controller, or with one process, it is the serial one.
 *
 * Under MPI every collective is entered only after an agreement that every rank has reached it
 * (the guard: docs/PARALLEL.md). A rank whose upstream failed never calls the filter, so the
 * others would wait in the collective for ever; instead, after SCHLIEREN_MPI_TIMEOUT seconds
 * (RuntimeOptions::MpiTimeout) every rank that reached it throws schlieren::Error naming the
 * ranks that did not.
 *
 * A failure upstream that the pipeline sees (a reader whose file is missing on one rank, any
 * upstream request that returns failure there) is agreed on at once instead: the filters'
 * executive (NewAgreeingExecutive) has every rank say, before a filter's data object,
 * information and data passes, whether its inputs' pass succeeded, and where one rank's did not,
 * no rank runs the filter and the others report the failing ranks (docs/PARALLEL.md).
 */
#ifndef SchlierenController_h
#define SchlierenController_h

#include "SchlierenParallel.h"

#include <string>

class vtkExecutive;
class vtkMultiProcessController;

namespace schlieren
{

/** Parallel over `controller` (nullptr: the global controller); serial with one process. */
class ControllerParallel final : public Parallel
{
public:
  explicit ControllerParallel(vtkMultiProcessController* controller = nullptr);
  /** The same, `who` (the filter: "RefractiveIndex") naming the collectives in the guard's
   * errors. */
  explicit ControllerParallel(const char* who, vtkMultiProcessController* controller = nullptr);
  int Rank() const override { return this->Me; }
  int Size() const override { return this->Ranks; }
  void Reduce(double* values, std::size_t count, ReduceOp op) override;
  void Broadcast(std::vector<char>& bytes, int root) override;
  std::vector<std::vector<char>> AllGather(const std::vector<char>& mine) override;
  std::vector<std::vector<char>> Exchange(const std::vector<std::vector<char>>& outgoing) override;
  /** Every rank says whether `ok` at the step `step` (a name in the guard's errors): the ranks
   * where it is not, in order (empty: every rank is ok). Collective, under the guard. */
  std::vector<int> FailedRanks(bool ok, const std::string& step);
  /** Whether this process's last guarded step ended in the guard's error (a rank did not come,
   * or the ranks were at different steps) rather than with every rank there. */
  bool GaveUp() const;

private:
  /** Returns once every rank has reached this collective (`what`); throws Error on every rank
   * that reached it where some rank does not within the timeout. */
  void Arrive(const char* what);
  /** The same at the step named `step` in full. */
  void ArriveAt(const std::string& step);

  vtkMultiProcessController* Controller; // null where serial
  std::string Who = "Schlieren";
  int Collectives = 0; // collectives this object entered, naming the next one
  int Me = 0;
  int Ranks = 1;
};

/**
 * A new executive for the filters (their CreateDefaultExecutive): ParaView's own
 * (vtkPVCompositeDataPipeline, which ParaView keeps since it is one) that, under MPI, has every
 * rank agree whether its inputs' data object, information or data pass succeeded before the
 * filter's runs. Where it failed on some ranks, the filter runs on none: the ranks where it
 * failed stay silent (their upstream said its error), the others report "the input of
 * RefractiveIndex failed on rank 2 ...", at once rather than after the guard's timeout. With one
 * process it is ParaView's executive unchanged.
 */
vtkExecutive* NewAgreeingExecutive();

} // namespace schlieren

#endif
