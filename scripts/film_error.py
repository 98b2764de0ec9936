#!/usr/bin/env python3
"""Error of a linear float image against a converged reference, for scripts/time_to_book_error.sh.

Images are little-endian float32 RGB Portable Float Maps, the raw films `clpt render -o NAME.pfm`
writes (NAME.pfm the per-pixel mean, NAME.var.pfm beside it the variance of that mean).

  film_error.py rmse IMAGE.pfm REFERENCE.pfm
      prints `rmse R raw_rmse R0 reference_noise V pixels N top_share S`, over all pixels and
      channels: raw_rmse = sqrt(mean((x - r)^2)); reference_noise = mean of the reference's
      variance of the mean (REFERENCE.var.pfm, which must exist); rmse = sqrt(max(0, raw_rmse^2 -
      reference_noise)). The reference is an independent estimate, so E[(x - r)^2] =
      E[(x - E r)^2] + Var(r): subtracting its mean variance leaves the image's error against the
      converged image itself. top_share: the fraction of the sum of (x - r)^2 that lies in the
      0.1% of pixels (at least one) where it is largest; a share far above 0.001 that grows with
      the samples is a bias in few pixels (an edge, a pixel filter), not noise.
  film_error.py ppm-match IMAGE.pfm BOOK.ppm
      checks that BOOK.ppm (the book renderer's clamped, gamma 1/2.2, 8-bit ASCII PPM, top row
      first) is IMAGE tone mapped the book's way; prints `values V differ D max_step M` and exits 1
      when more than 0.1% of the values differ or any by more than 1 (a float32 copy of the book's
      double image may round a value at a step the other way, never further).

Bad input (missing file, not a float RGB PFM, sizes that differ) exits 2 with a message naming
the file. Pure python3 (no numpy: Debian 12's minimal python3 is what scripts/common.sh installs).
"""
import array
import math
import sys


class BadInput(Exception):
    pass


def read_pfm(path):
    """Returns (width, height, floats): RGB interleaved, rows in the file's order (bottom first)."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise BadInput(f"{path}: cannot read: {e.strerror}")
    fields, pos = [], 0
    while len(fields) < 4:  # "PF", width, height, scale, separated by whitespace
        while pos < len(data) and data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while end < len(data) and not data[end:end + 1].isspace():
            end += 1
        if end == pos:
            raise BadInput(f"{path}: not a PFM (header ends early)")
        fields.append(data[pos:end])
        pos = end
    pos += 1  # the single whitespace byte after the scale
    if fields[0] != b"PF":
        raise BadInput(f"{path}: not a 3-channel float PFM (magic {fields[0][:8]!r}, expected PF)")
    try:
        width, height, scale = int(fields[1]), int(fields[2]), float(fields[3])
    except ValueError:
        raise BadInput(f"{path}: not a PFM (bad width, height or scale)")
    if width <= 0 or height <= 0:
        raise BadInput(f"{path}: image size {width}x{height}")
    if scale >= 0:
        raise BadInput(f"{path}: big-endian PFM (scale {scale}); only little-endian is read")
    values = array.array("f")
    count = 3 * width * height
    if len(data) - pos != 4 * count:
        raise BadInput(f"{path}: {len(data) - pos} bytes of pixels, expected {4 * count} for {width}x{height} RGB")
    values.frombytes(data[pos:])
    if sys.byteorder != "little":
        values.byteswap()
    return width, height, values


def variance_path(path):
    if not path.endswith(".pfm"):
        raise BadInput(f"{path}: the reference must be a .pfm with its .var.pfm beside it")
    return path[:-len(".pfm")] + ".var.pfm"


def same_size(a, a_path, b, b_path):
    if a[:2] != b[:2]:
        raise BadInput(f"{a_path} is {a[0]}x{a[1]} but {b_path} is {b[0]}x{b[1]}")


def rmse(image_path, reference_path):
    image = read_pfm(image_path)
    reference = read_pfm(reference_path)
    reference_var = read_pfm(variance_path(reference_path))
    same_size(image, image_path, reference, reference_path)
    same_size(reference_var, variance_path(reference_path), reference, reference_path)
    n = len(image[2])
    squares = [(x - r) ** 2 for x, r in zip(image[2], reference[2])]
    total = math.fsum(squares)
    mse = total / n
    noise = math.fsum(reference_var[2]) / n
    pixels = image[0] * image[1]
    per_pixel = sorted((squares[3 * p] + squares[3 * p + 1] + squares[3 * p + 2] for p in range(pixels)),
                       reverse=True)
    top = math.fsum(per_pixel[:max(1, pixels // 1000)])
    print(f"rmse {math.sqrt(max(0.0, mse - noise)):.6g} raw_rmse {math.sqrt(mse):.6g} "
          f"reference_noise {noise:.6g} pixels {pixels} top_share {top / total if total > 0 else 0:.4g}")
    return 0


def to_ldr(x):
    """gemspt's ppm.h: clamp to [0, 1], gamma 1/2.2, round to 0..255."""
    return int(min(1.0, max(0.0, x)) ** (1 / 2.2) * 255 + 0.5)


def ppm_match(image_path, ppm_path):
    width, height, values = read_pfm(image_path)
    try:
        with open(ppm_path, "rb") as f:
            tokens = f.read().split()
    except OSError as e:
        raise BadInput(f"{ppm_path}: cannot read: {e.strerror}")
    if len(tokens) < 4 or tokens[0] != b"P3":
        raise BadInput(f"{ppm_path}: not an ASCII (P3) PPM")
    if (int(tokens[1]), int(tokens[2])) != (width, height):
        raise BadInput(f"{ppm_path} is {int(tokens[1])}x{int(tokens[2])} but {image_path} is {width}x{height}")
    ppm = [int(t) for t in tokens[4:]]
    if len(ppm) != 3 * width * height:
        raise BadInput(f"{ppm_path}: {len(ppm)} values, expected {3 * width * height}")
    differ = max_step = 0
    row_len = 3 * width
    for row in range(height):  # the PPM's row `row` from the top is the PFM's row height-1-row
        pfm_row = (height - 1 - row) * row_len
        for i in range(row_len):
            step = abs(to_ldr(values[pfm_row + i]) - ppm[row * row_len + i])
            if step:
                differ += 1
                max_step = max(max_step, step)
    print(f"values {len(ppm)} differ {differ} max_step {max_step}")
    return 0 if differ <= len(ppm) // 1000 and max_step <= 1 else 1


def main(argv):
    commands = {"rmse": rmse, "ppm-match": ppm_match}
    if len(argv) != 4 or argv[1] not in commands:
        sys.stderr.write("usage:\n" + __doc__.split("\n\n")[2] + "\n")
        return 2
    try:
        return commands[argv[1]](argv[2], argv[3])
    except BadInput as e:
        sys.stderr.write(f"film_error.py: {e}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
