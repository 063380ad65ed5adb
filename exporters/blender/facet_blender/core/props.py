"""The property plan: which settings the panel edits, derived from the catalog, and the
conversion between those settings ("values") and facet's material JSON.

The plan is plain data: a tree of `Group`s of `Field`s. The Blender layer turns each
Group into a `bpy.types.PropertyGroup` class and each Field into a `bpy.props`
property, mechanically. `values` are nested dicts {field id: value} holding what
those properties hold, so the conversions below are testable without Blender.

Layout of the plan (one group per lobe model, built at register time):

    FACET_PG_material                     bpy.types.Material.facet
        use_facet        bool             "this material has facet settings"
        diffuse_model    enum             "none" or a diffuse model of the catalog
        specular_model   enum             "none" or a specular model
        diffuse_<model>  -> FACET_PG_diffuse_<model>     one per diffuse model
        specular_<model> -> FACET_PG_specular_<model>    one per specular model
        layer0_model, layer1_model  enum  "none" or a layer model (catalog: layer), the
                                          material's "layers" list, layer0 the lower
        layer<i>_<model> -> FACET_PG_layer_<model>       one per layer model (both slots
                                                         share the group class)
        ambient, emission, tangent_axis   the material keys of `facet schema`

    FACET_PG_<section>_<model>            the model's parameters, with the catalog's
        color, n, alpha, geometry, ...    defaults, ranges, choices and docs
        fresnel -> FACET_PG_<section>_<model>_fresnel
            model                         "none" | "schlick" | "exact" (catalog: fresnel)
            schlick_f0, exact_ior         every Fresnel model's parameters
        toon -> FACET_PG_<section>_<model>_toon
            enabled, cutoff, width        the toon modifier (catalog: modifier/toon)

Directions (tangent_axis) are edited in Blender's coordinates (+Z up) and written in
facet's (+Y up), so "up" means the same thing on both sides.
"""

from dataclasses import dataclass, field

from . import UserError
from .catalog import LAYER_SECTION, LAYER_SLOTS, LOBE_SECTIONS, SLOTS, slot_models
from .coords import clean_float, clean_vector, to_blender, to_facet

MATERIAL_GROUP = "FACET_PG_material"
NONE = "none"                       # the "no lobe" item of the model drop-downs
USE_FACET = "use_facet"
RESERVED = {"name", "rna_type", "bl_rna", "id_data", "model", "enabled"}
ACRONYMS = {"ior": "IOR", "ggx": "GGX"}


@dataclass
class Field:
    id: str                         # the Blender property identifier
    kind: str                       # float | color | vector | bool | enum | string | group
    label: str
    doc: str = ""
    default: object = None
    min: float = None
    max: float = None
    soft_max: float = None
    items: tuple = ()               # enum: ((identifier, label, description), ...)
    group: "Group" = None           # kind group: the nested group
    key: str = None                 # the material-JSON key the field is written under
    nested: str = None              # kind group: "model" (e.g. fresnel) or "object" (toon)
    owner: str = None               # in a "model" group: the model the field belongs to


@dataclass
class Group:
    name: str                       # the PropertyGroup class name
    label: str
    fields: list = field(default_factory=list)
    doc: str = ""

    def field(self, fid):
        for f in self.fields:
            if f.id == fid:
                return f
        raise KeyError(fid)


def label(name):
    """UI label from a catalog name: "alpha_x" -> "Alpha X"; short symbols ("n", "f0")
    stay as the formulas write them."""
    if len(name) <= 2:
        return name
    return " ".join(ACRONYMS.get(w, w.capitalize()) for w in name.split("_"))


def field_id(name):
    """A Blender identifier for a catalog parameter name (avoiding built-in names)."""
    return "p_" + name if name in RESERVED else name


def tooltip(doc, allowed=""):
    parts = [doc[:1].upper() + doc[1:] if doc else ""]
    if allowed:
        parts.append(f"Allowed: {allowed}")
    return ". ".join(p.rstrip(".") for p in parts if p) + ("." if any(parts) else "")


def _as_rgb(value, fallback=(1.0, 1.0, 1.0)):
    if value is None:
        return [float(x) for x in fallback]
    if isinstance(value, (int, float)):
        return [float(value)] * 3
    return [float(x) for x in value]


# ----------------------------------------------------------------------------- the plan

