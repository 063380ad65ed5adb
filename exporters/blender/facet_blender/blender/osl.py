"""Putting generated OSL into a material: Text datablock + Script node, compiled by Cycles.

Compiling headless: `bpy.ops.node.shader_script_update` needs a node editor in Blender
4.5 (its poll fails in background mode), so the add-on calls Cycles' own driver,
`cycles.osl.update_script_node(node, report)`, which is what that operator runs. That
driver imports `oslquery`, which the pip `bpy` wheel keeps in Blender's bundled
site-packages, not on sys.path; `enable_oslquery` appends it. What needs no bpy (the
compiler's output captured, the folder of `oslquery` found) is in core/osl.py.
"""

import sys
import tempfile

import bpy

from ..core import UserError, osl as core_osl

NODE_NAME = "facet OSL"


def available():
    """(True, "") when this Blender's Cycles has OSL, else (False, why not)."""
    version = bpy.app.version_string
    if not getattr(bpy.app.build_options, "cycles_osl", False):
        return False, f"this Blender ({version}) was built without OSL (Open Shading Language)"
    try:
        import _cycles
    except ImportError:
        return False, f"this Blender ({version}) has no Cycles"
    if not getattr(_cycles, "with_osl", False):
        return False, f"this Blender's Cycles ({version}) was built without OSL"
    return True, ""


def enable_oslquery():
    try:
        import oslquery  # noqa: F401
        return
    except ImportError:
        pass
    for folder in core_osl.site_packages_with(bpy.utils.system_resource("PYTHON"), "oslquery"):
        if folder not in sys.path:
            sys.path.append(folder)
    try:
        import oslquery  # noqa: F401,F811
    except ImportError as e:
        raise UserError(f"Blender's OSL query module is missing ({e}); cannot compile OSL")


def _output_node(tree):
    from .nodes import output_node
    node = output_node(tree)
    if node is None:
        node = tree.nodes.new("ShaderNodeOutputMaterial")
        node.target = "ALL"
    return node


def _compile(tree, text):
    """A new INTERNAL Script node in `tree` running `text`, compiled. Returns the node;
    on failure removes it and raises a UserError with the compiler's words."""
    import cycles.osl  # Cycles' add-on

    script = tree.nodes.new("ShaderNodeScript")
    script.mode = "INTERNAL"
    reports = []
    ok = False
    saved_tempdir = tempfile.tempdir
    capture = None
    try:
        # Cycles compiles the text to a temporary .oso it never deletes: keep those in a
        # folder of our own. Setting `script` also starts a compile (the node's update),
        # whose report is lost; the explicit call below reports.
        with tempfile.TemporaryDirectory(prefix="facet-osl-") as work:
            tempfile.tempdir = work
            try:
                with core_osl.CaptureNative() as capture:
                    script.script = text
                    ok = cycles.osl.update_script_node(script, lambda kind, msg: reports.append(msg))
            finally:
                tempfile.tempdir = saved_tempdir
        if not (ok and script.bytecode and "Out" in script.outputs):
            words = core_osl.compiler_errors(capture.text if capture else "", reports)
            raise UserError("the OSL compiler rejected the generated shader:\n"
                            + "\n".join(words or ["no bytecode, or no output named Out"]))
    except BaseException:
        tree.nodes.remove(script)
        raise
    return script


UV_NODE_NAME = "facet UV"


def _link_uv_maps(tree, script, uv_maps):
    """UV Map nodes (one per texture coordinate set the shader reads) into the shader's
    facet_uv0 / facet_uv1 inputs; Cycles exports a mesh's UV map only when a node asks.
    A normal-mapped shader's tangent frame too (_link_tangent_frame)."""
    for node in [n for n in tree.nodes if n.name.startswith(UV_NODE_NAME)]:
        tree.nodes.remove(node)
    for k, name in enumerate(uv_maps):
        socket = script.inputs.get(f"facet_uv{k}")
        if socket is None:
            continue
        node = tree.nodes.new("ShaderNodeUVMap")
        node.name = node.label = f"{UV_NODE_NAME} {k}"
        node.uv_map = name
        node.location = (script.location.x - 250, script.location.y - 150 * k)
        tree.links.new(node.outputs["UV"], socket)
    if "facet_uv_tangent" in script.inputs and uv_maps:
        _link_tangent_frame(tree, script, uv_maps)
    if "facet_color0" in script.inputs:    # the vertex colour: the mesh's render colour attribute
        node = tree.nodes.new("ShaderNodeVertexColor")
        node.name = node.label = f"{UV_NODE_NAME} colour"
        node.location = (script.location.x - 250, script.location.y + 150)
        tree.links.new(node.outputs["Color"], script.inputs["facet_color0"])
        tree.links.new(node.outputs["Alpha"], script.inputs["facet_alpha0"])


