"""Writes textured glTF files with Blender's own glTF exporter (pip bpy), for facet's import tests.

    python gltf_textured_blender.py OUT_FOLDER [SIDE]

A UV sphere and a plane seen by a camera, no lights (facet adds its headlight), each with a Principled BSDF whose Base Color comes from an
Image Texture and whose Metallic and Roughness come from one image through a Separate
Color node (G → Roughness, B → Metallic, as glTF packs them). The sphere's Normal comes
from a Normal Map node (tangent space, its UV map) reading a third image, glTF's
normalTexture; the plane's Emission Color is the base colour image at strength 0.3,
glTF's emissiveTexture. The images are made here (numpy, SIDE texels a side, 8 by
default: a larger SIDE measures the import's cost), no asset is read. Writes:

  OUT/textured.glb            GLB, the images embedded (what Blender users export), with
                              Blender's own MikkTSpace tangents as TANGENT
  OUT/external/textured.gltf  .gltf with its images as external files beside it, without
                              TANGENT (facet computes MikkTSpace tangents)
                              (one of them renamed to a name with a space, its URI
                              percent-encoded, as glTF 2.0 §3.7.2 requires)
  OUT/datauri/textured.gltf   the same with every image and buffer as a data URI
"""
import base64
import json
import math
import os
import sys

import bpy
import mathutils
import numpy as np


def image(name, pixels, colorspace, folder):
    """A PNG written by Blender from `pixels` (rows from the top, RGBA floats), loaded back from its file."""
    h, w, _ = pixels.shape
    im = bpy.data.images.new(name, w, h, alpha=True)
    im.colorspace_settings.name = colorspace
    im.pixels.foreach_set(np.ascontiguousarray(pixels[::-1]).ravel().astype(np.float32))  # Blender's rows: bottom first
    path = os.path.join(folder, name + ".png")
    im.filepath_raw = path
    im.file_format = "PNG"
    im.save()
    bpy.data.images.remove(im)
    return bpy.data.images.load(path)


