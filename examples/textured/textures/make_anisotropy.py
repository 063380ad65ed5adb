"""Writes examples/textured/textures/anisotropy.png: a 16×16 KHR_materials_anisotropy texture
(the extension's README, "Anisotropy": red and green the direction in the tangent frame, mapped
[0, 1] → [−1, 1], blue the strength, all linear), for textured_anisotropy.json. The direction
turns from +x (the tangent) through 100° across the image, slowly enough that bilinear
filtering never blends it towards zero; the strength runs from 0.35 to 1 down it. Standard
library only (the PNG writer is make_metal_roughness.py's):

    python3 examples/textured/textures/make_anisotropy.py
"""
import math

from make_metal_roughness import write_rgb_png

SIDE = 16


def texel(i, j):
    angle = math.radians(100.0) * (i + 0.5 * j) / (1.5 * (SIDE - 1))
    strength = 0.35 + 0.65 * j / (SIDE - 1)
    encode = lambda x: round((0.5 + 0.5 * x) * 255)
    return encode(math.cos(angle)), encode(math.sin(angle)), round(strength * 255)


def main():
    write_rgb_png("anisotropy.png", SIDE, texel)


if __name__ == "__main__":
    main()
