// The comparison has teeth: a deliberately wrong target (an exponent off by
// one, a missing π) rendered by the real renderer fails the same judgement
// that `facet validate` applies, while the generated code passes it.
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analysis/sweep.h"
#include "analysis/validate.h"
#include "catalog/material.h"
#include "catalog/program.h"
#include "core/io.h"
#include "scene/gltf.h"
#include "reference/raycaster.h"
#include "scene/shapes.h"
#include "renderers/compare.h"
#include "renderers/hlsl_shading.h"
#include "renderers/opengl.h"
#include "renderers/process.h"
#include "renderers/renderer.h"
#include "renderers/sweep.h"
#include "targets/targets.h"
#include "test_support.h"

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

Fixture fixture(const std::string& example, const std::string& renderer, const std::string& folder = "materials",
                const std::string& scene = "single") {
  Fixture f;
  f.material = load_material((kSource / "examples" / folder / (example + ".json")).string());
  f.scene = load_scene(scene);
  f.reference = render_reference(f.material, f.scene, kSize, kSize);
  f.job.material = f.material;
  f.job.scene = f.scene;
  f.job.width = f.job.height = kSize;
  f.job.workdir = (test::scratch("detection", renderer) / example).string();
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

// One job through the registry's renderer `name`.
RenderOutcome render_one(const std::string& name, const RenderJob& job) {
  return make_renderer(name)->render({job}).at(0);
}

ComparisonRow judged(const Fixture& f, const RenderOutcome& r) {
  EXPECT_TRUE(r.ok) << r.error;
  return judge(f.reference, r.image, r.alpha, false, ValidateOptions{});
}

// A renderer's shading code for a material: what the test draws, right or made wrong.
using Source = std::function<std::string(const Material&)>;

std::string glsl_source(const Material& m) { return GlRenderer::fragment_source(m); }
std::string osl_source(const Material& m, const Scene& scene) {
  GenerateOptions o;
  o.target = Target::Osl;
  o.scene = scene;
  return generate(m, o);
}

// The two faults of this file's opening comment in one renderer's shading code, drawn
// in one render() call (one Blender, Chromium or Python start): blinn_phong with its
// exponent one too high and cook_torrance without its π fail, while the generated
// blinn_phong passes. `pi_from` is the target's spelling of the microfacet return.
void expect_exponent_and_pi_faults_fail(const std::string& renderer, const Source& source,
                                        const std::string& pi_from = "return PI / 4.0 * D * G * F") {
  std::unique_ptr<Renderer> r = make_renderer(renderer);
  ASSERT_EQ(r->unavailable(), "") << renderer;
  Fixture bp = fixture("blinn_phong", renderer), ct = fixture("cook_torrance", renderer);
  const std::string good = source(bp.material);
  std::vector<RenderJob> jobs = {bp.job, bp.job, ct.job};
  jobs[0].code_override = good;
  jobs[1].code_override = inject(good, "pow(clamp(NoH, 0.0, 1.0), n)", "pow(clamp(NoH, 0.0, 1.0), n + 1.0)");
  jobs[1].material->name = "blinn_phong_exponent_plus_one";
  jobs[2].code_override = inject(source(ct.material), pi_from, "return 1.0 / 4.0 * D * G * F");
  jobs[2].material->name = "cook_torrance_without_pi";
  jobs[2].workdir = bp.job.workdir;  // one folder for the batch
  std::vector<RenderOutcome> out = r->render(jobs);
  ASSERT_EQ(out.size(), 3u) << renderer;
  ComparisonRow right = judged(bp, out[0]), exponent = judged(bp, out[1]), pi = judged(ct, out[2]);
  EXPECT_TRUE(right.pass) << renderer << ": max |Δ|/max(1,|ref|) " << right.metrics.max_excess;
  EXPECT_FALSE(exponent.pass) << renderer << ", exponent + 1: max |Δ|/max(1,|ref|) " << exponent.metrics.max_excess;
  EXPECT_GT(exponent.metrics.over, 0u) << renderer;
  EXPECT_FALSE(pi.pass) << renderer << ", no π: max |Δ|/max(1,|ref|) " << pi.metrics.max_excess;
  std::cout << renderer << ": exponent + 1 worst " << exponent.metrics.max_excess << " (" << exponent.metrics.over
            << " pixels over), no π worst " << pi.metrics.max_excess << "\n";
}

TEST(Detection, GlslExponentOffByOneAndMissingPiFail) { expect_exponent_and_pi_faults_fail("glsl", glsl_source); }

// The Vulkan renderers: glsl450 and HLSL as SPIR-V over the G-buffer.
TEST(Detection, VulkanExponentOffByOneAndMissingPiFail) {
  expect_exponent_and_pi_faults_fail(
      "vulkan", [](const Material& m) { return glsl_gbuffer_shading_source(m, Target::Glsl450); });
  expect_exponent_and_pi_faults_fail("vulkan-hlsl", hlsl_shading_source);
}

// WebGL2 in Chromium (the ES 3.00 shading pass over the GL ray caster's G-buffer); and
// a shader that does not compile comes back as the renderer's error with WebGL's own log.
TEST(Detection, WebglMissingPiAndExponentOffByOneFail) {
  auto essl = [](const Material& m) { return glsl_gbuffer_shading_source(m, Target::Essl); };
  expect_exponent_and_pi_faults_fail("webgl", essl);
  Fixture f = fixture("blinn_phong", "webgl");
  f.job.code_override = inject(essl(f.material), "facet_color = vec4(facet_shade(", "facet_color = vec5(facet_shade(");
  RenderOutcome out = render_one("webgl", f.job);
  EXPECT_FALSE(out.ok);
  EXPECT_NE(out.error.find("did not compile in WebGL"), std::string::npos) << out.error;
  EXPECT_NE(out.error.find("vec5"), std::string::npos) << out.error;  // WebGL's log names it
  std::cout << "webgl, a shader that does not compile: " << out.error << "\n";
}

// The wgpu renderer: the generated WGSL shading the GL ray caster's G-buffer.
TEST(Detection, WgpuExponentOffByOneAndMissingPiFail) {
  expect_exponent_and_pi_faults_fail("wgpu", wgsl_gbuffer_shading_source);
}

TEST(Detection, OslMissingPiAndExponentOffByOneFail) {
  const Scene single = load_scene("single");
  expect_exponent_and_pi_faults_fail(
      "osl", [&](const Material& m) { return osl_source(m, single); }, "return M_PI / 4.0 * D * G * F");
}

// docs/textures.md's sampling rule, each part made wrong in a renderer's generated code:
// the picture upside down (v up, as OpenGL's texture() and Blender's UV maps have it),
// lookups half a texel off (texel corners taken for centres), sRGB not decoded. Every
// one fails on the textured examples (sphere and square, the shadows scene), the right
// code passes; each example's right and wrong shaders are drawn in one render() call.
struct WrongTexturing {
  const char* what;
  const char* from;
  const char* to;
  const char* only;  // the example whose filter the fault is in, or null for both
};

void expect_texture_faults_fail(const std::string& renderer, const Source& source,
                                const std::vector<WrongTexturing>& wrongs) {
  std::unique_ptr<Renderer> r = make_renderer(renderer);
  ASSERT_EQ(r->unavailable(), "") << renderer;
  for (const char* example : {"textured_lambert", "textured_ggx"}) {
    Fixture f = fixture(example, renderer, "textured", "shadows");
    const std::string good = source(f.material);
    std::vector<RenderJob> jobs = {f.job};
    jobs[0].code_override = good;
    std::vector<std::string> names = {"right"};
    for (const auto& w : wrongs) {
      if (w.only && std::string(example) != w.only) continue;
      jobs.push_back(f.job);
      jobs.back().code_override = inject(good, w.from, w.to);
      jobs.back().material->name = fmt::format("{}_wrong_{}", example, jobs.size());
      names.push_back(w.what);
    }
    std::vector<RenderOutcome> out = r->render(jobs);
    ASSERT_EQ(out.size(), jobs.size()) << renderer;
    for (size_t k = 0; k < out.size(); ++k) {
      ComparisonRow row = judged(f, out[k]);
      std::cout << renderer << ", " << example << ", " << names[k] << ": " << row.metrics.over
                << " pixels over, worst " << row.metrics.max_excess << "\n";
      if (k == 0) EXPECT_TRUE(row.pass) << renderer << ", " << example << ": " << row.metrics.max_excess;
      else EXPECT_FALSE(row.pass) << renderer << ", " << example << ", " << names[k] << ": " << row.metrics.max_excess;
    }
  }
}

TEST(Detection, GlslTextureConventionsFailWhenWrong) {
  expect_texture_faults_fail(
      "glsl", glsl_source,
      {{"v flipped", "vec2 x = uv * vec2(size);", "vec2 x = vec2(uv.x, 1.0 - uv.y) * vec2(size);", nullptr},
       {"bilinear half a texel off", "    x -= 0.5;\n", "\n", "textured_ggx"},
       {"nearest half a texel off", "int(floor(x.x)), int(floor(x.y))", "int(floor(x.x - 0.5)), int(floor(x.y - 0.5))",
        "textured_lambert"},
       {"sRGB not decoded", "return srgb ? facet_srgb_decode(c) : c;", "return c;", nullptr}});
}

TEST(Detection, WgpuTextureConventionsFailWhenWrong) {
  expect_texture_faults_fail(
      "wgpu", wgsl_gbuffer_shading_source,
      {{"v flipped", "let x = uv * vec2<f32>(size);", "let x = vec2<f32>(uv.x, 1.0 - uv.y) * vec2<f32>(size);", nullptr},
       {"bilinear half a texel off", "let corner = x - 0.5;", "let corner = x;", "textured_ggx"},
       {"nearest half a texel off", "i32(floor(x.x)), i32(floor(x.y))", "i32(floor(x.x - 0.5)), i32(floor(x.y - 0.5))",
        "textured_lambert"},
       {"sRGB not decoded", "return facet_srgb_decode(c);", "return c;", nullptr}});
}

// In OSL, Blender's v is taken for glTF's.
TEST(Detection, OslTextureConventionsFailWhenWrong) {
  const Scene shadows = load_scene("shadows");
  expect_texture_faults_fail(
      "osl", [&](const Material& m) { return osl_source(m, shadows); },
      {{"v flipped", "t0 = 1 - facet_uv0[1];", "t0 = facet_uv0[1];", nullptr},
       {"bilinear half a texel off", "    x -= 0.5;\n    y -= 0.5;\n", "", "textured_ggx"},
       {"nearest half a texel off", "(int)floor(x), (int)floor(y)", "(int)floor(x - 0.5), (int)floor(y - 0.5)",
        "textured_lambert"},
       {"sRGB not decoded", "return srgb ? facet_srgb_decode(c) : c;", "return c;", nullptr}});
}

TEST(Detection, PovMissingPiFails) {
  Fixture f = fixture("cook_torrance", "pov");
  GenerateOptions o;
  o.target = Target::Pov;
  o.scene = f.scene;
  std::string good = generate(f.material, o);
  f.job.code_override = good;
  EXPECT_TRUE(judged(f, render_one("pov", f.job)).pass);
  f.job.code_override = inject(good, "{ pi/4*D*G*F/NoV }", "{ 1/4*D*G*F/NoV }");
  ComparisonRow bad = judged(f, render_one("pov", f.job));
  EXPECT_FALSE(bad.pass) << "max |Δ|/max(1,|ref|) " << bad.metrics.max_excess;
}

// POV-Ray's scene language reads and writes files (#fopen, #read, #write, #include), and
// POV-Ray 3.7 enforces no povray.conf (renderers/process.h): facet confines it to its work
// folder. A scene that writes outside it, or reads a file outside it, fails to render and
// leaves nothing; the same scene writing inside the folder renders (so the confinement,
// not a broken scene, is what stops it).
TEST(Detection, PovCannotReadOrWriteOutsideItsFolder) {
  ASSERT_GT(landlock_abi(), 0) << "this kernel has no Landlock: POV-Ray would run unconfined";
  Fixture f = fixture("lambert", "pov");
  GenerateOptions o;
  o.target = Target::Pov;
  o.scene = f.scene;
  const std::string good = generate(f.material, o);
  const fs::path outside = test::scratch("detection", "outside");
  fs::create_directories(outside);
  const fs::path secret = outside / "secret.inc", pwned = outside / "PWNED.txt";
  write_file_atomic(secret.string(), "#declare Facet_Secret = 1;\n");
  auto writes = [&](const std::string& file) {
    return "#fopen Facet_F \"" + file + "\" write\n#write(Facet_F, \"pwned\\n\")\n#fclose Facet_F\n" + good;
  };
  f.job.code_override = writes("inside.txt");
  EXPECT_TRUE(judged(f, render_one("pov", f.job)).pass) << "writing inside its own folder must work";
  EXPECT_TRUE(fs::exists(fs::path(f.job.workdir) / "inside.txt"));
  f.job.code_override = writes(pwned.string());
  RenderOutcome wrote = render_one("pov", f.job);
  EXPECT_FALSE(wrote.ok);
  EXPECT_FALSE(fs::exists(pwned)) << "POV-Ray wrote outside its folder";
  f.job.code_override = "#include \"" + secret.string() + "\"\n" + good;
  RenderOutcome read = render_one("pov", f.job);
  EXPECT_FALSE(read.ok) << "POV-Ray read a file outside its folder";
  EXPECT_NE(read.error.find(secret.string()), std::string::npos) << read.error;
  fs::remove_all(outside);
}

TEST(Detection, PovExponentOffByOneFails) {
  Fixture f = fixture("blinn_phong", "pov");  // POV-Ray's own finish: roughness = 1/n
  GenerateOptions o;
  o.target = Target::Pov;
  o.scene = f.scene;
  f.job.code_override = inject(generate(f.material, o), "roughness 0.02", "roughness 0.0196078431372549");
  ComparisonRow bad = judged(f, render_one("pov", f.job));
  EXPECT_FALSE(bad.pass) << "max |Δ|/max(1,|ref|) " << bad.metrics.max_excess;
}

// The orthographic camera's conventions, as POV-Ray is given them: `up` and `right` as long
// as the view is high and wide (POV-Ray's orthographic camera takes their lengths as its
// extent), and v one direction against the view on the function route (a material POV-Ray
// has no finish for). A view half as high, or v towards the camera's position as a
// perspective camera's, fails; the generated scene passes.
TEST(Detection, PovOrthographicCameraFailsWhenWrong) {
  Fixture f = fixture("ward", "pov-orthographic", "materials", (kSource / "tests/scenes/orthographic.json").string());
  ASSERT_TRUE(f.scene.camera.orthographic);
  GenerateOptions o;
  o.target = Target::Pov;
  o.scene = f.scene;
  const std::string good = generate(f.material, o);
  f.job.code_override = good;
  ComparisonRow right = judged(f, render_one("pov", f.job));
  EXPECT_TRUE(right.pass) << "max |Δ|/max(1,|ref|) " << right.metrics.max_excess;
  f.job.code_override = inject(good, "up y*3.2", "up y*1.6");
  ComparisonRow half = judged(f, render_one("pov", f.job));
  EXPECT_FALSE(half.pass) << "a view half as high: max |Δ|/max(1,|ref|) " << half.metrics.max_excess;
  // The perspective camera's v (towards its position) under the orthographic camera.
  GenerateOptions p = o;
  p.scene->camera.orthographic = false;
  const std::string perspective = generate(f.material, p);
  const auto camera = [](const std::string& code) {
    const size_t at = code.find("camera {");
    return code.substr(at, code.find("}\n", at) + 2 - at);
  };
  f.job.code_override = inject(perspective, camera(perspective), camera(good));
  ComparisonRow towards = judged(f, render_one("pov", f.job));
  EXPECT_FALSE(towards.pass) << "v towards the eye: max |Δ|/max(1,|ref|) " << towards.metrics.max_excess;
}

// A scene of high dynamic range (tests/scenes/high_range.json: the brightest pixel 1,281
// times the 5th percentile of the lit ones): one 16-bit exposure, scaled to keep the
// brightest below 1, cannot hold its dim pixels to the tolerance and fails; with the
// comparison's tolerance given, POV-Ray brackets its exposures and passes, and says so.
TEST(Detection, PovHighRangeNeedsBracketedExposures) {
  Fixture f = fixture("lambert", "pov-high-range", "materials", (kSource / "tests/scenes/high_range.json").string());
  f.job.tolerance = 0;  // one exposure
  ComparisonRow one = judged(f, render_one("pov", f.job));
  EXPECT_FALSE(one.pass) << "one exposure: max |Δ|/max(1,|ref|) " << one.metrics.max_excess;
  f.job.tolerance = ValidateOptions{}.tolerance;
  RenderOutcome r = render_one("pov", f.job);
  ComparisonRow bracketed = judged(f, r);
  EXPECT_TRUE(bracketed.pass) << "bracketed: max |Δ|/max(1,|ref|) " << bracketed.metrics.max_excess;
  EXPECT_NE(r.note.find("exposures bracketed"), std::string::npos) << r.note;
}

// The mesh conventions docs/povray-meshes.md measured, each proved by a wrong
// variant that fails: POV-Ray puts an image's first row at the top (v = 1) and
// a texel's centre half a texel in, `interpolate 2` blends a block's texels
// linearly, and on the native route POV-Ray blends the vertex normals itself.
Fixture mesh_fixture(const std::string& example, const std::string& name) {
  Fixture f = fixture(example, "pov-mesh-" + name);
  f.scene = mesh_bench_scene(3000);
  f.reference = render_reference(f.material, f.scene, kSize, kSize);
  f.job.scene = f.scene;
  f.job.max_value = 0;
  for (float v : f.reference.image.rgb) f.job.max_value = std::max<double>(f.job.max_value, v);
  return f;
}

// Every occurrence of `from` in `code` replaced; the test fails if there is none.
std::string inject_all(std::string code, const std::string& from, const std::string& to) {
  size_t at = code.find(from);
  EXPECT_NE(at, std::string::npos) << "the code no longer contains: " << from;
  for (; at != std::string::npos; at = code.find(from, at + to.size())) code.replace(at, from.size(), to);
  return code;
}

TEST(Detection, PovMeshDataConventionsFailWhenWrong) {
  Fixture f = mesh_fixture("ggx", "data");
  // Named as the renderer names its files, so the code read back finds its data images.
  PovOutput pov = generate_pov_files(f.scene, &f.material, "ggx.json", PovRoute::Auto, job_name(f.job));
  ASSERT_EQ(pov.files.size(), 6u) << "three meshes on the function route: their lists and their data images";
  EXPECT_TRUE(judged(f, render_one("pov", f.job)).pass);
  // Mesh 0's lookups, as its data functions write them: "(U + 0.5)/W, (V + K*R + 0.5)/H".
  const size_t at = pov.code.find("Facet_Mesh0_Image((U + 0.5)/");
  ASSERT_NE(at, std::string::npos);
  const size_t v_at = pov.code.find("(V + ", at), v_end = pov.code.find(", 0)", v_at);
  const std::string v = pov.code.substr(v_at, v_end - v_at);  // "(V + K*R + 0.5)/H"
  struct Wrong {
    const char* what;
    std::string code;
  };
  const Wrong wrong[] = {
      {"rows counted from the top", inject_all(pov.code, ", " + v + ", 0)", ", 1 - " + v + ", 0)")},
      {"texel centres on integers", inject_all(pov.code, "Facet_Mesh0_Image((U + 0.5)/", "Facet_Mesh0_Image(U/")},
      {"no bilinear blend (nearest texel)", inject(pov.code, "gamma 1.0 interpolate 2", "gamma 1.0")},
  };
  for (const auto& w : wrong) {
    f.job.code_override = w.code;
    ComparisonRow bad = judged(f, render_one("pov", f.job));
    std::cout << w.what << ": max |Δ|/max(1,|ref|) " << bad.metrics.max_excess << "\n";
    EXPECT_FALSE(bad.pass) << w.what << ": max |Δ|/max(1,|ref|) " << bad.metrics.max_excess;
  }
}

// The same three faults in POV-Ray's texture functions (pov_texture.h): the file's rows
// counted from the bottom (POV-Ray's y up taken for glTF's v), lookups half a texel off,
// sRGB not decoded. And a measured convention made wrong: the texel read at the image's
// row J instead of J + 1, forgetting the row of zeros on top.
TEST(Detection, PovTextureConventionsFailWhenWrong) {
  for (const char* example : {"textured_lambert", "textured_ggx"}) {
    Fixture f = fixture(example, "pov", "textured", "shadows");
    // Named as the renderer names its files, so the code read back finds its images.
    PovOutput pov = generate_pov_files(f.scene, &f.material, example, PovRoute::Auto, job_name(f.job));
    f.job.code_override = pov.code;
    ComparisonRow right = judged(f, render_one("pov", f.job));
    EXPECT_TRUE(right.pass) << example << ": " << right.metrics.max_excess;
    const bool bilinear = std::string(example) == "textured_ggx";
    struct Wrong {
      const char* what;
      std::string code;
    };
    const Wrong wrong[] = {
        {"v flipped", inject_all(pov.code, ", 1 - (", ", (")},
        {"half a texel off", bilinear ? inject_all(pov.code, "*8 - 0.5", "*8")
                                      : inject_all(pov.code, "floor(S*8), floor(T*8)", "floor(S*8 - 0.5), floor(T*8 - 0.5)")},
        {"sRGB not decoded", inject_all(pov.code, "Facet_Srgb(Facet_Image", "(Facet_Image")},
        {"the row of zeros forgotten", inject_all(pov.code, " + 1.5)/", " + 0.5)/")},
    };
    for (const auto& w : wrong) {
      f.job.code_override = w.code;
      ComparisonRow bad = judged(f, render_one("pov", f.job));
      std::cout << example << ", " << w.what << ": " << bad.metrics.over << " pixels over, worst "
                << bad.metrics.max_excess << "\n";
      EXPECT_FALSE(bad.pass) << example << ", " << w.what << ": " << bad.metrics.max_excess;
    }
  }
}

// The benchmark's 32,196-triangle scene with Lambert + Ward: before the data images began
// with a row of zeros, its torus's began with the byte 13, which POV-Ray's PPM reader
// took for the end of the header's line ("Unexpected EOF in PPM file").
TEST(Detection, PovMeshDataImagesReadWhateverTheirFirstByte) {
  Fixture f = fixture("ward", "pov-mesh-first-byte");
  f.material = parse_material(nlohmann::json::parse(R"({"name": "anisotropic",
      "diffuse": {"model": "lambert", "color": [0.25, 0.25, 0.28]},
      "specular": {"model": "ward", "color": [0.8, 0.75, 0.7], "alpha_x": 0.12, "alpha_y": 0.35}})"),
                              "anisotropic.json");
  f.scene = mesh_bench_scene(32768);
  f.reference = render_reference(f.material, f.scene, kSize, kSize);
  f.job.material = f.material;
  f.job.scene = f.scene;
  f.job.max_value = 0;
  for (float v : f.reference.image.rgb) f.job.max_value = std::max<double>(f.job.max_value, v);
  RenderOutcome r = render_one("pov", f.job);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(judged(f, r).pass);
}

