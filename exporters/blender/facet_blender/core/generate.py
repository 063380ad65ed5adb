"""What the operators ask of facet, on plain data: material files checked and written,
shaders generated.

Each function takes the facet executable and a material as its JSON (a dict, from
`props.material_to_json`) with the name the user knows it by. facet reads files, so
the material goes to a temporary folder first; facet's messages name the material,
never the temporary file (cli.error_lines' `replace`). Nothing is written to the
user's path unless facet accepted the material (cli.write_atomic, cli.generate_to).
"""

import json
import os
import re
import tempfile

from . import UserError, cli


def safe_name(name):
    """A file name from a Blender name: anything but letters, digits, `_`, `.`, `-`
    becomes `_`; "material" when nothing is left."""
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._") or "material"


def supports_normal_map(exe):
    """Whether this facet takes a Blender material's normal map: its material files have
    the "normal_map" key and its scene meshes carry "tangents" (facet schema, facet schema
    --scene); a facet with normal maps on its shapes only refuses a normal-mapped mesh."""
    schema = cli.material_schema(exe)
    if not (isinstance(schema, dict) and "normal_map" in schema.get("properties", {})):
        return False
    return "tangents" in cli.mesh_keys(cli.scene_schema(exe))


def texturable_material_keys(exe, meshes=True):
    """The material-level keys (normal_map, coat_normal_map, emission, ambient, alpha) this facet takes a
    texture on: normal_map where `supports_normal_map` (or, for a material file alone, `meshes`
    False, where the material schema has the key), the others where the material schema
    lets them be a texture object."""
    import json as json_mod
    schema = cli.material_schema(exe)
    props = schema.get("properties", {}) if isinstance(schema, dict) else {}
    keys = {k for k in ("emission", "ambient", "alpha") if "texture" in json_mod.dumps(props.get(k, {}))}
    if supports_normal_map(exe) if meshes else "normal_map" in props:
        keys.add("normal_map")
        if "coat_normal_map" in props:   # the coat's own normal map, on the same tangents
            keys.add("coat_normal_map")
    return keys


def osl_text_name(name):
    """The name of the Text that holds a material's generated OSL."""
    return f"facet_{safe_name(name)}.osl"


def write_material_temp(folder, data, name):
    """The material's JSON as `folder`/<safe name>.json; returns (path, replace map for
    facet's messages)."""
    path = os.path.join(folder, safe_name(name) + ".json")
    cli.write_atomic(path, cli.dump_json(data))
    return path, {path: f"material '{name}'"}


def check_material(exe, data, label):
    """Lets facet check a material given as data; `label` stands for its file in
    facet's messages. Raises cli.FacetError with facet's own lines."""
    with tempfile.TemporaryDirectory(prefix="facet-") as tmp:
        path = os.path.join(tmp, "material.json")
        cli.write_atomic(path, cli.dump_json(data))
        cli.validate_material(exe, path, {path: label})


def export_material(exe, data, name, path, files=None):
    """Writes the material file `path` once facet accepted `data`; `files` ({name: bytes},
    the texture images it names relatively) go beside it, written before it."""
    with tempfile.TemporaryDirectory(prefix="facet-") as tmp:
        if files:
            cli.write_all_atomic(tmp, files)
        temp, replace = write_material_temp(tmp, data, name)
        cli.validate_material(exe, temp, replace)
    cli.write_all_atomic(os.path.dirname(os.path.abspath(path)),
                         dict(files or {}, **{os.path.basename(path): cli.dump_json(data)}))


def read_material(exe, path):
    """The JSON of the material file `path` once facet accepted it (facet's own
    `error:` lines when it does not)."""
    if not os.path.isfile(path):
        raise UserError(f"no such file: {path}")
    cli.validate_material(exe, path)
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise UserError(f"cannot read {path}: {e}")


def code_to(exe, data, name, path, target, library=False, files=None):
    """`facet generate --target TARGET [--library]` of the material into `path`; the
    texture images it names relatively (`files`, {name: bytes}) are written beside it."""
    with tempfile.TemporaryDirectory(prefix="facet-") as tmp:
        if files:
            cli.write_all_atomic(tmp, files)
        temp, replace = write_material_temp(tmp, data, name)
        cli.generate_to(exe, path, [temp, "--target", target] + (["--library"] if library else []), replace)
    if files:
        cli.write_all_atomic(os.path.dirname(os.path.abspath(path)), files)


def allow_texture_folders(data):
    """`--allow-path` for each folder the material's absolute texture paths lie in: facet reads
    a material file's images inside its own folder only, and a material written to a temporary
    folder names images written elsewhere (blender/operators.py textured_material)."""
    folders = []

    def walk(node):
        if isinstance(node, dict):
            for key, value in node.items():
                if key == "texture" and isinstance(value, str) and os.path.isabs(value):
                    folder = os.path.dirname(value)
                    if folder not in folders:
                        folders.append(folder)
                else:
                    walk(value)
    walk(data)
    return [arg for folder in folders for arg in ("--allow-path", folder)]


def osl_shader(exe, data, name, scene, scene_name):
    """The OSL shader (text) of the material lit by `scene`'s lights and ambient colour
    (`facet generate --target osl --scene`)."""
    with tempfile.TemporaryDirectory(prefix="facet-") as tmp:
        temp, replace = write_material_temp(tmp, data, name)
        scene_path = os.path.join(tmp, "scene.json")
        replace[scene_path] = f"scene '{scene_name}'"
        cli.write_atomic(scene_path, cli.dump_json(scene))
        osl_path = os.path.join(tmp, "material.osl")
        cli.generate_to(exe, osl_path, [temp, "--target", "osl", "--scene", scene_path] + allow_texture_folders(data),
                        replace)
        with open(osl_path, encoding="utf-8") as f:
            return f.read()
