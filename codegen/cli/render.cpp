// facet render: render a material on a scene with one renderer (float image).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "cli/command.h"
#include "core/image.h"
#include "reference/raycaster.h"
#include "renderers/compare.h"
#include "renderers/renderers.h"
#include "scene/scene.h"

using nlohmann::json;

namespace facet::cli {
namespace {

struct RenderArgs {
  std::string material;
  std::string renderer = "reference";
  std::string scene = "single";
  std::string size = "256x256";
  std::string output;
  std::string preview;
  std::string workdir;
  bool compare = false;
  bool exact = false;
  bool one_run = false;
  double check = -1;
};

int run_render(const RenderArgs& a) {
  int w, h;
  if (!parse_size(a.size, w, h)) throw InputError({{"command line", "--size", "expected WIDTHxHEIGHT, e.g. 256x256", 0, 0}});
  Scene scene = load_scene(a.scene);
  std::optional<Material> m = load_optional_material(a.material, scene, "unless every object of --scene has its own");
  Render ref = m ? render_reference(*m, scene, w, h) : render_reference(scene, w, h);
  Image image = ref.image;
  if (a.renderer == "pov") {
    RenderJob job;
    job.material = m;
    job.scene = scene;
    job.width = w;
    job.height = h;
    job.workdir = a.workdir.empty() ? (std::filesystem::temp_directory_path() / "facet-render").string() : a.workdir;
    job.bracket = a.exact;
    job.one_run = a.one_run;
    job.max_value = 0;
    for (float v : ref.image.rgb) job.max_value = std::max<double>(job.max_value, v);
    RenderOutcome r = render_pov(job);
    if (!r.ok) {
      std::cerr << "error: POV-Ray: " << r.error << "\n";
      return 1;
    }
    image = r.image;
    fmt::print(stderr, "pov: {:.2f} s\n", r.seconds);
  } else if (a.renderer == "glsl") {
    RenderJob job;
    job.material = m;
    job.scene = scene;
    job.width = w;
    job.height = h;
    job.workdir = a.workdir;
    GlRenderer gl;
    RenderOutcome r = gl.render(job);
    if (!r.ok) {
      std::cerr << "error: OpenGL: " << r.error << "\n";
      return 1;
    }
    image = r.image;
    fmt::print(stderr, "glsl ({}): {:.2f} s\n", gl.description(), r.seconds);
  }
  int status = 0;
  if ((a.compare || a.check >= 0) && a.renderer != "reference") {
    double tol = a.check >= 0 ? a.check : 2e-3;
    Metrics mt = compare_images(ref, image, interior_mask(ref), tol);
    fmt::print("{} vs reference, {}: max |Δ| {:.3g}, max |Δ|/max(1,|ref|) {:.3g}, rmse {:.3g}; {} of {} interior pixels "
               "over {:g}; NaN/Inf {}; worst at ({}, {}): ref [{:.6g} {:.6g} {:.6g}] got [{:.6g} {:.6g} {:.6g}]\n",
               a.renderer, m ? m->name : std::filesystem::path(a.scene).stem().string(), mt.max_abs, mt.max_excess, mt.rmse, mt.over, mt.pixels, tol, mt.nan, mt.worst_x,
               mt.worst_y, mt.worst_ref[0], mt.worst_ref[1], mt.worst_ref[2], mt.worst_got[0], mt.worst_got[1],
               mt.worst_got[2]);
    if (a.check >= 0 && (mt.over > 0 || mt.nan > 0 || mt.pixels == 0)) status = 3;
  }
  if (!a.output.empty()) write_pfm(a.output, image);
  if (!a.preview.empty()) write_png_preview(a.preview, image);
  return status;
}

RenderArgs ra;

}  // namespace

Command render_command(CLI::App& app) {
  auto* rn = app.add_subcommand("render", "Render a material on a scene with one renderer (float image)");
  rn->add_option("material", ra.material,
                 "The material (JSON). May be left out when every object of --scene has its own material");
  rn->add_option("-r,--renderer", ra.renderer,
                 "reference (C++ ray caster), glsl (OpenGL through EGL) or pov (POV-Ray 3.7)")
      ->check(CLI::IsMember({"reference", "glsl", "pov"}))
      ->capture_default_str();
  rn->add_option("--scene", ra.scene, "A scene file or a built-in name (single, shadows)")->capture_default_str();
  rn->add_option("--size", ra.size, "Image size WIDTHxHEIGHT")->capture_default_str();
  rn->add_option("-o,--output", ra.output, "Linear float image (PFM)");
  rn->add_option("--preview", ra.preview, "An 8-bit sRGB PNG to look at");
  rn->add_option("--workdir", ra.workdir, "Where the renderer's files go (default: a temporary folder)");
  rn->add_flag("--compare", ra.compare, "Print the comparison with the reference");
  rn->add_option("--check", ra.check,
                 "Exit with status 3 unless |renderer − reference| ≤ TOL · max(1, |reference|) on every interior pixel")
      ->check(CLI::NonNegativeNumber);
  rn->add_flag("--exact", ra.exact,
               "POV-Ray: bracket exposures so every pixel keeps 16-bit relative precision (slower)");
  rn->add_flag("--one-run", ra.one_run,
               "POV-Ray: render every light in one run (the generated file's default) instead of one pass per light");
  return {rn, [] { return run_render(ra); }};
}

}  // namespace facet::cli
