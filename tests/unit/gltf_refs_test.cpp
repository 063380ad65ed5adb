// Scene files that reference their geometry in glTF files: the referencing scene
// `facet import-gltf` writes is the inline one, bit for bit; references by mesh,
// node, name and primitive read what they say; bad files and references fail
// naming the file and the key, with exit status 1 and nothing written.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/io.h"
#include "reference/raycaster.h"
#include "scene/gltf.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
const fs::path kSource = FACET_SOURCE_DIR;

fs::path scratch(const std::string& name) { return test::scratch("gltf-refs", name); }

// A GLB of `doc` with `bin` as its BIN chunk (padded to 4 bytes; the header's
// lengths are the true ones unless a test changes them).
void write_glb(const fs::path& path, const json& doc, std::string bin) {
  std::string text = doc.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  bin.append((4 - bin.size() % 4) % 4, '\0');
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  std::string glb = u32(0x46546C67) + u32(2) + u32(uint32_t(12 + 8 + text.size() + 8 + bin.size())) +
                    u32(uint32_t(text.size())) + u32(0x4E4F534A) + text + u32(uint32_t(bin.size())) +
                    u32(0x004E4942) + bin;
  std::ofstream(path, std::ios::binary) << glb;
}

// One triangle's mesh (float positions, uint16 indices repeated `copies` times:
// `copies` triangles; with `normals` a NORMAL accessor, else flat shading), one
// material, and `nodes` nodes that show it.
json triangle_doc(size_t copies, size_t nodes, std::string& bin, bool normals = false) {
  const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const float nor[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  bin.assign(reinterpret_cast<const char*>(pos), sizeof pos);
  for (size_t i = 0; i < copies; ++i)
    for (uint16_t k : {0, 1, 2}) bin.append(reinterpret_cast<const char*>(&k), 2);
  bin.append((4 - bin.size() % 4) % 4, '\0');
  const size_t normals_at = bin.size();
  if (normals) bin.append(reinterpret_cast<const char*>(nor), sizeof nor);
  json doc = {{"asset", {{"version", "2.0"}}},
              {"scene", 0},
              {"scenes", {{{"nodes", json::array()}}}},
              {"nodes", json::array()},
              {"meshes", {{{"name", "tri"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1},
                                                             {"material", 0}}}}}}},
              {"materials", {{{"name", "m"}}}},
              {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
                             {{"bufferView", 1}, {"componentType", 5123}, {"count", 3 * copies}, {"type", "SCALAR"}}}},
              {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                               {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 6 * copies}}}},
              {"buffers", {{{"byteLength", bin.size()}}}}};
  if (normals) {
    doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
    doc["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", normals_at}, {"byteLength", 36}});
  }
  for (size_t n = 0; n < nodes; ++n) {
    doc["nodes"].push_back({{"name", "n" + std::to_string(n)}, {"mesh", 0}});
    doc["scenes"][0]["nodes"].push_back(n);
  }
  return doc;
}

// A scene file whose objects are `objects`.
fs::path write_scene(const std::string& name, const json& objects) {
  fs::path p = scratch(name);
  json scene = {{"camera", {{"position", {0.3, 0.3, 3}}, {"look_at", {0.3, 0.3, 0}}}},
                {"materials", {{"grey", {{"diffuse", {{"model", "lambert"}, {"color", 0.7}}}}}}},
                {"objects", objects},
                {"lights", {{{"type", "point"}, {"position", {1, 2, 4}}, {"color", 1}}}}};
  write_file_atomic(p.string(), scene.dump(1));
  return p;
}

// The command fails with status 1, its message names each of `words` (the file,
// the key path), and `out` is not written.
void expect_fails(const std::vector<std::string>& args, const fs::path& out, const std::vector<std::string>& words) {
  fs::remove(out);
  ProcessResult r = test::facet(args);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  for (const auto& w : words) EXPECT_NE(r.output.find(w), std::string::npos) << "expected «" << w << "» in " << r.output;
  EXPECT_FALSE(fs::exists(out)) << out << " was written";
}

