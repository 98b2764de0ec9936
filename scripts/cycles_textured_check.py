#!/usr/bin/env python3
"""Compares clpt with Blender's Cycles on textured, environment-lit glTF scenes (issue 34's
independent check; docs/textures.md "Checked against Cycles"). Blender is not a dependency of clpt:
this script needs Debian's `blender` (3.4.1 checked) and OpenImageIO's and numpy's Python modules.

It writes four variants of one glTF scene into WORK_DIR (a parquet floor of 8 x 8 with the tree's
textures, a tiled cube, a gold cube, a camera; no light of its own): `white-metal` (metallic 1,
base colour 1: the floor's roughness from a metallicRoughness image and its normal map, lit by
scenes/environment-sky.hdr at strength 0.02), `metal` (the same with base-colour images),
`dielectric` (metallic 0: the glTF material's Lambertian and specular lobes) and `emissive` (black
base colour, the images as emissive textures, no environment). Each is rendered by `clpt render`
and by Cycles (the glTF importer, the HDR as the world's Environment Texture, plain GGX, no
clamping, no denoising, the same bounce limit), and the script prints each pair's mean per channel
and the luminance ratios over a 6 x 4 grid of blocks.

Where the two renderers' models agree the images must agree: `white-metal` (F0 = 1, so no Fresnel
model is involved) and `emissive` (8-bit sRGB texels seen directly). Where they differ, they are
expected to differ: Cycles 3.4's Principled BSDF uses a Burley diffuse and, for metals, a Fresnel
interpolated by the dielectric Fresnel curve rather than glTF's Schlick curve.

    scripts/cycles_textured_check.py CLPT_BINARY WORK_DIR [--spp N] [--cycles-spp N] [--only NAME,...]
"""
import argparse
import base64
import json
import os
import shutil
import struct
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = os.path.join(ROOT, "scenes", "environment-sky.hdr")
STRENGTH = 0.02
WIDTH, HEIGHT, BOUNCES = 360, 240, 8

BLENDER_SIDE = r'''
import bpy, sys, numpy
numpy.bool = bool  # Blender 3.4's glTF importer uses the alias numpy 1.24 removed
scene_file, env, strength, w, h, spp, bounces, out = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=scene_file)
s = bpy.context.scene
s.camera = [o for o in s.objects if o.type == "CAMERA"][0]
world = bpy.data.worlds.new("environment"); s.world = world; world.use_nodes = True
tex = world.node_tree.nodes.new("ShaderNodeTexEnvironment"); tex.image = bpy.data.images.load(env)
tex.interpolation = "Linear"
background = world.node_tree.nodes["Background"]
world.node_tree.links.new(tex.outputs["Color"], background.inputs["Color"])
background.inputs["Strength"].default_value = float(strength)
for material in bpy.data.materials:
    if material.use_nodes:
        for node in material.node_tree.nodes:
            if node.type == "BSDF_PRINCIPLED": node.distribution = "GGX"
c = s.cycles
s.render.engine = "CYCLES"; c.device = "CPU"; c.samples = int(spp)
c.use_adaptive_sampling = False; c.use_denoising = False
c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = int(bounces)
c.sample_clamp_direct = 0; c.sample_clamp_indirect = 0; c.blur_glossy = 0
c.caustics_reflective = True; c.caustics_refractive = True
s.render.resolution_x = int(w); s.render.resolution_y = int(h); s.render.resolution_percentage = 100
s.view_settings.view_transform = "Standard"
s.render.image_settings.file_format = "OPEN_EXR"; s.render.image_settings.color_depth = "32"
s.render.filepath = out
bpy.ops.render.render(write_still=True)
'''


