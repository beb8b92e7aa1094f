/* SPDX-License-Identifier: BSD-3-Clause */
/* A seeded fuzz of the engine's C interface (schlieren_c.h) from C, the way a hostile or careless
 * caller meets it: every exported function called with random lengths (right, off by one, zero,
 * negative, huge), NULLs, NaN/inf, huge and negative dimensions, unknown and wrongly cased names,
 * integers past 32 bits, freed and foreign session handles, and two threads on one session.
 *
 *   TestCApiFuzz [--cases N] [--seed S] [--verbose]
 *
 * The fuzz never lies about a buffer it owns: where it passes a length, the buffer holds that many
 * values (a length the function must refuse is the point); what it varies is whether the length is
 * the one the function needs. Every call must return (a crash or a sanitizer report fails the
 * test), and every refusal must come with a message (an empty one fails). The crashers are
 * fixed cases first, each with the message it must give (one more, a read outside the array in
 * ExtendIntoInvalid on a grid one point thick, was found by this fuzz under AddressSanitizer). A table of outcomes per function ends the
 * run. ctest runs the fixed cases and 4000 random ones (a few seconds); the longer run under
 * AddressSanitizer is in docs/FUZZING.md. Traces are kept small (a film of at most 24 x 24, a pass
 * or two, a grid of at most 12 points a side): long but legitimate traces are the plugin fuzz's
 * (Testing/Python/test_fuzz.py) and the benchmark's business. */
#include "schlieren_c.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;
static int verbose = 0;

/* ---- the random source: xorshift64*, seeded (the same cases on every machine) ---- */
static uint64_t state = 88172645463325252ull;
static uint64_t next(void)
{
  state ^= state >> 12;
  state ^= state << 25;
  state ^= state >> 27;
  return state * 2685821657736338717ull;
}
static int below(int n)
{
  return (int)(next() % (uint64_t)n);
}
static double uniform(void)
{
  return (next() >> 11) * (1.0 / 9007199254740992.0);
}

/* ---- the outcomes, per function ---- */
enum
{
  F_SET_VOLUME,
  F_SET,
  F_GET,
  F_TRACE,
  F_ARRAY,
  F_FILM,
  F_PLAN,
  F_REPORT,
  F_FREE,
  F_FILL,
  F_OCTREE,
  F_GRADIENT,
  F_NUMERICAL,
  F_FIELD,
  F_EXTEND,
  F_AUTODIMS,
  F_MEMORY,
  F_SYMMETRY,
  F_WEDGE,
  F_PROPERTY,
  F_PHOTOGRAPH,
  F_MISC,
  F_THREADS,
  F_SAMPLE,
  F_AMR,
  F_TIME_CACHE,
  F_INDEX_FIELD,
  F_INDEX_CHOICES,
  F_WALL_FACES,
  F_SAMPLING,
  F_PARALLEL,
  F_CELL_FIELDS,
  F_COUNT
};
static const char* fnames[F_COUNT] = { "session_set_volume", "session_set", "session_get",
  "session_trace", "session_array", "session_film", "session_plan_film", "session_report",
  "session_free", "fill_scene", "octree_levels", "gradient", "numerical", "field_index",
  "extend_into_invalid", "automatic_dimensions", "check_memory", "symmetry_plan/samples/expand",
  "wedge_warning", "check_property", "photograph", "version/properties/device",
  "two threads, one session", "sample_cells", "amr_overlap/grid/sample", "time_cache_find/insert",
  "index_field", "index_choices", "wall_faces",
  "sampling_grid and rules", "parallel (callbacks)", "cell_fields" };
static long calls[F_COUNT], done[F_COUNT], refused[F_COUNT], unclear[F_COUNT];

/* rc 0: done; else the message must say something */
static void outcome(int f, int rc, const char* message, const char* what)
{
  ++calls[f];
  if (rc == 0)
  {
    ++done[f];
    return;
  }
  ++refused[f];
  if (!message || !*message || strstr(message, "Unknown engine error"))
  {
    ++unclear[f];
    ++failures;
    printf("FAIL %s: %s refused without a clear message ('%s')\n", fnames[f], what,
      message ? message : "(NULL)");
  }
  else if (verbose)
    printf("     %s: %s -> %s\n", fnames[f], what, message);
}

static void expect(int ok, const char* name, const char* message)
{
  printf("%s %s%s%s\n", ok ? "ok  " : "FAIL", name, message ? ": " : "", message ? message : "");
  if (!ok)
    ++failures;
}

/* the condition first, then the message it left (C leaves the order of arguments open) */
#define EXPECT(cond, name, message)                                                               \
  do                                                                                              \
  {                                                                                               \
    const int ok_ = (cond) ? 1 : 0;                                                               \
    expect(ok_, name, message);                                                                   \
  } while (0)

static int has(const char* text, const char* part)
{
  return text && strstr(text, part) != NULL;
}

/* ---- the fixed cases: the crashers and silent-wrong answers of issue 48, named ---- */
static void fixed_cases(void)
{
  const int d40[3] = { 40, 40, 40 }, d400[3] = { 400, 400, 400 }, d8[3] = { 8, 8, 8 };
  const int neg[3] = { -5, 4, 4 }, huge[3] = { 8192, 8192, 8192 };
  const double o[3] = { 0, 0, 0 }, h[3] = { 1, 1, 1 }, nan3[3] = { NAN, 0, 0 };
  float small[10] = { 0 };
  unsigned char bytes[10] = { 0 };
  float* grid = calloc(64000, sizeof(float));
  float* grad = calloc(3 * 64000, sizeof(float));
  unsigned char* levels = calloc(64000, 1);
  schlieren_session* s = schlieren_session_new();
  schlieren_session* gone;
  int64_t filled = 0;

  EXPECT(schlieren_gradient(d400, h, small, 10, grad, 3 * 10) != 0 &&
      has(schlieren_last_error(), "n_minus_1 holds 10 values") && has(schlieren_last_error(), "64000000"),
    "fixed: gradient of a 400^3 grid given 10 values (a segfault before)", schlieren_last_error());
  EXPECT(schlieren_octree_levels(d40, small, 10, 1e-6, 7, levels, NULL) != 0 &&
      has(schlieren_last_error(), "holds 10 values") && has(schlieren_last_error(), "64000"),
    "fixed: octree_levels given 10 values for 40^3", schlieren_last_error());
  EXPECT(schlieren_extend_into_invalid(d40, bytes, 10, grid, &filled) != 0 &&
      has(schlieren_last_error(), "valid"),
    "fixed: extend_into_invalid given 10 valid flags for 40^3", schlieren_last_error());
  EXPECT(schlieren_numerical("", d40, o, h, small, 10, NULL, 0, NULL, 0, NULL, NULL, NULL, 16,
           small, small, bytes, NULL) != 0 && has(schlieren_last_error(), "values holds 10"),
    "fixed: numerical given 10 values for 40^3", schlieren_last_error());
  EXPECT(schlieren_session_set_volume(s, d40, o, h, grid, 64000, bytes, 10, NULL, 0, -1, 7) != 0 &&
      has(schlieren_session_error(s), "solid holds 10 values"),
    "fixed: set_volume with a solid mask of 10 for 40^3 (a segfault before)", schlieren_session_error(s));
  EXPECT(schlieren_session_set_volume(s, d40, o, h, grid, 64000, NULL, 0, levels, 63999, -1, 7) != 0 &&
      has(schlieren_session_error(s), "levels holds 63999 values") && has(schlieren_session_error(s), "64000"),
    "fixed: set_volume with levels one short (heap garbage traced before)", schlieren_session_error(s));
  EXPECT(schlieren_session_set_volume(s, d40, o, h, grid, 63999, NULL, 0, NULL, 0, -1, 7) != 0,
    "fixed: set_volume with n_minus_1 one short", schlieren_session_error(s));
  EXPECT(schlieren_session_set_volume(s, huge, o, h, grid, (int64_t)8192 * 8192 * 8192, NULL, 0, NULL,
           0, -1, 7) != 0 && has(schlieren_session_error(s), "needs"),
    "fixed: set_volume of 8192^3 points: refused for memory before the copy", schlieren_session_error(s));
  EXPECT(schlieren_fill_scene("", neg, o, h, 80, grid, NULL, NULL, NULL) != 0 &&
      has(schlieren_last_error(), "-5 4 4"),
    "fixed: fill_scene with negative dims (uninitialised memory as n - 1 before)", schlieren_last_error());
  EXPECT(schlieren_fill_scene("Body=Sphere\nBodyCenter=nan 0 0", d8, o, h, 512, grid, NULL, NULL,
           bytes) != 0 && has(schlieren_last_error(), "BodyCenter"),
    "fixed: a BodyCenter with NaN refused (the body silently dropped before)", schlieren_last_error());
  EXPECT(schlieren_session_plan_film(s, d8, nan3, h, NULL, NULL, NULL) != 0 &&
      has(schlieren_session_error(s), "origin"),
    "fixed: plan_film with a NaN origin", schlieren_session_error(s));
  EXPECT(schlieren_field_index("Passthrough", small, -1, 0, 1, NULL, small, NULL) != 0 &&
      has(schlieren_last_error(), "count is -1"),
    "fixed: field_index with count -1 says what is wrong", schlieren_last_error());
  /* found by this fuzz under AddressSanitizer: the smoothing of the fill read across an axis one
   * point thick (outside the array); a harmonic fill stays within its edge's values */
  {
    const int flat[3] = { 7, 6, 1 };
    float values[42];
    unsigned char inside[42];
    int i, bounded = 1;
    for (i = 0; i < 42; ++i)
    {
      const int x = i % 7, y = i / 7;
      inside[i] = (unsigned char)(x == 0 || y == 0 || x == 6 || y == 5);
      values[i] = inside[i] ? (float)(1e-4 * (1 + 0.1 * x + 0.05 * y)) : -1.0f;
    }
    EXPECT(schlieren_extend_into_invalid(flat, inside, 42, values, &filled) == 0 && filled == 20,
      "fixed: extend_into_invalid on a 7 x 6 x 1 grid with a hole of 20 points", schlieren_last_error());
    for (i = 0; i < 42; ++i)
      bounded = bounded && isfinite(values[i]) && values[i] >= 0.99e-4f && values[i] <= 1.9e-4f;
    EXPECT(bounded, "fixed: the 2D fill stays within its edge's values (read outside the array before)",
      NULL);
  }
  /* names and numbers */
  EXPECT(schlieren_session_set(s, "cutoff", "Shadowgraph") != 0 &&
      has(schlieren_session_error(s), "closest known name: 'Cutoff'"),
    "fixed: a wrongly cased property name names the closest", schlieren_session_error(s));
  EXPECT(schlieren_session_set(s, "Cutoff", "shadowgraph") != 0 &&
      has(schlieren_session_error(s), "closest known name: 'Shadowgraph'"),
    "fixed: a wrongly cased entry names the closest", schlieren_session_error(s));
  EXPECT(schlieren_session_set(s, "Passes", "3000000000") != 0 &&
      has(schlieren_session_error(s), "Passes is 3000000000") && !has(schlieren_session_error(s), "-2147483648"),
    "fixed: Passes 3e9 reported as given", schlieren_session_error(s));
  EXPECT(schlieren_session_set(s, "Seed", "4294967296") != 0 &&
      has(schlieren_session_error(s), "Seed is 4294967296") && has(schlieren_session_error(s), "4294967295"),
    "fixed: a seed past 2^32 reported with its range", schlieren_session_error(s));
  EXPECT(schlieren_session_set(s, "Seed", "4294967295") == 0 &&
      strcmp(schlieren_session_get(s, "Seed"), "4294967295") == 0,
    "fixed: the largest seed taken", NULL);
  EXPECT(schlieren_session_set(s, "UseOctree", "2") != 0 && has(schlieren_session_error(s), "0 or 1"),
    "fixed: a boolean 2 refused (as the C++ plugin does)", schlieren_session_error(s));
  EXPECT(schlieren_session_set(s, "KnifeAngle", "1e300") == 0 &&
      schlieren_session_plan_film(s, d8, o, h, NULL, NULL, NULL) != 0 &&
      has(schlieren_session_error(s), "KnifeAngle is 1e+300") && has(schlieren_session_error(s), "[-180, 180]"),
    "fixed: KnifeAngle 1e300 refused as the C++ plugin refuses it", schlieren_session_error(s));
  /* handles */
  gone = schlieren_session_new();
  schlieren_session_free(gone);
  EXPECT(schlieren_session_trace(gone) != 0 && has(schlieren_last_error(), "schlieren_session_trace") &&
      has(schlieren_session_error(gone), "freed") && has(schlieren_session_report(gone), "freed"),
    "fixed: a trace on a freed session refused", schlieren_session_error(gone));
  schlieren_session_free(gone);
  EXPECT(has(schlieren_last_error(), "schlieren_session_free"), "fixed: a second free refused",
    schlieren_last_error());
  EXPECT(schlieren_session_set((schlieren_session*)(void*)bytes, "Passes", "2") != 0 &&
      schlieren_session_get((schlieren_session*)(void*)bytes, "Passes") == NULL &&
      schlieren_session_film((schlieren_session*)(void*)bytes, NULL, NULL, NULL) != 0,
    "fixed: a foreign pointer refused, not followed", schlieren_last_error());
  EXPECT(schlieren_session_film(s, NULL, NULL, NULL) != 0 && has(schlieren_session_error(s), "no image"),
    "fixed: film before a trace says there is no image", schlieren_session_error(s));
  {
    /* issue 51: the BOS pair writer with no image, NULL arguments, a freed or foreign handle */
    const char* written = "unset";
    EXPECT(schlieren_session_write_bos_pair(s, NULL, 8, NULL, NULL, &written) != 0 && written == NULL &&
        has(schlieren_session_error(s), "no image"),
      "the BOS pair before a trace: no image, nothing written", schlieren_session_error(s));
    EXPECT(schlieren_session_write_bos_pair(gone, "/tmp", 8, "png", "bos", NULL) != 0 &&
        schlieren_session_write_bos_pair((schlieren_session*)(void*)bytes, "/tmp", 8, "png", "bos", NULL) != 0,
      "the BOS pair on a freed or foreign handle refused", schlieren_last_error());
  }
  schlieren_session_free(s);
  free(grid);
  free(grad);
  free(levels);
}

