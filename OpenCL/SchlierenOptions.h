// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SchlierenOptions.h
 * @brief The engine's runtime options: every environment variable it reads, read once.
 *
 * The options are read from the environment on first use (GetRuntimeOptions) and then kept for
 * the life of the process; nothing else in the engine calls getenv. An application (a filter, a
 * test, the benchmark) may replace them with SetRuntimeOptions. Per-trace settings override them:
 * TraceSettings::DeviceName overrides OpenCLDevice and TraceSettings::Threads overrides
 * CpuThreads (the filters' properties set those).
 */
#ifndef SchlierenOptions_h
#define SchlierenOptions_h

#include <cstdint>
#include <string>

namespace schlieren
{

struct RuntimeOptions
{
  /// SCHLIEREN_OPENCL_DEVICE: a substring of the OpenCL device's name; empty: the first GPU, else
  /// the first device
  std::string OpenCLDevice;
  /// SCHLIEREN_CPU_THREADS: threads of the CPU backend; 0: every hardware thread
  int CpuThreads = 0;
  /// SCHLIEREN_CL_USE_HOST_PTR (0 or 1): a CPU OpenCL device traces the caller's field in place
  /// where it is aligned (1), or always copies it (0, for measuring the copy's memory)
  bool UseHostPtr = true;
  /// SCHLIEREN_CL_SPECIALISE (0 or 1): build a program per integrator, octree, reconstruction and
  /// body setting (1), or one generic program (0)
  bool Specialise = true;
  /// SCHLIEREN_CL_OPTIONS: extra OpenCL build options for the kernels (e.g. -cl-mad-enable)
  std::string BuildOptions;
  /// SCHLIEREN_CL_MAX_ALLOC: bytes per device buffer at most (the field is split into slabs over
  /// it); 0: the device's own limit
  std::uint64_t MaxAlloc = 0;
  /// SCHLIEREN_CL_LOCKSTEP: 1 the lock-step kernel, 0 the per-item kernel; -1 (unset): lock step
  /// on CPU devices, per item elsewhere
  int Lockstep = -1;
  /// SCHLIEREN_CL_LOCAL_SIZE: work-items per work-group of the per-item kernels (rays, points,
  /// pieces), the global size rounded up to it; 0: the driver's choice; -1 (unset): 16 on CPU
  /// devices (PoCL compiles a work-group function per local size it meets, 0.6-0.75 s each), the
  /// driver's choice elsewhere
  int LocalSize = -1;
  /// SCHLIEREN_FIELD_BRICKS (0 or 1): the packed field in bricks of 4^3 points (faster oblique
  /// views) or in its linear layout; both give the same images, bit for bit. -1 (unset): a
  /// TraceSession packs its field in bricks where they pay (PackInBricks, docs/PERFORMANCE.md), a
  /// linear Volume given to Trace is read as it is. 1: bricks wherever they fit, a linear Volume
  /// copied into bricks beside it (16 more bytes a point, kept for the last stamped volume).
  /// 0: linear everywhere.
  int Bricks = -1;
  /// SCHLIEREN_PREFETCH (0 or 1): each step of a ray asks the cache for the lines of its next
  /// sample on the CPU path and on CPU OpenCL devices (1), or not (0); the images are the same,
  /// bit for bit. -1 (unset): where it pays (PrefetchPays: large fields, oblique views)
  int Prefetch = -1;
  /// SCHLIEREN_MEMORY_LIMIT: host bytes the engine assumes it may use at most; 0: what the
  /// machine has available
  std::uint64_t MemoryLimit = 0;
  /// SCHLIEREN_MPI_TIMEOUT: seconds a rank waits at one of the filters' collectives for the other
  /// ranks to reach it before every rank there stops with an error naming the missing ranks (a
  /// rank whose upstream failed never comes); more than 0
  double MpiTimeout = 120.0;
  /// SCHLIEREN_MPI_ABORT: 1: where a rank gives up waiting at a collective (the timeout above, or
  /// ranks at different collectives), it says its error and aborts the MPI job (MPI_Abort), so
  /// that a run whose other ranks are held in some other collective ends instead of spinning
  /// there for ever; 0 (the default): the error, and the run goes on (a script can bring its
  /// ranks in step again)
  bool MpiAbort = false;
  /// SCHLIEREN_COARSE (0 or 1): Integrator Auto may trace a large smooth field from a copy at 2
  /// or 4 times its spacing where the copy is certified within a quarter of the tolerance at
  /// every point (1, the default), or always the field itself (0)
  bool CoarseCopies = true;

  /** The options as the environment sets them (unset variables: the defaults above). Throws
   * schlieren::Error naming the variable where a value cannot be read. */
  static RuntimeOptions FromEnvironment();
  /** The OpenCL options that decide a device copy and its kernels: equal keys, same tracer. */
  std::string OpenCLKey() const;
};

/** The options in force: the environment's, read on the first call, or those last set. */
RuntimeOptions GetRuntimeOptions();

/** Replaces the options for the rest of the process; the next trace uses them. */
void SetRuntimeOptions(const RuntimeOptions& options);

/** Goes back to the environment's options (read again now). */
void ResetRuntimeOptions();

} // namespace schlieren

#endif
