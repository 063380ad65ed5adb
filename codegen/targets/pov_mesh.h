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
// * Triangle t owns a block of 2 × 2 texels of the image. Its corners' uv
//   vectors are the block's texel centres (2i, 2j), (2i+1, 2j), (2i, 2j+1)
//   (column, row from the bottom), and uv_mapping hands the pigment their
//   barycentric blend (Mesh::UVCoord).
// * The image is read with `interpolate 2`, POV-Ray's bilinear blend. The
//   block's fourth texel holds T₁₀ + T₀₁ − T₀₀, so the bilinear blend inside the
//   triangle is the linear one: one lookup returns Σ wₖ·valueₖ, the corners'
//   values blended exactly as facet's reference blends them.
// * Each value (a position or normal component) is a 31-bit code split into
//   two 16-bit channels, hi·32768 + lo, and both channels are blended
//   linearly; four planes of the image hold the positions' hi and lo and the
//   normals' hi and lo, x, y, z in R, G, B. The pigment reads the hit point and
//   the unnormalized normal in 12 lookups, and nothing is decoded by floor().
//   Texture coordinates, a normal map's tangents and vertex colours take more planes
//   of the same kind (PovMeshData::components).
#pragma once

#include <array>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "core/vec.h"
#include "scene/scene.h"

namespace facet::targets {

struct PovMeshData {
  std::string file;   // the image's name, beside the scene
  int blocks = 0;     // triangles (2 × 2 blocks) a row: the image is 2·blocks texels wide
  int plane_rows = 0; // rows of each of the four planes; the image is 4·plane_rows high
  // Component c (0–2 the position's x, y, z, 3–5 the normal's, and with texture coordinates
  // 6–9 u₀, v₀, u₁, v₁, 10–11 unused; with a normal map's tangents 10–12 the tangent's x, y,
  // z, 13 its w, 14 unused; with vertex colours 10–13 the tangent's or 0, 14–17 the colour's
  // r, g, b, a) = offset[c] + step[c] · code.
  int components = 6;  // 12 with texture coordinates: two more pairs of planes; 15 with tangents, 18 with colours
  std::array<double, 18> offset{}, step{};
  // A normal map's corner tangents (scene/tangents.h), 3 a triangle, or null.
  std::shared_ptr<const std::vector<std::array<double, 4>>> tangents;
  bool colors = false;  // the mesh's vertex colours (Mesh::colors), blended as the positions are
  // How far a value POV-Ray reads may be from the mesh's own, at most: positions in
  // scene units, normal components (the codes' step and float32's rounding of the blend).
  double position_error = 0, normal_error = 0, texcoord_error = 0, color_error = 0;
  int width() const { return 2 * blocks; }
  int planes() const { return 2 * components / 3; }
  // The four planes and, at the top, a row of zeros: POV-Ray's PPM reader takes a byte 13
  // right after the header for the end of the header's line (IStream::getline reads "\n\r"
  // as one line break), so the first pixel's first byte must not be 13.
  int height() const { return planes() * plane_rows + 1; }
};

// The data image's layout and precision for mesh `m`, named `file`; with `texcoords`, its
// texture coordinates too (two more planes, read by Facet_Mesh{o}_S0, _T0, _S1, _T1).
// With `tangents` (a normal map's corner tangents), those too (three more planes: Facet_Mesh{o}_UX,
// _UY, _UZ, _UW). With `colors` (the mesh has some), its vertex colours too (Facet_Mesh{o}_CR, _CG,
// _CB, _CA: six planes in all past the texture coordinates).
PovMeshData pov_mesh_data(const Mesh& m, const std::string& file, bool texcoords = false,
                          std::shared_ptr<const std::vector<std::array<double, 4>>> tangents = nullptr,
                          bool colors = false);
// The image itself (binary PPM, 16 bits a channel), a row at a time.
void write_pov_mesh_image(std::ostream& out, const Mesh& m, const PovMeshData& d);
// The functions that read it for object o: Facet_Mesh{o}_PX … _PZ (the hit point)
// and _MX … _MZ (the unnormalized normal), each of uv_mapping's (u, v).
std::string pov_mesh_decoder(const PovMeshData& d, size_t o);
// Mesh o's include file: the mesh2 objects the scene's objects instance,
// Facet_Mesh{o} and Facet_Mesh{o}_Copy{k} (inset by insets[k − 1] along the
// normals, for the one-run file's copies). `normals`: with normal_vectors (POV-Ray's
// own shading reads them); `numbered`: with the uv vectors of the data image's blocks.
// Lists in float32, which is what POV-Ray stores them in.
void write_pov_mesh_include(std::ostream& out, const Mesh& m, size_t o, const std::string& name, bool normals,
                            bool numbered, const std::vector<double>& insets);

}  // namespace facet::targets
