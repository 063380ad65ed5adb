"""Loads a glTF that facet wrote with Blender's own glTF importer (io_scene_gltf2).

    python gltf_blender_check.py FILE.gltf MESHES MATERIALS LIGHTS

A second, independent reader of the file: it must import without error and
bring the expected numbers of mesh objects, materials and lights.
"""
import sys

import bpy


def main():
    path, meshes, materials, lights = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    result = bpy.ops.import_scene.gltf(filepath=path)
    if result != {"FINISHED"}:
        print(f"FAIL: Blender's glTF importer returned {result}")
        return 1
    got = (sum(o.type == "MESH" for o in bpy.data.objects), len(bpy.data.materials),
           sum(o.type == "LIGHT" for o in bpy.data.objects))
    cameras = sum(o.type == "CAMERA" for o in bpy.data.objects)
    print(f"Blender {bpy.app.version_string} imported {path}: {got[0]} meshes, {got[1]} materials, "
          f"{got[2]} lights, {cameras} cameras")
    if got != (meshes, materials, lights) or cameras != 1:
        print(f"FAIL: expected {meshes} meshes, {materials} materials, {lights} lights and a camera")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
