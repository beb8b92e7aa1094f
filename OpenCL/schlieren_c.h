/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file schlieren_c.h
 * @brief The engine's stable C interface (libschlieren_engine.so): plain arrays in, arrays and a
 * report out. Every front end that is not the C++ plugin (Python through ctypes, C, Fortran) goes
 * through it.
 *
 * Rules of the interface:
 * - No C++ exception crosses it. A function that can fail returns 0 on success and non-zero on
 *   failure; the message is then schlieren_session_error() (per session) or
 *   schlieren_last_error() (per thread, for the functions without a session).
 * - Arrays are x fastest (VTK's point order). Inputs are copied: the caller may free them after
 *   the call. Outputs belong to the session and stay valid until its next trace or its free.
 * - Settings are the SchlierenImage proxy's properties, by name, as text: enumerations by their
 *   entry ("KnifeEdge", "RK4"), vectors as numbers separated by blanks ("0 0 -1"), booleans as
 *   0/1. schlieren_properties() lists them (JSON) with their kinds, defaults and entries.
 * - OpenCL is opened at run time (libOpenCL.so.1): without it the library loads and traces on the
 *   CPU backend (Backend Auto falls back with a warning).
 * - Strings returned are UTF-8, NUL-terminated, and owned by the library.
 * - Every array comes with its length (a count of values, or of points where the function says
 *   so); a length that is not the one needed is an error naming the array, the length given and
 *   the length needed, before anything is read or written. Grid dimensions below 1, or making
 *   more than 2^40 points, are refused before any allocation; an allocation that fails is an
 *   error ("... needs N GiB"), never an abort.
 * - A session handle that was freed, or not made by schlieren_session_new, is refused (the call
 *   fails, schlieren_session_error() and schlieren_last_error() say so) as long as its address
 *   has not been given to a new session since: a registry of the live sessions.
 * - Threads: a session is serialised, not refused: every function taking a session holds the
 *   session's mutex for its call, so a second thread calling into the same session waits for the
 *   first call to end (two threads tracing one session make one image after the other, never a
 *   torn one). The strings and arrays a session returns stay valid until the next call on that
 *   session from any thread: a program that shares a session between threads keeps its own lock
 *   over a call and the reading of what it returned. Different sessions run in parallel.
 * - Names are case-sensitive; an unknown property, setting or entry is an error naming the
 *   closest known name. Integers are read as 64-bit and an out-of-range value is reported as it
 *   was given. Settings' ranges are the engine's, the same for every front end (the C++ plugin's).
 *
 * SCHLIEREN_C_API_VERSION changes only when an existing function changes; functions are added
 * without changing it. Version 2: the array lengths (set_volume, fill_scene, numerical,
 * octree_levels, gradient, extend_into_invalid). Added since, in version 2: the ranks
 * (schlieren_parallel and the functions that take one: issue 47).
 */
#ifndef schlieren_c_h
#define schlieren_c_h

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#if defined(SCHLIEREN_C_BUILDING)
#define SCHLIEREN_C_API __declspec(dllexport)
#else
#define SCHLIEREN_C_API __declspec(dllimport)
#endif
#else
#define SCHLIEREN_C_API __attribute__((visibility("default")))
#endif

#define SCHLIEREN_C_API_VERSION 2

#ifdef __cplusplus
extern "C" {
#endif

/** SCHLIEREN_C_API_VERSION of the library loaded (compare with the header's). */
SCHLIEREN_C_API int schlieren_api_version(void);
/** The project version, "0.1.0". */
SCHLIEREN_C_API const char* schlieren_version(void);
/** This thread's last error of a session-less function ("" if none). */
SCHLIEREN_C_API const char* schlieren_last_error(void);
/**
 * The SchlierenImage properties this interface takes, as JSON:
 * [{"name": "Cutoff", "kind": "enum", "size": 1, "default": "KnifeEdge",
 *   "entries": ["KnifeEdge", ...]}, ...]; kinds: "int", "double", "bool", "enum", "string".
 */
SCHLIEREN_C_API const char* schlieren_properties(void);
/** The OpenCL device the OpenCL backend would use, as JSON {"available", "name", "platform",
 * "version", "reason"}; `device_name` a part of a device name or NULL/"" (the default choice). */
SCHLIEREN_C_API const char* schlieren_opencl_device(const char* device_name);

/** A trace session: one image traced again and again (the volume and the passes kept). */
typedef struct schlieren_session schlieren_session;

/** A new session with the SchlierenImage defaults; NULL only where memory is exhausted. */
SCHLIEREN_C_API schlieren_session* schlieren_session_new(void);
/** Frees the session and what the engine keeps for it (NULL: nothing; a handle already freed:
 * nothing, and schlieren_last_error() says so). A call running on another thread finishes first. */
SCHLIEREN_C_API void schlieren_session_free(schlieren_session* s);
/** The message of the session's last failure ("" if its last call succeeded); for a freed or
 * foreign handle, a message saying so. */
SCHLIEREN_C_API const char* schlieren_session_error(const schlieren_session* s);

/** Sets a property (see schlieren_properties) from text. Non-zero: an unknown name or entry (the
 * message names the closest known one), a value that does not parse, a boolean other than 0/1, an
 * integer outside its type (the message gives the property's range and the value as typed).
 * Other ranges are checked by the trace and schlieren_session_plan_film, as the C++ plugin does. */
SCHLIEREN_C_API int schlieren_session_set(schlieren_session* s, const char* name, const char* value);
/** A property's value as text (owned by the session until the next call); NULL: unknown name. */
SCHLIEREN_C_API const char* schlieren_session_get(schlieren_session* s, const char* name);

/**
 * The volume to trace: a regular grid of dims[0] x dims[1] x dims[2] points at `origin` with
 * `spacing`, n - 1 per point (float, `n_minus_1_count` values: the grid's points). Optional (NULL
 * and 0: none): `solid`, a byte per point, non-zero in a solid body; `levels`, RefractionOctree's
 * level per point, built for `level_tolerance` (< 0: unknown) with at most `max_level` (0 to 10)
 * levels; each with its count, the grid's points. The arrays are copied; every call counts as a
 * new volume (packed again on the next trace), so call it only when the data changed.
 */
SCHLIEREN_C_API int schlieren_session_set_volume(schlieren_session* s, const int dims[3],
  const double origin[3], const double spacing[3], const float* n_minus_1,
  int64_t n_minus_1_count, const unsigned char* solid, int64_t solid_count,
  const unsigned char* levels, int64_t levels_count, double level_tolerance, int max_level);

/** Traces the volume with the settings (continuing the kept passes where it can). 0: done. */
SCHLIEREN_C_API int schlieren_session_trace(schlieren_session* s);

/**
 * A trace's progress report: `fraction` of the update done (0 to 1, as the C++ filter's
 * UpdateProgress gets it), `text` the C++ filter's progress text ("SchlierenImage: 40 % traced,
 * about 3.2 s left"; "" until a pass's share is done), `user` as given. Called between chunks of
 * rays (each a fraction of a second), on the thread that traces, while the session is held: it
 * must not call into the same session (that call would wait for the trace). Returns non-zero to go
 * on, 0 to stop the trace (it is not called again in that trace).
 */
typedef int (*schlieren_progress_callback)(double fraction, const char* text, void* user);
/**
 * schlieren_session_trace with a progress report and a way out (`progress` NULL: the same as
 * schlieren_session_trace); the image is bit for bit the one schlieren_session_trace makes. A
 * trace the callback stopped fails with "aborted at P % of the trace: no image yet" (the report's
 * error too): no image, and the kept passes are dropped (the next trace traces all its passes).
 */
SCHLIEREN_C_API int schlieren_session_trace_progress(
  schlieren_session* s, schlieren_progress_callback progress, void* user);

/**
 * An image array of the last trace: "intensity" (1 component), "deflection" (2, radians),
 * "rgb" (3), "phase" (1), "bos_displacement" (2), "error_estimate" (1), "blocked" (1). NULL where
 * the last trace did not make it. `components` and `pixels` (may be NULL) get its shape.
 */
SCHLIEREN_C_API const float* schlieren_session_array(
  const schlieren_session* s, const char* name, int* components, int64_t* pixels);
/** The film of the last trace as an image: size in pixels, the world origin of pixel (0, 0)'s
 * centre on the film plane, and the pixel size. Non-zero: no trace yet. */
SCHLIEREN_C_API int schlieren_session_film(
  const schlieren_session* s, int size[2], double origin[2], double* pixel_size);
/** The film a trace of a volume with this grid would make with the session's settings (what
 * schlieren_session_film gives after the trace), without tracing: for a pipeline's information
 * pass. Non-zero: the settings or the grid are refused (the message says why). */
SCHLIEREN_C_API int schlieren_session_plan_film(schlieren_session* s, const int dims[3],
  const double origin[3], const double spacing[3], int size[2], double film_origin[2],
  double* pixel_size);
/**
 * The report of the last trace (or of its failure), JSON: {"field_data": {name: number or
 * string, ...} (the same names and values as the C++ SchlierenImage's field data),
 * "notes": [{"warning": true/false, "text": "..."}], "error": "..."}.
 */
SCHLIEREN_C_API const char* schlieren_session_report(const schlieren_session* s);

/**
 * BOS for cross-correlation codes (OpenPIV and other PIV software; docs/BENCH.md "BOS image
 * pairs"): writes the last trace's BOS recording and its undistorted background (the same film
 * without the flow) into the existing `folder` as `<prefix>_background.<ext>` and
 * `<prefix>_recording.<ext>`, grey, `bits` 8 or 16, `format` "png" or "tiff" (NULL: "png"), with
 * the side file `<prefix>.json` (the pixel size, the bench, the displacement's units and sign;
 * `prefix` NULL: "bos"). `written` (may be NULL) gets JSON {"background", "recording",
 * "side_file"}: the paths, owned by the session. Non-zero, with a one-line
 * schlieren_session_error(): no trace, a trace that is not Cutoff BOS, a folder that does not
 * exist, a bit depth other than 8 or 16, an unknown format, a file that cannot be written.
 */
SCHLIEREN_C_API int schlieren_session_write_bos_pair(schlieren_session* s, const char* folder,
  int bits, const char* format, const char* prefix, const char** written);

/* The other stages' engine functions, for front ends that make their own volumes. */

/**
 * RefractiveScene's analytic scenes: `settings` is text of "Name=value" lines with the proxy's
 * property names (Scene, Amplitude, Width, Radius, Center, GradientA, GradientB, Mach, Density,
 * Time; Body, BodyRadius, BodyCenter, BodyAxis), checked against the C++ filter's ranges. Writes
 * n - 1 (and where not NULL the density, the mixture fraction and, where a Body is set, the solid
 * points) at the grid's points: every array given holds `count` values, the grid's points.
 * Returns 0, or non-zero with schlieren_last_error().
 */
SCHLIEREN_C_API int schlieren_fill_scene(const char* settings, const int dims[3],
  const double origin[3], const double spacing[3], int64_t count, float* n_minus_1,
  float* density, float* mixture_fraction, unsigned char* solid);
/** RefractionOctree: a level per point for `tolerance` (>= 0; see ComputeOctreeLevels) with at
 * most `max_level` (0 to 10); `n_minus_1` and `levels` hold `count` values (the grid's points);
 * `fraction` (may be NULL) gets the fraction of cells at level >= 1. */
SCHLIEREN_C_API int schlieren_octree_levels(const int dims[3], const float* n_minus_1,
  int64_t count, double tolerance, int max_level, unsigned char* levels, double* fraction);
/**
 * NumericalSchlieren (the textbook image from the gradient of a scalar: Slice or LineOfSight) on a
 * grid of `values` (density or n - 1, x fastest). `settings`: the proxy's properties as
 * "Name=value" lines (Mode Slice/LineOfSight, Gradient Magnitude/KnifeComponent by entry text;
 * ViewDirection, ViewUp, Resolution, KnifeAngle, SliceOffset, StepSize, C0, C1, K,
 * GradientMaximum). `values` holds `values_count` values (the grid's points); `solid`, `excluded`
 * (NULL and 0: none; else the grid's points): non-zero at a body's points, at points outside the
 * input's cells. With `intensity` NULL only the film is planned (size, film_origin, pixel_size);
 * else `capacity` pixels of intensity, gradient and blocked are written and maximum_largest (may be
 * NULL) gets the qmax used and the largest q.
 */
SCHLIEREN_C_API int schlieren_numerical(const char* settings, const int dims[3],
  const double origin[3], const double spacing[3], const float* values, int64_t values_count,
  const unsigned char* solid, int64_t solid_count, const unsigned char* excluded,
  int64_t excluded_count, int size[2], double film_origin[2], double* pixel_size,
  int64_t capacity, float* intensity, float* gradient, unsigned char* blocked,
  double maximum_largest[2]);
/**
 * schlieren_numerical with a progress report and a way out (`progress` NULL: the same as
 * schlieren_numerical; see schlieren_progress_callback): called on the calling thread between
 * blocks of film rows (each a fraction of a second; a LineOfSight image of a 256^3 volume on a
 * 1024^2 film takes about a minute on two cores) with the share of the image done and the text
 * "NumericalSchlieren: P % of the image". A callback returning 0 stops the image: the call fails
 * with "aborted at P % of the image: no image" and writes no pixel. The image is bit for bit
 * schlieren_numerical's.
 */
SCHLIEREN_C_API int schlieren_numerical_progress(const char* settings, const int dims[3],
  const double origin[3], const double spacing[3], const float* values, int64_t values_count,
  const unsigned char* solid, int64_t solid_count, const unsigned char* excluded,
  int64_t excluded_count, int size[2], double film_origin[2], double* pixel_size,
  int64_t capacity, float* intensity, float* gradient, unsigned char* blocked,
  double maximum_largest[2], schlieren_progress_callback progress, void* user);
/** The gradient of n - 1 in world units, 3 floats per point (RefractiveIndex's grad_n):
 * `n_minus_1` holds `count` values (the grid's points), `grad3` `grad3_count` floats (3 a point). */
SCHLIEREN_C_API int schlieren_gradient(const int dims[3], const double spacing[3],
  const float* n_minus_1, int64_t count, float* grad3, int64_t grad3_count);
/**
 * RefractiveIndex's models on arrays of `count` points: `model` "Passthrough" (`input` is n - 1,
 * or n where `index_is_n`) or "GladstoneDale" (`input` is density, times `density_reference`,
 * gas `gas` by its table name, NULL: Air, or "Custom K M": the Gladstone-Dale constant K in
 * m^3/kg and the molar mass M in kg/mol, as the proxy's Gas Custom). Writes n - 1. `report` (may be NULL) gets the warnings
 * as lines (owned by the library until this thread's next call).
 */
SCHLIEREN_C_API int schlieren_field_index(const char* model, const float* input, int64_t count,
  int index_is_n, double density_reference, const char* gas, float* n_minus_1,
  const char** report);

/**
 * RefractiveIndex's index models, every one (the engine's ComputeFieldIndex, which the C++ filter
 * calls): `settings` are the proxy's properties as "Name=value" lines (entries by their text:
 * Model, PassthroughHoldsN, Gas, GladstoneDaleConstant, MolarMass, MixtureComposition,
 * IdealGasComposition, MixtureGas0, MixtureGas1, NumberOfSpecies, SpeciesGases (4 numbers: -1
 * Custom, 0 Air, 1 He, ...), SpeciesGladstoneDale, SpeciesMolarMass (4 each), BalanceGas (None,
 * Custom or a gas), BalanceGladstoneDale, BalanceMolarMass, DensityReference, TemperatureUnit,
 * TemperatureReference, PressureUnit, PressureReference, PressureOffset, Humidity,
 * HumidityMeasure, CO2, Wavelength; absent: the proxy's default). `number_of_arrays` arrays of
 * `count` floats, each with a role ("index", "density", "temperature", "pressure",
 * "mixture_fraction", "species1".."species4", "humidity", "co2"; "role:name" names the input array
 * in messages); `valid` (may be NULL) marks the points to compute. Writes n - 1 of the valid
 * points; `report` (may be NULL) gets the warnings as lines.
 */
SCHLIEREN_C_API int schlieren_index_model(const char* settings, int64_t count,
  int number_of_arrays, const char* const* roles, const float* const* arrays,
  const unsigned char* valid, float* n_minus_1, const char** report);
/**
 * BodyFromGrid's bodies beside a mesh's walls, the engine's part (schlieren::walls::ClassifyFaces,
 * which the C++ filter calls): the kind of each of `faces` boundary faces of the mesh from the
 * velocity beside it. Face f has the points connectivity[offsets[f]] .. [offsets[f + 1] - 1]
 * (indices below `points` of the surface's points: they tell which faces touch; offsets holds
 * faces + 1 values from 0), the unit normal normals[3f..] and the velocity velocity[3f..]
 * (the cell's beside it, or the mean of the face's points'); `largest_speed` the largest |U| of
 * the mesh; faces whose normal lies within 25 deg of axis `ignore_axis` (-1: none; the planar
 * case's front and back, a wedge's sides) and faces of fewer than 3 points are left out.
 * Writes `kinds` (a byte a face: 1 a wall, 2 crossed by the flow, 0 fluid at rest beside it,
 * 255 left out); `report` (may be NULL) gets JSON {"velocity" (`velocity_name`), "wall_faces",
 * "flow_faces", "still_faces", "turned_faces"} for schlieren_index_field's settings.
 */
SCHLIEREN_C_API int schlieren_wall_faces(int64_t faces, const int64_t* offsets,
  int64_t offsets_count, const int64_t* connectivity, int64_t connectivity_count, int64_t points,
  const double* normals, int64_t normals_count, const double* velocity, int64_t velocity_count,
  double largest_speed, int ignore_axis, const char* velocity_name, unsigned char* kinds,
  int64_t kinds_count, const char** report);
/**
 * RefractiveIndex's choice of the model and of the arrays left automatic (the engine's
 * ResolveIndexChoices, which the C++ filter calls): `settings` the proxy's properties as
 * "Name=value" lines (Model, Automatic included; PassthroughHoldsN; the arrays chosen per role,
 * InputArray .. CO2Array, absent or "": automatic; and what the notes say: Gas,
 * GladstoneDaleConstant, MolarMass, MixtureComposition, IdealGasComposition, TemperatureUnit,
 * TemperatureReference, PressureUnit, PressureReference, PressureOffset, DensityReference; the
 * other settings of schlieren_index_model are taken and not used). `present`: the input's array
 * names, one a line (point arrays, then cell arrays); `fallback_input` (may be NULL): the input
 * array where nothing chooses one (the active point scalars, else the first point array).
 * `report` (may be NULL; owned by the library until this thread's next call) gets JSON
 * {"model", "holds_n", "arrays": {"InputArray": name, ...}, "notes": [...]}. Non-zero: no name
 * says anything for Model Automatic (schlieren_last_error(), the C++ filter's message).
 */
SCHLIEREN_C_API int schlieren_index_choices(
  const char* settings, const char* present, const char* fallback_input, const char** report);
/**
 * RefractiveIndex's rule for input arrays given as cell data only (the engine's CellOnlyFields,
 * which the C++ filter calls): `settings` the model as resolved (schlieren_index_field's
 * settings of the model: Model, not Automatic; the arrays per role, InputArray .. CO2Array;
 * HumidityFromArray, CO2FromArray) says which arrays the model reads; `arrays` where the input
 * holds each array, one line a place it is found (a leaf's point or cell data): "name<TAB>point"
 * or "name<TAB>cell", then "<TAB>type", the type as VTK names it ("float", "double", "int",
 * "bit", "string"...; any but float and double is an integer type); `present` the input's array
 * names, one a line (for the message). Non-zero: an array the model reads is an id or of an
 * integer type (schlieren_last_error(), the C++ filter's message). `report` (may be NULL; owned
 * by the library until this thread's next call) gets JSON {"from_cells": [names], "note":
 * text or ""}: the arrays to convert with vtkCellDataToPointData (ProcessAllArrays off, only
 * those arrays, PassCellData off; not for an AMR) and the note that says so.
 */
SCHLIEREN_C_API int schlieren_cell_fields(
  const char* settings, const char* arrays, const char* present, const char** report);
/**
 * RefractiveIndex's work once the input is on a grid (the engine's ComputeIndexField, which the
 * C++ filter calls): the arrays the model reads chosen by name, the model, the points outside the
 * flow domain (AmbientMode), the checks of n, the gradient, the bodies (BodyFromGrid's enclosed
 * holes, an upstream `solid` array, SolidArray, the Body surface) and the output's field data,
 * with the C++
 * filter's messages. `settings`: "Name=value" lines, the proxy's names: every setting of
 * schlieren_index_model (Model as resolved: not Automatic), the arrays chosen per role
 * (InputArray, TemperatureArray, PressureArray, MixtureFractionArray, Species1Array ..
 * Species4Array, HumidityArray, CO2Array; absent or "": none), HumidityFromArray, CO2FromArray,
 * AmbientMode (Extend, DomainEdgeMedian, Value), AmbientValue, BodyFromGrid, BodyWallFaces (6),
 * SolidArray ("None" or "": none), and what the front end knows of its grid: Resampled (1: the
 * grid is a resampling of a mesh), UseSamplingBounds, CellsDescription (the input's cells in
 * words, for the message where no grid point lies in a cell). The grid's point arrays:
 * names[i], components[i], values[i] (value_bytes[i] 4 float or 8 double, value_counts[i] values:
 * the grid's points x components; NULL and 0 allowed for an array of more than one component,
 * which is only named in messages); `active_scalars` the index of the active scalars (-1: none:
 * the input array where none is chosen). `cell_arrays`, `notes` (may be NULL): the cell arrays'
 * names and the notes said so far, one a line. `valid` (NULL and 0: every point): non-zero in
 * the flow. `rim` (NULL and 0: none; else a byte a point): where the front end found the voids
 * beside a mesh's walls (BodyFromGrid on a resampled grid), the kind of the nearest boundary face
 * of the invalid points next to a valid one (1 wall, 2 crossed by the flow, else 0: see
 * schlieren_wall_faces), with the settings WallVelocity (the velocity's name) and WallFaceCounts
 * (walls, crossed, at rest, turned: the counts schlieren_wall_faces gave) for the note. `body`
 * (NULL and 0: none; else a byte a point): RefractiveIndex's Body input, the points inside the
 * closed surface as the front end found them (the C++ filter's test: vtkTriangleFilter,
 * vtkSelectEnclosedPoints shell by shell within each shell's bounds), with the settings
 * BodySurface (Inside, the default where `body` is given; NoPolygons, NotClosed, NoInsideTest:
 * the surface refused, with the C++ filter's message; None, the default otherwise) and
 * BodyOverlaps (0: no shell's bounds overlap the grid, for the note).
 * Writes n_minus_1 (the grid's points), grad3 (3 a point) and solid (a byte a point, 1
 * in a body). `report` (may be NULL; owned by the library until this thread's next call) gets
 * JSON, on failure too: {"model_done": the model ran (its warnings are to be said), "warnings",
 * "notes" (to say now: the voids beside walls), "solid_note", "solid" (any body point),
 * "arrays_read", "field_data": [[name, number or [strings]], ...] in the C++ filter's order,
 * "error"}. Non-zero: schlieren_last_error() says why.
 */
SCHLIEREN_C_API int schlieren_index_field(const char* settings, const int dims[3],
  const double spacing[3], int number_of_arrays, const char* const* names, const int* components,
  const int* value_bytes, const void* const* values, const int64_t* value_counts,
  int active_scalars, const char* cell_arrays, const char* notes, const unsigned char* valid,
  int64_t valid_count, const unsigned char* rim, int64_t rim_count, const unsigned char* body,
  int64_t body_count, float* n_minus_1, int64_t n_minus_1_count, float* grad3,
  int64_t grad3_count, unsigned char* solid, int64_t solid_count, const char** report);
/** Fills every point with valid[i] == 0 by the engine's smooth continuation of the flow (the
 * RefractiveIndex filter's AmbientMode Extend); `valid` and `n_minus_1` hold `count` values (the
 * grid's points); `filled` (may be NULL) gets how many. */
SCHLIEREN_C_API int schlieren_extend_into_invalid(const int dims[3], const unsigned char* valid,
  int64_t count, float* n_minus_1, int64_t* filled);
/** The points with valid[i] == 0 filled as RefractiveIndex's AmbientMode says: "Extend" (as
 * schlieren_extend_into_invalid), "DomainEdgeMedian" (the median of n - 1 at the flow domain's
 * edge) or "Value" (`value`). `valid` and `n_minus_1` hold `count` values (the grid's points);
 * `ambient` (may be NULL) gets the value used (NaN for Extend), `filled` (may be NULL) how many
 * points. */
SCHLIEREN_C_API int schlieren_fill_ambient(const int dims[3], const unsigned char* valid,
  int64_t count, float* n_minus_1, const char* mode, double value, double* ambient,
  int64_t* filled);
/** RefractiveIndex's bodies from the grid's holes (BodyFromGrid): marks in `solid` (a byte per
 * point) the points with valid[i] == 0 whose region of invalid points reaches no face of the grid
 * but those with wall_faces[f] != 0 (xmin, xmax, ymin, ymax, zmin, zmax; may be NULL: none).
 * `valid` and `solid` hold `count` values (the grid's points); `solid_points` (may be NULL) gets
 * how many are solid. */
SCHLIEREN_C_API int schlieren_enclosed_invalid(const int dims[3], const unsigned char* valid,
  int64_t count, const int wall_faces[6], unsigned char* solid, int64_t* solid_points);
/** RefractiveIndex's automatic sampling dimensions for a box: `longest` points along its longest
 * side, about the same spacing along the others. */
SCHLIEREN_C_API int schlieren_automatic_dimensions(const double bounds[6], int longest, int dims[3]);
/**
 * RefractiveIndex's resampling of a mesh onto an image grid, cell by cell (SchlierenSample.h): the
 * point-in-cell test and weights of VTK's vtkCell::EvaluatePosition, point arrays interpolated
 * with the cell's weights (in double, rounded to the array's type), cell arrays the holding cell's
 * value. `points`: x, y, z of each point (`points_length` values, 3 per point). The cells are
 * either a structured grid's (`structured_dims`, the points' dimensions, x fastest: its cells are
 * hexahedra; then cell_types, offsets and connectivity are NULL with length 0) or explicit
 * (`structured_dims` NULL): cell c has VTK type cell_types[c] and the points
 * connectivity[offsets[c]] .. connectivity[offsets[c + 1] - 1] (offsets holds the cells + 1
 * values, offsets[0] = 0). Tetrahedra, voxels, hexahedra, wedges and pyramids are sampled;
 * vertices, lines and faces are passed over; any other type is refused by name. `skip_cells` (may
 * be NULL with length 0) holds a byte per cell, non-zero: passed over (hidden ghost cells).
 * `number_of_arrays` arrays: names[i] (for messages), is_cell[i] (0 point array, 1 cell array),
 * components[i], value_bytes[i] (a point array: 4 float or 8 double; a cell array: the bytes of
 * one component, copied), inputs[i] with input_lengths[i] values (points or cells x components),
 * outputs[i] with output_lengths[i] values (grid points x components; the points not found are
 * left as they are). `found` holds `found_length` bytes (the grid's points): a point already
 * non-zero is left alone (found in an earlier block of a composite data set), a point found here
 * is set to 1; `found_here` (may be NULL) gets how many were.
 */
SCHLIEREN_C_API int schlieren_sample_cells(const double* points, int64_t points_length,
  const int structured_dims[3], const unsigned char* cell_types, int64_t cell_types_length,
  const int64_t* offsets, int64_t offsets_length, const int64_t* connectivity,
  int64_t connectivity_length, const unsigned char* skip_cells, int64_t skip_cells_length,
  int number_of_arrays, const char* const* names, const int* is_cell, const int* components,
  const int* value_bytes, const void* const* inputs, const int64_t* input_lengths,
  void* const* outputs, const int64_t* output_lengths, const int dims[3], const double origin[3],
  const double spacing[3], unsigned char* found, int64_t found_length, int64_t* found_here);
/**
 * The same sampler at any points (SchlierenSample.h's points mode; RefractiveIndex samples a 2D
 * input at the points schlieren_symmetry_samples gives): the mesh and arrays as for
 * schlieren_sample_cells, the points to sample `at` (x, y, z each, `at_length` values, 3 per
 * point; a point not finite is in no cell) instead of a grid; each output array and `found` hold a
 * value per point to sample. Here a 2D mesh's triangles, pixels and quads are sampled too (a point
 * within 1e-6 of a face's size of its plane); triangle strips and polygons are refused by name.
 */
SCHLIEREN_C_API int schlieren_sample_cells_at(const double* points, int64_t points_length,
  const int structured_dims[3], const unsigned char* cell_types, int64_t cell_types_length,
  const int64_t* offsets, int64_t offsets_length, const int64_t* connectivity,
  int64_t connectivity_length, const unsigned char* skip_cells, int64_t skip_cells_length,
  int number_of_arrays, const char* const* names, const int* is_cell, const int* components,
  const int* value_bytes, const void* const* inputs, const int64_t* input_lengths,
  void* const* outputs, const int64_t* output_lengths, const double* at, int64_t at_length,
  unsigned char* found, int64_t found_length, int64_t* found_here);
/** 0 where each of the `count` values of `property` (the ParaView name) of the filter `proxy`
 * ("RefractiveIndex", "RefractionOctree") lies in the range of its domain, the same check the C++
 * plugin's filters make, or where the engine lists no range for it; else non-zero and
 * schlieren_last_error() says "Name is V: it must be in [min, max]." (booleans: "must be 0 (off)
 * or 1 (on)"). NaN and infinities are in no range. */
SCHLIEREN_C_API int schlieren_check_property(
  const char* proxy, const char* property, const double* values, int count);
/** 0 where `bytes` fit in the memory this process may still use (the engine's measure: available
 * memory, the address-space limit, SCHLIEREN_MEMORY_LIMIT); else non-zero and
 * schlieren_last_error() says "<what> needs N GiB of memory; this machine has M available. <hint>":
 * for front ends that allocate arrays the engine fills. */
SCHLIEREN_C_API int schlieren_check_memory(double bytes, const char* what, const char* hint);
/** The engine's MPI options (its runtime options, as the C++ plugin's collective guard reads them):
 * `timeout`, the seconds a rank waits at a collective for the other ranks to reach it
 * (SCHLIEREN_MPI_TIMEOUT, default 120), and `abort_job`, 1 where a rank that gives up aborts the
 * MPI job (SCHLIEREN_MPI_ABORT, default 0). Either pointer may be NULL. For front ends that guard
 * their own collectives (the Python plugin). Non-zero where a variable's value cannot be read:
 * schlieren_last_error() names it. */
SCHLIEREN_C_API int schlieren_mpi_options(double* timeout, int* abort_job);

/**
 * RefractiveIndex's grid for a resampled input, in two calls (the C++ filter's RequestInformation;
 * an AMR input's dimensions come from schlieren_amr_grid between them). `settings`: "Name=value"
 * lines of SamplingDimensions (3; any <= 0: automatic), AutomaticDimension, UseSamplingBounds,
 * SamplingBounds (6) (absent: the proxy's defaults).
 * schlieren_sampling_box: the box resampled over, SamplingBounds where UseSamplingBounds is on, else
 * `input_bounds` (NULL or empty: the input has no points) pulled in about its centre by 1e-6.
 * schlieren_sampling_grid: the grid over `box`: dims (SamplingDimensions, else `amr_dims` where
 * given, else AutomaticDimension points along the longest side), origin, spacing; refused where
 * the grid with `array_bytes` per point of the input's arrays (a composite input: 64) would not fit
 * in memory. Non-zero: schlieren_last_error() gives the C++ filter's message.
 */
SCHLIEREN_C_API int schlieren_sampling_box(const char* settings, const double input_bounds[6], double box[6]);
SCHLIEREN_C_API int schlieren_sampling_grid(const char* settings, const double box[6],
  double array_bytes, const int amr_dims[3], int dims[3], double origin[3], double spacing[3]);
/** A mesh that moves over time: the grid (`whole_extent`, `origin`, `spacing`, as set over an
 * earlier step) made to span `input_bounds` (this step's, pulled in as schlieren_sampling_box
 * does) with the same points. `moved` gets 1 where it changed (then `new_origin`, `new_spacing`
 * the moved grid and `note` the C++ filter's note; owned by the library until this thread's next
 * call), else 0 (the grid as it was, `note` ""). */
SCHLIEREN_C_API int schlieren_follow_bounds(const int whole_extent[6], const double origin[3],
  const double spacing[3], const double input_bounds[6], int* moved, double new_origin[3],
  double new_spacing[3], const char** note);
/** What RefractiveIndex asks of its input for an update. A resampled input (`resampled`: not an
 * image; or `symmetric`: Symmetry made it a volume) is read whole: request = {rank, ranks, 1} (on
 * one process, or where `symmetric`, {0, 1, 1}). An image: the output's `update_extent` split into
 * piece `piece` of `pieces` with `ghosts` ghost levels (VTK's split by cells, `split_mode` 0/1/2 X/Y/Z
 * slab, 3 block), grown by one point on every side and clamped to `whole_extent` in `extent`, as
 * one piece: request = {0, 1, 0}. */
SCHLIEREN_C_API int schlieren_input_request(int resampled, int symmetric, int rank, int ranks,
  int piece, int pieces, int ghosts, int split_mode, const int update_extent[6],
  const int whole_extent[6], int request[3], int extent[6]);
/** The entries of an enumeration property of a filter ("RefractiveIndex"), as JSON [[value,
 * "Text"], ...] in Schlieren.xml's order ("[]": not an enumeration the engine lists); owned by the
 * library until this thread's next call. */
SCHLIEREN_C_API const char* schlieren_property_entries(const char* proxy, const char* property);

/**
 * RefractiveIndex's Symmetry Planar and Axisymmetric (a 2D input made a volume; an OpenFOAM wedge
 * found and revolved about its axis), in three calls: plan, samples, expand. The front end samples
 * its own mesh at the points schlieren_symmetry_samples gives.
 *
 * schlieren_symmetry_plan: `settings` are the proxy's properties as "Name=value" lines (Symmetry
 * Planar/Axisymmetric, SymmetryAxis X/Y/Z, Span, AxisFromWedge, SamplingDimensions (3),
 * AutomaticDimension, UseSamplingBounds, SamplingBounds (6); absent: the proxy's default).
 * `bounds` (NULL: the input has no points) are the input's; `points` (x, y, z each; may be NULL
 * and 0 for an image) every point of a mesh, `points_count` values (3 a point); `one_data_set`
 * 0 where the points are a composite data set's blocks. `image_extent`, `image_origin`,
 * `image_spacing`: an image input's (NULL: a mesh). Writes the grid (dims, origin, spacing) and
 * `geometry` (8 numbers for the calls below); `report` (may be NULL) gets lines "note: ..." (the
 * wedge found or not) and "warning: ..." (the input crossing the axis). Non-zero: the input or the
 * settings are refused; schlieren_last_error() says why (the C++ filter's messages).
 */
SCHLIEREN_C_API int schlieren_symmetry_plan(const char* settings, const double bounds[6],
  const double* points, int64_t points_count, int one_data_set, const int image_extent[6],
  const double image_origin[3], const double image_spacing[3], int dims[3], double origin[3],
  double spacing[3], double geometry[8], const char** report);
/** Where to sample the 2D input for the plan's grid (`geometry`, dims, origin, spacing as the
 * plan wrote them): `samples` gets their number; with `points` non-NULL (`points_count` values,
 * 3 a sample) their x, y, z, and `sample_of` (`sample_of_count` values, the grid's points) the
 * sample of every grid point. Call with `points` NULL first for the count. */
SCHLIEREN_C_API int schlieren_symmetry_samples(const double geometry[8], const int dims[3],
  const double origin[3], const double spacing[3], int64_t* samples, double* points,
  int64_t points_count, int64_t* sample_of, int64_t sample_of_count);
/** Where the plan's grid samples the 2D input at each of the points (x, y, z each;
 * `points_count` values, 3 a point): `at` the same count (for the front end's nearest-face search
 * of the voids beside walls; the engine's SymmetryToMesh). */
SCHLIEREN_C_API int schlieren_symmetry_to_mesh(const double geometry[8], const int dims[3],
  const double origin[3], const double spacing[3], const double* points, int64_t points_count,
  double* at, int64_t at_count);
/** The samples onto the grid: `out[i]` = `values[sample_of[i]]` for `components` floats each
 * (`values` holds `values_count` floats, `components` a sample; `out` `out_count`, `components` a
 * grid point), and where `sample_valid` is given (`samples` bytes, non-zero: the sample lies in
 * the mesh), `valid[i]` = 1 or 0 (`valid_count` bytes). `sample_of` holds `count` indices below
 * `samples`. Either part may be NULL and 0. */
SCHLIEREN_C_API int schlieren_symmetry_expand(const int64_t* sample_of, int64_t count,
  int64_t samples, const float* values, int64_t values_count, int components, float* out,
  int64_t out_count, const unsigned char* sample_valid, int64_t sample_valid_count,
  unsigned char* valid, int64_t valid_count);
/**
 * RefractiveIndex's overlapping AMR input (SchlierenAMRSample.h), in three calls: the overlap
 * check, the automatic grid, the sampling. Every front end reads its AMR into these arrays.
 *
 * The boxes that hold data (a process's loaded blocks): `number_of_blocks` of them, box b on level
 * block_levels[b] (0 to `levels` - 1; `levels` the levels the AMR lists, 0 to 1024), its image's
 * extent block_extents[6b .. 6b+5] (x min, x max, y min, ...; an empty extent: nothing to sample),
 * origin block_origins[3b ..] and spacing block_spacings[3b ..] (positive): point i along x lies
 * at origin x + i spacing x, i within the extent.
 */
/** 0 where no two boxes of one level overlap in cells; else non-zero and schlieren_last_error()
 * gives the C++ filter's message (the level, the first pair and their shared cells). Box i (of
 * `number_of_boxes`, the AMR's metadata, every box listed) is on level box_levels[i] (0 to 1023)
 * with the cell corners box_corners[6i .. 6i+5] (low x y z, high x y z: vtkAMRBox's); a box is
 * named by its index among its level's boxes in this order, an invalid one (high < low - 1) is
 * passed over. */
SCHLIEREN_C_API int schlieren_amr_overlap(
  int number_of_boxes, const int* box_levels, const int* box_corners);
/** The automatic grid of an AMR input: `dims` over `bounds` (finite, max >= min) at the finest
 * loaded level's spacing, capped so that the grid at `bytes_per_point` (positive) takes at most
 * half the memory available. Writes `dims`, `finest_spacing`, `finest_level`, `capped` (0/1) and
 * `note` (the C++ filter's words; owned by the library until this thread's next call). Non-zero
 * where no box is given. The blocks as above. */
SCHLIEREN_C_API int schlieren_amr_grid(int levels, int number_of_blocks, const int* block_levels,
  const int* block_extents, const double* block_origins, const double* block_spacings,
  const double bounds[6], double bytes_per_point, int dims[3], double finest_spacing[3],
  int* finest_level, int* capped, const char** note);
/**
 * The boxes sampled at the points of the grid `dims`, `origin`, `spacing` (positive), finest level
 * first, point arrays trilinear between a box's points, cell arrays between its cell centres, in
 * float. `number_of_arrays` arrays named names[k]; for box b and array k, entry
 * i = b * number_of_arrays + k of is_cell, components (1 to 1024), value_bytes (4 float, 8 double),
 * inputs and input_lengths: the box's values (its points, or its cells, max(points - 1, 1) along
 * each axis, times the components), or NULL and 0 where the box has no such array (a box whose
 * components differ from the first box's that is read is passed over for it). Writes
 * out_components[k] (0: no box holds array k), outputs[k] (grid points x out_components[k] floats,
 * NULL where 0), `valid` (a byte per grid point, 1 where a box covers it) and `report` (lines
 * "note: ..."), all owned by the library until this thread's next call of this function.
 */
SCHLIEREN_C_API int schlieren_amr_sample(int levels, int number_of_blocks, const int* block_levels,
  const int* block_extents, const double* block_origins, const double* block_spacings,
  int number_of_arrays, const char* const* names, const int* is_cell, const int* components,
  const int* value_bytes, const void* const* inputs, const int64_t* input_lengths,
  const int dims[3], const double origin[3], const double spacing[3], int* out_components,
  const float** outputs, const unsigned char** valid, const char** report);
/**
 * RefractiveIndex's per-time-step cache (SchlierenTimeStore.h), its rule without its state: the
 * front end holds its outputs, `count` entries oldest first, entry i keyed by times[i], tokens[i]
 * (the change token the front end gives: its pipeline's modified time) and extents[6i .. 6i+5],
 * holding bytes[i] (finite, >= 0; may be NULL in schlieren_time_cache_find). Times are finite.
 *
 * schlieren_time_cache_find: `index` gets the entry whose key is (time, token, extent), or -1;
 * `budget` (may be NULL) the cache's budget (a quarter of the memory available, counting the
 * bytes held).
 */
SCHLIEREN_C_API int schlieren_time_cache_find(int64_t count, const double* times,
  const uint64_t* tokens, const int* extents, const double* bytes, double time, uint64_t token,
  const int extent[6], int64_t* index, double* budget);
/** schlieren_time_cache_insert: where an entry of `new_bytes` is kept for (time, token, extent),
 * `keep` (`count` bytes) gets 1 for each entry that stays (the other tokens' and the same key's
 * go, then the oldest until the new one fits), `keep_new` 1 where the new one is kept (not where
 * it is larger than the budget), `budget` (may be NULL) the budget it was measured against. */
SCHLIEREN_C_API int schlieren_time_cache_insert(int64_t count, const double* times,
  const uint64_t* tokens, const int* extents, const double* bytes, double time, uint64_t token,
  const int extent[6], double new_bytes, unsigned char* keep, int* keep_new, double* budget);
/** The warning the C++ filter gives for an axisymmetric wedge traced with Symmetry None
 * (AxisFromWedge on): `points` every point of the mesh (`points_count` values, 3 a point),
 * `bounds` its bounds. `warning` gets it, or "" (not a wedge); owned by the library until this
 * thread's next call. `thin` (may be NULL) gets 1 where the bounds are thin enough for a wedge:
 * only then are the points read (call with NULL and 0 first to know whether to gather them). */
SCHLIEREN_C_API int schlieren_wedge_warning(const double bounds[6], const double* points,
  int64_t points_count, int* thin, const char** warning);
/**
 * A photograph beside the image (SchlierenPhotograph; docs/CFD.md): registers `photo`
 * (photo_size[0] x photo_size[1] grey values, x fastest, row 0 at the bottom as VTK reads images;
 * `photo_count` values) onto the film (film_size pixels of traced intensity, `film_count` values;
 * `film_origin` the world position of pixel (0, 0)'s centre, `pixel_size` world units a pixel),
 * calibrates its grey levels and compares the strong-gradient lines. `settings`: "Name=value"
 * lines (PhotoPixelSize, PointPairs, Refine Similarity/Rigid/Shift/None, ScaleRange, MaxRotation,
 * MaxShift, LineThreshold, MinLineLength, MaxLineDistance, CheckerSize, Refuse; NULL or "": the
 * defaults). Outputs on the film's grid, each NULL or `capacity` floats (the film's pixels):
 * `registered` (the photograph's grey, 0 where it does not cover the film), `calibrated` (in the
 * film's grey), `difference` (calibrated - film), `checkerboard`, `line_distance` (world units at
 * the film's line pixels, NaN elsewhere). `report` (may be NULL) gets JSON (owned by the library
 * until this thread's next call): "match", "reason", "scale", "rotation" (deg), "shift" (photo
 * px), "sigma_*", "edge_uncertainty" (film px), "score", "threshold", "gamma", "background",
 * "vignetting", "lines" [{"image", "distance", "offset", "matched", "points"}]... Returns 0 when it
 * ran (a photograph that does not match is "match": false with the reason, not an error);
 * non-zero for input it cannot take (schlieren_last_error()).
 */
SCHLIEREN_C_API int schlieren_photograph(const char* settings, const int film_size[2],
  const double film_origin[2], double pixel_size, const float* film, int64_t film_count,
  const int photo_size[2], const float* photo, int64_t photo_count, int64_t capacity,
  float* registered, float* calibrated, float* difference, float* checkerboard,
  float* line_distance, const char** report);
/**
 * A photograph's pixels as grey, as the photograph filters read a file (docs/CFD.md): `count`
 * pixels of `components` values each (1 grey, 2 grey and alpha: the grey, 3 RGB or 4 RGBA: the
 * luminance 0.2126 R + 0.7152 G + 0.0722 B) into `grey` (`count` floats). Returns 0, or non-zero
 * (schlieren_last_error()) for NULL arrays, a negative count or another number of components.
 */
SCHLIEREN_C_API int schlieren_photograph_grey(const double* values, int64_t count, int components, float* grey);
/**
 * The blend the photograph filters show over the film: `blend` = film + weight * difference (float
 * arithmetic; `difference` as schlieren_photograph gives it, 0 where the photograph does not cover
 * the film), `count` floats each; `weight` in [0, 1]. Returns 0, or non-zero (schlieren_last_error()).
 */
SCHLIEREN_C_API int schlieren_photograph_blend(double weight, const float* film, const float* difference,
  int64_t count, float* blend);

/*
 * Work spread over ranks (MPI processes: pvbatch, pvserver, mpi4py; docs/PARALLEL.md): the engine's
 * one seam to the ranks (schlieren::Parallel) as callbacks the caller fills in. Every function
 * below that takes a `const schlieren_parallel*` is then collective: every rank calls it, in the
 * same order, with arguments of the same shape (its own piece). NULL, or `size` 1 with no
 * callbacks: one process, as the functions without `_parallel`/`_piece` do. The engine calls the
 * callbacks on the calling thread, only during that call, always with the same `count` on every
 * rank (it exchanges lengths first where messages differ); each returns 0 on success, non-zero
 * for a failure, which ends the call with an error naming the callback (on that rank; the caller's
 * communication layer must then end the job or its other ranks, as an MPI error would). A
 * `size` below 1, a `rank` outside [0, size), a missing callback where size > 1, or what a
 * callback gives that cannot be (a length below 0 or over 2^40, a root outside the ranks) are
 * errors, never a crash.
 */
typedef struct schlieren_parallel
{
  int size;   /**< the number of ranks (>= 1) */
  int rank;   /**< this rank, in [0, size) */
  void* user; /**< given back to every callback */
  /** Element-wise over the ranks (op 0 sum, 1 min, 2 max) of `count` doubles: `in` this rank's,
   * `out` the result, the same on every rank. */
  int (*reduce)(const double* in, double* out, int64_t count, int op, void* user);
  /** `count` bytes from rank `root` into `bytes` on every rank. */
  int (*broadcast)(char* bytes, int64_t count, int root, void* user);
  /** Every rank's `count` bytes `mine`, in rank order, into `all` (size x count bytes). */
  int (*allgather)(const char* mine, int64_t count, char* all, void* user);
} schlieren_parallel;

/** Parallel::Failure: the agreement after a step that may fail on some ranks only (collective).
 * `mine` this rank's error ("" or NULL: none). `agreed` gets "" where no rank failed, else the
 * same failure on every rank: the lowest failing rank's own message on that rank, "another rank
 * (r) failed: <its message>" on the others (owned by the library until this thread's next call).
 * Returns 0, or non-zero where the parallel is refused or a callback failed. */
SCHLIEREN_C_API int schlieren_parallel_failure(
  const schlieren_parallel* parallel, const char* mine, const char** agreed);

/**
 * The session's volume as this rank's piece of a volume split over ranks (the C++ SchlierenImage's
 * input under MPI): `whole_extent` the point indices of the whole volume, `extent` this rank's
 * (inside the whole; empty, max < min on an axis, where this rank holds no point: then the arrays
 * are NULL and 0), `origin` the world position of point index (0, 0, 0) and `spacing` the whole
 * volume's; n - 1 (and the optional solid and levels) at the piece's points, x fastest. The pieces
 * of all ranks must cover the whole extent (they may overlap). Traced by
 * schlieren_session_trace_parallel; schlieren_session_trace traces it where it is the whole.
 */
SCHLIEREN_C_API int schlieren_session_set_piece(schlieren_session* s, const int whole_extent[6],
  const int extent[6], const double origin[3], const double spacing[3], const float* n_minus_1,
  int64_t n_minus_1_count, const unsigned char* solid, int64_t solid_count,
  const unsigned char* levels, int64_t levels_count, double level_tolerance, int max_level);
/**
 * schlieren_session_trace_progress over the ranks of `parallel` (collective; NULL: one process):
 * the pieces traced as the C++ SchlierenImage traces them under MPI (in pieces, rays handed
 * between ranks, or the whole volume gathered: TraceInPieces), the same image bit for bit as one
 * process on the CPU backend. Rank 0 holds the image (schlieren_session_film, _array, the report's
 * field data); the other ranks return 0 with no image (schlieren_session_film non-zero). A failure
 * on any rank fails every rank, with Parallel::Failure's words.
 */
SCHLIEREN_C_API int schlieren_session_trace_parallel(schlieren_session* s,
  const schlieren_parallel* parallel, schlieren_progress_callback progress, void* user);
/**
 * schlieren_index_field on this rank's piece of an image split over ranks (the C++
 * RefractiveIndex under MPI; collective): `grid_extent` the piece this rank holds (its requested
 * extent grown by a point on every side, within the whole: the arrays, valid, rim, body,
 * n_minus_1, grad3 and solid are at its points; empty where this rank holds none: then every
 * array is NULL and 0), `out_extent` the part it outputs, `whole_extent` the whole image's.
 * A failure on any rank fails every rank (Parallel::Failure); AmbientMode Extend becomes the
 * domain edge's median over all pieces and BodyFromGrid's holes are found across the pieces, as
 * in the C++ filter. `parallel` NULL (or one rank): schlieren_index_field on the grid.
 */
SCHLIEREN_C_API int schlieren_index_field_piece(const char* settings, const int grid_extent[6],
  const int out_extent[6], const int whole_extent[6], const double spacing[3],
  int number_of_arrays, const char* const* names, const int* components, const int* value_bytes,
  const void* const* values, const int64_t* value_counts, int active_scalars,
  const char* cell_arrays, const char* notes, const unsigned char* valid, int64_t valid_count,
  const unsigned char* rim, int64_t rim_count, const unsigned char* body, int64_t body_count,
  float* n_minus_1, int64_t n_minus_1_count, float* grad3, int64_t grad3_count,
  unsigned char* solid, int64_t solid_count, const schlieren_parallel* parallel,
  const char** report);
/**
 * schlieren_numerical_progress on a volume split over ranks (collective): `whole_dims`, `origin`
 * (the whole grid's first point) and `spacing` the whole grid's; `offset` the index of this
 * rank's first point in it and `piece_dims` its points (a 0 where this rank holds none: the
 * arrays NULL and 0). The pieces are gathered on rank 0, which makes the image of the whole grid
 * (bit for bit one process's) and gets `has_image` 1; the other ranks 0, nothing written.
 */
SCHLIEREN_C_API int schlieren_numerical_pieces(const char* settings, const int whole_dims[3],
  const double origin[3], const double spacing[3], const int offset[3], const int piece_dims[3],
  const float* values, int64_t values_count, const unsigned char* solid, int64_t solid_count,
  const unsigned char* excluded, int64_t excluded_count, int size[2], double film_origin[2],
  double* pixel_size, int64_t capacity, float* intensity, float* gradient, unsigned char* blocked,
  double maximum_largest[2], schlieren_progress_callback progress, void* user,
  const schlieren_parallel* parallel, int* has_image);
/** schlieren_amr_grid over the ranks (collective): each rank gives the boxes it holds; the
 * finest spacing and the grid are agreed over all. */
SCHLIEREN_C_API int schlieren_amr_grid_parallel(int levels, int number_of_blocks,
  const int* block_levels, const int* block_extents, const double* block_origins,
  const double* block_spacings, const double bounds[6], double bytes_per_point, int dims[3],
  double finest_spacing[3], int* finest_level, int* capped, const char** note,
  const schlieren_parallel* parallel);
/** schlieren_amr_sample over the ranks (collective): each rank samples the boxes it holds and
 * every rank gets the whole grid's values (finest level first over all ranks' boxes). */
SCHLIEREN_C_API int schlieren_amr_sample_parallel(int levels, int number_of_blocks,
  const int* block_levels, const int* block_extents, const double* block_origins,
  const double* block_spacings, int number_of_arrays, const char* const* names,
  const int* is_cell, const int* components, const int* value_bytes, const void* const* inputs,
  const int64_t* input_lengths, const int dims[3], const double origin[3],
  const double spacing[3], int* out_components, const float** outputs,
  const unsigned char** valid, const char** report, const schlieren_parallel* parallel);

#ifdef __cplusplus
}
#endif

#endif
