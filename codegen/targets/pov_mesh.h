// facet — a mesh for POV-Ray's exact route: its geometry as a data image.
// Private to codegen/targets (pov.cpp, pov_functions.cpp).
//
// A POV-Ray function sees only the point it is evaluated at, and a number
// written in a function enters POV-Ray's table of constants, which is searched
// linearly for every number parsed and holds at most 1,048,576 in all
// (FunctionVM::AddConstant, source/backend/vm/fnpovfpu.cpp): per-triangle
// functions parse in quadratic time and stop at about 87,000 triangles. So
// the exact route keeps every function the same whatever the mesh size and
// puts the mesh's data in an image instead (measured: docs/povray-meshes.md):
//
// * uv_mapping hands the pigment (u, v, 0), interpolated barycentrically from
//   the three corners' uv vectors (Mesh::MeshUV). Triangle t's corners get
//   (4i+1, 4j+1), (4i+2, 4j+1), (4i+1, 4j+2) with t = 2048 j + i, integers
//   that float32 holds exactly, so the pigment reads t = 2048·⌊v/4⌋ + ⌊u/4⌋ and
//   the barycentrics a = u − 4⌊u/4⌋ − 1, b = v − 4⌊v/4⌋ − 1 of corners 1 and 2.
// * A 16-bit PPM holds, per triangle, its three corners' positions and normals
//   as 24-bit fixed point (18 values, two per texel of three 16-bit channels,
//   9 texels); image_map with interpolate off returns each channel exactly.
//   The pigment rebuilds P = Σ wₖ pₖ and the unnormalized normal Σ wₖ nₖ.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "core/vec.h"
#include "scene/scene.h"

namespace facet::targets {

struct PovMeshData {
  std::string file;    // the image's name, beside the scene
  int width = 0, height = 0;
  Vec3 lo, step;       // position = lo + step ⊙ q, q the 24-bit integer
  double normal_step = 0;  // normal component = −1 + normal_step · q
  // The largest difference between a stored value and the mesh's own (measured
  // over every corner): positions in scene units, normal components.
  double position_error = 0, normal_error = 0;
};

// The data image's layout and precision for mesh `m`, named `file`.
PovMeshData pov_mesh_data(const Mesh& m, const std::string& file);
// The image itself (binary PPM, 16 bits a channel), a row at a time.
void write_pov_mesh_image(std::ostream& out, const Mesh& m, const PovMeshData& d);
// The functions that read it for object o (Facet_Mesh{o}_Tri, _Bary, _PX … _MZ).
std::string pov_mesh_decoder(const PovMeshData& d, size_t o);
// Mesh o's include file: the macros its mesh2 objects call, Facet_Mesh{o}_Vertices()
// (the vertices), Facet_Mesh{o}_Vertices_{k}() (inset by insets[k − 1] along the
// normals, for the one-run file's copies) and Facet_Mesh{o}_Shape() (normals, the uv
// numbering of the triangles when `numbered`, faces). Lists in float32, which is
// what POV-Ray stores them in.
void write_pov_mesh_include(std::ostream& out, const Mesh& m, size_t o, const std::string& name, bool numbered,
                            const std::vector<double>& insets);

}  // namespace facet::targets
