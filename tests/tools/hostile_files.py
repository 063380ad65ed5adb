"""Hostile files (issue 28): no file read or written outside what the user named, no hang, no
crash, no collision, nothing left behind.

    python hostile_files.py FACET WORK

1. glTF URIs that leave the file's folder — `..`, an absolute path, `%2e%2e`, a symbolic link
   leading out, /proc/self/environ — for a buffer and for an image: refused with the key named
   and one message whether the file named exists or not (so the error tells nothing about
   files outside); with `--allow-path` the absolute image is read.
2. Files that are not files — a FIFO, /dev/zero, a folder — as a material, a scene, a glTF and
   a texture: refused at once with what they are (a FIFO would block, /dev/zero read forever).
3. Depth and size: a glTF whose node hierarchy is a chain 100,000 deep imports; one whose
   `extras` nest 30,000 deep is refused past the stated 256 levels; a PNG that says it is
   100000×100000 texels is refused naming its size.
4. validate --out naming a file, or a folder that cannot be made: a clear error, exit 1.
5. Collisions: two materials named "a-b" and "a b", and two files p/x.json and q/x.json, in one
   `facet validate`: four images of their own, every one passing.
6. Concurrency: two `facet render -r pov` of the same material at once (no --workdir) both
   match the reference; two `facet validate` of the same material at once, each with its own
   --out, both pass with their own images; a second `facet validate` on an --out that a first one holds is refused
   while the first runs, and the first passes.
7. kill -9: during `facet validate -r pov` (while POV-Ray runs) — no POV-Ray process outlives it
   —, then a rerun passes and leaves no work files, no temporary files, no private work folder;
   during `facet import-gltf` (while it writes its output) — the rerun removes the temporary
   file the killed run left and writes the scene.
8. A full disk, as the file-size limit (`ulimit -f`, SIGXFSZ ignored) makes it: every write past
   the limit fails with EFBIG as one past the disk's end fails with ENOSPC. At limits that stop
   facet's own writes and POV-Ray's image: `render -r pov` (with and without --workdir),
   `validate`, `sweep` and `import-gltf` (whose image is too big) fail with an error naming what
   could not be written, and leave no partial output, no temporary file, no `.pov-state`, no
   work folder and no report of a run that did not finish.
9. Afterwards $TMPDIR (a folder of this script's own) holds nothing: no run left its work folder.

Prints one line per check; exits 1 on any failure.
"""
import base64
import random
import resource
import zlib
import glob
import json
import os
import shutil
import signal
import struct
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
FAILURES = []


def check(ok, what, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}" + (f": {detail}" if detail and not ok else ""), flush=True)
    if not ok:
        FAILURES.append(what)


def run(cmd, timeout=300, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, **kw)


