// facet — the command line.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "facet/catalog.h"
#include "facet/compare.h"
#include "facet/docs.h"
#include "facet/cost.h"
#include "facet/gltf.h"
#include "facet/image.h"
#include "facet/render.h"
#include "facet/renderers.h"
#include "facet/io.h"
#include "facet/material.h"
#include "facet/physics.h"
#include "facet/plot.h"
#include "facet/reference.h"
#include "facet/scene.h"
#include "facet/sweep.h"
#include "facet/targets.h"
#include "facet/validate.h"

using nlohmann::json;

namespace facet {
namespace {

// ---------------------------------------------------------------- generate

struct GenerateArgs {
  std::string material;
  std::string target = "glsl";
  std::string scene;
  std::string output;
  bool library = false;
  bool json = false;  // --json: print what was generated as one JSON object
};

// The material argument may be left out for a POV-Ray scene whose objects all carry their own materials.
std::optional<Material> load_optional_material(const std::string& path, const std::optional<Scene>& scene,
                                               const std::string& why) {
  if (!path.empty()) return load_material(path);
  if (scene && scene->has_own_materials()) return std::nullopt;
  throw InputError({{"command line", "MATERIAL", "a material file is required " + why, 0, 0}});
}

int run_generate(const GenerateArgs& a) {
  auto target = parse_target(a.target);  // CLI11 already checked the name
  std::optional<Scene> scene;
  if (!a.scene.empty()) scene = load_scene(a.scene);
  bool whole_scene = *target == Target::Pov && !a.library;
  std::optional<Material> m = whole_scene ? load_optional_material(a.material, scene,
                                                                   "unless every object of --scene has its own")
                                          : load_optional_material(a.material, std::nullopt,
                                                                   "for --target " + a.target + (a.library ? " --library" : ""));
  std::string code;
  if (m) {
    GenerateOptions o;
    o.target = *target;
    o.library = a.library;
    o.source = a.material;
    o.scene = scene;
    code = generate(*m, o);
  } else {
    code = generate_pov_scene(*scene, nullptr, a.scene);
  }
  bool to_stdout = a.output.empty() || a.output == "-";
  if (a.json) {
    using ojson = nlohmann::ordered_json;  // keys in the documented order
    ojson j = {{"target", a.target}, {"output", to_stdout ? ojson() : ojson(a.output)}};
    if (whole_scene) {  // the scene generate() renders: --scene's, else default_scene()
      PovPlan p = m ? pov_plan(*m, scene ? *scene : default_scene()) : pov_plan(*scene, nullptr);
      j["pov"] = {{"passes", p.passes}, {"native", p.native}, {"reason", p.reason}};
    }
    if (to_stdout) j["code"] = code;
    else write_file_atomic(a.output, code);
    std::cout << j.dump() << "\n";
    return 0;
  }
  if (to_stdout) {
    std::cout << code;
    return 0;
  }
  write_file_atomic(a.output, code);
  return 0;
}

// ---------------------------------------------------------------- eval

Vec3 unit_vector(const json& j, const std::string& path, DiagnosticSink& sink, bool& ok) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number()) {
    sink.error(path, "expected an array of three numbers, found " + json_type_name(j));
    ok = false;
    return {};
  }
  Vec3 v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  double len = length(v);
  if (!(len > 0) || !std::isfinite(len)) {
    sink.error(path, "has no direction (zero or not finite); allowed: a non-zero vector");
    ok = false;
    return {};
  }
  return v / len;
}

