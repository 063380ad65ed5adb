"""core/props.py: the property plan made from the catalog, and values <-> material JSON."""

import json
import os
import subprocess

import pytest

from facet_blender.core import UserError, convert, generate, props
from facet_blender.core.catalog import slot_models
from support import example

EXAMPLES = sorted(n for n in os.listdir(example("materials")) if n.endswith(".json"))
LAYERED = sorted(n for n in os.listdir(example("layered")) if n.endswith(".json"))
DIRECTIONS = [{"n": [0, 0, 1], "l": [0.3, 0.2, 0.9], "v": [-0.4, 0.1, 0.8], "t": [1, 0, 0]},
              {"n": [0, 0, 1], "l": [0.0, 0.7, 0.7], "v": [0.0, -0.6, 0.8], "t": [0, 1, 0]},
              {"n": [0, 0, 1], "l": [0.9, 0.0, 0.1], "v": [0.1, 0.1, 1.0], "t": [1, 0, 0]}]


def load(name, folder="materials"):
    with open(example(folder, name), encoding="utf-8") as f:
        return json.load(f)


def evaluate(facet, path):
    proc = subprocess.run([facet, "eval", path], input=json.dumps(DIRECTIONS), stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True, check=True)
    return json.loads(proc.stdout)


def test_labels_ids_and_tooltips():
    assert props.label("alpha_x") == "Alpha X"
    assert props.label("n") == "n" and props.label("f0") == "f0"
    assert props.label("exact_ior") == "Exact IOR"
    assert props.field_id("name") == "p_name" and props.field_id("model") == "p_model"
    assert props.field_id("sigma") == "sigma"
    assert props.tooltip("exponent; larger is tighter", "a number ≥ 1") == \
        "Exponent; larger is tighter. Allowed: a number ≥ 1."
    assert props.tooltip("") == ""


def test_the_plan_has_a_group_per_lobe_model_with_the_catalogs_parameters(catalog, plan):
    assert plan.name == props.MATERIAL_GROUP
    for section in ("diffuse", "specular"):
        models = catalog.models(section)
        choice = plan.field(f"{section}_model")
        assert [i[0] for i in choice.items] == [props.NONE] + [m.name for m in models]
        for m in models:
            group = plan.field(f"{section}_{m.name}").group
            assert group.name == f"FACET_PG_{section}_{m.name}"
            by_key = {f.key: f for f in group.fields}
            for p in m.params:
                if p.type == "object" and not catalog.has_model(p.section, p.name):
                    continue
                f = by_key[p.name]
                if p.type == "number":
                    assert (f.kind, f.default, f.min, f.max) == ("float", float(p.default if p.default is not None
                                                                                    else 0.0),
                                                                 p.range.min if p.range else None,
                                                                 p.range.max if p.range else None)
                elif p.type == "string" and p.choices:
                    assert f.kind == "enum" and [i[0] for i in f.items] == list(p.choices)
                elif p.type == "model":
                    assert f.kind == "group" and f.nested == "model"
                    assert [i[0] for i in f.group.field("model").items] == [x.name for x in
                                                                            catalog.models(p.section)]
                assert p.doc[:10].lower() in f.doc.lower() or not p.doc


def test_groups_are_registered_nested_first(plan):
    order = props.groups_in_registration_order(plan)
    assert order[-1] is plan
    seen = set()
    for group in order:
        for f in group.fields:
            if f.kind == "group":
                assert f.group.name in seen, f"{group.name} registered before {f.group.name}"
        seen.add(group.name)
    assert len(seen) == len(order)              # every class name once


def test_every_model_with_its_defaults_is_a_material_facet_accepts(facet, catalog, plan):
    for section, other in (("diffuse", "specular"), ("specular", "diffuse")):
        for m in catalog.models(section):
            values = props.default_values(plan)
            values[f"{section}_model"], values[f"{other}_model"] = m.name, props.NONE
            data = props.material_to_json(catalog, plan, values, f"{section} {m.name}")
            assert data[section]["model"] == m.name and other not in data
            generate.check_material(facet, data, f"{section} {m.name}")


def test_a_material_needs_a_lobe(catalog, plan):
    values = props.default_values(plan)
    values["diffuse_model"] = values["specular_model"] = props.NONE
    with pytest.raises(UserError, match="neither a diffuse nor a specular model"):
        props.material_to_json(catalog, plan, values, "Empty")


@pytest.mark.parametrize("name", EXAMPLES)
def test_examples_round_trip_to_the_same_reflectance(tmp_path, facet, catalog, plan, name):
    data = load(name)
    once = props.normalize_material(catalog, plan, data)
    assert props.normalize_material(catalog, plan, once) == once          # a second pass changes nothing
    assert once["name"] == data["name"]
    path = tmp_path / name
    path.write_text(json.dumps(once))
    assert evaluate(facet, str(path)) == evaluate(facet, example("materials", name))


