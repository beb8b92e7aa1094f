# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView side of test_gui_drag.py: run by `paraview --script=` (the plugin loaded from
PV_PLUGIN_PATH at startup, as a user's ParaView loads it).

Builds the chain (the NASA blunt fin from $SCHLIEREN_DATA, else a built-in off-centre sphere),
shows the volume's outline in the 3D view, waits for the driver to make a Schlieren Image with
ParaView's quick launch and press Apply, as a user would (it gives the new image the test's
settings before Apply), and then answers the driver through files in
$SCHLIEREN_GUI_WORK: a repeating timer of the 3D view's interactor (it runs in the GUI's event
loop, between the plugin's refinement chunks) records every image the GUI shows (its passes and
intensity) and executes the driver's commands (cmd-<n>.txt: `sizes`, `dump <name>`, `index`, `fields`, `quit`).
Nothing here moves the camera or updates the image: the plugin's toolbar does that.
Connected to a pvserver (test_gui_drag.py --pvserver), the images are fetched from the server.
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
    import numpy as np
    from paraview.simple import *  # noqa: F401,F403
    from paraview import servermanager
    from vtkmodules.util.numpy_support import vtk_to_numpy

    if "SchlierenImage" not in globals():
        raise RuntimeError("the Schlieren plugin is not loaded: PV_PLUGIN_PATH must name its folder")
    settings = json.load(open(os.path.join(work, "settings.json")))
    import paraview.simple as simple

    sys.path.insert(0, os.environ["SCHLIEREN_GUI_HERE"])  # a --script has no __file__
    import gui_drag_scene

    volume, scene = gui_drag_scene.volume(simple, os.environ.get("SCHLIEREN_DATA", ""))
    view = GetActiveViewOrCreate("RenderView")
    outline = Show(volume, view)
    outline.Representation = "Outline"
    Render(view)
    ResetCamera(view)
    camera = view.GetActiveCamera()
    camera.Elevation(25)
    camera.Azimuth(-30)
    camera.OrthogonalizeViewUp()
    ResetCamera(view)
    Render(view)
    pos, focal = np.array(camera.GetPosition()), np.array(camera.GetFocalPoint())
    direction = (focal - pos) / np.linalg.norm(focal - pos)
    SetActiveSource(volume)
    note("pipeline built (%s); waiting for the user's Schlieren Image" % scene)
    image = None

    def configure():
        """The driver made a Schlieren Image from the GUI (quick launch): the test's settings, the
        3D view's line of sight, before the user's Apply."""
        global image
        image = FindSource(settings.get("filter", "SchlierenImage") + "1")
        if image is None:
            return False
        for key, value in settings["image"].items():
            setattr(image, key, value)
        image.ViewDirection = direction.tolist()
        image.ViewUp = list(camera.GetViewUp())
        write_json("configured.json", {"passes": int(image.Passes) if hasattr(image, "Passes") else 1})
        note("configured %s for the test" % image.GetXMLName())
        return True

    state = {"last": None, "steps": [], "renders": 0, "image_view": None, "cmd": 0}

    remote = servermanager.ActiveConnection.IsRemote()
    fetched = {"key": None, "got": None}

    def read(out):
        a = out.GetPointData().GetArray("intensity") if out is not None else None
        if a is None or out.GetNumberOfPoints() == 0:
            return None
        nx, ny, _ = out.GetDimensions()
        passes = out.GetFieldData().GetArray("passes")  # (NumericalSchlieren has none: one update)
        return vtk_to_numpy(a).reshape(ny, nx).copy(), int(passes.GetValue(0)) if passes is not None else 1

    def current():
        """The image the GUI shows: its intensity and passes."""
        if not remote:
            return read(image.GetClientSideObject().GetOutputDataObject(0))
        # client/server: the data lives on the server. The data information (gathered after
        # each update of the plugin's) says which image is there; it is fetched once per image,
        # and only when it is the image of the proxy's present settings: a Fetch of a proxy
        # changed since its last update would run the trace itself, out of the plugin's hands.
        info = image.GetDataInformation()
        passes = image.FieldData["passes"] if "passes" in image.FieldData.keys() else None
        if passes is None or info.GetNumberOfPoints() == 0:
            return fetched["got"]
        e = info.GetExtent()
        key = (int(passes.GetRange()[0]), e[1] - e[0] + 1, e[3] - e[2] + 1)
        if key[0] != traced_passes() or list(key[1:]) != list(image.Resolution):
            return fetched["got"]
        key = key + (tuple(image.ViewDirection), tuple(image.ViewUp), info.GetMTime())
        if key != fetched["key"]:
            fetched["key"], fetched["got"] = key, read(servermanager.Fetch(image))
        return fetched["got"]

    def traced_passes():
        """The passes the filter traces: Passes (the user's target, as the panel shows it), at
        most the plugin's PassLimit while it refines."""
        if image.SMProxy.GetProperty("PassLimit") is None:
            return 1  # NumericalSchlieren
        limit = image.SMProxy.GetProperty("PassLimit").GetElement(0)
        return min(int(image.Passes), limit) if limit > 0 else int(image.Passes)

    def on_render(caller, event):
        state["renders"] += 1

    def command(words):
        if words[0] == "index":
            # what the panel set on the RefractiveIndex and the solid points it found
            volume.UpdatePipeline()
            fd = volume.GetDataInformation().DataInformation.GetFieldDataInformation()
            solid = fd.GetArrayInformation("solid_points")
            write_json("index.json", {"faces": [int(v) for v in volume.BodyWallFaces],
                                      "from_grid": int(volume.BodyFromGrid),
                                      "solid_points": solid.GetComponentRange(0)[0] if solid else None})
        elif words[0] == "fields":
            # the image's Framing, its film's size and the field data of its frame (builtin only)
            info = image.GetDataInformation()
            e = info.GetExtent()
            fd = image.GetClientSideObject().GetOutputDataObject(0).GetFieldData()
            value = lambda n: ([fd.GetArray(n).GetValue(i) for i in range(fd.GetArray(n).GetNumberOfValues())]
                               if fd.GetArray(n) is not None else None)
            spectrum = fd.GetAbstractArray("spectrum")
            iv = state["image_view"]
            shown = GetDisplayProperties(image, view=iv) if iv is not None else None
            write_json("fields.json", {"framing": str(image.Framing).strip("'"),
                                       "wavelength_range": list(image.WavelengthRange),
                                       "spectrum": spectrum.GetValue(0) if spectrum is not None else None,
                                       # what the image view colours the film by, and whether
                                       # through a colour map (1) or as the colours themselves (0)
                                       "image_colour": [shown.ColorArrayName[1], int(shown.MapScalars)]
                                       if shown is not None else None,
                                       "size": [e[1] - e[0] + 1, e[3] - e[2] + 1],
                                       "film_extent": value("film_extent"),
                                       "film_frame_kept": value("film_frame_kept"),
                                       "missed_rays": value("missed_rays"),
                                       "photons": value("photons")})
        elif words[0] == "quit":
            note("quit")
            os._exit(0)

    def poll(caller, event):
        try:
            if image is None and not configure():
                # before the user's Schlieren Image: only the commands about the index
                path = os.path.join(work, "cmd-%d.txt" % state["cmd"])
                words = open(path).read().split() if os.path.exists(path) else []
                if words and words[0] in ("index", "quit"):
                    state["cmd"] += 1
                    command(words)
                return
            if state["image_view"] is None:
                others = [v for v in GetViews() if v.GetGlobalIDAsString() != view.GetGlobalIDAsString()]
                if others:
                    state["image_view"] = others[0]
                    others[0].GetRenderWindow().AddObserver("EndEvent", on_render)
            got = current()
            key = None if got is None else (got[1], tuple(image.ViewDirection), tuple(image.ViewUp))
            if got is not None and key != state["last"]:
                state["last"] = key
                state["steps"].append((time.time(), got[1], list(image.ViewDirection), list(image.ViewUp), got[0]))
                del state["steps"][:-400]
            path = os.path.join(work, "cmd-%d.txt" % state["cmd"])
            if not os.path.exists(path):
                return
            words = open(path).read().split()
            state["cmd"] += 1
            if words[0] == "sizes":
                iv = state["image_view"]
                if not state.get("reset"):
                    # the 3D view is half as wide after the split: the whole volume in it again
                    # (a zoom: the image's line of sight stays)
                    state["reset"] = True
                    ResetCamera(view)
                    Render(view)
                write_json("sizes.json", {"view3d": list(view.ViewSize),
                                          "image_view": list(iv.ViewSize) if iv else None,
                                          "image_view_mode": str(iv.InteractionMode).strip("'") if iv else None,
                                          "image_in_3d": [int(r.Visibility) for r in view.Representations
                                                          if r.GetProperty("Input") is not None
                                                          and r.Input == image],
                                          "follow": int(image.FollowCamera),
                                          "shown_3d": dict(shown_3d),
                                          # the ranks the last trace ran on (its field data)
                                          "distributed_ranks": int(image.FieldData["distributed_ranks"].GetRange()[0])
                                          if "distributed_ranks" in image.FieldData.keys() else None})
            elif words[0] == "dump":
                got = current()
                # the images of this film (the coarse ones while the view turned are smaller)
                steps = [s for s in state["steps"] if s[4].shape == got[0].shape]
                np.savez(os.path.join(work, words[1] + ".npz"), intensity=got[0], passes=got[1],
                         direction=np.array(image.ViewDirection), up=np.array(image.ViewUp),
                         renders=state["renders"], follow=int(image.FollowCamera),
                         step_times=np.array([s[0] for s in steps]),
                         step_passes=np.array([s[1] for s in steps]),
                         step_directions=np.array([s[2] for s in steps]),
                         step_images=np.array([s[4] for s in steps]))
                state["steps"] = steps[-1:]
                write_json("dumped-%s.json" % words[1], {"passes": got[1]})
            else:
                command(words)
        except BaseException:
            note("poll failed: " + traceback.format_exc())
            os._exit(3)

    # every render of the 3D view: whether it drew the film (the image's representation visible
    # there) or a colour legend; Apply should show the film in its own view only, never here
    shown_3d = {"renders": 0, "film": 0, "legend": 0}

    def on_render_3d(caller, event):
        shown_3d["renders"] += 1
        im = FindSource(settings.get("filter", "SchlierenImage") + "1")
        if im is None:
            return
        for r in view.Representations:
            if r.GetProperty("Visibility") is None or not int(r.Visibility):
                continue
            if r.GetProperty("Input") is not None and r.Input == im:
                shown_3d["film"] += 1
            elif r.GetXMLName().endswith("ScalarBarWidgetRepresentation"):
                shown_3d["legend"] += 1

    view.GetRenderWindow().AddObserver("EndEvent", on_render_3d)
    interactor = view.GetRenderWindow().GetInteractor()
    interactor.CreateRepeatingTimer(50)
    poll_tag = interactor.AddObserver("TimerEvent", poll)
    write_json("ready.json", {"scene": scene, "view3d": list(view.ViewSize), "remote": bool(remote),
                              "ranks": int(servermanager.ActiveConnection.GetNumberOfDataPartitions())})
except BaseException:
    note("FAIL " + traceback.format_exc())
    sys.stderr.write(traceback.format_exc())
    sys.stderr.flush()
    os._exit(1)
