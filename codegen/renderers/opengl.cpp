// OpenGL renderer: EGL surfaceless on Mesa (llvmpipe without a GPU), as
// shared/notes/opengl.md recommends. The fragment shader is facet's generated
// GLSL 3.30 (library + light loop) under codegen/renderers/harness/raycast.glsl.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>


#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include "catalog/program.h"
#include "core/io.h"
#include "reference/raycaster.h"
#include "renderers/backends.h"
#include "renderers/gbuffer.h"
#include "renderers/harness.h"
#include "renderers/opengl.h"
#include "scene/bvh.h"
#include "scene/tangents.h"
#include "targets/texture_code.h"
#include "renderers/sweep.h"
#include "targets/glsl_lights.h"
#include "targets/targets.h"

namespace facet {

namespace {

const char* kVertexShader = R"(#version 330 core
// One triangle covering the viewport; the fragment shader casts the rays.
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// The shadow-ray offset: the reference's (render.h). Self-shadowing is excluded
// by object (convex) and by triangle, so float hit points need no more room.
const double kGlShadowOffset = kShadowRayOffset;
// facet_object_normal[i].w in harness/raycast.glsl (its {{sphere}} … placeholders): the object's kind.
const int kSphere = 0, kSquare = 1, kMesh = 2;

std::string shader_log(GLuint id, bool program) {
  GLint len = 0;
  program ? glGetProgramiv(id, GL_INFO_LOG_LENGTH, &len) : glGetShaderiv(id, GL_INFO_LOG_LENGTH, &len);
  std::string log(size_t(std::max(len, 1)), '\0');
  program ? glGetProgramInfoLog(id, len, nullptr, log.data()) : glGetShaderInfoLog(id, len, nullptr, log.data());
  return log.c_str();
}

// A program of the shared vertex shader and `source`; 0 with `error` set when
// it does not compile or link (`what` names the code in the message).
GLuint fragment_program(GLuint vertex, const std::string& source, const std::string& what, std::string& error) {
  GLuint fragment = glCreateShader(GL_FRAGMENT_SHADER);
  const char* src = source.c_str();
  glShaderSource(fragment, 1, &src, nullptr);
  glCompileShader(fragment);
  GLint status = 0;
  glGetShaderiv(fragment, GL_COMPILE_STATUS, &status);
  if (!status) {
    error = what + " did not compile: " + shader_log(fragment, false);
    glDeleteShader(fragment);
    return 0;
  }
  GLuint prog = glCreateProgram();
  glAttachShader(prog, vertex);
  glAttachShader(prog, fragment);
  glLinkProgram(prog);
  glDeleteShader(fragment);
  glGetProgramiv(prog, GL_LINK_STATUS, &status);
  if (!status) {
    error = what + " did not link: " + shader_log(prog, true);
    glDeleteProgram(prog);
    return 0;
  }
  return prog;
}

// GL rows run bottom-up; facet images top-down. Colours add up (a render's
// passes), coverage is the largest alpha.
void add_bottom_up(const std::vector<float>& px, RenderOutcome& out) {
  const int w = out.image.width, h = out.image.height;
  for (int y = 0; y < h; ++y) {
    const float* row = &px[size_t(h - 1 - y) * size_t(w) * 4];
    for (int x = 0; x < w; ++x) {
      float* dst = out.image.at(x, y);
      for (int c = 0; c < 3; ++c) dst[c] += row[x * 4 + c];
      float& a = out.alpha[size_t(y) * size_t(w) + size_t(x)];
      a = std::max(a, row[x * 4 + 3]);
    }
  }
}

// An RGBA32F framebuffer of `attachments` colour buffers (draw buffers 0, 1, …),
// bound while it lives: every draw renders into one.
class FloatFramebuffer {
 public:
  FloatFramebuffer(int width, int height, int attachments = 1)
      : width_(width), height_(height), rbo_(size_t(attachments), 0) {
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glGenRenderbuffers(GLsizei(rbo_.size()), rbo_.data());
    std::vector<GLenum> buffers;
    for (size_t i = 0; i < rbo_.size(); ++i) {
      glBindRenderbuffer(GL_RENDERBUFFER, rbo_[i]);
      glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, width, height);
      buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, buffers.back(), GL_RENDERBUFFER, rbo_[i]);
    }
    glDrawBuffers(GLsizei(buffers.size()), buffers.data());
    glViewport(0, 0, width, height);
  }
  ~FloatFramebuffer() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteRenderbuffers(GLsizei(rbo_.size()), rbo_.data());
    glDeleteFramebuffers(1, &fbo_);
  }
  FloatFramebuffer(const FloatFramebuffer&) = delete;
  FloatFramebuffer& operator=(const FloatFramebuffer&) = delete;
  bool complete() const { return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE; }
  // The next draws write colour buffer i where on[i] (the others' outputs go nowhere).
  void draw_to(const std::vector<bool>& on) const {
    std::vector<GLenum> buffers;
    for (size_t i = 0; i < rbo_.size(); ++i) buffers.push_back(i < on.size() && on[i] ? GLenum(GL_COLOR_ATTACHMENT0 + i) : GL_NONE);
    glDrawBuffers(GLsizei(buffers.size()), buffers.data());
  }
  // Colour buffer `attachment`: RGBA, rows bottom-up as GL stores them.
  std::vector<float> read(int attachment = 0) const {
    std::vector<float> px(size_t(width_) * size_t(height_) * 4);
    glReadBuffer(GLenum(GL_COLOR_ATTACHMENT0 + attachment));
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, px.data());
    return px;
  }

 private:
  int width_, height_;
  GLuint fbo_ = 0;
  std::vector<GLuint> rbo_;
};

}  // namespace

