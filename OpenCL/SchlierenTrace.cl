/*
 * SchlierenTrace.cl -- the OpenCL entry points. The physics is in SchlierenPhysics.h, which the build
 * embeds in front of this text (the #include below is replaced at build time), so this file only
 * maps work-items to rays.
 *
 * Build options: -DSCH_RAYS_PER_ITEM=N (rays advanced in turn by each work-item);
 * -DSCH_LOCKSTEP_GROUP=G builds the lock-step program instead (sch_trace_lockstep only, work-groups
 * of exactly G items, the walks in local memory).
 */
#ifndef SCH_RAYS_PER_ITEM
#define SCH_RAYS_PER_ITEM 1
#endif
#define SCH_PACKET SCH_RAYS_PER_ITEM
#ifdef SCH_LOCKSTEP_GROUP
#define SCH_WALK_AS __local
#define SCH_RECORD_AS __global
#endif
#include "SchlierenPhysics.h"

/* Every kernel takes four field buffers: the slabs of a volume split along z (-DSCH_SLABS=S), or
 * the whole volume in the first and the same buffer bound to the other three, unread. */
#define SCH_FIELD_ARGS                                                                              \
  __global const float *field0, __global const float *field1, __global const float *field2,        \
    __global const float *field3
static inline SCH_FIELD sch_field_of(__global const float* f0, __global const float* f1,
  __global const float* f2, __global const float* f3)
{
#ifdef SCH_SLABS
  sch_field F;
  F.slab[0] = f0;
  F.slab[1] = f1;
#if SCH_SLABS > 2
  F.slab[2] = f2;
#endif
#if SCH_SLABS > 3
  F.slab[3] = f3;
#endif
  return F;
#else
  return f0;
#endif
}

#ifndef SCH_LOCKSTEP_GROUP

/* Trace rays k = first .. first + count - 1 of a pass; ray k goes through pixel
 * P.rayOffset + k * P.rayStride and writes SCH_RECORD floats at out[(k - first) * SCH_RECORD].
 * Each work-item takes SCH_RAYS_PER_ITEM consecutive rays and advances them in turn
 * (sch_trace_packet, built with SCH_PACKET = SCH_RAYS_PER_ITEM). */
__kernel void sch_trace_rays(SCH_FIELD_ARGS, __global const uchar* levels,
  const sch_params P, const int first, const int count, __global float* out)
{
  SCH_FIELD field = sch_field_of(field0, field1, field2, field3);
  int base = (int)get_global_id(0) * SCH_RAYS_PER_ITEM;
  if (base >= count)
    return;
  int n = count - base < SCH_RAYS_PER_ITEM ? count - base : SCH_RAYS_PER_ITEM;
  float rec[SCH_RECORD * SCH_RAYS_PER_ITEM];
  sch_trace_packet(field, levels, &P, P.rayOffset + (first + base) * P.rayStride, P.rayStride, n, rec);
  for (int c = 0; c < n * SCH_RECORD; ++c)
    out[(long)base * SCH_RECORD + c] = rec[c];
}

/* Trace rays from explicit film coordinates (ab[2k], ab[2k+1]): used by tests and probes. */
__kernel void sch_trace_points(SCH_FIELD_ARGS, __global const uchar* levels,
  const sch_params P, __global const float* ab, const int count, __global float* out)
{
  SCH_FIELD field = sch_field_of(field0, field1, field2, field3);
  int k = (int)get_global_id(0);
  if (k >= count)
    return;
  float rec[SCH_RECORD];
  sch_trace(field, levels, &P, ab[2 * k], ab[2 * k + 1], rec);
  for (int c = 0; c < SCH_RECORD; ++c)
    out[(long)k * SCH_RECORD + c] = rec[c];
}

/* Distributed tracing (SchlierenDistributed.cxx): advances ray k of this rank until it leaves the
 * volume (status 0, its record in out) or the cells this rank owns (P.own*: status 1, its state
 * written back for the rank that owns where it went). The arithmetic per ray is sch_trace's. */
__kernel void sch_walk_pieces(SCH_FIELD_ARGS, __global const uchar* levels, const sch_params P,
  __global sch_piece_ray* rays, const int count, __global float* out, __global int* status)
{
  SCH_FIELD field = sch_field_of(field0, field1, field2, field3);
  int k = (int)get_global_id(0);
  if (k >= count)
    return;
  sch_piece_ray r = rays[k];
  if (SCH_USE_LEVELS(&P) | (SCH_RECON(&P) == SCH_CUBIC) | SCH_USE_SOLID(&P))
  {
    /* the byte of its cell as this rank (its owner) knows it: level, smoothness, near a body */
    long cell;
    sch_sample_cell(field, &P, r.w.x, &cell);
    if (SCH_USE_LEVELS(&P) | (SCH_RECON(&P) == SCH_CUBIC))
      r.w.level = (int)levels[cell];
    if (SCH_USE_SOLID(&P))
      r.w.nearSolid = (int)(levels[cell] & SCH_NEAR_BIT);
  }
  while (sch_walk_step(field, levels, &P, &r.w))
  {
    if (!sch_owns(&P, r.w.x))
    {
      rays[k] = r;
      status[k] = 1;
      return;
    }
  }
  sch_ray R;
  sch_walk_end(field, &P, &r.w, &R);
  float rec[SCH_RECORD];
  sch_record(field, levels, &P, r.a, r.b, r.o, r.entry, r.s1, &R, rec);
  for (int c = 0; c < SCH_RECORD; ++c)
    out[(long)k * SCH_RECORD + c] = rec[c];
  status[k] = 0;
}

#else

