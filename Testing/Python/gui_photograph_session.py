# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView side of test_gui_photograph.py: run by `paraview --script=` (the plugin loaded from
PV_PLUGIN_PATH at startup, as a user's ParaView loads it).

Builds the scene of python.photograph (a blast wave off the centre, a plane shock and a Gaussian
lump: test_photograph.test_volume), a Schlieren Image of it shown in its own 2D render view beside
the 3D view, and a "photograph" of that film made with a known similarity transform, gamma,
vignetting and noise, written as a 16-bit PNG (photo.png; truth in ready.json). Then it waits for
the driver's real events (the quick launch's Schlieren Photograph on the image, its File Name
typed, Apply, the Overlay changed) and answers its commands through files in $SCHLIEREN_GUI_WORK
(cmd-<n>.txt): `state` (what the image view shows of the photograph filter: representations,
colour arrays, the outputs' arrays and lines; state-<n>.json), `spreadsheet` (the lines' list in a
spreadsheet view beside the image view), `quit`.
"""
import json
import os
import sys
import time
import traceback

work = os.environ["SCHLIEREN_GUI_WORK"]


def note(text):
    with open(os.path.join(work, "session.log"), "a") as f:
        f.write("%.6f %s\n" % (time.time(), text))


def write_json(name, value):
    path = os.path.join(work, name)
    with open(path + ".tmp", "w") as f:
        json.dump(value, f)
    os.replace(path + ".tmp", path)  # the driver never reads half a file


try:
    from paraview.simple import *  # noqa: F401,F403
    from vtkmodules.util.numpy_support import vtk_to_numpy

    if "SchlierenPhotograph" not in globals():
        raise RuntimeError("the Schlieren plugin is not loaded: PV_PLUGIN_PATH must name its folder")
    sys.path.insert(0, os.environ["SCHLIEREN_GUI_HERE"])  # a --script has no __file__
    from schlieren import engine  # the Python package (PYTHONPATH): the scene and the photograph
    from test_photograph import test_volume, write

    volume = PVTrivialProducer(registrationName="scene")
    volume.GetClientSideObject().SetOutput(test_volume(engine))
    view = GetActiveViewOrCreate("RenderView")
    Show(volume, view).Representation = "Outline"
    ResetCamera(view)
    Render(view)
    image = SchlierenImage(registrationName="image", Input=volume, Resolution=[112, 112], Passes=4,
                           Backend="CPU", OpenImageView=0)
    image.UpdatePipeline()
    layout = GetLayout(view)
    layout.SplitHorizontal(0, 0.4)
    image_view = CreateView("RenderView")
    AssignViewToLayout(view=image_view, layout=layout, hint=2)
    image_view.InteractionMode = "2D"
    image_view.OrientationAxesVisibility = 0
    shown = Show(image, image_view)
    ColorBy(shown, ("POINTS", "intensity"))
    ResetCamera(image_view)
    Render(image_view)
    film = image.GetClientSideObject().GetOutputDataObject(0)
    nx, ny, _ = film.GetDimensions()
    intensity = vtk_to_numpy(film.GetPointData().GetArray("intensity")).reshape(ny, nx)
    truth = dict(scale=1.25, degrees=-6.0, shift=[12.0, 9.0])
    photo = engine.synthetic_photograph(intensity, truth["scale"], truth["degrees"], truth["shift"],
                                        (150, 170), gamma=0.7, vignetting=0.25, photons=3000)
    write(photo, os.path.join(work, "photo.png"), 16)
    SetActiveView(image_view)
    SetActiveSource(image)
    state = {"cmd": 0}

    def representation(source, port, v):
        """The representation of the source's output port in view v (none made: paraview.simple's
        GetRepresentation would show it)."""
        for r in v.Representations:
            p = r.SMProxy.GetProperty("Input") if r.SMProxy.GetProperty("Visibility") else None
            if p is None or p.GetNumberOfProxies() == 0 or p.GetProxy(0) != source.SMProxy or \
                    p.GetOutputPortForConnection(0) != port:
                continue
            lut = r.LookupTable
            return {"visible": int(r.Visibility), "type": str(r.Representation).strip("'"),
                    "colour": list(r.ColorArrayName),
                    "range": list(lut.RGBPoints[0::4][::len(lut.RGBPoints[0::4]) - 1]) if lut else None}
        return None

    def snapshot():
        ph = FindSource("SchlierenPhotograph1")
        out = {"photograph": ph is not None}
        if ph is None:
            return out
        out["file_name"] = str(ph.FileName)
        out["overlay"] = str(ph.Overlay).strip("'")
        alg = ph.GetClientSideObject()
        o0, o1 = alg.GetOutputDataObject(0), alg.GetOutputDataObject(1)
        out["points"] = o0.GetNumberOfPoints()
        out["mtime"] = o0.GetMTime()
        out["active"] = o0.GetPointData().GetScalars().GetName() if o0.GetPointData().GetScalars() else None
        out["port0"] = representation(ph, 0, image_view)
        out["port1"] = representation(ph, 1, image_view)
        out["image_shown"] = (representation(image, 0, image_view) or {}).get("visible")
        out["in_3d"] = [representation(ph, p, view) for p in (0, 1)]
        report = o0.GetFieldData().GetAbstractArray("photograph_report")
        out["report"] = json.loads(report.GetValue(0)) if report is not None else None
        cd = o1.GetCellData()
        out["lines"] = [{"image": int(cd.GetArray("image").GetValue(k)),
                         "distance": float(cd.GetArray("line_distance").GetValue(k))}
                        for k in range(o1.GetNumberOfCells())] if cd.GetArray("image") else []
        out["pixel"] = film.GetSpacing()[0]
        out["spreadsheets"] = [{"rows": int(v.GetClientSideObject().GetNumberOfRows()),
                                "columns": [v.GetClientSideObject().GetColumnName(c) for c in
                                            range(v.GetClientSideObject().GetNumberOfColumns())],
                                "attribute": str(v.FieldAssociation).strip("'")}
                               for v in GetViews() if v.GetXMLName() == "SpreadSheetView"]
        return out

    def poll(caller, event):
        try:
            path = os.path.join(work, "cmd-%d.txt" % state["cmd"])
            if not os.path.exists(path):
                return
            words = open(path).read().split()
            n = state["cmd"]
            state["cmd"] += 1
            if words[0] == "state":
                write_json("state-%d.json" % n, snapshot())
            elif words[0] == "spreadsheet":
                ph = FindSource("SchlierenPhotograph1")
                sheet = CreateView("SpreadSheetView")
                layout.SplitVertical(2, 0.6)  # the image view above (5), the list below (6)
                AssignViewToLayout(view=sheet, layout=layout, hint=6)
                SetActiveView(sheet)
                SetActiveSource(ph)
                Show(OutputPort(ph, 1), sheet)
                sheet.FieldAssociation = "Cell Data"
                Render(sheet)
                write_json("state-%d.json" % n, snapshot())
            elif words[0] == "quit":
                note("quit")
                os._exit(0)
        except BaseException:
            note("poll failed: " + traceback.format_exc())
            os._exit(3)

    interactor = view.GetRenderWindow().GetInteractor()
    interactor.CreateRepeatingTimer(100)
    interactor.AddObserver("TimerEvent", poll)
    write_json("ready.json", {"truth": truth, "photo": os.path.join(work, "photo.png"),
                              "film": [nx, ny], "pixel": film.GetSpacing()[0]})
    note("ready")
except BaseException:
    note("FAIL " + traceback.format_exc())
    sys.stderr.write(traceback.format_exc())
    sys.stderr.flush()
    os._exit(1)
