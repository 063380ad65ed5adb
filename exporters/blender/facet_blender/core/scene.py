"""Blender cameras, lights and meshes -> facet's scene JSON (plain data in, plain data out).

Scene contract (facet's world, +Y up; every Blender point and direction goes through
`coords.to_facet`):

    {"name": ..., "camera": {"position", "look_at", "up", "fov"}, "ambient": [r, g, b],
     "materials": {name: material}, "objects": [mesh, ...], "lights": [light, ...]}

Units (exact for Cycles with light radius 0, measured in Blender 3.4.1 and 4.5.15):
facet's light of colour C on a white Lambert surface facing it at distance 1 gives
radiance C. A Cycles point light of power P watts has intensity P/(4π) W/sr and the
Diffuse BSDF is ρ/π, so

    point, spot:  C = colour · P / (4π²),  attenuation inverse_square
    sun:          C = colour · S / π,      direction = the light's local −Z in world space
    spot:         cutoff = spot_size / 2 (degrees); Cycles ≤ 3.4 multiplies a spot by the
                  cosine to its axis (exponent 1), Cycles ≥ 3.5 does not (exponent 0)
                  (cycles src/kernel/light: spot_light_attenuation, v3.4.0 vs v3.5.0)

Approximations are returned as notes: a light radius (shadow_soft_size) or sun angle
> 0 (facet lights are points), spot_blend > 0 (facet's cone is hard), area lights
(skipped), camera shift, non-square pixels.
"""

import math

from . import UserError
from .coords import (clean_float, clean_vector, column_scale, cross, det3, normal_matrix, normalize,
                     to_facet, transform_direction, transform_point)

# facet's scene format needs at least one object. Generating OSL reads only the lights
# and the ambient colour of a scene, so that scene carries this stand-in instead of the
# Blender scene's whole geometry.
OSL_PLACEHOLDER_OBJECT = {"type": "sphere", "name": "unused_by_osl", "center": [0.0, 0.0, 0.0], "radius": 1.0}

FOUR_PI_SQUARED = 4.0 * math.pi * math.pi
SPOT_MAX_CUTOFF = 89.999        # facet's cutoff is < 90 degrees


# ----------------------------------------------------------------------------- camera

