#include "facet/targets.h"

#include <fmt/format.h>

#include "targets_internal.h"

namespace facet {

std::optional<Target> parse_target(const std::string& name) {
  for (Target t : all_targets())
    if (name == target_name(t)) return t;
  return std::nullopt;
}

const char* target_name(Target t) {
  switch (t) {
    case Target::Glsl: return "glsl";
    case Target::Glsl450: return "glsl450";
    case Target::Essl: return "essl";
    case Target::Osl: return "osl";
    case Target::Pov: return "pov";
  }
  return "?";
}

const std::vector<Target>& all_targets() {
  static const std::vector<Target> all = {Target::Glsl, Target::Glsl450, Target::Essl, Target::Osl, Target::Pov};
  return all;
}

std::string describe_lobe(const ModelSpec& s) {
  std::string params;
  for (const auto& p : s.def->params) {
    auto it = s.values.find(p.name);
    if (it == s.values.end()) continue;  // an absent optional object (toon)
    const Value& v = it->second;
    std::string text;
    switch (p.kind) {
      case ParamKind::Number: text = fmt::format("{}", v.number); break;
      case ParamKind::Bool: text = v.flag ? "true" : "false"; break;
      case ParamKind::Enum: text = v.choice; break;
      case ParamKind::Color:
        text = v.rgb[0] == v.rgb[1] && v.rgb[1] == v.rgb[2] ? fmt::format("{}", v.rgb[0])
                                                              : fmt::format("[{}, {}, {}]", v.rgb[0], v.rgb[1], v.rgb[2]);
        break;
      case ParamKind::Model: text = describe_lobe(*v.model); break;
      case ParamKind::Object:
        if (!v.model) continue;
        text = "{" + describe_lobe(*v.model) + "}";
        break;
      default: continue;
    }
    params += fmt::format("{}{} {}", params.empty() ? "" : ", ", p.name, text);
  }
  return params.empty() ? s.def->name : s.def->name + " (" + params + ")";
}

std::string describe_material(const Material& m, const std::string& marker) {
  std::string s;
  if (m.diffuse) s += fmt::format("{} Diffuse:  {} — {}\n", marker, describe_lobe(*m.diffuse), m.diffuse->def->citation);
  if (m.specular)
    s += fmt::format("{} Specular: {} — {}\n", marker, describe_lobe(*m.specular), m.specular->def->citation);
  return s;
}

std::string generate(const Material& m, const GenerateOptions& o) {
  switch (o.target) {
    case Target::Glsl:
    case Target::Glsl450:
    case Target::Essl: return generate_glsl(m, o);
    case Target::Osl: return generate_osl(m, o);
    case Target::Pov: return generate_pov(m, o);
  }
  return {};
}

}  // namespace facet
