# SPDX-License-Identifier: BSD-3-Clause
"""Helpers shared by the Python tests of the Schlieren plugin.

Each test script is run by pvpython, pvbatch or the paraview GUI with the built plugin's path in
the argument ``--plugin PATH`` (or the environment variable SCHLIEREN_PLUGIN). The known answers are
those of ../../../shared/ORACLES.md.
"""
import math
import os
import sys

import numpy as np

# Knife-edge scale used by the tests: k * max|eps| = 1000 * 1.52e-4 = 0.15 keeps every photon's
# weight 0.5 - k e.a inside [0, 1], so the clamp never acts and I = 0.5 - k eps.a exactly.
KNIFE_SCALE = 1000.0


def moving_mesh(path, shift, stretch=1.0):
    """A time step of a mesh that moves (a .vtu at `path`): an unstructured mesh of 13^3 points over
    [-1, 1]^3 moved by `shift` along x and stretched by `stretch` along x, carrying a Gaussian
    density that moves with it (RefractiveIndex's grid follows it: FollowBounds)."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkFiltersCore import vtkAppendFilter
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
    im = vtkImageData()
    im.SetDimensions(13, 13, 13)
    im.SetOrigin(-stretch + shift, -1.0, -1.0)
    im.SetSpacing(stretch / 6, 1 / 6, 1 / 6)
    x = [im.GetOrigin()[a] + np.arange(13) / 6 * (stretch if a == 0 else 1.0) for a in range(3)]
    Z, Y, X = np.meshgrid(x[2], x[1], x[0], indexing="ij")
    rho = numpy_to_vtk((1.2 + 0.4 * np.exp(-((X - shift) ** 2 + Y ** 2 + Z ** 2) / 0.1)).ravel(),
                       deep=1)
    rho.SetName("density")
    im.GetPointData().AddArray(rho)
    ap = vtkAppendFilter()
    ap.AddInputData(im)
    ap.Update()
    w = vtkXMLUnstructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(ap.GetOutput())
    w.Write()


def argument(name, default=None):
    """The value after `name` on the command line (``--name value`` or ``--name=value``)."""
    for i, a in enumerate(sys.argv):
        if a == name and i + 1 < len(sys.argv):
            return sys.argv[i + 1]
        if a.startswith(name + "="):
            return a[len(name) + 1:]
    return default


def plugin_path():
    path = argument("--plugin", os.environ.get("SCHLIEREN_PLUGIN"))
    if not path or not os.path.exists(path):
        raise RuntimeError("the Schlieren plugin was not found: pass --plugin PATH (got %r)" % path)
    return path


def load_plugin(ns):
    """Loads the plugin (client and server side) into the namespace `ns` (pass globals())."""
    from paraview import simple

    simple.LoadPlugin(plugin_path(), remote=False, ns=ns)


class CapturedOutput:
    """Collects what VTK writes to its output window (errors, warnings) while active.

    In pvpython, print() goes through the output window too: print only after leaving the block.
    """

    def __enter__(self):
        from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

        self._previous = vtkOutputWindow.GetInstance()
        self._window = vtkStringOutputWindow()
        vtkOutputWindow.SetInstance(self._window)
        self.text = ""
        return self

    def __exit__(self, *args):
        from vtkmodules.vtkCommonCore import vtkOutputWindow

        self.text = self._window.GetOutput()
        vtkOutputWindow.SetInstance(self._previous)
        return False


class CapturedStderr:
    """What the process writes to its standard error (file descriptor 2: VTK's output window, the
    C++ filters' vtkErrorMacro through vtkLogger, Python's tracebacks) while the block runs, in
    `text`; written on to the test's log after it."""

    def __enter__(self):
        import tempfile
        sys.stderr.flush()
        self._file = tempfile.TemporaryFile(mode="w+b")
        self._saved = os.dup(2)
        os.dup2(self._file.fileno(), 2)
        return self

    def __exit__(self, *exc):
        sys.stderr.flush()
        os.dup2(self._saved, 2)
        os.close(self._saved)
        self._file.seek(0)
        self.text = self._file.read().decode("utf-8", "replace")
        self._file.close()
        sys.stderr.write(self.text)  # still in the test's log
        return False


