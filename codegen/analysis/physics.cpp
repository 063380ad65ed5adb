#include "analysis/physics.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>

#include <fmt/format.h>

#include "catalog/material.h"
#include "core/parallel.h"
#include "core/vec.h"
#include "reference/interpreter.h"

namespace facet {

namespace {

// The proposals: a mixture of cosine-distributed directions and half vectors
// from a GGX distribution, v = reflect(l, h). A pilot run picks the width and
// the cosine share with the least variance for each estimate; its samples are
// not reused, so the estimate stays unbiased. GGX's long tails keep the weights
// bounded for the lighter-tailed lobes (Beckmann, Ward, Gaussian, Phong), and a
// Beckmann proposal, tried as well, lost to rare huge weights its pilot missed.
struct Proposal {
  double width = 0;
  double cosine = 1;  // the share of cosine-distributed samples
};

std::vector<Proposal> proposals() {
  std::vector<Proposal> out = {{0, 1}};
  for (double w : {0.01, 0.02, 0.04, 0.08, 0.16, 0.32, 0.64, 1.0})
    for (double c : {0.5, 0.1}) out.push_back({w, c});
  return out;
}
const size_t kPilotSamples = 2048;

// One parameter set of a lobe, as a label and the material it makes.
struct Variant {
  std::string label;
  Material material;
};

// The values a numeric parameter takes: even steps over a finite range (a hair
// inside an open end), else — or where the range is float32's, not the model's
// (docs/float32.md) — its default d times 1/4 … 4.
std::vector<double> sweep_values(const ParamDef& p, bool coarse) {
  const Range& r = p.range;
  std::vector<double> out;
  if (std::isfinite(r.min) && std::isfinite(r.max) && !r.float32) {
    std::vector<double> ts = coarse ? std::vector<double>{0, 0.5, 1} : std::vector<double>{0, 0.25, 0.5, 0.75, 1};
    for (double t : ts) {
      if (t == 0 && r.min_open) t = 0.05;
      if (t == 1 && r.max_open) t = 0.95;
      out.push_back(r.min + t * (r.max - r.min));
    }
    return out;
  }
  double d = p.fallback.number;
  std::vector<double> fs = coarse ? std::vector<double>{0.25, 1, 4} : std::vector<double>{0.25, 0.5, 1, 2, 4};
  for (double f : fs)
    if (r.contains(d * f)) out.push_back(d * f);
  return out;
}

constexpr size_t kCrossed = 4;

std::vector<Variant> variants(const ModelDef& def) {
  ModelSpec base = default_spec(def);
  if (def.param("fresnel")) {  // the white furnace: F = 1
    Value v;
    v.kind = ParamKind::Model;
    v.choice = "none";
    v.model = std::make_shared<ModelSpec>(default_spec(*find_model("fresnel", "none")));
    base.values["fresnel"] = v;
  }
  std::vector<const ParamDef*> numbers, flags;
  for (const auto& p : def.params) {
    if (p.kind == ParamKind::Number) numbers.push_back(&p);
    if (p.kind == ParamKind::Bool) flags.push_back(&p);
  }
  std::vector<std::pair<std::string, ModelSpec>> specs = {{"", base}};
  auto expand = [&](const ParamDef& p, const std::vector<std::pair<std::string, Value>>& values) {
    std::vector<std::pair<std::string, ModelSpec>> next;
    for (const auto& [label, spec] : specs) {
      for (const auto& [text, value] : values) {
        ModelSpec s = spec;
        s.values[p.name] = value;
        next.push_back({label + (label.empty() ? "" : ", ") + p.name + " " + text, s});
      }
    }
    specs = std::move(next);
  };
  // Up to kCrossed numbers: every combination of their sweeps. More (glTF's material with its
  // extensions): each number swept alone, the others at their defaults, so the work grows with
  // the parameters, not as the power of their count (3^6 = 729 variants for six).
  const bool crossed = numbers.size() <= kCrossed;
  std::vector<std::pair<std::string, ModelSpec>> alone;
  for (const ParamDef* p : numbers) {
    std::vector<std::pair<std::string, Value>> values;
    for (double x : sweep_values(*p, numbers.size() > 1)) {
      Value v;
      v.kind = ParamKind::Number;
      v.number = x;
      values.push_back({fmt::format("{:g}", x), v});
    }
    if (crossed) {
      expand(*p, values);
      continue;
    }
    for (const auto& [text, value] : values) {
      ModelSpec s = base;
      s.values[p->name] = value;
      alone.push_back({p->name + " " + text, s});
    }
  }
  if (!crossed) specs = std::move(alone);
  for (const ParamDef* p : flags) {
    Value off, on;
    off.kind = on.kind = ParamKind::Bool;
    on.flag = true;
    expand(*p, {{"off", off}, {"on", on}});
  }
  std::vector<Variant> out;
  for (auto& [label, spec] : specs) {
    if (def.section != "layer") {
      out.push_back({label, lobe_material(spec, def.name)});
      continue;
    }
    // A layer over a white Lambert (ρ_d = n·l, albedo 1): what the layer keeps of it and adds.
    Material m = lobe_material(default_spec(cost_baseline_model()), def.name);
    m.layers.push_back(spec);
    out.push_back({label, m});
  }
  return out;
}

// Reproducible streams: one per estimate, whatever the thread that runs it.
struct Rng {
  std::mt19937_64 engine;
  Rng(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
    std::seed_seq seq{seed, seed >> 32, a, b};
    engine.seed(seq);
  }
  double uniform() { return double(engine() >> 11) * 0x1.0p-53; }  // [0, 1)
};

Vec3 hemisphere_uniform(Rng& r) {
  double z = r.uniform(), phi = 2 * kPi * r.uniform(), s = std::sqrt(std::max(0.0, 1 - z * z));
  return Vec3(s * std::cos(phi), s * std::sin(phi), z);
}

const Vec3 kN(0, 0, 1), kT(1, 0, 0);

double brdf(const Reference& ref, const Vec3& l, const Vec3& v) {
  return ref.reflectance(kN, l, v, kT)[0] / (kPi * l.z);
}

// The density over half vectors h (per solid angle of h), D(h)(n·h).
double half_vector_pdf(const Proposal& p, double c) {
  double a2 = p.width * p.width, c2 = c * c;
  double d = c2 * (a2 - 1) + 1;
  return a2 / (kPi * d * d) * c;
}

// The mixture's density of v (solid angle) for light l.
double mixture_pdf(const Proposal& p, const Vec3& l, const Vec3& v) {
  double cosine = std::max(v.z, 0.0) / kPi, lobe = 0;
  if (p.cosine < 1) {
    Vec3 h = l + v;
    double len = length(h);
    if (len > 1e-12) {
      h = h / len;
      if (h.z < 0) h = -h;  // the sampled half vector was −h, on the far side of l
      double lh = std::fabs(dot(l, h));
      if (lh > 0 && h.z > 0) lobe = half_vector_pdf(p, h.z) / (4 * lh);
    }
  }
  return p.cosine * cosine + (1 - p.cosine) * lobe;
}

struct Moments {
  double sum = 0, sum2 = 0;
  size_t n = 0;
  double mean() const { return sum / double(n); }
  double variance() const { return std::max(0.0, sum2 / double(n) - mean() * mean()); }
};

Moments sample_albedo(const Reference& ref, const Vec3& l, const Proposal& q, size_t samples, Rng& rng) {
  Moments m;
  m.n = samples;
  for (size_t i = 0; i < samples; ++i) {
    double pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    Vec3 v;
    if (pick < q.cosine) {
      double r = std::sqrt(u1), phi = 2 * kPi * u2;
      v = Vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1)));
    } else {
      double a2 = q.width * q.width;
      double tan2 = a2 * u1 / (1 - u1);
      double c = 1 / std::sqrt(1 + tan2), s = std::sqrt(std::max(0.0, 1 - c * c));
      Vec3 h(s * std::cos(2 * kPi * u2), s * std::sin(2 * kPi * u2), c);
      v = h * (2 * dot(l, h)) - l;
    }
    double x = 0;
    if (v.z > 0) {
      v = normalize(v);
      double p = mixture_pdf(q, l, v);
      if (p > 0) x = brdf(ref, l, v) * v.z / p;
    }
    m.sum += x;
    m.sum2 += x * x;
  }
  return m;
}

