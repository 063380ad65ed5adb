// facet — a material parameter that comes from an image (docs/textures.md).
//
//   "color": {"texture": "bricks.png", "colorspace": "srgb", "filter": "bilinear",
//             "wrap": "repeat", "uv": 0, "channel": "rgb", "factor": [1, 1, 1],
//             "transform": {"offset": [0, 0], "scale": [1, 1], "rotation": 0},
//             "vertex_color": false, "offset": 0}
//
// value(u, v) = clamp(offset + factor ⊗ channel(sample(image, uv′)) ⊗ vc, the parameter's range),
// uv′ = KHR_texture_transform's offset + R(rotation) · (scale ⊗ uv); core/texture.h
// holds the sampling rule. vc is the surface's vertex colour (glTF's COLOR_0, Mesh::colors;
// white off meshes that carry none) where "vertex_color" is true, else 1: its rgb for a colour
// parameter, the component "channel" names for a number. With "vertex_color" the image may be
// left out: the value is then clamp(offset + factor ⊗ vc, range), a vertex colour alone.
#pragma once

#include <array>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "catalog/catalog.h"
#include "core/diagnostics.h"
#include "core/texture.h"

namespace facet {

// A surface's vertex colour, RGBA (glTF's COLOR_0: linear, alpha 1 where it is RGB); white
// where there is none, which leaves a value that reads it as without.
using VertexColor = std::array<double, 4>;
inline constexpr VertexColor kWhiteVertexColor{1, 1, 1, 1};

struct TextureRef {
  std::string file;     // as the material wrote it; empty: no image, the vertex colour alone
  std::string path;     // resolved against the material file's folder
  std::string channel;  // "rgb" (colours only), "r", "g", "b" or "a"
  int uv = 0;           // the texture coordinate set: 0 or 1
  std::array<double, 2> offset{0, 0}, scale{1, 1};
  double rotation = 0;  // radians
  std::string colorspace;  // "srgb" or "linear"
  Sampler sampler;
  std::shared_ptr<const Texels> texels;  // null without an image
  bool vertex_color = false;             // times the vertex colour (its rgb, or the channel's component)
  std::array<double, 3> bias{0, 0, 0};   // "offset": added before the clamp (lanes equal for a number)

  bool has_image() const { return !file.empty(); }
  // Which component of the vertex colour (and of the image) a number reads: 0–3 for r, g, b, a.
  int channel_index() const { return channel == "rgb" ? -1 : int(std::string("rgba").find(channel[0])); }
  bool has_transform() const { return offset != std::array<double, 2>{0, 0} || scale != std::array<double, 2>{1, 1} || rotation != 0; }
  // KHR_texture_transform's uv′ (its example "the lower left quadrant, rotated clockwise
  // 90°" fixes the rotation's sense: u′ = cos·s_u·u + sin·s_v·v + o_u, v′ = −sin·s_u·u + cos·s_v·v + o_v).
  std::array<double, 2> transform(double u, double v) const;
};

// The value a texel maps to is clamped to the parameter's range; an open bound a
// (as α > 0) clamps to a + kTextureOpenMargin.
inline constexpr double kTextureOpenMargin = 1e-3;
// The bounds a texture value is clamped to: [lo, hi] (hi may be +∞).
std::array<double, 2> texture_bounds(const Range& r);
// The largest factor a texture of a parameter of range `r` takes: the range's top,
// and at least the colour bound kColorMax, so that every value of the range stays
// reachable from a channel in (0, 1] and the factor stays a float32 number.
double texture_factor_max(const Range& r);

// {"texture": …} (or {"vertex_color": true, …}) for parameter `p` (texturable), given at
// `path` of a document read from `file` (relative image paths are resolved against its
// folder). Problems go to `sink`; the image is decoded here, so a missing or bad image is
// reported at `path`.texture.
std::optional<Value> parse_texture_value(const nlohmann::json& j, const std::string& path, const ParamDef& p,
                                         DiagnosticSink& sink);
// The JSON of a textured value (every key written out); the image's absolute path.
nlohmann::json texture_json(const Value& v);
// `j` (a material's JSON, or any JSON holding some) with every {"texture": PATH}'s
// image path written relative to `folder`: for a file written there, which reads it back.
nlohmann::json relative_textures(nlohmann::json j, const std::string& folder);
// The JSON Schema of {"texture": …} for a parameter of range `range`: a $ref into the
// material schema's $defs, which texture_schema_defs() holds, and the largest factor.
nlohmann::json texture_schema(bool color, const Range& range);
nlohmann::json texture_schema_defs();

// A nearest-filtered lookup closer than this (in texture coordinates) to a texel's edge
// reads one texel or its neighbour as the target's rounding goes: such pixels are
// left out of comparisons, as grazing shadow rays are.
inline constexpr double kTexelEdgeMargin = 1e-4;

// The parameter's value at texture coordinates (u, v) (the set the texture names) on a
// surface of vertex colour `color0`: for a Number parameter the three lanes are equal.
// `fragile`, if given, is set where the lookup lies within kTexelEdgeMargin of a
// nearest-filtered texel's edge.
std::array<double, 3> texture_value(const Value& v, const Range& range, double u, double v_, bool* fragile = nullptr,
                                    const VertexColor& color0 = kWhiteVertexColor);

// A tangent-space normal map (docs/textures.md, "Normal maps"): a material's top-level
//   "normal_map": {"texture": …, "uv": 0, "filter": …, "wrap": …, "transform": {…},
//                  "green": "up" | "down", "strength": 1}
// sampled by the one rule above, always rgb and linear. Its tangent-space normal is
// glTF 2.0's (§3.9.3, material.normalTexture): n_t = normalize((2·rgb − 1) ⊗ (s, s, 1)),
// s the strength (glTF's normalTexture.scale), with y negated first where green is
// "down" (DirectX's convention; OpenGL's and glTF's is +y up the picture).
struct NormalMap {
  Value value;  // its texture (channel "rgb", colour space "linear"); factor 1
  bool green_down = false;
  double strength = 1;
  const TextureRef& texture() const { return *value.texture; }
};

// The "normal_map" object at `path` (problems to `sink`, the image decoded here).
std::optional<NormalMap> parse_normal_map(const nlohmann::json& j, const std::string& path, DiagnosticSink& sink);
nlohmann::json normal_map_json(const NormalMap& m);
nlohmann::json normal_map_schema();
// The same object as a material's "coat_normal_map": the clear coat's own (glTF's
// clearcoatNormalTexture), on normal_map's tangent frame.
nlohmann::json coat_normal_map_schema();
// The raw filtered rgb of the map at (u, v) (the set it names, before its transform):
// what every target samples; `fragile` as texture_value's.
std::array<double, 3> normal_map_rgb(const NormalMap& m, double u, double v, bool* fragile = nullptr);
// n_t from that rgb: strength, green and normalisation applied (unit, or 0 for a zero vector).
std::array<double, 3> normal_map_tangent_normal(const NormalMap& m, const std::array<double, 3>& rgb);

}  // namespace facet
