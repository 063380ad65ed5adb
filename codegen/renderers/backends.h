// facet — the registry's renderers, each made by its own file (renderers/renderer.cpp lists them).
#pragma once

#include <memory>

#include "renderers/renderer.h"

namespace facet {

std::unique_ptr<Renderer> make_reference_renderer(const RendererInfo& info, const RendererSettings& settings);
std::unique_ptr<Renderer> make_opengl_renderer(const RendererInfo& info, const RendererSettings& settings);
std::unique_ptr<Renderer> make_cycles_renderer(const RendererInfo& info, const RendererSettings& settings);
std::unique_ptr<Renderer> make_povray_renderer(const RendererInfo& info, const RendererSettings& settings);
std::unique_ptr<Renderer> make_vulkan_renderer(const RendererInfo& info, const RendererSettings& settings);
std::unique_ptr<Renderer> make_vulkan_hlsl_renderer(const RendererInfo& info, const RendererSettings& settings);
std::unique_ptr<Renderer> make_webgl_renderer(const RendererInfo& info, const RendererSettings& settings);
std::unique_ptr<Renderer> make_wgpu_renderer(const RendererInfo& info, const RendererSettings& settings);

// In leak-checked builds (FACET_LEAK_CHECKED), every library loaded so far is pinned: a GPU
// driver's memory stays reachable after EGL or Vulkan unloads it (process.cpp says why).
void pin_loaded_libraries();

// Every job failed with `why`: what a renderer that cannot run returns.
std::vector<RenderOutcome> failed_renders(size_t jobs, const std::string& why);
std::vector<SweepCount> failed_sweeps(size_t jobs, const std::string& target, const std::string& why);

}  // namespace facet
