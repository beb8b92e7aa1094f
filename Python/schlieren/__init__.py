# SPDX-License-Identifier: BSD-3-Clause
"""Schlieren for plain VTK, PyVista and NumPy: no compiler, no ParaView.

    import schlieren
    scene = schlieren.RefractiveScene(Scene="GaussianSphere", Dimensions=[128] * 3)
    image = schlieren.SchlierenImage(Cutoff="KnifeEdge", Resolution=[512, 512])
    image.SetInputConnection(scene.GetOutputPort())
    image.Update()
    intensity = schlieren.image_to_numpy(image.GetOutput())   # (ny, nx) float32

The engine is libschlieren_engine.so (its C interface, schlieren_c.h) through ctypes; the VTK
algorithms need the `vtk` package (PyPI's wheels 9.2 and later), the engine functions only NumPy
(schlieren.engine: Session, fill_scene, ...). OpenCL is used where a driver is installed, else the
CPU (Backend Auto warns; Backend CPU is silent).
"""
from . import _engine as engine  # noqa: F401
from ._engine import EngineError, properties, version  # noqa: F401

__version__ = "0.1.0"

try:
    from .algorithms import (NumericalSchlieren, RefractionOctree, RefractiveIndex,  # noqa: F401
                             RefractiveScene, SchlierenImage, SchlierenPhotograph, image_to_numpy,
                             read_photograph)
except ImportError as _e:  # no VTK: the engine functions still work
    _vtk_error = _e

    def _front_end_missing(name):
        if name in ("RefractiveScene", "RefractiveIndex", "RefractionOctree", "SchlierenImage",
                    "NumericalSchlieren", "SchlierenPhotograph", "image_to_numpy",
                    "read_photograph"):
            raise ImportError("schlieren.%s needs VTK (pip install vtk): %s" % (name, _vtk_error))
        return None
else:
    def _front_end_missing(name):
        return None


def __getattr__(name):
    """The C++ plugin's compiled classes (vtkSchlierenImage, ...), which its package
    `schlieren_vtk` holds, under this name too: `from schlieren import vtkSchlierenImage`, as
    scripts wrote it before the compiled package was renamed, works where both are installed."""
    _front_end_missing(name)
    if name.startswith("vtk"):
        try:
            import schlieren_vtk
        except ImportError as e:
            raise ImportError("schlieren.%s is a class of the C++ plugin's package schlieren_vtk, "
                              "which was not found (%s): install the C++ plugin, or use the "
                              "Python front end's %s" % (name, e, name[3:])) from e
        return getattr(schlieren_vtk, name)
    raise AttributeError("module 'schlieren' has no attribute %r" % name)
