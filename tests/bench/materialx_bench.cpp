// MaterialX against facet, side by side (tests/bench/README.md): the C++ half of
// scripts/bench_materialx.sh. tests/bench/materialx_bench.py generates each case
// with MaterialX and times it; this times facet's generate() for the same BRDF,
// counts the SPIR-V of both fragment shaders through the same pipeline, draws both
// under callgrind in the same harness and compares both renders with facet's C++
// reference.
//
//   facet_materialx_bench JOB.json [--no-callgrind] [--size N] [--check]
//
// Exit 1 when facet's own render fails its reference, or with --check when
// facet's SPIR-V count exceeds MaterialX's for a case (deterministic counts; the
// test cost.materialx_bench). How far MaterialX's render is from facet's
// reference is reported, not judged: it is a different BRDF where they differ.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <regex>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analysis/cost.h"
#include "analysis/validate.h"
#include "core/io.h"
#include "core/vec.h"
#include "reference/raycaster.h"
#include "scene/scene.h"
#include "targets/targets.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace facet;

namespace {

// Seconds of one generate(), timed as materialx_bench.py times MaterialX's: after
// one untimed call, `repeats` calls in ten batches, the least batch mean.
double generate_seconds(const Material& m, Target t, int repeats) {
  const int batches = 10, per_batch = std::max(1, repeats / batches);
  GenerateOptions o;
  o.target = t;
  o.source = "materialx_bench";
  std::string code = generate(m, o);
  double best = 1e30;
  for (int b = 0; b < batches; ++b) {
    auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < per_batch; ++i) code = generate(m, o);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / per_batch);
  }
  return best;
}

// MaterialX's pixel shader under facet's cost frame: its vertex-data block becomes
// a global the frame's main fills, its main becomes mx_main.
std::string harness_source(const std::string& pixel, std::string& error) {
  static const std::regex block(R"(\bin\s+VertexData\s*\{([^}]*)\}\s*vd\s*;)");
  static const std::regex main_fn(R"(\bvoid\s+main\s*\(\s*\))");
  std::smatch m;
  if (!std::regex_search(pixel, m, block)) {
    error = "no `in VertexData { … } vd;` block in MaterialX's pixel shader";
    return "";
  }
  std::string s = std::regex_replace(pixel, block, "struct VertexData {$1};\nVertexData vd;",
                                     std::regex_constants::format_first_only);
  if (!std::regex_search(s, main_fn)) {
    error = "no main() in MaterialX's pixel shader";
    return "";
  }
  s = std::regex_replace(s, main_fn, "void mx_main()", std::regex_constants::format_first_only);
  // MaterialX 1.39.5 with SPECULAR_ENVIRONMENT_NONE leaves the private uniform
  // u_refractionTwoSided undeclared while mx_surface_transmission() reads it (the
  // code does not compile as generated); declared here with MaterialX's default, as
  // a constant since SPIR-V has no bool uniforms. Only scatter modes other than R
  // (reflection) read it, and every case here is R.
  static const std::regex declared(R"(\bu_refractionTwoSided\s*[=;])");
  if (s.find("u_refractionTwoSided") != std::string::npos && !std::regex_search(s, declared))
    s = std::regex_replace(s, std::regex(R"(// Uniform block: PrivateUniforms\n)"),
                           "// Uniform block: PrivateUniforms\nconst bool u_refractionTwoSided = false;  // facet's harness\n",
                           std::regex_constants::format_first_only);
  // The frame fills the vertex data MaterialX declared (a diffuse BSDF has no tangent).
  std::string fill;
  const std::string fields = m[1];
  for (const auto& [field, value] : {std::pair<std::string, std::string>{"positionWorld", "p"},
                                     {"normalWorld", "n"}, {"tangentWorld", "facet_tangent(n)"}})
    if (fields.find(field) != std::string::npos) fill += "    vd." + field + " = " + value + ";\n";
  std::string frame = read_file(std::string(FACET_SOURCE_DIR) + "/tests/bench/materialx_frame.glsl");
  frame.replace(frame.find("{{vertex_data}}\n"), std::string("{{vertex_data}}\n").size(), fill);
  return s + cost_raycast_source() + frame;
}

// MaterialX's light and view uniforms for the scene's first light: a point light
// (type 1, as bound) of intensity π and no decay, since MaterialX's radiance is
// intensity · f · n·l and facet's C ⊗ ρ with ρ = π f n·l.
std::vector<std::pair<std::string, std::vector<double>>> materialx_uniforms(int size) {
  auto u = cost_frame_uniforms(size, size);
  const Scene s = default_scene();
  const Light& l = s.lights.at(0);
  u.push_back({"u_viewPosition", {s.camera.position.x, s.camera.position.y, s.camera.position.z}});
  u.push_back({"u_numActiveLightSources", {1}});
  u.push_back({"u_lightData[0].type", {1}});
  u.push_back({"u_lightData[0].position", {l.position.x, l.position.y, l.position.z}});
  u.push_back({"u_lightData[0].color", {l.color[0], l.color[1], l.color[2]}});
  u.push_back({"u_lightData[0].intensity", {kPi}});
  u.push_back({"u_lightData[0].decay_rate", {0}});
  return u;
}

