#!/usr/bin/env python3
"""make_environment_sky.py: writes the procedural sky of scenes/environment.toml as a Radiance
.hdr (RGBE) equirectangular image, in pure Python (no dependency).

The mapping is clpt's (docs/environment.md): row 0 is the zenith, v = acos(y) / pi; column u looks
along (sin(theta) cos(phi), cos(theta), sin(theta) sin(phi)) with phi = 2 pi (u - 0.5). The sky
is a gradient from a deep blue zenith to a pale horizon, a darker ground below the horizon, and a
sun of a few texels at 1e5 times the zenith sky's radiance (the case the issue's sampler must
handle without fireflies), at elevation 35 degrees, azimuth towards -Z turned 30 degrees to +X.

Usage: python3 scripts/make_environment_sky.py [OUT.hdr] [--width W] [--sun-ratio R]
"""
import argparse
import math
import struct


def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32:
        return bytes((0, 0, 0, 0))
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes((min(255, int(r * scale)), min(255, int(g * scale)), min(255, int(b * scale)), exponent + 128))


def direction(u, v):
    phi, theta = 2 * math.pi * (u - 0.5), math.pi * v
    return (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="scenes/environment-sky.hdr")
    parser.add_argument("--width", type=int, default=128)
    parser.add_argument("--sun-ratio", type=float, default=1e5)
    args = parser.parse_args()
    width, height = args.width, args.width // 2
    zenith = (0.10, 0.20, 0.50)
    horizon = (0.45, 0.55, 0.70)
    ground = (0.12, 0.11, 0.10)
    elevation, azimuth = math.radians(35), math.radians(30)
    sun = (math.cos(elevation) * math.sin(azimuth), math.sin(elevation), -math.cos(elevation) * math.cos(azimuth))
    sun_cos = math.cos(math.radians(2.2))  # a disc a little over 2 texels across at width 128
    sun_radiance = args.sun_ratio * max(zenith)
    rows = []
    for row in range(height):
        line = bytearray()
        for column in range(width):
            d = direction((column + 0.5) / width, (row + 0.5) / height)
            if d[1] >= 0:
                t = (1 - d[1]) ** 3
                c = tuple(z + (h - z) * t for z, h in zip(zenith, horizon))
            else:
                c = ground
            if sum(a * b for a, b in zip(d, sun)) > sun_cos:
                c = (sun_radiance, sun_radiance * 0.95, sun_radiance * 0.85)
            line += rgbe(*c)
        rows.append(bytes(line))
    with open(args.out, "wb") as f:
        f.write(b"#?RADIANCE\n# clpt scripts/make_environment_sky.py\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(b"-Y %d +X %d\n" % (height, width))
        for line in rows:
            f.write(line)
    print("wrote %s: %d x %d, sun %g x the zenith sky" % (args.out, width, height, args.sun_ratio))


if __name__ == "__main__":
    main()
