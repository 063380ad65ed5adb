"""Writes the glTF corpus facet's import is checked on (issue 27: glTF files as they are found).

    python gltf_corpus.py OUT_FOLDER            (a Python with pip bpy 4.5 and numpy)

Writes OUT/corpus/*.gltf|glb (the corpus), OUT/variants/*.gltf (deliberately wrong twins
of those files, for the second opinion's own teeth), OUT/blender/lights.blend (the .blend
that OUT/corpus/blender_lights.glb was exported from, for the Cycles comparison) and
OUT/corpus.json (each file, what it covers, and which variants twin which file).

Hand-written files come from tests/tools/gltf_build.py (numpy; data URIs or a GLB's binary
chunk, no file beside them); the blender_* files are written by Blender 4.5's own glTF
exporter (pip bpy) from scenes built here. Nothing is read from disk and the output is the
same on every run, but for the triangle order in the index buffers of the two files Blender's
exporter writes, which changes from run to run (the same triangles; docs/gltf.md).

Every file is lit by KHR_lights_punctual lights, in the units Blender's exporter writes
(P W → P/(4π)·683 cd, S W/m² → S·683 lx), because a glTF without lights is lit by facet's
headlight and by nothing in Blender: the second opinion would compare unlike scenes. Every
visible object receives light from some light and faces the camera, so that `facet
validate` finds each scene informative. Sizes are a few hundred triangles and 16–32 texel
images: the whole corpus validates in seconds per renderer.
"""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gltf_build as gb  # noqa: E402

CORPUS = []       # (file name, what it covers)
VARIANTS = []     # (variant file, original file, what is wrong, which check must fail)


def entry(name, covers):
    def register(fn):
        CORPUS.append((name, covers, fn))
        return fn
    return register


# ----------------------------------------------------------------------------- a common stage

FLOOR_Y = 0.0


def stage(doc, floor=True, camera=True, key=True, fill=True, eye=(0.0, 2.6, 6.2), target=(0.0, 0.8, 0.0)):
    """A grey floor, a camera and two lights most files share: a 1000 W point light (Blender's
    default power) up right, and a 2 W/m² sun from behind the camera."""
    if floor:
        grey = doc.material("floor", base=(0.55, 0.55, 0.52, 1), roughness=0.8)
        doc.node(name="floor", mesh=doc.mesh(doc.primitive(gb.plane(9.0), grey), "floor"))
    if camera:
        doc.camera(eye, target)
    if key:
        doc.light("point", gb.point_candela(1000.0), at=(3.5, 5.0, 3.5), name="key")
    if fill:
        doc.light("directional", gb.sun_lux(2.0), color=(1.0, 0.95, 0.9), at=(-2.0, 6.0, 8.0),
                  toward=(0.5, 0.0, 0.0), name="sun")


def lit_material(doc, name, base, metallic=0.0, roughness=0.45, **kw):
    return doc.material(name, base=base + (1.0,) if len(base) == 3 else base, metallic=metallic,
                        roughness=roughness, **kw)


# ----------------------------------------------------------------------------- files

@entry("box_khronos.gltf", "Box.gltf's layout: a root node rotated −90° about x (quaternion) over a child "
                           "mesh node; flat box, one material (baseColorFactor, metallic 0)")
def box_khronos(doc):
    red = doc.material("Red", base=(0.8, 0.0, 0.0, 1.0), metallic=0.0, roughness=0.5)
    root = doc.node(name="root", rotation=[-0.7071068, 0.0, 0.0, 0.7071068])
    doc.child(root, name="Mesh", mesh=doc.mesh(doc.primitive(gb.box(0.5, 0.5, 0.5), red), "Mesh"))
    doc.camera((1.6, 1.3, 2.4), (0, 0, 0))
    doc.light("point", gb.point_candela(200.0), at=(2.0, 2.5, 2.0), name="key")
    doc.light("directional", gb.sun_lux(1.0), at=(0, 3, 5), toward=(-0.6, 0.2, 0), name="sun")


@entry("box_textured.gltf", "BoxTextured.gltf's layout: the rotated root, a base colour texture "
                            "(LINEAR_MIPMAP_LINEAR, REPEAT), metallic 0")
def box_textured(doc):
    tex = doc.texture(gb.checker(16, 4), gb.LINEAR, gb.LINEAR_MIPMAP_LINEAR, name="checker")
    mat = doc.material("Texture", base=(1, 1, 1, 1), metallic=0.0, roughness=0.6,
                       baseColorTexture={"index": tex})
    root = doc.node(name="root", rotation=[-0.7071068, 0.0, 0.0, 0.7071068])
    doc.child(root, name="Mesh", mesh=doc.mesh(doc.primitive(gb.box(0.5, 0.5, 0.5), mat), "Mesh"))
    # (From (1.5, 1.2, 2.5) one pixel centre at 96×72 fell on the box's top edge, within float32
    # rounding of both faces: Cycles took the other face there. Validation judges shading, not
    # which face an edge pixel rounds to; the edge's texel blend is checked from here as well.)
    doc.camera((1.52, 1.23, 2.47), (0, 0, 0))
    doc.light("point", gb.point_candela(200.0), at=(2.0, 2.5, 2.0), name="key")
    doc.light("directional", gb.sun_lux(1.0), at=(0, 3, 5), toward=(-0.6, 0.2, 0), name="sun")


def helmet_shape():
    """A helmet-like dome: a sphere flattened at the back and widened at the jaw (asymmetric)."""
    return gb.uv_sphere(1.0, 24, 12, squash=lambda d: 1.0 + 0.18 * d[0] * abs(d[0]) - 0.12 * max(d[1], 0) ** 2)


