/* SPDX-License-Identifier: BSD-3-Clause */
/* The engine's C interface from C (no C++ in this file): a trace of a Gaussian sphere through a
 * session, a second trace that keeps the volume, the errors as messages (an unknown property, a
 * bad value, a trace without a volume, a value the engine refuses), and the run-time OpenCL
 * loader: run with SCHLIEREN_OPENCL_LIBRARY pointing nowhere (ctest does), Backend Auto traces on
 * the CPU and says why; and the ranks (schlieren_parallel): two ranks on two threads trace, make
 * grad n and the numerical image of a volume in two pieces as one process does, bit for bit; the
 * MPI options (schlieren_mpi_options) from the environment. */
#define _POSIX_C_SOURCE 200112L /* pthread_barrier_t under -std=c99 (python.install builds this so) */
#include "schlieren_c.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;
#define CHECK(cond, ...)                                                                          \
  do                                                                                              \
  {                                                                                               \
    const int ok_ = (cond) ? 1 : 0; /* evaluated once: conditions call the library */            \
    printf("%s ", ok_ ? "ok  " : "FAIL");                                                         \
    printf(__VA_ARGS__);                                                                          \
    printf("\n");                                                                                 \
    if (!ok_)                                                                                     \
      ++failures;                                                                                 \
  } while (0)

/* ---- two ranks on two threads: the callbacks of schlieren_parallel over a shared slot each and a
 * barrier (what an MPI layer does, in one process) */
typedef struct
{
  pthread_barrier_t barrier;
  const char* slots[2];
} Shared;
typedef struct
{
  Shared* shared;
  int rank;
  /* what the rank's thread found, checked on the main thread */
  int ok_trace, ok_index, ok_numerical, has_image, numerical_image;
  char agreed[256];
  float* intensity; /* rank 0: the image of the pieces */
  float* n1_piece;  /* n - 1 on this rank's out extent */
  float* numerical; /* rank 0: the numerical image */
  char error[512];
} Rank;

static int t_allgather(const char* mine, int64_t count, char* all, void* user)
{
  Rank* me = (Rank*)user;
  int r;
  me->shared->slots[me->rank] = mine;
  pthread_barrier_wait(&me->shared->barrier);
  for (r = 0; r < 2; ++r)
    if (count > 0)
      memcpy(all + r * count, me->shared->slots[r], (size_t)count);
  pthread_barrier_wait(&me->shared->barrier);
  return 0;
}

static int t_broadcast(char* bytes, int64_t count, int root, void* user)
{
  Rank* me = (Rank*)user;
  me->shared->slots[me->rank] = bytes;
  pthread_barrier_wait(&me->shared->barrier);
  if (me->rank != root && count > 0)
    memcpy(bytes, me->shared->slots[root], (size_t)count);
  pthread_barrier_wait(&me->shared->barrier);
  return 0;
}

static int t_reduce(const double* in, double* out, int64_t count, int op, void* user)
{
  double* all = malloc(2 * (size_t)count * sizeof(double) + 1);
  int64_t i;
  t_allgather((const char*)in, count * (int64_t)sizeof(double), (char*)all, user);
  for (i = 0; i < count; ++i)
  {
    const double a = all[i], b = all[count + i];
    out[i] = op == 0 ? a + b : op == 1 ? (a < b ? a : b) : (a > b ? a : b);
  }
  free(all);
  return 0;
}

enum { RN = 25 };
static float ranks_n1[RN * RN * RN];
static const int ranks_dims[3] = { RN, RN, RN };
static const double ranks_origin[3] = { -1, -1, -1 }, ranks_spacing[3] = { 2.0 / (RN - 1), 2.0 / (RN - 1), 2.0 / (RN - 1) };
/* rank r's piece: z from its lower to its upper plane (the planes at 12 shared), and the extent it
 * holds for the index field (its out extent grown by one point, within the whole) */
static void piece_extents(int rank, int out[6], int grid[6])
{
  out[0] = 0; out[1] = RN - 1; out[2] = 0; out[3] = RN - 1;
  out[4] = rank == 0 ? 0 : 12;
  out[5] = rank == 0 ? 12 : RN - 1;
  memcpy(grid, out, 6 * sizeof(int));
  grid[4] = out[4] > 0 ? out[4] - 1 : 0;
  grid[5] = out[5] < RN - 1 ? out[5] + 1 : RN - 1;
}

static void* rank_main(void* arg)
{
  Rank* me = (Rank*)arg;
  schlieren_parallel p;
  int out[6], grid[6], size[2];
  int64_t gpoints, opoints, pixels = 0;
  const int whole[6] = { 0, RN - 1, 0, RN - 1, 0, RN - 1 };
  const float* piece_n1;
  float *g3, *n1g;
  unsigned char* solid;
  const char* names[1] = { "n_minus_1" };
  const int comps[1] = { 1 }, bytes[1] = { 4 };
  const void* vals[1];
  int64_t counts[1];
  const char* rep = NULL;
  const char* agreed = NULL;
  schlieren_session* s = schlieren_session_new();
  p.size = 2;
  p.rank = me->rank;
  p.user = me;
  p.reduce = t_reduce;
  p.broadcast = t_broadcast;
  p.allgather = t_allgather;
  piece_extents(me->rank, out, grid);
  gpoints = (int64_t)RN * RN * (grid[5] - grid[4] + 1);
  opoints = (int64_t)RN * RN * (out[5] - out[4] + 1);
  /* the trace: this rank's piece of the volume */
  piece_n1 = ranks_n1 + (size_t)RN * RN * out[4];
  schlieren_session_set(s, "Backend", "CPU");
  schlieren_session_set(s, "Resolution", "20 16");
  schlieren_session_set(s, "Passes", "1");
  schlieren_session_set(s, "ViewDirection", "0.3 -0.2 -1");
  me->ok_trace = schlieren_session_set_piece(s, whole, out, ranks_origin, ranks_spacing, piece_n1,
                   opoints, NULL, 0, NULL, 0, -1, 7) == 0 &&
    schlieren_session_trace_parallel(s, &p, NULL, NULL) == 0;
  if (!me->ok_trace)
    snprintf(me->error, sizeof(me->error), "%s", schlieren_session_error(s));
  me->has_image = schlieren_session_film(s, size, NULL, NULL) == 0;
  if (me->has_image)
  {
    const float* I = schlieren_session_array(s, "intensity", NULL, &pixels);
    me->intensity = malloc((size_t)pixels * sizeof(float));
    memcpy(me->intensity, I, (size_t)pixels * sizeof(float));
  }
  schlieren_session_free(s);
  /* the index field: the piece grown by a point, n - 1 passed through */
  g3 = malloc(3 * (size_t)gpoints * sizeof(float));
  n1g = malloc((size_t)gpoints * sizeof(float));
  solid = malloc((size_t)gpoints);
  vals[0] = ranks_n1 + (size_t)RN * RN * grid[4];
  counts[0] = gpoints;
  me->ok_index = schlieren_index_field_piece("Model=Passthrough\nInputArray=n_minus_1", grid, out,
                   whole, ranks_spacing, 1, names, comps, bytes, vals, counts, 0, NULL, NULL, NULL, 0,
                   NULL, 0, NULL, 0, n1g, gpoints, g3, 3 * gpoints, solid, gpoints, &p, &rep) == 0;
  if (!me->ok_index)
    snprintf(me->error, sizeof(me->error), "%s", schlieren_last_error());
  me->n1_piece = malloc(3 * (size_t)opoints * sizeof(float));
  memcpy(me->n1_piece, g3 + 3 * (size_t)RN * RN * (out[4] - grid[4]), 3 * (size_t)opoints * sizeof(float));
  free(g3);
  free(n1g);
  free(solid);
  /* the numerical image of the pieces, gathered on rank 0 */
  {
    const int offset[3] = { 0, 0, out[4] }, pdims[3] = { RN, RN, out[5] - out[4] + 1 };
    float* ni = malloc(20 * 16 * sizeof(float));
    float* ng = malloc(20 * 16 * sizeof(float));
    unsigned char* nb = malloc(20 * 16);
    me->ok_numerical = schlieren_numerical_pieces("Mode=LineOfSight\nResolution=20 16", ranks_dims,
                         ranks_origin, ranks_spacing, offset, pdims, piece_n1, opoints, NULL, 0, NULL,
                         0, size, NULL, NULL, 20 * 16, ni, ng, nb, NULL, NULL, NULL, &p,
                         &me->numerical_image) == 0;
    if (!me->ok_numerical)
      snprintf(me->error, sizeof(me->error), "%s", schlieren_last_error());
    me->numerical = ni;
    free(ng);
    free(nb);
  }
  /* a failure on rank 1 only: the same agreement on both */
  if (schlieren_parallel_failure(&p, me->rank == 1 ? "bad array on rank 1" : "", &agreed) == 0)
    snprintf(me->agreed, sizeof(me->agreed), "%s", agreed);
  return NULL;
}