AlbedoEstimate estimate_albedo(const Reference& ref, double theta, double phi, size_t samples, Rng& rng) {
  double th = theta * kPi / 180, ph = phi * kPi / 180;
  Vec3 l(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
  static const std::vector<Proposal> candidates = proposals();
  Proposal best;
  double best_variance = HUGE_VAL;
  for (const Proposal& q : candidates) {
    double var = sample_albedo(ref, l, q, kPilotSamples, rng).variance();
    if (var < best_variance) best = q, best_variance = var;
  }
  Moments m = sample_albedo(ref, l, best, samples, rng);
  AlbedoEstimate e;
  e.theta = theta;
  e.phi = phi;
  e.albedo = m.mean();
  e.error = std::sqrt(m.variance() / double(samples - 1));
  return e;
}

double asymmetry(const Reference& ref, size_t pairs, Rng& rng) {
  double worst = 0;
  for (size_t i = 0; i < pairs; ++i) {
    Vec3 l = hemisphere_uniform(rng), v = hemisphere_uniform(rng);
    if (l.z < 1e-3 || v.z < 1e-3) continue;
    double a = brdf(ref, l, v), b = brdf(ref, v, l), m = std::max(std::fabs(a), std::fabs(b));
    if (m < 1e-200) continue;  // both underflow: nothing to compare
    worst = std::max(worst, std::fabs(a - b) / m);
  }
  return worst;
}

// Whether ρ depends on the tangent: turn t about n and look.
bool is_isotropic(const Reference& ref, Rng& rng) {
  Vec3 t2(std::cos(0.6), std::sin(0.6), 0);
  for (int i = 0; i < 256; ++i) {
    Vec3 l = hemisphere_uniform(rng), v = hemisphere_uniform(rng);
    double a = ref.reflectance(kN, l, v, kT)[0], b = ref.reflectance(kN, l, v, t2)[0];
    if (std::fabs(a - b) > 1e-12 * std::max({1.0, std::fabs(a), std::fabs(b)})) return false;
  }
  return true;
}

std::string significant(double x, int digits) {
  if (!std::isfinite(x)) return fmt::format("{}", x);
  if (x != 0 && (std::fabs(x) >= 1e5 || std::fabs(x) < 1e-3)) return fmt::format("{:.{}e}", x, digits - 1);
  int magnitude = x == 0 ? 0 : int(std::floor(std::log10(std::fabs(x))));
  return fmt::format("{:.{}f}", x, std::max(0, digits - 1 - magnitude));
}

std::string estimate_text(const AlbedoEstimate& e) {
  return significant(e.albedo, 4) + " ± " + significant(e.error, 1);
}

}  // namespace

