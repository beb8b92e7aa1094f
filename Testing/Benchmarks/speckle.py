# SPDX-License-Identifier: BSD-3-Clause
"""The speckle of the first passes (docs/GUI.md): isolated black and white pixels counted against
the passes, without and with the Cone film filter, and with JitterPattern Lattice, on
gui_drag_scene.py's volume (the blunt fin).

    pvpython Testing/Benchmarks/speckle.py build/lib/paraview-*/plugins/Schlieren/Schlieren.so [film] [png]

With png: also writes one pass Random, one pass Lattice and 64 passes Random side by side (320^2,
OpenCL, intensity clipped to [0, 1]) and prints their RMS against the 64-pass image.

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
for filt, pattern in (("None", "Random"), ("Cone", "Random"), ("None", "Lattice")):
    img = SchlierenImage(Input=vol, Resolution=[res, res], Passes=1, Cutoff="KnifeEdge", CutoffScale=250.0,
                         Backend="CPU", Seed=4, ViewDirection=list(d), ViewUp=[0.21, 0.906, 0.36], Filter=filt,
                         JitterPattern=pattern)
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
        print("filter %s %s res %d passes %3d: speckle pixels %4d (%.2f %%), black %d white %d, NaN %d, landed %s" % (
            filt, pattern, res, p, sp.sum(), 100.0 * sp.mean(), (sp & (I < m)).sum(), (sp & (I > m)).sum(),
            np.isnan(I).sum(), lp.GetValue(0) if lp else None))
    Delete(img)

if len(sys.argv) > 3:
    import vtk
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.util import numpy_support as ns
    shots = []
    for pattern, p in (("Random", 1), ("Lattice", 1), ("Random", 64)):
        img = SchlierenImage(Input=vol, Resolution=[320, 320], Passes=p, Cutoff="KnifeEdge", CutoffScale=250.0,
                             Backend="OpenCL", Seed=4, ViewDirection=list(d), ViewUp=[0.21, 0.906, 0.36],
                             JitterPattern=pattern)
        o = servermanager.Fetch(img)
        nx, ny, _ = o.GetDimensions()
        shots.append(vtk_to_numpy(o.GetPointData().GetArray("intensity")).reshape(ny, nx))
        Delete(img)
    for name, I in zip(("1 pass Random", "1 pass Lattice"), shots):
        print("%s: RMS %.4f against 64 passes Random" % (name, np.sqrt(np.mean((I - shots[2]) ** 2))))
    I = np.hstack([np.clip(s, 0, 1) for s in shots])
    im = vtk.vtkImageData()
    im.SetDimensions(I.shape[1], I.shape[0], 1)
    im.GetPointData().SetScalars(ns.numpy_to_vtk((I.ravel() * 255).astype(np.uint8)))
    w = vtkPNGWriter()
    w.SetFileName(sys.argv[3])
    w.SetInputData(im)
    w.Write()
