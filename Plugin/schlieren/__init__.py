# SPDX-License-Identifier: BSD-3-Clause
"""VTK classes of the Schlieren plugin, for plain VTK Python (pvpython or pvbatch).

    from schlieren import vtkRefractiveScene, vtkRefractiveIndex, vtkSchlierenImage

ParaView users do not need this package: load the plugin and use RefractiveScene,
RefractiveIndex and SchlierenImage from paraview.simple.
"""
from .SchlierenFilters import *  # noqa: F401,F403
