// facet — checking JSON documents against catalog parameter definitions.
// Shared by the material and scene parsers (catalog/, scene/).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "catalog/catalog.h"
#include "catalog/material.h"
#include "catalog/texture.h"
#include "core/diagnostics.h"

namespace facet {

using nlohmann::json;

inline std::string number_text(double v) { return fmt::format("{}", v); }

inline std::string quoted_list(const std::vector<std::string>& xs) {
  std::string s;
  for (size_t i = 0; i < xs.size(); ++i) s += (i ? ", \"" : "\"") + xs[i] + "\"";
  return s;
}

inline std::vector<std::string> param_names(const ModelDef& m, bool with_model_key) {
  std::vector<std::string> names;
  if (with_model_key) names.push_back("model");
  for (const auto& p : m.params) names.push_back(p.name);
  return names;
}

class Checker {
 public:
  explicit Checker(DiagnosticSink& sink) : sink_(sink) {}

  // A finite number, else a diagnostic.
  std::optional<double> number(const json& j, const std::string& path, const std::string& allowed) {
    if (!j.is_number()) {
      sink_.error(path, fmt::format("expected a number, found {}; allowed: {}", json_type_name(j), allowed));
      return std::nullopt;
    }
    double v = j.get<double>();
    if (!std::isfinite(v)) {
      sink_.error(path, fmt::format("{} is not finite; allowed: {}", number_text(v), allowed));
      return std::nullopt;
    }
    return v;
  }

  std::optional<double> ranged(const json& j, const std::string& path, const ParamDef& p) {
    auto v = number(j, path, p.allowed());
    if (v && !p.range.contains(*v)) {
      sink_.error(path, fmt::format("{} is out of range; allowed: {}", number_text(*v), p.allowed()));
      return std::nullopt;
    }
    return v;
  }

  std::optional<RGB> color(const json& j, const std::string& path, const ParamDef& p) {
    if (j.is_number()) {
      auto v = ranged(j, path, p);
      if (!v) return std::nullopt;
      return RGB{*v, *v, *v};
    }
    if (!j.is_array() || j.size() != 3) {
      std::string found = j.is_array() ? fmt::format("an array of {} values", j.size()) : json_type_name(j);
      sink_.error(path, fmt::format("expected a colour, found {}; allowed: {}", found, p.allowed()));
      return std::nullopt;
    }
    RGB rgb{};
    bool ok = true;
    for (size_t i = 0; i < 3; ++i) {
      auto v = ranged(j[i], index_path(path, i), p);
      if (v) rgb[i] = *v;
      else ok = false;
    }
    return ok ? std::optional<RGB>(rgb) : std::nullopt;
  }

  // Why a vector cannot be a direction, or none: the zero vector, or one so short that no
  // component reaches kShortestDirection (its length's square underflows: [0, 1e-300, 0]
  // normalized is NaN in double, and anything below ~1e-19 is in float32).
  static std::optional<std::string> directionless(double x, double y, double z) {
    if (x == 0 && y == 0 && z == 0) return std::string("the zero vector has no direction");
    if (std::max({std::abs(x), std::abs(y), std::abs(z)}) < kShortestDirection)
      return fmt::format("[{}, {}, {}] is too short to be a direction (no component reaches {})", x, y, z,
                         kShortestDirection);
    return std::nullopt;
  }

  std::optional<RGB> vector(const json& j, const std::string& path, const ParamDef& p) {
    if (!j.is_array() || j.size() != 3) {
      std::string found = j.is_array() ? fmt::format("an array of {} values", j.size()) : json_type_name(j);
      sink_.error(path, fmt::format("expected a vector, found {}; allowed: {}", found, p.allowed()));
      return std::nullopt;
    }
    RGB v{};
    bool ok = true;
    for (size_t i = 0; i < 3; ++i) {
      auto x = ranged(j[i], index_path(path, i), p);
      if (x) v[i] = *x;
      else ok = false;
    }
    if (ok && p.nonzero) {
      if (auto why = directionless(v[0], v[1], v[2])) {
        sink_.error(path, *why + "; allowed: " + p.allowed());
        return std::nullopt;
      }
    }
    return ok ? std::optional<RGB>(v) : std::nullopt;
  }

