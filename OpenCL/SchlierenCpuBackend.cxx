// SPDX-License-Identifier: BSD-3-Clause
// The CPU backend: the C++ build of SchlierenPhysics.h on std::thread.
#include "SchlierenEngineInternal.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <thread>
#include <vector>

namespace schlieren
{

// Threads of the CPU backend: the trace's Threads, else the options' (SCHLIEREN_CPU_THREADS: for
// instance 1 per MPI rank, or to measure scaling), else every hardware thread.
unsigned CpuThreads(int requested)
{
  if (requested > 0)
    return static_cast<unsigned>(requested);
  const int n = GetRuntimeOptions().CpuThreads;
  if (n > 0)
    return static_cast<unsigned>(n);
  return std::max(1u, std::thread::hardware_concurrency());
}

// The CPU backend: the C++ build of SchlierenPhysics.h on std::thread.
void TraceChunkCPU(const float* field, const unsigned char* levels, const sch_params& P,
  std::size_t first, std::size_t count, float* out, unsigned threadCount)
{
  const unsigned nt = threadCount > 0 ? threadCount : CpuThreads();
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
  std::vector<std::thread> threads;
  for (unsigned t = 0; t + 1 < nt; ++t)
    threads.emplace_back(worker);
  worker();
  for (auto& th : threads)
    th.join();
}

} // namespace schlieren
