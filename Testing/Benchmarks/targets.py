# SPDX-License-Identifier: BSD-3-Clause
"""Benchmark (not a test): issue 24's targets table. For each volume size x backend x setting
(the panel's default: Euler 0.5 voxel, trilinear; Auto at its default tolerance; Auto + Cubic at
--tolerance), on a Gaussian sphere A = 2e-4, s = 0.25 and a 512^2 film:

  first update  the first update after Apply (index packing, upload, Auto's pilot, one pass)
  error         the largest |deflection - closed form| over the film, relative to the closed
                form's largest deflection, on axis (-z) and oblique (a view off every axis);
                Jitter 0, one pass: pixel centres
  samples/ray   on axis and oblique
  move -> first the time from a camera move to the first image on the interactive half film
                (Resolution / 2, 1 pass, as the GUI's follower traces while the view turns)
  move -> conv  the time from a camera move to the converged full-film image: N passes, N the
                fewest whose intensity is within 1 % RMS (of the intensity range) of the 64-pass
                JitterPattern Random image (the limit both patterns converge to). N is measured
                once per JitterPattern (Random, Lattice), on the Auto setting of the smallest
                size, and used for every row (the noise is the film's jitter, the same for every
                setting and size). Measured on oblique moves and on moves near the axis (the
                on-axis view's film is all volume: more samples per photon than oblique).

    pvpython targets.py --plugin Schlieren.so [--sizes 128,256,512] [--backends OpenCL,CPU]
        [--film 512] [--tolerance 3e-8] [--only default,auto,autocubic] [--patterns Random,Lattice]

Timings are one run each on this machine; compare rows of one run.
"""
import argparse
import math
import os
import sys
import time

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
import schlieren_testing as st  # noqa: E402  (the closed form the tests use)

ap = argparse.ArgumentParser()
ap.add_argument("--plugin", required=True)
ap.add_argument("--sizes", default="128,256,512")
ap.add_argument("--backends", default="OpenCL,CPU")
ap.add_argument("--film", type=int, default=512)
ap.add_argument("--tolerance", type=float, default=3e-8, help="Auto + Cubic's tolerance, radians")
ap.add_argument("--only", default="default,auto,autocubic")
ap.add_argument("--passes", default="", help="N for converged per pattern, e.g. 8,2 (empty: measure)")
ap.add_argument("--patterns", default="Random,Lattice", help="JitterPatterns of the converged columns")
args = ap.parse_args()
LoadPlugin(args.plugin, remote=False, ns=globals())

A, S = 2e-4, 0.25
EMAX = st.gaussian_max_deflection(A)
AXIS = ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0])


def view(k):
    """Oblique views, each a different one (a move, not a rest): off every axis. k < 0: views
    within 2 degrees of the axis (-z), each a different one."""
    if k < 0:
        a, b = 0.012 * k, 0.02 + 0.007 * k
    else:
        a, b = 0.6 + 0.35 * k, 0.45 + 0.1 * k
    d = np.array([math.sin(a) * math.cos(b), math.sin(b), -math.cos(a) * math.cos(b)])
    up = np.array([0.0, 1.0, 0.0]) - d * d[1]
    return d.tolist(), (up / np.linalg.norm(up)).tolist()


SETTINGS = [("default", "default (Euler 0.5 voxel, trilinear)", dict(Integrator="Euler", StepSize=0.5)),
            ("auto", "Auto, default tolerance", dict(Integrator="Auto", Tolerance=0.0)),
            ("autocubic", "Auto + Cubic, %g rad" % args.tolerance,
             dict(Integrator="Auto", Reconstruction="Cubic", Tolerance=args.tolerance))]


def error(data):
    """Largest |deflection - closed form| / EMAX over the film (film coordinates are world units
    in the film plane, centred on the volume's centre: the sphere's centre)."""
    X, Y, _, d, _ = st.image_arrays(data)
    return float(np.abs(d - st.gaussian_deflection(X, Y, A, S)).max() / EMAX)


def fields(data):
    return st.image_arrays(data)[4]


def intensity(data):
    return st.image_arrays(data)[2].ravel()


def timed(image):
    t0 = time.perf_counter()
    image.UpdatePipeline()
    return time.perf_counter() - t0


def look(image, d_up, **kw):
    image.ViewDirection, image.ViewUp = d_up
    for k, v in kw.items():
        setattr(image, k, v)


