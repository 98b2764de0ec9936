#!/usr/bin/env bash
# Renders the mesh scenes' pictures in docs/ (docs/scenes.md shows them): the Cornell box
# (docs/cornell-box.png, 256x256, 1024 spp; next-event estimation samples its emitting
# triangles) and the torus knot
# (docs/torus-knot.png, 320x240, 128 spp), each with its scene's estimator (next-event
# estimation) and the Sobol sampler, on the best device; and the environment-lit scene
# (docs/environment.png, 320x180, 1024 spp, ACES tone curve: README.md shows it). The EXRs go to out/; only the PNG
# previews are copied into docs/ (small enough to commit).
#   scripts/render_docs_pictures.sh [SPP]    samples per pixel for both (default: as above)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
spp=${1:-}
[[ -z $spp || $spp =~ ^[1-9][0-9]*$ ]] || { echo "usage: scripts/render_docs_pictures.sh [SPP]" >&2; exit 2; }

clpt_install_missing "${CLPT_PACKAGES[@]}"
clpt_generate_meshes
[[ -x "$CLPT_BUILD/clpt" ]] || clpt_build -DCLPT_BUILD_TESTS=OFF
mkdir -p "$CLPT_ROOT/out"
# picture SCENE WIDTH HEIGHT SPP [RENDER OPTIONS...]: renders scenes/SCENE.toml to
# out/SCENE.exr (SPP unless the command line gave one) and copies the PNG.
picture() {
  local scene=$1 width=$2 height=$3 samples=${spp:-$4}
  shift 4
  "$CLPT_BUILD/clpt" render "$CLPT_ROOT/scenes/$scene.toml" -o "$CLPT_ROOT/out/$scene.exr" \
      --width "$width" --height "$height" --spp "$samples" --sampler sobol -q "$@"
  cp "$CLPT_ROOT/out/$scene.png" "$CLPT_ROOT/docs/$scene.png"
  clpt_log "docs/$scene.png: ${width}x${height}, $samples spp"
}
picture cornell-box 256 256 1024
picture torus-knot 320 240 128
picture environment 320 180 1024 --tonemap aces
