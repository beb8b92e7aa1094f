# SPDX-License-Identifier: BSD-3-Clause
"""Real CFD data through RefractiveIndex and SchlierenImage, with numbers:

The NASA blunt fin (PLOT3D, Mach 2.95, density non-dimensional with free stream 1), resampled
(128 x 49 x 34, automatic), Gladstone-Dale air with rho_inf = 1.2 kg/m^3, traced looking down on
the plate (beam along -z, knife normal along x, film pixel = half a voxel, no jitter):
  - n - 1 = K_air 1.2 Density at every point inside the CFD grid;
  - the bow shock is where the density puts it: along film rows y = 0.3, 1, 2, 3, 4, the largest
    |deflection_x| is within 2 voxels of the largest |d/dx| of the projected index
    P(x, y) = sum_z (n - 1) dz of the resampled grid, and its size agrees (10 %); on the symmetry
    row it lies within the shock stand-off found in the raw curvilinear data (the half-jump
    crossing of the density along the stagnation line, z from 0.9 to 5.7);
  - no false edge: the largest |deflection| within one voxel of the upstream edge of the CFD grid
    (x < -2) is below 5 % of the image's largest, with the default AmbientMode (Extend); a constant
    ambient (DomainEdgeMedian) draws that edge at least 5 times stronger (why Extend is the default).
The reactor (Exodus II, unstructured), IdealGas hydrogen (Temp in K, Pres a gauge pressure in Pa
over an operating pressure of 101325 Pa):
  - n - 1 = K_H2 p M_H2 / (R T) from the resampled Temp and Pres at every point inside the mesh,
    and at its coldest point (293.15 K) the value of the table's constants;
  - by species (H2 and CH4 from the table, arsine and trimethylgallium typed, no balance gas) the
    same against the mass-fraction formula;
  - the traced image has no NaN and shows the heated gas (intensity spread > 0.1).

Skips (exit status 125) when ../shared/data (or $SCHLIEREN_DATA) is absent.

Run: pvpython test_cfd_data.py --plugin <build>/lib/paraview-X.Y/plugins/Schlieren/Schlieren.so
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

xyz, q, exo = ct.require_data("bluntfinxyz.bin", "bluntfinq.bin", "disk_out_ref.ex2")
st.load_plugin(globals())
T = st.Checker("test_cfd_data")


def fetch(proxy):
    with st.CapturedOutput() as out:
        proxy.UpdatePipeline()
        data = sm.Fetch(proxy)
    T.check("ERROR" not in out.text, "%s: no error%s" % (proxy.GetXMLName(), "" if "ERROR" not in out.text
                                                          else ": " + out.text.strip()[:400]))
    return data


# ================================================================ the blunt fin
K_AIR, RHO_INF = 0.2256e-3, 1.2
reader = PLOT3DReader(FileName=xyz, QFileName=[q])
index = RefractiveIndex(Input=reader, Model="GladstoneDale", Gas="Air", DensityReference=RHO_INF)
index.InputArray = ["POINTS", "Density"]
grid = fetch(index)
dims = grid.GetDimensions()
o = np.array(grid.GetOrigin())
h = np.array(grid.GetSpacing())
T.check(tuple(dims) == (128, 49, 34), "blunt fin resampled onto %s points (automatic: 128 along x)" % (dims,))
n1, rho, mask = ct.grid_arrays(grid, "n_minus_1", "Density", "vtkValidPointMask")
inside = mask > 0
T.check(0.8 < inside.mean() < 0.95, "%.1f %% of the grid inside the CFD grid" % (100 * inside.mean()))
T.close(n1[inside], K_AIR * RHO_INF * rho[inside], 2e-9, "n - 1 = K_air x 1.2 x Density inside the CFD grid")
T.check(np.isfinite(n1).all() and n1.min() > 0.15 * K_AIR * RHO_INF,
        "n - 1 finite and never near 0 (min %.3g; free stream %.3g)" % (n1.min(), K_AIR * RHO_INF))

# The projected index and its x-derivative (what a straight ray along z sees).
P = n1.sum(axis=0) * h[2]
dPdx = np.gradient(P, h[0], axis=1)
gx = o[0] + h[0] * np.arange(dims[0])
gy = o[1] + h[1] * np.arange(dims[1])


def trace(proxy_index, **extra):
    img = SchlierenImage(Input=proxy_index, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0],
                         Resolution=[2 * dims[0], 2 * dims[1]], Passes=1, Jitter=0, Cutoff="KnifeEdge",
                         KnifeAngle=0.0, **extra)
    X, Y, I, D, F = st.image_arrays(fetch(img))
    return X[0], Y[:, 0], I, D, F


X, Y, I, D, F = trace(index)
T.check(np.isfinite(I).all() and np.isfinite(D).all(), "blunt fin image: no NaN (%d x %d, %s)"
        % (I.shape[1], I.shape[0], F.get("backend")))
T.check(abs(X[1] - X[0] - h[0] / 2) < 0.02 * h[0], "film pixel %.4f = half a voxel (%.4f)" % (X[1] - X[0], h[0] / 2))
for yv in (0.3, 1.0, 2.0, 3.0, 4.0):
    jf = int(np.argmin(abs(Y - yv)))
    jg = int(np.argmin(abs(gy - yv)))
    xi = X[int(np.argmax(abs(D[jf, :, 0])))]
    xg = gx[int(np.argmax(abs(dPdx[jg])))]
    T.check(abs(xi - xg) <= 2 * h[0],
            "bow shock on row y = %.1f: image at x = %.3f, density gradient at x = %.3f (%.2f voxels apart)"
            % (yv, xi, xg, abs(xi - xg) / h[0]))
    ratio = abs(D[jf, :, 0]).max() * 1.00027 / abs(dPdx[jg]).max()
    T.check(abs(ratio - 1) < 0.1, "row y = %.1f: max |deflection| / max |dP/dx| = %.3f" % (yv, ratio))

# The shock stand-off in the raw curvilinear data, on the stagnation line (y = 0, ahead of the nose).
raw = sm.Fetch(reader).GetBlock(0)
rp = vtk_to_numpy(raw.GetPoints().GetData()).reshape(32, 32, 40, 3)  # k, j, i
rr = vtk_to_numpy(raw.GetPointData().GetArray("Density")).reshape(32, 32, 40)
stand = []
for k in range(22, 32):  # z from 0.9 to 5.7, above the separated boundary layer
    line, xl = rr[k, :, 0], rp[k, :, 0, 0]
    half = 0.5 * (1.0 + line.max())
    j = int(np.where(line >= half)[0].max())
    stand.append(xl[j] + (half - line[j]) * (xl[j + 1] - xl[j]) / (line[j + 1] - line[j]))
jf = int(np.argmin(abs(Y - 0.1)))
xi = X[int(np.argmax(abs(D[jf, :, 0])))]
T.check(min(stand) - h[0] <= xi <= max(stand) + h[0],
        "bow shock on the symmetry row (y = %.2f) at x = %.3f; the raw data's stand-off is %.3f .. %.3f"
        % (Y[jf], xi, min(stand), max(stand)))

# No false edge where the CFD grid ends (its outer boundary upstream of the fin).
columns_out = ~inside.any(axis=0)  # (y, x): no point of the column inside the CFD grid
edge = np.zeros_like(columns_out)
edge[:, 1:] |= columns_out[:, 1:] != columns_out[:, :-1]
edge[:, :-1] |= columns_out[:, 1:] != columns_out[:, :-1]
edge[1:] |= columns_out[1:] != columns_out[:-1]
edge[:-1] |= columns_out[1:] != columns_out[:-1]
GX, GY = np.meshgrid(gx, gy)
FX, FY = np.meshgrid(X, Y)
near = np.zeros(I.shape, bool)
for x0, y0 in zip(GX[edge & (GX < -2.0)], GY[edge & (GX < -2.0)]):
    near |= (abs(FX - x0) <= h[0]) & (abs(FY - y0) <= h[1])
mag = np.hypot(D[..., 0], D[..., 1])
extend_ratio = mag[near].max() / mag.max()
T.check(near.sum() > 100 and extend_ratio < 0.05,
        "no false edge: max |deflection| within a voxel of the grid's upstream edge (%d pixels) is %.2f %% "
        "of the largest (Extend)" % (near.sum(), 100 * extend_ratio))
median = RefractiveIndex(Input=reader, Model="GladstoneDale", Gas="Air", DensityReference=RHO_INF,
                         AmbientMode="DomainEdgeMedian")
median.InputArray = ["POINTS", "Density"]
amb = ct.field_value(fetch(median), "ambient_n_minus_1")
_, _, _, Dm, _ = trace(median)
magm = np.hypot(Dm[..., 0], Dm[..., 1])
median_ratio = magm[near].max() / magm.max()
T.check(median_ratio > 5 * extend_ratio,
        "a constant ambient (DomainEdgeMedian: %.3g = %.2f rho_inf, the inflow boundary layer's) draws "
        "the edge at %.1f %% of the largest deflection" % (amb, amb / (K_AIR * RHO_INF), 100 * median_ratio))

# ================================================================ the reactor
K_H2, M_H2 = ct.GASES["H2"]
exodus = ExodusIIReader(FileName=exo)
exodus.PointVariables = ["Temp", "Pres", "H2", "CH4", "AsH3", "GaMe3"]
hydrogen = RefractiveIndex(Input=exodus, Model="IdealGas", IdealGasComposition="Gas", Gas="H2",
                           PressureOffset=101325.0, AutomaticDimension=96)
hydrogen.TemperatureArray = ["POINTS", "Temp"]
hydrogen.PressureArray = ["POINTS", "Pres"]
rg = fetch(hydrogen)
rn1, Tk, pg, rmask = ct.grid_arrays(rg, "n_minus_1", "Temp", "Pres", "vtkValidPointMask")
ins = rmask > 0
T.check(0.5 < ins.mean() < 0.7, "reactor: %s grid, %.0f %% inside the mesh" % (rg.GetDimensions(), 100 * ins.mean()))
T.check(Tk[ins].min() > 290 and Tk[ins].max() < 920 and 0 < pg[ins].min() and pg[ins].max() < 0.03,
        "reactor: Temp %.1f..%.1f K, Pres %.4f..%.4f (gauge)" % (Tk[ins].min(), Tk[ins].max(), pg[ins].min(), pg[ins].max()))
expected = ct.ideal_gas_n1(Tk[ins], pg[ins] + 101325.0, "H2")
T.close(rn1[ins] / expected, 1.0, 1e-6, "reactor: n - 1 = K_H2 p M_H2 / (R T) at %d points" % ins.sum())
cold = ct.ideal_gas_n1(293.15, 101325.0, "H2")
T.close(rn1.max(), cold, 1e-6 * cold, "reactor: largest n - 1 %.6g = hydrogen at 293.15 K, 1 atm (%.6g)"
        % (rn1.max(), cold))
T.check(np.isfinite(rn1).all() and rn1.min() > 0.3 * cold, "reactor: n - 1 finite and > 0 everywhere")

# The same by species: arsine and trimethylgallium typed (molar masses 77.9454 and 114.827 g/mol;
# the Gladstone-Dale constants here are test values, not data).
TYPED = {"AsH3": (0.5e-3, 77.9454e-3), "GaMe3": (0.4e-3, 114.827e-3)}
species = RefractiveIndex(Input=exodus, Model="IdealGas", IdealGasComposition="Species", NumberOfSpecies=4,
                          SpeciesGases=[6, 8, -1, -1], SpeciesGladstoneDale=[0, 0, 0.5e-3, 0.4e-3],
                          SpeciesMolarMass=[0, 0, 77.9454e-3, 114.827e-3], BalanceGas="None",
                          PressureOffset=101325.0, AutomaticDimension=96)
species.TemperatureArray = ["POINTS", "Temp"]
species.PressureArray = ["POINTS", "Pres"]
for i, name in enumerate(("H2", "CH4", "AsH3", "GaMe3")):
    setattr(species, "Species%dArray" % (i + 1), ["POINTS", name])
sg = fetch(species)
sn1, y1, y2, y3, y4 = ct.grid_arrays(sg, "n_minus_1", "H2", "CH4", "AsH3", "GaMe3")
total = np.where(ins, y1 + y2 + y3 + y4, 1.0)  # outside the mesh the probe leaves 0
fractions = [y / total for y in (y1, y2, y3, y4)]
expected = ct.mixture_n1(Tk, pg + 101325.0, fractions, ["H2", "CH4", TYPED["AsH3"], TYPED["GaMe3"]])
T.close(sn1[ins] / expected[ins], 1.0, 1e-6, "reactor by species (H2, CH4, typed AsH3 and GaMe3): n - 1 "
        "= sum Y K x p / (sum Y/M R T)")
T.check(np.mean(sn1[ins]) > 1.02 * np.mean(rn1[ins]),
        "the heavy species raise the density: mean n - 1 %.4g vs %.4g for pure H2" % (np.mean(sn1[ins]), np.mean(rn1[ins])))

image = SchlierenImage(Input=hydrogen, ViewDirection=[1, 0, 0], ViewUp=[0, 0, 1], Resolution=[96, 128],
                       Passes=2, Cutoff="KnifeEdge", KnifeAngle=0.0)
FX, FY, I, D, F = st.image_arrays(fetch(image))
T.check(np.isfinite(I).all() and np.isfinite(D).all(), "reactor image: no NaN")
spread = np.percentile(I, 99) - np.percentile(I, 1)
T.check(spread > 0.1, "reactor image shows the heated gas: intensity 1-99 %% spread %.3f" % spread)
# The heated region is over the disk (z from about -1 to 4): the strongest deflections are there.
rows = np.abs(D[..., 0]).max(axis=1)
z_peak = FY[int(np.argmax(rows)), 0]
T.check(-2.0 < z_peak < 5.0, "reactor: strongest deflection at z = %.2f, over the heated disk" % z_peak)

T.finish()
