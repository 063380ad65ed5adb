#include "analysis/sweep.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace facet {

namespace {

Value number_value(double v) {
  Value x;
  x.kind = ParamKind::Number;
  x.number = v;
  return x;
}

Value color_value(double v) {
  Value x;
  x.kind = ParamKind::Color;
  x.rgb = {v, v, v};
  return x;
}

// The ends of a parameter's range: the bound itself, a hair inside an open one,
// 1e4 for an unbounded one.
double low_end(const Range& r) { return r.min_open ? r.min + std::max(1e-6, std::fabs(r.min) * 1e-6) : r.min; }
double high_end(const Range& r) {
  if (!std::isfinite(r.max)) return 1e4;
  return r.max_open ? r.max - std::max(1e-6, std::fabs(r.max) * 1e-6) : r.max;
}

ModelSpec fresnel(const char* name, std::map<std::string, Value> values) {
  ModelSpec f = default_spec(*find_model("fresnel", name));
  for (auto& [k, v] : values) f.values[k] = v;
  return f;
}

}  // namespace


std::vector<Material> extreme_materials() {
  std::vector<Material> out;
  auto add = [&](const ModelDef& def, const std::string& suffix, const ModelSpec& spec) {
    out.push_back(facet::lobe_material(spec, def.name + "_" + suffix));
    out.back().source = "extremes";
  };
  for (const auto& def : catalog()) {
    if (def.section != "diffuse" && def.section != "specular") continue;
    ModelSpec low = default_spec(def), high = default_spec(def);
    // Numbers at the ends of their ranges; colours (k_d, k_s) at the top of theirs in
    // both, the largest product a lobe's peak can reach (a colour of 0 hides nothing
    // the top does not show: 0 · ∞ is NaN only where the top gives ∞).
    for (const auto& p : def.params) {
      if (p.kind == ParamKind::Number) {
        low.values[p.name] = number_value(low_end(p.range));
        high.values[p.name] = number_value(high_end(p.range));
      } else if (p.kind == ParamKind::Color) {
        low.values[p.name] = high.values[p.name] = color_value(high_end(p.range));
      }
    }
    add(def, "low", low);
    add(def, "high", high);
    // Schlick's rational power x / (n − n x + x) in place of x^n, at both ends of n:
    // its denominator is where a cosine past 1 turns the lobe negative.
    if (def.param("approximation")) {
      Value schlick;
      schlick.kind = ParamKind::Enum;
      schlick.choice = "schlick";
      for (auto [suffix, spec] : {std::pair{"schlick_low", low}, std::pair{"schlick_high", high}}) {
        spec.values["approximation"] = schlick;
        add(def, suffix, spec);
      }
    }
    if (!def.param("fresnel")) continue;
    // The Fresnel terms at their ends: f0 = 0 and 1; η at the bottom of its range
    // (total internal reflection), exactly 1 (no reflection) and the top.
    const Range& ior = find_model("fresnel", "exact")->param("ior")->range;
    std::vector<std::pair<std::string, ModelSpec>> fresnels = {
        {"schlick0", fresnel("schlick", {{"f0", color_value(0)}})},
        {"schlick1", fresnel("schlick", {{"f0", color_value(1)}})},
        {"ior_tiny", fresnel("exact", {{"ior", number_value(low_end(ior))}})},
        {"ior_one", fresnel("exact", {{"ior", number_value(1)}})},
        {"ior_huge", fresnel("exact", {{"ior", number_value(high_end(ior))}})}};
    for (auto& [name, f] : fresnels) {
      ModelSpec s = low;
      Value v;
      v.kind = ParamKind::Model;
      v.choice = f.def->name;
      v.model = std::make_shared<ModelSpec>(f);
      s.values["fresnel"] = v;
      add(def, name, s);
    }
  }
  // Toon at its ends on a lobe that reaches both 0 and 1.
  const ModelDef& lambert = *find_model("diffuse", "lambert");
  const ModelDef& toon = *find_model("modifier", "toon");
  const double top_cutoff = high_end(toon.param("cutoff")->range), top_width = high_end(toon.param("width")->range);
  for (auto [name, cutoff, width] : {std::tuple{"toon_zero", 0.0, 0.0}, std::tuple{"toon_thin", 0.5, 1e-9},
                                     std::tuple{"toon_wide", top_cutoff, top_width}}) {
    ModelSpec s = default_spec(lambert);
    ModelSpec t = default_spec(toon);
    t.values["cutoff"] = number_value(cutoff);
    t.values["width"] = number_value(width);
    Value v;
    v.kind = ParamKind::Object;
    v.model = std::make_shared<ModelSpec>(t);
    s.values["toon"] = v;
    add(lambert, name, s);
  }
  return out;
}

// ---------------------------------------------------------------- every renderer

std::vector<std::vector<SweepCount>> sweep_materials(const std::vector<Material>& ms,
                                                     const std::vector<std::string>& renderers,
                                                     const SweepOptions& options, const SweepProgress& progress) {
  std::vector<SweepJob> jobs;
  for (const auto& m : ms) jobs.push_back({m, ""});
  std::vector<std::vector<SweepCount>> rows(ms.size());
  // The renderers one after another, in the registry's order.
  for (const auto& entry : renderer_registry()) {
    const std::string& name = entry.info.name;
    if (std::find(renderers.begin(), renderers.end(), name) == renderers.end()) continue;
    SweepSettings s = options.settings;
    s.workdir = options.settings.workdir + "/" + name;
    std::vector<SweepCount> counts = make_renderer(name, options.renderer)->sweep(jobs, s);
    for (size_t i = 0; i < ms.size(); ++i) rows[i].push_back(counts.at(i));
    if (progress) progress(name);
  }
  return rows;
}

}  // namespace facet
