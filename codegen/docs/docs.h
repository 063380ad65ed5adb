// facet — the generated catalog: static HTML, viewable offline, made from the
// model catalog and from measurements only.
//
//   DIR/index.html          every lobe model: formula, sphere, verdicts, cost
//   DIR/models/NAME.html    one lobe model (model_materials(): the lobe alone at its
//                           defaults): formula, parameters, citation, notes,
//                           physics claims, reflected-light diagrams (polar and
//                           lobe3d) at each light angle, the sphere by each
//                           renderer with its error, the cost row
//   DIR/terms.html          Fresnel, geometry, distributions, modifiers, lights, attenuation
//   DIR/cost.html           every cost row
//   DIR/plots/, DIR/validate/ (facet validate's own report, metrics and images)
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/cost.h"
#include "renderers/renderer.h"

namespace facet {

// The cost rows are analysis/cost.h's CostTable: `facet cost --json`'s output
// read back (load_cost_rows), or measured for the pages.

// ---------------------------------------------------------------- the pages

struct DocsOptions {
  std::string out = "out/docs";
  std::vector<std::string> models;  // lobe model names; empty: every diffuse and specular model
  std::optional<CostTable> cost;    // the cost rows (facet cost --json); absent: see measure_cost
  bool measure_cost = false;        // without `cost`: measure it for these models (else the pages say it was not)
  int size = 128;                   // the spheres' side, pixels
  std::vector<std::string> renderers = renderer_names();
  std::string python;               // bpy's Python; empty: default_python()
  std::vector<double> light_angles = {20, 60};
  bool interactive = false;         // progress as one updating line
};

struct DocsResult {
  size_t pages = 0;            // model pages written
  size_t comparisons = 0, passed = 0;
  std::string validate_summary;
  double seconds = 0;
};

// Checks the model names first (InputError naming --models), measures the cost
// when asked (measure_cost), then draws, renders
// through facet::validate() on the `single` scene, and writes every page whole.
// A renderer that fails is shown on its pages with its reason.
DocsResult write_docs(const DocsOptions& options, std::ostream& progress);

}  // namespace facet
