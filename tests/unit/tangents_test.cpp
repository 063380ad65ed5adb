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

#include "core/io.h"
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

}  // namespace
}  // namespace facet
