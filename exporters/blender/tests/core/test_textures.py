"""core/textures.py (and its use in convert.py and scene.py): Image Texture and Normal Map
nodes as plain descriptions -> facet's textured parameters, derived images, PNG files."""

import json
import math
import os
import random
import subprocess

import pytest

from facet_blender.core import UserError, generate, scene, textures
from facet_blender.core.convert import APPROXIMATE, EXACT, IGNORED, map_surface
from support import read_png


def image(name="checker", colorspace="sRGB", **kw):
    desc = {"name": name, "colorspace": colorspace, "source": "FILE", "filepath": f"/textures/{name}.png",
            "packed": False, "exists": True, "is_float": False}
    desc.update(kw)
    return desc


def tex_image(img, output="Color", interpolation="Closest", extension="REPEAT", vector=None, name="Image Texture"):
    return {"type": "TEX_IMAGE", "name": name, "output": output, "image": img, "interpolation": interpolation,
            "extension": extension, "projection": "FLAT", "links": {"Vector": vector}}


def separate(src, output):
    return {"type": "SEPARATE_COLOR", "name": "Separate Color", "output": output, "mode": "RGB",
            "links": {"Color": src}}


def principled(sources, **inputs):
    values = {"Base Color": [0.8, 0.8, 0.8, 1.0], "Metallic": 0.0, "Roughness": 0.5,
              "IOR": 1.5, "Specular IOR Level": 0.5}
    values.update(inputs)
    return {"type": "BSDF_PRINCIPLED", "name": "Principled BSDF", "distribution": "GGX", "inputs": values,
            "linked": sorted(sources), "sources": sources}


def messages(result, level=None):
    return [m for lv, m in result.notes if level is None or lv == level]


UV = {"type": "UVMAP", "name": "UV Map", "output": "UV", "uv_map": "UVMap"}


def checker_and_roughness():
    """A Diffuse BSDF with a colour image and a GGX Glossy BSDF with a roughness image (its G)."""
    diffuse = {"type": "BSDF_DIFFUSE", "name": "Diffuse BSDF", "inputs": {"Color": [1, 1, 1, 1], "Roughness": 0.0},
               "linked": ["Color"], "sources": {"Color": tex_image(image(), vector=UV)}}
    rough = separate(tex_image(image("rough", "Non-Color"), "Color", "Linear", "EXTEND"), "Green")
    glossy = {"type": "BSDF_GLOSSY", "name": "Glossy BSDF", "distribution": "GGX",
              "inputs": {"Color": [1, 1, 1, 1], "Roughness": 0.5}, "linked": ["Roughness"],
              "sources": {"Roughness": rough}}
    return {"type": "ADD_SHADER", "shaders": [diffuse, glossy]}


# ----------------------------------------------------------------------------- mapping

def test_colour_and_roughness_images_map_to_bindings():
    r = map_surface(checker_and_roughness(), "Textured")
    by_path = {tuple(b["path"]): b for b in r.textures}
    assert set(by_path) == {("diffuse", "color"), ("specular", "alpha")}
    kd = by_path[("diffuse", "color")]
    assert kd["model"] == "lambert" and "factor" not in kd
    assert kd["spec"] == {"image": "checker", "uv_map": "UVMap", "colorspace": "srgb", "filter": "nearest",
                          "wrap": "repeat", "channel": "rgb"}
    alpha = by_path[("specular", "alpha")]
    assert alpha["derive"] == {"op": "square"} and alpha["model"] == "ggx"
    assert alpha["spec"] == {"image": "rough", "uv_map": "", "colorspace": "linear", "filter": "bilinear",
                             "wrap": "clamp", "channel": "g"}
    # No "linked ... unlinked value is used" for inputs that became textures.
    assert not any("unlinked value" in m for m in messages(r))
    assert any("Roughness² baked" in m for m in messages(r, APPROXIMATE))


def gltf_maps(base_uv=UV, mr_uv=None):
    """glTF's baseColorTexture (× baseColorFactor) and metallicRoughnessTexture (B × metallicFactor,
    G × roughnessFactor) as Blender's glTF importer wires them into a Principled BSDF."""
    mr = tex_image(image("mr", "Non-Color"), "Color", "Linear", "EXTEND", vector=mr_uv)
    return principled({"Base Color": mix(tex_image(image(), vector=base_uv), [0.5, 0.25, 1.0, 1.0], linked_side="b"),
                       "Metallic": math_multiply(separate(mr, "Blue"), 0.5),
                       "Roughness": math_multiply(separate(mr, "Green"), 0.7)})


def test_principled_images_are_gltf_pbr_bindings_as_the_file_has_them():
    """Each map is a binding of the gltf_pbr lobe: the image itself, its channel and factor,
    nothing baked, whatever UV maps they read — what facet import-gltf reads from the file."""
    other = {"type": "UVMAP", "name": "UV Map", "output": "UV", "uv_map": "UVMap.001"}
    for mr_uv in (None, other):
        r = map_surface(gltf_maps(mr_uv=mr_uv), "Textured")
        by_path = {tuple(b["path"]): b for b in r.textures}
        assert set(by_path) == {("specular", "base_color"), ("specular", "metallic"), ("specular", "roughness")}
        assert all(b["model"] == "gltf_pbr" and "derive" not in b for b in r.textures)
        base = by_path[("specular", "base_color")]
        assert base["factor"] == pytest.approx([0.5, 0.25, 1.0])
        assert base["spec"] == {"image": "checker", "uv_map": "UVMap", "colorspace": "srgb", "filter": "nearest",
                                "wrap": "repeat", "channel": "rgb"}
        metal, rough = by_path[("specular", "metallic")], by_path[("specular", "roughness")]
        assert (metal["factor"], metal["spec"]["channel"]) == (pytest.approx(0.5), "b")
        assert (rough["factor"], rough["spec"]["channel"]) == (pytest.approx(0.7), "g")
        assert metal["spec"]["uv_map"] == ("UVMap.001" if mr_uv else "")
        assert not any("unlinked value" in m or "UV map" in m for m in messages(r))


