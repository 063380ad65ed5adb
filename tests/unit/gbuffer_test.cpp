// The G-buffer (renderers/gbuffer.h): the GL ray caster's hit positions, normals,
// view directions, texture coordinates and vertex colours agree with the scene's own double-precision
// geometry (what the reference ray caster shades with) to float precision, its
// visibility image holds every light's bit where the scene's geometry says (the `shadows`
// scene's shadows; 100 lights over 300 objects, past the image's first layer of 96), and
// the GLSL shading pass over it draws what the GL renderer draws — and not when it
// decodes another light's bit.
#include <cmath>
#include <cstdlib>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <tuple>


#include <fmt/format.h>
#include <gtest/gtest.h>

#include "catalog/material.h"
#include "reference/raycaster.h"
#include "renderers/gbuffer.h"
#include "renderers/opengl.h"
#include "scene/shapes.h"
#include "targets/targets.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = FACET_SOURCE_DIR;

RenderJob job_for(const std::string& material, const std::string& scene, int w, int h) {
  RenderJob job;
  job.material = load_material((kSource / "examples" / "materials" / (material + ".json")).string());
  job.scene = load_scene(scene);
  job.width = w;
  job.height = h;
  return job;
}

double distance(const float* a, const Vec3& b) { return length(Vec3(a[0], a[1], a[2]) - b); }

// What the G-buffer is checked against, per pixel: counts and worst deviations.
struct Agreement {
  size_t shaded = 0, coverage_differs = 0, nearest_differs = 0, shadowed = 0, lit_past_first_layer = 0;
  size_t visibility_differs = 0, grazing = 0;
  double position = 0, normal = 0, mesh_normal = 0, view = 0, uv = 0, color = 0;
  size_t colored = 0;  // pixels whose vertex colour is not white
};

// The object a ray meets first, every object tried in turn (the lowest index among equally
// near ones): what the reference finds walking its hierarchy.
int nearest(const Scene& s, const Vec3& o, const Vec3& d) {
  int best = -1;
  double t = 0;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Hit h = s.objects[i].hit(o, d);
    if (h.ok() && (best < 0 || h.t < t)) best = int(i), t = h.t;
  }
  return best;
}

// Light i's bit as the G-buffer should hold it at p (normal n), by the scene's own geometry in
// double precision as the reference casts it: every object but p's own convex one, from the
// offset on; 0 where the surface faces away by more than GBuffer::kHorizon. `fragile` when
// n·l is within float rounding of that margin.
bool lit(const Scene& s, int self, const Light& light, const Vec3& p, const Vec3& n, double offset, bool& fragile) {
  Vec3 l;
  double d;
  light.toward(p, l, d);
  fragile = std::fabs(dot(n, l) + GBuffer::kHorizon) < 1e-5;
  if (dot(n, l) < -GBuffer::kHorizon) return false;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    if (int(i) == self && s.objects[i].convex()) continue;
    double t = s.objects[i].intersect(p, l, offset);
    if (t > 0 && t < d) return false;
  }
  return true;
}

// Pixel (x, y)'s light bits (`object` hit at p, normal n; at gp by the ray caster's float
// ray) against lit(). Where lit() at p and at gp differ, the bit is a matter of where the hit
// point lies within float rounding (a glancing camera ray's hit slides along the surface, and
// its shadow ray passes an occluder's edge on either side): not judged.
void check_lights(const GBuffer& g, const Scene& s, int object, const Vec3& p, const Vec3& gp, const Vec3& n,
                  double offset, int x, int y, bool fragile, Agreement& a) {
  for (int i = 0; i < int(s.lights.size()) + 30; ++i) {  // and 0 past the scene's lights, in the last layer
    bool edge = false, gp_edge = false;
    const bool real = i < int(s.lights.size());
    const bool expected = real && lit(s, object, s.lights[size_t(i)], p, n, offset, edge);
    if (real && !expected) ++a.shadowed;
    if (expected && i >= glsl_light::kVisibilityLayerLights) ++a.lit_past_first_layer;
    if (i / glsl_light::kVisibilityLayerLights >= g.layers) break;
    const bool slides = real && lit(s, object, s.lights[size_t(i)], gp, n, offset, gp_edge) != expected;
    if (g.lit(x, y, i) != expected && !fragile && !edge && !gp_edge && !slides) ++a.visibility_differs;
  }
}