// Vertex data as comparable arrays.
std::vector<std::array<double, 3>> xyz(const std::vector<Vec3>& v) {
  std::vector<std::array<double, 3>> out;
  for (const auto& p : v) out.push_back(p.array());
  return out;
}
using Points = std::vector<std::array<double, 3>>;

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t nl; (nl = text.find('\n', start)) != std::string::npos; start = nl + 1)
    out.push_back(text.substr(start, nl - start));
  return out;
}

TEST(GltfRefs, ImportWritesAReferencingSceneThatIsTheInlineOne) {
  const std::string gltf = (kSource / "examples/scenes/three_meshes.gltf").string();
  fs::path refs = scratch("three_refs.json"), inl = scratch("three_inline.json");
  ASSERT_EQ(test::facet({"import-gltf", gltf, "-o", refs.string()}).exit_code, 0);
  ASSERT_EQ(test::facet({"import-gltf", gltf, "--inline", "-o", inl.string()}).exit_code, 0);
  EXPECT_LT(fs::file_size(refs), 8000u) << "a few kB, whatever the meshes";
  json doc = json::parse(read_file(refs.string()));
  for (const auto& o : doc["objects"]) {
    EXPECT_FALSE(o.contains("positions")) << o.dump();
    EXPECT_EQ(fs::path(o.at("gltf").get<std::string>()).filename(), "three_meshes.gltf");
    EXPECT_TRUE(fs::path(o["gltf"].get<std::string>()).is_relative()) << "relative to the scene file";
    EXPECT_TRUE(o.contains("node"));
  }
  Scene a = load_scene(refs.string()), b = load_scene(inl.string());
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t i = 0; i < a.objects.size(); ++i) {
    ASSERT_TRUE(a.objects[i].mesh && b.objects[i].mesh);
    EXPECT_EQ(xyz(a.objects[i].mesh->positions), xyz(b.objects[i].mesh->positions)) << i;
    EXPECT_EQ(xyz(a.objects[i].mesh->normals), xyz(b.objects[i].mesh->normals)) << i;
    EXPECT_EQ(a.objects[i].mesh->triangles, b.objects[i].mesh->triangles) << i;
  }
  Render ra = render_reference(a, 96, 72), rb = render_reference(b, 96, 72);
  EXPECT_EQ(ra.image.rgb, rb.image.rgb) << "the same picture";
  // The POV-Ray scenes differ only in the header line that names the source (written under one
  // name in two folders: a scene names its meshes' data images after itself), their data images not at all.
  fs::create_directories(scratch("refs"));
  fs::create_directories(scratch("inline"));
  fs::path pa = scratch("refs/three.pov"), pb = scratch("inline/three.pov");
  ASSERT_EQ(test::facet({"generate", "--target", "pov", "--scene", refs.string(), "-o", pa.string()}).exit_code, 0);
  ASSERT_EQ(test::facet({"generate", "--target", "pov", "--scene", inl.string(), "-o", pb.string()}).exit_code, 0);
  std::vector<std::string> la = lines(read_file(pa.string())), lb = lines(read_file(pb.string()));
  ASSERT_EQ(la.size(), lb.size());
  size_t differ = 0;
  for (size_t i = 0; i < la.size(); ++i)
    if (la[i] != lb[i]) {
      ++differ;
      EXPECT_NE(la[i].find("three_refs.json"), std::string::npos) << la[i];
    }
  EXPECT_EQ(differ, 1u);
  for (int m = 0; m < 4; ++m) {
    const std::string image = "three_mesh" + std::to_string(m) + ".ppm";
    EXPECT_EQ(read_file(scratch("refs/" + image).string()), read_file(scratch("inline/" + image).string())) << image;
  }
}

