#!/usr/bin/env python3
"""Writes tests/scenes/textured_mesh_tangents.json: tests/scenes/textured_mesh.json whose
sheet brings its own "tangents" (glTF's TANGENT), chosen unlike facet's MikkTSpace ones so
that a renderer which ignored them would show it: t = normalize(a × n) with a fixed axis a
tilted off the sheet's, w = −1 (a mirrored frame). And tests/scenes/mesh_tangents_no_uv.json:
the same sheet with its tangents but without texture coordinates, which glTF's anisotropy turns
from (KHR_materials_anisotropy: the TBN's tangent is TANGENT; nothing else reads coordinates).
Run from the repository root."""
import json
import math

SOURCE, TARGET = "tests/scenes/textured_mesh.json", "tests/scenes/textured_mesh_tangents.json"
NO_UV = "tests/scenes/mesh_tangents_no_uv.json"
AXIS = (0.4, 1.0, 0.2)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def main():
    with open(SOURCE) as f:
        scene = json.load(f)
    scene["name"] = "textured_mesh_tangents"
    sheet = scene["objects"][0]
    tangents = []
    for n in sheet["normals"]:
        t = cross(AXIS, n)
        length = math.sqrt(sum(c * c for c in t))
        tangents.append([round(c / length, 9) for c in t] + [-1.0])
    sheet["tangents"] = tangents
    with open(TARGET, "w") as f:
        json.dump(scene, f)
        f.write("\n")
    scene["name"] = "mesh_tangents_no_uv"
    for key in ("texcoords", "texcoords1"):
        del sheet[key]
    with open(NO_UV, "w") as f:
        json.dump(scene, f)
        f.write("\n")


if __name__ == "__main__":
    main()
