#!/usr/bin/env python3
"""Writes the glTF material sweep: scenes/pbr-sweep.gltf and its TOML twin scenes/pbr-sweep.toml.

Fifteen spheres in a grid, metallic 0, 0.5 and 1 (rows, bottom to top) by roughness 0, 0.25, 0.5,
0.75 and 1 (columns, left to right), one base colour, before a grey backdrop, lit by a
directional light (KHR_lights_punctual, lux) and a point light (candela), seen by a perspective
camera looking down -Z. In the .gltf every sphere is a triangle mesh (one UV sphere's accessors,
shared by fifteen meshes that differ in their material) and the buffer is embedded as base64; the
TOML twin writes the spheres as clpt's analytic spheres, the same materials and lights (candela
and lux as the glTF writes them), the same camera. Both are small enough to commit (about 60 KB
and 3 KB).

Usage: python3 scripts/make_pbr_sweep.py [OUT_DIR]   (default: scenes/)
The picture docs/pbr-sweep.png:
  clpt render scenes/pbr-sweep.toml -o /tmp/pbr-sweep.exr --width 384 --height 230 --spp 128 \\
      && cp /tmp/pbr-sweep.png docs/pbr-sweep.png
(the .gltf renders the same once clpt reads glTF files: clpt render scenes/pbr-sweep.gltf ...)
"""
import base64
import json
import math
import os
import struct
import sys

METALLIC = [0.0, 0.5, 1.0]
ROUGHNESS = [0.0, 0.25, 0.5, 0.75, 1.0]
BASE = [0.9, 0.55, 0.2]
RADIUS = 0.42
SPACING = 1.0
CAMERA_Z = 7.5
YFOV = math.radians(32.0)
SUN_DIRECTION = [0.35, -0.55, -0.76]  # where the light travels
SUN_LUX = 1500.0
BULB_POSITION = [-2.5, 2.5, 3.0]
BULB_CANDELA = 2000.0
BACKDROP_Z = -1.2


def centre(row, col):
    return [(col - (len(ROUGHNESS) - 1) / 2) * SPACING, (row - (len(METALLIC) - 1) / 2) * SPACING, 0.0]


def uv_sphere(rings=16, segments=32):
    """Unit sphere: positions (= normals) and triangle indices, counter-clockwise from outside."""
    points = []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            points.append([math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)])
    indices = []
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            if r > 0:
                indices += [a, b, a + 1]
            if r < rings - 1:
                indices += [a + 1, b, b + 1]
    return points, indices


def quaternion_from_minus_z(d):
    """The rotation taking the node's -Z onto unit direction d, as glTF's [x, y, z, w]."""
    n = math.sqrt(sum(c * c for c in d))
    d = [c / n for c in d]
    a = [0.0, 0.0, -1.0]
    axis = [a[1] * d[2] - a[2] * d[1], a[2] * d[0] - a[0] * d[2], a[0] * d[1] - a[1] * d[0]]
    dot = sum(x * y for x, y in zip(a, d))
    w = 1 + dot
    q = [axis[0], axis[1], axis[2], w]
    qn = math.sqrt(sum(c * c for c in q))
    return [c / qn for c in q]


def material_name(row, col):
    return "metallic %.2g roughness %.2g" % (METALLIC[row], ROUGHNESS[col])


