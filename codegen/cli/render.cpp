// facet render: render a material on a scene with one renderer (float image).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "cli/command.h"
#include "core/image.h"
#include "reference/raycaster.h"
#include "analysis/validate.h"
#include "renderers/compare.h"
#include "renderers/renderer.h"
#include "scene/scene.h"

using nlohmann::json;

namespace facet::cli {
namespace {

struct RenderArgs {
  std::string material;
  std::string renderer = reference_renderer().name;
  std::string scene = "single";
  std::string size = "256x256";
  std::string output;
  std::string preview;
  std::string mask;
  std::string normals;  // the reference's surface normals and coverage (PFM)
  std::string pov_route = "auto";
  std::string workdir;
  bool compare = false;
  bool exact = false;
  bool one_run = false;
  double check = -1;
  std::optional<double> exposure;  // the preview's, in stops; absent: the scene's
};

// The renderer's image of `job`; false, with the reason printed, when it failed.
bool render_with(const std::string& name, const RenderJob& job, Image& image) {
  std::unique_ptr<Renderer> renderer = make_renderer(name);
  RenderOutcome r = renderer->render({job}).at(0);
  if (!r.ok) {
    std::cerr << "error: " << renderer->info().tool << ": " << r.error << "\n";
    return false;
  }
  image = r.image;
  std::string about = renderer->description();
  fmt::print(stderr, "{}{}: {:.2f} s\n", name, about.empty() ? "" : " (" + about + ")", r.seconds);
  if (!r.note.empty()) fmt::print(stderr, "note: {}\n", r.note);
  return true;
}

// The comparison with the reference, printed; whether it passes `tol` (--check).
bool print_comparison(const RenderArgs& a, const std::optional<Material>& m, const Render& ref, const Scene& ref_scene,
                      const Image& image, double tol) {
  Metrics mt = compare_images(ref, image, interior_mask(ref), tol);
  fmt::print("{} vs reference, {}: max |Δ| {:.3g}, max |Δ|/max(1,|ref|) {:.3g}, rmse {:.3g}; {} of {} interior pixels "
             "over {:g}; NaN/Inf {}; worst at ({}, {}): ref [{:.6g} {:.6g} {:.6g}] got [{:.6g} {:.6g} {:.6g}]\n",
             a.renderer, m ? m->name : std::filesystem::path(a.scene).stem().string(), mt.max_abs, mt.max_excess, mt.rmse,
             mt.over, mt.pixels, tol, mt.nan, mt.worst_x, mt.worst_y, mt.worst_ref[0], mt.worst_ref[1], mt.worst_ref[2],
             mt.worst_got[0], mt.worst_got[1], mt.worst_got[2]);
  const std::string dull = uninformative(ref, ref_scene);
  if (!dull.empty()) fmt::print("uninformative: {} — the comparison cannot tell a right renderer from a wrong one\n", dull);
  return mt.over == 0 && mt.nan == 0 && mt.pixels > 0 && dull.empty();
}

int run_render(const RenderArgs& a) {
  int w, h;
  if (!parse_size(a.size, w, h)) throw InputError({{"command line", "--size", "expected WIDTHxHEIGHT, e.g. 256x256", 0, 0}});
  const bool reference = find_renderer(a.renderer)->reference;
  Scene scene = load_scene(a.scene);
  std::optional<Material> m = load_optional_material(a.material, scene, "unless every object of --scene has its own");
  check_texture_sets(scene, m ? &*m : nullptr);
  // The reference first: what the others are compared with, and the exposure POV-Ray needs.
  Render ref = m ? render_reference(*m, scene, w, h) : render_reference(scene, w, h);
  Image image = ref.image;
  if (!reference) {
    RenderJob job;
    job.material = m;
    job.scene = scene;
    job.width = w;
    job.height = h;
    job.workdir = a.workdir;
    job.bracket = a.exact;
    job.one_run = a.one_run;
    job.pov_route = *parse_pov_route(a.pov_route);
    job.max_value = 0;
    for (float v : ref.image.rgb) job.max_value = std::max<double>(job.max_value, v);
    if (a.compare || a.check >= 0) job.tolerance = a.check >= 0 ? a.check : 2e-3;  // POV-Ray brackets to meet it
    if (!render_with(a.renderer, job, image)) return 1;
  }
  int status = 0;
  if ((a.compare || a.check >= 0) && !reference) {
    bool pass = print_comparison(a, m, ref, scene, image, a.check >= 0 ? a.check : 2e-3);
    if (a.check >= 0 && !pass) status = 3;
  }
  if (!a.output.empty()) write_pfm(a.output, image);
  if (!a.preview.empty()) write_png_preview(a.preview, image, float(std::exp2(a.exposure.value_or(scene.exposure))));
  if (!a.normals.empty()) {  // the reference's own normals, and the object index + 1 in a second image
    Image n(w, h), id(w, h);
    n.rgb = ref.normal;
    for (size_t i = 0; i < ref.object.size(); ++i)
      for (int c = 0; c < 3; ++c) id.rgb[i * 3 + size_t(c)] = float(ref.object[i] + 1);
    write_pfm(a.normals, n);
    const std::filesystem::path p(a.normals);
    write_pfm((p.parent_path() / (p.stem().string() + "_objects.pfm")).string(), id);
  }
  if (!a.mask.empty()) {  // a binary PGM, rows from the top: 255 where the comparison looks
    std::vector<uint8_t> mask = interior_mask(ref);
    std::string pgm = fmt::format("P5\n{} {}\n255\n", w, h);
    for (uint8_t v : mask) pgm.push_back(char(v ? 255 : 0));
    write_file_atomic(a.mask, pgm);
  }
  return status;
}

RenderArgs ra;

}  // namespace

Command render_command(CLI::App& app) {
  auto* rn = app.add_subcommand("render", "Render a material on a scene with one renderer (float image)");
  rn->add_option("material", ra.material,
                 "The material (JSON). May be left out when every object of --scene has its own material");
  rn->add_option("-r,--renderer", ra.renderer, "One of " + renderer_choices() + " (listed below)")
      ->check(CLI::IsMember(renderer_names()))
      ->capture_default_str();
  rn->add_option("--scene", ra.scene, "A scene file or a built-in name (single, shadows)")->capture_default_str();
  rn->add_option("--size", ra.size, "Image size WIDTHxHEIGHT")->capture_default_str();
  rn->add_option("-o,--output", ra.output, "Linear float image (PFM)");
  rn->add_option("--preview", ra.preview, "An 8-bit sRGB PNG to look at (radiance × 2^exposure, sRGB, clipped)");
  rn->add_option("--exposure", ra.exposure,
                 "The preview's exposure in stops (default: the scene's \"exposure\", else 0)")
      ->check(CLI::Range(-40.0, 40.0));
  rn->add_option("--pov-route", ra.pov_route, "POV-Ray: auto, native, exact or fast (facet generate --pov-route)")
      ->check(CLI::IsMember({"auto", "native", "exact", "fast"}))
      ->capture_default_str();
  rn->add_option("--mask", ra.mask,
                 "The pixels --compare and facet validate judge, as a binary PGM (255: inside an object, not on its "
                 "silhouette, no shadow ray grazing an occluder's edge)");
  rn->add_option("--normals", ra.normals,
                 "The reference's surface normals (unit xyz, world space, before any normal map; 0 where no object is "
                 "hit) as a PFM, and beside it STEM_objects.pfm: the index + 1 of the object each pixel sees (0: "
                 "none). For checking a scene's geometry against another reader's");
  rn->add_option("--workdir", ra.workdir, "Where the renderer's files go (default: a temporary folder)");
  rn->add_flag("--compare", ra.compare, "Print the comparison with the reference");
  rn->add_option("--check", ra.check,
                 "Exit with status 3 unless |renderer − reference| ≤ TOL · max(1, |reference|) on every interior pixel")
      ->check(CLI::NonNegativeNumber);
  rn->add_flag("--exact", ra.exact,
               "POV-Ray: bracket exposures so every pixel keeps 16-bit relative precision (slower)");
  rn->add_flag("--one-run", ra.one_run,
               "POV-Ray: render every light in one run (the generated file's default) instead of one pass per light");
  rn->footer("Renderers (the reference is also what --compare and --check compare with):\n" + renderer_help() +
             "Examples:\n"
             "  facet render examples/materials/ggx.json -r glsl --compare --preview ggx.png\n"
             "  facet render examples/materials/ggx.json -r osl --compare\n"
             "  facet render examples/materials/ward.json -r pov --exact --check 2e-5 -o ward.pfm");
  return {rn, [] { return run_render(ra); }};
}

}  // namespace facet::cli
