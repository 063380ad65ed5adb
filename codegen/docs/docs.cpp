#include "docs/docs.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "analysis/cost.h"
#include "analysis/validate.h"
#include "catalog/checker.h"
#include "catalog/material.h"
#include "catalog/program.h"
#include "core/diagnostics.h"
#include "core/html.h"
#include "core/io.h"
#include "docs/plot.h"
#include "renderers/renderer.h"

namespace facet {

namespace fs = std::filesystem;

// ---------------------------------------------------------------- cost cells

namespace {

using nlohmann::json;

// The renderers a page's verdicts have (all but the reference), in the registry's order.
std::vector<std::string> targets() {
  std::vector<std::string> out;
  for (const auto& e : renderer_registry())
    if (!e.info.reference) out.push_back(e.info.name);
  return out;
}

std::string figure_text(const json& j, CostFigureKind kind) {
  if (j.is_null()) return "–";
  if (kind == CostFigureKind::Flag) return j.get<bool>() ? "yes" : "no";
  double v = j.get<double>();
  if (kind == CostFigureKind::Ratio) return fmt::format("{:.2f}×", v);
  if (j.is_number_integer()) return fmt::format("{}", j.get<long long>());
  return fmt::format("{:.3g}", v);
}

// A value the format does not name, as the pages print it: numbers to 4 digits.
std::string shown(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_null()) return "–";
  if (v.is_number_float()) return fmt::format("{:.4g}", v.get<double>());
  return v.dump();
}

// A cell's figures as the pages list them, label and text: the format's, then any others as they are.
std::vector<std::pair<std::string, std::string>> cell_figures(const CostCell& c, const CostTargetFormat& format) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& d : format.figures)
    if (auto it = c.figures.find(d.key); it != c.figures.end()) out.push_back({d.label, figure_text(*it, d.kind)});
  for (const auto& item : c.figures.items()) {  // no structured binding: clang 14 cannot capture one
    const std::string& key = item.key();
    const auto& defs = format.figures;
    if (std::none_of(defs.begin(), defs.end(), [&](const CostFigureDef& d) { return d.key == key; }))
      out.push_back({key, shown(item.value())});
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------- the pages

namespace {

using Clock = std::chrono::steady_clock;

// A model_materials() material's one lobe: the model its pages document.
const ModelDef& lobe_def(const Material& m) { return *(m.diffuse ? m.diffuse : m.specular)->def; }

const std::string& renderer_title(const std::string& r) { return find_renderer(r)->title; }

const char* kStyle = R"(body { font: 15px/1.5 "DejaVu Sans", system-ui, sans-serif; margin: 0; color: #222; background: #fafafa; }
main { max-width: 1180px; margin: 0 auto; padding: 20px 28px 60px; }
nav { font-size: 13px; margin-bottom: 8px; } nav a { margin-right: 14px; }
a { color: #2a5fa8; text-decoration: none; } a:hover { text-decoration: underline; }
h1 { margin: 4px 0 2px; font-size: 26px; } h1 code { font-size: 18px; color: #666; font-weight: normal; }
h2 { margin: 30px 0 8px; font-size: 19px; border-bottom: 1px solid #ddd; padding-bottom: 3px; }
h3 { margin: 20px 0 4px; font-size: 16px; }
.badge { display: inline-block; font-size: 12px; padding: 1px 8px; border-radius: 9px; color: #fff; vertical-align: middle; }
.badge.diffuse { background: #3a78c3; } .badge.specular { background: #e07b24; }
.formula { font: 15px/1.5 "DejaVu Sans Mono", ui-monospace, monospace; background: #fff; border: 1px solid #ddd;
           border-left: 4px solid #8e44ad; padding: 8px 12px; white-space: pre-wrap; }
.cite { color: #555; font-style: italic; } .muted { color: #666; font-size: 13px; }
table { border-collapse: collapse; margin: 8px 0; background: #fff; }
th, td { border: 1px solid #ddd; padding: 5px 8px; vertical-align: top; text-align: left; }
th { background: #f0f0f0; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
code { font: 13px "DejaVu Sans Mono", ui-monospace, monospace; }
.pass { color: #1b6e2a; font-weight: 600; } .fail { color: #b3261e; font-weight: 600; } .skip { color: #777; }
.error { font: 12px/1.35 "DejaVu Sans Mono", ui-monospace, monospace; color: #b3261e; white-space: pre-wrap;
         max-width: 250px; max-height: 180px; overflow: auto; }
.diagrams { display: flex; flex-wrap: wrap; gap: 10px; } .diagrams figure { margin: 0; }
.diagrams img { display: block; background: #fff; border: 1px solid #ddd; }
figcaption { font-size: 12px; color: #555; margin-top: 2px; }
.spheres { display: flex; flex-wrap: wrap; gap: 12px; }
.sphere { width: 250px; background: #fff; border: 1px solid #ddd; padding: 8px; }
.sphere img { width: 128px; height: 128px; image-rendering: pixelated; background: #000; display: block; }
.figs { font: 12px/1.4 "DejaVu Sans Mono", ui-monospace, monospace; margin-top: 4px; }
td img.thumb { width: 64px; height: 64px; image-rendering: pixelated; background: #000; }
td img.plot { height: 96px; }
)";

std::string page(const std::string& title, const std::string& body, bool nested) {
  std::string up = nested ? "../" : "";
  return fmt::format(R"(<!doctype html>
<html lang=en><head><meta charset=utf-8><title>{0}</title><link rel=stylesheet href="{1}style.css"></head>
<body><main>
<nav><a href="{1}index.html">Models</a><a href="{1}terms.html">Terms, lights, attenuation</a><a href="{1}cost.html">Cost</a><a href="{1}validate/report.html">Validation report</a></nav>
{2}
<p class=muted>Generated by <code>facet docs</code> {3} from the model catalog and from measurements; nothing on this page is written by hand.</p>
</main></body></html>
)",
                     html_escape(title), up, body, FACET_VERSION);
}

std::string default_text(const ParamDef& p) {
  if (p.kind == ParamKind::Object) return "absent";
  json d = default_json(p);
  if (d.is_null() || (d.is_string() && d.get<std::string>().empty())) return p.required ? "required" : "–";
  if (d.is_number()) return fmt::format("{:g}", d.get<double>());
  return d.dump();
}

std::string params_table(const ModelDef& m) {
  if (m.params.empty()) return "<p class=muted>No parameters.</p>\n";
  std::string h = "<table><tr><th>parameter</th><th>type</th><th>allowed</th><th>default</th><th>what it is</th></tr>\n";
  for (const auto& p : m.params)
    h += fmt::format("<tr><td><code>{}</code>{}</td><td>{}</td><td>{}</td><td><code>{}</code></td><td>{}</td></tr>\n",
                     html_escape(p.name), p.required ? " <span class=muted>(required)</span>" : "",
                     param_kind_name(p.kind), html_escape(p.allowed()), html_escape(default_text(p)), html_escape(p.doc));
  h += "</table>\n";
  if (!m.forms.empty()) h += fmt::format("<p>Written as {}.</p>\n", html_escape(m.forms_text()));
  return h;
}

// The formula, the citation and the documentation of a model, as every page shows them.
std::string model_text(const ModelDef& m) {
  std::string h = fmt::format("<div class=formula>{}</div>\n", html_escape(m.formula));
  if (!m.citation.empty()) h += fmt::format("<p class=cite>{}</p>\n", html_escape(m.citation));
  if (!m.doc.empty()) h += fmt::format("<p>{}</p>\n", html_escape(m.doc));
  return h;
}

std::string model_header(const ModelDef& m, const std::string& tag) {
  return fmt::format("<{0} id=\"{1}\">{2} <code>{1}</code></{0}>\n", tag, html_escape(m.name), html_escape(m.title)) +
         model_text(m);
}

// What the catalog publishes of the add-on's Build Blender Nodes: the nodes and the measured figure.
std::string blender_nodes_html(const BlenderNodes& b) {
  std::string measured =
      b.level == Equivalence::Level::Approximate ? fmt::format(" (measured on the example materials: worst |Δ|/max(1, |ref|) {:.3g})", b.error)
      : b.level == Equivalence::Level::Exact     ? " (measured on the example materials: within 2e-3)"
                                                 : "";
  return html_escape(b.nodes) + measured;
}

std::string equivalence_html(const ModelDef& m) {
  std::string h = "<table><tr><th>renderer</th><th>its own feature</th><th>note</th></tr>\n";
  for (const auto& [who, e] : {std::pair<const char*, const Equivalence*>{"Cycles", &m.cycles}, {"POV-Ray", &m.pov}})
    h += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td></tr>\n", who, level_name(e->level), html_escape(e->note));
  h += fmt::format("<tr><td>Blender nodes (the add-on's Build Blender Nodes)</td><td>{}</td><td>{}</td></tr>\n",
                   level_name(m.blender_nodes.level), blender_nodes_html(m.blender_nodes));
  return h + "</table>\n<p class=muted>facet generates the model exactly for every target either way; this says how "
             "closely the renderer's built-in features could stand in for it. The Blender nodes' figure is measured "
             "in Cycles under one point light of radius 0, direct light only, against the reference.</p>\n";
}

std::string physics_html(const ModelDef& m) {
  return fmt::format(
      "<table><tr><th>reciprocal, f(l, v) = f(v, l)</th><td>{}</td></tr><tr><th>energy conserving, albedo ≤ 1</th>"
      "<td>{}</td></tr></table>\n<p>{}</p>\n<p class=muted>The catalog's claims, from the literature; <code>facet "
      "physics</code> measures both on the C++ reference and fails when a measurement contradicts them.</p>\n",
      m.reciprocal ? "yes" : "no", m.energy_conserving ? "yes" : "no", html_escape(m.physics_note));
}

std::string plot_file(const std::string& model, const char* view, double angle) {
  return fmt::format("plots/{}_{}_{:g}.{}", model, view, angle, std::string(view) == "polar" ? "svg" : "png");
}

std::string diagrams_html(const std::string& model, const DocsOptions& o, bool anisotropic) {
  std::string h = fmt::format(
      "<p class=muted>For one white light at θ_l from the normal, the luminance of k_d⊗ρ_d + k_s⊗ρ_s (the C++ "
      "reference) in each view direction, as a radius. Each diagram's outer ring is a round number at least its peak "
      "and at least 1 (a white Lambert surface facing the light), so a lobe below 1 keeps its size from one light "
      "angle to the next; the ring values are labelled.{}</p>\n",
      anisotropic ? " The model reads the tangent: the polar plot shows the plane of n and t and the plane of n and b, "
                    "on one scale." : "");
  std::string polar, lobes;
  for (double a : o.light_angles) {
    polar += fmt::format("<figure><img src=\"../{}\" width={} alt=\"polar diagram, θ_l = {:g}°\"><figcaption>polar, "
                         "θ_l = {:g}°</figcaption></figure>",
                         plot_file(model, "polar", a), anisotropic ? 1120 : 556, a, a);
    lobes += fmt::format("<figure><img src=\"../{}\" width=556 alt=\"3-D lobe, θ_l = {:g}°\"><figcaption>over the "
                         "hemisphere, θ_l = {:g}°</figcaption></figure>",
                         plot_file(model, "lobe3d", a), a, a);
  }
  return h + "<div class=diagrams>" + polar + "</div>\n<div class=diagrams>" + lobes + "</div>\n";
}

struct Verdicts {
  const ValidateResult* result;
  const DocsOptions* options;
  const ComparisonRow* row(const std::string& key, const std::string& renderer) const {
    for (const auto& r : result->rows)
      if (r.key == key && r.renderer == renderer) return &r;
    return nullptr;
  }
  bool ran(const std::string& renderer) const {
    return std::find(options->renderers.begin(), options->renderers.end(), renderer) != options->renderers.end();
  }
};

std::string figures_html(const ComparisonRow& r) {
  const Metrics& m = r.metrics;
  return fmt::format("<div class=figs><span class={}>{}</span><br>max |Δ| {:.3g}<br>max |Δ|/max(1,|ref|) {:.3g}<br>"
                     "over tolerance: {} of {} px<br>coverage differs {:.3f} %<br>NaN/Inf {}</div>",
                     r.pass ? "pass" : "fail", r.pass ? "pass" : "FAIL", m.max_abs, m.max_excess, m.over, m.pixels,
                     100 * r.coverage_mismatch, m.nan);
}

std::string spheres_html(const std::string& key, const Verdicts& v) {
  std::string h = "<div class=spheres>\n";
  const RendererInfo& reference = reference_renderer();
  h += fmt::format("<div class=sphere><b>{0}</b><br><span class=muted>{1}</span><img src=\"../validate/{2}\" "
                   "alt=\"{0}\"><div class=figs>the image the others are compared with</div></div>\n",
                   reference.name, reference.title, validate_image(key, "single", reference.name));
  for (const auto& t : targets()) {
    h += fmt::format("<div class=sphere><b>{}</b><br><span class=muted>{}</span>", t, renderer_title(t));
    const ComparisonRow* r = v.row(key, t);
    if (!v.ran(t)) {
      h += "<div class=figs><span class=skip>not rendered: left out with --renderers</span></div>";
    } else if (!r) {
      h += "<div class=figs><span class=fail>FAILED</span>: no result came back</div>";
    } else if (!r->error.empty()) {
      h += fmt::format("<div class=figs><span class=fail>FAILED</span> to render:</div><div class=error>{}</div>",
                       html_escape(r->error.substr(0, 1500)));
    } else {
      h += fmt::format("<img src=\"../validate/{}\" alt=\"{}\">", validate_image(key, "single", t), t) + figures_html(*r);
    }
    h += "</div>\n";
  }
  return h + "</div>\n";
}

std::string verdict_cell(const std::string& key, const std::string& t, const Verdicts& v) {
  if (!v.ran(t)) return "<td class=skip>–</td>";
  const ComparisonRow* r = v.row(key, t);
  if (r && r->pass) return fmt::format("<td class=pass title=\"max |Δ|/max(1,|ref|) {:.3g}\">pass</td>", r->metrics.max_excess);
  return fmt::format("<td class=fail title=\"{}\">{}</td>", html_escape(r ? r->error.substr(0, 300) : "no result"),
                     r && r->error.empty() ? "FAIL" : "failed");
}

std::string not_measured(const DocsOptions& o, const std::string& name) {
  if (!o.cost)
    return "<p class=skip>Not measured: these pages were generated with <code>--no-cost</code> (without it, "
           "<code>facet docs</code> measures the cost, or reads <code>--cost COST.json</code>, the output of "
           "<code>facet cost --json</code>).</p>\n";
  return fmt::format("<p class=skip>Not measured: {} has no row named <code>{}</code>.</p>\n", html_escape(o.cost->source),
                     html_escape(name));
}

std::string cell_html(const CostCell& c, const CostTargetFormat& format) {
  if (!c.error.empty()) return "<span class=fail>not measured</span>: " + html_escape(c.error);
  std::string h;
  for (const auto& [label, text] : cell_figures(c, format))
    h += fmt::format("{}{}: <b>{}</b>", h.empty() ? "" : "<br>", html_escape(label), html_escape(text));
  return h;
}

// The cost targets' headings: "<th>OpenGL (GLSL)</th>…".
std::string cost_headings() {
  std::string h;
  for (const auto& format : cost_format()) h += "<th>" + find_renderer(format.target)->label + "</th>";
  return h;
}

std::string cost_row_html(const CostRow& r, const std::string& baseline) {
  std::string h = "<table><tr>" + cost_headings() + "</tr><tr>";
  for (const auto& format : cost_format()) h += "<td>" + cell_html(r.cell(format.target), format) + "</td>";
  return h + fmt::format("</tr></table>\n<p class=muted>Relative figures are to the baseline, <code>{}</code>; the "
                         "material measured: <code>{}</code>.</p>\n",
                         html_escape(baseline), html_escape(r.material));
}

std::string relative_summary(const CostRow& r) {
  std::string s;
  for (const auto& format : cost_format()) {
    const CostCell& c = r.cell(format.target);
    auto f = c.figures.find(format.relative);
    std::string what = !c.error.empty() ? fmt::format("<span class=fail title=\"{}\">not measured</span>", html_escape(c.error))
                       : f != c.figures.end() ? html_escape(figure_text(*f, CostFigureKind::Ratio))
                                              : "–";
    s += fmt::format("{}{} {}", s.empty() ? "" : "<br>", format.target, what);
  }
  return s;
}

std::string model_page(const Material& m, const DocsOptions& o, const Verdicts& v, bool anisotropic) {
  const ModelDef& def = lobe_def(m);
  std::string key = identifier(m.name);
  std::string b = fmt::format("<h1>{} <code>{}</code> <span class=\"badge {}\">{}</span></h1>\n", html_escape(def.title),
                              html_escape(def.name), def.section, def.section);
  b += model_text(def);
  b += "<h2>Parameters</h2>\n" + params_table(def);
  b += "<h2>Reflected light</h2>\n" + diagrams_html(def.name, o, anisotropic);
  b += fmt::format("<h2>The sphere in each renderer</h2>\n<p class=muted>The built-in <code>single</code> scene (one "
                   "sphere, one point light) at {0}×{0}, one sample at each pixel centre; a renderer passes when "
                   "|Δ| ≤ 2e-3 · max(1, |reference|) on every interior pixel (<code>facet validate</code>).</p>\n",
                   o.size);
  b += spheres_html(key, v);
  b += fmt::format("<details><summary>The material rendered and plotted</summary><pre><code>{}</code></pre></details>\n",
                   html_escape(to_json(m).dump(2)));
  b += "<h2>Cycles and POV-Ray equivalents</h2>\n" + equivalence_html(def);
  b += "<h2>Physics</h2>\n" + physics_html(def);
  b += "<h2>Cost</h2>\n";
  const CostRow* row = o.cost ? o.cost->find(def.name) : nullptr;
  b += row ? cost_row_html(*row, o.cost->baseline) : not_measured(o, def.name);
  return page(def.title + " — facet", b, true);
}

std::string index_page(const std::vector<Material>& ms, const DocsOptions& o, const Verdicts& v, const DocsResult& r) {
  std::string b = "<h1>facet: the lobe models</h1>\n";
  b += fmt::format("<p>Every diffuse and specular model of the catalog{}, each alone at its defaults: its formula, its "
                   "reflected-light diagrams, the sphere as each renderer draws it from the generated code, and what it "
                   "costs.</p>\n<p class=muted>Validation on the <code>single</code> scene at {}×{}: {}</p>\n",
                   o.models.empty() ? "" : " (those asked for)", o.size, o.size, html_escape(r.validate_summary));
  if (!o.cost)
    b += "<p class=skip>Cost not measured (<code>--no-cost</code>): <code>facet docs -o DIR</code> measures it, or "
         "reads <code>--cost COST.json</code>, the output of <code>facet cost --json</code>.</p>\n";
  b += "<table><tr><th>model</th><th>lobe</th><th>formula</th><th>sphere</th><th>θ_l = " +
       fmt::format("{:g}", o.light_angles.back()) + "°</th>";
  for (const auto& t : targets()) b += "<th>" + t + "</th>";
  b += "<th>cost (× baseline)</th></tr>\n";
  for (const auto& m : ms) {
    const ModelDef& def = lobe_def(m);
    std::string key = identifier(m.name);
    b += fmt::format("<tr><td><a href=\"models/{0}.html\"><b>{1}</b></a><br><code>{0}</code></td><td><span class=\"badge "
                     "{2}\">{2}</span></td><td><code>{3}</code></td><td><img class=thumb src=\"validate/{4}\" alt=\"\"></td>"
                     "<td><img class=plot src=\"{5}\" alt=\"\"></td>",
                     html_escape(def.name), html_escape(def.title), def.section, html_escape(def.formula),
                     validate_image(key, "single", reference_renderer().name), plot_file(def.name, "polar", o.light_angles.back()));
    for (const auto& t : targets()) b += verdict_cell(key, t, v);
    const CostRow* row = o.cost ? o.cost->find(def.name) : nullptr;
    b += "<td>" + (row ? relative_summary(*row) : std::string("<span class=skip>not measured</span>")) + "</td></tr>\n";
  }
  b += "</table>\n";
  return page("facet — models", b, false);
}

std::string terms_page() {
  const std::vector<std::pair<std::string, std::string>> sections = {
      {"fresnel", "Fresnel terms (F)"},      {"geometry", "Masking and shadowing (G)"},
      {"distribution", "Facet distributions (D)"}, {"layering", "Layering operators"}, {"modifier", "Modifiers"},
      {"term", "Ambient and emission"},      {"light", "Lights"},
      {"attenuation", "Attenuation laws"}};
  std::string b = "<h1>Terms, lights and attenuation</h1>\n<p>The parts the lobes are built from and the scene's "
                  "lights, as the catalog defines them.</p>\n";
  for (const auto& [name, title] : sections) {
    b += fmt::format("<h2>{}</h2>\n", html_escape(title));
    for (const ModelDef* m : section(name)) {
      b += model_header(*m, "h3") + params_table(*m);
      if (!m->blender_nodes.nodes.empty())
        b += fmt::format("<p><b>Blender nodes</b> (the add-on's Build Blender Nodes): {}, {}</p>\n",
                         level_name(m->blender_nodes.level), blender_nodes_html(m->blender_nodes));
    }
  }
  return page("facet — terms", b, false);
}

std::string cost_page(const DocsOptions& o) {
  std::string b = "<h1>Cost</h1>\n";
  if (!o.cost) return page("facet — cost", b + not_measured(o, ""), false);
  b += fmt::format("<p>From <code>{}</code>; relative figures are to the baseline, <code>{}</code>.</p>\n",
                   html_escape(o.cost->source), html_escape(o.cost->baseline));
  b += "<table><tr><th>row</th><th>diffuse</th><th>specular</th>" + cost_headings() + "</tr>\n";
  for (const auto& r : o.cost->rows) {
    b += fmt::format("<tr><td><b>{}</b><br><code>{}</code></td><td>{}</td><td>{}</td>", html_escape(r.name),
                     html_escape(r.material), html_escape(r.diffuse.empty() ? "–" : r.diffuse),
                     html_escape(r.specular.empty() ? "–" : r.specular));
    for (const auto& format : cost_format()) b += "<td>" + cell_html(r.cell(format.target), format) + "</td>";
    b += "</tr>\n";
  }
  b += "</table>\n";
  for (const auto& [title, list] : {std::pair{"The frame alone (what every row includes)", &o.cost->frame},
                                    std::pair{"Measured with", &o.cost->tools}}) {
    if (list->empty()) continue;
    b += "<h2>" + std::string(title) + "</h2>\n<table>\n";
    for (const auto& [k, v] : list->items())
      b += fmt::format("<tr><td><code>{}</code></td><td>{}</td></tr>\n", html_escape(k), html_escape(shown(v)));
    b += "</table>\n";
  }
  return page("facet — cost", b, false);
}

// The lobe models asked for, checked before anything is drawn.
std::vector<Material> chosen_models(const DocsOptions& o) {
  std::vector<Material> all = model_materials();
  if (o.models.empty()) return all;
  std::vector<std::string> names;
  for (const auto& m : all) names.push_back(m.name);
  std::vector<Diagnostic> problems;
  std::vector<Material> out;
  for (const auto& want : o.models) {
    auto it = std::find(names.begin(), names.end(), want);
    if (it != names.end()) {
      out.push_back(all[size_t(it - names.begin())]);
      continue;
    }
    std::string hint = suggest(want, names);
    problems.push_back({"command line", "--models",
                        fmt::format("unknown lobe model \"{}\"{}; allowed: {}", want,
                                    hint.empty() ? "" : " (did you mean \"" + hint + "\"?)", quoted_list(names)),
                        0, 0});
  }
  if (!problems.empty()) throw InputError(problems);
  return out;
}

void make_folder(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw IoError(dir.string() + ": cannot create the folder: " + ec.message());
}

void draw_diagrams(const Material& m, const DocsOptions& o, const fs::path& out) {
  const ModelDef& def = lobe_def(m);
  for (double a : o.light_angles) {
    PlotOptions p;
    p.light_angle = a;
    p.title = def.title;
    p.view = PlotOptions::View::Polar;
    write_plot(m, p, (out / plot_file(def.name, "polar", a)).string());
    p.view = PlotOptions::View::Lobe3d;
    write_plot(m, p, (out / plot_file(def.name, "lobe3d", a)).string());
  }
}

}  // namespace

DocsResult write_docs(const DocsOptions& options, std::ostream& progress) {
  auto start = Clock::now();
  DocsOptions o = options;
  std::vector<Material> ms = chosen_models(o);
  fs::path out = o.out;
  make_folder(out / "models");
  make_folder(out / "plots");
  progress << fmt::format("facet docs: {} lobe models into {}\n", ms.size(), out.string());
  if (!o.cost && o.measure_cost) {
    CostOptions co;
    co.python = o.python;
    CostBaselines baselines;
    auto rows = measure_costs(ms, co, [&](const std::string& what) { progress << "  cost: " << what << "\n"; }, &baselines);
    o.cost = cost_table(rows, baselines, "facet cost (measured for these pages)");
  }

  std::vector<bool> anisotropic;
  for (size_t i = 0; i < ms.size(); ++i) {
    anisotropic.push_back(LobeSampler(ms[i]).anisotropic());
    draw_diagrams(ms[i], o, out);
    progress << fmt::format("{}  diagrams {} {}/{}{}", o.interactive ? "\r" : "", ms[i].name, i + 1, ms.size(),
                            o.interactive ? "" : "\n")
             << std::flush;
  }
  progress << fmt::format("{}  diagrams: {} models in {:.1f} s\n", o.interactive ? "\r" : "", ms.size(),
                          std::chrono::duration<double>(Clock::now() - start).count());

  ValidateOptions vo;
  vo.given = ms;
  vo.scenes = {"single"};
  vo.width = vo.height = o.size;
  vo.renderers = o.renderers;
  const std::string& reference = reference_renderer().name;  // every page shows the reference sphere
  if (std::find(vo.renderers.begin(), vo.renderers.end(), reference) == vo.renderers.end())
    vo.renderers.insert(vo.renderers.begin(), reference);
  o.renderers = vo.renderers;
  vo.out = (out / "validate").string();
  vo.python = o.python;
  vo.interactive = o.interactive;
  ValidateResult vr = validate(vo, progress);

  DocsResult result;
  result.validate_summary = vr.summary;
  result.comparisons = vr.rows.size();
  for (const auto& r : vr.rows) result.passed += r.pass;
  Verdicts verdicts{&vr, &o};
  write_file_atomic((out / "style.css").string(), kStyle);
  for (size_t i = 0; i < ms.size(); ++i) {
    const ModelDef& def = lobe_def(ms[i]);
    write_file_atomic((out / "models" / (def.name + ".html")).string(),
                      model_page(ms[i], o, verdicts, anisotropic[i]));
    ++result.pages;
  }
  write_file_atomic((out / "terms.html").string(), terms_page());
  write_file_atomic((out / "cost.html").string(), cost_page(o));
  // The index last: it only ever links pages that exist.
  write_file_atomic((out / "index.html").string(), index_page(ms, o, verdicts, result));
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace facet
