"""core/convert.py: Blender BSDF nodes (as plain descriptions) -> facet lobes, and how exact."""

import math

import pytest

from facet_blender.core import UserError, convert
from facet_blender.core.convert import map_surface

DIFFUSE = {"type": "BSDF_DIFFUSE", "name": "D", "inputs": {"Color": [0.5, 0.4, 0.3, 1], "Roughness": 0.0}}
GLOSSY = {"type": "BSDF_GLOSSY", "name": "G", "distribution": "BECKMANN",
          "inputs": {"Color": [1, 1, 1, 1], "Roughness": 0.5}}


def test_diffuse_roughness_0_is_exactly_lambert():
    r = map_surface(DIFFUSE)
    assert r.diffuse == {"model": "lambert", "color": [0.5, 0.4, 0.3]} and r.specular is None
    assert r.exact
    assert r.headline() == "diffuse lambert (exact)"


def test_rough_diffuse_is_oren_nayar_approximately():
    r = map_surface(dict(DIFFUSE, inputs={"Color": [0.5, 0.5, 0.5, 1], "Roughness": 0.4}))
    assert r.diffuse["model"] == "oren_nayar" and r.diffuse["sigma"] == 0.4 and not r.exact


def test_add_shader_puts_the_lobes_together():
    r = map_surface({"type": "ADD_SHADER", "shaders": [DIFFUSE, GLOSSY]})
    assert r.diffuse == {"model": "lambert", "color": [0.5, 0.4, 0.3]}
    assert r.specular["model"] == "beckmann" and r.specular["m"] == pytest.approx(0.25)   # m = roughness²
    assert r.headline() == "diffuse lambert + specular beckmann (approximate)"
    assert r.summary()[0].startswith("exact:")                                          # exact notes first


def test_ggx_glossy():
    r = map_surface(dict(GLOSSY, distribution="GGX", inputs={"Color": [0.9, 0.8, 0.7, 1], "Roughness": 0.3}))
    assert r.specular == {"model": "ggx", "color": [0.9, 0.8, 0.7], "alpha": pytest.approx(0.09),
                          "geometry": "smith_ggx", "fresnel": {"model": "none"}}


def test_mix_shader_weights_the_colours():
    r = map_surface({"type": "MIX_SHADER", "name": "M", "inputs": {"Fac": 0.25}, "shaders": [DIFFUSE, GLOSSY]})
    assert r.diffuse["color"] == pytest.approx([0.375, 0.3, 0.225])
    assert r.specular["color"] == pytest.approx([0.25, 0.25, 0.25])


def _f0(lobe):
    """KHR_materials_specular's dielectric f0 of a gltf_pbr lobe: min(F0(ior)·specular_color, 1)·specular."""
    eta = lobe.get("ior", 1.5)
    return [min(((eta - 1) / (eta + 1)) ** 2 * c, 1.0) * lobe.get("specular", 1.0) for c in lobe["specular_color"]]


@pytest.mark.parametrize("inputs, f0, specular", [
    ({"IOR": 1.5, "Specular IOR Level": 0.5}, 0.04, 1.0),         # Blender 4.x defaults: glTF's core
    ({"IOR": 2.0, "Specular IOR Level": 0.5}, (1 / 3) ** 2, 1.0),
    ({"IOR": 1.5, "Specular IOR Level": 0.25}, 0.02, 0.5),        # specularFactor = 2·level
    ({"IOR": 1.5, "Specular IOR Level": 1.0}, 0.08, 1.0),         # 2·level > 1: the tint carries it
    ({"Specular": 0.5, "Specular Tint": 0.0}, 0.04, 1.0),         # Blender 3.x defaults
    ({"Specular": 1.0}, 0.08, 1.0)])
def test_principled_is_gltfs_brdf_as_blenders_exporter_writes_it(inputs, f0, specular):
    node = {"type": "BSDF_PRINCIPLED", "name": "P",
            "inputs": dict({"Base Color": [0.8, 0.2, 0.1, 1], "Metallic": 0.0, "Roughness": 0.5}, **inputs)}
    r = map_surface(node)
    assert r.diffuse is None and r.specular["model"] == "gltf_pbr"
    assert r.specular["base_color"] == pytest.approx([0.8, 0.2, 0.1])
    assert (r.specular["metallic"], r.specular["roughness"]) == (0.0, 0.5)
    assert _f0(r.specular) == pytest.approx([f0] * 3)
    assert r.specular.get("specular", 1.0) == specular
    assert not r.exact     # Cycles' Principled is not glTF's BRDF, and the notes say so
    assert any("docs/blender.md" in m for _, m in r.notes)


def test_principled_metal_is_the_lobe_at_metallic_1_and_unmapped_inputs_name_their_extension():
    r = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": {
        "Base Color": [0.9, 0.6, 0.3, 1], "Metallic": 1.0, "Roughness": 0.2, "Transmission Weight": 0.4}})
    assert r.diffuse is None
    assert (r.specular["base_color"], r.specular["metallic"]) == ([0.9, 0.6, 0.3], 1.0)
    assert any(level == convert.IGNORED and "Transmission" in m and "KHR_materials_transmission" in m
               for level, m in r.notes)


