"""Render facet's generated OSL shaders with Blender Cycles, sampled exactly at pixel centres.

Usage (with the project's Python, which has pip `bpy` built with Cycles OSL):

    python cycles_render.py JOB.json

One Blender process renders every item of the job: the scene is built once, then for
each item a fresh Script node is compiled from the item's .osl file and rendered.

Job file
--------
    {
      "width": 128, "height": 128,
      "scene": {                        # a facet scene, in facet's world: right-handed, +y up
        "camera": {"position": [x, y, z], "look_at": [x, y, z], "up": [x, y, z],
                   "fov": 40},          # vertical field of view, degrees
        "objects": [
          {"type": "sphere", "name": "...", "center": [x, y, z], "radius": r},
          {"type": "plane", "name": "...", "point": [x, y, z], "normal": [x, y, z], "size": s}
        ],
        ...                             # other keys ("lights", "ambient", "name") are ignored:
      },                                # the generated OSL has the lights baked in
      "items": [{"name": "lambert", "osl": "/abs/lambert.osl", "output": "/abs/lambert",
                 "materials": {"clay": "/abs/clay.osl"}}, ...]
    }

Objects may name a material of the scene ("material": key); an item then
gives that material's shader in "materials"[key]. Objects without one use the
item's "osl". Meshes ({"type": "mesh", "positions", "normals", "triangles"},
facet world space) are smooth shaded with their normals as custom normals, and carry
them in float as the point attribute "facet_normal", which an Attribute node hands the
generated shader's facet_normal input (objects without it leave the input at 0: Cycles' N).

Outputs
-------
For each item that renders:
  * `<output>.pfm`        linear RGB, PFM "PF", little-endian (scale -1.0), rows stored
                          bottom-to-top as PFM requires (a reader that flips rows gets
                          row 0 = the top of the image);
  * `<output>.alpha.pfm`  greyscale PFM "Pf": the coverage, 1 where a camera ray hit an
                          object, 0 on the background.
Both are written atomically (a temporary file in the same folder, then os.replace). A
failed item leaves no output files (stale ones from an earlier run are removed).

Then `JOB.json.result.json`:
    {"blender": "4.5.15 LTS", "osl": "<_cycles.osl_version_string>",
     "items": [{"name": ..., "ok": true|false, "error": "...", "seconds": s}, ...],
     "setup_seconds": s}
`error` is empty for a good item, otherwise the OSL compiler's or Blender's own words.
`seconds` is the item's wall time: compiling its Script node, rendering, reading back
and writing the images. `setup_seconds` is everything before the first item (importing
bpy, building the scene). One progress line per item goes to stdout. The exit code is
0 when every item is ok, 1 otherwise (also when bpy has no OSL: every item then fails
with that reason).

Conventions
-----------
* Coordinates: facet is +y up, Blender is +z up. Every point and direction (camera,
  sphere centres, plane point and normal) maps as (x, y, z) -> (x, -z, y), a proper
  rotation, so cross products and windings carry over. The OSL files were generated
  with their lights converted the same way.
* Camera: a pinhole whose ray through pixel (i, j), j counted from the top, is
  normalize(forward + right*x + up'*y) with x = (2(i+0.5)/w - 1) tan(fov/2) w/h and
  y = (1 - 2(j+0.5)/h) tan(fov/2); forward = normalize(look_at - position),
  right = normalize(forward x up), up' = right x forward. The Blender camera reproduces
  it with sensor_fit VERTICAL (vertical angle = fov) and a world matrix whose local
  axes are (right, up', -forward): Blender cameras look down local -Z, +Y up. Cycles
  shoots sample 0 exactly through the pixel centre; with 1 sample and a Gaussian pixel
  filter of width 0.01 the image is point-sampled at pixel centres (a box filter would
  be forced to width 1 and be slightly off centre).
* Sphere: analytic. A one-vertex mesh turned into a point by Geometry Nodes
  "Mesh to Points" (radius r) is ray traced by Cycles as an exact sphere with the exact
  normal, unlike any tessellated mesh.
* Plane: one quad, the square of half-side `size` centred at `point` with edges along
  u = normalize(normal x x_hat) (z_hat instead of x_hat where |normal x x_hat| < 1e-6)
  and v = normal x u, computed in facet coordinates; it is wound counter-clockwise
  about `normal` so its face normal is `normal`.
* Material: every object has the same material, whose node tree is a Script node
  (INTERNAL mode, a Text datablock with the .osl file's contents) whose "Out" closure
  feeds the Material Output's Surface. The shader computes direct light analytically
  (shadows with OSL trace()) and emits it, so with no bounces and no Blender lights the
  pixel is exactly the shader's value. It is compiled headless by Cycles' own Script
  node driver (cycles.osl.update_script_node, what the node's Update button runs);
  bpy.ops.node.shader_script_update cannot be used headless in Blender 4.5.
  Beware: Cycles sets OSL's `I` to the unit direction from the surface TOWARD the
  viewer (globals->I = sd->wi), the reverse of the OSL specification, so a shader's
  view vector there is V = normalize(I).
* Render: Cycles on the CPU with the OSL shading system, 1 sample, no adaptive
  sampling, no denoising, no bounces but 64 transparent ones (a cut-out's Transparent BSDF,
  which Cycles' camera path goes on through), light-sampling threshold 0, seed 0, transparent
  film (for the alpha), Standard view transform, black world, 32-bit float RGBA
  OpenEXR read back with bpy.data.images.load (Blender's rows run bottom-to-top).
  Blender renders at least 4x4 pixels: a smaller image is rendered with a margin of
  whole pixels and a matching wider field of view, then cropped (see Frame).
"""

