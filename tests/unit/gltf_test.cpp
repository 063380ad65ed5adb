// glTF through tinygltf: a round trip loses nothing, the example file is what
// its generator says, and bad files fail clearly without writing.
#include <cmath>
#include <functional>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "catalog/texture.h"
#include "core/image.h"
#include "core/io.h"
#include "reference/interpreter.h"
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

// A material's JSON with each image path replaced by what the image holds: an export
// carries images as copies (or inside a GLB), so the paths differ and the texels must not.
json with_texel_digests(json j) {
  if (j.is_object() && j.contains("texture") && j["texture"].is_string()) {
    const Texels& t = *load_texels(j["texture"].get<std::string>());
    const std::string bytes(reinterpret_cast<const char*>(t.rgba.data()), t.rgba.size() * sizeof(float));
    j["texture"] = fmt::format("{}x{}:{:016x}", t.width, t.height, std::hash<std::string>()(bytes));
    return j;
  }
  if (j.is_structured())
    for (auto& e : j) e = with_texel_digests(std::move(e));
  return j;
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
    EXPECT_EQ(with_texel_digests(to_json(ma)), with_texel_digests(to_json(mb))) << a.name;
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

// A mesh's own tangents go out as TANGENT and come back (float32), the normal-mapped picture
// the same; under a mirroring node the tangent turns with the mesh and w changes sign
// (B = w·(n × t) must still point where the mirrored bitangent points).
TEST(Gltf, TangentsRoundTripAndTurnWithAMirror) {
  Material m = load_material((kSource / "examples/textured/textured_normal_cook_torrance.json").string());
  Scene s = load_scene((kSource / "tests/scenes/textured_mesh_tangents.json").string());
  const std::string file = scratch("tangents.gltf").string();
  check_round_trip(s, &m, file);
  const Mesh& a = *s.objects[0].mesh;
  auto sheet = [&](const Scene& back) {
    for (const auto& o : back.objects)
      if (o.name == s.objects[0].name) return o.mesh;
    return std::shared_ptr<const Mesh>();
  };
  std::vector<std::string> notes;
  const auto b = sheet(import_gltf(file, GltfImportOptions{}, notes));
  ASSERT_TRUE(b);
  ASSERT_EQ(b->tangents.size(), a.tangents.size());
  for (size_t i = 0; i < a.tangents.size(); ++i) {
    for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(b->tangents[i][k], a.tangents[i][k], 2e-7);
    EXPECT_EQ(b->tangents[i][3], a.tangents[i][3]);
  }
  // The same file with the sheet's node mirrored in x.
  json doc = read_json_file(file);
  for (auto& node : doc["nodes"])
    if (node.value("name", "") == s.objects[0].name) node["scale"] = {-1, 1, 1};
  const fs::path mirrored = fs::path(file).parent_path() / "tangents_mirrored.gltf";
  write_file_atomic(mirrored.string(), doc.dump());
  const auto c = sheet(import_gltf(mirrored.string(), GltfImportOptions{}, notes));
  ASSERT_TRUE(c);
  ASSERT_EQ(c->tangents.size(), a.tangents.size());
  for (size_t i = 0; i < a.tangents.size(); ++i) {
    EXPECT_NEAR(c->tangents[i][0], -a.tangents[i][0], 2e-7);
    EXPECT_NEAR(c->tangents[i][1], a.tangents[i][1], 2e-7);
    EXPECT_EQ(c->tangents[i][3], -a.tangents[i][3]);
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

// glTF 2.0 §3.9.2: the material's factors become the catalog's gltf_pbr lobe as they are
// (Appendix B's BRDF; tests/unit/gltf_pbr_test.cpp checks the lobe against the specification).
TEST(Gltf, MetallicRoughnessIsTheGltfBrdfExactly) {
  std::vector<std::string> notes;
  Scene s = import_gltf((kSource / "tests/gltf/one_triangle.gltf").string(), {}, notes);
  const Material& m = s.materials.begin()->second;
  ASSERT_FALSE(m.diffuse);
  ASSERT_TRUE(m.specular);
  EXPECT_TRUE(m.specular->def->gltf_brdf);
  EXPECT_EQ(m.specular->at("base_color").rgb, (RGB{0.8, 0.2, 0.1}));
  EXPECT_EQ(m.specular->at("metallic").number, 0.0);
  EXPECT_EQ(m.specular->at("roughness").number, 0.5);
  EXPECT_EQ(m.specular->at("ior").number, 1.5);
  for (const auto& n : notes) EXPECT_EQ(n.find("approximate"), std::string::npos) << n;
}

// A material of one gltf_pbr lobe `lobe` (its maps read textures/leaf.png), in a folder of its own.
Material leaf_lobe_material(const std::string& folder_name, const std::string& name, const json& lobe,
                            const json& more = json::object()) {
  const fs::path folder = scratch(folder_name);
  fs::remove_all(folder);
  fs::create_directories(folder / "textures");
  fs::copy_file(kSource / "examples/textured/textures/leaf.png", folder / "textures/leaf.png");
  json doc = {{"name", name}, {"specular", lobe}};
  doc.update(more);
  write_file_atomic((folder / "m.json").string(), doc.dump());
  return load_material((folder / "m.json").string());
}

// glTF's own BRDF goes out as glTF says it: the factors, the metallic–roughness map (one
// image's B and G), KHR_materials_ior and KHR_materials_specular (with specularTexture's A),
// KHR_materials_clearcoat with the coat's own normal map (clearcoatNormalTexture, its scale and
// KHR_texture_transform), KHR_materials_anisotropy with its texture (one image's R and G as the
// direction, B the strength).
TEST(Gltf, GltfBrdfExportsAsItsFactorsMapsAndExtensions) {
  const json lobe = {{"model", "gltf_pbr"},
                     {"base_color", {{"texture", "textures/leaf.png"}, {"colorspace", "srgb"}, {"factor", {0.9, 0.8, 0.7}}}},
                     {"metallic", {{"texture", "textures/leaf.png"}, {"channel", "b"}, {"factor", 0.6}}},
                     {"roughness", {{"texture", "textures/leaf.png"}, {"channel", "g"}, {"factor", 0.7}}},
                     {"ior", 1.8},
                     {"specular", {{"texture", "textures/leaf.png"}, {"channel", "a"}, {"factor", 0.9}}},
                     {"specular_color", {{"texture", "textures/leaf.png"}, {"colorspace", "srgb"}, {"factor", {1.0, 0.5, 0.25}}}},
                     {"clearcoat", {{"texture", "textures/leaf.png"}, {"channel", "r"}, {"factor", 0.8}}},
                     {"clearcoat_roughness", 0.3},
                     {"sheen_color", {{"texture", "textures/leaf.png"}, {"colorspace", "srgb"}, {"factor", {0.6, 0.5, 0.4}}}},
                     {"sheen_roughness", {{"texture", "textures/leaf.png"}, {"channel", "a"}, {"factor", 0.45}}},
                     {"anisotropy_strength", {{"texture", "textures/leaf.png"}, {"channel", "b"}, {"factor", 0.5}}},
                     {"anisotropy_direction_x", {{"texture", "textures/leaf.png"}, {"channel", "r"}}},
                     {"anisotropy_direction_y", {{"texture", "textures/leaf.png"}, {"channel", "g"}}},
                     {"anisotropy_rotation", 1.25}};
  const json coat_map = {{"texture", "textures/leaf.png"}, {"transform", {{"rotation", 0.5}}}, {"strength", 0.7}};
  const Material m = leaf_lobe_material("gltf_brdf_export", "painted", lobe, {{"coat_normal_map", coat_map}});
  const std::string out = (scratch("gltf_brdf_export") / "out.gltf").string();
  std::vector<std::string> notes;
  export_gltf(load_scene("single"), &m, out, notes);
  json doc = json::parse(read_file(out));
  json& g = doc["materials"][0];
  const json& pbr = g["pbrMetallicRoughness"];
  EXPECT_EQ(pbr["baseColorFactor"], json::array({0.9, 0.8, 0.7, 1.0}));
  EXPECT_EQ(pbr["metallicFactor"], 0.6);
  EXPECT_EQ(pbr["roughnessFactor"], 0.7);
  EXPECT_TRUE(pbr.contains("baseColorTexture") && pbr.contains("metallicRoughnessTexture")) << pbr.dump();
  EXPECT_EQ(g["extensions"]["KHR_materials_ior"]["ior"], 1.8);
  EXPECT_EQ(g["extensions"]["KHR_materials_specular"]["specularFactor"], 0.9);
  EXPECT_EQ(g["extensions"]["KHR_materials_specular"]["specularColorFactor"], json::array({1.0, 0.5, 0.25}));
  EXPECT_TRUE(g["extensions"]["KHR_materials_specular"].contains("specularTexture"));
  EXPECT_TRUE(g["extensions"]["KHR_materials_specular"].contains("specularColorTexture"));
  EXPECT_TRUE(g["extensions"]["KHR_materials_sheen"].contains("sheenColorTexture"));
  EXPECT_TRUE(g["extensions"]["KHR_materials_sheen"].contains("sheenRoughnessTexture"));
  EXPECT_EQ(g["extensions"]["KHR_materials_clearcoat"]["clearcoatFactor"], 0.8);
  EXPECT_EQ(g["extensions"]["KHR_materials_clearcoat"]["clearcoatRoughnessFactor"], 0.3);
  EXPECT_TRUE(g["extensions"]["KHR_materials_clearcoat"].contains("clearcoatTexture"));
  const json& coat_normal = g["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"];
  EXPECT_EQ(coat_normal["scale"], 0.7) << coat_normal.dump();
  EXPECT_EQ(coat_normal["extensions"]["KHR_texture_transform"]["rotation"], 0.5) << coat_normal.dump();
  EXPECT_EQ(g["extensions"]["KHR_materials_sheen"]["sheenColorFactor"], json::array({0.6, 0.5, 0.4}));
  EXPECT_EQ(g["extensions"]["KHR_materials_sheen"]["sheenRoughnessFactor"], 0.45);
  EXPECT_EQ(g["extensions"]["KHR_materials_anisotropy"]["anisotropyStrength"], 0.5);
  EXPECT_EQ(g["extensions"]["KHR_materials_anisotropy"]["anisotropyRotation"], 1.25);
  EXPECT_TRUE(g["extensions"]["KHR_materials_anisotropy"].contains("anisotropyTexture"));
  for (const char* used : {"KHR_materials_ior", "KHR_materials_specular", "KHR_materials_sheen", "KHR_materials_clearcoat",
                           "KHR_materials_anisotropy"})
    EXPECT_NE(std::find(doc["extensionsUsed"].begin(), doc["extensionsUsed"].end(), used), doc["extensionsUsed"].end())
        << used;
  for (const auto& n : notes) EXPECT_EQ(n.find("approximate"), std::string::npos) << n;
  // FACET_material carries the lobe itself: the round trip through facet is exact, the
  // images copied beside the glTF file (the same texels under another path).
  Scene back = import_gltf(out, {}, notes);
  const ModelSpec& now = *back.materials.begin()->second.specular;
  json a = to_json(m)["specular"], b = to_json(back.materials.begin()->second)["specular"];
  for (const char* p : {"base_color", "metallic", "roughness", "specular", "clearcoat", "anisotropy_strength",
                        "anisotropy_direction_x", "anisotropy_direction_y", "specular_color", "sheen_color",
                        "sheen_roughness"}) {
    EXPECT_EQ(now.at(p).texture->texels->rgba, m.specular->at(p).texture->texels->rgba) << p;
    a[p].erase("texture");
    b[p].erase("texture");
  }
  EXPECT_EQ(b, a);
  // A reader without FACET_material (the file with it taken out) imports the same lobe from
  // the factors, maps and extensions alone.
  g["extensions"].erase("FACET_material");
  const fs::path folder = scratch("gltf_brdf_export");
  write_file_atomic((folder / "plain.gltf").string(), doc.dump());
  GltfImportOptions o;
  o.output = (folder / "back/scene.json").string();
  std::vector<GltfImportFile> files;
  Scene plain = import_gltf((folder / "plain.gltf").string(), o, notes, &files);
  const ModelSpec& read = *plain.materials.begin()->second.specular;
  EXPECT_EQ(read.def, m.specular->def);
  for (const char* p : {"base_color", "metallic", "roughness", "ior", "specular", "specular_color", "clearcoat",
                        "clearcoat_roughness", "anisotropy_strength", "anisotropy_rotation", "anisotropy_direction_x",
                        "anisotropy_direction_y", "sheen_color", "sheen_roughness"}) {
    const Value &x = m.specular->at(p), &y = read.at(p);
    EXPECT_EQ(x.rgb, y.rgb) << p;
    EXPECT_EQ(x.number, y.number) << p;
    ASSERT_EQ(bool(x.texture), bool(y.texture)) << p;
    if (!x.texture) continue;
    EXPECT_EQ(x.texture->channel, y.texture->channel) << p;
    EXPECT_EQ(x.texture->colorspace, y.texture->colorspace) << p;
    EXPECT_EQ(x.texture->bias, y.texture->bias) << p;
    EXPECT_EQ(x.texture->texels->rgba, y.texture->texels->rgba) << p;
  }
  const Material& plain_material = plain.materials.begin()->second;
  ASSERT_TRUE(plain_material.coat_normal_map) << "clearcoatNormalTexture read back";
  EXPECT_EQ(plain_material.coat_normal_map->strength, 0.7);
  EXPECT_EQ(plain_material.coat_normal_map->texture().rotation, 0.5);
  EXPECT_EQ(plain_material.coat_normal_map->texture().texels->rgba, m.coat_normal_map->texture().texels->rgba);
}

// Layers a material file writes over a gltf_pbr lobe are glTF's own parts where they lie where
// glTF's stack puts them (KHR_materials_sheen under KHR_materials_clearcoat): the export writes
// them as those extensions, and a reader without FACET_material gets the same reflectance. A
// layer over classic lobes, or the coat under the sheen, is no glTF: a note says so, and
// FACET_material carries it.
TEST(Gltf, LayersOverGltfPbrExportAsItsExtensions) {
  const json lobe = {{"model", "gltf_pbr"}, {"base_color", {0.4, 0.2, 0.6}}, {"roughness", 0.5}};
  const json layers = {{{"model", "sheen"}, {"color", {0.7, 0.8, 0.5}}, {"roughness", 0.4}},
                       {{"model", "clearcoat"},
                        {"weight", {{"texture", "textures/leaf.png"}, {"channel", "r"}, {"factor", 0.9}}},
                        {"roughness", 0.2}}};
  const Material m = leaf_lobe_material("gltf_layers_export", "layered", lobe, {{"layers", layers}});
  const fs::path folder = scratch("gltf_layers_export");
  const std::string out = (folder / "out.gltf").string();
  std::vector<std::string> notes;
  export_gltf(load_scene("single"), &m, out, notes);
  for (const auto& n : notes) EXPECT_EQ(n.find("approximate"), std::string::npos) << n;
  json doc = json::parse(read_file(out));
  json& ext = doc["materials"][0]["extensions"];
  EXPECT_EQ(ext["KHR_materials_sheen"]["sheenColorFactor"], json::array({0.7, 0.8, 0.5}));
  EXPECT_EQ(ext["KHR_materials_sheen"]["sheenRoughnessFactor"], 0.4);
  EXPECT_EQ(ext["KHR_materials_clearcoat"]["clearcoatFactor"], 0.9);
  EXPECT_TRUE(ext["KHR_materials_clearcoat"].contains("clearcoatTexture"));
  EXPECT_EQ(ext["FACET_material"]["material"]["layers"].size(), 2u) << "FACET_material keeps the file's own form";
  const Scene back = import_gltf(out, {}, notes);  // facet's import reads FACET_material: the layers as written
  ASSERT_EQ(back.materials.begin()->second.layers.size(), 2u);
  EXPECT_EQ(back.materials.begin()->second.layers[1].def->name, "clearcoat");
  ext.erase("FACET_material");
  write_file_atomic((folder / "plain.gltf").string(), doc.dump());
  GltfImportOptions o;
  o.output = (folder / "back/scene.json").string();
  std::vector<GltfImportFile> files;
  const Scene plain = import_gltf((folder / "plain.gltf").string(), o, notes, &files);
  const Reference a(m), b(plain.materials.begin()->second);
  for (double c : {1.0, 0.6, 0.2, 0.01}) {
    const Vec3 n(0, 0, 1), l = normalize(Vec3(0.3, 0.2, c)), v = normalize(Vec3(-0.5, 0.1, c * 0.7));
    ShadingInputs in = shading_inputs(n, l, v, Vec3(1, 0, 0));
    in.textured[0] = {0.55, 0.55, 0.55};  // the coat's weight at some texel, read the same by both
    const RGB x = a.reflectance(in), y = b.reflectance(in);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], y[k], 1e-12 * std::max(1.0, x[k])) << c;
  }
  // The coat under the sheen, and a coat over Lambert: not glTF's BRDF, said.
  for (const json& other : {json{{"layers", {layers[1], layers[0]}}}, json{{"layers", {layers[1]}}}}) {
    Material o2 = leaf_lobe_material("gltf_layers_export", "other", lobe, other);
    if (other["layers"].size() == 1) {
      o2.specular.reset();
      o2.diffuse = default_spec(*find_model("diffuse", "lambert"));
    }
    notes.clear();
    export_gltf(load_scene("single"), &o2, out, notes);
    bool said = false;
    for (const auto& n : notes) said = said || n.find("approximate (FACET_material carries the material)") != std::string::npos;
    EXPECT_TRUE(said) << other.dump();
    if (other["layers"].size() == 2) {
      bool why = false;
      for (const auto& n : notes) why = why || n.find("layers[1] (sheen), which lies above a part") != std::string::npos;
      EXPECT_TRUE(why) << "the coat under the sheen is named";
    }
  }
}

// What glTF cannot say (here a metallic map without its roughness half) is decided before
// anything is written: the fallback then has no map of the lobe and the file no texture nobody
// reads (the first export wrote the base colour's map, then gave up, leaving it behind).
TEST(Gltf, WhatGltfCannotSayOfTheLobeLeavesNothingBehind) {
  const json lobe = {{"model", "gltf_pbr"},
                     {"base_color", {{"texture", "textures/leaf.png"}, {"colorspace", "srgb"}}},
                     {"metallic", {{"texture", "textures/leaf.png"}, {"channel", "b"}}}};
  const Material m = leaf_lobe_material("gltf_brdf_unsaid", "half", lobe);
  const std::string out = (scratch("gltf_brdf_unsaid") / "out.gltf").string();
  std::vector<std::string> notes;
  export_gltf(load_scene("single"), &m, out, notes);
  const json doc = json::parse(read_file(out));
  const json& pbr = doc["materials"][0]["pbrMetallicRoughness"];
  EXPECT_FALSE(pbr.contains("baseColorTexture") || pbr.contains("metallicRoughnessTexture")) << pbr.dump();
  EXPECT_FALSE(doc.contains("textures")) << doc.value("textures", json()).dump();
  bool said = false;
  for (const auto& n : notes) said |= n.find("not one image's B and G") != std::string::npos;
  EXPECT_TRUE(said);
}

// KHR_materials_anisotropy has no direction but its texture's: a direction of numbers goes out
// as the rotation it adds (atan2(y, x)), and a direction from an image without the strength from
// the same image's B (which glTF multiplies) is what glTF cannot say: a note, the fallback.
TEST(Gltf, AnisotropyDirectionsGoOutAsGltfSaysThem) {
  // The direction (0, −0.5), stored as (d + 1)/2.
  const json turned = {{"model", "gltf_pbr"},          {"metallic", 1},
                       {"anisotropy_strength", 0.6},    {"anisotropy_rotation", 0.25},
                       {"anisotropy_direction_x", 0.5}, {"anisotropy_direction_y", 0.25}};
  const Material m = leaf_lobe_material("gltf_anisotropy_turned", "turned", turned);
  const std::string out = (scratch("gltf_anisotropy_turned") / "out.gltf").string();
  std::vector<std::string> notes;
  export_gltf(load_scene("single"), &m, out, notes);
  const json doc = json::parse(read_file(out));
  const json& ext = doc["materials"][0]["extensions"]["KHR_materials_anisotropy"];
  EXPECT_NEAR(ext["anisotropyRotation"].get<double>(), 0.25 - M_PI / 2, 1e-15) << ext.dump();
  EXPECT_FALSE(ext.contains("anisotropyTexture"));
  json half = turned;
  half["anisotropy_direction_x"] = {{"texture", "textures/leaf.png"}, {"channel", "r"}};
  const Material h = leaf_lobe_material("gltf_anisotropy_half", "half", half);
  notes.clear();
  export_gltf(load_scene("single"), &h, (scratch("gltf_anisotropy_half") / "out.gltf").string(), notes);
  bool said = false;
  for (const auto& n : notes) said |= n.find("anisotropy maps that are not one image's") != std::string::npos;
  EXPECT_TRUE(said);
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
    ::testing::Values(Bad{"missing_buffer.gltf", "buffers[0].uri", "missing_buffer.bin"},
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

// glTF 2.0 §3.9.1: a primitive without a material renders with every property at its default:
// base colour 1, metallic 1, roughness 1 (a white metal).
TEST(Gltf, PrimitiveWithoutMaterialTakesGltfsDefault) {
  std::vector<std::string> notes;
  Scene s = import_gltf((kSource / "tests/gltf/no_material.gltf").string(), {}, notes);
  ASSERT_EQ(s.objects.size(), 1u);
  const Material& m = s.material_of(0, nullptr);
  EXPECT_FALSE(m.diffuse);
  ASSERT_TRUE(m.specular && m.specular->def->gltf_brdf);
  EXPECT_EQ(m.specular->at("base_color").rgb, (RGB{1, 1, 1}));
  EXPECT_EQ(m.specular->at("metallic").number, 1.0);
  EXPECT_EQ(m.specular->at("roughness").number, 1.0);
  bool noted = false;
  for (const auto& n : notes) noted |= n.find("glTF's default material") != std::string::npos;
  EXPECT_TRUE(noted);
}

// ---------------------------------------------------------------- textures


// A 4×2 RGB PNG of distinct texels, 8 bits.
std::string small_png() {
  std::vector<uint8_t> rgb;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) rgb.insert(rgb.end(), {uint8_t(40 + 50 * i), uint8_t(30 + 100 * j), uint8_t(200 - 40 * i)});
  return encode_png(4, 2, rgb, "small.png");
}

// One triangle with TEXCOORD_0, material 0 with a base colour map (texture 0 → image 0)
// and, given `mr`, a metallic–roughness map (texture 1 → image 1); the images as `images`.
json textured_triangle(const json& images, bool mr = false) {
  const float data[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};  // positions, then u v
  std::string bytes(reinterpret_cast<const char*>(data), sizeof data);
  json g = json::parse(read_file((kSource / "tests/gltf/one_triangle.gltf").string()));
  g["buffers"][0] = {{"byteLength", 60}, {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}};
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}});
  g["accessors"].push_back({{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
  g["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 1;
  g["samplers"] = {{{"magFilter", 9728}, {"minFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33648}}};
  g["textures"] = {{{"source", 0}, {"sampler", 0}}};
  g["images"] = images;
  auto& pbr = g["materials"][0]["pbrMetallicRoughness"];
  pbr["baseColorTexture"] = {{"index", 0}};
  if (mr) {
    g["textures"].push_back({{"source", 1}});
    pbr["metallicRoughnessTexture"] = {{"index", 1}};
    pbr["metallicFactor"] = 1.0;
    pbr["roughnessFactor"] = 0.8;
  }
  return g;
}

json data_uri_image(const std::string& png) { return {{"uri", "data:image/png;base64," + test::base64(png)}}; }

fs::path write_gltf(const std::string& name, const json& g) {
  fs::path p = scratch(name);
  write_file_atomic(p.string(), g.dump(1));
  return p;
}

TEST(GltfTextures, BaseColourMapIsTheBaseColourTimesItsFactor) {
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  g["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 0.25;
  g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"offset", {0.5, 0}}, {"scale", {2, 1}}, {"rotation", 0.25}}}};
  fs::path in = write_gltf("base_colour.gltf", g);
  GltfImportOptions o;
  o.output = scratch("base_colour_out/scene.json").string();
  std::vector<std::string> notes;
  std::vector<GltfImportFile> files;
  Scene s = import_gltf(in.string(), o, notes, &files);
  const Material& m = s.materials.begin()->second;
  ASSERT_TRUE(m.specular && m.specular->def->gltf_brdf);
  // glTF 2.0 §3.9.2 "Metallic-Roughness Material": baseColorTexture (sRGB) times
  // baseColorFactor; the lobe mixes by metallic itself, so the map is the base colour, not
  // k_d = base·(1 − metallic).
  const Value& base = m.specular->at("base_color");
  ASSERT_TRUE(base.texture);
  EXPECT_EQ(base.texture->colorspace, "srgb");
  EXPECT_EQ(base.rgb, (RGB{0.8, 0.2, 0.1}));
  EXPECT_EQ(base.texture->sampler.filter, TextureFilter::Nearest);
  EXPECT_EQ(base.texture->sampler.wrap[0], TextureWrap::Clamp);
  EXPECT_EQ(base.texture->sampler.wrap[1], TextureWrap::Mirror);
  EXPECT_EQ(base.texture->offset, (std::array<double, 2>{0.5, 0}));
  EXPECT_EQ(base.texture->scale, (std::array<double, 2>{2, 1}));
  EXPECT_EQ(base.texture->rotation, 0.25);
  EXPECT_EQ(base.texture->bias, (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(m.specular->at("metallic").number, 0.25);
  const Texels& src = *base.texture->texels;
  for (double u : {0.1, 0.37, 0.8})
    for (double v : {0.2, 0.55, 0.9}) {
      const auto st = base.texture->transform(u, v);
      const auto texel = sample(src, base.texture->sampler, st[0], st[1]);
      const auto value = texture_value(base, Range::closed(0, 1), u, v);
      for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(value[c], (RGB{0.8, 0.2, 0.1})[c] * texel[c], 1e-15) << u << "," << v;
    }
  // Nothing is written until the caller writes the files; then the scene reads them back.
  ASSERT_EQ(files.size(), 1u);  // the image the glTF held, and no bake
  for (const auto& f : files) EXPECT_FALSE(fs::exists(f.path)) << f.path;
  EXPECT_EQ(fs::path(files[0].path).parent_path().filename(), "scene.textures");
  files.push_back({o.output, to_json(s, o.output).dump()});
  write_import_files(files);
  json written = json::parse(read_file(o.output));
  const json color = written["materials"].begin().value()["specular"]["base_color"];
  EXPECT_EQ(color["texture"], "scene.textures/image0.png") << color.dump();
  Scene back = load_scene(o.output);
  EXPECT_EQ(back.materials.begin()->second.specular->at("base_color").texture->texels->rgba, src.rgba);
}

// glTF allows any TEXCOORD_n: a base colour map reading TEXCOORD_3 (through
// KHR_texture_transform's texCoord, which overrides the textureInfo's) and a normal map
// reading TEXCOORD_2 take facet's sets 0 and 1, the mesh carries TEXCOORD_2 and _3 as them,
// and the scene file says so, so reading it back gives the same coordinates.
TEST(GltfTextures, AnyTexcoordSetIsMappedOntoTheMeshsTwo) {
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  // TEXCOORD_2 and _3 as TEXCOORD_0's values, turned: (u, v) → (v, u) and (1 − u, v).
  const float uv2[] = {0, 0, 0, 1, 1, 0}, uv3[] = {1, 0, 0, 0, 1, 1};
  std::string bin = test::base64_decode(g["buffers"][0]["uri"].get<std::string>());
  const size_t at = bin.size();
  bin += std::string(reinterpret_cast<const char*>(uv2), sizeof uv2) + std::string(reinterpret_cast<const char*>(uv3), sizeof uv3);
  g["buffers"][0] = {{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + test::base64(bin)}};
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 24}});
  g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 24}, {"byteLength", 24}});
  g["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
  g["accessors"].push_back({{"bufferView", 3}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
  g["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_2"] = 2;
  g["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_3"] = 3;
  auto& base = g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"];
  base["texCoord"] = 1;
  base["extensions"] = {{"KHR_texture_transform", {{"texCoord", 3}, {"scale", {2, 2}}}}};
  g["materials"][0]["normalTexture"] = {{"index", 0}, {"texCoord", 2}};
  g["extensionsUsed"] = {"KHR_texture_transform"};
  g["extensionsRequired"] = {"KHR_texture_transform"};  // facet implements it: a file may require it
  GltfImportOptions o;
  o.output = scratch("texcoords_out/scene.json").string();
  std::vector<std::string> notes;
  std::vector<GltfImportFile> files;
  Scene s = import_gltf(write_gltf("texcoords.gltf", g).string(), o, notes, &files);
  const Material& m = s.materials.begin()->second;
  EXPECT_EQ(m.specular->at("base_color").texture->uv, 1);  // TEXCOORD_3 is the mesh's set 1
  EXPECT_EQ(m.specular->at("base_color").texture->scale, (std::array<double, 2>{2, 2}));
  EXPECT_EQ(m.normal_map->texture().uv, 0);  // TEXCOORD_2 its set 0
  ASSERT_EQ(s.objects.size(), 1u);
  const Mesh& mesh = *s.objects[0].mesh;
  for (size_t v = 0; v < 3; ++v) {
    EXPECT_EQ(mesh.texcoords[0][v][0], uv2[2 * v]);
    EXPECT_EQ(mesh.texcoords[1][v][1], uv3[2 * v + 1]);
  }
  files.push_back({o.output, to_json(s, o.output).dump()});
  write_import_files(files);
  const json object = json::parse(read_file(o.output))["objects"][0];
  EXPECT_EQ(object["texcoord0"], 2) << object.dump();
  EXPECT_EQ(object["texcoord1"], 3) << object.dump();
  Scene back = load_scene(o.output);
  EXPECT_EQ(back.objects[0].mesh->texcoords, mesh.texcoords);
}

// glTF 2.0 §3.9.4: alphaMode MASK cuts the surface out where the base colour's alpha
// (baseColorFactor's times the texture's A, linear) is below alphaCutoff; BLEND is drawn
// opaque, with a note; OPAQUE is opaque.
TEST(GltfTextures, AlphaModeMaskIsACutOut) {
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1, 0.8};
  g["materials"][0]["alphaMode"] = "MASK";
  g["materials"][0]["alphaCutoff"] = 0.3;
  std::vector<std::string> notes;
  const fs::path file = write_gltf("mask.gltf", g);
  Scene s = import_gltf(file.string(), {}, notes);
  const Material& m = s.materials.begin()->second;
  ASSERT_TRUE(m.masked());
  EXPECT_EQ(*m.alpha_cutoff, 0.3);
  ASSERT_TRUE(m.alpha.texture);
  EXPECT_EQ(m.alpha.texture->channel, "a");
  EXPECT_EQ(m.alpha.texture->colorspace, "linear");
  EXPECT_EQ(m.alpha.number, 0.8);
  // Without a base colour texture, the factor's alpha alone.
  g["materials"][0]["pbrMetallicRoughness"].erase("baseColorTexture");
  Scene t = import_gltf(write_gltf("mask_factor.gltf", g).string(), {}, notes);
  EXPECT_FALSE(t.materials.begin()->second.alpha.texture);
  EXPECT_EQ(t.materials.begin()->second.alpha.number, 0.8);
  // The material round-trips through facet's own JSON (read as a file beside the scene would be).
  EXPECT_EQ(to_json(parse_material(to_json(m), (file.parent_path() / "round_trip.json").string())), to_json(m));
  g["materials"][0]["alphaMode"] = "BLEND";
  notes.clear();
  Scene b = import_gltf(write_gltf("blend.gltf", g).string(), {}, notes);
  EXPECT_FALSE(b.materials.begin()->second.masked());
  bool noted = false;
  for (const auto& n : notes) noted |= n.find("alphaMode BLEND is drawn opaque") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(GltfTextures, ExternalImageIsReferencedWhereItIsOrCopied) {
  // "my image.png" beside the glTF, its URI percent-encoded. A scene written in that folder
  // names it where it is; one written a folder down gets a copy beside it, bytes unchanged,
  // since a scene names images inside its own folder only (issue 28, catalog/texture.cpp).
  const fs::path folder = scratch("external");
  fs::remove_all(folder);
  fs::create_directories(folder / "out");
  write_file_atomic((folder / "my image.png").string(), small_png());
  json g = textured_triangle(json::array({{{"uri", "my%20image.png"}, {"name", "mine"}}}));
  write_file_atomic((folder / "ext.gltf").string(), g.dump());
  std::vector<std::string> notes;
  std::vector<GltfImportFile> files;
  GltfImportOptions o;
  o.output = (folder / "scene.json").string();
  Scene s = import_gltf((folder / "ext.gltf").string(), o, notes, &files);
  EXPECT_TRUE(files.empty()) << "an external image inside the scene's folder is not copied";
  EXPECT_EQ(to_json(s, o.output)["materials"]["m"]["specular"]["base_color"]["texture"], "my image.png");

  o.output = (folder / "out/scene.json").string();
  s = import_gltf((folder / "ext.gltf").string(), o, notes, &files);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].bytes, small_png());
  EXPECT_EQ(to_json(s, o.output)["materials"]["m"]["specular"]["base_color"]["texture"], "scene.textures/image0_mine.png");
}