def _scalar_field(catalog, p, fid=None, default=None):
    """The Field of a number/color/vector/boolean/string parameter."""
    fid = fid or field_id(p.name)
    default = p.default if default is None else default
    doc = tooltip(p.doc, p.allowed)
    lo = p.range.min if p.range else None
    hi = p.range.max if p.range else None
    if p.type == "number":
        return Field(fid, "float", label(p.name), doc, float(default if default is not None else 0.0),
                     min=lo, max=hi, key=p.name)
    if p.type == "color":
        return Field(fid, "color", label(p.name), doc, _as_rgb(default),
                     min=lo, max=hi, soft_max=min(hi, 1.0) if hi is not None else 1.0, key=p.name)
    if p.type == "vector":
        return Field(fid, "vector", label(p.name), doc, _as_rgb(default, (0.0, 0.0, 0.0)), key=p.name)
    if p.type == "boolean":
        return Field(fid, "bool", label(p.name), doc, bool(default), key=p.name)
    if p.type == "string" and p.choices:
        # Titles and docs of the choices when the catalog has a section of that name
        # (geometry: none / v_cavity / smith_ggx).
        section = {m.name: m for m in catalog.models(p.name)}
        items = tuple((c, section[c].title if c in section else label(c),
                       section[c].doc if c in section else "") for c in p.choices)
        return Field(fid, "enum", label(p.name), doc, default if default in p.choices else p.choices[0],
                     items=items, key=p.name)
    if p.type == "string":
        return Field(fid, "string", label(p.name), doc, str(default or ""), key=p.name)
    return None


def _model_field(catalog, p, owner):
    """A parameter whose value is a model of another section, e.g. fresnel:
    {"model": "schlick", "f0": ...}. One enum + every model's parameters."""
    models = catalog.models(p.section)
    default = p.default if isinstance(p.default, dict) else {}
    chosen = default.get("model", models[0].name if models else NONE)
    group = Group(f"{owner}_{p.name}", label(p.name), doc=tooltip(p.doc, p.allowed))
    group.fields.append(Field("model", "enum", "Model", tooltip(p.doc),
                              chosen, items=tuple((m.name, m.title, m.doc) for m in models),
                              key="model"))
    for m in models:
        for q in m.params:
            value = default[q.name] if (m.name == chosen and q.name in default) else None
            f = _scalar_field(catalog, q, fid=f"{m.name}_{q.name}", default=value)
            if f:
                f.owner = m.name
                group.fields.append(f)
    return Field(field_id(p.name), "group", label(p.name), group.doc, group=group,
                 key=p.name, nested="model")


def _object_field(catalog, p, owner):
    """A parameter whose value is an optional object of a model of another section,
    e.g. toon: {"cutoff": ..., "width": ...} from modifier/toon. An "enabled" switch
    says whether it is written at all."""
    model = catalog.model(p.section, p.name)
    group = Group(f"{owner}_{p.name}", model.title, doc=tooltip(p.doc or model.doc))
    group.fields.append(Field("enabled", "bool", f"Use {model.title}",
                              tooltip(model.doc + " " + p.doc if p.doc else model.doc), False))
    for q in model.params:
        f = _scalar_field(catalog, q)
        if f:
            group.fields.append(f)
    return Field(field_id(p.name), "group", model.title, group.doc, group=group,
                 key=p.name, nested="object")


def lobe_group(catalog, model):
    """The PropertyGroup plan of one diffuse or specular model."""
    name = f"FACET_PG_{model.section}_{model.name}"
    group = Group(name, model.title, doc=model.doc)
    for p in model.params:
        if p.type == "model" and p.section:
            group.fields.append(_model_field(catalog, p, name))
        elif p.type == "object" and p.section and catalog.has_model(p.section, p.name):
            group.fields.append(_object_field(catalog, p, name))
        else:
            f = _scalar_field(catalog, p)
            if f:
                group.fields.append(f)
    return group


