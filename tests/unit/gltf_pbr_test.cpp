// gltf_pbr against the glTF specification's own text, written here a second time from it:
//  * glTF 2.0 Specification, Appendix B "BRDF Implementation" (KhronosGroup/glTF,
//    specification/2.0/Specification.adoc): "Specular BRDF" (D, the height-correlated G,
//    MicrofacetBRDF = G D / (4 |N·L| |N·V|)), "Diffuse BRDF", "Fresnel" (conductor_fresnel,
//    fresnel_mix), "Metal BRDF and Dielectric BRDF" (the full code), "General"
//    (material = mix(dielectric_brdf, metal_brdf, metallic)).
//  * KHR_materials_specular README, "Implementation" (dielectric_f0, dielectric_f90 and
//    dielectric_brdf = F specular_brdf + (1 − max_value(F)) diffuse_brdf) and "Interaction
//    with other extensions" (the 0.04 replaced by the IOR's f0).
//  * KHR_materials_ior README: f0 = ((ior − outside_ior)/(ior + outside_ior))², outside_ior = 1.
//  * KHR_materials_clearcoat README, "Clearcoat" and "Implementation": clearcoat_brdf =
//    specular_brdf(α = clearcoatRoughness²), coated_material = mix(material, clearcoat_brdf,
//    clearcoat · (0.04 + (1 − 0.04)(1 − |V·Nc|)^5)), Nc the surface's normal here.
// Here G is written as the specification prints it (not as facet's visibility V), with the
// explicit vectors and χ⁺; the BRDF is f, and facet's ρ is π f (n·l) (MODELS.md, "Conventions").
// Direction sets reach n·l and n·v of 1e-3.
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "reference/interpreter.h"

