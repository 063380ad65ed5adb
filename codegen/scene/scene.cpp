#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "catalog/checker.h"
#include "catalog/program.h"
#include "catalog/texture.h"
#include "core/text.h"
#include "scene/gltf.h"

namespace facet {

// ---------------------------------------------------------------- geometry

Camera::Basis Camera::basis() const {
  Basis b;
  b.forward = normalize(look_at - position);
  b.right = normalize(cross(b.forward, up));
  b.up = cross(b.right, b.forward);
  b.tan_half = orthographic ? height / 2 : std::tan(fov * M_PI / 360.0);
  return b;
}

Vec3 Camera::ray(int i, int j, int w, int h, Vec3* origin) const {
  // Pixel centres, as POV-Ray, Cycles (sample 0) and gl_FragCoord place them.
  Basis b = basis();
  double aspect = double(w) / double(h);
  double x = (2.0 * (i + 0.5) / w - 1.0) * b.tan_half * aspect;
  double y = (1.0 - 2.0 * (j + 0.5) / h) * b.tan_half;
  if (orthographic) {
    if (origin) *origin = position + b.right * x + b.up * y;
    return b.forward;
  }
  if (origin) *origin = position;
  return normalize(b.forward + b.right * x + b.up * y);
}

Vec3 Camera::toward_eye(const Vec3& p) const {
  return orthographic ? -normalize(look_at - position) : normalize(position - p);
}

void Light::toward(const Vec3& p, Vec3& l, double& distance) const {
  if (type == Type::Directional) {
    l = -direction;
    distance = std::numeric_limits<double>::infinity();
    return;
  }
  Vec3 d = position - p;
  distance = length(d);
  l = d / distance;
}

void Object::plane_axes(Vec3& u, Vec3& v) const {
  Vec3 c = cross(normal, Vec3(1, 0, 0));
  if (length(c) < 1e-6) c = cross(normal, Vec3(0, 0, 1));
  u = normalize(c);
  v = cross(normal, u);
}

bool Scene::has_own_materials() const {
  return !objects.empty() &&
         std::all_of(objects.begin(), objects.end(), [](const Object& o) { return !o.material.empty(); });
}

const Material& Scene::material_of(size_t i, const Material* fallback) const {
  const std::string& name = objects.at(i).material;
  if (!name.empty()) return materials.at(name);
  if (!fallback) throw std::invalid_argument("object \"" + objects[i].name + "\" has no material and none was given");
  return *fallback;
}

// ---------------------------------------------------------------- parsing

namespace {

const std::vector<std::string> kSceneKeys = {"$schema", "name",    "camera", "ambient",
                                             "exposure", "materials", "objects", "lights"};

// A scene's material: inline, or a file named relative to the scene file.
// Diagnostics name the scene file and the key path materials.NAME.….
void parse_materials(const json& doc, const std::string& file, Scene& s, DiagnosticSink& sink) {
  auto it = doc.find("materials");
  if (it == doc.end()) return;
  if (!it->is_object()) {
    sink.error("materials", "expected an object of named materials, found " + json_type_name(*it) +
                                "; allowed: {\"name\": a material object or a material file's path}");
    return;
  }
  for (const auto& [name, val] : it->items()) {
    std::string path = join_path("materials", name);
    try {
      if (val.is_string()) {
        std::filesystem::path f = val.get<std::string>();
        if (f.is_relative()) f = std::filesystem::path(file).parent_path() / f;
        Material m = load_material(f.string());
        if (m.name.empty()) m.name = name;
        s.materials[name] = m;
      } else if (val.is_object()) {
        Material m = parse_material(val, file);
        m.name = val.contains("name") ? m.name : name;
        s.materials[name] = m;
      } else {
        sink.error(path, "expected a material object or a material file's path, found " + json_type_name(val));
      }
    } catch (const InputError& e) {
      for (const auto& d : e.diagnostics()) {
        if (d.file == file) sink.error(d.path.empty() ? path : join_path(path, d.path), d.message);
        else sink.error(path, d.format());  // a problem inside the referenced file
      }
    }
  }
}

// The glTF mesh an object spec references, its file's path from the working directory.
MeshReference reference_of(const ModelSpec& o, const std::string& file) {
  MeshReference r;
  std::filesystem::path f = o.at("gltf").choice;
  if (f.is_relative()) f = std::filesystem::path(file).parent_path() / f;
  r.file = f.string();
  r.node = o.given.count("node") > 0;
  const Value& which = o.at(r.node ? "node" : "mesh");
  r.index = which.number >= 0 ? int64_t(which.number) : -1;
  r.name = which.choice;
  if (o.given.count("primitive")) r.primitive = int64_t(o.at("primitive").number);
  for (size_t set = 0; set < 2; ++set)
    if (o.given.count("texcoord" + std::to_string(set))) r.texcoords[set] = int64_t(o.at("texcoord" + std::to_string(set)).number);
  return r;
}

// The mesh of an object spec: the vertex arrays, checked against each other.
std::shared_ptr<Mesh> mesh_of(const ModelSpec& o, const std::string& path, DiagnosticSink& sink) {
  auto m = std::make_shared<Mesh>();
  for (const auto& p : o.at("positions").points) m->positions.push_back(Vec3(p[0], p[1], p[2]));
  // Normals are made unit; one already unit to rounding is kept as written, so that
  // a mesh written out (to_json, import-gltf --inline) reads back bit for bit.
  for (const auto& n : o.at("normals").points) {
    Vec3 v(n[0], n[1], n[2]);
    m->normals.push_back(std::fabs(length(v) - 1) <= 1e-15 ? v : normalize(v));
  }
  if (m->normals.size() != m->positions.size())
    sink.error(join_path(path, "normals"), fmt::format("has {} normals for {} positions; allowed: one per position",
                                                       m->normals.size(), m->positions.size()));
  const char* sets[] = {"texcoords", "texcoords1"};
  for (size_t set = 0; set < 2; ++set) {
    if (!o.given.count(sets[set])) continue;
    for (const auto& st : o.at(sets[set]).points) m->texcoords[set].push_back({st[0], st[1]});
    if (m->texcoords[set].size() != m->positions.size())
      sink.error(join_path(path, sets[set]), fmt::format("has {} coordinates for {} positions; allowed: one per position",
                                                         m->texcoords[set].size(), m->positions.size()));
  }
  if (o.given.count("tangents")) {
    const auto& tangents = o.at("tangents").points;
    for (size_t i = 0; i < tangents.size(); ++i) {
      if (std::fabs(tangents[i][3]) != 1) {
        sink.error(index_path(join_path(path, "tangents"), i),
                   fmt::format("w is {}; allowed: +1 or −1 (the bitangent's sign, B = w·(n × t))", tangents[i][3]));
        break;
      }
      m->tangents.push_back(tangents[i]);
    }
    if (m->tangents.size() == tangents.size() && m->tangents.size() != m->positions.size())
      sink.error(join_path(path, "tangents"), fmt::format("has {} tangents for {} positions; allowed: one per position",
                                                          m->tangents.size(), m->positions.size()));
  }
  if (o.given.count("colors")) {
    for (const auto& c : o.at("colors").points) m->colors.push_back(c);
    if (m->colors.size() != m->positions.size())
      sink.error(join_path(path, "colors"), fmt::format("has {} colours for {} positions; allowed: one per position",
                                                        m->colors.size(), m->positions.size()));
  }
  const auto& tris = o.at("triangles").points;
  for (size_t i = 0; i < tris.size(); ++i) {
    std::array<uint32_t, 3> t{};
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      if (tris[i][k] >= double(m->positions.size())) ok = false;
      else t[k] = uint32_t(tris[i][k]);
    }
    if (!ok) {
      sink.error(index_path(join_path(path, "triangles"), i),
                 fmt::format("an index is out of range; allowed: 0 to {}", m->positions.size() - 1));
      break;
    }
    m->triangles.push_back(t);
  }
  if (m->triangles.empty()) sink.error(join_path(path, "triangles"), "empty; a mesh needs a triangle");
  m->build_bvh();
  return m;
}

Vec3 vec(const ModelSpec& s, const char* key) { return Vec3(s.at(key).rgb); }

Attenuation attenuation_of(const ModelSpec& light) {
  Attenuation a;
  const ModelSpec& m = *light.at("attenuation").model;
  a.law = m.def->attenuation_law.value();
  if (a.law == Attenuation::Law::InverseSquareRange) a.range = m.at("range").number;
  if (a.law == Attenuation::Law::Polynomial) {
    a.constant = m.at("constant").number;
    a.linear = m.at("linear").number;
    a.quadratic = m.at("quadratic").number;
  }
  return a;
}

template <class F>
void each(const json& doc, const char* key, DiagnosticSink& sink, F fn) {
  auto it = doc.find(key);
  if (it == doc.end()) return;
  if (!it->is_array()) {
    sink.error(key, "expected an array, found " + json_type_name(*it));
    return;
  }
  for (size_t i = 0; i < it->size(); ++i) fn((*it)[i], index_path(key, i));
}

void check_keys(const json& doc, DiagnosticSink& sink) {
  for (const auto& [key, val] : doc.items()) {
    if (std::find(kSceneKeys.begin(), kSceneKeys.end(), key) == kSceneKeys.end()) {
      std::string hint = suggest(key, kSceneKeys);
      sink.error(key, fmt::format("unknown key{}; allowed keys: {}",
                                  hint.empty() ? "" : " (did you mean \"" + hint + "\"?)", quoted_list(kSceneKeys)));
    }
  }
}

void parse_name(const json& doc, Scene& s, DiagnosticSink& sink) {
  auto it = doc.find("name");
  if (it == doc.end()) return;
  if (it->is_string() && !it->get<std::string>().empty()) s.name = it->get<std::string>();
  else sink.error("name", "expected a non-empty string, found " + json_type_name(*it));
}

void parse_camera(const json& doc, Scene& s, DiagnosticSink& sink) {
  auto it = doc.find("camera");
  if (it == doc.end()) {
    sink.error("camera", "missing; allowed: an object with keys \"position\", \"look_at\", \"up\", \"fov\" (or "
                         "\"type\": \"orthographic\" and \"height\" instead of \"fov\")");
    return;
  }
  Checker check(sink);
  // A camera without "type" is perspective, as before there were two.
  auto c = it->is_object() && it->contains("type") ? check.model(*it, "camera", "camera", nullptr, "type")
                                                   : check.model(*it, "camera", "camera", find_model("camera", "perspective"));
  if (!c) return;
  s.camera.position = vec(*c, "position");
  s.camera.look_at = vec(*c, "look_at");
  s.camera.up = vec(*c, "up");
  s.camera.orthographic = c->values.count("height") > 0;
  if (s.camera.orthographic) s.camera.height = c->at("height").number;
  else s.camera.fov = c->at("fov").number;
  Vec3 f = s.camera.look_at - s.camera.position;
  if (length(f) == 0) sink.error("camera.look_at", "equals camera.position; the camera needs a direction");
  else if (length(cross(normalize(f), normalize(s.camera.up))) < 1e-6)
    sink.error("camera.up", "is parallel to the viewing direction; allowed: any other direction");
}

// The previews' exposure in stops (Scene::exposure): within ±kExposureMax, where 2^EV stays a
// float32 number far from its ends.
constexpr double kExposureMax = 40;

void parse_exposure(const json& doc, Scene& s, DiagnosticSink& sink) {
  auto it = doc.find("exposure");
  if (it == doc.end()) return;
  if (!it->is_number() || std::fabs(it->get<double>()) > kExposureMax)
    sink.error("exposure", fmt::format("{0}; allowed: a number of stops in [−{1:g}, {1:g}] (previews show radiance × "
                                       "2^exposure)",
                                       it->is_number() ? fmt::format("{:g} is out of range", it->get<double>())
                                                       : "expected a number, found " + json_type_name(*it),
                                       kExposureMax));
  else
    s.exposure = it->get<double>();
}

void parse_ambient(const json& doc, Scene& s, DiagnosticSink& sink) {
  auto it = doc.find("ambient");
  if (it == doc.end()) return;
  ParamDef p;
  p.kind = ParamKind::Color;
  p.range = Range::color();
  Checker check(sink);
  if (auto c = check.color(*it, "ambient", p)) s.ambient = *c;
}

// The checked object `o` at `path`, to be the scene's next: unnamed, it is named
// after its type and index. Its material must be a key of the scene's materials.
// A mesh that references a glTF file is read later, by `refs`.
Object object_of(const ModelSpec& o, const std::string& path, const Scene& s, GltfReferences& refs,
                 DiagnosticSink& sink) {
  Object obj;
  obj.name = o.at("name").choice;
  if (obj.name.empty()) obj.name = fmt::format("{}{}", o.def->name, s.objects.size());
  obj.material = o.at("material").choice;
  if (!obj.material.empty() && !s.materials.count(obj.material)) {
    std::vector<std::string> names;
    for (const auto& [k, v] : s.materials) names.push_back(k);
    sink.error(join_path(path, "material"),
               fmt::format("unknown material \"{}\"; allowed: a key of \"materials\"{}", obj.material,
                           names.empty() ? " (the scene has none)" : ": " + quoted_list(names)));
  }
  obj.type = o.def->object_type.value();
  switch (obj.type) {
    case Object::Type::Sphere:
      obj.center = vec(o, "center");
      obj.radius = o.at("radius").number;
      break;
    case Object::Type::Plane:
      obj.point = vec(o, "point");
      obj.normal = normalize(vec(o, "normal"));
      obj.size = o.at("size").number;
      break;
    case Object::Type::Mesh:
      if (o.given.count("gltf")) {
        obj.reference = reference_of(o, sink.file());
        refs.add(s.objects.size(), *obj.reference, path, sink);
      } else {
        obj.mesh = mesh_of(o, path, sink);
      }
      break;
  }
  return obj;
}

void parse_objects(const json& doc, Scene& s, DiagnosticSink& sink) {
  Checker check(sink);
  GltfReferences refs(sink.file());
  each(doc, "objects", sink, [&](const json& j, const std::string& path) {
    if (auto o = check.model(j, path, "object", nullptr, "type"))
      s.objects.push_back(object_of(*o, path, s, refs, sink));
  });
  refs.build(s.objects, sink);
  if (!doc.contains("objects")) sink.error("objects", "missing; allowed: an array of spheres and planes");
  else if (doc["objects"].is_array() && doc["objects"].empty()) sink.error("objects", "empty; a scene needs an object");
}

Light light_of(const ModelSpec& l, const std::string& path, DiagnosticSink& sink) {
  Light light;
  light.color = l.at("color").rgb;
  light.type = l.def->light_type.value();
  const bool positioned = light.type != Light::Type::Directional;  // point and spot lights
  if (positioned) light.position = vec(l, "position");
  if (light.type != Light::Type::Point) light.direction = normalize(vec(l, "direction"));
  if (positioned) light.attenuation = attenuation_of(l);
  if (light.type == Light::Type::Spot) {
    light.cutoff = l.at("cutoff").number;
    light.exponent = l.at("exponent").number;
  }
  const Attenuation& a = light.attenuation;
  if (a.law == Attenuation::Law::Polynomial && a.constant + a.linear + a.quadratic <= 0)
    sink.error(join_path(path, "attenuation"), "constant, linear and quadratic are all 0; one must be positive");
  return light;
}

void parse_lights(const json& doc, Scene& s, DiagnosticSink& sink) {
  Checker check(sink);
  each(doc, "lights", sink, [&](const json& j, const std::string& path) {
    if (auto l = check.model(j, path, "light", nullptr, "type")) s.lights.push_back(light_of(*l, path, sink));
  });
}

// Names are printed into the generated code's comments (core/text.h): each must be one line.
void check_names_one_line(const json& doc, const Scene& s, DiagnosticSink& sink) {
  auto check = [&](const std::string& path, const std::string& what, const std::string& name) {
    if (auto b = line_break(name))
      sink.error(path, fmt::format("\"{}\" {}; {} is one line of text (it is printed into the generated code's "
                                   "comments)",
                                   one_line(name), describe(*b), what));
  };
  check(doc.contains("name") ? "name" : "(file name)", "a scene's name", s.name);
  for (const auto& [key, m] : s.materials)  // (a material's own "name" its parser checks)
    check(join_path("materials", one_line(key)), "a material's key", key);
  for (size_t i = 0; i < s.objects.size(); ++i)
    check(join_path(index_path("objects", i), "name"), "an object's name", s.objects[i].name);
}

}  // namespace

