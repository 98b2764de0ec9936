#!/usr/bin/env bash
# `clpt render --aovs` end to end (docs/aovs.md): the EXR carries albedo.R/G/B, N.X/Y/Z and Z
# (those asked for) and clpt:aovs; the same render without --aovs has exactly the six channels it
# had before (R, G, B, variance.R/G/B) and no clpt:aovs, and its beauty equals the one with the
# layers; --explain names CLPT_AOVS only with --aovs; bad lists and outputs that cannot carry the
# layers (a raw .pfm film, --checkpoint, --resume) are usage errors (exit 2) naming --aovs, with
# nothing written.
#   aovs_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
scene="$src/scenes/diffuse.toml"
export POCL_WORK_GROUP_SPECIALIZATION=0  # one work-group function per kernel: a faster test
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
tiny=(--width 16 --height 12 --spp 16 --seed 3 -q)

channels() { iinfo -v "$1" | sed -n 's/^ *channel list: //p'; }

"$clpt" render "$scene" "${tiny[@]}" -o plain.exr || fail "render without --aovs"
"$clpt" render "$scene" "${tiny[@]}" --aovs albedo,normal,depth -o all.exr || fail "render with --aovs"
"$clpt" render "$scene" "${tiny[@]}" --aovs depth -o depth.exr || fail "render with --aovs depth"

[[ "$(channels plain.exr)" == "R, G, B, variance.R, variance.G, variance.B" ]] ||
  fail "without --aovs the channels are: $(channels plain.exr)"
iinfo -v plain.exr | grep -q 'clpt:aovs' && fail "without --aovs the EXR has clpt:aovs"
for ch in albedo.R albedo.G albedo.B N.X N.Y N.Z Z; do
  channels all.exr | tr -d ' ' | tr ',' '\n' | grep -qx "$ch" || fail "--aovs albedo,normal,depth: no channel $ch"
done
iinfo -v all.exr | grep -q 'clpt:aovs: "albedo,normal,depth"' || fail "--aovs: clpt:aovs missing"
[[ "$(channels depth.exr)" == "R, G, B, Z, variance.R, variance.G, variance.B" ]] ||
  fail "--aovs depth: the channels are: $(channels depth.exr)"
# The beauty with and without the layers: the same samples, the same image.
diff_out=$(oiiotool plain.exr --ch R,G,B all.exr --ch R,G,B --diff 2>&1)
echo "$diff_out" | grep -q "PASS" || fail "the beauty changed with --aovs: $diff_out"

"$clpt" render "$scene" --width 16 --height 12 --spp 16 --explain -q -o e1.exr | grep -q CLPT_AOVS &&
  fail "--explain without --aovs names CLPT_AOVS"
"$clpt" render "$scene" --width 16 --height 12 --spp 16 --explain --aovs normal -q -o e2.exr | grep -q -- '-DCLPT_AOVS=1' ||
  fail "--explain with --aovs does not name -DCLPT_AOVS=1"

# usage_error LABEL EXPECTED -- ARGS: exit 2, the message names EXPECTED, nothing written.
usage_error() {
  local label=$1 expected=$2
  shift 3
  rm -f bad.exr bad.png bad.pfm bad.var.pfm
  local out code
  out=$("$clpt" render "$scene" "${tiny[@]}" "$@" 2>&1)
  code=$?
  [[ $code == 2 ]] || fail "$label: exit $code, not 2 ($out)"
  echo "$out" | grep -qF -- "$expected" || fail "$label: message lacks '$expected': $out"
  [[ -e bad.exr || -e bad.pfm || -e bad.png ]] && fail "$label: wrote an output"
}
usage_error "unknown layer" "--aovs albedo,nrm: 'nrm' is not a layer" -- --aovs albedo,nrm -o bad.exr
usage_error "repeated layer" "'depth' is named twice" -- --aovs depth,depth -o bad.exr
usage_error "raw film" "raw .pfm film" -- --aovs albedo -o bad.pfm
usage_error "checkpoint" "a checkpoint keeps no first-hit layers" -- --aovs albedo --checkpoint ck.bin -o bad.exr
usage_error "resume" "holds no first-hit layers" -- --aovs albedo --resume ck.bin -o bad.exr

if ((failures)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "aovs.cli: all passed"