def write_scene(work, variant):
    """The glTF of `variant` in `work` (images beside it); returns its path."""
    for f in ["parquet.png", "parquet_normal.png", "parquet_roughness.png", "tiles.png"]:
        shutil.copy(os.path.join(ROOT, "scenes", "textures", f), os.path.join(work, f))
    # A metallicRoughness image: G the tree's roughness image, B (metallic) 1.
    spec = oiio.ImageInput.open(os.path.join(work, "parquet_roughness.png"))
    grey = np.asarray(spec.read_image(0, 0, 0, 1, "uint8")).reshape(spec.spec().height, spec.spec().width)
    spec.close()
    mr = np.stack([np.zeros_like(grey), grey, np.full_like(grey, 255)], axis=-1)
    out = oiio.ImageOutput.create(os.path.join(work, "parquet_mr.png"))
    out.open(os.path.join(work, "parquet_mr.png"), oiio.ImageSpec(mr.shape[1], mr.shape[0], 3, "uint8"))
    out.write_image(mr)
    out.close()
    blob, views, accessors = bytearray(), [], []

    def add(values, fmt, count, kind, component, target, bounds=None):
        while len(blob) % 4:
            blob.append(0)
        start = len(blob)
        blob.extend(struct.pack("<" + fmt * len(values), *values))
        views.append({"buffer": 0, "byteOffset": start, "byteLength": len(blob) - start, "target": target})
        a = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": kind}
        if bounds:
            a["min"], a["max"] = bounds
        accessors.append(a)
        return len(accessors) - 1

    def mesh(p, n, t, i):
        bounds = ([min(v[k] for v in p) for k in range(3)], [max(v[k] for v in p) for k in range(3)])
        return {"attributes": {"POSITION": add([c for v in p for c in v], "f", len(p), "VEC3", 5126, 34962, bounds),
                               "NORMAL": add([c for v in n for c in v], "f", len(n), "VEC3", 5126, 34962),
                               "TEXCOORD_0": add([c for v in t for c in v], "f", len(t), "VEC2", 5126, 34962)},
                "indices": add(i, "I", len(i), "SCALAR", 5125, 34963)}

    floor = mesh([[-4, 0, 4], [4, 0, 4], [4, 0, -4], [-4, 0, -4]], [[0, 1, 0]] * 4,
                 [[0, 4], [4, 4], [4, 0], [0, 0]], [0, 1, 2, 0, 2, 3])
    p, n, t, i = [], [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            normal = [0, 0, 0]; normal[axis] = sign
            u = [0, 0, 0]; u[(axis + 1) % 3] = 1
            v = [0, 0, 0]; v[(axis + 2) % 3] = 1
            if sign < 0:
                u, v = v, u
            base = len(p)
            for (a, b), uv in zip([(-1, -1), (1, -1), (1, 1), (-1, 1)], [(0, 1), (1, 1), (1, 0), (0, 0)]):
                p.append([0.5 * (normal[k] + a * u[k] + b * v[k]) for k in range(3)]); n.append(normal); t.append(list(uv))
            i += [base, base + 1, base + 2, base, base + 2, base + 3]
    cube = mesh(p, n, t, i)
    metallic = 0.0 if variant == "dielectric" else 1.0
    parquet = {"name": "parquet", "normalTexture": {"index": 2},
               "pbrMetallicRoughness": {"metallicFactor": metallic, "roughnessFactor": 1.0,
                                        "metallicRoughnessTexture": {"index": 1}, "baseColorTexture": {"index": 0}}}
    tiles = {"name": "tiles", "pbrMetallicRoughness": {"baseColorTexture": {"index": 3}, "metallicFactor": metallic,
                                                       "roughnessFactor": 0.6}}
    if variant == "dielectric":
        parquet["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {"index": 4}  # the grey image: B is grey
    if variant == "white-metal":
        for m in (parquet, tiles):
            del m["pbrMetallicRoughness"]["baseColorTexture"]
    if variant == "emissive":
        for m, image in ((parquet, 0), (tiles, 3)):
            m["pbrMetallicRoughness"] = {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0, "roughnessFactor": 1.0}
            m.pop("normalTexture", None)
            m["emissiveTexture"], m["emissiveFactor"] = {"index": image}, [1, 1, 1]
    gold = {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.78, 0.34, 1], "metallicFactor": 1.0,
                                                     "roughnessFactor": 0.3}}
    doc = {"asset": {"version": "2.0", "generator": "clpt scripts/cycles_textured_check.py"},
           "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3]}],
           "nodes": [{"mesh": 0},
                     {"mesh": 1, "translation": [-1.1, 0.6, 0.0], "scale": [1.2, 1.2, 1.2],
                      "rotation": [0, 0.2588190451, 0, 0.9659258263]},
                     {"mesh": 2, "translation": [1.2, 0.5, 0.6], "rotation": [0, -0.3826834324, 0, 0.9238795325]},
                     {"camera": 0, "translation": [0.0, 2.2, 6.5], "rotation": [-0.1736481777, 0, 0, 0.9848077530]}],
           "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.1}}],
           "meshes": [{"primitives": [dict(floor, material=0)]}, {"primitives": [dict(cube, material=1)]},
                      {"primitives": [dict(cube, material=2)]}],
           "materials": [parquet, tiles, gold],
           "textures": [{"source": k, "sampler": 0} for k in range(5)],
           "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}],
           "images": [{"uri": "parquet.png"}, {"uri": "parquet_mr.png"}, {"uri": "parquet_normal.png"},
                      {"uri": "tiles.png"}, {"uri": "parquet_roughness.png"}],
           "buffers": [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
           "bufferViews": views, "accessors": accessors}
    path = os.path.join(work, variant + ".gltf")
    json.dump(doc, open(path, "w"), indent=1)
    return path


def load(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"cycles_textured_check.py: cannot read {path}")
    spec = image.spec()
    pixels = np.asarray(image.read_image(0, 0, 0, 3, "float")).reshape(spec.height, spec.width, 3).astype(np.float64)
    image.close()
    return pixels


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("clpt")
    parser.add_argument("work")
    parser.add_argument("--spp", type=int, default=512, help="clpt's samples per pixel")
    parser.add_argument("--cycles-spp", type=int, default=256)
    parser.add_argument("--only", default="white-metal,emissive,metal,dielectric")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    blender_side = os.path.join(args.work, "cycles_side.py")
    open(blender_side, "w").write(BLENDER_SIDE)
    for variant in args.only.split(","):
        scene = write_scene(args.work, variant)
        strength = 0.0 if variant == "emissive" else STRENGTH
        ours, theirs = os.path.join(args.work, variant + ".clpt.exr"), os.path.join(args.work, variant + ".cycles.exr")
        command = [args.clpt, "render", scene, "--width", str(WIDTH), "--height", str(HEIGHT), "--spp", str(args.spp),
                   "--max-bounces", str(BOUNCES), "-q", "-o", ours]
        if strength > 0:
            command += ["--environment", ENV, "--environment-strength", str(strength)]
        subprocess.run(command, check=True)
        subprocess.run(["blender", "-b", "--python", blender_side, "--", scene, ENV, str(strength), str(WIDTH),
                        str(HEIGHT), str(args.cycles_spp), str(BOUNCES), theirs], check=True, stdout=subprocess.DEVNULL)
        a, b = load(ours), load(theirs)
        blocks = lambda x: x[: HEIGHT // 4 * 4, : WIDTH // 6 * 6].reshape(4, HEIGHT // 4, 6, WIDTH // 6, 3).mean((1, 3))
        luminance = np.array([0.2126, 0.7152, 0.0722])
        ratio = (blocks(a) @ luminance) / np.maximum(blocks(b) @ luminance, 1e-12)
        lit = (blocks(b) @ luminance) > 0.01  # blocks of sky behind the scene hold too little to compare
        print(f"{variant}: mean RGB clpt/Cycles " + " ".join(f"{r:.3f}" for r in a.mean((0, 1)) / b.mean((0, 1))) +
              f"; lit blocks' luminance ratio median {np.median(ratio[lit]):.3f}, range {ratio[lit].min():.3f}-"
              f"{ratio[lit].max():.3f} ({lit.sum()} of 24 blocks)")


if __name__ == "__main__":
    main()