def mix(linked, value, blend="MULTIPLY", factor=1.0, linked_side="a"):
    other = "b" if linked_side == "a" else "a"
    return {"type": "MIX", "name": "Mix", "output": "Result", "data_type": "RGBA", "blend_type": blend,
            "clamp": False, "factor": factor, "factor_linked": False, linked_side: linked,
            f"{linked_side}_value": [1.0, 1.0, 1.0, 1.0], other: None, f"{other}_value": value}


def math_multiply(linked, value, operation="MULTIPLY"):
    return {"type": "MATH", "name": "Math", "output": "Value", "operation": operation, "clamp": False,
            "values": [0.0, value], "links": [linked, None]}


def test_glTF_factors_between_an_image_and_the_bsdf_become_factors():
    """Blender's glTF importer puts baseColorFactor, emissiveFactor (a colour), metallicFactor and
    roughnessFactor beside a texture into Mix (Multiply) and Math (Multiply) nodes."""
    src = principled({"Base Color": mix(tex_image(image()), [0.5, 0.25, 1.0, 1.0], linked_side="b"),
                      "Roughness": math_multiply(separate(tex_image(image("mr", "Non-Color")), "Green"), 0.5),
                      "Emission Color": mix(tex_image(image("glow")), [0.2, 0.4, 0.6, 1.0])},
                     **{"Emission Strength": 2.0, "Emission Color": [1.0, 1.0, 1.0, 1.0]})
    r = map_surface(src, "Factors")
    by_path = {tuple(b["path"]): b for b in r.textures}
    assert by_path[("specular", "base_color")]["factor"] == pytest.approx([0.5, 0.25, 1.0])
    assert by_path[("specular", "roughness")]["factor"] == pytest.approx(0.5)
    assert by_path[("emission",)]["factor"] == pytest.approx([0.4, 0.8, 1.2])
    assert not any("unlinked value" in m for m in messages(r))
    assert all("scale" not in b["spec"] for b in r.textures)


def alpha_clip(alpha_src, cutoff, constant=1.0):
    """Blender's glTF importer's MASK: Alpha = 1 − (alpha < cutoff), Math nodes."""
    less = {"type": "MATH", "name": "Less", "output": "Value", "operation": "LESS_THAN", "clamp": False,
            "values": [constant, cutoff], "links": [alpha_src, None]}
    return {"type": "MATH", "name": "Subtract", "output": "Value", "operation": "SUBTRACT", "clamp": False,
            "values": [1.0, 0.5], "links": [None, less]}


def test_alpha_mask_clip_is_a_cut_out():
    """glTF's alphaMode MASK as Blender's importer wires it: the base colour image's Alpha (times
    the alpha factor) through 1 − (a < c) -> facet's alpha (channel a, linear) and alpha_cutoff c."""
    base = tex_image(image("leaf"))
    alpha = math_multiply(tex_image(image("leaf"), "Alpha"), 0.8)
    r = map_surface(principled({"Base Color": base, "Alpha": alpha_clip(alpha, 0.4)}), "Leaf")
    assert r.alpha_cutoff == pytest.approx(0.4) and r.alpha == 1.0
    cut = next(b for b in r.textures if b["path"] == ["alpha"])
    assert cut["spec"]["channel"] == "a" and cut["spec"]["colorspace"] == "linear"
    assert cut["factor"] == pytest.approx(0.8)
    assert r.cut_out({"name": "Leaf"}) == {"name": "Leaf", "alpha": 1.0, "alpha_cutoff": pytest.approx(0.4)}
    assert not any("Alpha" in m and "not mapped" in m for m in messages(r))
    data, _ = textures.apply(r.cut_out(r.material("Leaf")), r.textures,
                             {textures.file_key(b): ("leaf.png", None) for b in r.textures})
    assert data["alpha"] == {"texture": "leaf.png", "channel": "a", "colorspace": "linear", "filter": "nearest",
                             "wrap": "repeat", "uv": 0, "factor": pytest.approx(0.8)}
    assert data["alpha_cutoff"] == pytest.approx(0.4)


def test_alpha_linked_otherwise_is_no_cut_out():
    """A blend (Alpha from the image directly) is no cut-out: named, and the material opaque."""
    r = map_surface(principled({"Alpha": tex_image(image("leaf"), "Alpha")}), "Glass")
    assert r.alpha_cutoff is None and r.cut_out({}) == {}
    assert any("Alpha" in m for m in messages(r, IGNORED)), r.notes


@pytest.mark.parametrize("src", [
    mix({"type": "TEX_IMAGE"}, [0.5, 0.5, 0.5, 1.0], blend="ADD"),
    mix({"type": "TEX_IMAGE"}, [0.5, 0.5, 0.5, 1.0], factor=0.5),
    math_multiply({"type": "TEX_IMAGE"}, 0.5, operation="POWER")])
def test_other_mix_and_math_nodes_are_named(src):
    src["a" if src["type"] == "MIX" else "links"] = (tex_image(image()) if src["type"] == "MIX"
                                                     else [tex_image(image("r", "Non-Color")), None])
    r = map_surface(principled({"Base Color" if src["type"] == "MIX" else "Roughness": src}), "Other")
    assert not r.textures
    assert any("Mix (Multiply) or Math (Multiply)" in m for m in messages(r, IGNORED)), r.notes


@pytest.mark.parametrize("setting, value, key, expected, level, words", [
    ("interpolation", "Cubic", "filter", "bilinear", APPROXIMATE, "Cubic interpolation"),
    ("interpolation", "Smart", "filter", "bilinear", APPROXIMATE, "Smart interpolation"),
    ("interpolation", "Linear", "filter", "bilinear", APPROXIMATE, "filters an sRGB image before"),
    ("extension", "EXTEND", "wrap", "clamp", None, ""),
    ("extension", "MIRROR", "wrap", "mirror", None, ""),
    ("extension", "CLIP", "wrap", "clamp", APPROXIMATE, "CLIP")])
def test_image_texture_settings(setting, value, key, expected, level, words):
    src = tex_image(image(), **{setting: value})
    r = map_surface(principled({"Base Color": src}), "S")
    assert r.textures[0]["spec"][key] == expected
    if level:
        assert any(words in m and "'Image Texture' (TEX_IMAGE)" in m and "material 'S'" in m
                   for m in messages(r, level)), r.notes
    else:
        assert not messages(r, APPROXIMATE) or all("Image Texture" not in m for m in messages(r, APPROXIMATE))


