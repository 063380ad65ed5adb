// facet — reading a glTF file's triangles, shared by `facet import-gltf`
// (scene/gltf.cpp) and the mesh references of scene files (GltfReferences).
//
// One code path turns a primitive into facet's mesh arrays: its accessors are
// checked against their buffer views, buffers and the file before anything is read,
// what it will hold is counted against the scene's limit before anything is
// allocated, and then it is streamed into the mesh (no per-vertex objects).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "core/vec.h"
#include "scene/scene.h"

namespace facet::gltf_detail {

// ---------------------------------------------------------------- 4×4 matrices, column-major as glTF

struct Mat4 {
  double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  double operator()(int row, int col) const { return m[col * 4 + row]; }
  double& operator()(int row, int col) { return m[col * 4 + row]; }
  Mat4 operator*(const Mat4& b) const;
  Vec3 point(const Vec3& p) const;
  Vec3 direction(const Vec3& d) const;
  double det3() const;
  // Normals transform by the inverse transpose of the upper 3×3 (up to scale: the cofactor matrix).
  Vec3 normal(const Vec3& n) const;
};

Mat4 local_matrix(const tinygltf::Node& n);

// ---------------------------------------------------------------- accessors

// An accessor's elements, checked to lie inside its buffer view and its buffer.
// An accessor's elements, checked to lie inside its buffer view and its buffer. A sparse
// accessor, or one without a buffer view (zeros, glTF 2.0 §3.6.2.3), is read into a dense
// copy the Reader keeps, with the sparse values substituted (§3.6.2.4).
struct AccessorView {
  int accessor = -1;
  const unsigned char* data = nullptr;
  size_t count = 0, stride = 0;
  int component = 0;
  int width = 0;            // components an element: 1 SCALAR … 4 VEC4, 16 MAT4
  bool normalized = false;  // integers as fractions (glTF 2.0 §3.11)
};

class Reader {
 public:
  Reader(const tinygltf::Model& m, std::string file) : m_(m), file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& path, const std::string& message) const;
  const tinygltf::Model& model() const { return m_; }
  const std::string& file() const { return file_; }

  // Accessor `index` (named at `path`): VEC3 of FLOAT, or unsigned SCALAR indices.
  AccessorView vec3(int index, const std::string& path) const;
  AccessorView indices(int index, const std::string& path) const;
  // VEC2 of FLOAT, or of normalized unsigned bytes or shorts (glTF's TEXCOORD_n).
  AccessorView vec2(int index, const std::string& path) const;
  Vec3 vec3_at(const AccessorView& a, size_t i) const;  // fails on a non-finite element
  std::array<double, 2> vec2_at(const AccessorView& a, size_t i) const;
  // VEC4 of FLOAT (glTF's TANGENT); an element must be finite, its xyz not zero.
  AccessorView vec4(int index, const std::string& path) const;
  std::array<double, 4> vec4_at(const AccessorView& a, size_t i) const;
  static uint32_t index_at(const AccessorView& a, size_t i);
  // COLOR_n: VEC3 or VEC4 of FLOAT or of normalized unsigned bytes or shorts; RGBA (alpha 1 for VEC3).
  AccessorView color(int index, const std::string& path) const;
  std::array<double, 4> color_at(const AccessorView& a, size_t i) const;
  // JOINTS_n: VEC4 of unsigned bytes or shorts; WEIGHTS_n: VEC4 of FLOAT or normalized unsigned
  // bytes or shorts; an inverse bind matrix: MAT4 of FLOAT. Elements as numbers, fails on a non-finite one.
  AccessorView joints(int index, const std::string& path) const;
  AccessorView weights(int index, const std::string& path) const;
  AccessorView mat4(int index, const std::string& path) const;
  std::array<double, 4> quad_at(const AccessorView& a, size_t i) const;
  Mat4 mat4_at(const AccessorView& a, size_t i) const;

  // The parent of every node (−1: none, kSeveral: more than one), from the children lists.
  static constexpr int kSeveral = -2;
  const std::vector<int>& parents() const;
  // Node `ni`'s world matrix: its ancestors' local matrices, the root's first (as a
  // scene's traversal multiplies them). Fails where a node has several parents or
  // the ancestors make a cycle.
  Mat4 world_matrix(int ni) const;

 private:
  AccessorView view(int index, const std::string& path, int type) const;
  // The bytes of `count` elements of `elem` bytes at `stride` from byte `offset` of buffer view
  // `view` (named by `owner`, the accessor's or its sparse part's key): checked to lie inside it.
  const unsigned char* view_bytes(int view, size_t offset, size_t count, size_t elem, size_t stride,
                                  const std::string& owner) const;
  AccessorView dense(int index, const tinygltf::Accessor& a, size_t elem) const;
  double component_at(const AccessorView& a, size_t i, int k) const;
  const tinygltf::Model& m_;
  std::string file_;
  mutable std::map<int, std::vector<unsigned char>> dense_;  // sparse accessors, made dense
  mutable std::vector<int> parents_;
  mutable bool have_parents_ = false;
};

// ---------------------------------------------------------------- primitives

// What the meshes of one scene hold, counted before they are read.
struct MeshSize {
  uint64_t vertices = 0, triangles = 0;
};

