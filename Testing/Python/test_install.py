# SPDX-License-Identifier: BSD-3-Clause
"""`cmake --install` into a fresh prefix gives a plugin that ParaView knows by name.

Run with Debian's Python (ctest does):

    /usr/bin/python3 test_install.py --cmake cmake --build <build> --prefix <empty folder> \\
        --libdir lib --python-dir lib/python3/dist-packages --pvpython pvpython

Checks:
  1. `cmake --install <build> --prefix <prefix>` succeeds and installs exactly what a user needs:
     the plugin folder <libdir>/paraview-X.Y/plugins/Schlieren/ (Schlieren.so and the module
     library libSchlierenFilters.so), the plugin list <libdir>/paraview-X.Y/plugins/Schlieren.plugins
     the `schlieren_vtk` Python package (the compiled classes) and the `schlieren` one (the Python
     front end, its engine library beside it), the engine library, its C header and pkg-config
     file; no other header, no static archive, no CMake package file;
  2. the plugin list is ParaView's <Plugins> XML and names "Schlieren";
  3. pvpython started with only that list known (PV_PLUGIN_CONFIG_FILE; no PV_PLUGIN_PATH, no
     build tree on PYTHONPATH) lists "Schlieren" at the installed path and loads it BY NAME
     (LoadDistributedPlugin), and its SchlierenImage gives the weak Gaussian sphere's knife-edge
     image (install_check.py);
  4. Debian's /usr/bin/python3 imports the installed `schlieren_vtk` and `schlieren` packages (one
     session, neither shadowing the other) with the prefix's package
     folder on PYTHONPATH and nothing loaded before (the extension finds libSchlierenFilters.so in
     the plugin folder by itself), and runs a vtkRefractiveScene;
  5. Testing/Cxx/TestCApi.c builds with `cc` and pkg-config's flags against the installed engine and
     passes.
Exit status 0 on success; each failure says what is wrong.
"""
import argparse
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

here = os.path.dirname(os.path.abspath(__file__))
parser = argparse.ArgumentParser()
parser.add_argument("--cmake", required=True)
parser.add_argument("--build", required=True, help="the configured and built build folder")
parser.add_argument("--prefix", required=True, help="an install prefix (emptied first)")
parser.add_argument("--libdir", required=True, help="CMAKE_INSTALL_LIBDIR, relative to the prefix")
parser.add_argument("--python-dir", required=True, help="SCHLIEREN_PYTHON_DESTINATION, relative to the prefix")
parser.add_argument("--paraview-subdir", required=True,
                    help="paraview-<major>.<minor> of the ParaView built against (CMake's SCHLIEREN_PARAVIEW_SUBDIR)")
parser.add_argument("--pvpython", required=True)
parser.add_argument("--python", default="/usr/bin/python3", help="Debian's Python for the VTK import check")
args = parser.parse_args()

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    sys.stdout.flush()
    if not condition:
        failures.append(message)
    return condition


def finish():
    if failures:
        print("FAIL: %d check(s) failed: %s" % (len(failures), "; ".join(failures)))
        sys.exit(1)
    print("PASS")
    sys.exit(0)


def clean_env(**extra):
    """The environment of a user who has only the installed prefix: nothing of the build tree."""
    env = dict(os.environ)
    for name in ("SCHLIEREN_PLUGIN", "PV_PLUGIN_PATH", "PV_PLUGIN_CONFIG_FILE", "PYTHONPATH"):
        env.pop(name, None)
    env.update(extra)
    return env


prefix = os.path.abspath(args.prefix)
if os.path.exists(prefix):
    shutil.rmtree(prefix)

# -- 1. the install and what it puts into the prefix
install_env = dict(os.environ)
install_env.pop("DESTDIR", None)  # the files must land in the prefix itself
run = subprocess.run([args.cmake, "--install", args.build, "--prefix", prefix], stdout=subprocess.PIPE,
                     stderr=subprocess.STDOUT, universal_newlines=True, timeout=300, env=install_env)
if not check(run.returncode == 0, "cmake --install %s --prefix %s: exit status %d" % (args.build, prefix, run.returncode)):
    print(run.stdout)
    finish()

installed = set()
for root, dirs, files in os.walk(prefix):
    for name in files + [d for d in dirs if os.path.islink(os.path.join(root, d))]:
        installed.add(os.path.relpath(os.path.join(root, name), prefix))
print("installed files:\n  " + "\n  ".join(sorted(installed)))
plugins = os.path.join(args.libdir, args.paraview_subdir, "plugins")
expected = {
    os.path.join(plugins, "Schlieren", "Schlieren.so"),
    os.path.join(plugins, "Schlieren", "libSchlierenFilters.so"),
    # `import schlieren_view` after LoadPlugin: the plugin puts its own folder on sys.path
    os.path.join(plugins, "Schlieren", "schlieren_view.py"),
    os.path.join(plugins, "Schlieren.plugins"),
    os.path.join(args.python_dir, "schlieren_vtk", "__init__.py"),
    os.path.join(args.python_dir, "schlieren_vtk", "SchlierenFilters.so"),
    # the Python front end, its engine library beside it
    os.path.join(args.python_dir, "schlieren", "libschlieren_engine.so.1"),
    # the engine for C and other front ends: library, header, pkg-config file
    os.path.join(args.libdir, "libschlieren_engine.so"),
    os.path.join(args.libdir, "libschlieren_engine.so.1"),
    os.path.join("include", "schlieren", "schlieren_c.h"),
    os.path.join(args.libdir, "pkgconfig", "schlieren_engine.pc"),
}
expected |= {os.path.join(args.python_dir, "schlieren", f) for f in
             os.listdir(os.path.join(here, "..", "..", "Python", "schlieren")) if f.endswith(".py")}
