#!/usr/bin/env bash
# The main job: install what is missing, build, and write a knife-edge schlieren image of a
# built-in scene (a Gaussian sphere of hot air, traced on OpenCL or the CPU) to out/schlieren.png.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
schlieren_install "${SCHLIEREN_BUILD_PACKAGES[@]}"
schlieren_build
mkdir -p "$SCHLIEREN_ROOT/out"
pvpython "$SCHLIEREN_ROOT/Examples/first_light.py" \
  --plugin "$(schlieren_plugin)" --output "$SCHLIEREN_ROOT/out/schlieren.png"
