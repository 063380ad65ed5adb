// The registry: every renderer by the name users type, in the order the commands show them.
#include "renderers/renderer.h"

#include <filesystem>
#include <stdexcept>

#include "core/io.h"
#include "renderers/backends.h"

namespace facet {

const std::vector<RendererEntry>& renderer_registry() {
  static const std::vector<RendererEntry> registry = {
      {{"reference", "the reference", "C++ reference", "C++ reference (double)",
        "facet's C++ ray caster shading with the C++ reference (double)", true},
       make_reference_renderer},
      {{"glsl", "OpenGL", "OpenGL (GLSL)", "OpenGL: generated GLSL (EGL)",
        "the generated GLSL in headless OpenGL (EGL; Mesa llvmpipe without a GPU), RGBA32F", false},
       make_opengl_renderer},
      {{"osl", "Cycles", "Cycles (OSL)", "Cycles: generated OSL (Blender 4.5)",
        "the generated OSL in Blender 4.5's Cycles (CPU, OSL), one Blender process per scene", false},
       make_cycles_renderer},
      {{"pov", "POV-Ray", "POV-Ray", "POV-Ray 3.7: generated scene",
        "the generated POV-Ray scene, 16-bit linear PNG, antialiasing off", false},
       make_povray_renderer},
      {{"vulkan", "Vulkan", "Vulkan (GLSL 4.50)", "Vulkan: generated GLSL 4.50 (SPIR-V)",
        "the generated glsl450 as SPIR-V (glslangValidator -V) on the first Vulkan device (Mesa lavapipe without a "
        "GPU), RGBA32F: a shading pass over the G-buffer the OpenGL ray caster casts",
        false},
       make_vulkan_renderer},
      {{"vulkan-hlsl", "Vulkan (HLSL)", "Vulkan (HLSL)", "Vulkan: generated HLSL (SPIR-V)",
        "the generated HLSL as SPIR-V (glslangValidator -D -V -S frag -e main) on the first Vulkan device, RGBA32F: "
        "the same shading pass over the OpenGL ray caster's G-buffer as vulkan",
        false},
       make_vulkan_hlsl_renderer},
      {{"webgl", "WebGL2", "WebGL2 (ESSL)", "Chromium WebGL2: generated ES 3.00 GLSL",
        "the generated ES 3.00 shader shading the GL ray caster's G-buffer in headless Chromium's WebGL2 "
        "(ANGLE on SwiftShader), RGBA32F", false},
       make_webgl_renderer},
      {{"wgpu", "wgpu", "wgpu (WGSL)", "wgpu: generated WGSL (WebGPU on Vulkan)",
        "the generated WGSL shading the GL ray caster's G-buffer in WebGPU (pip wgpu: wgpu-native on Vulkan, "
        "Mesa lavapipe without a GPU), rgba32float",
        false},
       make_wgpu_renderer},
  };
  return registry;
}

const RendererInfo* find_renderer(const std::string& name) {
  for (const auto& e : renderer_registry())
    if (e.info.name == name) return &e.info;
  return nullptr;
}

const RendererInfo& reference_renderer() {
  for (const auto& e : renderer_registry())
    if (e.info.reference) return e.info;
  throw std::logic_error("facet: the registry has no reference renderer");
}

std::vector<std::string> renderer_names() {
  std::vector<std::string> out;
  for (const auto& e : renderer_registry()) out.push_back(e.info.name);
  return out;
}

std::unique_ptr<Renderer> make_renderer(const std::string& name, const RendererSettings& settings) {
  for (const auto& e : renderer_registry())
    if (e.info.name == name) return e.make(e.info, settings);
  throw std::invalid_argument("no renderer named \"" + name + "\"");
}

std::string job_name(const RenderJob& job) {
  if (!job.name.empty()) return identifier(job.name);
  return (job.material ? identifier(job.material->name) + "_" : std::string()) + identifier(job.scene.name);
}

std::string pass_name(const RenderJob& job, size_t k, size_t passes, const std::string& material) {
  return job_name(job) + (passes > 1 ? "_" + std::to_string(k) + "_" + identifier(material) : "");
}

std::string RenderJob::folder() const {
  return workdir.empty() ? (std::filesystem::path(private_work_folder()) / "render").string() : workdir;
}

std::vector<RenderOutcome> failed_renders(size_t jobs, const std::string& why) {
  std::vector<RenderOutcome> out(jobs);
  for (auto& o : out) o.error = why;
  return out;
}

std::vector<SweepCount> failed_sweeps(size_t jobs, const std::string& target, const std::string& why) {
  std::vector<SweepCount> out(jobs);
  for (auto& c : out) {
    c.target = target;
    c.error = why;
  }
  return out;
}

}  // namespace facet