Scene parse_scene(const json& doc, const std::string& file) {
  DiagnosticSink sink(file);
  Scene s;
  s.source = file;
  s.name = std::filesystem::path(file).stem().string();
  if (!doc.is_object()) {
    sink.error("", "expected a scene object, found " + json_type_name(doc) + "; allowed: an object with keys " +
                       quoted_list(kSceneKeys));
    sink.throw_if_any();
  }
  check_keys(doc, sink);
  parse_name(doc, s, sink);
  parse_camera(doc, s, sink);
  parse_materials(doc, file, s, sink);
  parse_ambient(doc, s, sink);
  parse_exposure(doc, s, sink);
  parse_objects(doc, s, sink);
  parse_lights(doc, s, sink);
  check_names_one_line(doc, s, sink);
  sink.throw_if_any();
  return s;
}

// ---------------------------------------------------------------- built-in scenes

namespace {

// `single`: the validation scene of the issue — one unit sphere, one point light.
// `shadows`: the sphere on a square, a point light with OpenGL attenuation and a
// directional light; a small sphere outside the view casts a shadow on the sphere.
const char* kSingle = R"({
  "name": "single",
  "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
  "ambient": [0.05, 0.05, 0.05],
  "objects": [{"type": "sphere", "name": "sphere", "center": [0, 0, 0], "radius": 1}],
  "lights": [{"type": "point", "position": [-3, 4, 5], "color": [1, 1, 1]}]
})";

