#include "scene/gltf.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include <fmt/format.h>

#include "core/io.h"
#include "core/text.h"
#include "core/vec.h"
#define TINYGLTF_IMPLEMENTATION  // the one translation unit with tinygltf's code
#include "scene/gltf_read.h"
#include "scene/tangents.h"
#include "scene/gltf_images.h"
#include "catalog/program.h"
#include "catalog/texture.h"

namespace facet {

using nlohmann::json;
namespace fs = std::filesystem;
using gltf_detail::local_matrix;
using gltf_detail::Mat4;
using gltf_detail::PrimitivePlan;
using gltf_detail::Reader;
using gltf_detail::extension_of;
using gltf_detail::material_extensions_read;

namespace {

const char* kMaterialExt = "FACET_material";
const char* kObjectExt = "FACET_object";
const char* kLightExt = "FACET_light";
const char* kSceneExt = "FACET_scene";
const char* kLightsExt = "KHR_lights_punctual";
// The extensions facet reads as their specifications say, so a file may require them: the
// material extensions the material import reads (what one leaves out, e.g. a sheen texture, is
// said in that material's note), and these.
const std::set<std::string>& supported_required() {
  static const std::set<std::string> supported = [] {
    std::set<std::string> s = {kLightsExt, "KHR_texture_transform", kObjectExt, kLightExt, kSceneExt};
    s.insert(material_extensions_read().begin(), material_extensions_read().end());
    return s;
  }();
  return supported;
}

std::array<double, 3> rgb3(const std::vector<double>& v, double fallback) {
  return {v.size() > 0 ? v[0] : fallback, v.size() > 1 ? v[1] : fallback, v.size() > 2 ? v[2] : fallback};
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

// An RGB triple as a glTF array of three numbers.
tinygltf::Value rgb_value(const RGB& c) {
  return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(c[0]), tinygltf::Value(c[1]), tinygltf::Value(c[2])});
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

// A key path of the facet scene JSON import_gltf_data checks ("lights[2].color")
// as the glTF path it came from ("nodes[4].extensions.FACET_light.color").
std::string gltf_path(const std::string& p, const std::string& camera, const std::string& scene_ext,
                      const std::vector<std::string>& objects, const std::vector<std::string>& lights) {
  auto indexed = [&](const char* key, const std::vector<std::string>& paths) -> std::string {
    std::string prefix = std::string(key) + "[";
    if (p.rfind(prefix, 0) != 0) return "";
    size_t close = p.find(']');
    size_t i = std::stoul(p.substr(prefix.size(), close - prefix.size()));
    if (i >= paths.size()) return "";
    // The key goes before a parenthesis that says how the part was converted.
    const std::string& base = paths[i];
    const size_t paren = base.find(" (");
    const std::string rest = p.substr(close + 1);
    return paren == std::string::npos ? base + rest : base.substr(0, paren) + rest + base.substr(paren);
  };
  if (std::string q = indexed("lights", lights); !q.empty()) return q;
  if (std::string q = indexed("objects", objects); !q.empty()) return q;
  if (p.rfind("camera", 0) == 0 && !camera.empty()) return camera + " (as a facet camera: " + p + ")";
  if (p.rfind("ambient", 0) == 0) return scene_ext + "." + p;
  return p;
}

// One glTF file read into a facet scene, one function per kind of glTF object
// (scene, node, camera, light, mesh, primitive, material), as glTF-Blender-IO's
// importer is laid out. What facet's own scene checker reads (camera, lights,
// analytic objects, ambient) is gathered as facet scene JSON with the glTF path
// of each part, and checked in one go at the end: one checker for every source.
class Importer {
 public:
  // External images are read from `folder` (none with an empty one).
  Importer(const tinygltf::Model& model, const std::string& path, const std::string& folder,
           const GltfImportOptions& options, std::vector<std::string>& notes)
      : model_(model), reader_(model, path), path_(path), options_(options), notes_(notes),
        images_(model, path, folder, options.output, notes), keys_(model.materials.size()), on_path_(model.nodes.size(), false) {}

  std::vector<GltfImportFile>& files() { return images_.files(); }

  Scene read() {
    check_required_extensions();
    int scene_index = default_scene();
    const auto& gscene = model_.scenes[size_t(scene_index)];
    s_.source = path_;
    s_.name = gscene.name.empty() ? fs::path(path_).stem().string() : gscene.name;
    read_scene_extension(gscene, scene_index);
    for (int root : gscene.nodes) read_node(root, Mat4());
    if (s_.objects.empty()) reader_.fail(fmt::format("scenes[{}]", scene_index), "has no meshes");
    read_meshes();
    check_texture_coordinates();
    check_gathered_parts();
    if (!have_camera_) frame_camera();
    if (s_.lights.empty()) add_default_light();
    names_one_line();
    return std::move(s_);
  }

 private:
  // A name from the file goes into generated code's comments and into facet's messages: a line
  // break or a control character in it (core/text.h) is replaced by a visible stand-in, with a
  // note, since an asset from anywhere may carry one (a line break would end the comment).
  void names_one_line() {
    std::vector<std::string> changed;
    auto fix = [&](std::string& name, const std::string& what) {
      if (auto b = line_break(name)) {
        changed.push_back(fmt::format("{} \"{}\" ({})", what, one_line(name), describe(*b)));
        name = one_line(name);
      }
    };
    fix(s_.name, "the scene");
    for (auto& o : s_.objects) fix(o.name, "object");
    for (auto& [key, m] : s_.materials) fix(m.name, "material");
    if (!changed.empty())
      notes_.push_back(fmt::format("names made one line (a line break or control character shown as ␊, ␍, ␀, …; "
                                   "names are printed into generated code): {}",
                                   fmt::join(changed, "; ")));
  }

