"""The loaded catalog and the PropertyGroups built from it.

At register time the add-on runs `facet models --json` and `facet schema`, builds the
property plan and registers it. When facet cannot be found or run, the add-on registers
its properties from the catalog bundled with it (facet_blender/catalog.json, core/catalog.py),
so `material.facet` exists before facet is found; `STATE.error` keeps the reason, the panel
shows it with where to set the path, and the operators that run facet refuse with it.
Setting the path in the preferences (or the Reload button) loads facet's own catalog then;
where it differs from the bundled one (a newer or older facet), facet's is the one used.
"""

from ..core import UserError, catalog as catalog_mod, cli, props as plan_mod
from . import properties


class State:
    def __init__(self):
        self.catalog = None     # core.catalog.Catalog: facet's, else the bundled one
        self.plan = None        # core.props.Group of FACET_PG_material
        self.exe = ""           # the facet executable the catalog came from ("" = bundled)
        self.error = "facet is not loaded yet"   # why facet is not used ("" when it is)
        self.differs = False    # facet's catalog is not the bundled one
        self.classes = []       # the registered PropertyGroup classes


STATE = State()


def _facet_catalog(facet_path_setting):
    """(exe, catalog, "") from facet, or ("", None, reason)."""
    try:
        exe = cli.find_facet(facet_path_setting)
        return exe, catalog_mod.load(exe), ""
    except UserError as e:
        return "", None, str(e)
    except Exception as e:  # noqa: BLE001 - a catalog the add-on cannot handle
        return "", None, f"cannot build the facet panel from facet's catalog: {type(e).__name__}: {e}"


def load(facet_path_setting=""):
    """Loads facet's catalog (else the bundled one) and registers its PropertyGroups.
    Returns whether facet itself was loaded; the reason it was not stays in STATE.error.
    Never raises: registering the add-on must not fail."""
    unload()
    exe, catalog, error = _facet_catalog(facet_path_setting)
    try:
        bundled = catalog_mod.load_bundled()
    except UserError as e:
        bundled = None
        error = "\n".join(x for x in (error, str(e)) if x)
    differs = catalog is not None and bundled is not None and catalog != bundled
    catalog = catalog or bundled
    if catalog is None:
        STATE.error = error
        return False
    try:
        plan = plan_mod.material_group(catalog)
        STATE.classes = properties.register_plan(plan)
    except Exception as e:  # noqa: BLE001
        STATE.error = "\n".join(x for x in (error, f"cannot build the facet panel from the catalog: "
                                                      f"{type(e).__name__}: {e}") if x)
        return False
    STATE.catalog, STATE.plan, STATE.exe, STATE.error, STATE.differs = catalog, plan, exe, error, differs
    return not error


def unload():
    properties.unregister_classes(STATE.classes)
    STATE.classes = []
    STATE.catalog = STATE.plan = None
    STATE.exe = ""
    STATE.differs = False
    STATE.error = "facet is not loaded"


def reload(facet_path_setting=""):
    return load(facet_path_setting)


def require():
    """(catalog, plan), or a UserError with the reason facet is not loaded."""
    if STATE.catalog is None:
        raise UserError(f"facet is not available: {STATE.error}")
    return STATE.catalog, STATE.plan
