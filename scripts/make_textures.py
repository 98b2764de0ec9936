#!/usr/bin/env python3
"""Writes the textured room's images (scenes/textured-room.toml, docs/textures.md) into
scenes/textures/: a parquet floor's base colour (sRGB, 8-bit RGB), its roughness (8-bit grey,
linear) and its tangent-space normal map (8-bit RGB, linear), and a tiled back wall's base colour.
Deterministic (no randomness beyond a fixed hash), standard library only (zlib PNGs).

    python3 scripts/make_textures.py [OUT_DIR]
"""
import math
import os
import struct
import sys
import zlib


def png(path, width, height, channels, pixel):
    """pixel(x, y) -> tuple of `channels` values in [0, 1]; row 0 at the top."""
    colour = {1: 0, 3: 2, 4: 6}[channels]
    rows = bytearray()
    for y in range(height):
        rows.append(0)
        for x in range(width):
            for v in pixel(x, y):
                rows.append(max(0, min(255, int(round(v * 255)))))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(data)


def hash01(i, j):
    h = (i * 73856093) ^ (j * 19349663) ^ 0x5BD1E995
    h = (h * 2654435761) & 0xFFFFFFFF
    return (h >> 8) / float(1 << 24)


N = 128          # texels per side
PLANKS = 4       # planks across the image; each plank is split into boards along its length


def plank(x, y):
    """The board a texel is on, and where along its width (0..1) it lies."""
    p = x * PLANKS // N
    across = (x * PLANKS % N) / N
    shift = hash01(p, 0)
    along = (y / N + shift) * 2
    board = int(math.floor(along))
    return p, board, across, along - board


def floor_colour(x, y):
    p, board, across, along = plank(x, y)
    tone = 0.75 + 0.25 * hash01(p, board)
    grain = 0.08 * math.sin(40 * across + 6 * hash01(board, p) + 3 * math.sin(7 * along))
    edge = 0.55 if across < 0.03 or along < 0.015 else 1.0
    return tuple(edge * (tone + grain) * c for c in (0.62, 0.42, 0.25))


def floor_roughness(x, y):
    p, board, across, along = plank(x, y)
    return (0.35 + 0.3 * hash01(board, p + 7) + (0.3 if across < 0.03 or along < 0.015 else 0.0),)


def floor_normal(x, y):
    p, board, across, along = plank(x, y)
    # The board edges are bevelled: the normal tilts away from each edge over 4% of the board.
    nx = -0.5 if across < 0.04 else (0.5 if across > 0.96 else 0.0)
    ny = 0.5 if along < 0.02 else (-0.5 if along > 0.98 else 0.0)
    nz = 1.0
    n = math.sqrt(nx * nx + ny * ny + nz * nz)
    return (0.5 + 0.5 * nx / n, 0.5 + 0.5 * ny / n, 0.5 + 0.5 * nz / n)


def wall_colour(x, y):
    tx, ty = x % 32, y % 32
    grout = tx < 2 or ty < 2
    t = hash01(x // 32, y // 32)
    return (0.8, 0.8, 0.78) if grout else (0.15 + 0.1 * t, 0.45 + 0.2 * t, 0.5 + 0.1 * t)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes", "textures")
    os.makedirs(out, exist_ok=True)
    png(os.path.join(out, "parquet.png"), N, N, 3, floor_colour)
    png(os.path.join(out, "parquet_roughness.png"), N, N, 1, floor_roughness)
    png(os.path.join(out, "parquet_normal.png"), N, N, 3, floor_normal)
    png(os.path.join(out, "tiles.png"), N, N, 3, wall_colour)
    for name in ("parquet.png", "parquet_roughness.png", "parquet_normal.png", "tiles.png"):
        print("wrote", os.path.join(out, name), os.path.getsize(os.path.join(out, name)), "bytes")


if __name__ == "__main__":
    main()
