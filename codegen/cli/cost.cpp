// facet cost: measure what each material costs on each target (the survey's Appendix B).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analysis/cost.h"
#include "catalog/material.h"
#include "cli/command.h"
#include "core/io.h"

using nlohmann::json;

namespace facet::cli {
namespace {

struct CostArgs {
  std::vector<std::string> materials;
  bool as_json = false;
  std::string markdown;
  std::string check;
  bool no_timings = false;
  bool no_callgrind = false;
  CostOptions options;
};

int run_cost(CostArgs a) {
  std::vector<Material> ms;
  for (const auto& f : a.materials) ms.push_back(load_material(f));
  if (ms.empty()) ms = model_materials();
  a.options.timings = !a.no_timings && a.check.empty();
  a.options.callgrind = !a.no_callgrind && callgrind_available();
  if (!a.no_callgrind && !callgrind_available())
    fmt::print(stderr, "note: no llvmpipe instruction counts: valgrind cannot run this sanitizer build of facet "
                       "(the release build counts them)\n");
  auto start = std::chrono::steady_clock::now();
  auto progress = [&](const std::string& what) {
    fmt::print(stderr, "cost [{:5.1f} s]: {}\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
               what);
  };
  CostBaselines baselines;
  std::vector<CostRow> rows = measure_costs(ms, a.options, progress, &baselines);
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print(stderr, "cost: {} materials in {:.1f} s\n", rows.size(), wall);
  int status = std::all_of(rows.begin(), rows.end(), [](const CostRow& r) { return r.ok(); }) ? 0 : 1;
  if (a.as_json) std::cout << costs_json(rows, baselines).dump(2) << "\n";
  else std::cout << costs_table(rows, baselines);
  if (!a.markdown.empty()) write_file_atomic(a.markdown, costs_markdown(rows, baselines, a.options, wall));
  if (!a.check.empty()) {
    std::vector<std::string> stale = stale_costs(read_file(a.check), rows);
    for (const auto& line : stale) fmt::print("stale: {}\n", line);
    if (!stale.empty()) {
      fmt::print("{} is out of date; regenerate it with: facet cost --markdown {}\n", a.check, a.check);
      status = 1;
    } else {
      fmt::print("{}: every count is what the measurement gives\n", a.check);
    }
  }
  return status;
}

CostArgs co;

}  // namespace

Command cost_command(CLI::App& app) {
  auto* coc = app.add_subcommand("cost", "Measure what each material costs on each target (the survey's Appendix B)");
  coc->add_option("materials", co.materials, "Material files (default: every lobe model of the catalog at its defaults)");
  coc->add_flag("--json", co.as_json, "Print {\"baseline\": \"lambert\", \"rows\": [...]} instead of the table");
  coc->add_option("--markdown", co.markdown, "Also write the table as Markdown (docs/cost.md)");
  coc->add_option("--check", co.check,
                  "Exit 1 unless this Markdown file's counts (SPIR-V, HLSL SPIR-V, WGSL bytes, llvmpipe instructions, OSL ops, POV-Ray "
                  "functions) are what the measurement gives; no timings are taken");
  coc->add_flag("--no-timings", co.no_timings, "Only the deterministic counts: no Cycles or POV-Ray render times");
  coc->add_flag("--no-callgrind", co.no_callgrind, "No llvmpipe instruction counts (valgrind)");
  coc->add_option("--repeats", co.options.repeats, "Interleaved rounds of POV-Ray renders; each time is the least")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  coc->add_option("--cycles-repeats", co.options.cycles_repeats, "Interleaved rounds of Cycles renders")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  coc->add_option("--jobs", co.options.jobs, "Processes at once")->capture_default_str()->check(CLI::Range(1, 64));
  coc->add_option("--workdir", co.options.workdir, "Where shaders, scenes and the tools' outputs go (default: a temporary folder)");
  coc->add_option("--python", co.options.python, "The Python with bpy 4.5 (default: FACET_PYTHON, then the build's .venv)");
  coc->footer(
      "Per material (a row) and target: GLSL — SPIR-V instructions after spirv-opt -O of the single-light cost\n"
      "frame's fragment shader (and of the HLSL path: --target hlsl in the same frame as a pixel shader, through\n"
      "glslangValidator -D -V), and x86 instructions per pixel of its llvmpipe draw under callgrind; OSL — ops of\n"
      "the compiled .oso and Cycles' time per pixel and sample; POV-Ray — native finish or its function count, and\n"
      "the trace time per pixel. Times and counts also relative to Lambert. The table goes to standard output,\n"
      "progress to standard error; a tool that cannot run is an error in its rows and exit status 1.\n"
      "Examples:\n"
      "  facet cost                                   # the whole catalog, a few minutes\n"
      "  facet cost examples/materials/ward.json --json\n"
      "  facet cost --markdown docs/cost.md\n"
      "  facet cost --check docs/cost.md              # the counts only; what the test cost.table runs");
  return {coc, [] { return run_cost(co); }};
}

}  // namespace facet::cli
