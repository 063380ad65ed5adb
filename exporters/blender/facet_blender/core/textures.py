"""Image textures: Blender's Image Texture and Normal Map nodes -> facet's textured
parameters (docs/textures.md), derived images, and texture files.

The Blender layer describes what feeds a linked socket as plain data ("sources", see
`blender/nodes.py`):

    {"type": "TEX_IMAGE", "name": node name, "output": "Color" | "Alpha",
     "image": {"name", "colorspace", "source", "filepath", "packed", "exists", "is_float"} | None,
     "interpolation": "Linear" | "Closest" | "Cubic" | "Smart", "extension": "REPEAT" | "EXTEND" |
     "MIRROR" | "CLIP", "projection": "FLAT" | ..., "links": {"Vector": source | None}}
    {"type": "SEPARATE_COLOR" | "SEPRGB", "mode": "RGB" | "HSV" | "HSL", "output": "Red" | "R" | ...,
     "links": {"Color" | "Image": source}}
    {"type": "MAPPING", "vector_type": "POINT" | ..., "inputs": {"Location", "Rotation", "Scale"},
     "linked": [...], "links": {"Vector": source | None}}
    {"type": "UVMAP", "uv_map": name}   {"type": "TEX_COORD", "output": "UV" | ...}
    {"type": "NORMAL_MAP", "space": "TANGENT" | ..., "uv_map": name, "inputs": {"Strength"},
     "linked": [...], "links": {"Color": source}}
    {"type": "MIX" | "MIX_RGB", "data_type": "RGBA" | ..., "blend_type": "MULTIPLY" | ..., "clamp": bool,
     "factor": number, "factor_linked": bool, "a": source | None, "a_value": RGBA, "b": ..., "b_value": ...}
    {"type": "MATH", "operation": "MULTIPLY" | ..., "clamp": bool, "values": [v0, v1], "links": [src0, src1]}
    {"type": "VERTEX_COLOR", "layer": name}
    any other node: {"type", "name", "output"}

How each setting maps (Cycles' Image Texture node, measured in /work/texconv/FINDINGS.md B4):

| Blender | facet |
|---|---|
| image colour space sRGB / Non-Color, Raw, Linear (Rec.709) | colorspace "srgb" / "linear" (others: approximate, reported) |
| interpolation Closest / Linear / Cubic, Smart | filter "nearest" / "bilinear" / "bilinear" (reported) |
| extension REPEAT / EXTEND / MIRROR / CLIP | wrap "repeat" / "clamp" / "mirror" / "clamp" (CLIP is black outside: reported) |
| Vector unlinked, UV Map node, Texture Coordinate UV | uv: the material's UV map list (`uv_maps`), set 0 or 1 |
| Mapping node (Point/Vector, rotation about Z only) | transform (exact, `mapping_transform`) |
| Separate Color / Separate RGB (RGB mode) Red/Green/Blue | channel "r" / "g" / "b" |
| Image Texture Alpha output | channel "a" |
| Normal Map node (tangent space, Strength 1) | "normal_map" {texture, uv, filter, wrap, transform, green "up", strength} |
| … into a Principled BSDF's Coat Normal | "coat_normal_map" {…the same} (glTF's clearcoatNormalTexture) |
| Mix (Multiply, factor 1) of an image and a colour; Math Multiply of a channel and a number | the image's factor × that colour or number ("scale" of the spec; Blender's glTF importer makes these for baseColorFactor, emissiveFactor, metallicFactor and roughnessFactor beside a texture) |
| Color Attribute's Color into a colour input, alone or through a Mix (Multiply, factor 1) with an image | "vertex_color": true (glTF's COLOR_0; Blender's glTF importer's wiring), with or without the image; the mesh's colour attribute goes out as "colors" (`blender/scene_data.py`) |

Blender's UV has v up, facet's (glTF's) v down: the exporter writes a mesh's texture
coordinates as (u, 1 − v_blender) (`core.scene.mesh_objects`), which puts the image where
Cycles puts it. Under Linear interpolation Cycles filters an sRGB image's encoded values
and decodes afterwards, facet decodes each texel first (glTF): exact with Closest or a
Non-Color image, reported as approximate otherwise.

A parameter that is a function of the image rather than the image itself (a Glossy BSDF's
GGX α = Roughness², Beckmann's m) is baked: the image's texels go through the function (in
linear values) into a 16-bit PNG written beside the export (`bake`). A Principled BSDF's
images need no bake: its gltf_pbr lobe takes Base Color, Metallic, Roughness and Specular IOR
Level as the images themselves, as glTF does (`convert.principled_bsdf`), which is what
`facet import-gltf` reads from a glTF file.
"""