TEST(GltfTextures, ImportFromMemoryReadsNoExternalImage) {
  // What the fuzzer relies on: bytes from anywhere touch no file, even one that is there.
  const fs::path folder = scratch("memory");
  fs::create_directories(folder);
  write_file_atomic((folder / "there.png").string(), small_png());
  const std::string data = textured_triangle(json::array({{{"uri", (folder / "there.png").string()}}})).dump();
  std::vector<std::string> notes;
  try {
    (void)import_gltf_data(data, false, "memory.gltf", "", {}, notes);
    ADD_FAILURE() << "an external image was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("an import from memory reads none"), std::string::npos) << e.what();
  }
  Scene s = import_gltf_data(data, false, "memory.gltf", folder.string(), {}, notes);  // with a folder it is read
  EXPECT_TRUE(s.materials.begin()->second.specular->at("base_color").texture);
}

// glTF 2.0 §3.9.2 "Metallic-Roughness Material": metallicRoughnessTexture's B is metallic and
// G roughness, linear, each times its factor: the lobe reads the one image twice, channel by channel, and nothing is
// baked (α = roughness² is the lobe's own, computed where it shades).
TEST(GltfTextures, MetallicRoughnessMapIsReadChannelByChannel) {
  std::vector<uint8_t> rgb;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) rgb.insert(rgb.end(), {255, uint8_t(60 * i + 20), uint8_t(j ? 255 : 0)});
  const std::string mr = encode_png(4, 2, rgb, "mr.png");
  fs::path in = write_gltf("mr.gltf", textured_triangle(json::array({data_uri_image(small_png()), data_uri_image(mr)}), true));
  std::vector<std::string> notes;
  std::vector<GltfImportFile> files;
  GltfImportOptions o;
  o.output = scratch("mr_out/scene.json").string();
  Scene s = import_gltf(in.string(), o, notes, &files);
  const Material& m = s.materials.begin()->second;
  const Value& metal = m.specular->at("metallic");
  const Value& rough = m.specular->at("roughness");
  ASSERT_TRUE(metal.texture && rough.texture);
  EXPECT_EQ(metal.texture->channel, "b");
  EXPECT_EQ(rough.texture->channel, "g");
  EXPECT_EQ(metal.texture->colorspace, "linear");
  EXPECT_EQ(rough.texture->colorspace, "linear");
  EXPECT_EQ(metal.number, 1.0);   // metallicFactor
  EXPECT_EQ(rough.number, 0.8);   // roughnessFactor
  EXPECT_EQ(metal.texture->texels, rough.texture->texels) << "one image";
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      // At texel centres the texel itself, to float32's rounding of the stored texel.
      const double u = (i + 0.5) / 4, v = (j + 0.5) / 2;
      EXPECT_NEAR(texture_value(rough, Range::closed(0, 1), u, v)[0], 0.8 * (60 * i + 20) / 255.0, 1e-7) << i << j;
      EXPECT_NEAR(texture_value(metal, Range::closed(0, 1), u, v)[0], j ? 1.0 : 0.0, 1e-7) << i << j;
    }
  EXPECT_EQ(files.size(), 2u) << "the two images the glTF held, nothing baked";
  for (const auto& n : notes) EXPECT_EQ(n.find("baked"), std::string::npos) << n;
}

