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
 *    deflection on the film axes is exactly (w . axis) / |v|. x itself is put together at every
 *    step from the entry point, the distance along d0 and the displacement across it, each summed
 *    apart (sch_walk), so that seen obliquely to the grid its coordinates are not rounded anew at
 *    every step.
 *  - Film coordinates (a, b) are measured from c along the film's right (r) and top (t) axes.
 */
#ifndef SCHLIEREN_PHYSICS_H
#define SCHLIEREN_PHYSICS_H

/* The address space of a ray's walk state (sch_walk): private, or __local where the lock-step
 * kernel keeps a group's walks in local memory and steps them in place (SchlierenTrace.cl; that
 * program then has no private walks: no sch_march, hence no step-doubling estimate). */
#ifndef SCH_WALK_AS
#define SCH_WALK_AS
#define SCH_PRIVATE_WALKS 1
#endif
/* The address space of the record sch_record writes: private (copied out by the caller), or
 * __global where the lock-step kernel writes it straight into the output buffer. */
#ifndef SCH_RECORD_AS
#define SCH_RECORD_AS
#endif

#ifdef __OPENCL_VERSION__
/* always inlined (PoCL left sch_sample_field and the step as calls: "too costly to inline") */
#define SCH_FN static inline __attribute__((always_inline))
#define SCH_GLOBAL __global
typedef uint sch_uint;
typedef uchar sch_uchar;
#define sch_sqrt sqrt
#define sch_floor floor
#define sch_fabs fabs
#define sch_isfinite isfinite
#define sch_fmin fmin
#define sch_ldexp ldexp
/* the 4 floats of one grid point (n - 1, grad n) as one vector: loaded and blended at once */
typedef float4 sch_f4;
#define sch_f4_load(p) vload4(0, (p))
#define sch_f4_lerp(a, b, t) ((a) + (t) * ((b) - (a)))
#define sch_f4_zero() ((float4)(0.0f))
#define sch_f4_madd(acc, w, b) ((acc) + (w) * (b))
/* PoCL's CPU devices (clang) take the compiler's prefetch; the host builds with -DSCH_PREFETCH
 * there only (a GPU's compiler may not know it, and its caches are another matter) */
#ifdef SCH_PREFETCH
#define SCH_PREFETCH_LINE(p) __builtin_prefetch(p)
#endif
#else
#include <math.h>
#include <stdint.h>
#define SCH_FN static inline
#define SCH_GLOBAL
typedef uint32_t sch_uint;
typedef unsigned char sch_uchar;
#define sch_sqrt sqrtf
#define sch_floor floorf
#define sch_fabs fabsf
#define sch_isfinite isfinite
#define sch_fmin fminf
#define sch_ldexp ldexpf
#if defined(__GNUC__) || defined(__clang__)
#define SCH_PREFETCH_LINE(p) __builtin_prefetch((const void*)(p))
#endif
typedef struct
{
  float x, y, z, w;
} sch_f4;
static inline sch_f4 sch_f4_load(const float* p)
{
  sch_f4 r;
  r.x = p[0];
  r.y = p[1];
  r.z = p[2];
  r.w = p[3];
  return r;
}
static inline sch_f4 sch_f4_lerp(sch_f4 a, sch_f4 b, float t)
{
  sch_f4 r;
  r.x = a.x + t * (b.x - a.x);
  r.y = a.y + t * (b.y - a.y);
  r.z = a.z + t * (b.z - a.z);
  r.w = a.w + t * (b.w - a.w);
  return r;
}
static inline sch_f4 sch_f4_zero()
{
  sch_f4 r;
  r.x = r.y = r.z = r.w = 0.0f;
  return r;
}
/* acc + w b */
static inline sch_f4 sch_f4_madd(sch_f4 acc, float w, sch_f4 b)
{
  acc.x += w * b.x;
  acc.y += w * b.y;
  acc.z += w * b.z;
  acc.w += w * b.w;
  return acc;
}
#endif

#ifdef SCH_FIXED_INTEGRATOR
#define SCH_INTEGRATOR(P) (SCH_FIXED_INTEGRATOR)
#define SCH_USE_LEVELS(P) (SCH_FIXED_LEVELS)
#define SCH_KEEP(P) (SCH_FIXED_KEEP)
#ifdef SCH_FIXED_SOLID
#define SCH_USE_SOLID(P) (SCH_FIXED_SOLID)
#else
#define SCH_USE_SOLID(P) ((P)->useSolid)
#endif
#ifdef SCH_FIXED_RECON
#define SCH_RECON(P) (SCH_FIXED_RECON)
#else
#define SCH_RECON(P) ((P)->recon)
#endif
#else
#define SCH_RECON(P) ((P)->recon)
#define SCH_INTEGRATOR(P) ((P)->integrator)
#define SCH_USE_LEVELS(P) ((P)->useLevels)
#define SCH_KEEP(P) ((P)->keepInvariant)
#define SCH_USE_SOLID(P) ((P)->useSolid)
#endif
/* The lock-step kernel traces the film in tiles of SCH_TILE_W x SCH_TILE_ROWS pixels, bands of
 * SCH_TILE_ROWS rows (sch_tile_order); the host cuts its chunks of rays on whole bands */
#define SCH_TILE_W 8
#define SCH_TILE_ROWS 8

/* Number of floats per output ray record. */
#define SCH_RECORD 12
/* Record layout. */
#define SCH_REC_A 0         /* landing film coordinate along r (world units, from c) */
#define SCH_REC_B 1         /* landing film coordinate along t */
#define SCH_REC_EX 2        /* deflection along r (radians) */
#define SCH_REC_EY 3        /* deflection along t (radians) */
#define SCH_REC_OPL 4       /* optical path against the entry index: integral of (n - n_entry) ds */
#define SCH_REC_FLAGS 5     /* SCH_RAY_* bits, stored as a float (exact below 2^24) */
#define SCH_REC_SAMPLES 6   /* field samples taken */
#define SCH_REC_DRIFT 7     /* |v| - n at exit: the drift of the ray invariant (error indicator) */
#define SCH_REC_ERROR 8     /* step-doubling estimate of the deflection error (radians), if asked */
#define SCH_REC_PATH 9      /* geometric path length inside the volume */
#define SCH_REC_MISMATCH 10 /* the largest share of a step's index change that its end gradients  \
                             * missed (over 0.5: SCH_RAY_UNDERRESOLVED; 0 below featureTol) */
#define SCH_REC_STEPS 11    /* steps taken */

/* Ray status bits. */
#define SCH_RAY_MISSED 1u    /* never entered the volume: undeflected */
#define SCH_RAY_MAXSTEPS 2u  /* gave up after the step limit */
#define SCH_RAY_TURNED 4u    /* turned back against the beam */
#define SCH_RAY_NONFINITE 8u /* the state became NaN/Inf */
#define SCH_RAY_OFFFILM 16u  /* could not reach the film plane (parallel to it) */
#define SCH_RAY_UNDERRESOLVED                                                                      \
  32u                    /* a step jumped over structure (e.g. a shock): the result is suspect */
#define SCH_RAY_SIDE 64u /* left through a side of the box (grazing or strongly bent) */
#define SCH_RAY_BLOCKED 128u /* stopped by a solid body: no light of it reaches the film */
/* Rays whose photon is dropped from the image. */
#define SCH_RAY_LOST (SCH_RAY_MAXSTEPS | SCH_RAY_TURNED | SCH_RAY_NONFINITE | SCH_RAY_OFFFILM)

/* Integrators. */
#define SCH_EULER 0    /* the paper's explicit Euler: 1 sample per step, first order */
#define SCH_MIDPOINT 1 /* explicit midpoint: 2 samples per step, second order */
#define SCH_RK4 2      /* classical Runge-Kutta: 4 samples per step, fourth order */
#define SCH_STRAIGHT 3 /* line of sight: grad n integrated along the unbent ray (Yates 1993) */
/* velocity Verlet (Stormer-Verlet, leapfrog): 1 sample per step, second order. 5, not 4: the
 * engine's Integrator enum, which the host passes on as it is, has Auto at 4 */
#define SCH_VERLET 5

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
  int nx, ny, nz;       /* grid points */
  int maxSteps;         /* per ray */
  float isx, isy, isz;  /* 1 / spacing */
  float hx, hy, hz;     /* half extent of the box of grid points (box is [-h, h]) */
  float dx, dy, dz;     /* beam direction d0 (unit) */
  float rx, ry, rz;     /* film right axis (unit) */
  float tx, ty, tz;     /* film top axis (unit) */
  float sFront;         /* emission plane: x . d0 = sFront */
  float sFilm;          /* film plane: x . d0 = sFilm */
  float filmA0, filmB0; /* film coordinate of the lower-left corner of pixel (0,0) */
  float pixel;          /* pixel size in world units (square pixels) */
  int filmNx, filmNy;
  float step; /* base step in world units */
  sch_uint seed;
  int pass;
  int integrator;
  int jitter;               /* 0: rays through pixel centres; 1: an offset per pixel; 2: one per pass */
  int rayOffset, rayStride; /* ray k traces pixel rayOffset + k * rayStride */
  int useLevels;            /* 1: skip through octree blocks (levels buffer), 0: fixed steps */
  int keepInvariant;        /* 1: rescale v so that |v| = n after every step */
  int estimate;             /* 1: trace again at twice the base step and store the difference */
  float featureTol;         /* index change a step may leave unexplained before it is flagged */
  float cellStep;           /* the longest step that moves at most one cell along every axis */
  float gxMax, gyMax, gzMax; /* the largest grid coordinate sampled: the float below n - 1 */
  float gx0, gy0, gz0;       /* grid coordinate of the centre: -(origin - centre) / spacing */
  /* The packed field's layout (sch_axis_offset): point (i, j, k) sits at float offset
   * X(i) + Y(j) + Z(k), each term (c >> fieldShift) outer + (c & fieldMask) inner of its axis.
   * Bricks (SetFieldLayout): 2^fieldShift points a side, x fastest within a brick (a brick's row
   * of 4 points is one 64-byte line), the bricks in x, y, z order, so that a step in any direction
   * stays in the lines and pages its neighbours read. Linear (fieldShift 31, fieldMask all ones,
   * outer unused): inner 4, 4 nx, 4 nx ny, the layout of Volume::Field. */
  int fieldShift, fieldMask;
  int innerX, innerY, innerZ;
  int outerX, outerY, outerZ;
  int slabCells;              /* cells along z per slab (SCH_SLABS builds only) */
  int recon;       /* reconstruction: SCH_TRILINEAR, or SCH_CUBIC where the cell is smooth */
  float roughStep; /* SCH_CUBIC: the longest step (world units) from a cell that is not smooth */
  int useSolid;    /* 1: the cell bytes carry solid points (SCH_SOLID_BIT) that stop rays */
  /* The grid index of the first point the field and cell bytes hold: 0 for a whole volume; a
   * piece's first (ghost) point where a rank holds a piece of it. nx, ny, nz are the dimensions of
   * what is held (the strides); the grid coordinates (g0, gMax) are the whole volume's, so that a
   * sample, its cell and the octree blocks are the same whichever piece takes it. */
  int ox, oy, oz;
  /* Distributed tracing: the cells this rank owns, [own?0, own?1) along each axis (whole-grid
   * indices); a ray that steps out of them goes to the rank that owns where it went. */
  int ownX0, ownX1, ownY0, ownY1, ownZ0, ownZ1;
  /* n - 1 and grad n of every sample times this: a band's wavelength (1 for one wavelength) */
  float indexScale;
  /* 1: each step asks the cache for its next sample's lines (sch_prefetch_at), where the build has
   * a prefetch (the CPU path; OpenCL on CPU devices) */
  int prefetch;
} sch_params;

