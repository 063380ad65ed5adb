// WGSL through WebGPU ("wgpu" in the registry): the GL renderer's ray caster casts each
// job's G-buffer (renderers/gbuffer.h), facet writes the generated WGSL's shading pass
// (wgsl_gbuffer_shading_source()), the G-buffer's images and the FacetScene uniform
// buffer, and codegen/renderers/harness/wgpu_render.py (embedded) draws every pass of
// every job in one Python process with pip wgpu (wgpu-native; Mesa's lavapipe here).
#include <chrono>
#include <cstring>
#include <filesystem>
#include <memory>

#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "catalog/program.h"
#include "core/io.h"
#include "renderers/backends.h"
#include "renderers/gbuffer.h"
#include "renderers/harness.h"
#include "renderers/opengl.h"
#include "renderers/process.h"
#include "targets/targets.h"
#include "targets/texture_code.h"

namespace facet {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The shading pass's FacetScene (targets.h, LightSource::Buffer), laid out as the head of
// GLSL's std140 block: camera at 0, ambient at 16, the light count at 32; 48 bytes.
std::string scene_uniform_bytes(const GBuffer& g) {
  std::string b(48, '\0');
  std::memcpy(&b[0], g.camera_position.data(), 12);
  std::memcpy(&b[16], g.ambient.data(), 12);
  const int32_t count = g.light_count;
  std::memcpy(&b[32], &count, 4);
  return b;
}

// Its storage buffer of lights, 64 bytes each; one light's bytes at least (a runtime-sized
// array's binding must hold one element).
std::string light_bytes(const GBuffer& g) {
  std::string b(std::max<size_t>(g.lights.size(), 16) * sizeof(float), '\0');
  if (!g.lights.empty()) std::memcpy(&b[0], g.lights.data(), g.lights.size() * sizeof(float));
  return b;
}

void write_floats(const std::string& path, const std::vector<const std::vector<float>*>& arrays) {
  write_file_atomic(path, [&](std::ostream& out) {
    for (const auto* a : arrays) out.write(reinterpret_cast<const char*>(a->data()), std::streamsize(a->size() * 4));
  });
}

// A Python given as a relative path made absolute: the harness runs in the job's folder.
std::string run_from_anywhere(const std::string& python) {
  const fs::path p(python);
  return p.is_relative() && p.has_parent_path() ? fs::absolute(p).string() : python;
}

// Material pass `pass` of one job for the harness: the shading pass's WGSL, its uniforms and
// lights, the G-buffer as the pass reads it and the material's images written into `dir` as `base`.*.
json pass_entry(const RenderJob& job, const Material& m, const GBuffer& g, size_t pass, const fs::path& dir,
                const std::string& base) {
  const std::string stem = (dir / base).string();
  write_file_atomic(stem + ".wgsl", job.code_override.empty() ? wgsl_gbuffer_shading_source(m) : job.code_override);
  write_file_atomic(stem + ".uniforms", scene_uniform_bytes(g));
  write_file_atomic(stem + ".lights", light_bytes(g));
  const std::vector<float> position = g.pass_position(pass);
  std::vector<const std::vector<float>*> images = {&position};
  for (int i = 1; i < GBuffer::kImages; ++i) images.push_back(&g.images[size_t(i)]);
  write_floats(stem + ".gbuffer", images);
  json textures = json::array();
  int binding = 1;  // templates/wgsl: binding 0 is the scene's uniform buffer
  for (const auto& c : image_calls(compile(m))) {
    const std::string file = fmt::format("{}.texture{}", stem, binding);
    write_floats(file, {&c.texels->rgba});
    textures.push_back({{"binding", binding++}, {"width", c.texels->width}, {"height", c.texels->height},
                        {"file", file}});
  }
  fs::remove(stem + "_wgpu.pfm");
  fs::remove(stem + "_wgpu.alpha.pfm");
  return {{"name", m.name},         {"width", g.width},           {"height", g.height},
          {"layers", g.layers},      {"images", GBuffer::kImages}, {"wgsl", stem + ".wgsl"},
          {"uniforms", stem + ".uniforms"},
          {"lights", stem + ".lights"}, {"gbuffer", stem + ".gbuffer"}, {"textures", textures},
          {"output", stem + "_wgpu"}};
}

// What the harness drew for one pass, added into `out` (the passes add up; coverage is their maximum).
void add_pass(const json& entry, const json& result, RenderOutcome& out) {
  if (!result.value("ok", false)) {
    out.error = fmt::format("wgpu could not draw the WGSL of \"{}\": {}", entry["name"].get<std::string>(),
                            result.value("error", std::string("failed")));
    return;
  }
  const std::string output = entry["output"];
  Image img = read_pfm(output + ".pfm");
  int w = 0, h = 0;
  std::vector<float> alpha = read_pfm_grey(output + ".alpha.pfm", w, h);
  if (img.width != out.image.width || img.height != out.image.height || w != img.width || h != img.height) {
    out.error = "wgpu wrote an image of the wrong size";
    return;
  }
  for (size_t k = 0; k < img.rgb.size(); ++k) out.image.rgb[k] += img.rgb[k];
  for (size_t k = 0; k < alpha.size(); ++k) out.alpha[k] = std::max(out.alpha[k], alpha[k]);
  out.seconds += result.value("seconds", 0.0);
}

class WgpuRenderer : public Renderer {
 public:
  WgpuRenderer(const RendererInfo& info, const RendererSettings& settings)
      : info_(info), python_(run_from_anywhere(settings.python.empty() ? default_python() : settings.python)) {}
  const RendererInfo& info() const override { return info_; }
  std::string unavailable() const override {
    if (find_program(python_).empty()) return fmt::format("cannot run {0}: {0}: not found on PATH", python_);
    return gl().ok() ? "" : "the G-buffer's OpenGL: " + gl().error();
  }
  std::string description() const override { return description_; }

