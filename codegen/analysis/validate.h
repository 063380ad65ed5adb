// facet — cross-renderer validation: the same materials and scenes through the
// C++ reference and every renderer of the registry (renderers/renderer.h),
// compared pixel by pixel.
#pragma once

#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "renderers/compare.h"
#include "renderers/renderer.h"
#include "scene/scene.h"

namespace facet {

struct ValidateOptions {
  std::vector<std::string> materials;  // files; empty: every examples/materials/*.json (unless `given` has some)
  std::vector<Material> given;         // materials built in code (e.g. model_materials()), after the files;
                                       // their images are named after identifier(name)
  std::vector<std::string> scenes;     // built-in names or files; empty: single and shadows
  int width = 256, height = 256;
  std::vector<std::string> renderers = renderer_names();  // the reference renders every case whatever this says
  std::string out = "out/validate";
  std::string python;                  // bpy's Python; empty: default_python()
  double tolerance = 2e-3;             // |Δ| ≤ tolerance · max(1, |reference|)
  double coverage_tolerance = 1e-3;    // share of pixels whose coverage may differ
  double flip_tolerance = 1e-3;        // share of interior pixels a hard toon step may flip
  bool interactive = false;            // progress as one updating line (a terminal) or a line per step
  // The previews' exposure in stops (radiance × 2^EV, then sRGB, clipped); absent: each scene's own
  // (Scene::exposure). The comparison is of the linear images, whatever this says.
  std::optional<double> exposure;
};

struct ComparisonRow {
  std::string material;  // the material's name
  std::string key;       // its file's stem: names the images
  std::string renderer, scene;
  Metrics metrics;
  double coverage_mismatch = 0;  // share of all pixels
  size_t allowed_flips = 0;      // interior pixels a hard toon step may flip
  bool pass = false;
  std::string error;             // why it could not run, when it could not
  // Why the comparison proves nothing, when it does not (uninformative()): it does not pass.
  std::string uninformative;
  std::string note;  // a choice the renderer made (RenderOutcome::note)
  double seconds = 0;
};

struct ValidateResult {
  std::vector<ComparisonRow> rows;       // one per material × scene × renderer (not the reference)
  std::map<std::string, double> wall;    // seconds per renderer
  std::string summary;                   // the one-line verdict
  bool pass = false;
};

// Where OUT/images/ holds an image: "images/<key>_<scene>_<renderer>.png" (key: ComparisonRow::key).
std::string validate_image(const std::string& key, const std::string& scene, const std::string& renderer);

// examples/materials/*.json, sorted: from the working directory, else the source tree.
std::vector<std::string> example_materials();

// Renders, compares, writes OUT/metrics.json, OUT/report.html and OUT/images/.
ValidateResult validate(const ValidateOptions& options, std::ostream& progress);

// Why a reference image of scene `s` cannot tell a right renderer from a wrong one, or ""
// when it can: every renderer reading the same wrong scene agrees with it perfectly, so a
// comparison only proves something where the image shows shading. Uninformative: nothing
// visible; the image black or constant where objects are visible; or a visible object (of
// at least kInformativePixels pixels) seen from behind its normal at more than half its
// pixels, or reached by no light at any of them (each such object is named).
std::string uninformative(const Render& reference, const Scene& s);
inline constexpr size_t kInformativePixels = 8;

// The comparison the report and the tests share. `hard_toon`: a material in the
// image has a toon step of width 0, which may flip options.flip_tolerance of the pixels.
ComparisonRow judge(const Render& reference, const Image& image, const std::vector<float>& alpha, bool hard_toon,
                    const ValidateOptions& options);
// The same for what a renderer returned: a renderer that failed is a failed row with its reason.
ComparisonRow judge(const Render& reference, const RenderOutcome& outcome, bool hard_toon, const ValidateOptions& options);

}  // namespace facet
