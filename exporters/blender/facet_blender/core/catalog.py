"""The model catalog, as the facet executable describes it.

`facet models --json` lists every section (diffuse, specular, fresnel, modifier,
light, ...) and in each its models with typed parameters: type, range, default,
choices, documentation. `facet schema` adds the material-level keys (ambient,
emission, tangent_axis) with their defaults and descriptions. The add-on builds its
whole user interface from these two outputs and never repeats them in Python, so a
model added to facet's C++ catalog shows up in Blender without touching the add-on.
"""

import json
import os
from dataclasses import dataclass, field

from . import UserError

# The catalog shipped inside the add-on (`facet models --json` and `facet schema` of the
# facet it was made with; exporters/blender/bundle_catalog.py writes it, and the ctest
# addon.catalog_bundled fails when it differs from what the built facet prints). The add-on
# registers its properties from it when facet cannot be found or run.
BUNDLED_PATH = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "catalog.json")

# The sections whose models are a material's lobes (the panel's two drop-downs).
LOBE_SECTIONS = ("diffuse", "specular")
# The layers a material lays over its lobes (facet's "layers", a list, the first lowest): the
# panel holds LAYER_SLOTS of them, "layer0" under "layer1", each a drop-down of the catalog's
# layer models. SLOTS: every drop-down of the panel, with the catalog section it chooses from.
LAYER_SECTION = "layer"
LAYER_SLOTS = 2
SLOTS = tuple((s, s) for s in LOBE_SECTIONS) + tuple((f"layer{i}", LAYER_SECTION) for i in range(LAYER_SLOTS))


def slot_models(catalog, section):
    """The models a drop-down of `section` offers: a lobe section's all; of the layers, those the
    panel can hold whole — no lobe inside the layer (a mix's), whose own Fresnel and toon the
    property plan has no place for."""
    models = catalog.models(section)
    if section != LAYER_SECTION:
        return models
    return [m for m in models if all(p.type not in ("model", "object") for p in m.params)]


@dataclass(frozen=True)
class Range:
    """A numeric range; None is unbounded. Blender's own limits are inclusive, so an
    exclusive bound is kept as the limit and facet rejects the bound itself."""
    min: float = None
    max: float = None
    min_exclusive: bool = False
    max_exclusive: bool = False

    def contains(self, x):
        if self.min is not None and (x < self.min or (self.min_exclusive and x == self.min)):
            return False
        if self.max is not None and (x > self.max or (self.max_exclusive and x == self.max)):
            return False
        return True


@dataclass(frozen=True)
class Param:
    """One parameter of a model, exactly as `facet models --json` gives it."""
    name: str
    type: str                 # number | color | vector | boolean | string | model | object
    doc: str = ""
    allowed: str = ""         # facet's own words for the valid values
    default: object = None
    required: bool = False
    range: Range = None
    choices: tuple = None     # for strings with a fixed set of values
    section: str = None       # for type model/object: the catalog section of the value


@dataclass(frozen=True)
class Model:
    section: str
    name: str
    title: str
    doc: str = ""
    formula: str = ""
    citation: str = ""
    params: tuple = ()
    cycles: dict = None       # how exact Cycles' closest closure is (informative)
    pov: dict = None
    blender_nodes: dict = None  # Build Blender Nodes: kind, nodes, measured error (lobes)

    def param(self, name):
        for p in self.params:
            if p.name == name:
                return p
        raise KeyError(f"{self.section} model {self.name} has no parameter {name}")


@dataclass(frozen=True)
class MaterialKey:
    """A material-level key of the material schema (ambient, emission, tangent_axis)."""
    name: str
    kind: str                 # "color" (RGB or grey number) or "vector" (three numbers)
    default: tuple
    doc: str = ""
    maximum: float = None     # a colour's largest component (the float32 bound, docs/float32.md)


@dataclass
class Catalog:
    version: str
    epsilon: float
    sections: dict                        # section name -> list of Model
    material_keys: list = field(default_factory=list)

    def models(self, section):
        return self.sections.get(section, [])

    def model(self, section, name):
        for m in self.models(section):
            if m.name == name:
                return m
        raise KeyError(f"no {section} model named {name!r}")

    def has_model(self, section, name):
        return any(m.name == name for m in self.models(section))


def _range(data):
    if not isinstance(data, dict):
        return None
    return Range(min=data.get("min"), max=data.get("max"),
                 min_exclusive=bool(data.get("min_exclusive")),
                 max_exclusive=bool(data.get("max_exclusive")))


