"""The published JSON Schemas accept every example and reject the malformed corpus.

    python check_schema.py SOURCE_DIR

Uses the `jsonschema` package (draft 2020-12), independent of facet's own
checker, so the schema a user's editor loads says what facet says.
"""
import json
import math
import os
import sys

import jsonschema


def not_json(literal):
    raise ValueError(f"{literal} is not JSON")


def finite(text):
    x = float(text)
    if not math.isfinite(x):
        raise ValueError(f"{text} is not a finite number")
    return x


def main():
    root = sys.argv[1]
    material = json.load(open(os.path.join(root, "schemas/material.schema.json")))
    scene = json.load(open(os.path.join(root, "schemas/scene.schema.json")))
    jsonschema.Draft202012Validator.check_schema(material)
    jsonschema.Draft202012Validator.check_schema(scene)
    mv = jsonschema.Draft202012Validator(material)
    failures = 0
    examples = [os.path.join(folder, name) for folder in ("examples/materials", "examples/layered")
                for name in sorted(os.listdir(os.path.join(root, folder))) if name.endswith(".json")]
    for name in examples:
        doc = json.load(open(os.path.join(root, name)))
        errors = list(mv.iter_errors(doc))
        if errors:
            failures += 1
            print(f"FAIL example {name} rejected: {errors[0].message}")
    expected = json.load(open(os.path.join(root, "tests/malformed/EXPECTED")))
    rejected = 0
    for name in sorted(expected):
        text = open(os.path.join(root, "tests/malformed", name)).read()
        try:
            doc = json.loads(text, parse_constant=not_json, parse_float=finite)
        except ValueError:
            rejected += 1  # not JSON at all: nothing to validate
            continue
        if name == "duplicate_key.json" or not any(True for _ in mv.iter_errors(doc)):
            # Python's json keeps the last duplicate, which is a valid material: facet's parser is stricter.
            if name != "duplicate_key.json":
                failures += 1
                print(f"FAIL malformed {name} accepted by the schema")
            continue
        rejected += 1
    sv = jsonschema.Draft202012Validator(scene)
    for scene_dir in ["examples/scenes"]:
        d = os.path.join(root, scene_dir)
        for name in sorted(n for n in os.listdir(d) if n.endswith(".json")) if os.path.isdir(d) else []:
            errors = list(sv.iter_errors(json.load(open(os.path.join(d, name)))))
            if errors:
                failures += 1
                print(f"FAIL scene {name} rejected: {errors[0].message}")
    # A mesh is inline arrays or a glTF reference (by mesh or by node), exactly one of them.
    camera = {"position": [0, 0, 4]}
    arrays = {"positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "normals": [[0, 0, 1]] * 3, "triangles": [[0, 1, 2]]}
    good = [dict(arrays), {"gltf": "a.glb", "node": 0}, {"gltf": "a.glb", "mesh": "m", "primitive": 1}]
    bad = [dict(arrays, gltf="a.glb", node=0), {"gltf": "a.glb"}, {"gltf": "a.glb", "node": 0, "mesh": 0},
           {"gltf": "a.glb", "node": -1}, {"gltf": "a.glb", "node": 0, "primitive": "p"}, dict(arrays, primitive=0), {}]
    for mesh in good + bad:
        doc = {"camera": camera, "objects": [dict(mesh, type="mesh")]}
        accepted = not any(True for _ in sv.iter_errors(doc))
        if accepted != (mesh in good):
            failures += 1
            print(f"FAIL scene mesh {json.dumps(mesh)} {'accepted' if accepted else 'rejected'} by the schema")
    print(f"{len(good)} mesh forms accepted, {len(bad)} mixed or incomplete ones rejected")
    print(f"{len(examples)} examples accepted, {rejected} of {len(expected)} malformed files rejected "
          f"(duplicate keys are facet's own check)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
