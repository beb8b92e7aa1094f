# SPDX-License-Identifier: BSD-3-Clause
"""Bad inputs give clear errors, empty outputs and no crash; the process then exits 0.

Run: pvpython test_errors.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so

Each case captures VTK's output window (vtkStringOutputWindow) around the update and checks that
the error names what is wrong (and, for a missing array, the arrays that are there).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_errors")


def expect_error(proxy, case, *phrases):
    """Updates `proxy`; checks that an error containing every phrase was reported and that the
    output is empty."""
    with st.CapturedOutput() as out:
        data = sm.Fetch(proxy)
    text = out.text
    points = data.GetNumberOfPoints() if data is not None else 0
    T.check("ERROR" in text, "%s: an error is reported" % case)
    missing = [p for p in phrases if p not in text]
    T.check(not missing, "%s: the error names %s%s" % (case, ", ".join(repr(p) for p in phrases),
                                                         "" if not missing else " (missing %s; got: %s)"
                                                         % (missing, text.strip()[:600])))
    T.check(points == 0, "%s: the output is empty (%d points)" % (case, points))
    lines = [l for l in text.splitlines() if l.startswith("vtk")]
    print("     reported: %s" % (lines[0] if lines else "(nothing)"))


# 1. An image without n_minus_1 (the Wavelet's only point array is RTData).
wavelet = Wavelet()
image = SchlierenImage(Input=wavelet)
expect_error(image, "Wavelet into SchlierenImage", "n_minus_1", "RTData", "RefractiveIndex")

# 2. RefractiveIndex asked for an array that is not there.
index = RefractiveIndex(Input=wavelet, Model="GladstoneDale")
index.InputArray = ["POINTS", "pressure"]
expect_error(index, "RefractiveIndex with a missing array", "'pressure'", "RTData")

# 3. Not an image.
sphere = Sphere()
index_on_polydata = RefractiveIndex(Input=sphere)
expect_error(index_on_polydata, "RefractiveIndex on polydata", "vtkImageData", "vtkPolyData")
image_on_polydata = SchlierenImage(Input=sphere)
expect_error(image_on_polydata, "SchlierenImage on polydata", "vtkImageData", "vtkPolyData")

# 4. A volume one voxel thick: no gradient along z, nothing to trace through.
flat = RefractiveScene(Scene="GaussianSphere", Dimensions=[64, 64, 1])
flat_image = SchlierenImage(Input=flat, Resolution=[32, 32], Passes=1)
expect_error(flat_image, "one voxel thick into SchlierenImage", "64 x 64 x 1")
flat_index = RefractiveIndex(Input=flat)
expect_error(flat_index, "one voxel thick into RefractiveIndex", "64 x 64 x 1")

# 5. NaN in the field: n - 1 is NaN in the sphere's core (where n - 1 > A / 2), finite elsewhere.
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[32, 32, 32])
nan_field = PythonCalculator(Input=scene, ArrayName="n_minus_1",
                             Expression="where(n_minus_1 > 5e-5, n_minus_1 * float('nan'), n_minus_1)")
nan_index = RefractiveIndex(Input=nan_field, Model="Passthrough")
nan_index.InputArray = ["POINTS", "n_minus_1"]
expect_error(nan_index, "NaN into RefractiveIndex", "NaN")
nan_image = SchlierenImage(Input=nan_field, Resolution=[32, 32], Passes=1)
expect_error(nan_image, "NaN into SchlierenImage", "NaN")

# 6. n <= 0: n - 1 = -2 everywhere.
negative = PythonCalculator(Input=scene, Expression="n_minus_1 - 2", ArrayName="n_minus_1")
negative_index = RefractiveIndex(Input=negative, Model="Passthrough")
negative_index.InputArray = ["POINTS", "n_minus_1"]
expect_error(negative_index, "n <= 0 into RefractiveIndex", "n <= 0")

# 6b. Gladstone-Dale with a negative density, and with K = 0.
negative_density = PythonCalculator(Input=scene, Expression="density - 1.0", ArrayName="density")
gd = RefractiveIndex(Input=negative_density, Model="GladstoneDale")
gd.InputArray = ["POINTS", "density"]
expect_error(gd, "negative density", "density", "negative")
gd_zero = RefractiveIndex(Input=scene, Model="GladstoneDale", GladstoneDaleConstant=0.0)
gd_zero.InputArray = ["POINTS", "density"]
expect_error(gd_zero, "Gladstone-Dale constant 0", "Gladstone-Dale constant")

# 7. Bad tracing settings on a good volume.
good = RefractiveIndex(Input=scene, Model="Passthrough")
zero_passes = SchlierenImage(Input=good, Resolution=[32, 32], Passes=0)
expect_error(zero_passes, "Passes = 0", "Passes", "at least 1")
no_pixels = SchlierenImage(Input=good, Resolution=[0, 32], Passes=1)
expect_error(no_pixels, "Resolution 0 x 32", "Resolution")
parallel_up = SchlierenImage(Input=good, Resolution=[32, 32], Passes=1, ViewDirection=[0, 1, 0], ViewUp=[0, 2, 0])
expect_error(parallel_up, "ViewUp parallel to ViewDirection", "ViewUp")

# 8. Fixing the settings recovers: the same proxy then works.
zero_passes.Passes = 1
zero_passes.CutoffScale = 1000.0
with st.CapturedOutput() as out:
    data = sm.Fetch(zero_passes)
X, Y, I, D, F = st.image_arrays(data)
T.check("ERROR" not in out.text, "recovered: no error after setting Passes = 1")
T.check(I.shape == (32, 32), "recovered: a 32 x 32 image")
T.check(0.3 < I.min() < 0.5 < I.max() < 0.7, "recovered: a knife-edge image of the sphere (I in [%.3f, %.3f])"
        % (I.min(), I.max()))

T.finish()
