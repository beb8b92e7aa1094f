/* SPDX-License-Identifier: BSD-3-Clause */
/* The engine's C interface from C (no C++ in this file): a trace of a Gaussian sphere through a
 * session, a second trace that keeps the volume, the errors as messages (an unknown property, a
 * bad value, a trace without a volume, a value the engine refuses), and the run-time OpenCL
 * loader: run with SCHLIEREN_OPENCL_LIBRARY pointing nowhere (ctest does), Backend Auto traces on
 * the CPU and says why. */
#include "schlieren_c.h"

#include <math.h>
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

  CHECK(schlieren_api_version() == SCHLIEREN_C_API_VERSION, "API version %d", schlieren_api_version());
  CHECK(strstr(schlieren_properties(), "\"Cutoff\"") != NULL, "the property list names Cutoff");
  CHECK(schlieren_fill_scene("Scene=GaussianSphere\nAmplitude=1e-4\nWidth=0.25", dims, origin,
          spacing, n1, NULL, NULL, NULL) == 0,
    "fill_scene: %s", schlieren_last_error());
  CHECK(fabs(n1[16 + 33 * (16 + 33 * 16)] - 1e-4f) < 1e-9f, "n - 1 at the centre %g", n1[16 + 33 * (16 + 33 * 16)]);
  CHECK(schlieren_fill_scene("Scene=Sphere", dims, origin, spacing, n1, NULL, NULL, NULL) != 0 &&
      strstr(schlieren_last_error(), "GaussianSphere") != NULL,
    "a bad scene names the scenes: %s", schlieren_last_error());
  schlieren_fill_scene("Scene=GaussianSphere", dims, origin, spacing, n1, NULL, NULL, NULL);

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
  CHECK(schlieren_session_set_volume(s, dims, origin, spacing, n1, NULL, NULL, -1, 7) == 0,
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
  printf("%d failures\n", failures);
  return failures ? 1 : 0;
}
