// The comparison has teeth: a deliberately wrong target (an exponent off by
// one, a missing π) rendered by the real renderer fails the same judgement
// that `facet validate` applies, while the generated code passes it.
#include <filesystem>

#include <gtest/gtest.h>

#include "facet/material.h"
#include "facet/program.h"
#include "facet/render.h"
#include "facet/renderers.h"
#include "facet/targets.h"
#include "facet/validate.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = FACET_SOURCE_DIR;
const int kSize = 96;

struct Fixture {
  Material material;
  Scene scene;
  Render reference;
  RenderJob job;
};

Fixture fixture(const std::string& example, const std::string& renderer) {
  Fixture f;
  f.material = load_material((kSource / "examples/materials" / (example + ".json")).string());
  f.scene = load_scene("single");
  f.reference = render_reference(f.material, f.scene, kSize, kSize);
  f.job.material = f.material;
  f.job.scene = f.scene;
  f.job.width = f.job.height = kSize;
  f.job.workdir = (fs::temp_directory_path() / ("facet-detection-" + std::to_string(::getpid())) / renderer / example)
                      .string();
  for (float v : f.reference.image.rgb) f.job.max_value = std::max<double>(f.job.max_value, v);
  return f;
}

// Replaces `from` by `to` once; the test fails if `from` is not there, so a
// generator change cannot make the fault silently vanish.
std::string inject(const std::string& code, const std::string& from, const std::string& to) {
  size_t at = code.find(from);
  EXPECT_NE(at, std::string::npos) << "the code no longer contains: " << from;
  if (at == std::string::npos) return code;
  return code.substr(0, at) + to + code.substr(at + from.size());
}

ComparisonRow judged(const Fixture& f, const RenderOutcome& r) {
  EXPECT_TRUE(r.ok) << r.error;
  return judge(f.reference, r.image, r.alpha, false, ValidateOptions{});
}

TEST(Detection, GlslExponentOffByOneFails) {
  Fixture f = fixture("blinn_phong", "glsl");
  GlRenderer gl;
  ASSERT_TRUE(gl.ok()) << gl.error();
  std::string good = GlRenderer::fragment_source(f.material);
  f.job.code_override = good;
  EXPECT_TRUE(judged(f, gl.render(f.job)).pass);
  f.job.code_override = inject(good, "pow(max(NoH, 0.0), n)", "pow(max(NoH, 0.0), n + 1.0)");
  ComparisonRow bad = judged(f, gl.render(f.job));
  EXPECT_FALSE(bad.pass) << "max |Δ|/max(1,|ref|) " << bad.metrics.max_excess;
  EXPECT_GT(bad.metrics.over, 0u);
}

TEST(Detection, GlslMissingPiFails) {
  Fixture f = fixture("cook_torrance", "glsl");
  GlRenderer gl;
  ASSERT_TRUE(gl.ok()) << gl.error();
  f.job.code_override = inject(GlRenderer::fragment_source(f.material), "return PI * D * G * F", "return D * G * F");
  ComparisonRow bad = judged(f, gl.render(f.job));
  EXPECT_FALSE(bad.pass) << "max |Δ|/max(1,|ref|) " << bad.metrics.max_excess;
}

TEST(Detection, PovMissingPiFails) {
  Fixture f = fixture("cook_torrance", "pov");
  GenerateOptions o;
  o.target = Target::Pov;
  o.scene = f.scene;
  std::string good = generate(f.material, o);
  f.job.code_override = good;
  EXPECT_TRUE(judged(f, render_pov(f.job)).pass);
  f.job.code_override = inject(good, "{ pi * D * G * F / (4 * NoV) }", "{ D * G * F / (4 * NoV) }");
  ComparisonRow bad = judged(f, render_pov(f.job));
  EXPECT_FALSE(bad.pass) << "max |Δ|/max(1,|ref|) " << bad.metrics.max_excess;
}

TEST(Detection, PovExponentOffByOneFails) {
  Fixture f = fixture("blinn_phong", "pov");  // POV-Ray's own finish: roughness = 1/n
  GenerateOptions o;
  o.target = Target::Pov;
  o.scene = f.scene;
  f.job.code_override = inject(generate(f.material, o), "roughness 0.02", "roughness 0.0196078431372549");
  ComparisonRow bad = judged(f, render_pov(f.job));
  EXPECT_FALSE(bad.pass) << "max |Δ|/max(1,|ref|) " << bad.metrics.max_excess;
}

TEST(Detection, OslMissingPiAndExponentOffByOneFail) {
  Fixture ct = fixture("cook_torrance", "osl");
  Fixture bp = fixture("blinn_phong", "osl");
  GenerateOptions o;
  o.target = Target::Osl;
  o.scene = ct.scene;
  std::string ct_code = generate(ct.material, o);
  std::string bp_code = generate(bp.material, o);
  // One Blender process: the good code, then the two faults.
  std::vector<RenderJob> jobs = {ct.job, ct.job, bp.job};
  jobs[2].workdir = ct.job.workdir;
  jobs[0].code_override = ct_code;
  jobs[1].code_override = inject(ct_code, "return M_PI * D * G * F", "return D * G * F");
  jobs[1].material->name = "cook_torrance_without_pi";
  jobs[2].code_override = inject(bp_code, "pow(max(NoH, 0.0), n)", "pow(max(NoH, 0.0), n + 1.0)");
  jobs[2].material->name = "blinn_phong_exponent_plus_one";
  std::string log;
  std::vector<RenderOutcome> r = render_osl(jobs, default_python(), log);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_TRUE(judged(ct, r[0]).pass) << log;
  EXPECT_FALSE(judged(ct, r[1]).pass) << log;
  EXPECT_FALSE(judged(bp, r[2]).pass) << log;
}

}  // namespace
}  // namespace facet
