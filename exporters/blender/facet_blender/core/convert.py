"""Blender shader nodes -> facet lobes: the mapping table.

The Blender layer describes the nodes that feed the Material Output's Surface as plain
data (see `map_surface`); these functions choose the facet models and parameters and
say how faithful each choice is. "Exact" means the facet model computes the same
radiance as Cycles for a point or sun light of radius 0 (see scene.py for the units).

| Blender node (Cycles)                     | facet                                               | how faithful |
|-------------------------------------------|-----------------------------------------------------|--------------|
| Diffuse BSDF, Roughness 0                 | lambert, color = Color                              | exact: Cycles' diffuse is ρ/π, facet's Lambert the same lobe |
| Diffuse BSDF, Roughness r > 0             | oren_nayar, color = Color, sigma = r                | approximate: Cycles uses Fujii's improved Oren–Nayar (4.3+: plus a multiscatter term), facet the 1994 qualitative model with σ in radians |
| Glossy BSDF, GGX, Roughness r             | ggx, color = Color, alpha = r², geometry smith_ggx, fresnel none | approximate: Cycles' masking-shadowing is the height-correlated Smith G, facet's the separable one (equal at normal incidence, differ at grazing angles) |
| Glossy BSDF, Multiscatter GGX             | as GGX                                              | approximate: Cycles adds multiple-scattering energy |
| Glossy BSDF, Beckmann, Roughness r        | beckmann, m = r², geometry smith_ggx, fresnel none  | approximate: Cycles uses Smith G for Beckmann |
| Glossy BSDF, Roughness 0 / Sharp          | (no specular lobe)                                  | a mirror reflects no point light |
| Glossy BSDF, Ashikhmin–Shirley            | refused                                             | no facet model |
| Principled BSDF                           | gltf_pbr (glTF's BRDF, its specular lobe alone): base_color = Base Color, metallic, roughness | as Blender's glTF exporter writes the node; approximate to Cycles, whose Principled layers an energy-compensated dielectric, multiscatter GGX and F82-tinted metals (docs/blender.md measures it) |
|   IOR (4.x)                               | ior (KHR_materials_ior)                             | |
|   Specular IOR Level, Specular Tint (4.x) | specular = 2·level, specular_color = Tint, an image on it too (KHR_materials_specular's specularColorTexture; 2·level > 1: specular 1, Tint × 2·level, as the exporter writes it) | |
|   Specular, Specular Tint (3.x)           | specular_color = 2·Specular·mix(1, Base/luminance(Base), Tint) (f0 = 0.08·Specular·tint) | approximate: 3.x's f90 |
|   Roughness below 0.0316                  | roughness as typed; α = roughness² is floored at 1e-3 | approximate (a warning, never an error) |
|   Emission (× Strength)                   | emission                                            | exact |
|   Coat Weight, Coat Roughness (4.x)       | clearcoat, clearcoat_roughness (KHR_materials_clearcoat) | Coat IOR other than 1.5, Coat Tint, Coat Normal: named in a warning |
|   Sheen Weight, Sheen Tint, Sheen Roughness (4.x) | sheen_color = Weight × Tint, an image on it too (sheenColorTexture), sheen_roughness, an image on it too (sheenRoughnessTexture) (KHR_materials_sheen) | – |
|   Anisotropic, Anisotropic Rotation (4.x)  | anisotropy_strength, anisotropy_rotation = 2π·rotation (KHR_materials_anisotropy) | Cycles' anisotropic GGX is parametrized otherwise (docs/blender.md) |
|   Sheen (3.x), Transmission, Subsurface, Diffuse Roughness, Alpha | ignored, each named in a warning (Alpha: a cut-out where Blender's glTF importer wired one) | |
| Add Shader (a, b)                         | the lobes of a and b together                       | as exact as a and b (one diffuse and one specular lobe at most) |
| Mix Shader (Fac f, a, b)                  | a's colours × (1−f), b's colours × f               | as exact as a and b |
| anything else                             | refused: "no Diffuse, Glossy or Principled BSDF feeds the Material Output" | |

Colours are linear RGB in both. A socket fed by an Image Texture (directly, or through
Separate Color, Mapping and UV Map nodes) and a Normal Map node become textured
parameters (`Result.textures`, see textures.py); a socket linked to anything else is
named in a warning (material, node name and type) and its unlinked value is used.
"""

import math

from . import UserError, textures
from .coords import clean_float

