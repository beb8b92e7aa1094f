# SPDX-License-Identifier: BSD-3-Clause
"""The bench on SchlierenImage through the plugin (docs/BENCH.md): a finite source cut by the
knife, its read-outs in the field data, its errors, and Point unchanged.

Run: pvpython test_bench.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so

The scene is the weak Gaussian sphere of ORACLES.md, n = 1 + A exp(-r^2/s^2), A = 1e-4, s = 0.25,
on 64^3 over [-1, 1]^3 (metres), beam along -z, knife normal along film x (KnifeAngle 0): light
bent toward -x passes, so the source's image moves toward the open side by s = -f2 eps_x. Photons
start at pixel centres (Jitter off), one pass, the film on the volume's back face: each pixel holds
one photon, whose deflection is the pixel's `deflection`, so the image can be checked against the
closed form of that deflection to float precision, and against the sphere's analytic deflection to
the grid's sampling error.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_bench")

A, S = 1e-4, 0.25
EMAX = st.gaussian_max_deflection(A)
FLOAT = 2.0 ** -24

sphere = RefractiveScene(Scene="GaussianSphere", Dimensions=[64, 64, 64], Amplitude=A, Width=S)
film = dict(Resolution=[40, 40], Passes=1, Jitter=0, Backend="CPU", Cutoff="KnifeEdge")


def fields_of(data):
    fd = data.GetFieldData()
    out = {}
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        out[a.GetName()] = [a.GetValue(k) for k in range(a.GetNumberOfValues())]
    return out


def image(proxy):
    data = sm.Fetch(proxy)
    X, Y, I, D, _ = st.image_arrays(data)
    return X, Y, I, D, fields_of(data)


def disc_share(t):
    t = np.clip(t, -1.0, 1.0)
    return (np.arccos(t) - t * np.sqrt(1 - t * t)) / math.pi


# ---------------------------------------------------------------- 1. slit at 50 %: linear
# h = 1 mm, f1 = f2 = 1 m: a0 = 1 mm, a = 0.5 mm; the range +-5e-4 rad holds the sphere's
# largest deflection 1.52e-4, so I = (a + s) / a0 = 0.5 - f2 eps_x / a0 everywhere.
slit = SchlierenImage(Input=sphere, Source="Slit", SourceSize=[1.0, 5.0], CollimatorFocalLength=1.0,
                      SchlierenFocalLength=1.0, KnifeCut=0.5, **film)
X, Y, I, D, F = image(slit)
a0, a, f2 = 1e-3, 0.5e-3, 1.0
expected = (a - f2 * D[..., 0]) / a0
# the weight is a float expression of values of order 1 (a few roundings)
T.close(I, expected, 16 * FLOAT, "slit, 50 %: I == (a + f2 eps) / a0 of each pixel's deflection")
# against the sphere's closed-form deflection: the trilinear grid's error, at most 3.8 % of the
# largest deflection (ORACLES.md), times f2 / a0
eps = st.gaussian_deflection(X, Y, A, S)
T.close(I, 0.5 - f2 * eps[..., 0] / a0, 0.038 * EMAX * f2 / a0,
        "slit, 50 %: I == 0.5 - f2 eps_x / a0 of the sphere's analytic deflection")
T.close(F["bench_sensitivity"][0], f2 / a, 1e-9 * f2 / a, "field data bench_sensitivity == f2 / a")
T.close(F["bench_range"], [-a / f2, (a0 - a) / f2], 1e-12, "field data bench_range == (-a / f2, (a0 - a) / f2)")
T.close(F["bench_resolvable_deflection"][0], a0 / (255 * f2), 1e-12,
        "field data bench_resolvable_deflection == a0 / ((2^8 - 1) f2)")
T.check(F["bench_saturated_share"][0] == 0 and F["bench_dark_share"][0] == 0, "nothing saturated or dark in range")
T.check("closed form" in F["bench_model"][0] and "not sampled" in F["bench_model"][0],
        "bench_model says the response is computed, not sampled: %s" % F["bench_model"][0])
T.check(F["warnings"][0] == "", "no warning in range (got %r)" % F["warnings"][0])

# ---------------------------------------------------------------- 2. a short range: saturation
# h = 0.2 mm, f1 = 2 m, f2 = 1 m: a0 = 0.1 mm; 10 % cut leaves a = 0.09 mm, saturation at
# eps = (a0 - a) / f2 = 1e-5 rad toward the open side, reached around the sphere's flank.
slit.SourceSize = [0.2, 0.2]
slit.CollimatorFocalLength = 2.0
slit.KnifeCut = 0.1
slit.BitDepth = 12
X, Y, I, D, F = image(slit)
a0, a = 0.1e-3, 0.09e-3
shift = -f2 * D[..., 0]
T.close(I, np.clip((a + shift) / a0, 0, 1), 16 * FLOAT, "slit, 10 % cut: I == clamp((a + f2 eps) / a0)")
margin = 1e-3 * (a0 - a)
saturated = np.mean(shift >= (a0 - a) + margin)
maybe = np.mean(shift >= (a0 - a) - margin)
share = F["bench_saturated_share"][0]
T.check(saturated <= share <= maybe and share > 0.01,
        "bench_saturated_share %.4f == the pixels with f2 eps >= a0 - a (%.4f to %.4f)" % (share, saturated, maybe))
T.close(F["bench_dark_share"][0], np.mean(shift <= -a), 1.5 / I.size, "bench_dark_share == the pixels with f2 eps <= -a")
T.check("saturated" in F["warnings"][0] and "SaturationWarning" in F["warnings"][0],
        "a warning names the saturated share: %r" % F["warnings"][0])
T.close(F["bench_resolvable_deflection"][0], a0 / (4095 * f2), 1e-14, "12 bits: a0 / (4095 f2)")
slit.SaturationWarning = 0.9
F = image(slit)[4]
T.check(F["warnings"][0] == "", "no warning below SaturationWarning 0.9 (got %r)" % F["warnings"][0])

# ---------------------------------------------------------------- 3. disc and Gaussian
# pinhole of 1 mm, f1 = f2 = 1 m: R' = 0.5 mm; at 50 % the edge is on the centre, t = -s / R'
disc = SchlierenImage(Input=sphere, Source="Disc", SourceSize=[1.0, 1.0], KnifeCut=0.5, **film)
X, Y, I, D, F = image(disc)
R = 0.5e-3
T.close(I, disc_share(f2 * D[..., 0] / R), 16 * FLOAT, "disc, 50 %: I == F(t), t = -f2 eps / R'")
T.close(F["bench_sensitivity"][0], 4 / math.pi * f2 / R, 1e-6 * 4 / math.pi * f2 / R,
        "disc, 50 %: bench_sensitivity == (4 / pi) f2 / R'")
# Gaussian of 1/e^2 diameter 2 mm: sigma' = 0.5 mm, 50 %: I = erfc(-s / (sigma sqrt 2)) / 2
disc.Source = "Gaussian"
disc.SourceSize = [2.0, 2.0]
X, Y, I, D, F = image(disc)
sig = 0.5e-3
erfc = np.vectorize(math.erfc)
T.close(I, 0.5 * erfc(f2 * D[..., 0] / (sig * math.sqrt(2))), 16 * FLOAT, "Gaussian, 50 %: I == erfc(-s / (sigma sqrt 2)) / 2")
T.close(F["bench_sensitivity"][0], f2 / (sig * math.sqrt(2 * math.pi)) / 0.5, 1e-6 * 1600,
        "Gaussian, 50 %: bench_sensitivity == f2 pdf(0) / 0.5")
Delete(disc)
Delete(slit)

# ---------------------------------------------------------------- 4. Point unchanged
ref = sm.Fetch(SchlierenImage(Input=sphere, **film))
Ir = st.image_arrays(ref)[2]
point = SchlierenImage(Input=sphere, Source="Point", SourceSize=[3, 4], CollimatorFocalLength=0.4,
                       SchlierenFocalLength=3, KnifeCut=0.8, **film)
data = sm.Fetch(point)
T.check(np.array_equal(st.image_arrays(data)[2], Ir), "Point: the bench's settings leave the image bit for bit")
T.check("bench_model" not in fields_of(data), "Point: no bench read-outs in the field data")

# ---------------------------------------------------------------- 5. errors name the property
for prop, value, needle in (("KnifeCut", 1.0, "KnifeCut"), ("CollimatorFocalLength", 0.0, "CollimatorFocalLength"),
                            ("SchlierenFocalLength", -1.0, "SchlierenFocalLength"), ("SourceSize", [0.0, 1.0], "SourceSize"),
                            ("BitDepth", 40, "BitDepth")):
    bad = SchlierenImage(Input=sphere, Source="Slit", **film)
    setattr(bad, prop, value)
    with st.CapturedOutput() as out:
        data = sm.Fetch(bad)
    T.check("ERROR" in out.text and needle in out.text and data.GetNumberOfPoints() == 0,
            "%s = %r: an error naming it, no image" % (prop, value))
    Delete(bad)

T.finish()
