# SPDX-License-Identifier: BSD-3-Clause
"""The C++ plugin's images of frontend_cases.py, for test_frontend.py to compare with.

    pvpython frontend_reference.py --plugin Schlieren.so --output DIR [--data ../shared/data]

Writes DIR/<case>_<backend>.npz (image arrays, film origin/spacing/extent, field data) and
DIR/bluntfin_index.vti (RefractiveIndex's grid of the blunt fin, which both front ends trace) and
DIR/amr.vthb (frontend_cases.AMR's overlapping AMR, which both front ends resample and trace).
The OpenCL references are written only where an OpenCL device works (file DIR/opencl.txt says
which device, or why none)."""
import argparse
import json
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import LoadPlugin, PLOT3DReader, PVTrivialProducer, XMLImageDataReader
from vtkmodules.util import numpy_support
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import frontend_cases as cases  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--output", required=True)
ap.add_argument("--data", default=os.environ.get("SCHLIEREN_DATA") or os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared", "data"))
args = ap.parse_args()
os.makedirs(args.output, exist_ok=True)
LoadPlugin(args.plugin, remote=False, ns=globals())
ns = globals()


def save(name, proxy):
    proxy.UpdatePipeline()
    img = servermanager.Fetch(proxy)
    out = {"origin": np.array(img.GetOrigin()), "spacing": np.array(img.GetSpacing()),
           "extent": np.array(img.GetExtent())}
    for a in cases.ARRAYS:
        arr = img.GetPointData().GetArray(a)
        if arr is not None:
            out["array_" + a] = numpy_support.vtk_to_numpy(arr).copy()
    fd = img.GetFieldData()
    fields = {}
    for f in cases.FIELDS:
        arr = fd.GetAbstractArray(f)
        if arr is not None:
            fields[f] = arr.GetValue(0)
    out["fields"] = np.array(json.dumps(fields))
    out["field_data"] = np.array(json.dumps(cases.field_data_list(fd)))  # every entry, in order
    np.savez(os.path.join(args.output, name + ".npz"), **out)
    return fields


sources = {}
for name, props in cases.SCENES.items():
    sources[name] = ns["RefractiveScene"](**props)
    for stage, stage_props in cases.STAGES.get(name, []):
        sources[name] = ns[stage](Input=sources[name], **stage_props)
xyz, q = os.path.join(args.data, "bluntfinxyz.bin"), os.path.join(args.data, "bluntfinq.bin")
if os.path.exists(xyz) and os.path.exists(q):
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                    "Examples"))
    from bluntfin import blunt_fin_index  # the example's pipeline
    index = blunt_fin_index(ns, args.data, SamplingDimensions=[64, 32, 36])
    index.UpdatePipeline()
    w = vtkXMLImageDataWriter()
    w.SetInputData(servermanager.Fetch(index))
    w.SetFileName(os.path.join(args.output, "bluntfin_index.vti"))
    w.Write()
    # the C++ side traces the file too: both read the same bytes
    sources["bluntfin"] = XMLImageDataReader(
        FileName=[os.path.join(args.output, "bluntfin_index.vti")])
else:
    print("frontend_reference: no blunt fin data in %s; that case is left out" % args.data)



def write_amr(path):
    """frontend_cases.AMR's overlapping AMR (amr_cases.py, cell data), written as a .vthb."""
    from amr_cases import two_level_amr
    from vtkmodules.vtkIOXML import vtkXMLUniformGridAMRWriter
    w = vtkXMLUniformGridAMRWriter()
    w.SetInputData(two_level_amr(True, cases.AMR["cells0"]))
    w.SetFileName(path)
    w.Write()

def read_amr(path):
    """The .vthb as both sides read it: every level (vtkXMLUniformGridAMRReader)."""
    from vtkmodules.vtkIOXML import vtkXMLUniformGridAMRReader
    r = vtkXMLUniformGridAMRReader()
    r.SetFileName(path)
    r.SetMaximumLevelsToReadByDefault(0)  # 0: every level
    r.Update()
    return r.GetOutputDataObject(0)


amr_path = os.path.join(args.output, "amr.vthb")
write_amr(amr_path)
amr_source = PVTrivialProducer()
amr_source.GetClientSideObject().SetOutput(read_amr(amr_path))
# (CELLS: the array's association in every box; a name a box holds only as cells but asked for
# as POINTS is converted to points by ParaView's vtkPVPostFilter before the filter sees it)
amr_index = ns["RefractiveIndex"](Input=amr_source, **{
    k: (["CELLS", v] if k == "InputArray" else v) for k, v in cases.AMR["index"].items()})
sources["amr"] = amr_index

opencl = "none"
for backend in cases.BACKENDS:
    for name, source in sources.items():
        image = ns["SchlierenImage"](Input=source, Backend=backend, **cases.IMAGES[name])
        try:
            fields = save("%s_%s" % (name, backend), image)
        except Exception as e:  # noqa: BLE001 (an OpenCL failure under Backend OpenCL)
            print("frontend_reference: %s on %s failed: %s" % (name, backend, e))
            raise
        print("frontend_reference: %s %s: %s" % (name, backend, fields))
        if backend == "OpenCL":
            opencl = fields.get("backend", "?")
for name, (scene, props) in cases.NUMERICAL.items():
    fields = save(name, ns["NumericalSchlieren"](Input=sources[scene], **props))
    print("frontend_reference: %s: %s" % (name, fields))
with open(os.path.join(args.output, "opencl.txt"), "w") as f:
    f.write(opencl + "\n")
