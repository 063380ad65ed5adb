"""A material's node tree read into the plain description core/convert.py maps."""

import bpy

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


def _image_desc(image):
    if image is None:
        return None
    import os
    filepath = bpy.path.abspath(image.filepath, library=image.library) if image.filepath else ""
    return {"name": image.name, "colorspace": image.colorspace_settings.name, "source": image.source,
            "filepath": filepath, "packed": image.packed_file is not None,
            "exists": bool(filepath) and os.path.isfile(filepath), "is_float": bool(image.is_float)}


def _socket_values(node):
    values, linked = {}, []
    for socket in node.inputs:
        value = _value(socket)
        if value is not None:
            values.setdefault(socket.name, value)
        if socket.is_linked:
            linked.append(socket.name)
    return values, linked


def source(socket, depth=0):
    """The plain description of what feeds a (non-shader) input socket, following
    reroutes, for core/textures.py; None when nothing does."""
    if depth > 64:
        raise UserError("the shader node tree is too deep (a cycle?)")
    if not socket.is_linked:
        return None
    link = socket.links[0]
    if getattr(link, "is_muted", False) or not link.is_valid:
        return None
    node = link.from_node
    if node.type == "REROUTE":
        return source(node.inputs[0], depth + 1)
    desc = {"type": "MUTED" if getattr(node, "mute", False) else node.type, "name": node.name,
            "output": link.from_socket.name}
    if node.type == "TEX_IMAGE":
        desc.update(image=_image_desc(node.image), interpolation=node.interpolation,
                    extension=node.extension, projection=node.projection,
                    links={"Vector": source(node.inputs["Vector"], depth + 1)})
    elif node.type in ("SEPARATE_COLOR", "SEPRGB"):
        desc["mode"] = getattr(node, "mode", "RGB")
        desc["links"] = {node.inputs[0].name: source(node.inputs[0], depth + 1)}
    elif node.type == "MAPPING":
        desc["vector_type"] = node.vector_type
        desc["inputs"], linked = _socket_values(node)
        desc["linked"] = [n for n in linked if n != "Vector"]
        desc["links"] = {"Vector": source(node.inputs["Vector"], depth + 1)}
    elif node.type == "UVMAP":
        desc["uv_map"] = node.uv_map
    elif node.type == "NORMAL_MAP":
        desc.update(space=node.space, uv_map=node.uv_map)
        desc["inputs"], linked = _socket_values(node)
        desc["linked"] = [n for n in linked if n != "Color"]
        desc["links"] = {"Color": source(node.inputs["Color"], depth + 1)}
    elif node.type in ("MIX", "MIX_RGB"):
        desc.update(_mix(node, depth))
    elif node.type == "MATH":
        desc.update(operation=node.operation, clamp=bool(node.use_clamp),
                    values=[_value(s) for s in node.inputs[:2]],
                    links=[source(s, depth + 1) for s in node.inputs[:2]])
    elif node.type == "VERTEX_COLOR":
        desc["layer"] = node.layer_name
    return desc


# The Mix node's sockets by data type: its inputs repeat the names Factor, A and B once per type.
_MIX_SOCKETS = {"FLOAT": (0, 2, 3), "VECTOR": (1, 4, 5), "RGBA": (0, 6, 7)}


def _mix(node, depth):
    """A Mix node (4.x ShaderNodeMix, or 3.x MixRGB) as core/textures.py reads it: its blend,
    clamping, factor, and each of A and B as a linked source or an unlinked value."""
    if node.type == "MIX_RGB":
        data_type, clamp = "RGBA", bool(node.use_clamp)
        fac, a, b = node.inputs["Fac"], node.inputs["Color1"], node.inputs["Color2"]
    else:
        data_type, clamp = node.data_type, bool(node.clamp_result)
        fac, a, b = (node.inputs[k] for k in _MIX_SOCKETS.get(node.data_type, (0, 6, 7)))
    return {"data_type": data_type, "blend_type": getattr(node, "blend_type", "MIX"), "clamp": clamp,
            "factor": _value(fac), "factor_linked": fac.is_linked,
            "a": source(a, depth + 1), "a_value": _value(a), "b": source(b, depth + 1), "b_value": _value(b)}


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
        if socket.is_linked and socket.name not in desc["linked"]:
            desc["linked"].append(socket.name)
            src = source(socket, depth + 1)
            if src is not None:
                desc.setdefault("sources", {})[socket.name] = src
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
