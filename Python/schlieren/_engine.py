# SPDX-License-Identifier: BSD-3-Clause
"""The engine's C interface (schlieren_c.h) through ctypes, on NumPy arrays.

The shared library is looked for in this order: $SCHLIEREN_ENGINE_LIBRARY, the package's own
folder (a wheel), then the system's loader path. Nothing here needs VTK.
"""
import ctypes
import json
import os
import struct
import sys
import time

import numpy as np

API_VERSION = 2

_c_int3 = ctypes.c_int * 3
_c_double3 = ctypes.c_double * 3
_f32p = ctypes.POINTER(ctypes.c_float)
_u8p = ctypes.POINTER(ctypes.c_ubyte)


class EngineError(RuntimeError):
    """An error the engine reported (the message says what and what to do)."""


class ArgumentError(EngineError, ValueError):
    """An argument refused before the engine is called (a shape, a size, an order), named."""


class ArgumentTypeError(EngineError, TypeError):
    """An argument of a type or dtype that cannot be converted without changing it, named."""


def _library_names():
    """The engine library's file names on this platform, the versioned one first."""
    if os.name == "nt":
        return ["schlieren_engine.dll", "libschlieren_engine.dll"]  # MSVC's name, mingw-w64's
    if sys.platform == "darwin":
        return ["libschlieren_engine.1.dylib", "libschlieren_engine.dylib"]
    return ["libschlieren_engine.so.1", "libschlieren_engine.so"]


def _why(error):
    """The reason a library did not load, in words: a C library older than it needs is named."""
    import re
    text = str(error)
    needed = re.findall(r"GLIBC_([0-9]+\.[0-9]+)", text)
    if needed:
        have = os.confstr("CS_GNU_LIBC_VERSION") if hasattr(os, "confstr") else None
        return ("it was built for a newer glibc (it asks for %s at least; the loader names the "
                "first version it misses) than this system's %s: install the wheel "
                "(manylinux_2_28: glibc 2.28 or newer) or build it here with pip install ."
                % (max(needed, key=lambda v: tuple(int(x) for x in v.split("."))),
                   have or "an older one"))
    return text


def _load():
    here = os.path.dirname(os.path.abspath(__file__))
    names = _library_names()
    candidates = []
    if os.environ.get("SCHLIEREN_ENGINE_LIBRARY"):
        candidates.append(os.environ["SCHLIEREN_ENGINE_LIBRARY"])
    candidates += [os.path.join(here, n) for n in names] + names[:1]
    errors = []
    for path in candidates:
        if os.sep in path and not os.path.exists(path):
            continue
        try:
            return ctypes.CDLL(path)
        except OSError as e:
            errors.append("%s: %s" % (path, _why(e)))
    if any("glibc" in e for e in errors):
        raise ImportError("The Schlieren engine library could not be loaded: " + "; ".join(errors))
    raise ImportError("The Schlieren engine library (%s) was not found: "
                      "install the package with pip, or set SCHLIEREN_ENGINE_LIBRARY to its "
                      "path (a build tree has it in build/OpenCL/). Tried: %s"
                      % (names[0], "; ".join(errors or candidates)))


_lib = _load()


def _sig(name, res, *args):
    f = getattr(_lib, name)
    f.restype = res
    f.argtypes = list(args)
    return f


_sig("schlieren_api_version", ctypes.c_int)
_sig("schlieren_version", ctypes.c_char_p)
_sig("schlieren_last_error", ctypes.c_char_p)
_sig("schlieren_properties", ctypes.c_char_p)
_sig("schlieren_opencl_device", ctypes.c_char_p, ctypes.c_char_p)
_sig("schlieren_session_new", ctypes.c_void_p)
_sig("schlieren_session_free", None, ctypes.c_void_p)
_sig("schlieren_session_error", ctypes.c_char_p, ctypes.c_void_p)
_sig("schlieren_session_set", ctypes.c_int, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_char_p)
_sig("schlieren_session_get", ctypes.c_char_p, ctypes.c_void_p, ctypes.c_char_p)
_i64 = ctypes.c_int64
_sig("schlieren_session_set_volume", ctypes.c_int, ctypes.c_void_p, _c_int3, _c_double3,
     _c_double3, _f32p, _i64, _u8p, _i64, _u8p, _i64, ctypes.c_double, ctypes.c_int)
_sig("schlieren_session_trace", ctypes.c_int, ctypes.c_void_p)
_progress_fn = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_double, ctypes.c_char_p, ctypes.c_void_p)
_sig("schlieren_session_trace_progress", ctypes.c_int, ctypes.c_void_p, _progress_fn,
     ctypes.c_void_p)
_sig("schlieren_session_array", _f32p, ctypes.c_void_p, ctypes.c_char_p,
     ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int64))
_sig("schlieren_session_film", ctypes.c_int, ctypes.c_void_p, ctypes.c_int * 2,
     ctypes.c_double * 2, ctypes.POINTER(ctypes.c_double))
_sig("schlieren_session_plan_film", ctypes.c_int, ctypes.c_void_p, _c_int3, _c_double3,
     _c_double3, ctypes.c_int * 2, ctypes.c_double * 2, ctypes.POINTER(ctypes.c_double))
_sig("schlieren_session_report", ctypes.c_char_p, ctypes.c_void_p)
_sig("schlieren_session_write_bos_pair", ctypes.c_int, ctypes.c_void_p, ctypes.c_char_p,
     ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p, ctypes.POINTER(ctypes.c_char_p))
_sig("schlieren_fill_scene", ctypes.c_int, ctypes.c_char_p, _c_int3, _c_double3, _c_double3,
     _i64, _f32p, _f32p, _f32p, _u8p)
_sig("schlieren_octree_levels", ctypes.c_int, _c_int3, _f32p, _i64, ctypes.c_double, ctypes.c_int,
     _u8p, ctypes.POINTER(ctypes.c_double))
_sig("schlieren_gradient", ctypes.c_int, _c_int3, _c_double3, _f32p, _i64, _f32p, _i64)
_sig("schlieren_field_index", ctypes.c_int, ctypes.c_char_p, _f32p, ctypes.c_int64, ctypes.c_int,
     ctypes.c_double, ctypes.c_char_p, _f32p, ctypes.POINTER(ctypes.c_char_p))

_sig("schlieren_numerical", ctypes.c_int, ctypes.c_char_p, _c_int3, _c_double3, _c_double3, _f32p,
     _i64, _u8p, _i64, _u8p, _i64, ctypes.c_int * 2, ctypes.c_double * 2,
     ctypes.POINTER(ctypes.c_double), ctypes.c_int64, _f32p, _f32p, _u8p,
     ctypes.POINTER(ctypes.c_double))
_sig("schlieren_numerical_progress", ctypes.c_int, ctypes.c_char_p, _c_int3, _c_double3,
     _c_double3, _f32p, _i64, _u8p, _i64, _u8p, _i64, ctypes.c_int * 2, ctypes.c_double * 2,
     ctypes.POINTER(ctypes.c_double), ctypes.c_int64, _f32p, _f32p, _u8p,
     ctypes.POINTER(ctypes.c_double), _progress_fn, ctypes.c_void_p)
_sig("schlieren_extend_into_invalid", ctypes.c_int, _c_int3, _u8p, _i64, _f32p,
     ctypes.POINTER(ctypes.c_int64))
_sig("schlieren_automatic_dimensions", ctypes.c_int, ctypes.c_double * 6, ctypes.c_int, _c_int3)
_sig("schlieren_check_memory", ctypes.c_int, ctypes.c_double, ctypes.c_char_p, ctypes.c_char_p)
_sig("schlieren_mpi_options", ctypes.c_int, ctypes.POINTER(ctypes.c_double),
     ctypes.POINTER(ctypes.c_int))
_sig("schlieren_sampling_box", ctypes.c_int, ctypes.c_char_p, ctypes.POINTER(ctypes.c_double),
     ctypes.c_double * 6)
_sig("schlieren_sampling_grid", ctypes.c_int, ctypes.c_char_p, ctypes.c_double * 6,
     ctypes.c_double, ctypes.POINTER(ctypes.c_int), _c_int3, _c_double3, _c_double3)
_sig("schlieren_follow_bounds", ctypes.c_int, ctypes.c_int * 6, _c_double3, _c_double3,
     ctypes.c_double * 6, ctypes.POINTER(ctypes.c_int), _c_double3, _c_double3,
     ctypes.POINTER(ctypes.c_char_p))
_sig("schlieren_input_request", ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_int,
     ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_int * 6,
     ctypes.c_int * 6, ctypes.c_int * 3, ctypes.c_int * 6)
_sig("schlieren_property_entries", ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p)
_sig("schlieren_check_property", ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p,
     ctypes.POINTER(ctypes.c_double), ctypes.c_int)
_sig("schlieren_photograph", ctypes.c_int, ctypes.c_char_p, ctypes.c_int * 2, ctypes.c_double * 2,
     ctypes.c_double, _f32p, _i64, ctypes.c_int * 2, _f32p, _i64, _i64, _f32p, _f32p, _f32p, _f32p,
     _f32p, ctypes.POINTER(ctypes.c_char_p))
_sig("schlieren_photograph_grey", ctypes.c_int, ctypes.POINTER(ctypes.c_double), _i64, ctypes.c_int,
     _f32p)
_sig("schlieren_photograph_blend", ctypes.c_int, ctypes.c_double, _f32p, _f32p, _i64, _f32p)

if _lib.schlieren_api_version() != API_VERSION:
    raise ImportError("libschlieren_engine has C API version %d; this package needs %d"
                      % (_lib.schlieren_api_version(), API_VERSION))


def _text(b):
    return b.decode("utf-8") if b is not None else ""


def _dims(dims, name="dims"):
    """[nx, ny, nz] as ints >= 1, and the number of points."""
    try:
        d = [int(x) for x in dims]
        exact = all(float(x) == int(x) for x in dims)
    except (TypeError, ValueError, OverflowError):
        raise ArgumentTypeError("%s is %r: give three integers (points along x, y, z)"
                                % (name, dims))
    if len(d) != 3 or not exact:
        raise ArgumentError("%s is %r: give three integers (points along x, y, z)" % (name, dims))
    if min(d) < 1 or max(d) > 2 ** 31 - 1:
        raise ArgumentError("%s is %s: each must be at least 1 (and fit a 32-bit integer)"
                            % (name, d))
    return d, d[0] * d[1] * d[2]


def _grid_text(d):
    return "%d x %d x %d" % tuple(d)


def _point_array(a, name, dims, dtype, optional=False, mask=False):
    """`a` as a C-contiguous 1D array of `dtype` over the grid's points, x fastest: a 1D array of
    nx*ny*nz values, or a 3D array shaped (nz, ny, nx) (indexed [z, y, x], any memory order: it
    is copied in C order). Other shapes, sizes and dtypes are refused naming the argument; `mask`:
    any real dtype, non-zero is 1."""
    if a is None:
        if optional:
            return None
        raise ArgumentError("%s must be given" % name)
    d, n = _dims(dims)
    a = np.asarray(a)
    if a.dtype.kind not in "biuf":
        raise ArgumentTypeError("%s has dtype %s: give real numbers (%s is used)"
                                % (name, a.dtype, np.dtype(dtype).name))
    nx, ny, nz = d
    if a.ndim == 3:
        if a.shape != (nz, ny, nx):
            hint = ""
            if a.shape == (nx, ny, nz):
                hint = " (this array is shaped (nx, ny, nz): give its transpose, a.T, or " \
                       "a.ravel(order='F') if x is its first index)"
            raise ArgumentError("%s has shape %s; a grid of %s points (nx x ny x nz) needs a 3D "
                                "array shaped (nz, ny, nx) = %s, indexed [z, y, x], or a 1D array "
                                "of %d values, x fastest%s"
                                % (name, a.shape, _grid_text(d), (nz, ny, nx), n, hint))
    elif a.ndim != 1:
        raise ArgumentError("%s has shape %s: give a 1D array of %d values (x fastest) or a 3D "
                            "array shaped (nz, ny, nx) = %s" % (name, a.shape, n, (nz, ny, nx)))
    if a.size != n:
        raise ArgumentError("%s holds %d values; a grid of %s points needs %d"
                            % (name, a.size, _grid_text(d), n))
    if mask:
        a = a != 0
    elif np.dtype(dtype).kind in "iu" and a.dtype.kind == "f":
        raise ArgumentTypeError("%s has dtype %s: give integers" % (name, a.dtype))
    return np.ascontiguousarray(a, dtype=dtype).reshape(-1)


def _floats(a, name="values"):
    a = np.asarray(a)
    if a.dtype.kind not in "biuf":
        raise ArgumentTypeError("%s has dtype %s: give real numbers (float32 is used)"
                                % (name, a.dtype))
    a = np.ascontiguousarray(a, dtype=np.float32).reshape(-1)
    return a, a.ctypes.data_as(_f32p)


def _bytes(a):
    if a is None:
        return None, None
    a = np.ascontiguousarray(a, dtype=np.uint8)
    return a, a.ctypes.data_as(_u8p)


def _fp(a):
    return None if a is None else a.ctypes.data_as(_f32p)


def _up(a):
    return None if a is None else a.ctypes.data_as(_u8p)


