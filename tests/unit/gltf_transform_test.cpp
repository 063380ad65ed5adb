// glTF node transforms as the specification states them (glTF 2.0 §3.5.2, §3.7.2.1,
// §3.7.3): positions by the node's world matrix, normals by its inverse transpose,
// tangents by the matrix with their handedness turned by a mirror, the winding reversed
// by a mirror; TRS and `matrix`; nested hierarchies; one mesh instanced by several nodes;
// skins at the pose of the file's node transforms (the node's own transform ignored);
// morph targets at the file's weights. Each imported mesh is checked against the same
// transform worked out here, and against its own winding: a normal that faces away from
// its triangle is a mesh turned inside out.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/io.h"
#include "scene/gltf.h"
#include "scene/gltf_read.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using gltf_detail::Mat4;
using nlohmann::json;

// A unit cube around the origin, 24 vertices (each face its own four, its outward normal
// and a tangent along +u), 12 triangles wound counter-clockwise seen from outside, and a
// morph target that moves +x faces out by 1.
struct Cube {
  std::vector<float> positions, normals, tangents, morph;
  std::vector<uint16_t> indices;
  Cube() {
    const float axes[6][3][3] = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},   {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                                 {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},   {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
                                 {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}};
    for (const auto& f : axes) {  // n, u, v with u × v = n
      const uint16_t base = uint16_t(positions.size() / 3);
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        for (int k = 0; k < 3; ++k) {
          positions.push_back(0.5f * (f[0][k] + c[0] * f[1][k] + c[1] * f[2][k]));
          normals.push_back(f[0][k]);
          tangents.push_back(f[1][k]);
          morph.push_back(f[0][0] > 0 && k == 0 ? 1.0f : 0.0f);
        }
        tangents.push_back(1);
      }
      indices.insert(indices.end(), {base, uint16_t(base + 1), uint16_t(base + 2), base, uint16_t(base + 2),
                                     uint16_t(base + 3)});
    }
  }
};

std::string bytes_of(const void* p, size_t n) { return std::string(static_cast<const char*>(p), n); }

// The cube's buffer: positions, normals, tangents, the morph target, indices.
std::string cube_bin() {
  Cube c;
  return bytes_of(c.positions.data(), c.positions.size() * 4) + bytes_of(c.normals.data(), c.normals.size() * 4) +
         bytes_of(c.tangents.data(), c.tangents.size() * 4) + bytes_of(c.morph.data(), c.morph.size() * 4) +
         bytes_of(c.indices.data(), c.indices.size() * 2);
}

void set_buffer(json& g, const std::string& bin) {
  g["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + test::base64(bin)}}});
}

// The cube as a glTF document: mesh 0 (with its morph target, weight 0 unless `weights`),
// the buffer's views and accessors; nodes, skins and the scene are the caller's.
json cube_gltf(const std::vector<double>& weights = {}) {
  Cube c;
  const size_t p = c.positions.size() * 4, t = c.tangents.size() * 4, i = c.indices.size() * 2;
  json g = {{"asset", {{"version", "2.0"}}},
            {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", p}},
                             {{"buffer", 0}, {"byteOffset", p}, {"byteLength", p}},
                             {{"buffer", 0}, {"byteOffset", 2 * p}, {"byteLength", t}},
                             {{"buffer", 0}, {"byteOffset", 2 * p + t}, {"byteLength", p}},
                             {{"buffer", 0}, {"byteOffset", 3 * p + t}, {"byteLength", i}}}},
            {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 24}, {"type", "VEC3"},
                            {"min", {-0.5, -0.5, -0.5}}, {"max", {0.5, 0.5, 0.5}}},
                           {{"bufferView", 1}, {"componentType", 5126}, {"count", 24}, {"type", "VEC3"}},
                           {{"bufferView", 2}, {"componentType", 5126}, {"count", 24}, {"type", "VEC4"}},
                           {{"bufferView", 3}, {"componentType", 5126}, {"count", 24}, {"type", "VEC3"}},
                           {{"bufferView", 4}, {"componentType", 5123}, {"count", 36}, {"type", "SCALAR"}}}},
            {"materials", {{{"name", "grey"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}},
                                                                        {"metallicFactor", 0}}}}}},
            {"meshes", {{{"name", "cube"},
                         {"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TANGENT", 2}}},
                                          {"indices", 4},
                                          {"material", 0},
                                          {"targets", {{{"POSITION", 3}}}}}}}}}}};
  if (!weights.empty()) g["meshes"][0]["weights"] = weights;
  set_buffer(g, cube_bin());
  return g;
}