const AlbedoEstimate& PhysicsRow::max_albedo() const {
  return *std::max_element(albedo.begin(), albedo.end(),
                           [](const AlbedoEstimate& a, const AlbedoEstimate& b) { return a.albedo < b.albedo; });
}

bool PhysicsRow::measured_conserving() const {
  return std::all_of(albedo.begin(), albedo.end(),
                     [](const AlbedoEstimate& e) { return e.albedo <= 1 + kSigmas * e.error + 1e-12; });
}

namespace {

struct Task {
  size_t row = 0;
  const Variant* variant = nullptr;
  double theta = 0, phi = 0;
  bool reciprocity = false;  // this task measures reciprocity instead
  std::uint64_t id = 0;
};

}  // namespace

std::vector<PhysicsRow> measure_physics(const PhysicsOptions& o) {
  std::vector<const ModelDef*> models;
  for (const auto& def : catalog())
    if (def.section == "diffuse" || def.section == "specular" || def.section == "layer") models.push_back(&def);
  std::vector<PhysicsRow> rows(models.size());
  std::vector<std::vector<Variant>> vs(models.size());
  std::vector<Task> tasks;
  for (size_t r = 0; r < models.size(); ++r) {
    rows[r].model = models[r];
    vs[r] = variants(*models[r]);
    Rng rng(o.seed, r, 0xa150);
    Reference ref(vs[r].front().material);
    rows[r].isotropic = is_isotropic(ref, rng);
    for (const auto& v : vs[r]) {
      tasks.push_back({r, &v, 0, 0, true, tasks.size()});
      for (double theta : o.angles)
        for (double phi : rows[r].isotropic || theta == 0 ? std::vector<double>{0} : std::vector<double>{0, 90})
          tasks.push_back({r, &v, theta, phi, false, tasks.size()});
    }
  }
  // One reference per parameter set, shared by its estimates (reflectance() is const and thread-safe).
  std::vector<const Variant*> variant_list;
  for (const auto& v : vs)
    for (const auto& x : v) variant_list.push_back(&x);
  std::vector<std::unique_ptr<Reference>> refs(variant_list.size());
  const unsigned threads = unsigned(std::max(1, o.threads));
  parallel_for(refs.size(), threads, [&](size_t i) { refs[i] = std::make_unique<Reference>(variant_list[i]->material); });
  std::map<const Variant*, const Reference*> ref_of;
  for (size_t i = 0; i < refs.size(); ++i) ref_of[variant_list[i]] = refs[i].get();
  std::vector<AlbedoEstimate> estimates(tasks.size());
  std::vector<double> asym(tasks.size(), 0);
  parallel_for(tasks.size(), threads, [&](size_t i) {
    const Task& t = tasks[i];
    const Reference& ref = *ref_of.at(t.variant);
    Rng rng(o.seed, t.id, 0xf00d);
    if (t.reciprocity) {
      asym[i] = asymmetry(ref, o.reciprocity_pairs, rng);
    } else {
      estimates[i] = estimate_albedo(ref, t.theta, t.phi, o.albedo_samples, rng);
      estimates[i].params = t.variant->label;
    }
  });
  for (size_t i = 0; i < tasks.size(); ++i) {
    PhysicsRow& row = rows[tasks[i].row];
    if (tasks[i].reciprocity) row.asymmetry = std::max(row.asymmetry, asym[i]);
    else row.albedo.push_back(estimates[i]);
  }
  for (auto& row : rows) row.measured_reciprocal = row.asymmetry <= kReciprocityTolerance;
  return rows;
}

