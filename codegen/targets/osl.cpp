// OSL: a shader Cycles compiles in a Script node, or the functions alone.
#include <cmath>

#include <fmt/format.h>

#include "targets/cfamily.h"
#include "targets/sweep_grid.h"
#include "targets/targets.h"
#include "targets/targets_internal.h"
#include "targets/templates.h"

namespace facet {

namespace {

targets::CDialect osl_dialect() {
  targets::CDialect d;
  d.color_type = "color";
  d.color_ctor = "color";
  d.atan2_name = "atan2";
  d.pi_name = "M_PI";
  d.constants_as_params = true;
  return d;
}

// facet's world is y-up; Blender's is z-up: (x, y, z) → (x, −z, y).
Vec3 to_blender(const Vec3& p) { return {p.x, -p.z, p.y}; }

std::string triple(const targets::CPrinter& pr, const char* type, const Vec3& v) {
  return fmt::format("{}({}, {}, {})", type, pr.literal(v.x), pr.literal(v.y), pr.literal(v.z));
}


// The shader's parameters, one a line: "    type name = value,  // comment".
struct ShaderParams {
  std::string text;
  void add(const std::string& type, const std::string& name, const std::string& value, const char* comment = "") {
    text.append("    ").append(type).append(" ").append(name).append(" = ").append(value).append(",");
    if (*comment) text.append("  // ").append(comment);
    text += '\n';
  }
};

// Light i's block of the shader, its parameters added to `params`.
std::string light_block(const targets::CPrinter& pr, const Light& l, size_t i, ShaderParams& params,
                        const std::string& constant_args) {
  std::string id = fmt::format("light{}_", i);
  params.add("color", id + "color", pr.color_literal(l.color));
  std::string body;
  if (l.type == Light::Type::Directional) {
    params.add("vector", id + "direction", triple(pr, "vector", to_blender(l.direction)), "the way the light travels");
    body += fmt::format("        vector L = -normalize({}direction);\n", id);
    body += "        float d = 1e30;\n        float factor = 1.0;\n";
  } else {
    params.add("point", id + "position", triple(pr, "point", to_blender(l.position)));
    body += fmt::format("        vector to_light = {}position - P;\n", id);
    body += "        float d = length(to_light);\n        vector L = to_light / d;\n";
    const Attenuation& a = l.attenuation;
    if (a.law == Attenuation::Law::None) body += "        float factor = 1.0;\n";
    if (a.law == Attenuation::Law::InverseSquare) body += "        float factor = attenuation_inverse_square(d);\n";
    if (a.law == Attenuation::Law::Polynomial) {
      params.add("float", id + "constant", pr.literal(a.constant), "attenuation c1");
      params.add("float", id + "linear", pr.literal(a.linear), "attenuation c2");
      params.add("float", id + "quadratic", pr.literal(a.quadratic), "attenuation c3");
      body += fmt::format(
          "        float factor = attenuation_polynomial(d, {0}constant, {0}linear, {0}quadratic);\n", id);
    }
    if (l.type == Light::Type::Spot) {
      params.add("vector", id + "direction", triple(pr, "vector", to_blender(l.direction)), "the cone's axis");
      params.add("float", id + "cutoff", pr.literal(l.cutoff), "degrees");
      params.add("float", id + "exponent", pr.literal(l.exponent));
      body += fmt::format(
          "        factor *= spot_cone(-dot(L, normalize({0}direction)), cos(radians({0}cutoff)), {0}exponent);\n", id);
    }
  }
  const char* kind = l.type == Light::Type::Point ? "point" : l.type == Light::Type::Spot ? "spot" : "directional";
  std::string out = fmt::format("    {{   // light {}: {}\n{}", i, kind, body);
  out += "        if (factor > 0 && dot(Nn, L) > 0 && !(shadows && trace(P, L, \"maxdist\", d)))\n";
  out += fmt::format("            radiance += factor * {}color * facet_reflect(Nn, L, V, T{});\n    }}\n", id,
                     constant_args);
  return out;
}

}  // namespace

std::string osl_sweep_source(const Material& m) {
  GenerateOptions o;
  o.target = Target::Osl;
  o.library = true;
  o.source = m.source;
  MaterialProgram p = compile(m);
  targets::CPrinter pr(osl_dialect());
  std::string grid;
  for (const auto& f : ir::dependencies(sweep_grid())) grid += pr.function(f) + "\n";
  std::string params, args;
  for (const auto& c : pr.free_constants(p.reflectance)) {
    params += fmt::format("    {} {} = {},\n", pr.type(c->type), c->name,
                          c->type == ir::Type::Color ? pr.color_literal(c->value) : pr.literal(c->value[0]));
    args += ", " + c->name;
  }
  // The sweep's directions are in facet's frame: the tangent axis as written.
  Vec3 a = normalize(Vec3(m.tangent_axis));
  params += fmt::format("    vector tangent_axis = {},", triple(pr, "vector", a));
  return generate_osl(m, o) + "\n" + grid +
         render_template("osl/sweep.osl", {{"parameters", params}, {"constant_args", args}});
}

std::string generate_osl(const Material& m, const GenerateOptions& o) {
  MaterialProgram p = compile(m);
  targets::CPrinter pr(osl_dialect());

  std::string functions;
  for (const auto& f : p.functions()) functions += pr.function(f) + "\n";

  std::string constant_params, constant_args;
  for (const auto& c : pr.free_constants(p.reflectance)) {
    constant_params += ", " + pr.type(c->type) + " " + c->name;
    constant_args += ", " + c->name;
  }
  std::string inputs, arguments;
  if (p.uses_bitangent()) inputs += "    vector B = cross(Nn, T);\n";
  if (p.uses_half_vector())
    inputs += fmt::format("    // h = (L + V) / max(|L + V|, ε), as on every target\n"
                          "    vector H = (L + V) * inversesqrt(max(dot(L + V, L + V), {}));\n",
                          pr.literal(kEpsilon * kEpsilon));
  for (const auto& in : p.inputs) {
    auto vec = [](char c) -> std::string { return c == 'N' ? "Nn" : std::string(1, c); };
    inputs += fmt::format("    float {} = dot({}, {});\n", in, vec(in[0]), vec(in[2]));
    arguments += (arguments.empty() ? "" : ", ") + in;
  }
  arguments += constant_args;

  std::string header = render_template(
      "osl/header.osl", {{"name", m.name},
                         {"what", o.library ? "OSL library (functions for a shader)" : "OSL shader for Cycles"},
                         {"version", FACET_VERSION},
                         {"source", o.source},
                         {"description", describe_material(m, "//")}});
  std::string library = render_template("osl/library.osl", {{"functions", functions},
                                                            {"constant_params", constant_params},
                                                            {"inputs", inputs},
                                                            {"arguments", arguments}});
  if (o.library) return header + "\n" + library;

  const Scene scene = o.scene ? *o.scene : default_scene();
  // Shader parameters: the material constants, then the scene's ambient and lights.
  ShaderParams params;
  auto color_value = [&](const RGB& c) { return pr.color_literal(c); };
  for (const auto& c : pr.free_constants(p.reflectance))
    params.add(pr.type(c->type), c->name, c->type == ir::Type::Color ? color_value(c->value) : pr.literal(c->value[0]));
  params.add("color", "material_ambient", color_value(m.ambient), "m_a");
  params.add("color", "material_emission", color_value(m.emission), "m_e");
  params.add("vector", "tangent_axis", triple(pr, "vector", to_blender(normalize(Vec3(m.tangent_axis)))));
  params.add("color", "ambient_light", color_value(scene.ambient), "the scene's ambient colour A");

  std::string lights;
  for (size_t i = 0; i < scene.lights.size(); ++i) lights += light_block(pr, scene.lights[i], i, params, constant_args);
  std::string shader = render_template("osl/shader.osl", {{"scene", scene.name},
                                                          {"shader", "facet_" + identifier(m.name)},
                                                          {"parameters", params.text},
                                                          {"lights", lights}});
  return header + "\n" + library + shader;
}

}  // namespace facet