def _size(a):
    return 0 if a is None else a.size


def _check(rc):
    if rc:
        raise EngineError(_text(_lib.schlieren_last_error()))


def mpi_options():
    """(timeout, abort_job): the seconds a rank waits at a collective for the other ranks
    (SCHLIEREN_MPI_TIMEOUT, default 120) and whether a rank that gives up aborts the MPI job
    (SCHLIEREN_MPI_ABORT), from the engine's runtime options (the C++ plugin's guard's);
    EngineError naming the variable where a value cannot be read."""
    timeout, abort_job = ctypes.c_double(), ctypes.c_int()
    _check(_lib.schlieren_mpi_options(ctypes.byref(timeout), ctypes.byref(abort_job)))
    return timeout.value, bool(abort_job.value)


def check_memory(nbytes, what, hint=""):
    """Raises EngineError ("<what> needs N GiB of memory; this machine has M available. <hint>")
    where `nbytes` do not fit in the memory this process may still use (the engine's measure)."""
    _check(_lib.schlieren_check_memory(float(nbytes), what.encode(), hint.encode()))


def check_property(proxy, name, value):
    """Raises EngineError ("Name is V: it must be in [min, max].") where a value of the filter
    property `name` of `proxy` lies outside the range the engine lists for it (the check the C++
    plugin's filters make); a property with no range listed, or not numeric, passes."""
    values = value if isinstance(value, (list, tuple)) else [value]
    try:
        numbers = [float(v) for v in values]
    except (TypeError, ValueError):
        return
    array = (ctypes.c_double * max(1, len(numbers)))(*numbers)
    _check(_lib.schlieren_check_property(proxy.encode(), name.encode(), array, len(numbers)))


def _setting_lines(settings):
    """{name: value} as the C interface's "Name=value" lines (lists as numbers with spaces)."""
    return "\n".join("%s=%s" % (k, _value_text(v)) for k, v in settings.items()).encode()


def sampling_box(settings, bounds):
    """RefractiveIndex's box to resample over (schlieren_sampling_box): SamplingBounds where
    settings' UseSamplingBounds is on, else `bounds` (the input's; None: no points) pulled in by
    a hair about their centre. EngineError with the C++ filter's message."""
    box = (ctypes.c_double * 6)()
    b = None if bounds is None else (ctypes.c_double * 6)(*[float(x) for x in bounds])
    _check(_lib.schlieren_sampling_box(_setting_lines(settings), b, box))
    return list(box)


def sampling_grid(settings, box, array_bytes, amr_dims=None):
    """RefractiveIndex's grid over `box` (schlieren_sampling_grid): (dims, origin, spacing);
    `array_bytes` the input's arrays per point (a composite input: 64), `amr_dims` an AMR input's
    automatic dimensions. EngineError with the C++ filter's message (memory, the box)."""
    dims, origin, spacing = _c_int3(), _c_double3(), _c_double3()
    amr = None if amr_dims is None else (ctypes.c_int * 3)(*[int(d) for d in amr_dims])
    _check(_lib.schlieren_sampling_grid(_setting_lines(settings),
                                        (ctypes.c_double * 6)(*[float(x) for x in box]),
                                        float(array_bytes), amr, dims, origin, spacing))
    return list(dims), list(origin), list(spacing)


def follow_bounds(whole_extent, origin, spacing, bounds):
    """A mesh that moves over time (schlieren_follow_bounds): (origin, spacing, note) of the grid
    made to span this step's `bounds` with the same points, or None where it has not moved."""
    moved, o, h, note = ctypes.c_int(), _c_double3(), _c_double3(), ctypes.c_char_p()
    _check(_lib.schlieren_follow_bounds(
        (ctypes.c_int * 6)(*[int(e) for e in whole_extent]), _c_double3(*origin),
        _c_double3(*spacing), (ctypes.c_double * 6)(*[float(x) for x in bounds]),
        ctypes.byref(moved), o, h, ctypes.byref(note)))
    return (list(o), list(h), _text(note.value)) if moved.value else None


def input_request(resampled, symmetric, rank=0, ranks=1, piece=0, pieces=1, ghosts=0,
                  split_mode=3, update_extent=(0, -1, 0, -1, 0, -1),
                  whole_extent=(0, -1, 0, -1, 0, -1)):
    """What RefractiveIndex asks of its input (schlieren_input_request): (piece, pieces, extent),
    extent None for the whole extent. A plain function of the rank and the piece asked for."""
    request, extent = (ctypes.c_int * 3)(), (ctypes.c_int * 6)()
    _check(_lib.schlieren_input_request(
        int(bool(resampled)), int(bool(symmetric)), int(rank), int(ranks), int(piece),
        int(pieces), int(ghosts), int(split_mode), (ctypes.c_int * 6)(*update_extent),
        (ctypes.c_int * 6)(*whole_extent), request, extent))
    return request[0], request[1], (None if request[2] else list(extent))


def property_entries(proxy, name):
    """The entries of an enumeration property of a filter as the engine lists them (Schlieren.xml's
    order): [(value, text), ...]; [] where it is not an enumeration."""
    return [tuple(e) for e in json.loads(_text(_lib.schlieren_property_entries(
        proxy.encode(), name.encode())))]


def version():
    return _text(_lib.schlieren_version())


def properties():
    """The SchlierenImage properties the engine takes: a list of dicts (name, kind, size,
    default, entries)."""
    return json.loads(_text(_lib.schlieren_properties()))


def opencl_device(name=""):
    """The OpenCL device the OpenCL backend would use (a dict; 'reason' says why none)."""
    return json.loads(_text(_lib.schlieren_opencl_device(name.encode() if name else None)))


def _grid(dims, origin, spacing):
    d, _ = _dims(dims)
    try:
        o = [float(x) for x in origin]
        sp = [float(x) for x in spacing]
    except (TypeError, ValueError):
        raise ArgumentTypeError("origin and spacing take three numbers each; got %r and %r"
                                % (origin, spacing))
    if len(o) != 3 or len(sp) != 3:
        raise ArgumentError("origin and spacing take three numbers each; got %r and %r"
                            % (origin, spacing))
    return _c_int3(*d), _c_double3(*o), _c_double3(*sp)


def fill_scene(settings, dims, origin, spacing, body=False):
    """RefractiveScene's scene on a grid: a dict of point arrays (x fastest), float32 n_minus_1
    and density (mixture_fraction for HeliumPlume, solid where a Body is set)."""
    d, count = _dims(dims)
    plume = settings.get("Scene") == "HeliumPlume"
    has_body = settings.get("Body", "None") != "None"
    floats = 3 if plume else 2
    # the arrays are this process's to allocate: refused before, as the C++ filter does
    check_memory(count * (4.0 * floats + (1 if has_body else 0)),
                 "RefractiveScene's grid of %s points (%d float arrays)" % (_grid_text(d), floats),
                 "Lower Dimensions.")
    out = {"n_minus_1": np.empty(count, np.float32), "density": np.empty(count, np.float32)}
    if plume:
        out["mixture_fraction"] = np.empty(count, np.float32)
    if has_body:
        out["solid"] = np.zeros(count, np.uint8)
    text = "\n".join("%s=%s" % (k, _value_text(v)) for k, v in settings.items())
    _check(_lib.schlieren_fill_scene(
        text.encode(), *_grid(dims, origin, spacing), count, _fp(out["n_minus_1"]),
        _fp(out["density"]), _fp(out.get("mixture_fraction")), _up(out.get("solid"))))
    return out


def _with_progress(progress, call):
    """call(callback, user) with `progress(fraction, text) -> bool` (None: no callback) as the C
    interface's schlieren_progress_callback: a false return stops the engine; an exception in
    `progress` stops it too and is raised here, after the call."""
    if progress is None:
        return call(_progress_fn(), None)
    raised = []

    def report_progress(fraction, text, _user):
        if raised:
            return 0
        try:
            return 1 if progress(fraction, _text(text)) else 0
        except BaseException as e:  # noqa: BLE001 -- raised below, after the call
            raised.append(e)
            return 0
    rc = call(_progress_fn(report_progress), None)
    if raised:
        raise raised[0]
    return rc


def numerical(settings, dims, origin, spacing, values=None, solid=None, excluded=None,
              progress=None):
    """NumericalSchlieren on a grid: without `values` the film only, (size, origin, pixel);
    else a dict of intensity, numerical_gradient (float32), blocked (uint8) and the film, with
    maximum (the qmax used) and largest (the largest q). progress(fraction, text) -> bool, where
    given, is called between blocks of film rows (each a fraction of a second); a false return
    stops the image: EngineError "aborted at P % of the image: no image" (the image is bit for bit
    the same with or without it)."""
    text = _setting_lines(settings)
    size, film_origin, pixel = (ctypes.c_int * 2)(), (ctypes.c_double * 2)(), ctypes.c_double()
    grid = _grid(dims, origin, spacing)
    if values is None:
        _check(_lib.schlieren_numerical(text, *grid, None, 0, None, 0, None, 0, size,
                                        film_origin, ctypes.byref(pixel), 0, None, None, None,
                                        None))
        return list(size), list(film_origin), pixel.value
    a = _point_array(values, "values", dims, np.float32)
    s = _point_array(solid, "solid", dims, np.uint8, optional=True, mask=True)
    e = _point_array(excluded, "excluded", dims, np.uint8, optional=True, mask=True)
    _check(_lib.schlieren_numerical(text, *grid, None, 0, None, 0, None, 0, size,
                                    film_origin, ctypes.byref(pixel), 0, None, None, None, None))
    n = size[0] * size[1]
    check_memory(9.0 * n, "NumericalSchlieren's film of %d x %d pixels" % (size[0], size[1]),
                 "Lower Resolution.")
    out = {"intensity": np.empty(n, np.float32), "numerical_gradient": np.empty(n, np.float32),
           "blocked": np.empty(n, np.uint8)}
    ml = (ctypes.c_double * 2)()
    _check(_with_progress(progress, lambda callback, user: _lib.schlieren_numerical_progress(
        text, *grid, _fp(a), a.size, _up(s), _size(s), _up(e), _size(e), size, film_origin,
        ctypes.byref(pixel), n, _fp(out["intensity"]), _fp(out["numerical_gradient"]),
        _up(out["blocked"]), ml, callback, user)))
    out.update(size=list(size), origin=list(film_origin), pixel=pixel.value, maximum=ml[0],
               largest=ml[1])
    return out


def octree_levels(dims, n_minus_1, tolerance, max_level=7):
    """RefractionOctree's level per point, and the fraction of cells at level >= 1."""
    a = _point_array(n_minus_1, "n_minus_1", dims, np.float32)
    levels = np.zeros(a.size, np.uint8)
    fraction = ctypes.c_double(0)
    _check(_lib.schlieren_octree_levels(_grid(dims, [0] * 3, [1] * 3)[0], _fp(a), a.size,
                                        float(tolerance), int(max_level), _up(levels),
                                        ctypes.byref(fraction)))
    return levels, fraction.value


def gradient(dims, spacing, n_minus_1):
    """grad n in world units, (points, 3) float32."""
    a = _point_array(n_minus_1, "n_minus_1", dims, np.float32)
    check_memory(12.0 * a.size, "The gradient of %s points" % _grid_text(_dims(dims)[0]),
                 "Give a smaller grid.")
    g = np.empty((a.size, 3), np.float32)
    grid = _grid(dims, [0] * 3, spacing)
    _check(_lib.schlieren_gradient(grid[0], grid[2], _fp(a), a.size, _fp(g), g.size))
    return g


def field_index(model, values, index_is_n=False, density_reference=1.0, gas=None):
    """RefractiveIndex's Passthrough or GladstoneDale on an array: (n - 1 float32, warnings)."""
    a, p = _floats(values)
    out = np.empty(a.size, np.float32)
    report = ctypes.c_char_p()
    _check(_lib.schlieren_field_index(str(model).encode(), p, a.size, int(bool(index_is_n)),
                                      float(density_reference), gas.encode() if gas else None,
                                      out.ctypes.data_as(_f32p), ctypes.byref(report)))
    return out, [w for w in _text(report.value).split("\n") if w]


def index_model(settings, arrays, valid=None):
    """RefractiveIndex's index models, every one (the C interface's schlieren_index_model):
    `settings` the proxy's properties by name (entries by their text), `arrays` role -> values
    (roles: index, density, temperature, pressure, mixture_fraction, species1-4, humidity, co2;
    "role:name" names the input array in messages). Returns (n - 1 float32, warnings)."""
    f = _sig("schlieren_index_model", ctypes.c_int, ctypes.c_char_p, ctypes.c_int64, ctypes.c_int,
             ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(_f32p), _u8p,
             _f32p, ctypes.POINTER(ctypes.c_char_p))
    kept = [np.ascontiguousarray(v, dtype=np.float32) for v in arrays.values()]
    count = kept[0].size if kept else (0 if valid is None else np.asarray(valid).size)
    for role, a in zip(arrays, kept):
        if a.size != count:
            raise EngineError("index_model: array %s has %d values, not %d" % (role, a.size,
                                                                              count))
    roles = (ctypes.c_char_p * max(1, len(kept)))(*[r.encode() for r in arrays])
    ptrs = (_f32p * max(1, len(kept)))(*[a.ctypes.data_as(_f32p) for a in kept])
    v, vp = _bytes(valid)
    out = np.zeros(count, np.float32)
    text = _setting_lines(settings)
    report = ctypes.c_char_p()
    _check(f(text, count, len(kept), roles, ptrs, vp, out.ctypes.data_as(_f32p),
             ctypes.byref(report)))
    return out, [w for w in _text(report.value).split("\n") if w]


