// facet — the renderers that prove the targets agree, behind one interface: each
// turns materials and scenes into linear float images sampled at pixel centres,
// and runs its target's robustness sweep. The registry knows them by the names
// users type: reference, glsl, osl, pov, webgl.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "core/image.h"
#include "scene/scene.h"
#include "targets/targets.h"

namespace facet {

// ---------------------------------------------------------------- rendering

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
  // POV-Ray: the comparison's tolerance (|Δ| ≤ tolerance · max(1, |reference|)), when a
  // comparison will judge the image: where one exposure's 16 bits cannot meet it for
  // every pixel of the scene's range, exposures are bracketed as coarsely as it allows
  // (RenderOutcome::note says so). 0: as `bracket` says.
  double tolerance = 0;
  // POV-Ray: render the generated file as a user would, in one run with every
  // light at once (Facet_Light = -1: light_group copies), instead of one pass per light.
  bool one_run = false;
  // POV-Ray: how the generated scene draws its objects (facet generate --pov-route).
  PovRoute pov_route = PovRoute::Auto;
  // Render this code instead of generating it (tests feed deliberately wrong targets).
  std::string code_override;
  // Names the job's files in its folder, unique among the jobs that share the folder
  // (facet validate numbers them); empty: from the material's and the scene's names.
  std::string name;
  // The workdir, or the process's private folder (core/io.h) when it is empty: for the renderers
  // whose tools need files (OpenGL writes its shaders only into a given workdir).
  std::string folder() const;
};

// RenderJob::name, else "<material>_<scene>" (or "<scene>" when the scene brings its own
// materials): names files.
std::string job_name(const RenderJob& job);
// The files of pass `k` of `passes` (one per material the scene's objects use): the job's
// name, then the pass's number and material (numbered: two materials' names may fold to one
// identifier).
std::string pass_name(const RenderJob& job, size_t k, size_t passes, const std::string& material);

struct RenderOutcome {
  bool ok = false;
  std::string error;  // why not, when not ok: the tool's own words where it had some
  Image image;
  std::vector<float> alpha;  // coverage per pixel (1 object, 0 background); empty when the renderer has none
  double seconds = 0;
  std::string log;    // what the tool printed
  std::string note;   // a choice the renderer made that the report shows (POV-Ray's bracketed exposures)
};

// What a renderer tells while it works, both optional: finished(i) once job i
// is done (never two calls at once, from whichever thread), step(what) before a
// step of its own that takes a while ("Blender renders 22 materials on single").
struct RenderProgress {
  std::function<void(size_t)> finished;
  std::function<void(const std::string&)> step;
};

// The jobs one after another through `one` (RenderJob → RenderOutcome), each reported
// as it finishes: the render() of a renderer that draws a job at a time.
template <class One>
std::vector<RenderOutcome> render_each(const std::vector<RenderJob>& jobs, const RenderProgress& progress, One&& one) {
  std::vector<RenderOutcome> out;
  out.reserve(jobs.size());
  for (size_t i = 0; i < jobs.size(); ++i) {
    out.push_back(one(jobs[i]));
    if (progress.finished) progress.finished(i);
  }
  return out;
}

// ---------------------------------------------------------------- the robustness sweep

// One material's counts (analysis/sweep.h explains the direction sets).
struct SweepCount {
  std::string target;
  size_t samples = 0;
  size_t nan = 0, inf = 0, negative = 0;  // channels, among all samples
  std::string error;                      // the target could not run
  bool ok() const { return error.empty() && samples > 0 && nan + inf + negative == 0; }
};

struct SweepJob {
  Material material;
  std::string source;  // when not empty, replaces the generated harness (tests feed faults)
};

struct SweepSettings {
  // The direction-set grid's side: OpenGL takes it whole, Cycles at most 512,
  // POV-Ray at most 256; the reference always sweeps its 512² grid.
  int grid = 1024;
  size_t random = 0;    // the reference: random direction sets besides its grid
  std::string workdir;  // where the harnesses' files go
};

// ---------------------------------------------------------------- the interface

// What the registry knows of a renderer without starting it.
struct RendererInfo {
  std::string name;     // what users type: "glsl"
  std::string tool;     // what messages call it: "OpenGL"
  std::string label;    // a column's heading: "OpenGL (GLSL)"
  std::string title;    // the docs pages' caption: "OpenGL: generated GLSL (EGL)"
  std::string summary;  // one line of help: what it runs and how
  bool reference = false;  // the C++ reference: the image every other renderer is compared with
};

// How the renderers are set up, beyond their jobs.
struct RendererSettings {
  std::string python;  // the Python with bpy, for Cycles; empty: default_python()
};

class Renderer {
 public:
  virtual ~Renderer() = default;
  virtual const RendererInfo& info() const = 0;
  // Why it cannot run here (a tool not installed, no OpenGL context), or "" when
  // it can; render() and sweep() then fail every job with this reason.
  virtual std::string unavailable() const { return ""; }
  // The tool as it describes itself (OpenGL: GL_RENDERER and GL_VERSION), or "".
  virtual std::string description() const { return ""; }
  // Every job, as fast as the tool allows (Cycles: one Blender process for all
  // the jobs of a scene and size; POV-Ray: two processes at once). One outcome
  // per job, in order; a job that failed says why.
  virtual std::vector<RenderOutcome> render(const std::vector<RenderJob>& jobs, const RenderProgress& progress = {}) = 0;
  // The robustness sweep of every job's material: one count per job, in order.
  virtual std::vector<SweepCount> sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) = 0;
};

// ---------------------------------------------------------------- the registry

struct RendererEntry {
  RendererInfo info;
  std::unique_ptr<Renderer> (*make)(const RendererInfo& info, const RendererSettings& settings);
};

// reference, glsl, osl, pov, webgl: the order the commands run and show them in.
const std::vector<RendererEntry>& renderer_registry();
const RendererInfo* find_renderer(const std::string& name);  // null for an unknown name
std::vector<std::string> renderer_names();
const RendererInfo& reference_renderer();  // the image every other renderer is compared with
// Starts the renderer `name` (an OpenGL context, …); throws std::invalid_argument for an unknown name.
std::unique_ptr<Renderer> make_renderer(const std::string& name, const RendererSettings& settings = {});

// The Python with bpy: FACET_PYTHON, else the build's .venv, else "python3".
std::string default_python();
// default_python()'s choice given the environment's value and the build's path (either may be
// null): a build path this user cannot look at (no permission, a link loop, a name too long)
// falls back to "python3" instead of throwing (issue 28).
std::string choose_python(const char* environment, const char* build_python);

}  // namespace facet