EXACT, APPROXIMATE, IGNORED = "exact", "approximate", "ignored"
NOTHING_TO_MAP = "no Diffuse, Glossy or Principled BSDF feeds the Material Output"
LUMINANCE = (0.2126, 0.7152, 0.0722)     # Rec. 709, Blender's default scene-linear luminance


class Result:
    """The facet lobes found, and one (level, message) note per mapping decision."""

    def __init__(self):
        self.diffuse = None
        self.specular = None
        self.emission = None
        self.notes = []
        self.textures = []          # textures.binding(...) of the textured parameters
        self.material_name = ""     # the Blender material's name, for messages
        self.alpha = None           # a cut-out: alpha (a number; an image is a binding at ["alpha"])
        self.alpha_cutoff = None    # ... and its threshold, facet's "alpha_cutoff" (None: opaque)

    def note(self, level, message):
        self.notes.append((level, message))

    @property
    def exact(self):
        return all(level == EXACT for level, _ in self.notes)

    def material(self, name):
        """A facet material object with the lobes found (emission only if any)."""
        data = {"name": name}
        if self.diffuse:
            data["diffuse"] = self.diffuse
        if self.specular:
            data["specular"] = self.specular
        if self.emission is not None and any(self.emission):
            data["emission"] = self.emission
        return data

    def cut_out(self, data):
        """`data` (a material JSON) with the cut-out found, if any: "alpha" and "alpha_cutoff"."""
        if self.alpha_cutoff is not None:
            data["alpha"], data["alpha_cutoff"] = self.alpha, self.alpha_cutoff
        return data

    def headline(self):
        """What was found, e.g. "diffuse lambert + specular ggx (approximate)"."""
        lobes = " + ".join(f"{s} {getattr(self, s)['model']}" for s in ("diffuse", "specular") if getattr(self, s))
        return f"{lobes} ({'exact' if self.exact else 'approximate'})"

    def summary(self):
        """One line per note, exact ones first."""
        order = {EXACT: 0, APPROXIMATE: 1, IGNORED: 2}
        return [f"{level}: {message}" for level, message in sorted(self.notes, key=lambda n: order[n[0]])]


def _rgb(value):
    if isinstance(value, (int, float)):
        return [float(value)] * 3
    return [float(x) for x in list(value)[:3]]


def _scale(rgb, w):
    return [c * w for c in rgb]


class _Node:
    """Accessors for one plain node description with linked-input bookkeeping."""

    def __init__(self, desc, result):
        self.desc, self.result = desc, result
        self.label = desc.get("name") or desc.get("type")
        self.inputs = desc.get("inputs", {})
        self.linked = set(desc.get("linked", ()))
        self.sources = desc.get("sources", {})
        self.textured = set()       # inputs whose texture the caller maps
        self.reported = set()       # linked inputs already named in a note

    def has(self, name):
        return name in self.inputs

    def get(self, name, default=None):
        if name not in self.inputs:
            return default
        if name in self.linked and name not in self.textured and name not in self.reported:
            self.reported.add(name)
            src = self.sources.get(name)
            by = f" (node {textures.node_label(src)})" if src else ""
            where = f"material '{self.result.material_name}': " if self.result.material_name else ""
            self.result.note(IGNORED if src else APPROXIMATE,
                             f"{where}{self.label}: input '{name}' is linked to other nodes{by}; "
                             f"its unlinked value {self._fmt(self.inputs[name])} is used")
        return self.inputs[name]

    def texture(self, name, want):
        """The texture spec of a linked input (textures.texture_of), or None: unlinked, or
        nothing facet can map (then a warning names the node, and `get` adds that the
        unlinked value is used)."""
        if name not in self.linked or name not in self.sources:
            return None
        ctx = textures.Context(self.result.material_name, f"{self.label}: {name}", self.result.note)
        spec = textures.texture_of(self.sources[name], want, ctx)
        self.reported.add(name)          # texture_of warned when it could not map it
        if spec is not None:
            self.textured.add(name)
        return spec

    def normal_map(self, name="Normal", key="normal_map"):
        """The `key` binding spec of the node's normal input `name` (Normal, or Principled's Coat
        Normal for coat_normal_map), or None."""
        if name not in self.sources:
            return None
        ctx = textures.Context(self.result.material_name, f"{self.label}: {name}", self.result.note)
        return textures.normal_map_of(self.sources[name], ctx, key)

    def first(self, names, default=None):
        """The value of the first input of `names` the node has (3.x vs 4.x names)."""
        for n in names:
            if n in self.inputs:
                return self.get(n)
        return default

    @staticmethod
    def _fmt(v):
        if isinstance(v, (list, tuple)):
            return "(" + ", ".join(f"{x:.3g}" for x in v[:3]) + ")"
        return f"{v:.3g}"