TEST(Detection, PovMeshNativeNormalsFailWhenFlat) {
  Fixture f = mesh_fixture("blinn_phong", "native");  // POV-Ray's own finish on mesh2
  PovOutput pov = generate_pov_files(f.scene, &f.material, "blinn_phong.json", PovRoute::Auto, job_name(f.job));
  ASSERT_TRUE(pov.plan.native);
  ASSERT_EQ(pov.files.size(), 3u) << "each mesh's lists, no data image";
  EXPECT_TRUE(judged(f, render_one("pov", f.job)).pass);
  // Without the first mesh's normal_vectors POV-Ray shades its triangles flat: the scene
  // declares Facet_Mesh0 again after its include file, the same mesh2 without them.
  const std::string include = "#include \"" + job_name(f.job) + "_mesh0.inc\"";
  size_t inc = pov.code.find(include);
  ASSERT_NE(inc, std::string::npos);
  const Mesh& m = *f.scene.objects[0].mesh;
  std::string flat = "#declare Facet_Mesh0 = mesh2 {\n  vertex_vectors {\n    " + std::to_string(m.positions.size());
  for (const auto& p : m.positions)
    flat += fmt::format(",\n    <{}, {}, {}>", float(p.x), float(p.y), float(p.z));
  flat += "\n  }\n  face_indices {\n    " + std::to_string(m.triangles.size());
  for (const auto& t : m.triangles)
    flat += fmt::format(",\n    <{}, {}, {}>", t[0], t[1], t[2]);
  flat += "\n  }\n}\n";
  std::string flat_code = pov.code;
  flat_code.insert(flat_code.find('\n', inc) + 1, flat);
  f.job.code_override = flat_code;
  ComparisonRow bad = judged(f, render_one("pov", f.job));
  EXPECT_FALSE(bad.pass) << "flat normals: max |Δ|/max(1,|ref|) " << bad.metrics.max_excess;
}

