"""core/scene.py: cameras, lights (units), meshes (split normals, windings), the scene JSON."""

import math
import os
import re

import pytest

from facet_blender.core import UserError, pov, scene
from facet_blender.core.coords import to_blender

IDENTITY = [[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]]


def translated(x, y, z, m=IDENTITY):
    return [row[:3] + [t] for row, t in zip(m[:3], (x, y, z))] + [[0, 0, 0, 1.0]]


def rot_x(angle, at=(0.0, 0.0, 0.0)):
    c, s = math.cos(angle), math.sin(angle)
    return [[1.0, 0, 0, at[0]], [0, c, -s, at[1]], [0, s, c, at[2]], [0, 0, 0, 1.0]]


# ----------------------------------------------------------------------------- camera

def test_render_size():
    assert scene.render_size(1920, 1080, 50) == (960, 540)
    assert scene.render_size(33, 17, 100) == (33, 17)
    assert scene.render_size(3, 3, 1) == (1, 1)


@pytest.mark.parametrize("fit, w, h, sensor_w, sensor_h, lens, half_tan", [
    ("AUTO", 64, 32, 36.0, 24.0, 35.0, 0.5 * 36 / 35 * 32 / 64),       # wide: the sensor width spans the width
    ("AUTO", 32, 64, 36.0, 24.0, 35.0, 0.5 * 36 / 35),                 # tall: it spans the height
    ("HORIZONTAL", 40, 30, 30.0, 20.0, 42.0, 0.5 * 30 / 42 * 30 / 40),
    ("VERTICAL", 40, 30, 30.0, 20.0, 42.0, 0.5 * 20 / 42)])            # the sensor height spans the height
def test_vertical_fov_follows_blenders_sensor_fit(fit, w, h, sensor_w, sensor_h, lens, half_tan):
    fov = scene.vertical_fov(lens, sensor_w, sensor_h, fit, w, h)
    assert fov == pytest.approx(math.degrees(2 * math.atan(half_tan)), abs=1e-12)


def camera_desc(**kw):
    desc = {"name": "Cam", "type": "PERSP", "matrix": rot_x(math.pi / 2, (0.0, -5.0, 1.0)), "lens": 50.0,
            "sensor_width": 36.0, "sensor_height": 24.0, "sensor_fit": "AUTO", "width": 32, "height": 32}
    desc.update(kw)
    return desc


def test_camera_looks_down_its_local_minus_z_in_facets_axes():
    # Rotated 90° about X, a Blender camera looks along +Y with +Z up.
    cam, notes = scene.camera(camera_desc())
    assert not notes
    assert cam["position"] == pytest.approx([0.0, 1.0, 5.0])
    assert [a - b for a, b in zip(cam["look_at"], cam["position"])] == pytest.approx([0.0, 0.0, -1.0])
    assert cam["up"] == pytest.approx([0.0, 1.0, 0.0])
    assert cam["fov"] == pytest.approx(math.degrees(2 * math.atan(0.5 * 36 / 50)))


def test_camera_notes_and_refusals():
    _, notes = scene.camera(camera_desc(shift_x=0.1, pixel_aspect_x=2.0))
    assert any("shift" in n for n in notes) and any("pixel aspect" in n for n in notes)
    with pytest.raises(UserError, match="perspective and orthographic cameras"):
        scene.camera(camera_desc(type="PANO"))


def test_orthographic_scale_spans_the_fitted_axis():
    # Orthographic Scale spans the longer side (AUTO) or the side the sensor fit names; facet's
    # height is the vertical extent.
    wide = scene.camera(camera_desc(type="ORTHO", ortho_scale=6.0, width=64, height=32))[0]
    assert wide["type"] == "orthographic" and wide["height"] == pytest.approx(3.0) and "fov" not in wide
    tall = scene.camera(camera_desc(type="ORTHO", ortho_scale=6.0, width=32, height=64))[0]
    assert tall["height"] == pytest.approx(6.0)
    fixed = scene.camera(camera_desc(type="ORTHO", ortho_scale=6.0, width=64, height=32, sensor_fit="VERTICAL"))[0]
    assert fixed["height"] == pytest.approx(6.0)


def test_default_camera_is_the_catalogs(catalog):
    cam = scene.default_camera(catalog)
    assert set(cam) == {p.name for p in catalog.model("camera", "perspective").params}
    assert all(v is not None for v in cam.values())


# ----------------------------------------------------------------------------- lights

def light_desc(kind, **kw):
    desc = {"name": "L", "type": kind, "matrix": translated(1.0, 2.0, 3.0), "color": [1.0, 0.5, 0.25],
            "energy": 100.0}
    desc.update(kw)
    return desc


