/* SPDX-License-Identifier: BSD-3-Clause */
/* Traces the Gaussian sphere through the C interface with the optics that call the engine's own
 * elementary functions (SchlierenPhysics.h) and prints, per case, a hash of each image array's
 * bytes and its range: two builds (Linux and Windows under wine, or two glibcs) give the same
 * image if and only if they print the same lines. scripts/windows-engine.sh compares them.
 *
 *     SchlierenTraceHash [Backend] [raw-folder]     (Backend: CPU (default), OpenCL, Auto)
 *
 * With a raw folder, each array is also written there as <case>_<array>.f32 (little endian). */
#include "schlieren_c.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t Hash(const void* data, size_t bytes)
{
  const unsigned char* p = (const unsigned char*)data;
  uint64_t h = 1469598103934665603ull; /* FNV-1a */
  size_t i;
  for (i = 0; i < bytes; ++i)
    h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

int main(int argc, char** argv)
{
  static const char* cases[][2] = {
    { "knife", "Cutoff=KnifeEdge" },
    { "colour", "Cutoff=ColorFilter" },
    { "shadowgraph", "Cutoff=Shadowgraph;FilmDistance=20;Filter=Gaussian" },
    { "fringes", "Cutoff=Interferometry" },
    { "disc", "Cutoff=KnifeEdge;Source=Disc;SourceSize=1 1" },
    { "gaussian_source", "Cutoff=KnifeEdge;Source=Gaussian;SourceSize=1 1" },
    { "bos", "Cutoff=BOS" },
  };
  static const char* arrays[] = { "intensity", "rgb", "deflection" };
  const char* backend = argc > 1 ? argv[1] : "CPU";
  const char* raw = argc > 2 ? argv[2] : NULL;
  const int dims[3] = { 48, 48, 48 };
  const double origin[3] = { -1, -1, -1 }, spacing[3] = { 2.0 / 47, 2.0 / 47, 2.0 / 47 };
  float* n1 = (float*)malloc(sizeof(float) * 48 * 48 * 48);
  size_t c, a;
  int failures = 0;
  if (!n1 || schlieren_fill_scene("Scene=GaussianSphere", dims, origin, spacing, 48 * 48 * 48, n1, NULL, NULL,
                       NULL))
  {
    fprintf(stderr, "fill_scene: %s\n", schlieren_last_error());
    return 1;
  }
  for (c = 0; c < sizeof(cases) / sizeof(cases[0]); ++c)
  {
    schlieren_session* s = schlieren_session_new();
    char settings[256];
    char* item;
    schlieren_session_set(s, "Resolution", "64 48");
    schlieren_session_set(s, "Passes", "3");
    schlieren_session_set(s, "Backend", backend);
    strncpy(settings, cases[c][1], sizeof(settings) - 1);
    settings[sizeof(settings) - 1] = 0;
    for (item = strtok(settings, ";"); item; item = strtok(NULL, ";"))
    {
      char* eq = strchr(item, '=');
      *eq = 0;
      if (schlieren_session_set(s, item, eq + 1))
      {
        printf("%s: %s\n", cases[c][0], schlieren_session_error(s));
        ++failures;
      }
    }
    if (schlieren_session_set_volume(s, dims, origin, spacing, n1, 48 * 48 * 48, NULL, 0, NULL, 0, -1, 7) ||
      schlieren_session_trace(s))
    {
      printf("%s: %s\n", cases[c][0], schlieren_session_error(s));
      ++failures;
      schlieren_session_free(s);
      continue;
    }
    for (a = 0; a < sizeof(arrays) / sizeof(arrays[0]); ++a)
    {
      int comps = 0;
      int64_t pixels = 0, i;
      const float* v = schlieren_session_array(s, arrays[a], &comps, &pixels);
      float lo = 0, hi = 0;
      if (!v)
        continue;
      for (i = 0; i < pixels * comps; ++i)
      {
        lo = i == 0 || v[i] < lo ? v[i] : lo;
        hi = i == 0 || v[i] > hi ? v[i] : hi;
      }
      printf("%-16s %-10s %016llx  %.9g .. %.9g\n", cases[c][0], arrays[a],
        (unsigned long long)Hash(v, sizeof(float) * (size_t)(pixels * comps)), lo, hi);
      if (raw)
      {
        char path[1024];
        FILE* f;
        snprintf(path, sizeof(path), "%s/%s_%s.f32", raw, cases[c][0], arrays[a]);
        f = fopen(path, "wb");
        if (f)
        {
          fwrite(v, sizeof(float), (size_t)(pixels * comps), f);
          fclose(f);
        }
      }
    }
    schlieren_session_free(s);
  }
  free(n1);
  return failures ? 1 : 0;
}
