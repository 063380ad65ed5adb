#!/usr/bin/env python3
"""Writes examples/textured/textures/normals.png: facet's own tangent-space normal map (no third-party
asset), deterministic, in the OpenGL/glTF convention (+x right, +y up the picture, +z out).

The surface is the height field h(u, v) = A sin(2π·2u) cos(2π·3v') over the unit square, v' = 1 − v
the coordinate up the picture (glTF's v runs down the rows). Its normal is
normalize(−∂h/∂u, −∂h/∂v', 1), sampled at each texel's centre and stored as round(255·(n + 1)/2).
The x and y slopes differ in frequency and phase, so a flipped green channel or an ignored map
shows. Usage: make_normal_map.py [OUT.png] [SIZE]"""
import math
import os
import struct
import sys
import zlib


def normals(size, amplitude=0.06):
    rows = []
    for j in range(size):
        row = bytearray()
        for i in range(size):
            u, v_up = (i + 0.5) / size, 1 - (j + 0.5) / size
            dhdu = amplitude * 2 * math.pi * 2 * math.cos(2 * math.pi * 2 * u) * math.cos(2 * math.pi * 3 * v_up)
            dhdv = -amplitude * 2 * math.pi * 3 * math.sin(2 * math.pi * 2 * u) * math.sin(2 * math.pi * 3 * v_up)
            n = (-dhdu, -dhdv, 1.0)
            length = math.sqrt(sum(c * c for c in n))
            row += bytes(int(round(255 * (c / length + 1) / 2)) for c in n)
        rows.append(bytes(row))
    return rows


def png(width, height, rows):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    out = argv[1] if len(argv) > 1 else os.path.join(here, "..", "examples", "textured", "textures", "normals.png")
    size = int(argv[2]) if len(argv) > 2 else 16
    data = png(size, size, normals(size))
    tmp = out + ".tmp"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
