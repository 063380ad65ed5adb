"""Build Blender Nodes: the material's facet settings -> a tree of Blender's own shader
nodes (core/native.py chooses them), wired to the Material Output's Surface, so the
material renders in Cycles on any device and in EEVEE without OSL.

The nodes it makes are named "facet native …"; building again replaces them, and every
other node (a facet OSL Script node, the user's own) stays where it is, unlinked from
the Surface. The catalog's "blender_nodes" says how close the result is to facet's model.
"""

import bpy

from ..core import native as core_native
from . import material as material_mod, nodes as nodes_mod
from .operators import _MaterialOperator, context_material

PREFIX = "facet native"


def _set_input(node, name, value):
    socket = node.inputs[name]
    if isinstance(value, tuple) and len(value) == 3 and len(socket.default_value) == 4:
        value = value + (1.0,)
    socket.default_value = value


def build(material, plan):
    """Replaces the material's facet native nodes by `plan`'s, summed by Add Shader nodes
    and linked to the Material Output's Surface. Returns the node feeding the Surface."""
    material.use_nodes = True
    tree = material.node_tree
    for node in [n for n in tree.nodes if n.name.startswith(PREFIX)]:
        tree.nodes.remove(node)
    output = nodes_mod.output_node(tree) or tree.nodes.new("ShaderNodeOutputMaterial")
    made = []
    for i, spec in enumerate(plan):
        node = tree.nodes.new(spec["type"])
        node.name = node.label = f"{PREFIX} {node.bl_label}" if i == 0 else f"{PREFIX} {node.bl_label} {i}"
        for key, value in spec.get("props", {}).items():
            setattr(node, key, value)
        for key, value in spec["inputs"].items():
            _set_input(node, key, value)
        node.location = (output.location.x - 500, output.location.y - 200 * i)
        made.append(node)
    total = made[0]
    for i, node in enumerate(made[1:], 1):
        add = tree.nodes.new(core_native.ADD)
        add.name = add.label = f"{PREFIX} Add Shader {i}"
        add.location = (output.location.x - 250, output.location.y - 200 * i)
        tree.links.new(total.outputs[0], add.inputs[0])
        tree.links.new(node.outputs[0], add.inputs[1])
        total = add
    tree.links.new(total.outputs[0], output.inputs["Surface"])
    return total


class FACET_OT_build_native_nodes(_MaterialOperator, bpy.types.Operator):
    """Build a tree of Blender's own shader nodes nearest this facet material (Diffuse, Glossy, Emission, Add Shader), wired to the Material Output: it renders in Cycles on any device and in EEVEE, without OSL"""
    bl_idname = "facet.build_native_nodes"
    bl_label = "Build Blender Nodes"
    bl_options = {"REGISTER", "UNDO"}

    def run(self, context):
        mat = context_material(context)
        plan = core_native.node_plan(material_mod.to_json(mat), principled=bpy.app.version >= (4, 0, 0))
        build(mat, plan)
        kinds = ", ".join(spec["type"].replace("ShaderNode", "") for spec in plan)
        self.report_("INFO", f"built Blender nodes for '{mat.name}': {kinds} (the catalog's blender_nodes "
                             f"says how close each is to facet's model)")


classes = (FACET_OT_build_native_nodes,)