  // An array of triples: points (finite; not zero if p.nonzero) or triangles
  // (non-negative integer indices of distinct vertices). At most 8 problems are
  // reported per list.
  std::optional<Value> list(const json& j, const std::string& path, const ParamDef& p) {
    Value out;
    out.kind = p.kind;
    if (!j.is_array()) {
      sink_.error(path, fmt::format("expected an array, found {}; allowed: {}", json_type_name(j), p.allowed()));
      return std::nullopt;
    }
    int problems = 0;
    auto bad = [&](size_t i, const std::string& what) {
      if (++problems <= 8) sink_.error(index_path(path, i), what + "; allowed: " + p.allowed());
    };
    out.points.reserve(j.size());
    out.arity = p.kind == ParamKind::Points ? p.arity : 3;
    static const char* const counts[] = {"", "one", "two", "three", "four"};
    for (size_t i = 0; i < j.size(); ++i) {
      const json& e = j[i];
      const size_t arity = size_t(out.arity);
      if (!e.is_array() || e.size() != arity) {
        bad(i, fmt::format("expected {} numbers, found {}", counts[arity],
                           e.is_array() ? fmt::format("{} values", e.size()) : json_type_name(e)));
        continue;
      }
      std::array<double, 4> v{};
      bool ok = true;
      for (size_t k = 0; k < arity; ++k) {
        if (!e[k].is_number() || !std::isfinite(e[k].get<double>()) || !p.range.contains(e[k].get<double>())) ok = false;
        else v[k] = e[k].get<double>();
        if (ok && p.kind == ParamKind::Triangles && (!e[k].is_number_integer() || v[k] < 0)) ok = false;
      }
      if (!ok) {
        bad(i, p.kind == ParamKind::Triangles ? "expected three non-negative integers"
                                              : fmt::format("expected {} numbers {}", counts[arity], p.range.describe()));
        continue;
      }
      if (p.kind == ParamKind::Points && p.nonzero) {
        if (auto why = directionless(v[0], v[1], v[2])) {
          bad(i, *why);
          continue;
        }
      }
      if (p.kind == ParamKind::Triangles && (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])) {
        bad(i, "a triangle needs three distinct vertices");
        continue;
      }
      out.points.push_back(v);
    }
    if (problems > 8) sink_.error(path, fmt::format("{} more problems in this list", problems - 8));
    if (problems) return std::nullopt;
    return out;
  }

  // The value of parameter `p` given as `j`, else a diagnostic.
  std::optional<Value> value(const json& j, const std::string& path, const ParamDef& p) {
    if (p.texturable && j.is_object()) return parse_texture_value(j, path, p, sink_);
    switch (p.kind) {
      case ParamKind::Number: return wrap(p, ranged(j, path, p), &Value::number);
      case ParamKind::String: return string_value(j, path, p);
      case ParamKind::Points:
      case ParamKind::Triangles: return list(j, path, p);
      case ParamKind::Index: return index_value(j, path, p);
      case ParamKind::Bool: return bool_value(j, path, p);
      case ParamKind::Enum: return enum_value(j, path, p);
      case ParamKind::Color: return wrap(p, color(j, path, p), &Value::rgb);
      case ParamKind::Vector: return wrap(p, vector(j, path, p), &Value::rgb);
      case ParamKind::Model: return model_value(j, path, p);
      case ParamKind::Object: return object_value(j, path, p);
    }
    return std::nullopt;
  }