TEST(GltfRefs, ExampleReferencesByNameAreTheImport) {
  // examples/scenes/three_meshes_refs.json names the nodes of three_meshes.gltf.
  Scene refs = load_scene((kSource / "examples/scenes/three_meshes_refs.json").string());
  std::vector<std::string> notes;
  Scene imported = import_gltf((kSource / "examples/scenes/three_meshes.gltf").string(), {}, notes);
  ASSERT_EQ(refs.objects.size(), imported.objects.size());
  for (size_t i = 0; i < refs.objects.size(); ++i) {
    EXPECT_EQ(refs.objects[i].name, imported.objects[i].name);
    EXPECT_EQ(refs.objects[i].material, imported.objects[i].material);
    EXPECT_EQ(xyz(refs.objects[i].mesh->positions), xyz(imported.objects[i].mesh->positions)) << i;
    EXPECT_EQ(xyz(refs.objects[i].mesh->normals), xyz(imported.objects[i].mesh->normals)) << i;
    EXPECT_EQ(refs.objects[i].mesh->triangles, imported.objects[i].mesh->triangles) << i;
  }
}

TEST(GltfRefs, ByMeshNodeNameAndPrimitive) {
  // Node n1 is a child of n0: its world transform is n0's translation times its own scale.
  std::string bin;
  json doc = triangle_doc(1, 2, bin);
  doc["nodes"][0]["translation"] = {1, 2, 3};
  doc["nodes"][0]["children"] = {1};
  doc["nodes"][0].erase("mesh");
  doc["nodes"][1]["scale"] = {2, 2, -2};  // mirroring: the triangle turns round
  doc["scenes"][0]["nodes"] = {0};
  write_glb(scratch("tree.glb"), doc, bin);
  fs::path scene = write_scene("tree.json", {{{"type", "mesh"}, {"gltf", "tree.glb"}, {"node", "n1"}},
                                             {{"type", "mesh"}, {"gltf", "tree.glb"}, {"node", 1}},
                                             {{"type", "mesh"}, {"gltf", "tree.glb"}, {"mesh", 0}},
                                             {{"type", "mesh"}, {"gltf", "tree.glb"}, {"mesh", "tri"}},
                                             {{"type", "mesh"}, {"gltf", "tree.glb"}, {"node", 1}, {"primitive", 0}}});
  Scene s = load_scene(scene.string());
  ASSERT_EQ(s.objects.size(), 5u);
  const Mesh& node = *s.objects[0].mesh;
  // Flat (no NORMAL): the triangle's own vertices; the mirroring turned it round.
  EXPECT_EQ(xyz(node.positions), (Points{{1, 2, 3}, {1, 4, 3}, {3, 2, 3}}));
  EXPECT_EQ(node.triangles, (std::vector<std::array<uint32_t, 3>>{{0, 1, 2}}));
  EXPECT_EQ(xyz(node.normals), (Points{{0, 0, -1}, {0, 0, -1}, {0, 0, -1}}));
  EXPECT_EQ(s.objects[1].mesh, s.objects[0].mesh) << "the same node by name and by index: one mesh, read once";
  EXPECT_EQ(xyz(s.objects[2].mesh->positions), (Points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})) << "a mesh as it is";
  EXPECT_EQ(s.objects[3].mesh, s.objects[2].mesh) << "by name or by index: the same mesh";
  EXPECT_EQ(xyz(s.objects[4].mesh->positions), xyz(node.positions)) << "its one primitive, by index";
  // What import-gltf reads of the node is what the reference reads.
  std::vector<std::string> notes;
  Scene imported = import_gltf(scratch("tree.glb").string(), {}, notes);
  ASSERT_EQ(imported.objects.size(), 1u);
  EXPECT_EQ(xyz(imported.objects[0].mesh->positions), xyz(node.positions));
  EXPECT_EQ(xyz(imported.objects[0].mesh->normals), xyz(node.normals));
}

TEST(GltfRefs, ExportReadsAReferencingScene) {
  std::string bin;
  json doc = triangle_doc(1, 1, bin);
  write_glb(scratch("one.glb"), doc, bin);
  fs::path scene = write_scene("one.json", {{{"type", "mesh"}, {"gltf", "one.glb"}, {"node", 0}, {"material", "grey"}}});
  fs::path out = scratch("one_export.glb");
  ASSERT_EQ(test::facet({"export-gltf", scene.string(), "-o", out.string()}).exit_code, 0);
  std::vector<std::string> notes;
  Scene back = import_gltf(out.string(), {}, notes);
  ASSERT_EQ(back.objects.size(), 1u);
  EXPECT_EQ(back.objects[0].mesh->triangles.size(), 1u);
}

