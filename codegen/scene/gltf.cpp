#include "scene/gltf.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <fmt/format.h>
#include <tiny_gltf.h>

#include "core/io.h"
#include "core/vec.h"

namespace facet {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const char* kMaterialExt = "FACET_material";
const char* kObjectExt = "FACET_object";
const char* kLightExt = "FACET_light";
const char* kSceneExt = "FACET_scene";
const char* kLightsExt = "KHR_lights_punctual";
const std::set<std::string> kSupportedRequired = {kLightsExt, kMaterialExt, kObjectExt, kLightExt, kSceneExt};

// ---------------------------------------------------------------- 4×4 matrices, column-major as glTF

struct Mat4 {
  double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  double operator()(int row, int col) const { return m[col * 4 + row]; }
  double& operator()(int row, int col) { return m[col * 4 + row]; }
  Mat4 operator*(const Mat4& b) const {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        double s = 0;
        for (int k = 0; k < 4; ++k) s += (*this)(i, k) * b(k, j);
        r(i, j) = s;
      }
    return r;
  }
  Vec3 point(const Vec3& p) const {
    return {(*this)(0, 0) * p.x + (*this)(0, 1) * p.y + (*this)(0, 2) * p.z + (*this)(0, 3),
            (*this)(1, 0) * p.x + (*this)(1, 1) * p.y + (*this)(1, 2) * p.z + (*this)(1, 3),
            (*this)(2, 0) * p.x + (*this)(2, 1) * p.y + (*this)(2, 2) * p.z + (*this)(2, 3)};
  }
  Vec3 direction(const Vec3& d) const {
    return {(*this)(0, 0) * d.x + (*this)(0, 1) * d.y + (*this)(0, 2) * d.z,
            (*this)(1, 0) * d.x + (*this)(1, 1) * d.y + (*this)(1, 2) * d.z,
            (*this)(2, 0) * d.x + (*this)(2, 1) * d.y + (*this)(2, 2) * d.z};
  }
  double det3() const {
    const Mat4& a = *this;
    return a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) - a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0)) +
           a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
  }
  // Normals transform by the inverse transpose of the upper 3×3 (up to scale: the cofactor matrix).
  Vec3 normal(const Vec3& n) const {
    const Mat4& a = *this;
    Vec3 c0(a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1), a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2), a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
    Vec3 c1(a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2), a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0), a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1));
    Vec3 c2(a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1), a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2), a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0));
    Vec3 r = c0 * n.x + c1 * n.y + c2 * n.z;
    return normalize(det3() < 0 ? -r : r);
  }
};

Mat4 local_matrix(const tinygltf::Node& n) {
  Mat4 m;
  if (n.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i) m.m[i] = n.matrix[size_t(i)];
    return m;
  }
  Mat4 t, r, s;
  if (n.translation.size() == 3) t(0, 3) = n.translation[0], t(1, 3) = n.translation[1], t(2, 3) = n.translation[2];
  if (n.rotation.size() == 4) {
    double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
    r(0, 0) = 1 - 2 * (y * y + z * z), r(0, 1) = 2 * (x * y - z * w), r(0, 2) = 2 * (x * z + y * w);
    r(1, 0) = 2 * (x * y + z * w), r(1, 1) = 1 - 2 * (x * x + z * z), r(1, 2) = 2 * (y * z - x * w);
    r(2, 0) = 2 * (x * z - y * w), r(2, 1) = 2 * (y * z + x * w), r(2, 2) = 1 - 2 * (x * x + y * y);
  }
  if (n.scale.size() == 3) s(0, 0) = n.scale[0], s(1, 1) = n.scale[1], s(2, 2) = n.scale[2];
  return t * r * s;
}

json extension(const std::string& extensions_json, const char* name) {
  if (extensions_json.empty()) return nullptr;
  json all = json::parse(extensions_json, nullptr, false);
  if (!all.is_object() || !all.contains(name)) return nullptr;
  return all[name];
}

// ---------------------------------------------------------------- reading accessors

class Reader {
 public:
  Reader(const tinygltf::Model& m, const std::string& file) : m_(m), file_(file) {}

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw InputError({{file_, path, message, 0, 0}});
  }

  const unsigned char* data(int index, const std::string& path, size_t& count, size_t& stride, int& type,
                            int& component) const {
    if (index < 0 || size_t(index) >= m_.accessors.size()) fail(path, "names no accessor");
    const auto& a = m_.accessors[size_t(index)];
    std::string apath = fmt::format("accessors[{}]", index);
    if (a.sparse.isSparse) fail(apath, "sparse accessors are not supported");
    if (a.bufferView < 0 || size_t(a.bufferView) >= m_.bufferViews.size()) fail(apath, "has no buffer view");
    const auto& v = m_.bufferViews[size_t(a.bufferView)];
    if (v.buffer < 0 || size_t(v.buffer) >= m_.buffers.size()) fail(apath, "its buffer view names no buffer");
    const auto& b = m_.buffers[size_t(v.buffer)];
    count = a.count;
    type = a.type;
    component = a.componentType;
    int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(component));
    int components = tinygltf::GetNumComponentsInType(uint32_t(type));
    if (component_size <= 0 || components <= 0) fail(apath, "has an unknown componentType or type");
    size_t elem = size_t(component_size) * size_t(components);
    stride = v.byteStride ? v.byteStride : elem;
    if (stride < elem) fail(fmt::format("bufferViews[{}].byteStride", a.bufferView), "is smaller than one element");
    // start + stride·(count − 1) + elem ≤ size, checked without overflowing.
    size_t size = b.data.size();
    bool inside = v.byteOffset <= size && a.byteOffset <= size - v.byteOffset;
    size_t start = inside ? v.byteOffset + a.byteOffset : 0;
    if (count > 0) inside = inside && elem <= size - start && (size - start - elem) / stride >= count - 1;
    if (!inside) fail(apath, fmt::format("reads past the end of buffer {} ({} bytes)", v.buffer, size));
    return b.data.data() + start;
  }

  std::vector<Vec3> vec3(int index, const std::string& path) const {
    size_t count, stride;
    int type, component;
    const unsigned char* p = data(index, path, count, stride, type, component);
    if (type != TINYGLTF_TYPE_VEC3 || component != TINYGLTF_COMPONENT_TYPE_FLOAT)
      fail(fmt::format("accessors[{}]", index), "expected VEC3 of FLOAT");
    std::vector<Vec3> out(count);
    for (size_t i = 0; i < count; ++i) {
      float f[3];
      std::memcpy(f, p + i * stride, sizeof f);
      if (!std::isfinite(f[0]) || !std::isfinite(f[1]) || !std::isfinite(f[2]))
        fail(fmt::format("accessors[{}]", index), fmt::format("element {} is not finite", i));
      out[i] = Vec3(f[0], f[1], f[2]);
    }
    return out;
  }

  std::vector<uint32_t> indices(int index, const std::string& path) const {
    size_t count, stride;
    int type, component;
    const unsigned char* p = data(index, path, count, stride, type, component);
    if (type != TINYGLTF_TYPE_SCALAR) fail(fmt::format("accessors[{}]", index), "indices must be SCALAR");
    std::vector<uint32_t> out(count);
    for (size_t i = 0; i < count; ++i) {
      const unsigned char* e = p + i * stride;
      if (component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) out[i] = *e;
      else if (component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t v;
        std::memcpy(&v, e, 2);
        out[i] = v;
      } else if (component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        std::memcpy(&out[i], e, 4);
      } else {
        fail(fmt::format("accessors[{}]", index), "indices must be unsigned integers");
      }
    }
    return out;
  }

 private:
  const tinygltf::Model& m_;
  std::string file_;
};

