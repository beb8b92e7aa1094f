# SPDX-License-Identifier: BSD-3-Clause
"""NumericalSchlieren (Quirk's grey scale of the density gradient) against closed forms.

1. A linear density ramp rho = 1.2 + 0.3 x + 0.4 y (a named array, DensityArray): |grad rho| = 0.5
   and its knife components 0.3 (KnifeAngle 0) and 0.4 (90) at every pixel, exact for central
   differences (float rounding: 1e-5 relative); the grey exp(-K S) at given C0, C1, K and
   GradientMaximum against the formula; the automatic maximum saturates a uniform gradient
   (S = 1: exp(-K)).
2. The Gaussian sphere (density = A/K_air exp(-r^2/s^2), s = 0.25, on 128^3 points over
   [-0.6, 0.6]^3, h = 0.0094 = 0.038 s) on the slice through its centre: |grad rho| =
   (2 A / (K s^2)) r exp(-r^2/s^2) at every pixel within 1 % of its maximum (central differences and
   the trilinear interpolation of the point gradient are second order: errors of a few (h/s)^2 =
   0.14 % of the largest; 1 % leaves room for the float field); its largest at r = s / sqrt(2)
   within 1 % of s (a parabola through the binned radial profile); the automatic maximum within
   1 % of the closed form's; at r = 2.3, 2.5 and 2.8 s (the scale's unsaturated tail: q below 5 %
   of qmax) the grey is exp(-K S) of the image's q, and with qmax fixed at the closed form's, q and
   the grey against the closed form's within twice the point's second-order error
   (1/6 + 1/8) h^2 |f'''(r)| (the grey's through its slope K I / ((C1 - C0) qmax)).
3. Its line-of-sight average along z: the signed knife component's mean against the closed form
   (1/L) * (-2 x / s^2)(A/K) exp(-rho^2/s^2) sqrt(pi) s erf(Z/s), L = 2 Z the box's depth; the
   magnitude's mean against the integral of the closed form along each line (numerical quadrature,
   4001 points); both within 1 % of their largest. The mean knife component times L K is the
   straight-ray deflection (n - 1 = K rho): against SchlierenImage's Integrator Straight on the same
   film within 1 % of its largest.
4. Bad settings are errors naming the property (C0, SliceOffset with its range, DensityArray,
   Mode), and every range domain of the proxy in Plugin/Schlieren.xml is enforced: its ends
   accepted, just past them an error naming the property (Resolution's upper end, 16384 x 16384
   pixels, is MakeFilm's check shared with SchlierenImage and left out: minutes and GiBs; the
   whole survey: domain_survey.py --proxies NumericalSchlieren).
5. Plain VTK Python (`from schlieren_vtk import vtkNumericalSchlieren`) gives the proxy's image.
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_numerical")
K_AIR = 2.256e-4  # m^3/kg, the scenes' Gladstone-Dale constant (air)


def fetch(proxy):
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy)
    return data, out.text


def arrays(data):
    nx, ny, _ = data.GetDimensions()
    ox, oy, _ = data.GetOrigin()
    hx, hy, _ = data.GetSpacing()
    X, Y = np.meshgrid(ox + hx * np.arange(nx), oy + hy * np.arange(ny))
    pd = data.GetPointData()
    get = lambda n: vtk_to_numpy(pd.GetArray(n)).reshape(ny, nx).astype(float)
    fd = data.GetFieldData()
    fields = {fd.GetAbstractArray(i).GetName(): fd.GetAbstractArray(i).GetVariantValue(0).ToString()
              for i in range(fd.GetNumberOfArrays())}
    return X, Y, get("intensity"), get("numerical_gradient"), fields


def quirk(q, qmax, c0, c1, k):
    return np.exp(-k * np.clip((q - c0 * qmax) / ((c1 - c0) * qmax), 0.0, 1.0))


# 1. The linear ramp.
scene = RefractiveScene(Scene="Uniform", Dimensions=[17, 13, 9], Bounds=[-1, 1, -0.5, 0.5, -0.4, 0.4])
ramp = Calculator(Input=scene, ResultArrayName="ramp", Function="1.2 + 0.3 * coordsX + 0.4 * coordsY")
ns = NumericalSchlieren(Input=ramp, DensityArray="ramp", Resolution=[40, 20])
data, text = fetch(ns)
X, Y, I, q, fields = arrays(data)
T.check("ERROR" not in text, "ramp: no error %s" % text.strip()[:300])
T.check(fields.get("numerical_field") == "ramp", "ramp: the named array is used: %s" % fields.get("numerical_field"))
T.close(q / 0.5, 1.0, 1e-5, "ramp: |grad rho| = 0.5 at every pixel (relative)")
T.close(I, math.exp(-5.0), 1e-6, "ramp: a uniform gradient under the automatic maximum saturates: exp(-K)")
for angle, expected in ((0.0, 0.3), (90.0, 0.4), (180.0, -0.3)):
    ns.Gradient = "KnifeComponent"
    ns.KnifeAngle = angle
    _, _, _, qk, _ = arrays(fetch(ns)[0])
    T.close(qk / expected, 1.0, 1e-5, "ramp: the knife component at %g deg = %g (relative)" % (angle, expected))
ns.Gradient = "Magnitude"
for c0, c1, k, qmax in ((-0.001, 0.05, 5.0, 20.0), (-0.5, 1.0, 2.0, 0.8), (0.0, 0.2, 10.0, 4.0)):
    ns.C0, ns.C1, ns.K, ns.GradientMaximum = c0, c1, k, qmax
    _, _, Ik, _, f = arrays(fetch(ns)[0])
    T.close(Ik, quirk(0.5, qmax, c0, c1, k), 2e-6, "ramp: the grey at C0 %g, C1 %g, K %g, qmax %g against "
            "exp(-K S)" % (c0, c1, k, qmax))
    T.close(float(f["gradient_maximum"]), qmax, 1e-9, "ramp: the fixed maximum is the one used")
Delete(ns)
Delete(ramp)

# 2. The Gaussian sphere on the slice through its centre.
A, s = 1e-4, 0.25
scene = RefractiveScene(Scene="GaussianSphere", Amplitude=A, Width=s, Dimensions=[128] * 3, Bounds=[-0.6, 0.6] * 3)
ns = NumericalSchlieren(Input=scene, Resolution=[121, 121])
data, text = fetch(ns)
T.check("ERROR" not in text, "sphere: no error %s" % text.strip()[:300])
X, Y, I, q, fields = arrays(data)
T.check(fields.get("numerical_field") == "density", "sphere: the density array is used (not n - 1)")
R = np.hypot(X, Y)
exact = 2 * A / (K_AIR * s * s) * R * np.exp(-(R / s) ** 2)
qmax = math.sqrt(2.0) * A * math.exp(-0.5) / (K_AIR * s)
T.close(q / qmax, exact / qmax, 0.01, "sphere slice: |grad rho| against the closed form (of its largest)")
print("sphere slice: largest error %.3g of the largest (h/s = %.3f)" % (
    float(np.max(np.abs(q - exact))) / qmax, 1.2 / 127 / s))
T.close(float(fields["gradient_maximum"]) / qmax, 1.0, 0.01, "sphere slice: the automatic maximum against "
        "sqrt(2) A e^-1/2 / (K s)")
bins = np.linspace(0.5 * s, 0.9 * s, 17)
idx = np.digitize(R.ravel(), bins)
rc = np.array([R.ravel()[idx == b].mean() for b in range(1, len(bins))])
qc = np.array([q.ravel()[idx == b].mean() for b in range(1, len(bins))])
c2, c1_, _ = np.polyfit(rc, qc, 2)
peak = -c1_ / (2 * c2)
T.close(peak / s, 1 / math.sqrt(2.0), 0.01, "sphere slice: the largest |grad rho| at r = %.4f s against s/sqrt(2)" % (peak / s))
qm = float(fields["gradient_maximum"])
for rr in (2.3, 2.5, 2.8):
    j, i = np.unravel_index(np.argmin(np.abs(R - rr * s)), R.shape)
    T.close(I[j, i], quirk(q[j, i], qm, -0.001, 0.05, 5.0), 1e-6, "sphere slice: the grey is exp(-K S) of the "
            "image's own q at r = %.2f s" % (R[j, i] / s))
# The grey against the closed form's, with qmax fixed at the closed form's: the tail's grey is steep
# in q (dI/dq = K I / ((C1 - C0) qmax)), so its tolerance comes from the point's own second-order
# error, (1/6 + 1/8) h^2 |f'''| (central difference, then trilinear interpolation; f the radial
# profile), doubled.
ns.GradientMaximum = qmax
X, Y, I, q, fields = arrays(fetch(ns)[0])
h = 1.2 / 127
for rr in (2.3, 2.5, 2.8):
    j, i = np.unravel_index(np.argmin(np.abs(R - rr * s)), R.shape)
    u = R[j, i] / s
    f3 = A / K_AIR / s ** 3 * abs(-8 * u ** 3 + 12 * u) * math.exp(-u * u)
    tol_q = 2 * (1 / 6 + 1 / 8) * h * h * f3
    expected = float(quirk(exact[j, i], qmax, -0.001, 0.05, 5.0))
    T.close(q[j, i], exact[j, i], tol_q, "sphere slice: |grad rho| at r = %.2f s (q = %.4f qmax) within its "
            "second-order error" % (u, exact[j, i] / qmax))
    T.close(I[j, i], expected, 5 * expected * tol_q / (0.051 * qmax) + 1e-6, "sphere slice: the grey at "
            "r = %.2f s against Quirk's grey of the closed form (%.4f, unsaturated)" % (u, expected))
ns.GradientMaximum = 0

# 3. The line-of-sight average along z.
Z = 0.6
ns.Mode = "LineOfSight"
ns.Gradient = "KnifeComponent"
data, text = fetch(ns)
X, Y, I, qk, fields = arrays(data)
R = np.hypot(X, Y)
mean_exact = (-2 * X / s ** 2) * (A / K_AIR) * np.exp(-(R / s) ** 2) * math.sqrt(math.pi) * s * math.erf(Z / s) / (2 * Z)
big = float(np.max(np.abs(mean_exact)))
T.close(qk / big, mean_exact / big, 0.01, "sphere, line of sight: the mean knife component against its closed form")
ns.Gradient = "Magnitude"
X, Y, I, qa, fields = arrays(fetch(ns)[0])
z = np.linspace(-Z, Z, 4001)
Rs = np.sqrt(X[..., None] ** 2 + Y[..., None] ** 2 + z ** 2)
integral = np.trapz(2 * A / (K_AIR * s * s) * Rs * np.exp(-(Rs / s) ** 2), z, axis=-1) / (2 * Z)
T.close(qa / integral.max(), integral / integral.max(), 0.01, "sphere, line of sight: the mean |grad rho| "
        "against the integral of the closed form")
image = SchlierenImage(Input=scene, Integrator="Straight", Cutoff="KnifeEdge", Resolution=[121, 121], Passes=1,
                       Jitter=0, Backend="CPU")
_, _, _, deflection, _ = st.image_arrays(fetch(image)[0])
ex = deflection[..., 0]
T.close(qk * 2 * Z * K_AIR / np.abs(ex).max(), ex / np.abs(ex).max(), 0.01, "sphere: the mean knife component x "
        "L K against SchlierenImage's straight-ray deflection on the same film (of its largest)")
Delete(image)

# 4. Bad settings: errors naming the property.
ns.Mode = "Slice"
for prop, value, words in (("C0", 0.5, ["C0", "[-1, 0]"]), ("SliceOffset", 0.7, ["SliceOffset", "-0.6", "0.6"]),
                           ("DensityArray", "nothing", ["DensityArray", "nothing"]), ("K", 0.0, ["K is 0"])):
    old = getattr(ns, prop)
    setattr(ns, prop, value)
    data, text = fetch(ns)
    T.check("ERROR" in text and all(w in text for w in words), "%s = %r: an error naming it: %s" % (
        prop, value, [l for l in text.splitlines() if prop in l][:1]))
    setattr(ns, prop, old)
ns.GetProperty("Mode").SetData(5)
data, text = fetch(ns)
T.check("Mode is 5" in text, "Mode 5: an error naming it")
ns.Mode = "Slice"
data, text = fetch(ns)
T.check("ERROR" not in text and data.GetNumberOfPoints() == 121 * 121, "the filter recovers once the settings are good")
Delete(ns)

import xml.etree.ElementTree as ET
root = ET.parse(os.path.join(HERE, "..", "..", "Plugin", "Schlieren.xml")).getroot()
proxy = [p for p in root.iter("SourceProxy") if p.get("name") == "NumericalSchlieren"][0]
small = RefractiveScene(Dimensions=[12] * 3)
surveyed = 0
for prop in proxy:
    dom = prop.find("DoubleRangeDomain")
    dom = prop.find("IntRangeDomain") if dom is None else dom
    if dom is None:
        continue
    name, n = prop.get("name"), int(prop.get("number_of_elements", "1"))
    isint = prop.tag == "IntVectorProperty"
    for which in ("min", "max"):
        if dom.get(which) is None or (name == "Resolution" and which == "max"):
            continue
        end = float(dom.get(which).split()[0])
        step = 1 if isint else max(abs(end) * 1e-3, 1e-9)
        for label, v in (("at", end), ("past", end - step if which == "min" else end + step)):
            v = int(v) if isint else v
            p = NumericalSchlieren(Input=small, Resolution=[8, 8])
            setattr(p, name, [v] * n if n > 1 else v)
            _, text = fetch(p)
            ok = ("ERROR" not in text) if label == "at" else ("ERROR" in text and name in text)
            T.check(ok, "domain: %s %s its %s (%s): %s" % (name, label, which, v, "accepted" if label == "at"
                    else "an error naming it"))
            surveyed += 1
            Delete(p)
T.check(surveyed >= 20, "domain: %d settings of the XML's range domains tried" % surveyed)

# 5. Plain VTK Python: vtkNumericalSchlieren from the schlieren package, the same image as the proxy's.
from schlieren_vtk import vtkNumericalSchlieren, vtkRefractiveScene  # noqa: E402

vscene = vtkRefractiveScene()
vscene.SetSceneToGaussianSphere()
vscene.SetDimensions(40, 40, 40)
vns = vtkNumericalSchlieren()
vns.SetInputConnection(vscene.GetOutputPort())
vns.SetResolution(30, 30)
vns.SetMode(vtkNumericalSchlieren.LINE_OF_SIGHT)
vns.Update()
proxy = NumericalSchlieren(Input=RefractiveScene(Scene="GaussianSphere", Dimensions=[40] * 3), Resolution=[30, 30],
                           Mode="LineOfSight")
_, _, Ip, qp, _ = arrays(fetch(proxy)[0])
_, _, Iv, qv, fv = arrays(vns.GetOutput())
T.check(qp.max() > 0, "VTK Python: the sphere's gradient is seen")
T.close(qv, qp, 0.0, "VTK Python: vtkNumericalSchlieren's numerical_gradient equals the proxy's")
T.close(Iv, Ip, 0.0, "VTK Python: and its intensity")
T.finish()
