"""Coordinates and numbers shared by material and scene export.

facet's world is right-handed with +Y up (like OpenGL and glTF); Blender's is
right-handed with +Z up. Every point and direction maps as

    Blender (x, y, z)  ->  facet (x, z, -y)          facet (x, y, z) -> Blender (x, -z, y)

a proper rotation (a quarter turn about X), so lengths, angles, cross products and
triangle windings are unchanged.
"""

import math
import struct


def to_facet(v):
    """Blender (+Z up) -> facet (+Y up)."""
    return [float(v[0]), float(v[2]), -float(v[1])]


def to_blender(v):
    """facet (+Y up) -> Blender (+Z up)."""
    return [float(v[0]), -float(v[2]), float(v[1])]


def _f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def clean_float(x):
    """The shortest decimal that reads back as the same float32.

    Blender stores float properties in single precision: a value typed as 0.3 reads
    back as 0.30000001192092896. Written as 0.3 it means what the user typed and still
    round-trips exactly. Values that are not float32 (computed in double) are kept."""
    x = float(x)
    if not math.isfinite(x) or x == 0.0:
        return 0.0 if x == 0.0 else x
    try:
        if _f32(x) != x:
            return x
    except OverflowError:
        return x
    for digits in range(6, 10):
        y = float(f"{x:.{digits}g}")
        if _f32(y) == x:
            return y
    return x


def clean_vector(v):
    return [clean_float(x) for x in v]


def normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    if n == 0.0:
        raise ValueError("zero-length vector")
    return [x / n for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


# ----------------------------------------------------------------------------- 4x4 matrices (row-major nested lists)

def transform_point(m, p):
    return [m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3)]


def transform_direction(m, d):
    return [m[i][0] * d[0] + m[i][1] * d[1] + m[i][2] * d[2] for i in range(3)]


def det3(m):
    return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))


def normal_matrix(m):
    """The inverse transpose of the upper 3x3 of `m` (for transforming normals)."""
    d = det3(m)
    if d == 0.0:
        raise ValueError("singular matrix")
    # inverse = adjugate / det; its transpose is the cofactor matrix / det
    c = [[m[1][1] * m[2][2] - m[1][2] * m[2][1], m[1][2] * m[2][0] - m[1][0] * m[2][2], m[1][0] * m[2][1] - m[1][1] * m[2][0]],
         [m[0][2] * m[2][1] - m[0][1] * m[2][2], m[0][0] * m[2][2] - m[0][2] * m[2][0], m[0][1] * m[2][0] - m[0][0] * m[2][1]],
         [m[0][1] * m[1][2] - m[0][2] * m[1][1], m[0][2] * m[1][0] - m[0][0] * m[1][2], m[0][0] * m[1][1] - m[0][1] * m[1][0]]]
    return [[c[i][j] / d for j in range(3)] for i in range(3)]


def column_scale(m):
    """Lengths of the upper 3x3's columns (the object's scale along its local axes)."""
    return [math.sqrt(sum(m[i][j] ** 2 for i in range(3))) for j in range(3)]
