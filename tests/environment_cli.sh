#!/usr/bin/env bash
# The environment light through the real binary (docs/environment.md): bad environment files and
# options each exit with the documented code, name the file and the key or option, and leave no
# output file; a good one renders, and --exposure / --tonemap are recorded in the EXR.
#   environment_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work/out" "$work/in"
scene="$src/scenes/diffuse.toml"
sky="$src/scenes/environment-sky.hdr"
failures=0

# Inputs: an empty file, a directory, a truncated HDR, a text file named .exr, a valid sky.
: > "$work/in/empty.hdr"
mkdir -p "$work/in/folder.exr"
head -c 200 "$sky" > "$work/in/truncated.hdr"
echo "not an image" > "$work/in/text.exr"
cp "$sky" "$work/in/sky.hdr"
# Float maps (PFM: a header, then little-endian floats, bottom row first) as lossy EXR compression
# leaves them: two texels slightly negative; and one with a NaN.
pfm() {  # pfm NAME R0 R1 ...: a 4 x 2 RGB map, one value per channel of each texel in file order
  python3 -c 'import struct, sys; v = [float(x) for x in sys.argv[2:]]; open(sys.argv[1], "wb").write(b"PF\n4 2\n-1.0\n" + struct.pack("<%df" % len(v), *v))' "$@"
}
grey=(0.5 0.5 0.5)
pfm "$work/in/negative.pfm" "${grey[@]}" 0.5 -6.1e-06 0.5 "${grey[@]}" "${grey[@]}" "${grey[@]}" -3e-04 0.5 0.5 "${grey[@]}" "${grey[@]}"
pfm "$work/in/nan.pfm" "${grey[@]}" "${grey[@]}" 0.5 nan 0.5 "${grey[@]}" "${grey[@]}" "${grey[@]}" "${grey[@]}" "${grey[@]}"
# A TOML scene naming each in its [environment] table (the file relative to the scene).
toml_scene() {  # toml_scene NAME ENVIRONMENT_LINES
  printf '[camera]\nposition = [0.0, 1.0, 5.0]\nlook_at = [0.0, 1.0, 0.0]\n\n[[sphere]]\ncenter = [0.0, 1.0, 0.0]\nradius = 1.0\nmaterial = { type = "lambertian", reflectance = [0.5, 0.5, 0.5] }\n\n[environment]\n%b\n' "$2" > "$work/in/$1.toml"
}

