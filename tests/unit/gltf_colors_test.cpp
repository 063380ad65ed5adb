// glTF's COLOR_0 (glTF 2.0 §3.7.2.1; §3.9.2: the base colour is baseColorFactor ×
// baseColorTexture × COLOR_0): read in each form glTF allows (VEC3 and VEC4; FLOAT and
// normalized UNSIGNED_BYTE and UNSIGNED_SHORT), carried through a flat-shaded, mirrored
// primitive with its corners, white where a primitive of a mesh has none; the imported
// material multiplies the base colour by it (a material of its own for primitives with
// COLOR_0 where others share the glTF material without), exactly and without a bake; out of
// range colours refused; written back by export-gltf.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <filesystem>
#include <map>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "catalog/program.h"
#include "catalog/texture.h"
#include "core/io.h"
#include "reference/raycaster.h"
#include "scene/gltf.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
const fs::path kSource = FACET_SOURCE_DIR;
const fs::path kExample = kSource / "examples/scenes/vertex_colors.gltf";

// examples/scenes/make_vertex_colors.py's colour of vertex i, channel k, before quantization.
double hashed(uint64_t i, uint64_t k) {
  uint64_t x = (i * 2654435761u + k * 40503u + 12345u) & 0xFFFFFFFFu;
  x ^= x >> 13;
  x = (x * 1274126177u) & 0xFFFFFFFFu;
  return double(x & 0xFFFF) / 65536.0;
}
double generated(uint64_t first, uint64_t i, uint64_t k) { return k < 3 ? 0.1 + 0.9 * hashed(first + i, k) : 0.2 + 0.8 * hashed(first + i, 3); }

const Object& object(const Scene& s, const std::string& name) {
  for (const auto& o : s.objects)
    if (o.name == name) return o;
  throw std::runtime_error("no object " + name);
}

struct Imported {
  Scene scene;
  std::vector<std::string> notes;
  std::vector<GltfImportFile> files;
};

Imported import_example() {
  Imported out;
  out.scene = import_gltf(kExample.string(), {}, out.notes, &out.files);
  return out;
}

TEST(GltfVertexColours, EveryFormIsReadAsTheGeneratorWroteIt) {
  const Imported in = import_example();
  const Scene& s = in.scene;
  // VEC3 FLOAT: float32's value, alpha 1; smooth primitives keep the file's vertex order.
  const Mesh& painted = *object(s, "painted_float").mesh;
  ASSERT_EQ(painted.colors.size(), painted.positions.size());
  for (size_t i = 0; i < painted.colors.size(); ++i) {
    for (size_t k = 0; k < 3; ++k) EXPECT_EQ(painted.colors[i][k], double(float(generated(0, i, k)))) << i;
    EXPECT_EQ(painted.colors[i][3], 1.0) << "RGB: alpha 1";
  }
  // VEC4 normalized unsigned bytes and shorts: c / 255 and c / 65535 (glTF 2.0 §3.11).
  const Mesh& bytes = *object(s, "halves_ubyte_0").mesh;
  const Mesh& shorts = *object(s, "plain_ushort").mesh;
  ASSERT_EQ(bytes.colors.size(), bytes.positions.size());
  ASSERT_EQ(shorts.colors.size(), shorts.positions.size());
  for (size_t i = 0; i < bytes.colors.size(); ++i)
    for (size_t k = 0; k < 4; ++k) EXPECT_EQ(bytes.colors[i][k], std::round(generated(100, i, k) * 255) / 255.0) << i;
  for (size_t i = 0; i < shorts.colors.size(); ++i)
    for (size_t k = 0; k < 4; ++k) EXPECT_EQ(shorts.colors[i][k], std::round(generated(200, i, k) * 65535) / 65535.0) << i;
  EXPECT_NE(bytes.colors[0][3], 1.0);
  // No COLOR_0: no colours (white).
  EXPECT_TRUE(object(s, "halves_ubyte_1").mesh->colors.empty());
}

