#!/usr/bin/env bash
# Interrupts and checkpoints end to end:
#  * SIGINT mid-render: exit 130, OUT.exr and OUT.png of the finished passes (clpt:spp > 0,
#    clpt:interrupted = 1), a checkpoint that resumes, and no temporary file left;
#  * a second signal: exit 130 at once, nothing written;
#  * --checkpoint at 32 spp, then --resume to 64 spp equals a straight 64 spp render.
#   interrupt_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
scene="$src/scenes/diffuse.toml"
small=(--width 64 --height 48 --sampler jitter)
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# start_long ERR_FILE ARGS...: a long render in the background; sets $pid once its first pass
# is done (the progress line appears) and at least 3 s have passed, so the handlers are in place.
start_long() {
  local err=$1
  shift
  "$clpt" render "$scene" "${small[@]}" --spp 100000 --progress "$@" >/dev/null 2>"$err" &
  pid=$!
  local waited=0
  while ! grep -q "pass" "$err" 2>/dev/null || [[ $waited -lt 30 ]]; do
    sleep 0.1
    waited=$((waited + 1))
    [[ $waited -gt 600 ]] && { fail "no progress after 60 s: $(cat "$err")"; break; }
  done
}

# wait_exit PID: the exit status, or 255 (and the process killed) after 60 s.
wait_exit() {
  local waited=0
  while kill -0 "$1" 2>/dev/null && [[ $waited -lt 600 ]]; do sleep 0.1; waited=$((waited + 1)); done
  kill -0 "$1" 2>/dev/null && { kill -KILL "$1"; fail "clpt did not stop within 60 s"; }
  wait "$1"
}

no_temporaries() {
  local left
  left=$(find . -name '*clpt-tmp*')
  [[ -z "$left" ]] || fail "temporary files left: $left"
}

# 1. One SIGINT: the finished passes are written, with a checkpoint.
start_long err1.txt -o int.exr --checkpoint int.ckpt
kill -INT "$pid"
wait_exit "$pid"
status=$?
[[ $status -eq 130 ]] || fail "interrupted render exited $status, expected 130: $(cat err1.txt)"
grep -q "interrupted" err1.txt || fail "no note about the interrupt: $(cat err1.txt)"
[[ -s int.exr && -s int.png ]] || fail "int.exr or int.png missing"
info=$(oiiotool --info -v int.exr) || fail "oiiotool cannot read int.exr"
oiiotool --info int.png >/dev/null || fail "oiiotool cannot read int.png"
spp=$(sed -n 's/.*clpt:spp: "\([0-9]*\)".*/\1/p' <<<"$info")
[[ -n "$spp" && "$spp" -gt 0 ]] || fail "clpt:spp is '$spp', expected > 0"
grep -q 'clpt:interrupted: "1"' <<<"$info" || fail "clpt:interrupted is not 1"
echo "ok: SIGINT -> 130 with $spp spp written"
"$clpt" render "$scene" "${small[@]}" --spp $((spp + 4)) --resume int.ckpt -q -o int_resumed.pfm ||
  fail "resuming the interrupt's checkpoint exited $?"
no_temporaries

# 2. A second signal (SIGTERM right after SIGINT): exit at once, nothing written.
start_long err2.txt -o twice.exr
kill -INT "$pid"
kill -TERM "$pid"
wait_exit "$pid"
status=$?
[[ $status -eq 130 ]] || fail "twice-interrupted render exited $status, expected 130"
[[ ! -e twice.exr && ! -e twice.png ]] || fail "a twice-interrupted render wrote its outputs"
no_temporaries
echo "ok: second signal -> 130, nothing written"

# 3. Checkpoint at 32 spp, resume to 64: the image of a straight 64 spp render.
"$clpt" render "$scene" "${small[@]}" --spp 32 --checkpoint half.ckpt -q -o half.exr || fail "checkpointed render"
"$clpt" render "$scene" "${small[@]}" --spp 64 --resume half.ckpt -q -o resumed.exr || fail "resumed render"
"$clpt" render "$scene" "${small[@]}" --spp 64 -q -o straight.exr || fail "straight render"
"$clpt" compare resumed.exr straight.exr --same-seed >compare.txt 2>&1 ||
  fail "resumed and straight renders differ: $(cat compare.txt)"
grep -q 'clpt:spp: "64"' <<<"$(oiiotool --info -v resumed.exr)" || fail "resumed.exr lacks clpt:spp 64"
no_temporaries
echo "ok: checkpoint at 32 spp + resume to 64 == straight 64 spp"

if [[ $failures -ne 0 ]]; then
  echo "$failures interrupt case(s) failed"
  exit 1
fi
