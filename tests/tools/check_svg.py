#!/usr/bin/env python3
"""Parses an SVG diagram from `facet plot` with Python's XML parser and checks
its frame: an <svg> root of the stated size, filled and stroked shapes, text,
and the labels given with --expect (e.g. a plane's heading)."""
import argparse
import sys
import xml.etree.ElementTree as ET

NS = "{http://www.w3.org/2000/svg}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("svg")
    ap.add_argument("--expect", action="append", default=[], help="text that must appear in a <text> element")
    ap.add_argument("--colour", action="append", default=[], help="a stroke colour some shape must have, #rrggbb")
    ap.add_argument("--no-colour", action="append", default=[], help="a stroke colour no shape may have")
    a = ap.parse_args()
    root = ET.parse(a.svg).getroot()  # raises on malformed XML
    problems = []
    if root.tag != NS + "svg":
        problems.append(f"root is {root.tag}, not svg")
    w, h = int(root.get("width")), int(root.get("height"))
    if root.get("viewBox") != f"0 0 {w} {h}":
        problems.append(f"viewBox {root.get('viewBox')} is not the size {w}x{h}")
    shapes = [e for e in root.iter() if e.tag in (NS + "polygon", NS + "polyline", NS + "circle")]
    texts = ["".join(e.itertext()) for e in root.iter(NS + "text")]
    strokes = {e.get("stroke") for e in shapes}
    if len(shapes) < 20:
        problems.append(f"only {len(shapes)} shapes")
    for want in a.expect:
        if not any(want in t for t in texts):
            problems.append(f"no text holds {want!r}")
    for c in a.colour:
        if c not in strokes:
            problems.append(f"no shape is stroked {c}")
    for c in a.no_colour:
        if c in strokes:
            problems.append(f"a shape is stroked {c}")
    for e in shapes:
        for x in (e.get("points") or "").split():
            px, py = (float(v) for v in x.split(","))
            if not (-1 <= px <= w + 1 and -1 <= py <= h + 1):
                problems.append(f"point {x} lies outside the {w}x{h} frame")
                break
    if problems:
        print(f"{a.svg}: " + "; ".join(problems))
        return 1
    print(f"{a.svg}: valid SVG {w}x{h}, {len(shapes)} shapes, {len(texts)} texts")
    return 0


if __name__ == "__main__":
    sys.exit(main())