import ctypes
import glob
import hashlib
import json
import math
import os
import re
import shutil
import sys
import tempfile
import time

import numpy as np

T_START = time.perf_counter()
ERROR_WORD = re.compile(r"\berror\b", re.IGNORECASE)

# Defaults of facet's scene schema (`facet schema --scene`) for keys a job may leave out.
CAMERA_DEFAULTS = {"look_at": [0.0, 0.0, 0.0], "up": [0.0, 1.0, 0.0], "fov": 40.0}
PLANE_SIZE = 10.0


# ----------------------------------------------------------------------------- files

def write_atomic(path, data):
    """Write bytes to `path` through a temporary file in the same folder + os.replace."""
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp", dir=folder)
    try:
        umask = os.umask(0)
        os.umask(umask)
        os.fchmod(fd, 0o666 & ~umask)  # mkstemp makes 0600; give the file ordinary permissions
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


def pfm_bytes(pixels_bottom_up):
    """PFM of a float image given as (h, w, 3) or (h, w) with row 0 = the BOTTOM row.

    PFM stores rows bottom-to-top; scale -1.0 means little-endian floats."""
    h, w = pixels_bottom_up.shape[:2]
    magic = b"PF" if pixels_bottom_up.ndim == 3 else b"Pf"
    header = magic + b"\n%d %d\n-1.0\n" % (w, h)
    return header + np.ascontiguousarray(pixels_bottom_up, dtype="<f4").tobytes()


def output_paths(item):
    return item["output"] + ".pfm", item["output"] + ".alpha.pfm"


def remove_outputs(item):
    """A failed item must not leave an earlier run's images looking current."""
    for path in output_paths(item):
        try:
            os.remove(path)
        except OSError:
            pass


def write_result(job_path, blender, osl, results, setup_seconds):
    result = {"blender": blender, "osl": osl, "items": results, "setup_seconds": round(setup_seconds, 4)}
    write_atomic(job_path + ".result.json", (json.dumps(result, indent=2) + "\n").encode())


def fail_all(job_path, items, reason, blender="", osl=""):
    """Every item fails with the same reason (no OSL, no bpy, a bad scene...)."""
    results = []
    for k, item in enumerate(items, 1):
        name = item.get("name", "?") if isinstance(item, dict) else "?"
        results.append({"name": name, "ok": False, "error": reason, "seconds": 0.0})
        print(f"[{k}/{len(items)}] {name}: FAILED: {reason}".replace("\n", " | "), flush=True)
    write_result(job_path, blender, osl, results, time.perf_counter() - T_START)
    return 1


# ----------------------------------------------------------------------------- capturing native output

class CaptureOutput:
    """Redirects the process's stdout and stderr file descriptors to a temporary file.

    The OSL compiler and Cycles print from C/C++ straight to fds 1 and 2, where
    Python's sys.stdout cannot see them. Afterwards `.text` holds what was printed."""

    _libc = None

    def __enter__(self):
        self._flush()
        self._file = tempfile.TemporaryFile(mode="w+b")
        self._saved = [os.dup(1), os.dup(2)]
        os.dup2(self._file.fileno(), 1)
        os.dup2(self._file.fileno(), 2)
        return self

    def __exit__(self, *exc):
        self._flush()
        os.dup2(self._saved[0], 1)
        os.dup2(self._saved[1], 2)
        for fd in self._saved:
            os.close(fd)
        self._file.seek(0)
        self.text = self._file.read().decode("utf-8", "replace")
        self._file.close()
        return False

    @classmethod
    def _flush(cls):
        sys.stdout.flush()
        sys.stderr.flush()
        if cls._libc is None:
            try:
                cls._libc = ctypes.CDLL(None)
            except OSError:
                cls._libc = False
        if cls._libc:
            cls._libc.fflush(None)  # C stdio buffers (printf from native code)


# ----------------------------------------------------------------------------- geometry

def to_blender(v):
    """facet (+y up) -> Blender (+z up): (x, y, z) -> (x, -z, y)."""
    return (float(v[0]), -float(v[2]), float(v[1]))


def vec(v):
    return np.asarray(v, dtype=np.float64)


def normalize(v):
    return v / np.linalg.norm(v)


