# SPDX-License-Identifier: BSD-3-Clause
"""RefractiveScene -> RefractiveIndex -> SchlierenImage in pvpython, against known answers.

Run: pvpython test_pipeline.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so

Known answers (ORACLES.md, "Weak Gaussian sphere"): for n = 1 + A exp(-r^2/s^2) and a beam along
-z, eps = -(2 sqrt(pi) A / s) (x, y) exp(-rho^2/s^2), max |eps| = sqrt(2 pi) A e^(-1/2), and a
knife with normal a and scale k gives I = 0.5 - k eps.a.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_pipeline")

A, S = 1e-4, 0.25                      # Gaussian amplitude and 1/e width
EMAX = st.gaussian_max_deflection(A)   # 1.5203e-4 rad
K = st.KNIFE_SCALE

# ---------------------------------------------------------------- 1. a uniform medium
scene = RefractiveScene(Scene="Uniform", Dimensions=[32, 32, 32], Amplitude=A)
index = RefractiveIndex(Input=scene, Model="Passthrough")
image = SchlierenImage(Input=index, Cutoff="KnifeEdge", CutoffScale=K, Resolution=[64, 64], Passes=2)

volume = sm.Fetch(index)
n1 = vtk_to_numpy(volume.GetPointData().GetArray("n_minus_1"))
grad = vtk_to_numpy(volume.GetPointData().GetArray("grad_n"))
T.close(n1, A, 1e-7 * A, "uniform: n_minus_1 == Amplitude (float32)")
T.check(grad.shape == (32 ** 3, 3), "uniform: grad_n has 3 components per point")
T.close(grad, 0.0, 0.0, "uniform: grad_n == 0")
T.check(volume.GetPointData().GetArray("density") is not None, "uniform: RefractiveIndex keeps 'density'")

X, Y, I, D, F = st.image_arrays(sm.Fetch(image))
h = X[0, 1] - X[0, 0]
T.check(I.shape == (64, 64), "uniform: the image is 64 x 64 (got %s)" % (I.shape,))
T.close(I, 0.5, 1e-6, "uniform: intensity == 0.5")
T.close(D, 0.0, 1e-12, "uniform: deflection == 0")
# The film covers the volume's projection [-1, 1]^2 with square pixels; the origin is pixel (0, 0)'s centre.
T.close([X[0, 0] - h / 2, Y[0, 0] - h / 2, X[0, -1] + h / 2, Y[-1, 0] + h / 2], [-1, -1, 1, 1], 1e-9,
        "uniform: the film spans [-1, 1]^2")
T.close(F["cutoff_scale"], K, 0.0, "uniform: field data cutoff_scale == CutoffScale")
T.close(F["photons"], 64 * 64 * 2, 0.0, "uniform: photons == pixels x passes")
T.close(F["failed_rays"], 0.0, 0.0, "uniform: no failed rays")
T.check(F["backend"] in ("OpenCL", "CPU") and F["device"], "uniform: backend %r on %r" % (F["backend"], F["device"]))

# ---------------------------------------------------------------- 2. the weak Gaussian sphere, 128^3
scene.Scene = "GaussianSphere"
scene.Dimensions = [128, 128, 128]
scene.Bounds = [-1, 1, -1, 1, -1, 1]
scene.Width = S
# Gladstone-Dale on the scene's density must give back the scene's n - 1 (density = (n-1)/K_air).
index.Model = "GladstoneDale"
index.InputArray = ["POINTS", "density"]
index.GladstoneDaleConstant = 2.256e-4
volume = sm.Fetch(index)
pd = volume.GetPointData()
n1 = vtk_to_numpy(pd.GetArray("n_minus_1")).astype(float)
T.close(n1 / A, vtk_to_numpy(pd.GetArray("density")).astype(float) * 2.256e-4 / A, 1e-6,
        "Gladstone-Dale: n_minus_1 == K density (relative to A)")
# grad_n against the analytic gradient grad n = -2 A r / s^2 exp(-r^2/s^2). Central differences on
# a grid with s/h = 15.9 voxels: measured max error 1.3 % of max |grad n|; tolerance 2 %.
x = np.linspace(-1, 1, 128)
Z3, Y3, X3 = np.meshgrid(x, x, x, indexing="ij")
g = -2 * A / S ** 2 * np.exp(-(X3 ** 2 + Y3 ** 2 + Z3 ** 2) / S ** 2)
exact = np.stack([g * X3, g * Y3, g * Z3], axis=-1).reshape(-1, 3)
gmax = math.sqrt(2) * A / S * math.exp(-0.5)
grad = vtk_to_numpy(pd.GetArray("grad_n")).astype(float)
T.close(grad / gmax, exact / gmax, 0.02, "Gladstone-Dale: grad_n vs analytic (relative to max |grad n|)")
index.Model = "Passthrough"
index.InputArray = ["POINTS", "n_minus_1"]

# 2a. Photons at pixel centres (Jitter off), so that each pixel holds exactly the ray through its
# centre. Deflection against the closed form: measured max error 0.61 % of max|eps| at 128^3, 256^2
# pixels, StepSize 0.5, Euler (0.41 % at 128^2 pixels; 2.4 % at 64^3; 0.17 % at 256^3: second order
# in the grid spacing, the trilinear sampling of the grid, as ORACLES.md's "convergence" says).
# Tolerance 1 % of max|eps|. The knife-edge intensity 0.5 - k eps_x: measured 0.57 % of k max|eps|;
# tolerance 1 % of k max|eps| (0.0015 in intensity).
image.Resolution = [256, 256]
image.Passes = 1
image.Jitter = 0
image.Backend = "CPU"
X, Y, I, D, F = st.image_arrays(sm.Fetch(image))
eps = st.gaussian_deflection(X, Y, A, S)
err = np.sqrt(np.sum((D - eps) ** 2, axis=-1))
T.check(err.max() <= 0.01 * EMAX, "Gaussian, centres: max |deflection - eps| = %.3g %% of max|eps| (tolerance 1 %%)"
        % (100 * err.max() / EMAX))
T.close(np.abs(D).max() / EMAX, 1.0, 0.01, "Gaussian, centres: max |deflection| / max|eps|")
T.close(I, 0.5 - K * eps[..., 0], 0.01 * K * EMAX, "Gaussian, centres: intensity == 0.5 - k eps_x")
T.close(F["photons"], 256 * 256, 0.0, "Gaussian, centres: photons == pixels")

# 2b. Knife at 90 degrees: the knife normal is the film's y axis, I = 0.5 - k eps_y.
image.KnifeAngle = 90.0
X, Y, I, D, F = st.image_arrays(sm.Fetch(image))
T.close(I, 0.5 - K * eps[..., 1], 0.01 * K * EMAX, "Gaussian, KnifeAngle 90: intensity == 0.5 - k eps_y")
image.KnifeAngle = 0.0

# 2c. Automatic scale: k = 0.5 / max over photons of |e.a|, so the image spans [0, 1].
image.CutoffScale = 0.0
X, Y, I, D, F = st.image_arrays(sm.Fetch(image))
T.close(F["cutoff_scale"] * EMAX, 0.5, 0.01, "Gaussian, automatic k: cutoff_scale x max|eps| == 0.5")
T.close([I.min(), I.max()], [0.0, 1.0], 1e-5, "Gaussian, automatic k: intensity spans [0, 1]")
image.CutoffScale = K

# 2d. Jittered photons (the default), 4 passes, on both backends. The per-pixel mean deflection is
# then a 4-photon sample of the pixel's area: its noise is about |grad eps| h / sqrt(12 x 4) ~ 0.9 %
# of max|eps| (measured: RMS 0.26 %, max 3.3 %). Asserted: no bias beyond the grid's (least-squares
# scale of the deflection on eps: measured 0.9964 here and 0.9966 with Jitter off, the trilinear
# sampling's; tolerance 1 %) and RMS error under 1 % of max|eps|.
image.Jitter = 1
image.Passes = 4
image.Seed = 7
results = {}
for backend in ("CPU", "OpenCL"):
    image.Backend = backend
    with st.CapturedOutput() as out:
        data = sm.Fetch(image)
    if backend == "OpenCL" and data.GetNumberOfPoints() == 0 and "OpenCL" in out.text:
        # No usable OpenCL device: a skip, except where CI requires one (as the C++ tests do).
        required = os.environ.get("SCHLIEREN_REQUIRE_OPENCL") == "1"
        T.check(not required, "no OpenCL device: a skip unless SCHLIEREN_REQUIRE_OPENCL=1 (%s)" % out.text.strip()[:300])
        print("SKIP OpenCL parts: %s" % out.text.strip()[:300])
        break
    X, Y, I, D, F = st.image_arrays(data)
    T.check(F["backend"] == backend, "jittered, %s: field data backend == %r (got %r)" % (backend, backend, F["backend"]))
    T.check("ERROR" not in out.text, "jittered, %s: no error reported" % backend)
    results[backend] = (I, D)
    scale = np.sum(D * eps) / np.sum(eps * eps)
    rms = math.sqrt(np.mean(np.sum((D - eps) ** 2, axis=-1)))
    T.close(scale, 1.0, 0.01, "jittered, %s: least-squares scale of deflection on eps" % backend)
    T.check(rms <= 0.01 * EMAX, "jittered, %s: RMS |deflection - eps| = %.3g %% of max|eps| (tolerance 1 %%)"
            % (backend, 100 * rms / EMAX))
# One physics source, two builds: measured max difference 2.9e-7 of max|eps| (float32 arithmetic,
# ~250 steps per ray) and 1.2e-7 in intensity. Tolerances 2e-6 of max|eps| and 1e-6.
if "OpenCL" in results:
    T.close(results["OpenCL"][1] / EMAX, results["CPU"][1] / EMAX, 2e-6, "OpenCL vs CPU: deflection / max|eps|")
    T.close(results["OpenCL"][0], results["CPU"][0], 1e-6, "OpenCL vs CPU: intensity")

# 2e. JitterPattern Lattice (one offset per pass for every pixel) through the pipeline: the
# property's entries, a new image when it changes (the photons' key holds it: no kept sums
# reused), and at 1 pass an intensity closer to the many-pass image than Random's (the engine's
# TestEngineOracles measures the ratio: 2.7x on a sphere, 6.3x on a shock; asserted here: closer).
T.check(image.GetProperty("JitterPattern").Available == ["Random", "Lattice"],
        "JitterPattern: entries Random, Lattice (got %s)" % image.GetProperty("JitterPattern").Available)
T.check(image.JitterPattern == "Lattice", "JitterPattern: Lattice by default")
image.JitterPattern = "Random"
image.Backend = "CPU"
image.Passes = 16
ref_I = st.image_arrays(sm.Fetch(image))[2].copy()
image.Passes = 1
I_random = st.image_arrays(sm.Fetch(image))[2].copy()
image.JitterPattern = "Lattice"
with st.CapturedOutput() as out:
    X, Y, I_lattice, D, F = st.image_arrays(sm.Fetch(image))
T.check("ERROR" not in out.text, "Lattice: no error reported")
T.check(np.abs(I_lattice - I_random).max() > 0, "Lattice: a new image, not the Random pass kept")
rms_r = math.sqrt(np.mean((I_random - ref_I) ** 2))
rms_l = math.sqrt(np.mean((I_lattice - ref_I) ** 2))
T.check(rms_l < rms_r, "Lattice at 1 pass closer to 16 Random passes than Random at 1 pass (RMS %.3g vs %.3g)"
        % (rms_l, rms_r))

# ---------------------------------------------------------------- 3. plain VTK Python access
from schlieren_vtk import vtkRefractiveScene, vtkSchlierenImage  # noqa: E402

vscene = vtkRefractiveScene()
vscene.SetSceneToUniform()
vscene.SetDimensions(16, 16, 16)
vimage = vtkSchlierenImage()
vimage.SetInputConnection(vscene.GetOutputPort())
vimage.SetResolution(8, 8)
vimage.SetPasses(1)
vimage.SetCutoffScale(K)
vimage.Update()
vout = vimage.GetOutput()
T.check(vout.GetDimensions() == (8, 8, 1), "VTK Python: vtkSchlierenImage output is 8 x 8")
T.close(vtk_to_numpy(vout.GetPointData().GetArray("intensity")), 0.5, 1e-6, "VTK Python: uniform intensity == 0.5")

# Progress is reported while tracing, and an abort requested from a progress observer stops it.
progress = []


def on_progress(caller, event):
    progress.append(caller.GetProgress())
    if len(progress) == 2:
        caller.SetAbortExecute(1)


vimage.SetResolution(64, 64)
vimage.SetPasses(4)
vimage.AddObserver("ProgressEvent", on_progress)
with st.CapturedOutput() as out:
    vimage.Update()
T.check(len(progress) >= 2 and 0 < progress[1] < 1, "VTK Python: progress reported (%s)" % progress[:4])
T.check("aborted" in out.text and vimage.GetOutput().GetDimensions() == (8, 8, 1),
        "VTK Python: an abort from the progress observer stops the trace, said, the image of before kept")

# ---------------------------------------------------------------- 4. the input's array type
# float n_minus_1 is read in place (no copy), any other type converted: the same image bit for bit,
# and the input's floats are left as they were
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402

g = np.linspace(-0.5, 0.5, 24)
z, y, x = np.meshgrid(g, g, g, indexing="ij")
field = (A * np.exp(-(x * x + y * y + z * z) / (S * S))).ravel()
images = {}
for dtype in (np.float32, np.float64):
    grid = vtkImageData()
    grid.SetDimensions(24, 24, 24)
    grid.SetOrigin(-0.5, -0.5, -0.5)
    grid.SetSpacing(1.0 / 23, 1.0 / 23, 1.0 / 23)
    values = np.ascontiguousarray(field.astype(np.float32).astype(dtype))
    arr = numpy_to_vtk(values, deep=1)
    arr.SetName("n_minus_1")
    grid.GetPointData().AddArray(arr)
    im = vtkSchlierenImage()
    im.SetInputData(grid)
    im.SetResolution(32, 32)
    im.SetPasses(1)
    im.SetJitter(0)
    im.SetCutoffScale(K)
    im.Update()
    images[dtype] = vtk_to_numpy(im.GetOutput().GetPointData().GetArray("deflection")).copy()
    T.check(np.array_equal(vtk_to_numpy(arr), values), "input %s: n_minus_1 unchanged by the trace" % dtype.__name__)
T.check(np.abs(images[np.float32]).max() > 0.5 * EMAX and np.array_equal(images[np.float32], images[np.float64]),
        "float n_minus_1 (read in place) and double (converted): the same deflections bit for bit "
        "(max |eps| %.3g rad)" % np.abs(images[np.float32]).max())

# ---------------------------------------------------------------- 5. the image's range cache
# the filter fills each image array's range cache (what ParaView's data information asks after
# every update): every range as VTK computes it on a copy without the cache, for all values and the
# finite ones, per component and (-1) the norm's
from vtkmodules.vtkCommonCore import vtkAbstractArray, vtkFloatArray  # noqa: E402

pd = im.GetOutput().GetPointData()
for k in range(pd.GetNumberOfArrays()):
    arr = pd.GetArray(k)
    name = arr.GetName()
    T.check(arr.GetInformation().Has(vtkAbstractArray.PER_COMPONENT()),
            "range cache: '%s' has its ranges after the update" % name)
    fresh = vtkFloatArray()
    fresh.DeepCopy(arr)  # DeepCopy leaves the range keys behind: computed anew
    T.check(not fresh.GetInformation().Has(vtkAbstractArray.PER_COMPONENT()),
            "range cache: a deep copy of '%s' has none (so the ranges below are VTK's own)" % name)
    for c in range(-1, arr.GetNumberOfComponents()):
        cached, own = arr.GetRange(c), fresh.GetRange(c)
        cachedF, ownF = arr.GetFiniteRange(c), fresh.GetFiniteRange(c)
        T.check(cached == own and cachedF == ownF,
                "range cache: '%s' component %d: %r == VTK's %r, finite %r == %r"
                % (name, c, cached, own, cachedF, ownF))


T.finish()
