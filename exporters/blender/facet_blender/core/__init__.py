"""The Blender-free half of the facet add-on.

Nothing in this package imports `bpy` or `mathutils`: it works on plain Python data
(dicts, lists, tuples of floats) and talks to the facet command-line tool. The Blender
half (`..blender`) reads Blender data into plain data, calls these functions, and writes
the results back. This is the split of glTF-Blender-IO (`io/` vs `blender/`).

Modules:
    cli       find and run the facet executable; its errors; atomic file writes
    generate  what the operators ask of facet: material files checked, written, read;
              GLSL/OSL generated (temporary files, messages that name the material)
    catalog   the model catalog, parsed from `facet models --json` and `facet schema`
    props     the property plan built from the catalog, and material JSON <-> values
    coords    Blender (+Z up) <-> facet (+Y up) coordinates, float formatting
    scene     cameras, lights, meshes and the scene JSON
    convert   Blender BSDF nodes -> facet lobes (the mapping table)
    native    facet lobes -> Blender's own shader nodes (Build Blender Nodes; the other way)
    textures  Image Texture / Normal Map nodes -> textured parameters; derived images; PNGs
    gltf      facet's glTF extensions -> Blender light settings; FACET_material checked
    pov       POV-Ray scenes: generated with facet's Plan (passes), 16-bit PPM and PNG
    povray    finding and running POV-Ray: one run, or one per pass, added; a polled,
              cancellable Job (the render engine); anti-aliasing and quality Settings
    osl       compiling OSL in Blender's process: the compiler's output, oslquery's folder

Its tests are plain pytest (exporters/blender/tests/core/), run without Blender.
"""


class UserError(Exception):
    """A problem the user can fix; its message is shown as is in Blender's report."""
