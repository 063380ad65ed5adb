"""facet's glTF extensions -> Blender settings (plain data in, plain data out).

`facet export-gltf` writes facet's own descriptions beside the standard glTF data:

    materials[i].extensions.FACET_material = {"material": <facet material JSON>}
    nodes[i].extensions.FACET_light        = <facet light, without position/direction>
    scenes[i].extensions.FACET_scene       = {"ambient": [r, g, b]}

next to a metallic–roughness fallback, KHR_lights_punctual lights and a camera.
Blender's glTF importer reads the standard part; the add-on's importer hook
(blender/gltf_import.py) gives each Blender material its facet settings from
FACET_material (checked by facet first) and makes each Blender light the one
FACET_light describes, in the units of `scene.light` (which the export uses):

    point, spot:  facet C = colour · P / (4π²)   ->  P = 4π² · max(C), colour = C / max(C)
    sun:          facet C = colour · S / π       ->  S = π · max(C),   colour = C / max(C)

with radius 0 (sun angle 0), as facet's lights are points (parallel beams). The
glTF importer's own units depend on its Lighting Mode option (Standard divides by
683 lm/W), so FACET_light is what makes the Blender light exact.
"""

import math

from . import UserError, cli, generate

MATERIAL_EXTENSION = "FACET_material"
LIGHT_EXTENSION = "FACET_light"
SCENE_EXTENSION = "FACET_scene"

FOUR_PI_SQUARED = 4.0 * math.pi * math.pi


def _rgb(value, what):
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return [float(value)] * 3
    if isinstance(value, (list, tuple)) and len(value) == 3 and all(
            isinstance(x, (int, float)) and not isinstance(x, bool) for x in value):
        return [float(x) for x in value]
    raise UserError(f"{what}: expected a colour (three numbers), got {value!r}")


def material_of(extensions, where):
    """The facet material JSON held by a glTF material's extensions, or None when it
    has no FACET_material. `where` names the material in messages."""
    if not isinstance(extensions, dict) or MATERIAL_EXTENSION not in extensions:
        return None
    ext = extensions[MATERIAL_EXTENSION]
    if not isinstance(ext, dict) or not isinstance(ext.get("material"), dict):
        raise UserError(f"{where}: extensions.{MATERIAL_EXTENSION} must be an object with a "
                        f"\"material\" object (a facet material)")
    return ext["material"]


def check_material(exe, data, where, material_name):
    """Lets facet check a FACET_material's material (`data`) of the glTF material
    `where`; when facet refuses it, a UserError with facet's lines saying that the
    Blender material `material_name` keeps only the glTF fallback."""
    try:
        generate.check_material(exe, data, f"{where} ({MATERIAL_EXTENSION})")
    except cli.FacetError as e:
        raise UserError(f"facet rejected the facet material of {where}; material "
                        f"'{material_name}' keeps only the glTF fallback:\n{e}")


def ambient_of(extensions, where):
    """The ambient colour of a glTF scene's FACET_scene extension, or None."""
    if not isinstance(extensions, dict) or SCENE_EXTENSION not in extensions:
        return None
    ext = extensions[SCENE_EXTENSION]
    if not isinstance(ext, dict) or "ambient" not in ext:
        return None
    return _rgb(ext["ambient"], f"{where}: extensions.{SCENE_EXTENSION}.ambient")


def light_of(extensions):
    """A glTF node's FACET_light (a dict), or None."""
    if not isinstance(extensions, dict):
        return None
    light = extensions.get(LIGHT_EXTENSION)
    return light if isinstance(light, dict) else None


def _split(color):
    """(Blender colour, scale): colour = C / max(C), scale = max(C); black stays black."""
    k = max(color)
    if k <= 0.0:
        return [1.0, 1.0, 1.0], 0.0
    return [c / k for c in color], k


def blender_light(facet_light, blender_version=(4, 5, 0), where="light"):
    """The Blender light settings that export (core.scene.light) back to `facet_light`.

    Returns ({"type": POINT | SUN | SPOT, "color", "energy", "shadow_soft_size",
    "angle" (sun), "spot_size", "spot_blend" (spot)}, notes). The light's position and
    direction are the glTF node's, which the importer has already set."""
    notes = []
    kind = facet_light.get("type")
    color = _rgb(facet_light.get("color", [1.0, 1.0, 1.0]), f"{where}: {LIGHT_EXTENSION}.color")
    rgb, k = _split(color)
    if kind == "directional":
        return {"type": "SUN", "color": rgb, "energy": math.pi * k, "angle": 0.0}, notes
    if kind not in ("point", "spot"):
        raise UserError(f"{where}: {LIGHT_EXTENSION}.type {kind!r} is not a facet light "
                        f"(point, spot or directional)")
    attenuation = facet_light.get("attenuation", "none")
    if attenuation != "inverse_square":
        notes.append(f"{where}: facet attenuation {attenuation!r} has no Blender equivalent (Blender's "
                     f"lights fall off as 1/d²); the light keeps facet's colour as if it were "
                     f"inverse_square (approximate)")
    out = {"type": "POINT", "color": rgb, "energy": FOUR_PI_SQUARED * k, "shadow_soft_size": 0.0}
    if kind == "point":
        return out, notes
    cutoff = float(facet_light.get("cutoff", 45.0))
    exponent = float(facet_light.get("exponent", 0.0))
    blender_exponent = 1.0 if tuple(blender_version[:2]) < (3, 5) else 0.0
    if exponent != blender_exponent:
        notes.append(f"{where}: spot exponent {exponent:g} has no equivalent in this Blender, whose spot "
                     f"falls off as cos^{blender_exponent:g} inside its cone (approximate)")
    out.update({"type": "SPOT", "spot_size": math.radians(2.0 * cutoff), "spot_blend": 0.0})
    return out, notes