import array
import json
import math
import re
import struct
import sys
import zlib

from . import UserError
from .coords import clean_float, clean_vector

FILTERS = {"Closest": "nearest", "Linear": "bilinear", "Cubic": "bilinear", "Smart": "bilinear"}
WRAPS = {"REPEAT": "repeat", "EXTEND": "clamp", "MIRROR": "mirror", "CLIP": "clamp"}
LINEAR_SPACES = {"Non-Color", "Raw", "Linear", "Linear Rec.709", "Linear Rec.2020", "scene_linear",
                 "Linear CIE-XYZ E", "Linear CIE-XYZ D65"}
SRGB_SPACES = {"sRGB"}
CHANNELS = {"Red": "r", "R": "r", "Green": "g", "G": "g", "Blue": "b", "B": "b"}
# Image formats facet reads (docs/textures.md: stb_image, PNM/HDR/PIC refused).
READABLE = {".png", ".jpg", ".jpeg", ".tga", ".bmp", ".psd", ".gif"}
UNMAPPABLE_HINT = "facet maps only Image Texture nodes (through Separate Color, Mapping and UV Map nodes)"


def node_label(src):
    """ "'Noise Texture' (TEX_NOISE)": a node's name and type, as messages show them."""
    return f"'{src.get('name') or src.get('type')}' ({src.get('type')})"


class Context:
    """Where a source is read: the material's name and the socket, for messages, and
    the notes list of a convert.Result (`note(level, message)`)."""

    def __init__(self, material, socket, note):
        self.material, self.socket, self.note = material, socket, note

    def where(self, src):
        return f"material '{self.material}': node {node_label(src)} feeding '{self.socket}'"


# ----------------------------------------------------------------------------- Mapping node

def mapping_transform(src):
    """facet's KHR_texture_transform of a Mapping node, or None when it has no exact one.

    Blender's Point mapping is out = Rz(θ)(S ⊙ uv_b) + L in Blender's UV (v_b = 1 − v).
    Sampled at facet's (u′, 1 − out_v) this is
        u′ = cos θ s_u u + sin θ s_v v + (L_u − sin θ s_v)
        v′ = −sin θ s_u u + cos θ s_v v + (1 − cos θ s_v − L_v),
    KHR_texture_transform's form with rotation θ, scale (s_u, s_v) and that offset.
    (Cycles 4.5, kernel/svm/mapping_util.h, svm_mapping.) Vector mapping is Point without
    L; Texture mapping, R(−θ)(uv − L)/S, is Point's
    inverse (exact when the scale is uniform or θ = 0). Rotations about X or Y, other
    Texture mappings and the Normal type have no such form."""
    kind = src.get("vector_type", "POINT")
    if kind not in ("POINT", "VECTOR", "TEXTURE") or src.get("linked"):
        return None
    inputs = src.get("inputs", {})
    loc = [float(x) for x in inputs.get("Location", (0.0, 0.0, 0.0))]
    rot = [float(x) for x in inputs.get("Rotation", (0.0, 0.0, 0.0))]
    scale = [float(x) for x in inputs.get("Scale", (1.0, 1.0, 1.0))]
    if rot[0] != 0.0 or rot[1] != 0.0:
        return None
    if kind == "VECTOR":
        loc = [0.0, 0.0, 0.0]
    if kind == "TEXTURE":
        # Texture is the inverse: out = R(−θ)(uv − L) / S. With a uniform scale (or no
        # rotation) that is Point with scale 1/S, rotation −θ, location −R(−θ)L / S.
        if 0.0 in scale[:2] or (rot[2] != 0.0 and scale[0] != scale[1]):
            return None
        c, s = math.cos(-rot[2]), math.sin(-rot[2])
        loc = [-(c * loc[0] - s * loc[1]) / scale[0], -(s * loc[0] + c * loc[1]) / scale[1], 0.0]
        rot = [0.0, 0.0, -rot[2]]
        scale = [1.0 / scale[0], 1.0 / scale[1], 1.0]
    theta, su, sv = float(rot[2]), float(scale[0]), float(scale[1])
    s, c = math.sin(theta), math.cos(theta)
    out = {"offset": [float(loc[0]) - s * sv, 1.0 - c * sv - float(loc[1])], "scale": [su, sv], "rotation": theta}
    if out == {"offset": [0.0, 0.0], "scale": [1.0, 1.0], "rotation": 0.0}:
        return {}
    return out