/* ---- two threads on one session: serialised, each image the one a single thread makes ---- */
struct shared
{
  schlieren_session* s;
  int rc;
};
static void* trace_thread(void* p)
{
  struct shared* t = (struct shared*)p;
  t->rc = schlieren_session_trace(t->s);
  return NULL;
}

static double image_sum(schlieren_session* s, int64_t* n)
{
  double sum = 0;
  int64_t i;
  const float* a = schlieren_session_array(s, "intensity", NULL, n);
  for (i = 0; a && i < *n; ++i)
    sum += a[i];
  return a ? sum : -1;
}

static void threads_case(void)
{
  const int dims[3] = { 17, 17, 17 };
  const double o[3] = { -1, -1, -1 }, h[3] = { 0.125, 0.125, 0.125 };
  float* n1 = malloc(17 * 17 * 17 * sizeof(float));
  schlieren_session* s = schlieren_session_new();
  struct shared a = { s, -1 }, b = { s, -1 };
  pthread_t ta, tb;
  double single, both;
  int64_t n = 0, m = 0;
  schlieren_fill_scene("Scene=GaussianSphere", dims, o, h, 17 * 17 * 17, n1, NULL, NULL, NULL);
  schlieren_session_set(s, "Resolution", "48 48");
  schlieren_session_set(s, "Passes", "4");
  schlieren_session_set(s, "Backend", "CPU");
  schlieren_session_set_volume(s, dims, o, h, n1, 17 * 17 * 17, NULL, 0, NULL, 0, -1, 7);
  schlieren_session_trace(s);
  single = image_sum(s, &n);
  /* a new volume (the same values): both threads trace it from the start, one after the other;
   * the second finds the passes done. Unserialised, the two traces wrote one film at once. */
  schlieren_session_set_volume(s, dims, o, h, n1, 17 * 17 * 17, NULL, 0, NULL, 0, -1, 7);
  pthread_create(&ta, NULL, trace_thread, &a);
  pthread_create(&tb, NULL, trace_thread, &b);
  pthread_join(ta, NULL);
  pthread_join(tb, NULL);
  both = image_sum(s, &m);
  ++calls[F_THREADS];
  ++done[F_THREADS];
  printf("%s fixed: two threads tracing one session: rc %d %d, intensity sum %.9g, one thread's "
         "%.9g (%lld pixels)\n",
    a.rc == 0 && b.rc == 0 && n > 0 && m == n && both == single ? "ok  " : "FAIL", a.rc, b.rc, both,
    single, (long long)n);
  if (!(a.rc == 0 && b.rc == 0 && n > 0 && m == n && both == single))
    ++failures;
  schlieren_session_free(s);
  free(n1);
}

/* progress and stop (schlieren_session_trace_progress): a callback that stops at its first call
 * ends Passes 1000000 at once with the message and no image; one that goes on changes no bit of
 * the image; NULL is schlieren_session_trace; a freed handle is refused */
struct progress_log
{
  int calls, stop_at, ordered;
  double last;
};

static int progress_cb(double fraction, const char* text, void* user)
{
  struct progress_log* log = (struct progress_log*)user;
  log->ordered = log->ordered && text != NULL && fraction >= log->last && fraction <= 1;
  log->last = fraction;
  return ++log->calls != log->stop_at;
}

static void progress_case(void)
{
  const int dims[3] = { 17, 17, 17 };
  const double o[3] = { -1, -1, -1 }, h[3] = { 0.125, 0.125, 0.125 };
  float* n1 = malloc(17 * 17 * 17 * sizeof(float));
  float* plain = NULL;
  schlieren_session* s = schlieren_session_new();
  struct progress_log stop = { 0, 1, 1, 0 }, go = { 0, -1, 1, 0 };
  int64_t n = 0, m = 0;
  const float* a;
  int rc;
  schlieren_fill_scene("Scene=GaussianSphere", dims, o, h, 17 * 17 * 17, n1, NULL, NULL, NULL);
  schlieren_session_set(s, "Resolution", "24 24");
  schlieren_session_set(s, "Backend", "CPU");
  schlieren_session_set(s, "Passes", "1000000");
  schlieren_session_set_volume(s, dims, o, h, n1, 17 * 17 * 17, NULL, 0, NULL, 0, -1, 7);
  rc = schlieren_session_trace_progress(s, progress_cb, &stop);
  EXPECT(rc != 0 && stop.calls == 1 && has(schlieren_session_error(s), "aborted at 0 % of the trace") &&
      !schlieren_session_array(s, "intensity", NULL, NULL) &&
      has(schlieren_session_report(s), "aborted at"),
    "fixed: Passes 1000000 stopped at the first progress call, no image", schlieren_session_error(s));
  schlieren_session_set(s, "Passes", "3");
  rc = schlieren_session_trace(s);
  a = schlieren_session_array(s, "intensity", NULL, &n);
  if (rc == 0 && a && n > 0)
  {
    plain = malloc((size_t)n * sizeof(float));
    memcpy(plain, a, (size_t)n * sizeof(float));
  }
  /* the same volume again: traced from the start (a new volume), with the callback */
  schlieren_session_set_volume(s, dims, o, h, n1, 17 * 17 * 17, NULL, 0, NULL, 0, -1, 7);
  rc = schlieren_session_trace_progress(s, progress_cb, &go);
  a = schlieren_session_array(s, "intensity", NULL, &m);
  EXPECT(rc == 0 && plain && a && m == n && memcmp(a, plain, (size_t)n * sizeof(float)) == 0 &&
      go.calls > 3 && go.ordered,
    "fixed: a callback that goes on changes no bit of the image (3 passes), fractions in order",
    schlieren_session_error(s));
  schlieren_session_set_volume(s, dims, o, h, n1, 17 * 17 * 17, NULL, 0, NULL, 0, -1, 7);
  rc = schlieren_session_trace_progress(s, NULL, NULL);
  a = schlieren_session_array(s, "intensity", NULL, &m);
  EXPECT(rc == 0 && plain && a && m == n && memcmp(a, plain, (size_t)n * sizeof(float)) == 0,
    "fixed: a NULL callback is schlieren_session_trace", schlieren_session_error(s));
  schlieren_session_free(s);
  rc = schlieren_session_trace_progress(s, progress_cb, &go);
  EXPECT(rc != 0 && has(schlieren_last_error(), "schlieren_session_trace_progress"),
    "fixed: schlieren_session_trace_progress refuses a freed handle", schlieren_last_error());
  free(plain);
  free(n1);
}

/* NumericalSchlieren's progress and stop (schlieren_numerical_progress): a small LineOfSight image
 * (one block of rows: python.python_plugin_parity sees several on a larger one); a callback that stops at its first call fails with the message and writes no
 * pixel; one that goes on, and NULL, give schlieren_numerical's image bit for bit */
static void numerical_progress_case(void)
{
  const int dims[3] = { 24, 24, 24 };
  const double o[3] = { -1, -1, -1 }, h[3] = { 2.0 / 23, 2.0 / 23, 2.0 / 23 };
  const int64_t count = 24 * 24 * 24, pixels = 128 * 128;
  const char* settings = "Mode=LineOfSight\nResolution=128 128\nViewDirection=0.2 0.1 -1";
  float* n1 = malloc((size_t)count * sizeof(float));
  float* rho = malloc((size_t)count * sizeof(float));
  float* out[2][2];
  unsigned char* blocked[2];
  struct progress_log stop = { 0, 1, 1, 0 }, go = { 0, -1, 1, 0 };
  int size[2], rc, k, same = 1;
  double origin[2], pixel, ml[2];
  for (k = 0; k < 2; ++k)
  {
    out[k][0] = malloc((size_t)pixels * sizeof(float));
    out[k][1] = malloc((size_t)pixels * sizeof(float));
    blocked[k] = malloc((size_t)pixels);
  }
  schlieren_fill_scene("Scene=GaussianSphere", dims, o, h, count, n1, rho, NULL, NULL);
  out[1][0][0] = -7.0f;
  rc = schlieren_numerical_progress(settings, dims, o, h, rho, count, NULL, 0, NULL, 0, size, origin,
    &pixel, pixels, out[1][0], out[1][1], blocked[1], ml, progress_cb, &stop);
  EXPECT(rc != 0 && stop.calls == 1 && has(schlieren_last_error(), "aborted at 0 % of the image") &&
      out[1][0][0] == -7.0f,
    "fixed: NumericalSchlieren stopped at the first progress call, no pixel written",
    schlieren_last_error());
  rc = schlieren_numerical(settings, dims, o, h, rho, count, NULL, 0, NULL, 0, size, origin, &pixel,
    pixels, out[0][0], out[0][1], blocked[0], ml);
  for (k = 0; k < 2 && rc == 0; ++k)
  {
    rc = schlieren_numerical_progress(settings, dims, o, h, rho, count, NULL, 0, NULL, 0, size,
      origin, &pixel, pixels, out[1][0], out[1][1], blocked[1], ml, k ? NULL : progress_cb,
      k ? NULL : &go);
    same = same && rc == 0 && memcmp(out[0][0], out[1][0], (size_t)pixels * sizeof(float)) == 0 &&
      memcmp(out[0][1], out[1][1], (size_t)pixels * sizeof(float)) == 0 &&
      memcmp(blocked[0], blocked[1], (size_t)pixels) == 0;
  }
  EXPECT(rc == 0 && same && go.calls >= 2 && go.ordered && go.last == 1.0,
    "fixed: NumericalSchlieren with a callback that goes on (progress in order to 1) and with "
    "NULL: schlieren_numerical's image bit for bit",
    schlieren_last_error());
  for (k = 0; k < 2; ++k)
  {
    free(out[k][0]);
    free(out[k][1]);
    free(blocked[k]);
  }
  free(rho);
  free(n1);
}