struct GlRenderer::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLuint vao = 0, vertex = 0;
};

GlRenderer::GlRenderer() : state_(new State) {
  const char* ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!ext) {
    error_ = "EGL: no client extensions (is libegl1 with Mesa's vendor library installed?)";
    return;
  }
  if (std::strstr(ext, "EGL_MESA_platform_surfaceless")) {
    state_->display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  } else if (std::strstr(ext, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (eglQueryDevicesEXT(8, devices, &count) && count > 0)
      state_->display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
  }
  if (state_->display == EGL_NO_DISPLAY) {
    error_ = "EGL: no surfaceless or device display";
    return;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(state_->display, &major, &minor)) {
    error_ = fmt::format("EGL: eglInitialize failed (0x{:x})", eglGetError());
    return;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    error_ = "EGL: no desktop OpenGL";
    return;
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  state_->context = eglCreateContext(state_->display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (state_->context == EGL_NO_CONTEXT) {
    error_ = fmt::format("EGL: cannot create an OpenGL 3.3 core context (0x{:x})", eglGetError());
    return;
  }
  if (!eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context)) {
    error_ = "EGL: eglMakeCurrent failed";
    return;
  }
  pin_loaded_libraries();
  description_ = fmt::format("{}, {}", reinterpret_cast<const char*>(glGetString(GL_RENDERER)),
                             reinterpret_cast<const char*>(glGetString(GL_VERSION)));
  glGenVertexArrays(1, &state_->vao);
  state_->vertex = glCreateShader(GL_VERTEX_SHADER);
  glShaderSource(state_->vertex, 1, &kVertexShader, nullptr);
  glCompileShader(state_->vertex);
}

GlRenderer::~GlRenderer() {
  if (state_->display != EGL_NO_DISPLAY) {
    if (state_->context != EGL_NO_CONTEXT) {
      if (state_->vao) glDeleteVertexArrays(1, &state_->vao);
      if (state_->vertex) glDeleteShader(state_->vertex);
      eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(state_->display, state_->context);
    }
    eglTerminate(state_->display);
  }
  delete state_;
}

const RendererInfo& GlRenderer::info() const { return *find_renderer("glsl"); }

std::unique_ptr<Renderer> make_opengl_renderer(const RendererInfo&, const RendererSettings&) {
  return std::make_unique<GlRenderer>();
}

RenderOutcome GlRenderer::sweep_draw(const std::string& source, int grid) {
  RenderOutcome out;
  if (!ok()) {
    out.error = error_;
    return out;
  }
  GLuint prog = fragment_program(state_->vertex, source, "the sweep's GLSL", out.error);
  if (!prog) return out;
  glUseProgram(prog);
  glUniform2f(glGetUniformLocation(prog, "facet_resolution"), float(grid), float(grid));
  GLenum e;
  {
    FloatFramebuffer fb(grid, grid);
    glBindVertexArray(state_->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> px = fb.read();
    out.image = Image(grid, grid);
    for (size_t i = 0; i < size_t(grid) * size_t(grid); ++i)
      for (int c = 0; c < 3; ++c) out.image.rgb[i * 3 + size_t(c)] = px[i * 4 + size_t(c)];
    e = glGetError();
  }
  glDeleteProgram(prog);
  if (e != GL_NO_ERROR) out.error = fmt::format("OpenGL error 0x{:x}", e);
  else out.ok = true;
  return out;
}

std::vector<SweepCount> GlRenderer::sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) {
  std::vector<SweepCount> out(jobs.size());
  for (size_t i = 0; i < jobs.size(); ++i) {
    SweepCount& c = out[i];
    c.target = info().name;
    const SweepJob& j = jobs[i];
    count_sweep_outcome(c, sweep_draw(j.source.empty() ? glsl_sweep_source(j.material) : j.source, settings.grid));
  }
  return out;
}

std::string GlRenderer::fragment_source(const Material& m, bool gbuffer) {
  MaterialProgram p = compile(m);
  GlslParts parts = glsl_parts(p, Target::Glsl, m.source, LightSource::Buffer);
  std::string sample;
  if (p.has_textures())
    sample = p.uses_vertex_color()
                 ? "    facet_sample_textures(facet_uv(hit, p, best, 0), facet_uv(hit, p, best, 1), facet_color0_at(hit, best));\n"
                 : "    facet_sample_textures(facet_uv(hit, p, best, 0), facet_uv(hit, p, best, 1));\n";
  if (p.has_uv_frame())
    sample += "    vec4 frame = facet_uv_tangent_at(hit, p, best);\n"
              "    facet_uv_tangent = frame.xyz;\n    facet_uv_handedness = frame.w;\n";
  std::map<std::string, std::string> values = glsl_light::visibility_values();
  values.insert({{"directional", std::to_string(glsl_light::kDirectional)},
                 {"sphere", std::to_string(kSphere)},
                 {"square", std::to_string(kSquare)},
                 {"mesh", std::to_string(kMesh)},
                 {"horizon", fmt::format("{:g}", GBuffer::kHorizon)},
                 {"sample", sample}});
  return std::string("#version 330 core\n") + (gbuffer ? "#define FACET_GBUFFER\n" : "") + parts.header +
         parts.library + parts.lights + render_harness("raycast.glsl", values);
}

namespace {

// Every mesh's BVH and triangles, concatenated: 2 RGBA32F texels a node, 6 a
// triangle (in BVH order), as codegen/renderers/harness/raycast.glsl reads them; the
// vertex colours of the meshes that have them, 3 texels a triangle.
struct MeshBuffers {
  std::vector<float> nodes, triangles, texcoords, tangents, colors;
  std::vector<int> first_node;  // per object (meshes only)
  // Per object: its triangle t's colours start at texel colors_base + 3t (t counted over every
  // mesh, as facet_triangles counts them); −1 without colours.
  std::vector<double> colors_base;
};

MeshBuffers mesh_buffers(const Scene& s, const Material* fallback) {
  MeshBuffers b;
  auto push = [](std::vector<float>& v, const Vec3& x, double w) {
    v.insert(v.end(), {float(x.x), float(x.y), float(x.z), float(w)});
  };
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    b.first_node.push_back(int(b.nodes.size() / 8));
    b.colors_base.push_back(-1);
    if (o.type != Object::Type::Mesh) continue;
    const Mesh& m = *o.mesh;
    // A normal-mapped mesh's corner tangents (scene/tangents.h), 3 texels a triangle; 0 elsewhere.
    const auto set = s.material_of(i, fallback).frame_uv();
    const std::vector<std::array<double, 4>> corners = set ? mesh_tangents(m, *set)
                                                          : std::vector<std::array<double, 4>>{};
    int node0 = int(b.nodes.size() / 8), tri0 = int(b.triangles.size() / 24);
    if (!m.colors.empty()) b.colors_base.back() = double(b.colors.size() / 4) - 3.0 * tri0;
    for (const auto& n : m.nodes) {
      push(b.nodes, n.lo, n.count > 0 ? double(tri0 + int(n.start)) : double(node0 + n.right));
      push(b.nodes, n.hi, double(n.count));
    }
    for (uint32_t t : m.order) {
      const auto& k = m.triangles[t];
      const uint32_t t_index = t;
      for (int c = 0; c < 3; ++c) push(b.triangles, m.positions[k[size_t(c)]], 0);
      for (int c = 0; c < 3; ++c) push(b.triangles, m.normals[k[size_t(c)]], 0);
      for (int c = 0; c < 3; ++c) {
        std::array<double, 2> st[2] = {{0, 0}, {0, 0}};
        for (size_t set = 0; set < 2; ++set)
          if (!m.texcoords[set].empty()) st[set] = m.texcoords[set][k[size_t(c)]];
        b.texcoords.insert(b.texcoords.end(), {float(st[0][0]), float(st[0][1]), float(st[1][0]), float(st[1][1])});
        const std::array<double, 4> t = corners.empty() ? std::array<double, 4>{} : corners[3 * size_t(t_index) + size_t(c)];
        b.tangents.insert(b.tangents.end(), {float(t[0]), float(t[1]), float(t[2]), float(t[3])});
        if (m.colors.empty()) continue;
        const auto& rgba = m.colors[k[size_t(c)]];
        b.colors.insert(b.colors.end(), {float(rgba[0]), float(rgba[1]), float(rgba[2]), float(rgba[3])});
      }
    }
  }
  // Texture buffers may not be empty.
  if (b.nodes.empty()) b.nodes.assign(8, 0);
  if (b.triangles.empty()) b.triangles.assign(24, 0);
  if (b.texcoords.empty()) b.texcoords.assign(12, 0);
  if (b.tangents.empty()) b.tangents.assign(12, 0);
  if (b.colors.empty()) b.colors.assign(4, 1);
  return b;
}

GLuint texture_buffer(const std::vector<float>& data, GLuint& buffer) {
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_STATIC_DRAW);
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_BUFFER, tex);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, buffer);
  return tex;
}