// A triangle primitive checked and counted, nothing read yet. `where` names the
// node or mesh whose transform it gets, for the errors that transform causes.
struct PrimitivePlan {
  const tinygltf::Primitive* prim = nullptr;
  std::string path, where;
  AccessorView positions, normals, indices;
  bool has_normals = false, has_indices = false;
  std::array<AccessorView, 2> texcoords;  // the mesh's sets 0 and 1: TEXCOORD_0 and _1 unless mapped otherwise
  std::array<bool, 2> has_texcoords{false, false};
  AccessorView tangents;  // TANGENT
  bool has_tangents = false;
  AccessorView colors;  // COLOR_0: RGB or RGBA, float or normalized unsigned bytes or shorts
  bool has_colors = false;
  int mode = TINYGLTF_MODE_TRIANGLES;  // or a strip (5) or a fan (6): corner() lists their triangles
  MeshSize size;  // at most: zero-area (flat) and degenerate triangles are dropped
  // Morph targets of non-zero weight, at the weights the file gives (the node's, else the
  // mesh's; glTF 2.0 §3.7.2.2): each attribute is its base plus Σ weight · the target's.
  struct Morph {
    double weight = 0;
    AccessorView positions, normals, tangents;
    bool has_positions = false, has_normals = false, has_tangents = false;
  };
  std::vector<Morph> morphs;
  // A skinned primitive (glTF 2.0 §3.7.3): vertex i takes Σ_k WEIGHTS_0[i][k] ·
  // joint_matrices[JOINTS_0[i][k]], each a joint's world matrix times its inverse bind
  // matrix, at the pose the nodes' transforms give; its own node's transform is ignored.
  bool skinned = false;
  std::vector<Mat4> joint_matrices;
  AccessorView joints, weights;
};

bool is_triangles(const tinygltf::Primitive& prim);
// `texcoords`: the glTF sets TEXCOORD_n read as the mesh's sets 0 and 1.
PrimitivePlan plan_primitive(const Reader& r, const tinygltf::Primitive& prim, const std::string& path,
                             const std::string& where, std::array<int64_t, 2> texcoords = {0, 1});
// The primitive's morph targets at the weights `node` (or else `mesh`) gives, and, where
// `node` has a skin, its skinning at the pose of the file's node transforms (the rest pose a
// viewer shows without animation). `node_index` −1: a mesh read without a node (weights of
// the mesh, no skin). `notes` says what was applied.
void plan_deformation(const Reader& r, PrimitivePlan& p, const tinygltf::Mesh& mesh, int node_index,
                      std::vector<std::string>& notes);
// Appends the primitive in the world transform `world` to `mesh`: with NORMAL, its
// vertices and normals (degenerate triangles dropped); without, flat normals, each
// triangle its own three vertices (zero-area triangles dropped); a mirroring
// transform turns the triangles round so they still face their normals. TANGENT
// goes along (xyz by the transform, w negated by a mirroring one) where every primitive
// of the mesh has it; else the mesh keeps none and takes facet's MikkTSpace tangents.
// COLOR_0 goes along as the mesh's vertex colours (RGBA, alpha 1 for RGB); a primitive of a
// mesh whose others have them and it not is white (glTF: no COLOR_0 multiplies by nothing).
// Does not build the hierarchy. `notes` says which primitives had no normals, which
// tangents were left and which primitives were made white.
void append_primitive(const Reader& r, const PrimitivePlan& p, const Mat4& world, Mesh& mesh,
                      std::vector<std::string>& notes);

// The limit on what one scene's meshes may hold, checked before they are allocated:
// at most kMaxSceneTriangles triangles and kMaxSceneVertices vertices, and no more
// than the memory available (about kVertexBytes a vertex and kTriangleBytes a
// triangle, with the hierarchy).
inline constexpr uint64_t kMaxSceneTriangles = 100'000'000;
inline constexpr uint64_t kMaxSceneVertices = 100'000'000;
inline constexpr uint64_t kVertexBytes = 48, kTriangleBytes = 64;
class MeshBudget {
 public:
  // Adds `more`; else throws InputError naming `file`, `path` and the limit. `what`
  // says what is added ("nodes[3]'s meshes[0].primitives[0]").
  void add(const MeshSize& more, const std::string& file, const std::string& path, const std::string& what);
  const MeshSize& total() const { return total_; }

 private:
  MeshSize total_;
};

// "2,000,000"
std::string thousands(uint64_t n);
// Reading a mesh this big takes a second or so: progress() says so (a million
// triangles, read and their hierarchy built, take about 0.4 s on a 2-core machine).
inline constexpr uint64_t kProgressTriangles = 1'000'000;

// ---------------------------------------------------------------- files

// Checks a GLB's header and chunks (each inside the file, the buffer the BIN chunk
// holds no longer than it) and a .gltf's external buffers (each there), naming the
// key, and each image's buffer view inside its buffer and no data URI empty; then loads
// the bytes with tinygltf, whose warnings become notes. External buffers are read from
// `folder` (none with an empty one). Images are not decoded: tinygltf keeps a data URI's
// bytes, a buffer view's stay in the buffer, an external file's URI is kept
// (scene/gltf_images.h reads them).
tinygltf::Model load_model(const std::string& data, bool binary, const std::string& path, const std::string& folder,
                           std::vector<std::string>& notes);
// The file at `path`, read and loaded; its bytes are freed before this returns.
tinygltf::Model load_model_file(const std::string& path, std::vector<std::string>& notes);

// RFC 3986 percent-decoding of a relative URI (glTF 2.0 §3.7.2: "URIs … percent-encoded").
std::string percent_decoded(const std::string& uri);
// The file an external `uri` (not a data: URI) of the glTF at `path` names, as an absolute
// path: percent-decoded, relative to `folder` (the glTF's), and inside it or inside a folder
// the user allowed (core/io.h, confined_path()). Else InputError naming `path` and `key`,
// with one message whether or not such a file exists.
std::string uri_file(const std::string& folder, const std::string& uri, const std::string& path,
                     const std::string& key);

}  // namespace facet::gltf_detail