  // A required extension facet does not implement is refused (glTF 2.0 §3.12: a loader that
  // does not support one of them must fail); one only used is named in a note, since the
  // file then renders without it, and what facet reads instead is the core glTF.
  void check_required_extensions() const {
    std::string supported;
    for (const auto& e : supported_required()) supported += (supported.empty() ? "" : ", ") + e;
    for (size_t i = 0; i < model_.extensionsRequired.size(); ++i) {
      const std::string& e = model_.extensionsRequired[i];
      if (!supported_required().count(e))
        reader_.fail(fmt::format("extensionsRequired[{}]", i),
                     fmt::format("\"{}\" is required by the file and facet does not implement it; a file may "
                                 "require: {}",
                                 e, supported));
    }
    std::string ignored;
    size_t count = 0;
    for (const auto& e : model_.extensionsUsed)
      if (!supported_required().count(e)) ignored += (count++ ? ", " : "") + e;
    if (count)
      notes_.push_back(fmt::format("{}: extensionsUsed {} {} not implemented by facet and ignored (the file renders "
                                   "as core glTF without {}; each material names its own)",
                                   path_, ignored, count == 1 ? "is" : "are", count == 1 ? "it" : "them"));
  }

  // The index of the scene to read: the file's default one, else the first.
  int default_scene() const {
    if (model_.scenes.empty()) reader_.fail("scenes", "the file has no scene");
    int scene_index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (size_t(scene_index) >= model_.scenes.size())
      reader_.fail("scene", fmt::format("names no scene ({})", scene_index));
    return scene_index;
  }

  // Node `ni` was reached from a root of the scene other than its ancestors' root:
  // one of its ancestors (or itself) is a root and also a child.
  [[noreturn]] void fail_root_with_parent(int ni) const {
    const auto& roots = model_.scenes[size_t(default_scene())].nodes;
    const std::vector<int>& up = reader_.parents();
    for (int n = ni; n >= 0; n = up[size_t(n)])
      if (up[size_t(n)] >= 0 && std::find(roots.begin(), roots.end(), n) != roots.end())
        reader_.fail(fmt::format("nodes[{}]", n), fmt::format("is one of the scene's roots and also a child of "
                                                              "nodes[{}]; glTF's node hierarchy is a set of disjoint "
                                                              "trees",
                                                              up[size_t(n)]));
    reader_.fail(fmt::format("nodes[{}]", ni), "is reached from the scene's roots other than through its ancestors");
  }

  // FACET_scene: the ambient colour.
  void read_scene_extension(const tinygltf::Scene& gscene, int scene_index) {
    json scene_ext = extension_of(gscene.extensions_json_string, kSceneExt);
    scene_ext_path_ = fmt::format("scenes[{}].extensions.{}", scene_index, kSceneExt);
    if (scene_ext.is_object() && scene_ext.contains("ambient")) checked_["ambient"] = scene_ext["ambient"];
  }

  // The hierarchy under root node `ni`, depth first, each node before its children: its
  // camera (the first one met is the scene's), its light, its mesh. Walked with a stack of
  // its own, so that a chain of any depth (a file may hold millions of nodes) needs no
  // more than a vector.
  struct NodeFrame {
    int node;
    Mat4 world;
    size_t next_child = 0;
  };
  void read_node(int ni, const Mat4& parent) {
    std::vector<NodeFrame> path;
    enter_node(ni, parent, path);
    while (!path.empty()) {
      NodeFrame& f = path.back();
      const auto& children = model_.nodes[size_t(f.node)].children;
      if (f.next_child == children.size()) {
        on_path_[size_t(f.node)] = false;
        path.pop_back();
        continue;
      }
      const int child = children[f.next_child++];
      const Mat4 world = f.world;  // `f` may move when the child is pushed
      enter_node(child, world, path);
    }
  }

  void enter_node(int ni, const Mat4& parent, std::vector<NodeFrame>& path) {
    if (ni < 0 || size_t(ni) >= model_.nodes.size()) reader_.fail("nodes", fmt::format("no node {}", ni));
    std::string npath = fmt::format("nodes[{}]", ni);
    if (on_path_[size_t(ni)]) reader_.fail(npath + ".children", "the node hierarchy has a cycle through this node");
    on_path_[size_t(ni)] = true;
    const auto& node = model_.nodes[size_t(ni)];
    Mat4 world = parent * local_matrix(node);
    if (node.camera >= 0 && !have_camera_) read_camera(node, npath, world);
    read_light(node, npath, world);
    if (node.mesh >= 0) read_mesh(node, npath, world);
    path.push_back({ni, world, 0});
  }

  void read_camera(const tinygltf::Node& node, const std::string& npath, const Mat4& world) {
    if (size_t(node.camera) >= model_.cameras.size()) reader_.fail(npath + ".camera", "names no camera");
    const auto& cam = model_.cameras[size_t(node.camera)];
    camera_path_ = fmt::format("cameras[{}]", node.camera);
    if (cam.type != "perspective" && cam.type != "orthographic")
      reader_.fail(camera_path_ + ".type", "is \"" + cam.type + "\"; glTF's cameras are perspective or orthographic");
    // glTF 2.0 §3.10: the camera looks down its node's −Z with +Y up.
    Vec3 position = world.point(Vec3(0, 0, 0));
    Vec3 forward = normalize(world.direction(Vec3(0, 0, -1)));
    checked_["camera"] = {{"position", position.array()},
                          {"look_at", (position + forward).array()},
                          {"up", normalize(world.direction(Vec3(0, 1, 0))).array()}};
    if (cam.type == "orthographic") {  // ymag: half the view's height (§3.10.3); the image's aspect gives the width
      checked_["camera"]["type"] = "orthographic";
      checked_["camera"]["height"] = 2 * cam.orthographic.ymag;
      if (cam.orthographic.xmag != cam.orthographic.ymag)
        notes_.push_back(fmt::format("{}: orthographic, xmag {} and ymag {}: facet takes ymag, and the image's aspect "
                                     "ratio sets the width (as glTF viewers do)",
                                     camera_path_, cam.orthographic.xmag, cam.orthographic.ymag));
    } else {
      checked_["camera"]["fov"] = cam.perspective.yfov * 180 / kPi;
      if (cam.perspective.aspectRatio > 0)
        notes_.push_back(fmt::format("{}: aspectRatio {} ignored; the image's own aspect ratio sets the width, "
                                     "yfov the height",
                                     camera_path_, cam.perspective.aspectRatio));
    }
    have_camera_ = true;
  }

