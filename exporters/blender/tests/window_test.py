"""The facet panel in a real Blender window: every model drawn, no Python error, a screenshot.

    xvfb-run -a -s "-screen 0 1280x900x24" blender --factory-startup \\
        --python exporters/blender/tests/window_test.py -- --facet build/bin/facet --screenshot panel.png

Not headless (-b draws nothing): Blender opens its window (on Xvfb, a virtual X server),
enables the add-on, gives the startup cube's material facet settings, turns the
Properties editor to the Material tab and, for every diffuse and every specular model of
the catalog, sets it on the material and redraws the window (wm.redraw_timer). Each
facet panel's draw() is wrapped: an exception in it is recorded (and re-raised, as
Blender would report it), and each (panel, model) draw is counted, so a model whose
panel was never drawn is a failure too. Then it saves the Properties editor as a PNG
(screen.screenshot_area) and exits 0, or 1 naming every draw() error.

--break-draw makes the Specular panel's draw() raise for one model: the run must then
fail and name it (ctest addon.window34.broken_draw_fails checks that it does).
"""

import os
import sys
import traceback

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
ADDON_ROOT = os.path.dirname(HERE)
ADDON = "facet_blender"
BROKEN_MODEL = "ggx"

ERRORS = []     # (panel, model, traceback text)
DRAWN = set()   # (panel, section, model)
ORDER = []      # the material panels in the order the last redraw laid them out


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    opts = {"facet": None, "screenshot": None, "break_draw": False}
    it = iter(argv)
    for a in it:
        if a == "--facet":
            opts["facet"] = os.path.abspath(next(it))
        elif a == "--screenshot":
            opts["screenshot"] = os.path.abspath(next(it))
        elif a == "--break-draw":
            opts["break_draw"] = True
        else:
            raise SystemExit(f"window_test.py: unknown argument {a!r}")
    if not opts["facet"]:
        raise SystemExit("window_test.py: --facet PATH is required")
    return opts


def chosen(context, section):
    mat = getattr(context, "material", None)
    settings = getattr(mat, "facet", None)
    return getattr(settings, f"{section}_model", "") if section else ""


def watch(cls):
    """Wraps cls.draw: counts the draw, records (and re-raises) any exception."""
    original = cls.draw

    def draw(self, context):
        section = getattr(cls, "section", "")
        model = chosen(context, section)
        DRAWN.add((cls.__name__, section, model))
        ORDER.append(cls.__name__)
        try:
            original(self, context)
        except Exception:
            ERRORS.append((cls.__name__, model, traceback.format_exc()))
            raise
    cls.draw = draw


def log_order(cls):
    """Wraps a (Blender's own) material panel's draw to log the layout order."""
    original = cls.draw

    def draw(self, context):
        ORDER.append(cls.__name__)
        original(self, context)
    cls.draw = draw


def placement_error():
    """The facet panel must come before Blender's own material panels that have a header
    (Preview, Surface, Settings...): right under the material slots."""
    if "FACET_PT_material" not in ORDER:
        return f"the facet panel was not drawn: {ORDER}"
    first = ORDER.index("FACET_PT_material")
    before = [name for name in ORDER[:first] if not name.endswith("_context_material")]
    return f"Blender's panels {before} come before the facet panel ({ORDER})" if before else ""


def break_specular(ui):
    original = ui.FACET_PT_specular.draw

    def draw(self, context):
        if chosen(context, "specular") == BROKEN_MODEL:
            raise RuntimeError("deliberately broken draw")
        original(self, context)
    ui.FACET_PT_specular.draw = draw


def properties_area(window):
    """The Properties editor of the window, on the Material tab."""
    for area in window.screen.areas:
        if area.type == "PROPERTIES":
            area.spaces.active.context = "MATERIAL"
            return area
    raise SystemExit("window_test.py: the startup screen has no Properties editor")


def redraw(window, iterations=1):
    with bpy.context.temp_override(window=window):
        bpy.ops.wm.redraw_timer(type="DRAW_WIN_SWAP", iterations=iterations)


