#!/usr/bin/env bash
# `clpt tradeoff` end to end: a small reference (32x24, 256 spp), then two combinations
# (megakernel, wavefront) at two tiny budgets plus a --target-from render write a well-formed CSV
# (the exact header, one row per run, numeric fields that parse) and a PNG plot (PNG magic, the
# expected size); -o .json writes valid JSON. Bad input (missing reference, size mismatch, a
# reference without variance channels, bad --precision, wrong-type -o, a bad --target-from, the
# reference's seed, no gnuplot on PATH) exits 2 naming the option, and an -o in a directory that
# does not exist exits 5 (the output error), before rendering, writing nothing.
#   tradeoff_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work/inputs" "$work/out" && cd "$work" || exit 1
scene="$src/scenes/diffuse.toml"
# PoCL otherwise compiles a work-group function for each new launch size of the megakernel (about
# 1 s each on this machine), which only makes the test slower.
export POCL_WORK_GROUP_SPECIALIZATION=0
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$clpt" render "$scene" --width 32 --height 24 --spp 256 --sampler jitter --seed 1 -q -o inputs/ref.exr ||
  { echo "FAIL: reference render exited $?"; exit 1; }
size=(--width 32 --height 24 --sampler jitter)

# --- A measurement: CSV and plot ------------------------------------------------------------------
"$clpt" tradeoff "$scene" --reference inputs/ref.exr "${size[@]}" --form megakernel,wavefront \
  --budgets 0.05,0.1 --target-from book@16 -o out/runs.csv --plot out/plot.png >stdout.txt 2>stderr.txt
status=$?
[[ $status -eq 0 ]] || { fail "tradeoff exited $status"; cat stdout.txt stderr.txt; }
grep -q "noise RMS" stdout.txt || fail "stdout lacks the reference's noise: $(cat stdout.txt)"
grep -q "time to reach an RMSE" stdout.txt || fail "stdout lacks the time-to-reach table"
grep -q "(--target-from)" stdout.txt || fail "the table lacks the --target-from target"
python3 - out/runs.csv <<'EOF' || fail "runs.csv is not the expected CSV"
import csv, math, sys
expected = ("run,combination,precision,estimator,form,device,budget_s,render_s,build_s,spp,paths,paths_per_s,"
            "rmse,relative_mse,mse,noise_render,noise_reference,noise,bias_sq,bias_sq_stderr,bias_rms,"
            "dropped_samples").split(",")
rows = list(csv.reader(open(sys.argv[1], newline="")))
assert rows[0] == expected, rows[0]
body = rows[1:]
# 2 forms x 2 budgets, then the --target-from render
assert len(body) == 5, len(body)
assert sorted({r[4] for r in body[:4]}) == ["megakernel", "wavefront"], body
assert [r[0] for r in body] == ["budget"] * 4 + ["fixed_spp"], [r[0] for r in body]
assert body[4][9] == "16" and body[4][6] == "", body[4]
for r in body:
    assert len(r) == len(expected), r
    for name, value in zip(expected, r):
        if name in ("run", "combination", "precision", "estimator", "form", "device"):
            continue
        if value == "" and name in ("budget_s",):
            continue
        x = float(value)
        assert math.isfinite(x) and x >= 0, (name, value)
    assert float(r[12]) > 0 and int(r[9]) >= 2 and float(r[11]) > 0, r
print("ok: runs.csv has the header and 5 well-formed rows")
EOF
head -c 8 out/plot.png | od -An -tx1 | tr -d ' \n' | grep -q '^89504e470d0a1a0a$' || fail "plot.png lacks the PNG magic"
oiiotool --info out/plot.png 2>/dev/null | grep -q "900 x  *600" || fail "plot.png is not 900x600: $(oiiotool --info out/plot.png)"
[[ -z "$(ls -A out | grep -v -x -e runs.csv -e plot.png)" ]] || fail "temporary files left: $(ls -A out)"

# --- JSON -------------------------------------------------------------------------------------------
"$clpt" tradeoff "$scene" --reference inputs/ref.exr "${size[@]}" --form wavefront --budgets 0.05 \
  --target-rmse 0.5 -q -o out/runs.json >stdout.txt 2>stderr.txt || fail "tradeoff -o runs.json exited $?"
