#!/usr/bin/env bash
# Bad texture input through the real `clpt render` (docs/textures.md): a missing, empty,
# unreadable, truncated or absurdly large image, a directory named as a texture, a normal map on a
# sphere, a sphere's missing image, a texture on a mesh (inline, OBJ or PLY) without texture coordinates, a bad wrap word, a glTF
# image that is not there. Each must exit 3 (a bad scene), print a message that starts with the
# file and key (or glTF element) and names the image, and leave no output. (The line numbers are
# those of mesh_scene below.)
#   texture_bad_cli.sh CLPT WORK_DIR
set -u
clpt=$1 work=$2
rm -rf "$work" && mkdir -p "$work/out" "$work/dir.png"
failures=0 checked=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# A valid 2 x 2 PNG and a PNG header that declares 60000 x 60000 pixels (valid CRCs, no data).
python3 - "$work" <<'PY'
import struct, sys, zlib
work = sys.argv[1]
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
def png(w, h, rows):
    ihdr = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")
good = png(2, 2, b"\0" + b"\xff\0\0\0\xff\0" + b"\0" + b"\0\0\xff\xff\xff\xff")
open(work + "/good.png", "wb").write(good)
open(work + "/truncated.png", "wb").write(good[:40])
open(work + "/huge.png", "wb").write(png(60000, 60000, b"\0" * 64))
open(work + "/garbage.png", "wb").write(b"this is not an image at all" * 8)
open(work + "/empty.png", "wb").write(b"")
PY

# expect_refused MESSAGE_PREFIX NAMED SCENE: clpt exits 3, stderr starts with the prefix and
# contains NAMED, no output.
expect_refused() {
  local prefix=$1 named=$2 scene=$3 err status
  err=$("$clpt" render "$scene" -o "$work/out/out.exr" 2>&1 >/dev/null)
  status=$?
  checked=$((checked + 1))
  [[ $status -eq 3 ]] || fail "$scene: exit $status, expected 3 ($err)"
  # clpt's own line (libpng may print its complaint on a line of its own before it).
  grep -qF -- "$prefix" <<<"$err" && [[ "$(grep -F -- "clpt: error:" <<<"$err")" == "$prefix"* ]] ||
      fail "$scene: message '$err', expected a line starting with '$prefix'"
  [[ "$err" == *"$named"* ]] || fail "$scene: message '$err' does not name '$named'"
  if [[ -n "$(ls -A "$work/out")" ]]; then
    fail "$scene: left $(ls "$work/out")"
    rm -f "$work/out"/*
  fi
}

# mesh_scene NAME MATERIAL [UVS]: a scene with one textured quad.
mesh_scene() {
  local name=$1 material=$2 uvs=${3-'uvs = [[0, 0], [1, 0], [1, 1], [0, 1]]'}
  cat >"$work/$name.toml" <<TOML
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
[[sphere]]
center = [0, 5, 5]
radius = 1
material = { type = "emitter", emission = [4, 4, 4] }
[[mesh]]
vertices = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]
$uvs
quads = [[0, 1, 2, 3]]
material = $material
TOML
}

for image in missing.png dir.png truncated.png huge.png garbage.png empty.png; do
  mesh_scene "$image" "{ type = \"lambertian\", reflectance = { texture = \"$image\" } }"
  expect_refused "clpt: error: $work/$image.toml:12:61: mesh[0].material.reflectance.texture: " "$image" "$work/$image.toml"
done
# A truncated PNG is named as such (clpt checks for the IEND chunk before the codec reads it).
"$clpt" render "$work/truncated.png.toml" -o "$work/t.exr" 2>&1 | grep -q "truncated.png: cannot read image: a PNG file ends with its IEND chunk and this one does not (truncated?)" ||
  fail "the truncated PNG's message does not say it is truncated"
mesh_scene nouvs '{ type = "pbr", roughness = { texture = "good.png", channel = 1 } }' ""
expect_refused "clpt: error: $work/nouvs.toml:8:1: mesh 'mesh[0]' has no texture coordinates" \
    "mesh[0].material.roughness" "$work/nouvs.toml"
# The same for mesh files without texture coordinates: an OBJ (no vt) and a PLY (no s/t, u/v,
# texture_u/texture_v or texture_s/texture_t): the message names the file as having none.
printf 'v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n' >"$work/bare.obj"
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n4 0 1 2 3\n' >"$work/bare.ply"
for ext in obj ply; do
  cat >"$work/nouvs_$ext.toml" <<TOML
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
[[sphere]]
center = [0, 5, 5]
radius = 1
material = { type = "emitter", emission = [4, 4, 4] }
[[mesh]]
file = "bare.$ext"
material = { type = "lambertian", reflectance = { texture = "good.png" } }
TOML
  expect_refused "clpt: error: $work/nouvs_$ext.toml:8:1: mesh 'mesh[0]' has no texture coordinates (bare.$ext has none)" \
      "mesh[0].material.reflectance" "$work/nouvs_$ext.toml"
done
mesh_scene wrap '{ type = "lambertian", reflectance = { texture = "good.png", wrap = "wrapped" } }'
expect_refused "clpt: error: $work/wrap.toml:" "mesh[0].material.reflectance.wrap" "$work/wrap.toml"
cat >"$work/sphere.toml" <<TOML
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
[[sphere]]
center = [0, 0, 0]
radius = 1
material = { type = "lambertian", reflectance = { texture = "good.png" }, normal_map = { texture = "good.png" } }
TOML
expect_refused "clpt: error: $work/sphere.toml:7:" "sphere[0].material.normal_map: sphere 'sphere[0]'" "$work/sphere.toml"
cat >"$work/sphere_missing.toml" <<TOML
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
[[sphere]]
center = [0, 0, 0]
radius = 1
material = { type = "emitter", emission = { texture = "missing.png" } }
TOML
expect_refused "clpt: error: $work/sphere_missing.toml:7:" "sphere[0].material.emission.texture" "$work/sphere_missing.toml"

# A glTF file whose base colour image is not there.
python3 - "$work/missing.gltf" <<'PY'
import base64, json, struct, sys
data = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<6f", 0, 0, 1, 0, 0, 1)
doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
       "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
       "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "emissiveFactor": [1, 1, 1]}],
       "textures": [{"source": 0}], "images": [{"uri": "nothere.png"}],
       "buffers": [{"byteLength": len(data),
                    "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
       "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
       "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                     {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]}
open(sys.argv[1], "w").write(json.dumps(doc))
PY
expect_refused "clpt: error: $work/missing.gltf: materials[0].pbrMetallicRoughness.baseColorTexture (images[0])" \
    "nothere.png" "$work/missing.gltf"
echo "$checked refusals checked, $failures failures"
[[ $failures -eq 0 ]]
