"""A second opinion facet did not write: each glTF file read by `facet import-gltf` and by
Blender's own importer followed by the add-on's Export Scene must render the same.

    python gltf_second_opinion.py --facet FACET --corpus FOLDER --work DIR [--size 96x72]
        [--files a.gltf,b.glb] [--variant VARIANT=ORIGINAL:CHECK ...] [--lit FILE,...]

(a Python with pip bpy 4.5; FOLDER is what gltf_corpus.py wrote: FOLDER/corpus/*.gltf|glb,
FOLDER/variants/*.gltf.)

For each file:

  A  `facet import-gltf FILE -o A/scene.json`: facet's own reading;
  B  `bpy.ops.import_scene.gltf(filepath=FILE)` (glTF-Blender-IO 4.5, default options: lighting
     mode "Standard", shading from the file's normals) into an empty scene without a World
     (a glTF file has no environment), the render size set to --size, then the add-on's
     Export Scene (`bpy.ops.facet.export_scene`, blender/scene_data.py `full_scene`): the
     file as Blender reads it and the add-on maps it, through code facet's import shares
     nothing with.

Both scenes are rendered by facet's reference (`facet render --scene S -r reference -o S.pfm
--normals N.pfm --mask M.pgm`, one sample at each pixel centre) and compared:

  coverage  the objects each pixel sees: A's objects are matched to B's by majority (B may hold
            several glTF primitives of one material as one object); a pixel differs where B sees
            another object than A's match, or one sees an object and the other none. At most
            COVERAGE_TOL of the pixels may differ (validate's rule: 0.1 %).
  normals   the angle between A's and B's unit normals (before normal maps) at every pixel both
            see the same object and where A's normals vary smoothly (no neighbour on another
            object, none turned by more than CREASE_DEG: a crease or silhouette is a matter of
            which side a pixel centre falls). At most NORMAL_TOL_DEG anywhere.
  image     |A − B| ≤ IMAGE_TOL · max(1, |A|) on every channel of every pixel that both
            reference renders count as interior (their --mask: inside an object, not on a
            silhouette, no shadow ray grazing an occluder's edge) and that sees the same object.

The tolerances, and why they are what they are (measured on the corpus, docs/gltf.md):

  NORMAL_TOL_DEG 0.05°: Blender stores an imported mesh's normals as custom split normals, two
      16-bit integers in each corner's own frame (quantisation ~π/32767 ≈ 0.0055°), and
      transforms them by its float32 world matrix; facet reads the file's float32 normals and
      transforms them in double. The corpus's worst is printed per file. A wrong transform
      (the adjugate bug) turns normals by tens of degrees.
  IMAGE_TOL 2e-3: validate's tolerance. The readers agree on the materials exactly (the same
      metallic–roughness mapping, the same textures and texels, the same light units), so what
      differs is the normals' quantisation above (4e-4 at most on the example scene) and
      float32 geometry.
  COVERAGE_TOL 0.1 %: validate's; silhouette pixels whose centre lies within float32 rounding
      of an edge.

--variant VARIANT=ORIGINAL:CHECK[+CHECK...] reads VARIANT with facet and ORIGINAL with Blender
(a deliberately wrong file standing for a wrong facet import) and passes only if every CHECK
(coverage, normals, image or lit) fails: the comparison's own teeth. --lit FILE,... requires
that facet's reading of those files shows light on at least LIT_FRACTION of the pixels where
objects are seen (a file that imported inside out renders black there).

Prints one line per file (worst figures and what differs) and a summary; exits 1 on any
failure, 0 otherwise.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

import numpy as np

# The add-on's warnings every file of the corpus gets, which say nothing about one file: the
# importer's materials have no facet settings (they are converted, as Export Scene does), its
# suns have Blender's default angle of 0.526° and a glTF spot's inner cone is Blender's blend
# (facet's lights are parallel beams and hard cones, as facet import-gltf reads the file too).
COMMON_WARNINGS = ("has no facet settings: exported as converted", "sun angle > 0", "spot blend")

COVERAGE_TOL = 1e-3
NORMAL_TOL_DEG = 0.05
CREASE_DEG = 20.0
IMAGE_TOL = 2e-3
LIT_FRACTION = 0.9
LIT_LEVEL = 1e-3            # a pixel counts as lit when its brightest channel exceeds this

# Where Blender's reading is known to differ from the file, and by how much it may. Blender's
# importer keeps an imported mesh's normals as custom split normals, stored relative to each
# corner's faces (io_scene_gltf2/blender/imp/mesh.py: normals_split_custom_set_from_vertices):
# when an armature or shape keys move the faces, Blender's normals turn with them. glTF instead
# skins the normals by the joints' matrices and adds the morph targets' NORMAL deltas (glTF 2.0
# §3.7.3.3, §3.8.3), which facet does; Blender's shape keys hold no normals at all. So on a
# deformed smooth mesh the two readings differ where the deformation bends the surface: the
# skinned tube's blend zone and the morphed sphere's bulge. Positions are not affected: coverage
# keeps its tolerance there. The allowances are the measured worst (skin 7.88°, 0.105; morph
# 1.94°, 0.0153; docs/gltf.md) with about a quarter to spare; a flat-shaded deformed mesh
# (sparse.gltf's morph target) needs none, and meets the common tolerances.
KNOWN = {
    "skin.gltf": {"normals_deg": 10.0, "image": 0.15,
                  "why": "Blender's normals follow the skinned faces; glTF skins them by the joint matrices"},
    "morph.gltf": {"normals_deg": 2.5, "image": 0.025,
                   "why": "Blender's shape keys carry no normals (the targets' NORMAL deltas are dropped); its "
                          "normals follow the morphed faces"},
}

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
ADDON_ROOT = os.path.join(REPO, "exporters", "blender")
ADDON = "facet_blender"


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--facet", required=True)
    p.add_argument("--corpus", required=True, help="the folder gltf_corpus.py wrote")
    p.add_argument("--work", required=True)
    p.add_argument("--size", default="96x72")
    p.add_argument("--files", default="", help="comma-separated corpus files (default: all of corpus.json)")
    p.add_argument("--no-corpus", action="store_true", help="compare only the --variant pairs")
    p.add_argument("--variant", action="append", default=[],
                   help="VARIANT=ORIGINAL:CHECK[+CHECK] (must fail every CHECK)")
    p.add_argument("--lit", default="", help="comma-separated files whose facet reading must be lit")
    return p.parse_args()


# ----------------------------------------------------------------------------- images

def read_pfm(path):
    """A PFM as an array [row from the top][column][channel]."""
    with open(path, "rb") as f:
        data = f.read()
    parts, pos = [], 0
    while len(parts) < 3:
        end = data.index(b"\n", pos)
        parts.append(data[pos:end].decode())
        pos = end + 1
    w, h = map(int, parts[1].split())
    channels = 3 if parts[0] == "PF" else 1
    dtype = "<f4" if float(parts[2]) < 0 else ">f4"
    img = np.frombuffer(data[pos:pos + 4 * w * h * channels], dtype).reshape(h, w, channels)
    return img[::-1].astype(np.float64)


def read_pgm(path):
    with open(path, "rb") as f:
        data = f.read()
    parts, pos = [], 0
    while len(parts) < 3:
        end = data.index(b"\n", pos)
        parts.append(data[pos:end].decode())
        pos = end + 1
    w, h = map(int, parts[1].split())
    return np.frombuffer(data[pos:pos + w * h], np.uint8).reshape(h, w) > 0


class Render:
    """facet's reference of one scene: image, normals, object index + 1 (0: none), interior mask."""

    def __init__(self, facet, scene, size, stem):
        out = subprocess.run([facet, "render", "--scene", scene, "-r", "reference", "--size", size,
                              "-o", stem + ".pfm", "--normals", stem + "_n.pfm", "--mask", stem + "_mask.pgm"],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if out.returncode != 0:
            raise Failure(f"facet render of {scene} failed:\n{out.stdout[-2000:]}")
        self.image = read_pfm(stem + ".pfm")
        self.normals = read_pfm(stem + "_n.pfm")
        self.objects = np.rint(read_pfm(stem + "_n_objects.pfm")[..., 0]).astype(int)
        self.mask = read_pgm(stem + "_mask.pgm")


class Failure(Exception):
    pass


# ----------------------------------------------------------------------------- the comparison

def match_objects(a, b):
    """{A object: B object} by majority over the pixels A's object covers (0 ↔ 0)."""
    match = {0: 0}
    for obj in np.unique(a):
        if obj == 0:
            continue
        seen, counts = np.unique(b[a == obj], return_counts=True)
        match[int(obj)] = int(seen[np.argmax(counts)])
    return match


def compare(a, b, normal_tol=NORMAL_TOL_DEG, image_tol=IMAGE_TOL):
    """The figures of one file: coverage, normals, image; each with its pass/fail."""
    h, w = a.objects.shape
    match = match_objects(a.objects, b.objects)
    back = match_objects(b.objects, a.objects)
    mapped = np.vectorize(lambda o: match.get(int(o), -1))(a.objects)
    mapped_back = np.vectorize(lambda o: back.get(int(o), -1))(b.objects)
    differ = (mapped != b.objects) | (mapped_back != a.objects)
    coverage = float(differ.sum()) / (w * h)
    same = (a.objects > 0) & ~differ

    # Normals where A's surface is smooth around the pixel.
    smooth = same.copy()
    cos_crease = np.cos(np.radians(CREASE_DEG))
    pad_o = np.pad(a.objects, 1, constant_values=-1)
    pad_n = np.pad(a.normals, ((1, 1), (1, 1), (0, 0)))
    for dj in (-1, 0, 1):
        for di in (-1, 0, 1):
            o = pad_o[1 + dj:1 + dj + h, 1 + di:1 + di + w]
            n = pad_n[1 + dj:1 + dj + h, 1 + di:1 + di + w]
            smooth &= (o == a.objects) & (np.sum(n * a.normals, axis=2) >= cos_crease)
    dots = np.clip(np.sum(a.normals * b.normals, axis=2), -1.0, 1.0)
    angles = np.degrees(np.arccos(dots))
    normal_worst = float(angles[smooth].max()) if smooth.any() else float("nan")
    normal_bad = int((angles[smooth] > normal_tol).sum())

    interior = same & a.mask & b.mask
    rel = np.abs(a.image - b.image) / np.maximum(1.0, np.abs(a.image))
    rel_px = rel.max(axis=2)
    image_worst = float(rel_px[interior].max()) if interior.any() else float("nan")
    image_bad = int((rel_px[interior] > image_tol).sum())
    where = None
    if interior.any():
        j, i = np.unravel_index(np.argmax(np.where(interior, rel_px, -1.0)), rel_px.shape)
        where = (int(i), int(j), a.image[j, i].round(5).tolist(), b.image[j, i].round(5).tolist())
    lit = (a.image.max(axis=2) > LIT_LEVEL) & (a.objects > 0)
    return {
        "pixels": w * h, "objects_a": len(match) - 1, "objects_b": len(back) - 1,
        "coverage": coverage, "coverage_ok": coverage <= COVERAGE_TOL,
        "normal_pixels": int(smooth.sum()), "normal_worst_deg": normal_worst, "normal_bad": normal_bad,
        "normals_ok": smooth.sum() > 0 and normal_bad == 0,
        "image_pixels": int(interior.sum()), "image_worst": image_worst, "image_bad": image_bad,
        "image_where": where, "image_ok": interior.sum() > 0 and image_bad == 0,
        "lit_fraction": float(lit.sum()) / max(1, int((a.objects > 0).sum())),
    }


# ----------------------------------------------------------------------------- the two readers

def facet_reading(facet, gltf, folder):
    os.makedirs(folder, exist_ok=True)
    scene = os.path.join(folder, "scene.json")
    out = subprocess.run([facet, "import-gltf", gltf, "-o", scene], stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True)
    if out.returncode != 0:
        raise Failure(f"facet import-gltf {gltf} failed:\n{out.stdout[-2000:]}")
    return scene


def reset_blender():
    import bpy
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras,
                       bpy.data.images, bpy.data.worlds, bpy.data.node_groups, bpy.data.armatures,
                       bpy.data.actions, bpy.data.shape_keys if hasattr(bpy.data, "shape_keys") else []):
        for block in list(collection):
            try:
                collection.remove(block)
            except (TypeError, RuntimeError):
                pass
    for coll in list(bpy.data.collections):
        bpy.data.collections.remove(coll)
    scene = bpy.context.scene
    scene.camera = None
    scene.world = None          # a glTF file has no environment: the exported ambient is 0, as facet's
    return scene


