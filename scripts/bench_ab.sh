#!/usr/bin/env bash
# bench_ab.sh OLD_CLPT NEW_CLPT ROUNDS [BENCH ARGS...]: the same `clpt bench` matrix run by two
# builds of clpt in turn (old, new, old, new, ...), ROUNDS times each, then per row the median
# over the rounds of each build's paths per CPU-second (and per wall second) and their ratio
# new/old. Alternating, and comparing CPU-seconds, keeps a comparison on a shared machine from
# following its load. Prints one line per row and the worst ratio; exits 1 when a row of the new
# build is more than --tolerance-percent (env CLPT_AB_TOLERANCE, default 3) below the old in paths
# per CPU-second. Each build runs from its own source tree's root (the directory above the
# binary's build directory), so each reads its own scenes.
#   scripts/bench_ab.sh /work/old/build/clpt build/clpt 5 --scenes scenes/diffuse.toml \
#       --forms megakernel,wavefront --precisions fast,robust,double --estimators book,nee
set -euo pipefail
[[ $# -ge 3 ]] || { echo "usage: scripts/bench_ab.sh OLD_CLPT NEW_CLPT ROUNDS [BENCH ARGS...]" >&2; exit 2; }
old=$(realpath "$1") new=$(realpath "$2") rounds=$3
shift 3
[[ -x $old && -x $new ]] || { echo "bench_ab.sh: $1 or $2 is not an executable" >&2; exit 2; }
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "bench_ab.sh: ROUNDS must be a positive integer" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tree_of() { dirname "$(dirname "$1")"; }
for ((i = 1; i <= rounds; ++i)); do
  for side in old new; do
    binary=${!side}
    (cd "$(tree_of "$binary")" && "$binary" bench "$@" --json "$work/$side.$i.json" >/dev/null) ||
      { echo "bench_ab.sh: the $side build's bench failed (round $i)" >&2; exit 1; }
  done
  echo "round $i of $rounds done" >&2
done
python3 - "$work" "$rounds" "${CLPT_AB_TOLERANCE:-3}" <<'PY'
import json, statistics, sys
work, rounds, tolerance = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
def rows(side):
    out = {}
    for i in range(1, rounds + 1):
        for r in json.load(open(f"{work}/{side}.{i}.json"))["rows"]:
            out.setdefault(r["key"], []).append((r["paths_per_cpu_s"]["median"], r["paths_per_s"]["median"]))
    return out
old, new = rows("old"), rows("new")
worst, failed = None, False
print(f"{'row':90s} {'old Mpaths/CPU-s':>16s} {'new':>8s} {'new/old':>8s} {'(wall)':>8s}")
for key in sorted(old):
    if key not in new:
        print(f"{key:90s} only in the old build's rows"); continue
    oc = statistics.median(v[0] for v in old[key]); nc = statistics.median(v[0] for v in new[key])
    ow = statistics.median(v[1] for v in old[key]); nw = statistics.median(v[1] for v in new[key])
    ratio = nc / oc
    worst = ratio if worst is None else min(worst, ratio)
    flag = "  BELOW" if ratio < 1 - tolerance / 100 else ""
    failed = failed or bool(flag)
    print(f"{key[:90]:90s} {oc / 1e6:16.3f} {nc / 1e6:8.3f} {ratio:8.3f} {nw / ow:8.3f}{flag}")
print(f"worst new/old in paths per CPU-second: {worst:.3f} (tolerance {tolerance:g}%)")
sys.exit(1 if failed else 0)
PY