class Checker:
    """Counts failed checks and reports them; `finish()` raises if any failed."""

    def __init__(self, name):
        self.name = name
        self.failures = []
        self.count = 0

    def check(self, condition, message):
        self.count += 1
        status = "ok  " if condition else "FAIL"
        print("%s %s" % (status, message))
        sys.stdout.flush()
        if not condition:
            self.failures.append(message)
        return bool(condition)

    def close(self, value, expected, tolerance, message):
        """|value - expected| <= tolerance (scalars or arrays: the largest difference)."""
        diff = float(np.max(np.abs(np.asarray(value, dtype=float) - np.asarray(expected, dtype=float))))
        return self.check(diff <= tolerance, "%s: max |difference| = %.3g (tolerance %.3g)" % (message, diff, tolerance))

    def finish(self):
        print("%s: %d checks, %d failed" % (self.name, self.count, len(self.failures)))
        sys.stdout.flush()
        if self.failures:
            raise AssertionError("%s failed: %s" % (self.name, "; ".join(self.failures)))


def image_arrays(data):
    """Numpy views of a SchlierenImage output: X, Y (pixel-centre film coordinates, world units),
    intensity (ny, nx), deflection (ny, nx, 2) and the field data as a dict."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    nx, ny, nz = data.GetDimensions()
    ox, oy, _ = data.GetOrigin()
    hx, hy, _ = data.GetSpacing()
    X, Y = np.meshgrid(ox + hx * np.arange(nx), oy + hy * np.arange(ny))
    pd = data.GetPointData()
    intensity = vtk_to_numpy(pd.GetArray("intensity")).reshape(ny, nx).astype(float)
    deflection = vtk_to_numpy(pd.GetArray("deflection")).reshape(ny, nx, 2).astype(float)
    fields = {}
    fd = data.GetFieldData()
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        fields[a.GetName()] = a.GetValue(0)
    return X, Y, intensity, deflection, fields


def gaussian_deflection(X, Y, amplitude, width):
    """Closed-form deflection of the weak Gaussian sphere n = 1 + A exp(-r^2/s^2), beam along -z
    (film x = world x, film y = world y): eps = -(2 sqrt(pi) A / s) (x, y) exp(-rho^2 / s^2)."""
    f = -(2.0 * math.sqrt(math.pi) * amplitude / width) * np.exp(-(X ** 2 + Y ** 2) / width ** 2)
    return np.stack([f * X, f * Y], axis=-1)


def gaussian_max_deflection(amplitude):
    """Largest |eps| of the weak Gaussian sphere: sqrt(2 pi) A exp(-1/2) (at rho = s / sqrt 2)."""
    return math.sqrt(2.0 * math.pi) * amplitude * math.exp(-0.5)


def start_pvserver(ns):
    """Starts `--mpiexec -n --ranks pvserver` (the --pvserver program) on a free local port,
    connects paraview.simple to it and loads the plugin on the server. Returns the server process
    (see stop_pvserver); its output goes to --output + ".pvserver.log"."""
    import socket
    import subprocess
    import time
    from paraview import simple

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    log_path = argument("--output") + ".pvserver.log"
    log = open(log_path, "w")
    server = subprocess.Popen([argument("--mpiexec"), "-n", argument("--ranks", "2"),
                               "--allow-run-as-root", "--oversubscribe", argument("--pvserver"),
                               "--server-port=%d" % port],
                              stdout=log, stderr=subprocess.STDOUT,
                              env={k: v for k, v in os.environ.items()
                                   if not k.startswith(("OMPI_", "PMIX_", "OPAL_", "PRTE_"))})
    deadline = time.time() + 120
    while time.time() < deadline and "Accepting connection" not in open(log_path).read():
        if server.poll() is not None:
            raise RuntimeError("pvserver exited with status %s: %s" % (server.returncode, open(log_path).read()))
        time.sleep(0.25)
    if not simple.Connect("localhost", port):
        raise RuntimeError("could not connect to pvserver on port %d" % port)
    simple.LoadPlugin(plugin_path(), remote=True, ns=ns)
    return server


def stop_pvserver(server):
    """Disconnects from a server of start_pvserver and waits for it (kills it after 5 s)."""
    if server is None:
        return
    from paraview import simple
    simple.Disconnect()
    try:
        server.wait(timeout=5)
    except Exception:
        server.kill()


def mpi_pipeline(ns):
    """The pipeline that test_mpi.py runs on 2 ranks and test_mpi_compare.py on one: an off-centre
    Gaussian sphere (64^3), its index, an oblique knife-edge image with the automatic scale (the
    largest deflection is reduced across ranks) and a shadowgraph 2 units behind the volume
    (photons land in pixels traced by the other rank). `ns` is the namespace the plugin was loaded
    into (see load_plugin). Returns (index, knife, shadow)."""
    scene = ns["RefractiveScene"](Scene="GaussianSphere", Dimensions=[64, 64, 64],
                                   Bounds=[-1, 1, -1, 1, -1, 1], Amplitude=1e-4, Width=0.3,
                                   Center=[0.1, -0.05, 0.02])
    index = ns["RefractiveIndex"](Input=scene, Model="GladstoneDale")
    index.InputArray = ["POINTS", "density"]
    # Backend CPU: under MPI the volume is traced in pieces, on the CPU backend; one process on
    # the same backend then gives the same image bit for bit
    knife = ns["SchlierenImage"](Input=index, ViewDirection=[0.3, -0.2, -1.0], ViewUp=[0, 1, 0],
                                  Resolution=[96, 80], Passes=2, Seed=3, Cutoff="KnifeEdge",
                                  CutoffScale=0.0, KnifeAngle=30.0, Backend="CPU")
    # the shadowgraph's contrast is photon counting (this sphere is too weak for a shadow: with
    # JitterPattern Lattice every photon stays in its pixel: I in [1.000, 1.000]), so Random: its
    # photons cross into pixels the other rank traced, which the comparison is about
    shadow = ns["SchlierenImage"](Input=index, Resolution=[64, 64], Passes=2, Seed=5,
                                   Cutoff="Shadowgraph", FilmDistance=2.0, Integrator="Midpoint",
                                   Backend="CPU", JitterPattern="Random")
    return index, knife, shadow


def image_record(prefix, data):
    """A dict of numpy arrays describing a SchlierenImage output (for np.savez)."""
    X, Y, I, D, F = image_arrays(data)
    return {
        prefix + "_intensity": I,
        prefix + "_deflection": D,
        prefix + "_origin": np.array(data.GetOrigin()),
        prefix + "_spacing": np.array(data.GetSpacing()),
        prefix + "_cutoff_scale": np.array(F.get("cutoff_scale", np.nan)),
        prefix + "_photons": np.array(F.get("photons", np.nan)),
    }


def errors_of(text):
    """(class, message) of every error in VTK's output `text` (loguru's "ERR|" lines and the
    "ERROR: In ..." form), but the executive's "returned failure" lines."""
    lines = text.splitlines()
    out = []
    for i, line in enumerate(lines):
        if "ERR|" in line:
            body = line.split("ERR|", 1)[1].strip()
        elif line.startswith("ERROR: In") and i + 1 < len(lines):
            body = lines[i + 1].strip()
        else:
            continue
        if "returned failure" in body:
            continue
        out.append((body.split(" ", 1)[0], body.split("): ", 1)[-1]))
    return out


def write_mpi_volume(path):
    """A 21^3 image with n_minus_1 and density (VTK's wavelet), written by this process alone (no
    MPI in the writer): the file each rank of an MPI test reads, or leaves missing to fail."""
    from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
    from vtkmodules.vtkFiltersCore import vtkArrayCalculator
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

    src = vtkRTAnalyticSource()
    src.SetWholeExtent(-10, 10, -10, 10, -10, 10)
    calcs = []
    last = src
    for name, fn in (("n_minus_1", "RTData*1e-7"), ("density", "1.2+RTData*1e-4")):
        c = vtkArrayCalculator()
        c.SetInputConnection(last.GetOutputPort())
        c.AddScalarArrayName("RTData")
        c.SetFunction(fn)
        c.SetResultArrayName(name)
        calcs.append(c)
        last = c
    w = vtkXMLImageDataWriter()
    w.SetInputConnection(last.GetOutputPort())
    w.SetFileName(path)
    w.Write()
