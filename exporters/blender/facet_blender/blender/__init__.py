"""The Blender half of the facet add-on: preferences, properties, panel, operators,
the "facet POV-Ray" render engine (engine.py).

Everything here reads or writes Blender data and delegates the rest to `..core`.
"""

import bpy

from . import engine, native, operators, preferences, state, ui

_CLASSES = preferences.classes + operators.classes + native.classes + ui.classes


def register():
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    ui.register_menus()
    engine.register()
    # The catalog last: without facet the add-on still registers, and the panel says why.
    state.load(preferences.facet_path_setting())


def unregister():
    state.unload()
    engine.unregister()
    ui.unregister_menus()
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