# ----------------------------------------------------------------------------- single nodes

def _bind(result, path, model, spec, factor=None, derive=None, offset=None):
    result.textures.append(textures.binding(path, model, spec, factor, derive, offset))


def _texture_exactness(result, node, what):
    result.note(EXACT, f"{node.label}: {what} from its image (the texel as Cycles reads it: Closest filter, "
                       f"or Linear on a Non-Color image)")


def diffuse_bsdf(node, weight, result):
    color_tex = node.texture("Color", "color")
    rough_tex = node.texture("Roughness", "number")
    color = _scale(_rgb(node.get("Color", (0.8, 0.8, 0.8))), weight)
    roughness = float(node.get("Roughness", 0.0))
    model = "oren_nayar" if (roughness > 0.0 or rough_tex) else "lambert"
    if color_tex:
        _bind(result, ("diffuse", "color"), model, color_tex, weight if weight != 1.0 else None)
        _texture_exactness(result, node, "colour")
    if model == "lambert":
        result.note(EXACT, f"{node.label} -> lambert (Cycles' diffuse is ρ/π, facet's Lambert the same lobe)")
        return {"model": "lambert", "color": color}
    if rough_tex:
        _bind(result, ("diffuse", "sigma"), model, rough_tex)
    result.note(APPROXIMATE, f"{node.label} (Roughness {'image' if rough_tex else f'{roughness:.3g}'}) -> oren_nayar "
                             f"sigma = Roughness (Cycles uses Fujii's improved Oren–Nayar, facet the 1994 "
                             f"qualitative model)")
    return {"model": "oren_nayar", "color": color, "sigma": roughness if roughness > 0.0 else 0.5}


def _alpha_texture(result, node, section, model, rough_tex):
    """α = Roughness² baked from a roughness image."""
    _bind(result, (section, "alpha" if model == "ggx" else "m"), model, rough_tex, derive={"op": "square"})
    result.note(APPROXIMATE, f"{node.label}: {'alpha' if model == 'ggx' else 'm'} = Roughness² baked per texel "
                             f"from image '{rough_tex['image']}' into a derived image (Cycles squares after "
                             f"filtering: equal with Closest)")


def _microfacet(node, result, distribution, roughness, color, fresnel, what):
    """ggx/beckmann lobe of Cycles' GGX/Beckmann (α = roughness²), or None for a mirror."""
    alpha = roughness * roughness
    if distribution == "ASHIKHMIN_SHIRLEY":
        raise UserError(f"{node.label}: the Ashikhmin–Shirley distribution has no facet model; "
                        f"use GGX or Beckmann")
    if distribution == "SHARP" or alpha <= 0.0:
        result.note(APPROXIMATE, f"{node.label}: roughness 0 is a perfect mirror, which reflects no point "
                                 f"light; no specular lobe")
        return None
    geometry_note = "Cycles' masking-shadowing is the height-correlated Smith G, facet's the separable Smith G"
    if distribution == "BECKMANN":
        result.note(APPROXIMATE, f"{what} -> beckmann m = Roughness² = {alpha:.4g}, geometry smith_ggx "
                                 f"(Cycles uses Smith G for Beckmann)")
        return {"model": "beckmann", "color": color, "m": alpha, "geometry": "smith_ggx", "fresnel": fresnel}
    extra = "; Multiscatter GGX adds multiple-scattering energy" if distribution == "MULTI_GGX" else ""
    result.note(APPROXIMATE, f"{what} -> ggx alpha = Roughness² = {alpha:.4g}, geometry smith_ggx "
                             f"({geometry_note}{extra})")
    return {"model": "ggx", "color": color, "alpha": alpha, "geometry": "smith_ggx", "fresnel": fresnel}


def glossy_bsdf(node, weight, result):
    color_tex = node.texture("Color", "color")
    rough_tex = node.texture("Roughness", "number")
    color = _scale(_rgb(node.get("Color", (0.8, 0.8, 0.8))), weight)
    roughness = float(node.get("Roughness", 0.5))
    if rough_tex and roughness <= 0.0:
        roughness = 0.5               # the lobe exists; its α comes from the image
    anisotropy = float(node.get("Anisotropy", 0.0)) if node.has("Anisotropy") else 0.0
    if anisotropy:
        result.note(IGNORED, f"{node.label}: Anisotropy {anisotropy:.3g} is ignored (isotropic lobe)")
    lobe = _microfacet(node, result, node.desc.get("distribution", "GGX"), roughness, color,
                       {"model": "none"}, f"{node.label} ({node.desc.get('distribution', 'GGX')})")
    if lobe and color_tex:
        _bind(result, ("specular", "color"), lobe["model"], color_tex, weight if weight != 1.0 else None)
        _texture_exactness(result, node, "colour")
    if lobe and rough_tex:
        _alpha_texture(result, node, "specular", lobe["model"], rough_tex)
    return lobe