// The flat-shaded primitive's node mirrors x: the import turns each triangle round (so that it
// still faces its normal) and its corners' colours with it. Each corner's colour is its own
// vertex's: the source vertex at the mirrored position (a 6 × 5 grid over [−2.2, −0.3] × [−1.5, −0.1]).
TEST(GltfVertexColours, MirroredFlatTrianglesKeepEachCornersColour) {
  const Imported in = import_example();
  const Mesh& m = *object(in.scene, "mirrored_flat").mesh;
  ASSERT_EQ(m.colors.size(), m.positions.size());
  ASSERT_EQ(m.positions.size(), 3 * m.triangles.size());
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const double x = -m.positions[v].x, y = m.positions[v].y;
    const auto i = uint64_t(std::lround((x + 2.2) / 1.9 * 5)), j = uint64_t(std::lround((y + 1.5) / 1.4 * 4));
    for (size_t k = 0; k < 3; ++k) EXPECT_EQ(m.colors[v][k], double(float(generated(300, j * 6 + i, k)))) << v;
  }
  // And the turned triangles face their normals.
  for (const auto& t : m.triangles) {
    const Vec3 n = cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    EXPECT_GT(dot(n, m.normals[t[0]]), 0);
  }
}

// glTF 2.0 §3.7.2.1: COLOR_0 multiplies the base colour. The lobe's base_color is the base
// colour map (or none) times the factor and the vertex colour; the occlusion ambient term
// times COLOR_0 too. A primitive without COLOR_0 sharing the glTF material gets the material
// without the vertex colour, under another key. Nothing is baked.
TEST(GltfVertexColours, TheBaseColourTakesTheVertexColourWithoutABake) {
  const Imported in = import_example();
  const Scene& s = in.scene;
  EXPECT_EQ(object(s, "painted_float").material, "painted_vertex_colors");
  EXPECT_EQ(object(s, "halves_ubyte_0").material, "painted_vertex_colors");
  EXPECT_EQ(object(s, "mirrored_flat").material, "painted_vertex_colors");
  EXPECT_EQ(object(s, "halves_ubyte_1").material, "painted");
  EXPECT_EQ(object(s, "plain_ushort").material, "plain_vertex_colors");
  EXPECT_TRUE(in.files.empty()) << "nothing baked: " << in.files.front().path;
  const RGB base = {0.95, 0.9, 0.85};
  const double metal = 0.4;
  for (const char* key : {"painted", "painted_vertex_colors"}) {
    const bool vc = std::string(key) != "painted";
    const Material& m = s.materials.at(key);
    const Value& color = m.specular->at("base_color");
    ASSERT_TRUE(color.texture) << key;
    EXPECT_TRUE(color.texture->has_image());
    EXPECT_EQ(color.texture->vertex_color, vc) << key;
    EXPECT_EQ(color.rgb, base) << key;
    EXPECT_EQ(m.specular->at("metallic").number, metal) << key;
    EXPECT_EQ(compile(m).uses_vertex_color(), vc);
  }
  // The base colour at a point, on a surface of vertex colour vc: base·texel·vc.
  const Value& color = s.materials.at("painted_vertex_colors").specular->at("base_color");
  const VertexColor vc{0.3, 0.6, 0.9, 0.5};
  const auto texel = sample(*color.texture->texels, color.texture->sampler, 0.3, 0.7);
  const auto value = texture_value(color, Range::closed(0, 1), 0.3, 0.7, nullptr, vc);
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(value[c], base[c] * texel[c] * vc[c], 1e-15);
  // Without a base colour map: the vertex colour alone; the occlusion map's ambient term times it.
  const Material& plain = s.materials.at("plain_vertex_colors");
  const Value& plain_color = plain.specular->at("base_color");
  ASSERT_TRUE(plain_color.texture);
  EXPECT_FALSE(plain_color.texture->has_image());
  EXPECT_TRUE(plain_color.texture->vertex_color);
  ASSERT_TRUE(plain.ambient_texture);
  EXPECT_TRUE(plain.ambient_texture->vertex_color);
  EXPECT_EQ(plain.ambient_texture->channel, "r");
  for (const auto& n : in.notes) EXPECT_EQ(n.find("baked"), std::string::npos) << n;
}

