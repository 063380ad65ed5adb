// Helpers for writing catalog entries; private to codegen/catalog/.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "catalog/catalog.h"

namespace facet::catalog_detail {

void add_diffuse(std::vector<ModelDef>& all);
void add_specular(std::vector<ModelDef>& all);
void add_layers(std::vector<ModelDef>& all);  // what a material lays over its lobes (Material::layers)
void add_terms(std::vector<ModelDef>& all);   // fresnel, geometry, distribution, modifiers, ambient, emission
void add_lights(std::vector<ModelDef>& all);  // lights and attenuation laws
void add_scene_vocabulary(std::vector<ModelDef>& all);  // camera and objects

inline ParamDef number(std::string name, std::string doc, Range range, double start, bool required = true) {
  ParamDef p;
  p.name = std::move(name);
  p.kind = ParamKind::Number;
  p.doc = std::move(doc);
  p.range = range;
  p.required = required;
  p.fallback.kind = ParamKind::Number;
  p.fallback.number = start;
  return p;
}

inline ParamDef text(std::string name, std::string doc) {
  ParamDef p;
  p.name = std::move(name);
  p.kind = ParamKind::String;
  p.doc = std::move(doc);
  p.fallback.kind = ParamKind::String;
  return p;
}

inline ParamDef list(std::string name, std::string doc, ParamKind kind, bool nonzero = false) {
  ParamDef p;
  p.name = std::move(name);
  p.kind = kind;
  p.doc = std::move(doc);
  p.required = true;
  p.nonzero = nonzero;
  if (kind == ParamKind::Points) p.range = Range::coordinate();
  p.fallback.kind = kind;
  return p;
}

// An optional index into something (a glTF file's meshes), or also its name (`by_name`).
inline ParamDef index(std::string name, std::string doc, bool by_name) {
  ParamDef p;
  p.name = std::move(name);
  p.kind = ParamKind::Index;
  p.doc = std::move(doc);
  p.by_name = by_name;
  p.fallback.kind = ParamKind::Index;
  p.fallback.number = -1;
  return p;
}

inline ParamDef flag(std::string name, std::string doc, bool fallback) {
  ParamDef p;
  p.name = std::move(name);
  p.kind = ParamKind::Bool;
  p.doc = std::move(doc);
  p.fallback.kind = ParamKind::Bool;
  p.fallback.flag = fallback;
  return p;
}

inline ParamDef choice(std::string name, std::string doc, std::vector<std::string> choices, std::string fallback) {
  ParamDef p;
  p.name = std::move(name);
  p.kind = ParamKind::Enum;
  p.doc = std::move(doc);
  p.choices = std::move(choices);
  p.fallback.kind = ParamKind::Enum;
  p.fallback.choice = std::move(fallback);
  return p;
}

inline ParamDef color(std::string name, std::string doc, Range range, std::array<double, 3> fallback,
                      bool required = false) {
  ParamDef p;
  p.name = std::move(name);
  p.kind = ParamKind::Color;
  p.doc = std::move(doc);
  p.range = range;
  p.required = required;
  p.fallback.kind = ParamKind::Color;
  p.fallback.rgb = fallback;
  return p;
}

inline ParamDef vector(std::string name, std::string doc, std::array<double, 3> fallback, bool required = false,
                       bool nonzero = false) {
  ParamDef p;
  p.nonzero = nonzero;
  p.name = std::move(name);
  p.kind = ParamKind::Vector;
  p.doc = std::move(doc);
  p.range = Range::coordinate();
  p.required = required;
  p.fallback.kind = ParamKind::Vector;
  p.fallback.rgb = fallback;
  return p;
}

// {"model": <one of section>, …}; `fallback` names the default model, with
// `values` overriding that model's own defaults.
inline ParamDef model(std::string name, std::string doc, std::string section, std::string fallback,
                      std::map<std::string, Value> values = {}) {
  ParamDef p;
  p.name = std::move(name);
  p.kind = ParamKind::Model;
  p.doc = std::move(doc);
  p.section = std::move(section);
  p.fallback.kind = ParamKind::Model;
  p.fallback.choice = std::move(fallback);
  auto spec = std::make_shared<ModelSpec>();
  spec->values = std::move(values);
  p.fallback.model = spec;
  return p;
}

// An optional object holding the parameters of the model `section`/`fixed`;
// absent means the feature is off.
inline ParamDef object(std::string name, std::string doc, std::string section, std::string fixed) {
  ParamDef p;
  p.name = std::move(name);
  p.kind = ParamKind::Object;
  p.doc = std::move(doc);
  p.section = std::move(section);
  p.fixed = std::move(fixed);
  p.fallback.kind = ParamKind::Object;
  return p;
}

inline Value number_value(double v) {
  Value x;
  x.kind = ParamKind::Number;
  x.number = v;
  return x;
}

inline Value color_value(double v) {
  Value x;
  x.kind = ParamKind::Color;
  x.rgb = {v, v, v};
  return x;
}

inline Equivalence exact(std::string note) { return {Equivalence::Level::Exact, std::move(note)}; }
inline Equivalence approximate(std::string note) { return {Equivalence::Level::Approximate, std::move(note)}; }
inline Equivalence none(std::string note) { return {Equivalence::Level::None, std::move(note)}; }
inline BlenderNodes nodes_exact(std::string nodes) { return {Equivalence::Level::Exact, std::move(nodes), 0.0}; }
inline BlenderNodes nodes_approximate(std::string nodes, double measured_error) {
  return {Equivalence::Level::Approximate, std::move(nodes), measured_error};
}
inline BlenderNodes nodes_none(std::string why) { return {Equivalence::Level::None, std::move(why), 0.0}; }

// Every diffuse and specular lobe takes its colour and the toon modifier.
inline void add_lobe_params(ModelDef& m) {
  const bool diffuse = m.section == "diffuse";
  m.params.insert(m.params.begin(),
                  color("color", diffuse ? "k_d, the diffuse colour" : "k_s, the specular colour",
                        Range::color(), {1, 1, 1}));
  m.params.push_back(object("toon", "Toon modifier: ρ' = smoothstep(cutoff − width/2, cutoff + width/2, ρ)",
                            "modifier", "toon"));
  m.params.front().every_lobe = m.params.back().every_lobe = true;
}

}  // namespace facet::catalog_detail
