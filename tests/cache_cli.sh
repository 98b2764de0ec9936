#!/usr/bin/env bash
# The kernel binary cache end to end, from an empty CLPT_CACHE_DIR, on Oclgrind (PoCL keeps its
# own cache and clpt stores none of its binaries, cl_device.h): two renders at once both succeed
# and leave one complete entry (no half-written file seen, no temporary left), a third render
# reports a cache hit, --no-cache compiles, a PoCL render stores nothing and says why under
# --explain, and `clpt cache clear` empties the directory. Oclgrind and PoCL are exposed through
# a vendors directory of the test's own (OCL_ICD_VENDORS) unless ctest set one.
#   cache_cli.sh CLPT SOURCE_DIR WORK_DIR
set -euo pipefail
clpt=$1 src=$2 work=$3
oclgrind_icd=/usr/lib/oclgrind/liboclgrind-rt-icd.so
pocl_icd=/etc/OpenCL/vendors/pocl.icd
if [[ ! -f $oclgrind_icd || ! -f $pocl_icd ]]; then
  echo "FAIL: needs $oclgrind_icd (Debian package oclgrind) and $pocl_icd (pocl-opencl-icd)"
  exit 1
fi
rm -rf "$work" && mkdir -p "$work" && cd "$src"
if [[ -z ${OCL_ICD_VENDORS:-} ]]; then
  mkdir "$work/vendors" && cp "$pocl_icd" "$work/vendors/pocl.icd" && echo "$oclgrind_icd" >"$work/vendors/oclgrind.icd"
  export OCL_ICD_VENDORS="$work/vendors"
fi
export CLPT_CACHE_DIR=$work/cache
unset POCL_DEVICES
# Oclgrind simulates a few hundred paths/s: 8x6 pixels, 1 jittered sample each.
args=(scenes/diffuse.toml --width 8 --height 6 --spp 1 --sampler jitter)

"$clpt" render "${args[@]}" --device cpu --explain -o "$work/p.pfm" > "$work/pocl.txt"
grep -q "kernel cache: the driver's own" "$work/pocl.txt" ||
  { echo "FAIL: --explain on PoCL does not say its own cache serves"; cat "$work/pocl.txt"; exit 1; }
test "$(find "$work" -name '*.bin' | wc -l)" -eq 0 ||
  { echo "FAIL: a PoCL render stored a binary"; find "$work" -name '*.bin'; exit 1; }

"$clpt" render "${args[@]}" --device oclgrind -q -o "$work/a.pfm" 2> "$work/a.err" & a=$!
"$clpt" render "${args[@]}" --device oclgrind -q -o "$work/b.pfm" 2> "$work/b.err" & b=$!
wait $a || { echo "FAIL: first concurrent render"; cat "$work/a.err"; exit 1; }
wait $b || { echo "FAIL: second concurrent render"; cat "$work/b.err"; exit 1; }
if grep -q "kernel cache" "$work/a.err" "$work/b.err"; then
  echo "FAIL: a concurrent render saw a damaged entry or could not store one"; cat "$work"/*.err; exit 1
fi
test "$(find "$CLPT_CACHE_DIR" -name '*.bin' | wc -l)" -eq 1
test "$(find "$CLPT_CACHE_DIR" -name '*clpt-tmp*' | wc -l)" -eq 0

"$clpt" render "${args[@]}" --device oclgrind -o "$work/c.pfm" > "$work/hit.txt"
grep -Eq "kernel build [0-9.]+ s \(clpt cache hit\)" "$work/hit.txt" ||
  { echo "FAIL: the third render did not hit the cache"; cat "$work/hit.txt"; exit 1; }
"$clpt" render "${args[@]}" --device oclgrind --no-cache -o "$work/d.pfm" > "$work/nocache.txt"
grep -Eq "kernel build [0-9.]+ s \(compiled\)" "$work/nocache.txt" ||
  { echo "FAIL: --no-cache did not compile"; cat "$work/nocache.txt"; exit 1; }

test "$("$clpt" cache dir)" = "$CLPT_CACHE_DIR"
"$clpt" cache clear > "$work/clear.txt"
grep -q "^removed 1 kernel cache entry from $CLPT_CACHE_DIR\$" "$work/clear.txt" ||
  { echo "FAIL: cache clear"; cat "$work/clear.txt"; exit 1; }
test "$(find "$CLPT_CACHE_DIR" -name '*.bin' | wc -l)" -eq 0
echo "cache CLI: concurrent renders, hit, --no-cache, none on PoCL and clear all as expected"