/* ---- the random part ---- */
static const char* const property_names[] = { "ViewDirection", "ViewUp", "Resolution", "Framing",
  "Passes", "StepSize", "Integrator", "Reconstruction", "Tolerance", "KeepInvariant",
  "EstimateError", "UseOctree", "Cutoff", "KnifeAngle", "CutoffScale", "FilmDistance",
  "Wavelength", "ReferenceTilt", "WavelengthRange", "WavelengthBins", "Dispersion",
  "BackgroundDistance", "BackgroundPattern", "BackgroundPeriod", "Filter", "FilterWidth",
  "RussianRoulette", "Jitter", "JitterPattern", "Seed", "Backend", "DeviceName", "Threads",
  "TraceInPieces", "Source", "SourceSize", "CollimatorFocalLength", "SchlierenFocalLength",
  "KnifeCut", "StopDiameter", "BitDepth", "SaturationWarning", "Camera", "CameraFocalLength",
  "FNumber", "CameraDistance", "FocusPlane", "SourceGridDistance" };
#define NPROPS ((int)(sizeof(property_names) / sizeof(property_names[0])))
static const char* const values[] = { "0", "1", "-1", "2", "0.5", "1e300", "-1e300", "nan", "inf",
  "-inf", "3000000000", "-3000000000", "4294967296", "18446744073709551617", "1e-320", "64 48",
  "0 0 -1", "0 1 0", "1 2 3 4", "", " ", "abc", "KnifeEdge", "knifeedge", "Shadowgraph", "RK4",
  "Cubic", "CPU", "OpenCL", "Auto", "Lens", "Disc", "0x10", "1,2", "[1 2]", "1e9 1e9",
  "2147483648 2", "-2147483649", "\xff\xfe", "Euler", "BOS", "Gaussian" };
#define NVALUES ((int)(sizeof(values) / sizeof(values[0])))

static char scratch[256];
static const char* random_name(const char* const* names, int count)
{
  const char* base = names[below(count)];
  size_t n = strlen(base), i;
  switch (below(6))
  {
    case 0: /* wrongly cased */
      for (i = 0; i < n && i < sizeof(scratch) - 1; ++i)
        scratch[i] = (char)((base[i] >= 'A' && base[i] <= 'Z') ? base[i] + 32 : base[i]);
      scratch[i] = 0;
      return scratch;
    case 1: /* a letter dropped */
      snprintf(scratch, sizeof(scratch), "%s", base);
      if (n > 1)
        memmove(scratch + n / 2, scratch + n / 2 + 1, n - n / 2);
      return scratch;
    case 2:
      return below(4) ? "NoSuchProperty" : NULL;
    default:
      return base;
  }
}

static int64_t random_count(int64_t needed)
{
  switch (below(16))
  {
    case 0: return needed < INT64_MAX ? needed + 1 : needed - 1; /* (no overflow: undefined) */
    case 1: return needed > INT64_MIN ? needed - 1 : needed + 1;
    case 2: return 0;
    case 3: return -1;
    case 4: return INT64_MIN;
    case 5: return INT64_MAX;
    case 6: return below(100);
    default: return needed;
  }
}

/* v * k, held at the ends of int64_t (a count of INT64_MIN times 3 overflowed: undefined) */
static int64_t scaled(int64_t v, int k)
{
  if (v > INT64_MAX / k)
    return INT64_MAX;
  if (v < INT64_MIN / k)
    return INT64_MIN;
  return v * k;
}

/* a buffer that truly holds `count` values where it can (the caller does not lie): NULL where the
 * count is negative or past a million (then the function must refuse it: no grid here is that big
 * unless the fuzz chose a huge one, whose count it never gives as the needed one) */
static void* buffer(int64_t count, size_t size, int may_null)
{
  if (may_null && below(30) == 0)
    return NULL;
  if (count < 0 || count > 1000000)
    return malloc(16 * size); /* the function must refuse the count before reading */
  return calloc((size_t)(count ? count : 1), size);
}

static void random_grid(int dims[3], int64_t* needed, int* valid)
{
  int a;
  *valid = 1;
  for (a = 0; a < 3; ++a)
  {
    switch (below(40))
    {
      case 0: dims[a] = 0; break;
      case 1: dims[a] = -below(5) - 1; break;
      case 2: dims[a] = 2147483647; break;
      case 3: dims[a] = -2147483647 - 1; break;
      default: dims[a] = below(8) ? 2 + below(11) : 1;
    }
    if (dims[a] < 1 || dims[a] > 12)
      *valid = 0;
  }
  *needed = *valid ? (int64_t)dims[0] * dims[1] * dims[2] : 64;
}

/* a count for a grid: a huge grid never gets its true count (the fuzz has no such buffer) */
static int64_t grid_count(int64_t needed, int valid)
{
  int64_t c = random_count(needed);
  if (!valid && c > 1000000)
    c = 64;
  return c;
}

static void random_point(double v[3])
{
  int a;
  for (a = 0; a < 3; ++a)
  {
    switch (below(60))
    {
      case 0: v[a] = NAN; break;
      case 1: v[a] = INFINITY; break;
      case 2: v[a] = -1e308; break;
      case 3: v[a] = 0; break;
      case 4: v[a] = -uniform(); break;
      default: v[a] = 0.05 + uniform();
    }
  }
}

#define POOL 4
static schlieren_session* pool[POOL];
static schlieren_session* freed[POOL];

static schlieren_session* random_session(void)
{
  static int foreign = 0;
  switch (below(30))
  {
    case 0: return NULL;
    case 1: return freed[below(POOL)]; /* maybe NULL; maybe an address a new session reuses */
    case 2: return (schlieren_session*)(void*)&foreign;
    default: return pool[below(POOL)];
  }
}

/* settings a trace may take without running long */
static void keep_small(schlieren_session* s)
{
  schlieren_session_set(s, "Resolution", below(2) ? "16 12" : "24 24");
  schlieren_session_set(s, "Passes", below(2) ? "1" : "2");
  schlieren_session_set(s, "WavelengthBins", "2");
  schlieren_session_set(s, "Threads", below(2) ? "0" : "2");
  schlieren_session_set(s, "Backend", "CPU");
  schlieren_session_set(s, "Framing", "Volume");
}

