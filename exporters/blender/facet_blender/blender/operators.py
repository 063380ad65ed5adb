"""The add-on's operators. Each one checks its context in poll(), reads the Blender data
it needs into plain data, hands that to core (which runs facet and POV-Ray and writes
files whole or not at all) and writes the results back into Blender; a problem ends it
with one clear error report and nothing written.

Operators (bl_idname):
    facet.export_material    material facet settings -> material JSON (checked by facet)
    facet.import_material    material JSON (checked by facet) -> facet settings
    facet.export_glsl        facet generate --target glsl|glsl450|essl [--library]
    facet.generate_osl       facet generate --target osl --scene (the Blender lights)
                             -> Text + Script node wired to the Material Output (needs OSL),
                             its light inputs driven by the light objects (osl_lights);
                             the scene switched to Cycles/CPU/OSL only with configure_scene
    facet.convert_material   Diffuse / Glossy / Principled BSDF -> facet settings
    facet.export_scene       the whole scene -> facet scene JSON (materials + meshes)
    facet.export_pov         the whole scene -> POV-Ray (facet generate --target pov
                             --scene), optionally rendered by POV-Ray into an Image
                             (both scene exports: a material without facet settings is
                             exported as convert_material would set it, with a warning,
                             unless `strict`)
    facet.reload_catalog     runs facet again (after setting its path)

For scripts, the messages of the last run of any of them are kept in LAST_REPORTS
[(level, message), ...] (Blender also raises RuntimeError for an error report).
"""

import os

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from ..core import UserError, cli, generate, osl as core_osl, pov, povray, textures
from ..core.convert import IGNORED, map_surface
from . import images, material as material_mod, nodes, osl, osl_lights, preferences, scene_data, state

LAST_REPORTS = []


def context_material(context):
    """The material the panel shows: context.material (Properties editor, or a
    context override), else the active object's active material."""
    mat = getattr(context, "material", None)
    if mat is None:
        obj = getattr(context, "object", None)
        mat = getattr(obj, "active_material", None) if obj else None
    return mat


class _FacetOperator:
    """execute() runs self.run(context); a UserError becomes one error report."""

    def report_(self, level, message):
        LAST_REPORTS.append((level, message))
        self.report({level}, message)

    def execute(self, context):
        LAST_REPORTS.clear()
        try:
            return self.run(context) or {"FINISHED"}
        except UserError as e:
            self.report_("ERROR", str(e))
            return {"CANCELLED"}

    def run(self, context):
        raise NotImplementedError


class _MaterialOperator(_FacetOperator):
    @classmethod
    def poll(cls, context):
        if context_material(context) is None:
            cls.poll_message_set("No active material: select an object with a material")
            return False
        return True


# ----------------------------------------------------------------------------- material JSON

class FACET_OT_export_material(_MaterialOperator, ExportHelper, bpy.types.Operator):
    """Write the material's facet settings as a facet material file (JSON), checked by facet"""
    bl_idname = "facet.export_material"
    bl_label = "Export facet Material"
    bl_options = {"REGISTER"}
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def invoke(self, context, event):
        mat = context_material(context)
        if mat is not None and not self.filepath:
            self.filepath = generate.safe_name(mat.name) + ".json"
        return ExportHelper.invoke(self, context, event)

    def run(self, context):
        mat = context_material(context)
        exe = preferences.facet_exe(context)
        data, files, _, notes = textured_files(exe, mat, meshes=False)
        generate.export_material(exe, data, mat.name, self.filepath, files)
        for note in notes:
            self.report_("WARNING", note)
        self.report_("INFO", f"Exported material '{mat.name}' to {self.filepath}")


class FACET_OT_import_material(_FacetOperator, ImportHelper, bpy.types.Operator):
    """Read a facet material file (JSON) into the material's facet settings, after facet checked it"""
    bl_idname = "facet.import_material"
    bl_label = "Import facet Material"
    bl_options = {"REGISTER", "UNDO"}
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def run(self, context):
        exe = preferences.facet_exe(context)
        state.require()
        data = generate.read_material(exe, self.filepath)   # facet's own error lines if it is not valid
        mat = context_material(context)
        created = mat is None
        if created:
            mat = bpy.data.materials.new(data.get("name") or "facet")
            obj = context.object
            if obj is not None and hasattr(obj.data, "materials"):
                obj.data.materials.append(mat)
                obj.active_material_index = len(obj.material_slots) - 1
        for note in material_mod.from_json(mat, data, os.path.dirname(os.path.abspath(self.filepath))):
            self.report_("WARNING", note)
        self.report_("INFO", f"Imported facet material '{data.get('name', '?')}' into "
                             f"{'new ' if created else ''}material '{mat.name}'")


