#!/usr/bin/env bash
# `clpt compare` end to end: two seeds of a small render pass, the same seed twice passes
# --same-seed (one of the two written with OpenImageIO's module hidden), every --exr-compression
# writes the same pixels, --json writes valid JSON,
# and an EXR without variance channels is a usage error (exit 2) whose message names the file and
# the variance channel.
#   compare_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

render() {  # render SEED OUTPUT
  "$clpt" render "$src/scenes/diffuse.toml" --width 64 --height 48 --spp 64 --sampler jitter \
    --seed "$1" -q -o "$2" || { echo "FAIL: render --seed $1 exited $?"; exit 1; }
}
render 1 a.exr
render 2 b.exr
# A render writes its EXR and PNG without OpenImageIO's module (host/io/exr_writer.h): with the
# module hidden it still succeeds, and OpenImageIO reads both files back below.
CLPT_IMAGE_IO_MODULE=/nonexistent/libclpt_image_io.so render 1 a_again.exr
iinfo a_again.png >/dev/null || fail "OpenImageIO cannot read the PNG clpt wrote"
# --exr-compression: the EXR says which it was written with, and every compression holds the same
# values (all are lossless): OpenImageIO finds no pixel differing from the zip file's.
for compression in none rle piz; do
  "$clpt" render "$src/scenes/diffuse.toml" --width 64 --height 48 --spp 64 --sampler jitter --seed 1 -q \
    --exr-compression $compression -o a_$compression.exr || fail "render --exr-compression $compression exited $?"
  iinfo -v a_$compression.exr | grep -q "compression: \"$compression\"" ||
    fail "a_$compression.exr: $(iinfo -v a_$compression.exr | grep compression)"
  oiiotool a.exr a_$compression.exr --diff --fail 0 --failpercent 0 >diff.txt ||
    fail "a_$compression.exr differs from the zip render: $(cat diff.txt)"
done
iinfo -v a.exr | grep -q 'compression: "zip"' || fail "a.exr (the default) is not zip: $(iinfo -v a.exr | grep compression)"

# expect CODE ARGS...: runs `clpt compare ARGS`, keeps stdout in out.txt and stderr in err.txt.
expect() {
  local code=$1
  shift
  "$clpt" compare "$@" >out.txt 2>err.txt
  local status=$?
  if [[ $status -ne $code ]]; then
    fail "clpt compare $* exited $status, expected $code"
    cat out.txt err.txt
  else
    echo "ok: clpt compare $* -> $status"
  fi
}

expect 0 a.exr b.exr --json report.json --diff-png diff.png
grep -q "result: PASS" out.txt || fail "the report lacks 'result: PASS'"
python3 -c 'import json,sys; json.load(open(sys.argv[1]))' report.json || fail "report.json is not valid JSON"
[[ -s diff.png ]] || fail "no diff.png written"
expect 0 a.exr a_again.exr --same-seed

oiiotool a.exr --ch R,G,B -o rgb.exr || fail "oiiotool could not make rgb.exr"
expect 2 a.exr rgb.exr
grep -q "rgb.exr" err.txt && grep -q "variance" err.txt || fail "message lacks the file or 'variance': $(cat err.txt)"
oiiotool a.exr --resize 32x24 -o small.exr || fail "oiiotool could not make small.exr"
expect 2 a.exr small.exr
grep -q "same size" err.txt || fail "size mismatch message: $(cat err.txt)"

if [[ $failures -ne 0 ]]; then
  echo "$failures compare case(s) failed"
  exit 1
fi
