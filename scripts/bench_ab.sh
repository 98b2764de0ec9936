#!/usr/bin/env bash
# bench_ab.sh OLD_CLPT NEW_CLPT ROUNDS [BENCH ARGS...]: the same `clpt bench` matrix run by two
# builds of clpt in turn (old, new, old, new, ...), ROUNDS times each, then per row the median
# over the rounds of each build's paths per CPU-second (and per wall second) and their ratio
# new/old. Alternating, and comparing CPU-seconds, keeps a comparison on a shared machine from
# following its load. Prints one line per row and the worst ratio; exits 1 when a row of the new
# build is more than --tolerance-percent (env CLPT_AB_TOLERANCE, default 3) below the old in paths
# per CPU-second. Each build runs from its own source tree's root (the directory above the
# binary's build directory), so each reads its own scenes. Rows that time the closest hit alone
# (--traversal-alone, --traversal-anchor) also get its rays per CPU-second, new/old per round, and
# with the anchor clpt's ratio to Embree's rtcIntersect1 (not part of the exit status).
#   scripts/bench_ab.sh /work/old/build/clpt build/clpt 5 --scenes scenes/diffuse.toml \
#       --forms megakernel,wavefront --precisions fast,robust,double --estimators book,nee
set -euo pipefail
[[ $# -ge 3 ]] || { echo "usage: scripts/bench_ab.sh OLD_CLPT NEW_CLPT ROUNDS [BENCH ARGS...]" >&2; exit 2; }
[[ -x $1 && -x $2 ]] || { echo "bench_ab.sh: $1 or $2 is not an executable" >&2; exit 2; }
old=$(realpath "$1") new=$(realpath "$2") rounds=$3
shift 3
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
            trace = r.get("trace", {}).get("rays_per_cpu_s")
            anchor = r.get("anchor", {}).get("rtcIntersect1_rays_per_cpu_s")
            out.setdefault(r["key"], []).append((r["paths_per_cpu_s"]["median"], r["paths_per_s"]["median"],
                                                 trace, trace / anchor if trace and anchor else None))
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
# Rows with --traversal-alone (or --traversal-anchor): the closest-hit queries alone (trace.cl),
# rays per CPU-second, each round's new/old and their median; with the anchor, clpt's ratio to
# Embree's rtcIntersect1 in each build's runs (medians). Information, not part of the exit status.
traced = [k for k in sorted(old) if k in new and all(v[2] for v in old[k] + new[k])]
if traced:
    print(f"{'closest hit alone (trace.cl)':90s} {'old Mrays/CPU-s':>16s} {'new':>8s} {'new/old':>8s}  per round")
    for key in traced:
        rounds_ratio = [n[2] / o[2] for o, n in zip(old[key], new[key])]
        line = (f"{key[:90]:90s} {statistics.median(v[2] for v in old[key]) / 1e6:16.3f} "
                f"{statistics.median(v[2] for v in new[key]) / 1e6:8.3f} {statistics.median(rounds_ratio):8.3f}  "
                + " ".join(f"{x:.3f}" for x in rounds_ratio))
        if all(v[3] for v in old[key] + new[key]):
            line += (f"; / rtcIntersect1 {statistics.median(v[3] for v in old[key]):.3f} -> "
                     f"{statistics.median(v[3] for v in new[key]):.3f}")
        print(line)
sys.exit(1 if failed else 0)
PY