// A job's scene as raycast.glsl reads it: the objects in the order of their hierarchy
// (scene/bvh.h), 4 texels each; the hierarchy, 2 texels a node; the lights, 4 texels each
// (targets/glsl_lights.h's encoding); the meshes'.
struct SceneBuffers {
  std::vector<float> objects, hierarchy, lights;
  MeshBuffers meshes;
  // The cut-outs (raycast.glsl's facet_cutouts), 4 texels an object, and their alpha images
  // one above another in an atlas of atlas_width × atlas_height RGBA texels (the value in r).
  std::vector<float> cutouts, atlas;
  int atlas_width = 1, atlas_height = 1;
};

// The cut-outs' alpha images, one above another (raycast.glsl's facet_alpha_atlas): each
// material's once, the channel its alpha takes, sRGB decoded per texel where it says so (as
// every target samples it), the value in r.
struct AlphaAtlas {
  std::map<const Material*, std::array<int, 4>> rects;  // x0, y0, width, height
  std::vector<std::vector<float>> images;              // in the order of their y0, each its own width
  int width = 1, height = 0;

  const std::array<int, 4>& add(const Material& m, const TextureRef& image) {
    auto known = rects.find(&m);
    if (known != rects.end()) return known->second;
    const Texels& x = *image.texels;
    const int channel = image.channel == "rgb" ? 0 : int(std::string("rgba").find(image.channel[0]));
    std::vector<float> values(size_t(x.width) * size_t(x.height));
    for (int j = 0; j < x.height; ++j)
      for (int i = 0; i < x.width; ++i) {
        const double v = x.at(i, j)[channel];
        values[size_t(j) * size_t(x.width) + size_t(i)] = float(image.sampler.srgb && channel < 3 ? srgb_to_linear(v) : v);
      }
    images.push_back(std::move(values));
    width = std::max(width, x.width);
    height += x.height;
    return rects[&m] = {0, height - x.height, x.width, x.height};
  }
  // RGBA texels, width × max(height, 1), rows from y = 0.
  std::vector<float> texels() const {
    std::vector<float> out(size_t(width) * size_t(std::max(height, 1)) * 4, 0.0f);
    std::vector<std::array<int, 4>> order;
    for (const auto& [m, r] : rects) order.push_back(r);
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& c) { return a[1] < c[1]; });
    for (size_t k = 0; k < order.size(); ++k)
      for (int j = 0; j < order[k][3]; ++j)
        for (int i = 0; i < order[k][2]; ++i)
          out[(size_t(order[k][1] + j) * size_t(width) + size_t(i)) * 4] = images[k][size_t(j) * size_t(order[k][2]) + size_t(i)];
    return out;
  }
};

