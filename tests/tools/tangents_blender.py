"""Blender's own tangents of a test mesh, for facet's MikkTSpace comparison
(tests/unit/tangents_test.cpp, docs/textures.md "Tangent frames").

Builds, with pip bpy, a smooth UV sphere (its UV seam and poles included) and a plane whose
UVs are mirrored in u (so its tangents have w = -1), triangulated, and calls
Mesh.calc_tangents() on the UV map. Writes OUT.json: per corner (loop) its position,
normal, UV (Blender's, v up), tangent and bitangent_sign, and the triangles as loop
indices. Usage: python tangents_blender.py OUT.json"""
import json
import os
import sys

import bpy
import bmesh  # noqa: E402 (after bpy, which makes it importable)


def mesh_data(obj):
    mesh = obj.data
    mesh.calc_tangents(uvmap=mesh.uv_layers.active.name)
    uv = mesh.uv_layers.active.data
    normals = [tuple(n.vector) for n in mesh.corner_normals]
    corners = []
    for loop in mesh.loops:
        corners.append({"position": list(mesh.vertices[loop.vertex_index].co),
                        "normal": list(normals[loop.index]),
                        "uv": list(uv[loop.index].uv),
                        "tangent": list(loop.tangent),
                        "sign": loop.bitangent_sign})
    triangles = [[p.loop_indices[k] for k in range(3)] for p in mesh.polygons]
    return {"corners": corners, "triangles": triangles}


def triangulated(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bmesh.ops.triangulate(bm, faces=bm.faces[:])
    bm.to_mesh(obj.data)
    bm.free()
    obj.data.update()
    return obj


def main(out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12, radius=1.0, calc_uvs=True)
    sphere = triangulated(bpy.context.active_object)
    for p in sphere.data.polygons:
        p.use_smooth = True
    # A plane, its UVs mirrored in u (a mirrored half, as artists make): w = -1 there.
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=4, y_subdivisions=3, size=2.0, calc_uvs=True, location=(3, 0, 0),
                                    rotation=(0.4, 0.2, 0.1))
    plane = triangulated(bpy.context.active_object)
    for d in plane.data.uv_layers.active.data:
        d.uv = (1 - d.uv[0], d.uv[1])
    result = {"meshes": [mesh_data(sphere), mesh_data(plane)]}
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(result, f)
    os.replace(tmp, out)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else sys.argv[1])
