"""A Blender material's facet settings <-> facet's material JSON."""

from ..core import UserError, props as plan_mod, textures
from . import properties, state


def has_settings(material):
    """Whether the material has facet settings (its facet panel is enabled)."""
    pg = getattr(material, "facet", None)
    return bool(pg is not None and getattr(pg, plan_mod.USE_FACET, False))


def no_settings_error(material):
    return UserError(f"material '{material.name}' has no facet settings: enable facet in its "
                     f"Material Properties > facet panel, or run 'Convert Blender Material to facet'")


def to_json(material):
    """facet's material JSON (a dict) from the material's facet settings."""
    catalog, plan = state.require()
    if not has_settings(material):
        raise no_settings_error(material)
    values = properties.read(material.facet, plan)
    return plan_mod.material_to_json(catalog, plan, values, material.name)


def from_json(material, data, folder=None):
    """Sets the material's facet settings from a (valid) material JSON; its textures (files
    relative to `folder`, the material file's) become Images and texture bindings. Returns
    notes (textures left out when there is no folder)."""
    import os

    import bpy
    catalog, plan = state.require()
    unmapped = textures.unmapped_values(data)
    if unmapped:
        raise UserError(f"material '{data.get('name', material.name)}': {', '.join(unmapped)} take the vertex colour "
                        f"or an offset, which the add-on does not map yet (docs/textures.md, \"Vertex colours\"); "
                        f"the material is not imported")
    numbers, found = textures.split(data)
    values = plan_mod.material_from_json(catalog, plan, numbers)   # everything computed first,
    bindings, notes = [], []
    for path, tex in found:
        where = f"material '{data.get('name', material.name)}': {textures.key_path(path)}"
        if folder is None:
            notes.append(f"{where}: its texture '{tex['texture']}' is not imported (no file folder); the "
                         f"parameter keeps its factor or default")
            continue
        file = os.path.normpath(os.path.join(folder, tex["texture"]))
        if not os.path.isfile(file):
            raise UserError(f"{where}: image '{tex['texture']}' not found ({file})")
        try:
            image = bpy.data.images.load(file, check_existing=True)
        except RuntimeError as e:
            raise UserError(f"{where}: Blender cannot read image '{file}': {e}")
        model = textures.model_at(numbers, path).get("model") if len(path) > 1 else None
        bindings.append(textures.binding_of_json(path, tex, model, image.name))
    properties.write(material.facet, plan, values)              # then written in one go
    material.facet_textures = textures.dumps(bindings) if bindings else ""
    return notes


def set_lobes(material, result):
    """Sets the facet settings from a core.convert.Result (Blender BSDF mapping)."""
    catalog, plan = state.require()
    properties.write(material.facet, plan, plan_mod.conversion_values(catalog, plan, result))
    material.facet_textures = textures.dumps(result.textures) if result.textures else ""


def _overlay(base, over):
    """`base` (nested dicts) with the values of `over` put in, as properties.write puts them."""
    out = dict(base)
    for key, value in over.items():
        out[key] = _overlay(base[key], value) if isinstance(value, dict) and isinstance(base.get(key), dict) \
            else value
    return out


def exported(material, strict=False):
    """(material JSON, texture bindings, notes) of a material as a scene export writes it:
    its facet settings; without them, unless `strict`, what 'Convert Blender Material to
    facet' would set from its Blender nodes, worked out on plain data (the material is
    not changed), with a warning that names it. `strict` keeps the refusal."""
    if has_settings(material) or strict:
        return to_json(material), texture_bindings(material), []
    from ..core.convert import IGNORED, map_surface
    from . import nodes
    catalog, plan = state.require()
    try:
        result = map_surface(nodes.surface_description(material), material.name)
    except UserError as e:
        raise UserError(f"material '{material.name}' has no facet settings and its Blender nodes do not convert "
                        f"({e}): enable facet in its Material Properties > facet panel, or give it a Diffuse, "
                        f"Glossy or Principled BSDF")
    values = _overlay(properties.read(material.facet, plan), plan_mod.conversion_values(catalog, plan, result))
    data = result.cut_out(plan_mod.material_to_json(catalog, plan, values, material.name))
    notes = [f"material '{material.name}' has no facet settings: exported as converted from its Blender nodes, "
             f"{result.headline()} (the material is unchanged; 'Convert Blender Material to facet' makes this its "
             f"settings, and 'Strict' refuses such a material)"]
    named = f"material '{material.name}'"
    notes += [message if named in message else f"{named}: {message}"
              for level, message in result.notes if level == IGNORED]
    return data, result.textures, notes


def texture_bindings(material):
    """The textures Convert Blender Material found (core/textures.py bindings)."""
    return textures.loads(getattr(material, "facet_textures", ""), material.name)
