#!/usr/bin/env python3
"""Checks that no file of the tree points outside the repository, or to nothing, for what it relies on.

    scripts/check_doc_links.py    exit 1, naming file and line, for each reference that fails

Every mention of a Markdown file (`numerics.md`, `docs/design.md`, `[x](../README.md)`) in a file
git tracks must name a file of the repository, relative to the mentioning file's directory, to the
repository's root or to docs/; and nothing may point into the notes kept beside the repository
(`../shared/`), which a clone does not have. Web addresses (provenance of data, upstream issues)
are not checked, nor are files a command writes (`out/...`, `${DIR}/name.md`, `OUTDIR/name.md`).
In Markdown files every link target (`[x](docs/a.png)`, `![x](b.png)`), whatever its type, must
be a file or folder relative to the linking file, and an anchor (`[x](cli.md#limits)`) a heading
of the page it names. A section named after a Markdown file (`design.md, "Execution forms"`,
`[x](mpi.md), "Scaling"`) must begin a heading of that file.
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
# A Markdown link or image: [text](target) or ![alt](target "title"); the target up to a space or ')'.
MD_LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
# After a mention of a .md file: an optional anchor and ')' closing a link, then `, "Section"`,
# ` "Section"` or ` ("Section"`. The quotes may be escaped, as in a C++ string.
SECTION = re.compile(r"^(?:#[^)\s]*)?\)?,?\s\(?\\?\"([^\"\\]+)\\?\"")
FENCE = re.compile(r"^\s*(```|~~~)")


def headings(path, cache={}):
    """The headings of a Markdown file, outside code fences, without their leading #s."""
    if path not in cache:
        found, fenced = [], False
        with open(path, encoding="utf-8", errors="replace") as f:
            for line in f:
                if FENCE.match(line):
                    fenced = not fenced
                elif not fenced and line.startswith("#"):
                    found.append(line.lstrip("#").strip())
        cache[path] = found
    return cache[path]


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces as '-'."""
    return re.sub(r"[^\w\- ]", "", heading.lower()).replace(" ", "-")


def resolve(ref, here):
    """The file `ref` names, relative to `here`, the root or docs/; None when there is none."""
    for base in (here, "", "docs"):
        path = os.path.normpath(os.path.join(ROOT, base, ref))
        if os.path.isfile(path):
            return path
    return None


def section_problem(path, section):
    """Why `section` names no heading of the Markdown file `path`, or None."""
    plain = [h.replace("`", "") for h in headings(path)]
    wanted = section.replace("`", "")
    if any(h.startswith(wanted) for h in plain):
        return None
    return f"no heading of {os.path.relpath(path, ROOT)} begins with \"{section}\""


def check_links(path, number, line, problems):
    """Markdown link targets of a .md file: the file exists, the anchor is one of its headings."""
    here = os.path.dirname(path)
    for match in MD_LINK.finditer(line):
        target = match.group(1)
        if re.match(r"[a-z]+:", target):
            continue  # a web address or mailto:
        file_part, _, anchor = target.partition("#")
        full = os.path.normpath(os.path.join(ROOT, here, file_part)) if file_part else os.path.join(ROOT, path)
        if not os.path.exists(full):
            problems.append(f"{path}:{number}: link '{target}' names no file of the repository")
        elif anchor and full.endswith(".md") and anchor not in {slug(h) for h in headings(full)}:
            problems.append(f"{path}:{number}: link '{target}': no heading of {os.path.relpath(full, ROOT)} has the anchor '#{anchor}'")


def check_file(path, problems, seen):
    here = os.path.dirname(path)
    fenced = False
    with open(os.path.join(ROOT, path), encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            if OUTSIDE.search(line):
                problems.append(f"{path}:{number}: points outside the repository: {line.strip()}")
            if path.endswith(".md"):
                if FENCE.match(line):
                    fenced = not fenced
                elif not fenced:
                    check_links(path, number, line, problems)
            for match in MD_REFERENCE.finditer(line):
                ref = match.group(0)
                before = line[:match.start()]
                if re.search(r"https?://\S*$", before):
                    continue  # part of a web address
                placeholder = re.match(r"[A-Z_]+/", ref)  # OUTDIR/..., DIR/...: a command's argument
                if ref.startswith("out/") or before.endswith(("/", "$", "}")) or ref.startswith("/") or placeholder:
                    continue  # an output a command writes, not a document of the tree
                target = resolve(ref, here)
                if not target:
                    if (path, number, ref) not in seen:  # once per line
                        problems.append(f"{path}:{number}: '{ref}' is no file of the repository")
                    seen.add((path, number, ref))
                    continue
                section = SECTION.match(line[match.end():])
                if section:
                    why = section_problem(target, section.group(1))
                    if why:
                        problems.append(f"{path}:{number}: {why}")


def main():
    files = subprocess.run(["git", "-C", ROOT, "ls-files", "--cached", "--others", "--exclude-standard"], check=True, capture_output=True, text=True).stdout.split()
    problems, seen = [], set()
    for path in files:
        if not TEXT.search(path) or not os.path.exists(os.path.join(ROOT, path)) or path == SELF:
            continue  # (this file names the patterns it looks for)
        check_file(path, problems, seen)
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} reference(s) point outside the repository or to nothing")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