def index_choices(settings, present, fallback_input=""):
    """RefractiveIndex's choice of the model and of the arrays left automatic (the C interface's
    schlieren_index_choices, the C++ filter's): `settings` the proxy's properties by name (Model,
    Automatic included; the arrays per role, "" automatic), `present` the input's array names,
    `fallback_input` the input array where nothing chooses one. Returns {"model", "holds_n",
    "arrays": {property: name}, "notes": [...]}; Model Automatic with no name to go by raises
    EngineError with the C++ filter's message."""
    f = _sig("schlieren_index_choices", ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p,
             ctypes.c_char_p, ctypes.POINTER(ctypes.c_char_p))
    text = "\n".join("%s=%s" % (key, _value_text(x)) for key, x in settings.items()).encode()
    report = ctypes.c_char_p()
    _check(f(text, "\n".join(present).encode(), (fallback_input or "").encode(),
             ctypes.byref(report)))
    return json.loads(_text(report.value))


def cell_fields(settings, places, present):
    """RefractiveIndex's rule for arrays given as cell data only (the C interface's
    schlieren_cell_fields, the C++ filter's): `settings` the model as resolved (Model, the arrays
    per role, HumidityFromArray, CO2FromArray), `places` (name, "point" or "cell", VTK type name)
    for each place an array is found, `present` the input's array names. Returns {"from_cells":
    [names to convert with vtkCellDataToPointData], "note": text or ""}; an id or an array of an
    integer type read by the model raises EngineError with the C++ filter's message."""
    f = _sig("schlieren_cell_fields", ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p,
             ctypes.c_char_p, ctypes.POINTER(ctypes.c_char_p))
    text = "\n".join("%s=%s" % (key, _value_text(x)) for key, x in settings.items()).encode()
    lines = "\n".join("%s\t%s\t%s" % tuple(p) for p in places).encode()
    report = ctypes.c_char_p()
    _check(f(text, lines, "\n".join(present).encode(), ctypes.byref(report)))
    return json.loads(_text(report.value))


def wall_faces(offsets, connectivity, points, normals, velocity, largest_speed, ignore_axis=-1,
               velocity_name="U"):
    """The kinds of a mesh's boundary faces from the velocity beside them (the C interface's
    schlieren_wall_faces, the C++ filter's): face f has the surface points
    connectivity[offsets[f]:offsets[f + 1]] (below `points`), the normal normals[f] and the
    velocity velocity[f] (arrays of shape (faces, 3)). Returns (kinds uint8: 1 wall, 2 crossed
    by the flow, 0 at rest, 255 left out; the report: velocity, wall_faces, flow_faces,
    still_faces, turned_faces)."""
    f = _sig("schlieren_wall_faces", ctypes.c_int, _i64, ctypes.POINTER(ctypes.c_int64), _i64,
             ctypes.POINTER(ctypes.c_int64), _i64, _i64, ctypes.POINTER(ctypes.c_double), _i64,
             ctypes.POINTER(ctypes.c_double), _i64, ctypes.c_double, ctypes.c_int,
             ctypes.c_char_p, _u8p, _i64, ctypes.POINTER(ctypes.c_char_p))
    o = np.ascontiguousarray(offsets, dtype=np.int64).reshape(-1)
    c = np.ascontiguousarray(connectivity, dtype=np.int64).reshape(-1)
    n = np.ascontiguousarray(normals, dtype=np.float64).reshape(-1)
    u = np.ascontiguousarray(velocity, dtype=np.float64).reshape(-1)
    faces = max(0, o.size - 1)
    kinds = np.zeros(faces, np.uint8)
    i64p = ctypes.POINTER(ctypes.c_int64)
    dp = ctypes.POINTER(ctypes.c_double)
    report = ctypes.c_char_p()
    _check(f(faces, o.ctypes.data_as(i64p), o.size, c.ctypes.data_as(i64p), c.size, int(points),
             n.ctypes.data_as(dp), n.size, u.ctypes.data_as(dp), u.size, float(largest_speed),
             int(ignore_axis), str(velocity_name).encode(), _up(kinds), kinds.size,
             ctypes.byref(report)))
    return kinds, json.loads(_text(report.value))


def index_field(settings, dims, spacing, arrays, valid=None, active_scalars=-1, cell_arrays=(),
                notes=(), rim=None, body=None, extents=None, ranks=None):
    """RefractiveIndex's work once the input is on a grid (the C interface's
    schlieren_index_field, which the C++ filter's engine call is): `settings` the proxy's
    properties by name (Model as resolved, the arrays chosen per role, AmbientMode, BodyFromGrid,
    SolidArray...; and Resampled, UseSamplingBounds, CellsDescription), `arrays` the grid's point
    arrays in order, name -> values (points x components; float32 and float64 read as they are,
    other types as float64), `valid` (None: every point) non-zero in the flow, `body` (None:
    none) non-zero inside RefractiveIndex's Body surface (settings BodySurface, BodyOverlaps:
    see schlieren_c.h). Returns (n - 1
    float32, grad n float32 (points, 3), solid uint8 or None where there is no body, the report:
    warnings, notes, solid_note, arrays_read, field_data [(name, number or [strings])]). A
    failure raises EngineError with the C++ filter's message; its report is then `error.report`."""
    f = _sig("schlieren_index_field", ctypes.c_int, ctypes.c_char_p, _c_int3, _c_double3,
             ctypes.c_int, ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(ctypes.c_int),
             ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_void_p),
             ctypes.POINTER(ctypes.c_int64), ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p,
             _u8p, _i64, _u8p, _i64, _u8p, _i64, _f32p, _i64, _f32p, _i64, _u8p, _i64,
             ctypes.POINTER(ctypes.c_char_p))
    if extents is not None:
        # a piece (index_field_piece): the grid is the piece's
        g = [int(v) for v in extents[0]]
        dims = [max(g[2 * a + 1] - g[2 * a] + 1, 0) for a in range(3)]
    grid = _grid(dims if min(dims) > 0 else [1, 1, 1], [0] * 3, spacing)
    n = int(np.prod([int(d) for d in dims]))
    kept, names, comps, nbytes = [], [], [], []
    for name, a in arrays.items():
        a = np.asarray(a)
        if a.dtype.kind not in "biuf":
            raise ArgumentTypeError("array %r has dtype %s: give real numbers" % (name, a.dtype))
        a = np.ascontiguousarray(a, dtype=a.dtype if a.dtype in (np.float32, np.float64)
                                 else np.float64)
        c = 1 if a.ndim == 1 else int(np.prod(a.shape[1:]))
        kept.append(a.reshape(-1))
        names.append(str(name).encode())
        comps.append(c)
        nbytes.append(a.dtype.itemsize)
    k = max(1, len(kept))
    c_names = (ctypes.c_char_p * k)(*names)
    c_comps = (ctypes.c_int * k)(*comps)
    c_bytes = (ctypes.c_int * k)(*nbytes)
    c_values = (ctypes.c_void_p * k)(*[a.ctypes.data for a in kept])
    c_counts = (ctypes.c_int64 * k)(*[a.size for a in kept])
    v = None if valid is None else _point_array(valid, "valid", dims, np.uint8, mask=True)
    r = None if rim is None else _point_array(rim, "rim", dims, np.uint8)
    b = None if body is None else _point_array(body, "body", dims, np.uint8, mask=True)
    n1 = np.zeros(n, np.float32)
    grad = np.zeros((n, 3), np.float32)
    solid = np.zeros(n, np.uint8)
    text = "\n".join("%s=%s" % (key, _value_text(x)) for key, x in settings.items()).encode()
    report = ctypes.c_char_p()
    tail = (_up(v), _size(v), _up(r), _size(r), _up(b), _size(b),
            n1.ctypes.data_as(_f32p) if n else None, n1.size,
            grad.ctypes.data_as(_f32p) if n else None, grad.size,
            solid.ctypes.data_as(_u8p) if n else None, solid.size)
    if extents is None:
        rc = f(text, grid[0], grid[2], len(kept), c_names, c_comps, c_bytes, c_values, c_counts,
               int(active_scalars), "\n".join(cell_arrays).encode(), "\n".join(notes).encode(),
               *tail, ctypes.byref(report))
    else:
        ext6 = ctypes.c_int * 6
        fp = _sig("schlieren_index_field_piece", ctypes.c_int, ctypes.c_char_p, ext6, ext6, ext6,
                  _c_double3, ctypes.c_int, ctypes.POINTER(ctypes.c_char_p),
                  ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int),
                  ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_int64), ctypes.c_int,
                  ctypes.c_char_p, ctypes.c_char_p, _u8p, _i64, _u8p, _i64, _u8p, _i64, _f32p,
                  _i64, _f32p, _i64, _u8p, _i64, _parallel_p, ctypes.POINTER(ctypes.c_char_p))
        rc = fp(text, *[ext6(*[int(x) for x in e]) for e in extents], grid[2], len(kept),
                c_names, c_comps, c_bytes, c_values, c_counts, int(active_scalars),
                "\n".join(cell_arrays).encode(), "\n".join(notes).encode(), *tail,
                _piece_ranks(ranks), ctypes.byref(report))
    result = json.loads(_text(report.value) or "{}")
    result["field_data"] = [tuple(p) for p in result.get("field_data", [])]
    if rc:
        error = ranks.error() if ranks is not None else \
            EngineError(_text(_lib.schlieren_last_error()))
        error.report = result
        raise error
    return n1, grad, (solid if result.get("solid") else None), result


def extend_into_invalid(dims, valid, n_minus_1):
    """Fills n - 1 (float32, changed in place) where valid == 0 by the engine's smooth
    continuation of the flow; returns how many points were filled."""
    n_minus_1 = np.asarray(n_minus_1)
    if n_minus_1.dtype != np.float32 or not n_minus_1.flags.c_contiguous:
        raise ArgumentTypeError("n_minus_1 must be a C-contiguous float32 array (it is filled in "
                                "place); got %s%s" % (n_minus_1.dtype, "" if
                                                      n_minus_1.flags.c_contiguous else
                                                      ", not C-contiguous"))
    _point_array(n_minus_1, "n_minus_1", dims, np.float32)  # the shape and size checks
    v = _point_array(valid, "valid", dims, np.uint8, mask=True)
    filled = ctypes.c_int64(0)
    _check(_lib.schlieren_extend_into_invalid(_grid(dims, [0] * 3, [1] * 3)[0], _up(v), v.size,
                                              n_minus_1.ctypes.data_as(_f32p),
                                              ctypes.byref(filled)))
    return filled.value


def fill_ambient(dims, valid, n_minus_1, mode, value=0.0):
    """Fills n - 1 (float32, in place) where valid == 0 as RefractiveIndex's AmbientMode says
    (Extend, DomainEdgeMedian, Value); returns (the value used, NaN for Extend; points filled)."""
    f = _sig("schlieren_fill_ambient", ctypes.c_int, _c_int3, _u8p, ctypes.c_int64, _f32p,
             ctypes.c_char_p, ctypes.c_double, ctypes.POINTER(ctypes.c_double),
             ctypes.POINTER(ctypes.c_int64))
    n_minus_1 = np.asarray(n_minus_1)
    if n_minus_1.dtype != np.float32 or not n_minus_1.flags.c_contiguous:
        raise ArgumentTypeError("n_minus_1 must be a C-contiguous float32 array (it is filled in "
                                "place)")
    _point_array(n_minus_1, "n_minus_1", dims, np.float32)  # the shape and size checks
    v = _point_array(valid, "valid", dims, np.uint8, mask=True)
    used, filled = ctypes.c_double(0.0), ctypes.c_int64(0)
    _check(f(_grid(dims, [0] * 3, [1] * 3)[0], _up(v), v.size, n_minus_1.ctypes.data_as(_f32p),
             mode.encode(), float(value), ctypes.byref(used), ctypes.byref(filled)))
    return used.value, filled.value


def enclosed_invalid(dims, valid, wall_faces=None):
    """RefractiveIndex's bodies from the grid's holes: a uint8 array, 1 at the invalid points that
    the flow encloses (their region reaches no face of the grid but the wall faces)."""
    f = _sig("schlieren_enclosed_invalid", ctypes.c_int, _c_int3, _u8p, ctypes.c_int64,
             ctypes.POINTER(ctypes.c_int), _u8p, ctypes.POINTER(ctypes.c_int64))
    v = _point_array(valid, "valid", dims, np.uint8, mask=True)
    solid = np.zeros(v.size, np.uint8)
    walls = None if wall_faces is None else (ctypes.c_int * 6)(*[int(w) for w in wall_faces])
    count = ctypes.c_int64(0)
    _check(f(_grid(dims, [0] * 3, [1] * 3)[0], _up(v), v.size, walls,
             solid.ctypes.data_as(_u8p), ctypes.byref(count)))
    return solid