leaked = sorted(f for f in installed if f.endswith((".h", ".hxx", ".txx", ".a", ".cmake"))
                and not f.endswith("schlieren_c.h"))
check(not leaked, "no header but the C interface's, no static archive or CMake file installed "
      "(found: %s)" % (", ".join(leaked) or "none"))
check(not (expected - installed), "the plugin, its module library, the plugin list and the Python package are "
      "installed (missing: %s)" % (", ".join(sorted(expected - installed)) or "none"))
check(not (installed - expected), "nothing else is installed (extra: %s; a new installed file must be one a user "
      "needs: add it to this test's list)" % (", ".join(sorted(installed - expected)) or "none"))

# -- 2. the plugin list
plugins_file = os.path.join(prefix, plugins, "Schlieren.plugins")
try:
    root = ET.parse(plugins_file).getroot()
    names = [p.get("name") for p in root.findall("Plugin")]
    check(root.tag == "Plugins" and names == ["Schlieren"],
          "%s is a <Plugins> list naming Schlieren (root %s, names %s)" % (plugins_file, root.tag, names))
except (OSError, ET.ParseError) as e:
    check(False, "%s could not be read as XML: %s" % (plugins_file, e))
if failures:
    finish()

# -- 3. pvpython with only the installed plugin list known loads the plugin by name
python_dir = os.path.join(prefix, args.python_dir)
env = clean_env(PV_PLUGIN_CONFIG_FILE=plugins_file, PYTHONPATH=python_dir)
run = subprocess.run([args.pvpython, os.path.join(here, "install_check.py"),
                      "--prefix", prefix, "--plugin-dir", os.path.join(prefix, plugins, "Schlieren")],
                     env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                     timeout=300, cwd=prefix)
print(run.stdout.rstrip())
check(run.returncode == 0, "pvpython with PV_PLUGIN_CONFIG_FILE=%s: loaded Schlieren by name and traced "
      "(exit status %d)" % (plugins_file, run.returncode))

# -- 4. the VTK Python package of the prefix, in Debian's Python, with nothing loaded before; the
# Python front end `schlieren` imports in the same session, from its own folder, and gives the
# compiled classes under their old name too
code = ("import schlieren_vtk, sys\n"
        "from schlieren_vtk import vtkRefractiveScene\n"
        "import schlieren\n"
        "from schlieren import vtkRefractiveScene as old_name\n"
        "assert old_name is vtkRefractiveScene, 'schlieren.vtkRefractiveScene'\n"
        "assert schlieren.engine._lib._name.startswith(schlieren.__path__[0]), "
        "schlieren.engine._lib._name\n"
        "f = schlieren.RefractiveScene(Dimensions=[8, 8, 8]); f.Update()\n"
        "assert f.GetOutput().GetDimensions() == (8, 8, 8)\n"
        "s = vtkRefractiveScene()\n"
        "s.SetDimensions(16, 16, 16)\n"
        "s.Update()\n"
        "print(schlieren_vtk.__file__, s.GetOutput().GetDimensions())\n")
run = subprocess.run([args.python, "-c", code], env=clean_env(PYTHONPATH=python_dir), stdout=subprocess.PIPE,
                     stderr=subprocess.STDOUT, universal_newlines=True, timeout=120, cwd=prefix)
print(run.stdout.rstrip())
words = run.stdout.split()
check(run.returncode == 0 and words and words[0].startswith(python_dir + os.sep) and "(16, 16, 16)" in run.stdout,
      "%s imports the installed schlieren_vtk and schlieren packages from %s in one session (schlieren's "
      "engine from its folder, schlieren.vtkRefractiveScene the compiled class) and runs a 16^3 "
      "vtkRefractiveScene (exit status %d)" % (args.python, python_dir, run.returncode))

# -- 5. a C program against the installed engine: Testing/Cxx/TestCApi.c built with pkg-config's
# flags only (nothing of the build tree), run with no OpenCL loader (the CPU)
pc_dir = os.path.join(prefix, args.libdir, "pkgconfig")
flags = subprocess.run(["pkg-config", "--cflags", "--libs", "schlieren_engine"], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True,
                       env=clean_env(PKG_CONFIG_PATH=pc_dir))
exe = os.path.join(prefix, "TestCApi")
if check(flags.returncode == 0 and os.path.join(prefix, "include", "schlieren") in
         [os.path.normpath(f[2:]) for f in flags.stdout.split() if f.startswith("-I")],
         "pkg-config finds schlieren_engine in %s: %s" % (pc_dir, flags.stdout.strip())):
    libdir = os.path.join(prefix, args.libdir)
    cc = subprocess.run(["cc", "-std=c99", "-o", exe, os.path.join(here, "..", "Cxx", "TestCApi.c")]
                        + flags.stdout.split() + ["-Wl,-rpath," + libdir, "-lm"],
                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    print(cc.stdout.rstrip())
    if check(cc.returncode == 0, "cc builds TestCApi.c against the installed header and library"):
        t = subprocess.run([exe], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                           timeout=120, env=clean_env(SCHLIEREN_OPENCL_LIBRARY="/nonexistent/libOpenCL.so.1"))
        print(t.stdout.rstrip()[-2000:])
        ldd = subprocess.run(["ldd", exe], stdout=subprocess.PIPE, universal_newlines=True).stdout
        check(t.returncode == 0 and os.path.join(libdir, "libschlieren_engine.so.1") in ldd,
              "the installed TestCApi passes with the installed library (exit status %d)" % t.returncode)
    os.remove(exe) if os.path.exists(exe) else None
finish()