def plane_corners(point, normal, size):
    """The quad's corners in facet coordinates, counter-clockwise about `normal`."""
    n = normalize(vec(normal))
    c = np.cross(n, [1.0, 0.0, 0.0])
    if np.linalg.norm(c) < 1e-6:
        c = np.cross(n, [0.0, 0.0, 1.0])
    u = normalize(c)
    v = np.cross(n, u)
    p = vec(point)
    # (b - a) x (c - b) = (2u s) x (2v s) ∝ u x v = n: this order faces `normal`.
    return [p - u * size - v * size, p + u * size - v * size,
            p + u * size + v * size, p - u * size + v * size]


def camera_matrix(camera):
    """The Blender camera's world matrix (rows), built in Blender coordinates."""
    pos = vec(to_blender(camera["position"]))
    forward = normalize(vec(to_blender(camera["look_at"])) - pos)
    right = normalize(np.cross(forward, vec(to_blender(camera["up"]))))
    up = np.cross(right, forward)
    back = -forward  # Blender cameras look down their local -Z, with local +Y up
    return [[right[k], up[k], back[k], pos[k]] for k in range(3)] + [[0.0, 0.0, 0.0, 1.0]]


# ----------------------------------------------------------------------------- Blender scene

class Frame:
    """The job's image and the (possibly larger) image Blender renders.

    Blender renders at least MIN_SIZE x MIN_SIZE pixels. A smaller job image is rendered
    with whole pixels of margin on each side and the field of view widened to match, so
    the job's pixel centres stay exactly where they were; the margin is cropped off."""

    MIN_SIZE = 4

    def __init__(self, width, height):
        self.width, self.height = width, height
        self.pad_x = max(0, math.ceil((self.MIN_SIZE - width) / 2))
        self.pad_y = max(0, math.ceil((self.MIN_SIZE - height) / 2))
        self.render_width = width + 2 * self.pad_x
        self.render_height = height + 2 * self.pad_y

    def crop(self, rgba):
        """The job's pixels out of a rendered (render_height, render_width, 4) array."""
        return rgba[self.pad_y:self.pad_y + self.height, self.pad_x:self.pad_x + self.width]


def configure_render(bpy, scene, width, height, exr_path):
    """Settings for an untonemapped, point-sampled, direct-emission-only render."""
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y = width, height
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.use_border = False
    r.use_motion_blur = False
    r.film_transparent = True          # alpha = coverage
    r.threads_mode = "AUTO"            # all cores
    r.use_compositing = False
    r.use_sequencer = False
    r.dither_intensity = 0.0
    r.use_persistent_data = True       # keep the synced scene between items; only the shader changes
    r.filepath = exr_path
    ims = r.image_settings
    ims.file_format = "OPEN_EXR"
    ims.color_depth = "32"
    ims.color_mode = "RGBA"
    ims.exr_codec = "NONE"

    c = scene.cycles
    c.device = "CPU"
    c.shading_system = True            # OSL
    c.samples = 1                      # sample 0 goes exactly through the pixel centre
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.pixel_filter_type = "GAUSSIAN"   # BOX would be forced to width 1 (and be off centre)
    c.filter_width = 0.01
    c.max_bounces = 0
    c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = 0
    c.volume_bounces = 0
    # A cut-out (glTF's alphaMode MASK) is a Transparent BSDF where the surface is not there: the
    # camera path goes on through it as a transparent bounce, which max_bounces 0 does not count.
    c.transparent_max_bounces = 64
    c.light_sampling_threshold = 0.0
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.seed = 0
    c.use_animated_seed = False
    c.film_exposure = 1.0

    v = scene.view_settings
    v.view_transform = "Standard"
    v.look = "None"
    v.exposure = 0.0
    v.gamma = 1.0

    world = bpy.data.worlds.new("facet_black")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bg.inputs["Strength"].default_value = 0.0
    if hasattr(world, "cycles") and hasattr(world.cycles, "sampling_method"):
        world.cycles.sampling_method = "NONE"
    scene.world = world


def add_camera(bpy, scene, camera, frame):
    """The pinhole camera of the docstring's Conventions, as the scene's camera."""
    from mathutils import Matrix
    data = bpy.data.cameras.new("facet_camera")
    data.sensor_fit = "VERTICAL"       # `fov` (`height`) is the vertical angle (extent) whatever the aspect
    data.sensor_height = 24.0          # (mm; only the ratio to the lens matters)
    margin = frame.render_height / frame.height   # the margin of a tiny image, if any
    if camera.get("type") == "orthographic":
        data.type = "ORTHO"
        data.ortho_scale = float(camera["height"]) * margin   # the extent along the sensor fit: vertical
    else:
        data.type = "PERSP"
        tan_half = math.tan(math.radians(float(camera["fov"])) / 2.0) * margin
        data.lens = 12.0 / tan_half    # tan(vertical angle / 2) = (sensor_height / 2) / lens
    data.shift_x = data.shift_y = 0.0
    data.clip_start = 1e-3
    data.clip_end = 1e6
    data.dof.use_dof = False
    obj = bpy.data.objects.new("facet_camera", data)
    scene.collection.objects.link(obj)
    obj.rotation_mode = "QUATERNION"
    obj.matrix_world = Matrix(camera_matrix(camera))
    scene.camera = obj


