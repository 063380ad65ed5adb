"""A small glTF 2.0 writer and the shapes and images the test corpus is made of (numpy only).

Used by gltf_corpus.py. Everything is computed, nothing is read: the same call writes the
same bytes. Buffers and images go into the file as data URIs (.gltf) or into the binary
chunk (.glb), so each corpus file is one self-contained file.
"""
import base64
import json
import math
import struct
import zlib

import numpy as np

FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
NEAREST, LINEAR, LINEAR_MIPMAP_LINEAR = 9728, 9729, 9987
REPEAT, CLAMP, MIRROR = 10497, 33071, 33648
TYPES = {1: "SCALAR", 2: "VEC2", 3: "VEC3", 4: "VEC4", 16: "MAT4"}
NUMPY = {FLOAT: np.float32, UBYTE: np.uint8, USHORT: np.uint16, UINT: np.uint32}

# Blender's glTF exporter writes a light of P watts as P/(4π)·683 cd (point, spot) and a sun of
# S W/m² as S·683 lx (io_scene_gltf2/blender/exp/lights.py, lighting mode "Standard").
LUMENS_PER_WATT = 683.0


def point_candela(watts):
    return watts / (4.0 * math.pi) * LUMENS_PER_WATT


def sun_lux(watts_per_m2):
    return watts_per_m2 * LUMENS_PER_WATT


# ----------------------------------------------------------------------------- rotations

def quat_axis_angle(axis, degrees):
    """glTF's [x, y, z, w] of a rotation by `degrees` about `axis`."""
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    h = math.radians(degrees) / 2
    return [float(a[0] * math.sin(h)), float(a[1] * math.sin(h)), float(a[2] * math.sin(h)), float(math.cos(h))]


def quat_mul(q, r):
    x1, y1, z1, w1 = q
    x2, y2, z2, w2 = r
    return [w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2]


