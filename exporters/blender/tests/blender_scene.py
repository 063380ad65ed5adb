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
