# SPDX-License-Identifier: BSD-3-Clause
"""Runs OpenFOAM tutorial cases (Debian's `openfoam` and `openfoam-examples`, v1912) into a folder of
the build tree, once: each case is copied, meshed and solved there, and a key (a hash of the
tutorial's files and of what is changed here) is written beside it; a later run with the same key
does nothing. The tests read the cases as a user does, through a `case.foam` file and ParaView's
OpenFOAM reader.

What is changed against the tutorials, to keep CI short:
- wedge15Ma5: written only at t = 0.1 and 0.2 (the tutorial writes every 0.02); solved as given
  (40 x 40 + 80 x 40 cells, 2000 steps, about 9 s on this machine).
- forwardStep: endTime 2 (the tutorial's 4), written every 0.5 (the tutorial's 0.2: the test
  reads t = 1.5 and 2, to see the bow shock settled); about 37 s.
- biconic25-55Run35 and LadenburgJet60psi: meshed only; their time-0 fields are a converged
  solution on that mesh (the tutorials' READMEs), so no solver runs.

Run: /usr/bin/python3 openfoam_cases.py --out <build>/openfoam [case ...]
Without OpenFOAM it says so and exits 0 (the tests that need a case then skip with the reason).
"""
import argparse
import gzip
import hashlib
import os
import shutil
import subprocess
import sys
import time

VERSION = "2"  # bump when what is done to a case changes
BASHRC = os.environ.get("SCHLIEREN_OPENFOAM_BASHRC", "/usr/share/openfoam/etc/bashrc")
TUTORIALS = os.environ.get(
    "SCHLIEREN_OPENFOAM_TUTORIALS",
    "/usr/share/doc/openfoam-examples/examples/compressible/rhoCentralFoam")


def set_entry(path, key, value):
    """Sets `key value;` in an OpenFOAM dictionary file (a top-level entry)."""
    lines = open(path).read().splitlines()
    for i, line in enumerate(lines):
        if line.split() and line.split()[0] == key:
            lines[i] = "%-16s%s;" % (key, value)
    open(path, "w").write("\n".join(lines) + "\n")


def gunzip_all(folder):
    for root, _, files in os.walk(folder):
        for f in files:
            if f.endswith(".gz"):
                src = os.path.join(root, f)
                with gzip.open(src, "rb") as i, open(src[:-3], "wb") as o:
                    shutil.copyfileobj(i, o)
                os.remove(src)


def prepare_wedge(case):
    set_entry(os.path.join(case, "system", "controlDict"), "writeInterval", "0.1")
    return ["blockMesh", "rhoCentralFoam"]


def prepare_step(case):
    cd = os.path.join(case, "system", "controlDict")
    set_entry(cd, "endTime", "2")
    set_entry(cd, "writeInterval", "0.5")
    return ["blockMesh", "rhoCentralFoam"]


def prepare_biconic(case):
    gunzip_all(case)
    return ["blockMesh", "datToFoam grid256.dat",
            "cat constant/pointsHeader constant/points.tmp > constant/polyMesh/points",
            "collapseEdges -overwrite",
            "mv constant/polyMesh/boundary constant/polyMesh/boundary.bak && "
            "sed -f constant/wedgeScr constant/polyMesh/boundary.bak > constant/polyMesh/boundary && "
            "rm constant/polyMesh/boundary.bak"]


def prepare_jet(case):
    gunzip_all(case)
    shutil.rmtree(os.path.join(case, "0.orig"), ignore_errors=True)
    return ["blockMesh"]


CASES = {
    "wedge15Ma5": prepare_wedge,
    "forwardStep": prepare_step,
    "biconic25-55Run35": prepare_biconic,
    "LadenburgJet60psi": prepare_jet,
}


# what the tests read
DEFAULT_CASES = ["wedge15Ma5", "forwardStep", "biconic25-55Run35", "LadenburgJet60psi"]


def key_of(name):
    h = hashlib.sha256((VERSION + name).encode())
    src = os.path.join(TUTORIALS, name)
    for root, dirs, files in sorted(os.walk(src)):
        dirs.sort()
        for f in sorted(files):
            p = os.path.join(root, f)
            h.update(os.path.relpath(p, src).encode())
            h.update(open(p, "rb").read())
    h.update(open(os.path.abspath(__file__), "rb").read())
    return h.hexdigest()


def available():
    """'' where OpenFOAM and its tutorials are here, else why not."""
    if not os.path.exists(BASHRC):
        return "OpenFOAM is not installed (%s missing: apt-get install openfoam openfoam-examples)" % BASHRC
    if not os.path.isdir(TUTORIALS):
        return "the OpenFOAM tutorials are not installed (%s missing: apt-get install openfoam-examples)" % TUTORIALS
    return ""


def run_case(out, name):
    case = os.path.join(out, name)
    key = key_of(name)
    stamp = os.path.join(case, ".schlieren_key")
    if os.path.exists(stamp) and open(stamp).read().strip() == key:
        print("%s: cached in %s" % (name, case))
        return True
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(os.path.join(TUTORIALS, name), case)
    os.chmod(case, 0o755)
    for root, dirs, files in os.walk(case):
        for d in dirs:
            os.chmod(os.path.join(root, d), 0o755)
        for f in files:
            os.chmod(os.path.join(root, f), 0o644)
    steps = CASES[name](case)
    start = time.time()
    for i, step in enumerate(steps):
        log = os.path.join(case, "log.%d.%s" % (i, step.split()[0]))
        cmd = "source '%s' >/dev/null 2>&1; %s" % (BASHRC, step)
        with open(log, "w") as f:
            rc = subprocess.call(["bash", "-c", cmd], cwd=case, stdout=f, stderr=subprocess.STDOUT)
        if rc != 0:
            print("%s: '%s' failed (status %d); see %s" % (name, step, rc, log))
            return False
    open(os.path.join(case, "case.foam"), "w").close()
    open(stamp, "w").write(key + "\n")
    print("%s: prepared in %s (%.1f s)" % (name, case, time.time() - start))
    return True


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("cases", nargs="*", default=DEFAULT_CASES)
    a = ap.parse_args()
    why = available()
    if why:
        print("NOTE: %s; the OpenFOAM tests will be skipped." % why)
        return 0
    os.makedirs(a.out, exist_ok=True)
    ok = all([run_case(a.out, n) for n in a.cases])
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
