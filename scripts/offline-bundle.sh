#!/usr/bin/env bash
# The bundle a GPU machine without a package registry builds clpt from: Debian packages unpacked
# into a prefix, the tree, and PoCL's reference films (for scripts/gpu-report.sh).
#
# scripts/offline-bundle.sh DIR [--verify-args "ARGS"]
#
# Gathers, on a Debian 12 machine with a package registry, what a machine without one (a GPU box
# on a cluster or in a cloud: x86-64, the GPU vendor's OpenCL driver, g++ and CMake, no apt) needs
# to build clpt's render core and report on its GPUs with scripts/gpu-report.sh:
#   DIR/prefix/    the Debian 12 packages below, unpacked (dpkg-deb -x, not installed): what the
#                  core builds against that such a machine lacks. No OpenImageIO: the core writes
#                  raw PFM films, and `clpt verify` compares them there.
#   DIR/src/       this tree: tracked files and untracked ones git does not ignore, plus the
#                  generated torus-knot mesh (scenes/meshes/torus_knot.ply) and the book's scene
#                  with 1000 small spheres (scenes/many-spheres.toml, scripts/many_spheres_scene.py:
#                  issue 35's sphere hierarchy, which the report benches and traverses)
#   DIR/films/     reference renders of `clpt verify` on this machine's PoCL CPU device, with
#                  films.json (their size, spp, seed and device): the GPU's verify compares with
#                  these, since that machine may have no PoCL (`verify --reference films`)
#   DIR/MANIFEST   the packages and versions, the tree's commit, this machine and the date
# DIR must not exist or be empty; the whole of it must stay under 60 MB (checked at the end).
# --verify-args passes options to the films' `clpt verify` (a test uses a tiny size:
# "--width 16 --height 12 --spp 64 --scenes diffuse"); the default is verify's own matrix.
# It builds `clpt` in $CLPT_BUILD (default build/) if that has none. docs/portability.md says how
# to use the bundle.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

usage() { echo "usage: scripts/offline-bundle.sh DIR [--verify-args \"ARGS\"]" >&2; exit 2; }
[[ $# -ge 1 ]] || usage
out=$1
shift
verify_args=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --verify-args) [[ $# -ge 2 ]] || usage; verify_args=$2; shift 2 ;;
    *) usage ;;
  esac
done
if [[ -e "$out" && -n "$(ls -A "$out" 2>/dev/null)" ]]; then
  clpt_log "$out exists and is not empty; give a new directory"
  exit 2
fi

# What the render core links or includes that a GPU machine without a registry cannot be assumed
# to have (README "Dependencies" says why each is a dependency at all):
CLPT_BUNDLE_PACKAGES=(
  ocl-icd-libopencl1 ocl-icd-opencl-dev opencl-c-headers  # the OpenCL ICD loader and C headers
  libtomlplusplus3 libtomlplusplus-dev                    # TOML scenes
  libcli11-dev nlohmann-json3-dev                         # the command line; bench and verify JSON
  libassimp5 libassimp-dev libdraco7 libminizip1          # mesh files, and what libassimp.so.5 links
  libtinygltf-dev                                         # glTF scenes (header-only, over nlohmann-json)
)
[[ -f "$CLPT_ROOT/scenes/meshes/torus_knot.ply" ]] || python3 "$CLPT_ROOT/scripts/make_mesh_scene.py" >&2

mkdir -p "$out"
out=$(cd "$out" && pwd)
debs=$(mktemp -d)
chmod a+rwx "$debs"  # apt-get download writes as its _apt user
trap 'rm -rf "$debs"' EXIT

clpt_log "downloading ${#CLPT_BUNDLE_PACKAGES[@]} Debian packages"
(cd "$debs" && apt-get download -qq "${CLPT_BUNDLE_PACKAGES[@]}" >/dev/null)
mkdir -p "$out/prefix"
for deb in "$debs"/*.deb; do dpkg-deb -x "$deb" "$out/prefix"; done
rm -rf "$out/prefix/usr/share/doc" "$out/prefix/usr/share/man" "$out/prefix/usr/share/lintian"

clpt_log "copying the tree"
mkdir -p "$out/src"
(cd "$CLPT_ROOT" && { git ls-files -co --exclude-standard -z; printf 'scenes/meshes/torus_knot.ply\0'; } |
   tar --null -T - -cf - ) | tar -xf - -C "$out/src"
python3 "$CLPT_ROOT/scripts/many_spheres_scene.py" "$out/src/scenes/many-spheres.toml"

clpt_log "rendering the reference films on PoCL"
if [[ ! -x "$CLPT_BUILD/clpt" ]]; then
  cmake -S "$CLPT_ROOT" -B "$CLPT_BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$CLPT_BUILD" -j "$(nproc)" --target clpt
fi
mkdir -p "$out/films"
# shellcheck disable=SC2086  # verify_args is a list of options
"$CLPT_BUILD/clpt" verify --device "Portable Computing Language" --reference device --save-reference-films "$out/films" -q $verify_args \
  >"$out/films/verify-on-pocl.txt"

{
  echo "clpt offline bundle"
  echo "tree: $(git -C "$CLPT_ROOT" rev-parse HEAD)$(git -C "$CLPT_ROOT" diff --quiet HEAD -- 2>/dev/null || echo ' (with uncommitted changes)')"
  clpt_machine_line
  echo "packages (Debian 12, unpacked into prefix/):"
  for deb in "$debs"/*.deb; do dpkg-deb -f "$deb" Package Version | paste -sd' ' | sed 's/^/  /'; done
  echo "films: clpt verify --device 'Portable Computing Language' --reference device --save-reference-films films ${verify_args}"
} >"$out/MANIFEST"

bytes=$(du -sb "$out" | cut -f1)
limit=$((60 * 1000 * 1000))
if [[ $bytes -gt $limit ]]; then
  clpt_log "the bundle is $bytes bytes, over the 60 MB limit"
  exit 1
fi
clpt_log "bundle: $out ($((bytes / 1000)) kB); on the GPU machine: scripts/gpu-report.sh BUNDLE OUTDIR (from BUNDLE/src)"