def _vector(src, ctx, image_node):
    """(uv map name, transform) of an Image Texture's Vector input; None when it is not
    a UV (a warning says why)."""
    if src is None:
        return "", {}
    kind = src.get("type")
    if kind == "UVMAP":
        return src.get("uv_map", ""), {}
    if kind == "TEX_COORD" and src.get("output") == "UV":
        return "", {}
    if kind == "MAPPING":
        inner = src.get("links", {}).get("Vector")
        if inner is None:
            ctx.note("ignored", f"{ctx.where(image_node)}: its Mapping node {node_label(src)} has no Vector input "
                                f"linked (a constant coordinate); the texture is not used")
            return None
        base = _vector(inner, ctx, image_node)
        if base is None:
            return None
        transform = mapping_transform(src)
        if transform is None:
            ctx.note("approximate", f"{ctx.where(image_node)}: Mapping node {node_label(src)} "
                                    f"({src.get('vector_type', 'POINT')}, rotation about X/Y, or linked inputs) has "
                                    f"no exact KHR_texture_transform; the texture is used without it")
            transform = {}
        if base[1]:
            ctx.note("approximate", f"{ctx.where(image_node)}: chained Mapping nodes; only the last is used")
        return base[0], transform
    ctx.note("ignored", f"{ctx.where(image_node)}: its Vector comes from node {node_label(src)} "
                        f"(output '{src.get('output')}'), not a UV map; the texture is not used")
    return None


# ----------------------------------------------------------------------------- Image Texture

def _image(src, ctx):
    """The image settings of an Image Texture node: a dict of facet keys (without
    channel) plus "image" and "uv_map"; None (with a warning) when it cannot be used.
    A missing image file is an error naming the material and the node."""
    image = src.get("image")
    if image is None:
        ctx.note("ignored", f"{ctx.where(src)}: the Image Texture has no image; its unlinked value is used")
        return None
    if image.get("source", "FILE") == "FILE" and not image.get("packed") and not image.get("exists", True):
        raise UserError(f"{ctx.where(src)}: image '{image['name']}' reads '{image.get('filepath')}', "
                        f"which does not exist: fix the path or pack the image")
    if image.get("source", "FILE") not in ("FILE", "GENERATED"):
        ctx.note("ignored", f"{ctx.where(src)}: image '{image['name']}' is a {image.get('source')} image "
                            f"(facet maps still images only); its unlinked value is used")
        return None
    if src.get("projection", "FLAT") != "FLAT":
        ctx.note("ignored", f"{ctx.where(src)}: projection {src.get('projection')} is not a UV lookup; "
                            f"its unlinked value is used")
        return None
    vector = _vector(src.get("links", {}).get("Vector"), ctx, src)
    if vector is None:
        return None
    spec = {"image": image["name"], "uv_map": vector[0]}
    space = image.get("colorspace", "sRGB")
    if space in SRGB_SPACES:
        spec["colorspace"] = "srgb"
    elif space in LINEAR_SPACES:
        spec["colorspace"] = "linear"
    else:
        spec["colorspace"] = "srgb" if "srgb" in space.lower() else "linear"
        ctx.note("approximate", f"{ctx.where(src)}: image colour space '{space}' is read as {spec['colorspace']}")
    interpolation = src.get("interpolation", "Linear")
    spec["filter"] = FILTERS.get(interpolation, "bilinear")
    if interpolation in ("Cubic", "Smart"):
        ctx.note("approximate", f"{ctx.where(src)}: {interpolation} interpolation has no facet filter; "
                                f"bilinear is used")
    extension = src.get("extension", "REPEAT")
    spec["wrap"] = WRAPS.get(extension, "repeat")
    if extension == "CLIP":
        ctx.note("approximate", f"{ctx.where(src)}: extension CLIP (black outside the image) has no facet "
                                f"wrap; clamp is used")
    if spec["colorspace"] == "srgb" and spec["filter"] == "bilinear" and not image.get("is_float"):
        ctx.note("approximate", f"{ctx.where(src)}: Cycles filters an sRGB image before decoding it, facet "
                                f"decodes each texel first (glTF); equal with Closest interpolation or Non-Color")
    if vector[1]:
        spec["transform"] = vector[1]
    return spec


