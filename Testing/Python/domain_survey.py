# SPDX-License-Identifier: BSD-3-Clause
"""Every numeric property of the plugin's proxies, as Plugin/Schlieren.xml lists them, set at its
range domain's ends (an image expected) and just past them (an error naming the property
expected); prints one row per setting. BAD: an error at an end, or no error naming the property
past one (a clamp, or a value the code takes silently).

Run: pvpython domain_survey.py --plugin <Schlieren.so> [--proxies A,B] [--strict]

The list comes from the XML: every IntVectorProperty and DoubleVectorProperty of every
SourceProxy. A property with no range domain (or one with neither end) has no ends to walk and is
counted as such; a property with no command is the GUI's (the toolbar reads it: nothing reaches
the filter) and is counted apart. An error at an end that is the memory check's refusal (a film
or volume larger than the machine's memory) is a resource limit, not a domain's, and is allowed;
work still going after 2 s is aborted (the value was taken).

--proxies: only these proxies; --strict: exit 1 where any row is BAD or no row was made
(python.domains runs it strict on the four tracing proxies; NumericalSchlieren's domains are
walked by python.numerical, its Resolution at 16384 x 16384 taking minutes here).
"""
import os
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import schlieren_testing as st

st.load_plugin(globals())

root = ET.parse(os.path.join(HERE, "..", "..", "Plugin", "Schlieren.xml")).getroot()
only = st.argument("--proxies")
only = only.split(",") if only else None


def make(pname):
    """A small pipeline ending in `pname`'s proxy; (the proxy, every proxy to delete)."""
    if pname == "RefractiveScene":
        p = RefractiveScene(Dimensions=[12] * 3)
        return p, [p]
    s = RefractiveScene(Dimensions=[12] * 3)
    if pname == "RefractiveIndex":
        p = RefractiveIndex(Input=s, Model="Passthrough")
    elif pname == "RefractionOctree":
        p = RefractionOctree(Input=s)
    elif pname == "NumericalSchlieren":
        p = NumericalSchlieren(Input=s, Resolution=[8, 8])
    else:
        p = SchlierenImage(Input=s, Resolution=[8, 8], Backend="CPU")
    return p, [p, s]


def fetch(p):
    """Updates `p`, aborting work still going after 2 s (a value at a domain's end that asks for
    long work, Passes = 1000000: it was taken, the work was under way)."""
    import time

    algo = p.GetClientSideObject()
    start = time.time()

    def on_progress(obj, event):
        if time.time() - start > 2:
            obj.SetAbortExecute(1)

    tag = algo.AddObserver("ProgressEvent", on_progress)
    try:
        sm.Fetch(p)
    finally:
        algo.RemoveObserver(tag)
        algo.SetAbortExecute(0)


def value_of(v, n, isint):
    v = int(v) if isint else v
    return [v] * n if n > 1 else v


rows = []
counts = dict(numeric=0, walked=0, no_range=0, client_side=0)
for proxy in root.iter("SourceProxy"):
    pname = proxy.get("name")
    if only and pname not in only:
        continue
    pipeline = None
    for prop in proxy:
        if prop.tag not in ("IntVectorProperty", "DoubleVectorProperty"):
            continue
        if prop.get("information_only") == "1":
            continue
        counts["numeric"] += 1
        name = prop.get("name")
        if prop.get("command") is None:
            counts["client_side"] += 1
            continue
        dom = prop.find("IntRangeDomain")
        if dom is None:
            dom = prop.find("DoubleRangeDomain")
        if dom is None or (dom.get("min") is None and dom.get("max") is None):
            counts["no_range"] += 1
            continue
        counts["walked"] += 1
        n = int(prop.get("number_of_elements", "1"))
        isint = prop.tag == "IntVectorProperty"
        default = [float(v) for v in prop.get("default_values", "0").split()]
        default = [int(v) for v in default] if isint else default
        default = default if n > 1 else default[0]
        if pipeline is None:
            pipeline = make(pname)
        p = pipeline[0]
        for which in ("min", "max"):
            if dom.get(which) is None:
                continue
            end = float(dom.get(which).split()[0])
            step = 1 if isint else max(abs(end) * 1e-3, 1e-9)
            past = end - step if which == "min" else end + step
            for label, v in (("at", end), ("past", past)):
                val = value_of(v, n, isint)
                try:
                    setattr(p, name, val)
                    with st.CapturedOutput() as out:
                        fetch(p)
                    aborted = "): aborted" in out.text
                    err = ("ERROR" in out.text or "ERR|" in out.text) and not aborted
                    named = name in out.text
                    memory = "memory" in out.text
                    text = out.text
                except Exception as e:  # a value ParaView itself refuses to set
                    err, named, memory, text = "EXC", False, False, str(e)
                finally:
                    setattr(p, name, default)
                if err:
                    # a failed update can leave requests behind (an update extent of the film
                    # refused): the next setting starts on a fresh pipeline
                    for q in pipeline[1]:
                        Delete(q)
                    pipeline = make(pname)
                    p = pipeline[0]
                line = ""
                for ln in text.splitlines():
                    if name in ln or ("ERR" in ln and not line):
                        line = ln.split("): ", 1)[-1].strip()
                rows.append((pname, name, which, label, val, err, named, memory, line, text))
    if pipeline is not None:
        for q in pipeline[1]:
            Delete(q)