fs::path write(const std::string& name, const json& g) {
  fs::path p = test::scratch("gltf_transform", name);
  write_file_atomic(p.string(), g.dump());
  return p;
}

Scene import(const json& g, const std::string& name, std::vector<std::string>* notes_out = nullptr) {
  std::vector<std::string> notes;
  Scene s = import_gltf(write(name, g).string(), {}, notes);
  if (notes_out) *notes_out = notes;
  return s;
}

Mat4 matrix_of(const json& node) {
  tinygltf::Node n;
  if (node.contains("matrix")) n.matrix = node["matrix"].get<std::vector<double>>();
  if (node.contains("translation")) n.translation = node["translation"].get<std::vector<double>>();
  if (node.contains("rotation")) n.rotation = node["rotation"].get<std::vector<double>>();
  if (node.contains("scale")) n.scale = node["scale"].get<std::vector<double>>();
  return gltf_detail::local_matrix(n);
}

// The inverse transpose of m's upper 3×3, worked out by Gauss–Jordan elimination (an
// independent route to what the import computes as a cofactor matrix).
std::array<std::array<double, 3>, 3> inverse_transpose(const Mat4& m) {
  double a[3][6];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 6; ++c) a[r][c] = c < 3 ? m(r, c) : (c - 3 == r ? 1 : 0);
  for (int c = 0; c < 3; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 3; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[pivot][c])) pivot = r;
    std::swap(a[c], a[pivot]);
    for (int r = 0; r < 3; ++r) {
      if (r == c) continue;
      const double k = a[r][c] / a[c][c];
      for (int j = 0; j < 6; ++j) a[r][j] -= k * a[c][j];
    }
  }
  std::array<std::array<double, 3>, 3> out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[size_t(r)][size_t(c)] = a[c][3 + r] / a[c][c];  // (A⁻¹)ᵀ
  return out;
}

