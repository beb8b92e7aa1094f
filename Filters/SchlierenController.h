// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenController.h
 * @brief The engine's Parallel (OpenCL/SchlierenParallel.h) on VTK's vtkMultiProcessController.
 *
 * The one place in the filters where ranks talk to each other: every MPI collective of the plugin
 * goes through schlieren::Parallel, and this is its implementation under ParaView (pvbatch,
 * pvserver, vtkMPIController). Without a controller, or with one process, it is the serial one.
 */
#ifndef SchlierenController_h
#define SchlierenController_h

#include "SchlierenParallel.h"

class vtkMultiProcessController;

namespace schlieren
{

/** Parallel over `controller` (nullptr: the global controller); serial with one process. */
class ControllerParallel final : public Parallel
{
public:
  explicit ControllerParallel(vtkMultiProcessController* controller = nullptr);
  int Rank() const override { return this->Me; }
  int Size() const override { return this->Ranks; }
  void Reduce(double* values, std::size_t count, ReduceOp op) override;
  void Broadcast(std::vector<char>& bytes, int root) override;
  std::vector<std::vector<char>> AllGather(const std::vector<char>& mine) override;
  std::vector<std::vector<char>> Exchange(const std::vector<std::vector<char>>& outgoing) override;

private:
  vtkMultiProcessController* Controller; // null where serial
  int Me = 0;
  int Ranks = 1;
};

} // namespace schlieren

#endif
