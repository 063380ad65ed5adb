// facet — the G-buffer (docs/architecture.md, "The G-buffer"): the GL renderer's
// ray caster (renderers/harness/raycast.glsl under FACET_GBUFFER) casts a job's
// scene once, every material pass at a time, into seven RGBA32F images, and the renderers
// of other targets shade them pass by pass with a small pass in their own language
// (targets.h, glsl_gbuffer_shading_source(); the same main in each target) instead of
// each re-implementing the ray caster.
#pragma once

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "renderers/renderer.h"
#include "targets/glsl_lights.h"

namespace facet {

class GlRenderer;

struct GBuffer {
  // The seven images, in this order (the shading pass's samplers facet_gbuffer_position …
  // facet_gbuffer_visibility):
  //  0 position: p (world space); w the material pass of the object hit (0, 1, …: an index
  //    into material_passes(job)), -1 background. A shading pass reads it as pass_position()
  //    gives it: w 1 shaded in this pass, 0 a hit drawn black (another pass's object: output
  //    (0, 0, 0, 1)), -1 background (output 0)
  //  1 normal: the unit surface normal n; 2 view: v = -(the ray's unit direction)
  //  3 uv tangent: facet_uv_tangent_at() (xyz, w = ±1), for normal maps
  //  4 uv: texture coordinate sets 0 (xy) and 1 (zw)
  //  5 color0: the vertex colour (glTF's COLOR_0, RGBA), a mesh's blended barycentrically; white
  //    on spheres, squares and meshes without colours
  //  6 visibility: `layers` layers (a 2D array), light i's bit (lit()) is bit i mod 24 of
  //    channel (i / 24) mod 4 of layer i / 96 (targets/glsl_lights.h): 1 lit, 0 in shadow, 0
  //    where the surface faces away from the light by more than kHorizon (n·l < −kHorizon,
  //    where the light loop never asks) and beyond the scene's lights. Each channel is an
  //    integer below 2^24, which float32 holds exactly, so every language decodes the same bits.
  static constexpr int kImages = 7;
  enum Image { Position, Normal, View, UvTangent, Uv, Color0, Visibility };
  static constexpr double kHorizon = 1e-3;
  int width = 0, height = 0;
  int layers = 1;  // the visibility image's: max(1, ⌈lights / 96⌉)
  // RGBA, width × height texels each (the visibility image: `layers` of them, one after the
  // other), texel (x, y) at 4·(y·width + x), y = 0 the bottom row (OpenGL's order).
  std::array<std::vector<float>, kImages> images;

  // What the shading pass's light loop is given: the values the GL renderer sets
  // (targets/glsl_lights.h encodes a light). lights holds 16 floats a light, FacetLight's
  // four vec4 in order: position (w type), color (a spot exponent), spot (w cos cutoff),
  // attenuation (w law).
  std::array<float, 3> camera_position{}, ambient{};
  int light_count = 0;
  std::vector<float> lights;

  // Image i's sampler in the shading pass: "facet_gbuffer_position" … "facet_gbuffer_visibility".
  static std::string sampler(int image) {
    const char* names[kImages] = {"position", "normal", "view", "uv_tangent", "uv", "color0", "visibility"};
    return std::string("facet_gbuffer_") + names[image];
  }
  // The visibility image's layers for `lights` lights.
  static int layers_for(int lights) {
    return std::max(1, (lights + glsl_light::kVisibilityLayerLights - 1) / glsl_light::kVisibilityLayerLights);
  }
  const float* texel(int image, int x, int y, int layer = 0) const {
    return &images[size_t(image)][((size_t(layer) * size_t(height) + size_t(y)) * size_t(width) + size_t(x)) * 4];
  }
  // Light i's bit of the visibility image at texel (x, y), decoded as every shading pass decodes it.
  bool lit(int x, int y, int light) const;
  // Image 0 as material pass `pass`'s shading pass reads it: w 1 where that pass's objects
  // were hit, 0 where another pass's, −1 the background.
  std::vector<float> pass_position(size_t pass) const;
};

// The distinct materials of a job's scene, in object order: one pass each, as every
// renderer that draws pass by pass takes them (the material under test for the
// objects without one of their own). pass_of, when given, gets each object's pass.
// Throws std::runtime_error (the scene's words) when an object has no material.
std::vector<const Material*> material_passes(const RenderJob& job, std::vector<size_t>* pass_of = nullptr);

// The shading pass's uniforms by name, the values above (what GlRenderer sets): facet_camera_position,
// facet_ambient and facet_light_count. The lights themselves are a buffer or texture (below).
std::vector<std::pair<std::string, std::vector<double>>> shading_uniforms(const GBuffer& g);

// The lights as ES 3.00's facet_light_texture (targets.h, LightSource::Buffer): glsl_light::kLightsPerRow
// lights a row, 4 texels each; width × height RGBA texels, row 0 first; at least one texel.
struct LightTexture {
  int width = 1, height = 1;
  std::vector<float> rgba;
};
LightTexture light_texture(const GBuffer& g);

struct GBufferOutcome {
  bool ok = false;
  std::string error;  // why not: GL's words where it had some
  GBuffer gbuffer;
};

// The G-buffer of every material pass of `job` at once, cast by `gl`'s context at
// job.width × job.height; its source written into job.workdir (as <job>.gbuffer.frag)
// when there is one.
GBufferOutcome cast_gbuffer(GlRenderer& gl, const RenderJob& job);

}  // namespace facet
