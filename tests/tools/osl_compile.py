"""Compiles generated OSL with the OSL compiler inside Blender (pip bpy).

    python osl_compile.py FACET OUTDIR MATERIAL.json [MATERIAL.json ...]

For each material: `facet generate --target osl`, then Cycles' own compiler
(_cycles.osl_compile, the one a Script node uses). Fails if bpy has no OSL, if
a shader does not compile, or if the compiled shader lacks its `Out` closure.
"""
import os
import subprocess
import sys


def main():
    facet, outdir, materials = sys.argv[1], sys.argv[2], sys.argv[3:]
    import bpy  # noqa: F401  (loads Cycles' native module)
    import _cycles
    if not (bpy.app.build_options.cycles_osl and getattr(_cycles, "with_osl", False)):
        print(f"FAIL: this bpy {bpy.app.version_string} was built without OSL")
        return 1
    os.makedirs(outdir, exist_ok=True)
    failed = 0
    for material in materials:
        name = os.path.splitext(os.path.basename(material))[0]
        osl = os.path.join(outdir, name + ".osl")
        oso = os.path.join(outdir, name + ".oso")
        if os.path.exists(oso):
            os.remove(oso)
        gen = subprocess.run([facet, "generate", material, "--target", "osl", "-o", osl],
                             capture_output=True, text=True)
        if gen.returncode != 0:
            print(f"FAIL {material}: facet: {gen.stderr}")
            failed += 1
            continue
        if not _cycles.osl_compile(osl, oso) or not os.path.exists(oso):
            print(f"FAIL {material}: the OSL compiler rejected {osl}")
            failed += 1
            continue
        text = open(oso).read()
        if "\nshader facet_" not in text or "closure color\tOut" not in text:
            print(f"FAIL {material}: {oso} has no facet shader with an Out closure")
            failed += 1
            continue
        print(f"ok {material} -> {oso} (OSL {_cycles.osl_version_string}, Blender {bpy.app.version_string})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