@pytest.mark.parametrize("space, expected", [("sRGB", "srgb"), ("Non-Color", "linear"), ("Linear Rec.709", "linear"),
                                             ("Linear", "linear"), ("Raw", "linear")])
def test_colour_spaces(space, expected):
    r = map_surface(principled({"Base Color": tex_image(image(colorspace=space))}), "C")
    assert r.textures[0]["spec"]["colorspace"] == expected


def test_alpha_output_and_colour_to_number():
    r = map_surface(principled({"Roughness": tex_image(image("r", "Non-Color"), "Alpha")}), "A")
    assert r.textures[0]["spec"]["channel"] == "a"
    r = map_surface(principled({"Roughness": tex_image(image("r", "Non-Color"))}), "L")
    assert r.textures[0]["spec"]["channel"] == "r"
    assert any("luminance" in m for m in messages(r, APPROXIMATE))


@pytest.mark.parametrize("kind, name", [("TEX_NOISE", "Noise Texture"), ("TEX_VORONOI", "Voronoi Texture"),
                                        ("TEX_CHECKER", "Checker Texture"), ("MATH", "Math"),
                                        ("VALTORGB", "Color Ramp")])
def test_unmappable_nodes_are_named_in_a_warning(kind, name):
    r = map_surface(principled({"Base Color": {"type": kind, "name": name, "output": "Color"}}), "Procedural")
    warnings = messages(r, IGNORED)
    assert any(f"'{name}' ({kind})" in m and "material 'Procedural'" in m and "Base Color" in m for m in warnings), \
        r.notes
    assert not r.textures


def test_unmappable_input_of_an_image_is_named():
    geo = {"type": "TEX_COORD", "name": "Texture Coordinate", "output": "Generated"}
    r = map_surface(principled({"Base Color": tex_image(image(), vector=geo)}), "Gen")
    assert any("'Texture Coordinate' (TEX_COORD)" in m and "not a UV map" in m for m in messages(r, IGNORED))
    assert not r.textures


def test_other_linked_inputs_are_named():
    r = map_surface(principled({"Coat Weight": {"type": "MATH", "name": "Math.001", "output": "Value"}},
                               **{"Coat Weight": 0.0}), "Coat")
    assert any("'Math.001' (MATH)" in m and "Coat Weight" in m for m in messages(r, IGNORED)), r.notes


def test_a_missing_image_file_is_an_error_naming_material_and_node():
    src = tex_image(image(exists=False, filepath="/nowhere/checker.png"), name="Albedo")
    with pytest.raises(UserError) as e:
        map_surface(principled({"Base Color": src}), "Painted")
    assert "material 'Painted'" in str(e.value) and "'Albedo' (TEX_IMAGE)" in str(e.value) \
        and "/nowhere/checker.png" in str(e.value)
    # A packed image needs no file.
    map_surface(principled({"Base Color": tex_image(image(exists=False, packed=True))}), "Packed")


def test_diffuse_and_glossy_textures():
    d = {"type": "BSDF_DIFFUSE", "name": "Diffuse BSDF", "inputs": {"Color": [1, 1, 1, 1], "Roughness": 0.0},
         "linked": ["Color"], "sources": {"Color": tex_image(image())}}
    r = map_surface(d, "D")
    assert r.diffuse["model"] == "lambert" and r.textures[0]["path"] == ["diffuse", "color"] and r.exact
    g = {"type": "BSDF_GLOSSY", "name": "Glossy BSDF", "distribution": "BECKMANN",
         "inputs": {"Color": [1, 1, 1, 1], "Roughness": 0.0}, "linked": ["Roughness"],
         "sources": {"Roughness": tex_image(image("r", "Non-Color"))}}
    r = map_surface(g, "G")
    assert r.specular["model"] == "beckmann" and r.textures[0]["path"] == ["specular", "m"]


# ----------------------------------------------------------------------------- Mapping node

def blender_mapping(uv_b, loc, rot_z, scale):
    """Blender's Point mapping in Blender UV: Rz(θ)(S ⊙ uv) + L."""
    x, y = uv_b[0] * scale[0], uv_b[1] * scale[1]
    c, s = math.cos(rot_z), math.sin(rot_z)
    return (c * x - s * y + loc[0], s * x + c * y + loc[1])


def khr(uv, t):
    """KHR_texture_transform as docs/textures.md writes it."""
    r, (su, sv), (ou, ov) = t["rotation"], t["scale"], t["offset"]
    u, v = uv
    return (math.cos(r) * su * u + math.sin(r) * sv * v + ou, -math.sin(r) * su * u + math.cos(r) * sv * v + ov)


@pytest.mark.parametrize("loc, rot_z, scale", [((0.1, 0.2, 0.0), 0.0, (2.0, 3.0, 1.0)),
                                               ((0.3, -0.4, 5.0), 0.7, (1.5, 0.5, 1.0)),
                                               ((0.0, 0.0, 0.0), -1.2, (1.0, 1.0, 1.0))])
def test_mapping_node_is_khr_texture_transform_in_facets_v_down(loc, rot_z, scale):
    src = {"type": "MAPPING", "vector_type": "POINT",
           "inputs": {"Location": list(loc), "Rotation": [0.0, 0.0, rot_z], "Scale": list(scale)}}
    t = textures.mapping_transform(src)
    rng = random.Random(1)
    for _ in range(50):
        u, v = rng.uniform(-1, 2), rng.uniform(-1, 2)
        bu, bv = blender_mapping((u, 1.0 - v), loc, rot_z, scale)        # Blender's v_b = 1 − v
        assert khr((u, v), t) == pytest.approx((bu, 1.0 - bv), abs=1e-12)  # sampled at facet's v = 1 − v_b


@pytest.mark.parametrize("loc, rot_z, scale", [((0.1, 0.2, 0.0), 0.0, (2.0, 3.0, 1.0)),
                                               ((0.3, -0.4, 0.0), 0.7, (1.5, 1.5, 1.0))])
