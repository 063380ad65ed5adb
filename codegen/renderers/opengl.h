// facet — the OpenGL renderer ("glsl" in the registry), and what else the cost
// measurement and the benchmarks draw with it: shaders of their own.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "renderers/gbuffer.h"
#include "renderers/renderer.h"

namespace facet {

// A fragment shader of one's own for GlRenderer::draw(): its GLSL and the values
// of its uniforms, by name ("facet_resolution", "u_lightData[0].position").
// Float, vecN, int and bool uniforms are set by their declared type; names the
// program does not use (the compiler may drop them) are ignored.
struct ShaderDraw {
  std::string name;
  std::string fragment_source;
  std::vector<std::pair<std::string, std::vector<double>>> uniforms;
};
// A texture for GlRenderer::draw(): an RGBA32F image, nearest-filtered (read it with
// texelFetch), bound to the sampler uniform of its name; rgba holds width × height
// texels, row 0 first; with `layers`, a 2D array (sampler2DArray) of that many such images
// one after the other; with `buffer`, a buffer texture (samplerBuffer) of rgba's texels.
struct ShaderTexture {
  std::string name;
  int width = 0, height = 0;
  std::vector<float> rgba;
  int layers = 0;
  bool buffer = false;
};

// OpenGL through EGL (Mesa llvmpipe headless): the generated GLSL 3.30 library
// and light loop under a ray-casting main, drawn into an RGBA32F framebuffer.
// One context serves many renders.
class GlRenderer : public Renderer {
 public:
  GlRenderer();
  ~GlRenderer() override;
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;
  const RendererInfo& info() const override;  // the registry's "glsl"
  std::string unavailable() const override { return error_; }  // why there is no context
  std::string description() const override { return description_; }  // GL_RENDERER and GL_VERSION
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

  // One after another, in the one context.
  std::vector<RenderOutcome> render(const std::vector<RenderJob>& jobs, const RenderProgress& progress = {}) override;
  RenderOutcome render(const RenderJob& job);
  // A program from glsl_sweep_source() drawn on grid × grid pixels, its raw values counted.
  std::vector<SweepCount> sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) override;
  // The fragment shader render() compiles for one material: the generated GLSL under the ray caster;
  // with `gbuffer`, the same under FACET_GBUFFER, which writes the G-buffer instead (renderers/gbuffer.h).
  static std::string fragment_source(const Material& m, bool gbuffer = false);
  // The G-buffer of `job`, every material pass at once (renderers/gbuffer.h, cast_gbuffer()).
  GBufferOutcome gbuffer(const RenderJob& job);
  // Each shader over the full-screen triangle on width × height pixels: every
  // program is compiled and drawn once first (llvmpipe JIT-compiles a shader at its
  // first draw), then each is drawn twice more, the second time between
  // around(i, true) and around(i, false), glFinish() included, and read back. One outcome per shader,
  // its image the second draw's (rows from the top, alpha as coverage). textures[i], when
  // there, are shader i's textures (on units 0, 1, …).
  std::vector<RenderOutcome> draw(const std::vector<ShaderDraw>& shaders, int width, int height,
                                  const std::function<void(size_t, bool)>& around = {},
                                  const std::vector<std::vector<ShaderTexture>>& textures = {});

 private:
  struct State;
  RenderOutcome sweep_draw(const std::string& fragment_source, int grid);
  State* state_ = nullptr;
  std::string error_, description_;
};

}  // namespace facet