Agreement agreement(const GBuffer& g, const RenderJob& job) {
  const Scene& s = job.scene;
  const Render ref = job.material ? render_reference(*job.material, s, g.width, g.height)
                                  : render_reference(s, g.width, g.height);
  std::vector<size_t> pass_of;
  material_passes(job, &pass_of);
  const double offset = kShadowRayOffset * std::max(1.0, length(s.camera.position) + 2);
  Agreement a;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const int row = g.height - 1 - y;  // the reference's rows run from the top
      const Vec3 dir = s.camera.ray(x, row, g.width, g.height);
      const int object = ref.object[size_t(row) * size_t(g.width) + size_t(x)];
      const float* pos = g.texel(GBuffer::Position, x, y);
      // w: the material pass of the object hit, -1 background.
      if (object < 0 ? pos[3] != -1.0f : pos[3] != float(pass_of[size_t(object)])) {
        ++a.coverage_differs;
        continue;
      }
      if (nearest(s, s.camera.position, dir) != object) ++a.nearest_differs;
      if (object < 0) continue;
      ++a.shaded;
      const Object& o = s.objects[size_t(object)];
      const Hit hit = o.hit(s.camera.position, dir);
      const Vec3 p = s.camera.position + dir * hit.t;
      // A float ray's hit slides along the surface by its direction's rounding over |n·v|
      // (a glancing ray's hit moves most): the deviations are weighed by |n·v|.
      const Vec3 n = o.normal_at(p, hit);
      const double facing = std::fabs(dot(n, dir));
      const bool fragile = ref.grazing[size_t(row) * size_t(g.width) + size_t(x)];
      a.grazing += fragile;
      check_lights(g, s, object, p, Vec3(pos[0], pos[1], pos[2]), n, offset, x, y, fragile, a);
      a.view = std::max(a.view, distance(g.texel(GBuffer::View, x, y), -dir));
      a.position = std::max(a.position, distance(pos, p) * facing / std::max(1.0, length(p)));
      // A mesh's normal is its vertices' blended by the hit's barycentrics, which float rounds more.
      double& normal = o.type == Object::Type::Mesh ? a.mesh_normal : a.normal;
      normal = std::max(normal, distance(g.texel(GBuffer::Normal, x, y), n) * facing);
      // The vertex colour, blended by the hit's barycentrics as the normal is: weighed alike.
      const auto c = o.color_at(hit);
      const float* gc = g.texel(GBuffer::Color0, x, y);
      for (size_t k = 0; k < 4; ++k) a.color = std::max(a.color, std::fabs(gc[k] - c[k]) * facing);
      a.colored += c != std::array<double, 4>{1, 1, 1, 1};
      const auto uv = o.uv_at(p, hit);
      const float* st = g.texel(GBuffer::Uv, x, y);
      // Away from a sphere's seam (u = 0 | 1); near its poles, atan and acos magnify p's rounding by
      // 1 / the distance from the axis: weighed by it.
      const Vec3 d = (p - o.center) / o.radius;
      const bool sphere = o.type == Object::Type::Sphere;
      if (!sphere || d.z > 0 || std::fabs(d.x) > 1e-3)
        a.uv = std::max(a.uv, facing * (sphere ? std::hypot(d.x, d.z) : 1.0) * std::max({std::fabs(st[0] - uv[0][0]), std::fabs(st[1] - uv[0][1]),
                                                 std::fabs(st[2] - uv[1][0]), std::fabs(st[3] - uv[1][1])}));
    }
  return a;
}

