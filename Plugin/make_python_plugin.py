# SPDX-License-Identifier: BSD-3-Clause
"""Writes SchlierenPython.py, the ParaView Python plugin (paraview.util.vtkAlgorithm), from the
two sources it must not drift from: the C++ plugin's Plugin/Schlieren.xml (every property's XML,
documentation and domains are copied from it) and the Python package Python/schlieren (embedded).

    python3 make_python_plugin.py --xml Plugin/Schlieren.xml --package Python/schlieren \
        --output SchlierenPython.py

The plugin exposes RefractiveScene, RefractiveIndex, RefractionOctree, SchlierenImage,
NumericalSchlieren and SchlierenPhotograph with every property of their XML, in its order, with its groups (RefractiveIndex's
optional Body input included); a property the package does not implement takes its default
only (the package refuses another value by name); it loads
libschlieren_engine.so from beside itself, SCHLIEREN_ENGINE_LIBRARY or the loader's path."""
import argparse
import xml.etree.ElementTree as ET

ap = argparse.ArgumentParser()
ap.add_argument("--xml", required=True)
ap.add_argument("--package", required=True)
ap.add_argument("--output", required=True)
ap.add_argument("--view", help="Plugin/schlieren_view.py, embedded as the module schlieren_view "
                "(Follow Camera from Python, as the C++ plugin embeds it)")
args = ap.parse_args()

root = ET.parse(args.xml).getroot()
proxies = {p.get("name"): p for p in root.iter("SourceProxy")}
sources = {}
for name in ("_engine", "png", "algorithms"):
    with open("%s/%s.py" % (args.package, name)) as f:
        sources[name] = f.read()
view_source = None
if args.view:
    with open(args.view) as f:
        view_source = f.read()

import re

# the proxies the Python package implements (all the C++ plugin's), and what of their XML it
# leaves out: these properties are not in the Python plugin
PROXIES = ("RefractiveScene", "RefractiveIndex", "RefractionOctree", "SchlierenImage",
           "NumericalSchlieren", "SchlierenPhotograph")
LEFT_OUT = {
    "RefractiveScene": {"TimeSteps"},  # the time steps ParaView's animation reads
    # the C++ plugin's toolbar's (its interactive film scale, its own image view, its pass limit)
    "SchlierenImage": {"InteractiveScale", "OpenImageView", "PassLimit"},
    "NumericalSchlieren": {"FollowCamera", "OpenImageView"},  # the C++ plugin's toolbar's
}
# properties of the plugin alone (not the package's): their setters are written below
GUI_PROPERTIES = {"SchlierenImage": {"FollowCamera": "_set_follow_camera",
                                     "InteractivePasses": "_set_interactive_passes"}}


def python_name(prop):
    """The name paraview.simple gives a property: its label without spaces and punctuation."""
    return re.sub(r"[^A-Za-z0-9_]", "", prop.get("label") or prop.get("name"))