// Blender keeps a mesh's custom normals in 16 bits, and a sharp lobe shows it on a dense
// mesh: the generated shader reads the harness's float normals (its facet_normal input,
// templates/osl/shader.osl) and passes; the same shader on Cycles' N fails.
TEST(Detection, OslMeshOnBlendersNormalsFails) {
  Fixture f = fixture("ward", "osl-mesh-normals");  // Ward αx = 0.08
  f.scene = mesh_bench_scene(131072);
  const int w = 320, h = 240;
  f.reference = render_reference(f.material, f.scene, w, h);
  f.job.scene = f.scene;
  f.job.width = w, f.job.height = h;
  GenerateOptions o;
  o.target = Target::Osl;
  o.scene = f.scene;
  const std::string good = generate(f.material, o);
  std::vector<RenderJob> jobs = {f.job, f.job};
  jobs[0].code_override = good;
  jobs[1].code_override = inject(
      good, "facet_normal != 0 ? normalize(facet_normal) : (backfacing() ? -normalize(N) : normalize(N))", "normalize(N)");
  jobs[1].material->name = "ward_on_blenders_normals";
  std::vector<RenderOutcome> r = make_renderer("osl")->render(jobs);
  ASSERT_EQ(r.size(), 2u);
  ComparisonRow ok = judged(f, r[0]), bad = judged(f, r[1]);
  std::cout << "float normals: " << ok.metrics.max_excess << ", Blender's 16-bit normals: " << bad.metrics.max_excess
            << "\n";
  EXPECT_TRUE(ok.pass) << "max |Δ|/max(1,|ref|) " << ok.metrics.max_excess;
  EXPECT_FALSE(bad.pass) << "max |Δ|/max(1,|ref|) " << bad.metrics.max_excess;
}

// ---------------------------------------------------------------- cut-outs

