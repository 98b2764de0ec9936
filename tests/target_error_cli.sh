#!/usr/bin/env bash
# `clpt render --target-error` end to end:
#  * it stops at the target: exit 0, the summary says so, the progress line shows the estimate
#    and the target, and the EXR records clpt:error_estimate (<= the target), clpt:target_error
#    and clpt:stop;
#  * a Sobol render's plan splits its half-films as a power of two first, without a target error
#    only;
#  * with --spp, whichever comes first: a small --spp stops at the sample count;
#  * a checkpointed target render resumes (a checkpoint with its half-films);
#  * --adaptive: a render interrupted at a round's end (32 spp) and resumed to 64 has the film of
#    a straight 64-spp render, bit for bit (adaptive passes are sized by the image alone); the
#    EXR records clpt:adaptive; resuming an adaptive checkpoint without --adaptive is refused;
#  * adaptive and uniform renders of the three book scenes at equal total samples (512, nee,
#    64x48, other seeds) pass `clpt compare`'s statistical test against each other.
#   target_error_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
scene="$src/scenes/diffuse.toml"
small=(--width 32 --height 24 --estimator nee --sampler jitter --seed 5)
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
meta() { oiiotool --info -v "$1" | grep "$2"; }

# 1. Stops at the target.
"$clpt" render "$scene" "${small[@]}" --target-error 0.2 --progress -o t.exr >out.txt 2>err.txt ||
  fail "--target-error 0.2 exited $?: $(cat err.txt)"
grep -q "stopped at the target error" out.txt || fail "summary lacks the stop: $(cat out.txt)"
grep -q "target 20.00%" err.txt || fail "progress line lacks the target: $(cat err.txt)"
grep -q "error [0-9.]*% (target" err.txt || fail "progress line lacks the estimate: $(cat err.txt)"
estimate=$(meta t.exr 'clpt:error_estimate' | sed 's/.*: "\(.*\)"/\1/')
python3 -c "import sys; e = float(sys.argv[1]); sys.exit(0 if 0 < e <= 0.2 else 1)" "$estimate" ||
  fail "clpt:error_estimate '$estimate' is not in (0, 0.2]"
meta t.exr 'clpt:target_error: "0.2"' >/dev/null || fail "t.exr lacks clpt:target_error 0.2"
meta t.exr 'clpt:stop: "target error"' >/dev/null || fail "t.exr lacks clpt:stop \"target error\""

# 1b. A Sobol render splits its half-films as a power of two first, unless it has a target error
# (equal halves there: the error estimate's), and --explain says which.
sobol=(--width 32 --height 24 --estimator nee --seed 5 --sampler sobol)
"$clpt" render "$scene" "${sobol[@]}" --spp 6 --explain -q -o p.exr >p.txt 2>&1 || fail "--sampler sobol --spp 6 exited $?"
grep -q "half-films of 4 and 2 spp" p.txt || fail "no 4 + 2 split in the plan: $(cat p.txt)"
"$clpt" render "$scene" "${sobol[@]}" --spp 6 --target-error 0.001 --explain -q -o q.exr >q.txt 2>&1 ||
  fail "--sampler sobol --target-error exited $?"
grep -q "half-films of" q.txt && fail "a target-error render printed a power-of-two split: $(cat q.txt)"

# 2. With --spp, whichever comes first.
"$clpt" render "$scene" "${small[@]}" --target-error 0.001 --spp 4 -q -o s.exr || fail "--spp 4 exited $?"
meta s.exr 'clpt:spp: "4"' >/dev/null || fail "s.exr is not 4 spp"
meta s.exr 'clpt:stop: "sample count"' >/dev/null || fail "s.exr lacks clpt:stop \"sample count\""

# 3. A checkpoint of a target render resumes to a longer one.
"$clpt" render "$scene" "${small[@]}" --spp 8 --checkpoint c.ckpt -q -o c.exr || fail "checkpointed render"
"$clpt" render "$scene" "${small[@]}" --target-error 0.2 --resume c.ckpt -q -o r.exr || fail "resumed target render"
meta r.exr 'clpt:stop: "target error"' >/dev/null || fail "the resumed render did not stop at the target"

# 4. Adaptive: straight and resumed renders draw the same samples in the same passes.
"$clpt" render "$scene" "${small[@]}" --adaptive --spp 64 -q -o a64.exr --checkpoint a64.ckpt || fail "--adaptive 64 spp"
"$clpt" render "$scene" "${small[@]}" --adaptive --spp 32 -q -o a32.pfm --checkpoint a32.ckpt || fail "--adaptive 32 spp"
"$clpt" render "$scene" "${small[@]}" --adaptive --spp 64 -q -o ar.pfm --resume a32.ckpt --checkpoint ar.ckpt ||
  fail "--adaptive resumed to 64 spp"
cmp -s a64.ckpt ar.ckpt || fail "--adaptive: the resumed film differs from the straight one"
meta a64.exr 'clpt:adaptive: "1"' >/dev/null || fail "a64.exr lacks clpt:adaptive 1"
"$clpt" render "$scene" "${small[@]}" --spp 64 -q -o x.pfm --resume a32.ckpt 2>x.err
[[ $? -eq 2 ]] && grep -q "adaptively" x.err || fail "resuming an adaptive checkpoint without --adaptive: $(cat x.err)"

for name in diffuse specular glass; do
  common=("$src/scenes/$name.toml" --width 64 --height 48 --estimator nee --sampler jitter --spp 512 -q)
  "$clpt" render "${common[@]}" --seed 3 --adaptive -o adaptive_$name.exr || fail "$name: adaptive render"
  "$clpt" render "${common[@]}" --seed 4 -o uniform_$name.exr || fail "$name: uniform render"
  "$clpt" compare adaptive_$name.exr uniform_$name.exr >compare_$name.txt ||
    { fail "$name: adaptive and uniform renders differ"; cat compare_$name.txt; }
done

if [[ $failures -ne 0 ]]; then
  echo "$failures target-error case(s) failed"
  exit 1
fi
echo "ok: --target-error stops at the target, records it, and resumes"