# Follow Camera in the Python plugin: the FollowCamera and InteractivePasses properties drive
# schlieren_view's CameraFollower from the proxy's setters. ParaView 5.10-6.1 let a Python plugin add
# proxies and properties (paraview.util.vtkAlgorithm), not toolbars, reactions or macros (a macro
# is a file in the user's settings folder, listed when ParaView starts): a property in the panel is
# what a Python plugin can give without the user typing Python. The setter runs in the process that
# holds the filter: with the GUI's builtin server that is the GUI (its Python, its render views),
# so it finds the proxy and the render view there and follows its camera; on a remote pvserver there
# is no view in that process and it says so (pvpython: schlieren_view.follow_camera).
FOLLOW = '''
def _proxy_and_views(algorithm):
    """The paraview.simple proxy whose filter is `algorithm`, the render view to follow (the active
    one, else one showing the image's input, else the first) and the views showing the image."""
    from paraview import servermanager, simple
    proxy = None
    for p in simple.GetSources().values():
        try:
            if p.GetClientSideObject() is algorithm:
                proxy = p
        except Exception:  # noqa: BLE001 -- a proxy of a remote server: no client-side object
            pass
    if proxy is None:
        return None, None, []
    views = [v for v in simple.GetViews() if v.GetXMLName() == "RenderView"]
    source = proxy.Input
    active = simple.GetActiveView()
    follow = active if active in views else None
    shown = lambda p, v: servermanager.GetRepresentation(p, v) is not None and \\
        servermanager.GetRepresentation(p, v).Visibility  # (simple's would make one)
    for v in views:
        if follow is None and shown(source, v):
            follow = v
    follow = follow or (views[0] if views else None)
    shows = [v for v in simple.GetViews() if v is not follow and shown(proxy, v)]
    return proxy, follow, shows


def _follow_now(algorithm):
    """Starts or stops following as FollowCamera says (called once ParaView's property push is over)."""
    follower = algorithm.__dict__.get("_follower")
    if not algorithm.__dict__.get("_follow_wanted"):
        if follower is not None:
            follower.stop()
            object.__setattr__(algorithm, "_follower", None)
        return
    if follower is not None:
        return
    import schlieren_view
    try:
        proxy, view, shows = _proxy_and_views(algorithm)
    except Exception as e:  # noqa: BLE001
        proxy, view, shows = None, None, str(e)
    if proxy is None or view is None:
        algorithm._warn("Follow Camera: no render view in this process to follow (a remote "
                        "server?); in pvpython use schlieren_view.follow_camera(view, image).")
        return
    interactor = view.GetRenderWindow().GetInteractor()
    follower = schlieren_view.follow_camera(
        view, proxy, interactive_passes=algorithm.__dict__.get("_interactive_passes", 1),
        timer=interactor is not None and interactor.IsA("QVTKInteractor"))
    follower.also_render = shows
    # the image deleted from the pipeline: stop (its proxy is no longer registered)
    pxm = proxy.SMProxy.GetSessionProxyManager()
    follower.alive = lambda: bool(pxm.GetProxyName("sources", proxy.SMProxy))
    object.__setattr__(algorithm, "_follower", follower)


def _later(algorithm):
    """_follow_now once the current property push is done: from a one-shot timer of a render view's
    interactor (the GUI's Qt event loop runs it), or now where no view has one (pvpython)."""
    try:
        from paraview import simple
        views = [v for v in simple.GetViews() if v.GetXMLName() == "RenderView"]
    except Exception:  # noqa: BLE001 -- not in a ParaView client
        views = []
    # the GUI's views have Qt interactors (QVTKInteractor), whose timers its event loop runs;
    # pvpython's have none or an X one that nothing drives
    interactor = next((v.GetRenderWindow().GetInteractor() for v in views
                       if v.GetRenderWindow().GetInteractor() is not None and
                       v.GetRenderWindow().GetInteractor().IsA("QVTKInteractor")), None)
    if interactor is None:
        _follow_now(algorithm)
        return
    # the first timer event (this one-shot timer's or another's: any comes from the event loop,
    # after the push; QVTKInteractor does not set GetTimerEventId for its observers)
    interactor.CreateOneShotTimer(10)
    tag = []

    def fire(caller, event):
        caller.RemoveObserver(tag[0])
        _follow_now(algorithm)

    tag.append(interactor.AddObserver("TimerEvent", fire))


def _set_follow_camera(self, value):
    wanted = bool(int(value))
    if wanted != bool(self.__dict__.get("_follow_wanted")):
        object.__setattr__(self, "_follow_wanted", wanted)
        _later(self)


def _set_interactive_passes(self, value):
    object.__setattr__(self, "_interactive_passes", max(1, int(value)))
    follower = self.__dict__.get("_follower")
    if follower is not None:
        follower.interactive_passes = max(1, int(value))
'''

specs = {}
for proxy in PROXIES:
    p = proxies[proxy]
    xmls, props, kept = [], [], set()
    for child in p:
        child = ET.fromstring(ET.tostring(child))
        name = child.get("name")
        if child.tag == "InputProperty":
            if name in LEFT_OUT.get(proxy, ()):
                continue
        elif child.tag.endswith("VectorProperty"):
            if child.get("information_only") == "1" or name in LEFT_OUT.get(proxy, ()):
                continue
            # the setter the generated class has; the package's attribute is the proxy's name,
            # or the name paraview.simple gives it (SelectInputArray: InputArray)
            child.set("command", "Set" + name)
            for attr in ("panel_widget",):
                child.attrib.pop(attr, None)
            values = {e.get("value"): e.get("text") for e in child.iter("Entry")}
            props.append((name, python_name(child), values,
                          int(child.get("number_of_elements", "1")), child.tag))
        elif child.tag == "PropertyGroup":
            for q in list(child):
                if q.get("name") in LEFT_OUT.get(proxy, ()):
                    child.remove(q)
        elif child.tag == "Hints":
            # the menu (not the C++ plugin's icons, which are its Qt resources), the output
            # ports' names and default representations
            menu = child.find("ShowInMenu")
            port_hints = [h for h in child if h.tag in ("OutputPort", "RepresentationType")]
            child = ET.Element("Hints")
            if menu is not None:
                ET.SubElement(child, "ShowInMenu", category=menu.get("category"))
            for h in port_hints:
                child.append(h)
        elif child.tag != "Documentation":
            continue
        xmls.append(ET.tostring(child, encoding="unicode"))
    specs[proxy] = dict(label=p.get("label"), props=props, xmls=xmls)

