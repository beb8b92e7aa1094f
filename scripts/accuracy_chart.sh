#!/usr/bin/env bash
# The speed-versus-accuracy chart: builds, traces every method x step x octree tolerance
# on four known-answer scenes, prints the table and the Pareto fronts, and draws
# docs/accuracy_chart.png. About 30 s on 2 cores. Extra arguments go to SchlierenAccuracyChart
# (--size N --film N --backend CPU|OpenCL).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
schlieren_install "${SCHLIEREN_BUILD_PACKAGES[@]}"
schlieren_build
mkdir -p "$SCHLIEREN_ROOT/out"
"$SCHLIEREN_BUILD/bin/SchlierenAccuracyChart" --csv "$SCHLIEREN_ROOT/out/accuracy_chart.csv" "$@" |
  tee "$SCHLIEREN_ROOT/out/accuracy_chart.md"
/usr/bin/python3 "$SCHLIEREN_ROOT/Testing/Benchmarks/accuracy_chart.py" \
  "$SCHLIEREN_ROOT/out/accuracy_chart.csv" "$SCHLIEREN_ROOT/docs/accuracy_chart.png"
