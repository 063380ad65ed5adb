// facet docs: generate the model catalog as static HTML: formulas, diagrams, renders, cost.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analysis/cost.h"
#include "analysis/physics.h"
#include "cli/command.h"
#include "docs/docs.h"
#include "docs/plot.h"

using nlohmann::json;

namespace facet::cli {
namespace {

struct DocsArgs {
  DocsOptions options;
  std::string cost;
  bool no_cost = false;
  std::string models;
  std::string renderers = all_renderers();
};

int run_docs(DocsArgs& a) {
  // Every input is checked before anything is drawn or written.
  if (!a.cost.empty()) a.options.cost = load_cost_rows(a.cost);
  a.options.models = split_commas(a.models);
  a.options.renderers = renderer_list("--renderers", a.renderers);
  a.options.measure_cost = a.cost.empty() && !a.no_cost;
  a.options.interactive = isatty(2);
  DocsResult r = write_docs(a.options, std::cerr);
  fmt::print("facet docs: {} model pages in {:.1f} s; {} of {} renderer comparisons pass; open {}\n", r.pages,
             r.seconds, r.passed, r.comparisons, (std::filesystem::path(a.options.out) / "index.html").string());
  if (r.passed == r.comparisons) return 0;
  // The catalog is whole (each failure is on its pages), but what it documents failed.
  fmt::print(stderr, "error: {} of {} renderer comparisons failed; the pages show each with its reason\n",
             r.comparisons - r.passed, r.comparisons);
  return 1;
}

DocsArgs da;

}  // namespace

Command docs_command(CLI::App& app) {
  auto* dc = app.add_subcommand("docs", "Generate the model catalog as static HTML: formulas, diagrams, renders, cost");
  dc->add_option("-o,--out", da.options.out, "The folder to write (index.html, models/, plots/, validate/)")->required();
  dc->add_option("--cost", da.cost, "The output of 'facet cost --json': each model's cost row (default: measured now)");
  dc->add_flag("--no-cost", da.no_cost, "Leave the cost out (the pages say it was not measured)");
  dc->add_option("--size", da.options.size, "The spheres' side in pixels")->capture_default_str()->check(CLI::Range(8, 2048));
  dc->add_option("--models", da.models, "Comma-separated lobe models (default: every diffuse and specular model)");
  dc->add_option("--renderers", da.renderers, "Comma-separated: " + renderer_choices())->capture_default_str();
  dc->add_option("--python", da.options.python, "The Python with bpy 4.5 for Cycles (default: FACET_PYTHON, then the "
                                               "build's .venv)");
  dc->footer(
      "One page per lobe model, the lobe alone at its defaults: formula, parameters, citation, notes, physics claims,\n"
      "polar and 3-D diagrams at θ_l = 20° and 60°, the sphere rendered by the reference, OpenGL, Cycles and POV-Ray\n"
      "(facet validate on the single scene) with each one's error, and the model's cost row. A renderer that fails is\n"
      "shown failed with its reason (and the exit status is 1). Viewable offline: no scripts, no network.\n"
      "Examples:\n"
      "  facet docs -o out/docs                              # every model, its cost measured: a few minutes\n"
      "  facet docs -o out/docs --cost cost.json             # cost rows from an earlier 'facet cost --json'\n"
      "  facet docs -o out/docs --no-cost                    # no cost rows: about 20 s\n"
      "  facet docs -o /tmp/d --models lambert,ward --renderers reference,glsl --size 64");
  return {dc, [] { return run_docs(da); }};
}

}  // namespace facet::cli
