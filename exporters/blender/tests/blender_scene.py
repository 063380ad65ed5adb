"""Scene building shared by the add-on's test scripts (run inside Blender).

Objects are made from data, not operators: bpy.ops mesh operators need a window
context in Blender 3.4's background mode.
"""

import math

import bpy


def link(obj):
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_uv_sphere(name, location, radius, segments=32, rings=16, smooth=True, material=None):
    """A UV sphere of `segments` × `rings` faces, linked to the scene."""
    verts = [(0.0, 0.0, radius)]
    for r in range(1, rings):
        theta = math.pi * r / rings
        for s in range(segments):
            phi = 2.0 * math.pi * s / segments
            verts.append((radius * math.sin(theta) * math.cos(phi), radius * math.sin(theta) * math.sin(phi),
                          radius * math.cos(theta)))
    verts.append((0.0, 0.0, -radius))
    bottom = len(verts) - 1
    ring = lambda r, s: 1 + (r - 1) * segments + (s % segments)   # noqa: E731
    faces = [(0, ring(1, s), ring(1, s + 1)) for s in range(segments)]
    for r in range(1, rings - 1):
        faces += [(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s + 1)) for s in range(segments)]
    faces += [(ring(rings - 1, s), bottom, ring(rings - 1, s + 1)) for s in range(segments)]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    for p in mesh.polygons:
        p.use_smooth = smooth
    if material:
        mesh.materials.append(material)
    obj = link(bpy.data.objects.new(name, mesh))
    obj.location = location
    bpy.context.view_layer.update()
    return obj


def point_sampled_cycles(scene, seed=0):
    """Cycles as a point sampler: one sample at each pixel centre (Gaussian filter of
    width 0.01), CPU, no bounces, no denoising, linear 32-bit EXR with alpha, the
    Standard view transform. With point and sun lights of radius 0 this is each
    light's exact direct lighting (shared/notes/blender.md)."""
    r = scene.render
    r.engine = "CYCLES"
    r.film_transparent = True
    r.use_compositing = r.use_sequencer = False
    r.dither_intensity = 0.0
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.color_mode = "RGBA"
    c = scene.cycles
    c.device = "CPU"
    c.samples = 1
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.pixel_filter_type = "GAUSSIAN"
    c.filter_width = 0.01
    c.max_bounces = 0
    c.light_sampling_threshold = 0.0
    c.seed = seed
    c.use_animated_seed = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0


def add_uv_map(obj, uv_of_face, name="UVMap"):
    """A UV map on a mesh object: `uv_of_face(positions)` gives the (u, v) of each corner
    of a face from its vertices' local positions (Blender's UV: v up)."""
    mesh = obj.data
    layer = mesh.uv_layers.new(name=name)
    for poly in mesh.polygons:
        corners = [tuple(mesh.vertices[mesh.loops[l].vertex_index].co) for l in poly.loop_indices]
        for l, uv in zip(poly.loop_indices, uv_of_face(corners)):
            layer.data[l].uv = uv
    return layer


def sphere_uvs(corners):
    """Longitude/latitude UVs of a face of a sphere centred on its origin: u = φ/2π from +X
    towards +Y, v = 1 − θ/π (v = 1 at the +Z pole); a face across the seam gets u > 1,
    and a pole corner the mean u of the others."""
    out = []
    for x, y, z in corners:
        r = math.sqrt(x * x + y * y + z * z)
        u = (math.atan2(y, x) / (2.0 * math.pi)) % 1.0
        pole = math.hypot(x, y) < 1e-6 * r
        out.append([None if pole else u, 1.0 - math.acos(max(-1.0, min(1.0, z / r))) / math.pi])
    us = [u for u, _ in out if u is not None]
    if us and max(us) - min(us) > 0.5:
        us = [u + 1.0 if u < 0.5 else u for u in us]
        for c in out:
            if c[0] is not None and c[0] < 0.5:
                c[0] += 1.0
    mean = sum(us) / len(us) if us else 0.0
    return [(mean if u is None else u, v) for u, v in out]
