"""Blender materials through Blender 3.4's bundled POV-Ray exporter and through facet,
each compared with Cycles' own render of the same materials.

    blender -b --factory-startup --python exporters/blender/tests/compare_render_povray.py -- \\
        --facet build/bin/facet [--out DIR] [--size 240x160] [--picture docs/blender_render_povray.png] [--check]

One scene, built here: six smooth UV-sphere meshes on a floor, each with one Blender
material (Diffuse BSDF smooth and rough, Glossy BSDF GGX, Principled BSDF dielectric,
metal and half-metal), a point light (radius 0) and a sun (angle 0), a camera. Three
renders of it at the same size, every one a single ray through each pixel centre:

(i)   Cycles itself: direct light only (max bounces 0), one sample through each pixel
      centre (Gaussian filter of width 0.01), one render per light, added. With one
      light of radius 0 that sample is deterministic (the light sample is the light's
      position; a BSDF sample cannot hit a point light), so this is Cycles' exact direct
      lighting; the noise floor is measured by rendering again with another seed, and
      a 64-sample render with both lights checks that the sum is what Cycles converges
      to. The spheres' Geometry Offset (shadow terminator) is 0, so Cycles' shadow rays
      start on the surface as POV-Ray's and facet's do.
(ii)  render_povray, Blender 3.4's bundled exporter: its `write_pov` writes the .pov
      (as its render engine does), POV-Ray renders it without antialiasing to OpenEXR.
      Its default radiosity is switched off (all three renders are direct light only).
      render_povray reads no shader node: a mesh whose material uses nodes gets an
      empty texture{} per triangle (POV-Ray's default grey). So it is also run with
      every material's Use Nodes off while it exports (its own material path: the
      Viewport Display colour, set here to the node colour as a careful user would, and
      its POV finish settings at their defaults). It takes light colours, not powers.
(iii) facet: the add-on's Convert Blender Material to facet on every material, then its
      Export POV-Ray (facet) with POV-Ray render (one run per light, added; Exposure
      chosen so the 16-bit PNG does not clip). facet's C++ reference render of the
      exported scene is reported too: it separates the mapping (reference vs Cycles)
      from the POV-Ray export (POV-Ray vs reference).

Per material: max |Δ|, mean |Δ| and RMSE over the interior pixels of its sphere (the
pixel and its 8 neighbours show that sphere in Cycles), and the RMSE relative to the
mean Cycles value there. "fit" rows scale each render by the one factor that best
matches Cycles over all spheres (least squares), which removes a global brightness
difference (render_povray ignores light power) and leaves the shape of the lobes.

--check makes it a test (exit status 1 on failure): Cycles' two seeds agree to 1e-6
and the 64-sample two-light render to 1 % on average; facet's exact mapping (Diffuse BSDF, roughness 0 -> lambert) agrees with Cycles within
2e-3 · max(1, |Cycles|) on the Diffuse sphere and the floor; facet's POV-Ray render
agrees with facet's reference within the same tolerance everywhere; and coverage differs
on at most 0.1 % of the pixels. The approximate mappings are measured, not checked.
"""

import array
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib

import bpy
import addon_utils

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_scene import add_uv_sphere, link, point_sampled_cycles  # noqa: E402  (the tests' shared scene building)

HERE = os.path.dirname(os.path.abspath(__file__))
ADDON_ROOT = os.path.dirname(HERE)
ADDON = "facet_blender"
TOL = 2e-3

# name, node builder, label for the tables
MATERIALS = [
    ("Diffuse", "Diffuse BSDF, Roughness 0", {"type": "DIFFUSE", "color": (0.8, 0.25, 0.15), "roughness": 0.0}),
    ("DiffuseRough", "Diffuse BSDF, Roughness 0.5",
     {"type": "DIFFUSE", "color": (0.25, 0.6, 0.3), "roughness": 0.5}),
    ("Glossy", "Glossy BSDF GGX, Roughness 0.3", {"type": "GLOSSY", "color": (0.9, 0.85, 0.8), "roughness": 0.3}),
    ("Plastic", "Principled, Metallic 0, Roughness 0.3",
     {"type": "PRINCIPLED", "color": (0.1, 0.3, 0.8), "metallic": 0.0, "roughness": 0.3}),
    ("Metal", "Principled, Metallic 1, Roughness 0.35",
     {"type": "PRINCIPLED", "color": (0.95, 0.64, 0.54), "metallic": 1.0, "roughness": 0.35}),
    ("HalfMetal", "Principled, Metallic 0.5, Roughness 0.6",
     {"type": "PRINCIPLED", "color": (0.6, 0.6, 0.2), "metallic": 0.5, "roughness": 0.6}),
]
FLOOR = ("Floor", "floor: Diffuse BSDF, Roughness 0", {"type": "DIFFUSE", "color": (0.5, 0.5, 0.5), "roughness": 0.0})
EXACT = {"Diffuse", "Floor"}          # the exact mapping (Diffuse BSDF, Roughness 0 -> lambert)