def material_group(catalog):
    """The plan of `bpy.types.Material.facet`, with every lobe group nested."""
    group = Group(MATERIAL_GROUP, "facet", doc="facet material settings")
    group.fields.append(Field(USE_FACET, "bool", "facet",
                              "Give this material facet settings: export it as a facet material, "
                              "generate GLSL/OSL/POV-Ray from it", False))
    slots = [(slot, section) for slot, section in SLOTS if slot_models(catalog, section)]  # an older facet: no layers
    for slot, section in slots:
        models = slot_models(catalog, section)
        what = f"{section} lobe" if section != LAYER_SECTION else f"layer {slot[len('layer'):]} (0 the lower)"
        items = ((NONE, "None", f"No {what}"),) + tuple(
            (m.name, m.title, f"{m.doc} {m.formula} ({m.citation})".strip()) for m in models)
        default = models[0].name if section == "diffuse" else NONE
        group.fields.append(Field(f"{slot}_model", "enum", f"{slot.capitalize()} Model",
                                  f"The {what}'s model (facet catalog)", default, items=items))
    lobes = {}
    for slot, section in slots:
        for m in slot_models(catalog, section):
            lobe = lobes.setdefault(m.name + "/" + section, lobe_group(catalog, m))
            group.fields.append(Field(f"{slot}_{m.name}", "group", m.title, m.doc, group=lobe))
    for k in catalog.material_keys:
        default = to_blender(k.default) if k.kind == "vector" else list(k.default)
        doc = tooltip(k.doc) + (" Edited in Blender's axes (Z up); written in facet's (Y up)."
                                if k.kind == "vector" else "")
        group.fields.append(Field(k.name, k.kind, label(k.name), doc, default, min=0.0 if k.kind == "color" else None,
                                  max=k.maximum, soft_max=1.0 if k.kind == "color" else None, key=k.name))
    return group


def groups_in_registration_order(group, seen=None):
    """Every group of the tree, nested ones before the groups that point to them, each once (the
    layer slots share their models' groups)."""
    seen = set() if seen is None else seen
    order = []
    for f in group.fields:
        if f.kind == "group" and f.group.name not in seen:
            order.extend(groups_in_registration_order(f.group, seen))
    if group.name not in seen:
        seen.add(group.name)
        order.append(group)
    return order


# ----------------------------------------------------------------------------- values <-> JSON

def _clean(f, value):
    if f.kind == "float":
        return clean_float(value)
    if f.kind in ("color", "vector"):
        return clean_vector(value)
    if f.kind == "bool":
        return bool(value)
    return str(value)


def lobe_to_json(model, group, values):
    """{"model": ..., param: value, ...} of one lobe from its group's values."""
    lobe = {"model": model.name}
    for f in group.fields:
        v = values[f.id]
        if f.kind != "group":
            lobe[f.key] = _clean(f, v)
        elif f.nested == "model":
            chosen = v["model"]
            sub = {"model": chosen}
            for g in f.group.fields:
                if g.owner == chosen:
                    sub[g.key] = _clean(g, v[g.id])
            lobe[f.key] = sub
        elif f.nested == "object" and v.get("enabled"):
            lobe[f.key] = {g.key: _clean(g, v[g.id]) for g in f.group.fields if g.key}
    return lobe


def _value_from_json(f, data):
    """A field's value from a JSON value (None: the default)."""
    if data is None:
        return f.default
    if f.kind == "color":
        return _as_rgb(data)
    if f.kind == "vector":
        return [float(x) for x in data]
    if f.kind == "float":
        return float(data)
    if f.kind == "bool":
        return bool(data)
    return str(data)


def lobe_from_json(group, lobe):
    """The values of a lobe group from a lobe object (absent keys get defaults)."""
    values = {}
    for f in group.fields:
        data = lobe.get(f.key)
        if f.kind != "group":
            values[f.id] = _value_from_json(f, data)
        elif f.nested == "model":
            data = data if isinstance(data, dict) else {}
            sub = {g.id: g.default for g in f.group.fields}
            chosen = data.get("model", f.group.field("model").default)
            sub["model"] = chosen
            for g in f.group.fields:
                if g.owner == chosen and g.key in data:
                    sub[g.id] = _value_from_json(g, data[g.key])
            values[f.id] = sub
        elif f.nested == "object":
            sub = {g.id: g.default for g in f.group.fields}
            sub["enabled"] = isinstance(data, dict)
            for g in f.group.fields:
                if g.key and isinstance(data, dict) and g.key in data:
                    sub[g.id] = _value_from_json(g, data[g.key])
            values[f.id] = sub
    return values


def default_values(group):
    """The values a group has when nothing was set (the catalog's defaults)."""
    return {f.id: default_values(f.group) if f.kind == "group" else f.default for f in group.fields}


