# SPDX-License-Identifier: BSD-3-Clause
"""The speckle of the first passes (docs/GUI.md): isolated black and white pixels counted against
the passes, without and with the Cone film filter, on gui_drag_scene.py's volume (the blunt fin).

    pvpython Testing/Benchmarks/speckle.py build/lib/paraview-5.11/plugins/Schlieren/Schlieren.so [film]

A speckle pixel differs by more than 0.25 from the median of its 3x3 neighbourhood.
"""
import sys, os, numpy as np
from paraview.simple import *
import paraview.simple as simple
LoadPlugin(sys.argv[1], remote=False, ns=simple.__dict__)
LoadPlugin(sys.argv[1], remote=False, ns=globals())
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
import gui_drag_scene, paraview.simple as simple
data = os.environ.get("SCHLIEREN_DATA", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared", "data"))
vol, scene = gui_drag_scene.volume(simple, data)
print("volume:", scene)
from vtkmodules.util.numpy_support import vtk_to_numpy
from scipy.ndimage import median_filter
d = np.array([-0.8675, 0.0138, 0.4974]); d /= np.linalg.norm(d)
res = int(sys.argv[2]) if len(sys.argv) > 2 else 160
for filt in ("None", "Cone"):
    img = SchlierenImage(Input=vol, Resolution=[res, res], Passes=1, Cutoff="KnifeEdge", CutoffScale=250.0,
                         Backend="CPU", Seed=4, ViewDirection=list(d), ViewUp=[0.21, 0.906, 0.36], Filter=filt)
    for p in (1, 2, 4, 8, 16, 64):
        img.Passes = p
        img.UpdatePipeline()
        o = servermanager.Fetch(img)
        nx, ny, _ = o.GetDimensions()
        I = vtk_to_numpy(o.GetPointData().GetArray("intensity")).reshape(ny, nx)
        m = median_filter(I, 3)
        sp = np.abs(I - m) > 0.25
        fd = o.GetFieldData()
        lp = fd.GetArray("landed_photons")
        print("filter %s res %d passes %3d: speckle pixels %4d (%.2f %%), black %d white %d, NaN %d, landed %s" % (
            filt, res, p, sp.sum(), 100.0 * sp.mean(), (sp & (I < m)).sum(), (sp & (I > m)).sum(),
            np.isnan(I).sum(), lp.GetValue(0) if lp else None))
    Delete(img)
