// facet validate: render materials through OpenGL, Cycles (OSL) and POV-Ray and compare each with the C++ reference, pixel by pixel.
#include <iostream>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "analysis/validate.h"
#include "catalog/material.h"
#include "cli/command.h"
#include "core/image.h"
#include "reference/raycaster.h"

using nlohmann::json;

namespace facet::cli {
namespace {

ValidateOptions va;
std::string va_size = "256x256", va_renderers = all_renderers();

int run_validate() {
  int w, h;
  if (!parse_size(va_size, w, h)) throw InputError({{"command line", "--size", "expected WIDTHxHEIGHT, e.g. 256x256", 0, 0}});
  va.width = w;
  va.height = h;
  va.renderers = renderer_list("--renderers", va_renderers);
  va.interactive = isatty(2);
  ValidateResult result = validate(va, std::cerr);
  std::cout << "facet validate: " << result.summary << "\n";
  return result.pass ? 0 : 1;
}
}  // namespace

Command validate_command(CLI::App& app) {
  auto* v = app.add_subcommand("validate",
                               "Render materials through OpenGL, Cycles (OSL) and POV-Ray and compare each with the "
                               "C++ reference, pixel by pixel");
  v->add_option("materials", va.materials, "Material files (default: every examples/materials/*.json)");
  v->add_option("--scene", va.scenes, "A built-in scene (single, shadows) or a scene file; repeat for several "
                                      "(default: single and shadows)");
  v->add_option("--size", va_size, "Image size WIDTHxHEIGHT")->capture_default_str();
  v->add_option("--renderers", va_renderers, "Comma-separated: " + renderer_choices())->capture_default_str();
  v->add_option("--out", va.out, "Where metrics.json, report.html and the images go")->capture_default_str();
  v->add_option("--python", va.python, "The Python with bpy 4.5 for Cycles (default: FACET_PYTHON, then the "
                                       "build's .venv)");
  v->add_option("--exposure", va.exposure,
                "The previews' exposure in stops: radiance × 2^EV through the standard view transform (sRGB, "
                "clipped to 1); default: each scene's \"exposure\" (0 without). Comparisons are of the linear images")
      ->check(CLI::Range(-40.0, 40.0));
  v->add_option("--tolerance", va.tolerance, "Pass when |Δ| ≤ TOL · max(1, |reference|) on every interior pixel")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  v->footer(
      "Each renderer draws the same scene, one sample at each pixel centre, linear and unclamped:\n" + renderer_help() +
      "Writes OUT/metrics.json (one row per material × scene × renderer), OUT/report.html (images side by side,\n"
      "|Δ| × 16, failures first) and exits 1 when any comparison fails; a renderer that cannot run fails.\n"
      "Examples:\n"
      "  facet validate                                   # the whole example catalog, both scenes\n"
      "  facet validate my.json --scene shadows --renderers reference,glsl --size 128x128");
  return {v, [] { return run_validate(); }};
}

}  // namespace facet::cli
