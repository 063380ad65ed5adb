"""What Blender 4.5's glTF importer (io_scene_gltf2, pip bpy) makes of a glTF file, measured on
the corpus: the conventions docs/gltf.md states, each checked so that the page cannot go stale.

    python gltf_blender_conventions.py --corpus FOLDER --work DIR

(FOLDER: what gltf_corpus.py wrote.) The importer runs alone here (the facet add-on is not
enabled: its hook would add glTF's default material) with its default options. Each line
printed is one convention with the value measured; the script exits 1 when one does not hold.
Sources read for them (bpy/4.5/scripts/addons_core/io_scene_gltf2/): blender/imp/light.py,
camera.py, mesh.py, texture.py, pbrMetallicRoughness.py, material_utils.py,
blender/com/conversion.py; blender/exp/lights.py for the other direction.
"""
import argparse
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gltf_build as gb  # noqa: E402

FAILURES = []


def check(ok, what, measured):
    print(f"{'ok  ' if ok else 'FAIL'} {what}: {measured}")
    if not ok:
        FAILURES.append(what)


def load(path):
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    result = bpy.ops.import_scene.gltf(filepath=path)
    if result != {"FINISHED"}:
        raise SystemExit(f"FAIL: the importer returned {result} for {path}")
    bpy.context.view_layer.update()
    return json.load(open(path)) if path.endswith(".gltf") else None


def lights(corpus):
    import bpy
    for name in ("lights_point.gltf", "lights_spot.gltf", "lights_directional.gltf"):
        doc = load(os.path.join(corpus, name))
        for gl in doc["extensions"]["KHR_lights_punctual"]["lights"]:
            light = bpy.data.lights[gl["name"]]
            if gl["type"] == "directional":
                want = gl["intensity"] / 683.0
                check(abs(light.energy - want) <= 1e-5 * want, f"{name}: sun '{gl['name']}' S = lux / 683 W/m²",
                      f"{gl['intensity']:g} lx -> {light.energy:.6g} W/m² (facet C = S/π = {light.energy / math.pi:.6g})")
            else:
                want = gl["intensity"] * 4 * math.pi / 683.0
                check(abs(light.energy - want) <= 1e-5 * want,
                      f"{name}: {gl['type']} '{gl['name']}' P = cd · 4π / 683 W",
                      f"{gl['intensity']:g} cd -> {light.energy:.6g} W (facet C = P/(4π²) = "
                      f"{light.energy / (4 * math.pi ** 2):.6g} = cd/(683π) = {gl['intensity'] / (683 * math.pi):.6g})")
                check(light.shadow_soft_size == 0.0, f"{name}: '{gl['name']}' radius", light.shadow_soft_size)
            if gl["type"] == "spot":
                outer, inner = gl["spot"]["outerConeAngle"], gl["spot"]["innerConeAngle"]
                check(abs(light.spot_size - 2 * outer) < 1e-6 and abs(light.spot_blend - (1 - inner / outer)) < 1e-6,
                      f"{name}: spot size = 2·outer, blend = 1 − inner/outer",
                      f"{math.degrees(light.spot_size):.4g}°, blend {light.spot_blend:.4g}")
            if gl["type"] == "directional":
                check(light.angle > 0.0, f"{name}: sun '{gl['name']}' keeps Blender's default angle",
                      f"{math.degrees(light.angle):.4g}° (facet's directional light is a parallel beam)")


def cameras(corpus):
    import bpy
    doc = load(os.path.join(corpus, "camera_nested.gltf"))
    cam = next(o.data for o in bpy.data.objects if o.type == "CAMERA")
    yfov = doc["cameras"][0]["perspective"]["yfov"]
    check(cam.sensor_fit == "VERTICAL" and abs(cam.angle_y - yfov) < 1e-6,
          "perspective: sensor fit VERTICAL, angle_y = yfov (aspectRatio ignored)",
          f"{cam.sensor_fit}, {math.degrees(cam.angle_y):.5g}° for {math.degrees(yfov):.5g}°")
    check(cam.clip_end >= 1e11, "perspective without zfar: far clip 1e12", f"{cam.clip_end:g}")
    doc = load(os.path.join(corpus, "camera_orthographic.gltf"))
    cam = next(o.data for o in bpy.data.objects if o.type == "CAMERA")
    o = doc["cameras"][0]["orthographic"]
    check(cam.type == "ORTHO" and abs(cam.ortho_scale - 2 * max(o["xmag"], o["ymag"])) < 1e-6,
          "orthographic: Orthographic Scale = 2·max(xmag, ymag), sensor fit AUTO",
          f"{cam.ortho_scale:.5g} ({cam.sensor_fit}) for xmag {o['xmag']}, ymag {o['ymag']}: the view height is "
          f"2·ymag only when the render's aspect is xmag/ymag")


