#include "catalog/catalog.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "catalog/catalog_internal.h"

namespace facet {

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  if (min_open ? !(v > min) : !(v >= min)) return false;
  if (max_open ? !(v < max) : !(v <= max)) return false;
  return true;
}

std::string Range::describe() const {
  bool lo = std::isfinite(min), hi = std::isfinite(max);
  if (!lo && !hi) return "any number";
  if (lo && !hi) return fmt::format("{} {}", min_open ? ">" : "≥", min);
  if (!lo && hi) return fmt::format("{} {}", max_open ? "<" : "≤", max);
  return fmt::format("in {}{}, {}{}", min_open ? "(" : "[", min, max, max_open ? ")" : "]");
}

const char* param_kind_name(ParamKind k) {
  switch (k) {
    case ParamKind::Number: return "number";
    case ParamKind::Bool: return "boolean";
    case ParamKind::Enum: return "string";
    case ParamKind::Color: return "color";
    case ParamKind::Vector: return "vector";
    case ParamKind::Model: return "model";
    case ParamKind::Object: return "object";
    case ParamKind::String: return "string";
    case ParamKind::Points: return "points";
    case ParamKind::Triangles: return "triangles";
    case ParamKind::Index: return "index";
  }
  return "?";
}

const char* level_name(Equivalence::Level l) {
  switch (l) {
    case Equivalence::Level::Exact: return "exact";
    case Equivalence::Level::Approximate: return "approximate";
    case Equivalence::Level::None: return "none";
  }
  return "?";
}

std::string ParamDef::allowed() const {
  // A texturable parameter also takes an image; texels are clamped to the range (catalog/texture.h).
  const std::string image = texturable ? ", or an image {\"texture\": file, …} whose values are clamped to that range" : "";
  switch (kind) {
    case ParamKind::Number: return "a number " + range.describe() + image;
    case ParamKind::Bool: return "true or false";
    case ParamKind::Enum: {
      std::string s = "one of";
      for (size_t i = 0; i < choices.size(); ++i) s += (i ? ", \"" : " \"") + choices[i] + "\"";
      return s;
    }
    case ParamKind::Color:
      return "an RGB array [r, g, b] or one number for grey, each " + range.describe() + image;
    case ParamKind::Vector:
      return std::string(nonzero ? fmt::format("an array of three numbers, one of them at least {} in size",
                                               kShortestDirection)
                                 : "an array of three numbers") + ", each " +
             range.describe();
    case ParamKind::Model: {
      if (!fixed.empty()) {  // the shorthand form (attenuation)
        std::string s;
        for (const auto* m : facet::section(section))
          if (m->params.empty()) s += (s.empty() ? "\"" : ", \"") + m->name + "\"";
        const ModelDef* m = find_model(section, fixed);
        s += ", or an object with keys";
        for (size_t i = 0; m && i < m->params.size(); ++i) s += (i ? ", \"" : " \"") + m->params[i].name + "\"";
        return s;
      }
      std::string s = "an object {\"model\": …} with model one of";
      auto models = facet::section(section);
      for (size_t i = 0; i < models.size(); ++i) s += (i ? ", \"" : " \"") + models[i]->name + "\"";
      return s;
    }
    case ParamKind::String: return "a non-empty string";
    case ParamKind::Points:
      if (arity == 2) return "an array of [u, v], each " + range.describe();
      return std::string(nonzero ? fmt::format("an array of [x, y, z], each with a component at least {} in size",
                                               kShortestDirection)
                                 : "an array of [x, y, z]") + ", each " +
             range.describe();
    case ParamKind::Triangles: return "an array of [a, b, c], indices of distinct vertices";
    case ParamKind::Index: return by_name ? "an index (a whole number ≥ 0) or a name" : "an index (a whole number ≥ 0)";
    case ParamKind::Object: {
      std::string s = "an object with keys";
      const ModelDef* m = find_model(section, fixed);
      for (size_t i = 0; m && i < m->params.size(); ++i) s += (i ? ", \"" : " \"") + m->params[i].name + "\"";
      return s;
    }
  }
  return "?";
}

