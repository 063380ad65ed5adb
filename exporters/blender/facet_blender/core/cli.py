"""Finding and running the facet executable, and writing files atomically.

Everything the add-on knows about materials comes from this executable: the catalog
(`facet models --json`), the file formats (`facet schema`, `facet schema --scene`) and
the generated code (`facet generate`). A failing facet command exits 1 and prints
`error: FILE: key.path: message` lines on stderr; `FacetError` carries those lines.
"""

import contextlib
import json
import os
import shutil
import subprocess
import tempfile

from . import UserError

# Where the user can set the path (shown in every "not found" message).
PREFERENCES_HINT = "Edit > Preferences > Add-ons > facet > facet executable"
ENV_VAR = "FACET_BIN"

# Seconds; generous because a big scene or a POV-Ray render can take a while.
TIMEOUT_QUICK = 60
TIMEOUT_GENERATE = 600


class FacetNotFound(UserError):
    """No usable facet executable."""


ERROR_PREFIX = "error: "


def without_prefix(line):
    """facet's line without its `error: ` prefix: Blender prefixes an error report with
    "Error: " itself, and "Error: error: ..." says it twice."""
    return line[len(ERROR_PREFIX):] if line.startswith(ERROR_PREFIX) else line


class FacetError(UserError):
    """facet ran and refused: `lines` are its own `error: ...` lines; the message is
    those lines without the prefix (`without_prefix`)."""

    def __init__(self, lines, command=""):
        self.lines = list(lines)
        self.command = command
        super().__init__("\n".join(without_prefix(line) for line in self.lines) or f"facet failed: {command}")


def _is_executable(path):
    return bool(path) and os.path.isfile(path) and os.access(path, os.X_OK)


def default_facet_path():
    """The preference's default: facet on PATH, else $FACET_BIN, else ''."""
    return shutil.which("facet") or os.environ.get(ENV_VAR, "")


def find_facet(preferred=""):
    """The facet executable to run.

    `preferred` is the path set in the add-on's preferences. When it is set it must
    work (the user chose it; silently running another facet would be confusing);
    when it is empty, facet on PATH, then $FACET_BIN, are tried."""
    preferred = os.path.expanduser(preferred or "")
    if preferred:
        if _is_executable(preferred):
            return preferred
        found = shutil.which(preferred)  # a bare command name such as "facet"
        if found:
            return found
        raise FacetNotFound(
            f"facet executable not found at '{preferred}': "
            f"set the path of facet in {PREFERENCES_HINT}")
    for candidate in (shutil.which("facet"), os.environ.get(ENV_VAR, "")):
        if _is_executable(candidate):
            return candidate
    raise FacetNotFound(
        f"facet executable not found (not on PATH, ${ENV_VAR} not set): "
        f"set the path of facet in {PREFERENCES_HINT}")


def error_lines(stderr, replace=None):
    """facet's `error: ...` lines (all of stderr when there are none).

    `replace` maps strings to substitute, e.g. a temporary file's path to the name of
    the material it holds, so messages name what the user knows."""
    lines = [line.strip() for line in stderr.splitlines() if line.strip()]
    errors = [line for line in lines if line.startswith("error:")] or lines[-10:]
    for old, new in (replace or {}).items():
        errors = [line.replace(old, new) for line in errors]
    return errors


def run(exe, args, timeout=TIMEOUT_GENERATE, replace=None, stdout=True):
    """Runs `exe args...`; returns its stdout (text), raises FacetError on failure."""
    command = [exe] + [str(a) for a in args]
    try:
        proc = subprocess.run(command, stdout=subprocess.PIPE if stdout else subprocess.DEVNULL,
                              stderr=subprocess.PIPE, timeout=timeout, text=True,
                              encoding="utf-8", errors="replace")
    except FileNotFoundError:
        raise FacetNotFound(f"cannot run '{exe}': no such file; set the path in {PREFERENCES_HINT}")
    except PermissionError:
        raise FacetNotFound(f"cannot run '{exe}': not executable; set the path in {PREFERENCES_HINT}")
    except OSError as e:
        raise FacetNotFound(f"cannot run '{exe}': {e}")
    except subprocess.TimeoutExpired:
        raise FacetError([f"error: '{' '.join(command)}' took more than {timeout} s"], " ".join(command))
    if proc.returncode != 0:
        raise FacetError(error_lines(proc.stderr, replace), " ".join(command))
    return proc.stdout if stdout else ""


def _parse_json(text, exe, args):
    try:
        return json.loads(text)
    except ValueError as e:
        raise FacetError([f"error: '{exe} {' '.join(str(a) for a in args)}' printed no valid JSON ({e}); "
                          f"is '{exe}' really facet?"])