def quat_matrix(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def matrix_quat(m):
    """The unit quaternion [x, y, z, w] of a rotation matrix (Shepperd's method)."""
    t = m[0, 0] + m[1, 1] + m[2, 2]
    if t > 0:
        s = math.sqrt(t + 1) * 2
        q = [(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, s / 4]
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = math.sqrt(1 + m[0, 0] - m[1, 1] - m[2, 2]) * 2
        q = [s / 4, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s]
    elif m[1, 1] > m[2, 2]:
        s = math.sqrt(1 + m[1, 1] - m[0, 0] - m[2, 2]) * 2
        q = [(m[0, 1] + m[1, 0]) / s, s / 4, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s]
    else:
        s = math.sqrt(1 + m[2, 2] - m[0, 0] - m[1, 1]) * 2
        q = [(m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, s / 4, (m[1, 0] - m[0, 1]) / s]
    n = math.sqrt(sum(c * c for c in q))
    return [float(c / n) for c in q]


def look_at(eye, target, up=(0.0, 1.0, 0.0)):
    """The rotation [x, y, z, w] that turns a glTF camera or light (looking down its −Z, +Y up)
    at `eye` towards `target`."""
    f = np.asarray(target, float) - np.asarray(eye, float)
    f /= np.linalg.norm(f)
    r = np.cross(f, up)
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    return matrix_quat(np.column_stack([r, u, -f]))


def trs_matrix(translation=(0, 0, 0), rotation=(0, 0, 0, 1), scale=(1, 1, 1)):
    """The 4×4 matrix of glTF's T·R·S."""
    m = np.eye(4)
    m[:3, :3] = quat_matrix(rotation) @ np.diag(scale)
    m[:3, 3] = translation
    return m


def column_major(m):
    return [float(x) for x in np.asarray(m, float).T.ravel()]


# ----------------------------------------------------------------------------- shapes

class Shape:
    """Triangles with per-vertex positions, normals, uvs (glTF's: v down the picture)."""

    def __init__(self, positions, normals, uvs, indices):
        self.positions = np.asarray(positions, np.float32)
        self.normals = None if normals is None else np.asarray(normals, np.float32)
        self.uvs = None if uvs is None else np.asarray(uvs, np.float32)
        self.indices = np.asarray(indices, np.uint16 if len(positions) < 65536 else np.uint32).ravel()

    @property
    def triangles(self):
        return len(self.indices) // 3


def box(sx=1.0, sy=1.0, sz=1.0):
    """An axis-aligned box of half sizes (sx, sy, sz): 24 vertices, flat faces, a 0–1 uv square
    per face, counter-clockwise seen from outside."""
    pos, nor, uv, idx = [], [], [], []
    for axis in range(3):
        for sign in (1.0, -1.0):
            n = np.zeros(3)
            n[axis] = sign
            a, b = [(axis + 1) % 3, (axis + 2) % 3]
            u, v = np.zeros(3), np.zeros(3)
            u[a], v[b] = 1.0, 1.0
            if sign < 0:
                u, v = v, u
            base = len(pos)
            for cu, cv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = n + cu * u + cv * v
                pos.append(p * (sx, sy, sz))
                nor.append(n)
                uv.append(((cu + 1) / 2, (1 - cv) / 2))
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return Shape(pos, nor, uv, idx)


def uv_sphere(radius=1.0, segments=16, rings=8, squash=None):
    """A smooth UV sphere (u = φ/2π from +X towards −Z, v = θ/π from the +Y pole); `squash`, a
    function of the unit direction, scales the radius (an asymmetric egg), normals from the
    surface's own derivatives."""
    pos, nor, uv = [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            d = np.array([math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)])
            pos.append(radius * d * (squash(d) if squash else 1.0))
            uv.append((s / segments, r / rings))
    pos = np.array(pos)
    idx = []
    for r in range(rings):
        for s in range(segments):
            a, b = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            if r > 0:
                idx += [a, b, a + 1]
            if r < rings - 1:
                idx += [a + 1, b, b + 1]
    nor = vertex_normals(pos, idx) if squash else pos / radius
    return Shape(pos, nor, uv, idx)


def torus(major=1.0, minor=0.35, segments=20, sides=10):
    pos, nor, uv, idx = [], [], [], []
    for i in range(segments + 1):
        a = 2 * math.pi * i / segments
        c = np.array([math.cos(a), 0.0, -math.sin(a)])
        for j in range(sides + 1):
            b = 2 * math.pi * j / sides
            n = math.cos(b) * c + np.array([0.0, math.sin(b), 0.0])
            pos.append(major * c + minor * n)
            nor.append(n)
            uv.append((i / segments, j / sides))
    for i in range(segments):
        for j in range(sides):
            a, b = i * (sides + 1) + j, (i + 1) * (sides + 1) + j
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return Shape(pos, nor, uv, idx)


def plane(size=4.0, uv_repeat=1.0):
    """A square in y = 0 facing +Y, corners ±size/2."""
    h = size / 2
    pos = [(-h, 0, h), (h, 0, h), (h, 0, -h), (-h, 0, -h)]
    uv = [(0, uv_repeat), (uv_repeat, uv_repeat), (uv_repeat, 0), (0, 0)]
    return Shape(pos, [(0, 1, 0)] * 4, uv, [0, 1, 2, 0, 2, 3])


def cylinder(radius=0.3, height=2.0, segments=12, rings=8):
    """An open smooth tube along +Y from y = 0 to `height` (a skinned limb)."""
    pos, nor, uv, idx = [], [], [], []
    for r in range(rings + 1):
        y = height * r / rings
        for s in range(segments + 1):
            a = 2 * math.pi * s / segments
            n = np.array([math.cos(a), 0.0, -math.sin(a)])
            pos.append(radius * n + (0, y, 0))
            nor.append(n)
            uv.append((s / segments, 1 - r / rings))
    for r in range(rings):
        for s in range(segments):
            a, b = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            idx += [a, a + 1, b, a + 1, b + 1, b]
    return Shape(pos, nor, uv, idx)


def vertex_normals(pos, idx):
    """Area-weighted normals of triangles `idx` over `pos`, summed over every vertex at the same
    place (a seam's or a pole's copies get one normal: the surface stays smooth across them)."""
    pos = np.asarray(pos, float)
    tri = np.asarray(idx).reshape(-1, 3)
    face = np.cross(pos[tri[:, 1]] - pos[tri[:, 0]], pos[tri[:, 2]] - pos[tri[:, 0]])
    _, place = np.unique(np.round(pos, 6), axis=0, return_inverse=True)
    place = place.ravel()
    n = np.zeros((place.max() + 1, 3))
    for k in range(3):
        np.add.at(n, place[tri[:, k]], face)
    n = n[place]
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.where(length > 0, length, 1)


# ----------------------------------------------------------------------------- images

def png(pixels):
    """An 8-bit RGBA PNG (bytes) of `pixels`, rows from the top, values 0–255."""
    p = np.asarray(pixels, np.uint8)
    h, w, _ = p.shape
    raw = b"".join(b"\x00" + p[j].tobytes() for j in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def grid(n):
    j, i = np.mgrid[0:n, 0:n]
    return i, j


def rgba(r, g, b, a=None):
    """Channels in [0, 1] (arrays or numbers of one shape) -> 0–255 RGBA texels."""
    r, g, b, a = np.broadcast_arrays(*(np.asarray(x, float) for x in (r, g, b, 1.0 if a is None else a)))
    out = np.stack([r, g, b, a], axis=-1)
    return np.clip(np.round(out * 255), 0, 255).astype(np.uint8)


def checker(n=16, cells=4, a=(0.9, 0.75, 0.2), b=(0.15, 0.35, 0.8)):
    i, j = grid(n)
    on = ((i * cells // n) + (j * cells // n)) % 2 == 0
    return rgba(*(np.where(on, a[k], b[k]) for k in range(3)))


def gradient(n=16):
    """Red across, green down, blue in a diagonal band: every texel differs, so a wrong
    coordinate set or transform shows."""
    i, j = grid(n)
    return rgba(0.1 + 0.8 * i / (n - 1), 0.1 + 0.8 * j / (n - 1), 0.2 + 0.6 * (((i + j) // 3) % 2))


def stripes(n=16, period=4):
    i, j = grid(n)
    on = (i // (period // 2)) % 2 == 0
    return rgba(np.where(on, 0.95, 0.3), np.where(on, 0.4, 0.85), 0.25 + 0.5 * j / (n - 1))


def normal_bumps(n=32, amplitude=0.35):
    """A tangent-space normal map of gentle bumps, encoded (n + 1)/2."""
    i, j = grid(n)
    nx = amplitude * np.sin(2 * np.pi * 2 * (i + 0.5) / n)
    ny = amplitude * np.cos(2 * np.pi * 3 * (j + 0.5) / n)
    length = np.sqrt(nx * nx + ny * ny + 1)
    return rgba((nx / length + 1) / 2, (ny / length + 1) / 2, (1 / length + 1) / 2)


# ----------------------------------------------------------------------------- the document

class Document:
    """One glTF asset being written: add_* return indices; save() writes it."""

    def __init__(self, generator="facet tests/tools/gltf_corpus.py"):
        self.d = {"asset": {"version": "2.0", "generator": generator}, "scene": 0, "scenes": [{"nodes": []}]}
        self.bin = bytearray()

    def _list(self, key, item):
        self.d.setdefault(key, []).append(item)
        return len(self.d[key]) - 1

    def view(self, data, target=None, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target:
            view["target"] = target
        if stride:
            view["byteStride"] = stride
        self.bin += data
        return self._list("bufferViews", view)

    def accessor(self, array, component=FLOAT, normalized=False, target=ARRAY_BUFFER, bounds=False, sparse=None):
        """An accessor of `array` (count × n, or count scalars) in its own buffer view."""
        a = np.asarray(array)
        width = 1 if a.ndim == 1 else a.shape[1]
        data = np.ascontiguousarray(a.astype(NUMPY[component]))
        acc = {"componentType": component, "count": int(a.shape[0]), "type": TYPES[width]}
        if data.size:
            acc["bufferView"] = self.view(data.tobytes(), target)
        if normalized:
            acc["normalized"] = True
        if bounds:
            flat = a.reshape(len(a), -1).astype(float)
            acc["min"] = [float(x) for x in flat.min(axis=0)]
            acc["max"] = [float(x) for x in flat.max(axis=0)]
        if sparse is not None:
            acc["sparse"] = sparse
        return self._list("accessors", acc)

    def primitive(self, shape, material=None, normals=True, uvs=True, extra=None, indexed=True):
        attrs = {"POSITION": self.accessor(shape.positions, bounds=True)}
        if normals and shape.normals is not None:
            attrs["NORMAL"] = self.accessor(shape.normals)
        if uvs and shape.uvs is not None:
            attrs["TEXCOORD_0"] = self.accessor(shape.uvs)
        attrs.update(extra or {})
        prim = {"attributes": attrs}
        if indexed:
            component = USHORT if shape.indices.dtype == np.uint16 else UINT
            prim["indices"] = self.accessor(shape.indices, component, target=ELEMENT_ARRAY_BUFFER)
        if material is not None:
            prim["material"] = material
        return prim

    def mesh(self, primitives, name=None, **kw):
        m = {"primitives": primitives if isinstance(primitives, list) else [primitives]}
        if name:
            m["name"] = name
        m.update(kw)
        return self._list("meshes", m)

    def node(self, root=True, **kw):
        i = self._list("nodes", {k: v for k, v in kw.items() if v is not None})
        if root:
            self.d["scenes"][0]["nodes"].append(i)
        return i

    def child(self, parent, **kw):
        i = self.node(root=False, **kw)
        self.d["nodes"][parent].setdefault("children", []).append(i)
        return i

    def image(self, pixels, name=None):
        img = {"bufferView": self.view(png(pixels)), "mimeType": "image/png"}
        if name:
            img["name"] = name
        return self._list("images", img)

    def texture(self, pixels, mag=LINEAR, min_=LINEAR_MIPMAP_LINEAR, wrap=(REPEAT, REPEAT), name=None):
        sampler = self._list("samplers", {"magFilter": mag, "minFilter": min_, "wrapS": wrap[0], "wrapT": wrap[1]})
        return self._list("textures", {"source": self.image(pixels, name), "sampler": sampler})

    def material(self, name, base=(0.8, 0.8, 0.8, 1.0), metallic=0.0, roughness=0.5, **kw):
        pbr = {"baseColorFactor": [float(c) for c in base], "metallicFactor": metallic, "roughnessFactor": roughness}
        for key in ("baseColorTexture", "metallicRoughnessTexture"):
            if key in kw:
                pbr[key] = kw.pop(key)
        m = {"name": name, "pbrMetallicRoughness": pbr}
        m.update(kw)
        return self._list("materials", m)

    def camera(self, eye, target, yfov=40.0, ortho=None, parent=None, **node):
        if ortho:
            cam = {"type": "orthographic", "orthographic": {"xmag": ortho[0], "ymag": ortho[1], "znear": 0.01,
                                                             "zfar": 100.0}}
        else:
            cam = {"type": "perspective", "perspective": {"yfov": math.radians(yfov), "znear": 0.05, "zfar": 100.0}}
        c = self._list("cameras", cam)
        kw = {"name": "camera", "camera": c, "translation": [float(x) for x in eye], "rotation": look_at(eye, target)}
        kw.update(node)
        return self.child(parent, **kw) if parent is not None else self.node(**kw)

    def light(self, kind, intensity, color=(1.0, 1.0, 1.0), at=(0, 5, 0), toward=None, spot=None, name=None):
        ext = self.d.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})
        light = {"type": kind, "color": [float(c) for c in color], "intensity": float(intensity)}
        if spot:
            light["spot"] = {"innerConeAngle": math.radians(spot[0]), "outerConeAngle": math.radians(spot[1])}
        if name:
            light["name"] = name
        ext["lights"].append(light)
        self.uses("KHR_lights_punctual")
        kw = {"name": name or f"{kind}_light", "translation": [float(x) for x in at],
              "extensions": {"KHR_lights_punctual": {"light": len(ext["lights"]) - 1}}}
        if toward is not None:
            d = np.asarray(toward, float) - np.asarray(at, float)
            vertical = abs(d[0]) + abs(d[2]) < 1e-6 * np.linalg.norm(d)
            kw["rotation"] = look_at(at, toward, (0, 0, -1) if vertical else (0, 1, 0))
        return self.node(**kw)

    def uses(self, extension, required=False):
        used = self.d.setdefault("extensionsUsed", [])
        if extension not in used:
            used.append(extension)
        if required and extension not in self.d.setdefault("extensionsRequired", []):
            self.d["extensionsRequired"].append(extension)

    def save(self, path):
        """Writes .gltf (the buffer as a data URI) or .glb (the buffer as its binary chunk)."""
        d = json.loads(json.dumps(self.d))
        if path.endswith(".glb"):
            d["buffers"] = [{"byteLength": len(self.bin)}]
            text = json.dumps(d, separators=(",", ":")).encode()
            text += b" " * (-len(text) % 4)
            body = bytes(self.bin) + b"\x00" * (-len(self.bin) % 4)
            out = (struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + 8 + len(body))
                   + struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(body), b"BIN\x00") + body)
            with open(path, "wb") as f:
                f.write(out)
            return
        d["buffers"] = [{"byteLength": len(self.bin),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()}]
        with open(path, "w") as f:
            json.dump(d, f, indent=1)
            f.write("\n")
