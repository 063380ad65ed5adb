// facet's MikkTSpace tangents (scene/tangents.h) against Blender's own: a smooth UV sphere
// (seam and poles included) and a plane with mirrored UVs, built by pip bpy, whose
// Mesh.calc_tangents() gives each corner a tangent and a bitangent sign
// (tests/tools/tangents_blender.py). facet reads the same corners as a mesh (one vertex a
// corner, glTF's v = 1 − Blender's v) and must give every corner Blender's sign and its
// tangent to within 2e-5 (Blender computes in float).
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "core/diagnostics.h"
#include "core/io.h"
#include "reference/raycaster.h"
#include "scene/tangents.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
constexpr double kTolerance = 2e-5;

Mesh corners_mesh(const nlohmann::json& j) {
  Mesh m;
  for (const auto& c : j["corners"]) {
    m.positions.push_back(Vec3(c["position"][0].get<double>(), c["position"][1].get<double>(), c["position"][2].get<double>()));
    m.normals.push_back(normalize(Vec3(c["normal"][0].get<double>(), c["normal"][1].get<double>(), c["normal"][2].get<double>())));
    m.texcoords[0].push_back({c["uv"][0].get<double>(), 1 - c["uv"][1].get<double>()});
  }
  for (const auto& t : j["triangles"]) m.triangles.push_back({t[0].get<uint32_t>(), t[1].get<uint32_t>(), t[2].get<uint32_t>()});
  return m;
}

// The largest |T − T_blender| over the corners, and how many signs differ.
struct Deviation {
  double tangent = 0;
  int signs = 0;
};
Deviation compare(const nlohmann::json& j, const std::vector<std::array<double, 4>>& ours) {
  Deviation d;
  const auto& tris = j["triangles"];
  for (size_t f = 0; f < tris.size(); ++f)
    for (size_t k = 0; k < 3; ++k) {
      const auto& c = j["corners"][tris[f][k].get<size_t>()];
      const auto& t = ours[3 * f + k];
      for (size_t a = 0; a < 3; ++a) d.tangent = std::max(d.tangent, std::fabs(t[a] - c["tangent"][a].get<double>()));
      if (t[3] != c["sign"].get<double>()) ++d.signs;
    }
  return d;
}

// A deliberately wrong rule: each corner's own triangle's ∂p/∂s, made ⟂ n, not the group's
// angle-weighted sum.
std::vector<std::array<double, 4>> unsmoothed(const Mesh& m, const std::vector<std::array<double, 4>>& right) {
  std::vector<std::array<double, 4>> out = right;
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    Mesh one;
    for (uint32_t v : m.triangles[f]) {
      one.positions.push_back(m.positions[v]);
      one.normals.push_back(m.normals[v]);
      one.texcoords[0].push_back(m.texcoords[0][v]);
    }
    one.triangles = {{0, 1, 2}};
    auto t = mikktspace_tangents(one, 0);
    for (size_t k = 0; k < 3; ++k) out[3 * f + k] = t[k];
  }
  return out;
}

TEST(Tangents, MikkTSpaceAsBlenderComputesIt) {
  const fs::path dir = test::scratch("tangents", "");
  const std::string out = (dir / "blender_tangents.json").string();
  const std::string command = std::string("'") + FACET_PYTHON + "' '" + FACET_SOURCE_DIR +
                              "/tests/tools/tangents_blender.py' '" + out + "' > '" + (dir / "blender.log").string() + "' 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const nlohmann::json blender = read_json_file(out);
  ASSERT_EQ(blender["meshes"].size(), 2u);
  int mirrored = 0;
  for (const auto& j : blender["meshes"]) {
    const Mesh m = corners_mesh(j);
    const auto ours = mikktspace_tangents(m, 0);
    ASSERT_EQ(ours.size(), m.triangles.size() * 3);
    const Deviation d = compare(j, ours);
    std::cout << m.triangles.size() << " triangles: max |T − T_blender| " << d.tangent << ", signs differing " << d.signs
              << "\n";
    EXPECT_LT(d.tangent, kTolerance);
    EXPECT_EQ(d.signs, 0);
    for (const auto& t : ours) mirrored += t[3] < 0;
    const Deviation wrong = compare(j, unsmoothed(m, ours));
    std::cout << "  without the group's weighted sum: " << wrong.tangent << "\n";
    if (m.triangles.size() > 100) {
      EXPECT_GT(wrong.tangent, 100 * kTolerance) << "the sphere's corners are smoothed";
    }
  }
  EXPECT_GT(mirrored, 0) << "the mirrored plane's corners have w = −1";
}

