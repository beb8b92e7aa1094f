# SPDX-License-Identifier: BSD-3-Clause
"""A survey, not a pass/fail test: every numeric property with a range domain in
Plugin/Schlieren.xml set at its domain's ends and just past them; prints for each whether the
filter gave an error and whether the error named the property. BAD: an error inside the domain,
or no error naming the property outside it (a clamp, or a value the code takes silently).

Run: pvpython domain_survey.py --plugin <Schlieren.so> [--proxies A,B] [--strict]

--proxies: only these proxies; --strict: exit 1 where any row is BAD (python.domains runs it
strict on the proxies whose domains and code agree: RefractiveScene, RefractionOctree;
NumericalSchlieren agrees too, surveyed by hand: its Resolution at 16384 x 16384 takes minutes).
"""
import sys, math
import xml.etree.ElementTree as ET
import os
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from paraview.simple import *
from paraview import servermanager as sm
import schlieren_testing as st
st.load_plugin(globals())

root = ET.parse(os.path.join(HERE, "..", "..", "Plugin", "Schlieren.xml")).getroot()
rows = []
only = st.argument("--proxies")
only = only.split(",") if only else None
for proxy in root.iter("SourceProxy"):
    pname = proxy.get("name")
    if only and pname not in only:
        continue
    for prop in proxy:
        if prop.tag not in ("IntVectorProperty", "DoubleVectorProperty"):
            continue
        dom = prop.find("IntRangeDomain") or prop.find("DoubleRangeDomain")
        if dom is None:
            dom = prop.find("IntRangeDomain")
        if dom is None:
            dom = prop.find("DoubleRangeDomain")
        if dom is None or (dom.get("min") is None and dom.get("max") is None):
            continue
        n = int(prop.get("number_of_elements", "1"))
        default = [float(v) for v in prop.get("default_values", "0").split()]
        isint = prop.tag == "IntVectorProperty"
        mins = [float(v) for v in (dom.get("min") or "").split()] or [None]
        maxs = [float(v) for v in (dom.get("max") or "").split()] or [None]
        for which, ends in (("min", mins), ("max", maxs)):
            if ends[0] is None:
                continue
            end = ends[0]
            step = 1 if isint else max(abs(end) * 1e-3, 1e-9)
            for label, v in (("at", end), ("past", end - step if which == "min" else end + step)):
                val = [int(v) if isint else v] * n if n > 1 else (int(v) if isint else v)
                try:
                    if pname == "RefractiveScene":
                        p = RefractiveScene(Dimensions=[12] * 3)
                        q = p
                    elif pname == "RefractiveIndex":
                        s = RefractiveScene(Dimensions=[12] * 3)
                        p = RefractiveIndex(Input=s, Model="Passthrough")
                        q = p
                    elif pname == "RefractionOctree":
                        s = RefractiveScene(Dimensions=[12] * 3)
                        p = RefractionOctree(Input=s)
                        q = p
                    elif pname == "NumericalSchlieren":
                        s = RefractiveScene(Dimensions=[12] * 3)
                        p = NumericalSchlieren(Input=s, Resolution=[8, 8])
                        q = p
                    else:
                        s = RefractiveScene(Dimensions=[12] * 3)
                        p = SchlierenImage(Input=s, Resolution=[8, 8], Backend="CPU")
                        q = p
                    setattr(p, prop.get("name"), val)
                    with st.CapturedOutput() as out:
                        d = sm.Fetch(q)
                    err = "ERROR" in out.text or "ERR|" in out.text
                    named = prop.get("name") in out.text
                    got = p.GetClientSideObject()
                    getter = getattr(got, "Get" + prop.get("command", "Set" + prop.get("name"))[3:], None)
                    actual = getter() if getter else "?"
                    rows.append((pname, prop.get("name"), which, label, val, err, named, actual))
                except Exception as e:
                    rows.append((pname, prop.get("name"), which, label, val, "EXC", str(e)[:60], ""))
for r in rows:
    pname, name, which, label, val, err, named, actual = r
    bad = (label == "at" and err is True) or (label == "past" and not (err is True and named))
    print("%-4s %-17s %-24s %s %-4s %-14s err=%-5s named=%-5s actual=%s" % (
        "BAD" if bad else "ok", pname, name, which, label, str(val)[:14], err, named, str(actual)[:40]))
nbad = 0
for r in rows:
    label, err, named = r[3], r[5], r[6]
    nbad += (label == "at" and err is True) or (label == "past" and not (err is True and named))
print("domain_survey: %d settings, %d BAD" % (len(rows), nbad))
if "--strict" in sys.argv and (nbad or not rows):
    sys.exit(1)
