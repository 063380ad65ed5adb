// glTF through tinygltf: a round trip loses nothing, the example file is what
// its generator says, and bad files fail clearly without writing.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/io.h"
#include "reference/raycaster.h"
#include "renderers/process.h"
#include "scene/gltf.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
const fs::path kSource = FACET_SOURCE_DIR;

fs::path scratch(const std::string& name) { return test::scratch("gltf", name); }

void expect_near(const Vec3& a, const Vec3& b, double tol, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

// Everything a renderer reads survives export then import.
void check_round_trip(const Scene& original, const Material* fallback, const std::string& file) {
  std::vector<std::string> notes;
  export_gltf(original, fallback, file, notes);
  Scene back = import_gltf(file, {}, notes);

  ASSERT_EQ(back.objects.size(), original.objects.size());
  for (size_t i = 0; i < original.objects.size(); ++i) {
    const Object& a = original.objects[i];
    const Object& b = back.objects[i];
    EXPECT_EQ(a.type, b.type) << a.name;
    EXPECT_EQ(a.name, b.name);
    // Materials: the full facet description, exactly.
    const Material& ma = original.material_of(i, fallback);
    const Material& mb = back.material_of(i, nullptr);
    EXPECT_EQ(to_json(ma), to_json(mb)) << a.name;
    if (a.type == Object::Type::Sphere) {
      expect_near(a.center, b.center, 0, a.name);
      EXPECT_EQ(a.radius, b.radius);
    } else if (a.type == Object::Type::Plane) {
      expect_near(a.point, b.point, 0, a.name);
      expect_near(a.normal, b.normal, 1e-15, a.name);
      EXPECT_EQ(a.size, b.size);
    } else {
      // glTF stores vertex data as float32.
      ASSERT_EQ(a.mesh->positions.size(), b.mesh->positions.size());
      ASSERT_EQ(a.mesh->triangles, b.mesh->triangles);
      for (size_t v = 0; v < a.mesh->positions.size(); ++v) {
        expect_near(a.mesh->positions[v], b.mesh->positions[v], 1e-6 * (1 + length(a.mesh->positions[v])), a.name);
        expect_near(a.mesh->normals[v], b.mesh->normals[v], 2e-7, a.name);
      }
    }
  }
  ASSERT_EQ(back.lights.size(), original.lights.size());
  for (size_t i = 0; i < original.lights.size(); ++i) {
    const Light& a = original.lights[i];
    const Light& b = back.lights[i];
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.color, b.color);
    EXPECT_EQ(a.attenuation.law, b.attenuation.law);
    EXPECT_EQ(a.attenuation.constant, b.attenuation.constant);
    EXPECT_EQ(a.attenuation.linear, b.attenuation.linear);
    EXPECT_EQ(a.attenuation.quadratic, b.attenuation.quadratic);
    EXPECT_EQ(a.cutoff, b.cutoff);
    EXPECT_EQ(a.exponent, b.exponent);
    if (a.type != Light::Type::Directional) expect_near(a.position, b.position, 1e-12, "light position");
    if (a.type != Light::Type::Point) expect_near(a.direction, b.direction, 1e-12, "light direction");
  }
  EXPECT_EQ(original.ambient, back.ambient);
  Camera::Basis ca = original.camera.basis(), cb = back.camera.basis();
  expect_near(original.camera.position, back.camera.position, 1e-12, "camera position");
  expect_near(ca.forward, cb.forward, 1e-12, "camera forward");
  expect_near(ca.up, cb.up, 1e-12, "camera up");
  EXPECT_NEAR(original.camera.fov, back.camera.fov, 1e-12);

  // And the pictures agree: the reference renders of both.
  Render ra = fallback ? render_reference(*fallback, original, 96, 72) : render_reference(original, 96, 72);
  Render rb = render_reference(back, 96, 72);
  double worst = 0;
  size_t differ = 0;
  for (size_t p = 0; p < ra.object.size(); ++p) {
    differ += ra.object[p] != rb.object[p];
    for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::fabs(ra.image.rgb[p * 3 + size_t(c)] - rb.image.rgb[p * 3 + size_t(c)])));
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_LT(worst, 1e-4) << "float32 vertex data only";
}