def render_size(resolution_x, resolution_y, percentage):
    """The render's size in pixels (Blender's resolution × percentage, at least 1×1)."""
    return (max(1, resolution_x * percentage // 100), max(1, resolution_y * percentage // 100))


def default_camera(catalog):
    """facet's default perspective camera: the catalog's defaults of camera/perspective."""
    return {p.name: p.default for p in catalog.model("camera", "perspective").params}


def vertical_fov(lens, sensor_width, sensor_height, sensor_fit, width, height,
                 pixel_aspect_x=1.0, pixel_aspect_y=1.0):
    """The vertical field of view (degrees) of a Blender perspective camera.

    Blender's rule (BKE_camera_params_compute_viewplane): the sensor size is the
    sensor *width* unless sensor_fit is VERTICAL; it spans the image's width when the
    fit is HORIZONTAL, or AUTO with the image at least as wide as tall, and its height
    otherwise. `lens` and the sensor are in millimetres; only their ratio matters."""
    size_x, size_y = width * pixel_aspect_x, height * pixel_aspect_y
    if sensor_fit == "AUTO":
        fit = "HORIZONTAL" if size_x >= size_y else "VERTICAL"
    else:
        fit = sensor_fit
    sensor = sensor_height if sensor_fit == "VERTICAL" else sensor_width
    tan_half = 0.5 * sensor / lens                      # along the fitted axis
    if fit == "HORIZONTAL":
        ycor = pixel_aspect_y / pixel_aspect_x
        tan_half *= ycor * height / width
    return math.degrees(2.0 * math.atan(tan_half))


def fitted_axis(sensor_fit, width, height, pixel_aspect_x=1.0, pixel_aspect_y=1.0):
    """The image axis a Blender camera's sensor (or orthographic scale) spans: HORIZONTAL or
    VERTICAL (AUTO: the longer side, BKE_camera_params_compute_viewplane)."""
    if sensor_fit != "AUTO":
        return sensor_fit
    return "HORIZONTAL" if width * pixel_aspect_x >= height * pixel_aspect_y else "VERTICAL"


def orthographic_height(ortho_scale, sensor_fit, width, height, pixel_aspect_x=1.0, pixel_aspect_y=1.0):
    """The vertical extent of a Blender orthographic camera's view: Orthographic Scale spans
    the fitted axis, so across a horizontal fit it is scale · height / width (in display
    units, the pixel aspect included), as vertical_fov's tangent is."""
    if fitted_axis(sensor_fit, width, height, pixel_aspect_x, pixel_aspect_y) == "VERTICAL":
        return ortho_scale
    return ortho_scale * (pixel_aspect_y / pixel_aspect_x) * height / width


def camera(cam):
    """facet's camera from a plain camera description; returns (camera, notes).

    `cam`: {"name", "type" (PERSP/ORTHO/PANO), "matrix" (4x4 rows, world), "lens",
    "ortho_scale", "sensor_width", "sensor_height", "sensor_fit", "width", "height" (render
    pixels), "pixel_aspect_x", "pixel_aspect_y", "shift_x", "shift_y"}."""
    notes = []
    name = cam.get("name", "camera")
    kind = cam.get("type", "PERSP")
    if kind not in ("PERSP", "ORTHO"):
        raise UserError(f"camera '{name}' is {kind}: facet has perspective and orthographic cameras")
    m = cam["matrix"]
    position = [m[0][3], m[1][3], m[2][3]]
    forward = normalize(transform_direction(m, (0.0, 0.0, -1.0)))   # cameras look down local -Z
    up = normalize(transform_direction(m, (0.0, 1.0, 0.0)))         # with local +Y up
    ax, ay = cam.get("pixel_aspect_x", 1.0), cam.get("pixel_aspect_y", 1.0)
    if ax != ay:
        notes.append(f"camera '{name}': pixel aspect {ax}:{ay} is not square; facet's pixels are (approximate)")
    if cam.get("shift_x", 0.0) or cam.get("shift_y", 0.0):
        notes.append(f"camera '{name}': lens shift has no facet equivalent and is ignored (approximate)")
    out = {"position": to_facet(position),
           "look_at": to_facet([p + f for p, f in zip(position, forward)]),
           "up": to_facet(up)}
    if kind == "ORTHO":
        height = orthographic_height(cam["ortho_scale"], cam["sensor_fit"], cam["width"], cam["height"], ax, ay)
        if not height > 0.0:
            raise UserError(f"camera '{name}': orthographic scale {cam['ortho_scale']:g} gives no view")
        return {"type": "orthographic", **out, "height": height}, notes
    fov = vertical_fov(cam["lens"], cam["sensor_width"], cam["sensor_height"], cam["sensor_fit"],
                       cam["width"], cam["height"], ax, ay)
    if not 0.0 < fov < 180.0:
        raise UserError(f"camera '{name}': vertical field of view {fov:.3f} degrees is not in (0, 180)")
    return {**out, "fov": fov}, notes


# ----------------------------------------------------------------------------- lights

def light_power_divisor(kind):
    """facet's light colour is Blender's colour × power divided by this: 4π² for a point
    or spot light (W), π for a sun (W/m²); see the module's units."""
    return math.pi if kind == "SUN" else FOUR_PI_SQUARED


def spot_cutoff(spot_size):
    """facet's cutoff (degrees, half the cone) of a Blender spot size (radians, the whole
    cone), at most SPOT_MAX_CUTOFF."""
    return min(math.degrees(spot_size) / 2.0, SPOT_MAX_CUTOFF)


def light(desc, blender_version=(4, 5, 0)):
    """facet's light from a plain Blender light description; returns (light or None, notes).

    `desc`: {"name", "type" (POINT/SUN/SPOT/AREA), "matrix" (4x4 rows, world),
    "color" (RGB), "energy" (W, or W/m² for a sun), "shadow_soft_size", "angle" (sun,
    radians), "spot_size" (radians), "spot_blend", "use_nodes"}."""
    notes = []
    name, kind = desc.get("name", "light"), desc["type"]
    m = desc["matrix"]
    position = to_facet([m[0][3], m[1][3], m[2][3]])
    color = [float(c) for c in desc["color"]]
    energy = float(desc["energy"])
    if desc.get("use_nodes"):
        notes.append(f"light '{name}': its node tree is ignored; colour × power are used (approximate)")
    if kind == "AREA":
        notes.append(f"light '{name}': area lights have no facet equivalent; skipped")
        return None, notes
    if kind == "SUN":
        if desc.get("angle", 0.0) > 0.0:
            notes.append(f"light '{name}': sun angle > 0 (soft shadows); facet's directional light is "
                         f"a parallel beam (exact only with Angle 0)")
        direction = normalize(transform_direction(m, (0.0, 0.0, -1.0)))
        return {"type": "directional", "direction": to_facet(direction),
                "color": clean_vector(c * energy / light_power_divisor(kind) for c in color)}, notes
    if kind not in ("POINT", "SPOT"):
        notes.append(f"light '{name}': {kind} lights have no facet equivalent; skipped")
        return None, notes
    if desc.get("shadow_soft_size", 0.0) > 0.0:
        notes.append(f"light '{name}': radius {desc['shadow_soft_size']:g} > 0; facet treats the light as "
                     f"a point (exact only with Radius 0)")
    out = {"type": "point", "position": position,
           "color": clean_vector(c * energy / light_power_divisor(kind) for c in color),
           "attenuation": "inverse_square"}
    if kind == "POINT":
        return out, notes
    direction = normalize(transform_direction(m, (0.0, 0.0, -1.0)))
    cutoff = spot_cutoff(desc["spot_size"])
    if cutoff == SPOT_MAX_CUTOFF:
        notes.append(f"light '{name}': spot size {math.degrees(desc['spot_size']):g}° reaches 180°; facet's "
                     f"cutoff is < 90°, using {SPOT_MAX_CUTOFF}° (approximate)")
    if desc.get("spot_blend", 0.0) > 0.0:
        notes.append(f"light '{name}': spot blend {desc['spot_blend']:g} > 0 has no facet equivalent; "
                     f"facet's cone edge is hard (approximate)")
    sx, sy, _ = column_scale(m)
    if abs(sx - sy) > 1e-6 * max(sx, sy):
        notes.append(f"light '{name}': non-uniform scale makes Cycles' cone elliptical; facet's is "
                     f"circular (approximate)")
    exponent = 1.0 if tuple(blender_version[:2]) < (3, 5) else 0.0
    out.update({"type": "spot", "direction": to_facet(direction), "cutoff": cutoff, "exponent": exponent})
    return {k: out[k] for k in ("type", "position", "direction", "cutoff", "exponent", "color",
                                "attenuation")}, notes


# ----------------------------------------------------------------------------- lights as OSL drivers

# facet's OSL takes the i-th light of its scene as Script-node inputs "light<i>_color",
# "_position", "_direction" (spot, directional) and "_cutoff", "_exponent" (spot), in
# Blender's axes (facet writes them back through coords.to_blender). The add-on drives
# them from the light object, so the shader follows the scene without regenerating.
# Each component's driver is a *simple expression* (arithmetic and the functions in
# DRIVER_FUNCTIONS), which Blender evaluates without Python: it runs in a file opened
# with Auto Run Python Scripts off. Its variables read a property of the light object
# (RNA paths: matrix_world[c][r] is column c, row r of the world matrix; data.* the
# light's settings). What the expressions compute is light()'s conversion, written with
# the same constants and helpers, and read back in coords.to_blender's axes:
#   position:  to_blender(to_facet(world translation)) = the translation
#   direction: normalize(local −Z in world space) = −(column 2) / |column 2|
#   color:     colour × power / light_power_divisor
#   cutoff:    spot_cutoff(spot size)
# tests/core/test_scene.py evaluates them against light() for each kind.
# Not driven: a spot's exponent (it depends on the Blender version only).

DRIVER_FUNCTIONS = {"min": min, "degrees": math.degrees, "sqrt": math.sqrt}


def light_drivers(kind, index):
    """{Script-node input name: [(expression, {variable: RNA path on the light object}),
    one per component]} that make facet's OSL inputs of light number `index` follow a
    Blender light object of type `kind`; {} for a kind facet skips (area)."""
    if kind not in ("POINT", "SPOT", "SUN"):
        return {}
    prefix = f"light{index}_"
    out = {prefix + "color": [(f"c * e / {light_power_divisor(kind)!r}", {"c": f"data.color[{i}]", "e": "data.energy"})
                              for i in range(3)]}
    if kind in ("POINT", "SPOT"):
        out[prefix + "position"] = [("p", {"p": f"matrix_world[3][{i}]"}) for i in range(3)]
    if kind in ("SPOT", "SUN"):
        column = {v: f"matrix_world[2][{i}]" for i, v in enumerate("xyz")}
        out[prefix + "direction"] = [(f"-{v} / sqrt(x * x + y * y + z * z)", column) for v in "xyz"]
    if kind == "SPOT":
        out[prefix + "cutoff"] = [(f"min(degrees(s) / 2, {SPOT_MAX_CUTOFF!r})", {"s": "data.spot_size"})]
    return out


# ----------------------------------------------------------------------------- meshes

def _triangle_normal(a, b, c):
    n = cross([b[i] - a[i] for i in range(3)], [c[i] - a[i] for i in range(3)])
    try:
        return normalize(n)
    except ValueError:
        return [0.0, 0.0, 1.0]


def triangle_corners(vertices, loops, polygons, corner_normals, smooth, face_normals):
    """(triangles, normals) of a Blender mesh's loop triangles, from flat arrays as
    `foreach_get` fills them: per triangle its three vertex indices, and per corner
    the corner's (split) normal on a smooth face, the face's normal on a flat one.

    vertices, loops:  3 per triangle (loop_triangles' "vertices", "loops")
    polygons:         1 per triangle, the face it is part of ("polygon_index")
    corner_normals:   3 floats per loop (corner_normals / split normals)
    smooth:           1 per face ("use_smooth");  face_normals: 3 floats per face"""
    triangles, normals = [], []
    for t in range(len(polygons)):
        triangles.append(tuple(vertices[3 * t:3 * t + 3]))
        p = polygons[t]
        if smooth[p]:
            normals.append(tuple(tuple(corner_normals[3 * l:3 * l + 3]) for l in loops[3 * t:3 * t + 3]))
        else:
            n = tuple(face_normals[3 * p:3 * p + 3])
            normals.append((n, n, n))
    return triangles, normals


def texcoord(uv):
    """facet's (glTF's) texture coordinate of a Blender UV: v runs down the picture in
    facet, up in Blender (docs/textures.md; /work/texconv/FINDINGS.md B4), so v = 1 − v_b."""
    return [float(uv[0]), 1.0 - float(uv[1])]


def world_tangent(matrix, tangent, flip):
    """facet's [x, y, z, w] of a Blender corner tangent (local T, bitangent sign)."""
    try:
        t = normalize(transform_direction(matrix, tangent[:3]))
    except ValueError:
        t = [1.0, 0.0, 0.0]
    return to_facet(t) + [-float(tangent[3]) if flip else float(tangent[3])]


def mesh_objects(name, matrix, positions, triangles, corner_normals, materials, corner_uvs=None,
                 corner_tangents=None, corner_colors=None):
    """facet mesh objects (one per material) of one Blender mesh.

    positions:       [(x, y, z), ...] local vertex positions
    triangles:       [(v0, v1, v2), ...] vertex indices, counter-clockwise seen from the
                     side the face's normal points to (Blender's loop triangles)
    corner_normals:  [((nx, ny, nz), (..), (..)), ...] per triangle, local space: the
                     per-corner normals of smooth faces, the face normal of flat faces
    materials:       [material name, ...] per triangle
    corner_uvs:      None, or per triangle three corners' tuples of Blender UVs ((u, v) of
                     the UV maps the triangle's material reads: set 0, then set 1), written
                     as facet's "texcoords" and "texcoords1" with v = 1 − v_blender
    corner_tangents: None, or per triangle None (its material has no normal map) or three
                     corners' (t_x, t_y, t_z, sign): Blender's MikkTSpace tangent (local) and
                     bitangent sign, B = sign·(N × T), written as facet's "tangents"
                     [x, y, z, w] (glTF's TANGENT): T to world space and facet's axes, w the
                     sign, negated by a mirroring matrix (N × T flips under a reflection)
    corner_colors:   None, or per triangle None (its material reads no vertex colour) or three
                     corners' linear RGBA (a Blender colour attribute's `color`), written as
                     facet's "colors" (glTF's COLOR_0)

    Positions go to world space through `matrix` (4x4 rows), normals through its
    inverse transpose. A vertex is split where its corners' normals differ. A mirroring
    matrix (negative determinant) reverses the winding, so triangles stay
    counter-clockwise seen from their normals' side."""
    nm = normal_matrix(matrix)
    flip = det3(matrix) < 0.0
    out = {}   # material -> [index map, positions, normals, triangles]
    world = {}
    uvs_of = {}      # material -> [texcoords, texcoords1]
    tangents_of = {}  # material -> tangents
    colors_of = {}    # material -> colours
    for t, (tri, normals, material) in enumerate(zip(triangles, corner_normals, materials)):
        entry = out.setdefault(material, [{}, [], [], []])
        index, pos, nor, tris = entry
        corners = []
        uv_corners = corner_uvs[t] if corner_uvs is not None else (None, None, None)
        tangent_corners = (corner_tangents[t] if corner_tangents is not None else None) or (None, None, None)
        color_corners = (corner_colors[t] if corner_colors is not None else None) or (None, None, None)
        for v, n, uv, tangent, color in zip(tri, normals, uv_corners, tangent_corners, color_corners):
            uv = tuple(tuple(x) for x in uv) if uv else ()
            color = tuple(float(c) for c in color) if color else None
            key = (v, tuple(n), uv, tuple(tangent) if tangent else None, color)
            i = index.get(key)
            if i is None:
                if v not in world:
                    world[v] = transform_point(matrix, positions[v])
                try:
                    wn = normalize(transform_direction(nm, n))
                except ValueError:   # a degenerate normal: fall back to the triangle's
                    p = [transform_point(matrix, positions[u]) for u in tri]
                    wn = _triangle_normal(*p) if not flip else _triangle_normal(p[0], p[2], p[1])
                i = index[key] = len(pos)
                pos.append(to_facet(world[v]))
                nor.append(to_facet(wn))
                sets = uvs_of.setdefault(material, [[] for _ in uv])
                for k, c in enumerate(uv):
                    sets[k].append(texcoord(c))
                if tangent:
                    tangents_of.setdefault(material, []).append(world_tangent(matrix, tangent, flip))
                if color:
                    colors_of.setdefault(material, []).append([clean_float(c) for c in color])
            corners.append(i)
        tris.append([corners[0], corners[2], corners[1]] if flip else corners)
    objects = []
    for material, (_, pos, nor, tris) in out.items():
        obj = {"type": "mesh", "name": name if len(out) == 1 else f"{name}.{material}",
               "material": material, "positions": pos, "normals": nor}
        for key, coords in zip(("texcoords", "texcoords1"), uvs_of.get(material, ())):
            obj[key] = coords
        if material in tangents_of:
            if len(tangents_of[material]) != len(pos):
                raise UserError(f"object '{name}': material '{material}' has a normal map but not every "
                                f"vertex has a tangent")
            obj["tangents"] = tangents_of[material]
        if material in colors_of:
            if len(colors_of[material]) != len(pos):
                raise UserError(f"object '{name}': material '{material}' reads the vertex colour but not every "
                                f"vertex has one")
            obj["colors"] = colors_of[material]
        obj["triangles"] = tris
        objects.append(obj)
    return objects


# ----------------------------------------------------------------------------- the scene

def scene(name, camera_json, ambient, lights, objects, materials=None, exposure=0.0):
    """The scene JSON, keys in the contract's order; `exposure` (stops, Blender's Film
    exposure) is written when not 0: facet's previews show radiance × 2^exposure."""
    data = {"name": name, "camera": camera_json, "ambient": clean_vector(ambient)}
    if exposure:
        data["exposure"] = float(exposure)
    if materials is not None:
        data["materials"] = materials
    data["objects"] = objects
    data["lights"] = lights
    return data
