"""Writes examples/scenes/vertex_colors.gltf: glTF's COLOR_0 in each of its forms, under
metallic–roughness materials whose metallic factor lies strictly between 0 and 1.

    python3 examples/scenes/make_vertex_colors.py > examples/scenes/vertex_colors.gltf

* top left, "painted" over a bent sheet: COLOR_0 VEC3 FLOAT, times a base colour texture
  (examples/scenes/textures/checker.png, copied there from examples/textured/textures/ since a glTF
reads images inside its own folder only, nearest) and factor, metallic 0.4;
* top right, two primitives of one mesh sharing "painted": the left COLOR_0 VEC4 normalized
  UNSIGNED_BYTE, the right none (white: the import gives it a material of its own);
* bottom left, "plain" (no base colour texture, metallic 0.25, the checker as occlusion map):
  COLOR_0 VEC4 normalized UNSIGNED_SHORT, under the scene's ambient (FACET_scene);
* bottom right, "painted" on a tilted sheet without NORMAL (flat-shaded) whose node mirrors
  x (scale −1): COLOR_0 VEC3 FLOAT, its triangles turned round by the import with their colours.

The colours change strongly from vertex to vertex, so that a renderer that dropped them or
blended a triangle's corners in another order would show it. One point light
(KHR_lights_punctual), a perspective camera. The vertex data is a base64 data URI; standard
library only.
"""
import base64
import json
import math
import os
import shutil
import struct


def hashed(i, k):
    """A number in [0, 1) from vertex i and channel k, repeatable."""
    x = (i * 2654435761 + k * 40503 + 12345) & 0xFFFFFFFF
    x ^= x >> 13
    x = (x * 1274126177) & 0xFFFFFFFF
    return (x & 0xFFFF) / 65536.0


def grid(x0, x1, y0, y1, nx, ny, depth):
    """A sheet of nx × ny vertices over [x0, x1] × [y0, y1], z = depth(x, y), facing +z: positions,
    normals, texture coordinates (v down the picture) and triangle indices."""
    pos, nor, uv, idx = [], [], [], []
    h = 1e-4
    for j in range(ny):
        for i in range(nx):
            x, y = x0 + (x1 - x0) * i / (nx - 1), y0 + (y1 - y0) * j / (ny - 1)
            pos.append((x, y, depth(x, y)))
            dx = (depth(x + h, y) - depth(x - h, y)) / (2 * h)
            dy = (depth(x, y + h) - depth(x, y - h)) / (2 * h)
            n = (-dx, -dy, 1.0)
            length = math.sqrt(sum(c * c for c in n))
            nor.append(tuple(c / length for c in n))
            uv.append((i / (nx - 1), 1 - j / (ny - 1)))
    for j in range(ny - 1):
        for i in range(nx - 1):
            a = j * nx + i
            idx += [a, a + 1, a + nx + 1, a, a + nx + 1, a + nx]
    return pos, nor, uv, idx


class Writer:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def accessor(self, values, gltf_type, component, fmt, normalized=False, target=34962, bounds=False):
        while len(self.data) % 4:
            self.data.append(0)
        start = len(self.data)
        width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[gltf_type]
        flat = [v for e in values for v in (e if isinstance(e, (tuple, list)) else (e,))]
        self.data += struct.pack("<%d%s" % (len(flat), fmt), *flat)
        self.views.append({"buffer": 0, "byteOffset": start, "byteLength": len(self.data) - start, "target": target})
        a = {"bufferView": len(self.views) - 1, "componentType": component, "count": len(flat) // width,
             "type": gltf_type}
        if normalized:
            a["normalized"] = True
        if bounds:
            a["min"] = [min(flat[k::width]) for k in range(width)]
            a["max"] = [max(flat[k::width]) for k in range(width)]
        self.accessors.append(a)
        return len(self.accessors) - 1


def colors(first, count, alpha):
    return [tuple(0.1 + 0.9 * hashed(first + i, k) for k in range(3)) + ((0.2 + 0.8 * hashed(first + i, 3),) if alpha else ())
            for i in range(count)]


