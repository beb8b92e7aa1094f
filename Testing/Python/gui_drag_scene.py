# SPDX-License-Identifier: BSD-3-Clause
"""The volume of test_gui_drag.py, built the same way in the GUI (gui_drag_session.py) and in
pvpython (gui_drag_check.py): the NASA blunt fin resampled to 64 voxels along its longest side, or,
where the data is absent, a built-in off-centre Gaussian sphere (A = 1e-3, s = 0.3 on 64^3)."""
import os


def volume(simple, data):
    """Returns (proxy, name); `simple` is paraview.simple (the plugin loaded). With
    SCHLIEREN_GUI_SCENE=blast: the built-in blast wave with 4 time steps (ParaView's animation
    steps through them), whatever the data."""
    if os.environ.get("SCHLIEREN_GUI_SCENE") == "blast":
        scene = simple.RefractiveScene(registrationName="RefractiveScene1", Scene="BlastWave",
                                       Dimensions=[48, 48, 48], TimeSteps=4)
        return scene, "blast"
    xyz, q = os.path.join(data, "bluntfinxyz.bin"), os.path.join(data, "bluntfinq.bin")
    if os.path.exists(xyz) and os.path.exists(q):
        reader = simple.PLOT3DReader(registrationName="bluntfin", FileName=xyz, QFileName=[q])
        index = simple.RefractiveIndex(registrationName="RefractiveIndex1", Input=reader, Model="GladstoneDale",
                                       Gas="Air", DensityReference=1.2, UseSamplingBounds=1,
                                       SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7], AutomaticDimension=64,
                                       AmbientMode="Extend")
        index.InputArray = ["POINTS", "Density"]
        return index, "bluntfin"
    scene = simple.RefractiveScene(registrationName="RefractiveScene1", Scene="GaussianSphere",
                                   Dimensions=[64, 64, 64], Amplitude=1e-3, Width=0.3, Center=[0.3, 0.1, -0.2])
    return scene, "sphere"