def uv_sets_and_transforms(corpus):
    import bpy
    load(os.path.join(corpus, "uv_sets.gltf"))
    obj = bpy.data.objects["box_sets"]
    names = [l.name for l in obj.data.uv_layers]
    check(names == ["UVMap", "UVMap.001", "UVMap.002"], "TEXCOORD_n -> UV map 'UVMap' (n = 0), 'UVMap.%03d' % n",
          names)
    mat = bpy.data.materials["sets_1_and_2"]
    maps = sorted(n.uv_map for n in mat.node_tree.nodes if n.type == "UVMAP")
    check(maps == ["UVMap.001", "UVMap.002"], "a texture's texCoord n -> a UV Map node naming that map", maps)
    over = bpy.data.materials["override"]
    maps = [n.uv_map for n in over.node_tree.nodes if n.type == "UVMAP"]
    check(maps == ["UVMap.002"], "KHR_texture_transform's texCoord overrides the texture's", maps)
    doc = load(os.path.join(corpus, "texture_transform.gltf"))
    mat = bpy.data.materials["transformed"]
    gm = next(m for m in doc["materials"] if m["name"] == "transformed")
    base = gm["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"]
    mapping = [n for n in mat.node_tree.nodes if n.type == "MAPPING"]
    o, r, s = base["offset"], base["rotation"], base["scale"]
    want = (o[0] + s[1] * math.sin(r), 1 - o[1] - s[1] * math.cos(r), r, s[0], s[1])
    got = [(m.inputs["Location"].default_value[0], m.inputs["Location"].default_value[1],
            m.inputs["Rotation"].default_value[2], m.inputs["Scale"].default_value[0],
            m.inputs["Scale"].default_value[1]) for m in mapping if m.vector_type == "POINT"]
    check(any(max(abs(a - b) for a, b in zip(g, want)) < 1e-6 for g in got),
          "KHR_texture_transform -> Mapping (Point): Location (o_u + s_v sin θ, 1 − o_v − s_v cos θ), Rotation z θ, "
          "Scale (s_u, s_v), in Blender's v-up UV (com/conversion.py)",
          f"{len(mapping)} Mapping nodes; base colour's {tuple(round(x, 5) for x in want)}")
    mixes = [n for n in mat.node_tree.nodes if n.type == "MIX"]
    maths = [n for n in mat.node_tree.nodes if n.type == "MATH"]
    check(any(m.blend_type == "MULTIPLY" and m.data_type == "RGBA" for m in mixes) and
          any(m.operation == "MULTIPLY" for m in maths),
          "a factor beside a texture -> Mix (Multiply, RGBA) for colours, Math (Multiply) for metallic/roughness",
          f"{[(m.data_type, m.blend_type) for m in mixes]}, {[m.operation for m in maths]}")


def normals_and_deformations(corpus):
    import bpy
    doc = load(os.path.join(corpus, "rotated_quaternion.gltf"))
    obj = bpy.data.objects["torus"]
    mesh = obj.data
    file_normals = gb.torus(0.6, 0.22).normals.astype(float)
    got = np.zeros((len(mesh.loops), 3))
    mesh.corner_normals.foreach_get("vector", got.ravel())
    verts = np.array([l.vertex_index for l in mesh.loops])
    # Blender's axes: glTF (x, y, z) is Blender (x, −z, y).
    want = file_normals[verts][:, [0, 2, 1]] * (1, -1, 1)
    angle = np.degrees(np.arccos(np.clip((got * want).sum(axis=1), -1, 1))).max()
    check(mesh.has_custom_normals and angle < 0.05,
          "NORMAL -> custom split normals (two 16-bit numbers per corner, relative to its faces)",
          f"worst corner {angle:.4f}° from the file's")
    load(os.path.join(corpus, "morph.gltf"))
    obj = bpy.data.objects["morphed"]
    keys = obj.data.shape_keys
    check(keys is not None and [round(k.value, 6) for k in keys.key_blocks[1:]] == [0.6, 0.3],
          "morph targets -> shape keys at the mesh's weights, positions only (NORMAL deltas dropped)",
          [(k.name, round(k.value, 3)) for k in keys.key_blocks] if keys else None)
    load(os.path.join(corpus, "skin.gltf"))
    arm = [o for o in bpy.data.objects if o.type == "ARMATURE"]
    mods = [m.type for o in bpy.data.objects if o.type == "MESH" for m in o.modifiers]
    check(len(arm) == 1 and "ARMATURE" in mods, "a skin -> an armature (bones at the joints' nodes) and an Armature "
                                                "modifier: Blender's normals follow the deformed faces",
          f"{len(arm)} armature, modifiers {mods}")


def default_material(corpus):
    import bpy
    load(os.path.join(corpus, "multi_primitive.gltf"))
    slots = [m.name if m else None for m in bpy.data.objects["statue"].data.materials]
    check(slots.count(None) == 1, "a primitive without a material -> an empty slot (Blender's own default "
                                  "surface, not glTF's white metal); the facet add-on's import hook fills it", slots)
    load(os.path.join(corpus, "default_material.gltf"))
    slots = [len(bpy.data.objects[n].data.materials) for n in ("sphere", "box")]
    check(slots == [0, 0], "a mesh none of whose primitives has a material -> no slot at all", slots)


