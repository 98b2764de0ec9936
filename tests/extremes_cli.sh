#!/usr/bin/env bash
# `clpt scene-transform` end to end and the safe-range warning of `clpt render`:
#  - a transformed scene is written, loads and renders; bad options exit 2, bad scenes 3 and an
#    output in a directory that does not exist 5,
#    naming the option or file, and leave no file behind;
#  - the book scene renders without a warning; a tiny sphere far away and a camera touching the
#    floor each get one naming the sphere and its file line;
#  - samples overflowing to Inf are dropped and counted in the render summary.
#   extremes_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect_error CODE SUBSTRING ARGS...: exit code, message, and nothing written.
expect_error() {
  local code=$1 needle=$2
  shift 2
  local err status
  err=$(cd "$work" && "$clpt" "$@" 2>&1 >/dev/null)
  status=$?
  if [[ $status -ne $code ]]; then fail "clpt $* exited $status, expected $code; stderr: $err"
  elif [[ "$err" != *"$needle"* ]]; then fail "clpt $*: stderr lacks '$needle'; got: $err"
  elif [[ -n "$(ls -A "$work")" ]]; then fail "clpt $* left files: $(ls -A "$work")"; rm -rf "${work:?}"/*
  else echo "ok: clpt $* -> $status ($needle)"
  fi
}

book="$src/scenes/diffuse.toml"
expect_error 2 "--scale" scene-transform "$book" --scale 0 -o out.toml
expect_error 2 "--scale" scene-transform "$book" --scale -1 -o out.toml
expect_error 2 "--translate" scene-transform "$book" --translate 1,2 -o out.toml
expect_error 2 "--translate" scene-transform "$book" --translate 1,x,2 -o out.toml
expect_error 2 "--output" scene-transform "$book" --scale 2
expect_error 5 "-o no/such/dir/out.toml: directory 'no/such/dir' does not exist" \
  scene-transform "$book" --scale 2 -o no/such/dir/out.toml
expect_error 3 "missing.toml" scene-transform missing.toml --scale 2 -o out.toml
expect_error 3 "radius must be > 0" scene-transform "$src/tests/scenes/bad/zero_radius.toml" -o out.toml

# A transformed scene: written, loadable, renderable, and equal to its source up to the transform.
"$clpt" scene-transform "$book" --scale 1e-4 --translate 1e5,0,-3 -o "$work/t.toml" -q || fail "scene-transform failed"
grep -q '^# made by `clpt scene-transform`' "$work/t.toml" || fail "no provenance comment in the written scene"
grep -q "center = \[ 100000.0, -10.0, -3.0 \]" "$work/t.toml" || fail "floor not at scale 1e-4 + (1e5, 0, -3): $(grep center "$work/t.toml" | head -1)"
out=$("$clpt" render "$work/t.toml" --spp 1 --sampler jitter --width 8 --height 6 -o "$work/t.exr" -q 2>&1) || fail "render of the transformed scene failed: $out"
[[ -z "$out" ]] || fail "unexpected output from a quiet render of the transformed scene: $out"

# Warnings: none for the book scene, one naming the sphere for the extreme ones.
warn=$("$clpt" render "$book" --spp 1 --sampler jitter --width 8 --height 6 -o "$work/book.exr" 2>&1 >/dev/null)
[[ "$warn" != *warning* ]] && echo "ok: no warning for the book scene" || fail "book scene warned: $warn"

cat > "$work/speck.toml" <<'TOML'
[camera]
position = [0.0, 1.0, 5.0]
look_at = [0.0, 1.0, 0.0]

[[sphere]]
name = "light"
center = [0.0, 50.0, 0.0]
radius = 10.0
material = { type = "emitter", emission = [4.0, 4.0, 4.0] }

[[sphere]]
name = "speck"
center = [0.0, 1.0, -1.0e7]
radius = 0.001
material = { type = "lambertian", reflectance = [0.7, 0.7, 0.7] }
TOML
warn=$("$clpt" render "$work/speck.toml" --spp 1 --sampler jitter --width 8 --height 6 -o "$work/speck.exr" 2>&1 >/dev/null)
if [[ "$warn" == *"clpt: warning: $work/speck.toml:11:"*"sphere 'speck'"*"--precision double"* ]]; then
  echo "ok: tiny sphere far away warns"
else fail "no or wrong warning for the tiny far sphere: $warn"; fi
[[ -f "$work/speck.exr" ]] || fail "a warning must not stop the render"

cat > "$work/low.toml" <<'TOML'
[camera]
position = [0.0, 0.000001, 0.0]
look_at = [0.0, 0.000001, -10.0]

[[sphere]]
name = "sky"
center = [0.0, 0.0, 0.0]
radius = 1000.0
material = { type = "emitter", emission = [2.0, 2.0, 2.0] }

[[sphere]]
name = "floor"
center = [0.0, -100000.0, 0.0]
radius = 100000.0
material = { type = "lambertian", reflectance = [0.5, 0.5, 0.5] }
TOML
warn=$("$clpt" render "$work/low.toml" --spp 1 --sampler jitter --width 8 --height 6 -o "$work/low.exr" 2>&1 >/dev/null)
if [[ "$warn" == *"sphere 'floor': the camera is 1e-06 from its surface"* ]]; then
  echo "ok: camera touching the floor warns"
else fail "no or wrong warning for a camera touching the floor: $warn"; fi
warn=$("$clpt" render "$work/speck.toml" -q --spp 1 --sampler jitter --width 8 --height 6 -o "$work/speck.exr" 2>&1)
[[ -z "$warn" ]] || fail "--quiet must silence warnings: $warn"

# Samples that overflow to Inf (radiance 3e38 scaled by 1.5^2 leaving glass) are dropped and the
# summary says how many; the emission itself draws a warning.
cat > "$work/overflow.toml" <<'TOML'
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.0, 0.0, -1.0]

[[sphere]]
name = "glass_around_camera"
center = [0.0, 0.0, 0.0]
radius = 2.0
material = { type = "glass", reflectance = [1.0, 1.0, 1.0], ior = 1.5 }

[[sphere]]
name = "overflowing_light"
center = [0.0, 0.0, -10.0]
radius = 5.0
material = { type = "emitter", emission = [3.0e38, 3.0e38, 3.0e38] }
TOML
summary=$("$clpt" render "$work/overflow.toml" --spp 16 --sampler jitter --width 16 --height 12 \
          -o "$work/overflow.exr" 2>"$work/overflow.err")
if [[ "$summary" =~ dropped\ [1-9][0-9]*\ samples\ with\ NaN/Inf\ radiance ]]; then
  echo "ok: the summary reports dropped samples"
else fail "no 'dropped N samples' in the summary: $summary"; fi
grep -q "sphere 'overflowing_light': emission 3e+38" "$work/overflow.err" && echo "ok: huge emission warns" ||
  fail "no emission warning: $(cat "$work/overflow.err")"

exit $((failures > 0))
