# SPDX-License-Identifier: BSD-3-Clause
"""The engine's C interface (schlieren_c.h) through ctypes, on NumPy arrays.

The shared library is looked for in this order: $SCHLIEREN_ENGINE_LIBRARY, the package's own
folder (a wheel), then the system's loader path. Nothing here needs VTK.
"""
import ctypes
import json
import os
import sys

import numpy as np

API_VERSION = 1

_c_int3 = ctypes.c_int * 3
_c_double3 = ctypes.c_double * 3
_f32p = ctypes.POINTER(ctypes.c_float)
_u8p = ctypes.POINTER(ctypes.c_ubyte)


class EngineError(RuntimeError):
    """An error the engine reported (the message says what and what to do)."""


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
_sig("schlieren_session_set_volume", ctypes.c_int, ctypes.c_void_p, _c_int3, _c_double3,
     _c_double3, _f32p, _u8p, _u8p, ctypes.c_double, ctypes.c_int)
_sig("schlieren_session_trace", ctypes.c_int, ctypes.c_void_p)
_sig("schlieren_session_array", _f32p, ctypes.c_void_p, ctypes.c_char_p,
     ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int64))
_sig("schlieren_session_film", ctypes.c_int, ctypes.c_void_p, ctypes.c_int * 2,
     ctypes.c_double * 2, ctypes.POINTER(ctypes.c_double))
_sig("schlieren_session_plan_film", ctypes.c_int, ctypes.c_void_p, _c_int3, _c_double3,
     _c_double3, ctypes.c_int * 2, ctypes.c_double * 2, ctypes.POINTER(ctypes.c_double))
_sig("schlieren_session_report", ctypes.c_char_p, ctypes.c_void_p)
_sig("schlieren_fill_scene", ctypes.c_int, ctypes.c_char_p, _c_int3, _c_double3, _c_double3,
     _f32p, _f32p, _f32p, _u8p)
_sig("schlieren_octree_levels", ctypes.c_int, _c_int3, _f32p, ctypes.c_double, ctypes.c_int,
     _u8p, ctypes.POINTER(ctypes.c_double))
_sig("schlieren_gradient", ctypes.c_int, _c_int3, _c_double3, _f32p, _f32p)
_sig("schlieren_field_index", ctypes.c_int, ctypes.c_char_p, _f32p, ctypes.c_int64, ctypes.c_int,
     ctypes.c_double, ctypes.c_char_p, _f32p, ctypes.POINTER(ctypes.c_char_p))

_sig("schlieren_numerical", ctypes.c_int, ctypes.c_char_p, _c_int3, _c_double3, _c_double3, _f32p,
     _u8p, _u8p, ctypes.c_int * 2, ctypes.c_double * 2, ctypes.POINTER(ctypes.c_double),
     ctypes.c_int64, _f32p, _f32p, _u8p, ctypes.POINTER(ctypes.c_double))
_sig("schlieren_extend_into_invalid", ctypes.c_int, _c_int3, _u8p, _f32p,
     ctypes.POINTER(ctypes.c_int64))
_sig("schlieren_automatic_dimensions", ctypes.c_int, ctypes.c_double * 6, ctypes.c_int, _c_int3)

if _lib.schlieren_api_version() != API_VERSION:
    raise ImportError("libschlieren_engine has C API version %d; this package needs %d"
                      % (_lib.schlieren_api_version(), API_VERSION))


def _text(b):
    return b.decode("utf-8") if b is not None else ""


def _floats(a):
    a = np.ascontiguousarray(a, dtype=np.float32)
    return a, a.ctypes.data_as(_f32p)


def _bytes(a):
    if a is None:
        return None, None
    a = np.ascontiguousarray(a, dtype=np.uint8)
    return a, a.ctypes.data_as(_u8p)


def _check(rc):
    if rc:
        raise EngineError(_text(_lib.schlieren_last_error()))


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
    return (_c_int3(*[int(d) for d in dims]), _c_double3(*[float(o) for o in origin]),
            _c_double3(*[float(s) for s in spacing]))


