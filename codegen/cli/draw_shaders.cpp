// facet draw-shaders: draw the shaders of a cost job (run under callgrind by facet cost).

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "analysis/cost.h"
#include "cli/command.h"

using nlohmann::json;

namespace facet::cli {
namespace {

// Hidden: what `facet cost` runs under valgrind (analysis/cost.h, run_draw_job).
std::string draw_job;

}  // namespace

Command draw_shaders_command(CLI::App& app) {
  auto* dr = app.add_subcommand("draw-shaders", "Draw the shaders of a cost job (run under callgrind by facet cost)");
  dr->group("");
  dr->add_option("job", draw_job, "The job file")->required();
  return {dr, [] { return run_draw_job(draw_job); }};
}

}  // namespace facet::cli
