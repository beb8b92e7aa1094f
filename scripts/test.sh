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
# two tests at a time on 2 cores: most of a test's time is one core's (pvpython starting, PoCL
# compiling a kernel, an OpenFOAM solver), so a pair fills both. Alone: the GUI tests and the tests
# that time an abort (RUN_SERIAL), MPI jobs, the fuzz and the wheel's build (PROCESSORS 2).
# SCHLIEREN_TEST_JOBS=1 runs one at a time.
ctest --output-on-failure -j "${SCHLIEREN_TEST_JOBS:-2}" "$@"
