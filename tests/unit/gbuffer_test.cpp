// The G-buffer (renderers/gbuffer.h): the GL ray caster's hit positions, normals,
// view directions and texture coordinates agree with the scene's own double-precision
// geometry (what the reference ray caster shades with) to float precision, its
// visibility images mark the `shadows` scene's shadowed pixels, and the GLSL shading
// pass over it draws what the GL renderer draws.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <tuple>

#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "catalog/material.h"
#include "reference/raycaster.h"
#include "renderers/gbuffer.h"
#include "renderers/opengl.h"
#include "targets/targets.h"

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
  size_t shaded = 0, coverage_differs = 0, shadowed = 0, visibility_differs = 0, grazing = 0;
  double position = 0, normal = 0, view = 0, uv = 0;
};

// Light i's visibility at p by the scene's own geometry in double precision, as
// the reference casts it: every object but p's own convex one, from the offset on.
bool lit(const Scene& s, int self, const Light& light, const Vec3& p, double offset) {
  Vec3 l;
  double d;
  light.toward(p, l, d);
  for (size_t i = 0; i < s.objects.size(); ++i) {
    if (int(i) == self && s.objects[i].convex()) continue;
    double t = s.objects[i].intersect(p, l, offset);
    if (t > 0 && t < d) return false;
  }
  return true;
}

Agreement agreement(const GBuffer& g, const RenderJob& job) {
  const Scene& s = job.scene;
  const Render ref = render_reference(*job.material, s, g.width, g.height);
  const double offset = kShadowRayOffset * std::max(1.0, length(s.camera.position) + 2);
  Agreement a;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const int row = g.height - 1 - y;  // the reference's rows run from the top
      const Vec3 dir = s.camera.ray(x, row, g.width, g.height);
      const int object = ref.object[size_t(row) * size_t(g.width) + size_t(x)];
      const float* pos = g.texel(GBuffer::Position, x, y);
      if ((object >= 0) != (pos[3] == 1.0f) || (object < 0 && pos[3] != -1.0f)) {
        ++a.coverage_differs;
        continue;
      }
      if (object < 0) continue;
      ++a.shaded;
      const Object& o = s.objects[size_t(object)];
      const Hit hit = o.hit(s.camera.position, dir);
      const Vec3 p = s.camera.position + dir * hit.t;
      // A float ray's hit slides along the surface by its direction's rounding over |n·v|
      // (a glancing ray's hit moves most): the deviations are weighed by |n·v|.
      const Vec3 n = o.normal_at(p, hit);
      const double facing = std::fabs(dot(n, dir));
      a.position = std::max(a.position, distance(pos, p) * facing / std::max(1.0, length(p)));
      a.normal = std::max(a.normal, distance(g.texel(GBuffer::Normal, x, y), n) * facing);
      a.view = std::max(a.view, distance(g.texel(GBuffer::View, x, y), -dir));
      const auto uv = o.uv_at(p, hit);
      const float* st = g.texel(GBuffer::Uv, x, y);
      // Away from a sphere's seam (u = 0 | 1); near its poles, atan and acos magnify p's rounding by
      // 1 / the distance from the axis: weighed by it.
      const Vec3 d = (p - o.center) / o.radius;
      const bool sphere = o.type == Object::Type::Sphere;
      if (!sphere || d.z > 0 || std::fabs(d.x) > 1e-3)
        a.uv = std::max(a.uv, facing * (sphere ? std::hypot(d.x, d.z) : 1.0) * std::max({std::fabs(st[0] - uv[0][0]), std::fabs(st[1] - uv[0][1]),
                                                 std::fabs(st[2] - uv[1][0]), std::fabs(st[3] - uv[1][1])}));
      const bool fragile = ref.grazing[size_t(row) * size_t(g.width) + size_t(x)];
      a.grazing += fragile;
      for (size_t i = 0; i < 8; ++i) {
        const float v = g.texel(i < 4 ? GBuffer::VisibilityLow : GBuffer::VisibilityHigh, x, y)[i % 4];
        const bool expected = i < s.lights.size() && lit(s, object, s.lights[i], p, offset);
        if (i < s.lights.size() && !expected) ++a.shadowed;
        if (v != (expected ? 1.0f : 0.0f) && !fragile) ++a.visibility_differs;
      }
    }
  return a;
}

