#!/usr/bin/env bash
# Installs what is missing, builds clpt, and renders the default scene (the book's diffuse room,
# 640x480, 16 spp as in the book) on the best available OpenCL device.
# Extra arguments go to `clpt render`, e.g. scripts/render.sh --spp 1024 --device cpu
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

clpt_install_missing "${CLPT_PACKAGES[@]}"
clpt_generate_meshes
clpt_build -DCLPT_BUILD_TESTS=OFF
mkdir -p "$CLPT_ROOT/out"
"$CLPT_BUILD/clpt" render "$CLPT_ROOT/scenes/diffuse.toml" -o "$CLPT_ROOT/out/diffuse.exr" "$@"
clpt_log "images: $CLPT_ROOT/out/diffuse.exr (linear HDR with variance) and $CLPT_ROOT/out/diffuse.png (preview)"
