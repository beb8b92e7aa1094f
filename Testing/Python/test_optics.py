# SPDX-License-Identifier: BSD-3-Clause
"""Image formation in pvpython: every cutoff, interferometry, BOS, the film filters,
passes, seeds and photon killing, against known answers.

Run: pvpython test_optics.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so

The scene is the weak Gaussian sphere of ORACLES.md, n = 1 + A exp(-r^2/s^2), s = 0.25, on 128^3
over [-1, 1]^3, beam along -z: eps = -(2 sqrt(pi) A / s) (x, y) exp(-rho^2/s^2), max |eps| =
sqrt(2 pi) A e^(-1/2), projected phase P = sqrt(pi) A s exp(-rho^2/s^2). Photons start at the
pixel centres (Jitter off) unless a check is about passes, so a pixel holds the ray through its
centre. Every measured number a tolerance was set from is in the comments (CPU backend).
"""
import colorsys
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
T = st.Checker("test_optics")

A, S = 1e-4, 0.25
EMAX = st.gaussian_max_deflection(A)


def image(proxy):
    """X, Y, intensity, deflection, field data and a function giving any other point array."""
    data = sm.Fetch(proxy)
    X, Y, I, D, F = st.image_arrays(data)

    def extra(name):
        a = data.GetPointData().GetArray(name)
        if a is None:
            return None
        v = vtk_to_numpy(a).astype(float)
        return v.reshape(I.shape + ((a.GetNumberOfComponents(),) if a.GetNumberOfComponents() > 1 else ()))

    return X, Y, I, D, F, extra


def arrays_of(proxy):
    data = sm.Fetch(proxy)
    pd = data.GetPointData()
    return sorted(pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays()))


gauss = RefractiveScene(Scene="GaussianSphere", Dimensions=[128, 128, 128], Amplitude=A, Width=S)
film = dict(Resolution=[48, 48], Passes=1, Jitter=0, Backend="CPU")

# ---------------------------------------------------------------- 1. circular stops
# I = 1 - k|eps| (pinhole) and I = k|eps| (dot stop) with k = 0.8 / max|eps| (no photon reaches a
# clamp). Measured: within 0.0046 = 0.58 % of the contrast 0.8 (the grid's trilinear error); asserted 1 %,
# and checked at four pixels on their own.
k = 0.8 / EMAX
for cutoff in ("Circular", "ComplementCircular"):
    proxy = SchlierenImage(Input=gauss, Cutoff=cutoff, CutoffScale=k, **film)
    X, Y, I, D, F, extra = image(proxy)
    eps = np.sqrt(np.sum(st.gaussian_deflection(X, Y, A, S) ** 2, axis=-1))
    expected = 1 - k * eps if cutoff == "Circular" else k * eps
    T.close(I, expected, 0.01 * 0.8, "%s: I == %s (k = 0.8 / max|eps|)" % (cutoff, "1 - k|eps|" if cutoff == "Circular" else "k|eps|"))
    for (j, i) in ((24, 24), (24, 33), (30, 20), (10, 10)):
        T.close(I[j, i], expected[j, i], 0.01 * 0.8, "%s at pixel (%d, %d), film (%.3f, %.3f)" % (cutoff, i, j, X[j, i], Y[j, i]))
    T.close(F["cutoff_scale"], k, 1e-9 * k, "%s: field data cutoff_scale == CutoffScale" % cutoff)
    T.check(arrays_of(proxy) == ["deflection", "intensity"], "%s: intensity and deflection only" % cutoff)
    # automatic k: the largest deflection maps to full contrast
    proxy.CutoffScale = 0
    X, Y, I, D, F, extra = image(proxy)
    T.close(F["cutoff_scale"] * EMAX, 1.0, 0.01, "%s, automatic k: cutoff_scale x max|eps| == 1" % cutoff)
    T.close([I.min(), I.max()], [0.0, 1.0], 1e-5, "%s, automatic k: intensity spans [0, 1]" % cutoff)
    Delete(proxy)