// A cut-out (glTF's alphaMode MASK: the leaf's alpha, bilinear, repeated 3 × 2, cutoff 0.5) on
// every object of the shadows scene: the sphere's holes show its far side and the floor, and
// the cut-out occluder and sphere cast cut-out shadows. Its colour is a number, so that Cycles
// reads no image's colour (which a code override would read premultiplied: cycles.cpp).
Fixture cutout_fixture(const std::string& renderer) {
  Fixture f = fixture("lambert", renderer, "materials", "shadows");
  const std::string leaf = (kSource / "examples/textured/textures/leaf.png").string();
  allow_folder((kSource / "examples").string());  // as --allow-path: the image is outside the file's folder
  f.material = parse_material(
      {{"name", "cutout"},
       {"diffuse", {{"model", "lambert"}, {"color", {0.55, 0.7, 0.3}}}},
       {"specular", {{"model", "blinn_phong"}, {"color", 0.2}, {"n", 40}}},
       {"alpha", {{"texture", leaf}, {"channel", "a"}, {"filter", "bilinear"}, {"transform", {{"scale", {3, 2}}}}}},
       {"alpha_cutoff", 0.5}},
      "cutout.json");
  f.reference = render_reference(f.material, f.scene, kSize, kSize);
  f.job.material = f.material;
  return f;
}

struct WrongCutout {
  const char* what;
  std::string code;
};

// Each wrong variant fails the judgement the right code passes.
void expect_cutout_faults_fail(const Fixture& f, const std::string& renderer, const std::string& good,
                               const std::vector<WrongCutout>& wrongs) {
  std::vector<RenderJob> jobs = {f.job};
  jobs[0].code_override = good;
  for (const auto& w : wrongs) {
    jobs.push_back(f.job);
    jobs.back().code_override = w.code;
    jobs.back().material->name = fmt::format("cutout_wrong_{}", jobs.size());
  }
  std::vector<RenderOutcome> out = make_renderer(renderer)->render(jobs);
  ASSERT_EQ(out.size(), jobs.size());
  for (size_t k = 0; k < out.size(); ++k) {
    ComparisonRow row = judged(f, out[k]);
    std::cout << renderer << ", " << (k ? wrongs[k - 1].what : "right") << ": " << row.metrics.over
              << " pixels over, worst " << row.metrics.max_excess << ", coverage differs on "
              << 100 * row.coverage_mismatch << " %\n";
    if (k == 0) EXPECT_TRUE(row.pass) << renderer << ": " << row.metrics.max_excess;
    else EXPECT_FALSE(row.pass) << renderer << ", " << wrongs[k - 1].what;
  }
}

TEST(Detection, OslCutoutFailsWhenWrong) {
  Fixture f = cutout_fixture("osl-cutout");
  const std::string good = osl_source(f.material, f.scene);
  expect_cutout_faults_fail(
      f, "osl", good,
      {{"the cutoff compared the wrong way", inject(good, "if (!(facet_alpha0(s0, t0, s1, t1) >= 0.5))",
                                                    "if (!(facet_alpha0(s0, t0, s1, t1) < 0.5))")},
       {"shadows that ignore the cut-out", inject(good, "if (facet_kept_hit(L, start + t, d)) return 1;", "return 1;")},
       {"a sphere's far side past its holes ignored",
        inject(good, "if (!facet_far_side(Pt, Nn, s0, t0, s1, t1, uv_tangent, uv_handedness, shadow_from))", "if (1)")},
       {"a sphere's far side ignored by shadow rays", inject(good, "if (along + through >= d) return 0;", "return 0;")}});
}

TEST(Detection, PovCutoutFailsWhenWrong) {
  Fixture f = cutout_fixture("pov-cutout");
  const std::string good = generate_pov_files(f.scene, &f.material, "cutout", PovRoute::Auto, job_name(f.job)).code;
  expect_cutout_faults_fail(
      f, "pov", good,
      {{"the cutoff compared the wrong way", inject(good, "select(Facet_Sample_alpha(S0, T0) - 0.5, 0, 1)",
                                                    "select(Facet_Sample_alpha(S0, T0) - 0.5, 1, 0)")},
       {"cut-outs that cast no shadow", inject_all(good, "  texture {\n", "  no_shadow\n  texture {\n")},
       {"holes that block shadow rays (transmit 0.5)", inject_all(good, "[0 rgbt <0, 0, 0, 1>]", "[0 rgbt <0, 0, 0, 0.5>]")}});
}

// ---------------------------------------------------------------- POV-Ray in one run

// The generated scene rendered as a user renders it, every light at once
// through light_group copies (Facet_Light = -1), agrees with the reference but
// for the few pixels on the shadow edge that the copies' inset moves (≤ 0.2 %).
// (Weights that forgot the outer copies' transmittance, or a colour scale that
// also scaled transmit, put most pixels off.)
TEST(PovOneRun, AgreesButOnShadowEdges) {
  Fixture f = fixture("oren_nayar", "pov-one-run");
  f.scene = load_scene("shadows");
  f.reference = render_reference(f.material, f.scene, kSize, kSize);
  f.job.scene = f.scene;
  f.job.max_value = 0;
  for (float v : f.reference.image.rgb) f.job.max_value = std::max<double>(f.job.max_value, v);
  f.job.one_run = true;
  RenderOutcome r = render_one("pov", f.job);
  ASSERT_TRUE(r.ok) << r.error;
  Metrics m = compare_images(f.reference, r.image, interior_mask(f.reference), 2e-3);
  EXPECT_GT(m.pixels, 1000u);
  EXPECT_LE(double(m.over), 0.002 * double(m.pixels))
      << m.over << " of " << m.pixels << " pixels over 2e-3; max |Δ| " << m.max_abs << ", rmse " << m.rmse;
}

// ---------------------------------------------------------------- the sweeps

// The sweep reaches every hard place of targets/sweep_grid.h, on the grid alone and on
// the random sets alone: a function that goes negative only there is caught.
TEST(SweepDetection, ReachesEveryHardPlace) {
  const Vec3 axis(0, 1, 0);
  struct Place {
    const char* name;
    std::function<bool(const Vec3&, const Vec3&, const Vec3&)> at;
    bool grid_only = false;  // exact values: the grid's business
  };
  std::vector<Place> places = {
      {"n·l = 0 exactly", [](const Vec3& n, const Vec3& l, const Vec3&) { return dot(n, l) == 0; }, true},
      {"n·v = 0 exactly", [](const Vec3& n, const Vec3&, const Vec3& v) { return dot(n, v) == 0; }, true},
      {"0 < n·l ≤ 1e-6", [](const Vec3& n, const Vec3& l, const Vec3&) { return dot(n, l) > 0 && dot(n, l) <= 1e-6; }},
      {"0 < n·v ≤ 1e-6", [](const Vec3& n, const Vec3&, const Vec3& v) { return dot(n, v) > 0 && dot(n, v) <= 1e-6; }},
      {"light below the horizon", [](const Vec3& n, const Vec3& l, const Vec3&) { return dot(n, l) < 0; }},
      {"viewer below the horizon", [](const Vec3& n, const Vec3&, const Vec3& v) { return dot(n, v) < 0; }},
      {"l = v", [](const Vec3&, const Vec3& l, const Vec3& v) { return length(l - v) < 1e-6; }},
      {"h ∥ n", [](const Vec3& n, const Vec3& l, const Vec3& v) {
         return dot(n, l) > 0.1 && 1 - dot(n, normalize(l + v)) < 1e-12;
       }},
      {"l = −v grazing", [](const Vec3& n, const Vec3& l, const Vec3& v) {
         return dot(l, v) < -1 + 1e-9 && std::fabs(dot(n, l)) < 1e-6;
       }},
      {"n ∥ tangent axis", [&](const Vec3& n, const Vec3&, const Vec3&) { return length(cross(axis, n)) < 1e-4; }},
  };
  for (const auto& p : places) {
    for (auto [grid, random] : {std::pair{256, size_t(0)}, std::pair{0, size_t(200000)}}) {
      if (p.grid_only && grid == 0) continue;
      SweepCount c = sweep_directions(grid, random, axis, [&](const Vec3& n, const Vec3& l, const Vec3& v, const Vec3&) {
        return p.at(n, l, v) ? RGB{-1, 0, 0} : RGB{0, 0, 0};
      });
      EXPECT_GT(c.negative, 0u) << p.name << (grid ? " on the grid" : " in the random sets");
      EXPECT_FALSE(c.ok());
    }
  }
  // And the counting itself: NaN, Inf and negative land in their own columns.
  SweepCount c = sweep_directions(16, 0, axis, [](const Vec3&, const Vec3&, const Vec3&, const Vec3&) {
    return RGB{std::nan(""), HUGE_VAL, -1e-300};
  });
  EXPECT_EQ(c.samples, 256u);
  EXPECT_EQ(c.nan, 256u);
  EXPECT_EQ(c.inf, 256u);
  EXPECT_EQ(c.negative, 256u);
}

// On the targets, a harness with a fault at the horizon (n·l = 0 exactly) is
// caught on exactly the grid cells the C++ side puts there.
size_t horizon_cells(int grid) {
  size_t k = 0;
  for (const auto& s : sweep_grid_sets(grid)) k += dot(s[0], s[1]) == 0;
  return k;
}

const int kSweepGrid = 256;

Material sweep_material() { return load_material((kSource / "examples/materials/lambert.json").string()); }