Vec3 apply(const std::array<std::array<double, 3>, 3>& m, const Vec3& v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

// Every vertex of `mesh` is the cube's, moved by `world` (and the morph at `weight`): its
// position, its normal by the inverse transpose, its tangent by the matrix, w turned by a
// mirror; and every triangle faces the way its normals do.
void expect_cube(const Mesh& mesh, const Mat4& world, const std::string& what, double weight = 0) {
  Cube c;
  ASSERT_EQ(mesh.positions.size(), 24u) << what;
  ASSERT_EQ(mesh.tangents.size(), 24u) << what;
  const auto it = inverse_transpose(world);
  const bool mirror = world.det3() < 0;
  for (size_t v = 0; v < 24; ++v) {
    const Vec3 p(c.positions[3 * v] + weight * c.morph[3 * v], c.positions[3 * v + 1], c.positions[3 * v + 2]);
    const Vec3 n(c.normals[3 * v], c.normals[3 * v + 1], c.normals[3 * v + 2]);
    const Vec3 t(c.tangents[4 * v], c.tangents[4 * v + 1], c.tangents[4 * v + 2]);
    const Vec3 wp = world.point(p), wn = normalize(apply(it, n)), wt = normalize(world.direction(t));
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(mesh.positions[v][k], wp[k], 1e-9) << what << " vertex " << v;
      EXPECT_NEAR(mesh.normals[v][k], wn[k], 1e-9) << what << " normal " << v;
      EXPECT_NEAR(mesh.tangents[v][size_t(k)], wt[k], 1e-9) << what << " tangent " << v;
    }
    EXPECT_EQ(mesh.tangents[v][3], mirror ? -1.0 : 1.0) << what << " handedness " << v;
  }
  for (const auto& tri : mesh.triangles) {
    const Vec3 face = cross(mesh.positions[tri[1]] - mesh.positions[tri[0]], mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    for (uint32_t k : tri) EXPECT_GT(dot(face, mesh.normals[k]), 0) << what << ": a triangle faces away from its normals";
  }
}

const double kHalf = std::sqrt(0.5);

// One node of each transform kind, each holding the cube.
TEST(GltfTransforms, EachKindMovesPositionsNormalsTangentsAndWinding) {
  const std::vector<json> nodes = {
      {{"name", "rotated"}, {"rotation", {-kHalf, 0, 0, kHalf}}},  // Box.gltf's Y-up root: −90° about x
      {{"name", "trs"}, {"translation", {1, 2, 3}}, {"rotation", {0.1, 0.7, -0.2, 0.678233}}, {"scale", {2, 2, 2}}},
      {{"name", "nonuniform"}, {"rotation", {0, 0, std::sin(0.3), std::cos(0.3)}}, {"scale", {3, 0.5, 1}}},
      {{"name", "mirrored"}, {"scale", {-1, 1, 1}}, {"rotation", {0, kHalf, 0, kHalf}}},
      {{"name", "matrix"}, {"matrix", {1, 0.5, 0, 0, 0, 1, 0.25, 0, 0.3, 0, 2, 0, 4, 5, 6, 1}}},  // sheared
  };
  for (const auto& node : nodes) {
    json g = cube_gltf();
    json n = node;
    n["mesh"] = 0;
    g["nodes"] = {n};
    g["scenes"] = {{{"nodes", {0}}}};
    Scene s = import(g, node["name"].get<std::string>() + ".gltf");
    ASSERT_EQ(s.objects.size(), 1u);
    expect_cube(*s.objects[0].mesh, matrix_of(node), node["name"]);
  }
}

TEST(GltfTransforms, NestedNodesAndInstancesTakeTheirWholeChain) {
  json g = cube_gltf();
  const json parent = {{"name", "parent"}, {"rotation", {0, 0, kHalf, kHalf}}, {"translation", {0, 1, 0}},
                       {"children", {1, 2}}};
  const json child = {{"name", "child"}, {"mesh", 0}, {"rotation", {kHalf, 0, 0, kHalf}}, {"translation", {2, 0, 0}},
                      {"children", {3}}};
  const json other = {{"name", "instance"}, {"mesh", 0}, {"scale", {1, -2, 1}}};
  const json grandchild = {{"name", "grandchild"}, {"mesh", 0}, {"rotation", {0, kHalf, 0, kHalf}}};
  g["nodes"] = {parent, child, other, grandchild};
  g["scenes"] = {{{"nodes", {0}}}};
  Scene s = import(g, "nested.gltf");
  ASSERT_EQ(s.objects.size(), 3u);
  const Mat4 p = matrix_of(parent), c = p * matrix_of(child);
  for (const auto& o : s.objects) {
    if (o.name == "child") expect_cube(*o.mesh, c, "child");
    if (o.name == "instance") expect_cube(*o.mesh, p * matrix_of(other), "instance");
    if (o.name == "grandchild") expect_cube(*o.mesh, c * matrix_of(grandchild), "grandchild");
  }
}

// glTF 2.0 §3.7.3.3: a skinned mesh takes its joints' transforms; its own node's is ignored.
TEST(GltfTransforms, SkinnedMeshTakesItsJointsPoseAndNotItsNode) {
  json g = cube_gltf();
  // One joint, rotated and moved; its inverse bind matrix undoes a bind pose translated by (0, 0, 1).
  const float ibm[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1};
  const uint8_t joints[24 * 4] = {};
  std::vector<float> weights(24 * 4, 0.0f);
  for (size_t v = 0; v < 24; ++v) weights[4 * v] = 1;
  std::string bin = cube_bin();
  const size_t at = bin.size();
  bin += bytes_of(ibm, sizeof ibm) + bytes_of(joints, sizeof joints) + bytes_of(weights.data(), weights.size() * 4);
  set_buffer(g, bin);
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 64}});
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 64}, {"byteLength", 96}});
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 160}, {"byteLength", 384}});
  g["accessors"].push_back({{"bufferView", 5}, {"componentType", 5126}, {"count", 1}, {"type", "MAT4"}});
  g["accessors"].push_back({{"bufferView", 6}, {"componentType", 5121}, {"count", 24}, {"type", "VEC4"}});
  g["accessors"].push_back({{"bufferView", 7}, {"componentType", 5126}, {"count", 24}, {"type", "VEC4"}});
  g["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = 6;
  g["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = 7;
  g["skins"] = {{{"joints", {1}}, {"inverseBindMatrices", 5}}};
  const json skinned = {{"name", "skinned"}, {"mesh", 0}, {"skin", 0}, {"translation", {100, 0, 0}}};
  const json joint = {{"name", "joint"}, {"rotation", {0, kHalf, 0, kHalf}}, {"translation", {0, 2, 1}}};
  g["nodes"] = {skinned, joint};
  g["scenes"] = {{{"nodes", {0, 1}}}};
  std::vector<std::string> notes;
  Scene s = import(g, "skinned.gltf", &notes);
  ASSERT_EQ(s.objects.size(), 1u);
  Mat4 inv;
  inv(2, 3) = -1;
  expect_cube(*s.objects[0].mesh, matrix_of(joint) * inv, "skinned");
  bool noted = false;
  for (const auto& n : notes) noted |= n.find("skinned by skins[0]") != std::string::npos;
  EXPECT_TRUE(noted);
}

// glTF 2.0 §3.7.2.2: the base plus Σ weight · target, at the mesh's (or the node's) weights.
TEST(GltfTransforms, MorphTargetsAtTheFilesWeights) {
  for (const auto& [mesh_w, node_w, expected] : {std::tuple<double, double, double>{0.5, -1, 0.5}, {0.5, 0.25, 0.25}}) {
    json g = cube_gltf({mesh_w});
    json node = {{"name", "morphed"}, {"mesh", 0}, {"rotation", {0, 0, kHalf, kHalf}}};
    if (node_w >= 0) node["weights"] = {node_w};
    g["nodes"] = {node};
    g["scenes"] = {{{"nodes", {0}}}};
    Scene s = import(g, "morphed.gltf");
    ASSERT_EQ(s.objects.size(), 1u);
    expect_cube(*s.objects[0].mesh, matrix_of(node), "morphed", expected);
  }
}

// A sparse accessor, and one without a buffer view, read as glTF 2.0 §3.6.2 says.
TEST(GltfTransforms, SparseMorphTargetIsReadDense) {
  json g = cube_gltf({1.0});
  // The morph target as zeros with the four +x vertices (0–3) replaced by (1, 0, 0): sparse.
  const uint16_t idx[4] = {0, 1, 2, 3};
  const float val[12] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
  std::string bin = cube_bin();
  const size_t at = bin.size();
  bin += bytes_of(idx, sizeof idx) + bytes_of(val, sizeof val);
  set_buffer(g, bin);
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 8}});
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 8}, {"byteLength", 48}});
  g["accessors"].push_back({{"componentType", 5126},
                            {"count", 24},
                            {"type", "VEC3"},
                            {"sparse", {{"count", 4},
                                        {"indices", {{"bufferView", 5}, {"componentType", 5123}}},
                                        {"values", {{"bufferView", 6}}}}}});
  g["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 5}}};
  g["nodes"] = {{{"name", "sparse"}, {"mesh", 0}}};
  g["scenes"] = {{{"nodes", {0}}}};
  Scene s = import(g, "sparse.gltf");
  ASSERT_EQ(s.objects.size(), 1u);
  expect_cube(*s.objects[0].mesh, Mat4(), "sparse", 1.0);
}