  // An object naming a model of `section` with "model" (or holding the
  // parameters of `fixed`), with every parameter checked and defaults filled.
  // `key` names the discriminating key: "model" in materials, "type" for lights.
  std::optional<ModelSpec> model(const json& j, const std::string& path, const std::string& section,
                                 const ModelDef* fixed, const std::string& key = "model") {
    auto models = facet::section(section);
    std::vector<std::string> names;
    for (const auto* m : models) names.push_back(m->name);
    if (!j.is_object()) {
      std::string allowed = fixed ? "an object with keys " + quoted_list(param_names(*fixed, false))
                                  : "an object {\"" + key + "\": …} with " + key + " one of " + quoted_list(names);
      sink_.error(path, fmt::format("expected an object, found {}; allowed: {}", json_type_name(j), allowed));
      return std::nullopt;
    }
    const ModelDef* def = fixed;
    if (!def) {
      auto it = j.find(key);
      if (it == j.end()) {
        sink_.error(join_path(path, key), "missing; allowed: one of " + quoted_list(names));
        return std::nullopt;
      }
      if (!it->is_string()) {
        sink_.error(join_path(path, key), fmt::format("expected a string, found {}; allowed: one of {}",
                                                      json_type_name(*it), quoted_list(names)));
        return std::nullopt;
      }
      std::string name = it->get<std::string>();
      def = find_model(section, name);
      if (!def) {
        std::string hint = suggest(name, names);
        sink_.error(join_path(path, key),
                    fmt::format("unknown {} model \"{}\"{}; allowed: one of {}", section, name,
                                hint.empty() ? "" : " (did you mean \"" + hint + "\"?)", quoted_list(names)));
        return std::nullopt;
      }
    }
    ModelSpec spec;
    spec.def = def;
    bool ok = true;
    std::vector<std::string> keys = param_names(*def, false);
    if (!fixed) keys.insert(keys.begin(), key);
    for (const auto& [k, val] : j.items()) {
      if (k == key && !fixed) continue;
      const ParamDef* p = def->param(k);
      if (!p) {
        std::string hint = suggest(k, keys);
        sink_.error(join_path(path, k),
                    fmt::format("unknown key for {} \"{}\"{}; allowed keys: {}", fixed ? "object" : key,
                                def->name, hint.empty() ? "" : " (did you mean \"" + hint + "\"?)",
                                quoted_list(keys)));
        ok = false;
        continue;
      }
      spec.given.insert(k);
      auto v = value(val, join_path(path, k), *p);
      if (v) spec.values[k] = *v;
      else ok = false;
    }
    if (ok && !def->forms.empty()) ok = one_form(*def, spec.given, path);
    for (const auto& p : def->params) {
      if (spec.values.count(p.name) || j.contains(p.name)) continue;  // present: valid, or already reported
      if (p.required) {
        sink_.error(join_path(path, p.name),
                    fmt::format("missing; {} \"{}\" requires it: {}", fixed ? "object" : "model", def->name, p.allowed()));
        ok = false;
      } else if (p.kind != ParamKind::Object || p.fallback.model) {
        spec.values[p.name] = p.fallback;
      }
    }
    if (!ok) return std::nullopt;
    return spec;
  }

 private:
  // A Value of p's kind holding `v` in `field`, or nothing where `v` is nothing.
  template <class T, class Field>
  static std::optional<Value> wrap(const ParamDef& p, const std::optional<T>& v, Field Value::*field) {
    if (!v) return std::nullopt;
    Value out;
    out.kind = p.kind;
    out.*field = *v;
    return out;
  }

  std::optional<Value> string_value(const json& j, const std::string& path, const ParamDef& p) {
    if (!j.is_string() || j.get<std::string>().empty()) {
      sink_.error(path, fmt::format("expected a non-empty string, found {}",
                                    j.is_string() ? "an empty string" : json_type_name(j)));
      return std::nullopt;
    }
    return wrap(p, std::optional<std::string>(j.get<std::string>()), &Value::choice);
  }

  // A whole number ≥ 0, or (by_name) a non-empty string.
  std::optional<Value> index_value(const json& j, const std::string& path, const ParamDef& p) {
    Value out;
    out.kind = p.kind;
    out.number = -1;
    if (j.is_number_integer() && j.get<double>() >= 0) out.number = j.get<double>();
    else if (p.by_name && j.is_string() && !j.get<std::string>().empty()) out.choice = j.get<std::string>();
    else {
      std::string found = j.is_string() && j.get<std::string>().empty() ? "an empty string"
                          : j.is_number()                             ? "the number " + j.dump()
                                                                      : json_type_name(j);
      sink_.error(path, fmt::format("expected {}, found {}", p.allowed(), found));
      return std::nullopt;
    }
    return out;
  }