_sig("schlieren_sample_cells", ctypes.c_int, ctypes.POINTER(ctypes.c_double), _i64, ctypes.c_void_p,
     _u8p, _i64, ctypes.POINTER(ctypes.c_int64), _i64, ctypes.POINTER(ctypes.c_int64), _i64, _u8p,
     _i64, ctypes.c_int, ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(ctypes.c_int),
     ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_void_p),
     ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_void_p),
     ctypes.POINTER(ctypes.c_int64), _c_int3, _c_double3, _c_double3, _u8p, _i64,
     ctypes.POINTER(ctypes.c_int64))


def _mesh_array(a, name, dtype, columns=None):
    """`a` as a C-contiguous array of `dtype` (a copy only where it must convert), refused by
    name where it is not real numbers or not shaped (n,) or (n, columns)."""
    a = np.asarray(a)
    if a.dtype.kind not in "biuf" or (np.dtype(dtype).kind in "iu" and a.dtype.kind == "f"):
        raise ArgumentTypeError("%s has dtype %s: give %s" % (
            name, a.dtype, "integers" if np.dtype(dtype).kind in "iu" else "real numbers"))
    if columns is not None and not (a.ndim == 2 and a.shape[1] == columns) and \
            not (a.ndim == 1 and a.size % columns == 0):
        raise ArgumentError("%s has shape %s: give an array shaped (n, %d)" % (name, a.shape, columns))
    if columns is None and a.ndim != 1:
        raise ArgumentError("%s has shape %s: give a 1D array" % (name, a.shape))
    return np.ascontiguousarray(a, dtype=dtype).reshape(-1)


_sig("schlieren_sample_cells_at", ctypes.c_int, ctypes.POINTER(ctypes.c_double), _i64,
     ctypes.c_void_p, _u8p, _i64, ctypes.POINTER(ctypes.c_int64), _i64,
     ctypes.POINTER(ctypes.c_int64), _i64, _u8p, _i64, ctypes.c_int,
     ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int),
     ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_void_p),
     ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_void_p),
     ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_double), _i64, _u8p, _i64,
     ctypes.POINTER(ctypes.c_int64))


def _sample(n, where, call, points, cell_types, offsets, connectivity, structured_dims,
            skip_cells, point_arrays, cell_arrays, found):
    """sample_cells' and sample_cells_at's arguments checked and made C's; `call(mesh_args,
    array_args, found)` calls the engine. Returns (found, {name: array of n values})."""
    pts = _mesh_array(points, "points", np.float64, 3)
    structured = structured_dims is not None
    if structured:
        sd, _ = _dims(structured_dims, "structured_dims")
        sdims, types, offs, conn = _c_int3(*sd), None, None, None
    else:
        if cell_types is None or offsets is None or connectivity is None:
            raise ArgumentError("cell_types, offsets and connectivity must be given (or "
                                "structured_dims for a structured grid)")
        sdims = None
        types = _mesh_array(cell_types, "cell_types", np.uint8)
        offs = _mesh_array(offsets, "offsets", np.int64)
        conn = _mesh_array(connectivity, "connectivity", np.int64)
    skip = None if skip_cells is None else _mesh_array(skip_cells, "skip_cells", np.uint8)
    if found is None:
        found = np.zeros(n, np.uint8)
    elif not (isinstance(found, np.ndarray) and found.dtype == np.uint8 and found.ndim == 1 and
              found.flags.c_contiguous):
        raise ArgumentTypeError("found must be a C-contiguous 1D uint8 array (updated in place)")
    names, cells, comps, nbytes, ins, outs, keep = [], [], [], [], [], [], []
    point_arrays, cell_arrays = list(point_arrays), list(cell_arrays)
    per_point = sum(np.asarray(a).itemsize * max(1, np.asarray(a).size // max(1, len(a)))
                    for _, a in point_arrays + cell_arrays)
    check_memory(n * (per_point + 1.0), "The resampled arrays (%s points)" % where,
                 "Lower SamplingDimensions.")
    for is_cell, arrays in ((0, point_arrays), (1, cell_arrays)):
        for name, a in arrays:
            a = np.asarray(a)
            if a.ndim not in (1, 2) or a.dtype.kind not in "biuf":
                raise ArgumentError("array '%s' has shape %s and dtype %s: give real numbers "
                                    "shaped (tuples,) or (tuples, components)"
                                    % (name, a.shape, a.dtype))
            if not is_cell and a.dtype != np.float32:
                a = a.astype(np.float64)
            a = np.ascontiguousarray(a)
            c = 1 if a.ndim == 1 else a.shape[1]
            out = np.zeros((n,) if a.ndim == 1 else (n, c), a.dtype)
            names.append(str(name).encode())
            cells.append(is_cell)
            comps.append(c)
            nbytes.append(a.dtype.itemsize)
            ins.append(a)
            outs.append(out)
            keep.append(name)
    k = len(names)

    def ptr(a, t):
        return None if a is None else a.ctypes.data_as(ctypes.POINTER(t))
    mesh_args = (ptr(pts, ctypes.c_double), pts.size, sdims, ptr(types, ctypes.c_ubyte),
                 _size(types), ptr(offs, ctypes.c_int64), _size(offs), ptr(conn, ctypes.c_int64),
                 _size(conn), ptr(skip, ctypes.c_ubyte), _size(skip))
    array_args = (k, (ctypes.c_char_p * k)(*names), (ctypes.c_int * k)(*cells),
                  (ctypes.c_int * k)(*comps), (ctypes.c_int * k)(*nbytes),
                  (ctypes.c_void_p * k)(*[a.ctypes.data for a in ins]),
                  (ctypes.c_int64 * k)(*[a.size for a in ins]),
                  (ctypes.c_void_p * k)(*[a.ctypes.data for a in outs]),
                  (ctypes.c_int64 * k)(*[a.size for a in outs]))
    _check(call(mesh_args, array_args, found))
    return found, dict(zip(keep, outs))


def sample_cells(points, dims, origin, spacing, cell_types=None, offsets=None, connectivity=None,
                 structured_dims=None, skip_cells=None, point_arrays=(), cell_arrays=(),
                 found=None):
    """RefractiveIndex's resampling of a mesh onto an image grid, cell by cell (schlieren_c.h's
    schlieren_sample_cells): VTK's point-in-cell test and weights, the C++ filter's values.

    `points` (n, 3); the cells either explicit (`cell_types` uint8 VTK types, `offsets` of
    cells + 1 values, `connectivity`) or a structured grid's (`structured_dims`, its points'
    dimensions). `skip_cells` (a byte per cell, non-zero: passed over) may be None.
    `point_arrays` and `cell_arrays`: (name, array) pairs, each array shaped (tuples,) or
    (tuples, components); a point array of float32 stays float32, any other is interpolated
    as float64; a cell array keeps its dtype. `found` (a uint8 array over the grid's points,
    updated in place: an earlier block's points are left alone) may be None.
    Returns (found, {name: array over the grid's points, (points,) or (points, components)}):
    the points not found hold 0."""
    d, n = _dims(dims)
    count = ctypes.c_int64(0)

    def call(mesh_args, array_args, found):
        return _lib.schlieren_sample_cells(
            *mesh_args, *array_args, _c_int3(*d), _grid(dims, origin, spacing)[1],
            _grid(dims, origin, spacing)[2], found.ctypes.data_as(_u8p), found.size,
            ctypes.byref(count))
    return _sample(n, _grid_text(d), call, points, cell_types, offsets, connectivity,
                   structured_dims, skip_cells, point_arrays, cell_arrays, found)


def sample_cells_at(points, at, cell_types=None, offsets=None, connectivity=None,
                    structured_dims=None, skip_cells=None, point_arrays=(), cell_arrays=(),
                    found=None):
    """The same sampler at any points (schlieren_sample_cells_at): the mesh and arrays as
    sample_cells takes them, `at` ((m, 3) float64) the points to sample instead of a grid; a 2D
    mesh's triangles, pixels and quads are sampled in their plane too. Returns (found, {name:
    array of m values}) as sample_cells does."""
    if at is None:
        raise ArgumentError("at (the points to sample, (m, 3)) must be given")
    where = _xyz(at, "at")
    m = where.size // 3
    count = ctypes.c_int64(0)

    def call(mesh_args, array_args, found):
        return _lib.schlieren_sample_cells_at(
            *mesh_args, *array_args, where.ctypes.data_as(ctypes.POINTER(ctypes.c_double)),
            where.size, found.ctypes.data_as(_u8p), found.size, ctypes.byref(count))
    return _sample(m, "%d" % m, call, points, cell_types, offsets, connectivity, structured_dims,
                   skip_cells, point_arrays, cell_arrays, found)


def _xyz(points, name="points"):
    """Points as a C-contiguous float64 array of x, y, z each (an (n, 3) array or n*3 values)."""
    if points is None:
        return None
    a = np.asarray(points)
    if a.dtype.kind not in "biuf":
        raise ArgumentTypeError("%s has dtype %s: give real numbers (float64 is used)"
                                % (name, a.dtype))
    if not (a.ndim == 2 and a.shape[1] == 3) and not (a.ndim == 1 and a.size % 3 == 0):
        raise ArgumentError("%s has shape %s: give an (n, 3) array of x, y, z or n*3 values"
                            % (name, a.shape))
    return np.ascontiguousarray(a, dtype=np.float64).reshape(-1)


def _six(v, name):
    try:
        v = [float(x) for x in v]
    except (TypeError, ValueError):
        raise ArgumentTypeError("%s is %r: give 6 numbers" % (name, v))
    if len(v) != 6:
        raise ArgumentError("%s is %r: give 6 numbers" % (name, v))
    return (ctypes.c_double * 6)(*v)


_f64p = ctypes.POINTER(ctypes.c_double)
_i64p = ctypes.POINTER(ctypes.c_int64)


def symmetry_plan(settings, bounds, points=None, one_data_set=True, image=None):
    """RefractiveIndex's Symmetry Planar/Axisymmetric (the C interface's schlieren_symmetry_plan):
    the checks, the wedge and the 3D grid for a 2D input. `settings`: Symmetry, SymmetryAxis,
    Span, AxisFromWedge, SamplingDimensions, AutomaticDimension, UseSamplingBounds,
    SamplingBounds by name; `bounds` the input's (None: it has no points); `points` a mesh's
    points ((n, 3) or n*3 values; None for an image); `image` an image input's (extent, origin,
    spacing). Returns a dict: dims, origin, spacing, geometry (8 numbers), notes, warnings."""
    f = _sig("schlieren_symmetry_plan", ctypes.c_int, ctypes.c_char_p,
             ctypes.POINTER(ctypes.c_double), _f64p, ctypes.c_int64, ctypes.c_int,
             ctypes.POINTER(ctypes.c_int), _f64p, _f64p, _c_int3, _c_double3, _c_double3,
             ctypes.c_double * 8, ctypes.POINTER(ctypes.c_char_p))
    xyz = _xyz(points)
    b = None if bounds is None else _six(bounds, "bounds")
    extent = origin = spacing = None
    if image is not None:
        e, o, h = image
        if len(e) != 6 or len(o) != 3 or len(h) != 3:
            raise ArgumentError("image is (extent (6), origin (3), spacing (3)); got %r"
                                % (image,))
        extent = (ctypes.c_int * 6)(*[int(x) for x in e])
        origin, spacing = _c_double3(*[float(x) for x in o]), _c_double3(*[float(x) for x in h])
    dims, o3, h3, g = _c_int3(), _c_double3(), _c_double3(), (ctypes.c_double * 8)()
    report = ctypes.c_char_p()
    text = _setting_lines(settings)
    _check(f(text, b, None if xyz is None else xyz.ctypes.data_as(_f64p),
             0 if xyz is None else xyz.size, 1 if one_data_set else 0, extent, origin, spacing,
             dims, o3, h3, g, ctypes.byref(report)))
    lines = [w for w in _text(report.value).split("\n") if w]
    return dict(dims=list(dims), origin=list(o3), spacing=list(h3), geometry=list(g),
                notes=[w[len("note: "):] for w in lines if w.startswith("note: ")],
                warnings=[w[len("warning: "):] for w in lines if w.startswith("warning: ")])


def symmetry_to_mesh(plan, points):
    """Where the plan's grid samples the 2D input at `points` (n x 3): the C interface's
    schlieren_symmetry_to_mesh (the engine's SymmetryToMesh)."""
    f = _sig("schlieren_symmetry_to_mesh", ctypes.c_int, ctypes.c_double * 8, _c_int3, _c_double3,
             _c_double3, _f64p, _i64, _f64p, _i64)
    xyz = np.ascontiguousarray(points, dtype=np.float64).reshape(-1)
    at = np.zeros_like(xyz)
    _check(f((ctypes.c_double * 8)(*plan["geometry"]), *_grid(plan["dims"], plan["origin"],
                                                               plan["spacing"]),
             xyz.ctypes.data_as(_f64p), xyz.size, at.ctypes.data_as(_f64p), at.size))
    return at.reshape(-1, 3)


def symmetry_samples(plan):
    """Where to sample the 2D input for `plan` (symmetry_plan's): (points, an (m, 3) float64
    array; sample_of, an int64 per grid point, x fastest: the sample it takes)."""
    f = _sig("schlieren_symmetry_samples", ctypes.c_int, ctypes.c_double * 8, _c_int3,
             _c_double3, _c_double3, _i64p, _f64p, ctypes.c_int64, _i64p, ctypes.c_int64)
    d, n = _dims(plan["dims"])
    args = ((ctypes.c_double * 8)(*[float(x) for x in plan["geometry"]]), _c_int3(*d),
            _c_double3(*[float(x) for x in plan["origin"]]),
            _c_double3(*[float(x) for x in plan["spacing"]]))
    m = ctypes.c_int64(0)
    _check(f(*args, ctypes.byref(m), None, 0, None, 0))
    check_memory(24.0 * m.value + 8.0 * n, "The symmetric grid's samples",
                 "Lower SamplingDimensions or AutomaticDimension.")
    points = np.zeros(3 * m.value, np.float64)
    sample_of = np.zeros(n, np.int64)
    _check(f(*args, ctypes.byref(m), points.ctypes.data_as(_f64p), points.size,
             sample_of.ctypes.data_as(_i64p), sample_of.size))
    return points.reshape(-1, 3), sample_of


def symmetry_expand(sample_of, samples, values=None, sample_valid=None):
    """The samples onto the grid (schlieren_symmetry_expand): `values` (float32, `samples` rows
    of any number of components) gives a float32 array per grid point of the same components;
    `sample_valid` (a byte per sample, non-zero: in the mesh) gives uint8 validity. Returns
    (values or None, valid or None)."""
    f = _sig("schlieren_symmetry_expand", ctypes.c_int, _i64p, ctypes.c_int64, ctypes.c_int64,
             _f32p, ctypes.c_int64, ctypes.c_int, _f32p, ctypes.c_int64, _u8p, ctypes.c_int64,
             _u8p, ctypes.c_int64)
    s = np.asarray(sample_of)
    if s.dtype != np.int64 or s.ndim != 1:
        raise ArgumentTypeError("sample_of must be a 1D int64 array (symmetry_samples'); got %s "
                                "%s" % (s.dtype, s.shape))
    s = np.ascontiguousarray(s)
    count, out, valid, v, sv, components = s.size, None, None, None, None, 1
    if values is not None:
        v = np.asarray(values)
        if v.dtype.kind not in "biuf" or v.ndim not in (1, 2) or v.shape[0] != samples:
            raise ArgumentError("values has dtype %s and shape %s: give %d samples of real "
                                "numbers (one row each)" % (v.dtype, v.shape, samples))
        components = 1 if v.ndim == 1 else v.shape[1]
        v = np.ascontiguousarray(v, dtype=np.float32)
        out = np.zeros((count, components) if v.ndim == 2 else count, np.float32)
    if sample_valid is not None:
        sv = np.ascontiguousarray(np.asarray(sample_valid) != 0, dtype=np.uint8).reshape(-1)
        valid = np.zeros(count, np.uint8)
    _check(f(s.ctypes.data_as(_i64p), count, int(samples), _fp(v), _size(v), components,
             _fp(out), _size(out), _up(sv), _size(sv), _up(valid), _size(valid)))
    return out, valid


def wedge_warning(bounds, points):
    """The C++ filter's warning for an axisymmetric wedge traced with Symmetry None, or "".
    `points`: an (n, 3) array, or a function that gives it (called only where the bounds are thin
    enough for a wedge: a 3D mesh's points are not gathered)."""
    f = _sig("schlieren_wedge_warning", ctypes.c_int, ctypes.c_double * 6, _f64p, ctypes.c_int64,
             ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_char_p))
    b = _six(bounds, "bounds")
    thin, warning = ctypes.c_int(0), ctypes.c_char_p()
    if callable(points):
        _check(f(b, None, 0, ctypes.byref(thin), ctypes.byref(warning)))
        if not thin.value:
            return ""
        points = points()
    xyz = _xyz(points)
    _check(f(b, None if xyz is None else xyz.ctypes.data_as(_f64p),
             0 if xyz is None else xyz.size, ctypes.byref(thin), ctypes.byref(warning)))
    return _text(warning.value)


