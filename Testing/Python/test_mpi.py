# SPDX-License-Identifier: BSD-3-Clause
"""SchlierenImage under MPI: 2 (or --ranks N) ranks of pvbatch, or of a pvserver (--pvserver). Writes the images (and the RefractiveIndex pieces)
to --output, for test_mpi_compare.py to compare with a one-process run of the same pipeline.

Run: mpiexec -n 2 pvbatch --mpi test_mpi.py --plugin <Schlieren.so> --output <dir>/mpi_images.npz

Checked here: there really are 2 ranks, RefractiveScene/RefractiveIndex really are split into two
pieces that tile the volume, rank 0 holds the whole image and rank 1 an empty one.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview import simple
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

import schlieren_testing as st

# --pvserver PATH --mpiexec PATH: the same checks in client-server mode, against a pvserver of
# --ranks ranks that this script starts on a free loopback port and stops at the end
server = st.start_pvserver(globals()) if st.argument("--pvserver") else None
st.load_plugin(globals())
T = st.Checker("test_mpi")
output = st.argument("--output")
if not output:
    raise RuntimeError("pass --output FILE.npz")
if os.path.exists(output):
    os.remove(output)  # a failed run must not leave an older result for test_mpi_compare.py

expected = int(st.argument("--ranks", "2"))
ranks = sm.ActiveConnection.GetNumberOfDataPartitions()
T.check(ranks == expected, "pvbatch runs on %d ranks (got %d)" % (expected, ranks))

index, knife, shadow = st.mpi_pipeline(globals())
record = {}

# The index is computed piecewise: each rank holds one piece (point extents of neighbouring
# pieces share their boundary plane); together they cover 64^3.
covered = np.zeros((64, 64, 64), dtype=int)
extents = []
for r in range(ranks):
    piece = sm.Fetch(index, r)
    e = piece.GetExtent()
    extents.append(e)
    covered[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1] += 1
    pd = piece.GetPointData()
    record["piece%d_extent" % r] = np.array(piece.GetExtent())
    record["piece%d_n_minus_1" % r] = vtk_to_numpy(pd.GetArray("n_minus_1")).copy()
    record["piece%d_grad_n" % r] = vtk_to_numpy(pd.GetArray("grad_n")).copy()
T.check(covered.min() == 1 and covered.max() <= 2 * ranks and covered.sum() < 2 * 64 ** 3,
        "RefractiveIndex pieces %s cover the 64^3 volume, each point once or twice" % (extents,))

for name, proxy in (("knife", knife), ("shadow", shadow)):
    with st.CapturedOutput() as out:
        image = sm.Fetch(proxy, 0)
        others = [sm.Fetch(proxy, r).GetNumberOfPoints() for r in range(1, ranks)]
    T.check("ERROR" not in out.text, "%s: no error reported%s" % (name, "" if "ERROR" not in out.text else ": " + out.text[:500]))
    T.check(image.GetNumberOfPoints() > 0 and all(n == 0 for n in others),
            "%s: rank 0 holds the image (%d pixels), the other ranks empty ones (%s)"
            % (name, image.GetNumberOfPoints(), others))
    record.update(st.image_record(name, image))
    # traced in pieces: no rank held more than its piece's owned cells and 4 ghost layers (the
    # ghosts of 0.5-voxel steps), clipped to the volume
    fd = image.GetFieldData()
    number = lambda key: fd.GetArray(key).GetValue(0) if fd.GetArray(key) else -1
    held = max(np.prod([min(63, e[2 * a + 1] + 4) - max(0, e[2 * a] - 4) + 1 for a in range(3)])
               for e in extents)
    T.check(number("distributed_ranks") == ranks and number("ghost_layers") == 4
            and number("held_points_max") == held and held < 64 ** 3,
            "%s: traced in pieces on %d ranks, the most a rank held %d points (expected %d of %d)"
            % (name, number("distributed_ranks"), number("held_points_max"), held, 64 ** 3))
    T.check(number("rays_handed_on") > 0 and number("ray_traffic_bytes") > 0,
            "%s: rays were handed between ranks (%d rays, %d bytes)"
            % (name, number("rays_handed_on"), number("ray_traffic_bytes")))

# TraceInPieces off: every rank gathers the whole volume; the same image (Backend CPU: the same
# arithmetic either way)
knife.TraceInPieces = 0
with st.CapturedOutput() as out:
    gathered = sm.Fetch(knife, 0)
whole = st.image_record("knife", gathered)
fd = gathered.GetFieldData()
T.check(fd.GetArray("distributed_ranks").GetValue(0) == 0,
        "TraceInPieces off: the whole volume on every rank (distributed_ranks 0)")
T.close(whole["knife_intensity"], record["knife_intensity"], 0.0,
        "TraceInPieces off: the image of the pieces, bit for bit")
knife.TraceInPieces = 1

# A sanity check that the traced image is the sphere's: max |deflection| near sqrt(2 pi) A e^-1/2
# (coarse here: 64^3 and an oblique view; the pixel-exact comparison is test_mpi_compare.py).
dmax = np.abs(record["knife_deflection"]).max() / st.gaussian_max_deflection(1e-4)
T.check(0.8 < dmax < 1.1, "knife: max |deflection| / max|eps| = %.3f" % dmax)

np.savez(output, **record)
print("wrote %s" % output)
st.stop_pvserver(server)
T.finish()