const char* kShadows = R"({
  "name": "shadows",
  "camera": {"position": [0, 1.2, 4.5], "look_at": [0, -0.2, 0], "up": [0, 1, 0], "fov": 45},
  "ambient": [0.04, 0.04, 0.05],
  "objects": [
    {"type": "sphere", "name": "sphere", "center": [0, 0, 0], "radius": 1},
    {"type": "plane", "name": "floor", "point": [0, -1, 0], "normal": [0, 1, 0], "size": 2.5},
    {"type": "sphere", "name": "occluder", "center": [-1.41, 1.87, 2.49], "radius": 0.25}
  ],
  "lights": [
    {"type": "point", "position": [-3, 4, 5], "color": [1.1, 1.0, 0.9],
     "attenuation": {"constant": 1, "quadratic": 0.02}},
    {"type": "directional", "direction": [0.6, -1, -0.4], "color": [0.3, 0.32, 0.4]}
  ]
})";

}  // namespace

const std::vector<std::string>& builtin_scene_names() {
  static const std::vector<std::string> names = {"single", "shadows"};
  return names;
}

json builtin_scene_json(const std::string& name) {
  if (name == "single") return json::parse(kSingle);
  if (name == "shadows") return json::parse(kShadows);
  throw std::invalid_argument("no built-in scene " + name);
}

