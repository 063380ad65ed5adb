"""The example scenes' meshes (make_three_meshes.py, make_textured.py): a smooth UV sphere, a
smooth torus and a flat-shaded box, each as (positions, normals, texcoords, triangles), with
glTF's texture coordinates (v down the picture), and one scene-file mesh object of them.
Standard library only."""
import math


def uv_sphere(center, radius, rings=24, segments=48, u_turns=1):
    """v from the top pole down; u round the equator `u_turns` times."""
    pos, nor, uv, tri = [], [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segments + 1):
            ph = 2 * math.pi * j / segments
            n = [math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)]
            nor.append(n)
            pos.append([center[k] + radius * n[k] for k in range(3)])
            uv.append([u_turns * j / segments, i / rings])
    w = segments + 1
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = i * w + j, i * w + j + 1, (i + 1) * w + j, (i + 1) * w + j + 1
            if i > 0:
                tri.append([a, c, b])
            if i < rings - 1:
                tri.append([b, c, d])
    return pos, nor, uv, tri


def torus(center, major, minor, rings=48, sides=24, u_turns=1):
    """u round the ring `u_turns` times, v once round the tube."""
    pos, nor, uv, tri = [], [], [], []
    for i in range(rings + 1):
        u = 2 * math.pi * i / rings
        for j in range(sides + 1):
            v = 2 * math.pi * j / sides
            n = [math.cos(v) * math.cos(u), math.sin(v), -math.cos(v) * math.sin(u)]
            nor.append(n)
            r = major + minor * math.cos(v)
            pos.append([center[0] + r * math.cos(u), center[1] + minor * math.sin(v), center[2] - r * math.sin(u)])
            uv.append([u_turns * i / rings, j / sides])
    w = sides + 1
    for i in range(rings):
        for j in range(sides):
            a, b, c, d = i * w + j, i * w + j + 1, (i + 1) * w + j, (i + 1) * w + j + 1
            tri.append([a, c, b])
            tri.append([b, c, d])
    return pos, nor, uv, tri


def box(center, half, angle):
    """Turned by `angle` about +y; each face its own four vertices and the whole picture."""
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


def mesh(name, material, data, texcoords=True):
    """A scene file's inline mesh object, numbers to 6 decimals."""
    pos, nor, uv, tri = data
    r6 = lambda v: [round(x, 6) for x in v]
    out = {"type": "mesh", "name": name, "material": material, "positions": [r6(p) for p in pos],
           "normals": [r6(n) for n in nor]}
    if texcoords:
        out["texcoords"] = [r6(t) for t in uv]
    out["triangles"] = tri
    return out