namespace facet {
namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;
constexpr double kRelTol = 1e-6;

struct Params {
  RGB base{1, 1, 1};
  double metallic = 1, roughness = 1, ior = 1.5, specular = 1;
  RGB specular_color{1, 1, 1};
  double clearcoat = 0, clearcoat_roughness = 0;
};

double chi(double x) { return x > 0 ? 1.0 : 0.0; }
double max_value(const RGB& c) { return std::max({c[0], c[1], c[2]}); }

// Appendix B, "Specular BRDF": specular_brdf(α) = G D / (4 |N·L| |N·V|) with α = roughness²,
// clamped to a small positive value (its note: "α should be clamped to a small positive
// value"); facet's floor is 1e-3.
double specular_brdf_of(double roughness, const Vec3& N, const Vec3& L, const Vec3& V) {
  const Vec3 H = normalize(L + V);
  const double a = std::max(roughness * roughness, 1e-3), a2 = a * a;
  const double NdotL = dot(N, L), NdotV = dot(N, V), NdotH = dot(N, H), VdotH = dot(V, H), HdotL = dot(H, L);
  const double D = a2 * chi(NdotH) / (kPi * std::pow(NdotH * NdotH * (a2 - 1) + 1, 2));
  const double G = 2 * std::fabs(NdotL) * std::fabs(NdotV) * chi(HdotL) * chi(VdotH) /
                   (std::fabs(NdotV) * std::sqrt(a2 + (1 - a2) * NdotL * NdotL) +
                    std::fabs(NdotL) * std::sqrt(a2 + (1 - a2) * NdotV * NdotV));
  return G * D / (4 * std::fabs(NdotL) * std::fabs(NdotV));
}

// The specification's BRDF f(l, v), every line from the texts cited above.
RGB gltf_brdf(const Params& p, const Vec3& N, const Vec3& L, const Vec3& V) {
  const Vec3 H = normalize(L + V);
  const double specular_brdf = specular_brdf_of(p.roughness, N, L, V);
  const double fresnel_w = std::pow(1 - std::fabs(dot(V, H)), 5);
  // KHR_materials_ior: f0 from the IOR, outside_ior = 1.
  const double f0_ior = std::pow((p.ior - 1) / (p.ior + 1), 2);
  RGB f;
  RGB F;
  for (int c = 0; c < 3; ++c) {
    // KHR_materials_specular: dielectric_f0 = min(f0_ior · specularColor, 1) · specular, f90 = specular.
    const double dielectric_f0 = std::min(f0_ior * p.specular_color[c], 1.0) * p.specular;
    F[c] = dielectric_f0 + (p.specular - dielectric_f0) * fresnel_w;  // mix(f0, f90, fresnel_w)
  }
  for (int c = 0; c < 3; ++c) {
    const double diffuse_brdf = (1 / kPi) * p.base[c];
    const double dielectric_brdf = F[c] * specular_brdf + (1 - max_value(F)) * diffuse_brdf;
    const double metal_fresnel = p.base[c] + (1 - p.base[c]) * fresnel_w;
    const double metal_brdf = metal_fresnel * specular_brdf;
    f[c] = (1 - p.metallic) * dielectric_brdf + p.metallic * metal_brdf;  // mix(dielectric, metal, metallic)
  }
  // KHR_materials_clearcoat: fresnel_coat(normal = Nc, ior = 1.5, weight = clearcoat, base = material,
  // layer = clearcoat_brdf) = mix(base, layer, weight · fr), fr = f0 + (1 − f0)(1 − |V·Nc|)^5.
  if (p.clearcoat > 0) {
    const double f0 = std::pow((1 - 1.5) / (1 + 1.5), 2);  // 0.04
    const double fr = f0 + (1 - f0) * std::pow(1 - std::fabs(dot(V, N)), 5);
    const double clearcoat_brdf = specular_brdf_of(p.clearcoat_roughness, N, L, V);
    for (int c = 0; c < 3; ++c) f[c] = f[c] * (1 - p.clearcoat * fr) + clearcoat_brdf * p.clearcoat * fr;
  }
  return f;
}

json material_json(const Params& p) {
  return {{"specular",
           {{"model", "gltf_pbr"},
            {"base_color", {p.base[0], p.base[1], p.base[2]}},
            {"metallic", p.metallic},
            {"roughness", p.roughness},
            {"ior", p.ior},
            {"specular", p.specular},
            {"specular_color", {p.specular_color[0], p.specular_color[1], p.specular_color[2]}},
            {"clearcoat", p.clearcoat},
            {"clearcoat_roughness", p.clearcoat_roughness}}}};
}

// A direction at cosine `c` from `n` (a unit vector), at azimuth `phi` about it.
Vec3 at_cosine(const Vec3& n, double c, double phi) {
  const Vec3 a = std::fabs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 t = normalize(cross(n, a)), b = cross(n, t);
  const double s = std::sqrt(std::max(0.0, 1 - c * c));
  return normalize(n * c + t * (s * std::cos(phi)) + b * (s * std::sin(phi)));
}

struct Directions {
  Vec3 n, l, v;
};

// n random; n·l and n·v log-uniform in [1e-3, 1], every 7th of them exactly 1e-3 (grazing).
std::vector<Directions> direction_sets(uint64_t seed, int count) {
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

// facet's reference ρ against π f (n·l) of the specification, worst relative error.
double worst_error(const Params& p, const std::function<RGB(const Params&, const Vec3&, const Vec3&, const Vec3&)>& f,
                   uint64_t seed = 7) {
  Material m = parse_material(material_json(p), "test:gltf_pbr");
  Reference ref(m);
  double worst = 0;
  for (const auto& d : direction_sets(seed, 3000)) {
    const RGB got = ref.reflectance(d.n, d.l, d.v);
    const RGB want = f(p, d.n, d.l, d.v);
    for (int c = 0; c < 3; ++c) {
      const double rho = kPi * want[c] * dot(d.n, d.l);
      worst = std::max(worst, std::fabs(got[c] - rho) / std::max(std::fabs(rho), 1e-300));
    }
  }
  return worst;
}

std::string describe(const Params& p) {
  return material_json(p).dump();
}

TEST(GltfPbr, AppendixBMetallicRoughness) {
  for (double metallic : {0.0, 0.3, 1.0})
    for (double roughness : {0.0, 0.02, 0.25, 0.6, 1.0}) {
      Params p;
      p.base = {0.9, 0.45, 0.1};
      p.metallic = metallic;
      p.roughness = roughness;
      EXPECT_LE(worst_error(p, gltf_brdf), kRelTol) << describe(p);
    }
}

TEST(GltfPbr, KhrMaterialsIor) {
  for (double ior : {1.0, 1.33, 1.5, 2.4, 0.0}) {
    Params p;
    p.base = {0.2, 0.5, 0.8};
    p.metallic = 0;
    p.roughness = 0.3;
    p.ior = ior;
    EXPECT_LE(worst_error(p, gltf_brdf), kRelTol) << describe(p);
  }
}

TEST(GltfPbr, KhrMaterialsSpecular) {
  // Coloured f0, one channel past the clamp (min(0.04 · 30, 1) = 1), and f90 below 1.
  for (double specular : {0.0, 0.4, 1.0})
    for (RGB tint : {RGB{1, 1, 1}, RGB{1.5, 0.5, 0.2}, RGB{30, 2, 0}}) {
      Params p;
      p.base = {0.7, 0.7, 0.7};
      p.metallic = 0.2;
      p.roughness = 0.4;
      p.ior = 1.6;
      p.specular = specular;
      p.specular_color = tint;
      EXPECT_LE(worst_error(p, gltf_brdf), kRelTol) << describe(p);
    }
}

// A near miss of the coat: its Fresnel of v·h (as the core's), where the README takes |n·v|.
RGB coat_fresnel_of_vh(const Params& p, const Vec3& N, const Vec3& L, const Vec3& V) {
  Params core = p;
  core.clearcoat = 0;
  RGB f = gltf_brdf(core, N, L, V);
  const double fr = 0.04 + 0.96 * std::pow(1 - std::fabs(dot(V, normalize(L + V))), 5);
  const double clearcoat_brdf = specular_brdf_of(p.clearcoat_roughness, N, L, V);
  for (int c = 0; c < 3; ++c) f[c] = f[c] * (1 - p.clearcoat * fr) + clearcoat_brdf * p.clearcoat * fr;
  return f;
}

TEST(GltfPbr, KhrMaterialsClearcoat) {
  // Over a dielectric, a metal and a half metal; a smooth coat (its roughness 0 floored like the
  // core's), a rough one, and the README's varnish (clearcoatFactor 1).
  for (double clearcoat : {0.3, 1.0})
    for (double coat_roughness : {0.0, 0.1, 0.7})
      for (double metallic : {0.0, 0.5, 1.0}) {
        Params p;
        p.base = {0.8, 0.3, 0.1};
        p.metallic = metallic;
        p.roughness = 0.5;
        p.clearcoat = clearcoat;
        p.clearcoat_roughness = coat_roughness;
        EXPECT_LE(worst_error(p, gltf_brdf), kRelTol) << describe(p);
      }
  Params varnish;
  varnish.base = {0.8, 0.3, 0.1};
  varnish.metallic = 0;
  varnish.roughness = 0.5;
  varnish.clearcoat = 1;
  varnish.clearcoat_roughness = 0.1;
  EXPECT_GT(worst_error(varnish, coat_fresnel_of_vh), 1e-2) << "the coat's Fresnel of v·h must fail";
}

// What a near miss looks like: the BRDF facet had before (separable Smith G, a Lambert not
// weighted by 1 − F) is told apart from the specification's at the test's tolerance.
RGB separable_g(const Params& p, const Vec3& N, const Vec3& L, const Vec3& V) {
  RGB f = gltf_brdf(p, N, L, V);
  const double a = std::max(p.roughness * p.roughness, 1e-3), a2 = a * a;
  auto g1 = [&](double x) { return 2 * x / (x + std::sqrt(a2 + (1 - a2) * x * x)); };
  auto correlated = [&](double nl, double nv) {
    return 2 * nl * nv / (nv * std::sqrt(a2 + (1 - a2) * nl * nl) + nl * std::sqrt(a2 + (1 - a2) * nv * nv));
  };
  // Scale the specular part alone: with metallic 1 and white base colour f is all specular.
  const double ratio = g1(dot(N, L)) * g1(dot(N, V)) / correlated(dot(N, L), dot(N, V));
  for (auto& x : f) x *= ratio;
  return f;
}

RGB unweighted_lambert(const Params& p, const Vec3& N, const Vec3& L, const Vec3& V) {
  Params specular_only = p;
  specular_only.base = {0, 0, 0};
  RGB f = gltf_brdf(specular_only, N, L, V);  // dielectric: F specular_brdf
  for (int c = 0; c < 3; ++c) f[c] += p.base[c] / kPi;
  return f;
}

TEST(GltfPbr, TheSeparableGAndAnUnweightedLambertAreToldApart) {
  Params metal;
  metal.base = {1, 1, 1};
  metal.metallic = 1;
  metal.roughness = 0.5;
  EXPECT_LE(worst_error(metal, gltf_brdf), kRelTol);
  EXPECT_GT(worst_error(metal, separable_g), 1e-2) << "the separable G must fail";
  Params plastic;
  plastic.base = {0.8, 0.1, 0.1};
  plastic.metallic = 0;
  plastic.roughness = 0.5;
  EXPECT_LE(worst_error(plastic, gltf_brdf), kRelTol);
  EXPECT_GT(worst_error(plastic, unweighted_lambert), 1e-2) << "the Lambert not weighted by 1 − F must fail";
}

// The catalog's geometry "smith_ggx_correlated" on the ggx lobe is Appendix B's specular_brdf
// times Schlick's Fresnel: the same V as gltf_pbr.
TEST(GltfPbr, GgxWithTheCorrelatedGeometryIsTheSpecificationsSpecularBrdf) {
  Material m = parse_material(
      json{{"specular", {{"model", "ggx"}, {"alpha", 0.25}, {"geometry", "smith_ggx_correlated"}}}}, "test:ggx");
  Reference ref(m);
  Params p;
  p.base = {0.04, 0.04, 0.04};  // a metal of f0 = 0.04 is Schlick's F of the ggx default
  p.metallic = 1;
  p.roughness = 0.5;  // α = 0.25
  double worst = 0;
  for (const auto& d : direction_sets(11, 2000)) {
    const RGB got = ref.reflectance(d.n, d.l, d.v);
    const double want = kPi * gltf_brdf(p, d.n, d.l, d.v)[0] * dot(d.n, d.l);
    worst = std::max(worst, std::fabs(got[0] - want) / std::max(want, 1e-300));
  }
  EXPECT_LE(worst, kRelTol);
}

}  // namespace
}  // namespace facet
