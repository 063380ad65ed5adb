"""Generates WGSL (the full shader and --library) and validates it with naga, the WGSL
front end inside wgpu-native (pip wgpu; headless on Mesa's lavapipe here).

    wgsl_check.py FACET OUTDIR MATERIAL...   each material file
    wgsl_check.py FACET OUTDIR --models      one material per catalog model, at its defaults
    wgsl_check.py FACET OUTDIR --self-test MATERIAL
        the check has teeth: the material's shader passes, and deliberately wrong
        variants of it (a return of the wrong type, C's ?:, an i32 assigned to an
        f32, a texture read with GLSL's texelFetch) are each refused.

Exit 1 when any shader is refused (naga's message printed) or facet fails.
"""
import json
import os
import subprocess
import sys


def device():
    import wgpu  # here, so that a missing wgpu says so in the test's own words

    adapter = wgpu.gpu.request_adapter_sync()
    if adapter is None:
        sys.exit("wgsl_check: wgpu found no adapter (Mesa's lavapipe: Debian mesa-vulkan-drivers)")
    return adapter.request_device_sync()


def naga_error(dev, code):
    """naga's complaint about `code`, or None when it validates."""
    import wgpu

    try:
        dev.create_shader_module(code=code)
    except wgpu.GPUError as e:  # GPUValidationError: naga's message
        return str(e)
    return None


def generate(facet, material, out, library):
    cmd = [facet, "generate", material, "--target", "wgsl", "-o", out]
    if library:
        cmd.append("--library")
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        return None, f"facet generate failed ({r.returncode}): {r.stderr.strip()}"
    with open(out, encoding="utf-8") as f:
        return f.read(), None


def model_materials(facet, outdir):
    """One material file per catalog model: the lobe alone, every parameter at its default."""
    models = json.loads(subprocess.run([facet, "models", "--json"], capture_output=True, text=True,
                                       check=True).stdout)
    files = []
    for section in ("diffuse", "specular"):
        for m in models["sections"][section]:
            spec = {"model": m["name"]}
            for p in m["parameters"]:
                if p.get("default") is not None:
                    spec[p["name"]] = p["default"]
            path = os.path.join(outdir, f"model_{m['name']}.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump({"name": m["name"], section: spec}, f)
            files.append(path)
    if not files:
        sys.exit("wgsl_check: facet models --json listed no model")
    return files


def check(facet, outdir, materials):
    dev = device()
    failed = 0
    for material in materials:
        name = os.path.splitext(os.path.basename(material))[0]
        for library in (False, True):
            out = os.path.join(outdir, name + (".lib.wgsl" if library else ".wgsl"))
            code, error = generate(facet, material, out, library)
            if error is None:
                error = naga_error(dev, code)
            what = f"{name}{' --library' if library else ''}"
            if error:
                failed += 1
                print(f"FAIL {what}: {out}\n{error}")
            else:
                print(f"ok   {what} ({len(code)} bytes)")
    return failed


# Each wrong variant: (what, the text replaced, its replacement).
WRONG = [
    ("a return of the wrong type", "fn facet_tangent(n: vec3<f32>) -> vec3<f32> {",
     "fn facet_tangent(n: vec3<f32>) -> f32 {"),
    ("C's ?: for select()", "if (factor > 0.0 && dot(n, l) > 0.0) {", "if (factor > 0.0 ? true : false) {"),
    ("an integer where a float is wanted", "d = length(to_light);", "d = i;"),
    ("GLSL's texelFetch", "textureLoad(image,", "texelFetch(image,"),
]


def self_test(facet, outdir, material):
    dev = device()
    code, error = generate(facet, material, os.path.join(outdir, "self_test.wgsl"), False)
    if error or naga_error(dev, code):
        print(f"FAIL: the right shader is refused: {error or naga_error(dev, code)}")
        return 1
    failed = 0
    for what, old, new in WRONG:
        if old not in code:
            print(f"FAIL: cannot make the variant ({what}): {old!r} not in the shader")
            failed += 1
            continue
        error = naga_error(dev, code.replace(old, new, 1))
        print(f"{'ok  ' if error else 'FAIL'} {what}: {'refused' if error else 'ACCEPTED'}")
        if error:
            print("     " + error.strip().splitlines()[-1].strip())
        failed += error is None
    return failed


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    facet, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    if sys.argv[3] == "--self-test":
        failed = self_test(facet, outdir, sys.argv[4])
    elif sys.argv[3] == "--models":
        failed = check(facet, outdir, model_materials(facet, outdir))
    else:
        failed = check(facet, outdir, sys.argv[3:])
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
