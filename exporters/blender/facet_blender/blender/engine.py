"""The "facet POV-Ray" render engine: F12 (bpy.ops.render.render) exports the scene
through facet and renders it with POV-Ray in the background.

The convention of Blender's own POV-Ray add-on and of every external renderer: a
`bpy.types.RenderEngine` whose render() writes the scene for the renderer, runs it as a
subprocess in a temporary folder and loads its image into the Render Result, which the
Image Editor shows. Here the scene is exported exactly as File > Export > POV-Ray
(facet) exports it (scene_data.full_scene, pov.generate_scene: a material without facet
settings is converted, with a warning) and POV-Ray runs as core/povray.Job: polled,
with Blender's progress bar (`update_progress`, `update_stats`); Esc (`test_break`)
kills every POV-Ray run (its whole process group) and the temporary folder is removed
in every case.

Render properties (scene.facet_povray, the "facet POV-Ray" panel of the Render tab,
shown only for this engine):
    validation  the exact mode of `facet validate` and Export POV-Ray: no anti-aliasing,
                one ray through each pixel centre, full quality (+Q9); the image equals
                facet's reference within validation's tolerance. Off by default.
    antialias, threshold, depth, method, quality
                POV-Ray's +A<threshold> +AM<method> +R<depth> and +Q<quality>, used
                when validation is off. Defaults: on, 0.3, 3, adaptive (2), 9 (POV-Ray's
                own defaults for +A, +R and +Q; +AM2 for its quality on edges).
    max_radiance  "Range": the brightest radiance kept (POV-Ray's 16-bit images hold
                0..1: the scene is rendered × 1/Range and the Render Result scaled
                back). Default 1. A render in which pixels reach it warns how many
                clipped.

The Render Result holds scene-linear radiance (alpha 1). The messages of the last render
are kept in LAST_REPORTS [(level, message), ...] for scripts and tests.
"""

import os
import shutil
import tempfile
import time
import types

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty

from ..core import UserError, cli, generate, pov, povray
from . import preferences, scene_data

ENGINE_ID = "FACET_POVRAY"
POLL_SECONDS = 0.1
LAST_REPORTS = []
SCENE_FILE = "scene.pov"
# Blender's own panels shown for this engine too (besides those for BLENDER_RENDER):
# the material slots and the World's colour, which the export reads.
EXTRA_PANELS = ("EEVEE_MATERIAL_PT_context_material", "EEVEE_WORLD_PT_surface")


class FACET_PG_povray_render(bpy.types.PropertyGroup):
    validation: BoolProperty(
        name="Validation (exact)",
        description="Render as facet validate and Export POV-Ray do: no anti-aliasing (one ray through each "
                    "pixel centre) at full quality, so the image equals facet's reference render pixel by "
                    "pixel; the settings below are not used",
        default=False)
    antialias: BoolProperty(
        name="Anti-Aliasing", description="Supersample pixels whose neighbours differ (POV-Ray +A)", default=True)
    threshold: FloatProperty(
        name="Threshold", description="Supersample where a pixel differs from its neighbours by more than "
                                      "this (POV-Ray +A<threshold>; lower is smoother and slower)",
        default=0.3, min=0.0, max=3.0, precision=3)
    depth: IntProperty(
        name="Depth", description="Supersampling depth (POV-Ray +R<depth>): up to (depth+1)² rays per pixel "
                                  "with the non-recursive method, recursion levels with the adaptive one",
        default=3, min=1, max=9)
    method: EnumProperty(
        name="Method",
        items=(("1", "Non-Recursive", "POV-Ray +AM1: a fixed grid in pixels that need it"),
               ("2", "Adaptive", "POV-Ray +AM2: recursive subdivision where the corners differ")),
        default="2")
    quality: IntProperty(
        name="Quality", description="POV-Ray +Q<quality>: 9 renders everything facet's scenes use; lower "
                                    "values leave out shadows (below 4) and other features",
        default=9, min=0, max=11)
    max_radiance: FloatProperty(
        name="Range", description="The brightest radiance the Render Result keeps: POV-Ray's 16-bit images "
                                  "hold 0..1, so the scene is rendered × 1/Range and scaled back (brighter "
                                  "values clip; each step is Range/65535)",
        default=1.0, min=1e-3, soft_max=64.0)


def settings_of(props):
    """core/povray.Settings of the scene's render properties."""
    if props.validation:
        return povray.EXACT
    return povray.Settings(antialias=props.antialias, threshold=props.threshold, depth=props.depth,
                           method=int(props.method), quality=props.quality)


def clipped_pixels(samples, limit=65535 * 0.98):
    """How many pixels of 16-bit RGB samples reach the top of the range in some channel:
    their radiance was at least Range and is lost (POV-Ray clips at full scale)."""
    return sum(1 for i in range(0, len(samples) - 2, 3)
               if samples[i] >= limit or samples[i + 1] >= limit or samples[i + 2] >= limit)


def result_rect(width, height, samples, scale):
    """Render Result pixels (RGBA rows bottom first) of 16-bit RGB samples (top row first)."""
    k = scale / 65535.0
    rect = []
    for y in range(height - 1, -1, -1):
        row = 3 * width * y
        rect.extend([samples[i] * k, samples[i + 1] * k, samples[i + 2] * k, 1.0]
                    for i in range(row, row + 3 * width, 3))
    return rect


