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
 */
#ifndef SchlierenController_h
#define SchlierenController_h

#include "SchlierenParallel.h"

#include <string>

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

private:
  /** Returns once every rank has reached this collective (`what`); throws Error on every rank
   * that reached it where some rank does not within the timeout. */
  void Arrive(const char* what);

  vtkMultiProcessController* Controller; // null where serial
  std::string Who = "Schlieren";
  int Collectives = 0; // collectives this object entered, naming the next one
  int Me = 0;
  int Ranks = 1;
};

} // namespace schlieren

#endif
