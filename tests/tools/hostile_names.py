"""Names are data, never code (issue 28): hostile names and file names through every target.

    python hostile_names.py FACET WORK        (a Python with pip bpy 4.5, wgpu and numpy)

1. A textured material whose name holds what a comment or a string literal must survive —
   `"`, `\\`, `*/`, `#error`, `//`, non-ASCII, 10,000 characters, a trailing backslash — and whose
   images sit in a folder and under file names with `"`, `\\`, `#` and spaces, generated for all
   seven targets. Each file must be accepted by the target's own tool (glslangValidator for
   glsl, essl and glsl450, its HLSL front end for hlsl, naga for wgsl, the OSL compiler inside
   Blender for osl, POV-Ray for pov), and no line of any may start with `#error` (the name's
   payload, which would be a directive there). The POV-Ray file is rendered and compared with
   the reference (`facet render -r pov --check`), reading the images through their odd names.
2. A line break in a name cannot be made harmless in a `//` comment, so facet refuses it, naming
   the key: a material's `name` with U+000A, a scene's object named with U+000D, a scene's
   material key with U+2028 (a line break in WGSL).
3. A glTF asset whose material, node and scene names carry POV-Ray's file directives after
   line breaks (`#fopen … write`, `#include "/etc/passwd"`): `facet import-gltf` makes the names
   one line (stand-ins ␊ ␍, with a note), and `facet render -r pov` of it, run in a folder of its
   own with its work folder elsewhere, writes no file the payload names, anywhere it could.

Prints one line per check; exits 1 on any failure.
"""
import json
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

