# SPDX-License-Identifier: BSD-3-Clause
"""RefractiveIndex resampling an unstructured input under MPI: the reactor
(disk_out_ref.ex2) through IdealGas hydrogen on 2 ranks of pvbatch, then the same pipeline on one
process: the pieces of n - 1 and grad n and the traced image must be the same.

    mpiexec -n 2 pvbatch --mpi test_cfd_mpi.py --plugin <Schlieren.so> --output <dir>/cfd_mpi.npz
    pvpython test_cfd_mpi.py --plugin <Schlieren.so> --compare <dir>/cfd_mpi.npz

Under MPI each rank probes the whole grid against its own piece of the input (here the reader
gives the whole mesh to one rank and nothing to the other) and the arrays the model reads are
summed over the ranks; each rank then keeps its piece of the grid. Skips (exit status 125)
without the shared data.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

import cfd_testing as ct
import schlieren_testing as st

(exo,) = ct.require_data("disk_out_ref.ex2")
st.load_plugin(globals())
T = st.Checker("test_cfd_mpi")
output = st.argument("--output")
compare = st.argument("--compare")
if not output and not compare:
    raise RuntimeError("pass --output FILE.npz (under MPI) or --compare FILE.npz (one process)")
if output and os.path.exists(output):
    os.remove(output)  # a failed run must not leave an older result for the comparison

reader = ExodusIIReader(FileName=exo)
reader.PointVariables = ["Temp", "Pres"]
index = RefractiveIndex(Input=reader, Model="IdealGas", Gas="H2", PressureOffset=101325.0,
                        AutomaticDimension=64)
index.TemperatureArray = ["POINTS", "Temp"]
index.PressureArray = ["POINTS", "Pres"]
image = SchlierenImage(Input=index, ViewDirection=[1, 0, 0], ViewUp=[0, 0, 1], Resolution=[48, 64],
                       Passes=1, Jitter=0, Cutoff="KnifeEdge", CutoffScale=1000.0)

ranks = sm.ActiveConnection.GetNumberOfDataPartitions()
with st.CapturedOutput() as out:
    index.UpdatePipeline()
    pieces = [sm.Fetch(index, r) for r in range(ranks)]
    film = sm.Fetch(image, 0)
T.check("ERROR" not in out.text, "no error%s" % ("" if "ERROR" not in out.text else ": " + out.text.strip()[:500]))
T.check(film.GetNumberOfPoints() == 48 * 64, "rank 0 holds the %d-pixel image" % film.GetNumberOfPoints())
record = {"intensity": vtk_to_numpy(film.GetPointData().GetArray("intensity")).copy(),
          "deflection": vtk_to_numpy(film.GetPointData().GetArray("deflection")).copy()}
dims = None
for r, piece in enumerate(pieces):
    record["extent%d" % r] = np.array(piece.GetExtent())
    for name in ("n_minus_1", "grad_n"):
        record["%s%d" % (name, r)] = vtk_to_numpy(piece.GetPointData().GetArray(name)).copy()

if output:
    T.check(ranks == 2, "pvbatch runs on 2 ranks (got %d)" % ranks)
    whole = [0, 0, 0]
    covered = None
    for r in range(ranks):
        e = record["extent%d" % r]
        whole = [max(whole[a], e[2 * a + 1] + 1) for a in range(3)]
    covered = np.zeros(whole[::-1], dtype=int)
    for r in range(ranks):
        e = record["extent%d" % r]
        covered[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1] += 1
    T.check(covered.min() == 1 and covered.max() <= 2,
            "the %d pieces %s tile the %s grid" % (ranks, [list(record["extent%d" % r]) for r in range(ranks)], whole))
    np.savez(output, ranks=ranks, **record)
    print("wrote %s" % output)
else:
    mpi = np.load(compare)
    e0 = record["extent0"]
    full = {name: record["%s0" % name].reshape(e0[5] + 1, e0[3] + 1, e0[1] + 1, -1) for name in ("n_minus_1", "grad_n")}
    for r in range(int(mpi["ranks"])):
        e = mpi["extent%d" % r]
        for name in ("n_minus_1", "grad_n"):
            mine = full[name][e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1].reshape(-1)
            theirs = mpi["%s%d" % (name, r)].reshape(-1)
            scale = np.abs(mine).max()
            T.close(theirs / scale, mine / scale, 1e-6, "rank %d's piece %s of %s = one process's" % (r, list(e), name))
    T.close(mpi["intensity"], record["intensity"], 1e-6, "the image on 2 ranks = on one process")
    T.close(mpi["deflection"], record["deflection"], 1e-9, "the deflections on 2 ranks = on one process")
T.finish()