def test_anisotropic_is_gltfs_anisotropy_its_rotation_in_radians():
    """Blender's glTF exporter: anisotropyStrength = Anisotropic, anisotropyRotation = 2π·Anisotropic
    Rotation (Blender's rotation is in turns)."""
    inputs = {"Base Color": [0.9, 0.9, 0.9, 1], "Metallic": 1.0, "Roughness": 0.4, "IOR": 1.5,
              "Specular IOR Level": 0.5, "Anisotropic": 0.6, "Anisotropic Rotation": 0.125}
    r = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": inputs})
    assert r.specular["anisotropy_strength"] == 0.6
    assert r.specular["anisotropy_rotation"] == pytest.approx(math.pi / 4)
    assert not any(level == convert.IGNORED for level, _ in r.notes)
    off = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": dict(inputs, **{"Anisotropic": 0.0})})
    assert "anisotropy_strength" not in off.specular


def test_sheen_is_gltfs_sheen_its_weight_folded_into_the_colour():
    """Blender's glTF exporter writes sheenColorFactor = Sheen Tint and sheenRoughnessFactor = Sheen
    Roughness (its importer: Sheen Weight 1); a Weight other than 1 is folded into the colour, said."""
    inputs = {"Base Color": [0.3, 0.1, 0.6, 1], "Roughness": 0.6, "IOR": 1.5, "Specular IOR Level": 0.5,
              "Sheen Weight": 1.0, "Sheen Tint": [0.9, 0.5, 0.7, 1], "Sheen Roughness": 0.35}
    r = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": inputs})
    assert (r.specular["sheen_color"], r.specular["sheen_roughness"]) == ([0.9, 0.5, 0.7], 0.35)
    assert not any(level == convert.IGNORED for level, m in r.notes)
    half = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": dict(inputs, **{"Sheen Weight": 0.5})})
    assert half.specular["sheen_color"] == pytest.approx([0.45, 0.25, 0.35])
    assert any(level == convert.IGNORED and "Sheen Weight 0.5 is folded" in m for level, m in half.notes)  # a warning
    off = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": dict(inputs, **{"Sheen Weight": 0.0})})
    assert "sheen_color" not in off.specular


def test_coat_is_gltfs_clearcoat_and_what_gltf_cannot_say_of_it_is_named():
    """Blender's glTF importer: Coat Weight = clearcoatFactor, Coat Roughness = clearcoatRoughnessFactor
    (0.03, Blender's default, where the file has none); IOR 1.5, no tint, the surface's normal."""
    inputs = {"Base Color": [0.6, 0.04, 0.03, 1], "Roughness": 0.6, "IOR": 1.5, "Specular IOR Level": 0.5,
              "Coat Weight": 0.8, "Coat Roughness": 0.2, "Coat IOR": 1.5, "Coat Tint": [1, 1, 1, 1]}
    r = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": inputs})
    assert (r.specular["clearcoat"], r.specular["clearcoat_roughness"]) == (0.8, 0.2)
    assert not any(level == convert.IGNORED for level, _ in r.notes)
    assert "clearcoat" not in map_surface({"type": "BSDF_PRINCIPLED", "name": "P",
                                           "inputs": dict(inputs, **{"Coat Weight": 0.0})}).specular
    # A Coat Normal from a Bump node (no Normal Map node) is named, as the Normal's would be.
    odd = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "linked": ["Coat Normal"],
                       "sources": {"Coat Normal": {"type": "BUMP", "name": "Bump", "output": "Normal"}},
                       "inputs": dict(inputs, **{"Coat IOR": 1.8, "Coat Tint": [1, 0.5, 0.5, 1]})})
    for words in ("Coat IOR 1.8", "Coat Tint", "Coat Normal"):
        assert any(level == convert.IGNORED and words in m for level, m in odd.notes), words


def test_a_roughness_below_the_floor_is_kept_with_a_warning_not_an_error():
    r = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": {"Roughness": 0.02}})
    assert r.specular["roughness"] == 0.02
    assert any(level == convert.IGNORED and "floor" in m for level, m in r.notes)     # a warning


def test_a_mix_shader_weights_the_gltf_lobe_by_its_colour():
    principled = {"type": "BSDF_PRINCIPLED", "name": "P", "inputs": {"Base Color": [0.5, 0.5, 0.5, 1]}}
    r = map_surface({"type": "MIX_SHADER", "name": "M", "inputs": {"Fac": 0.25}, "shaders": [principled, None]})
    assert r.specular["color"] == [0.75] * 3 and r.specular["base_color"] == [0.5] * 3


def test_a_linked_input_makes_the_mapping_approximate():
    r = map_surface(dict(DIFFUSE, linked=["Color"]))
    assert not r.exact and any("linked" in m for _, m in r.notes)


def test_material_of_the_result():
    r = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": {"Emission Color": [1, 1, 1, 1],
                                                                          "Emission Strength": 3.0}})
    data = r.material("m")
    assert data["emission"] == [3.0, 3.0, 3.0] and data["name"] == "m"
    assert "emission" not in map_surface(DIFFUSE).material("m")


@pytest.mark.parametrize("tree, words", [
    (None, "no Diffuse, Glossy or Principled"),
    ({"type": "EMISSION", "name": "Glow"}, "(found: Glow)"),
    ({"type": "ADD_SHADER", "shaders": [DIFFUSE, DIFFUSE]}, "more than one diffuse"),
    (dict(GLOSSY, distribution="ASHIKHMIN_SHIRLEY"), "Ashikhmin"),
    (dict(GLOSSY, distribution="SHARP"), "nothing facet can render remains")])
def test_refusals(tree, words):
    with pytest.raises(UserError) as e:
        map_surface(tree)
    assert words in str(e.value)
