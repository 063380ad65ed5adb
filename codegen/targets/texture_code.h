// facet — what a target needs to sample one textured parameter (catalog/texture.h):
// the numbers of its statement, in the same form for GLSL, OSL and POV-Ray.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "catalog/program.h"
#include "core/texture.h"

namespace facet {

struct TextureCall {
  std::string name;       // the parameter's input name (diffuse_color, specular_alpha, …)
  bool color = false;     // a colour (three lanes) or a number
  int uv = 0;             // the coordinate set
  // uv′ = (a·u + b·v + ou, c·u + d·v + ov): KHR_texture_transform; identity when !transformed.
  bool transformed = false;
  double a = 1, b = 0, c = 0, d = 1, ou = 0, ov = 0;
  std::array<int, 2> wrap{0, 0};  // 0 repeat, 1 clamp, 2 mirror
  bool bilinear = true;
  bool srgb = false;
  int channel = -1;               // −1: rgb; else 0–3 (r, g, b, a)
  std::array<double, 3> factor{1, 1, 1};
  double lo = 0, hi = 0;          // the range the value is clamped to; hi may be +∞
  const Texels* texels = nullptr;
  std::string file;               // the image, as the material names it
};

// The textured parameters' calls (MaterialProgram::textured's order).
std::vector<TextureCall> texture_calls(const MaterialProgram& p);
// The normal map's call, named "normal_map": its raw rgb (linear, factor 1, range [0, 1]),
// which the target turns into n_t itself (catalog/texture.h, NormalMap). Empty without one.
std::optional<TextureCall> normal_map_call(const MaterialProgram& p);
// Every image the material samples: texture_calls(p), then the normal map's.
std::vector<TextureCall> image_calls(const MaterialProgram& p);
// The cut-out's alpha (Material::alpha), named "alpha", where it comes from an image (range
// [0, 1]); empty where it is a number or the material has no cut-out.
std::optional<TextureCall> alpha_call(const Material& m);

}  // namespace facet
