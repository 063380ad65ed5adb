// facet eval: evaluate the C++ reference for direction sets read from standard input.
#include <cmath>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "catalog/catalog.h"
#include "catalog/material.h"
#include "cli/command.h"
#include "core/io.h"
#include "reference/interpreter.h"

using nlohmann::json;

namespace facet::cli {
namespace {

Vec3 unit_vector(const json& j, const std::string& path, DiagnosticSink& sink, bool& ok) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number()) {
    sink.error(path, "expected an array of three numbers, found " + json_type_name(j));
    ok = false;
    return {};
  }
  Vec3 v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  double len = length(v);
  if (!(len > 0) || !std::isfinite(len)) {
    sink.error(path, "has no direction (zero or not finite); allowed: a non-zero vector");
    ok = false;
    return {};
  }
  return v / len;
}

int run_eval(const std::string& material_path) {
  Material m = load_material(material_path);
  Reference ref(m);
  std::stringstream in;
  in << std::cin.rdbuf();
  const std::string file = "(stdin)";
  json sets = parse_json(in.str(), file);
  DiagnosticSink sink(file);
  if (!sets.is_array()) {
    sink.error("", "expected an array of direction sets {\"n\", \"l\", \"v\", \"t\"?}, found " + json_type_name(sets));
    sink.throw_if_any();
  }
  json out = json::array();
  for (size_t i = 0; i < sets.size(); ++i) {
    const json& s = sets[i];
    std::string path = index_path("", i);
    if (!s.is_object()) {
      sink.error(path, "expected an object {\"n\", \"l\", \"v\", \"t\"?}, found " + json_type_name(s));
      continue;
    }
    for (const auto& [key, val] : s.items())
      if (key != "n" && key != "l" && key != "v" && key != "t")
        sink.error(join_path(path, key), "unknown key; allowed keys: \"n\", \"l\", \"v\", \"t\"");
    bool ok = true;
    auto get = [&](const char* key) -> Vec3 {
      if (!s.contains(key)) {
        sink.error(join_path(path, key), "missing; allowed: an array of three numbers");
        ok = false;
        return {};
      }
      return unit_vector(s[key], join_path(path, key), sink, ok);
    };
    Vec3 n = get("n"), l = get("l"), v = get("v");
    Vec3 t;
    if (ok && s.contains("t")) {
      t = unit_vector(s["t"], join_path(path, "t"), sink, ok);
      // MODELS.md needs t ⟂ n: keep the part of t across n.
      Vec3 across = t - n * dot(n, t);
      if (ok && length(across) < kEpsilon) {
        sink.error(join_path(path, "t"), "is parallel to n; allowed: a tangent across the normal");
        ok = false;
      }
      if (ok) t = normalize(across);
    } else if (ok) {
      t = tangent_rule(n, Vec3(m.tangent_axis));
    }
    if (!ok) continue;
    RGB c = ref.reflectance(n, l, v, t);
    out.push_back({c[0], c[1], c[2]});
  }
  sink.throw_if_any();
  std::cout << out.dump() << "\n";
  return 0;
}

std::string eval_material;

}  // namespace

Command eval_command(CLI::App& app) {
  auto* e = app.add_subcommand("eval", "Evaluate the C++ reference for direction sets read from standard input");
  e->add_option("material", eval_material, "The material (JSON)")->required();
  e->footer(
      "Reads a JSON array of {\"n\": [x,y,z], \"l\": [...], \"v\": [...], \"t\": [...]} (t optional: without it,\n"
      "t = normalize(tangent_axis × n)). Vectors are normalized; t is made perpendicular to n. Writes a JSON array\n"
      "of [r, g, b] = k_d ⊗ ρ_d + k_s ⊗ ρ_s for one white light: no attenuation, ambient or emission.\n"
      "Example:\n"
      "  echo '[{\"n\":[0,0,1],\"l\":[0,1,1],\"v\":[0,-1,1]}]' | facet eval examples/materials/phong.json");
  return {e, [] { return run_eval(eval_material); }};
}

}  // namespace facet::cli