def _amr_blocks(levels, blocks):
    """The AMR boxes as schlieren_amr_grid and schlieren_amr_sample take them: levels, count and
    the four arrays (level, extent, origin, spacing of each)."""
    blocks = list(blocks)
    try:
        levels = int(levels)
        lv = (ctypes.c_int * max(1, len(blocks)))(*[int(b["level"]) for b in blocks])
        ext = (ctypes.c_int * max(6, 6 * len(blocks)))(
            *[int(v) for b in blocks for v in b["extent"]])
        org = (ctypes.c_double * max(3, 3 * len(blocks)))(
            *[float(v) for b in blocks for v in b["origin"]])
        spc = (ctypes.c_double * max(3, 3 * len(blocks)))(
            *[float(v) for b in blocks for v in b["spacing"]])
    except (TypeError, ValueError, KeyError) as e:
        raise ArgumentTypeError("AMR blocks: each a dict of level, extent (6 integers), origin "
                                "and spacing (3 numbers each) (%s)" % e)
    if any(len(b["extent"]) != 6 or len(b["origin"]) != 3 or len(b["spacing"]) != 3
           for b in blocks):
        raise ArgumentError("AMR blocks: each takes an extent of 6 integers and an origin and a "
                            "spacing of 3 numbers")
    return levels, len(blocks), lv, ext, org, spc


def amr_overlap(boxes):
    """Raises EngineError with the C++ filter's message where two boxes of one level of an
    overlapping AMR share cells (schlieren_amr_overlap). `boxes`: the AMR's metadata boxes,
    (level, low corner (3), high corner (3)) each, every box of every level in order."""
    boxes = list(boxes)
    try:
        lv = (ctypes.c_int * max(1, len(boxes)))(*[int(b[0]) for b in boxes])
        corners = (ctypes.c_int * max(6, 6 * len(boxes)))(
            *[int(v) for b in boxes for v in list(b[1]) + list(b[2])])
    except (TypeError, ValueError, IndexError) as e:
        raise ArgumentTypeError("AMR boxes: (level, low corner, high corner) each (%s)" % e)
    if any(len(b[1]) != 3 or len(b[2]) != 3 for b in boxes):
        raise ArgumentError("AMR boxes: each corner takes 3 integers")
    _check(_lib.schlieren_amr_overlap(len(boxes), lv, corners))


def amr_grid(levels, blocks, bounds, bytes_per_point, ranks=None):
    """RefractiveIndex's automatic grid of an AMR input (schlieren_amr_grid): the finest loaded
    level's spacing over `bounds`, capped by memory. `blocks`: dicts of level, extent, origin,
    spacing. Returns dict(dims, finest_spacing, finest_level, capped, note). With `ranks` (a
    Ranks; collective: schlieren_amr_grid_parallel) `blocks` are this rank's."""
    args = [ctypes.c_int, ctypes.c_int, ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int),
            ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double),
            ctypes.c_double * 6, ctypes.c_double, _c_int3, _c_double3,
            ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int),
            ctypes.POINTER(ctypes.c_char_p)]
    f = _sig("schlieren_amr_grid" if ranks is None else "schlieren_amr_grid_parallel",
             ctypes.c_int, *(args + ([] if ranks is None else [_parallel_p])))
    levels, n, lv, ext, org, spc = _amr_blocks(levels, blocks)
    dims, finest, level, capped, note = _c_int3(), _c_double3(), ctypes.c_int(), ctypes.c_int(), \
        ctypes.c_char_p()
    rc = f(levels, n, lv, ext, org, spc, _six(bounds, "bounds"), float(bytes_per_point), dims,
           finest, ctypes.byref(level), ctypes.byref(capped), ctypes.byref(note),
           *([] if ranks is None else [ranks.pointer()]))
    if rc:
        raise EngineError(_text(_lib.schlieren_last_error())) if ranks is None else ranks.error()
    return dict(dims=list(dims), finest_spacing=list(finest), finest_level=level.value,
                capped=bool(capped.value), note=_text(note.value))


def amr_sample(levels, blocks, names, dims, origin, spacing, ranks=None):
    """An overlapping AMR's boxes sampled onto an image grid by the engine (schlieren_amr_sample),
    as the C++ RefractiveIndex samples them: every grid point from the finest level covering it,
    point arrays trilinear between a box's points, cell arrays between its cell centres, float32.
    `blocks`: dicts of level, extent, origin, spacing and arrays ({name: (values, is_cell)}, the
    values shaped (tuples,) or (tuples, components); float32 read as it is, anything else as
    float64). Returns (valid: uint8 over the grid's points, {name: float32 array (points,) or
    (points, components)} for the names some box holds, notes: list of str). With `ranks` (a
    Ranks; collective: schlieren_amr_sample_parallel) `blocks` are this rank's, `names` the same
    list on every rank, and every rank gets the whole grid's values."""
    args = [ctypes.c_int, ctypes.c_int, ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int),
            ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double), ctypes.c_int,
            ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(ctypes.c_int),
            ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int),
            ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_int64), _c_int3, _c_double3,
            _c_double3, ctypes.POINTER(ctypes.c_int), ctypes.POINTER(_f32p),
            ctypes.POINTER(_u8p), ctypes.POINTER(ctypes.c_char_p)]
    f = _sig("schlieren_amr_sample" if ranks is None else "schlieren_amr_sample_parallel",
             ctypes.c_int, *(args + ([] if ranks is None else [_parallel_p])))
    blocks = list(blocks)
    names = [str(n) for n in names]
    levels, n, lv, ext, org, spc = _amr_blocks(levels, blocks)
    d, count = _dims(dims)
    grid = _grid(dims, origin, spacing)
    k = len(names)
    entries = max(1, n * k)
    cells, comps, nbytes = (ctypes.c_int * entries)(), (ctypes.c_int * entries)(), \
        (ctypes.c_int * entries)()
    ins, lengths, keep = (ctypes.c_void_p * entries)(), (ctypes.c_int64 * entries)(), []
    for b, block in enumerate(blocks):
        arrays = block.get("arrays", {})
        for j, name in enumerate(names):
            if name not in arrays:
                continue
            values, is_cell = arrays[name]
            a = np.asarray(values)
            if a.ndim not in (1, 2) or a.dtype.kind not in "biuf":
                raise ArgumentError("AMR block %d's array '%s' has shape %s and dtype %s: give "
                                    "real numbers shaped (tuples,) or (tuples, components)"
                                    % (b, name, a.shape, a.dtype))
            a = np.ascontiguousarray(a, np.float32 if a.dtype == np.float32 else np.float64)
            keep.append(a)
            i = b * k + j
            cells[i], comps[i], nbytes[i] = int(bool(is_cell)), 1 if a.ndim == 1 else \
                a.shape[1], a.dtype.itemsize
            ins[i], lengths[i] = a.ctypes.data, a.size
    out_comps = (ctypes.c_int * max(1, k))()
    outs = (_f32p * max(1, k))()
    valid, report = _u8p(), ctypes.c_char_p()
    rc = f(levels, n, lv, ext, org, spc, k, (ctypes.c_char_p * max(1, k))(
        *[x.encode() for x in names]), cells, comps, nbytes, ins, lengths, *grid, out_comps, outs,
        ctypes.byref(valid), ctypes.byref(report), *([] if ranks is None else [ranks.pointer()]))
    if rc:
        raise EngineError(_text(_lib.schlieren_last_error())) if ranks is None else ranks.error()
    sampled = {}
    for j, name in enumerate(names):
        c = out_comps[j]
        if c:
            v = np.ctypeslib.as_array(outs[j], shape=(count * c,)).copy()
            sampled[name] = v if c == 1 else v.reshape(count, c)
    mask = np.ctypeslib.as_array(valid, shape=(count,)).copy()
    notes = [line[len("note: "):] for line in _text(report.value).splitlines()
             if line.startswith("note: ")]
    return mask, sampled, notes


def _time_cache_arrays(entries):
    """(time, token, extent, bytes) entries as the C arrays of schlieren_time_cache_*."""
    entries = list(entries)
    n = len(entries)
    try:
        times = (ctypes.c_double * max(1, n))(*[float(e[0]) for e in entries])
        tokens = (ctypes.c_uint64 * max(1, n))(*[int(e[1]) for e in entries])
        extents = (ctypes.c_int * max(6, 6 * n))(*[int(v) for e in entries for v in e[2]])
        sizes = (ctypes.c_double * max(1, n))(*[float(e[3]) for e in entries])
    except (TypeError, ValueError, IndexError, OverflowError) as e:
        raise ArgumentTypeError("time cache entries: (time, token, extent (6), bytes) each (%s)"
                                % e)
    if any(len(e[2]) != 6 for e in entries):
        raise ArgumentError("time cache entries: each extent takes 6 integers")
    return n, times, tokens, extents, sizes


def _time_cache_key(time, token, extent):
    try:
        key = float(time), ctypes.c_uint64(int(token)), (ctypes.c_int * 6)(*[int(v) for v in extent])
    except (TypeError, ValueError, OverflowError) as e:
        raise ArgumentTypeError("time cache key: a time, a token and an extent of 6 (%s)" % e)
    if len(list(extent)) != 6:
        raise ArgumentError("time cache key: the extent takes 6 integers")
    return key


