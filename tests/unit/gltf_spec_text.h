// The glTF texts' formulas that more than one test writes from: Appendix B's specular_brdf, the
// KHR_materials_sheen README's sheen BRDF, and the direction sets the tests evaluate at
// (tests/unit/gltf_pbr_test.cpp cites each text; tests/unit/layers_test.cpp reads the same ones).
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "catalog/material.h"
#include "core/vec.h"

namespace facet::spec_text {

inline double chi(double x) { return x > 0 ? 1.0 : 0.0; }
inline double max_value(const RGB& c) { return std::max({c[0], c[1], c[2]}); }

// Appendix B, "Specular BRDF": specular_brdf(α) = G D / (4 |N·L| |N·V|) with α = roughness²,
// clamped to a small positive value (its note: "α should be clamped to a small positive
// value"); facet's floor is 1e-3.
inline double specular_brdf_of(double roughness, const Vec3& N, const Vec3& L, const Vec3& V) {
  const Vec3 H = normalize(L + V);
  const double a = std::max(roughness * roughness, 1e-3), a2 = a * a;
  const double NdotL = dot(N, L), NdotV = dot(N, V), NdotH = dot(N, H), VdotH = dot(V, H), HdotL = dot(H, L);
  const double D = a2 * chi(NdotH) / (kPi * std::pow(NdotH * NdotH * (a2 - 1) + 1, 2));
  const double G = 2 * std::fabs(NdotL) * std::fabs(NdotV) * chi(HdotL) * chi(VdotH) /
                   (std::fabs(NdotV) * std::sqrt(a2 + (1 - a2) * NdotL * NdotL) +
                    std::fabs(NdotL) * std::sqrt(a2 + (1 - a2) * NdotV * NdotV));
  return G * D / (4 * std::fabs(NdotL) * std::fabs(NdotV));
}

// KHR_materials_sheen, "Sheen distribution" and "Sheen visibility", as the README's GLSL.
inline double sheen_l(double x, double alpha_g) {
  const double one_minus_alpha_sq = (1.0 - alpha_g) * (1.0 - alpha_g);
  auto mix = [&](double a, double b) { return a + (b - a) * one_minus_alpha_sq; };
  const double a = mix(21.5473, 25.3245), b = mix(3.82987, 3.32435), c = mix(0.19823, 0.16801),
               d = mix(-1.97760, -1.27393), e = mix(-4.32054, -4.85967);
  return a / (1.0 + b * std::pow(x, c)) + d * x + e;
}

inline double lambda_sheen(double cos_theta, double alpha_g) {
  return std::fabs(cos_theta) < 0.5 ? std::exp(sheen_l(std::fabs(cos_theta), alpha_g))
                                    : std::exp(2.0 * sheen_l(0.5, alpha_g) - sheen_l(1.0 - std::fabs(cos_theta), alpha_g));
}

// sheen_brdf = ν_s D_s, α_g = sheenRoughness² floored as the GGX α is (at 1e-3).
inline double sheen_brdf(double sheen_roughness, const Vec3& N, const Vec3& L, const Vec3& V) {
  const Vec3 H = normalize(L + V);
  const double alpha_g = std::max(sheen_roughness * sheen_roughness, 1e-3);
  const double inv_r = 1 / alpha_g, NdotH = dot(N, H), NdotV = dot(N, V), NdotL = dot(N, L);
  const double cos2h = NdotH * NdotH, sin2h = 1 - cos2h;
  const double sheen_distribution = (2 + inv_r) * std::pow(sin2h, inv_r * 0.5) / (2 * kPi);
  const double sheen_visibility =
      1.0 / ((1.0 + lambda_sheen(NdotV, alpha_g) + lambda_sheen(NdotL, alpha_g)) * (4.0 * NdotV * NdotL));
  return sheen_visibility * sheen_distribution;
}

// A direction at cosine `c` from `n` (a unit vector), at azimuth `phi` about it.
inline Vec3 at_cosine(const Vec3& n, double c, double phi) {
  const Vec3 a = std::fabs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 t = normalize(cross(n, a)), b = cross(n, t);
  const double s = std::sqrt(std::max(0.0, 1 - c * c));
  return normalize(n * c + t * (s * std::cos(phi)) + b * (s * std::sin(phi)));
}

struct Directions {
  Vec3 n, l, v;
};

// n random; n·l and n·v log-uniform in [1e-3, 1], every 7th of them exactly 1e-3 (grazing).
inline std::vector<Directions> direction_sets(uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Directions> out;
  for (int i = 0; i < count; ++i) {
    Directions d;
    d.n = normalize(Vec3(g(rng), g(rng), g(rng)));
    const double cl = i % 7 == 0 ? 1e-3 : std::pow(10.0, -3 * u(rng));
    const double cv = i % 7 == 3 ? 1e-3 : std::pow(10.0, -3 * u(rng));
    d.l = at_cosine(d.n, cl, 2 * kPi * u(rng));
    d.v = at_cosine(d.n, cv, 2 * kPi * u(rng));
    out.push_back(d);
  }
  return out;
}

}  // namespace facet::spec_text