Scene load_scene(const std::string& name_or_path) {
  const auto& names = builtin_scene_names();
  if (std::find(names.begin(), names.end(), name_or_path) != names.end()) {
    Scene s = parse_scene(builtin_scene_json(name_or_path), name_or_path);
    s.source = "built-in";
    return s;
  }
  return parse_scene(read_json_file(name_or_path), name_or_path);
}

// Parsed once: OSL and POV-Ray generation ask for it on every material, and
// parsing and checking it took a quarter of generate()'s time.
void check_texture_sets(const Scene& s, const Material* fallback) {
  std::vector<Diagnostic> problems;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    if (o.type != Object::Type::Mesh) continue;
    if (o.material.empty() && !fallback) continue;  // reported where the material is needed
    const Material& m = s.material_of(i, fallback);
    // A frame the lobes alone read (glTF's anisotropy) is the mesh's own tangents where it brings
    // them (KHR_materials_anisotropy: the TBN's T is TANGENT; only where there is none are tangents
    // computed, from texture coordinates); a normal map samples its image there as well.
    const bool own_frame = !o.mesh->tangents.empty() && !m.normal_map && !m.coat_normal_map;
    if (const auto frame = m.frame_uv(); frame && o.mesh->texcoords[size_t(*frame)].empty() && !own_frame) {
      const size_t set = size_t(*frame);
      problems.push_back({s.source, index_path("objects", i),
                          fmt::format("mesh \"{}\" has no texture coordinates set {} ({}), whose tangent frame "
                                      "material \"{}\" reads at {} (its tangents come from them)",
                                      o.name, set, set == 0 ? "texcoords, glTF's TEXCOORD_0" : "texcoords1, glTF's TEXCOORD_1",
                                      m.name, m.frame_key())});
    }
    for (const auto& t : compile(m).textured) {
      if (!t.value.texture->has_image()) continue;  // the vertex colour alone reads no coordinates
      const size_t set = size_t(t.value.texture->uv);
      if (!o.mesh->texcoords[set].empty()) continue;
      problems.push_back({s.source, index_path("objects", i),
                          fmt::format("mesh \"{}\" has no texture coordinates set {} ({}), which material \"{}\" "
                                      "reads at {}.uv",
                                      o.name, set, set == 0 ? "texcoords, glTF's TEXCOORD_0" : "texcoords1, glTF's TEXCOORD_1",
                                      m.name, t.key)});
    }
  }
  if (!problems.empty()) throw InputError(problems);
}

