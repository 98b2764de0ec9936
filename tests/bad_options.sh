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
expect 2 "--sampler" -- render "$scene" --sampler sobol -o out.exr
expect 2 "--time" -- render "$scene" --time -1 -o out.exr
expect 2 "--spp 10: the grid sampler needs a multiple of 16" -- render "$scene" --sampler grid --spp 10 -o out.exr
expect 2 "--device 'nosuchdevice': no such device" -- render "$scene" --device nosuchdevice --sampler jitter --spp 1 -o out.exr
expect 2 "-o out.jpg: the output must be an .exr" -- render "$scene" -o out.jpg
expect 2 "does not exist" -- render "$scene" -o no/such/dir/out.exr
expect 3 "missing.toml: cannot open scene file" -- render missing.toml -o out.exr
expect 2 "subcommand" -- frobnicate

if [[ $failures -ne 0 ]]; then
  echo "$failures bad-option case(s) failed"
  exit 1
fi