out = ['# SPDX-License-Identifier: BSD-3-Clause',
       '# GENERATED by Plugin/make_python_plugin.py from Plugin/Schlieren.xml and Python/schlieren:',
       '# do not edit; edit those and rebuild.',
       '"""Schlieren as a ParaView Python plugin: RefractiveScene and SchlierenImage with the C++',
       "plugin's property names, defaults, domains and documentation, on the engine's C interface.",
       "",
       "Load it with Tools > Manage Plugins > Load New (or LoadPlugin('SchlierenPython.py') in",
       "pvpython) in any ParaView with Python and NumPy; libschlieren_engine.so.1 (Windows:",
       "libschlieren_engine.dll) must lie beside it",
       "(or SCHLIEREN_ENGINE_LIBRARY name it). Not together with the C++ plugin: the proxies have",
       'the same names."""',
       "import sys as _sys",
       "import types as _types",
       "",
       "_SOURCES = %r" % sources,
       "_SPECS = %r" % specs,
       "_GUI = %r" % GUI_PROPERTIES,
       "",
       "_PKG = 'schlieren_paraview_plugin'",
       "_pkg = _types.ModuleType(_PKG)",
       "_pkg.__path__ = []",
       "_sys.modules[_PKG] = _pkg",
       "for _name in ('_engine', 'png', 'algorithms'):",
       "    _m = _types.ModuleType(_PKG + '.' + _name)",
       "    _m.__package__ = _PKG",
       "    _m.__file__ = __file__  # the engine library is looked for beside this file",
       "    _sys.modules[_m.__name__] = _m",
       "    setattr(_pkg, _name, _m)",
       "    exec(compile(_SOURCES[_name], 'schlieren/%s.py' % _name, 'exec'), _m.__dict__)",
       "_alg = _pkg.algorithms",
       "",
       "# schlieren_view (Follow Camera from Python), as the C++ plugin embeds it: `import",
       "# schlieren_view` works after LoadPlugin, in pvpython, pvbatch and the GUI's Python shell",
       "_VIEW = %r" % view_source,
       "if _VIEW is not None and 'schlieren_view' not in _sys.modules:",
       "    _view = _types.ModuleType('schlieren_view')",
       "    _view.__file__ = __file__",
       "    exec(compile(_VIEW, 'schlieren_view.py', 'exec'), _view.__dict__)",
       "    _sys.modules['schlieren_view'] = _view",
       "",
       "from paraview.util.vtkAlgorithm import smproperty, smproxy  # noqa: E402",
       "",
       "",
       "def _setter(name, attr, values_map, size, tag):",
       "    def set_(self, *values):",
       "        # a value the package refuses is kept as the filter's error (Output Messages, an",
       "        # empty output until it is changed), never raised here: an exception out of a",
       "        # proxy's setter is a raw traceback, and the filter would run with the old value",
       "        # while the panel shows the new one",
       "        try:",
       "            value = _value(values_map, size, tag, values)",
       "        except (KeyError, TypeError, ValueError, IndexError) as e:",
       "            self._refused[attr] = '%s: %r is not a value of this property (%s)' % (",
       "                name, values, e)",
       "            self.Modified()",
       "            return",
       "        if getattr(self, attr) != value or attr in self._refused:",
       "            self.SetProperty(attr, value)",
       "    set_.__name__ = 'Set' + name",
       "    return set_",
       "",
       "",
       "def _value(values_map, size, tag, values):",
       "        if values_map:",
       "            value = values_map[str(int(values[0]))]  # the entry's text",
       "        elif tag == 'StringVectorProperty' and size == 5:",
       "            # an array selection (port, connection, association, name): the name",
       "            value = values[-1] if values[-1] not in (None, '', '(automatic)') else ''",
       "        elif tag == 'StringVectorProperty':",
       "            value = values[0] if values and values[0] is not None else ''  # empty: None",
       "        elif size == 1:",
       "            value = values[0]",
       "        else:",
       "            value = list(values)",
       "        return value",
       "",
       "",
       FOLLOW,
       "",
       "",
       "def _make(base, proxy, is_filter):",
       "    spec = _SPECS[proxy]",
       "    body = {'__doc__': base.__doc__}",
       "    for name, attr, values_map, size, tag in spec['props']:",
       "        if name in _GUI.get(proxy, {}):",
       "            body['Set' + name] = globals()[_GUI[proxy][name]]",
       "            continue",
       "        if attr not in base._defaults:",
       "            raise ImportError('SchlierenPython: %s.%s (%s) is in the XML, not in the package: '",
       "                              'regenerate the plugin' % (proxy, name, attr))",
       "        body['Set' + name] = _setter(name, attr, values_map, size, tag)",
       "    cls = type(proxy, (base,), body)",
       "    # the properties' XML on the class, in the C++ plugin's order (Input, groups, menu)",
       "    for x in spec['xmls']:",
       "        cls = smproperty.xml(xmlstr=x)(cls)",
       "    if is_filter:",
       "        return smproxy.filter(name=proxy, label=spec['label'])(cls)",
       "    return smproxy.source(name=proxy, label=spec['label'])(cls)",
       "",
       "",
       "RefractiveScene = _make(_alg.RefractiveScene, 'RefractiveScene', False)",
       "RefractiveIndex = _make(_alg.RefractiveIndex, 'RefractiveIndex', True)",
       "RefractionOctree = _make(_alg.RefractionOctree, 'RefractionOctree', True)",
       "SchlierenImage = _make(_alg.SchlierenImage, 'SchlierenImage', True)",
       "NumericalSchlieren = _make(_alg.NumericalSchlieren, 'NumericalSchlieren', True)",
       "SchlierenPhotograph = _make(_alg.SchlierenPhotograph, 'SchlierenPhotograph', True)",
       ""]
with open(args.output, "w") as f:
    f.write("\n".join(out))
