// facet's generated GLSL against hand-minimized GLSL of the same formulas
// (tests/bench/hand/<model>.glsl), in the same single-light cost frame: SPIR-V
// instruction counts after spirv-opt -O side by side, and both renders compared
// with the C++ reference, so the minimum is honest. The HLSL path likewise: facet's
// --target hlsl library against tests/bench/hand/hlsl/<model>.hlsl (the same hand
// formulas in HLSL) in the HLSL cost frame, through glslangValidator -D -V.
//
//   facet_hand_bench [--check] [--callgrind] [--size N] [--workdir DIR]
//
// --check: exit 1 if facet's count exceeds 1.10 × the hand version's for any
// model, in GLSL or in HLSL, if a lobe model has no hand version, or if either render fails the
// comparison (|Δ| ≤ 2e-3 · max(1, |reference|) on interior pixels).
// --callgrind: also llvmpipe instructions per pixel of both (valgrind; ~30 s).
#include <cstring>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "analysis/cost.h"
#include "analysis/validate.h"
#include "core/io.h"
#include "reference/raycaster.h"
#include "scene/scene.h"

namespace fs = std::filesystem;
using namespace facet;

namespace {

const double kMaxRatio = 1.10;

struct Args {
  bool check = false, callgrind = false;
  int size = 128;
  std::string workdir = (fs::temp_directory_path() / "facet-hand-bench").string();
  std::string hand = std::string(FACET_SOURCE_DIR) + "/tests/bench/hand";
};

// facet's and the hand version's SPIR-V counts of one path (GLSL or HLSL) for one model.
struct PathCount {
  SpirvCount facet, hand;
  double ratio() const { return double(facet.instructions) / hand.instructions; }
};

// The HLSL path of `m`: facet's --target hlsl library and hand/hlsl/<model>.hlsl in the HLSL cost frame.
PathCount hlsl_counts(const Material& m, const Args& a, const std::string& common, std::vector<std::string>& problems) {
  PathCount c;
  const std::string file = a.hand + "/hlsl/" + m.name + ".hlsl";
  if (!fs::exists(file)) {
    problems.push_back(m.name + ": no HLSL hand version " + file);
    return c;
  }
  c.facet = hlsl_spirv_instructions(hlsl_cost_fragment_source(m), a.workdir, m.name + "_facet_hlsl");
  c.hand = hlsl_spirv_instructions(hlsl_cost_frame_source(common + read_file(file)), a.workdir, m.name + "_hand_hlsl");
  if (!c.facet.error.empty() || !c.hand.error.empty())
    problems.push_back(m.name + " (HLSL): " + (c.facet.error.empty() ? c.hand.error : c.facet.error));
  return c;
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    std::string s = argv[i];
    if (s == "--check") a.check = true;
    else if (s == "--callgrind") a.callgrind = true;
    else if (s == "--size" && i + 1 < argc) a.size = std::stoi(argv[++i]);
    else if (s == "--workdir" && i + 1 < argc) a.workdir = argv[++i];
    else {
      std::cerr << "usage: facet_hand_bench [--check] [--callgrind] [--size N] [--workdir DIR]\n";
      std::exit(2);
    }
  }
  return a;
}

std::string verdict(const ComparisonRow& r) {
  if (!r.error.empty()) return "error";
  return fmt::format("{} {:.1e}", r.pass ? "ok" : "FAIL", r.metrics.max_abs);
}

}  // namespace

