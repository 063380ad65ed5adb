"""core/pov.py: the Plan facet gives with a POV-Ray scene, 16-bit PPM in, 16-bit PNG out."""

import json
import os
import re
import struct

import pytest

from facet_blender.core import UserError, cli, pov
from support import example, read_png, script


def three_meshes():
    with open(example("scenes", "three_meshes.json"), encoding="utf-8") as f:
        return json.load(f)


def declared_passes(path):
    """What the .pov declares for people (the add-on itself never reads it)."""
    with open(path, encoding="utf-8") as f:
        return int(re.search(r"^#declare Facet_Passes = (\d+);", f.read(), re.MULTILINE).group(1))


# ----------------------------------------------------------------------------- the Plan

def test_plan_of_facets_description():
    assert pov.plan_of({"target": "pov", "output": "a.pov",
                        "pov": {"passes": 3, "native": False, "reason": "meshes"}}) == pov.Plan(3, False, "meshes")
    assert pov.plan_of({"pov": {"passes": 1, "native": True, "reason": ""}}) == pov.Plan(1, True, "")


@pytest.mark.parametrize("description", [
    {"target": "pov", "output": "a.inc"},                                  # --library: no "pov"
    {"pov": {"passes": 0, "native": True}}, {"pov": {"passes": True, "native": True}},
    {"pov": {"passes": 2.0, "native": False}}, {"pov": {"passes": 2}}, {"pov": "3"}, [], None])
def test_plan_of_refuses_anything_else(description):
    with pytest.raises(UserError, match="did not say how to render"):
        pov.plan_of(description)


def test_generate_scene_returns_facets_plan_and_writes_the_scene(tmp_path, facet):
    out = tmp_path / "three.pov"
    plan = pov.generate_scene(facet, three_meshes(), "three", str(out))
    # GGX, Oren–Nayar, Ward: function pigments, one pass per light (two lights) and one for the emission/ambient
    # term; each mesh's geometry in a data image beside the scene, named after it
    assert plan.native is False and "not a POV-Ray finish" in plan.reason
    assert plan.passes == declared_passes(out) == 3
    assert sorted(os.listdir(tmp_path)) == ["three.pov"] + sorted(f"three_mesh{i}.{x}" for i in range(4) for x in ("inc", "ppm"))
    assert all(f'ppm "three_mesh{i}.ppm"' in out.read_text() for i in range(4))


def test_generate_scene_of_native_spheres_is_one_run(tmp_path, facet):
    data = three_meshes()
    data["materials"] = {"plain": {"name": "plain", "diffuse": {"model": "lambert", "color": [0.5, 0.5, 0.5]}}}
    data["objects"] = [{"type": "sphere", "name": "s", "center": [0, 0, 0], "radius": 1, "material": "plain"}]
    plan = pov.generate_scene(facet, data, "spheres", str(tmp_path / "s.pov"))
    assert plan == pov.Plan(1, True, "")
    assert declared_passes(tmp_path / "s.pov") == 1


def test_generate_scene_refused_names_the_scene_and_keeps_the_old_file(tmp_path, facet):
    out = tmp_path / "three.pov"
    out.write_text("previous\n")
    data = three_meshes()
    data["lights"][0]["color"] = "bright"
    with pytest.raises(cli.FacetError) as e:
        pov.generate_scene(facet, data, "Three", str(out))
    assert "scene 'Three'" in str(e.value) and "lights[0].color" in str(e.value)
    assert out.read_text() == "previous\n"
    assert os.listdir(tmp_path) == ["three.pov"]


def test_generate_scene_with_a_facet_that_describes_nothing(tmp_path):
    # A facet that accepts --json but prints no "pov" object: refused, nothing written.
    fake = script(tmp_path / "facet", 'for a; do o="$a"; done; echo x > "$o"; echo \'{"target": "pov"}\'\n')
    out = tmp_path / "s.pov"
    with pytest.raises(UserError, match="did not say how to render"):
        pov.generate_scene(fake, three_meshes(), "s", str(out))
    assert not out.exists() and sorted(os.listdir(tmp_path)) == ["facet"]


def test_require_scene_support(tmp_path, facet):
    pov.require_scene_support(facet)
    old = script(tmp_path / "facet", "echo '{\"properties\": {\"objects\": {}}}'\n")
    with pytest.raises(UserError, match="facet lacks scene materials/meshes"):
        pov.require_scene_support(old)


# ----------------------------------------------------------------------------- images

def ppm(path, width, height, samples, comment=b"# Software: POV-Ray\n"):
    with open(path, "wb") as f:
        f.write(b"P6\n" + comment + b"%d %d\n65535\n" % (width, height) + struct.pack(f">{len(samples)}H", *samples))
    return str(path)


def test_ppm_passes_add_up_clipped_into_a_16_bit_png(tmp_path):
    w, h = 3, 2
    a = [0, 1, 2, 65535, 40000, 3, 7, 8, 9, 100, 200, 300, 65000, 1000, 0, 5, 6, 7]
    b = [1, 1, 1, 1, 30000, 0, 0, 0, 0, 1, 2, 3, 1000, 0, 0, 0, 0, 65535]
    images = []
    for k, samples in enumerate((a, b)):
        got_w, got_h, got = pov.read_ppm16(ppm(tmp_path / f"pass{k}.ppm", w, h, samples))
        assert (got_w, got_h, list(got)) == (w, h, samples)
        images.append(got)
    total = pov.add_clipped(images)
    assert list(total) == [min(x + y, 65535) for x, y in zip(a, b)]
    png = tmp_path / "sum.png"
    png.write_bytes(pov.png16(w, h, total))
    assert read_png(str(png)) == (w, h, 16, list(total))
    assert b"gAMA" in png.read_bytes()                       # marked linear


def test_read_ppm16_refuses_other_images(tmp_path):
    path = tmp_path / "8bit.ppm"
    path.write_bytes(b"P6\n2 1\n255\n" + bytes(6))
    with pytest.raises(UserError, match="not a 16-bit binary PPM"):
        pov.read_ppm16(str(path))
    short = ppm(tmp_path / "short.ppm", 2, 2, [1, 2, 3])
    with pytest.raises(UserError, match="truncated"):
        pov.read_ppm16(short)