// Object i's cut-out (Material::masked()) as raycast.glsl's facet_cutouts reads it: 5 texels.
void push_cutout(const Material& m, AlphaAtlas& atlas, std::vector<float>& out) {
  std::array<double, 20> t{};
  t[0] = m.masked() ? *m.alpha_cutoff : -1;
  t[1] = m.alpha.number;
  const TextureRef* value = m.alpha.texture.get();
  if (m.masked() && value) t[16] = value->bias[0];  // the offset (a cut-out takes no vertex colour: material.cpp)
  if (const TextureRef* image = value; m.masked() && image && image->has_image()) {
    const auto& r = atlas.add(m, *image);
    const double cs = std::cos(image->rotation), sn = std::sin(image->rotation);
    t[2] = image->uv;
    t[3] += 1;
    t[4] = r[0], t[5] = r[1], t[6] = r[2], t[7] = r[3];
    t[8] = cs * image->scale[0], t[9] = sn * image->scale[1], t[10] = -sn * image->scale[0], t[11] = cs * image->scale[1];
    t[12] = image->offset[0], t[13] = image->offset[1];
    t[14] = int(image->sampler.wrap[0]) + 4 * int(image->sampler.wrap[1]);
    t[15] = image->sampler.filter == TextureFilter::Bilinear ? 1 : 0;
  }
  for (double v : t) out.push_back(float(v));
}

// Object i's 4 texels (raycast.glsl's facet_objects): its shape, its normal and kind, its
// axis and material pass, its index.
void push_object(const Scene& s, size_t i, const MeshBuffers& meshes, size_t pass, std::vector<float>& out) {
  const Object& o = s.objects[i];
  std::array<double, 16> t{};
  if (o.type == Object::Type::Sphere) {
    t = {o.center.x, o.center.y, o.center.z, o.radius, 0, 0, 0, double(kSphere)};
  } else if (o.type == Object::Type::Plane) {
    Vec3 a, b;
    o.plane_axes(a, b);
    t = {o.point.x, o.point.y, o.point.z, o.size, o.normal.x, o.normal.y, o.normal.z, double(kSquare), a.x, a.y, a.z};
  } else {
    t = {double(meshes.first_node[i]), 0, 0, 0, 0, 0, 0, double(kMesh)};
  }
  t[11] = double(pass);
  t[12] = double(i);
  if (meshes.colors_base[i] != -1) t[13] = meshes.colors_base[i], t[14] = 1;
  for (double v : t) out.push_back(float(v));
}

SceneBuffers scene_buffers(const Scene& s, const Material* fallback, const std::vector<size_t>& pass_of) {
  SceneBuffers b;
  b.meshes = mesh_buffers(s, fallback);
  const ObjectBvh bvh = object_bvh(s, false);  // its rays only meet objects: the tight boxes
  AlphaAtlas atlas;
  for (uint32_t i : bvh.order) {
    push_object(s, i, b.meshes, pass_of[i], b.objects);
    push_cutout(s.material_of(i, fallback), atlas, b.cutouts);
  }
  b.atlas = atlas.texels();
  b.atlas_width = atlas.width;
  b.atlas_height = std::max(atlas.height, 1);
  for (const Mesh::Node& n : bvh.nodes) {
    const double link = n.count > 0 ? double(n.start) : double(n.right);
    b.hierarchy.insert(b.hierarchy.end(), {float(n.lo.x), float(n.lo.y), float(n.lo.z), float(link), float(n.hi.x),
                                           float(n.hi.y), float(n.hi.z), float(n.count)});
  }
  for (const Light& l : s.lights) {
    const std::array<float, 16> e = glsl_light::encode(l);
    b.lights.insert(b.lights.end(), e.begin(), e.end());
  }
  // Texture buffers may not be empty.
  if (b.objects.empty()) b.objects.assign(16, 0);
  if (b.hierarchy.empty()) b.hierarchy.assign(8, 0);
  if (b.lights.empty()) b.lights.assign(16, 0);
  if (b.cutouts.empty()) b.cutouts.assign(20, 0);
  return b;
}

GLuint float_texture(int width, int height, const float* rgba);

