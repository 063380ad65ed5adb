// WGSL (WebGPU's shading language): a fragment shader or the functions alone. WGSL is
// not a C dialect: `fn f(a: f32) -> f32`, `let`, `vec3<f32>`, select(f, t, c) for ?:,
// && and || never mixed without parentheses, no preprocessor; the expressions' walk,
// precedence and numbers are the shared writer's (targets/writer.h).
#include <cmath>

#include <fmt/format.h>

#include "catalog/catalog.h"
#include "core/vec.h"
#include "targets/glsl_lights.h"
#include "targets/sweep_grid.h"
#include "targets/targets.h"
#include "targets/targets_internal.h"
#include "targets/templates.h"
#include "targets/texture_code.h"
#include "targets/writer.h"

namespace facet {

namespace {

using ir::Node;
using ir::NodePtr;
using ir::Op;
using ir::Type;

class WgslPrinter : public targets::ExprWriter {
 public:
  static const char* type(Type t) { return t == Type::Float ? "f32" : "vec3<f32>"; }

  void literal_to(std::string& out, double v) const {
    if (v == kPi) {
      out += "PI";
      return;
    }
    const size_t start = out.size();
    targets::number_to(out, v);
    // "2" → "2.0": an abstract float, never an integer.
    if (out.find_first_of(".eEn", start) == std::string::npos) out += ".0";
  }
  std::string literal(double v) const {
    std::string s;
    literal_to(s, v);
    return s;
  }
  std::string color_literal(const std::array<double, 3>& c) const {
    std::string s = "vec3<f32>(";
    literal_to(s, c[0]);
    if (c[0] != c[1] || c[1] != c[2]) {
      s += ", ";
      literal_to(s, c[1]);
      s += ", ";
      literal_to(s, c[2]);
    }
    return s + ")";
  }
  std::string expr(const NodePtr& n) const {
    std::string s;
    expr_to(s, n, 0);
    return s;
  }
  // `n` as a value of type `wanted`: a float where a colour is wanted becomes vec3<f32>(x)
  // (WGSL's min, max, pow, clamp and select take operands of one type).
  void as_to(std::string& out, const NodePtr& n, Type wanted) const {
    if (wanted == Type::Color && n->type == Type::Float) {
      out += "vec3<f32>(";
      expr_to(out, n, 0);
      out += ')';
      return;
    }
    expr_to(out, n, 0);
  }
  std::string function(const ir::FunctionPtr& f) const;