// A mesh read whole (a scene file's reference to glTF mesh 1, both primitives): the primitive
// without COLOR_0 is white, as glTF means it.
TEST(GltfVertexColours, APrimitiveWithoutColoursIsWhiteInAMeshWithSome) {
  const fs::path scene = test::scratch("gltf_colors", "whole_mesh.json");
  write_file_atomic(scene.string(), json{{"camera", {{"position", {0, 0, 6}}, {"look_at", {0, 0, 0}}, {"up", {0, 1, 0}}, {"fov", 40}}},
                                         {"lights", json::array()},
                                         {"objects", {{{"type", "mesh"}, {"gltf", kExample.string()}, {"mesh", 1}}}}}
                                        .dump());
  const Scene s = load_scene(scene.string());
  const Mesh& m = *s.objects.at(0).mesh;
  ASSERT_EQ(m.colors.size(), m.positions.size());
  const Imported in = import_example();
  const Mesh& half = *object(in.scene, "halves_ubyte_0").mesh;
  for (size_t i = 0; i < m.colors.size(); ++i)
    if (i < half.colors.size()) EXPECT_EQ(m.colors[i], half.colors[i]) << i;
    else EXPECT_EQ(m.colors[i], (std::array<double, 4>{1, 1, 1, 1})) << i;
}

