# Shared by scripts/demo.sh and scripts/test.sh: install what is missing, configure and build.
# Usage: source scripts/common.sh; schlieren_install <packages...>; schlieren_build
set -euo pipefail

SCHLIEREN_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SCHLIEREN_BUILD="${SCHLIEREN_BUILD:-$SCHLIEREN_ROOT/build}"

# Debian 12 packages: OpenCL (PoCL on the CPU), ParaView 5.11 with its development files and Python,
# the -dev packages ParaView's CMake files ask for, and the compiler toolchain.
SCHLIEREN_BUILD_PACKAGES=(
  build-essential cmake ninja-build
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  paraview paraview-dev python3-paraview
  openmpi-bin libopenmpi-dev
  libdouble-conversion-dev liblz4-dev libutfcpp-dev
  qtbase5-dev qttools5-dev qttools5-dev-tools libqt5svg5-dev qhelpgenerator-qt5 qtxmlpatterns5-dev-tools
  libglew-dev libxml2-dev libhdf5-dev libboost-dev libnetcdf-dev libtiff-dev
  libavformat-dev libavcodec-dev libavutil-dev libswscale-dev
)
# Only the tests need these: an X server for rendering tests; a window manager, xdotool (real mouse
# and key events) and ImageMagick (screenshots) for the GUI tests.
# python3-numpy: the GUI tests' checks run under Debian's Python (it also comes with paraview)
SCHLIEREN_TEST_PACKAGES=(xvfb openbox xdotool x11-utils imagemagick python3-numpy openfoam openfoam-examples
  python3-venv pkg-config)  # python3-venv: the python.frontend tests make venvs with PyPI's vtk;
# pkg-config: python.install builds Testing/Cxx/TestCApi.c against the installed engine

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

schlieren_build() {
  echo "== configuring and building in $SCHLIEREN_BUILD"
  mkdir -p "$SCHLIEREN_BUILD"
  cmake -S "$SCHLIEREN_ROOT" -B "$SCHLIEREN_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release > "$SCHLIEREN_BUILD/configure.log" 2>&1 ||
    { cat "$SCHLIEREN_BUILD/configure.log" >&2; exit 1; }
  cmake --build "$SCHLIEREN_BUILD" -j "$(nproc)"
}

# Where the built plugin is (for pvpython's LoadPlugin).
schlieren_plugin() {
  echo "$SCHLIEREN_BUILD/lib/paraview-5.11/plugins/Schlieren/Schlieren.so"
}