def time_cache_find(entries, time, token, extent):
    """RefractiveIndex's per-time-step cache (schlieren_time_cache_find): the index among
    `entries` ((time, token, extent, bytes) each, oldest first) of the one keyed (time, token,
    extent), or -1; and the cache's budget in bytes (a quarter of the memory available, counting
    the entries')."""
    f = _sig("schlieren_time_cache_find", ctypes.c_int, ctypes.c_int64,
             ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_uint64),
             ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_double), ctypes.c_double,
             ctypes.c_uint64, ctypes.c_int * 6, ctypes.POINTER(ctypes.c_int64),
             ctypes.POINTER(ctypes.c_double))
    n, times, tokens, extents, sizes = _time_cache_arrays(entries)
    index, budget = ctypes.c_int64(-1), ctypes.c_double(0.0)
    _check(f(n, times, tokens, extents, sizes, *_time_cache_key(time, token, extent),
             ctypes.byref(index), ctypes.byref(budget)))
    return index.value, budget.value


def time_cache_insert(entries, time, token, extent, nbytes):
    """Where an output of `nbytes` is kept for (time, token, extent) (schlieren_time_cache_insert):
    (a keep flag per entry of `entries`, oldest first; whether the new one is kept; the budget)."""
    f = _sig("schlieren_time_cache_insert", ctypes.c_int, ctypes.c_int64,
             ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_uint64),
             ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_double), ctypes.c_double,
             ctypes.c_uint64, ctypes.c_int * 6, ctypes.c_double, _u8p,
             ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_double))
    n, times, tokens, extents, sizes = _time_cache_arrays(entries)
    keep = np.zeros(max(1, n), np.uint8)
    kept, budget = ctypes.c_int(0), ctypes.c_double(0.0)
    _check(f(n, times, tokens, extents, sizes, *_time_cache_key(time, token, extent),
             float(nbytes), keep.ctypes.data_as(_u8p), ctypes.byref(kept), ctypes.byref(budget)))
    return [bool(k) for k in keep[:n]], bool(kept.value), budget.value


def automatic_dimensions(bounds, longest):
    """RefractiveIndex's automatic sampling dimensions of a box."""
    dims = _c_int3()
    try:
        longest = int(longest)
    except (TypeError, ValueError):
        raise ArgumentTypeError("AutomaticDimension is %r: give an integer" % (longest,))
    if not -2 ** 31 <= longest < 2 ** 31:
        raise ArgumentError("AutomaticDimension is %d: it must fit a 32-bit integer (and be "
                            "at least 2)" % longest)
    _check(_lib.schlieren_automatic_dimensions((ctypes.c_double * 6)(*bounds), longest, dims))
    return list(dims)


def _value_text(v):
    if isinstance(v, str):
        return v
    if isinstance(v, bool):
        return "1" if v else "0"
    if np.ndim(v) == 0:
        return repr(float(v)) if isinstance(v, float) else str(v)
    return " ".join(_value_text(x.item() if hasattr(x, "item") else x) for x in v)


class Session:
    """A trace session (schlieren_c.h): the volume, the settings, repeated traces.

    One call at a time: the engine serialises the calls of two threads on one session (the
    second waits), so a session shared by threads traces one image after the other."""

    def __init__(self):
        self._s = _lib.schlieren_session_new()
        if not self._s:
            raise MemoryError("schlieren_session_new failed: " + _text(_lib.schlieren_last_error()))

    def free(self):
        """Frees the engine's session now (also done when the object is collected); any later
        call raises EngineError."""
        s, self._s = getattr(self, "_s", None), None
        if s and _lib is not None:
            _lib.schlieren_session_free(s)

    def __del__(self):
        self.free()

    def _live(self, what):
        if not self._s:
            raise EngineError("Session.%s: this session was freed (Session.free()); make a new "
                              "Session" % what)
        return self._s

    def _error(self):
        return EngineError(_text(_lib.schlieren_session_error(self._s)))

    def set(self, name, value):
        s = self._live("set")
        if _lib.schlieren_session_set(s, str(name).encode(), _value_text(value).encode()):
            raise self._error()

    def get(self, name):
        s = self._live("get")
        v = _lib.schlieren_session_get(s, str(name).encode())
        if v is None:
            raise self._error()
        return _text(v)

    def set_volume(self, dims, origin, spacing, n_minus_1, solid=None, levels=None,
                   level_tolerance=-1.0, max_level=7):
        """The volume: n_minus_1 (and solid, levels where given) as 1D arrays of nx*ny*nz values,
        x fastest, or 3D arrays shaped (nz, ny, nx); other shapes and sizes are refused."""
        s = self._live("set_volume")
        a = _point_array(n_minus_1, "n_minus_1", dims, np.float32)
        sol = _point_array(solid, "solid", dims, np.uint8, optional=True, mask=True)
        lv = _point_array(levels, "levels", dims, np.uint8, optional=True)
        if _lib.schlieren_session_set_volume(s, *_grid(dims, origin, spacing), _fp(a), a.size,
                                             _up(sol), _size(sol), _up(lv), _size(lv),
                                             float(level_tolerance), int(max_level)):
            raise self._error()

    def set_piece(self, whole_extent, extent, origin, spacing, n_minus_1, solid=None,
                  levels=None, level_tolerance=-1.0, max_level=7):
        """This rank's piece of a volume split over ranks (schlieren_session_set_piece): the
        whole volume's point extent, this piece's (empty: n_minus_1 None), `origin` the world
        position of point index (0, 0, 0), the arrays at the piece's points."""
        s = self._live("set_piece")
        e = [int(v) for v in extent]
        d = [e[2 * a + 1] - e[2 * a] + 1 for a in range(3)]
        empty = min(d) < 1
        a = None if empty else _point_array(n_minus_1, "n_minus_1", d, np.float32)
        sol = None if empty else _point_array(solid, "solid", d, np.uint8, optional=True,
                                              mask=True)
        lv = None if empty else _point_array(levels, "levels", d, np.uint8, optional=True)
        ext6 = ctypes.c_int * 6
        if _lib.schlieren_session_set_piece(s, ext6(*[int(v) for v in whole_extent]), ext6(*e),
                                            _c_double3(*origin), _c_double3(*spacing), _fp(a),
                                            _size(a), _up(sol), _size(sol), _up(lv), _size(lv),
                                            float(level_tolerance), int(max_level)):
            raise self._error()

    def trace_parallel(self, ranks, progress=None):
        """trace() over `ranks` (collective; schlieren_session_trace_parallel): rank 0 gets the
        report of the image, the others a report without one (film() raises there)."""
        s = self._live("trace_parallel")
        rc = _with_progress(progress, lambda callback, user:
                            _lib.schlieren_session_trace_parallel(s, _piece_ranks(ranks),
                                                                  callback, user))
        report = json.loads(_text(_lib.schlieren_session_report(s)))
        if rc:
            err = self._error()
            if ranks is not None and ranks._raised:
                err = ranks._raised[0] if isinstance(ranks._raised[0], OutOfStep) else \
                    EngineError("%s (%s)" % (err, ranks._raised[0]))
            err.report = report
            raise err
        return report

    def has_image(self):
        """Whether the last trace left an image here (rank 0 of a parallel trace)."""
        s = self._live("has_image")
        return bool(_lib.schlieren_session_array(s, b"intensity", None, None))

    def trace(self, progress=None):
        """Traces; returns the report (dict: field_data, notes, error). Raises EngineError.

        progress(fraction, text) -> bool, where given, is called between chunks of rays (each a
        fraction of a second) with the share of the update done and the C++ filter's progress
        text ("" at first); a false return stops the trace: EngineError "aborted at P % of the
        trace: no image yet" (the image is bit for bit the same with or without it). It must not
        call into this session. An exception it raises stops the trace and is raised here."""
        s = self._live("trace")
        if progress is None:
            rc = _lib.schlieren_session_trace(s)
        else:
            rc = _with_progress(progress, lambda callback, user:
                                _lib.schlieren_session_trace_progress(s, callback, user))
        report = json.loads(_text(_lib.schlieren_session_report(s)))
        if rc:
            err = self._error()
            err.report = report
            raise err
        return report

    def array(self, name):
        """An image array of the last trace, (pixels, components) float32 copy, or None."""
        s = self._live("array")
        comps, pixels = ctypes.c_int(0), ctypes.c_int64(0)
        p = _lib.schlieren_session_array(s, str(name).encode(), ctypes.byref(comps),
                                         ctypes.byref(pixels))
        if not p:
            return None
        a = np.ctypeslib.as_array(p, shape=(pixels.value * comps.value,)).copy()
        return a.reshape(pixels.value, comps.value) if comps.value > 1 else a

    def plan_film(self, dims, origin, spacing):
        """The film a trace of this grid would make: (size, origin, pixel size)."""
        s = self._live("plan_film")
        size, o, px = (ctypes.c_int * 2)(), (ctypes.c_double * 2)(), ctypes.c_double()
        if _lib.schlieren_session_plan_film(s, *_grid(dims, origin, spacing), size, o,
                                            ctypes.byref(px)):
            raise self._error()
        return list(size), list(o), px.value

    def film(self):
        """(size [nx, ny], origin of pixel (0, 0) [x, y], pixel size) of the last trace."""
        s = self._live("film")
        size, origin, px = (ctypes.c_int * 2)(), (ctypes.c_double * 2)(), ctypes.c_double()
        if _lib.schlieren_session_film(s, size, origin, ctypes.byref(px)):
            raise self._error()
        return list(size), list(origin), px.value

    def write_bos_pair(self, folder, bits=8, format="png", prefix="bos"):
        """The last trace (Cutoff BOS) as an image pair for PIV codes (docs/BENCH.md "BOS image
        pairs"): <prefix>_background and <prefix>_recording (grey PNG or TIFF, 8 or 16 bits) and
        the side file <prefix>.json in the existing `folder`. Returns the paths {"background",
        "recording", "side_file"}; raises EngineError with one line on bad input."""
        s = self._live("write_bos_pair")
        if isinstance(bits, bool) or not isinstance(bits, (int, np.integer)):
            raise ArgumentTypeError("write_bos_pair: bits must be 8 or 16, not %r" % (bits,))
        if not -2 ** 31 <= bits < 2 ** 31:
            raise ArgumentError("write_bos_pair: a bit depth of %d is not one PIV codes read "
                                "here: use 8 or 16." % bits)
        written = ctypes.c_char_p()
        if _lib.schlieren_session_write_bos_pair(s, os.fsencode(str(folder)), int(bits),
                                                 str(format).encode(), str(prefix).encode(),
                                                 ctypes.byref(written)):
            raise self._error()
        return json.loads(_text(written.value))


PHOTOGRAPH_IMAGES = ("registered", "calibrated", "difference", "checkerboard", "line_distance")


def grey(image, name="photo"):
    """A photograph as grey float32 (h, w): a 2D array as it is; (h, w, 1) its values, (h, w, 2)
    (grey and alpha) the grey, (h, w, 3) or (h, w, 4) colour by its luminance (Rec. 709 weights;
    alpha ignored): the engine's schlieren_photograph_grey, as the C++ filter reads a photograph.
    Other shapes and dtypes are refused."""
    a = np.asarray(image)
    if a.dtype.kind not in "biuf":
        raise ArgumentTypeError("%s has dtype %s: give grey levels or RGB(A) numbers" % (name, a.dtype))
    if a.ndim == 3 and 1 <= a.shape[2] <= 4:
        values = np.ascontiguousarray(a, dtype=np.float64)
        out = np.empty(a.shape[:2], np.float32)
        _check(_lib.schlieren_photograph_grey(values.ctypes.data_as(ctypes.POINTER(ctypes.c_double)),
                                              out.size, a.shape[2], _fp(out)))
        return out
    if a.ndim != 2:
        raise ArgumentError("%s has shape %s: give a 2D array (rows, columns) of grey levels or "
                            "(rows, columns, 1 to 4) of grey, grey and alpha, RGB or RGBA" % (name, a.shape))
    return np.ascontiguousarray(a, dtype=np.float32)


def photograph_blend(film, difference, weight):
    """The blend the photograph filters show: film + weight * difference (float32; the engine's
    schlieren_photograph_blend), `film` and `difference` float32 arrays of one shape."""
    f = np.ascontiguousarray(film, dtype=np.float32)
    d = np.ascontiguousarray(difference, dtype=np.float32)
    if f.shape != d.shape:
        raise ArgumentError("film %s and difference %s differ in shape" % (f.shape, d.shape))
    out = np.empty(f.shape, np.float32)
    _check(_lib.schlieren_photograph_blend(float(weight), _fp(f), _fp(d), f.size, _fp(out)))
    return out


