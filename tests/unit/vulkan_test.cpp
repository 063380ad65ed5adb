// The Vulkan machinery (renderers/vulkan.h) on its own: what a draw binds reaches the
// shader where vulkan.h says (a 2D array image and the storage buffer of set 2 included),
// pixels come back in facet's order, the FacetScene block and the light buffer hold the
// scene's numbers where the generated glsl450 reads them (100 lights: any number), the
// renderers shade 100 lights as the GL renderer does and not when their pass decodes
// another light's visibility bit, and glslang's and the validation layers' complaints name the file.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>


#include "catalog/material.h"
#include "catalog/program.h"
#include "renderers/hlsl_shading.h"
#include "renderers/vulkan.h"
#include "scene/scene.h"
#include "scene/shapes.h"
#include "targets/glsl_lights.h"
#include "targets/targets.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace facet;

namespace {

const fs::path kSource = FACET_SOURCE_DIR;

std::string folder(const std::string& name) {
  return test::scratch("vulkan", name).string();
}

VulkanDevice& device() {
  static VulkanDevice d;
  return d;
}

// Every binding of vulkan.h at once: the uniform block (a float and an int), a 3×2 texture in
// set 0, an image of one texel per pixel and a 2D array of two such layers in set 1, the
// storage buffer of set 2 (a float per pixel), the push constants; the pixel centre from gl_FragCoord.
const char* kEveryBinding = R"(#version 450
layout(std140, set = 0, binding = 0) uniform Block { vec4 offset; int count; };
layout(set = 0, binding = 1) uniform sampler2D image;
layout(set = 1, binding = 0) uniform sampler2D values;
layout(set = 1, binding = 1) uniform sampler2DArray layers;
layout(std430, set = 2, binding = 0) readonly buffer Storage { float stored[]; };
layout(push_constant) uniform Size { ivec2 size; };
layout(location = 0) out vec4 color;
void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float texel = texelFetch(image, ivec2(p.x % 3, p.y % 2), 0).r;
    float layered = texelFetch(layers, ivec3(p, 0), 0).y + texelFetch(layers, ivec3(p, 1), 0).z;
    color = vec4(gl_FragCoord.xy, texelFetch(values, p, 0).x + texel + float(size.x * 100000),
                 offset.x + float(count) + layered + stored[p.y * size.x + p.x]);
}
)";

}  // namespace

TEST(Vulkan, DeviceIsThere) {
  ASSERT_EQ(device().unavailable(), "");
  EXPECT_NE(device().description(), "");
  std::cout << device().description() << (device().validation_layers() ? ", validation layers on\n" : "\n");
}

TEST(Vulkan, EveryBindingReachesItsPixel) {
  ASSERT_EQ(device().unavailable(), "");
  const int w = 7, h = 5;
  Texels tex;
  tex.width = 3;
  tex.height = 2;
  for (int i = 0; i < 6; ++i) tex.rgba.insert(tex.rgba.end(), {float(1000 * (i + 1)), 0, 0, 1});
  VulkanDraw d;
  d.name = "every_binding";
  d.source = kEveryBinding;
  float offset = 0.25f;
  int32_t count = 3;
  d.uniforms.resize(32);
  std::memcpy(d.uniforms.data(), &offset, 4);
  std::memcpy(d.uniforms.data() + 16, &count, 4);
  d.textures = {{tex.width, tex.height, tex.rgba.data()}};
  std::vector<float> values;
  for (int i = 0; i < w * h; ++i) values.insert(values.end(), {float(i), 0, 0, 0});
  // Layer 0's y is 10 000 · (pixel index), layer 1's z 20 000 · (pixel index); the storage 0.5 · (pixel index).
  std::vector<float> layers(size_t(2 * w * h * 4), 0.0f);
  std::vector<float> stored;
  for (int i = 0; i < w * h; ++i) {
    layers[size_t(i) * 4 + 1] = float(10000 * i);
    layers[size_t(w * h + i) * 4 + 2] = float(20000 * i);
    stored.push_back(0.5f * float(i));
  }
  d.images = {{w, h, values.data()}, {w, h, layers.data(), 2}};
  d.storage.resize(stored.size() * 4);
  std::memcpy(d.storage.data(), stored.data(), d.storage.size());
  RenderOutcome r = device().draw(d, w, h, folder("bindings"));
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.image.width, w);
  ASSERT_EQ(r.image.height, h);
  // Row y of the image is the framebuffer's row y: gl_FragCoord.y = y + 0.5 (Vulkan's y runs down).
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float* px = r.image.at(x, y);
      EXPECT_EQ(px[0], x + 0.5f) << x << "," << y;
      EXPECT_EQ(px[1], y + 0.5f) << x << "," << y;
      EXPECT_EQ(px[2], float(y * w + x) + float(1000 * ((y % 2) * 3 + x % 3 + 1)) + float(w * 100000)) << x << "," << y;
      const int i = y * w + x;
      EXPECT_EQ(r.alpha[size_t(i)], 3.25f + float(30000 * i) + 0.5f * float(i)) << x << "," << y;
    }
}

