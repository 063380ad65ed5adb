// OSL: a shader Cycles compiles in a Script node, or the functions alone.
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "targets/cfamily.h"
#include "targets/osl_cutouts.h"
#include "targets/sweep_grid.h"
#include "targets/targets.h"
#include "targets/targets_internal.h"
#include "targets/templates.h"
#include "targets/texture_code.h"

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
Vec3 to_blender(const Vec3& p) { return targets::osl_blender(p); }

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

// Light i's block of the shader, its parameters added to `params`; the lobes read `normal`
// (Nn, or Ns under a normal map) while Nn decides which lights are above the surface. Where
// the scene has cut-outs (`cutouts`), shadow rays go on past the surfaces cut out (facet_blocked).
std::string light_block(const targets::CPrinter& pr, const Light& l, size_t i, ShaderParams& params,
                        const std::string& constant_args, const char* normal, bool cutouts) {
  std::string id = fmt::format("light{}_", i);
  params.add("color", id + "color", pr.color_literal(l.color));
  std::string body;
  if (l.type == Light::Type::Directional) {
    params.add("vector", id + "direction", triple(pr, "vector", to_blender(l.direction)), "the way the light travels");
    body += fmt::format("        vector L = -normalize({}direction);\n", id);
    body += "        float d = 1e30;\n        float factor = 1.0;\n";
  } else {
    params.add("point", id + "position", triple(pr, "point", to_blender(l.position)));
    body += fmt::format("        vector to_light = {}position - Pt;\n", id);
    body += "        float d = length(to_light);\n        vector L = to_light / d;\n";
    const Attenuation& a = l.attenuation;
    if (a.law == Attenuation::Law::None) body += "        float factor = 1.0;\n";
    if (a.law == Attenuation::Law::InverseSquare) body += "        float factor = attenuation_inverse_square(d);\n";
    if (a.law == Attenuation::Law::InverseSquareRange) {
      params.add("float", id + "range", pr.literal(a.range), "where the light reaches 0");
      body += fmt::format("        float factor = attenuation_inverse_square_range(d, {}range);\n", id);
    }
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
  out += cutouts ? "        if (factor > 0 && dot(Nn, L) > 0 && !(shadows && facet_blocked(Pt, L, d, shadow_from)))\n"
                 : "        if (factor > 0 && dot(Nn, L) > 0 && !(shadows && trace(Pt, L, \"maxdist\", d)))\n";
  out += fmt::format("            radiance += factor * {}color * facet_reflect({}, L, V, T{});\n    }}\n", id, normal,
                     constant_args);
  return out;
}

// The textured parameters' shader parameters (each image's path), and the statements that
// sample them at the shading point, before the lights: the locals facet_reflect takes.
// ", W" for facet_reflect's handedness parameter or argument where the lobes' tangent is the
// texture frame's (MaterialProgram::uv_tangent), else nothing.
std::string handedness_arg(const MaterialProgram& p, const std::string& w) { return p.uv_tangent() ? ", " + w : ""; }

// facet_reflect's statements that compute the shading inputs from Nn, L, V, T (and W, Nc), and
// the reflectance's arguments: the inputs, its textured parameters by name.
void reflect_inputs(const targets::CPrinter& pr, const MaterialProgram& p, std::string& inputs, std::string& arguments) {
  if (p.uses_bitangent()) inputs += p.uv_tangent() ? "    vector B = W * cross(Nn, T);  // W: the frame's handedness\n"
                                                    : "    vector B = cross(Nn, T);\n";
  if (p.uses_half_vector())
    inputs += fmt::format("    // h = (L + V) / max(|L + V|, ε), as on every target\n"
                          "    vector H = (L + V) * inversesqrt(max(dot(L + V, L + V), {}));\n",
                          pr.literal(kEpsilon * kEpsilon));
  for (const auto& in : p.inputs) {
    arguments += (arguments.empty() ? "" : ", ") + in;
    if (p.is_textured(in)) continue;  // a parameter of facet_reflect, sampled by the shader
    auto vec = [](char c) -> std::string { return c == 'N' ? "Nn" : c == 'C' ? "Nc" : std::string(1, c); };
    inputs += fmt::format("    float {} = dot({}, {});\n", in, vec(in[0]), vec(in[2]));
  }
}

struct OslTextures {
  std::string params, samples, reflect_params, reflect_args, mapping;
};

// The normal maps' statements (catalog/texture.h, NormalMap; glTF 2.0 §3.9.3): Ns, the lobes'
// normal, from the sampled rgb and the frame facet_uv_tangent, facet_uv_handedness (T follows
// it), and Nc, the coat's own (Material::coat_normal_map), from its map on the same frame; T the
// frame's own Tu made ⟂ the lobes' normal where the lobes turn from it (MaterialProgram::uv_tangent).
std::string osl_normal_mapping(const targets::CPrinter& pr, const MaterialProgram& p) {
  const Material& m = p.material;
  std::string out =
      "    // The normal maps: n_t = normalize((2·rgb − 1) ⊗ (s, s, 1)) (y negated for a green-down map),\n"
      "    // the normal normalize(n_t.x·Tu + n_t.y·Bu + n_t.z·Nn), Tu = ∂p/∂u made ⟂ Nn, Bu = w·(Nn × Tu)\n"
      "    // (uv_tangent and w = uv_handedness: facet_uv_tangent, facet_uv_handedness).\n"
      "    vector Tu = normalize(uv_tangent - Nn * dot(Nn, uv_tangent));\n"
      "    vector Bu = uv_handedness * cross(Nn, Tu);\n";
  auto mapped = [&](const NormalMap& map, const char* texel, const char* tag, const char* normal, const char* whose) {
    out += fmt::format(
        "    color {2}_c = 2 * {3} - 1;\n"
        "    vector {2}_t = normalize(vector({0} * {2}_c[0], {1}{0} * {2}_c[1], {2}_c[2]));\n"
        "    vector {4} = normalize({2}_t[0] * Tu + {2}_t[1] * Bu + {2}_t[2] * Nn);  // {5}\n",
        pr.literal(map.strength), map.green_down ? "-" : "", tag, texel, normal, whose);
  };
  if (m.normal_map) mapped(*m.normal_map, "normal_map", "nm", "Ns", "the lobes' normal");
  const char* lobes = m.normal_map ? "Ns" : "Nn";
  if (p.uv_tangent())  // KHR_materials_anisotropy: the mesh's tangent; facet_reflect's B = W·(N × T)
    out += fmt::format("    T = normalize(Tu - {0} * dot({0}, Tu));  // the lobes' tangent: the texture frame's\n", lobes);
  else if (m.normal_map)
    out += "    T = normalize(T - Ns * dot(Ns, T));  // the anisotropic tangent follows the mapped normal\n";
  if (m.coat_normal_map) mapped(*m.coat_normal_map, "coat_normal_map", "cm", "Nc", "the clear coat's own normal");
  return out;
}

// The statements that set s0, t0, s1, t1 (glTF's coordinates) and the tangent frame at the
// shading point, where the shader samples images (`uv`) or has a cut-out of its own (`cut`).
std::string osl_coordinates(const MaterialProgram& p, bool uv, bool cut) {
  std::string out;
  if (uv)
    out = "    // facet_uv0/1 are Blender's UV (v up); glTF's t = 1 − v.\n"
          "    float s0 = facet_uv0[0], t0 = 1 - facet_uv0[1];\n"
          "    float s1 = facet_uv1[0], t1 = 1 - facet_uv1[1];\n";
  else if (cut)
    out = "    float s0 = 0, t0 = 0, s1 = 0, t1 = 0;  // read by no image\n";
  if (p.has_uv_frame())
    out += "    vector uv_tangent = facet_uv_tangent;\n    float uv_handedness = facet_uv_handedness;\n";
  else if (cut)
    out += "    vector uv_tangent = 0;  // read by no normal map\n    float uv_handedness = 1;\n";
  return out;
}

OslTextures osl_textures(const targets::CPrinter& pr, const MaterialProgram& p, ShaderParams& params,
                         const GenerateOptions& o, bool uv) {
  OslTextures out;
  if (uv)
    out.params = "    vector facet_uv0 = 0,  // texture coordinates: link a UV Map node (Blender's UV, v up)\n"
                 "    vector facet_uv1 = 0,\n";
  if (!p.has_textures()) return out;
  out.samples = "    // Textured parameters.\n";
  std::vector<TextureCall> calls = texture_calls(p);
  for (const auto& n : normal_map_calls(p)) calls.push_back(n);
  for (const auto& c : calls) {
    std::string file = "facet_texture_" + c.name;
    if (c.image) {
      std::string note = c.file;
      if (targets::osl_premultiplied(c, o))
        note += " (its alpha is below 1 somewhere: Cycles premultiplies its colour by it; read a copy without alpha)";
      params.add("string", file, targets::osl_image_file(c, o), note.c_str());
    }
    const targets::OslSample sample = targets::osl_sample(pr, c, file);
    const std::string type = c.color ? "color" : "float";
    out.samples += sample.statements + fmt::format("    {} {} = {};\n", type, c.name, sample.value);
    if (c.name == "normal_map" || c.name == "coat_normal_map") continue;  // read by the mapping below
    if (!p.uses(c.name)) continue;  // m_a or m_e: read by the shader, not by facet_reflect
    out.reflect_params += ", " + type + " " + c.name;
    out.reflect_args += ", " + c.name;
  }
  if (p.uses_vertex_color())
    out.params += "    color facet_color0 = 1,  // the vertex colour (glTF's COLOR_0, linear): link an Attribute node's Color\n"
                  "    float facet_alpha0 = 1,  // … and its Alpha; unlinked, white\n";
  if (const auto frame = p.material.frame_uv()) {
    out.params += "    vector facet_uv_tangent = 0,  // the normal map's ∂p/∂u, world space (docs/textures.md, Tangent frames)\n"
                  "    float facet_uv_handedness = 1,  // w: B = w·(N × T)\n" +
                  fmt::format("    int facet_normal_map_uv = {},  // the coordinate set the normal maps read (their tangents')\n",
                              *frame);
    out.mapping = osl_normal_mapping(pr, p);
  }
  return out;
}

}  // namespace

