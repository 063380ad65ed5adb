// facet schema: print the JSON Schema of material files (or of scene files).
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "cli/command.h"
#include "scene/scene.h"

using nlohmann::json;

namespace facet::cli {
namespace {

bool schema_scene = false;

int run_schema() {
  std::cout << (schema_scene ? scene_schema() : material_schema()).dump(2) << "\n";
  return 0;
}
}  // namespace

Command schema_command(CLI::App& app) {
  auto* sc = app.add_subcommand("schema", "Print the JSON Schema of material files (or of scene files)");
  sc->add_flag("--scene", schema_scene, "The scene schema instead");
  return {sc, [] { return run_schema(); }};
}

}  // namespace facet::cli
