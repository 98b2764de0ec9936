#!/usr/bin/env bash
# `clpt render`'s summary says what each figure measured (cli/render_summary.h):
#  * the passes' paths/s and ray segments/s are this run's paths and segments over the passes' own
#    time: in the EXR to 1e-6 (clpt:paths_per_s = clpt:paths / clpt:passes_s), and the printed
#    figures are the EXR's to their printed digits;
#  * the kernel build is shown apart from the passes, on the wall line, as compiled (--no-cache,
#    and on PoCL always: clpt keeps no PoCL binaries; a clpt cache hit is cache_cli.sh's, on Oclgrind);
#  * the wall line's parts do not overlap: scene load + device discovery + conversion + kernel
#    build + first launch + passes + output writing <= wall, in the summary and in the EXR
#    (clpt:elapsed_s, taken before the EXR itself is written);
#  * the progress line's samples/s is the passes' rate;
#  * a resumed render counts its own paths only and shows the checkpoint's load;
#  * a scene with images (textures, environment) shows their load apart from the scene's.
# No figure is compared with a time limit: the checks hold on any machine at any load.
#   render_summary_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
scene="$src/scenes/diffuse.toml"
size=(--width 32 --height 24 --sampler jitter --seed 7)
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# check SUMMARY EXR PATHS [RESUMED]: the summary's and the EXR's figures (python3 below).
check() {
  oiiotool --info -v "$2" | grep "clpt:" >"$2.meta" || { fail "$2: no clpt:* metadata"; return; }
  python3 - "$1" "$2.meta" "$3" "${4:-}" <<'EOF' || fail "$1 / $2: the figures disagree (above)"
import re, sys
summary, meta_file, paths, resumed = open(sys.argv[1]).read(), open(sys.argv[2]).read(), int(sys.argv[3]), sys.argv[4]
meta = dict(re.findall(r'(clpt:\w+): "([^"]*)"', meta_file))
problems = []
def expect(ok, what):
    if not ok: problems.append(what)
def number(key):
    if key not in meta:
        problems.append(f"the EXR lacks {key}")
        return 0.0
    return float(meta[key])

# The EXR: the rates are this run's paths and segments over the passes' time.
passes, exr_paths, segments = number("clpt:passes_s"), number("clpt:paths"), number("clpt:segments")
expect(exr_paths == paths, f"clpt:paths {exr_paths:.0f}, expected {paths}")
expect(passes > 0, f"clpt:passes_s {passes} is not positive")
if passes > 0:
    expect(abs(number("clpt:paths_per_s") - exr_paths / passes) <= 1e-6 * exr_paths / passes,
           f"clpt:paths_per_s {meta.get('clpt:paths_per_s')} is not clpt:paths / clpt:passes_s")
    expect(abs(number("clpt:segments_per_s") - segments / passes) <= 1e-6 * segments / passes,
           f"clpt:segments_per_s {meta.get('clpt:segments_per_s')} is not clpt:segments / clpt:passes_s")
parts = ["scene_load_s", "discovery_s", "convert_s", "kernel_build_s", "first_launch_s", "passes_s", "output_s"]
if resumed == "resumed":
    parts.append("resume_load_s")
else:
    expect("clpt:resume_load_s" not in meta, "clpt:resume_load_s without --resume")
if resumed == "images":
    parts.append("image_load_s")
else:
    expect("clpt:image_load_s" not in meta, "clpt:image_load_s for a scene without images")
values = {p: number("clpt:" + p) for p in parts}
expect(all(v >= 0 for v in values.values()), f"a negative part: {values}")
expect(sum(values.values()) <= number("clpt:elapsed_s"),
       f"the parts {values} add up to more than clpt:elapsed_s {meta.get('clpt:elapsed_s')}")

# The summary: the passes' line, and the build apart from it.
m = re.search(r"^  passes ([0-9.]+) s \(their launches and the waits for them\): ([0-9.]+) M paths/s, "
              r"([0-9.]+) M ray segments/s", summary, re.M)
expect(m is not None, "no passes line")
if m:
    expect(abs(float(m.group(1)) - passes) <= 0.0005 + 1e-9, f"printed passes {m.group(1)} s, EXR {passes}")
    expect(abs(float(m.group(2)) - number("clpt:paths_per_s") * 1e-6) <= 0.005 + 1e-9,
           f"printed {m.group(2)} M paths/s, EXR {meta.get('clpt:paths_per_s')}")
    expect(abs(float(m.group(3)) - number("clpt:segments_per_s") * 1e-6) <= 0.005 + 1e-9,
           f"printed {m.group(3)} M segments/s, EXR {meta.get('clpt:segments_per_s')}")
expect("kernel build" not in (m.group(0) if m else ""), "the passes line counts the kernel build")
w = re.search(r"^  wall ([0-9.]+) s = (.*)$", summary, re.M)
expect(w is not None, "no wall line")
if w:
    named = {name.strip(): float(value) for name, value in re.findall(r"(?:^|\+ )([a-z ]+?) (-?[0-9.]+) s", w.group(2))}
    want = ["scene load", "device discovery", "conversion and hierarchy", "kernel build", "first launch", "passes",
            "output writing", "other"] + (["checkpoint load"] if resumed == "resumed" else []) + \
           (["image load"] if resumed == "images" else [])
    expect(sorted(named) == sorted(want), f"the wall line's parts are {sorted(named)}, expected {sorted(want)}")
    wall = float(w.group(1))
    expect(all(v >= 0 for k, v in named.items()), f"a negative part on the wall line: {named}")
    expect(abs(sum(named.values()) - wall) <= 0.0005 * (len(named) + 1) + 1e-9,
           f"the wall line's parts add up to {sum(named.values()):.3f}, not {wall}")
    expect(abs(named.get("kernel build", -1) - number("clpt:kernel_build_s")) <= 0.0005 + 1e-9,
           "the printed kernel build is not the EXR's")
    expect(re.search(r"kernel build [0-9.]+ s \((compiled|clpt cache hit)\)", w.group(2)) is not None,
           "the kernel build does not say how it was served")
    expect(f"({meta.get('clpt:kernel_build')})" in w.group(2), "the EXR's clpt:kernel_build is not the summary's")
for p in problems:
    print("  " + p)
sys.exit(1 if problems else 0)
EOF
}