static void random_case(int k)
{
  char what[160];
  int dims[3], valid, f = below(23), rc;
  int64_t needed, count, count2, count3;
  double o[3], h[3];
  schlieren_session* s = random_session();
  random_grid(dims, &needed, &valid);
  random_point(o);
  random_point(h);
  if (below(2))
  {
    o[0] = o[1] = o[2] = -1;
    h[0] = h[1] = h[2] = 0.2;
  }
  snprintf(what, sizeof(what), "case %d: dims %d %d %d", k, dims[0], dims[1], dims[2]);
  if (verbose)
    printf("  %s\n", what), fflush(stdout);
  switch (f)
  {
    case 0:
    case 1:
    {
      float* n1;
      unsigned char *solid, *levels;
      count = grid_count(needed, valid);
      count2 = below(2) ? 0 : grid_count(needed, valid);
      count3 = below(2) ? 0 : grid_count(needed, valid);
      n1 = buffer(count, sizeof(float), 1);
      solid = count2 ? buffer(count2, 1, 1) : NULL;
      levels = count3 ? buffer(count3, 1, 1) : NULL;
      if (solid && count2 > 0 && count2 <= 1000000)
        memset(solid, 0, (size_t)count2), solid[below((int)count2)] = 1;
      if (levels && count3 > 0 && count3 <= 1000000)
        memset(levels, below(2) ? 0 : below(12), (size_t)count3);
      if (n1 && count >= 0 && count <= 1000000)
      {
        int64_t i;
        for (i = 0; i < count; ++i)
          n1[i] = below(50) == 0 ? NAN : (float)(1e-4 * uniform());
      }
      rc = schlieren_session_set_volume(s, dims, o, h, n1, count, solid, count2, levels, count3,
        below(3) ? -1 : (below(4) ? 1e-6 : NAN), below(4) ? 7 : below(40) - 20);
      outcome(F_SET_VOLUME, rc, schlieren_session_error(s), what);
      free(n1);
      free(solid);
      free(levels);
      break;
    }
    case 2:
    case 3:
    case 4:
    {
      const char* name = random_name(property_names, NPROPS);
      const char* value = below(20) ? values[below(NVALUES)] : NULL;
      rc = schlieren_session_set(s, name, value);
      outcome(F_SET, rc, schlieren_session_error(s), what);
      break;
    }
    case 5:
    {
      const char* v = schlieren_session_get(s, random_name(property_names, NPROPS));
      outcome(F_GET, v == NULL, v ? "" : schlieren_session_error(s), what);
      break;
    }
    case 6:
      if (s == pool[0] || s == pool[1] || s == pool[2] || s == pool[3])
        keep_small(s);
      rc = schlieren_session_trace(s);
      outcome(F_TRACE, rc, schlieren_session_error(s), what);
      break;
    case 7:
    {
      /* a fresh session, a volume it takes, a few settings, a trace, its image read whole */
      schlieren_session* t = schlieren_session_new();
      const int d[3] = { 2 + below(10), 2 + below(10), 2 + below(10) };
      const int64_t n = (int64_t)d[0] * d[1] * d[2];
      const double oo[3] = { -1, -1, -1 }, hh[3] = { 0.2, 0.2 * (0.5 + uniform()), 0.2 };
      float* n1 = malloc((size_t)n * sizeof(float));
      unsigned char* solid = below(4) ? NULL : calloc((size_t)n, 1);
      int i, m = below(4), comps = 0;
      int64_t pixels = 0, j;
      double sum = 0;
      const float* img;
      schlieren_fill_scene(below(2) ? "Scene=GaussianSphere" : "Scene=BlastWave", d, oo, hh, n, n1,
        NULL, NULL, NULL);
      if (solid)
        solid[below((int)n)] = 1;
      schlieren_session_set_volume(t, d, oo, hh, n1, n, solid, solid ? n : 0, NULL, 0, -1, 7);
      for (i = 0; i < m; ++i)
        schlieren_session_set(t, property_names[below(NPROPS)], values[below(NVALUES)]);
      keep_small(t);
      rc = schlieren_session_trace(t);
      outcome(F_TRACE, rc, schlieren_session_error(t), what);
      img = schlieren_session_array(t, below(2) ? "intensity" : "deflection", &comps, &pixels);
      for (j = 0; img && j < pixels * comps; ++j)
        sum += img[j];
      if (rc == 0 && !img)
      {
        ++failures;
        printf("FAIL %s: a trace that succeeded has no intensity/deflection\n", what);
      }
      (void)sum;
      schlieren_session_free(t);
      free(n1);
      free(solid);
      break;
    }
    case 8:
    {
      static const char* arrays[] = { "intensity", "deflection", "rgb", "phase", "bos_displacement",
        "error_estimate", "blocked", "Intensity", "", NULL };
      int comps = 0;
      int64_t pixels = 0, i;
      const float* a = schlieren_session_array(s, arrays[below(10)], below(2) ? &comps : NULL, &pixels);
      double sum = 0;
      for (i = 0; a && i < pixels * (comps ? comps : 1); ++i)
        sum += a[i]; /* read it all: the sanitizer sees an array shorter than it says */
      ++calls[F_ARRAY];
      ++done[F_ARRAY];
      (void)sum;
      break;
    }
    case 9:
    {
      int size[2];
      double origin[2], px;
      rc = schlieren_session_film(s, below(4) ? size : NULL, origin, below(2) ? &px : NULL);
      outcome(F_FILM, rc, schlieren_session_error(s), what);
      rc = schlieren_session_plan_film(s, dims, o, h, size, origin, &px);
      outcome(F_PLAN, rc, schlieren_session_error(s), what);
      break;
    }
    case 10:
    {
      const char* r = schlieren_session_report(s);
      outcome(F_REPORT, r == NULL, "no report", what);
      break;
    }
    case 11:
    {
      int i = below(POOL);
      if (below(3) == 0)
      {
        schlieren_session_free(pool[i]);
        freed[i] = pool[i];
        pool[i] = schlieren_session_new();
      }
      else
      {
        /* freed, foreign, NULL: refused (a freed address a new session took is that session) */
        static int foreign = 0;
        schlieren_session* bad = below(3) == 0 ? NULL : (below(2) ? freed[below(POOL)] : (schlieren_session*)(void*)&foreign);
        for (i = 0; i < POOL; ++i)
          if (bad == pool[i])
            bad = NULL;
        schlieren_session_free(bad);
      }
      ++calls[F_FREE];
      ++done[F_FREE];
      break;
    }
    case 12:
    {
      static const char* lines[] = { "Scene=GaussianSphere", "Scene=HeliumPlume", "Scene=BlastWave",
        "Scene=gaussiansphere", "Scene=NoScene", "Amplitude=1e300", "Amplitude=nan", "Amplitude=big",
        "Width=0", "Width=-1", "Radius=inf", "Mach=0.5", "Density=1e7", "Time=0", "Body=Sphere",
        "Body=Cylinder", "BodyCenter=nan 0 0", "BodyCenter=0 0", "BodyAxis=0 0 0", "BodyRadius=-1",
        "Center=inf 0 0", "GradientB=1e300", "Nonsense", "Bogus=1", "=1", "Scene=LinearGradient" };
      char settings[512] = "";
      int i, n = below(4);
      float *n1, *density, *mix;
      unsigned char* solid;
      for (i = 0; i < n; ++i)
      {
        strcat(settings, lines[below((int)(sizeof(lines) / sizeof(lines[0])))]);
        strcat(settings, "\n");
      }
      count = grid_count(needed, valid);
      n1 = buffer(count, sizeof(float), 1);
      density = below(2) ? buffer(count, sizeof(float), 0) : NULL;
      mix = below(2) ? buffer(count, sizeof(float), 0) : NULL;
      solid = below(2) ? buffer(count, 1, 0) : NULL;
      rc = schlieren_fill_scene(below(10) ? settings : NULL, dims, o, h, count, n1, density, mix, solid);
      outcome(F_FILL, rc, schlieren_last_error(), what);
      free(n1);
      free(density);
      free(mix);
      free(solid);
      break;
    }
    case 13:
    {
      float* n1;
      unsigned char* levels;
      double fraction;
      count = grid_count(needed, valid);
      n1 = buffer(count, sizeof(float), 1);
      levels = buffer(count, 1, 1);
      rc = schlieren_octree_levels(dims, n1, count, below(4) ? uniform() * 1e-5 : (below(2) ? NAN : -1),
        below(3) ? 7 : below(40) - 20, levels, below(2) ? &fraction : NULL);
      outcome(F_OCTREE, rc, schlieren_last_error(), what);
      free(n1);
      free(levels);
      break;
    }
    case 14:
    {
      float *n1, *g;
      count = grid_count(needed, valid);
      count2 = below(4) ? (count >= 0 && count < 1000000 ? 3 * count : count) : random_count(3 * needed);
      if (!valid && count2 > 1000000)
        count2 = 3;
      n1 = buffer(count, sizeof(float), 1);
      g = buffer(count2, sizeof(float), 1);
      rc = schlieren_gradient(dims, below(8) ? h : NULL, n1, count, g, count2);
      outcome(F_GRADIENT, rc, schlieren_last_error(), what);
      free(n1);
      free(g);
      break;
    }
    case 15:
    {
      static const char* settings[] = { "", "Mode=Slice", "Mode=LineOfSight", "Mode=slice",
        "Resolution=24 20", "Resolution=0 0", "Resolution=1e300 2", "KnifeAngle=1e300",
        "Gradient=KnifeComponent", "StepSize=0", "Bogus=1", "ViewDirection=0 0 0",
        "GradientMaximum=nan" };
      float *values, *out, *grad;
      unsigned char *solid, *excluded, *blocked;
      int64_t capacity = below(3) ? 24 * 20 : random_count(24 * 20);
      int size[2];
      double film_origin[2], px, ml[2];
      if (capacity < 0 || capacity > 1000000)
        capacity = below(2) ? 10 : -1;
      count = grid_count(needed, valid);
      count2 = below(2) ? 0 : grid_count(needed, valid);
      count3 = below(2) ? 0 : grid_count(needed, valid);
      values = buffer(count, sizeof(float), 1);
      solid = count2 ? buffer(count2, 1, 1) : NULL;
      excluded = count3 ? buffer(count3, 1, 1) : NULL;
      out = below(6) ? calloc((size_t)(capacity > 0 ? capacity : 1), sizeof(float)) : NULL;
      grad = calloc((size_t)(capacity > 0 ? capacity : 1), sizeof(float));
      blocked = below(6) ? calloc((size_t)(capacity > 0 ? capacity : 1), 1) : NULL;
      rc = schlieren_numerical(settings[below(13)], dims, o, h, values, count, solid, count2,
        excluded, count3, size, film_origin, &px, capacity, out, grad, blocked, below(2) ? ml : NULL);
      outcome(F_NUMERICAL, rc, schlieren_last_error(), what);
      free(values);
      free(solid);
      free(excluded);
      free(out);
      free(grad);
      free(blocked);
      break;
    }
    case 16:
    {
      static const char* models[] = { "Passthrough", "GladstoneDale", "passthrough", "Ciddor", "", NULL };
      static const char* gases[] = { NULL, "", "Air", "He", "air", "Custom 2.256e-4 0.029",
        "Custom nan 1", "Custom 1", "Unobtainium" };
      int64_t c = random_count(below(100));
      float *in, *out;
      const char* report = NULL;
      if (c > 1000000)
        c = -5;
      in = buffer(c, sizeof(float), 1);
      out = buffer(c, sizeof(float), 1);
      if (in && c > 0)
      {
        int64_t i;
        for (i = 0; i < c; ++i)
          in[i] = below(10) ? (float)uniform() : (below(2) ? NAN : -1.0f);
      }
      rc = schlieren_field_index(models[below(6)], in, c, below(2), below(4) ? 1.0 : NAN,
        gases[below(9)], out, below(2) ? &report : NULL);
      outcome(F_FIELD, rc, schlieren_last_error(), what);
      free(in);
      free(out);
      break;
    }
    case 17:
    {
      unsigned char* v;
      float* n1;
      int64_t filled;
      count = grid_count(needed, valid);
      v = buffer(count, 1, 1);
      n1 = buffer(count, sizeof(float), 1);
      if (v && count > 0 && count <= 1000000)
      {
        int64_t i;
        for (i = 0; i < count; ++i)
          v[i] = (unsigned char)(below(3) != 0);
      }
      rc = schlieren_extend_into_invalid(dims, v, count, n1, below(2) ? &filled : NULL);
      outcome(F_EXTEND, rc, schlieren_last_error(), what);
      free(v);
      free(n1);
      break;
    }
    case 18:
    {
      double b[6];
      int out[3], i, longest;
      static const int longs[] = { 128, 2, 1, 0, -5, 2147483647, -2147483647 - 1, 4096 };
      for (i = 0; i < 6; ++i)
        b[i] = below(10) ? (i % 2 ? 1.0 : -1.0) * uniform() * 10 : (below(2) ? NAN : INFINITY);
      longest = longs[below(8)];
      rc = schlieren_automatic_dimensions(below(10) ? b : NULL, longest, below(10) ? out : NULL);
      outcome(F_AUTODIMS, rc, schlieren_last_error(), what);
      rc = schlieren_check_memory(below(2) ? 1e20 : (below(2) ? NAN : -1.0), below(2) ? "A thing" : NULL,
        below(2) ? "Lower it." : NULL);
      outcome(F_MEMORY, rc, schlieren_last_error(), what);
      {
        static const char* const proxies[] = { "RefractiveIndex", "RefractionOctree", "Nothing",
          "" };
        static const char* const props[] = { "Wavelength", "SamplingDimensions", "BodyWallFaces",
          "Tolerance", "BodyFromGrid", "NoSuchName", "" };
        const int count = below(4) ? (int)below(7) : -3;
        rc = schlieren_check_property(below(10) ? proxies[below(4)] : NULL,
          below(10) ? props[below(7)] : NULL, below(10) ? b : NULL, count);
        outcome(F_PROPERTY, rc, schlieren_last_error(), what);
      }
      break;
    }
    case 19:
    {
      /* RefractiveIndex's symmetry: a plan from random settings and points (a rectangle or a
       * wedge-like slab, NaN at times, lengths off at times), then its samples and their
       * expansion with random lengths and indices */
      static const char* settings[] = { "Symmetry=Planar\nAutomaticDimension=12",
        "Symmetry=Axisymmetric\nSymmetryAxis=X\nAutomaticDimension=10",
        "Symmetry=Axisymmetric\nSymmetryAxis=Z\nAxisFromWedge=0\nAutomaticDimension=8",
        "Symmetry=Planar\nSpan=-1", "Symmetry=None", "Symmetry=planar", "Symetry=Planar",
        "Symmetry=Planar\nSamplingDimensions=4 5 3",
        "Symmetry=Axisymmetric\nSamplingDimensions=1 1 1",
        "Symmetry=Axisymmetric\nSamplingDimensions=5 6 7\nUseSamplingBounds=1\n"
        "SamplingBounds=0 1 -1 1 -1 1",
        "not a line", "Symmetry=Planar\nAutomaticDimension=1e30", "Symmetry=Planar\nSpan=nan",
        "Symmetry=Axisymmetric\nSymmetryAxis=W", "" };
      double b[6], g[8], o3[3], h3[3], *pts, *xyz;
      int d3[3], ext[6], i, thin;
      const char* report;
      int64_t np = below(5) ? 3 * (int64_t)below(60) : (below(2) ? -3 : 7), m = 0, cells, c, xc,
        vc, oc;
      int64_t *of;
      float *vals, *out;
      unsigned char *sv, *v;
      pts = buffer(np, sizeof(double), 1);
      if (pts && np > 0 && np <= 1000000)
      {
        int64_t k;
        for (k = 0; k < np / 3; ++k)
        {
          pts[3 * k] = uniform();
          pts[3 * k + 1] = 0.1 + uniform();
          pts[3 * k + 2] = below(2) ? 0.0 : 0.05 * pts[3 * k + 1] * (below(2) ? 1 : -1);
          if (below(80) == 0)
            pts[3 * k + below(3)] = below(2) ? NAN : INFINITY;
        }
      }
      for (i = 0; i < 6; ++i)
        b[i] = below(20) ? (i % 2 ? 1.1 : (i == 4 ? -0.06 : 0.0)) : (below(2) ? NAN : -5.0);
      if (below(2))
        b[4] = b[5] = 0.0;
      for (i = 0; i < 3; ++i)
      {
        ext[2 * i] = below(8) ? 0 : -2;
        ext[2 * i + 1] = below(20) ? below(6) : -7;
      }
      rc = schlieren_symmetry_plan(below(20) ? settings[below(15)] : NULL, below(10) ? b : NULL,
        pts, np, (int)below(2), below(3) == 0 ? ext : NULL, below(10) ? o : NULL, h,
        below(40) ? d3 : NULL, o3, h3, g, below(2) ? &report : NULL);
      outcome(F_SYMMETRY, rc, schlieren_last_error(), what);
      free(pts);
      if (rc != 0)
      {
        /* the later calls with a made-up geometry */
        for (i = 0; i < 8; ++i)
          g[i] = below(10) ? (double)below(3) : (below(2) ? NAN : -1.5);
        for (i = 0; i < 3; ++i)
          d3[i] = dims[i], o3[i] = o[i], h3[i] = h[i];
      }
      if (rc != 0 && !valid)
        break; /* a huge made-up grid: its samples would be real allocations */
      cells = (int64_t)d3[0] * d3[1] * d3[2];
      if (cells > 300000 || d3[0] < 1 || d3[1] < 1 || d3[2] < 1)
        break;
      rc = schlieren_symmetry_samples(g, d3, o3, h3, below(30) ? &m : NULL, NULL, 0, NULL, 0);
      outcome(F_SYMMETRY, rc, schlieren_last_error(), what);
      if (rc != 0)
        m = 1 + below(5);
      c = random_count(cells);
      xc = below(5) ? 3 * m : random_count(3 * m);
      xyz = buffer(xc, sizeof(double), 1);
      of = buffer(c, sizeof(int64_t), 1);
      rc = schlieren_symmetry_samples(g, d3, o3, h3, &m, xyz, xc, of, c);
      outcome(F_SYMMETRY, rc, schlieren_last_error(), what);
      if (of && rc != 0 && c > 0 && c <= 1000000)
      {
        int64_t k;
        for (k = 0; k < c; ++k)
          of[k] = below(50) ? (int64_t)below((unsigned)(m > 0 ? m : 1)) : (below(2) ? -1 : m);
      }
      thin = 1 + (int)below(4);
      vc = below(5) ? scaled(m, thin) : random_count(scaled(m, thin));
      oc = below(5) ? scaled(c, thin) : random_count(scaled(c, thin));
      vals = buffer(vc, sizeof(float), 1);
      out = buffer(oc, sizeof(float), 1);
      sv = buffer(m, 1, 1);
      v = buffer(c, 1, 1);
      rc = schlieren_symmetry_expand(of, c, below(20) ? m : -1, vals, vc, below(20) ? thin : 0,
        out, oc, sv, m, v, c);
      outcome(F_SYMMETRY, rc, schlieren_last_error(), what);
      free(xyz);
      free(of);
      free(vals);
      free(out);
      free(sv);
      free(v);
      break;
    }
    case 20:
    {
      double b[6], *pts;
      const char* warning;
      int thin, i;
      int64_t np = below(5) ? 3 * (int64_t)below(60) : (below(2) ? -3 : 5);
      pts = buffer(np, sizeof(double), 1);
      if (pts && np > 0 && np <= 1000000)
      {
        int64_t k;
        for (k = 0; k < np / 3; ++k)
        {
          pts[3 * k] = uniform();
          pts[3 * k + 1] = 0.1 + uniform();
          pts[3 * k + 2] = 0.04 * pts[3 * k + 1] * (below(2) ? 1 : -1);
          if (below(80) == 0)
            pts[3 * k] = NAN;
        }
      }
      for (i = 0; i < 6; ++i)
        b[i] = below(20) ? (i % 2 ? 1.1 : (i == 4 ? -0.05 : 0.0)) : NAN;
      rc = schlieren_wedge_warning(below(20) ? b : NULL, pts, np, below(2) ? &thin : NULL,
        below(20) ? &warning : NULL);
      outcome(F_WEDGE, rc, schlieren_last_error(), what);
      free(pts);
      break;
    }
    case 21:
    {
      /* a photograph beside the film: sizes, lengths, NaN, blank and bad settings */
      static const int sides[] = { 16, 24, 17, 15, 0, -3, 40000, 300 };
      static const char* settings[] = { "", "Refine=Shift", "Refine=None", "Refine=none", "PhotoPixelSize=0.01",
        "PointPairs=1 2 3 4", "PointPairs=0 0 0 0 1 1 0 0", "ScaleRange=2 1", "LineThreshold=0", "Bogus=1",
        "MaxRotation=nan", "PointPairs=0 0 -1 -1 20 20 1 1\nRefine=None" };
      int fs[2], ps[2], i;
      double fo[2] = { -1, -1 };
      int64_t nf, np, cap;
      float *film, *photo, *out;
      const char* report = NULL;
      fs[0] = sides[below(4) ? 0 : below(8)];
      fs[1] = sides[below(4) ? 1 : below(7)];
      ps[0] = sides[below(4) ? 1 : below(8)];
      ps[1] = sides[below(4) ? 2 : below(7)];
      nf = (int64_t)fs[0] * fs[1];
      np = (int64_t)ps[0] * ps[1];
      if (nf < 0 || nf > 10000)
        nf = below(2) ? 16 : -1;
      if (np < 0 || np > 10000)
        np = below(2) ? 16 : -1;
      nf = below(8) ? nf : random_count(nf);
      if (nf > 10000)
        nf = 3;
      cap = below(6) ? nf : nf + 1;
      film = buffer(nf, sizeof(float), 1);
      photo = buffer(np, sizeof(float), 1);
      out = below(3) ? calloc((size_t)(cap > 0 ? cap : 1), sizeof(float)) : NULL;
      if (film && nf > 0)
      {
        for (i = 0; i < nf; ++i)
          film[i] = (float)uniform();
        if (below(10) == 0)
          film[below((int)nf)] = NAN;
      }
      if (photo && np > 0)
      {
        int blank = below(4) == 0;
        for (i = 0; i < np; ++i)
          photo[i] = blank ? 0.5f : (float)uniform();
        if (below(10) == 0)
          photo[below((int)np)] = INFINITY;
      }
      rc = schlieren_photograph(below(10) ? settings[below(12)] : NULL, below(20) ? fs : NULL, fo,
        below(10) ? 0.01 : (below(2) ? NAN : -1.0), film, nf, ps, photo, np, cap, out, NULL, out ? NULL : NULL,
        NULL, below(2) ? out : NULL, below(2) ? &report : NULL);
      outcome(F_PHOTOGRAPH, rc, schlieren_last_error(), what);
      free(film);
      free(photo);
      free(out);
      break;
    }
    default:
    {
      const char* text;
      text = schlieren_version();
      text = schlieren_properties();
      text = schlieren_opencl_device(below(2) ? NULL : (below(2) ? "" : "no such device \xff"));
      text = schlieren_session_error(s);
      ++calls[F_MISC];
      ++done[F_MISC];
      (void)text;
      break;
    }
  }
}