// ---------------------------------------------------------------- materials

std::array<double, 3> rgb3(const std::vector<double>& v, double fallback) {
  return {v.size() > 0 ? v[0] : fallback, v.size() > 1 ? v[1] : fallback, v.size() > 2 ? v[2] : fallback};
}

// glTF metallic–roughness onto the catalog (see gltf.h).
json pbr_material(const tinygltf::Material& g, const std::string& path, std::vector<std::string>& notes) {
  const auto& pbr = g.pbrMetallicRoughness;
  auto base = rgb3(pbr.baseColorFactor, 1);
  double metal = pbr.metallicFactor, rough = pbr.roughnessFactor;
  json m = {{"name", g.name.empty() ? path : g.name}};
  RGB kd, f0;
  for (int c = 0; c < 3; ++c) {
    kd[size_t(c)] = base[size_t(c)] * (1 - metal);
    f0[size_t(c)] = 0.04 * (1 - metal) + base[size_t(c)] * metal;
  }
  if (kd[0] + kd[1] + kd[2] > 0) m["diffuse"] = {{"model", "lambert"}, {"color", kd}};
  m["specular"] = {{"model", "ggx"},
                   {"alpha", std::max(rough * rough, 1e-4)},
                   {"geometry", "smith_ggx"},
                   {"fresnel", {{"model", "schlick"}, {"f0", f0}}}};
  auto e = rgb3(g.emissiveFactor, 0);
  json strength = extension(g.extensions_json_string, "KHR_materials_emissive_strength");
  double k = strength.is_object() ? strength.value("emissiveStrength", 1.0) : 1.0;
  if (e[0] + e[1] + e[2] > 0) m["emission"] = {e[0] * k, e[1] * k, e[2] * k};
  if (pbr.baseColorTexture.index >= 0 || pbr.metallicRoughnessTexture.index >= 0 || g.normalTexture.index >= 0 ||
      g.emissiveTexture.index >= 0 || g.occlusionTexture.index >= 0)
    notes.push_back(path + ": textures are ignored; the material uses its factors");
  if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty())
    notes.push_back(path + ": alphaMode " + g.alphaMode + " is ignored (facet's surfaces are opaque)");
  if (metal < 1 && kd[0] + kd[1] + kd[2] > 0)
    notes.push_back(path + ": approximate: glTF weights a dielectric's diffuse by (1 − F); the catalog's Lambert does not");
  return m;
}

// ---------------------------------------------------------------- export helpers

tinygltf::Value value_of(const json& j) {
  switch (j.type()) {
    case json::value_t::boolean: return tinygltf::Value(j.get<bool>());
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return tinygltf::Value(j.get<int>());
    case json::value_t::number_float: return tinygltf::Value(j.get<double>());
    case json::value_t::string: return tinygltf::Value(j.get<std::string>());
    case json::value_t::array: {
      tinygltf::Value::Array a;
      for (const auto& e : j) a.push_back(value_of(e));
      return tinygltf::Value(a);
    }
    case json::value_t::object: {
      tinygltf::Value::Object o;
      for (const auto& [k, v] : j.items()) o[k] = value_of(v);
      return tinygltf::Value(o);
    }
    default: return tinygltf::Value();
  }
}

// The nearest metallic–roughness material, from what the catalog says of the
// lobes: the specular lobe's equivalent GGX α (roughness = √α; α = 1 where it has
// none) and, for a material without diffuse whose Fresnel term states F(0), a
// conductor whose base colour is that F(0).
void fallback_pbr(const Material& m, tinygltf::Material& g) {
  RGB base{0, 0, 0};
  double metal = 0, alpha = 1;
  if (m.diffuse) base = m.diffuse->at("color").rgb;
  if (m.specular) {
    const ModelDef& lobe = *m.specular->def;
    if (lobe.ggx_alpha) alpha = lobe.ggx_alpha(*m.specular);
    auto f = m.specular->values.find("fresnel");
    const ModelSpec* fresnel = f != m.specular->values.end() ? f->second.model.get() : nullptr;
    if (!m.diffuse && fresnel && fresnel->def->normal_reflectance) {
      base = fresnel->def->normal_reflectance(*fresnel);  // a conductor: its F(0) is the base colour
      metal = 1;
    }
  }
  for (double& c : base) c = std::clamp(c, 0.0, 1.0);
  g.pbrMetallicRoughness.baseColorFactor = {base[0], base[1], base[2], 1.0};
  g.pbrMetallicRoughness.metallicFactor = metal;
  g.pbrMetallicRoughness.roughnessFactor = std::clamp(std::sqrt(alpha), 0.0, 1.0);
  g.emissiveFactor = {std::clamp(m.emission[0], 0.0, 1.0), std::clamp(m.emission[1], 0.0, 1.0),
                      std::clamp(m.emission[2], 0.0, 1.0)};
}