  // The node's KHR_lights_punctual light: facet's own (FACET_light) where the node
  // carries it, exactly, else the punctual light's nearest facet light.
  void read_light(const tinygltf::Node& node, const std::string& npath, const Mat4& world) {
    json light_ref = extension_of(node.extensions_json_string, kLightsExt);
    if (!light_ref.is_object() || !light_ref.contains("light")) return;
    std::string ref_path = npath + ".extensions.KHR_lights_punctual.light";
    if (!light_ref["light"].is_number_integer()) reader_.fail(ref_path, "expected the index of a light");
    int64_t li = light_ref["light"].get<int64_t>();
    if (li < 0 || size_t(li) >= model_.lights.size()) reader_.fail(ref_path, "names no light");
    json exact = extension_of(node.extensions_json_string, kLightExt);
    json lj;
    if (exact.is_object()) {
      lj = exact;
      light_paths_.push_back(npath + ".extensions." + kLightExt);
    } else {
      light_paths_.push_back(fmt::format("extensions.KHR_lights_punctual.lights[{}] (its colour × intensity / "
                                         "({} lm/W · π) as a facet light's colour C)",
                                         li, options_.lumens_per_watt));
      lj = punctual_light(model_.lights[size_t(li)], li);
    }
    place_light(lj, world);
    lights_.push_back(lj);
  }

  // C = colour · intensity / (lumens per watt · π) (gltf.h, kLumensPerWatt), inverse-square;
  // spot cones hard at the outer angle.
  json punctual_light(const tinygltf::Light& gl, int64_t li) {
    auto c = rgb3(gl.color, 1);
    double k = gl.intensity / (options_.lumens_per_watt * kPi);
    json lj = {{"type", gl.type}, {"color", {c[0] * k, c[1] * k, c[2] * k}}};
    if (gl.type != "directional") lj["attenuation"] = "inverse_square";
    if (gl.type == "spot") {
      double outer = gl.spot.outerConeAngle * 180 / kPi;
      lj["cutoff"] = std::min(outer, 89.9);
      lj["exponent"] = 0;
      if (gl.spot.innerConeAngle != gl.spot.outerConeAngle)
        notes_.push_back(fmt::format("lights[{}]: approximate: facet's spot cone is hard (cutoff = outerConeAngle)", li));
    }
    // KHR_lights_punctual, "Range Property": the recommended window clamp(1 − (d/r)⁴, 0, 1) / d².
    if (gl.range > 0 && gl.type != "directional")
      lj["attenuation"] = {{"model", "inverse_square_range"}, {"range", gl.range}};
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
    json analytic = extension_of(node.extensions_json_string, kObjectExt);
    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const auto& prim = mesh.primitives[pi];
      std::string ppath = fmt::format("meshes[{}].primitives[{}]", node.mesh, pi);
      if (!analytic.is_object() && !gltf_detail::is_triangles(prim)) {  // points and lines: no surface
        notes_.push_back(fmt::format("{}: mode {} (points or lines) has no surface to shade; left out", ppath, prim.mode));
        continue;
      }
      Object o;
      o.name = (node.name.empty() ? (mesh.name.empty() ? fmt::format("mesh{}", node.mesh) : mesh.name) : node.name) +
               (mesh.primitives.size() > 1 ? fmt::format("_{}", pi) : "");
      o.material = material_key(prim.material, ppath, !analytic.is_object() && prim.attributes.count("COLOR_0"));
      std::array<int64_t, 2> texcoords{0, 1};
      if (auto mp = material_paths_.find(o.material); mp != material_paths_.end())
        if (auto it = texcoord_sources_.find(mp->second); it != texcoord_sources_.end()) texcoords = it->second;
      if (analytic.is_object()) {
        analytic_objects_.push_back(s_.objects.size());
        analytic_json_.push_back(analytic);
        object_paths_.push_back(npath + ".extensions." + kObjectExt);
      } else {
        o.type = Object::Type::Mesh;
        o.reference = MeshReference{path_, true, int64_t(&node - model_.nodes.data()), "",
                                    mesh.primitives.size() > 1 ? int64_t(pi) : -1, texcoords};
        PrimitivePlan plan = gltf_detail::plan_primitive(reader_, prim, ppath, npath, texcoords);
        gltf_detail::plan_deformation(reader_, plan, mesh, int(&node - model_.nodes.data()), notes_);
        budget_.add(plan.size, path_, npath, fmt::format("{}'s {}", npath, ppath));
        pending_.push_back({s_.objects.size(), std::move(plan), world});
      }
      s_.objects.push_back(o);
    }
  }

