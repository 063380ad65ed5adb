"""core/cli.py: finding and running facet, its error lines, atomic writes, JSON text."""

import json
import os

import pytest

from facet_blender.core import UserError, cli
from support import REPO, example, script


# ----------------------------------------------------------------------------- finding facet

def test_find_facet_takes_the_preferred_path(facet):
    assert cli.find_facet(facet) == facet


def test_find_facet_refuses_a_preferred_path_that_does_not_work(tmp_path, facet, monkeypatch):
    monkeypatch.setenv(cli.ENV_VAR, facet)         # a working fallback must not be used instead
    with pytest.raises(cli.FacetNotFound) as e:
        cli.find_facet(str(tmp_path / "nope" / "facet"))
    assert f"at '{tmp_path / 'nope' / 'facet'}'" in str(e.value)
    assert cli.PREFERENCES_HINT in str(e.value)


def test_find_facet_without_a_preference_uses_path_then_the_environment(tmp_path, facet, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))      # no facet on PATH
    monkeypatch.setenv(cli.ENV_VAR, facet)
    assert cli.find_facet("") == facet
    assert cli.default_facet_path() == facet
    monkeypatch.delenv(cli.ENV_VAR)
    with pytest.raises(cli.FacetNotFound) as e:
        cli.find_facet("")
    assert "not on PATH" in str(e.value) and cli.PREFERENCES_HINT in str(e.value)
    on_path = script(tmp_path / "facet", "exit 0\n")
    assert cli.find_facet("") == on_path
    assert cli.find_facet("facet") == on_path      # a bare command name


# ----------------------------------------------------------------------------- running facet

def test_error_lines_keep_facets_own_lines_and_name_what_the_user_knows():
    stderr = "note: reading\nerror: /tmp/x/M.json: specular.alpha: out of range\n\nerror: /tmp/x/M.json: second\n"
    assert cli.error_lines(stderr, {"/tmp/x/M.json": "material 'M'"}) == [
        "error: material 'M': specular.alpha: out of range", "error: material 'M': second"]
    assert cli.error_lines("\n".join(f"line {i}" for i in range(20))) == [f"line {i}" for i in range(10, 20)]


def test_run_raises_facets_errors(facet):
    bad = os.path.join(REPO, "tests", "malformed", "unknown_model.json")
    with pytest.raises(cli.FacetError) as e:
        cli.run(facet, ["generate", bad, "--target", "glsl"], replace={bad: "material 'bad'"})
    assert e.value.lines and all(line.startswith("error: material 'bad'") for line in e.value.lines)
    assert bad not in str(e.value)


def test_run_reports_an_executable_that_cannot_run(tmp_path):
    with pytest.raises(cli.FacetNotFound, match="no such file"):
        cli.run(str(tmp_path / "missing"), ["models"])
    plain = tmp_path / "plain"
    plain.write_text("not a program")
    with pytest.raises(cli.FacetNotFound, match="not executable"):
        cli.run(str(plain), ["models"])


def test_run_json_refuses_text_that_is_not_json(tmp_path):
    fake = script(tmp_path / "facet", "echo 'facet 0.0 says hello'\n")
    with pytest.raises(cli.FacetError, match="printed no valid JSON"):
        cli.models(fake)


def test_schemas_and_models_are_facets(facet):
    assert "sections" in cli.models(facet)
    assert "properties" in cli.material_schema(facet)
    assert cli.scene_support(cli.scene_schema(facet)) == (True, True)


def test_scene_support_reads_materials_and_mesh_objects_anywhere_in_the_schema():
    mesh = {"properties": {"type": {"const": "mesh"}}}
    assert cli.scene_support({"properties": {"materials": {}, "objects": {"items": {"oneOf": [mesh]}}}}) == (True, True)
    sphere = {"properties": {"type": {"enum": ["sphere", "plane"]}}}
    assert cli.scene_support({"properties": {"objects": {"items": sphere}}}) == (False, False)
    assert cli.scene_support("not a schema") == (False, False)


