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
//    clearcoat · (0.04 + (1 − 0.04)(1 − |V·Nc|)^5)), Nc the surface's normal, or a normal of the
//    coat's own ("`normal` is a float3 vector that affects the top layer, but not the base"), the
//    coat's cosine then Nc·L and the coat 0 below Nc's horizon, as the Khronos glTF Sample
//    Viewer's getPunctualRadianceClearCoat has it (punctual.glsl).
//  * KHR_materials_sheen README, "Sheen" and "Implementation Notes": the "Charlie" sheen
//    distribution and visibility (α_g = sheenRoughness²), SheenBRDF = ν_s D_s, and the albedo
//    scaling sheen_material = sheenColor sheen_brdf + material min(1 − max3(sheenColor) E(V·N),
//    1 − max3(sheenColor) E(L·N)), the clear coat layered on top of the sheen. E is facet's fit
//    (sheen_albedo), checked here against the integral of E's definition at its stated error.
//  * KHR_materials_anisotropy README, "Anisotropy" (α_t = mix(α, 1, strength²), α_b = α, Burley's
//    D) and "Implementation" (the rotated direction in the TBN frame, V_GGX_anisotropic).
// Here G is written as the specification prints it (not as facet's visibility V), with the
// explicit vectors and χ⁺; the BRDF is f, and facet's ρ is π f (n·l) (MODELS.md, "Conventions").
// Direction sets reach n·l and n·v of 1e-3.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

#include "catalog/catalog.h"
#include "catalog/material.h"
#include "reference/interpreter.h"
#include "gltf_spec_text.h"