// glTF 2.0 §3.7.2.1: strips and fans are triangles (a strip's odd triangles turned so all keep
// the first's winding); points and lines have no surface and are left out with a note.
TEST(GltfTransforms, StripsAndFansAreTrianglesPointsAndLinesLeftOut) {
  // Six vertices on the unit circle in z = 0, counter-clockwise seen from +z, normals +z.
  std::vector<float> pos, nor;
  for (int k = 0; k < 6; ++k) {
    const double a = 2 * M_PI * k / 6;
    pos.insert(pos.end(), {float(std::cos(a)), float(std::sin(a)), 0});
    nor.insert(nor.end(), {0, 0, 1});
  }
  const uint16_t strip[6] = {0, 1, 5, 2, 4, 3};  // a zig-zag across the hexagon, counter-clockwise first
  std::string bin = bytes_of(pos.data(), pos.size() * 4) + bytes_of(nor.data(), nor.size() * 4) + bytes_of(strip, 12);
  json g = {{"asset", {{"version", "2.0"}}},
            {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 72}},
                             {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 72}},
                             {{"buffer", 0}, {"byteOffset", 144}, {"byteLength", 12}}}},
            {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 6}, {"type", "VEC3"},
                            {"min", {-1, -1, 0}}, {"max", {1, 1, 0}}},
                           {{"bufferView", 1}, {"componentType", 5126}, {"count", 6}, {"type", "VEC3"}},
                           {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
            {"meshes", {{{"name", "shapes"},
                         {"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"mode", 5}},
                                         {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"mode", 6}},
                                         {{"attributes", {{"POSITION", 0}}}, {"mode", 6}},
                                         {{"attributes", {{"POSITION", 0}}}, {"mode", 1}}}}}}},
            {"nodes", {{{"name", "shapes"}, {"mesh", 0}}}},
            {"scenes", {{{"nodes", {0}}}}}};
  set_buffer(g, bin);
  std::vector<std::string> notes;
  Scene s = import(g, "strips.gltf", &notes);
  ASSERT_EQ(s.objects.size(), 3u);  // the lines are left out
  for (const auto& o : s.objects) {
    EXPECT_EQ(o.mesh->triangles.size(), 4u) << o.name;
    for (const auto& tri : o.mesh->triangles) {
      const Vec3 face = cross(o.mesh->positions[tri[1]] - o.mesh->positions[tri[0]],
                              o.mesh->positions[tri[2]] - o.mesh->positions[tri[0]]);
      EXPECT_GT(face.z, 0) << o.name << ": a triangle wound the other way";
      for (uint32_t k : tri) EXPECT_EQ(o.mesh->normals[k].z, 1) << o.name;
    }
  }
  bool noted = false;
  for (const auto& n : notes) noted |= n.find("meshes[0].primitives[3]: mode 1 (points or lines)") != std::string::npos;
  EXPECT_TRUE(noted);
}

