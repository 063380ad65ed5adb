#include "analysis/sweep.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <random>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/io.h"
#include "core/vec.h"
#include "reference/interpreter.h"
#include "renderers/harness.h"
#include "renderers/process.h"
#include "targets/sweep_grid.h"
#include "targets/targets.h"

namespace facet {

namespace fs = std::filesystem;
using ir::Expr;
using nlohmann::json;

namespace {

Value number_value(double v) {
  Value x;
  x.kind = ParamKind::Number;
  x.number = v;
  return x;
}

// The ends of a parameter's range: the bound itself, a hair inside an open one,
// 1e4 for an unbounded one.
double low_end(const Range& r) { return r.min_open ? r.min + std::max(1e-6, std::fabs(r.min) * 1e-6) : r.min; }
double high_end(const Range& r) {
  if (!std::isfinite(r.max)) return 1e4;
  return r.max_open ? r.max - std::max(1e-6, std::fabs(r.max) * 1e-6) : r.max;
}

ModelSpec fresnel(const char* name, std::map<std::string, Value> values) {
  ModelSpec f = default_spec(*find_model("fresnel", name));
  for (auto& [k, v] : values) f.values[k] = v;
  return f;
}

}  // namespace


std::vector<Material> extreme_materials() {
  std::vector<Material> out;
  auto add = [&](const ModelDef& def, const std::string& suffix, const ModelSpec& spec) {
    out.push_back(facet::lobe_material(spec, def.name + "_" + suffix));
    out.back().source = "extremes";
  };
  for (const auto& def : catalog()) {
    if (def.section != "diffuse" && def.section != "specular") continue;
    ModelSpec low = default_spec(def), high = default_spec(def);
    for (const auto& p : def.params) {
      if (p.kind != ParamKind::Number) continue;
      low.values[p.name] = number_value(low_end(p.range));
      high.values[p.name] = number_value(high_end(p.range));
    }
    add(def, "low", low);
    add(def, "high", high);
    if (!def.param("fresnel")) continue;
    // The Fresnel terms at their ends: f0 = 0 and 1; η below 1 (total internal
    // reflection), exactly 1 (no reflection) and large.
    auto color = [](double v) {
      Value x;
      x.kind = ParamKind::Color;
      x.rgb = {v, v, v};
      return x;
    };
    std::vector<std::pair<std::string, ModelSpec>> fresnels = {
        {"schlick0", fresnel("schlick", {{"f0", color(0)}})},
        {"schlick1", fresnel("schlick", {{"f0", color(1)}})},
        {"ior_tiny", fresnel("exact", {{"ior", number_value(1e-3)}})},
        {"ior_one", fresnel("exact", {{"ior", number_value(1)}})},
        {"ior_huge", fresnel("exact", {{"ior", number_value(1e3)}})}};
    for (auto& [name, f] : fresnels) {
      ModelSpec s = low;
      Value v;
      v.kind = ParamKind::Model;
      v.choice = f.def->name;
      v.model = std::make_shared<ModelSpec>(f);
      s.values["fresnel"] = v;
      add(def, name, s);
    }
  }
  // Toon at its ends on a lobe that reaches both 0 and 1.
  const ModelDef& lambert = *find_model("diffuse", "lambert");
  for (auto [name, cutoff, width] : {std::tuple{"toon_zero", 0.0, 0.0}, std::tuple{"toon_thin", 0.5, 1e-9},
                                     std::tuple{"toon_wide", 1e4, 1e4}}) {
    ModelSpec s = default_spec(lambert);
    ModelSpec t = default_spec(*find_model("modifier", "toon"));
    t.values["cutoff"] = number_value(cutoff);
    t.values["width"] = number_value(width);
    Value v;
    v.kind = ParamKind::Object;
    v.model = std::make_shared<ModelSpec>(t);
    s.values["toon"] = v;
    add(lambert, name, s);
  }
  return out;
}

// ---------------------------------------------------------------- the reference

namespace {

void count(SweepCount& c, const RGB& r) {
  ++c.samples;
  for (double x : r) {
    if (std::isnan(x)) ++c.nan;
    else if (std::isinf(x)) ++c.inf;
    else if (x < 0) ++c.negative;
  }
}

}  // namespace

// The grid's direction sets, evaluated once per size through the IR.
const std::vector<std::array<Vec3, 3>>& sweep_grid_sets(int grid) {
  static std::map<int, std::vector<std::array<Vec3, 3>>> cache;
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  auto& sets = cache[grid];
  if (!sets.empty()) return sets;
  Interpreter interp;
  std::vector<int> ids;
  for (const auto& f : sweep_grid()) ids.push_back(interp.prepare(f));
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      double s = (i + 0.5) / grid, t = (j + 0.5) / grid;
      RGB args[2] = {{s, s, s}, {t, t, t}};
      double c[9];
      for (int k = 0; k < 9; ++k) c[k] = interp.run(ids[size_t(k)], args)[0];
      sets.push_back({Vec3(c[0], c[1], c[2]), Vec3(c[3], c[4], c[5]), Vec3(c[6], c[7], c[8])});
    }
  }
  return sets;
}

SweepCount sweep_reference(const Material& m, int grid, size_t random) {
  Reference ref(m);
  SweepCount c = sweep_directions(grid, random, Vec3(m.tangent_axis), [&](const Vec3& n, const Vec3& l, const Vec3& v,
                                                                          const Vec3& t) {
    return ref.reflectance(n, l, v, t);
  });
  c.target = "reference";
  return c;
}

