#!/usr/bin/env bash
# The speed benchmark (not a test): photons/s, samples/s and ms per pass of the OpenCL and CPU
# backends side by side on a 256^3 Gaussian sphere and a 512^2 film, with the deflection error
# each was bought at. Extra arguments go to SchlierenBenchmark (--size N --film N --passes N
# --step voxels --backends CPU,OpenCL).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
schlieren_install "${SCHLIEREN_BUILD_PACKAGES[@]}"
schlieren_build
"$SCHLIEREN_BUILD/bin/SchlierenBenchmark" "$@"
