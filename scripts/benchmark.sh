#!/usr/bin/env bash
# The speed benchmark (not a test): photons/s, samples/s and ms per pass of the OpenCL and CPU
# backends and of a plain NumPy implementation of the same Euler tracer, side by side, on a 256^3
# Gaussian sphere and a 512^2 film, each with the deflection error it was bought at. Ratios are
# only meaningful within one run. Extra arguments go to SchlierenBenchmark (--size N --film N
# --passes N --step voxels --backends CPU,OpenCL --rays-per-item N).
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
"$SCHLIEREN_BUILD/bin/SchlierenBenchmark" --size "$size" --film "$film" "$@"
echo
echo "NumPy, the same tracer vectorised over the rays of 32 film rows (its rate is per sample):"
/usr/bin/python3 "$SCHLIEREN_ROOT/Testing/Benchmarks/numpy_tracer.py" --size "$size" --film "$film" --rows 32
