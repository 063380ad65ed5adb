// facet — what a target needs to sample one textured parameter (catalog/texture.h):
// the numbers of its statement, in the same form for GLSL, OSL and POV-Ray.
#pragma once

#include <array>
#include <functional>
#include <map>
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
  const Texels* texels = nullptr;  // null without an image
  std::string file;               // the image, as the material names it
  bool image = true;              // false: the vertex colour alone (no image to bind or sample)
  bool vertex_color = false;      // times the vertex colour: its rgb (colours) or component `channel` (numbers)
  std::array<double, 3> offset{0, 0, 0};  // added before the clamp
  // Non-empty: max₃ of the colour call of that name, sampled before it (TexturedInput::max_of);
  // no image or vertex colour of its own, every other field the colour's.
  std::string max_of;
  bool offset_zero() const { return offset == std::array<double, 3>{0, 0, 0}; }
};

// The textured parameters' calls (MaterialProgram::textured's order), those of the vertex
// colour alone included: every target's facet_sample_textures() sets each.
std::vector<TextureCall> texture_calls(const MaterialProgram& p);
// The normal maps' calls, named "normal_map" and "coat_normal_map" (Material::coat_normal_map),
// those the material has, in that order: their raw rgb (linear, factor 1, range [0, 1]), which
// the target turns into n_t itself (catalog/texture.h, NormalMap).
std::vector<TextureCall> normal_map_calls(const MaterialProgram& p);
// Every image the material samples: texture_calls(p) that have one, then the normal maps'.
// What the renderers upload and bind, and the targets declare: a value of the vertex colour
// alone has no image.
std::vector<TextureCall> image_calls(const MaterialProgram& p);
// The cut-out's alpha (Material::alpha), named "alpha", where it comes from an image (range
// [0, 1]); empty where it is a number or the material has no cut-out.
std::optional<TextureCall> alpha_call(const Material& m);

// How a C-family target (GLSL, HLSL, WGSL, OSL) words numbers and colours.
struct ValueWords {
  std::function<std::string(double)> number;                       // a number literal
  std::function<std::string(const std::array<double, 3>&)> color;  // a colour literal
  std::function<std::string(double)> grey;                         // a colour of three equal lanes (clamp's bounds)
};
// The value of call `c` as an expression: clamp(offset + factor * texel * vc, lo, hi), or
// max(…, lo) where hi is +∞ (catalog/texture.h), in the order every target and the
// reference compute it. `texel`: the image's channel as the parameter's type ("" without an
// image); `vc`: the vertex colour's rgb (colours) or component (numbers), "" where c does not
// read it. Without a vertex colour and an offset: factor * texel, clamped, as ever.
std::string texture_value_code(const TextureCall& c, const std::string& texel, const std::string& vc,
                               const ValueWords& w);

// How a GPU shading language (GLSL, HLSL, WGSL) words a sampling statement besides its values.
struct SampleWords {
  ValueWords value;
  std::string int2;       // a two-integer vector's constructor: "ivec2", "int2", "vec2<i32>"
  std::string to_color;   // what turns a channel into a colour of three equal lanes: "vec3", "(float3)", "vec3<f32>"
};
// One textured parameter's statement in facet_sample_textures() of the GPU targets'
// templates: `<name> = <texture_value_code>;`, the texel read by the template's
// facet_texture(image, uv, wrap, bilinear, srgb) at coordinates `uv` (unused without an
// image), the vertex colour from `color0`.
std::string gpu_sample_statement(const TextureCall& c, const std::string& uv, const SampleWords& w);

}  // namespace facet

namespace facet {

// The sampling templates' words on what facet_sample_textures() reads besides the
// coordinates ({{color_doc}}, {{offset}}, {{vc}}): "" for a material without vertex colours
// and offsets, so that its code reads as it always has.
std::map<std::string, std::string> sampling_doc(const MaterialProgram& p);

}  // namespace facet