SweepCount sweep_directions(int grid, size_t random, const Vec3& axis, const SweepFunction& f) {
  SweepCount c;
  c.target = "directions";
  for (const auto& set : sweep_grid_sets(grid)) count(c, f(set[0], set[1], set[2], tangent_rule(set[0], axis)));
  // Random sets, half of them near the hard places: grazing angles down to 1e-12,
  // l and v close to each other, to the mirror direction and to −each other, and
  // normals along the tangent axis.
  std::mt19937_64 rng(0x5eed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  auto unit = [&] { return normalize(Vec3(g(rng), g(rng), g(rng))); };
  for (size_t i = 0; i < random; ++i) {
    Vec3 n = unit(), l = unit(), v = unit();
    switch (i % 8) {
      case 0: break;  // uniform
      case 1: l = normalize(l - n * dot(n, l) + n * std::pow(10.0, -12 * u(rng))); break;  // n·l → 0⁺
      case 2: v = normalize(v - n * dot(n, v) + n * std::pow(10.0, -12 * u(rng))); break;  // n·v → 0⁺
      case 3: v = normalize(l + unit() * std::pow(10.0, -10 * u(rng))); break;              // l ≈ v
      case 4: v = normalize(n * (2 * dot(n, l)) - l + unit() * std::pow(10.0, -10 * u(rng))); break;  // h ≈ n
      case 5: {  // l ≈ −v, both grazing
        Vec3 t = normalize(cross(n, l));
        double e = std::pow(10.0, -12 * u(rng));
        l = normalize(t + n * e);
        v = normalize(-t + n * e * u(rng));
        break;
      }
      case 6: n = normalize(axis + unit() * std::pow(10.0, -10 * u(rng))); break;  // n ∥ tangent axis
      case 7: l = n; v = normalize(n + unit() * 1e-9); break;                       // normal incidence
    }
    count(c, f(n, l, v, tangent_rule(n, axis)));
  }
  return c;
}

// ---------------------------------------------------------------- GLSL

SweepCount sweep_glsl(GlRenderer& gl, const Material& m, int grid, const std::string& source) {
  SweepCount c;
  c.target = "glsl";
  RenderOutcome r = gl.sweep(source.empty() ? glsl_sweep_source(m) : source, grid);
  if (!r.ok) {
    c.error = r.error;
    return c;
  }
  for (size_t i = 0; i < r.image.rgb.size(); i += 3) count(c, {r.image.rgb[i], r.image.rgb[i + 1], r.image.rgb[i + 2]});
  return c;
}

// ---------------------------------------------------------------- OSL

std::vector<SweepCount> sweep_osl(const std::vector<Material>& ms, int grid, const std::string& python,
                                  const std::string& workdir, const std::vector<std::string>& sources) {
  std::vector<SweepCount> out(ms.size());
  for (auto& c : out) c.target = "osl";
  fs::create_directories(workdir);
  fs::path dir = fs::absolute(workdir);
  fs::path script = dir / "cycles_sweep.py";
  write_file_atomic(script.string(), embedded_harness().at("cycles_sweep.py"));
  write_file_atomic((dir / "cycles_render.py").string(), embedded_harness().at("cycles_render.py"));
  json items = json::array();
  for (size_t i = 0; i < ms.size(); ++i) {
    // Numbered: two materials may share a name.
    std::string path = (dir / fmt::format("{:03}_{}_sweep.osl", i, identifier(ms[i].name))).string();
    write_file_atomic(path, i < sources.size() && !sources[i].empty() ? sources[i] : osl_sweep_source(ms[i]));
    items.push_back({{"name", ms[i].name}, {"osl", path}});
  }
  fs::path job = dir / "sweep_job.json";
  write_file_atomic(job.string(), json({{"size", grid}, {"items", items}}).dump(1));
  fs::remove(job.string() + ".result.json");
  ProcessResult r = run_process({python, script.string(), job.string()}, dir.string());
  json result;
  try {
    result = json::parse(read_file(job.string() + ".result.json"));
  } catch (const std::exception&) {
    for (auto& c : out) c.error = fmt::format("Blender exited with {} and wrote no result:\n{}", r.exit_code, r.output);
    return out;
  }
  for (size_t i = 0; i < ms.size() && i < result["items"].size(); ++i) {
    const json& ri = result["items"][i];
    if (!ri.value("ok", false)) {
      out[i].error = ri.value("error", std::string("failed"));
      continue;
    }
    out[i].samples = ri.value("samples", size_t(0));
    out[i].nan = ri.value("nan", size_t(0));
    out[i].inf = ri.value("inf", size_t(0));
    out[i].negative = ri.value("negative", size_t(0));
  }
  return out;
}

// ---------------------------------------------------------------- POV-Ray

SweepCount sweep_pov(const Material& m, int grid, const std::string& workdir, const std::string& source) {
  SweepCount c;
  c.target = "pov";
  fs::create_directories(workdir);
  std::string base = identifier(m.name) + "_sweep";
  write_file_atomic((fs::path(workdir) / (base + ".pov")).string(), source.empty() ? generate_pov_sweep(m) : source);
  ProcessResult r = run_process({"povray", "+I" + base + ".pov", "+O" + base + ".png", fmt::format("+W{}", grid),
                                 fmt::format("+H{}", grid), "-A", "+FN16", "File_Gamma=1.0", "-D"},
                                workdir);
  if (r.exit_code != 0) {
    c.error = fmt::format("povray exited with {}:\n{}", r.exit_code, r.output);
    return c;
  }
  Image img = read_png((fs::path(workdir) / (base + ".png")).string());
  // Each channel shows 1 where the value was finite and ≥ 0; the function cannot
  // tell NaN from Inf from negative, so a failure counts as NaN.
  for (size_t i = 0; i < img.rgb.size(); i += 3) {
    ++c.samples;
    for (int k = 0; k < 3; ++k)
      if (img.rgb[i + size_t(k)] < 0.5f) ++c.nan;
  }
  return c;
}

}  // namespace facet