  std::vector<RenderOutcome> render(const std::vector<RenderJob>& jobs, const RenderProgress& progress) override;
  std::vector<SweepCount> sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) override;

 private:
  GlRenderer& gl() const {
    if (!gl_) gl_ = std::make_unique<GlRenderer>();
    return *gl_;
  }
  // Casts job i's G-buffers and writes its passes' files, their entries appended to `entries`;
  // false (the reason in out.error) when it cannot.
  bool prepare(const RenderJob& job, json& entries, RenderOutcome& out) const;
  json run_harness(const json& batch, const fs::path& dir, const std::string& name, std::string& error);

  const RendererInfo& info_;
  std::string python_;
  std::string description_;
  mutable std::unique_ptr<GlRenderer> gl_;  // casts the G-buffers
};

bool WgpuRenderer::prepare(const RenderJob& job, json& entries, RenderOutcome& out) const {
  const auto start = std::chrono::steady_clock::now();
  std::vector<const Material*> passes;
  try {
    passes = material_passes(job);
  } catch (const std::runtime_error& e) {
    out.error = e.what();
    return false;
  }
  if (!job.code_override.empty() && passes.size() != 1) {
    out.error = "code_override needs a scene with one material";
    return false;
  }
  fs::create_directories(job.folder());
  const fs::path dir = fs::absolute(job.folder());
  const GBufferOutcome g = cast_gbuffer(gl(), job);  // once for every pass
  if (!g.ok) {
    out.error = "the G-buffer: " + g.error;
    return false;
  }
  for (size_t k = 0; k < passes.size(); ++k) {
    std::string base = pass_name(job, k, passes.size(), passes[k]->name);
    // Jobs of one batch may share a name and a folder (a test's variants of one material): numbered then.
    auto taken = [&](const std::string& b) {
      for (const auto& e : entries)
        if (e["output"] == (dir / b).string() + "_wgpu") return true;
      return false;
    };
    std::string unique = base;
    for (int n = 2; taken(unique); ++n) unique = fmt::format("{}_{}", base, n);
    entries.push_back(pass_entry(job, *passes[k], g.gbuffer, k, dir, unique));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

// One Python process draws every job or sweep of `batch`; its result, or why there is none.
json WgpuRenderer::run_harness(const json& batch, const fs::path& dir, const std::string& name, std::string& error) {
  const fs::path script = dir / "wgpu_render.py", job = dir / name;
  write_file_atomic(script.string(), embedded_harness().at("wgpu_render.py"));
  write_file_atomic(job.string(), batch.dump(1));
  fs::remove(job.string() + ".result.json");
  ProcessResult r = run_process({python_, script.string(), job.string()}, dir.string());
  try {
    json result = json::parse(read_file(job.string() + ".result.json"));
    if (result.contains("error")) error = result["error"];
    description_ = result.value("adapter", std::string()) + ", wgpu " + result.value("wgpu", std::string("?"));
    return result;
  } catch (const std::exception&) {
    error = fmt::format("{} {} exited with {} and wrote no result:\n{}", python_, script.string(), r.exit_code, r.output);
    return {};
  }
}

std::vector<RenderOutcome> WgpuRenderer::render(const std::vector<RenderJob>& jobs, const RenderProgress& progress) {
  if (std::string why = unavailable(); !why.empty()) return failed_renders(jobs.size(), why);
  std::vector<RenderOutcome> out(jobs.size());
  json entries = json::array();
  std::vector<size_t> first(jobs.size() + 1, 0);  // job i's entries: [first[i], first[i + 1])
  for (size_t i = 0; i < jobs.size(); ++i) {
    first[i] = entries.size();
    out[i].image = Image(jobs[i].width, jobs[i].height);
    out[i].alpha.assign(size_t(jobs[i].width) * size_t(jobs[i].height), 0);
    if (!prepare(jobs[i], entries, out[i])) entries.erase(entries.begin() + long(first[i]), entries.end());
  }
  first[jobs.size()] = entries.size();
  std::string error;
  json result;
  if (!entries.empty()) {
    if (progress.step) progress.step(fmt::format("wgpu draws {} passes", entries.size()));
    fs::create_directories(jobs.front().folder());
    result = run_harness(json({{"jobs", entries}}), fs::absolute(jobs.front().folder()), "wgpu_job.json", error);
  }
  for (size_t i = 0; i < jobs.size(); ++i) {
    for (size_t e = first[i]; e < first[i + 1] && out[i].error.empty(); ++e) {
      if (!error.empty() || !result.contains("results") || e >= result["results"].size()) {
        out[i].error = error.empty() ? "wgpu wrote no result for this pass" : error;
        break;
      }
      try {
        add_pass(entries[e], result["results"][e], out[i]);
      } catch (const IoError& x) {
        out[i].error = x.what();
      }
    }
    out[i].ok = out[i].error.empty();
    if (progress.finished) progress.finished(i);
  }
  return out;
}

// One Python process draws every material's sweep (wgsl_sweep_source()) and counts its values.
std::vector<SweepCount> WgpuRenderer::sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) {
  if (find_program(python_).empty()) return failed_sweeps(jobs.size(), "wgsl", "cannot run " + python_);
  std::vector<SweepCount> out(jobs.size());
  // Without a workdir, a folder in this process's own (core/io.h).
  const fs::path dir = fs::absolute(settings.workdir.empty() ? fs::path(private_work_folder()) / "wgpu-sweep"
                                                            : fs::path(settings.workdir));
  fs::create_directories(dir);
  json items = json::array();
  for (size_t i = 0; i < jobs.size(); ++i) {
    out[i].target = "wgsl";
    // Numbered: two materials may share a name.
    const std::string path = (dir / fmt::format("{:03}_{}_sweep.wgsl", i, identifier(jobs[i].material.name))).string();
    write_file_atomic(path, jobs[i].source.empty() ? wgsl_sweep_source(jobs[i].material) : jobs[i].source);
    items.push_back({{"name", jobs[i].material.name}, {"wgsl", path}, {"grid", settings.grid}});
  }
  std::string error;
  json result = run_harness(json({{"sweeps", items}}), dir, "wgpu_sweep_job.json", error);
  for (size_t i = 0; i < jobs.size(); ++i) {
    const json* r = result.contains("sweeps") && i < result["sweeps"].size() ? &result["sweeps"][i] : nullptr;
    if (!r || !r->value("ok", false)) {
      out[i].error = r ? r->value("error", std::string("failed")) : error.empty() ? "wgpu wrote no count" : error;
      continue;
    }
    out[i].samples = r->value("samples", size_t(0));
    out[i].nan = r->value("nan", size_t(0));
    out[i].inf = r->value("inf", size_t(0));
    out[i].negative = r->value("negative", size_t(0));
  }
  return out;
}

}  // namespace

std::unique_ptr<Renderer> make_wgpu_renderer(const RendererInfo& info, const RendererSettings& settings) {
  return std::make_unique<WgpuRenderer>(info, settings);
}

}  // namespace facet
