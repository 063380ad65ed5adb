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
#include <regex>
#include <tuple>

#include <fmt/format.h>

#include "analysis/cost.h"
#include "analysis/validate.h"
#include "core/io.h"
#include "reference/raycaster.h"
#include "renderers/process.h"
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

using Uniforms = std::vector<std::pair<std::string, std::vector<double>>>;

// facet's HLSL, drawn: the HLSL path's SPIR-V back to GLSL 3.30 by spirv-cross, the
// cbuffer as one plain uniform struct whose members the frame's uniforms then name.
ShaderDraw hlsl_as_glsl(const std::string& name, const SpirvCount& c, const Uniforms& uniforms, const Args& a) {
  ShaderDraw d{name + " (HLSL)", "", {}};
  const std::string glsl = a.workdir + "/" + name + "_hlsl_as.frag";
  ProcessResult r = run_process({"spirv-cross", "--version", "330", "--no-es", "--glsl-emit-ubo-as-plain-uniforms",
                                 c.module, "--output", glsl});
  if (r.exit_code != 0) {
    d.fragment_source = "spirv-cross failed: " + r.output;  // fails to compile, and says why
    return d;
  }
  d.fragment_source = read_file(glsl);
  std::smatch instance;
  std::regex_search(d.fragment_source, instance, std::regex(R"(uniform FacetCostFrame (\w+);)"));
  for (const auto& [uniform, values] : uniforms) d.uniforms.push_back({instance[1].str() + "." + uniform, values});
  return d;
}

// The HLSL frame computes gl_FragCoord's y from SV_Position's, which runs down; drawn by GL,
// whose gl_FragCoord runs up, the image comes out upside down: its rows are put back.
void flip_rows(RenderOutcome& r) {
  Image& im = r.image;
  for (int y = 0; y < im.height / 2; ++y)
    for (int x = 0; x < im.width; ++x) {
      std::swap_ranges(im.at(x, y), im.at(x, y) + 3, im.at(x, im.height - 1 - y));
      if (!r.alpha.empty())
        std::swap(r.alpha[size_t(y) * im.width + x], r.alpha[size_t(im.height - 1 - y) * im.width + x]);
    }
}

// The HLSL path of every model: facet's and the hand counts, and facet's HLSL drawn.
struct HlslPath {
  int frame = 0;
  std::vector<PathCount> counts;
  std::vector<RenderOutcome> images;
};

HlslPath hlsl_path(const std::vector<Material>& models, const Args& a, const Uniforms& uniforms, GlRenderer& gl,
                   std::vector<std::string>& problems) {
  HlslPath out;
  const std::string common = read_file(a.hand + "/hlsl/common.hlsl");
  out.frame = hlsl_spirv_instructions(hlsl_cost_frame_source(common + R"(
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t) { return n + l + v; }
)"),
                                      a.workdir, "frame_hlsl")
                  .instructions;
  std::vector<ShaderDraw> draws;
  for (const auto& m : models) {
    out.counts.push_back(hlsl_counts(m, a, common, problems));
    draws.push_back(hlsl_as_glsl(m.name, out.counts.back().facet, uniforms, a));
  }
  out.images = gl.draw(draws, a.size, a.size);
  for (auto& image : out.images) flip_rows(image);
  return out;
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
  HlslPath hlsl = hlsl_path(models, a, uniforms, gl, problems);
  const int hlsl_frame = hlsl.frame;
  std::vector<CallgrindCount> counts;
  if (a.callgrind) counts = callgrind_draws(draws, a.size, a.size, CostOptions{}, a.workdir + "/callgrind");

  fmt::print("SPIR-V instructions after spirv-opt -O, in the cost frame ({} of them alone; the HLSL frame {}); renders "
             "against the C++ reference at {}×{} (max |Δ|)\n",
             frame, hlsl_frame, a.size, a.size);
  fmt::print("{:<18} {:>6} {:>6} {:>6}  {:>10} {:>10}  {:>6} {:>6} {:>6}  {:<12} {:<12} {:<12}{}\n", "model", "facet",
             "hand", "ratio", "facet BRDF", "hand BRDF", "HLSL", "hand", "ratio", "facet", "hand", "facet HLSL",
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
    ComparisonRow rf, rh, rl;
    for (auto [row, image, what] : {std::tuple{&rf, &images[2 * k], "facet"}, std::tuple{&rh, &images[2 * k + 1], "hand"},
                                    std::tuple{&rl, &hlsl.images[k], "facet HLSL"}}) {
      *row = judge(ref, *image, false, tolerance);
      if (!row->error.empty() || !row->pass)
        problems.push_back(fmt::format("{}: the {} render does not match the reference: {}", m.name, what,
                                       row->error.empty() ? verdict(*row) : row->error));
    }
    double ratio = double(f.instructions) / h.instructions;
    worst = std::max(worst, ratio);
    if (ratio > kMaxRatio)
      problems.push_back(fmt::format("{}: facet's {} instructions are {:.3f} × the hand version's {}", m.name,
                                     f.instructions, ratio, h.instructions));
    const PathCount& hl = hlsl.counts[k];
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
    fmt::print("{:<18} {:>6} {:>6} {:>6.3f}  {:>10} {:>10}  {:>6} {:>6} {:>6}  {:<12} {:<12} {:<12}{}\n", m.name,
               f.instructions, h.instructions, ratio, f.instructions - frame, h.instructions - frame,
               hl.facet.instructions, hl.hand.instructions, hlsl_ok ? fmt::format("{:.3f}", hl.ratio()) : "error",
               verdict(rf), verdict(rh), verdict(rl), dynamic);
  }
  fmt::print("worst ratio {:.3f}, HLSL {:.3f} (limit {:.2f})\n", worst, worst_hlsl, kMaxRatio);
  for (const auto& p : problems) fmt::print("problem: {}\n", p);
  return a.check && !problems.empty() ? 1 : 0;
}