def test_texture_mapping_is_the_inverse(loc, rot_z, scale):
    src = {"type": "MAPPING", "vector_type": "TEXTURE",
           "inputs": {"Location": list(loc), "Rotation": [0.0, 0.0, rot_z], "Scale": list(scale)}}
    t = textures.mapping_transform(src)
    c, s = math.cos(rot_z), math.sin(rot_z)
    rng = random.Random(2)
    for _ in range(50):
        u, v = rng.uniform(-1, 2), rng.uniform(-1, 2)
        x, y = u - loc[0], (1.0 - v) - loc[1]                              # Blender: R(−θ)(uv − L) / S
        bu, bv = (c * x + s * y) / scale[0], (-s * x + c * y) / scale[1]
        assert khr((u, v), t) == pytest.approx((bu, 1.0 - bv), abs=1e-12)
    assert textures.mapping_transform(dict(src, inputs=dict(src["inputs"], Scale=[1.0, 2.0, 1.0],
                                                              Rotation=[0.0, 0.0, 0.3]))) is None


def test_mapping_without_an_exact_transform_is_reported():
    src = {"type": "MAPPING", "name": "Mapping", "output": "Vector", "vector_type": "POINT",
           "inputs": {"Location": [0, 0, 0], "Rotation": [0.5, 0, 0], "Scale": [1, 1, 1]}, "linked": [],
           "links": {"Vector": UV}}
    r = map_surface(principled({"Base Color": tex_image(image(), vector=src)}), "Tilted")
    assert any("'Mapping' (MAPPING)" in m and "KHR_texture_transform" in m for m in messages(r, APPROXIMATE))
    assert "transform" not in r.textures[0]["spec"]
    src = dict(src, inputs={"Location": [0.25, 0, 0], "Rotation": [0, 0, 0], "Scale": [2, 2, 1]})
    r = map_surface(principled({"Base Color": tex_image(image(), vector=src)}), "Moved")
    assert r.textures[0]["spec"]["transform"] == {"offset": [0.25, -1.0], "scale": [2.0, 2.0], "rotation": 0.0}
    assert r.textures[0]["spec"]["uv_map"] == "UVMap"


# ----------------------------------------------------------------------------- normal maps

def normal_map(strength=1.0, space="TANGENT", colorspace="Non-Color"):
    return {"type": "NORMAL_MAP", "name": "Normal Map", "output": "Normal", "space": space, "uv_map": "",
            "inputs": {"Strength": strength}, "linked": [],
            "links": {"Color": tex_image(image("bumps", colorspace), interpolation="Linear")}}


def test_normal_map_strength_1_is_exact():
    r = map_surface(principled({"Normal": normal_map()}), "Bumpy")
    (b,) = [b for b in r.textures if b["path"] == ["normal_map"]]
    assert b["spec"] == {"image": "bumps", "uv_map": "", "filter": "bilinear", "wrap": "repeat",
                         "green": "up", "strength": 1.0}
    assert any("Strength 1 -> normal_map" in m for m in messages(r, EXACT))
    data, notes = textures.apply({"name": "Bumpy", "diffuse": {"model": "lambert", "color": [1, 1, 1]}},
                                 r.textures, {textures.file_key(b): ("bumps.png", None)})
    assert data["normal_map"] == {"texture": "bumps.png", "filter": "bilinear", "wrap": "repeat", "uv": 0,
                                  "green": "up", "strength": 1.0} and not notes


def test_normal_map_other_strengths_spaces_and_bump_are_reported():
    r = map_surface(principled({"Normal": normal_map(0.5)}), "Half")
    assert any("Strength 0.5" in m and "equal only at Strength 1" in m for m in messages(r, APPROXIMATE))
    assert r.textures[0]["spec"]["strength"] == 0.5
    r = map_surface(principled({"Normal": normal_map(space="OBJECT")}), "Obj")
    assert not r.textures and any("OBJECT space" in m for m in messages(r, IGNORED))
    r = map_surface(principled({"Normal": {"type": "BUMP", "name": "Bump", "output": "Normal"}}), "Bump")
    assert not r.textures and any("'Bump' (BUMP)" in m and "Bump nodes" in m for m in messages(r, IGNORED))
    r = map_surface(principled({"Normal": normal_map(colorspace="sRGB")}), "Srgb")
    assert any("should be Non-Color" in m for m in messages(r, APPROXIMATE))


def test_coat_normal_is_the_coats_own_normal_map():
    """A Coat Normal through a Normal Map node is the material's coat_normal_map (glTF's
    clearcoatNormalTexture), written as normal_map is; without a coat (Coat Weight 0) it is not
    read, said; on another UV map than the Normal's it is left out, said."""
    r = map_surface(principled({"Coat Normal": normal_map()}, **{"Coat Weight": 0.7}), "Coated")
    (b,) = [b for b in r.textures if b["path"] == ["coat_normal_map"]]
    assert b["spec"]["green"] == "up" and b["spec"]["strength"] == 1.0
    assert any("Strength 1 -> coat_normal_map" in m for m in messages(r, EXACT))
    data, notes = textures.apply({"name": "Coated", "specular": r.specular}, r.textures,
                                 {textures.file_key(b): ("bumps.png", None)})
    assert data["coat_normal_map"] == {"texture": "bumps.png", "filter": "bilinear", "wrap": "repeat", "uv": 0,
                                       "green": "up", "strength": 1.0} and not notes
    r = map_surface(principled({"Coat Normal": normal_map()}), "Uncoated")
    assert not r.textures and any("no coat" in m for m in messages(r, IGNORED))
    other = dict(normal_map(), links={"Color": tex_image(image("bumps", "Non-Color"), interpolation="Linear",
                                                         vector=UV)})
    r = map_surface(principled({"Normal": normal_map(), "Coat Normal": other}, **{"Coat Weight": 0.7}), "Apart")
    assert [b["path"] for b in r.textures] == [["normal_map"]]
    assert any("one tangent frame" in m for m in messages(r, APPROXIMATE))