# ----------------------------------------------------------------------------- GLSL, OSL

class FACET_OT_export_glsl(_MaterialOperator, ExportHelper, bpy.types.Operator):
    """Generate GLSL from the material's facet settings (facet generate)"""
    bl_idname = "facet.export_glsl"
    bl_label = "Export GLSL"
    bl_options = {"REGISTER"}
    filename_ext = ".glsl"
    filter_glob: StringProperty(default="*.glsl;*.frag;*.vert", options={"HIDDEN"})
    dialect: EnumProperty(
        name="Dialect",
        items=(("glsl", "GLSL 3.30", "OpenGL 3.3 core fragment shader"),
               ("glsl450", "GLSL 4.50 (Vulkan)", "Vulkan GLSL, compiles to SPIR-V with glslangValidator -V"),
               ("essl", "ESSL 3.00", "OpenGL ES 3.00 / WebGL 2")),
        default="glsl")
    library: BoolProperty(
        name="Library Only",
        description="Only the functions and facet_reflect(n, l, v, t), for an engine; "
                    "otherwise a standalone fragment shader with the lights as uniforms",
        default=False)

    def invoke(self, context, event):
        mat = context_material(context)
        if mat is not None and not self.filepath:
            self.filepath = generate.safe_name(mat.name) + ".glsl"
        return ExportHelper.invoke(self, context, event)

    def run(self, context):
        mat = context_material(context)
        exe = preferences.facet_exe(context)
        data, files, _, notes = textured_files(exe, mat, meshes=False)
        generate.code_to(exe, data, mat.name, self.filepath, self.dialect, self.library, files)
        for note in notes:
            self.report_("WARNING", note)
        self.report_("INFO", f"Wrote {self.dialect}{' library' if self.library else ''} of '{mat.name}' "
                             f"to {self.filepath}")


class FACET_OT_generate_osl(_MaterialOperator, bpy.types.Operator):
    """Generate an OSL shader lit by this scene's lights (its light inputs driven by the light objects) and put it in a Script node wired to the Material Output"""
    bl_idname = "facet.generate_osl"
    bl_label = "Generate OSL"
    bl_options = {"REGISTER", "UNDO"}
    configure_scene: BoolProperty(
        name="Switch Scene to Cycles OSL",
        description="Also set the scene's Render Engine to Cycles, Device to CPU and Open Shading Language on, "
                    "which the Script node needs to render; off, the scene is left alone and the report says "
                    "what to switch",
        default=False)

    def invoke(self, context, event):
        # Asked, not done silently: a dialog with the switch (off) when the scene needs it.
        if context.scene is not None and osl.scene_settings_to_switch(context.scene):
            return context.window_manager.invoke_props_dialog(self, width=420)
        return self.execute(context)

    def draw(self, context):
        layout = self.layout
        layout.label(text="The scene must render with Cycles, CPU, Open Shading Language:")
        layout.label(text="switch " + ", ".join(osl.scene_settings_to_switch(context.scene)) + "?")
        layout.prop(self, "configure_scene")

    def run(self, context):
        mat = context_material(context)
        ok, why = osl.available()
        if not ok:
            raise UserError(f"{why}: Generate OSL needs Cycles with OSL (e.g. the official Blender 4.x "
                            f"builds); material '{mat.name}' was not changed")
        catalog, _ = state.require()
        exe = preferences.facet_exe(context)
        scene_json, notes, sources = scene_data.lights_scene(context, catalog)
        data, uv_maps, more = textured_material(exe, mat)
        notes += more
        osl_text = generate.osl_shader(exe, data, mat.name, scene_json, context.scene.name)
        names = [name for name, _, _ in sources]
        header = core_osl.addon_header(names, {name for name, obj, _ in sources if obj is not None})
        script = osl.install(mat, core_osl.with_addon_header(osl_text, header), generate.osl_text_name(mat.name),
                             uv_maps)
        notes += osl_lights.drive(mat.node_tree, script, sources)
        lights = len(sources)
        for note in notes:
            self.report_("WARNING", note)
        message = (f"Generated OSL for '{mat.name}' lit by {lights} light{'s' * (lights != 1)}, its inputs "
                   f"driven by the light objects (regenerate only after adding or removing lights)")
        if self.configure_scene:
            osl.configure_scene(context.scene)
            message += "; scene set to Cycles, CPU, OSL"
        switch = osl.scene_settings_to_switch(context.scene)
        if switch:
            self.report_("WARNING", f"scene '{context.scene.name}' left as it is: for a render to run the shader, "
                                    f"switch {', '.join(switch)} (Render Properties), or run Generate OSL with "
                                    f"'Switch Scene to Cycles OSL'")
        self.report_("INFO", message)


