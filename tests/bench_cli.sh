#!/usr/bin/env bash
# clpt bench end to end: a tiny matrix (both forms, both megakernel loops) writes a table and a
# JSON holding every field, passes
# against its own results as baseline, and fails (exit 1, REGRESSION) against a baseline that
# claims 1000 times the speed. --bvh-builders: an unknown builder is refused (exit 2, naming the
# option); the Cornell box's rows report their hierarchy and builder, one row per builder (clpt's,
# and Embree's two in a build with Embree), each with its own key. Each row reports its vector
# width (vector_width): on PoCL's CPU device a positive number of work-items, elsewhere null and
# why; --no-vector-width: null, "not measured". Mesh rows report the hierarchy's statistics (SAH
# cost, nodes, boxes and triangles per ray, build threads) and, with --traversal-anchor embree in
# a build with Embree, Embree's rays/s on the same triangles and rays, and on a hierarchy of spheres
# the same spheres (else exit 2, and skipped).
#   bench_cli.sh CLPT SOURCE_DIR WORK_DIR
set -euo pipefail
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$src"
common=(--width 32 --height 24 --spp 2 --warmup 0 --repeat 2 --devices cpu --forms megakernel,wavefront
        --megakernel-loops lockstep,path)

# The platform of the first CPU device, which --devices cpu benchmarks: PoCL reports vector widths.
cpu_platform=$("$clpt" devices | awk '/^platform: /{sub(/^platform: /, ""); p=$0} /^ *\[[0-9]+\] CPU /{print p; exit}')
"$clpt" bench "${common[@]}" --json "$work/bench.json" > "$work/table.txt"
grep -q "megakernel" "$work/table.txt" && grep -q "wavefront" "$work/table.txt"
grep -q " lanes " "$work/table.txt"
python3 - "$work/bench.json" "$cpu_platform" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
pocl = sys.argv[2] == "Portable Computing Language"
rows = doc["rows"]
assert len(rows) == 3, rows  # megakernel (lockstep, per path) and the wavefront once
fields = {"key", "scene", "form", "loop", "kernel", "precision", "estimator", "device", "local_size", "paths_in_flight", "build_cold_s",
          "build_cached_s", "paths_per_s", "segments_per_s", "paths_per_cpu_s", "stage_seconds", "vector_width"}
for r in rows:
    missing = fields - r.keys()
    assert not missing, missing
    for s in ("paths_per_s", "segments_per_s", "paths_per_cpu_s"):
        assert r[s]["min"] <= r[s]["median"] <= r[s]["max"] and r[s]["median"] > 0, r[s]
assert sorted(r["loop"] for r in rows) == ["", "lockstep", "path"], rows
assert len({r["key"] for r in rows}) == 3, rows
lockstep = [r for r in rows if r["loop"] == "lockstep"][0]
assert lockstep["local_size"] == 64, lockstep  # the lockstep loop's default work-group
wf = [r for r in rows if r["form"] == "wavefront"][0]
assert {"generate", "intersect", "shade", "film"} <= wf["stage_seconds"].keys(), wf
for r in rows:
    v = r["vector_width"]
    if pocl:  # measured: the kernel's width, the widest loop, and the loops it counted
        assert isinstance(v["widest"], int) and v["widest"] >= 1, v
        assert v["not_vectorised"] >= 0 and all(int(w) >= 2 and n >= 1 for w, n in v["loops"].items()), v
        assert v["widest"] == max([1] + [int(w) for w in v["loops"]]), v
        # lanes: the width of most loops, or 1 where a blocker kept a work-item loop scalar
        assert isinstance(v["blockers"], dict) and all(n >= 1 for n in v["blockers"].values()), v
        if v["blockers"] or not v["loops"]:
            assert v["lanes"] == 1, v
        else:
            most = max(v["loops"].values())
            assert v["lanes"] == max(int(w) for w, n in v["loops"].items() if n == most), v
    else:
        assert v["lanes"] is None and v["widest"] is None and v["why"] == "the driver does not report it", v
if pocl:  # PoCL vectorises the lockstep loop across work-items (docs/performance.md)
    assert lockstep["vector_width"]["lanes"] > 1, lockstep
# A baseline 1000 times faster than measured: every row must be a regression, however noisy
# the machine (a timing ratio of 1000 cannot come from load).
for r in rows:
    r["paths_per_s"]["median"] *= 1000
