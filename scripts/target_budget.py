#!/usr/bin/env python3
"""What a path-rate target leaves a path segment, beside what one closest-hit query costs: reads
the JSON of one or more runs of `clpt bench --traversal-anchor embree` whose first row without a
hierarchy is the plain scene (the book's diffuse scene), and prints, per other row with an anchor,
nanoseconds of one core per path segment or query (from the rates per CPU-second) over the runs:
clpt's whole segment, the budget a target ratio of the plain scene's paths per CPU-second leaves
it, Embree's rtcIntersect1 (fastest and robust scenes) and rtcIntersect16 per ray, and clpt's own
closest-hit query alone (trace.cl). Several runs give min-max ranges. docs/performance.md, "What
limits the speed", has the table this prints and its command.

usage: scripts/target_budget.py [--target SUBSTRING=RATIO ...] RUN.json [RUN.json ...]
  e.g. --target many1000=0.5 --target dense-surface=0.25
"""
import argparse
import json
import sys


def ns(rate):
    return 1e9 / rate if rate > 0 else float("nan")


def span(values):
    lo, hi = min(values), max(values)
    return f"{lo:.0f}" if round(lo) == round(hi) else f"{lo:.0f}-{hi:.0f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", help="clpt bench --json files")
    parser.add_argument("--target", action="append", default=[],
                        help="SUBSTRING=RATIO: rows whose scene contains SUBSTRING aim at RATIO of the plain paths/CPU-s")
    args = parser.parse_args()
    targets = []
    for t in args.target:
        key, sep, ratio = t.partition("=")
        try:
            targets.append((key, float(ratio)))
        except ValueError:
            sep = ""
        if not sep or not key:
            sys.exit(f"target_budget.py: --target {t}: expected SUBSTRING=RATIO")

    table = {}  # scene -> column -> values over the runs
    plain_ns = []
    for path in args.runs:
        try:
            rows = json.load(open(path))["rows"]
        except (OSError, ValueError, KeyError) as e:
            sys.exit(f"target_budget.py: {path}: not a clpt bench JSON file ({e})")
        plain = next((r for r in rows if r.get("triangles", 0) == 0 and r.get("hierarchy_spheres", 0) == 0), None)
        if plain is None:
            sys.exit(f"target_budget.py: {path}: no row without a hierarchy (the plain scene) to compare with")
        plain_paths_cpu = plain["paths_per_cpu_s"]["median"]
        plain_segments = plain["segments_per_s"]["median"] / plain["paths_per_s"]["median"]
        plain_ns.append(ns(plain_paths_cpu * plain_segments))
        for r in rows:
            if "anchor" not in r:
                continue
            segments = r["segments_per_s"]["median"] / r["paths_per_s"]["median"]
            paths_cpu = r["paths_per_cpu_s"]["median"]
            a = r["anchor"]
            col = table.setdefault(r["scene"], {})
            col.setdefault("clpt", []).append(ns(paths_cpu * segments))
            col.setdefault("ratio", []).append(paths_cpu / plain_paths_cpu)
            ratio = next((v for k, v in targets if k in r["scene"]), None)
            if ratio is not None:
                col.setdefault("budget", []).append(ns(ratio * plain_paths_cpu * segments))
            col.setdefault("embree", []).append(ns(a["rtcIntersect1_rays_per_cpu_s"]))
            col.setdefault("robust", []).append(ns(a["robust"]["rtcIntersect1_rays_per_cpu_s"]))
            col.setdefault("packet", []).append(ns(a["rtcIntersect16_rays_per_cpu_s"]))
            if "trace" in r:
                col.setdefault("trace", []).append(ns(r["trace"]["rays_per_cpu_s"]))
    if not table:
        sys.exit("target_budget.py: no row has an anchor (run clpt bench with --traversal-anchor embree)")

    print(f"plain scene: {span(plain_ns)} ns a segment ({len(plain_ns)} run{'s' if len(plain_ns) > 1 else ''})")
    print("| scene | clpt ns/segment | of the plain paths/CPU-s | target's budget ns/segment | "
          "Embree rtcIntersect1 ns (robust) | rtcIntersect16 ns/ray | clpt trace.cl ns |")
    print("|---|---|---|---|---|---|---|")
    for scene, col in table.items():
        lo, hi = f"{min(col['ratio']):.3f}", f"{max(col['ratio']):.3f}"
        ratio = lo if lo == hi else f"{lo}-{hi}"
        budget = span(col["budget"]) if "budget" in col else "-"
        trace = span(col["trace"]) if "trace" in col else "-"
        print(f"| {scene} | {span(col['clpt'])} | {ratio} | {budget} | {span(col['embree'])} ({span(col['robust'])}) "
              f"| {span(col['packet'])} | {trace} |")


if __name__ == "__main__":
    main()
