#!/usr/bin/env bash
# A glTF scene rendered end to end by the real `clpt render` (issue 33): tests/gltf_corpus.py's
# lit.glb (a floor and a box in the glTF material, a point and a spot light, a camera) at 32x24,
# 4 spp, as a raw film; the film must be finite and not black (the lights reach the floor), and
# the same file as .gltf with its buffer embedded must load alike (--camera by name).
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
[[ $failures -eq 0 ]]