PAYLOAD = '#error injected'
HOSTILE = ('Gold "quoted" */ /* ' + PAYLOAD + ' // \\ back\\slash — ünïcödé ✓ ' + 'n' * 10000 + ' \\')
POV_PAYLOAD = 'PWNED_by_name.txt'
FAILURES = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}" + (f": {detail}" if detail and not ok else ""))
    if not ok:
        FAILURES.append(what)


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def hostile_material(work):
    """The material and its images in a folder whose name and files' names need escaping."""
    folder = os.path.join(work, 'lib "odd" \\ #1')
    os.makedirs(folder, exist_ok=True)
    shutil.copy(os.path.join(REPO, "examples", "textured", "textures", "checker.png"), os.path.join(folder, 'check "er" #2.png'))
    shutil.copy(os.path.join(REPO, "examples", "textured", "textures", "roughness16.png"), os.path.join(folder, 'rough\\ness.png'))
    material = {"name": HOSTILE,
                "diffuse": {"model": "lambert", "color": {"texture": 'check "er" #2.png', "factor": 0.8}},
                "specular": {"model": "ggx", "color": [1, 1, 1], "alpha": {"texture": "rough\\ness.png", "factor": 0.5},
                             "geometry": "smith_ggx", "fresnel": {"model": "schlick", "f0": [0.04, 0.04, 0.04]}}}
    path = os.path.join(folder, "hostile.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(material, f, ensure_ascii=False)
    return path


def no_directive(text):
    return not any(line.lstrip().startswith(PAYLOAD) for line in text.splitlines())


def targets(facet, work, material):
    out = os.path.join(work, "generated")
    os.makedirs(out, exist_ok=True)
    files = {}
    for target in ("glsl", "essl", "glsl450", "hlsl", "wgsl", "osl", "pov"):
        path = os.path.join(out, f"hostile.{target}")
        gen = run([facet, "generate", material, "--target", target, "-o", path])
        check(gen.returncode == 0, f"{target}: facet generate", gen.stderr)
        if gen.returncode != 0:
            continue
        text = open(path, encoding="utf-8").read()
        check(no_directive(text), f"{target}: no line starts with the name's '{PAYLOAD}'")
        check("n" * 10000 in text, f"{target}: the 10,000-character name is kept whole in its comments")
        files[target] = path
    glslang = {"glsl": ["-S", "frag"], "essl": ["-S", "frag"], "glsl450": ["-V", "-S", "frag", "-o", os.devnull],
               "hlsl": ["-D", "-V", "-S", "frag", "-e", "main", "-o", os.devnull]}
    for target, args in glslang.items():
        if target in files:
            r = run(["glslangValidator", *args, files[target]])
            check(r.returncode == 0, f"{target}: glslangValidator accepts it", r.stdout + r.stderr)
    if "wgsl" in files:
        import wgsl_check
        err = wgsl_check.naga_errors([open(files["wgsl"], encoding="utf-8").read()])[0]
        check(err is None, "wgsl: naga accepts it", str(err))
    if "osl" in files:
        import bpy  # noqa: F401  (Cycles' native module)
        import _cycles
        oso = files["osl"][:-4] + ".oso"
        check(bool(_cycles.osl_compile(files["osl"], oso)) and os.path.exists(oso),
              "osl: Blender's OSL compiler accepts it (the image paths are string literals)")
    if "pov" in files:
        r = run([facet, "render", material, "-r", "pov", "--size", "48x48", "--check", "2e-5",
                 "--workdir", os.path.join(work, "pov_work")])
        check(r.returncode == 0, "pov: POV-Ray renders it, within 2e-5 of the reference", r.stdout + r.stderr)


def refusals(facet, work):
    folder = os.path.join(work, "refused")
    os.makedirs(folder, exist_ok=True)
    lambert = {"diffuse": {"model": "lambert", "color": [0.5, 0.5, 0.5]}}
    m = os.path.join(folder, "newline.json")
    json.dump(dict(lambert, name="x\n" + PAYLOAD), open(m, "w"))
    r = run([facet, "generate", m, "--target", "glsl"])
    check(r.returncode != 0 and "name:" in r.stderr and "U+000A (a line feed) at character 1" in r.stderr,
          "a material name with a line feed is refused, naming the key", r.stderr)
    check("\n" + PAYLOAD not in r.stderr, "the refusal shows the line feed as a stand-in", r.stderr)
    camera = {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40}
    scene = {"name": "s", "camera": camera, "materials": {"grey": lambert},
             "objects": [{"type": "sphere", "name": "ball\r" + PAYLOAD, "material": "grey", "center": [0, 0, 0],
                          "radius": 1}],
             "lights": [{"type": "point", "position": [2, 2, 2], "color": [1, 1, 1]}]}
    s = os.path.join(folder, "cr.json")
    json.dump(scene, open(s, "w"))
    r = run([facet, "render", "--scene", s, "--size", "8x8", "-o", os.path.join(folder, "cr.pfm")])
    check(r.returncode != 0 and "objects[0].name" in r.stderr and "U+000D" in r.stderr,
          "an object name with a carriage return is refused, naming the key", r.stderr)
    scene["objects"][0]["name"] = "ball"
    scene["materials"] = {"grey\u2028" + PAYLOAD: lambert}
    scene["objects"][0]["material"] = "grey\u2028" + PAYLOAD
    json.dump(scene, open(s, "w"), ensure_ascii=False)
    r = run([facet, "generate", "--scene", s, "--target", "wgsl"])
    check(r.returncode != 0 and "U+2028" in r.stderr and "materials." in r.stderr,
          "a material key with U+2028 (a WGSL line break) is refused, naming the key", r.stderr)


def gltf_payload(facet, work):
    import gltf_build as gb
    folder = os.path.join(work, "gltf")
    here = os.path.join(folder, "cwd")
    workdir = os.path.join(folder, "work")
    os.makedirs(here, exist_ok=True)
    directive = (f'\n#fopen F "{POV_PAYLOAD}" write #write(F, "pwned\\n") #fclose F\n'
                 '#include "/etc/passwd"\n//')
    doc = gb.Document()
    mat = doc.material('x"' + directive, base=(0.7, 0.5, 0.3, 1.0), roughness=0.5)
    doc.node(name="node\r" + directive, mesh=doc.mesh(doc.primitive(gb.uv_sphere(1.0, 16, 8), mat), "ball"))
    doc.camera((0.0, 0.5, 4.0), (0.0, 0.0, 0.0))
    doc.light("point", gb.point_candela(500.0), at=(2.0, 3.0, 3.0), name="key" + directive)
    doc.d["scenes"][0]["name"] = "scene" + directive
    src = os.path.join(folder, "payload.gltf")
    doc.save(src)
    scene = os.path.join(folder, "payload.json")
    r = run([facet, "import-gltf", src, "-o", scene])
    check(r.returncode == 0, "glTF with directives in its names imports", r.stderr)
    check("names made one line" in r.stderr and "U+000A" in r.stderr, "import-gltf says which names it made one line",
          r.stderr)
    data = json.load(open(scene, encoding="utf-8"))
    names = [data.get("name", "")] + [o.get("name", "") for o in data["objects"]] + \
            [m.get("name", "") for m in data.get("materials", {}).values() if isinstance(m, dict)]
    check(not any(re.search("[\x00-\x1f\x7f\u0085\u2028\u2029]", n) for n in names),
          "the imported scene's names are one line each", repr(names))
    for renderer in ("pov", "glsl", "osl"):
        r = run([facet, "render", "--scene", scene, "-r", renderer, "--size", "32x32", "--check", "2e-3",
                 "--workdir", os.path.join(workdir, renderer), "-o", os.path.join(folder, f"{renderer}.pfm")], cwd=here)
        check(r.returncode == 0, f"{renderer}: the scene renders, within 2e-3 of the reference", r.stdout + r.stderr)
    written = [os.path.join(d, POV_PAYLOAD) for d in (here, workdir, os.path.join(workdir, "pov"), folder, "/tmp",
                                                        os.path.expanduser("~"))]
    check(not any(os.path.exists(p) for p in written), "POV-Ray wrote no file the names asked for",
          ", ".join(p for p in written if os.path.exists(p)))
    pov_files = []
    for root, _, files in os.walk(os.path.join(workdir, "pov")):
        pov_files += [os.path.join(root, f) for f in files if f.endswith((".pov", ".inc"))]
    check(bool(pov_files) and all(no_directive_pov(open(p, encoding="utf-8").read()) for p in pov_files),
          "the generated POV-Ray files hold no #fopen or #include of the names", ", ".join(pov_files))


def no_directive_pov(text):
    return not any(re.match(r'\s*#(fopen|write|include\s+"/etc)', line) for line in text.splitlines())


def main():
    facet, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for stale in (os.path.join("/tmp", POV_PAYLOAD),):
        if os.path.exists(stale):
            os.remove(stale)
    targets(facet, work, hostile_material(work))
    refusals(facet, work)
    gltf_payload(facet, work)
    print(f"hostile names: {'FAIL: ' + ', '.join(FAILURES) if FAILURES else 'every check passes'}")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