/* Reconstructions of the packed field between grid points. */
#define SCH_TRILINEAR 0 /* trilinear: second order (with central differences for grad n) */
#define SCH_CUBIC 1     /* tricubic Lagrange on the 4 x 4 x 4 points around the cell, where the
                           level byte's SCH_SMOOTH_CELL bit says the data there is smooth; trilinear
                           elsewhere: fourth order (with fourth-order differences for grad n) */

/* The per-cell byte of the levels buffer: the octree level in the low four bits; for SCH_CUBIC
 * (PackFieldHighOrder) the smoothness of the data around the cell above them. */
#define SCH_OCTREE_BITS 15
#define SCH_SMOOTH_CELL 128 /* the 4 x 4 x 4 points around the cell are smooth: cubic is safe */
#define SCH_SMOOTH_SHIFT 4  /* bits 4-6, q: every cell within 2^q cells is smooth (q = 0: none) */

/* With a solid body (useSolid; the host then traces SCH_TRILINEAR, so bits 4-7 are free of the
 * smoothness): SCH_SOLID_BIT where the point lies in a body; SCH_NEAR_BIT where a solid point lies
 * within the reach of a step (twice the base step with the step-doubling estimate) of the cell.
 * The host keeps a cell's octree level 0 where its block, with the block's one-point halo, holds a
 * solid point, so that no skip crosses a body, and near a body no step is longer than a cell, so
 * that none passes over a thin one. */
#define SCH_NEAR_BIT 0x40
#define SCH_SOLID_BIT 0x80