def _constant_factor(src, ctx, want):
    """(the linked side's source, its factor) of a Mix (Multiply, factor 1) of one linked input
    and an unlinked colour, or of a Math Multiply of one linked input and a number: what
    Blender's glTF importer puts between an image and a Principled BSDF for a glTF factor.
    None (warned) for any other Mix or Math node."""
    kind = src.get("type")
    if kind in ("MIX", "MIX_RGB"):
        ok = (src.get("data_type") == "RGBA" and src.get("blend_type") == "MULTIPLY" and not src.get("factor_linked")
              and src.get("factor") == 1.0 and (src.get("a") is None) != (src.get("b") is None))
        linked, value = (src.get("a"), src.get("b_value")) if src.get("a") is not None else (src.get("b"),
                                                                                            src.get("a_value"))
        if ok and isinstance(value, (list, tuple)) and (not src.get("clamp") or max(value[:3]) <= 1.0):
            return linked, [float(c) for c in value[:3]]
    elif kind == "MATH":
        links, values = src.get("links") or [None, None], src.get("values") or [None, None]
        ok = src.get("operation") == "MULTIPLY" and (links[0] is None) != (links[1] is None)
        k = 1 if links[0] is not None else 0
        if ok and isinstance(values[k], (int, float)) and (not src.get("clamp") or 0.0 <= values[k] <= 1.0):
            return links[1 - k], float(values[k])
    ctx.note("ignored", f"{ctx.where(src)}: {UNMAPPABLE_HINT}, and Mix (Multiply) or Math (Multiply) nodes "
                        f"that scale one by a constant; its unlinked value is used")
    return None


def _times(a, b):
    """A factor times a factor (numbers or RGB lists)."""
    if isinstance(a, list) or isinstance(b, list):
        a3 = a if isinstance(a, list) else [a] * 3
        b3 = b if isinstance(b, list) else [b] * 3
        return [x * y for x, y in zip(a3, b3)]
    return a * b


def _vertex_color_product(src):
    """(the other side's source, the Color Attribute source) of a Mix (Multiply, factor 1) of a
    Color Attribute node's Color and another linked source, as Blender's glTF importer wires
    COLOR_0 beside a base colour texture ("Mix Vertex Color"); None for any other node."""
    if src.get("type") not in ("MIX", "MIX_RGB") or src.get("data_type") != "RGBA" or \
            src.get("blend_type") != "MULTIPLY" or src.get("factor_linked") or src.get("factor") != 1.0:
        return None
    a, b = src.get("a"), src.get("b")
    if a is None or b is None:
        return None
    for mine, other in ((a, b), (b, a)):
        if mine.get("type") == "VERTEX_COLOR" and mine.get("output", "Color") == "Color" and \
                other.get("type") != "VERTEX_COLOR":
            return other, mine
    return None


def _vertex_color_spec(src, want, ctx):
    """The spec of a Color Attribute node's Color feeding a colour socket: facet's
    "vertex_color" without an image (the mesh's colour attribute `src["layer"]`, "" for the
    render one). None (warned) for a number socket or the Alpha output."""
    if want != "color" or src.get("output", "Color") != "Color":
        ctx.note("ignored", f"{ctx.where(src)}: facet's vertex colour multiplies colours only (its Color output "
                            f"into a colour input); its unlinked value is used")
        return None
    return {"vertex_color": True, "layer": src.get("layer", "")}


def texture_of(src, want, ctx):
    """The texture spec of the source feeding a socket, or None (warned) when facet has
    no equivalent. `want` is "color" or "number". A constant factor between the image and the
    socket (a Mix or Math node multiplying it) is the spec's "scale" (a number or an RGB list).
    A Color Attribute node, alone or multiplying an image (a Mix, Multiply, factor 1), is the
    spec's "vertex_color" (glTF's COLOR_0; docs/textures.md, "Vertex colours"): a spec without
    "image" is the vertex colour alone."""
    kind = src.get("type")
    if kind == "VERTEX_COLOR":
        return _vertex_color_spec(src, want, ctx)
    product = _vertex_color_product(src)
    if product is not None:
        if _vertex_color_spec(product[1], want, ctx) is None:
            return None
        spec = texture_of(product[0], want, ctx)
        if spec is None:
            return None
        if spec.get("vertex_color"):
            ctx.note("ignored", f"{ctx.where(src)}: a vertex colour times a vertex colour; facet multiplies by one")
            return None
        return dict(spec, vertex_color=True, layer=product[1].get("layer", ""))
    if kind in ("MIX", "MIX_RGB", "MATH"):
        found = _constant_factor(src, ctx, want)
        if found is None:
            return None
        spec = texture_of(found[0], want, ctx)
        if spec is not None:
            spec["scale"] = _times(spec.get("scale", 1.0), found[1])
        return spec
    channel = None
    if kind in ("SEPARATE_COLOR", "SEPRGB"):
        if src.get("mode", "RGB") != "RGB":
            ctx.note("ignored", f"{ctx.where(src)}: {src.get('mode')} mode has no facet channel; "
                                f"its unlinked value is used")
            return None
        channel = CHANNELS.get(src.get("output"))
        links = src.get("links", {})
        inner = links.get("Color") or links.get("Image")
        if inner is None:
            ctx.note("ignored", f"{ctx.where(src)}: nothing feeds it; its unlinked value is used")
            return None
        if inner.get("type") != "TEX_IMAGE" or inner.get("output") != "Color":
            ctx.note("ignored", f"{ctx.where(inner)}: {UNMAPPABLE_HINT}; its unlinked value is used")
            return None
        src = inner
        if want == "color":
            ctx.note("approximate", f"{ctx.where(src)}: one channel of an image feeds a colour; "
                                    f"facet reads its red, green and blue")
            channel = None
    elif kind != "TEX_IMAGE":
        ctx.note("ignored", f"{ctx.where(src)}: {UNMAPPABLE_HINT}; its unlinked value is used")
        return None
    spec = _image(src, ctx)
    if spec is None:
        return None
    if channel is None:
        if src.get("output") == "Alpha":
            channel = "a"
        elif want == "color":
            channel = "rgb"
        else:
            channel = "r"
            ctx.note("approximate", f"{ctx.where(src)}: Blender turns the colour into a number by its "
                                    f"luminance, facet reads the red channel (equal for grey images); "
                                    f"use Separate Color to choose a channel")
    spec["channel"] = channel
    return spec


