"""Writes examples/scenes/three_meshes.json: three meshes, three facet materials.

    python3 examples/scenes/make_three_meshes.py > examples/scenes/three_meshes.json

A smooth UV sphere (curved, smooth normals), a flat-shaded box (its own vertices
per face), a smooth torus (concave: it shadows itself) on a floor quad, lit by a
point light and a directional light. `facet export-gltf` turns it into
three_meshes.gltf. The meshes come from shapes.py,
without their texture coordinates. Standard library only.
"""
import json

from shapes import box, mesh, torus, uv_sphere

scene = {
    "name": "three_meshes",
    "camera": {"position": [0.4, 3.4, 6.0], "look_at": [0, -0.35, -0.2], "up": [0, 1, 0], "fov": 36},
    "ambient": [0.03, 0.03, 0.04],
    "materials": {
        "clay": {"name": "clay", "diffuse": {"model": "oren_nayar", "color": [0.72, 0.45, 0.3], "sigma": 0.4},
                 "ambient": [1, 1, 1]},
        "brushed": {"name": "brushed", "diffuse": {"model": "lambert", "color": [0.25, 0.25, 0.28]},
                    "specular": {"model": "ward", "color": [0.8, 0.75, 0.7], "alpha_x": 0.12, "alpha_y": 0.35},
                    "ambient": [1, 1, 1]},
        "plastic": {"name": "plastic", "diffuse": {"model": "lambert", "color": [0.15, 0.3, 0.65]},
                    "specular": {"model": "ggx", "alpha": 0.12}, "ambient": [1, 1, 1]},
    },
    "objects": [
        mesh("sphere", "plastic", uv_sphere([-1.35, 0.0, 0.1], 0.75), False),
        mesh("box", "clay", box([1.35, -0.25, 0.2], [0.5, 0.5, 0.5], 0.5), False),
        mesh("torus", "brushed", torus([0.05, -0.45, -0.9], 0.7, 0.27), False),
        mesh("floor", "clay", ([[-4, -0.75, -4], [4, -0.75, -4], [4, -0.75, 3], [-4, -0.75, 3]],
                               [[0, 1, 0]] * 4, None, [[0, 2, 1], [0, 3, 2]]), False),
    ],
    "lights": [
        {"type": "point", "position": [-2.5, 4.5, 3.5], "color": [18, 17, 16], "attenuation": "inverse_square"},
        {"type": "directional", "direction": [0.5, -1, -0.35], "color": [0.35, 0.36, 0.42]},
    ],
}
print(json.dumps(scene, separators=(",", ":")))
