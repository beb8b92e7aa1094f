# SPDX-License-Identifier: BSD-3-Clause
"""Writes cone_m2_15deg.vtu: the axisymmetric supersonic flow over a sharp cone, an r-x half plane
(not a CFD run: the closed-form Taylor-Maccoll solution, which a CFD code converges to).

    pvpython Examples/data/make_cone_flow.py [--output cone_m2_15deg.vtu]

Air (gamma 1.4) at Mach 2, 50 kPa and 220 K (rho = 0.792 kg/m^3) meets a 15 degree half-angle cone
whose tip is at the origin and whose axis is x. The flow is conical: behind the attached conical
shock every quantity depends only on the angle theta from the axis. Taylor-Maccoll's equation for
the radial velocity V_r(theta) (velocities over the maximum velocity),

    V_r'' = [V_th^2 V_r' - (g-1)/2 (1 - V_r^2 - V_th^2)(2 V_r + V_th cot th)]
            / [(g-1)/2 (1 - V_r^2 - V_th^2) - V_th^2],   V_th = V_r',

is integrated (RK4) from the shock angle beta, where the oblique-shock relations give the state,
inwards to the angle where V_th = 0, the cone's surface; beta is found by bisection so that this
angle is 15 degrees (Anderson, Modern Compressible Flow, ch. 10: beta = 33.9 degrees and a surface
Mach number 1.71 at M = 2, 15 degrees). The density is rho0_2 (1 - V^2)^(1/(g-1)), rho0_2 the
stagnation density behind the shock (p0 falls across it). Upstream of the shock the free stream.

The mesh: 1 mm quads on x in [-0.02, 0.30] m, r in [0, 0.21] m (321 x 211 points), without the
cells inside the cone (the body: the resampling fills that void). Point arrays: density (kg/m^3),
pressure (Pa), temperature (K), mach. (Examples/cone.py writes it where it is missing.)
"""
import argparse
import math
import os

import numpy as np

G = 1.4
M1, P1, T1 = 2.0, 5.0e4, 220.0
R_AIR = 287.05
CONE = math.radians(15.0)
# The mesh: 1 mm quads; r up to 0.21 m keeps the shock (r = x tan 33.9 deg) inside the domain up
# to x = 0.30 m, so that it does not leave through the outer radius within the picture.
NX, NR, R_MAX = 321, 211, 0.21


def vmax_ratio(mach):
    """V / V_max for a Mach number: (2 / ((g-1) M^2) + 1)^(-1/2)."""
    return (2.0 / ((G - 1.0) * mach ** 2) + 1.0) ** -0.5


def behind_shock(beta):
    """Deflection, Mach number behind an oblique shock of angle beta at M1, and p0_2/p0_1."""
    mn1 = M1 * math.sin(beta)
    mn2 = math.sqrt((1 + 0.5 * (G - 1) * mn1 ** 2) / (G * mn1 ** 2 - 0.5 * (G - 1)))
    theta = math.atan(2 / math.tan(beta) * (mn1 ** 2 - 1) / (M1 ** 2 * (G + math.cos(2 * beta)) + 2))
    m2 = mn2 / math.sin(beta - theta)
    p0 = ((G + 1) * mn1 ** 2 / ((G - 1) * mn1 ** 2 + 2)) ** (G / (G - 1)) * \
        ((G + 1) / (2 * G * mn1 ** 2 - (G - 1))) ** (1 / (G - 1))
    return theta, m2, p0


def rhs(th, y):
    vr, vt = y
    a = 0.5 * (G - 1) * (1 - vr ** 2 - vt ** 2)
    return np.array([vt, (vt ** 2 * vr - a * (2 * vr + vt / math.tan(th))) / (a - vt ** 2)])


def integrate(beta, steps=4000):
    """(theta, V_r, V_theta) from the shock inwards to the surface (V_theta = 0)."""
    delta, m2, _ = behind_shock(beta)
    v = vmax_ratio(m2)
    y = np.array([v * math.cos(beta - delta), -v * math.sin(beta - delta)])
    h = -beta / steps
    th = beta
    out = [(th, y[0], y[1])]
    for _ in range(steps):
        k1 = rhs(th, y)
        k2 = rhs(th + h / 2, y + h / 2 * k1)
        k3 = rhs(th + h / 2, y + h / 2 * k2)
        k4 = rhs(th + h, y + h * k3)
        ynew = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if ynew[1] >= 0:  # crossed the surface: interpolate V_theta = 0
            f = -y[1] / (ynew[1] - y[1])
            out.append((th + f * h, y[0] + f * (ynew[0] - y[0]), 0.0))
            return np.array(out)
        th += h
        y = ynew
        out.append((th, y[0], y[1]))
    return np.array(out)


