#!/usr/bin/env bash
# Installs what is missing, builds clpt with its tests, and runs the whole suite through ctest
# on the OpenCL CPU device (PoCL). Extra arguments go to ctest, e.g. scripts/test.sh -L unit
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

clpt_install_missing "${CLPT_PACKAGES[@]}" "${CLPT_TEST_PACKAGES[@]}" "${CLPT_FUZZ_PACKAGES[@]}"
clpt_generate_meshes
clpt_build -DCLPT_BUILD_TESTS=ON
"$CLPT_BUILD/clpt" devices
cd "$CLPT_BUILD"
# Without arguments: everything but the preset x extreme matrix (label `extremes`, a few
# minutes; scripts/extremes.sh runs it, or scripts/test.sh -L extremes), the Oclgrind kernel
# variants that complete every pair of dimension values (label `oclgrind-pairs`, 20-40 minutes on
# 2 cores: scripts/test.sh -L oclgrind-pairs; docs/oclgrind.md), and label `long` (about 6
# minutes: scripts/test.sh -L long): two long end-to-end scripts, the GPU report on PoCL and
# `clpt verify` on Oclgrind, and the two checks of what compilers make of every kernel (PoCL's
# vectoriser remarks, the GPU compilers' budget), to run after a kernel change; they kept CI over
# its 20 minutes with an empty kernel cache.
if [[ $# -eq 0 ]]; then
  ctest --output-on-failure -j "$(nproc)" --label-exclude 'extremes|oclgrind-pairs|long'
else
  ctest --output-on-failure -j "$(nproc)" "$@"
fi
# The whole suite (no ctest arguments) goes on with 10 s fuzz runs (side by side, one per processor) of the scene loader, mesh
# files and the option parser, then the unit and bad-input tests under ASan + UBSan, each in its own build
# directory (about 6 minutes more on 2 cores).
if [[ $# -eq 0 ]]; then
  "$CLPT_ROOT/scripts/fuzz.sh" 10
  "$CLPT_ROOT/scripts/sanitize.sh"
fi
