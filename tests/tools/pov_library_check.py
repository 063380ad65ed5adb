"""Draws a material's POV-Ray library (facet generate --target pov --library) the way its
header tells a user to: a unit sphere whose normal (and, for a textured material, texture
coordinates: docs/textures.md's sphere mapping; for one that reads the vertex colour, a colour
varying over the sphere) the scene gives as functions, lit by one
point light through Facet_Pigment_Point. Fails unless POV-Ray parses and renders it and
the sphere is lit (some pixel above a small level in every channel the material reflects).

    python pov_library_check.py FACET MATERIAL.json OUTDIR
"""
import os
import subprocess
import sys

SCENE = """#version 3.7;
global_settings {{ assumed_gamma 1.0 }}
#include "library.inc"
camera {{ location <0, 0, 4> look_at 0 angle 40 }}
#declare NX = function(x, y, z) {{ x }}
#declare NY = function(x, y, z) {{ y }}
#declare NZ = function(x, y, z) {{ z }}
#declare S0 = function(x, y, z) {{ 0.5 + atan2(x, z)/(2*pi) }}
#declare T0 = function(x, y, z) {{ acos(min(max(y, -1), 1))/pi }}
#declare R0 = function(x, y, z) {{ 0.5 + 0.5*x }}
#declare G0 = function(x, y, z) {{ 0.5 + 0.5*y }}
#declare B0 = function(x, y, z) {{ 0.5 + 0.5*z }}
#declare A0 = function(x, y, z) {{ 1 }}
light_group {{
  light_source {{ <3, 4, 5> color 1 }}
  sphere {{ 0, 1 texture {{ Facet_Pigment_Point({args}, <3, 4, 5>, <0, 0, 4>, 1) finish {{ Facet_Finish }} }} }}
  global_lights off
}}
"""


def main():
    facet, material, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    subprocess.run([facet, "generate", material, "--target", "pov", "--library", "-o",
                    os.path.join(out, "library.inc")], check=True)
    library = open(os.path.join(out, "library.inc")).read()
    colored = "NX, NY, NZ, S0, T0, S1, T1, R0, G0, B0, A0, LightPosition" in library
    textured = colored or "NX, NY, NZ, S0, T0, S1, T1, LightPosition" in library
    args = "NX, NY, NZ, S0, T0, S0, T0" if textured else "NX, NY, NZ"
    if colored:
        args += ", R0, G0, B0, A0"
    with open(os.path.join(out, "scene.pov"), "w") as f:
        f.write(SCENE.format(args=args))
    r = subprocess.run(["povray", "+Iscene.pov", "+Oscene.ppm", "+FP", "+W48", "+H48", "-D", "-A"], cwd=out,
                       capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stderr[-2000:])
        print(f"FAIL: POV-Ray could not draw the library of {material}")
        return 1
    data = open(os.path.join(out, "scene.ppm"), "rb").read()
    # P6, width, height, maxval (comment lines between them), one whitespace, the pixels.
    fields, at = [], 0
    while len(fields) < 4:
        while data[at:at + 1].isspace():
            at += 1
        if data[at:at + 1] == b"#":
            at = data.index(b"\n", at) + 1
            continue
        end = at
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[at:end])
        at = end
    depth = 2 if int(fields[3]) > 255 else 1
    px = data[at + 1:]
    peak = max(px[i * depth] for i in range(len(px) // depth))
    print(f"{material}: {'textured, ' if textured else ''}{'vertex-coloured, ' if colored else ''}brightest channel byte {peak}")
    if peak < 8:
        print("FAIL: the sphere is black")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
