"""Writes examples/textured/textures/anisotropy.png: a 16×16 KHR_materials_anisotropy texture
(the extension's README, "Anisotropy": red and green the direction in the tangent frame, mapped
[0, 1] → [−1, 1], blue the strength, all linear), for textured_anisotropy.json. The direction
turns from +x (the tangent) through 100° across the image, slowly enough that bilinear
filtering never blends it towards zero; the strength runs from 0.35 to 1 down it. Standard
library only:

    python3 examples/textured/textures/make_anisotropy.py
"""
import math
import os
import struct
import zlib

SIDE = 16


def texel(i, j):
    angle = math.radians(100.0) * (i + 0.5 * j) / (1.5 * (SIDE - 1))
    strength = 0.35 + 0.65 * j / (SIDE - 1)
    encode = lambda x: round((0.5 + 0.5 * x) * 255)
    return encode(math.cos(angle)), encode(math.sin(angle)), round(strength * 255)


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def main():
    rows = b"".join(b"\0" + bytes(c for i in range(SIDE) for c in texel(i, j)) for j in range(SIDE))
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", SIDE, SIDE, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "anisotropy.png")
    with open(path, "wb") as f:
        f.write(png)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
