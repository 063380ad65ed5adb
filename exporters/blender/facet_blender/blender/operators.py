"""The add-on's operators. Each one checks its context in poll(), does its work through
the facet executable and writes files whole or not at all (a temporary file, then
os.replace); a problem ends it with one clear error report and nothing written.

Operators (bl_idname):
    facet.export_material    material facet settings -> material JSON (checked by facet)
    facet.import_material    material JSON (checked by facet) -> facet settings
    facet.export_glsl        facet generate --target glsl|glsl450|essl [--library]
    facet.generate_osl       facet generate --target osl --scene (the Blender lights)
                             -> Text + Script node wired to the Material Output (needs OSL)
    facet.convert_material   Diffuse / Glossy / Principled BSDF -> facet settings
    facet.export_scene       the whole scene -> facet scene JSON (materials + meshes)
    facet.export_pov         the whole scene -> POV-Ray (facet generate --target pov
                             --scene), optionally rendered by POV-Ray into an Image
    facet.reload_catalog     runs facet again (after setting its path)

For scripts, the messages of the last run of any of them are kept in LAST_REPORTS
[(level, message), ...] (Blender also raises RuntimeError for an error report).
"""

import json
import os
import re
import subprocess
import tempfile

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from ..core import UserError, cli, pov
from ..core.convert import map_surface
from . import material as material_mod, nodes, osl, preferences, scene_data, state

LAST_REPORTS = []


def context_material(context):
    """The material the panel shows: context.material (Properties editor, or a
    context override), else the active object's active material."""
    mat = getattr(context, "material", None)
    if mat is None:
        obj = getattr(context, "object", None)
        mat = getattr(obj, "active_material", None) if obj else None
    return mat


def _safe_name(name):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._") or "material"


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


def _write_material_temp(folder, material):
    """The material's JSON in `folder`; returns (path, data, replace map for messages)."""
    data = material_mod.to_json(material)
    path = os.path.join(folder, _safe_name(material.name) + ".json")
    cli.write_atomic(path, cli.dump_json(data))
    return path, data, {path: f"material '{material.name}'"}


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
            self.filepath = _safe_name(mat.name) + ".json"
        return ExportHelper.invoke(self, context, event)

    def run(self, context):
        mat = context_material(context)
        exe = preferences.facet_exe(context)
        with tempfile.TemporaryDirectory(prefix="facet-") as tmp:
            path, data, replace = _write_material_temp(tmp, mat)
            cli.validate_material(exe, path, replace)
        cli.write_atomic(self.filepath, cli.dump_json(data))
        self.report_("INFO", f"Exported material '{mat.name}' to {self.filepath}")


class FACET_OT_import_material(_FacetOperator, ImportHelper, bpy.types.Operator):
    """Read a facet material file (JSON) into the material's facet settings, after facet checked it"""
    bl_idname = "facet.import_material"
    bl_label = "Import facet Material"
    bl_options = {"REGISTER", "UNDO"}
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def run(self, context):
        path = self.filepath
        exe = preferences.facet_exe(context)
        state.require()
        if not os.path.isfile(path):
            raise UserError(f"no such file: {path}")
        cli.validate_material(exe, path)          # facet's own error lines if it is not valid
        try:
            with open(path, encoding="utf-8") as f:
                data = json.load(f)
        except (OSError, ValueError) as e:
            raise UserError(f"cannot read {path}: {e}")
        mat = context_material(context)
        created = mat is None
        if created:
            mat = bpy.data.materials.new(data.get("name") or "facet")
            obj = context.object
            if obj is not None and hasattr(obj.data, "materials"):
                obj.data.materials.append(mat)
                obj.active_material_index = len(obj.material_slots) - 1
        material_mod.from_json(mat, data)
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
            self.filepath = _safe_name(mat.name) + ".glsl"
        return ExportHelper.invoke(self, context, event)

    def run(self, context):
        mat = context_material(context)
        exe = preferences.facet_exe(context)
        with tempfile.TemporaryDirectory(prefix="facet-") as tmp:
            path, _, replace = _write_material_temp(tmp, mat)
            args = [path, "--target", self.dialect] + (["--library"] if self.library else [])
            cli.generate_to(exe, self.filepath, args, replace)
        self.report_("INFO", f"Wrote {self.dialect}{' library' if self.library else ''} of '{mat.name}' "
                             f"to {self.filepath}")


