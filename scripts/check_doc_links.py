#!/usr/bin/env python3
"""Checks that no file of the tree points outside the repository for what it relies on.

    scripts/check_doc_links.py    exit 1, naming file and line, for each reference that fails

Every mention of a Markdown file (`numerics.md`, `docs/design.md`, `[x](../README.md)`) in a file
git tracks must name a file of the repository, relative to the mentioning file's directory, to the
repository's root or to docs/; and nothing may point into the notes kept beside the repository
(`../shared/`), which a clone does not have. Web addresses (provenance of data, upstream issues)
are not checked, nor are files a command writes (`out/...`, `${DIR}/name.md`, `OUTDIR/name.md`).
"""
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SELF = "scripts/check_doc_links.py"
MD_REFERENCE = re.compile(r"[A-Za-z0-9_./-]*[A-Za-z0-9_-]\.md\b")
OUTSIDE = re.compile(r"\.\./shared\b|\bshared/(notes|specs)/")
TEXT = re.compile(r"\.(h|hpp|cpp|cl|sh|cmake|py|md|txt|toml)$|(^|/)(run|CMakeLists\.txt|\.gitignore)$")


def main():
    files = subprocess.run(["git", "-C", ROOT, "ls-files", "--cached", "--others", "--exclude-standard"], check=True, capture_output=True, text=True).stdout.split()
    problems, seen = [], set()
    for path in files:
        if not TEXT.search(path) or not os.path.exists(os.path.join(ROOT, path)) or path == SELF:
            continue  # (this file names the patterns it looks for)
        here = os.path.dirname(path)
        with open(os.path.join(ROOT, path), encoding="utf-8", errors="replace") as f:
            for number, line in enumerate(f, 1):
                if OUTSIDE.search(line):
                    problems.append(f"{path}:{number}: points outside the repository: {line.strip()}")
                for match in MD_REFERENCE.finditer(line):
                    ref = match.group(0)
                    before = line[:match.start()]
                    if re.search(r"https?://\S*$", before):
                        continue  # part of a web address
                    placeholder = re.match(r"[A-Z_]+/", ref)  # OUTDIR/..., DIR/...: a command's argument
                    if ref.startswith("out/") or before.endswith(("/", "$", "}")) or ref.startswith("/") or placeholder:
                        continue  # an output a command writes, not a document of the tree
                    if (path, number, ref) in seen:
                        continue
                    seen.add((path, number, ref))
                    if not any(os.path.isfile(os.path.normpath(os.path.join(ROOT, base, ref))) for base in (here, "", "docs")):
                        problems.append(f"{path}:{number}: '{ref}' is no file of the repository")
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} reference(s) point outside the repository or to nothing")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
