# SPDX-License-Identifier: BSD-3-Clause
"""RefractiveIndex's resampling of a mesh, cell by cell, against vtkProbeFilter's.

Run: pvpython test_resample.py --plugin <Schlieren.so>

RefractiveIndex samples a non-image mesh cell by cell (SchlierenResample.h) instead of probing
point by point; the values must be the probe's. Two meshes: the Wavelet tetrahedralized (a convex
domain) and the Wavelet's hexahedra thresholded on RTData (a non-convex region with holes), on a
grid that does not line up with the mesh's points. Checked against vtkCompositeDataProbeFilter on
the same image grid: as many points found (vtkValidPointMask; a point found by one and not the
other would also show as a value difference), RTData (passed to the output with its type) and
n - 1 equal where found to float rounding (1e-6 of the range: the interpolation is the probe's own
vtkDataArray::InterpolateTuple).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersCore import vtkCompositeDataProbeFilter

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_resample")

wavelet = Wavelet(WholeExtent=[-8, 8] * 3)
withcells = PointDatatoCellData(Input=wavelet, PassPointData=1)
tets = Tetrahedralize(Input=withcells)
holes = Threshold(Input=withcells, Scalars=["POINTS", "RTData"], LowerThreshold=120,
                  UpperThreshold=300)
DIMS = [37, 29, 33]
for label, mesh_proxy in (("tetrahedra", tets), ("thresholded hexahedra", holes)):
    n1 = Calculator(Input=mesh_proxy, ResultArrayName="n_minus_1", Function="RTData*1e-6")
    index = RefractiveIndex(Input=n1, Model="Passthrough", SamplingDimensions=DIMS)
    with st.CapturedOutput():
        index.UpdatePipeline()
    out = index.GetClientSideObject().GetOutputDataObject(0)
    mesh = n1.GetClientSideObject().GetOutputDataObject(0)
    structure = vtkImageData()
    structure.SetDimensions(*out.GetDimensions())
    structure.SetOrigin(*out.GetOrigin())
    structure.SetSpacing(*out.GetSpacing())
    probe = vtkCompositeDataProbeFilter()
    probe.SetInputData(structure)
    probe.SetSourceData(mesh)
    probe.Update()
    ref = probe.GetOutput()
    mask = vtk_to_numpy(ref.GetPointData().GetArray("vtkValidPointMask")) != 0
    inside = int(mask.sum())
    # RefractiveIndex's output has no mask; its valid_point_fraction counts the points found
    fraction = out.GetFieldData().GetArray("valid_point_fraction").GetValue(0)
    T.check(abs(fraction - inside / mask.size) < 0.5 / mask.size,
            "%s: the points found are the probe's (%d of %d; valid_point_fraction %.6f)"
            % (label, inside, mask.size, fraction))
    for name, scale in (("RTData", 1.0), ("n_minus_1", 1e-6)):
        ours = vtk_to_numpy(out.GetPointData().GetArray(name)).astype(float)
        theirs = vtk_to_numpy(ref.GetPointData().GetArray(name)).astype(float)
        d = np.abs(ours - theirs)[mask].max() / (scale * 300)
        T.check(d <= 1e-6, "%s: %s equals the probe's where found (largest difference %.2g of "
                "300 %s)" % (label, name, d, "x 1e-6" if scale != 1.0 else ""))
    a = out.GetPointData().GetArray("RTData")
    T.check(a is not None and a.GetDataType() == ref.GetPointData().GetArray("RTData").GetDataType(),
            "%s: the input's point array passes to the output with its type" % label)

T.finish()
