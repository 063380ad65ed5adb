"""The facet panel (Properties > Material > facet) and the File > Export entries.

The panel draws whatever the property plan holds, so it follows the catalog: the
model drop-downs list facet's models, and the parameters below them are the chosen
model's, with the catalog's documentation as tooltips.
"""

import bpy

from ..core import cli, native as core_native, props as plan_mod
from . import material as material_mod, osl, osl_lights, state
from .operators import context_material


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


def _ready(context):
    mat = context_material(context)
    return state.STATE.catalog is not None and mat is not None and material_mod.has_settings(mat)


class FACET_PT_material(bpy.types.Panel):
    bl_label = "facet"
    bl_idname = "FACET_PT_material"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return context_material(context) is not None

    def draw_header(self, context):
        mat = context_material(context)
        if state.STATE.catalog is not None and hasattr(mat, "facet"):
            self.layout.prop(mat.facet, plan_mod.USE_FACET, text="")

    def draw(self, context):
        layout = self.layout
        mat = context_material(context)
        if state.STATE.catalog is None:
            box = layout.box()
            box.label(text="facet is not available", icon="ERROR")
            for line in state.STATE.error.splitlines():
                box.label(text=line)
            if cli.PREFERENCES_HINT not in state.STATE.error:     # said once: most errors say it already
                box.label(text=f"Set the facet executable in {cli.PREFERENCES_HINT}")
            box.operator("facet.reload_catalog", icon="FILE_REFRESH")
            return
        row = layout.row(align=True)
        row.operator("facet.import_material", text="Import", icon="IMPORT")
        row.operator("facet.export_material", text="Export", icon="EXPORT")
        layout.operator("facet.convert_material", text="From Blender Nodes", icon="NODETREE")
        if not material_mod.has_settings(mat):
            layout.label(text="Enable facet (the box in this panel's header) to edit facet settings")
            return
        try:
            bindings = material_mod.texture_bindings(mat)
        except Exception as e:  # noqa: BLE001 - a panel must draw
            bindings = []
            layout.label(text=str(e), icon="ERROR")
        if bindings:
            box = layout.box()
            box.label(text="Textures (exported with the material; the values below stand in for them):",
                      icon="TEXTURE")
            for b in bindings:
                where = ".".join(b["path"]) + (f" ({b['model']})" if b.get("model") else "")
                baked = f", {b['derive']['op']} baked" if b.get("derive") else ""
                box.label(text=f"{where} <- image '{b['spec']['image']}'{baked}")


class _LobePanel:
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"
    bl_parent_id = "FACET_PT_material"
    section = ""

    @classmethod
    def poll(cls, context):
        return _ready(context)

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        catalog, plan = state.STATE.catalog, state.STATE.plan
        settings = context_material(context).facet
        chosen = getattr(settings, f"{self.section}_model")
        layout.prop(settings, f"{self.section}_model", text="Model")
        if chosen == plan_mod.NONE:
            return
        model = catalog.model(self.section, chosen)
        info = layout.column(align=True)
        info.scale_y = 0.8
        info.label(text=model.formula)
        if model.citation:
            info.label(text=model.citation)
        info.label(text=core_native.summary(model.blender_nodes))
        draw_fields(layout, getattr(settings, f"{self.section}_{chosen}"),
                    plan.field(f"{self.section}_{chosen}").group)


class FACET_PT_diffuse(_LobePanel, bpy.types.Panel):
    bl_label = "Diffuse"
    bl_idname = "FACET_PT_diffuse"
    section = "diffuse"


class FACET_PT_specular(_LobePanel, bpy.types.Panel):
    bl_label = "Specular"
    bl_idname = "FACET_PT_specular"
    section = "specular"


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
                box.label(text=head, icon="ERROR")
                box.label(text="Regenerate" + tail)
                box.operator("facet.generate_osl", text="Regenerate OSL", icon="FILE_REFRESH")
        col.operator("facet.export_pov", text="Export Scene to POV-Ray...", icon="SCENE")


def menu_export(self, context):
    self.layout.operator("facet.export_pov", text="facet: POV-Ray Scene (.pov)")
    self.layout.operator("facet.export_scene", text="facet: Scene (.json)")


classes = (FACET_PT_material, FACET_PT_diffuse, FACET_PT_specular, FACET_PT_surface, FACET_PT_generate)


def register_menus():
    bpy.types.TOPBAR_MT_file_export.append(menu_export)


def unregister_menus():
    bpy.types.TOPBAR_MT_file_export.remove(menu_export)
