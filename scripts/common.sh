# Shared by scripts/demo.sh and scripts/test.sh: install what is missing, configure and build.
# Usage: source scripts/common.sh; schlieren_install <packages...>; schlieren_build
set -euo pipefail

SCHLIEREN_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SCHLIEREN_BUILD="${SCHLIEREN_BUILD:-$SCHLIEREN_ROOT/build}"

# The Debian release, from /etc/os-release: bookworm (Debian 12, ParaView 5.11, Qt 5), trixie
# (Debian 13, ParaView 5.13, Qt 6) or sid (unstable, ParaView 6.1 on an external VTK 9.6, Qt 6).
# Sid has no VERSION_ID and names the next release in VERSION_CODENAME; SCHLIEREN_DEBIAN overrides.
schlieren_debian_release() {
  if [ -n "${SCHLIEREN_DEBIAN:-}" ]; then
    echo "$SCHLIEREN_DEBIAN"
    return
  fi
  local codename="" version_id=""
  if [ -r /etc/os-release ]; then
    codename="$(. /etc/os-release && echo "${VERSION_CODENAME:-}")"
    version_id="$(. /etc/os-release && echo "${VERSION_ID:-}")"
  fi
  if [ -z "$version_id" ] && grep -q sid /etc/debian_version 2>/dev/null; then
    echo sid
  else
    echo "${codename:-bookworm}"
  fi
}
SCHLIEREN_DEBIAN_RELEASE="$(schlieren_debian_release)"

# Packages: OpenCL (PoCL on the CPU), ParaView with its development files and Python, the -dev
# packages ParaView's CMake files ask for, and the compiler toolchain. Debian 12's names first.
SCHLIEREN_BUILD_PACKAGES=(
  build-essential cmake ninja-build
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  paraview paraview-dev python3-paraview python3-dev
  openmpi-bin libopenmpi-dev python3-mpi4py
  libdouble-conversion-dev liblz4-dev libutfcpp-dev
  libglew-dev libxml2-dev libhdf5-dev libboost-dev libnetcdf-dev libtiff-dev
  libavformat-dev libavcodec-dev libavutil-dev libswscale-dev
)
case "$SCHLIEREN_DEBIAN_RELEASE" in
  bookworm)
    SCHLIEREN_BUILD_PACKAGES+=(qtbase5-dev qttools5-dev qttools5-dev-tools libqt5svg5-dev
      qhelpgenerator-qt5 qtxmlpatterns5-dev-tools) ;;
  trixie)  # ParaView 5.13 is built with Qt 6; its CMake files also look for FreeType; Qt 5's
    # xmlpatterns (the tool only) makes the plugin's help pages there (Plugin/SchlierenHelp.cmake)
    SCHLIEREN_BUILD_PACKAGES+=(qt6-base-dev qt6-tools-dev qt6-tools-dev-tools qt6-svg-dev qt6-5compat-dev
      qt6-documentation-tools libfreetype-dev xsltproc qtxmlpatterns5-dev-tools) ;;
  *)  # sid: ParaView 6.1 on Debian's own VTK 9.6 (libvtk9-dev) with Qt 6
    SCHLIEREN_BUILD_PACKAGES+=(qt6-base-dev qt6-tools-dev qt6-tools-dev-tools qt6-svg-dev qt6-5compat-dev
      qt6-documentation-tools libfreetype-dev libvtk9-dev xsltproc) ;;
esac
# Only the tests need these: an X server for rendering tests; a window manager, xdotool (real mouse
# and key events) and ImageMagick (screenshots) for the GUI tests.
# python3-numpy: the GUI tests' checks run under Debian's Python (it also comes with paraview)
SCHLIEREN_TEST_PACKAGES=(xvfb openbox xdotool x11-utils imagemagick python3-numpy openfoam openfoam-examples
  python3-venv pkg-config python3-scipy python3-pil)  # python3-venv: the python.frontend tests make venvs with PyPI's vtk;
# pkg-config: python.install builds Testing/Cxx/TestCApi.c against the installed engine;
# python3-scipy, python3-pil: python.bos_openpiv runs OpenPIV (from PyPI, without its dependencies)
# over Debian's SciPy and reads the pair with Pillow