namespace facet {
namespace {

using nlohmann::json;
using namespace spec_text;
constexpr double kRelTol = 1e-6;

struct Params {
  RGB base{1, 1, 1};
  double metallic = 1, roughness = 1, ior = 1.5, specular = 1;
  RGB specular_color{1, 1, 1};
  double clearcoat = 0, clearcoat_roughness = 0;
  RGB sheen_color{0, 0, 0};
  double sheen_roughness = 0;
  double anisotropy_strength = 0, anisotropy_rotation = 0;
  // The direction before the rotation (anisotropyTexture's 2·rg − 1; (1, 0) without one) and the
  // tangent frame's handedness w (glTF's TANGENT.w: B = w·(N × T)).
  double direction_x = 1, direction_y = 0, w = 1;
};

// The tangent both sides are given at a normal N: any unit vector across N, by the test's own rule.
Vec3 tangent_of(const Vec3& N) { return normalize(cross(N, Vec3(0.3, 0.5, 0.8))); }

// KHR_materials_anisotropy, "Anisotropy" and "Implementation": the direction
// mat2(cos r, sin r, −sin r, cos r) · normalize(direction) (the texture's, else (1, 0): then
// (cos r, sin r), u_AnisotropyRotation itself) in the TBN frame (B = w·(N × T), the tangent's
// w), α_t = mix(α, 1, strength²) along it, α_b = α across it (B' = N × T'); D_GGX_anisotropic and
// V_GGX_anisotropic as the README writes them, without the sample's clamp of V at 1 (Appendix
// B's isotropic V has none; facet follows it).
double anisotropic_specular_brdf(const Params& p, const Vec3& N, const Vec3& L, const Vec3& V) {
  const Vec3 H = normalize(L + V), T = tangent_of(N), B = cross(N, T) * p.w;
  const double length = std::hypot(p.direction_x, p.direction_y);
  const double x = p.direction_x / length, y = p.direction_y / length;
  const double c = std::cos(p.anisotropy_rotation), s_r = std::sin(p.anisotropy_rotation);
  // GLSL's mat2(a, b, c, d) is column-major: the columns (a, b) and (c, d).
  const double direction[2] = {c * x - s_r * y, s_r * x + c * y};
  const Vec3 anisotropicT = normalize(T * direction[0] + B * direction[1]);
  const Vec3 anisotropicB = normalize(cross(N, anisotropicT));
  const double alphaRoughness = std::max(p.roughness * p.roughness, 1e-3);
  const double s = p.anisotropy_strength;
  const double at = alphaRoughness * (1 - s * s) + 1.0 * s * s, ab = alphaRoughness;
  const double NdotL = dot(N, L), NdotV = dot(N, V), NdotH = dot(N, H);
  const double TdotH = dot(anisotropicT, H), BdotH = dot(anisotropicB, H);
  const double a2 = at * ab;
  const Vec3 f(ab * TdotH, at * BdotH, a2 * NdotH);
  const double w2 = a2 / dot(f, f);
  const double D = a2 * w2 * w2 / kPi;
  const double GGXV = NdotL * std::sqrt(std::pow(at * dot(anisotropicT, V), 2) + std::pow(ab * dot(anisotropicB, V), 2) +
                                        NdotV * NdotV);
  const double GGXL = NdotV * std::sqrt(std::pow(at * dot(anisotropicT, L), 2) + std::pow(ab * dot(anisotropicB, L), 2) +
                                        NdotL * NdotL);
  return 0.5 / (GGXV + GGXL) * D;
}

// The specification's BRDF f(l, v), every line from the texts cited above.
RGB gltf_brdf(const Params& p, const Vec3& N, const Vec3& L, const Vec3& V) {
  const Vec3 H = normalize(L + V);
  const double specular_brdf = p.anisotropy_strength > 0 ? anisotropic_specular_brdf(p, N, L, V)
                                                         : specular_brdf_of(p.roughness, N, L, V);
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
  // KHR_materials_sheen: "If sheenColorFactor is zero, the whole sheen layer is disabled."
  if (max_value(p.sheen_color) > 0) {
    const double sheen = sheen_brdf(p.sheen_roughness, N, L, V);
    const double c = max_value(p.sheen_color);
    const double scaling = std::min(1 - c * sheen_albedo(dot(V, N), p.sheen_roughness),
                                    1 - c * sheen_albedo(dot(L, N), p.sheen_roughness));
    for (int k = 0; k < 3; ++k) f[k] = p.sheen_color[k] * sheen + f[k] * scaling;
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
            {"clearcoat_roughness", p.clearcoat_roughness},
            {"sheen_color", {p.sheen_color[0], p.sheen_color[1], p.sheen_color[2]}},
            {"sheen_roughness", p.sheen_roughness},
            {"anisotropy_strength", p.anisotropy_strength},
            {"anisotropy_rotation", p.anisotropy_rotation},
            // stored as anisotropyTexture stores them: (d + 1)/2
            {"anisotropy_direction_x", (p.direction_x + 1) / 2},
            {"anisotropy_direction_y", (p.direction_y + 1) / 2}}}};
}

