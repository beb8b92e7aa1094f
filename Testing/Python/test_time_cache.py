# SPDX-License-Identifier: BSD-3-Clause
"""A time series played twice: every frame re-traced when the time changes, and the second play
neither resampled (RefractiveIndex's per-time-step cache) nor packed again (SchlierenImage's
earlier volumes), with the same images bit for bit as fresh pipelines.

Run: pvpython test_time_cache.py --plugin <Schlieren.so>

The series: RefractiveScene BlastWave (4 time steps, the shock radius growing with t) made an
unstructured grid (AppendDatasets), so that RefractiveIndex resamples it onto its grid.
Checked:
- first play: each frame computed (field data index_computed = 1, 2, 3, 4; volume_from
  "packed") and each frame's deflection differs from the one before (the time was followed);
- second play: index_computed stays 4 and index_from_cache = 1 (no resampling), volume_from
  "cache" and volumes_packed stays 4 (no packing), the deflection and intensity equal the first
  play's and those of a fresh RefractiveIndex and SchlierenImage at that time, bit for bit;
- a property changed upstream (the scene's Radius) drops what was kept: the frame is computed and
  packed again and differs from before.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_time_cache")

scene = RefractiveScene(Scene="BlastWave", Dimensions=[32] * 3, Bounds=[-1, 1] * 3, Radius=0.7,
                        Width=0.05, Time=1.0, TimeSteps=4)
grid = AppendDatasets(Input=scene)
INDEX = dict(SamplingDimensions=[40] * 3)
IMAGE = dict(Resolution=[64, 64], Passes=1, Cutoff="Shadowgraph", FilmDistance=1.0)
index = RefractiveIndex(Input=grid, **INDEX)
image = SchlierenImage(Input=index, **IMAGE)
scene.UpdatePipelineInformation()
times = list(scene.TimestepValues)
T.check(len(times) == 4, "the scene has 4 time steps (%s)" % times)


def fields(proxy):
    fd = proxy.GetClientSideObject().GetOutputDataObject(0).GetFieldData()
    return {fd.GetAbstractArray(i).GetName(): fd.GetAbstractArray(i).GetVariantValue(0).ToString()
            for i in range(fd.GetNumberOfArrays())}


def frame(img, t):
    img.UpdatePipeline(t)
    out = img.GetClientSideObject().GetOutputDataObject(0)
    return (vtk_to_numpy(out.GetPointData().GetArray("deflection")).copy(),
            vtk_to_numpy(out.GetPointData().GetArray("intensity")).copy())


def play():
    frames, notes = [], []
    for t in times:
        with st.CapturedOutput():
            frames.append(frame(image, t))
        notes.append((fields(index), fields(image)))
    return frames, notes


first, first_notes = play()
for k, (fi, fs) in enumerate(first_notes):
    T.check(fi.get("index_computed") == str(k + 1) and fi.get("index_from_cache") == "0",
            "first play, t = %g: resampled (index_computed %s)" % (times[k], fi.get("index_computed")))
    T.check(fs.get("volume_from") == "packed", "first play, t = %g: packed (%s)"
            % (times[k], fs.get("volume_from")))
for k in range(1, len(times)):
    T.check(not np.array_equal(first[k][0], first[k - 1][0]),
            "t = %g re-traced: its deflection differs from t = %g's" % (times[k], times[k - 1]))
print("cache budget %s bytes, held %s bytes after the first play"
      % (first_notes[-1][0].get("index_cache_budget"), first_notes[-1][0].get("index_cache_bytes")))

second, second_notes = play()
for k, (fi, fs) in enumerate(second_notes):
    T.check(fi.get("index_computed") == "4" and fi.get("index_from_cache") == "1",
            "second play, t = %g: not resampled (index_computed %s, from cache %s)"
            % (times[k], fi.get("index_computed"), fi.get("index_from_cache")))
    T.check(fs.get("volume_from") == "cache" and fs.get("volumes_packed") == "4",
            "second play, t = %g: not packed (volume_from %s, volumes_packed %s)"
            % (times[k], fs.get("volume_from"), fs.get("volumes_packed")))
    T.check(np.array_equal(second[k][0], first[k][0]) and np.array_equal(second[k][1], first[k][1]),
            "second play, t = %g: the first play's image bit for bit" % times[k])
    fresh_index = RefractiveIndex(Input=grid, **INDEX)
    fresh_image = SchlierenImage(Input=fresh_index, **IMAGE)
    with st.CapturedOutput():
        fresh = frame(fresh_image, times[k])
    Delete(fresh_image)
    Delete(fresh_index)
    T.check(np.array_equal(second[k][0], fresh[0]) and np.array_equal(second[k][1], fresh[1]),
            "second play, t = %g: a fresh pipeline's image bit for bit" % times[k])

# a property upstream changes: nothing kept applies
scene.Radius = 0.5
with st.CapturedOutput():
    changed = frame(image, times[1])
fi, fs = fields(index), fields(image)
T.check(fi.get("index_computed") == "5" and fi.get("index_from_cache") == "0",
        "after Radius changed: resampled again (index_computed %s)" % fi.get("index_computed"))
T.check(fs.get("volume_from") == "packed" and fs.get("volumes_packed") == "5",
        "after Radius changed: packed again (%s, %s)" % (fs.get("volume_from"), fs.get("volumes_packed")))
T.check(not np.array_equal(changed[0], first[1][0]), "after Radius changed: another image")

T.finish()
