# SPDX-License-Identifier: BSD-3-Clause
"""The C interface's SchlierenImage properties (schlieren_properties(), which the Python package's
keywords, attributes and defaults come from) against the C++ plugin's Plugin/Schlieren.xml: the
same names, element counts, defaults and enumeration entries, so that neither can drift from
the other unnoticed. The XML's properties that are the GUI's (the Follow group, the image view)
are not the engine's and are listed here by name.

    python test_frontend_properties.py --xml Plugin/Schlieren.xml"""
import argparse
import sys
import xml.etree.ElementTree as ET

import schlieren

GUI_ONLY = {"FollowCamera", "InteractivePasses", "InteractiveScale", "OpenImageView", "PassLimit"}

ap = argparse.ArgumentParser()
ap.add_argument("--xml", required=True)
args = ap.parse_args()
proxy = [p for p in ET.parse(args.xml).getroot().iter("SourceProxy")
         if p.get("name") == "SchlierenImage"][0]
xml = {}
for prop in proxy:
    if not prop.tag.endswith("VectorProperty") or prop.get("name") is None:
        continue
    if prop.get("information_only") == "1":
        continue
    entries = [e.get("text") for e in prop.iter("Entry")]
    values = prop.get("default_values", "")
    xml[prop.get("name")] = dict(size=int(prop.get("number_of_elements", "1")),
                                 default=values, entries=entries,
                                 kind=prop.tag)
api = {p["name"]: p for p in schlieren.properties()}
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


engine_xml = set(xml) - GUI_ONLY
check(engine_xml == set(api), "the same property names (XML only: %s; C API only: %s)"
      % (sorted(engine_xml - set(api)), sorted(set(api) - engine_xml)))
for name in sorted(engine_xml & set(api)):
    x, a = xml[name], api[name]
    check(x["size"] == a["size"], "%s: %d elements" % (name, a["size"]))
    if a["kind"] == "enum":
        check(x["entries"] == a["entries"], "%s: entries %s" % (name, a["entries"]))
        check(x["entries"][int(x["default"])] == a["default"] if x["entries"] else False,
              "%s: default %s" % (name, a["default"]))
    elif a["kind"] == "string":
        check(x["default"] == a["default"], "%s: default %r" % (name, a["default"]))
    else:
        want = [float(v) for v in x["default"].split()]
        have = a["default"] if isinstance(a["default"], list) else [a["default"]]
        check([float(v) for v in have] == want, "%s: default %s (XML %s)" % (name, have, want))

# the other proxies the package implements: its algorithms' keywords and defaults against the XML
# (the names paraview.simple gives: the labels without spaces; what the package leaves out is
# listed by name, as the Python plugin's test lists it)
import re  # noqa: E402
# (RefractiveIndex's Body is an input, not a keyword: the package's class takes it on port 1)
LEFT_OUT = {"RefractiveScene": {"TimeSteps"},
            "NumericalSchlieren": {"FollowCamera", "OpenImageView"}}  # the GUI's
root = ET.parse(args.xml).getroot()
for proxy_name in ("RefractiveScene", "RefractiveIndex", "RefractionOctree", "NumericalSchlieren",
                   "SchlierenPhotograph"):
    cls = getattr(schlieren, proxy_name)
    px = [p for p in root.iter("SourceProxy") if p.get("name") == proxy_name][0]
    props = {}
    for prop in px:
        if not prop.tag.endswith("VectorProperty") or prop.get("information_only") == "1" or \
                prop.get("name") in LEFT_OUT.get(proxy_name, ()):
            continue
        props[re.sub(r"[^A-Za-z0-9_]", "", prop.get("label") or prop.get("name"))] = prop
    check(set(props) == set(cls._defaults), "%s: the same properties (XML only: %s; package "
          "only: %s)" % (proxy_name, sorted(set(props) - set(cls._defaults)),
                         sorted(set(cls._defaults) - set(props))))
    for name in sorted(set(props) & set(cls._defaults)):
        prop, have = props[name], cls._defaults[name]
        want = prop.get("default_values", "")
        entries = {e.get("value"): e.get("text") for e in prop.iter("Entry")}
        size = int(prop.get("number_of_elements", "1"))
        if entries:
            ok = cls._entries.get(name) == list(entries.values()) and have == entries[want]
        elif prop.tag == "StringVectorProperty":
            ok = have == ("" if size == 5 and want.endswith("(automatic)") else want)
        else:
            h = have if isinstance(have, list) else [have]
            ok = len(h) == size and [float(v) for v in h] == [float(v) for v in want.split()]
        check(ok, "%s.%s: default %r, entries %s (XML %r, %s)" % (
            proxy_name, name, have, cls._entries.get(name), want, list(entries.values())))
print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