// A sphere as a UV mesh (the analytic definition travels in FACET_object).
void sphere_mesh(const Object& o, std::vector<Vec3>& pos, std::vector<Vec3>& nor, std::vector<uint32_t>& idx) {
  const int rings = 32, segments = 64;
  for (int i = 0; i <= rings; ++i) {
    double th = kPi * i / rings;
    for (int j = 0; j <= segments; ++j) {
      double ph = 2 * kPi * j / segments;
      Vec3 n(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph));
      nor.push_back(n);
      pos.push_back(o.center + n * o.radius);
    }
  }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      uint32_t a = uint32_t(i * (segments + 1) + j), b = a + 1, c = a + uint32_t(segments + 1), d = c + 1;
      if (i > 0) idx.insert(idx.end(), {a, c, b});
      if (i < rings - 1) idx.insert(idx.end(), {b, c, d});
    }
}

// ---------------------------------------------------------------- import

// tinygltf reads a glTF's external buffers through these; an import from memory
// has no folder, so it reads none (and says which it was asked for).
tinygltf::FsCallbacks no_files() {
  tinygltf::FsCallbacks fs{};
  fs.FileExists = [](const std::string&, void*) { return false; };
  fs.ExpandFilePath = [](const std::string& p, void*) { return p; };
  fs.ReadWholeFile = [](std::vector<unsigned char>*, std::string* err, const std::string& p, void*) {
    if (err) *err += "\"" + p + "\" is an external file, and an import from memory reads none\n";
    return false;
  };
  fs.WriteWholeFile = [](std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; };
  return fs;
}

// A key path of the facet scene JSON import_gltf_data checks ("lights[2].color")
// as the glTF path it came from ("nodes[4].extensions.FACET_light.color").
std::string gltf_path(const std::string& p, const std::string& camera, const std::string& scene_ext,
                      const std::vector<std::string>& objects, const std::vector<std::string>& lights) {
  auto indexed = [&](const char* key, const std::vector<std::string>& paths) -> std::string {
    std::string prefix = std::string(key) + "[";
    if (p.rfind(prefix, 0) != 0) return "";
    size_t close = p.find(']');
    size_t i = std::stoul(p.substr(prefix.size(), close - prefix.size()));
    return i < paths.size() ? paths[i] + p.substr(close + 1) : "";
  };
  if (std::string q = indexed("lights", lights); !q.empty()) return q;
  if (std::string q = indexed("objects", objects); !q.empty()) return q;
  if (p.rfind("camera", 0) == 0 && !camera.empty()) return camera + " (as a facet camera: " + p + ")";
  if (p.rfind("ambient", 0) == 0) return scene_ext + "." + p;
  return p;
}

// Names a missing external buffer by its key, before tinygltf reports it bare.
void check_external_buffers(const std::string& text, const std::string& path) {
  json doc = parse_json(text, path);
  if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return;
  for (size_t i = 0; i < doc["buffers"].size(); ++i) {
    const json& b = doc["buffers"][i];
    if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
    std::string uri = b["uri"];
    if (uri.rfind("data:", 0) == 0) continue;
    fs::path file = fs::path(path).parent_path() / uri;
    if (!fs::exists(file))
      throw InputError({{path, fmt::format("buffers[{}].uri", i),
                         fmt::format("\"{}\" is not there ({}); the buffer must sit beside the glTF", uri,
                                     file.string()),
                         0, 0}});
  }
}

// Loads the glTF's bytes with tinygltf; its warnings become notes.
tinygltf::Model load_model(const std::string& data, bool binary, const std::string& path, const std::string& folder,
                           std::vector<std::string>& notes) {
  tinygltf::TinyGLTF loader;
  loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
  if (folder.empty()) loader.SetFsCallbacks(no_files());
  tinygltf::Model model;
  std::string err, warn;
  if (data.size() > std::numeric_limits<unsigned int>::max())
    throw InputError({{path, "", "is larger than 4 GiB, which glTF cannot address", 0, 0}});
  auto size = static_cast<unsigned int>(data.size());
  bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                 reinterpret_cast<const unsigned char*>(data.data()), size, folder)
                   : loader.LoadASCIIFromString(&model, &err, &warn, data.data(), size, folder);
  if (!warn.empty()) notes.push_back(path + ": tinygltf: " + warn);
  if (!ok) {
    std::string msg = err.empty() ? "tinygltf could not load the file" : err;
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
    throw InputError({{path, "", msg, 0, 0}});
  }
  return model;
}

// One glTF file read into a facet scene, one function per kind of glTF object
// (scene, node, camera, light, mesh, primitive, material), as glTF-Blender-IO's
// importer is laid out. What facet's own scene checker reads (camera, lights,
// analytic objects, ambient) is gathered as facet scene JSON with the glTF path
// of each part, and checked in one go at the end: one checker for every source.
class Importer {
 public:
  Importer(const tinygltf::Model& model, const std::string& path, const GltfImportOptions& options,
           std::vector<std::string>& notes)
      : model_(model), reader_(model, path), path_(path), options_(options), notes_(notes),
        keys_(model.materials.size()), on_path_(model.nodes.size(), false) {}