# ============================================================================ arguments

def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    opts = {"facet": None, "out": None, "size": "240x160", "picture": None, "check": False,
            "povray": shutil.which("povray")}
    it = iter(argv)
    for a in it:
        if a in ("--facet", "--out", "--size", "--picture", "--povray"):
            opts[a[2:]] = next(it)
        elif a == "--check":
            opts["check"] = True
        else:
            raise SystemExit(f"compare_render_povray.py: unknown argument {a!r}")
    if not opts["facet"]:
        raise SystemExit("compare_render_povray.py: --facet PATH is required")
    opts["facet"] = os.path.abspath(opts["facet"])
    w, h = (int(x) for x in opts["size"].lower().split("x"))
    opts["width"], opts["height"] = w, h
    return opts


# ============================================================================ scene

def quad(name, size, material):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([(-size, -size, 0.0), (size, -size, 0.0), (size, size, 0.0), (-size, size, 0.0)], [],
                     [(0, 1, 2, 3)])
    mesh.update()
    mesh.materials.append(material)
    return link(bpy.data.objects.new(name, mesh))


def node_material(name, spec):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.clear()
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    color = tuple(spec["color"]) + (1.0,)
    if spec["type"] == "DIFFUSE":
        node = tree.nodes.new("ShaderNodeBsdfDiffuse")
        node.inputs["Color"].default_value = color
        node.inputs["Roughness"].default_value = spec["roughness"]
    elif spec["type"] == "GLOSSY":
        node = tree.nodes.new("ShaderNodeBsdfGlossy")
        node.distribution = "GGX"
        node.inputs["Color"].default_value = color
        node.inputs["Roughness"].default_value = spec["roughness"]
    else:
        node = tree.nodes.new("ShaderNodeBsdfPrincipled")
        node.distribution = "GGX"
        node.inputs["Base Color"].default_value = color
        node.inputs["Metallic"].default_value = spec["metallic"]
        node.inputs["Roughness"].default_value = spec["roughness"]
    tree.links.new(node.outputs[0], out.inputs["Surface"])
    # What render_povray reads instead of the nodes (Material > Viewport Display).
    mat.diffuse_color = color
    mat.metallic = spec.get("metallic", 0.0)
    mat.roughness = spec["roughness"]
    return mat


