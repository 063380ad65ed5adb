// facet physics: measure each lobe's reciprocity and albedo (the white furnace).
#include <chrono>
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "analysis/physics.h"
#include "cli/command.h"
#include "core/io.h"

using nlohmann::json;

namespace facet::cli {
namespace {

struct PhysicsArgs {
  std::string output;
  std::string check;
  size_t samples = PhysicsOptions{}.albedo_samples;
};

int run_physics(const PhysicsArgs& a) {
  PhysicsOptions o;
  o.albedo_samples = a.samples;
  fmt::print(stderr, "physics: measuring every lobe ({} samples per albedo estimate)…\n", o.albedo_samples);
  auto start = std::chrono::steady_clock::now();
  std::vector<PhysicsRow> rows = measure_physics(o);
  std::string text = physics_markdown(rows, o);
  fmt::print(stderr, "physics: {:.1f} s\n",
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  int status = 0;
  fmt::print("{:<18} {:<10} {:>12} {:<10} {:>22}  {}\n", "lobe", "reciprocal", "asymmetry", "conserving",
             "max albedo", "verdict");
  for (const auto& r : rows) {
    std::vector<std::string> wrong;
    if (r.measured_reciprocal != r.model->reciprocal)
      wrong.push_back(r.model->reciprocal ? "catalog says reciprocal, measured not" : "catalog says not reciprocal, measured reciprocal");
    if (r.model->energy_conserving && !r.measured_conserving()) wrong.push_back("catalog says energy-conserving, albedo exceeds 1");
    const AlbedoEstimate& m = r.max_albedo();
    fmt::print("{:<18} {:<10} {:>12.3g} {:<10} {:>12.6g} ± {:<7.2g}  {}\n", r.model->name,
               r.model->reciprocal ? "yes" : "no", r.asymmetry, r.model->energy_conserving ? "yes" : "no", m.albedo,
               m.error, wrong.empty() ? "ok" : fmt::format("WRONG: {}", fmt::join(wrong, "; ")));
    if (!wrong.empty()) status = 1;
  }
  if (!a.output.empty()) write_file_atomic(a.output, text);
  if (!a.check.empty()) {
    std::string committed;
    try {
      committed = read_file(a.check);
    } catch (const std::exception& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return 1;
    }
    if (committed != text) {
      fmt::print("{} differs from the measurement; regenerate it with: facet physics -o {}\n", a.check, a.check);
      status = 1;
    } else {
      fmt::print("{} is what the measurement gives\n", a.check);
    }
  }
  if (a.output.empty() && a.check.empty()) std::cout << "\n" << text;
  return status;
}

PhysicsArgs ph;

}  // namespace

Command physics_command(CLI::App& app) {
  auto* phc = app.add_subcommand("physics", "Measure each lobe's reciprocity and albedo (the white furnace)");
  phc->add_option("-o,--output", ph.output, "Write the Markdown report (docs/physics.md)");
  phc->add_option("--check", ph.check, "Exit 1 unless this file is exactly what the measurement gives");
  phc->add_option("--samples", ph.samples, "Monte Carlo samples per albedo estimate")->capture_default_str()
      ->check(CLI::Range(size_t(64), size_t(1) << 30));
  phc->footer(
      "f(l, v) = ρ/(π n·l) against f(v, l), and a(l) = ∫ f (n·v) dω by importance-sampled Monte Carlo, for every\n"
      "diffuse and specular lobe over its parameters and incidence angles (see analysis/physics.h). Exit 1 when a\n"
      "measurement contradicts the catalog: reciprocity, or albedo above 1 for a lobe called energy-conserving.\n"
      "Examples:\n"
      "  facet physics -o docs/physics.md\n"
      "  facet physics --check docs/physics.md");
  return {phc, [] { return run_physics(ph); }};
}

}  // namespace facet::cli