Scene default_scene() {
  static const Scene single = load_scene("single");
  return single;
}

json to_json(const Scene& s) { return to_json(s, ""); }

namespace {

// `file` (from the working directory) as a path from `folder`; absolute where there is none.
std::string relative_to(const std::string& file, const std::string& folder) {
  namespace fs = std::filesystem;
  fs::path f = fs::absolute(file).lexically_normal();
  fs::path rel = f.lexically_relative(fs::absolute(folder.empty() ? "." : folder).lexically_normal());
  return rel.empty() ? f.generic_string() : rel.generic_string();
}

json mesh_json(const Object& o, const std::string& scene_file) {
  if (o.reference && !scene_file.empty()) {
    const MeshReference& r = *o.reference;
    json oj = {{"type", "mesh"}, {"name", o.name},
               {"gltf", relative_to(r.file, std::filesystem::path(scene_file).parent_path().string())}};
    oj[r.node ? "node" : "mesh"] = r.index >= 0 ? json(r.index) : json(r.name);
    if (r.primitive >= 0) oj["primitive"] = r.primitive;
    for (size_t set = 0; set < 2; ++set)
      if (r.texcoords[set] != int64_t(set)) oj["texcoord" + std::to_string(set)] = r.texcoords[set];
    return oj;
  }
  json pos = json::array(), nor = json::array(), tri = json::array();
  for (const auto& p : o.mesh->positions) pos.push_back(p.array());
  for (const auto& n : o.mesh->normals) nor.push_back(n.array());
  for (const auto& t : o.mesh->triangles) tri.push_back(t);
  json oj = {{"type", "mesh"}, {"name", o.name}, {"positions", pos}, {"normals", nor}, {"triangles", tri}};
  const char* sets[] = {"texcoords", "texcoords1"};
  for (size_t set = 0; set < 2; ++set)
    if (!o.mesh->texcoords[set].empty()) oj[sets[set]] = o.mesh->texcoords[set];
  if (!o.mesh->tangents.empty()) oj["tangents"] = o.mesh->tangents;
  if (!o.mesh->colors.empty()) oj["colors"] = o.mesh->colors;
  return oj;
}

}  // namespace