// A draw of `parts`' light loop declarations under a main that writes light p.x's k-th vec4
// (facet_light(p.x), the light loop's one accessor) at pixel (p.x, k) for k < 4, and at
// row 4 the camera position (x = 0) or the ambient colour with the light count.
VulkanDraw light_reader(const std::string& name, const GlslParts& parts) {
  VulkanDraw d;
  d.name = name;
  d.source = "#version 450\n" + parts.library + parts.lights +
             "float facet_visibility(vec3 p, vec3 l, float d, int light) { return 1.0; }\n"
             "layout(location = 0) out vec4 color;\n"
             "void main()\n{\n    ivec2 p = ivec2(gl_FragCoord.xy);\n    FacetLight l = facet_light(p.x);\n"
             "    vec4 v[4] = vec4[4](l.position, l.color, l.spot, l.attenuation);\n"
             "    color = p.y < 4 ? v[p.y] : p.x == 0 ? facet_camera_position\n"
             "          : vec4(facet_ambient.rgb, float(facet_light_count));\n}\n";
  return d;
}

// The draw's pixels show each of the scene's lights, its camera and ambient colour exactly.
void expect_lights(const RenderOutcome& r, const Scene& s) {
  const int w = r.image.width;
  auto px = [&](int x, int y) {
    const float* c = r.image.at(x, y);
    return std::array<float, 4>{c[0], c[1], c[2], r.alpha[size_t(y * w + x)]};
  };
  for (size_t i = 0; i < s.lights.size(); ++i) {
    const Light& l = s.lights[i];
    const Vec3& where = l.type == Light::Type::Directional ? l.direction : l.position;
    EXPECT_EQ(px(int(i), 0)[0], float(where.x)) << i;
    EXPECT_EQ(px(int(i), 0)[3], float(glsl_light::type_code(l.type))) << i;
    EXPECT_EQ(px(int(i), 1)[2], float(l.color[2])) << i;
    EXPECT_EQ(px(int(i), 1)[3], float(l.exponent)) << i;
    EXPECT_EQ(px(int(i), 2)[1], float(l.direction.y)) << i;
    EXPECT_EQ(px(int(i), 2)[3], float(std::cos(l.cutoff * M_PI / 180.0))) << i;
    EXPECT_EQ(px(int(i), 3)[2], float(l.attenuation.quadratic)) << i;
    EXPECT_EQ(px(int(i), 3)[3], float(glsl_light::law_code(l.attenuation.law))) << i;
  }
  EXPECT_EQ(px(0, 4)[2], float(s.camera.position.z));
  EXPECT_EQ(px(1, 4)[0], float(s.ambient[0]));
  EXPECT_EQ(px(1, 4)[3], float(s.lights.size()));
}

// The engine-facing glsl450 (facet generate's: the FacetScene block with FACET_MAX_LIGHTS
// lights), filled as vulkan.h says: facet_scene_block() and the first lights of
// facet_light_buffer() from byte 48, 560 bytes.
TEST(Vulkan, SceneBlockIsWhereTheGeneratedCodeReadsIt) {
  ASSERT_EQ(device().unavailable(), "");
  Material m = load_material((kSource / "examples/materials/blinn_phong.json").string());
  Scene s = load_scene((kSource / "tests/scenes/spot.json").string());
  ASSERT_GE(s.lights.size(), 2u);
  VulkanDraw d = light_reader("scene_block", glsl_parts(compile(m), Target::Glsl450, m.source));
  d.uniforms = facet_scene_block(s);
  EXPECT_EQ(d.uniforms.size(), 48u);
  const std::vector<unsigned char> lights = facet_light_buffer(s);
  EXPECT_EQ(lights.size(), s.lights.size() * 64);
  d.uniforms.insert(d.uniforms.end(), lights.begin(), lights.end());
  d.uniforms.resize(560);
  RenderOutcome r = device().draw(d, 8, 5, folder("scene_block"));
  ASSERT_TRUE(r.ok) << r.error;
  expect_lights(r, s);
}

