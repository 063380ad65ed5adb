"""Writes examples/textured/textures/leaf.png: a 16×16 RGBA image for cut-out materials (glTF's
alphaMode MASK, facet's "alpha_cutoff"), through numpy and Blender's own image writer:

    .venv/bin/python examples/textured/textures/make_leaf.py

The alpha falls off from the middle as a leaf-shaped distance, so a bilinear lookup crosses
a cutoff of 0.5 along a smooth curve through many texels, and the colour varies across it
(green to yellow), so a renderer that shows the wrong texel shows it.
"""
import os
import sys

import bpy
import numpy as np

SIZE = 16


def leaf():
    """RGBA in [0, 1], rows from the top of the picture."""
    v, u = (np.mgrid[0:SIZE, 0:SIZE] + 0.5) / SIZE
    x, y = 2 * u - 1, 2 * v - 1
    d = np.sqrt((x / 0.95) ** 2 + (y / (0.55 + 0.35 * (1 - np.abs(x)))) ** 2)  # a pointed ellipse
    alpha = np.clip(1.6 - 1.2 * d, 0.0, 1.0)
    rgba = np.stack([0.25 + 0.6 * u, 0.55 + 0.35 * v, 0.15 + 0.1 * u * v, alpha], axis=-1)
    return np.round(rgba * 255) / 255  # exactly the 8-bit values the file holds


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "leaf.png")
    img = bpy.data.images.new("leaf", SIZE, SIZE, alpha=True)
    img.colorspace_settings.name = "Non-Color"      # the numbers as they are: no view transform
    img.alpha_mode = "STRAIGHT"
    img.pixels.foreach_set(leaf()[::-1].ravel().astype(np.float32))  # Blender's rows start at the bottom
    img.filepath_raw = out
    img.file_format = "PNG"
    img.save()
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
