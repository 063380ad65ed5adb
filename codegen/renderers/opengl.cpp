// OpenGL renderer: EGL surfaceless on Mesa (llvmpipe without a GPU), as
// shared/notes/opengl.md recommends. The fragment shader is facet's generated
// GLSL 3.30 (library + light loop) under codegen/renderers/harness/raycast.glsl.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>


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
const int kMaxLights = 8, kMaxObjects = 16;
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
  GlslParts parts = glsl_parts(p, Target::Glsl, m.source);
  std::string sample = p.has_textures() ? "    facet_sample_textures(facet_uv(hit, p, best, 0), facet_uv(hit, p, best, 1));\n" : "";
  if (p.normal_mapped())
    sample += "    vec4 frame = facet_uv_tangent_at(hit, p, best);\n"
              "    facet_uv_tangent = frame.xyz;\n    facet_uv_handedness = frame.w;\n";
  return std::string("#version 330 core\n") + (gbuffer ? "#define FACET_GBUFFER\n" : "") + parts.header +
         parts.library + parts.lights +
         render_harness("raycast.glsl", {{"sphere", std::to_string(kSphere)},
                                         {"square", std::to_string(kSquare)},
                                         {"mesh", std::to_string(kMesh)},
                                         {"directional", std::to_string(glsl_light::kDirectional)},
                                         {"sample", sample}});
}

namespace {

// Every mesh's BVH and triangles, concatenated: 2 RGBA32F texels a node, 6 a
// triangle (in BVH order), as codegen/renderers/harness/raycast.glsl reads them.
struct MeshBuffers {
  std::vector<float> nodes, triangles, texcoords, tangents;
  std::vector<int> first_node;  // per object (meshes only)
};

MeshBuffers mesh_buffers(const Scene& s, const Material* fallback) {
  MeshBuffers b;
  auto push = [](std::vector<float>& v, const Vec3& x, double w) {
    v.insert(v.end(), {float(x.x), float(x.y), float(x.z), float(w)});
  };
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    b.first_node.push_back(int(b.nodes.size() / 8));
    if (o.type != Object::Type::Mesh) continue;
    const Mesh& m = *o.mesh;
    // A normal-mapped mesh's corner tangents (scene/tangents.h), 3 texels a triangle; 0 elsewhere.
    const auto& nm = s.material_of(i, fallback).normal_map;
    const std::vector<std::array<double, 4>> corners = nm ? mesh_tangents(m, nm->texture().uv)
                                                          : std::vector<std::array<double, 4>>{};
    int node0 = int(b.nodes.size() / 8), tri0 = int(b.triangles.size() / 24);
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
      }
    }
  }
  // Texture buffers may not be empty.
  if (b.nodes.empty()) b.nodes.assign(8, 0);
  if (b.triangles.empty()) b.triangles.assign(24, 0);
  if (b.texcoords.empty()) b.texcoords.assign(12, 0);
  if (b.tangents.empty()) b.tangents.assign(12, 0);
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

// The meshes' texture buffers, bound while they live.
class MeshTextures {
 public:
  explicit MeshTextures(const MeshBuffers& m)
      : textures_{texture_buffer(m.nodes, buffers_[0]), texture_buffer(m.triangles, buffers_[1]),
                  texture_buffer(m.texcoords, buffers_[2]), texture_buffer(m.tangents, buffers_[3])} {}
  ~MeshTextures() {
    glDeleteTextures(4, textures_);
    glDeleteBuffers(4, buffers_);
  }
  MeshTextures(const MeshTextures&) = delete;
  MeshTextures& operator=(const MeshTextures&) = delete;
  // On texture units 0 and 1, as raycast.glsl's facet_bvh and facet_triangles.
  void bind(GLuint prog) const {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_BUFFER, textures_[0]);
    glUniform1i(glGetUniformLocation(prog, "facet_bvh"), 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_BUFFER, textures_[1]);
    glUniform1i(glGetUniformLocation(prog, "facet_triangles"), 1);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_BUFFER, textures_[2]);
    glUniform1i(glGetUniformLocation(prog, "facet_texcoords"), 2);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_BUFFER, textures_[3]);
    glUniform1i(glGetUniformLocation(prog, "facet_tangents"), 3);
  }

 private:
  GLuint buffers_[4] = {0, 0, 0, 0};
  GLuint textures_[4];
};

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
// only (glsl/textures.glsl), on units 4, 5, …, bound to facet_texture_<parameter>.
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
      glActiveTexture(GLenum(GL_TEXTURE4 + i));
      glBindTexture(GL_TEXTURE_2D, textures_[i]);
      glUniform1i(glGetUniformLocation(prog, names_[i].c_str()), GLint(4 + i));
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