// The right harness and one with a fault at the horizon, in one sweep() call of the
// registry's `renderer`: the right one is clean, and the wrong one's counts come back.
SweepCount horizon_fault(const std::string& renderer, const std::string& bad_code) {
  std::unique_ptr<Renderer> r = make_renderer(renderer);
  EXPECT_EQ(r->unavailable(), "") << renderer;
  const Material m = sweep_material();
  Material faulty = m;
  faulty.name = m.name + "_with_a_fault";
  const std::string workdir = test::scratch("detection", renderer + "-sweep").string();
  std::vector<SweepCount> c = r->sweep({{m, ""}, {faulty, bad_code}}, {kSweepGrid, 0, workdir});
  EXPECT_EQ(c.size(), 2u) << renderer;
  EXPECT_TRUE(c.at(0).ok()) << renderer << ": " << c.at(0).error;
  EXPECT_TRUE(c.at(1).error.empty()) << renderer << ": " << c.at(1).error;
  EXPECT_EQ(c.at(1).samples, size_t(kSweepGrid) * kSweepGrid) << renderer;
  EXPECT_GT(horizon_cells(kSweepGrid), 0u);
  return c.at(1);
}

// The fault in the C-family harnesses: red −1 and green NaN where n·l is exactly 0.
std::string glsl_horizon_fault(const Material& m, Target dialect) {
  return inject(glsl_sweep_source(m, dialect), "facet_color = vec4(facet_reflect(n, l, v, facet_tangent(n)), 1.0);",
                "facet_color = vec4(facet_reflect(n, l, v, facet_tangent(n)), 1.0);\n"
                "    float z = dot(n, l);\n"
                "    if (z == 0.0) facet_color.r = -1.0;\n"
                "    facet_color.g += z / z - 1.0;  // NaN at z = 0\n");
}

// The same fault in GLSL 3.30 on OpenGL, GLSL 4.50 on Vulkan and ES 3.00 in Chromium's WebGL2.
TEST(SweepDetection, GlslFaultAtTheHorizonIsCounted) {
  for (auto [name, dialect] :
       {std::pair{"glsl", Target::Glsl}, std::pair{"vulkan", Target::Glsl450}, std::pair{"webgl", Target::Essl}}) {
    SweepCount c = horizon_fault(name, glsl_horizon_fault(sweep_material(), dialect));
    EXPECT_EQ(c.negative, horizon_cells(kSweepGrid)) << name;
    EXPECT_EQ(c.nan, horizon_cells(kSweepGrid)) << name;
  }
}

// HLSL's sweep (a pixel shader) on Vulkan.
TEST(SweepDetection, HlslFaultAtTheHorizonIsCounted) {
  SweepCount c = horizon_fault(
      "vulkan-hlsl", inject(hlsl_sweep_source(sweep_material()), "return float4(facet_reflect(n, l, v, facet_tangent(n)), 1.0);",
                            "float4 c = float4(facet_reflect(n, l, v, facet_tangent(n)), 1.0);\n"
                            "    float z = dot(n, l);\n"
                            "    if (z == 0.0) c.r = -1.0;\n"
                            "    c.g += z / z - 1.0;  // NaN at z = 0\n"
                            "    return c;"));
  EXPECT_EQ(c.negative, horizon_cells(kSweepGrid));
  EXPECT_EQ(c.nan, horizon_cells(kSweepGrid));
}

TEST(SweepDetection, WgpuFaultAtTheHorizonIsCounted) {
  SweepCount c = horizon_fault(
      "wgpu", inject(wgsl_sweep_source(sweep_material()), "    return vec4<f32>(facet_reflect(n, l, v, facet_tangent(n)), 1.0);\n",
                     "    var c = vec4<f32>(facet_reflect(n, l, v, facet_tangent(n)), 1.0);\n"
                     "    let z = dot(n, l);\n"
                     "    if (z == 0.0) {\n        c.r = -1.0;\n    }\n"
                     "    c.g += z / z - 1.0;  // NaN at z = 0\n"
                     "    return c;\n"));
  EXPECT_EQ(c.negative, horizon_cells(kSweepGrid));
  EXPECT_EQ(c.nan, horizon_cells(kSweepGrid));
}

TEST(SweepDetection, OslFaultAtTheHorizonIsCounted) {
  SweepCount c = horizon_fault(
      "osl", inject(osl_sweep_source(sweep_material()), "    color bad = 0;\n",
                    "    if (dot(Nn, L) == 0) { r[0] = -1; r[1] = 1e38 * (10 + r[1]); }\n    color bad = 0;\n"));
  EXPECT_EQ(c.negative, horizon_cells(kSweepGrid));
  EXPECT_EQ(c.inf, horizon_cells(kSweepGrid));
}

TEST(SweepDetection, PovFaultAtTheHorizonIsCounted) {
  const std::string nl = "Sweep_n_x(x, y) * Sweep_l_x(x, y) + Sweep_n_y(x, y) * Sweep_l_y(x, y) + "
                         "Sweep_n_z(x, y) * Sweep_l_z(x, y)";
  SweepCount c = horizon_fault("pov", inject(generate_pov_sweep(sweep_material()), "[1 function { Facet_Ok(Facet_Reflect",
                                             "[1 function { Facet_Ok(select(" + nl + ", 0, -1, 0) + Facet_Reflect"));
  EXPECT_EQ(c.nan, horizon_cells(kSweepGrid));  // POV-Ray counts every bad channel as NaN
}

// A fault injected into generated code, `from` → `to` (once, or everywhere: see check_wrongs).
struct Wrong {
  const char* what;
  std::string from, to;
};

// `w` made in `code` at its first place (once) or at every place (all).
std::string once(const std::string& code, const Wrong& w) { return inject(code, w.from, w.to); }
std::string all(const std::string& code, const Wrong& w) { return inject_all(code, w.from, w.to); }

// Example `example` of examples/`folder` on `scene` through `renderer`: the generated code
// `good` passes and each of `wrongs`, made by `make` from it, fails.
void check_wrongs(const std::string& example, const std::string& folder, const std::string& scene,
                  const std::string& renderer, const std::string& good, const std::vector<Wrong>& wrongs,
                  const std::function<std::string(const std::string&, const Wrong&)>& make) {
  Fixture f = fixture(example, renderer, folder, scene);
  std::vector<RenderJob> jobs = {f.job};
  jobs[0].code_override = good;
  for (const auto& w : wrongs) {
    jobs.push_back(f.job);
    jobs.back().code_override = make(good, w);
  }
  // One batch (one Blender process) where jobs have their own names; POV-Ray's code reads
  // images named after its job, so there each job is rendered alone under the same name.
  std::vector<RenderOutcome> r;
  if (renderer == "pov") {
    for (const auto& j : jobs) r.push_back(render_one(renderer, j));
  } else {
    for (size_t k = 1; k < jobs.size(); ++k) jobs[k].material->name = fmt::format("{}_wrong_{}", example, k);
    r = make_renderer(renderer)->render(jobs);
  }
  ASSERT_EQ(r.size(), jobs.size());
  for (size_t k = 0; k < r.size(); ++k) {
    ComparisonRow row = judged(f, r[k]);
    const char* what = k == 0 ? "right" : wrongs[k - 1].what;
    std::cout << renderer << ", " << what << ": " << row.metrics.over << " pixels over, worst "
              << row.metrics.max_excess << "\n";
    if (k == 0) EXPECT_TRUE(row.pass) << renderer << ": " << row.metrics.max_excess;
    else EXPECT_FALSE(row.pass) << renderer << ", " << what << ": " << row.metrics.max_excess;
  }
}

// One route's wrongs and how they are made (once, or all).
struct RouteWrongs {
  std::vector<Wrong> wrongs;
  std::function<std::string(const std::string&, const Wrong&)> make;
};

// Example `example` of examples/textured on `scene` through the GLSL, OSL and POV-Ray routes:
// each route's generated code passes and each of its wrongs fails (check_wrongs). POV-Ray's
// code is generated under the job's file names: the renderer reads the images beside it.
void check_routes(const std::string& example, const std::string& scene, const RouteWrongs& glsl,
                  const RouteWrongs& osl, const RouteWrongs& pov) {
  Fixture f = fixture(example, "glsl", "textured", scene);
  check_wrongs(example, "textured", scene, "glsl", GlRenderer::fragment_source(f.material), glsl.wrongs, glsl.make);
  GenerateOptions o;
  o.target = Target::Osl;
  o.scene = f.scene;
  check_wrongs(example, "textured", scene, "osl", generate(f.material, o), osl.wrongs, osl.make);
  Fixture p = fixture(example, "pov", "textured", scene);
  PovOutput code = generate_pov_files(p.scene, &p.material, example, PovRoute::Auto, job_name(p.job));
  check_wrongs(example, "textured", scene, "pov", code.code, pov.wrongs, pov.make);
}

// Ambient and emission maps (docs/textures.md): each image dropped — its factor taken for
// the colour — fails on every renderer, while the generated code passes. One material,
// examples/textured/textured_emission.json, on the shadows scene.
TEST(Detection, EmissionAndAmbientMapsFailWhenDropped) {
  const char *emission = "emission map dropped", *ambient = "ambient map dropped";
  check_routes("textured_emission", "shadows",
               {{{emission, "    material_emission = ", "    material_emission = vec3(0.6, 0.4, 0.3) + 0.0 * "},
                 {ambient, "    material_ambient = ", "    material_ambient = vec3(4.0) + 0.0 * "}},
                once},
               {{{emission, "color material_emission = ", "color material_emission = color(0.6, 0.4, 0.3) + 0 * "},
                 {ambient, "color material_ambient = ", "color material_ambient = color(4.0) + 0 * "}},
                once},
               {{{emission, "+ Facet_Sample_material_emission_R(S0, T0)", "+ 0.6"},
                 {ambient, "Facet_Sample_material_ambient(S0, T0)*", "4*"}},
                all});
}

