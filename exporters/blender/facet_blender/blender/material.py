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
    numbers, found = textures.split(data)
    values = plan_mod.material_from_json(catalog, plan, numbers)   # everything computed first,
    bindings, notes = [], []
    for path, tex in found:
        where = f"material '{data.get('name', material.name)}': {'.'.join(path)}"
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
        model = numbers.get(path[0], {}).get("model") if len(path) > 1 else None
        bindings.append(textures.binding_of_json(path, tex, model, image.name))
    properties.write(material.facet, plan, values)              # then written in one go
    material.facet_textures = textures.dumps(bindings) if bindings else ""
    return notes


def set_lobes(material, result):
    """Sets the facet settings from a core.convert.Result (Blender BSDF mapping)."""
    catalog, plan = state.require()
    properties.write(material.facet, plan, plan_mod.conversion_values(catalog, plan, result))
    material.facet_textures = textures.dumps(result.textures) if result.textures else ""


def texture_bindings(material):
    """The textures Convert Blender Material found (core/textures.py bindings)."""
    return textures.loads(getattr(material, "facet_textures", ""), material.name)