def photograph(film, film_origin, pixel_size, photo, settings=None):
    """A photograph beside the film (schlieren_photograph): `film` the traced intensity as
    (ny, nx) (row 0 at the film's origin, as image_to_numpy gives it), `film_origin` the world
    position of its pixel (0, 0), `pixel_size` world units a pixel; `photo` grey (h, w) or colour
    (h, w, 3|4), row 0 at the bottom (VTK's readers' order; flip an array read top-first).
    `settings`: a dict of the settings (PhotoPixelSize, PointPairs, Refine, ...). Returns the report
    (a dict: match, reason, scale, rotation, shift, score, threshold, gamma, lines, ...) with the
    images on the film's grid as (ny, nx) float32 under "images"."""
    f = grey(film, "film")
    p = grey(photo, "photo")
    try:
        origin = [float(x) for x in film_origin]
    except (TypeError, ValueError):
        raise ArgumentTypeError("film_origin is %r: give two numbers" % (film_origin,))
    if len(origin) != 2:
        raise ArgumentError("film_origin is %r: give two numbers (x, y)" % (film_origin,))
    text = "\n".join("%s=%s" % (k, _value_text(v)) for k, v in (settings or {}).items())
    ny, nx = f.shape
    out = {k: np.empty(f.shape, np.float32) for k in PHOTOGRAPH_IMAGES}
    report = ctypes.c_char_p()
    _check(_lib.schlieren_photograph(
        text.encode(), (ctypes.c_int * 2)(nx, ny), (ctypes.c_double * 2)(*origin), float(pixel_size),
        _fp(f), f.size, (ctypes.c_int * 2)(p.shape[1], p.shape[0]), _fp(p), p.size, f.size,
        *[_fp(out[k]) for k in PHOTOGRAPH_IMAGES], ctypes.byref(report)))
    text = _text(report.value)
    r = json.loads(text)
    r["images"] = out
    r["json"] = text  # the engine's report as it wrote it (the filters' field data photograph_report)
    return r


def synthetic_photograph(film, scale=1.0, rotation=0.0, shift=(0.0, 0.0), size=None, gamma=1.0,
                         vignetting=0.0, blur=0.0, photons=0.0, gain=0.8, seed=5):
    """A "photograph" of a film ((ny, nx), row 0 at the bottom) for tests and examples: the film's
    pixel (i, j) lands at scale R(rotation, degrees) ((i, j) - centre) + the photograph's centre +
    shift (photograph pixels), the convention of schlieren_photograph's transform; the grey is
    gain (1 - vignetting r^2) I^gamma (r: 1 at the corners; outside the film the film's median),
    blurred by a Gaussian of `blur` pixels and with Poisson noise of `photons` a unit of grey
    (0: none). `size` (rows, columns), default the film's. float32 (rows, columns)."""
    f = np.asarray(film, dtype=np.float64)
    ny, nx = f.shape
    h, w = size or f.shape
    th = np.radians(rotation)
    v, u = np.mgrid[0:h, 0:w].astype(np.float64)
    a, b = u - 0.5 * (w - 1) - shift[0], v - 0.5 * (h - 1) - shift[1]
    x = (np.cos(th) * a + np.sin(th) * b) / scale + 0.5 * (nx - 1)
    y = (-np.sin(th) * a + np.cos(th) * b) / scale + 0.5 * (ny - 1)
    inside = (x >= 0) & (y >= 0) & (x <= nx - 1) & (y <= ny - 1)
    xi, yi = np.clip(x.astype(int), 0, nx - 2), np.clip(y.astype(int), 0, ny - 2)
    fx, fy = np.clip(x - xi, 0, 1), np.clip(y - yi, 0, 1)
    i = ((1 - fy) * ((1 - fx) * f[yi, xi] + fx * f[yi, xi + 1]) +
         fy * ((1 - fx) * f[yi + 1, xi] + fx * f[yi + 1, xi + 1]))
    i = np.where(inside, i, np.median(f))
    r2 = ((u - 0.5 * w) ** 2 + (v - 0.5 * h) ** 2) / (0.25 * (w * w + h * h))
    p = gain * (1 - vignetting * r2) * np.clip(i, 0, None) ** gamma
    if blur > 0:
        k = np.arange(-int(np.ceil(3 * blur)), int(np.ceil(3 * blur)) + 1)
        k = np.exp(-0.5 * (k / blur) ** 2)
        k /= k.sum()
        pad = len(k) // 2
        p = np.pad(p, pad, mode="edge")
        p = np.apply_along_axis(lambda r: np.convolve(r, k, mode="valid"), 1, p)
        p = np.apply_along_axis(lambda c: np.convolve(c, k, mode="valid"), 0, p)
    if photons > 0:
        p = np.random.default_rng(seed).poisson(p * photons) / photons
    return p.astype(np.float32)


# ---- the ranks (MPI processes) through the C interface's schlieren_parallel (docs/PARALLEL.md)

_reduce_fn = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int64,
                              ctypes.c_int, ctypes.c_void_p)
_broadcast_fn = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_int64, ctypes.c_int,
                                 ctypes.c_void_p)
_allgather_fn = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_int64, ctypes.c_void_p,
                                 ctypes.c_void_p)


class _ParallelStruct(ctypes.Structure):
    _fields_ = [("size", ctypes.c_int), ("rank", ctypes.c_int), ("user", ctypes.c_void_p),
                ("reduce", _reduce_fn), ("broadcast", _broadcast_fn),
                ("allgather", _allgather_fn)]


_parallel_p = ctypes.POINTER(_ParallelStruct)
_sig("schlieren_parallel_failure", ctypes.c_int, _parallel_p, ctypes.c_char_p,
     ctypes.POINTER(ctypes.c_char_p))
_sig("schlieren_session_set_piece", ctypes.c_int, ctypes.c_void_p, ctypes.c_int * 6,
     ctypes.c_int * 6, _c_double3, _c_double3, _f32p, _i64, _u8p, _i64, _u8p, _i64,
     ctypes.c_double, ctypes.c_int)
_sig("schlieren_session_trace_parallel", ctypes.c_int, ctypes.c_void_p, _parallel_p,
     _progress_fn, ctypes.c_void_p)
_sig("schlieren_numerical_pieces", ctypes.c_int, ctypes.c_char_p, _c_int3, _c_double3,
     _c_double3, _c_int3, _c_int3, _f32p, _i64, _u8p, _i64, _u8p, _i64, ctypes.c_int * 2,
     ctypes.c_double * 2, ctypes.POINTER(ctypes.c_double), ctypes.c_int64, _f32p, _f32p, _u8p,
     ctypes.POINTER(ctypes.c_double), _progress_fn, ctypes.c_void_p, _parallel_p,
     ctypes.POINTER(ctypes.c_int))


class Ranks:
    """The ranks of a job as the engine's collectives take them (schlieren_parallel): `comm` has
    rank, size and the three collectives on NumPy arrays, allreduce(float64 array, op) -> array
    (op "sum", "min", "max"), broadcast(uint8 array, root) -> array and allgather(uint8 array) ->
    (size, n) array, each the same count on every rank. controller_ranks() makes one of ParaView's
    or VTK's vtkMultiProcessController. An exception in a collective fails the engine's call with
    its message (the job's other ranks are then left in the collective: an MPI error ends the job
    as it would in C). Where `comm` has a `guard` (controller_ranks() on MPI with mpi4py:
    _MpiGuard), every collective waits first until every rank has reached it, at most
    SCHLIEREN_MPI_TIMEOUT seconds (OutOfStep past it), as the C++ plugin's do."""

    def __init__(self, comm):
        self.rank, self.size = int(comm.rank), int(comm.size)
        # every collective, ours and the engine's, entered only once every rank is there (where
        # `comm` has a guard: _ControllerComm on MPI with mpi4py), as the C++ plugin's
        self._guard = getattr(comm, "guard", None)
        self.comm = comm if self._guard is None else _GuardedComm(comm, self._arrive)
        # the filter's pass running (begin()): [who, its collectives so far, the guard's error
        # where it gave up]
        self._pass = None
        self._raised = []

        def guarded(f):
            def call(*args):
                try:
                    f(*args)
                    return 0
                except BaseException as e:  # noqa: BLE001 -- said by the engine's error
                    self._raised.append(e)
                    return 1
            return call

        def view(p, count, dtype=np.uint8):
            return np.ctypeslib.as_array((ctypes.c_ubyte * (int(count) * np.dtype(dtype)
                                                            .itemsize)).from_address(p)) \
                .view(dtype)

        comm = self.comm

        def reduce(src, dst, count, op, _user):
            view(dst, count, np.float64)[:] = comm.allreduce(
                view(src, count, np.float64).copy(), ("sum", "min", "max")[op])

        def broadcast(data, count, root, _user):
            buf = view(data, count)
            buf[:] = comm.broadcast(buf.copy(), int(root))

        def allgather(mine, count, out, _user):
            view(out, count * self.size)[:] = np.asarray(
                comm.allgather(view(mine, count).copy())).reshape(-1)
        # kept: the engine calls them for as long as this object lives
        self._callbacks = (_reduce_fn(guarded(reduce)), _broadcast_fn(guarded(broadcast)),
                           _allgather_fn(guarded(allgather)))
        self._struct = _ParallelStruct(self.size, self.rank, None, *self._callbacks)

    def pointer(self):
        """The schlieren_parallel for a C call (valid while this object lives)."""
        self._raised.clear()
        return ctypes.pointer(self._struct)

    def begin(self, who):
        """A filter's pass starts (`who`: "RefractiveIndex's data pass"): its collectives are
        numbered from 1 in the guard's step names ("RefractiveIndex's collective 1 (an
        all-gather, its data pass)"), the same on every rank that runs the same pass. Returns what
        end() takes back (a pass may run inside another: an upstream updated by RequestInformation).
        """
        kept, self._pass = self._pass, [who, 0, None]
        return kept

    def end(self, kept):
        self._pass = kept

    def _arrive(self, what):
        """Before a collective: every rank there at the same step, or OutOfStep (the guard)."""
        if self._pass is None:
            self._guard.arrive("a collective of Schlieren's (%s)" % what)
            return
        if self._pass[2] is not None:
            # this pass gave up (every rank that came did): no second wait (an agreement on the
            # failure, the engine's own), the same error at once
            raise self._pass[2]
        self._pass[1] += 1
        who, _, when = self._pass[0].partition("'s ")
        try:
            self._guard.arrive("%s's collective %d (%s%s)" % (
                who, self._pass[1], what, ", its " + when if when else ""))
        except OutOfStep as e:
            self._pass[2] = e
            raise

    def error(self):
        """The engine's last error, with what a collective raised where one did (the guard's
        OutOfStep itself: its words are the error)."""
        if self._raised and isinstance(self._raised[0], OutOfStep):
            return self._raised[0]
        text = _text(_lib.schlieren_last_error())
        if self._raised:
            text += " (%s: %s)" % (type(self._raised[0]).__name__, self._raised[0])
        return EngineError(text)

    def failure(self, mine, step=""):
        """Parallel::Failure (collective): "" where no rank failed, else the same failure on every
        rank (the lowest failing rank's message on it, "another rank (r) failed: ..." on the
        others). With `step` (what the caller is about to do, "SchlierenImage's trace"), first
        whether every rank is at the same step: where not (an update that ran on some ranks only
        put them out of step) every rank gets the same message naming each rank's step, and no
        collective of the step runs (the C++ plugin's guard, as its words say)."""
        if step:
            names = self.comm.allgather(np.frombuffer(step.encode()[:255].ljust(256, b"\0"),
                                                      np.uint8))
            steps = [bytes(np.asarray(n, np.uint8)).rstrip(b"\0").decode("utf-8", "replace")
                     for n in names]
            if any(other != steps[0] for other in steps):
                return ("the ranks are at different collectives: %s (an upstream failure on some "
                        "ranks put them out of step)" % ", ".join(
                            "rank %d at %s" % (r, at) for r, at in enumerate(steps)))
        agreed = ctypes.c_char_p()
        if _lib.schlieren_parallel_failure(self.pointer(), (mine or "").encode(),
                                           ctypes.byref(agreed)):
            raise self.error()
        return _text(agreed.value)


class _ControllerComm:
    """A vtkMultiProcessController's collectives on NumPy arrays (for Ranks)."""

    def __init__(self, controller):
        from vtkmodules.vtkParallelCore import vtkCommunicator
        self.controller = controller
        self.rank = controller.GetLocalProcessId()
        self.size = controller.GetNumberOfProcesses()
        self.ops = {"sum": vtkCommunicator.SUM_OP, "min": vtkCommunicator.MIN_OP,
                    "max": vtkCommunicator.MAX_OP}
        self.guard = _MpiGuard.of(controller)

    @staticmethod
    def _vtk(a):
        from vtkmodules.util import numpy_support
        return numpy_support.numpy_to_vtk(np.ascontiguousarray(a), deep=1)

    @staticmethod
    def _np(a):
        from vtkmodules.util import numpy_support
        return numpy_support.vtk_to_numpy(a)

    def allreduce(self, values, op):
        from vtkmodules.vtkCommonCore import vtkDoubleArray
        out = vtkDoubleArray()
        out.SetNumberOfTuples(len(values))
        if not self.controller.AllReduce(self._vtk(values), out, self.ops[op]):
            raise RuntimeError("the controller's all-reduce failed")
        return self._np(out).copy()

    def broadcast(self, data, root):
        a = self._vtk(data)
        if not self.controller.Broadcast(a, root):
            raise RuntimeError("the controller's broadcast failed")
        return self._np(a).copy()

    def allgather(self, data):
        from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
        out = vtkUnsignedCharArray()
        out.SetNumberOfTuples(len(data) * self.size)
        if not self.controller.AllGather(self._vtk(data), out):
            raise RuntimeError("the controller's all-gather failed")
        return self._np(out).reshape(self.size, len(data)).copy()