def solve():
    lo, hi = math.asin(1 / M1) + 1e-4, math.radians(60)
    for _ in range(60):
        beta = 0.5 * (lo + hi)
        cone = integrate(beta)[-1, 0]
        lo, hi = (beta, hi) if cone < CONE else (lo, beta)
    return beta, integrate(beta)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default="cone_m2_15deg.vtu")
    write(ap.parse_args().output)


def write(path):
    """Solves Taylor-Maccoll and writes the half plane to `path`; returns the shock angle (rad)."""
    beta, sol = solve()
    th, vr, vt = sol[::-1, 0], sol[::-1, 1], sol[::-1, 2]  # increasing theta
    v2 = vr ** 2 + vt ** 2
    rho1 = P1 / (R_AIR * T1)
    t01 = T1 * (1 + 0.5 * (G - 1) * M1 ** 2)
    rho01 = rho1 * (1 + 0.5 * (G - 1) * M1 ** 2) ** (1 / (G - 1))
    p0ratio = behind_shock(beta)[2]
    rho02 = rho01 * p0ratio  # T0 is unchanged across the shock
    rho_th = rho02 * (1 - v2) ** (1 / (G - 1))
    t_th = t01 * (1 - v2)
    mach_th = np.sqrt(2 / (G - 1) * v2 / (1 - v2))
    surface_mach = mach_th[0]
    print("Taylor-Maccoll, M %.1f, cone %.1f deg: shock %.2f deg, surface Mach %.3f, rho %.4f..%.4f kg/m^3 "
          "(free stream %.4f)" % (M1, math.degrees(CONE), math.degrees(beta), surface_mach, rho_th.min(),
                                  rho_th.max(), rho1))

    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import VTK_QUAD, vtkCellArray, vtkUnstructuredGrid
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

    nx, nr = NX, NR
    x = np.linspace(-0.02, 0.30, nx)
    r = np.linspace(0.0, R_MAX, nr)
    R2, X2 = np.meshgrid(r, x, indexing="ij")
    theta = np.arctan2(R2, X2)
    inside_shock = (X2 > 0) & (theta <= beta)
    rho = np.full(X2.shape, rho1)
    temp = np.full(X2.shape, T1)
    mach = np.full(X2.shape, M1)
    tq = np.clip(theta, th[0], th[-1])
    rho[inside_shock] = np.interp(tq[inside_shock], th, rho_th)
    temp[inside_shock] = np.interp(tq[inside_shock], th, t_th)
    mach[inside_shock] = np.interp(tq[inside_shock], th, mach_th)
    pres = rho * R_AIR * temp

    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.stack([X2.ravel(), R2.ravel(), np.zeros(X2.size)], axis=1).astype(np.float32),
                             deep=1))
    grid = vtkUnstructuredGrid()
    grid.SetPoints(pts)
    # quads (i, j)-(i+1, j+1), less those whose centre is inside the cone (the body)
    I, J = np.meshgrid(np.arange(nx - 1), np.arange(nr - 1))
    xc, rc = 0.5 * (x[I] + x[I + 1]), 0.5 * (r[J] + r[J + 1])
    keep = ~((xc > 0) & (np.arctan2(rc, xc) < CONE))
    p = (J * nx + I)[keep]
    legacy = np.stack([np.full(p.shape, 4), p, p + 1, p + nx + 1, p + nx], axis=1).ravel()
    cells = vtkCellArray()
    cells.SetCells(p.size, numpy_to_vtkIdTypeArray(legacy.astype(np.int64), deep=1))
    grid.SetCells(VTK_QUAD, cells)
    for name, values in (("density", rho), ("pressure", pres), ("temperature", temp), ("mach", mach)):
        a = numpy_to_vtk(values.ravel().astype(np.float32), deep=1)
        a.SetName(name)
        grid.GetPointData().AddArray(a)
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(grid)
    writer.SetDataModeToBinary()
    writer.SetCompressorTypeToZLib()
    writer.Write()
    print("wrote %s: %d points, %d cells" % (path, grid.GetNumberOfPoints(), grid.GetNumberOfCells()))
    return beta


if __name__ == "__main__":
    main()