// Each baked image is a file of its own (issue 28): named from the whole material name (a
// long one was cut at 40 characters, so baked images shared one file), numbered where two
// names make one identifier ("…-b" and "… b"). The one bake left is the ambient term.
TEST(GltfTextures, BakedImagesNeverShareAFile) {
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  g["materials"][0]["occlusionTexture"] = {{"index", 0}, {"strength", 0.5}};
  const std::string stem(50, 'm');
  g["materials"][0]["name"] = stem + "-b";
  json second = g["materials"][0];
  second["name"] = stem + " b";
  g["materials"].push_back(second);
  json mesh = g["meshes"][0];
  mesh["primitives"][0]["material"] = 1;
  g["meshes"].push_back(mesh);
  g["nodes"].push_back({{"mesh", 1}});
  g["scenes"][0]["nodes"].push_back(int(g["nodes"].size()) - 1);
  std::vector<std::string> notes;
  Scene s = import_gltf(write_gltf("baked_names.gltf", g).string(), {}, notes);
  ASSERT_EQ(s.materials.size(), 2u);
  std::set<std::string> files;
  for (const auto& [key, m] : s.materials) {
    ASSERT_TRUE(m.ambient_texture) << key;
    files.insert(m.ambient_texture->path);
  }
  EXPECT_EQ(files.size(), 2u) << "two materials, a baked ambient term each";
}