def _cut_out(node, result):
    """A cut-out (glTF's alphaMode MASK) from the Principled BSDF's Alpha, where Blender's glTF
    importer wired its clip: Alpha = 1 − (a < c) (Math Subtract of 1 and a Math Less Than; a the
    base colour image's Alpha output, through a Math Multiply for the alpha factor) -> facet's
    "alpha" (the image's A channel, linear, × the factor) and "alpha_cutoff" c. Cycles takes
    alpha as coverage, so the clipped 0 or 1 is exactly a cut-out. Anything else linked into
    Alpha (a blend) is named by the caller's unmapped-input warning."""
    src = node.sources.get("Alpha")
    if src is None or src.get("type") != "MATH" or src.get("operation") != "SUBTRACT":
        return
    links, values = src.get("links") or [None, None], src.get("values") or [None, None]
    less = links[1]
    if links[0] is not None or values[0] != 1.0 or not less or less.get("type") != "MATH" \
            or less.get("operation") != "LESS_THAN":
        return
    inner, cutoff = (less.get("links") or [None, None]), (less.get("values") or [None, None])[1]
    if inner[1] is not None or not isinstance(cutoff, (int, float)):
        return
    ctx = textures.Context(result.material_name, f"{node.label}: Alpha", result.note)
    if inner[0] is None:
        alpha = float((less.get("values") or [1.0])[0])
        result.alpha, spec = alpha, None
    else:
        spec = textures.texture_of(inner[0], "number", ctx)
        if spec is None:
            return
        spec["colorspace"] = "linear"           # alpha is coverage, never colour-managed
        result.alpha = 1.0
    result.alpha_cutoff = clean_float(float(cutoff))        # Blender's float32, as typed
    node.textured.add("Alpha")
    node.reported.add("Alpha")
    if spec is not None:
        _bind(result, ("alpha",), None, spec)
    result.note(EXACT, f"{node.label}: Alpha = 1 − (alpha < {float(cutoff):.4g}) -> a cut-out: alpha "
                       + (f"from image '{spec['image']}' ({spec['channel']})" if spec else f"{result.alpha:.4g}")
                       + f", alpha_cutoff {float(cutoff):.4g} (glTF's alphaMode MASK as Blender's importer wires it)")


def _color_attribute_in(src):
    """The Color Attribute source under a chain of Mix nodes (what texture_of found there)."""
    if src is None or src.get("type") == "VERTEX_COLOR":
        return src
    for side in ("a", "b"):
        found = _color_attribute_in(src.get(side)) if src.get(side) else None
        if found is not None:
            return found
    return None


# (3.x name, 4.x name, value meaning "off", what it is) of inputs facet's gltf_pbr lobe has no
# parameter for: glTF's extension for it where there is one.
_PRINCIPLED_IGNORED = (
    (("Subsurface", "Subsurface Weight"), 0.0, "subsurface scattering: no glTF extension says it"),
    (("Sheen",), 0.0, "Blender 3.x's sheen, Disney's: glTF's KHR_materials_sheen is Blender 4's Sheen Weight"),
    (("Transmission", "Transmission Weight"), 0.0, "transmission: glTF's KHR_materials_transmission, which facet "
                                                   "does not implement"),
    (("Diffuse Roughness",), 0.0, "a rough diffuse: glTF's BRDF has a Lambert base"),
    (("Alpha",), 1.0, "alpha (transparency): facet's materials are opaque or cut out"),
)


