"""The facet panel (Properties > Material > facet) and the File > Export entries.

The panel draws whatever the property plan holds, so it follows the catalog: the
model drop-downs list facet's models, and the parameters below them are the chosen
model's, with the catalog's documentation as tooltips.

Where people look: the panel has no header, which places it right below the material
slots, above Blender's own Preview and Surface panels (PANEL_OPTIONS says why). Blender's
labels do not wrap, they are cut at the editor's edge; every long line (formula,
citation, messages) goes through `wrapped_label`, which wraps it to the region's width.
"""

import textwrap

import bpy

from ..core import cli, native as core_native, props as plan_mod, textures
from ..core.catalog import LAYER_SECTION
from . import material as material_mod, osl, osl_lights, state
from .operators import context_material


# Where the panel goes: Blender lists header-less panels before every panel with a header
# (rna_ui's "no header has priority"), in registration order. bl_order cannot do it: it has
# a hard minimum of 0, which all of Blender's own material panels have, so an add-on panel
# with a header always comes after Surface, Volume and Settings. Header-less, FACET_PT_material
# sits right under the material slots and selector, above Preview and Surface; its lobe
# panels (Diffuse, Specular, ...) are its sub-panels, with headers, and fold as usual.
PANEL_OPTIONS = {"HIDE_HEADER"}

# Width estimate of Blender's UI font: 7 px a character at UI scale 1 (DejaVu Sans /
# Inter at 11 pt average ~6 px; 7 leaves room for wide glyphs such as "ω" and "—"),
# and the panel's own margins, both scaled by Preferences > Interface > Resolution Scale.
CHAR_PX = 7.0
MARGIN_PX = 30.0
ICON_CHARS = 3              # an icon takes about three characters' width
DEFAULT_WIDTH_PX = 320.0    # when the context has no region (drawn from a script)
MIN_CHARS = 16


def line_chars(context):
    """How many characters of text fit on one line of the region `context` draws in."""
    region = getattr(context, "region", None)
    width = float(getattr(region, "width", 0) or DEFAULT_WIDTH_PX)
    prefs = getattr(context, "preferences", None)
    scale = float(prefs.system.ui_scale) if prefs is not None else 1.0
    return max(MIN_CHARS, int((width - MARGIN_PX * scale) / (CHAR_PX * scale)))


def wrap(text, chars):
    """`text` as lines of at most `chars` characters (words kept whole where they fit;
    a word longer than a line is split); its own line breaks are kept."""
    lines = []
    for paragraph in str(text).splitlines() or [""]:
        lines += textwrap.wrap(paragraph, max(1, chars), break_on_hyphens=False) or [""]
    return lines


def wrapped_label(layout, context, text, icon="NONE"):
    """`text` as labels that fit the region's width; the icon, if any, on the first line
    and its width kept free on the others, so continued lines stay aligned."""
    chars = line_chars(context) - (ICON_CHARS if icon != "NONE" else 0)
    col = layout.column(align=True)
    for i, line in enumerate(wrap(text, chars)):
        col.label(text=line, icon=icon if i == 0 or icon == "NONE" else "BLANK1")
    return col


def draw_fields(layout, pg, group):
    """The fields of a lobe group: plain parameters, then nested Fresnel/toon boxes."""
    col = layout.column()
    for f in group.fields:
        if f.kind != "group":
            col.prop(pg, f.id)
    for f in group.fields:
        if f.kind != "group":
            continue
        sub = getattr(pg, f.id)
        box = layout.box()
        if f.nested == "model":                       # e.g. Fresnel: model + its parameters
            box.prop(sub, "model", text=f.label)
            for g in f.group.fields:
                if g.owner == sub.model:
                    box.prop(sub, g.id)
        else:                                          # e.g. toon: a switch + its parameters
            box.prop(sub, "enabled")
            inner = box.column()
            inner.active = sub.enabled
            for g in f.group.fields:
                if g.id != "enabled":
                    inner.prop(sub, g.id)


