#!/usr/bin/env bash
# The kernel binary cache end to end, from an empty CLPT_CACHE_DIR: two renders at once both
# succeed and leave one complete entry (no half-written file seen, no temporary left), a third
# render reports a cache hit, --no-cache compiles, and `clpt cache clear` empties the directory.
#   cache_cli.sh CLPT SOURCE_DIR WORK_DIR
set -euo pipefail
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$src"
export CLPT_CACHE_DIR=$work/cache
args=(scenes/diffuse.toml --width 32 --height 24 --spp 16)

"$clpt" render "${args[@]}" -q -o "$work/a.pfm" 2> "$work/a.err" & a=$!
"$clpt" render "${args[@]}" -q -o "$work/b.pfm" 2> "$work/b.err" & b=$!
wait $a || { echo "FAIL: first concurrent render"; cat "$work/a.err"; exit 1; }
wait $b || { echo "FAIL: second concurrent render"; cat "$work/b.err"; exit 1; }
if grep -q "kernel cache" "$work/a.err" "$work/b.err"; then
  echo "FAIL: a concurrent render saw a damaged entry or could not store one"; cat "$work"/*.err; exit 1
fi
test "$(find "$CLPT_CACHE_DIR" -name '*.bin' | wc -l)" -eq 1
test "$(find "$CLPT_CACHE_DIR" -name '*clpt-tmp*' | wc -l)" -eq 0

"$clpt" render "${args[@]}" -o "$work/c.pfm" > "$work/hit.txt"
grep -Eq "kernel build [0-9.]+ s \(clpt cache hit\)" "$work/hit.txt" ||
  { echo "FAIL: the third render did not hit the cache"; cat "$work/hit.txt"; exit 1; }
"$clpt" render "${args[@]}" --no-cache -o "$work/d.pfm" > "$work/nocache.txt"
grep -Eq "kernel build [0-9.]+ s \(compiled\)" "$work/nocache.txt" ||
  { echo "FAIL: --no-cache did not compile"; cat "$work/nocache.txt"; exit 1; }

test "$("$clpt" cache dir)" = "$CLPT_CACHE_DIR"
"$clpt" cache clear > "$work/clear.txt"
grep -q "^removed 1 kernel cache entry from $CLPT_CACHE_DIR\$" "$work/clear.txt" ||
  { echo "FAIL: cache clear"; cat "$work/clear.txt"; exit 1; }
test "$(find "$CLPT_CACHE_DIR" -name '*.bin' | wc -l)" -eq 0
echo "cache CLI: concurrent renders, hit, --no-cache and clear all as expected"