def _specular_level(node, result, lobe, level_tex):
    """KHR_materials_specular as Blender's glTF exporter writes it from Specular IOR Level and
    Specular Tint (glTF-Blender-IO 4.5, exp/material/extensions/specular.py; its importer reads
    specularFactor back as Specular IOR Level = 0.5·specularFactor): specular = 2·level, and
    where that exceeds glTF's 1, specular 1 with the tint times 2·level. An image on Specular Tint
    is glTF's specularColorTexture: specular_color = the image times that factor."""
    tint_tex = node.texture("Specular Tint", "color")
    tint = [1.0, 1.0, 1.0] if tint_tex else _rgb(node.get("Specular Tint", (1.0, 1.0, 1.0)))
    level = max(float(node.get("Specular IOR Level", 0.5)), 0.0)
    factor = 2.0 * (level_tex.get("scale", 1.0) if level_tex else level)
    lobe["specular"] = min(factor, 1.0)
    lobe["specular_color"] = [t * max(factor, 1.0) for t in tint]
    if tint_tex:   # the image times the factor (a Mix's constant side, `scale`, folded by binding)
        _bind(result, ("specular", "specular_color"), "gltf_pbr", tint_tex, max(factor, 1.0) if factor > 1.0 else None)
        result.note(EXACT, f"{node.label}: specular_color from image '{tint_tex['image']}', glTF's "
                           f"specularColorTexture")
    if level_tex:
        spec = dict(level_tex)
        spec.pop("scale", None)
        _bind(result, ("specular", "specular"), "gltf_pbr", spec, min(factor, 1.0))
        result.note(EXACT, f"{node.label}: specular = 2·Specular IOR Level from image '{level_tex['image']}' "
                           f"({level_tex['channel']}), glTF's specularTexture")


def _coat(node, result, lobe):
    """KHR_materials_clearcoat as Blender's glTF exporter writes it from Coat Weight and Coat
    Roughness (its importer: Coat Weight = clearcoatFactor × clearcoatTexture's R, Coat Roughness =
    clearcoatRoughnessFactor × clearcoatRoughnessTexture's G). glTF's coat is fixed at IOR 1.5,
    untinted: another Coat IOR or Coat Tint is named. Its Coat Normal (a Normal Map node) is the
    material's coat_normal_map (_normal_map), as glTF's clearcoatNormalTexture."""
    maps = {"clearcoat": node.texture("Coat Weight", "number"),
            "clearcoat_roughness": node.texture("Coat Roughness", "number")}
    weight = min(max(float(node.get("Coat Weight", 0.0)), 0.0), 1.0)
    if weight == 0.0 and not maps["clearcoat"]:
        return
    lobe["clearcoat"] = weight
    lobe["clearcoat_roughness"] = min(max(float(node.get("Coat Roughness", 0.03)), 0.0), 1.0)
    for key, spec in maps.items():
        if spec:
            _bind(result, ("specular", key), "gltf_pbr", spec)
    result.note(EXACT, f"{node.label}: Coat Weight and Coat Roughness -> clearcoat, clearcoat_roughness "
                       f"(KHR_materials_clearcoat, as Blender's glTF exporter writes them)")
    if node.has("Coat IOR") and abs(float(node.get("Coat IOR", 1.5)) - 1.5) > 1e-6:
        result.note(IGNORED, f"{node.label}: Coat IOR {float(node.inputs['Coat IOR']):.3g} is ignored (glTF's clear "
                             f"coat has IOR 1.5)")
    if node.has("Coat Tint") and _rgb(node.get("Coat Tint", (1.0, 1.0, 1.0))) != [1.0, 1.0, 1.0]:
        result.note(IGNORED, f"{node.label}: Coat Tint is ignored (glTF's clear coat is untinted)")


def _sheen(node, result, lobe):
    """KHR_materials_sheen from Sheen Weight, Sheen Roughness and Sheen Tint (Blender 4.x):
    sheen_color = Weight × Tint, sheen_roughness = Roughness. Blender's glTF exporter
    (glTF-Blender-IO 4.5, exp/material/extensions/sheen.py) writes the Tint alone and its importer
    sets Weight 1: a Weight of 1 round-trips exactly; another Weight is folded into the colour
    (said). An image on Sheen Tint is glTF's sheenColorTexture (sheen_color = Weight × the image),
    one on Sheen Roughness glTF's sheenRoughnessTexture (sheen_roughness = the image: facet sums
    the sheen's albedo fit at every pixel)."""
    weight = min(max(float(node.get("Sheen Weight", 0.0)), 0.0), 1.0)
    if weight == 0.0:
        return
    tint_tex = node.texture("Sheen Tint", "color")
    tint = [1.0, 1.0, 1.0] if tint_tex else [min(max(c, 0.0), 1.0) for c in _rgb(node.get("Sheen Tint", (1.0, 1.0, 1.0)))]
    lobe["sheen_color"] = [weight * c for c in tint]
    if tint_tex:
        _bind(result, ("specular", "sheen_color"), "gltf_pbr", tint_tex, weight if weight != 1.0 else None)
        result.note(EXACT, f"{node.label}: sheen_color from image '{tint_tex['image']}', glTF's sheenColorTexture")
    rough_tex = node.texture("Sheen Roughness", "number")
    lobe["sheen_roughness"] = min(max(float(node.get("Sheen Roughness", 0.5)), 0.0), 1.0)
    if rough_tex:
        _bind(result, ("specular", "sheen_roughness"), "gltf_pbr", rough_tex)
        result.note(EXACT, f"{node.label}: sheen_roughness from image '{rough_tex['image']}' "
                           f"({rough_tex['channel']}), glTF's sheenRoughnessTexture")
    result.note(EXACT, f"{node.label}: Sheen Weight × Sheen Tint and Sheen Roughness -> sheen_color, sheen_roughness "
                       f"(KHR_materials_sheen)")
    if weight != 1.0:
        # A warning: what Blender's own exporter writes for this node differs.
        result.note(IGNORED, f"{node.label}: Sheen Weight {weight:.3g} is folded into sheen_color; Blender's glTF "
                             f"exporter writes Sheen Tint alone (as if the Weight were 1)")