TEST(Gltf, MeshSceneRoundTrip) {
  check_round_trip(load_scene((kSource / "examples/scenes/three_meshes.json").string()), nullptr,
                   scratch("three_meshes.gltf").string());
}

// TEXCOORD_0 and TEXCOORD_1 out and back in (float32), and the textured picture the same.
TEST(Gltf, TextureCoordinatesRoundTrip) {
  Material m = load_material((kSource / "examples/textured/textured_cook_torrance.json").string());  // sets 0 and 1
  Scene s = load_scene((kSource / "tests/scenes/textured_mesh.json").string());
  const std::string file = scratch("textured_mesh.glb").string();
  check_round_trip(s, &m, file);
  std::vector<std::string> notes;
  Scene back = import_gltf(file, GltfImportOptions{}, notes);
  const Mesh& a = *s.objects[0].mesh;
  const Mesh* b = nullptr;
  for (const auto& o : back.objects)
    if (o.name == s.objects[0].name) b = o.mesh.get();
  ASSERT_NE(b, nullptr);
  for (size_t set = 0; set < 2; ++set) {
    ASSERT_EQ(b->texcoords[set].size(), a.texcoords[set].size()) << set;
    for (size_t i = 0; i < a.texcoords[set].size(); ++i)
      for (size_t k = 0; k < 2; ++k) EXPECT_EQ(b->texcoords[set][i][k], double(float(a.texcoords[set][i][k])));
  }
}

TEST(Gltf, ExportedCameraHasAValidFarPlane) {
  // glTF 2.0: zfar, when present, is greater than znear (0 made Blender clip the whole scene).
  std::string path = scratch("camera.gltf").string();
  std::vector<std::string> notes;
  export_gltf(load_scene((kSource / "examples/scenes/three_meshes.json").string()), nullptr, path, notes);
  for (const std::string& file : {path, (kSource / "examples/scenes/three_meshes.gltf").string()}) {
    nlohmann::json doc = nlohmann::json::parse(read_file(file));
    const auto& p = doc.at("cameras").at(0).at("perspective");
    EXPECT_GT(p.at("znear").get<double>(), 0) << file;
    if (p.contains("zfar")) {
      EXPECT_GT(p["zfar"].get<double>(), p["znear"].get<double>()) << file;
    }
  }
}

TEST(Gltf, AnalyticSceneRoundTripAsGlb) {
  Material ward = load_material((kSource / "examples/materials/ward.json").string());
  check_round_trip(load_scene("shadows"), &ward, scratch("shadows.glb").string());
}

TEST(Gltf, ExampleFileIsTheExampleScene) {
  // examples/scenes/three_meshes.gltf is `facet export-gltf three_meshes.json`.
  std::vector<std::string> notes;
  Scene g = import_gltf((kSource / "examples/scenes/three_meshes.gltf").string(), {}, notes);
  Scene j = load_scene((kSource / "examples/scenes/three_meshes.json").string());
  ASSERT_EQ(g.objects.size(), 4u);
  EXPECT_GE(g.materials.size(), 3u);
  size_t curved = 0;
  for (const auto& o : g.objects) {
    ASSERT_EQ(o.type, Object::Type::Mesh);
    if (o.mesh->triangles.size() > 100) ++curved;
  }
  EXPECT_GE(curved, 2u) << "a smooth sphere and a torus";
  for (const auto& [k, m] : j.materials) EXPECT_EQ(to_json(m), to_json(g.materials.at(k))) << k;
}

TEST(Gltf, MetallicRoughnessMapsOntoGgx) {
  std::vector<std::string> notes;
  Scene s = import_gltf((kSource / "tests/gltf/one_triangle.gltf").string(), {}, notes);
  const Material& m = s.materials.begin()->second;
  ASSERT_TRUE(m.diffuse && m.specular);
  EXPECT_EQ(m.diffuse->def->name, "lambert");
  EXPECT_EQ(m.diffuse->at("color").rgb, (RGB{0.8, 0.2, 0.1}));  // metallic 0: base colour
  EXPECT_EQ(m.specular->def->name, "ggx");
  EXPECT_DOUBLE_EQ(m.specular->at("alpha").number, 0.25);       // roughness²
  EXPECT_EQ(m.specular->at("geometry").choice, "smith_ggx");
  EXPECT_EQ(m.specular->at("fresnel").model->at("f0").rgb, (RGB{0.04, 0.04, 0.04}));
  bool told = false;
  for (const auto& n : notes) told |= n.find("(1 − F)") != std::string::npos;
  EXPECT_TRUE(told) << "the approximate dielectric diffuse is reported";
}

