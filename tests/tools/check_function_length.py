#!/usr/bin/env python3
"""No function of facet's library over 80 lines, except declarative data (ctest layers.function_length).

    check_function_length.py ROOT             check codegen/, print the ten longest functions
    check_function_length.py self-test        the check fails on a deliberately long function

Functions are found by lizard (PyPI, pinned in requirements.txt); a function's length is
its lines from the signature to the closing brace, blank and comment lines included.
The exceptions are the catalog's entries (a table of models written as code) and are
named here with their reason; anything else over the limit fails.
"""

import os
import sys
import tempfile

import lizard

LIMIT = 80
# Declarative data: name -> why it is exempt.
EXEMPT = {
    "facet::catalog_detail::add_specular": "the specular models' catalog entries (data: one ModelDef each)",
    "facet::catalog_detail::add_diffuse": "the diffuse models' catalog entries (data: one ModelDef each)",
    "facet::catalog_detail::add_layers": "the layer models' catalog entries (data: one ModelDef each)",
}


def functions(paths):
    for path in paths:
        info = lizard.analyze_file(path)
        for f in info.function_list:
            yield f.long_name.split("(")[0], f.length, path, f.start_line


def sources(root):
    for dirpath, _, files in os.walk(os.path.join(root, "codegen")):
        for name in sorted(files):
            if name.endswith((".cpp", ".h")):
                yield os.path.join(dirpath, name)


def check(paths, root):
    found = sorted(set(functions(paths)), key=lambda f: -f[1])
    print(f"The ten longest functions (limit {LIMIT} lines):")
    for name, length, path, line in found[:10]:
        mark = f"  (exempt: {EXEMPT[name]})" if name in EXEMPT else ""
        print(f"  {length:4d}  {name}  {os.path.relpath(path, root)}:{line}{mark}")
    over = [f for f in found if f[1] > LIMIT and f[0] not in EXEMPT]
    for name, length, path, line in over:
        print(f"{os.path.relpath(path, root)}:{line}: {name} is {length} lines (limit {LIMIT})")
    print(f"{len(found)} functions checked, {len(over)} over {LIMIT} lines")
    return 1 if over else 0


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        short = os.path.join(tmp, "short.cpp")
        long_ = os.path.join(tmp, "long.cpp")
        with open(short, "w") as f:
            f.write("int f(int x) {\n" + "  x += 1;\n" * (LIMIT - 2) + "}\n")
        with open(long_, "w") as f:
            f.write("int g(int x) {\n" + "  x += 1;\n" * (LIMIT - 1) + "}\n")
        results = [check([short], tmp), check([long_], tmp)]
    ok = results == [0, 1]
    print(f"{1 if ok else 0} passed, {0 if ok else 1} failed")
    return 0 if ok else 1


if __name__ == "__main__":
    if sys.argv[1:] == ["self-test"]:
        sys.exit(self_test())
    if len(sys.argv) == 2:
        sys.exit(check(list(sources(sys.argv[1])), sys.argv[1]))
    print(__doc__.strip(), file=sys.stderr)
    sys.exit(2)