static void ranks_test(void)
{
  Shared shared;
  Rank ranks[2];
  pthread_t threads[2];
  int r;
  const int64_t n = (int64_t)RN * RN * RN;
  const float* whole_I;
  int64_t pixels = 0;
  schlieren_session* s;
  float g3[3 * RN * RN * RN], n1g[RN * RN * RN];
  unsigned char solid[RN * RN * RN];
  const char* names[1] = { "n_minus_1" };
  const int comps[1] = { 1 }, bytes[1] = { 4 };
  const void* vals[1];
  const int64_t counts[1] = { RN * RN * RN };
  const char* rep = NULL;
  const char* agreed = NULL;
  float ni[20 * 16], ng[20 * 16];
  unsigned char nb[20 * 16];
  int size[2];
  schlieren_parallel bad;

  schlieren_fill_scene("Scene=GaussianSphere\nAmplitude=1e-4\nWidth=0.3\nCenter=0.1 -0.05 0.02",
    ranks_dims, ranks_origin, ranks_spacing, n, ranks_n1, NULL, NULL, NULL);
  pthread_barrier_init(&shared.barrier, NULL, 2);
  memset(ranks, 0, sizeof(ranks));
  for (r = 0; r < 2; ++r)
  {
    ranks[r].shared = &shared;
    ranks[r].rank = r;
    pthread_create(&threads[r], NULL, rank_main, &ranks[r]);
  }
  for (r = 0; r < 2; ++r)
    pthread_join(threads[r], NULL);
  pthread_barrier_destroy(&shared.barrier);

  /* one process: the whole volume */
  s = schlieren_session_new();
  schlieren_session_set(s, "Backend", "CPU");
  schlieren_session_set(s, "Resolution", "20 16");
  schlieren_session_set(s, "Passes", "1");
  schlieren_session_set(s, "ViewDirection", "0.3 -0.2 -1");
  schlieren_session_set_volume(s, ranks_dims, ranks_origin, ranks_spacing, ranks_n1, n, NULL, 0, NULL, 0, -1, 7);
  schlieren_session_trace(s);
  whole_I = schlieren_session_array(s, "intensity", NULL, &pixels);
  CHECK(ranks[0].ok_trace && ranks[1].ok_trace && ranks[0].has_image && !ranks[1].has_image &&
      whole_I && pixels == 20 * 16 && memcmp(whole_I, ranks[0].intensity, (size_t)pixels * sizeof(float)) == 0,
    "parallel: a volume in two pieces on two ranks (threads) traced by schlieren_session_trace_parallel: "
    "rank 0 holds one process's image bit for bit, rank 1 none (%s)", ranks[0].error);
  /* the index field: each rank's out extent equals the whole's there */
  vals[0] = ranks_n1;
  CHECK(schlieren_index_field("Model=Passthrough\nInputArray=n_minus_1", ranks_dims, ranks_spacing, 1,
          names, comps, bytes, vals, counts, 0, NULL, NULL, NULL, 0, NULL, 0, NULL, 0, n1g, n, g3, 3 * n,
          solid, n, &rep) == 0 && ranks[0].ok_index && ranks[1].ok_index &&
      memcmp(ranks[0].n1_piece, g3, 3 * sizeof(float) * RN * RN * 13) == 0 &&
      memcmp(ranks[1].n1_piece, g3 + 3 * RN * RN * 12, 3 * sizeof(float) * RN * RN * 13) == 0,
    "parallel: schlieren_index_field_piece on two pieces grown by a point: grad n on each out "
    "extent is the whole grid's bit for bit (%s)", ranks[1].error);
  CHECK(schlieren_numerical("Mode=LineOfSight\nResolution=20 16", ranks_dims, ranks_origin, ranks_spacing,
          ranks_n1, n, NULL, 0, NULL, 0, size, NULL, NULL, 20 * 16, ni, ng, nb, NULL) == 0 &&
      ranks[0].ok_numerical && ranks[1].ok_numerical && ranks[0].numerical_image &&
      !ranks[1].numerical_image && memcmp(ni, ranks[0].numerical, sizeof(ni)) == 0,
    "parallel: schlieren_numerical_pieces gathers the pieces on rank 0: one process's image bit for bit");
  CHECK(strcmp(ranks[0].agreed, "another rank (1) failed: bad array on rank 1") == 0 &&
      strcmp(ranks[1].agreed, "bad array on rank 1") == 0,
    "parallel: schlieren_parallel_failure agrees on rank 1's failure ('%s' / '%s')", ranks[0].agreed,
    ranks[1].agreed);
  for (r = 0; r < 2; ++r)
  {
    free(ranks[r].intensity);
    free(ranks[r].n1_piece);
    free(ranks[r].numerical);
  }
  /* refused: the ranks as given make no sense */
  memset(&bad, 0, sizeof(bad));
  bad.size = 0;
  CHECK(schlieren_session_trace_parallel(s, &bad, NULL, NULL) != 0 &&
      strstr(schlieren_session_error(s), "parallel->size is 0"),
    "parallel: size 0 refused: %s", schlieren_session_error(s));
  bad.size = 2;
  bad.rank = 2;
  CHECK(schlieren_parallel_failure(&bad, "", &agreed) != 0 &&
      strstr(schlieren_last_error(), "parallel->rank is 2: it must be in [0, 2)"),
    "parallel: rank 2 of 2 refused: %s", schlieren_last_error());
  bad.rank = 1;
  CHECK(schlieren_parallel_failure(&bad, "", &agreed) != 0 &&
      strstr(schlieren_last_error(), "callback is NULL"),
    "parallel: size 2 without callbacks refused: %s", schlieren_last_error());
  bad.size = 1;
  bad.rank = 0;
  CHECK(schlieren_parallel_failure(&bad, "mine", &agreed) == 0 && strcmp(agreed, "mine") == 0 &&
      schlieren_parallel_failure(NULL, "", &agreed) == 0 && strcmp(agreed, "") == 0,
    "parallel: one rank (size 1 without callbacks, or NULL) is one process");
  schlieren_session_free(s);
}

