#!/usr/bin/env bash
# scripts/bench_ab.sh end to end on one build against itself (one round, a tiny Cornell box render
# with its closest-hit queries timed alone): the paths table with a ratio for the row and the worst
# ratio, the closest-hit table with its per-round ratio, exit 0 with a tolerance no noise can
# break; a missing binary or a bad round count is a usage error (exit 2).
#   bench_ab_cli.sh CLPT SOURCE_DIR WORK_DIR
set -euo pipefail
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
ab="$src/scripts/bench_ab.sh"
status=0
"$ab" "$work/no-such-clpt" "$clpt" 1 > /dev/null 2>&1 || status=$?
test "$status" -eq 2 || { echo "FAIL: a missing binary exited $status, not 2"; exit 1; }
status=0
"$ab" "$clpt" "$clpt" 0 > /dev/null 2>&1 || status=$?
test "$status" -eq 2 || { echo "FAIL: ROUNDS 0 exited $status, not 2"; exit 1; }
CLPT_AB_TOLERANCE=99 "$ab" "$clpt" "$clpt" 1 --scenes "$src/scenes/cornell-box.toml" --traversal-alone --devices cpu \
  --forms megakernel --width 16 --height 16 --spp 1 --warmup 0 --repeat 1 --no-vector-width > "$work/ab.txt" 2> "$work/ab.err"
grep -q "cornell-box.toml|megakernel" "$work/ab.txt" || { cat "$work/ab.txt" "$work/ab.err"; exit 1; }
grep -q "^worst new/old in paths per CPU-second: [0-9.]* (tolerance 99%)" "$work/ab.txt" || { cat "$work/ab.txt"; exit 1; }
grep -q "^closest hit alone (trace.cl) .*old Mrays/CPU-s" "$work/ab.txt" || { cat "$work/ab.txt"; exit 1; }
grep -Eq "cornell-box.toml\|megakernel.* [0-9]+\.[0-9]{3} +[0-9]+\.[0-9]{3} +[0-9]+\.[0-9]{3}  [0-9]+\.[0-9]{3}$" "$work/ab.txt" ||
  { cat "$work/ab.txt"; exit 1; }
echo "bench_ab.sh: usage errors, the paths table and the closest-hit table as expected"