std::string osl_sweep_source(const Material& m) {
  require_no_images(m, "which the OSL sweep target does not sample yet (GLSL does; docs/textures.md)");
  GenerateOptions o;
  o.target = Target::Osl;
  o.library = true;
  o.source = m.source;
  MaterialProgram p = compile(m);
  targets::CPrinter pr(osl_dialect());
  std::string grid;
  for (const auto& f : ir::dependencies(sweep_grid())) grid += pr.function(f) + "\n";
  // The frame's handedness +1 (the sweep's t is the tangent), the coat's normal the sweep's n.
  std::string params, args = handedness_arg(p, "1") + coat_normal_arg(p, "Nn");
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
  reflect_inputs(pr, p, inputs, arguments);
  arguments += constant_args;
  // facet_reflect(Nn, L, V, T[, W][, Nc], constants…): W the texture frame's handedness where the
  // lobes' tangent is that frame's, Nc the coat's own normal where the lobes read it.
  constant_params = handedness_arg(p, "float W") + coat_normal_arg(p, "vector Nc") + constant_params;
  constant_args = handedness_arg(p, "uv_handedness") + coat_normal_arg(p, p.coat_normal_mapped() ? "Nc" : "Nn") +
                  constant_args;
  ShaderParams params;
  const Scene& scene = o.scene ? *o.scene : default_scene();
  const targets::OslCutouts cutouts = targets::osl_cutouts(pr, m, scene, o.fallback ? *o.fallback : m, o);
  const bool uv = p.has_textures() || cutouts.own_uv;
  const OslTextures textures = osl_textures(pr, p, params, o, uv);

  std::string header = render_template(
      "osl/header.osl", {{"name", m.name},
                         {"what", o.library ? "OSL library (functions for a shader)" : "OSL shader for Cycles"},
                         {"version", FACET_VERSION},
                         {"source", o.source},
                         {"description", describe_material(m, "//")}});
  std::string library = render_template("osl/library.osl", {{"functions", functions},
                                                            {"textures", p.has_textures() || cutouts.images ? render_template("osl/textures.osl", {}) : ""},
                                                            {"constant_params", constant_params + textures.reflect_params},
                                                            {"inputs", inputs},
                                                            {"arguments", arguments}});
  if (o.library) return header + "\n" + library;

  // Shader parameters: the images, the material constants, then the scene's ambient and lights.
  auto color_value = [&](const RGB& c) { return pr.color_literal(c); };
  for (const auto& c : p.constants())
    params.add(pr.type(c->type), c->name, c->type == ir::Type::Color ? color_value(c->value) : pr.literal(c->value[0]));
  // m_e as it leaves the surface: under the layers over it, weighted by n·v of the surface's own normal.
  std::string emitted = kEmissionInput;
  if (p.emission_weight) {
    std::vector<std::string> constants;
    for (const auto& c : pr.free_constants(p.emission_weight)) constants.push_back(c->name);
    emitted += " * " + emission_weight_call(p, p.coat_normal_mapped() ? "dot(Nc, V)" : "dot(Nn, V)", constants);
  }
  // m_a and m_e: parameters, or locals sampled from their images (kAmbientInput, kEmissionInput).
  if (!m.ambient_texture) params.add("color", kAmbientInput, color_value(m.ambient), "m_a");
  if (!m.emission_texture) params.add("color", kEmissionInput, color_value(m.emission), "m_e");
  params.add("vector", "tangent_axis", triple(pr, "vector", to_blender(normalize(Vec3(m.tangent_axis)))));
  params.add("color", "ambient_light", color_value(scene.ambient), "the scene's ambient colour A");

  std::string lights;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    lights += light_block(pr, scene.lights[i], i, params, constant_args + textures.reflect_args,
                          p.normal_mapped() ? "Ns" : "Nn", cutouts.any);
  std::string shader = render_template("osl/shader.osl", {{"scene", scene.name},
                                                          {"shader", "facet_" + identifier(m.name)},
                                                          {"parameters", params.text + textures.params},
                                                          {"cutouts", cutouts.functions},
                                                          {"coordinates", osl_coordinates(p, uv, !cutouts.test.empty())},
                                                          {"shadow_from", cutouts.any ? "    float shadow_from = 0;  // facet_blocked: the first trace() skips the shaded primitive\n" : ""},
                                                          {"cutout", cutouts.test},
                                                          {"samples", textures.samples + textures.mapping},
                                                          {"emitted", emitted},
                                                          {"lights", lights}});
  return header + "\n" + library + shader;
}

}  // namespace facet
