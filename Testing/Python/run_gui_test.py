# SPDX-License-Identifier: BSD-3-Clause
"""Runs test_gui.py (or --script NAME) in the ParaView GUI under Xvfb and turns its outcome into an exit status.

Run with Debian's Python: /usr/bin/python3 run_gui_test.py --paraview /usr/bin/paraview
    --plugin <Schlieren.so> --result <file> [--with-xvfb ../with_xvfb.sh]

Passes only if paraview exits 0 and the script wrote "PASS" to the result file (a script that did
not run at all cannot pass).
"""
import argparse
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
parser = argparse.ArgumentParser()
parser.add_argument("--paraview", required=True)
parser.add_argument("--plugin", required=True)
parser.add_argument("--result", required=True)
parser.add_argument("--with-xvfb", default=os.path.join(here, "..", "with_xvfb.sh"),
                    help="runs its arguments under a private Xvfb")
parser.add_argument("--timeout", type=float, default=120)
parser.add_argument("--script", default="test_gui.py", help="the GUI script, in this folder")
args = parser.parse_args()

if os.path.exists(args.result):
    os.remove(args.result)
env = dict(os.environ, SCHLIEREN_PLUGIN=args.plugin, SCHLIEREN_GUI_RESULT=args.result)
# the GUI's script has no __file__: tell it where the shared CFD data is
env.setdefault("SCHLIEREN_DATA", os.path.join(here, "..", "..", "..", "shared", "data"))
env.setdefault("SCHLIEREN_GUI_BASELINE", os.path.join(here, "..", "Baselines", "gui_follow_bluntfin.png"))
command = [args.with_xvfb, args.paraview, "--dr",
           "--script=" + os.path.join(here, args.script), "--exit"]
print(" ".join(command))
sys.stdout.flush()
process = subprocess.Popen(command, env=env)
try:
    rc = process.wait(timeout=args.timeout)
except subprocess.TimeoutExpired:
    process.terminate()  # the wrapper stops paraview and its Xvfb
    process.wait()
    print("FAIL: the GUI did not exit within %g s" % args.timeout)
    sys.exit(1)

text = open(args.result).read() if os.path.exists(args.result) else ""
print(text)
if rc != 0:
    print("FAIL: paraview exited with status %d" % rc)
    sys.exit(1)
if not text.rstrip().endswith("PASS"):
    print("FAIL: the GUI script did not report PASS (result file %s)" % args.result)
    sys.exit(1)
print("%s: passed" % args.script)
