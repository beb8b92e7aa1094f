# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView GUI follows the camera; run by run_gui_test.py --script test_gui_follow.py.

In the GUI: load the plugin, build PLOT3DReader -> RefractiveIndex -> SchlierenImage on the NASA
blunt fin (../shared/data or $SCHLIEREN_DATA; a built-in off-centre sphere where the data is
absent), show the volume's outline in a 3D render view, follow its camera with schlieren_view,
rotate the view, and check: the image's line of sight is the camera's, the image changed, it equals
a separate trace with the same camera (numbers), refinement brings it to the target-pass image, and
a new rotation cancels the refinement in progress. Success is written to SCHLIEREN_GUI_RESULT.
"""
import os
import sys
import traceback

result_path = os.environ.get("SCHLIEREN_GUI_RESULT")
lines = []


def check(condition, message):
    lines.append("%s %s" % ("ok  " if condition else "FAIL", message))
    if not condition:
        raise AssertionError(message)


try:
    import numpy as np
    from paraview.simple import *  # noqa: F401,F403
    from paraview import servermanager as sm
    from vtkmodules.util.numpy_support import vtk_to_numpy

    LoadPlugin(os.environ["SCHLIEREN_PLUGIN"], remote=False, ns=globals())
    import schlieren_view

    data = os.environ.get("SCHLIEREN_DATA", "")  # set by run_gui_test.py
    xyz, q = os.path.join(data, "bluntfinxyz.bin"), os.path.join(data, "bluntfinq.bin")
    if os.path.exists(xyz) and os.path.exists(q):
        reader = PLOT3DReader(FileName=xyz, QFileName=[q])
        volume = RefractiveIndex(Input=reader, Model="GladstoneDale", Gas="Air", DensityReference=1.2,
                                 UseSamplingBounds=1, SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7],
                                 AutomaticDimension=64, AmbientMode="Extend")
        volume.InputArray = ["POINTS", "Density"]
        lines.append("     the blunt fin from %s" % os.path.abspath(data))
    else:
        volume = RefractiveScene(Scene="GaussianSphere", Dimensions=[48, 48, 48], Amplitude=1e-4,
                                 Width=0.3, Center=[0.3, 0.1, -0.2])
        lines.append("     no blunt-fin data in %s: an off-centre Gaussian sphere instead" % data)
    common = dict(Resolution=[96, 96], Cutoff="KnifeEdge", CutoffScale=40.0, Backend="CPU", Seed=4)
    if "blunt fin" not in lines[0]:
        # the smooth sphere under the Lattice jitter (one offset per pass) is converged at the first
        # pass, so its refinement would show nothing: Random jitter (an offset per pixel) leaves
        # every pass's image noisy, and the refinement must bring the noise down
        common["JitterPattern"] = "Random"
    image = SchlierenImage(Input=volume, Passes=8, **common)
    view = GetActiveViewOrCreate("RenderView")
    outline = Show(volume, view)
    outline.Representation = "Outline"
    view.CameraPosition = [2.5, 2.5, 30.0]
    view.CameraFocalPoint = [2.5, 2.5, 2.85]
    view.CameraViewUp = [0, 1, 0]
    Render(view)

    follower = schlieren_view.follow_camera(view, image, interactive_passes=1, target_passes=8, step=2,
                                            timer=False)
    d0, u0 = follower.camera_vectors()
    check(np.allclose(image.ViewDirection, d0) and int(image.Passes) == 1,
          "following: the image looks along the camera (%s) with 1 pass" % np.round(d0, 3).tolist())
    image.UpdatePipeline()
    before = vtk_to_numpy(sm.Fetch(image).GetPointData().GetArray("deflection")).copy()

    # rotate the 3D view as a user would (azimuth and elevation of the camera)
    camera = view.GetActiveCamera()
    camera.Azimuth(35)
    camera.Elevation(20)
    camera.OrthogonalizeViewUp()
    Render(view)
    d1, u1 = follower.camera_vectors()
    check(follower.moved >= 1 and np.allclose(image.ViewDirection, d1) and np.allclose(image.ViewUp, u1),
          "after the rotation the image looks along the new camera (%s)" % np.round(d1, 3).tolist())
    image.UpdatePipeline()
    after = sm.Fetch(image)
    D1 = vtk_to_numpy(after.GetPointData().GetArray("deflection")).copy()
    # a 35/20 degree turn moves the projection of an off-centre feature by many pixels, so the
    # change is of the order of the image's peak deflection whatever the scene: a quarter of the
    # peak (the blunt fin's is ~1e-3 rad, the built-in sphere's ~1.4e-4 rad) tells a re-traced image
    # from an unchanged one (0) or from noise of one pass
    peak = max(np.abs(before).max(), np.abs(D1).max())
    change = np.abs(D1 - before).max()
    check(peak > 0 and change > 0.25 * peak,
          "the schlieren image changed with the view (max |change| %.3g rad, %.0f %% of the peak %.3g rad)"
          % (change, 100 * change / peak if peak > 0 else 0, peak))

    # the same camera traced by a separate filter (as a pvpython script would): the same numbers
    same = SchlierenImage(Input=volume, Passes=1, ViewDirection=d1, ViewUp=u1, **common)
    Ds = vtk_to_numpy(sm.Fetch(same).GetPointData().GetArray("deflection"))
    check(np.array_equal(D1, Ds), "the followed image equals a trace with the same camera, bit for bit")

    # refinement: pass after pass up to the target, converging to the target-pass image
    target = SchlierenImage(Input=volume, Passes=8, ViewDirection=d1, ViewUp=u1, **common)
    It = vtk_to_numpy(sm.Fetch(target).GetPointData().GetArray("intensity")).copy()
    errors = []
    while True:
        more = follower.refine()
        I = vtk_to_numpy(sm.Fetch(image).GetPointData().GetArray("intensity"))
        errors.append(float(np.sqrt(np.mean((I - It) ** 2))))
        if not more:
            break
    lines.append("     RMS against the 8-pass image while refining (3, 5, 7, 8 passes): %s"
                 % ["%.2e" % e for e in errors])
    check(int(image.Passes) == 8 and errors[-1] == 0.0,
          "refinement reaches the target: the 8-pass image, bit for bit")
    # (the blunt fin 3e-4, the sphere under Random jitter 9e-4; under Lattice it was below 5e-5)
    check(errors[0] > 1e-4, "the case needs refinement: the first refined image differs from the 8-pass one "
          "(RMS %.2e > 1e-4)" % errors[0])
    check(all(b <= a + 1e-12 for a, b in zip(errors, errors[1:])), "the error falls pass after pass")

    # the refined image against a baseline PNG someone looked at (the blunt fin only): 8-bit grey,
    # I in [0, 1]; a missing baseline fails and leaves the candidate beside the result file
    if "blunt fin" in lines[0]:
        from vtkmodules.util.numpy_support import numpy_to_vtk
        from vtkmodules.vtkCommonDataModel import vtkImageData
        from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

        I8 = np.clip(255 * I + 0.5, 0, 255).astype(np.uint8)
        baseline = os.environ.get("SCHLIEREN_GUI_BASELINE", "")
        if os.path.exists(baseline):
            reader = vtkPNGReader()
            reader.SetFileName(baseline)
            reader.Update()
            B = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).reshape(-1)
            diff = np.abs(B.astype(int) - I8.astype(int))
            check(B.size == I8.size and diff.mean() < 1.0 and np.mean(diff > 8) < 0.01,
                  "the followed image matches the baseline %s (mean |difference| %.2f grey levels)"
                  % (os.path.basename(baseline), diff.mean()))
        else:
            candidate = vtkImageData()
            candidate.SetDimensions(96, 96, 1)
            candidate.GetPointData().SetScalars(numpy_to_vtk(I8, deep=1))
            writer = vtkPNGWriter()
            writer.SetInputData(candidate)
            writer.SetFileName(result_path + ".candidate.png")
            writer.Write()
            check(False, "no baseline %r: the candidate is %s.candidate.png" % (baseline, result_path))

    # a new interaction cancels the refinement in progress
    image.Passes = 5
    camera.Azimuth(-10)
    Render(view)
    check(int(image.Passes) == 1, "a new rotation drops the image back to 1 pass")
    follower.stop()
    lines.append("PASS")
except BaseException:
    lines.append("FAIL " + traceback.format_exc())
    if result_path:
        with open(result_path, "w") as f:
            f.write("\n".join(lines) + "\n")
    sys.stderr.write("\n".join(lines) + "\n")
    sys.stderr.flush()
    os._exit(1)

if result_path:
    with open(result_path, "w") as f:
        f.write("\n".join(lines) + "\n")
