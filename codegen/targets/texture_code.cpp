#include "targets/texture_code.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "catalog/texture.h"

namespace facet {

namespace {

TextureCall call_of(const TexturedInput& t) {
  const TextureRef& r = *t.value.texture;
  TextureCall c;
  c.name = t.name;
  c.color = t.type == ir::Type::Color;
  c.uv = r.uv;
  c.transformed = r.has_transform();
  const double cs = std::cos(r.rotation), sn = std::sin(r.rotation);
  c.a = cs * r.scale[0];
  c.b = sn * r.scale[1];
  c.c = -sn * r.scale[0];
  c.d = cs * r.scale[1];
  c.ou = r.offset[0];
  c.ov = r.offset[1];
  c.wrap = {int(r.sampler.wrap[0]), int(r.sampler.wrap[1])};
  c.bilinear = r.sampler.filter == TextureFilter::Bilinear;
  c.srgb = r.sampler.srgb;
  c.channel = r.channel == "rgb" ? -1 : int(std::string("rgba").find(r.channel[0]));
  c.factor = t.value.rgb;
  auto b = texture_bounds(t.range);
  c.lo = b[0];
  c.hi = b[1];
  c.texels = r.texels.get();
  c.file = r.file;
  c.image = r.has_image();
  c.vertex_color = r.vertex_color;
  c.offset = r.bias;
  if (!t.max_of.empty()) {
    c.max_of = t.max_of;
    c.color = false;
    c.image = c.vertex_color = false;
  }
  return c;
}

}  // namespace

std::vector<TextureCall> texture_calls(const MaterialProgram& p) {
  std::vector<TextureCall> out;
  for (const auto& t : p.textured) out.push_back(call_of(t));
  return out;
}

std::vector<TextureCall> normal_map_calls(const MaterialProgram& p) {
  std::vector<TextureCall> out;
  const Material& m = p.material;
  if (m.normal_map) out.push_back(call_of({"normal_map", "normal_map", ir::Type::Color, m.normal_map->value, Range::closed(0, 1), ""}));
  if (m.coat_normal_map)
    out.push_back(call_of({"coat_normal_map", "coat_normal_map", ir::Type::Color, m.coat_normal_map->value,
                           Range::closed(0, 1), ""}));
  return out;
}

std::optional<TextureCall> alpha_call(const Material& m) {
  if (!m.masked() || !m.alpha.texture) return std::nullopt;
  return call_of({"alpha", "alpha", ir::Type::Float, m.alpha, alpha_param().range, ""});
}

std::vector<TextureCall> image_calls(const MaterialProgram& p) {
  std::vector<TextureCall> out;
  for (const auto& c : texture_calls(p))
    if (c.image) out.push_back(c);
  for (const auto& n : normal_map_calls(p)) out.push_back(n);
  return out;
}

std::string texture_value_code(const TextureCall& c, const std::string& texel, const std::string& vc,
                               const ValueWords& w) {
  const std::string factor = c.color ? w.color(c.factor) : w.number(c.factor[0]);
  std::string value = factor;
  if (c.image) value += " * " + texel;
  if (c.vertex_color) value += " * " + vc;
  if (!c.offset_zero()) value = (c.color ? w.color(c.offset) : w.number(c.offset[0])) + " + " + value;
  const std::string lo = c.color ? w.grey(c.lo) : w.number(c.lo);
  if (!std::isfinite(c.hi)) return fmt::format("max({}, {})", value, lo);
  return fmt::format("clamp({}, {}, {})", value, lo, c.color ? w.grey(c.hi) : w.number(c.hi));
}

std::string gpu_sample_statement(const TextureCall& c, const std::string& uv, const SampleWords& w) {
  if (!c.max_of.empty()) return fmt::format("    {0} = max(max({1}.x, {1}.y), {1}.z);\n", c.name, c.max_of);
  std::string texel;
  if (c.image) {
    const std::string lookup = fmt::format("facet_texture(facet_texture_{}, {}, {}({}, {}), {}, {})", c.name, uv,
                                           w.int2, c.wrap[0], c.wrap[1], c.bilinear ? "true" : "false",
                                           c.srgb ? "true" : "false");
    texel = c.channel < 0 ? lookup + ".rgb" : lookup + "." + std::string(1, "rgba"[c.channel]);
    if (c.color && c.channel >= 0) texel = w.to_color + "(" + texel + ")";
  }
  const std::string vc = c.color ? "color0.rgb" : std::string("color0.") + "rgba"[std::max(c.channel, 0)];
  return fmt::format("    {} = {};\n", c.name, texture_value_code(c, texel, vc, w.value));
}

std::map<std::string, std::string> sampling_doc(const MaterialProgram& p) {
  const auto calls = texture_calls(p);
  const bool offset = std::any_of(calls.begin(), calls.end(), [](const TextureCall& c) { return !c.offset_zero(); });
  const bool vc = p.uses_vertex_color();
  return {{"color_doc", vc ? ",\n// and the surface's vertex colour color0 (glTF's COLOR_0, linear RGBA; white where a surface has none)"
                           : ""},
          {"offset", offset ? "offset + " : ""},
          {"vc", vc ? " ⊗ color0" : ""}};
}

}  // namespace facet