def fill_scene(settings, dims, origin, spacing, body=False):
    """RefractiveScene's scene on a grid: a dict of point arrays (x fastest), float32 n_minus_1
    and density (mixture_fraction for HeliumPlume, solid where a Body is set)."""
    count = int(np.prod(dims))
    out = {"n_minus_1": np.empty(count, np.float32), "density": np.empty(count, np.float32)}
    plume = settings.get("Scene") == "HeliumPlume"
    if plume:
        out["mixture_fraction"] = np.empty(count, np.float32)
    has_body = settings.get("Body", "None") != "None"
    if has_body:
        out["solid"] = np.zeros(count, np.uint8)
    text = "\n".join("%s=%s" % (k, _value_text(v)) for k, v in settings.items())
    _check(_lib.schlieren_fill_scene(
        text.encode(), *_grid(dims, origin, spacing), out["n_minus_1"].ctypes.data_as(_f32p),
        out["density"].ctypes.data_as(_f32p),
        out["mixture_fraction"].ctypes.data_as(_f32p) if plume else None,
        out["solid"].ctypes.data_as(_u8p) if has_body else None))
    return out


def numerical(settings, dims, origin, spacing, values=None, solid=None, excluded=None):
    """NumericalSchlieren on a grid: without `values` the film only, (size, origin, pixel);
    else a dict of intensity, numerical_gradient (float32), blocked (uint8) and the film, with
    maximum (the qmax used) and largest (the largest q)."""
    text = "\n".join("%s=%s" % (k, _value_text(v)) for k, v in settings.items()).encode()
    size, film_origin, pixel = (ctypes.c_int * 2)(), (ctypes.c_double * 2)(), ctypes.c_double()
    if values is None:
        _check(_lib.schlieren_numerical(text, *_grid(dims, origin, spacing), None, None, None, size,
                                        film_origin, ctypes.byref(pixel), 0, None, None, None,
                                        None))
        return list(size), list(film_origin), pixel.value
    a, p = _floats(values)
    s_keep, s_p = _bytes(solid)
    e_keep, e_p = _bytes(excluded)
    _check(_lib.schlieren_numerical(text, *_grid(dims, origin, spacing), None, None, None, size,
                                    film_origin, ctypes.byref(pixel), 0, None, None, None, None))
    n = size[0] * size[1]
    out = {"intensity": np.empty(n, np.float32), "numerical_gradient": np.empty(n, np.float32),
           "blocked": np.empty(n, np.uint8)}
    ml = (ctypes.c_double * 2)()
    _check(_lib.schlieren_numerical(text, *_grid(dims, origin, spacing), p, s_p, e_p, size,
                                    film_origin, ctypes.byref(pixel), n,
                                    out["intensity"].ctypes.data_as(_f32p),
                                    out["numerical_gradient"].ctypes.data_as(_f32p),
                                    out["blocked"].ctypes.data_as(_u8p), ml))
    out.update(size=list(size), origin=list(film_origin), pixel=pixel.value, maximum=ml[0],
               largest=ml[1])
    return out


def octree_levels(dims, n_minus_1, tolerance, max_level=7):
    """RefractionOctree's level per point, and the fraction of cells at level >= 1."""
    a, p = _floats(n_minus_1)
    levels = np.zeros(a.size, np.uint8)
    fraction = ctypes.c_double(0)
    _check(_lib.schlieren_octree_levels(_c_int3(*dims), p, float(tolerance), int(max_level),
                                        levels.ctypes.data_as(_u8p), ctypes.byref(fraction)))
    return levels, fraction.value


def gradient(dims, spacing, n_minus_1):
    """grad n in world units, (points, 3) float32."""
    a, p = _floats(n_minus_1)
    g = np.empty((a.size, 3), np.float32)
    _check(_lib.schlieren_gradient(_c_int3(*dims), _c_double3(*spacing), p,
                                   g.ctypes.data_as(_f32p)))
    return g


def field_index(model, values, index_is_n=False, density_reference=1.0, gas=None):
    """RefractiveIndex's Passthrough or GladstoneDale on an array: (n - 1 float32, warnings)."""
    a, p = _floats(values)
    out = np.empty(a.size, np.float32)
    report = ctypes.c_char_p()
    _check(_lib.schlieren_field_index(model.encode(), p, a.size, int(bool(index_is_n)),
                                      float(density_reference), gas.encode() if gas else None,
                                      out.ctypes.data_as(_f32p), ctypes.byref(report)))
    return out, [w for w in _text(report.value).split("\n") if w]


