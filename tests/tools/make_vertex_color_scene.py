#!/usr/bin/env python3
"""Writes tests/scenes/vertex_colors.json: tests/scenes/textured_mesh.json whose sheet brings
vertex colours ("colors", glTF's COLOR_0, RGBA), and a second, small sheet of RGB colours
(alpha 1) beside it. The colours change strongly from vertex to vertex (a hash of the vertex
index), so that a renderer which dropped them, or blended a triangle's corners in another
order, would show it; alpha runs over [0.2, 1], which a material's number parameter reads
through "channel": "a". The sphere has no colours: white. Run from the repository root."""
import json

SOURCE, TARGET = "tests/scenes/textured_mesh.json", "tests/scenes/vertex_colors.json"


def hashed(i, k):
    """A number in [0, 1) from vertex i and channel k, repeatable."""
    x = (i * 2654435761 + k * 40503 + 12345) & 0xFFFFFFFF
    x ^= x >> 13
    x = (x * 1274126177) & 0xFFFFFFFF
    return (x & 0xFFFF) / 65536.0


def main():
    with open(SOURCE) as f:
        scene = json.load(f)
    scene["name"] = "vertex_colors"
    sheet = scene["objects"][0]
    sheet["colors"] = [[round(0.15 + 0.85 * hashed(i, k), 6) for k in range(3)] + [round(0.2 + 0.8 * hashed(i, 3), 6)]
                       for i in range(len(sheet["positions"]))]
    # A small flat sheet facing the camera, above the sphere: RGB colours, alpha 1.
    xs, ys = [0.6, 1.05, 1.5], [0.35, 0.6, 0.85]
    positions = [[x, y, 0.2] for y in ys for x in xs]
    triangles = []
    for j in range(2):
        for i in range(2):
            a = j * 3 + i
            triangles += [[a, a + 1, a + 4], [a, a + 4, a + 3]]
    scene["objects"].append({
        "type": "mesh", "name": "rgb_sheet", "positions": positions, "normals": [[0, 0, 1]] * len(positions),
        "triangles": triangles,
        "texcoords": [[(p[0] - 0.6) / 0.9, (0.85 - p[1]) / 0.5] for p in positions],
        "colors": [[round(0.1 + 0.9 * hashed(100 + i, k), 6) for k in range(3)] + [1.0] for i in range(len(positions))],
    })
    with open(TARGET, "w") as f:
        json.dump(scene, f)
        f.write("\n")


if __name__ == "__main__":
    main()