int run_eval(const std::string& material_path) {
  Material m = load_material(material_path);
  Reference ref(m);
  std::stringstream in;
  in << std::cin.rdbuf();
  const std::string file = "(stdin)";
  json sets = parse_json(in.str(), file);
  DiagnosticSink sink(file);
  if (!sets.is_array()) {
    sink.error("", "expected an array of direction sets {\"n\", \"l\", \"v\", \"t\"?}, found " + json_type_name(sets));
    sink.throw_if_any();
  }
  json out = json::array();
  for (size_t i = 0; i < sets.size(); ++i) {
    const json& s = sets[i];
    std::string path = index_path("", i);
    if (!s.is_object()) {
      sink.error(path, "expected an object {\"n\", \"l\", \"v\", \"t\"?}, found " + json_type_name(s));
      continue;
    }
    for (const auto& [key, val] : s.items())
      if (key != "n" && key != "l" && key != "v" && key != "t")
        sink.error(join_path(path, key), "unknown key; allowed keys: \"n\", \"l\", \"v\", \"t\"");
    bool ok = true;
    auto get = [&](const char* key) -> Vec3 {
      if (!s.contains(key)) {
        sink.error(join_path(path, key), "missing; allowed: an array of three numbers");
        ok = false;
        return {};
      }
      return unit_vector(s[key], join_path(path, key), sink, ok);
    };
    Vec3 n = get("n"), l = get("l"), v = get("v");
    Vec3 t;
    if (ok && s.contains("t")) {
      t = unit_vector(s["t"], join_path(path, "t"), sink, ok);
      // MODELS.md needs t ⟂ n: keep the part of t across n.
      Vec3 across = t - n * dot(n, t);
      if (ok && length(across) < kEpsilon) {
        sink.error(join_path(path, "t"), "is parallel to n; allowed: a tangent across the normal");
        ok = false;
      }
      if (ok) t = normalize(across);
    } else if (ok) {
      t = tangent_rule(n, Vec3(m.tangent_axis));
    }
    if (!ok) continue;
    RGB c = ref.reflectance(n, l, v, t);
    out.push_back({c[0], c[1], c[2]});
  }
  sink.throw_if_any();
  std::cout << out.dump() << "\n";
  return 0;
}

// ---------------------------------------------------------------- render

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

bool parse_size(const std::string& s, int& w, int& h) {
  auto x = s.find('x');
  if (x == std::string::npos) return false;
  try {
    w = std::stoi(s.substr(0, x));
    h = std::stoi(s.substr(x + 1));
  } catch (...) {
    return false;
  }
  return w > 0 && h > 0 && w <= 16384 && h <= 16384;
}

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

// ---------------------------------------------------------------- sweep

struct SweepArgs {
  std::vector<std::string> materials;
  bool extremes = false;
  std::string renderers = "reference,glsl,osl,pov";
  int grid = 1024;
  size_t random = 800000;
  std::string workdir;
  std::string python;
};

int run_sweep(const SweepArgs& a) {
  std::vector<Material> ms;
  std::vector<std::string> files = a.materials;
  if (files.empty()) {
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(FACET_SOURCE_DIR) / "examples/materials"))
      files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
  }
  for (const auto& f : files) ms.push_back(load_material(f));
  if (a.extremes)
    for (auto& m : extreme_materials()) ms.push_back(m);
  std::string workdir = a.workdir.empty() ? (std::filesystem::temp_directory_path() / "facet-sweep").string() : a.workdir;
  auto has = [&](const char* r) { return a.renderers.find(r) != std::string::npos; };
  std::vector<std::vector<SweepCount>> rows(ms.size());
  // Targets run one after another; the reference on both cores.
  if (has("reference")) {
    std::vector<SweepCount> counts(ms.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
      for (size_t i; (i = next++) < ms.size();) counts[i] = sweep_reference(ms[i], 512, a.random);
    };
    std::thread t1(work), t2(work);
    t1.join();
    t2.join();
    for (size_t i = 0; i < ms.size(); ++i) rows[i].push_back(counts[i]);
    fmt::print(stderr, "reference: {} materials swept\n", ms.size());
  }
  if (has("glsl")) {
    GlRenderer gl;
    for (size_t i = 0; i < ms.size(); ++i) rows[i].push_back(sweep_glsl(gl, ms[i], a.grid));
    fmt::print(stderr, "glsl: {} materials swept\n", ms.size());
  }
  if (has("osl")) {
    auto counts = sweep_osl(ms, std::min(a.grid, 512), a.python.empty() ? default_python() : a.python, workdir + "/osl");
    for (size_t i = 0; i < ms.size(); ++i) rows[i].push_back(counts[i]);
    fmt::print(stderr, "osl: {} materials swept\n", ms.size());
  }
  if (has("pov")) {
    for (size_t i = 0; i < ms.size(); ++i) rows[i].push_back(sweep_pov(ms[i], std::min(a.grid, 256), workdir + "/pov"));
    fmt::print(stderr, "pov: {} materials swept\n", ms.size());
  }
  std::map<std::string, size_t> samples;
  size_t bad_rows = 0;
  fmt::print("{:<34} {:<10} {:>10} {:>6} {:>6} {:>9}\n", "material", "target", "samples", "NaN", "Inf", "negative");
  for (size_t i = 0; i < ms.size(); ++i) {
    for (const auto& c : rows[i]) {
      samples[c.target] += c.samples;
      if (!c.ok()) ++bad_rows;
      if (!c.error.empty()) {
        fmt::print("{:<34} {:<10} FAILED: {}\n", ms[i].name, c.target, c.error.substr(0, c.error.find('\n')));
        continue;
      }
      fmt::print("{:<34} {:<10} {:>10} {:>6} {:>6} {:>9}{}\n", ms[i].name, c.target, c.samples, c.nan, c.inf, c.negative,
                 c.ok() ? "" : "   <-- bad values");
    }
  }
  std::string totals;
  for (const auto& [t, n] : samples) totals += fmt::format("{}{} {}", totals.empty() ? "" : ", ", t, n);
  fmt::print("sweep: {} materials; direction sets checked: {}; {} with NaN, Inf or negative values or errors\n", ms.size(),
             totals, bad_rows);
  return bad_rows ? 1 : 0;
}

