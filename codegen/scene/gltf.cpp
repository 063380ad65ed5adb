#include "scene/gltf.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <set>
#include <sstream>

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

// An equivalent GGX roughness (√α) for the nearest metallic–roughness fallback.
double equivalent_alpha(const ModelSpec& s) {
  const std::string& n = s.def->name;
  auto num = [&](const char* k) { return s.at(k).number; };
  if (n == "ggx") return num("alpha");
  if (n == "beckmann" || n == "cook_torrance") return num("m");
  if (n == "blinn") return num("c");
  if (n == "ward" || n == "ward_nvidia") return std::sqrt(num("alpha_x") * num("alpha_y"));
  if (n == "blinn_phong") return std::sqrt(2 / (num("n") + 2));
  if (n == "phong" || n == "heidrich_seidel") return std::sqrt(2 / (4 * num("n") + 2));  // Phong n ≈ Blinn–Phong 4n
  if (n == "gaussian") return 1 / std::sqrt(num("m"));
  return 1;
}

void fallback_pbr(const Material& m, tinygltf::Material& g) {
  RGB base{0, 0, 0};
  double metal = 0, alpha = 1;
  if (m.diffuse) base = m.diffuse->at("color").rgb;
  if (m.specular) {
    alpha = equivalent_alpha(*m.specular);
    auto f = m.specular->values.find("fresnel");
    if (!m.diffuse && f != m.specular->values.end() && f->second.model && f->second.model->def->name == "schlick") {
      base = f->second.model->at("f0").rgb;  // a conductor: its f0 is the base colour
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
  Reader reader(model, path);
  for (size_t i = 0; i < model.extensionsRequired.size(); ++i) {
    const std::string& e = model.extensionsRequired[i];
    if (!kSupportedRequired.count(e))
      reader.fail(fmt::format("extensionsRequired[{}]", i),
                  fmt::format("\"{}\" is required by the file and facet does not support it; supported: "
                              "KHR_lights_punctual and facet's own FACET_* extensions",
                              e));
  }
  if (model.scenes.empty()) reader.fail("scenes", "the file has no scene");
  int scene_index = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (size_t(scene_index) >= model.scenes.size()) reader.fail("scene", fmt::format("names no scene ({})", scene_index));
  const auto& gscene = model.scenes[size_t(scene_index)];

  Scene s;
  s.source = path;
  s.name = gscene.name.empty() ? fs::path(path).stem().string() : gscene.name;
  // What facet's own scene checker reads (camera, lights, analytic objects,
  // ambient), gathered as facet scene JSON with the glTF path of each part, and
  // checked in one go at the end: one checker for every source.
  json checked = json::object();
  std::vector<std::string> light_paths, object_paths;
  std::vector<size_t> analytic_objects;  // indices into s.objects
  json scene_ext = extension(gscene.extensions_json_string, kSceneExt);
  std::string scene_ext_path = fmt::format("scenes[{}].extensions.{}", scene_index, kSceneExt);
  if (scene_ext.is_object() && scene_ext.contains("ambient")) checked["ambient"] = scene_ext["ambient"];

  // Materials, by key; only those the primitives use are kept.
  std::vector<std::string> keys(model.materials.size());
  std::set<std::string> used_keys;
  auto material_key = [&](int index, const std::string& where) -> std::string {
    if (index < 0) {
      if (!options.default_material)
        reader.fail(where + ".material",
                    "missing: the primitive has no material (glTF's default is white metal); give facet one "
                    "with --default-material MATERIAL.json");
      s.materials["default"] = *options.default_material;
      return "default";
    }
    if (size_t(index) >= model.materials.size()) reader.fail(where + ".material", "names no material");
    std::string& key = keys[size_t(index)];
    if (!key.empty()) return key;
    const auto& g = model.materials[size_t(index)];
    std::string mpath = fmt::format("materials[{}]", index);
    key = identifier(g.name.empty() ? fmt::format("material{}", index) : g.name);
    while (used_keys.count(key)) key += "_";
    used_keys.insert(key);
    json ext = extension(g.extensions_json_string, kMaterialExt);
    try {
      if (ext.is_object() && ext.contains("material")) {
        s.materials[key] = parse_material(ext["material"], path);
      } else {
        s.materials[key] = parse_material(pbr_material(g, mpath, notes), path);
      }
    } catch (const InputError& e) {
      std::vector<Diagnostic> ds = e.diagnostics();
      for (auto& d : ds) d.path = mpath + ".extensions." + kMaterialExt + ".material" + (d.path.empty() ? "" : "." + d.path);
      throw InputError(ds);
    }
    return key;
  };

  bool have_camera = false;
  std::string camera_path;
  json lights = json::array();  // met while visiting nodes, as facet scene JSON
  json analytic_json = json::array();
  std::vector<bool> on_path(model.nodes.size(), false);  // the nodes being visited: a cycle is an error
  std::function<void(int, const Mat4&)> visit = [&](int ni, const Mat4& parent) {
    if (ni < 0 || size_t(ni) >= model.nodes.size()) reader.fail("nodes", fmt::format("no node {}", ni));
    std::string npath = fmt::format("nodes[{}]", ni);
    if (on_path[size_t(ni)]) reader.fail(npath + ".children", "the node hierarchy has a cycle through this node");
    on_path[size_t(ni)] = true;
    const auto& node = model.nodes[size_t(ni)];
    Mat4 world = parent * local_matrix(node);

    if (node.camera >= 0 && !have_camera) {
      if (size_t(node.camera) >= model.cameras.size()) reader.fail(npath + ".camera", "names no camera");
      const auto& cam = model.cameras[size_t(node.camera)];
      camera_path = fmt::format("cameras[{}]", node.camera);
      if (cam.type != "perspective") reader.fail(camera_path, "is " + cam.type + "; facet cameras are perspective");
      Vec3 position = world.point(Vec3(0, 0, 0));
      Vec3 forward = normalize(world.direction(Vec3(0, 0, -1)));
      checked["camera"] = {{"position", position.array()},
                           {"look_at", (position + forward).array()},
                           {"up", normalize(world.direction(Vec3(0, 1, 0))).array()},
                           {"fov", cam.perspective.yfov * 180 / kPi}};
      have_camera = true;
    }
    json light_ref = extension(node.extensions_json_string, kLightsExt);
    if (light_ref.is_object() && light_ref.contains("light")) {
      std::string ref_path = npath + ".extensions.KHR_lights_punctual.light";
      if (!light_ref["light"].is_number_integer()) reader.fail(ref_path, "expected the index of a light");
      int64_t li = light_ref["light"].get<int64_t>();
      if (li < 0 || size_t(li) >= model.lights.size()) reader.fail(ref_path, "names no light");
      const auto& gl = model.lights[size_t(li)];
      json exact = extension(node.extensions_json_string, kLightExt);
      json lj;
      if (exact.is_object()) {
        lj = exact;  // facet's own light, exact
        light_paths.push_back(npath + ".extensions." + kLightExt);
      } else {
        light_paths.push_back(fmt::format("extensions.KHR_lights_punctual.lights[{}]", li));
        auto c = rgb3(gl.color, 1);
        double k = gl.intensity / kPi;
        lj = {{"type", gl.type}, {"color", {c[0] * k, c[1] * k, c[2] * k}}};
        if (gl.type != "directional") lj["attenuation"] = "inverse_square";
        if (gl.type == "spot") {
          double outer = gl.spot.outerConeAngle * 180 / kPi;
          lj["cutoff"] = std::min(outer, 89.9);
          lj["exponent"] = 0;
          if (gl.spot.innerConeAngle != gl.spot.outerConeAngle)
            notes.push_back(fmt::format("lights[{}]: approximate: facet's spot cone is hard (cutoff = outerConeAngle)", li));
        }
        if (gl.range > 0) notes.push_back(fmt::format("lights[{}]: its range is not modelled (inverse square to infinity)", li));
      }
      if (lj.value("type", "") != "directional") lj["position"] = world.point(Vec3(0, 0, 0)).array();
      if (lj.value("type", "") != "point") lj["direction"] = normalize(world.direction(Vec3(0, 0, -1))).array();
      lights.push_back(lj);
    }
    if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model.meshes.size()) reader.fail(npath + ".mesh", "names no mesh");
      const auto& mesh = model.meshes[size_t(node.mesh)];
      json analytic = extension(node.extensions_json_string, kObjectExt);
      for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
        const auto& prim = mesh.primitives[pi];
        std::string ppath = fmt::format("meshes[{}].primitives[{}]", node.mesh, pi);
        Object o;
        o.name = (node.name.empty() ? (mesh.name.empty() ? fmt::format("mesh{}", node.mesh) : mesh.name) : node.name) +
                 (mesh.primitives.size() > 1 ? fmt::format("_{}", pi) : "");
        o.material = material_key(prim.material, ppath);
        if (analytic.is_object()) {  // facet's own sphere or plane, exact (world space): checked at the end
          analytic_objects.push_back(s.objects.size());
          analytic_json.push_back(analytic);
          object_paths.push_back(npath + ".extensions." + kObjectExt);
          s.objects.push_back(o);
          continue;
        }
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
          reader.fail(ppath + ".mode", fmt::format("{}; facet takes triangles (mode 4)", prim.mode));
        auto pos_it = prim.attributes.find("POSITION");
        if (pos_it == prim.attributes.end()) reader.fail(ppath + ".attributes", "has no POSITION");
        std::vector<Vec3> pos = reader.vec3(pos_it->second, ppath + ".attributes.POSITION");
        std::vector<uint32_t> idx;
        if (prim.indices >= 0) idx = reader.indices(prim.indices, ppath + ".indices");
        else
          for (uint32_t i = 0; i < pos.size(); ++i) idx.push_back(i);
        if (idx.size() % 3) reader.fail(ppath + ".indices", "the count is not a multiple of 3");
        for (uint32_t i : idx)
          if (i >= pos.size()) reader.fail(ppath + ".indices", fmt::format("index {} is out of range", i));
        auto mesh_out = std::make_shared<Mesh>();
        bool flip = world.det3() < 0;
        auto nor_it = prim.attributes.find("NORMAL");
        if (nor_it != prim.attributes.end()) {
          std::vector<Vec3> nor = reader.vec3(nor_it->second, ppath + ".attributes.NORMAL");
          if (nor.size() != pos.size()) reader.fail(ppath + ".attributes.NORMAL", "has a different count from POSITION");
          for (size_t i = 0; i < pos.size(); ++i) {
            mesh_out->positions.push_back(world.point(pos[i]));
            mesh_out->normals.push_back(world.normal(nor[i]));
          }
          for (size_t t = 0; t + 2 < idx.size(); t += 3) {
            if (idx[t] == idx[t + 1] || idx[t + 1] == idx[t + 2] || idx[t] == idx[t + 2]) continue;
            mesh_out->triangles.push_back(flip ? std::array<uint32_t, 3>{idx[t], idx[t + 2], idx[t + 1]}
                                               : std::array<uint32_t, 3>{idx[t], idx[t + 1], idx[t + 2]});
          }
        } else {
          // glTF: without normals, flat shading: each triangle its own vertices.
          notes.push_back(ppath + ": no NORMAL; flat normals computed");
          for (size_t t = 0; t + 2 < idx.size(); t += 3) {
            Vec3 a = world.point(pos[idx[t]]), b = world.point(pos[idx[t + 1]]), c = world.point(pos[idx[t + 2]]);
            if (flip) std::swap(b, c);
            Vec3 n = cross(b - a, c - a);
            if (length(n) == 0) continue;
            n = normalize(n);
            uint32_t base = uint32_t(mesh_out->positions.size());
            mesh_out->positions.insert(mesh_out->positions.end(), {a, b, c});
            mesh_out->normals.insert(mesh_out->normals.end(), {n, n, n});
            mesh_out->triangles.push_back({base, base + 1, base + 2});
          }
        }
        if (mesh_out->triangles.empty()) reader.fail(ppath, "has no triangles");
        for (size_t i = 0; i < mesh_out->positions.size(); ++i)
          if (!finite(mesh_out->positions[i]) || !finite(mesh_out->normals[i]))
            reader.fail(npath, "its world transform makes a vertex or a normal of " + ppath +
                                   " infinite or undefined (a zero scale, or a huge one)");
        mesh_out->build_bvh();
        o.type = Object::Type::Mesh;
        o.mesh = mesh_out;
        s.objects.push_back(o);
      }
    }
    for (int child : node.children) visit(child, world);
    on_path[size_t(ni)] = false;
  };
  for (int root : gscene.nodes) visit(root, Mat4());
  if (s.objects.empty()) reader.fail(fmt::format("scenes[{}]", scene_index), "has no meshes");

  // The gathered parts through the scene checker; its diagnostics name the glTF's paths.
  if (!have_camera) checked["camera"] = {{"position", {0, 0, 1}}};  // framed below
  checked["objects"] = analytic_json.empty() ? json::array({{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}}})
                                             : analytic_json;
  checked["lights"] = lights;
  Scene parts;
  try {
    parts = parse_scene(checked, path);
  } catch (const InputError& e) {
    std::vector<Diagnostic> ds = e.diagnostics();
    for (auto& d : ds) d.path = gltf_path(d.path, camera_path, scene_ext_path, object_paths, light_paths);
    throw InputError(ds);
  }
  for (size_t i = 0; i < analytic_objects.size(); ++i) {
    Object& o = s.objects[analytic_objects[i]];
    const Object& a = parts.objects[i];
    o.type = a.type;
    o.center = a.center;
    o.radius = a.radius;
    o.point = a.point;
    o.normal = a.normal;
    o.size = a.size;
  }
  s.lights = parts.lights;
  s.ambient = parts.ambient;
  if (have_camera) s.camera = parts.camera;

  if (!have_camera) {
    // Frame the scene's bounding sphere from the front, a little above.
    Vec3 lo(INFINITY, INFINITY, INFINITY), hi(-INFINITY, -INFINITY, -INFINITY);
    for (const auto& o : s.objects) {
      Vec3 c;
      double r;
      o.bounds(c, r);
      lo = Vec3(std::min(lo.x, c.x - r), std::min(lo.y, c.y - r), std::min(lo.z, c.z - r));
      hi = Vec3(std::max(hi.x, c.x + r), std::max(hi.y, c.y + r), std::max(hi.z, c.z + r));
    }
    Vec3 c = (lo + hi) * 0.5;
    double r = length(hi - lo) * 0.5;
    s.camera.look_at = c;
    s.camera.position = c + normalize(Vec3(0, 0.35, 1)) * (r / std::tan(20 * kPi / 180) * 1.1);
    s.camera.up = Vec3(0, 1, 0);
    s.camera.fov = 40;
    notes.push_back(path + ": no camera; facet framed the scene from the front (fov 40°)");
  }
  return s;
}

