#!/usr/bin/env python3
"""Checks that every file of host/ includes only files of its own layer or of the layers below.

    scripts/check_layers.py    exit 1, naming file, line and both layers, for each upward include

The layers and their order are read from the table under "## Layers" in docs/architecture.md, the
one place that states them (from the bottom up: each row's first cell names a directory, e.g.
`host/cl/`). An include is `#include "DIR/NAME"`; DIR/NAME is looked up under host/ first and then
under the repository's root (so "kernels/types.h", shared with the device, is the kernels/ layer's
and "kernels/kernel_options.h" is host/kernels/'s). A directory of host/ missing from the table,
an include that names no file of the tree, or a table that cannot be read is an error too, so the
check cannot pass by not looking.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ARCHITECTURE = "docs/architecture.md"
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
LAYER_ROW = re.compile(r"^\|\s*`([A-Za-z0-9_/]+/)`\s*\|")
SOURCE = re.compile(r"\.(h|hpp|cpp)$")


def read_layers():
    """The layers' directories from the bottom up, as docs/architecture.md's table lists them."""
    layers, in_section = [], False
    with open(os.path.join(ROOT, ARCHITECTURE), encoding="utf-8") as f:
        for line in f:
            if line.startswith("## "):
                in_section = line.strip() == "## Layers"
                continue
            match = LAYER_ROW.match(line) if in_section else None
            if match:
                layers.append(match.group(1))
    return layers


def layer_of(path, layers):
    """The index of the layer holding the repository path `path`, or None."""
    best = None
    for index, directory in enumerate(layers):
        if path.startswith(directory) and (best is None or len(directory) > len(layers[best])):
            best = index
    return best


def resolve(include):
    """The repository path `#include "include"` names, or None."""
    for base in ("host", ""):
        candidate = os.path.join(base, include) if base else include
        if os.path.isfile(os.path.join(ROOT, candidate)):
            return candidate
    return None


def main():
    layers = read_layers()
    if len(layers) < 2:
        print(f"{ARCHITECTURE}: no layer table under '## Layers' (rows starting | `dir/` |)")
        return 1
    problems = []
    for directory in sorted(os.listdir(os.path.join(ROOT, "host"))):
        if os.path.isdir(os.path.join(ROOT, "host", directory)) and f"host/{directory}/" not in layers:
            problems.append(f"host/{directory}/: not in the layer table of {ARCHITECTURE}")
    checked = 0
    for folder, _, names in sorted(os.walk(os.path.join(ROOT, "host"))):
        for name in sorted(names):
            if not SOURCE.search(name):
                continue
            path = os.path.relpath(os.path.join(folder, name), ROOT)
            own = layer_of(path, layers)
            with open(os.path.join(ROOT, path), encoding="utf-8", errors="replace") as f:
                for number, line in enumerate(f, 1):
                    match = INCLUDE.match(line)
                    if not match or "/" not in match.group(1):
                        continue  # a system header, or one beside the file (its own layer)
                    checked += 1
                    target = resolve(match.group(1))
                    if target is None:
                        problems.append(f"{path}:{number}: includes \"{match.group(1)}\", no file of the tree")
                        continue
                    theirs = layer_of(target, layers)
                    if own is not None and (theirs is None or theirs > own):
                        above = layers[theirs] if theirs is not None else "a directory in no layer"
                        problems.append(f"{path}:{number}: includes {target} ({above}) from {layers[own]}, "
                                        f"a lower layer ({ARCHITECTURE}, Layers)")
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} include(s) break the layers")
        return 1
    print(f"ok: {checked} includes of host/ follow the layers {' < '.join(layers)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
