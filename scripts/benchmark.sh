#!/usr/bin/env bash
# The speed benchmark (not a test): photons/s, samples/s and ms per pass of the OpenCL and CPU
# backends side by side (and of a plain NumPy implementation of the same Euler tracer), each with
# the deflection error it was bought at, on three cases: the 256^3 Gaussian sphere (closed form),
# a 480 x 720 x 100 helium plume and the NASA blunt fin resampled to 256^3 (both against RK4 at
# 1/8 voxel). Ratios are only meaningful within one run. Extra arguments go to SchlierenBenchmark
# (--cases gaussian,plume,bluntfin --size N --film N --passes N --step voxels
#  --backends OpenCL,CPU --rays-per-item N --rows euler,octree,auto,onethread). The
# reconstructions' case, the weak Gaussian on 64^3 to 512^3 under Auto at a fixed tolerance (512^3
# needs about 5 GB of memory): --cases grids --grids 64,128,256,512 --tolerance 1e-3 --backends OpenCL
# Auto's step (issue 50: Auto at its default tolerance and at 3e-8 rad beside the swept cheapest
# setting and the line of sight at the feature's width, then the scaling table):
# --cases autostep --grids 64,128,256,512 --backends OpenCL
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
schlieren_install "${SCHLIEREN_BUILD_PACKAGES[@]}"
schlieren_build
size=256
film=512
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  case "${args[$i]}" in
    --size) size="${args[$((i + 1))]}" ;;
    --film) film="${args[$((i + 1))]}" ;;
  esac
done
# the blunt fin, resampled once by the plugin's RefractiveIndex (about a minute) and kept
mkdir -p "$SCHLIEREN_BUILD/benchmark"
pvpython "$SCHLIEREN_ROOT/Testing/Benchmarks/bluntfin_volume.py" --plugin "$(schlieren_plugin)" \
  --output "$SCHLIEREN_BUILD/benchmark" --size 256 2>&1 | grep -v "^vtk version" || true
"$SCHLIEREN_BUILD/bin/SchlierenBenchmark" --size "$size" --film "$film" \
  --raw "$SCHLIEREN_BUILD/benchmark/bluntfin_256" "$@"
echo "NumPy, the same Euler tracer vectorised over the rays of 32 film rows of the Gaussian case"
echo "(its rate is per sample; compare with the Euler rows of that case):"
/usr/bin/python3 "$SCHLIEREN_ROOT/Testing/Benchmarks/numpy_tracer.py" --size "$size" --film "$film" --rows 32
