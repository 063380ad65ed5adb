"""Lights in the file's units against Cycles (issue 27, acceptance): the scene Blender's glTF
exporter wrote (gltf_corpus.py: corpus/blender_lights.glb from blender/lights.blend: the
default 1000 W point light, an 800 W spot of blend 0, a 2 W/m² sun, all of radius 0), imported
by `facet import-gltf` and rendered by facet's reference, against Cycles' render of the .blend
itself, at pixel centres.

    python gltf_lights_cycles.py --facet FACET --corpus FOLDER --work DIR [--size 96x72]

(a Python with pip bpy 4.5). Cycles runs as docs/blender.md's point sampler
(exporters/blender/tests/blender_scene.py `point_sampled_cycles`: CPU, 1 sample through each
pixel centre with a 0.01-pixel Gaussian filter, max bounces 0, light sampling threshold 0, no
denoising, Standard view transform), Geometry Offset 0 on every mesh (Cycles' default 0.1
starts shadow rays off a faceted surface, facet starts them on it), one render per light with
the others hidden, the renders added: with one point, spot or sun light of radius 0, one sample
is that light's exact direct lighting.

Compared over the pixels facet's reference counts as interior (`facet render --mask`: inside
an object, not on its silhouette, no shadow ray grazing an occluder's edge). The materials are
Principled BSDFs (Blender's glTF exporter writes no other BSDF), distribution GGX: the floor,
the scaled cube and the mirrored cone Metallic 1, the sphere Metallic 0. facet imports them as
glTF's BRDF (the catalog's gltf_pbr: GGX, height-correlated Smith, the metal's Schlick Fresnel
of the base colour; docs/textures.md), which for a metal is Cycles 4.5's Principled BSDF itself
(its F82-tint Fresnel with a white tint is Schlick's, and its Smith G the height-correlated one),
and for a dielectric is not: Cycles weights the diffuse by 1 − the specular layer's directional
albedo, glTF by 1 − F per direction pair (Appendix B's fresnel_mix). The differences are the
material's; a wrong light unit is a factor.
The test therefore holds the lights and the materials apart:

  LIGHTS   per light (each alone on both sides), the least-squares brightness ratio
           facet / Cycles = Σ f·c / Σ c² over the interior pixels of the Metallic-1 objects:
           1 within RATIO_TOL (1 %). A unit error anywhere between Blender's watts, the
           exporter's candela and lux and facet's 683 lm/W import is a factor: π (a converter
           taking W/(4π) for facet's C instead of W/(4π²)), 4π (W for W/sr), 683 (lumens for
           watts). The script shows it: the same file imported with --lumens-per-watt 683/π
           (the first of those errors) must fail this check on every light.
  IMAGE    the whole image (all lights): on the Metallic-1 objects |Δ| ≤ METAL_TOL (1e-4) ·
           max(1, |Cycles|) on every channel of every interior pixel, and a relative RMSE
           (RMSE / mean) ≤ 1e-4: the same BRDF in float32 on both sides (measured: 6.6e-7
           worst). On the dielectric facet must be the brighter (glTF's diffuse weight
           1 − max(F) lacks the layering's 1 − E), by at most DIELECTRIC_TOL (15 %) on any pixel
           and in RMSE (measured: 4.1 % worst, 2.0 % RMSE, +0.66 % in sum).
  COVERAGE facet's objects and Cycles' alpha (film transparent) agree on all but 0.1 % of the
           pixels (the camera, the mirrored and scaled nodes, the Y-up conversion).

docs/gltf.md states the tolerances with the figures this script prints. Exits 1 when a
check fails.
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(REPO, "exporters", "blender", "tests"))

COVERAGE_TOL = 1e-3
RATIO_TOL = 0.01
METAL_TOL, METAL_RMSE = 1e-4, 1e-4
DIELECTRIC_TOL, DIELECTRIC_RMSE = 0.15, 0.15
WRONG_LUMENS_PER_WATT = 683.0 / 3.141592653589793     # a converter that divides watts by 4π, not 4π²
KINDS = {"POINT": "point", "SPOT": "spot", "SUN": "directional"}


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--facet", required=True)
    p.add_argument("--corpus", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--size", default="96x72")
    return p.parse_args()


def cycles_renders(folder, w, h):
    """Point-sampled Cycles of the open .blend, each light alone: ({light name: RGB rows from the
    top}, alpha rows from the top)."""
    import bpy
    import blender_scene
    scene = bpy.context.scene
    blender_scene.point_sampled_cycles(scene)
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = w, h, 100
    for obj in scene.objects:
        if obj.type == "MESH":
            obj.cycles.shadow_terminator_geometry_offset = 0.0
    lights = [o for o in scene.objects if o.type == "LIGHT"]
    images, alpha = {}, None
    for light in lights:
        for other in lights:
            other.hide_render = other is not light
        scene.render.filepath = os.path.join(folder, f"cycles_{light.name}.exr")
        bpy.ops.render.render(write_still=True)
        image = bpy.data.images.load(scene.render.filepath, check_existing=False)
        px = np.array(image.pixels[:], np.float64).reshape(h, w, 4)[::-1]
        bpy.data.images.remove(image)
        images[light.name] = px[..., :3]
        alpha = px[..., 3]          # film transparent: 1 where a surface is seen, 0 on the background
    for light in lights:
        light.hide_render = False
    return images, alpha


def facet_render(facet, scene, size, stem):
    out = subprocess.run([facet, "render", "--scene", scene, "-r", "reference", "--size", size, "-o", stem + ".pfm",
                          "--normals", stem + "_n.pfm", "--mask", stem + "_mask.pgm"],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if out.returncode:
        raise SystemExit(f"FAIL: facet render {scene}:\n{out.stdout[-2000:]}")
    import gltf_second_opinion as so
    return (so.read_pfm(stem + ".pfm"), np.rint(so.read_pfm(stem + "_n_objects.pfm")[..., 0]).astype(int),
            so.read_pgm(stem + "_mask.pgm"))


def facet_import(facet, glb, scene_json, *extra):
    out = subprocess.run([facet, "import-gltf", glb, "-o", scene_json, *extra], stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True)
    if out.returncode:
        raise SystemExit(f"FAIL: facet import-gltf refused Blender's export:\n{out.stdout}")
    return out.stdout.strip()


def principled_metallic(material):
    """The Metallic of the Principled BSDF feeding a material's output, or None."""
    tree = material.node_tree if material.use_nodes else None
    bsdf = next((n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"), None) if tree else None
    return float(bsdf.inputs["Metallic"].default_value) if bsdf else None


def light_ratios(opts, scene_json, names, cycles, select, label):
    """{light name: facet / Cycles} with each light alone (facet's scene cut to that light)."""
    import bpy
    data = json.load(open(scene_json))
    by_kind = {l["type"]: i for i, l in enumerate(data["lights"])}
    ratios = {}
    for name in names:
        blender = bpy.data.objects[name].data
        index = by_kind[KINDS[blender.type]]
        path = os.path.join(opts.work, f"{label.split()[0]}_{name}.json")
        with open(path, "w") as f:
            json.dump(dict(data, lights=[data["lights"][index]]), f)
        img, _, m = facet_render(opts.facet, path, opts.size, path[:-5])
        c = cycles[name]
        sel = m & select & (c.max(axis=2) > 1e-3)
        ratios[name] = float((img[sel] * c[sel]).sum() / (c[sel] ** 2).sum()) if sel.any() else float("nan")
        print(f"  {label}: light {name} ({blender.type}, {blender.energy:g} {'W/m²' if blender.type == 'SUN' else 'W'} "
              f"in Blender, facet colour {[round(x, 5) for x in data['lights'][index]['color']]}): facet / Cycles = "
              f"{ratios[name]:.5f} over {int(sel.sum())} lit interior pixels of the Metallic-1 objects")
    return ratios


def compare_images(data, metallic, full, cycles, objects, mask):
    """One line per object; the objects that fail their material's rule."""
    failures = []
    print("image, all lights, per object over interior pixels: worst |Δ|/max(1, |Cycles|), relative RMSE "
          "(RMSE / mean Cycles value), facet − Cycles in per cent of Cycles' sum:")
    rel_px = (np.abs(full - cycles) / np.maximum(1.0, np.abs(cycles))).max(axis=2)
    for i, o in enumerate(data["objects"]):
        sel = (objects == i + 1) & mask
        if not sel.any():
            continue
        material = o.get("material", "?")
        worst = float(rel_px[sel].max())
        rmse = float(np.sqrt(((full[sel] - cycles[sel]) ** 2).mean()) / cycles[sel].mean())
        signed = float((full[sel] - cycles[sel]).sum() / cycles[sel].sum())
        if metallic.get(material) == 1.0:
            ok = worst <= METAL_TOL and rmse <= METAL_RMSE
            rule = f"Metallic 1: worst ≤ {METAL_TOL}, RMSE ≤ {METAL_RMSE}"
        else:
            ok = worst <= DIELECTRIC_TOL and rmse <= DIELECTRIC_RMSE and signed > 0
            rule = f"Metallic 0: facet brighter, worst ≤ {DIELECTRIC_TOL}, RMSE ≤ {DIELECTRIC_RMSE}"
        print(f"  {'ok  ' if ok else 'FAIL'} {o['name']:15s} {material:15s} {int(sel.sum()):5d} px: worst {worst:.2e}, "
              f"relative RMSE {rmse:.2e}, facet − Cycles {100 * signed:+.2f} % ({rule})")
        if not ok:
            failures.append(f"image {o['name']}")
    return failures


def main():
    opts = parse_args()
    import bpy
    os.makedirs(opts.work, exist_ok=True)
    w, h = (int(x) for x in opts.size.split("x"))
    glb = os.path.join(opts.corpus, "corpus", "blender_lights.glb")
    scene_json = os.path.join(opts.work, "blender_lights.json")
    print(facet_import(opts.facet, glb, scene_json))
    data = json.load(open(scene_json))
    bpy.ops.wm.open_mainfile(filepath=os.path.join(opts.corpus, "blender", "lights.blend"))
    names = sorted(o.name for o in bpy.context.scene.objects if o.type == "LIGHT")
    kinds = sorted(KINDS[bpy.data.objects[n].data.type] for n in names)
    if sorted(l["type"] for l in data["lights"]) != kinds:     # one light of each type: matched by type
        print(f"FAIL: the imported lights {[l['type'] for l in data['lights']]} are not the .blend's {kinds}")
        return 1
    metallic = {m.name: principled_metallic(m) for m in bpy.data.materials}
    failures = []
    cycles, alpha = cycles_renders(opts.work, w, h)
    full, objects, mask = facet_render(opts.facet, scene_json, opts.size, os.path.join(opts.work, "facet_all"))
    mismatch = float(((objects > 0) != (alpha >= 0.5)).sum()) / (w * h)
    print(f"coverage: facet's objects vs Cycles' alpha differ on {100 * mismatch:.3f} % of {w * h} pixels "
          f"(tolerance {100 * COVERAGE_TOL:g} %)")
    if mismatch > COVERAGE_TOL:
        failures.append("coverage")

    metal_ids = [i + 1 for i, o in enumerate(data["objects"]) if metallic.get(o.get("material")) == 1.0]
    metal_px = np.isin(objects, metal_ids) & mask
    print(f"lights, each alone (tolerance 1 ± {RATIO_TOL}):")
    for name, ratio in light_ratios(opts, scene_json, names, cycles, metal_px, "import").items():
        if not abs(ratio - 1) <= RATIO_TOL:
            failures.append(f"light {name}")
    wrong = os.path.join(opts.work, "wrong_units.json")
    facet_import(opts.facet, glb, wrong, "--lumens-per-watt", repr(WRONG_LUMENS_PER_WATT))
    for name, ratio in light_ratios(opts, wrong, names, cycles, metal_px,
                                    f"wrong (--lumens-per-watt {WRONG_LUMENS_PER_WATT:.4g}, must fail)").items():
        if abs(ratio - 1) <= RATIO_TOL:
            failures.append(f"the check passes light {name} in wrong units")

    failures += compare_images(data, metallic, full, sum(cycles.values()), objects, mask)
    print("lights against Cycles: " + ("pass" if not failures else "FAIL: " + ", ".join(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
