#include "targets/targets.h"

#include <fmt/compile.h>
#include <fmt/format.h>

#include "targets/targets_internal.h"
#include "targets/templates.h"

namespace facet {

std::optional<Target> parse_target(const std::string& name) {
  for (Target t : all_targets())
    if (name == target_name(t)) return t;
  return std::nullopt;
}

std::optional<PovRoute> parse_pov_route(const std::string& name) {
  static const std::pair<const char*, PovRoute> routes[] = {
      {"auto", PovRoute::Auto}, {"native", PovRoute::Native}, {"exact", PovRoute::Exact}, {"fast", PovRoute::Fast}};
  for (const auto& [n, r] : routes)
    if (name == n) return r;
  return std::nullopt;
}

const char* target_name(Target t) {
  switch (t) {
    case Target::Glsl: return "glsl";
    case Target::Glsl450: return "glsl450";
    case Target::Essl: return "essl";
    case Target::Osl: return "osl";
    case Target::Pov: return "pov";
    case Target::Hlsl: return "hlsl";
    case Target::Wgsl: return "wgsl";
  }
  return "?";
}

const std::vector<Target>& all_targets() {
  static const std::vector<Target> all = {Target::Glsl, Target::Glsl450, Target::Essl, Target::Osl, Target::Pov,
                                               Target::Hlsl, Target::Wgsl};
  return all;
}

namespace {
void number_to(std::string& out, double v) { fmt::format_to(std::back_inserter(out), FMT_COMPILE("{}"), v); }
}  // namespace

std::string describe_lobe(const ModelSpec& s) {
  std::string params;
  for (const auto& p : s.def->params) {
    auto it = s.values.find(p.name);
    if (it == s.values.end()) continue;  // an absent optional object (toon)
    const Value& v = it->second;
    if (p.kind == ParamKind::Object && !v.model) continue;
    const size_t before = params.size();
    params.append(params.empty() ? "" : ", ").append(p.name).append(" ");
    switch (p.kind) {
      case ParamKind::Number: number_to(params, v.number); break;
      case ParamKind::Bool: params += v.flag ? "true" : "false"; break;
      case ParamKind::Enum: params += v.choice; break;
      case ParamKind::Color:
        if (v.rgb[0] == v.rgb[1] && v.rgb[1] == v.rgb[2]) {
          number_to(params, v.rgb[0]);
        } else {
          params += '[';
          for (int c = 0; c < 3; ++c) {
            if (c) params += ", ";
            number_to(params, v.rgb[size_t(c)]);
          }
          params += ']';
        }
        break;
      case ParamKind::Model: params += describe_lobe(*v.model); break;
      case ParamKind::Object: params.append("{").append(describe_lobe(*v.model)).append("}"); break;
      default: params.resize(before);  // not described
    }
  }
  return params.empty() ? s.def->name : s.def->name + " (" + params + ")";
}

std::string describe_material(const Material& m, const std::string& marker) {
  std::string s;
  if (m.diffuse)
    s.append(marker).append(" Diffuse:  ").append(describe_lobe(*m.diffuse)).append(" — ").append(m.diffuse->def->citation).append("\n");
  if (m.specular)
    s.append(marker).append(" Specular: ").append(describe_lobe(*m.specular)).append(" — ").append(m.specular->def->citation).append("\n");
  for (size_t i = 0; i < m.layers.size(); ++i)
    s.append(marker).append(fmt::format(" Layer {}:  ", i)).append(describe_lobe(m.layers[i])).append(" — ").append(m.layers[i].def->citation).append("\n");
  return s;
}

std::string generate(const Material& m, const GenerateOptions& o) {
  switch (o.target) {
    case Target::Glsl:
    case Target::Glsl450:
    case Target::Essl: return generate_glsl(m, o);
    case Target::Osl: return generate_osl(m, o);
    case Target::Pov: return generate_pov(m, o);
    case Target::Hlsl: return generate_hlsl(m, o);
    case Target::Wgsl: return generate_wgsl(m, o);
  }
  return {};
}

std::string emission_weight_call(const MaterialProgram& p, const std::string& NoV, const std::vector<std::string>& after) {
  std::string call = p.emission_weight->name + "(" + NoV;
  for (size_t i = 1; i < p.emission_weight->params.size(); ++i) call += ", " + p.emission_weight->params[i].name;
  for (const auto& a : after) call += ", " + a;
  return call + ")";
}

void emitted_values(const MaterialProgram& p, std::map<std::string, std::string>& values) {
  values["emitted"] = p.emission_weight ? std::string(kEmissionInput) + " * " + emission_weight_call(p, "dot(n, v)")
                                        : std::string(kEmissionInput);
  values["emitted_doc"] = p.emission_weight ? "m_e under the layers over it, weighted by " + p.emission_weight->name +
                                                  "(n·v) (" + p.emission_weight->citation + ")"
                                            : "m_e itself (nothing lies over it)";
}

void coat_normal_values(const MaterialProgram& p, const std::string& declaration,
                        std::map<std::string, std::string>& values) {
  values["coat_param"] = p.uses_coat_normal() ? ", " + declaration : "";
  values["coat_doc"] = p.uses_coat_normal() ? "; c, unit, the clear coat's own normal (the surface's own, unmapped, "
                                              "where n is a normal map's: KHR_materials_clearcoat)"
                                            : "";
}

std::string normal_map_functions(const MaterialProgram& p, const std::string& template_path,
                                 const std::function<std::string(double)>& literal) {
  std::string out;
  auto add = [&](const NormalMap& m, const char* what, const char* whose, const char* function, const char* map) {
    out += render_template(template_path, {{"what", what},
                                           {"whose", whose},
                                           {"function", function},
                                           {"map", map},
                                           {"strength", literal(m.strength)},
                                           {"green", m.green_down ? "-" : ""}});
  };
  if (const auto& m = p.material.normal_map) add(*m, "The normal map", "the lobes'", "facet_normal_mapped", "normal_map");
  if (const auto& m = p.material.coat_normal_map)
    add(*m, "The clear coat's own normal map (KHR_materials_clearcoat's clearcoatNormalTexture)", "the coat's",
        "facet_coat_normal_mapped", "coat_normal_map");
  return out;
}

void normal_mapping_values(const MaterialProgram& p, const std::string& let, std::map<std::string, std::string>& values) {
  std::string mapping;
  if (p.normal_mapped())
    mapping = "    // The lobes read the normal map's normal and a tangent that follows it.\n"
              "    " + let + " ns = facet_normal_mapped(n, facet_uv_tangent, facet_uv_handedness);\n";
  else
    mapping = "    " + let + " ns = n;\n";
  // The lobes' tangent: the texture frame's where they turn from it (KHR_materials_anisotropy:
  // the mesh's tangent; facet_reflect's b is then w·(n × t)), else t; made ⟂ the lobes' normal.
  if (p.uv_tangent())
    mapping += "    // The lobes' tangent is the surface's texture frame's (the mesh's tangent), made ⟂ ns.\n"
               "    t = normalize(facet_uv_tangent - ns * dot(ns, facet_uv_tangent));\n";
  else if (p.normal_mapped())
    mapping += "    t = normalize(t - ns * dot(ns, t));\n";
  // The coat's normal: its own map's, else the surface's own (KHR_materials_clearcoat).
  if (p.coat_normal_mapped())
    mapping += "    " + let + " nc = facet_coat_normal_mapped(n, facet_uv_tangent, facet_uv_handedness);\n";
  values["mapping"] = mapping;
  values["coat_arg"] = coat_normal_arg(p, p.coat_normal_mapped() ? "nc" : "n");
  values["emitted_normal"] = p.coat_normal_mapped() ? "nc" : "n";
}

std::string bitangent(const MaterialProgram& p, const std::string& let) {
  if (!p.uses_bitangent()) return "";
  if (!p.uv_tangent()) return "    " + let + " b = cross(n, t);\n";
  return "    // b = w·(n × t): the texture frame's handedness w (B = w·(N × T), glTF's TANGENT.w).\n"
         "    " + let + " b = facet_uv_handedness * cross(n, t);\n";
}

std::string coat_normal_arg(const MaterialProgram& p, const std::string& normal) {
  return p.uses_coat_normal() ? ", " + normal : "";
}

}  // namespace facet
