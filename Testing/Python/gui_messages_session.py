# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView side of test_gui_messages.py: run by `paraview --script=` (the plugin loaded from
PV_PLUGIN_PATH). Builds the Exodus reactor (disk_out_ref.ex2 from $SCHLIEREN_DATA) with its `Pres`
read as it is, an absolute pressure in Pa (Model Automatic), and the blunt fin's PLOT3D reader; then
answers the driver's commands (cmd-<n>.txt in $SCHLIEREN_GUI_WORK) from a timer of the 3D view:
`state` (the views, the SchlierenImage's field data), `select <name>` (the active source), `quit`.
Nothing here makes the SchlierenImage or presses Apply: the driver does, with X events.
"""
import json
import os
import sys
import time
import traceback

work = os.environ["SCHLIEREN_GUI_WORK"]


def write_json(name, value):
    path = os.path.join(work, name)
    with open(path + ".tmp", "w") as f:
        json.dump(value, f)
    os.replace(path + ".tmp", path)


try:
    from paraview.simple import *  # noqa: F401,F403

    data = os.environ.get("SCHLIEREN_DATA", "")
    reactor = os.path.join(data, "disk_out_ref.ex2")
    if not os.path.exists(reactor):
        write_json("ready.json", {"scene": None})
        raise SystemExit
    reader = ExodusIIReader(registrationName="reactor", FileName=reactor)
    reader.PointVariables = ["Temp", "Pres", "H2"]
    index = RefractiveIndex(registrationName="RefractiveIndex1", Input=reader, AutomaticDimension=48)
    plot3d = None
    xyz, q = os.path.join(data, "bluntfinxyz.bin"), os.path.join(data, "bluntfinq.bin")
    if os.path.exists(xyz) and os.path.exists(q):
        plot3d = PLOT3DReader(registrationName="bluntfin", FileName=xyz, QFileName=[q])
        plot3d.UpdatePipeline()
    view = GetActiveViewOrCreate("RenderView")
    outline = Show(index, view)
    outline.Representation = "Outline"
    Render(view)
    ResetCamera(view)
    SetActiveSource(index)
    state = {"cmd": 0}

    def command(words):
        if words[0] == "state":
            image = FindSource("SchlierenImage1")
            fd = {}
            if image is not None:
                out = image.GetClientSideObject().GetOutputDataObject(0)
                f = out.GetFieldData() if out is not None else None
                for i in range(f.GetNumberOfArrays() if f is not None else 0):
                    a = f.GetAbstractArray(i)
                    if a.GetNumberOfValues() == 1:
                        fd[a.GetName()] = a.GetVariantValue(0).ToString()
            idx = FindSource("RefractiveIndex1")
            notes = idx.GetClientSideObject().GetOutputDataObject(0).GetFieldData().GetAbstractArray("index_notes")
            write_json("state-%s.json" % words[1], {
                "views": len(GetViews()),
                "active_view": GetActiveView() is not None,
                "image": image is not None,
                "image_points": image.GetDataInformation().GetNumberOfPoints() if image is not None else None,
                "resolution": list(image.Resolution) if image is not None else None,
                "field": fd,
                "index_notes": notes.GetValue(0) if notes is not None else None,
                "index_model": idx.GetProperty("Model").GetData()})
        elif words[0] == "select":
            SetActiveSource(FindSource(words[1]))
            write_json("selected-%s.json" % words[1], {})
        elif words[0] == "quit":
            os._exit(0)

    def poll(caller, event):
        try:
            path = os.path.join(work, "cmd-%d.txt" % state["cmd"])
            if not os.path.exists(path):
                return
            words = open(path).read().split()
            state["cmd"] += 1
            command(words)
        except BaseException:
            with open(os.path.join(work, "session.log"), "a") as f:
                f.write("poll failed: " + traceback.format_exc())
            os._exit(3)

    interactor = view.GetRenderWindow().GetInteractor()
    interactor.CreateRepeatingTimer(50)
    interactor.AddObserver("TimerEvent", poll)
    write_json("ready.json", {"scene": "reactor", "plot3d": plot3d is not None})
except SystemExit:
    pass
except BaseException:
    with open(os.path.join(work, "session.log"), "a") as f:
        f.write("FAIL " + traceback.format_exc())
    sys.stderr.write(traceback.format_exc())
    os._exit(1)