  // The keys of exactly one of def's forms; else what is missing or extra, by key.
  // The form meant is the one with most of its keys given (its own keys count
  // double); where several are as near and none is complete, the error names each.
  bool one_form(const ModelDef& def, const std::set<std::string>& given, const std::string& path) {
    auto in = [](const std::vector<std::string>& v, const std::string& k) {
      return std::find(v.begin(), v.end(), k) != v.end();
    };
    auto missing = [&](const ParamForm& f) {
      std::vector<std::string> m;
      for (const auto& k : f.keys)
        if (!given.count(k)) m.push_back(k);
      return m;
    };
    std::vector<const ParamForm*> best;
    size_t best_score = 0;
    for (const auto& f : def.forms) {
      size_t score = 0;
      for (const auto& k : f.keys) score += given.count(k) * 2;
      for (const auto& k : f.optional) score += given.count(k);
      if (best.empty() || score > best_score) best.clear(), best_score = score;
      if (score == best_score) best.push_back(&f);
    }
    std::string says = fmt::format("{} \"{}\" is {}", def.section, def.name, def.forms_text());
    auto complete = std::find_if(best.begin(), best.end(), [&](const ParamForm* f) { return missing(*f).empty(); });
    if (complete == best.end() && best.size() > 1) {
      std::string alts;
      for (const auto* f : best) alts += (alts.empty() ? "" : " or ") + quoted_list(missing(*f)) + " (" + f->what + ")";
      sink_.error(path, fmt::format("missing {}; {}", alts, says));
      return false;
    }
    const ParamForm& form = complete != best.end() ? **complete : *best.front();
    bool ok = true;
    for (const auto& k : missing(form)) {
      sink_.error(join_path(path, k), fmt::format("missing for {}; {}", form.what, says));
      ok = false;
    }
    for (const auto& k : given) {
      bool of_a_form = std::any_of(def.forms.begin(), def.forms.end(),
                                   [&](const ParamForm& f) { return in(f.keys, k) || in(f.optional, k); });
      if (of_a_form && !in(form.keys, k) && !in(form.optional, k)) {
        sink_.error(join_path(path, k), fmt::format("not allowed with {}; {}", form.what, says));
        ok = false;
      }
    }
    return ok;
  }

  std::optional<Value> bool_value(const json& j, const std::string& path, const ParamDef& p) {
    if (!j.is_boolean()) {
      sink_.error(path, fmt::format("expected a boolean, found {}; allowed: true or false", json_type_name(j)));
      return std::nullopt;
    }
    return wrap(p, std::optional<bool>(j.get<bool>()), &Value::flag);
  }

  std::optional<Value> enum_value(const json& j, const std::string& path, const ParamDef& p) {
    if (!j.is_string()) {
      sink_.error(path, fmt::format("expected a string, found {}; allowed: {}", json_type_name(j), p.allowed()));
      return std::nullopt;
    }
    std::string s = j.get<std::string>();
    if (std::find(p.choices.begin(), p.choices.end(), s) == p.choices.end()) {
      std::string hint = suggest(s, p.choices);
      sink_.error(path, fmt::format("\"{}\" is not allowed{}; allowed: {}", s,
                                    hint.empty() ? "" : " (did you mean \"" + hint + "\"?)", p.allowed()));
      return std::nullopt;
    }
    return wrap(p, std::optional<std::string>(s), &Value::choice);
  }

  // The model `spec` as the value of a Model-kind parameter (`choice` names it).
  static Value model_of(const ParamDef& p, const ModelSpec& spec) {
    Value out;
    out.kind = p.kind;
    out.choice = spec.def->name;
    out.model = std::make_shared<ModelSpec>(spec);
    return out;
  }

  // {"model": …, …}, or the shorthands: a string names a model that needs no
  // parameters; an object without "model" holds the parameters of `fixed`.
  std::optional<Value> model_value(const json& j, const std::string& path, const ParamDef& p) {
    if (j.is_string()) {
      const ModelDef* def = find_model(p.section, j.get<std::string>());
      if (def && std::none_of(def->params.begin(), def->params.end(), [](const ParamDef& q) { return q.required; })) {
        ModelSpec spec;
        spec.def = def;
        for (const auto& q : def->params) spec.values[q.name] = q.fallback;
        return model_of(p, spec);
      }
    }
    if (j.is_object() && !j.contains("model") && !p.fixed.empty()) {
      auto spec = model(j, path, p.section, find_model(p.section, p.fixed));
      if (!spec) return std::nullopt;
      return model_of(p, *spec);
    }
    if (j.is_string()) {
      sink_.error(path, fmt::format("\"{}\" is not allowed; allowed: {}", j.get<std::string>(), p.allowed()));
      return std::nullopt;
    }
    auto spec = model(j, path, p.section, nullptr);
    if (!spec) return std::nullopt;
    return model_of(p, *spec);
  }

  // The parameters of the fixed model p.section/p.fixed.
  std::optional<Value> object_value(const json& j, const std::string& path, const ParamDef& p) {
    auto spec = model(j, path, p.section, find_model(p.section, p.fixed));
    if (!spec) return std::nullopt;
    Value out;
    out.kind = p.kind;
    out.model = std::make_shared<ModelSpec>(*spec);
    return out;
  }

  DiagnosticSink& sink_;
};


}  // namespace facet
