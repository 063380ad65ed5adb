"""facet's robustness sweep in Cycles: render each item's sweep shader on a unit square.

    python cycles_sweep.py JOB.json

JOB.json: {"size": N, "items": [{"name": ..., "osl": "/abs/x_sweep.osl"}, ...]}. The
square z = 0, x, y in [0, 1] is seen straight down by an orthographic camera, one
sample at each of N x N pixel centres; each shader (templates/osl/sweep.osl) writes
the number of NaN, infinite and negative channels of its direction set into R, G, B.
Writes JOB.json.result.json: {"items": [{"name", "ok", "error", "samples", "nan",
"inf", "negative"}]}. Exit 0 when every item ran, 1 otherwise.
"""
import json
import os
import sys
import tempfile

import cycles_render as harness  # the validation harness: Script-node compiling, render settings


def main(argv):
    job_path = argv[1]
    with open(job_path) as f:
        job = json.load(f)
    size, items = int(job["size"]), job["items"]
    import bpy
    harness.enable_oslquery(bpy)
    work = tempfile.mkdtemp(prefix="facet-sweep-")
    tempfile.tempdir = work
    exr = os.path.join(work, "sweep.exr")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    harness.configure_render(bpy, scene, size, size, exr)
    cam_data = bpy.data.cameras.new("sweep_camera")
    cam_data.type = "ORTHO"
    cam_data.ortho_scale = 1.0
    cam = bpy.data.objects.new("sweep_camera", cam_data)
    cam.location = (0.5, 0.5, 1.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    mesh = bpy.data.meshes.new("sweep_square")
    mesh.from_pydata([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [], [(0, 1, 2, 3)])
    material = harness.new_material(bpy, "facet_sweep")
    mesh.materials.append(material)
    scene.collection.objects.link(bpy.data.objects.new("sweep_square", mesh))
    results = []
    for item in items:
        entry = {"name": item["name"], "ok": False, "error": "", "samples": 0, "nan": 0, "inf": 0, "negative": 0}
        try:
            error = harness.compile_material(bpy, material, item["osl"])
            if error:
                entry["error"] = error
            else:
                rgba = harness.render_pixels(bpy, scene, size, size)
                counts = rgba[:, :, :3].reshape(-1, 3)
                entry.update(ok=True, samples=size * size, nan=int(round(float(counts[:, 0].sum()))),
                             inf=int(round(float(counts[:, 1].sum()))), negative=int(round(float(counts[:, 2].sum()))))
        except Exception as e:  # noqa: BLE001 - one bad item must not stop the others
            entry["error"] = f"{type(e).__name__}: {e}"
        results.append(entry)
        print(f"{item['name']}: {'ok' if entry['ok'] else 'FAILED ' + entry['error']}", flush=True)
    with open(job_path + ".result.json", "w") as f:
        json.dump({"items": results}, f)
    return 0 if all(r["ok"] for r in results) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