def vertex_colours(work):
    """COLOR_0 as float RGB, normalized ubyte RGBA and normalized ushort RGB, on three primitives."""
    import bpy
    doc = gb.Document()
    colours = {}
    prims = []
    for k, (component, width) in enumerate(((gb.FLOAT, 3), (gb.UBYTE, 4), (gb.USHORT, 3))):
        shape = gb.box(0.3, 0.3, 0.3)
        shape.positions = shape.positions + np.float32([k, 0, 0])
        n = len(shape.positions)
        c = np.stack([np.linspace(0.05, 0.95, n), np.linspace(0.9, 0.1, n), 0.37 + 0.0 * np.arange(n),
                      np.linspace(0.2, 1.0, n)], axis=1)[:, :width]
        top = {gb.FLOAT: 1.0, gb.UBYTE: 255.0, gb.USHORT: 65535.0}[component]
        stored = c if component == gb.FLOAT else np.round(c * top)
        colours[k] = stored / top
        acc = doc.accessor(stored, component, normalized=component != gb.FLOAT)
        mat = doc.material(f"m{k}", base=(1, 1, 1, 1))
        prims.append(doc.primitive(shape, mat, extra={"COLOR_0": acc}))
    doc.node(name="coloured", mesh=doc.mesh(prims, "coloured"))
    path = os.path.join(work, "vertex_colours.gltf")
    doc.save(path)
    load(path)
    mesh = bpy.data.objects["coloured"].data
    attrs = [(a.name, a.data_type, a.domain) for a in mesh.color_attributes]
    check(attrs == [("Color", "BYTE_COLOR", "CORNER")] or attrs == [("Color", "BYTE_COLOR", "POINT")],
          "COLOR_0 -> one colour attribute 'Color', 8-bit (BYTE_COLOR: sRGB-encoded bytes), the render colour", attrs)
    got = np.zeros((len(mesh.color_attributes[0].data), 4))
    mesh.color_attributes[0].data.foreach_get("color", got.ravel())
    domain = mesh.color_attributes[0].domain
    verts = np.array([l.vertex_index for l in mesh.loops]) if domain == "CORNER" else np.arange(len(mesh.vertices))
    want = np.concatenate([np.pad(colours[k], ((0, 0), (0, 4 - colours[k].shape[1])), constant_values=1.0)
                           for k in range(3)])[verts]
    err = np.abs(got - want)
    check(err[:, :3].max() < 0.02, "vertex colours come back as linear values through 8-bit sRGB bytes",
          f"worst |Δ| {err[:, :3].max():.2e} on RGB (an sRGB byte step is ~3e-4 of linear near 0, ~4e-3 near 1), "
          f"{err[:, 3].max():.2e} on alpha (a linear byte: k/255 kept)")
    nodes = {n.type for m in bpy.data.materials if m.node_tree for n in m.node_tree.nodes}
    check("VERTEX_COLOR" in nodes, "a material on a COLOR_0 primitive -> a Color Attribute node (the render colour) "
                                   "into Base Color, through a Mix (Multiply) with the texture or factor where there "
                                   "is one (pbrMetallicRoughness.py base_color)", sorted(nodes))


def alpha_mask(work):
    """alphaMode MASK with a cutoff: the base colour texture's alpha through Blender's clip."""
    import bpy
    doc = gb.Document()
    i, j = gb.grid(8)
    tex = doc.texture(gb.rgba(0.8, 0.5, 0.2, (i + j) / 14.0), gb.NEAREST, gb.NEAREST)
    mat = doc.material("cut", base=(1, 1, 1, 1), baseColorTexture={"index": tex}, alphaMode="MASK", alphaCutoff=0.4)
    doc.node(name="leaf", mesh=doc.mesh(doc.primitive(gb.plane(1.0), mat), "leaf"))
    path = os.path.join(work, "mask.gltf")
    doc.save(path)
    load(path)
    tree = bpy.data.materials["cut"].node_tree
    ops = sorted((n.operation, round(n.inputs[1].default_value, 4)) for n in tree.nodes if n.type == "MATH")
    alpha = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED").inputs["Alpha"]
    check(("LESS_THAN", 0.4) in ops and any(o == "SUBTRACT" for o, _ in ops) and alpha.is_linked,
          "alphaMode MASK -> Alpha = 1 − (texture alpha < alphaCutoff) into the Principled BSDF's Alpha (Math "
          "Less Than, Subtract: pbrMetallicRoughness.py base_color)", ops)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--corpus", required=True)
    p.add_argument("--work", required=True)
    opts = p.parse_args()
    os.makedirs(opts.work, exist_ok=True)
    corpus = os.path.join(opts.corpus, "corpus")
    import bpy
    print(f"Blender {bpy.app.version_string}'s glTF importer, default options:")
    for part in (lights, cameras, uv_sets_and_transforms, normals_and_deformations, default_material):
        part(corpus)
    vertex_colours(opts.work)
    alpha_mask(opts.work)
    print(f"conventions: {'all hold' if not FAILURES else 'FAILED: ' + '; '.join(FAILURES)}")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
