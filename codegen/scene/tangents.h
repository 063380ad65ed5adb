// facet — tangent frames of a mesh's texture coordinates, for normal maps: the
// MikkTSpace rule (Mikkelsen 2008, "Simulation of Wrinkled Surfaces Revisited"), which
// Blender's Mesh.calc_tangents() and glTF's exporters compute, written for facet from
// the algorithm's description (docs/textures.md, "Tangent frames").
//
// Per triangle, the unit ∂p/∂s of its texture coordinates and whether the (s, t)
// triangle keeps its orientation (t up the picture: t = 1 − v, glTF's v runs down).
// Per corner, the corners of the same vertex — vertices with equal position, normal and
// coordinates are one — that are joined through edges of triangles of the same
// orientation form a group; the group's tangent is the sum of its triangles' ∂p/∂s,
// each projected into the plane of the vertex normal, made unit and weighted by the
// triangle's angle at the vertex (its edges projected into the same plane), made unit.
// w = +1 where the triangle keeps its orientation, −1 where it mirrors: B = w·(N × T)
// points up the picture (towards decreasing v), as glTF's TANGENT.w and Blender's
// bitangent_sign (which glTF-Blender-IO writes unchanged) say.
#pragma once

#include <array>
#include <vector>

#include "scene/scene.h"

namespace facet {

// MODELS.md's tangent rule, the anisotropic lobes' t where no texture coordinates give one:
// t = normalize(axis × n), or normalize(x̂ × n) where |axis × n| < ε.
Vec3 tangent_rule(const Vec3& n, const Vec3& axis);

// Texture coordinate set `set`'s tangents, one per triangle corner (3·i + k for corner k
// of triangle i): xyz unit and ⟂ the vertex normal (0 where the triangles give no
// direction), w = ±1. The mesh must have that set.
std::vector<std::array<double, 4>> mikktspace_tangents(const Mesh& m, int set);

// The tangents a normal map on texture coordinate set `set` of `m` uses, per corner (3 a
// triangle): the mesh's own where it brings them (Mesh::tangents: glTF's TANGENT, which glTF
// defines for the normal texture, whichever set it reads), else facet's MikkTSpace ones.
std::vector<std::array<double, 4>> mesh_tangents(const Mesh& m, int set);

// The tangent frame at a hit of triangle h.triangle from its corners' tangents
// (`corners`, as mikktspace_tangents gives them): t the barycentric blend of their xyz
// (made ⟂ n by the normal map's Gram–Schmidt), w = +1 where the blend of their w is ≥ 0, else −1.
void blend_tangent(const Mesh& m, const std::vector<std::array<double, 4>>& corners, const Hit& h, Vec3& t, double& w);

}  // namespace facet