def _nodes_line(catalog, model, pg, group):
    """The Blender nodes line: the lobe's, or an enabled modifier's that replaces its node
    (toon: Toon BSDF), named."""
    for f in group.fields:
        if f.kind == "group" and f.nested == "object" and getattr(pg, f.id).enabled:
            modifier = catalog.model("modifier", f.key)
            if modifier is not None and modifier.blender_nodes:
                return f"With {modifier.title}: " + core_native.summary(modifier.blender_nodes)
    return core_native.summary(model.blender_nodes)


def _ready(context):
    mat = context_material(context)
    return state.STATE.catalog is not None and mat is not None and material_mod.has_settings(mat)


def draw_not_found(layout, context):
    """The box that says why facet is not used and what to set: the reason, and where to
    set the path only when the reason does not say it already (said once)."""
    box = layout.box()
    box.label(text="facet is not available", icon="ERROR")
    wrapped_label(box, context, state.STATE.error)
    if cli.PREFERENCES_HINT not in state.STATE.error:
        wrapped_label(box, context, f"Set the facet executable in {cli.PREFERENCES_HINT}")
    if state.STATE.catalog is not None:
        wrapped_label(box, context, f"Editing with the catalog bundled with the add-on (facet "
                                    f"{state.STATE.catalog.version}); exporting needs facet.")
    box.operator("facet.reload_catalog", icon="FILE_REFRESH")


class FACET_PT_material(bpy.types.Panel):
    bl_label = "facet"
    bl_idname = "FACET_PT_material"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    bl_options = PANEL_OPTIONS

    @classmethod
    def poll(cls, context):
        return context_material(context) is not None

    def draw(self, context):
        layout = self.layout
        mat = context_material(context)
        if state.STATE.error:
            draw_not_found(layout, context)
        if state.STATE.catalog is None or not hasattr(mat, "facet"):
            return
        # No header (see PANEL_OPTIONS): the switch is the panel's first line, beside the buttons
        # that give a material facet settings; the rest shows only once it is on.
        row = layout.row(align=True)
        row.prop(mat.facet, plan_mod.USE_FACET, text="facet")
        row.operator("facet.convert_material", text="From Blender Nodes", icon="NODETREE")
        row = layout.row(align=True)
        row.operator("facet.import_material", text="Import", icon="IMPORT")
        row.operator("facet.export_material", text="Export", icon="EXPORT")
        if not material_mod.has_settings(mat):
            return
        try:
            bindings = material_mod.texture_bindings(mat)
        except Exception as e:  # noqa: BLE001 - a panel must draw
            bindings = []
            wrapped_label(layout, context, str(e), icon="ERROR")
        if bindings:
            box = layout.box()
            wrapped_label(box, context, "Textures (exported with the material; the values below stand in for them):",
                          icon="TEXTURE")
            for b in bindings:
                where = textures.key_path(b["path"]) + (f" ({b['model']})" if b.get("model") else "")
                baked = f", {b['derive']['op']} baked" if b.get("derive") else ""
                wrapped_label(box, context, f"{where} <- image '{b['spec']['image']}'{baked}")


class _LobePanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    bl_parent_id = "FACET_PT_material"
    section = ""   # the catalog section its drop-down chooses from
    slot = ""      # the drop-down (properties "<slot>_model", "<slot>_<model>"); the section's name for lobes

    @classmethod
    def poll(cls, context):
        # A layer slot only where this facet's catalog has layers (the plan has its drop-down).
        return _ready(context) and any(f.id == f"{cls.slot or cls.section}_model" for f in state.STATE.plan.fields)

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        catalog, plan = state.STATE.catalog, state.STATE.plan
        settings = context_material(context).facet
        slot = getattr(self, "slot", "") or self.section  # the tests draw with a stand-in self
        chosen = getattr(settings, f"{slot}_model")
        layout.prop(settings, f"{slot}_model", text="Model")
        if chosen == plan_mod.NONE:
            return
        model = catalog.model(self.section, chosen)
        info = layout.column(align=True)
        info.scale_y = 0.8
        wrapped_label(info, context, model.formula)
        if model.citation:
            wrapped_label(info, context, model.citation)
        wrapped_label(info, context, _nodes_line(catalog, model, getattr(settings, f"{slot}_{chosen}"),
                                                 plan.field(f"{slot}_{chosen}").group))
        draw_fields(layout, getattr(settings, f"{slot}_{chosen}"), plan.field(f"{slot}_{chosen}").group)