/* schlieren_sample_cells: a small mesh (two hexahedra side by side, a tetrahedron, a wedge, a
 * pyramid, a face) with each length, id, type and number varied; the right call must find the
 * points it should (fixed_sample_case) */
/* mostly the right count: a call with one thing wrong tests that thing */
static int64_t sometimes_wrong(int64_t needed)
{
  return below(4) ? needed : random_count(needed);
}

static void random_sample_case(void)
{
  /* points: a 3 x 2 x 2 block (12 points) and a few loose ones */
  double pts[3 * 16];
  unsigned char types[6] = { 12, 12, 10, 13, 14, 9 };
  int64_t offsets[7] = { 0, 8, 16, 20, 26, 31, 35 };
  int64_t conn[35] = { 0, 1, 4, 3, 6, 7, 10, 9, 1, 2, 5, 4, 7, 8, 11, 10, 0, 1, 3, 6, 0, 1, 3, 6,
    7, 9, 0, 1, 4, 3, 12, 0, 1, 4, 3 };
  unsigned char skip[6] = { 0, 0, 0, 0, 0, 0 };
  int dims[3], sdims[3] = { 3, 2, 2 }, valid, i, structured = below(4) == 0;
  int64_t needed, npts = 13, ncells = 6, nconn = 35, c_pts, c_types, c_off, c_conn, c_skip, c_found;
  int64_t found_here;
  double origin[3] = { -0.1, -0.1, -0.1 }, spacing[3] = { 0.25, 0.25, 0.25 };
  float pa[16 * 2];
  double ca[6];
  const char* names[2] = { "pa", "ca" };
  int is_cell[2] = { 0, 1 }, comps[2] = { 2, 1 }, bytes[2] = { 4, 8 };
  const void* ins[2];
  void* outs[2];
  int64_t in_len[2], out_len[2];
  unsigned char* found;
  int narrays = below(10) ? 2 : (below(2) ? 0 : -1);
  int rc;
  for (i = 0; i < 12; ++i)
  {
    pts[3 * i] = (double)(i % 3);
    pts[3 * i + 1] = (double)((i / 3) % 2);
    pts[3 * i + 2] = (double)(i / 6);
  }
  pts[36] = 0.5;
  pts[37] = 0.5;
  pts[38] = -1.0;
  for (i = 0; i < 16 * 2; ++i)
    pa[i] = (float)i;
  for (i = 0; i < 6; ++i)
    ca[i] = 10.0 * i;
  if (below(16) == 0)
    random_point(pts + 3 * below(13));
  if (below(16) == 0)
    types[below(6)] = (unsigned char)(below(2) ? 42 : below(256));
  if (below(16) == 0)
    conn[below(35)] = below(2) ? -1 : (below(2) ? 13 : INT64_MAX);
  if (below(16) == 0)
    offsets[1 + below(6)] = below(2) ? 3 : -2;
  if (below(16) == 0)
    sdims[below(3)] = below(2) ? 0 : 2147483647;
  random_grid(dims, &needed, &valid);
  if (below(10) == 0)
    spacing[below(3)] = below(2) ? 0.0 : NAN;
  c_pts = sometimes_wrong(3 * (structured ? 12 : npts));
  if (c_pts < 0 || c_pts > 3 * 16)
    c_pts = below(2) ? -1 : 3 * 16;
  c_types = structured ? (below(4) ? 0 : 6) : sometimes_wrong(ncells);
  if (c_types < 0 || c_types > 6)
    c_types = below(2) ? -1 : 6;
  c_off = structured ? (below(4) ? 0 : 7) : sometimes_wrong(c_types + 1);
  if (c_off < 0 || c_off > 7)
    c_off = below(2) ? -1 : 7;
  c_conn = structured ? 0 : sometimes_wrong(nconn);
  if (c_conn < 0 || c_conn > 35)
    c_conn = below(2) ? -1 : 35;
  c_skip = below(2) ? 0 : sometimes_wrong(structured ? 2 : ncells);
  if (c_skip < 0 || c_skip > 6)
    c_skip = below(2) ? -1 : 6;
  c_found = (below(4) ? needed : grid_count(needed, valid));
  found = buffer(c_found, 1, 1);
  ins[0] = pa;
  ins[1] = ca;
  in_len[0] = sometimes_wrong(2 * (structured ? 12 : npts));
  if (in_len[0] < 0 || in_len[0] > 32)
    in_len[0] = below(2) ? -1 : 32;
  in_len[1] = sometimes_wrong(structured ? 2 : ncells);
  if (in_len[1] < 0 || in_len[1] > 6)
    in_len[1] = below(2) ? -1 : 6;
  if (below(20) == 0)
    comps[below(2)] = below(2) ? 0 : 3;
  if (below(20) == 0)
    bytes[below(2)] = below(2) ? 2 : 0;
  out_len[0] = (below(4) ? 2 * needed : grid_count(2 * needed, valid));
  out_len[1] = (below(4) ? needed : grid_count(needed, valid));
  outs[0] = buffer(out_len[0], sizeof(float), 1);
  outs[1] = buffer(out_len[1], sizeof(double), 1);
  if (below(2))
  {
    rc = schlieren_sample_cells(below(30) ? pts : NULL, c_pts, structured ? sdims : NULL,
      below(30) ? types : NULL, c_types, below(30) ? offsets : NULL, c_off,
      below(30) ? conn : NULL, c_conn, c_skip ? skip : NULL, c_skip, narrays,
      below(40) ? names : NULL, is_cell, comps, bytes, ins, in_len, outs, out_len, dims, origin,
      spacing, found, c_found, below(2) ? &found_here : NULL);
    outcome(F_SAMPLE, rc, schlieren_last_error(), "schlieren_sample_cells");
  }
  else
  {
    /* the points mode: 8 points to sample (a few not finite or far), the outputs and found
     * sized for them (or wrongly) */
    double at[3 * 8];
    int64_t c_at = sometimes_wrong(24), c_found_at, m = 8, len_at[2];
    unsigned char* found_at;
    void* outs_at[2];
    for (i = 0; i < 24; ++i)
      at[i] = 2.2 * uniform() - 0.1;
    if (below(8) == 0)
      random_point(at + 3 * below(8));
    if (c_at < 0 || c_at > 24)
      c_at = below(2) ? -1 : 24;
    c_found_at = sometimes_wrong(m);
    if (c_found_at < -1 || c_found_at > m)
      c_found_at = m;
    len_at[0] = sometimes_wrong(2 * m);
    if (len_at[0] < -1 || len_at[0] > 2 * m)
      len_at[0] = 2 * m;
    len_at[1] = sometimes_wrong(m);
    if (len_at[1] < -1 || len_at[1] > m)
      len_at[1] = m;
    found_at = buffer(c_found_at, 1, 1);
    outs_at[0] = buffer(len_at[0], sizeof(float), 1);
    outs_at[1] = buffer(len_at[1], sizeof(double), 1);
    rc = schlieren_sample_cells_at(below(30) ? pts : NULL, c_pts, structured ? sdims : NULL,
      below(30) ? types : NULL, c_types, below(30) ? offsets : NULL, c_off,
      below(30) ? conn : NULL, c_conn, c_skip ? skip : NULL, c_skip, narrays,
      below(40) ? names : NULL, is_cell, comps, bytes, ins, in_len, outs_at, len_at,
      below(30) ? at : NULL, c_at, found_at, c_found_at, below(2) ? &found_here : NULL);
    outcome(F_SAMPLE, rc, schlieren_last_error(), "schlieren_sample_cells_at");
    free(found_at);
    free(outs_at[0]);
    free(outs_at[1]);
  }
  free(found);
  free(outs[0]);
  free(outs[1]);
}