Agreement expect_agreement(const RenderJob& job, size_t min_shadowed, size_t min_shaded) {
  GlRenderer gl;
  EXPECT_TRUE(gl.ok()) << gl.error();
  GBufferOutcome out = cast_gbuffer(gl, job);
  EXPECT_TRUE(out.ok) << out.error;
  if (!out.ok) return {};
  const GBuffer& g = out.gbuffer;
  EXPECT_EQ(g.width, job.width);
  EXPECT_EQ(g.height, job.height);
  EXPECT_EQ(g.layers, GBuffer::layers_for(int(job.scene.lights.size())));
  const size_t texels = size_t(job.width) * size_t(job.height) * 4;
  for (int i = 0; i < GBuffer::kImages; ++i)
    EXPECT_EQ(g.images[size_t(i)].size(), texels * size_t(i == GBuffer::Visibility ? g.layers : 1));
  const Agreement a = agreement(g, job);
  std::cout << fmt::format("{}: {} shaded pixels, coverage differs on {}, the reference's object differs from every "
                           "object's nearest on {}, worst |Δp|/max(1,|p|) {:.3g}, |Δn| {:.3g} (meshes {:.3g}), |Δv| {:.3g}, |Δuv| {:.3g}, "
                           "|Δcolour| {:.3g} ({} coloured pixels); "
                           "{} shadowed (pixel, light) pairs, {} lit past the first layer, {} differ ({} grazing pixels)\n",
                           job.scene.name, a.shaded, a.coverage_differs, a.nearest_differs, a.position, a.normal, a.mesh_normal, a.view,
                           a.uv, a.color, a.colored, a.shadowed, a.lit_past_first_layer, a.visibility_differs, a.grazing);
  EXPECT_GE(a.shaded, min_shaded);
  EXPECT_LE(a.coverage_differs, size_t(2));  // a pixel centre on a silhouette, at most
  EXPECT_EQ(a.nearest_differs, size_t(0));
  // Measured ≤ 2.3e-6 (300 objects), 5.8e-7 (shadows): a few float ulps, since the ray caster
  // meets a sphere without cancellation (raycast.glsl; 3.7e-6 on `shadows` before).
  EXPECT_LT(a.position, 1e-5);
  EXPECT_LT(a.normal, 1e-5);
  EXPECT_LT(a.mesh_normal, 1e-4);  // measured 1.5e-5
  EXPECT_LT(a.view, 1e-6);
  // llvmpipe's acos (harness/raycast.glsl's facet_uv, the GL renderer's own) is an
  // approximation: v = acos(d_y)/π measured 2.2e-5 off the double value on the spheres.
  EXPECT_LT(a.uv, 1e-4);
  EXPECT_LT(a.color, 1e-4);  // as the meshes' normals
  EXPECT_GE(a.shadowed, min_shadowed);
  EXPECT_EQ(a.visibility_differs, size_t(0));
  EXPECT_EQ(g.light_count, int(job.scene.lights.size()));
  EXPECT_EQ(g.lights.size(), job.scene.lights.size() * 16);
  return a;
}

TEST(GBuffer, SingleAgreesWithTheSceneGeometry) { expect_agreement(job_for("lambert", "single", 96, 80), 0, 1000); }

// The shadows scene's spheres shadow the floor and each other: those pixels are marked 0.
TEST(GBuffer, ShadowsVisibilityMarksTheShadows) { expect_agreement(job_for("lambert", "shadows", 96, 80), 500, 1000); }

// Meshes with vertex colours (tests/scenes/vertex_colors.json): image 5 holds each hit's
// colour, blended as the reference blends it; white on the sphere.
TEST(GBuffer, VertexColoursAreTheMeshesBlendedColours) {
  RenderJob job = job_for("lambert", (kSource / "tests/scenes/vertex_colors.json").string(), 96, 72);
  const Agreement a = expect_agreement(job, 0, 1000);
  EXPECT_GT(a.colored, 1000u);
}

