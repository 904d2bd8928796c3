#!/usr/bin/env python3
"""Compares the pixels of two PNG files (8-bit RGB or RGBA, non-interlaced), whatever their
encoder's compression: prints 'same' or how many channel values differ and by how much at most.
Exit status 0 when the pixels are equal, 1 when they differ, 2 on a file it cannot read.
Usage: scripts/png-pixels.py A.png B.png"""
import struct
import sys
import zlib


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG file")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace:
        raise ValueError(f"{path}: only 8-bit grey, RGB and RGBA PNGs without interlacing are compared")
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, channels, b"".join(rows)


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        a, b = read_png(sys.argv[1]), read_png(sys.argv[2])
    except (OSError, ValueError, zlib.error) as e:
        print(e, file=sys.stderr)
        return 2
    if a[:3] != b[:3]:
        print(f"different sizes: {a[:3]} against {b[:3]}")
        return 1
    differing = [abs(x - y) for x, y in zip(a[3], b[3]) if x != y]
    if not differing:
        print("same")
        return 0
    print(f"{len(differing)} of {len(a[3])} values differ, by at most {max(differing)}/255")
    return 1


if __name__ == "__main__":
    sys.exit(main())
