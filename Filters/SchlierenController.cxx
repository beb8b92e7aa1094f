// SPDX-License-Identifier: BSD-3-Clause
#include "SchlierenController.h"

#include "SchlierenEngine.h"
#include "SchlierenOptions.h"

#include "vtkAlgorithm.h"
#include "vtkCommunicator.h"
#include "vtkDataObject.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVCompositeDataPipeline.h"
#if VTK_MODULE_ENABLE_VTK_ParallelMPI
#include "vtkMPI.h"
#include "vtkMPICommunicator.h"
#endif
#include "vtkOutputWindow.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <sstream>
#include <thread>

namespace schlieren
{

namespace
{
/** The tag of the plugin's point-to-point messages (Exchange). */
const int ExchangeTag = 51207;

/** "rank 2", "ranks 0, 2". */
std::string RankList(const std::vector<int>& ranks)
{
  std::string s = ranks.size() == 1 ? "rank " : "ranks ";
  for (std::size_t i = 0; i < ranks.size(); ++i)
    s += (i ? ", " : "") + std::to_string(ranks[i]);
  return s;
}
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

ControllerParallel::ControllerParallel(const char* who, vtkMultiProcessController* controller)
  : ControllerParallel(controller)
{
  this->Who = who;
}

// ------------------------------------------------------------------ the guard
//
// Before each collective, every rank tells rank 0 (the coordinator) that it is there (Arrived)
// and waits for its answer: Go once all ranks are there, Abort (with the error to report) where
// some are not within the timeout. Only point-to-point messages that never block are used, so
// that a rank that never comes leaves no collective half done: nothing but these small messages
// is outstanding, and each carries the sender's own count of arrivals (its epoch) so that an
// answer to an earlier, failed arrival is told from the answer to this one. A rank that hears
// nothing gives up (Withdrawn) and then waits a little more for the coordinator's last word; the
// coordinator drops an arrival withdrawn before it was answered.
#if VTK_MODULE_ENABLE_VTK_ParallelMPI
namespace
{
const int GuardTag = 51208;
/** The coordinator's answer to a withdrawal. */
const char* const WithdrawnReply = "withdrawn";

enum Kind : std::int64_t
{
  Arrived = 1,
  Withdrawn = 2,
  Go = 3,
  Abort = 4
};

/** One guard message: fixed size, the step's name or the error to report in Text. */
struct Message
{
  std::int64_t Type = 0;
  std::int64_t Epoch = 0;
  char Text[496] = {};

  void SetText(const std::string& s)
  {
    const std::size_t n = std::min(s.size(), sizeof(this->Text) - 1);
    std::copy(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(n), this->Text);
    this->Text[n] = '\0';
  }
};

/** A send in flight, kept until MPI is done with its buffer. */
struct Sending
{
  Message Buffer;
  vtkMPICommunicator::Request Request;
};

/** What one process knows of the guard on one communicator. */
struct GuardState
{
  std::int64_t Epoch = 0;                  // this rank's arrivals so far
  std::vector<std::int64_t> Live;          // coordinator: each rank's unanswered arrival, or 0
  std::vector<std::string> LiveStep;       // ... and the step it arrived at
  std::list<std::unique_ptr<Sending>> Out; // sends in flight
  bool Failed = false;                     // the last step this rank reached was given up
};

std::mutex GuardMutex;
std::map<vtkMPICommunicator*, GuardState> Guards;

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/** A pause between polls: short at first (the other ranks are usually there), then longer. */
void Pause(int& polls)
{
  ++polls;
  if (polls < 200)
    std::this_thread::yield();
  else
    std::this_thread::sleep_for(std::chrono::microseconds(polls < 2000 ? 100 : 2000));
}

std::string Seconds(double s)
{
  std::ostringstream o;
  o << s << " s";
  return o.str();
}

class Guard
{
public:
  Guard(vtkMPICommunicator* comm, GuardState& state, int me, int ranks)
    : Comm(comm)
    , State(state)
    , Me(me)
    , Ranks(ranks)
  {
    if (this->State.Live.size() != static_cast<std::size_t>(ranks))
    {
      this->State.Live.assign(ranks, 0);
      this->State.LiveStep.assign(ranks, std::string());
    }
    // forget the sends MPI is done with
    for (auto it = this->State.Out.begin(); it != this->State.Out.end();)
      it = (*it)->Request.Test() ? this->State.Out.erase(it) : std::next(it);
  }

  void Send(int to, Kind type, std::int64_t epoch, const std::string& text)
  {
    auto s = std::make_unique<Sending>();
    s->Buffer.Type = type;
    s->Buffer.Epoch = epoch;
    s->Buffer.SetText(text);
    if (!this->Comm->NoBlockSend(reinterpret_cast<const char*>(&s->Buffer),
          static_cast<int>(sizeof(Message)), to, GuardTag, s->Request))
      throw schlieren::Error("MPI: the collective guard could not send to rank " +
        std::to_string(to));
    this->State.Out.push_back(std::move(s));
  }

