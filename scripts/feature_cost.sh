#!/usr/bin/env bash
# feature_cost.sh CLPT [ROUNDS]: what textures and the environment light cost in paths/s on the
# default device, measured against twins of the same scenes without them (docs/textures.md,
# "Cost", and docs/environment.md, "What it costs"): scenes/textured-room.toml against a copy whose four textures are
# constants of about their mean colour (floor base colour [0.45, 0.3, 0.18], roughness 0.5, no
# normal map; wall [0.2, 0.5, 0.55]), and scenes/environment.toml (the HDR sky, sampled by nee)
# against copies whose environment is a constant colour [0.3, 0.4, 0.6] and black. ROUNDS
# (default 3) runs of one `clpt bench` over all five scenes, both forms, nee, robust, 160x120,
# 16 spp; per row the median over the rounds of paths/s and paths per CPU-second, and the ratios.
#   scripts/feature_cost.sh build/clpt 5
set -euo pipefail
[[ $# -ge 1 ]] || { echo "usage: scripts/feature_cost.sh CLPT [ROUNDS]" >&2; exit 2; }
clpt=$(realpath "$1") rounds=${2:-3}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "feature_cost.sh: ROUNDS must be a positive integer" >&2; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
cd "$root/scenes"
# The twins sit beside the originals (their relative image paths resolve), under names of their own.
untextured=.cost-untextured-room.toml constant=.cost-environment-constant.toml black=.cost-environment-black.toml
trap 'rm -rf "$work"; rm -f "$root/scenes/$untextured" "$root/scenes/$constant" "$root/scenes/$black"' EXIT
sed -e 's|^base_color = { texture = "textures/parquet.png", uv_scale = 4 }$|base_color = [0.45, 0.3, 0.18]|' \
    -e 's|^roughness = { texture = "textures/parquet_roughness.png", uv_scale = 4 }$|roughness = 0.5|' \
    -e '/^normal_map = /d' \
    -e 's|reflectance = { texture = "textures/tiles.png", uv_scale = \[1, 1\] }|reflectance = [0.2, 0.5, 0.55]|' \
    textured-room.toml >"$untextured"
sed -e 's|^file = "environment-sky.hdr".*$|color = [0.3, 0.4, 0.6]|' environment.toml >"$constant"
sed -e 's|^file = "environment-sky.hdr".*$|color = [0.0, 0.0, 0.0]|' environment.toml >"$black"
for f in "$untextured" "$constant" "$black"; do
  ! grep -q 'texture =\|^file = ' "$f" || { echo "feature_cost.sh: $f still names an image (scenes changed?)" >&2; exit 1; }
done
for ((i = 1; i <= rounds; ++i)); do
  "$clpt" bench --no-vector-width --scenes "textured-room.toml,$untextured,environment.toml,$constant,$black" \
      --forms megakernel,wavefront --estimators nee --width 160 --height 120 --spp 16 --warmup 1 --repeat 3 \
      --json "$work/$i.json" >/dev/null
  echo "round $i of $rounds done" >&2
done
python3 - "$work" "$rounds" "$untextured" "$constant" "$black" <<'PY'
import json, statistics, sys
work, rounds, untextured, constant, black = sys.argv[1], int(sys.argv[2]), *sys.argv[3:]
rates = {}
for i in range(1, rounds + 1):
    for r in json.load(open(f"{work}/{i}.json"))["rows"]:
        rates.setdefault((r["scene"], r["form"]), []).append((r["paths_per_s"]["median"], r["paths_per_cpu_s"]["median"]))
def med(scene, form, k):
    return statistics.median(v[k] for v in rates[(scene, form)])
names = {"textured-room.toml": "textured room", untextured: "  the same, untextured",
         "environment.toml": "environment: HDR sky", constant: "  constant colour", black: "  black"}
print(f"{'scene':26s} {'form':11s} {'M paths/s':>10s} {'M paths/CPU-s':>14s}")
for scene in names:
    for form in ("megakernel", "wavefront"):
        print(f"{names[scene]:26s} {form:11s} {med(scene, form, 0) / 1e6:10.3f} {med(scene, form, 1) / 1e6:14.3f}")
for form in ("megakernel", "wavefront"):
    for a, b, what in (("textured-room.toml", untextured, "textured / untextured"),
                       ("environment.toml", constant, "HDR sky / constant colour"),
                       ("environment.toml", black, "HDR sky / black")):
        print(f"{form:11s} {what:26s} paths/s {med(a, form, 0) / med(b, form, 0):.3f}, per CPU-second {med(a, form, 1) / med(b, form, 1):.3f}")
PY
