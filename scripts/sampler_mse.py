#!/usr/bin/env python3
"""Error of each sampler at equal samples on the book's three scenes, against the gemspt references
(docs/sampler.md). For every scene, estimator, sampler and sample count it renders 160x120 with
`clpt render` and prints, as a markdown table, the render's MSE against
tests/reference/gemspt_<scene>_160x120.exr with the reference's own noise taken out:

    MSE = mean over pixels and RGB channels of (x - ref)^2  -  mean of the reference's variance channels

(E[(x - ref)^2] = bias^2 + var(x) + var(ref) per value, and the variance channels are the
reference's variances of its pixel means). Each entry is the mean over --seeds renders.

The references were made with the book's grid sampler (16 fixed sub-pixel positions), while jitter
and sobol average over the whole pixel: the two converge to slightly different images (different
pixel filters), so every MSE here has a floor that no sample count removes. --floor-spp N prints,
instead of the table, that floor per scene and estimator: one jitter render at N spp, its MSE
minus its own noise (the mean of its variance channels) and the reference's.

    scripts/sampler_mse.py [--clpt build/clpt] [--spp 16,64,256] [--seeds 1,2]
                           [--samplers jitter,sobol] [--estimators book,nee] [--scenes diffuse,...]
                           [--floor-spp N]

Needs oiiotool (OpenImageIO's command-line tool, whose --dumpdata prints the EXR channels)."""
import argparse
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read_channels(exr, names):
    """Lists of the named channels of an EXR, pixel by pixel, as oiiotool prints them."""
    info = subprocess.run(["oiiotool", "--info", "-v", exr], check=True, capture_output=True, text=True).stdout
    listed = next(line.split(":", 1)[1] for line in info.splitlines() if "channel list:" in line)
    order = [c.strip() for c in listed.split(",")]
    index = [order.index(n) for n in names]
    dump = subprocess.run(["oiiotool", "--dumpdata", exr], check=True, capture_output=True, text=True).stdout
    out = [[] for _ in names]
    for line in dump.splitlines():
        if "Pixel (" not in line:
            continue
        values = line.split(":", 1)[1].split()
        for k, i in enumerate(index):
            out[k].append(float(values[i]))
    return [v for pixel in zip(*out) for v in pixel]


def render(a, scene, spp, sampler, estimator, seed, exr):
    subprocess.run([a.clpt, "render", os.path.join(ROOT, "scenes", scene + ".toml"), "--width", "160",
                    "--height", "120", "--spp", str(spp), "--sampler", sampler, "--estimator", estimator,
                    "--seed", seed, "-q", "-o", exr], check=True)


def mean_square_difference(x, ref):
    return sum((p - q) ** 2 for p, q in zip(x, ref)) / len(x)


def print_floors(a):
    variances = ["variance.R", "variance.G", "variance.B"]
    print(f"| scene | estimator | floor (jitter, {a.floor_spp} spp) |")
    print("|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for scene in a.scenes.split(","):
            ref_exr = os.path.join(ROOT, "tests", "reference", f"gemspt_{scene}_160x120.exr")
            ref = read_channels(ref_exr, ["R", "G", "B"])
            ref_var = read_channels(ref_exr, variances)
            for estimator in a.estimators.split(","):
                exr = os.path.join(work, "floor.exr")
                render(a, scene, a.floor_spp, "jitter", estimator, "1", exr)
                x = read_channels(exr, ["R", "G", "B"])
                x_var = read_channels(exr, variances)
                floor = mean_square_difference(x, ref) - sum(x_var) / len(x_var) - sum(ref_var) / len(ref_var)
                print(f"| {scene} | {estimator} | {floor:.3g} |", flush=True)
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--clpt", default=os.path.join(ROOT, "build", "clpt"))
    ap.add_argument("--spp", default="16,64,256")
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--samplers", default="jitter,sobol")
    ap.add_argument("--estimators", default="book,nee")
    ap.add_argument("--scenes", default="diffuse,specular,glass")
    ap.add_argument("--floor-spp", type=int, default=0)
    a = ap.parse_args()
    if a.floor_spp:
        return print_floors(a)
    spps = [int(s) for s in a.spp.split(",")]
    seeds = a.seeds.split(",")
    samplers = a.samplers.split(",")
    with tempfile.TemporaryDirectory() as work:
        print("| scene | estimator | spp | " + " | ".join(f"MSE {s}" for s in samplers) +
              (f" | {samplers[1]} / {samplers[0]}" if len(samplers) == 2 else "") + " |")
        print("|---" * (3 + len(samplers) + (1 if len(samplers) == 2 else 0)) + "|")
        for scene in a.scenes.split(","):
            ref_exr = os.path.join(ROOT, "tests", "reference", f"gemspt_{scene}_160x120.exr")
            ref = read_channels(ref_exr, ["R", "G", "B"])
            ref_var = read_channels(ref_exr, ["variance.R", "variance.G", "variance.B"])
            ref_noise = sum(ref_var) / len(ref_var)
            for estimator in a.estimators.split(","):
                for spp in spps:
                    mse = {}
                    for sampler in samplers:
                        total = 0.0
                        for seed in seeds:
                            exr = os.path.join(work, "render.exr")
                            render(a, scene, spp, sampler, estimator, seed, exr)
                            x = read_channels(exr, ["R", "G", "B"])
                            total += mean_square_difference(x, ref) - ref_noise
                        mse[sampler] = total / len(seeds)
                    row = f"| {scene} | {estimator} | {spp} | " + " | ".join(f"{mse[s]:.3g}" for s in samplers)
                    if len(samplers) == 2:
                        row += f" | {mse[samplers[1]] / mse[samplers[0]]:.2f}"
                    print(row + " |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
