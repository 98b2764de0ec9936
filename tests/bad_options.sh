#!/usr/bin/env bash
# Bad command-line options: each case must exit with the documented code, name the option in its
# message, and leave no output file behind.
#   bad_options.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
scene="$src/scenes/diffuse.toml"
failures=0

# expect CODE SUBSTRING -- ARGS...
expect() {
  local code=$1 needle=$2
  shift 3
  local err status
  err=$(cd "$work" && "$clpt" "$@" 2>&1 >/dev/null)
  status=$?
  if [[ $status -ne $code ]]; then
    echo "FAIL: clpt $* exited $status, expected $code; stderr: $err"
    failures=$((failures + 1))
  elif [[ "$err" != *"$needle"* ]]; then
    echo "FAIL: clpt $*: stderr lacks '$needle'; got: $err"
    failures=$((failures + 1))
  elif [[ -n "$(ls -A "$work")" ]]; then
    echo "FAIL: clpt $* left files: $(ls -A "$work")"
    failures=$((failures + 1))
    rm -rf "${work:?}"/*
  else
    echo "ok: clpt $* -> $status ($needle)"
  fi
}

expect 2 "scene is required" -- render
expect 2 "--frobnicate" -- render "$scene" --frobnicate
expect 2 "--spp" -- render "$scene" --spp 0 -o out.exr
expect 2 "--spp" -- render "$scene" --spp many -o out.exr
expect 2 "--width" -- render "$scene" --width 0 -o out.exr
expect 2 "--height" -- render "$scene" --height 99999 -o out.exr
expect 2 "--max-bounces" -- render "$scene" --max-bounces 5000 -o out.exr
expect 2 "--sampler" -- render "$scene" --sampler halton -o out.exr
expect 2 "--exr-compression" -- render "$scene" --exr-compression lzw -o out.exr
expect 2 "--time" -- render "$scene" --time -1 -o out.exr
expect 2 "--spp 10: the grid sampler needs a multiple of 16" -- render "$scene" --sampler grid --spp 10 -o out.exr
expect 2 "--device 'nosuchdevice': no such device" -- render "$scene" --device nosuchdevice --sampler jitter --spp 1 -o out.exr
expect 2 "-o out.jpg: the output must be an .exr" -- render "$scene" -o out.jpg
expect 5 "-o no/such/dir/out.exr: directory 'no/such/dir' does not exist" -- render "$scene" -o no/such/dir/out.exr
expect 3 "missing.toml: cannot open scene file" -- render missing.toml -o out.exr
expect 2 "subcommand" -- frobnicate
expect 2 "--precision" -- render "$scene" --precision quad -o out.exr
expect 2 "--estimator" -- render "$scene" --estimator bdpt -o out.exr
expect 2 "--megakernel-loop" -- render "$scene" --megakernel-loop unrolled -o out.exr
expect 2 "--scene-loops" -- render "$scene" --scene-loops lockstep -o out.exr
expect 2 "--rr-from" -- render "$scene" --rr-from -1 -o out.exr
expect 2 "--intersection" -- render "$scene" --intersection exact -o out.exr
expect 2 "--light-sampling" -- render "$scene" --light-sampling cone -o out.exr
# The OpenImageIO module missing: a command that reads images stops, naming the path tried (a
# render needs no module: compare_cli.sh renders with it hidden).
CLPT_IMAGE_IO_MODULE=/nonexistent/libclpt_image_io.so expect 2 "/nonexistent/libclpt_image_io.so: no such file" \
  -- compare missing_a.exr missing_b.exr

# A device without fp64 (CLPT_HIDE_FP64 hides PoCL's) refuses the double preset, naming it.
CLPT_HIDE_FP64=1 expect 4 "--precision double: device '" -- render "$scene" --precision double --spp 16 --width 8 --height 8 -o out.exr

# Limits, checked before anything is allocated (so they fail fast), and --resume. Their inputs
# live beside WORK_DIR, which must stay empty.
inputs="$work.inputs"
rm -rf "$inputs" && mkdir -p "$inputs"
{
  printf '[image]\nwidth = 8\nheight = 8\n[camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, -1.0]\n'
  printf '[[sphere]]\ncenter = [0.0, 0.0, -5.0]\nradius = 1.0\nmaterial = { type = "emitter", emission = [1.0, 1.0, 1.0] }\n'
  for i in $(seq 1 4999); do
    printf '[[sphere]]\ncenter = [%d.0, 0.0, -20.0]\nradius = 0.1\nmaterial = { type = "lambertian", reflectance = [0.5, 0.5, 0.5] }\n' "$i"
  done
} >"$inputs/many_spheres.toml"
start_ns=$(date +%s%N)
expect 2 "--width/--height: the image 16384x16384 has 268435456 pixels; at most 67108864 (2^26) are supported" \
  -- render "$scene" --width 16384 --height 16384 -o out.exr
expect 3 "many_spheres.toml: sphere: the scene has 5000 spheres; at most 4096 are supported" \
  -- render "$inputs/many_spheres.toml" -o out.exr
elapsed_ms=$((($(date +%s%N) - start_ns) / 1000000))
if [[ $elapsed_ms -gt 10000 ]]; then
  echo "FAIL: the two limit checks took $elapsed_ms ms (they must fail before any allocation)"
  failures=$((failures + 1))
fi
"$clpt" render "$scene" --width 8 --height 8 --spp 1 --sampler jitter -q --checkpoint "$inputs/seed1.ckpt" \
  -o "$inputs/seed1.pfm" || { echo "FAIL: could not write a checkpoint"; failures=$((failures + 1)); }
expect 2 "--resume missing.ckpt: cannot open checkpoint" -- render "$scene" --resume missing.ckpt -o out.exr
expect 2 "the checkpoint's seed 1 does not match this render's seed 2" \
  -- render "$scene" --width 8 --height 8 --sampler jitter --spp 4 --seed 2 --resume "$inputs/seed1.ckpt" -o out.exr
expect 2 "the checkpoint's sampler jitter does not match this render's sampler sobol" \
  -- render "$scene" --width 8 --height 8 --sampler sobol --spp 4 --resume "$inputs/seed1.ckpt" -o out.exr

if [[ $failures -ne 0 ]]; then
  echo "$failures bad-option case(s) failed"
  exit 1
fi
