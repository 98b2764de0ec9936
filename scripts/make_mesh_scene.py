#!/usr/bin/env python3
"""Writes scenes/meshes/torus_knot.ply, the mesh of scenes/torus-knot.toml: a (2, 3) torus knot
as a tube of 320 x 160 quads (102,400 triangles), binary little-endian PLY with a unit normal per
vertex (the tube's analytic normals, so the mesh shades smooth). Generated, not committed (2.5 MB):
scripts/test.sh and scripts/render.sh run this when the file is missing.

    python3 scripts/make_mesh_scene.py [OUTPUT.ply]
"""
import math
import os
import struct
import sys

SEGMENTS = 320      # along the knot
SIDES = 160         # around the tube
P, Q = 2, 3         # the knot winds P times through the hole, Q times around the axis
TUBE_RADIUS = 0.18  # world units; the knot's centre line spans about [-1.5, 1.5]


def knot_point(t):
    """The knot's centre line at parameter t in [0, 2 pi)."""
    r = 1.0 + 0.5 * math.cos(Q * t)
    return (r * math.cos(P * t), 0.5 * math.sin(Q * t), r * math.sin(P * t))


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    return (a[0] / n, a[1] / n, a[2] / n)


def vertices():
    """(position, normal) per tube vertex, ring by ring."""
    out = []
    for i in range(SEGMENTS):
        t = 2 * math.pi * i / SEGMENTS
        centre = knot_point(t)
        h = 1e-4
        tangent = normalize(sub(knot_point(t + h), knot_point(t - h)))
        # A frame around the tangent from the curve's acceleration (never parallel for this knot).
        accel = sub(sub(knot_point(t + h), centre), sub(centre, knot_point(t - h)))
        binormal = normalize(cross(tangent, accel))
        normal = cross(binormal, tangent)
        for j in range(SIDES):
            a = 2 * math.pi * j / SIDES
            n = tuple(math.cos(a) * normal[k] + math.sin(a) * binormal[k] for k in range(3))
            out.append((tuple(centre[k] + TUBE_RADIUS * n[k] for k in range(3)), n))
    return out


def faces():
    """Quads (as two triangles) joining ring i to ring i + 1, wrapping around both ways."""
    for i in range(SEGMENTS):
        for j in range(SIDES):
            a = i * SIDES + j
            b = i * SIDES + (j + 1) % SIDES
            c = ((i + 1) % SEGMENTS) * SIDES + (j + 1) % SIDES
            d = ((i + 1) % SEGMENTS) * SIDES + j
            yield (a, d, c)
            yield (a, c, b)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "scenes", "meshes", "torus_knot.ply")
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    verts = vertices()
    tris = list(faces())
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        "comment written by scripts/make_mesh_scene.py: a (2, 3) torus knot tube\n"
        f"element vertex {len(verts)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\n"
        f"element face {len(tris)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    temporary = path + ".tmp"
    with open(temporary, "wb") as out:
        out.write(header.encode("ascii"))
        vertex = struct.Struct("<6f")
        out.write(b"".join(vertex.pack(*p, *n) for p, n in verts))
        face = struct.Struct("<B3i")
        out.write(b"".join(face.pack(3, *t) for t in tris))
    os.replace(temporary, path)  # never a half-written mesh under the scene's name
    print(f"wrote {path}: {len(verts)} vertices, {len(tris)} triangles")


if __name__ == "__main__":
    main()