# Object.pass_index of each kind of shape: FACET_UV_OSL tells them apart by it.
SPHERE_INDEX, SQUARE_INDEX, MESH_INDEX = 1, 2, 3


def add_sphere(bpy, scene, obj_desc, material, index):
    """An analytic sphere: a one-vertex mesh -> Geometry Nodes "Mesh to Points".
    The vertex is the object's origin and the object sits at the centre, so that object
    space is centred on the sphere (FACET_UV_OSL's texture coordinates)."""
    mesh = bpy.data.meshes.new(f"facet_sphere_{index}")
    mesh.from_pydata([(0.0, 0.0, 0.0)], [], [])
    obj = bpy.data.objects.new(obj_desc.get("name") or f"sphere_{index}", mesh)
    obj.location = to_blender(obj_desc["center"])
    obj.pass_index = SPHERE_INDEX
    scene.collection.objects.link(obj)

    tree = bpy.data.node_groups.new(f"facet_sphere_{index}", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    group_in = tree.nodes.new("NodeGroupInput")
    group_out = tree.nodes.new("NodeGroupOutput")
    to_points = tree.nodes.new("GeometryNodeMeshToPoints")
    to_points.inputs["Radius"].default_value = float(obj_desc["radius"])
    set_material = tree.nodes.new("GeometryNodeSetMaterial")
    set_material.inputs["Material"].default_value = material
    tree.links.new(group_in.outputs[0], to_points.inputs["Mesh"])
    tree.links.new(to_points.outputs["Points"], set_material.inputs["Geometry"])
    tree.links.new(set_material.outputs["Geometry"], group_out.inputs[0])
    obj.modifiers.new("facet_sphere", "NODES").node_group = tree


def add_plane(bpy, scene, obj_desc, material, index):
    """A single quad facing `normal`: the corners (±1, ±1, 0) of object space, whose
    axes are the square's own a, b (scaled by the half-side) and n, its origin the
    square's point (FACET_UV_OSL's texture coordinates)."""
    from mathutils import Matrix
    size = float(obj_desc.get("size", PLANE_SIZE))
    corners = plane_corners(obj_desc["point"], obj_desc["normal"], size)
    p = vec(obj_desc["point"])
    a = vec(to_blender((corners[1] - corners[0]) / (2 * size)))
    b = vec(to_blender((corners[3] - corners[0]) / (2 * size)))
    n = np.cross(a, b)
    origin = vec(to_blender(p))
    mesh = bpy.data.meshes.new(f"facet_plane_{index}")
    mesh.from_pydata([(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (1.0, 1.0, 0.0), (-1.0, 1.0, 0.0)], [], [(0, 1, 2, 3)])
    mesh.update()
    mesh.materials.append(material)
    obj = bpy.data.objects.new(obj_desc.get("name") or f"plane_{index}", mesh)
    obj.matrix_world = Matrix([[a[k] * size, b[k] * size, n[k], origin[k]] for k in range(3)] + [[0.0, 0.0, 0.0, 1.0]])
    obj.pass_index = SQUARE_INDEX
    scene.collection.objects.link(obj)


def add_mesh(bpy, scene, obj_desc, material, index):
    """A triangle mesh, smooth shaded with the scene's per-vertex normals as
    custom normals (Cycles interpolates them barycentrically, as facet does)."""
    mesh = bpy.data.meshes.new(f"facet_mesh_{index}")
    mesh.from_pydata([to_blender(p) for p in obj_desc["positions"]], [],
                     [tuple(int(k) for k in t) for t in obj_desc["triangles"]])
    mesh.update()
    if len(mesh.vertices) != len(obj_desc["positions"]) or len(mesh.polygons) != len(obj_desc["triangles"]):
        raise ValueError(f"mesh {obj_desc.get('name', index)!r}: Blender changed its vertices or triangles")
    mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
    if hasattr(mesh, "use_auto_smooth"):  # Blender < 4.1: custom normals need auto smooth
        mesh.use_auto_smooth = True
    normals = [to_blender(normalize(n)) for n in obj_desc["normals"]]
    mesh.normals_split_custom_set_from_vertices(normals)
    # The same normals in float, which compile_material hands the shader's facet_normal input
    # (templates/osl/shader.osl): Blender keeps custom normals in 16 bits, and a sharp lobe turns
    # that into visible error on a dense mesh (Ward, 131,480 triangles: 5.8e-3 with Cycles' N, 1.8e-5 with these).
    attribute = mesh.attributes.new("facet_normal", "FLOAT_VECTOR", "POINT")
    attribute.data.foreach_set("vector", np.asarray(normals, dtype=np.float32).ravel())
    # The vertex colours (facet's "colors", glTF's COLOR_0; white where the mesh has none), per
    # vertex, which Cycles blends barycentrically as facet does: a float colour attribute, which
    # Cycles reads as it is (linear); a byte colour would hold 8 bits, sRGB-encoded.
    rgba = np.asarray(obj_desc.get("colors", [[1.0, 1.0, 1.0, 1.0]] * len(obj_desc["positions"])), dtype=np.float32)
    attribute = mesh.attributes.new("facet_color0", "FLOAT_COLOR", "POINT")
    if attribute.data_type != "FLOAT_COLOR":
        raise ValueError(f"mesh {obj_desc.get('name', index)!r}: Blender made its vertex colours {attribute.data_type}")
    attribute.data.foreach_set("color", rgba.ravel())
    # Texture coordinates, per corner as Blender keeps them, v up: Blender's v = 1 − glTF's v.
    for set_index, key in enumerate(("texcoords", "texcoords1")):
        if key not in obj_desc:
            continue
        st = np.asarray(obj_desc[key], dtype=np.float64)
        corners = np.asarray(obj_desc["triangles"], dtype=np.int64).ravel()
        uv = np.stack([st[corners, 0], 1.0 - st[corners, 1]], axis=1)
        layer = mesh.uv_layers.new(name=f"facet_uv{set_index}")
        layer.data.foreach_set("uv", uv.astype(np.float32).ravel())
    # A normal map's tangent frames, per corner (facet's, docs/textures.md): xyz and w apart.
    for set_index in (0, 1):
        key = f"facet_tangents{set_index}"
        if key not in obj_desc:
            continue
        tw = np.asarray(obj_desc[key], dtype=np.float64)
        xyz = np.stack([tw[:, 0], -tw[:, 2], tw[:, 1]], axis=1)  # facet's (x, y, z) is Blender's (x, -z, y)
        attribute = mesh.attributes.new(f"facet_tangent{set_index}", "FLOAT_VECTOR", "CORNER")
        attribute.data.foreach_set("vector", xyz.astype(np.float32).ravel())
        attribute = mesh.attributes.new(f"facet_tangent_w{set_index}", "FLOAT", "CORNER")
        attribute.data.foreach_set("value", tw[:, 3].astype(np.float32))
    mesh.materials.append(material)
    obj = bpy.data.objects.new(obj_desc.get("name") or f"mesh_{index}", mesh)
    obj.pass_index = MESH_INDEX
    scene.collection.objects.link(obj)


def new_material(bpy, name):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    if hasattr(material, "cycles") and hasattr(material.cycles, "emission_sampling"):
        material.cycles.emission_sampling = "NONE"   # not a light source for Cycles
    return material


def build_scene(bpy, job, exr_path):
    """Empties Blender, then builds camera, objects, world and settings.

    Returns (scene, materials, Frame): `materials` maps "" (objects without a
    material of their own: the item's "osl") and each scene material key the
    objects name (the item's "materials"[key]) to its Blender material."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    frame = Frame(int(job["width"]), int(job["height"]))
    configure_render(bpy, scene, frame.render_width, frame.render_height, exr_path)
    add_camera(bpy, scene, job["scene"]["camera"], frame)

    materials = {}
    for index, obj_desc in enumerate(job["scene"].get("objects", [])):
        key = obj_desc.get("material", "")
        if key not in materials:
            materials[key] = new_material(bpy, f"facet_{key or 'material'}")
        material = materials[key]
        kind = obj_desc.get("type")
        if kind == "sphere":
            add_sphere(bpy, scene, obj_desc, material, index)
        elif kind == "plane":
            add_plane(bpy, scene, obj_desc, material, index)
        elif kind == "mesh":
            add_mesh(bpy, scene, obj_desc, material, index)
        else:
            raise ValueError(f"scene object {index} has unsupported type {kind!r}")
    return scene, materials, frame


# ----------------------------------------------------------------------------- per-item material

def enable_oslquery(bpy):
    """Makes `import oslquery` work, as Cycles' Script-node compiler needs it.

    The pip `bpy` wheel ships OSL's Python module in Blender's own bundled site-packages
    (<bpy>/4.5/python/lib/python3.11/site-packages), which is not on the path of the
    Python that imports bpy. It is appended (not prepended), so the environment's own
    packages keep priority."""
    try:
        import oslquery  # noqa: F401
        return
    except ImportError:
        pass
    root = bpy.utils.system_resource("PYTHON")
    for folder in sorted(glob.glob(os.path.join(root, "lib", "python*", "site-packages"))):
        if os.path.isdir(os.path.join(folder, "oslquery")) and folder not in sys.path:
            sys.path.append(folder)
    import oslquery  # noqa: F401,F811  (raises ImportError with Python's words if still missing)


# The built-in shapes' texture coordinates (docs/textures.md) for a textured material's
# facet_uv0/facet_uv1 inputs, in Blender's UV convention (v up; the shader takes t = 1 − v),
# from the shading point in object space (add_sphere, add_plane). Facet's (x, y, z) is
# Blender's (x, −z, y).
FACET_UV_OSL = """\
shader facet_uv(float kind = 0, vector mesh_uv = 0, vector mesh_uv1 = 0, vector mesh_tangent = 0, float mesh_w = 1,
                color mesh_color = 1, float mesh_alpha = 1,
                output vector uv = 0, output vector uv1 = 0, output vector tangent = 0, output float handedness = 1,
                output color color0 = 1, output float alpha0 = 1)
{
    point q = transform("object", P);
    if (kind == %d) {
        vector d = normalize(q);
        float x = d[0], y = d[2], z = -d[1];
        uv = vector(0.5 + atan2(x, z) / M_2PI, 1 - acos(clamp(y, -1, 1)) / M_PI, 0);
        uv1 = uv;
        // docs/textures.md, "Tangent frames": facet's (d_z, 0, -d_x), in Blender's axes.
        tangent = normalize(transform("object", "common", vector(z, x, 0)));
    } else if (kind == %d) {
        uv = vector(0.5 + q[0] / 2, 0.5 + q[1] / 2, 0);
        uv1 = uv;
        tangent = normalize(transform("object", "common", vector(1, 0, 0)));  // the square's first axis
    } else {
        uv = mesh_uv;
        uv1 = mesh_uv1;
        // facet's corner tangents (add_mesh), blended by Cycles as facet blends them.
        tangent = mesh_tangent;
        handedness = mesh_w < 0 ? -1 : 1;
        // The vertex colour (add_mesh's attribute); the shapes keep white.
        color0 = mesh_color;
        alpha0 = mesh_alpha;
    }
}
""" % (SPHERE_INDEX, SQUARE_INDEX)


def link_texture_coordinates(bpy, nt, script):
    """FACET_UV_OSL in a Script node of its own, fed the object's kind (Object Info's
    pass index) and the mesh's UV map, linked to the shader's facet_uv0 and facet_uv1; and where the
    shader reads the vertex colour, its facet_color0 and facet_alpha0 (white on the shapes)."""
    import cycles.osl
    # Named by its content and written whole before it is renamed into place: Blender processes
    # of other facet versions on the machine write their own shader beside it, never over it.
    digest = hashlib.sha1(FACET_UV_OSL.encode()).hexdigest()[:12]
    path = os.path.join(tempfile.gettempdir(), f"facet_uv_{digest}.osl")
    with open(f"{path}.{os.getpid()}.tmp", "w") as f:
        f.write(FACET_UV_OSL)
    os.replace(f"{path}.{os.getpid()}.tmp", path)
    node = nt.nodes.new("ShaderNodeScript")
    node.mode = "INTERNAL"
    node.script = bpy.data.texts.load(path, internal=False)
    reports = []
    if not cycles.osl.update_script_node(node, lambda kind, message: reports.append(message)) or "uv" not in node.outputs:
        return "the harness's texture coordinate shader did not compile: " + "; ".join(reports)
    info = nt.nodes.new("ShaderNodeObjectInfo")
    nt.links.new(info.outputs["Object Index"], node.inputs["kind"])
    for k, (into, out) in enumerate((("mesh_uv", "uv"), ("mesh_uv1", "uv1"))):
        uvmap = nt.nodes.new("ShaderNodeUVMap")
        uvmap.uv_map = f"facet_uv{k}"  # add_mesh's layers
        nt.links.new(uvmap.outputs["UV"], node.inputs[into])
        nt.links.new(node.outputs[out], script.inputs[f"facet_uv{k}"])
    if "facet_uv_tangent" in script.inputs:  # a normal-mapped material: the shapes' and meshes' tangent frames
        nt.links.new(node.outputs["tangent"], script.inputs["facet_uv_tangent"])
        nt.links.new(node.outputs["handedness"], script.inputs["facet_uv_handedness"])
        tangent_set = int(script.inputs["facet_normal_map_uv"].default_value)
        for into, name, output in (("mesh_tangent", "facet_tangent", "Vector"), ("mesh_w", "facet_tangent_w", "Fac")):
            attribute = nt.nodes.new("ShaderNodeAttribute")
            attribute.attribute_name = f"{name}{tangent_set}"  # add_mesh's corner attributes
            nt.links.new(attribute.outputs[output], node.inputs[into])
    if "facet_color0" in script.inputs:  # a material that reads the vertex colour: add_mesh's float attribute
        attribute = nt.nodes.new("ShaderNodeAttribute")
        attribute.attribute_name = "facet_color0"
        nt.links.new(attribute.outputs["Color"], node.inputs["mesh_color"])
        nt.links.new(attribute.outputs["Alpha"], node.inputs["mesh_alpha"])
        nt.links.new(node.outputs["color0"], script.inputs["facet_color0"])
        nt.links.new(node.outputs["alpha0"], script.inputs["facet_alpha0"])
    return ""


def compile_material(bpy, material, osl_path):
    """Replaces the material's nodes with a Script node compiled from `osl_path`.

    Returns an error string ('' when the shader compiled and its Out is linked)."""
    import cycles.osl  # Cycles' add-on: the compiler driver behind the Script node's Update button

    nt = material.node_tree
    old_texts = {n.script for n in nt.nodes if n.type == "SCRIPT" and n.script}
    nt.nodes.clear()
    for text in old_texts:
        bpy.data.texts.remove(text)

    output = nt.nodes.new("ShaderNodeOutputMaterial")
    output.target = "ALL"
    script = nt.nodes.new("ShaderNodeScript")
    script.mode = "INTERNAL"
    try:
        # A Text linked to the file: compiled from the file itself, so the compiler's
        # messages name the real file.
        text = bpy.data.texts.load(osl_path, internal=False)
    except (RuntimeError, OSError) as e:
        return f"cannot read {osl_path}: {e}"

    reports = []
    with CaptureOutput() as cap:
        # Setting the script already makes Blender compile it (the node's RNA update asks the
        # scene's engine), but that path swallows Blender's report, so compile it again
        # explicitly with a report callback. (bpy.ops.node.shader_script_update cannot be
        # used headless in 4.5: its poll now needs a node editor.)
        script.script = text
        ok = cycles.osl.update_script_node(script, lambda kind, message: reports.append(message))
    # The compiler's own words (file:line: error: ...); the auto-compile printed them too.
    lines = []
    for line in cap.text.splitlines():
        if line.strip() and line not in lines:
            lines.append(line)
    compiler = "\n".join(lines)
    blender = "\n".join(m for m in reports if m != "OSL shader compilation succeeded")

    if not ok or not script.bytecode or "Out" not in script.outputs:
        words = [w for w in (compiler, blender) if w]
        if ok and script.bytecode:
            words.append("the compiled shader has no output named Out (outputs: %s)"
                         % (", ".join(s.name for s in script.outputs) or "none"))
        elif not words:
            words.append("the OSL compiler produced no bytecode")
        return "\n".join(words)
    if compiler:
        print(compiler, file=sys.stderr, flush=True)   # warnings from a good compile
    nt.links.new(script.outputs["Out"], output.inputs["Surface"])
    if "facet_normal" in script.inputs:  # meshes' float normals (add_mesh); 0 elsewhere, where N is exact
        attribute = nt.nodes.new("ShaderNodeAttribute")
        attribute.attribute_name = "facet_normal"
        nt.links.new(attribute.outputs["Vector"], script.inputs["facet_normal"])
    if "facet_uv0" in script.inputs:  # a textured material
        return link_texture_coordinates(bpy, nt, script)
    return ""


# ----------------------------------------------------------------------------- render + read back

def error_lines(text, limit=20):
    """The distinct lines of native output that report an error (Cycles' progress lines
    "Fra:..." excluded), at most `limit` of them."""
    found = []
    for line in text.splitlines():
        line = line.strip()
        if line and not line.startswith("Fra:") and ERROR_WORD.search(line) and line not in found:
            found.append(line)
    if len(found) > limit:
        found = found[:limit] + [f"... ({len(found) - limit} more)"]
    return found


def render_pixels(bpy, scene, width, height):
    """Renders to the EXR at scene.render.filepath and returns its RGBA, rows bottom-up.

    Raises RuntimeError with Blender's or OSL's words when the render fails, including
    when a shader reported an error while running (e.g. an index out of range)."""
    exr = scene.render.filepath
    if os.path.exists(exr):
        os.remove(exr)
    error = ""
    with CaptureOutput() as cap:
        try:
            bpy.ops.render.render(write_still=True)
        except RuntimeError as e:
            error = str(e).strip()
    problems = error_lines(cap.text) + ([error] if error else [])
    if not os.path.exists(exr):
        problems.append("Blender wrote no image")
    if problems:
        if os.path.exists(exr):
            os.remove(exr)
        raise RuntimeError("\n".join(problems))

    image = bpy.data.images.load(exr, check_existing=False)
    try:
        if tuple(image.size) != (width, height):
            raise RuntimeError(f"rendered image is {tuple(image.size)}, expected {(width, height)}")
        buf = np.empty(width * height * 4, dtype=np.float32)
        image.pixels.foreach_get(buf)
    finally:
        bpy.data.images.remove(image)
        os.remove(exr)
    return buf.reshape(height, width, 4)


def render_item(bpy, scene, materials, item, frame):
    """Compile, render and write one item. Returns the error ('' on success)."""
    for key, material in materials.items():
        osl_path = item.get("materials", {}).get(key) if key else item["osl"]
        if not osl_path:
            return f"the scene's material {key!r} has no shader in this item's \"materials\""
        if not os.path.isfile(osl_path):
            return f"no such OSL file: {osl_path}"
        error = compile_material(bpy, material, osl_path)
        if error:
            return f"{key}: {error}" if key else error
    rgba = frame.crop(render_pixels(bpy, scene, frame.render_width, frame.render_height))
    rgb_path, alpha_path = output_paths(item)
    write_atomic(rgb_path, pfm_bytes(rgba[:, :, :3]))
    write_atomic(alpha_path, pfm_bytes(rgba[:, :, 3]))
    return ""


# ----------------------------------------------------------------------------- main

def load_job(job_path):
    """Returns (job, items, problem); `problem` is '' for a usable job."""
    job, items = None, []
    try:
        with open(job_path) as f:
            job = json.load(f)
        items = job["items"]
        if not isinstance(items, list) or not all(isinstance(i, dict) for i in items):
            items = []
            raise ValueError('"items" must be a list of objects')
        for item in items:
            for key in ("name", "output"):
                if not isinstance(item.get(key), str):
                    raise ValueError(f"item {item.get('name', '?')!r} has no string {key!r}")
            if not isinstance(item.get("osl", ""), str) or not isinstance(item.get("materials", {}), dict):
                raise ValueError(f"item {item.get('name', '?')!r}: \"osl\" must be a path, \"materials\" an object")
        width, height = int(job["width"]), int(job["height"])
        if width <= 0 or height <= 0:
            raise ValueError(f"bad image size {width}x{height}")
        camera = job["scene"]["camera"]
        for key, value in CAMERA_DEFAULTS.items():
            camera.setdefault(key, value)
        for key in ("position", "look_at", "up"):
            if len(camera[key]) != 3:
                raise ValueError(f"camera {key} must have 3 numbers")
        if not 0 < float(camera["fov"]) < 180:
            raise ValueError(f"camera fov {camera['fov']} is not in (0, 180) degrees")
    except (OSError, ValueError, KeyError, TypeError) as e:
        return job, items, f"{type(e).__name__}: {e}"
    return job, items, ""


def main(argv):
    if len(argv) != 2:
        print("usage: python cycles_render.py JOB.json   (the job format is in this file's docstring)",
              file=sys.stderr)
        return 2
    job_path = argv[1]
    job, items, problem = load_job(job_path)
    if problem:
        print(f"cycles_render: {job_path}: {problem}", file=sys.stderr)
        return fail_all(job_path, items, f"bad job file: {problem}")
    width, height = int(job["width"]), int(job["height"])

    try:
        import bpy
        import _cycles
    except ImportError as e:
        return fail_all(job_path, items, f"cannot import bpy: {e}")
    blender = bpy.app.version_string
    osl_version = str(getattr(_cycles, "osl_version_string", "")).strip()
    if not (bpy.app.build_options.cycles_osl and getattr(_cycles, "with_osl", False)):
        return fail_all(job_path, items, f"this Blender ({blender}) was built without Cycles OSL support",
                        blender, osl_version)
    try:
        enable_oslquery(bpy)
    except ImportError as e:
        return fail_all(job_path, items, f"Blender's OSL query module is missing: {e}", blender, osl_version)

    work = tempfile.mkdtemp(prefix="facet-cycles-")
    exr_path = os.path.join(work, "render.exr")
    # Cycles' add-on compiles a Script node's text to a temporary .oso that it never
    # deletes; sending every temporary file of this process into `work` cleans them up.
    tempfile.tempdir = work
    try:
        cap = CaptureOutput()
        try:
            with cap:
                scene, materials, frame = build_scene(bpy, job, exr_path)
        except Exception as e:  # noqa: BLE001 - any scene problem fails every item
            words = [f"cannot build the scene: {type(e).__name__}: {e}"] + error_lines(getattr(cap, "text", ""))
            return fail_all(job_path, items, "\n".join(words), blender, osl_version)
        setup_seconds = time.perf_counter() - T_START
        print(f"cycles_render: Blender {blender}, OSL {osl_version}, {width}x{height}, "
              f"{len(items)} item(s), setup {setup_seconds:.2f} s", flush=True)

        results = []
        for k, item in enumerate(items, 1):
            t0 = time.perf_counter()
            name = item.get("name", "?")
            try:
                error = render_item(bpy, scene, materials, item, frame)
            except RuntimeError as e:      # Blender's / OSL's words
                error = str(e) or "RuntimeError"
            except Exception as e:  # noqa: BLE001 - one bad item must not stop the others
                error = f"{type(e).__name__}: {e}"
            seconds = time.perf_counter() - t0
            if error:
                remove_outputs(item)
            results.append({"name": name, "ok": not error, "error": error, "seconds": round(seconds, 4)})
            status = "ok" if not error else "FAILED: " + error.replace("\n", " | ")
            print(f"[{k}/{len(items)}] {name}: {status} ({seconds:.2f} s)", flush=True)
        write_result(job_path, blender, osl_version, results, setup_seconds)
        return 0 if all(r["ok"] for r in results) else 1
    finally:
        tempfile.tempdir = None
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
