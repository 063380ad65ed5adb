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

#include <nlohmann/json.hpp>

namespace facet {

// ---------------------------------------------------------------- cost rows

// `facet cost --json`: {"baseline": NAME, "rows": [ROW, …], "frame": {…}, "tools": {…}}
// ("frame" and "tools" optional), a ROW being
// {"name", "material", "diffuse", "specular", "glsl": {…}, "osl": {…}, "pov": {…}}
// and each target's object its figures or {"error": "why"}.
struct CostFigure {
  std::string key;    // as in the file, e.g. "ns_per_pixel"
  std::string label;  // as the pages print it, e.g. "ns / pixel"
  std::string text;   // the value, printed
};

struct CostCell {
  std::string error;  // why the target was not measured; empty when it was
  std::vector<CostFigure> figures;
  const CostFigure* find(const std::string& key) const;
};

struct CostPageRow {
  std::string name, material, diffuse, specular;  // diffuse, specular: "" for null
  CostCell glsl, osl, pov;
  const CostCell& cell(const std::string& target) const;  // "glsl", "osl" or "pov"
  CostCell& cell(const std::string& target);
};

struct CostTable {
  std::string source;  // the file, for the pages
  std::string baseline;
  std::vector<CostPageRow> rows;
  // "frame" (what the measuring frame alone costs) and "tools" (their versions),
  // each key and value as printed; shown on the cost page.
  std::vector<std::pair<std::string, std::string>> frame, tools;
  const CostPageRow* find(const std::string& name) const;
};

// Checks `doc` (what `facet cost --json` prints); every problem names `file` and
// the key path. Throws InputError. Figures the agreed format does not name are
// kept and shown as they are, so a newer cost command still documents.
CostTable parse_cost_rows(const nlohmann::json& doc, const std::string& file);
CostTable load_cost_rows(const std::string& path);

// ---------------------------------------------------------------- the pages

struct DocsOptions {
  std::string out = "out/docs";
  std::vector<std::string> models;  // lobe model names; empty: every diffuse and specular model
  std::optional<CostTable> cost;    // the cost rows (facet cost --json); absent: see measure_cost
  bool measure_cost = false;        // without `cost`: measure it for these models (else the pages say it was not)
  int size = 128;                   // the spheres' side, pixels
  std::vector<std::string> renderers = {"reference", "glsl", "osl", "pov"};
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