// A float COLOR_0 beyond what a scene's "colors" hold (negative, here) is refused, naming the
// accessor; so are a count unlike POSITION's and a VEC2.
TEST(GltfVertexColours, BadColoursAreRefused) {
  json g = json::parse(read_file(kExample.string()));
  facet::allow_folder((kSource / "examples").string());  // as --allow-path: the image is outside the file's folder
  g["images"][0]["uri"] = (kSource / "examples/textured/textures/checker.png").string();
  const int color = g["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"];
  auto refused = [&](const json& file, const std::string& key, const std::string& words) {
    const fs::path p = test::scratch("gltf_colors", "bad.gltf");
    write_file_atomic(p.string(), file.dump());
    std::vector<std::string> notes;
    try {
      import_gltf(p.string(), {}, notes);
      ADD_FAILURE() << "accepted: " << key;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  // The first colour's red as −1: the buffer's bytes rewritten.
  json negative = g;
  std::string bin = test::base64_decode(negative["buffers"][0]["uri"].get<std::string>());
  const json& view = negative["bufferViews"][negative["accessors"][color]["bufferView"].get<size_t>()];
  const float minus_one = -1;
  bin.replace(view["byteOffset"].get<size_t>(), 4, reinterpret_cast<const char*>(&minus_one), 4);
  negative["buffers"][0]["uri"] = "data:application/octet-stream;base64," + test::base64(bin);
  refused(negative, fmt::format("accessors[{}]", color), "a vertex colour component is -1");
  json fewer = g;
  fewer["accessors"][color]["count"] = fewer["accessors"][color]["count"].get<int>() - 1;
  refused(fewer, "meshes[0].primitives[0].attributes.COLOR_0", "a different count from POSITION");
  json vec2 = g;
  vec2["accessors"][color]["type"] = "VEC2";
  refused(vec2, fmt::format("accessors[{}]", color), "expected VEC4");
}

// export-gltf writes a mesh's colours as COLOR_0 (VEC4 FLOAT) and the material (FACET_material)
// with its "vertex_color"; the import reads both back: the same colours to float32, the same
// material.
TEST(GltfVertexColours, ExportWritesColor0AndTheImportReadsItBack) {
  const Scene original = load_scene((kSource / "tests/scenes/vertex_colors.json").string());
  const Material m = load_material((kSource / "examples/textured/textured_vertex_color.json").string());
  const fs::path out = test::scratch("gltf_colors", "export/vertex_colors.gltf");
  std::vector<std::string> notes;
  export_gltf(original, &m, out.string(), notes);
  const json written = json::parse(read_file(out.string()));
  EXPECT_TRUE(written["meshes"][0]["primitives"][0]["attributes"].contains("COLOR_0"));
  EXPECT_FALSE(written["meshes"][1]["primitives"][0]["attributes"].contains("COLOR_0")) << "the sphere has none";
  const Scene back = import_gltf(out.string(), {}, notes);
  ASSERT_EQ(back.objects.size(), original.objects.size());
  for (size_t i = 0; i < original.objects.size(); ++i) {
    if (original.objects[i].type != Object::Type::Mesh) continue;
    const auto& a = original.objects[i].mesh->colors;
    const auto& b = back.objects[i].mesh->colors;
    ASSERT_EQ(a.size(), b.size()) << i;
    for (size_t v = 0; v < a.size(); ++v)
      for (size_t k = 0; k < 4; ++k) EXPECT_EQ(b[v][k], double(float(a[v][k]))) << i << "," << v;
    EXPECT_TRUE(compile(back.material_of(i, nullptr)).uses_vertex_color());
  }
}


// glTF's alphaMode MASK compares the base colour's alpha times COLOR_0's; facet's renderers
// cut by the base colour's alpha alone (Cycles' shadow rays cannot read another mesh's vertex
// colour), so the import leaves COLOR_0's alpha out, says so, and a material whose alpha takes
// the vertex colour is refused by name. The ushort sheet (vertex alpha 0.2 … 1, base alpha 1)
// therefore covers what it covers opaque.
TEST(GltfVertexColours, TheCutOutLeavesTheVertexAlphaOutWithANote) {
  json g = json::parse(read_file(kExample.string()));
  facet::allow_folder((kSource / "examples").string());  // as --allow-path: the image is outside the file's folder
  g["images"][0]["uri"] = (kSource / "examples/textured/textures/checker.png").string();
  g["materials"][1]["alphaMode"] = "MASK";
  g["materials"][1]["alphaCutoff"] = 0.6;
  const fs::path p = test::scratch("gltf_colors", "masked.gltf");
  write_file_atomic(p.string(), g.dump());
  std::vector<std::string> notes;
  const Scene masked = import_gltf(p.string(), {}, notes);
  const Material& m = masked.materials.at("plain_vertex_colors");
  ASSERT_TRUE(m.masked());
  EXPECT_FALSE(m.alpha.texture && m.alpha.texture->vertex_color);
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const std::string& n) {
    return n.find("materials[1] (COLOR_0)") != std::string::npos && n.find("COLOR_0's alpha is left out") != std::string::npos;
  }));
  std::vector<std::string> plain_notes;
  const Scene opaque = import_gltf(kExample.string(), {}, plain_notes);
  size_t sheet = 0;
  while (masked.objects[sheet].name != "plain_ushort") ++sheet;
  auto covered = [&](const Scene& s) {
    const Render r = render_reference(s, 160, 120);
    return size_t(std::count(r.object.begin(), r.object.end(), int(sheet)));
  };
  EXPECT_GT(covered(opaque), 0u);
  EXPECT_EQ(covered(masked), covered(opaque));

  json refused = {{"name", "leaf"}, {"alpha", {{"vertex_color", true}, {"channel", "a"}}}, {"alpha_cutoff", 0.5}};
  try {
    parse_material(refused, "leaf.json");
    ADD_FAILURE() << "a cut-out of the vertex alpha was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("alpha.vertex_color"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot take the vertex colour"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace facet