json to_json(const Scene& s, const std::string& scene_file) {
  json j;
  j["name"] = s.name;
  j["camera"] = {{"position", s.camera.position.array()},
                 {"look_at", s.camera.look_at.array()},
                 {"up", s.camera.up.array()}};
  if (s.camera.orthographic) {
    j["camera"]["type"] = "orthographic";
    j["camera"]["height"] = s.camera.height;
  } else {
    j["camera"]["fov"] = s.camera.fov;
  }
  j["ambient"] = s.ambient;
  if (s.exposure != 0) j["exposure"] = s.exposure;
  if (!s.materials.empty()) {
    j["materials"] = json::object();
    // Image paths relative to the file written (absolute in the canonical form, which may go anywhere).
    const std::string folder = std::filesystem::path(scene_file).parent_path().string();
    for (const auto& [name, m] : s.materials)
      j["materials"][name] = scene_file.empty() ? to_json(m) : relative_textures(to_json(m), folder);
  }
  j["objects"] = json::array();
  for (const auto& o : s.objects) {
    json oj;
    if (o.type == Object::Type::Sphere) {
      oj = {{"type", "sphere"}, {"name", o.name}, {"center", o.center.array()}, {"radius", o.radius}};
    } else if (o.type == Object::Type::Plane) {
      oj = {{"type", "plane"}, {"name", o.name}, {"point", o.point.array()}, {"normal", o.normal.array()},
            {"size", o.size}};
    } else {
      oj = mesh_json(o, scene_file);
    }
    if (!o.material.empty()) oj["material"] = o.material;
    j["objects"].push_back(oj);
  }
  j["lights"] = json::array();
  for (const auto& l : s.lights) {
    json lj;
    if (l.type == Light::Type::Point) lj = {{"type", "point"}, {"position", l.position.array()}};
    if (l.type == Light::Type::Directional) lj = {{"type", "directional"}, {"direction", l.direction.array()}};
    if (l.type == Light::Type::Spot)
      lj = {{"type", "spot"}, {"position", l.position.array()}, {"direction", l.direction.array()},
            {"cutoff", l.cutoff}, {"exponent", l.exponent}};
    lj["color"] = l.color;
    if (l.type != Light::Type::Directional) {
      const Attenuation& a = l.attenuation;
      if (a.law == Attenuation::Law::None) lj["attenuation"] = "none";
      if (a.law == Attenuation::Law::InverseSquare) lj["attenuation"] = "inverse_square";
      if (a.law == Attenuation::Law::Polynomial)
        lj["attenuation"] = {{"constant", a.constant}, {"linear", a.linear}, {"quadratic", a.quadratic}};
      if (a.law == Attenuation::Law::InverseSquareRange)
        lj["attenuation"] = {{"model", "inverse_square_range"}, {"range", a.range}};
    }
    j["lights"].push_back(lj);
  }
  return j;
}