// The generated GLSL's facet_lights[], encoded as targets/glsl_lights.h says.
void set_lights(const Uniforms& u, const Scene& s) {
  glUniform1i(u.loc("facet_light_count"), int(s.lights.size()));
  for (size_t i = 0; i < s.lights.size(); ++i) {
    const std::array<float, 16> e = glsl_light::encode(s.lights[i]);
    const char* fields[] = {"position", "color", "spot", "attenuation"};
    for (int f = 0; f < 4; ++f)
      glUniform4fv(u.loc(fmt::format("facet_lights[{}].{}", i, fields[f])), 1, &e[size_t(f) * 4]);
  }
}

// The objects, those of pass `pass` shaded; the shadow rays' offset, relative to the scene's size.
void set_objects(const Uniforms& u, const Scene& s, const MeshBuffers& meshes, const std::vector<size_t>& pass_of,
                 size_t pass) {
  double scale = length(s.camera.position);
  glUniform1i(u.loc("facet_object_count"), int(s.objects.size()));
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    std::string at = fmt::format("[{}]", i);
    Vec3 c;
    double r;
    o.bounds(c, r);
    scale = std::max(scale, length(c) + r);
    glUniform1i(u.loc("facet_object_shaded" + at), pass_of[i] == pass ? 1 : 0);
    if (o.type == Object::Type::Sphere) {
      u.vec4("facet_object_shape" + at, o.center.x, o.center.y, o.center.z, o.radius);
      u.vec4("facet_object_normal" + at, 0, 0, 0, kSphere);
    } else if (o.type == Object::Type::Plane) {
      Vec3 a, b;
      o.plane_axes(a, b);
      u.vec4("facet_object_shape" + at, o.point.x, o.point.y, o.point.z, o.size);
      u.vec4("facet_object_normal" + at, o.normal.x, o.normal.y, o.normal.z, kSquare);
      u.vec4("facet_object_axis" + at, a.x, a.y, a.z, 0);
    } else {
      u.vec4("facet_object_shape" + at, meshes.first_node[i], 0, 0, 0);
      u.vec4("facet_object_normal" + at, 0, 0, 0, kMesh);
    }
  }
  glUniform1f(u.loc("facet_shadow_offset"), float(kGlShadowOffset * std::max(scale, 1.0)));
}

// Why the GL harness cannot draw this job, or "".
std::string job_limits(const RenderJob& job, size_t passes) {
  const Scene& s = job.scene;
  if (s.lights.size() > size_t(kMaxLights) || s.objects.size() > size_t(kMaxObjects))
    return fmt::format("the GLSL renderer takes at most {} lights and {} objects", kMaxLights, kMaxObjects);
  if (!job.code_override.empty() && passes != 1) return "code_override needs a scene with one material";
  return "";
}

// A job's scene as the harness draws it, pass by pass: its material passes, its
// meshes' texture buffers (bound while it lives).
struct PassScene {
  explicit PassScene(const RenderJob& j)
      : job(j), passes(material_passes(j, &pass_of)),
        meshes(mesh_buffers(j.scene, j.material ? &*j.material : nullptr)), textures(meshes) {}
  const RenderJob& job;
  std::vector<size_t> pass_of;
  std::vector<const Material*> passes;
  MeshBuffers meshes;
  MeshTextures textures;
  // "<material>_<scene>[_<pass's material>]<suffix>": the file a pass's source is written to.
  std::string file(size_t pass, const std::string& suffix) const {
    std::string base = (job.material ? identifier(job.material->name) + "_" : std::string()) + identifier(job.scene.name);
    if (passes.size() > 1) base += "_" + identifier(passes[pass]->name);
    return base + suffix;
  }
};

// Pass `pass` of the scene drawn with `source` (written into the job's workdir as
// `file`) into the bound framebuffer, every uniform and texture the harness reads
// set: "", or why not.
std::string draw_pass(GLuint vertex, GLuint vao, const PassScene& ps, size_t pass, const std::string& source,
                      const std::string& file) {
  const RenderJob& job = ps.job;
  if (!job.workdir.empty()) {
    std::filesystem::create_directories(job.workdir);
    write_file_atomic((std::filesystem::path(job.workdir) / file).string(), source);
  }
  std::string error;
  GLuint prog = fragment_program(vertex, source, "the GLSL of \"" + ps.passes[pass]->name + "\"", error);
  if (!prog) return error;
  glUseProgram(prog);
  const Uniforms u{prog};
  set_camera(u, job.scene, job.width, job.height);
  set_lights(u, job.scene);
  set_objects(u, job.scene, ps.meshes, ps.pass_of, pass);
  ps.textures.bind(prog);
  const MaterialImages images(compile(*ps.passes[pass]));
  images.bind(prog);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDeleteProgram(prog);
  if (GLenum e = glGetError(); e != GL_NO_ERROR) return fmt::format("OpenGL error 0x{:x}", e);
  return "";
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
  for (size_t k = 0; k < ps.passes.size(); ++k) {
    std::string source = !job.code_override.empty() ? job.code_override : GlRenderer::fragment_source(*ps.passes[k]);
    out.error = draw_pass(vertex, vao, ps, k, source, ps.file(k, ".frag"));
    if (!out.error.empty()) return out;
    add_bottom_up(fb.read(), out);
  }
  out.ok = true;
  return out;
}

}  // namespace

