#!/usr/bin/env bash
# `clpt verify` end to end on PoCL (the device under test is also the reference device, so every
# row compares two same-seed renders of one device):
#  (a) --device cpu --precisions robust: exit 0, 6 rows (3 scenes x 2 forms), all PASS with
#      same-seed fraction 1, valid JSON holding every row. At 32x24 and 320 spp, 1/16 of the
#      default samples: passing needs no power, and (b) runs at the default size and spp. One
#      preset, not the default three: the fast and double presets' 12 programs were compiled by
#      this test alone, about 60 s of CI's time with an empty kernel cache (2026-12-06);
#  (b) CLPT_INJECT_FAULT=perturb:0:G:1.02 at the default size and spp: exit 1, every row FAIL, each
#      FAIL line naming its scene and channel G with |z| beyond 5 + the critical z (the power the
#      defaults promise, tools/verify.h);
#  (c) a device failing its build (build:1 of two PoCL devices): that device's row fails with the
#      CL error, the other device's row still runs and passes;
#  (d) --reference builtin (gemspt's images) at 160x120 on one scene, form and precision: exit 0,
#      same-seed "n/a" and null in the JSON;
#  (e) bad options and inputs: exit 2 with a message naming the option, the file or the variable.
#   verify_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
export CLPT_CACHE_DIR="$work/cache"
unset CLPT_INJECT_FAULT POCL_DEVICES
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
show() { sed 's/^/    /' "$@"; }

# (a) The whole matrix passes on the reference device itself.
"$clpt" verify --device cpu --precisions robust --width 32 --height 24 --spp 320 --json full.json >full.out 2>full.err
status=$?
[[ $status -eq 0 ]] || { fail "(a) verify --device cpu exited $status, expected 0"; show full.out full.err; }
grep -q "^verify: 6 of 6 rows passed$" full.out || { fail "(a) not 6 of 6 rows passed"; show full.out; }
[[ $(grep -c "^0 .* PASS " full.out) -eq 6 ]] || { fail "(a) not 6 PASS row lines"; show full.out; }
python3 - full.json <<'PY' || fail "(a) JSON"
import json, sys
doc = json.load(open(sys.argv[1]))
rows = doc["rows"]
assert doc["reference_mode"] == "device" and doc["total"] == 6 and doc["passed"] == 6, doc
assert (doc["width"], doc["height"], doc["spp"]) == (32, 24, 320), doc
combos = {(r["scene"], r["form"], r["precision"]) for r in rows}
assert combos == {(s, f, p) for s in ("diffuse", "specular", "glass") for f in ("megakernel", "wavefront")
                  for p in ("robust",)}, combos
for r in rows:
    assert r["verdict"] == "PASS" and r["error"] is None and r["is_reference_device"], r
    assert r["same_seed_fraction"] == 1.0 and r["pixel_accept_fraction"] == 1.0, r
    assert r["paths_per_s"] > 0 and r["driver"], r
    assert r["worst"]["channel"] in "RGB" and r["worst"]["z_critical"] > 2, r
PY

# (b) A device whose G samples come out 2% bright fails every row, naming the scene and channel G.
CLPT_INJECT_FAULT=perturb:0:G:1.02 "$clpt" verify --device cpu --forms megakernel --precisions robust \
  --json perturb.json >perturb.out 2>perturb.err
status=$?
[[ $status -eq 1 ]] || { fail "(b) perturbed verify exited $status, expected 1"; show perturb.out perturb.err; }
grep -q "^verify: 0 of 3 rows passed$" perturb.out || { fail "(b) not 0 of 3 rows passed"; show perturb.out; }
for scene in diffuse specular glass; do
  grep -Eq "^FAIL: $scene, megakernel, robust on device 0 .*: (image mean|64x64 blocks) channel G: z = \+" perturb.out ||
    { fail "(b) no FAIL line naming $scene and channel G"; show perturb.out; }
done
python3 - perturb.json <<'PY' || fail "(b) JSON"
import json, sys
doc = json.load(open(sys.argv[1]))
assert (doc["width"], doc["height"], doc["spp"]) == (64, 48, 1280), doc  # the defaults
for r in doc["rows"]:
    # What the defaults promise for any 2% one-channel shift: the weakest channel's z is ~5
    # past the image mean's critical z (2.93); 7.9 to 8.3 measured (B is the weakest).
    assert r["shift_z_2pct"] > 7.5, r
    w = r["worst"]
    assert r["verdict"] == "FAIL" and w["channel"] == "G" and w["z"] > 0, r
    assert w["z"] - w["z_critical"] >= 5, r  # the margin the defaults are chosen for
    assert r["same_seed_fraction"] < 0.5, r
PY

# (c) Two PoCL devices, the second failing its kernel build: its row fails with the CL error, the
# first device's row runs and passes; exit 1.
POCL_DEVICES="pthread pthread" CLPT_INJECT_FAULT=build:1 "$clpt" verify --device all --scenes diffuse \
  --forms megakernel --precisions robust --width 16 --height 12 --spp 64 >build.out 2>build.err
