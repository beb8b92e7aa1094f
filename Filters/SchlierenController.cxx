// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenController.h"

#include "SchlierenEngine.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <numeric>

namespace schlieren
{

namespace
{
/** The tag of the plugin's point-to-point messages (Exchange). */
const int ExchangeTag = 51207;
}

ControllerParallel::ControllerParallel(vtkMultiProcessController* controller)
{
  if (!controller)
    controller = vtkMultiProcessController::GetGlobalController();
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    this->Controller = controller;
    this->Me = controller->GetLocalProcessId();
    this->Ranks = controller->GetNumberOfProcesses();
  }
  else
    this->Controller = nullptr;
}

void ControllerParallel::Reduce(double* values, std::size_t count, ReduceOp op)
{
  if (!this->Controller || count == 0)
    return;
  std::vector<double> mine(values, values + count);
  const int vop = op == ReduceOp::Sum ? vtkCommunicator::SUM_OP
                                      : (op == ReduceOp::Min ? vtkCommunicator::MIN_OP
                                                             : vtkCommunicator::MAX_OP);
  if (!this->Controller->AllReduce(mine.data(), values, static_cast<vtkIdType>(count), vop))
    throw Error("MPI: an all-reduce across ranks failed");
}

void ControllerParallel::Broadcast(std::vector<char>& bytes, int root)
{
  if (!this->Controller)
    return;
  vtkIdType length = static_cast<vtkIdType>(bytes.size());
  this->Controller->Broadcast(&length, 1, root);
  bytes.resize(static_cast<std::size_t>(length));
  if (length > 0)
    this->Controller->Broadcast(bytes.data(), length, root);
}

std::vector<std::vector<char>> ControllerParallel::AllGather(const std::vector<char>& mine)
{
  if (!this->Controller)
    return { mine };
  vtkIdType length = static_cast<vtkIdType>(mine.size());
  std::vector<vtkIdType> lengths(this->Ranks), offsets(this->Ranks, 0);
  this->Controller->AllGather(&length, lengths.data(), 1);
  for (int r = 1; r < this->Ranks; ++r)
    offsets[r] = offsets[r - 1] + lengths[r - 1];
  const vtkIdType total = offsets.back() + lengths.back();
  std::vector<char> all(static_cast<std::size_t>(std::max<vtkIdType>(total, 1)));
  // AllGatherV does not take a null buffer: a byte of room where every rank sends nothing
  std::vector<char> send = mine.empty() ? std::vector<char>(1) : mine;
  this->Controller->AllGatherV(
    send.data(), all.data(), length, lengths.data(), offsets.data());
  std::vector<std::vector<char>> out(this->Ranks);
  for (int r = 0; r < this->Ranks; ++r)
    out[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + lengths[r]);
  return out;
}

std::vector<std::vector<char>> ControllerParallel::Exchange(
  const std::vector<std::vector<char>>& outgoing)
{
  if (static_cast<int>(outgoing.size()) != this->Ranks)
    throw Error("Parallel::Exchange: one message per rank expected");
  if (!this->Controller)
    return outgoing;
  const int n = this->Ranks;
  // every rank learns every message's length, so that no empty message is sent
  std::vector<vtkIdType> mine(n), lengths(static_cast<std::size_t>(n) * n);
  for (int r = 0; r < n; ++r)
    mine[r] = static_cast<vtkIdType>(outgoing[r].size());
  this->Controller->AllGather(mine.data(), lengths.data(), n);
  std::vector<std::vector<char>> incoming(n);
  incoming[this->Me] = outgoing[this->Me];
  // round k: send to me + k, receive from me - k. A rank whose destination wraps around below it
  // receives first; every other rank sends first. Each round's sends form cycles that wrap
  // around, and every cycle holds a rank that receives first, so blocking sends cannot deadlock.
  for (int k = 1; k < n; ++k)
  {
    const int to = (this->Me + k) % n, from = (this->Me - k + n) % n;
    const vtkIdType sendLength = mine[to];
    const vtkIdType recvLength = lengths[static_cast<std::size_t>(from) * n + this->Me];
    incoming[from].resize(static_cast<std::size_t>(recvLength));
    auto send = [&] {
      if (sendLength > 0 &&
        !this->Controller->Send(outgoing[to].data(), sendLength, to, ExchangeTag))
        throw Error("MPI: sending to rank " + std::to_string(to) + " failed");
    };
    auto receive = [&] {
      if (recvLength > 0 &&
        !this->Controller->Receive(incoming[from].data(), recvLength, from, ExchangeTag))
        throw Error("MPI: receiving from rank " + std::to_string(from) + " failed");
    };
    if (to < this->Me)
    {
      receive();
      send();
    }
    else
    {
      send();
      receive();
    }
  }
  return incoming;
}

} // namespace schlieren
