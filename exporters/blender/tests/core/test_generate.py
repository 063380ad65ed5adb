"""core/generate.py: material files checked, written and read through facet; code generated."""

import json
import os

import pytest

from facet_blender.core import UserError, cli, generate
from support import example


def lambert():
    with open(example("materials", "lambert.json"), encoding="utf-8") as f:
        return json.load(f)


def out_of_range():
    data = lambert()
    data["specular"] = {"model": "ggx", "alpha": 0.0}           # facet needs α > 0
    return data


@pytest.mark.parametrize("name, expected", [
    ("Paint", "Paint"), ("Red Paint/2", "Red_Paint_2"), ("..hidden", "hidden"), ("Ölfarbe", "lfarbe"),
    ("???", "material"), ("a.b-c_d", "a.b-c_d")])
def test_safe_name(name, expected):
    assert generate.safe_name(name) == expected


def test_osl_text_name():
    assert generate.osl_text_name("My Mat") == "facet_My_Mat.osl"


def test_write_material_temp_names_the_material_for_messages(tmp_path):
    path, replace = generate.write_material_temp(str(tmp_path), lambert(), "Red Paint")
    assert path == str(tmp_path / "Red_Paint.json")
    assert json.loads((tmp_path / "Red_Paint.json").read_text()) == lambert()
    assert replace == {path: "material 'Red Paint'"}


def test_export_material_writes_what_facet_accepts(tmp_path, facet):
    out = tmp_path / "paint.json"
    generate.export_material(facet, lambert(), "Paint", str(out))
    assert json.loads(out.read_text()) == lambert()


def test_export_material_refused_keeps_the_old_file_and_names_the_material(tmp_path, facet):
    out = tmp_path / "mirror.json"
    out.write_text("previous\n")
    with pytest.raises(cli.FacetError) as e:
        generate.export_material(facet, out_of_range(), "Mirror", str(out))
    assert "specular.alpha" in str(e.value) and "material 'Mirror'" in str(e.value)
    assert "Mirror.json" not in str(e.value)                    # not the temporary file
    assert out.read_text() == "previous\n"
    assert os.listdir(tmp_path) == ["mirror.json"]


def test_read_material(tmp_path, facet):
    assert generate.read_material(facet, example("materials", "ggx.json"))["specular"]["model"] == "ggx"
    with pytest.raises(UserError, match="no such file"):
        generate.read_material(facet, str(tmp_path / "missing.json"))
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(out_of_range()))
    with pytest.raises(cli.FacetError, match="specular.alpha"):
        generate.read_material(facet, str(bad))


def test_check_material_uses_the_label(facet):
    generate.check_material(facet, lambert(), "glTF material 'x'")
    with pytest.raises(cli.FacetError) as e:
        generate.check_material(facet, out_of_range(), "glTF material 'x'")
    assert all(line.startswith("error: glTF material 'x'") for line in e.value.lines)


@pytest.mark.parametrize("target, library, first", [
    ("glsl", False, "#version 330 core"), ("glsl450", False, "#version 450"), ("essl", False, "#version 300 es")])
def test_code_to_writes_each_dialect(tmp_path, facet, target, library, first):
    out = tmp_path / "paint.glsl"
    generate.code_to(facet, lambert(), "Paint", str(out), target, library)
    assert out.read_text().startswith(first)


def test_code_to_library_has_the_reflect_function_and_no_main(tmp_path, facet):
    out = tmp_path / "lib.glsl"
    generate.code_to(facet, lambert(), "Paint", str(out), "glsl", library=True)
    code = out.read_text()
    assert "facet_reflect" in code and "void main" not in code


def test_code_to_refused_writes_nothing(tmp_path, facet):
    out = tmp_path / "mirror.glsl"
    with pytest.raises(cli.FacetError, match="material 'Mirror'"):
        generate.code_to(facet, out_of_range(), "Mirror", str(out), "glsl")
    assert os.listdir(tmp_path) == []


def test_osl_shader_is_lit_by_the_scenes_lights(facet):
    scene = {"name": "s", "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
             "ambient": [0.0, 0.0, 0.0],
             "objects": [{"type": "sphere", "name": "o", "center": [0, 0, 0], "radius": 1}],
             "lights": [{"type": "point", "position": [1.5, 2.5, 3.5], "color": [1, 1, 1]},
                        {"type": "point", "position": [-4.25, 1, 2], "color": [0.5, 0.5, 0.5]}]}
    text = generate.osl_shader(facet, lambert(), "Paint", scene, "Scene")
    assert "shader" in text
    assert "-4.25" in text                                     # the lights are baked into the shader
    scene["lights"][0]["color"] = [1, 1]
    with pytest.raises(cli.FacetError, match="scene 'Scene'"):
        generate.osl_shader(facet, lambert(), "Paint", scene, "Scene")


def test_texturable_material_keys_follow_the_schema(facet):
    """The material-level keys this facet takes an image on: emission, ambient and a cut-out's
    alpha where the schema lets them be a texture object (normal_map where meshes take tangents);
    alpha_cutoff, one plain number, is none of them."""
    keys = generate.texturable_material_keys(facet)
    props = cli.material_schema(facet)["properties"]
    for key in ("emission", "ambient", "alpha"):
        assert (key in keys) == ("texture" in json.dumps(props.get(key, {}))), key
    assert "alpha" in keys and "alpha_cutoff" not in keys