@pytest.mark.parametrize("name", LAYERED)
def test_layered_examples_round_trip_through_the_layer_slots(tmp_path, facet, catalog, plan, name):
    """examples/layered: the layers go into the panel's slots, lowest first, and come back as the
    same list: facet evaluates the same reflectance. A layer with a lobe inside (mix), which the
    panel has no place for, is refused by name rather than imported without it."""
    data = load(name, "layered")
    held = {m.name for m in slot_models(catalog, "layer")}
    if any(layer["model"] not in held for layer in data["layers"]):
        with pytest.raises(UserError, match=r"layers\[\d\] is a mix layer, which the facet panel does not hold"):
            props.material_from_json(catalog, plan, data)
        return
    values = props.material_from_json(catalog, plan, data)
    for i, layer in enumerate(data["layers"]):
        assert values[f"layer{i}_model"] == layer["model"]
    once = props.normalize_material(catalog, plan, data)
    assert [layer["model"] for layer in once["layers"]] == [layer["model"] for layer in data["layers"]]
    assert props.normalize_material(catalog, plan, once) == once
    path = tmp_path / name
    path.write_text(json.dumps(once))
    assert evaluate(facet, str(path)) == evaluate(facet, example("layered", name))


def test_layer_slots_share_their_models_groups_and_hold_two(catalog, plan):
    layer_models = [m.name for m in slot_models(catalog, "layer")]
    assert layer_models, "facet's catalog has layer models"
    assert "mix" in [m.name for m in catalog.models("layer")] and "mix" not in layer_models, \
        "a layer with a lobe inside is not offered"
    for slot in ("layer0", "layer1"):
        assert [i[0] for i in plan.field(f"{slot}_model").items] == [props.NONE] + layer_models
        assert plan.field(f"{slot}_model").default == props.NONE
    for m in layer_models:
        assert plan.field(f"layer0_{m}").group is plan.field(f"layer1_{m}").group
    names = [g.name for g in props.groups_in_registration_order(plan)]
    assert len(names) == len(set(names)), "a shared group is registered once"
    three = {"name": "Three", "diffuse": {"model": "lambert"},
             "layers": [{"model": "sheen"}, {"model": "clearcoat"}, {"model": "clearcoat"}]}
    with pytest.raises(UserError, match="has 3 layers; the facet panel holds 2"):
        props.material_from_json(catalog, plan, three)
    # A slot left empty under a chosen one: the list has no gap.
    values = props.default_values(plan)
    values["layer1_model"] = "clearcoat"
    assert props.material_to_json(catalog, plan, values, "Gap")["layers"] == [
        {"model": "clearcoat", "weight": 1.0, "roughness": 0.0}]


def test_tangent_axis_is_edited_in_blenders_axes(catalog, plan):
    values = props.material_from_json(catalog, plan, load("ward.json"))      # facet's +Y up
    assert values["tangent_axis"] == [0.0, 0.0, 1.0]                        # Blender's +Z up
    values["tangent_axis"] = [1.0, 0.0, 0.0]
    values["diffuse_model"] = "lambert"
    values["diffuse_lambert"] = props.default_values(plan.field("diffuse_lambert").group)
    assert props.material_to_json(catalog, plan, values, "w")["tangent_axis"] == [1.0, 0.0, 0.0]
    values["tangent_axis"] = [0.0, 1.0, 0.0]                                # Blender +Y = facet -Z
    assert props.material_to_json(catalog, plan, values, "w")["tangent_axis"] == [0.0, 0.0, -1.0]


def test_float32_values_are_written_as_typed(catalog, plan):
    values = props.default_values(plan)
    values["specular_model"] = "ggx"
    values["specular_ggx"]["alpha"] = 0.30000001192092896                  # 0.3 stored as float32
    assert props.material_to_json(catalog, plan, values, "g")["specular"]["alpha"] == 0.3


def test_toon_and_fresnel_are_written_only_as_chosen(catalog, plan):
    values = props.material_from_json(catalog, plan, load("toon.json"))
    assert values["specular_blinn_phong"]["toon"]["enabled"] is True
    data = props.material_to_json(catalog, plan, values, "t")
    assert set(data["specular"]["toon"]) == {"cutoff", "width"}
    values["specular_blinn_phong"]["toon"]["enabled"] = False
    assert "toon" not in props.material_to_json(catalog, plan, values, "t")["specular"]
    glassy = props.normalize_material(catalog, plan, load("ggx_exact_fresnel.json"))
    assert glassy["specular"]["fresnel"] == {"model": "exact", "ior": 1.33}


def test_conversion_values_set_the_lobes_found(catalog, plan):
    result = convert.map_surface({"type": "BSDF_PRINCIPLED", "name": "P", "inputs": {
        "Base Color": [0.5, 0.5, 0.5, 1.0], "Roughness": 0.5, "Emission Color": [1.0, 0.5, 0.0, 1.0],
        "Emission Strength": 2.0}})
    values = props.conversion_values(catalog, plan, result)
    assert values[props.USE_FACET] is True
    assert (values["diffuse_model"], values["specular_model"]) == (props.NONE, "gltf_pbr")
    assert values["emission"] == [2.0, 1.0, 0.0]
    assert values["specular_gltf_pbr"]["base_color"] == [0.5, 0.5, 0.5]
    assert values["specular_gltf_pbr"]["roughness"] == 0.5
    data = props.material_to_json(catalog, plan, dict(props.default_values(plan), **values), "P")
    assert "diffuse" not in data and data["specular"]["model"] == "gltf_pbr"
    assert (data["specular"]["ior"], data["specular"]["specular"]) == (1.5, 1.0)
    glossy_only = convert.map_surface({"type": "BSDF_GLOSSY", "name": "G", "inputs": {"Roughness": 0.3}})
    values = props.conversion_values(catalog, plan, glossy_only)
    assert values["diffuse_model"] == props.NONE and values["emission"] == [0.0, 0.0, 0.0]