def _anisotropy(node, result, lobe):
    """KHR_materials_anisotropy as Blender's glTF exporter writes it (glTF-Blender-IO 4.5,
    exp/material/extensions/anisotropy.py): anisotropy_strength = Anisotropic, anisotropy_rotation
    = 2π·Anisotropic Rotation (Blender's rotation is in turns). Cycles parametrizes its anisotropic
    GGX otherwise (docs/blender.md measures it); images on them (glTF's anisotropyTexture) are not
    taken: node.get names a linked input and uses its unlinked value."""
    strength = min(max(float(node.get("Anisotropic", 0.0)), 0.0), 1.0)
    if strength == 0.0:
        return
    lobe["anisotropy_strength"] = strength
    lobe["anisotropy_rotation"] = 2.0 * math.pi * float(node.get("Anisotropic Rotation", 0.0))
    result.note(EXACT, f"{node.label}: Anisotropic and Anisotropic Rotation -> anisotropy_strength, "
                       f"anisotropy_rotation = 2π·rotation (KHR_materials_anisotropy, as Blender's glTF exporter "
                       f"writes them)")
    if "Tangent" in node.linked:
        node.reported.add("Tangent")
        result.note(IGNORED, f"{node.label}: Tangent is not read (the anisotropy turns from the mesh's UV tangent)")


