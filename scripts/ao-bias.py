#!/usr/bin/env python3
"""Signed bias of AO images against a truth, overall and on open surfaces (issue 62's measure).

    python3 scripts/ao-bias.py OUT_DIR [TECHNIQUE ...]

OUT_DIR is an `obscura compare` output folder; every TECHNIQUE.png (default: every image there)
is read against reference.png. Per image: MAE, bias (mean of row - truth), and both again over
the open surfaces (truth >= 0.99), with their share of the pixels. compare's report gives MAE
without a sign, which hides whether a row is too dark or too bright. The PNGs hold AO rounded to
1/255 (round to nearest, so the bias of the rounding averages out); standard library only.
"""
import os
import struct
import sys
import zlib


def read_png_grey(path):
    """The first channel of an 8-bit grey or grey+alpha PNG, as floats in [0, 1], row-major."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat, width = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour in (0, 4) and interlace == 0, f"{path}: not 8-bit grey"
            bpp = 1 if colour == 0 else 2
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride = zlib.decompress(idat), width * bpp
    prev, out = bytearray(stride), []
    for y in range(height):
        line = raw[y * (stride + 1):(y + 1) * (stride + 1)]
        f, row = line[0], bytearray(line[1:])
        for i in range(stride):
            a = row[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                row[i] = (row[i] + a) & 255
            elif f == 2:
                row[i] = (row[i] + b) & 255
            elif f == 3:
                row[i] = (row[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out.extend(v / 255.0 for v in row[::bpp])
        prev = row
    return out


def main():
    folder, names = sys.argv[1], sys.argv[2:]
    if not names:
        names = sorted(f[:-4] for f in os.listdir(folder)
                       if f.endswith(".png") and not f.endswith(".diff.png") and f != "reference.png")
    truth = read_png_grey(os.path.join(folder, "reference.png"))
    print("technique\tmae\tbias\topen_mae\topen_bias\topen_share")
    for name in names:
        row = read_png_grey(os.path.join(folder, name + ".png"))
        d = [a - t for a, t in zip(row, truth)]
        o = [x for x, t in zip(d, truth) if t >= 0.99]
        mean = lambda xs: sum(xs) / max(len(xs), 1)
        print(f"{name}\t{mean([abs(x) for x in d]):.4f}\t{mean(d):+.4f}\t"
              f"{mean([abs(x) for x in o]):.4f}\t{mean(o):+.4f}\t{len(o) / len(d):.3f}")


if __name__ == "__main__":
    main()