void expect_agreement(const std::string& scene, size_t min_shadowed) {
  GlRenderer gl;
  ASSERT_TRUE(gl.ok()) << gl.error();
  const RenderJob job = job_for("lambert", scene, 96, 80);
  GBufferOutcome out = cast_gbuffer(gl, job, 0);
  ASSERT_TRUE(out.ok) << out.error;
  const GBuffer& g = out.gbuffer;
  ASSERT_EQ(g.width, 96);
  ASSERT_EQ(g.height, 80);
  for (const auto& image : g.images) ASSERT_EQ(image.size(), size_t(96 * 80 * 4));
  const Agreement a = agreement(g, job);
  std::cout << fmt::format("{}: {} shaded pixels, coverage differs on {}, worst |Δp|/max(1,|p|) {:.3g}, |Δn| {:.3g}, "
                           "|Δv| {:.3g}, |Δuv| {:.3g}; {} shadowed (pixel, light) pairs, {} differ ({} grazing pixels)\n",
                           scene, a.shaded, a.coverage_differs, a.position, a.normal, a.view, a.uv, a.shadowed,
                           a.visibility_differs, a.grazing);
  EXPECT_GT(a.shaded, size_t(1000));
  EXPECT_LE(a.coverage_differs, size_t(2));  // a pixel centre on a silhouette, at most
  EXPECT_LT(a.position, 1e-5);  // measured ≤ 3.7e-6: tens of float ulps
  EXPECT_LT(a.normal, 1e-5);
  EXPECT_LT(a.view, 1e-6);
  // llvmpipe's acos (harness/raycast.glsl's facet_uv, the GL renderer's own) is an
  // approximation: v = acos(d_y)/π measured 2.2e-5 off the double value on the spheres.
  EXPECT_LT(a.uv, 1e-4);
  EXPECT_GE(a.shadowed, min_shadowed);
  EXPECT_EQ(a.visibility_differs, size_t(0));
  EXPECT_EQ(g.light_count, int(job.scene.lights.size()));
  EXPECT_EQ(g.lights.size(), job.scene.lights.size() * 16);
}

TEST(GBuffer, SingleAgreesWithTheSceneGeometry) { expect_agreement("single", 0); }

// The shadows scene's spheres shadow the floor and each other: those pixels are marked 0.
TEST(GBuffer, ShadowsVisibilityMarksTheShadows) { expect_agreement("shadows", 500); }

// The GLSL shading pass (templates/glsl/gbuffer_shade.glsl) over the G-buffer draws the
// GL renderer's image: the same facet_shade on the same p, n, v and visibility.
TEST(GBuffer, GlslShadingPassDrawsTheRenderersImage) {
  GlRenderer gl;
  ASSERT_TRUE(gl.ok()) << gl.error();
  for (const std::string material : {"blinn_phong", "oren_nayar"}) {
    const RenderJob job = job_for(material, "shadows", 96, 80);
    GBufferOutcome g = cast_gbuffer(gl, job, 0);
    ASSERT_TRUE(g.ok) << g.error;
    ShaderDraw draw{material, glsl_gbuffer_shading_source(*job.material, Target::Glsl), shading_uniforms(g.gbuffer)};
    std::vector<ShaderTexture> images;
    for (int i = 0; i < GBuffer::kImages; ++i) images.push_back({GBuffer::sampler(i), 96, 80, g.gbuffer.images[size_t(i)]});
    RenderOutcome shaded = gl.draw({draw}, 96, 80, {}, {images}).at(0);
    ASSERT_TRUE(shaded.ok) << shaded.error;
    RenderOutcome direct = gl.render(job);
    ASSERT_TRUE(direct.ok) << direct.error;
    double worst = 0, peak = 0;
    for (size_t k = 0; k < direct.image.rgb.size(); ++k) {
      worst = std::max(worst, double(std::fabs(shaded.image.rgb[k] - direct.image.rgb[k])));
      peak = std::max(peak, double(direct.image.rgb[k]));
    }
    EXPECT_EQ(shaded.alpha, direct.alpha);
    EXPECT_GT(peak, 0.1);
    EXPECT_LE(worst, 1e-6 * std::max(1.0, peak)) << material;
    std::cout << fmt::format("{}: shading pass vs GL renderer, worst |Δ| {:.3g} (peak {:.3g})\n", material, worst, peak);
  }
}

// The shading pass compiles in each dialect (glslang: GLSL 3.30, ES 3.00, and Vulkan SPIR-V).
TEST(GBuffer, ShadingPassCompilesInEveryDialect) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("facet-gbuffer-{}", ::getpid());
  fs::create_directories(dir);
  const Material m = load_material((kSource / "examples" / "textured" / "textured_normal_cook_torrance.json").string());
  for (auto [target, name, flags] : {std::tuple{Target::Glsl, "glsl", ""}, std::tuple{Target::Essl, "essl", ""},
                                     std::tuple{Target::Glsl450, "glsl450", "-V "}}) {
    const fs::path file = dir / fmt::format("shade_{}.frag", name);
    std::ofstream(file) << glsl_gbuffer_shading_source(m, target);
    const std::string spirv = *flags ? " -o " + (dir / "out.spv").string() : "";
    const std::string cmd = fmt::format("{} {}{}{} > {} 2>&1", GLSLANG_VALIDATOR, flags, file.string(), spirv,
                                        (dir / fmt::format("{}.log", name)).string());
    std::ifstream log(dir / fmt::format("{}.log", name));
    EXPECT_EQ(std::system(cmd.c_str()), 0) << name << ": " << cmd << "\n" << std::string(std::istreambuf_iterator<char>(log), {});
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace facet