// The emission under the clear coat (KHR_materials_clearcoat, "Emission": emission ·
// (1 − clearcoat · Fc(n·v))): left undimmed, or dimmed by the textured coat's factor alone (its
// texel not read), it fails on the GLSL, OSL and POV-Ray routes, while the generated code passes.
// examples/textured/textured_emissive_coat.json (a checker emission under a coat from an image,
// over a normal map) on the single scene.
TEST(Detection, EmissionUnderTheCoatFailsUndimmedOrWithoutItsTexel) {
  check_routes("textured_emissive_coat", "single",
               {{{"undimmed", "material_emission * emission_weight(", "material_emission + 0.0 * emission_weight("},
                 {"the coat's factor alone", "emission_weight(dot(n, v), specular_clearcoat)",
                  "emission_weight(dot(n, v), 0.9)"}},
                once},
               {{{"undimmed", "material_emission * emission_weight(", "material_emission + 0 * emission_weight("},
                 {"the coat's factor alone", "emission_weight(dot(Nn, V), specular_clearcoat",
                  "emission_weight(dot(Nn, V), 0.9"}},
                once},
               // The emission function calls the weight once for each channel; it is declared once.
               {{{"undimmed", "*Emission_weight(", " + 0*Emission_weight("},
                 {"the coat's factor alone", "{ Emission_weight__1(Specular_clearcoat,", "{ Emission_weight__1(0.9,"}},
                all});
}

// Layers a material file writes over classic lobes (examples/textured/textured_layers.json: a
// sheen with its colour and roughness from images, then a clear coat whose weight is an image's
// blue, over Oren–Nayar and Phong, on the coat's own normal map): the sheen without its albedo
// scaling of what lies under it (KHR_materials_sheen, "Albedo-scaling technique"), and the coat's
// weight taken as its factor (its texel not read), each fail on the GLSL, OSL and POV-Ray routes,
// while the generated code passes.
TEST(Detection, LayersFailWithoutTheSheensScalingOrTheCoatsTexel) {
  const char *unscaled = "what lies under the sheen unscaled", *factor = "the coat's weight its factor alone";
  check_routes("textured_layers", "single",
               {{{unscaled, "+ base * sheen_scaling;", "+ base;"},
                 {factor, "layer1_weight * coat_fresnel);", "1.0 * coat_fresnel);"}},
                once},
               {{{unscaled, "+ base * sheen_scaling;", "+ base;"},
                 {factor, "layer1_weight * coat_fresnel);", "1.0 * coat_fresnel);"}},
                once},
               {{{unscaled, "+ Base*Sheen_scaling", "+ Base"}, {factor, "Layer1_weight*Coat_fresnel)", "1*Coat_fresnel)"}},
                all});
}

// The clear coat over a normal-mapped base (KHR_materials_clearcoat: "no normal mapping is
// applied to the clear coat layer, even if normal mapping is applied to the base material"): the
// coat shaded on the base's mapped normal (facet before the coat's own normal) fails on the
// GLSL, OSL and POV-Ray routes, while the generated code passes. The same example, whose coat
// lies over a normal map.
TEST(Detection, CoatOnTheBasesNormalMapFails) {
  const char* what = "the coat on the mapped normal";
  check_routes("textured_emissive_coat", "single",
               {{{what, "facet_reflect(ns, l, v, t, n)", "facet_reflect(ns, l, v, t, ns)"}}, once},
               {{{what, "facet_reflect(Ns, L, V, T, Nn", "facet_reflect(Ns, L, V, T, Ns"}}, all},
               // The sphere's light functions take the mapped normal Q/Ql, then the coat's: its own, (x, y, z)/R.
               {{{what, "Qz/Ql, x/R, y/R, z/R, S0", "Qz/Ql, Qx/Ql, Qy/Ql, Qz/Ql, S0"}}, all});
}

// The clear coat's own normal map (KHR_materials_clearcoat's clearcoatNormalTexture; facet's
// coat_normal_map): ignored (the coat on the surface's own normal) or with its green channel
// flipped, it fails on the GLSL, OSL and POV-Ray routes, while the generated code passes.
// examples/textured/textured_coat_normal.json (a coat normal map over an unmapped base).
TEST(Detection, CoatNormalMapFailsIgnoredOrFlipped) {
  const char *ignored = "the coat's map ignored", *flipped = "the coat's green flipped";
  check_routes("textured_coat_normal", "single",
               {{{ignored, "vec3 nc = facet_coat_normal_mapped(n, facet_uv_tangent, facet_uv_handedness);", "vec3 nc = n;"},
                 {flipped, "0.6 * c.y", "-0.6 * c.y"}},
                once},
               {{{ignored, "vector Nc = normalize(cm_t[0] * Tu + cm_t[1] * Bu + cm_t[2] * Nn);", "vector Nc = Nn;"},
                 {flipped, "0.6 * cm_c[1]", "-0.6 * cm_c[1]"}},
                once},
               // The sphere's light functions take its own normal (x, y, z)/R, then the coat's mapped one ZQ/ZQl.
               {{{ignored, "z/R, ZQx/ZQl, ZQy/ZQl, ZQz/ZQl, S0", "z/R, x/R, y/R, z/R, S0"},
                 {flipped, "0.6*(2*Facet_Sample_coat_normal_map_g", "-0.6*(2*Facet_Sample_coat_normal_map_g"}},
                all});
}

// KHR_materials_anisotropy's direction from the mesh's tangent frame and its texture
// (examples/textured/textured_anisotropy.json: direction and strength from an image, turned by
// anisotropyRotation) on a mesh whose own TANGENTs are mirrored (w = −1,
// tests/scenes/textured_mesh_tangents.json): the bitangent taken as n × t without the frame's
// handedness (B = w·(N × T)), the tangent rule on tangent_axis for the mesh's tangent, and the
// texture's direction left out each fail on the GLSL, OSL and POV-Ray routes, while the
// generated code passes.
TEST(Detection, AnisotropyFailsOffTheMeshFrameOrWithoutItsTexture) {
  const char *handedness = "the frame's handedness ignored", *rule = "the tangent rule for the mesh's tangent",
             *direction = "the texture's direction left out";
  const std::string scene = (kSource / "tests" / "scenes" / "textured_mesh_tangents.json").string();
  check_routes("textured_anisotropy", scene,
               {{{handedness, "vec3 b = facet_uv_handedness * cross(n, t);", "vec3 b = cross(n, t);"},
                 {rule, "t = normalize(facet_uv_tangent - ns * dot(ns, facet_uv_tangent));", ""},
                 {direction, "float direction_unit_y = direction_y / direction_length;",
                  "float direction_unit_y = 0.0;"}},
                once},
               {{{handedness, "vector B = W * cross(Nn, T);", "vector B = cross(Nn, T);"},
                 {rule, "T = normalize(Tu - Nn * dot(Nn, Tu));", ""},
                 {direction, "float direction_unit_y = direction_y / direction_length;",
                  "float direction_unit_y = 0;"}},
                once},
               {{{handedness, "*Tw)", ")"},
                 {direction, "Facet_Sample_specular_anisotropy_direction_y(S0, T0)", "0.5"}},
                all});
}

// max₃ of a textured colour (KHR_materials_specular's specularColorTexture: max₃(F) weights the
// base; KHR_materials_sheen's sheenColorTexture: max₃(sheenColor) scales the layers under the
// sheen), derived from the sampled colour on every target (TexturedInput::max_of), and the sheen's
// roughness from sheenRoughnessTexture (its D, V and E at every pixel: gltf_sheen's
// sheen_per_pixel): each taken as its factor instead, as facet did with values of numbers, fails
// on the GLSL, OSL and POV-Ray routes, while the generated code passes.
// examples/textured/textured_specular_sheen.json.
TEST(Detection, SpecularAndSheenImagesFailAsTheirFactors) {
  const char *specular = "max(specular_color) as its factor's", *sheen = "max(sheen_color) as its factor's",
             *roughness = "sheen_roughness as its factor";
  const std::string sheen_r = "float sheen_r = clamp(specular_sheen_roughness,";
  check_routes("textured_specular_sheen", "single",
               {{{specular, "specular_specular_color_max = max(max(specular_specular_color.x, specular_specular_color.y), "
                            "specular_specular_color.z);",
                  "specular_specular_color_max = 1.6;"},
                 {sheen, "specular_sheen_color_max = max(max(specular_sheen_color.x, specular_sheen_color.y), "
                         "specular_sheen_color.z);",
                  "specular_sheen_color_max = 0.9;"},
                 {roughness, sheen_r, "float sheen_r = clamp(0.9,"}},
                once},
               {{{specular, "float specular_specular_color_max = max(max(specular_specular_color[0], "
                            "specular_specular_color[1]), specular_specular_color[2]);",
                  "float specular_specular_color_max = 1.6;"},
                 {sheen, "float specular_sheen_color_max = max(max(specular_sheen_color[0], specular_sheen_color[1]), "
                         "specular_sheen_color[2]);",
                  "float specular_sheen_color_max = 0.9;"},
                 {roughness, sheen_r, "float sheen_r = clamp(0.9,"}},
                once},
               {{{specular, "Facet_Sample_specular_specular_color_max(S0, T0)", "1.6"},
                 {sheen, "Facet_Sample_specular_sheen_color_max(S0, T0)", "0.9"},
                 {roughness, "Facet_Sample_specular_sheen_roughness(S0, T0)", "0.9"}},
                all});
}