def build_scene(width, height):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    world = bpy.data.worlds.new("Black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    world.color = (0.0, 0.0, 0.0)
    scene.world = world
    spheres = []
    for k, (name, _, spec) in enumerate(MATERIALS):
        x = (k % 3 - 1) * 1.25
        y = (k // 3) * 1.25 - 0.3
        sphere = add_uv_sphere(name, (x, y, 0.5), 0.5, 32, 16, True, node_material(name, spec))
        # Cycles' default Geometry Offset (0.1) starts shadow rays off the faceted surface to
        # hide the terminator of coarse meshes; POV-Ray and facet start them on the surface.
        sphere.cycles.shadow_terminator_geometry_offset = 0.0
        spheres.append(sphere)
    quad(FLOOR[0], 6.0, node_material(FLOOR[0], FLOOR[2]))

    from mathutils import Vector
    cam = bpy.data.cameras.new("Camera")
    cam.lens, cam.sensor_fit, cam.sensor_width = 40.0, "AUTO", 36.0
    cam_obj = link(bpy.data.objects.new("Camera", cam))
    cam_obj.location = (0.0, -5.2, 3.4)
    cam_obj.rotation_euler = (Vector((0.0, 0.35, 0.35)) - cam_obj.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam_obj

    point = bpy.data.lights.new("Point", "POINT")
    point.energy, point.color, point.shadow_soft_size = 400.0, (1.0, 0.95, 0.9), 0.0
    point_obj = link(bpy.data.objects.new("Point", point))
    point_obj.location = (-2.5, -3.0, 4.0)
    sun = bpy.data.lights.new("Sun", "SUN")
    sun.energy, sun.color, sun.angle = 1.5, (0.85, 0.9, 1.0), 0.0
    sun_obj = link(bpy.data.objects.new("Sun", sun))
    sun_obj.rotation_euler = (math.radians(50.0), 0.0, math.radians(-40.0))
    bpy.context.view_layer.update()
    return [point_obj, sun_obj]


# ============================================================================ renders

def load_pixels(path, width, height):
    """RGBA rows of an image Blender can read (EXR, PNG), row 0 the BOTTOM row, linear."""
    image = bpy.data.images.load(path, check_existing=False)
    try:
        if tuple(image.size) != (width, height):
            raise RuntimeError(f"{path}: {tuple(image.size)} is not {width}x{height}")
        if not path.lower().endswith(".exr"):
            image.colorspace_settings.name = "Non-Color"        # the stored values themselves
        buf = array.array("f", [0.0]) * (width * height * 4)
        image.pixels.foreach_get(buf)
    finally:
        bpy.data.images.remove(image)
    return [[tuple(buf[4 * (j * width + i):4 * (j * width + i) + 4]) for i in range(width)]
            for j in range(height)]


def cycles_render(path, width, height, seed=0):
    scene = bpy.context.scene
    point_sampled_cycles(scene, seed)
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    return load_pixels(path, width, height)


MANY_SAMPLES = 64


def cycles_render_samples(path, width, height, samples):
    """Both lights at once, `samples` samples per pixel (all within the 0.01-pixel
    Gaussian filter, so at the pixel centre): Cycles picks one light per sample, so this
    is noisy; its mean over the image checks that the per-light sum is what Cycles
    converges to."""
    scene = bpy.context.scene
    point_sampled_cycles(scene, 7)
    scene.cycles.samples = samples
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    return load_pixels(path, width, height)


def add_rows(a, b):
    return [[tuple(x + y for x, y in zip(p, q)) for p, q in zip(ra, rb)] for ra, rb in zip(a, b)]


def cycles_per_light(work, lights, width, height, seed):
    """Cycles with one light at a time (deterministic), the renders added."""
    total = None
    for light in lights:
        for other in lights:
            other.hide_render = other is not light
        rows = cycles_render(os.path.join(work, f"cycles_{light.name}_{seed}.exr"), width, height, seed)
        total = rows if total is None else add_rows(total, rows)
    for light in lights:
        light.hide_render = False
    return total


def cycles_ids(work, objects, width, height):
    """Object number (1..n) at each pixel centre, by Cycles (emission only)."""
    saved = {o.name: [s.material for s in o.material_slots] for o in objects}
    for k, obj in enumerate(objects):
        m = bpy.data.materials.new(f"id{k}")
        m.use_nodes = True
        tree = m.node_tree
        tree.nodes.clear()
        out = tree.nodes.new("ShaderNodeOutputMaterial")
        em = tree.nodes.new("ShaderNodeEmission")
        em.inputs["Color"].default_value = (k + 1.0, 0.0, 0.0, 1.0)
        tree.links.new(em.outputs[0], out.inputs["Surface"])
        obj.material_slots[0].material = m
    rows = cycles_render(os.path.join(work, "ids.exr"), width, height)
    for obj in objects:
        for slot, mat in zip(obj.material_slots, saved[obj.name]):
            slot.material = mat
    return [[int(round(px[0])) if px[3] > 0.5 else 0 for px in row] for row in rows]


def povray_run(povray, folder, pov_name, out_name, width, height, extra=()):
    command = [povray, "+I" + pov_name, "+O" + out_name, f"+W{width}", f"+H{height}", "-A",
               "File_Gamma=1.0", "-D", "-P", "-V"] + list(extra)
    proc = subprocess.run(command, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          errors="replace")
    if proc.returncode != 0:
        raise RuntimeError(f"POV-Ray failed: {' '.join(command)}\n{proc.stdout[-2000:]}")


def render_povray_render(work, povray, width, height, use_nodes=True):
    """Blender 3.4's bundled exporter: its write_pov, then POV-Ray to OpenEXR with alpha
    (no clipping). use_nodes False: every material's Use Nodes switched off while it
    exports (render_povray's own material path: Viewport Display colour and its POV
    finish settings), then back on."""
    mod = addon_utils.enable("render_povray", default_set=True)
    if mod is None:
        raise RuntimeError("the bundled render_povray add-on did not enable")
    from render_povray import render as pov_render
    stem = "render_povray" if use_nodes else "render_povray_legacy"
    path = os.path.join(work, stem + ".pov")
    materials = [m for m in bpy.data.materials if m.users]
    # render_povray turns POV-Ray's radiosity on by default (indirect light, and a render
    # that changes from run to run); Cycles here and facet compute direct light only.
    bpy.context.scene.pov.radio_enable = False
    try:
        for m in materials:
            m.use_nodes = use_nodes
        pov_render.write_pov(path, bpy.context.scene)
    finally:
        for m in materials:
            m.use_nodes = True
    povray_run(povray, work, stem + ".pov", stem + ".exr", width, height, ["+FE", "+UA"])
    return load_pixels(os.path.join(work, stem + ".exr"), width, height)


def povray_alpha(work, povray, pov_name, width, height, extra=()):
    """Coverage (alpha) of a POV-Ray scene at the pixel centres: one run with +UA."""
    povray_run(povray, work, pov_name, "coverage.png", width, height, ["+FN16", "+UA"] + list(extra))
    return [[px[3] > 0.5 for px in row] for row in load_pixels(os.path.join(work, "coverage.png"), width, height)]


def facet_render(work, opts, width, height):
    """The facet add-on: Convert Blender Material to facet, then Export POV-Ray (facet)."""
    from facet_blender.blender import operators
    notes = {}
    for name in [m[0] for m in MATERIALS] + [FLOOR[0]]:
        mat = bpy.data.materials[name]
        with bpy.context.temp_override(material=mat):
            result = bpy.ops.facet.convert_material()
        if result != {"FINISHED"}:
            raise RuntimeError(f"convert_material failed on {name}: {operators.LAST_REPORTS}")
        notes[name] = [m for _, m in operators.LAST_REPORTS]
    scene_path = os.path.join(work, "facet_scene.json")
    bpy.ops.facet.export_scene(filepath=scene_path)
    ref_path = os.path.join(work, "facet_reference.pfm")
    mask_path = os.path.join(work, "facet_mask.pgm")
    subprocess.run([opts["facet"], "render", "--scene", scene_path, "-r", "reference", "--size",
                    f"{width}x{height}", "-o", ref_path, "--mask", mask_path], check=True, stdout=subprocess.DEVNULL)
    reference = read_pfm(ref_path)
    brightest = max(max(px[:3]) for row in reference for px in row)
    exposure = 2.0 ** -math.ceil(math.log2(brightest * 1.05)) if brightest >= 0.95 else 1.0
    bpy.context.preferences.addons[ADDON].preferences.povray_path = opts["povray"]
    pov = os.path.join(work, "facet.pov")
    result = bpy.ops.facet.export_pov(filepath=pov, render=True, exposure=exposure)
    if result != {"FINISHED"}:
        raise RuntimeError(f"export_pov failed: {operators.LAST_REPORTS}")
    rows = load_pixels(os.path.join(work, "facet.png"), width, height)
    rows = [[tuple(c / exposure for c in px[:3]) + (1.0,) for px in row] for row in rows]
    return rows, reference, notes, exposure, [m for _, m in operators.LAST_REPORTS], read_pgm(mask_path)


def read_header(path):
    """(data, the three header lines, where the samples start) of a binary PGM or PFM."""
    with open(path, "rb") as f:
        data = f.read()
    parts, pos = [], 0
    while len(parts) < 3:
        end = data.index(b"\n", pos)
        parts.append(data[pos:end].decode())
        pos = end + 1
    return data, parts, pos


def read_pgm(path):
    """facet render --mask: a binary PGM, rows from the top; returned bottom row first, as read_pfm's."""
    data, parts, pos = read_header(path)
    w, h = map(int, parts[1].split())
    rows = [[data[pos + j * w + i] > 127 for i in range(w)] for j in range(h)]
    return rows[::-1]


def read_pfm(path):
    data, parts, pos = read_header(path)
    w, h = map(int, parts[1].split())
    floats = array.array("f")
    floats.frombytes(data[pos:pos + 12 * w * h])
    if float(parts[2]) > 0:
        floats.byteswap()
    return [[tuple(floats[3 * (j * w + i):3 * (j * w + i) + 3]) + (1.0,) for i in range(w)] for j in range(h)]


# ============================================================================ metrics

def interior(ids, i, j):
    h, w = len(ids), len(ids[0])
    if not (0 < i < w - 1 and 0 < j < h - 1):
        return False
    k = ids[j][i]
    return k > 0 and all(ids[j + dj][i + di] == k for dj in (-1, 0, 1) for di in (-1, 0, 1))


def pixels_of(ids):
    """{object number: [(i, j), ...] interior pixels}."""
    out = {}
    for j in range(len(ids)):
        for i in range(len(ids[0])):
            if interior(ids, i, j):
                out.setdefault(ids[j][i], []).append((i, j))
    return out


def stats(got, ref, pixels, scale=1.0):
    diffs, total = [], 0.0
    for i, j in pixels:
        for c in range(3):
            diffs.append(abs(scale * got[j][i][c] - ref[j][i][c]))
            total += ref[j][i][c]
    n = len(diffs)
    rmse = math.sqrt(sum(d * d for d in diffs) / n)
    mean_ref = total / n
    return {"max": max(diffs), "mean": sum(diffs) / n, "rmse": rmse,
            "rel_rmse": rmse / mean_ref if mean_ref > 0 else float("inf"), "pixels": len(pixels)}


def best_scale(got, ref, groups):
    num = den = 0.0
    for pixels in groups:
        for i, j in pixels:
            for c in range(3):
                num += got[j][i][c] * ref[j][i][c]
                den += got[j][i][c] * got[j][i][c]
    return num / den if den > 0 else 1.0


def coverage(ids, rows, covered):
    return sum(1 for j in range(len(ids)) for i in range(len(ids[0])) if (ids[j][i] > 0) != covered(rows[j][i]))


def max_rel(got, ref, pixels):
    return max(abs(got[j][i][c] - ref[j][i][c]) / max(1.0, abs(ref[j][i][c])) for i, j in pixels for c in range(3))


# ============================================================================ picture

def srgb8(v):
    v = min(max(v, 0.0), 1.0)
    v = 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
    return int(round(255 * v))


def write_picture(path, panels, width, height):
    """Panels side by side (rows of RGB, row 0 the bottom), as an 8-bit sRGB PNG."""
    gap = 4
    total_w = len(panels) * width + (len(panels) - 1) * gap
    lines = []
    for j in range(height - 1, -1, -1):
        line = bytearray()
        for k, rows in enumerate(panels):
            if k:
                line += b"\xff" * (3 * gap)
            for px in rows[j]:
                line += bytes(srgb8(c) for c in px[:3])
        lines.append(b"\x00" + bytes(line))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    data = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", total_w, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(b"".join(lines), 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(data)


def difference(a, b, gain):
    return [[tuple(gain * abs(x - y) for x, y in zip(p[:3], q[:3])) for p, q in zip(ra, rb)] for ra, rb in zip(a, b)]


# ============================================================================ main

def main():
    opts = parse_args()
    width, height = opts["width"], opts["height"]
    work = opts["out"] or tempfile.mkdtemp(prefix="facet-render-povray-")
    os.makedirs(work, exist_ok=True)
    os.environ["FACET_BIN"] = opts["facet"]
    if ADDON_ROOT not in sys.path:
        sys.path.insert(0, ADDON_ROOT)
    t0 = time.perf_counter()
    lights = build_scene(width, height)
    if addon_utils.enable(ADDON, default_set=True, handle_error=None) is None:
        raise SystemExit("the facet add-on did not enable")
    prefs = bpy.context.preferences.addons[ADDON].preferences
    if prefs.facet_path != opts["facet"]:
        prefs.facet_path = opts["facet"]
    objects = [bpy.data.objects[m[0]] for m in MATERIALS] + [bpy.data.objects[FLOOR[0]]]
    labels = {k + 1: (m[0], m[1]) for k, m in enumerate(MATERIALS + [FLOOR])}

    timings = {}
    t = time.perf_counter()
    ids = cycles_ids(work, objects, width, height)
    cycles = cycles_per_light(work, lights, width, height, seed=0)
    cycles_again = cycles_per_light(work, lights, width, height, seed=12345)
    scene = bpy.context.scene
    scene.cycles.samples = MANY_SAMPLES
    converged = None
    try:
        converged = cycles_render_samples(os.path.join(work, "cycles_both_lights.exr"), width, height, MANY_SAMPLES)
    finally:
        scene.cycles.samples = 1
    timings["cycles"] = time.perf_counter() - t
    t = time.perf_counter()
    rp = render_povray_render(work, opts["povray"], width, height)
    rp_legacy = render_povray_render(work, opts["povray"], width, height, use_nodes=False)
    timings["render_povray"] = time.perf_counter() - t
    t = time.perf_counter()
    fc, reference, notes, exposure, export_report, judged = facet_render(work, opts, width, height)
    print("facet export: " + " / ".join(export_report))
    timings["facet"] = time.perf_counter() - t
    fc_alpha = povray_alpha(work, opts["povray"], "facet.pov", width, height, ["Declare=Facet_Light=0"])

    groups = pixels_of(ids)
    all_pixels = [p for k in sorted(groups) for p in groups[k]]
    noise = max(abs(a - b) for row_a, row_b in zip(cycles, cycles_again) for p, q in zip(row_a, row_b)
                for a, b in zip(p[:3], q[:3]))
    scale_rp = best_scale(rp, cycles, groups.values())
    scale_rpl = best_scale(rp_legacy, cycles, groups.values())
    scale_fc = best_scale(fc, cycles, groups.values())
    signed = [converged[j][i][c] - cycles[j][i][c] for i, j in all_pixels for c in range(3)]
    mean_cycles = sum(cycles[j][i][c] for i, j in all_pixels for c in range(3)) / len(signed)
    both_lights = {"samples": MANY_SAMPLES, "rmse": math.sqrt(sum(d * d for d in signed) / len(signed)),
                   "mean_signed": sum(signed) / len(signed), "mean_cycles": mean_cycles}
    results = {"size": [width, height], "noise_floor_max_abs": noise, "exposure_facet": exposure,
               "both_lights_many_samples": both_lights,
               "fit_scale": {"render_povray": scale_rp, "render_povray_legacy": scale_rpl, "facet": scale_fc},
               "materials": {},
               "coverage_mismatch": {"render_povray": coverage(ids, rp, lambda px: px[3] > 0.5),
                                     "render_povray_legacy": coverage(ids, rp_legacy, lambda px: px[3] > 0.5),
                                     "facet_pov": coverage(ids, fc_alpha, lambda covered: covered)},
               # on the pixels facet validate judges: no silhouette, no shadow ray grazing an occluder's edge
               "facet_pov_vs_reference_max_rel": max_rel(fc, reference, [(i, j) for i, j in all_pixels if judged[j][i]]),
               "timings_s": timings, "mapping_notes": notes, "work": work}
    for k in sorted(groups):
        name, label = labels[k]
        px = groups[k]
        results["materials"][name] = {
            "label": label, "pixels": len(px),
            "cycles_mean": sum(cycles[j][i][c] for i, j in px for c in range(3)) / (3 * len(px)),
            "render_povray": stats(rp, cycles, px), "render_povray_fit": stats(rp, cycles, px, scale_rp),
            "render_povray_legacy": stats(rp_legacy, cycles, px),
            "render_povray_legacy_fit": stats(rp_legacy, cycles, px, scale_rpl),
            "facet_pov": stats(fc, cycles, px), "facet_reference": stats(reference, cycles, px),
            "facet_pov_fit": stats(fc, cycles, px, scale_fc),
            "facet_exact_max_rel": max_rel(fc, cycles, [(i, j) for i, j in px if judged[j][i]]) if name in EXACT else None}
    results["timings_s"]["total"] = time.perf_counter() - t0
    with open(os.path.join(work, "results.json"), "w") as f:
        json.dump(results, f, indent=2)

    print_tables(results)
    if opts["picture"]:
        write_picture(opts["picture"], [cycles, rp, rp_legacy, fc, difference(fc, cycles, 8.0)], width, height)
        print(f"picture: {opts['picture']} (Cycles | render_povray | render_povray, Use Nodes off | facet POV-Ray "
              f"| |facet − Cycles| × 8)")
    if opts["out"]:
        print(f"work folder: {work}")
    else:
        shutil.rmtree(work, ignore_errors=True)
    if opts["check"]:
        return check(results)
    return 0


def print_tables(r):
    w, h = r["size"]
    cov = r["coverage_mismatch"]
    print(f"\nBlender {bpy.app.version_string}, {w}x{h}, interior pixels of each sphere; "
          f"Cycles noise floor (two seeds): max |Δ| {r['noise_floor_max_abs']:.3g}")
    b = r["both_lights_many_samples"]
    print(f"Cycles with both lights at {b['samples']} samples vs the per-light sum: RMSE {b['rmse']:.3g} "
          f"(the 64-sample render's noise), mean signed difference {b['mean_signed']:.2g} (mean value {b['mean_cycles']:.3g})")
    print(f"coverage mismatch vs Cycles (of {w * h} pixels): render_povray {cov['render_povray']}, "
          f"render_povray with Use Nodes off {cov['render_povray_legacy']}, facet {cov['facet_pov']}")
    print(f"facet POV-Ray vs facet reference: max |Δ|/max(1,|ref|) {r['facet_pov_vs_reference_max_rel']:.2g} "
          f"(Exposure {r['exposure_facet']:g})")
    fit = r["fit_scale"]
    print(f"best global scale (fit): render_povray × {fit['render_povray']:.4g}, Use Nodes off × "
          f"{fit['render_povray_legacy']:.4g}, facet × {fit['facet']:.4g}\n")
    print("| material | Cycles mean | render_povray: max / mean / RMSE (rel. RMSE) | fit: RMSE (rel.) "
          "| render_povray, Use Nodes off: max / mean / RMSE (rel.) | fit: RMSE (rel.) "
          "| facet POV-Ray: max / mean / RMSE (rel.) | facet reference: RMSE (rel.) |")
    print("|---|---|---|---|---|---|---|---|")

    def cell(m, digits=0):
        return f"{m['max']:.3g} / {m['mean']:.3g} / {m['rmse']:.3g} ({100 * m['rel_rmse']:.{digits}f} %)"

    for name, m in r["materials"].items():
        print(f"| {m['label']} | {m['cycles_mean']:.3f} | {cell(m['render_povray'])} "
              f"| {m['render_povray_fit']['rmse']:.3g} ({100 * m['render_povray_fit']['rel_rmse']:.0f} %) "
              f"| {cell(m['render_povray_legacy'])} "
              f"| {m['render_povray_legacy_fit']['rmse']:.3g} ({100 * m['render_povray_legacy_fit']['rel_rmse']:.0f} %) "
              f"| {cell(m['facet_pov'], 2)} "
              f"| {m['facet_reference']['rmse']:.3g} ({100 * m['facet_reference']['rel_rmse']:.2f} %) |")
    t = r["timings_s"]
    print(f"\nwall time: Cycles {t['cycles']:.1f} s (ids + 2 seeds × 2 lights), render_povray {t['render_povray']:.1f} s "
          f"(2 exports), facet {t['facet']:.1f} s, total {t['total']:.1f} s")


def check(r):
    failures = []
    if r["noise_floor_max_abs"] > 1e-6:
        failures.append(f"Cycles is not deterministic: two seeds differ by {r['noise_floor_max_abs']:.3g}")
    b = r["both_lights_many_samples"]
    if abs(b["mean_signed"]) > 0.01 * b["mean_cycles"]:
        failures.append(f"the per-light sum is not what Cycles converges to with both lights: mean difference "
                        f"{b['mean_signed']:.3g} (> 1 % of {b['mean_cycles']:.3g})")
    w, h = r["size"]
    if r["coverage_mismatch"]["facet_pov"] > w * h // 1000:
        failures.append(f"facet coverage differs from Cycles on {r['coverage_mismatch']['facet_pov']} pixels")
    if r["facet_pov_vs_reference_max_rel"] > TOL:
        failures.append(f"facet POV-Ray vs facet reference: {r['facet_pov_vs_reference_max_rel']:.3g} > {TOL}")
    for name in sorted(EXACT):
        got = r["materials"][name]["facet_exact_max_rel"]
        if got is None or got > TOL:
            failures.append(f"exact mapping of {name}: facet vs Cycles max |Δ|/max(1,|ref|) {got} > {TOL}")
    for f in failures:
        print(f"CHECK FAILED: {f}")
    print("check: " + ("passed" if not failures else f"{len(failures)} failed"))
    return 1 if failures else 0


if __name__ == "__main__":
    try:
        code = main()
    except Exception:  # noqa: BLE001
        import traceback
        traceback.print_exc()
        code = 1
    sys.stdout.flush()
    sys.exit(code)
