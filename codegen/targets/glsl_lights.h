// facet — how the generated GLSL's FacetLight (templates/glsl/lights.glsl) encodes
// a light: an application fills facet_lights[] with these numbers (facet's own
// renderers fill a buffer of them, renderers/opengl.cpp), and the template's numbers, its
// comments included, are filled from them. Also where facet's own renderers put the lights
// (targets.h, LightSource::Buffer) and how the G-buffer holds each light's visibility
// (renderers/gbuffer.h): the shading passes of every language decode what the GL ray
// caster encodes by these numbers.
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <string>

#include "scene/scene.h"

namespace facet::glsl_light {

// FacetLight.position.w: the light's type.
inline constexpr int kPoint = 0, kDirectional = 1, kSpot = 2;
// FacetLight.attenuation.w: its attenuation law.
inline constexpr int kNoAttenuation = 0, kInverseSquare = 1, kPolynomial = 2, kInverseSquareRange = 3;

inline int type_code(Light::Type t) {
  switch (t) {
    case Light::Type::Directional: return kDirectional;
    case Light::Type::Spot: return kSpot;
    case Light::Type::Point: break;
  }
  return kPoint;
}

inline int law_code(Attenuation::Law law) {
  switch (law) {
    case Attenuation::Law::InverseSquare: return kInverseSquare;
    case Attenuation::Law::Polynomial: return kPolynomial;
    case Attenuation::Law::InverseSquareRange: return kInverseSquareRange;
    case Attenuation::Law::None: break;
  }
  return kNoAttenuation;
}

// LightSource::Buffer: ES 3.00's light texture holds this many lights a row (4 texels each;
// 1,024 texels, within ES 3.00's least maximum texture size, 2,048); glsl450's storage buffer,
// HLSL's StructuredBuffer and WGSL's storage buffer of lights are descriptor set (bind group)
// kLightSet, binding 0.
inline constexpr int kLightsPerRow = 256, kLightSet = 2;

// The G-buffer's visibility image: light i's bit is bit i mod kVisibilityBits of channel
// (i / kVisibilityBits) mod 4 of layer i / kVisibilityLayerLights; a channel holds an integer
// below 2^24, which float32 holds exactly.
inline constexpr int kVisibilityBits = 24, kVisibilityLayerLights = 4 * kVisibilityBits;

// A light as FacetLight's four vec4, in order: position (xyz: the position, or the
// direction a directional light travels; w: type_code), color (rgb; a: the spot
// exponent), spot (xyz: the cone's axis; w: cos(cutoff)), attenuation (c1, c2, c3, or x the
// range of the windowed inverse square; w: law_code).
inline std::array<float, 16> encode(const Light& l) {
  const Vec3& where = l.type == Light::Type::Directional ? l.direction : l.position;
  const Attenuation& a = l.attenuation;
  const double v[16] = {where.x, where.y, where.z, double(type_code(l.type)),
                        l.color[0], l.color[1], l.color[2], l.exponent,
                        l.direction.x, l.direction.y, l.direction.z, std::cos(l.cutoff * M_PI / 180.0),
                        a.law == Attenuation::Law::InverseSquareRange ? a.range : a.constant, a.linear, a.quadratic,
                        double(law_code(a.law))};
  std::array<float, 16> out;
  for (size_t i = 0; i < 16; ++i) out[i] = float(v[i]);
  return out;
}

// The template's placeholders, {{point}} … {{polynomial}}: each code as an
// integer ("1"; the template's code compares with "{{directional}}.0").
inline std::map<std::string, std::string> template_values() {
  return {{"point", std::to_string(kPoint)},
          {"directional", std::to_string(kDirectional)},
          {"spot", std::to_string(kSpot)},
          {"no_attenuation", std::to_string(kNoAttenuation)},
          {"inverse_square", std::to_string(kInverseSquare)},
          {"polynomial", std::to_string(kPolynomial)},
          {"inverse_square_range", std::to_string(kInverseSquareRange)}};
}

// The visibility image's numbers as the shading passes' and the ray caster's placeholders:
// {{bits}} (kVisibilityBits) and {{layer_lights}} (kVisibilityLayerLights).
inline std::map<std::string, std::string> visibility_values() {
  return {{"bits", std::to_string(kVisibilityBits)}, {"layer_lights", std::to_string(kVisibilityLayerLights)}};
}

}  // namespace facet::glsl_light
