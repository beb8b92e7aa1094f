/*
 * SchlierenPhysics.h -- the one source of the tracing physics.
 *
 * Written in the subset of C99 that both OpenCL C 1.2 and C++ compile. The OpenCL kernels include
 * it (the build embeds it in front of the kernel text) and the CPU path of the engine includes it
 * as C++, so both backends run the same sampling, ray step, film mapping and cutoff code.
 *
 * Conventions (see DESIGN.md):
 *  - The volume holds, per grid point, 4 floats: n-1, dn/dx, dn/dy, dn/dz (x fastest). Gradients
 *    are in 1/world-unit.
 *  - All positions inside the tracer are relative to the volume centre c, so that float32 keeps its
 *    digits when the data sits far from the world origin.
 *  - The ray state is x and v = n dx/ds. v is kept as n_e d0 + w, where n_e is the index at entry
 *    and w = integral of grad n ds: w is small and summed in float without cancellation, and the
 *    deflection on the film axes is exactly (w . axis) / |v|.
 *  - Film coordinates (a, b) are measured from c along the film's right (r) and top (t) axes.
 */
#ifndef SCHLIEREN_PHYSICS_H
#define SCHLIEREN_PHYSICS_H

#ifdef __OPENCL_VERSION__
#define SCH_FN static inline
#define SCH_GLOBAL __global
typedef uint sch_uint;
#define sch_sqrt sqrt
#define sch_floor floor
#define sch_fabs fabs
#define sch_cos cos
#define sch_sin sin
#define sch_isfinite isfinite
#else
#include <math.h>
#include <stdint.h>
#define SCH_FN static inline
#define SCH_GLOBAL
typedef uint32_t sch_uint;
#define sch_sqrt sqrtf
#define sch_floor floorf
#define sch_fabs fabsf
#define sch_cos cosf
#define sch_sin sinf
#define sch_isfinite isfinite
#endif

/* Number of floats per output ray record. */
#define SCH_RECORD 8
/* Record layout. */
#define SCH_REC_A 0       /* landing film coordinate along r (world units, from c) */
#define SCH_REC_B 1       /* landing film coordinate along t */
#define SCH_REC_EX 2      /* deflection along r (radians) */
#define SCH_REC_EY 3      /* deflection along t (radians) */
#define SCH_REC_OPL 4     /* excess optical path: integral of (n-1) ds inside the volume */
#define SCH_REC_FLAGS 5   /* SCH_RAY_* bits, stored as a float (exact below 2^24) */
#define SCH_REC_SAMPLES 6 /* field samples taken */
#define SCH_REC_DRIFT 7   /* |v| - n at exit: the drift of the ray invariant (error indicator) */

/* Ray status bits. */
#define SCH_RAY_MISSED 1u    /* never entered the volume: undeflected */
#define SCH_RAY_MAXSTEPS 2u  /* gave up after the step limit */
#define SCH_RAY_TURNED 4u    /* turned back against the beam (total internal reflection-like) */
#define SCH_RAY_NONFINITE 8u /* the state became NaN/Inf */
#define SCH_RAY_OFFFILM 16u  /* could not reach the film plane (parallel to it) */

/* Integrators. */
#define SCH_EULER 0
#define SCH_MIDPOINT 1
#define SCH_RK4 2

/* Cutoffs. */
#define SCH_KNIFE 0
#define SCH_SHADOWGRAPH 1

typedef struct
{
  float x, y, z;
} sch_v3;

/* All that a kernel needs besides the field and the output: only 4-byte members, so that the
 * host and every device lay it out the same way. */
