# SPDX-License-Identifier: BSD-3-Clause
"""Solid bodies under MPI: the same image and the same stopped rays on 2 ranks as on one process.

    mpiexec -n 2 pvbatch --mpi test_solids_mpi.py --plugin <Schlieren.so> --output <dir>/solids_mpi.npz
    pvpython test_solids_mpi.py --plugin <Schlieren.so> --compare <dir>/solids_mpi.npz

Three bodies, each split over the ranks' pieces: RefractiveScene's sphere beside the Gaussian
sphere (its `solid` array kept by RefractiveIndex and gathered by SchlierenImage like n - 1), a
closed sphere surface on RefractiveIndex's Body input (every rank voxelises its own piece against
the whole surface), and a hole in the grid that the flow encloses (BodyFromGrid: the outside is
flooded across the pieces), beside a hole on a face that is not a body. Knife edge, Auto: the intensity, the `blocked` fraction and `blocked_rays`
must equal one process's exactly (the photons are put on the film in ray order on rank 0). The
2 ranks trace in pieces: each holds its piece's solid points and their ghosts.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_solids_mpi")
output_file = st.argument("--output")
compare = st.argument("--compare")
if not output_file and not compare:
    raise RuntimeError("pass --output FILE.npz (under MPI) or --compare FILE.npz (one process)")
if output_file and os.path.exists(output_file):
    os.remove(output_file)  # a failed run must not leave an older result for the comparison

scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[49, 49, 49], Body="Sphere", BodyRadius=0.25,
                        BodyCenter=[0.45, 0.1, 0.0])
# holes in the grid (vtkValidPointMask 0), made on each rank's piece: a ball that the flow encloses,
# across the middle of the volume where the pieces meet (a body, BodyFromGrid), and a slab on the
# z min face (outside the flow domain, not a body)
# (the script runs in this interpreter under pvpython and pvbatch: its names end in _ so that
# they do not replace this test's)
HOLES = """
import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
o_ = self.GetOutputDataObject(0)
o_.ShallowCopy(self.GetInputDataObject(0, 0))
e_, O_, S_ = o_.GetExtent(), o_.GetOrigin(), o_.GetSpacing()
z_, y_, x_ = np.meshgrid(*[O_[a_] + S_[a_] * np.arange(e_[2 * a_], e_[2 * a_ + 1] + 1) for a_ in (2, 1, 0)],
                         indexing="ij")
x_, y_, z_ = x_.ravel(), y_.ravel(), z_.ravel()
ball_ = (x_ ** 2 + (y_ + 0.55) ** 2 + z_ ** 2) <= 0.18 ** 2
slab_ = (z_ <= -0.85) & (abs(x_) <= 0.2) & (abs(y_ - 0.5) <= 0.2)
dsa.WrapDataObject(o_).PointData.append((~(ball_ | slab_)).astype(np.uint8), "vtkValidPointMask")
"""
holes = ProgrammableFilter(Input=scene, Script=HOLES)
# (the holes filled with the median at the flow domain's edge: Extend, the default, cannot extend
# across an image's pieces and is taken as DomainEdgeMedian under MPI)
refr = RefractiveIndex(Input=holes, Model="Passthrough", AmbientMode="DomainEdgeMedian",
                       Body=Sphere(Radius=0.2, Center=[-0.5, -0.3, 0.1], ThetaResolution=32, PhiResolution=32))
refr.InputArray = ["POINTS", "n_minus_1"]
image = SchlierenImage(Input=refr, Resolution=[48, 48], Passes=2, Integrator="Auto", Cutoff="KnifeEdge",
                       CutoffScale=1000.0, Backend="CPU")
ranks = sm.ActiveConnection.GetNumberOfDataPartitions()
with st.CapturedOutput() as out:
    image.UpdatePipeline()
    film = sm.Fetch(image, 0)
T.check("ERROR" not in out.text, "no error%s" % ("" if "ERROR" not in out.text else ": " + out.text.strip()[:500]))
fd = film.GetFieldData()
record = {"intensity": vtk_to_numpy(film.GetPointData().GetArray("intensity")).copy(),
          "blocked": vtk_to_numpy(film.GetPointData().GetArray("blocked")).copy(),
          "blocked_rays": np.array(fd.GetArray("blocked_rays").GetValue(0))}
print("%d rank(s): %.0f rays stopped, blocked pixels %d" % (ranks, record["blocked_rays"], (record["blocked"] > 0.5).sum()))
T.check(record["blocked_rays"] > 100 and (record["blocked"] == 1).sum() > 20,
        "the bodies stop rays (%.0f)" % record["blocked_rays"])
if output_file:
    T.check(ranks == 2, "pvbatch runs on 2 ranks (got %d)" % ranks)
    # in pieces: no rank held the whole volume, rays were handed between the ranks
    held = fd.GetArray("held_points_max")
    handed = fd.GetArray("rays_handed_on")
    T.check(held is not None and 0 < held.GetValue(0) < 49 ** 3 and handed is not None and handed.GetValue(0) > 0,
            "traced in pieces with the bodies: the most a rank held %s of %d points, %s rays handed on"
            % (held.GetValue(0) if held else None, 49 ** 3, handed.GetValue(0) if handed else None))
    np.savez(output_file, **record)
    print("wrote %s" % output_file)
else:
    # one process: the enclosed ball is a body, the slab on the face is not
    grid = sm.Fetch(refr)
    solid = vtk_to_numpy(grid.GetPointData().GetArray("solid"))
    pts = np.array([grid.GetPoint(i) for i in range(grid.GetNumberOfPoints())])  # 49^3: a second
    ball = (pts[:, 0] ** 2 + (pts[:, 1] + 0.55) ** 2 + pts[:, 2] ** 2) <= 0.18 ** 2
    slab = (pts[:, 2] <= -0.85) & (abs(pts[:, 0]) <= 0.2) & (abs(pts[:, 1] - 0.5) <= 0.2)
    T.check(ball.sum() > 50 and solid[ball].all() and not solid[slab].any(),
            "BodyFromGrid: the enclosed ball is solid (%d points), the slab on the z min face is not (%d)"
            % (ball.sum(), slab.sum()))
    mpi = np.load(compare)
    T.check(float(mpi["blocked_rays"]) == float(record["blocked_rays"]),
            "the same rays stopped on 2 ranks as on one process (%.0f)" % record["blocked_rays"])
    T.check(np.array_equal(mpi["blocked"], record["blocked"]), "the same blocked fraction in every pixel")
    T.close(mpi["intensity"], record["intensity"], 0.0, "the image on 2 ranks = on one process, bit for bit")
T.finish()