def blender_reading(gltf, folder, size):
    """Blender's importer, then the add-on's Export Scene: the exported scene's path and the
    operator's warnings."""
    import bpy
    from facet_blender.blender import operators
    scene = reset_blender()
    w, h = (int(x) for x in size.split("x"))
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = w, h, 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
    result = bpy.ops.import_scene.gltf(filepath=gltf)
    if result != {"FINISHED"}:
        raise Failure(f"Blender's glTF importer returned {result} for {gltf}")
    if scene.camera is None:
        cameras = sorted((o for o in scene.objects if o.type == "CAMERA"), key=lambda o: o.name)
        if not cameras:
            raise Failure(f"Blender's glTF importer made no camera from {gltf}")
        scene.camera = cameras[0]
    bpy.context.view_layer.update()
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "scene.json")
    operators.LAST_REPORTS.clear()
    try:
        result = bpy.ops.facet.export_scene(filepath=path)
    except RuntimeError as e:
        raise Failure(f"the add-on's Export Scene failed on Blender's reading of {gltf}: {e}")
    if result != {"FINISHED"}:
        raise Failure(f"the add-on's Export Scene returned {result} for {gltf}")
    return path, [m for level, m in operators.LAST_REPORTS if level == "WARNING"]


def enable_addon(facet):
    import bpy
    import addon_utils
    if ADDON_ROOT not in sys.path:
        sys.path.insert(0, ADDON_ROOT)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if addon_utils.enable(ADDON, default_set=True, handle_error=None) is None:
        raise Failure("the facet add-on did not enable")
    bpy.context.preferences.addons[ADDON].preferences.facet_path = facet
    from facet_blender.blender import state
    if state.STATE.catalog is None:
        raise Failure(f"the add-on could not load facet's catalog: {state.STATE.error}")