  Scene read() {
    check_required_extensions();
    int scene_index = default_scene();
    const auto& gscene = model_.scenes[size_t(scene_index)];
    s_.source = path_;
    s_.name = gscene.name.empty() ? fs::path(path_).stem().string() : gscene.name;
    read_scene_extension(gscene, scene_index);
    for (int root : gscene.nodes) read_node(root, Mat4());
    if (s_.objects.empty()) reader_.fail(fmt::format("scenes[{}]", scene_index), "has no meshes");
    check_gathered_parts();
    if (!have_camera_) frame_camera();
    return std::move(s_);
  }

 private:
  void check_required_extensions() const {
    for (size_t i = 0; i < model_.extensionsRequired.size(); ++i) {
      const std::string& e = model_.extensionsRequired[i];
      if (!kSupportedRequired.count(e))
        reader_.fail(fmt::format("extensionsRequired[{}]", i),
                     fmt::format("\"{}\" is required by the file and facet does not support it; supported: "
                                 "KHR_lights_punctual and facet's own FACET_* extensions",
                                 e));
    }
  }

  // The index of the scene to read: the file's default one, else the first.
  int default_scene() const {
    if (model_.scenes.empty()) reader_.fail("scenes", "the file has no scene");
    int scene_index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (size_t(scene_index) >= model_.scenes.size())
      reader_.fail("scene", fmt::format("names no scene ({})", scene_index));
    return scene_index;
  }

  // FACET_scene: the ambient colour.
  void read_scene_extension(const tinygltf::Scene& gscene, int scene_index) {
    json scene_ext = extension(gscene.extensions_json_string, kSceneExt);
    scene_ext_path_ = fmt::format("scenes[{}].extensions.{}", scene_index, kSceneExt);
    if (scene_ext.is_object() && scene_ext.contains("ambient")) checked_["ambient"] = scene_ext["ambient"];
  }

  // Node `ni` under the world transform `parent`: its camera (the first one met
  // is the scene's), its light, its mesh, then its children.
  void read_node(int ni, const Mat4& parent) {
    if (ni < 0 || size_t(ni) >= model_.nodes.size()) reader_.fail("nodes", fmt::format("no node {}", ni));
    std::string npath = fmt::format("nodes[{}]", ni);
    if (on_path_[size_t(ni)]) reader_.fail(npath + ".children", "the node hierarchy has a cycle through this node");
    on_path_[size_t(ni)] = true;
    const auto& node = model_.nodes[size_t(ni)];
    Mat4 world = parent * local_matrix(node);
    if (node.camera >= 0 && !have_camera_) read_camera(node, npath, world);
    read_light(node, npath, world);
    if (node.mesh >= 0) read_mesh(node, npath, world);
    for (int child : node.children) read_node(child, world);
    on_path_[size_t(ni)] = false;
  }

  void read_camera(const tinygltf::Node& node, const std::string& npath, const Mat4& world) {
    if (size_t(node.camera) >= model_.cameras.size()) reader_.fail(npath + ".camera", "names no camera");
    const auto& cam = model_.cameras[size_t(node.camera)];
    camera_path_ = fmt::format("cameras[{}]", node.camera);
    if (cam.type != "perspective") reader_.fail(camera_path_, "is " + cam.type + "; facet cameras are perspective");
    Vec3 position = world.point(Vec3(0, 0, 0));
    Vec3 forward = normalize(world.direction(Vec3(0, 0, -1)));
    checked_["camera"] = {{"position", position.array()},
                          {"look_at", (position + forward).array()},
                          {"up", normalize(world.direction(Vec3(0, 1, 0))).array()},
                          {"fov", cam.perspective.yfov * 180 / kPi}};
    have_camera_ = true;
  }

  // The node's KHR_lights_punctual light: facet's own (FACET_light) where the node
  // carries it, exactly, else the punctual light's nearest facet light.
  void read_light(const tinygltf::Node& node, const std::string& npath, const Mat4& world) {
    json light_ref = extension(node.extensions_json_string, kLightsExt);
    if (!light_ref.is_object() || !light_ref.contains("light")) return;
    std::string ref_path = npath + ".extensions.KHR_lights_punctual.light";
    if (!light_ref["light"].is_number_integer()) reader_.fail(ref_path, "expected the index of a light");
    int64_t li = light_ref["light"].get<int64_t>();
    if (li < 0 || size_t(li) >= model_.lights.size()) reader_.fail(ref_path, "names no light");
    json exact = extension(node.extensions_json_string, kLightExt);
    json lj;
    if (exact.is_object()) {
      lj = exact;
      light_paths_.push_back(npath + ".extensions." + kLightExt);
    } else {
      light_paths_.push_back(fmt::format("extensions.KHR_lights_punctual.lights[{}]", li));
      lj = punctual_light(model_.lights[size_t(li)], li);
    }
    place_light(lj, world);
    lights_.push_back(lj);
  }

  // C = colour · intensity / π, inverse-square; spot cones hard at the outer angle.
  json punctual_light(const tinygltf::Light& gl, int64_t li) {
    auto c = rgb3(gl.color, 1);
    double k = gl.intensity / kPi;
    json lj = {{"type", gl.type}, {"color", {c[0] * k, c[1] * k, c[2] * k}}};
    if (gl.type != "directional") lj["attenuation"] = "inverse_square";
    if (gl.type == "spot") {
      double outer = gl.spot.outerConeAngle * 180 / kPi;
      lj["cutoff"] = std::min(outer, 89.9);
      lj["exponent"] = 0;
      if (gl.spot.innerConeAngle != gl.spot.outerConeAngle)
        notes_.push_back(fmt::format("lights[{}]: approximate: facet's spot cone is hard (cutoff = outerConeAngle)", li));
    }
    if (gl.range > 0) notes_.push_back(fmt::format("lights[{}]: its range is not modelled (inverse square to infinity)", li));
    return lj;
  }