# ---------------------------------------------------------------- 2. knife edge at any angle
# I = 0.5 - k eps.a, a = (cos t, sin t); 180 degrees flips the knife. k = 1000 (no clamp).
# Measured: 0.58 % of k max|eps| (0.00088 in intensity); asserted 1 %.
knife = SchlierenImage(Input=gauss, Cutoff="KnifeEdge", CutoffScale=1000.0, **film)
for angle in (45.0, 180.0, -120.0):
    knife.KnifeAngle = angle
    X, Y, I, D, F, extra = image(knife)
    eps = st.gaussian_deflection(X, Y, A, S)
    t = math.radians(angle)
    T.close(I, 0.5 - 1000.0 * (eps[..., 0] * math.cos(t) + eps[..., 1] * math.sin(t)), 0.01 * 1000 * EMAX,
            "KnifeEdge at %g degrees: I == 0.5 - k eps.a" % angle)
Delete(knife)

# ---------------------------------------------------------------- 3. colour filter
# Hue from the direction of eps: atan2(eps_y, eps_x) (0 degrees red along +x, green at 120);
# value k|eps| with the automatic k = 1 / max|eps|. Measured: hue within 0.13 degrees where |eps| >
# 0.2 max|eps|, value within 0.3 % of 1; asserted 2 degrees and 1 %.
color = SchlierenImage(Input=gauss, Cutoff="ColorFilter", **film)
X, Y, I, D, F, extra = image(color)
rgb = extra("rgb")
T.check(rgb is not None and rgb.shape == (48, 48, 3), "ColorFilter: point array rgb with 3 components")
eps = st.gaussian_deflection(X, Y, A, S)
mag = np.sqrt(np.sum(eps ** 2, axis=-1))
strong = mag > 0.2 * EMAX
hsv = np.array([colorsys.rgb_to_hsv(*c) for c in rgb.reshape(-1, 3)]).reshape(48, 48, 3)
expected_hue = np.degrees(np.arctan2(eps[..., 1], eps[..., 0])) % 360
dh = np.abs(hsv[..., 0] * 360 - expected_hue)
dh = np.minimum(dh, 360 - dh)[strong]
T.check(dh.max() <= 2.0, "ColorFilter: hue == atan2(eps_y, eps_x) within %.2f degrees (tolerance 2)" % dh.max())
T.close(hsv[..., 2], mag / EMAX, 0.01, "ColorFilter: value == k|eps| with the automatic k = 1 / max|eps|")
T.close(hsv[..., 1][strong], 1.0, 1e-6, "ColorFilter: full saturation")
T.close(I, mag / EMAX, 0.01, "ColorFilter: intensity == k|eps| (the value)")
for (j, i) in ((24, 34), (34, 24), (14, 24)):
    print("     pixel (%d, %d): eps direction %.1f deg, rgb %s" % (i, j, expected_hue[j, i], np.round(rgb[j, i], 3)))
Delete(color)