typedef struct
{
  int nx, ny, nz;  /* grid points */
  int maxSteps;    /* per ray */
  float ox, oy, oz; /* position of point (0,0,0), relative to the centre */
  float isx, isy, isz; /* 1 / spacing */
  float hx, hy, hz;    /* half extent of the box of grid points (box is [-h, h]) */
  float dx, dy, dz;    /* beam direction d0 (unit) */
  float rx, ry, rz;    /* film right axis (unit) */
  float tx, ty, tz;    /* film top axis (unit) */
  float sFront;        /* emission plane: x . d0 = sFront */
  float sFilm;         /* film plane: x . d0 = sFilm */
  float filmA0, filmB0; /* film coordinate of the lower-left corner of pixel (0,0) */
  float pixel;          /* pixel size in world units (square pixels) */
  int filmNx, filmNy;
  float step;           /* base step in world units */
  sch_uint seed;
  int pass;
  int integrator;
  int jitter;           /* 0: rays through pixel centres; 1: jittered inside each pixel */
  int rayOffset, rayStride; /* ray k traces pixel rayOffset + k * rayStride */
  int pad0;
} sch_params;

SCH_FN sch_v3 sch_make(float x, float y, float z)
{
  sch_v3 r;
  r.x = x;
  r.y = y;
  r.z = z;
  return r;
}
SCH_FN sch_v3 sch_add(sch_v3 a, sch_v3 b) { return sch_make(a.x + b.x, a.y + b.y, a.z + b.z); }
SCH_FN sch_v3 sch_scale(sch_v3 a, float s) { return sch_make(a.x * s, a.y * s, a.z * s); }
SCH_FN sch_v3 sch_axpy(float s, sch_v3 a, sch_v3 y)
{
  return sch_make(s * a.x + y.x, s * a.y + y.y, s * a.z + y.z);
}
SCH_FN float sch_dot(sch_v3 a, sch_v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* ---------------------------------------------------------------- hashing and jitter */

SCH_FN sch_uint sch_hash(sch_uint x)
{
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/* Uniform in [0, 1) with 24 random bits. */
SCH_FN float sch_unit(sch_uint h) { return (float)(h >> 8) * (1.0f / 16777216.0f); }

/* ---------------------------------------------------------------- sampling */

typedef struct
{
  float n1;      /* n - 1 */
  sch_v3 g;      /* grad n */
} sch_sample;

/* Trilinear interpolation of the packed field at p (relative to the centre); outside the grid the
 * nearest border value is used. */
SCH_FN sch_sample sch_sample_field(SCH_GLOBAL const float* field, const sch_params* P, sch_v3 p)
{
  float fx = (p.x - P->ox) * P->isx;
  float fy = (p.y - P->oy) * P->isy;
  float fz = (p.z - P->oz) * P->isz;
  fx = fx < 0.0f ? 0.0f : (fx > (float)(P->nx - 1) ? (float)(P->nx - 1) : fx);
  fy = fy < 0.0f ? 0.0f : (fy > (float)(P->ny - 1) ? (float)(P->ny - 1) : fy);
  fz = fz < 0.0f ? 0.0f : (fz > (float)(P->nz - 1) ? (float)(P->nz - 1) : fz);
  int i = (int)fx;
  int j = (int)fy;
  int k = (int)fz;
  if (i > P->nx - 2)
    i = P->nx - 2;
  if (j > P->ny - 2)
    j = P->ny - 2;
  if (k > P->nz - 2)
    k = P->nz - 2;
  float tx = fx - (float)i;
  float ty = fy - (float)j;
  float tz = fz - (float)k;
  long sy = (long)P->nx * 4;
  long sz = (long)P->nx * (long)P->ny * 4;
  SCH_GLOBAL const float* c000 = field + ((long)k * P->ny + j) * sy + (long)i * 4;
  /* the eight corners */
  SCH_GLOBAL const float* c100 = c000 + 4;
  SCH_GLOBAL const float* c010 = c000 + sy;
  SCH_GLOBAL const float* c110 = c010 + 4;
  SCH_GLOBAL const float* c001 = c000 + sz;
  SCH_GLOBAL const float* c101 = c001 + 4;
  SCH_GLOBAL const float* c011 = c001 + sy;
  SCH_GLOBAL const float* c111 = c011 + 4;
  float w000 = (1.0f - tx) * (1.0f - ty) * (1.0f - tz);
  float w100 = tx * (1.0f - ty) * (1.0f - tz);
  float w010 = (1.0f - tx) * ty * (1.0f - tz);
  float w110 = tx * ty * (1.0f - tz);
  float w001 = (1.0f - tx) * (1.0f - ty) * tz;
  float w101 = tx * (1.0f - ty) * tz;
  float w011 = (1.0f - tx) * ty * tz;
  float w111 = tx * ty * tz;
  float r[4];
  int c;
  for (c = 0; c < 4; ++c)
  {
    r[c] = w000 * c000[c] + w100 * c100[c] + w010 * c010[c] + w110 * c110[c] + w001 * c001[c] +
      w101 * c101[c] + w011 * c011[c] + w111 * c111[c];
  }
  sch_sample s;
  s.n1 = r[0];
  s.g = sch_make(r[1], r[2], r[3]);
  return s;
}

/* ---------------------------------------------------------------- geometry */

SCH_FN int sch_inside(const sch_params* P, sch_v3 p)
{
  return sch_fabs(p.x) <= P->hx && sch_fabs(p.y) <= P->hy && sch_fabs(p.z) <= P->hz;
}

/* Slab test of the line o + s d against the box [-h, h]; returns 1 and the parameter range on a hit. */
SCH_FN int sch_clip_box(const sch_params* P, sch_v3 o, sch_v3 d, float* s0, float* s1)
{
  float lo = -1e30f, hi = 1e30f;
  float oc[3] = { o.x, o.y, o.z };
  float dc[3] = { d.x, d.y, d.z };
  float hc[3] = { P->hx, P->hy, P->hz };
  int a;
  for (a = 0; a < 3; ++a)
  {
    if (sch_fabs(dc[a]) < 1e-12f)
    {
      if (oc[a] < -hc[a] || oc[a] > hc[a])
        return 0;
    }
    else
    {
      float inv = 1.0f / dc[a];
      float t0 = (-hc[a] - oc[a]) * inv;
      float t1 = (hc[a] - oc[a]) * inv;
      if (t0 > t1)
      {
        float tmp = t0;
        t0 = t1;
        t1 = tmp;
      }
      lo = t0 > lo ? t0 : lo;
      hi = t1 < hi ? t1 : hi;
    }
  }
  *s0 = lo;
  *s1 = hi;
  return hi > lo;
}

/* Film coordinates of ray pixel `pix` in pass P->pass: jittered inside the pixel or at its centre. */
SCH_FN void sch_emit(const sch_params* P, int pix, float* a, float* b)
{
  int ix = pix % P->filmNx;
  int iy = pix / P->filmNx;
  float jx = 0.5f, jy = 0.5f;
  if (P->jitter)
  {
    sch_uint h = sch_hash(P->seed ^ sch_hash((sch_uint)pix * 2654435761u ^ sch_hash((sch_uint)P->pass + 0x9e3779b9u)));
    jx = sch_unit(h);
    jy = sch_unit(sch_hash(h ^ 0x68bc21ebu));
  }
  *a = P->filmA0 + ((float)ix + jx) * P->pixel;
  *b = P->filmB0 + ((float)iy + jy) * P->pixel;
}

/* ---------------------------------------------------------------- tracing */

/* Trace one ray that starts on the emission plane at film coordinates (a, b) and write its record. */
SCH_FN void sch_trace(SCH_GLOBAL const float* field, const sch_params* P, float a, float b,
  float* rec)
{
  sch_v3 d0 = sch_make(P->dx, P->dy, P->dz);
  sch_v3 ra = sch_make(P->rx, P->ry, P->rz);
  sch_v3 ta = sch_make(P->tx, P->ty, P->tz);
  sch_v3 o = sch_add(sch_add(sch_scale(ra, a), sch_scale(ta, b)), sch_scale(d0, P->sFront));
  sch_uint flags = 0u;
  float samples = 0.0f;
  float opl = 0.0f;
  float drift = 0.0f;
  sch_v3 x = o;
  sch_v3 w = sch_make(0.0f, 0.0f, 0.0f);
  float ne = 1.0f;
  float s0, s1;
  if (!sch_clip_box(P, o, d0, &s0, &s1) || s1 <= 0.0f)
  {
    flags |= SCH_RAY_MISSED;
  }
  else
  {
    x = sch_axpy(s0 > 0.0f ? s0 : 0.0f, d0, o);
    float ds = P->step;
    /* the index where the ray enters is the background the deflection is measured against */
    sch_sample s = sch_sample_field(field, P, x);
    samples += 1.0f;
    ne = 1.0f + s.n1;
    int it;
    /* march until the ray leaves the box; a tiny tolerance keeps rays that start on a face */
    for (it = 0; it < P->maxSteps; ++it)
    {
      sch_v3 v = sch_axpy(ne, d0, w);
      if (P->integrator == SCH_MIDPOINT)
      {
        /* half step with the slope at x, full step with the slope at the midpoint */
        sch_v3 xm = sch_axpy(0.5f * ds / (1.0f + s.n1), v, x);
        sch_v3 vm = sch_axpy(0.5f * ds, s.g, v);
        sch_sample sm = sch_sample_field(field, P, xm);
        samples += 1.0f;
        x = sch_axpy(ds / (1.0f + sm.n1), vm, x);
        w = sch_axpy(ds, sm.g, w);
        opl += ds * sm.n1;
      }
      else
      {
        /* the paper's explicit Euler: x += ds v / n, v += ds grad n */
        x = sch_axpy(ds / (1.0f + s.n1), v, x);
        w = sch_axpy(ds, s.g, w);
        opl += ds * s.n1;
      }
      if (!(sch_isfinite(x.x) && sch_isfinite(x.y) && sch_isfinite(x.z) && sch_isfinite(w.x) &&
            sch_isfinite(w.y) && sch_isfinite(w.z)))
      {
        flags |= SCH_RAY_NONFINITE;
        break;
      }
      if (ne + sch_dot(d0, w) <= 0.0f)
      {
        flags |= SCH_RAY_TURNED;
        break;
      }
      if (!sch_inside(P, x))
        break;
      s = sch_sample_field(field, P, x);
      samples += 1.0f;
    }
    if (it >= P->maxSteps)
      flags |= SCH_RAY_MAXSTEPS;
    sch_v3 vexit = sch_axpy(ne, d0, w);
    float vn = sch_sqrt(sch_dot(vexit, vexit));
    /* the ray invariant |v| = n, measured against the index where the ray left */
    drift = vn - (1.0f + s.n1);
  }
  sch_v3 v = sch_axpy(ne, d0, w);
  float vn = sch_sqrt(sch_dot(v, v));
  float ex = sch_dot(w, ra) / vn;
  float ey = sch_dot(w, ta) / vn;
  /* straight flight from the exit point to the film plane */
  float dd = (ne + sch_dot(w, d0)) / vn;
  float la = sch_dot(x, ra), lb = sch_dot(x, ta);
  if (dd > 1e-6f)
  {
    float t = (P->sFilm - sch_dot(x, d0)) / dd;
    la += t * ex;
    lb += t * ey;
  }
  else
  {
    flags |= SCH_RAY_OFFFILM;
  }
  rec[SCH_REC_A] = la;
  rec[SCH_REC_B] = lb;
  rec[SCH_REC_EX] = ex;
  rec[SCH_REC_EY] = ey;
  rec[SCH_REC_OPL] = opl;
  rec[SCH_REC_FLAGS] = (float)flags;
  rec[SCH_REC_SAMPLES] = samples;
  rec[SCH_REC_DRIFT] = drift;
}

/* ---------------------------------------------------------------- cutoffs */

/* Knife-edge energy weighting: the fraction of the light-source image that passes a knife whose
 * normal in the film plane is (ca, sa), for deflection (ex, ey) and scale k. */
SCH_FN float sch_knife_weight(float ex, float ey, float ca, float sa, float k)
{
  float I = 0.5f - k * (ex * ca + ey * sa);
  return I < 0.0f ? 0.0f : (I > 1.0f ? 1.0f : I);
}

#endif
