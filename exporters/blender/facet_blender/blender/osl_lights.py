"""Generated OSL that follows the scene's lights.

facet's OSL takes each light as Script-node inputs (core/scene.py, "lights as OSL
drivers"). `drive` puts a driver on each of them that reads the light object, so
moving, rotating, recolouring or dimming a light (or a spot's size) needs no
regeneration. What drivers cannot follow, a light added, removed, hidden from the
render or changed to another type, `changed_lights` finds by comparing the lights the
shader was generated for (kept on the Script node) with the scene's.
"""

import json

from ..core import scene as core_scene
from . import scene_data

LIGHTS_PROPERTY = "facet_lights"      # on the Script node: JSON [[name, facet type], ...]


def signature(sources):
    """[[name, facet light type], ...] of light_sources' lights, in the shader's order."""
    return [[name, light["type"]] for name, _, light in sources]


def _remove_drivers(tree, node):
    data = tree.animation_data
    if data is None:
        return
    prefix = f'nodes["{node.name}"].'
    for fcurve in [f for f in data.drivers if f.data_path.startswith(prefix)]:
        data.drivers.remove(fcurve)


def _drive_component(socket, index, expression, variables, obj):
    fcurve = socket.driver_add("default_value", index) if index is not None else socket.driver_add("default_value")
    driver = fcurve.driver
    driver.type = "SCRIPTED"
    for v in list(driver.variables):
        driver.variables.remove(v)
    for name, path in variables.items():
        var = driver.variables.new()
        var.name, var.type = name, "SINGLE_PROP"
        var.targets[0].id_type = "OBJECT"
        var.targets[0].id = obj
        var.targets[0].data_path = path
    driver.expression = expression
    return fcurve


def drive(tree, script, sources):
    """Drivers on `script`'s light inputs from the light objects of `sources`
    (scene_data.light_sources, the order the shader was generated in), replacing any
    the node had; records the lights' signature on the node. Returns notes."""
    _remove_drivers(tree, script)
    notes = []
    for index, (name, obj, _) in enumerate(sources):
        if obj is None:
            notes.append(f"light '{name}' is an instance (no object of its own to drive the shader from): "
                         f"the shader keeps its position, colour and power as generated; regenerate after "
                         f"changing it")
            continue
        for input_name, components in core_scene.light_drivers(obj.data.type, index).items():
            socket = script.inputs.get(input_name)
            if socket is None:
                notes.append(f"light '{name}': the shader has no input '{input_name}'; it keeps the value "
                             f"generated (regenerate after changing the light)")
                continue
            array = len(components) > 1 or socket.type in ("VECTOR", "RGBA")
            for k, (expression, variables) in enumerate(components):
                _drive_component(socket, k if array else None, expression, variables, obj)
    script[LIGHTS_PROPERTY] = json.dumps(signature(sources))
    return notes


def osl_node(material):
    """The material's facet OSL Script node, or None."""
    from .osl import NODE_NAME
    tree = material.node_tree if material is not None and material.use_nodes else None
    node = tree.nodes.get(NODE_NAME) if tree is not None else None
    return node if node is not None and node.type == "SCRIPT" else None


def changed_lights(material, depsgraph):
    """None when the material has no facet OSL node recording its lights, or the scene
    renders those lights; else a message naming what changed since Generate OSL."""
    node = osl_node(material)
    stored = node.get(LIGHTS_PROPERTY) if node is not None else None
    if stored is None:
        return None
    then = [tuple(x) for x in json.loads(stored)]
    sources, _ = scene_data.light_sources(depsgraph)
    now = [tuple(x) for x in signature(sources)]
    if sorted(then) == sorted(now):
        return None
    then_names, now_names = {n: t for n, t in then}, {n: t for n, t in now}
    parts = []
    added = [n for n in now_names if n not in then_names]
    removed = [n for n in then_names if n not in now_names]
    retyped = [n for n in now_names if n in then_names and now_names[n] != then_names[n]]
    for words, names in (("added", added), ("removed or hidden from the render", removed),
                         ("changed type", retyped)):
        if names:
            parts.append(f"{words}: " + ", ".join(f"'{n}'" for n in sorted(names)))
    return "Lights changed since Generate OSL (" + "; ".join(parts) + "): regenerate for the shader to see them"
