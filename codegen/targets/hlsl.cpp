// HLSL: a Shader Model 5 pixel shader, or the functions alone. The third C dialect of
// targets/cfamily.h: float3, atan2, lerp, rsqrt, `static const` globals, and no float3(x)
// splat (fxc and dxc refuse it; glslang's HLSL front end would not say so).
#include <cmath>
#include <map>

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

targets::CDialect hlsl_dialect() {
  targets::CDialect d;
  d.color_type = "float3";
  d.color_ctor = "float3";
  d.atan2_name = "atan2";
  d.splat_ctor = false;
  return d;
}

std::string grey(const targets::CPrinter& pr, double x) { return pr.color_literal({x, x, x}); }

// The uv′ of a texture call: KHR_texture_transform's affine map of set `uv`.
std::string hlsl_uv(const targets::CPrinter& pr, const TextureCall& c) {
  std::string uv = fmt::format("uv{}", c.uv);
  if (!c.transformed) return uv;
  return fmt::format("float2({} * {uv}.x + {} * {uv}.y + {}, {} * {uv}.x + {} * {uv}.y + {})", pr.literal(c.a),
                     pr.literal(c.b), pr.literal(c.ou), pr.literal(c.c), pr.literal(c.d), pr.literal(c.ov),
                     fmt::arg("uv", uv));
}

// One textured parameter's statement in facet_sample_textures(): the one sampling rule
// (docs/textures.md), as the GLSL's.
std::string hlsl_sample(const targets::CPrinter& pr, const TextureCall& c) {
  const SampleWords words{{[&](double x) { return pr.literal(x); },
                           [&](const std::array<double, 3>& x) { return pr.color_literal(x); },
                           [&](double x) { return std::isfinite(x) ? grey(pr, x) : pr.literal(x); }},
                          "int2",
                          "(float3)"};
  return gpu_sample_statement(c, c.image ? hlsl_uv(pr, c) : "", words);
}

// The textures (Texture2D at t1, t2, …: Vulkan bindings 1, 2, … of set 0, as the glsl450
// shader's samplers), their parameters' globals and facet_sample_textures(): empty for a
// material without textures. A value of the vertex colour alone has no texture.
std::string hlsl_textures(const MaterialProgram& p) {
  if (!p.has_textures()) return "";
  targets::CPrinter pr(hlsl_dialect());
  std::string uniforms, globals, samples;
  int binding = 1;  // binding 0 is the scene's cbuffer
  for (const auto& c : image_calls(p))
    uniforms += fmt::format("Texture2D<float4> facet_texture_{} : register(t{});  // \"{}\", {}×{}\n", c.name,
                            binding++, c.file, c.texels->width, c.texels->height);
  std::vector<TextureCall> calls = texture_calls(p);
  for (const auto& n : normal_map_calls(p)) calls.push_back(n);
  for (const auto& c : calls) {
    globals += fmt::format("static {} {};\n", c.color ? "float3" : "float", c.name);
    samples += hlsl_sample(pr, c);
  }
  // catalog/texture.h, NormalMap: n_t from the sampled rgb, then the mapped normal.
  if (p.has_uv_frame())
    globals += "// The normal map's frame at the shading point: t the unit ∂p/∂u, w = ±1 (B = w·(n × t)).\n"
               "static float3 facet_uv_tangent;\nstatic float facet_uv_handedness = 1.0;\n";
  const std::string mapping =
      normal_map_functions(p, "hlsl/normal_map.hlsl", [&](double x) { return pr.literal(x); });
  std::map<std::string, std::string> values = sampling_doc(p);
  values.insert({{"uniforms", uniforms}, {"globals", globals}, {"samples", samples},
                 {"params", p.uses_vertex_color() ? "float2 uv0, float2 uv1, float4 color0" : "float2 uv0, float2 uv1"}});
  return render_template("hlsl/textures.hlsl", values) + mapping;
}

// facet_reflect's body before its return: the inputs the lobes read, and their names.
std::pair<std::string, std::string> hlsl_inputs(const MaterialProgram& p, const targets::CPrinter& printer) {
  std::string inputs, arguments;
  inputs += bitangent(p, "float3");
  if (p.uses_half_vector())
    inputs += fmt::format("    // catalog.h, Input: h = (l + v) / max(|l + v|, ε)\n"
                          "    float3 h = (l + v) * rsqrt(max(dot(l + v, l + v), {}));\n",
                          printer.literal(kEpsilon * kEpsilon));
  for (const auto& in : p.inputs) {
    arguments += (arguments.empty() ? "" : ", ") + in;
    if (p.is_textured(in)) continue;  // a global facet_sample_textures() set
    // NoL → dot(n, l): the two letters either side of "o" name the vectors.
    std::string a(1, char(std::tolower(in[0]))), b(1, char(std::tolower(in[2])));
    inputs += fmt::format("    float {} = dot({}, {});\n", in, a, b);
  }
  return {inputs, arguments};
}

std::string hlsl_header(const Material& m, const std::string& what, const std::string& source) {
  return render_template("hlsl/header.hlsl", {{"name", m.name},
                                              {"what", what},
                                              {"version", FACET_VERSION},
                                              {"source", source},
                                              {"description", describe_material(m, "//")}});
}

