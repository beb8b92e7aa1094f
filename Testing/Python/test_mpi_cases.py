# SPDX-License-Identifier: BSD-3-Clause
"""Tracing in pieces under MPI gives one process's image, bit for bit, on 1, 2 and 4 ranks of
pvbatch and on pvservers of 2 and 4 ranks with pvpython as their client, for the cases where rays
cross pieces in every way: the Gaussian sphere seen obliquely (also with the step-doubling error
estimate, its error_estimate compared too), a blast wave with Reconstruction Cubic, Auto choosing
between the reconstructions, two solid bodies (RefractiveScene's sphere and a surface), the
octree at its default MaxLevel, the Luneburg lens (rays that bend
across the pieces and back to a focus), a shadowgraph far behind a strong sphere (caustics: the
rays cross), and the NASA blunt fin through its reader's own partition (when the shared data is
there).

    mpiexec -n N pvbatch --mpi test_mpi_cases.py --plugin <Schlieren.so> --output <dir>/cases_N.npz --ranks N
    pvpython test_mpi_cases.py --plugin <Schlieren.so> --output <dir>/cases_pvs.npz --ranks 2 \\
        --pvserver <pvserver> --mpiexec <mpiexec>
    pvpython test_mpi_cases.py --plugin <Schlieren.so> --compare <dir>/cases_1.npz <dir>/cases_2.npz ...

A run with ranks checks that the volume was traced in pieces (no rank held the whole volume, rays
were handed between ranks) and writes its images; the comparison traces the same pipelines in one
process and requires every pixel of intensity and deflection, and the photon counts, to be equal.
Backend CPU on both sides (pieces are traced on the CPU backend).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview import simple  # noqa: F401
from paraview import servermanager as sm

import cfd_testing as ct
import schlieren_testing as st

server = st.start_pvserver(globals()) if st.argument("--pvserver") else None
st.load_plugin(globals())
T = st.Checker("test_mpi_cases")


def cases():
    """name -> SchlierenImage proxy, the same pipelines on every run."""
    out = {}
    gauss = RefractiveScene(Scene="GaussianSphere", Dimensions=[48, 48, 48], Bounds=[-1, 1, -1, 1, -1, 1],  # noqa: F821
                            Amplitude=1e-4, Width=0.3, Center=[0.1, -0.05, 0.02])
    out["oblique"] = SchlierenImage(Input=gauss, ViewDirection=[0.5, -0.4, -0.75], ViewUp=[0, 1, 0],  # noqa: F821
                                    Resolution=[48, 40], Passes=2, Integrator="RK4", StepSize=1.0,
                                    Cutoff="KnifeEdge", KnifeAngle=20.0, Backend="CPU")
    # the step-doubling estimate: a second trace at twice the step on the pieces
    out["estimate"] = SchlierenImage(Input=gauss, ViewDirection=[-0.4, 0.5, -0.8], ViewUp=[0, 1, 0],  # noqa: F821
                                     Resolution=[40, 40], Passes=2, Integrator="Midpoint", StepSize=1.0,
                                     EstimateError=1, Cutoff="KnifeEdge", Backend="CPU")
    lens = RefractiveScene(Scene="LuneburgLens", Dimensions=[48, 48, 48], Bounds=[-1, 1, -1, 1, -1, 1],  # noqa: F821
                           Radius=0.8)
    out["lens"] = SchlierenImage(Input=lens, ViewDirection=[0.3, 0.2, -1.0], Resolution=[40, 40], Passes=1,  # noqa: F821
                                 Integrator="Midpoint", StepSize=0.5, Cutoff="Shadowgraph", Backend="CPU")
    strong = RefractiveScene(Scene="GaussianSphere", Dimensions=[48, 48, 48], Bounds=[-1, 1, -1, 1, -1, 1],  # noqa: F821
                             Amplitude=2e-3, Width=0.3, Center=[0.1, 0.0, 0.0])
    out["caustics"] = SchlierenImage(Input=strong, Resolution=[40, 40], Passes=2, Cutoff="Shadowgraph",  # noqa: F821
                                     FilmDistance=40.0, Backend="CPU")
    # Reconstruction Cubic (tricubic where smooth, trilinear beside the shock, steps sized by the
    # smoothness) and Auto's choice between the reconstructions, in pieces
    blast = RefractiveScene(Scene="BlastWave", Dimensions=[48, 48, 48], Bounds=[-1, 1, -1, 1, -1, 1],  # noqa: F821
                            Radius=0.6, Width=0.04)
    out["cubic"] = SchlierenImage(Input=blast, ViewDirection=[0.5, 0.4, -0.8], ViewUp=[0, 1, 0],  # noqa: F821
                                  Resolution=[40, 40], Passes=1, Integrator="RK4", StepSize=2.0,
                                  Reconstruction="Cubic", Cutoff="KnifeEdge", Backend="CPU")
    out["auto_cubic"] = SchlierenImage(Input=gauss, ViewDirection=[0.3, -0.2, -1.0], ViewUp=[0, 1, 0],  # noqa: F821
                                       Resolution=[40, 40], Passes=1, Integrator="Auto",
                                       Reconstruction="Auto", Cutoff="KnifeEdge", Backend="CPU")
    # solid bodies in pieces: RefractiveScene's sphere and a closed surface voxelised by
    # RefractiveIndex on every rank's piece; and the octree at RefractionOctree's defaults
    # (MaxLevel 7: the pieces hold the levels the volume reaches, with ghosts as deep as a block)
    bodies = RefractiveScene(Scene="GaussianSphere", Dimensions=[48, 48, 48], Bounds=[-1, 1, -1, 1, -1, 1],  # noqa: F821
                             Amplitude=1e-4, Width=0.3, Body="Sphere", BodyRadius=0.25, BodyCenter=[0.45, 0.1, 0.0])
    walled = RefractiveIndex(Input=bodies, Model="Passthrough",  # noqa: F821
                             Body=Sphere(Radius=0.2, Center=[-0.5, -0.3, 0.1], ThetaResolution=24, PhiResolution=24))  # noqa: F821
    walled.InputArray = ["POINTS", "n_minus_1"]
    out["bodies"] = SchlierenImage(Input=walled, ViewDirection=[0.3, -0.2, -1.0], ViewUp=[0, 1, 0],  # noqa: F821
                                   Resolution=[40, 40], Passes=1, Integrator="RK4", StepSize=1.0,
                                   Cutoff="KnifeEdge", CutoffScale=1000.0, Backend="CPU")
    octree = RefractionOctree(Input=gauss)  # noqa: F821
    out["octree"] = SchlierenImage(Input=octree, ViewDirection=[-0.3, 0.2, -1.0], ViewUp=[0, 1, 0],  # noqa: F821
                                   Resolution=[40, 40], Passes=1, Integrator="RK4", StepSize=0.5,
                                   Cutoff="KnifeEdge", Backend="CPU")
    data = ct.data_dir()
    xyz, q = os.path.join(data, "bluntfinxyz.bin"), os.path.join(data, "bluntfinq.bin")
    if os.path.exists(xyz) and os.path.exists(q):
        reader = PLOT3DReader(FileName=xyz, QFileName=[q])  # noqa: F821
        index = RefractiveIndex(Input=reader, Model="GladstoneDale", Gas="Air", DensityReference=1.2,  # noqa: F821
                                UseSamplingBounds=1, SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7],
                                AutomaticDimension=48, AmbientMode="Extend")
        index.InputArray = ["POINTS", "Density"]
        out["bluntfin"] = SchlierenImage(Input=index, ViewDirection=[0.4, 0.3, -1], ViewUp=[0, 1, 0],  # noqa: F821
                                         Resolution=[64, 32], Passes=1, Cutoff="KnifeEdge", Backend="CPU")
    else:
        print("NOTE: the blunt fin is not traced: the shared data is not in %s" % data)
    return out


def estimate(image):
    """The error_estimate array of an image, empty where it has none."""
    a = image.GetPointData().GetArray("error_estimate")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    return vtk_to_numpy(a).copy() if a is not None else np.array([])


def number(fd, key):
    a = fd.GetArray(key)
    return a.GetValue(0) if a is not None else float("nan")


images = cases()
output = st.argument("--output")
if output:
    if os.path.exists(output):
        os.remove(output)  # a failed run must not leave an older result behind
    expected = int(st.argument("--ranks", "1"))
    ranks = sm.ActiveConnection.GetNumberOfDataPartitions()
    T.check(ranks == expected, "%d ranks (got %d)" % (expected, ranks))
    record = {"ranks": np.array(ranks)}
    for name, proxy in images.items():
        with st.CapturedOutput() as out:
            image = sm.Fetch(proxy, 0)
        T.check("ERROR" not in out.text, "%s: no error%s" % (name, "" if "ERROR" not in out.text else ": " + out.text[:400]))
        X, Y, I, D, F = st.image_arrays(image)
        fd = image.GetFieldData()
        record[name + "_intensity"] = I
        record[name + "_deflection"] = D
        record[name + "_photons"] = np.array(F.get("photons", np.nan))
        record[name + "_error"] = estimate(image)
        if ranks > 1:
            info = proxy.Input.GetDataInformation()
            e = info.GetExtent()
            points = (e[1] - e[0] + 1) * (e[3] - e[2] + 1) * (e[5] - e[4] + 1)
            held = number(fd, "held_points_max")
            # Auto with tricubic candidates steps up to 64 voxels: its ghosts (133 layers) cover
            # this small grid, so a rank may hold all of it (traced in pieces all the same)
            most = points + 1 if name == "auto_cubic" else points
            T.check(number(fd, "distributed_ranks") == ranks and 0 < held < most,
                    "%s: traced in pieces on %d ranks; the most a rank held: %d of %d points (%d ghost layers)"
                    % (name, number(fd, "distributed_ranks"), held, points, number(fd, "ghost_layers")))
            T.check(number(fd, "rays_handed_on") > 0,
                    "%s: %d rays handed between ranks, %d bytes" % (name, number(fd, "rays_handed_on"),
                                                                   number(fd, "ray_traffic_bytes")))
    np.savez(output, **record)
    print("wrote %s" % output)
    st.stop_pvserver(server)
else:
    inputs = []
    if "--compare" in sys.argv:
        inputs = sys.argv[sys.argv.index("--compare") + 1:]
    inputs = [p for p in inputs if not p.startswith("--")]
    T.check(len(inputs) > 0, "runs to compare with: %s" % inputs)
    serial = {}
    for name, proxy in images.items():
        image = sm.Fetch(proxy)
        X, Y, I, D, F = st.image_arrays(image)
        serial[name] = (I, D, F.get("photons", np.nan), estimate(image))
        if name == "bodies":
            stopped = number(image.GetFieldData(), "blocked_rays")
            T.check(stopped > 50, "bodies: the two bodies stop %d rays" % stopped)
        if name == "octree":
            fd = image.GetFieldData()
            T.check(number(fd, "octree") == 1, "octree: traced over the octree")
    # the caustics case has caustics: photons pile up where the rays cross
    I = serial["caustics"][0]
    T.check(I.max() > 4 * I.mean(), "caustics: the brightest pixel is %.1f x the mean" % (I.max() / I.mean()))
    # the lens focuses: the shadowgraph is far from uniform
    I = serial["lens"][0]
    T.check(I.max() > 3 * np.median(I), "lens: focused light, brightest %.1f x the median" % (I.max() / np.median(I)))
    E = serial["estimate"][3]
    T.check(E.size > 0 and E.max() > 0, "estimate: one process's error_estimate is there and not zero (largest %.3g rad)"
            % (E.max() if E.size else float("nan")))
    for path in inputs:
        if not os.path.exists(path):
            T.check(False, "%s is missing: run the MPI case first" % path)
            continue
        mpi = np.load(path)
        ranks = int(mpi["ranks"])
        for name, (I, D, photons, E) in serial.items():
            if name + "_intensity" not in mpi:
                T.check(False, "%s: not in %s" % (name, path))
                continue
            T.close(mpi[name + "_intensity"], I, 0.0, "%s: intensity on %d ranks = one process" % (name, ranks))
            T.close(mpi[name + "_deflection"], D, 0.0, "%s: deflection on %d ranks = one process" % (name, ranks))
            T.close(mpi[name + "_photons"], photons, 0.0, "%s: photons on %d ranks" % (name, ranks))
            if E.size:
                T.close(mpi[name + "_error"], E, 0.0, "%s: error_estimate on %d ranks = one process" % (name, ranks))
T.finish()
