"""core/native.py: which Blender nodes stand in for a facet material, and the catalog's
blender_nodes agreeing with it (the figures themselves are measured in Blender:
run_tests.py, test_native_nodes_match_published_error)."""

import json
import math
import subprocess

import pytest

from facet_blender.core import UserError, native


def test_lambert_and_emission_sum():
    plan = native.node_plan({"name": "m", "diffuse": {"model": "lambert", "color": [0.8, 0.5, 0.3]},
                             "emission": [0.1, 0.0, 0.0]})
    assert [n["type"] for n in plan] == [native.DIFFUSE, native.EMISSION]
    assert plan[0]["inputs"] == {"Color": (0.8, 0.5, 0.3), "Roughness": 0.0}
    assert plan[1]["inputs"] == {"Color": (0.1, 0.0, 0.0), "Strength": 1.0}


def test_roughness_mappings():
    ggx = native.lobe_node("specular", {"model": "ggx", "alpha": 0.09}, principled=False)
    assert ggx["type"] == native.GLOSSY and ggx["props"] == {"distribution": "GGX"}
    assert ggx["inputs"]["Roughness"] == pytest.approx(0.3)
    assert ggx["inputs"]["Color"] == pytest.approx((0.04, 0.04, 0.04))      # k_s 1 × Schlick's default f0
    metal = native.lobe_node("specular", {"model": "ggx", "alpha": 0.09, "color": 0.5})
    assert metal["type"] == native.PRINCIPLED and metal["props"] == {"distribution": "GGX"}
    assert sorted(metal["inputs"]) == ["Base Color", "Metallic", "Roughness"] and metal["inputs"]["Metallic"] == 1.0
    assert metal["inputs"]["Base Color"] == pytest.approx((0.02, 0.02, 0.02))  # k_s ⊗ f0
    assert metal["inputs"]["Roughness"] == pytest.approx(0.3)
    glass = native.lobe_node("specular", {"model": "ggx", "alpha": 0.09, "fresnel": {"model": "exact", "ior": 1.33}})
    assert glass["inputs"]["IOR"] == 1.33 and glass["inputs"]["Metallic"] == 0.0
    assert glass["inputs"]["Specular Tint"] == (1.0, 1.0, 1.0) and glass["inputs"]["Base Color"] == (0.0, 0.0, 0.0)
    plain = native.lobe_node("specular", {"model": "ggx", "alpha": 0.09, "fresnel": {"model": "none"}})
    assert plain["type"] == native.GLOSSY and plain["inputs"]["Color"] == (1.0, 1.0, 1.0)
    ct = native.lobe_node("specular", {"model": "cook_torrance", "m": 0.25, "color": 1})
    assert ct["props"] == {"distribution": "BECKMANN"} and ct["inputs"]["Roughness"] == pytest.approx(0.5)
    assert ct["inputs"]["Color"] == pytest.approx((0.04, 0.04, 0.04))       # F(0) of ior 1.5
    blinn = native.lobe_node("specular", {"model": "blinn", "c": 0.5, "color": 1,
                                          "fresnel": {"model": "none"}})
    assert blinn["inputs"]["Color"] == pytest.approx((1.0, 1.0, 1.0))       # 4c² = 1
    s = 0.5
    a, b = 1 - 0.5 * s * s / (s * s + 0.33), 0.45 * s * s / (s * s + 0.09)
    on = native.lobe_node("diffuse", {"model": "oren_nayar", "sigma": s, "color": 0.5})
    assert on["inputs"]["Roughness"] == pytest.approx(b / a) and on["inputs"]["Color"] == (0.5, 0.5, 0.5)
    assert native.oren_nayar_roughness(0.0) == (0.0, 1.0)


def test_gltf_pbr_is_the_principled_bsdf_blenders_gltf_importer_builds():
    """glTF-Blender-IO 4.5: Specular IOR Level = 0.5·specularFactor, Specular Tint = specularColorFactor."""
    node = native.lobe_node("specular", {"model": "gltf_pbr", "base_color": [0.8, 0.2, 0.1], "metallic": 0.25,
                                         "roughness": 0.4, "ior": 1.8, "specular": 0.6,
                                         "specular_color": [1.0, 0.6, 0.3]})
    assert node["type"] == native.PRINCIPLED and node["props"] == {"distribution": "GGX"}
    assert node["inputs"] == {"Base Color": (0.8, 0.2, 0.1), "Metallic": 0.25, "Roughness": 0.4, "IOR": 1.8,
                              "Specular IOR Level": pytest.approx(0.3), "Specular Tint": (1.0, 0.6, 0.3)}
    coated = native.lobe_node("specular", {"model": "gltf_pbr", "clearcoat": 0.5, "clearcoat_roughness": 0.2})
    assert (coated["inputs"]["Coat Weight"], coated["inputs"]["Coat Roughness"]) == (0.5, 0.2)
    defaults = native.lobe_node("specular", {"model": "gltf_pbr"})["inputs"]
    assert (defaults["Specular IOR Level"], defaults["IOR"], defaults["Roughness"]) == (0.5, 1.5, 0.5)
    with pytest.raises(UserError, match="'gltf_pbr' with a colour other than white"):
        native.lobe_node("specular", {"model": "gltf_pbr", "color": 0.5})
    old = native.lobe_node("specular", {"model": "gltf_pbr", "ior": 2.0, "specular": 0.5}, principled=False)
    assert old["inputs"]["Specular"] == pytest.approx((1 / 3) ** 2 * 0.5 / 0.08)     # Blender 3.x: f0 = 0.08·Specular