// The standalone main's inputs after the normal (and the optional vertex tangent), and
// what it does before shading.
std::pair<std::string, std::string> hlsl_main_inputs(const MaterialProgram& p) {
  std::string in, sample;
  if (p.has_textures()) {
    in += "            , FACET_LOCATION(3) float2 facet_texcoord0 : TEXCOORD3  // glTF's TEXCOORD_0: v down the picture\n"
          "            , FACET_LOCATION(4) float2 facet_texcoord1 : TEXCOORD4\n";
    sample = "    facet_sample_textures(facet_texcoord0, facet_texcoord1);\n";
  }
  if (p.uses_vertex_color()) {
    in += "            , FACET_LOCATION(6) float4 facet_color0 : COLOR0  // glTF's COLOR_0: linear RGBA; white (1) where a mesh has none\n";
    sample = "    facet_sample_textures(facet_texcoord0, facet_texcoord1, facet_color0);\n";
  }
  if (p.has_uv_frame()) {
    in += "            , FACET_LOCATION(5) float4 facet_texture_tangent : TEXCOORD5  // xyz: ∂p/∂u, w: ±1 (glTF's TANGENT)\n";
    sample += "    facet_uv_tangent = facet_texture_tangent.xyz;\n"
              "    facet_uv_handedness = facet_texture_tangent.w;\n";
  }
  return {in, sample};
}

// The light loop's lights (templates/hlsl/lights.hlsl's {{declarations}}): the engine-facing
// cbuffer with an array of FACET_MAX_LIGHTS, laid out as glsl450's FacetScene block, or for
// facet's own renderers the cbuffer without the array and a StructuredBuffer of any length
// (Vulkan: set glsl_light::kLightSet, binding 0, as glsl450's storage buffer).
std::string hlsl_light_declarations(LightSource source) {
  const std::string accessor = "\n"
                               "// Light i (i below facet_light_count): the light loop reads every light through this.\n"
                               "FacetLight facet_light(int i)\n"
                               "{\n"
                               "    return facet_lights[i];\n"
                               "}";
  if (source == LightSource::Buffer)
    return fmt::format("// The head of glsl450's FacetScene block, byte for byte; Vulkan binding 0 of set 0.\n"
                       "cbuffer FacetScene : register(b0)\n"
                       "{{\n"
                       "    float4 facet_camera_position;  // xyz: the eye, world space\n"
                       "    float4 facet_ambient;          // rgb: the scene's ambient colour A\n"
                       "    int facet_light_count;\n"
                       "}};\n"
                       "// The lights, any number: 64 bytes each, as glsl450's storage buffer.\n"
                       "StructuredBuffer<FacetLight> facet_lights : register(t0, space{});\n{}",
                       glsl_light::kLightSet, accessor);
  return "#define FACET_MAX_LIGHTS 8\n"
         "// The glsl450 shader's FacetScene block, byte for byte (std140 and HLSL's packing agree\n"
         "// here: the light array starts at byte 48, 64 bytes a light); Vulkan binding 0 of set 0.\n"
         "cbuffer FacetScene : register(b0)\n"
         "{\n"
         "    float4 facet_camera_position;  // xyz: the eye, world space\n"
         "    float4 facet_ambient;          // rgb: the scene's ambient colour A\n"
         "    int facet_light_count;         // how many of facet_lights shine, at most FACET_MAX_LIGHTS\n"
         "    FacetLight facet_lights[FACET_MAX_LIGHTS];\n"
         "};\n" +
         accessor;
}

}  // namespace

HlslParts hlsl_parts(const MaterialProgram& p, const std::string& source, LightSource light_source) {
  targets::CPrinter printer(hlsl_dialect());
  HlslParts parts;
  std::string functions;
  for (const auto& f : p.functions()) functions += printer.function(f) + "\n";
  auto [inputs, arguments] = hlsl_inputs(p, printer);
  parts.header = hlsl_header(p.material, "HLSL pixel shader (Shader Model 5)", source);
  // `static const`: a plain HLSL global is a uniform.
  const std::string constants = targets::material_constants(p, printer, "static const");
  std::map<std::string, std::string> library = {{"constants", constants},
                                                 {"textures", hlsl_textures(p)},
                                                 {"functions", functions},
                                                 {"inputs", inputs},
                                                 {"arguments", arguments}};
  coat_normal_values(p, "float3 c", library);
  parts.library = render_template("hlsl/library.hlsl", library);
  std::map<std::string, std::string> lights = glsl_light::template_values();  // the light encoding's numbers
  emitted_values(p, lights);
  normal_mapping_values(p, "float3", lights);
  lights["declarations"] = hlsl_light_declarations(light_source);
  // An engine's cbuffer holds FACET_MAX_LIGHTS: a larger count reads no further.
  lights["count"] = light_source == LightSource::Buffer ? "facet_light_count" : "min(facet_light_count, FACET_MAX_LIGHTS)";
  parts.lights = render_template("hlsl/lights.hlsl", lights);
  auto [main_in, sample] = hlsl_main_inputs(p);
  parts.main = render_template("hlsl/main.hlsl", {{"inputs", main_in}, {"sample", sample}});
  return parts;
}

std::string hlsl_sweep_source(const Material& m) {
  const MaterialProgram p = compile(m);
  HlslParts parts = hlsl_parts(p, m.source);
  targets::CPrinter printer(hlsl_dialect());
  std::string grid;
  for (const auto& f : ir::dependencies(sweep_grid())) grid += printer.function(f) + "\n";
  return parts.header + parts.library + "\n" + grid +
         render_template("hlsl/sweep.hlsl", {{"coat_arg", coat_normal_arg(p, "n")}});
}

std::string generate_hlsl(const Material& m, const GenerateOptions& o) {
  MaterialProgram p = compile(m);
  HlslParts parts = hlsl_parts(p, o.source);
  if (o.library) return hlsl_header(m, "HLSL library (include it in a shader)", o.source) + "\n" + parts.library;
  return parts.header + "\n" + parts.library + "\n" + parts.lights + parts.main;
}

}  // namespace facet