python3 - out/runs.json <<'EOF' || fail "runs.json is not the expected JSON"
import json, sys
j = json.load(open(sys.argv[1]))
assert len(j["runs"]) == 1 and j["runs"][0]["form"] == "wavefront", j["runs"]
assert j["reference"]["width"] == 32 and j["reference"]["spp"] == 256, j["reference"]
t = j["targets"][0]
assert t["rmse"] == 0.5 and t["time_to_reach"][0]["status"] in ("interpolated", "at_or_before_smallest_budget"), t
# One combination: nothing can dominate it, and it says so with an empty list.
assert [c["dominated_by"] for c in j["combinations"]] == [[]], j["combinations"]
print("ok: runs.json")
EOF

# --- Adaptive sampling as a dimension: both curves, their labels in the table and JSON --------------
"$clpt" tradeoff "$scene" --reference inputs/ref.exr "${size[@]}" --estimator nee --adaptive off,on --budgets 0.05 \
  --target-rmse 0.5 -o out/adaptive.json >stdout.txt 2>stderr.txt || fail "tradeoff --adaptive off,on exited $?"
python3 - out/adaptive.json <<'EOF' || fail "adaptive.json lacks the two combinations"
import json, sys
j = json.load(open(sys.argv[1]))
labels = sorted({r["combination"] for r in j["runs"]})
assert len(labels) == 2 and any("/adaptive/" in l for l in labels) and any("/adaptive/" not in l for l in labels), labels
print("ok: adaptive.json has both combinations")
EOF
grep -q "/adaptive/dev" stdout.txt || fail "the time-to-reach table lacks the adaptive combination: $(cat stdout.txt)"
rm -f out/adaptive.json

# --- Bad input --------------------------------------------------------------------------------------
oiiotool inputs/ref.exr --ch R,G,B -o inputs/rgb.exr || fail "oiiotool could not make rgb.exr"
# expect CODE SUBSTRING ARGS...: exits CODE, stderr holds SUBSTRING, nothing written to out2/.
expect() {
  local code=$1 needle=$2
  shift 2
  rm -rf out2 && mkdir out2
  local err status
  err=$("$clpt" tradeoff "$@" 2>&1 >/dev/null)
  status=$?
  if [[ $status -ne $code ]]; then
    fail "clpt tradeoff $* exited $status, expected $code; stderr: $err"
  elif [[ "$err" != *"$needle"* ]]; then
    fail "clpt tradeoff $*: stderr lacks '$needle'; got: $err"
  elif [[ -n "$(ls -A out2)" ]]; then
    fail "clpt tradeoff $* left files: $(ls -A out2)"
  else
    echo "ok: clpt tradeoff $* -> $status ($needle)"
  fi
}
ok_args=("${size[@]}" --budgets 0.05 -o out2/runs.csv --plot out2/plot.png)
expect 2 "--reference inputs/missing.exr: no such file" "$scene" --reference inputs/missing.exr "${ok_args[@]}"
expect 2 "--reference inputs/ref.exr is 32x24 but the renders are 16x24" \
  "$scene" --reference inputs/ref.exr --width 16 --height 24 --budgets 0.05 -o out2/runs.csv
expect 2 "no channel 'variance.R'" "$scene" --reference inputs/rgb.exr "${ok_args[@]}"
expect 2 "--precision" "$scene" --reference inputs/ref.exr "${ok_args[@]}" --precision robust,quad
expect 5 "-o out2/no/such/dir/runs.csv: directory 'out2/no/such/dir' does not exist" \
  "$scene" --reference inputs/ref.exr "${size[@]}" --budgets 0.05 -o out2/no/such/dir/runs.csv
expect 2 "-o out2/runs.txt: the output must be a .csv or a .json" \
  "$scene" --reference inputs/ref.exr "${size[@]}" --budgets 0.05 -o out2/runs.txt
expect 2 "--target-from book@0" "$scene" --reference inputs/ref.exr "${ok_args[@]}" --target-from book@0
expect 2 "--seed 1: the reference" "$scene" --reference inputs/ref.exr "${ok_args[@]}" --seed 1
# Without gnuplot, --plot fails before any rendering (PATH emptied for clpt alone).
rm -rf out2 && mkdir out2
err=$(PATH=/nonexistent "$clpt" tradeoff "$scene" --reference inputs/ref.exr "${ok_args[@]}" 2>&1 >/dev/null)
status=$?
if [[ $status -eq 2 && "$err" == *"gnuplot is not on PATH"* && -z "$(ls -A out2)" ]]; then
  echo "ok: no gnuplot on PATH -> 2"
else
  fail "no gnuplot on PATH: exit $status, stderr: $err, files: $(ls -A out2)"
fi

if [[ $failures -ne 0 ]]; then
  echo "$failures tradeoff case(s) failed"
  exit 1
fi
echo "all tradeoff cases passed"
