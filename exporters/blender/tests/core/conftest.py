"""pytest set-up for the tests of facet_blender/core, which run without Blender.

    python -m pytest exporters/blender/tests/core -q --facet build/bin/facet

`--facet PATH` (or $FACET) is the facet executable the tests run; a test that needs
facet fails when neither is given (it is never skipped). `bpy` and `mathutils` are
made unimportable before the add-on is imported, so every test here also shows that
core/ does without them, even in a Python that has the `bpy` module installed.
"""

import os
import shutil
import sys

import pytest

sys.modules["bpy"] = None               # `import bpy` now raises ImportError
sys.modules["mathutils"] = None

from support import ADDON_ROOT  # noqa: E402  (puts the add-on on sys.path)

assert ADDON_ROOT in sys.path


def pytest_addoption(parser):
    parser.addoption("--facet", default=os.environ.get("FACET", ""),
                     help="the facet executable (default: $FACET); tests that need it fail without it")
    parser.addoption("--povray", default=os.environ.get("POVRAY", "") or shutil.which("povray") or "",
                     help="POV-Ray 3.7 (default: $POVRAY, else povray on PATH)")


@pytest.fixture(scope="session")
def facet(request):
    """The facet executable (absolute path)."""
    path = request.config.getoption("--facet")
    if not path:
        pytest.fail("no facet executable: pass --facet PATH (or set FACET=PATH)", pytrace=False)
    path = os.path.abspath(path)
    if not (os.path.isfile(path) and os.access(path, os.X_OK)):
        pytest.fail(f"--facet {path}: not an executable file", pytrace=False)
    return path


@pytest.fixture(scope="session")
def povray_exe(request):
    """POV-Ray (a missing POV-Ray fails the tests that render, as in the rest of facet's tests)."""
    path = request.config.getoption("--povray")
    found = shutil.which(path) if path else None
    if not found:
        pytest.fail("POV-Ray (povray) is not installed: install it or pass --povray PATH", pytrace=False)
    return found


@pytest.fixture(scope="session")
def catalog(facet):
    from facet_blender.core import catalog as catalog_mod
    return catalog_mod.load(facet)


@pytest.fixture(scope="session")
def plan(catalog):
    from facet_blender.core import props
    return props.material_group(catalog)