  // The node's origin is a light's position, its −Z the light's direction, where
  // the light's type (as the catalog knows it) has them; an unknown type gets both
  // and the checker names the type.
  static void place_light(json& lj, const Mat4& world) {
    std::optional<LightType> type;
    const ModelDef* def = lj.contains("type") && lj["type"].is_string()
                              ? find_model("light", lj["type"].get<std::string>())
                              : nullptr;
    if (def) type = def->light_type;
    if (type != LightType::Directional) lj["position"] = world.point(Vec3(0, 0, 0)).array();
    if (type != LightType::Point) lj["direction"] = normalize(world.direction(Vec3(0, 0, -1))).array();
  }

  // One object per primitive: facet's own sphere or plane where the node carries
  // FACET_object (exact, world space: checked at the end), else the triangles.
  void read_mesh(const tinygltf::Node& node, const std::string& npath, const Mat4& world) {
    if (size_t(node.mesh) >= model_.meshes.size()) reader_.fail(npath + ".mesh", "names no mesh");
    const auto& mesh = model_.meshes[size_t(node.mesh)];
    json analytic = extension(node.extensions_json_string, kObjectExt);
    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const auto& prim = mesh.primitives[pi];
      std::string ppath = fmt::format("meshes[{}].primitives[{}]", node.mesh, pi);
      Object o;
      o.name = (node.name.empty() ? (mesh.name.empty() ? fmt::format("mesh{}", node.mesh) : mesh.name) : node.name) +
               (mesh.primitives.size() > 1 ? fmt::format("_{}", pi) : "");
      o.material = material_key(prim.material, ppath);
      if (analytic.is_object()) {
        analytic_objects_.push_back(s_.objects.size());
        analytic_json_.push_back(analytic);
        object_paths_.push_back(npath + ".extensions." + kObjectExt);
      } else {
        o.type = Object::Type::Mesh;
        o.mesh = read_primitive(prim, ppath, npath, world);
      }
      s_.objects.push_back(o);
    }
  }

  // A triangle primitive's mesh in world space.
  std::shared_ptr<Mesh> read_primitive(const tinygltf::Primitive& prim, const std::string& ppath,
                                       const std::string& npath, const Mat4& world) const {
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
      reader_.fail(ppath + ".mode", fmt::format("{}; facet takes triangles (mode 4)", prim.mode));
    auto pos_it = prim.attributes.find("POSITION");
    if (pos_it == prim.attributes.end()) reader_.fail(ppath + ".attributes", "has no POSITION");
    std::vector<Vec3> pos = reader_.vec3(pos_it->second, ppath + ".attributes.POSITION");
    std::vector<uint32_t> idx = triangle_indices(prim, ppath, pos.size());
    auto mesh = std::make_shared<Mesh>();
    auto nor_it = prim.attributes.find("NORMAL");
    if (nor_it != prim.attributes.end()) {
      std::vector<Vec3> nor = reader_.vec3(nor_it->second, ppath + ".attributes.NORMAL");
      if (nor.size() != pos.size()) reader_.fail(ppath + ".attributes.NORMAL", "has a different count from POSITION");
      smooth_triangles(*mesh, pos, nor, idx, world);
    } else {
      notes_.push_back(ppath + ": no NORMAL; flat normals computed");
      flat_triangles(*mesh, pos, idx, world);
    }
    if (mesh->triangles.empty()) reader_.fail(ppath, "has no triangles");
    for (size_t i = 0; i < mesh->positions.size(); ++i)
      if (!finite(mesh->positions[i]) || !finite(mesh->normals[i]))
        reader_.fail(npath, "its world transform makes a vertex or a normal of " + ppath +
                                " infinite or undefined (a zero scale, or a huge one)");
    mesh->build_bvh();
    return mesh;
  }

  // The primitive's vertex indices (without an indices accessor: every vertex in
  // order), three per triangle, each of one of the `vertices`.
  std::vector<uint32_t> triangle_indices(const tinygltf::Primitive& prim, const std::string& ppath,
                                         size_t vertices) const {
    std::vector<uint32_t> idx;
    if (prim.indices >= 0) idx = reader_.indices(prim.indices, ppath + ".indices");
    else
      for (uint32_t i = 0; i < vertices; ++i) idx.push_back(i);
    if (idx.size() % 3) reader_.fail(ppath + ".indices", "the count is not a multiple of 3");
    for (uint32_t i : idx)
      if (i >= vertices) reader_.fail(ppath + ".indices", fmt::format("index {} is out of range", i));
    return idx;
  }

  // The vertices with their normals; degenerate triangles are dropped, and a
  // mirroring transform turns the others round so they still face their normals.
  static void smooth_triangles(Mesh& mesh, const std::vector<Vec3>& pos, const std::vector<Vec3>& nor,
                               const std::vector<uint32_t>& idx, const Mat4& world) {
    bool flip = world.det3() < 0;
    for (size_t i = 0; i < pos.size(); ++i) {
      mesh.positions.push_back(world.point(pos[i]));
      mesh.normals.push_back(world.normal(nor[i]));
    }
    for (size_t t = 0; t + 2 < idx.size(); t += 3) {
      if (idx[t] == idx[t + 1] || idx[t + 1] == idx[t + 2] || idx[t] == idx[t + 2]) continue;
      mesh.triangles.push_back(flip ? std::array<uint32_t, 3>{idx[t], idx[t + 2], idx[t + 1]}
                                    : std::array<uint32_t, 3>{idx[t], idx[t + 1], idx[t + 2]});
    }
  }

  // glTF: without normals, flat shading: each triangle its own vertices (and
  // zero-area triangles none).
  static void flat_triangles(Mesh& mesh, const std::vector<Vec3>& pos, const std::vector<uint32_t>& idx,
                             const Mat4& world) {
    bool flip = world.det3() < 0;
    for (size_t t = 0; t + 2 < idx.size(); t += 3) {
      Vec3 a = world.point(pos[idx[t]]), b = world.point(pos[idx[t + 1]]), c = world.point(pos[idx[t + 2]]);
      if (flip) std::swap(b, c);
      Vec3 n = cross(b - a, c - a);
      if (length(n) == 0) continue;
      n = normalize(n);
      uint32_t base = uint32_t(mesh.positions.size());
      mesh.positions.insert(mesh.positions.end(), {a, b, c});
      mesh.normals.insert(mesh.normals.end(), {n, n, n});
      mesh.triangles.push_back({base, base + 1, base + 2});
    }
  }

  // The key in s_.materials of glTF material `index` (read once, on first use),
  // or of the default material for a primitive without one.
  std::string material_key(int index, const std::string& where) {
    if (index < 0) {
      if (!options_.default_material)
        reader_.fail(where + ".material",
                     "missing: the primitive has no material (glTF's default is white metal); give facet one "
                     "with --default-material MATERIAL.json");
      s_.materials["default"] = *options_.default_material;
      return "default";
    }
    if (size_t(index) >= model_.materials.size()) reader_.fail(where + ".material", "names no material");
    std::string& key = keys_[size_t(index)];
    if (!key.empty()) return key;
    const auto& g = model_.materials[size_t(index)];
    std::string mpath = fmt::format("materials[{}]", index);
    key = identifier(g.name.empty() ? fmt::format("material{}", index) : g.name);
    while (used_keys_.count(key)) key += "_";
    used_keys_.insert(key);
    s_.materials[key] = read_material(g, mpath);
    return key;
  }

  // facet's own material (FACET_material) exactly, else the metallic–roughness one.
  Material read_material(const tinygltf::Material& g, const std::string& mpath) {
    json ext = extension(g.extensions_json_string, kMaterialExt);
    try {
      if (ext.is_object() && ext.contains("material")) return parse_material(ext["material"], path_);
      return parse_material(pbr_material(g, mpath, notes_), path_);
    } catch (const InputError& e) {
      std::vector<Diagnostic> ds = e.diagnostics();
      for (auto& d : ds)
        d.path = mpath + ".extensions." + kMaterialExt + ".material" + (d.path.empty() ? "" : "." + d.path);
      throw InputError(ds);
    }
  }

  // The gathered parts through the scene checker; its diagnostics name the glTF's
  // paths. Then the analytic objects, lights, ambient and camera it read.
  void check_gathered_parts() {
    if (!have_camera_) checked_["camera"] = {{"position", {0, 0, 1}}};  // framed after
    checked_["objects"] = analytic_json_.empty()
                              ? json::array({{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}}})
                              : analytic_json_;
    checked_["lights"] = lights_;
    Scene parts;
    try {
      parts = parse_scene(checked_, path_);
    } catch (const InputError& e) {
      std::vector<Diagnostic> ds = e.diagnostics();
      for (auto& d : ds) d.path = gltf_path(d.path, camera_path_, scene_ext_path_, object_paths_, light_paths_);
      throw InputError(ds);
    }
    for (size_t i = 0; i < analytic_objects_.size(); ++i) {
      Object& o = s_.objects[analytic_objects_[i]];
      const Object& a = parts.objects[i];
      o.type = a.type;
      o.center = a.center;
      o.radius = a.radius;
      o.point = a.point;
      o.normal = a.normal;
      o.size = a.size;
    }
    s_.lights = parts.lights;
    s_.ambient = parts.ambient;
    if (have_camera_) s_.camera = parts.camera;
  }

  // No camera: frame the scene's bounding sphere from the front, a little above.
  void frame_camera() {
    Vec3 lo(INFINITY, INFINITY, INFINITY), hi(-INFINITY, -INFINITY, -INFINITY);
    for (const auto& o : s_.objects) {
      Vec3 c;
      double r;
      o.bounds(c, r);
      lo = Vec3(std::min(lo.x, c.x - r), std::min(lo.y, c.y - r), std::min(lo.z, c.z - r));
      hi = Vec3(std::max(hi.x, c.x + r), std::max(hi.y, c.y + r), std::max(hi.z, c.z + r));
    }
    Vec3 c = (lo + hi) * 0.5;
    double r = length(hi - lo) * 0.5;
    s_.camera.look_at = c;
    s_.camera.position = c + normalize(Vec3(0, 0.35, 1)) * (r / std::tan(20 * kPi / 180) * 1.1);
    s_.camera.up = Vec3(0, 1, 0);
    s_.camera.fov = 40;
    notes_.push_back(path_ + ": no camera; facet framed the scene from the front (fov 40°)");
  }

  const tinygltf::Model& model_;
  Reader reader_;
  std::string path_;
  const GltfImportOptions& options_;
  std::vector<std::string>& notes_;
  Scene s_;
  json checked_ = json::object();  // the parts facet's scene checker reads, as facet scene JSON
  json lights_ = json::array();    // met while visiting nodes
  json analytic_json_ = json::array();
  std::vector<std::string> light_paths_, object_paths_;  // the glTF path of each
  std::vector<size_t> analytic_objects_;                 // indices into s_.objects
  std::string camera_path_, scene_ext_path_;
  bool have_camera_ = false;
  std::vector<std::string> keys_;  // materials by index; only those the primitives use are read
  std::set<std::string> used_keys_;
  std::vector<bool> on_path_;  // the nodes being visited: a cycle is an error
};

