# SPDX-License-Identifier: BSD-3-Clause
"""Issue 48's own case, which the pipeline cannot see, with SCHLIEREN_MPI_ABORT=1: the run ends.

    mpiexec -n 3 pvbatch --mpi --symmetric test_mpi_abort.py --plugin <Schlieren.so>

A PythonCalculator whose expression takes a global reduction (max() is an MPI all-reduce under
pvbatch) and raises on rank 1 only, in front of RefractiveIndex and SchlierenImage. Ranks 0 and 2
wait in that all-reduce, inside ParaView's calculator, and never reach our filters; rank 1's
calculator returns success (it prints the traceback), so rank 1 reaches RefractiveIndex and waits
there for rank 0. Without SCHLIEREN_MPI_ABORT the guard's error comes after SCHLIEREN_MPI_TIMEOUT
and the job then stays in MPI, spinning, for ever (rank 1 in pvbatch's final barrier, the others
in the all-reduce). With it, rank 1 says the guard's error and aborts the job: the test passes on
that line in the output (ctest's PASS_REGULAR_EXPRESSION: the job's exit code is MPI_Abort's); its
TIMEOUT catches the hang, and the line printed after the update must not come.
"""
import os
import sys

os.environ["SCHLIEREN_MPI_TIMEOUT"] = "2"
os.environ["SCHLIEREN_MPI_ABORT"] = "1"

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkParallelCore import vtkMultiProcessController

import schlieren_testing as st

st.load_plugin(globals())
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[16, 24, 16])
calc = PythonCalculator(Input=scene, ArrayName="density",
                        Expression=("no_such_name" if rank == 1 else "density") + "/max(density)")
image = SchlierenImage(Input=RefractiveIndex(Input=calc), Resolution=[16, 16], Backend="CPU")
image.UpdatePipeline()
print("rank %d: the run went on after the update (SCHLIEREN_MPI_ABORT did not end it)" % rank)
