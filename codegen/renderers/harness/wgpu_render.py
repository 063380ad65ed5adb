"""facet's wgpu renderer harness (renderers/wgpu.cpp writes and runs it with the .venv's Python).

    python wgpu_render.py JOB.json

JOB.json: {"jobs": [{"name", "width", "height", "layers": the visibility image's,
                     "images": the G-buffer's images (renderers/gbuffer.h, GBuffer::kImages),
                     "wgsl": the shading pass (the generated WGSL and templates/wgsl/gbuffer_shade.wgsl),
                     "uniforms": the FacetScene uniform buffer's bytes (templates/wgsl/lights.wgsl),
                     "lights": the lights' storage buffer's bytes, 64 a light (@group(2) @binding(0)),
                     "gbuffer": the G-buffer's images, float32 RGBA, one after another, each
                                width × height texels from the bottom row up (the G-buffer contract),
                                the last (the visibility) `layers` such images,
                     "textures": [{"binding", "width", "height", "file"}]: the material's images,
                                float32 RGBA from the top row down, at @group(0) @binding(binding),
                     "output": where the image goes: OUTPUT.pfm (RGB) and OUTPUT.alpha.pfm}]}

or {"sweeps": [{"name", "wgsl": the robustness sweep (templates/wgsl/sweep.wgsl), "grid"}]}: each
drawn on grid × grid pixels and its raw values counted (NaN, Inf and negative channels).

Each job is drawn into an rgba32float texture by WebGPU (wgpu-native; Mesa's lavapipe here),
one full-screen triangle running the WGSL's facet_gbuffer_shade, read back and written as
PFM. JOB.json.result.json then says, per job, ok, seconds and, when not ok, naga's or
wgpu's own words; and which adapter drew.
"""
import json
import os
import sys
import time

import numpy as np
import wgpu


def write_atomic(path, data):
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)


def write_pfm(path, rows_from_top, channels):
    """PFM stores rows from the bottom up, little-endian (a negative scale)."""
    h, w = rows_from_top.shape[:2]
    header = f"{'PF' if channels == 3 else 'Pf'}\n{w} {h}\n-1.0\n".encode()
    body = np.ascontiguousarray(rows_from_top[::-1], dtype="<f4").tobytes()
    write_atomic(path, header + body)


def float_texture(device, width, height, texels, layers=1):
    """An rgba32float texture holding `texels` (layers × height × width × 4 float32, row 0 first)."""
    tex = device.create_texture(size=(width, height, layers), format=wgpu.TextureFormat.rgba32float,
                                usage=wgpu.TextureUsage.TEXTURE_BINDING | wgpu.TextureUsage.COPY_DST)
    device.queue.write_texture({"texture": tex}, np.ascontiguousarray(texels, dtype="<f4"),
                               {"bytes_per_row": width * 16, "rows_per_image": height}, (width, height, layers))
    return tex


def texture_entry(binding, array=False):
    dimension = wgpu.TextureViewDimension.d2_array if array else wgpu.TextureViewDimension.d2
    return {"binding": binding, "visibility": wgpu.ShaderStage.FRAGMENT,
            "texture": {"sample_type": wgpu.TextureSampleType.unfilterable_float, "view_dimension": dimension}}


def read_floats(path, count, what):
    data = np.fromfile(path, dtype="<f4")
    if data.size != count:
        raise ValueError(f"{path}: {what} holds {data.size} floats, not {count}")
    return data


def bind_groups(device, job):
    """Group 0: the scene's uniform buffer and the material's images; group 1: the G-buffer;
    group 2: the lights."""
    w, h = job["width"], job["height"]
    with open(job["uniforms"], "rb") as f:
        uniform_bytes = f.read()
    buf = device.create_buffer_with_data(data=uniform_bytes, usage=wgpu.BufferUsage.UNIFORM)
    entries0 = [{"binding": 0, "visibility": wgpu.ShaderStage.FRAGMENT, "buffer": {"type": wgpu.BufferBindingType.uniform}}]
    binds0 = [{"binding": 0, "resource": {"buffer": buf, "offset": 0, "size": len(uniform_bytes)}}]
    for t in job.get("textures", []):
        texels = read_floats(t["file"], t["width"] * t["height"] * 4, "a texture")
        tex = float_texture(device, t["width"], t["height"], texels.reshape(t["height"], t["width"], 4))
        entries0.append(texture_entry(t["binding"]))
        binds0.append({"binding": t["binding"], "resource": tex.create_view()})
    layers, count = job["layers"], job["images"]  # the last image, the visibility, a 2D array of `layers`
    images = count - 1 + layers
    gbuffer = read_floats(job["gbuffer"], images * w * h * 4, "the G-buffer").reshape(images, h, w, 4)
    entries1, binds1 = [], []
    for k in range(count):
        array = k == count - 1
        tex = float_texture(device, w, h, gbuffer[k:] if array else gbuffer[k], layers if array else 1)
        entries1.append(texture_entry(k, array))
        view = tex.create_view(dimension=wgpu.TextureViewDimension.d2_array) if array else tex.create_view()
        binds1.append({"binding": k, "resource": view})
    with open(job["lights"], "rb") as f:
        light_bytes = f.read()
    lights = device.create_buffer_with_data(data=light_bytes, usage=wgpu.BufferUsage.STORAGE)
    entries2 = [{"binding": 0, "visibility": wgpu.ShaderStage.FRAGMENT,
                 "buffer": {"type": wgpu.BufferBindingType.read_only_storage}}]
    binds2 = [{"binding": 0, "resource": {"buffer": lights, "offset": 0, "size": len(light_bytes)}}]
    layouts = [device.create_bind_group_layout(entries=e) for e in (entries0, entries1, entries2)]
    groups = [device.create_bind_group(layout=layouts[i], entries=b) for i, b in enumerate((binds0, binds1, binds2))]
    return layouts, groups