// ---------------------------------------------------------------- export

// A node's matrix (column-major) whose axes are the columns x, y, z and whose origin is `origin`.
std::vector<double> frame_matrix(const Vec3& x, const Vec3& y, const Vec3& z, const Vec3& origin) {
  Vec3 cols[3] = {x, y, z};
  std::vector<double> m(16, 0);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[size_t(c * 4 + r)] = cols[c][r];
  for (int r = 0; r < 3; ++r) m[size_t(12 + r)] = origin[r];
  m[15] = 1;
  return m;
}

// A square plane's two triangles, wound to face its normal.
void plane_mesh(const Object& o, std::vector<Vec3>& pos, std::vector<Vec3>& nor, std::vector<uint32_t>& idx) {
  Vec3 u, v;
  o.plane_axes(u, v);
  pos = {o.point + (u + v) * o.size, o.point + (v - u) * o.size, o.point - (u + v) * o.size,
         o.point + (u - v) * o.size};
  nor = {o.normal, o.normal, o.normal, o.normal};
  idx = {0, 1, 2, 0, 2, 3};
  if (dot(cross(pos[1] - pos[0], pos[2] - pos[0]), o.normal) < 0) idx = {0, 2, 1, 0, 3, 2};
}

// A facet scene written as one glTF model: materials, one mesh node per object,
// the camera, the lights, each in its own function; then the file.
class Exporter {
 public:
  Exporter(const Scene& s, const Material* fallback, std::vector<std::string>& notes)
      : s_(s), fallback_(fallback), notes_(notes) {
    model_.asset.version = "2.0";
    model_.asset.generator = "facet " FACET_VERSION;
    model_.buffers.emplace_back();
  }

