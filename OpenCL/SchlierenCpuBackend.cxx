// SPDX-License-Identifier: BSD-3-Clause
// The CPU backend: the C++ build of SchlierenPhysics.h on std::thread.
#include "SchlierenEngineInternal.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <new>
#include <system_error>
#include <thread>
#include <vector>

namespace schlieren
{

// Threads of the CPU backend: the trace's Threads, else the options' (SCHLIEREN_CPU_THREADS: for
// instance 1 per MPI rank, or to measure scaling), else every hardware thread.
unsigned CpuThreads(int requested)
{
  unsigned n = std::max(1u, std::thread::hardware_concurrency());
  if (requested > 0)
    n = static_cast<unsigned>(requested);
  else if (GetRuntimeOptions().CpuThreads > 0)
    n = static_cast<unsigned>(GetRuntimeOptions().CpuThreads);
  return std::min(n, MaxCpuThreads());
}

unsigned MaxCpuThreads()
{
  return 16 * std::max(1u, std::thread::hardware_concurrency());
}

void RunOnThreads(unsigned n, const std::function<void(unsigned)>& work)
{
  n = std::max(1u, n);
  std::vector<std::exception_ptr> errors(n);
  auto guarded = [&](unsigned t) {
    try
    {
      work(t);
    }
    catch (...)
    {
      errors[t] = std::current_exception();
    }
  };
  // a std::thread that failed to start leaves the earlier ones joinable: they are joined below,
  // never destroyed joinable (that is std::terminate, "terminate called without an active
  // exception")
  std::vector<std::thread> threads;
  unsigned started = 1;
  try
  {
    threads.reserve(n - 1);
    for (; started < n; ++started)
      threads.emplace_back(guarded, started);
  }
  catch (const std::system_error&)
  {
  }
  catch (const std::bad_alloc&)
  {
  }
  guarded(0);
  for (unsigned t = started; t < n; ++t)
    guarded(t);
  for (auto& th : threads)
    th.join();
  for (const std::exception_ptr& e : errors)
    if (e)
      std::rethrow_exception(e);
}

// The CPU backend: the C++ build of SchlierenPhysics.h on std::thread.
void TraceChunkCPU(const float* field, const unsigned char* levels, const sch_params& P,
  std::size_t first, std::size_t count, float* out, unsigned threadCount)
{
  const unsigned nt = threadCount > 0 ? std::min(threadCount, MaxCpuThreads()) : CpuThreads();
  std::atomic<std::size_t> next(0);
  // blocks of 256 rays, smaller where a chunk has fewer rays than that for each thread
  const std::size_t block = std::max<std::size_t>(1, std::min<std::size_t>(256, (count + nt - 1) / nt));
  auto worker = [&]() {
    // each thread reads its own copy of the parameters: the caller's sits on the main thread's
    // stack, next to what that thread writes every step, and the other thread's reads of it
    // missed the cache on every step (false sharing)
    const sch_params Pw = P;
    for (;;)
    {
      const std::size_t b0 = next.fetch_add(block);
      if (b0 >= count)
        break;
      const std::size_t b1 = std::min(count, b0 + block);
      for (std::size_t k = b0; k < b1; k += SCH_PACKET)
      {
        const int pix = static_cast<int>(Pw.rayOffset + (first + k) * Pw.rayStride);
        const int n = static_cast<int>(std::min<std::size_t>(SCH_PACKET, b1 - k));
        sch_trace_packet(field, levels, &Pw, pix, Pw.rayStride, n, out + k * SCH_RECORD);
      }
    }
  };
  // no more threads than blocks of rays: the others would find no work
  const std::size_t blocks = (count + block - 1) / block;
  RunOnThreads(static_cast<unsigned>(std::min<std::size_t>(nt, blocks)), [&](unsigned) { worker(); });
}

} // namespace schlieren
