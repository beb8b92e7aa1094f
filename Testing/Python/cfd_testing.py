# SPDX-License-Identifier: BSD-3-Clause
"""Helpers of the CFD-data tests: where the shared data is, images built from numpy
arrays, numpy views of RefractiveIndex outputs, and the refractive-index formulas of
../../../shared/ORACLES.md restated in numpy for comparisons.
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO_ROOT = os.path.dirname(os.path.dirname(HERE))

# Exit status that ctest reports as "skipped" (SKIP_RETURN_CODE in CMakeLists.txt).
SKIP = 125

# ORACLES.md, section "Refractive index" (SI).
R = 8.314462618
GASES = {  # K (m^3/kg), M (kg/mol)
    "Air": (0.2256e-3, 28.9641e-3),
    "He": (0.1954e-3, 4.002602e-3),
    "N2": (0.2381e-3, 28.0134e-3),
    "O2": (0.1888e-3, 31.9988e-3),
    "Ar": (0.1576e-3, 39.948e-3),
    "CO2": (0.2265e-3, 44.0095e-3),
    "H2": (1.5395e-3, 2.01588e-3),
    "H2O": (0.3127e-3, 18.01528e-3),
    "CH4": (0.617e-3, 16.0425e-3),
    "CO": (0.268e-3, 28.0101e-3),
}


def data_dir():
    """The shared data folder: $SCHLIEREN_DATA, else <repo>/../shared/data."""
    return os.environ.get("SCHLIEREN_DATA") or os.path.join(REPO_ROOT, "..", "shared", "data")


def require_data(*names):
    """The paths of the data files `names`; exits with SKIP (and says why) if any is missing."""
    folder = data_dir()
    paths = [os.path.join(folder, n) for n in names]
    missing = [p for p in paths if not os.path.exists(p)]
    if missing:
        print("SKIP: the shared CFD data is not there (%s); set SCHLIEREN_DATA to the folder that "
              "holds %s" % (", ".join(missing), ", ".join(names)))
        sys.stdout.flush()
        sys.exit(SKIP)
    return paths


def make_image(dims, origin, spacing, arrays):
    """A vtkImageData with the point arrays `arrays` (name -> numpy array of shape (nz, ny, nx))."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData

    img = vtkImageData()
    img.SetDimensions(*dims)
    img.SetOrigin(*origin)
    img.SetSpacing(*spacing)
    for name, values in arrays.items():
        a = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float32).ravel(), deep=1)
        a.SetName(name)
        img.GetPointData().AddArray(a)
    return img


def producer(ns, data):
    """A pipeline source (TrivialProducer) that outputs the VTK data object `data` (builtin
    session only). `ns` is the namespace the plugin was loaded into."""
    tp = ns["TrivialProducer"]()
    tp.GetClientSideObject().SetOutput(data)
    tp.UpdatePipeline()
    return tp


def grid_arrays(data, *names):
    """Numpy views (nz, ny, nx[, ncomp]) of point arrays of an image, and its geometry."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    nx, ny, nz = data.GetDimensions()
    out = []
    for name in names:
        a = data.GetPointData().GetArray(name)
        if a is None:
            raise KeyError("no point array %r (have %s)" % (
                name, [data.GetPointData().GetArrayName(i) for i in range(data.GetPointData().GetNumberOfArrays())]))
        v = vtk_to_numpy(a).astype(float)
        out.append(v.reshape((nz, ny, nx) + ((a.GetNumberOfComponents(),) if a.GetNumberOfComponents() > 1 else ())))
    return out


def field_value(data, name, default=None):
    fd = data.GetFieldData()
    a = fd.GetAbstractArray(name) if fd else None
    return a.GetVariantValue(0).ToDouble() if a is not None else default


def ideal_gas_n1(T, p, gas="Air"):
    """n - 1 = K p M / (R T) of one gas of the table (T in K, p in Pa)."""
    K, M = GASES[gas]
    return K * np.asarray(p, dtype=float) * M / (R * np.asarray(T, dtype=float))


def mixture_n1(T, p, fractions, gases):
    """n - 1 of a mixture by mass fractions (summing to 1): K = sum Y K, 1/M = sum Y / M."""
    K = sum(np.asarray(Y, dtype=float) * GASES[g][0] if isinstance(g, str) else np.asarray(Y) * g[0]
            for Y, g in zip(fractions, gases))
    invM = sum(np.asarray(Y, dtype=float) / (GASES[g][1] if isinstance(g, str) else g[1])
               for Y, g in zip(fractions, gases))
    return K * np.asarray(p, dtype=float) / (invM * R * np.asarray(T, dtype=float))
