#!/usr/bin/env python3
"""Times clpt against Blender's Cycles at equal error on the Cornell box (issue 35's independent
check; docs/performance.md "Against Cycles"). Blender is not a dependency of clpt: this script needs
Debian's `blender` (3.4.1 checked) and OpenImageIO's and numpy's Python modules.

The scene is scenes/cornell-box.toml, read by both: clpt renders the file; Cycles builds the same
quads, camera and materials from it (Diffuse BSDF, which is Lambertian, for the walls and blocks;
an Emission shader of the file's radiance for the light), next-event estimation with MIS (its
default for a mesh light), the same bounce limit, a 1-pixel box filter, no clamping, no denoising,
no adaptive sampling, the Standard view transform, both threads of this machine.

Each renderer is compared with its own converged image (REF_SPP samples per pixel), so that a
difference of model (Cycles' bounce counting, its light's two sides) does not count as error. For
each sample count the script times the whole process (wall seconds), then reports the RMSE against
the reference, the samples per second from the difference between the largest and smallest counts
(which removes the start-up), and the seconds each renderer needs, by its own 1/sqrt(spp) fit, to
reach the RMSE given by --target.

    scripts/cycles_speed_check.py CLPT_BINARY WORK_DIR [--size N] [--spp 16,32,64] [--ref-spp 4096]
        [--target 0.01] [--repeat 2] [--mesh PLY]
"""
import argparse
import math
import os
import subprocess
import sys
import time

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "scenes", "cornell-box.toml")

BLENDER_SIDE = r'''
import bpy, math, os, sys, tomllib
scene_file, size, spp, seed, out = sys.argv[sys.argv.index("--") + 1:]
doc = tomllib.load(open(scene_file, "rb"))
bpy.ops.wm.read_factory_settings(use_empty=True)
s = bpy.context.scene
for m in doc["mesh"]:
    if "file" in m:  # a PLY, scaled then translated as clpt does (no rotation here)
        bpy.ops.import_mesh.ply(filepath=os.path.join(os.path.dirname(scene_file), m["file"]))
        obj = bpy.context.selected_objects[0]
        obj.scale = (m.get("scale", 1.0),) * 3
        obj.location = tuple(m.get("translate", (0.0, 0.0, 0.0)))
        for poly in obj.data.polygons: poly.use_smooth = True
        mesh = obj.data
    else:
        mesh = bpy.data.meshes.new(m["name"])
        mesh.from_pydata([tuple(v) for v in m["vertices"]], [], [tuple(q) for q in m.get("quads", [])] +
                         [tuple(t) for t in m.get("triangles", [])])
        obj = bpy.data.objects.new(m["name"], mesh)
        s.collection.objects.link(obj)
    mat = bpy.data.materials.new(m["name"]); mat.use_nodes = True
    nodes = mat.node_tree.nodes; nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    spec = m["material"]
    if spec["type"] == "emitter":
        shader = nodes.new("ShaderNodeEmission")
        e = spec["emission"]; peak = max(e)
        shader.inputs["Color"].default_value = (e[0] / peak, e[1] / peak, e[2] / peak, 1)
        shader.inputs["Strength"].default_value = peak
    elif spec["type"] == "lambertian":
        shader = nodes.new("ShaderNodeBsdfDiffuse")
        r = spec["reflectance"]
        shader.inputs["Color"].default_value = (r[0], r[1], r[2], 1)
        shader.inputs["Roughness"].default_value = 0.0
    else:
        sys.exit("cycles_speed_check.py: material type " + spec["type"] + " is not translated")
    mat.node_tree.links.new(shader.outputs[0], output.inputs["Surface"])
    mesh.materials.clear()
    mesh.materials.append(mat)
cam_doc = doc["camera"]
camera = bpy.data.cameras.new("camera")
camera.sensor_fit = "VERTICAL"
camera.angle_y = math.radians(cam_doc["vertical_fov_deg"])
camera.clip_start = 1.0; camera.clip_end = 1e5
cam = bpy.data.objects.new("camera", camera)
s.collection.objects.link(cam)
s.camera = cam
cam.location = tuple(cam_doc["position"])
# The file looks along +z with +y up: the camera's -Z axis turned to +z about y.
assert cam_doc["look_at"][0] == cam_doc["position"][0] and cam_doc["look_at"][1] == cam_doc["position"][1]
cam.rotation_euler = (0.0, math.pi, 0.0)
world = bpy.data.worlds.new("black"); s.world = world; world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
c = s.cycles
s.render.engine = "CYCLES"; c.device = "CPU"; c.samples = int(spp); c.seed = int(seed)
c.use_adaptive_sampling = False; c.use_denoising = False
c.max_bounces = c.diffuse_bounces = int(doc["render"]["max_bounces"])
c.glossy_bounces = c.transmission_bounces = c.volume_bounces = c.transparent_max_bounces = 0
c.sample_clamp_direct = 0; c.sample_clamp_indirect = 0
c.pixel_filter_type = "BOX"; c.filter_width = 1.0
s.render.threads_mode = "FIXED"; s.render.threads = 2
s.render.resolution_x = s.render.resolution_y = int(size); s.render.resolution_percentage = 100
s.view_settings.view_transform = "Standard"; s.view_settings.look = "None"
s.render.image_settings.file_format = "OPEN_EXR"; s.render.image_settings.color_depth = "32"
s.render.filepath = out
bpy.ops.render.render(write_still=True)
'''