# The enumeration and boolean properties: each entry taken (an image, or an error that is not
# the domain's: a memory refusal, or a model needing arrays the small pipeline lacks, which
# names neither the property nor "must be one of"), and just below the smallest / above the
# largest entry (booleans: -1 and 2) refused with an error naming the property.
enum_counts = dict(walked=0, client_side=0)
for proxy in root.iter("SourceProxy"):
    pname = proxy.get("name")
    if only and pname not in only:
        continue
    pipeline = None
    for prop in proxy:
        if prop.tag != "IntVectorProperty" or prop.get("information_only") == "1":
            continue
        enum, boolean = prop.find("EnumerationDomain"), prop.find("BooleanDomain")
        if enum is None and boolean is None:
            continue
        name = prop.get("name")
        if prop.get("command") is None:
            enum_counts["client_side"] += 1
            continue
        enum_counts["walked"] += 1
        values = [int(e.get("value")) for e in enum.findall("Entry")] if enum is not None else [0, 1]
        default = int(prop.get("default_values", "0").split()[0])
        if pipeline is None:
            pipeline = make(pname)
        p = pipeline[0]
        tries = [("entry", v) for v in values] + [("below", min(values) - 1), ("above", max(values) + 1)]
        for label, v in tries:
            try:
                p.SetPropertyWithName(name, v)
                with st.CapturedOutput() as out:
                    fetch(p)
                aborted = "): aborted" in out.text
                err = ("ERROR" in out.text or "ERR|" in out.text) and not aborted
                named = name + " is %d" % v in out.text
                memory = "memory" in out.text or ("must be one of" not in out.text and
                                                  "must be 0 (off)" not in out.text)
                text = out.text
            except Exception as e:
                err, named, memory, text = "EXC", False, False, str(e)
            finally:
                p.SetPropertyWithName(name, default)
            if err:
                for q in pipeline[1]:
                    Delete(q)
                pipeline = make(pname)
                p = pipeline[0]
            line = ""
            for ln in text.splitlines():
                if name in ln or ("ERR" in ln and not line):
                    line = ln.split("): ", 1)[-1].strip()
            which = "entry" if label == "entry" else label
            rows.append((pname, name, which, "at" if label == "entry" else "past", v, err,
                         named, memory, line, text))
    if pipeline is not None:
        for q in pipeline[1]:
            Delete(q)


def is_bad(label, err, named, memory):
    if label == "at":
        return err is True and not memory
    return not (err is True and named)


nbad = 0
for pname, name, which, label, val, err, named, memory, line, text in rows:
    bad = is_bad(label, err, named, memory)
    nbad += bad
    print("%-4s %-17s %-24s %s %-4s %-16s err=%-5s named=%-5s %s" % (
        "BAD" if bad else "ok", pname, name, which, label, str(val)[:16], err, named,
        line[:110]))
    if bad:
        print("     what it said: " + " | ".join(
            ln.strip() for ln in text.splitlines() if ln.strip())[:700])
print("domain_survey: %d numeric properties: %d walked, %d without a range domain, %d the GUI's "
      "(no command); %d settings, %d BAD" % (
          counts["numeric"], counts["walked"], counts["no_range"], counts["client_side"],
          len(rows), nbad))
print("domain_survey: %d enumeration/boolean properties walked (every entry, and just past "
      "the ends), %d the GUI's (no command)" % (enum_counts["walked"], enum_counts["client_side"]))
if "--strict" in sys.argv and (nbad or not rows):
    sys.exit(1)
