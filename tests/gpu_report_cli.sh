#!/usr/bin/env bash
# The GPU report end to end on PoCL, so that it cannot rot while no GPU is at hand:
#  (a) scripts/offline-bundle.sh makes a bundle (Debian packages unpacked into a prefix, the tree,
#      PoCL reference films of a tiny verify, MANIFEST) under 60 MB;
#  (b) scripts/gpu-report.sh --quick builds clpt from the bundle alone (its prefix, CMake told to
#      ignore /usr) and runs every step on the CPU device: exit 0, the seven files and no others,
#      each small; verify passes against the bundle's films; bench, budget and picture are whole;
#  (c) bad arguments: exit 2, naming what is wrong.
# Needs the package registry (apt-get download): skipped (77) where it cannot be reached.
#   gpu_report_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
export CLPT_CACHE_DIR="$work/cache"
unset CLPT_INJECT_FAULT POCL_DEVICES
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
show() { sed 's/^/    /' "$@"; }

if ! (cd "$work" && timeout 60 apt-get download -qq opencl-c-headers >/dev/null 2>&1); then
  echo "SKIP: the package registry cannot be reached (apt-get download failed)"
  exit 77
fi
rm -f "$work"/*.deb

# (a) The bundle, with a tiny verify matrix: the diffuse scene, robust, both forms.
CLPT_BUILD=$(dirname "$clpt") "$src/scripts/offline-bundle.sh" bundle \
  --verify-args "--width 16 --height 12 --spp 64 --scenes diffuse --precisions robust" >bundle.out 2>&1 ||
  { fail "(a) offline-bundle.sh exited $?"; show bundle.out; }
for f in prefix/usr/include/CL/cl.h prefix/usr/include/toml++/toml.h prefix/usr/include/CLI/CLI.hpp \
         prefix/usr/include/nlohmann/json.hpp prefix/usr/include/assimp/Importer.hpp \
         prefix/usr/lib/x86_64-linux-gnu/libassimp.so.5 prefix/usr/lib/x86_64-linux-gnu/libOpenCL.so.1 \
         src/CMakeLists.txt src/scenes/meshes/torus_knot.ply films/films.json MANIFEST; do
  [[ -e bundle/$f ]] || fail "(a) the bundle has no $f"
done
[[ $(ls bundle/films/verify_*.pfm 2>/dev/null | wc -l) -eq 4 ]] || { fail "(a) not 2 films with their variances"; ls bundle/films; }
grep -q "Package: libassimp5 Version:" bundle/MANIFEST || { fail "(a) MANIFEST lists no packages"; show bundle/MANIFEST; }
bytes=$(du -sb bundle | cut -f1)
[[ $bytes -le 60000000 ]] || fail "(a) the bundle is $bytes bytes, over 60 MB"

# (b) The report on the CPU device. Its build of the bundle goes through ccache where this machine
# has it (CMake reads the launcher from the environment; a GPU machine's run sets none), so CI
# does not compile the same -O0 tree from scratch each time.
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(CMAKE_CXX_COMPILER_LAUNCHER=ccache CMAKE_C_COMPILER_LAUNCHER=ccache)
env "${launcher[@]}" CLPT_REPORT_WORK="$work/report-work" "$src/scripts/gpu-report.sh" bundle out --quick >report.out 2>&1
status=$?
[[ $status -eq 0 ]] || { fail "(b) gpu-report.sh exited $status"; show report.out; [[ -f out/report.log ]] && tail -40 out/report.log | show; }
expected="out/bench.json out/first-picture.pfm out/first-picture.var.pfm out/kernel-budget.tsv out/report.log"
expected+=" out/summary.md out/traversal.json out/verify.json"
[[ "$(ls -d out/* 2>/dev/null | xargs)" == "$expected" ]] || fail "(b) files: $(ls -d out/* | xargs), expected $expected"
for f in out/*; do
  [[ $(stat -c %s "$f") -lt 16000000 ]] || fail "(b) $f is 16 MB or more"
done
grep -q "^verify: 2 of 2 rows passed$" out/summary.md || { fail "(b) the summary has no passing verify"; show out/summary.md; }
grep -q "traversal alone: clpt (trace.cl" out/summary.md || { fail "(b) the summary has no traversal line"; show out/summary.md; }
grep -q "^Failed steps: none$" out/summary.md || { fail "(b) a step failed"; show out/summary.md; }
for s in build devices verify bench traversal picture budget; do
  grep -qE "^\| $s \| [0-9.]+ s \| ok \|$" out/summary.md || fail "(b) the summary's steps table has no ok row for $s"
done
python3 - out <<'PY' || fail "(b) the report's JSON, table or film"
import json, os, sys
out = sys.argv[1]
v = json.load(open(os.path.join(out, "verify.json")))
assert v["reference_mode"] == "films" and v["total"] == 2 and v["passed"] == 2, v
assert all(r["same_seed_fraction"] == 1 for r in v["rows"]), v["rows"]
b = json.load(open(os.path.join(out, "bench.json")))
cells = {(r["scene"], r["form"]) for r in b["rows"]}
assert cells == {(s, f) for s in ("scenes/diffuse.toml", "scenes/cornell-box.toml")
                 for f in ("megakernel", "wavefront")}, cells
assert all(r["paths_per_s"]["median"] > 0 for r in b["rows"]), b["rows"]
t = json.load(open(os.path.join(out, "traversal.json")))["rows"]
assert [r["scene"] for r in t] == ["scenes/cornell-box.toml", "scenes/many-spheres.toml"], t
assert all(r["trace"]["hits"] > 0 and r["trace"]["rays_per_s"] > 0 for r in t), t
assert t[1]["hierarchy_spheres"] == 1000, t[1]  # the bundle's scene: 1000 small spheres in the hierarchy
rows = [l.split("\t") for l in open(os.path.join(out, "kernel-budget.tsv")).read().splitlines()]
assert rows[0][:3] == ["variant", "kernel", "build_s"] and len(rows) > 10, rows[:3]
assert all(len(r) == len(rows[0]) for r in rows), "ragged table"
with open(os.path.join(out, "first-picture.pfm"), "rb") as f:
    assert f.read(11) == b"PF\n32 24\n-1", "not the 32x24 picture"
PY

# (c) Bad arguments.
"$src/scripts/gpu-report.sh" "$work/nowhere" out2 >bad1.out 2>&1
[[ $? -eq 2 ]] && grep -q "no bundle directory" bad1.out || { fail "(c) a missing bundle"; show bad1.out; }
mkdir -p notabundle
"$src/scripts/gpu-report.sh" notabundle out2 >bad2.out 2>&1
[[ $? -eq 2 ]] && grep -q "notabundle/prefix is missing" bad2.out || { fail "(c) not a bundle"; show bad2.out; }
"$src/scripts/offline-bundle.sh" bundle >bad3.out 2>&1
[[ $? -eq 2 ]] && grep -q "is not empty" bad3.out || { fail "(c) a bundle into a full directory"; show bad3.out; }

[[ $failures -eq 0 ]] && echo "gpu report: all checks passed"
exit $((failures > 0))
