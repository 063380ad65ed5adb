// facet — the G-buffer (docs/architecture.md, "The G-buffer"): the GL renderer's
// ray caster (renderers/harness/raycast.glsl under FACET_GBUFFER) casts a job's
// scene once per material pass into seven RGBA32F images, and the renderers of
// other targets shade them with a small pass in their own language
// (targets.h, glsl_gbuffer_shading_source(); the same main in each target) instead
// of each re-implementing the ray caster.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "renderers/renderer.h"

namespace facet {

class GlRenderer;

struct GBuffer {
  // The seven images, in this order (the shading pass's samplers
  // facet_gbuffer_position … facet_gbuffer_visibility_high):
  //  0 position: p (world space); w 1 shaded in this pass, 0 a hit drawn black
  //    (another pass's object: output (0, 0, 0, 1)), -1 background (output 0)
  //  1 normal: the unit surface normal n; 2 view: v = -(the ray's unit direction)
  //  3 uv tangent: facet_uv_tangent_at() (xyz, w = ±1), for normal maps
  //  4 uv: texture coordinate sets 0 (xy) and 1 (zw)
  //  5, 6 visibility of lights 0-3 and 4-7 (1 lit, 0 in shadow; 0 beyond the scene's lights)
  static constexpr int kImages = 7;
  enum Image { Position, Normal, View, UvTangent, Uv, VisibilityLow, VisibilityHigh };
  int width = 0, height = 0;
  // RGBA, width × height texels each, texel (x, y) at 4·(y·width + x), y = 0 the
  // bottom row (OpenGL's order).
  std::array<std::vector<float>, kImages> images;

  // What the shading pass's light loop is given: the values the GL renderer sets
  // (targets/glsl_lights.h encodes a light). lights holds 16 floats a light, FacetLight's
  // four vec4 in order: position (w type), color (a spot exponent), spot (w cos cutoff),
  // attenuation (w law).
  std::array<float, 3> camera_position{}, ambient{};
  int light_count = 0;
  std::vector<float> lights;

  // Image i's sampler in the shading pass: "facet_gbuffer_position" … "facet_gbuffer_visibility_high".
  static std::string sampler(int image) {
    const char* names[kImages] = {"position", "normal", "view", "uv_tangent", "uv", "visibility_low", "visibility_high"};
    return std::string("facet_gbuffer_") + names[image];
  }
  const float* texel(int image, int x, int y) const {
    return &images[size_t(image)][(size_t(y) * size_t(width) + size_t(x)) * 4];
  }
};

// The distinct materials of a job's scene, in object order: one pass each, as every
// renderer that draws pass by pass takes them (the material under test for the
// objects without one of their own). pass_of, when given, gets each object's pass.
// Throws std::runtime_error (the scene's words) when an object has no material.
std::vector<const Material*> material_passes(const RenderJob& job, std::vector<size_t>* pass_of = nullptr);

// The shading pass's light-loop uniforms by name, the values above (what GlRenderer
// sets): facet_camera_position, facet_ambient, facet_light_count and
// facet_lights[i].position, .color, .spot, .attenuation.
std::vector<std::pair<std::string, std::vector<double>>> shading_uniforms(const GBuffer& g);

struct GBufferOutcome {
  bool ok = false;
  std::string error;  // why not: GL's words where it had some
  GBuffer gbuffer;
};

// The G-buffer of pass `pass` (an index into material_passes(job)) of `job`, cast by
// `gl`'s context at job.width × job.height; its source written into job.workdir
// (as <job>[_<material>].gbuffer.frag) when there is one.
GBufferOutcome cast_gbuffer(GlRenderer& gl, const RenderJob& job, size_t pass);

}  // namespace facet
