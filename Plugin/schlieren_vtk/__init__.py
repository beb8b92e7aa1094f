# SPDX-License-Identifier: BSD-3-Clause
"""VTK classes of the Schlieren C++ plugin, for plain VTK Python (pvpython or pvbatch).

    from schlieren_vtk import vtkRefractiveScene, vtkRefractiveIndex, vtkSchlierenImage

ParaView users do not need this package: load the plugin and use RefractiveScene,
RefractiveIndex and SchlierenImage from paraview.simple. The name `schlieren` is the Python front
end's (Python/schlieren, pip install .); it gives these classes too (`from schlieren import
vtkSchlierenImage`, the name scripts used before) where this package is importable.
"""
from .SchlierenFilters import *  # noqa: F401,F403