namespace {

// Either camera, "type" naming it; a camera without "type" is perspective.
json camera_schema() {
  json alts = json::array();
  const auto cameras = section("camera");
  for (const auto* m : cameras) {
    json c = model_schema(*m, "type");
    if (m == cameras.front()) {  // the first, perspective, the default: "type" optional
      json required = json::array();
      for (const auto& r : c["required"])
        if (r != "type") required.push_back(r);
      c["required"] = required;
    }
    alts.push_back(c);
  }
  return {{"oneOf", alts}, {"description", "the camera: perspective (\"type\" may be left out) or orthographic"}};
}

}  // namespace

json scene_schema() {
  auto alternatives = [](const char* sec) {
    json alts = json::array();
    for (const auto* m : section(sec)) alts.push_back(model_schema(*m, "type"));
    return alts;
  };
  ParamDef ambient;
  ambient.kind = ParamKind::Color;
  ambient.range = Range::color();
  ambient.doc = "the scene's ambient colour A";
  json props = {{"$schema", {{"type", "string"}}},
                {"name", {{"type", "string"}, {"minLength", 1}}},
                {"camera", camera_schema()},
                {"ambient", param_schema(ambient)},
                {"exposure", {{"type", "number"},
                              {"minimum", -kExposureMax},
                              {"maximum", kExposureMax},
                              {"description", "previews show radiance × 2^exposure through the standard view "
                                              "transform (sRGB, clipped), as Blender's Film exposure; renderers "
                                              "ignore it"}}},
                {"materials", {{"type", "object"},
                               {"description", "named materials the objects refer to: material objects, or paths of "
                                               "material files relative to the scene file"},
                               {"additionalProperties", {{"oneOf", json::array({{{"type", "string"}},
                                                                                material_schema()})}}}}},
                {"objects", {{"type", "array"}, {"minItems", 1}, {"items", {{"oneOf", alternatives("object")}}}}},
                {"lights", {{"type", "array"}, {"items", {{"oneOf", alternatives("light")}}}}}};
  return {{"$schema", "https://json-schema.org/draft/2020-12/schema"},
          {"$id", "https://facet.invalid/schemas/scene.schema.json"},
          {"title", "facet scene"},
          {"description", "A scene for facet's renderers: right-handed, +y up. Generated by `facet schema --scene`."},
          {"type", "object"},
          {"properties", props},
          {"required", {"camera", "objects"}},
          {"additionalProperties", false}};
}

}  // namespace facet