def extend_into_invalid(dims, valid, n_minus_1):
    """Fills n - 1 (float32, changed in place) where valid == 0 by the engine's smooth
    continuation of the flow; returns how many points were filled."""
    if n_minus_1.dtype != np.float32 or not n_minus_1.flags.c_contiguous:
        raise TypeError("n_minus_1 must be a contiguous float32 array (it is filled in place)")
    v, vp = _bytes(valid)
    filled = ctypes.c_int64(0)
    _check(_lib.schlieren_extend_into_invalid(_c_int3(*dims), vp,
                                              n_minus_1.ctypes.data_as(_f32p),
                                              ctypes.byref(filled)))
    return filled.value


def automatic_dimensions(bounds, longest):
    """RefractiveIndex's automatic sampling dimensions of a box."""
    dims = _c_int3()
    _check(_lib.schlieren_automatic_dimensions((ctypes.c_double * 6)(*bounds), int(longest), dims))
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
    """A trace session (schlieren_c.h): the volume, the settings, repeated traces."""

    def __init__(self):
        self._s = _lib.schlieren_session_new()
        if not self._s:
            raise MemoryError("schlieren_session_new failed")

    def __del__(self):
        s, self._s = getattr(self, "_s", None), None
        if s and _lib is not None:
            _lib.schlieren_session_free(s)

    def _error(self):
        return EngineError(_text(_lib.schlieren_session_error(self._s)))

    def set(self, name, value):
        if _lib.schlieren_session_set(self._s, name.encode(), _value_text(value).encode()):
            raise self._error()

    def get(self, name):
        v = _lib.schlieren_session_get(self._s, name.encode())
        if v is None:
            raise self._error() if _text(_lib.schlieren_session_error(self._s)) else \
                KeyError(name)
        return _text(v)

    def set_volume(self, dims, origin, spacing, n_minus_1, solid=None, levels=None,
                   level_tolerance=-1.0, max_level=7):
        a, p = _floats(n_minus_1)
        if a.size != int(np.prod(dims)):
            raise EngineError("n_minus_1 has %d values for a grid of %d points"
                              % (a.size, int(np.prod(dims))))
        s, sp = _bytes(solid)
        lv, lp = _bytes(levels)
        if _lib.schlieren_session_set_volume(self._s, *_grid(dims, origin, spacing), p, sp, lp,
                                             float(level_tolerance), int(max_level)):
            raise self._error()

    def trace(self):
        """Traces; returns the report (dict: field_data, notes, error). Raises EngineError."""
        rc = _lib.schlieren_session_trace(self._s)
        report = json.loads(_text(_lib.schlieren_session_report(self._s)))
        if rc:
            err = self._error()
            err.report = report
            raise err
        return report

    def array(self, name):
        """An image array of the last trace, (pixels, components) float32 copy, or None."""
        comps, pixels = ctypes.c_int(0), ctypes.c_int64(0)
        p = _lib.schlieren_session_array(self._s, name.encode(), ctypes.byref(comps),
                                         ctypes.byref(pixels))
        if not p:
            return None
        a = np.ctypeslib.as_array(p, shape=(pixels.value * comps.value,)).copy()
        return a.reshape(pixels.value, comps.value) if comps.value > 1 else a

    def plan_film(self, dims, origin, spacing):
        """The film a trace of this grid would make: (size, origin, pixel size)."""
        size, o, px = (ctypes.c_int * 2)(), (ctypes.c_double * 2)(), ctypes.c_double()
        if _lib.schlieren_session_plan_film(self._s, *_grid(dims, origin, spacing), size, o,
                                            ctypes.byref(px)):
            raise self._error()
        return list(size), list(o), px.value

    def film(self):
        """(size [nx, ny], origin of pixel (0, 0) [x, y], pixel size) of the last trace."""
        size, origin, px = (ctypes.c_int * 2)(), (ctypes.c_double * 2)(), ctypes.c_double()
        if _lib.schlieren_session_film(self._s, size, origin, ctypes.byref(px)):
            raise EngineError("no image traced yet")
        return list(size), list(origin), px.value