// KHR_lights_punctual is photometric (candela, lux); facet's light colour is radiometric as
// Blender's lights are, at glTF-Blender-IO's 683 lm/W: Blender's exporter writes a 1000 W
// point light as 1000 / (4π) · 683 cd, which must import as Blender's own conversion of the
// same light, C = P / (4π²); a 2 W/m² sun (683 · 2 lux) as C = S / π. A node's scale leaves
// a light's intensity as it is (the extension's README).
TEST(GltfLights, PhotometricUnitsImportAsBlendersRadiometricOnes) {
  json g = cube_gltf();
  g["extensionsUsed"] = {"KHR_lights_punctual"};
  g["extensions"] = {{"KHR_lights_punctual",
                      {{"lights", {{{"type", "point"}, {"intensity", 1000 / (4 * M_PI) * 683}},
                                   {{"type", "directional"}, {"intensity", 2 * 683}, {"color", {1, 0.5, 0.25}}},
                                   {{"type", "spot"}, {"intensity", 100 / (4 * M_PI) * 683}, {"range", 7.5},
                                    {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.5}}}}}}}}};
  g["nodes"] = {{{"name", "cube"}, {"mesh", 0}},
                {{"name", "point"}, {"translation", {0, 3, 0}}, {"scale", {5, 5, 5}},
                 {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                {{"name", "sun"}, {"rotation", {-kHalf, 0, 0, kHalf}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}},
                {{"name", "spot"}, {"translation", {0, 0, 4}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}}};
  g["scenes"] = {{{"nodes", {0, 1, 2, 3}}}};
  Scene s = import(g, "lights.gltf");
  ASSERT_EQ(s.lights.size(), 3u);
  const double point = 1000 / (4 * M_PI * M_PI), sun = 2 / M_PI, spot = 100 / (4 * M_PI * M_PI);
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(s.lights[0].color[c], point, 1e-12 * point);
  EXPECT_NEAR(s.lights[1].color[0], sun, 1e-12);
  EXPECT_NEAR(s.lights[1].color[1], sun / 2, 1e-12);
  EXPECT_NEAR(s.lights[2].color[0], spot, 1e-12 * spot);
  EXPECT_EQ(s.lights[0].attenuation.law, Attenuation::Law::InverseSquare);
  EXPECT_NEAR(s.lights[0].position.y, 3, 1e-12);
  EXPECT_NEAR(s.lights[1].direction.y, -1, 1e-12);  // −Z turned −90° about x: straight down
  EXPECT_NEAR(s.lights[2].cutoff, 0.5 * 180 / M_PI, 1e-12);
  EXPECT_EQ(s.lights[0].attenuation.law, Attenuation::Law::InverseSquare);  // no range: to infinity
  EXPECT_EQ(s.lights[2].attenuation.law, Attenuation::Law::InverseSquareRange);  // the extension's window
  EXPECT_EQ(s.lights[2].attenuation.range, 7.5);
}

}  // namespace
}  // namespace facet
