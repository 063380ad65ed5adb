// Vulkan renderer: the first Vulkan device (Mesa's lavapipe without a GPU), SPIR-V from
// glslangValidator, a full-screen triangle (harness/vulkan_triangle.vert) into an
// RGBA32F colour attachment, read back through a host-visible buffer. Every draw makes
// its own objects and destroys them (a Trash), so a failure half-way leaks nothing.
#include "renderers/vulkan.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <stdexcept>

#include <fmt/format.h>
#include <vulkan/vulkan.h>

#include "catalog/program.h"
#include "core/io.h"
#include "renderers/backends.h"
#include "renderers/gbuffer.h"
#include "renderers/harness.h"
#include "renderers/hlsl_shading.h"
#include "renderers/opengl.h"
#include "renderers/process.h"
#include "renderers/sweep.h"
#include "targets/glsl_lights.h"
#include "targets/targets.h"
#include "targets/texture_code.h"

namespace facet {

namespace {

const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// A Vulkan call that failed: what it was and its VkResult.
struct VulkanError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A Vulkan structure of type `type`, every other member zero.
template <class T>
T make(VkStructureType type) {
  T x{};
  x.sType = type;
  return x;
}

void vk(VkResult r, const char* what) {
  if (r != VK_SUCCESS) throw VulkanError(fmt::format("{} failed (VkResult {})", what, int(r)));
}

// The validation layers' errors and warnings, gathered until the draw looks at them. An
// error also stops the call (VK_ERROR_VALIDATION_FAILED_EXT): the driver never runs what
// the layers found invalid (lavapipe crashes on a shader reading a binding the layout lacks).
VKAPI_ATTR VkBool32 VKAPI_CALL gather_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT && data && data->pMessage)
    *static_cast<std::string*>(user) += std::string(data->pMessage) + "\n";
  return severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? VK_TRUE : VK_FALSE;
}

bool has_layer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

// Vulkan objects a draw made, destroyed in reverse order once the device is idle.
class Trash {
 public:
  explicit Trash(VkDevice device) : device_(device) {}
  ~Trash() {
    vkDeviceWaitIdle(device_);
    for (auto it = undo_.rbegin(); it != undo_.rend(); ++it) (*it)();
  }
  Trash(const Trash&) = delete;
  Trash& operator=(const Trash&) = delete;
  void operator()(std::function<void()> undo) { undo_.push_back(std::move(undo)); }

 private:
  VkDevice device_;
  std::vector<std::function<void()>> undo_;
};

}  // namespace

struct VulkanDevice::State {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory{};
  std::string glslang;            // glslangValidator's path
  std::vector<uint32_t> vertex;   // harness/vulkan_triangle.vert's SPIR-V, compiled at the first draw
  bool layers = false;            // the validation layers are on
  std::string messages;           // what they said since the last draw

  void create_instance();
  void create_device(std::string& description);
  uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const;
};

