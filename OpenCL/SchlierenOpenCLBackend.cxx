// SPDX-License-Identifier: BSD-3-Clause
// The OpenCL backend: the tracer (device buffers, slabs, kernels), the kept device volume, device queries.
#include "SchlierenEngineInternal.h"
#include "SchlierenLimits.h"
#include "SchlierenOpenCL.h"
#include "SchlierenOptions.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>

namespace schlieren
{

// The OpenCL backend for one volume on one device: the field's buffers (in slabs over the
// device's buffer limit), the cell bytes, the records buffer and the kernels built for it. Kept
// between calls for a stamped volume (see KeptTracer).
class OpenCLTracer
{
public:
  // bytes: the cell bytes (octree levels, solid points) or null; deviceName: a part of the
  // device's name, empty for the options' device
  OpenCLTracer(const Volume& volume, const unsigned char* cellBytes, std::size_t chunk, int raysPerItem,
    const RuntimeOptions& options, const std::string& deviceName, bool bricked)
    : RT(ocl::GetRuntime(deviceName))
    , Options(options)
    , RaysPerItem(raysPerItem > 0 ? raysPerItem : (RT.IsCPU ? 4 : 1))
    , Bricked(bricked)
  {
    // over one buffer's limit, the field goes in slabs along z, up to MaxSlabs buffers: slab q
    // holds planes q K .. q K + K (K cells; the shared plane keeps every cell in one slab). The
    // field is held in units along z of `unit` planes (a layer of bricks, or a plane): a slab
    // starts on a unit (K is a multiple of `unit`) and holds the units of its planes.
    const std::uint64_t maxAlloc = MaxAllocation();
    const int nz = volume.Dimensions[2];
    const BrickLayout layout(volume.Dimensions);
    const int unit = bricked ? 1 << FieldBrickShift : 1;
    const std::uint64_t unitFloats =
      bricked ? layout.LayerFloats() : std::uint64_t(volume.Dimensions[0]) * volume.Dimensions[1] * 4;
    const std::uint64_t bytes =
      (bricked ? layout.Floats() : volume.NumberOfPoints() * 4) * sizeof(float);
    SlabCells = nz - 1;
    Slabs = 1;
    std::uint64_t total = bytes;
    if (bytes > maxAlloc)
    {
      const std::int64_t cells = (std::int64_t(maxAlloc / (unitFloats * sizeof(float))) - 1) * unit;
      Slabs = cells >= 1 ? static_cast<int>((nz - 1 + cells - 1) / cells) : MaxSlabs + 1;
      SlabCells = static_cast<int>(std::max<std::int64_t>(cells, 1));
      total = bytes + std::uint64_t(Slabs - 1) * unitFloats * sizeof(float);
    }
    const std::uint64_t levelBytes = cellBytes ? volume.NumberOfPoints() : 1;
    if (Slabs > MaxSlabs || total + levelBytes > RT.GlobalMemory)
    {
      std::ostringstream msg;
      msg << "The volume needs " << total / (1 << 20) << " MiB on the OpenCL device '"
          << RT.DeviceName << "', which allows " << maxAlloc / (1 << 20) << " MiB per buffer (split "
          << "in at most " << MaxSlabs << " buffers) and " << RT.GlobalMemory / (1 << 20)
          << " MiB in all. Resample the data to fewer points, or choose Backend CPU.";
      throw Error(msg.str());
    }
    // A CPU device's buffers live in host memory: there the buffer uses the caller's field where
    // its address has the device's alignment (no second copy of the volume), else the driver
    // keeps a copy, which must fit in what the machine has left.
    cl_uint alignBits = 0;
    clGetDeviceInfo(RT.Device, CL_DEVICE_MEM_BASE_ADDR_ALIGN, sizeof(alignBits), &alignBits, nullptr);
    const std::uintptr_t align = std::max<std::uintptr_t>(alignBits / 8, 64);
    const bool shareHost = RT.IsCPU && Options.UseHostPtr;
    auto slabStart = [&](int q) {
      return volume.Field + std::uint64_t(q) * SlabCells / unit * unitFloats;
    };
    double copied = 0;
    for (int q = 0; q < Slabs; ++q)
    {
      Shared[q] = shareHost && reinterpret_cast<std::uintptr_t>(slabStart(q)) % align == 0;
      if (!Shared[q] && RT.IsCPU)
        copied += double(total) / Slabs;
    }
    if (copied > 0)
      CheckHostMemory(copied + levelBytes,
        "The OpenCL device '" + RT.DeviceName + "' keeps its copy of the volume in host memory; it",
        "Choose Backend CPU (which traces the field in place), or resample the data to fewer points.");
    try
    {
      cl_int err = CL_SUCCESS;
      for (int q = 0; q < Slabs; ++q)
      {
        const std::uint64_t first = std::uint64_t(q) * SlabCells;
        const std::uint64_t last = first + std::min<std::uint64_t>(SlabCells, nz - 1 - first);
        const std::uint64_t units = last / unit - first / unit + 1;
        const cl_mem_flags flags = CL_MEM_READ_ONLY | (Shared[q] ? CL_MEM_USE_HOST_PTR : CL_MEM_COPY_HOST_PTR);
        Fields[q] = clCreateBuffer(RT.Context, flags, units * unitFloats * sizeof(float),
          const_cast<float*>(slabStart(q)), &err);
        ocl::Check(err, "clCreateBuffer(field)");
      }
      // the cell bytes (octree levels, solid points), or one byte that no kernel reads when
      // there are none; shared like the field where aligned (they live as long as it: the
      // session's, or held with the kept tracer, see AcquireTracer's bytesOwner)
      static unsigned char none = 0;
      const bool shareBytes =
        shareHost && cellBytes && reinterpret_cast<std::uintptr_t>(cellBytes) % align == 0;
      Levels = clCreateBuffer(RT.Context,
        CL_MEM_READ_ONLY | (shareBytes ? CL_MEM_USE_HOST_PTR : CL_MEM_COPY_HOST_PTR),
        cellBytes ? volume.NumberOfPoints() : 1, const_cast<unsigned char*>(cellBytes ? cellBytes : &none), &err);
      ocl::Check(err, "clCreateBuffer(levels)");
      EnsureOut(chunk);
    }
    catch (...)
    {
      // a failed allocation leaves nothing behind on the device (no destructor runs here)
      Release();
      throw;
    }
  }
  // the records buffer holds at least `chunk` rays
  void EnsureOut(std::size_t chunk)
  {
    if (Out && chunk <= Chunk)
      return;
    if (Out)
      clReleaseMemObject(Out);
    Out = nullptr;
    cl_int err = CL_SUCCESS;
    Chunk = std::max<std::size_t>(1, chunk);
    Out = clCreateBuffer(RT.Context, CL_MEM_WRITE_ONLY, Chunk * SCH_RECORD * sizeof(float), nullptr, &err);
    ocl::Check(err, "clCreateBuffer(records)");
  }
  ~OpenCLTracer() { Release(); }
  void Release()
  {
    if (Out)
      clReleaseMemObject(Out);
    for (cl_mem& f : Fields)
      if (f)
        clReleaseMemObject(f);
    if (Levels)
      clReleaseMemObject(Levels);
    for (auto& k : Kernels)
      clReleaseKernel(k.second);
    Out = Levels = nullptr;
    for (cl_mem& f : Fields)
      f = nullptr;
    Kernels.clear();
  }
  OpenCLTracer(const OpenCLTracer&) = delete;
  OpenCLTracer& operator=(const OpenCLTracer&) = delete;