def test_point_light_units():
    light, notes = scene.light(light_desc("POINT"))
    k = 100.0 / (4 * math.pi ** 2)
    assert not notes
    assert light == {"type": "point", "position": [1.0, 3.0, -2.0],
                     "color": pytest.approx([k, k / 2, k / 4]), "attenuation": "inverse_square"}


def test_sun_light_points_along_its_local_minus_z():
    s = math.radians(30)
    light, _ = scene.light(light_desc("SUN", matrix=rot_x(s), energy=3.0))
    assert light["type"] == "directional"
    assert light["direction"] == pytest.approx([0.0, -math.cos(s), -math.sin(s)])   # Blender (0, sin, −cos)
    assert light["color"] == pytest.approx([3.0 / math.pi, 1.5 / math.pi, 0.75 / math.pi])


@pytest.mark.parametrize("version, exponent", [((3, 4, 1), 1.0), ((3, 5, 0), 0.0), ((4, 5, 15), 0.0)])
def test_spot_light_cutoff_and_exponent_per_blender(version, exponent):
    light, notes = scene.light(light_desc("SPOT", spot_size=math.radians(60), spot_blend=0.0), version)
    assert not notes
    assert list(light) == ["type", "position", "direction", "cutoff", "exponent", "color", "attenuation"]
    assert light["cutoff"] == pytest.approx(30.0) and light["exponent"] == exponent


def test_light_approximations_are_noted():
    _, notes = scene.light(light_desc("POINT", shadow_soft_size=0.25, use_nodes=True))
    assert any("radius" in n for n in notes) and any("node tree" in n for n in notes)
    light, notes = scene.light(light_desc("SPOT", spot_size=math.radians(179.9999), spot_blend=0.2))
    assert light["cutoff"] == scene.SPOT_MAX_CUTOFF
    assert any("blend" in n for n in notes) and any("reaches 180" in n for n in notes)
    light, notes = scene.light(light_desc("AREA"))
    assert light is None and "skipped" in notes[0]


def resolve_driver_path(desc, path):
    """The value a driver variable's RNA path reads on the light object `desc` describes."""
    found = re.fullmatch(r"matrix_world\[(\d)\]\[(\d)\]", path)
    if found:                                  # RNA's matrix_world[c][r]: column c, row r
        return desc["matrix"][int(found.group(2))][int(found.group(1))]
    found = re.fullmatch(r"data\.(\w+)(?:\[(\d)\])?", path)
    value = desc[found.group(1)]
    return value[int(found.group(2))] if found.group(2) is not None else value


SIMPLE_EXPRESSION = re.compile(r"[a-z][a-z_]*|[0-9.e+-]+|[-+*/(), ]")


@pytest.mark.parametrize("kind, settings", [
    ("POINT", {}), ("SUN", {"energy": 2.5}), ("SPOT", {"spot_size": math.radians(70)}),
    ("SPOT", {"spot_size": math.radians(180)})])
def test_light_drivers_compute_what_light_exports(kind, settings):
    """Each driven Script-node input equals light()'s value read back in Blender's axes,
    for a rotated, scaled and moved light: the drivers are the export's conversion."""
    m = rot_x(0.7, at=(1.5, -2.0, 3.25))
    m = [[m[0][0], m[0][1], 2.0 * m[0][2], m[0][3]], [m[1][0], m[1][1], 2.0 * m[1][2], m[1][3]],
         [m[2][0], m[2][1], 2.0 * m[2][2], m[2][3]], m[3]]          # scaled ×2 along local z
    desc = light_desc(kind, matrix=m, color=[0.9, 0.5, 0.125], **settings)
    light, _ = scene.light(desc)
    drivers = scene.light_drivers(kind, 3)
    expected_keys = {"position", "direction", "cutoff", "color"} & set(light)
    assert set(drivers) == {f"light3_{k}" for k in expected_keys}
    for key in expected_keys:
        want = light[key]
        want = to_blender(want) if key in ("position", "direction") else want
        want = want if isinstance(want, list) else [want]
        got = []
        for expression, variables in drivers[f"light3_{key}"]:
            assert "".join(SIMPLE_EXPRESSION.findall(expression)) == expression
            names = set(re.findall(r"[a-z_]+", expression)) - set(variables)
            assert names <= set(scene.DRIVER_FUNCTIONS), f"{expression}: {names}"
            values = {v: resolve_driver_path(desc, p) for v, p in variables.items()}
            got.append(eval(expression, {"__builtins__": {}}, dict(scene.DRIVER_FUNCTIONS, **values)))
        assert got == pytest.approx(want, rel=1e-12, abs=1e-12), key
    assert scene.light_drivers("AREA", 0) == {}