  /** The next guard message from `from`, where one has come. */
  bool Poll(int from, Message& m)
  {
    int flag = 0, source = 0;
    if (!this->Comm->Iprobe(from, GuardTag, &flag, &source) || !flag)
      return false;
    if (!this->Comm->Receive(reinterpret_cast<char*>(&m), static_cast<vtkIdType>(sizeof(Message)),
          from, GuardTag))
      throw schlieren::Error("MPI: the collective guard could not receive from rank " +
        std::to_string(from));
    m.Text[sizeof(m.Text) - 1] = '\0';
    return true;
  }

  /** A rank but the coordinator: arrive, and wait for Go (return) or Abort (throw). */
  void Follow(const std::string& step, double timeout)
  {
    const std::int64_t epoch = ++this->State.Epoch;
    this->Send(0, Arrived, epoch, step);
    // the coordinator answers within `timeout` of its own arrival; a rank that hears nothing a
    // while after that gives up, then waits as long again for the coordinator's last word
    const double grace = std::min(10.0, std::max(1.0, 0.25 * timeout));
    const Clock::time_point t0 = Clock::now();
    bool withdrawn = false;
    int polls = 0;
    auto gaveUp = [&] {
      return schlieren::Error("rank 0 did not reach " + step + " within " + Seconds(timeout) +
        ": its upstream probably failed (see its error). SCHLIEREN_MPI_TIMEOUT sets the wait.");
    };
    for (;;)
    {
      Message m;
      while (this->Poll(0, m))
      {
        if (m.Epoch != epoch)
          continue; // the answer to an earlier arrival, given up
        if (m.Type == Go)
          return;
        if (m.Type == Abort)
        {
          if (std::string(m.Text) == WithdrawnReply)
            throw gaveUp(); // rank 0 was elsewhere when it read our withdrawal
          throw schlieren::Error(m.Text);
        }
      }
      const double waited = Since(t0);
      if (!withdrawn && waited > timeout + grace)
      {
        this->Send(0, Withdrawn, epoch, step);
        withdrawn = true;
      }
      else if (withdrawn && waited > timeout + 2 * grace)
        throw gaveUp();
      Pause(polls);
    }
  }