def main():
    w = Writer()

    def primitive(pos, nor, uv, idx, color_values, color_kind, material):
        attributes = {"POSITION": w.accessor(pos, "VEC3", 5126, "f", bounds=True),
                      "TEXCOORD_0": w.accessor(uv, "VEC2", 5126, "f")}
        if nor:
            attributes["NORMAL"] = w.accessor(nor, "VEC3", 5126, "f")
        if color_kind == "float":
            attributes["COLOR_0"] = w.accessor(color_values, "VEC3", 5126, "f")
        elif color_kind == "ubyte":
            attributes["COLOR_0"] = w.accessor([tuple(round(c * 255) for c in v) for v in color_values], "VEC4", 5121,
                                               "B", normalized=True)
        elif color_kind == "ushort":
            attributes["COLOR_0"] = w.accessor([tuple(round(c * 65535) for c in v) for v in color_values], "VEC4",
                                               5123, "H", normalized=True)
        return {"attributes": attributes, "indices": w.accessor(idx, "SCALAR", 5125, "I", target=34963),
                "material": material, "mode": 4}

    bent = grid(-2.2, -0.3, 0.1, 1.5, 9, 6, lambda x, y: -0.35 * (x + 1.25) ** 2)
    painted = primitive(*bent, colors(0, len(bent[0]), False), "float", 0)
    left = grid(0.3, 1.25, 0.1, 1.5, 5, 6, lambda x, y: 0.0)
    right = grid(1.25, 2.2, 0.1, 1.5, 5, 6, lambda x, y: 0.0)
    halves = [primitive(*left, colors(100, len(left[0]), True), "ubyte", 0),
              primitive(*right, None, None, 0)]
    plain_sheet = grid(-2.2, -0.3, -1.5, -0.1, 9, 6, lambda x, y: 0.15 * math.sin(2 * x) * math.cos(2 * y))
    plain = primitive(*plain_sheet, colors(200, len(plain_sheet[0]), True), "ushort", 1)
    tilted = grid(-2.2, -0.3, -1.5, -0.1, 6, 5, lambda x, y: 0.3 * (x + 1.25) * (y + 0.8))
    flat = primitive(tilted[0], None, tilted[2], tilted[3], colors(300, len(tilted[0]), False), "float", 0)

    light = {"type": "point", "color": [1.0, 0.95, 0.9], "intensity": 30.0 * 683 * math.pi}
    gltf = {
        "asset": {"version": "2.0", "generator": "facet examples/scenes/make_vertex_colors.py"},
        "extensionsUsed": ["KHR_lights_punctual", "FACET_scene"],
        "extensions": {"KHR_lights_punctual": {"lights": [light]}},
        "scene": 0,
        "scenes": [{"name": "vertex_colors", "nodes": [0, 1, 2, 3, 4, 5],
                    "extensions": {"FACET_scene": {"ambient": [0.15, 0.15, 0.15]}}}],
        "nodes": [
            {"name": "painted_float", "mesh": 0},
            {"name": "halves_ubyte", "mesh": 1},
            {"name": "plain_ushort", "mesh": 2},
            {"name": "mirrored_flat", "mesh": 3, "scale": [-1.0, 1.0, 1.0]},
            {"name": "camera", "camera": 0, "translation": [0.0, 0.0, 6.2]},
            {"name": "light", "translation": [-2.0, 3.0, 5.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.75, "znear": 0.05, "zfar": 100.0}}],
        "meshes": [{"name": "painted_float", "primitives": [painted]},
                   {"name": "halves_ubyte", "primitives": halves},
                   {"name": "plain_ushort", "primitives": [plain]},
                   {"name": "mirrored_flat", "primitives": [flat]}],
        "materials": [
            {"name": "painted",
             "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [0.95, 0.9, 0.85, 1.0],
                                      "metallicFactor": 0.4, "roughnessFactor": 0.45}},
            {"name": "plain", "occlusionTexture": {"index": 0},
             "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.7, 0.6, 1.0], "metallicFactor": 0.25,
                                      "roughnessFactor": 0.6}},
        ],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9728, "minFilter": 9728}],
        "images": [{"uri": "textures/checker.png"}],
        "buffers": [{"byteLength": len(w.data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(w.data)).decode()}],
        "bufferViews": w.views,
        "accessors": w.accessors,
    }
    here = os.path.dirname(os.path.abspath(__file__))
    os.makedirs(os.path.join(here, "textures"), exist_ok=True)
    shutil.copyfile(os.path.join(here, "..", "textured", "textures", "checker.png"), os.path.join(here, "textures", "checker.png"))
    print(json.dumps(gltf, indent=1))


if __name__ == "__main__":
    main()