// normalTexture becomes the normal map (scale its strength, +Y up), emissiveTexture the
// emission map (sRGB, × emissiveFactor × KHR_materials_emissive_strength), occlusionTexture
// the ambient term: the diffuse albedo base·(1 − metallic) times lerp(1, R, strength), a
// factor of the map where it can be, else baked texel by texel on the base colour map's grid.
TEST(GltfTextures, NormalEmissiveAndOcclusionMapsAreImported) {
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  json& gm = g["materials"][0];
  gm["pbrMetallicRoughness"]["metallicFactor"] = 0.5;
  gm["normalTexture"] = {{"index", 0}, {"scale", 0.7}};
  gm["emissiveTexture"] = {{"index", 0}};
  gm["emissiveFactor"] = {1.0, 0.5, 0.25};
  gm["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}};
  gm["occlusionTexture"] = {{"index", 0}, {"strength", 0.5}};
  g["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  std::vector<std::string> notes;
  Scene s = import_gltf(write_gltf("other_maps.gltf", g).string(), {}, notes);
  const Material& m = s.materials.begin()->second;
  ASSERT_TRUE(m.normal_map);
  EXPECT_EQ(m.normal_map->strength, 0.7);
  EXPECT_FALSE(m.normal_map->green_down);
  ASSERT_TRUE(m.emission_texture);
  EXPECT_EQ(m.emission_texture->colorspace, "srgb");
  EXPECT_EQ(m.emission, (RGB{4.0, 2.0, 1.0}));
  ASSERT_TRUE(m.ambient_texture);  // base map × (1 − metallic) × lerp(1, R, 0.5): baked
  const Texels& src = *m.specular->at("base_color").texture->texels;
  const Texels& a = *m.ambient_texture->texels;
  ASSERT_EQ(a.width, src.width);
  const RGB base = {0.8, 0.2, 0.1};  // tests/gltf/one_triangle.gltf's baseColorFactor
  for (int j = 0; j < src.height; ++j)
    for (int i = 0; i < src.width; ++i)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(a.at(i, j)[c],
                    base[size_t(c)] * srgb_to_linear(src.at(i, j)[c]) * 0.5 * (1 + 0.5 * (src.at(i, j)[0] - 1)),
                    0.6 / 65535)
            << i << "," << j << "," << c;
  // Without a base colour map and with strength 1, the occlusion map itself, the albedo its factor.
  gm["pbrMetallicRoughness"].erase("baseColorTexture");
  gm["occlusionTexture"]["strength"] = 1.0;
  Scene plain = import_gltf(write_gltf("occlusion_factor.gltf", g).string(), {}, notes);
  const Material& q = plain.materials.begin()->second;
  ASSERT_TRUE(q.ambient_texture);
  EXPECT_EQ(q.ambient_texture->channel, "r");
  EXPECT_EQ(q.ambient, (RGB{0.8 * 0.5, 0.2 * 0.5, 0.1 * 0.5}));
}

// KHR_materials_clearcoat ("Clearcoat"): clearcoat = clearcoatFactor × clearcoatTexture's R and
// clearcoat_roughness = clearcoatRoughnessFactor × clearcoatRoughnessTexture's G, linear; what the
// the coat's own normal map (clearcoatNormalTexture) is the material's coat_normal_map, its scale the
// map's strength, left out with a note where it reads other coordinates than the normalTexture
// or the coat is disabled; the emission's dimming under a textured coat is exact, so no note names it.
TEST(GltfTextures, ClearcoatIsReadWithItsMapsAndItsLimitsSaid) {
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  json& gm = g["materials"][0];
  gm["extensions"] = {{"KHR_materials_clearcoat",
                       {{"clearcoatFactor", 0.75},
                        {"clearcoatTexture", {{"index", 0}}},
                        {"clearcoatRoughnessFactor", 0.25},
                        {"clearcoatRoughnessTexture", {{"index", 0}, {"texCoord", 0}}}}}};
  g["extensionsUsed"] = {"KHR_materials_clearcoat"};
  std::vector<std::string> notes;
  Scene s = import_gltf(write_gltf("clearcoat.gltf", g).string(), {}, notes);
  const ModelSpec& lobe = *s.materials.begin()->second.specular;
  const Value &coat = lobe.at("clearcoat"), &rough = lobe.at("clearcoat_roughness");
  ASSERT_TRUE(coat.texture && rough.texture);
  EXPECT_EQ(coat.texture->channel, "r");
  EXPECT_EQ(coat.texture->colorspace, "linear");
  EXPECT_EQ(coat.number, 0.75);
  EXPECT_EQ(rough.texture->channel, "g");
  EXPECT_EQ(rough.number, 0.25);
  for (const auto& n : notes) EXPECT_EQ(n.find("approximate"), std::string::npos) << n;
  EXPECT_EQ(s.materials.begin()->second.specular->def->name, "gltf_pbr");
  // A coat normal map over a normal-mapped base, with an emission: read, nothing approximate.
  gm["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"] = {{"index", 0}, {"scale", 0.4}};
  gm["normalTexture"] = {{"index", 0}};
  gm["emissiveFactor"] = {0.5, 0.5, 0.5};
  notes.clear();
  Scene both = import_gltf(write_gltf("clearcoat_normal.gltf", g).string(), {}, notes);
  const Material& mb = both.materials.begin()->second;
  ASSERT_TRUE(mb.normal_map && mb.coat_normal_map);
  EXPECT_EQ(mb.coat_normal_map->strength, 0.4);
  EXPECT_FALSE(mb.coat_normal_map->green_down);
  for (const auto& n : notes) EXPECT_EQ(n.find("approximate"), std::string::npos) << n;
  // On other coordinates than the base's map: not read, said; the coat on the surface's own normal.
  gm["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"]["texCoord"] = 1;
  g["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 1;
  notes.clear();
  Scene apart = import_gltf(write_gltf("clearcoat_normal_apart.gltf", g).string(), {}, notes);
  EXPECT_FALSE(apart.materials.begin()->second.coat_normal_map);
  int coat_normal = 0, emission = 0;
  for (const auto& n : notes) {
    coat_normal += n.find("clearcoatNormalTexture: approximate: not read") != std::string::npos;
    emission += n.find("emission") != std::string::npos;
  }
  EXPECT_EQ(coat_normal, 1);
  EXPECT_EQ(emission, 0) << "the emission under the coat is exact: no note";
  // A disabled coat (clearcoatFactor 0): its normal map is not read, said.
  gm["extensions"]["KHR_materials_clearcoat"] = {{"clearcoatFactor", 0}, {"clearcoatNormalTexture", {{"index", 0}}}};
  notes.clear();
  Scene off = import_gltf(write_gltf("clearcoat_normal_off.gltf", g).string(), {}, notes);
  EXPECT_FALSE(off.materials.begin()->second.coat_normal_map);
  EXPECT_EQ(std::count_if(notes.begin(), notes.end(),
                          [](const std::string& n) { return n.find("the clear coat is disabled") != std::string::npos; }),
            1);
}

// KHR_materials_sheen ("Sheen"): sheen_color = sheenColorFactor × sheenColorTexture's rgb (sRGB),
// sheen_roughness = sheenRoughnessFactor × sheenRoughnessTexture's alpha ("sheenRoughness =
// sheenRoughnessFactor * sample(sheenRoughnessTexture).a"), no note left for either; the extension
// may be required (facet reads it as its README says); a colour out of [0, 1] is refused naming
// its key. KHR_materials_specular's specularColorTexture is read the same way (factor × rgb, sRGB).
TEST(GltfTextures, SheenIsReadWithItsTextures) {
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  json& gm = g["materials"][0];
  gm["extensions"] = {{"KHR_materials_sheen", {{"sheenColorFactor", {0.9, 0.5, 0.3}}, {"sheenRoughnessFactor", 0.4}}}};
  g["extensionsUsed"] = {"KHR_materials_sheen"};
  g["extensionsRequired"] = {"KHR_materials_sheen"};
  std::vector<std::string> notes;
  Scene s = import_gltf(write_gltf("sheen.gltf", g).string(), {}, notes);
  const ModelSpec& lobe = *s.materials.begin()->second.specular;
  EXPECT_EQ(lobe.at("sheen_color").rgb, (RGB{0.9, 0.5, 0.3}));
  EXPECT_EQ(lobe.at("sheen_roughness").number, 0.4);
  for (const auto& n : notes) EXPECT_EQ(n.find("KHR_materials_sheen"), std::string::npos) << n;
  gm["extensions"]["KHR_materials_sheen"]["sheenColorTexture"] = {{"index", 0}};
  gm["extensions"]["KHR_materials_sheen"]["sheenRoughnessTexture"] = {{"index", 0}};
  gm["extensions"]["KHR_materials_specular"] = {{"specularColorFactor", {1.5, 1.0, 0.5}},
                                                {"specularColorTexture", {{"index", 0}}}};
  g["extensionsUsed"].push_back("KHR_materials_specular");
  notes.clear();
  Scene t = import_gltf(write_gltf("sheen_textures.gltf", g).string(), {}, notes);
  const ModelSpec& textured = *t.materials.begin()->second.specular;
  for (const auto& [param, factor] : {std::pair<const char*, RGB>{"sheen_color", {0.9, 0.5, 0.3}},
                                      {"specular_color", {1.5, 1.0, 0.5}}}) {
    const Value& v = textured.at(param);
    ASSERT_TRUE(v.texture) << param;
    EXPECT_EQ(v.texture->channel, "rgb") << param;
    EXPECT_EQ(v.texture->colorspace, "srgb") << param;
    EXPECT_EQ(v.rgb, factor) << param;
  }
  const Value& roughness = textured.at("sheen_roughness");
  ASSERT_TRUE(roughness.texture);
  EXPECT_EQ(roughness.texture->channel, "a");
  EXPECT_EQ(roughness.texture->colorspace, "linear");
  EXPECT_EQ(roughness.number, 0.4);
  for (const auto& n : notes) EXPECT_EQ(n.find("Texture"), std::string::npos) << "every texture is read: " << n;
  gm["extensions"]["KHR_materials_sheen"]["sheenColorFactor"] = {0.9, 1.5, 0.3};
  try {
    import_gltf(write_gltf("sheen_bad.gltf", g).string(), {}, notes);
    ADD_FAILURE() << "a sheen colour of 1.5 was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("KHR_materials_sheen.sheenColorFactor[1]"), std::string::npos) << e.what();
  }
}

// KHR_materials_anisotropy ("Anisotropy"): anisotropy_strength and anisotropy_rotation are the
// factors; anisotropyTexture's B times the strength, its R and G the direction (which the lobe
// maps red [0, 1] to X [−1, 1]), linear, on the texture's coordinates; the direction turns from the mesh's
// tangent frame (TEXCOORD_0's without a normal or anisotropy texture), so nothing is approximate
// and no note is left; the extension may be required. A mesh without the frame's coordinates is
// refused naming the extension, as the README's "MUST have a defined tangent space" asks.
TEST(GltfTextures, AnisotropyIsReadOnTheMeshFrameWithItsTexture) {
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  json& gm = g["materials"][0];
  gm["extensions"] = {{"KHR_materials_anisotropy", {{"anisotropyStrength", 0.6}}}};
  g["extensionsUsed"] = {"KHR_materials_anisotropy"};
  g["extensionsRequired"] = {"KHR_materials_anisotropy"};
  auto anisotropy_notes = [](const std::vector<std::string>& notes) {
    std::string found;
    for (const auto& n : notes)
      if (n.find("KHR_materials_anisotropy") != std::string::npos) found += n + "\n";
    return found;
  };
  std::vector<std::string> notes;
  Scene s = import_gltf(write_gltf("anisotropy.gltf", g).string(), {}, notes);
  const Material& m = s.materials.begin()->second;
  EXPECT_EQ(m.specular->at("anisotropy_strength").number, 0.6);
  EXPECT_EQ(m.specular->at("anisotropy_rotation").number, 0.0);
  EXPECT_TRUE(m.lobes_uv_tangent());
  EXPECT_EQ(m.frame_uv(), std::optional<int>(0));
  EXPECT_EQ(anisotropy_notes(notes), "");
  gm["extensions"]["KHR_materials_anisotropy"]["anisotropyRotation"] = 1.0;
  gm["extensions"]["KHR_materials_anisotropy"]["anisotropyTexture"] = {{"index", 0}};
  notes.clear();
  Scene t = import_gltf(write_gltf("anisotropy_texture.gltf", g).string(), {}, notes);
  const ModelSpec& lobe = *t.materials.begin()->second.specular;
  EXPECT_EQ(lobe.at("anisotropy_rotation").number, 1.0);
  const Value &strength = lobe.at("anisotropy_strength"), &x = lobe.at("anisotropy_direction_x"),
              &y = lobe.at("anisotropy_direction_y");
  ASSERT_TRUE(strength.texture && x.texture && y.texture);
  EXPECT_EQ(strength.texture->channel, "b");
  EXPECT_EQ(strength.number, 0.6);
  EXPECT_EQ(strength.texture->bias, (RGB{0, 0, 0}));
  for (const auto& [v, c] : {std::pair<const Value*, const char*>{&x, "r"}, {&y, "g"}}) {
    EXPECT_EQ(v->texture->channel, c);
    EXPECT_EQ(v->texture->colorspace, "linear");
    EXPECT_EQ(v->number, 1.0);
    EXPECT_EQ(v->texture->bias, (RGB{0, 0, 0}));
  }
  EXPECT_EQ(anisotropy_notes(notes), "");
  // Without TEXCOORD_0 (and without the textures, which read it) the mesh has no tangent frame.
  gm["extensions"]["KHR_materials_anisotropy"].erase("anisotropyTexture");
  gm["pbrMetallicRoughness"].erase("baseColorTexture");
  g["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
  try {
    import_gltf(write_gltf("anisotropy_no_frame.gltf", g).string(), {}, notes);
    ADD_FAILURE() << "a mesh without a tangent frame was read for an anisotropic material";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("KHR_materials_anisotropy"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("TEXCOORD_0"), std::string::npos) << e.what();
  }
}

TEST(GltfTextures, UnlitFileGetsAHeadlight) {
  std::vector<std::string> notes;
  Scene s = import_gltf((kSource / "tests/gltf/one_triangle.gltf").string(), {}, notes);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Point);
  expect_near(s.lights[0].position, s.camera.position, 0, "the light is at the camera");
  EXPECT_EQ(s.lights[0].color, (RGB{1, 1, 1}));
  EXPECT_EQ(s.lights[0].attenuation.law, Attenuation::Law::None);
  bool told = false;
  for (const auto& n : notes) told |= n.find("headlight") != std::string::npos;
  EXPECT_TRUE(told);
}

TEST(GltfTextures, ExportCarriesTheBaseColourMapOut) {
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"offset", {0.25, 0}}, {"scale", {1, 3}}, {"rotation", 0.5}}}};
  GltfImportOptions o;
  o.output = scratch("export_src/scene.json").string();
  std::vector<std::string> notes;
  std::vector<GltfImportFile> files;
  Scene s = import_gltf(write_gltf("export_src.gltf", g).string(), o, notes, &files);
  files.push_back({o.output, to_json(s, o.output).dump()});
  write_import_files(files);
  for (const char* ext : {".gltf", ".glb"}) {
    const fs::path out = scratch(std::string("export_out/textured") + ext);
    fs::remove_all(out.parent_path());
    fs::create_directories(out.parent_path());
    export_gltf(load_scene(o.output), nullptr, out.string(), notes);
    Scene back = import_gltf(out.string(), {}, notes);
    const Value& a = s.materials.begin()->second.specular->at("base_color");
    const Value& b = back.materials.begin()->second.specular->at("base_color");
    ASSERT_TRUE(b.texture) << ext;
    EXPECT_EQ(b.texture->texels->rgba, a.texture->texels->rgba) << ext;
    EXPECT_EQ(b.rgb, a.rgb);
    EXPECT_EQ(b.texture->rotation, 0.5);
    EXPECT_EQ(b.texture->sampler.wrap, a.texture->sampler.wrap);
    if (std::string(ext) == ".gltf") {
      json doc = json::parse(read_file(out.string()));
      const json& info = doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"];
      EXPECT_EQ(info["extensions"]["KHR_texture_transform"]["scale"], json::array({1.0, 3.0})) << info.dump();
      EXPECT_EQ(doc["images"][0]["uri"], "textured.textures/image0.png");
      EXPECT_TRUE(fs::exists(out.parent_path() / "textured.textures/image0.png"));
      const json own = doc["materials"][0]["extensions"]["FACET_material"];
      EXPECT_EQ(own["material"]["specular"]["base_color"]["texture"], "textured.textures/image0.png") << "relative";
      EXPECT_EQ(doc["samplers"][0]["magFilter"], 9728);
    } else {
      EXPECT_FALSE(fs::exists(out.parent_path() / "textured.textures")) << "embedded in the GLB";
    }
  }
}