json.dump(doc, open(sys.argv[1].replace("bench.json", "faster.json"), "w"))
PY
# A 100% tolerance accepts any speed; the 1000x baseline at 10% must fail. These runs measure no
# vector width: their rows say so.
"$clpt" bench "${common[@]}" --no-vector-width --baseline "$work/bench.json" --tolerance 100 \
    --json "$work/same.json" > "$work/same.txt"
python3 - "$work/same.json" <<'PY'
import json, sys
for r in json.load(open(sys.argv[1]))["rows"]:
    assert r["vector_width"] == {"lanes": None, "widest": None, "why": "not measured (--no-vector-width)"}, r
PY
if grep -q "vector width:" "$work/same.txt"; then echo "FAIL: --no-vector-width measured a vector width"; exit 1; fi
if "$clpt" bench "${common[@]}" --no-vector-width --baseline "$work/faster.json" --tolerance 10 > "$work/slower.txt"; then
  echo "FAIL: a baseline 1000x faster did not fail"; exit 1
fi
test "$(grep -c REGRESSION "$work/slower.txt")" -eq 3

status=0
"$clpt" bench --bvh-builders nosuch --devices cpu > /dev/null 2> "$work/builder.err" || status=$?
test "$status" -eq 2 || { echo "FAIL: --bvh-builders nosuch exited $status, not 2"; exit 1; }
grep -q -- "--bvh-builders: unknown hierarchy builder 'nosuch'" "$work/builder.err" || { cat "$work/builder.err"; exit 1; }
builders=clpt,clpt-1thread
if "$clpt" bench --no-vector-width --bvh-builders embree --scenes scenes/diffuse.toml --width 4 --height 4 --spp 1 --warmup 0 \
       --repeat 1 --devices cpu --forms megakernel > /dev/null 2> "$work/embree.err"; then
  builders=clpt,clpt-1thread,embree,embree-1thread
else
  grep -q "built without Embree" "$work/embree.err" || { cat "$work/embree.err"; exit 1; }
fi
"$clpt" bench --no-vector-width --scenes scenes/cornell-box.toml --bvh-builders "$builders" --width 16 --height 16 --spp 1 --warmup 0 \
    --repeat 1 --devices cpu --forms megakernel --json "$work/mesh.json" > "$work/mesh.txt"
python3 - "$work/mesh.json" "$builders" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))["rows"]
builders = sys.argv[2].split(",")
assert [r["bvh_builder"] for r in rows] == builders, rows
assert len({r["key"] for r in rows}) == len(rows), rows
for r in rows:
    assert r["triangles"] == 32 and r["bvh_nodes"] > 0 and r["bvh_depth"] > 0, r
    assert r["device_bytes_per_triangle"] > 0 and r["bvh_build_s"] >= 0, r
    # The hierarchy's statistics: SAH cost, and per ray of the replica's sample (16 x 16 camera rays
    # at 16x16, one per pixel, plus a bounce from each hit) nodes, boxes and triangles; the Cornell box is closed
    # but for its front, so every ray tests a triangle, never more than all 32.
    t = r["traversal"]
    assert r["sah_cost"] > 1 and r["bvh_build_threads"] >= 1, r
    assert t["camera_rays"] == 256 and t["rays"] > t["camera_rays"], t
    assert t["nodes_per_ray"] >= 1 and t["boxes_per_ray"] > t["nodes_per_ray"], t
    assert 1 <= t["triangles_per_ray"] <= 32 and t["spheres_per_ray"] == 0, t
    assert r["rays_per_s"] == r["segments_per_s"]["median"] and r["rays_per_cpu_s"] > 0, r
    assert "anchor" not in r, r
PY
test "$(grep -c "hierarchy: 32 triangles" "$work/mesh.txt")" -eq "$(tr , '\n' <<< "$builders" | wc -l)"
test "$(grep -c "traversal: SAH cost" "$work/mesh.txt")" -eq "$(tr , '\n' <<< "$builders" | wc -l)"