# ----------------------------------------------------------------------------- meshes

def test_triangle_corners_take_split_normals_on_smooth_faces_and_the_face_normal_on_flat_ones():
    # Two triangles of face 0 (smooth) and one of face 1 (flat).
    verts, loops, polys = [0, 1, 2, 0, 2, 3, 4, 5, 6], [0, 1, 2, 0, 2, 3, 4, 5, 6], [0, 0, 1]
    corner = [float(i) for i in range(21)]
    smooth, face = [True, False], [0.0, 0.0, 1.0, 0.0, 1.0, 0.0]
    tris, normals = scene.triangle_corners(verts, loops, polys, corner, smooth, face)
    assert tris == [(0, 1, 2), (0, 2, 3), (4, 5, 6)]
    assert normals[1] == ((0.0, 1.0, 2.0), (6.0, 7.0, 8.0), (9.0, 10.0, 11.0))
    assert normals[2] == ((0.0, 1.0, 0.0),) * 3


def test_mesh_normals_go_through_the_inverse_transpose():
    m = [[2.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1]]
    nrm = [0.6, 0.8, 0.0]
    (obj,) = scene.mesh_objects("t", m, [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2)], [(nrm, nrm, nrm)], ["x"])
    n = math.hypot(0.3, 0.8)
    assert obj["normals"][0] == pytest.approx([0.3 / n, 0.0, -0.8 / n])        # facet axes
    assert obj["positions"][1] == [2.0, 0.0, 0.0]


def counter_clockwise(obj):
    for tri in obj["triangles"]:
        a, b, c = (obj["positions"][i] for i in tri)
        n = [sum(obj["normals"][i][k] for i in tri) for k in range(3)]
        e1, e2 = [b[k] - a[k] for k in range(3)], [c[k] - a[k] for k in range(3)]
        cr = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        if sum(x * y for x, y in zip(cr, n)) <= 0:
            return False
    return True


def test_a_mirroring_matrix_reverses_the_winding():
    positions, tris, up = [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2)], (0.0, 0.0, 1.0)
    (plain,) = scene.mesh_objects("p", IDENTITY, positions, tris, [(up, up, up)], ["x"])
    mirror = [[-1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1]]
    (mirrored,) = scene.mesh_objects("m", mirror, positions, tris, [(up, up, up)], ["x"])
    assert counter_clockwise(plain) and counter_clockwise(mirrored)
    assert mirrored["triangles"] == [[0, 2, 1]]


def test_vertices_split_where_normals_differ_and_objects_per_material():
    positions = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
    a, b = (0.0, 0.0, 1.0), (0.0, 0.6, 0.8)
    objs = scene.mesh_objects("q", IDENTITY, positions, [(0, 1, 2), (1, 3, 2), (0, 1, 2)],
                              [(a, a, a), (b, b, b), (a, a, a)], ["A", "A", "B"])
    by_name = {o["name"]: o for o in objs}
    assert sorted(by_name) == ["q.A", "q.B"]
    assert len(by_name["q.A"]["positions"]) == 6            # 1 and 2 are split: two normals each
    assert len(by_name["q.B"]["positions"]) == 3 and by_name["q.B"]["material"] == "B"


# ----------------------------------------------------------------------------- the scene

def test_a_scene_built_here_is_one_facet_renders(tmp_path, facet):
    cam, _ = scene.camera(camera_desc())
    light, _ = scene.light(light_desc("POINT", matrix=translated(2.0, -3.0, 4.0)))
    n = (0.0, 0.0, 1.0)
    objects = scene.mesh_objects("Floor", IDENTITY, [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)],
                                 [(0, 1, 2), (0, 2, 3)], [(n, n, n)] * 2, ["Grey"] * 2)
    materials = {"Grey": {"name": "Grey", "diffuse": {"model": "lambert", "color": [0.5, 0.5, 0.5]}}}
    data = scene.scene("S", cam, [0.0, 0.0, 0.0], [light], objects, materials)
    assert list(data) == ["name", "camera", "ambient", "materials", "objects", "lights"]
    plan = pov.generate_scene(facet, data, "S", str(tmp_path / "s.pov"))
    assert plan.passes == 1 and plan.native                    # a Lambert mesh: POV-Ray's own finish on mesh2
    assert os.path.getsize(tmp_path / "s.pov") > 0
    osl_scene = scene.scene("S", cam, [0.1, 0.1, 0.1], [light], [dict(scene.OSL_PLACEHOLDER_OBJECT)])
    assert "materials" not in osl_scene
