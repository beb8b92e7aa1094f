# SPDX-License-Identifier: BSD-3-Clause
"""SchlierenImage's Reconstruction through the pipeline, at shocks (the fourth-order scheme must
keep the trilinear one beside jumps): what each check asserts, with its bound.

The normal shock (RefractiveScene NormalShock, Mach 2, 64^3 on [-1, 1]^3, Width one voxel: a
shock two voxels thick in the plane x = 0), beam along -z (edge-on), film pixel a quarter voxel,
no jitter, line of sight at half a voxel:
  - Cubic against Trilinear: the deflection peaks at the same film column, with the same size
    (0.5 %); its integral across x, the jump of the index times the path, is the same (0.5 %); the
    deflection of the wrong sign (ringing beside the shock) grows by no more than 0.5 % of the peak;
  - the field data says which reconstruction was used, and Auto picks one;
  - beam at 40 degrees through the shock, Euler: Trilinear at 8 voxels jumps the shock and the image
    says so (underresolved_rays > 0); Cubic at StepSize 8 takes steps of a voxel from the cells near
    the shock, so no ray is flagged and the image is that of Trilinear at one voxel (1 % of its
    largest deflection).
The NASA blunt fin (from ../shared/data or $SCHLIEREN_DATA; that part is skipped with a message
where the data is absent), resampled as in test_cfd_data.py, seen from above: on film rows
y = 0.3, 1, 2, 3, 4 the bow shock (largest |deflection_x|) is at the same place with Cubic as with
Trilinear (within half a voxel), its peak within 5 %, and ahead of the shock (upstream, more than
three voxels) Cubic's largest |deflection| exceeds Trilinear's by no more than 1 % of the row's
peak; Trilinear at 8 voxels is flagged, Cubic at StepSize 8 is not, and its shock stays within
half a voxel.

Run: pvpython test_reconstruction.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import cfd_testing as ct
import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_reconstruction")


def image(source, **props):
    img = SchlierenImage(Input=source, Passes=1, Jitter=0, Cutoff="KnifeEdge", KnifeAngle=0.0, **props)
    with st.CapturedOutput() as out:
        img.UpdatePipeline()
        data = sm.Fetch(img)
    T.check("ERROR" not in out.text, "%s: no error%s" % (props.get("Reconstruction", "Trilinear"),
                                                        "" if "ERROR" not in out.text else ": " + out.text[:300]))
    X, Y, I, D, F = st.image_arrays(data)
    Delete(img)
    return X[0], Y[:, 0], D, F


# ================================================================ the normal shock, edge-on
n = 64
h = 2.0 / (n - 1)
shock = RefractiveScene(Scene="NormalShock", Dimensions=[n] * 3, Bounds=[-1, 1] * 3, Width=h, Mach=2.0)
edge = dict(ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], Resolution=[8 * (n - 1), 8],
            Integrator="Straight", StepSize=0.5)
res = {}
for rc in ("Trilinear", "Cubic"):
    X, Y, D, F = image(shock, Reconstruction=rc, **edge)
    T.check(F.get("reconstruction") == rc, "%s: the field data says reconstruction %s" % (rc, F.get("reconstruction")))
    row = D[D.shape[0] // 2, :, 0]
    res[rc] = (X, row)
X, t = res["Trilinear"]
_, c = res["Cubic"]
it, ic = int(np.argmax(abs(t))), int(np.argmax(abs(c)))
peak = abs(t[it])
jt, jc = np.trapz(t, X), np.trapz(c, X)
under_t = max(0.0, float((-np.sign(t[it]) * t).max()))
under_c = max(0.0, float((-np.sign(t[it]) * c).max()))
print("edge-on shock: peak %.5g / %.5g at x = %.4f / %.4f, integral %.5g / %.5g, wrong-sign %.3g / %.3g of "
      "the peak (Trilinear / Cubic)" % (t[it], c[ic], X[it], X[ic], jt, jc, under_t / peak, under_c / peak))
T.check(it == ic, "the deflection peaks on the same film column (%d, %d)" % (it, ic))
T.close(c[ic] / t[it], 1.0, 0.005, "the same peak deflection")
T.close(jc / jt, 1.0, 0.005, "the same jump (the deflection's integral across the shock)")
T.check(under_c <= under_t + 0.005 * peak, "no new ringing beside the shock (%.3g, %.3g of the peak)"
        % (under_t / peak, under_c / peak))

al = math.radians(40.0)
tilted = dict(ViewDirection=[math.sin(al), 0, -math.cos(al)], ViewUp=[0, 1, 0], Resolution=[48, 48],
              Integrator="Euler")
_, _, Dref, Fref = image(shock, Reconstruction="Trilinear", StepSize=1.0, **tilted)
_, _, Dlong, Flong = image(shock, Reconstruction="Trilinear", StepSize=8.0, **tilted)
_, _, Dcub, Fcub = image(shock, Reconstruction="Cubic", StepSize=8.0, **tilted)
big = abs(Dref[..., 0]).max()
print("shock at 40 deg, flagged rays: Trilinear 1 voxel %d, Trilinear 8 voxels %d, Cubic 8 voxels %d; "
      "samples per ray %.1f, %.1f, %.1f" % (Fref["underresolved_rays"], Flong["underresolved_rays"],
                                            Fcub["underresolved_rays"], Fref["samples_per_ray"],
                                            Flong["samples_per_ray"], Fcub["samples_per_ray"]))
T.check(Flong["underresolved_rays"] > 0, "Trilinear at 8 voxels jumps the shock, and is flagged")
T.check(Fcub["underresolved_rays"] == 0, "Cubic at StepSize 8: no step jumps the shock")
T.close(Dcub[..., 0] / big, Dref[..., 0] / big, 0.01,
        "Cubic at StepSize 8 gives Trilinear's image at one voxel (of its largest deflection)")
auto = SchlierenImage(Input=shock, Passes=1, Jitter=0, Reconstruction="Auto", Integrator="Auto", **{
    k: v for k, v in tilted.items() if k != "Integrator"})
auto.UpdatePipeline()
Fa = st.image_arrays(sm.Fetch(auto))[4]
print("Auto on the shock: %s" % Fa.get("auto_report"))
T.check(Fa.get("reconstruction") in ("Trilinear", "Cubic") and "reconstruction" in Fa.get("auto_report", ""),
        "Auto reports the reconstruction it chose (%s)" % Fa.get("reconstruction"))
Delete(auto)

# ================================================================ the blunt fin
folder = ct.data_dir()
names = ("bluntfinxyz.bin", "bluntfinq.bin")
if not all(os.path.exists(os.path.join(folder, f)) for f in names):
    print("SKIP the blunt fin part: the shared CFD data is not there (%s); set SCHLIEREN_DATA to the "
          "folder that holds %s" % (folder, ", ".join(names)))
else:
    reader = PLOT3DReader(FileName=os.path.join(folder, names[0]), QFileName=[os.path.join(folder, names[1])])
    index = RefractiveIndex(Input=reader, Model="GladstoneDale", Gas="Air", DensityReference=1.2)
    index.InputArray = ["POINTS", "Density"]
    index.UpdatePipeline()
    grid = sm.Fetch(index)
    dims, hs = grid.GetDimensions(), grid.GetSpacing()
    top = dict(ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0], Resolution=[2 * dims[0], 2 * dims[1]],
               Integrator="Euler")
    X, Y, Dt, Ft = image(index, Reconstruction="Trilinear", StepSize=0.5, **top)
    _, _, Dc, Fc = image(index, Reconstruction="Cubic", StepSize=0.5, **top)
    _, _, Dt8, Ft8 = image(index, Reconstruction="Trilinear", StepSize=8.0, **top)
    _, _, Dc8, Fc8 = image(index, Reconstruction="Cubic", StepSize=8.0, **top)
    for yv in (0.3, 1.0, 2.0, 3.0, 4.0):
        j = int(np.argmin(abs(Y - yv)))
        rt, rc, rc8 = Dt[j, :, 0], Dc[j, :, 0], Dc8[j, :, 0]
        it, ic, ic8 = int(np.argmax(abs(rt))), int(np.argmax(abs(rc))), int(np.argmax(abs(rc8)))
        peak = abs(rt[it])
        ahead = X < X[it] - 3 * hs[0]
        over_t = float(np.hypot(Dt[j, ahead, 0], Dt[j, ahead, 1]).max()) if ahead.any() else 0.0
        over_c = float(np.hypot(Dc[j, ahead, 0], Dc[j, ahead, 1]).max()) if ahead.any() else 0.0
        print("blunt fin row y = %.1f: shock at x = %.3f / %.3f / %.3f (Trilinear, Cubic, Cubic at 8), "
              "peak %.4g / %.4g, ahead of it %.3g / %.3g of the peak"
              % (yv, X[it], X[ic], X[ic8], rt[it], rc[ic], over_t / peak, over_c / peak))
        T.check(abs(X[ic] - X[it]) <= 0.5 * hs[0], "row y = %.1f: Cubic puts the shock where Trilinear does" % yv)
        T.close(abs(rc[ic]) / peak, 1.0, 0.05, "row y = %.1f: the same peak (5 %%)" % yv)
        T.check(over_c <= over_t + 0.01 * peak, "row y = %.1f: no new overshoot ahead of the shock" % yv)
        T.check(abs(X[ic8] - X[it]) <= 0.5 * hs[0], "row y = %.1f: Cubic at StepSize 8 too" % yv)
    print("blunt fin, flagged rays: Trilinear at 8 voxels %d, Cubic at StepSize 8 %d (samples per ray "
          "%.1f, %.1f); Cubic's samples per ray at 0.5 voxel %.1f"
          % (Ft8["underresolved_rays"], Fc8["underresolved_rays"], Ft8["samples_per_ray"],
             Fc8["samples_per_ray"], Fc["samples_per_ray"]))
    T.check(Ft8["underresolved_rays"] > 0, "blunt fin: Trilinear at 8 voxels jumps the bow shock, and is flagged")
    T.check(Fc8["underresolved_rays"] == 0, "blunt fin: Cubic at StepSize 8 does not jump it")
T.finish()