  // The kernels for P's integrator, octree use and invariant rescaling: built with them as
  // constants (-DSCH_FIXED_*), so that the step has no branches on them. Two programs per setting: the per-item one (sch_trace_rays, sch_trace_points) and the
  // lock-step one (sch_trace_lockstep, -DSCH_LOCKSTEP_GROUP: its walks in local memory). Each is
  // built on first use and kept, known by its entry point and every build option;
  // RuntimeOptions::Specialise false (SCHLIEREN_CL_SPECIALISE=0) builds one generic program of each.
  enum class Entry
  {
    Rays,
    Points,
    Lockstep,
    Pieces
  };
  cl_kernel KernelFor(const sch_params& P, Entry entry)
  {
    const bool specialise = Options.Specialise;
    const int setting = specialise
      ? 1 + P.integrator * 8 + (P.useSolid ? 4 : 0) + (P.useLevels ? 2 : 0) + (P.keepInvariant ? 1 : 0) +
        64 * P.recon
      : 0;
    std::ostringstream opts;
    opts << "-cl-std=CL1.2";
    if (entry == Entry::Lockstep)
      opts << " -DSCH_LOCKSTEP_GROUP=" << LockstepGroup;
    else
      opts << " -DSCH_RAYS_PER_ITEM=" << RaysPerItem;
    if (Slabs > 1)
      opts << " -DSCH_SLABS=" << Slabs;
    // a CPU device's compiler (PoCL's clang) has the prefetch sch_prefetch_at asks with
    if (RT.IsCPU)
      opts << " -DSCH_PREFETCH";
    if (specialise)
      opts << " -DSCH_FIXED_INTEGRATOR=" << P.integrator << " -DSCH_FIXED_LEVELS=" << (P.useLevels ? 1 : 0)
           << " -DSCH_FIXED_KEEP=" << (P.keepInvariant ? 1 : 0) << " -DSCH_FIXED_RECON=" << P.recon
           << " -DSCH_FIXED_SOLID=" << (P.useSolid ? 1 : 0);
    // extra OpenCL build options, for experiments (e.g. -cl-mad-enable)
    if (!Options.BuildOptions.empty())
      opts << " " << Options.BuildOptions;
    const char* name = entry == Entry::Rays ? "sch_trace_rays"
      : entry == Entry::Points              ? "sch_trace_points"
      : entry == Entry::Pieces              ? "sch_walk_pieces"
                                            : "sch_trace_lockstep";
    // the kernel is known by its entry point and every build option
    const std::string key = std::string(name) + " " + opts.str();
    auto it = Kernels.find(key);
    if (it != Kernels.end())
      return it->second;
    cl_program prog = ocl::GetProgram(RT, "SchlierenTrace.cl", EmbeddedKernelSource(), opts.str());
    cl_int err = CL_SUCCESS;
    cl_kernel k = clCreateKernel(prog, name, &err);
    ocl::Check(err, (std::string("clCreateKernel(") + name + ")").c_str());
    return Kernels[key] = k;
  }
  // The kernel that Trace (points false) or TracePoints (true) runs for P.
  cl_kernel KernelFor(const sch_params& P, bool points)
  {
    return KernelFor(P, points ? Entry::Points : UseLockstep(P) ? Entry::Lockstep : Entry::Rays);
  }