void VulkanDevice::State::create_instance() {
  auto app = make<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = "facet";
  app.apiVersion = VK_API_VERSION_1_1;
  auto ci = make<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  ci.pApplicationInfo = &app;
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  layers = has_layer(kValidationLayer);
  if (layers) {
    ci.enabledLayerCount = 1;
    ci.ppEnabledLayerNames = &kValidationLayer;
    ci.enabledExtensionCount = 1;
    ci.ppEnabledExtensionNames = &extension;
  }
  VkResult r = vkCreateInstance(&ci, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw VulkanError("no Vulkan driver (ICD) found: install one, e.g. Debian's mesa-vulkan-drivers (lavapipe)");
  vk(r, "vkCreateInstance");
  if (!layers) return;
  auto mi = make<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
  mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
  mi.pfnUserCallback = gather_message;
  mi.pUserData = &messages;
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
  if (create) vk(create(instance, &mi, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
}

// The first device with a graphics queue that renders into RGBA32F.
void VulkanDevice::State::create_device(std::string& description) {
  uint32_t count = 0;
  vk(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  vk(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
  for (VkPhysicalDevice d : devices) {
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(d, VK_FORMAT_R32G32B32A32_SFLOAT, &fp);
    if (!(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT)) continue;
    uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &nq, nullptr);
    std::vector<VkQueueFamilyProperties> qs(nq);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &nq, qs.data());
    for (uint32_t q = 0; q < nq && !physical; ++q)
      if (qs[q].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
        physical = d;
        family = q;
      }
    if (physical) break;
  }
  if (!physical) throw VulkanError(fmt::format("none of the {} Vulkan devices draws into RGBA32F", count));
  VkPhysicalDeviceProperties p;
  vkGetPhysicalDeviceProperties(physical, &p);
  description = fmt::format("{}, Vulkan {}.{}.{}", p.deviceName, VK_API_VERSION_MAJOR(p.apiVersion),
                            VK_API_VERSION_MINOR(p.apiVersion), VK_API_VERSION_PATCH(p.apiVersion));
  vkGetPhysicalDeviceMemoryProperties(physical, &memory);
  float priority = 1;
  auto qi = make<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  qi.queueFamilyIndex = family;
  qi.queueCount = 1;
  qi.pQueuePriorities = &priority;
  auto di = make<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  di.queueCreateInfoCount = 1;
  di.pQueueCreateInfos = &qi;
  vk(vkCreateDevice(physical, &di, nullptr, &device), "vkCreateDevice");
  vkGetDeviceQueue(device, family, 0, &queue);
  auto pi = make<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  pi.queueFamilyIndex = family;
  vk(vkCreateCommandPool(device, &pi, nullptr, &pool), "vkCreateCommandPool");
}

uint32_t VulkanDevice::State::memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const {
  for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags) return i;
  throw VulkanError("no Vulkan memory type fits");
}

VulkanDevice::VulkanDevice() : state_(new State) {
  state_->glslang = find_program("glslangValidator");
  if (state_->glslang.empty()) {
    error_ = "glslangValidator not found on PATH (Debian's glslang-tools): it compiles the shaders to SPIR-V";
    return;
  }
  try {
    state_->create_instance();
    state_->create_device(description_);
    pin_loaded_libraries();  // the ICD's and the layers' memory stays reachable at exit (LeakSanitizer)
  } catch (const VulkanError& e) {
    error_ = std::string("Vulkan: ") + e.what();
  }
}

VulkanDevice::~VulkanDevice() {
  State& s = *state_;
  if (s.device) {
    vkDeviceWaitIdle(s.device);
    if (s.pool) vkDestroyCommandPool(s.device, s.pool, nullptr);
    vkDestroyDevice(s.device, nullptr);
  }
  if (s.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(s.instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(s.instance, s.messenger, nullptr);
  }
  if (s.instance) vkDestroyInstance(s.instance, nullptr);
  delete state_;
}

bool VulkanDevice::validation_layers() const { return state_->layers; }

// ---------------------------------------------------------------- the scene's uniform block

std::vector<unsigned char> facet_scene_block(const Scene& s) {
  // std140: vec4 camera (0), vec4 ambient (16), int count (32), padded to 48.
  std::vector<float> f(48 / 4, 0.0f);
  const Vec3& eye = s.camera.position;
  const float head[8] = {float(eye.x), float(eye.y), float(eye.z), 1,
                         float(s.ambient[0]), float(s.ambient[1]), float(s.ambient[2]), 0};
  std::copy(head, head + 8, f.begin());
  const int32_t count = int32_t(s.lights.size());
  std::vector<unsigned char> out(f.size() * 4);
  std::memcpy(out.data(), f.data(), out.size());
  std::memcpy(out.data() + 32, &count, 4);
  return out;
}

std::vector<unsigned char> facet_light_buffer(const Scene& s) {
  std::vector<unsigned char> out(s.lights.size() * 64);
  for (size_t i = 0; i < s.lights.size(); ++i) {
    const std::array<float, 16> light = glsl_light::encode(s.lights[i]);
    std::memcpy(out.data() + i * 64, light.data(), 64);
  }
  return out;
}

// ---------------------------------------------------------------- compiling

namespace {

std::vector<uint32_t> read_spirv(const std::string& path) {
  std::string bytes = read_file(path);
  if (bytes.empty() || bytes.size() % 4) throw VulkanError(path + " is not SPIR-V");
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  return words;
}

// `source` written to `path` and compiled by glslangValidator into path + ".spv"; the
// error is glslang's words, which name the file.
std::vector<uint32_t> compile_spirv(const std::string& glslang, const std::string& path, const std::string& source,
                                    const std::string& stage, bool hlsl) {
  write_file_atomic(path, source);
  std::vector<std::string> argv = {glslang, "-V", "-S", stage};
  if (hlsl) argv.insert(argv.end(), {"-D", "-e", "main"});
  argv.insert(argv.end(), {"-o", path + ".spv", path});
  ProcessResult r = run_process(argv);
  if (r.exit_code != 0)
    throw VulkanError(fmt::format("glslangValidator rejected {} (exit {}):\n{}", path, r.exit_code, r.output));
  return read_spirv(path + ".spv");
}

VkShaderModule shader_module(VkDevice device, Trash& trash, const std::vector<uint32_t>& spirv) {
  auto ci = make<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  ci.codeSize = spirv.size() * 4;
  ci.pCode = spirv.data();
  VkShaderModule m;
  vk(vkCreateShaderModule(device, &ci, nullptr, &m), "vkCreateShaderModule");
  trash([=] { vkDestroyShaderModule(device, m, nullptr); });
  return m;
}

// ---------------------------------------------------------------- memory

struct HostBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  void* data = nullptr;
  VkDeviceSize size = 0;
};

// A host-visible, coherent buffer, mapped; at least 16 bytes (Vulkan has no empty buffers).
template <class State>
HostBuffer host_buffer(const State& s, Trash& trash, size_t bytes, VkBufferUsageFlags usage) {
  HostBuffer b;
  b.size = std::max<VkDeviceSize>(bytes, 16);
  auto ci = make<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  ci.size = b.size;
  ci.usage = usage;
  VkDevice device = s.device;
  vk(vkCreateBuffer(device, &ci, nullptr, &b.buffer), "vkCreateBuffer");
  VkBuffer buffer = b.buffer;
  trash([=] { vkDestroyBuffer(device, buffer, nullptr); });
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, b.buffer, &req);
  auto ai = make<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  ai.allocationSize = req.size;
  ai.memoryTypeIndex =
      s.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory memory;
  vk(vkAllocateMemory(device, &ai, nullptr, &memory), "vkAllocateMemory");
  trash([=] { vkFreeMemory(device, memory, nullptr); });
  vk(vkBindBufferMemory(device, b.buffer, memory, 0), "vkBindBufferMemory");
  vk(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &b.data), "vkMapMemory");
  std::memset(b.data, 0, size_t(b.size));
  return b;
}

struct GpuImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

// A device-local RGBA32F image and its view; with `layers` (> 0), a 2D array of that many.
template <class State>
GpuImage float_image(const State& s, Trash& trash, int width, int height, VkImageUsageFlags usage, int layers = 0) {
  auto ci = make<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  ci.extent = {uint32_t(width), uint32_t(height), 1};
  ci.mipLevels = 1;
  ci.arrayLayers = uint32_t(std::max(layers, 1));
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  VkDevice device = s.device;
  GpuImage g;
  vk(vkCreateImage(device, &ci, nullptr, &g.image), "vkCreateImage");
  VkImage image = g.image;
  trash([=] { vkDestroyImage(device, image, nullptr); });
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, g.image, &req);
  auto ai = make<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = s.memory_type(req.memoryTypeBits, 0);
  VkDeviceMemory memory;
  vk(vkAllocateMemory(device, &ai, nullptr, &memory), "vkAllocateMemory");
  trash([=] { vkFreeMemory(device, memory, nullptr); });
  vk(vkBindImageMemory(device, g.image, memory, 0), "vkBindImageMemory");
  auto vi = make<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
  vi.image = g.image;
  vi.viewType = layers > 0 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  vi.format = ci.format;
  vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, ci.arrayLayers};
  vk(vkCreateImageView(device, &vi, nullptr, &g.view), "vkCreateImageView");
  VkImageView view = g.view;
  trash([=] { vkDestroyImageView(device, view, nullptr); });
  return g;
}

