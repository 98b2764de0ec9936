#!/usr/bin/env python3
"""Writes the book's diffuse scene plus N small spheres on its floor (the issue-14 speed scene:
"the book's diffuse scene with 1000 extra small spheres"), for `clpt bench` and the traversal
notes in docs/performance.md. Deterministic: the same N and seed give the same file.

usage: scripts/many_spheres_scene.py [--count 1000] [--seed 14] OUT.toml
"""
import argparse
import pathlib
import random

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("out")
parser.add_argument("--count", type=int, default=1000)
parser.add_argument("--seed", type=int, default=14)
args = parser.parse_args()

root = pathlib.Path(__file__).resolve().parent.parent
text = (root / "scenes" / "diffuse.toml").read_text()
rng = random.Random(args.seed)
lines = [text.rstrip("\n"), "", f"# {args.count} small Lambertian balls on the floor (scripts/many_spheres_scene.py, seed {args.seed})."]
for i in range(args.count):
    r = rng.uniform(0.04, 0.12)
    x = rng.uniform(-2.8, 8.8)
    z = rng.uniform(-2.8, 2.8)
    rho = [round(rng.uniform(0.2, 0.9), 3) for _ in range(3)]
    lines += ["", "[[sphere]]", f'name = "pebble{i}"', f"center = [{x:.4f}, {r:.4f}, {z:.4f}]", f"radius = {r:.4f}",
              f'material = {{ type = "lambertian", reflectance = [{rho[0]}, {rho[1]}, {rho[2]}] }}']
pathlib.Path(args.out).write_text("\n".join(lines) + "\n")