/* the right call: the points inside the two hexahedra and the tetrahedron are found, with the
 * trilinear value (exact at these points), and a polyhedron is refused by name */
static void fixed_sample_case(void)
{
  double pts[3 * 12];
  unsigned char types[2] = { 12, 42 };
  int64_t offsets[3] = { 0, 8, 16 };
  int64_t conn[16] = { 0, 1, 4, 3, 6, 7, 10, 9, 1, 2, 5, 4, 7, 8, 11, 10 };
  double values[12];
  float out[5 * 3 * 3];
  unsigned char found[5 * 3 * 3];
  const char* names[1] = { "x" };
  int is_cell[1] = { 0 }, comps[1] = { 1 }, bytes[1] = { 4 };
  float fvalues[12];
  const void* ins[1] = { fvalues };
  void* outs[1] = { out };
  int64_t in_len[1] = { 12 }, out_len[1] = { 45 }, n = -1;
  int dims[3] = { 5, 3, 3 }, i, rc, ok = 1;
  double origin[3] = { 0, 0, 0 }, spacing[3] = { 0.5, 0.5, 0.5 };
  for (i = 0; i < 12; ++i)
  {
    pts[3 * i] = (double)(i % 3);
    pts[3 * i + 1] = (double)((i / 3) % 2);
    pts[3 * i + 2] = (double)(i / 6);
    values[i] = pts[3 * i];
    fvalues[i] = (float)values[i];
  }
  memset(found, 0, sizeof found);
  memset(out, 0, sizeof out);
  types[1] = 12;
  rc = schlieren_sample_cells(pts, 36, NULL, types, 2, offsets, 3, conn, 16, NULL, 0, 1, names,
    is_cell, comps, bytes, ins, in_len, outs, out_len, dims, origin, spacing, found, 45, &n);
  /* the block is x in [0, 2], y and z in [0, 1]: 5 x 3 x 3 grid points, all inside */
  for (i = 0; i < 45 && rc == 0; ++i)
    ok = ok && found[i] == 1 && out[i] == (float)(0.5 * (i % 5));
  if (rc != 0 || n != 45 || !ok)
  {
    ++failures;
    printf("FAIL: schlieren_sample_cells on two hexahedra: rc %d, %lld found (45 wanted), values %s: %s\n",
      rc, (long long)n, ok ? "right" : "wrong", schlieren_last_error());
  }
  types[1] = 42;
  rc = schlieren_sample_cells(pts, 36, NULL, types, 2, offsets, 3, conn, 16, NULL, 0, 1, names,
    is_cell, comps, bytes, ins, in_len, outs, out_len, dims, origin, spacing, found, 45, &n);
  if (rc == 0 || !strstr(schlieren_last_error(), "polyhedron"))
  {
    ++failures;
    printf("FAIL: schlieren_sample_cells took a polyhedron (rc %d): %s\n", rc, schlieren_last_error());
  }
}

/* schlieren_amr_overlap, _grid and _sample: two boxes on two levels (a float point array, a
 * double cell array of 2 components) with levels, extents, origins, spacings, lengths, names and
 * grids varied; every buffer holds what its count says (or the count must be refused) */
static void random_amr_case(void)
{
  static const int extent_values[] = { 0, 4, 2, 6, -1, 2147483647, -2147483647 - 1, 1073741824 };
  int levels = below(6) ? 2 : (below(2) ? -1 : (below(2) ? 0 : 5000));
  int nblocks = below(8) ? 2 : (below(2) ? 1 : (below(2) ? 0 : -1));
  int block_levels[2] = { 0, 1 }, extents[12] = { 0, 4, 0, 4, 0, 4, 2, 6, 2, 6, 2, 6 };
  double origins[6] = { 0, 0, 0, 0, 0, 0 }, spacings[6] = { 1, 1, 1, 0.5, 0.5, 0.5 };
  double bounds[6] = { 0, 4, 0, 4, 0, 4 }, finest[3], go[3], gh[3];
  const char* names[2] = { "p", "c" };
  int is_cell[4] = { 0, 1, 0, 1 }, comps[4] = { 1, 2, 1, 2 }, bytes[4] = { 4, 8, 4, 8 };
  const void* ins[4];
  int64_t lengths[4], needed;
  int out_components[2], gd[3], gdims[3], flevel, capped, b, a, valid, i, corners[12];
  const float* outs[2];
  const unsigned char* mask;
  const char *report, *note;
  void* buffers[4];
  for (b = 0; b < 2; ++b)
  {
    if (below(12) == 0)
      block_levels[b] = below(2) ? -1 : 7;
    for (a = 0; a < 6; ++a)
      if (below(30) == 0)
        extents[6 * b + a] = extent_values[below(8)];
    for (a = 0; a < 3; ++a)
    {
      if (below(30) == 0)
        origins[3 * b + a] = below(2) ? NAN : -1e308;
      if (below(30) == 0)
        spacings[3 * b + a] = below(3) ? 0.0 : (below(2) ? -0.5 : INFINITY);
    }
  }
  for (i = 0; i < 4; ++i)
  {
    const int* e = extents + 6 * (i / 2);
    int64_t tuples = 1;
    for (a = 0; a < 3; ++a)
    {
      int64_t np = (int64_t)e[2 * a + 1] - e[2 * a] + 1;
      np = np < 0 ? 0 : np;
      tuples *= is_cell[i] ? (np - 1 > 1 ? np - 1 : 1) : np;
      if (tuples > 1000000)
        tuples = 2000000;
    }
    needed = tuples * comps[i];
    if (below(20) == 0)
      comps[i] = below(2) ? 0 : 3000;
    if (below(20) == 0)
      bytes[i] = below(2) ? 2 : 16;
    lengths[i] = sometimes_wrong(needed);
    buffers[i] = buffer(lengths[i], bytes[i] == 8 ? sizeof(double) : sizeof(float), 1);
    ins[i] = below(6) ? buffers[i] : NULL;
    if (!ins[i] && below(2))
      lengths[i] = 0; /* the box has no such array */
  }
  random_grid(gd, &needed, &valid);
  if (!valid)
    gd[below(3)] = below(2) ? 0 : -3; /* no huge grid: the engine would allocate it */
  for (a = 0; a < 3; ++a)
  {
    go[a] = below(30) ? -0.5 + uniform() : NAN;
    gh[a] = below(30) ? 0.2 + uniform() : (below(2) ? 0.0 : -1.0);
    if (below(40) == 0)
      bounds[2 * a + 1] = below(2) ? NAN : -9.0;
  }
  {
    int rc = schlieren_amr_sample(levels, nblocks, below(30) ? block_levels : NULL, extents,
      below(30) ? origins : NULL, spacings, below(8) ? 2 : (below(2) ? 0 : -2),
      below(30) ? names : NULL, is_cell, comps, bytes, ins, lengths, below(30) ? gd : NULL, go, gh,
      below(30) ? out_components : NULL, below(30) ? outs : NULL, below(30) ? &mask : NULL,
      below(30) ? &report : NULL);
    outcome(F_AMR, rc, schlieren_last_error(), "schlieren_amr_sample");
    rc = schlieren_amr_grid(levels, nblocks, block_levels, extents, origins, spacings,
      below(30) ? bounds : NULL, below(20) ? 100.0 : (below(2) ? 0.0 : NAN), gdims, finest,
      below(30) ? &flevel : NULL, &capped, below(30) ? &note : NULL);
    outcome(F_AMR, rc, schlieren_last_error(), "schlieren_amr_grid");
    for (i = 0; i < 12; ++i)
      corners[i] = below(10) && extents[i] > -2147483647 - 1 ? extents[i] - (i % 6 >= 3 ? 1 : 0)
                                                             : extent_values[below(8)];
    rc = schlieren_amr_overlap(below(10) ? 2 : (below(2) ? 0 : -1), below(30) ? block_levels : NULL,
      below(30) ? corners : NULL);
    outcome(F_AMR, rc, schlieren_last_error(), "schlieren_amr_overlap");
  }
  for (i = 0; i < 4; ++i)
    free(buffers[i]);
}

/* schlieren_time_cache_find and _insert: up to 4 entries (times, tokens, extents, bytes) with
 * counts, NaN, negative and huge bytes, NULLs and extents varied */
static void random_time_cache_case(void)
{
  double times[4], bytes[4], budget;
  uint64_t tokens[4];
  int extents[24], i, keep_new;
  unsigned char keep[4];
  int64_t index, count = below(10) ? below(5) : (below(2) ? -1 : INT64_MAX);
  for (i = 0; i < 4; ++i)
  {
    times[i] = below(20) ? below(4) : NAN;
    tokens[i] = below(4) ? 3 : (uint64_t)below(1000) << 40;
    bytes[i] = below(20) ? 1e6 * uniform() : (below(2) ? -1.0 : (below(2) ? NAN : 1e300));
  }
  for (i = 0; i < 24; ++i)
    extents[i] = below(20) ? (i % 2 ? 9 : 0) : below(2) ? -2147483647 - 1 : 2147483647;
  {
    const int rc = schlieren_time_cache_find(count, below(30) ? times : NULL,
      below(30) ? tokens : NULL, below(30) ? extents : NULL, below(3) ? bytes : NULL,
      below(20) ? below(4) : NAN, below(4) ? 3 : 4, below(30) ? extents : NULL,
      below(30) ? &index : NULL, below(2) ? &budget : NULL);
    outcome(F_TIME_CACHE, rc, schlieren_last_error(), "schlieren_time_cache_find");
  }
  {
    const int rc = schlieren_time_cache_insert(count, below(30) ? times : NULL,
      below(30) ? tokens : NULL, below(30) ? extents : NULL, below(30) ? bytes : NULL,
      below(20) ? below(4) : INFINITY, below(4) ? 3 : 4, below(30) ? extents : NULL,
      below(20) ? 1e6 * uniform() : (below(2) ? -5.0 : 1e300), below(30) ? keep : NULL,
      below(30) ? &keep_new : NULL, below(2) ? &budget : NULL);
    outcome(F_TIME_CACHE, rc, schlieren_last_error(), "schlieren_time_cache_insert");
  }
}

/* schlieren_index_field with random settings, arrays, lengths and masks: done, or refused with a
   message, never a crash */