PhysicsRow measure_physics(const ModelDef& model, const PhysicsOptions& o) {
  // The same measurement as for the catalog, for one model (tests use it on
  // models of their own).
  std::vector<Variant> vs = variants(model);
  PhysicsRow row;
  row.model = &model;
  Rng rng(o.seed, 0, 0xa150);
  row.isotropic = is_isotropic(Reference(vs.front().material), rng);
  std::uint64_t id = 0;
  for (const auto& v : vs) {
    Reference ref(v.material);
    Rng r(o.seed, id++, 0xf00d);
    row.asymmetry = std::max(row.asymmetry, asymmetry(ref, o.reciprocity_pairs, r));
    for (double theta : o.angles)
      for (double phi : row.isotropic || theta == 0 ? std::vector<double>{0} : std::vector<double>{0, 90}) {
        Rng re(o.seed, id++, 0xf00d);
        row.albedo.push_back(estimate_albedo(ref, theta, phi, o.albedo_samples, re));
        row.albedo.back().params = v.label;
      }
  }
  row.measured_reciprocal = row.asymmetry <= kReciprocityTolerance;
  return row;
}

std::string physics_markdown(const std::vector<PhysicsRow>& rows, const PhysicsOptions& o) {
  std::string angles;
  for (double a : o.angles) angles += fmt::format("{}{:g}°", angles.empty() ? "" : ", ", a);
  std::string s;
  s += "# Reciprocity and albedo of the catalog's lobes\n\n";
  s += fmt::format(
      "Generated by `facet physics -o docs/physics.md` (seed {}, {} samples per albedo estimate, {} pairs per "
      "reciprocity check); the test `physics.table` regenerates it and fails if this file differs, if a lobe's "
      "measured reciprocity is not what the catalog says, or if a lobe the catalog calls energy-conserving "
      "exceeds albedo 1 by more than {:g} standard errors. Do not edit it by hand.\n\n",
      o.seed, o.albedo_samples, o.reciprocity_pairs, kSigmas);
  s += "**How.** Every lobe is measured white (k = 1) and, where it has a Fresnel term, with F = 1 (the white "
       "furnace); every layer over a white Lambert lobe (albedo 1). Its BRDF is f(l, v) = ρ(l, v) / (π n·l), "
       "MODELS.md's convention.\n\n";
  s += fmt::format(
      "- *Reciprocity*: f(l, v) and f(v, l) at random pairs above the horizon (n·l, n·v ≥ 1e-3), for every "
      "parameter set; the table gives the worst relative difference |f(l,v) − f(v,l)| / max. A lobe counts as "
      "reciprocal when that stays below {:g} (the rounding of double precision).\n",
      kReciprocityTolerance);
  s += fmt::format(
      "- *Directional albedo* a(l) = ∫ f(l, v) (n·v) dω_v, by Monte Carlo with a one-sample mixture of "
      "cosine-distributed directions and mirror directions of half vectors drawn from a GGX distribution; for "
      "each estimate a pilot run (2048 samples per candidate, not reused) picks the width (0.01 … 1) and the "
      "cosine share (1, 0.5 or 0.1) with the least variance, so sharp and broad lobes alike are sampled well, at incidence θ = {}; anisotropic lobes (those whose ρ changes when the tangent turns, "
      "measured) with the light along the tangent (φ = 0°) and along the bitangent (φ = 90°). Estimates are given "
      "± one standard error.\n",
      angles);
  s += fmt::format(
      "- *Parameters*: each numeric parameter at d/4, d/2, d, 2d and 4d of its default d (d/4, d and 4d when the "
      "lobe has two), or at even steps over a finite range, every combination of them for a lobe of up to {} numbers "
      "and each alone (the others at their defaults) beyond; flags both ways; the geometry term and approximations "
      "at their defaults, as the catalog's claims are made for those.\n\n",
      kCrossed);
  s += "## Summary\n\n";
  s += "| lobe | reciprocal (catalog) | worst asymmetry (measured) | energy-conserving (catalog) | maximum albedo "
       "(measured) | where | why |\n";
  s += "|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const AlbedoEstimate& m = r.max_albedo();
    std::string where = fmt::format("θ = {:g}°", m.theta);
    if (!r.isotropic && m.theta != 0) where += fmt::format(", φ = {:g}°", m.phi);
    if (!m.params.empty()) where += ", " + m.params;
    s += fmt::format("| `{}` {} | {} | {} | {} | {} | {} | {} |\n", r.model->name, r.model->section,
                     r.model->reciprocal ? "yes" : "no", significant(r.asymmetry, 2),
                     r.model->energy_conserving ? "yes" : "no", estimate_text(m), where, r.model->physics_note);
  }
  s += "\n## Albedo by lobe\n\n";
  for (const auto& r : rows) {
    s += fmt::format("### `{}` ({})\n\n", r.model->name, r.model->title);
    s += "| parameters |" + std::string(r.isotropic ? "" : " light |");
    for (double a : o.angles) s += fmt::format(" θ = {:g}° |", a);
    s += "\n|---|" + std::string(r.isotropic ? "" : "---|");
    for (size_t i = 0; i < o.angles.size(); ++i) s += "---|";
    s += "\n";
    std::vector<std::string> labels;
    for (const auto& e : r.albedo)
      if (std::find(labels.begin(), labels.end(), e.params) == labels.end()) labels.push_back(e.params);
    for (const auto& label : labels) {
      for (double phi : r.isotropic ? std::vector<double>{0} : std::vector<double>{0, 90}) {
        s += "| " + (label.empty() ? std::string("—") : label) + " |";
        if (!r.isotropic) s += phi == 0 ? " along t |" : " along b |";
        for (double a : o.angles) {
          for (const auto& e : r.albedo)
            if (e.params == label && e.theta == a && (e.phi == phi || a == 0)) {
              s += " " + estimate_text(e) + " |";
              break;
            }
        }
        s += "\n";
      }
    }
    s += "\n";
  }
  return s;
}

}  // namespace facet
