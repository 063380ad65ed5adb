"""Writes or checks the catalog bundled with the add-on (facet_blender/catalog.json).

    python exporters/blender/bundle_catalog.py --facet build/bin/facet           # write it
    python exporters/blender/bundle_catalog.py --facet build/bin/facet --check   # ctest addon.catalog_bundled

The file holds `facet models --json` and `facet schema` of that facet. The add-on
registers its properties from it while facet is not found, and uses facet's own catalog
once it is; --check exits 1 (naming the first difference) when the bundled copy is not
what this facet prints, so a catalog change in C++ cannot leave it stale. No bpy needed.
"""

import argparse
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from facet_blender.core import UserError, catalog, cli  # noqa: E402


def first_difference(a, b, path="$"):
    """The key path of the first difference between two JSON values, or None."""
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f"{path}.{k} ({'only in the bundled copy' if k in a else 'only in facet'})"
            d = first_difference(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{path} (length {len(a)} bundled, {len(b)} in facet)"
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_difference(x, y, f"{path}[{i}]")
            if d:
                return d
        return None
    return None if a == b and type(a) is type(b) else f"{path} ({a!r} bundled, {b!r} in facet)"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--facet", required=True)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--bundled", default=catalog.BUNDLED_PATH)
    args = ap.parse_args()
    try:
        data = catalog.facet_data(args.facet)
        if not args.check:
            cli.write_atomic(args.bundled, catalog.dump_bundled(data))
            print(f"wrote {args.bundled} (facet {data['models'].get('facet', '?')})")
            return 0
        diff = first_difference(catalog.bundled_data(args.bundled), data)
    except UserError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    if diff:
        print(f"error: {args.bundled}: {diff}: the bundled catalog is not what '{args.facet}' prints; "
              f"run python {os.path.relpath(__file__)} --facet {args.facet}", file=sys.stderr)
        return 1
    print(f"{args.bundled} is what {args.facet} prints")
    return 0


if __name__ == "__main__":
    sys.exit(main())
