#!/usr/bin/env bash
# The mesh scenes of scenes/ through the real `clpt` binary (issue 14 part A):
#  - scripts/make_mesh_scene.py writes the 102,400-triangle torus knot and torus-knot.toml loads it;
#  - `clpt scene-transform` writes a file mesh as the same file (named from the output's directory)
#    with the composed scale and translation, and the written scene loads again from there;
#  - the Cornell box (inline meshes only) transforms and loads back the same way.
#   mesh_scenes_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work/src/meshes" "$work/out"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# expect_ok ARGS...: clpt exits 0.
expect_ok() {
  local err
  if err=$("$clpt" "$@" 2>&1 >/dev/null); then echo "ok: clpt $*"; else fail "clpt $* exited $?: $err"; fi
}
expect_line() {  # FILE LINE: the file holds the exact line
  if grep -qxF -- "$2" "$1"; then echo "ok: $1 has '$2'"; else fail "$1 lacks the line '$2'"; fi
}

python3 "$src/scripts/make_mesh_scene.py" "$work/src/meshes/torus_knot.ply" >/dev/null || fail "make_mesh_scene.py failed"
cp "$src/scenes/torus-knot.toml" "$src/scenes/cornell-box.toml" "$work/src/"

expect_ok scene-transform "$work/src/torus-knot.toml" --scale 2 --translate 1,2,3 -q -o "$work/out/knot.toml"
expect_line "$work/out/knot.toml" "file = '../src/meshes/torus_knot.ply'"
expect_line "$work/out/knot.toml" 'scale = [ 2.3999999999999999, 2.3999999999999999, 2.3999999999999999 ]'
expect_line "$work/out/knot.toml" 'translate = [ 1.0, 4.2000000000000002, 3.0 ]'
expect_line "$work/out/knot.toml" 'rotate_deg = [ 0.0, 30.0, 0.0 ]'
expect_ok scene-transform "$work/out/knot.toml" --scale 0.5 -q -o "$work/src/again.toml"
expect_line "$work/src/again.toml" "file = 'meshes/torus_knot.ply'"

expect_ok scene-transform "$work/src/cornell-box.toml" --scale 0.001 -q -o "$work/out/cornell.toml"
[[ $(grep -c '^\[\[mesh\]\]$' "$work/out/cornell.toml") -eq 8 ]] || fail "cornell.toml should hold 8 [[mesh]] tables"
grep -q '^file' "$work/out/cornell.toml" && fail "cornell.toml names a mesh file, but its meshes are inline"
expect_ok scene-transform "$work/out/cornell.toml" --scale 1000 -q -o "$work/out/cornell_back.toml"

[[ $failures -eq 0 ]] && echo "mesh scenes: all ok" || echo "mesh scenes: $failures failure(s)"
exit $((failures > 0))
