#include "targets/texture_code.h"

#include <cmath>

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
  return c;
}

}  // namespace

std::vector<TextureCall> texture_calls(const MaterialProgram& p) {
  std::vector<TextureCall> out;
  for (const auto& t : p.textured) out.push_back(call_of(t));
  return out;
}

std::optional<TextureCall> normal_map_call(const MaterialProgram& p) {
  if (!p.material.normal_map) return std::nullopt;
  return call_of({"normal_map", "normal_map", ir::Type::Color, p.material.normal_map->value, Range::closed(0, 1)});
}

std::optional<TextureCall> alpha_call(const Material& m) {
  if (!m.masked() || !m.alpha.texture) return std::nullopt;
  return call_of({"alpha", "alpha", ir::Type::Float, m.alpha, alpha_param().range});
}

std::vector<TextureCall> image_calls(const MaterialProgram& p) {
  std::vector<TextureCall> out = texture_calls(p);
  if (auto n = normal_map_call(p)) out.push_back(*n);
  return out;
}

}  // namespace facet