def write_gltf(path):
    points, indices = uv_sphere()
    positions = [[c * RADIUS for c in p] for p in points]
    backdrop = [[-6, -4, BACKDROP_Z], [6, -4, BACKDROP_Z], [6, 4, BACKDROP_Z], [-6, 4, BACKDROP_Z]]
    blob = b"".join(struct.pack("<3f", *p) for p in positions)
    normals_offset = len(blob)
    blob += b"".join(struct.pack("<3f", *p) for p in points)
    indices_offset = len(blob)
    blob += struct.pack("<%dH" % len(indices), *indices)
    blob += b"\0" * (-len(blob) % 4)
    backdrop_offset = len(blob)
    blob += b"".join(struct.pack("<3f", *p) for p in backdrop)
    backdrop_indices_offset = len(blob)
    blob += struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    blob += b"\0" * (-len(blob) % 4)

    def bounds(ps):
        return [min(p[i] for p in ps) for i in range(3)], [max(p[i] for p in ps) for i in range(3)]

    lo, hi = bounds(positions)
    nlo, nhi = bounds(points)
    blo, bhi = bounds(backdrop)
    views = [
        {"buffer": 0, "byteOffset": 0, "byteLength": normals_offset, "target": 34962},
        {"buffer": 0, "byteOffset": normals_offset, "byteLength": normals_offset, "target": 34962},
        {"buffer": 0, "byteOffset": indices_offset, "byteLength": 2 * len(indices), "target": 34963},
        {"buffer": 0, "byteOffset": backdrop_offset, "byteLength": 48, "target": 34962},
        {"buffer": 0, "byteOffset": backdrop_indices_offset, "byteLength": 12, "target": 34963},
    ]
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3", "min": lo, "max": hi},
        {"bufferView": 1, "componentType": 5126, "count": len(points), "type": "VEC3", "min": nlo, "max": nhi},
        {"bufferView": 2, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC3", "min": blo, "max": bhi},
        {"bufferView": 4, "componentType": 5123, "count": 6, "type": "SCALAR"},
    ]
    materials, meshes, nodes = [], [], []
    for row in range(len(METALLIC)):
        for col in range(len(ROUGHNESS)):
            materials.append({"name": material_name(row, col), "pbrMetallicRoughness": {
                "baseColorFactor": BASE + [1.0], "metallicFactor": METALLIC[row], "roughnessFactor": ROUGHNESS[col]}})
            meshes.append({"name": "sphere " + material_name(row, col), "primitives": [
                {"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": len(materials) - 1}]})
            nodes.append({"name": "sphere %d,%d" % (row, col), "mesh": len(meshes) - 1, "translation": centre(row, col)})
    materials.append({"name": "backdrop", "pbrMetallicRoughness": {
        "baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
    meshes.append({"name": "backdrop", "primitives": [
        {"attributes": {"POSITION": 3}, "indices": 4, "material": len(materials) - 1}]})
    nodes.append({"name": "backdrop", "mesh": len(meshes) - 1})
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 0.0, CAMERA_Z]})
    nodes.append({"name": "sun", "rotation": quaternion_from_minus_z(SUN_DIRECTION),
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    nodes.append({"name": "bulb", "translation": BULB_POSITION, "extensions": {"KHR_lights_punctual": {"light": 1}}})
    gltf = {
        "asset": {"version": "2.0", "generator": "clpt scripts/make_pbr_sweep.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "sun", "type": "directional", "intensity": SUN_LUX},
            {"name": "bulb", "type": "point", "intensity": BULB_CANDELA}]}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {"yfov": YFOV, "znear": 0.1}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    }
    with open(path, "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def fmt(v):
    return "[" + ", ".join("%.6g" % c for c in v) + "]"


def write_toml(path):
    lines = [
        "# The glTF material sweep's TOML twin (scripts/make_pbr_sweep.py writes both; docs/materials.md).",
        "# Rows bottom to top: metallic %s; columns left to right: roughness %s." % (METALLIC, ROUGHNESS),
        "",
        "[image]", "width = 480", "height = 288", "",
        "[render]", "spp = 64", "estimator = \"nee\"", "",
        "[camera]", "position = %s" % fmt([0, 0, CAMERA_Z]), "look_at = [0, 0, 0]",
        "vertical_fov_deg = %.6g" % math.degrees(YFOV), "",
    ]
    for row in range(len(METALLIC)):
        for col in range(len(ROUGHNESS)):
            lines += ["[[sphere]]", "name = \"%s\"" % material_name(row, col), "center = %s" % fmt(centre(row, col)),
                      "radius = %.6g" % RADIUS,
                      "material = { type = \"pbr\", base_color = %s, metallic = %.6g, roughness = %.6g }"
                      % (fmt(BASE), METALLIC[row], ROUGHNESS[col]), ""]
    lines += ["[[mesh]]", "name = \"backdrop\"",
              "vertices = [%s]" % ", ".join(fmt(p) for p in
                                            [[-6, -4, BACKDROP_Z], [6, -4, BACKDROP_Z], [6, 4, BACKDROP_Z], [-6, 4, BACKDROP_Z]]),
              "triangles = [[0, 1, 2], [0, 2, 3]]",
              "material = { type = \"pbr\", base_color = [0.5, 0.5, 0.5], metallic = 0, roughness = 1 }", "",
              "[[light]]", "name = \"sun\"", "type = \"directional\"", "direction = %s" % fmt(SUN_DIRECTION),
              "lux = %.6g" % SUN_LUX, "",
              "[[light]]", "name = \"bulb\"", "type = \"point\"", "position = %s" % fmt(BULB_POSITION),
              "candela = %.6g" % BULB_CANDELA, ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes")
    write_gltf(os.path.join(out, "pbr-sweep.gltf"))
    write_toml(os.path.join(out, "pbr-sweep.toml"))
    print("wrote %s and %s" % (os.path.join(out, "pbr-sweep.gltf"), os.path.join(out, "pbr-sweep.toml")))


if __name__ == "__main__":
    main()
