#!/usr/bin/env bash
# Installs what is missing, builds clpt with its tests, and runs the whole suite through ctest
# on the OpenCL CPU device (PoCL). Extra arguments go to ctest, e.g. scripts/test.sh -L unit
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

clpt_install_missing "${CLPT_PACKAGES[@]}" "${CLPT_TEST_PACKAGES[@]}"
clpt_build -DCLPT_BUILD_TESTS=ON
"$CLPT_BUILD/clpt" devices
cd "$CLPT_BUILD"
ctest --output-on-failure -j "$(nproc)" "$@"