schlieren_install() {
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  if [ "$(id -u)" -ne 0 ]; then
    echo "Missing packages: ${missing[*]}" >&2
    echo "Run as root (or with sudo) once:" >&2
    echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
  echo "== installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${missing[@]}" > /tmp/schlieren-apt.log 2>&1 ||
    { tail -n 40 /tmp/schlieren-apt.log >&2; exit 1; }
}

# Debian's paraview-dev bug (Debian 13 and sid; not Debian 12): its CMake target files name each
# Python extension module without the suffix it is installed with
# (".../vtkmodules/vtkCommonCore.so" for vtkCommonCore.cpython-313-x86_64-linux-gnu.so), and
# find_package(ParaView) stops at "The imported target ... references the file ... but this file
# does not exist". Work-around: for every such file that is missing while the suffixed one exists,
# a symbolic link from the name CMake wants to the installed module (180 in Debian 13, 45 in sid;
# none on Debian 12, where nothing is missing). Nothing is made where the bug is not.
schlieren_paraview_dev_links() {
  local dirs=() missing=() f real
  for d in /usr/lib/*/cmake/paraview-* /usr/lib/*/cmake/vtk /usr/lib/*/cmake/vtk-*; do
    [ -d "$d" ] && dirs+=("$d")
  done
  [ ${#dirs[@]} -eq 0 ] && return 0
  while IFS= read -r f; do
    [ -e "$f" ] && continue
    real="$(ls "${f%.so}".cpython-*.so 2>/dev/null | head -n 1 || true)"
    [ -n "$real" ] && missing+=("$f=$real")
  done < <(grep -rhoE '"(\$\{_IMPORT_PREFIX\}|/usr)/lib/python3[^"]*\.so"' "${dirs[@]}" --include='*-targets-*.cmake' 2>/dev/null |
           tr -d '"' | sed 's|^${_IMPORT_PREFIX}|/usr|' | sort -u)  # Debian's prefix is /usr
  [ ${#missing[@]} -eq 0 ] && return 0
  if [ "$(id -u)" -ne 0 ]; then
    echo "Debian's paraview-dev names ${#missing[@]} Python modules without their suffix; run as root once" >&2
    echo "(scripts/common.sh, schlieren_paraview_dev_links) to add the links CMake needs." >&2
    exit 1
  fi
  echo "== paraview-dev suffix work-around: ${#missing[@]} links (docs/BUILDING.md)"
  for f in "${missing[@]}"; do
    ln -s "$(basename "${f#*=}")" "${f%%=*}"
  done
}

schlieren_build() {
  schlieren_paraview_dev_links
  echo "== configuring and building in $SCHLIEREN_BUILD"
  mkdir -p "$SCHLIEREN_BUILD"
  cmake -S "$SCHLIEREN_ROOT" -B "$SCHLIEREN_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release > "$SCHLIEREN_BUILD/configure.log" 2>&1 ||
    { cat "$SCHLIEREN_BUILD/configure.log" >&2; exit 1; }
  cmake --build "$SCHLIEREN_BUILD" -j "$(nproc)"
}

# ParaView's <major>.<minor> as the build saw it (the plugin goes to lib/paraview-<major>.<minor>/)
schlieren_paraview_version() {
  local v
  v="$(sed -n 's/^ParaView_DIR:PATH=.*paraview-\([0-9]*\.[0-9]*\)$/\1/p' "$SCHLIEREN_BUILD/CMakeCache.txt" 2>/dev/null || true)"
  if [ -z "$v" ]; then  # no build yet: ask pvpython
    v="$(pvpython --version 2>/dev/null | sed -n 's/.*paraview version \([0-9]*\.[0-9]*\).*/\1/p')"
  fi
  echo "${v:-unknown}"
}

# Where the built plugin is (for pvpython's LoadPlugin).
schlieren_plugin() {
  echo "$SCHLIEREN_BUILD/lib/paraview-$(schlieren_paraview_version)/plugins/Schlieren/Schlieren.so"
}
