"""A facet material -> the nearest tree of Blender's own shader nodes (plain data).

"Build Blender Nodes" (blender/native.py) builds what `node_plan()` returns, so the
material renders in Cycles on any device and in EEVEE, with the World and indirect
light, without OSL. How close each model comes is measured, not assumed: the catalog
publishes it (`facet models --json`, each lobe model's "blender_nodes": exact,
approximate with the worst |Δ|/max(1, |ref|) measured under one point light, or none)
and exporters/blender/tests/run_tests.py (test_native_nodes_match_published_error)
measures it again against facet's reference.

The mappings (ρ as MODELS.md defines it, relative to Lambert; Cycles' BSDFs are f_r):
- lambert: Diffuse BSDF, Roughness 0 (f = k_d/π): the same lobe.
- oren_nayar: Diffuse BSDF, Roughness r = B/A of the 1994 model, colour k_d. Cycles
  evaluates Fujii's improved Oren–Nayar, ρ = n·l·A'(1 + r·s/t), plus OpenPBR's
  energy-preserving multiscatter term; r = B/A gives the same ratio of the angular term
  to the constant one where cos φ ≥ 0. Measured on examples/materials/oren_nayar.json
  (σ = 0.5), k_d unscaled is nearest (0.043; scaled by A/A' 0.088, by A 0.148; r = σ
  0.043, 0.8·B/A 0.062, 1.3·B/A 0.059): the multiscatter term returns the energy
  that A' < 1 takes away.
- beckmann, cook_torrance: Glossy BSDF, Beckmann, Roughness √m (Cycles' α = Roughness²);
  the Fresnel term is taken at normal incidence into the colour (Cycles' Glossy BSDF
  has none), the masking is Cycles' Smith G.
- ggx: Principled BSDF (Blender 4.x), GGX (single scattering), Roughness √α, nothing
  but its specular layer: Schlick's Fresnel is a metal of Base Colour k_s ⊗ f0 (with
  Specular Tint white, 4.x's F82 metal is Schlick's; k_s ⊗ F = Schlick(k_s ⊗ f0) only for
  a white k_s), the exact one a dielectric of that IOR, Specular Tint k_s, Base Colour
  black. Without a Fresnel term, and before Blender 4 (whose Principled BSDF has another
  Fresnel and IOR), a Glossy BSDF, GGX, colour × F(0).
- blinn: D_TR(c) = π c² D_GGX(α = c), and Blinn's ρ lacks the 1/4 of a microfacet
  BRDF: Glossy BSDF, GGX, Roughness √c, colour × 4c² F(0).
- gltf_pbr: the Principled BSDF (Blender 4.x), GGX, as Blender's glTF importer builds it
  from the same glTF material: Base Color, Metallic, Roughness, IOR, Specular IOR Level =
  specular/2, Specular Tint = specular_color, Coat Weight and Coat Roughness = clearcoat and
  clearcoat_roughness, Sheen Weight 1, Sheen Tint = sheen_color and Sheen Roughness (a colour
  k_s other than white is refused);
  Blender 3.x: Specular = the dielectric f0 / 0.08. A GGX metal is glTF's exactly; a
  dielectric is Cycles' energy-compensated layering (docs/blender.md, F).
- emission: an Emission shader of strength 1 (radiance m_e).
- the toon modifier, ρ' = smoothstep(c − w/2, c + w/2, ρ): Toon BSDF, which steps on an
  angle (Cycles' bsdf_toon.h): the Diffuse one on angle(n, l), the Glossy one on the angle
  between l and v mirrored about n. lambert's ρ = n·l and phong's ρ = (r·v)^n are
  functions of exactly those angles, so ρ = c is an angle θ(c): Size θ(c + w/2)/(π/2),
  Smooth (θ(c − w/2) − θ(c + w/2))/(π/2). Cycles' value is 1/(2π(1 − cos θ_s)) with
  θ_s = min(π/2, Size + Smooth) and no cosine, so the colour is k·2(1 − cos θ_s): exact for
  width 0; with a width Cycles' ramp is linear in the angle where facet's smoothstep is in ρ.
  blinn_phong's ρ = (n·h)^n steps on angle(n, h), which is half the mirrored angle only in
  the plane of incidence: measured with Size 2θ(c)/(π/2), its band is elsewhere (0.80 off at
  n = 8), so it has no node, like the toon modifier on every other model.
Models without such a node (Minnaert, Phong, Blinn–Phong, …) are refused by name.
"""