NORMAL_KEYS = ("normal_map", "coat_normal_map")   # material-level normal maps: the lobes', the coat's


def normal_map_of(src, ctx, key="normal_map"):
    """The `key` binding (normal_map; coat_normal_map from a Coat Normal) of the source feeding
    a BSDF's Normal input, or None."""
    if src.get("type") != "NORMAL_MAP":
        what = "Bump nodes (height maps)" if src.get("type") == "BUMP" else UNMAPPABLE_HINT
        ctx.note("ignored", f"{ctx.where(src)}: facet maps Normal Map nodes only, not {what}; "
                            f"the normal is the mesh's")
        return None
    if src.get("space", "TANGENT") != "TANGENT":
        ctx.note("ignored", f"{ctx.where(src)}: {src.get('space')} space normal maps have no facet "
                            f"equivalent (tangent space only); the normal is the mesh's")
        return None
    strength = float(src.get("inputs", {}).get("Strength", 1.0))
    if "Strength" in src.get("linked", ()):
        ctx.note("approximate", f"{ctx.where(src)}: its Strength is linked; its unlinked value "
                                f"{strength:.3g} is used")
    inner = src.get("links", {}).get("Color")
    if inner is None:
        ctx.note("ignored", f"{ctx.where(src)}: no image feeds its Color; the normal is the mesh's")
        return None
    spec = texture_of(inner, "color", ctx)
    if spec is None:
        return None
    if spec["colorspace"] != "linear":
        ctx.note("approximate", f"{ctx.where(inner)}: a normal map image should be Non-Color; Blender decodes "
                                f"this one as sRGB, facet reads its values as stored")
    if src.get("uv_map", "") != spec["uv_map"]:
        ctx.note("approximate", f"{ctx.where(src)}: its tangents come from UV map '{src.get('uv_map')}', the "
                                f"image from '{spec['uv_map']}'; facet uses the image's")
    if strength != 1.0:
        # Cycles 4.5 (kernel/svm/tex_coord.h, svm_node_normal_map, as shipped in bpy 4.5's
        # addons_core/cycles/source): tangent-space c = 2·rgb − 1 becomes (s·c_x, s·c_y,
        # mix(1, c_z, clamp(s, 0, 1))) before normalizing; glTF's normalTexture.scale gives
        # (s·c_x, s·c_y, c_z). (Cycles 3.x blended world-space normals instead:
        # normalize(N + (N_mapped − N)·s).) The two agree at s = 1 only.
        ctx.note("approximate", f"{ctx.where(src)}: Strength {strength:.3g}: Blender scales the tangent-space "
                                f"x and y and blends z towards 1, facet (glTF's normalTexture.scale) scales x and "
                                f"y only; equal only at Strength 1")
    else:
        ctx.note("exact", f"{ctx.where(src)}: tangent-space normal map, Strength 1 -> {key}")
    spec.pop("colorspace", None)
    spec.pop("channel", None)
    spec["green"] = "up"          # Blender's tangent-space normal maps are OpenGL's (+Y up)
    spec["strength"] = strength
    return spec


