# SPDX-License-Identifier: BSD-3-Clause
"""The overlapping AMR that python.python_plugin_parity resamples
through both front ends: level 0 of `cells0`^3 cells over [-1, 1]^3, level 1 two boxes side by side
(sharing a face) at half the spacing over [-0.5, 0.5]^3, a Gaussian density 1.2 + 0.4 exp(-r^2/0.1)
centred at x = 0.1, 0.01 higher on level 1 (so that the finest level's choice shows), as point data
or as cell data (float32)."""
import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import (vtkAMRBox, vtkAMRUtilities, vtkOverlappingAMR,
                                           vtkUniformGrid)


def _block(lo, h, n, cells, offset):
    g = vtkUniformGrid()
    g.SetOrigin(*lo)
    g.SetSpacing(h, h, h)
    g.SetDimensions(n[0] + 1, n[1] + 1, n[2] + 1)
    axes = [lo[a] + h * (np.arange(n[a] + (0 if cells else 1)) + (0.5 if cells else 0.0))
            for a in range(3)]
    z, y, x = np.meshgrid(axes[2], axes[1], axes[0], indexing="ij")
    rho = 1.2 + 0.4 * np.exp(-((x - 0.1) ** 2 + y ** 2 + z ** 2) / 0.1) + offset
    a = numpy_support.numpy_to_vtk(rho.ravel().astype(np.float32), deep=1)
    a.SetName("density")
    (g.GetCellData() if cells else g.GetPointData()).AddArray(a)
    return g


def two_level_amr(cells, cells0=16):
    """The AMR above, its density as cell data (`cells`) or point data."""
    h0 = 2.0 / cells0
    amr = vtkOverlappingAMR()
    amr.Initialize(2, [1, 2])
    amr.SetOrigin([-1.0] * 3)
    amr.SetSpacing(0, [h0] * 3)
    amr.SetAMRBox(0, 0, vtkAMRBox([-1.0] * 3, [cells0 + 1] * 3, [h0] * 3, [-1.0] * 3, 8))
    amr.SetDataSet(0, 0, _block([-1.0] * 3, h0, [cells0] * 3, cells, 0.0))
    amr.SetSpacing(1, [h0 / 2] * 3)
    fine = [cells0 // 2, cells0, cells0]  # 0.5 x 1 x 1 at h0 / 2
    for b, x0 in enumerate((-0.5, 0.0)):
        amr.SetAMRBox(1, b, vtkAMRBox([x0, -0.5, -0.5], [c + 1 for c in fine], [h0 / 2] * 3,
                                      [-1.0] * 3, 8))
        amr.SetDataSet(1, b, _block([x0, -0.5, -0.5], h0 / 2, fine, cells, 0.01))
    amr.SetRefinementRatio(0, 2)
    vtkAMRUtilities.BlankCells(amr)
    return amr