struct BadTexture {
  const char* name;
  std::function<void(json&)> spoil;
  const char* path;
  const char* words;
};

void PrintTo(const BadTexture& b, std::ostream* os) { *os << b.name; }

class BadGltfTexture : public ::testing::TestWithParam<BadTexture> {};

TEST_P(BadGltfTexture, FailsClearlyAndWritesNothing) {
  const BadTexture& b = GetParam();
  json g = textured_triangle(json::array({data_uri_image(small_png())}));
  b.spoil(g);
  fs::path in = write_gltf(std::string(b.name) + ".gltf", g);
  fs::path out = scratch(std::string(b.name) + "_out/scene.json");
  fs::remove_all(out.parent_path());
  fs::create_directories(out.parent_path());
  ProcessResult r = run_process({std::string(FACET_BIN), "import-gltf", in.string(), "-o", out.string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(in.string() + ": " + b.path + ": "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(b.words), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_empty(out.parent_path())) << "nothing written";
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadGltfTexture,
    ::testing::Values(
        BadTexture{"missing_external", [](json& g) { g["images"][0] = {{"uri", "not%20here.png"}}; },
                   "materials[0].pbrMetallicRoughness.baseColorTexture.index", "\"not%20here.png\" is not there"},
        BadTexture{"corrupt", [](json& g) { g["images"][0] = data_uri_image("\x89PNG\r\n\x1a\nnot really a png"); },
                   "materials[0].pbrMetallicRoughness.baseColorTexture.index", "not an image facet can decode"},
        BadTexture{"empty", [](json& g) { g["images"][0] = {{"uri", "data:image/png;base64,"}}; }, "images[0].uri",
                   "holds no bytes"},
        BadTexture{"webp_data_uri", [](json& g) { g["images"][0] = {{"uri", "data:image/webp;base64,UklGRg=="}}; },
                   "materials[0].pbrMetallicRoughness.baseColorTexture.index", "\"image/webp\""},
        BadTexture{"ktx2_buffer_view",
                   [](json& g) {
                     g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 12}});
                     g["images"][0] = {{"bufferView", 2}, {"mimeType", "image/ktx2"}};
                   },
                   "materials[0].pbrMetallicRoughness.baseColorTexture.index", "mimeType \"image/ktx2\""},
        BadTexture{"view_past_buffer",
                   [](json& g) {
                     g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 40}, {"byteLength", 40}});
                     g["images"][0] = {{"bufferView", 2}, {"mimeType", "image/png"}};
                   },
                   "images[0].bufferView", "reaches past its buffer"},
        BadTexture{"no_such_image", [](json& g) { g["textures"][0]["source"] = 5; },
                   "materials[0].pbrMetallicRoughness.baseColorTexture.index", "names no image"},
        BadTexture{"no_such_texture",
                   [](json& g) { g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 3; },
                   "materials[0].pbrMetallicRoughness.baseColorTexture.index", "names no texture"},
        BadTexture{"missing_texcoord",
                   [](json& g) { g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1; },
                   "materials[0].pbrMetallicRoughness.baseColorTexture.texCoord", "TEXCOORD_1"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace facet