class FACET_PT_diffuse(_LobePanel, bpy.types.Panel):
    bl_label = "Diffuse"
    bl_idname = "FACET_PT_diffuse"
    section = "diffuse"


class FACET_PT_specular(_LobePanel, bpy.types.Panel):
    bl_label = "Specular"
    bl_idname = "FACET_PT_specular"
    section = "specular"


class FACET_PT_layer0(_LobePanel, bpy.types.Panel):
    bl_label = "Layer over the Lobes"
    bl_idname = "FACET_PT_layer0"
    bl_options = {"DEFAULT_CLOSED"}
    section = LAYER_SECTION
    slot = "layer0"


class FACET_PT_layer1(_LobePanel, bpy.types.Panel):
    bl_label = "Layer over Layer 0"
    bl_idname = "FACET_PT_layer1"
    bl_options = {"DEFAULT_CLOSED"}
    section = LAYER_SECTION
    slot = "layer1"


class FACET_PT_surface(bpy.types.Panel):
    bl_label = "Ambient, Emission, Tangent"
    bl_idname = "FACET_PT_surface"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    bl_parent_id = "FACET_PT_material"
    bl_options = {"DEFAULT_CLOSED"}

    @classmethod
    def poll(cls, context):
        return _ready(context)

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        settings = context_material(context).facet
        for k in state.STATE.catalog.material_keys:
            layout.prop(settings, k.name)


class FACET_PT_generate(bpy.types.Panel):
    bl_label = "Generate"
    bl_idname = "FACET_PT_generate"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    bl_parent_id = "FACET_PT_material"

    @classmethod
    def poll(cls, context):
        return _ready(context)

    def draw(self, context):
        col = self.layout.column(align=True)
        col.operator("facet.export_glsl", text="Export GLSL...", icon="FILE_SCRIPT")
        col.operator("facet.build_native_nodes", text="Build Blender Nodes", icon="NODE_MATERIAL")
        if osl.available()[0]:          # hidden, not refused, where Cycles has no OSL (Debian's 3.4)
            col.operator("facet.generate_osl", text="Generate OSL (Cycles)", icon="SHADING_RENDERED")
            view_layer = getattr(context, "view_layer", None) or bpy.context.view_layer
            changed = osl_lights.changed_lights(context_material(context), view_layer.depsgraph)
            if changed:
                box = self.layout.box()
                head, _, tail = changed.partition(": regenerate")
                wrapped_label(box, context, head, icon="ERROR")
                wrapped_label(box, context, "Regenerate" + tail)
                box.operator("facet.generate_osl", text="Regenerate OSL", icon="FILE_REFRESH")
        col.operator("facet.export_pov", text="Export Scene to POV-Ray...", icon="SCENE")


def menu_export(self, context):
    self.layout.operator("facet.export_pov", text="facet: POV-Ray Scene (.pov)")
    self.layout.operator("facet.export_scene", text="facet: Scene (.json)")


classes = (FACET_PT_material, FACET_PT_diffuse, FACET_PT_specular, FACET_PT_layer0, FACET_PT_layer1, FACET_PT_surface,
           FACET_PT_generate)


def register_menus():
    bpy.types.TOPBAR_MT_file_export.append(menu_export)


def unregister_menus():
    bpy.types.TOPBAR_MT_file_export.remove(menu_export)