std::string ModelDef::forms_text() const {
  std::string s = "one of: ";
  for (size_t i = 0; i < forms.size(); ++i) {
    const ParamForm& f = forms[i];
    s += (i ? "; " : "") + f.what + " (";
    for (size_t k = 0; k < f.keys.size(); ++k) s += (k ? ", \"" : "\"") + f.keys[k] + "\"";
    for (const auto& k : f.optional) s += ", optional \"" + k + "\"";
    s += ")";
  }
  return s;
}

const ParamDef* ModelDef::param(const std::string& name) const {
  for (const auto& p : params)
    if (p.name == name) return &p;
  return nullptr;
}

const Value& ModelSpec::at(const std::string& name) const {
  auto it = values.find(name);
  if (it == values.end())
    throw std::logic_error("facet: " + (def ? def->name : std::string("?")) + " has no value for " + name);
  return it->second;
}

const char* input_name(Input i) {
  switch (i) {
    case Input::NoL: return "NoL";
    case Input::NoV: return "NoV";
    case Input::LoV: return "LoV";
    case Input::LoT: return "LoT";
    case Input::VoT: return "VoT";
    case Input::LoB: return "LoB";
    case Input::VoB: return "VoB";
    case Input::NoH: return "NoH";
    case Input::VoH: return "VoH";
    case Input::HoT: return "HoT";
    case Input::HoB: return "HoB";
    case Input::CoL: return "CoL";
    case Input::CoV: return "CoV";
    case Input::CoH: return "CoH";
  }
  return "?";
}

const std::vector<std::string>& input_order() {
  static const std::vector<std::string> order = {"NoL", "NoV", "LoV", "LoT", "VoT", "LoB", "VoB",
                                                  "NoH", "VoH", "HoT", "HoB", "CoL", "CoV", "CoH"};
  return order;
}

// ---------------------------------------------------------------- LobeContext

LobeContext::LobeContext(const ModelSpec& spec, std::string lobe, ir::FunctionBuilder& fb, bool coat_normal,
                         std::string key)
    : spec_(spec), lobe_(std::move(lobe)), fb_(fb), coat_normal_(coat_normal), key_(key.empty() ? lobe_ : key) {}

LobeContext::LobeContext(const ModelSpec& spec, std::string lobe, LobeContext& parent, std::string key)
    : spec_(spec), lobe_(std::move(lobe)), fb_(parent.fb_), coat_normal_(parent.coat_normal_), key_(std::move(key)),
      textured_(parent.textured_) {}

ir::Expr LobeContext::input(Input i) { return fb_.param(input_name(i)); }

ir::Expr LobeContext::NoH() {
  // n·h ≤ 1 for unit vectors, but rounding can go a hair above, where tan²θ_h < 0
  // or (n·h)²(α² − 1) + 1 < α² would follow; the min keeps it at 1.
  return ir::min(input(Input::NoH), 1.0);
}

ir::Expr LobeContext::VoH() {
  // v·h ≥ 0 (h bisects l and v); the bracket keeps rounding from making it negative.
  return ir::pos(input(Input::VoH));
}

bool LobeContext::has(const std::string& param) const { return spec_.values.count(param) > 0; }

ir::Expr LobeContext::number(const std::string& param) { return parameter(spec_, param, lobe_ + "_" + param); }

bool LobeContext::textured(const ModelSpec& spec, const std::string& param) const {
  return spec.at(param).texture != nullptr;
}