# ----------------------------------------------------------------------------- main

def fmt_figures(f):
    return (f"objects {f['objects_a']}/{f['objects_b']}, coverage {100 * f['coverage']:.3f} %, "
            f"normals worst {f['normal_worst_deg']:.4f}° over {f['normal_pixels']} px ({f['normal_bad']} over), "
            f"image worst {f['image_worst']:.2e} over {f['image_pixels']} px ({f['image_bad']} over), "
            f"lit {100 * f['lit_fraction']:.1f} %")


def run_one(opts, facet_file, blender_file, label, lit, known=None):
    work = os.path.join(opts.work, label)
    shutil.rmtree(work, ignore_errors=True)
    t0 = time.perf_counter()
    a_scene = facet_reading(opts.facet, facet_file, os.path.join(work, "facet"))
    b_scene, warnings = blender_reading(blender_file, os.path.join(work, "blender"), opts.size)
    a = Render(opts.facet, a_scene, opts.size, os.path.join(work, "facet", "ref"))
    b = Render(opts.facet, b_scene, opts.size, os.path.join(work, "blender", "ref"))
    f = compare(a, b, *((known["normals_deg"], known["image"]) if known else ()))
    f["seconds"] = time.perf_counter() - t0
    f["warnings"] = warnings
    f["lit_ok"] = (not lit) or f["lit_fraction"] >= LIT_FRACTION
    return f


