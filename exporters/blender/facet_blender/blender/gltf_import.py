"""A hook into Blender's glTF importer: facet's extensions -> facet settings.

Blender's glTF importer (io_scene_gltf2, Blender 3.4 and 4.x alike) calls the hooks of
every enabled add-on whose module has a `glTF2ImportUserExtension` class (the add-on's
top-level __init__.py has one, which makes an `ImportHooks` here). So importing a
glTF written by `facet export-gltf` with *File > Import > glTF 2.0* gives:

* each material with a FACET_material extension its facet settings, through the
  add-on's Import path: the material JSON goes to a temporary file, facet checks it
  (`facet generate FILE --target glsl`), and the panel is set from it. The node tree
  the importer made from the metallic–roughness fallback is kept;
* each light with a FACET_light extension the colour, power and radius 0 that export
  back to exactly that facet light (core/gltf.py; the importer's own units depend on
  its Lighting Mode option);
* the scene's FACET_scene ambient colour as a new World (Background colour, strength 1),
  which is what the add-on exports as facet's ambient, and the file's camera as the
  scene camera when the scene has none;
* a camera whose far clip is not beyond its near clip (a glTF zfar ≤ znear, which the
  glTF specification does not allow) an infinite far clip, as glTF's "no zfar" means;
  otherwise Blender would clip the whole scene away;
* a primitive without a material glTF's default material (glTF 2.0 §3.9.6: base colour 1,
  metallic 1, roughness 1) as a Principled BSDF, where the importer leaves the slot empty
  (Blender would render its own grey diffuse surface, and the add-on's scene export refuses a
  mesh without a material). The importer makes that material itself only for a primitive with
  COLOR_0 (io_scene_gltf2/blender/imp/mesh.py).

The importer catches and only logs exceptions from hooks, so every hook here turns
its problems into report lines and never stops the import. The lines go to the
importer's log (shown after the import in Blender 4.x) and, for scripts and tests,
to LAST_IMPORT [(level, message), ...] of the latest import.
"""

import traceback

import bpy

from ..core import UserError, gltf as core_gltf
from . import material as material_mod, preferences, state

LAST_IMPORT = []
INFINITE_CLIP = 1.0e12         # what Blender's glTF importer uses for "no zfar"


def _log(gltf, level, message):
    LAST_IMPORT.append((level, message))
    log = getattr(gltf, "log", None)
    method = getattr(log, level.lower(), None) if log is not None else None
    if method is None:
        print(f"facet glTF import: {level}: {message}")
        return
    try:
        method(f"facet: {message}", popup=True)    # Blender 4.x: shown as a report afterwards
    except TypeError:
        method(f"facet: {message}")                 # Blender 3.x: a logging.Logger


def _guarded(hook):
    """Runs a hook; a problem becomes one report line (the importer would only print it)."""
    def run(self, *args):
        gltf = args[-1]
        try:
            hook(self, *args)
        except UserError as e:
            _log(gltf, "WARNING", str(e))
        except Exception:  # noqa: BLE001 - a bug here must not stop the user's import
            _log(gltf, "ERROR", "the facet add-on's glTF hook failed:\n" + traceback.format_exc())
    run.__name__, run.__doc__ = hook.__name__, hook.__doc__
    return run