// Why a GGX render differs: MaterialX's source with its energy compensation
// taken out, then also its height-correlated Smith G made separable, as facet's.
// Each patch is a line of MaterialX 1.39's library code; "" where it is not there.
struct Variant {
  std::string label, source;
};
std::vector<Variant> explanations(const std::string& mx) {
  const std::string comp = "return 1.0 + Fss * (1.0 - Ess) / Ess;";
  const std::string g2 = "return 2.0 * NdotL * NdotV / (lambdaL * NdotV + lambdaV * NdotL);";
  if (mx.find(comp) == std::string::npos || mx.find(g2) == std::string::npos) return {};
  std::string a = mx;
  a.replace(a.find(comp), comp.size(), "return vec3(1.0);");
  std::string b = a;
  b.replace(b.find(g2), g2.size(), "return 4.0 * NdotL * NdotV / ((NdotL + lambdaL) * (NdotV + lambdaV));");
  return {{"without energy compensation", a}, {"and with separable Smith G", b}};
}

std::string us(double seconds) { return fmt::format("{:.1f}", seconds * 1e6); }
std::string verdict(const ComparisonRow& r) {
  if (!r.error.empty()) return "error";
  return fmt::format("{} |Δ| {:.1e} (rel {:.1e})", r.pass ? "pass" : "FAIL", r.metrics.max_abs, r.metrics.max_excess);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: facet_materialx_bench JOB.json [--no-callgrind] [--size N]\n"
                 "(scripts/bench_materialx.sh makes the job with tests/bench/materialx_bench.py)\n";
    return 2;
  }
  bool callgrind = true, check = false;
  int size = 128;
  for (int i = 2; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--no-callgrind") callgrind = false;
    else if (a == "--check") check = true;
    else if (a == "--size" && i + 1 < argc) size = std::stoi(argv[++i]);
  }
  const json job = json::parse(read_file(argv[1]));
  const std::string workdir = fs::path(argv[1]).parent_path().string();
  const int repeats = job["repeats"];

  struct Case {
    std::string name, node, note;
    Material m;
    double mx_glsl, mx_osl, facet_glsl, facet_osl;
    SpirvCount spv_facet, spv_mx;
    ComparisonRow cmp_facet, cmp_mx;
    std::vector<Variant> variants;
    std::vector<ComparisonRow> cmp_variants;
  };
  std::vector<Case> cases;
  std::vector<ShaderDraw> draws;
  int status = 0;
  for (const auto& c : job["cases"]) {
    Case k;
    k.name = c["name"];
    k.node = c["materialx_node"];
    k.note = c["note"];
    k.m = parse_material(c["facet_material"], k.name);
    k.mx_glsl = c["materialx_seconds"]["glsl"];
    k.mx_osl = c["materialx_seconds"]["osl"];
    k.facet_glsl = generate_seconds(k.m, Target::Glsl, repeats);
    k.facet_osl = generate_seconds(k.m, Target::Osl, repeats);
    std::string error;
    std::string mx = harness_source(read_file(c["files"]["pixel"]), error);
    if (mx.empty()) {
      std::cerr << "error: " << k.name << ": " << error << "\n";
      return 1;
    }
    write_file_atomic((fs::path(workdir) / (k.name + ".harness.frag")).string(), mx);
    if (k.m.specular) k.variants = explanations(mx);  // the GGX cases
    draws.push_back({k.name + " (facet)", cost_fragment_source(k.m), cost_frame_uniforms(size, size)});
    draws.push_back({k.name + " (MaterialX)", mx, materialx_uniforms(size)});
    k.spv_facet = spirv_instructions(draws[draws.size() - 2].fragment_source, workdir, k.name + "_facet");
    k.spv_mx = spirv_instructions(mx, workdir, k.name + "_materialx");
    for (const SpirvCount* s : {&k.spv_facet, &k.spv_mx})
      if (!s->error.empty()) {
        std::cerr << "error: " << k.name << ": " << s->error << "\n";
        status = 1;
      }
    cases.push_back(std::move(k));
  }

  GlRenderer gl;
  std::vector<RenderOutcome> images = gl.draw(draws, size, size);
  std::vector<ShaderDraw> variant_draws;
  for (const auto& c : cases)
    for (const auto& v : c.variants) variant_draws.push_back({c.name + " " + v.label, v.source, materialx_uniforms(size)});
  std::vector<RenderOutcome> variant_images = gl.draw(variant_draws, size, size);
  std::vector<CallgrindCount> counts(draws.size());
  if (callgrind) counts = callgrind_draws(draws, size, size, CostOptions{}, workdir + "/callgrind");
  const Scene scene = default_scene();
  auto compare = [](const Render& ref, const RenderOutcome& image) { return judge(ref, image, false, ValidateOptions{}); };
  size_t next_variant = 0;
  for (size_t k = 0; k < cases.size(); ++k) {
    Render ref = render_reference(cases[k].m, scene, size, size);
    cases[k].cmp_facet = compare(ref, images[2 * k]);
    cases[k].cmp_mx = compare(ref, images[2 * k + 1]);
    for (size_t v = 0; v < cases[k].variants.size(); ++v)
      cases[k].cmp_variants.push_back(compare(ref, variant_images[next_variant++]));
  }

  fmt::print("MaterialX {} against facet {}: the same BRDF, the scene \"single\" at {}×{} ({}; {})\n",
             job["materialx"].get<std::string>(), FACET_VERSION, size, size, gl.description(),
             "SPIR-V after glslangValidator -G --aml and spirv-opt -O, as facet cost counts");
  fmt::print("{:<18} {:>21} {:>21} {:>18} {:>26}\n", "", "generate GLSL µs", "generate OSL µs", "SPIR-V", "llvmpipe instr/px");
  fmt::print("{:<18} {:>7} {:>7} {:>6} {:>7} {:>7} {:>6} {:>6} {:>6} {:>5} {:>8} {:>8} {:>8}\n", "case", "facet",
             "MtlX", "MtlX/f", "facet", "MtlX", "MtlX/f", "facet", "MtlX", "f/Mx", "facet", "MtlX", "f/MtlX");
  for (size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const CallgrindCount &cf = counts[2 * k], &cm = counts[2 * k + 1];
    std::string dynamic = !callgrind ? fmt::format("{:>8} {:>8} {:>8}", "–", "–", "–")
                          : cf.error.empty() && cm.error.empty()
                              ? fmt::format("{:8.1f} {:8.1f} {:8.3f}", cf.per_pixel, cm.per_pixel, cf.per_pixel / cm.per_pixel)
                              : "callgrind failed: " + (cf.error.empty() ? cm.error : cf.error).substr(0, 60);
    fmt::print("{:<18} {:>7} {:>7} {:>6.1f} {:>7} {:>7} {:>6.1f} {:>6} {:>6} {:>5.2f} {}\n", c.name, us(c.facet_glsl),
               us(c.mx_glsl), c.mx_glsl / c.facet_glsl, us(c.facet_osl), us(c.mx_osl), c.mx_osl / c.facet_osl,
               c.spv_facet.instructions, c.spv_mx.instructions,
               double(c.spv_facet.instructions) / c.spv_mx.instructions, dynamic);
  }
  fmt::print("\nBoth renders against facet's C++ reference (|Δ| ≤ 2e-3 · max(1, |ref|) on interior pixels):\n");
  for (const auto& c : cases) {
    fmt::print("  {:<18} facet: {:<34} MaterialX {}: {}\n", c.name, verdict(c.cmp_facet), c.node, verdict(c.cmp_mx));
    for (size_t v = 0; v < c.variants.size(); ++v)
      fmt::print("  {:<18} MaterialX {}: {}\n", "", c.variants[v].label, verdict(c.cmp_variants[v]));
    const ComparisonRow& w = c.cmp_mx;
    if (w.error.empty())
      fmt::print("  {:<18} worst pixel ({}, {}): reference {:.5g}, MaterialX {:.5g} (× {:.4f})\n", "", w.metrics.worst_x,
                 w.metrics.worst_y, w.metrics.worst_ref[0], w.metrics.worst_got[0],
                 w.metrics.worst_ref[0] > 0 ? w.metrics.worst_got[0] / w.metrics.worst_ref[0] : 0.0);
    fmt::print("  {:<18} {}\n", "", c.note);
    if (!c.cmp_facet.pass) status = 1;  // facet's own code must match its reference
    if (check && c.spv_facet.instructions > c.spv_mx.instructions) {
      fmt::print("  {:<18} facet's SPIR-V ({}) exceeds MaterialX's ({})\n", "", c.spv_facet.instructions,
                 c.spv_mx.instructions);
      status = 1;
    }
  }
  fmt::print("\nGeneration: one generate() call per material and target, each side in its own process (MaterialX's "
             "generate() from Python, facet's generate() in C++): {} calls in 10 batches after one untimed call, the "
             "least batch mean.\n",
             repeats);
  return status;
}