def main():
    opts = parse_args()
    index = json.load(open(os.path.join(opts.corpus, "corpus.json")))
    files = [] if opts.no_corpus else [f for f in opts.files.split(",") if f] or [e["file"] for e in index["corpus"]]
    folder_of = {f: "corpus" for f in files}
    lit = set(f for f in opts.lit.split(",") if f)
    unknown = lit - set(files)
    if unknown:
        print(f"FAIL: --lit names files not compared: {sorted(unknown)}")
        return 1
    enable_addon(opts.facet)
    failures, table = [], {}
    print(f"second opinion at {opts.size}: tolerances coverage {100 * COVERAGE_TOL:g} %, normals {NORMAL_TOL_DEG}°, "
          f"image {IMAGE_TOL} · max(1, |A|); A = facet import-gltf, B = Blender's importer + the add-on's Export Scene")
    for name in files:
        path = os.path.join(opts.corpus, folder_of[name], name)
        try:
            f = run_one(opts, path, path, os.path.splitext(name)[0], name in lit, KNOWN.get(name))
        except Failure as e:
            print(f"FAIL {name}: {e}")
            failures.append(name)
            continue
        table[name] = f
        ok = f["coverage_ok"] and f["normals_ok"] and f["image_ok"] and f["lit_ok"]
        what = [k for k in ("coverage", "normals", "image", "lit") if not f[k + "_ok"]]
        print(f"{'ok  ' if ok else 'FAIL'} {name}: {fmt_figures(f)}; {f['seconds']:.1f} s"
              + (f"; differs in {', '.join(what)} (worst image pixel (x, y from top, A, B) {f['image_where']})"
                 if what else ""))
        if name in KNOWN:
            k = KNOWN[name]
            print(f"       known difference, allowed normals {k['normals_deg']}°, image {k['image']}: {k['why']}")
        for w in f["warnings"]:
            if not any(common in w for common in COMMON_WARNINGS):
                print(f"       add-on: {w[:300]}")
        if not ok:
            failures.append(name)
    for spec in opts.variant:
        variant, rest = spec.split("=", 1)
        original, check = rest.rsplit(":", 1)
        try:
            f = run_one(opts, os.path.join(opts.corpus, "variants", variant), os.path.join(opts.corpus, "corpus", original),
                        "variant_" + os.path.splitext(variant)[0], True)
        except Failure as e:
            print(f"FAIL variant {variant}: {e}")
            failures.append(variant)
            continue
        checks = check.split("+")
        missed = [c for c in checks if f[c + "_ok"]]
        caught = not missed
        print(f"{'ok  ' if caught else 'FAIL'} variant {variant} (facet) vs {original} (Blender): {fmt_figures(f)}; "
              + (f"{' and '.join(checks)} fail, as they must" if caught
                 else f"{' and '.join(missed)} pass: the comparison cannot see this error"))
        if not caught:
            failures.append(variant)
        table[variant] = f
    with open(os.path.join(opts.work, "second_opinion.json"), "w") as out:
        json.dump(table, out, indent=1, default=str)
    corpus = [table[n] for n in files if n in table and n not in KNOWN]
    worst = {k: max((f[k] for f in corpus if f.get(k) == f.get(k)), default=float("nan"))
             for k in ("coverage", "normal_worst_deg", "image_worst")}
    print(f"second opinion: {len(files) + len(opts.variant) - len(failures)} of {len(files) + len(opts.variant)} "
          f"pass; worst over the files without a known difference: coverage {100 * worst['coverage']:.3f} %, "
          f"normals {worst['normal_worst_deg']:.4f}°, image {worst['image_worst']:.2e}" + (f"; failed: {', '.join(failures)}" if failures else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
