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
    facet_uv0 / facet_uv1 inputs; Cycles exports a mesh's UV map only when a node asks."""
    for node in [n for n in tree.nodes if n.type == "UVMAP" and n.name.startswith(UV_NODE_NAME)]:
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


def configure_scene(scene):
    """Cycles on the CPU with the OSL shading system, as Script nodes need."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.shading_system = True
