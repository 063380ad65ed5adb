"""core/catalog.py: the catalog as `facet models --json` and `facet schema` give it."""

import copy

import pytest

from facet_blender.core import UserError, catalog as catalog_mod, cli


def test_every_model_and_parameter_of_facet_is_in_the_catalog(facet, catalog):
    raw = cli.models(facet)
    assert catalog.version == str(raw["facet"])
    assert catalog.epsilon == float(raw["epsilon"])
    for section, models in raw["sections"].items():
        assert [m.name for m in catalog.models(section)] == [m["name"] for m in models]
        for data in models:
            model = catalog.model(section, data["name"])
            assert model.formula == data.get("formula", "")
            assert [p.name for p in model.params] == [p["name"] for p in data.get("parameters", [])]
            for p in data.get("parameters", []):
                param = model.param(p["name"])
                assert (param.type, param.default, param.required) == (p["type"], p.get("default"),
                                                                       bool(p.get("required")))
                if "choices" in p:
                    assert param.choices == tuple(p["choices"])
                if isinstance(p.get("range"), dict):
                    assert (param.range.min, param.range.max) == (p["range"]["min"], p["range"]["max"])


def test_the_lobe_sections_hold_the_known_models(catalog):
    diffuse = {m.name for m in catalog.models("diffuse")}
    specular = {m.name for m in catalog.models("specular")}
    assert {"lambert", "oren_nayar", "minnaert"} <= diffuse
    assert {"phong", "blinn_phong", "ggx", "beckmann", "cook_torrance", "ward"} <= specular
    assert catalog.has_model("fresnel", "schlick") and not catalog.has_model("diffuse", "ggx")
    with pytest.raises(KeyError):
        catalog.model("diffuse", "no_such_model")
    with pytest.raises(KeyError):
        catalog.model("diffuse", "lambert").param("no_such_parameter")


def test_material_keys_come_from_the_schema(catalog):
    keys = {k.name: k for k in catalog.material_keys}
    assert sorted(keys) == ["ambient", "emission", "tangent_axis"]
    assert keys["ambient"].kind == "color" and keys["emission"].kind == "color"
    assert keys["tangent_axis"].kind == "vector" and len(keys["tangent_axis"].default) == 3
    assert keys["emission"].default == (0.0, 0.0, 0.0)


def test_one_number_material_keys_are_not_colours(facet):
    """alpha and alpha_cutoff (a cut-out's coverage and threshold) take one number each: read
    as grey colours they were written as arrays facet refuses, and alpha_cutoff on every
    material would make each a cut-out."""
    schema = cli.material_schema(facet)
    scalars = {name for name, prop in schema["properties"].items() if prop.get("type") == "number"}
    assert {"alpha_cutoff"} <= scalars
    keys = {k.name for k in catalog_mod.parse(cli.models(facet), schema).material_keys}
    assert not keys & (scalars | {"alpha"})


def test_range_contains_with_exclusive_bounds():
    r = catalog_mod.Range(min=0.0, max=1.0, min_exclusive=True)
    assert not r.contains(0.0) and r.contains(1e-9) and r.contains(1.0) and not r.contains(1.0001)
    assert catalog_mod.Range().contains(-1e30)
    assert not catalog_mod.Range(max=2.0, max_exclusive=True).contains(2.0)


def test_a_catalog_in_another_format_is_refused(facet):
    raw, schema = cli.models(facet), cli.material_schema(facet)
    with pytest.raises(UserError, match="not in the expected format"):
        catalog_mod.parse({"version": 2}, schema)
    broken = copy.deepcopy(raw)
    del broken["sections"]["specular"][0]["name"]
    with pytest.raises(UserError, match="not in the expected format"):
        catalog_mod.parse(broken, schema)
    no_diffuse = copy.deepcopy(raw)
    no_diffuse["sections"]["diffuse"] = []
    with pytest.raises(UserError, match="no diffuse models"):
        catalog_mod.parse(no_diffuse, schema)