 protected:
  void leaf_to(std::string& out, const Node& n) const override {
    if (n.op != Op::Literal) out += n.name;
    else if (n.type == Type::Color) out += color_literal(n.value);
    else literal_to(out, n.value[0]);
  }
  // select(f, t, c) for ?:; && and || print their own parentheses, since WGSL refuses
  // `a && b || c` (and so the shared precedence, which would omit them).
  bool spells(const Node& n) const override { return n.op == Op::Select || n.op == Op::And || n.op == Op::Or; }
  void spell_to(std::string& out, const NodePtr& np) const override {
    const Node& n = *np;
    if (n.op == Op::Select) {
      out += "select(";
      as_to(out, n.args[2], n.type);
      out += ", ";
      as_to(out, n.args[1], n.type);
      out += ", ";
      expr_to(out, n.args[0], 0);
      out += ')';
      return;
    }
    for (size_t i = 0; i < 2; ++i) {
      if (i) out += n.op == Op::And ? " && " : " || ";
      const Op child = n.args[i]->op;
      const bool other = (child == Op::And || child == Op::Or) && (child != n.op || i == 1);
      if (other) out += '(';
      expr_to(out, n.args[i], targets::kAndPrecedence);
      if (other) out += ')';
    }
  }
  // A call's arguments take its parameters' types, a builtin's its own.
  void operand_to(std::string& out, const Node& parent, size_t i) const override {
    as_to(out, parent.args[i], parent.op == Op::Call ? parent.callee->params[i].type : parent.type);
  }
};

std::string WgslPrinter::function(const ir::FunctionPtr& f) const {
  std::string s = "fn " + f->name + "(";
  for (size_t i = 0; i < f->params.size(); ++i)
    s += fmt::format("{}{}: {}", i ? ", " : "", f->params[i].name, type(f->params[i].type));
  s += fmt::format(") -> {} {{", type(f->result_type()));
  targets::CodeWriter w(0, "    ");
  w.line(s);
  w.open("");
  w.comment(f->citation);
  if (!f->doc.empty()) w.comment(f->doc);
  for (const auto& l : f->lets) {
    s = fmt::format("let {}: {} = ", l.name, type(l.value.type()));
    expr_to(s, l.value.node(), 0);
    w.line(s + ';');
  }
  const NodePtr& r = f->result.node();
  if (r->op == Op::Select) {
    // A guard reads better as an early return.
    s = "if (";
    expr_to(s, r->args[0], 0);
    w.open(s + ") {");
    s = "return ";
    as_to(s, r->args[1], r->type);
    w.line(s + ';');
    w.close("}");
    s = "return ";
    as_to(s, r->args[2], r->type);
  } else {
    s = "return ";
    as_to(s, r, f->result_type());
  }
  w.line(s + ';');
  w.close("}");
  std::string out = w.take();
  // CodeWriter's open("") left an empty line after the signature.
  if (auto at = out.find("{\n\n"); at != std::string::npos) out.erase(at + 1, 1);
  return out;
}

// The uv′ of a texture call: KHR_texture_transform's affine map of set `uv`.
std::string wgsl_uv(const WgslPrinter& pr, const TextureCall& c) {
  std::string uv = fmt::format("uv{}", c.uv);
  if (!c.transformed) return uv;
  return fmt::format("vec2<f32>({} * {uv}.x + {} * {uv}.y + {}, {} * {uv}.x + {} * {uv}.y + {})", pr.literal(c.a),
                     pr.literal(c.b), pr.literal(c.ou), pr.literal(c.c), pr.literal(c.d), pr.literal(c.ov),
                     fmt::arg("uv", uv));
}

// One textured parameter's statement in facet_sample_textures() (texture_value_code()).
std::string sample_statement(const WgslPrinter& pr, const TextureCall& c) {
  const SampleWords words{{[&](double x) { return pr.literal(x); },
                           [&](const std::array<double, 3>& x) { return pr.color_literal(x); },
                           [&](double x) { return "vec3<f32>(" + pr.literal(x) + ")"; }},
                          "vec2<i32>",
                          "vec3<f32>"};
  return gpu_sample_statement(c, c.image ? wgsl_uv(pr, c) : "", words);
}

// The textures' bindings, their parameters' private globals and facet_sample_textures():
// empty for a material without textures. A value of the vertex colour alone has no binding.
std::string wgsl_textures(const MaterialProgram& p) {
  if (!p.has_textures()) return "";
  WgslPrinter pr;
  std::string uniforms, globals, samples;
  int binding = 1;  // binding 0 is the scene's uniform buffer
  for (const auto& c : image_calls(p))
    uniforms += fmt::format("@group(0) @binding({}) var facet_texture_{}: texture_2d<f32>;  // \"{}\", {}×{}\n",
                            binding++, c.name, c.file, c.texels->width, c.texels->height);
  std::vector<TextureCall> calls = texture_calls(p);
  for (const auto& n : normal_map_calls(p)) calls.push_back(n);
  for (const auto& c : calls) {
    globals += fmt::format("var<private> {}: {};\n", c.name, c.color ? "vec3<f32>" : "f32");
    samples += sample_statement(pr, c);
  }
  // catalog/texture.h, NormalMap: n_t from the sampled rgb, then the mapped normal.
  if (p.has_uv_frame())
    globals += "// The normal map's frame at the shading point: t the unit ∂p/∂u, w = ±1 (B = w·(n × t)).\n"
               "var<private> facet_uv_tangent: vec3<f32>;\nvar<private> facet_uv_handedness: f32 = 1.0;\n";
  const std::string mapping =
      normal_map_functions(p, "wgsl/normal_map.wgsl", [&](double x) { return pr.literal(x); });
  std::map<std::string, std::string> values = sampling_doc(p);
  values.insert({{"uniforms", uniforms}, {"globals", globals}, {"samples", samples},
                 {"params", p.uses_vertex_color() ? "uv0: vec2<f32>, uv1: vec2<f32>, color0: vec4<f32>"
                                                  : "uv0: vec2<f32>, uv1: vec2<f32>"}});
  return render_template("wgsl/textures.wgsl", values) + mapping;
}

// The material's constants: m_a and m_e (unless images set them), the tangent axis, the parameters.
std::string wgsl_constants(const MaterialProgram& p, const WgslPrinter& pr) {
  const Material& m = p.material;
  std::string constants;
  auto add = [&](const char* type, const std::string& name, const std::string& value) {
    constants += fmt::format("const {}: {} = {};\n", name, type, value);
  };
  if (!m.ambient_texture) add("vec3<f32>", kAmbientInput, pr.color_literal(m.ambient));
  if (!m.emission_texture) add("vec3<f32>", kEmissionInput, pr.color_literal(m.emission));
  add("vec3<f32>", "tangent_axis", pr.color_literal(normalize(Vec3(m.tangent_axis)).array()));
  for (const auto& c : p.constants())
    add(WgslPrinter::type(c->type), c->name,
        c->type == Type::Color ? pr.color_literal(c->value) : pr.literal(c->value[0]));
  return constants;
}

// facet_reflect's inputs from n, l, v, t, and reflectance()'s arguments.
std::pair<std::string, std::string> reflect_inputs(const MaterialProgram& p, const WgslPrinter& pr) {
  std::string inputs, arguments;
  inputs += bitangent(p, "let");
  if (p.uses_half_vector())
    inputs += fmt::format("    // catalog.h, Input: h = (l + v) / max(|l + v|, ε)\n"
                          "    let h = (l + v) * inverseSqrt(max(dot(l + v, l + v), {}));\n",
                          pr.literal(kEpsilon * kEpsilon));
  for (const auto& in : p.inputs) {
    arguments += (arguments.empty() ? "" : ", ") + in;
    if (p.is_textured(in)) continue;  // a private global facet_sample_textures() set
    // NoL → dot(n, l): the two letters either side of "o" name the vectors.
    std::string a(1, char(std::tolower(in[0]))), b(1, char(std::tolower(in[2])));
    inputs += fmt::format("    let {} = dot({}, {});\n", in, a, b);
  }
  return {inputs, arguments};
}

std::string header(const Material& m, const char* what, const std::string& source) {
  return render_template("wgsl/header.wgsl", {{"name", m.name},
                                              {"what", what},
                                              {"version", FACET_VERSION},
                                              {"source", source},
                                              {"description", describe_material(m, "//")}});
}

// The light loop's lights (templates/wgsl/lights.wgsl's {{declarations}}): the engine-facing
// uniform buffer with an array of FACET_MAX_LIGHTS, laid out as glsl450's std140 FacetScene
// block, or for facet's own renderers the uniform buffer without the array and a storage
// buffer of any length at @group(glsl_light::kLightSet) @binding(0).
std::string wgsl_light_declarations(LightSource source) {
  const std::string accessor = "\n"
                               "// Light i (i below the light count): the light loop reads every light through this.\n"
                               "fn facet_light(i: i32) -> FacetLight {{\n"
                               "    return {};\n"
                               "}}";
  if (source == LightSource::Buffer)
    return fmt::format("// The head of glsl450's FacetScene block: camera at 0, ambient at 16, the light count at 32.\n"
                       "struct FacetScene {{\n"
                       "    camera_position: vec4<f32>,  // xyz: the eye, world space\n"
                       "    ambient: vec4<f32>,          // rgb: the scene's ambient colour A\n"
                       "    light_count: i32,\n"
                       "}};\n"
                       "@group(0) @binding(0) var<uniform> facet_scene: FacetScene;\n"
                       "// The lights, any number: 64 bytes each, as glsl450's storage buffer.\n"
                       "@group({}) @binding(0) var<storage, read> facet_lights: array<FacetLight>;\n{}",
                       glsl_light::kLightSet, fmt::format(accessor, "facet_lights[i]"));
  return "// One uniform buffer at @group(0) @binding(0), laid out as GLSL's std140 FacetScene block of\n"
         "// --target glsl450 (560 bytes: camera at 0, ambient at 16, light count at 32, the lights from\n"
         "// 48, 64 bytes each).\n"
         "const FACET_MAX_LIGHTS: i32 = 8;\n"
         "struct FacetScene {\n"
         "    camera_position: vec4<f32>,  // xyz: the eye, world space\n"
         "    ambient: vec4<f32>,          // rgb: the scene's ambient colour A\n"
         "    light_count: i32,            // how many of `lights` shine, at most FACET_MAX_LIGHTS\n"
         "    lights: array<FacetLight, 8>,\n"
         "};\n"
         "@group(0) @binding(0) var<uniform> facet_scene: FacetScene;\n" +
         fmt::format(accessor, "facet_scene.lights[i]");
}

}  // namespace

WgslParts wgsl_parts(const MaterialProgram& p, const std::string& source, LightSource light_source) {
  WgslPrinter pr;
  WgslParts parts;
  std::string functions;
  for (const auto& f : p.functions()) functions += pr.function(f) + "\n";
  auto [inputs, arguments] = reflect_inputs(p, pr);
  parts.header = header(p.material, "WGSL fragment shader (WebGPU)", source);
  std::map<std::string, std::string> library = {{"constants", wgsl_constants(p, pr)},
                                                 {"textures", wgsl_textures(p)},
                                                 {"functions", functions},
                                                 {"inputs", inputs},
                                                 {"arguments", arguments}};
  coat_normal_values(p, "c: vec3<f32>", library);
  parts.library = render_template("wgsl/library.wgsl", library);
  std::map<std::string, std::string> lights = glsl_light::template_values();  // the light encoding's numbers
  emitted_values(p, lights);
  normal_mapping_values(p, "let", lights);
  lights["declarations"] = wgsl_light_declarations(light_source);
  // An engine's uniform buffer holds FACET_MAX_LIGHTS: a larger count reads no further.
  lights["count"] = light_source == LightSource::Buffer ? "facet_scene.light_count"
                                                        : "min(facet_scene.light_count, FACET_MAX_LIGHTS)";
  parts.lights = render_template("wgsl/lights.wgsl", lights);
  std::string in = "    @location(0) position: vec3<f32>,  // world space\n"
                   "    @location(1) normal: vec3<f32>,    // world space\n";
  std::string sample;
  if (p.has_textures()) {
    in += "    @location(3) texcoord0: vec2<f32>,  // glTF's TEXCOORD_0: v down the picture\n"
          "    @location(4) texcoord1: vec2<f32>,\n";
    sample = "    facet_sample_textures(fragment.texcoord0, fragment.texcoord1);\n";
  }
  if (p.uses_vertex_color()) {
    in += "    @location(6) color0: vec4<f32>,  // glTF's COLOR_0: linear RGBA; white (1) where a mesh has none\n";
    sample = "    facet_sample_textures(fragment.texcoord0, fragment.texcoord1, fragment.color0);\n";
  }
  if (p.has_uv_frame()) {
    in += "    @location(5) texture_tangent: vec4<f32>,  // xyz: ∂p/∂u, w: ±1 (glTF's TANGENT)\n";
    sample += "    facet_uv_tangent = fragment.texture_tangent.xyz;\n"
              "    facet_uv_handedness = fragment.texture_tangent.w;\n";
  }
  parts.main = render_template("wgsl/main.wgsl", {{"inputs", in}, {"sample", sample}});
  return parts;
}

std::string wgsl_gbuffer_shading_source(const Material& m) {
  MaterialProgram p = compile(m);
  WgslParts parts = wgsl_parts(p, m.source, LightSource::Buffer);
  std::string sample;
  if (p.has_textures())
    sample = p.uses_vertex_color() ? "    facet_sample_textures(uv.xy, uv.zw, textureLoad(facet_gbuffer_color0, texel, 0));\n"
                                   : "    facet_sample_textures(uv.xy, uv.zw);\n";
  if (p.has_uv_frame()) sample += "    facet_uv_tangent = frame.xyz;\n    facet_uv_handedness = frame.w;\n";
  std::map<std::string, std::string> values = glsl_light::visibility_values();
  values["sample"] = sample;
  return parts.header + "\n" + parts.library + "\n" + parts.lights + render_template("wgsl/gbuffer_shade.wgsl", values);
}

std::string wgsl_sweep_source(const Material& m) {
  const MaterialProgram p = compile(m);
  WgslParts parts = wgsl_parts(p, m.source);
  WgslPrinter pr;
  std::string grid;
  for (const auto& f : ir::dependencies(sweep_grid())) grid += pr.function(f) + "\n";
  return parts.header + "\n" + parts.library + "\n" + grid +
         render_template("wgsl/sweep.wgsl", {{"coat_arg", coat_normal_arg(p, "n")}});
}

std::string generate_wgsl(const Material& m, const GenerateOptions& o) {
  WgslParts parts = wgsl_parts(compile(m), o.source);
  if (o.library)
    return header(m, "WGSL library (copy it into a module beside its entry point)", o.source) + "\n" + parts.library;
  return parts.header + "\n" + parts.library + "\n" + parts.lights + parts.main;
}

}  // namespace facet
