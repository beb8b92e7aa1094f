# SPDX-License-Identifier: BSD-3-Clause
"""A failure on one rank only, under MPI: every rank stops, with one agreed message, and no rank hangs.

    mpiexec -n 2 pvbatch --mpi --symmetric test_mpi_errors.py --plugin <Schlieren.so>

--symmetric: every rank runs this script, so each checks what its own filters said.

RefractiveScene LinearGradient (n^2 = 1 + 0.01 (y - c), c = -0.5, 24 points along y, the longest
axis, so the 2 pieces split y near 0) gives n - 1 < 0 exactly where y < c, which lies in rank 0's piece
only. Two steps read it where negative values are an error:
- RefractiveIndex IdealGas with n_minus_1 as the temperature (T <= 0 on rank 0's piece);
- RefractionOctree on n_minus_1 = -2 where y < c (n <= 0 on rank 0's piece);
- NumericalSchlieren on a density that is NaN where y < c (issue 48: it was imaged).
Rank 0 must report its own error; rank 1, whose piece is fine, must report "another rank (0)
failed: " followed by rank 0's error (schlieren::Parallel::Failure); both outputs are empty. With
c = -2 (n - 1 > 0 everywhere) the same RefractiveIndex runs with no error on either rank.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm
from vtkmodules.vtkParallelCore import vtkMultiProcessController

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_mpi_errors")
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
ranks = controller.GetNumberOfProcesses() if controller else 1
T.check(ranks == 2, "rank %d: pvbatch --symmetric runs on 2 ranks (got %d)" % (rank, ranks))


def run(proxy):
    """Updates `proxy` on this rank; returns (number of output points, what VTK said)."""
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
    data = proxy.GetClientSideObject().GetOutputDataObject(0)
    return (data.GetNumberOfPoints() if data else 0), out.text


def errors_of(text, cls):
    """The messages of `cls`'s errors in `text` (the line after "ERROR: In ...", less the object)."""
    lines = text.splitlines()
    return [lines[i + 1].split("): ", 1)[-1] for i, line in enumerate(lines[:-1])
            if line.startswith("ERROR: In") and lines[i + 1].startswith(cls)]


def check_agreed(case, text, points, own_phrase):
    """Rank 0 (the failing piece) says its own error; rank 1 says rank 0's, named as such."""
    cls = {"RefractionOctree": "vtkRefractionOctree",
           "NumericalSchlieren": "vtkNumericalSchlieren"}.get(case, "vtkRefractiveIndex")
    errors = errors_of(text, cls)
    T.check(points == 0, "%s, rank %d: empty output (%d points)" % (case, rank, points))
    if rank == 0:
        T.check(len(errors) == 1 and own_phrase in errors[0] and "another rank" not in errors[0],
                "%s, rank 0: its own error, naming the problem: %s" % (case, "; ".join(e[:140] for e in errors)))
    else:
        prefix = "another rank (0) failed: "
        T.check(len(errors) == 1 and errors[0].startswith(prefix) and own_phrase in errors[0],
                "%s, rank %d: rank 0's error, said to be another rank's: %s" % (case, rank, "; ".join(e[:140] for e in errors)))


def gradient(center_y):
    return RefractiveScene(Scene="LinearGradient", Dimensions=[9, 24, 9], GradientA=1.0,
                           GradientB=0.01, Center=[0, center_y, 0])


scene = gradient(-0.5)
piece = scene.GetClientSideObject()
scene.UpdatePipeline()
extent = piece.GetOutputDataObject(0).GetExtent()
# the pieces share the plane y index 11 (y = -0.04); with RefractiveIndex's one more point on each
# side rank 1 reads from index 10 (y = -0.13), still above c
T.check(extent[2:4] == ((0, 11) if rank == 0 else (11, 23)),
        "rank %d: the scene is split along y near 0 (y extent %s)" % (rank, extent[2:4]))

index = RefractiveIndex(Input=scene, Model="IdealGas")
index.TemperatureArray = ["POINTS", "n_minus_1"]
index.PressureArray = ["POINTS", "density"]
points, text = run(index)
check_agreed("RefractiveIndex", text, points, "at or below absolute zero")

calc = Calculator(Input=scene, ResultArrayName="n_minus_1", Function="-2*(coordsY<-0.5)")
points, text = run(RefractionOctree(Input=calc))
check_agreed("RefractionOctree", text, points, "have n <= 0")

# issue 48: NumericalSchlieren with NaN in rank 0's piece of the density (where y < c): rank 0,
# which images the gathered pieces, refuses it; rank 1 says so as another rank's (it gave NaN
# pixels or a white image)
nan_density = PythonCalculator(Input=scene, ArrayName="rho_nan",
                               Expression="where(n_minus_1 < 0, float('nan'), density)")
points, text = run(NumericalSchlieren(Input=nan_density, DensityArray="rho_nan", Resolution=[16, 16]))
check_agreed("NumericalSchlieren", text, points, "points of the flow are NaN or Inf")

# the control: the same model where no piece fails
fine = RefractiveIndex(Input=gradient(-2.0), Model="IdealGas")
fine.TemperatureArray = ["POINTS", "n_minus_1"]
fine.PressureArray = ["POINTS", "density"]
points, text = run(fine)
T.check(points > 0 and "ERROR" not in text,
        "control, rank %d: no error where no piece fails (%d points)%s" % (rank, points, "" if "ERROR" not in text else ": " + text[:300]))
T.finish()