def draw(device, job):
    """The job's image, rows from the top, height × width × 4 float32."""
    layouts, groups = bind_groups(device, job)
    return full_screen(device, job["wgsl"], "facet_gbuffer_shade", layouts, groups, job["width"], job["height"])


def sweep(device, item):
    """The sweep's counts: every channel of grid × grid direction sets."""
    grid = item["grid"]
    buf = device.create_buffer_with_data(data=np.array([grid, grid, 0, 0], dtype="<f4").tobytes(),
                                         usage=wgpu.BufferUsage.UNIFORM)
    layout = device.create_bind_group_layout(entries=[{
        "binding": 0, "visibility": wgpu.ShaderStage.FRAGMENT, "buffer": {"type": wgpu.BufferBindingType.uniform}}])
    group = device.create_bind_group(layout=layout, entries=[{"binding": 0, "resource": {"buffer": buf}}])
    rgb = full_screen(device, item["wgsl"], "facet_sweep", [layout], [group], grid, grid)[:, :, :3]
    nan, inf = np.isnan(rgb), np.isinf(rgb)
    return {"ok": True, "samples": grid * grid, "nan": int(nan.sum()), "inf": int(inf.sum()),
            "negative": int((~nan & ~inf & (rgb < 0)).sum())}


def full_screen(device, wgsl, entry_point, layouts, groups, w, h):
    """`entry_point` of the WGSL file on w × h pixels (facet_vertex's one triangle), read back."""
    with open(wgsl, encoding="utf-8") as f:
        module = device.create_shader_module(code=f.read())
    pipeline = device.create_render_pipeline(
        layout=device.create_pipeline_layout(bind_group_layouts=layouts),
        vertex={"module": module, "entry_point": "facet_vertex"},
        primitive={"topology": wgpu.PrimitiveTopology.triangle_list},
        fragment={"module": module, "entry_point": entry_point,
                  "targets": [{"format": wgpu.TextureFormat.rgba32float}]})
    target = device.create_texture(size=(w, h, 1), format=wgpu.TextureFormat.rgba32float,
                                   usage=wgpu.TextureUsage.RENDER_ATTACHMENT | wgpu.TextureUsage.COPY_SRC)
    encoder = device.create_command_encoder()
    rp = encoder.begin_render_pass(color_attachments=[{
        "view": target.create_view(), "load_op": wgpu.LoadOp.clear, "store_op": wgpu.StoreOp.store,
        "clear_value": (0, 0, 0, 0)}])
    rp.set_pipeline(pipeline)
    for i, g in enumerate(groups):
        rp.set_bind_group(i, g)
    rp.draw(3)
    rp.end()
    device.queue.submit([encoder.finish()])
    data = device.queue.read_texture({"texture": target}, {"bytes_per_row": w * 16, "rows_per_image": h}, (w, h, 1))
    return np.frombuffer(data, dtype="<f4").reshape(h, w, 4)


def main():
    job_file = sys.argv[1]
    with open(job_file, encoding="utf-8") as f:
        batch = json.load(f)
    adapter = wgpu.gpu.request_adapter_sync()
    if adapter is None:
        write_atomic(job_file + ".result.json", json.dumps({"error": "wgpu found no adapter"}).encode())
        return 1
    device = adapter.request_device_sync()
    info = adapter.info
    about = {"adapter": f"{info.get('device', '?')} ({info.get('backend_type', '?')})", "wgpu": wgpu.__version__}
    if "sweeps" in batch:
        counts = []
        for item in batch["sweeps"]:
            try:
                counts.append(sweep(device, item))
            except Exception as e:  # naga's or wgpu's words, for this material alone
                counts.append({"ok": False, "error": f"{type(e).__name__}: {e}".strip()})
        write_atomic(job_file + ".result.json", json.dumps({**about, "sweeps": counts}).encode())
        return 0
    results = []
    for job in batch["jobs"]:
        start = time.perf_counter()
        try:
            px = draw(device, job)
            write_pfm(job["output"] + ".pfm", px[:, :, :3], 3)
            write_pfm(job["output"] + ".alpha.pfm", px[:, :, 3], 1)
            results.append({"ok": True, "seconds": time.perf_counter() - start})
        except Exception as e:  # naga's or wgpu's words, for this job alone
            results.append({"ok": False, "error": f"{type(e).__name__}: {e}".strip()})
    write_atomic(job_file + ".result.json", json.dumps({**about, "results": results}).encode())
    return 0


if __name__ == "__main__":
    sys.exit(main())