// facet's reference ρ against π f (n·l) of the specification, worst relative error.
double worst_error(const Params& p, const std::function<RGB(const Params&, const Vec3&, const Vec3&, const Vec3&)>& f,
                   uint64_t seed = 7) {
  Material m = parse_material(material_json(p), "test:gltf_pbr");
  Reference ref(m);
  double worst = 0;
  for (const auto& d : direction_sets(seed, 3000)) {
    const RGB got = ref.reflectance(d.n, d.l, d.v, tangent_of(d.n));
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

// specularColorTexture, sheenColorTexture and sheenRoughnessTexture (KHR_materials_specular,
// KHR_materials_sheen: the factor times the texture's rgb, sRGB; sheenRoughnessFactor times the
// texture's alpha): max₃ of the sampled colour enters max₃(F) and the sheen's albedo scaling, the
// sampled roughness the sheen's D, V and E (E's fit summed at the pixel, catalog/specular.cpp
// sheen_per_pixel). At random texture coordinates the reference samples all three (and derives
// the colours' max₃: TexturedInput::max_of); the specification's BRDF of those values, with E
// folded for the sampled roughness (sheen_albedo), is its reflectance.
TEST(GltfPbr, SpecularAndSheenTextures) {
  Params p;
  p.base = {0.25, 0.3, 0.6};
  p.metallic = 0.3;
  p.roughness = 0.45;
  p.ior = 1.6;
  p.specular = 0.8;
  p.sheen_roughness = 0.5;
  p.sheen_color = {0.5, 0.9, 0.7};
  json doc = material_json(p);
  doc["specular"]["specular_color"] = {{"texture", "checker.png"}, {"colorspace", "srgb"}, {"factor", {1.6, 1.2, 0.8}}};
  doc["specular"]["sheen_color"] = {{"texture", "metal_roughness.png"}, {"colorspace", "srgb"}, {"factor", {0.5, 0.9, 0.7}}};
  doc["specular"]["sheen_roughness"] = {{"texture", "leaf.png"}, {"channel", "a"}, {"factor", 0.9}};
  const std::filesystem::path textures = std::filesystem::path(FACET_SOURCE_DIR) / "examples/textured/textures";
  Material m = parse_material(doc, (textures / "tinted.json").string(), textures.string());
  Reference ref(m);
  auto index_of = [&](const std::string& name) {
    const auto& t = ref.program().textured;
    const auto it = std::find_if(t.begin(), t.end(), [&](const TexturedInput& x) { return x.name == name; });
    EXPECT_NE(it, t.end()) << name;
    return size_t(it - t.begin());
  };
  const size_t tint = index_of("specular_specular_color"), sheen = index_of("specular_sheen_color"),
               sheen_roughness = index_of("specular_sheen_roughness");
  index_of("specular_specular_color_max");
  index_of("specular_sheen_color_max");
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0;
  std::set<double> tint_maxima;
  std::array<int, 3> r_pieces{};  // sampled roughnesses in each piece of E's fit: [floor, 0.1), [0.1, 0.3), [0.3, 1]
  for (const auto& d : direction_sets(29, 3000)) {
    ShadingInputs in = shading_inputs(d.n, d.l, d.v, tangent_of(d.n));
    const std::array<double, 2> st = {u(rng), u(rng)};
    ref.sample_textures({st, st}, in);
    Params q = p;
    q.specular_color = in.textured[tint];
    q.sheen_color = in.textured[sheen];
    q.sheen_roughness = in.textured[sheen_roughness][0];
    tint_maxima.insert(max_value(q.specular_color));
    ++r_pieces[q.sheen_roughness < 0.1 ? 0 : q.sheen_roughness < 0.3 ? 1 : 2];
    const RGB got = ref.reflectance(in);
    const RGB want = gltf_brdf(q, d.n, d.l, d.v);
    for (int c = 0; c < 3; ++c) {
      const double rho = kPi * want[c] * dot(d.n, d.l);
      worst = std::max(worst, std::fabs(got[c] - rho) / rho);
    }
  }
  EXPECT_LE(worst, kRelTol);
  EXPECT_GT(tint_maxima.size(), 100u) << "the texture's colours must vary";
  for (int n : r_pieces) EXPECT_GT(n, 100) << "the sheen roughness must reach every piece of E's fit";
  std::printf("specular and sheen colours and sheen roughness from images: worst relative error %.2e\n", worst);
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

// KHR_materials_clearcoat README, "Clearcoat": the coat on a normal Nc of its own ("`normal` is a
// float3 vector that affects the top layer, but not the base"): with a normal map the base shades
// with the mapped N while the coat keeps Nc ("no normal mapping is applied to the clear coat
// layer, even if normal mapping is applied to the base material"). ρ = π [f_base (1 − c fr) (N·L)
// + c fr clearcoat_brdf(Nc) (Nc·L)], fr of |V·Nc|, the coat 0 where Nc·L or Nc·V is not above 0
// (getPunctualRadianceClearCoat's clampedDot). facet's reference given N and Nc apart
// (shading_inputs' c), at direction sets down to Nc·L, Nc·V = 1e-3, and where Nc·L < 0 < N·L.
TEST(GltfPbr, KhrMaterialsClearcoatOnItsOwnNormal) {
  Params p;
  p.base = {0.8, 0.3, 0.1};
  p.metallic = 0.3;
  p.roughness = 0.5;
  p.clearcoat = 0.8;
  p.clearcoat_roughness = 0.2;
  json doc = material_json(p);
  // A normal map makes the coat's normal the surface's own, apart from the lobes' (its image is
  // not read here: the reference is handed both normals).
  doc["normal_map"] = {{"texture", "normals.png"}};
  const std::filesystem::path textures = std::filesystem::path(FACET_SOURCE_DIR) / "examples/textured/textures";
  Material m = parse_material(doc, (textures / "coat.json").string(), textures.string());
  ASSERT_TRUE(m.coat_normal_differs());
  Reference ref(m);
  ASSERT_TRUE(ref.program().uses_coat_normal());
  Params core = p;
  core.clearcoat = 0;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  double worst = 0;
  int below = 0, checked = 0;
  for (const auto& d : direction_sets(13, 3000)) {  // l, v about Nc = d.n
    const Vec3 Nc = d.n;
    // The base's normal: Nc tipped by up to about 35°, kept where N·L and N·V are above 1e-3.
    const Vec3 N = normalize(Nc + Vec3(g(rng), g(rng), g(rng)) * 0.35);
    if (dot(N, d.l) <= 1e-3 || dot(N, d.v) <= 1e-3) continue;
    const RGB base = gltf_brdf(core, N, d.l, d.v);
    const double fr = 0.04 + (1 - 0.04) * std::pow(1 - std::fabs(dot(d.v, Nc)), 5);
    const double coat = specular_brdf_of(p.clearcoat_roughness, Nc, d.l, d.v) * dot(Nc, d.l);
    const RGB got = ref.reflectance(shading_inputs(N, d.l, d.v, tangent_of(N), Nc));
    for (int c = 0; c < 3; ++c) {
      const double rho = kPi * (base[c] * (1 - p.clearcoat * fr) * dot(N, d.l) + p.clearcoat * fr * coat);
      worst = std::max(worst, std::fabs(got[c] - rho) / rho);
    }
    ++checked;
    // The same l mirrored below Nc's horizon while it stays above N's: the coat gives nothing.
    const Vec3 l_below = d.l - Nc * (2 * dot(d.l, Nc));
    if (dot(N, l_below) > 1e-3) {
      const RGB under = ref.reflectance(shading_inputs(N, l_below, d.v, tangent_of(N), Nc));
      const RGB base_below = gltf_brdf(core, N, l_below, d.v);
      for (int c = 0; c < 3; ++c) {
        const double rho = kPi * base_below[c] * (1 - p.clearcoat * fr) * dot(N, l_below);
        worst = std::max(worst, std::fabs(under[c] - rho) / rho);
      }
      ++below;
    }
  }
  std::printf("%d direction sets, %d with l below the coat's horizon: worst %.3g\n", checked, below, worst);
  EXPECT_GT(checked, 1000);
  EXPECT_GT(below, 100);
  EXPECT_LE(worst, kRelTol);
  // On one normal (N = Nc) it is the coat of KhrMaterialsClearcoat: the usual BRDF.
  const Directions d = direction_sets(5, 1)[0];
  const RGB one = ref.reflectance(shading_inputs(d.n, d.l, d.v, tangent_of(d.n), d.n));
  const RGB want = gltf_brdf(p, d.n, d.l, d.v);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(one[c], kPi * want[c] * dot(d.n, d.l), kRelTol * one[c]);
}

// KHR_materials_clearcoat README, "Emission": "The clearcoat layer is on top of emission in the
// layering stack": coated_emission = emission (1 − clearcoat · clearcoat_fresnel), the coat's
// Fresnel 0.04 + (1 − 0.04)(1 − |V·Nc|)^5 as in its layering. The emission left undimmed, or
// dimmed by the Fresnel of normal incidence alone, must be told apart.
TEST(GltfPbr, KhrMaterialsClearcoatDimsTheEmission) {
  for (double clearcoat : {0.0, 0.4, 1.0}) {
    Params p;
    p.base = {0.05, 0.05, 0.06};
    p.metallic = 0;
    p.roughness = 0.5;
    p.clearcoat = clearcoat;
    p.clearcoat_roughness = 0.2;
    json j = material_json(p);
    j["emission"] = {0.9, 0.35, 0.08};
    const Reference ref(parse_material(j, "test:emissive_under_coat"));
    EXPECT_EQ(bool(ref.program().emission_weight), clearcoat > 0) << "no weight where nothing lies over the emission";
    double undimmed = 0, normal_only = 0;
    for (double NoV : {1.0, 0.7, 0.3, 0.1, 1e-3}) {
      const RGB got = ref.emitted(ShadingInputs{}, {0, 0, 0}, NoV);
      const double fresnel = 0.04 + (1 - 0.04) * std::pow(1 - NoV, 5);
      for (int c = 0; c < 3; ++c) {
        const double e = j["emission"][c].get<double>();
        const double want = e * (1 - clearcoat * fresnel);
        EXPECT_NEAR(got[c], want, kRelTol * want) << "clearcoat " << clearcoat << ", n·v " << NoV;
        undimmed = std::max(undimmed, std::fabs(got[c] - e) / e);
        normal_only = std::max(normal_only, std::fabs(got[c] - e * (1 - clearcoat * 0.04)) / e);
      }
    }
    if (clearcoat > 0) {
      EXPECT_GT(undimmed, 1e-2) << "the emission left undimmed must fail";
      EXPECT_GT(normal_only, 1e-2) << "the dimming by normal incidence alone must fail";
    }
  }
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

TEST(GltfPbr, KhrMaterialsAnisotropy) {
  // Brushed metals and a dielectric: strengths up to 1 (α_t = 1), rotations either way and past π.
  for (double strength : {0.3, 0.8, 1.0})
    for (double rotation : {0.0, 0.7, -2.0, 4.0})
      for (double metallic : {0.0, 1.0}) {
        Params p;
        p.base = {0.9, 0.7, 0.4};
        p.metallic = metallic;
        p.roughness = 0.4;
        p.anisotropy_strength = strength;
        p.anisotropy_rotation = rotation;
        EXPECT_LE(worst_error(p, gltf_brdf), kRelTol) << describe(p);
      }
  // The rotation turns towards b = n × t (counter-clockwise from t about n): its opposite fails.
  Params brushed;
  brushed.base = {0.9, 0.9, 0.9};
  brushed.metallic = 1;
  brushed.roughness = 0.3;
  brushed.anisotropy_strength = 0.9;
  brushed.anisotropy_rotation = 0.6;
  auto turned_the_other_way = [](const Params& p, const Vec3& N, const Vec3& L, const Vec3& V) {
    Params q = p;
    q.anisotropy_rotation = -p.anisotropy_rotation;
    return gltf_brdf(q, N, L, V);
  };
  EXPECT_GT(worst_error(brushed, turned_the_other_way), 1e-2) << "the rotation's sense must show";
}

// The direction given apart from the rotation (facet's anisotropy_direction_x, _y, stored as
// anisotropyTexture stores them: numbers, or its red and green, which the README maps to
// 2·rg − 1; its blue times anisotropyStrength) on tangent
// frames of either handedness: the README's normalize, mat2 rotation and TBN · (direction, 0)
// with B = w·(N × T). Numbers are folded when the code is generated; the texture's values are
// handed to the reference as its textured inputs, at random texels, with w = +1 and −1.
TEST(GltfPbr, KhrMaterialsAnisotropyDirectionAndHandedness) {
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0, 1}, {-0.6, 0.3}, {0.2, -0.9}})
    for (double rotation : {0.0, 0.7, -2.0}) {
      Params p;
      p.base = {0.9, 0.7, 0.4};
      p.roughness = 0.35;
      p.anisotropy_strength = 0.8;
      p.anisotropy_rotation = rotation;
      p.direction_x = x;
      p.direction_y = y;
      EXPECT_LE(worst_error(p, gltf_brdf), kRelTol) << describe(p);
    }
  Params p;
  p.base = {0.95, 0.9, 0.85};
  p.roughness = 0.3;
  p.anisotropy_rotation = 0.5;
  json doc = material_json(p);
  auto channel = [](const char* c, double factor) {
    return json{{"texture", "anisotropy.png"}, {"channel", c}, {"factor", factor}};
  };
  doc["specular"]["anisotropy_strength"] = channel("b", 0.9);
  doc["specular"]["anisotropy_direction_x"] = channel("r", 1);
  doc["specular"]["anisotropy_direction_y"] = channel("g", 1);
  const std::filesystem::path textures = std::filesystem::path(FACET_SOURCE_DIR) / "examples/textured/textures";
  Material m = parse_material(doc, (textures / "anisotropy.json").string(), textures.string());
  Reference ref(m);
  ASSERT_TRUE(ref.program().uv_tangent());
  ASSERT_EQ(ref.program().textured.size(), 3u);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> texel(0, 1);
  double worst = 0, handedness_ignored = 0;
  for (const auto& d : direction_sets(19, 3000))
    for (double w : {1.0, -1.0}) {
      const double r = texel(rng), g = texel(rng), b = texel(rng);
      Params q = p;
      q.anisotropy_strength = 0.9 * b;
      q.direction_x = 2 * r - 1;
      q.direction_y = 2 * g - 1;
      q.w = w;
      ShadingInputs in = shading_inputs(d.n, d.l, d.v, tangent_of(d.n), d.n, w);
      for (size_t k = 0; k < ref.program().textured.size(); ++k) {
        const std::string& key = ref.program().textured[k].key;
        const double value = key == "specular.anisotropy_strength"      ? q.anisotropy_strength
                             : key == "specular.anisotropy_direction_x" ? r
                                                                        : g;
        in.textured[k] = {value, value, value};
      }
      const RGB got = ref.reflectance(in);
      const RGB want = gltf_brdf(q, d.n, d.l, d.v);
      Params mirrored = q;
      mirrored.w = -w;
      const RGB other = gltf_brdf(mirrored, d.n, d.l, d.v);
      for (int c = 0; c < 3; ++c) {
        const double rho = kPi * want[c] * dot(d.n, d.l);
        worst = std::max(worst, std::fabs(got[c] - rho) / rho);
        handedness_ignored = std::max(handedness_ignored, std::fabs(got[c] - kPi * other[c] * dot(d.n, d.l)) / rho);
      }
    }
  EXPECT_LE(worst, kRelTol);
  EXPECT_GT(handedness_ignored, 1e-2) << "the frame's handedness must show";
  std::printf("anisotropy from the texture on frames of either handedness: worst relative error %.2e\n", worst);
}

TEST(GltfPbr, KhrMaterialsSheen) {
  // Velvet over a dielectric, satin over a metal and a half metal, the README's velvet
  // (sheenColorFactor 0.9, roughness 0 floored), a coloured sheen, and a coat over a sheen.
  for (double sheen_roughness : {0.0, 0.3, 0.5, 0.8, 1.0})
    for (double metallic : {0.0, 0.5, 1.0}) {
      Params p;
      p.base = {0.3, 0.1, 0.6};
      p.metallic = metallic;
      p.roughness = 0.6;
      p.sheen_color = {0.9, 0.9, 0.9};
      p.sheen_roughness = sheen_roughness;
      EXPECT_LE(worst_error(p, gltf_brdf), kRelTol) << describe(p);
      p.sheen_color = {1.0, 0.4, 0.1};
      EXPECT_LE(worst_error(p, gltf_brdf), kRelTol) << describe(p);
      p.clearcoat = 0.7;
      p.clearcoat_roughness = 0.2;
      EXPECT_LE(worst_error(p, gltf_brdf), kRelTol) << describe(p);
    }
}

// E(μ, r) = ∫ ν_s D_s (n·l) dω_l, the README's sheen BRDF's directional albedo, integrated here
// on a midpoint grid in t and φ with n·l = t⁶ (dω = 6 t⁵ dt dφ: Λ's (n·l)^0.2 made smooth) and φ
// in (0, π) (the integrand is even in φ), against facet's fit: within the error the fit states
// (scripts/fit_sheen_albedo.py) plus this grid's own (measured below, < 5e-4).
double albedo_integral(double mu, double sheen_roughness, int n) {
  const Vec3 N(0, 0, 1), V(std::sqrt(1 - mu * mu), 0, mu);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) / n, cos_l = std::pow(t, 6), sin_l = std::sqrt(1 - cos_l * cos_l);
    for (int j = 0; j < 2 * n; ++j) {
      const double phi = (j + 0.5) / (2 * n) * kPi;
      const Vec3 L(sin_l * std::cos(phi), sin_l * std::sin(phi), cos_l);
      sum += sheen_brdf(sheen_roughness, N, L, V) * cos_l * 6 * std::pow(t, 5);
    }
  }
  return 2 * sum * (1.0 / n) * (kPi / (2 * n));
}