def test_material_level_maps_left_out_for_a_facet_without_them():
    emission = tex_image(image("glow"))
    r = map_surface(principled({"Normal": normal_map(), "Emission Color": emission},
                               **{"Emission Color": [0.1, 0.2, 0.3, 1.0], "Emission Strength": 2.0}), "Old")
    assert sorted(b["path"][0] for b in r.textures) == ["emission", "normal_map"]
    assert r.emission == pytest.approx([0.2, 0.4, 0.6])          # the unlinked colour × strength, as a fallback
    files = {textures.file_key(b): (b["spec"]["image"] + ".png", None) for b in r.textures}
    material = {"name": "Old", "diffuse": {"model": "lambert", "color": [1, 1, 1]}, "emission": r.emission}
    data, notes = textures.apply(material, r.textures, files, material_keys=set())
    assert "normal_map" not in data and data["emission"] == r.emission
    assert any("cannot take its normal map" in n for n in notes) and any("emission map" in n for n in notes)
    assert textures.exported(r.textures, set()) == []
    data, notes = textures.apply(material, r.textures, files, material_keys={"emission", "normal_map"})
    assert not notes and data["emission"] == {"texture": "glow.png", "channel": "rgb", "colorspace": "srgb",
                                              "filter": "nearest", "wrap": "repeat", "uv": 0, "factor": 2.0}


# ----------------------------------------------------------------------------- apply, UV sets

def test_apply_writes_facets_texture_objects():
    r = map_surface(checker_and_roughness(), "Textured")
    files = {textures.file_key(b): (f"{b['spec']['image']}.png", None) for b in r.textures}
    material = {"name": "Textured", "diffuse": r.diffuse, "specular": r.specular}
    data, notes = textures.apply(material, r.textures, files)
    assert not notes
    assert data["diffuse"]["color"] == {"texture": "checker.png", "channel": "rgb", "colorspace": "srgb",
                                        "filter": "nearest", "wrap": "repeat", "uv": 0}
    # The roughness image reads the active render map (""), the second set; α is the baked image's r.
    assert data["specular"]["alpha"] == {"texture": "rough.png", "channel": "r", "colorspace": "linear",
                                         "filter": "bilinear", "wrap": "clamp", "uv": 1}
    assert textures.uv_maps(r.textures) == ["UVMap", ""]
    # A lobe whose model changed since the conversion keeps its numbers, and says so.
    data, notes = textures.apply(dict(material, specular={"model": "phong", "color": [1, 1, 1], "n": 10}),
                                 r.textures, files)
    assert data["specular"] == {"model": "phong", "color": [1, 1, 1], "n": 10}
    assert "made for the specular model ggx" in notes[0]


def test_more_than_two_uv_maps_are_refused():
    bindings = [textures.binding(["diffuse", "color"], "lambert", {"image": "a", "uv_map": n}) for n in "xyz"]
    with pytest.raises(UserError, match="material 'Three': its textures read 3 UV maps"):
        textures.uv_maps(bindings, "Three")


def test_mesh_texcoords_flip_v_and_split_vertices():
    positions = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    tris = [(0, 1, 2), (0, 2, 3)]
    n = ((0.0, 0.0, 1.0),) * 3
    # Vertex 0 and 2 have different UVs in the two triangles (a seam): split.
    uvs = [(((0.0, 0.0),), ((1.0, 0.0),), ((1.0, 1.0),)), (((0.5, 0.0),), ((1.0, 1.0),), ((0.0, 0.75),))]
    (obj,) = scene.mesh_objects("Quad", [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], positions, tris,
                                [n, n], ["M", "M"], uvs)
    assert len(obj["positions"]) == 5 and "texcoords1" not in obj
    assert obj["texcoords"] == [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.5, 1.0], [0.0, 0.25]]   # v = 1 − v_b
    (plain,) = scene.mesh_objects("Quad", [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], positions, tris,
                                  [n, n], ["M", "M"])
    assert "texcoords" not in plain and len(plain["positions"]) == 4


# ----------------------------------------------------------------------------- pixels and files

def test_pixels_png_puts_blenders_bottom_row_last(tmp_path):
    # 2×2, Blender's order: bottom row first. Top-left texel red, bottom-right blue.
    bottom = [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0]
    top = [1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0]
    data = textures.pixels_png(2, 2, bottom + top)
    # support.read_png reads RGB; bake a square (the identity on 0 and 1) to get RGB and check the order.
    rgb = textures.bake(2, 2, bottom + top, {"channel": "rgb", "colorspace": "linear"}, {"op": "square"}, False)
    path = tmp_path / "t.png"
    path.write_bytes(rgb)
    w, h, depth, samples = read_png(str(path))
    assert (w, h, depth) == (2, 2, 16)
    assert samples == [65535, 0, 0, 65535, 65535, 65535, 0, 65535, 0, 0, 0, 65535]
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[25] == 6          # colour type 6: RGBA


def test_bake_square_and_srgb(tmp_path):
    px = [0.5, 0.25, 0.0, 1.0]
    png = textures.bake(1, 1, px, {"channel": "g", "colorspace": "linear"}, {"op": "square"}, False)
    path = tmp_path / "s.png"
    path.write_bytes(png)
    assert read_png(str(path))[3] == [round(0.0625 * 65535)] * 3
    png = textures.bake(1, 1, px, {"channel": "r", "colorspace": "srgb"}, {"op": "square"}, False)
    path.write_bytes(png)
    assert read_png(str(path))[3] == [round(textures.srgb_decode(0.5) ** 2 * 65535)] * 3
    png = textures.bake(1, 1, px, {"channel": "r", "colorspace": "srgb"}, {"op": "square"}, True)   # float: linear
    path.write_bytes(png)
    assert read_png(str(path))[3] == [round(0.25 * 65535)] * 3


def test_bake_square_with_a_factor(tmp_path):
    png = textures.bake(1, 1, [0.5, 0.6, 0.0, 1.0], {"channel": "g", "colorspace": "linear"},
                        {"op": "square", "scale": 0.5}, False)
    path = tmp_path / "s.png"
    path.write_bytes(png)
    assert read_png(str(path))[3] == [round(0.09 * 65535)] * 3


def test_file_names_are_unique():
    taken = set()
    assert textures.file_name("checker.png", ".png", None, taken) == "checker.png"
    assert textures.file_name("Checker", ".png", None, taken) == "Checker_2.png"
    assert textures.file_name("checker", ".png", {"op": "square"}, taken) == "checker_square.png"
    assert textures.file_name("a/b c", ".jpg", None, taken) == "a_b_c.jpg"


