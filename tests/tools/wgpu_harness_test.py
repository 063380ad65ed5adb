"""The wgpu renderer's harness (codegen/renderers/harness/wgpu_render.py) on a hand-made
G-buffer, without facet's ray caster: a unit sphere seen along −z (orthographic), a Lambert
material lit by one directional light along −z, the bottom rows in shadow (light 0's bit of
the G-buffer's visibility image 0), one corner "another pass's object" (drawn black) and
background elsewhere. The light comes from the standalone WGSL's uniform buffer (the renderer's
own passes read a storage buffer of lights, which the harness binds too: validate.wgpu.* draw it).
The expected image is k_d · n_z where lit, in facet's order (top row first).

    wgpu_harness_test.py FACET SOURCE_DIR OUTDIR [--wrong]

(the shading pass: templates/wgsl/gbuffer_shade.wgsl; the harness: codegen/renderers/harness/)

--wrong feeds a deliberately wrong G-buffer (rows top first, as a y-down framebuffer would
leave them): the comparison must then fail (exit 1), which the ctest asks of it.
"""
import json
import os
import struct
import subprocess
import sys

import numpy as np

W, H = 48, 32
COLOR = (0.6, 0.3, 0.2)


def gbuffer(wrong):
    """Seven images (the sixth the vertex colour, white; the seventh the visibility, one layer), rows
    from the bottom up (the contract), and the expected RGBA, rows from the top."""
    g = np.zeros((7, H, W, 4), dtype=np.float32)
    g[5] = 1.0
    expected = np.zeros((H, W, 4), dtype=np.float32)
    for row in range(H):  # row 0: the bottom
        for x in range(W):
            X = (x + 0.5) / W * 3.0 - 1.5
            Y = (row + 0.5) / H * 2.0 - 1.0
            top_row = H - 1 - row
            if x < 4 and row >= H - 4:  # top-left corner: another pass's object
                g[0, row, x] = (X, Y, 0.0, 0.0)
                expected[top_row, x] = (0, 0, 0, 1)
                continue
            r2 = X * X + Y * Y
            if r2 >= 1.0:
                g[0, row, x] = (0, 0, 0, -1)
                continue
            n = np.array([X, Y, np.sqrt(1.0 - r2)], dtype=np.float32)
            lit = 1.0 if row >= H // 4 else 0.0  # the bottom quarter in shadow
            g[0, row, x] = (*n, 1.0)
            g[1, row, x] = (*n, 0.0)
            g[2, row, x] = (0.0, 0.0, 1.0, 0.0)
            g[3, row, x] = (1.0, 0.0, 0.0, 1.0)
            # Light 0's bit is bit 0 of channel 0; the other bits (lights the scene lacks) all set.
            g[6, row, x] = (float((1 << 24) - 2) + lit, float((1 << 24) - 1), float((1 << 24) - 1), float((1 << 24) - 1))
            expected[top_row, x] = (*(c * n[2] * lit for c in COLOR), 1.0)
    if wrong:
        g = g[:, ::-1].copy()
    return g, expected


def uniforms():
    """templates/wgsl/lights.wgsl's FacetScene: camera, ambient, count, one directional light along −z."""
    b = struct.pack("<4f4fi12x", 0, 0, 5, 0, 0, 0, 0, 0, 1)
    b += struct.pack("<16f", 0, 0, -1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0)
    return b + bytes(560 - len(b))


def read_pfm(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, size, _scale, body = data.split(b"\n", 3)
    w, h = map(int, size.split())
    ch = 3 if magic == b"PF" else 1
    return np.frombuffer(body, dtype="<f4").reshape(h, w, ch)[::-1]


def main():
    facet, source, out = sys.argv[1:4]
    harness = os.path.join(source, "codegen", "renderers", "harness")
    wrong = "--wrong" in sys.argv
    os.makedirs(out, exist_ok=True)
    material = os.path.join(out, "lambert.json")
    with open(material, "w") as f:
        json.dump({"name": "lambert", "diffuse": {"model": "lambert", "color": list(COLOR)}}, f)
    code = subprocess.run([facet, "generate", material, "--target", "wgsl"], capture_output=True, text=True,
                          check=True).stdout
    library = code[:code.index("// ---- Standalone entry point")]
    with open(os.path.join(source, "templates", "wgsl", "gbuffer_shade.wgsl"), encoding="utf-8") as f:
        shading = f.read().replace("{{sample}}", "").replace("{{bits}}", "24").replace("{{layer_lights}}", "96")
    with open(os.path.join(out, "pass.wgsl"), "w", encoding="utf-8") as f:
        f.write(library + shading)
    g, expected = gbuffer(wrong)
    g.astype("<f4").tofile(os.path.join(out, "gbuffer.raw"))
    with open(os.path.join(out, "uniforms.raw"), "wb") as f:
        f.write(uniforms())
    with open(os.path.join(out, "lights.raw"), "wb") as f:
        f.write(uniforms()[48:112])
    job = {"jobs": [{"name": "lambert", "width": W, "height": H, "layers": 1, "images": 7, "wgsl": os.path.join(out, "pass.wgsl"),
                     "uniforms": os.path.join(out, "uniforms.raw"), "lights": os.path.join(out, "lights.raw"),
                     "gbuffer": os.path.join(out, "gbuffer.raw"), "textures": [], "output": os.path.join(out, "image")}]}
    job_file = os.path.join(out, "job.json")
    with open(job_file, "w") as f:
        json.dump(job, f)
    subprocess.run([sys.executable, os.path.join(harness, "wgpu_render.py"), job_file], check=True)
    with open(job_file + ".result.json") as f:
        result = json.load(f)
    print("adapter:", result["adapter"])
    r = result["results"][0]
    if not r["ok"]:
        sys.exit(f"the harness failed: {r['error']}")
    rgb, alpha = read_pfm(os.path.join(out, "image.pfm")), read_pfm(os.path.join(out, "image.alpha.pfm"))
    worst = max(float(np.abs(rgb - expected[:, :, :3]).max()), float(np.abs(alpha[:, :, 0] - expected[:, :, 3]).max()))
    print(f"worst |Δ| = {worst:.3g} over {W}×{H} pixels ({'a wrong G-buffer' if wrong else 'the right one'})")
    sys.exit(0 if worst <= 1e-6 else 1)


if __name__ == "__main__":
    main()
