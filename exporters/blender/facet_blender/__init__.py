"""facet for Blender: edit facet materials (classic and physically based reflection
models) on Blender materials, and generate GLSL, OSL (Cycles) and POV-Ray from them.

A thin layer over the facet command-line tool, which holds the model catalog and the
code generators: the panel is built from `facet models --json` (until facet is found,
from the copy bundled in catalog.json), and every export runs `facet generate`. `core/` is free of bpy (plain data + the facet CLI); `blender/`
reads and writes Blender data.

With the add-on enabled, Blender's own glTF importer gives materials, lights and the
World what facet's glTF extensions describe (`glTF2ImportUserExtension` below).

Loads as a Blender 4.2+ extension (blender_manifest.toml) and as a legacy add-on
(bl_info) in Blender 3.4+.
"""

bl_info = {
    "name": "facet",
    "author": "facet contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Material > facet; File > Export > facet; Render Engine > facet POV-Ray",
    "description": "facet materials: classic and physically based reflection models "
                   "-> GLSL, OSL and POV-Ray, through the facet command-line tool",
    "category": "Material",
}


class glTF2ImportUserExtension:
    """Blender's glTF importer makes one of these per import when the add-on is enabled
    (it looks for this name in every enabled add-on's module): the hooks give the
    imported materials, lights and World what facet's glTF extensions (FACET_material,
    FACET_light, FACET_scene) describe, and primitives without a material glTF's default
    material. See blender/gltf_import.py."""

    def __init__(self):
        from .blender import gltf_import
        self._hooks = gltf_import.ImportHooks()

    def gather_import_material_after_hook(self, *args):
        self._hooks.gather_import_material_after_hook(*args)

    def gather_import_light_after_hook(self, *args):
        self._hooks.gather_import_light_after_hook(*args)

    def gather_import_camera_after_hook(self, *args):
        self._hooks.gather_import_camera_after_hook(*args)

    def gather_import_mesh_after_hook(self, *args):
        self._hooks.gather_import_mesh_after_hook(*args)

    def gather_import_scene_after_nodes_hook(self, *args):
        self._hooks.gather_import_scene_after_nodes_hook(*args)


def register():
    from . import blender
    blender.register()


def unregister():
    from . import blender
    blender.unregister()