SCH_FN sch_v3 sch_make(float x, float y, float z)
{
  sch_v3 r;
  r.x = x;
  r.y = y;
  r.z = z;
  return r;
}
SCH_FN sch_v3 sch_add(sch_v3 a, sch_v3 b)
{
  return sch_make(a.x + b.x, a.y + b.y, a.z + b.z);
}
SCH_FN sch_v3 sch_scale(sch_v3 a, float s)
{
  return sch_make(a.x * s, a.y * s, a.z * s);
}
SCH_FN sch_v3 sch_axpy(float s, sch_v3 a, sch_v3 y)
{
  return sch_make(s * a.x + y.x, s * a.y + y.y, s * a.z + y.z);
}
SCH_FN float sch_dot(sch_v3 a, sch_v3 b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
/* A ray's position from the parts a walk keeps apart: where it entered (x0), the distance covered
 * along the beam d0, and the displacement across it (dev; zero for line of sight) */
SCH_FN sch_v3 sch_walk_at(sch_v3 x0, float along, sch_v3 d0, sch_v3 dev)
{
  return sch_add(sch_axpy(along, d0, x0), dev);
}

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
SCH_FN float sch_unit(sch_uint h)
{
  return (float)(h >> 8) * (1.0f / 16777216.0f);
}

/* ---------------------------------------------------------------- sampling */

/* The packed field: one buffer, or (OpenCL, -DSCH_SLABS=S for S = 2..4) S buffers of slabs along
 * z, for volumes over one buffer's size limit: slab q holds grid planes q K .. q K + K (K =
 * P->slabCells; one plane shared with the next slab, so that every cell lies in one slab). */
#ifdef SCH_SLABS
typedef struct
{
  SCH_GLOBAL const float* slab[SCH_SLABS];
} sch_field;
#define SCH_FIELD sch_field

/* The buffer of slab q, by comparisons (an indexed array of pointers would sit in memory). */
SCH_FN SCH_GLOBAL const float* sch_slab_base(sch_field field, int q)
{
  SCH_GLOBAL const float* base = q == 1 ? field.slab[1] : field.slab[0];
#if SCH_SLABS > 2
  base = q == 2 ? field.slab[2] : base;
#endif
#if SCH_SLABS > 3
  base = q == 3 ? field.slab[3] : base;
#endif
  return base;
}
#else
#define SCH_FIELD SCH_GLOBAL const float*
#endif

/* four flat floats (a nested sch_v3 made PoCL copy samples through the stack) */
typedef struct
{
  float n1;         /* n - 1 */
  float gx, gy, gz; /* grad n */
} sch_sample;

SCH_FN sch_v3 sch_grad(sch_sample s)
{
  return sch_make(s.gx, s.gy, s.gz);
}

/* Grid coordinate of x along one axis (x / spacing + g0, g0: that of the centre), clamped to
 * [0, hi], and the cell it falls in: what the sampler and the octree lookup both need. hi is the
 * largest float below n - 1 (sch_params), so the cell is at most n - 2 without a test of its own;
 * on the far face itself the interpolation weight is 1 - 2^-24 (relative) instead of 1. The clamp
 * is written in the operand order of the min and max instructions (a NaN ends at hi). */
SCH_FN float sch_grid_coord(float x, float is, float g0, float hi, int* c)
{
  float f = x * is + g0;
  f = f < hi ? f : hi;
  f = f > 0.0f ? f : 0.0f;
  *c = (int)f;
  return f;
}

/* The float offset along one axis of the packed field's point c (sch_params: fieldShift). */
SCH_FN long sch_axis_offset(int c, int shift, int mask, int outer, int inner)
{
  return (long)(c >> shift) * outer + (long)(c & mask) * inner;
}

/* The buffer that holds grid plane k (index in the points held), k made local to it: its slab
 * where the field is in slabs (the slab of k found by comparisons, no indexed array). */
SCH_FN SCH_GLOBAL const float* sch_field_base(SCH_FIELD field, const sch_params* P, int* k)
{
#ifdef SCH_SLABS
  const int q = *k / P->slabCells;
  *k -= q * P->slabCells;
  return sch_slab_base(field, q);
#else
  (void)P;
  (void)k;
  return field;
#endif
}

/* Trilinear interpolation of the packed field at p (relative to the centre); outside the grid the
 * nearest border value is used. *cell: the point index of the cell's first corner. */
SCH_FN sch_sample sch_sample_cell(
  SCH_FIELD field, const sch_params* P, sch_v3 p, long* cell)
{
  int i, j, k;
  float fx = sch_grid_coord(p.x, P->isx, P->gx0, P->gxMax, &i);
  float fy = sch_grid_coord(p.y, P->isy, P->gy0, P->gyMax, &j);
  float fz = sch_grid_coord(p.z, P->isz, P->gz0, P->gzMax, &k);
  float tx = fx - (float)i;
  float ty = fy - (float)j;
  float tz = fz - (float)k;
  /* the weights from the whole grid's coordinates, the address in the points held */
  i -= P->ox;
  j -= P->oy;
  k -= P->oz;
  *cell = ((long)k * P->ny + j) * P->nx + i;
  SCH_GLOBAL const float* base = sch_field_base(field, P, &k);
  const int sh = P->fieldShift, m = P->fieldMask;
  const long x0 = sch_axis_offset(i, sh, m, P->outerX, P->innerX);
  const long x1 = sch_axis_offset(i + 1, sh, m, P->outerX, P->innerX);
  const long y0 = sch_axis_offset(j, sh, m, P->outerY, P->innerY);
  const long y1 = sch_axis_offset(j + 1, sh, m, P->outerY, P->innerY);
  SCH_GLOBAL const float* c0 = base + sch_axis_offset(k, sh, m, P->outerZ, P->innerZ);
  SCH_GLOBAL const float* c1 = base + sch_axis_offset(k + 1, sh, m, P->outerZ, P->innerZ);
  /* seven lerps of the four channels at once: along x on the four edges, then y, then z */
  sch_f4 e00 = sch_f4_lerp(sch_f4_load(c0 + y0 + x0), sch_f4_load(c0 + y0 + x1), tx);
  sch_f4 e10 = sch_f4_lerp(sch_f4_load(c0 + y1 + x0), sch_f4_load(c0 + y1 + x1), tx);
  sch_f4 e01 = sch_f4_lerp(sch_f4_load(c1 + y0 + x0), sch_f4_load(c1 + y0 + x1), tx);
  sch_f4 e11 = sch_f4_lerp(sch_f4_load(c1 + y1 + x0), sch_f4_load(c1 + y1 + x1), tx);
  sch_f4 f0 = sch_f4_lerp(e00, e10, ty);
  sch_f4 f1 = sch_f4_lerp(e01, e11, ty);
  sch_f4 r = sch_f4_lerp(f0, f1, tz);
  sch_sample s;
  s.n1 = r.x;
  s.gx = r.y;
  s.gy = r.z;
  s.gz = r.w;
  return s;
}

/* a sample of the field k (n - 1) in place of n - 1: the index at another wavelength */
SCH_FN sch_sample sch_scaled(sch_sample s, float k)
{
  s.n1 *= k;
  s.gx *= k;
  s.gy *= k;
  s.gz *= k;
  return s;
}

SCH_FN sch_sample sch_sample_field(SCH_FIELD field, const sch_params* P, sch_v3 p)
{
  long cell;
  return sch_scaled(sch_sample_cell(field, P, p, &cell), P->indexScale);
}

/* 1 if p (relative to the centre) lies in a solid body: where the trilinear interpolation of the
 * solid points (SCH_SOLID_BIT of the cell bytes: 1 solid, 0 not) is at least
 * one half. The body's surface is then the half-level surface of that interpolant: it passes
 * half-way between a solid point and its fluid neighbours along the grid lines, and between
 * them it is smooth, not a staircase of voxels. */
SCH_FN int sch_solid_at(SCH_GLOBAL const sch_uchar* bytes, const sch_params* P, sch_v3 p)
{
  int i, j, k;
  float fx = sch_grid_coord(p.x, P->isx, P->gx0, P->gxMax, &i);
  float fy = sch_grid_coord(p.y, P->isy, P->gy0, P->gyMax, &j);
  float fz = sch_grid_coord(p.z, P->isz, P->gz0, P->gzMax, &k);
  float tx = fx - (float)i, ty = fy - (float)j, tz = fz - (float)k;
  i -= P->ox;
  j -= P->oy;
  k -= P->oz;
  const long sy = P->nx, sz = (long)P->nx * P->ny;
  SCH_GLOBAL const sch_uchar* c = bytes + (long)k * sz + (long)j * sy + i;
  /* SCH_SOLID_BIT is the top bit: b >> 7 is 1 in a body, 0 elsewhere */
  float e00 = (float)(c[0] >> 7) + tx * ((float)(c[1] >> 7) - (float)(c[0] >> 7));
  float e10 = (float)(c[sy] >> 7) + tx * ((float)(c[sy + 1] >> 7) - (float)(c[sy] >> 7));
  float e01 = (float)(c[sz] >> 7) + tx * ((float)(c[sz + 1] >> 7) - (float)(c[sz] >> 7));
  float e11 =
    (float)(c[sz + sy] >> 7) + tx * ((float)(c[sz + sy + 1] >> 7) - (float)(c[sz + sy] >> 7));
  float f0 = e00 + ty * (e10 - e00);
  float f1 = e01 + ty * (e11 - e01);
  return f0 + tz * (f1 - f0) >= 0.5f;
}

/* The weights of 4-point Lagrange interpolation at t in [0, 1] between the second and third of
 * the points -1, 0, 1, 2: exact for cubics, so the interpolation error is O(h^4). Scalars, not an
 * array: PoCL kept small indexed arrays in memory. */
#define SCH_CUBIC_WEIGHTS(t, w0, w1, w2, w3)                                                       \
  const float w0 = -(t) * ((t) - 1.0f) * ((t) - 2.0f) * (1.0f / 6.0f);                               \
  const float w1 = ((t) + 1.0f) * ((t) - 1.0f) * ((t) - 2.0f) * 0.5f;                                \
  const float w2 = -((t) + 1.0f) * (t) * ((t) - 2.0f) * 0.5f;                                        \
  const float w3 = ((t) + 1.0f) * (t) * ((t) - 1.0f) * (1.0f / 6.0f)

/* One row of 4 points (x - 1 .. x + 2, at row + a0 .. row + a3) blended along x. */
SCH_FN sch_f4 sch_cubic_row(SCH_GLOBAL const float* row, long a0, long a1, long a2, long a3, float w0,
  float w1, float w2, float w3)
{
  sch_f4 r = sch_f4_zero();
  r = sch_f4_madd(r, w0, sch_f4_load(row + a0));
  r = sch_f4_madd(r, w1, sch_f4_load(row + a1));
  r = sch_f4_madd(r, w2, sch_f4_load(row + a2));
  r = sch_f4_madd(r, w3, sch_f4_load(row + a3));
  return r;
}

/* The x offsets and weights of a cubic row, the arguments every row repeats. */
#define SCH_CUBIC_XS a0, a1, a2, a3, x0, x1, x2, x3

/* One plane of 4 x 4 points (rows at p + b0 .. p + b3) blended along x, then y. */
SCH_FN sch_f4 sch_cubic_plane(SCH_GLOBAL const float* p, long b0, long b1, long b2, long b3, long a0,
  long a1, long a2, long a3, float x0, float x1, float x2, float x3, float y0, float y1, float y2,
  float y3)
{
  sch_f4 r = sch_f4_zero();
  r = sch_f4_madd(r, y0, sch_cubic_row(p + b0, SCH_CUBIC_XS));
  r = sch_f4_madd(r, y1, sch_cubic_row(p + b1, SCH_CUBIC_XS));
  r = sch_f4_madd(r, y2, sch_cubic_row(p + b2, SCH_CUBIC_XS));
  r = sch_f4_madd(r, y3, sch_cubic_row(p + b3, SCH_CUBIC_XS));
  return r;
}

/* Tricubic (tensor-product Lagrange) interpolation of the packed field at p on the 4 x 4 x 4 points
 * around cell (i, j, k) (grid coordinates f): the caller has checked that the cell is smooth, which
 * also keeps the neighbourhood inside the grid (PackFieldHighOrder leaves the border cells
 * trilinear). */
SCH_FN sch_sample sch_sample_cubic_at(SCH_GLOBAL const float* base, const sch_params* P, int i,
  int j, int k, float fx, float fy, float fz)
{
  const float tx = fx - (float)i, ty = fy - (float)j, tz = fz - (float)k;
  SCH_CUBIC_WEIGHTS(tx, x0, x1, x2, x3);
  SCH_CUBIC_WEIGHTS(ty, y0, y1, y2, y3);
  SCH_CUBIC_WEIGHTS(tz, z0, z1, z2, z3);
  const int sh = P->fieldShift, m = P->fieldMask;
  const long a0 = sch_axis_offset(i - 1, sh, m, P->outerX, P->innerX);
  const long a1 = sch_axis_offset(i, sh, m, P->outerX, P->innerX);
  const long a2 = sch_axis_offset(i + 1, sh, m, P->outerX, P->innerX);
  const long a3 = sch_axis_offset(i + 2, sh, m, P->outerX, P->innerX);
  const long b0 = sch_axis_offset(j - 1, sh, m, P->outerY, P->innerY);
  const long b1 = sch_axis_offset(j, sh, m, P->outerY, P->innerY);
  const long b2 = sch_axis_offset(j + 1, sh, m, P->outerY, P->innerY);
  const long b3 = sch_axis_offset(j + 2, sh, m, P->outerY, P->innerY);
  sch_f4 r = sch_f4_zero();
  r = sch_f4_madd(r, z0,
    sch_cubic_plane(base + sch_axis_offset(k - 1, sh, m, P->outerZ, P->innerZ), b0, b1, b2, b3,
      SCH_CUBIC_XS, y0, y1, y2, y3));
  r = sch_f4_madd(r, z1,
    sch_cubic_plane(base + sch_axis_offset(k, sh, m, P->outerZ, P->innerZ), b0, b1, b2, b3,
      SCH_CUBIC_XS, y0, y1, y2, y3));
  r = sch_f4_madd(r, z2,
    sch_cubic_plane(base + sch_axis_offset(k + 1, sh, m, P->outerZ, P->innerZ), b0, b1, b2, b3,
      SCH_CUBIC_XS, y0, y1, y2, y3));
  r = sch_f4_madd(r, z3,
    sch_cubic_plane(base + sch_axis_offset(k + 2, sh, m, P->outerZ, P->innerZ), b0, b1, b2, b3,
      SCH_CUBIC_XS, y0, y1, y2, y3));
  sch_sample s;
  s.n1 = r.x;
  s.gx = r.y;
  s.gy = r.z;
  s.gz = r.w;
  return s;
}

/* The field at p under the trace's reconstruction: tricubic where the cell's level byte says the
 * data around it is smooth (SCH_CUBIC), trilinear elsewhere (and always for SCH_TRILINEAR, which
 * reads no level here). *cell: as sch_sample_cell. */
SCH_FN sch_sample sch_sample_at(SCH_FIELD field, SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P, sch_v3 p, long* cell)
{
  if (SCH_RECON(P) == SCH_CUBIC)
  {
    int i, j, k;
    float fx = sch_grid_coord(p.x, P->isx, P->gx0, P->gxMax, &i);
    float fy = sch_grid_coord(p.y, P->isy, P->gy0, P->gyMax, &j);
    float fz = sch_grid_coord(p.z, P->isz, P->gz0, P->gzMax, &k);
    /* local indices and grid coordinates: the same fractions (an integer offset of a float below
     * 2^24 is exact) */
    i -= P->ox;
    j -= P->oy;
    k -= P->oz;
    fx -= (float)P->ox;
    fy -= (float)P->oy;
    fz -= (float)P->oz;
    *cell = ((long)k * P->ny + j) * P->nx + i;
    if (levels[*cell] & SCH_SMOOTH_CELL)
    {
#ifdef SCH_SLABS
      /* the 4 planes k - 1 .. k + 2 must lie in cell k's slab (which holds its planes q K .. q K +
       * K): the first and last cell of a slab stay trilinear */
      const int q = k / P->slabCells;
      const int kk = k - q * P->slabCells;
      if (kk >= 1 && kk + 2 <= P->slabCells)
      {
        return sch_scaled(sch_sample_cubic_at(sch_slab_base(field, q), P, i, j, kk, fx, fy,
                            fz - (float)(q * P->slabCells)),
          P->indexScale);
      }
#else
      return sch_scaled(sch_sample_cubic_at(field, P, i, j, k, fx, fy, fz), P->indexScale);
#endif
    }
  }
  return sch_scaled(sch_sample_cell(field, P, p, cell), P->indexScale);
}

SCH_FN sch_sample sch_sample_pt(SCH_FIELD field, SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P, sch_v3 p)
{
  long cell;
  return sch_sample_at(field, levels, P, p, &cell);
}

/* Asks the cache for the lines a sample at p will read (the cell byte and the points around p: the
 * 2 x 2 x 2 of a trilinear sample, the 4 x 4 x 4 of a tricubic one), where the build has a prefetch
 * (SCH_PREFETCH_LINE: the CPU path, and PoCL's CPU devices with -DSCH_PREFETCH). A walk asks for
 * its next sample while it takes this one: the other rays of its packet step in between, so the
 * lines arrive before they are read. Without it an oblique ray waits on memory at every sample: its
 * packet's rays read lines far apart (rows and planes of the field), where along an axis they read
 * neighbouring lines that the hardware's own prefetch brings in (issue 50: 512^3 oblique 2.3-3.9x
 * the axis view's time a sample). A prefetch never faults: p is clamped as a sample is, and a
 * cubic neighbourhood's rows past the grid's edge are only asked for, not read. */
#ifdef SCH_PREFETCH_LINE
/* always inlined: GCC takes a function that only prefetches for one without effects and drops the
 * call */
#ifdef __OPENCL_VERSION__
SCH_FN
#else
static inline __attribute__((always_inline))
#endif
void sch_prefetch_at(SCH_FIELD field, SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P, sch_v3 p)
{
  int i, j, k;
  sch_grid_coord(p.x, P->isx, P->gx0, P->gxMax, &i);
  sch_grid_coord(p.y, P->isy, P->gy0, P->gyMax, &j);
  sch_grid_coord(p.z, P->isz, P->gz0, P->gzMax, &k);
  i -= P->ox;
  j -= P->oy;
  k -= P->oz;
  const int sh = P->fieldShift, m = P->fieldMask;
  const int cubic = SCH_RECON(P) == SCH_CUBIC;
  if (cubic | SCH_USE_LEVELS(P) | SCH_USE_SOLID(P))
    SCH_PREFETCH_LINE(levels + ((long)k * P->ny + j) * P->nx + i);
  const int lo = cubic ? -1 : 0, hi = cubic ? 2 : 1;
  SCH_GLOBAL const float* base = sch_field_base(field, P, &k);
  const long xa = sch_axis_offset(i + lo, sh, m, P->outerX, P->innerX);
  const long xb = sch_axis_offset(i + hi, sh, m, P->outerX, P->innerX);
  for (int c = k + lo; c <= k + hi; ++c)
  {
    SCH_GLOBAL const float* plane = base + sch_axis_offset(c, sh, m, P->outerZ, P->innerZ);
    for (int b = j + lo; b <= j + hi; ++b)
    {
      SCH_GLOBAL const float* row = plane + sch_axis_offset(b, sh, m, P->outerY, P->innerY);
      SCH_PREFETCH_LINE(row + xa);
      SCH_PREFETCH_LINE(row + xb + 3);
    }
  }
}
#endif

/* ---------------------------------------------------------------- geometry */

SCH_FN int sch_inside(const sch_params* P, sch_v3 p)
{
  return sch_fabs(p.x) <= P->hx && sch_fabs(p.y) <= P->hy && sch_fabs(p.z) <= P->hz;
}

/* Slab test of the line o + s d against the box [-h, h]; returns 1 and the parameter range on a
 * hit. */
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

/* Film coordinates of ray pixel `pix` in pass P->pass: jittered inside the pixel or at its centre.
 */
SCH_FN void sch_emit(const sch_params* P, int pix, float* a, float* b)
{
  int ix = pix % P->filmNx;
  int iy = pix / P->filmNx;
  float jx = 0.5f, jy = 0.5f;
  if (P->jitter)
  {
    /* a random offset per pixel and seed (jitter 1), or one per seed for every pixel (2: the
     * pixel grid shifted as a whole), then the R2 low-discrepancy sequence over the passes
     * (additive recurrence with the plastic number): the passes of a pixel never repeat and fill
     * it evenly, and the same seed gives the same photons */
    sch_uint h = P->jitter == 2 ? sch_hash(P->seed ^ 0x5bd1e995u)
                                : sch_hash(P->seed ^ sch_hash((sch_uint)pix * 2654435761u + 0x9e3779b9u));
    float ox = sch_unit(h), oy = sch_unit(sch_hash(h ^ 0x68bc21ebu));
    float p = (float)P->pass;
    jx = ox + p * 0.7548776662f;
    jy = oy + p * 0.5698402910f;
    jx -= sch_floor(jx);
    jy -= sch_floor(jy);
  }
  *a = P->filmA0 + ((float)ix + jx) * P->pixel;
  *b = P->filmB0 + ((float)iy + jy) * P->pixel;
}

/* ---------------------------------------------------------------- tracing */

/* |v| - n computed without cancellation: v = ne d0 + w with ne = 1 + ne1, n = 1 + n1. */
SCH_FN float sch_invariant_gap(float ne1, float n1, sch_v3 d0, sch_v3 w)
{
  float ne = 1.0f + ne1, n = 1.0f + n1;
  sch_v3 v = sch_axpy(ne, d0, w);
  float vn = sch_sqrt(sch_dot(v, v));
  /* |v|^2 - n^2 = 2 ne d0.w + |w|^2 - (n1 - ne1)(n + ne) */
  float num = 2.0f * ne * sch_dot(d0, w) + sch_dot(w, w) - (n1 - ne1) * (n + ne);
  return num / (vn + n);
}

/* The step allowed at x: the base step, or the distance to the far side of the octree block that
 * holds x when that is longer (paper section 4.2; the block is uniform within the tolerance, with a
 * one-voxel halo, so the ray may cross it in one straight step). */
/* Along one axis: the distance (in steps of the direction's component dI, cells per unit length)
 * from the grid coordinate f in cell c to the face of its block of B = 2^lvl cells that the ray
 * heads for. The block starts at cell (c >> lvl) << lvl (integers: floor() is a library call in
 * PoCL). */
SCH_FN float sch_block_exit(float f, int c, int lvl, float B, float dI)
{
  float lo = (float)((c >> lvl) << lvl);
  if (dI > 1e-20f)
    return (lo + B - f) / dI;
  if (dI < -1e-20f)
    return (f - lo) / -dI;
  return 1e30f;
}

/* The step from x along dir: across the rest of x's block when its level lvl (looked up with the
 * sample at x) is above 0, else the base step. */
SCH_FN float sch_skip(const sch_params* P, sch_v3 x, sch_v3 dir, float base, int lvl)
{
  if (lvl == 0)
    return base;
  /* per axis, without arrays: PoCL kept small indexed arrays in memory, and this runs every step */
  int i, j, k;
  float fx = sch_grid_coord(x.x, P->isx, P->gx0, P->gxMax, &i);
  float fy = sch_grid_coord(x.y, P->isy, P->gy0, P->gyMax, &j);
  float fz = sch_grid_coord(x.z, P->isz, P->gz0, P->gzMax, &k);
  float B = (float)(1 << lvl);
  /* the nearest face, by comparison (fmin's NaN rules made the grid clamp slower on PoCL) */
  float t = sch_block_exit(fx, i, lvl, B, dir.x * P->isx);
  float ty = sch_block_exit(fy, j, lvl, B, dir.y * P->isy);
  float tz = sch_block_exit(fz, k, lvl, B, dir.z * P->isz);
  t = ty < t ? ty : t;
  t = tz < t ? tz : t;
  /* a hair past the block face, so that the next lookup sees the next block */
  t += 0.01f * base;
  return t > base ? t : base;
}

/* Distance from x (inside the box) along the unit direction d to the box's boundary. */
SCH_FN float sch_exit_distance(const sch_params* P, sch_v3 x, sch_v3 d)
{
  float t = 1e30f;
  if (d.x > 1e-20f)
    t = sch_fmin(t, (P->hx - x.x) / d.x);
  else if (d.x < -1e-20f)
    t = sch_fmin(t, (-P->hx - x.x) / d.x);
  if (d.y > 1e-20f)
    t = sch_fmin(t, (P->hy - x.y) / d.y);
  else if (d.y < -1e-20f)
    t = sch_fmin(t, (-P->hy - x.y) / d.y);
  if (d.z > 1e-20f)
    t = sch_fmin(t, (P->hz - x.z) / d.z);
  else if (d.z < -1e-20f)
    t = sch_fmin(t, (-P->hz - x.z) / d.z);
  return t > 0.0f ? t : 0.0f;
}

/* The step ds from x along dir, cut at the box: the last step ends on the box (a hair past it),
 * so no gradient is integrated beyond the data, and a ray on the boundary heading out (a grazing
 * ray on a face) has left. Only a step whose straight end point is outside pays for the exact
 * distance. Returns 1 where the step stays inside (ds unchanged), 2 where it was cut (the last
 * step), 0 where the ray has left (after its first step, `it` > 0). */
SCH_FN int sch_box_step(const sch_params* P, sch_v3 x, sch_v3 dir, int it, float base, float* ds)
{
  if (sch_inside(P, sch_axpy(*ds, dir, x)))
    return 1;
  float tex = sch_exit_distance(P, x, dir);
  if (it > 0 && tex < 1e-3f * base)
    return 0;
  tex += 1e-4f * base;
  *ds = *ds < tex ? *ds : tex;
  return 2;
}

typedef struct
{
  sch_v3 x;   /* where the ray left the volume (on the box, a hair outside) */
  sch_v3 dev; /* integral of w / n ds: how far the ray moved across the beam */
  sch_v3 w;   /* integral of grad n ds */
  float ne1;  /* n - 1 where it entered */
  float n1;   /* n - 1 at the last sample */
  float opl, path, samples, steps, mismatch;
  sch_uint flags;
} sch_ray;

/* The state of one ray's march: the whole loop of sch_march, one step at a time, so that a
 * work-item can advance several rays in turn (their memory accesses then overlap). */
typedef struct
{
  /* x is kept as x0 + along d0 + dev (x0 where the ray entered, along the distance covered along
   * the beam, dev the displacement that w turns it by): each position is rounded once, from
   * parts that keep their digits, instead of every step's rounding of x summed across the beam.
   * along is summed with its rounding carried (alongLo, compensated summation): its error would
   * otherwise move the ray along the beam, and across it where the ray is strongly bent */
  sch_v3 x, w, dev, x0;
  float along, alongLo;
  sch_sample s;
  float ne1, ne, base;
  float invn; /* 1 / n at x */
  int level;  /* octree level of x's cell (with levels) */
  int nearSolid; /* x's cell is within a step's reach of a solid body (SCH_NEAR_BIT) */
  float samples, opl, path, mismatch;
  sch_uint flags;
  int it;
} sch_walk;

/* A ray of distributed tracing as it goes from rank to rank: which ray, where it started, its
 * march (the host and every device lay it out alike: 4-byte members only). */
typedef struct
{
  sch_uint index;
  float a, b, s1;
  sch_v3 o, entry;
  sch_walk w;
} sch_piece_ray;

/* 1 if x (relative to the centre) is in a cell this rank owns (P->own*), found as the sampler
 * finds its cell. */
SCH_FN int sch_owns(const sch_params* P, sch_v3 x)
{
  int i, j, k;
  sch_grid_coord(x.x, P->isx, P->gx0, P->gxMax, &i);
  sch_grid_coord(x.y, P->isy, P->gy0, P->gyMax, &j);
  sch_grid_coord(x.z, P->isz, P->gz0, P->gzMax, &k);
  return i >= P->ownX0 && i < P->ownX1 && j >= P->ownY0 && j < P->ownY1 && k >= P->ownZ0 &&
    k < P->ownZ1;
}

SCH_FN void sch_walk_begin(SCH_FIELD field,
  SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P,
  sch_v3 x,
  float base,
  SCH_WALK_AS sch_walk* W)
{
  W->x = x;
  W->x0 = x;
  W->along = W->alongLo = 0.0f;
  W->w = sch_make(0.0f, 0.0f, 0.0f);
  W->dev = sch_make(0.0f, 0.0f, 0.0f);
  W->flags = 0u;
  W->samples = 1.0f;
  W->opl = W->path = W->mismatch = 0.0f;
  W->base = base;
  W->it = 0;
  /* the index where the ray enters is the background the deflection is measured against */
  long cell;
  W->s = sch_sample_at(field, levels, P, x, &cell);
  W->level = (SCH_USE_LEVELS(P) | (SCH_RECON(P) == SCH_CUBIC)) ? (int)levels[cell] : 0;
  W->nearSolid = SCH_USE_SOLID(P) ? (int)(levels[cell] & SCH_NEAR_BIT) : 0;
  /* a ray that enters inside a body (one that touches the box) is stopped where it enters */
  if (SCH_USE_SOLID(P) && sch_solid_at(levels, P, x))
    W->flags |= SCH_RAY_BLOCKED;
  W->ne1 = W->s.n1;
  W->ne = 1.0f + W->ne1;
  W->invn = 1.0f / W->ne;
}

/* Verlet's closing half kick of a ray's last step (ds long), which ends outside the box: the
 * sample where it left (counted), the other half of the step's kick and of its optical path. */
SCH_FN void sch_verlet_last(SCH_FIELD field,
  SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P,
  SCH_WALK_AS sch_walk* W,
  float ds)
{
  const sch_sample se = sch_sample_pt(field, levels, P, W->x);
  W->samples += 1.0f;
  W->w = sch_axpy(0.5f * ds, sch_grad(se), W->w);
  W->opl += 0.5f * ds * se.n1;
}

/* One step; returns 0 when the ray has left the box or failed. */
SCH_FN int sch_walk_step(SCH_FIELD field,
  SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P,
  SCH_WALK_AS sch_walk* W)
{
  if (W->it >= P->maxSteps)
    return 0;
  if (SCH_USE_SOLID(P) && (W->flags & SCH_RAY_BLOCKED))
    return 0;
  sch_v3 d0 = sch_make(P->dx, P->dy, P->dz);
  sch_v3 v = sch_axpy(W->ne, d0, W->w);
  /* 1 / n was taken with the last sample, off the path from this step's start to its sample:
   * the lock-step kernel is bound by that path's latency */
  float invn = W->invn;
  float ds = W->base;
  /* v / n is the unit direction to first order (|v| = n): good enough to aim the step. Line of
   * sight steps along the unbent beam d0, so it aims along d0: aimed along v / n, a ray grazing a
   * face that the gradient tilts it towards takes ever shorter steps and never leaves */
  sch_v3 dir = sch_scale(v, invn);
  if (SCH_INTEGRATOR(P) == SCH_STRAIGHT)
    dir = d0;
  if (SCH_RECON(P) == SCH_CUBIC)
  {
    /* steps sized by the field: the base step only where every cell within 2^q cells is smooth
     * (level bits 4-6), so that a long step stays in smooth data; from other cells at most
     * roughStep (a cell), so that no step jumps a shock or an interface */
    const int q = (W->level >> SCH_SMOOTH_SHIFT) & 7;
    const float room = q > 0 ? (float)((1 << q) - 1) * P->cellStep : 0.0f;
    const float cap = room > P->roughStep ? room : P->roughStep;
    ds = ds < cap ? ds : cap;
  }
  if (SCH_USE_LEVELS(P))
    ds = sch_skip(P, W->x, dir, ds, W->level & SCH_OCTREE_BITS);
  /* next to a body no step is longer than a cell: a longer one could pass over a thin body */
  if (SCH_USE_SOLID(P) && W->nearSolid)
    ds = ds < P->cellStep ? ds : P->cellStep;
  const int fit = sch_box_step(P, W->x, dir, W->it, W->base, &ds);
  if (!fit)
    return 0;
  const int whole = fit == 1; /* the straight end point is inside: not the last step */
  /* ddev: the step's part across the beam, w / n, summed apart from x so that the sideways
   * displacement keeps its digits next to coordinates of order one */
  /* dal: the step's part along d0 (ne / n of ds, the d0 part of v / n); the end point is then
   * put together from the walk's parts (sch_walk_at), not summed into x */
  sch_v3 dw, ddev;
  float dopl, dal;
  if (SCH_INTEGRATOR(P) == SCH_STRAIGHT)
  {
    dal = ds;
    dw = sch_scale(sch_grad(W->s), ds);
    /* sampled along the unbent line, but the photon lands where the first-order (weak-field)
     * deflection takes it, as with the curved schemes */
    ddev = sch_scale(W->w, ds * invn);
    dopl = ds * (W->s.n1 - W->ne1);
  }
  else if (SCH_INTEGRATOR(P) == SCH_MIDPOINT)
  {
    /* half step with the slope at x, full step with the slope at the midpoint */
    sch_v3 xm = sch_axpy(0.5f * ds * invn, v, W->x);
    sch_v3 vm = sch_axpy(0.5f * ds, sch_grad(W->s), v);
    sch_sample sm = sch_sample_pt(field, levels, P, xm);
    W->samples += 1.0f;
    const float dsm = ds / (1.0f + sm.n1);
    dal = W->ne * dsm;
    dw = sch_scale(sch_grad(sm), ds);
    ddev = sch_scale(sch_axpy(0.5f * ds, sch_grad(W->s), W->w), dsm);
    dopl = ds * (sm.n1 - W->ne1);
  }
  else if (SCH_INTEGRATOR(P) == SCH_RK4)
  {
    /* classical RK4 on dx/ds = v / n, dv/ds = grad n */
    sch_v3 k1x = sch_scale(v, invn);
    sch_sample sa = sch_sample_pt(field, levels, P, sch_axpy(0.5f * ds, k1x, W->x));
    const float ia = 1.0f / (1.0f + sa.n1);
    sch_v3 v2 = sch_axpy(0.5f * ds, sch_grad(W->s), v);
    sch_v3 k2x = sch_scale(v2, ia);
    sch_sample sb = sch_sample_pt(field, levels, P, sch_axpy(0.5f * ds, k2x, W->x));
    const float ib = 1.0f / (1.0f + sb.n1);
    sch_v3 v3 = sch_axpy(0.5f * ds, sch_grad(sa), v);
    sch_v3 k3x = sch_scale(v3, ib);
    sch_sample sc = sch_sample_pt(field, levels, P, sch_axpy(ds, k3x, W->x));
    const float ic = 1.0f / (1.0f + sc.n1);
    W->samples += 3.0f;
    sch_v3 kw = sch_add(
      sch_add(sch_grad(W->s), sch_grad(sc)), sch_scale(sch_add(sch_grad(sa), sch_grad(sb)), 2.0f));
    dw = sch_scale(kw, ds / 6.0f);
    /* the same stages with v_i = ne d0 + w_i: the d0 parts ne / n_i and the w_i / n_i parts */
    dal = ds / 6.0f * W->ne * (invn + ic + 2.0f * (ia + ib));
    sch_v3 d1 = sch_scale(W->w, invn);
    sch_v3 d2 = sch_scale(sch_axpy(0.5f * ds, sch_grad(W->s), W->w), ia);
    sch_v3 d3 = sch_scale(sch_axpy(0.5f * ds, sch_grad(sa), W->w), ib);
    sch_v3 d4 = sch_scale(sch_axpy(ds, sch_grad(sb), W->w), ic);
    ddev = sch_scale(sch_add(sch_add(d1, d4), sch_scale(sch_add(d2, d3), 2.0f)), ds / 6.0f);
    dopl = ds / 6.0f * (W->s.n1 + sc.n1 + 2.0f * (sa.n1 + sb.n1) - 6.0f * W->ne1);
  }
  else if (SCH_INTEGRATOR(P) == SCH_VERLET)
  {
    /* velocity Verlet: half a kick with the gradient at x, the drift with the slope it gives,
     * the other half kick with the gradient where the step ends (after that sample, below). The
     * same one sample a step as Euler, but second order: Euler's drift lags by the whole step's
     * kick, which is the error it leaves (issue 50: 2e-8 rad at 27 voxels at 512^3) */
    const sch_v3 g = sch_grad(W->s);
    /* 1 / n half a step on, to first order (dn/ds = g . v / n): with 1 / n of the step's start
     * the drift is off by O(ds^2 dn/ds) a step, first order over the ray (on a linear gradient
     * of the test's, order 0.8 in the landing point) */
    const float invh = invn * (1.0f - 0.5f * ds * sch_dot(g, v) * invn * invn);
    dal = ds * invh * W->ne;
    dw = sch_scale(g, 0.5f * ds);
    ddev = sch_scale(sch_axpy(0.5f * ds, g, W->w), ds * invh);
    /* the optical path by the trapezoid: this end's half now, the other's with its sample */
    dopl = 0.5f * ds * (W->s.n1 - 2.0f * W->ne1);
  }
  else
  {
    /* the paper's explicit Euler: x += ds v / n, v += ds grad n (v / n is dir: the end point is
     * the one checked above, to rounding) */
    dal = ds * invn * W->ne;
    dw = sch_scale(sch_grad(W->s), ds);
    ddev = sch_scale(W->w, ds * invn);
    dopl = ds * (W->s.n1 - W->ne1);
  }
  {
    const float y = dal - W->alongLo;
    const float t = W->along + y;
    W->alongLo = (t - W->along) - y;
    W->along = t;
  }
  W->dev = sch_add(W->dev, ddev);
  const sch_v3 xn = sch_walk_at(W->x0, W->along, d0,
    SCH_INTEGRATOR(P) == SCH_STRAIGHT ? sch_make(0.0f, 0.0f, 0.0f) : W->dev);
  sch_v3 dx = sch_add(xn, sch_scale(W->x, -1.0f));
  W->x = xn;
  W->w = sch_add(W->w, dw);
  W->opl += dopl;
  W->path += ds;
  /* a NaN fails every comparison: it leaves the loop through the exit test below and is caught
   * in sch_walk_end, as is a ray that turned back against the beam (it marches back out through
   * the front or a side: a test here costs a measurable part of the step) */
  /* Euler and line of sight end where the check above aimed: a whole step inside, a cut one a
   * hair outside. The other schemes bend away from that line and look again. */
  const int aimed = (SCH_INTEGRATOR(P) == SCH_EULER) | (SCH_INTEGRATOR(P) == SCH_STRAIGHT);
  if (aimed ? !whole : !sch_inside(P, W->x))
  {
    /* Verlet's last half kick, with the gradient where the ray left (a hair outside: the sampler
     * takes the boundary's data), so that the last step is second order too */
    if (SCH_INTEGRATOR(P) == SCH_VERLET)
      sch_verlet_last(field, levels, P, W, ds);
    return 0;
  }
  /* a body stops the ray where a step ends in it; only where the step began within a step's reach
   * of a body (SCH_NEAR_BIT) can it end in one. Near a body steps are at most a cell long (and no
   * octree skip crosses one), so a step cannot pass over a plate of solid points one point thick
   * (its half-level surfaces lie half a spacing either side); it can clip an edge of a body */
  if (SCH_USE_SOLID(P) && W->nearSolid && sch_solid_at(levels, P, W->x))
  {
    W->flags |= SCH_RAY_BLOCKED;
    W->it++;
    return 0;
  }
#ifdef SCH_PREFETCH_LINE
  /* the next step's end, as far along as this one went (sch_prefetch_at) */
  if (P->prefetch)
    sch_prefetch_at(field, levels, P, sch_axpy(ds, dir, W->x));
#endif
  /* the sample at the end of a step is counted by it (sch_walk_end), W->samples counts the others */
  long cell;
  sch_sample sn = sch_sample_at(field, levels, P, W->x, &cell);
  if (SCH_USE_LEVELS(P) | (SCH_RECON(P) == SCH_CUBIC))
    W->level = (int)levels[cell];
  if (SCH_USE_SOLID(P))
    W->nearSolid = (int)(levels[cell] & SCH_NEAR_BIT);
  if (SCH_INTEGRATOR(P) == SCH_VERLET)
  {
    W->w = sch_axpy(0.5f * ds, sch_grad(sn), W->w);
    W->opl += 0.5f * ds * sn.n1;
  }
  /* a step longer than a feature: over a step of more than one cell, the index changed in a way
   * that the gradients at both ends (trapezoidal rule) do not explain, by more than half of what
   * the step saw: the larger of the index's change and the change its end gradients speak of
   * (the step times their mean size along it). Across a jump the ends lie in uniform data and the
   * change is the jump; across a smooth crest inside the step the index changes little while the
   * gradients at its ends speak of much, and the trapezoid's own error (the step cubed) is
   * measured against that (issue 50: on the Gaussian of width 64 voxels the check fired at 53.8
   * voxels, 3.7e-9 rad off; now it fires from 64, where the error grows 7.5-fold). Steps of a
   * cell or less cannot jump over anything: trilinear data has no structure finer than a cell. */
  if (SCH_INTEGRATOR(P) != SCH_STRAIGHT && (ds > P->cellStep || SCH_USE_LEVELS(P)))
  {
    float act = sn.n1 - W->s.n1;
    float mis = sch_fabs(act - 0.5f * sch_dot(sch_add(sch_grad(W->s), sch_grad(sn)), dx));
    float saw = 0.5f * (sch_fabs(sch_dot(sch_grad(W->s), dx)) + sch_fabs(sch_dot(sch_grad(sn), dx)));
    saw = saw > sch_fabs(act) ? saw : sch_fabs(act);
    float cells = sch_fabs(dx.x) * P->isx;
    cells = sch_fabs(dx.y) * P->isy > cells ? sch_fabs(dx.y) * P->isy : cells;
    cells = sch_fabs(dx.z) * P->isz > cells ? sch_fabs(dx.z) * P->isz : cells;
    if (cells > 1.0f)
    {
      /* the share of what the step saw that it missed (0 where the miss is below the feature
       * tolerance); the record keeps the largest, so that Auto's pilot can keep a margin */
      float share = mis > P->featureTol ? mis / saw : 0.0f;
      W->mismatch = share > W->mismatch ? share : W->mismatch;
      if (share > 0.5f)
        W->flags |= SCH_RAY_UNDERRESOLVED;
    }
  }
  if (SCH_KEEP(P))
  {
    /* rescale v to |v| = n(x); written so that no term near 1 is subtracted */
    float gap = sch_invariant_gap(W->ne1, sn.n1, d0, W->w);
    sch_v3 vv = sch_axpy(W->ne, d0, W->w);
    float scale = -gap / sch_sqrt(sch_dot(vv, vv)); /* scale - 1 */
    W->w = sch_add(sch_scale(W->w, 1.0f + scale), sch_scale(d0, W->ne * scale));
  }
  W->s = sn;
  W->invn = 1.0f / (1.0f + sn.n1);
  W->it++;
  return 1;
}

/* After the last step: the final flags and the record of the march. */
SCH_FN void sch_walk_end(SCH_FIELD field,
  const sch_params* P,
  SCH_WALK_AS sch_walk* W,
  sch_ray* R)
{
  if (!(sch_isfinite(W->x.x) && sch_isfinite(W->x.y) && sch_isfinite(W->x.z) &&
        sch_isfinite(W->w.x) && sch_isfinite(W->w.y) && sch_isfinite(W->w.z)))
    W->flags |= SCH_RAY_NONFINITE;
  if (W->it >= P->maxSteps)
    W->flags |= SCH_RAY_MAXSTEPS;
  else if (!(W->flags & (SCH_RAY_NONFINITE | SCH_RAY_BLOCKED)))
  {
    /* heading back against the beam where it left (a mirage): it never reaches the film */
    if (W->ne + sch_dot(sch_make(P->dx, P->dy, P->dz), W->w) <= 0.0f)
      W->flags |= SCH_RAY_TURNED;
    else
      W->s = sch_sample_field(field, P, W->x); /* the index where it left, for |v| = n */
  }
  R->x = W->x;
  R->dev = W->dev;
  R->w = W->w;
  R->ne1 = W->ne1;
  R->n1 = W->s.n1;
  R->opl = W->opl;
  R->path = W->path;
  R->samples = W->samples + (float)W->it;
  R->steps = (float)W->it;
  R->mismatch = W->mismatch;
  R->flags = W->flags;
}

#ifdef SCH_PRIVATE_WALKS
/* March from x (on the box) with base step `base` until the ray leaves the box. */
SCH_FN void sch_march(SCH_FIELD field,
  SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P,
  sch_v3 x,
  float base,
  sch_ray* R)
{
  sch_walk W;
  sch_walk_begin(field, levels, P, x, base, &W);
  while (sch_walk_step(field, levels, P, &W))
    ;
  sch_walk_end(field, P, &W, R);
}

#endif

/* Deflection of a marched ray on the film axes: (w . r, w . t) / |v|. */
SCH_FN void sch_deflection(const sch_params* P, const sch_ray* R, float* ex, float* ey)
{
  sch_v3 d0 = sch_make(P->dx, P->dy, P->dz);
  sch_v3 v = sch_axpy(1.0f + R->ne1, d0, R->w);
  float vn = sch_sqrt(sch_dot(v, v));
  *ex = sch_dot(R->w, sch_make(P->rx, P->ry, P->rz)) / vn;
  *ey = sch_dot(R->w, sch_make(P->tx, P->ty, P->tz)) / vn;
}

/* Where the ray of film point (a, b) starts (o, on the emission plane) and enters the box (entry);
 * s1 is where the straight line would leave it. Returns 0 if the ray misses the box. */
SCH_FN int sch_entry(const sch_params* P, float a, float b, sch_v3* o, sch_v3* entry, float* s1)
{
  sch_v3 d0 = sch_make(P->dx, P->dy, P->dz);
  *o = sch_add(sch_add(sch_scale(sch_make(P->rx, P->ry, P->rz), a),
                 sch_scale(sch_make(P->tx, P->ty, P->tz), b)),
    sch_scale(d0, P->sFront));
  float s0;
  if (!sch_clip_box(P, *o, d0, &s0, s1) || *s1 <= 0.0f)
  {
    *entry = *o;
    return 0;
  }
  *entry = sch_axpy(s0 > 0.0f ? s0 : 0.0f, d0, *o);
  return 1;
}

/* A ray that missed the box: straight, undeflected. */
SCH_FN void sch_missed(sch_v3 o, sch_ray* R)
{
  R->x = o;
  R->w = sch_make(0.0f, 0.0f, 0.0f);
  R->dev = sch_make(0.0f, 0.0f, 0.0f);
  R->ne1 = R->n1 = R->opl = R->path = R->samples = R->steps = R->mismatch = 0.0f;
  R->flags = SCH_RAY_MISSED;
}

/* Step doubling: the deflection error estimated from the deflections of a ray at the base step
 * (1) and at twice it (2), scaled by the scheme's order. */
SCH_FN float sch_doubling_error(int integrator, float ex1, float ey1, float ex2, float ey2)
{
  float order = integrator == SCH_RK4 ? 15.0f
    : ((integrator == SCH_MIDPOINT) | (integrator == SCH_VERLET)) ? 3.0f
                                                                  : 1.0f;
  return sch_sqrt((ex1 - ex2) * (ex1 - ex2) + (ey1 - ey2) * (ey1 - ey2)) / order;
}

/* The record of a marched (or missed) ray: side exits, the step-doubling estimate, deflection,
 * and the flight to the film. */
SCH_FN void sch_record(SCH_FIELD field,
  SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P,
  float a,
  float b,
  sch_v3 o,
  sch_v3 entry,
  float s1,
  sch_ray* Rp,
  SCH_RECORD_AS float* rec)
{
  sch_ray R = *Rp;
  sch_v3 d0 = sch_make(P->dx, P->dy, P->dz);
  sch_v3 ra = sch_make(P->rx, P->ry, P->rz);
  sch_v3 ta = sch_make(P->tx, P->ty, P->tz);
  float err = 0.0f;
  if (!(R.flags & SCH_RAY_MISSED))
  {
    /* it left through a side if the exit point is not beyond the back of the box */
    if (!(R.flags & (SCH_RAY_LOST | SCH_RAY_BLOCKED)) &&
      sch_dot(sch_axpy(-s1, d0, sch_axpy(-1.0f, o, R.x)), d0) < -P->step)
      R.flags |= SCH_RAY_SIDE;
#ifdef SCH_PRIVATE_WALKS
    if (P->estimate && !(R.flags & SCH_RAY_BLOCKED))
    {
      /* step doubling: the difference to a trace at twice the step, scaled by the scheme's order */
      sch_ray R2;
      sch_march(field, levels, P, entry, 2.0f * P->step, &R2);
      float ex1, ey1, ex2, ey2;
      sch_deflection(P, &R, &ex1, &ey1);
      sch_deflection(P, &R2, &ex2, &ey2);
      /* a ray the doubled step stops at a body has no deflection to compare */
      if (!(R2.flags & SCH_RAY_BLOCKED))
        err = sch_doubling_error(P->integrator, ex1, ey1, ex2, ey2);
      R.samples += R2.samples;
    }
#endif
  }
  float ex, ey;
  sch_deflection(P, &R, &ex, &ey);
  sch_v3 v = sch_axpy(1.0f + R.ne1, d0, R.w);
  float vn = sch_sqrt(sch_dot(v, v));
  /* straight flight from the exit point to the film plane */
  float dd = sch_dot(v, d0) / vn;
  /* across the beam: where it started plus how far it moved (x itself has lost those digits) */
  float la = a + sch_dot(R.dev, ra), lb = b + sch_dot(R.dev, ta);
  if (dd > 1e-6f)
  {
    float t = (P->sFilm - sch_dot(R.x, d0)) / dd;
    la += t * ex;
    lb += t * ey;
  }
  else
  {
    R.flags |= SCH_RAY_OFFFILM;
  }
  rec[SCH_REC_A] = la;
  rec[SCH_REC_B] = lb;
  rec[SCH_REC_EX] = ex;
  rec[SCH_REC_EY] = ey;
  rec[SCH_REC_OPL] = R.opl;
  rec[SCH_REC_FLAGS] = (float)R.flags;
  rec[SCH_REC_SAMPLES] = R.samples;
  rec[SCH_REC_DRIFT] = (R.flags & SCH_RAY_MISSED) ? 0.0f : sch_invariant_gap(R.ne1, R.n1, d0, R.w);
  rec[SCH_REC_ERROR] = err;
  rec[SCH_REC_PATH] = R.path;
  rec[SCH_REC_MISMATCH] = R.mismatch;
  rec[SCH_REC_STEPS] = R.steps;
}

#ifdef SCH_PRIVATE_WALKS
/* Trace one ray that starts on the emission plane at film coordinates (a, b) and write its record. */
SCH_FN void sch_trace(SCH_FIELD field,
  SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P,
  float a,
  float b,
  float* rec)
{
  sch_v3 o, entry;
  float s1 = 0.0f;
  sch_ray R;
  if (sch_entry(P, a, b, &o, &entry, &s1))
    sch_march(field, levels, P, entry, P->step, &R);
  else
    sch_missed(o, &R);
  sch_record(field, levels, P, a, b, o, entry, s1, &R, rec);
}

#ifndef SCH_PACKET
#define SCH_PACKET 4
#endif

/* Trace `count` (at most SCH_PACKET) rays of a pass, through pixels pix0, pix0 + stride, ...,
 * advancing them in turn one step at a time: each ray's steps depend on each other, the rays do
 * not, so the memory reads of several rays are in flight together. The same arithmetic per ray
 * as sch_trace: the records are identical. */
SCH_FN void sch_trace_packet(SCH_FIELD field,
  SCH_GLOBAL const sch_uchar* levels,
  const sch_params* P,
  int pix0,
  int stride,
  int count,
  float* rec)
{
  sch_walk W[SCH_PACKET];
  sch_v3 O[SCH_PACKET], E[SCH_PACKET];
  float A[SCH_PACKET], B[SCH_PACKET], S1[SCH_PACKET];
  int hit[SCH_PACKET], live[SCH_PACKET];
  int r, any = 0;
  for (r = 0; r < SCH_PACKET; ++r)
  {
    live[r] = 0;
    hit[r] = 0;
    if (r < count)
    {
      sch_emit(P, pix0 + r * stride, &A[r], &B[r]);
      S1[r] = 0.0f;
      hit[r] = sch_entry(P, A[r], B[r], &O[r], &E[r], &S1[r]);
      if (hit[r])
      {
        sch_walk_begin(field, levels, P, E[r], P->step, &W[r]);
        live[r] = 1;
        any = 1;
      }
    }
  }
  while (any)
  {
    any = 0;
    for (r = 0; r < SCH_PACKET; ++r)
      if (live[r])
      {
        live[r] = sch_walk_step(field, levels, P, &W[r]);
        any |= live[r];
      }
  }
  for (r = 0; r < count && r < SCH_PACKET; ++r)
  {
    sch_ray R;
    if (hit[r])
      sch_walk_end(field, P, &W[r], &R);
    else
      sch_missed(O[r], &R);
    sch_record(field, levels, P, A[r], B[r], O[r], E[r], S1[r], &R, rec + r * SCH_RECORD);
  }
}
#endif

/* ---------------------------------------------------------------- cutoffs */

/* The engine's own elementary functions (acos, atan2, erfc, exp, cos), in float, from +, -, *, /,
 * sqrt, floor and ldexp only: operations that IEEE 754 rounds exactly, so the same inputs give the
 * same bits with any C library (glibc 2.31 to 2.43, mingw's on Windows) and on the CPU path and the
 * host finishing step alike. The C library's acosf, atan2f and erfcf changed in their last bit
 * between glibc 2.36 and 2.41 (2.41 made them correctly rounded) and erfc's (double) at 2.43; these
 * are not correctly rounded either, but they do not move. Accuracy, measured against the double
 * functions over 4e6 points each (logs in the commit that brought them): within 1.4 ulp (acos),
 * 2.2 (atan2), 1.1 (exp), 1.6 (cos, |x| <= 1e4) and 5e-7 relative (erfc, where above 1e-30). The polynomials were fitted for this file
 * (weighted least squares toward minimax on Chebyshev nodes against 40-digit references). */
#define SCH_PIO2_HI 1.57079637050628662109375f /* pi/2 rounded to float */
#define SCH_PIO2_LO -4.37113900018624283e-8f   /* pi/2 - SCH_PIO2_HI */
/* asin(x) = x + x^3 P(x^2), |x| <= 1/2 */
SCH_FN float sch_asin_core(float x)
{
  float z = x * x;
  float p = 0.16666672733f + z * (0.07498813190f + z * (0.04500990130f + z * (0.02649937067f + z * 0.03819629091f)));
  return x + x * z * p;
}
SCH_FN float sch_acos(float x)
{
  if (!(x >= -1.0f && x <= 1.0f))
    return x != x ? x : NAN;
  if (x >= -0.5f && x <= 0.5f)
    return SCH_PIO2_HI - (sch_asin_core(x) - SCH_PIO2_LO);
  {
    float z = 0.5f * (1.0f - sch_fabs(x)); /* exact for |x| in [1/2, 1] */
    float s = sch_sqrt(z);
    float a = 2.0f * sch_asin_core(s); /* acos |x| = 2 asin sqrt((1 - |x|) / 2) */
    return x > 0.0f ? a : 2.0f * SCH_PIO2_HI - (a - 2.0f * SCH_PIO2_LO);
  }
}
/* atan(t), t in [0, 1]: atan(u) = u + u^3 Q(u^2) for |u| <= tan(pi/8), pi/4 + atan((t-1)/(t+1)) above */
SCH_FN float sch_atan01(float t)
{
  float base = 0.0f, blo = 0.0f, u = t;
  if (t > 0.41421356f)
  {
    u = (t - 1.0f) / (t + 1.0f);
    base = 0.5f * SCH_PIO2_HI;
    blo = 0.5f * SCH_PIO2_LO;
  }
  {
    float z = u * u;
    float q = -0.33333333280f +
      z * (0.19999977578f + z * (-0.14284165831f + z * (0.11071600688f + z * (-0.08626227899f + z * 0.05051719275f))));
    return base + (u + (u * z * q + blo));
  }
}
SCH_FN float sch_atan2(float y, float x)
{
  float ax = sch_fabs(x), ay = sch_fabs(y), a;
  if (x != x || y != y)
    return x + y;
  if (ax == 0.0f && ay == 0.0f)
    a = 0.0f;
  else if (ay <= ax)
    a = ax == ay ? 0.5f * SCH_PIO2_HI : sch_atan01(ay / ax); /* both infinite: pi/4 */
  else
    a = SCH_PIO2_HI - (sch_atan01(ax / ay) - SCH_PIO2_LO);
  if (x < 0.0f || (x == 0.0f && 1.0f / x < 0.0f))
    a = 2.0f * SCH_PIO2_HI - (a - 2.0f * SCH_PIO2_LO);
  return y < 0.0f || (y == 0.0f && 1.0f / y < 0.0f) ? -a : a;
}
SCH_FN float sch_exp(float x)
{
  if (x != x)
    return x;
  if (x > 88.72283f)
    return INFINITY;
  if (x < -103.97208f)
    return 0.0f;
  {
    float k = sch_floor(x * 1.44269504088896341f + 0.5f);
    /* r = x - k ln 2 in two parts (ln2 hi has 16 significant bits: k * hi is exact for |k| < 256) */
    float r = (x - k * 0.693145751953125f) - k * 1.42860682030941723e-6f;
    float p = 0.49999999553f + r * (0.16666577293f + r * (0.04166685345f + r * (0.00836314492f + r * 0.00139012829f)));
    return sch_ldexp(1.0f + (r + r * r * p), (int)k);
  }
}
SCH_FN float sch_erfc(float x)
{
  float ax = sch_fabs(x), v;
  if (x != x)
    return x;
  if (ax < 0.84f)
  {
    float z = x * x;
    float e = 1.1283791669f +
      z * (-0.3761263687f + z * (0.1128374714f + z * (-0.02686248208f + z * (0.005209298839f + z * (-0.0008244291022f + z * 8.836255070e-05f)))));
    return 1.0f - x * e;
  }
  if (ax > 10.5f)
    v = 0.0f;
  else
  {
    /* erfc(x) = exp(-x^2) G(t), t = 1 / (1 + x/2), G in powers of t - 0.44; x^2 split so that exp sees it whole */
    float t = 1.0f / (1.0f + 0.5f * ax);
    float u = t - 0.44f;
    float g = 0.2074777229f +
      u * (0.7451336977f + u * (0.8546648147f + u * (0.6097221801f + u * (0.1230399339f +
      u * (-0.1950923658f + u * (-0.1040329891f + u * (0.1060928121f + u * (0.05805757471f + u * -0.06928476547f))))))));
    float hi = sch_floor(ax * 256.0f) * (1.0f / 256.0f); /* 12 significant bits (ax < 16): hi * hi exact */
    float lo = ax - hi;
    v = sch_exp(-hi * hi) * sch_exp(-lo * (ax + hi)) * g;
  }
  return x < 0.0f ? 2.0f - v : v;
}
SCH_FN float sch_fmod_pos4(float k)
{
  return k - 4.0f * sch_floor(k * 0.25f);
}
/* cos(x): x - k pi/2 in three parts (exact products for |k| < 2^12; beyond, still deterministic) */
SCH_FN float sch_cos(float x)
{
  if (!sch_isfinite(x))
    return x - x;
  {
    float k = sch_floor(x * 0.636619772367581343f + 0.5f);
    float r = ((x - k * 1.5703125f) - k * 4.83751296997070312e-4f) - k * 7.54978995489188216e-8f;
    float z = r * r;
    int q = ((int)sch_fmod_pos4(k));
    float s = r + r * z * (-0.16666666664f + z * (0.008333331864f + z * (-0.0001984008197f + z * 2.724941111e-06f)));
    float c = 1.0f - 0.5f * z + z * z * (0.04166666666f + z * (-0.001388888767f + z * (2.480059784e-05f + z * -2.730068537e-07f)));
    return q == 0 ? c : (q == 1 ? -s : (q == 2 ? -c : s));
  }
}

/* Energy weighting (paper section 5.3): the fraction of a photon's light that passes the cutoff in
 * the focal plane, for deflection (ex, ey) and scale k, clamped to [0, 1]. */

/* knife edge whose normal in the film plane is (ca, sa) */
SCH_FN float sch_knife_weight(float ex, float ey, float ca, float sa, float k)
{
  float I = 0.5f - k * (ex * ca + ey * sa);
  return I < 0.0f ? 0.0f : (I > 1.0f ? 1.0f : I);
}

/* A finite source's image at the knife (the bench): the fraction of the uncut source image's light
 * that passes the knife when the image is shifted by s toward the knife's open side (s = f2 eps,
 * eps = -(e . a): light bent toward -a passes, as for the point source). The knife covers the image
 * below the edge at d, measured from the image's centre across the knife; size is the image's height
 * a0 (slit, rectangle), its radius R' (disc) or its standard deviation (Gaussian). Closed forms:
 * slit: clamp((a0/2 - d + s) / a0); disc: [acos t - t sqrt(1 - t^2)] / pi, t = (d - s) / R'
 * clamped to [-1, 1]; Gaussian: erfc((d - s) / (sigma sqrt 2)) / 2. */
#define SCH_SOURCE_POINT 0
#define SCH_SOURCE_SLIT 1
#define SCH_SOURCE_RECTANGLE 2
#define SCH_SOURCE_DISC 3
#define SCH_SOURCE_GAUSSIAN 4
SCH_FN float sch_bench_weight(int source, float s, float d, float size)
{
  if (source == SCH_SOURCE_DISC)
  {
    float t = (d - s) / size;
    t = t < -1.0f ? -1.0f : (t > 1.0f ? 1.0f : t);
    return (sch_acos(t) - t * sch_sqrt(1.0f - t * t)) * (1.0f / 3.14159265358979f);
  }
  if (source == SCH_SOURCE_GAUSSIAN)
    return 0.5f * sch_erfc((d - s) * (0.70710678118654752f / size));
  {
    float I = (0.5f * size - d + s) / size;
    return I < 0.0f ? 0.0f : (I > 1.0f ? 1.0f : I);
  }
}

/* circular (pinhole) stop: I = 1 - k |e|; complement (a dot in the focal plane): I = k |e| */
SCH_FN float sch_circular_weight(float ex, float ey, float k, int complement)
{
  float I = k * sch_sqrt(ex * ex + ey * ey);
  I = I > 1.0f ? 1.0f : I;
  return complement ? I : 1.0f - I;
}

/* colour filter: the hue of the deflection's direction in the film plane (0 along +x, through
 * green at +120 degrees), full saturation; value comes separately (k |e|). */
SCH_FN void sch_hue_rgb(float ex, float ey, float* r, float* g, float* b)
{
  float h = 0.0f;
  if (ex != 0.0f || ey != 0.0f)
  {
    h = sch_atan2(ey, ex) * (3.0f / 3.14159265358979f); /* sixths of a turn, in (-3, 3] */
    if (h < 0.0f)
      h += 6.0f;
  }
  float f = h - sch_floor(h);
  int i = (int)h;
  float q = 1.0f - f;
  float R, G, B;
  if (i == 0)
  {
    R = 1.0f;
    G = f;
    B = 0.0f;
  }
  else if (i == 1)
  {
    R = q;
    G = 1.0f;
    B = 0.0f;
  }
  else if (i == 2)
  {
    R = 0.0f;
    G = 1.0f;
    B = f;
  }
  else if (i == 3)
  {
    R = 0.0f;
    G = q;
    B = 1.0f;
  }
  else if (i == 4)
  {
    R = f;
    G = 0.0f;
    B = 1.0f;
  }
  else
  {
    R = 1.0f;
    G = 0.0f;
    B = q;
  }
  *r = R;
  *g = G;
  *b = B;
}

/* interferometry: a photon with phase phi (radians) against a reference beam of phase ref */
SCH_FN float sch_fringe_weight(float phi, float ref)
{
  return 0.5f * (1.0f + sch_cos(phi - ref));
}

/* background-oriented schlieren: a pattern of dots (kind 0) or stripes (kind 1) of period `period`
 * (world units) on the background, seeded; values in [0, 1] */
SCH_FN float sch_bos_pattern(float a, float b, float period, int kind, sch_uint seed)
{
  if (kind == 1)
    return 0.5f + 0.5f * sch_cos(6.28318530718f * a / period);
  /* one dot per cell at a hashed place, Gaussian of radius period/4; the 3 x 3 neighbourhood */
  float u = a / period, v = b / period;
  int ci = (int)sch_floor(u), cj = (int)sch_floor(v);
  float I = 0.0f;
  int di, dj;
  for (dj = -1; dj <= 1; ++dj)
    for (di = -1; di <= 1; ++di)
    {
      sch_uint h = sch_hash(
        seed ^ sch_hash((sch_uint)(ci + di) * 73856093u ^ (sch_uint)(cj + dj) * 19349663u));
      float cx = (float)(ci + di) + 0.15f + 0.7f * sch_unit(h);
      float cy = (float)(cj + dj) + 0.15f + 0.7f * sch_unit(sch_hash(h ^ 0x5bd1e995u));
      float r2 = (u - cx) * (u - cx) + (v - cy) * (v - cy);
      float d = sch_exp(-r2 * 32.0f); /* 1/e radius of a quarter period */
      I = d > I ? d : I;
    }
  return I;
}

#ifndef __OPENCL_VERSION__
/* The host's double functions that glibc changed between 2.31 (Debian 11) and 2.36 (Debian 12):
 * atan, acos, hypot and tanh (the wedge's angles, the bench's disc and stop shares, the cone
 * filter, the auto integrator's measures, the scenes' fronts). Built from +, -, *, /, sqrt and exp
 * (exp did not change from 2.28 to 2.43); within a few ulp of the C library's. */
/* atan(t), t >= 0: atan(k/8) + atan(u), u = (t - k/8) / (1 + t k/8), |u| <= 1/16, by its series */
static inline double sch_atan_d(double x)
{
  static const double atan_k8[9] = { 0.0, 0.12435499454676144, 0.24497866312686414,
    0.35877067027057225, 0.4636476090008061, 0.5585993153435624, 0.6435011087932844,
    0.7188299996216245, 0.7853981633974483 };
  double t = x < 0 ? -x : x, r;
  int inv = t > 1.0, k, i;
  if (x != x)
    return x;
  if (inv)
    t = 1.0 / t; /* t = inf gives 0: pi/2 below */
  k = (int)(t * 8.0 + 0.5);
  {
    double c = k * 0.125, u = (t - c) / (1.0 + t * c), z = u * u, sum = 0.0;
    for (i = 17; i >= 3; i -= 2) /* u - u^3/3 + ... - u^19/19 */
      sum = ((i & 2) ? -1.0 : 1.0) / i + z * sum;
    r = atan_k8[k] + (u + u * z * sum);
  }
  if (inv)
    r = 1.5707963267948966 - (r - 6.123233995736757e-17);
  return x < 0 ? -r : r;
}
/* acos x = 2 atan sqrt((1 - x) / (1 + x)) */
static inline double sch_acos_d(double x)
{
  if (!(x >= -1.0 && x <= 1.0))
    return x != x ? x : NAN;
  if (x == -1.0)
    return 3.141592653589793;
  return 2.0 * sch_atan_d(sqrt((1.0 - x) / (1.0 + x)));
}
/* hypot: scaled by a power of two where the squares would overflow or underflow */
static inline double sch_hypot_d(double x, double y)
{
  double ax = x < 0 ? -x : x, ay = y < 0 ? -y : y, m = ax > ay ? ax : ay;
  if (ax == INFINITY || ay == INFINITY)
    return INFINITY;
  if (x != x || y != y)
    return x + y;
  if (m > 1e150 || (m < 1e-150 && m > 0.0))
  {
    int e = 0;
    frexp(m, &e);
    ax = ldexp(ax, -e);
    ay = ldexp(ay, -e);
    return ldexp(sqrt(ax * ax + ay * ay), e);
  }
  return sqrt(ax * ax + ay * ay);
}
/* exp(x) = 2^k exp(r), r = x - k ln 2 in two parts (|r| <= ln2/2), exp(r) by its Taylor series to
 * r^14/14! (the remainder is below 1e-17 of it) */
static inline double sch_exp_d(double x)
{
  double k, r, sum = 1.0;
  int i;
  if (x != x)
    return x;
  if (x > 709.78)
    return INFINITY;
  if (x < -745.2)
    return 0.0;
  k = floor(x * 1.4426950408889634 + 0.5);
  /* ln 2 = 0.693147180369123816490 (31 significant bits: k * hi exact) + 1.90821492927058770e-10 */
  r = (x - k * 0.693147180369123816490) - k * 1.90821492927058770e-10;
  for (i = 14; i >= 1; --i)
    sum = 1.0 + sum * r / i;
  return ldexp(sum, (int)k);
}
/* tanh: its series below 1/16, 1 - 2 / (exp(2|x|) + 1) above */
static inline double sch_tanh_d(double x)
{
  double a = x < 0 ? -x : x, r;
  if (x != x)
    return x;
  if (a < 0.0625)
  {
    double z = x * x; /* x - x^3/3 + 2x^5/15 - 17x^7/315 + 62x^9/2835 - 1382x^11/155925 */
    return x + x * z * (-1.0 / 3 + z * (2.0 / 15 + z * (-17.0 / 315 + z * (62.0 / 2835 + z * (-1382.0 / 155925)))));
  }
  r = a > 40.0 ? 1.0 : 1.0 - 2.0 / (sch_exp_d(2.0 * a) + 1.0);
  return x < 0 ? -r : r;
}
#endif

#endif