def ply_bounds(path):
    """The lower and upper corners of a binary little-endian PLY's vertices (x, y, z first)."""
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                sys.exit(f"cycles_speed_check.py: {path}: no end_header")
            header += line
        lines = header.decode("ascii").splitlines()
        if "format binary_little_endian 1.0" not in lines:
            sys.exit(f"cycles_speed_check.py: {path}: not a binary little-endian PLY")
        count = next(int(l.split()[2]) for l in lines if l.startswith("element vertex"))
        start = next(i for i, l in enumerate(lines) if l.startswith("element vertex"))
        props = []
        for l in lines[start + 1:]:
            if l.startswith("element") or l == "end_header":
                break
            props.append(l.split())
        if [p[2] for p in props[:3]] != ["x", "y", "z"] or any(p[:2] != ["property", "float"] for p in props):
            sys.exit(f"cycles_speed_check.py: {path}: expected vertices of float properties, x, y, z first")
        v = np.frombuffer(f.read(count * 4 * len(props)), dtype="<f4").reshape(count, len(props))[:, :3]
    return v.min(0).astype(float), v.max(0).astype(float)


def scene_with_mesh(work, ply):
    """scenes/cornell-box.toml without its two blocks (its last two meshes) and with the PLY in their
    place: 250 mm across, on the floor at the box's middle."""
    lo, hi = ply_bounds(ply)
    scale = 250.0 / float((hi - lo).max())
    centre = (lo + hi) / 2
    translate = [278.0 - scale * centre[0], 20.0 - scale * lo[1], 280.0 - scale * centre[2]]
    path = os.path.join(work, "cornell-box-" + os.path.splitext(os.path.basename(ply))[0] + ".toml")
    box = open(SCENE).read()
    cut = box.find('[[mesh]]\nname = "short_block"')
    if cut < 0:
        sys.exit(f"cycles_speed_check.py: {SCENE}: no short_block mesh to replace")
    text = box[:cut] + (
        f'[[mesh]]\nname = "inside"\nfile = "{os.path.abspath(ply)}"\nscale = {scale!r}\n'
        f"translate = [{translate[0]!r}, {translate[1]!r}, {translate[2]!r}]\n"
        'material = { type = "lambertian", reflectance = [0.7, 0.5, 0.3] }\n')
    open(path, "w").write(text)
    return path