std::vector<const Material*> material_passes(const RenderJob& job, std::vector<size_t>* pass_of) {
  const Scene& s = job.scene;
  const Material* fallback = job.material ? &*job.material : nullptr;
  std::vector<const Material*> passes;
  if (pass_of) pass_of->assign(s.objects.size(), 0);
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Material* m = &s.material_of(i, fallback);
    auto it = std::find(passes.begin(), passes.end(), m);
    if (pass_of) (*pass_of)[i] = size_t(it - passes.begin());
    if (it == passes.end()) passes.push_back(m);
  }
  return passes;
}

std::vector<RenderOutcome> GlRenderer::render(const std::vector<RenderJob>& jobs, const RenderProgress& progress) {
  return render_each(jobs, progress, [&](const RenderJob& job) { return render(job); });
}

RenderOutcome GlRenderer::render(const RenderJob& job) {
  RenderOutcome out;
  auto start = std::chrono::steady_clock::now();
  if (!ok()) {
    out.error = error_;
    return out;
  }
  try {
    const PassScene ps(job);
    if ((out.error = job_limits(job, ps.passes.size())).empty()) out = draw_passes(state_->vertex, state_->vao, ps);
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

GBufferOutcome GlRenderer::gbuffer(const RenderJob& job, size_t pass) {
  GBufferOutcome out;
  if (!ok()) {
    out.error = error_;
    return out;
  }
  try {
    const PassScene ps(job);
    if (!(out.error = job_limits(job, ps.passes.size())).empty()) return out;
    if (pass >= ps.passes.size()) throw std::out_of_range(fmt::format("no material pass {} in the job", pass));
    FloatFramebuffer fb(job.width, job.height, GBuffer::kImages);
    if (!fb.complete()) throw std::runtime_error("no framebuffer of seven RGBA32F images");
    std::string source = fragment_source(*ps.passes[pass], true);
    if (!(out.error = draw_pass(state_->vertex, state_->vao, ps, pass, source, ps.file(pass, ".gbuffer.frag"))).empty())
      return out;
    GBuffer& g = out.gbuffer;
    g.width = job.width;
    g.height = job.height;
    for (int i = 0; i < GBuffer::kImages; ++i) g.images[size_t(i)] = fb.read(i);
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

std::vector<std::pair<std::string, std::vector<double>>> shading_uniforms(const GBuffer& g) {
  auto values = [](const float* v, size_t n) { return std::vector<double>(v, v + n); };
  std::vector<std::pair<std::string, std::vector<double>>> out = {
      {"facet_camera_position", values(g.camera_position.data(), 3)},
      {"facet_ambient", values(g.ambient.data(), 3)},
      {"facet_light_count", {double(g.light_count)}}};
  const char* fields[] = {"position", "color", "spot", "attenuation"};
  for (int i = 0; i < g.light_count; ++i)
    for (int f = 0; f < 4; ++f)
      out.push_back({fmt::format("facet_lights[{}].{}", i, fields[f]), values(&g.lights[size_t(i * 16 + f * 4)], 4)});
  return out;
}

GBufferOutcome cast_gbuffer(GlRenderer& gl, const RenderJob& job, size_t pass) { return gl.gbuffer(job, pass); }

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

// The shaders' textures (GlRenderer::draw()'s), made while it lives.
class DrawTextures {
 public:
  explicit DrawTextures(const std::vector<std::vector<ShaderTexture>>& images) : images_(images), textures_(images.size()) {
    for (size_t i = 0; i < images.size(); ++i)
      for (const ShaderTexture& t : images[i]) textures_[i].push_back(float_texture(t.width, t.height, t.rgba.data()));
  }
  ~DrawTextures() {
    for (const auto& t : textures_)
      if (!t.empty()) glDeleteTextures(GLsizei(t.size()), t.data());
  }
  DrawTextures(const DrawTextures&) = delete;
  DrawTextures& operator=(const DrawTextures&) = delete;
  // Shader i's textures on units 0, 1, …, its program in use.
  void bind(size_t i, GLuint prog) const {
    for (size_t k = 0; i < textures_.size() && k < textures_[i].size(); ++k) {
      glActiveTexture(GLenum(GL_TEXTURE0 + k));
      glBindTexture(GL_TEXTURE_2D, textures_[i][k]);
      glUniform1i(glGetUniformLocation(prog, images_[i][k].name.c_str()), GLint(k));
    }
  }

 private:
  const std::vector<std::vector<ShaderTexture>>& images_;
  std::vector<std::vector<GLuint>> textures_;
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
