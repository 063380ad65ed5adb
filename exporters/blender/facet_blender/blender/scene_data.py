"""The Blender scene read into plain data and assembled into facet's scene JSON.

Only reading happens here (bpy -> lists and dicts); every conversion (axes, units,
normals, windings) is in core/scene.py.
"""

import bpy

from ..core import UserError, scene as core_scene, textures
from . import images, material as material_mod

MESH_TYPES = {"MESH", "CURVE", "SURFACE", "META", "FONT"}


def _rows(matrix):
    return [[float(x) for x in row] for row in matrix]


def render_size(scene):
    r = scene.render
    return core_scene.render_size(r.resolution_x, r.resolution_y, r.resolution_percentage)


def camera_json(scene):
    """(facet camera, notes) of the scene's active camera."""
    obj = scene.camera
    if obj is None or obj.type != "CAMERA":
        raise UserError(f"scene '{scene.name}' has no active camera")
    cam = obj.data
    width, height = render_size(scene)
    return core_scene.camera({
        "name": obj.name, "type": cam.type, "matrix": _rows(obj.matrix_world),
        "lens": cam.lens, "ortho_scale": cam.ortho_scale,
        "sensor_width": cam.sensor_width, "sensor_height": cam.sensor_height,
        "sensor_fit": cam.sensor_fit, "width": width, "height": height,
        "pixel_aspect_x": scene.render.pixel_aspect_x, "pixel_aspect_y": scene.render.pixel_aspect_y,
        "shift_x": cam.shift_x, "shift_y": cam.shift_y})


def world_ambient(scene):
    """(ambient RGB, notes): the World's colour × strength when it is a plain Background."""
    world = scene.world
    if world is None:
        return [0.0, 0.0, 0.0], []
    if not world.use_nodes or world.node_tree is None:
        return [float(c) for c in world.color], []
    outputs = [n for n in world.node_tree.nodes if n.type == "OUTPUT_WORLD"]
    output = next((n for n in outputs if n.is_active_output), outputs[0] if outputs else None)
    surface = output.inputs.get("Surface") if output else None
    node = surface.links[0].from_node if surface is not None and surface.is_linked else None
    if node is None:
        return [0.0, 0.0, 0.0], []
    color, strength = node.inputs.get("Color"), node.inputs.get("Strength")
    if node.type != "BACKGROUND" or color.is_linked or strength.is_linked:
        return [0.0, 0.0, 0.0], [f"world '{world.name}' is not a plain Background colour; ambient 0"]
    return [float(c) * float(strength.default_value) for c in list(color.default_value)[:3]], []


def _light_desc(obj, matrix):
    light = obj.data
    return {"name": obj.name, "type": light.type, "matrix": _rows(matrix),
            "color": [float(c) for c in light.color], "energy": float(light.energy),
            "shadow_soft_size": float(getattr(light, "shadow_soft_size", 0.0)),
            "angle": float(getattr(light, "angle", 0.0)),
            "spot_size": float(getattr(light, "spot_size", 0.0)),
            "spot_blend": float(getattr(light, "spot_blend", 0.0)),
            "use_nodes": bool(getattr(light, "use_nodes", False))}


def _instances(depsgraph, originals=None):
    """(name, evaluated object, world matrix) of everything the scene renders,
    instances included, hidden-for-render objects excluded. `originals`, a list, gets
    each one's original object, or None for an instance (a copy that no object is)."""
    seen = {}
    for inst in depsgraph.object_instances:
        obj = inst.object
        original = obj.original
        if getattr(original, "hide_render", False):
            continue
        name = original.name
        if inst.is_instance:
            seen[name] = seen.get(name, 0) + 1
            name = f"{name}.instance{seen[name]}"
        if originals is not None:
            originals.append(None if inst.is_instance else original)
        yield name, obj, inst.matrix_world.copy()


def light_sources(depsgraph):
    """([(name, original light object or None for an instance, facet light)], notes) of
    every light the scene renders that facet takes, in the order of lights_json."""
    sources, notes, originals = [], [], []
    for name, obj, matrix in _instances(depsgraph, originals):
        if obj.type != "LIGHT":
            continue
        desc = _light_desc(obj, matrix)
        desc["name"] = name
        light, light_notes = core_scene.light(desc, tuple(bpy.app.version))
        notes.extend(light_notes)
        if light:
            sources.append((name, originals[-1], light))
    return sources, notes


