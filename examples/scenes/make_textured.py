"""Writes examples/scenes/textured.json: textured materials on meshes with texture coordinates.

    python3 examples/scenes/make_textured.py > examples/scenes/textured.json
    build/bin/facet export-gltf examples/scenes/textured.json -o examples/scenes/textured.gltf

A smooth UV sphere under the normal-mapped Cook–Torrance, a smooth torus under Ward with
α_x, α_y maps, a box whose faces glow with the emission map, and a floor under GGX with a
roughness map and a mirrored colour map: the examples of examples/textured/, by path, on
meshes whose texture coordinates are glTF's (v down the picture). `facet export-gltf`
turns it into textured.gltf, its images copied into textured.textures/. The meshes come
from shapes.py. Standard library only.
"""
import json

from shapes import box, mesh, torus, uv_sphere

scene = {
    "name": "textured",
    "camera": {"position": [0.4, 3.4, 6.0], "look_at": [0, -0.35, -0.2], "up": [0, 1, 0], "fov": 36},
    "ambient": [0.03, 0.03, 0.04],
    "materials": {
        "bumpy": "../textured/textured_normal_cook_torrance.json",
        "brushed": "../textured/textured_ward.json",
        "glowing": "../textured/textured_emission.json",
        "floor": "../textured/textured_ggx.json",
    },
    "objects": [
        mesh("sphere", "bumpy", uv_sphere([-1.35, 0.0, 0.1], 0.75, u_turns=2)),
        mesh("box", "glowing", box([1.35, -0.25, 0.2], [0.5, 0.5, 0.5], 0.5)),
        mesh("torus", "brushed", torus([0.05, -0.45, -0.9], 0.7, 0.27, u_turns=3)),
        mesh("floor", "floor", ([[-4, -0.75, -4], [4, -0.75, -4], [4, -0.75, 3], [-4, -0.75, 3]], [[0, 1, 0]] * 4,
                                [[0, 0], [4, 0], [4, 3.5], [0, 3.5]], [[0, 2, 1], [0, 3, 2]])),
    ],
    "lights": [
        {"type": "point", "position": [-2.5, 4.5, 3.5], "color": [18, 17, 16], "attenuation": "inverse_square"},
        {"type": "directional", "direction": [0.5, -1, -0.35], "color": [0.35, 0.36, 0.42]},
    ],
}
print(json.dumps(scene, separators=(",", ":")))