// The many-objects scene (scene/shapes.h): 300 objects of four materials, every object kind,
// under 100 lights of every type, past the first layer of 96.
RenderJob many_job(size_t lights, int w, int h) {
  std::vector<Material> materials;
  for (const char* name : {"lambert", "blinn_phong", "oren_nayar", "ggx"})
    materials.push_back(load_material((kSource / "examples" / "materials" / (std::string(name) + ".json")).string()));
  RenderJob job;
  job.scene = many_objects_scene(300, lights, materials);
  job.width = w;
  job.height = h;
  return job;
}

// Every light's bit, 100 lights in two layers, where the scene's geometry in double precision
// says; the reference's objects are every object's nearest (its hierarchy misses none).
TEST(GBuffer, HundredLightsHoldTheirBitsPastTheFirstLayer) {
  const RenderJob job = many_job(100, 64, 48);
  ASSERT_EQ(GBuffer::layers_for(100), 2);
  const Agreement a = expect_agreement(job, 10000, 2000);
  EXPECT_GT(a.lit_past_first_layer, size_t(1000));
}

// The GLSL 3.30 shading pass of each material pass drawn over the G-buffer (cast once for
// them all), the passes summed as the renderers sum them; `wrong` edits each pass's source first.
RenderOutcome shade_gbuffer(GlRenderer& gl, const RenderJob& job, const std::function<std::string(std::string)>& wrong = {}) {
  GBufferOutcome g = cast_gbuffer(gl, job);
  EXPECT_TRUE(g.ok) << g.error;
  const std::vector<const Material*> passes = material_passes(job);
  std::vector<ShaderDraw> draws;
  std::vector<std::vector<ShaderTexture>> textures;
  for (size_t k = 0; k < passes.size(); ++k) {
    std::string source = glsl_gbuffer_shading_source(*passes[k], Target::Glsl);
    draws.push_back({passes[k]->name, wrong ? wrong(source) : source, shading_uniforms(g.gbuffer)});
    std::vector<ShaderTexture> images = {{GBuffer::sampler(0), job.width, job.height, g.gbuffer.pass_position(k)}};
    for (int i = 1; i < GBuffer::kImages; ++i)
      images.push_back({GBuffer::sampler(i), job.width, job.height, g.gbuffer.images[size_t(i)],
                        i == GBuffer::Visibility ? g.gbuffer.layers : 0});
    ShaderTexture lights{"facet_light_buffer", 0, 0, g.gbuffer.lights};
    lights.buffer = true;
    if (lights.rgba.empty()) lights.rgba.assign(16, 0);
    images.push_back(lights);
    textures.push_back(images);
  }
  RenderOutcome sum;
  sum.image = Image(job.width, job.height);
  sum.alpha.assign(size_t(job.width) * size_t(job.height), 0);
  sum.ok = true;
  for (const RenderOutcome& pass : gl.draw(draws, job.width, job.height, {}, textures)) {
    EXPECT_TRUE(pass.ok) << pass.error;
    sum.ok = sum.ok && pass.ok;
    for (size_t i = 0; pass.ok && i < sum.image.rgb.size(); ++i) sum.image.rgb[i] += pass.image.rgb[i];
    for (size_t i = 0; pass.ok && i < sum.alpha.size(); ++i) sum.alpha[i] = std::max(sum.alpha[i], pass.alpha[i]);
  }
  return sum;
}

// The largest |shaded − direct| and the largest value of `direct`.
std::pair<double, double> difference(const RenderOutcome& shaded, const RenderOutcome& direct) {
  double worst = 0, peak = 0;
  for (size_t k = 0; k < direct.image.rgb.size(); ++k) {
    worst = std::max(worst, double(std::fabs(shaded.image.rgb[k] - direct.image.rgb[k])));
    peak = std::max(peak, double(direct.image.rgb[k]));
  }
  return {worst, peak};
}