def lights_json(depsgraph):
    """(facet lights, notes) of every light the scene renders."""
    sources, notes = light_sources(depsgraph)
    return [light for _, _, light in sources], notes


def _corner_normals(mesh):
    """Per-corner normals, flat list (Blender 4.1+: corner_normals; older: split normals)."""
    values = [0.0] * (3 * len(mesh.loops))
    if hasattr(mesh, "corner_normals"):
        mesh.corner_normals.foreach_get("vector", values)
    else:
        mesh.calc_normals_split()
        mesh.loops.foreach_get("normal", values)
    return values


def _mesh_data(obj, mesh):
    """Positions, triangles, per-corner normals and per-triangle slot indices."""
    mesh.calc_loop_triangles()
    count = len(mesh.loop_triangles)
    co = [0.0] * (3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", co)
    positions = [tuple(co[i:i + 3]) for i in range(0, len(co), 3)]
    verts, loops = [0] * (3 * count), [0] * (3 * count)
    polys, slots = [0] * count, [0] * count
    mesh.loop_triangles.foreach_get("vertices", verts)
    mesh.loop_triangles.foreach_get("loops", loops)
    mesh.loop_triangles.foreach_get("polygon_index", polys)
    mesh.loop_triangles.foreach_get("material_index", slots)
    corner = _corner_normals(mesh)
    smooth = [False] * len(mesh.polygons)
    mesh.polygons.foreach_get("use_smooth", smooth)
    face_normal = [0.0] * (3 * len(mesh.polygons))
    mesh.polygons.foreach_get("normal", face_normal)

    triangles, normals = core_scene.triangle_corners(verts, loops, polys, corner, smooth, face_normal)
    return positions, triangles, normals, slots, loops


def _find_uv_layer(mesh, name, obj_name, material, reader=None):
    """The named UV map ("" the active render one, "#k" the k-th) or a UserError naming it and what
    reads it (`reader`: the textures of `material` where None)."""
    layers = mesh.uv_layers
    if name.startswith("#") and name[1:].isdigit():        # a material file's set k: the k-th UV map
        k = int(name[1:])
        layer = layers[k] if k < len(layers) else None
        name = f"number {k + 1}"
    else:
        layer = layers.get(name) if name else next((l for l in layers if l.active_render), layers.active)
    if layer is None:
        raise UserError(f"object '{obj_name}' has no UV map " + (f"'{name}'" if name else "at all")
                        + (f", which the textures of material '{material}' read: add it, or change the "
                           f"UV Map node and convert the material again" if reader is None else
                           f", {reader}"))
    return layer


def _uv_layer(mesh, name, obj_name, material, reader=None):
    """Per-loop UVs (flat list) of the named UV map."""
    layer = _find_uv_layer(mesh, name, obj_name, material, reader)
    values = [0.0] * (2 * len(mesh.loops))
    layer.data.foreach_get("uv", values)
    return values


def _corner_uvs(mesh, obj_name, loops, slot_names, bindings_of, frame_of):
    """Per triangle, its corners' UVs of the UV maps its material's textures read, or of the one
    its tangent frame is taken from (`frame_of`) where they read none."""
    per_material, layers, out = {}, {}, []
    for t, material in enumerate(slot_names):
        maps = per_material.get(material.name)
        reader = None
        if maps is None:
            maps = textures.uv_maps(bindings_of(material), material.name)
            if not maps and frame_of(material) is not None:
                maps = [frame_of(material)]
                reader = (f"whose tangents the anisotropy of material '{material.name}' turns from (glTF's "
                          f"KHR_materials_anisotropy): add one (UV > Unwrap), or set its Anisotropic to 0")
            per_material[material.name] = maps
        data = []
        for name in maps:
            if name not in layers:
                layers[name] = _uv_layer(mesh, name, obj_name, material.name, reader)
            data.append(layers[name])
        out.append(tuple(tuple((d[2 * l], d[2 * l + 1]) for d in data) for l in loops[3 * t:3 * t + 3]))
    return out


def _corner_tangents(mesh, obj_name, loops, slot_materials, material_keys, bindings_of):
    """Per triangle, None or its corners' (MikkTSpace tangent, bitangent sign) for the UV
    map of its material's normal map (Mesh.calc_tangents)."""
    per_uv, out = {}, []
    for t, material in enumerate(slot_materials):
        bindings = textures.exported(bindings_of(material), material_keys)
        # The tangent frame's map: the lobes' normal map, else the coat's (both on one UV map).
        normal = next((b for b in bindings if b["path"] in (["normal_map"], ["coat_normal_map"])), None)
        if normal is None:
            out.append(None)
            continue
        name = normal["spec"].get("uv_map", "")
        if name not in per_uv:
            layer = _find_uv_layer(mesh, name, obj_name, material.name)
            try:
                mesh.calc_tangents(uvmap=layer.name)
            except RuntimeError as e:
                raise UserError(f"object '{obj_name}': the normal map of material '{material.name}' needs "
                                f"tangents, which Blender cannot compute here ({e}); triangulate its n-gons")
            tangents = [0.0] * (3 * len(mesh.loops))
            signs = [0.0] * len(mesh.loops)
            mesh.loops.foreach_get("tangent", tangents)
            mesh.loops.foreach_get("bitangent_sign", signs)
            per_uv[name] = (tangents, signs)
        tangents, signs = per_uv[name]
        out.append(tuple((tangents[3 * l], tangents[3 * l + 1], tangents[3 * l + 2], signs[l])
                         for l in loops[3 * t:3 * t + 3]))
    return out


def _color_layer(mesh, name, obj_name, material):
    """Per-loop linear RGBA (flat list) of the named colour attribute ("" the render one, as a
    Color Attribute node without a name reads), of any domain (a point's colour on each of
    its corners)."""
    attributes = mesh.color_attributes
    if name:
        layer = attributes.get(name)
    else:
        index = attributes.render_color_index
        layer = attributes[index] if 0 <= index < len(attributes) else (attributes[0] if len(attributes) else None)
    if layer is None:
        raise UserError(f"object '{obj_name}' has no colour attribute " + (f"'{name}'" if name else "at all")
                        + f", which material '{material}' reads (a Color Attribute node): add one, or remove the node")
    values = [0.0] * (4 * len(layer.data))
    layer.data.foreach_get("color", values)       # scene linear, whatever the storage (8-bit sRGB or float)
    if layer.domain == "CORNER":
        return values
    if layer.domain != "POINT":
        raise UserError(f"object '{obj_name}': colour attribute '{layer.name}' is on the {layer.domain.lower()} "
                        f"domain; facet reads vertex or face-corner colours")
    vertex = [0] * len(mesh.loops)
    mesh.loops.foreach_get("vertex_index", vertex)
    return [values[4 * v + k] for v in vertex for k in range(4)]


def _corner_colors(mesh, obj_name, loops, slot_materials, bindings_of):
    """Per triangle, None or its corners' linear RGBA of the colour attribute its material's
    vertex colour reads (facet's "colors")."""
    layers, per_material, out = {}, {}, []
    for t, material in enumerate(slot_materials):
        names = per_material.get(material.name)
        if names is None:
            names = per_material[material.name] = textures.vertex_color_layers(bindings_of(material))
        if not names:
            out.append(None)
            continue
        if len(names) > 1:
            raise UserError(f"material '{material.name}' reads {len(names)} colour attributes "
                            f"({', '.join(repr(n or 'the render one') for n in names)}); facet meshes have one")
        if names[0] not in layers:
            layers[names[0]] = _color_layer(mesh, names[0], obj_name, material.name)
        data = layers[names[0]]
        out.append(tuple(tuple(data[4 * l:4 * l + 4]) for l in loops[3 * t:3 * t + 3]))
    return out


def objects_json(depsgraph, materials, material_keys=None, bindings_of=material_mod.texture_bindings,
                 frame_of=lambda material: None):
    """(facet mesh objects, notes). `materials` collects name -> Blender material of
    every material used (their facet settings are checked by the caller); `bindings_of`
    gives a material's texture bindings as the export writes it, `frame_of` the UV map ("" the
    active render one) whose tangent frame it reads without a texture (glTF's anisotropy turns
    from the mesh's tangent: facet computes Blender's MikkTSpace tangents from it), or None."""
    objects, notes = [], []
    for name, obj, matrix in _instances(depsgraph):
        if obj.type not in MESH_TYPES:
            if obj.type not in ("LIGHT", "CAMERA", "EMPTY"):
                notes.append(f"object '{name}' ({obj.type}) is not a mesh; skipped")
            continue
        mesh = obj.to_mesh()
        try:
            if mesh is None or not mesh.polygons:
                continue
            positions, triangles, normals, slot_of, loops = _mesh_data(obj, mesh)
            slots = [s.material for s in obj.material_slots]
            names, used_materials = [], []
            for slot in slot_of:
                mat = slots[slot] if slot < len(slots) else None
                if mat is None:
                    raise UserError(f"object '{name}' has no material"
                                    + (f" in slot {slot + 1}" if slots else "")
                                    + ": give it a material with facet settings")
                materials[mat.name] = mat.original if hasattr(mat, "original") else mat
                names.append(mat.name)
                used_materials.append(materials[mat.name])
            uvs = tangents = colors = None
            if any(bindings_of(m) or frame_of(m) is not None for m in set(used_materials)):
                uvs = _corner_uvs(mesh, name, loops, used_materials, bindings_of, frame_of)
                tangents = _corner_tangents(mesh, name, loops, used_materials, material_keys, bindings_of)
                colors = _corner_colors(mesh, name, loops, used_materials, bindings_of)
            objects.extend(core_scene.mesh_objects(name, _rows(matrix), positions, triangles, normals, names, uvs,
                                                   tangents, colors))
        finally:
            obj.to_mesh_clear()
    return objects, notes


def full_scene(context, material_keys=None, reserved=(), strict=False):
    """(facet scene JSON with materials and meshes, notes, texture files) of the whole
    scene; the texture files ({file name: bytes}) go beside the scene file, which names
    them relatively, under names other than `reserved` (what else the export writes).

    A material without facet settings is exported as 'Convert Blender Material to facet'
    would set it, with a note naming it (material.exported); with `strict` a UserError
    names the first one instead."""
    scene = context.scene
    depsgraph = context.evaluated_depsgraph_get()
    cam, notes = camera_json(scene)
    ambient, more = world_ambient(scene)
    notes += more
    resolved = {}       # material name -> (material JSON, texture bindings, notes), worked out once

    def resolve(material):
        if material.name not in resolved:
            resolved[material.name] = material_mod.exported(material, strict)
        return resolved[material.name]

    used = {}
    objects, more = objects_json(depsgraph, used, material_keys, lambda m: resolve(m)[1],
                                 lambda m: textures.frame_uv_map(resolve(m)[0]))
    notes += more
    if not objects:
        raise UserError(f"scene '{scene.name}' has no mesh objects to export")
    materials = {}
    for name in sorted(used):
        notes += resolve(used[name])[2]
    bindings = {name: resolve(used[name])[1] for name in sorted(used)}
    names, files, more = images.texture_files({n: textures.exported(b, material_keys)
                                               for n, b in bindings.items() if b},
                                              {r.lower() for r in reserved})
    notes += more
    for name in sorted(used):
        materials[name], more = textures.apply(resolve(used[name])[0], bindings[name],
                                               names.get(name, {}), material_keys)
        notes += more
    lights, more = lights_json(depsgraph)
    notes += more
    exposure = float(scene.view_settings.exposure)      # the Film's exposure: facet's previews take it
    return core_scene.scene(scene.name, cam, ambient, lights, objects, materials, exposure), notes, files


def lights_scene(context, catalog):
    """(facet scene JSON, notes, light_sources) for generating OSL: the lights and
    ambient colour, and where each light came from.

    facet's OSL generator reads only those. The camera is the scene's (facet's default
    camera when there is none, or it is not a perspective one) and the objects are a
    placeholder: exporting every mesh (and requiring facet settings on every material)
    just to generate one material's shader would cost time for nothing."""
    scene = context.scene
    depsgraph = context.evaluated_depsgraph_get()
    ambient, notes = world_ambient(scene)
    sources, more = light_sources(depsgraph)
    notes += more
    try:
        camera, _ = camera_json(scene)
    except UserError:
        camera = core_scene.default_camera(catalog)
    lights = [light for _, _, light in sources]
    return core_scene.scene(scene.name, camera, ambient, lights,
                            [dict(core_scene.OSL_PLACEHOLDER_OBJECT)]), notes, sources