int main(void)
{
  const int dims[3] = { 33, 33, 33 };
  const double origin[3] = { -1, -1, -1 }, spacing[3] = { 2.0 / 32, 2.0 / 32, 2.0 / 32 };
  const size_t n = 33 * 33 * 33;
  float* n1 = malloc(n * sizeof(float));
  int size[2];
  double film_origin[2], pixel;
  schlieren_session* s;
  const float* intensity;
  const float* deflection;
  int components = 0;
  int64_t pixels = 0;
  double sum = 0, maxdefl = 0;
  int64_t i;
  const char* report;
  const char* no_loader = getenv("SCHLIEREN_OPENCL_LIBRARY");
  double mpi_timeout = 0;
  int mpi_abort = -1;

  /* the MPI options as the engine reads them (read on first use: set before any call) */
#ifdef _WIN32
  _putenv("SCHLIEREN_MPI_TIMEOUT=7.5");
  _putenv("SCHLIEREN_MPI_ABORT="); /* (removes it) */
#else
  setenv("SCHLIEREN_MPI_TIMEOUT", "7.5", 1);
  unsetenv("SCHLIEREN_MPI_ABORT");
#endif
  CHECK(schlieren_mpi_options(&mpi_timeout, &mpi_abort) == 0 && mpi_timeout == 7.5 && mpi_abort == 0,
    "mpi_options: SCHLIEREN_MPI_TIMEOUT=7.5 gives %g s, abort %d (%s)", mpi_timeout, mpi_abort,
    schlieren_last_error());
  CHECK(schlieren_mpi_options(NULL, NULL) == 0, "mpi_options: NULL pointers are allowed");

  CHECK(schlieren_api_version() == SCHLIEREN_C_API_VERSION, "API version %d", schlieren_api_version());
  CHECK(strstr(schlieren_properties(), "\"Cutoff\"") != NULL, "the property list names Cutoff");
  CHECK(schlieren_fill_scene("Scene=GaussianSphere\nAmplitude=1e-4\nWidth=0.25", dims, origin,
          spacing, (int64_t)n, n1, NULL, NULL, NULL) == 0,
    "fill_scene: %s", schlieren_last_error());
  CHECK(fabs(n1[16 + 33 * (16 + 33 * 16)] - 1e-4f) < 1e-9f, "n - 1 at the centre %g", n1[16 + 33 * (16 + 33 * 16)]);
  CHECK(schlieren_fill_scene("Scene=Sphere", dims, origin, spacing, (int64_t)n, n1, NULL, NULL, NULL) != 0 &&
      strstr(schlieren_last_error(), "GaussianSphere") != NULL,
    "a bad scene names the scenes: %s", schlieren_last_error());
  schlieren_fill_scene("Scene=GaussianSphere", dims, origin, spacing, (int64_t)n, n1, NULL, NULL, NULL);

  s = schlieren_session_new();
  CHECK(schlieren_session_trace(s) != 0 && strstr(schlieren_session_error(s), "volume") != NULL,
    "a trace without a volume: %s", schlieren_session_error(s));
  CHECK(schlieren_session_set(s, "Resolutoin", "8 8") != 0 &&
      strstr(schlieren_session_error(s), "Resolution") != NULL,
    "an unknown property lists the properties");
  CHECK(schlieren_session_set(s, "Cutoff", "Knife") != 0 &&
      strstr(schlieren_session_error(s), "KnifeEdge") != NULL,
    "a bad entry: %s", schlieren_session_error(s));
  CHECK(schlieren_session_set(s, "Resolution", "64") != 0, "a vector of the wrong length: %s",
    schlieren_session_error(s));
  CHECK(strcmp(schlieren_session_get(s, "Passes"), "4") == 0, "Passes defaults to 4 (the proxy's)");
  CHECK(schlieren_session_set(s, "Resolution", "64 48") == 0 &&
      schlieren_session_set(s, "Passes", "2") == 0 && schlieren_session_set(s, "Cutoff", "KnifeEdge") == 0,
    "settings taken");
  CHECK(schlieren_session_set_volume(s, dims, origin, spacing, n1, (int64_t)n, NULL, 0, NULL, 0, -1, 7) == 0,
    "set_volume");
  free(n1); /* copied */
  CHECK(schlieren_session_trace(s) == 0, "trace: %s", schlieren_session_error(s));
  intensity = schlieren_session_array(s, "intensity", &components, &pixels);
  CHECK(intensity && components == 1 && pixels == 64 * 48, "intensity of 64 x 48 pixels");
  deflection = schlieren_session_array(s, "deflection", &components, &pixels);
  CHECK(deflection && components == 2, "deflection with 2 components");
  CHECK(schlieren_session_array(s, "rgb", NULL, NULL) == NULL, "no rgb for a knife edge");
  for (i = 0; intensity && i < pixels; ++i)
    sum += intensity[i];
  for (i = 0; deflection && i < 2 * pixels; ++i)
    maxdefl = fabs(deflection[i]) > maxdefl ? fabs(deflection[i]) : maxdefl;
  /* the closed form: the line-of-sight deflection of a Gaussian peaks at sqrt(2 pi / e) A = 1.52 A */
  CHECK(fabs(maxdefl / 1.52e-4 - 1) < 0.1, "largest deflection %.4g rad (closed form 1.52e-4)", maxdefl);
  CHECK(fabs(sum / pixels - 0.5) < 0.05, "mean intensity %.4f (a knife edge: about 0.5)", sum / pixels);
  CHECK(schlieren_session_film(s, size, film_origin, &pixel) == 0 && size[0] == 64 && size[1] == 48,
    "film %d x %d, pixel %g", size[0], size[1], pixel);
  report = schlieren_session_report(s);
  CHECK(strstr(report, "\"passes\": 2") && strstr(report, "\"landed_photons\""), "report: %.200s", report);
  if (no_loader && *no_loader)
    CHECK(strstr(report, "\"backend\": \"CPU\"") && strstr(report, "OpenCL loader could not be opened"),
      "no OpenCL loader: traced on the CPU, and the warning says why");
  /* more passes: only the new ones are traced */
  schlieren_session_set(s, "Passes", "3");
  CHECK(schlieren_session_trace(s) == 0 && strstr(schlieren_session_report(s), "\"passes_traced\": 1"),
    "raising Passes traces only the new pass");
  /* a value the engine refuses: its message, no exception */
  schlieren_session_set(s, "StepSize", "-1");
  CHECK(schlieren_session_trace(s) != 0 && strstr(schlieren_session_error(s), "StepSize") != NULL,
    "StepSize -1: %s", schlieren_session_error(s));
  CHECK(schlieren_session_array(s, "intensity", NULL, NULL) == NULL, "no image after a failure");
  schlieren_session_free(s);
  schlieren_session_free(NULL);

  /* NumericalSchlieren on a density ramp rho = 1 + 0.5 x: |grad rho| = 0.5 on every pixel of the
   * slice through the volume (central differences are exact on a linear field) */
  {
    const char* settings = "Mode=Slice\nGradient=Magnitude\nResolution=24 20";
    int nsize[2] = { 0, 0 }, flow = 0, x, y, z;
    double norigin[2], npixel = 0, ml[2] = { 0, 0 }, worst = 0;
    float *rho = malloc(n * sizeof(float)), *ni, *ng;
    unsigned char* nb;
    for (z = 0; z < 33; ++z)
      for (y = 0; y < 33; ++y)
        for (x = 0; x < 33; ++x)
          rho[x + 33 * (y + 33 * z)] = (float)(1.0 + 0.5 * (origin[0] + x * spacing[0]));
    CHECK(schlieren_numerical(settings, dims, origin, spacing, NULL, 0, NULL, 0, NULL, 0, nsize, norigin,
            &npixel, 0, NULL, NULL, NULL, NULL) == 0 && nsize[0] == 24 && nsize[1] == 20 && npixel > 0,
      "numerical: the film planned, %d x %d pixels of %g (%s)", nsize[0], nsize[1], npixel,
      schlieren_last_error());
    ni = malloc(24 * 20 * sizeof(float));
    ng = malloc(24 * 20 * sizeof(float));
    nb = malloc(24 * 20);
    CHECK(schlieren_numerical(settings, dims, origin, spacing, rho, (int64_t)n, NULL, 0, NULL, 0, nsize,
            norigin, &npixel, 24 * 20, ni, ng, nb, ml) == 0, "numerical: traced (%s)", schlieren_last_error());
    for (i = 0; i < 24 * 20; ++i)
      if (ng[i] > 0)
      {
        ++flow;
        worst = fmax(worst, fabs(ng[i] / 0.5 - 1));
      }
    CHECK(flow > 24 * 20 / 2 && worst < 1e-5, "numerical: |grad rho| = 0.5 on %d pixels (worst relative "
      "error %.2g; largest %g)", flow, worst, ml[1]);
    CHECK(schlieren_numerical("Mode=Sideways", dims, origin, spacing, NULL, 0, NULL, 0, NULL, 0, nsize,
            norigin, &npixel, 0, NULL, NULL, NULL, NULL) != 0 && strstr(schlieren_last_error(), "Mode") != NULL,
      "numerical: a bad Mode is refused by name: %s", schlieren_last_error());
    CHECK(schlieren_numerical(settings, dims, origin, spacing, rho, (int64_t)n, NULL, 0, NULL, 0, nsize,
            norigin, &npixel, 10, ni, ng, nb, ml) != 0 && strstr(schlieren_last_error(), "buffers") != NULL,
      "numerical: buffers too small are refused: %s", schlieren_last_error());
    free(rho);
    free(ni);
    free(ng);
    free(nb);
  }
  {
    /* RefractiveIndex's symmetry (schlieren_symmetry_*): known answers on small planes */
    const double plane[6] = { 0.0, 1.0, 0.0, 2.0, 0.0, 0.0 };   /* a 2D x-y plane at z = 0 */
    const double rz[6] = { 0.0, 2.0, 0.0, 1.0, 0.0, 0.0 };      /* an r-z half plane, r along y */
    int sd[3];
    double so[3], sh[3], g[8];
    int64_t m = 0, of[3 * 5 * 4], k;
    double xyz[3 * 15];
    const char* report = NULL;
    float values[15], out[3 * 5 * 4];
    unsigned char found[15], valid[3 * 5 * 4];
    int ok = 1;
    CHECK(schlieren_symmetry_plan("Symmetry=Planar\nSpan=0.6\nSamplingDimensions=3 5 4", plane,
            NULL, 0, 1, NULL, NULL, NULL, sd, so, sh, g, &report) == 0 &&
          sd[0] == 3 && sd[1] == 5 && sd[2] == 4 && fabs(so[2] + 0.3) < 1e-15 &&
          fabs(sh[2] - 0.2) < 1e-15 && g[0] == 1 && g[1] == 2,
      "symmetry: Planar over a 2D x-y plane: 3 x 5 x 4 points, z from -Span/2 by Span/3 (%d %d %d, "
      "z %g by %g; %s)", sd[0], sd[1], sd[2], so[2], sh[2], schlieren_last_error());
    CHECK(schlieren_symmetry_samples(g, sd, so, sh, &m, xyz, 3 * 15, of, 3 * 5 * 4) == 0 && m == 15,
      "symmetry: Planar samples one per in-plane point (%lld; %s)", (long long)m,
      schlieren_last_error());
    for (k = 0; k < 3 * 5 * 4; ++k)
      ok = ok && of[k] == k % 15 && xyz[3 * of[k] + 2] == 0.0;
    for (k = 0; k < 15; ++k)
    {
      values[k] = (float)k;
      found[k] = k != 7;
    }
    CHECK(ok && schlieren_symmetry_expand(of, 60, 15, values, 15, 1, out, 60, found, 15, valid, 60) == 0 &&
          out[59] == 14.0f && out[22] == 7.0f && valid[22] == 0 && valid[21] == 1,
      "symmetry: each grid point takes its in-plane sample, extruded across the span (%s)",
      schlieren_last_error());
    CHECK(schlieren_symmetry_plan("Symmetry=Axisymmetric\nSymmetryAxis=X\nSamplingDimensions=3 3 3",
            rz, NULL, 0, 1, NULL, NULL, NULL, sd, so, sh, g, &report) == 0 &&
          sd[0] == 3 && fabs(so[1] + 1.0) < 1e-15 && fabs(sh[2] - 1.0) < 1e-15 && g[5] == 0,
      "symmetry: Axisymmetric about x: r from -R to R along y and z (%g by %g; %s)", so[1], sh[2],
      schlieren_last_error());
    CHECK(schlieren_symmetry_samples(g, sd, so, sh, &m, NULL, 0, NULL, 0) == 0 && m == 6 &&
          schlieren_symmetry_samples(g, sd, so, sh, &m, xyz, 18, of, 27) == 0 && of[13] == 2 * 1 + 1 &&
          of[0] == 0 && fabs(xyz[3 * 1 + 1]) < 1e-15 && fabs(xyz[3 * 0 + 1] - (1 - 1e-6)) < 1e-12,
      "symmetry: 3 x 3 x 3 revolved: 2 distinct radii per axial position (the axis, and the corners "
      "and edges held at the largest r), the centre point on the axis (%lld samples; %s)",
      (long long)m, schlieren_last_error());
    CHECK(schlieren_symmetry_plan("Symmetry=Planar\nSpan=0", plane, NULL, 0, 1, NULL, NULL, NULL,
            sd, so, sh, g, NULL) != 0 &&
          strstr(schlieren_last_error(), "Span is 0.000000: it must be positive") != NULL,
      "symmetry: Span 0 refused with the C++ filter's message: %s", schlieren_last_error());
    CHECK(schlieren_symmetry_plan("Symmetry=Axisymmetric\nSymmetryAxis=Z", rz, NULL, 0, 1, NULL, NULL,
            NULL, sd, so, sh, g, NULL) != 0 &&
          strstr(schlieren_last_error(), "SymmetryAxis z is normal to the input's plane") != NULL,
      "symmetry: an axis normal to the plane refused: %s", schlieren_last_error());
  }
  {
    /* RefractiveIndex's pipeline rules (SchlierenSamplingGrid.h), the C++ filter's: the box, the
     * grid, a mesh that moved, the input's piece and extent, the enumerations */
    const double bounds[6] = { 0, 10, 0, 5, 0, 0 }, away[6] = { 1, 21, 0, 5, 0, 0 };
    double box[6], o[3], h[3], no[3], nh[3];
    int d[3], moved = -1, request[3], ext[6], i;
    const int whole[6] = { 0, 10, 0, 5, 0, 0 }, cube[6] = { 0, 10, 0, 10, 0, 10 };
    const char* note = NULL;
    CHECK(schlieren_sampling_box("AutomaticDimension=11", bounds, box) == 0 &&
        fabs(box[0] - 5e-6) < 1e-12 && fabs(box[1] - (10 - 5e-6)) < 1e-12 &&
        fabs(box[3] - (5 - 2.5e-6)) < 1e-12 && box[4] == 0 && box[5] == 0,
      "sampling_box: 0 10 0 5 0 0 pulled in by 1e-6 about its centre: %.9g %.9g %.9g %.9g (%s)",
      box[0], box[1], box[2], box[3], schlieren_last_error());
    CHECK(schlieren_sampling_grid("AutomaticDimension=11", box, 8.0, NULL, d, o, h) == 0 &&
        d[0] == 11 && d[1] == 6 && d[2] == 1 && o[0] == box[0] &&
        fabs(h[0] - (box[1] - box[0]) / 10) < 1e-15 && h[2] == 1.0,
      "sampling_grid: AutomaticDimension 11 over 10 x 5 x 0: 11 x 6 x 1 points, spacing %.9g (%s)",
      h[0], schlieren_last_error());
    {
      const int amr[3] = { 5, 4, 1 };
      CHECK(schlieren_sampling_grid("", box, 64.0, amr, d, o, h) == 0 && d[0] == 5 && d[1] == 4 &&
          d[2] == 1 && fabs(h[0] - (box[1] - box[0]) / 4) < 1e-15 &&
          schlieren_sampling_grid("SamplingDimensions=3 3 3", box, 64.0, amr, d, o, h) == 0 &&
          d[0] == 3 && d[1] == 3 && d[2] == 3,
        "sampling_grid: an AMR's automatic 5 x 4 x 1 taken where automatic, SamplingDimensions "
        "3 3 3 where typed (%d %d %d; %s)", d[0], d[1], d[2], schlieren_last_error());
    }
    CHECK(schlieren_sampling_box("", NULL, box) != 0 &&
        strcmp(schlieren_last_error(), "The input has no points to resample onto an image grid.") == 0,
      "sampling_box: no points refused with the C++ filter's message: %s", schlieren_last_error());
    CHECK(schlieren_sampling_box("UseSamplingBounds=1\nSamplingBounds=1 0 0 1 0 1", bounds, box) != 0 &&
        strstr(schlieren_last_error(), "are empty or not finite") != NULL &&
        strstr(schlieren_last_error(), " (SamplingBounds: xmin xmax ymin ymax zmin zmax)") != NULL,
      "sampling_box: SamplingBounds 1 0 refused, the property named: %s", schlieren_last_error());
    schlieren_sampling_box("", bounds, box);
    CHECK(schlieren_sampling_grid("SamplingDimensions=65536 65536 65536", box, 8.0, NULL, d, o, h) != 0 &&
        strstr(schlieren_last_error(), "Resampling onto 65536 x 65536 x 65536 points needs") != NULL &&
        strstr(schlieren_last_error(), "Lower SamplingDimensions.") != NULL,
      "sampling_grid: 65536^3 points refused by memory: %s", schlieren_last_error());
    CHECK(schlieren_sampling_grid("Bogus=1", box, 8.0, NULL, d, o, h) != 0 &&
        strstr(schlieren_last_error(), "unknown setting 'Bogus'") != NULL,
      "sampling_grid: an unknown setting named: %s", schlieren_last_error());
    schlieren_sampling_grid("AutomaticDimension=11", box, 0.0, NULL, d, o, h);
    CHECK(schlieren_follow_bounds(whole, o, h, bounds, &moved, no, nh, &note) == 0 && moved == 0 &&
        no[0] == o[0] && nh[0] == h[0] && note && !*note,
      "follow_bounds: the bounds the grid was set over: not moved (%s)", schlieren_last_error());
    CHECK(schlieren_follow_bounds(whole, o, h, away, &moved, no, nh, &note) == 0 && moved == 1 &&
        fabs(nh[0] - 2 * (1 - 1e-6)) < 1e-12 && fabs(no[0] - (1 + 1e-5)) < 1e-12 && nh[1] == h[1] &&
        strstr(note, "the grid follows them, the same points over [1.00001, 21]") != NULL,
      "follow_bounds: moved to x 1..21, the same 11 points, spacing %.9g: %s", nh[0], note);
    CHECK(schlieren_input_request(1, 0, 1, 3, 0, 1, 0, 3, NULL, NULL, request, ext) == 0 &&
        request[0] == 1 && request[1] == 3 && request[2] == 1,
      "input_request: a mesh on rank 1 of 3: its piece 1 of 3, whole (%s)", schlieren_last_error());
    CHECK(schlieren_input_request(1, 1, 1, 3, 0, 1, 0, 3, NULL, NULL, request, ext) == 0 &&
        request[0] == 0 && request[1] == 1 && request[2] == 1,
      "input_request: a symmetric input read whole on every rank (%s)", schlieren_last_error());
    CHECK(schlieren_input_request(0, 0, 0, 1, 1, 2, 0, 3, cube, cube, request, ext) == 0 &&
        request[0] == 0 && request[1] == 1 && request[2] == 0 && ext[0] == 0 && ext[1] == 10 &&
        ext[4] == 4 && ext[5] == 10,
      "input_request: an image's piece 1 of 2 (z 5..10, VTK's block split) grown by one: z %d..%d (%s)",
      ext[4], ext[5], schlieren_last_error());
    CHECK(schlieren_input_request(0, 0, 0, 1, 2, 2, 0, 3, cube, cube, request, ext) != 0 &&
        strstr(schlieren_last_error(), "piece 2 of 2") != NULL,
      "input_request: piece 2 of 2 refused: %s", schlieren_last_error());
    CHECK(strcmp(schlieren_property_entries("RefractiveIndex", "Symmetry"),
            "[[0, \"None\"], [1, \"Planar\"], [2, \"Axisymmetric\"]]") == 0 &&
        strcmp(schlieren_property_entries("RefractiveIndex", "Wavelength"), "[]") == 0 &&
        strcmp(schlieren_property_entries(NULL, NULL), "[]") == 0,
      "property_entries: Symmetry's entries, none for a number: %s",
      schlieren_property_entries("RefractiveIndex", "Symmetry"));
    (void)i;
  }
  {
    /* the filters' property ranges, the engine's (the C++ filters check the same table) */
    const double wavelength = 50, inside[3] = { 0, 64, 65536 }, past[3] = { 0, 64, 65537 };
    const double tolerance = 1e-6, nan = NAN, boolean = 2;
    CHECK(schlieren_check_property("RefractiveIndex", "Wavelength", &wavelength, 1) != 0 &&
        strcmp(schlieren_last_error(), "Wavelength is 50: it must be in [100, 20000].") == 0,
      "check_property: Wavelength 50 refused by name and range: %s", schlieren_last_error());
    CHECK(schlieren_check_property("RefractiveIndex", "SamplingDimensions", inside, 3) == 0,
      "check_property: SamplingDimensions 0 64 65536 taken (%s)", schlieren_last_error());
    CHECK(schlieren_check_property("RefractiveIndex", "SamplingDimensions", past, 3) != 0 &&
        strstr(schlieren_last_error(), "SamplingDimensions[2] is 65537") != NULL,
      "check_property: SamplingDimensions[2] 65537 refused: %s", schlieren_last_error());
    CHECK(schlieren_check_property("RefractiveIndex", "PressureOffset", &nan, 1) != 0 &&
        strstr(schlieren_last_error(), "PressureOffset is nan: it must be a finite value") != NULL,
      "check_property: PressureOffset NaN refused: %s", schlieren_last_error());
    CHECK(schlieren_check_property("RefractiveIndex", "BodyFromGrid", &boolean, 1) != 0 &&
        strstr(schlieren_last_error(), "must be 0 (off) or 1 (on)") != NULL,
      "check_property: BodyFromGrid 2 refused: %s", schlieren_last_error());
    CHECK(schlieren_check_property("RefractionOctree", "Tolerance", &tolerance, 1) == 0 &&
        schlieren_check_property("RefractiveIndex", "Model", &boolean, 1) == 0,
      "check_property: Tolerance 1e-6 taken, a property without a listed range passes (%s)",
      schlieren_last_error());
  }
  {
    /* AMR: level 0 over [0, 4]^3 (spacing 1) holds f = x, level 1 over [1, 3]^3 (spacing 0.5)
     * holds x + 10: on a grid of spacing 0.5 every point in the patch takes level 1's value, every
     * other one level 0's trilinear interpolant (exact for a linear field) */
    const int levels[2] = { 0, 1 };
    const int extents[12] = { 0, 4, 0, 4, 0, 4, 2, 6, 2, 6, 2, 6 };
    const double origins[6] = { 0, 0, 0, 0, 0, 0 }, spacings[6] = { 1, 1, 1, 0.5, 0.5, 0.5 };
    const double bounds[6] = { 0, 4, 0, 4, 0, 4 };
    const int gd[3] = { 9, 9, 9 };
    const double go[3] = { 0, 0, 0 }, gh[3] = { 0.5, 0.5, 0.5 };
    float coarse[125], fine[125];
    const char* names[1] = { "f" };
    const int is_cell[2] = { 0, 0 }, comps[2] = { 1, 1 }, bytes[2] = { 4, 4 };
    const void* inputs[2];
    int64_t lengths[2] = { 125, 125 };
    int out_components[1] = { 0 }, gdims[3] = { 0, 0, 0 }, finest_level = -1, capped = -1;
    double finest[3] = { 0, 0, 0 };
    const float* outputs[1] = { NULL };
    const unsigned char* valid = NULL;
    const char* report = NULL;
    const char* note = NULL;
    const int overlapping[12] = { 0, 0, 0, 3, 3, 3, 2, 2, 2, 5, 5, 5 };
    const int touching[12] = { 0, 0, 0, 3, 3, 3, 4, 0, 0, 7, 3, 3 };
    const int two_on_zero[2] = { 0, 0 };
    int x, y, z, right = 1, all_valid = 1;
    for (z = 0; z < 5; ++z)
      for (y = 0; y < 5; ++y)
        for (x = 0; x < 5; ++x)
        {
          coarse[(z * 5 + y) * 5 + x] = (float)x;
          fine[(z * 5 + y) * 5 + x] = (float)(1.0 + 0.5 * x + 10.0);
        }
    inputs[0] = coarse;
    inputs[1] = fine;
    CHECK(schlieren_amr_grid(2, 2, levels, extents, origins, spacings, bounds, 100.0, gdims, finest,
            &finest_level, &capped, &note) == 0 &&
          gdims[0] == 9 && gdims[2] == 9 && finest[0] == 0.5 && finest_level == 1 && capped == 0 &&
          strstr(note, "level 1 of 2, spacing 0.5): 9 x 9 x 9 points") != NULL,
      "amr_grid: the finest level's spacing, 9 x 9 x 9 points (%s%s)", note ? note : "",
      schlieren_last_error());
    CHECK(schlieren_amr_sample(2, 2, levels, extents, origins, spacings, 1, names, is_cell, comps,
            bytes, inputs, lengths, gd, go, gh, out_components, outputs, &valid, &report) == 0 &&
          out_components[0] == 1 && outputs[0] != NULL && valid != NULL,
      "amr_sample: two levels onto 9 x 9 x 9 points (%s)", schlieren_last_error());
    for (z = 0; z < 9 && outputs[0] && valid; ++z)
      for (y = 0; y < 9; ++y)
        for (x = 0; x < 9; ++x)
        {
          const int in = x >= 2 && x <= 6 && y >= 2 && y <= 6 && z >= 2 && z <= 6;
          const float want = (float)(0.5 * x + (in ? 10.0 : 0.0));
          right = right && outputs[0][(z * 9 + y) * 9 + x] == want;
          all_valid = all_valid && valid[(z * 9 + y) * 9 + x] == 1;
        }
    CHECK(right && all_valid && report && strstr(report, "points per level: L0 604, L1 125") != NULL,
      "amr_sample: the patch's 125 points from level 1 (x + 10), the other 604 from level 0 (x), "
      "exactly; every point valid (%s)", report ? report : "");
    {
      /* a grid of one plane: z = 2 crosses the patch, z = 10 no box (every point invalid, nothing
       * written past the plane: the filter's code before the engine wrote one plane past it) */
      const int flat[3] = { 9, 9, 1 };
      const double at2[3] = { 0, 0, 2 }, at10[3] = { 0, 0, 10 };
      int inside = 0, none = 0;
      CHECK(schlieren_amr_sample(2, 2, levels, extents, origins, spacings, 1, names, is_cell, comps,
              bytes, inputs, lengths, flat, at2, gh, out_components, outputs, &valid, &report) == 0 &&
            outputs[0] && outputs[0][4 * 9 + 4] == 12.0f && outputs[0][0] == 0.0f && valid[80] == 1,
        "amr_sample: the plane z = 2 takes the patch's x + 10 at (2, 2) and level 0 at (0, 0) (%s)",
        schlieren_last_error());
      CHECK(schlieren_amr_sample(2, 2, levels, extents, origins, spacings, 1, names, is_cell, comps,
              bytes, inputs, lengths, flat, at10, gh, out_components, outputs, &valid, &report) == 0,
        "amr_sample: the plane z = 10, off every box (%s)", schlieren_last_error());
      for (x = 0; x < 81 && valid; ++x)
        none += valid[x] == 0;
      inside = out_components[0] == 0 && outputs[0] == NULL;
      CHECK(none == 81 && inside, "amr_sample: off every box: the 81 points invalid, no values "
        "(no box holds 'f' there: 0 components) (%d invalid)", none);
    }
    lengths[1] = 124;
    CHECK(schlieren_amr_sample(2, 2, levels, extents, origins, spacings, 1, names, is_cell, comps,
            bytes, inputs, lengths, gd, go, gh, out_components, outputs, &valid, &report) != 0 &&
          strstr(schlieren_last_error(), "block 1's array 'f' holds 124 values") != NULL,
      "amr_sample: a short array refused by block and name: %s", schlieren_last_error());
    CHECK(schlieren_amr_sample(1, 2, levels, extents, origins, spacings, 0, NULL, NULL, NULL, NULL,
            NULL, NULL, gd, go, gh, NULL, NULL, &valid, &report) != 0 &&
          strstr(schlieren_last_error(), "block 1 is on level 1: the levels are 0 to 0") != NULL,
      "amr_sample: a block past the levels listed refused: %s", schlieren_last_error());
    CHECK(schlieren_amr_overlap(2, two_on_zero, overlapping) != 0 &&
          strstr(schlieren_last_error(), "level 0 has boxes that overlap: boxes 0 and 1 share 8 cells "
                                         "(cells i 2-3 j 2-3 k 2-3)") != NULL,
      "amr_overlap: two boxes sharing 8 cells refused with the C++ filter's message: %s",
      schlieren_last_error());
    CHECK(schlieren_amr_overlap(2, two_on_zero, touching) == 0,
      "amr_overlap: boxes that share a face taken (%s)", schlieren_last_error());
  }
  {
    /* the per-time-step cache's rule: three entries of token 7 (times 0, 1, 2), a key found, the
     * oldest evicted first when a new one does not fit, another token dropping them all */
    const double times[3] = { 0, 1, 2 };
    const uint64_t tokens[3] = { 7, 7, 7 };
    const int extents[18] = { 0, 9, 0, 9, 0, 9, 0, 9, 0, 9, 0, 9, 0, 9, 0, 9, 0, 9 };
    double bytes[3] = { 0, 0, 0 }, budget = 0, measured = 0;
    int64_t index = -2;
    unsigned char keep[3] = { 9, 9, 9 };
    int keep_new = -1;
    CHECK(schlieren_time_cache_find(3, times, tokens, extents, bytes, 1.0, 7, extents, &index,
            &budget) == 0 && index == 1 && budget > 0,
      "time_cache_find: (t 1, token 7, extent) is entry 1 (%lld; budget %g bytes; %s)",
      (long long)index, budget, schlieren_last_error());
    CHECK(schlieren_time_cache_find(3, times, tokens, extents, NULL, 1.0, 8, extents, &index,
            NULL) == 0 && index == -1,
      "time_cache_find: another token finds nothing (%lld)", (long long)index);
    bytes[0] = bytes[1] = bytes[2] = 0.1 * budget;
    schlieren_time_cache_find(3, times, tokens, extents, bytes, 0, 7, extents, &index, &budget);
    /* 3 x 0.1 b held, a new entry of 0.75 b: it fits once the oldest goes (0.2 b + 0.75 b) */
    CHECK(schlieren_time_cache_insert(3, times, tokens, extents, bytes, 3.0, 7, extents,
            0.75 * budget, keep, &keep_new, &measured) == 0 &&
          keep[0] == 0 && keep[1] == 1 && keep[2] == 1 && keep_new == 1,
      "time_cache_insert: the oldest evicted for a new entry that fits then (keep %d %d %d, new %d)",
      keep[0], keep[1], keep[2], keep_new);
    CHECK(schlieren_time_cache_insert(3, times, tokens, extents, bytes, 2.0, 7, extents, 1.0, keep,
            &keep_new, NULL) == 0 && keep[0] == 1 && keep[1] == 1 && keep[2] == 0 && keep_new == 1,
      "time_cache_insert: the same key replaced, the others kept (keep %d %d %d, new %d)", keep[0],
      keep[1], keep[2], keep_new);
    CHECK(schlieren_time_cache_insert(3, times, tokens, extents, bytes, 0.0, 8, extents, 1.0, keep,
            &keep_new, NULL) == 0 && keep[0] + keep[1] + keep[2] == 0 && keep_new == 1,
      "time_cache_insert: another token drops every entry (keep %d %d %d)", keep[0], keep[1],
      keep[2]);
    CHECK(schlieren_time_cache_insert(3, times, tokens, extents, bytes, 3.0, 7, extents, 1e30, keep,
            &keep_new, NULL) == 0 && keep_new == 0,
      "time_cache_insert: an entry past the budget is not kept");
    bytes[1] = -1;
    CHECK(schlieren_time_cache_insert(3, times, tokens, extents, bytes, 3.0, 7, extents, 1.0, keep,
            &keep_new, NULL) != 0 && strstr(schlieren_last_error(), "bytes[1]") != NULL,
      "time_cache_insert: negative bytes refused: %s", schlieren_last_error());
  }
  {
    /* RefractiveIndex's work on a grid (schlieren_index_field, the C++ filter's engine call):
       density 1.0, 1.1, 1.2 along x on 3 x 3 x 3 points, the centre outside the flow */
    const int d3[3] = { 3, 3, 3 };
    const double h3[3] = { 0.5, 0.5, 0.5 };
    float rho[27], n1f[27], g3[81];
    unsigned char valid3[27], solid3[27];
    const char* names3[2] = { "density", "U" };
    const int comps3[2] = { 1, 3 }, bytes3[2] = { 4, 4 };
    const void* vals3[2];
    const int64_t counts3[2] = { 27, 0 };
    const double K = 2.256e-4;
    const char* rep = NULL;
    int i3;
    for (i3 = 0; i3 < 27; ++i3)
    {
      rho[i3] = 1.0f + 0.1f * (float)(i3 % 3);
      valid3[i3] = i3 != 13;
    }
    vals3[0] = rho;
    vals3[1] = NULL;
    CHECK(schlieren_index_field("Model=GladstoneDale\nInputArray=density\nResampled=1", d3, h3, 2,
            names3, comps3, bytes3, vals3, counts3, -1, NULL, NULL, valid3, 27, NULL, 0, NULL, 0, n1f, 27, g3, 81,
            solid3, 27, &rep) == 0 &&
          fabs(n1f[1] - K * 1.1) < 1e-9 && fabs(g3[3 * 13] - K * 0.2) < 1e-8 &&
          fabs(g3[3 * 13 + 1]) < 1e-12 && solid3[13] == 1 && solid3[0] == 0 &&
          strstr(rep, "[\"index_model\", [\"GladstoneDale\"]], [\"index_arrays\", [\"density\"]]") &&
          strstr(rep, "[\"solid_points\", 1]") && strstr(rep, "\"solid\": true"),
      "index_field: n - 1 = K rho (%g), d(n-1)/dx = 0.2 K (%g) at the centre, the enclosed hole "
      "solid (%d), the field data (%s; %s)", n1f[1], g3[3 * 13], solid3[13], rep ? rep : "",
      schlieren_last_error());
    CHECK(schlieren_index_field("Model=GladstoneDale\nInputArray=rho", d3, h3, 2, names3, comps3,
            bytes3, vals3, counts3, -1, NULL, NULL, NULL, 0, NULL, 0, NULL, 0, n1f, 27, g3, 81, solid3, 27, &rep) != 0 &&
          strcmp(schlieren_last_error(), "GladstoneDale needs a density array ('rho', InputArray) "
                                         "but the input has no point array of that name. Point "
                                         "arrays present: density, U.") == 0,
      "index_field: a missing array refused with the C++ filter's message: %s", schlieren_last_error());
    CHECK(schlieren_index_field("Model=Passthrough\nInputArray=U", d3, h3, 2, names3, comps3,
            bytes3, vals3, counts3, -1, NULL, NULL, NULL, 0, NULL, 0, NULL, 0, n1f, 27, g3, 81, solid3, 27, &rep) != 0 &&
          strcmp(schlieren_last_error(), "The n - 1 (or n) array 'U' has 3 components; InputArray "
                                         "needs a scalar array.") == 0,
      "index_field: a vector refused: %s", schlieren_last_error());
    CHECK(schlieren_index_field("Model=Passthrough\nInputArray=density", d3, h3, 1, names3, comps3,
            bytes3, vals3, counts3, -1, NULL, NULL, NULL, 0, NULL, 0, NULL, 0, n1f, 27, g3, 81, solid3, 27, &rep) != 0 &&
          strstr(schlieren_last_error(), "Passthrough takes 'density' as n - 1, but it gives n - 1 "
                                         "from 1 to 1.2") != NULL,
      "index_field: a density taken for n - 1 refused: %s", schlieren_last_error());
    CHECK(schlieren_index_field("Model=GladstoneDale\nAmbientMode=Sideways", d3, h3, 1, names3,
            comps3, bytes3, vals3, counts3, -1, NULL, NULL, NULL, 0, NULL, 0, NULL, 0, n1f, 27, g3, 81, solid3, 27,
            &rep) != 0 && strstr(schlieren_last_error(), "AmbientMode 'Sideways' is not one of") != NULL,
      "index_field: a bad AmbientMode named: %s", schlieren_last_error());
    {
      /* the Body surface's inside as the front end found it (RefractiveIndex's port 1): ORed
         into solid with the hole; a refused surface's message; the note where it encloses
         nothing */
      unsigned char body3[27] = { 0 }, none3[27] = { 0 };
      body3[0] = body3[1] = 1;
      CHECK(schlieren_index_field("Model=GladstoneDale\nInputArray=density\nResampled=1", d3, h3,
              1, names3, comps3, bytes3, vals3, counts3, -1, NULL, NULL, valid3, 27, NULL, 0,
              body3, 27, n1f, 27, g3, 81, solid3, 27, &rep) == 0 &&
            solid3[0] == 1 && solid3[1] == 1 && solid3[2] == 0 && solid3[13] == 1 &&
            strstr(rep, "[\"solid_points\", 3]") && strstr(rep, "\"solid_note\": \"\""),
        "index_field: the Body's inside solid with the hole (%s; %s)", rep ? rep : "",
        schlieren_last_error());
      CHECK(schlieren_index_field("Model=GladstoneDale\nInputArray=density\nBodySurface=NotClosed",
              d3, h3, 1, names3, comps3, bytes3, vals3, counts3, -1, NULL, NULL, NULL, 0, NULL, 0,
              NULL, 0, n1f, 27, g3, 81, solid3, 27, &rep) != 0 &&
            strncmp(schlieren_last_error(), "The Body input is not a closed surface (it has "
                                            "boundary or non-manifold edges)", 70) == 0,
        "index_field: an open Body surface refused: %s", schlieren_last_error());
      CHECK(schlieren_index_field("Model=GladstoneDale\nInputArray=density\nBodyOverlaps=0", d3,
              h3, 1, names3, comps3, bytes3, vals3, counts3, -1, NULL, NULL, NULL, 0, NULL, 0,
              none3, 27, n1f, 27, g3, 81, solid3, 27, &rep) == 0 &&
            strstr(rep, "\"solid_note\": \"The Body surface encloses no point of the grid") &&
            strstr(rep, "\"solid\": false"),
        "index_field: a Body enclosing no point noted (%s; %s)", rep ? rep : "",
        schlieren_last_error());
      CHECK(schlieren_index_field("Model=GladstoneDale\nInputArray=density\nBodySurface=Inside",
              d3, h3, 1, names3, comps3, bytes3, vals3, counts3, -1, NULL, NULL, NULL, 0, NULL, 0,
              NULL, 0, n1f, 27, g3, 81, solid3, 27, &rep) != 0 &&
            strstr(schlieren_last_error(), "BodySurface Inside needs `body`") != NULL,
        "index_field: BodySurface Inside without its points refused: %s", schlieren_last_error());
    }
  }
  {
    /* Model Automatic's choice and the arrays found by name (schlieren_index_choices) */
    const char* rep = NULL;
    CHECK(schlieren_index_choices("Model=Automatic", "x\nRho\nT", NULL, &rep) == 0 &&
          strstr(rep, "\"model\": \"GladstoneDale\"") && strstr(rep, "\"InputArray\": \"Rho\"") &&
          strstr(rep, "RefractiveIndex: Model Automatic chose GladstoneDale: the input has a "
                      "density ('Rho'). Gas: air (Gas Custom, whose defaults are air's: K = "
                      "0.0002256 m^3/kg; set Gas for another gas). Density 'Rho' read in kg/m^3 "
                      "times DensityReference (1)"),
      "index_choices: Automatic takes Rho as a density, with the C++ filter's note (%s; %s)",
      rep ? rep : "", schlieren_last_error());
    CHECK(schlieren_index_choices("Model=IdealGas", "Temp\nPres\nU", NULL, &rep) == 0 &&
          strstr(rep, "\"TemperatureArray\": \"Temp\", \"PressureArray\": \"Pres\"") &&
          strstr(rep, "RefractiveIndex: TemperatureArray 'Temp', found by name."),
      "index_choices: IdealGas finds Temp and Pres by name (%s; %s)", rep ? rep : "",
      schlieren_last_error());
    CHECK(schlieren_index_choices("Model=Automatic", "a\nb", "a", &rep) != 0 &&
          strcmp(schlieren_last_error(),
            "Model Automatic found no array named as a refractive index (n_minus_1, n), a density "
            "(density, rho) or a temperature and a pressure (temperature, Temp, T; pressure, Pres, "
            "p) among the input's arrays: a, b. Choose the Model and its arrays.") == 0,
      "index_choices: no name to go by, the C++ filter's message: %s", schlieren_last_error());
    CHECK(schlieren_index_choices("Model=Passthrough", "a\nb", "b", &rep) == 0 &&
          strstr(rep, "\"InputArray\": \"b\""),
      "index_choices: nothing chosen or named, the fallback (the active scalars) (%s)", rep ? rep : "");
  }
  {
    /* the arrays the model reads given as cell data only, ids and integer arrays
       (schlieren_cell_fields, the C++ filter's PointFields) */
    const char* rep = NULL;
    CHECK(schlieren_cell_fields("Model=IdealGas\nTemperatureArray=T\nPressureArray=p",
            "T\tcell\tfloat\np\tpoint\tdouble\np\tcell\tdouble\nrho\tcell\tfloat", "T\np\nrho",
            &rep) == 0 && strcmp(rep, "{\"from_cells\": [\"T\"], \"note\": \"RefractiveIndex: "
            "the cell array T converted to point data (each point the mean of the cells around "
            "it, vtkCellDataToPointData), since n - 1 and its gradient are fields on points.\"}") == 0,
      "cell_fields: T only in the cells converted, p (in points too) and rho (not read) not (%s; %s)",
      rep ? rep : "", schlieren_last_error());
    CHECK(schlieren_cell_fields("Model=GladstoneDale\nInputArray=rho", "rho\tpoint\tfloat",
            "rho", &rep) == 0 && strcmp(rep, "{\"from_cells\": [], \"note\": \"\"}") == 0,
      "cell_fields: point data, nothing to convert (%s)", rep ? rep : "");
    CHECK(schlieren_cell_fields("Model=GladstoneDale\nInputArray=blk", "blk\tcell\tint",
            "blk\nrho", &rep) != 0 &&
            strstr(schlieren_last_error(), "The array 'blk' is of an integer type (int): ids and "
              "index arrays") == schlieren_last_error() &&
            strstr(schlieren_last_error(), "arrays present: blk, rho.") != NULL,
      "cell_fields: an int array refused: %s", schlieren_last_error());
    CHECK(schlieren_cell_fields("Model=GladstoneDale\nInputArray=ObjectId",
            "ObjectId\tcell\tdouble", "ObjectId", &rep) != 0 &&
            strstr(schlieren_last_error(), "'ObjectId' is named as an id") != NULL,
      "cell_fields: an id's name refused: %s", schlieren_last_error());
    CHECK(schlieren_cell_fields("Model=GladstoneDale\nInputArray=rho", "rho cell float", "rho",
            &rep) != 0 && strstr(schlieren_last_error(), "is not \"name<TAB>point|cell<TAB>type\"") != NULL,
      "cell_fields: a malformed line refused: %s", schlieren_last_error());
  }
  {
    /* the voids beside walls: the faces' kinds (schlieren_wall_faces) and a rim handed to
       schlieren_index_field */
    const int64_t offsets[6] = { 0, 3, 6, 9, 11, 14 };
    const int64_t conn[14] = { 0, 1, 2, 2, 3, 4, 5, 6, 7, 8, 9, 7, 10, 11 };
    const double normals[15] = { 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0 };
    const double velocity[15] = { 1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0 };
    unsigned char kinds[5];
    const char* rep = NULL;
    const int d3[3] = { 3, 3, 3 };
    const double h3[3] = { 0.5, 0.5, 0.5 };
    float rho[27], n1f[27], g3[81];
    unsigned char valid3[27], rim3[27], solid3[27];
    const char* names3[1] = { "density" };
    const int comps3[1] = { 1 }, bytes3[1] = { 4 };
    const void* vals3[1];
    const int64_t counts3[1] = { 27 };
    int i3;
    CHECK(schlieren_wall_faces(5, offsets, 6, conn, 14, 12, normals, 15, velocity, 15, 2.0, -1, "U",
            kinds, 5, &rep) == 0 && kinds[0] == 1 && kinds[1] == 1 && kinds[2] == 0 &&
          kinds[3] == 255 && kinds[4] == 2 &&
          strcmp(rep, "{\"velocity\": \"U\", \"wall_faces\": 2, \"flow_faces\": 1, \"still_faces\": 1, "
                      "\"turned_faces\": 1}") == 0,
      "wall_faces: a wall, a flow face beside it turned wall, fluid at rest, a line left out, a "
      "flow face beside none (%d %d %d %d %d; %s; %s)", kinds[0], kinds[1], kinds[2], kinds[3],
      kinds[4], rep ? rep : "", schlieren_last_error());
    for (i3 = 0; i3 < 27; ++i3)
    {
      rho[i3] = 1.0f;
      valid3[i3] = i3 % 3 != 0; /* the plane x = 0 outside the mesh, on the grid's face */
      rim3[i3] = i3 % 3 == 0 ? 1 : 0;
    }
    vals3[0] = rho;
    CHECK(schlieren_index_field("Model=GladstoneDale\nInputArray=density\nResampled=1\n"
                                "WallVelocity=U\nWallFaceCounts=2 1 1 1",
            d3, h3, 1, names3, comps3, bytes3, vals3, counts3, -1, NULL, NULL, valid3, 27, rim3, 27, NULL, 0,
            n1f, 27, g3, 81, solid3, 27, &rep) == 0 &&
          solid3[0] == 1 && solid3[1] == 0 && strstr(rep, "[\"solid_points\", 9]") &&
          strstr(rep, "RefractiveIndex: BodyFromGrid: of the mesh's 4 boundary faces, 2 are walls "
                      "(the flow runs along them: |U.n| < 5 % of |U| there, or 1 in groups of a few "
                      "between walls, where the flow turns onto a wall), 1 are crossed by the flow, "
                      "1 have fluid at rest beside them; 9 grid points of the voids beside them"),
      "index_field: the void on the grid's face beside a wall rim is a body, with the C++ filter's "
      "note (%s; %s)", rep ? rep : "", schlieren_last_error());
  }
  {
    /* the registration's coarse search bounded (the fuzz's seeds 3 and 11 hung here): a 300 x 16
     * film cannot be coarsened (its shorter side), so the search at its full size would visit
     * 4.4e12 pixels; a ScaleRange from 1e-300 asks for 15700 scales. Both end at once, refused
     * with what to change. */
    const int fs[2] = { 300, 16 }, ps[2] = { 24, 24 }, fs2[2] = { 64, 64 };
    const double fo[2] = { 0, 0 };
    float* film = malloc(300 * 16 * sizeof(float));
    float* photo = malloc(24 * 24 * sizeof(float));
    float* reg = malloc(300 * 16 * sizeof(float));
    int q;
    for (q = 0; q < 300 * 16; ++q)
      film[q] = (float)((q * 7919) % 101) / 100.0f;
    for (q = 0; q < 24 * 24; ++q)
      photo[q] = (float)((q * 104729) % 97) / 96.0f;
    CHECK(schlieren_photograph("", fs, fo, 0.01, film, 300 * 16, ps, photo, 24 * 24, 300 * 16, reg,
            NULL, NULL, NULL, NULL, NULL) != 0 &&
          strstr(schlieren_last_error(), "coarse search would visit") != NULL &&
          strstr(schlieren_last_error(), "less elongated") != NULL,
      "photograph: a 300 x 16 film's search is refused, not run for hours: %s", schlieren_last_error());
    CHECK(schlieren_photograph("ScaleRange=1e-300 100", fs2, fo, 0.01, film, 64 * 64, ps, photo, 24 * 24,
            64 * 64, reg, NULL, NULL, NULL, NULL, NULL) != 0 &&
          strstr(schlieren_last_error(), "narrow ScaleRange") != NULL &&
          strstr(schlieren_last_error(), "less elongated") == NULL,
      "photograph: a ScaleRange from 1e-300 is refused: %s", schlieren_last_error());
    free(film);
    free(photo);
    free(reg);
  }
  ranks_test();
  printf("%d failures\n", failures);
  return failures ? 1 : 0;
}