def test_validate_material_accepts_every_example(facet):
    for name in sorted(os.listdir(example("materials"))):
        cli.validate_material(facet, example("materials", name))


# ----------------------------------------------------------------------------- writing files

def test_write_atomic_writes_text_and_bytes_with_ordinary_permissions(tmp_path):
    path = tmp_path / "a.json"
    cli.write_atomic(str(path), "héllo\n")
    assert path.read_bytes() == "héllo\n".encode("utf-8")
    cli.write_atomic(str(path), b"\x00\x01")
    assert path.read_bytes() == b"\x00\x01"
    umask = os.umask(0)
    os.umask(umask)
    assert os.stat(path).st_mode & 0o777 == 0o666 & ~umask
    assert os.listdir(tmp_path) == ["a.json"]


def test_write_atomic_into_a_missing_folder_says_so(tmp_path):
    with pytest.raises(UserError, match="does not exist"):
        cli.write_atomic(str(tmp_path / "no" / "a.json"), "x")


def test_generate_to_keeps_the_old_file_when_facet_refuses(tmp_path, facet):
    out = tmp_path / "m.frag"
    out.write_text("previous\n")
    bad = os.path.join(REPO, "tests", "malformed", "unknown_model.json")
    with pytest.raises(cli.FacetError):
        cli.generate_to(facet, str(out), [bad, "--target", "glsl"])
    assert out.read_text() == "previous\n"
    assert os.listdir(tmp_path) == ["m.frag"]
    cli.generate_to(facet, str(out), [example("materials", "lambert.json"), "--target", "glsl"])
    assert out.read_text().startswith("#version 330 core")


def test_generate_to_hands_facets_description_over_before_the_file_is_moved(tmp_path, facet):
    out = tmp_path / "l.pov"
    seen = []
    got = cli.generate_to(facet, str(out), [example("materials", "lambert.json"), "--target", "pov"],
                          describe=lambda d: seen.append(d) or "result")
    assert got == "result" and out.exists()
    assert seen[0]["target"] == "pov" and seen[0]["pov"]["passes"] == 1
    assert "code" not in seen[0]                   # written to the file, not printed

    out.write_text("previous\n")

    def refuse(description):
        raise UserError("refused")
    with pytest.raises(UserError, match="refused"):
        cli.generate_to(facet, str(out), [example("materials", "ggx.json"), "--target", "pov"], describe=refuse)
    assert out.read_text() == "previous\n"
    assert os.listdir(tmp_path) == ["l.pov"]


def test_generate_to_names_a_facet_without_json(tmp_path):
    # What CLI11 prints for an option an older facet does not know.
    old = script(tmp_path / "facet", "echo 'The following argument was not expected: --json' >&2\n"
                                     "echo 'Run with --help for more information.' >&2\nexit 109\n")
    out = tmp_path / "s.pov"
    with pytest.raises(cli.FacetError) as e:
        cli.generate_to(old, str(out), ["--target", "pov"], describe=lambda d: d)
    assert "has no 'generate --json'" in str(e.value) and "update facet" in str(e.value)
    assert not out.exists()


# ----------------------------------------------------------------------------- JSON text

def test_dump_json_is_written_as_facets_files_are():
    data = {"name": "ü", "color": [0.5, 0.25, 1.0], "lobe": {"model": "ggx", "f0": [0.04, 0.04, 0.04]},
            "positions": [[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]], "empty": {}}
    text = cli.dump_json(data)
    assert json.loads(text) == data
    assert text.endswith("}\n")
    assert '  "color": [0.5, 0.25, 1.0],\n' in text          # a colour on one line
    assert '    [0.0, 1.0, 2.0],\n' in text                 # a mesh's positions one per line
    assert '"ü"' in text                                     # UTF-8, not \u escapes