def principled_bsdf(node, weight, result):
    """(None, the gltf_pbr lobe, emission) of a Principled BSDF: glTF's material, read as Blender's
    glTF exporter writes the node (glTF-Blender-IO 4.5) and its importer wires it back, so a
    glTF file imported by Blender and exported by the add-on is the material `facet import-gltf`
    reads from the file. Base Color, Metallic and Roughness are the core's factors and maps;
    IOR is KHR_materials_ior; Specular IOR Level and Tint are KHR_materials_specular, Sheen
    KHR_materials_sheen, Coat Weight and Coat Roughness KHR_materials_clearcoat (4.x).
    Cycles renders the Principled BSDF with its own layering, which docs/blender.md measures."""
    _cut_out(node, result)
    four = node.has("Specular IOR Level")          # Blender 4.x
    maps = {"base_color": node.texture("Base Color", "color"), "metallic": node.texture("Metallic", "number"),
            "roughness": node.texture("Roughness", "number")}
    level_tex = node.texture("Specular IOR Level", "number") if four else None
    lobe = {"model": "gltf_pbr", "color": [weight] * 3,
            "base_color": [min(max(c, 0.0), 1.0) for c in _rgb(node.get("Base Color", (0.8, 0.8, 0.8)))],
            "metallic": min(max(float(node.get("Metallic", 0.0)), 0.0), 1.0),
            "roughness": min(max(float(node.get("Roughness", 0.5)), 0.0), 1.0)}
    for names, off, what in _PRINCIPLED_IGNORED:
        for n in names:
            if node.has(n) and float(node.inputs[n]) != off and not (n == "Alpha" and result.alpha_cutoff is not None):
                result.note(IGNORED, f"{node.label}: {n} {float(node.inputs[n]):.3g} is ignored ({what})")
    if four:
        lobe["ior"] = max(float(node.get("IOR", 1.5)), 0.0)
        _specular_level(node, result, lobe, level_tex)
        _sheen(node, result, lobe)
        _coat(node, result, lobe)
        _anisotropy(node, result, lobe)
    else:                                          # Blender 2.8-3.x: f0 = 0.08·Specular·tint at IOR 1.5
        specular = float(node.get("Specular", 0.5))
        tint = float(node.get("Specular Tint", 0.0)) if node.has("Specular Tint") else 0.0
        lum = sum(c * k for c, k in zip(lobe["base_color"], LUMINANCE))
        ctint = [c / lum for c in lobe["base_color"]] if lum > 0.0 else [1.0] * 3
        lobe["specular_color"] = [2.0 * specular * ((1.0 - tint) + ct * tint) for ct in ctint]
        result.note(APPROXIMATE, f"{node.label}: Blender 3.x's Specular {specular:.3g} and Specular Tint "
                                 f"{tint:.3g} -> specular_color (f0 = 0.08·Specular·tint, f90 1; Cycles 3.x's f90 "
                                 f"is not glTF's)")
    for key, spec in maps.items():
        if spec:
            _bind(result, ("specular", key), "gltf_pbr", spec)
            if "image" in spec:
                _texture_exactness(result, node, {"base_color": "Base Color", "metallic": "Metallic",
                                                  "roughness": "Roughness"}[key])
    if maps["base_color"] and maps["base_color"].get("vertex_color"):
        result.note(EXACT, f"{node.label}: Base Color times the Color Attribute -> \"vertex_color\" on base_color "
                           f"(glTF's COLOR_0, as Blender's importer wires it)")
    distribution = node.desc.get("distribution", "GGX")
    result.note(APPROXIMATE, f"{node.label} -> gltf_pbr, glTF's BRDF as Blender's glTF exporter writes this node "
                             f"(Cycles' Principled is not that BRDF: its dielectric is energy-compensated"
                             + (", its GGX multiscatter" if distribution == "MULTI_GGX" else "")
                             + (", its metals F82-tinted (Schlick's with a white Specular Tint)"
                                if lobe["metallic"] > 0.0 or maps["metallic"] else "")
                             + "; docs/blender.md measures the difference)")
    roughness = lobe["roughness"]
    if not maps["roughness"] and roughness * roughness < 1e-3:
        result.note(IGNORED, f"{node.label}: Roughness {roughness:.3g} is below facet's floor: α = roughness² is "
                             f"clamped to 1e-3 (Roughness 0.0316), as glTF's specification says to clamp a delta "
                             f"(Appendix B); a point light's highlight is wider and dimmer than Cycles' near-mirror")

    # Emission: radiance, the same on both sides; an image × Strength where facet takes
    # emission maps (the export checks; elsewhere the unlinked colour is used, and said).
    strength_value = float(node.inputs.get("Emission Strength", 1.0))
    for name in ("Emission Color", "Emission"):
        if name in node.inputs:
            emission_tex = node.texture(name, "color")
            if emission_tex and emission_tex.get("vertex_color"):
                vc = _color_attribute_in(node.sources[name])
                result.note(IGNORED, f"material '{result.material_name}': {node.label}: '{name}' is linked to "
                                     f"{textures.node_label(vc) if vc else 'a Color Attribute'}; the add-on maps the "
                                     f"vertex colour into a BSDF's colour only; the unlinked value is used")
                emission_tex = None
            if emission_tex:
                _bind(result, ("emission",), None, emission_tex, strength_value * weight)
                result.note(EXACT, f"{node.label}: emission = image '{emission_tex['image']}' × Emission Strength "
                                   f"(an emission map, where facet takes one)")
            break
    color = node.first(("Emission Color", "Emission"), (0.0, 0.0, 0.0))
    strength = float(node.get("Emission Strength", 1.0)) if node.has("Emission Strength") else 1.0
    emission = _scale(_rgb(color), strength * weight)
    if any(emission):
        result.note(EXACT, f"{node.label}: emission colour × strength -> emission")
    return None, lobe, emission


# ----------------------------------------------------------------------------- the tree