  void add_scene() {
    for (const auto& [key, m] : s_.materials) add_material(key, m);
    gscene_.name = s_.name;
    if (s_.ambient[0] + s_.ambient[1] + s_.ambient[2] > 0) {
      gscene_.extensions[kSceneExt] = value_of({{"ambient", s_.ambient}});
      used_.insert(kSceneExt);
    }
    for (size_t i = 0; i < s_.objects.size(); ++i) add_object(i);
    add_camera();
    for (size_t i = 0; i < s_.lights.size(); ++i) add_light(i);
    model_.scenes.push_back(gscene_);
    model_.defaultScene = 0;
    model_.extensionsUsed.assign(used_.begin(), used_.end());
  }

  // As .gltf (one self-contained file: the buffer as a data URI) or .glb.
  void write(const std::string& path) {
    bool binary = fs::path(path).extension() == ".glb";
    std::vector<unsigned char>& bin = model_.buffers[0].data;
    if (!binary) {
      model_.buffers[0].uri = "data:application/octet-stream;base64," +
                              tinygltf::base64_encode(bin.data(), static_cast<unsigned int>(bin.size()));
    }
    tinygltf::TinyGLTF writer;
    std::ostringstream out;
    if (!writer.WriteGltfSceneToStream(&model_, out, /*prettyPrint=*/!binary, binary))
      throw IoError(path + ": tinygltf could not write the glTF");
    write_file_atomic(path, out.str());
  }

 private:
  // A buffer view + accessor over `bytes`, 4-byte aligned.
  int add_accessor(const void* bytes, size_t size, size_t count, int type, int component, int target,
                   const std::vector<double>& lo = {}, const std::vector<double>& hi = {}) {
    std::vector<unsigned char>& bin = model_.buffers[0].data;
    while (bin.size() % 4) bin.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = bin.size();
    v.byteLength = size;
    v.target = target;
    bin.insert(bin.end(), static_cast<const unsigned char*>(bytes), static_cast<const unsigned char*>(bytes) + size);
    model_.bufferViews.push_back(v);
    tinygltf::Accessor a;
    a.bufferView = int(model_.bufferViews.size() - 1);
    a.count = count;
    a.type = type;
    a.componentType = component;
    a.minValues = lo;
    a.maxValues = hi;
    model_.accessors.push_back(a);
    return int(model_.accessors.size() - 1);
  }

  // The full facet description (FACET_material) beside the metallic–roughness fallback.
  void add_material(const std::string& key, const Material& m) {
    tinygltf::Material g;
    g.name = key;
    fallback_pbr(m, g);
    g.extensions[kMaterialExt] = value_of({{"material", to_json(m)}});
    model_.materials.push_back(g);
    material_index_[key] = int(model_.materials.size() - 1);
  }

  // Object i's material: its own, else the fallback (added on first use).
  int material_of(size_t i) {
    std::string key = s_.objects[i].material;
    if (key.empty()) {
      if (!fallback_)
        throw InputError({{s_.source, fmt::format("objects[{}].material", i), "missing, and no --material given", 0, 0}});
      key = "facet_" + identifier(fallback_->name);
      if (!material_index_.count(key)) add_material(key, *fallback_);
    }
    return material_index_.at(key);
  }

  // Object i as a mesh node; spheres and planes keep their exact definition in FACET_object.
  void add_object(size_t i) {
    const Object& o = s_.objects[i];
    int material = material_of(i);
    std::vector<Vec3> pos, nor;
    std::vector<uint32_t> idx;
    tinygltf::Node node;
    node.name = o.name;
    switch (o.type) {
      case Object::Type::Mesh:
        pos = o.mesh->positions;
        nor = o.mesh->normals;
        for (const auto& t : o.mesh->triangles) idx.insert(idx.end(), t.begin(), t.end());
        break;
      case Object::Type::Sphere:
        sphere_mesh(o, pos, nor, idx);
        node.extensions[kObjectExt] =
            value_of({{"type", "sphere"}, {"center", o.center.array()}, {"radius", o.radius}});
        used_.insert(kObjectExt);
        break;
      case Object::Type::Plane:
        plane_mesh(o, pos, nor, idx);
        node.extensions[kObjectExt] = value_of(
            {{"type", "plane"}, {"point", o.point.array()}, {"normal", o.normal.array()}, {"size", o.size}});
        used_.insert(kObjectExt);
        break;
    }
    node.mesh = add_mesh(o.name, material, pos, nor, idx);
    add_node(node);
  }

