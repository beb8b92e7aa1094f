#!/usr/bin/env bash
# Install what is missing, build, and run every test (C++ engine tests, pvpython/pvbatch tests,
# MPI, GUI and image baselines under Xvfb).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
schlieren_install "${SCHLIEREN_BUILD_PACKAGES[@]}" "${SCHLIEREN_TEST_PACKAGES[@]}"
schlieren_build
# here a missing OpenCL device is a failure, not a skip
export SCHLIEREN_REQUIRE_OPENCL=1
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$SCHLIEREN_BUILD/pocl-cache}"
cd "$SCHLIEREN_BUILD"
ctest --output-on-failure -j 1 "$@"