ir::Expr LobeContext::parameter(const ModelSpec& spec, const std::string& param, const std::string& name, bool grey) {
  const Value& v = spec.at(param);
  if (v.texture) {
    const ParamDef* def = spec.def->param(param);
    ir::Type type = v.kind == ParamKind::Color ? ir::Type::Color : ir::Type::Float;
    auto known = std::find_if(textured_->begin(), textured_->end(), [&](const TexturedInput& t) { return t.name == name; });
    if (known == textured_->end()) {
      // The key path: the lobe's own parameter, or a sub-model's (fresnel_f0 → fresnel.f0).
      std::string rest = name.substr(lobe_.size() + 1);
      if (&spec != &spec_) rest[rest.find('_')] = '.';
      textured_->push_back({name, key_ + "." + rest, type, v, def ? def->range : Range{}, ""});
    }
    return fb_.param(name, type);
  }
  if (v.kind != ParamKind::Color) return ir::constant(name, v.number);
  if (grey && v.rgb[0] == v.rgb[1] && v.rgb[1] == v.rgb[2]) return ir::constant(name, v.rgb[0]);
  return ir::constant(name, v.rgb);
}

ir::Expr LobeContext::max_of(const ModelSpec& spec, const std::string& param, const std::string& name) {
  const Value& v = spec.at(param);
  if (!v.texture) return ir::constant(name + "_max", std::max({v.rgb[0], v.rgb[1], v.rgb[2]}));
  parameter(spec, param, name);  // the colour, sampled first
  const std::string derived = name + "_max";
  auto known = std::find_if(textured_->begin(), textured_->end(), [&](const TexturedInput& t) { return t.name == derived; });
  if (known == textured_->end()) {
    const TexturedInput& colour =
        *std::find_if(textured_->begin(), textured_->end(), [&](const TexturedInput& t) { return t.name == name; });
    TexturedInput d = colour;
    d.name = derived;
    d.type = ir::Type::Float;
    d.max_of = name;
    textured_->push_back(d);
  }
  return fb_.param(derived, ir::Type::Float);
}

bool LobeContext::flag(const std::string& param) const { return spec_.at(param).flag; }
const std::string& LobeContext::choice(const std::string& param) const { return spec_.at(param).choice; }
const ModelSpec& LobeContext::model(const std::string& param) const {
  const Value& v = spec_.at(param);
  if (!v.model) throw std::logic_error("facet: " + param + " holds no model");
  return *v.model;
}

ir::Expr LobeContext::fresnel() {
  const ModelSpec& f = model("fresnel");
  const std::string& name = f.def->name;
  if (name == "none") return 1.0;
  if (name == "schlick") {
    // A grey f0 is one number: F stays scalar until k ⊗ ρ. Schlick's term clamps
    // its own base, so v·h goes in without the bracket.
    ir::Expr c = parameter(f, "f0", lobe_ + "_fresnel_f0", true);
    return ir::call(terms::fresnel_schlick(c.type()), {c, input(Input::VoH)});
  }
  if (name == "exact") {
    // An image may give η on either side of 1: the form with total internal reflection then.
    double ior = f.at("ior").number;
    bool tir = textured(f, "ior") || ior <= 1;
    return ir::call(tir ? terms::fresnel_exact_tir() : terms::fresnel_exact(),
                    {parameter(f, "ior", lobe_ + "_fresnel_ior"), VoH()});
  }
  throw std::logic_error("facet: unknown Fresnel model " + name);
}

ir::Expr lobe_rho(LobeContext& ctx) {
  const ModelSpec& spec = ctx.spec();
  ir::Expr rho = spec.def->build(ctx);
  auto toon = spec.values.find("toon");
  if (toon != spec.values.end() && toon->second.model) {
    const ModelSpec& t = *toon->second.model;
    const std::string& lobe = ctx.lobe();
    ir::Expr cutoff = ctx.parameter(t, "cutoff", lobe + "_toon_cutoff");
    double width = t.at("width").number;
    if (width > 0) {
      rho = ir::call(terms::toon(rho.type()), {rho, cutoff, ir::constant(lobe + "_toon_width", width)});
    } else {
      rho = ir::call(terms::toon_hard(rho.type()), {rho, cutoff});
    }
  }
  return rho;
}

