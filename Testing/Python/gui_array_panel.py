# SPDX-License-Identifier: BSD-3-Clause
"""Builds, in the ParaView GUI, a RefractiveIndex by script on an input that has not run yet and
chooses its Input Array; gui_array_panel.xml then checks what the Properties panel shows.

Run by ctest (python.gui_array_panel) as
    with_xvfb.sh paraview --dr --script=gui_array_panel.py --test-script=gui_array_panel.xml --exit
which exits 1 when the panel's Input Array combobox does not show `density` (it showed nothing
while Python reported ['POINTS', 'density'] when the array list had no '(automatic)' entry).
"""
import os

from paraview.simple import *  # noqa: F401,F403

LoadPlugin(os.environ["SCHLIEREN_PLUGIN"], remote=False, ns=globals())
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[16, 16, 16])  # noqa: F821
index = RefractiveIndex(Input=scene, Model="GladstoneDale")  # noqa: F821
index.InputArray = ["POINTS", "density"]
Show(index)
SetActiveSource(index)
Render()
print("gui_array_panel: Python reports InputArray %s" % (list(index.InputArray),))