static void random_index_field_case(int k)
{
  static const char* settings[] = { "", "Model=GladstoneDale", "Model=Passthrough\nInputArray=a",
    "Model=IdealGas\nTemperatureArray=a\nPressureArray=b", "Model=Automatic",
    "Model=GladstoneDale\nInputArray=b\nAmbientMode=Value\nAmbientValue=nan",
    "Model=GladstoneDaleMixture\nInputArray=a\nMixtureFractionArray=b",
    "Model=Ciddor\nTemperatureArray=a\nPressureArray=b\nHumidityFromArray=2",
    "Model=Passthrough\nInputArray=a\nSolidArray=b\nBodyWallFaces=1 0 1", "Bogus=1",
    "Model=GladstoneDale\nInputArray=a\nAmbientMode=DomainEdgeMedian\nResampled=1\nBodyOverlaps=0",
    "Model=GladstoneDale\nInputArray=c\nSolidArray=c",
    "Model=GladstoneDale\nInputArray=a\nResampled=1\nWallFaceCounts=3 1 0 0\nWallVelocity=U",
    "Model=GladstoneDale\nWallFaceCounts=-1 1 0 nan\nBodySurface=open" };
  static const char* names[] = { "a", "b", "c", "", NULL };
  static const int good[] = { 1, 2, 3, 6, 10, 12 };
  char what[160];
  int dims[3], valid, i, rc;
  int64_t needed, counts[3], c_valid, c_rim, c_n1, c_grad, c_solid;
  double h[3];
  const char* nm[3];
  int comps[3], bytes[3];
  void* values[3];
  unsigned char *v, *rim, *solid;
  float *n1, *grad;
  const char* report = NULL;
  int arrays = below(4);
  /* half the cases with every length right and names given: the settings and values decide */
  const int sane = below(2);
  random_grid(dims, &needed, &valid);
  if (sane && !valid)
  {
    dims[0] = 3 + below(4), dims[1] = 2 + below(3), dims[2] = 1 + below(3);
    needed = (int64_t)dims[0] * dims[1] * dims[2];
    valid = 1;
  }
  random_point(h);
  if (below(2) || sane)
    h[0] = h[1] = h[2] = 0.2;
  snprintf(what, sizeof(what), "index_field case %d: dims %d %d %d, %d arrays", k, dims[0],
    dims[1], dims[2], arrays);
  for (i = 0; i < arrays; ++i)
  {
    int64_t j;
    nm[i] = sane ? names[i] : names[below(5)];
    comps[i] = below(5) || sane ? 1 : below(4) - 1;
    bytes[i] = below(5) ? 4 : (below(2) || sane ? 8 : 3);
    counts[i] = sane ? needed : below(4) ? grid_count(needed, valid) : random_count(needed);
    if (counts[i] >= 0 && counts[i] <= 1000000 && comps[i] > 1)
      counts[i] *= comps[i];
    if (counts[i] > 1000000 || counts[i] < 0)
      counts[i] = below(2) ? -1 : 7;
    values[i] = buffer(counts[i], bytes[i] == 8 ? 8 : 4, !sane);
    for (j = 0; values[i] && j < counts[i]; ++j)
    {
      const double x = sane && below(20) ? 0.001 * (1.0 + uniform())
                                         : below(10) ? 1.0 + uniform() : (below(2) ? NAN : -1.0);
      if (bytes[i] == 8)
        ((double*)values[i])[j] = x;
      else
        ((float*)values[i])[j] = (float)x;
    }
  }
  c_valid = below(2) ? 0 : sane ? needed : grid_count(needed, valid);
  c_n1 = sane ? needed : grid_count(needed, valid);
  c_grad = below(5) || sane ? 3 * c_n1 : c_n1;
  if (c_n1 < 0 || c_n1 > 1000000)
    c_grad = c_n1;
  c_solid = sane ? needed : grid_count(needed, valid);
  v = c_valid ? (sane ? calloc((size_t)c_valid, 1) : buffer(c_valid, 1, 1)) : NULL;
  for (i = 0; v && c_valid <= 1000000 && i < c_valid; ++i)
    v[i] = (unsigned char)(below(4) != 0);
  c_rim = below(3) ? 0 : sane ? needed : grid_count(needed, valid);
  rim = c_rim ? (sane ? calloc((size_t)c_rim, 1) : buffer(c_rim, 1, 1)) : NULL;
  for (i = 0; rim && c_rim <= 1000000 && i < c_rim; ++i)
    rim[i] = (unsigned char)below(3);
  n1 = buffer(c_n1, sizeof(float), !sane);
  grad = buffer(c_grad, sizeof(float), !sane);
  solid = buffer(c_solid, 1, !sane);
  rc = schlieren_index_field(settings[sane ? good[below(6)] : below(14)], dims, h, arrays, nm, comps, bytes,
    (const void* const*)values, counts, below(4) - 1, below(2) ? "c\nd" : NULL,
    below(2) ? "a note" : NULL, v, c_valid, rim, c_rim,
    c_rim % 2 ? rim : NULL, c_rim % 2 ? c_rim : 0, /* the rim's bytes as a Body's inside */
    n1, c_n1, grad, c_grad, solid, c_solid,
    below(2) ? &report : NULL);
  outcome(F_INDEX_FIELD, rc, schlieren_last_error(), what);
  for (i = 0; i < arrays; ++i)
    free(values[i]);
  free(v);
  free(rim);
  free(n1);
  free(grad);
  free(solid);
}

/* schlieren_index_choices with random settings and names */
static void random_index_choices_case(int k)
{
  static const char* settings[] = { "", "Model=Automatic", "Model=automatic", "Model=IdealGas",
    "Model=Passthrough\nPassthroughHoldsN=1", "Model=Automatic\nInputArray=T",
    "Model=Automatic\nGas=He", "Model=Automatic\nGas=Unobtainium", "Model=GladstoneDaleMixture",
    "Model=Automatic\nTemperatureUnit=F", "Model=Ciddor\nPressureUnit=bar", "Wavelength=x",
    "Model=IdealGas\nIdealGasComposition=MixtureFraction", NULL, "Model" };
  static const char* present[] = { "", "rho", "T\np", "n\nx", "N_MINUS_1\nrho", "a\nb", NULL,
    "\n\n", "Temp\nPres\nF" };
  static const char* fallback[] = { NULL, "", "a", "rho" };
  char what[64];
  const char* report = NULL;
  int rc;
  snprintf(what, sizeof(what), "index_choices case %d", k);
  rc = schlieren_index_choices(settings[below(15)], present[below(9)], fallback[below(4)],
    below(2) ? &report : NULL);
  outcome(F_INDEX_CHOICES, rc, schlieren_last_error(), what);
}

/* schlieren_cell_fields with random settings, places and names */
static void random_cell_fields_case(int k)
{
  static const char* settings[] = { "", "Model=GladstoneDale\nInputArray=rho",
    "Model=IdealGas\nTemperatureArray=T\nPressureArray=p", "Model=Automatic", "Model=Ciddor\n"
    "TemperatureArray=T\nPressureArray=p\nHumidityFromArray=1\nHumidityArray=rh",
    "InputArray=ObjectId", NULL, "Model", "Gas=Unobtainium", "Model=Passthrough\nInputArray=\t" };
  static const char* arrays[] = { "", NULL, "rho\tcell\tfloat", "rho\tpoint\tdouble\nrho\tcell",
    "T\tcell\tint\np\tcell\tdouble", "rho", "rho\t\t", "ObjectId\tcell\tdouble\n\t\t\n",
    "rh\tcell\tbit\nT\tpoint\tfloat\np\tpoint\tfloat", "\tcell\tfloat" };
  static const char* present[] = { NULL, "", "rho\nT\np", "\n\n" };
  char what[64];
  const char* report = NULL;
  int rc;
  snprintf(what, sizeof(what), "cell_fields case %d", k);
  rc = schlieren_cell_fields(settings[below(10)], arrays[below(10)], present[below(4)],
    below(2) ? &report : NULL);
  outcome(F_CELL_FIELDS, rc, schlieren_last_error(), what);
}

/* schlieren_wall_faces with random faces, lengths and indices */
static void random_wall_faces_case(int k)
{
  char what[64];
  const char* report = NULL;
  int64_t faces = below(8) ? below(12) : random_count(5), i, total;
  int64_t points = below(8) ? 1 + below(20) : random_count(10);
  int64_t *offsets, *conn, c_off, c_conn, c_n, c_u, c_k;
  double *normals, *u;
  unsigned char* kinds;
  int rc;
  if (faces < 0 || faces > 1000)
    faces = below(2) ? -1 : 3;
  c_off = below(6) ? faces + 1 : random_count(faces + 1);
  offsets = buffer(c_off, sizeof(int64_t), 1);
  total = 0;
  for (i = 0; offsets && c_off >= 0 && c_off <= 1000000 && i < c_off; ++i)
  {
    offsets[i] = total;
    total += below(10) ? below(5) : -1;
  }
  c_conn = offsets && c_off == faces + 1 && faces >= 0 ? offsets[faces] : random_count(4);
  if (c_conn < 0 || c_conn > 1000000)
    c_conn = below(2) ? -1 : 4;
  conn = buffer(c_conn, sizeof(int64_t), 1);
  for (i = 0; conn && i < c_conn; ++i)
    conn[i] = below(10) ? below(points > 0 && points < 1000 ? (int)points : 5) : -3;
  c_n = below(6) ? 3 * faces : random_count(3 * faces);
  c_u = below(6) ? 3 * faces : random_count(3 * faces);
  c_k = below(6) ? faces : random_count(faces);
  normals = buffer(c_n, sizeof(double), 1);
  u = buffer(c_u, sizeof(double), 1);
  kinds = buffer(c_k, 1, 1);
  for (i = 0; normals && c_n <= 1000000 && i < c_n; ++i)
    normals[i] = below(10) ? uniform() - 0.5 : NAN;
  for (i = 0; u && c_u <= 1000000 && i < c_u; ++i)
    u[i] = below(10) ? uniform() - 0.5 : INFINITY;
  snprintf(what, sizeof(what), "wall_faces case %d: %lld faces", k, (long long)faces);
  rc = schlieren_wall_faces(faces, offsets, c_off, conn, c_conn, points, normals, c_n, u, c_u,
    below(8) ? 1.0 : NAN, below(5) - 2, below(2) ? "U" : NULL, kinds, c_k, below(2) ? &report : NULL);
  outcome(F_WALL_FACES, rc, schlieren_last_error(), what);
  free(offsets);
  free(conn);
  free(normals);
  free(u);
  free(kinds);
}