# ----------------------------------------------------------------------------- bindings

def binding(path, model, spec, factor=None, derive=None, offset=None):
    """A parameter's texture: `path` of keys in the material JSON (["diffuse", "color"],
    ["specular", "fresnel", "f0"], ["normal_map"]), the lobe's model it was made for, the
    texture spec (image, uv_map and facet's keys; "vertex_color", with or without an image),
    factor, offset (facet's "offset": value = offset + factor·vc·image) and the function baked
    into a derived image (None or {"op": "square"}).

    The spec's "scale" (a constant factor between the image and the socket) goes into the
    factor, or into the derived image's function: (s·v)² for "square"."""
    spec = dict(spec)
    scale = spec.pop("scale", None)
    if scale is not None and derive is None:
        factor = _times(1.0 if factor is None else factor, scale)
    elif scale is not None:
        derive = dict(derive, scale=scale)
    b = {"path": list(path), "model": model, "spec": spec}
    if factor is not None:
        b["factor"] = factor
    if derive is not None:
        b["derive"] = derive
    if offset is not None:
        b["offset"] = offset
    return b


def has_image(b):
    """Whether a binding reads an image (one that takes the vertex colour alone does not)."""
    return b["spec"].get("image") is not None


def unmapped_values(material_json):
    """The key paths ("diffuse.color") of the values the add-on cannot hold yet: those that take
    the vertex colour ("vertex_color": true, with or without an image) or an "offset"
    (docs/textures.md, "Vertex colours"). Its panel and bindings have no place for either, so a
    material with one is refused rather than imported without it."""
    found = []

    def walk(node, path):
        for key, value in _items(node):
            if isinstance(value, dict) and (value.get("vertex_color") or "offset" in value) and \
                    ("texture" in value or "vertex_color" in value):
                found.append(key_path(path + [key]))
            elif isinstance(value, (dict, list)):
                walk(value, path + [key])
    walk(material_json, [])
    return found


def _items(node):
    """(key, value) of an object, (index, value) of a list (a material's "layers")."""
    return node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()


def key_path(path):
    """A path of keys and list indices as facet's messages write it: "layers[1].weight"."""
    text = ""
    for key in path:
        text += f"[{key}]" if isinstance(key, int) else ("." if text else "") + key
    return text


def model_at(material_json, path):
    """The lobe or layer object a parameter's path lies in (["specular", "fresnel", "f0"]: the
    specular lobe; ["layers", 1, "weight"]: the second layer), or {}."""
    node = material_json.get(path[0]) if isinstance(material_json, dict) else None
    if path[0] == "layers" and len(path) > 2:
        node = node[path[1]] if isinstance(node, list) and path[1] < len(node) else None
    return node if isinstance(node, dict) else {}


def split(material_json):
    """(the material JSON with every {"texture": …} replaced by its factor, or left out so
    that the default applies, [(key path, texture object), …]): what a material file's
    textures become in the add-on (numbers in the panel, bindings beside them)."""
    found = []

    def walk(node, path):
        out = {} if isinstance(node, dict) else [None] * len(node)
        for key, value in _items(node):
            if isinstance(value, dict) and "texture" in value:
                found.append((path + [key], value))
                if "factor" in value and key not in NORMAL_KEYS:
                    out[key] = value["factor"]
            elif isinstance(value, (dict, list)):
                out[key] = walk(value, path + [key])
            else:
                out[key] = value
        return out
    return walk(material_json, []), found


def binding_of_json(path, tex, model, image_name):
    """The binding of a texture object read from a material file (`split`). Its UV set is
    kept as "" (set 0: the mesh's active render UV map) or "#1" (the mesh's second UV map)."""
    spec = {"image": image_name, "uv_map": "#1" if tex.get("uv", 0) == 1 else ""}
    for key in ("channel", "colorspace", "filter", "wrap", "transform", "green", "strength"):
        if key in tex:
            spec[key] = tex[key]
    return binding(path, model, spec, tex.get("factor"))


def dumps(bindings):
    return json.dumps(bindings, sort_keys=True)


def loads(text, material=""):
    if not text:
        return []
    try:
        data = json.loads(text)
    except ValueError as e:
        raise UserError(f"material '{material}': its texture settings are not valid JSON ({e})")
    return data if isinstance(data, list) else []