import math

from . import UserError

DIFFUSE, GLOSSY, EMISSION, ADD = "ShaderNodeBsdfDiffuse", "ShaderNodeBsdfGlossy", "ShaderNodeEmission", \
    "ShaderNodeAddShader"
TOON = "ShaderNodeBsdfToon"
PRINCIPLED = "ShaderNodeBsdfPrincipled"


def _rgb(value, default=1.0):
    if value is None:
        value = default
    if isinstance(value, (int, float)):
        return (float(value),) * 3
    if isinstance(value, dict):
        raise UserError("a textured parameter has no Blender-node equivalent here: build nodes from "
                        "a material without textures")
    return tuple(float(c) for c in value[:3])


def _scaled(rgb, k):
    return tuple(c * k for c in rgb)


def _number(lobe, key, default=None):
    value = lobe.get(key, default)
    if isinstance(value, dict):
        raise UserError(f"'{key}' from a texture has no Blender-node equivalent here")
    return float(value)


FRESNEL_DEFAULTS = {"cook_torrance": {"model": "exact", "ior": 1.5}, "blinn": {"model": "exact", "ior": 1.5},
                    "ggx": {"model": "schlick", "f0": 0.04}, "beckmann": {"model": "none"}}


def fresnel_at_normal(model, lobe):
    """F(0) of the lobe's Fresnel term (its default where the lobe names none), as RGB."""
    fresnel = lobe.get("fresnel") or FRESNEL_DEFAULTS[model]
    kind = fresnel.get("model", "none")
    if kind == "schlick":
        return _rgb(fresnel.get("f0", 0.04))
    if kind == "exact":
        eta = float(fresnel.get("ior", 1.5))
        return (((eta - 1.0) / (eta + 1.0)) ** 2,) * 3
    return (1.0, 1.0, 1.0)


def oren_nayar_roughness(sigma, interreflection=False):
    """(Roughness, colour factor) of Cycles' Diffuse BSDF nearest the 1994 model's σ."""
    s2 = sigma * sigma
    a = 1.0 - 0.5 * s2 / (s2 + (0.57 if interreflection else 0.33))
    b = 0.45 * s2 / (s2 + 0.09)
    return min(1.0, b / a), 1.0


def _diffuse(lobe, principled=True):
    model, color = lobe["model"], _rgb(lobe.get("color"))
    if model == "lambert":
        return {"type": DIFFUSE, "inputs": {"Color": color, "Roughness": 0.0}}
    if model == "oren_nayar":
        r, k = oren_nayar_roughness(_number(lobe, "sigma"), bool(lobe.get("interreflection", False)))
        return {"type": DIFFUSE, "inputs": {"Color": _scaled(color, k), "Roughness": r}}
    return None


def _glossy(distribution, roughness, color):
    return {"type": GLOSSY, "props": {"distribution": distribution},
            "inputs": {"Color": color, "Roughness": math.sqrt(roughness)}}


def _principled_ggx(lobe, color):
    """The GGX lobe as Principled BSDF's specular layer (4.x), or None (no Fresnel term)."""
    fresnel = lobe.get("fresnel") or FRESNEL_DEFAULTS["ggx"]
    inputs = {"Roughness": math.sqrt(_number(lobe, "alpha")), "Base Color": (0.0, 0.0, 0.0), "Metallic": 0.0}
    if fresnel.get("model") == "exact":
        inputs.update({"IOR": float(fresnel.get("ior", 1.5)), "Specular Tint": color})
    elif fresnel.get("model") == "schlick":
        f0 = _rgb(fresnel.get("f0", 0.04))
        inputs.update({"Metallic": 1.0, "Base Color": tuple(c * f for c, f in zip(color, f0))})
    else:
        return None
    return {"type": PRINCIPLED, "props": {"distribution": "GGX"}, "inputs": inputs}


