# SPDX-License-Identifier: BSD-3-Clause
"""Runs a script of the Python front end in a venv with PyPI's vtk and NumPy, made once and kept.

    python3 frontend_venv.py --venv DIR --requirements "vtk==9.7.2 numpy" -- script.py args...

The venv is made from this interpreter (Debian's /usr/bin/python3 in CI) in DIR, the wheels come
through a pip cache beside it (DIR/../pip-cache), and a venv whose requirements were installed
before is used as it is: a CI run downloads the wheels once per build tree. Where PyPI cannot be
reached the script exits 77 (ctest: skipped) saying so. The script runs with the venv's python,
Python/ on PYTHONPATH and SCHLIEREN_ENGINE_LIBRARY from the environment."""
import argparse
import os
import subprocess
import sys
import venv

ap = argparse.ArgumentParser()
ap.add_argument("--venv", required=True)
ap.add_argument("--requirements", required=True)
ap.add_argument("--pythonpath", default="")
# a venv over this interpreter's packages (Debian's NumPy and SciPy) with only the requirements
# themselves from PyPI: a small download where those are all a script needs of the dependencies
ap.add_argument("--system-site-packages", action="store_true")
ap.add_argument("--no-deps", action="store_true")
# an optional package (OpenPIV): any failure to install it skips (77) the script, saying why
ap.add_argument("--skip-on-install-failure", action="store_true")
ap.add_argument("script", nargs=argparse.REMAINDER)
args = ap.parse_args()
script = args.script[1:] if args.script[:1] == ["--"] else args.script

python = os.path.join(args.venv, "bin", "python")
marker = os.path.join(args.venv, "requirements.txt")
wanted = " ".join(args.requirements.split())
flags = (["--no-deps"] if args.no_deps else [])
made_as = wanted + (" (system site packages)" if args.system_site_packages else "") + \
    (" (no deps)" if args.no_deps else "")
have = open(marker).read().strip() if os.path.exists(marker) else None
if have != made_as:
    print("frontend_venv: making %s with %s" % (args.venv, made_as))
    venv.EnvBuilder(with_pip=True, clear=True,
                    system_site_packages=args.system_site_packages).create(args.venv)
    env = dict(os.environ, PIP_CACHE_DIR=os.path.join(os.path.dirname(args.venv), "pip-cache"),
               PIP_DISABLE_PIP_VERSION_CHECK="1")
    p = subprocess.run([python, "-m", "pip", "install", "--only-binary", ":all:", "-q"] + flags
                       + wanted.split(), env=env, capture_output=True, text=True, timeout=900)
    if p.returncode != 0:
        text = p.stdout + p.stderr
        print(text[-3000:])
        offline = any(s in text for s in ("Name or service not known", "Temporary failure in name",
                                          "No matching distribution", "Network is unreachable",
                                          "Could not fetch URL", "Failed to establish"))
        if args.skip_on_install_failure:
            print("frontend_venv: SKIPPED: pip could not install %s (see above: PyPI out of "
                  "reach, or no wheel for this Python): %s is not run."
                  % (wanted, os.path.basename(script[0]) if script else "the script"))
            sys.exit(77)
        if offline:
            print("frontend_venv: SKIPPED: PyPI could not be reached to install %s (see above); "
                  "the Python front end is not tested in this run." % wanted)
            sys.exit(77)
        sys.exit("frontend_venv: pip could not install %s" % wanted)
    with open(marker, "w") as f:
        f.write(made_as + "\n")
env = dict(os.environ)
# only the package: not the plugin's compiled `schlieren` package the other tests put there
env["PYTHONPATH"] = args.pythonpath
sys.exit(subprocess.call([python] + script, env=env))