# ---------------------------------------------------------------- 4. interferometry
# phase = 2 pi / lambda * sqrt(pi) A s exp(-rho^2/s^2), with A = 2e-6 so that the fringes are
# resolved (8.8 rad at the centre at 632.8 nm, world units in metres); I = (1 + cos phase) / 2.
# Measured: phase within 0.15 % of its peak (8.68 rad), intensity within 0.0067; asserted 1 % and
# 0.05. Tilted reference on a uniform medium: within 4e-4 (float32 n - 1 leaves ~1e-3 rad of phase).
# At twice the wavelength the phase halves.
A2 = 2e-6
faint = RefractiveScene(Scene="GaussianSphere", Dimensions=[128, 128, 128], Amplitude=A2, Width=S)
fringes = SchlierenImage(Input=faint, Cutoff="Interferometry", Wavelength=632.8, **film)
X, Y, I, D, F, extra = image(fringes)
phase = extra("phase")
exact = 2 * math.pi / 632.8e-9 * math.sqrt(math.pi) * A2 * S * np.exp(-(X ** 2 + Y ** 2) / S ** 2)
T.check(phase is not None, "Interferometry: point array phase")
T.close(phase / exact.max(), exact / exact.max(), 0.01, "Interferometry: phase == 2 pi/lambda sqrt(pi) A s exp(-rho^2/s^2) (peak %.2f rad)" % exact.max())
T.close(I, 0.5 * (1 + np.cos(exact)), 0.05, "Interferometry: fringes I == (1 + cos phase) / 2")
T.check(exact.max() / (2 * math.pi) > 1.3, "Interferometry: more than one fringe (%.2f)" % (exact.max() / (2 * math.pi)))
fringes.Wavelength = 2 * 632.8
phase2 = image(fringes)[5]("phase")
T.close(phase2 / exact.max(), 0.5 * phase / exact.max(), 1e-5, "Interferometry: twice the wavelength, half the phase")
# a tilted reference beam on a uniform medium: straight fringes cos(2 pi tilt a), a the film x
uniform = RefractiveScene(Scene="Uniform", Dimensions=[32, 32, 32], Amplitude=2.7e-4)
fringes.Input = uniform
fringes.Wavelength = 632.8
fringes.ReferenceTilt = 5.0
X, Y, I, D, F, extra = image(fringes)
T.close(I, 0.5 * (1 + np.cos(2 * math.pi * 5.0 * X)), 2e-3, "Interferometry, ReferenceTilt 5 per unit: straight fringes of period 0.2")
Delete(fringes)

# ---------------------------------------------------------------- 5. BOS
# A background Z behind the object's centre appears shifted by -Z eps. Z = BackgroundDistance + the
# distance from the front of the box to its centre (1.001 x the half depth, the emission plane).
# Measured: within 0.28 % of max |Z eps|; asserted 2 %. Stripes: within 7e-7.
bos = SchlierenImage(Input=gauss, Cutoff="BOS", BackgroundDistance=2.0, **film)
X, Y, I, D, F, extra = image(bos)
shift = extra("bos_displacement")
Z = 2.0 + 1.001
eps = st.gaussian_deflection(X, Y, A, S)
T.check(shift is not None and shift.shape == (48, 48, 2), "BOS: point array bos_displacement with 2 components")
T.close(shift / (Z * EMAX), -eps / EMAX, 0.02, "BOS: displacement == -Z eps (relative to max |Z eps| = %.3g)" % (Z * EMAX))
T.check(I.min() < 0.1 and I.max() > 0.9, "BOS dots: dark gaps and bright dots (I in [%.2f, %.2f])" % (I.min(), I.max()))
# stripes on a uniform medium: I = (1 + cos(2 pi a / period)) / 2 at the pixel centres
bos.Input = uniform
bos.BackgroundPattern = "Stripes"
bos.BackgroundPeriod = 0.25
X, Y, I, D, F, extra = image(bos)
T.close(I, 0.5 * (1 + np.cos(2 * math.pi * X / 0.25)), 1e-5, "BOS stripes of period 0.25 on a uniform medium")
T.close(extra("bos_displacement"), 0.0, 1e-9, "BOS on a uniform medium: no displacement")
Delete(bos)

# ---------------------------------------------------------------- 6. passes, filters, seeds
# Shadowgraph 20 units behind the box, 48^3 sphere, 96^2 film: the photon counts are what
# fluctuates. Measured RMS against a 128-pass image: JitterPattern Random 0.133, 0.064, 0.032 at 2,
# 8, 32 passes (N^-0.52); Lattice (the default) 0.047, 0.017, 0.010 (N^-0.55). The filters are for
# Random's noise: at 10 passes Random with no filter 0.061, Gaussian (0.5 px) 0.041, cone (2 px /
# sqrt N) 0.042; Lattice with no filter 0.016, closer than either.
small = RefractiveScene(Scene="GaussianSphere", Dimensions=[48, 48, 48], Amplitude=A, Width=S)
shadow = SchlierenImage(Input=small, Cutoff="Shadowgraph", FilmDistance=20.0, Resolution=[96, 96],
                        Passes=128, Seed=99, Integrator="Midpoint", StepSize=1.0, Backend="CPU")