// Normal maps (docs/textures.md, "Normal maps"): the example's map with its green channel
// flipped (DirectX's convention taken for OpenGL's), the map ignored (the lobes on the
// object's own normal) and the tangent reversed each fail on the sphere and the square of
// the shadows scene; the generated code passes. One test per renderer.
const char* const kNormalExample = "textured_normal_cook_torrance";

TEST(Detection, GlslNormalMapFailsWhenWrong) {
  GlRenderer gl;
  ASSERT_TRUE(gl.ok()) << gl.error();
  Fixture f = fixture(kNormalExample, "glsl", "textured", "shadows");
  const std::string good = GlRenderer::fragment_source(f.material);
  f.job.code_override = good;
  ComparisonRow right = judged(f, gl.render(f.job));
  EXPECT_TRUE(right.pass) << right.metrics.max_excess;
  const std::pair<const char*, std::string> wrongs[] = {
      {"green flipped", inject(good, "0.8 * c.y", "-0.8 * c.y")},
      {"map ignored", inject(good, "vec3 ns = facet_normal_mapped(n, facet_uv_tangent, facet_uv_handedness);", "vec3 ns = n;")},
      {"tangent reversed", inject(good, "facet_uv_tangent = frame.xyz;", "facet_uv_tangent = -frame.xyz;")},
  };
  for (const auto& [what, code] : wrongs) {
    f.job.code_override = code;
    ComparisonRow bad = judged(f, gl.render(f.job));
    std::cout << what << ": " << bad.metrics.over << " pixels over, worst " << bad.metrics.max_excess << "\n";
    EXPECT_FALSE(bad.pass) << what << ": " << bad.metrics.max_excess;
  }
}

// On a mesh the normal map's frame comes from the mesh's corner tangents (scene/tangents.h),
// which GLSL's BVH carries: the handedness w read the wrong way round (B = −w·(n × T)) fails
// on the bent sheet of tests/scenes/textured_mesh.json, the generated code passes.
TEST(Detection, GlslMeshTangentHandednessFailsWhenWrong) {
  GlRenderer gl;
  ASSERT_TRUE(gl.ok()) << gl.error();
  Fixture f = fixture(kNormalExample, "glsl-mesh", "textured", (kSource / "tests/scenes/textured_mesh.json").string());
  const std::string good = GlRenderer::fragment_source(f.material);
  f.job.code_override = good;
  ComparisonRow right = judged(f, gl.render(f.job));
  EXPECT_TRUE(right.pass) << right.metrics.max_excess;
  f.job.code_override = inject(good, "return vec4(c.xyz, c.w >= 0.0 ? 1.0 : -1.0);", "return vec4(c.xyz, c.w >= 0.0 ? -1.0 : 1.0);");
  ComparisonRow bad = judged(f, gl.render(f.job));
  std::cout << "mesh handedness flipped: " << bad.metrics.over << " pixels over, worst " << bad.metrics.max_excess << "\n";
  EXPECT_FALSE(bad.pass) << bad.metrics.max_excess;
}

// A mesh's own tangents reach every renderer's normal map: on
// tests/scenes/textured_mesh_tangents.json, whose sheet brings a mirrored frame (w = −1 at
// every vertex), each renderer with the mesh's w taken as +1 fails and the generated code
// passes (the sphere beside it has w = +1 either way).
TEST(Detection, MeshTangentsHandednessReachesEveryRenderer) {
  const std::string scene = (kSource / "tests/scenes/textured_mesh_tangents.json").string();
  {
    GlRenderer gl;
    ASSERT_TRUE(gl.ok()) << gl.error();
    Fixture f = fixture(kNormalExample, "glsl-own-tangents", "textured", scene);
    const std::string good = GlRenderer::fragment_source(f.material);
    f.job.code_override = good;
    EXPECT_TRUE(judged(f, gl.render(f.job)).pass);
    f.job.code_override = inject(good, "return vec4(c.xyz, c.w >= 0.0 ? 1.0 : -1.0);", "return vec4(c.xyz, 1.0);");
    ComparisonRow bad = judged(f, gl.render(f.job));
    std::cout << "GLSL, the mesh's w taken as +1: " << bad.metrics.over << " pixels over, worst " << bad.metrics.max_excess << "\n";
    EXPECT_FALSE(bad.pass);
  }
  {
    Fixture f = fixture(kNormalExample, "osl-own-tangents", "textured", scene);
    GenerateOptions o;
    o.target = Target::Osl;
    o.scene = f.scene;
    const std::string good = generate(f.material, o);
    std::vector<RenderJob> jobs(2, f.job);
    jobs[0].code_override = good;
    jobs[1].code_override = inject(good, "vector Bu = uv_handedness * cross(Nn, Tu);", "vector Bu = cross(Nn, Tu);");
    jobs[1].material->name += "_w_ignored";
    std::vector<RenderOutcome> r = make_renderer("osl")->render(jobs);
    ASSERT_EQ(r.size(), 2u);
    EXPECT_TRUE(judged(f, r[0]).pass);
    ComparisonRow bad = judged(f, r[1]);
    std::cout << "OSL, the mesh's w taken as +1: " << bad.metrics.over << " pixels over, worst " << bad.metrics.max_excess << "\n";
    EXPECT_FALSE(bad.pass);
  }
  {
    Fixture f = fixture(kNormalExample, "pov-own-tangents", "textured", scene);
    PovOutput pov = generate_pov_files(f.scene, &f.material, kNormalExample, PovRoute::Auto, job_name(f.job));
    f.job.code_override = pov.code;
    EXPECT_TRUE(judged(f, render_one("pov", f.job)).pass);
    f.job.code_override = inject_all(pov.code, "select(Facet_Mesh0_UW(x, y), -1, 1)", "1");
    ComparisonRow bad = judged(f, render_one("pov", f.job));
    std::cout << "POV-Ray, the mesh's w taken as +1: " << bad.metrics.over << " pixels over, worst " << bad.metrics.max_excess << "\n";
    EXPECT_FALSE(bad.pass);
  }
}

// POV-Ray lights a flat triangle that faces the light a little past the smooth normal's
// terminator, where the mapped normal n′ may still face it; the object functions of a
// normal-mapped mesh keep the reference's rule (the smooth normal decides) with a
// select(N·L, 0, 0, 1). On examples/scenes/textured.json (the normal-mapped sphere mesh) POV-Ray
// with every such select lit fails, the generated scene passes.
TEST(Detection, PovNormalMappedMeshIsLitBySmoothNormal) {
  Fixture f = fixture(kNormalExample, "pov-lit-side", "textured", (kSource / "examples/scenes/textured.json").string());
  PovOutput pov = generate_pov_files(f.scene, &f.material, kNormalExample, PovRoute::Auto, job_name(f.job));
  f.job.code_override = pov.code;
  ComparisonRow right = judged(f, render_one("pov", f.job));
  EXPECT_TRUE(right.pass) << right.metrics.max_excess;
  f.job.code_override = inject_all(pov.code, ", 0, 0, 1)", ", 1, 1, 1)");
  ComparisonRow bad = judged(f, render_one("pov", f.job));
  std::cout << "the flat triangle's lit side: " << bad.metrics.over << " pixels over, worst " << bad.metrics.max_excess << "\n";
  EXPECT_FALSE(bad.pass);
}

// Under a normal map the anisotropic tangent follows the mapped normal (t Gram–Schmidt'd
// against n′): Ward on the tangent rule's t, left as it was, fails; the generated code passes.
TEST(Detection, GlslAnisotropicTangentFollowsTheNormalMap) {
  GlRenderer gl;
  ASSERT_TRUE(gl.ok()) << gl.error();
  Fixture f = fixture("textured_normal_ward", "glsl", "textured", "shadows");
  const std::string good = GlRenderer::fragment_source(f.material);
  f.job.code_override = good;
  ComparisonRow right = judged(f, gl.render(f.job));
  EXPECT_TRUE(right.pass) << right.metrics.max_excess;
  f.job.code_override = inject(good, "    t = normalize(t - ns * dot(ns, t));\n", "");
  ComparisonRow bad = judged(f, gl.render(f.job));
  std::cout << "tangent not following: " << bad.metrics.over << " pixels over, worst " << bad.metrics.max_excess << "\n";
  EXPECT_FALSE(bad.pass) << bad.metrics.max_excess;
}