# --traversal-anchor: an unknown anchor is refused; embree, in a build with Embree, times
# rtcIntersect1 and rtcIntersect16 on the mesh rows' triangles and rays (hits as the replica's
# sample: the Cornell box's camera rays all hit), and on the hierarchy's spheres of the book's
# scene with 40 pebbles (Embree's sphere points, from the rays' t_min), and clpt's own queries on
# them (trace.cl): the same hits; the plain book scene (its spheres all in the loop) has neither.
# A build without Embree says so (exit 2).
status=0
"$clpt" bench --traversal-anchor nosuch --devices cpu > /dev/null 2> "$work/anchor.err" || status=$?
test "$status" -eq 2 || { echo "FAIL: --traversal-anchor nosuch exited $status, not 2"; exit 1; }
grep -q -- "--traversal-anchor: unknown anchor 'nosuch'" "$work/anchor.err" || { cat "$work/anchor.err"; exit 1; }
# --traversal-anchor-width: 4 or 8 only, and only with an anchor (exit 2 naming the option).
status=0
"$clpt" bench --traversal-anchor-width 5 --devices cpu > /dev/null 2> "$work/width.err" || status=$?
test "$status" -eq 2 && grep -q -- "--traversal-anchor-width" "$work/width.err" || { cat "$work/width.err"; exit 1; }
status=0
"$clpt" bench --traversal-anchor-width 4 --devices cpu > /dev/null 2> "$work/width.err" || status=$?
test "$status" -eq 2 && grep -q -- "--traversal-anchor-width: needs --traversal-anchor embree" "$work/width.err" || { cat "$work/width.err"; exit 1; }
python3 scripts/many_spheres_scene.py --count 40 "$work/pebbles.toml"
status=0
"$clpt" bench --no-vector-width --traversal-anchor embree --scenes scenes/cornell-box.toml,scenes/diffuse.toml,"$work/pebbles.toml" --width 16 \
    --height 16 --spp 1 --warmup 0 --repeat 1 --devices cpu --forms megakernel --json "$work/anchor.json" \
    > "$work/anchor.txt" 2> "$work/anchor.err" || status=$?
if [[ $status -eq 0 ]]; then
  python3 - "$work/anchor.json" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))["rows"]
assert len(rows) == 3, rows
mesh, spheres, pebbles = rows
assert "anchor" not in spheres and "trace" not in spheres, spheres  # every sphere in the loop: no anchor
a = mesh["anchor"]
assert a["name"].startswith("embree ") and a["threads"] >= 1, a
assert a["triangles"] == 32 and a["spheres"] == 0, a
assert a["rays"] == mesh["traversal"]["rays"] and a["hits"] >= 200, a
assert a["rtcIntersect1_rays_per_s"] > 0 and a["rtcIntersect16_rays_per_s"] > 0, a
assert a["rtcIntersect1_rays_per_cpu_s"] > 0 and a["rtcIntersect16_rays_per_cpu_s"] > 0, a
# Embree as Cycles builds it (robust, medium quality): the same rays. Its exact test also reports
# the wall a bounce ray leaves, at t of 1e-7 to 1e-5 mm, where the float origin of the sample's
# ray (offset by the ray epsilon in double) rounded back to the wall: in this Cornell box sample
# 489 hits against 455 and clpt's 458 (2026-12-07): within 10% of the rays of each other.
rb = a["robust"]
assert rb["flags"] == "RTC_SCENE_FLAG_ROBUST" and rb["build_quality"] == "medium", rb
assert rb["rtcIntersect1_rays_per_s"] > 0 and rb["rtcIntersect1_rays_per_cpu_s"] > 0, rb
assert abs(rb["hits"] - a["hits"]) <= 0.1 * a["rays"], (rb, a)
# clpt's own queries on the same rays (kernels/trace.cl): the same rays, about the same hits.
t = mesh["trace"]
assert t["rays"] == a["rays"] and abs(t["hits"] - a["hits"]) <= 0.02 * a["rays"] + 1, (t, a)
assert t["rays_per_s"] > 0 and t["rays_per_cpu_s"] > 0 and t["launch_rays"] >= t["rays"], t
# The pebbles: the 40 small spheres in the hierarchy (the room's 8 in the loop), as Embree's sphere
# points; both sides test them alone from each ray's t_min, so the hits agree but for rays that
# graze a pebble (float against Embree's own sphere test). Some rays do hit them.
pa, pt = pebbles["anchor"], pebbles["trace"]
assert pebbles["hierarchy_spheres"] == 40 and pa["spheres"] == 40 and pa["triangles"] == 0, pa
assert pa["rays"] == pebbles["traversal"]["rays"] == pt["rays"], (pa, pt)
assert pa["hits"] > 0 and abs(pt["hits"] - pa["hits"]) <= 0.01 * pa["rays"] + 1, (pa, pt)
assert abs(pa["robust"]["hits"] - pa["hits"]) <= 0.01 * pa["rays"] + 1, pa
assert pa["rtcIntersect1_rays_per_s"] > 0 and pt["rays_per_s"] > 0, (pa, pt)
PY
  grep -q "anchor: clpt .* the same 40 spheres and .* rays: rtcIntersect1" "$work/anchor.txt" || { cat "$work/anchor.txt"; exit 1; }
  # Embree's choice of tree when no width is given (JSON tri_accel null); --traversal-anchor-width
  # 4 forces its 4-wide tree over the fastest scene's triangles, named on the line and in the JSON,
  # the same hits.
  python3 -c 'import json, sys; assert json.load(open(sys.argv[1]))["rows"][0]["anchor"]["tri_accel"] is None' "$work/anchor.json"
  "$clpt" bench --no-vector-width --traversal-anchor embree --traversal-anchor-width 4 --scenes scenes/cornell-box.toml \
      --width 16 --height 16 --spp 1 --warmup 0 --repeat 1 --devices cpu --forms megakernel --json "$work/anchor4.json" \
      > "$work/anchor4.txt"
  grep -q "anchor: clpt .* rays: rtcIntersect1 (bvh4.triangle4) [0-9.]* M rays/s" "$work/anchor4.txt" || { cat "$work/anchor4.txt"; exit 1; }
  python3 - "$work/anchor4.json" "$work/anchor.json" <<'PY'