def _principled_gltf(lobe, color, principled):
    """glTF's BRDF as the Principled BSDF Blender's glTF importer makes of it (glTF-Blender-IO
    4.5: Specular IOR Level = specular/2, Specular Tint = specular_color, IOR; Sheen Weight 1,
    Sheen Tint and Roughness; Coat Weight and Roughness), GGX. Blender 3.x
    (`principled` False): Specular = the dielectric f0 / 0.08 (its f0 = 0.08·Specular), the
    largest channel of min(F0(ior)·specular_color, 1)·specular, Specular Tint 0."""
    if color != (1.0, 1.0, 1.0):
        raise UserError("specular model 'gltf_pbr' with a colour other than white has no Blender-node "
                        "equivalent (a Principled BSDF has no overall weight): set its color to 1")
    specular_color = _rgb(lobe.get("specular_color", 1.0))
    inputs = {"Base Color": _rgb(lobe.get("base_color", 0.8)), "Metallic": _number(lobe, "metallic", 0.0),
              "Roughness": _number(lobe, "roughness", 0.5)}
    eta, specular = _number(lobe, "ior", 1.5), _number(lobe, "specular", 1.0)
    coat = (_number(lobe, "clearcoat", 0.0), _number(lobe, "clearcoat_roughness", 0.0))
    if principled:
        inputs.update({"IOR": eta, "Specular IOR Level": 0.5 * specular, "Specular Tint": specular_color})
        if coat[0] > 0.0:
            inputs.update({"Coat Weight": coat[0], "Coat Roughness": coat[1], "Coat IOR": 1.5})
        strength = _number(lobe, "anisotropy_strength", 0.0)
        if strength > 0.0:
            inputs.update({"Anisotropic": strength,
                           "Anisotropic Rotation": _number(lobe, "anisotropy_rotation", 0.0) / (2.0 * math.pi)})
        sheen = _rgb(lobe.get("sheen_color", 0.0), 0.0)
        if any(sheen):
            inputs.update({"Sheen Weight": 1.0, "Sheen Tint": sheen,
                           "Sheen Roughness": _number(lobe, "sheen_roughness", 0.0)})
    else:
        f0 = max(min(((eta - 1.0) / (eta + 1.0)) ** 2 * c, 1.0) * specular for c in specular_color)
        inputs.update({"Specular": f0 / 0.08, "Specular Tint": 0.0})
        if coat[0] > 0.0:
            inputs.update({"Clearcoat": coat[0], "Clearcoat Roughness": coat[1]})
    return {"type": PRINCIPLED, "props": {"distribution": "GGX"}, "inputs": inputs}


def _specular(lobe, principled=True):
    model, color = lobe["model"], _rgb(lobe.get("color"))
    if model == "gltf_pbr":
        return _principled_gltf(lobe, color, principled)
    if model == "ggx" and principled:
        node = _principled_ggx(lobe, color)
        if node:
            return node
    if model in ("beckmann", "cook_torrance"):
        f0 = fresnel_at_normal(model, lobe)
        return _glossy("BECKMANN", _number(lobe, "m"), tuple(c * f for c, f in zip(color, f0)))
    if model == "ggx":
        f0 = fresnel_at_normal(model, lobe)
        return _glossy("GGX", _number(lobe, "alpha"), tuple(c * f for c, f in zip(color, f0)))
    if model == "blinn":
        c, f0 = _number(lobe, "c"), fresnel_at_normal(model, lobe)
        return _glossy("GGX", c, tuple(4.0 * c * c * k * f for k, f in zip(color, f0)))
    return None


def _power_cosine(model, lobe):
    """x ↦ the cosine where the lobe's ρ(cos) = x, for the lobes Toon BSDF can step on
    (their ρ is a function of the one cosine it measures)."""
    if model == "lambert":
        return lambda x: x
    n = _number(lobe, "n")
    if lobe.get("approximation") == "schlick":   # x = c / (n − n c + c)  ⇔  c = n x / (1 + x (n − 1))
        inverse = (lambda x: n * x / (1.0 + x * (n - 1.0)))
    else:
        inverse = (lambda x: x ** (1.0 / n))
    return inverse


