"""core/convert.py: Blender BSDF nodes (as plain descriptions) -> facet lobes, and how exact."""

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


@pytest.mark.parametrize("inputs, f0", [
    ({"IOR": 1.5, "Specular IOR Level": 0.5}, 0.04),              # Blender 4.x defaults
    ({"IOR": 2.0, "Specular IOR Level": 0.5}, (1 / 3) ** 2),
    ({"Specular": 0.5, "Specular Tint": 0.0}, 0.04),              # Blender 3.x defaults
    ({"Specular": 1.0}, 0.08)])
def test_principled_dielectric_f0(inputs, f0):
    node = {"type": "BSDF_PRINCIPLED", "name": "P",
            "inputs": dict({"Base Color": [0.8, 0.2, 0.1, 1], "Metallic": 0.0, "Roughness": 0.5}, **inputs)}
    r = map_surface(node)
    assert r.specular["fresnel"] == {"model": "schlick", "f0": pytest.approx([f0] * 3)}
    assert r.diffuse == {"model": "lambert", "color": pytest.approx([0.8, 0.2, 0.1])}


def test_principled_metal_takes_the_base_colour_as_f0_and_has_no_diffuse_colour():
    r = map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": {
        "Base Color": [0.9, 0.6, 0.3, 1], "Metallic": 1.0, "Roughness": 0.2, "Sheen Weight": 0.5}})
    assert r.diffuse["color"] == [0.0, 0.0, 0.0]
    assert r.specular["fresnel"]["f0"] == pytest.approx([0.9, 0.6, 0.3])
    assert any(level == convert.IGNORED and "Sheen" in m for level, m in r.notes)


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