def material_to_json(catalog, plan, values, name):
    """facet's material JSON from the values of FACET_PG_material."""
    data = {"name": name}
    for section in LOBE_SECTIONS:
        chosen = values[f"{section}_model"]
        if chosen != NONE:
            model = catalog.model(section, chosen)
            data[section] = lobe_to_json(model, plan.field(f"{section}_{chosen}").group,
                                         values[f"{section}_{chosen}"])
    if not any(section in data for section in LOBE_SECTIONS):
        raise UserError(f"material '{name}' has neither a diffuse nor a specular model: "
                        f"choose at least one in its facet panel")
    layers = []
    for i in range(LAYER_SLOTS):
        chosen = values.get(f"layer{i}_model", NONE)
        if chosen != NONE:
            layers.append(lobe_to_json(catalog.model(LAYER_SECTION, chosen),
                                       plan.field(f"layer{i}_{chosen}").group, values[f"layer{i}_{chosen}"]))
    if layers:
        data["layers"] = layers
    for k in catalog.material_keys:
        v = values[k.name]
        data[k.name] = clean_vector(to_facet(v) if k.kind == "vector" else v)
    return data


def material_from_json(catalog, plan, data):
    """Values to write into FACET_PG_material from facet's material JSON.

    Only the chosen lobes' groups are included: the other models keep whatever the
    user set in them. The JSON is assumed valid (facet checked it)."""
    values = {USE_FACET: True}
    layers = data.get("layers") or []
    slots = [slot for slot, section in SLOTS if section == LAYER_SECTION and slot_models(catalog, section)]
    if len(layers) > len(slots):
        raise UserError(f"material '{data.get('name', '')}' has {len(layers)} layers; the facet panel holds "
                        f"{len(slots)}: the material is not imported (facet itself renders it)")
    held = {m.name for m in slot_models(catalog, LAYER_SECTION)}
    for i, layer in enumerate(layers):
        if isinstance(layer, dict) and layer.get("model") not in held:
            raise UserError(f"material '{data.get('name', '')}': layers[{i}] is a {layer.get('model')} layer, which "
                            f"the facet panel does not hold (it holds {', '.join(sorted(held)) or 'none'}): the "
                            f"material is not imported (facet itself renders it)")
    chosen = {section: data.get(section) for section in LOBE_SECTIONS}
    chosen.update({slot: layers[i] if i < len(layers) else None for i, slot in enumerate(slots)})
    for slot, lobe in chosen.items():
        section = slot if slot in LOBE_SECTIONS else LAYER_SECTION
        if isinstance(lobe, dict) and catalog.has_model(section, lobe.get("model")):
            values[f"{slot}_model"] = lobe["model"]
            values[f"{slot}_{lobe['model']}"] = lobe_from_json(plan.field(f"{slot}_{lobe['model']}").group, lobe)
        else:
            values[f"{slot}_model"] = NONE
    for k in catalog.material_keys:
        v = data.get(k.name)
        v = list(k.default) if v is None else _as_rgb(v) if k.kind == "color" else [float(x) for x in v]
        values[k.name] = to_blender(v) if k.kind == "vector" else v
    return values


def conversion_values(catalog, plan, result):
    """Values to write into FACET_PG_material from a convert.Result (the mapping of
    Blender's BSDF nodes): facet on, the lobes found ("none" for a section without
    one) and, when the catalog has it, the emission (black when none was found)."""
    values = {USE_FACET: True}
    for section in LOBE_SECTIONS:
        lobe = getattr(result, section)
        if lobe is None:
            values[f"{section}_model"] = NONE
            continue
        values[f"{section}_model"] = lobe["model"]
        group = plan.field(f"{section}_{lobe['model']}").group
        values[f"{section}_{lobe['model']}"] = lobe_from_json(group, lobe)
    for slot, section in SLOTS:       # Blender's BSDFs map to lobes (gltf_pbr holds its own sheen and coat)
        if section == LAYER_SECTION and slot_models(catalog, section):
            values[f"{slot}_model"] = NONE
    if any(k.name == "emission" for k in catalog.material_keys):
        values["emission"] = list(result.emission) if result.emission else [0.0, 0.0, 0.0]
    return values


def normalize_material(catalog, plan, data):
    """A material JSON with every default written out (what exporting it gives)."""
    return material_to_json(catalog, plan, material_from_json(catalog, plan, data),
                            data.get("name", "material"))
