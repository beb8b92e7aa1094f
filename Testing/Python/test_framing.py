# SPDX-License-Identifier: BSD-3-Clause
"""Framing Silhouette through the plugin (docs/GUI.md "Framing"): the film framed to the data.

Run: pvpython test_framing.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so

- The blunt fin as a GUI user opens it (PLOT3DReader -> RefractiveIndex with its defaults ->
  SchlierenImage, 256 x 256, seen from the side): Framing Volume puts the 22 x 5.7 box on a square
  film (most rays miss the box); Silhouette frames the box in its own shape with as many pixels,
  no ray missing it, the pixels smaller by sqrt(aspect) (closed form), the output's information
  (whole extent) the image's.
- A small Gaussian blob in a large box: the frame is its disc where |grad n| > 1e-3 of the
  largest (the radius from the closed form), and the image fills the film.
- The frame is kept while only the view, Resolution or Passes change (what Follow Camera
  changes), and found again after any other change.
- A bad Framing is refused by name; Framing Volume gives the images of before bit for bit.
The frame's arithmetic is asserted on the engine by engine.TestEngineFraming.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import cfd_testing
import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_framing")


def fields_of(data):
    fd = data.GetFieldData()
    out = {}
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        out[a.GetName()] = [a.GetValue(k) for k in range(a.GetNumberOfValues())]
    return out


def fetch(proxy):
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy)
    return data, fields_of(data), out.text


# ---------------------------------------------------------------- 1. the blunt fin, from the side
folder = cfd_testing.data_dir()
xyz, q = os.path.join(folder, "bluntfinxyz.bin"), os.path.join(folder, "bluntfinq.bin")
if os.path.exists(xyz) and os.path.exists(q):
    reader = PLOT3DReader(FileName=xyz, QFileName=[q])
    index = RefractiveIndex(Input=reader)
    index.InputArray = ["POINTS", "Density"]
    side = dict(Resolution=[256, 256], Passes=1, ViewDirection=[0, 1, 0], ViewUp=[0, 0, 1],
                Backend="CPU")
    vol = SchlierenImage(Input=index, Framing="Volume", **side)
    dv, Fv, _ = fetch(vol)
    sil = SchlierenImage(Input=index, Framing="Silhouette", **side)
    ds, Fs, _ = fetch(sil)
    b = index.GetDataInformation().GetBounds()
    aspect = (b[1] - b[0]) / (b[5] - b[4])  # film x is world x, film y world z
    nx, ny, _ = ds.GetDimensions()
    print("fin: box %.3f x %.3f (aspect %.3f); Volume %s, Silhouette %s, pixels %.5f -> %.5f"
          % (b[1] - b[0], b[5] - b[4], aspect, dv.GetDimensions()[:2], (nx, ny),
             dv.GetSpacing()[0], ds.GetSpacing()[0]))
    T.check(dv.GetDimensions()[:2] == (256, 256), "Framing Volume: Resolution's film")
    T.check(abs(nx / ny - aspect) <= aspect / ny + 1e-9,
            "Silhouette: the film has the box's shape, %d x %d for aspect %.3f" % (nx, ny, aspect))
    T.check(abs(nx * ny - 65536) <= 0.01 * 65536, "Silhouette: as many pixels as 256 x 256 (%d)" % (nx * ny))
    T.close(dv.GetSpacing()[0] / ds.GetSpacing()[0], math.sqrt(aspect), 0.01 * math.sqrt(aspect),
            "Silhouette: pixels sqrt(aspect) smaller (the shock that much larger on the film)")
    T.check(Fv["missed_rays"][0] > 0.6 * Fv["photons"][0],
            "Framing Volume: most rays miss the box (%d of %d)" % (Fv["missed_rays"][0], Fv["photons"][0]))
    # the film's shape is the box's to a pixel: at most a row or column of pixels lies beyond it
    T.check(Fs["missed_rays"][0] <= nx + ny,
            "Silhouette: at most a pixel's strip misses the box (%d rays)" % Fs["missed_rays"][0])
    T.check(Fs["film_frame_share"] == [1.0] and Fs["film_frame_kept"] == [0.0] and
            len(Fs["film_extent"]) == 4,
            "the fin's flow fills its box: the frame is the box (film_extent %s)" % Fs["film_extent"])
    info = sil.GetDataInformation().GetExtent()
    T.check(tuple(info[:4]) == (0, nx - 1, 0, ny - 1),
            "the output's information is the framed film's (extent %s)" % (info,))
    for p in (vol, sil, index, reader):
        Delete(p)
else:
    print("SKIP part 1: the blunt fin is not in %s (set SCHLIEREN_DATA)" % folder)

# ---------------------------------------------------------------- 2. a small blob in a large box
S, C = 0.1, (0.3, -0.2, 0.1)
blob = RefractiveScene(Scene="GaussianSphere", Dimensions=[81, 81, 81], Amplitude=1e-4, Width=S,
                       Center=list(C), Bounds=[-1, 1, -1, 1, -1, 1])
film = dict(Resolution=[64, 64], Passes=2, Backend="CPU", Integrator="RK4", Cutoff="KnifeEdge")
img = SchlierenImage(Input=blob, Framing="Silhouette", **film)
d, F, text = fetch(img)
lo, hi = S / math.sqrt(2), 10 * S  # the radius where |grad| falls to 1e-3 of its largest
target = 1e-3 * lo * math.exp(-0.5)
for _ in range(200):
    mid = 0.5 * (lo + hi)
    lo, hi = (mid, hi) if mid * math.exp(-mid * mid / S / S) > target else (lo, mid)
rt, h = 0.5 * (lo + hi), 2.0 / 80
pad = h + 0.04 * rt
e = F["film_extent"]
print("blob: r_t = %.4f, film_extent %s, share %s" % (rt, e, F["film_frame_share"]))
T.close(e, [C[0] - rt - pad, C[0] + rt + pad, C[1] - rt - pad, C[1] + rt + pad], h,
        "the blob's frame: its disc of radius r_t = %.3f (closed form), padded" % rt)
T.close(F["film_frame_share"][0], (2 * (rt + pad)) ** 2 / 4, 0.1 * (2 * (rt + pad)) ** 2 / 4,
        "the frame's share of the box's projection")
X, Y, I, _, _ = st.image_arrays(d)
border = np.concatenate([I[0], I[-1], I[:, 0], I[:, -1]])
T.check(np.max(np.abs(I - 0.5)) > 0.3 and np.max(np.abs(border - 0.5)) < 0.02,
        "the blob fills the film: full contrast inside (%.3f), grey at the border (%.4f)"
        % (np.max(np.abs(I - 0.5)), np.max(np.abs(border - 0.5))))

# ---------------------------------------------------------------- 3. kept while the camera moves
img.ViewDirection = [0.3, -0.2, -1.0]
img.ViewUp = [0, 1, 0.1]
img.Resolution = [32, 32]
img.Passes = 1
d2, F2, _ = fetch(img)
T.check(F2["film_frame_kept"] == [1.0] and F2["film_extent"] == e and d2.GetDimensions()[:2] == (32, 32),
        "a camera move, a half film and fewer passes keep the frame (%s)" % F2["film_extent"])
img.Cutoff = "Shadowgraph"
d3, F3, _ = fetch(img)
T.check(F3["film_frame_kept"] == [0.0] and F3["film_extent"] != e,
        "another property changed (an Apply): framed again for the view of now (%s)" % F3["film_extent"])
Delete(img)

# ---------------------------------------------------------------- 4. errors; Volume as before
bad = SchlierenImage(Input=blob, **film)
bad.GetProperty("Framing").SetData(7)
with st.CapturedOutput() as out:
    bad.UpdatePipeline()
T.check("Framing is 7" in out.text and "Silhouette" in out.text,
        "Framing 7 is refused by name: %s" % out.text.strip()[:160])
Delete(bad)
plain = SchlierenImage(Input=blob, **film)
a, Fa, _ = fetch(plain)
vol = SchlierenImage(Input=blob, Framing="Volume", **film)
b_, Fb, _ = fetch(vol)
T.check(np.array_equal(st.image_arrays(a)[2], st.image_arrays(b_)[2]) and "film_extent" not in Fb,
        "Framing Volume (the default) is the image of before bit for bit, without film_extent")
T.finish()
