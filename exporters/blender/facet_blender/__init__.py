"""facet for Blender: edit facet materials (classic and physically based reflection
models) on Blender materials, and generate GLSL, OSL (Cycles) and POV-Ray from them.

A thin layer over the facet command-line tool, which holds the model catalog and the
code generators: the panel is built from `facet models --json`, and every export runs
`facet generate`. `core/` is free of bpy (plain data + the facet CLI); `blender/`
reads and writes Blender data.

Loads as a Blender 4.2+ extension (blender_manifest.toml) and as a legacy add-on
(bl_info) in Blender 3.4+.
"""

bl_info = {
    "name": "facet",
    "author": "facet contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Material > facet; File > Export > facet",
    "description": "facet materials: classic and physically based reflection models "
                   "-> GLSL, OSL and POV-Ray, through the facet command-line tool",
    "category": "Material",
}


def register():
    from . import blender
    blender.register()


def unregister():
    from . import blender
    blender.unregister()