def helmet_textures(doc, n=32):
    i, j = gb.grid(n)
    grime = 0.5 + 0.5 * np.sin(i * 0.9) * np.cos(j * 0.7)
    base = gb.rgba(0.35 + 0.35 * grime, 0.3 + 0.3 * grime, 0.25 + 0.2 * (j / (n - 1)))
    rough = 0.35 + 0.5 * (((i * 3 + j * 5) % 11) / 10)
    metal = np.where((i // 8 + j // 8) % 2 == 0, 1.0, 0.0)
    occl = 0.6 + 0.4 * np.cos(np.pi * (j - n / 2) / n) ** 2
    mr = gb.rgba(occl, rough, metal)
    emit = gb.rgba(np.where((j > 12) & (j < 16), 1.0, 0.0), np.where((j > 12) & (j < 16), 0.6, 0.0), 0.1)
    samp = dict(mag=gb.LINEAR, min_=gb.LINEAR_MIPMAP_LINEAR)
    return (doc.texture(base, name="albedo", **samp), doc.texture(mr, name="metal_roughness", **samp),
            doc.texture(gb.normal_bumps(n), name="normal", **samp), doc.texture(emit, name="emissive", **samp))


def helmet(doc, tangents):
    albedo, mr, normal, emissive = helmet_textures(doc)
    mat = doc.material("Material_MR", base=(1, 1, 1, 1), metallic=1.0, roughness=1.0,
                       baseColorTexture={"index": albedo}, metallicRoughnessTexture={"index": mr},
                       normalTexture={"index": normal}, occlusionTexture={"index": mr},
                       emissiveTexture={"index": emissive}, emissiveFactor=[1.0, 1.0, 1.0])
    shape = helmet_shape()
    extra = {}
    if tangents:
        extra["TANGENT"] = doc.accessor(mikktspace_tangents(shape))
    # DamagedHelmet's node: its mesh authored z-up, turned +90° about x into glTF's y-up.
    doc.node(name="node_damagedHelmet", mesh=doc.mesh(doc.primitive(shape, mat, extra=extra), "helmet"),
             rotation=[0.7071068, 0.0, 0.0, 0.7071068], translation=[0.0, 1.1, 0.0])
    stage(doc, eye=(0.8, 2.0, 4.2), target=(0.0, 1.0, 0.0))


@entry("helmet_like.gltf", "DamagedHelmet's layout: a node rotated +90° about x, base colour, "
                           "metallic–roughness, normal, occlusion and emissive maps (emissiveFactor 1), "
                           "TANGENT (Blender's MikkTSpace)")
def helmet_like(doc):
    helmet(doc, tangents=True)


@entry("helmet_like_notangent.glb", "the same as a GLB without TANGENT (facet's MikkTSpace), its images in the "
                                    "binary chunk")
def helmet_like_notangent(doc):
    helmet(doc, tangents=False)


@entry("rotated_quaternion.gltf", "nodes rotated by quaternions about oblique axes (a box, a torus, an egg)")
def rotated_quaternion(doc):
    stage(doc)
    a = lit_material(doc, "orange", (0.9, 0.45, 0.1))
    b = lit_material(doc, "teal", (0.1, 0.6, 0.55), roughness=0.3)
    c = lit_material(doc, "violet", (0.55, 0.3, 0.8))
    doc.node(name="box", mesh=doc.mesh(doc.primitive(gb.box(0.45, 0.45, 0.45), a), "box"),
             translation=[-1.6, 0.8, 0.3], rotation=gb.quat_axis_angle((1, 1, 0.3), 37))
    doc.node(name="torus", mesh=doc.mesh(doc.primitive(gb.torus(0.6, 0.22), b), "torus"),
             translation=[0.2, 0.75, -0.2], rotation=gb.quat_axis_angle((0.2, 0.4, 1), 62))
    egg = gb.uv_sphere(0.55, 16, 8, squash=lambda d: 1 + 0.3 * d[1])
    doc.node(name="egg", mesh=doc.mesh(doc.primitive(egg, c), "egg"),
             translation=[1.7, 0.7, 0.5], rotation=gb.quat_axis_angle((0.8, -0.2, 0.5), 115))


@entry("scaled_nonuniform.gltf", "non-uniform scales (normals need the inverse transpose): a squashed "
                                 "sphere, a stretched rotated box")
def scaled_nonuniform(doc):
    stage(doc)
    a = lit_material(doc, "yellow", (0.85, 0.75, 0.15), roughness=0.35)
    b = lit_material(doc, "blue", (0.15, 0.3, 0.85))
    doc.node(name="squashed", mesh=doc.mesh(doc.primitive(gb.uv_sphere(1.0, 20, 10), a), "sphere"),
             translation=[-1.0, 0.6, 0.0], scale=[1.2, 0.5, 0.8], rotation=gb.quat_axis_angle((0, 0, 1), 25))
    doc.node(name="stretched", mesh=doc.mesh(doc.primitive(gb.box(0.5, 0.5, 0.5), b), "box"),
             translation=[1.3, 0.9, 0.2], scale=[0.5, 1.6, 0.9], rotation=gb.quat_axis_angle((1, 0.5, 0), 30))


@entry("mirrored.gltf", "negative determinants: scale (−1, 1, 1), a rotated (1, −1, 1) and a mirror through a "
                        "parent, on an asymmetric smooth egg (windings reversed)")
def mirrored(doc):
    stage(doc)
    egg = gb.uv_sphere(0.5, 16, 8, squash=lambda d: 1 + 0.35 * d[0] + 0.15 * d[1])
    a = lit_material(doc, "green", (0.2, 0.75, 0.3))
    b = lit_material(doc, "pink", (0.9, 0.4, 0.55), roughness=0.3)
    c = lit_material(doc, "sand", (0.8, 0.7, 0.45))
    doc.node(name="egg", mesh=doc.mesh(doc.primitive(egg, a), "egg_a"), translation=[-1.8, 0.6, 0.0])
    doc.node(name="egg_mirror_x", mesh=doc.mesh(doc.primitive(egg, b), "egg_b"), translation=[-0.3, 0.6, 0.2],
             scale=[-1.0, 1.0, 1.0])
    doc.node(name="egg_mirror_y_rotated", mesh=doc.mesh(doc.primitive(egg, c), "egg_c"),
             translation=[1.2, 0.7, 0.0], scale=[1.0, -1.0, 1.0], rotation=gb.quat_axis_angle((0, 1, 0.4), 50))
    parent = doc.node(name="mirror_parent", scale=[1.0, 1.0, -1.0], translation=[0.0, 0.0, -1.2])
    doc.child(parent, name="box_in_mirror", mesh=doc.mesh(doc.primitive(gb.box(0.35, 0.3, 0.25), a), "box"),
              translation=[0.9, 0.5, 0.3], rotation=gb.quat_axis_angle((0, 1, 0), 30))


@entry("matrix_nodes.gltf", "nodes given by `matrix` (column-major): rotation × non-uniform scale × "
                            "translation, one with a negative determinant, one under a TRS parent")
def matrix_nodes(doc):
    stage(doc)
    a = lit_material(doc, "copper", (0.95, 0.6, 0.4), metallic=1.0, roughness=0.4)
    b = lit_material(doc, "slate", (0.35, 0.45, 0.6))
    m1 = gb.trs_matrix((-1.4, 0.7, 0.0), gb.quat_axis_angle((0.3, 1, 0.2), 40), (0.6, 0.4, 0.7))
    m2 = gb.trs_matrix((1.3, 0.8, 0.0), gb.quat_axis_angle((1, 0, 0.5), -35), (-0.7, 0.5, 0.5))
    doc.node(name="matrix_sphere", mesh=doc.mesh(doc.primitive(gb.uv_sphere(1.0, 18, 9), a), "sphere"),
             matrix=gb.column_major(m1))
    doc.node(name="matrix_mirrored_box", mesh=doc.mesh(doc.primitive(gb.box(), b), "box"),
             matrix=gb.column_major(m2))
    parent = doc.node(name="trs_parent", translation=[0.0, 0.0, 1.0], rotation=gb.quat_axis_angle((0, 1, 0), 20))
    m3 = gb.trs_matrix((0.0, 0.45, 0.0), gb.quat_axis_angle((0, 0, 1), 90), (0.45, 0.9, 0.3))
    doc.child(parent, name="matrix_child", mesh=doc.mesh(doc.primitive(gb.torus(0.5, 0.2), b), "torus"),
              matrix=gb.column_major(m3))


@entry("nested_hierarchy.gltf", "four levels of nodes, each with its own rotation, scale or translation")
def nested_hierarchy(doc):
    stage(doc)
    a = lit_material(doc, "red", (0.85, 0.2, 0.15))
    b = lit_material(doc, "cyan", (0.1, 0.7, 0.8), roughness=0.3)
    root = doc.node(name="level0", translation=[0.0, 0.2, 0.0], rotation=gb.quat_axis_angle((0, 1, 0), 30),
                    scale=[1.2, 1.2, 1.2])
    l1 = doc.child(root, name="level1", translation=[0.5, 0.3, 0.0], rotation=gb.quat_axis_angle((0, 0, 1), 15))
    l2 = doc.child(l1, name="level2", scale=[1.0, 0.6, 1.4], translation=[-0.4, 0.3, 0.2])
    doc.child(l2, name="level3", mesh=doc.mesh(doc.primitive(gb.uv_sphere(0.5, 16, 8), a), "sphere"),
              rotation=gb.quat_axis_angle((1, 0, 0), 45), translation=[-0.6, 0.4, 0.0])
    doc.child(l1, name="level2_box", mesh=doc.mesh(doc.primitive(gb.box(0.3, 0.3, 0.3), b), "box"),
              translation=[0.7, 0.25, 0.3], rotation=gb.quat_axis_angle((1, 1, 1), 20))


@entry("instanced.gltf", "one mesh instanced by four nodes (translated, rotated, scaled, mirrored)")
def instanced(doc):
    stage(doc)
    mat = lit_material(doc, "gold", (1.0, 0.78, 0.34), metallic=1.0, roughness=0.35)
    mesh = doc.mesh(doc.primitive(gb.torus(0.45, 0.16, 16, 8), mat), "ring")
    doc.node(name="ring_a", mesh=mesh, translation=[-2.0, 0.4, 0.3])
    doc.node(name="ring_b", mesh=mesh, translation=[-0.7, 0.65, 0.0], rotation=gb.quat_axis_angle((1, 0, 0), 60))
    doc.node(name="ring_c", mesh=mesh, translation=[0.7, 0.6, 0.2], scale=[1.2, 0.6, 1.0],
             rotation=gb.quat_axis_angle((0, 0, 1), 50))
    doc.node(name="ring_d", mesh=mesh, translation=[2.0, 0.6, 0.0], scale=[-1.0, 1.0, 1.0],
             rotation=gb.quat_axis_angle((1, 0, 1), 70))


@entry("multi_primitive.gltf", "one mesh of two primitives with two materials, and a third primitive "
                               "without a material (glTF's default material)")
def multi_primitive(doc):
    stage(doc)
    a = lit_material(doc, "lime", (0.5, 0.8, 0.2))
    b = lit_material(doc, "plum", (0.6, 0.25, 0.5), roughness=0.3)
    top = gb.uv_sphere(0.5, 16, 8)
    top.positions = top.positions + np.float32([0, 1.3, 0])
    base = gb.box(0.6, 0.4, 0.6)
    base.positions = base.positions + np.float32([0, 0.4, 0])
    side = gb.box(0.25, 0.25, 0.25)
    side.positions = side.positions + np.float32([1.1, 0.25, 0.4])
    doc.node(name="statue", mesh=doc.mesh([doc.primitive(base, a), doc.primitive(top, b), doc.primitive(side)],
                                          "statue"), rotation=gb.quat_axis_angle((0, 1, 0), -25))


@entry("default_material.gltf", "primitives without a material (glTF's default: white, metallic 1, roughness 1) "
                                "and a node with no mesh between")
def default_material(doc):
    stage(doc, floor=False)
    grey = doc.material("floor", base=(0.4, 0.45, 0.5, 1), roughness=0.9)
    doc.node(name="floor", mesh=doc.mesh(doc.primitive(gb.plane(9.0), grey), "floor"))
    empty = doc.node(name="empty", translation=[0.0, 0.0, 0.0])
    doc.child(empty, name="sphere", mesh=doc.mesh(doc.primitive(gb.uv_sphere(0.7, 20, 10)), "sphere"),
              translation=[-0.8, 0.7, 0.0])
    doc.child(empty, name="box", mesh=doc.mesh(doc.primitive(gb.box(0.5, 0.5, 0.5)), "box"),
              translation=[1.0, 0.5, 0.0], rotation=gb.quat_axis_angle((0, 1, 0), 35))


@entry("flat_no_normals.gltf", "primitives without NORMAL (flat-shaded by both readers), one of them "
                               "without indices")
def flat_no_normals(doc):
    stage(doc)
    a = lit_material(doc, "rust", (0.75, 0.35, 0.2))
    b = lit_material(doc, "sky", (0.4, 0.6, 0.9))
    ico = gb.uv_sphere(0.7, 8, 5)
    doc.node(name="faceted", mesh=doc.mesh(doc.primitive(ico, a, normals=False), "faceted"),
             translation=[-0.9, 0.7, 0.0])
    tri = gb.box(0.45, 0.45, 0.45)
    flat = gb.Shape(tri.positions[tri.indices], None, tri.uvs[tri.indices], np.arange(len(tri.indices)))
    doc.node(name="unindexed", mesh=doc.mesh(doc.primitive(flat, b, normals=False, indexed=False), "unindexed"),
             translation=[1.0, 0.5, 0.0], rotation=gb.quat_axis_angle((0, 1, 0), 30))


def three_uv_sets(doc, shape):
    """TEXCOORD_1 and TEXCOORD_2 beside the shape's own: set 1 the uv turned 90° and doubled, set 2
    a planar projection of x and y."""
    uv0 = shape.uvs.astype(float)
    uv1 = np.stack([2.0 * uv0[:, 1], 2.0 * (1.0 - uv0[:, 0])], axis=1)
    p = shape.positions.astype(float)
    uv2 = np.stack([0.5 + 0.6 * p[:, 0], 0.5 - 0.6 * p[:, 1]], axis=1)
    return {"TEXCOORD_1": doc.accessor(uv1), "TEXCOORD_2": doc.accessor(uv2)}


@entry("uv_sets.gltf", "three TEXCOORD sets: a base colour reading TEXCOORD_1 and an emissive map reading "
                       "TEXCOORD_2; another material's map whose KHR_texture_transform overrides texCoord")
def uv_sets(doc):
    stage(doc)
    grad = doc.texture(gb.gradient(16), gb.NEAREST, gb.NEAREST, name="gradient")
    strip = doc.texture(gb.stripes(16), gb.NEAREST, gb.NEAREST, name="stripes")
    doc.uses("KHR_texture_transform")
    a = doc.material("sets_1_and_2", base=(1, 1, 1, 1), roughness=0.6, baseColorTexture={"index": grad, "texCoord": 1},
                     emissiveTexture={"index": strip, "texCoord": 2}, emissiveFactor=[0.3, 0.3, 0.3])
    b = doc.material("override", base=(1, 1, 1, 1), roughness=0.6,
                     baseColorTexture={"index": strip, "texCoord": 0, "extensions": {"KHR_texture_transform": {
                         "texCoord": 2, "scale": [1.5, 1.5]}}})
    box = gb.box(0.6, 0.6, 0.6)
    doc.node(name="box_sets", mesh=doc.mesh(doc.primitive(box, a, extra=three_uv_sets(doc, box)), "box_sets"),
             translation=[-1.0, 0.6, 0.0], rotation=gb.quat_axis_angle((0, 1, 0), 30))
    sphere = gb.uv_sphere(0.6, 16, 8)
    doc.node(name="sphere_override",
             mesh=doc.mesh(doc.primitive(sphere, b, extra=three_uv_sets(doc, sphere)), "sphere_override"),
             translation=[1.1, 0.6, 0.0])


@entry("texture_transform.gltf", "KHR_texture_transform (required) per texture: offset, rotation and scale on "
                                 "the base colour, another on the metallic–roughness map, the normal map and the "
                                 "emissive map")
def texture_transform(doc):
    stage(doc)
    doc.uses("KHR_texture_transform", required=True)
    chk = doc.texture(gb.checker(16, 4), gb.LINEAR, gb.LINEAR, name="checker")
    i, j = gb.grid(16)
    mr = doc.texture(gb.rgba(1.0, 0.3 + 0.6 * ((i + j) % 5) / 4, 0.0), gb.NEAREST, gb.NEAREST, name="roughness")
    nrm = doc.texture(gb.normal_bumps(16), gb.LINEAR, gb.LINEAR, name="normal")
    emit = doc.texture(gb.stripes(16), gb.NEAREST, gb.NEAREST, wrap=(gb.MIRROR, gb.MIRROR), name="stripes")

    def tt(offset, rotation, scale):
        return {"KHR_texture_transform": {"offset": offset, "rotation": rotation, "scale": scale}}

    a = doc.material("transformed", base=(1, 1, 1, 1), metallic=0.0, roughness=1.0,
                     baseColorTexture={"index": chk, "extensions": tt([0.2, -0.1], 0.6, [1.7, 0.8])},
                     metallicRoughnessTexture={"index": mr, "extensions": tt([0.5, 0.25], -0.3, [2.0, 2.0])},
                     normalTexture={"index": nrm, "extensions": tt([0.0, 0.3], 0.0, [1.5, 1.5])},
                     emissiveTexture={"index": emit, "extensions": tt([0.1, 0.0], 1.2, [0.7, 1.3])},
                     emissiveFactor=[0.4, 0.3, 0.2])
    doc.node(name="sphere", mesh=doc.mesh(doc.primitive(gb.uv_sphere(0.8, 20, 10), a), "sphere"),
             translation=[-0.9, 0.85, 0.0])
    doc.node(name="box", mesh=doc.mesh(doc.primitive(gb.box(0.55, 0.55, 0.55), a), "box"),
             translation=[1.2, 0.6, 0.1], rotation=gb.quat_axis_angle((0, 1, 0), -30))


@entry("materials_ior_specular.gltf", "glTF's BRDF with KHR_materials_ior (1.33, 1.8, 2.4), KHR_materials_specular "
                                      "(specularFactor, specularColorFactor, specularTexture's A through a "
                                      "KHR_texture_transform), KHR_materials_clearcoat (factors, clearcoatTexture's "
                                      "R), a metallic–roughness map at metallic 0.5, roughness 0")
def materials_ior_specular(doc):
    stage(doc)
    doc.uses("KHR_materials_ior")
    doc.uses("KHR_materials_specular")
    doc.uses("KHR_texture_transform")
    doc.uses("KHR_materials_clearcoat")
    i, j = gb.grid(16)
    spec = doc.texture(gb.rgba(0.5, 0.5, 0.5, 0.2 + 0.8 * ((i // 4 + j // 4) % 3) / 2), gb.NEAREST, gb.NEAREST,
                       name="specular")
    mr = doc.texture(gb.rgba(0.0, 0.25 + 0.5 * i / 15, 0.2 + 0.8 * j / 15), gb.NEAREST, gb.NEAREST, name="mr")
    coat = doc.texture(gb.rgba(0.3 + 0.7 * ((i // 4 + j // 4) % 2), 0.5, 0.5), gb.NEAREST, gb.NEAREST, name="coat")
    materials = (
        ("water", (0.1, 0.3, 0.5), 0.0, 0.35, {"KHR_materials_ior": {"ior": 1.33}}),
        ("tinted", (0.7, 0.2, 0.1), 0.0, 0.4, {"KHR_materials_ior": {"ior": 1.8},
                                                "KHR_materials_specular": {"specularFactor": 0.6,
                                                                           "specularColorFactor": [1.0, 0.6, 0.3]}}),
        ("mapped", (0.2, 0.6, 0.3), 0.0, 0.3, {"KHR_materials_ior": {"ior": 2.4}, "KHR_materials_specular": {
            "specularFactor": 0.9, "specularTexture": {"index": spec, "extensions": {"KHR_texture_transform": {
                "offset": [0.1, 0.2], "rotation": 0.4, "scale": [1.5, 1.5]}}}}}),
        ("glossy", (0.9, 0.9, 0.85), 0.0, 0.0, {}),
        ("coated", (0.6, 0.04, 0.03), 0.0, 0.6, {"KHR_materials_clearcoat": {
            "clearcoatFactor": 0.9, "clearcoatRoughnessFactor": 0.3, "clearcoatTexture": {"index": coat}}}))
    for k, (name, base, metallic, roughness, ext) in enumerate(materials):
        m = lit_material(doc, name, base, metallic, roughness, **({"extensions": ext} if ext else {}))
        doc.node(name=name, mesh=doc.mesh(doc.primitive(gb.uv_sphere(0.5, 20, 10), m), name),
                 translation=[-2.2 + 1.1 * k, 0.55, 0.0])
    half = lit_material(doc, "half_metal", (0.9, 0.7, 0.4), 0.5, 1.0, metallicRoughnessTexture={"index": mr})
    doc.node(name="box", mesh=doc.mesh(doc.primitive(gb.box(0.5, 0.5, 0.5), half), "box"),
             translation=[0.0, 0.5, 1.3], rotation=gb.quat_axis_angle((0, 1, 0), 25))


@entry("camera_orthographic.gltf", "an orthographic camera (xmag/ymag = the image's 4:3) looking down at a tilt")
def camera_orthographic(doc):
    stage(doc, camera=False)
    doc.camera((3.0, 4.0, 5.0), (0.0, 0.5, 0.0), ortho=(2.8, 2.1))
    a = lit_material(doc, "orange", (0.9, 0.5, 0.15))
    b = lit_material(doc, "blue", (0.2, 0.35, 0.9), roughness=0.3)
    doc.node(name="sphere", mesh=doc.mesh(doc.primitive(gb.uv_sphere(0.6, 18, 9), a), "sphere"),
             translation=[-0.8, 0.6, 0.0])
    doc.node(name="box", mesh=doc.mesh(doc.primitive(gb.box(0.5, 0.5, 0.5), b), "box"),
             translation=[0.9, 0.5, -0.3], rotation=gb.quat_axis_angle((0, 1, 0), 20))


@entry("camera_nested.gltf", "a perspective camera (aspectRatio given, no zfar: infinite) under a rotated, "
                             "scaled parent node")
def camera_nested(doc):
    stage(doc, camera=False)
    rig = doc.node(name="camera_rig", rotation=gb.quat_axis_angle((0, 1, 0), 35), scale=[2.0, 2.0, 2.0])
    # The child's own placement is in the rig's frame: the world eye is R·2·eye.
    cam = doc._list("cameras", {"type": "perspective", "perspective": {"yfov": math.radians(38), "aspectRatio": 1.5,
                                                                       "znear": 0.05}})
    eye_world = np.array([2.6, 2.4, 5.4])
    rot = gb.quat_matrix(gb.quat_axis_angle((0, 1, 0), 35))
    eye_local = rot.T @ eye_world / 2.0
    q_world = gb.look_at(eye_world, (0.0, 0.6, 0.0))
    q_local = gb.quat_mul([-c for c in gb.quat_axis_angle((0, 1, 0), 35)[:3]] + [gb.quat_axis_angle((0, 1, 0), 35)[3]],
                          q_world)
    doc.child(rig, name="camera", camera=cam, translation=[float(x) for x in eye_local], rotation=q_local)
    a = lit_material(doc, "mint", (0.4, 0.85, 0.6))
    doc.node(name="torus", mesh=doc.mesh(doc.primitive(gb.torus(0.7, 0.25), a), "torus"),
             translation=[0.0, 0.6, 0.0], rotation=gb.quat_axis_angle((1, 0, 0), 50))


@entry("lights_point.gltf", "point lights only: Blender's default 1000 W (54351 cd as its exporter writes it) "
                            "and a coloured 300 W one")
def lights_point(doc):
    stage(doc, key=False, fill=False)
    doc.light("point", gb.point_candela(1000.0), at=(2.5, 4.0, 2.0), name="point_1000W")
    doc.light("point", gb.point_candela(300.0), color=(1.0, 0.6, 0.3), at=(-3.0, 2.0, 2.5), name="point_300W")
    a = lit_material(doc, "white", (0.8, 0.8, 0.8), roughness=0.4)
    doc.node(name="sphere", mesh=doc.mesh(doc.primitive(gb.uv_sphere(0.7, 20, 10), a), "sphere"),
             translation=[0.0, 0.7, 0.0])


@entry("lights_spot.gltf", "spot lights only (outer cones 30° and 40°, inner cones inside: Blender's blend), "
                           "aimed by rotated nodes")
def lights_spot(doc):
    stage(doc, key=False, fill=False)
    doc.light("spot", gb.point_candela(1000.0), at=(0.5, 4.5, 1.5), toward=(0.0, 0.0, 0.0), spot=(20.0, 30.0),
              name="spot_a")
    doc.light("spot", gb.point_candela(600.0), color=(0.6, 0.8, 1.0), at=(-3.5, 3.0, 3.0), toward=(-0.3, 0.5, 0.0),
              spot=(30.0, 40.0), name="spot_b")
    a = lit_material(doc, "cream", (0.85, 0.8, 0.65), roughness=0.5)
    doc.node(name="box", mesh=doc.mesh(doc.primitive(gb.box(0.5, 0.5, 0.5), a), "box"),
             translation=[0.0, 0.5, 0.0], rotation=gb.quat_axis_angle((0, 1, 0), 20))


@entry("lights_directional.gltf", "directional lights only (3 W/m² and a coloured 1 W/m², in lux as Blender "
                                  "writes them)")
def lights_directional(doc):
    stage(doc, key=False, fill=False)
    doc.light("directional", gb.sun_lux(3.0), at=(2.0, 5.0, 3.0), toward=(0.0, 0.0, 0.0), name="sun_3")
    doc.light("directional", gb.sun_lux(1.0), color=(0.5, 0.7, 1.0), at=(-4.0, 2.0, 2.0), toward=(0.0, 0.3, 0.0),
              name="sun_1")
    a = lit_material(doc, "peach", (0.95, 0.6, 0.45), roughness=0.35)
    doc.node(name="torus", mesh=doc.mesh(doc.primitive(gb.torus(0.7, 0.25), a), "torus"),
             translation=[0.0, 0.6, 0.0], rotation=gb.quat_axis_angle((1, 0, 0), 70))


@entry("skin.gltf", "a skinned tube (two joints, the second bent 50° in the file's pose; JOINTS_0 ubyte, "
                    "WEIGHTS_0 float)")
def skin(doc):
    stage(doc)
    mat = lit_material(doc, "skin", (0.9, 0.55, 0.45), roughness=0.55)
    tube = gb.cylinder(0.3, 2.0, 12, 8)
    y = tube.positions[:, 1]
    w1 = np.clip((y - 0.6) / 0.8, 0.0, 1.0)
    weights = np.stack([1 - w1, w1, np.zeros_like(w1), np.zeros_like(w1)], axis=1)
    joints = np.zeros((len(y), 4), np.uint8)
    joints[:, 1] = 1
    # The skinned mesh's own node has no transform (glTF ignores it for skinned meshes); the
    # joints place the tube.
    root = doc.node(name="armature", translation=[-0.3, 0.0, 0.0])
    j0 = doc.child(root, name="joint0", translation=[0.0, 0.0, 0.0])
    j1 = doc.child(j0, name="joint1", translation=[0.0, 1.0, 0.0], rotation=gb.quat_axis_angle((0, 0, 1), -50))
    # Inverse bind matrices: the joints' world inverses at bind time (joint1 unrotated at y = 1).
    ibm = np.stack([np.eye(4), np.linalg.inv(gb.trs_matrix((0, 1, 0)))]).astype(np.float32)
    inv = doc.accessor(np.stack([gb.column_major(m) for m in ibm]), target=None)
    doc.d.setdefault("skins", []).append({"joints": [j0, j1], "inverseBindMatrices": inv, "skeleton": j0})
    prim = doc.primitive(tube, mat, extra={"JOINTS_0": doc.accessor(joints, gb.UBYTE),
                                           "WEIGHTS_0": doc.accessor(weights)})
    doc.node(name="skinned_tube", mesh=doc.mesh(prim, "tube"), skin=0)


@entry("morph.gltf", "morph targets (POSITION and NORMAL deltas) at the mesh's default weights [0.6, 0.3]")
def morph(doc):
    stage(doc)
    mat = lit_material(doc, "aqua", (0.3, 0.75, 0.85), roughness=0.4)
    s = gb.uv_sphere(0.7, 20, 10)
    p = s.positions.astype(float)
    bulge = gb.uv_sphere(0.7, 20, 10, squash=lambda d: 1 + 0.45 * max(d[0], 0) ** 2)
    twist = gb.uv_sphere(0.7, 20, 10, squash=lambda d: 1 - 0.3 * d[1] ** 2)
    targets = []
    for t in (bulge, twist):
        targets.append({"POSITION": doc.accessor(t.positions - p, bounds=True),
                        "NORMAL": doc.accessor(t.normals - s.normals)})
    prim = doc.primitive(s, mat)
    prim["targets"] = targets
    doc.node(name="morphed", mesh=doc.mesh(prim, "morphed", weights=[0.6, 0.3]), translation=[0.0, 0.8, 0.0])


@entry("sparse.gltf", "sparse accessors: positions as a base accessor plus sparse replacements (two vertices "
                      "of a box pulled out), and a view-less sparse morph target (flat-shaded)")
def sparse(doc):
    stage(doc)
    mat = lit_material(doc, "steel", (0.55, 0.6, 0.7), metallic=0.3, roughness=0.45)
    b = gb.box(0.5, 0.5, 0.5)
    moved = np.array([8, 9], np.uint16)          # two corners of the +y face's first quad
    values = b.positions[moved].copy()
    values[:, 1] += 0.35
    sparse_desc = {"count": 2, "indices": {"bufferView": doc.view(moved.tobytes()), "componentType": gb.USHORT},
                   "values": {"bufferView": doc.view(values.astype(np.float32).tobytes())}}
    pos = b.positions.copy()
    pos[moved] = values
    acc = doc.accessor(b.positions, bounds=False, sparse=sparse_desc)
    doc.d["accessors"][acc]["min"] = [float(x) for x in pos.min(axis=0)]
    doc.d["accessors"][acc]["max"] = [float(x) for x in pos.max(axis=0)]
    # The geometry the sparse values make, flat-shaded: the pulled face is no longer a plane.
    prim = {"attributes": {"POSITION": acc, "TEXCOORD_0": doc.accessor(b.uvs)},
            "indices": doc.accessor(b.indices, gb.USHORT, target=gb.ELEMENT_ARRAY_BUFFER), "material": mat}
    doc.node(name="pulled_box", mesh=doc.mesh(prim, "pulled_box"), translation=[-0.9, 0.5, 0.0],
             rotation=gb.quat_axis_angle((0, 1, 0), 25))
    s = gb.uv_sphere(0.55, 16, 8)
    top = np.nonzero(s.positions[:, 1] > 0.3)[0].astype(np.uint16)
    delta = np.zeros((len(top), 3), np.float32)
    delta[:, 1] = 0.3
    target = doc.accessor(np.zeros((len(s.positions), 3), np.float32), bounds=False, sparse={
        "count": int(len(top)), "indices": {"bufferView": doc.view(top.tobytes()), "componentType": gb.USHORT},
        "values": {"bufferView": doc.view(delta.tobytes())}})
    acc_t = doc.d["accessors"][target]
    acc_t.pop("bufferView", None)                 # view-less: zeros plus the sparse values
    acc_t["min"], acc_t["max"] = [0.0, 0.0, 0.0], [0.0, 0.3, 0.0]
    # Flat-shaded (no NORMAL): glTF keeps a smooth mesh's normals when a target moves only its
    # positions, while Blender's custom normals turn with the moved faces (docs/gltf.md); without
    # normals both readers shade the moved faces by their own planes.
    prim2 = doc.primitive(s, mat, normals=False)
    prim2["targets"] = [{"POSITION": target}]
    doc.node(name="stretched_sphere", mesh=doc.mesh(prim2, "stretched", weights=[1.0]), translation=[0.9, 0.6, 0.0])


# ----------------------------------------------------------------------------- cut-outs and vertex colours

def leaf_alpha(n=16):
    """A leaf's coverage: an ellipse with a notch, alpha 1 inside, fading to 0 across its edge
    (so the cutoff decides), rgb a green that varies."""
    i, j = gb.grid(n)
    x, y = (i + 0.5) / n * 2 - 1, (j + 0.5) / n * 2 - 1
    r = np.sqrt((x / 0.9) ** 2 + (y / 0.6) ** 2)
    alpha = np.clip((1.1 - r) * 2.5, 0.0, 1.0) * np.where((np.abs(y) < 0.12) & (x > 0.3), 0.2, 1.0)
    return gb.rgba(0.2 + 0.3 * (i / n), 0.5 + 0.4 * (j / n), 0.15, alpha)


@entry("mask_leaf.gltf", "alphaMode MASK (alphaCutoff 0.45) on a base colour texture's alpha × baseColorFactor's "
                        "0.9, double-sided, in front of a sphere, its shadow cut out too")
def mask_leaf(doc):
    stage(doc)
    leaf = doc.texture(leaf_alpha(16), gb.NEAREST, gb.NEAREST, name="leaf")
    cut = doc.material("leaf", base=(1, 1, 1, 0.9), roughness=0.6, baseColorTexture={"index": leaf},
                       alphaMode="MASK", alphaCutoff=0.45, doubleSided=True)
    plane = gb.plane(1.8)
    doc.node(name="leaf_a", mesh=doc.mesh(doc.primitive(plane, cut), "leaf"), translation=[-0.6, 1.0, 0.3],
             rotation=gb.quat_axis_angle((1, 0, 0.2), 70))
    doc.node(name="sphere_behind", mesh=doc.mesh(doc.primitive(gb.uv_sphere(0.5, 16, 8),
                                                               lit_material(doc, "red", (0.8, 0.2, 0.15))), "sphere"),
             translation=[-0.4, 0.5, -0.8])
    doc.node(name="box", mesh=doc.mesh(doc.primitive(gb.box(0.4, 0.4, 0.4), lit_material(doc, "blue", (0.2, 0.3, 0.8))),
                                       "box"), translation=[1.4, 0.4, 0.0])


# Blender's importer keeps COLOR_0 as an 8-bit sRGB-encoded colour attribute (BYTE_COLOR;
# docs/gltf.md), so a linear value survives its reading only where it is an 8-bit sRGB code's
# value. The colours here are such values: decode(k/255) for the float and 16-bit files, and for
# the 8-bit normalized file the bytes b whose b/255 lies within 1e-4 (relative) of one (0, 39,
# 136, 144, 192, 235, 246, 255). Any other colour would be a difference of up to 3.7e-3 that the
# second opinion would have to allow, and that would hide a wrong reading as small as it.
SRGB_BYTES = (0, 39, 136, 144, 192, 235, 246, 255)


def srgb_code_value(k):
    """The linear value of the 8-bit sRGB code k (IEC 61966-2-1)."""
    s = k / 255.0
    return s / 12.92 if s <= 0.04045 else ((s + 0.055) / 1.055) ** 2.4


def corner_palette(count, seed, codes):
    """`count` RGB colours drawn from `codes` (0–255 values), the same on every run."""
    rng = np.random.default_rng(seed)
    return np.asarray(codes)[rng.integers(0, len(codes), size=(count, 3))]


@entry("vertex_colors.gltf", "COLOR_0 multiplying the base colour: VEC3 float on a rotated box (factor only), VEC4 "
                             "normalized ubyte on a textured sphere whose material a COLOR_0-less box shares, VEC3 "
                             "normalized ushort on a metallic 0.6 box")
def vertex_colors(doc):
    stage(doc)
    codes = (0, 40, 90, 140, 180, 215, 240, 255)          # sRGB codes: their linear values are exact in Blender
    box = gb.box(0.45, 0.45, 0.45)
    rgb = np.vectorize(srgb_code_value)(corner_palette(len(box.positions), 1, codes))
    plain = lit_material(doc, "tinted", (0.9, 0.85, 0.8), roughness=0.5)
    colour = {"COLOR_0": doc.accessor(rgb, gb.FLOAT)}
    doc.node(name="box_float_rgb", mesh=doc.mesh(doc.primitive(box, plain, extra=colour), "box_float"),
             translation=[-1.5, 0.55, 0.3], rotation=gb.quat_axis_angle((0.3, 1, 0.2), 35))
    sphere = gb.uv_sphere(0.6, 16, 8)
    picked = corner_palette(len(sphere.positions), 2, SRGB_BYTES)
    alpha = corner_palette(len(sphere.positions), 3, SRGB_BYTES)[:, :1]
    bytes_rgba = np.concatenate([picked, alpha], axis=1).astype(np.uint8)
    textured = lit_material(doc, "checker_tinted", (1.0, 1.0, 1.0), roughness=0.55,
                            baseColorTexture={"index": doc.texture(gb.checker(16), gb.NEAREST, gb.NEAREST,
                                                                   name="checker")})
    colour = {"COLOR_0": doc.accessor(bytes_rgba, gb.UBYTE, normalized=True)}
    doc.node(name="sphere_ubyte_rgba", mesh=doc.mesh(doc.primitive(sphere, textured, extra=colour), "sphere"),
             translation=[0.0, 0.7, 0.0])
    doc.node(name="box_without_color", mesh=doc.mesh(doc.primitive(gb.box(0.3, 0.3, 0.3), textured), "small_box"),
             translation=[0.2, 0.3, 1.3], rotation=gb.quat_axis_angle((0, 1, 0), 20))
    metal_box = gb.box(0.4, 0.4, 0.4)
    linear = np.vectorize(srgb_code_value)(corner_palette(len(metal_box.positions), 4, codes))
    shorts = np.round(linear * 65535).astype(np.uint16)
    metal = lit_material(doc, "metal_tinted", (0.95, 0.9, 0.85), metallic=0.6, roughness=0.4)
    colour = {"COLOR_0": doc.accessor(shorts, gb.USHORT, normalized=True)}
    doc.node(name="box_ushort_rgb", mesh=doc.mesh(doc.primitive(metal_box, metal, extra=colour), "box_ushort"),
             translation=[1.5, 0.5, 0.2], rotation=gb.quat_axis_angle((0, 1, 0), -30))


# ----------------------------------------------------------------------------- Blender's own exporter

def mikktspace_tangents(shape):
    """Per-vertex MikkTSpace tangents [x, y, z, w] of a shape as Blender computes them
    (Mesh.calc_tangents), in the shape's own frame; w is Blender's bitangent sign, which is
    glTF's: B = w·(N × T) points up the picture (Blender's v up, glTF's v down)."""
    import bpy
    mesh = bpy.data.meshes.new("tangents")
    tris = shape.indices.reshape(-1, 3)
    mesh.from_pydata([tuple(map(float, p)) for p in shape.positions], [], [tuple(map(int, t)) for t in tris])
    layer = mesh.uv_layers.new(name="UVMap")
    loops = np.array([l.vertex_index for l in mesh.loops])
    uv = shape.uvs[loops].astype(float)
    uv[:, 1] = 1.0 - uv[:, 1]
    layer.data.foreach_set("uv", uv.ravel())
    mesh.shade_smooth()           # from_pydata's faces are flat, and flat faces would hide the normals
    mesh.normals_split_custom_set_from_vertices([tuple(map(float, n)) for n in shape.normals])
    mesh.calc_tangents(uvmap="UVMap")
    out = np.zeros((len(shape.positions), 4), np.float32)
    for loop in mesh.loops:
        out[loop.vertex_index, :3] = loop.tangent
        out[loop.vertex_index, 3] = loop.bitangent_sign
    bpy.data.meshes.remove(mesh)
    # A vertex no triangle uses (a pole's spare copy) has no tangent; glTF wants a unit one.
    for k in np.nonzero(np.linalg.norm(out[:, :3], axis=1) < 0.5)[0]:
        n = shape.normals[k].astype(float)
        t = np.cross(n, (0.0, 0.0, 1.0) if abs(n[2]) < 0.9 else (1.0, 0.0, 0.0))
        out[k] = list(t / np.linalg.norm(t)) + [1.0]
    return out


def blender_material(name, base, metallic, roughness, image=None, uv_map=None, mapping=None):
    import bpy
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = tuple(base) + (1.0,)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.distribution = "GGX"        # facet's GGX: no multiple-scattering energy
    if image is not None:
        nodes, links = m.node_tree.nodes, m.node_tree.links
        tex = nodes.new("ShaderNodeTexImage")
        tex.image, tex.interpolation = image, "Closest"
        links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
        vector = tex.inputs["Vector"]
        if mapping is not None:
            mp = nodes.new("ShaderNodeMapping")
            mp.vector_type = "POINT"
            mp.inputs["Location"].default_value = mapping[0] + (0.0,)
            mp.inputs["Rotation"].default_value = (0.0, 0.0, mapping[1])
            mp.inputs["Scale"].default_value = mapping[2] + (1.0,)
            links.new(mp.outputs["Vector"], vector)
            vector = mp.inputs["Vector"]
        if uv_map is not None:
            uv = nodes.new("ShaderNodeUVMap")
            uv.uv_map = uv_map
            links.new(uv.outputs["UV"], vector)
    return m


def blender_object(name, mesh_fn, material, location, rotation=(0, 0, 0), scale=(1, 1, 1), smooth=True):
    import bpy
    mesh_fn()
    obj = bpy.context.active_object
    obj.name = name
    if smooth:
        bpy.ops.object.shade_smooth()
    obj.data.materials.append(material)
    obj.location, obj.rotation_euler, obj.scale = location, rotation, scale
    return obj


def blender_lights_scene():
    """Blender's default lights, as the acceptance of issue 27 asks: the default 1000 W point
    light, a spot and a sun, all of radius 0 (facet's lights are points and parallel beams) and
    the spot's blend 0 (facet's cone is hard, as glTF's inner = outer cone); objects rotated,
    scaled and mirrored, Principled BSDF materials whose facet mapping is measured in docs/gltf.md;
    a camera; the Film's exposure left at 0."""
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = 96, 72
    # Metallic 1 where glTF's BRDF is Cycles' Principled BSDF (Schlick's Fresnel is Cycles' F82-tint
    # one with a white tint, both Smith G terms height-correlated), one dielectric (Metallic 0)
    # where Cycles layers its diffuse under the specular by albedo and glTF by 1 − max(F): the
    # test holds the two to different tolerances (docs/gltf.md).
    floor_m = blender_material("floor_metal", (0.75, 0.75, 0.72), 1.0, 0.7)
    red = blender_material("red_dielectric", (0.8, 0.15, 0.1), 0.0, 0.45)
    metal = blender_material("brass_metal", (0.9, 0.7, 0.35), 1.0, 0.4)
    blue = blender_material("blue_metal", (0.25, 0.4, 0.9), 1.0, 0.55)
    blender_object("floor", lambda: bpy.ops.mesh.primitive_plane_add(size=10), floor_m, (0, 0, 0), smooth=False)
    blender_object("sphere_rotated", lambda: bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12,
                                                                                  radius=0.7),
                   red, (-1.4, 0.2, 0.7), rotation=(0.4, 0.3, 0.9))
    blender_object("cube_scaled", lambda: bpy.ops.mesh.primitive_cube_add(size=1.0), metal, (0.6, -0.5, 0.5),
                   rotation=(0.0, 0.0, 0.6), scale=(1.4, 0.6, 1.0), smooth=False)
    blender_object("cone_mirrored", lambda: bpy.ops.mesh.primitive_cone_add(vertices=16, radius1=0.5, depth=1.2),
                   blue, (1.9, 0.9, 0.6), rotation=(0.3, 0.0, 0.2), scale=(-1.0, 1.0, 1.0), smooth=False)
    point = bpy.data.lights.new("Point", "POINT")        # Blender's default: 1000 W
    point.energy, point.shadow_soft_size = 1000.0, 0.0
    spot = bpy.data.lights.new("Spot", "SPOT")
    spot.energy, spot.shadow_soft_size, spot.spot_size, spot.spot_blend = 800.0, 0.0, math.radians(50), 0.0
    sun = bpy.data.lights.new("Sun", "SUN")
    sun.energy, sun.angle, sun.color = 2.0, 0.0, (1.0, 0.95, 0.85)
    import mathutils
    for light, location, target in ((point, (4.07625, 1.00545, 5.90386), None),     # the startup file's light
                                    (spot, (-3.0, -2.5, 4.0), (-1.0, 0.0, 0.0)),
                                    (sun, (0.0, -6.0, 8.0), (0.5, 0.5, 0.0))):
        obj = bpy.data.objects.new(light.name, light)
        scene.collection.objects.link(obj)
        obj.location = location
        if target is not None:
            obj.rotation_euler = (mathutils.Vector(target) - obj.location).to_track_quat("-Z", "Y").to_euler()
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(cam)
    cam.location = (0.5, -7.5, 4.2)
    cam.rotation_euler = (mathutils.Vector((0.2, 0.0, 0.5)) - cam.location).to_track_quat("-Z", "Y").to_euler()
    cam.data.lens = 40.0
    scene.camera = cam
    scene.world = None
    bpy.context.view_layer.update()


def point_sun_camera(scene, point_at, sun_energy, sun_rotation, camera_at):
    """A 1000 W point light and a sun of `sun_energy` W/m², both of radius 0, and a camera aimed at
    (0, 0, 0.5); no World (a glTF file has no environment)."""
    import bpy
    import mathutils
    light = bpy.data.lights.new("Point", "POINT")
    light.energy, light.shadow_soft_size = 1000.0, 0.0
    obj = bpy.data.objects.new("Point", light)
    scene.collection.objects.link(obj)
    obj.location = point_at
    sun = bpy.data.lights.new("Sun", "SUN")
    sun.energy, sun.angle = sun_energy, 0.0
    obj = bpy.data.objects.new("Sun", sun)
    scene.collection.objects.link(obj)
    obj.rotation_euler = sun_rotation
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(cam)
    cam.location = camera_at
    cam.rotation_euler = (mathutils.Vector((0.0, 0.0, 0.5)) - cam.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam
    scene.world = None


def blender_textured_scene(folder):
    """A second exporter-written file: an image through a Mapping node (KHR_texture_transform) on
    a second UV map (TEXCOORD_1), on a mirrored and a rotated object; Closest interpolation
    (glTF's NEAREST)."""
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    img = bpy.data.images.new("grid", 16, 16, alpha=True)
    img.pixels.foreach_set((gb.gradient(16)[::-1].astype(np.float32) / 255.0).ravel())
    img.filepath_raw = os.path.join(folder, "grid.png")
    img.file_format = "PNG"
    img.save()
    mat = blender_material("mapped", (1, 1, 1), 0.0, 0.5, image=img, uv_map="second",
                           mapping=((0.25, -0.1), 0.5, (1.5, 2.0)))
    floor = blender_material("floor", (0.5, 0.5, 0.5), 0.0, 0.7)
    blender_object("floor", lambda: bpy.ops.mesh.primitive_plane_add(size=10), floor, (0, 0, 0), smooth=False)
    for name, location, rotation, scale in (("cube_mirrored", (-1.0, 0.0, 0.6), (0.0, 0.0, 0.5), (-1.0, 1.0, 1.0)),
                                            ("sphere_rotated", (1.1, 0.2, 0.8), (0.7, 0.2, 0.0), (1.0, 1.0, 1.0))):
        if name.startswith("cube"):
            blender_object(name, lambda: bpy.ops.mesh.primitive_cube_add(size=1.1), mat, location, rotation, scale,
                           smooth=False)
        else:
            blender_object(name, lambda: bpy.ops.mesh.primitive_uv_sphere_add(segments=20, ring_count=10,
                                                                              radius=0.7), mat, location, rotation,
                           scale)
        obj = bpy.context.active_object
        second = obj.data.uv_layers.new(name="second")
        first = obj.data.uv_layers[0]
        for k, loop in enumerate(second.data):
            u, v = first.data[k].uv
            loop.uv = (v * 1.3 + 0.1, 1.0 - u)
    point_sun_camera(scene, (3.0, -3.0, 5.0), 1.5, (0.5, -0.4, 0.3), (0.3, -6.5, 3.5))


def blender_principled_scene(folder):
    """A third exporter-written file (issue 29, acceptance 3): Principled BSDFs using the inputs
    glTF's material extensions carry, as Blender's exporter writes them: IOR (KHR_materials_ior),
    Specular IOR Level and Tint (KHR_materials_specular), Sheen Weight, Tint and Roughness
    (KHR_materials_sheen), Coat Weight and Roughness and a Coat Normal through a Normal Map node
    (KHR_materials_clearcoat with its clearcoatNormalTexture), Emission Color and
    a Strength above 1 (KHR_materials_emissive_strength), images on Sheen Tint and Specular Tint
    (sheenColorTexture, specularColorTexture), an image's alpha on Sheen Roughness
    (sheenRoughnessTexture, its A), Anisotropic and its Rotation (KHR_materials_anisotropy; the
    sphere is rotated and mirrored, so its direction turns from its own UV tangents, which facet
    reads as the README's TBN with the node's mirror in its handedness, not from any fixed axis)."""
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene

    def principled(name, base, metallic, roughness, **inputs):
        m = blender_material(name, base, metallic, roughness)
        bsdf = m.node_tree.nodes["Principled BSDF"]
        for key, value in inputs.items():
            bsdf.inputs[key].default_value = tuple(value) + (1.0,) if isinstance(value, tuple) else value
        return m

    materials = (
        principled("velvet_coat", (0.3, 0.05, 0.15), 0.0, 0.7, **{
            "Sheen Weight": 1.0, "Sheen Tint": (0.9, 0.6, 0.7), "Sheen Roughness": 0.4,
            "Coat Weight": 0.6, "Coat Roughness": 0.3}),
        principled("tinted_specular", (0.1, 0.3, 0.6), 0.0, 0.4, **{
            "IOR": 1.7, "Specular IOR Level": 0.7, "Specular Tint": (1.0, 0.7, 0.4)}),
        principled("emissive_metal", (0.9, 0.6, 0.3), 1.0, 0.35, **{
            "Emission Color": (1.0, 0.4, 0.1), "Emission Strength": 2.0}),
        principled("brushed", (0.8, 0.8, 0.85), 1.0, 0.4, **{"Anisotropic": 0.5, "Anisotropic Rotation": 0.25}))
    def image(name, pixels, non_color=False):
        """A Blender image of `pixels` (RGBA in [0, 1], rows from the bottom), saved in `folder`."""
        img = bpy.data.images.new(name, pixels.shape[1], pixels.shape[0], alpha=True)
        img.pixels.foreach_set(pixels.astype(np.float32).ravel())
        img.filepath_raw = os.path.join(folder, name + ".png")
        img.file_format = "PNG"
        img.save()
        if non_color:
            img.colorspace_settings.name = "Non-Color"
        return img

    def image_output(material, img, output="Color"):
        """An Image Texture node of `img` (Linear) in `material`'s tree: its tree and its `output`."""
        tree = material.node_tree
        tex = tree.nodes.new("ShaderNodeTexImage")
        tex.image, tex.interpolation = img, "Linear"
        return tree, tex.outputs[output]

    # The coat's own normal map (Non-Color image → Normal Map node, strength 0.8 → Coat Normal),
    # which Blender's exporter writes as clearcoatNormalTexture with scale 0.8.
    bumps = image("coat_bumps", gb.normal_bumps(32)[::-1].astype(np.float32) / 255.0, non_color=True)
    tree, color = image_output(materials[0], bumps)
    normal_map = tree.nodes.new("ShaderNodeNormalMap")
    normal_map.inputs["Strength"].default_value = 0.8
    tree.links.new(color, normal_map.inputs["Color"])
    tree.links.new(normal_map.outputs["Normal"], tree.nodes["Principled BSDF"].inputs["Coat Normal"])
    # Colour images (sRGB) on Sheen Tint and Specular Tint, which Blender's exporter writes as
    # sheenColorTexture and specularColorTexture.
    side = 16
    tints = image("tints", np.array([[(0.3 + 0.7 * i / (side - 1), 0.2 + 0.8 * j / (side - 1), 0.6, 1.0)
                                      for i in range(side)] for j in range(side)]))
    for material, socket in ((materials[0], "Sheen Tint"), (materials[1], "Specular Tint")):
        tree, color = image_output(material, tints)
        tree.links.new(color, tree.nodes["Principled BSDF"].inputs[socket])
    # An image's alpha on Sheen Roughness (0.15 to 0.85 across it, so the sheen's albedo fit is
    # summed at the pixel in every piece of r), which Blender's exporter writes into the alpha of
    # sheenRoughnessTexture.
    sheen_rough = image("sheen_rough", np.array([[(0.5, 0.5, 0.5, 0.15 + 0.7 * (i + j) / (2 * side - 2))
                                                  for i in range(side)] for j in range(side)]), non_color=True)
    tree, alpha = image_output(materials[0], sheen_rough, "Alpha")
    tree.links.new(alpha, tree.nodes["Principled BSDF"].inputs["Sheen Roughness"])
    floor = blender_material("floor", (0.5, 0.5, 0.5), 0.0, 0.7)
    blender_object("floor", lambda: bpy.ops.mesh.primitive_plane_add(size=10), floor, (0, 0, 0), smooth=False)
    for k, m in enumerate(materials):
        blender_object(m.name, lambda: bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12, radius=0.6),
                       m, (-2.1 + 1.4 * k, 0.0, 0.6), rotation=(0.3 * k, 0.2, 0.5 * k),
                       scale=(-1, 1, 1) if m.name == "brushed" else (1, 1, 1))
    point_sun_camera(scene, (2.0, -3.5, 4.5), 2.0, (0.6, -0.3, 0.2), (0.0, -7.0, 3.2))


def export_blender(path, **options):
    """Blender's exporter as a user runs it (lights in its "Standard" units, Y up, cameras); a
    .gltf is written with its buffer and images beside it, then made one file (data URIs)."""
    import bpy
    separate = os.path.join(os.path.dirname(os.path.dirname(path)), "blender", "separate", os.path.basename(path))
    settings = dict(export_format="GLB" if path.endswith(".glb") else "GLTF_SEPARATE", export_lights=True,
                    export_cameras=True, export_apply=True, export_yup=True, export_texcoords=True,
                    export_normals=True, export_materials="EXPORT", export_import_convert_lighting_mode="SPEC")
    settings.update(options)
    os.makedirs(os.path.dirname(separate), exist_ok=True)
    result = bpy.ops.export_scene.gltf(filepath=path if path.endswith(".glb") else separate, **settings)
    if result != {"FINISHED"}:
        raise SystemExit(f"FAIL: Blender's glTF exporter returned {result} for {path}")
    if not path.endswith(".glb"):
        inline(separate, path)


def inline(src, dst):
    """`src` with its buffers and images as data URIs, written to `dst`."""
    import base64
    doc = json.load(open(src))
    folder = os.path.dirname(src)
    for key, mime in (("buffers", "application/octet-stream"), ("images", None)):
        for item in doc.get(key, []):
            data = open(os.path.join(folder, item["uri"]), "rb").read()
            item["uri"] = f"data:{mime or item.get('mimeType') or 'image/png'};base64," + base64.b64encode(data).decode()
            item.pop("mimeType", None)
    with open(dst, "w") as f:
        json.dump(doc, f)


def write_blender_files(out):
    import bpy
    blend_folder = os.path.join(out, "blender")
    os.makedirs(blend_folder, exist_ok=True)
    blender_lights_scene()
    bpy.context.scene.name = "blender_lights"      # the glTF scene's name, which facet's reports show
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(blend_folder, "lights.blend"))
    export_blender(os.path.join(out, "corpus", "blender_lights.glb"))
    blender_textured_scene(blend_folder)
    bpy.context.scene.name = "blender_textured"
    export_blender(os.path.join(out, "corpus", "blender_textured.gltf"))
    blender_principled_scene(blend_folder)
    bpy.context.scene.name = "blender_principled"
    export_blender(os.path.join(out, "corpus", "blender_principled.glb"))


CORPUS.append(("blender_lights.glb", "written by Blender's glTF exporter (Y-up conversion, applied transforms): "
                                     "rotated, non-uniformly scaled and mirrored objects, the default 1000 W point "
                                     "light, a 800 W spot (blend 0) and a 2 W/m² sun, a camera; the Cycles "
                                     "comparison's scene", None))
CORPUS.append(("blender_textured.gltf", "written by Blender's glTF exporter: an image through a Mapping node on "
                                        "a second UV map (KHR_texture_transform, TEXCOORD_1), mirrored and rotated "
                                        "objects, a point light and a sun", None))
CORPUS.append(("blender_principled.glb", "written by Blender's glTF exporter from Principled BSDFs: IOR, Specular IOR "
                                         "Level and Tint (an image), Sheen (its Tint an image), Coat with its own Coat "
                                         "Normal map, Emission Strength 2, Anisotropic on a rotated, mirrored "
                                         "sphere: KHR_materials_ior, _specular (specularColorTexture), _sheen "
                                         "(sheenColorTexture, sheenRoughnessTexture), _clearcoat "
                                         "(clearcoatNormalTexture), "
                                         "_emissive_strength, _anisotropy", None))


# ----------------------------------------------------------------------------- wrong twins

def adjugate_twin(src, dst):
    """The Box-like file with each NORMAL pre-turned so that facet's correct transform (the
    inverse transpose A⁻ᵀ of the node's world matrix A) gives what the old adjugate bug gave
    for the original, normalize(A⁻¹·n) (a rotation turned the wrong way round):
    n' = Aᵀ·A⁻¹·n. The geometry and windings are the original's."""
    doc = json.load(open(src))
    rot = np.array(gb.quat_matrix(doc["nodes"][0]["rotation"]))   # root rotation; the child is the identity
    turn = rot.T @ np.linalg.inv(rot)
    rewrite_accessor(doc, doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"],
                     lambda n: (turn @ n.T).T / np.linalg.norm(n, axis=1, keepdims=True))
    with open(dst, "w") as f:
        json.dump(doc, f, indent=1)


def swapped_uv_twin(src, dst):
    """uv_sets.gltf with TEXCOORD_0 and TEXCOORD_1 exchanged in every primitive that has both."""
    doc = json.load(open(src))
    for mesh in doc["meshes"]:
        for prim in mesh["primitives"]:
            a = prim["attributes"]
            if "TEXCOORD_1" in a:
                a["TEXCOORD_0"], a["TEXCOORD_1"] = a["TEXCOORD_1"], a["TEXCOORD_0"]
    with open(dst, "w") as f:
        json.dump(doc, f, indent=1)


def rewrite_accessor(doc, index, fn):
    """Replaces a FLOAT VEC3 accessor's data (in the data-URI buffer) by fn(values)."""
    import base64
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    uri = doc["buffers"][0]["uri"]
    head, b64 = uri.split(",", 1)
    data = bytearray(base64.b64decode(b64))
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    values = np.frombuffer(bytes(data[start:start + 12 * acc["count"]]), np.float32).reshape(-1, 3).astype(float)
    data[start:start + 12 * acc["count"]] = np.asarray(fn(values), np.float32).tobytes()
    doc["buffers"][0]["uri"] = head + "," + base64.b64encode(bytes(data)).decode()


def no_colour_twin(src, dst):
    """vertex_colors.gltf with COLOR_0 dropped from every primitive (a reader that ignores it)."""
    doc = json.load(open(src))
    for mesh in doc["meshes"]:
        for prim in mesh["primitives"]:
            prim["attributes"].pop("COLOR_0", None)
    with open(dst, "w") as f:
        json.dump(doc, f, indent=1)


def opaque_twin(src, dst):
    """mask_leaf.gltf with its cut-out dropped: every material's alphaMode OPAQUE."""
    doc = json.load(open(src))
    for m in doc["materials"]:
        m.pop("alphaMode", None)
        m.pop("alphaCutoff", None)
    with open(dst, "w") as f:
        json.dump(doc, f, indent=1)


VARIANTS += [
    ("box_khronos_adjugate.gltf", "box_khronos.gltf", "normals as the adjugate bug turned them (n' = AᵀA⁻¹n)",
     "normals", adjugate_twin),
    ("uv_sets_swapped.gltf", "uv_sets.gltf", "TEXCOORD_0 and TEXCOORD_1 exchanged", "image", swapped_uv_twin),
    ("mask_leaf_opaque.gltf", "mask_leaf.gltf", "alphaMode MASK dropped (drawn opaque)", "coverage", opaque_twin),
    ("vertex_colors_dropped.gltf", "vertex_colors.gltf", "COLOR_0 dropped", "image", no_colour_twin),
]


# ----------------------------------------------------------------------------- main

def main():
    out = os.path.abspath(sys.argv[1])
    corpus_dir, variant_dir = os.path.join(out, "corpus"), os.path.join(out, "variants")
    for d in (corpus_dir, variant_dir):
        os.makedirs(d, exist_ok=True)
        for f in os.listdir(d):
            os.remove(os.path.join(d, f))
    for name, _, fn in CORPUS:
        if fn is None:
            continue
        doc = gb.Document()
        fn(doc)
        doc.save(os.path.join(corpus_dir, name))
    write_blender_files(out)
    for variant, original, _, _, make in VARIANTS:
        make(os.path.join(corpus_dir, original), os.path.join(variant_dir, variant))
    index = {"corpus": [{"file": n, "covers": c} for n, c, _ in CORPUS],
             "variants": [{"file": v, "original": o, "wrong": w, "must_fail": f} for v, o, w, f, _ in VARIANTS]}
    with open(os.path.join(out, "corpus.json"), "w") as f:
        json.dump(index, f, indent=1)
    missing = [n for n, _, _ in CORPUS if not os.path.isfile(os.path.join(corpus_dir, n))]
    if missing:
        raise SystemExit(f"FAIL: not written: {missing}")
    print(f"wrote {len(CORPUS)} corpus files and {len(VARIANTS)} variants to {out}")
    for n, c, _ in CORPUS:
        print(f"  {n:28s} {os.path.getsize(os.path.join(corpus_dir, n)):8d} bytes  {c}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