// A mesh's own tangents ("tangents", glTF's TANGENT) are the normal map's frame, corner by
// corner, in place of facet's MikkTSpace ones: the reference render of
// tests/scenes/textured_mesh_tangents.json (a mirrored frame unlike MikkTSpace's) differs from
// the same mesh without them, and `validate.*.textured.mesh_tangents` hold every renderer to it.
TEST(Tangents, AMeshsOwnTangentsAreTheNormalMapsFrame) {
  const std::string source = FACET_SOURCE_DIR;
  const Material m = load_material(source + "/examples/textured/textured_normal_cook_torrance.json");
  Scene own = load_scene(source + "/tests/scenes/textured_mesh_tangents.json");
  const Mesh& mesh = *own.objects[0].mesh;
  ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
  const auto corners = mesh_tangents(mesh, 0);
  ASSERT_EQ(corners.size(), 3 * mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (size_t k = 0; k < 3; ++k) EXPECT_EQ(corners[3 * t + k], mesh.tangents[mesh.triangles[t][k]]);

  Scene computed = own;
  auto bare = std::make_shared<Mesh>(mesh);
  bare->tangents.clear();
  computed.objects[0].mesh = bare;
  const Render a = render_reference(m, own, 80, 60), b = render_reference(m, computed, 80, 60);
  int differ = 0;
  for (size_t i = 0; i < a.image.rgb.size(); ++i) differ += std::fabs(a.image.rgb[i] - b.image.rgb[i]) > 1e-2;
  std::cout << "channels that differ by more than 1e-2 without the mesh's tangents: " << differ << "\n";
  EXPECT_GT(differ, 500);
}

// Bad "tangents" fail naming the key: a w that is not ±1, a count unlike the positions', a
// tangent of length 0, four numbers not given.
TEST(Tangents, BadMeshTangentsNameTheKey) {
  const nlohmann::json mesh = {{"type", "mesh"},
                               {"positions", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                               {"normals", {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}},
                               {"texcoords", {{0, 0}, {1, 0}, {0, 1}}},
                               {"triangles", {{0, 1, 2}}}};
  const std::pair<nlohmann::json, std::string> cases[] = {
      {{{1, 0, 0, 1}, {1, 0, 0, 0.5}, {1, 0, 0, 1}}, "objects[0].tangents[1]: w is 0.5; allowed: +1 or −1"},
      {{{1, 0, 0, 1}, {1, 0, 0, 1}}, "objects[0].tangents: has 2 tangents for 3 positions"},
      {{{1, 0, 0, 1}, {0, 0, 0, 1}, {1, 0, 0, 1}}, "objects[0].tangents[1]: the zero vector has no direction"},
      {{{1, 0, 0, 1}, {1, 0, 0}, {1, 0, 0, 1}}, "objects[0].tangents[1]: expected four numbers, found 3 values"},
  };
  for (const auto& [tangents, expected] : cases) {
    nlohmann::json doc = {{"camera", {{"position", {0, 0, 3}}, {"look_at", {0, 0, 0}}}}, {"objects", {mesh}}};
    doc["objects"][0]["tangents"] = tangents;
    try {
      (void)parse_scene(doc, "bad.json");
      ADD_FAILURE() << "accepted " << tangents.dump();
    } catch (const InputError& e) {
      std::string all;
      for (const auto& d : e.diagnostics()) all += d.format() + "\n";
      EXPECT_NE(all.find(expected), std::string::npos) << all;
    }
  }
}

}  // namespace
}  // namespace facet
