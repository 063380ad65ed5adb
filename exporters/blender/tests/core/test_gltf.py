"""core/gltf.py: facet's glTF extensions -> Blender settings, the inverse of core/scene.py's units."""

import math

import pytest

from facet_blender.core import UserError, gltf, scene

IDENTITY = [[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]]


@pytest.mark.parametrize("version", [(3, 4, 1), (4, 5, 15)])
@pytest.mark.parametrize("facet_light", [
    {"type": "point", "color": [18.0, 17.0, 16.0], "attenuation": "inverse_square"},
    {"type": "directional", "color": [0.35, 0.36, 0.42]},
    {"type": "spot", "color": [2.0, 0.5, 0.0], "attenuation": "inverse_square", "cutoff": 30.0}])
def test_blender_light_exports_back_to_the_facet_light(version, facet_light):
    facet_light = dict(facet_light)
    if facet_light["type"] == "spot":
        facet_light["exponent"] = 1.0 if version < (3, 5, 0) else 0.0
    settings, notes = gltf.blender_light(facet_light, version)
    assert not notes
    assert max(settings["color"]) == pytest.approx(1.0)
    light, _ = scene.light(dict(settings, name="probe", matrix=IDENTITY, use_nodes=False), version)
    assert light["type"] == facet_light["type"]
    assert light["color"] == pytest.approx(facet_light["color"], rel=1e-12)
    if facet_light["type"] == "spot":
        assert light["cutoff"] == pytest.approx(30.0, rel=1e-12)
        assert light["exponent"] == facet_light["exponent"]


def test_units():
    settings, _ = gltf.blender_light({"type": "point", "color": [2.0, 1.0, 0.0], "attenuation": "inverse_square"})
    assert settings == {"type": "POINT", "color": [1.0, 0.5, 0.0], "energy": pytest.approx(8 * math.pi ** 2),
                        "shadow_soft_size": 0.0}
    settings, _ = gltf.blender_light({"type": "directional", "color": [0.0, 0.0, 0.0]})
    assert settings["energy"] == 0.0 and settings["color"] == [1.0, 1.0, 1.0]


def test_what_blender_cannot_do_is_noted_or_refused():
    _, notes = gltf.blender_light({"type": "point", "color": [1, 1, 1]})
    assert notes and "attenuation" in notes[0]
    _, notes = gltf.blender_light({"type": "spot", "color": [1, 1, 1], "attenuation": "inverse_square",
                                   "exponent": 4.0}, (4, 5, 0))
    assert notes and "exponent" in notes[0]
    with pytest.raises(UserError, match="not a facet light"):
        gltf.blender_light({"type": "area", "color": [1, 1, 1]}, where="light 'L'")
    with pytest.raises(UserError, match="expected a colour"):
        gltf.blender_light({"type": "point", "color": [1, 1]})


def test_extensions_are_read_and_bad_ones_refused():
    m = {"name": "plastic", "diffuse": {"model": "lambert"}}
    assert gltf.material_of({"FACET_material": {"material": m}}, "glTF material 'x'") is m
    assert gltf.material_of({"KHR_materials_unlit": {}}, "m") is None
    assert gltf.material_of(None, "m") is None
    for bad in ({"FACET_material": {"material": 3}}, {"FACET_material": []}):
        with pytest.raises(UserError, match="glTF material 'x'"):
            gltf.material_of(bad, "glTF material 'x'")
    assert gltf.ambient_of({"FACET_scene": {"ambient": 0.25}}, "s") == [0.25, 0.25, 0.25]
    assert gltf.ambient_of({"FACET_scene": {}}, "s") is None
    with pytest.raises(UserError, match="FACET_scene.ambient"):
        gltf.ambient_of({"FACET_scene": {"ambient": [1, "x", 2]}}, "s")
    assert gltf.light_of({"FACET_light": {"type": "point"}}) == {"type": "point"}
    assert gltf.light_of({"FACET_light": 1}) is None


def test_check_material_keeps_the_fallback_of_a_material_facet_refuses(facet):
    gltf.check_material(facet, {"name": "ok", "diffuse": {"model": "lambert"}}, "glTF material 'ok'", "ok")
    with pytest.raises(UserError) as e:
        gltf.check_material(facet, {"name": "bad", "diffuse": {"model": "lambert", "color": [-1, 0, 0]}},
                            "glTF material 'bad'", "bad.001")
    text = str(e.value)
    assert "material 'bad.001' keeps only the glTF fallback" in text
    assert "glTF material 'bad' (FACET_material)" in text and "diffuse.color" in text
