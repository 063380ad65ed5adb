"""Writes examples/scenes/three_meshes.json: three meshes, three facet materials.

    python3 examples/scenes/make_three_meshes.py > examples/scenes/three_meshes.json

A smooth UV sphere (curved, smooth normals), a flat-shaded box (its own vertices
per face), a smooth torus (concave: it shadows itself) on a floor quad, lit by a
point light and a directional light. `facet export-gltf` turns it into
three_meshes.gltf. Standard library only.
"""
import json
import math


def uv_sphere(center, radius, rings=24, segments=48):
    pos, nor, tri = [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments + 1):
            ph = 2 * math.pi * j / segments
            n = [math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)]
            nor.append(n)
            pos.append([center[k] + radius * n[k] for k in range(3)])
    w = segments + 1
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = i * w + j, i * w + j + 1, (i + 1) * w + j, (i + 1) * w + j + 1
            if i > 0:
                tri.append([a, c, b])
            if i < rings - 1:
                tri.append([b, c, d])
    return pos, nor, tri


def torus(center, major, minor, rings=48, sides=24):
    pos, nor, tri = [], [], []
    for i in range(rings + 1):
        u = 2 * math.pi * i / rings
        for j in range(sides + 1):
            v = 2 * math.pi * j / sides
            n = [math.cos(v) * math.cos(u), math.sin(v), -math.cos(v) * math.sin(u)]
            nor.append(n)
            r = major + minor * math.cos(v)
            pos.append([center[0] + r * math.cos(u), center[1] + minor * math.sin(v), center[2] - r * math.sin(u)])
    w = sides + 1
    for i in range(rings):
        for j in range(sides):
            a, b, c, d = i * w + j, i * w + j + 1, (i + 1) * w + j, (i + 1) * w + j + 1
            tri.append([a, c, b])
            tri.append([b, c, d])
    return pos, nor, tri


def box(center, half, angle):
    pos, nor, tri = [], [], []
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
            quad = [[base, base + 1, base + 2], [base, base + 2, base + 3]]
            if sign < 0:
                quad = [[t[0], t[2], t[1]] for t in quad]
            tri += quad
    return pos, nor, tri


def mesh(name, material, data):
    pos, nor, tri = data
    r6 = lambda v: [round(x, 6) for x in v]
    return {"type": "mesh", "name": name, "material": material,
            "positions": [r6(p) for p in pos], "normals": [r6(n) for n in nor], "triangles": tri}


scene = {
    "name": "three_meshes",
    "camera": {"position": [0.4, 3.4, 6.0], "look_at": [0, -0.35, -0.2], "up": [0, 1, 0], "fov": 36},
    "ambient": [0.03, 0.03, 0.04],
    "materials": {
        "clay": {"name": "clay", "diffuse": {"model": "oren_nayar", "color": [0.72, 0.45, 0.3], "sigma": 0.4},
                 "ambient": [1, 1, 1]},
        "brushed": {"name": "brushed", "diffuse": {"model": "lambert", "color": [0.25, 0.25, 0.28]},
                    "specular": {"model": "ward", "color": [0.8, 0.75, 0.7], "alpha_x": 0.12, "alpha_y": 0.35},
                    "ambient": [1, 1, 1]},
        "plastic": {"name": "plastic", "diffuse": {"model": "lambert", "color": [0.15, 0.3, 0.65]},
                    "specular": {"model": "ggx", "alpha": 0.12}, "ambient": [1, 1, 1]},
    },
    "objects": [
        mesh("sphere", "plastic", uv_sphere([-1.35, 0.0, 0.1], 0.75)),
        mesh("box", "clay", box([1.35, -0.25, 0.2], [0.5, 0.5, 0.5], 0.5)),
        mesh("torus", "brushed", torus([0.05, -0.45, -0.9], 0.7, 0.27)),
        mesh("floor", "clay", ([[-4, -0.75, -4], [4, -0.75, -4], [4, -0.75, 3], [-4, -0.75, 3]],
                               [[0, 1, 0]] * 4, [[0, 2, 1], [0, 3, 2]])),
    ],
    "lights": [
        {"type": "point", "position": [-2.5, 4.5, 3.5], "color": [18, 17, 16], "attenuation": "inverse_square"},
        {"type": "directional", "direction": [0.5, -1, -0.35], "color": [0.35, 0.36, 0.42]},
    ],
}
print(json.dumps(scene, separators=(",", ":")))
