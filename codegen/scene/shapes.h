// facet — smooth test meshes of any size, made in C++ (the mesh benchmark,
// tests): a subdivided icosphere, a torus and a box with bumps and creases.
// Normals are the area-weighted average of the faces around each vertex.
#pragma once

#include <cstddef>
#include <vector>

#include "scene/scene.h"

namespace facet {

// An icosahedron whose faces are split into k² triangles each (20 k² in all),
// projected onto the sphere of `radius` around `center`.
Mesh icosphere(int k, const Vec3& center, double radius);
// A torus around the y axis: `around` × `across` quads, 2·around·across triangles.
Mesh torus(int around, int across, const Vec3& center, double major, double minor);
// A cube of half-side `half` whose six faces are n × n grids raised by smooth
// bumps (height `bump` · half) that vanish at the edges: 12 n² triangles, and
// sharp creases along the cube's edges, where the faces keep their own normals.
Mesh creased_box(int n, const Vec3& center, double half, double bump);

// The three side by side, about `triangles` in all, under one point light and a
// camera that sees them all; every object shaded with the material under test.
Scene mesh_bench_scene(size_t triangles);

// A floor square and `objects` − 1 objects on a grid over it — mostly spheres, every tenth
// a small mesh (an icosphere, a torus or a creased box in turn: 48 to 144 triangles), every
// tenth a small tilted square — under `lights` lights: point, spot and directional in turn,
// the points' and spots' attenuation none, inverse-square and polynomial in turn, their
// colours scaled so that the scene's brightness does not grow with their number. The
// camera sees the whole grid. Object k (the floor is 0) is shaded with
// materials[k mod materials.size()], which the scene carries by name. The same numbers
// give the same scene; the many-objects benchmark and tests draw it (docs/many_objects.md).
Scene many_objects_scene(size_t objects, size_t lights, const std::vector<Material>& materials);

// Recomputes m.normals: area-weighted face normals summed at each vertex.
void smooth_normals(Mesh& m);

}  // namespace facet
