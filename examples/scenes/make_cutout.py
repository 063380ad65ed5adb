"""Writes examples/scenes/cutout.gltf: glTF's alphaMode MASK on meshes, for every renderer's
cut-outs (facet's "alpha" and "alpha_cutoff", docs/textures.md):

    python3 examples/scenes/make_cutout.py

A bent sheet and a UV sphere, both under a MASK material whose base colour texture is
examples/scenes/textures/leaf.png, copied there from examples/textured/textures/ since a glTF
reads images inside its own folder only (its alpha a leaf shape; alphaCutoff 0.5; the sphere's texture
repeated 3 × 2 by KHR_texture_transform), over an opaque floor, lit by a point light from
above and a sun, so that both cut-outs cast cut-out shadows on the floor and the sphere's
inside shows through its holes. Plain glTF 2.0 (no FACET_ extension): the import maps MASK
onto facet's cut-out. Needs only Python's standard library.
"""
import base64
import json
import math
import os
import shutil
import struct


def sheet(n=8):
    """A 2 × 1.4 sheet bent about x, facing +z, with texture coordinates over it."""
    pos, nrm, uv, tri = [], [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            u, v = i / n, j / n
            a = (v - 0.5) * 1.2
            pos += [2 * u - 1, 0.7 * math.sin(a) / 0.6, 0.35 * (1 - math.cos(a)) / 0.36]
            nrm += [0, -math.sin(a), math.cos(a)]
            uv += [u, 1 - v]
    for j in range(n):
        for i in range(n):
            k = j * (n + 1) + i
            tri += [k, k + 1, k + n + 2, k, k + n + 2, k + n + 1]
    return pos, nrm, uv, tri


def uv_sphere(rings=10, segments=20):
    pos, nrm, uv, tri = [], [], [], []
    for j in range(rings + 1):
        theta = math.pi * j / rings
        for i in range(segments + 1):
            phi = 2 * math.pi * i / segments
            d = [math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi)]
            pos += [0.6 * c for c in d]
            nrm += d
            uv += [i / segments, j / rings]
    for j in range(rings):
        for i in range(segments):
            k = j * (segments + 1) + i
            if j > 0:
                tri += [k, k + segments + 1, k + 1]
            if j < rings - 1:
                tri += [k + 1, k + segments + 1, k + segments + 2]
    return pos, nrm, uv, tri


def floor():
    return ([-3, 0, -3, 3, 0, -3, 3, 0, 3, -3, 0, 3], [0, 1, 0] * 4, [0, 0, 1, 0, 1, 1, 0, 1], [0, 2, 1, 0, 3, 2])


def main():
    blob = bytearray()
    views, accessors, meshes = [], [], []

    def add(data, fmt, count, kind, target, minmax=False):
        while len(blob) % 4:
            blob.append(0)
        offset = len(blob)
        blob.extend(struct.pack("<%d%s" % (len(data), fmt), *data))
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset, "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": 5126 if fmt == "f" else 5125, "count": count,
               "type": kind}
        if minmax:
            acc["min"] = [min(data[k::3]) for k in range(3)]
            acc["max"] = [max(data[k::3]) for k in range(3)]
        accessors.append(acc)
        return len(accessors) - 1

    for name, (pos, nrm, uv, tri), material in (("sheet", sheet(), 0), ("ball", uv_sphere(), 1), ("floor", floor(), 2)):
        attributes = {"POSITION": add(pos, "f", len(pos) // 3, "VEC3", 34962, True),
                      "NORMAL": add(nrm, "f", len(nrm) // 3, "VEC3", 34962),
                      "TEXCOORD_0": add(uv, "f", len(uv) // 2, "VEC2", 34962)}
        indices = add(tri, "I", len(tri), "SCALAR", 34963)
        meshes.append({"name": name, "primitives": [{"attributes": attributes, "indices": indices, "material": material}]})

    leaf = {"index": 0}
    gltf = {
        "asset": {"version": "2.0", "generator": "facet examples/scenes/make_cutout.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_texture_transform"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 0.95, 0.9], "intensity": 15000},
            {"type": "directional", "color": [0.6, 0.65, 0.8], "intensity": 900}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3, 4, 5]}],
        "nodes": [
            {"name": "sheet", "mesh": 0, "translation": [-0.9, 1.1, 0], "rotation": [-0.2588, 0, 0, 0.9659]},
            {"name": "ball", "mesh": 1, "translation": [1.1, 0.75, 0.3]},
            {"name": "floor", "mesh": 2},
            {"name": "camera", "camera": 0, "translation": [0, 2.6, 5.2], "rotation": [-0.2164, 0, 0, 0.9763]},
            {"name": "lamp", "translation": [-1, 5, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "sun", "rotation": [-0.5, 0.3, 0.1, 0.8062], "extensions": {"KHR_lights_punctual": {"light": 1}}}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.75, "aspectRatio": 4 / 3, "znear": 0.1}}],
        "meshes": meshes,
        "materials": [
            {"name": "leaf", "alphaMode": "MASK", "alphaCutoff": 0.5,
             "pbrMetallicRoughness": {"baseColorTexture": leaf, "metallicFactor": 0, "roughnessFactor": 0.6}},
            {"name": "leafy_ball", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
             "pbrMetallicRoughness": {"baseColorTexture": dict(leaf, extensions={"KHR_texture_transform": {
                 "scale": [3, 2]}}), "metallicFactor": 0, "roughnessFactor": 0.5}},
            {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.65, 1], "metallicFactor": 0,
                                                        "roughnessFactor": 0.9}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}],
        "images": [{"uri": "textures/leaf.png"}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    here = os.path.dirname(os.path.abspath(__file__))
    os.makedirs(os.path.join(here, "textures"), exist_ok=True)
    shutil.copyfile(os.path.join(here, "..", "textured", "textures", "leaf.png"), os.path.join(here, "textures", "leaf.png"))
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cutout.gltf")
    with open(out, "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