// The scene's texture buffers, bound while they live: on units 0, 1, … in kSamplers' order,
// and the cut-outs' atlas after them.
class SceneTextures {
 public:
  static constexpr int kCount = 9;
  explicit SceneTextures(const SceneBuffers& b) {
    const std::vector<float>* data[kCount] = {&b.meshes.nodes,   &b.meshes.triangles, &b.meshes.texcoords,
                                              &b.meshes.tangents, &b.meshes.colors,   &b.objects,
                                              &b.hierarchy,       &b.lights,          &b.cutouts};
    for (int i = 0; i < kCount; ++i) textures_[i] = texture_buffer(*data[i], buffers_[i]);
    atlas_ = float_texture(b.atlas_width, b.atlas_height, b.atlas.data());
  }
  ~SceneTextures() {
    glDeleteTextures(kCount, textures_);
    glDeleteBuffers(kCount, buffers_);
    glDeleteTextures(1, &atlas_);
  }
  SceneTextures(const SceneTextures&) = delete;
  SceneTextures& operator=(const SceneTextures&) = delete;
  void bind(GLuint prog) const {
    static const char* kSamplers[kCount] = {"facet_bvh",      "facet_triangles",    "facet_texcoords",
                                            "facet_tangents", "facet_colors",       "facet_objects",
                                            "facet_scene_bvh", "facet_light_buffer", "facet_cutouts"};
    // The atlas first: a texture made later (a material's image, float_texture()) binds to the
    // unit active then, which must be a buffer texture's, whose 2D binding no sampler reads.
    glActiveTexture(GLenum(GL_TEXTURE0 + kCount));
    glBindTexture(GL_TEXTURE_2D, atlas_);
    glUniform1i(glGetUniformLocation(prog, "facet_alpha_atlas"), kCount);
    for (int i = 0; i < kCount; ++i) {
      glActiveTexture(GLenum(GL_TEXTURE0 + i));
      glBindTexture(GL_TEXTURE_BUFFER, textures_[i]);
      glUniform1i(glGetUniformLocation(prog, kSamplers[i]), i);
    }
  }

 private:
  GLuint buffers_[kCount] = {};
  GLuint textures_[kCount] = {};
  GLuint atlas_ = 0;
};

// The material's images follow the scene's texture buffers and the cut-outs' atlas.
constexpr int kMaterialUnit = SceneTextures::kCount + 1;

// An RGBA32F texture holding `rgba` (width × height texels, row 0 first: texelFetch's
// j is row j, no flip), one level, nearest: the harnesses read it by texelFetch only.
GLuint float_texture(int width, int height, const float* rgba) {
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, rgba);
  return tex;
}

// A material's images as RGBA32F textures holding the files' values, read by texelFetch
// only (glsl/textures.glsl), on units kMaterialUnit, …, bound to facet_texture_<parameter>.
class MaterialImages {
 public:
  explicit MaterialImages(const MaterialProgram& p) {
    for (const auto& c : image_calls(p)) {
      textures_.push_back(float_texture(c.texels->width, c.texels->height, c.texels->rgba.data()));
      names_.push_back("facet_texture_" + c.name);
    }
  }
  ~MaterialImages() {
    if (!textures_.empty()) glDeleteTextures(GLsizei(textures_.size()), textures_.data());
  }
  MaterialImages(const MaterialImages&) = delete;
  MaterialImages& operator=(const MaterialImages&) = delete;
  void bind(GLuint prog) const {
    for (size_t i = 0; i < textures_.size(); ++i) {
      glActiveTexture(GLenum(GL_TEXTURE0 + kMaterialUnit + i));
      glBindTexture(GL_TEXTURE_2D, textures_[i]);
      glUniform1i(glGetUniformLocation(prog, names_[i].c_str()), GLint(kMaterialUnit + i));
    }
  }

 private:
  std::vector<GLuint> textures_;
  std::vector<std::string> names_;
};

// Setting a program's uniforms by name.
struct Uniforms {
  GLuint prog;
  GLint loc(const std::string& name) const { return glGetUniformLocation(prog, name.c_str()); }
  void vec3(const std::string& name, const Vec3& v) const { glUniform3f(loc(name), float(v.x), float(v.y), float(v.z)); }
  void vec4(const std::string& name, double x, double y, double z, double w) const {
    glUniform4f(loc(name), float(x), float(y), float(z), float(w));
  }
};

void set_camera(const Uniforms& u, const Scene& s, int width, int height) {
  Camera::Basis b = s.camera.basis();
  glUniform2f(u.loc("facet_resolution"), float(width), float(height));
  u.vec3("facet_camera_position", s.camera.position);
  u.vec3("facet_camera_forward", b.forward);
  u.vec3("facet_camera_right", b.right);
  u.vec3("facet_camera_up", b.up);
  glUniform2f(u.loc("facet_camera_tan"), float(b.tan_half * width / height), float(b.tan_half));
  glUniform1i(u.loc("facet_camera_orthographic"), s.camera.orthographic ? 1 : 0);
  glUniform3f(u.loc("facet_ambient"), float(s.ambient[0]), float(s.ambient[1]), float(s.ambient[2]));
}

// The objects (those of pass `pass` shaded), how many lights, and the shadow rays' offset,
// relative to the scene's size.
void set_scene(const Uniforms& u, const Scene& s, size_t pass) {
  double scale = length(s.camera.position);
  for (const Object& o : s.objects) {
    Vec3 c;
    double r;
    o.bounds(c, r);
    scale = std::max(scale, length(c) + r);
  }
  glUniform1i(u.loc("facet_object_count"), int(s.objects.size()));
  glUniform1i(u.loc("facet_light_count"), int(s.lights.size()));
  glUniform1i(u.loc("facet_pass"), int(pass));
  glUniform1i(u.loc("facet_probe_turns"), 2);
  glUniform1f(u.loc("facet_shadow_offset"), float(kGlShadowOffset * std::max(scale, 1.0)));
}

// A job's scene as the harness draws it, pass by pass: its material passes, its
// buffers (bound while it lives).
struct PassScene {
  explicit PassScene(const RenderJob& j)
      : job(j), passes(material_passes(j, &pass_of)),
        buffers(scene_buffers(j.scene, j.material ? &*j.material : nullptr, pass_of)), textures(buffers) {
    if (!job.code_override.empty() && passes.size() != 1)
      throw std::runtime_error("code_override needs a scene with one material");
  }
  const RenderJob& job;
  std::vector<size_t> pass_of;
  std::vector<const Material*> passes;
  SceneBuffers buffers;
  SceneTextures textures;
  // pass_name()<suffix>: the file a pass's source is written to (every pass's, past the last
  // pass: the G-buffer's).
  std::string file(size_t pass, const std::string& suffix) const {
    return (pass < passes.size() ? pass_name(job, pass, passes.size(), passes[pass]->name) : job_name(job)) + suffix;
  }
};

