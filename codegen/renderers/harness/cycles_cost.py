"""facet cost in Cycles: the compiled size of each OSL shader and its render time.

    python cycles_cost.py JOB.json

JOB.json:
    {"width": 128, "height": 128, "scene": {...},   # a facet scene, as for cycles_render.py
     "samples": 64, "repeats": 7, "time": true,
     "items": [{"name": "lambert", "osl": "/abs/lambert.osl"}, ...]}

For each item, compiled by Cycles' own Script-node compiler (cycles_render.compile_material):
  * "instructions": the ops of the compiled shader's main code section (the .oso's
    "code ___main___" up to "end"), the "functioncall" markers excluded: oslc
    inlines every function and marks each inlined body with one, which executes
    nothing of its own. Parameter-initialisation sections are not counted.
  * with "time": the render time per pixel and sample. Per round, each item in turn
    (the order reversed every other round): its shader is compiled, then rendered
    with 1 sample and with 1 + "samples" samples (the process's CPU time, Cycles set
    to two threads: see render_seconds and main), without persistent
    data (a persistent session ignores the changed sample count). The least time
    of each over the rounds, differenced, is what the extra samples cost: session
    start, scene sync, the OSL shader group's optimisation and JIT, and film
    read-back are in both and cancel.
    ns_per_pixel = (t_high - t_low) / (samples * width * height), background pixels included.
Writes JOB.json.result.json:
    {"blender": ..., "osl": ..., "items": [{"name", "ok", "error", "instructions",
      "seconds_low", "seconds_high", "ns_per_pixel"}]}
Exit 0 when every item compiled (and rendered), 1 otherwise.
"""
import json
import os
import sys
import tempfile
import time

import cycles_render as harness  # scene building, Script-node compiling, render settings


def count_ops(oso):
    """Ops of the ___main___ code section of .oso text, functioncall markers excluded."""
    count, inside = 0, False
    for line in oso.splitlines():
        if line.startswith("code "):
            inside = line.split()[1] == "___main___"
            continue
        if line.startswith("end"):
            inside = False
            continue
        if inside and line.startswith("\t"):
            op = line.split()[0]
            if op != "functioncall":
                count += 1
    return count


def script_bytecode(material):
    for node in material.node_tree.nodes:
        if node.type == "SCRIPT":
            return node.bytecode or ""
    return ""


def render_seconds(bpy, scene, samples):
    """The CPU time of a render, which other processes on the machine disturb less
    than its wall time."""
    scene.cycles.samples = samples
    t0 = time.process_time()
    bpy.ops.render.render(write_still=False)
    return time.process_time() - t0


def main(argv):
    job_path = argv[1]
    with open(job_path) as f:
        job = json.load(f)
    items = job["items"]
    import bpy
    import _cycles
    harness.enable_oslquery(bpy)
    work = tempfile.mkdtemp(prefix="facet-cost-")
    tempfile.tempdir = work  # the Script node's temporary .oso files go there
    with harness.CaptureOutput():
        scene, materials, _frame = harness.build_scene(bpy, job, os.path.join(work, "cost.exr"))
    material = materials[""]
    # Two threads, measured: with one, Blender's caller thread busy-waits beside
    # the render and doubles the CPU time; with two the process's CPU time is the
    # render's work (about one core busy at this size).
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    scene.render.use_persistent_data = False
    results = [{"name": i["name"], "ok": False, "error": "", "instructions": 0, "seconds_low": None,
                "seconds_high": None, "ns_per_pixel": 0.0} for i in items]

    for item, entry in zip(items, results):
        error = harness.compile_material(bpy, material, item["osl"])
        if error:
            entry["error"] = error
            continue
        entry["instructions"] = count_ops(script_bytecode(material))
        entry["ok"] = True

    samples = int(job.get("samples", 16))
    if job.get("time"):
        order = [k for k, e in enumerate(results) if e["ok"]]
        for round_ in range(int(job.get("repeats", 7))):
            for k in (order if round_ % 2 == 0 else reversed(order)):
                entry = results[k]
                try:
                    harness.compile_material(bpy, material, items[k]["osl"])
                    with harness.CaptureOutput():
                        low = render_seconds(bpy, scene, 1)
                        high = render_seconds(bpy, scene, 1 + samples)
                except RuntimeError as e:
                    entry.update(ok=False, error=str(e))
                    continue
                entry["seconds_low"] = low if entry["seconds_low"] is None else min(entry["seconds_low"], low)
                entry["seconds_high"] = high if entry["seconds_high"] is None else min(entry["seconds_high"], high)
            print(f"cycles_cost: round {round_ + 1} done", flush=True)
        pixels = int(job["width"]) * int(job["height"])
        for entry in results:
            if entry["ok"]:
                entry["ns_per_pixel"] = (entry["seconds_high"] - entry["seconds_low"]) / (samples * pixels) * 1e9

    result = {"blender": bpy.app.version_string, "osl": str(getattr(_cycles, "osl_version_string", "")).strip(),
              "items": results}
    harness.write_atomic(job_path + ".result.json", (json.dumps(result, indent=1) + "\n").encode())
    return 0 if all(e["ok"] for e in results) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