def uv_maps(bindings, material=""):
    """The UV map names a material's textures read, in order: set 0, then set 1. "" is the
    mesh's active render UV map (an Image Texture with nothing in its Vector)."""
    names = []
    for b in bindings:
        if not has_image(b):
            continue
        name = b["spec"].get("uv_map", "")
        if name not in names:
            names.append(name)
    if "#1" in names:                     # a material file's set 1 stays set 1
        names = [n for n in names if n != "#1"]
        names = (names or [""]) + ["#1"]
    if len(names) > 2:
        raise UserError(f"material '{material}': its textures read {len(names)} UV maps "
                        f"({', '.join(repr(n or 'the active render one') for n in names)}); facet meshes have two")
    return names


def frame_uv_map(material_json):
    """The UV map whose tangent frame a material reads besides its textures' ("" the active
    render one), or None: glTF's anisotropy (an anisotropic gltf_pbr lobe) turns from the mesh's
    tangent (KHR_materials_anisotropy), which facet computes from texture coordinates set 0."""
    lobe = (material_json or {}).get("specular") or {}
    strength = lobe.get("anisotropy_strength", 0)
    if lobe.get("model") == "gltf_pbr" and (isinstance(strength, dict) or strength > 0):
        return ""
    return None


MATERIAL_KEYS = ("normal_map", "coat_normal_map", "emission", "ambient", "alpha")   # material-level keys a texture may fill


def exported(bindings, material_keys=None):
    """The bindings whose images an export writes: a material-level one (normal_map,
    emission) only where this facet takes it (`material_keys`; None: all); `apply` says
    what it leaves out."""
    return [b for b in bindings if len(b["path"]) > 1 or material_keys is None or b["path"][0] in material_keys]


def file_key(b):
    """What makes a texture file distinct: the image and the function baked into it."""
    return (b["spec"]["image"], json.dumps(b.get("derive"), sort_keys=True), b["spec"].get("channel")
            if b.get("derive") else None)


def apply(material_json, bindings, files, material_keys=None):
    """The material JSON with its textured parameters; returns (JSON, notes).

    `files` maps `file_key(b)` to (relative file name, colour space override or None).
    A binding whose lobe model changed since the conversion, or of a material-level key
    this facet takes no texture on (`material_keys`, None: all), is left out and noted."""
    data = json.loads(json.dumps(material_json))
    notes = []
    names = uv_maps(bindings, data.get("name", ""))
    for b in bindings:
        path = b["path"]
        section = path[0]
        if len(path) == 1 and material_keys is not None and section not in material_keys:
            what = {"normal_map": "its normal map", "coat_normal_map": "its coat's normal map",
                    "emission": "an emission map"}.get(section, f"a {section} map")
            needs = (f"the material key '{section}' or mesh 'tangents'" if section in NORMAL_KEYS
                     else f"a texture on '{section}'")
            notes.append(f"material '{data.get('name')}': this facet cannot take {what} (image "
                         f"'{b['spec']['image']}'): its schemas lack {needs}; it is not exported"
                         + ("" if section in NORMAL_KEYS else ", the unlinked value is"))
            continue
        if len(path) > 1 and model_at(data, path).get("model") != b.get("model"):
            where = key_path(path[:2] if section == "layers" else path[:1])
            notes.append(f"material '{data.get('name')}': the texture of {key_path(path)} was made for the "
                         f"{where} model {b.get('model')}; the model is now "
                         f"{model_at(data, path).get('model', 'none')}, so it is left out")
            continue
        spec = b["spec"]
        if not has_image(b):
            tex = {"vertex_color": True}
            for key in ("factor", "offset"):
                if b.get(key) is not None:
                    tex[key] = clean_vector(b[key]) if isinstance(b[key], (list, tuple)) else clean_float(b[key])
            _put(data, path, tex)
            continue
        name, space = files[file_key(b)]
        tex = {"texture": name}
        for key in ("channel", "colorspace"):
            if section not in NORMAL_KEYS and spec.get(key) is not None:
                tex[key] = spec[key]
        if space and section not in NORMAL_KEYS:
            tex["colorspace"] = space
        if b.get("derive"):
            tex["channel"] = "rgb" if spec.get("channel") == "rgb" or b["derive"].get("rgb") else "r"
            tex["colorspace"] = "linear"
        for key in ("filter", "wrap"):
            if spec.get(key) is not None:
                tex[key] = spec[key]
        tex["uv"] = names.index(spec.get("uv_map", ""))
        if spec.get("transform"):
            tex["transform"] = spec["transform"]
        for key in ("green", "strength"):
            if section in NORMAL_KEYS and spec.get(key) is not None:
                tex[key] = spec[key]
        for key in ("factor", "offset"):     # Blender's float32 values written as typed
            f = b.get(key)
            if f is not None:
                tex[key] = clean_vector(f) if isinstance(f, (list, tuple)) else clean_float(f)
        if spec.get("vertex_color"):
            tex["vertex_color"] = True
        _put(data, path, tex)
    return data, notes