def run_json(exe, args):
    """Runs a facet command that prints JSON, returns the parsed object."""
    return _parse_json(run(exe, args, timeout=TIMEOUT_QUICK), exe, args)


def models(exe):
    """`facet models --json`: the whole catalog."""
    return run_json(exe, ["models", "--json"])


def material_schema(exe):
    """`facet schema`: the JSON Schema of material files."""
    return run_json(exe, ["schema"])


def scene_schema(exe):
    """`facet schema --scene`: the JSON Schema of scene files."""
    return run_json(exe, ["schema", "--scene"])


def scene_support(schema):
    """Whether a scene schema has scene-level materials and mesh objects.

    Returns (has_materials, has_meshes). Both are needed to export a whole Blender
    scene (every object with its own material) to POV-Ray."""
    props = schema.get("properties", {}) if isinstance(schema, dict) else {}
    return "materials" in props, "mesh" in _object_types(props.get("objects", {}))


def mesh_keys(schema):
    """The keys a scene schema allows on a mesh (the objects whose properties have
    "texcoords"), merged over its variants."""
    found = set()

    def walk(node):
        if isinstance(node, dict):
            props = node.get("properties")
            if isinstance(props, dict) and "texcoords" in props:
                found.update(props)
            for value in node.values():
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)
    walk(schema)
    return found


def _object_types(node):
    """Every value a `"type": {"const": ...}` (or enum) allows anywhere under `node`."""
    found = set()
    if isinstance(node, dict):
        kind = node.get("properties", {}).get("type") if isinstance(node.get("properties"), dict) else None
        if isinstance(kind, dict):
            if "const" in kind:
                found.add(kind["const"])
            found.update(kind.get("enum", []))
        for value in node.values():
            found |= _object_types(value)
    elif isinstance(node, list):
        for value in node:
            found |= _object_types(value)
    return found


def validate_material(exe, path, replace=None):
    """Lets facet check a material file (by generating GLSL and discarding it)."""
    run(exe, ["generate", path, "--target", "glsl"], replace=replace, stdout=False)


# ----------------------------------------------------------------------------- files

def temp_path_beside(path):
    """A fresh temporary file name in the folder of `path` (same file system, so
    os.replace onto `path` is atomic). The file exists (empty); the caller removes it."""
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp", dir=folder)
    os.close(fd)
    return tmp


def _give_ordinary_permissions(path):
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(path, 0o666 & ~umask)  # mkstemp makes 0600


def write_atomic(path, data):
    """Writes text or bytes to `path` whole or not at all (temporary file + os.replace)."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise UserError(f"cannot write '{path}': folder '{folder}' does not exist")
    try:
        tmp = temp_path_beside(path)
    except OSError as e:
        raise UserError(f"cannot write '{path}': {e.strerror or e}")
    try:
        with open(tmp, "wb") as f:
            f.write(data)
        _give_ordinary_permissions(tmp)
        os.replace(tmp, path)
    except OSError as e:
        raise UserError(f"cannot write '{path}': {e.strerror or e}")
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_all_atomic(folder, files):
    """Writes {file name: bytes} into `folder`: every file first to a temporary name beside
    it, then all renamed in the order given (put the file that names the others last).
    When a write fails, nothing is renamed and the temporaries are removed."""
    if not os.path.isdir(folder):
        raise UserError(f"cannot write into '{folder}': the folder does not exist")
    staged = []
    try:
        for name, data in files.items():
            target = os.path.join(folder, name)
            tmp = temp_path_beside(target)
            staged.append((tmp, target))
            with open(tmp, "wb") as f:
                f.write(data.encode("utf-8") if isinstance(data, str) else data)
            _give_ordinary_permissions(tmp)
        for tmp, target in staged:
            os.replace(tmp, target)
    except OSError as e:
        raise UserError(f"cannot write into '{folder}': {e.strerror or e}")
    finally:
        for tmp, _ in staged:
            if os.path.exists(tmp):
                os.remove(tmp)


def generate_to(exe, path, args, replace=None, describe=None):
    """Runs `facet generate ... -o TMP/NAME` and moves what it wrote onto `path` (and,
    for a POV-Ray scene whose meshes read data images, those beside it) when facet
    succeeds.

    facet itself writes whole-or-nothing; the temporary folder beside `path` (same
    file system, so each move is atomic, and the same file names, which a POV-Ray
    scene refers to its data images by) also keeps a previous `path` intact when
    facet fails.

    With `describe` (a function of one argument), facet is also asked what it
    generated (`facet generate --json`: {"target", "output", "pov": {...}}) and
    `describe(that object)` runs before anything is moved: when it raises, `path`
    stays as it was. Its result is returned.

    `replace` maps the temporary files facet reads to what the user knows them by, in
    facet's messages and in the header of what it wrote (`name_sources`)."""
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise UserError(f"cannot write '{path}': folder '{folder}' does not exist")
    tmp_dir = tempfile.mkdtemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp", dir=folder)
    tmp = os.path.join(tmp_dir, os.path.basename(path))
    command = ["generate"] + list(args) + (["--json"] if describe else []) + ["-o", tmp]
    try:
        try:
            out = run(exe, command, replace=replace, stdout=describe is not None)
        except FacetError as e:
            # CLI11's words for an option it does not know: "... argument was not expected: --json"
            if describe and any("not expected" in line and "--json" in line for line in e.lines):
                raise FacetError([f"error: this facet ('{exe}') has no 'generate --json', which the add-on "
                                  f"needs: it is older than the add-on; update facet"], e.command)
            raise
        result = describe(_parse_json(out, exe, command)) if describe else None
        name_sources(tmp, replace)
        _move_all(tmp_dir, folder, os.path.basename(path))
    finally:
        shutil.rmtree(tmp_dir, ignore_errors=True)
    return result