// ---------------------------------------------------------------- bad input

// A GLB whose accessor claims more elements than its buffer view holds.
TEST(GltfRefs, AccessorPastItsBufferView) {
  std::string bin;
  json doc = triangle_doc(1, 1, bin);
  doc["accessors"][0]["count"] = 1000;
  write_glb(scratch("long_accessor.glb"), doc, bin);
  fs::path out = scratch("long_accessor.json");
  expect_fails({"import-gltf", scratch("long_accessor.glb").string(), "-o", out.string()}, out,
               {"long_accessor.glb: accessors[0]: ", "bufferViews[0]"});
  fs::path scene = write_scene("long_accessor_ref.json", {{{"type", "mesh"}, {"gltf", "long_accessor.glb"}, {"node", 0}}});
  fs::path pov = scratch("long_accessor.pov");
  expect_fails({"generate", "--target", "pov", "--scene", scene.string(), "-o", pov.string()}, pov,
               {"long_accessor_ref.json: objects[0].gltf: ", "long_accessor.glb: accessors[0]: "});
}

// A buffer view past the end of its buffer.
TEST(GltfRefs, BufferViewPastItsBuffer) {
  std::string bin;
  json doc = triangle_doc(1, 1, bin);
  doc["bufferViews"][1]["byteLength"] = 6000;
  doc["accessors"][1]["count"] = 3000;
  write_glb(scratch("long_view.glb"), doc, bin);
  fs::path out = scratch("long_view.json");
  expect_fails({"import-gltf", scratch("long_view.glb").string(), "-o", out.string()}, out,
               {"long_view.glb: bufferViews[1]: ", "past the end of buffer 0"});
}

// A buffer longer than the BIN chunk that holds it, and a BIN chunk longer than the file.
TEST(GltfRefs, BufferPastTheBinChunk) {
  std::string bin;
  json doc = triangle_doc(1, 1, bin);
  doc["buffers"][0]["byteLength"] = 1 << 20;
  write_glb(scratch("long_buffer.glb"), doc, bin);
  fs::path out = scratch("long_buffer.json");
  expect_fails({"import-gltf", scratch("long_buffer.glb").string(), "-o", out.string()}, out,
               {"long_buffer.glb: buffers[0].byteLength: ", "BIN chunk"});
  fs::path scene = write_scene("long_buffer_ref.json", {{{"type", "mesh"}, {"gltf", "long_buffer.glb"}, {"mesh", 0}}});
  fs::path pov = scratch("long_buffer.pov");
  expect_fails({"generate", "--target", "pov", "--scene", scene.string(), "-o", pov.string()}, pov,
               {"long_buffer_ref.json: objects[0].gltf: ", "long_buffer.glb: buffers[0].byteLength: "});

  doc = triangle_doc(1, 1, bin);
  write_glb(scratch("long_chunk.glb"), doc, bin);
  std::string bytes = read_file(scratch("long_chunk.glb").string());
  const uint32_t json_length = [&] { uint32_t v; std::memcpy(&v, bytes.data() + 12, 4); return v; }();
  const uint32_t claimed = 1 << 20;
  std::memcpy(&bytes[20 + json_length], &claimed, 4);
  std::ofstream(scratch("long_chunk.glb"), std::ios::binary) << bytes;
  expect_fails({"import-gltf", scratch("long_chunk.glb").string(), "-o", out.string()}, out,
               {"long_chunk.glb: (document): ", "BIN chunk claims 1,048,576 bytes"});
}

// Node 1 is a child of node 0 and, wrongly, a root of the scene too: a reference to
// node 1 could not say which of its two transforms it means.
TEST(GltfRefs, RootThatIsAChild) {
  std::string bin;
  json doc = triangle_doc(1, 2, bin);
  doc["nodes"][0]["translation"] = {1, 0, 0};
  doc["nodes"][0]["children"] = {1};
  write_glb(scratch("two_roots.glb"), doc, bin);
  fs::path out = scratch("two_roots.json");
  expect_fails({"import-gltf", scratch("two_roots.glb").string(), "-o", out.string()}, out,
               {"two_roots.glb: nodes[1]: ", "is one of the scene's roots and also a child of nodes[0]"});
}