def texture_folder(material):
    """Where Generate OSL writes a material's texture files: //facet_textures/<material>
    beside the saved .blend, else a new temporary folder."""
    if bpy.data.filepath:
        folder = os.path.join(bpy.path.abspath("//facet_textures"), generate.safe_name(material.name))
        os.makedirs(folder, exist_ok=True)
        return folder, []
    import tempfile
    folder = tempfile.mkdtemp(prefix="facet-textures-")
    return folder, [f"material '{material.name}': the .blend is not saved; its texture files are in {folder}"]


def textured_files(exe, mat, meshes=True):
    """(material JSON naming its texture images relatively, {file name: bytes} of those
    images, UV map names of sets 0 and 1, notes) of one material; `meshes` False for a
    material file alone, which keeps a normal map wherever facet's material files take one."""
    data = material_mod.to_json(mat)
    bindings = material_mod.texture_bindings(mat)
    if not bindings:
        return data, {}, [], []
    keys = generate.texturable_material_keys(exe, meshes)
    names, files, notes = images.texture_files({mat.name: textures.exported(bindings, keys)})
    data, more = textures.apply(data, bindings, names[mat.name], keys)
    return data, files, textures.uv_maps(bindings, mat.name), notes + more


def textured_material(exe, mat):
    """(material JSON with its textures as absolute files, UV map names of sets 0 and 1,
    notes) for generating OSL: the images are written to `texture_folder`."""
    data, files, uv_maps, notes = textured_files(exe, mat)
    if not files:
        return data, uv_maps, notes
    folder, where = texture_folder(mat)
    cli.write_all_atomic(folder, files)
    return textures.absolute(data, folder), uv_maps, notes + where


# ----------------------------------------------------------------------------- Blender nodes -> facet

class FACET_OT_convert_material(_MaterialOperator, bpy.types.Operator):
    """Set the facet settings from the Diffuse, Glossy or Principled BSDF feeding the Material Output (reports which mappings are exact)"""
    bl_idname = "facet.convert_material"
    bl_label = "Convert Blender Material to facet"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        mat = context_material(context)
        state.require()
        result = map_surface(nodes.surface_description(mat), mat.name)
        material_mod.set_lobes(mat, result)
        for level, message in result.notes:
            if level == IGNORED:
                self.report_("WARNING", message)
        images_used = sorted({b["spec"]["image"] for b in result.textures if textures.has_image(b)})
        self.report_("INFO", f"Converted '{mat.name}' to {result.headline()}"
                             + (f", textured by {', '.join(repr(i) for i in images_used)}" if images_used else "")
                             + ":\n" + "\n".join(result.summary()))


# ----------------------------------------------------------------------------- scenes

STRICT_DESCRIPTION = ("Refuse a material without facet settings instead of exporting what 'Convert Blender "
                      "Material to facet' makes of its Blender nodes (approximate; a warning names it)")


class FACET_OT_export_scene(_FacetOperator, ExportHelper, bpy.types.Operator):
    """Write the scene as a facet scene file (JSON): camera, World ambient, lights, meshes and their facet materials"""
    bl_idname = "facet.export_scene"
    bl_label = "Export facet Scene"
    bl_options = {"REGISTER"}
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})
    strict: BoolProperty(name="Strict", description=STRICT_DESCRIPTION, default=False)

    @classmethod
    def poll(cls, context):
        return context.scene is not None

    def run(self, context):
        exe = preferences.facet_exe(context)
        data, notes, files = scene_data.full_scene(context, generate.texturable_material_keys(exe),
                                                   [os.path.basename(self.filepath)], self.strict)
        folder = os.path.dirname(os.path.abspath(self.filepath))
        # The images first, the scene that names them last.
        cli.write_all_atomic(folder, dict(files, **{os.path.basename(self.filepath): cli.dump_json(data)}))
        for note in notes:
            self.report_("WARNING", note)
        self.report_("INFO", f"Exported scene '{context.scene.name}' ({len(data['objects'])} meshes, "
                             f"{len(data['lights'])} lights) to {self.filepath}")