HEADER_LINES = 20      # lines before facet's header comment (#version, precision) at most


def name_sources(path, replace):
    """facet's header names the files it read ("Generated by facet V from FILE."); those
    the add-on wrote to a temporary folder, gone once the export is done, are named in the
    generated file's first comment block (after `#version` and `precision` lines) as
    `replace` names them in messages (e.g. "scene 'Scene'"). Nothing past that block is
    touched."""
    if not replace:
        return
    with open(path, "rb") as f:
        data = f.read()
    end, comments, lines = 0, False, 0
    while end < len(data) and (comments or lines < HEADER_LINES):   # up to the end of the first comment block
        nl = data.find(b"\n", end)
        line_end = len(data) if nl < 0 else nl + 1
        line = data[end:line_end].strip()
        if line.startswith(b"//"):
            comments = True
        elif line and comments:
            break
        end, lines = line_end, lines + 1
    head = data[:end]
    for old, new in replace.items():
        head = head.replace(old.encode("utf-8"), new.encode("utf-8"))
    if head != data[:end]:
        with open(path, "wb") as f:
            f.write(head + data[end:])


def _move_all(tmp_dir, folder, last):
    """Moves the files of `tmp_dir` into `folder`, the one named `last` last (a scene
    that names the others never names a missing file)."""
    for name in sorted(os.listdir(tmp_dir), key=lambda n: n == last):
        if os.path.isfile(os.path.join(tmp_dir, name)):
            _give_ordinary_permissions(os.path.join(tmp_dir, name))
            os.replace(os.path.join(tmp_dir, name), os.path.join(folder, name))


@contextlib.contextmanager
def staged(path):
    """A temporary folder beside `path` (same file system) for everything one export
    writes: `path`'s file and the files beside it, by the same names. When the block ends
    without an exception they are moved beside `path` (`path`'s file last); otherwise the
    folder is removed and nothing beside `path` has changed (a previous export stays
    whole)."""
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise UserError(f"cannot write '{path}': folder '{folder}' does not exist")
    try:
        tmp_dir = tempfile.mkdtemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp", dir=folder)
    except OSError as e:
        raise UserError(f"cannot write into '{folder}': {e.strerror or e}")
    try:
        yield tmp_dir
        try:
            _move_all(tmp_dir, folder, os.path.basename(path))
        except OSError as e:
            raise UserError(f"cannot write into '{folder}': {e.strerror or e}")
    finally:
        shutil.rmtree(tmp_dir, ignore_errors=True)


def _is_scalar(v):
    return v is None or isinstance(v, (bool, int, float, str))


def _format(value, depth):
    pad, inner = "  " * depth, "  " * (depth + 1)
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = [f"{inner}{json.dumps(k, ensure_ascii=False)}: {_format(v, depth + 1)}" for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, (list, tuple)):
        if all(_is_scalar(v) for v in value):           # [r, g, b], [x, y, z]: one line
            return json.dumps(list(value), ensure_ascii=False)
        return "[\n" + ",\n".join(inner + _format(v, depth + 1) for v in value) + "\n" + pad + "]"
    return json.dumps(value, ensure_ascii=False)


def dump_json(data):
    """JSON text as facet's own files are written: two-space indent, a vector or colour
    on one line (a mesh's positions one per line), UTF-8, final newline."""
    return _format(data, 0) + "\n"
