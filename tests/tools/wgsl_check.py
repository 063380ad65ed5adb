"""Generates WGSL (the full shader and --library) and validates it with naga, the WGSL
front end inside wgpu-native (pip wgpu; headless on Mesa's lavapipe here), or with
--tint in Chromium's WebGPU (Dawn, whose WGSL compiler is Tint; headless, on its
SwiftShader adapter), every shader in one browser start.

    wgsl_check.py [--tint] FACET OUTDIR MATERIAL...   each material file
    wgsl_check.py [--tint] FACET OUTDIR --models      and/or one material per catalog model, at its defaults
    wgsl_check.py [--tint] FACET OUTDIR --self-test MATERIAL
        the check has teeth: the material's shader passes, and deliberately wrong
        variants of it (a return of the wrong type, C's ?:, an i32 assigned to an
        f32, a texture read with GLSL's texelFetch) are each refused.

Exit 1 when any shader is refused (the compiler's message printed) or facet fails.
"""
import base64
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time


def device():
    import wgpu  # here, so that a missing wgpu says so in the test's own words

    adapter = wgpu.gpu.request_adapter_sync()
    if adapter is None:
        sys.exit("wgsl_check: wgpu found no adapter (Mesa's lavapipe: Debian mesa-vulkan-drivers)")
    return adapter.request_device_sync()


def naga_errors(codes):
    """naga's complaint about each of `codes`, None for each that validates."""
    import wgpu

    dev = device()
    errors = []
    for code in codes:
        try:
            dev.create_shader_module(code=code)
            errors.append(None)
        except wgpu.GPUError as e:  # GPUValidationError: naga's message
            errors.append(str(e))
    return errors


# The page: every shader through createShaderModule and getCompilationInfo(), the errors
# handed back on the console (base64 JSON, so no message can break the line).
TINT_PAGE = """<!doctype html><meta charset="utf-8"><script>
const b64 = s => new TextDecoder().decode(Uint8Array.from(atob(s), c => c.charCodeAt(0)));
const report = o => {
  const bytes = new TextEncoder().encode(JSON.stringify(o));
  let bin = ""; for (const b of bytes) bin += String.fromCharCode(b);
  console.log("FACET_TINT " + btoa(bin));
};
(async () => {
  try {
    if (!navigator.gpu) return report({error: "this Chromium has no navigator.gpu"});
    const adapter = await navigator.gpu.requestAdapter();
    if (!adapter) return report({error: "Chromium's WebGPU found no adapter"});
    const device = await adapter.requestDevice();
    const errors = [];
    for (const code of JSON.parse(b64("@SOURCES@"))) {
      const info = await device.createShaderModule({code}).getCompilationInfo();
      const e = info.messages.filter(m => m.type === "error").map(m => `${m.lineNum}:${m.linePos}: ${m.message}`);
      errors.push(e.length ? e.join("\\n") : null);
    }
    const a = adapter.info || {};
    report({adapter: `${a.vendor} ${a.architecture}`.trim(), errors});
  } catch (e) { report({error: String(e)}); }
})();
</script>"""


def tint_errors(codes, outdir):
    """Tint's complaint about each of `codes` (None where it compiles), in one headless
    Chromium (Debian's chromium) with WebGPU on: its console goes to stderr, read until
    the page's report."""
    chromium = shutil.which("chromium")
    if not chromium:
        sys.exit("wgsl_check: chromium not found on PATH (Debian's chromium package)")
    page = os.path.join(os.path.abspath(outdir), "tint.html")
    sources = base64.b64encode(json.dumps(codes).encode()).decode()
    with open(page, "w", encoding="utf-8") as f:
        f.write(TINT_PAGE.replace("@SOURCES@", sources))
    # Chromium's helper processes may still write into the profile as it is removed.
    with tempfile.TemporaryDirectory(ignore_cleanup_errors=True) as profile:
        p = subprocess.Popen([chromium, "--headless=new", "--enable-unsafe-webgpu", "--enable-features=Vulkan",
                              "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--no-sandbox",
                              "--no-first-run", f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0",
                              "file://" + page], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                             errors="replace", start_new_session=True)
        deadline, result, log = time.time() + 300, None, []
        try:
            for line in p.stderr:
                if "FACET_TINT " in line:
                    result = json.loads(base64.b64decode(line.split("FACET_TINT ", 1)[1].split('"', 1)[0]))
                    break
                log.append(line)
                if time.time() > deadline:
                    break
        finally:  # the browser and every helper it started
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
    if result is None:
        sys.exit("wgsl_check: Chromium gave no report; its log:\n" + "".join(log[-40:]))
    if "error" in result:
        sys.exit("wgsl_check: " + result["error"])
    print(f"Chromium WebGPU adapter: {result['adapter']}")
    return result["errors"]


