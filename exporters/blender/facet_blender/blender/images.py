"""The images of textured facet materials, as files to write beside an export.

Everything is read into memory first (file bytes, packed bytes, or a 16-bit PNG of the
image's pixels), so an export that cannot find an image fails before anything is
written. What facet cannot read as it is (a generated image, an EXR, a format stb_image
does not know), and every derived image (core/textures.py `bake`), becomes a 16-bit
PNG; a file facet reads (PNG, JPEG, TGA, BMP, PSD, GIF) is copied byte for byte.
"""

import os

import bpy

from ..core import UserError, textures

FORMAT_EXTENSIONS = {"PNG": ".png", "JPEG": ".jpg", "TARGA": ".tga", "TARGA_RAW": ".tga", "BMP": ".bmp"}


def _pixels(image, material):
    width, height = image.size
    if width < 1 or height < 1:
        raise UserError(f"material '{material}': image '{image.name}' has no pixels (it could not be loaded"
                        + (f" from '{image.filepath}'" if image.filepath else "") + ")")
    count = len(image.pixels)
    pixels = [0.0] * count
    image.pixels.foreach_get(pixels)
    channels = count // (width * height)
    if channels != 4:                              # RGB or grey: RGBA as pixels_png takes
        if channels not in (1, 3) or count != channels * width * height:
            raise UserError(f"material '{material}': image '{image.name}' has {count} values for "
                            f"{width}x{height} pixels")
        rgba = []
        for k in range(width * height):
            px = pixels[channels * k:channels * (k + 1)]
            rgba.extend((px * 3 if channels == 1 else px) + [1.0])
        pixels = rgba
    return width, height, pixels


def _extension(image):
    path = image.filepath_raw or image.filepath or ""
    ext = os.path.splitext(path)[1].lower()
    return ext or FORMAT_EXTENSIONS.get(image.file_format, "")


def _file_bytes(image, material):
    """(bytes, extension) of an image facet reads as it is, else None."""
    ext = _extension(image)
    if ext not in textures.READABLE:
        return None
    if image.packed_file is not None:
        return bytes(image.packed_file.data), ext
    if image.source != "FILE":
        return None
    path = bpy.path.abspath(image.filepath, library=image.library)
    if not os.path.isfile(path):
        raise UserError(f"material '{material}': image '{image.name}' reads '{path}', which does not exist: "
                        f"fix the path or pack the image")
    try:
        with open(path, "rb") as f:
            return f.read(), ext
    except OSError as e:
        raise UserError(f"material '{material}': cannot read image '{image.name}' ('{path}'): {e.strerror or e}")


def _produce(image, b, material, notes):
    """(bytes, extension, colour space override or None) of one texture file."""
    derive = b.get("derive")
    if derive:
        width, height, pixels = _pixels(image, material)
        return (textures.bake(width, height, pixels, b["spec"], derive, bool(image.is_float)), ".png",
                "linear")
    found = _file_bytes(image, material)
    if found:
        return found[0], found[1], None
    if image.source == "FILE" and image.packed_file is None:
        path = bpy.path.abspath(image.filepath, library=image.library)
        if not os.path.isfile(path):
            raise UserError(f"material '{material}': image '{image.name}' reads '{path}', which does not exist: "
                            f"fix the path or pack the image")
    width, height, pixels = _pixels(image, material)
    if image.is_float and max(pixels) > 1.0:
        notes.append(f"material '{material}': image '{image.name}' has values above 1, clipped in the 16-bit PNG "
                     f"facet reads")
    # Blender keeps float images in linear values; byte images as stored.
    return textures.pixels_png(width, height, pixels), ".png", "linear" if image.is_float else None


def texture_files(bindings_by_material, taken=None):
    """The files of every material's textures.

    Returns ({material: {textures.file_key: (file name, colour space override)}},
    {file name: bytes}, notes). File names are unique (in `taken`, lower case, which
    grows), made from the images' names."""
    taken = set() if taken is None else taken
    by_key, files, per_material, notes = {}, {}, {}, []
    for material in sorted(bindings_by_material):
        names = per_material.setdefault(material, {})
        for b in bindings_by_material[material]:
            if not textures.has_image(b):         # the vertex colour alone: no file
                continue
            key = textures.file_key(b)
            if key not in by_key:
                image = bpy.data.images.get(b["spec"]["image"])
                if image is None:
                    raise UserError(f"material '{material}': its texture image '{b['spec']['image']}' is gone "
                                    f"(run Convert Blender Material again)")
                data, ext, space = _produce(image, b, material, notes)
                path = image.filepath_raw or image.filepath
                base = os.path.splitext(os.path.basename(path))[0] if path else image.name
                name = textures.file_name(base or image.name, ext, b.get("derive"), taken)
                files[name] = data
                by_key[key] = (name, space)
            names[key] = by_key[key]
    return per_material, files, notes