import json, sys
a4 = json.load(open(sys.argv[1]))["rows"][0]["anchor"]
a = json.load(open(sys.argv[2]))["rows"][0]["anchor"]
assert a4["tri_accel"] == "bvh4.triangle4" and a4["rtcIntersect1_rays_per_s"] > 0, a4
assert abs(a4["hits"] - a["hits"]) <= 0.01 * a["rays"] + 1, (a4["hits"], a["hits"])
PY
  # scripts/target_budget.py (docs/performance.md, "What limits the speed") reads these rows: the
  # plain scene is the book's, every anchored row gets a line, the target's budget where asked.
  python3 scripts/target_budget.py --target pebbles=0.5 "$work/anchor.json" > "$work/budget.txt"
  grep -q "^plain scene: [0-9]" "$work/budget.txt" || { cat "$work/budget.txt"; exit 1; }
  grep -q "^| scenes/cornell-box.toml | [0-9][0-9-]* | [0-9.-]* | - | [0-9]" "$work/budget.txt" || { cat "$work/budget.txt"; exit 1; }
  grep -q "^| .*pebbles.toml | [0-9][0-9-]* | [0-9.-]* | [0-9][0-9-]* | [0-9]" "$work/budget.txt" || { cat "$work/budget.txt"; exit 1; }
  grep -q "anchor: clpt .* rtcIntersect1 .* rtcIntersect16 .* robust, as Cycles builds it: rtcIntersect1" "$work/anchor.txt" || { cat "$work/anchor.txt"; exit 1; }
  grep -q "traversal alone: clpt (trace.cl" "$work/anchor.txt" || { cat "$work/anchor.txt"; exit 1; }
else
  test "$status" -eq 2 && grep -q "built without Embree" "$work/anchor.err" || { cat "$work/anchor.err"; exit 1; }
  echo "bench CLI: no Embree in this build: the anchor's timing is not checked"
fi
# --traversal-alone (no Embree needed): the mesh row also times clpt's own closest-hit queries on its
# statistics' rays (kernels/trace.cl); a row without triangles does not.
"$clpt" bench --no-vector-width --traversal-alone --scenes scenes/cornell-box.toml,scenes/diffuse.toml --width 16 \
    --height 16 --spp 1 --warmup 0 --repeat 1 --devices cpu --forms megakernel --json "$work/alone.json" > "$work/alone.txt"
python3 - "$work/alone.json" <<'PY'
import json, sys
mesh, spheres = json.load(open(sys.argv[1]))["rows"]
assert "trace" not in spheres and "anchor" not in mesh, (mesh, spheres)
t = mesh["trace"]
# 16 x 16 camera rays and a bounce from each hit; the box is closed but for its front, so most hit.
assert t["rays"] == mesh["traversal"]["rays"] and t["rays"] // 2 < t["hits"] <= t["rays"], t
assert t["rays_per_s"] > 0 and t["rays_per_cpu_s"] > 0 and t["launch_rays"] >= t["rays"], t
PY
grep -q "traversal alone: clpt (trace.cl, the row's options) .* rays hit$" "$work/alone.txt" || { cat "$work/alone.txt"; exit 1; }
echo "bench CLI: table, JSON fields, vector widths, baseline pass and regression, hierarchy builders, statistics, anchor and traversal alone all as expected"