def test_facet_reads_what_apply_writes(facet, tmp_path):
    """The material JSON and the baked PNGs are accepted by facet (facet generate)."""
    r = map_surface(checker_and_roughness(), "Textured")
    files = {}
    px = [v for k in range(16) for v in ((k % 2) * 1.0, (k // 4) / 3.0, 0.5, 1.0)]
    for b in r.textures:
        name = f"{b['spec']['image']}.png"
        data = textures.bake(4, 4, px, b["spec"], b["derive"], False) if b.get("derive") else \
            textures.pixels_png(4, 4, px)
        (tmp_path / name).write_bytes(data)
        files[textures.file_key(b)] = (name, None)
    data, _ = textures.apply({"name": "Textured", "diffuse": r.diffuse, "specular": r.specular}, r.textures, files)
    path = tmp_path / "m.json"
    path.write_text(json.dumps(data))
    proc = subprocess.run([facet, "generate", str(path), "--target", "osl", "-o", str(tmp_path / "m.osl")],
                          stderr=subprocess.PIPE, text=True)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "m.osl").read_text()
    assert "facet_texture_diffuse_color" in text and "facet_texture_specular_alpha" in text
    absolute = textures.absolute(data, "/x")
    assert absolute["diffuse"]["color"]["texture"] == os.path.join("/x", "checker.png")
    # Generate OSL's material file, in a folder of its own, names its images where they were
    # written: facet reads images elsewhere only with --allow-path (issue 28).
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    moved = elsewhere / "m.json"
    moved.write_text(json.dumps(textures.absolute(data, str(tmp_path))))
    command = [facet, "generate", str(moved), "--target", "osl", "-o", str(elsewhere / "m.osl")]
    proc = subprocess.run(command, stderr=subprocess.PIPE, text=True)
    assert proc.returncode == 1 and "cannot be used" in proc.stderr and "--allow-path" in proc.stderr, proc.stderr
    allow = generate.allow_texture_folders(textures.absolute(data, str(tmp_path)))
    assert allow == ["--allow-path", str(tmp_path)]
    proc = subprocess.run(command + allow, stderr=subprocess.PIPE, text=True)
    assert proc.returncode == 0, proc.stderr


def test_facet_generates_what_apply_writes_of_a_principled_bsdf(facet, tmp_path):
    """The gltf_pbr lobe with its three maps (one image read for B and G) is accepted by facet."""
    r = map_surface(gltf_maps(), "Textured")
    px = [v for k in range(16) for v in ((k % 2) * 1.0, (k // 4) / 3.0, 0.5, 1.0)]
    files = {}
    for b in r.textures:
        (tmp_path / f"{b['spec']['image']}.png").write_bytes(textures.pixels_png(4, 4, px))
        files[textures.file_key(b)] = (f"{b['spec']['image']}.png", None)
    data, notes = textures.apply({"name": "Textured", "specular": r.specular}, r.textures, files)
    assert not notes and data["specular"]["metallic"]["texture"] == data["specular"]["roughness"]["texture"]
    (tmp_path / "m.json").write_text(json.dumps(data))
    proc = subprocess.run([facet, "generate", str(tmp_path / "m.json"), "--target", "glsl"],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.returncode == 0, proc.stderr
    assert "facet_texture_specular_base_color" in proc.stdout and "facet_texture_specular_roughness" in proc.stdout


def test_a_material_files_textures_round_trip():
    """split + binding_of_json + apply give back the file's texture objects (uv written out)."""
    tex_kd = {"texture": "textures/checker.png", "filter": "nearest", "wrap": "mirror", "factor": 0.8,
              "transform": {"offset": [0.1, 0.2], "scale": [3, 2], "rotation": 0.5}}
    tex_alpha = {"texture": "r16.png", "wrap": ["clamp", "repeat"], "channel": "g", "uv": 1}
    data = {"name": "T", "diffuse": {"model": "lambert", "color": tex_kd},
            "specular": {"model": "ggx", "alpha": tex_alpha, "fresnel": {"model": "schlick", "f0": 0.04}}}
    numbers, found = textures.split(data)
    assert numbers["diffuse"] == {"model": "lambert", "color": 0.8}
    assert numbers["specular"] == {"model": "ggx", "fresnel": {"model": "schlick", "f0": 0.04}}
    bindings = [textures.binding_of_json(path, tex, numbers[path[0]]["model"], os.path.basename(tex["texture"]))
                for path, tex in found]
    files = {textures.file_key(b): (b["spec"]["image"], None) for b in bindings}
    again, notes = textures.apply(dict(numbers, diffuse={"model": "lambert", "color": [1, 1, 1]},
                                       specular={"model": "ggx", "alpha": 0.5}), bindings, files)
    assert not notes
    assert again["diffuse"]["color"] == dict(tex_kd, texture="checker.png", uv=0)
    assert again["specular"]["alpha"] == dict(tex_alpha, texture="r16.png")
    assert textures.uv_maps(bindings) == ["", "#1"]


def test_a_layers_textures_round_trip_by_their_list_index():
    """A texture inside the material's "layers" list: its path holds the index, messages write
    it as facet does (layers[1].weight), and apply puts it back into the same layer."""
    tex = {"texture": "textures/metal_roughness.png", "channel": "b", "factor": 0.9}
    data = {"name": "L", "diffuse": {"model": "lambert"},
            "layers": [{"model": "sheen", "color": [1, 1, 1]}, {"model": "clearcoat", "weight": tex}]}
    numbers, found = textures.split(data)
    assert numbers["layers"] == [{"model": "sheen", "color": [1, 1, 1]}, {"model": "clearcoat", "weight": 0.9}]
    assert found == [(["layers", 1, "weight"], tex)]
    assert textures.key_path(found[0][0]) == "layers[1].weight"
    assert textures.model_at(numbers, found[0][0]) == {"model": "clearcoat", "weight": 0.9}
    bindings = [textures.binding_of_json(path, t, textures.model_at(numbers, path)["model"], "mr.png")
                for path, t in found]
    files = {textures.file_key(b): ("mr.png", None) for b in bindings}
    again, notes = textures.apply(numbers, bindings, files)
    assert not notes
    assert again["layers"][1]["weight"] == {"texture": "mr.png", "channel": "b", "factor": 0.9, "uv": 0}
    # The layer's model changed since: left out, and said with the layer's path.
    other = dict(numbers, layers=[numbers["layers"][0], {"model": "sheen"}])
    again, notes = textures.apply(other, bindings, files)
    assert "made for the layers[1] model clearcoat" in notes[0]
    assert textures.absolute(data, "/m")["layers"][1]["weight"]["texture"] == "/m/textures/metal_roughness.png"


def test_mesh_tangents_go_to_world_space_and_mirroring_flips_w():
    positions = [(0, 0, 0), (1, 0, 0), (1, 1, 0)]
    n = ((0.0, 0.0, 1.0),) * 3
    uvs = [(((0.0, 0.0),), ((1.0, 0.0),), ((1.0, 1.0),))]
    tangent = [((1.0, 0.0, 0.0, 1.0),) * 3]
    rot_z = [[0.0, -2.0, 0, 0], [2.0, 0.0, 0, 0], [0, 0, 2.0, 0], [0, 0, 0, 1.0]]      # 90° about Z, scale 2
    (obj,) = scene.mesh_objects("T", rot_z, positions, [(0, 1, 2)], [n], ["M"], uvs, tangent)
    # Blender's +X turned to +Y, in facet's axes (x, z, −y): (0, 0, −1); w kept.
    assert [pytest.approx(c, abs=1e-12) for c in obj["tangents"][0]] == [0.0, 0.0, -1.0, 1.0]
    mirror = [[-1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]]
    (obj,) = scene.mesh_objects("T", mirror, positions, [(0, 1, 2)], [n], ["M"], uvs, tangent)
    assert obj["tangents"][0] == [-1.0, 0.0, -0.0, -1.0]                                # B = w (N × T) kept
    (obj,) = scene.mesh_objects("T", mirror, positions, [(0, 1, 2)], [n], ["M"], uvs, [None])
    assert "tangents" not in obj


@pytest.mark.parametrize("specular_factor", [0.5, 1.0])
def test_a_specular_level_image_is_gltfs_specular_texture(specular_factor):
    """Blender's importer: Specular IOR Level = specularTexture's A × 0.5·specularFactor (a Math
    Multiply): specular = the image's A × specularFactor."""
    values = {"Base Color": [0.8, 0.4, 0.2, 1.0], "Metallic": 0.25, "Roughness": 0.5, "IOR": 1.5,
              "Specular IOR Level": 0.5}
    level = math_multiply(tex_image(image("spec", "Non-Color"), "Alpha"), 0.5 * specular_factor)
    node = {"type": "BSDF_PRINCIPLED", "name": "P", "distribution": "GGX", "inputs": values,
            "linked": ["Specular IOR Level"], "sources": {"Specular IOR Level": level}}
    r = map_surface(node, "Spec")
    (b,) = r.textures
    assert b["path"] == ["specular", "specular"] and b["spec"]["channel"] == "a" and "derive" not in b
    assert b["factor"] == pytest.approx(specular_factor)
    assert not any("unlinked value" in m for m in messages(r))


def test_a_specular_image_in_blender_3_is_named():
    values = {"Base Color": [0.8, 0.4, 0.2, 1.0], "Specular": 0.5, "Specular Tint": 0.0}
    node = {"type": "BSDF_PRINCIPLED", "name": "P", "inputs": values, "linked": ["Specular"],
            "sources": {"Specular": tex_image(image("spec", "Non-Color"))}}
    r = map_surface(node, "Spec")
    assert r.textures == [] and any("'Specular'" in m and "unlinked value" in m for m in messages(r, IGNORED))


def test_values_of_the_vertex_colour_are_named_as_unmapped():
    """A material value that takes the vertex colour, or an offset, has no place in the add-on
    yet: unmapped_values names it (the import refuses the material with those keys)."""
    repo = os.path.join(os.path.dirname(__file__), "..", "..", "..", "..")
    with open(os.path.join(repo, "examples", "textured", "textured_vertex_color.json")) as f:
        data = json.load(f)
    assert textures.unmapped_values(data) == ["ambient", "diffuse.color", "specular.alpha", "specular.fresnel.f0"]
    with open(os.path.join(repo, "examples", "textured", "textured_ggx.json")) as f:
        assert textures.unmapped_values(json.load(f)) == []


# ----------------------------------------------------------------------------- vertex colours

VERTEX_COLOR = {"type": "VERTEX_COLOR", "name": "Color Attribute", "output": "Color", "layer": ""}


def product(a, b):
    """A Mix (Multiply, factor 1) of two linked sources: Blender's importer's "Mix Vertex Color"."""
    return {"type": "MIX", "name": "Mix Vertex Color", "output": "Result", "data_type": "RGBA",
            "blend_type": "MULTIPLY", "clamp": False, "factor": 1.0, "factor_linked": False,
            "a": a, "a_value": [1.0] * 4, "b": b, "b_value": [1.0] * 4}


def test_a_color_attribute_is_the_vertex_colour_on_base_color():
    """COLOR_0 as Blender's glTF importer wires it without a texture (the Color Attribute through
    the baseColorFactor's Mix): base_color = baseColorFactor·COLOR_0, facet's vertex colour with a
    factor, exact, no image."""
    src = principled({"Base Color": mix(VERTEX_COLOR, [0.5, 0.25, 1.0, 1.0])}, Metallic=0.6)
    r = map_surface(src, "Tinted")
    (base,) = r.textures
    assert base["path"] == ["specular", "base_color"] and base["model"] == "gltf_pbr"
    assert base["spec"] == {"vertex_color": True, "layer": ""} and not textures.has_image(base)
    assert base["factor"] == pytest.approx([0.5, 0.25, 1.0])
    assert textures.uv_maps(r.textures) == [] and textures.vertex_color_layers(r.textures) == [""]
    data, notes = textures.apply({"name": "Tinted", "specular": r.specular}, r.textures, {})
    assert not notes
    assert data["specular"]["base_color"] == {"vertex_color": True, "factor": pytest.approx([0.5, 0.25, 1.0])}
    assert data["specular"]["metallic"] == pytest.approx(0.6)
    assert any("Color Attribute -> \"vertex_color\" on base_color" in m for m in messages(r, EXACT))
    assert not any("unlinked value" in m for m in messages(r))


def test_an_image_times_a_color_attribute_keeps_both(facet, tmp_path):
    """Blender's importer's "Mix Vertex Color" (the image times the Color Attribute, either side)
    -> the texture with "vertex_color": true, which facet accepts."""
    for a, b in ((tex_image(image()), VERTEX_COLOR), (VERTEX_COLOR, tex_image(image()))):
        r = map_surface(principled({"Base Color": product(a, b)}), "Checker")
        (base,) = [x for x in r.textures if x["path"] == ["specular", "base_color"]]
        assert base["spec"]["image"] == "checker" and base["spec"]["vertex_color"] is True
    files = {textures.file_key(base): ("checker.png", None)}
    (tmp_path / "checker.png").write_bytes(textures.pixels_png(2, 2, [1.0, 0.5, 0.25, 1.0] * 4))
    data, _ = textures.apply({"name": "Checker", "specular": r.specular}, r.textures, files)
    color = data["specular"]["base_color"]
    assert color["vertex_color"] is True and color["texture"] == "checker.png"
    (tmp_path / "m.json").write_text(json.dumps(data))
    proc = subprocess.run([facet, "generate", str(tmp_path / "m.json"), "--target", "glsl"],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.returncode == 0, proc.stderr
    assert "facet_color0" in proc.stdout


def test_a_color_attribute_elsewhere_is_named():
    """Into a number socket, or its Alpha output: no facet equivalent, named."""
    r = map_surface(principled({"Roughness": VERTEX_COLOR,
                                "Base Color": dict(VERTEX_COLOR, output="Alpha")}), "Odd")
    assert r.textures == []
    assert sum("vertex colour multiplies colours only" in m for m in messages(r, IGNORED)) == 2


def test_mesh_colors_are_written_per_vertex_and_split_vertices():
    positions = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    tris = [(0, 1, 2), (0, 2, 3)]
    n = ((0.0, 0.0, 1.0),) * 3
    red, green, blue = (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 0.5), (0.0, 0.0, 1.0, 1.0)
    # Vertex 0 is red in one triangle and blue in the other (a face-corner colour): split.
    colors = [(red, green, blue), (blue, blue, green)]
    (obj,) = scene.mesh_objects("Quad", [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], positions, tris,
                                [n, n], ["M", "M"], None, None, colors)
    assert len(obj["positions"]) == 5
    assert obj["colors"] == [list(red), list(green), list(blue), list(blue), list(green)]


def test_a_color_attribute_into_emission_is_named():
    r = map_surface(principled({"Emission Color": VERTEX_COLOR}, **{"Emission Color": [0.5, 0.5, 0.5, 1.0]}), "Glow")
    assert r.textures == []
    assert any("'Color Attribute' (VERTEX_COLOR)" in m and "material 'Glow'" in m for m in messages(r, IGNORED))


def test_a_color_attribute_two_mixes_deep_into_emission_is_named():
    src = mix(product(tex_image(image("glow")), VERTEX_COLOR), [0.5, 0.5, 0.5, 1.0])
    r = map_surface(principled({"Emission Color": src}, **{"Emission Color": [0.5, 0.5, 0.5, 1.0]}), "Glow")
    assert not any(b["path"] == ["emission"] for b in r.textures)
    assert any("'Color Attribute' (VERTEX_COLOR)" in m for m in messages(r, IGNORED))


def test_an_anisotropic_gltf_pbr_lobe_reads_the_active_uv_maps_frame():
    """glTF's anisotropy turns from the mesh's tangent (KHR_materials_anisotropy), which facet
    computes from texture coordinates set 0: the export writes the active render UV map for it
    even where no texture reads one; an isotropic lobe, or another model, reads none."""
    def lobe(**values):
        return {"specular": {"model": "gltf_pbr", **values}}
    assert textures.frame_uv_map(lobe(anisotropy_strength=0.5)) == ""
    assert textures.frame_uv_map(lobe(anisotropy_strength={"texture": "a.png", "channel": "b"})) == ""
    assert textures.frame_uv_map(lobe(anisotropy_strength=0)) is None
    assert textures.frame_uv_map(lobe()) is None
    assert textures.frame_uv_map({"specular": {"model": "ward", "anisotropy_strength": 0.5}}) is None
    assert textures.frame_uv_map({"diffuse": {"model": "lambert"}}) is None


def test_images_on_specular_and_sheen_tint_and_sheen_roughness_are_gltfs_textures():
    """Blender's glTF exporter writes an image on Specular Tint as specularColorTexture, one on
    Sheen Tint as sheenColorTexture and one on Sheen Roughness as sheenRoughnessTexture
    (KHR_materials_specular, _sheen): bindings of gltf_pbr's specular_color, sheen_color (the
    Sheen Weight its factor) and sheen_roughness (the channel the link reads)."""
    tint = tex_image(image("tint"))
    r = map_surface(principled({"Specular Tint": tint, "Sheen Tint": tex_image(image("sheen"))},
                               **{"Sheen Weight": 0.5, "Sheen Roughness": 0.3}), "Tinted")
    by_path = {tuple(b["path"]): b for b in r.textures}
    assert set(by_path) == {("specular", "specular_color"), ("specular", "sheen_color")}
    assert by_path[("specular", "specular_color")]["spec"]["image"] == "tint"
    assert "factor" not in by_path[("specular", "specular_color")]
    assert by_path[("specular", "sheen_color")]["factor"] == pytest.approx(0.5)
    assert r.specular["specular_color"] == [1.0, 1.0, 1.0] and r.specular["sheen_color"] == [0.5, 0.5, 0.5]
    assert not any("unlinked value" in m for m in messages(r))
    rough = map_surface(principled({"Sheen Roughness": tex_image(image("rough", "Non-Color"), output="Alpha")},
                                   **{"Sheen Weight": 1.0}), "Rough")
    [binding] = rough.textures
    assert tuple(binding["path"]) == ("specular", "sheen_roughness")
    assert binding["spec"]["image"] == "rough" and binding["spec"]["channel"] == "a"
    assert not any("unlinked value" in m for m in messages(rough))
    assert any("sheenRoughnessTexture" in m for m in messages(rough, EXACT))
