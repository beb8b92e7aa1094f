# SPDX-License-Identifier: BSD-3-Clause
"""The images of test_mpi.py (2 MPI ranks) equal those of one process.

Run after test_mpi.py: pvpython test_mpi_compare.py --plugin <Schlieren.so> --input <dir>/mpi_images.npz

Tolerances: the ranks trace disjoint sets of pixels with the same per-pixel jitter, and their film
sums are added in double; what may differ is the order of additions (a few ulps): 1e-6 in intensity,
1e-6 of the largest deflection. The index pieces must equal the serial volume's sub-blocks to the bit:
RefractiveIndex grows each piece by one point so its central differences see the neighbours.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview import simple
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_mpi_compare")
path = st.argument("--input")
if not path or not os.path.exists(path):
    raise RuntimeError("the 2-rank result %r is missing: run test_mpi.py first" % path)
mpi = np.load(path)

index, knife, shadow = st.mpi_pipeline(globals())

volume = sm.Fetch(index)
n1 = vtk_to_numpy(volume.GetPointData().GetArray("n_minus_1")).reshape(64, 64, 64)
grad = vtk_to_numpy(volume.GetPointData().GetArray("grad_n")).reshape(64, 64, 64, 3)
for r in range(2):
    e = mpi["piece%d_extent" % r]
    shape = (e[5] - e[4] + 1, e[3] - e[2] + 1, e[1] - e[0] + 1)
    block = (slice(e[4], e[5] + 1), slice(e[2], e[3] + 1), slice(e[0], e[1] + 1))
    T.close(mpi["piece%d_n_minus_1" % r].reshape(shape), n1[block], 0.0,
            "piece %d %s: n_minus_1 == serial" % (r, list(e)))
    T.close(mpi["piece%d_grad_n" % r].reshape(shape + (3,)), grad[block], 0.0,
            "piece %d %s: grad_n == serial (borders included)" % (r, list(e)))

for name, proxy in (("knife", knife), ("shadow", shadow)):
    serial = st.image_record(name, sm.Fetch(proxy))
    # servermanager.Fetch under pvbatch moves the image through a text form that keeps 6
    # significant digits of its origin and spacing (the arrays themselves are exact).
    for key in ("_origin", "_spacing"):
        T.close(mpi[name + key], serial[name + key], 1e-5 * np.abs(serial[name + key]).max(),
                "%s: film %s" % (name, key[1:]))
    T.check(mpi[name + "_intensity"].shape == serial[name + "_intensity"].shape,
            "%s: image size %s" % (name, serial[name + "_intensity"].shape))
    T.close(mpi[name + "_photons"], serial[name + "_photons"], 0.0, "%s: photons" % name)
    # traced in pieces with rays handed between ranks, the records splatted in pixel order on rank
    # 0: the same arithmetic as one process, so the same numbers bit for bit
    T.close(mpi[name + "_cutoff_scale"], serial[name + "_cutoff_scale"], 0.0, "%s: cutoff_scale" % name)
    T.close(mpi[name + "_intensity"], serial[name + "_intensity"], 0.0, "%s: intensity, MPI vs 1 process" % name)
    dmax = np.abs(serial[name + "_deflection"]).max()
    T.check(dmax > 0, "%s: the image has deflections (max %.3g rad)" % (name, dmax))
    T.close(mpi[name + "_deflection"], serial[name + "_deflection"], 0.0,
            "%s: deflection, MPI vs 1 process" % name)
    I = serial[name + "_intensity"]
    T.check(I.max() - I.min() > 0.1, "%s: the image has contrast (I in [%.3f, %.3f])" % (name, I.min(), I.max()))

T.finish()