// The program of `source` (written into the job's workdir as `file`) in use for pass `pass`,
// every uniform and texture the harness reads set, the pass's material's images bound while
// `images` lives: 0, with `error` set, when it does not compile.
GLuint use_program(GLuint vertex, const PassScene& ps, size_t pass, const std::string& source, const std::string& file,
                   std::unique_ptr<MaterialImages>& images, std::string& error) {
  const RenderJob& job = ps.job;
  if (!job.workdir.empty()) {
    std::filesystem::create_directories(job.workdir);
    write_file_atomic((std::filesystem::path(job.workdir) / file).string(), source);
  }
  const Material& m = *ps.passes[std::min(pass, ps.passes.size() - 1)];
  GLuint prog = fragment_program(vertex, source, "the GLSL of \"" + m.name + "\"", error);
  if (!prog) return 0;
  glUseProgram(prog);
  const Uniforms u{prog};
  set_camera(u, job.scene, job.width, job.height);
  set_scene(u, job.scene, pass);
  ps.textures.bind(prog);
  images = std::make_unique<MaterialImages>(compile(m));
  images->bind(prog);
  return prog;
}

// One full-screen draw into the bound framebuffer: "", or GL's error.
std::string draw_once(GLuint vao) {
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (GLenum e = glGetError(); e != GL_NO_ERROR) return fmt::format("OpenGL error 0x{:x}", e);
  return "";
}

// Lights [first, end) of a scene, a draw's share (raycast.glsl: llvmpipe cuts a shader
// invocation's loops short past 65,535 turns).
struct LightRange {
  int first, end;
};

// Takes the lights of `ranges` in turn, each through draw(range, cut), which sets `cut` when the
// draw's loops were cut short: that range again in two halves, and at most as many lights a draw
// from then on (`most`, kept from job to pass: every cut draw costs a draw's worth of turns).
// "", or why not.
std::string in_turns(std::vector<LightRange> ranges, int& most,
                     const std::function<std::string(LightRange, bool&)>& draw) {
  while (!ranges.empty()) {
    LightRange r = ranges.back();
    ranges.pop_back();
    if (r.end - r.first > most) {
      ranges.push_back({r.first + most, r.end});
      r.end = r.first + most;
    }
    bool cut = false;
    if (std::string e = draw(r, cut); !e.empty()) return e;
    if (!cut) continue;
    if (r.end - r.first <= 1)
      return "a pixel's shadow rays took more loop turns than llvmpipe allows a shader invocation (65,535) for "
             "a single light: the scene is too deep for the GL ray caster";
    most = (r.end - r.first) / 2;
    ranges.push_back(r);
  }
  return "";
}

// Sets the draw's lights (raycast.glsl: facet_light_first, facet_light_count).
void set_lights(GLuint prog, LightRange r) {
  glUniform1i(glGetUniformLocation(prog, "facet_light_first"), r.first);
  glUniform1i(glGetUniformLocation(prog, "facet_light_count"), r.end - r.first);
}

// Pass `pass` drawn with `prog` into `out`: every light at once where llvmpipe lets it, in turns
// where not (the ambient colour with the first turn only; the turns add up).
std::string draw_pass(GLuint prog, GLuint vao, const FloatFramebuffer& fb, const Scene& s, int& most,
                      RenderOutcome& out) {
  return in_turns({{0, int(s.lights.size())}}, most, [&](LightRange r, bool& cut) {
    set_lights(prog, r);
    const float a = r.first == 0 ? 1.0f : 0.0f;
    glUniform3f(glGetUniformLocation(prog, "facet_ambient"), a * float(s.ambient[0]), a * float(s.ambient[1]),
                a * float(s.ambient[2]));
    if (std::string e = draw_once(vao); !e.empty()) return e;
    const std::vector<float> px = fb.read();
    for (size_t i = 3; i < px.size() && !cut; i += 4) cut = px[i] < 0;
    if (!cut) add_bottom_up(px, out);
    return std::string();
  });
}

// Each pass draws the scene with one material's program, its objects shaded and the others black; the passes add up.
RenderOutcome draw_passes(GLuint vertex, GLuint vao, const PassScene& ps) {
  RenderOutcome out;
  const RenderJob& job = ps.job;
  FloatFramebuffer fb(job.width, job.height);
  if (!fb.complete()) {
    out.error = "no RGBA32F framebuffer";
    return out;
  }
  out.image = Image(job.width, job.height);
  out.alpha.assign(size_t(job.width) * size_t(job.height), 0);
  int most = std::numeric_limits<int>::max();  // lights a draw takes, as in_turns() learns it
  for (size_t k = 0; k < ps.passes.size(); ++k) {
    std::string source = !job.code_override.empty() ? job.code_override : GlRenderer::fragment_source(*ps.passes[k]);
    std::unique_ptr<MaterialImages> images;
    GLuint prog = use_program(vertex, ps, k, source, ps.file(k, ".frag"), images, out.error);
    if (!prog) return out;
    out.error = draw_pass(prog, vao, fb, job.scene, most, out);
    glDeleteProgram(prog);
    if (!out.error.empty()) return out;
  }
  out.ok = true;
  return out;
}