// ---------------------------------------------------------------- export

void export_gltf(const Scene& s, const Material* fallback, const std::string& path, std::vector<std::string>& notes) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "facet " FACET_VERSION;
  model.buffers.emplace_back();
  std::vector<unsigned char>& bin = model.buffers[0].data;
  std::set<std::string> used = {kMaterialExt};

  // A buffer view + accessor over `bytes`, 4-byte aligned.
  auto add_accessor = [&](const void* bytes, size_t size, size_t count, int type, int component, int target,
                          const std::vector<double>& lo = {}, const std::vector<double>& hi = {}) {
    while (bin.size() % 4) bin.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = bin.size();
    v.byteLength = size;
    v.target = target;
    bin.insert(bin.end(), static_cast<const unsigned char*>(bytes), static_cast<const unsigned char*>(bytes) + size);
    model.bufferViews.push_back(v);
    tinygltf::Accessor a;
    a.bufferView = int(model.bufferViews.size() - 1);
    a.count = count;
    a.type = type;
    a.componentType = component;
    a.minValues = lo;
    a.maxValues = hi;
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
  };

  // Materials: the scene's, and the fallback for objects without one.
  std::map<std::string, int> material_index;
  auto add_material = [&](const std::string& key, const Material& m) {
    tinygltf::Material g;
    g.name = key;
    fallback_pbr(m, g);
    g.extensions[kMaterialExt] = value_of({{"material", to_json(m)}});
    model.materials.push_back(g);
    material_index[key] = int(model.materials.size() - 1);
  };
  for (const auto& [key, m] : s.materials) add_material(key, m);

  tinygltf::Scene gscene;
  gscene.name = s.name;
  if (s.ambient[0] + s.ambient[1] + s.ambient[2] > 0) {
    gscene.extensions[kSceneExt] = value_of({{"ambient", s.ambient}});
    used.insert(kSceneExt);
  }
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    std::string key = o.material;
    if (key.empty()) {
      if (!fallback) throw InputError({{s.source, fmt::format("objects[{}].material", i), "missing, and no --material given", 0, 0}});
      key = "facet_" + identifier(fallback->name);
      if (!material_index.count(key)) add_material(key, *fallback);
    }
    std::vector<Vec3> pos, nor;
    std::vector<uint32_t> idx;
    tinygltf::Node node;
    node.name = o.name;
    if (o.type == Object::Type::Mesh) {
      pos = o.mesh->positions;
      nor = o.mesh->normals;
      for (const auto& t : o.mesh->triangles) idx.insert(idx.end(), t.begin(), t.end());
    } else if (o.type == Object::Type::Sphere) {
      sphere_mesh(o, pos, nor, idx);
      node.extensions[kObjectExt] =
          value_of({{"type", "sphere"}, {"center", o.center.array()}, {"radius", o.radius}});
      used.insert(kObjectExt);
    } else {
      Vec3 u, v;
      o.plane_axes(u, v);
      pos = {o.point + (u + v) * o.size, o.point + (v - u) * o.size, o.point - (u + v) * o.size,
             o.point + (u - v) * o.size};
      nor = {o.normal, o.normal, o.normal, o.normal};
      idx = {0, 1, 2, 0, 2, 3};
      if (dot(cross(pos[1] - pos[0], pos[2] - pos[0]), o.normal) < 0) idx = {0, 2, 1, 0, 3, 2};
      node.extensions[kObjectExt] = value_of(
          {{"type", "plane"}, {"point", o.point.array()}, {"normal", o.normal.array()}, {"size", o.size}});
      used.insert(kObjectExt);
    }
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
    prim.material = material_index.at(key);
    prim.attributes["POSITION"] = add_accessor(fp.data(), fp.size() * 4, pos.size(), TINYGLTF_TYPE_VEC3,
                                               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER, lo, hi);
    prim.attributes["NORMAL"] = add_accessor(fn.data(), fn.size() * 4, nor.size(), TINYGLTF_TYPE_VEC3,
                                             TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.indices = add_accessor(idx.data(), idx.size() * 4, idx.size(), TINYGLTF_TYPE_SCALAR,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    tinygltf::Mesh mesh;
    mesh.name = o.name;
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
    node.mesh = int(model.meshes.size() - 1);
    model.nodes.push_back(node);
    gscene.nodes.push_back(int(model.nodes.size() - 1));
  }

  // The camera: a node whose −Z looks at look_at and whose +Y is up.
  {
    tinygltf::Camera cam;
    cam.type = "perspective";
    cam.perspective.yfov = s.camera.fov * kPi / 180;
    cam.perspective.znear = 0.01;
    // facet's camera has no far plane. glTF's way to say so is to leave zfar out,
    // which tinygltf cannot (it writes 0, an invalid value that makes Blender clip
    // everything), so the far plane goes far beyond the scene instead.
    double extent = 1;
    for (const auto& o : s.objects) {
      Vec3 c;
      double r = 0;
      o.bounds(c, r);
      extent = std::max(extent, length(c - s.camera.position) + r);
    }
    cam.perspective.zfar = 1000 * extent;
    model.cameras.push_back(cam);
    Camera::Basis b = s.camera.basis();
    tinygltf::Node node;
    node.name = "camera";
    node.camera = 0;
    Vec3 cols[3] = {b.right, b.up, -b.forward};
    node.matrix.assign(16, 0);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) node.matrix[size_t(c * 4 + r)] = cols[c][r];
    for (int r = 0; r < 3; ++r) node.matrix[size_t(12 + r)] = s.camera.position[r];
    node.matrix[15] = 1;
    model.nodes.push_back(node);
    gscene.nodes.push_back(int(model.nodes.size() - 1));
  }

  // Lights: KHR_lights_punctual (intensity = π · C, the inverse of the import)
  // beside facet's own definition.
  for (size_t i = 0; i < s.lights.size(); ++i) {
    const Light& l = s.lights[i];
    tinygltf::Light gl;
    double k = std::max({l.color[0], l.color[1], l.color[2], 1e-12});
    gl.color = {l.color[0] / k, l.color[1] / k, l.color[2] / k};
    gl.intensity = k * kPi;
    gl.type = l.type == Light::Type::Point ? "point" : l.type == Light::Type::Spot ? "spot" : "directional";
    if (l.type == Light::Type::Spot) gl.spot.innerConeAngle = gl.spot.outerConeAngle = l.cutoff * kPi / 180;
    if (l.type != Light::Type::Directional && l.attenuation.law != Attenuation::Law::InverseSquare)
      notes.push_back(fmt::format("lights[{}]: glTF lights fall off with 1/d²; facet's own attenuation travels in {}", i, kLightExt));
    model.lights.push_back(gl);
    json own = to_json(s)["lights"][i];
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
    Vec3 cols[3] = {x, y, z};
    node.matrix.assign(16, 0);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) node.matrix[size_t(c * 4 + r)] = cols[c][r];
    Vec3 p = l.type == Light::Type::Directional ? Vec3(0, 0, 0) : l.position;
    for (int r = 0; r < 3; ++r) node.matrix[size_t(12 + r)] = p[r];
    node.matrix[15] = 1;
    model.nodes.push_back(node);
    gscene.nodes.push_back(int(model.nodes.size() - 1));
    used.insert(kLightsExt);
    used.insert(kLightExt);
  }
  model.scenes.push_back(gscene);
  model.defaultScene = 0;
  model.extensionsUsed.assign(used.begin(), used.end());

  bool binary = fs::path(path).extension() == ".glb";
  if (!binary) {
    // One self-contained file: the buffer as a data URI.
    model.buffers[0].uri = "data:application/octet-stream;base64," +
                           tinygltf::base64_encode(bin.data(), static_cast<unsigned int>(bin.size()));
  }
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/!binary, binary))
    throw IoError(path + ": tinygltf could not write the glTF");
  write_file_atomic(path, out.str());
}

}  // namespace facet