/* RefractiveIndex's pipeline rules: settings, bounds, extents, ranks and pieces hostile or not */
static void random_sampling_case(int k)
{
  static const char* settings[] = { "", "AutomaticDimension=64", "AutomaticDimension=1",
    "AutomaticDimension=1e12", "SamplingDimensions=4 5 6", "SamplingDimensions=0 7 0",
    "SamplingDimensions=-3 2147483647 2", "SamplingDimensions=1.5 2 2", "UseSamplingBounds=1",
    "UseSamplingBounds=1\nSamplingBounds=0 1 0 1 0 1", "UseSamplingBounds=1\nSamplingBounds=1 0 0 1 0 1",
    "UseSamplingBounds=1\nSamplingBounds=nan 1 0 1 0 1", "SamplingBounds=0 1", "Bogus=2", "novalue",
    "SamplingDimensions=65536 65536 65536", "UseSamplingBounds=1\nSamplingBounds=0 0 0 0 0 0" };
  static const int sizes[] = { 0, 1, 2, 5, 17, -1, -2147483647 - 1, 2147483647 };
  char what[96];
  double bounds[6], box[6], o[3], h[3], no[3], nh[3];
  int d[3], amr[3], whole[6], upd[6], request[3], ext[6], moved, i, rc;
  const char* note = NULL;
  const char* text = settings[below(17)];
  snprintf(what, sizeof(what), "sampling case %d: '%s'", k, text);
  for (i = 0; i < 6; ++i)
  {
    bounds[i] = below(20) ? (i % 2 ? 1 + 10 * uniform() : -10 * uniform()) : (below(2) ? NAN : -INFINITY);
    box[i] = bounds[i];
  }
  rc = schlieren_sampling_box(below(20) ? text : NULL, below(10) ? bounds : NULL, below(30) ? box : NULL);
  outcome(F_SAMPLING, rc, schlieren_last_error(), what);
  for (i = 0; i < 3; ++i)
    amr[i] = sizes[below(8)];
  rc = schlieren_sampling_grid(below(20) ? text : NULL, below(30) ? box : NULL,
    below(10) ? 8.0 * below(10) : (below(2) ? NAN : -1.0), below(4) ? NULL : amr, below(30) ? d : NULL,
    o, h);
  outcome(F_SAMPLING, rc, schlieren_last_error(), what);
  for (i = 0; i < 3; ++i)
  {
    whole[2 * i] = below(10) ? 0 : sizes[below(8)];
    whole[2 * i + 1] = below(10) ? sizes[below(5)] : sizes[below(8)];
    o[i] = below(20) ? -1 : NAN;
    h[i] = below(20) ? 0.25 : (below(2) ? 0 : INFINITY);
  }
  rc = schlieren_follow_bounds(below(30) ? whole : NULL, o, h, below(30) ? bounds : NULL,
    below(30) ? &moved : NULL, no, nh, below(2) ? &note : NULL);
  outcome(F_SAMPLING, rc, schlieren_last_error(), what);
  for (i = 0; i < 6; ++i)
    upd[i] = below(6) ? whole[i] : sizes[below(8)];
  rc = schlieren_input_request(below(2), below(4) == 0, below(8) - 1, below(8) ? 1 + below(4) : sizes[below(8)],
    below(8) - 1, below(8) ? 1 + below(6) : sizes[below(8)], below(8) ? below(3) : -1,
    below(8) ? 3 : below(6) - 1, below(30) ? upd : NULL, below(30) ? whole : NULL,
    below(30) ? request : NULL, ext);
  outcome(F_SAMPLING, rc, schlieren_last_error(), what);
  /* an image's extent asked for, where not empty, never leaves the whole extent */
  if (rc == 0 && request[2] == 0 && ext[0] <= ext[1] && ext[2] <= ext[3] && ext[4] <= ext[5])
    for (i = 0; i < 3; ++i)
      if (ext[2 * i] < whole[2 * i] || ext[2 * i + 1] > whole[2 * i + 1])
      {
        ++failures;
        printf("FAIL %s: the extent asked for leaves the whole extent along axis %d\n", what, i);
      }
  text = schlieren_property_entries(below(2) ? "RefractiveIndex" : "Nothing",
    below(2) ? "Model" : (below(2) ? "AmbientMode" : NULL));
  if (!text || text[0] != '[')
  {
    ++failures;
    printf("FAIL %s: property_entries is not a JSON list: %s\n", what, text ? text : "(NULL)");
  }
}

/* ---- the ranks' callbacks as a caller may get them wrong (schlieren_parallel): a size or rank
 * that cannot be, callbacks missing, failing, writing noise, or a consistent fake of identical
 * ranks (every rank's bytes this rank's); every call ends with a clear error or a result ---- */
static int p_mode; /* 0 fake ranks, 1 failing, 2 noise, 3 the fake with one byte of each message
                     changed (the lengths and the reductions right): what the engine decodes */
/* mode 3: one random byte of a message changed; the 8-byte lengths the engine exchanges first
 * stay, so that the changed contents reach the engine's decoding */
static void p_corrupt(char* bytes, int64_t count)
{
  if (count != 8 && count > 0)
    bytes[count < 0x7fffffff ? below((int)count) : 0] = (char)below(256);
}
static int p_reduce(const double* in, double* out, int64_t count, int op, void* user)
{
  int64_t i;
  (void)op;
  (void)user;
  if (p_mode == 1)
    return below(3) + 1;
  for (i = 0; i < count; ++i)
    out[i] = p_mode == 0 || p_mode == 3 ? in[i] : (below(4) ? (uniform() - 0.5) * 1e6 : NAN);
  return 0;
}
static int p_broadcast(char* bytes, int64_t count, int root, void* user)
{
  int64_t i;
  (void)root;
  (void)user;
  if (p_mode == 1)
    return -1;
  if (p_mode == 2)
    for (i = 0; i < count; ++i)
      bytes[i] = (char)below(256);
  if (p_mode == 3)
    p_corrupt(bytes, count);
  return 0;
}
static int p_allgather(const char* mine, int64_t count, char* all, void* user)
{
  const schlieren_parallel* p = (const schlieren_parallel*)user;
  int64_t i;
  int r;
  if (p_mode == 1)
    return 7;
  for (r = 0; r < p->size; ++r)
  {
    for (i = 0; i < count; ++i)
      all[r * count + i] = p_mode == 0 || p_mode == 3 ? mine[i] : (char)below(256);
    if (p_mode == 3)
      p_corrupt(all + r * count, count);
  }
  return 0;
}

static void random_parallel_case(int k)
{
  static const int sizes[] = { -1, 0, 1, 2, 2, 3 };
  static const int rank_of[] = { -1, 0, 0, 1, 2, 5 };
  schlieren_parallel p;
  char what[160];
  int rc = 0, which = below(5);
  const char* message = NULL;
  const int d[3] = { 6, 5, 4 };
  const double o[3] = { -1, -1, -1 }, h[3] = { 0.4, 0.5, 0.6 };
  float n1[120], g3[360], ni[64], ng[64];
  unsigned char solid[120], nb[64];
  int i, size[2];
  const char* out = NULL;
  p.size = sizes[below(6)];
  p.rank = rank_of[below(6)];
  p.user = &p;
  p.reduce = below(8) ? p_reduce : NULL;
  p.broadcast = below(8) ? p_broadcast : NULL;
  p.allgather = below(8) ? p_allgather : NULL;
  p_mode = below(3);
  if (which == 1 && p_mode == 2 && below(2))
    p_mode = 3; /* (the draw that once kept noise out of the trace cases, when the pieces trusted
                   what arrived: the same draws keep a seed's later cases those of earlier runs) */
  for (i = 0; i < 120; ++i)
    n1[i] = 1e-4f * (float)uniform();
  snprintf(what, sizeof(what), "parallel case %d: call %d, size %d, rank %d, mode %d", k, which,
    p.size, p.rank, p_mode);
  if (verbose > 1)
  {
    printf("     (%s)\n", what);
    fflush(stdout);
  }
  if (which == 0)
  {
    rc = schlieren_parallel_failure(below(8) ? &p : NULL, below(2) ? "mine" : "", &out);
    message = schlieren_last_error();
  }
  else if (which == 1)
  {
    schlieren_session* s = schlieren_session_new();
    const int whole[6] = { 0, 5, 0, 4, 0, 3 };
    int ext[6] = { 0, 5, 0, 4, 0, 3 };
    ext[4] = below(3) - 1;
    ext[5] = below(5) - 1;
    schlieren_session_set(s, "Resolution", "8 8");
    schlieren_session_set(s, "Passes", "1");
    schlieren_session_set(s, "Backend", "CPU");
    rc = schlieren_session_set_piece(s, whole, ext, o, h, n1,
      ext[5] >= ext[4] ? 30 * (ext[5] - ext[4] + 1) : 0, NULL, 0, NULL, 0, -1, 7);
    if (rc == 0)
      rc = schlieren_session_trace_parallel(s, below(8) ? &p : NULL, NULL, NULL);
    message = schlieren_session_error(s);
    /* copied: the session goes */
    snprintf(what + strlen(what), sizeof(what) - strlen(what), " (trace, z %d..%d)", ext[4], ext[5]);
    if (rc != 0 && (!message || !*message))
      message = "";
    {
      static char kept[512];
      snprintf(kept, sizeof(kept), "%s", message ? message : "");
      message = kept;
    }
    schlieren_session_free(s);
  }
  else if (which == 2)
  {
    const int whole[6] = { 0, 5, 0, 4, 0, 3 };
    const int grid[6] = { 0, 5, 0, 4, 0, 3 };
    int outx[6] = { 0, 5, 0, 4, 0, 3 };
    const char* names[1] = { "n" };
    const int comps[1] = { 1 }, bytes[1] = { 4 };
    const void* vals[1];
    const int64_t counts[1] = { 120 };
    vals[0] = n1;
    outx[4] = below(3);
    rc = schlieren_index_field_piece(below(2) ? "Model=Passthrough\nInputArray=n" : "Model=Passthrough\nInputArray=n\nAmbientMode=DomainEdgeMedian",
      grid, outx, whole, h, 1, names, comps, bytes, vals, counts, 0, NULL, NULL, NULL, 0, NULL, 0, NULL,
      0, n1, 120, g3, 360, solid, 120, &p, &out);
    message = schlieren_last_error();
  }
  else if (which == 3)
  {
    const int off[3] = { 0, 0, below(3) }, pd[3] = { 6, 5, 4 - off[2] };
    int has_image = -1;
    rc = schlieren_numerical_pieces("Resolution=8 8", d, o, h, off, pd, n1, 30 * pd[2], NULL, 0, NULL,
      0, size, NULL, NULL, 64, ni, ng, nb, NULL, NULL, NULL, &p, &has_image);
    message = schlieren_last_error();
  }
  else
  {
    const int levels[1] = { 0 }, ext[6] = { 0, 5, 0, 4, 0, 3 };
    const double bo[3] = { 0, 0, 0 }, bs[3] = { 0.1, 0.1, 0.1 }, bounds[6] = { 0, 0.5, 0, 0.4, 0, 0.3 };
    int dims[3], finest_level, capped;
    double finest[3];
    rc = schlieren_amr_grid_parallel(1, 1, levels, ext, bo, bs, bounds, 64, dims, finest,
      &finest_level, &capped, &out, &p);
    message = schlieren_last_error();
  }
  outcome(F_PARALLEL, rc, message, what);
}

int main(int argc, char** argv)
{
  long cases = 4000, seed = 48, k;
  int i, f;
  long total = 0, total_refused = 0, total_done = 0;
  for (i = 1; i < argc; ++i)
  {
    if (strcmp(argv[i], "--cases") == 0 && i + 1 < argc)
      cases = atol(argv[++i]);
    else if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc)
      seed = atol(argv[++i]);
    else if (strcmp(argv[i], "--verbose") == 0)
      verbose = 1;
    else if (strcmp(argv[i], "--trace-calls") == 0)
      verbose = 2; /* also each parallel case before its call (a crash's case) */
  }
  state ^= (uint64_t)seed * 0x9E3779B97F4A7C15ull;
  if (!state)
    state = 1;
  fixed_cases();
  threads_case();
  progress_case(); /* no random number drawn: the random cases stay those of earlier runs */
  numerical_progress_case(); /* none drawn either */
  for (i = 0; i < POOL; ++i)
    pool[i] = schlieren_session_new();
  for (k = 0; k < cases; ++k)
    random_case((int)k);
  /* after the others, so that their cases stay those of earlier runs for a seed */
  fixed_sample_case();
  for (k = 0; k < cases / 4; ++k)
    random_sample_case();
  for (k = 0; k < cases / 4; ++k)
    random_amr_case();
  for (k = 0; k < cases / 4; ++k)
    random_time_cache_case();
  for (k = 0; k < cases / 4; ++k)
    random_index_field_case((int)k);
  for (k = 0; k < cases / 8; ++k)
    random_index_choices_case((int)k);
  for (k = 0; k < cases / 8; ++k)
    random_wall_faces_case((int)k);
  for (k = 0; k < cases / 4; ++k)
    random_sampling_case((int)k);
  for (k = 0; k < cases / 8; ++k)
    random_parallel_case((int)k);
  for (k = 0; k < cases / 8; ++k)
    random_cell_fields_case((int)k);
  for (i = 0; i < POOL; ++i)
    schlieren_session_free(pool[i]);
  printf("\n%-28s %8s %8s %8s %8s\n", "function", "calls", "done", "refused", "unclear");
  for (f = 0; f < F_COUNT; ++f)
  {
    printf("%-28s %8ld %8ld %8ld %8ld\n", fnames[f], calls[f], done[f], refused[f], unclear[f]);
    total += calls[f];
    total_done += done[f];
    total_refused += refused[f];
  }
  printf("%ld random cases (seed %ld), %ld calls: %ld done, %ld refused with a message, crashes 0 "
         "(the run ended), %d failures\n",
    cases, seed, total, total_done, total_refused, failures);
  return failures ? 1 : 0;
}
