#!/usr/bin/env python3
"""Writes tiny valid environment images for tests and fuzz seeds: sky.hdr (Radiance RGBE,
16 x 8, flat scanlines) and sky.exr (OpenEXR 2.0, 16 x 8, half RGB, uncompressed scanlines),
both a sky gradient over a dark ground. Python 3 standard library only; the EXR layout follows
"The OpenEXR File Layout" (magic, version, header attributes, line offset table, scanlines).

Usage: make_environment_files.py   (writes next to this script)
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
WIDTH, HEIGHT = 16, 8


def radiance_at(x, y):
    up = 1.0 - (y + 0.5) / HEIGHT  # 1 at the zenith row, 0 at the nadir
    sky = max(up - 0.5, 0.0) * 2.0
    return (0.2 + 0.8 * sky, 0.25 + 0.9 * sky, 0.3 + 1.2 * sky + 0.1 * math.sin(x))


def rgbe(r, g, b):
    v = max(r, g, b)
    if v < 1e-32:
        return bytes([0, 0, 0, 0])
    mantissa, exponent = math.frexp(v)
    scale = mantissa * 256.0 / v
    return bytes([int(r * scale), int(g * scale), int(b * scale), exponent + 128])


def write_hdr(path):
    header = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {HEIGHT} +X {WIDTH}\n".encode()
    pixels = b"".join(rgbe(*radiance_at(x, y)) for y in range(HEIGHT) for x in range(WIDTH))
    with open(path, "wb") as f:
        f.write(header + pixels)


def attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def write_exr(path):
    channels = b"".join(c + b"\0" + struct.pack("<iB3xii", 1, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    header = b"\x76\x2f\x31\x01" + struct.pack("<I", 2)
    header += attribute("channels", "chlist", channels)
    header += attribute("compression", "compression", b"\0")
    header += attribute("dataWindow", "box2i", struct.pack("<4i", 0, 0, WIDTH - 1, HEIGHT - 1))
    header += attribute("displayWindow", "box2i", struct.pack("<4i", 0, 0, WIDTH - 1, HEIGHT - 1))
    header += attribute("lineOrder", "lineOrder", b"\0")
    header += attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
    header += attribute("screenWindowCenter", "v2f", struct.pack("<2f", 0.0, 0.0))
    header += attribute("screenWindowWidth", "float", struct.pack("<f", 1.0))
    header += b"\0"
    lines = []
    for y in range(HEIGHT):
        values = [radiance_at(x, y) for x in range(WIDTH)]
        data = b"".join(struct.pack("<" + "e" * WIDTH, *[v[c] for v in values]) for c in (2, 1, 0))  # B, G, R
        lines.append(struct.pack("<ii", y, len(data)) + data)
    offset = len(header) + 8 * HEIGHT
    table = b""
    for line in lines:
        table += struct.pack("<Q", offset)
        offset += len(line)
    with open(path, "wb") as f:
        f.write(header + table + b"".join(lines))


def main():
    write_hdr(os.path.join(HERE, "sky.hdr"))
    write_exr(os.path.join(HERE, "sky.exr"))


if __name__ == "__main__":
    main()