def main():
    opts = parse_args()
    if bpy.app.background:
        raise SystemExit("window_test.py: run it with a window (xvfb-run ... blender, without -b)")
    sys.path.insert(0, ADDON_ROOT)
    import addon_utils
    if addon_utils.enable(ADDON, default_set=True, handle_error=None) is None:
        raise SystemExit("window_test.py: the add-on did not enable")
    bpy.context.preferences.addons[ADDON].preferences.facet_path = opts["facet"]
    from facet_blender.blender import state, ui
    if not state.STATE.exe:
        raise SystemExit(f"window_test.py: facet did not load: {state.STATE.error}")
    if opts["break_draw"]:
        break_specular(ui)
    for cls in ui.classes:
        watch(cls)
    for cls in bpy.types.Panel.__subclasses__():
        if getattr(cls, "bl_context", "") == "material" and cls not in ui.classes and hasattr(cls, "draw"):
            log_order(cls)

    cube = bpy.data.objects["Cube"]
    mat = cube.active_material or bpy.data.materials.new("Material")
    if cube.active_material is None:
        cube.data.materials.append(mat)
    bpy.context.view_layer.objects.active = cube
    mat.facet.use_facet = True
    window = bpy.context.window_manager.windows[0]
    area = properties_area(window)
    catalog = state.STATE.catalog
    expected = set()
    for section, other, other_model in (("diffuse", "specular", "none"), ("specular", "diffuse", "lambert")):
        setattr(mat.facet, f"{other}_model", other_model)
        panel = "FACET_PT_" + section
        for model in catalog.models(section):
            setattr(mat.facet, f"{section}_model", model.name)
            redraw(window)
            expected.add((panel, section, model.name))
    # The picture the docs show: Lambert + Cook-Torrance, the formulas wrapped.
    mat.facet.diffuse_model, mat.facet.specular_model = "lambert", "cook_torrance"
    ORDER.clear()
    redraw(window)
    placement, order = placement_error(), list(ORDER)
    # The picture, from the event loop (a timer), once the panels' open/move animation ran.
    bpy.app.timers.register(lambda: guarded(finish, opts, window, area, expected, placement, order),
                            first_interval=2.0)
    return None


def finish(opts, window, area, expected, placement, order):
    catalog = __import__("facet_blender.blender.state", fromlist=["STATE"]).STATE.catalog
    missing = sorted(expected - DRAWN)
    if opts["screenshot"]:
        os.makedirs(os.path.dirname(opts["screenshot"]), exist_ok=True)
        with bpy.context.temp_override(window=window, area=area):
            bpy.ops.screen.screenshot_area(filepath=opts["screenshot"])
        print(f"screenshot of the Properties editor ({area.width}x{area.height}): {opts['screenshot']}")
    print(f"Blender {bpy.app.version_string} with a window: {len(expected)} models drawn "
          f"({len(catalog.models('diffuse'))} diffuse, {len(catalog.models('specular'))} specular), "
          f"{len(DRAWN)} (panel, model) draws seen, {len(ERRORS)} draw() errors")
    for panel, model, text in ERRORS:
        print(f"draw() of {panel} ({model}) raised:\n{text}")
    failures = []
    if ERRORS:
        failures.append(f"{len(ERRORS)} draw() error(s): " + "; ".join(
            f"{panel} ({model}): {text.strip().splitlines()[-1]}" for panel, model, text in ERRORS))
    if missing:
        failures.append(f"panels never drawn: {missing}")
    if placement:
        failures.append(placement)
    print(f"material panels in order: {order}")
    if opts["screenshot"] and not os.path.exists(opts["screenshot"]):
        failures.append(f"no screenshot written at {opts['screenshot']}")
    print("WINDOW TEST FAILED: " + " | ".join(failures) if failures else "WINDOW TEST PASSED", flush=True)
    leave(1 if failures else 0)


def leave(code):
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)     # a windowed Blender would otherwise keep running its event loop


def guarded(fn, *args):
    try:
        fn(*args)
    except SystemExit as e:
        print(e, flush=True)
        leave(1)
    except Exception:  # noqa: BLE001
        traceback.print_exc()
        leave(1)


if __name__ == "__main__":
    guarded(main)
