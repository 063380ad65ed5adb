// facet — Vulkan for the renderers: SPIR-V that glslangValidator
// compiles from a fragment shader (GLSL 4.50, or HLSL through glslang's HLSL front
// end), drawn with a full-screen triangle into an RGBA32F colour attachment on the
// first Vulkan device (Mesa's lavapipe without a GPU) and read back.
#pragma once

#include <string>
#include <vector>

#include "renderers/renderer.h"

namespace facet {

// RGBA32F texels, row j (texelFetch's j) at rgba + 4·j·width; the caller keeps them alive.
// With `layers`, a 2D array (sampler2DArray, Texture2DArray) of that many such images one
// after the other.
struct VulkanImage {
  int width = 0, height = 0;
  const float* rgba = nullptr;
  int layers = 0;
};

// One fragment shader and what its descriptor sets hold, every image an RGBA32F combined
// image sampler (nearest, read with texelFetch):
//  set 0, binding 0      a uniform block of `uniforms` bytes (std140: the generated glsl450's FacetScene)
//  set 0, bindings 1…    `textures` (the generated glsl450's facet_texture_<parameter>, in image_calls() order)
//  set 1, bindings 0…    `images` (the G-buffer's seven, renderers/gbuffer.h; the visibility a 2D array)
//  set 2, binding 0      a storage buffer of `storage` bytes (the lights, 64 bytes each: targets.h,
//                        LightSource::Buffer; at least 64 bytes are bound, zeros past `storage`)
//  push constants        ivec2 (width, height) at offset 0
// The framebuffer's y runs down (gl_FragCoord.y = 0.5 on the top row); the image comes back
// in facet's order, rows from the top.
struct VulkanDraw {
  std::string name;    // the shader's file name without its extension: files and messages name it
  std::string source;  // the fragment shader
  bool hlsl = false;   // HLSL (entry point main) rather than GLSL 4.50
  std::vector<unsigned char> uniforms, storage;
  std::vector<VulkanImage> textures, images;
};

// The head of the generated glsl450's FacetScene uniform block (templates/glsl, std140) for
// scene `s`: the camera position (at 0), the ambient colour (16) and the light count (32);
// 48 bytes, the whole block of the shading passes (LightSource::Buffer). The engine-facing
// block (LightSource::Uniforms) goes on with the first 8 lights from byte 48, as
// facet_light_buffer() lays them out.
std::vector<unsigned char> facet_scene_block(const Scene& s);
// The scene's lights as the shading passes' storage buffer: FacetLight's four vec4 a light
// (64 bytes, std430), encoded as targets/glsl_lights.h says.
std::vector<unsigned char> facet_light_buffer(const Scene& s);

// The Vulkan machinery: an instance with the validation layers when they are installed
// (VK_LAYER_KHRONOS_validation: their warnings and errors fail a draw), the first device that
// renders into RGBA32F, and draw(). The renderer (make_vulkan_renderer) draws with one.
class VulkanDevice {
 public:
  VulkanDevice();
  ~VulkanDevice();
  VulkanDevice(const VulkanDevice&) = delete;
  VulkanDevice& operator=(const VulkanDevice&) = delete;
  // Why it cannot draw (no Vulkan ICD, no glslangValidator, …), or "".
  const std::string& unavailable() const { return error_; }
  const std::string& description() const { return description_; }  // the device's name and API version
  bool validation_layers() const;

  // Compiles d.source in `folder` (d.name + ".frag" or ".hlsl", and its ".spv") and draws it on
  // width × height pixels; the error names the file (glslang's, the validation layers' or
  // Vulkan's words).
  RenderOutcome draw(const VulkanDraw& d, int width, int height, const std::string& folder);

 private:
  struct State;
  State* state_ = nullptr;
  std::string error_, description_;
};

}  // namespace facet