int main(int argc, char** argv) {
  Args a = parse(argc, argv);
  const std::string common = read_file(a.hand + "/common.glsl");
  const auto uniforms = cost_frame_uniforms(a.size, a.size);
  const Scene scene = default_scene();
  // The frame with its normal, light and view vectors live: what is left is the BRDF's.
  const int frame = spirv_instructions(cost_frame_source(common + R"(
vec3 facet_reflect(vec3 n, vec3 l, vec3 v, vec3 t) { return n + l + v; }
)"),
                                       a.workdir, "frame")
                        .instructions;

  const std::string hlsl_common = read_file(a.hand + "/hlsl/common.hlsl");
  const int hlsl_frame = hlsl_spirv_instructions(hlsl_cost_frame_source(hlsl_common + R"(
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t) { return n + l + v; }
)"),
                                                 a.workdir, "frame_hlsl")
                             .instructions;

  std::vector<Material> models = model_materials();
  std::vector<ShaderDraw> draws;  // facet's, then the hand version, per model
  std::vector<std::string> problems;
  for (const auto& m : models) {
    std::string hand_file = a.hand + "/" + m.name + ".glsl";
    std::string hand = fs::exists(hand_file) ? read_file(hand_file) : "";
    if (hand.empty()) problems.push_back(m.name + ": no hand version " + hand_file);
    draws.push_back({m.name, cost_fragment_source(m), uniforms});
    draws.push_back({m.name + " (hand)", cost_frame_source(common + hand), uniforms});
  }
  GlRenderer gl;
  std::vector<RenderOutcome> images = gl.draw(draws, a.size, a.size);
  std::vector<CallgrindCount> counts;
  if (a.callgrind) counts = callgrind_draws(draws, a.size, a.size, CostOptions{}, a.workdir + "/callgrind");

  fmt::print("SPIR-V instructions after spirv-opt -O, in the cost frame ({} of them alone; the HLSL frame {}); renders "
             "against the C++ reference at {}×{} (max |Δ|)\n",
             frame, hlsl_frame, a.size, a.size);
  fmt::print("{:<18} {:>6} {:>6} {:>6}  {:>10} {:>10}  {:>6} {:>6} {:>6}  {:<12} {:<12}{}\n", "model", "facet", "hand",
             "ratio", "facet BRDF", "hand BRDF", "HLSL", "hand", "ratio", "facet", "hand",
             a.callgrind ? "  llvmpipe instr/px facet, hand, ratio" : "");
  double worst = 0, worst_hlsl = 0;
  ValidateOptions tolerance;
  for (size_t k = 0; k < models.size(); ++k) {
    const Material& m = models[k];
    SpirvCount f = spirv_instructions(draws[2 * k].fragment_source, a.workdir, m.name + "_facet");
    SpirvCount h = spirv_instructions(draws[2 * k + 1].fragment_source, a.workdir, m.name + "_hand");
    if (!f.error.empty() || !h.error.empty()) {
      problems.push_back(m.name + ": " + (f.error.empty() ? h.error : f.error));
      continue;
    }
    Render ref = render_reference(m, scene, a.size, a.size);
    ComparisonRow rf, rh;
    for (auto [row, image] : {std::pair{&rf, &images[2 * k]}, std::pair{&rh, &images[2 * k + 1]}}) {
      *row = judge(ref, *image, false, tolerance);
      if (!row->error.empty() || !row->pass)
        problems.push_back(fmt::format("{}: the {} render does not match the reference: {}", m.name,
                                       row == &rf ? "facet" : "hand", row->error.empty() ? verdict(*row) : row->error));
    }
    double ratio = double(f.instructions) / h.instructions;
    worst = std::max(worst, ratio);
    if (ratio > kMaxRatio)
      problems.push_back(fmt::format("{}: facet's {} instructions are {:.3f} × the hand version's {}", m.name,
                                     f.instructions, ratio, h.instructions));
    PathCount hl = hlsl_counts(m, a, hlsl_common, problems);
    const bool hlsl_ok = hl.facet.error.empty() && hl.hand.error.empty() && hl.hand.instructions > 0;
    if (hlsl_ok) worst_hlsl = std::max(worst_hlsl, hl.ratio());
    if (hlsl_ok && hl.ratio() > kMaxRatio)
      problems.push_back(fmt::format("{}: facet's HLSL {} instructions are {:.3f} × the hand HLSL's {}", m.name,
                                     hl.facet.instructions, hl.ratio(), hl.hand.instructions));
    std::string dynamic;
    if (a.callgrind) {
      const CallgrindCount &cf = counts[2 * k], &ch = counts[2 * k + 1];
      dynamic = cf.error.empty() && ch.error.empty()
                    ? fmt::format("  {:8.1f} {:8.1f} {:6.3f}", cf.per_pixel, ch.per_pixel, cf.per_pixel / ch.per_pixel)
                    : "  callgrind failed: " + (cf.error.empty() ? ch.error : cf.error).substr(0, 80);
    }
    fmt::print("{:<18} {:>6} {:>6} {:>6.3f}  {:>10} {:>10}  {:>6} {:>6} {:>6}  {:<12} {:<12}{}\n", m.name,
               f.instructions, h.instructions, ratio, f.instructions - frame, h.instructions - frame,
               hl.facet.instructions, hl.hand.instructions, hlsl_ok ? fmt::format("{:.3f}", hl.ratio()) : "error",
               verdict(rf), verdict(rh), dynamic);
  }
  fmt::print("worst ratio {:.3f}, HLSL {:.3f} (limit {:.2f})\n", worst, worst_hlsl, kMaxRatio);
  for (const auto& p : problems) fmt::print("problem: {}\n", p);
  return a.check && !problems.empty() ? 1 : 0;
}