def _link_tangent_frame(tree, script, uv_maps):
    """The normal map's frame (docs/textures.md, "Tangent frames") from Cycles' own
    MikkTSpace tangents of the UV map the normal map reads, as Blender's Normal Map node
    takes them: a Tangent node (UV Map) gives the interpolated tangent in world space made
    ⟂ N and unit, which is facet's t after its Gram–Schmidt; the Attribute
    "<uv map>.tangent_sign" (Cycles computes it beside the tangent) gives the blended w,
    whose sign, +1 where w ≥ 0, becomes facet_uv_handedness (two Math nodes: 1 − 2·[w < 0])."""
    socket = script.inputs.get("facet_normal_map_uv")
    k = int(socket.default_value) if socket is not None else 0
    name = uv_maps[min(k, len(uv_maps) - 1)]
    x, y = script.location.x - 250, script.location.y - 320

    def node(kind, label, dx, dy):
        n = tree.nodes.new(kind)
        n.name = n.label = f"{UV_NODE_NAME} {label}"
        n.location = (x + dx, y + dy)
        return n

    tangent = node("ShaderNodeTangent", "tangent", 0, 0)
    tangent.direction_type, tangent.uv_map = "UV_MAP", name
    tree.links.new(tangent.outputs["Tangent"], script.inputs["facet_uv_tangent"])
    sign = node("ShaderNodeAttribute", "tangent sign", -500, -150)
    sign.attribute_name = f"{name}.tangent_sign"
    below = node("ShaderNodeMath", "w < 0", -300, -150)
    below.operation = "LESS_THAN"
    below.inputs[1].default_value = 0.0
    tree.links.new(sign.outputs["Fac"], below.inputs[0])
    handedness = node("ShaderNodeMath", "handedness", -100, -150)
    handedness.operation = "MULTIPLY_ADD"
    handedness.inputs[1].default_value, handedness.inputs[2].default_value = -2.0, 1.0
    tree.links.new(below.outputs["Value"], handedness.inputs[0])
    tree.links.new(handedness.outputs["Value"], script.inputs["facet_uv_handedness"])


def install(material, osl_text, text_name, uv_maps=()):
    """Compiles `osl_text` in a new Script node of `material` and wires its "Out" to the
    Material Output's Surface, replacing an earlier facet OSL node.

    The shader is first compiled in a scratch material, so a shader that does not
    compile leaves `material` exactly as it was (not even its node tree is created)."""
    enable_oslquery()
    text = bpy.data.texts.new(text_name)
    text.write(osl_text)
    scratch = bpy.data.materials.new("facet OSL check")
    try:
        scratch.use_nodes = True
        _compile(scratch.node_tree, text)
    except BaseException:
        bpy.data.texts.remove(text)
        raise
    finally:
        bpy.data.materials.remove(scratch)
    material.use_nodes = True
    tree = material.node_tree
    try:
        script = _compile(tree, text)
    except BaseException:
        bpy.data.texts.remove(text)
        raise

    # Success: replace an earlier facet node and its text, then wire the new one.
    old_texts = set()
    for node in [n for n in tree.nodes if n.type == "SCRIPT" and n != script and n.name.startswith(NODE_NAME)]:
        if node.script is not None:
            old_texts.add(node.script.name)
        tree.nodes.remove(node)
    if text_name in bpy.data.texts and text_name != text.name:
        old_texts.add(text_name)
    in_use = _texts_in_use()
    for name in old_texts - in_use:
        bpy.data.texts.remove(bpy.data.texts[name])
    if text_name not in bpy.data.texts:
        text.name = text_name
    script.name = script.label = NODE_NAME
    output = _output_node(tree)
    script.location = (output.location.x - 300, output.location.y)
    tree.links.new(script.outputs["Out"], output.inputs["Surface"])
    _link_uv_maps(tree, script, uv_maps)
    if hasattr(material, "cycles") and hasattr(material.cycles, "emission_sampling"):
        # The shader emits the lit result; it is not a light source for other objects.
        material.cycles.emission_sampling = "NONE"
    return script


def _texts_in_use():
    """Names of the Texts some Script node (in any material or node group) runs."""
    trees = [m.node_tree for m in bpy.data.materials if m.node_tree] + list(bpy.data.node_groups)
    return {n.script.name for t in trees for n in t.nodes if n.type == "SCRIPT" and n.script is not None}


def scene_settings_to_switch(scene):
    """What the scene must switch for Cycles to run Script nodes: [] when it renders with
    Cycles on the CPU with Open Shading Language, else the settings (Render Properties)."""
    missing = []
    if scene.render.engine != "CYCLES":
        missing.append("Render Engine to Cycles")
    cycles = getattr(scene, "cycles", None)
    if cycles is None or cycles.device != "CPU":
        missing.append("Device to CPU")
    if cycles is None or not cycles.shading_system:
        missing.append("Open Shading Language on")
    return missing


def configure_scene(scene):
    """Cycles on the CPU with the OSL shading system, as Script nodes need."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.shading_system = True