// ---------------------------------------------------------------- physics

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

// ---------------------------------------------------------------- cost

struct CostArgs {
  std::vector<std::string> materials;
  bool as_json = false;
  std::string markdown;
  std::string check;
  bool no_timings = false;
  bool no_callgrind = false;
  CostOptions options;
};

int run_cost(CostArgs a) {
  std::vector<Material> ms;
  for (const auto& f : a.materials) ms.push_back(load_material(f));
  if (ms.empty()) ms = model_materials();
  a.options.timings = !a.no_timings && a.check.empty();
  a.options.callgrind = !a.no_callgrind && callgrind_available();
  if (!a.no_callgrind && !callgrind_available())
    fmt::print(stderr, "note: no llvmpipe instruction counts: valgrind cannot run this sanitizer build of facet "
                       "(the release build counts them)\n");
  auto start = std::chrono::steady_clock::now();
  auto progress = [&](const std::string& what) {
    fmt::print(stderr, "cost [{:5.1f} s]: {}\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
               what);
  };
  CostBaselines baselines;
  std::vector<CostRow> rows = measure_costs(ms, a.options, progress, &baselines);
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print(stderr, "cost: {} materials in {:.1f} s\n", rows.size(), wall);
  int status = std::all_of(rows.begin(), rows.end(), [](const CostRow& r) { return r.ok(); }) ? 0 : 1;
  if (a.as_json) std::cout << costs_json(rows, baselines).dump(2) << "\n";
  else std::cout << costs_table(rows, baselines);
  if (!a.markdown.empty()) write_file_atomic(a.markdown, costs_markdown(rows, baselines, a.options, wall));
  if (!a.check.empty()) {
    std::vector<std::string> stale = stale_costs(read_file(a.check), rows);
    for (const auto& line : stale) fmt::print("stale: {}\n", line);
    if (!stale.empty()) {
      fmt::print("{} is out of date; regenerate it with: facet cost --markdown {}\n", a.check, a.check);
      status = 1;
    } else {
      fmt::print("{}: every count is what the measurement gives\n", a.check);
    }
  }
  return status;
}

// ---------------------------------------------------------------- plot

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

// ---------------------------------------------------------------- docs

struct DocsArgs {
  DocsOptions options;
  std::string cost;
  bool no_cost = false;
  std::string models;
  std::string renderers = "reference,glsl,osl,pov";
};

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<std::string> renderer_list(const std::string& option, const std::string& names) {
  std::vector<std::string> out;
  for (const auto& r : split_commas(names)) {
    if (r != "reference" && r != "glsl" && r != "osl" && r != "pov")
      throw InputError({{"command line", option, "unknown renderer \"" + r + "\"; allowed: reference, glsl, osl, pov", 0, 0}});
    out.push_back(r);
  }
  return out;
}