// The G-buffer's draws: each writes two layers of the visibility image for its lights (GL 3.3
// promises 8 draw buffers: 6 + 2), the first the geometry images too; every draw casts the
// camera rays again, a small cost beside its shadow rays. A draw's lights are those of two
// layers, fewer where llvmpipe cut its loops short (the bits of a layer's draws add up).
std::string cast_layers(GLuint prog, GLuint vao, const FloatFramebuffer& fb, int lights, GBuffer& g) {
  constexpr int kLayers = 8 - GBuffer::Visibility;  // a draw's
  const size_t texels = size_t(g.width) * size_t(g.height) * 4;
  g.images[GBuffer::Visibility].assign(texels * size_t(g.layers), 0.0f);
  const int span = kLayers * glsl_light::kVisibilityLayerLights;
  std::vector<LightRange> ranges;
  for (int first = 0; first < std::max(lights, 1); first += span) ranges.insert(ranges.begin(), {first, std::min(first + span, lights)});
  bool geometry = true;  // not yet drawn
  int most = span;
  return in_turns(ranges, most, [&](LightRange r, bool& cut) {
    const int layer = r.first / glsl_light::kVisibilityLayerLights;
    std::vector<bool> on(8, geometry);
    for (int k = 0; k < kLayers; ++k) on[size_t(GBuffer::Visibility + k)] = layer + k < g.layers;
    fb.draw_to(on);
    glUniform1i(glGetUniformLocation(prog, "facet_first_layer"), layer);
    set_lights(prog, r);
    if (std::string e = draw_once(vao); !e.empty()) return e;
    std::vector<std::vector<float>> drawn;
    for (int k = 0; k < kLayers && layer + k < g.layers; ++k) drawn.push_back(fb.read(GBuffer::Visibility + k));
    for (const auto& d : drawn)
      for (size_t i = 0; i < d.size() && !cut; ++i) cut = d[i] < 0;
    if (cut) return std::string();
    if (geometry)
      for (int i = 0; i < GBuffer::Visibility; ++i) g.images[size_t(i)] = fb.read(i);
    geometry = false;
    for (size_t k = 0; k < drawn.size(); ++k)  // disjoint bits: adding is or-ing, exact below 2^24
      for (size_t i = 0; i < texels; ++i) g.images[GBuffer::Visibility][(size_t(layer) + k) * texels + i] += drawn[k][i];
    return std::string();
  });
}

}  // namespace

