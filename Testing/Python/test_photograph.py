# SPDX-License-Identifier: BSD-3-Clause
"""A photograph beside the image through the Python front end (issue 51): a traced film, a
"photograph" of it made with a known similarity transform, gamma, vignetting and noise, written as
a 16-bit PNG and an 8-bit colour JPEG and read back by SchlierenPhotograph with VTK's readers; the
transform recovered, the outputs' arrays and lines; a photograph of noise refused with the reason
and an empty output; bad arrays refused by schlieren.engine.photograph with a named error.

    PYTHONPATH=Python SCHLIEREN_ENGINE_LIBRARY=build/OpenCL/libschlieren_engine.so \
        pvpython Testing/Python/test_photograph.py --work /tmp/photograph
"""
import argparse
import json
import math
import os
import sys

import numpy as np

failures = 0


def check(ok, what):
    global failures
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures += 1


def write(values, path, bits, colour=False):
    """A grey image (row 0 at the bottom) as a PNG (8 or 16 bit) or JPEG, with VTK's writers."""
    from vtkmodules.util import numpy_support
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkJPEGWriter, vtkPNGWriter
    top = 255 if bits == 8 else 65535
    q = np.clip(values / values.max() * top, 0, top).astype(np.uint8 if bits == 8 else np.uint16)
    if colour:  # a colour camera: the same grey in R, G and B, a little blue cast
        q = np.stack([q, q, (q * 0.9).astype(q.dtype)], axis=-1)
    image = vtkImageData()
    image.SetDimensions(values.shape[1], values.shape[0], 1)
    a = numpy_support.numpy_to_vtk(q.reshape(values.size, -1), deep=1)
    image.GetPointData().SetScalars(a)
    writer = vtkJPEGWriter() if path.endswith(".jpg") else vtkPNGWriter()
    if path.endswith(".jpg"):
        writer.SetQuality(95)
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()


def test_volume(engine, blast_radius=0.4):
    """The volume whose film the tests photograph: a blast wave off the centre with a plane shock
    gives lines in two directions, a Gaussian lump a soft feature (scenes summed through the
    engine's fill); n_minus_1 on a 48^3 image over [-1, 1]^3. `engine`: the package's _engine
    (python.photograph_plugins passes the Python plugin's); `blast_radius` moves the blast's
    shock (python.photograph_plugins' moved photograph)."""
    from vtkmodules.util import numpy_support
    from vtkmodules.vtkCommonDataModel import vtkImageData
    dims = [48, 48, 48]
    spacing = [2.0 / 47] * 3
    blast = engine.fill_scene({"Scene": "BlastWave", "Radius": blast_radius, "Width": 0.04,
                               "Center": [0.2, 0.15, 0.0]}, dims, [-1.0] * 3, spacing)
    lump = engine.fill_scene({"Scene": "GaussianSphere", "Amplitude": 3e-3, "Width": 0.2,
                              "Center": [-0.45, -0.4, 0.0]}, dims, [-1.0] * 3, spacing)
    shock = engine.fill_scene({"Scene": "NormalShock", "Center": [-0.25, 0.0, 0.0], "Width": 0.03,
                               "Mach": 1.3}, dims, [-1.0] * 3, spacing)
    n1 = blast["n_minus_1"] + lump["n_minus_1"] + shock["n_minus_1"] - shock["n_minus_1"][0]
    volume = vtkImageData()
    volume.SetDimensions(*dims)
    volume.SetOrigin(-1.0, -1.0, -1.0)
    volume.SetSpacing(*spacing)
    a = numpy_support.numpy_to_vtk(n1.astype(np.float32), deep=1)
    a.SetName("n_minus_1")
    volume.GetPointData().AddArray(a)
    return volume