class FACET_OT_generate_osl(_MaterialOperator, bpy.types.Operator):
    """Generate an OSL shader lit by this scene's lights, put it in a Script node wired to the Material Output, and switch the scene to Cycles with OSL"""
    bl_idname = "facet.generate_osl"
    bl_label = "Generate OSL"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        mat = context_material(context)
        ok, why = osl.available()
        if not ok:
            raise UserError(f"{why}: Generate OSL needs Cycles with OSL (e.g. the official Blender 4.x "
                            f"builds); material '{mat.name}' was not changed")
        catalog, _ = state.require()
        exe = preferences.facet_exe(context)
        scene_json, notes = scene_data.lights_scene(context, catalog)
        with tempfile.TemporaryDirectory(prefix="facet-") as tmp:
            path, _, replace = _write_material_temp(tmp, mat)
            scene_path = os.path.join(tmp, "scene.json")
            replace[scene_path] = f"scene '{context.scene.name}'"
            cli.write_atomic(scene_path, cli.dump_json(scene_json))
            osl_path = os.path.join(tmp, "material.osl")
            cli.generate_to(exe, osl_path, [path, "--target", "osl", "--scene", scene_path], replace)
            with open(osl_path, encoding="utf-8") as f:
                osl_text = f.read()
        osl.install(mat, osl_text, f"facet_{_safe_name(mat.name)}.osl")
        osl.configure_scene(context.scene)
        lights = len(scene_json["lights"])
        for note in notes:
            self.report_("WARNING", note)
        self.report_("INFO", f"Generated OSL for '{mat.name}' lit by {lights} light{'s' * (lights != 1)} "
                             f"(regenerate after moving lights); scene set to Cycles, CPU, OSL")


# ----------------------------------------------------------------------------- Blender nodes -> facet

class FACET_OT_convert_material(_MaterialOperator, bpy.types.Operator):
    """Set the facet settings from the Diffuse, Glossy or Principled BSDF feeding the Material Output (reports which mappings are exact)"""
    bl_idname = "facet.convert_material"
    bl_label = "Convert Blender Material to facet"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        mat = context_material(context)
        state.require()
        result = map_surface(nodes.surface_description(mat))
        material_mod.set_lobes(mat, result)
        lobes = " + ".join(f"{s} {getattr(result, s)['model']}" for s in ("diffuse", "specular")
                           if getattr(result, s))
        verdict = "exact" if result.exact else "approximate"
        self.report_("INFO", f"Converted '{mat.name}' to {lobes} ({verdict}):\n" + "\n".join(result.summary()))


# ----------------------------------------------------------------------------- scenes

def _scene_support(exe):
    has_materials, has_meshes = cli.scene_support(cli.scene_schema(exe))
    if not (has_materials and has_meshes):
        raise UserError("facet lacks scene materials/meshes: this facet executable cannot read a scene "
                        "with per-object materials and meshes yet (facet schema --scene); update facet")


class FACET_OT_export_scene(_FacetOperator, ExportHelper, bpy.types.Operator):
    """Write the scene as a facet scene file (JSON): camera, World ambient, lights, meshes and their facet materials"""
    bl_idname = "facet.export_scene"
    bl_label = "Export facet Scene"
    bl_options = {"REGISTER"}
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    @classmethod
    def poll(cls, context):
        return context.scene is not None

    def run(self, context):
        data, notes = scene_data.full_scene(context)
        cli.write_atomic(self.filepath, cli.dump_json(data))
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

    @classmethod
    def poll(cls, context):
        if context.scene is None or context.scene.camera is None:
            cls.poll_message_set("The scene needs an active camera")
            return False
        return True

    def run(self, context):
        exe = preferences.facet_exe(context)
        data, notes = scene_data.full_scene(context)       # names a material without settings
        _scene_support(exe)
        povray = preferences.povray_exe(context) if self.render else None
        stem = os.path.splitext(self.filepath)[0]
        with tempfile.TemporaryDirectory(prefix="facet-") as tmp:
            scene_path = os.path.join(tmp, "scene.json")
            cli.write_atomic(scene_path, cli.dump_json(data))
            cli.generate_to(exe, self.filepath, ["--target", "pov", "--scene", scene_path],
                            {scene_path: f"scene '{context.scene.name}'"})
        if self.save_scene:
            cli.write_atomic(stem + ".json", cli.dump_json(data))
        for note in notes:
            self.report_("WARNING", note)
        message = f"Exported scene '{context.scene.name}' to {self.filepath}"
        if povray:
            png = stem + ".png"
            width, height = scene_data.render_size(context.scene)
            if self.exposure != 1.0:
                _check_exposure_hook(self.filepath)
            runs = run_povray(povray, self.filepath, png, width, height, self.exposure)
            image = load_image(png, f"{context.scene.name} (POV-Ray)")
            message += (f"; rendered {width}x{height} to {png} (image '{image.name}'"
                        + (f", {runs} POV-Ray runs, one per light, added" if runs > 1 else "")
                        + (f", radiance × {self.exposure:g}" if self.exposure != 1.0 else "") + ")")
        self.report_("INFO", message)


