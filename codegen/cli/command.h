// facet's command line: one file per command (cli/<command>.cpp), each adding its
// subcommand, options and help to the app and returning how to run it.
// The files are compiled as one translation unit (UNITY_BUILD in codegen/CMakeLists.txt,
// so CLI11 is compiled once): names in their anonymous namespaces must differ between files.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "catalog/material.h"
#include "scene/scene.h"

namespace facet::cli {

// A subcommand and what runs when it was given; the exit status comes back.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Command generate_command(CLI::App& app);
Command eval_command(CLI::App& app);
Command models_command(CLI::App& app);
Command render_command(CLI::App& app);
Command validate_command(CLI::App& app);
Command import_gltf_command(CLI::App& app);
Command export_gltf_command(CLI::App& app);
Command sweep_command(CLI::App& app);
Command physics_command(CLI::App& app);
Command plot_command(CLI::App& app);
Command docs_command(CLI::App& app);
Command cost_command(CLI::App& app);
Command draw_shaders_command(CLI::App& app);
Command schema_command(CLI::App& app);

// ---- Shared by several commands (common.cpp).

// The material argument may be left out when every object of `scene` carries its own
// material; otherwise an error naming MATERIAL and `why` it is needed.
std::optional<Material> load_optional_material(const std::string& path, const std::optional<Scene>& scene,
                                               const std::string& why);
// "WIDTHxHEIGHT", each in 1 … 16384.
bool parse_size(const std::string& s, int& w, int& h);
std::vector<std::string> split_commas(const std::string& s);
// The renderers of a comma-separated list, each checked against the registry's names.
std::vector<std::string> renderer_list(const std::string& option, const std::string& names);
// The registry's names, for help texts: "reference, glsl, osl, pov"; as an option's
// default: "reference,glsl,osl,pov"; and one line each, "  glsl       the generated GLSL …\n".
std::string renderer_choices();
std::string all_renderers();
std::string renderer_help();

}  // namespace facet::cli
