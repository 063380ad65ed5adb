// facet plot: draw a material's reflected-light diagram (the NVIDIA survey's lobe plot).
#include <cstdio>
#include <filesystem>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "cli/command.h"
#include "docs/plot.h"

using nlohmann::json;

namespace facet::cli {
namespace {

struct PlotArgs {
  std::string material;
  double light_angle = 45;
  std::string view = "polar";
  std::string scale = "linear";
  double max = 0;
  std::string output;
};

// The command line is checked before the material is read, and nothing is written on an error.
int run_plot(const PlotArgs& a) {
  std::string ext = std::filesystem::path(a.output).extension().string();
  std::vector<Diagnostic> problems;
  if (ext != ".svg" && ext != ".png")
    problems.push_back({"command line", "-o", fmt::format("\"{}\" is neither .svg nor .png; allowed: FILE.svg or "
                                                          "FILE.png", a.output), 0, 0});
  else if (a.view == "lobe3d" && ext != ".png")
    problems.push_back({"command line", "-o", fmt::format("\"{}\": the lobe3d view is rendered; allowed: FILE.png",
                                                          a.output), 0, 0});
  if (!(a.light_angle >= 0 && a.light_angle < 90))
    problems.push_back({"command line", "--light-angle", fmt::format("{} is out of range; allowed: 0 ≤ θ_l < 90 "
                                                                     "(degrees from the normal)", a.light_angle), 0, 0});
  if (!problems.empty()) throw InputError(problems);
  Material m = load_material(a.material);
  PlotOptions o;
  o.light_angle = a.light_angle;
  o.view = a.view == "lobe3d" ? PlotOptions::View::Lobe3d : PlotOptions::View::Polar;
  o.scale = a.scale == "log" ? PlotOptions::Scale::Log : PlotOptions::Scale::Linear;
  o.max = a.max;
  write_plot(m, o, a.output);
  fmt::print(stderr, "{}: {} diagram of {} at θ_l = {:g}°\n", a.output, a.view, m.name, a.light_angle);
  return 0;
}

PlotArgs pl;

}  // namespace

Command plot_command(CLI::App& app) {
  auto* plc = app.add_subcommand("plot", "Draw a material's reflected-light diagram (the NVIDIA survey's lobe plot)");
  plc->add_option("material", pl.material, "The material (JSON)")->required();
  plc->add_option("--light-angle", pl.light_angle, "θ_l: the light's angle from the normal, degrees in [0, 90)")
      ->capture_default_str();
  plc->add_option("--view", pl.view, "polar (the value over a plane of incidence) or lobe3d (over the hemisphere)")
      ->check(CLI::IsMember({"polar", "lobe3d"}))
      ->capture_default_str();
  plc->add_option("--scale", pl.scale, "Radius scale: linear, or log (3 powers of ten; for sharp highlights)")
      ->check(CLI::IsMember({"linear", "log"}))
      ->capture_default_str();
  plc->add_option("--max", pl.max, "The value of the outer ring (default: a round number ≥ max(peak, 1))")
      ->check(CLI::PositiveNumber);
  plc->add_option("-o,--output", pl.output, "FILE.svg or FILE.png (lobe3d: FILE.png). Written whole or not at all")
      ->required();
  plc->footer(
      "The value plotted is the luminance Y (Rec. 709) of k_d ⊗ ρ_d + k_s ⊗ ρ_s for one white light at θ_l, as the\n"
      "C++ reference computes it, over view directions: blue the diffuse part, orange the specular part stacked on\n"
      "it, purple the light. Materials that read the tangent (Ward, Heidrich–Seidel) get two planes: n–t and n–b.\n"
      "A material with layers (\"layers\": a clear coat, a sheen) is drawn whole, in teal, under its layers, and its\n"
      "lobes alone dashed beside it: a layer weights the lobes' sum as a whole, so their parts are not drawn apart.\n"
      "Examples:\n"
      "  facet plot examples/materials/phong.json --light-angle 45 -o phong.svg\n"
      "  facet plot examples/materials/ward.json --light-angle 30 --view lobe3d -o ward.png\n"
      "  facet plot examples/materials/ggx.json --light-angle 60 --scale log -o ggx.png");
  return {plc, [] { return run_plot(pl); }};
}

}  // namespace facet::cli