TEST(Gltf, ExportFallbackIsTheNearestMetallicRoughness) {
  // What viewers without FACET_material show. A conductor (no diffuse, a Fresnel
  // term that states f0) is a metal of base colour f0; roughness is √α.
  auto fallback = [](const char* material) {
    Material m = load_material((kSource / "examples/materials" / material).string());
    std::string path = scratch(std::string(material) + ".gltf").string();
    std::vector<std::string> notes;
    export_gltf(load_scene("single"), &m, path, notes);
    return json::parse(read_file(path)).at("materials").at(0).at("pbrMetallicRoughness");
  };
  json copper = fallback("ggx_conductor.json");  // ggx α 0.3, Schlick f0 (0.95, 0.64, 0.54)
  EXPECT_EQ(copper.value("metallicFactor", 1.0), 1.0);
  EXPECT_EQ(copper.at("baseColorFactor"), json::array({0.95, 0.64, 0.54, 1.0}));
  EXPECT_DOUBLE_EQ(copper.value("roughnessFactor", 1.0), std::sqrt(0.3));
  json plastic = fallback("blinn_phong.json");  // Lambert (0.8, 0.5, 0.3), Blinn–Phong n 50
  EXPECT_EQ(plastic.value("metallicFactor", 1.0), 0.0);
  EXPECT_EQ(plastic.at("baseColorFactor"), json::array({0.8, 0.5, 0.3, 1.0}));
  EXPECT_DOUBLE_EQ(plastic.value("roughnessFactor", 1.0), std::sqrt(std::sqrt(2 / 52.0)));  // α = √(2/(n+2))
}

struct Bad {
  const char* file;
  const char* path;
  const char* words;
};

class BadGltf : public ::testing::TestWithParam<Bad> {};

TEST_P(BadGltf, FailsClearlyAndWritesNothing) {
  const Bad& b = GetParam();
  fs::path out = scratch(std::string(b.file) + ".json");
  fs::remove(out);
  std::string cmd = std::string(FACET_BIN) + " import-gltf " + (kSource / "tests/gltf" / b.file).string() + " -o " +
                    out.string();
  ProcessResult r = run_process({"sh", "-c", cmd});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(std::string(": ") + b.path + ": "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(b.words), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

INSTANTIATE_TEST_SUITE_P(
    Files, BadGltf,
    ::testing::Values(Bad{"no_material.gltf", "meshes[0].primitives[0].material", "--default-material"},
                      Bad{"missing_buffer.gltf", "buffers[0].uri", "missing_buffer.bin"},
                      Bad{"required_extension.gltf", "extensionsRequired[0]", "KHR_draco_mesh_compression"},
                      // Found by the fuzzer (tests/fuzz): each once ended facet with an uncaught
                      // exception, a stack overflow or an unchecked index.
                      Bad{"facet_object_misspelt.gltf", "nodes[0].extensions.FACET_object.onrmal", "did you mean \"normal\""},
                      Bad{"node_cycle.gltf", "nodes[0].children", "cycle"},
                      Bad{"no_such_camera.gltf", "nodes[0].camera", "names no camera"},
                      Bad{"nan_position.gltf", "accessors[0]", "not finite"}),
    [](const auto& info) { return fs::path(info.param.file).stem().string(); });

TEST(Gltf, DefaultMaterialShadesPrimitivesWithoutOne) {
  GltfImportOptions o;
  o.default_material = load_material((kSource / "examples/materials/lambert.json").string());
  std::vector<std::string> notes;
  Scene s = import_gltf((kSource / "tests/gltf/no_material.gltf").string(), o, notes);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.material_of(0, nullptr).name, "lambert");
}

}  // namespace
}  // namespace facet