  void Trace(const sch_params& P, std::size_t first, std::size_t count, float* out)
  {
    const bool lockstep = UseLockstep(P);
    cl_kernel Kernel = KernelFor(P, false);
    const int f = static_cast<int>(first), c = static_cast<int>(count);
    const sch_params Q = WithSlabs(P);
    SetFieldArgs(Kernel);
    ocl::Check(clSetKernelArg(Kernel, 5, sizeof(sch_params), &Q), "clSetKernelArg(params)");
    ocl::Check(clSetKernelArg(Kernel, 6, sizeof(int), &f), "clSetKernelArg(first)");
    ocl::Check(clSetKernelArg(Kernel, 7, sizeof(int), &c), "clSetKernelArg(count)");
    ocl::Check(clSetKernelArg(Kernel, 8, sizeof(cl_mem), &Out), "clSetKernelArg(out)");
    if (lockstep)
    {
      // a ray per work-item, groups of LockstepGroup (the global size rounded up to them)
      const std::size_t local = LockstepGroup;
      const std::size_t global = (count + local - 1) / local * local;
      ocl::Check(clEnqueueNDRangeKernel(RT.Queue, Kernel, 1, nullptr, &global, &local, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel(sch_trace_lockstep)");
    }
    else
    {
      ocl::Check(EnqueueItems(Kernel, (count + RaysPerItem - 1) / RaysPerItem),
        "clEnqueueNDRangeKernel(sch_trace_rays)");
    }
    ocl::Check(clEnqueueReadBuffer(RT.Queue, Out, CL_TRUE, 0, count * SCH_RECORD * sizeof(float), out,
                 0, nullptr, nullptr),
      "clEnqueueReadBuffer(records)");
  }

  void TracePoints(const sch_params& P, const float* ab, std::size_t count, float* out)
  {
    cl_kernel PointsKernel = KernelFor(P, true);
    cl_int err = CL_SUCCESS;
    cl_mem abBuf = clCreateBuffer(RT.Context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
      std::max<std::size_t>(1, count) * 2 * sizeof(float), const_cast<float*>(ab), &err);
    ocl::Check(err, "clCreateBuffer(points)");
    const int c = static_cast<int>(count);
    const sch_params Q = WithSlabs(P);
    try
    {
      SetFieldArgs(PointsKernel);
      ocl::Check(clSetKernelArg(PointsKernel, 5, sizeof(sch_params), &Q), "clSetKernelArg(params)");
      ocl::Check(clSetKernelArg(PointsKernel, 6, sizeof(cl_mem), &abBuf), "clSetKernelArg(points)");
      ocl::Check(clSetKernelArg(PointsKernel, 7, sizeof(int), &c), "clSetKernelArg(count)");
      ocl::Check(clSetKernelArg(PointsKernel, 8, sizeof(cl_mem), &Out), "clSetKernelArg(out)");
    }
    catch (...)
    {
      // the points' buffer is this call's: released however the call ends
      clReleaseMemObject(abBuf);
      throw;
    }
    cl_int st = EnqueueItems(PointsKernel, count);
    if (st == CL_SUCCESS)
      st = clEnqueueReadBuffer(RT.Queue, Out, CL_TRUE, 0, count * SCH_RECORD * sizeof(float), out, 0,
        nullptr, nullptr);
    clReleaseMemObject(abBuf);
    ocl::Check(st, "sch_trace_points");
  }

  // Distributed tracing: advances `count` rays (in place) until each leaves the volume (status 0,
  // its record in out) or this rank's cells (status 1, its state written back).
  void WalkPieces(const sch_params& P, sch_piece_ray* rays, std::size_t count, float* out, int* status)
  {
    if (count == 0)
      return;
    cl_kernel kernel = KernelFor(P, Entry::Pieces);
    cl_int err = CL_SUCCESS;
    cl_mem raysBuf = clCreateBuffer(RT.Context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
      count * sizeof(sch_piece_ray), rays, &err);
    ocl::Check(err, "clCreateBuffer(rays)");
    cl_mem outBuf = clCreateBuffer(RT.Context, CL_MEM_WRITE_ONLY, count * SCH_RECORD * sizeof(float),
      nullptr, &err);
    cl_mem statusBuf = err == CL_SUCCESS
      ? clCreateBuffer(RT.Context, CL_MEM_WRITE_ONLY, count * sizeof(int), nullptr, &err)
      : nullptr;
    const int c = static_cast<int>(count);
    const sch_params Q = WithSlabs(P);
    cl_int st = err;
    if (st == CL_SUCCESS)
    {
      SetFieldArgs(kernel);
      const cl_int args[] = { clSetKernelArg(kernel, 5, sizeof(sch_params), &Q),
        clSetKernelArg(kernel, 6, sizeof(cl_mem), &raysBuf),
        clSetKernelArg(kernel, 7, sizeof(int), &c),
        clSetKernelArg(kernel, 8, sizeof(cl_mem), &outBuf),
        clSetKernelArg(kernel, 9, sizeof(cl_mem), &statusBuf) };
      for (cl_int a : args)
        st = st == CL_SUCCESS ? a : st;
    }
    if (st == CL_SUCCESS)
      st = EnqueueItems(kernel, count);
    if (st == CL_SUCCESS)
      st = clEnqueueReadBuffer(RT.Queue, raysBuf, CL_TRUE, 0, count * sizeof(sch_piece_ray), rays, 0,
        nullptr, nullptr);
    if (st == CL_SUCCESS)
      st = clEnqueueReadBuffer(RT.Queue, outBuf, CL_TRUE, 0, count * SCH_RECORD * sizeof(float), out,
        0, nullptr, nullptr);
    if (st == CL_SUCCESS)
      st = clEnqueueReadBuffer(RT.Queue, statusBuf, CL_TRUE, 0, count * sizeof(int), status, 0,
        nullptr, nullptr);
    // this call's buffers: released however it ends
    clReleaseMemObject(raysBuf);
    if (outBuf)
      clReleaseMemObject(outBuf);
    if (statusBuf)
      clReleaseMemObject(statusBuf);
    ocl::Check(st, "sch_walk_pieces");
  }

  // Arguments 0-4 of every kernel: the field's buffers (the first bound again where there are
  // fewer than four slabs; those are not read) and the octree levels.
  void SetFieldArgs(cl_kernel k)
  {
    for (int q = 0; q < MaxSlabs; ++q)
      ocl::Check(clSetKernelArg(k, q, sizeof(cl_mem), &Fields[q < Slabs ? q : 0]), "clSetKernelArg(field)");
    ocl::Check(clSetKernelArg(k, 4, sizeof(cl_mem), &Levels), "clSetKernelArg(levels)");
  }
  sch_params WithSlabs(const sch_params& P) const
  {
    if (P.fieldShift != (Bricked ? FieldBrickShift : 31))
      throw Error("internal: the trace's field layout (sch_params.fieldShift) is not its buffers'.");
    sch_params Q = P;
    Q.slabCells = SlabCells;
    return Q;
  }
  // The device's largest buffer, or less where RuntimeOptions::MaxAlloc (SCHLIEREN_CL_MAX_ALLOC)
  // says so: the split into slabs is tested on small volumes that way.
  std::uint64_t MaxAllocation() const
  {
    return Options.MaxAlloc > 0 ? std::min(RT.MaxAlloc, Options.MaxAlloc) : RT.MaxAlloc;
  }

  // Lock-step rays (sch_trace_lockstep) on CPU devices: PoCL then runs each step over the whole
  // group of rays, whose memory reads overlap (line of sight and the octree included). Other
  // devices take the per-item kernel, and so does the step-doubling estimate (the lock-step
  // program has no private walks to march the second ray with). RuntimeOptions::Lockstep
  // (SCHLIEREN_CL_LOCKSTEP=0/1) overrides (for measurements).
  bool UseLockstep(const sch_params& P) const
  {
    if (P.estimate)
      return false;
    if (Options.Lockstep >= 0)
      return Options.Lockstep != 0;
    return RT.IsCPU;
  }
  static constexpr std::size_t LockstepGroup = 64;
  // Launches a per-item kernel (sch_trace_rays, sch_trace_points, sch_walk_pieces: each returns
  // for an item at or past its count) over `items` work-items in groups of a fixed size, the global
  // size rounded up to a whole group. PoCL builds a work-group function for every local size it is
  // given or picks, and with none given it picks a divisor of the global size: the piece walks'
  // counts, which change every exchange round, made 147 builds of sch_walk_pieces in
  // engine.TestEngineDistributed alone (0.6-0.75 s each on 2 cores, 110 of its 119 s on a cold
  // cache). RuntimeOptions::LocalSize (SCHLIEREN_CL_LOCAL_SIZE) overrides; 0 leaves the choice to
  // the driver, as on GPUs (whose drivers build no code per local size).
  cl_int EnqueueItems(cl_kernel kernel, std::size_t items)
  {
    const std::size_t local = Options.LocalSize >= 0 ? std::size_t(Options.LocalSize) : RT.IsCPU ? 16 : 0;
    const std::size_t global = local ? (items + local - 1) / local * local : items;
    return clEnqueueNDRangeKernel(
      RT.Queue, kernel, 1, nullptr, &global, local ? &local : nullptr, 0, nullptr, nullptr);
  }

  ocl::Runtime& RT;
  const RuntimeOptions Options;
  int RaysPerItem;
  std::size_t Chunk = 0;
  std::map<std::string, cl_kernel> Kernels;
  // the field: one buffer, or Slabs buffers of SlabCells cells along z (see the constructor)
  static constexpr int MaxSlabs = 4;
  cl_mem Fields[MaxSlabs] = { nullptr, nullptr, nullptr, nullptr };
  bool Shared[MaxSlabs] = { false, false, false, false }; // uses the caller's memory (CPU device)
  int Slabs = 1, SlabCells = 0;
  bool Bricked = false; // the field in bricks (BrickedField), else linear
  cl_mem Levels = nullptr, Out = nullptr;
};

namespace
{
// The device copy of the last stamped volume, kept for the next call (an interactive view traces
// the same volume again and again, so the upload is paid once). Allocated once; its
// device objects are released by the runtime's exit hook (ocl::AtRelease), before the context.
struct KeptTracer
{
  VolumeIdentity Identity;
  int RaysPerItem = 0;
  // the device asked for and the OpenCL options (RuntimeOptions::OpenCLKey) it was made with
  std::string Device;
  // the cell bytes the device copy was made from, held (where the engine made them: a body's,
  // which change with the step's reach, or the octree merged with Cubic's smoothness) so that
  // no other allocation can take their address while the copy is kept, nor free them while a
  // CPU device uses them in place
  const unsigned char* Bytes = nullptr;
  std::shared_ptr<const void> BytesOwner;
  std::shared_ptr<OpenCLTracer> Tracer;
};
void ReleaseKeptAtExit();
KeptTracer& Kept()
{
  static KeptTracer* kept = [] {
    ocl::AtRelease(&ReleaseKeptAtExit);
    return new KeptTracer;
  }();
  return *kept;
}
void ReleaseKeptAtExit()
{
  std::lock_guard<std::mutex> lock(KeptMutex);
  Kept().Tracer.reset();
  Kept().Identity = VolumeIdentity();
}

} // namespace

std::shared_ptr<OpenCLTracer> AcquireTracer(const Volume& volume, const unsigned char* bytes,
  const std::shared_ptr<const void>& bytesOwner, std::size_t chunk, int raysPerItem,
  const RuntimeOptions& options, const std::string& deviceName, bool bricked)
{
  const std::string device = deviceName + '\n' + options.OpenCLKey() + (bricked ? "\nbricks" : "");
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    KeptTracer& k = Kept();
    // in use by another call (use_count > 1): that call keeps it; this one makes its own
    if (k.Tracer && k.Identity == VolumeIdentity(volume) && k.RaysPerItem == raysPerItem &&
      k.Device == device && k.Bytes == bytes && k.Tracer.use_count() == 1)
    {
      std::shared_ptr<OpenCLTracer> t = k.Tracer;
      t->EnsureOut(chunk);
      return t;
    }
    // one volume on the device at a time: the old copy goes before the new one is made
    k.Tracer.reset();
    k.Identity = VolumeIdentity();
    k.Device.clear();
    k.Bytes = nullptr;
    k.BytesOwner.reset();
  }
  auto t = std::make_shared<OpenCLTracer>(volume, bytes, chunk, raysPerItem, options, deviceName, bricked);
  if (volume.Stamp != 0)
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    Kept().Identity = VolumeIdentity(volume);
    Kept().RaysPerItem = raysPerItem;
    Kept().Device = device;
    Kept().Bytes = bytes;
    Kept().BytesOwner = bytesOwner;
    Kept().Tracer = t;
  }
  return t;
}

void PrepareKernel(OpenCLTracer& t, const sch_params& P, bool points)
{
  t.KernelFor(P, points);
}

std::string TracerDeviceName(const OpenCLTracer& t)
{
  std::string device = t.RT.DeviceName;
  if (t.Slabs > 1)
    device += " (the field split in " + std::to_string(t.Slabs) + " buffers)";
  return device;
}

std::size_t OpenCLProgramsBuilt()
{
  return ocl::ProgramsBuilt();
}

bool OpenCLDeviceIsCPU(const std::string& deviceName)
{
  try
  {
    return ocl::GetRuntime(deviceName).IsCPU;
  }
  catch (const Error&)
  {
    return false;
  }
}

void TraceOpenCL(OpenCLTracer& t, const sch_params& P, std::size_t first, std::size_t count, float* out)
{
  t.Trace(P, first, count, out);
}

void TracePointsOpenCL(
  OpenCLTracer& t, const sch_params& P, const float* ab, std::size_t count, float* out)
{
  t.TracePoints(P, ab, count, out);
}

void PreparePiecesKernel(OpenCLTracer& t, const sch_params& P)
{
  t.KernelFor(P, OpenCLTracer::Entry::Pieces);
}

void WalkPiecesOpenCL(OpenCLTracer& t, const sch_params& P, sch_piece_ray* rays, std::size_t count,
  float* out, int* status)
{
  t.WalkPieces(P, rays, count, out, status);
}

void ReleaseKeptVolume()
{
  {
    std::lock_guard<std::mutex> lock(KeptMutex);
    Kept().Tracer.reset();
    Kept().Identity = VolumeIdentity();
  }
  ReleaseBrickedField();
  ReleaseCoarseCopies();
}

DeviceInfo QueryOpenCLDevice(const std::string& deviceName)
{
  DeviceInfo info;
  try
  {
    ocl::Runtime& rt = ocl::GetRuntime(deviceName);
    info.Available = true;
    info.Name = rt.DeviceName;
    info.Platform = rt.PlatformName;
    info.Version = rt.Version;
    info.MaxAlloc = rt.MaxAlloc;
    info.GlobalMemory = rt.GlobalMemory;
  }
  catch (const Error& e)
  {
    info.Reason = e.what();
  }
  return info;
}

void BuildOpenCLProgram(const std::string& name, const std::string& source, const std::string& options)
{
  ocl::GetProgram(name, source, options);
}

} // namespace schlieren
