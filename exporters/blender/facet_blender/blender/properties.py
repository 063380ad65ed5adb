"""PropertyGroups built at register time from the property plan (core/props.py).

Each `Group` of the plan becomes one `bpy.types.PropertyGroup` subclass made with
`type()`, each `Field` one `bpy.props` property carrying the catalog's default, range
and documentation (as the tooltip). This works the same in Blender 3.4 and 4.x.
"""

import bpy

from ..core import props as plan


def _bpy_property(f, classes):
    """The bpy.props definition of one Field."""
    kw = {"name": f.label, "description": f.doc}
    if f.kind == "float":
        kw.update(default=f.default, precision=4, step=1)
        if f.min is not None:
            kw["min"] = f.min
        if f.max is not None:
            kw["max"] = f.max
        if f.soft_max is not None:
            kw["soft_max"] = f.soft_max
        return bpy.props.FloatProperty(**kw)
    if f.kind == "color":
        # COLOR is scene-linear, as facet's colours are.
        kw.update(subtype="COLOR", size=3, default=tuple(f.default), precision=4)
        if f.min is not None:
            kw["min"] = f.min
        if f.max is not None:
            kw["max"] = f.max
        if f.soft_max is not None:
            kw["soft_max"] = f.soft_max
        return bpy.props.FloatVectorProperty(**kw)
    if f.kind == "vector":
        return bpy.props.FloatVectorProperty(subtype="XYZ", size=3, default=tuple(f.default), **kw)
    if f.kind == "bool":
        return bpy.props.BoolProperty(default=bool(f.default), **kw)
    if f.kind == "enum":
        return bpy.props.EnumProperty(items=[tuple(i) for i in f.items], default=f.default, **kw)
    if f.kind == "string":
        return bpy.props.StringProperty(default=f.default, **kw)
    if f.kind == "group":
        return bpy.props.PointerProperty(type=classes[f.group.name], **kw)
    raise ValueError(f"unknown field kind {f.kind}")


def register_plan(material_plan):
    """Registers one PropertyGroup per group of the plan (nested first) and
    `bpy.types.Material.facet`. Returns the classes, for `unregister_classes`."""
    classes, registered = {}, []
    try:
        for group in plan.groups_in_registration_order(material_plan):
            annotations = {f.id: _bpy_property(f, classes) for f in group.fields}
            cls = type(group.name, (bpy.types.PropertyGroup,),
                       {"__annotations__": annotations, "__doc__": group.doc or group.label,
                        "__module__": __name__})
            bpy.utils.register_class(cls)
            registered.append(cls)
            classes[group.name] = cls
        bpy.types.Material.facet = bpy.props.PointerProperty(
            type=classes[material_plan.name], name="facet",
            description="facet material settings (diffuse and specular models of the facet catalog)")
        bpy.types.Material.facet_textures = bpy.props.StringProperty(
            name="facet Textures", default="", options={"HIDDEN"},
            description="The images of the facet parameters that Convert Blender Material found "
                        "(core/textures.py bindings, JSON); exported with the scene")
    except Exception:
        unregister_classes(registered)
        raise
    return registered


def unregister_classes(registered):
    if hasattr(bpy.types.Material, "facet"):
        del bpy.types.Material.facet
    if hasattr(bpy.types.Material, "facet_textures"):
        del bpy.types.Material.facet_textures
    for cls in reversed(registered):
        try:
            bpy.utils.unregister_class(cls)
        except RuntimeError:
            pass


# ----------------------------------------------------------------------------- values

def read(pg, group):
    """The values of a PropertyGroup instance as plain nested dicts (see core/props)."""
    values = {}
    for f in group.fields:
        v = getattr(pg, f.id)
        if f.kind == "group":
            values[f.id] = read(v, f.group)
        elif f.kind in ("color", "vector"):
            values[f.id] = [float(x) for x in v]
        else:
            values[f.id] = v
    return values


def write(pg, group, values):
    """Sets the fields of `values` (others are left alone)."""
    for f in group.fields:
        if f.id not in values:
            continue
        if f.kind == "group":
            write(getattr(pg, f.id), f.group, values[f.id])
        elif f.kind in ("color", "vector"):
            setattr(pg, f.id, tuple(float(x) for x in values[f.id]))
        else:
            setattr(pg, f.id, values[f.id])
