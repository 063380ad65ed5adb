// The Vulkan machinery (renderers/vulkan.h) on its own: what a draw binds reaches the
// shader where vulkan.h says, pixels come back in facet's order, the FacetScene block
// holds the scene's numbers where the generated glsl450 reads them, and glslang's and
// the validation layers' complaints name the file.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <unistd.h>

#include "catalog/material.h"
#include "catalog/program.h"
#include "renderers/vulkan.h"
#include "scene/scene.h"
#include "targets/glsl_lights.h"
#include "targets/targets.h"

namespace fs = std::filesystem;
using namespace facet;

namespace {

const fs::path kSource = FACET_SOURCE_DIR;

std::string folder(const std::string& name) {
  return (fs::temp_directory_path() / ("facet-vulkan-" + std::to_string(::getpid())) / name).string();
}

VulkanDevice& device() {
  static VulkanDevice d;
  return d;
}

// Every binding of vulkan.h at once: the uniform block (a float and an int), a 3×2 texture in
// set 0, an image of one texel per pixel in set 1, the push constants; the pixel centre from gl_FragCoord.
const char* kEveryBinding = R"(#version 450
layout(std140, set = 0, binding = 0) uniform Block { vec4 offset; int count; };
layout(set = 0, binding = 1) uniform sampler2D image;
layout(set = 1, binding = 0) uniform sampler2D values;
layout(push_constant) uniform Size { ivec2 size; };
layout(location = 0) out vec4 color;
void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float texel = texelFetch(image, ivec2(p.x % 3, p.y % 2), 0).r;
    color = vec4(gl_FragCoord.xy, texelFetch(values, p, 0).x + texel + float(size.x * 100000), offset.x + float(count));
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
  d.images = {{w, h, values.data()}};
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
      EXPECT_EQ(r.alpha[size_t(y * w + x)], 3.25f);
    }
}

// The generated glsl450's own FacetScene declaration (glsl_parts), filled by facet_scene_block():
// pixel (i, k) is light i's k-th vec4, row 4 the camera and the ambient colour, with the count.
TEST(Vulkan, SceneBlockIsWhereTheGeneratedCodeReadsIt) {
  ASSERT_EQ(device().unavailable(), "");
  Material m = load_material((kSource / "examples/materials/blinn_phong.json").string());
  Scene s = load_scene((kSource / "tests/scenes/spot.json").string());
  ASSERT_GE(s.lights.size(), 2u);
  GlslParts parts = glsl_parts(compile(m), Target::Glsl450, m.source);
  VulkanDraw d;
  d.name = "scene_block";
  d.source = "#version 450\n" + parts.library + parts.lights +
             "float facet_visibility(vec3 p, vec3 l, float d, int light) { return 1.0; }\n"
             "layout(location = 0) out vec4 color;\n"
             "void main()\n{\n    ivec2 p = ivec2(gl_FragCoord.xy);\n    FacetLight l = facet_lights[p.x];\n"
             "    vec4 v[4] = vec4[4](l.position, l.color, l.spot, l.attenuation);\n"
             "    color = p.y < 4 ? v[p.y] : p.x == 0 ? facet_camera_position\n"
             "          : vec4(facet_ambient.rgb, float(facet_light_count));\n}\n";
  d.uniforms = facet_scene_block(s);
  EXPECT_EQ(d.uniforms.size(), 560u);
  RenderOutcome r = device().draw(d, 8, 5, folder("scene_block"));
  ASSERT_TRUE(r.ok) << r.error;
  auto px = [&](int x, int y) {
    const float* c = r.image.at(x, y);
    return std::array<float, 4>{c[0], c[1], c[2], r.alpha[size_t(y * 8 + x)]};
  };
  for (size_t i = 0; i < s.lights.size(); ++i) {
    const Light& l = s.lights[i];
    const Vec3& where = l.type == Light::Type::Directional ? l.direction : l.position;
    EXPECT_EQ(px(int(i), 0)[0], float(where.x));
    EXPECT_EQ(px(int(i), 0)[3], float(glsl_light::type_code(l.type)));
    EXPECT_EQ(px(int(i), 1)[2], float(l.color[2]));
    EXPECT_EQ(px(int(i), 1)[3], float(l.exponent));
    EXPECT_EQ(px(int(i), 2)[1], float(l.direction.y));
    EXPECT_EQ(px(int(i), 2)[3], float(std::cos(l.cutoff * M_PI / 180.0)));
    EXPECT_EQ(px(int(i), 3)[1], float(l.attenuation.linear));
    EXPECT_EQ(px(int(i), 3)[3], float(glsl_light::law_code(l.attenuation.law)));
  }
  EXPECT_EQ(px(0, 4)[2], float(s.camera.position.z));
  EXPECT_EQ(px(1, 4)[0], float(s.ambient[0]));
  EXPECT_EQ(px(1, 4)[3], float(s.lights.size()));
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
