#!/usr/bin/env python3
"""Keeps the README a page a newcomer reads in minutes: at most 30 KB, i.e. 30 x 1024 = 30,720 bytes.

    scripts/check_readme_size.py [FILE] [--limit BYTES]    exit 1, with the size, when FILE is larger

FILE defaults to the repository's README.md and BYTES to 30720. Depth belongs in docs/ (the
README's last section lists a page per topic), so a README that outgrows the limit should move a
section there rather than raise the limit.
"""
import argparse
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LIMIT_BYTES = 30 * 1024  # 30 KB in binary units, as the test's name says


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file", nargs="?", default=os.path.join(ROOT, "README.md"))
    parser.add_argument("--limit", type=int, default=LIMIT_BYTES, help="largest size allowed, in bytes")
    args = parser.parse_args()
    size = os.path.getsize(args.file)
    if size > args.limit:
        print(f"{args.file}: {size} bytes, over the limit of {args.limit} bytes ({args.limit / 1024:g} KB); "
              "move depth to docs/")
        return 1
    print(f"{args.file}: {size} bytes, within {args.limit} bytes ({args.limit / 1024:g} KB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
