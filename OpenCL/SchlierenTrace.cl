/*
 * SchlierenTrace.cl -- the OpenCL entry points. The physics is in SchlierenPhysics.h, which the build
 * embeds in front of this text (the #include below is replaced at build time), so this file only
 * maps work-items to rays.
 *
 * Build options: -DSCH_RAYS_PER_ITEM=N (rays advanced in turn by each work-item).
 */
#ifndef SCH_RAYS_PER_ITEM
#define SCH_RAYS_PER_ITEM 1
#endif
#define SCH_PACKET SCH_RAYS_PER_ITEM
#include "SchlierenPhysics.h"

/* Trace rays k = first .. first + count - 1 of a pass; ray k goes through pixel
 * P.rayOffset + k * P.rayStride and writes SCH_RECORD floats at out[(k - first) * SCH_RECORD].
 * Each work-item takes SCH_RAYS_PER_ITEM consecutive rays and advances them in turn
 * (sch_trace_packet, built with SCH_PACKET = SCH_RAYS_PER_ITEM). */
__kernel void sch_trace_rays(__global const float* field, __global const uchar* levels,
  const sch_params P, const int first, const int count, __global float* out)
{
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
__kernel void sch_trace_points(__global const float* field, __global const uchar* levels,
  const sch_params P, __global const float* ab, const int count, __global float* out)
{
  int k = (int)get_global_id(0);
  if (k >= count)
    return;
  float rec[SCH_RECORD];
  sch_trace(field, levels, &P, ab[2 * k], ab[2 * k + 1], rec);
  for (int c = 0; c < SCH_RECORD; ++c)
    out[(long)k * SCH_RECORD + c] = rec[c];
}