int run_docs(DocsArgs& a) {
  // Every input is checked before anything is drawn or written.
  if (!a.cost.empty()) a.options.cost = load_cost_rows(a.cost);
  a.options.models = split_commas(a.models);
  a.options.renderers = renderer_list("--renderers", a.renderers);
  a.options.measure_cost = a.cost.empty() && !a.no_cost;
  a.options.interactive = isatty(2);
  DocsResult r = write_docs(a.options, std::cerr);
  fmt::print("facet docs: {} model pages in {:.1f} s; {} of {} renderer comparisons pass; open {}\n", r.pages,
             r.seconds, r.passed, r.comparisons, (std::filesystem::path(a.options.out) / "index.html").string());
  if (r.passed == r.comparisons) return 0;
  // The catalog is whole (each failure is on its pages), but what it documents failed.
  fmt::print(stderr, "error: {} of {} renderer comparisons failed; the pages show each with its reason\n",
             r.comparisons - r.passed, r.comparisons);
  return 1;
}

// ---------------------------------------------------------------- models

json catalog_json() {
  json sections = json::object();
  for (const auto& m : catalog()) {
    json params = json::array();
    for (const auto& p : m.params) {
      json pj = {{"name", p.name}, {"type", param_kind_name(p.kind)}, {"doc", p.doc}, {"required", p.required},
                 {"allowed", p.allowed()}};
      if (p.kind == ParamKind::Number || p.kind == ParamKind::Color) {
        pj["range"] = {{"min", std::isfinite(p.range.min) ? json(p.range.min) : json(nullptr)},
                       {"max", std::isfinite(p.range.max) ? json(p.range.max) : json(nullptr)},
                       {"min_exclusive", p.range.min_open},
                       {"max_exclusive", p.range.max_open}};
      }
      if (p.kind == ParamKind::Enum) pj["choices"] = p.choices;
      if (p.kind == ParamKind::Model || p.kind == ParamKind::Object) pj["section"] = p.section;
      if (p.kind != ParamKind::Object) pj["default"] = default_json(p);
      params.push_back(pj);
    }
    json mj = {{"name", m.name},       {"title", m.title}, {"citation", m.citation},
               {"formula", m.formula}, {"doc", m.doc},     {"parameters", params}};
    if (m.section == "diffuse" || m.section == "specular") {
      mj["cycles"] = {{"level", level_name(m.cycles.level)}, {"note", m.cycles.note}};
      mj["pov"] = {{"level", level_name(m.pov.level)}, {"note", m.pov.note}};
      // Claims from the literature; docs/physics.md holds the measurement (facet physics).
      mj["physics"] = {{"reciprocal", m.reciprocal},
                       {"energy_conserving", m.energy_conserving},
                       {"note", m.physics_note}};
    }
    sections[m.section].push_back(mj);
  }
  return {{"facet", FACET_VERSION}, {"epsilon", kEpsilon}, {"sections", sections}};
}

int run_models(bool as_json) {
  if (as_json) {
    std::cout << catalog_json().dump(2) << "\n";
    return 0;
  }
  std::string current;
  for (const auto& m : catalog()) {
    if (m.section != current) {
      current = m.section;
      fmt::print("\n{}\n{}\n", current, std::string(current.size(), '-'));
    }
    fmt::print("  {:<18} {}\n", m.name, m.formula);
    if (!m.citation.empty()) fmt::print("  {:<18} {}\n", "", m.citation);
    for (const auto& p : m.params) {
      if (p.name == "color" || p.name == "toon") continue;
      std::string dflt;
      if (p.kind == ParamKind::Number) dflt = fmt::format(", default {}", p.fallback.number);
      if (p.kind == ParamKind::Enum) dflt = fmt::format(", default \"{}\"", p.fallback.choice);
      if (p.kind == ParamKind::Model && p.fallback.model) dflt = fmt::format(", default {}", p.fallback.choice);
      fmt::print("  {:<18}   {}{}: {}{}\n", "", p.name, p.required ? " (required)" : "", p.allowed(), dflt);
    }
  }
  fmt::print("\nEvery diffuse and specular lobe also takes \"color\" (k_d or k_s, default 1) and \"toon\".\n");
  return 0;
}

}  // namespace
}  // namespace facet

