# SPDX-License-Identifier: BSD-3-Clause
"""RefractiveIndex's pipeline rules, the engine's (OpenCL/SchlierenSamplingGrid.h, issue 47),
against the VTK they replace in the C++ filter.

- The extent asked of an image input (schlieren_input_request): the piece of the output's update
  extent as vtkExtentTranslator.PieceToExtentThreadSafe splits it by cells (block mode and the X, Y
  and Z slabs, ghost levels), grown by one point and clamped to the whole extent, on 20000 random
  extents, pieces and ghost levels: no difference.
- The sampling box (schlieren_sampling_box): the input's bounds pulled in by 1e-6 as
  vtkBoundingBox.ScaleAboutCenter pulls them, bit for bit, on 4000 random boxes of every scale.
- A resampled input is asked for whole, as piece rank of ranks (one piece where symmetric).

Runs in pvpython (VTK's translator and bounding box) on the engine library through the Python
front end's wrappers (schlieren._engine); about a second.
"""
import argparse
import os
import random
import sys

from vtkmodules.vtkCommonDataModel import vtkBoundingBox
from vtkmodules.vtkCommonExecutionModel import vtkExtentTranslator

ap = argparse.ArgumentParser()
ap.add_argument("--python", required=True, help="the folder holding the schlieren package")
args = ap.parse_args()
sys.path.insert(0, os.path.abspath(args.python))
from schlieren import _engine  # noqa: E402

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


rng = random.Random(47)
translator = vtkExtentTranslator()
differ, cases, first = 0, 0, None
for _ in range(20000):
    whole = []
    for a in range(3):
        lo = rng.randint(-3, 3)
        whole += [lo, lo + rng.choice([0, 0, 1, 2, 3, 5, 8, 17, 40])]
    update = list(whole)
    if rng.random() < 0.3:  # a sub-extent asked downstream
        for a in range(3):
            lo = rng.randint(whole[2 * a], whole[2 * a + 1])
            update[2 * a:2 * a + 2] = [lo, rng.randint(lo, whole[2 * a + 1])]
    pieces = rng.choice([2, 3, 4, 5, 7, 8, 13, 64, 1000])
    piece = rng.randrange(pieces)
    ghosts = rng.choice([0, 0, 1, 2])
    mode = rng.choice([3, 3, 0, 1, 2])
    split = [0] * 6
    translator.PieceToExtentThreadSafe(piece, pieces, ghosts, list(update), split, mode, 0)
    expected = list(split)  # the C++ filter's growth before issue 47
    if not (expected[1] < expected[0] or expected[3] < expected[2] or expected[5] < expected[4]):
        for a in range(3):
            expected[2 * a] = max(expected[2 * a] - 1, whole[2 * a])
            expected[2 * a + 1] = min(expected[2 * a + 1] + 1, whole[2 * a + 1])
    got = _engine.input_request(False, False, piece=piece, pieces=pieces, ghosts=ghosts,
                                split_mode=mode, update_extent=update, whole_extent=whole)
    cases += 1
    if got != (0, 1, expected):
        differ += 1
        first = first or (whole, update, piece, pieces, ghosts, mode, expected, got)
check(differ == 0, "an image's extent asked for: vtkExtentTranslator's split grown by one point, "
      "%d cases, %d differ%s" % (cases, differ, "" if first is None else " (first: %s)" % (first,)))

check(_engine.input_request(True, False, rank=2, ranks=4) == (2, 4, None) and
      _engine.input_request(True, True, rank=2, ranks=4) == (0, 1, None) and
      _engine.input_request(False, True, rank=1, ranks=2) == (0, 1, None),
      "a mesh read whole as piece rank of ranks; a symmetric input whole on one piece")

differ, first = 0, None
for k in range(4000):
    scale = 10.0 ** rng.uniform(-12, 12)
    bounds = []
    for a in range(3):
        lo = rng.uniform(-1, 1) * scale * rng.choice([1, 1e3, 1e-3])
        bounds += [lo, lo + (0.0 if rng.random() < 0.05 else rng.uniform(0, 2) * scale)]
    if max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4]) <= 0:
        bounds[1] = bounds[0] + scale
    box = vtkBoundingBox(bounds)
    box.ScaleAboutCenter(1.0 - 1e-6)
    vtk = [0.0] * 6
    box.GetBounds(vtk)
    engine = _engine.sampling_box({}, bounds)
    if engine != vtk:
        differ += 1
        first = first or (bounds, vtk, engine)
check(differ == 0, "the sampling box pulled in as vtkBoundingBox.ScaleAboutCenter(1 - 1e-6), bit "
      "for bit: 4000 boxes, %d differ%s" % (differ, "" if first is None else " (%s)" % (first,)))

try:
    _engine.sampling_box({}, None)
    said = ""
except _engine.EngineError as e:
    said = str(e)
check(said == "The input has no points to resample onto an image grid.",
      "no points: the C++ filter's message (%r)" % said)

print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