// The renderers' glsl450 (LightSource::Buffer): 100 lights, more than a G-buffer layer's 96,
// from the storage buffer of set 2, each where the light loop reads it.
TEST(Vulkan, LightBufferHoldsHundredLights) {
  ASSERT_EQ(device().unavailable(), "");
  Material m = load_material((kSource / "examples/materials/blinn_phong.json").string());
  const Scene s = many_objects_scene(1, 100, {});
  ASSERT_EQ(s.lights.size(), 100u);
  VulkanDraw d = light_reader("light_buffer", glsl_parts(compile(m), Target::Glsl450, m.source, LightSource::Buffer));
  d.uniforms = facet_scene_block(s);
  d.storage = facet_light_buffer(s);
  RenderOutcome r = device().draw(d, 100, 5, folder("light_buffer"));
  ASSERT_TRUE(r.ok) << r.error;
  expect_lights(r, s);
}

// A job of 300 objects under 100 lights, one material (code_override takes one).
RenderJob hundred_lights_job(const Material& m) {
  RenderJob job;
  job.scene = many_objects_scene(300, 100, {m});
  job.width = 64;
  job.height = 48;
  return job;
}

double worst_difference(const RenderOutcome& a, const RenderOutcome& b) {
  double worst = 0;
  for (size_t k = 0; k < a.image.rgb.size(); ++k) worst = std::max(worst, double(std::fabs(a.image.rgb[k] - b.image.rgb[k])));
  return worst;
}

// Both Vulkan renderers shade the G-buffer of 100 lights (two layers of its visibility image) as
// the GL renderer draws the scene; the same passes decoding light i + 1's bit for light i, or
// every light's from the first layer, do not.
TEST(Vulkan, HundredLightsShadeAsTheGlRenderer) {
  ASSERT_EQ(device().unavailable(), "");
  const Material m = load_material((kSource / "examples/materials/blinn_phong.json").string());
  RenderJob job = hundred_lights_job(m);
  const RenderOutcome gl = make_renderer("glsl")->render({job}).at(0);
  ASSERT_TRUE(gl.ok) << gl.error;
  for (const bool hlsl : {false, true}) {
    const std::string name = hlsl ? "vulkan-hlsl" : "vulkan";
    job.workdir = folder(name);
    job.code_override.clear();
    const RenderOutcome right = make_renderer(name)->render({job}).at(0);
    ASSERT_TRUE(right.ok) << right.error;
    EXPECT_LE(worst_difference(right, gl), 1e-5) << name;
    const std::string source = hlsl ? hlsl_shading_source(m) : glsl_gbuffer_shading_source(m, Target::Glsl450);
    for (const auto& [good, bad] : {std::pair<std::string, std::string>{"(light % 24)", "((light + 1) % 24)"},
                                    std::pair<std::string, std::string>{"light / 96", "0"}}) {
      const size_t at = source.find(good);
      ASSERT_NE(at, std::string::npos) << name << ": " << good;
      job.code_override = std::string(source).replace(at, good.size(), bad);
      const RenderOutcome wrong = make_renderer(name)->render({job}).at(0);
      ASSERT_TRUE(wrong.ok) << wrong.error;
      std::cout << name << ", " << bad << " for " << good << ": worst |Δ| " << worst_difference(wrong, gl) << "\n";
      EXPECT_GT(worst_difference(wrong, gl), 2e-3) << name << ": " << bad;
    }
  }
}

TEST(Vulkan, GlslangErrorsNameTheFile) {
  ASSERT_EQ(device().unavailable(), "");
  VulkanDraw d;
  d.name = "broken_shader";
  d.source = "#version 450\nlayout(location = 0) out vec4 color;\nvoid main() { color = vec4(undeclared); }\n";
  RenderOutcome r = device().draw(d, 4, 4, folder("broken"));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("broken_shader.frag"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("undeclared"), std::string::npos) << r.error;
}

// A shader that reads a binding the draw does not make: the validation layers say so, and
// the error names the file. Without the layers (Debian's vulkan-validationlayers) this fails.
TEST(Vulkan, ValidationLayersNameTheFile) {
  ASSERT_EQ(device().unavailable(), "");
  ASSERT_TRUE(device().validation_layers()) << "VK_LAYER_KHRONOS_validation is not installed (vulkan-validationlayers)";
  VulkanDraw d;
  d.name = "missing_binding";
  d.source = "#version 450\nlayout(set = 1, binding = 3) uniform sampler2D missing;\n"
             "layout(location = 0) out vec4 color;\nvoid main() { color = texelFetch(missing, ivec2(0), 0); }\n";
  RenderOutcome r = device().draw(d, 4, 4, folder("missing"));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("missing_binding.frag"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("validation layers"), std::string::npos) << r.error;
}
