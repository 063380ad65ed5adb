"""The split itself: core/ needs neither bpy nor mathutils, and every core module has tests."""

import os
import pkgutil
import subprocess
import sys

from support import ADDON_ROOT, HERE

CORE = os.path.join(ADDON_ROOT, "facet_blender", "core")

PROBE = """
import importlib, pkgutil, sys
sys.modules["bpy"] = None           # any `import bpy` now raises ImportError
sys.modules["mathutils"] = None
sys.path.insert(0, sys.argv[1])
import facet_blender.core as core
names = sorted(m.name for m in pkgutil.iter_modules(core.__path__))
for name in names:
    importlib.import_module("facet_blender.core." + name)
print("CORE", " ".join(names))
print("LOADED", "bpy" in sys.modules and sys.modules["bpy"] is not None)
"""


def core_modules():
    return sorted(m.name for m in pkgutil.iter_modules([CORE]))


def test_every_core_module_imports_without_bpy_or_mathutils():
    # A fresh interpreter, so no module imported by another test hides an import.
    proc = subprocess.run([sys.executable, "-c", PROBE, ADDON_ROOT], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    assert proc.returncode == 0, proc.stdout
    lines = dict(line.split(" ", 1) for line in proc.stdout.splitlines() if " " in line)
    assert lines["CORE"].split() == core_modules()
    assert lines["LOADED"] == "False"


def test_no_core_source_imports_bpy():
    for name in core_modules():
        with open(os.path.join(CORE, name + ".py"), encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                code = line.split("#")[0].strip()
                assert not code.startswith(("import bpy", "from bpy", "import mathutils", "from mathutils")), \
                    f"core/{name}.py:{number}: {line.strip()}"


def test_every_core_module_has_a_test_file():
    missing = [name for name in core_modules() if not os.path.exists(os.path.join(HERE, f"test_{name}.py"))]
    assert not missing, f"core modules without tests/core/test_<module>.py: {missing}"


def test_the_core_package_lists_its_modules():
    import facet_blender.core as core
    listed = core.__doc__
    for name in core_modules():
        assert f"\n    {name} " in listed, f"core/__init__.py's docstring does not describe {name}"
