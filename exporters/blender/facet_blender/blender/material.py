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


def from_json(material, data):
    """Sets the material's facet settings from a (valid) material JSON."""
    catalog, plan = state.require()
    values = plan_mod.material_from_json(catalog, plan, data)   # everything computed first,
    properties.write(material.facet, plan, values)              # then written in one go
    material.facet_textures = ""


def set_lobes(material, result):
    """Sets the facet settings from a core.convert.Result (Blender BSDF mapping)."""
    catalog, plan = state.require()
    properties.write(material.facet, plan, plan_mod.conversion_values(catalog, plan, result))
    material.facet_textures = textures.dumps(result.textures) if result.textures else ""


def texture_bindings(material):
    """The textures Convert Blender Material found (core/textures.py bindings)."""
    return textures.loads(getattr(material, "facet_textures", ""), material.name)