TEST(GltfPbr, TheSheenAlbedoFitIsWithinItsStatedErrorOfTheIntegral) {
  double worst = 0, grid = 0;
  // The floor (r = 0: α = 1e-3), off the table's rows and on them, down to n·v = 1e-3.
  for (double r : {0.0, 0.058, 0.15, 0.23, 0.35, 0.5, 0.7, 0.9, 1.0})
    for (double mu : {0.001, 0.02, 0.07, 0.2, 0.45, 0.75, 1.0}) {
      const double e = albedo_integral(mu, r, 200);
      grid = std::max(grid, std::fabs(std::min(e, 1.0) - std::min(albedo_integral(mu, r, 100), 1.0)));
      worst = std::max(worst, std::fabs(sheen_albedo(mu, r) - std::min(e, 1.0)));
    }
  std::printf("sheen albedo fit: worst |E − min(∫, 1)| %.2e here (the fit states %.2e); the grid's own %.1e\n", worst,
              sheen_albedo_worst_error(), grid);
  EXPECT_LT(grid, 5e-4) << "the test's own quadrature";
  EXPECT_LE(worst, sheen_albedo_worst_error() + grid) << "the fit states " << sheen_albedo_worst_error();
  EXPECT_LT(sheen_albedo_worst_error(), 1e-3);
  // What E is for: it is large at grazing angles and small at normal incidence for a smooth sheen.
  EXPECT_GT(sheen_albedo(0.05, 0.3), 0.5);
  EXPECT_LT(sheen_albedo(1.0, 0.3), 0.01);
}

