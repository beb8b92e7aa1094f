#!/bin/bash
# SPDX-License-Identifier: BSD-3-Clause
# The engine for Windows x86_64, cross-built here and run under wine (docs/BUILDING.md "Windows"):
#   1. schlieren_engine.dll, TestCApi.exe and SchlierenTraceHash.exe with Debian's mingw-w64
#      (cmake/MingwToolchain.cmake), in build-windows/;
#   2. the same engine for Linux (engine only) in build-linux-engine/, unless given one;
#   3. under wine64: TestCApi.exe with no OpenCL (the CPU backend and its warning), and with wine's
#      OpenCL.dll (which hands the calls to this machine's OpenCL, PoCL here);
#   4. SchlierenTraceHash (the Gaussian sphere: knife, colour, shadowgraph, fringes, disc and
#      Gaussian sources, BOS) on Windows and on Linux: the hashes of the images must be equal;
#   5. the Python plugin's folder for Windows: SchlierenPython.py with libschlieren_engine.dll
#      beside it, in build-windows/schlieren-python-plugin/.
#
#     scripts/windows-engine.sh [--install] [--linux-build DIR]
#
# --install apt-gets mingw-w64, wine64, opencl-headers, cmake and ninja first. Exits non-zero on
# any failure. About 3-5 minutes on 2 cores (the two engine builds); not part of .ci/run.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
linux_build=""
while [ $# -gt 0 ]; do
  case "$1" in
    --install) apt-get -o DPkg::Lock::Timeout=900 install -y --no-install-recommends \
                 mingw-w64 wine64 opencl-headers cmake ninja-build >/dev/null ;;
    --linux-build) linux_build="$2"; shift ;;
    *) echo "usage: $0 [--install] [--linux-build DIR]" >&2; exit 2 ;;
  esac
  shift
done
for tool in x86_64-w64-mingw32-g++-posix cmake ninja; do
  command -v "$tool" >/dev/null || { echo "windows-engine: $tool is missing (run with --install)" >&2; exit 1; }
done
wine=$(command -v wine64 || true)
[ -n "$wine" ] || wine=/usr/lib/wine/wine64
[ -x "$wine" ] || { echo "windows-engine: wine64 is missing (run with --install)" >&2; exit 1; }
[ -f /usr/include/CL/cl.h ] || { echo "windows-engine: the OpenCL headers are missing (opencl-headers)" >&2; exit 1; }

win="$here/build-windows"
cmake -S "$here" -B "$win" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_TOOLCHAIN_FILE="$here/cmake/MingwToolchain.cmake" -DSCHLIEREN_ENGINE_ONLY=ON \
  -DSCHLIEREN_OPENCL_INCLUDE_DIR=/usr/include >/dev/null
cmake --build "$win" --target schlieren_engine TestCApi SchlierenTraceHash
if [ -z "$linux_build" ]; then
  linux_build="$here/build-linux-engine"
  cmake -S "$here" -B "$linux_build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSCHLIEREN_ENGINE_ONLY=ON >/dev/null
fi
cmake --build "$linux_build" --target SchlierenTraceHash

export WINEPREFIX="$win/wine-prefix" WINEDEBUG=-all
dll="$win/OpenCL/libschlieren_engine.dll"
echo "== $(basename "$dll") imports: $(x86_64-w64-mingw32-objdump -p "$dll" | sed -n 's/.*DLL Name: //p' | tr '\n' ' ')"
fail=0
echo "== TestCApi.exe under $($wine --version), no OpenCL"
(cd "$win/OpenCL" && SCHLIEREN_OPENCL_LIBRARY=no-such-OpenCL.dll "$wine" TestCApi.exe) | tr -d '\r' | tail -n 3 || fail=1
echo "== TestCApi.exe under wine, wine's OpenCL.dll"
(cd "$win/OpenCL" && "$wine" TestCApi.exe) | tr -d '\r' | tail -n 1 || fail=1
for backend in CPU OpenCL; do
  (cd "$win/OpenCL" && "$wine" SchlierenTraceHash.exe "$backend") | tr -d '\r' > "$win/hash-windows-$backend.txt" || true
  (cd "$linux_build/OpenCL" && ./SchlierenTraceHash "$backend") > "$win/hash-linux-$backend.txt" || true
  if [ "$backend" = OpenCL ] && grep -q 'OpenCL' "$win/hash-linux-$backend.txt"; then
    echo "== $backend: no OpenCL device on this machine; not compared"; continue
  fi
  if diff "$win/hash-linux-$backend.txt" "$win/hash-windows-$backend.txt" >/dev/null; then
    echo "== $backend: the Gaussian sphere's $(wc -l < "$win/hash-linux-$backend.txt") image arrays are equal, bit for bit, on Windows (wine) and Linux"
  else
    echo "== $backend: Windows (wine) and Linux differ:"; diff "$win/hash-linux-$backend.txt" "$win/hash-windows-$backend.txt" || true
    fail=1
  fi
done

plugin="$win/schlieren-python-plugin"
mkdir -p "$plugin"
python3=/usr/bin/python3
[ -x "$python3" ] || python3=python3
"$python3" "$here/Plugin/make_python_plugin.py" --xml "$here/Plugin/Schlieren.xml" \
  --package "$here/Python/schlieren" --output "$plugin/SchlierenPython.py"
cp "$dll" "$plugin/"
echo "== the Python plugin for Windows: $plugin ($(ls "$plugin" | tr '\n' ' '))"
exit $fail