TEST(GltfRefs, MissingFile) {
  fs::path scene = write_scene("missing.json", {{{"type", "mesh"}, {"gltf", "no_such.glb"}, {"node", 0}}});
  fs::path pov = scratch("missing.pov");
  expect_fails({"generate", "--target", "pov", "--scene", scene.string(), "-o", pov.string()}, pov,
               {"missing.json: objects[0].gltf: ", "no_such.glb"});
}

TEST(GltfRefs, NoSuchMeshOrNode) {
  std::string bin;
  json doc = triangle_doc(1, 2, bin);
  doc["nodes"][1].erase("mesh");  // n1: a node without a mesh
  write_glb(scratch("two.glb"), doc, bin);
  struct Case {
    json ref;
    std::string key, words;
  };
  for (const Case& c : {Case{{{"mesh", 3}}, "objects[0].mesh: ", "has no meshes[3]; it has 1 (0 to 0)"},
                        Case{{{"mesh", "trx"}}, "objects[0].mesh: ", "has no mesh named \"trx\" (did you mean \"tri\"?)"},
                        Case{{{"node", 7}}, "objects[0].node: ", "has no nodes[7]; it has 2 (0 to 1)"},
                        Case{{{"node", "n9"}}, "objects[0].node: ", "has no node named \"n9\""},
                        Case{{{"node", "n1"}}, "objects[0].node: ", "nodes[1] (\"n1\") has no mesh"},
                        Case{{{"node", 0}, {"primitive", 1}}, "objects[0].primitive: ", "meshes[0] has 1 primitive (0 to 0)"}}) {
    json ref = {{"type", "mesh"}, {"gltf", "two.glb"}};
    ref.update(c.ref);
    fs::path scene = write_scene("two_ref.json", json::array({ref}));
    fs::path pov = scratch("two_ref.pov");
    expect_fails({"generate", "--target", "pov", "--scene", scene.string(), "-o", pov.string()}, pov,
                 {"two_ref.json: " + c.key, "two.glb", c.words});
  }
}

TEST(GltfRefs, InlineAndReferenceAtOnceOrNeither) {
  json both = {{"type", "mesh"}, {"gltf", "two.glb"}, {"node", 0}, {"positions", {{0, 0, 0}}}};
  json neither = {{"type", "mesh"}, {"gltf", "two.glb"}};
  fs::path scene = write_scene("both.json", {both, neither});
  fs::path pov = scratch("both.pov");
  expect_fails({"generate", "--target", "pov", "--scene", scene.string(), "-o", pov.string()}, pov,
               {"both.json: objects[0].positions: not allowed with a glTF file's node",
                "both.json: objects[1]: missing \"mesh\" (a glTF file's mesh) or \"node\" (a glTF file's node)"});
}

// 401 nodes of a 250,000-triangle mesh: 100,250,000 triangles, over the limit,
// refused before any mesh is allocated (the command takes well under a second).
TEST(GltfRefs, SceneOverTheTriangleLimit) {
  std::string bin;
  json doc = triangle_doc(250'000, 401, bin, true);
  write_glb(scratch("many.glb"), doc, bin);
  fs::path out = scratch("many.json");
  expect_fails({"import-gltf", scratch("many.glb").string(), "-o", out.string()}, out,
               {"many.glb: nodes[400]: ", "100,250,000 triangles", "limit is 100,000,000 triangles"});
  json objects = json::array();
  for (int n = 0; n < 401; ++n) objects.push_back({{"type", "mesh"}, {"gltf", "many.glb"}, {"node", n}});
  fs::path scene = write_scene("many_ref.json", objects);
  fs::path pov = scratch("many_ref.pov");
  expect_fails({"generate", "--target", "pov", "--scene", scene.string(), "-o", pov.string()}, pov,
               {"many_ref.json: objects[400]: ", "nodes[400] of", "many.glb", "limit is 100,000,000 triangles"});
}

}  // namespace
}  // namespace facet