// The GLSL shading pass (templates/glsl/gbuffer_shade.glsl) over the G-buffer draws the
// GL renderer's image: the same facet_shade on the same p, n, v and visibility.
void expect_shading_pass_draws_the_image(const RenderJob& job) {
  GlRenderer gl;
  ASSERT_TRUE(gl.ok()) << gl.error();
  RenderOutcome shaded = shade_gbuffer(gl, job);
  ASSERT_TRUE(shaded.ok);
  RenderOutcome direct = gl.render(job);
  ASSERT_TRUE(direct.ok) << direct.error;
  const auto [worst, peak] = difference(shaded, direct);
  EXPECT_EQ(shaded.alpha, direct.alpha);
  EXPECT_GT(peak, 0.1);
  EXPECT_LE(worst, 1e-6 * std::max(1.0, peak)) << job.scene.name;
  std::cout << fmt::format("{}: shading pass vs GL renderer, worst |Δ| {:.3g} (peak {:.3g})\n", job_name(job), worst, peak);
}

TEST(GBuffer, GlslShadingPassDrawsTheRenderersImage) {
  for (const std::string material : {"blinn_phong", "oren_nayar"})
    expect_shading_pass_draws_the_image(job_for(material, "shadows", 96, 80));
}

// 300 objects of four materials (four passes over one G-buffer) and 100 lights.
TEST(GBuffer, GlslShadingPassDrawsTheRenderersImageWithHundredLights) {
  expect_shading_pass_draws_the_image(many_job(100, 64, 48));
}

// The comparison has teeth: a shading pass that reads light i + 1's bit for light i (or a
// layer off for the lights past the first 96) does not draw the GL renderer's image.
TEST(GBuffer, WrongVisibilityBitIsSeen) {
  GlRenderer gl;
  ASSERT_TRUE(gl.ok()) << gl.error();
  const RenderJob job = many_job(100, 64, 48);
  RenderOutcome direct = gl.render(job);
  ASSERT_TRUE(direct.ok) << direct.error;
  const std::pair<std::string, std::string> wrongs[] = {
      {"(bits >> (light % 24))", "(bits >> ((light + 1) % 24))"},
      {"ivec3(facet_gbuffer_texel, light / 96)", "ivec3(facet_gbuffer_texel, 0)"}};
  for (const auto& [right, wrong] : wrongs) {
    RenderOutcome shaded = shade_gbuffer(gl, job, [&, r = right, w = wrong](std::string source) {
      const size_t at = source.find(r);
      EXPECT_NE(at, std::string::npos) << r;
      return at == std::string::npos ? source : source.replace(at, r.size(), w);
    });
    ASSERT_TRUE(shaded.ok);
    const auto [worst, peak] = difference(shaded, direct);
    std::cout << fmt::format("{} for {}: worst |Δ| {:.3g} (peak {:.3g})\n", wrong, right, worst, peak);
    EXPECT_GT(worst, 2e-3 * std::max(1.0, peak)) << wrong;
  }
}

// The shading pass compiles in each dialect (glslang: GLSL 3.30, ES 3.00, and Vulkan SPIR-V).
TEST(GBuffer, ShadingPassCompilesInEveryDialect) {
  const fs::path dir = test::scratch("gbuffer", "dialects");
  fs::create_directories(dir);
  const Material m = load_material((kSource / "examples" / "textured" / "textured_normal_cook_torrance.json").string());
  for (auto [target, name, flags] : {std::tuple{Target::Glsl, "glsl", ""}, std::tuple{Target::Essl, "essl", ""},
                                     std::tuple{Target::Glsl450, "glsl450", "-V "}}) {
    const fs::path file = dir / fmt::format("shade_{}.frag", name);
    std::ofstream(file) << glsl_gbuffer_shading_source(m, target);
    const std::string spirv = *flags ? " -o " + (dir / "out.spv").string() : "";
    const std::string cmd = fmt::format("{} {}{}{} > {} 2>&1", GLSLANG_VALIDATOR, flags, file.string(), spirv,
                                        (dir / fmt::format("{}.log", name)).string());
    const int status = std::system(cmd.c_str());
    std::ifstream log(dir / fmt::format("{}.log", name));  // glslang's words, read after it ran
    EXPECT_EQ(status, 0) << name << ": " << cmd << "\n" << std::string(std::istreambuf_iterator<char>(log), {});
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace facet