TEST(Detection, OslNormalMapFailsWhenWrong) {
  Fixture f = fixture(kNormalExample, "osl", "textured", "shadows");
  GenerateOptions o;
  o.target = Target::Osl;
  o.scene = f.scene;
  const std::string good = generate(f.material, o);
  const std::pair<const char*, std::string> wrongs[] = {
      {"right", good},
      {"green flipped", inject(good, "0.8 * nm_c[1]", "-0.8 * nm_c[1]")},
      {"map ignored", inject(good, "vector Ns = normalize(nm_t[0] * Tu + nm_t[1] * Bu + nm_t[2] * Nn);", "vector Ns = Nn;")},
      {"tangent reversed", inject(good, "vector Tu = normalize(", "vector Tu = -normalize(")},
  };
  std::vector<RenderJob> jobs;
  for (const auto& [what, code] : wrongs) {
    jobs.push_back(f.job);
    jobs.back().code_override = code;
    jobs.back().material->name = fmt::format("{}_{}", kNormalExample, jobs.size());
  }
  std::vector<RenderOutcome> r = make_renderer("osl")->render(jobs);
  ASSERT_EQ(r.size(), jobs.size());
  for (size_t k = 0; k < r.size(); ++k) {
    ComparisonRow row = judged(f, r[k]);
    std::cout << wrongs[k].first << ": " << row.metrics.over << " pixels over, worst " << row.metrics.max_excess << "\n";
    if (k == 0) EXPECT_TRUE(row.pass) << row.metrics.max_excess;
    else EXPECT_FALSE(row.pass) << wrongs[k].first << ": " << row.metrics.max_excess;
  }
}

TEST(Detection, PovNormalMapFailsWhenWrong) {
  Fixture f = fixture(kNormalExample, "pov", "textured", "shadows");
  PovOutput pov = generate_pov_files(f.scene, &f.material, kNormalExample, PovRoute::Auto, job_name(f.job));
  f.job.code_override = pov.code;
  ComparisonRow right = judged(f, render_one("pov", f.job));
  EXPECT_TRUE(right.pass) << right.metrics.max_excess;
  const std::string r = "0.8*(2*Facet_Sample_normal_map_r(S0, T0) - 1)", g = "0.8*(2*Facet_Sample_normal_map_g(S0, T0) - 1)",
                    b = "2*Facet_Sample_normal_map_b(S0, T0) - 1";
  const std::pair<const char*, std::string> wrongs[] = {
      {"green flipped", inject_all(pov.code, g, "-" + g)},
      {"map ignored", inject_all(inject_all(inject_all(pov.code, r, "0"), g, "0"), b, "1")},
      {"tangent reversed", inject_all(inject_all(pov.code, r, "-" + r), g, "-" + g)},
  };
  for (const auto& [what, code] : wrongs) {
    f.job.code_override = code;
    ComparisonRow bad = judged(f, render_one("pov", f.job));
    std::cout << what << ": " << bad.metrics.over << " pixels over, worst " << bad.metrics.max_excess << "\n";
    EXPECT_FALSE(bad.pass) << what << ": " << bad.metrics.max_excess;
  }
}


// Vertex colours (glTF's COLOR_0, docs/textures.md): examples/textured/textured_vertex_color.json
// on tests/scenes/vertex_colors.json, whose meshes' colours change strongly from vertex to
// vertex. Dropped (white taken) each renderer fails; where a renderer blends a triangle's
// corners itself — the GL ray caster (and so the G-buffer the others shade), POV-Ray's data
// image — a blend with corners 1 and 2 swapped fails too; the generated code passes. Cycles
// blends its float colour attribute itself, as it blends the normals.
const char* const kVertexColorExample = "textured_vertex_color";
const fs::path kVertexColorScene = kSource / "tests/scenes/vertex_colors.json";

void expect_vertex_colour_faults_fail(const std::string& renderer, const std::string& good,
                                      const std::vector<std::pair<const char*, std::string>>& wrongs) {
  Fixture f = fixture(kVertexColorExample, renderer + "-vertex-colors", "textured", kVertexColorScene.string());
  std::vector<RenderJob> jobs = {f.job};
  jobs[0].code_override = good;
  for (const auto& w : wrongs) {
    jobs.push_back(f.job);
    jobs.back().code_override = w.second;
    jobs.back().material->name = fmt::format("{}_wrong_{}", kVertexColorExample, jobs.size());
  }
  // POV-Ray's code reads files named after its job: each job alone, under the same name.
  std::vector<RenderOutcome> out;
  if (renderer == "pov") {
    for (auto& j : jobs) j.material->name = kVertexColorExample;
    for (const auto& j : jobs) out.push_back(render_one(renderer, j));
  } else {
    out = make_renderer(renderer)->render(jobs);
  }
  ASSERT_EQ(out.size(), jobs.size()) << renderer;
  for (size_t k = 0; k < out.size(); ++k) {
    const ComparisonRow row = judged(f, out[k]);
    const char* what = k == 0 ? "right" : wrongs[k - 1].first;
    std::cout << renderer << ", " << what << ": " << row.metrics.over << " pixels over, worst " << row.metrics.max_excess
              << "\n";
    if (k == 0) EXPECT_TRUE(row.pass) << renderer << ": " << row.metrics.max_excess;
    else EXPECT_FALSE(row.pass) << renderer << ", " << what << ": " << row.metrics.max_excess;
  }
}

TEST(Detection, GlslVertexColoursFailWhenDroppedOrMisordered) {
  const Material m = load_material((kSource / "examples/textured" / (std::string(kVertexColorExample) + ".json")).string());
  const std::string good = GlRenderer::fragment_source(m);
  const std::string corner1 = "texelFetch(facet_colors, t + 1) * h.uv.x", corner2 = "texelFetch(facet_colors, t + 2) * h.uv.y";
  expect_vertex_colour_faults_fail(
      "glsl", good,
      {{"dropped", inject(good, "facet_color0_at(hit, best));", "vec4(1.0));")},
       {"corners 1 and 2 swapped",
        inject(inject(good, corner1, "texelFetch(facet_colors, t + 2) * h.uv.x"), corner2,
               "texelFetch(facet_colors, t + 1) * h.uv.y")}});
}

// The G-buffer's renderers read image 5; each pass with it left out fails.
TEST(Detection, GBufferVertexColoursFailWhenDropped) {
  const Material m = load_material((kSource / "examples/textured" / (std::string(kVertexColorExample) + ".json")).string());
  const std::string vk = glsl_gbuffer_shading_source(m, Target::Glsl450), es = glsl_gbuffer_shading_source(m, Target::Essl);
  const std::string read = "texelFetch(facet_gbuffer_color0, facet_gbuffer_texel, 0)";
  expect_vertex_colour_faults_fail("vulkan", vk, {{"dropped", inject(vk, read, "vec4(1.0)")}});
  expect_vertex_colour_faults_fail("webgl", es, {{"dropped", inject(es, read, "vec4(1.0)")}});
  const std::string hlsl = hlsl_shading_source(m);
  expect_vertex_colour_faults_fail(
      "vulkan-hlsl", hlsl, {{"dropped", inject(hlsl, "facet_gbuffer_color0.Load(texel)", "float4(1.0, 1.0, 1.0, 1.0)")}});
  const std::string wgsl = wgsl_gbuffer_shading_source(m);
  expect_vertex_colour_faults_fail(
      "wgpu", wgsl, {{"dropped", inject(wgsl, "textureLoad(facet_gbuffer_color0, texel, 0)", "vec4<f32>(1.0)")}});
}

// Cycles: the shader's facet_color0 and facet_alpha0 left unlinked (the harness links what
// the shader declares), white inside the shader.
TEST(Detection, OslVertexColoursFailWhenDropped) {
  const Material m = load_material((kSource / "examples/textured" / (std::string(kVertexColorExample) + ".json")).string());
  const std::string good = osl_source(m, load_scene(kVertexColorScene.string()));
  const std::string dropped =
      inject(inject(inject(good, "color facet_color0 = 1,", "color facet_color0_dropped = 1,"), "float facet_alpha0 = 1,",
                    "float facet_alpha0_dropped = 1,"),
             "    // Textured parameters.", "    color facet_color0 = 1;\n    float facet_alpha0 = 1;\n    // Textured parameters.");
  expect_vertex_colour_faults_fail("osl", good, {{"dropped", dropped}});
}

// POV-Ray: the data image's colours not read (1 taken), or read with the block's corners 1 and
// 2 swapped (pov_mesh.h: corner k of a triangle's block at (2i + [k = 1], 2j + [k = 2]), so
// swapping them swaps the point's offsets within its block).
TEST(Detection, PovVertexColoursFailWhenDroppedOrMisordered) {
  Fixture f = fixture(kVertexColorExample, "pov-vertex-colors", "textured", kVertexColorScene.string());
  const std::string good =
      generate_pov_files(f.scene, &f.material, kVertexColorExample, PovRoute::Auto, job_name(f.job)).code;
  std::string dropped = good, swapped = good;
  for (int o : {0, 2})
    for (const char* c : {"R", "G", "B", "A"}) {
      const std::string read = fmt::format("Facet_Mesh{}_C{}(x, y)", o, c);
      dropped = inject_all(dropped, read, "1");
      swapped = inject_all(swapped, read,
                           fmt::format("Facet_Mesh{}_C{}(2*floor(x/2) + y - 2*floor(y/2), 2*floor(y/2) + x - 2*floor(x/2))", o, c));
    }
  expect_vertex_colour_faults_fail("pov", good, {{"dropped", dropped}, {"corners 1 and 2 swapped", swapped}});
}


}  // namespace
}  // namespace facet