ir::Expr LobeContext::geometry() {
  const std::string& g = choice("geometry");
  if (g == "none") return 1.0;
  if (g == "v_cavity") {
    return ir::call(terms::geometry_v_cavity(), {NoL(), NoV(), NoH(), VoH()});
  }
  throw std::logic_error("facet: unknown geometry term " + g);
}

// ---------------------------------------------------------------- registry

namespace {

// Model- and Object-kind parameters name their models by section and name;
// once every ModelDef is in place, resolve those names and fill their defaults.
void resolve_defaults(std::vector<ModelDef>& all) {
  auto find = [&](const std::string& sec, const std::string& name) -> const ModelDef* {
    for (const auto& m : all)
      if (m.section == sec && m.name == name) return &m;
    return nullptr;
  };
  for (auto& m : all) {
    for (auto& p : m.params) {
      if (p.kind != ParamKind::Model && p.kind != ParamKind::Object) continue;
      if (!p.fallback.model) continue;  // an optional object: absent means "off"
      const std::string& name = p.kind == ParamKind::Model ? p.fallback.choice : p.fixed;
      const ModelDef* def = find(p.section, name);
      if (!def) throw std::logic_error("facet catalog: " + m.name + "." + p.name + " names unknown " + name);
      auto spec = std::make_shared<ModelSpec>(*p.fallback.model);
      spec->def = def;
      for (const auto& sub : def->params)
        if (!spec->values.count(sub.name)) spec->values[sub.name] = sub.fallback;
      p.fallback.model = spec;
    }
  }
}

// The shading parameters (the lobes', their Fresnel terms' and modifiers' numbers and
// colours) may come from an image; the lights', the camera's and the objects' may not.
void mark_texturable(std::vector<ModelDef>& all) {
  for (auto& m : all) {
    if (m.section != "diffuse" && m.section != "specular" && m.section != "layer" && m.section != "fresnel" &&
        m.section != "modifier")
      continue;
    for (auto& p : m.params) {
      // Toon's width 0 selects the hard step when the code is generated: it stays a number.
      if (m.name == "toon" && p.name == "width") continue;
      // gltf_pbr folds the anisotropy's rotation into constants (catalog/specular.cpp): glTF
      // gives it no image; max₃ of specular_color and sheen_color it takes from their sampled
      // values where they are images (LobeContext::max_of), the sheen albedo's fit at a sampled
      // sheen_roughness it sums at every pixel (gltf_sheen).
      if (m.name == "gltf_pbr" && p.name == "anisotropy_rotation") continue;
      p.texturable = p.kind == ParamKind::Number || p.kind == ParamKind::Color;
    }
  }
}

std::vector<ModelDef> build_catalog() {
  std::vector<ModelDef> all;
  catalog_detail::add_diffuse(all);
  catalog_detail::add_specular(all);
  catalog_detail::add_layers(all);
  catalog_detail::add_terms(all);
  catalog_detail::add_lights(all);
  catalog_detail::add_scene_vocabulary(all);
  mark_texturable(all);
  resolve_defaults(all);
  return all;
}

}  // namespace

const std::vector<ModelDef>& catalog() {
  static const std::vector<ModelDef> all = build_catalog();
  return all;
}

ModelSpec default_spec(const ModelDef& def) {
  ModelSpec s;
  s.def = &def;
  for (const auto& p : def.params)
    if (p.kind != ParamKind::Object || p.fallback.model) s.values[p.name] = p.fallback;
  return s;
}

const ModelDef* find_model(const std::string& sec, const std::string& name) {
  for (const auto& m : catalog())
    if (m.section == sec && m.name == name) return &m;
  return nullptr;
}

std::vector<const ModelDef*> section(const std::string& name) {
  std::vector<const ModelDef*> out;
  for (const auto& m : catalog())
    if (m.section == name) out.push_back(&m);
  return out;
}

const ModelDef& cost_baseline_model() { return *find_model("diffuse", "lambert"); }

}  // namespace facet
