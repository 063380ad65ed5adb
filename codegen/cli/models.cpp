// facet models: list the model catalog: parameters, ranges, defaults, citations.
#include <cmath>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analysis/physics.h"
#include "catalog/catalog.h"
#include "cli/command.h"

using nlohmann::json;

namespace facet::cli {
namespace {

const char* const kNormalMapDoc =
    "a material's \"normal_map\": {\"texture\": file, \"uv\", \"filter\", \"wrap\", \"transform\" (as a texture's), "
    "\"green\": \"up\" (OpenGL, glTF; default) | \"down\" (DirectX), \"strength\": s (glTF's normalTexture.scale, default 1)}: "
    "a tangent-space normal map, rgb and linear; n_t = normalize((2·rgb − 1) ⊗ (s, s, 1)), both lobes shade with "
    "normalize(n_t.x·T + n_t.y·B + n_t.z·N), B = w·(N × T) (glTF 2.0 §3.9.3; docs/textures.md)";
const char* const kCoatNormalMapDoc =
    "a material's \"coat_normal_map\": the same object, the clear coat's own normal map (KHR_materials_clearcoat's "
    "clearcoatNormalTexture, its scale the strength), on normal_map's tangent frame (the same uv); it needs a coat "
    "(gltf_pbr's clearcoat), which without it takes the surface's own, unmapped normal (docs/textures.md, "
    "\"Coat normal maps\")";

json catalog_json() {
  json sections = json::object();
  for (const auto& m : catalog()) {
    json params = json::array();
    for (const auto& p : m.params) {
      json pj = {{"name", p.name}, {"type", param_kind_name(p.kind)}, {"doc", p.doc}, {"required", p.required},
                 {"allowed", p.allowed()},
                 {"texturable", p.texturable}};
      if (p.kind == ParamKind::Number || p.kind == ParamKind::Color) {
        pj["range"] = {{"min", std::isfinite(p.range.min) ? json(p.range.min) : json(nullptr)},
                       {"max", std::isfinite(p.range.max) ? json(p.range.max) : json(nullptr)},
                       {"min_exclusive", p.range.min_open},
                       {"max_exclusive", p.range.max_open}};
      }
      if (p.kind == ParamKind::Enum) pj["choices"] = p.choices;
      if (p.kind == ParamKind::Model || p.kind == ParamKind::Object) pj["section"] = p.section;
      if (p.kind != ParamKind::Object) pj["default"] = default_json(p);
      params.push_back(pj);
    }
    json mj = {{"name", m.name},       {"title", m.title}, {"citation", m.citation},
               {"formula", m.formula}, {"doc", m.doc},     {"parameters", params}};
    for (const auto& f : m.forms) mj["forms"].push_back({{"what", f.what}, {"keys", f.keys}, {"optional", f.optional}});
    // Lobes, and the modifiers that have Blender nodes (toon): the add-on's Build Blender Nodes.
    const BlenderNodes& b = m.blender_nodes;
    if (m.section == "diffuse" || m.section == "specular" || !b.nodes.empty())
      mj["blender_nodes"] = {{"kind", level_name(b.level)},
                             {"nodes", b.nodes},
                             {"error", b.level == Equivalence::Level::Approximate ? json(b.error) : json(nullptr)}};
    if (m.section == "diffuse" || m.section == "specular") {
      mj["cycles"] = {{"level", level_name(m.cycles.level)}, {"note", m.cycles.note}};
      mj["pov"] = {{"level", level_name(m.pov.level)}, {"note", m.pov.note}};
      // Claims from the literature; docs/physics.md holds the measurement (facet physics).
      mj["physics"] = {{"reciprocal", m.reciprocal},
                       {"energy_conserving", m.energy_conserving},
                       {"note", m.physics_note}};
    }
    sections[m.section].push_back(mj);
  }
  // A material's top-level keys besides its lobes (docs/textures.md).
  json material = {{"normal_map", {{"doc", kNormalMapDoc}}}, {"coat_normal_map", {{"doc", kCoatNormalMapDoc}}}};
  return {{"facet", FACET_VERSION}, {"epsilon", kEpsilon}, {"sections", sections}, {"material", material}};
}

int run_models(bool as_json) {
  if (as_json) {
    std::cout << catalog_json().dump(2) << "\n";
    return 0;
  }
  std::string current;
  for (const auto& m : catalog()) {
    if (m.section != current) {
      current = m.section;
      fmt::print("\n{}\n{}\n", current, std::string(current.size(), '-'));
    }
    fmt::print("  {:<18} {}\n", m.name, m.formula);
    if (!m.citation.empty()) fmt::print("  {:<18} {}\n", "", m.citation);
    for (const auto& p : m.params) {
      if (p.every_lobe) continue;  // said once, below
      std::string dflt;
      if (p.kind == ParamKind::Number) dflt = fmt::format(", default {}", p.fallback.number);
      if (p.kind == ParamKind::Enum) dflt = fmt::format(", default \"{}\"", p.fallback.choice);
      if (p.kind == ParamKind::Model && p.fallback.model) dflt = fmt::format(", default {}", p.fallback.choice);
      fmt::print("  {:<18}   {}{}: {}{}\n", "", p.name, p.required ? " (required)" : "", p.allowed(), dflt);
    }
    if (!m.forms.empty()) fmt::print("  {:<18}   written as {}\n", "", m.forms_text());
  }
  fmt::print("\nEvery diffuse and specular lobe also takes \"color\" (k_d or k_s, default 1) and \"toon\".\n");
  fmt::print("A material may also take {};\nand {}.\n", kNormalMapDoc, kCoatNormalMapDoc);
  return 0;
}

bool models_json = false;

}  // namespace

Command models_command(CLI::App& app) {
  auto* mo = app.add_subcommand("models", "List the model catalog: parameters, ranges, defaults, citations");
  mo->add_flag("--json", models_json, "Machine-readable (the Blender add-on reads this)");
  return {mo, [] { return run_models(models_json); }};
}

}  // namespace facet::cli