class OutOfStep(RuntimeError):
    """The guard gave up: some rank did not reach a collective in time, or the ranks reached
    different ones (the message names them, in the C++ plugin's words). Not an EngineError: no
    handler of a filter's failure on some ranks may take it for one and agree on it (a collective:
    it would wait again); the filter fails with its words (algorithms' ProcessRequest)."""


class _GuardedComm:
    """A comm whose collectives first call arrive(what) (Ranks' guard)."""

    def __init__(self, comm, arrive):
        self._comm, self._arrive = comm, arrive
        self.rank, self.size = comm.rank, comm.size

    def allreduce(self, values, op):
        self._arrive("an all-reduce")
        return self._comm.allreduce(values, op)

    def broadcast(self, data, root):
        self._arrive("a broadcast")
        return self._comm.broadcast(data, root)

    def allgather(self, data):
        self._arrive("an all-gather")
        return self._comm.allgather(data)


class _MpiGuard:
    """The C++ plugin's collective guard (Filters/SchlierenController.cxx, docs/PARALLEL.md) for
    the Python plugin, over mpi4py on the controller's own MPI communicator with a tag of its own:
    before each collective every rank tells rank 0 that it is there (ARRIVED, with the step's
    name) and waits for GO; rank 0 answers GO once every rank has come to the same step, or ABORT
    with the error (naming the ranks that did not come) after SCHLIEREN_MPI_TIMEOUT seconds. Only
    non-blocking point-to-point messages: a rank that never comes (its upstream failed, so the
    pipeline never ran our filter there) leaves no collective half done. Each message carries its
    sender's count of arrivals (its epoch), so an answer to an earlier, given-up arrival is not
    taken for this one's. A rank that hears nothing withdraws (WITHDRAWN) and waits a little more
    for rank 0's last word."""

    TAG = 51209  # the C++ guard's is 51208: the two plugins' messages never meet
    ARRIVED, WITHDRAWN, GO, ABORT = 1, 2, 3, 4
    SIZE, TEXT = 512, 496
    WITHDRAWN_REPLY = "withdrawn"
    _kept = {}

    @classmethod
    def of(cls, controller):
        """The guard of `controller`'s communicator; None where it is not MPI or mpi4py is not
        importable (pip VTK without it: no guard, as before)."""
        try:
            from vtkmodules.vtkParallelMPI import vtkMPICommunicator
            from vtkmodules.vtkParallelMPI4Py import vtkMPI4PyCommunicator
            communicator = controller.GetCommunicator()
            if not isinstance(communicator, vtkMPICommunicator):
                return None
            import mpi4py
            if "mpi4py.MPI" not in sys.modules:
                # VTK has initialised MPI and finalises it: mpi4py must do neither
                mpi4py.rc.initialize = False
                mpi4py.rc.finalize = False
            from mpi4py import MPI
            if not MPI.Is_initialized() or MPI.Is_finalized():
                return None
            comm = vtkMPI4PyCommunicator.ConvertToPython(communicator)
        except Exception:  # noqa: BLE001 -- no mpi4py, or one that does not load: no guard
            return None
        if comm is None or comm.size <= 1:
            return None
        key = communicator.__this__
        if key not in cls._kept:
            cls._kept[key] = cls(comm, MPI)
        return cls._kept[key]

    def __init__(self, comm, mpi):
        self.comm, self.mpi = comm, mpi
        self.rank, self.size = comm.rank, comm.size
        self.epoch = 0                    # this rank's arrivals so far
        self.live = [0] * self.size       # rank 0: each rank's unanswered arrival, or 0
        self.at = [""] * self.size        # ... and the step it arrived at
        self.out = []                     # sends in flight (request, buffer)

    def _send(self, to, kind, epoch, text):
        b = text.encode("utf-8", "replace")[:self.TEXT - 1]
        buf = bytearray(self.SIZE)
        struct.pack_into("<qq", buf, 0, kind, epoch)
        buf[16:16 + len(b)] = b
        self.out.append((self.comm.Isend([buf, self.mpi.BYTE], dest=to, tag=self.TAG), buf))

    def _poll(self, source):
        """(kind, epoch, text) of the next guard message from `source`, or None."""
        if not self.comm.Iprobe(source=source, tag=self.TAG):
            return None
        buf = bytearray(self.SIZE)
        self.comm.Recv([buf, self.mpi.BYTE], source=source, tag=self.TAG)
        kind, epoch = struct.unpack_from("<qq", buf, 0)
        return kind, epoch, bytes(buf[16:]).split(b"\0", 1)[0].decode("utf-8", "replace")

    @staticmethod
    def _pause(polls):
        """Short at first (the other ranks are usually there), then longer (a sleep)."""
        if polls < 200:
            time.sleep(0)
        else:
            time.sleep(1e-4 if polls < 2000 else 2e-3)

    def arrive(self, step):
        """Returns once every rank is at `step`; OutOfStep (on every rank that came) where some
        rank did not come within the timeout or the ranks are at different steps."""
        timeout, abort_job = mpi_options()
        self.out = [(r, b) for r, b in self.out if not r.Test()]  # sends MPI is done with
        try:
            if self.rank == 0:
                self._coordinate(step, timeout)
            else:
                self._follow(step, timeout)
        except OutOfStep as e:
            if abort_job:
                # the ranks are out of step: end the job rather than meet a rank held elsewhere
                from vtkmodules.vtkCommonCore import vtkOutputWindow
                vtkOutputWindow.GetInstance().DisplayErrorText(
                    "Schlieren, rank %d: %s SCHLIEREN_MPI_ABORT=1: the MPI job is aborted.\n"
                    % (self.rank, e))
                self.comm.Abort(1)
            raise

    def _follow(self, step, timeout):
        self.epoch += 1
        epoch = self.epoch
        self._send(0, self.ARRIVED, epoch, step)
        # rank 0 answers within `timeout` of its own arrival; a rank that hears nothing a while
        # after that gives up, then waits as long again for rank 0's last word
        grace = min(10.0, max(1.0, 0.25 * timeout))
        gave_up = OutOfStep("rank 0 did not reach %s within %s: its upstream probably failed "
                            "(see its error). SCHLIEREN_MPI_TIMEOUT sets the wait."
                            % (step, _seconds(timeout)))
        t0, withdrawn, polls = time.monotonic(), False, 0
        while True:
            m = self._poll(0)
            while m is not None:
                kind, their_epoch, text = m
                if their_epoch == epoch:
                    if kind == self.GO:
                        return
                    if kind == self.ABORT:
                        raise gave_up if text == self.WITHDRAWN_REPLY else OutOfStep(text)
                m = self._poll(0)  # (an answer to an earlier arrival, given up: dropped)
            waited = time.monotonic() - t0
            if not withdrawn and waited > timeout + grace:
                self._send(0, self.WITHDRAWN, epoch, step)
                withdrawn = True
            elif withdrawn and waited > timeout + 2 * grace:
                raise gave_up
            polls += 1
            self._pause(polls)

    def _coordinate(self, step, timeout):
        self.epoch += 1
        live, at = self.live, self.at

        def abort_all(why):
            for r in range(1, self.size):
                if live[r]:
                    self._send(r, self.ABORT, live[r], why)
                    live[r] = 0
            raise OutOfStep(why)
        t0, first, polls = time.monotonic(), True, 0
        while True:
            for r in range(1, self.size):
                m = self._poll(r)
                while m is not None:
                    kind, epoch, text = m
                    if kind == self.ARRIVED:
                        live[r], at[r] = epoch, text
                    elif kind == self.WITHDRAWN:
                        self._send(r, self.ABORT, epoch, self.WITHDRAWN_REPLY)
                        if live[r] == epoch:
                            live[r] = 0
                            # given up while this round waited: it will not come back to this step
                            if not first:
                                abort_all(
                                    "rank %d stopped waiting at %s before rank 0 reached %s: the "
                                    "ranks are out of step (an upstream failure or a rank slower "
                                    "than SCHLIEREN_MPI_TIMEOUT = %s)"
                                    % (r, text, step, _seconds(timeout)))
                    m = self._poll(r)
            first = False
            missing = [r for r in range(1, self.size) if not live[r]]
            if not missing:
                for r in range(1, self.size):
                    if at[r] != step:
                        abort_all("the ranks are at different collectives: rank 0 at %s, rank %d "
                                  "at %s (an upstream failure on some ranks put them out of step)"
                                  % (step, r, at[r]))
                for r in range(1, self.size):
                    self._send(r, self.GO, live[r], step)
                    live[r] = 0
                return
            if time.monotonic() - t0 > timeout:
                abort_all("%s did not reach %s within %s: %s. SCHLIEREN_MPI_TIMEOUT sets the wait."
                          % (_rank_list(missing), step, _seconds(timeout),
                             "its upstream probably failed (see its error)" if len(missing) == 1
                             else "their upstream probably failed (see their errors)"))
            polls += 1
            self._pause(polls)


def _seconds(s):
    """Seconds as the C++ guard writes them (a stream's default: 6 significant digits)."""
    return "%g s" % s


def _rank_list(ranks):
    """"rank 2", "ranks 1, 3" (the C++ guard's RankList)."""
    return ("rank " if len(ranks) == 1 else "ranks ") + ", ".join(str(r) for r in ranks)


def controller_ranks(controller=None):
    """The ranks of `controller` (None: VTK's global controller, which pvbatch and pvserver under
    MPI set) as a Ranks, or None where it runs one process (or VTK has no parallel module)."""
    if controller is None:
        try:
            from vtkmodules.vtkParallelCore import vtkMultiProcessController
        except ImportError:
            return None
        controller = vtkMultiProcessController.GetGlobalController()
    if controller is None or controller.GetNumberOfProcesses() <= 1:
        return None
    key = controller.__this__
    kept = _kept_ranks.get(key)
    if kept is None:
        kept = _kept_ranks[key] = Ranks(_ControllerComm(controller))
    return kept


_kept_ranks = {}


def _piece_ranks(ranks):
    return None if ranks is None else ranks.pointer()


def numerical_pieces(settings, whole_dims, origin, spacing, offset, piece_dims, values=None,
                     solid=None, excluded=None, ranks=None, progress=None):
    """NumericalSchlieren on this rank's piece of a volume split over `ranks` (collective;
    schlieren_numerical_pieces): the whole grid's dims, first point and spacing, this piece's
    offset and points (a 0: none, values None). Rank 0 gets numerical()'s dict; the others None."""
    text = "\n".join("%s=%s" % (k, _value_text(v)) for k, v in settings.items()).encode()
    size, film_origin, pixel = numerical(settings, whole_dims, origin, spacing)
    empty = min(int(d) for d in piece_dims) == 0
    a = None if empty else _point_array(values, "values", piece_dims, np.float32)
    s = None if empty else _point_array(solid, "solid", piece_dims, np.uint8, optional=True,
                                        mask=True)
    e = None if empty else _point_array(excluded, "excluded", piece_dims, np.uint8,
                                        optional=True, mask=True)
    n = size[0] * size[1]
    out = {"intensity": np.empty(n, np.float32), "numerical_gradient": np.empty(n, np.float32),
           "blocked": np.empty(n, np.uint8)}
    ml, has = (ctypes.c_double * 2)(), ctypes.c_int(0)
    size, film_origin = (ctypes.c_int * 2)(), (ctypes.c_double * 2)()
    pixel = ctypes.c_double()
    rc = _with_progress(progress, lambda callback, user: _lib.schlieren_numerical_pieces(
        text, _c_int3(*[int(d) for d in whole_dims]), _c_double3(*origin), _c_double3(*spacing),
        _c_int3(*[int(o) for o in offset]), _c_int3(*[int(d) for d in piece_dims]), _fp(a),
        _size(a), _up(s), _size(s), _up(e), _size(e), size, film_origin, ctypes.byref(pixel), n,
        _fp(out["intensity"]), _fp(out["numerical_gradient"]), _up(out["blocked"]), ml,
        callback, user, _piece_ranks(ranks), ctypes.byref(has)))
    if rc:
        raise ranks.error() if ranks is not None else EngineError(
            _text(_lib.schlieren_last_error()))
    if not has.value:
        return None
    out.update(size=list(size), origin=list(film_origin), pixel=pixel.value, maximum=ml[0],
               largest=ml[1])
    return out


def index_field_piece(settings, grid_extent, out_extent, whole_extent, spacing, arrays,
                      valid=None, active_scalars=-1, cell_arrays=(), notes=(), ranks=None,
                      body=None):
    """index_field() on this rank's piece of an image split over `ranks` (collective;
    schlieren_index_field_piece): the arrays at the points of `grid_extent` (the requested
    `out_extent` grown by a point on every side within `whole_extent`). Returns index_field()'s
    tuple on the grid's points."""
    return index_field(settings, None, spacing, arrays, valid, active_scalars, cell_arrays,
                       notes, body=body, extents=(grid_extent, out_extent, whole_extent),
                       ranks=ranks)
