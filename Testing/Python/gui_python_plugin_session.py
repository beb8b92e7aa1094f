# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView side of test_gui_python_plugin.py: run by `paraview --script=` with no plugin
loaded. It runs the two-line getargspec shim that Debian's ParaView 5.11.0 needs before any Python
plugin loads under Python 3.11 (docs/PYTHON.md: the user types it into View > Python Shell), and
answers the driver's commands (cmd-<n>.txt in $SCHLIEREN_GUI_WORK) from a timer of the render view:
`state <tag>` (which Schlieren proxies ParaView knows, the pipeline's sources, their property
lists), `set <json>` (properties of the active source, the settings the driver could type),
`dump <tag> [name]` (the SchlierenImage1 (or name) output's arrays, film and field data, as .npz),
`image <tag> [name]` (its ViewDirection, Passes, whether Follow Camera's follower runs, a hash of
its intensity), `setin <name> <json>` (properties of a source that is not active), `bluntfin <tag>`
(the blunt fin's PLOT3D files opened, as File > Open does, shown and made active; the rest
hidden), `index <tag>` (RefractiveIndex1's Body Wall Faces and its output's solid points),
`view2d <tag> <name>` (the image shown in a 2D render view beside the 3D one), `quit`.
Nothing here loads the plugin, creates a proxy or presses Apply: the driver does, with X events.
"""
import collections
import inspect
import json
import os
import sys
import traceback

work = os.environ["SCHLIEREN_GUI_WORK"]
here = os.environ["SCHLIEREN_GUI_HERE"]


def write_json(name, value):
    path = os.path.join(work, name)
    with open(path + ".tmp", "w") as f:
        json.dump(value, f)
    os.replace(path + ".tmp", path)


try:
    if not hasattr(inspect, "getargspec"):  # ParaView 5.11.0 on Python >= 3.11 (docs/PYTHON.md)
        _A = collections.namedtuple("ArgSpec", "args varargs keywords defaults")
        inspect.getargspec = lambda f: _A(*inspect.getfullargspec(f)[:4])
    from paraview import servermanager
    from paraview.simple import *  # noqa: F401,F403

    sys.path.insert(0, here)
    import frontend_cases as cases  # noqa: E402

    view = GetActiveViewOrCreate("RenderView")
    Render(view)
    state = {"cmd": 0}

    def known():
        pxm = servermanager.ProxyManager()
        out = {}
        for group, name in (("sources", "RefractiveScene"), ("filters", "RefractiveIndex"),
                            ("filters", "RefractionOctree"), ("filters", "SchlierenImage"),
                            ("filters", "NumericalSchlieren")):
            out[name] = pxm.SMProxyManager.GetPrototypeProxy(group, name) is not None
        return out

    def command(words):
        if words[0] == "state":
            sources = {}
            for (name, _id), proxy in GetSources().items():
                sources[name] = {"xml": proxy.GetXMLName(), "properties": proxy.ListProperties(),
                                 "points": proxy.GetDataInformation().GetNumberOfPoints()}
            write_json("state-%s.json" % words[1], {"known": known(), "sources": sources})
        elif words[0] == "set":
            props = json.loads(" ".join(words[1:]))
            source = GetActiveSource()
            for k, v in props.items():
                setattr(source, k, v)
            write_json("set-%d.json" % state["cmd"], {"set": list(props)})
        elif words[0] == "setin":  # setin <source name> <json>: a source that is not active
            props = json.loads(" ".join(words[2:]))
            source = FindSource(words[1])
            for k, v in props.items():
                setattr(source, k, v)
            write_json("set-%d.json" % state["cmd"], {"set": list(props)})
        elif words[0] == "bluntfin":
            # the blunt fin's PLOT3D files opened (as File > Open does), shown, made active; the
            # Gaussian sphere's pipeline hidden
            data = os.environ.get("SCHLIEREN_DATA", "")
            xyz, q = os.path.join(data, "bluntfinxyz.bin"), os.path.join(data, "bluntfinq.bin")
            found = os.path.exists(xyz) and os.path.exists(q)
            if found:
                for (name, _id), proxy in GetSources().items():
                    Hide(proxy, view)
                reader = PLOT3DReader(registrationName="bluntfin", FileName=xyz, QFileName=[q])
                Show(reader, view)
                SetActiveSource(reader)
                view.ResetCamera()
                Render(view)
            write_json("bluntfin-%s.json" % words[1], {"found": found})
        elif words[0] == "index":
            # RefractiveIndex1's Body Wall Faces and its output's solid points
            import numpy as np
            from vtkmodules.util import numpy_support
            index = FindSource("RefractiveIndex1")
            out = servermanager.Fetch(index)
            solid = out.GetPointData().GetArray("solid") if out else None
            write_json("index-%s.json" % words[1], {
                "faces": [int(v) for v in index.BodyWallFaces],
                "points": out.GetNumberOfPoints() if out else 0,
                "solid_points": int(np.count_nonzero(numpy_support.vtk_to_numpy(solid)))
                if solid is not None else 0})
        elif words[0] == "view2d":
            # the image in a 2D render view beside the 3D one (the C++ plugin's Open Image View
            # makes one; the Python plugin cannot add that behaviour): the layout split, the
            # image shown there by its intensity, the 3D view active again (Follow Camera follows
            # the active render view)
            image = FindSource(words[2])
            layout = GetLayout(view)
            view2d = CreateView("RenderView")
            view2d.InteractionMode = "2D"
            AssignViewToLayout(view=view2d, layout=layout, hint=0)
            display = Show(image, view2d)
            ColorBy(display, ("POINTS", "intensity"))
            display.LookupTable.ApplyPreset("Grayscale", True)
            display.LookupTable.RescaleTransferFunction(0.0, 1.0)
            Hide(image, view)
            Show(FindSource("bluntfin"), view)  # the grid's outline in the 3D view that is dragged
            view2d.ResetCamera()
            Render(view2d)
            SetActiveView(view)
            Render(view)
            write_json("view2d-%s.json" % words[1], {"views": len(GetViews())})
        elif words[0] == "dump":
            import numpy as np
            from vtkmodules.util import numpy_support
            image = FindSource(words[2] if len(words) > 2 else "SchlierenImage1")
            img = servermanager.Fetch(image)
            out = {"origin": np.array(img.GetOrigin()), "spacing": np.array(img.GetSpacing()),
                   "extent": np.array(img.GetExtent())}
            for a in cases.ARRAYS:
                arr = img.GetPointData().GetArray(a)
                if arr is not None:
                    out["array_" + a] = numpy_support.vtk_to_numpy(arr).copy()
            out["field_data"] = np.array(json.dumps(cases.field_data_list(img.GetFieldData())))
            np.savez(os.path.join(work, words[1] + ".npz"), **out)
            write_json("dumped-%s.json" % words[1], {})
        elif words[0] == "image":
            # the SchlierenImage1 proxy's line of sight and passes, its follower, its film's mean
            image = FindSource(words[2] if len(words) > 2 else "SchlierenImage1")
            alg = image.GetClientSideObject()
            follower = alg.__dict__.get("_follower")
            img = servermanager.Fetch(image)
            a = img.GetPointData().GetArray("intensity") if img else None
            import numpy as np
            from vtkmodules.util import numpy_support
            write_json("image-%s.json" % words[1], {
                "ViewDirection": list(image.ViewDirection), "ViewUp": list(image.ViewUp),
                "Passes": int(image.Passes), "following": follower is not None,
                "moved": follower.moved if follower is not None else 0,
                "passes_done": [float(img.GetFieldData().GetArray("passes").GetValue(0))]
                if img and img.GetFieldData().GetArray("passes") else [],
                "intensity_sha": __import__("hashlib").sha256(
                    numpy_support.vtk_to_numpy(a).tobytes()).hexdigest() if a else ""})
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
    write_json("ready.json", {"known": known()})
except BaseException:
    with open(os.path.join(work, "session.log"), "a") as f:
        f.write("FAIL " + traceback.format_exc())
    sys.stderr.write(traceback.format_exc())
    os._exit(1)