  /** Rank 0: gather the arrivals; Go to all once every rank is there at the same step, else
   * Abort (and throw) after `timeout`. */
  void Coordinate(const std::string& step, double timeout)
  {
    ++this->State.Epoch;
    std::vector<std::int64_t>& live = this->State.Live;
    std::vector<std::string>& at = this->State.LiveStep;
    const Clock::time_point t0 = Clock::now();
    int polls = 0;
    bool first = true;
    auto abortAll = [&](const std::string& why) {
      for (int r = 1; r < this->Ranks; ++r)
        if (live[r])
        {
          this->Send(r, Abort, live[r], why);
          live[r] = 0;
        }
      throw schlieren::Error(why);
    };
    for (;;)
    {
      for (int r = 1; r < this->Ranks; ++r)
      {
        Message m;
        while (this->Poll(r, m))
        {
          if (m.Type == Arrived)
          {
            live[r] = m.Epoch;
            at[r] = m.Text;
          }
          else if (m.Type == Withdrawn)
          {
            this->Send(r, Abort, m.Epoch, WithdrawnReply);
            if (live[r] == m.Epoch)
            {
              live[r] = 0;
              // given up while this round waited: it will not come back to this step
              if (!first)
                abortAll("rank " + std::to_string(r) + " stopped waiting at " + m.Text +
                  " before rank 0 reached " + step + ": the ranks are out of step (an upstream "
                  "failure or a rank slower than SCHLIEREN_MPI_TIMEOUT = " + Seconds(timeout) +
                  ")");
            }
          }
        }
      }
      first = false;
      std::vector<int> missing;
      for (int r = 1; r < this->Ranks; ++r)
        if (!live[r])
          missing.push_back(r);
      if (missing.empty())
      {
        for (int r = 1; r < this->Ranks; ++r)
          if (at[r] != step)
            abortAll("the ranks are at different collectives: rank 0 at " + step + ", rank " +
              std::to_string(r) + " at " + at[r] +
              " (an upstream failure on some ranks put them out of step)");
        for (int r = 1; r < this->Ranks; ++r)
        {
          this->Send(r, Go, live[r], step);
          live[r] = 0;
        }
        return;
      }
      if (Since(t0) > timeout)
        abortAll(RankList(missing) + " did not reach " + step + " within " + Seconds(timeout) +
          (missing.size() == 1 ? ": its upstream probably failed (see its error)"
                               : ": their upstream probably failed (see their errors)") +
          ". SCHLIEREN_MPI_TIMEOUT sets the wait.");
      Pause(polls);
    }
  }

private:
  vtkMPICommunicator* Comm;
  GuardState& State;
  int Me, Ranks;
};
} // namespace
#endif

void ControllerParallel::Arrive(const char* what)
{
  const int number = ++this->Collectives;
  this->ArriveAt(this->Who + "'s collective " + std::to_string(number) + " (" + what + ")");
}

void ControllerParallel::ArriveAt(const std::string& step)
{
#if VTK_MODULE_ENABLE_VTK_ParallelMPI
  auto* comm = vtkMPICommunicator::SafeDownCast(this->Controller->GetCommunicator());
  if (!comm)
    return; // not MPI (a socket or threaded controller): no guard
  const RuntimeOptions& options = GetRuntimeOptions();
  std::lock_guard<std::mutex> lock(GuardMutex);
  GuardState& state = Guards[comm];
  Guard guard(comm, state, this->Me, this->Ranks);
  state.Failed = true;
  try
  {
    if (this->Me == 0)
      guard.Coordinate(step, options.MpiTimeout);
    else
      guard.Follow(step, options.MpiTimeout);
  }
  catch (const Error& e)
  {
    if (options.MpiAbort)
    {
      // the ranks are out of step: end the job rather than meet a rank held elsewhere
      vtkOutputWindowDisplayErrorText(("Schlieren, rank " + std::to_string(this->Me) + ": " +
        e.what() + " SCHLIEREN_MPI_ABORT=1: the MPI job is aborted.\n")
                                        .c_str());
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    throw;
  }
  state.Failed = false;
#else
  (void)step;
#endif
}

void ControllerParallel::Reduce(double* values, std::size_t count, ReduceOp op)
{
  if (!this->Controller || count == 0)
    return;
  this->Arrive("an all-reduce");
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
  this->Arrive("a broadcast");
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
  this->Arrive("an all-gather");
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
  this->Arrive("an exchange");
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

bool ControllerParallel::GaveUp() const
{
#if VTK_MODULE_ENABLE_VTK_ParallelMPI
  auto* comm = this->Controller
    ? vtkMPICommunicator::SafeDownCast(this->Controller->GetCommunicator())
    : nullptr;
  std::lock_guard<std::mutex> lock(GuardMutex);
  return comm && Guards.count(comm) && Guards[comm].Failed;
#else
  return false;
#endif
}

std::vector<int> ControllerParallel::FailedRanks(bool ok, const std::string& step)
{
  std::vector<int> failed;
  if (!this->Controller)
  {
    if (!ok)
      failed.push_back(0);
    return failed;
  }
  this->ArriveAt(step);
  // every rank is here (the guard): one byte each
  char mine = ok ? 1 : 0;
  std::vector<char> all(static_cast<std::size_t>(this->Ranks));
  if (!this->Controller->AllGather(&mine, all.data(), 1))
    throw Error("MPI: an all-gather across ranks failed");
  for (int r = 0; r < this->Ranks; ++r)
    if (!all[r])
      failed.push_back(r);
  return failed;
}

// ------------------------------------------------------------------ the executive

namespace
{
/** ParaView's executive; under MPI the ranks agree on their inputs' passes (SchlierenController.h). */
class AgreeingExecutive : public vtkPVCompositeDataPipeline
{
public:
  static AgreeingExecutive* New();
  vtkTypeMacro(AgreeingExecutive, vtkPVCompositeDataPipeline);

protected:
  AgreeingExecutive() = default;
  ~AgreeingExecutive() override = default;

  using vtkPVCompositeDataPipeline::ForwardUpstream;
  int ForwardUpstream(vtkInformation* request) override
  {
    const int result = this->Superclass::ForwardUpstream(request);
    const char* pass = request->Has(vtkDemandDrivenPipeline::REQUEST_DATA())
      ? "its data"
      : request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION())
      ? "its information"
      : request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()) ? "its data object" : nullptr;
    vtkAlgorithm* algorithm = this->GetAlgorithm();
    if (!pass || !algorithm)
      return result;
    std::string who = algorithm->GetClassName();
    if (who.compare(0, 3, "vtk") == 0)
      who.erase(0, 3);
    ControllerParallel parallel(who.c_str());
    // a rank that gave up waiting for another (the guard) failed upstream on every rank that
    // came, and they all gave up: no second wait for the rank that did not come
    if (parallel.Size() <= 1 || (!result && parallel.GaveUp()))
      return result;
    std::vector<int> failed;
    std::string error;
    try
    {
      failed = parallel.FailedRanks(result != 0, who + "'s inputs (" + pass + ")");
      if (!failed.empty() && result)
        error = "the input of " + who + " failed on " + RankList(failed) + " (" +
          (failed.size() == 1 ? "its" : "their") + " upstream's error is in " +
          (failed.size() == 1 ? "that rank's" : "those ranks'") + " output): " + who +
          " runs on no rank";
    }
    catch (const std::exception& e)
    {
      error = e.what(); // the guard: some rank did not come
    }
    if (!error.empty())
      vtkErrorWithObjectMacro(algorithm, << error);
    if (error.empty() && failed.empty())
      return result;
    if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
      for (int port = 0; port < algorithm->GetNumberOfOutputPorts(); ++port)
        if (vtkDataObject* out = algorithm->GetOutputDataObject(port))
          out->Initialize(); // no earlier update's output left to pass for this one's
    return 0;
  }

private:
  AgreeingExecutive(const AgreeingExecutive&) = delete;
  void operator=(const AgreeingExecutive&) = delete;
};
vtkStandardNewMacro(AgreeingExecutive);
}

vtkExecutive* NewAgreeingExecutive()
{
  return AgreeingExecutive::New();
}

} // namespace schlieren
