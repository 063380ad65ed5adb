"""The Blender-free half of the facet add-on.

Nothing in this package imports `bpy` or `mathutils`: it works on plain Python data
(dicts, lists, tuples of floats) and talks to the facet command-line tool. The Blender
half (`..blender`) reads Blender data into plain data, calls these functions, and writes
the results back. This is the split of glTF-Blender-IO (`io/` vs `blender/`).

Modules:
    cli       find and run the facet executable; its errors; atomic file writes
    catalog   the model catalog, parsed from `facet models --json` and `facet schema`
    props     the property plan built from the catalog, and material JSON <-> values
    coords    Blender (+Z up) <-> facet (+Y up) coordinates, float formatting
    scene     cameras, lights, meshes and the scene JSON
    convert   Blender BSDF nodes -> facet lobes (the mapping table)
"""


class UserError(Exception):
    """A problem the user can fix; its message is shown as is in Blender's report."""
