#!/usr/bin/env python3
"""Writes scenes/meshes/dense_surface.ply, the mesh of scenes/dense-surface.toml: a finely
tessellated displaced surface (a height field of rolling hills, 725 x 725 quads: 1,051,250
triangles) for the book's room, binary little-endian PLY with the height field's analytic unit
normal per vertex. The 1 M-triangle scene of issue 35 (build time, traversal statistics and the
Embree anchor of `clpt bench`: docs/performance.md, "Traversal"). Generated, not committed
(26 MB): scripts/test.sh and scripts/render.sh run this when the file is missing
(scripts/common.sh, clpt_generate_meshes).

    python3 scripts/make_dense_mesh_scene.py [OUTPUT.ply] [--quads N]
"""
import math
import os
import struct
import sys

QUADS = 725        # per side: 2 * 725^2 = 1,051,250 triangles
HALF_SIZE = 2.6    # world units: the surface spans [-2.6, 2.6] in x and z (model space)


def height(x, z):
    """The displacement: a few crossed waves and a bump, between about 0.05 and 0.75."""
    r = math.hypot(x - 0.6, z + 0.4)
    return (0.32 + 0.12 * math.sin(3.1 * x + 0.7) * math.cos(2.3 * z - 0.4)
            + 0.06 * math.sin(9.0 * x + 5.0 * z) + 0.25 * math.exp(-3.0 * r * r))


def normal(x, z):
    """The unit normal of the height field y = height(x, z), by central differences."""
    h = 1e-5
    dx = (height(x + h, z) - height(x - h, z)) / (2 * h)
    dz = (height(x, z + h) - height(x, z - h)) / (2 * h)
    n = math.sqrt(dx * dx + 1 + dz * dz)
    return (-dx / n, 1 / n, -dz / n)


def main():
    args = [a for a in sys.argv[1:]]
    quads = QUADS
    if "--quads" in args:
        i = args.index("--quads")
        quads = int(args[i + 1])
        del args[i:i + 2]
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    path = args[0] if args else os.path.join(root, "scenes", "meshes", "dense_surface.ply")
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    side = quads + 1
    vertex = struct.Struct("<6f")
    chunks = []
    for i in range(side):
        x = -HALF_SIZE + 2 * HALF_SIZE * i / quads
        for j in range(side):
            z = -HALF_SIZE + 2 * HALF_SIZE * j / quads
            chunks.append(vertex.pack(x, height(x, z), z, *normal(x, z)))
    face = struct.Struct("<B3i")
    faces = []
    for i in range(quads):
        for j in range(quads):
            a = i * side + j
            b = a + 1
            c = a + side + 1
            d = a + side
            # Counter-clockwise seen from +y (the normal's side).
            faces.append(face.pack(3, a, b, c))
            faces.append(face.pack(3, a, c, d))
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        "comment written by scripts/make_dense_mesh_scene.py: a displaced surface\n"
        f"element vertex {side * side}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    temporary = path + ".tmp"
    with open(temporary, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(b"".join(chunks))
        out.write(b"".join(faces))
    os.replace(temporary, path)  # never a half-written mesh under the scene's name
    print(f"wrote {path}: {side * side} vertices, {len(faces)} triangles")


if __name__ == "__main__":
    main()
