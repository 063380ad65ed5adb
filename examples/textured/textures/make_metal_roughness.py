"""Writes examples/textured/textures/metal_roughness.png: a 16×16 glTF metallic–roughness map
(glTF 2.0 §3.9.2: G roughness, B metallic, linear; R 1, the occlusion channel some files share
it with), for textured_gltf_pbr.json. Metallic is 1 in a checker of 4×4-texel squares and 0
between them; roughness runs from 0.35 to 0.9 across, glossy enough to show a highlight and
rough enough that float32 targets meet the reference within validation's 2e-3
(examples/gltf_pbr/README.md). Standard library only:

    python3 examples/textured/textures/make_metal_roughness.py
"""
import os
import struct
import zlib

SIDE = 16


def texel(i, j):
    roughness = 0.35 + 0.55 * i / (SIDE - 1)
    metallic = 1.0 if (i // 4 + j // 4) % 2 == 0 else 0.0
    return 255, round(roughness * 255), round(metallic * 255)


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def write_rgb_png(name, side, texel):
    """Writes `name` beside this script: an 8-bit RGB PNG of side × side texels, texel(i, j) the
    (r, g, b) bytes of column i, row j (row 0 at the top). make_anisotropy.py writes with it too."""
    rows = b"".join(b"\0" + bytes(c for i in range(side) for c in texel(i, j)) for j in range(side))
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), name)
    with open(path, "wb") as f:
        f.write(png)
    print(f"wrote {path}")


def main():
    write_rgb_png("metal_roughness.png", SIDE, texel)


if __name__ == "__main__":
    main()