# 1. A render built from source (--no-cache), with the progress line.
"$clpt" render "$scene" "${size[@]}" --spp 8 --no-cache --progress -o a.exr >a.txt 2>a.err || fail "render exited $?: $(cat a.err)"
check a.txt a.exr $((32 * 24 * 8))
grep -q "kernel build [0-9.]* s (compiled)" a.txt || fail "--no-cache: the build is not 'compiled': $(cat a.txt)"
# The progress line's rate is the passes' rate: its last redraw (after the last pass) equals the summary's.
progress=$(tr '\r' '\n' <a.err | grep -o "[0-9.]* M samples/s in passes" | tail -1 | cut -d' ' -f1)
summary=$(grep -o "[0-9.]* M paths/s" a.txt | head -1 | cut -d' ' -f1)
[[ -n "$progress" && "$progress" == "$summary" ]] ||
  fail "the progress line's last rate '$progress' M samples/s is not the passes' $summary M paths/s"

# 2. The same render again, kernel cache on: clpt stores no PoCL binaries (PoCL's own cache
#    serves, cl_device.h), so the build is "compiled" again; the same figures' relations. The
#    cache hit's wording is checked on Oclgrind (cache_cli.sh).
"$clpt" render "$scene" "${size[@]}" --spp 8 -o b.exr >b.txt 2>b.err || fail "render exited $?: $(cat b.err)"
check b.txt b.exr $((32 * 24 * 8))
grep -q "kernel build [0-9.]* s (compiled)" b.txt || fail "PoCL's build is not 'compiled': $(cat b.txt)"

# 3. A resumed render counts its own 8 spp of the 16, and shows the checkpoint's load.
"$clpt" render "$scene" "${size[@]}" --spp 8 -q --checkpoint c.ckpt -o c8.exr || fail "checkpointed render exited $?"
"$clpt" render "$scene" "${size[@]}" --spp 16 --resume c.ckpt -o c.exr >c.txt 2>c.err || fail "resumed render exited $?: $(cat c.err)"
check c.txt c.exr $((32 * 24 * 8)) resumed

# 4. A scene with images (textures): their reading and decoding is a part of its own.
"$clpt" render "$src/scenes/textured-room.toml" "${size[@]}" --spp 8 -o t.exr >t.txt 2>t.err || fail "textured render exited $?: $(cat t.err)"
check t.txt t.exr $((32 * 24 * 8)) images

# 5. The wavefront (its stage times are the passes', the first launch's left out).
"$clpt" render "$scene" "${size[@]}" --spp 8 --form wavefront -o w.exr >w.txt 2>w.err || fail "wavefront exited $?: $(cat w.err)"
check w.txt w.exr $((32 * 24 * 8))
python3 - w.txt <<'EOF' || fail "wavefront: the stages' launches are not the passes' (above)"
import re, sys
text = open(sys.argv[1]).read()
stages = dict(re.findall(r" (\w+) [0-9.]+ s \((\d+) launches\);", text))
# film_sum_jobs runs once per range of a pass, and a pass of these 768 pixels is one range (a
# device's first launch takes up to 4096, render/work_queue.h): one each, none for the warm-up.
film = int(stages.get("film", "0"))
passes = int(re.search(r"(\d+) passes", text).group(1))
ok = film == passes
print(f"  film launches {film}, passes {passes}" + ("" if ok else ": the stage times are not the passes' alone"))
sys.exit(0 if ok else 1)
EOF

if [[ $failures -ne 0 ]]; then
  echo "$failures summary case(s) failed"
  exit 1
fi
echo "ok: the render summary's and the EXR's figures say what they measured and add up"
