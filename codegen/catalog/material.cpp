#include "catalog/material.h"

#include "catalog/checker.h"
#include "catalog/texture.h"
#include "core/text.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

namespace facet {

using nlohmann::json;

namespace {

ParamDef material_color(const char* name, const char* doc) {
  ParamDef p;
  p.name = name;
  p.kind = ParamKind::Color;
  p.doc = doc;
  p.range = Range::color();
  p.fallback.kind = ParamKind::Color;
  return p;
}

// m_a and m_e: colours ≥ 0, each may come from an image.
ParamDef material_term_param(const char* name) {
  ParamDef p = material_color(name, std::string(name) == "ambient" ? "m_a, multiplied by the scene's ambient colour"
                                                                    : "m_e, emitted radiance");
  p.texturable = true;
  return p;
}

ParamDef tangent_axis_param() {
  ParamDef p;
  p.name = "tangent_axis";
  p.kind = ParamKind::Vector;
  p.doc = "axis the tangent field t = normalize(axis × n) circles (anisotropic models)";
  p.fallback.kind = ParamKind::Vector;
  p.fallback.rgb = {0, 1, 0};
  p.nonzero = true;
  p.range = Range::coordinate();
  return p;
}

const std::vector<std::string> kMaterialKeys = {"$schema",      "name",       "ambient",         "emission",
                                                "diffuse",      "specular",   "layers",          "tangent_axis",
                                                "normal_map",   "coat_normal_map", "alpha",      "alpha_cutoff"};

ParamDef alpha_cutoff_param() {
  ParamDef p;
  p.name = "alpha_cutoff";
  p.kind = ParamKind::Number;
  p.doc = "glTF's alphaMode MASK: the surface is there only where alpha ≥ alpha_cutoff (glTF's alphaCutoff); "
          "absent: opaque";
  p.range = Range::closed(0, 1);
  p.fallback.number = 0.5;
  return p;
}

// "alpha" and "alpha_cutoff" of `m` (the cut-out), from key `key`.
void parse_alpha(const std::string& key, const json& val, Material& m, Checker& check, DiagnosticSink& sink) {
  if (key == "alpha_cutoff") {
    if (auto c = check.ranged(val, key, alpha_cutoff_param())) m.alpha_cutoff = *c;
  } else if (val.is_object()) {  // {"texture": …, "channel": "a"}: factor × the image's channel
    if (val.contains("vertex_color")) {  // Cycles' shadow rays cannot read another mesh's vertex colour
      sink.error(key + ".vertex_color",
                 "a cut-out cannot take the vertex colour (no renderer cuts by a vertex alpha yet); "
                 "allowed: a number, or an image's channel × a factor");
      return;
    }
    if (auto v = parse_texture_value(val, key, alpha_param(), sink)) m.alpha = *v;
  } else if (auto c = check.ranged(val, key, alpha_param())) {
    m.alpha.number = *c;
  }
}

// "layers": a list of layer objects, the first lowest, each {"model": one of section "layer", …}.
void parse_layers(const json& val, Material& m, Checker& check, DiagnosticSink& sink) {
  std::vector<std::string> names;
  for (const auto* d : section("layer")) names.push_back(d->name);
  if (!val.is_array()) {
    sink.error("layers", fmt::format("expected a list of layers, the first lowest, found {}; allowed: [{{\"model\": "
                                     "…}}, …] with model one of {}",
                                     json_type_name(val), quoted_list(names)));
    return;
  }
  for (size_t i = 0; i < val.size(); ++i) {
    auto spec = check.model(val[i], fmt::format("layers[{}]", i), "layer", nullptr);
    if (!spec) continue;
    // A lobe inside a layer (mix) lives in the layer's function: what a lobe asks of the material
    // itself — a coat's normal and emission weight, a texture-coordinate frame — it cannot.
    for (const auto& [key, v] : spec->values) {
      const ModelDef* lobe = v.model ? v.model->def : nullptr;
      if (lobe && (lobe->section == "diffuse" || lobe->section == "specular") &&
          (lobe->coated || lobe->emission_weight || lobe->uv_tangent))
        sink.error(fmt::format("layers[{}].{}.model", i, key),
                   fmt::format("{} cannot be a layer's lobe: its coat, emission weight or tangent frame are the "
                               "material's (write it as the specular lobe instead)",
                               lobe->name));
    }
    m.layers.push_back(*spec);
  }
}

}  // namespace

std::optional<ModelSpec> gltf_brdf_lobe(const Material& m, std::string* why) {
  auto refuse = [&](std::string text) -> std::optional<ModelSpec> {
    if (why) *why = std::move(text);
    return std::nullopt;
  };
  if (m.diffuse || !m.specular || !m.specular->def->gltf_brdf) return refuse("");
  ModelSpec lobe = *m.specular;
  if (m.layers.empty()) return lobe;
  // A layer lies over k_s ⊗ ρ_s and its toon; glTF's parts lie inside them.
  const Value& k_s = lobe.at("color");
  if (k_s.texture || k_s.rgb != RGB{1, 1, 1}) return refuse("the specular colour k_s under its layers (not white)");
  if (auto toon = lobe.values.find("toon"); toon != lobe.values.end() && toon->second.model)
    return refuse("the toon modifier under its layers");
  auto on = [](const Value& v) { return v.texture || (v.kind == ParamKind::Color ? v.rgb != RGB{0, 0, 0} : v.number != 0); };
  int top = 0;  // the highest part of glTF's stack the lobe holds so far
  for (const ModelDef* part : section("layer"))  // its switch: the first parameter's counterpart
    if (!part->gltf_brdf_params.empty() && on(lobe.at(part->gltf_brdf_params[0].second)))
      top = std::max(top, part->gltf_brdf_stack);
  for (size_t i = 0; i < m.layers.size(); ++i) {
    const ModelSpec& layer = m.layers[i];
    const ModelDef& def = *layer.def;
    if (def.gltf_brdf_params.empty())
      return refuse(fmt::format("layers[{}] ({}), which is no part of glTF's BRDF", i, def.name));
    if (def.gltf_brdf_stack <= top)
      return refuse(fmt::format("layers[{}] ({}), which lies above a part that glTF's BRDF puts over it, or repeats "
                                "one",
                                i, def.name));
    top = def.gltf_brdf_stack;
    for (const auto& [from, to] : def.gltf_brdf_params) lobe.values[to] = layer.at(from);
  }
  return lobe;
}

bool Material::coated() const {
  auto coated = [](const ModelSpec& s) { return s.def->coated && s.def->coated(s); };
  return (specular && coated(*specular)) || std::any_of(layers.begin(), layers.end(), coated);
}

const ParamDef& alpha_param() {
  static const ParamDef p = [] {
    ParamDef a;
    a.name = "alpha";
    a.kind = ParamKind::Number;
    a.doc = "the coverage alpha_cutoff compares (glTF's base colour alpha): a number, or an image's channel × a factor";
    a.range = Range::closed(0, 1);
    a.texturable = true;
    a.fallback = Material::opaque_alpha();
    return a;
  }();
  return p;
}

Material parse_material(const json& doc, const std::string& file, const std::string& folder) {
  DiagnosticSink sink(file, folder);
  Checker check(sink);
  Material m;
  m.source = file;
  m.name = std::filesystem::path(file).stem().string();
  if (!doc.is_object()) {
    sink.error("", fmt::format("expected a material object, found {}; allowed: an object with keys {}",
                               json_type_name(doc), quoted_list(kMaterialKeys)));
    sink.throw_if_any();
  }
  for (const auto& [key, val] : doc.items()) {
    if (key == "$schema") {
      if (!val.is_string()) sink.error(key, "expected a string (the schema's URL or path)");
    } else if (key == "name") {
      if (!val.is_string() || val.get<std::string>().empty())
        sink.error(key, fmt::format("expected a non-empty string, found {}",
                                    val.is_string() ? "an empty string" : json_type_name(val)));
      else m.name = val.get<std::string>();
    } else if (key == "ambient" || key == "emission") {
      const bool ambient = key == "ambient";
      if (val.is_object()) {  // {"texture": …}: factor ⊗ the image's value
        auto v = parse_texture_value(val, key, material_term_param(key.c_str()), sink);
        if (v) (ambient ? m.ambient : m.emission) = v->rgb, (ambient ? m.ambient_texture : m.emission_texture) = v->texture;
      } else {
        auto c = check.color(val, key, material_color(key.c_str(), ""));
        if (c) (ambient ? m.ambient : m.emission) = *c;
      }
    } else if (key == "tangent_axis") {
      auto v = check.vector(val, key, tangent_axis_param());
      if (v) m.tangent_axis = *v;
    } else if (key == "normal_map") {
      m.normal_map = parse_normal_map(val, key, sink);
    } else if (key == "coat_normal_map") {
      m.coat_normal_map = parse_normal_map(val, key, sink);
    } else if (key == "alpha" || key == "alpha_cutoff") {
      parse_alpha(key, val, m, check, sink);
    } else if (key == "diffuse" || key == "specular") {
      auto spec = check.model(val, key, key, nullptr);
      if (spec) (key == "diffuse" ? m.diffuse : m.specular) = *spec;
    } else if (key == "layers") {
      parse_layers(val, m, check, sink);
    } else {
      std::string hint = suggest(key, kMaterialKeys);
      sink.error(key, fmt::format("unknown key{}; allowed keys: {}",
                                  hint.empty() ? "" : " (did you mean \"" + hint + "\"?)", quoted_list(kMaterialKeys)));
    }
  }
  if (!doc.contains("diffuse") && !doc.contains("specular"))
    sink.error("", "a material needs a \"diffuse\" or a \"specular\" lobe (or both)");
  if (m.coat_normal_map) {
    // The coat's map needs a coat, and shares the lobes' map's tangent frame (KHR_materials_clearcoat:
    // "these textures SHOULD use the same texture coordinates because they operate in the same
    // tangent space").
    if (!m.coated())
      sink.error("coat_normal_map", "the material has no layer with a normal of its own: a coat normal map needs a "
                                    "clear coat (specular: gltf_pbr with clearcoat above 0, or from an image; or a "
                                    "layer {\"model\": \"clearcoat\"} with its weight above 0)");
    if (m.normal_map && m.normal_map->texture().uv != m.coat_normal_map->texture().uv)
      sink.error("coat_normal_map.uv",
                 fmt::format("{} differs from normal_map.uv ({}): both maps turn on one tangent frame, of one texture "
                             "coordinate set",
                             m.coat_normal_map->texture().uv, m.normal_map->texture().uv));
  }
  if (auto b = line_break(m.name))  // printed into every target's comments (core/text.h)
    sink.error(doc.is_object() && doc.contains("name") ? "name" : "(file name)",
               fmt::format("\"{}\" {}; a material's name is one line of text (it is printed into the generated "
                           "code's comments)",
                           one_line(m.name), describe(*b)));
  sink.throw_if_any();
  return m;
}

Material load_material(const std::string& path) { return parse_material(read_json_file(path), path); }

Value material_term(const Material& m, bool ambient) {
  Value v;
  v.kind = ParamKind::Color;
  v.rgb = ambient ? m.ambient : m.emission;
  v.texture = ambient ? m.ambient_texture : m.emission_texture;
  return v;
}

Material lobe_material(const ModelSpec& spec, const std::string& name) {
  Material m;
  m.name = name;
  (spec.def->section == "diffuse" ? m.diffuse : m.specular) = spec;
  return m;
}

std::vector<Material> model_materials() {
  std::vector<Material> out;
  for (const auto& def : catalog())
    if (def.section == "diffuse" || def.section == "specular") out.push_back(lobe_material(default_spec(def), def.name));
  return out;
}

namespace {

json value_json(const Value& v);

}  // namespace

json spec_json(const ModelSpec& s, bool with_model) {
  json j = json::object();
  if (with_model) j["model"] = s.def->name;
  for (const auto& p : s.def->params) {
    auto it = s.values.find(p.name);
    if (it == s.values.end()) continue;
    if (p.kind == ParamKind::Object && !it->second.model) continue;
    j[p.name] = value_json(it->second);
  }
  return j;
}

namespace {

json value_json(const Value& v) {
  if (v.texture) return texture_json(v);
  switch (v.kind) {
    case ParamKind::Number: return v.number;
    case ParamKind::Bool: return v.flag;
    case ParamKind::Enum: return v.choice;
    case ParamKind::Color:
    case ParamKind::Vector: return json::array({v.rgb[0], v.rgb[1], v.rgb[2]});
    case ParamKind::Model: return spec_json(*v.model, true);
    case ParamKind::Object: return spec_json(*v.model, false);
    case ParamKind::String: return v.choice;
    case ParamKind::Points:
    case ParamKind::Triangles: {
      json list = json::array();
      for (const auto& e : v.points) list.push_back(std::vector<double>(e.begin(), e.begin() + v.arity));
      return list;
    }
    case ParamKind::Index: return v.number >= 0 ? json(int64_t(v.number)) : json(v.choice);
  }
  return nullptr;
}

}  // namespace

json default_json(const ParamDef& p) {
  const Value& v = p.fallback;
  switch (p.kind) {
    case ParamKind::Number: return v.number;
    case ParamKind::Bool: return v.flag;
    case ParamKind::Enum:
    case ParamKind::String: return v.choice;
    case ParamKind::Color:
    case ParamKind::Vector: return v.rgb;
    case ParamKind::Model: return v.model ? spec_json(*v.model) : json(nullptr);
    case ParamKind::Object:
    case ParamKind::Points:
    case ParamKind::Triangles:
    case ParamKind::Index: return nullptr;
  }
  return nullptr;
}

json to_json(const Material& m) {
  json j = json::object();
  j["name"] = m.name;
  j["ambient"] = value_json(material_term(m, true));
  j["emission"] = value_json(material_term(m, false));
  if (m.diffuse) j["diffuse"] = spec_json(*m.diffuse, true);
  if (m.specular) j["specular"] = spec_json(*m.specular, true);
  if (!m.layers.empty()) {
    j["layers"] = json::array();
    for (const auto& l : m.layers) j["layers"].push_back(spec_json(l, true));
  }
  j["tangent_axis"] = m.tangent_axis;
  if (m.normal_map) j["normal_map"] = normal_map_json(*m.normal_map);
  if (m.coat_normal_map) j["coat_normal_map"] = normal_map_json(*m.coat_normal_map);
  if (m.alpha.texture || m.alpha.number != 1) j["alpha"] = value_json(m.alpha);
  if (m.alpha_cutoff) j["alpha_cutoff"] = *m.alpha_cutoff;
  return j;
}

// ---------------------------------------------------------------- schema

namespace {

json number_schema(const Range& r) {
  json s = {{"type", "number"}};
  if (std::isfinite(r.min)) s[r.min_open ? "exclusiveMinimum" : "minimum"] = r.min;
  if (std::isfinite(r.max)) s[r.max_open ? "exclusiveMaximum" : "maximum"] = r.max;
  return s;
}

}  // namespace

json param_schema(const ParamDef& p) {
  json s;
  switch (p.kind) {
    case ParamKind::Number:
      s = number_schema(p.range);
      s["default"] = p.fallback.number;
      break;
    case ParamKind::Bool:
      s = {{"type", "boolean"}, {"default", p.fallback.flag}};
      break;
    case ParamKind::Enum:
      s = {{"enum", p.choices}, {"default", p.fallback.choice}};
      break;
    case ParamKind::String:
      s = {{"type", "string"}, {"minLength", 1}};
      break;
    case ParamKind::Points:
    case ParamKind::Triangles: {
      json item = p.kind == ParamKind::Points ? number_schema(p.range) : json{{"type", "integer"}};
      if (p.kind == ParamKind::Triangles) item["minimum"] = 0;
      const int n = p.kind == ParamKind::Points ? p.arity : 3;
      s = {{"type", "array"}, {"items", {{"type", "array"}, {"items", item}, {"minItems", n}, {"maxItems", n}}}};
      break;
    }
    case ParamKind::Index: {
      json index = {{"type", "integer"}, {"minimum", 0}};
      s = p.by_name ? json{{"oneOf", json::array({index, {{"type", "string"}, {"minLength", 1}}})}} : index;
      break;
    }
    case ParamKind::Color: {
      json comp = number_schema(p.range);
      s = {{"oneOf", json::array({comp, {{"type", "array"}, {"items", comp}, {"minItems", 3}, {"maxItems", 3}}})}};
      s["default"] = p.fallback.rgb;
      break;
    }
    case ParamKind::Vector:
      s = {{"type", "array"}, {"items", number_schema(p.range)}, {"minItems", 3}, {"maxItems", 3}};
      if (p.nonzero) s["not"] = {{"items", {{"const", 0}}}};
      s["default"] = p.fallback.rgb;
      break;
    case ParamKind::Model: {
      json alts = json::array();
      if (!p.fixed.empty()) {  // shorthand: a parameterless model's name, or the fixed model's object
        json names = json::array();
        for (const auto* m : section(p.section))
          if (m->params.empty()) names.push_back(m->name);
        alts.push_back({{"enum", names}});
        alts.push_back(model_schema(*find_model(p.section, p.fixed), ""));
      } else {
        for (const auto* m : section(p.section)) alts.push_back(model_schema(*m, "model"));
      }
      s = {{"oneOf", alts}};
      break;
    }
    case ParamKind::Object:
      s = model_schema(*find_model(p.section, p.fixed), "");
      break;
  }
  if (p.texturable) {
    // The value itself, or {"texture": …} (catalog/texture.h).
    json def = s.contains("default") ? s["default"] : json();
    s.erase("default");
    s = {{"anyOf", json::array({s, texture_schema(p.kind == ParamKind::Color, p.range)})}};
    if (!def.is_null()) s["default"] = def;
  }
  s["description"] = p.doc;
  return s;
}

namespace {

// Exactly one of the model's forms: its keys present, every other form's keys absent.
json forms_schema(const ModelDef& m) {
  json alts = json::array();
  for (const auto& f : m.forms) {
    json absent = json::object();
    for (const auto& other : m.forms)
      for (const auto* keys : {&other.keys, &other.optional})
        for (const auto& k : *keys)
          if (std::find(f.keys.begin(), f.keys.end(), k) == f.keys.end() &&
              std::find(f.optional.begin(), f.optional.end(), k) == f.optional.end())
            absent[k] = false;
    alts.push_back({{"description", f.what}, {"required", f.keys}, {"properties", absent}});
  }
  return alts;
}

}  // namespace

json model_schema(const ModelDef& m, const std::string& key) {
  json props = json::object();
  json required = json::array();
  if (!key.empty()) {
    props[key] = {{"const", m.name}};
    required.push_back(key);
  }
  for (const auto& p : m.params) {
    props[p.name] = param_schema(p);
    if (p.required) required.push_back(p.name);
  }
  json s = {{"type", "object"}, {"properties", props}, {"required", required}, {"additionalProperties", false}};
  if (!m.forms.empty()) s["oneOf"] = forms_schema(m);
  s["title"] = m.title;
  if (!m.citation.empty()) s["description"] = m.citation + ". " + m.formula;
  return s;
}

json material_schema() {
  json lobes = json::object();
  for (const char* sec : {"diffuse", "specular"}) {
    json alts = json::array();
    for (const auto* m : section(sec)) alts.push_back(model_schema(*m, "model"));
    lobes[sec] = {{"oneOf", alts}, {"description", std::string("the ") + sec + " lobe"}};
  }
  json layers = json::array();
  for (const auto* m : section("layer")) layers.push_back(model_schema(*m, "model"));
  json ambient = param_schema(material_term_param("ambient")), emission = param_schema(material_term_param("emission"));
  json props = {{"$schema", {{"type", "string"}}},
                {"name", {{"type", "string"}, {"minLength", 1}, {"description", "the material's name"}}},
                {"ambient", ambient},
                {"emission", emission},
                {"diffuse", lobes["diffuse"]},
                {"specular", lobes["specular"]},
                {"layers",
                 {{"type", "array"},
                  {"items", {{"oneOf", layers}}},
                  {"description", "layers over the lobes, the first lowest: each weights what lies under it by what "
                                  "it reflects itself"}}},
                {"tangent_axis", param_schema(tangent_axis_param())},
                {"normal_map", normal_map_schema()},
                {"coat_normal_map", coat_normal_map_schema()},
                {"alpha", param_schema(alpha_param())},
                {"alpha_cutoff", param_schema(alpha_cutoff_param())}};
  return {{"$schema", "https://json-schema.org/draft/2020-12/schema"},
          {"$id", "https://facet.invalid/schemas/material.schema.json"},
          {"title", "facet material"},
          {"$defs", texture_schema_defs()},
          {"description", "One material for facet: a diffuse and/or a specular lobe from the model catalog "
                          "(MODELS.md), with ambient and emissive colours. Generated by `facet schema`."},
          {"type", "object"},
          {"properties", props},
          {"additionalProperties", false},
          {"anyOf", json::array({{{"required", {"diffuse"}}}, {{"required", {"specular"}}}})}};
}

std::string identifier(const std::string& name) {
  std::string s;
  for (unsigned char c : name) s += std::isalnum(c) ? char(c) : '_';
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) s = "m_" + s;
  if (s.size() > kIdentifierMax) {  // a file name's limit is 255 bytes; keep names apart by a hash of the whole
    uint64_t h = 14695981039346656037ull;  // FNV-1a
    for (unsigned char c : name) h = (h ^ c) * 1099511628211ull;
    s = fmt::format("{}_{:016x}", s.substr(0, kIdentifierMax - 17), h);
  }
  return s;
}

}  // namespace facet