RenderOutcome GlRenderer::render(const RenderJob& job) {
  RenderOutcome out;
  auto start = std::chrono::steady_clock::now();
  if (!ok()) {
    out.error = error_;
    return out;
  }
  try {
    const PassScene ps(job);
    out = draw_passes(state_->vertex, state_->vao, ps);
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::vector<RenderOutcome> GlRenderer::render(const std::vector<RenderJob>& jobs, const RenderProgress& progress) {
  return render_each(jobs, progress, [&](const RenderJob& job) { return render(job); });
}

GBufferOutcome GlRenderer::gbuffer(const RenderJob& job) {
  GBufferOutcome out;
  if (!ok()) {
    out.error = error_;
    return out;
  }
  try {
    const PassScene ps(job);
    GBuffer& g = out.gbuffer;
    g.width = job.width;
    g.height = job.height;
    g.layers = GBuffer::layers_for(int(job.scene.lights.size()));
    FloatFramebuffer fb(job.width, job.height, 8);
    if (!fb.complete()) throw std::runtime_error("no framebuffer of eight RGBA32F images");
    // Every pass's objects at once: the first material only brings the light loop's declarations.
    std::unique_ptr<MaterialImages> images;
    GLuint prog = use_program(state_->vertex, ps, ps.passes.size(), fragment_source(*ps.passes[0], true),
                              ps.file(ps.passes.size(), ".gbuffer.frag"), images, out.error);
    if (!prog) return out;
    out.error = cast_layers(prog, state_->vao, fb, int(job.scene.lights.size()), g);
    glDeleteProgram(prog);
    if (!out.error.empty()) return out;
    const Scene& s = job.scene;
    g.camera_position = {float(s.camera.position.x), float(s.camera.position.y), float(s.camera.position.z)};
    g.ambient = {float(s.ambient[0]), float(s.ambient[1]), float(s.ambient[2])};
    g.light_count = int(s.lights.size());
    for (const Light& l : s.lights) {
      const std::array<float, 16> e = glsl_light::encode(l);
      g.lights.insert(g.lights.end(), e.begin(), e.end());
    }
    out.ok = true;
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

GBufferOutcome cast_gbuffer(GlRenderer& gl, const RenderJob& job) { return gl.gbuffer(job); }

namespace {

// The program's active uniforms: name → (location, type). Arrays answer to
// "name" and "name[0]" alike.
std::map<std::string, std::pair<GLint, GLenum>> active_uniforms(GLuint prog) {
  std::map<std::string, std::pair<GLint, GLenum>> out;
  GLint count = 0;
  glGetProgramiv(prog, GL_ACTIVE_UNIFORMS, &count);
  for (GLint i = 0; i < count; ++i) {
    char name[256];
    GLint size = 0;
    GLenum type = 0;
    glGetActiveUniform(prog, GLuint(i), sizeof name, nullptr, &size, &type, name);
    std::string n = name;
    GLint loc = glGetUniformLocation(prog, name);
    out[n] = {loc, type};
    if (n.size() > 3 && n.compare(n.size() - 3, 3, "[0]") == 0) out[n.substr(0, n.size() - 3)] = {loc, type};
  }
  return out;
}

// Sets `values` on the uniform by its declared type; an unused name is ignored,
// a mismatched arity is an error.
std::string set_uniform(const std::map<std::string, std::pair<GLint, GLenum>>& active, const std::string& name,
                        const std::vector<double>& v) {
  auto it = active.find(name);
  if (it == active.end()) return "";
  auto [loc, type] = it->second;
  auto need = [&](size_t n) {
    return v.size() == n ? std::string() : fmt::format("uniform {} takes {} values, given {}", name, n, v.size());
  };
  auto f = [&](size_t i) { return GLfloat(v[i]); };
  std::string error;
  switch (type) {
    case GL_FLOAT: if ((error = need(1)).empty()) glUniform1f(loc, f(0)); break;
    case GL_FLOAT_VEC2: if ((error = need(2)).empty()) glUniform2f(loc, f(0), f(1)); break;
    case GL_FLOAT_VEC3: if ((error = need(3)).empty()) glUniform3f(loc, f(0), f(1), f(2)); break;
    case GL_FLOAT_VEC4: if ((error = need(4)).empty()) glUniform4f(loc, f(0), f(1), f(2), f(3)); break;
    case GL_INT:
    case GL_BOOL: if ((error = need(1)).empty()) glUniform1i(loc, GLint(v[0])); break;
    default: error = fmt::format("uniform {} has a type (0x{:x}) the harness does not set", name, type);
  }
  return error;
}

// A ShaderTexture as GL's: its target and name.
std::pair<GLenum, GLuint> shader_texture(const ShaderTexture& t, std::vector<GLuint>& buffers) {
  if (t.buffer) {
    buffers.push_back(0);
    return {GL_TEXTURE_BUFFER, texture_buffer(t.rgba, buffers.back())};
  }
  if (t.layers == 0) return {GL_TEXTURE_2D, float_texture(t.width, t.height, t.rgba.data())};
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D_ARRAY, tex);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA32F, t.width, t.height, t.layers, 0, GL_RGBA, GL_FLOAT, t.rgba.data());
  return {GL_TEXTURE_2D_ARRAY, tex};
}

// The shaders' textures (GlRenderer::draw()'s), made while it lives.
class DrawTextures {
 public:
  explicit DrawTextures(const std::vector<std::vector<ShaderTexture>>& images) : images_(images), textures_(images.size()) {
    for (size_t i = 0; i < images.size(); ++i)
      for (const ShaderTexture& t : images[i]) textures_[i].push_back(shader_texture(t, buffers_));
  }
  ~DrawTextures() {
    for (const auto& shader : textures_)
      for (const auto& t : shader) glDeleteTextures(1, &t.second);
    if (!buffers_.empty()) glDeleteBuffers(GLsizei(buffers_.size()), buffers_.data());
  }
  DrawTextures(const DrawTextures&) = delete;
  DrawTextures& operator=(const DrawTextures&) = delete;
  // Shader i's textures on units 0, 1, …, its program in use.
  void bind(size_t i, GLuint prog) const {
    for (size_t k = 0; i < textures_.size() && k < textures_[i].size(); ++k) {
      glActiveTexture(GLenum(GL_TEXTURE0 + k));
      glBindTexture(textures_[i][k].first, textures_[i][k].second);
      glUniform1i(glGetUniformLocation(prog, images_[i][k].name.c_str()), GLint(k));
    }
  }

 private:
  const std::vector<std::vector<ShaderTexture>>& images_;
  std::vector<std::vector<std::pair<GLenum, GLuint>>> textures_;
  std::vector<GLuint> buffers_;
};

}  // namespace

std::vector<RenderOutcome> GlRenderer::draw(const std::vector<ShaderDraw>& shaders, int width, int height,
                                            const std::function<void(size_t, bool)>& around,
                                            const std::vector<std::vector<ShaderTexture>>& images) {
  std::vector<RenderOutcome> out(shaders.size());
  if (!ok()) {
    for (auto& o : out) o.error = error_;
    return out;
  }
  FloatFramebuffer fb(width, height);
  glBindVertexArray(state_->vao);
  std::vector<GLuint> programs(shaders.size(), 0);
  const DrawTextures textures(images);
  auto use = [&](size_t i) {
    glUseProgram(programs[i]);
    textures.bind(i, programs[i]);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
  };
  // Compile and link all, each with its uniforms set (a program keeps them), then
  // the first draw of each: the JIT, not measured.
  for (size_t i = 0; i < shaders.size(); ++i) {
    programs[i] = fragment_program(state_->vertex, shaders[i].fragment_source, "the GLSL of \"" + shaders[i].name + "\"",
                                   out[i].error);
    if (!programs[i]) continue;
    glUseProgram(programs[i]);
    auto active = active_uniforms(programs[i]);
    for (const auto& [name, values] : shaders[i].uniforms)
      if (std::string e = set_uniform(active, name, values); !e.empty()) out[i].error = e;
  }
  for (size_t i = 0; i < shaders.size(); ++i) {
    if (!programs[i] || !out[i].error.empty()) continue;
    use(i);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
  }
  for (size_t i = 0; i < shaders.size(); ++i) {
    if (!programs[i] || !out[i].error.empty()) continue;
    use(i);
    // Once more untimed, so the measured draw finds the state as its own last
    // draw left it, whatever program ran before.
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    auto start = std::chrono::steady_clock::now();
    if (around) around(i, true);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    if (around) around(i, false);
    out[i].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out[i].image = Image(width, height);
    out[i].alpha.assign(size_t(width) * size_t(height), 0);
    add_bottom_up(fb.read(), out[i]);
    if (GLenum e = glGetError(); e != GL_NO_ERROR) out[i].error = fmt::format("OpenGL error 0x{:x}", e);
    out[i].ok = out[i].error.empty();
  }
  for (GLuint p : programs)
    if (p) glDeleteProgram(p);
  return out;
}

}  // namespace facet
