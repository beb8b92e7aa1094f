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
print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