def material(name, base, mr, base_interpolation, mr_interpolation, normals=None, emission=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes, links = m.node_tree.nodes, m.node_tree.links
    bsdf = nodes["Principled BSDF"]
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = base
    tex.interpolation = base_interpolation
    links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    mr_tex = nodes.new("ShaderNodeTexImage")
    mr_tex.image = mr
    mr_tex.interpolation = mr_interpolation
    sep = nodes.new("ShaderNodeSeparateColor")
    links.new(mr_tex.outputs["Color"], sep.inputs["Color"])
    links.new(sep.outputs["Green"], bsdf.inputs["Roughness"])
    links.new(sep.outputs["Blue"], bsdf.inputs["Metallic"])
    if normals is not None:
        n_tex = nodes.new("ShaderNodeTexImage")
        n_tex.image = normals
        n_map = nodes.new("ShaderNodeNormalMap")
        n_map.space, n_map.uv_map = "TANGENT", "UVMap"
        links.new(n_tex.outputs["Color"], n_map.inputs["Color"])
        links.new(n_map.outputs["Normal"], bsdf.inputs["Normal"])
    if emission:
        links.new(tex.outputs["Color"], bsdf.inputs["Emission Color"])
        bsdf.inputs["Emission Strength"].default_value = emission
    return m


def make_images(folder, n):
    j, i = np.mgrid[0:n, 0:n]
    checker = np.zeros((n, n, 4))
    checker[..., 0] = np.where((i * 8 // n + j * 8 // n) % 2 == 0, 0.85, 0.15)
    checker[..., 1] = 0.2 + 0.6 * i / (n - 1)
    checker[..., 2] = 0.2 + 0.6 * j / (n - 1)
    checker[..., 3] = 1
    mr = np.zeros((n, n, 4))
    mr[..., 0] = 1  # occlusion channel: unused
    mr[..., 1] = 0.35 + 0.55 * ((i + 2 * j) % n) / (n - 1)  # roughness
    mr[..., 2] = np.where(j < n // 2, 0.0, np.where(i % 3 == 0, 1.0, 0.5))  # metallic: dielectric top, metals below
    mr[..., 3] = 1
    # A tangent-space normal map of gentle bumps (x from u, y from v), encoded (n + 1)/2.
    nx = 0.3 * np.sin(2 * np.pi * 2 * (i + 0.5) / n)
    ny = 0.25 * np.cos(2 * np.pi * 3 * (j + 0.5) / n)
    length = np.sqrt(nx * nx + ny * ny + 1)
    normals = np.stack([(nx / length + 1) / 2, (ny / length + 1) / 2, (1 / length + 1) / 2, np.ones((n, n))], axis=-1)
    return (image("checker", checker, "sRGB", folder), image("metal_rough", mr, "Non-Color", folder),
            image("normals", normals, "Non-Color", folder))


def build_scene(folder, side):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    base, mr, normals = make_images(folder, side)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=1, location=(0, 0.5, 1.0))
    bpy.ops.object.shade_smooth()
    sphere = bpy.context.active_object
    sphere.name = "sphere"
    sphere.data.materials.append(material("sphere_mat", base, mr, "Closest", "Closest", normals=normals))
    bpy.ops.mesh.primitive_plane_add(size=4, location=(0, 0, 0))
    plane = bpy.context.active_object
    plane.name = "plane"
    plane.data.materials.append(material("plane_mat", base, mr, "Linear", "Linear", emission=0.3))
    bpy.ops.object.camera_add(location=(0.5, -5.5, 3.2))
    camera = bpy.context.active_object
    camera.rotation_euler = (mathutils.Vector((0, 0.3, 0.7)) - camera.location).to_track_quat("-Z", "Y").to_euler()
    camera.data.angle = math.radians(45)


def export(path, fmt, tangents):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    result = bpy.ops.export_scene.gltf(filepath=path, export_format=fmt, export_lights=False, export_cameras=True,
                                       export_texcoords=True, export_normals=True, export_tangents=tangents,
                                       export_materials="EXPORT",
                                       export_image_format="AUTO", export_apply=True)
    if result != {"FINISHED"}:
        raise SystemExit(f"FAIL: Blender's glTF exporter returned {result} for {path}")


def rename_with_space(gltf_path):
    """The first image's file renamed to a name with a space, its URI percent-encoded."""
    folder = os.path.dirname(gltf_path)
    doc = json.load(open(gltf_path))
    old = doc["images"][0]["uri"]
    new = "base colour.png"
    os.replace(os.path.join(folder, old), os.path.join(folder, new))
    doc["images"][0]["uri"] = "base%20colour.png"
    json.dump(doc, open(gltf_path, "w"), indent=1)


def inline_everything(src, dst):
    """`src` with its buffers and images as data URIs."""
    doc = json.load(open(src))
    folder = os.path.dirname(src)
    for key, mime in (("buffers", "application/octet-stream"), ("images", None)):
        for item in doc.get(key, []):
            uri = item["uri"].replace("%20", " ")
            data = open(os.path.join(folder, uri), "rb").read()
            kind = mime or item.get("mimeType") or "image/png"
            item["uri"] = f"data:{kind};base64," + base64.b64encode(data).decode()
            item.pop("mimeType", None)
    os.makedirs(os.path.dirname(dst), exist_ok=True)
    json.dump(doc, open(dst, "w"))


def main():
    out = os.path.abspath(sys.argv[1])
    sources = os.path.join(out, "sources")
    os.makedirs(sources, exist_ok=True)
    build_scene(sources, int(sys.argv[2]) if len(sys.argv) > 2 else 8)
    export(os.path.join(out, "textured.glb"), "GLB", True)
    external = os.path.join(out, "external", "textured.gltf")
    export(external, "GLTF_SEPARATE", False)
    rename_with_space(external)
    inline_everything(external, os.path.join(out, "datauri", "textured.gltf"))
    doc = json.load(open(external))
    print(f"Blender {bpy.app.version_string} wrote {out}: {len(doc['images'])} images, {len(doc['textures'])} "
          f"textures, {len(doc['materials'])} materials; samplers {doc.get('samplers')}")
    for m in doc["materials"]:
        print(" ", m["name"], json.dumps({k: v for k, v in m.items() if k != "name"}))
    if not any("normalTexture" in m for m in doc["materials"]) or not any("emissiveTexture" in m for m in doc["materials"]):
        raise SystemExit("FAIL: Blender's exporter wrote no normalTexture or no emissiveTexture")
    return 0


if __name__ == "__main__":
    sys.exit(main())
