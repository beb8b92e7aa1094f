# SPDX-License-Identifier: BSD-3-Clause
"""pvpython side of test_install.py: the installed plugin, known by name, loaded by name, traces.

Run by test_install.py as

    PV_PLUGIN_CONFIG_FILE=<prefix>/<libdir>/paraview-X.Y/plugins/Schlieren.plugins \\
    PYTHONPATH=<prefix>/lib/python3/dist-packages \\
        pvpython install_check.py --prefix <prefix> --plugin-dir <the installed plugin folder>

with nothing of the build tree in the environment. Checks that ParaView's plugin list holds
"Schlieren" at the installed Schlieren.so (it read the .plugins file), that
LoadDistributedPlugin("Schlieren", remote=False) loads it by name, and that its SchlierenImage of
the weak Gaussian sphere is the knife-edge image of ORACLES.md ("Weak Gaussian sphere"):
I = 0.5 - k eps_x with eps = -(2 sqrt(pi) A / s) (x, y) exp(-rho^2 / s^2).
"""
import math
import os
import sys

import numpy as np
from paraview import servermanager as sm
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    sys.stdout.flush()
    if not condition:
        failures.append(message)
    return condition


def argument(name):
    return sys.argv[sys.argv.index(name) + 1]


prefix = os.path.realpath(argument("--prefix"))
plugin_so = os.path.join(os.path.realpath(argument("--plugin-dir")), "Schlieren.so")

# -- ParaView's list of plugins it knows (what the Plugin Manager shows), before any load by us
info = sm.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
known = {info.GetPluginName(i): info.GetPluginFileName(i) for i in range(info.GetNumberOfPlugins())}
print("plugins ParaView knows: %s" % known)
check("Schlieren" in known, "ParaView's plugin list names Schlieren (from PV_PLUGIN_CONFIG_FILE=%s)"
      % os.environ.get("PV_PLUGIN_CONFIG_FILE"))
check(os.path.realpath(known.get("Schlieren", "")) == plugin_so,
      "Schlieren's file is the installed %s (listed: %s)" % (plugin_so, known.get("Schlieren")))

# -- the load by name
try:
    LoadDistributedPlugin("Schlieren", remote=False, ns=globals())
    check(True, 'LoadDistributedPlugin("Schlieren", remote=False) succeeded')
except Exception as e:  # the message is the check's result
    check(False, 'LoadDistributedPlugin("Schlieren", remote=False) raised %s' % e)
if failures or "SchlierenImage" not in globals():
    check("SchlierenImage" in globals(), "the plugin's SchlierenImage is defined after the load")
    sys.exit(1)
try:
    import schlieren_view  # the plugin's Python module, beside Schlieren.so, importable once loaded
    where = os.path.dirname(os.path.realpath(schlieren_view.__file__))
    check(where == os.path.dirname(plugin_so),
          "the plugin's Python module schlieren_view imports from the plugin's folder (%s)" % where)
except ImportError as e:
    check(False, "the plugin's Python module schlieren_view does not import: %s" % e)

# -- a trace through the installed plugin: the weak Gaussian sphere, knife edge along x
A, S, K = 1e-4, 0.25, 1000.0
EMAX = math.sqrt(2 * math.pi) * A * math.exp(-0.5)  # largest |eps|, at rho = s / sqrt 2
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[64, 64, 64], Bounds=[-1, 1, -1, 1, -1, 1],
                        Width=S, Amplitude=A)
image = SchlierenImage(Input=scene, Cutoff="KnifeEdge", CutoffScale=K, Resolution=[64, 64], Passes=1,
                       Jitter=0, Backend="CPU")
data = sm.Fetch(image)
nx, ny, _ = data.GetDimensions()
check((nx, ny) == (64, 64), "the image is 64 x 64 pixels (got %d x %d)" % (nx, ny))
I = vtk_to_numpy(data.GetPointData().GetArray("intensity")).astype(float).reshape(ny, nx)
x0, y0, _ = data.GetOrigin()
hx, hy, _ = data.GetSpacing()
X, Y = np.meshgrid(x0 + hx * np.arange(nx), y0 + hy * np.arange(ny))
eps_x = -(2 * math.sqrt(math.pi) * A / S) * X * np.exp(-(X ** 2 + Y ** 2) / S ** 2)
check(I.std() > 0.1 * K * EMAX, "the intensity is not constant (std %.4g, k max|eps| = %.4g)" % (I.std(), K * EMAX))
# The error is the trilinear sampling's, second order in the grid spacing: test_pipeline.py bounds
# it by 1 % of k max|eps| on a 128^3 grid; this grid is half as fine, so 4 %.
err = np.abs(I - (0.5 - K * eps_x)).max()
check(err <= 0.04 * K * EMAX, "intensity == 0.5 - k eps_x: max |difference| = %.3g %% of k max|eps| "
      "(tolerance 4 %%)" % (100 * err / (K * EMAX)))
if failures:
    print("FAIL: %s" % "; ".join(failures))
    sys.exit(1)
print("install_check: PASS")