def _put(data, path, value):
    target = data
    for key in path[:-1]:
        target = target[key] if isinstance(key, int) else target.setdefault(key, {})
    target[path[-1]] = value


def vertex_color_layers(bindings):
    """The colour attributes ("" for the render one) a material's bindings read, in order."""
    layers = []
    for b in bindings:
        if b["spec"].get("vertex_color") and b["spec"].get("layer", "") not in layers:
            layers.append(b["spec"].get("layer", ""))
    return layers


def absolute(material_json, folder):
    """The material JSON with its texture file names made absolute in `folder` (for a
    material file facet reads elsewhere, e.g. to generate OSL)."""
    import os

    def walk(node):
        if isinstance(node, dict):
            return {k: (os.path.join(folder, v) if k == "texture" and isinstance(v, str) else walk(v))
                    for k, v in node.items()}
        if isinstance(node, list):
            return [walk(v) for v in node]
        return node
    return walk(material_json)


# ----------------------------------------------------------------------------- pixels

def srgb_decode(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def _rows_top_first(width, height, pixels, channels):
    """Blender's pixels (rows from the bottom, RGBA floats) as rows from the top."""
    stride = width * channels
    return [pixels[(height - 1 - j) * stride:(height - j) * stride] for j in range(height)]


def png16(width, height, rows, channels):
    """A 16-bit PNG (bytes) of rows from the top, `channels` (3 or 4) floats per pixel in
    [0, 1] (clipped), each stored as round(v·65535): k/255 becomes k·257 exactly."""
    if width < 1 or height < 1:
        raise UserError(f"cannot write a {width}x{height} image")
    raw = bytearray()
    for row in rows:
        samples = array.array("H", (int(round(min(max(v, 0.0), 1.0) * 65535.0)) for v in row))
        if len(samples) != width * channels:
            raise UserError("image row of the wrong length")
        if sys.byteorder == "little":
            samples.byteswap()                        # PNG is big-endian
        raw += b"\x00" + samples.tobytes()

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    color_type = 6 if channels == 4 else 2
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 16, color_type, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(bytes(raw), 6)) + chunk(b"IEND", b""))


def pixels_png(width, height, pixels):
    """A 16-bit RGBA PNG of Blender's `Image.pixels` (RGBA floats, bottom row first)."""
    return png16(width, height, _rows_top_first(width, height, pixels, 4), 4)


CHANNEL_INDEX = {"r": 0, "g": 1, "b": 2, "a": 3}


def bake(width, height, pixels, spec, derive, linear_pixels):
    """A 16-bit RGB PNG of `derive` applied to the channel(s) `spec` reads, in linear values:
    sRGB texels (of `spec`'s colour space) are decoded first unless `linear_pixels`
    (Blender's float images hold linear values already).

    derive {"op": "square", "scale": s (default 1, or one per channel)}: (s·v)², v the channel,
    or the pixel's r, g, b for channel "rgb" (GGX's α = Roughness², Beckmann's m)."""
    decode = spec.get("colorspace") == "srgb" and not linear_pixels
    channel = spec.get("channel", "r")
    if derive.get("op") != "square":
        raise UserError(f"unknown derived image {derive}")
    rows = []
    for row in _rows_top_first(width, height, pixels, 4):
        out = []
        for i in range(width):
            px = row[4 * i:4 * i + 4]
            if channel == "rgb":
                values = [srgb_decode(c) if decode else c for c in px[:3]]
            else:
                k = CHANNEL_INDEX[channel]
                v = px[k]
                v = srgb_decode(v) if decode and k < 3 else v
                values = [v, v, v]
            s = derive.get("scale", 1.0)
            out.extend((sk * v) ** 2 for v, sk in zip(values, s if isinstance(s, list) else [s] * 3))
        rows.append(out)
    return png16(width, height, rows, 3)


def file_name(image_name, extension, derive, taken):
    """A file name for an image beside the export, unique in `taken` (which it joins)."""
    stem = re.sub(r"[^A-Za-z0-9_.-]+", "_", image_name).strip("._") or "image"
    if stem.lower().endswith(extension):
        stem = stem[:-len(extension)]
    if derive:
        stem += "_" + derive["op"]
    name, k = stem + extension, 2
    while name.lower() in taken:
        name, k = f"{stem}_{k}{extension}", k + 1
    taken.add(name.lower())
    return name