def _normal_map(node, result):
    """The node's Normal as the material's normal_map, and a Principled BSDF's Coat Normal as its
    coat_normal_map (KHR_materials_clearcoat's clearcoatNormalTexture: the coat's own normal, on
    the same tangent frame), where the material has a coat to map."""
    for name, key in (("Normal", "normal_map"), ("Coat Normal", "coat_normal_map")):
        if name not in node.linked and name != "Normal":
            continue
        if key == "coat_normal_map" and "clearcoat" not in (result.specular or {}):
            node.reported.add(name)
            result.note(IGNORED, f"{node.label}: Coat Normal is not read: the material has no coat (Coat Weight 0)")
            continue
        spec = node.normal_map(name, key)
        node.textured.add(name)
        if spec is None:
            continue
        if any(b["path"] == [key] for b in result.textures):
            if not any(b["path"] == [key] and b["spec"] == spec for b in result.textures):
                result.note(APPROXIMATE, f"material '{result.material_name}': {node.label}: a second, different "
                                         f"{name} map; facet's material has one: the first is used")
            continue
        base = next((b for b in result.textures if b["path"] == ["normal_map"]), None)
        if key == "coat_normal_map" and base and base["spec"].get("uv_map", "") != spec.get("uv_map", ""):
            result.note(APPROXIMATE, f"{node.label}: Coat Normal reads UV map '{spec.get('uv_map')}' where Normal "
                                     f"reads '{base['spec'].get('uv_map')}'; facet turns both on one tangent frame: "
                                     f"the coat takes the surface's own normal")
            continue
        _bind(result, (key,), None, spec)


def _unmapped_inputs(node, result):
    """Every other linked input is named in a warning: its unlinked value is used."""
    for name in sorted(node.linked - node.textured - node.reported):
        src = node.sources.get(name)
        if src is None:
            continue
        ctx = textures.Context(result.material_name, f"{node.label}: {name}", result.note)
        result.note(IGNORED, f"{ctx.where(src)}: this input is not mapped to facet; its unlinked value is used")


def _terms(desc, weight, result, out):
    """Flattens Add/Mix Shader trees into (weight, node description) terms."""
    if desc is None or weight == 0.0:
        return
    kind = desc.get("type")
    if kind == "ADD_SHADER":
        for child in desc.get("shaders", []):
            _terms(child, weight, result, out)
    elif kind == "MIX_SHADER":
        node = _Node(desc, result)
        fac = min(max(float(node.get("Fac", 0.5)), 0.0), 1.0)
        shaders = list(desc.get("shaders", [None, None])) + [None, None]
        _terms(shaders[0], weight * (1.0 - fac), result, out)
        _terms(shaders[1], weight * fac, result, out)
    else:
        out.append((weight, desc))


def map_surface(surface, material=""):
    """Maps the shader tree feeding the Material Output's Surface onto facet lobes.

    `surface` is None (nothing linked) or a node description:
        {"type": "BSDF_DIFFUSE" | "BSDF_GLOSSY" | "BSDF_PRINCIPLED" | "ADD_SHADER" |
                 "MIX_SHADER" | any other Blender node type,
         "name": the node's name, "distribution": Glossy/Principled distribution,
         "inputs": {socket name: unlinked value (number or RGBA)},
         "linked": [names of linked inputs],
         "shaders": [child description or None, ...]   (Add/Mix Shader)}
    Returns a Result; raises UserError when nothing maps or the lobes do not fit one
    facet material (one diffuse and one specular lobe)."""
    result = Result()
    result.material_name = material
    terms = []
    _terms(surface, 1.0, result, terms)
    handled = {"BSDF_DIFFUSE", "BSDF_GLOSSY", "BSDF_PRINCIPLED"}
    others = [d for _, d in terms if d.get("type") not in handled]
    if not terms or others:
        found = ", ".join(sorted({d.get("name") or d.get("type") for d in others}))
        raise UserError(NOTHING_TO_MAP + (f" (found: {found})" if found else ""))

    def put(section, lobe, label):
        if lobe is None:
            return
        if getattr(result, section) is not None:
            raise UserError(f"more than one {section} lobe feeds the Material Output ({label}); "
                            f"a facet material has one diffuse and one specular lobe")
        setattr(result, section, lobe)

    for weight, desc in terms:
        node = _Node(desc, result)
        if desc["type"] == "BSDF_DIFFUSE":
            put("diffuse", diffuse_bsdf(node, weight, result), node.label)
        elif desc["type"] == "BSDF_GLOSSY":
            put("specular", glossy_bsdf(node, weight, result), node.label)
        else:
            diffuse, specular, emission = principled_bsdf(node, weight, result)
            put("diffuse", diffuse, node.label)
            put("specular", specular, node.label)
            result.emission = emission
        if weight != 1.0:
            result.note(EXACT, f"{node.label}: Mix Shader weight {weight:.4g} -> colours scaled by it")
        _normal_map(node, result)
        _unmapped_inputs(node, result)
    if result.diffuse is None and result.specular is None:
        raise UserError(f"nothing facet can render remains: {'; '.join(m for _, m in result.notes)}")
    return result
