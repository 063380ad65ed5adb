// facet sweep: check for NaN, Inf and negative values over dense direction sets.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analysis/sweep.h"
#include "analysis/validate.h"
#include "catalog/material.h"
#include "cli/command.h"
#include "core/io.h"
#include "renderers/renderer.h"

using nlohmann::json;

namespace facet::cli {
namespace {

struct SweepArgs {
  std::vector<std::string> materials;
  bool extremes = false;
  std::string renderers = all_renderers();
  int grid = 1024;
  size_t random = 800000;
  std::string workdir;
  std::string python;
};

// The table, one row per material and renderer; how many rows are bad.
size_t print_counts(const std::vector<Material>& ms, const std::vector<std::vector<SweepCount>>& rows) {
  std::map<std::string, size_t> samples;
  size_t bad_rows = 0;
  fmt::print("{:<34} {:<10} {:>10} {:>6} {:>6} {:>9}\n", "material", "target", "samples", "NaN", "Inf", "negative");
  for (size_t i = 0; i < ms.size(); ++i) {
    for (const auto& c : rows[i]) {
      samples[c.target] += c.samples;
      if (!c.ok()) ++bad_rows;
      if (!c.error.empty()) {
        fmt::print("{:<34} {:<10} FAILED: {}\n", ms[i].name, c.target, c.error.substr(0, c.error.find('\n')));
        continue;
      }
      fmt::print("{:<34} {:<10} {:>10} {:>6} {:>6} {:>9}{}\n", ms[i].name, c.target, c.samples, c.nan, c.inf, c.negative,
                 c.ok() ? "" : "   <-- bad values");
    }
  }
  std::string totals;
  for (const auto& [t, n] : samples) totals += fmt::format("{}{} {}", totals.empty() ? "" : ", ", t, n);
  fmt::print("sweep: {} materials; direction sets checked: {}; {} with NaN, Inf or negative values or errors\n", ms.size(),
             totals, bad_rows);
  return bad_rows;
}

int run_sweep(const SweepArgs& a) {
  const std::vector<std::string> renderers = renderer_list("--renderers", a.renderers);
  std::vector<Material> ms;
  std::vector<std::string> files = a.materials;
  if (files.empty()) files = example_materials();
  for (const auto& f : files) ms.push_back(load_material(f));
  if (a.extremes)
    for (auto& m : extreme_materials()) ms.push_back(m);
  SweepOptions o;
  o.settings.grid = a.grid;
  o.settings.random = a.random;
  o.settings.workdir = a.workdir.empty() ? (std::filesystem::path(private_work_folder()) / "sweep").string() : a.workdir;
  o.renderer.python = a.python;
  std::vector<std::vector<SweepCount>> rows =
      sweep_materials(ms, renderers, o, [&](const std::string& renderer) {
        fmt::print(stderr, "{}: {} materials swept\n", renderer, ms.size());
      });
  return print_counts(ms, rows) ? 1 : 0;
}

SweepArgs sw;

}  // namespace

Command sweep_command(CLI::App& app) {
  auto* swc = app.add_subcommand("sweep", "Check for NaN, Inf and negative values over dense direction sets");
  swc->add_option("materials", sw.materials, "Material files (default: every examples/materials/*.json)");
  swc->add_flag("--extremes", sw.extremes, "Also every model at the ends of its parameter ranges");
  swc->add_option("--renderers", sw.renderers, "Comma-separated: " + renderer_choices())->capture_default_str();
  swc->add_option("--grid", sw.grid, "Direction-set grid side for OpenGL (OSL takes at most 512, POV-Ray 256)")
      ->capture_default_str();
  swc->add_option("--random", sw.random, "Random direction sets on the C++ reference, besides its 512² grid")
      ->capture_default_str();
  swc->add_option("--workdir", sw.workdir, "Where the harnesses' files go");
  swc->add_option("--python", sw.python, "The Python with bpy 4.5 (default: FACET_PYTHON, then the build's .venv)");
  swc->footer(
      "The grid (analysis/sweep.h) holds the hard places: n·l and n·v at 1, 1e-7, 1e-4, 0, below the horizon;\n"
      "l = v; h = n; l = −v grazing; the normal along the tangent axis. The reference adds random sets near\n"
      "them. Exit 1 when any value is NaN, infinite or negative. Example:\n"
      "  facet sweep my.json --extremes --renderers reference,glsl");
  return {swc, [] { return run_sweep(sw); }};
}

}  // namespace facet::cli
