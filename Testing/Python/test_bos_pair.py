# SPDX-License-Identifier: BSD-3-Clause
"""Issue 51: the BOS image pair (docs/BENCH.md "BOS image pairs") from every front end, and its
bad inputs. The engine writes the files (schlieren::WriteBOSPair): the C++ filter's
WriteBOSPair (pvpython), the C interface through the Python package (schlieren.engine, in a
child of Debian's Python), the Python front end's SchlierenImage.WriteBOSPair (ParaView's
vtkmodules there) and `python -m schlieren bos` write the pair, the first three the same bytes for
the same film; bad input is one line, never a file: no BOS image, a folder that does not exist,
a bit depth not 8/16, an unknown format.

Run: pvpython test_bos_pair.py --plugin <Schlieren.so> --output DIR --python /usr/bin/python3
     (PYTHONPATH of the child: <source>/Python; SCHLIEREN_ENGINE_LIBRARY from the environment)

OpenPIV on the pair is python.bos_openpiv (Examples/bos_openpiv.py)."""
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403

import schlieren_testing as st
# the filters' Python wrapping: WriteBOSPair on the client-side object
import schlieren_vtk  # noqa: F401

st.load_plugin(globals())
T = st.Checker("test_bos_pair")
out = st.argument("--output")
python = st.argument("--python", "/usr/bin/python3")
source = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)

# 1. the C++ filter: a 64^3 Gaussian sphere, n - 1 = 1e-3, BOS 10 units behind the box
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[64, 64, 64], Amplitude=1e-3, Width=0.25)
bos = SchlierenImage(Input=scene, Cutoff="BOS", BackgroundDistance=10.0, Resolution=[96, 80],
                     Passes=2, Backend="CPU")
bos.UpdatePipeline()
f = bos.GetClientSideObject()
for bits, fmt in ((8, "png"), (16, "tiff")):
    d = os.path.join(out, "cpp%d" % bits)
    os.makedirs(d)
    T.check(f.WriteBOSPair(d, bits, fmt) == 1, "C++ WriteBOSPair(%d, %s): %s"
            % (bits, fmt, f.GetBOSPairMessage()))
    ext = ".png" if fmt == "png" else ".tif"
    T.check(sorted(os.listdir(d)) == sorted(["bos.json", "bos_background" + ext,
                                              "bos_recording" + ext]),
            "C++ %d-bit: bos.json, bos_background%s, bos_recording%s" % (bits, ext, ext))
side = json.load(open(os.path.join(out, "cpp8", "bos.json")))
T.check(side["width"] == 96 and side["height"] == 80 and side["bits"] == 8,
        "side file: 96 x 80, 8 bit (%r x %r)" % (side["width"], side["height"]))
T.close(side["bench"]["background_distance"], 10.0 + 1.001, 1e-9,
        "side file: Z_D = BackgroundDistance + 1.001 half-depths")
T.check(side["trace_report"]["backend"] == "CPU" and "+d" in side["displacement"]["sign"],
        "side file: the trace's report and the sign")
shift = side["displacement"]["max_pixels"]
T.check(shift > 0.5, "side file: the largest displacement %.3f px" % shift)
# the 16-bit PNG's grey levels round the same intensities as the 8-bit: > 255 levels in use
raw8 = open(os.path.join(out, "cpp8", "bos_recording.png"), "rb").read()
raw16 = open(os.path.join(out, "cpp16", "bos_recording.tif"), "rb").read()
T.check(raw8[:8] == b"\x89PNG\r\n\x1a\n" and raw16[:4] == b"II*\x00",
        "PNG and little-endian TIFF signatures")
T.check(len(raw16) > 2 * 96 * 80, "16-bit TIFF holds 2 bytes a pixel (%d bytes)" % len(raw16))

# VTK's readers read them: the 16-bit PNG and TIFF hold the same levels, the 8-bit PNG those
# rounded to 8 bits; the files' first row is the film's top (vtk readers flip it back to row 0 at
# the bottom, as the image's intensity)
from vtkmodules.vtkIOImage import vtkPNGReader, vtkTIFFReader  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from paraview import servermanager as sm  # noqa: E402