TOON_MODELS = {"diffuse": ("lambert",), "specular": ("phong",)}


def toon_node(section, lobe):
    """The Toon BSDF standing in for a toon-modified lobe (the module's docstring derives it)."""
    model = lobe["model"]
    if model not in TOON_MODELS[section]:
        raise UserError(f"{section} '{model}' with toon has no Blender-node equivalent (Toon BSDF steps "
                        f"lambert's n·l and phong's r·v only)")
    toon = lobe["toon"]
    cutoff, width = float(toon.get("cutoff", 0.5)), float(toon.get("width", 0.0))  # the catalog's defaults
    inverse = _power_cosine(model, lobe)

    def angle(x):    # the angle Toon BSDF measures where ρ = x; ρ ≤ 0 never reaches the band
        return math.acos(min(1.0, inverse(min(1.0, x)))) if x > 0.0 else math.pi / 2.0
    inner, outer = angle(cutoff + width / 2.0), angle(cutoff - width / 2.0)
    if cutoff - width / 2.0 > 1.0:
        inner = outer = 0.0   # ρ ≤ 1 never reaches the band: nothing is lit
    sample = min(math.pi / 2.0, outer)
    colour = _scaled(_rgb(lobe.get("color")), 2.0 * (1.0 - math.cos(sample)) if sample > 0.0 else 0.0)
    return {"type": TOON, "props": {"component": "DIFFUSE" if section == "diffuse" else "GLOSSY"},
            "inputs": {"Color": colour, "Size": min(1.0, inner / (math.pi / 2.0)),
                       "Smooth": min(1.0, (outer - inner) / (math.pi / 2.0))}}


def summary(blender_nodes):
    """The panel's line for a model's published blender_nodes (None: the catalog has none)."""
    if not blender_nodes:
        return "Blender nodes: not published by this facet"
    kind = blender_nodes.get("kind")
    if kind == "exact":
        return "Blender nodes: exact (within 2e-3)"
    if kind == "approximate":
        return f"Blender nodes: approximate, worst measured |Δ|/max(1, |ref|) {blender_nodes['error']:.2g}"
    return f"Blender nodes: none ({blender_nodes.get('nodes', '').split(':')[0]})"


def lobe_node(section, lobe, principled=True):
    """The node (a dict: type, inputs, props) standing in for one lobe, or UserError.
    `principled`: Blender's Principled BSDF is 4.x's (Fresnel of its IOR, F82 metals)."""
    if lobe.get("toon"):
        return toon_node(section, lobe)
    node = (_diffuse if section == "diffuse" else _specular)(lobe, principled)
    if node is None:
        raise UserError(f"{section} model '{lobe['model']}' has no Blender-node equivalent "
                        f"(the catalog says so: facet models --json, blender_nodes)")
    return node


def node_plan(material, principled=True):
    """The nodes for a facet material JSON (a dict), in the order they are summed by Add
    Shader nodes: [node, ...]. Ambient is left out (Cycles' World lights the material)."""
    if material.get("layers"):   # a layer weights the lobes' sum by what it reflects: no Add Shader does
        names = ", ".join(layer.get("model", "?") for layer in material["layers"])
        raise UserError(f"material '{material.get('name', '')}' has layers over its lobes ({names}), which no "
                        f"Blender node makes (the catalog says so: facet models --json, blender_nodes); Generate OSL "
                        f"(Cycles) and the facet POV-Ray engine render them")
    plan = [lobe_node(s, material[s], principled) for s in ("diffuse", "specular") if material.get(s)]
    emission = material.get("emission")
    if emission is not None and any(c != 0.0 for c in _rgb(emission)):
        plan.append({"type": EMISSION, "inputs": {"Color": _rgb(emission), "Strength": 1.0}})
    if not plan:
        raise UserError(f"material '{material.get('name', '')}' has no lobe and no emission")
    return plan
