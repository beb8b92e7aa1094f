# SPDX-License-Identifier: BSD-3-Clause
"""The C++ plugin's images of frontend_cases.py, for test_frontend.py to compare with.

    pvpython frontend_reference.py --plugin Schlieren.so --output DIR [--data ../shared/data]

Writes DIR/<case>_<backend>.npz (image arrays, film origin/spacing/extent, field data) and
DIR/bluntfin_index.vti (RefractiveIndex's grid of the blunt fin, which both front ends trace).
The OpenCL references are written only where an OpenCL device works (file DIR/opencl.txt says
which device, or why none). RefractiveIndex's parity matrix (frontend_cases.INDEX): its inputs as
DIR/input_<name>.vti/.vts/.vtu/.vtm (frontend_matrix.make_inputs; the blunt fin and
disk_out_ref.ex2 where ../shared/data has them) and the C++ plugin's records DIR/index_<case>.npz
(frontend_matrix.record: the index's grid, point arrays and field data, the film on it)."""
import argparse
import json
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import LoadPlugin, PLOT3DReader, XMLImageDataReader
from vtkmodules.util import numpy_support
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import frontend_cases as cases  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--output", required=True)
ap.add_argument("--openfoam", help="openfoam_cases.py's folder (the matrix's OpenFOAM inputs)")
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

# RefractiveIndex's matrix (frontend_cases.INDEX): the inputs written as VTK XML files that every
# leg reads, the C++ plugin's index and film on each (DIR/index_<case>.npz)
import time  # noqa: E402

import frontend_matrix as matrix  # noqa: E402
matrix_started = time.time()
for old in os.listdir(args.output):  # an earlier run's, which may have had the data
    if old.startswith(("input_", "index_")):
        path = os.path.join(args.output, old)
        if os.path.isdir(path):
            import shutil
            shutil.rmtree(path)
        else:
            os.remove(path)
from paraview.simple import Delete, ExodusIIReader, PVTrivialProducer  # noqa: E402
scene = ns["RefractiveScene"](Dimensions=[24, 20, 16])
scene.UpdatePipeline()
readers = {}
if os.path.exists(xyz) and os.path.exists(q):
    readers["bluntfin"] = servermanager.Fetch(PLOT3DReader(FileName=xyz, QFileName=[q]))
exo = os.path.join(args.data, "disk_out_ref.ex2")
if os.path.exists(exo):
    disk = ExodusIIReader(FileName=exo)
    disk.PointVariables = ["Temp", "V"]
    # its hexahedra (the Exodus multiblock's one unstructured block: the XML writer refuses the
    # empty side-set blocks)
    it = servermanager.Fetch(disk).NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        if it.GetCurrentDataObject().GetNumberOfCells() > 0 and "disk" not in readers:
            readers["disk"] = it.GetCurrentDataObject()
        it.GoToNextItem()
# the suite's OpenFOAM cases (openfoam_cases.py, the schlieren_openfoam fixture) where solved: the
# axisymmetric wedge at its time 0 (a converged solution), the forward step at t = 2; T and p only
# (with U the C++ filter finds bodies beside the walls, which the Python front end does not yet)
for name, case, time_value in (("ladenburg", "LadenburgJet60psi", 0.0),
                               ("forward_step", "forwardStep", 2.0)):
    foam = os.path.join(args.openfoam or "/nonexistent", case, "case.foam")
    if not os.path.exists(foam):
        print("frontend_reference: no %s (run openfoam_cases.py; --openfoam %s)"
              % (foam, args.openfoam))
        continue
    from paraview.simple import OpenFOAMReader
    reader = OpenFOAMReader(FileName=foam)
    reader.SkipZeroTime = 0
    reader.Refresh()
    reader.UpdatePipelineInformation()
    reader.CellArrays = ["T", "p"]
    reader.UpdatePipeline(time_value)
    readers[name] = servermanager.Fetch(reader)
    Delete(reader)
used = {which for which, _, _ in cases.INDEX.values()} | set(cases.INDEX_BODY.values())
for name, data in matrix.make_inputs(servermanager.Fetch(scene), readers).items():
    if name in used:  # (an input no case reads yet is not written: the AMR one)
        matrix.write_input(args.output, name, data)
for case, (which, props, image_props) in cases.INDEX.items():
    data = matrix.read_input(args.output, which)
    if data is None:
        print("frontend_reference: %s left out: no %s in %s" % (case, which, args.data))
        continue
    source = PVTrivialProducer()
    source.GetClientSideObject().SetOutput(data)
    body = {}
    if case in cases.INDEX_BODY:  # the Body input (port 1)
        body["Body"] = PVTrivialProducer()
        body["Body"].GetClientSideObject().SetOutput(
            matrix.read_input(args.output, cases.INDEX_BODY[case]))
    index = ns["RefractiveIndex"](Input=source, **body, **matrix.proxy_properties(props, case))
    image = ns["SchlierenImage"](Input=index, **dict(cases.INDEX_IMAGE, **image_props))
    image.UpdatePipeline()
    got = matrix.record(servermanager.Fetch(index), servermanager.Fetch(image))
    np.savez(os.path.join(args.output, "index_%s.npz" % case), **got)
    print("frontend_reference: %s: %d index arrays, film %s" % (
        case, len(json.loads(str(got["index_arrays"]))), got["film_geometry"][:6].tolist()))
    for proxy in [image, index, source] + list(body.values()):
        Delete(proxy)
print("frontend_reference: RefractiveIndex's matrix in %.1f s" % (time.time() - matrix_started))
with open(os.path.join(args.output, "opencl.txt"), "w") as f:
    f.write(opencl + "\n")
