"""Add-on preferences: where the facet and POV-Ray executables are."""

import bpy
from bpy.props import StringProperty

from ..core import cli, povray

# The add-on's own module name: "facet_blender" as a legacy add-on,
# "bl_ext.<repository>.facet" as an extension. This module is <root>.blender.preferences.
ADDON_ID = __package__.rpartition(".")[0]


def _facet_path_changed(self, context):
    # A new path may bring the catalog (and the panel's properties) back.
    from . import state
    state.reload(self.facet_path)


class FACET_AP_preferences(bpy.types.AddonPreferences):
    bl_idname = ADDON_ID

    facet_path: StringProperty(
        name="facet executable",
        description="Path of the facet command-line tool, which holds the model catalog and generates "
                    "the GLSL, OSL and POV-Ray code. Default: facet on PATH, else $FACET_BIN",
        subtype="FILE_PATH",
        default=cli.default_facet_path(),
        update=_facet_path_changed,
    )
    povray_path: StringProperty(
        name="POV-Ray executable",
        description="Path of POV-Ray 3.7 (povray), used to render exported POV-Ray scenes. "
                    "Default: povray on PATH",
        subtype="FILE_PATH",
        default=povray.default_povray_path(),
    )

    def draw(self, context):
        from . import state
        layout = self.layout
        layout.prop(self, "facet_path")
        c = state.STATE.catalog
        if c and state.STATE.exe:
            layout.label(text=f"facet {c.version}: {len(c.models('diffuse'))} diffuse and "
                              f"{len(c.models('specular'))} specular models ({state.STATE.exe})",
                         icon="CHECKMARK")
            if state.STATE.differs:
                layout.label(text="facet's catalog differs from the one bundled with the add-on: facet's is used",
                             icon="INFO")
        else:
            for line in state.STATE.error.splitlines() or ["facet is not loaded"]:
                layout.label(text=line, icon="ERROR")
            if c:
                layout.label(text=f"Using the catalog bundled with the add-on (facet {c.version})", icon="INFO")
        layout.operator("facet.reload_catalog", icon="FILE_REFRESH")
        layout.prop(self, "povray_path")


def get(context=None):
    """The preferences, or None when the add-on is registered without an add-on entry
    (e.g. by calling register() directly from a script)."""
    context = context or bpy.context
    addon = context.preferences.addons.get(ADDON_ID)
    return addon.preferences if addon else None


def facet_path_setting(context=None):
    prefs = get(context)
    return prefs.facet_path if prefs else ""


def facet_exe(context=None):
    """The facet executable to run (raises a UserError that says where to set it)."""
    return cli.find_facet(facet_path_setting(context))


def povray_exe(context=None):
    """The POV-Ray executable to run (raises a UserError that says where to set it)."""
    prefs = get(context)
    return povray.find_povray(prefs.povray_path if prefs else "")


classes = (FACET_AP_preferences,)