sizes = [int(s) for s in args.sizes.split(",")]
backends = args.backends.split(",")
volumes = {}
for n in sizes:
    scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[n] * 3, Amplitude=A, Width=S)
    index = RefractiveIndex(Input=scene, Model="Passthrough")
    index.UpdatePipeline()
    volumes[n] = index

film = [args.film] * 2
half = [args.film // 2] * 2
common = dict(Cutoff="KnifeEdge", CutoffScale=1000.0, Passes=1)

patterns = args.patterns.split(",")
NP = dict(zip(patterns, [int(v) for v in args.passes.split(",")])) if args.passes else {}
if not NP:
    # the fewest passes within 1 % RMS of the 64-pass Random image (Auto, smallest size, first
    # backend); a new seed for each image, so that no pass is kept from the last
    image = SchlierenImage(Input=volumes[sizes[0]], Resolution=film, Backend=backends[0], **common,
                           **SETTINGS[1][2])
    look(image, view(0), Passes=64, Seed=1000)
    ref = intensity(sm.Fetch(image))
    scale = ref.max() - ref.min()
    for pattern in patterns:
        for N in (1, 2, 4, 8, 16, 32, 64):
            look(image, view(0), Passes=N, Seed=N, JitterPattern=pattern)
            rms = float(np.sqrt(np.mean((intensity(sm.Fetch(image)) - ref) ** 2)) / scale)
            print("%s, passes %d: RMS %.4f of the intensity range against 64 Random passes" % (pattern, N, rms))
            if rms <= 0.01:
                break
        NP[pattern] = N
    Delete(image)

rows = []
for n in sizes:
    for backend in backends:
        for key, name, kw in SETTINGS:
            if key not in args.only.split(","):
                continue
            image = SchlierenImage(Input=volumes[n], Resolution=film, Backend=backend, Jitter=0,
                                   ViewDirection=AXIS[0], ViewUp=AXIS[1], **common, **kw)
            first = timed(image)
            data = sm.Fetch(image)
            f = fields(data)
            e_axis, spr_axis = error(data), f.get("samples_per_ray", float("nan"))
            choice = f.get("auto_report", name)
            look(image, view(1))
            data = sm.Fetch(image)
            e_obl, spr_obl = error(data), fields(data).get("samples_per_ray", float("nan"))
            # camera moves as the GUI's follower makes them: half film, 1 pass; then the full
            # film refined to N passes
            # at rest with the film's jitter on (Jitter is a setting Auto's pilot is keyed on;
            # the moves below change the view and the film's size only, as the follower does)
            look(image, view(1), Jitter=1)
            image.UpdatePipeline()
            t_first, t_conv = {}, {}
            for pattern in patterns:
                look(image, view(1), JitterPattern=pattern)
                image.UpdatePipeline()
                for where, ks in (("oblique", (2, 3)), ("axis", (-1, -2))):
                    for k in ks:
                        look(image, view(k), Resolution=half, Passes=1)
                        t = timed(image)
                        t_first.setdefault(where, []).append(t)
                        t0 = time.perf_counter()
                        look(image, view(k), Resolution=film, Passes=NP[pattern])
                        image.UpdatePipeline()
                        t_conv.setdefault((pattern, where), []).append(t + time.perf_counter() - t0)
            conv = " | ".join("%.2f" % np.mean(t_conv[p, w]) for w in ("oblique", "axis") for p in patterns)
            rows.append((n, backend, name, first, e_axis, e_obl, spr_axis, spr_obl,
                         float(np.mean(t_first["oblique"])), float(np.mean(t_first["axis"])), conv,
                         str(choice)[:70]))
            print("| %d^3 | %s | %s | %.2f | %.2e | %.2e | %.0f | %.0f | %.3f | %.3f | %s | %s |" % rows[-1], flush=True)
            Delete(image)

print()
print("Gaussian sphere A = %g, s = %g; %d^2 film; converged = %s passes; errors of the largest deflection %.3g rad"
      % (A, S, args.film, ", ".join("%s %d" % (p, NP[p]) for p in patterns), EMAX))
print()
conv_heads = " | ".join("move -> converged s, %s, %s" % (w, p) for w in ("oblique", "axis") for p in patterns)
print("| volume | backend | setting | first update s | error on axis | error oblique | samples/ray axis "
      "| samples/ray oblique | move -> first image s, oblique | axis | %s | choice |" % conv_heads)
print("|" + "---|" * (11 + 2 * len(patterns)))
for r in rows:
    print("| %d^3 | %s | %s | %.2f | %.2e | %.2e | %.0f | %.0f | %.3f | %.3f | %s | %s |" % r)
