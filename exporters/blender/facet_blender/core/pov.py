"""facet's POV-Ray scenes: how many runs make the exact image, 16-bit PPM in, 16-bit PNG out.

facet shades meshes (and every non-native model) with function pigments, and a
function pigment holds one light. facet's scene therefore declares `Facet_Light`:
rendered once per light with `Declare=Facet_Light=i` (i = 0 .. passes−1: the lights,
then the emission and ambient term) the images add up to the exact image, which is how
`facet validate` renders it. How many runs that takes is facet's to say, and it says
it when it writes the scene (`facet generate --target pov --json`):

    {"target": "pov", "output": "scene.pov",
     "pov": {"passes": 3, "native": false, "reason": "meshes are shaded by function pigments ..."}}

`generate_scene` asks for that and returns it as a `Plan`, which povray.render takes.
passes 1 means one plain run is exact (POV-Ray's own finish, or one light). The .pov
also declares `#declare Facet_Passes = N;` for people who render it by hand; the
add-on does not read it back.

Each pass is written as a 16-bit binary PPM (trivial to read without any library),
the passes are added in integers and the sum, clipped at 1 as a PNG is, is written as
a linear 16-bit PNG (POV-Ray's own format for single runs).
"""

import array
import json
import os
import struct
import sys
import tempfile
import zlib
from dataclasses import dataclass

from . import UserError, cli


@dataclass(frozen=True)
class Plan:
    """How facet's POV-Ray scene renders exactly (facet's PovPlan, from `--json`)."""
    passes: int       # runs with Declare=Facet_Light=i, i < passes, that add up; 1: one plain run
    native: bool      # POV-Ray's own finish is the model
    reason: str = ""  # why not, when not


def plan_of(description):
    """The Plan in `facet generate --target pov --json`'s object (its "pov" member)."""
    p = description.get("pov") if isinstance(description, dict) else None
    passes = p.get("passes") if isinstance(p, dict) else None
    if (not isinstance(passes, int) or isinstance(passes, bool) or passes < 1
            or not isinstance(p.get("native"), bool)):
        shown = json.dumps(description)
        raise UserError("facet did not say how to render its POV-Ray scene ('facet generate --json' printed "
                        f"{shown[:200] + ('…' if len(shown) > 200 else '')}, with no \"pov\" object of passes "
                        "≥ 1 and native); is facet older than the add-on?")
    return Plan(passes, p["native"], str(p.get("reason", "")))


def require_scene_support(exe):
    """A UserError unless facet reads scenes with per-object materials and meshes."""
    has_materials, has_meshes = cli.scene_support(cli.scene_schema(exe))
    if not (has_materials and has_meshes):
        raise UserError("facet lacks scene materials/meshes: this facet executable cannot read a scene "
                        "with per-object materials and meshes yet (facet schema --scene); update facet")


def generate_scene(exe, scene, scene_name, pov_path, files=None):
    """Writes the POV-Ray scene of a facet scene (JSON data whose objects carry their own
    materials) to `pov_path`; returns its Plan. Nothing is written when facet refuses.
    `files` ({name: bytes}, the texture images the scene names relatively) are put
    beside the scene facet reads; facet writes the texels it uses beside the .pov."""
    with tempfile.TemporaryDirectory(prefix="facet-") as tmp:
        if files:
            cli.write_all_atomic(tmp, files)
        scene_path = os.path.join(tmp, "scene.json")
        cli.write_atomic(scene_path, cli.dump_json(scene))
        return cli.generate_to(exe, pov_path, ["--target", "pov", "--scene", scene_path],
                               {scene_path: f"scene '{scene_name}'"}, describe=plan_of)


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
