"""The loaded catalog and the PropertyGroups built from it.

At register time the add-on runs `facet models --json` and `facet schema`, builds the
property plan and registers it. When facet cannot be found or run, the add-on still
registers (panel, operators, preferences) and keeps the reason in `STATE.error`; the
panel shows it, and setting the path in the preferences (or the Reload button) loads
the catalog then.
"""

from ..core import UserError, catalog as catalog_mod, cli, props as plan_mod
from . import properties


class State:
    def __init__(self):
        self.catalog = None     # core.catalog.Catalog
        self.plan = None        # core.props.Group of FACET_PG_material
        self.exe = ""           # the facet executable the catalog came from
        self.error = "facet is not loaded yet"
        self.classes = []       # the registered PropertyGroup classes


STATE = State()


def load(facet_path_setting=""):
    """Loads the catalog and registers its PropertyGroups; on failure keeps the
    reason in STATE.error (never raises: registering the add-on must not fail)."""
    unload()
    try:
        exe = cli.find_facet(facet_path_setting)
        catalog = catalog_mod.load(exe)
        plan = plan_mod.material_group(catalog)
        STATE.classes = properties.register_plan(plan)
    except UserError as e:
        STATE.error = str(e)
        return False
    except Exception as e:  # noqa: BLE001 - a catalog the add-on cannot handle
        STATE.error = f"cannot build the facet panel from facet's catalog: {type(e).__name__}: {e}"
        return False
    STATE.catalog, STATE.plan, STATE.exe, STATE.error = catalog, plan, exe, ""
    return True


def unload():
    properties.unregister_classes(STATE.classes)
    STATE.classes = []
    STATE.catalog = STATE.plan = None
    STATE.exe = ""
    STATE.error = "facet is not loaded"


def reload(facet_path_setting=""):
    return load(facet_path_setting)


def require():
    """(catalog, plan), or a UserError with the reason facet is not loaded."""
    if STATE.catalog is None:
        raise UserError(f"facet is not available: {STATE.error}")
    return STATE.catalog, STATE.plan