// Sheen without the albedo scaling (the base not dimmed), and with the README's view-only
// shortcut 1 − max3(c) E(V·N), are told apart from the specification's reciprocal scaling.
RGB sheen_unscaled(const Params& p, const Vec3& N, const Vec3& L, const Vec3& V) {
  Params base = p;
  base.sheen_color = {0, 0, 0};
  RGB f = gltf_brdf(base, N, L, V);
  for (int k = 0; k < 3; ++k) f[k] += p.sheen_color[k] * sheen_brdf(p.sheen_roughness, N, L, V);
  return f;
}

RGB sheen_view_only(const Params& p, const Vec3& N, const Vec3& L, const Vec3& V) {
  Params base = p;
  base.sheen_color = {0, 0, 0};
  RGB f = gltf_brdf(base, N, L, V);
  const double scaling = 1 - max_value(p.sheen_color) * sheen_albedo(dot(V, N), p.sheen_roughness);
  for (int k = 0; k < 3; ++k) f[k] = p.sheen_color[k] * sheen_brdf(p.sheen_roughness, N, L, V) + f[k] * scaling;
  return f;
}

TEST(GltfPbr, SheenWithoutItsAlbedoScalingIsToldApart) {
  Params velvet;
  velvet.base = {0.3, 0.1, 0.6};
  velvet.metallic = 0;
  velvet.roughness = 0.6;
  velvet.sheen_color = {0.9, 0.9, 0.9};
  velvet.sheen_roughness = 0.4;
  EXPECT_LE(worst_error(velvet, gltf_brdf), kRelTol);
  EXPECT_GT(worst_error(velvet, sheen_unscaled), 1e-2) << "sheen without albedo scaling must fail";
  EXPECT_GT(worst_error(velvet, sheen_view_only), 1e-2) << "the view-only scaling must fail";
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
