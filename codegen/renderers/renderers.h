// facet — the renderers that prove the targets agree: each turns a material and
// a scene into a linear float image sampled at pixel centres.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "core/image.h"
#include "scene/scene.h"

namespace facet {

struct RenderJob {
  // The material under test: it shades every object without a material of its
  // own; absent when every object has one (Scene::has_own_materials()).
  std::optional<Material> material;
  Scene scene;
  int width = 256, height = 256;
  std::string workdir;   // where generated code and raw outputs go (kept for inspection)
  double max_value = 1;  // the largest radiance expected (POV-Ray: sets the exposure that keeps PNGs below 1)
  // POV-Ray: bracket exposures in factors of 2 (16, 8, …) so every pixel of
  // every pass keeps 16-bit relative precision (≤ 1.6e-5 · value); otherwise one
  // exposure for the whole image (error ≤ 7.7e-6 / exposure per pass).
  bool bracket = false;
  // POV-Ray: render the generated file as a user would, in one run with every
  // light at once (Facet_Light = -1: light_group copies), instead of one pass per light.
  bool one_run = false;
  // Render this code instead of generating it (tests feed deliberately wrong targets).
  std::string code_override;
};

// "<material>_<scene>" (or "<scene>" when the scene brings its own materials): names files.
std::string job_name(const RenderJob& job);

struct RenderOutcome {
  bool ok = false;
  std::string error;  // why not, when not ok: the tool's own words where it had some
  Image image;
  std::vector<float> alpha;  // coverage per pixel (1 object, 0 background); empty when the renderer has none
  double seconds = 0;
  std::string log;    // what the tool printed
};

// POV-Ray 3.7: the generated scene, one frame per pass (see pov_plan) and
// exposure, each a linear 16-bit PNG with antialiasing off, rendered as one
// animation; the passes are summed and divided by their exposure.
RenderOutcome render_pov(const RenderJob& job);

// Cycles with OSL inside Blender (pip bpy), many materials in one Blender
// process: codegen/renderers/cycles_render.py, run by `python`. One outcome per
// material, in order; a failed item carries Blender's or the OSL compiler's words.
std::vector<RenderOutcome> render_osl(const std::vector<RenderJob>& jobs, const std::string& python,
                                      std::string& log);
// The Python with bpy: FACET_PYTHON, else the build's .venv, else "python3".
std::string default_python();

// A fragment shader of one's own for GlRenderer::draw(): its GLSL and the values
// of its uniforms, by name ("facet_resolution", "u_lightData[0].position").
// Float, vecN, int and bool uniforms are set by their declared type; names the
// program does not use (the compiler may drop them) are ignored.
struct ShaderDraw {
  std::string name;
  std::string fragment_source;
  std::vector<std::pair<std::string, std::vector<double>>> uniforms;
};

// OpenGL through EGL (Mesa llvmpipe headless): the generated GLSL 3.30 library
// and light loop under a ray-casting main, drawn into an RGBA32F framebuffer.
// One context serves many renders.
class GlRenderer {
 public:
  GlRenderer();
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }  // why there is no context
  const std::string& description() const { return description_; }  // GL_RENDERER and GL_VERSION
  RenderOutcome render(const RenderJob& job);
  // The robustness sweep: a program from glsl_sweep_source() drawn on `grid` × `grid` pixels, raw values.
  RenderOutcome sweep(const std::string& fragment_source, int grid);
  // The fragment shader render() compiles for one material: the generated GLSL under the ray caster.
  static std::string fragment_source(const Material& m);
  // Each shader over the full-screen triangle on width × height pixels: every
  // program is compiled and drawn once first (llvmpipe JIT-compiles a shader at its
  // first draw), then each is drawn twice more, the second time between
  // around(i, true) and around(i, false), glFinish() included, and read back. One outcome per shader,
  // its image the second draw's (rows from the top, alpha as coverage).
  std::vector<RenderOutcome> draw(const std::vector<ShaderDraw>& shaders, int width, int height,
                                  const std::function<void(size_t, bool)>& around = {});

 private:
  struct State;
  State* state_ = nullptr;
  std::string error_, description_;
};

}  // namespace facet
