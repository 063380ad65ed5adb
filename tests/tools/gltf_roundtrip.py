"""glTF both ways (issue 29): a file imported by facet, written back by `facet export-gltf` and
imported again gives the same materials: every gltf_pbr parameter the same number (to 1e-6),
every map the same channel, colour space, factor, filter, wrap and texture coordinates (the image
itself is copied, its file name may change), the same emission, and the extensions glTF says
them with written.

    python gltf_roundtrip.py FACET WORK FILE [FILE …]

The export also writes facet's own FACET_material beside glTF's material, which the import would
read first and make the round trip trivially equal: it is removed from the exported file before
the second import, so the second import reads glTF's factors, maps and KHR_materials_* alone.
"""
import json
import os
import subprocess
import sys

# The extension each gltf_pbr parameter is written back as, where it differs from its default.
EXTENSION_OF = {"ior": ("KHR_materials_ior", 1.5), "specular": ("KHR_materials_specular", 1.0),
                "specular_color": ("KHR_materials_specular", [1.0, 1.0, 1.0]),
                "sheen_color": ("KHR_materials_sheen", [0.0, 0.0, 0.0]),
                "clearcoat": ("KHR_materials_clearcoat", 0.0)}


def run(*args):
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"FAIL: {' '.join(args)}\n{done.stderr}")
    return done.stderr


def comparable(value):
    """A parameter as compared: numbers to 1e-6, a map without its image's file name."""
    if isinstance(value, dict):
        return {k: comparable(v) for k, v in value.items() if k != "texture"}
    if isinstance(value, list):
        return [comparable(v) for v in value]
    if isinstance(value, float):
        return round(value, 6)
    return value


def main():
    facet, work, files = sys.argv[1], sys.argv[2], sys.argv[3:]
    failures, compared = [], 0
    for path in files:
        stem = os.path.splitext(os.path.basename(path))[0]
        first, exported, second = (os.path.join(work, stem, name) for name in ("first.json", "out/x.gltf", "second.json"))
        run(facet, "import-gltf", path, "-o", first)
        run(facet, "export-gltf", first, "-o", exported)
        gltf = json.load(open(exported))
        for m in gltf.get("materials", []):
            m.get("extensions", {}).pop("FACET_material", None)
        for key in ("extensionsUsed", "extensionsRequired"):
            if key in gltf:
                gltf[key] = [e for e in gltf[key] if e != "FACET_material"]
        glTF_only = os.path.join(work, stem, "out", "gltf_only.gltf")
        with open(glTF_only, "w") as f:
            json.dump(gltf, f)
        run(facet, "import-gltf", glTF_only, "-o", second)
        a, b = (json.load(open(p))["materials"] for p in (first, second))
        written = {m["name"]: m.get("extensions", {}) for m in gltf.get("materials", [])}
        for key, material in a.items():
            lobe = material.get("specular") or {}
            if lobe.get("model") != "gltf_pbr":
                continue
            compared += 1
            other = b.get(key, {}).get("specular")
            if comparable(lobe) != comparable(other):
                failures.append(f"{path}: material '{key}': {json.dumps(lobe)} came back as {json.dumps(other)}")
            if comparable(material.get("emission")) != comparable(b.get(key, {}).get("emission")):
                failures.append(f"{path}: material '{key}': emission {material.get('emission')} came back as "
                                f"{b.get(key, {}).get('emission')}")
            for param, (extension, default) in EXTENSION_OF.items():
                if param in lobe and comparable(lobe[param]) != default and extension not in written.get(key, {}):
                    failures.append(f"{path}: material '{key}': {param} was not written as {extension}")
            print(f"{stem}: '{key}' round-trips" + "".join(
                f", {e}" for e in sorted(written.get(key, {})) if e.startswith("KHR_")))
    if compared == 0:
        failures.append("no gltf_pbr material in the files")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
