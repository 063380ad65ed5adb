// GLSL: a fragment shader in three dialects, or the functions alone.
#include <cmath>

#include <fmt/format.h>

#include "targets/cfamily.h"
#include "targets/glsl_lights.h"
#include "targets/sweep_grid.h"
#include "targets/targets.h"
#include "targets/targets_internal.h"
#include "targets/templates.h"
#include "targets/texture_code.h"

namespace facet {

namespace {

const char* dialect_what(Target t, bool library) {
  if (library) return "GLSL library (include it in a fragment shader)";
  switch (t) {
    case Target::Glsl: return "GLSL 3.30 core fragment shader";
    case Target::Glsl450: return "GLSL 4.50 fragment shader for Vulkan (SPIR-V)";
    case Target::Essl: return "OpenGL ES 3.00 fragment shader";
    default: return "?";
  }
}

std::string version_line(Target t) {
  switch (t) {
    case Target::Glsl: return "#version 330 core\n";
    case Target::Glsl450: return "#version 450\n";
    case Target::Essl: return "#version 300 es\nprecision highp float;\nprecision highp int;\n";
    default: return "";
  }
}

// The light loop's accessor, where the lights are an array facet_lights.
const char* kLightAccessor =
    "\n"
    "// Light i (i below facet_light_count): the light loop reads every light through this.\n"
    "FacetLight facet_light(int i)\n"
    "{\n"
    "    return facet_lights[i];\n"
    "}";

// The engine-facing lights (LightSource::Uniforms): a uniform array of FACET_MAX_LIGHTS, in
// Vulkan the FacetScene block's.
std::string light_uniforms(Target t) {
  if (t == Target::Glsl450) {
    return std::string("#define FACET_MAX_LIGHTS 8\n"
                       "layout(std140, set = 0, binding = 0) uniform FacetScene {\n"
                       "    vec4 facet_camera_position;  // xyz: the eye, world space\n"
                       "    vec4 facet_ambient;          // rgb: the scene's ambient colour A\n"
                       "    int facet_light_count;       // how many of facet_lights shine, at most FACET_MAX_LIGHTS\n"
                       "    FacetLight facet_lights[FACET_MAX_LIGHTS];\n"
                       "};\n") +
           kLightAccessor;
  }
  return std::string("#define FACET_MAX_LIGHTS 8\n"
                     "uniform vec3 facet_camera_position;  // the eye, world space\n"
                     "uniform vec3 facet_ambient;          // the scene's ambient colour A\n"
                     "uniform int facet_light_count;       // how many of facet_lights shine, at most FACET_MAX_LIGHTS\n"
                     "uniform FacetLight facet_lights[FACET_MAX_LIGHTS];\n") +
         kLightAccessor;
}

// facet's own renderers' lights (LightSource::Buffer): any number, from a buffer or texture
// (targets/glsl_lights.h says where).
std::string light_buffer(Target t) {
  if (t == Target::Glsl450)
    return fmt::format(
        "layout(std140, set = 0, binding = 0) uniform FacetScene {{\n"
        "    vec4 facet_camera_position;  // xyz: the eye, world space\n"
        "    vec4 facet_ambient;          // rgb: the scene's ambient colour A\n"
        "    int facet_light_count;\n"
        "}};\n"
        "// The lights, any number: a storage buffer of FacetLight, 64 bytes each.\n"
        "layout(std430, set = {}, binding = 0) readonly buffer FacetLights {{\n"
        "    FacetLight facet_lights[];\n"
        "}};\n{}",
        glsl_light::kLightSet, kLightAccessor);
  const std::string head = "uniform vec3 facet_camera_position;  // the eye, world space\n"
                           "uniform vec3 facet_ambient;          // the scene's ambient colour A\n"
                           "uniform int facet_light_count;\n";
  if (t == Target::Essl)
    return head + fmt::format(
        "// The lights, any number: an RGBA32F texture of {0} lights a row, light i's four vec4 (position,\n"
        "// color, spot, attenuation) at texels (4·(i mod {0}) + k, i / {0}), k = 0 … 3.\n"
        "uniform highp sampler2D facet_light_texture;\n"
        "\n"
        "// Light i (i below facet_light_count): the light loop reads every light through this.\n"
        "FacetLight facet_light(int i)\n"
        "{{\n"
        "    ivec2 at = ivec2(4 * (i % {0}), i / {0});\n"
        "    return FacetLight(texelFetch(facet_light_texture, at, 0), texelFetch(facet_light_texture, at + ivec2(1, 0), 0),\n"
        "                      texelFetch(facet_light_texture, at + ivec2(2, 0), 0),\n"
        "                      texelFetch(facet_light_texture, at + ivec2(3, 0), 0));\n"
        "}}",
        glsl_light::kLightsPerRow);
  return head +
         "// The lights, any number: light i's four vec4 (position, color, spot, attenuation) at texels\n"
         "// 4i … 4i + 3 of an RGBA32F buffer texture; a draw may take lights facet_light_first on (0\n"
         "// unless set: facet's GL ray caster draws many lights in turns).\n"
         "uniform samplerBuffer facet_light_buffer;\n"
         "uniform int facet_light_first;\n"
         "\n"
         "// Light i (i below facet_light_count): the light loop reads every light through this.\n"
         "FacetLight facet_light(int i)\n"
         "{\n"
         "    int at = 4 * (facet_light_first + i);\n"
         "    return FacetLight(texelFetch(facet_light_buffer, at), texelFetch(facet_light_buffer, at + 1),\n"
         "                      texelFetch(facet_light_buffer, at + 2), texelFetch(facet_light_buffer, at + 3));\n"
         "}";
}

std::string main_inputs(Target t) {
  if (t == Target::Glsl450) {
    return "layout(location = 0) in vec3 facet_position;  // world space\n"
           "layout(location = 1) in vec3 facet_normal;    // world space\n"
           "#ifdef FACET_VERTEX_TANGENT\n"
           "layout(location = 2) in vec3 facet_vertex_tangent;\n"
           "#endif\n"
           "layout(location = 0) out vec4 facet_color;\n";
  }
  return "in vec3 facet_position;  // world space\n"
         "in vec3 facet_normal;    // world space\n"
         "#ifdef FACET_VERTEX_TANGENT\n"
         "in vec3 facet_vertex_tangent;\n"
         "#endif\n"
         "out vec4 facet_color;\n";
}

// The uv′ of a texture call: KHR_texture_transform's affine map of set `uv`.
std::string glsl_uv(const targets::CPrinter& pr, const TextureCall& c) {
  std::string uv = fmt::format("uv{}", c.uv);
  if (!c.transformed) return uv;
  return fmt::format("vec2({} * {uv}.x + {} * {uv}.y + {}, {} * {uv}.x + {} * {uv}.y + {})", pr.literal(c.a),
                     pr.literal(c.b), pr.literal(c.ou), pr.literal(c.c), pr.literal(c.d), pr.literal(c.ov),
                     fmt::arg("uv", uv));
}

// One textured parameter's statement in facet_sample_textures() (texture_value_code()).
std::string glsl_sample(const targets::CPrinter& pr, const TextureCall& c) {
  const SampleWords words{{[&](double x) { return pr.literal(x); },
                           [&](const std::array<double, 3>& x) { return pr.color_literal(x); },
                           [&](double x) { return "vec3(" + pr.literal(x) + ")"; }},
                          "ivec2",
                          "vec3"};
  return gpu_sample_statement(c, c.image ? glsl_uv(pr, c) : "", words);
}

// The textures' uniforms, their parameters' globals and facet_sample_textures(): empty
// for a material without textures. A value of the vertex colour alone has no uniform.
std::string glsl_textures(const MaterialProgram& p, Target dialect) {
  if (!p.has_textures()) return "";
  targets::CPrinter pr({});
  std::string uniforms, globals, samples;
  int binding = 1;  // Vulkan: binding 0 is the scene's uniform block
  for (const auto& c : image_calls(p)) {
    std::string layout = dialect == Target::Glsl450 ? fmt::format("layout(set = 0, binding = {}) ", binding++) : "";
    uniforms += fmt::format("{}uniform sampler2D facet_texture_{};  // \"{}\", {}×{}\n", layout, c.name, c.file,
                            c.texels->width, c.texels->height);
  }
  std::vector<TextureCall> calls = texture_calls(p);
  for (const auto& n : normal_map_calls(p)) calls.push_back(n);
  for (const auto& c : calls) {
    globals += fmt::format("{} {};\n", c.color ? "vec3" : "float", c.name);
    samples += glsl_sample(pr, c);
  }
  // catalog/texture.h, NormalMap: n_t from the sampled rgb, then the mapped normal.
  if (p.has_uv_frame())
    globals += "// The normal map's frame at the shading point: t the unit ∂p/∂u, w = ±1 (B = w·(n × t)).\n"
               "vec3 facet_uv_tangent;\nfloat facet_uv_handedness = 1.0;\n";
  const std::string mapping =
      normal_map_functions(p, "glsl/normal_map.glsl", [&](double x) { return pr.literal(x); });
  std::map<std::string, std::string> values = sampling_doc(p);
  values.insert({{"uniforms", uniforms}, {"globals", globals}, {"samples", samples},
                 {"params", p.uses_vertex_color() ? "vec2 uv0, vec2 uv1, vec4 color0" : "vec2 uv0, vec2 uv1"}});
  return render_template("glsl/textures.glsl", values) + mapping;
}

}  // namespace

GlslParts glsl_parts(const MaterialProgram& p, Target dialect, const std::string& source, LightSource light_source) {
  targets::CPrinter printer({});
  GlslParts parts;
  const Material& m = p.material;

  const std::string constants = targets::material_constants(p, printer, "const");

  std::string functions;
  for (const auto& f : p.functions()) functions += printer.function(f) + "\n";

  std::string inputs, arguments;
  inputs += bitangent(p, "vec3");
  if (p.uses_half_vector())
    inputs += fmt::format("    // catalog.h, Input: h = (l + v) / max(|l + v|, ε)\n"
                          "    vec3 h = (l + v) * inversesqrt(max(dot(l + v, l + v), {}));\n",
                          printer.literal(kEpsilon * kEpsilon));
  for (const auto& in : p.inputs) {
    arguments += (arguments.empty() ? "" : ", ") + in;
    if (p.is_textured(in)) continue;  // a global facet_sample_textures() set
    // NoL → dot(n, l): the two letters either side of "o" name the vectors.
    std::string a(1, char(std::tolower(in[0]))), b(1, char(std::tolower(in[2])));
    inputs += fmt::format("    float {} = dot({}, {});\n", in, a, b);
  }

  parts.header = render_template("glsl/header.glsl", {{"name", m.name},
                                                       {"what", dialect_what(dialect, false)},
                                                       {"version", FACET_VERSION},
                                                       {"source", source},
                                                       {"description", describe_material(m, "//")}});
  std::map<std::string, std::string> library = {{"constants", constants},
                                                 {"textures", glsl_textures(p, dialect)},
                                                 {"functions", functions},
                                                 {"inputs", inputs},
                                                 {"arguments", arguments}};
  coat_normal_values(p, "vec3 c", library);
  parts.library = render_template("glsl/library.glsl", library);
  std::map<std::string, std::string> lights = glsl_light::template_values();  // the light encoding's numbers
  emitted_values(p, lights);
  const bool buffer = light_source == LightSource::Buffer;
  lights["declarations"] = buffer ? light_buffer(dialect) : light_uniforms(dialect);
  // An engine's uniform array holds FACET_MAX_LIGHTS: a larger count reads no further.
  lights["count"] = buffer ? "facet_light_count" : "min(facet_light_count, FACET_MAX_LIGHTS)";
  normal_mapping_values(p, "vec3", lights);
  parts.lights = render_template("glsl/lights.glsl", lights);
  std::string main_in = main_inputs(dialect), sample;
  if (p.has_textures()) {
    main_in += dialect == Target::Glsl450 ? "layout(location = 3) in vec2 facet_texcoord0;\n"
                                            "layout(location = 4) in vec2 facet_texcoord1;\n"
                                          : "in vec2 facet_texcoord0;  // glTF's TEXCOORD_0: v down the picture\n"
                                            "in vec2 facet_texcoord1;\n";
    sample = "    facet_sample_textures(facet_texcoord0, facet_texcoord1);\n";
  }
  if (p.uses_vertex_color()) {
    main_in += dialect == Target::Glsl450 ? "layout(location = 6) in vec4 facet_color0;\n"
                                          : "in vec4 facet_color0;  // glTF's COLOR_0: linear RGBA; give white (1) where a mesh has none\n";
    sample = "    facet_sample_textures(facet_texcoord0, facet_texcoord1, facet_color0);\n";
  }
  if (p.has_uv_frame()) {
    main_in += dialect == Target::Glsl450 ? "layout(location = 5) in vec4 facet_texture_tangent;\n"
                                          : "in vec4 facet_texture_tangent;  // xyz: ∂p/∂u, w: ±1 (glTF's TANGENT)\n";
    sample += "    facet_uv_tangent = facet_texture_tangent.xyz;\n"
              "    facet_uv_handedness = facet_texture_tangent.w;\n";
  }
  parts.main = render_template("glsl/main.glsl", {{"inputs", main_in}, {"sample", sample}});
  return parts;
}

namespace {

// The G-buffer shading pass's samplers and output: set 1 in Vulkan (set 0 holds the
// scene's block and the material's images, set 2 the lights), highp in ES (a sampler's
// default is lowp).
std::string gbuffer_declarations(Target dialect) {
  const char* names[] = {"position", "normal", "view", "uv_tangent", "uv", "color0", "visibility"};
  std::string out;
  for (int i = 0; i < 7; ++i) {
    std::string layout = dialect == Target::Glsl450 ? fmt::format("layout(set = 1, binding = {}) ", i) : "";
    out += fmt::format("{}uniform highp {} facet_gbuffer_{};  // image {}\n", layout, i < 6 ? "sampler2D" : "sampler2DArray",
                       names[i], i);
  }
  return out + (dialect == Target::Glsl450 ? "layout(location = 0) out vec4 facet_color;\n" : "out vec4 facet_color;\n");
}

}  // namespace

std::string glsl_gbuffer_shading_source(const Material& m, Target dialect) {
  MaterialProgram p = compile(m);
  GlslParts parts = glsl_parts(p, dialect, m.source, LightSource::Buffer);
  std::string sample;
  if (p.has_textures())
    sample = p.uses_vertex_color() ? "    facet_sample_textures(uvs.xy, uvs.zw, texelFetch(facet_gbuffer_color0, facet_gbuffer_texel, 0));\n"
                                   : "    facet_sample_textures(uvs.xy, uvs.zw);\n";
  if (p.has_uv_frame()) sample += "    facet_uv_tangent = frame.xyz;\n    facet_uv_handedness = frame.w;\n";
  // Vulkan's gl_FragCoord has y down: the G-buffer's row is counted from the bottom.
  std::string texel = dialect == Target::Glsl450
                          ? "ivec2(int(gl_FragCoord.x), textureSize(facet_gbuffer_position, 0).y - 1 - int(gl_FragCoord.y))"
                          : "ivec2(gl_FragCoord.xy)";
  std::map<std::string, std::string> values = glsl_light::visibility_values();
  values.insert({{"declarations", gbuffer_declarations(dialect)}, {"texel", texel}, {"sample", sample}});
  return version_line(dialect) + "\n" + parts.header + "\n" + parts.library + "\n" + parts.lights +
         render_template("glsl/gbuffer_shade.glsl", values);
}

std::string glsl_sweep_source(const Material& m, Target dialect) {
  const MaterialProgram p = compile(m);
  GlslParts parts = glsl_parts(p, dialect, m.source);
  targets::CPrinter printer({});
  std::string grid;
  for (const auto& f : ir::dependencies(sweep_grid())) grid += printer.function(f) + "\n";
  const std::string declarations =
      dialect == Target::Glsl450 ? "layout(push_constant) uniform FacetSweep { ivec2 facet_grid; };\n"
                                   "#define facet_resolution vec2(facet_grid)\n"
                                   "layout(location = 0) out vec4 facet_color;\n"
                                 : "uniform vec2 facet_resolution;\nout vec4 facet_color;\n";
  return version_line(dialect) + parts.header + parts.library + "\n" + grid +
         render_template("glsl/sweep.glsl", {{"declarations", declarations}, {"coat_arg", coat_normal_arg(p, "n")}});
}

std::string generate_glsl(const Material& m, const GenerateOptions& o) {
  MaterialProgram p = compile(m);
  GlslParts parts = glsl_parts(p, o.target, o.source);
  if (o.library) {
    std::string header = render_template("glsl/header.glsl", {{"name", m.name},
                                                              {"what", dialect_what(o.target, true)},
                                                              {"version", FACET_VERSION},
                                                              {"source", o.source},
                                                              {"description", describe_material(m, "//")}});
    return header + "\n" + parts.library;
  }
  return version_line(o.target) + "\n" + parts.header + "\n" + parts.library + "\n" + parts.lights + parts.main;
}

}  // namespace facet
