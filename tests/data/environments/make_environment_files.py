#!/usr/bin/env python3
"""Writes tiny valid environment images for tests and fuzz seeds: sky.hdr (Radiance RGBE,
16 x 8, flat scanlines), sky_rle.hdr (the same, run-length encoded scanlines), sky_xyze.hdr (CIE
XYZ, FORMAT=32-bit_rle_xyze, with an EXPOSURE line), sky.exr (OpenEXR 2.0, 16 x 8, half RGB,
uncompressed scanlines) and sky_tiled.exr (the same in 8 x 8 tiles), all a sky gradient over a
dark ground. Python 3 standard library only; the EXR layout follows "The OpenEXR File Layout"
(magic, version, header attributes, line or tile offset table, scanlines or tiles), the Radiance
one Ward's "Real Pixels" (Graphics Gems II) and Radiance's run-length scanline encoding.

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


def write_rle_hdr(path):
    # Each scanline: 2, 2, width (big-endian), then per channel runs (count + 128, value) of
    # repeated bytes and literal runs (count, bytes), at most 127 / 128 long.
    header = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + f"-Y {HEIGHT} +X {WIDTH}\n".encode()
    out = bytearray(header)
    for y in range(HEIGHT):
        texels = [rgbe(*radiance_at(x, y)) for x in range(WIDTH)]
        out += bytes([2, 2, WIDTH >> 8, WIDTH & 255])
        for c in range(4):
            values = [t[c] for t in texels]
            x = 0
            while x < WIDTH:
                run = 1
                while x + run < WIDTH and values[x + run] == values[x] and run < 127:
                    run += 1
                if run >= 3:
                    out += bytes([128 + run, values[x]])
                    x += run
                else:
                    literal = min(WIDTH - x, 2)
                    out += bytes([literal]) + bytes(values[x:x + literal])
                    x += literal
    with open(path, "wb") as f:
        f.write(bytes(out))


def write_xyze_hdr(path):
    # Radiance's RGB primaries and equal-energy white (its color.h), and EXPOSURE=2: stored values
    # are twice the radiance.
    to_xyz = ((0.5141446, 0.3238845, 0.1619709), (0.2651058, 0.6701058, 0.0647884),
              (0.0241005, 0.1228527, 0.8530467))
    header = b"#?RADIANCE\nFORMAT=32-bit_rle_xyze\nEXPOSURE=2\n\n" + f"-Y {HEIGHT} +X {WIDTH}\n".encode()
    pixels = bytearray()
    for y in range(HEIGHT):
        for x in range(WIDTH):
            rgb = radiance_at(x, y)
            pixels += rgbe(*[2.0 * sum(m[k] * rgb[k] for k in range(3)) for m in to_xyz])
    with open(path, "wb") as f:
        f.write(header + bytes(pixels))


def attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def exr_header(version, extra=b""):
    channels = b"".join(c + b"\0" + struct.pack("<iB3xii", 1, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    header = b"\x76\x2f\x31\x01" + struct.pack("<I", version)
    header += attribute("channels", "chlist", channels)
    header += attribute("compression", "compression", b"\0")
    header += attribute("dataWindow", "box2i", struct.pack("<4i", 0, 0, WIDTH - 1, HEIGHT - 1))
    header += attribute("displayWindow", "box2i", struct.pack("<4i", 0, 0, WIDTH - 1, HEIGHT - 1))
    header += attribute("lineOrder", "lineOrder", b"\0")
    header += attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
    header += attribute("screenWindowCenter", "v2f", struct.pack("<2f", 0.0, 0.0))
    header += attribute("screenWindowWidth", "float", struct.pack("<f", 1.0))
    return header + extra + b"\0"


def write_chunks(path, header, chunks):
    """The header, the offset table (one 64-bit offset per chunk), the chunks."""
    offset = len(header) + 8 * len(chunks)
    table = b""
    for chunk in chunks:
        table += struct.pack("<Q", offset)
        offset += len(chunk)
    with open(path, "wb") as f:
        f.write(header + table + b"".join(chunks))


def write_exr(path):
    header = exr_header(2)
    lines = []
    for y in range(HEIGHT):
        values = [radiance_at(x, y) for x in range(WIDTH)]
        data = b"".join(struct.pack("<" + "e" * WIDTH, *[v[c] for v in values]) for c in (2, 1, 0))  # B, G, R
        lines.append(struct.pack("<ii", y, len(data)) + data)
    write_chunks(path, header, lines)


TILE = 8


def write_tiled_exr(path):
    # Single-part tiled (version flag 0x200), one level, rounding down.
    header = exr_header(2 | 0x200, attribute("tiles", "tiledesc", struct.pack("<IIB", TILE, TILE, 0)))
    tiles = []
    for ty in range(HEIGHT // TILE):
        for tx in range(WIDTH // TILE):
            data = b""
            for y in range(ty * TILE, (ty + 1) * TILE):
                values = [radiance_at(x, y) for x in range(tx * TILE, (tx + 1) * TILE)]
                data += b"".join(struct.pack("<" + "e" * TILE, *[v[c] for v in values]) for c in (2, 1, 0))
            tiles.append(struct.pack("<5i", tx, ty, 0, 0, len(data)) + data)
    write_chunks(path, header, tiles)


def main():
    write_hdr(os.path.join(HERE, "sky.hdr"))
    write_rle_hdr(os.path.join(HERE, "sky_rle.hdr"))
    write_xyze_hdr(os.path.join(HERE, "sky_xyze.hdr"))
    write_exr(os.path.join(HERE, "sky.exr"))
    write_tiled_exr(os.path.join(HERE, "sky_tiled.exr"))


if __name__ == "__main__":
    main()
