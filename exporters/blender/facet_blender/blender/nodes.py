"""A material's node tree read into the plain description core/convert.py maps."""

from ..core import UserError
from ..core.convert import NOTHING_TO_MAP

SHADER_COMBINERS = {"ADD_SHADER", "MIX_SHADER"}


def _value(socket):
    v = getattr(socket, "default_value", None)
    if v is None or isinstance(v, str):
        return None
    try:
        return float(v)
    except TypeError:
        return [float(x) for x in v]


def _from_link(socket, depth=0):
    """The description of the node linked into `socket` (reroutes followed), or None."""
    if depth > 64:
        raise UserError("the shader node tree is too deep (a cycle?)")
    if not socket.is_linked:
        return None
    link = socket.links[0]
    if getattr(link, "is_muted", False) or not link.is_valid:
        return None
    node = link.from_node
    if node.type == "REROUTE":
        return _from_link(node.inputs[0], depth + 1)
    return describe(node, depth)


def describe(node, depth=0):
    desc = {"type": node.type, "name": node.name, "inputs": {}, "linked": []}
    if getattr(node, "mute", False):
        desc["type"] = "MUTED"
        return desc
    if hasattr(node, "distribution"):
        desc["distribution"] = node.distribution
    shaders = []
    for socket in node.inputs:
        if socket.type == "SHADER":
            shaders.append(_from_link(socket, depth + 1))
            continue
        if not getattr(socket, "enabled", True):
            continue
        value = _value(socket)
        if value is None:
            continue
        desc["inputs"].setdefault(socket.name, value)
        if socket.is_linked:
            desc["linked"].append(socket.name)
    if node.type in SHADER_COMBINERS:
        desc["shaders"] = shaders
    return desc


def output_node(tree):
    """The Material Output Cycles uses (the active one for All or Cycles)."""
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_MATERIAL"]
    for n in outputs:
        if n.is_active_output and n.target in ("ALL", "CYCLES"):
            return n
    for n in outputs:
        if n.target in ("ALL", "CYCLES"):
            return n
    return outputs[0] if outputs else None


def surface_description(material):
    """The description of what feeds the Material Output's Surface."""
    tree = material.node_tree if material.use_nodes else None
    output = output_node(tree) if tree else None
    if output is None:
        raise UserError(f"material '{material.name}': {NOTHING_TO_MAP} (it has no Material Output node)")
    return _from_link(output.inputs["Surface"])
