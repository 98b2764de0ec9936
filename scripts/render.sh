#!/usr/bin/env bash
# Installs what is missing, builds clpt, and renders the default scene (the book's diffuse room,
# 640x480) on the best available OpenCL device: a good first picture, next-event estimation with
# the Sobol sampler until clpt's own error estimate says 10% relative RMSE (--target-error 0.1;
# about 5 s on the project's 2-core CPU, README "Render to a target error").
#   scripts/render.sh                       the first picture
#   scripts/render.sh --target-error 0.03   extra arguments go to `clpt render` after these defaults
#                                           (a later option overrides an earlier one)
#   scripts/render.sh --book [ARGS]         the book's own render: its estimator, grid sampler, 16 spp,
#                                           as scenes/diffuse.toml says
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

first_picture=(--estimator nee --sampler sobol --target-error 0.1)
if [[ "${1:-}" == "--book" ]]; then
  first_picture=()
  shift
fi

clpt_install_missing "${CLPT_PACKAGES[@]}"
clpt_generate_meshes
clpt_build -DCLPT_BUILD_TESTS=OFF
mkdir -p "$CLPT_ROOT/out"
"$CLPT_BUILD/clpt" render "$CLPT_ROOT/scenes/diffuse.toml" -o "$CLPT_ROOT/out/diffuse.exr" ${first_picture[@]+"${first_picture[@]}"} "$@"
clpt_log "images: $CLPT_ROOT/out/diffuse.exr (linear HDR with variance) and $CLPT_ROOT/out/diffuse.png (preview)"
