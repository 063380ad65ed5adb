"""Rendering facet's POV-Ray scenes exactly: passes, 16-bit PPM in, 16-bit PNG out.

facet shades meshes (and every non-native model) with function pigments, and a
function pigment holds one light. facet's scene therefore declares `Facet_Light`:
rendered once per light with `Declare=Facet_Light=i` (i = 0 .. passes−1: the lights,
then the emission and ambient term) the images add up to the exact image, which is how
`facet validate` renders it. Every generated scene declares how many runs that takes:

    #declare Facet_Passes = 3;  // renders with Facet_Light = 0 … 2 sum to the exact image

1 means one plain run is exact (POV-Ray's own finish, or one light).
Each pass is written as a 16-bit binary PPM (trivial to read without any library),
the passes are added in integers and the sum, clipped at 1 as a PNG is, is written as
a linear 16-bit PNG (POV-Ray's own format for single runs).
"""

import array
import re
import struct
import sys
import zlib

from . import UserError

PASSES_LINE = re.compile(r"^#declare Facet_Passes = (\d+);", re.MULTILINE)
HEADER_BYTES = 65536


def passes(header_text):
    """How many runs (Declare=Facet_Light=i) make the exact image; 1 means one plain run."""
    match = PASSES_LINE.search(header_text)
    if not match:
        raise UserError("the POV-Ray scene declares no Facet_Passes: was it written by this version of facet?")
    return int(match.group(1))


def read_header(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read(HEADER_BYTES)


def read_ppm16(path):
    """(width, height, samples): a binary PPM (P6) with maxval 65535, samples as an
    array('H') of RGB in reading order (top row first), native byte order."""
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:
        while pos < len(data) and data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":                       # a comment line
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while end < len(data) and not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    pos += 1                                                  # the one whitespace byte
    magic, width, height, maxval = fields[0], int(fields[1]), int(fields[2]), int(fields[3])
    if magic != b"P6" or maxval != 65535:
        raise UserError(f"{path}: not a 16-bit binary PPM (got {magic!r}, maxval {maxval})")
    samples = array.array("H")
    samples.frombytes(data[pos:pos + 6 * width * height])
    if len(samples) != 3 * width * height:
        raise UserError(f"{path}: truncated PPM")
    if sys.byteorder == "little":
        samples.byteswap()                                   # PPM is big-endian
    return width, height, samples


def add_clipped(images):
    """The sum of same-sized sample arrays, clipped at 65535 (1.0)."""
    total = array.array("H", images[0])
    for image in images[1:]:
        total = array.array("H", [min(a + b, 65535) for a, b in zip(total, image)])
    return total


def png16(width, height, samples):
    """A 16-bit RGB PNG (bytes) of RGB samples (array('H'), top row first)."""
    big = array.array("H", samples)
    if sys.byteorder == "little":
        big.byteswap()
    raw = big.tobytes()
    stride = 6 * width
    rows = b"".join(b"\x00" + raw[y * stride:(y + 1) * stride] for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n"
            + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 16, 2, 0, 0, 0))
            + chunk(b"gAMA", struct.pack(">I", 100000))          # linear, as POV-Ray writes File_Gamma=1.0
            + chunk(b"IDAT", zlib.compress(rows, 6))
            + chunk(b"IEND", b""))
