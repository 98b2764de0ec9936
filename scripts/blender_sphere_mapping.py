#!/usr/bin/env python3
"""Checks clpt's spherical mapping (docs/textures.md, "Spheres") against Blender's: run inside
Blender (Debian's `blender`, 3.4.1 checked), it renders a unit UV sphere whose emission is a 5 x 3
marker image read through an Image Texture node (Sphere projection, Generated coordinates, Closest)
with Cycles, from clpt's +X, -Z, -X and +Z (Blender's camera at (x, -z, y) for clpt's (x, y, z),
the axes Blender's glTF exchange turns), renders the same views with clpt (an emitter sphere with
the marker as its emission), and compares the 11 x 11 images pixel by pixel: every pixel whose
colour is one of the marker's in both must be the same one (pixels that mix two texels, at texel
edges and the silhouette, are skipped: the two renderers filter pixels differently). Exit 0 when
they agree, 1 when not, printing each view's middle row from both.

    blender -b --python scripts/blender_sphere_mapping.py -- CLPT_BINARY WORK_DIR
"""
import os
import struct
import subprocess
import sys
import zlib

import bpy
import mathutils

SIZE = 11
MIDDLE = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (1, 0, 1)]
ROWS = [[(1, 1, 1)] * 5, MIDDLE, [(0, 1, 1)] * 5]  # top (north) to bottom (south)
NAMES = {(1, 0, 0): "red", (0, 1, 0): "green", (0, 0, 1): "blue", (1, 1, 0): "yellow", (1, 0, 1): "magenta",
         (1, 1, 1): "white", (0, 1, 1): "cyan", (0, 0, 0): "black"}
VIEWS = [("+X", (5, 0, 0)), ("-Z", (0, 0, -5)), ("-X", (-5, 0, 0)), ("+Z", (0, 0, 5))]


def write_png(path, rows):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    raw = b"".join(b"\0" + bytes(255 * c for px in row for c in px) for row in rows)
    header = struct.pack(">IIBBBBB", len(rows[0]), len(rows), 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def colour_name(rgb):
    """The marker colour a pixel shows, or None where it mixes texels (any channel not near 0 or 1)."""
    if any(0.1 < c < 0.9 for c in rgb):
        return None
    return NAMES.get(tuple(int(round(c)) for c in rgb))


def image_names(path):
    """Row-major from the top: the colour name of every pixel of an image Blender can load."""
    image = bpy.data.images.load(path, check_existing=False)
    px = list(image.pixels)  # bottom row first, RGBA floats
    w, h = image.size
    return [[colour_name(px[((h - 1 - r) * w + c) * 4:((h - 1 - r) * w + c) * 4 + 3]) for c in range(w)] for r in range(h)]


def blender_view(work, marker, position):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 16
    scene.cycles.device = "CPU"
    scene.cycles.use_denoising = False
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "PNG"
    bpy.ops.mesh.primitive_uv_sphere_add(segments=256, ring_count=128, radius=1)
    sphere = bpy.context.active_object
    material = bpy.data.materials.new("marker")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    links = material.node_tree.links
    nodes.clear()
    coordinates = nodes.new("ShaderNodeTexCoord")
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = bpy.data.images.load(marker)
    texture.projection = "SPHERE"
    texture.interpolation = "Closest"
    emission = nodes.new("ShaderNodeEmission")
    output = nodes.new("ShaderNodeOutputMaterial")
    links.new(coordinates.outputs["Generated"], texture.inputs["Vector"])
    links.new(texture.outputs["Color"], emission.inputs["Color"])
    links.new(emission.outputs["Emission"], output.inputs["Surface"])
    sphere.data.materials.append(material)
    camera_data = bpy.data.cameras.new("camera")
    camera_data.type = "ORTHO"
    camera_data.ortho_scale = 2.2
    camera = bpy.data.objects.new("camera", camera_data)
    scene.collection.objects.link(camera)
    scene.camera = camera
    x, y, z = position
    camera.location = (x, -z, y)  # clpt (+Y up) to Blender (+Z up)
    camera.rotation_euler = (-mathutils.Vector(camera.location)).to_track_quat("-Z", "Y").to_euler()
    scene.render.filepath = os.path.join(work, "blender.png")
    bpy.ops.render.render(write_still=True)
    return image_names(scene.render.filepath)


def clpt_view(clpt, work, position):
    scene = os.path.join(work, "view.toml")
    with open(scene, "w") as f:
        f.write(f"""[image]
width = {SIZE}
height = {SIZE}
[render]
spp = 16
max_bounces = 0
[camera]
position = [{position[0]}, {position[1]}, {position[2]}]
look_at = [0, 0, 0]
projection = "orthographic"
height = 2.2
[[sphere]]
center = [0, 0, 0]
radius = 1
material = {{ type = "emitter", emission = {{ texture = "marker.png", filter = "nearest" }} }}
""")
    subprocess.run([clpt, "render", scene, "-q", "-o", os.path.join(work, "clpt.exr")], check=True)
    return image_names(os.path.join(work, "clpt.png"))


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2:
        print(__doc__)
        return 2
    clpt, work = os.path.abspath(args[0]), os.path.abspath(args[1])
    os.makedirs(work, exist_ok=True)
    marker = os.path.join(work, "marker.png")
    write_png(marker, ROWS)
    compared = mismatches = 0
    for label, position in VIEWS:
        b = blender_view(work, marker, position)
        c = clpt_view(clpt, work, position)
        print(f"from clpt's {label}: Blender {b[SIZE // 2]}")
        print(f"from clpt's {label}: clpt    {c[SIZE // 2]}")
        for r in range(SIZE):
            for col in range(SIZE):
                if b[r][col] is None or c[r][col] is None:
                    continue
                compared += 1
                if b[r][col] != c[r][col]:
                    mismatches += 1
                    print(f"  MISMATCH from {label} at ({col}, {r}): Blender {b[r][col]}, clpt {c[r][col]}")
    print(f"{compared} pixels compared, {mismatches} differ")
    return 1 if mismatches or compared < 4 * SIZE * SIZE // 3 else 0


if __name__ == "__main__":
    sys.exit(main())
