#!/usr/bin/env bash
# A glTF scene rendered end to end by the real `clpt render` (issue 33): tests/gltf_corpus.py's
# lit.glb (a floor and a box in the glTF material, a point and a spot light, a camera) at 32x24,
# 4 spp, as a raw film; the film must be finite and not black (the lights reach the floor), and
# the same file as .gltf with its buffer embedded must load alike (--camera by name). The same
# file without its lights renders under the default environment with a notice (black, with the
# warning that it will be, under --environment none), and with neither once --environment lights it.
# Needs the device side of issue 33 (the Pbr material and punctual lights in the kernels).
#   gltf_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work/good"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
python3 "$src/tests/gltf_corpus.py" good "$work/good" || fail "gltf_corpus.py good failed"
for scene in lit.glb lit.gltf; do
  out=$work/${scene%.*}-${scene##*.}.pfm
  if err=$("$clpt" render "$work/good/$scene" --camera view --width 32 --height 24 --spp 4 -q -o "$out" 2>&1); then
    echo "ok: clpt render $scene"
  else
    fail "clpt render $scene exited $?: $err"
    continue
  fi
  # The film's mean over every pixel and channel: finite and > 0.
  python3 - "$out" <<'PY' || fail "$scene: the film is black or not finite"
import math, struct, sys
data = open(sys.argv[1], "rb").read()
header = data.split(b"\n", 3)
width, height = map(int, header[1].split())
scale = float(header[2])
pixels = struct.unpack(("<" if scale < 0 else ">") + "%df" % (3 * width * height), header[3][:12 * width * height])
mean = sum(pixels) / len(pixels)
print("mean", mean)
sys.exit(0 if math.isfinite(mean) and mean > 0 and all(math.isfinite(p) for p in pixels) else 1)
PY
done
python3 - "$work/good/lit.gltf" "$work/unlit.gltf" <<'PY' || fail "could not write unlit.gltf"
import json, sys
d = json.load(open(sys.argv[1]))
d.pop("extensions", None)
d["extensionsUsed"] = [e for e in d.get("extensionsUsed", []) if e != "KHR_lights_punctual"]
for n in d["nodes"]:
    n.get("extensions", {}).pop("KHR_lights_punctual", None)
for m in d.get("materials", []):
    m.pop("emissiveFactor", None)
json.dump(d, open(sys.argv[2], "w"))
PY
cp "$work"/good/*.bin "$work/" 2>/dev/null
# pfm_mean FILE: the mean of a PFM film's values.
pfm_mean() {
  python3 -c '
import struct, sys
data = open(sys.argv[1], "rb").read()
parts = data.split(b"\n", 3)
w, h = map(int, parts[1].split())
n = w * h * (3 if parts[0] == b"PF" else 1)
v = struct.unpack(("<" if float(parts[2]) < 0 else ">") + "%df" % n, parts[3][:4 * n])
print(sum(v) / n)' "$1"
}
# Without a light of its own the scene is lit by the default environment, said in one notice;
# --environment none renders it black, with the warning that it will be.
err=$("$clpt" render "$work/unlit.gltf" --width 8 --height 6 --spp 4 -o "$work/unlit.pfm" 2>&1) || fail "unlit.gltf exited $?: $err"
grep -q "unlit.gltf: the scene has no lights, no emissive material and no environment; lit by clpt's default studio environment" <<<"$err" ||
  fail "unlit.gltf: no notice of the default light: $err"
if grep -q "will be black" <<<"$err"; then fail "unlit.gltf: warned that the image will be black: $err"; fi
mean=$(pfm_mean "$work/unlit.pfm") && awk -v m="$mean" 'BEGIN { exit !(m > 0.05) }' ||
  fail "unlit.gltf under the default light: mean $mean, expected a lit image"
err=$("$clpt" render "$work/unlit.gltf" --environment none --width 8 --height 6 --spp 1 -o "$work/black.pfm" 2>&1) ||
  fail "unlit.gltf --environment none exited $?: $err"
grep -q "unlit.gltf: the scene has no lights, no emissive material and no environment, so the image will be black" <<<"$err" ||
  fail "unlit.gltf --environment none: no warning that the image will be black: $err"
mean=$(pfm_mean "$work/black.pfm") && [[ $mean == 0.0 ]] || fail "unlit.gltf --environment none: mean $mean, expected 0"
err=$("$clpt" render "$work/unlit.gltf" --environment "$src/scenes/environment-sky.hdr" --width 8 --height 6 --spp 1 \
      -o "$work/env.pfm" 2>&1) || fail "unlit.gltf --environment exited $?: $err"
if grep -q "will be black" <<<"$err"; then fail "unlit.gltf --environment: warned that the image will be black: $err"; fi
# A TOML scene lit by its emitter spheres (the book's) renders without that warning.
err=$("$clpt" render "$src/scenes/diffuse.toml" --width 8 --height 6 --spp 16 -o "$work/diffuse.pfm" 2>&1) ||
  fail "diffuse.toml exited $?: $err"
if grep -q "will be black" <<<"$err"; then fail "diffuse.toml: warned that the image will be black: $err"; fi
[[ $failures -eq 0 ]]