reference = image(shadow)[2]


def rms(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)))


shadow.Seed = 1
errors = []
for n in (2, 8, 32):
    shadow.Passes = n
    errors.append(rms(image(shadow)[2], reference))
slope = math.log(errors[2] / errors[0]) / math.log(16.0)
print("     shadowgraph RMS against 128 passes: %s at 2, 8, 32 passes: N^%.2f" % (np.round(errors, 4), slope))
T.check(slope < -0.4, "noise falls about as 1/sqrt(passes) (N^%.2f)" % slope)
shadow.Passes = 10
lattice10 = rms(image(shadow)[2], reference)
shadow.JitterPattern = "Random"
plain10 = rms(image(shadow)[2], reference)
shadow.Filter = "Gaussian"
shadow.FilterWidth = 0.5
gauss10 = rms(image(shadow)[2], reference)
shadow.Filter = "Cone"
shadow.FilterWidth = 2.0
cone10 = rms(image(shadow)[2], reference)
print("     10 passes against 128: Random: no filter %.4f, Gaussian %.4f, cone %.4f; Lattice, no filter %.4f"
      % (plain10, gauss10, cone10, lattice10))
T.check(gauss10 < 0.85 * plain10, "a Gaussian filter at 10 passes comes closer to the converged image (Random)")
T.check(cone10 < 0.85 * plain10, "the cone filter at 10 passes comes closer to the converged image (Random)")
T.check(lattice10 < 0.85 * min(gauss10, cone10),
        "Lattice at 10 passes, no filter, closer than Random with either filter")
shadow.Filter = "None"
shadow.JitterPattern = "Lattice"
shadow.Passes = 3
shadow.Seed = 7
a = image(shadow)
shadow.Seed = 7
shadow.Passes = 4
shadow.UpdatePipeline()
shadow.Passes = 3
b = image(shadow)
shadow.Seed = 8
c = image(shadow)
T.check(np.array_equal(a[2], b[2]) and np.array_equal(a[3], b[3]), "same seed, same image, bit for bit")
T.check(not np.array_equal(a[2], c[2]), "another seed, another image")
Delete(shadow)

# ---------------------------------------------------------------- 7. photon killing
# Knife edge, k = 2500, 8 passes: energy weighting and Russian roulette have the same mean;
# weighting is less noisy. Measured: means 0.5000 and 0.4999 (4 sigma = 0.0073), RMS against 128
# passes 0.0007 weighted, 0.176 killed.
roulette = SchlierenImage(Input=small, Cutoff="KnifeEdge", CutoffScale=2500.0, Resolution=[96, 96],
                          Passes=128, Integrator="Midpoint", StepSize=1.0, Backend="CPU")
kref = image(roulette)[2]
roulette.Passes = 8
weighted = image(roulette)[2]
roulette.RussianRoulette = 1
killed = image(roulette)[2]
ew, ek = rms(weighted, kref), rms(killed, kref)
print("     8 passes: weighting mean %.4f RMS %.4f; killing mean %.4f RMS %.4f" % (weighted.mean(), ew, killed.mean(), ek))
T.close(killed.mean(), weighted.mean(), 4 * ek / math.sqrt(killed.size), "photon killing has the mean of energy weighting (4 sigma)")
T.check(ew < 0.5 * ek, "energy weighting is at least twice less noisy than photon killing (%.4f vs %.4f)" % (ew, ek))
T.check(np.allclose(killed * 8, np.round(killed * 8), atol=1e-5), "photon killing: each pixel is a count of whole photons out of 8")
# photon killing needs a fixed scale for the knife: the automatic one is known only after the trace
roulette.CutoffScale = 0
with st.CapturedOutput() as out:
    data = sm.Fetch(roulette)
T.check("ERROR" in out.text and "CutoffScale" in out.text and data.GetNumberOfPoints() == 0,
        "photon killing with the automatic scale: an error that names CutoffScale, no image")
Delete(roulette)

T.finish()