d16 = os.path.join(out, "cpp16png")
os.makedirs(d16)
T.check(f.WriteBOSPair(d16, 16, "png") == 1, "C++ WriteBOSPair(16, png)")


def read(reader, path):
    r = reader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    return vtk_to_numpy(img.GetPointData().GetScalars()).astype(float).reshape(
        img.GetDimensions()[1], img.GetDimensions()[0])


png16 = read(vtkPNGReader, os.path.join(d16, "bos_recording.png"))
tif16 = read(vtkTIFFReader, os.path.join(out, "cpp16", "bos_recording.tif"))
png8 = read(vtkPNGReader, os.path.join(out, "cpp8", "bos_recording.png"))
intensity = vtk_to_numpy(sm.Fetch(bos).GetPointData().GetArray("intensity")).reshape(80, 96)
# vtkTIFFReader does not flip a top-left TIFF (its OrientationType 1, the default, keeps the
# file's first row as row 0; PIL and imageio read it as PIV codes do: python.bos_openpiv)
T.check(png16.shape == (80, 96) and np.array_equal(png16, tif16[::-1]),
        "16-bit PNG and TIFF: the same levels (vtkPNGReader, vtkTIFFReader)")
T.close(png8, np.round(png16 / 65535 * 255), 0.5 + 1e-9, "8-bit PNG: the 16-bit levels rounded")
T.close(png16 / 65535, np.clip(intensity, 0, 1), 0.5 / 65535 + 1e-7,
        "16-bit levels: the image's intensity times 65535, rounded, row 0 at the bottom")

# bad input through the filter: one line each, nothing written
for args, words in (((os.path.join(out, "missing"), 8, "png"), "does not exist"),
                    ((out, 12, "png"), "use 8 or 16"),
                    ((out, 8, "jpeg"), "png or tiff")):
    T.check(f.WriteBOSPair(*args) == 0 and words in f.GetBOSPairMessage() and
            "\n" not in f.GetBOSPairMessage().strip(),
            "C++ WriteBOSPair%r refused: %s" % (args, f.GetBOSPairMessage()))
knife = SchlierenImage(Input=scene, Cutoff="KnifeEdge", Resolution=[32, 32], Passes=1,
                       Backend="CPU")
knife.UpdatePipeline()
k = knife.GetClientSideObject()
T.check(k.WriteBOSPair(out, 8, "png") == 0 and "not BOS" in k.GetBOSPairMessage(),
        "C++ WriteBOSPair of a knife-edge image refused: %s" % k.GetBOSPairMessage())
fresh = SchlierenImage(Input=scene, Cutoff="BOS")
T.check(fresh.GetClientSideObject().WriteBOSPair(out, 8, "png") == 0 and
        "no BOS image" in fresh.GetClientSideObject().GetBOSPairMessage(),
        "C++ WriteBOSPair before any update refused: %s"
        % fresh.GetClientSideObject().GetBOSPairMessage())
T.check(sorted(os.listdir(out)) == ["cpp16", "cpp16png", "cpp8"],
        "no file written by a refused call")