# expect CODE SUBSTRING... -- ARGS...: exit code, every substring in stderr, nothing in out/.
expect() {
  local code=$1
  shift
  local needles=()
  while [[ $1 != -- ]]; do needles+=("$1"); shift; done
  shift
  local err status
  err=$(cd "$work/out" && "$clpt" "$@" 2>&1 >/dev/null)
  status=$?
  local ok=1
  if [[ $status -ne $code ]]; then
    echo "FAIL: clpt $* exited $status, expected $code; stderr: $err"; ok=0
  else
    for n in "${needles[@]}"; do
      if [[ "$err" != *"$n"* ]]; then echo "FAIL: clpt $*: stderr lacks '$n'; got: $err"; ok=0; fi
    done
  fi
  if [[ -n "$(ls -A "$work/out")" ]]; then
    echo "FAIL: clpt $* left files: $(ls -A "$work/out")"; ok=0
    rm -rf "${work:?}/out"/*
  fi
  if [[ $ok -eq 1 ]]; then echo "ok: clpt $* -> $status"; else failures=$((failures + 1)); fi
}

r=(render "$scene" --spp 16 --width 8 --height 6 -o out.exr)
# --environment FILE: usage errors (exit 2) naming the option and the file.
expect 2 "--environment: $work/in/missing.hdr: no such file" -- "${r[@]}" --environment "$work/in/missing.hdr"
expect 2 "--environment: $work/in/empty.hdr: the file is empty (0 bytes)" -- "${r[@]}" --environment "$work/in/empty.hdr"
expect 2 "--environment: $work/in/folder.exr: is a directory" -- "${r[@]}" --environment "$work/in/folder.exr"
expect 2 "--environment" "truncated.hdr" -- "${r[@]}" --environment "$work/in/truncated.hdr"
expect 2 "--environment" "text.exr" -- "${r[@]}" --environment "$work/in/text.exr"
expect 2 "--environment: $work/in/nan.pfm: texel (" "has the value nan (radiance must be finite)" -- "${r[@]}" --environment "$work/in/nan.pfm"
expect 2 "--environment-strength -1: must be finite and >= 0" -- "${r[@]}" --environment "$sky" --environment-strength -1
expect 2 "--environment-strength: the scene" "has no environment" -- "${r[@]}" --environment-strength 2
expect 2 "--environment-rotation: the scene" "has no environment" -- "${r[@]}" --environment-rotation 90
expect 2 "--tonemap" -- "${r[@]}" --tonemap reinhard
expect 2 "--exposure" -- "${r[@]}" --exposure lots

# The [environment] table: scene errors (exit 3) naming file:line:column and the key.
toml_scene missing 'file = "missing.hdr"'
expect 3 "missing.toml:11:8: environment.file: missing.hdr: no such file" -- render "$work/in/missing.toml" -o out.exr
toml_scene empty 'file = "empty.hdr"'
expect 3 "empty.toml:11:8: environment.file: empty.hdr: the file is empty (0 bytes)" -- render "$work/in/empty.toml" -o out.exr
toml_scene folder 'file = "folder.exr"'
expect 3 "folder.toml:11:8: environment.file: folder.exr: is a directory" -- render "$work/in/folder.toml" -o out.exr
toml_scene truncated 'file = "truncated.hdr"'
expect 3 "truncated.toml:11:8: environment.file:" "truncated.hdr" -- render "$work/in/truncated.toml" -o out.exr
toml_scene both 'file = "sky.hdr"\ncolor = [1.0, 1.0, 1.0]'
expect 3 "both.toml:12:9: environment.color: 'color' does not go with 'file'" -- render "$work/in/both.toml" -o out.exr
toml_scene neither 'strength = 2.0'
expect 3 "neither.toml:10:1: environment: missing required key 'file' (or 'color')" -- render "$work/in/neither.toml" -o out.exr
toml_scene strength 'color = [1.0, 1.0, 1.0]\nstrength = -2.0'
expect 3 "strength.toml:12:12: environment.strength: must be finite and >= 0, got -2" -- render "$work/in/strength.toml" -o out.exr
toml_scene colour 'color = [1.0, -1.0, 1.0]'
expect 3 "colour.toml:11:9: environment.color: radiance must be finite and >= 0, element 1 is -1" -- render "$work/in/colour.toml" -o out.exr
toml_scene rotation 'color = [1.0, 1.0, 1.0]\nrotation_deg = nan'
expect 3 "rotation.toml:12:16: environment.rotation_deg: must be finite, got nan" -- render "$work/in/rotation.toml" -o out.exr
toml_scene typo 'color = [1.0, 1.0, 1.0]\nstrenght = 2.0'
expect 3 "typo.toml:12:1: environment.strenght: unknown key" "strength" -- render "$work/in/typo.toml" -o out.exr

# Good: a TOML scene lit by its environment alone, and --environment on the book's room; the EXR
# records the preview's exposure and curve.
toml_scene good 'file = "sky.hdr"\nstrength = 0.5\nrotation_deg = 45.0'
if (cd "$work/out" && "$clpt" render "$work/in/good.toml" --spp 4 --width 16 --height 12 --estimator nee -q -o good.exr \
      --exposure -1.5 --tonemap aces) && [[ -f "$work/out/good.exr" && -f "$work/out/good.png" ]]; then
  meta=$(oiiotool --info -v "$work/out/good.exr" 2>/dev/null)
  if [[ "$meta" == *'clpt:preview_tonemap: "aces"'* && "$meta" == *'clpt:preview_exposure: "-1.5"'* ]]; then
    echo "ok: environment-lit TOML scene rendered, preview settings recorded"
  else
    echo "FAIL: the EXR lacks clpt:preview_tonemap/exposure: $meta"; failures=$((failures + 1))
  fi
else
  echo "FAIL: the environment-lit TOML scene did not render"; failures=$((failures + 1))
fi
rm -rf "${work:?}/out"/*
if (cd "$work/out" && "$clpt" render "$scene" --spp 16 --width 16 --height 12 -q -o room.exr --environment "$sky" \
      --environment-strength 0.01 --environment-rotation 30) && [[ -f "$work/out/room.exr" ]]; then
  echo "ok: --environment on a TOML scene"
else
  echo "FAIL: --environment on the book's room did not render"; failures=$((failures + 1))
fi
rm -rf "${work:?}/out"/*
# Negative texels render, read as 0, with one notice naming the file, the count and the most negative.
toml_scene negative 'file = "negative.pfm"'
err=$(cd "$work/out" && "$clpt" render "$work/in/negative.toml" --spp 4 --width 8 --height 6 -o negative.exr 2>&1)
status=$?
notice="negative.toml:11:8: environment.file: negative.pfm: 2 texels are negative (the most negative -0.0003 at (1, 0)"
if [[ $status -eq 0 && -f "$work/out/negative.exr" && "$err" == *"$notice"*"read as 0"* && $(grep -c "texels are negative" <<<"$err") -eq 1 ]]; then
  echo "ok: negative texels read as 0 with one notice"
else
  echo "FAIL: the environment with negative texels: exit $status, stderr: $err"; failures=$((failures + 1))
fi
rm -rf "${work:?}/out"/*

if [[ $failures -ne 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "all environment CLI cases passed"
