#!/usr/bin/env python3
"""facet's layering, checked (ctest layers.*; docs/architecture.md says why).

    check_layers.py includes ROOT          every #include of codegen/ points down the layers
    check_layers.py model-names ROOT FACET no code outside codegen/catalog/ compares a model's name
    check_layers.py self-test              both checks fail on deliberately wrong sources

codegen/ has one folder per layer, lowest first:

    core → catalog → scene → reference → targets → renderers → analysis → docs → cli

A file of a layer may include headers of its own layer and of the layers below it,
never of a layer above. The catalog owns what is known about a model (its name
included): outside codegen/catalog/, a model's name is never compared, neither
`def->name == …` nor a string literal holding a catalog model's name on either side
of `==` or `!=` (the names come from `facet models --json`).
"""

import json
import os
import re
import subprocess
import sys

LAYERS = ["core", "catalog", "scene", "reference", "targets", "renderers", "analysis", "docs", "cli"]
SOURCES = (".cpp", ".h")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
# The shading vocabulary (the scene vocabulary, camera/light/object, is the scene layer's to read).
MODEL_SECTIONS = ["diffuse", "specular", "fresnel", "geometry", "distribution", "modifier", "attenuation", "term"]


def strip_comments(text):
    """The text with // and /* */ comments blanked, string literals kept."""
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            out.append("\n" * text.count("\n", i, n if j < 0 else j))
            i = n if j < 0 else j + 2
        elif text[i] == '"' and not text.startswith('R"', i - 1):
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


def include_problems(path, layer, text):
    """(line, message) for every include of a higher layer in `text` (a file of `layer`)."""
    rank = LAYERS.index(layer)
    problems = []
    for m in INCLUDE.finditer(text):
        target = m.group(1).split("/")[0]
        if target in LAYERS and LAYERS.index(target) > rank:
            problems.append((line_of(text, m.start()),
                             f'{layer} includes "{m.group(1)}" of the higher layer {target}'))
    return problems


def name_problems(text, names):
    """(line, message) for every comparison of a model's name in `text`."""
    code = strip_comments(text)
    problems = []
    for m in re.finditer(r"(?:[!=]=\s*[\w.>\-\[\]()]*def->name\b)|(?:\bdef->name\s*[!=]=)", code):
        problems.append((line_of(code, m.start()), f"compares a model's name: {m.group(0).strip()}"))
    alternatives = "|".join(sorted(map(re.escape, names), key=len, reverse=True))
    literal = re.compile(r'(?:[!=]=\s*"(%s)")|(?:"(%s)"\s*[!=]=)' % (alternatives, alternatives))
    for m in literal.finditer(code):
        problems.append((line_of(code, m.start()),
                         f'compares with the model name "{m.group(1) or m.group(2)}": {m.group(0).strip()}'))
    return problems


def codegen_files(root):
    base = os.path.join(root, "codegen")
    for layer in LAYERS:
        folder = os.path.join(base, layer)
        for dirpath, _, files in os.walk(folder):
            for f in sorted(files):
                if f.endswith(SOURCES):
                    path = os.path.join(dirpath, f)
                    yield layer, path, open(path, encoding="utf-8").read()


def model_names(facet):
    catalog = json.loads(subprocess.run([facet, "models", "--json"], check=True, capture_output=True,
                                        text=True).stdout)
    names = set()
    for section in MODEL_SECTIONS:
        names.update(m["name"] for m in catalog["sections"][section] if m["name"] != "none")
    return names


def report(problems, root, what):
    for path, line, message in problems:
        print(f"{os.path.relpath(path, root)}:{line}: {message}")
    if problems:
        print(f"FAILED: {len(problems)} {what}")
        return 1
    return 0


def check_includes(root):
    problems, files = [], 0
    for layer, path, text in codegen_files(root):
        files += 1
        problems += [(path, line, msg) for line, msg in include_problems(path, layer, text)]
    missing = [l for l in LAYERS if not os.path.isdir(os.path.join(root, "codegen", l))]
    if missing:
        print(f"FAILED: codegen/ has no folder for the layers {', '.join(missing)}")
        return 1
    print(f"{files} files of {len(LAYERS)} layers checked")
    return report(problems, root, "includes of a higher layer")


def check_names(root, facet):
    names = model_names(facet)
    problems, files = [], 0
    for layer, path, text in codegen_files(root):
        if layer == "catalog":
            continue
        files += 1
        problems += [(path, line, msg) for line, msg in name_problems(text, names)]
    print(f"{files} files outside the catalog checked against {len(names)} model names")
    return report(problems, root, "comparisons of a model's name outside the catalog")


def self_test():
    """Each check must catch its deliberately wrong source, and pass the right one."""
    names = {"lambert", "ggx", "inverse_square"}
    cases = [
        (include_problems("x", "targets", '#include "analysis/sweep.h"\n'), 1),
        (include_problems("x", "core", '#include "catalog/catalog.h"\n'), 1),
        (include_problems("x", "targets", '#include "core/ir.h"\n#include "targets/targets.h"\n'), 0),
        (name_problems('if (s.def->name == "phong") {}', names), 1),
        (name_problems('bool b = "ggx" != m.specular->def->name;', names), 2),
        (name_problems('return m.name == "lambert";', names), 1),
        (name_problems('// a comment: def->name == "ggx"\nauto d = find_model("diffuse", "lambert");', names), 0),
        (name_problems('if (p.name == "color") {}', names), 0),
    ]
    failed = [i for i, (got, want) in enumerate(cases) if len(got) != want]
    for i in failed:
        print(f"self-test case {i}: expected {cases[i][1]} problems, found {cases[i][0]}")
    print(f"{len(cases) - len(failed)} passed, {len(failed)} failed")
    return 1 if failed else 0


def main(argv):
    if len(argv) >= 2 and argv[1] == "self-test":
        return self_test()
    if len(argv) == 3 and argv[1] == "includes":
        return check_includes(argv[2])
    if len(argv) == 4 and argv[1] == "model-names":
        return check_names(argv[2], argv[3])
    print(__doc__.strip(), file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