def test_layers_have_no_blender_nodes():
    with pytest.raises(UserError, match=r"has layers over its lobes \(sheen, clearcoat\), which no Blender node makes"):
        native.node_plan({"name": "V", "diffuse": {"model": "lambert"},
                          "layers": [{"model": "sheen"}, {"model": "clearcoat"}]})


def test_refusals_name_the_model():
    with pytest.raises(UserError, match="'phong' has no Blender-node equivalent"):
        native.node_plan({"diffuse": {"model": "lambert"}, "specular": {"model": "phong", "n": 10}})
    with pytest.raises(UserError, match="'blinn_phong' with toon has no Blender-node equivalent"):
        native.lobe_node("specular", {"model": "blinn_phong", "n": 8, "toon": {"cutoff": 0.5}})
    with pytest.raises(UserError, match="'oren_nayar' with toon"):
        native.lobe_node("diffuse", {"model": "oren_nayar", "sigma": 0.3, "toon": {"cutoff": 0.5}})


def test_toon_steps_on_the_angle_where_rho_is_the_cutoff():
    """lambert: n·l = c at acos(c); phong: (r·v)^n = c at acos(c^(1/n)), Schlick's
    x/(n − n x + x) = c at acos(n c/(1 + c(n − 1))); colour k·2(1 − cos θ_s)."""
    step = native.lobe_node("diffuse", {"model": "lambert", "color": 0.5, "toon": {"cutoff": 0.4}})
    assert step["type"] == native.TOON and step["props"]["component"] == "DIFFUSE"
    assert step["inputs"]["Size"] == pytest.approx(math.acos(0.4) / (math.pi / 2)) and step["inputs"]["Smooth"] == 0
    assert step["inputs"]["Color"] == pytest.approx((0.5 * 2 * 0.6,) * 3)
    ramp = native.lobe_node("diffuse", {"model": "lambert", "toon": {"cutoff": 0.4, "width": 0.2}})
    assert ramp["inputs"]["Size"] == pytest.approx(math.acos(0.5) / (math.pi / 2))
    assert ramp["inputs"]["Smooth"] == pytest.approx((math.acos(0.3) - math.acos(0.5)) / (math.pi / 2))
    assert ramp["inputs"]["Color"] == pytest.approx((2 * 0.7,) * 3)
    phong = native.lobe_node("specular", {"model": "phong", "n": 4, "toon": {"cutoff": 0.3}})
    assert phong["props"]["component"] == "GLOSSY"
    assert phong["inputs"]["Size"] == pytest.approx(math.acos(0.3 ** 0.25) / (math.pi / 2))
    schlick = native.lobe_node("specular", {"model": "phong", "n": 4, "approximation": "schlick",
                                            "toon": {"cutoff": 0.3}})
    x = 4 * 0.3 / (1 + 0.3 * 3)
    assert x / (4 - 4 * x + x) == pytest.approx(0.3)
    assert schlick["inputs"]["Size"] == pytest.approx(math.acos(x) / (math.pi / 2))
    dark = native.lobe_node("diffuse", {"model": "lambert", "toon": {"cutoff": 1.5}})
    assert dark["inputs"]["Color"] == (0.0, 0.0, 0.0)


def test_catalog_publishes_what_the_add_on_builds(facet):
    models = json.loads(subprocess.run([facet, "models", "--json"], check=True, capture_output=True,
                                       text=True).stdout)["sections"]
    for section in ("diffuse", "specular"):
        for m in models[section]:
            nodes = m["blender_nodes"]
            lobe = {"model": m["name"], **{p["name"]: p["default"] for p in m["parameters"]
                                           if p.get("required") or p["type"] == "number"}}
            lobe.pop("toon", None)
            lobe.pop("fresnel", None)
            try:
                native.lobe_node(section, lobe)
                built = True
            except UserError:
                built = False
            assert built == (nodes["kind"] != "none"), f"{m['name']}: catalog {nodes}, add-on builds: {built}"
            assert (nodes["error"] is not None) == (nodes["kind"] == "approximate")
            if nodes["error"] is not None:
                assert math.isfinite(nodes["error"]) and nodes["error"] > 0
