#include "analysis/validate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "core/diagnostics.h"
#include "core/html.h"
#include "core/io.h"
#include "reference/raycaster.h"
#include "renderers/renderer.h"

namespace facet {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

bool has_hard_toon(const Material& m) {
  for (const auto* lobe : {&m.diffuse, &m.specular}) {
    if (!*lobe) continue;
    auto it = (*lobe)->values.find("toon");
    if (it != (*lobe)->values.end() && it->second.model && it->second.model->at("width").number == 0) return true;
  }
  return false;
}

// One image to compare: a material on a scene, or a scene with its own materials.
struct Case {
  std::optional<Material> material;  // absent: the scene's own materials
  std::string key;                   // names the images: the material file's stem, or the scene's name
  Scene scene;
  std::string scene_key;             // names the scene's images and work folder (unique among the scenes)
  Render reference;
  std::string uninformative;  // why the reference proves nothing (validate.h), or ""
  std::string label() const { return material ? material->name : scene.name + " (its own materials)"; }
  std::string models() const {
    std::vector<const Material*> ms;
    if (material) ms.push_back(&*material);
    for (const auto& [k, m] : scene.materials) ms.push_back(&m);
    std::string s;
    for (const Material* m : ms) {
      std::string lobes = (m->diffuse ? m->diffuse->def->name : std::string("")) +
                          (m->diffuse && m->specular ? " + " : "") +
                          (m->specular ? m->specular->def->name : std::string(""));
      for (const auto& layer : m->layers) lobes += " under " + layer.def->name;
      if (s.find(lobes) == std::string::npos) s += (s.empty() ? "" : ", ") + lobes;
    }
    return s;
  }
  bool hard_toon() const {
    bool any = material && has_hard_toon(*material);
    for (const auto& [k, m] : scene.materials) any |= has_hard_toon(m);
    return any;
  }
};

std::string image_name(const Case& c, const std::string& renderer, const char* suffix = "") {
  return validate_image(c.key, c.scene_key, renderer + suffix);
}

// A renderer's image beside the reference: its preview at the exposure `ev` (stops) and
// |Δ| × 16 at the same exposure.
void write_images(const fs::path& out, const Case& c, const std::string& renderer, const Image& img, double ev) {
  const float scale = float(std::exp2(ev));
  write_png_preview((out / image_name(c, renderer)).string(), img, scale);
  if (renderer == reference_renderer().name) return;
  Image diff(img.width, img.height);
  for (size_t i = 0; i < diff.rgb.size(); ++i) diff.rgb[i] = std::fabs(img.rgb[i] - c.reference.image.rgb[i]);
  write_png_preview((out / image_name(c, renderer, "_diff")).string(), diff, 16.0f * scale, false);
}

json row_json(const ComparisonRow& r, int w, int h) {
  const Metrics& m = r.metrics;
  json j = {{"material", r.material},
            {"renderer", r.renderer},
            {"scene", r.scene},
            {"max_abs", m.max_abs},
            {"rmse", m.rmse},
            {"pixels", m.pixels},
            {"coverage_mismatch", r.coverage_mismatch},
            {"nan", m.nan},
            {"pass", r.pass},
            {"max_relative", m.max_excess},
            {"over", m.over},
            {"allowed_flips", r.allowed_flips},
            {"size", fmt::format("{}x{}", w, h)},
            {"seconds", r.seconds},
            {"file", r.key}};
  if (!r.error.empty()) j["error"] = r.error;
  if (!r.uninformative.empty()) j["uninformative"] = r.uninformative;
  if (!r.note.empty()) j["note"] = r.note;
  if (m.worst_x >= 0)
    j["worst"] = {{"x", m.worst_x},
                  {"y", m.worst_y},
                  {"reference", {m.worst_ref[0], m.worst_ref[1], m.worst_ref[2]}},
                  {"got", {m.worst_got[0], m.worst_got[1], m.worst_got[2]}}};
  return j;
}

std::string figures(const ComparisonRow& r) {
  if (!r.error.empty()) return "<div class=error>" + html_escape(r.error.substr(0, 2000)) + "</div>";
  const Metrics& m = r.metrics;
  const std::string why =
      (r.uninformative.empty() ? "" : "<div class=error>uninformative: " + html_escape(r.uninformative) + "</div>") +
      (r.note.empty() ? "" : "<div class=muted>" + html_escape(r.note) + "</div>");
  return why + fmt::format(
      "<div class=figs>max |Δ| {:.3g}<br>max |Δ|/max(1,|ref|) {:.3g}<br>rmse {:.3g}<br>over tolerance {}{}<br>"
      "coverage differs {:.3f} %<br>NaN/Inf {}<br>{} interior px</div>",
      m.max_abs, m.max_excess, m.rmse, m.over, r.allowed_flips ? fmt::format(" (≤ {} allowed: toon step)", r.allowed_flips) : "",
      100 * r.coverage_mismatch, m.nan, m.pixels);
}

const char* kReportHead = R"(<!doctype html>
<html lang=en><head><meta charset=utf-8><title>facet validate</title>
<style>
body { font: 14px/1.4 system-ui, sans-serif; margin: 24px; color: #222; background: #fafafa; }
h1 { margin: 0 0 8px; } .summary { font-size: 16px; font-weight: 600; }
.summary.pass { color: #1b6e2a; } .summary.fail { color: #b3261e; }
table { border-collapse: collapse; margin: 12px 0; }
th, td { border: 1px solid #ddd; padding: 6px 8px; vertical-align: top; background: #fff; }
th { background: #f0f0f0; text-align: left; }
tr.fail td:first-child { border-left: 5px solid #b3261e; } tr.pass td:first-child { border-left: 5px solid #1b6e2a; }
td.bad { background: #fdecea; }
img { width: 160px; height: auto; image-rendering: pixelated; display: block; background: #000; }
.pair { display: flex; gap: 4px; } .figs { font: 12px/1.35 ui-monospace, monospace; margin-top: 4px; }
.error { font: 12px/1.35 ui-monospace, monospace; color: #b3261e; white-space: pre-wrap; max-width: 340px; }
.name { font-weight: 600; } .muted { color: #666; font-size: 12px; }
</style></head><body>
<h1>facet validate</h1>
)";

// The renderers under test among `names`, in their order: all but the reference.
std::vector<std::string> under_test(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const auto& r : names)
    if (!find_renderer(r)->reference) out.push_back(r);
  return out;
}

// Per renderer: comparisons passed, the worst figures and the wall time.
std::string renderer_table(const std::vector<std::string>& targets, const ValidateResult& result) {
  std::string html = "<table><tr><th>renderer</th><th>comparisons passed</th><th>worst max |Δ|</th><th>worst "
                     "|Δ|/max(1,|ref|)</th><th>where</th><th>wall time</th></tr>\n";
  for (const auto& t : targets) {
    size_t n = 0, ok = 0;
    const ComparisonRow* worst = nullptr;
    for (const auto& r : result.rows) {
      if (r.renderer != t) continue;
      ++n;
      ok += r.pass;
      if (r.error.empty() && (!worst || r.metrics.max_excess > worst->metrics.max_excess)) worst = &r;
    }
    html += fmt::format("<tr><td>{}</td><td>{} / {}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.1f} s</td></tr>\n", t,
                        ok, n, worst ? fmt::format("{:.3g}", worst->metrics.max_abs) : "–",
                        worst ? fmt::format("{:.3g}", worst->metrics.max_excess) : "–",
                        worst ? html_escape(worst->material + " on " + worst->scene) : "–",
                        result.wall.count(t) ? result.wall.at(t) : 0.0);
  }
  return html + "</table>\n";
}

// One case's row: its name, the reference, and each renderer's image, difference and figures.
std::string case_row(const Case& c, bool failed, const std::vector<std::string>& targets, const ValidateResult& result) {
  std::string html =
      fmt::format("<tr class={}><td><div class=name>{}</div><div class=muted>{}<br>scene {}<br>{}</div></td>",
                  failed ? "fail" : "pass", html_escape(c.label()),
                  html_escape(!c.material ? c.scene.source : c.material->source.empty() ? "(built in)" : c.key + ".json"),
                  html_escape(c.scene.name), html_escape(c.models()));
  html += fmt::format("<td><img src=\"{}\" alt=\"reference\"></td>", image_name(c, reference_renderer().name));
  for (const auto& t : targets) {
    const ComparisonRow* row = nullptr;
    for (const auto& r : result.rows)
      if (r.key == c.key && r.scene == c.scene.name && r.renderer == t) row = &r;
    if (!row) continue;
    html += fmt::format("<td class=\"{}\">", row->pass ? "" : "bad");
    if (row->error.empty())
      html += fmt::format("<div class=pair><img src=\"{}\" alt=\"{}\"><img src=\"{}\" alt=\"difference\"></div>",
                          image_name(c, t), t, image_name(c, t, "_diff"));
    html += figures(*row) + "</td>";
  }
  return html + "</tr>\n";
}

void write_report(const fs::path& out, const ValidateOptions& o, const std::vector<Case>& cases,
                  const ValidateResult& result) {
  const std::vector<std::string> targets = under_test(o.renderers);
  std::string html = kReportHead;
  html += fmt::format("<p class=\"summary {}\">{}</p>\n", result.pass ? "pass" : "fail", html_escape(result.summary));
  html += renderer_table(targets, result);
  html += fmt::format(
      "<p class=muted>{}×{} pixels, one sample at each pixel centre; previews at each scene's exposure (radiance × "
      "2^EV, sRGB, clipped{}). A comparison passes when |renderer − reference| ≤ "
      "{:g} · max(1, |reference|) per channel on every interior pixel (the reference hit the same object at the pixel "
      "and its 8 neighbours, and no shadow ray there passes within 1e-4 of an occluder's edge), coverage differs on at "
      "most {:g} % of pixels, and no value is NaN or Inf. A hard toon step may flip {:g} % of interior pixels. "
      "Difference images show |Δ| × 16.</p>\n",
      o.width, o.height, o.exposure ? fmt::format("; --exposure {:g} for all", *o.exposure) : "", o.tolerance,
      100 * o.coverage_tolerance, 100 * o.flip_tolerance);

  // Rows, failures first.
  std::vector<size_t> order(cases.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto failed = [&](size_t i) {
    for (const auto& r : result.rows)
      if (r.key == cases[i].key && r.scene == cases[i].scene.name && !r.pass) return true;
    return false;
  };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return failed(a) && !failed(b); });
  html += "<table><tr><th>material</th><th>reference</th>";
  for (const auto& t : targets) html += "<th>" + t + " · |Δ| × 16</th>";
  html += "</tr>\n";
  for (size_t i : order) html += case_row(cases[i], failed(i), targets, result);
  html += "</table>\n</body></html>\n";
  write_file_atomic((out / "report.html").string(), html);
}

}  // namespace

std::vector<std::string> example_materials() {
  fs::path dir = "examples/materials";
#ifdef FACET_SOURCE_DIR
  if (!fs::exists(dir)) dir = fs::path(FACET_SOURCE_DIR) / "examples/materials";
#endif
  std::vector<std::string> files;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string validate_image(const std::string& key, const std::string& scene, const std::string& renderer) {
  return fmt::format("images/{}_{}_{}.png", key, identifier(scene), renderer);
}

namespace {

// Each name as an identifier, numbered (_2, _3, …) where two fold to one ("a-b", "a b").
std::vector<std::string> unique_keys(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  std::set<std::string> taken;
  for (const auto& n : names) {
    const std::string base = identifier(n);
    std::string key = base;
    for (int k = 2; !taken.insert(key).second; ++k) key = base + "_" + std::to_string(k);
    out.push_back(key);
  }
  return out;
}

// The visible objects that show no shading: seen from behind, or reached by no light.
std::string dark_objects(const Render& ref, const Scene& s) {
  std::vector<size_t> pixels(s.objects.size()), back(s.objects.size()), lit(s.objects.size());
  for (size_t i = 0; i < ref.object.size(); ++i) {
    const int o = ref.object[i];
    if (o < 0 || size_t(o) >= s.objects.size()) continue;
    ++pixels[size_t(o)];
    back[size_t(o)] += !(ref.seen[i] & Render::kFacesCamera);
    lit[size_t(o)] += (ref.seen[i] & Render::kReceivesLight) != 0;
  }
  std::string out;
  for (size_t o = 0; o < s.objects.size(); ++o) {
    if (pixels[o] < kInformativePixels) continue;
    std::string why;
    if (2 * back[o] > pixels[o])
      why = fmt::format("faces away from the camera at {:.0f} % of its {} pixels (its normals point into it?)",
                        100.0 * double(back[o]) / double(pixels[o]), pixels[o]);
    else if (lit[o] == 0)
      why = fmt::format("no light reaches any of its {} pixels (every light below its horizon, outside its cone or "
                        "in shadow)",
                        pixels[o]);
    if (!why.empty()) out += fmt::format("{}\"{}\" {}", out.empty() ? "" : "; ", s.objects[o].name, why);
  }
  return out;
}

}  // namespace

std::string uninformative(const Render& ref, const Scene& s) {
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  size_t visible = 0;
  for (size_t i = 0; i < ref.object.size(); ++i) {
    if (ref.object[i] < 0) continue;
    ++visible;
    for (size_t c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], ref.image.rgb[i * 3 + c]);
      hi[c] = std::max(hi[c], ref.image.rgb[i * 3 + c]);
    }
  }
  if (visible == 0) return "no object is visible";
  const float peak = std::max({hi[0], hi[1], hi[2]});
  bool constant = true;
  for (size_t c = 0; c < 3; ++c) constant = constant && hi[c] - lo[c] <= 1e-6f * std::max(1.0f, peak);
  std::string image;
  if (!(peak > 0)) image = fmt::format("the reference is black at all {} pixels where objects are visible", visible);
  else if (constant)
    image = fmt::format("the reference is one colour ({:.4g}, {:.4g}, {:.4g}) at all {} pixels where objects are "
                        "visible",
                        hi[0], hi[1], hi[2], visible);
  const std::string dark = dark_objects(ref, s);
  if (dark.empty()) return image;
  return (image.empty() ? "" : image + "; ") + "objects show no shading: " + dark;
}

ComparisonRow judge(const Render& reference, const Image& image, const std::vector<float>& alpha, bool hard_toon,
                    const ValidateOptions& o) {
  ComparisonRow row;
  row.metrics = compare_images(reference, image, interior_mask(reference), o.tolerance);
  size_t differ = 0;
  for (size_t i = 0; i < reference.object.size(); ++i) {
    bool hit = reference.object[i] >= 0;
    bool covered = alpha.empty() ? hit : alpha[i] >= 0.5f;
    differ += hit != covered;
  }
  row.coverage_mismatch = reference.object.empty() ? 0 : double(differ) / double(reference.object.size());
  row.allowed_flips = hard_toon ? size_t(std::floor(o.flip_tolerance * double(row.metrics.pixels))) : 0;
  row.pass = row.metrics.nan == 0 && row.metrics.pixels > 0 && row.metrics.over <= row.allowed_flips &&
             row.coverage_mismatch <= o.coverage_tolerance;
  return row;
}

ComparisonRow judge(const Render& reference, const RenderOutcome& outcome, bool hard_toon, const ValidateOptions& o) {
  if (outcome.ok) return judge(reference, outcome.image, outcome.alpha, hard_toon, o);
  ComparisonRow row;
  row.error = outcome.error.empty() ? "the renderer failed without a message" : outcome.error;
  return row;
}

namespace {

// What is validated, read before anything renders: a bad material or scene stops the run.
struct Inputs {
  std::vector<Scene> scenes;
  std::vector<Material> materials;
  std::vector<std::string> keys;  // per material: names its images (unique_keys())
  std::vector<std::string> scene_keys;  // per scene
  bool need_materials = false;    // a scene without materials of its own
};

Inputs load_inputs(ValidateOptions& o) {
  for (const auto& r : o.renderers)
    if (!find_renderer(r))
      throw InputError({{"validate", "renderers", fmt::format("unknown renderer \"{}\"; allowed: {}", r,
                                                              fmt::join(renderer_names(), ", ")), 0, 0}});
  Inputs in;
  for (const auto& s : o.scenes) in.scenes.push_back(load_scene(s));
  // Scenes with their own materials render once; the others with every material
  // (by default the example catalog).
  in.need_materials =
      std::any_of(in.scenes.begin(), in.scenes.end(), [](const Scene& s) { return !s.has_own_materials(); });
  if (o.materials.empty() && o.given.empty() && in.need_materials) o.materials = example_materials();
  for (const auto& f : o.materials) {
    in.materials.push_back(load_material(f));
    in.keys.push_back(fs::path(f).stem().string());
  }
  for (const auto& m : o.given) {
    in.materials.push_back(m);
    in.keys.push_back(identifier(m.name));
  }
  in.keys = unique_keys(in.keys);  // p/x.json and q/x.json, "a-b" and "a b": images of their own
  for (const auto& s : in.scenes) in.scene_keys.push_back(s.name);
  in.scene_keys = unique_keys(in.scene_keys);
  for (const auto& s : in.scenes) {
    if (s.has_own_materials()) check_texture_sets(s, nullptr);
    else
      for (const auto& m : in.materials) check_texture_sets(s, &m);
  }
  return in;
}

// Counters update in place on a terminal; a log gets a line per step.
struct Progress {
  std::ostream& out;
  bool interactive;
  void tick(const std::string& what, size_t i, size_t n) const {
    if (interactive) out << fmt::format("\r  {} {}/{}", what, i, n) << std::flush;
    else out << fmt::format("  {} {}/{}\n", what, i, n);
  }
  void step(const std::string& what) const {
    out << fmt::format("{}  {}{}", interactive ? "\r" : "", what, interactive ? "" : "\n") << std::flush;
  }
};

// Every material on every scene (a scene with its own materials once), each with its reference image.
std::vector<Case> reference_cases(const Inputs& in, const ValidateOptions& o, const fs::path& out, const Progress& p) {
  std::vector<Case> cases;
  size_t total = 0;
  for (const auto& s : in.scenes) total += s.has_own_materials() ? 1 : in.materials.size();
  p.out << fmt::format("facet validate: {} images ({} scenes) at {}×{} through {}\n", total, in.scenes.size(), o.width,
                       o.height, fmt::join(o.renderers, ", "));
  auto add = [&](Case c) {
    c.reference = c.material ? render_reference(*c.material, c.scene, o.width, o.height)
                             : render_reference(c.scene, o.width, o.height);
    c.uninformative = uninformative(c.reference, c.scene);
    write_images(out, c, reference_renderer().name, c.reference.image, o.exposure.value_or(c.scene.exposure));
    cases.push_back(std::move(c));
    p.tick("reference " + cases.back().key + " on " + cases.back().scene.name, cases.size(), total);
  };
  for (size_t k = 0; k < in.scenes.size(); ++k) {
    const Scene& s = in.scenes[k];
    if (s.has_own_materials()) {
      add(Case{std::nullopt, in.scene_keys[k], s, in.scene_keys[k], {}, {}});
      continue;
    }
    for (size_t i = 0; i < in.materials.size(); ++i) add(Case{in.materials[i], in.keys[i], s, in.scene_keys[k], {}, {}});
  }
  return cases;
}

RenderJob job_for(const Case& c, const std::string& renderer, const ValidateOptions& o, const fs::path& out) {
  RenderJob j;
  j.material = c.material;
  j.scene = c.scene;
  j.width = o.width;
  j.height = o.height;
  j.workdir = (out / "work" / renderer / c.scene_key).string();
  j.name = c.material ? c.key + "_" + c.scene_key : c.scene_key;  // unique in the folder
  j.max_value = 0;
  for (float v : c.reference.image.rgb) j.max_value = std::max<double>(j.max_value, v);
  j.tolerance = o.tolerance;  // POV-Ray brackets its exposures where one cannot hold the range to it
  return j;
}

// The renderer's rows (from `start` on): how many pass, and why each failure failed.
void report_phase(const std::string& renderer, const ValidateResult& result, size_t start, const Progress& p) {
  size_t n = 0, ok = 0;
  for (size_t i = start; i < result.rows.size(); ++i, ++n) ok += result.rows[i].pass;
  p.out << fmt::format("\r  {}: {} of {} pass in {:.1f} s\n", renderer, ok, n, result.wall.at(renderer));
  for (size_t i = start; i < result.rows.size(); ++i) {
    const auto& r = result.rows[i];
    if (!r.pass && r.error.empty() && !r.uninformative.empty() && r.metrics.over == 0)
      p.out << fmt::format("    UNINFORMATIVE {} on {}: {}\n", r.material, r.scene, r.uninformative);
    else if (!r.pass && r.error.empty() && r.metrics.pixels == 0)
      p.out << fmt::format("    FAIL {} on {}: no pixel to compare: the reference sees no object's interior (no "
                           "object in view, or none wider than 3 pixels)\n",
                           r.material, r.scene);
    else if (!r.pass)
      p.out << fmt::format("    FAIL {} on {}: {}\n", r.material, r.scene,
                           r.error.empty() ? fmt::format("max |Δ|/max(1,|ref|) {:.3g}, {} pixels over, coverage "
                                                         "{:.3f} %, NaN/Inf {}{}",
                                                         r.metrics.max_excess, r.metrics.over,
                                                         100 * r.coverage_mismatch, r.metrics.nan,
                                                         r.uninformative.empty() ? "" : "; uninformative: " + r.uninformative)
                                           : r.error.substr(0, r.error.find('\n')));
  }
}

// Every case through one renderer, each judged against its reference.
void run_renderer(const RendererEntry& entry, const std::vector<Case>& cases, const ValidateOptions& o,
                  const fs::path& out, const Progress& p, ValidateResult& result) {
  const std::string& name = entry.info.name;
  const size_t start = result.rows.size();
  auto t = Clock::now();
  std::unique_ptr<Renderer> renderer = entry.make(entry.info, RendererSettings{o.python});
  std::vector<RenderJob> jobs;
  for (const auto& c : cases) jobs.push_back(job_for(c, name, o, out));
  size_t done = 0;
  RenderProgress progress;
  progress.finished = [&](size_t i) { p.tick(name + " " + cases[i].key + " on " + cases[i].scene.name, ++done, cases.size()); };
  progress.step = [&](const std::string& what) { p.step(name + ": " + what); };
  std::vector<RenderOutcome> outcomes = renderer->render(jobs, progress);
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const RenderOutcome& r = outcomes.at(i);
    ComparisonRow row = judge(c.reference, r, c.hard_toon(), o);
    row.uninformative = c.uninformative;
    row.pass = row.pass && row.uninformative.empty();
    row.note = r.note;
    if (r.ok) write_images(out, c, name, r.image, o.exposure.value_or(c.scene.exposure));
    row.material = c.label();
    row.key = c.key;
    row.renderer = name;
    row.scene = c.scene.name;
    row.seconds = r.seconds;
    result.rows.push_back(row);
  }
  result.wall[name] = since(t);
  report_phase(name, result, start, p);
}

// The one-line verdict: comparisons passed, worst errors and wall times.
std::string summary(const ValidateOptions& o, const Inputs& in, const ValidateResult& result, size_t ok) {
  std::string worst;
  const std::vector<std::string> targets = under_test(o.renderers);
  for (const auto& renderer : targets) {
    double w = -1;
    for (const auto& r : result.rows)
      if (r.renderer == renderer && r.error.empty()) w = std::max(w, r.metrics.max_excess);
    worst += fmt::format("{}{} {}", worst.empty() ? "" : ", ", renderer, w < 0 ? "–" : fmt::format("{:.2g}", w));
  }
  std::string times;
  for (const auto& [r, s] : result.wall) times += fmt::format("{}{} {:.1f} s", times.empty() ? "" : ", ", r, s);
  std::string what = in.need_materials
                         ? fmt::format("{} materials × {} scenes", in.materials.size(), in.scenes.size())
                         : fmt::format("{} scenes with their own materials", in.scenes.size());
  size_t dull = 0;
  for (const auto& r : result.rows) dull += !r.uninformative.empty();
  return fmt::format(
      "{} of {} comparisons pass{} ({} × {} renderers at {}×{}); worst |Δ|/max(1,|ref|): {} (tolerance {:g}); wall "
      "time: {}",
      ok, result.rows.size(), dull ? fmt::format(", {} uninformative", dull) : "", what, targets.size(), o.width,
      o.height, worst, o.tolerance, times);
}

}  // namespace

ValidateResult validate(const ValidateOptions& options, std::ostream& progress) {
  ValidateOptions o = options;
  if (o.scenes.empty()) o.scenes = builtin_scene_names();
  if (o.python.empty()) o.python = default_python();
  Inputs in = load_inputs(o);
  fs::path out = o.out;
  const FolderLock lock(out.string(), "--out");  // two runs on one folder would mix their files
  fs::remove_all(out / "work");  // what an interrupted run left
  // An earlier run's report goes first: a run that fails (a full disk) leaves no report that
  // describes other images than the ones in the folder.
  fs::remove(out / "report.html");
  fs::remove(out / "metrics.json");
  fs::create_directories(out / "images");
  fs::create_directories(out / "work");
  // The renderers' files, removed however this ends: done, or failed on a write.
  struct RemoveWork {
    fs::path work;
    ~RemoveWork() {
      std::error_code ignored;
      fs::remove_all(work, ignored);
    }
  } remove_work{out / "work"};
  const Progress p{progress, o.interactive};
  ValidateResult result;

  auto t0 = Clock::now();
  std::vector<Case> cases = reference_cases(in, o, out, p);
  const std::string& reference = reference_renderer().name;
  result.wall[reference] = since(t0);
  progress << fmt::format("\r  {}: {} images in {:.1f} s\n", reference, cases.size(), result.wall[reference]);
  // The renderers under test, in the registry's order; the reference rendered every case above.
  for (const auto& entry : renderer_registry())
    if (!entry.info.reference && std::count(o.renderers.begin(), o.renderers.end(), entry.info.name))
      run_renderer(entry, cases, o, out, p, result);

  size_t ok = 0;
  for (const auto& r : result.rows) ok += r.pass;
  result.pass = ok == result.rows.size() && !result.rows.empty();
  result.summary = summary(o, in, result, ok);
  json metrics = json::array();
  for (const auto& r : result.rows) metrics.push_back(row_json(r, o.width, o.height));
  write_file_atomic((out / "metrics.json").string(), metrics.dump(2) + "\n");
  write_report(out, o, cases, result);  // the renderers' files go with remove_work: the report has what they said
  progress << fmt::format("report: {}\n", (out / "report.html").string());
  return result;
}

}  // namespace facet