def triangle_gltf(buffer_uri=None, image_uri=None, textured=True):
    """One triangle; its positions and (when textured) its base-colour image from the URIs given
    (else data URIs). Its texture coordinates are a second buffer, always a data URI."""
    pos = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
    uv = struct.pack('<6f', 0, 0, 1, 0, 0, 1)
    png = open(os.path.join(REPO, "examples", "textured", "textures", "checker.png"), "rb").read()
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 1, 0]}],
           "bufferViews": [{"buffer": 0, "byteLength": 36}],
           "buffers": [{"byteLength": 36,
                        "uri": buffer_uri or "data:application/octet-stream;base64," + base64.b64encode(pos).decode()}]}
    if textured:
        doc["meshes"][0]["primitives"][0].update({"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0})
        doc["accessors"].append({"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"})
        doc["bufferViews"].append({"buffer": 1, "byteLength": 24})
        doc["buffers"].append({"byteLength": 24,
                               "uri": "data:application/octet-stream;base64," + base64.b64encode(uv).decode()})
        doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        doc["textures"] = [{"source": 0}]
        doc["images"] = [{"uri": image_uri or "data:image/png;base64," + base64.b64encode(png).decode()}]
    return doc


def write_json(path, doc):
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


def error_line(out, uri):
    """The error with the URI taken out: what it says apart from the name given."""
    lines = [l for l in out.splitlines() if l.startswith("error:")]
    return lines[0].replace(uri, "<uri>") if lines else ""


def uris(facet, work):
    folder, outside = os.path.join(work, "uris", "asset"), os.path.join(work, "uris", "outside")
    os.makedirs(folder)
    os.makedirs(outside)
    shutil.copy(os.path.join(REPO, "examples", "textured", "textures", "checker.png"), os.path.join(outside, "c.png"))
    with open(os.path.join(outside, "secret.bin"), "wb") as f:
        f.write(os.urandom(36))
    os.symlink(os.path.join(outside, "c.png"), os.path.join(folder, "link.png"))
    os.symlink(os.path.join(outside, "secret.bin"), os.path.join(folder, "link.bin"))
    out = os.path.join(work, "uris", "out.json")
    cases = [("buffer", "../outside/secret.bin", "../outside/missing.bin"),
             ("buffer", os.path.join(outside, "secret.bin"), os.path.join(outside, "missing.bin")),
             ("buffer", "%2e%2e/outside/secret.bin", "%2e%2e/outside/missing.bin"),
             ("buffer", "link.bin", None),
             ("image", "../outside/c.png", "../outside/missing.png"),
             ("image", os.path.join(outside, "c.png"), os.path.join(outside, "missing.png")),
             ("image", "%2E%2E/outside/c.png", "%2E%2E/outside/missing.png"),
             ("image", "link.png", None),
             ("image", "/proc/self/environ", "/proc/self/no-such-file")]
    for kind, there, missing in cases:
        key = "buffers[0].uri" if kind == "buffer" else "baseColorTexture"
        said = []
        for uri in [u for u in (there, missing) if u]:
            doc = triangle_gltf(buffer_uri=uri) if kind == "buffer" else triangle_gltf(image_uri=uri)
            r = run([facet, "import-gltf", write_json(os.path.join(folder, "a.gltf"), doc), "-o", out])
            said.append(error_line(r.stderr, uri))
            check(r.returncode == 1 and key in r.stderr and "cannot be used" in r.stderr and "--allow-path" in r.stderr,
                  f"{kind} URI {uri!r} outside the glTF's folder is refused, naming {key}", r.stderr[-300:])
        if missing:
            check(said[0] == said[1], f"{kind} URI: the same error whether {os.path.basename(there)} exists or not",
                  f"{said[0]!r} vs {said[1]!r}")
    doc = triangle_gltf(image_uri=os.path.join(outside, "c.png"))
    r = run([facet, "import-gltf", write_json(os.path.join(folder, "a.gltf"), doc), "-o", out, "--allow-path", outside])
    check(r.returncode == 0, "--allow-path DIR lets an image in DIR be read", r.stderr[-300:])
    r = run([facet, "import-gltf", write_json(os.path.join(folder, "a.gltf"), triangle_gltf(image_uri="link.png")),
             "-o", out, "--allow-path", outside])
    check(r.returncode == 0, "--allow-path DIR lets a link into DIR be read", r.stderr[-300:])


def texture_paths(facet, work):
    """A material's and a scene's texture paths follow the glTF's rule: inside the file's folder."""
    folder, outside = os.path.join(work, "textures", "here"), os.path.join(work, "textures", "outside")
    os.makedirs(folder)
    os.makedirs(outside)
    shutil.copy(os.path.join(REPO, "examples", "textured", "textures", "checker.png"), os.path.join(outside, "c.png"))
    os.symlink(os.path.join(outside, "c.png"), os.path.join(folder, "link.png"))
    cases = [("../outside/c.png", "../outside/missing.png"),
             (os.path.join(outside, "c.png"), os.path.join(outside, "missing.png")),
             ("link.png", None), ("/proc/self/environ", "/proc/self/no-such-file")]

    def material_with(texture):
        return {"name": "m", "diffuse": {"model": "lambert", "color": {"texture": texture}}}

    def scene_with(texture):
        return {"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
                "materials": {"m": material_with(texture)},
                "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
                "lights": [{"type": "point", "position": [2, 2, 4], "color": [1, 1, 1]}]}

    def material_run(texture, extra=()):
        path = write_json(os.path.join(folder, "m.json"), material_with(texture))
        return run([facet, "generate", path, "-t", "glsl", *extra])

    def scene_run(texture, extra=()):
        path = write_json(os.path.join(folder, "s.json"), scene_with(texture))
        return run([facet, "render", "--scene", path, "-r", "reference", "--size", "16x16", "-o",
                    os.path.join(work, "textures", "s.pfm"), *extra])

    for kind, go, key in (("material", material_run, "diffuse.color.texture"),
                          ("scene", scene_run, "materials.m.diffuse.color.texture")):
        for there, missing in cases:
            said = []
            for texture in [t for t in (there, missing) if t]:
                r = go(texture)
                said.append(error_line(r.stderr, texture))
                check(r.returncode == 1 and key in r.stderr and "cannot be used" in r.stderr and
                      "--allow-path" in r.stderr, f"a {kind}'s texture {texture!r} outside its folder is refused, "
                      f"naming {key}", r.stderr[-300:])
            if missing:
                check(said[0] == said[1], f"a {kind}'s texture: the same error whether {os.path.basename(there)} "
                      "exists or not", f"{said[0]!r} vs {said[1]!r}")
        r = go(os.path.join(outside, "c.png"), ("--allow-path", outside))
        check(r.returncode == 0, f"--allow-path DIR lets a {kind}'s texture in DIR be read", r.stderr[-300:])


def not_files(facet, work):
    folder = os.path.join(work, "not_files")
    os.makedirs(folder)
    fifo = os.path.join(folder, "fifo")
    os.mkfifo(fifo)
    for path, what in ((fifo, "a FIFO"), ("/dev/zero", "a device"), (folder, "a folder")):
        for cmd in (["generate", path, "-t", "glsl"], ["render", "--scene", path, "-o", os.path.join(folder, "x.pfm")],
                    ["import-gltf", path, "-o", os.path.join(folder, "x.json")]):
            try:
                r = run([facet] + cmd, timeout=20)
                check(r.returncode == 1 and what in r.stderr, f"facet {cmd[0]} of {what} ({path}) is refused",
                      r.stderr[-300:])
            except subprocess.TimeoutExpired:
                check(False, f"facet {cmd[0]} of {what} ({path}) is refused", "it hung")
        material = write_json(os.path.join(folder, "m.json"),
                              {"name": "m", "diffuse": {"model": "lambert", "color": {"texture": path}}})
        try:  # allowed, so that what it is (not where it is) refuses it
            r = run([facet, "generate", material, "-t", "glsl", "--allow-path", os.path.dirname(path)], timeout=20)
            check(r.returncode == 1 and what in r.stderr and "diffuse.color.texture" in r.stderr,
                  f"a texture that is {what} is refused, naming the key", r.stderr[-300:])
        except subprocess.TimeoutExpired:
            check(False, f"a texture that is {what} is refused", "it hung")


def depth_and_size(facet, work):
    folder = os.path.join(work, "depth")
    os.makedirs(folder)
    doc = triangle_gltf(textured=False)
    n = 100_000
    doc["nodes"] = [{"children": [i + 1]} for i in range(n - 1)] + [{"mesh": 0}]
    doc["nodes"][n // 2]["translation"] = [0, 0, 1]  # the chain's transforms are multiplied all the way down
    r = run([facet, "import-gltf", write_json(os.path.join(folder, "chain.gltf"), doc), "-o",
             os.path.join(folder, "chain.json")])
    check(r.returncode == 0, f"a node chain {n:,} deep imports", r.stderr[-300:])
    if r.returncode == 0:
        scene = json.load(open(os.path.join(folder, "chain.json")))
        obj = scene["objects"][0]
        check(len(scene["objects"]) == 1 and obj.get("type") == "mesh" and obj.get("node") == n - 1,
              "the chain's one mesh is in the scene, at the chain's last node", json.dumps(obj))
        r = run([facet, "render", "--scene", os.path.join(folder, "chain.json"), "-r", "reference", "--size", "16x16",
                 "-o", os.path.join(folder, "chain.pfm")])
        check(r.returncode == 0, "the scene that names it renders (the chain walked again)", r.stderr[-300:])
    text = json.dumps(triangle_gltf())[:-1] + ', "extras": ' + "[" * 30000 + "]" * 30000 + "}"
    with open(os.path.join(folder, "deep.gltf"), "w") as f:
        f.write(text)
    r = run([facet, "import-gltf", os.path.join(folder, "deep.gltf"), "-o", os.path.join(folder, "deep.json")])
    check(r.returncode == 1 and "256 levels" in r.stderr and "extras" in r.stderr,
          "extras nested 30,000 deep are refused past 256 levels, naming where", r.stderr[-300:])
    ihdr = struct.pack(">IIBBBBB", 100000, 100000, 8, 6, 0, 0, 0)
    png = b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + b"IHDR" + ihdr + b"\0\0\0\0"
    with open(os.path.join(folder, "huge.png"), "wb") as f:
        f.write(png)
    material = write_json(os.path.join(folder, "m.json"),
                          {"name": "m", "diffuse": {"model": "lambert", "color": {"texture": "huge.png"}}})
    r = run([facet, "generate", material, "-t", "glsl"])
    check(r.returncode == 1 and "100000×100000" in r.stderr and "16384" in r.stderr,
          "a PNG of 100000×100000 texels is refused, naming its size and the limit", r.stderr[-300:])


def validate_out(facet, work):
    folder = os.path.join(work, "out_errors")
    os.makedirs(folder)
    a_file = os.path.join(folder, "a_file")
    open(a_file, "w").close()
    lambert = os.path.join(REPO, "examples", "materials", "lambert.json")
    for out, words in ((a_file, "is a file, not a folder"), (os.path.join(a_file, "below"), "cannot make the folder")):
        r = run([facet, "validate", lambert, "--renderers", "reference", "--size", "16x16", "--out", out])
        check(r.returncode == 1 and words in r.stderr and "--out" in r.stderr, f"validate --out {out}: {words}",
              r.stderr[-300:])


def material(path, name, model="lambert"):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    spec = {"model": model, "color": [0.5, 0.3, 0.2]}
    if model == "oren_nayar":
        spec["sigma"] = 0.3
    return write_json(path, {"name": name, "diffuse": spec})


def collisions(facet, work):
    folder = os.path.join(work, "collisions")
    files = [material(os.path.join(folder, "ab1.json"), "a-b"), material(os.path.join(folder, "ab2.json"), "a b",
                                                                           "oren_nayar"),
             material(os.path.join(folder, "p", "x.json"), "x p"),
             material(os.path.join(folder, "q", "x.json"), "x q", "oren_nayar")]
    out = os.path.join(folder, "out")
    r = run([facet, "validate", *files, "--renderers", "reference,pov", "--scene", "single", "--size", "48x48",
             "--out", out])
    check(r.returncode == 0, "validate of a-b, a b, p/x.json and q/x.json passes", r.stdout[-600:] + r.stderr[-300:])
    pov = sorted(os.path.basename(p) for p in glob.glob(os.path.join(out, "images", "*_pov.png")))
    check(len(pov) == 4, "four materials, four POV-Ray images of their own", str(pov))
    check(not os.path.exists(os.path.join(out, "work")), "validate removes its work folder when done")


def our_tmp_folders():
    tmp = os.environ.get("TMPDIR", "/tmp")
    return {p for p in glob.glob(os.path.join(tmp, "facet-*-*"))
            if os.path.basename(p).split("-")[1].isdigit()}


def pov_children_of(folder):
    """POV-Ray processes whose working folder is under `folder`."""
    found = []
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            if open(f"/proc/{pid}/comm").read().strip() == "povray" and \
                    os.readlink(f"/proc/{pid}/cwd").startswith(os.path.realpath(folder)):
                found.append(int(pid))
        except OSError:
            pass
    return found


def wait_for(condition, seconds):
    end = time.time() + seconds
    while time.time() < end:
        value = condition()
        if value:
            return value
        time.sleep(0.02)
    return None


def concurrency(facet, work):
    folder = os.path.join(work, "concurrent")
    os.makedirs(folder)
    ggx = os.path.join(REPO, "examples", "textured", "textured_ggx.json")
    runs = [subprocess.Popen([facet, "render", ggx, "-r", "pov", "--scene", "shadows", "--size", "64x48", "--check",
                              "1e-3", "-o", os.path.join(folder, f"r{i}.pfm")], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True) for i in range(2)]
    for i, p in enumerate(runs):
        out, err = p.communicate(timeout=300)
        check(p.returncode == 0, f"concurrent render {i + 1} of 2 (same material, no --workdir) matches the reference",
              out[-300:] + err[-300:])
    # Two validates of the same material at once, each with its own --out: separate, correct results.
    lambert = os.path.join(REPO, "examples", "materials", "lambert.json")
    both = [subprocess.Popen([facet, "validate", lambert, "--renderers", "reference,pov", "--scene", "single", "--size",
                              "64x64", "--out", os.path.join(folder, f"v{i}")], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True) for i in range(2)]
    for i, p in enumerate(both):
        o, e = p.communicate(timeout=600)
        images = glob.glob(os.path.join(folder, f"v{i}", "images", "*_pov.png"))
        check(p.returncode == 0 and len(images) == 1,
              f"concurrent validate {i + 1} of 2 (same material, its own --out) passes with its own images",
              o[-300:] + e[-300:])
    out = os.path.join(folder, "validate")
    first = subprocess.Popen([facet, "validate", "--renderers", "reference,pov", "--scene", "single", "--size",
                              "96x96", "--out", out], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    started = wait_for(lambda: pov_children_of(out), 120)
    second = run([facet, "validate", os.path.join(REPO, "examples", "materials", "lambert.json"), "--renderers",
                  "reference", "--size", "16x16", "--out", out])
    check(started and second.returncode == 1 and "another facet run" in second.stderr,
          "a second validate on an --out another one holds is refused", second.stderr[-300:])
    o, e = first.communicate(timeout=600)
    check(first.returncode == 0, "the first validate, undisturbed, passes", o[-400:] + e[-300:])


def kill_validate(facet, work):
    out = os.path.join(work, "killed", "validate")
    before = our_tmp_folders()
    cmd = [facet, "validate", "--renderers", "reference,pov", "--scene", "single", "--size", "96x96", "--out", out]
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    children = wait_for(lambda: pov_children_of(out), 120)
    check(bool(children), "POV-Ray runs under validate (to kill it there)")
    p.send_signal(signal.SIGKILL)
    p.wait()
    left = wait_for(lambda: not pov_children_of(out), 10)
    check(bool(left), "no POV-Ray process outlives facet's kill -9", str(pov_children_of(out)))
    r = run(cmd, timeout=900)
    check(r.returncode == 0, "validate after the kill passes", r.stdout[-400:] + r.stderr[-300:])
    check(not os.path.exists(os.path.join(out, "work")), "no work files after the rerun")
    temps = glob.glob(os.path.join(out, "**", ".facet-*"), recursive=True)
    check(not temps, "no temporary files in --out after the rerun", str(temps[:5]))
    check(not (our_tmp_folders() - before), "no private work folder left in $TMPDIR",
          str(sorted(our_tmp_folders() - before)))


def kill_import(facet, work):
    folder = os.path.join(work, "killed", "import")
    os.makedirs(folder)
    # A mesh big enough that writing its scene inline takes a while (about 40 MB of JSON).
    n = 300_000
    positions = bytearray()
    for i in range(n):
        x = float(i % 1000)
        y = float(i // 1000)
        positions += struct.pack("<9f", x, y, 0, x + 1, y, 0, x, y + 1, 0)
    doc = triangle_gltf(textured=False)
    doc["accessors"][0].update({"count": 3 * n, "max": [1000, 301, 0]})
    doc["bufferViews"][0]["byteLength"] = len(positions)
    doc["buffers"] = [{"byteLength": len(positions), "uri": "big.bin"}]
    with open(os.path.join(folder, "big.bin"), "wb") as f:
        f.write(positions)
    gltf = write_json(os.path.join(folder, "big.gltf"), doc)
    out = os.path.join(folder, "out", "scene.json")
    os.makedirs(os.path.dirname(out))
    cmd = [facet, "import-gltf", gltf, "-o", out, "--inline"]
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    temp = wait_for(lambda: glob.glob(os.path.join(os.path.dirname(out), ".facet-*")), 120)
    p.send_signal(signal.SIGKILL)
    p.wait()
    check(bool(temp), "import-gltf was killed while writing (its temporary file there)")
    r = run(cmd)
    check(r.returncode == 0 and os.path.exists(out), "import-gltf after the kill writes the scene", r.stderr[-300:])
    left = glob.glob(os.path.join(os.path.dirname(out), ".facet-*"))
    check(not left, "the rerun removed the killed run's temporary file", str(left))


def file_size_limited(kib):
    """For Popen's preexec_fn: files this process (and its children: POV-Ray) writes may not grow
    past `kib` KiB, and a write past that fails (EFBIG) instead of killing the writer, as a write
    past a full disk's end fails with ENOSPC."""
    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (kib * 1024, kib * 1024))
    return limit


def noise_png(path, side):
    """An RGB PNG of random texels: it does not compress, so its size is about 3·side² bytes."""
    rng = random.Random(28)
    raw = b"".join(b"\0" + bytes(rng.getrandbits(8) for _ in range(3 * side)) for _ in range(side))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def leftovers(*folders):
    """What a failed run must not leave: temporary files, POV-Ray's state and work folders."""
    found = []
    for folder in folders:
        for root, dirs, files in os.walk(folder):
            found += [os.path.join(root, n) for n in files if n.startswith(".facet-") or n.endswith(".pov-state")]
            found += [os.path.join(root, d) for d in dirs if d == "work"]
    return found


def full_disk(facet, work):
    folder = os.path.join(work, "full_disk")
    os.makedirs(folder)
    ward = os.path.join(REPO, "examples", "materials", "ward.json")
    before = our_tmp_folders()

    def limited(cmd, kib):
        return subprocess.run(cmd, capture_output=True, text=True, timeout=300, preexec_fn=file_size_limited(kib))

    # render -r pov: at 4 KiB facet's own scene file is too big; at 60 KiB POV-Ray's 128² image.
    for kib, says in ((4, "cannot write: File too large"), (60, "could not write its image")):
        for workdir in (None, os.path.join(folder, f"render_work_{kib}")):
            out = os.path.join(folder, f"render_{kib}_{'workdir' if workdir else 'private'}")
            os.makedirs(out)
            cmd = [facet, "render", ward, "-r", "pov", "--size", "128x128", "-o", os.path.join(out, "ward.png")]
            r = limited(cmd + (["--workdir", workdir] if workdir else []), kib)
            what = f"render -r pov at {kib} KiB{' with --workdir' if workdir else ''}"
            check(r.returncode == 1 and says in r.stderr, f"{what}: exit 1, '{says}'", r.stderr[:300])
            check(os.listdir(out) == [], f"{what}: no output, partial or whole", str(os.listdir(out)))
            if workdir:
                frames = [n for n in os.listdir(workdir) if "_frame" in n]
                check(not frames, f"{what}: no frame nor .pov-state left in the --workdir", str(frames))
            check(not leftovers(out, *( [workdir] if workdir else [])), f"{what}: no temporary file",
                  str(leftovers(out)))
    # The same render without a limit, to show the limits are what stopped it.
    out = os.path.join(folder, "render_unlimited")
    os.makedirs(out)
    r = run([facet, "render", ward, "-r", "pov", "--size", "128x128", "-o", os.path.join(out, "ward.png")])
    check(r.returncode == 0 and os.listdir(out) == ["ward.png"], "the same render without a limit writes its image",
          r.stderr[:300])

    # validate: at 20 KiB facet's POV-Ray scene fails (an error: nothing to report); at 60 KiB
    # POV-Ray's images (a FAIL row saying why, and a report of it).
    for kib in (20, 60):
        out = os.path.join(folder, f"validate_{kib}")
        os.makedirs(os.path.join(out, "images"))
        with open(os.path.join(out, "report.html"), "w") as f:
            f.write("an earlier run's report\n")
        r = limited([facet, "validate", ward, "--renderers", "reference,pov", "--size", "128x128", "--out", out], kib)
        check(r.returncode == 1, f"validate at {kib} KiB: exit 1", r.stdout[-300:] + r.stderr[-300:])
        if kib == 20:
            check("cannot write: File too large" in r.stderr, "validate at 20 KiB: says which file", r.stderr[-300:])
            check(not os.path.exists(os.path.join(out, "report.html")),
                  "validate at 20 KiB: no report left of an earlier run", str(os.listdir(out)))
        else:
            report = open(os.path.join(out, "report.html")).read() if os.path.exists(
                os.path.join(out, "report.html")) else ""
            check("could not write its image" in r.stdout + r.stderr and "could not write its image" in report,
                  "validate at 60 KiB: POV-Ray's rows FAIL saying it could not write, in the report too",
                  r.stdout[-400:] + r.stderr[-400:])
        check(not leftovers(out), f"validate at {kib} KiB: no work folder, temporary file or .pov-state",
              str(leftovers(out)))

    # sweep -r pov in a --workdir: POV-Ray's 256² image does not fit in 100 KiB.
    sweep_work = os.path.join(folder, "sweep_work")
    r = limited([facet, "sweep", ward, "--renderers", "pov", "--workdir", sweep_work], 100)
    check(r.returncode == 1 and "could not write its image" in r.stdout + r.stderr, "sweep -r pov at 100 KiB: exit 1",
          r.stdout[-300:] + r.stderr[-300:])
    left = [n for n in os.listdir(os.path.join(sweep_work, "pov")) if not n.endswith(".pov")]
    check(not left, "sweep at 100 KiB: no partial image nor .pov-state in the --workdir", str(left))

    # import-gltf: the scene fits, its 200 KiB image does not.
    source = os.path.join(folder, "gltf")
    os.makedirs(source)
    noise_png(os.path.join(source, "noise.png"), 256)
    gltf = write_json(os.path.join(source, "noise.gltf"), triangle_gltf(image_uri="noise.png"))
    out = os.path.join(folder, "import")
    os.makedirs(out)
    r = limited([facet, "import-gltf", gltf, "-o", os.path.join(out, "scene.json")], 64)
    check(r.returncode == 1 and "File too large" in r.stderr and "noise" in r.stderr,
          "import-gltf at 64 KiB: exit 1 naming the image that did not fit", r.stderr[-300:])
    check(os.listdir(out) == [], "import-gltf at 64 KiB: no scene, no image folder, no temporary file",
          str(os.listdir(out)))
    r = run([facet, "import-gltf", gltf, "-o", os.path.join(out, "scene.json")])
    check(r.returncode == 0, "the same import without a limit writes the scene", r.stderr[-300:])
    check(not (our_tmp_folders() - before), "no private work folder left by the runs on a full disk",
          str(our_tmp_folders() - before))


def main():
    facet, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # Every facet this script starts keeps its private work folder here, where no other
    # program's (a test running beside this one) can be mistaken for one of them.
    os.environ["TMPDIR"] = os.path.join(work, "tmp")
    os.makedirs(os.environ["TMPDIR"])
    for step in (uris, texture_paths, not_files, depth_and_size, validate_out, collisions, concurrency, kill_validate, kill_import,
                 full_disk):
        print(f"== {step.__name__}", flush=True)
        step(facet, work)
    left = os.listdir(os.environ["TMPDIR"])
    check(not left, "every run removed its private work folder (or the next run did, after a kill -9)", str(left))
    print(f"{len(FAILURES)} failures" if FAILURES else "all checks pass")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
