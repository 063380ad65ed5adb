"""Writes examples/scenes/textured.json: textured materials on meshes with texture coordinates.

    python3 examples/scenes/make_textured.py > examples/scenes/textured.json
    build/bin/facet export-gltf examples/scenes/textured.json -o examples/scenes/textured.gltf

A smooth UV sphere under the normal-mapped Cook–Torrance, a smooth torus under Ward with
α_x, α_y maps, a box whose faces glow with the emission map, and a floor under GGX with a
roughness map and a mirrored colour map: the examples of examples/textured/, by path, on
meshes whose texture coordinates are glTF's (v down the picture). `facet export-gltf`
turns it into textured.gltf, its images copied into textured.textures/. Standard library
only.
"""
import json
import math


def uv_sphere(center, radius, rings=24, segments=48):
    pos, nor, uv, tri = [], [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments + 1):
            ph = 2 * math.pi * j / segments
            n = [math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)]
            nor.append(n)
            pos.append([center[k] + radius * n[k] for k in range(3)])
            uv.append([2 * j / segments, i / rings])  # the map twice round, v down from the top pole
    w = segments + 1
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = i * w + j, i * w + j + 1, (i + 1) * w + j, (i + 1) * w + j + 1
            if i > 0:
                tri.append([a, c, b])
            if i < rings - 1:
                tri.append([b, c, d])
    return pos, nor, uv, tri


def torus(center, major, minor, rings=48, sides=24):
    pos, nor, uv, tri = [], [], [], []
    for i in range(rings + 1):
        u = 2 * math.pi * i / rings
        for j in range(sides + 1):
            v = 2 * math.pi * j / sides
            n = [math.cos(v) * math.cos(u), math.sin(v), -math.cos(v) * math.sin(u)]
            nor.append(n)
            pos.append([center[0] + (major + minor * math.cos(v)) * math.cos(u), center[1] + minor * math.sin(v),
                        center[2] - (major + minor * math.cos(v)) * math.sin(u)])
            uv.append([3 * i / rings, j / sides])
    w = sides + 1
    for i in range(rings):
        for j in range(sides):
            a, b, c, d = i * w + j, i * w + j + 1, (i + 1) * w + j, (i + 1) * w + j + 1
            tri += [[a, c, b], [b, c, d]]
    return pos, nor, uv, tri


def box(center, half, angle):
    pos, nor, uv, tri = [], [], [], []
    ca, sa = math.cos(angle), math.sin(angle)

    def rot(p):  # about +y
        return [ca * p[0] + sa * p[2], p[1], -sa * p[0] + ca * p[2]]

    for axis in range(3):
        for sign in (1, -1):
            n = [0, 0, 0]
            n[axis] = sign
            u = [0, 0, 0]
            u[(axis + 1) % 3] = 1
            v = [0, 0, 0]
            v[(axis + 2) % 3] = 1
            base = len(pos)
            for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [n[k] * half[k] + su * u[k] * half[k] + sv * v[k] * half[k] for k in range(3)]
                pos.append([center[k] + rot(p)[k] for k in range(3)])
                nor.append(rot(n))
                uv.append([(su + 1) / 2, (1 - sv) / 2])
            quad = [[base, base + 1, base + 2], [base, base + 2, base + 3]]
            if sign < 0:
                quad = [[t[0], t[2], t[1]] for t in quad]
            tri += quad
    return pos, nor, uv, tri


def mesh(name, material, data):
    pos, nor, uv, tri = data
    r6 = lambda v: [round(x, 6) for x in v]
    return {"type": "mesh", "name": name, "material": material, "positions": [r6(p) for p in pos],
            "normals": [r6(n) for n in nor], "texcoords": [r6(t) for t in uv], "triangles": tri}


scene = {
    "name": "textured",
    "camera": {"position": [0.4, 3.4, 6.0], "look_at": [0, -0.35, -0.2], "up": [0, 1, 0], "fov": 36},
    "ambient": [0.03, 0.03, 0.04],
    "materials": {
        "bumpy": "../textured/textured_normal_cook_torrance.json",
        "brushed": "../textured/textured_ward.json",
        "glowing": "../textured/textured_emission.json",
        "floor": "../textured/textured_ggx.json",
    },
    "objects": [
        mesh("sphere", "bumpy", uv_sphere([-1.35, 0.0, 0.1], 0.75)),
        mesh("box", "glowing", box([1.35, -0.25, 0.2], [0.5, 0.5, 0.5], 0.5)),
        mesh("torus", "brushed", torus([0.05, -0.45, -0.9], 0.7, 0.27)),
        mesh("floor", "floor", ([[-4, -0.75, -4], [4, -0.75, -4], [4, -0.75, 3], [-4, -0.75, 3]], [[0, 1, 0]] * 4,
                                [[0, 0], [4, 0], [4, 3.5], [0, 3.5]], [[0, 2, 1], [0, 3, 2]])),
    ],
    "lights": [
        {"type": "point", "position": [-2.5, 4.5, 3.5], "color": [18, 17, 16], "attenuation": "inverse_square"},
        {"type": "directional", "direction": [0.5, -1, -0.35], "color": [0.35, 0.36, 0.42]},
    ],
}
print(json.dumps(scene, separators=(",", ":")))
