# SPDX-License-Identifier: BSD-3-Clause
"""The knife-edge image of the Gaussian sphere, rendered, against a baseline PNG.

Run (needs an X server): Testing/with_xvfb.sh pvpython test_baseline.py
    --plugin <Schlieren.so> -V Testing/Baselines/knife_edge_gaussian.png -T <temp dir>

The image is drawn with a grey colour map fixed to [0, 1], the view looking at the film straight on
with a parallel projection that the film fills. A missing or different baseline fails and leaves
the candidate in the -T folder. Before the picture, numbers: the film arrays must be those of the
weak Gaussian sphere (ORACLES.md), so that a baseline cannot be regenerated from a wrong image
without a numeric failure too.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from paraview import smtesting

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_baseline")
A, S = 1e-4, 0.25
EMAX = st.gaussian_max_deflection(A)

scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[96, 96, 96], Amplitude=A, Width=S)
index = RefractiveIndex(Input=scene, Model="Passthrough")
image = SchlierenImage(Input=index, Resolution=[256, 256], Passes=4, Seed=11,
                       Cutoff="KnifeEdge", CutoffScale=2000.0, KnifeAngle=0.0, Backend="CPU")

# Numbers first. 96^3 and jittered photons: the RMS deviation from the closed form is ~0.5 % of
# max|eps| (grid sampling plus 4-photon noise); tolerance 1.5 %.
X, Y, I, D, F = st.image_arrays(sm.Fetch(image))
eps = st.gaussian_deflection(X, Y, A, S)
rms = np.sqrt(np.mean(np.sum((D - eps) ** 2, axis=-1)))
T.check(rms < 0.015 * EMAX, "RMS |deflection - eps| = %.3g %% of max|eps|" % (100 * rms / EMAX))
T.check(I.shape == (256, 256), "a 256 x 256 film")
# Bright where the light is bent towards -x (x > 0: eps_x < 0, I = 0.5 - k eps_x > 0.5).
T.check(I[128, 150] > 0.6 and I[128, 105] < 0.4 and abs(I[5, 5] - 0.5) < 1e-6,
        "bright right of the centre (%.3f), dark left (%.3f), grey background (%.6f)"
        % (I[128, 150], I[128, 105], I[5, 5]))

view = CreateRenderView()
view.ViewSize = [300, 300]
view.OrientationAxesVisibility = 0
view.Background = [1.0, 1.0, 1.0]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
display = Show(image, view)
display.Representation = "Slice"
ColorBy(display, ("POINTS", "intensity"))
lut = GetColorTransferFunction("intensity")
lut.ApplyPreset("Grayscale", True)
lut.AutomaticRescaleRangeMode = "Never"
lut.RescaleTransferFunction(0.0, 1.0)
display.SetScalarBarVisibility(view, False)
display.MapScalars = 1
display.InterpolateScalarsBeforeMapping = 0

Render(view)  # the first render resets the camera; set ours after it
view.CameraParallelProjection = 1
view.CameraPosition = [0.0, 0.0, 10.0]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
view.CameraParallelScale = 1.0  # half the film's height: the film fills the view
Render(view)

smtesting.ProcessCommandLineArguments()
T.check(smtesting.DoRegressionTesting(view.SMProxy), "the rendered image matches %s" % smtesting.BaselineImage)
T.finish()