# 2. the C interface through the Python package, the same film: the same bytes
child = r'''
import sys, json
import numpy as np
from schlieren import engine
out = sys.argv[1]
dims, origin, spacing = [64] * 3, [-1.0] * 3, [2.0 / 63] * 3
n1 = engine.fill_scene(dict(Scene="GaussianSphere", Amplitude=1e-3, Width=0.25), dims, origin,
                       spacing)["n_minus_1"]
s = engine.Session()
s.set_volume(dims, origin, spacing, n1)
for k, v in dict(Cutoff="BOS", BackgroundDistance=10.0, Resolution=[96, 80], Passes=2,
                 Backend="CPU").items():
    s.set(k, v)
s.trace()
print(json.dumps(s.write_bos_pair(out + "/py8", 8, "png")))
print(json.dumps(s.write_bos_pair(out + "/py16", 16, "tiff")))
errors = []
for a in ((out + "/missing", 8, "png"), (out, 12, "png"), (out, 8, "bmp"), (out, "8", "png")):
    try:
        s.write_bos_pair(*a)
        errors.append("none")
    except engine.EngineError as e:
        errors.append(str(e))
s.set("Cutoff", "KnifeEdge")
s.trace()
try:
    s.write_bos_pair(out, 8, "png")
    errors.append("none")
except engine.EngineError as e:
    errors.append(str(e))
print(json.dumps(errors))
# the Python front end's VTK algorithm (ParaView's vtkmodules under Debian's Python)
import schlieren
scene = schlieren.RefractiveScene(Scene="GaussianSphere", Dimensions=[64, 64, 64], Amplitude=1e-3,
                                  Width=0.25)
img = schlieren.SchlierenImage(Cutoff="BOS", BackgroundDistance=10.0, Resolution=[96, 80],
                               Passes=2, Backend="CPU")
img.SetInputConnection(scene.GetOutputPort())
img.Update()
print(json.dumps(img.WriteBOSPair(out + "/vtk8", 8, "png")))
'''
for d in ("py8", "py16", "vtk8"):
    os.makedirs(os.path.join(out, d))
env = dict(os.environ, PYTHONPATH=os.path.join(source, "Python"))
p = subprocess.run([python, "-c", child, out], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                   env=env, timeout=300)
text = p.stdout.decode("utf-8", "replace")
T.check(p.returncode == 0, "the Python package's write_bos_pair ran (%s)" % text.strip()[-300:])
if p.returncode == 0:
    lines = text.strip().splitlines()
    errors = json.loads(lines[-2])
    for e, words in zip(errors, ("does not exist", "use 8 or 16", "png or tiff", "bits must be",
                                 "not BOS")):
        T.check(words in e and "\n" not in e, "Python write_bos_pair refused: %s" % e)
    for bits, ext in ((8, ".png"), (16, ".tif")):
        for name in ("bos_background", "bos_recording"):
            a = open(os.path.join(out, "cpp%d" % bits, name + ext), "rb").read()
            b = open(os.path.join(out, "py%d" % bits, name + ext), "rb").read()
            T.check(a == b, "C++ plugin and Python package: %s%s (%d bit) the same bytes"
                    % (name, ext, bits))
    for name in ("bos_background.png", "bos_recording.png"):
        T.check(open(os.path.join(out, "cpp8", name), "rb").read() ==
                open(os.path.join(out, "vtk8", name), "rb").read(),
                "C++ plugin and the Python front end's SchlierenImage.WriteBOSPair: %s the same "
                "bytes" % name)

# 3. python -m schlieren bos: the pair, and its bad arguments (one line, exit 2)
os.makedirs(os.path.join(out, "cli"))
p = subprocess.run([python, "-m", "schlieren", "bos", "--folder", os.path.join(out, "cli"),
                    "--resolution", "64", "--passes", "1", "--backend", "CPU", "--bits", "16"],
                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, timeout=300)
T.check(p.returncode == 0 and sorted(os.listdir(os.path.join(out, "cli"))) ==
        ["bos.json", "bos_background.png", "bos_recording.png"],
        "python -m schlieren bos: the pair (%s)" % (p.stdout + p.stderr).decode().strip()[-200:])
for args, words in ((["--folder", os.path.join(out, "missing")], "does not exist"),
                    (["--folder", out, "--bits", "12"], "8 or 16"),
                    (["--folder", out, "--format", "jpeg"], "invalid choice")):
    p = subprocess.run([python, "-m", "schlieren", "bos"] + args, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, env=env, timeout=120)
    err = p.stderr.decode()
    T.check(p.returncode == 2 and len(err.strip().splitlines()) == 1 and words in err,
            "python -m schlieren bos %s: exit 2, one line (%s)" % (" ".join(args[2:]) or
                                                                   args[1], err.strip()))
T.finish()
