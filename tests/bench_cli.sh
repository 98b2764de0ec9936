#!/usr/bin/env bash
# clpt bench end to end: a tiny matrix (both forms, both megakernel loops) writes a table and a
# JSON holding every field, passes
# against its own results as baseline, and fails (exit 1, REGRESSION) against a baseline that
# claims 1000 times the speed.
#   bench_cli.sh CLPT SOURCE_DIR WORK_DIR
set -euo pipefail
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$src"
common=(--width 32 --height 24 --spp 2 --warmup 0 --repeat 2 --devices cpu --forms megakernel,wavefront
        --megakernel-loops lockstep,path)

"$clpt" bench "${common[@]}" --json "$work/bench.json" > "$work/table.txt"
grep -q "megakernel" "$work/table.txt" && grep -q "wavefront" "$work/table.txt"
python3 - "$work/bench.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
rows = doc["rows"]
assert len(rows) == 3, rows  # megakernel (lockstep, per path) and the wavefront once
fields = {"key", "scene", "form", "loop", "kernel", "precision", "estimator", "device", "local_size", "paths_in_flight", "build_cold_s",
          "build_cached_s", "paths_per_s", "segments_per_s", "stage_seconds"}
for r in rows:
    missing = fields - r.keys()
    assert not missing, missing
    for s in ("paths_per_s", "segments_per_s"):
        assert r[s]["min"] <= r[s]["median"] <= r[s]["max"] and r[s]["median"] > 0, r[s]
assert sorted(r["loop"] for r in rows) == ["", "lockstep", "path"], rows
assert len({r["key"] for r in rows}) == 3, rows
lockstep = [r for r in rows if r["loop"] == "lockstep"][0]
assert lockstep["local_size"] == 64, lockstep  # the lockstep loop's default work-group
wf = [r for r in rows if r["form"] == "wavefront"][0]
assert {"generate", "intersect", "shade", "film"} <= wf["stage_seconds"].keys(), wf
# A baseline 1000 times faster than measured: every row must be a regression, however noisy
# the machine (a timing ratio of 1000 cannot come from load).
for r in rows:
    r["paths_per_s"]["median"] *= 1000
json.dump(doc, open(sys.argv[1].replace("bench.json", "faster.json"), "w"))
PY
# A 100% tolerance accepts any speed; the 1000x baseline at 10% must fail.
"$clpt" bench "${common[@]}" --baseline "$work/bench.json" --tolerance 100 > "$work/same.txt"
if "$clpt" bench "${common[@]}" --baseline "$work/faster.json" --tolerance 10 > "$work/slower.txt"; then
  echo "FAIL: a baseline 1000x faster did not fail"; exit 1
fi
test "$(grep -c REGRESSION "$work/slower.txt")" -eq 3
echo "bench CLI: table, JSON fields, baseline pass and regression all as expected"