status=$?
[[ $status -eq 1 ]] || { fail "(c) build fault exited $status, expected 1"; show build.out build.err; }
grep -q "^0 .* PASS " build.out || { fail "(c) device 0's row did not pass"; show build.out; }
grep -q "^FAIL: diffuse, megakernel, robust on device 1 .*clBuildProgram failed with .*injected by CLPT_INJECT_FAULT" \
  build.out || { fail "(c) device 1's row does not carry the build error"; show build.out; }
grep -q "^verify: 1 of 2 rows passed$" build.out || { fail "(c) not 1 of 2 rows passed"; show build.out; }

# (d) The fallback: gemspt's reference images, forced.
"$clpt" verify --reference builtin --device cpu --scenes diffuse --forms megakernel --precisions robust \
  --json builtin.json >builtin.out 2>builtin.err
status=$?
[[ $status -eq 0 ]] || { fail "(d) builtin verify exited $status, expected 0"; show builtin.out builtin.err; }
grep -q "^reference: gemspt references in .*tests/reference" builtin.out || { fail "(d) reference not named"; show builtin.out; }
grep -q "^0 .* diffuse .* PASS .* n/a " builtin.out || { fail "(d) row not PASS with same-seed n/a"; show builtin.out; }
python3 - builtin.json <<'PY' || fail "(d) JSON"
import json, sys
doc = json.load(open(sys.argv[1]))
assert doc["reference_mode"] == "builtin" and (doc["width"], doc["height"]) == (160, 120), doc
(r,) = doc["rows"]
assert r["verdict"] == "PASS" and r["same_seed_fraction"] is None and not r["is_reference_device"], r
PY

# (e) Bad options and inputs: exit 2, naming what is wrong; nothing rendered.
expect_usage() {  # expect_usage MESSAGE ARGS...
  local message=$1
  shift
  "$clpt" verify "$@" >bad.out 2>bad.err
  local status=$?
  [[ $status -eq 2 ]] || { fail "verify $* exited $status, expected 2"; show bad.out bad.err; return; }
  grep -qF -- "$message" bad.err || { fail "verify $*: expected '$message'"; show bad.err; }
  grep -q "PASS\|FAIL" bad.out && fail "verify $*: rendered rows"
}
expect_usage "--scenes: bogus not in {diffuse,specular,glass}" --scenes diffuse,bogus
expect_usage "--precisions: quad not in {fast,robust,double}" --precisions robust,quad
expect_usage "--forms: mega not in {megakernel,wavefront}" --forms mega
expect_usage "--device '7': no such device" --device 7
expect_usage "--spp 100: verify renders with the book's grid sampler" --spp 100
expect_usage "--reference: remote not in {auto,device,builtin,films}" --reference remote
expect_usage "reference $work/nowhere/gemspt_glass_160x120.exr: no such file" --reference builtin \
  --reference-dir "$work/nowhere" --scenes glass
expect_usage "--width/--height 64x120: the builtin references are 160x120" --reference builtin --width 64
# Films mode (its end-to-end run is tests/gpu_report_cli.sh): what it needs and what may not clash.
expect_usage "--reference films: --reference-dir names the films' directory" --reference films
expect_usage "--reference films: $work/nowhere/films.json: no such file" --reference films --reference-dir "$work/nowhere"
expect_usage "--save-reference-films: only a PoCL reference device's renders are saved" --reference builtin \
  --save-reference-films "$work"
mkdir -p films && "$clpt" verify --device cpu --reference device --save-reference-films films --scenes diffuse \
  --forms megakernel --precisions robust --width 16 --height 12 --spp 64 -q >films.out 2>&1 ||
  { fail "saving films"; show films.out; }
expect_usage "--spp: the films in films were rendered with 64 spp" --reference films --reference-dir films --spp 128
"$clpt" verify --device cpu --reference films --reference-dir films >films2.out 2>&1
status=$?
[[ $status -eq 0 ]] && grep -q "^verify: 1 of 1 rows passed$" films2.out && grep -q "^skipped: glass, wavefront, double: no reference film" films2.out ||
  { fail "films mode with a subset of the matrix: exit $status"; show films2.out; }
CLPT_INJECT_FAULT=perturb:0:X:1.02 expect_usage "CLPT_INJECT_FAULT='perturb:0:X:1.02': entry 'perturb:0:X:1.02'" \
  --scenes diffuse
# An --json or --save-reference-films in a directory that does not exist: the output error (5),
# before any rendering.
"$clpt" verify --json "$work/nowhere/v.json" >bad.out 2>bad.err
status=$?
[[ $status -eq 5 ]] || fail "verify --json in a missing directory exited $status, expected 5"
grep -qF -- "--json $work/nowhere/v.json: directory '$work/nowhere' does not exist" bad.err ||
  { fail "verify --json in a missing directory: wrong message"; show bad.err; }
grep -q "PASS\|FAIL" bad.out && fail "verify --json in a missing directory: rendered rows"
"$clpt" verify --reference device --save-reference-films "$work/nowhere" >bad.out 2>bad.err
status=$?
[[ $status -eq 5 ]] || fail "verify --save-reference-films in a missing directory exited $status, expected 5"
grep -qF -- "--save-reference-films $work/nowhere: directory '$work/nowhere' does not exist" bad.err ||
  { fail "verify --save-reference-films in a missing directory: wrong message"; show bad.err; }

if [[ $failures -gt 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "all verify CLI checks passed"