void image_barrier(VkCommandBuffer cb, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src,
                   VkAccessFlags dst, VkPipelineStageFlags src_stage, VkPipelineStageFlags dst_stage,
                   uint32_t layers = 1) {
  auto b = make<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
  b.oldLayout = from;
  b.newLayout = to;
  b.srcAccessMask = src;
  b.dstAccessMask = dst;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
  vkCmdPipelineBarrier(cb, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

}  // namespace

// ---------------------------------------------------------------- one draw

namespace {

// The descriptor sets of a VulkanDraw (vulkan.h): their layouts, the sets, and the
// images' uploads to record before the render pass.
struct Bindings {
  static constexpr uint32_t kSets = 3;
  VkDescriptorSetLayout layouts[kSets] = {VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE};
  VkDescriptorSet sets[kSets] = {VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE};
  struct Upload {
    HostBuffer staging;
    GpuImage image;
    int width, height, layers;
  };
  std::vector<Upload> uploads;
};

// A set of bindings 0, 1, … of `types`.
VkDescriptorSetLayout set_layout(VkDevice device, Trash& trash, const std::vector<VkDescriptorType>& types) {
  std::vector<VkDescriptorSetLayoutBinding> b;
  for (size_t i = 0; i < types.size(); ++i) b.push_back({uint32_t(i), types[i], 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
  auto ci = make<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  ci.bindingCount = uint32_t(b.size());
  ci.pBindings = b.data();
  VkDescriptorSetLayout layout;
  vk(vkCreateDescriptorSetLayout(device, &ci, nullptr, &layout), "vkCreateDescriptorSetLayout");
  trash([=] { vkDestroyDescriptorSetLayout(device, layout, nullptr); });
  return layout;
}

void allocate_sets(VkDevice device, Trash& trash, const VulkanDraw& d, Bindings& b) {
  std::vector<VkDescriptorPoolSize> sizes = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
  if (size_t n = d.textures.size() + d.images.size()) sizes.push_back({VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, uint32_t(n)});
  auto pi = make<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  pi.maxSets = Bindings::kSets;
  pi.poolSizeCount = uint32_t(sizes.size());
  pi.pPoolSizes = sizes.data();
  VkDescriptorPool pool;
  vk(vkCreateDescriptorPool(device, &pi, nullptr, &pool), "vkCreateDescriptorPool");
  trash([=] { vkDestroyDescriptorPool(device, pool, nullptr); });
  auto ai = make<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  ai.descriptorPool = pool;
  ai.descriptorSetCount = Bindings::kSets;
  ai.pSetLayouts = b.layouts;
  vk(vkAllocateDescriptorSets(device, &ai, b.sets), "vkAllocateDescriptorSets");
}

VkWriteDescriptorSet write(VkDescriptorSet set, uint32_t binding, VkDescriptorType type) {
  auto w = make<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
  w.dstSet = set;
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = type;
  return w;
}

VkSampler nearest_sampler(VkDevice device, Trash& trash) {
  auto ci = make<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
  ci.magFilter = ci.minFilter = VK_FILTER_NEAREST;
  ci.addressModeU = ci.addressModeV = ci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSampler sampler;
  vk(vkCreateSampler(device, &ci, nullptr, &sampler), "vkCreateSampler");
  trash([=] { vkDestroySampler(device, sampler, nullptr); });
  return sampler;
}

// `images` staged for upload and written into `set` from binding `first` (`infos` keeps the
// descriptors' image infos alive until the writes are made).
template <class State>
void bind_images(const State& s, Trash& trash, const std::vector<VulkanImage>& images, VkDescriptorSet set,
                 uint32_t first, VkSampler sampler, Bindings& b, std::vector<VkDescriptorImageInfo>& infos,
                 std::vector<VkWriteDescriptorSet>& writes) {
  for (size_t i = 0; i < images.size(); ++i) {
    const VulkanImage& t = images[i];
    const size_t bytes = size_t(t.width) * size_t(t.height) * size_t(std::max(t.layers, 1)) * 16;
    Bindings::Upload up{host_buffer(s, trash, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT),
                        float_image(s, trash, t.width, t.height, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                    t.layers),
                        t.width, t.height, std::max(t.layers, 1)};
    std::memcpy(up.staging.data, t.rgba, bytes);
    infos.push_back({sampler, up.image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
    writes.push_back(write(set, first + uint32_t(i), VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER));
    writes.back().pImageInfo = &infos.back();
    b.uploads.push_back(up);
  }
}

// A host buffer holding `bytes` (at least `least` bytes, zeros past them), written into
// binding `binding` of `set` as a descriptor of `type` (`info` keeps its buffer info alive).
template <class State>
void bind_buffer(const State& s, Trash& trash, const std::vector<unsigned char>& bytes, size_t least,
                 VkDescriptorType type, VkDescriptorSet set, uint32_t binding, VkDescriptorBufferInfo& info,
                 std::vector<VkWriteDescriptorSet>& writes) {
  const bool uniform = type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  HostBuffer h = host_buffer(s, trash, std::max(bytes.size(), least),
                             uniform ? VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT : VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  if (!bytes.empty()) std::memcpy(h.data, bytes.data(), bytes.size());
  info = {h.buffer, 0, VK_WHOLE_SIZE};
  writes.push_back(write(set, binding, type));
  writes.back().pBufferInfo = &info;
}

// The uniform block, the images (staged for upload) and the storage buffer, written into the sets.
template <class State>
Bindings bindings(const State& s, Trash& trash, const VulkanDraw& d) {
  Bindings b;
  std::vector<VkDescriptorType> set0(d.textures.size() + 1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
  set0[0] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  b.layouts[0] = set_layout(s.device, trash, set0);
  b.layouts[1] = set_layout(s.device, trash, std::vector<VkDescriptorType>(d.images.size(), VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER));
  b.layouts[2] = set_layout(s.device, trash, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  allocate_sets(s.device, trash, d, b);
  std::vector<VkWriteDescriptorSet> writes;
  VkDescriptorBufferInfo block, storage;
  bind_buffer(s, trash, d.uniforms, 16, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, b.sets[0], 0, block, writes);
  // A light's 64 bytes at least: a runtime array's binding holds one element (WebGPU's rule too).
  bind_buffer(s, trash, d.storage, 64, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, b.sets[2], 0, storage, writes);
  std::vector<VkDescriptorImageInfo> infos;
  infos.reserve(d.textures.size() + d.images.size());
  if (!d.textures.empty() || !d.images.empty()) {
    VkSampler sampler = nearest_sampler(s.device, trash);
    bind_images(s, trash, d.textures, b.sets[0], 1, sampler, b, infos, writes);
    bind_images(s, trash, d.images, b.sets[1], 0, sampler, b, infos, writes);
  }
  vkUpdateDescriptorSets(s.device, uint32_t(writes.size()), writes.data(), 0, nullptr);
  return b;
}

void record_uploads(VkCommandBuffer cb, const Bindings& b) {
  for (const auto& up : b.uploads) {
    const uint32_t layers = uint32_t(up.layers);
    image_barrier(cb, up.image.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                  VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, layers);
    VkBufferImageCopy copy{};  // the layers one after the other in the staging buffer
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, layers};
    copy.imageExtent = {uint32_t(up.width), uint32_t(up.height), 1};
    vkCmdCopyBufferToImage(cb, up.staging.buffer, up.image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    image_barrier(cb, up.image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                  VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, layers);
  }
}

// The colour attachment, its render pass (cleared to 0, left ready to copy from) and framebuffer.
struct ColorTarget {
  GpuImage image;
  VkRenderPass pass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
};

template <class State>
ColorTarget color_target(const State& s, Trash& trash, int width, int height) {
  ColorTarget t;
  t.image = float_image(s, trash, width, height, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  VkAttachmentDescription a{};
  a.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  a.samples = VK_SAMPLE_COUNT_1_BIT;
  a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  a.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = 1;
  sub.pColorAttachments = &ref;
  // The copy to the readback buffer waits for the colour writes.
  VkSubpassDependency dep{0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                          VK_ACCESS_TRANSFER_READ_BIT, 0};
  auto ci = make<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
  ci.attachmentCount = 1;
  ci.pAttachments = &a;
  ci.subpassCount = 1;
  ci.pSubpasses = &sub;
  ci.dependencyCount = 1;
  ci.pDependencies = &dep;
  VkDevice device = s.device;
  vk(vkCreateRenderPass(device, &ci, nullptr, &t.pass), "vkCreateRenderPass");
  VkRenderPass pass = t.pass;
  trash([=] { vkDestroyRenderPass(device, pass, nullptr); });
  auto fi = make<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
  fi.renderPass = t.pass;
  fi.attachmentCount = 1;
  fi.pAttachments = &t.image.view;
  fi.width = uint32_t(width);
  fi.height = uint32_t(height);
  fi.layers = 1;
  vk(vkCreateFramebuffer(device, &fi, nullptr, &t.framebuffer), "vkCreateFramebuffer");
  VkFramebuffer fb = t.framebuffer;
  trash([=] { vkDestroyFramebuffer(device, fb, nullptr); });
  return t;
}

VkPipelineLayout pipeline_layout(VkDevice device, Trash& trash, const Bindings& b) {
  VkPushConstantRange push{VK_SHADER_STAGE_FRAGMENT_BIT, 0, 8};  // ivec2 (width, height)
  auto ci = make<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  ci.setLayoutCount = Bindings::kSets;
  ci.pSetLayouts = b.layouts;
  ci.pushConstantRangeCount = 1;
  ci.pPushConstantRanges = &push;
  VkPipelineLayout layout;
  vk(vkCreatePipelineLayout(device, &ci, nullptr, &layout), "vkCreatePipelineLayout");
  trash([=] { vkDestroyPipelineLayout(device, layout, nullptr); });
  return layout;
}

// The full-screen triangle's pipeline: no vertex input, no culling, no blending, a fixed viewport.
VkPipeline pipeline(VkDevice device, Trash& trash, VkShaderModule vertex, VkShaderModule fragment,
                    VkPipelineLayout layout, VkRenderPass pass, int width, int height) {
  VkPipelineShaderStageCreateInfo stages[2] = {make<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO),
                                               make<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO)};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment;
  stages[1].pName = "main";
  auto input = make<VkPipelineVertexInputStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
  auto assembly = make<VkPipelineInputAssemblyStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkViewport viewport{0, 0, float(width), float(height), 0, 1};
  VkRect2D scissor{{0, 0}, {uint32_t(width), uint32_t(height)}};
  auto vp = make<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
  vp.viewportCount = vp.scissorCount = 1;
  vp.pViewports = &viewport;
  vp.pScissors = &scissor;
  auto raster = make<VkPipelineRasterizationStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1;
  auto ms = make<VkPipelineMultisampleStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                         VK_COLOR_COMPONENT_A_BIT;
  auto cb = make<VkPipelineColorBlendStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
  cb.attachmentCount = 1;
  cb.pAttachments = &blend;
  auto ci = make<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &input;
  ci.pInputAssemblyState = &assembly;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &raster;
  ci.pMultisampleState = &ms;
  ci.pColorBlendState = &cb;
  ci.layout = layout;
  ci.renderPass = pass;
  VkPipeline p;
  vk(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, &p), "vkCreateGraphicsPipelines");
  trash([=] { vkDestroyPipeline(device, p, nullptr); });
  return p;
}

// Everything one draw records, in order.
struct Recording {
  const Bindings* bindings;
  const ColorTarget* target;
  VkPipelineLayout layout;
  VkPipeline pipeline;
  VkBuffer readback;
  int width, height;
};

void record(VkCommandBuffer cb, const Recording& r) {
  record_uploads(cb, *r.bindings);
  VkClearValue clear{};
  auto bi = make<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
  bi.renderPass = r.target->pass;
  bi.framebuffer = r.target->framebuffer;
  bi.renderArea = {{0, 0}, {uint32_t(r.width), uint32_t(r.height)}};
  bi.clearValueCount = 1;
  bi.pClearValues = &clear;
  vkCmdBeginRenderPass(cb, &bi, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r.pipeline);
  vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, r.layout, 0, Bindings::kSets, r.bindings->sets, 0,
                          nullptr);
  const int32_t size[2] = {r.width, r.height};
  vkCmdPushConstants(cb, r.layout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof size, size);
  vkCmdDraw(cb, 3, 1, 0, 0);
  vkCmdEndRenderPass(cb);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {uint32_t(r.width), uint32_t(r.height), 1};
  vkCmdCopyImageToBuffer(cb, r.target->image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, r.readback, 1, &copy);
  auto host = make<VkBufferMemoryBarrier>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER);
  host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  host.srcQueueFamilyIndex = host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  host.buffer = r.readback;
  host.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &host, 0,
                       nullptr);
}

// Records with `fill`, submits and waits.
template <class State>
void submit(const State& s, Trash& trash, const std::function<void(VkCommandBuffer)>& fill) {
  auto ai = make<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  ai.commandPool = s.pool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cb;
  vk(vkAllocateCommandBuffers(s.device, &ai, &cb), "vkAllocateCommandBuffers");
  VkDevice device = s.device;
  VkCommandPool pool = s.pool;
  trash([=] { vkFreeCommandBuffers(device, pool, 1, &cb); });
  auto bi = make<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vk(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
  fill(cb);
  vk(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
  auto fi = make<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  VkFence fence;
  vk(vkCreateFence(device, &fi, nullptr, &fence), "vkCreateFence");
  trash([=] { vkDestroyFence(device, fence, nullptr); });
  auto si = make<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cb;
  vk(vkQueueSubmit(s.queue, 1, &si, fence), "vkQueueSubmit");
  vk(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

}  // namespace

RenderOutcome VulkanDevice::draw(const VulkanDraw& d, int width, int height, const std::string& folder) {
  RenderOutcome out;
  if (!error_.empty()) {
    out.error = error_;
    return out;
  }
  auto start = std::chrono::steady_clock::now();
  const std::filesystem::path dir(folder);
  const std::string file = (dir / (d.name + (d.hlsl ? ".hlsl" : ".frag"))).string();
  State& s = *state_;
  try {
    std::filesystem::create_directories(dir);
    if (s.vertex.empty())
      s.vertex = compile_spirv(s.glslang, (dir / "vulkan_triangle.vert").string(),
                               render_harness("vulkan_triangle.vert"), "vert", false);
    std::vector<uint32_t> spirv = compile_spirv(s.glslang, file, d.source, "frag", d.hlsl);
    s.messages.clear();
    Trash trash(s.device);
    Bindings b = bindings(s, trash, d);
    ColorTarget target = color_target(s, trash, width, height);
    VkPipelineLayout layout = pipeline_layout(s.device, trash, b);
    VkPipeline p = pipeline(s.device, trash, shader_module(s.device, trash, s.vertex),
                            shader_module(s.device, trash, spirv), layout, target.pass, width, height);
    const size_t pixels = size_t(width) * size_t(height);
    HostBuffer readback = host_buffer(s, trash, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    submit(s, trash, [&](VkCommandBuffer cb) { record(cb, {&b, &target, layout, p, readback.buffer, width, height}); });
    const float* px = static_cast<const float*>(readback.data);
    out.image = Image(width, height);
    out.alpha.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
      for (size_t c = 0; c < 3; ++c) out.image.rgb[i * 3 + c] = px[i * 4 + c];
      out.alpha[i] = px[i * 4 + 3];
    }
  } catch (const std::exception& e) {
    out.error = std::string(e.what()).find(file) != std::string::npos ? e.what() : file + ": " + e.what();
  }
  if (!s.messages.empty())
    out.error = fmt::format("the Vulkan validation layers on {}:\n{}{}", file, s.messages, out.error);
  if (!out.error.empty()) return out;
  out.ok = true;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

// ---------------------------------------------------------------- the renderer

namespace {

// The material's images (image_calls() order: set 0, bindings 1…).
std::vector<VulkanImage> material_images(const Material& m) {
  std::vector<VulkanImage> out;
  for (const auto& c : image_calls(compile(m))) out.push_back({c.texels->width, c.texels->height, c.texels->rgba.data()});
  return out;
}

// "vulkan" and "vulkan-hlsl": each material pass's G-buffer cast by the GL renderer's
// ray caster (renderers/gbuffer.h), shaded on the Vulkan device by the generated glsl450
// shading pass (glsl_gbuffer_shading_source) or the HLSL one (hlsl_shading_source,
// through glslang's HLSL front end); the passes add up.
class VulkanRenderer : public Renderer {
 public:
  VulkanRenderer(const RendererInfo& info, bool hlsl) : info_(info), hlsl_(hlsl) {
    if (!device_.unavailable().empty()) error_ = device_.unavailable();
    else if (!gl_.ok()) error_ = "the G-buffer is cast with OpenGL, which is not here: " + gl_.error();
  }
  const RendererInfo& info() const override { return info_; }
  std::string unavailable() const override { return error_; }
  std::string description() const override {
    return device_.description() + "; G-buffer: " + gl_.description();
  }
  std::vector<RenderOutcome> render(const std::vector<RenderJob>& jobs, const RenderProgress& progress) override {
    return render_each(jobs, progress, [&](const RenderJob& job) { return render_one(job); });
  }
  std::vector<SweepCount> sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) override;

 private:
  RenderOutcome render_one(const RenderJob& job);
  RenderOutcome shade(const RenderJob& job, const Material& m, const std::string& name, const GBuffer& g, size_t pass);
  RendererInfo info_;
  bool hlsl_;
  VulkanDevice device_;
  GlRenderer gl_;
  std::string error_;
};

// Material pass `pass` over the G-buffer.
RenderOutcome VulkanRenderer::shade(const RenderJob& job, const Material& m, const std::string& name,
                                    const GBuffer& g, size_t pass) {
  VulkanDraw d;
  d.name = name;
  d.hlsl = hlsl_;
  d.source = !job.code_override.empty() ? job.code_override
             : hlsl_                    ? hlsl_shading_source(m)
                                        : glsl_gbuffer_shading_source(m, Target::Glsl450);
  d.uniforms = facet_scene_block(job.scene);
  d.storage = facet_light_buffer(job.scene);
  d.textures = material_images(m);
  const std::vector<float> position = g.pass_position(pass);
  d.images.push_back({g.width, g.height, position.data()});
  for (int i = 1; i < GBuffer::kImages; ++i)
    d.images.push_back({g.width, g.height, g.images[size_t(i)].data(), i == GBuffer::Visibility ? g.layers : 0});
  return device_.draw(d, job.width, job.height, job.folder());
}

RenderOutcome VulkanRenderer::render_one(const RenderJob& job) {
  RenderOutcome out;
  if (!error_.empty()) {
    out.error = error_;
    return out;
  }
  auto start = std::chrono::steady_clock::now();
  std::vector<const Material*> passes;
  try {
    passes = material_passes(job);
  } catch (const std::exception& e) {
    out.error = e.what();
    return out;
  }
  if (!job.code_override.empty() && passes.size() != 1) {
    out.error = "code_override needs a scene with one material";
    return out;
  }
  const size_t pixels = size_t(job.width) * size_t(job.height);
  out.image = Image(job.width, job.height);
  out.alpha.assign(pixels, 0);
  const GBufferOutcome g = cast_gbuffer(gl_, job);  // once for every pass
  if (!g.ok) {
    out.error = "the G-buffer: " + g.error;
    return out;
  }
  for (size_t k = 0; k < passes.size(); ++k) {
    const std::string name = pass_name(job, k, passes.size(), passes[k]->name);
    RenderOutcome pass = shade(job, *passes[k], name, g.gbuffer, k);
    if (!pass.ok) {
      out.error = pass.error;
      return out;
    }
    for (size_t i = 0; i < pixels; ++i) {
      for (size_t c = 0; c < 3; ++c) out.image.rgb[i * 3 + c] += pass.image.rgb[i * 3 + c];
      out.alpha[i] = std::max(out.alpha[i], pass.alpha[i]);
    }
  }
  out.ok = true;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::vector<SweepCount> VulkanRenderer::sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) {
  if (!error_.empty()) return failed_sweeps(jobs.size(), info_.name, error_);
  std::vector<SweepCount> out(jobs.size());
  const std::string folder =
      settings.workdir.empty() ? (std::filesystem::path(private_work_folder()) / "sweep").string() : settings.workdir;
  for (size_t i = 0; i < jobs.size(); ++i) {
    SweepCount& c = out[i];
    c.target = info_.name;
    const Material& m = jobs[i].material;
    VulkanDraw d;
    d.name = identifier(m.name) + "_sweep";
    d.hlsl = hlsl_;
    d.source = !jobs[i].source.empty() ? jobs[i].source : hlsl_ ? hlsl_sweep_source(m) : glsl_sweep_source(m, Target::Glsl450);
    if (hlsl_) {  // hlsl/sweep.hlsl's cbuffer FacetSweep: float2 facet_resolution (glsl450 reads the push constants)
      const float side[2] = {float(settings.grid), float(settings.grid)};
      d.uniforms.resize(sizeof side);
      std::memcpy(d.uniforms.data(), side, sizeof side);
    }
    d.textures = material_images(jobs[i].material);
    count_sweep_outcome(c, device_.draw(d, settings.grid, settings.grid, folder));
  }
  return out;
}

}  // namespace

std::unique_ptr<Renderer> make_vulkan_renderer(const RendererInfo& info, const RendererSettings&) {
  return std::make_unique<VulkanRenderer>(info, false);
}

std::unique_ptr<Renderer> make_vulkan_hlsl_renderer(const RendererInfo& info, const RendererSettings&) {
  return std::make_unique<VulkanRenderer>(info, true);
}

}  // namespace facet