class ImportHooks:
    """One glTF import's hooks (the importer makes one per import)."""

    def __init__(self):
        LAST_IMPORT.clear()
        self._facet_missing_reported = False
        self._cameras = []
        self._default_material = None

    def _facet(self, gltf):
        """The facet executable, or None (reported once) when the add-on has no catalog."""
        try:
            state.require()
            return preferences.facet_exe()
        except UserError as e:
            if not self._facet_missing_reported:
                self._facet_missing_reported = True
                _log(gltf, "WARNING", f"{e}; the file's facet materials were not applied")
            return None

    @_guarded
    def gather_import_material_after_hook(self, pymaterial, vertex_color, blender_material, gltf):
        """FACET_material -> the Blender material's facet settings (checked by facet)."""
        name = getattr(pymaterial, "name", None) or blender_material.name
        where = f"glTF material '{name}'"
        data = core_gltf.material_of(getattr(pymaterial, "extensions", None), where)
        if data is None:
            return
        exe = self._facet(gltf)
        if exe is None:
            return
        core_gltf.check_material(exe, data, where, blender_material.name)
        for note in material_mod.from_json(blender_material, data):
            _log(gltf, "WARNING", note)
        _log(gltf, "INFO", f"material '{blender_material.name}': facet settings from {where} "
                           f"({core_gltf.MATERIAL_EXTENSION})")

    @_guarded
    def gather_import_light_after_hook(self, vnode, blender_object, blender_light, gltf):
        """FACET_light -> the Blender light that exports back to it exactly."""
        index = getattr(vnode, "light_node_idx", None)
        nodes = getattr(gltf.data, "nodes", None) or []
        if index is None or not 0 <= index < len(nodes):
            return
        facet_light = core_gltf.light_of(getattr(nodes[index], "extensions", None))
        if facet_light is None:
            return
        where = f"light '{blender_object.name}'"
        settings, notes = core_gltf.blender_light(facet_light, tuple(bpy.app.version), where)
        if settings["type"] != blender_light.type:
            raise UserError(f"{where}: {core_gltf.LIGHT_EXTENSION} is a {facet_light.get('type')} light but "
                            f"the glTF light is {blender_light.type}; the glTF light was kept")
        for key in ("color", "energy", "shadow_soft_size", "angle", "spot_size", "spot_blend"):
            if key in settings:
                setattr(blender_light, key, settings[key])
        for note in notes:
            _log(gltf, "WARNING", note)
        _log(gltf, "INFO", f"{where}: colour and power from {core_gltf.LIGHT_EXTENSION} "
                           f"({facet_light.get('type')}, radius 0)")

    @_guarded
    def gather_import_mesh_after_hook(self, pymesh, mesh, gltf):
        """Empty material slots (primitives without a material) -> glTF's default material. A
        mesh none of whose primitives has a material gets no slot from the importer: it gets one."""
        empty = [i for i, m in enumerate(mesh.materials) if m is None]
        if not empty and (len(mesh.materials) or not mesh.polygons):
            return
        if self._default_material is None or self._default_material.name not in bpy.data.materials:
            self._default_material = default_material()
        for i in empty:
            mesh.materials[i] = self._default_material
        if not mesh.materials:
            mesh.materials.append(self._default_material)       # every face's material index is 0
            empty = [0]
        _log(gltf, "INFO", f"mesh '{mesh.name}': {len(empty)} primitive slot(s) without a material get glTF's default "
                           f"material '{self._default_material.name}' (base colour 1, metallic 1, roughness 1)")

    @_guarded
    def gather_import_camera_after_hook(self, vnode, blender_object, blender_camera, gltf):
        """A far clip at or before the near clip (zfar ≤ znear) -> infinite, as 'no zfar'."""
        self._cameras.append(blender_object)
        if blender_camera.type == "PERSP" and blender_camera.clip_end <= blender_camera.clip_start:
            blender_camera.clip_end = INFINITE_CLIP
            _log(gltf, "WARNING", f"camera '{blender_object.name}': its glTF zfar is not greater than znear "
                                  f"(invalid glTF); using an infinite far clip")

    @_guarded
    def gather_import_scene_after_nodes_hook(self, gltf_scene, blender_scene, gltf):
        """FACET_scene ambient -> a new World whose Background colour is the ambient."""
        name = getattr(gltf_scene, "name", None) or "scene"
        ambient = core_gltf.ambient_of(getattr(gltf_scene, "extensions", None), f"glTF scene '{name}'")
        if ambient is None:
            return
        world = bpy.data.worlds.new(f"{name} (facet ambient)")
        world.use_nodes = True
        background = next((n for n in world.node_tree.nodes if n.type == "BACKGROUND"), None)
        if background is None:
            background = world.node_tree.nodes.new("ShaderNodeBackground")
            output = next((n for n in world.node_tree.nodes if n.type == "OUTPUT_WORLD"), None) \
                or world.node_tree.nodes.new("ShaderNodeOutputWorld")
            world.node_tree.links.new(background.outputs[0], output.inputs["Surface"])
        background.inputs["Color"].default_value = tuple(ambient) + (1.0,)
        background.inputs["Strength"].default_value = 1.0
        world.color = ambient
        blender_scene.world = world
        if blender_scene.camera is None and self._cameras:
            blender_scene.camera = self._cameras[0]
            _log(gltf, "INFO", f"scene '{blender_scene.name}': camera '{self._cameras[0].name}' is the scene camera")
        _log(gltf, "INFO", f"scene '{blender_scene.name}': World '{world.name}' with facet's ambient "
                           f"({', '.join(f'{c:g}' for c in ambient)}) from {core_gltf.SCENE_EXTENSION}")


DEFAULT_MATERIAL = "glTF default material"


def default_material():
    """glTF's default material (glTF 2.0 §3.9.6) as Blender's glTF importer would build a
    metallic–roughness material of those values: a Principled BSDF with Base Color 1, Metallic 1,
    Roughness 1 (and the importer's IOR 1.5) into the Material Output."""
    mat = bpy.data.materials.new(DEFAULT_MATERIAL)
    mat.use_nodes = True
    tree = mat.node_tree
    bsdf = next((n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        bsdf = tree.nodes.new("ShaderNodeBsdfPrincipled")
        output = next((n for n in tree.nodes if n.type == "OUTPUT_MATERIAL"), None) \
            or tree.nodes.new("ShaderNodeOutputMaterial")
        tree.links.new(bsdf.outputs[0], output.inputs["Surface"])
    bsdf.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bsdf.inputs["Metallic"].default_value = 1.0
    bsdf.inputs["Roughness"].default_value = 1.0
    if "IOR" in bsdf.inputs:
        bsdf.inputs["IOR"].default_value = 1.5
    return mat