def _param(data):
    choices = data.get("choices")
    return Param(name=data["name"], type=data["type"], doc=data.get("doc", ""),
                 allowed=data.get("allowed", ""), default=data.get("default"),
                 required=bool(data.get("required")), range=_range(data.get("range")),
                 choices=tuple(choices) if choices else None, section=data.get("section"))


def _model(section, data):
    return Model(section=section, name=data["name"], title=data.get("title", data["name"]),
                 doc=data.get("doc", ""), formula=data.get("formula", ""),
                 citation=data.get("citation", ""),
                 params=tuple(_param(p) for p in data.get("parameters", [])),
                 cycles=data.get("cycles"), pov=data.get("pov"), blender_nodes=data.get("blender_nodes"))


def _allows_number(prop):
    """Whether a schema (or one of its oneOf/anyOf alternatives) accepts a plain number."""
    return _allows_type(prop, "number")


def _allows_type(prop, kind):
    """Whether a schema (or one of its oneOf/anyOf alternatives) accepts a value of JSON type `kind`."""
    if not isinstance(prop, dict):
        return False
    if prop.get("type") == kind:
        return True
    return any(_allows_type(p, kind) for key in ("oneOf", "anyOf") for p in prop.get(key, ()))


def _number_maximum(prop):
    """The "maximum" of the plain number a schema (or one of its alternatives) accepts, or None."""
    if not isinstance(prop, dict):
        return None
    if prop.get("type") == "number":
        return prop.get("maximum")
    for key in ("oneOf", "anyOf"):
        for p in prop.get(key, ()):
            m = _number_maximum(p)
            if m is not None:
                return m
    return None


def _material_keys(schema):
    """ambient/emission/tangent_axis (and whatever facet adds later) from `facet schema`."""
    keys = []
    for name, prop in schema.get("properties", {}).items():
        if name in ("$schema", "name", "layers") or name in LOBE_SECTIONS:
            continue
        if not _allows_type(prop, "array"):
            continue  # a number (alpha, alpha_cutoff): not a colour or vector the panel edits
        default = prop.get("default")
        if isinstance(default, (int, float)):
            default = [float(default)] * 3
        if not (isinstance(default, list) and len(default) == 3):
            continue  # not a three-number key: nothing the panel can edit
        # A colour may be written as one grey number (the schema's oneOf number/array, which
        # an anyOf with a texture object may wrap); a vector is only ever an array.
        kind = "color" if _allows_number(prop) else "vector"
        keys.append(MaterialKey(name=name, kind=kind, default=tuple(float(x) for x in default),
                                doc=prop.get("description", ""),
                                maximum=_number_maximum(prop) if kind == "color" else None))
    return keys


def parse(models_json, material_schema_json):
    """A Catalog from the outputs of `facet models --json` and `facet schema`."""
    try:
        sections = {name: [_model(name, m) for m in models]
                    for name, models in models_json["sections"].items()}
        catalog = Catalog(version=str(models_json.get("facet", "")),
                          epsilon=float(models_json.get("epsilon", 1e-4)),
                          sections=sections,
                          material_keys=_material_keys(material_schema_json))
    except (KeyError, TypeError, ValueError) as e:
        raise UserError(f"facet's catalog is not in the expected format ({type(e).__name__}: {e}); "
                        f"is the facet executable too old or too new for this add-on?")
    for section in LOBE_SECTIONS:
        if not catalog.models(section):
            raise UserError(f"facet's catalog has no {section} models")
    return catalog


def facet_data(exe):
    """What the bundled file holds, from a facet executable: {"models": `facet models
    --json`, "schema": `facet schema`}."""
    from . import cli
    return {"models": cli.models(exe), "schema": cli.material_schema(exe)}


def load(exe):
    """Runs facet and parses its catalog."""
    data = facet_data(exe)
    return parse(data["models"], data["schema"])


def bundled_data(path=None):
    path = path or BUNDLED_PATH
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
        return {"models": data["models"], "schema": data["schema"]}
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise UserError(f"{path}: the add-on's bundled catalog cannot be read ({type(e).__name__}: {e})")


def load_bundled(path=None):
    """The catalog shipped with the add-on (used until facet is found)."""
    data = bundled_data(path)
    return parse(data["models"], data["schema"])


def dump_bundled(data):
    """The bundled file's text for `facet_data(exe)` (stable, one key per line)."""
    return json.dumps(data, indent=1, ensure_ascii=False, sort_keys=True) + "\n"