def compile_errors(codes, outdir, tint):
    return tint_errors(codes, outdir) if tint else naga_errors(codes)


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


def check(facet, outdir, materials, tint):
    failed, shaders = 0, []
    for material in materials:
        name = os.path.splitext(os.path.basename(material))[0]
        for library in (False, True):
            out = os.path.join(outdir, name + (".lib.wgsl" if library else ".wgsl"))
            code, error = generate(facet, material, out, library)
            what = f"{name}{' --library' if library else ''}"
            if error:
                failed += 1
                print(f"FAIL {what}: {error}")
            else:
                shaders.append((what, out, code))
    for (what, out, code), error in zip(shaders, compile_errors([c for _, _, c in shaders], outdir, tint)):
        if error:
            failed += 1
            print(f"FAIL {what}: {out}\n{error}")
        else:
            print(f"ok   {what} ({len(code)} bytes)")
    print(f"{len(shaders) - failed} of {len(shaders)} WGSL files accepted by {'Tint' if tint else 'naga'}")
    return failed


# Each wrong variant: (what, the text replaced, its replacement).
WRONG = [
    ("a return of the wrong type", "fn facet_tangent(n: vec3<f32>) -> vec3<f32> {",
     "fn facet_tangent(n: vec3<f32>) -> f32 {"),
    ("C's ?: for select()", "if (factor > 0.0 && dot(n, l) > 0.0) {", "if (factor > 0.0 ? true : false) {"),
    ("an integer where a float is wanted", "d = length(to_light);", "d = i;"),
    ("GLSL's texelFetch", "textureLoad(image,", "texelFetch(image,"),
]


def self_test(facet, outdir, material, tint):
    code, error = generate(facet, material, os.path.join(outdir, "self_test.wgsl"), False)
    if error:
        print(f"FAIL: {error}")
        return 1
    variants = []
    for what, old, new in WRONG:
        if old not in code:
            print(f"FAIL: cannot make the variant ({what}): {old!r} not in the shader")
            return 1
        variants.append(code.replace(old, new, 1))
    errors = compile_errors([code] + variants, outdir, tint)
    if errors[0]:
        print(f"FAIL: the right shader is refused: {errors[0]}")
        return 1
    failed = 0
    for (what, _, _), error in zip(WRONG, errors[1:]):
        print(f"{'ok  ' if error else 'FAIL'} {what}: {'refused' if error else 'ACCEPTED'}")
        if error:
            print("     " + error.strip().splitlines()[-1].strip())
        failed += error is None
    return failed


def main():
    args = sys.argv[1:]
    tint = "--tint" in args
    if tint:
        args.remove("--tint")
    if len(args) < 3:
        sys.exit(__doc__)
    facet, outdir, rest = args[0], args[1], args[2:]
    os.makedirs(outdir, exist_ok=True)
    if rest[0] == "--self-test":
        failed = self_test(facet, outdir, rest[1], tint)
    else:
        materials = [m for m in rest if m != "--models"]
        if "--models" in rest:
            materials += model_materials(facet, outdir)
        failed = check(facet, outdir, materials, tint)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