class FACET_RE_povray(bpy.types.RenderEngine):
    """facet's materials rendered by POV-Ray, exactly as facet generates them"""
    bl_idname = ENGINE_ID
    bl_label = "facet POV-Ray"
    bl_use_preview = False
    bl_use_postprocess = True

    def report_(self, level, message):
        LAST_REPORTS.append((level, message))
        self.report({level}, message)

    # Python methods (Blender's own, test_break and update_progress, are looked up in RNA
    # before the class, so a script or test cannot wrap those).
    def cancelled(self):
        """Esc pressed (Blender's test_break)."""
        return self.test_break()

    def show_progress(self, done, stats, shown=""):
        """Blender's progress bar at `done` (0..1) and `stats` in its status line, unless
        it already shows it (in the background Blender prints each); returns it."""
        self.update_progress(done)
        if stats != shown:
            self.update_stats("", stats)
        return stats

    def render(self, depsgraph):
        LAST_REPORTS.clear()
        folder = tempfile.mkdtemp(prefix="facet-render-")
        try:
            self._render(depsgraph, folder)
        except UserError as e:
            self.report_("ERROR", str(e))
        finally:
            shutil.rmtree(folder, ignore_errors=True)

    def _export(self, depsgraph, folder):
        """(pov.Plan, notes): the scene written to folder/scene.pov as Export POV-Ray writes it."""
        self.update_stats("", "facet: exporting the scene")
        exe = preferences.facet_exe()
        pov.require_scene_support(exe)
        context = types.SimpleNamespace(scene=depsgraph.scene, evaluated_depsgraph_get=lambda: depsgraph)
        data, notes, files = scene_data.full_scene(context, generate.texturable_material_keys(exe), [SCENE_FILE])
        plan = pov.generate_scene(exe, data, depsgraph.scene.name, os.path.join(folder, SCENE_FILE), files)
        if files:                       # the images the scene names, beside the .pov
            cli.write_all_atomic(folder, files)
        return plan, notes

    def _render(self, depsgraph, folder):
        scene = depsgraph.scene
        props = scene.facet_povray
        povray_path = preferences.povray_exe()
        plan, notes = self._export(depsgraph, folder)
        for note in notes:
            self.report_("WARNING", note)
        width, height = scene_data.render_size(scene)
        t0, shown = time.monotonic(), ""
        with povray.Job(povray_path, os.path.join(folder, SCENE_FILE), plan, width, height,
                        1.0 / props.max_radiance, settings_of(props)) as job:
            while not job.poll():
                if self.cancelled():                           # Esc: the Job's close kills every run
                    self.report_("INFO", "facet POV-Ray: render cancelled")
                    return
                done = job.progress()
                shown = self.show_progress(done, f"facet POV-Ray: {plan.passes} run{'s' * (plan.passes > 1)}, "
                                                 f"{100 * done:.0f} %, {time.monotonic() - t0:.0f} s", shown)
                time.sleep(POLL_SECONDS)
            w, h, samples = job.image()
        result = self.begin_result(0, 0, w, h)
        result.layers[0].passes["Combined"].rect = result_rect(w, h, samples, props.max_radiance)
        self.end_result(result)
        clipped = clipped_pixels(samples)
        if clipped:
            self.report_("WARNING", f"facet POV-Ray: {clipped} of {w * h} pixels ({100.0 * clipped / (w * h):.1f} %) "
                                    f"reached Range ({props.max_radiance:g}) and clipped there: their radiance is "
                                    f"lost; raise Range in the facet POV-Ray render panel")
        self.show_progress(1.0, f"facet POV-Ray: {w}x{h} rendered")
        self.report_("INFO", f"facet POV-Ray: {w}x{h} in {time.monotonic() - t0:.1f} s, {plan.passes} "
                             f"run{'s' * (plan.passes > 1)}" + (", validation (exact)" if props.validation else ""))


class FACET_PT_povray_render(bpy.types.Panel):
    bl_label = "facet POV-Ray"
    bl_idname = "FACET_PT_povray_render"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {ENGINE_ID}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        props = context.scene.facet_povray
        layout = self.layout
        layout.use_property_split = True
        layout.prop(props, "validation")
        col = layout.column()
        col.active = not props.validation
        col.prop(props, "antialias")
        sub = col.column()
        sub.active = props.antialias
        sub.prop(props, "method")
        sub.prop(props, "threshold")
        sub.prop(props, "depth")
        col.prop(props, "quality")
        layout.prop(props, "max_radiance")


classes = (FACET_PG_povray_render, FACET_RE_povray, FACET_PT_povray_render)


def compatible_panels():
    """Blender's panels that draw for BLENDER_RENDER, and EXTRA_PANELS (as Blender's
    RenderEngine template does): Output, Format, camera, light and material slots."""
    found = [p for p in bpy.types.Panel.__subclasses__() if "BLENDER_RENDER" in getattr(p, "COMPAT_ENGINES", ())]
    return found + [getattr(bpy.types, name) for name in EXTRA_PANELS if hasattr(bpy.types, name)]


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.facet_povray = PointerProperty(type=FACET_PG_povray_render)
    for panel in compatible_panels():
        panel.COMPAT_ENGINES.add(ENGINE_ID)


def unregister():
    for panel in compatible_panels():
        panel.COMPAT_ENGINES.discard(ENGINE_ID)
    del bpy.types.Scene.facet_povray
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
