// The G-buffer's parts that need no GL context (renderers/gbuffer.h): the material passes,
// the visibility image's decoding, what a shading pass reads besides the images.
#include "renderers/gbuffer.h"

#include <algorithm>

namespace facet {

std::vector<const Material*> material_passes(const RenderJob& job, std::vector<size_t>* pass_of) {
  const Scene& s = job.scene;
  const Material* fallback = job.material ? &*job.material : nullptr;
  std::vector<const Material*> passes;
  if (pass_of) pass_of->assign(s.objects.size(), 0);
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Material* m = &s.material_of(i, fallback);
    auto it = std::find(passes.begin(), passes.end(), m);
    if (pass_of) (*pass_of)[i] = size_t(it - passes.begin());
    if (it == passes.end()) passes.push_back(m);
  }
  return passes;
}

bool GBuffer::lit(int x, int y, int light) const {
  const float* word = texel(Visibility, x, y, light / glsl_light::kVisibilityLayerLights);
  const int bits = int(word[(light / glsl_light::kVisibilityBits) % 4]);
  return (bits >> (light % glsl_light::kVisibilityBits)) & 1;
}

std::vector<float> GBuffer::pass_position(size_t pass) const {
  std::vector<float> out = images[Position];
  for (size_t i = 3; i < out.size(); i += 4)
    if (out[i] >= 0) out[i] = out[i] == float(pass) ? 1.0f : 0.0f;
  return out;
}

std::vector<std::pair<std::string, std::vector<double>>> shading_uniforms(const GBuffer& g) {
  auto values = [](const float* v, size_t n) { return std::vector<double>(v, v + n); };
  return {{"facet_camera_position", values(g.camera_position.data(), 3)},
          {"facet_ambient", values(g.ambient.data(), 3)},
          {"facet_light_count", {double(g.light_count)}}};
}

LightTexture light_texture(const GBuffer& g) {
  const int per_row = glsl_light::kLightsPerRow;
  LightTexture t;
  t.width = 4 * std::clamp(g.light_count, 1, per_row);
  t.height = std::max(1, (g.light_count + per_row - 1) / per_row);
  t.rgba.assign(size_t(t.width) * size_t(t.height) * 4, 0.0f);
  for (int i = 0; i < g.light_count; ++i) {
    const size_t at = (size_t(i / per_row) * size_t(t.width) + size_t(4 * (i % per_row))) * 4;
    std::copy_n(g.lights.begin() + ptrdiff_t(i) * 16, 16, t.rgba.begin() + ptrdiff_t(at));
  }
  return t;
}

}  // namespace facet