EXPOSURE_DECLARATION = "Facet_Exposure"


def _check_exposure_hook(pov_path):
    """facet's POV-Ray scenes declare Facet_Exposure near their top; make sure this one does."""
    if EXPOSURE_DECLARATION not in pov.read_header(pov_path):
        raise UserError(f"{pov_path} does not declare {EXPOSURE_DECLARATION} (an older facet?): "
                        f"render with Exposure 1")


def _povray(povray, folder, pov_name, out_name, width, height, options):
    """One POV-Ray run in `folder`; returns the Popen (output in its .communicate())."""
    # POV-Ray's I/O restrictions allow the working folder: run it there with plain names.
    command = [povray, "+I" + pov_name, "+O" + out_name, f"+W{width}", f"+H{height}", "-A",
               "File_Gamma=1.0", "-D", "-P", "-V"] + options
    try:
        return subprocess.Popen(command, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True, errors="replace")
    except OSError as e:
        raise UserError(f"cannot run POV-Ray '{povray}': {e}")


def _finish(proc, out_path, what):
    try:
        stdout, stderr = proc.communicate(timeout=3600)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        raise UserError(f"POV-Ray took more than an hour ({what}); stopped")
    if proc.returncode != 0 or not os.path.exists(out_path) or os.path.getsize(out_path) == 0:
        why = f"exit status {proc.returncode}" if proc.returncode != 0 else "it wrote no image"
        lines = [l for l in (stderr + stdout).splitlines() if l.strip()][-8:]
        raise UserError(f"POV-Ray failed ({what}; {why}):\n" + "\n".join(lines))


def run_povray(povray, pov_path, png_path, width, height, exposure=1.0):
    """Renders `pov_path` to `png_path` (linear 16-bit PNG, whole or not at all); the PNG
    holds radiance × `exposure` (facet's scenes declare Facet_Exposure for that).

    A scene whose function pigments hold one light each (core/pov.py) is rendered the
    exact way: one run per light (Declare=Facet_Light=i), as many at a time as there are
    processors, each a 16-bit PPM, added up. Returns the number of runs."""
    folder = os.path.dirname(os.path.abspath(pov_path))
    count = pov.passes(pov.read_header(pov_path))
    options = [f"Declare={EXPOSURE_DECLARATION}={exposure!r}"] if exposure != 1.0 else []
    with tempfile.TemporaryDirectory(prefix=".facet-pov-", dir=folder) as tmp:
        name = os.path.basename(tmp)
        if count == 1:
            out = os.path.join(tmp, "render.png")
            _finish(_povray(povray, folder, os.path.basename(pov_path), os.path.join(name, "render.png"),
                            width, height, ["+FN16"] + options), out, "one run")
            result = out
        else:
            outs = [os.path.join(tmp, f"pass{i}.ppm") for i in range(count)]
            running, at_once = [], max(1, os.cpu_count() or 1)
            try:
                for i in range(count):
                    if len(running) >= at_once:
                        _finish(*running.pop(0))
                    running.append((_povray(povray, folder, os.path.basename(pov_path),
                                            os.path.join(name, f"pass{i}.ppm"), width, height,
                                            ["+FP16", f"Declare=Facet_Light={i}"] + options),
                                    outs[i], f"pass {i + 1} of {count}"))
                while running:
                    _finish(*running.pop(0))
            finally:
                for proc, _, _ in running:          # after a failure: stop the others
                    proc.kill()
                    proc.communicate()
            images = [pov.read_ppm16(path) for path in outs]
            if any(img[:2] != (width, height) for img in images):
                raise UserError(f"POV-Ray wrote images of another size than {width}x{height}")
            result = os.path.join(tmp, "sum.png")
            with open(result, "wb") as f:
                f.write(pov.png16(width, height, pov.add_clipped([img[2] for img in images])))
        with open(result, "rb") as f:
            cli.write_atomic(png_path, f.read())
    return count


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