int main(int argc, char** argv) {
  using namespace facet;
  CLI::App app{"facet " FACET_VERSION
               " — one material description, equivalent GLSL, OSL and POV-Ray code, and a C++ reference.\n"};
  app.require_subcommand(1);
  app.footer(
      "Examples:\n"
      "  facet generate examples/materials/ggx.json --target glsl -o ggx.frag\n"
      "  facet generate examples/materials/oren_nayar.json --target pov -o oren.pov && \\\n"
      "    povray +Ioren.pov +Ooren.png +W256 +H256 -A +FN16 File_Gamma=1.0\n"
      "  echo '[{\"n\":[0,0,1],\"l\":[0,1,1],\"v\":[0,0,1]}]' | facet eval examples/materials/lambert.json\n"
      "  facet models\n"
      "Run 'facet <command> --help' for a command's options. Formulas: MODELS.md.");

  GenerateArgs gen;
  auto* g = app.add_subcommand("generate", "Generate GLSL, OSL or POV-Ray code from a material file");
  g->add_option("material", gen.material,
                "The material (JSON; see 'facet schema'). May be left out for --target pov when every object of "
                "--scene has its own material");
  g->add_option("-t,--target", gen.target,
                "glsl (GLSL 3.30 core), glsl450 (Vulkan, compiles to SPIR-V), essl (OpenGL ES 3.00), "
                "osl (Cycles shader), pov (POV-Ray 3.7 scene)")
      ->check(CLI::IsMember({"glsl", "glsl450", "essl", "osl", "pov"}))
      ->capture_default_str();
  g->add_option("--scene", gen.scene,
                "Scene for OSL's lights and POV-Ray's frame: a scene file or a built-in name (single, shadows). "
                "Default: single");
  g->add_flag("--library", gen.library,
              "Only the functions, for an engine (GLSL, OSL), or an include file declaring the texture (POV-Ray)");
  g->add_option("-o,--output", gen.output, "Output file; standard output without it. Written whole or not at all");
  g->add_flag("--json", gen.json,
              "Print one JSON object describing what was generated: target, output, and for POV-Ray scenes the "
              "passes to render (\"pov\": {passes, native, reason}); without -o the code is its \"code\"");
  g->footer(
      "Examples:\n"
      "  facet generate mat.json --target glsl450 -o mat.frag && glslangValidator -V mat.frag\n"
      "  facet generate mat.json --target osl --scene shadows -o mat.osl\n"
      "  facet generate mat.json --target pov -o mat.pov      # a complete scene: sphere, camera, light\n"
      "  facet generate mat.json --target glsl --library       # just the functions: facet_reflect(n, l, v, t)\n"
      "  facet generate --target pov --scene examples/scenes/three_meshes.json -o meshes.pov  # objects' own materials\n"
      "Nothing is written when the material has an error; the exit status is then 1.");

  std::string eval_material;
  auto* e = app.add_subcommand("eval", "Evaluate the C++ reference for direction sets read from standard input");
  e->add_option("material", eval_material, "The material (JSON)")->required();
  e->footer(
      "Reads a JSON array of {\"n\": [x,y,z], \"l\": [...], \"v\": [...], \"t\": [...]} (t optional: without it,\n"
      "t = normalize(tangent_axis × n)). Vectors are normalized; t is made perpendicular to n. Writes a JSON array\n"
      "of [r, g, b] = k_d ⊗ ρ_d + k_s ⊗ ρ_s for one white light: no attenuation, ambient or emission.\n"
      "Example:\n"
      "  echo '[{\"n\":[0,0,1],\"l\":[0,1,1],\"v\":[0,-1,1]}]' | facet eval examples/materials/phong.json");

  bool models_json = false;
  auto* mo = app.add_subcommand("models", "List the model catalog: parameters, ranges, defaults, citations");
  mo->add_flag("--json", models_json, "Machine-readable (the Blender add-on reads this)");

  RenderArgs ra;
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

  ValidateOptions va;
  std::string va_size = "256x256", va_renderers = "reference,glsl,osl,pov";
  auto* v = app.add_subcommand("validate",
                               "Render materials through OpenGL, Cycles (OSL) and POV-Ray and compare each with the "
                               "C++ reference, pixel by pixel");
  v->add_option("materials", va.materials, "Material files (default: every examples/materials/*.json)");
  v->add_option("--scene", va.scenes, "A built-in scene (single, shadows) or a scene file; repeat for several "
                                      "(default: single and shadows)");
  v->add_option("--size", va_size, "Image size WIDTHxHEIGHT")->capture_default_str();
  v->add_option("--renderers", va_renderers, "Comma-separated: reference, glsl, osl, pov")->capture_default_str();
  v->add_option("--out", va.out, "Where metrics.json, report.html and the images go")->capture_default_str();
  v->add_option("--python", va.python, "The Python with bpy 4.5 for Cycles (default: FACET_PYTHON, then the "
                                       "build's .venv)");
  v->add_option("--tolerance", va.tolerance, "Pass when |Δ| ≤ TOL · max(1, |reference|) on every interior pixel")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  v->footer(
      "Each renderer draws the same scene, one sample at each pixel centre, linear and unclamped:\n"
      "  reference  facet's C++ ray caster shading with the C++ reference (double)\n"
      "  glsl       the generated GLSL in headless OpenGL (EGL; Mesa llvmpipe without a GPU), RGBA32F\n"
      "  osl        the generated OSL in Blender 4.5's Cycles (CPU, OSL), one Blender process per scene\n"
      "  pov        the generated POV-Ray scene, 16-bit linear PNG, antialiasing off\n"
      "Writes OUT/metrics.json (one row per material × scene × renderer), OUT/report.html (images side by side,\n"
      "|Δ| × 16, failures first) and exits 1 when any comparison fails; a renderer that cannot run fails.\n"
      "Examples:\n"
      "  facet validate                                   # the whole example catalog, both scenes\n"
      "  facet validate my.json --scene shadows --renderers reference,glsl --size 128x128");

  std::string gi_in, gi_out, gi_default;
  auto* gi = app.add_subcommand("import-gltf", "Turn a glTF 2.0 scene (.gltf, .glb) into a facet scene file");
  gi->add_option("scene", gi_in, "The glTF file")->required();
  gi->add_option("-o,--output", gi_out, "The facet scene (JSON)")->required();
  gi->add_option("--default-material", gi_default, "A facet material for primitives without one");
  gi->footer(
      "Meshes (node transforms applied), the first perspective camera, KHR_lights_punctual lights and the\n"
      "materials: FACET_material exactly, else metallic–roughness as GGX (α = roughness², separable Smith,\n"
      "Schlick f0 = mix(0.04, base, metallic)) over Lambert (base · (1 − metallic)). What is approximate or\n"
      "ignored is printed. Example:\n"
      "  facet import-gltf examples/scenes/three_meshes.gltf -o scene.json && facet validate --scene scene.json");

  std::string ge_in, ge_out, ge_material;
  auto* ge = app.add_subcommand("export-gltf", "Write a facet scene as glTF 2.0 with its facet materials");
  ge->add_option("scene", ge_in, "The facet scene (JSON) or a built-in name")->required();
  ge->add_option("-o,--output", ge_out, "The glTF file: .gltf (one file) or .glb")->required();
  ge->add_option("--material", ge_material, "A facet material for objects without one");
  ge->footer(
      "Materials carry the whole facet description (FACET_material) beside the nearest metallic–roughness\n"
      "fallback; spheres and planes are tessellated and keep their exact definition (FACET_object). Example:\n"
      "  facet export-gltf examples/scenes/three_meshes.json -o three_meshes.gltf");

  SweepArgs sw;
  auto* swc = app.add_subcommand("sweep", "Check for NaN, Inf and negative values over dense direction sets");
  swc->add_option("materials", sw.materials, "Material files (default: every examples/materials/*.json)");
  swc->add_flag("--extremes", sw.extremes, "Also every model at the ends of its parameter ranges");
  swc->add_option("--renderers", sw.renderers, "Comma-separated: reference, glsl, osl, pov")->capture_default_str();
  swc->add_option("--grid", sw.grid, "Direction-set grid side for OpenGL (OSL takes at most 512, POV-Ray 256)")
      ->capture_default_str();
  swc->add_option("--random", sw.random, "Random direction sets on the C++ reference, besides its 512² grid")
      ->capture_default_str();
  swc->add_option("--workdir", sw.workdir, "Where the harnesses' files go");
  swc->add_option("--python", sw.python, "The Python with bpy 4.5 (default: FACET_PYTHON, then the build's .venv)");
  swc->footer(
      "The grid (facet/sweep.h) holds the hard places: n·l and n·v at 1, 1e-7, 1e-4, 0, below the horizon;\n"
      "l = v; h = n; l = −v grazing; the normal along the tangent axis. The reference adds random sets near\n"
      "them. Exit 1 when any value is NaN, infinite or negative. Example:\n"
      "  facet sweep my.json --extremes --renderers reference,glsl");

  PhysicsArgs ph;
  auto* phc = app.add_subcommand("physics", "Measure each lobe's reciprocity and albedo (the white furnace)");
  phc->add_option("-o,--output", ph.output, "Write the Markdown report (docs/physics.md)");
  phc->add_option("--check", ph.check, "Exit 1 unless this file is exactly what the measurement gives");
  phc->add_option("--samples", ph.samples, "Monte Carlo samples per albedo estimate")->capture_default_str()
      ->check(CLI::Range(size_t(64), size_t(1) << 30));
  phc->footer(
      "f(l, v) = ρ/(π n·l) against f(v, l), and a(l) = ∫ f (n·v) dω by importance-sampled Monte Carlo, for every\n"
      "diffuse and specular lobe over its parameters and incidence angles (see facet/physics.h). Exit 1 when a\n"
      "measurement contradicts the catalog: reciprocity, or albedo above 1 for a lobe called energy-conserving.\n"
      "Examples:\n"
      "  facet physics -o docs/physics.md\n"
      "  facet physics --check docs/physics.md");

  PlotArgs pl;
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
      "Examples:\n"
      "  facet plot examples/materials/phong.json --light-angle 45 -o phong.svg\n"
      "  facet plot examples/materials/ward.json --light-angle 30 --view lobe3d -o ward.png\n"
      "  facet plot examples/materials/ggx.json --light-angle 60 --scale log -o ggx.png");

  DocsArgs da;
  auto* dc = app.add_subcommand("docs", "Generate the model catalog as static HTML: formulas, diagrams, renders, cost");
  dc->add_option("-o,--out", da.options.out, "The folder to write (index.html, models/, plots/, validate/)")->required();
  dc->add_option("--cost", da.cost, "The output of 'facet cost --json': each model's cost row (default: measured now)");
  dc->add_flag("--no-cost", da.no_cost, "Leave the cost out (the pages say it was not measured)");
  dc->add_option("--size", da.options.size, "The spheres' side in pixels")->capture_default_str()->check(CLI::Range(8, 2048));
  dc->add_option("--models", da.models, "Comma-separated lobe models (default: every diffuse and specular model)");
  dc->add_option("--renderers", da.renderers, "Comma-separated: reference, glsl, osl, pov")->capture_default_str();
  dc->add_option("--python", da.options.python, "The Python with bpy 4.5 for Cycles (default: FACET_PYTHON, then the "
                                               "build's .venv)");
  dc->footer(
      "One page per lobe model, the lobe alone at its defaults: formula, parameters, citation, notes, physics claims,\n"
      "polar and 3-D diagrams at θ_l = 20° and 60°, the sphere rendered by the reference, OpenGL, Cycles and POV-Ray\n"
      "(facet validate on the single scene) with each one's error, and the model's cost row. A renderer that fails is\n"
      "shown failed with its reason (and the exit status is 1). Viewable offline: no scripts, no network.\n"
      "Examples:\n"
      "  facet docs -o out/docs                              # every model, its cost measured: a few minutes\n"
      "  facet docs -o out/docs --cost cost.json             # cost rows from an earlier 'facet cost --json'\n"
      "  facet docs -o out/docs --no-cost                    # no cost rows: about 20 s\n"
      "  facet docs -o /tmp/d --models lambert,ward --renderers reference,glsl --size 64");
  CostArgs co;
  auto* coc = app.add_subcommand("cost", "Measure what each material costs on each target (the survey's Appendix B)");
  coc->add_option("materials", co.materials, "Material files (default: every lobe model of the catalog at its defaults)");
  coc->add_flag("--json", co.as_json, "Print {\"baseline\": \"lambert\", \"rows\": [...]} instead of the table");
  coc->add_option("--markdown", co.markdown, "Also write the table as Markdown (docs/cost.md)");
  coc->add_option("--check", co.check,
                  "Exit 1 unless this Markdown file's counts (SPIR-V, llvmpipe instructions, OSL ops, POV-Ray "
                  "functions) are what the measurement gives; no timings are taken");
  coc->add_flag("--no-timings", co.no_timings, "Only the deterministic counts: no Cycles or POV-Ray render times");
  coc->add_flag("--no-callgrind", co.no_callgrind, "No llvmpipe instruction counts (valgrind)");
  coc->add_option("--repeats", co.options.repeats, "Interleaved rounds of POV-Ray renders; each time is the least")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  coc->add_option("--cycles-repeats", co.options.cycles_repeats, "Interleaved rounds of Cycles renders")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  coc->add_option("--jobs", co.options.jobs, "Processes at once")->capture_default_str()->check(CLI::Range(1, 64));
  coc->add_option("--workdir", co.options.workdir, "Where shaders, scenes and the tools' outputs go (default: a temporary folder)");
  coc->add_option("--python", co.options.python, "The Python with bpy 4.5 (default: FACET_PYTHON, then the build's .venv)");
  coc->footer(
      "Per material (a row) and target: GLSL — SPIR-V instructions after spirv-opt -O of the single-light cost\n"
      "frame's fragment shader, and x86 instructions per pixel of its llvmpipe draw under callgrind; OSL — ops of\n"
      "the compiled .oso and Cycles' time per pixel and sample; POV-Ray — native finish or its function count, and\n"
      "the trace time per pixel. Times and counts also relative to Lambert. The table goes to standard output,\n"
      "progress to standard error; a tool that cannot run is an error in its rows and exit status 1.\n"
      "Examples:\n"
      "  facet cost                                   # the whole catalog, a few minutes\n"
      "  facet cost examples/materials/ward.json --json\n"
      "  facet cost --markdown docs/cost.md\n"
      "  facet cost --check docs/cost.md              # the counts only; what the test cost.table runs");

  // Hidden: what `facet cost` runs under valgrind (facet/cost.h, run_draw_job).
  std::string draw_job;
  auto* dr = app.add_subcommand("draw-shaders", "Draw the shaders of a cost job (run under callgrind by facet cost)");
  dr->group("");
  dr->add_option("job", draw_job, "The job file")->required();

  bool schema_scene = false;
  auto* sc = app.add_subcommand("schema", "Print the JSON Schema of material files (or of scene files)");
  sc->add_flag("--scene", schema_scene, "The scene schema instead");

  CLI11_PARSE(app, argc, argv);

  try {
    if (g->parsed()) return run_generate(gen);
    if (e->parsed()) return run_eval(eval_material);
    if (mo->parsed()) return run_models(models_json);
    if (rn->parsed()) return run_render(ra);
    if (swc->parsed()) return run_sweep(sw);
    if (phc->parsed()) return run_physics(ph);
    if (plc->parsed()) return run_plot(pl);
    if (dc->parsed()) return run_docs(da);
    if (dr->parsed()) return run_draw_job(draw_job);
    if (coc->parsed()) return run_cost(co);
    if (gi->parsed()) {
      GltfImportOptions opt;
      if (!gi_default.empty()) opt.default_material = load_material(gi_default);
      std::vector<std::string> notes;
      Scene s = import_gltf(gi_in, opt, notes);
      for (const auto& n : notes) std::cerr << "note: " << n << "\n";
      write_file_atomic(gi_out, to_json(s).dump(1) + "\n");
      fmt::print(stderr, "{}: {} objects, {} materials, {} lights\n", gi_out, s.objects.size(), s.materials.size(),
                 s.lights.size());
      return 0;
    }
    if (ge->parsed()) {
      Scene s = load_scene(ge_in);
      std::optional<Material> m;
      if (!ge_material.empty()) m = load_material(ge_material);
      std::vector<std::string> notes;
      export_gltf(s, m ? &*m : nullptr, ge_out, notes);
      for (const auto& n : notes) std::cerr << "note: " << n << "\n";
      return 0;
    }
    if (v->parsed()) {
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
    if (sc->parsed()) {
      std::cout << (schema_scene ? scene_schema() : material_schema()).dump(2) << "\n";
      return 0;
    }
  } catch (const InputError& err) {
    for (const auto& d : err.diagnostics()) std::cerr << "error: " << d.format() << "\n";
    return 1;
  } catch (const IoError& err) {
    std::cerr << "error: " << err.what() << "\n";
    return 1;
  }
  return 0;
}