/* The ray that work-item g of a launch traces: the rays of a film band of SCH_TILE_ROWS rows
 * taken tile by tile (SCH_TILE_W columns, the band's height), row by row within a tile, so that
 * a lock-step group of 64 is an 8 x 8 block of pixels whose samples share cache lines (a group
 * along one film row spans 32 voxels at two pixels a voxel). A permutation of 0 .. count - 1:
 * narrower tiles at the right edge, a lower band at the bottom; the launch of a rank's strided
 * rays, or one that does not start and end on whole bands, keeps the film's order (the host cuts
 * its chunks on bands, SchlierenTrace.cxx), and so does a view of the linear layout whose film
 * rows run along x. Which ray a work-item takes changes no arithmetic:
 * the records are written in the film's order and are the same, bit for bit. */
static inline int sch_tile_order(const sch_params* P, int first, int count, int g)
{
  const int W = P->filmNx, band = SCH_TILE_ROWS * W;
  /* the linear layout seen with the film's rows along x, its lines: a group along a film row
   * reads the lines its neighbours read (issue 50, 512^3 along z on a 256^2 film, PoCL: 77-80
   * against 42-44 M trilinear samples/s in tiles, 20.6-23.5 against 16.2-18.8 tricubic); in
   * bricks, and obliquely, the tiles */
  if ((P->fieldShift == 31 && sch_fabs(P->rx) > 0.9f) || P->rayStride != 1 || P->rayOffset != 0 ||
    first % band != 0 || (count % band != 0 && first + count != W * P->filmNy))
    return g;
  const int b = g / band, L = g - b * band;
  const int rows = P->filmNy - (first / W + b * SCH_TILE_ROWS);
  const int H = rows < SCH_TILE_ROWS ? rows : SCH_TILE_ROWS;
  const int full = W / SCH_TILE_W, inFull = full * SCH_TILE_W * H;
  int row, col;
  if (L < inFull)
  {
    const int t = L / (SCH_TILE_W * H), e = L - t * (SCH_TILE_W * H);
    row = e / SCH_TILE_W;
    col = t * SCH_TILE_W + (e - row * SCH_TILE_W);
  }
  else
  {
    const int wr = W - full * SCH_TILE_W, e = L - inFull;
    row = e / wr;
    col = full * SCH_TILE_W + (e - row * wr);
  }
  return b * band + row * W + col;
}

/* The same rays, one per work-item, advanced in lock step: every work-item of a group takes its
 * step, then the group meets at a barrier, until none of its rays is still marching. On CPU
 * devices PoCL then runs each step as a loop over the group's work-items, whose memory reads are
 * independent and overlap; without the barrier it runs one work-item's whole march after another.
 * The walks live in local memory and are stepped in place: kept in private variables, PoCL copies
 * every field of every walk between context arrays at each barrier; called as a function, each
 * step pays a call and reloads the parameters (docs/PERFORMANCE.md has the figures). Not vectorised (PoCL's remarks: vector values, branches that are not
 * selects; a probe that was, with 4-wide gathers, ran slower): the gain is the overlapped reads.
 * The arithmetic per ray is sch_trace's: the records are identical. The host launches groups of
 * exactly SCH_LOCKSTEP_GROUP items and never asks this program for the step-doubling estimate. */
__kernel void sch_trace_lockstep(SCH_FIELD_ARGS, __global const uchar* levels,
  const sch_params P, const int first, const int count, __global float* out)
{
  SCH_FIELD field = sch_field_of(field0, field1, field2, field3);
  const int g = (int)get_global_id(0);
  const int valid = g < count;
  const int k = valid ? sch_tile_order(&P, first, count, g) : g;
  float a = 0.0f, b = 0.0f, s1 = 0.0f;
  sch_v3 o, entry;
  __local sch_walk walks[SCH_LOCKSTEP_GROUP];
  __local sch_walk* W = &walks[get_local_id(0)];
  /* each step asks for the lines of its next end point while the rest of the group steps
   * (sch_walk_step, P.prefetch; the host builds with -DSCH_PREFETCH for CPU devices) */
  int hit = 0;
  if (valid)
  {
    sch_emit(&P, P.rayOffset + (first + k) * P.rayStride, &a, &b);
    hit = sch_entry(&P, a, b, &o, &entry, &s1);
    /* the walks begin after the barrier below: their entry samples are asked for while the rest
     * of the group finds its entries */
#ifdef SCH_PREFETCH_LINE
    if (hit & P.prefetch)
      sch_prefetch_at(field, levels, &P, entry);
#endif
  }
  int live = hit;
  /* one barrier per step: a flag per step, in three slots so that resetting the slot of step
   * t + 1 before the barrier of step t cannot race with reads of the slot of step t - 1, which all
   * happened before the barrier of step t - 1 */
  __local int anyLive[3];
  if (get_local_id(0) == 0)
    anyLive[0] = anyLive[1] = anyLive[2] = 0;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (hit)
    sch_walk_begin(field, levels, &P, entry, P.step, W);
  for (int t = 0;; t = t == 2 ? 0 : t + 1)
  {
    if (live)
      live = sch_walk_step(field, levels, &P, W);
    if (live)
      anyLive[t] = 1;
    if (get_local_id(0) == 0)
      anyLive[t == 2 ? 0 : t + 1] = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (!anyLive[t])
      break;
  }
  if (!valid)
    return;
  sch_ray R;
  if (hit)
    sch_walk_end(field, &P, W, &R);
  else
    sch_missed(o, &R);
  /* written in place: a record built in private memory and copied out was read back wider than
   * it was written, a stall at every ray (store forwarding; 1 in 9 of the kernel's time when each
   * ray takes one step) */
  sch_record(field, levels, &P, a, b, o, entry, s1, &R, out + (long)k * SCH_RECORD);
}

#endif
