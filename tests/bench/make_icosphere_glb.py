"""Writes a GLB of a subdivided icosphere: POSITION, NORMAL and uint32 indices.

    python3 tests/bench/make_icosphere_glb.py TRIANGLES OUT.glb

Each of the icosahedron's 20 faces is cut into n² triangles (n = round(√(TRIANGLES/20)),
so 2,000,000 gives 1,997,120), projected onto the unit sphere; a face keeps its own
vertices along its edges (the seams are shared positions with equal normals). One
material (a glTF metallic–roughness dielectric), one node, one mesh, one primitive.
Standard library only: the big-mesh measurements of tests/bench/gltf_scale.py use it.
"""
import array
import json
import math
import struct
import sys


def icosahedron():
    t = (1 + math.sqrt(5)) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    return v, f


def sphere(n):
    """Positions (= normals) and counter-clockwise triangles of the subdivided icosphere."""
    verts, faces = icosahedron()
    pos = array.array("f")
    idx = array.array("I")
    for a, b, c in faces:
        A, B, C = verts[a], verts[b], verts[c]
        row_start = []
        for i in range(n + 1):  # row i has n - i + 1 vertices: A + (B−A)·j/n + (C−A)·i/n
            row_start.append(len(pos) // 3)
            for j in range(n - i + 1):
                p = [A[k] + (B[k] - A[k]) * j / n + (C[k] - A[k]) * i / n for k in range(3)]
                r = math.sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])
                pos.extend((p[0] / r, p[1] / r, p[2] / r))
        for i in range(n):
            r0, r1 = row_start[i], row_start[i + 1]
            for j in range(n - i):
                idx.extend((r0 + j, r0 + j + 1, r1 + j))
                if j < n - i - 1:
                    idx.extend((r0 + j + 1, r1 + j + 1, r1 + j))
    return pos, idx


def glb(doc, bin_bytes):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    bin_bytes += b"\0" * (-len(bin_bytes) % 4)
    total = 12 + 8 + len(text) + 8 + len(bin_bytes)
    return (struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<II", len(text), 0x4E4F534A) + text +
            struct.pack("<II", len(bin_bytes), 0x004E4942) + bin_bytes)


def main():
    triangles, out = int(sys.argv[1]), sys.argv[2]
    n = max(1, round(math.sqrt(triangles / 20)))
    pos, idx = sphere(n)
    vertices, count = len(pos) // 3, len(idx)
    pbytes, ibytes = pos.tobytes(), idx.tobytes()  # positions are the normals of a unit sphere
    doc = {
        "asset": {"version": "2.0", "generator": "tests/bench/make_icosphere_glb.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "icosphere", "mesh": 0}],
        "meshes": [{"name": "icosphere",
                    "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1],
                                                                "metallicFactor": 0, "roughnessFactor": 0.5}}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": vertices, "type": "VEC3",
             "min": [-1, -1, -1], "max": [1, 1, 1]},
            {"bufferView": 1, "componentType": 5126, "count": vertices, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": count, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pbytes), "target": 34962},
            {"buffer": 0, "byteOffset": len(pbytes), "byteLength": len(pbytes), "target": 34962},
            {"buffer": 0, "byteOffset": 2 * len(pbytes), "byteLength": len(ibytes), "target": 34963},
        ],
        "buffers": [{"byteLength": 2 * len(pbytes) + len(ibytes)}],
    }
    with open(out, "wb") as f:
        f.write(glb(doc, pbytes + pbytes + ibytes))
    print(f"{out}: {count // 3} triangles, {vertices} vertices", file=sys.stderr)


if __name__ == "__main__":
    main()