class FACET_OT_export_pov(_FacetOperator, ExportHelper, bpy.types.Operator):
    """Export the scene to POV-Ray through facet (every object with its facet material) and optionally render it"""
    bl_idname = "facet.export_pov"
    bl_label = "Export POV-Ray (facet)"
    bl_options = {"REGISTER"}
    filename_ext = ".pov"
    filter_glob: StringProperty(default="*.pov", options={"HIDDEN"})
    render: BoolProperty(
        name="Render with POV-Ray",
        description="Run POV-Ray at the scene's render resolution (linear 16-bit PNG beside the .pov) "
                    "and load the image into Blender",
        default=True)
    save_scene: BoolProperty(
        name="Save facet Scene",
        description="Also write the facet scene file (JSON) beside the .pov",
        default=False)
    exposure: FloatProperty(
        name="Exposure",
        description="POV-Ray render: every radiance is multiplied by this before the PNG, which clips "
                    "at 1, is written (the PNG holds radiance × exposure); below 1 keeps bright highlights",
        default=1.0, min=1e-6, soft_min=0.01, soft_max=1.0)
    strict: BoolProperty(name="Strict", description=STRICT_DESCRIPTION, default=False)

    @classmethod
    def poll(cls, context):
        if context.scene is None or context.scene.camera is None:
            cls.poll_message_set("The scene needs an active camera")
            return False
        return True

    def run(self, context):
        exe = preferences.facet_exe(context)
        pov.require_scene_support(exe)
        # converts (or, strict, names) a material without settings; reads every image before anything is written
        stem = os.path.splitext(self.filepath)[0]
        reserved = [os.path.basename(stem) + ext for ext in (".pov", ".png", ".json")]
        data, notes, files = scene_data.full_scene(context, generate.texturable_material_keys(exe), reserved,
                                                   self.strict)
        povray_path = preferences.povray_exe(context) if self.render else None
        width, height = scene_data.render_size(context.scene)
        name = os.path.basename(stem)
        # Everything is written and rendered in a folder beside the .pov and moved beside it
        # only when all of it worked: a failed POV-Ray run leaves no .pov, no side file, and
        # a previous export (and its PNG) whole.
        with cli.staged(self.filepath) as stage:
            staged_pov = os.path.join(stage, os.path.basename(self.filepath))
            plan = pov.generate_scene(exe, data, context.scene.name, staged_pov, files)   # facet's pass count
            beside = dict(files)
            if self.save_scene:
                beside[name + ".json"] = cli.dump_json(data)
            if beside:     # the images the scene names, beside the .pov (and the scene, last)
                cli.write_all_atomic(stage, beside)
            if povray_path:
                runs = povray.render(povray_path, staged_pov, plan, os.path.join(stage, name + ".png"),
                                     width, height, self.exposure)
        for note in notes:
            self.report_("WARNING", note)
        message = f"Exported scene '{context.scene.name}' to {self.filepath}"
        if povray_path:
            png = stem + ".png"
            image = load_image(png, f"{context.scene.name} (POV-Ray)")
            message += (f"; rendered {width}x{height} to {png} (image '{image.name}'"
                        + (f", {runs} POV-Ray runs, one per light, added" if runs > 1 else "")
                        + (f", radiance × {self.exposure:g}" if self.exposure != 1.0 else "") + ")")
        self.report_("INFO", message)


def load_image(path, name):
    """Loads (or reloads) the rendered PNG as an Image holding linear values."""
    image = bpy.data.images.get(name)
    if image is None or image.source != "FILE":
        image = bpy.data.images.load(path, check_existing=False)
        image.name = name
    else:
        image.filepath = path
        image.reload()
    for space in ("Linear Rec.709", "Linear"):   # 4.x / 3.x names of scene-linear Rec. 709
        try:
            image.colorspace_settings.name = space
            break
        except TypeError:
            continue
    return image


# ----------------------------------------------------------------------------- catalog

class FACET_OT_reload_catalog(bpy.types.Operator):
    """Run facet again to read its model catalog (after setting its path in the preferences)"""
    bl_idname = "facet.reload_catalog"
    bl_label = "Reload facet Catalog"
    bl_options = {"REGISTER"}

    def execute(self, context):
        LAST_REPORTS.clear()
        if state.reload(preferences.facet_path_setting(context)):
            LAST_REPORTS.append(("INFO", f"facet {state.STATE.catalog.version} loaded from {state.STATE.exe}"))
            self.report({"INFO"}, LAST_REPORTS[-1][1])
            return {"FINISHED"}
        LAST_REPORTS.append(("ERROR", state.STATE.error))
        self.report({"ERROR"}, state.STATE.error)
        return {"CANCELLED"}


classes = (
    FACET_OT_export_material,
    FACET_OT_import_material,
    FACET_OT_export_glsl,
    FACET_OT_generate_osl,
    FACET_OT_convert_material,
    FACET_OT_export_scene,
    FACET_OT_export_pov,
    FACET_OT_reload_catalog,
)