  // A one-primitive triangle mesh of float32 positions and normals.
  int add_mesh(const std::string& name, int material, const std::vector<Vec3>& pos, const std::vector<Vec3>& nor,
               const std::vector<uint32_t>& idx) {
    std::vector<float> fp, fn;
    std::vector<double> lo(3, INFINITY), hi(3, -INFINITY);
    for (const auto& p : pos)
      for (int k = 0; k < 3; ++k) {
        float f = float(p[k]);
        fp.push_back(f);
        lo[size_t(k)] = std::min<double>(lo[size_t(k)], f);
        hi[size_t(k)] = std::max<double>(hi[size_t(k)], f);
      }
    for (const auto& n : nor)
      for (int k = 0; k < 3; ++k) fn.push_back(float(n[k]));
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = material;
    prim.attributes["POSITION"] = add_accessor(fp.data(), fp.size() * 4, pos.size(), TINYGLTF_TYPE_VEC3,
                                               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER, lo, hi);
    prim.attributes["NORMAL"] = add_accessor(fn.data(), fn.size() * 4, nor.size(), TINYGLTF_TYPE_VEC3,
                                             TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.indices = add_accessor(idx.data(), idx.size() * 4, idx.size(), TINYGLTF_TYPE_SCALAR,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(prim);
    model_.meshes.push_back(mesh);
    return int(model_.meshes.size() - 1);
  }

  void add_node(const tinygltf::Node& node) {
    model_.nodes.push_back(node);
    gscene_.nodes.push_back(int(model_.nodes.size() - 1));
  }

  // The camera: a node whose −Z looks at look_at and whose +Y is up.
  void add_camera() {
    tinygltf::Camera cam;
    cam.type = "perspective";
    cam.perspective.yfov = s_.camera.fov * kPi / 180;
    cam.perspective.znear = 0.01;
    cam.perspective.zfar = far_plane();
    model_.cameras.push_back(cam);
    Camera::Basis b = s_.camera.basis();
    tinygltf::Node node;
    node.name = "camera";
    node.camera = 0;
    node.matrix = frame_matrix(b.right, b.up, -b.forward, s_.camera.position);
    add_node(node);
  }

  // facet's camera has no far plane. glTF's way to say so is to leave zfar out,
  // which tinygltf cannot (it writes 0, an invalid value that makes Blender clip
  // everything), so the far plane goes far beyond the scene instead.
  double far_plane() const {
    double extent = 1;
    for (const auto& o : s_.objects) {
      Vec3 c;
      double r = 0;
      o.bounds(c, r);
      extent = std::max(extent, length(c - s_.camera.position) + r);
    }
    return 1000 * extent;
  }

  // Light i: KHR_lights_punctual (intensity = π · C, the inverse of the import)
  // beside facet's own definition (FACET_light).
  void add_light(size_t i) {
    const Light& l = s_.lights[i];
    model_.lights.push_back(punctual_light(l, i));
    json own = to_json(s_)["lights"][i];
    own.erase("position");
    own.erase("direction");
    tinygltf::Node node;
    node.name = fmt::format("light{}", i);
    node.extensions[kLightsExt] = value_of({{"light", int(i)}});
    node.extensions[kLightExt] = value_of(own);
    // Position by translation; direction: rotate −Z onto it.
    Vec3 d = l.type == Light::Type::Point ? Vec3(0, 0, -1) : l.direction;
    Vec3 z = -d, x = cross(Vec3(0, 1, 0), z);
    if (length(x) < 1e-6) x = cross(Vec3(1, 0, 0), z);
    x = normalize(x);
    Vec3 y = cross(z, x);
    node.matrix = frame_matrix(x, y, z, l.type == Light::Type::Directional ? Vec3(0, 0, 0) : l.position);
    add_node(node);
    used_.insert(kLightsExt);
    used_.insert(kLightExt);
  }

  tinygltf::Light punctual_light(const Light& l, size_t i) {
    tinygltf::Light gl;
    double k = std::max({l.color[0], l.color[1], l.color[2], 1e-12});
    gl.color = {l.color[0] / k, l.color[1] / k, l.color[2] / k};
    gl.intensity = k * kPi;
    gl.type = l.type == Light::Type::Point ? "point" : l.type == Light::Type::Spot ? "spot" : "directional";
    if (l.type == Light::Type::Spot) gl.spot.innerConeAngle = gl.spot.outerConeAngle = l.cutoff * kPi / 180;
    if (l.type != Light::Type::Directional && l.attenuation.law != Attenuation::Law::InverseSquare)
      notes_.push_back(
          fmt::format("lights[{}]: glTF lights fall off with 1/d²; facet's own attenuation travels in {}", i, kLightExt));
    return gl;
  }

  const Scene& s_;
  const Material* fallback_;
  std::vector<std::string>& notes_;
  tinygltf::Model model_;
  tinygltf::Scene gscene_;
  std::set<std::string> used_ = {kMaterialExt};
  std::map<std::string, int> material_index_;  // materials by key
};

}  // namespace

Scene import_gltf(const std::string& path, const GltfImportOptions& options, std::vector<std::string>& notes) {
  if (!fs::exists(path)) throw InputError({{path, "", "no such file", 0, 0}});
  bool binary = fs::path(path).extension() == ".glb";
  std::string data = read_file(path);
  if (!binary) check_external_buffers(data, path);
  std::string folder = fs::path(path).parent_path().string();
  return import_gltf_data(data, binary, path, folder.empty() ? "." : folder, options, notes);
}

Scene import_gltf_data(const std::string& data, bool binary, const std::string& path, const std::string& folder,
                       const GltfImportOptions& options, std::vector<std::string>& notes) {
  tinygltf::Model model = load_model(data, binary, path, folder, notes);
  return Importer(model, path, options, notes).read();
}

void export_gltf(const Scene& s, const Material* fallback, const std::string& path, std::vector<std::string>& notes) {
  Exporter exporter(s, fallback, notes);
  exporter.add_scene();
  exporter.write(path);
}

}  // namespace facet