def main():
    global schlieren, engine
    import schlieren
    from schlieren import engine
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", default="photograph_test")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)

    volume = test_volume(engine)
    image = schlieren.SchlierenImage(Resolution=[112, 112], Passes=4, Backend="CPU")
    image.SetInputData(volume)
    image.Update()
    film = schlieren.image_to_numpy(image.GetOutput())
    pixel = image.GetOutput().GetSpacing()[0]
    print("film %s, pixel %.4g" % (film.shape, pixel))

    truth = dict(scale=1.25, degrees=-6.0, shift=(12.0, 9.0))
    photo = engine.synthetic_photograph(film, truth["scale"], truth["degrees"], truth["shift"],
                                        (150, 170), gamma=0.7, vignetting=0.25, photons=3000)
    png, jpg = os.path.join(args.work, "photo16.png"), os.path.join(args.work, "photo8.jpg")
    write(photo, png, 16)
    write(photo, jpg, 8, colour=True)
    read = schlieren.read_photograph(png)
    check(read.shape == (150, 170) and abs(read.max() - 65535) < 1,
          "a 16-bit PNG read by VTK as grey (rows, columns) %s, up to %g" % (read.shape, read.max()))

    for path in (png, jpg):
        alg = schlieren.SchlierenPhotograph(FileName=path)
        alg.SetInputConnection(0, image.GetOutputPort())
        alg.Update()
        r = alg.Report
        out = alg.GetOutput()
        # the error at the film's corners, film pixels
        corner = 0.0
        for cx in (0, 111):
            for cy in (0, 111):
                x, y = cx - 55.5, cy - 55.5
                def place(s, deg, t):
                    th = math.radians(deg)
                    return (s * (math.cos(th) * x - math.sin(th) * y) + t[0],
                            s * (math.sin(th) * x + math.cos(th) * y) + t[1])
                u0 = place(truth["scale"], truth["degrees"], truth["shift"])
                u1 = place(r["scale"], r["rotation"], r["shift"])
                corner = max(corner, math.hypot(u1[0] - u0[0], u1[1] - u0[1]) / truth["scale"])
        print("%s: score %.3f (threshold %.3f), scale %.4f, rotation %.3f, shift %.2f %.2f, corner "
              "error %.3f px (uncertainty %.3f), gamma %.3f +- %.3f, %.2f s"
              % (os.path.basename(path), r["score"], r["threshold"], r["scale"], r["rotation"],
                 r["shift"][0], r["shift"][1], corner, r["edge_uncertainty"], r["gamma"],
                 r["gamma_error"], r["seconds"]))
        check(r["match"] and corner < 0.5 and abs(r["rotation"] - truth["degrees"]) < 0.2,
              "%s registered: corner error %.3f px < 0.5, rotation error %.3f deg < 0.2"
              % (os.path.basename(path), corner, abs(r["rotation"] - truth["degrees"])))
        check(abs(r["gamma"] - 0.7) < 0.07, "%s: gamma %.3f (0.7 within 10 %%)"
              % (os.path.basename(path), r["gamma"]))
        names = [out.GetPointData().GetArrayName(k) for k in range(out.GetPointData().GetNumberOfArrays())]
        check(set(["intensity", "photograph", "photograph_calibrated", "difference", "checkerboard",
                   "line_distance"]) <= set(names) and out.GetDimensions() == (112, 112, 1),
              "the output on the film's grid with its arrays: %s" % names)
        diff = schlieren.image_to_numpy(out, "difference")
        cal = schlieren.image_to_numpy(out, "photograph_calibrated")
        covered = cal > 0
        rms = float(np.sqrt(np.mean(diff[covered] ** 2)))
        check(rms < 0.05, "the calibrated photograph minus the film: rms %.4f (< 0.05 of the "
              "film's grey)" % rms)
        lines = alg.GetOutputDataObject(1)
        kinds = lines.GetCellData().GetArray("image")
        n_film = sum(1 for k in range(lines.GetNumberOfCells()) if kinds.GetValue(k) == 0)
        check(n_film >= 2 and lines.GetNumberOfCells() > n_film,
              "lines: %d of the film, %d of the photograph" % (n_film, lines.GetNumberOfCells() - n_film))
        d = [lines.GetCellData().GetArray("line_distance").GetValue(k)
             for k in range(lines.GetNumberOfCells()) if kinds.GetValue(k) == 0]
        d = [x for x in d if x == x]
        check(d and max(d) < 2 * pixel, "the same flow: the film's matched lines within 2 pixels "
              "of the photograph's (largest %.4g, a pixel %.4g)" % (max(d) if d else -1, pixel))
        report = json.loads(out.GetFieldData().GetAbstractArray("photograph_report").GetValue(0))
        check(report["match"] and "lines" in report, "the report in the field data")

    # refused: a photograph of noise (the request fails with the reason, the output is empty)
    noise = np.random.default_rng(2).poisson(500, (150, 170)).astype(np.float32)
    npath = os.path.join(args.work, "noise.png")
    write(noise, npath, 16)
    alg = schlieren.SchlierenPhotograph(FileName=npath)
    alg.SetInputConnection(0, image.GetOutputPort())
    alg.Update()
    check("does not match" in alg.LastError and alg.GetOutput().GetNumberOfPoints() == 0 and
          alg.Report["score"] < alg.Report["threshold"],
          "noise refused: %s; output points %d" % (alg.LastError[:160], alg.GetOutput().GetNumberOfPoints()))
    # a photograph that is not there, and bad arrays to the engine function
    alg = schlieren.SchlierenPhotograph(FileName=os.path.join(args.work, "missing.png"))
    alg.SetInputConnection(0, image.GetOutputPort())
    alg.Update()
    check("not found" in alg.LastError, "a missing file: %s" % alg.LastError)
    for what, call, needle in [
            ("a 1D photograph", lambda: engine.photograph(film, [0, 0], pixel, photo.ravel()), "2D"),
            ("text", lambda: engine.photograph(film, [0, 0], pixel, np.array([["a"]])), "dtype"),
            ("a tiny photograph", lambda: engine.photograph(film, [0, 0], pixel, photo[:8, :8]), "16 to"),
            ("NaN", lambda: engine.photograph(film, [0, 0], pixel, np.full((40, 40), np.nan)), "not finite"),
            ("a bad setting", lambda: engine.photograph(film, [0, 0], pixel, photo, {"Refine": "Affine"}), "Refine"),
            ("one point pair", lambda: engine.photograph(film, [0, 0], pixel, photo,
                                                         {"PointPairs": [1, 2, 3, 4]}), "2 to 4 pairs")]:
        try:
            call()
            check(False, "%s: no error" % what)
        except engine.EngineError as e:
            check(needle in str(e), "%s refused: %s" % (what, e))
    print("%d failures" % failures)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