  // The triangle primitives met while visiting the nodes, counted within the limit:
  // each node's in its world transform, which must be the one its ancestors give
  // it (as a scene file's reference to the node reads it: glTF's nodes are trees).
  void read_meshes() {
    const uint64_t total = budget_.total().triangles;
    auto start = std::chrono::steady_clock::now();
    const bool big = total >= gltf_detail::kProgressTriangles;
    if (big) progress(fmt::format("reading {}: {} triangles", path_, gltf_detail::thousands(total)));
    for (const auto& p : pending_) {
      const int ni = int(s_.objects[p.object].reference->index);
      Mat4 tree = reader_.world_matrix(ni);
      if (std::memcmp(tree.m, p.world.m, sizeof tree.m) != 0) fail_root_with_parent(ni);
      auto mesh = std::make_shared<Mesh>();
      gltf_detail::append_primitive(reader_, p.plan, p.world, *mesh, notes_);
      if (mesh->triangles.empty()) reader_.fail(p.plan.path, "has no triangles");
      mesh->build_bvh();
      s_.objects[p.object].mesh = std::move(mesh);
    }
    if (big)
      progress(fmt::format("{}: {} triangles read in {:.1f} s", path_, gltf_detail::thousands(total),
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
  }

  // The key in s_.materials of glTF material `index` (read once, on first use),
  // or of the default material for a primitive without one. `colors`: for a primitive with
  // COLOR_0, which multiplies the base colour: a material of its own (key suffixed
  // "_vertex_colors"), as glTF-Blender-IO's importer makes one Blender material per
  // (material, has COLOR_0), since primitives without COLOR_0 share the glTF material.
  // A primitive without a material takes glTF's default material (glTF 2.0 §3.9.1: every
  // property at its default, base colour 1, metallic 1, roughness 1: white metal), or the one
  // the user gave (--default-material).
  std::string material_key(int index, const std::string& where, bool colors) {
    if (index < 0) return default_material_key(where, colors && !options_.default_material);
    if (size_t(index) >= model_.materials.size()) reader_.fail(where + ".material", "names no material");
    const auto& g = model_.materials[size_t(index)];
    // facet's own material says itself whether it reads the vertex colour: one key either way.
    const json ext = extension_of(g.extensions_json_string, kMaterialExt);
    if (ext.is_object() && ext.contains("material")) colors = false;
    std::string& key = keys_[size_t(index)][colors ? 1 : 0];
    if (!key.empty()) return key;
    std::string mpath = fmt::format("materials[{}]", index);
    key = unique_key(identifier(g.name.empty() ? fmt::format("material{}", index) : g.name) +
                     (colors ? "_vertex_colors" : ""));
    material_paths_[key] = mpath;
    s_.materials[key] = read_material(g, mpath, colors);
    return key;
  }

  std::string default_material_key(const std::string& where, bool colors) {
    std::string& key = default_keys_[colors ? 1 : 0];
    if (!key.empty()) return key;
    key = unique_key(colors ? "default_vertex_colors" : "default");
    if (options_.default_material) {
      s_.materials[key] = *options_.default_material;
    } else {
      tinygltf::Material none;
      none.name = "default";
      std::vector<std::pair<int, std::string>> sets;
      s_.materials[key] = parse_material(gltf_detail::pbr_material(none, "default", images_, sets, notes_, colors), path_,
                                         images_.scene_folder());
      notes_.push_back(where + ": no material; glTF's default material taken (base colour 1, metallic 1, roughness "
                               "1: white metal; --default-material MATERIAL.json gives another)");
    }
    return key;
  }

  // `key`, or with underscores after it until no material has it.
  std::string unique_key(std::string key) {
    while (used_keys_.count(key)) key += "_";
    used_keys_.insert(key);
    return key;
  }

  // facet's own material (FACET_material) exactly, else the metallic–roughness one (for
  // primitives with COLOR_0 where `colors`).
  Material read_material(const tinygltf::Material& g, const std::string& mpath, bool colors) {
    json ext = extension_of(g.extensions_json_string, kMaterialExt);
    // Each variant (with and without COLOR_0) reads the same sets: the last one read is kept.
    std::vector<std::pair<int, std::string>> sets;
    const bool own = ext.is_object() && ext.contains("material");
    json m = own ? own_material(ext, mpath, sets) : gltf_detail::pbr_material(g, mpath, images_, sets, notes_, colors);
    if (!own) map_texture_sets(m, sets, mpath);
    texture_sets_[mpath] = sets;
    try {
      return parse_material(m, path_, images_.scene_folder());  // its images lie beside the scene
    } catch (const InputError& e) {
      // FACET_material's own key, or the glTF material with the key of the facet
      // material it became (a metallic–roughness factor beyond what float32 holds).
      std::vector<Diagnostic> ds = e.diagnostics();
      for (auto& d : ds)
        d.path = own ? mpath + ".extensions." + kMaterialExt + ".material" + (d.path.empty() ? "" : "." + d.path)
                     : mpath + " (as a facet material: " + d.path + ")";
      throw InputError(ds);
    }
  }

  // glTF's textures may read any set TEXCOORD_n; a facet mesh carries two sets, 0 and 1. A
  // material whose textures read other sets (at most two of them) has them mapped onto 0 and
  // 1, in order, and its meshes read those sets as 0 and 1 (MeshReference::texcoords, the
  // scene file's "texcoord0"/"texcoord1"): every texture keeps its own set and transform.
  void map_texture_sets(json& m, std::vector<std::pair<int, std::string>>& sets, const std::string& mpath) {
    std::vector<int64_t> distinct;
    for (const auto& [set, key] : sets)
      if (std::find(distinct.begin(), distinct.end(), set) == distinct.end()) distinct.push_back(set);
    std::sort(distinct.begin(), distinct.end());
    if (distinct.empty() || distinct.back() < 2) return;
    if (distinct.size() > 2) {
      std::string keys;
      for (const auto& [set, key] : sets) keys += fmt::format("{}{} (TEXCOORD_{})", keys.empty() ? "" : ", ", key, set);
      reader_.fail(mpath, fmt::format("its textures read {} texture coordinate sets: {}; a facet mesh carries two",
                                      distinct.size(), keys));
    }
    const std::array<int64_t, 2> from{distinct[0], distinct.size() > 1 ? distinct[1] : 1};  // one set: it is 0
    auto slot = [&](int64_t set) { return set == from[0] ? 0 : 1; };
    std::function<void(json&)> visit = [&](json& j) {
      if (j.is_object() && j.contains("texture") && j.contains("uv")) j["uv"] = slot(j["uv"].get<int64_t>());
      if (j.is_structured())
        for (auto& e : j) visit(e);
    };
    visit(m);
    for (auto& [set, key] : sets) set = slot(set);
    texcoord_sources_[mpath] = from;
    notes_.push_back(fmt::format("{}: its textures read TEXCOORD_{}{}; its meshes carry {} as facet's set{} 0{}",
                                 mpath, from[0], distinct.size() > 1 ? fmt::format(" and TEXCOORD_{}", from[1]) : "",
                                 distinct.size() > 1 ? "them" : "it", distinct.size() > 1 ? "s" : "",
                                 distinct.size() > 1 ? " and 1" : ""));
  }

  // FACET_material's material, each image its "images" names ({"file as the material
  // names it": glTF image index}, as export_gltf writes) read as the glTF's image.
  json own_material(const json& ext, const std::string& mpath, std::vector<std::pair<int, std::string>>& sets) {
    const std::string key = mpath + ".extensions." + kMaterialExt;
    std::map<std::string, std::string> files;
    if (ext.contains("images") && ext["images"].is_object())
      for (const auto& [name, index] : ext["images"].items()) {
        if (!index.is_number_integer()) reader_.fail(key + ".images." + name, "expected a glTF image index");
        files[name] = images_.image_file(index.get<int>(), key + ".images." + name);
      }
    std::function<void(json&, const std::string&)> visit = [&](json& j, const std::string& at) {
      if (j.is_object() && j.contains("texture") && j["texture"].is_string()) {
        auto f = files.find(j["texture"].get<std::string>());
        if (f != files.end()) j["texture"] = f->second;
        sets.emplace_back(j.value("uv", 0), at + ".uv");
        return;
      }
      if (j.is_object())
        for (auto& [k, v] : j.items()) visit(v, at + "." + k);
      if (j.is_array())
        for (size_t i = 0; i < j.size(); ++i) visit(j[i], fmt::format("{}[{}]", at, i));
    };
    json m = ext["material"];
    visit(m, key + ".material");
    return m;
  }

  // Each mesh has the texture coordinate sets its material's textures read.
  void check_texture_coordinates() const {
    for (const auto& o : s_.objects) {
      if (o.type != Object::Type::Mesh || !o.mesh) continue;
      auto it = material_paths_.find(o.material);
      if (it == material_paths_.end()) continue;
      auto sets = texture_sets_.find(it->second);
      if (sets == texture_sets_.end()) continue;
      for (const auto& [set, key] : sets->second)
        if (set >= 0 && set < 2 && o.mesh->texcoords[size_t(set)].empty())
          reader_.fail(key, fmt::format("TEXCOORD_{}, which {} ({}) lacks", o.reference ? o.reference->texcoords[size_t(set)] : set,
                                        o.name, o.reference ? "nodes[" + std::to_string(o.reference->index) + "]" : "a mesh"));
    }
  }

  // A glTF without lights (most sample models) would render black: facet adds a
  // headlight, a point light at the camera without falloff (facet's attenuation
  // "none"), colour 1: a white Lambert surface facing it shows 1 at any distance. A
  // viewer's fallback is of this kind (README, "Scenes, meshes and glTF").
  void add_default_light() {
    Light l;
    l.type = Light::Type::Point;
    l.position = s_.camera.position;
    l.color = {1, 1, 1};
    l.attenuation.law = Attenuation::Law::None;
    s_.lights.push_back(l);
    notes_.push_back(fmt::format("{}: no lights; facet added a headlight: a point light at the camera ({:.6g}, {:.6g}, "
                                 "{:.6g}), colour 1, no falloff (a white Lambert surface facing it shows 1)",
                                 path_, l.position.x, l.position.y, l.position.z));
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
  gltf_detail::GltfImages images_;
  // Materials by index, without and with COLOR_0; only those the primitives use are read.
  std::vector<std::array<std::string, 2>> keys_;
  std::set<std::string> used_keys_;
  std::array<std::string, 2> default_keys_;  // the material primitives without one take, once read
  std::map<std::string, std::string> material_paths_;  // facet material key → glTF path
  std::map<std::string, std::array<int64_t, 2>> texcoord_sources_;  // by glTF path: the sets read as 0 and 1
  std::map<std::string, std::vector<std::pair<int, std::string>>> texture_sets_;  // by glTF path: (set, key)
  std::vector<bool> on_path_;  // the nodes being visited: a cycle is an error
  struct Pending {
    size_t object;  // in s_.objects
    PrimitivePlan plan;
    Mat4 world;
  };
  std::vector<Pending> pending_;  // the triangle primitives, read once all are counted
  gltf_detail::MeshBudget budget_;
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
  Exporter(const Scene& s, const Material* fallback, const std::string& path, std::vector<std::string>& notes)
      : s_(s), fallback_(fallback), notes_(notes), images_(model_, path, notes) {
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
    std::vector<GltfImportFile> files = images_.files();  // the images copied beside it, then the file
    files.push_back({path, out.str()});
    write_import_files(files);
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

  // Why the texture `t` is no glTF textureInfo of channel `channel` in `colorspace` (a vertex
  // colour, an offset, another channel or colour space); "" where it is one.
  static std::string gltf_texture_unsaid(const TextureRef& t, const char* channel, const char* colorspace) {
    if (!t.has_image() || t.vertex_color || t.bias != RGB{0, 0, 0}) return "a vertex colour or an offset";
    if (t.channel != channel || t.colorspace != colorspace)
      return fmt::format("channel {} in {} where glTF reads {} in {}", t.channel, t.colorspace, channel, colorspace);
    return "";
  }

  // What of glTF's own BRDF (ModelDef::gltf_brdf) glTF cannot say — a colour k_s, toon, maps
  // glTF does not read that way, metallic and roughness maps that are not one image's B and G,
  // an ior map —, or "" where it says all of it. Decided before anything is written.
  static std::string gltf_brdf_unsaid(const ModelSpec& s) {
    if (s.at("color").texture || s.at("color").rgb != RGB{1, 1, 1}) return "the colour k_s";
    if (s.values.count("toon") && s.at("toon").model) return "the toon modifier";
    if (s.at("ior").texture) return "an ior map";
    auto map = [](const Value& v, const char* channel, const char* colorspace, const char* what) {
      const std::string why = v.texture ? gltf_texture_unsaid(*v.texture, channel, colorspace) : "";
      return why.empty() ? why : fmt::format("the {} map ({})", what, why);
    };
    const Value &metal = s.at("metallic"), &rough = s.at("roughness");
    for (const std::string& why : {map(s.at("base_color"), "rgb", "srgb", "base colour"),
                                   map(metal, "b", "linear", "metallic"), map(rough, "g", "linear", "roughness"),
                                   map(s.at("specular"), "a", "linear", "specular"),
                                   map(s.at("specular_color"), "rgb", "srgb", "specular colour"),
                                   map(s.at("sheen_color"), "rgb", "srgb", "sheen colour"),
                                   map(s.at("sheen_roughness"), "a", "linear", "sheen roughness"),
                                   map(s.at("clearcoat"), "r", "linear", "clear coat"),
                                   map(s.at("clearcoat_roughness"), "g", "linear", "clear coat roughness")})
      if (!why.empty()) return why;
    if (const std::string why = anisotropy_unsaid(s); !why.empty()) return why;
    if (!metal.texture && !rough.texture) return "";
    // One image's B (metallic) and G (roughness).
    const bool one = metal.texture && rough.texture && same_image(*metal.texture, *rough.texture);
    return one ? "" : "metallic and roughness maps that are not one image's B and G";
  }

  // Whether two textured values read one image the same way: the same file, sampler, set and transform.
  static bool same_image(const TextureRef& a, const TextureRef& b) {
    return a.path == b.path && a.uv == b.uv && a.sampler.filter == b.sampler.filter && a.sampler.wrap == b.sampler.wrap &&
           a.offset == b.offset && a.scale == b.scale && a.rotation == b.rotation;
  }

  // KHR_materials_anisotropy's texture holds the direction's x and y as R and G (2·rg − 1) and the
  // strength as B (times anisotropyStrength): facet's three values say it where they are one
  // image's R and G (factor 1) and B, or where none is an image (a direction of numbers turns into
  // anisotropyRotation). "" where glTF says them.
  static std::string anisotropy_unsaid(const ModelSpec& s) {
    const Value &strength = s.at("anisotropy_strength"), &x = s.at("anisotropy_direction_x"),
                &y = s.at("anisotropy_direction_y");
    if (!strength.texture && !x.texture && !y.texture) return "";
    const char* why = "anisotropy maps that are not one image's R and G (factor 1) and B";
    if (!strength.texture || !x.texture || !y.texture) return why;
    auto channel = [](const Value& v, const char* c, bool factor_one) {
      return gltf_texture_unsaid(*v.texture, c, "linear").empty() && (!factor_one || v.number == 1);
    };
    const bool one = channel(strength, "b", false) && channel(x, "r", true) && channel(y, "g", true) &&
                     same_image(*strength.texture, *x.texture) && same_image(*strength.texture, *y.texture);
    return one ? "" : why;
  }

  // glTF's own BRDF written back as glTF: pbrMetallicRoughness's factors and maps,
  // KHR_materials_ior, KHR_materials_specular, KHR_materials_sheen and KHR_materials_clearcoat
  // (glTF 2.0 §3.9.2; the extensions' READMEs).
  // False, with a note and nothing written, where the lobe holds what glTF cannot say: the
  // fallback then.
  // `m` as one gltf_pbr lobe, its layers folded in (gltf_brdf_lobe); nullopt, with a note where
  // it has layers, where glTF's BRDF cannot hold it.
  std::optional<ModelSpec> gltf_brdf_of(const std::string& key, const Material& m) {
    std::string why;
    std::optional<ModelSpec> folded = gltf_brdf_lobe(m, &why);
    if (!folded && !why.empty())
      notes_.push_back(fmt::format("materials.{}: glTF's BRDF cannot hold {}; the metallic–roughness core is "
                                   "approximate (FACET_material carries the material)",
                                   key, why));
    else if (!folded && !m.layers.empty())
      notes_.push_back(fmt::format("materials.{}: its layers are left out of the metallic–roughness core, which is "
                                   "approximate (FACET_material carries the material)",
                                   key));
    return folded;
  }

  bool gltf_brdf(const std::string& key, const Material& m, tinygltf::Material& g) {
    const std::optional<ModelSpec> folded = gltf_brdf_of(key, m);  // its layers as its extensions
    if (!folded) return false;
    const ModelSpec& s = *folded;
    if (const std::string why = gltf_brdf_unsaid(s); !why.empty()) {
      notes_.push_back(fmt::format("materials.{}: glTF cannot say {} of its gltf_pbr lobe; the metallic–roughness "
                                   "core is approximate (FACET_material carries the material)",
                                   key, why));
      return false;
    }
    auto& pbr = g.pbrMetallicRoughness;
    const Value &base = s.at("base_color"), &metal = s.at("metallic");
    pbr.baseColorFactor = {base.rgb[0], base.rgb[1], base.rgb[2], 1.0};
    pbr.metallicFactor = metal.number;
    pbr.roughnessFactor = s.at("roughness").number;
    if (base.texture) images_.texture_info(*base.texture, pbr.baseColorTexture, used_);
    if (metal.texture) images_.texture_info(*metal.texture, pbr.metallicRoughnessTexture, used_);
    if (s.at("ior").number != 1.5) {
      tinygltf::Value::Object ior;
      ior["ior"] = tinygltf::Value(s.at("ior").number);
      g.extensions["KHR_materials_ior"] = tinygltf::Value(ior);
      used_.insert("KHR_materials_ior");
    }
    const Value &specular = s.at("specular"), &tint = s.at("specular_color");
    if (specular.texture || specular.number != 1 || tint.texture || tint.rgb != RGB{1, 1, 1}) {
      tinygltf::Value::Object ext;
      ext["specularFactor"] = tinygltf::Value(specular.number);
      ext["specularColorFactor"] = rgb_value(tint.rgb);
      if (specular.texture) ext["specularTexture"] = extension_texture_info(*specular.texture);
      if (tint.texture) ext["specularColorTexture"] = extension_texture_info(*tint.texture);
      g.extensions["KHR_materials_specular"] = tinygltf::Value(ext);
      used_.insert("KHR_materials_specular");
    }
    if (const Value& strength = s.at("anisotropy_strength"); strength.texture || strength.number > 0) {
      tinygltf::Value::Object ext;
      ext["anisotropyStrength"] = tinygltf::Value(strength.number);
      // A direction of numbers is the lobe's turn beyond the rotation (catalog/specular.cpp).
      const double x = 2 * s.at("anisotropy_direction_x").number - 1, y = 2 * s.at("anisotropy_direction_y").number - 1;
      const bool turned = !strength.texture && !(x == 0 && y == 0);
      ext["anisotropyRotation"] = tinygltf::Value(s.at("anisotropy_rotation").number + (turned ? std::atan2(y, x) : 0.0));
      if (strength.texture) ext["anisotropyTexture"] = extension_texture_info(*strength.texture);
      g.extensions["KHR_materials_anisotropy"] = tinygltf::Value(ext);
      used_.insert("KHR_materials_anisotropy");
    }
    const Value& sheen = s.at("sheen_color");
    if (sheen.rgb != RGB{0, 0, 0}) {
      tinygltf::Value::Object ext;
      ext["sheenColorFactor"] = rgb_value(sheen.rgb);
      ext["sheenRoughnessFactor"] = tinygltf::Value(s.at("sheen_roughness").number);
      if (sheen.texture) ext["sheenColorTexture"] = extension_texture_info(*sheen.texture);
      if (const Value& r = s.at("sheen_roughness"); r.texture)
        ext["sheenRoughnessTexture"] = extension_texture_info(*r.texture);
      g.extensions["KHR_materials_sheen"] = tinygltf::Value(ext);
      used_.insert("KHR_materials_sheen");
    }
    const Value &coat = s.at("clearcoat"), &coat_roughness = s.at("clearcoat_roughness");
    if (coat.texture || coat.number != 0) {
      tinygltf::Value::Object ext;
      ext["clearcoatFactor"] = tinygltf::Value(coat.number);
      ext["clearcoatRoughnessFactor"] = tinygltf::Value(coat_roughness.number);
      if (coat.texture) ext["clearcoatTexture"] = extension_texture_info(*coat.texture);
      if (coat_roughness.texture) ext["clearcoatRoughnessTexture"] = extension_texture_info(*coat_roughness.texture);
      // The coat's own normal map: a normalTextureInfo, its scale the map's strength (glTF's is green up).
      if (const auto& map = m.coat_normal_map; map && map->green_down) {
        notes_.push_back(fmt::format("materials.{}: its coat normal map's green points down (DirectX); glTF's "
                                     "clearcoatNormalTexture is left out (FACET_material carries it)",
                                     key));
      } else if (map) {
        tinygltf::Value::Object info = extension_texture_info(map->texture()).Get<tinygltf::Value::Object>();
        info["scale"] = tinygltf::Value(map->strength);
        ext["clearcoatNormalTexture"] = tinygltf::Value(info);
      }
      g.extensions["KHR_materials_clearcoat"] = tinygltf::Value(ext);
      used_.insert("KHR_materials_clearcoat");
    }
    return true;
  }

  // A textureInfo inside a material extension (tinygltf keeps extensions as values): the
  // texture written as the core's are, its index, texCoord and KHR_texture_transform.
  tinygltf::Value extension_texture_info(const TextureRef& texture) {
    tinygltf::TextureInfo info;
    images_.texture_info(texture, info, used_);
    tinygltf::Value::Object t;
    t["index"] = tinygltf::Value(info.index);
    t["texCoord"] = tinygltf::Value(info.texCoord);
    if (!info.extensions.empty()) t["extensions"] = tinygltf::Value(info.extensions);
    return tinygltf::Value(t);
  }

  // The full facet description (FACET_material, its images as the glTF's: "images" maps
  // each file name it uses to one) beside the metallic–roughness fallback, whose base
  // colour is the diffuse colour's map where that is an sRGB colour map.
  void add_material(const std::string& key, const Material& m) {
    tinygltf::Material g;
    g.name = key;
    if (!gltf_brdf(key, m, g)) fallback_pbr(m, g);
    json images = json::object();
    json own = {{"material", images_.material_images(to_json(m), images)}};
    if (!images.empty()) own["images"] = images;
    g.extensions[kMaterialExt] = value_of(own);
    if (m.diffuse) {
      const Value& color = m.diffuse->at("color");
      if (color.texture && color.texture->has_image() && color.texture->channel == "rgb" &&
          color.texture->colorspace == "srgb")
        images_.texture_info(*color.texture, g.pbrMetallicRoughness.baseColorTexture, used_);
      else if (color.texture && color.texture->has_image())
        notes_.push_back(fmt::format("materials.{}: its diffuse colour map is not an sRGB colour map; glTF's "
                                     "baseColorTexture is left out (FACET_material carries it)",
                                     key));
    }
    if (m.normal_map) {  // glTF's normal texture is facet's with green up; down has no glTF form
      if (m.normal_map->green_down) {
        notes_.push_back(fmt::format("materials.{}: its normal map's green points down (DirectX); glTF's "
                                     "normalTexture is left out (FACET_material carries it)",
                                     key));
      } else {
        tinygltf::TextureInfo info;
        images_.texture_info(m.normal_map->texture(), info, used_);
        g.normalTexture.index = info.index;
        g.normalTexture.texCoord = info.texCoord;
        g.normalTexture.extensions = info.extensions;
        g.normalTexture.scale = m.normal_map->strength;
      }
    }
    if (m.emission_texture && m.emission_texture->has_image() && m.emission_texture->channel == "rgb" &&
        m.emission_texture->colorspace == "srgb")
      images_.texture_info(*m.emission_texture, g.emissiveTexture, used_);
    // glTF's factor is at most 1: the rest is KHR_materials_emissive_strength (the emission's
    // radiance, a map's texels times it, is then the same).
    const double peak = std::max({m.emission[0], m.emission[1], m.emission[2]});
    const double k = std::max(peak, 1.0);
    g.emissiveFactor = {m.emission[0] / k, m.emission[1] / k, m.emission[2] / k};
    if (k > 1) {
      tinygltf::Value::Object strength;
      strength["emissiveStrength"] = tinygltf::Value(k);
      g.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(strength);
      used_.insert("KHR_materials_emissive_strength");
    }
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
    node.mesh = add_mesh(o.name, material, pos, nor, idx, o.type == Object::Type::Mesh ? o.mesh.get() : nullptr);
    add_node(node);
    // glTF viewers multiply the base colour by COLOR_0 whatever the material; facet's reads it where it says so.
    if (o.type == Object::Type::Mesh && !o.mesh->colors.empty() && !compile(s_.material_of(i, fallback_)).uses_vertex_color())
      notes_.push_back(fmt::format("objects[{}] (\"{}\"): its vertex colours go out as COLOR_0, which glTF viewers "
                                   "multiply the base colour by; its material (FACET_material) does not read them",
                                   i, o.name));
  }

  // A one-primitive triangle mesh of float32 positions and normals (and `source`'s texture
  // coordinates as TEXCOORD_0/1, vertex colours as COLOR_0 and tangents as TANGENT, where it
  // has them).
  int add_mesh(const std::string& name, int material, const std::vector<Vec3>& pos, const std::vector<Vec3>& nor,
               const std::vector<uint32_t>& idx, const Mesh* source = nullptr) {
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
    for (size_t set = 0; source && set < 2; ++set) {
      if (source->texcoords[set].empty()) continue;
      std::vector<float> st;
      for (const auto& c : source->texcoords[set]) st.insert(st.end(), {float(c[0]), float(c[1])});
      prim.attributes["TEXCOORD_" + std::to_string(set)] =
          add_accessor(st.data(), st.size() * 4, st.size() / 2, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_FLOAT,
                       TINYGLTF_TARGET_ARRAY_BUFFER);
    }
    if (source && !source->colors.empty()) {  // RGBA float: what facet holds, exactly as float32 holds it
      std::vector<float> c;
      for (const auto& v : source->colors) c.insert(c.end(), {float(v[0]), float(v[1]), float(v[2]), float(v[3])});
      prim.attributes["COLOR_0"] = add_accessor(c.data(), c.size() * 4, c.size() / 4, TINYGLTF_TYPE_VEC4,
                                                TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
    }
    if (source && !source->tangents.empty()) {
      std::vector<float> tw;
      for (const auto& t : source->tangents) tw.insert(tw.end(), {float(t[0]), float(t[1]), float(t[2]), float(t[3])});
      prim.attributes["TANGENT"] = add_accessor(tw.data(), tw.size() * 4, tw.size() / 4, TINYGLTF_TYPE_VEC4,
                                                TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
    }
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
    if (s_.camera.orthographic) {  // ymag half the height; xmag as ymag, viewers take the aspect from the image
      cam.type = "orthographic";
      cam.orthographic.ymag = cam.orthographic.xmag = s_.camera.height / 2;
      cam.orthographic.znear = 0;
      cam.orthographic.zfar = far_plane();
    } else {
      cam.type = "perspective";
      cam.perspective.yfov = s_.camera.fov * kPi / 180;
      cam.perspective.znear = 0.01;
      cam.perspective.zfar = far_plane();
    }
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

  // Light i: KHR_lights_punctual (intensity = 683 lm/W · π · C, the inverse of the import)
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
    gl.intensity = k * kPi * kLumensPerWatt;
    gl.type = l.type == Light::Type::Point ? "point" : l.type == Light::Type::Spot ? "spot" : "directional";
    if (l.type == Light::Type::Spot) gl.spot.innerConeAngle = gl.spot.outerConeAngle = l.cutoff * kPi / 180;
    if (l.type != Light::Type::Directional && l.attenuation.law == Attenuation::Law::InverseSquareRange)
      gl.range = l.attenuation.range;
    else if (l.type != Light::Type::Directional && l.attenuation.law != Attenuation::Law::InverseSquare)
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
  gltf_detail::GltfImageWriter images_;
};

}  // namespace

namespace {

// The files a scene's materials read: an image every texture was baked from is not written.
std::vector<GltfImportFile> used_files(const Scene& s, std::vector<GltfImportFile>& files) {
  std::set<std::string> used;
  std::function<void(const json&)> visit = [&](const json& j) {
    if (j.is_object() && j.contains("texture") && j["texture"].is_string())
      used.insert(fs::absolute(j["texture"].get<std::string>()).lexically_normal().string());
    if (j.is_structured())
      for (const auto& e : j) visit(e);
  };
  for (const auto& [key, m] : s.materials) visit(to_json(m));
  std::vector<GltfImportFile> out;
  for (auto& f : files)
    if (used.count(fs::absolute(f.path).lexically_normal().string())) out.push_back(std::move(f));
  return out;
}

}  // namespace

Scene import_gltf(const std::string& path, const GltfImportOptions& options, std::vector<std::string>& notes,
                  std::vector<GltfImportFile>* files) {
  tinygltf::Model model = gltf_detail::load_model_file(path, notes);
  const std::string folder = fs::path(path).parent_path().string();
  Importer importer(model, path, folder.empty() ? "." : folder, options, notes);
  Scene s = importer.read();
  if (files) *files = used_files(s, importer.files());
  return s;
}

Scene import_gltf_data(const std::string& data, bool binary, const std::string& path, const std::string& folder,
                       const GltfImportOptions& options, std::vector<std::string>& notes,
                       std::vector<GltfImportFile>* files) {
  tinygltf::Model model = gltf_detail::load_model(data, binary, path, folder, notes);
  Importer importer(model, path, folder, options, notes);
  Scene s = importer.read();
  if (files) *files = used_files(s, importer.files());
  return s;
}

void write_import_files(const std::vector<GltfImportFile>& files) {
  std::vector<std::string> written;
  std::vector<fs::path> made;  // folders created, deepest last
  try {
    for (const auto& f : files) {
      fs::path folder = fs::path(f.path).parent_path();
      std::vector<fs::path> missing;
      for (fs::path p = folder; !p.empty() && !fs::exists(p); p = p.parent_path()) missing.push_back(p);
      for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        std::error_code ec;
        if (!fs::create_directory(*it, ec) && ec) throw IoError(it->string() + ": cannot create the folder (" + ec.message() + ")");
        made.push_back(*it);
      }
      write_file_atomic(f.path, f.bytes);
      written.push_back(f.path);
    }
  } catch (const IoError&) {
    std::error_code ec;
    for (const auto& w : written) fs::remove(w, ec);
    for (auto it = made.rbegin(); it != made.rend(); ++it) fs::remove(*it, ec);  // only if empty
    throw;
  }
}

void export_gltf(const Scene& s, const Material* fallback, const std::string& path, std::vector<std::string>& notes) {
  Exporter exporter(s, fallback, path, notes);
  exporter.add_scene();
  exporter.write(path);
}

}  // namespace facet