def load(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"cycles_speed_check.py: cannot read {path}")
    spec = image.spec()
    pixels = np.asarray(image.read_image(0, 0, 0, 3, "float")).reshape(spec.height, spec.width, 3).astype(np.float64)
    image.close()
    return pixels


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("clpt")
    parser.add_argument("work")
    parser.add_argument("--size", type=int, default=256, help="image width and height")
    parser.add_argument("--spp", default="16,32,64", help="sample counts timed")
    parser.add_argument("--ref-spp", type=int, default=4096, help="each reference's samples per pixel")
    parser.add_argument("--target", type=float, default=0.01, help="RMSE to compare the times at")
    parser.add_argument("--repeat", type=int, default=2, help="runs of each count, alternating renderers")
    parser.add_argument("--clpt-args", default="--sampler sobol", help="more arguments to clpt render")
    parser.add_argument("--mesh", help="a binary PLY (e.g. scenes/meshes/torus_knot.ply) put in the box")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    scene = scene_with_mesh(args.work, args.mesh) if args.mesh else SCENE
    blender_side = os.path.join(args.work, "cycles_side.py")
    open(blender_side, "w").write(BLENDER_SIDE)
    counts = [int(n) for n in args.spp.split(",")]

    def render(who, spp, seed, out):
        if who == "clpt":
            command = [args.clpt, "render", scene, "--width", str(args.size), "--height", str(args.size),
                       "--spp", str(spp), "--seed", str(seed), "-q", "-o", out] + args.clpt_args.split()
        else:
            command = ["blender", "-b", "--python", blender_side, "--", scene, str(args.size), str(spp), str(seed), out]
        start = time.monotonic()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        return time.monotonic() - start

    refs = {}
    for who in ("clpt", "cycles"):
        path = os.path.join(args.work, f"{who}.ref.exr")
        if not os.path.exists(path):
            print(f"{who}: reference at {args.ref_spp} spp ...", flush=True)
            render(who, args.ref_spp, 1000, path)
        refs[who] = load(path)
    mean = {w: refs[w].mean((0, 1)) for w in refs}
    print("references' mean RGB: clpt " + " ".join(f"{v:.4f}" for v in mean["clpt"]) + ", Cycles " +
          " ".join(f"{v:.4f}" for v in mean["cycles"]) + ", ratio " +
          " ".join(f"{a / b:.3f}" for a, b in zip(mean["clpt"], mean["cycles"])))
    results = {w: {n: [] for n in counts} for w in refs}
    for r in range(args.repeat):
        for n in counts:
            for who in ("clpt", "cycles"):
                out = os.path.join(args.work, f"{who}.{n}.{r}.exr")
                seconds = render(who, n, r + 1, out)
                rmse = math.sqrt(np.mean((load(out) - refs[who]) ** 2))
                results[who][n].append((seconds, rmse))
                print(f"{who:6s} {n:5d} spp: {seconds:6.2f} s, RMSE {rmse:.5f}", flush=True)
    pixels = args.size * args.size
    for who in ("clpt", "cycles"):
        med = {n: (float(np.median([s for s, _ in results[who][n]])), float(np.median([e for _, e in results[who][n]])))
               for n in counts}
        lo, hi = counts[0], counts[-1]
        rate = pixels * (hi - lo) / max(med[hi][0] - med[lo][0], 1e-9)
        # RMSE^2 = a / spp fitted over the counts; the time to the target by the fitted rate and start-up.
        a = float(np.mean([med[n][1] ** 2 * n for n in counts]))
        spp_needed = a / args.target ** 2
        startup = med[lo][0] - pixels * lo / rate
        print(f"{who}: " + ", ".join(f"{n} spp {med[n][0]:.2f} s RMSE {med[n][1]:.4f}" for n in counts) +
              f"; {rate / 1e6:.2f} M samples/s from {lo} to {hi} spp; RMSE {args.target} at about "
              f"{spp_needed:.0f} spp, {startup + pixels * spp_needed / rate:.1f} s")


if __name__ == "__main__":
    main()
