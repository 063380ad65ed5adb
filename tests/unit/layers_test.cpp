// The layers a material file writes over its lobes ("layers": catalog section "layer"), against
// the glTF extension READMEs they come from, written here again from their text:
//  * KHR_materials_clearcoat README, "Clearcoat" and "Implementation": coated_material =
//    mix(material, clearcoat_brdf, clearcoat · fr), clearcoat_brdf = specular_brdf(α =
//    clearcoatRoughness²), fr = 0.04 + (1 − 0.04)(1 − |V·Nc|)^5; "Emission": coated_emission =
//    emission · (1 − clearcoat · fr).
//  * KHR_materials_sheen README, "Sheen" and "Albedo-scaling technique": sheen_material =
//    sheenColor · sheen_brdf + material · min(1 − max3(sheenColor) E(V·N), 1 − max3(sheenColor)
//    E(L·N)), E facet's fit (its error against the integral: GltfPbr.TheSheenAlbedoFit…).
// "material" is here whatever lies under the layer: facet's reference ρ of the same material
// without its layers (MODELS.md's k_d ⊗ ρ_d + k_s ⊗ ρ_s). facet's ρ is π f (n·l).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "catalog/catalog.h"
#include "catalog/material.h"
#include "catalog/program.h"
#include "core/diagnostics.h"
#include "gltf_spec_text.h"
#include "reference/interpreter.h"

namespace facet {
namespace {

using nlohmann::json;
using namespace spec_text;

// The lobes the layers are laid over: diffuse alone, diffuse and a classic specular, a
// microfacet lobe alone, an anisotropic one, and glTF's own BRDF with its own coat.
const std::vector<json> kBases = {
    {{"diffuse", {{"model", "lambert"}, {"color", {0.6, 0.3, 0.2}}}}},
    {{"diffuse", {{"model", "oren_nayar"}, {"color", {0.5, 0.4, 0.3}}, {"sigma", 0.4}}},
     {"specular", {{"model", "phong"}, {"color", {0.3, 0.3, 0.3}}, {"n", 25}}}},
    {{"specular", {{"model", "cook_torrance"}, {"color", {0.9, 0.7, 0.4}}, {"m", 0.3}}}},
    {{"diffuse", {{"model", "lambert"}, {"color", {0.2, 0.2, 0.3}}}},
     {"specular", {{"model", "ward"}, {"color", {0.5, 0.5, 0.5}}, {"alpha_x", 0.1}, {"alpha_y", 0.3}}}},
    {{"specular", {{"model", "gltf_pbr"}, {"base_color", {0.7, 0.2, 0.1}}, {"clearcoat", 0.5},
                   {"clearcoat_roughness", 0.3}}}}};

json with_layers(json base, const json& layers) {
  base["layers"] = layers;
  return base;
}

// Worst relative error of `layered`'s ρ against want(ρ of `base`, directions) over direction sets
// down to n·l, n·v = 1e-3.
double worst_error(const json& layered, const json& base,
                   const std::function<RGB(const RGB& under, const Directions&)>& want) {
  const Reference got(parse_material(layered, "test:layered"));
  const Reference under(parse_material(base, "test:base"));
  double worst = 0;
  for (const auto& d : direction_sets(11, 2000)) {
    const Vec3 t = normalize(cross(d.n, Vec3(0.3, 0.5, 0.8)));
    const RGB g = got.reflectance(d.n, d.l, d.v, t);
    const RGB w = want(under.reflectance(d.n, d.l, d.v, t), d);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(g[c] - w[c]) / std::max(std::fabs(w[c]), 1e-300));
  }
  return worst;
}

// KHR_materials_clearcoat's coated_material over `under` (ρ), as π f (n·l).
RGB coated(const RGB& under, const Directions& d, double weight, double roughness) {
  const double fr = 0.04 + (1 - 0.04) * std::pow(1 - std::fabs(dot(d.v, d.n)), 5);
  const double coat = kPi * specular_brdf_of(roughness, d.n, d.l, d.v) * dot(d.n, d.l);
  RGB out;
  for (int c = 0; c < 3; ++c) out[c] = under[c] * (1 - weight * fr) + coat * weight * fr;
  return out;
}

// KHR_materials_sheen's sheen_material over `under` (ρ), as π f (n·l).
RGB sheened(const RGB& under, const Directions& d, const RGB& color, double roughness) {
  const double s = kPi * sheen_brdf(roughness, d.n, d.l, d.v) * dot(d.n, d.l);
  const double c = max_value(color);
  const double scaling = std::min(1 - c * sheen_albedo(dot(d.v, d.n), roughness), 1 - c * sheen_albedo(dot(d.l, d.n), roughness));
  RGB out;
  for (int k = 0; k < 3; ++k) out[k] = color[k] * s + under[k] * scaling;
  return out;
}

// The messages a material file's layers get name the key and what is allowed.
std::vector<Diagnostic> errors_of(const json& doc) {
  try {
    parse_material(doc, FACET_SOURCE_DIR "/examples/textured/test.json");  // its images in textures/
  } catch (const InputError& e) {
    return e.diagnostics();
  }
  return {};
}

TEST(Layers, AClearCoatOverAnyLobeIsTheReadmesCoatedMaterial) {
  double worst = 0;
  for (const json& base : kBases)
    for (double weight : {0.3, 1.0})
      for (double roughness : {0.0, 0.2, 0.7}) {
        const json layered = with_layers(base, {{{"model", "clearcoat"}, {"weight", weight}, {"roughness", roughness}}});
        const double e = worst_error(layered, base, [&](const RGB& u, const Directions& d) {
          return coated(u, d, weight, roughness);
        });
        EXPECT_LE(e, 1e-9) << layered.dump();
        worst = std::max(worst, e);
      }
  std::printf("a clear coat over %zu bases: worst relative error %.3g\n", kBases.size(), worst);
  // The coat's Fresnel of v·h, not the README's |V·N|, is told apart.
  const json layered = with_layers(kBases[0], {{{"model", "clearcoat"}, {"weight", 1}, {"roughness", 0.2}}});
  EXPECT_GT(worst_error(layered, kBases[0],
                        [&](const RGB& u, const Directions& d) {
                          const double w = std::pow(1 - std::fabs(dot(d.v, normalize(d.l + d.v))), 5);
                          const double fr = 0.04 + 0.96 * w;
                          const double coat = kPi * specular_brdf_of(0.2, d.n, d.l, d.v) * dot(d.n, d.l);
                          RGB out;
                          for (int c = 0; c < 3; ++c) out[c] = u[c] * (1 - fr) + coat * fr;
                          return out;
                        }),
            1e-2);
}

TEST(Layers, ASheenOverAnyLobeIsTheReadmesSheenMaterial) {
  double worst = 0;
  for (const json& base : kBases)
    for (const RGB& color : {RGB{0.9, 0.9, 0.9}, RGB{1.0, 0.4, 0.1}})
      for (double roughness : {0.0, 0.3, 0.8}) {
        const json layered =
            with_layers(base, {{{"model", "sheen"}, {"color", {color[0], color[1], color[2]}}, {"roughness", roughness}}});
        const double e = worst_error(layered, base, [&](const RGB& u, const Directions& d) {
          return sheened(u, d, color, roughness);
        });
        EXPECT_LE(e, 1e-9) << layered.dump();
        worst = std::max(worst, e);
      }
  std::printf("a sheen over %zu bases: worst relative error %.3g\n", kBases.size(), worst);
  // What lies under the sheen scaled by the view's albedo alone (the README's shortcut) is told apart.
  const RGB color{0.9, 0.9, 0.9};
  const json layered = with_layers(kBases[0], {{{"model", "sheen"}, {"color", {0.9, 0.9, 0.9}}, {"roughness", 0.5}}});
  EXPECT_GT(worst_error(layered, kBases[0],
                        [&](const RGB& u, const Directions& d) {
                          const double s = kPi * sheen_brdf(0.5, d.n, d.l, d.v) * dot(d.n, d.l);
                          const double scaling = 1 - 0.9 * sheen_albedo(dot(d.v, d.n), 0.5);
                          RGB out;
                          for (int k = 0; k < 3; ++k) out[k] = color[k] * s + u[k] * scaling;
                          return out;
                        }),
            1e-2);
}

// A mix layer is glTF 2.0 Appendix B's mix(under, k ⊗ ρ_lobe, w) = (1 − w) under + w k ⊗ ρ_lobe, the
// lobe with its own colour, Fresnel and toon as it would be the material's specular lobe alone.
TEST(Layers, AMixIsTheWeightedMeanOfWhatLiesUnderAndItsLobe) {
  const std::vector<json> lobes = {
      {{"model", "ward"}, {"color", {0.9, 0.6, 0.3}}, {"alpha_x", 0.08}, {"alpha_y", 0.3}},
      {{"model", "cook_torrance"}, {"m", 0.25}, {"fresnel", {{"model", "exact"}, {"ior", 2.2}}}},
      {{"model", "phong"}, {"color", 0.7}, {"n", 30}, {"toon", {{"cutoff", 0.3}, {"width", 0.1}}}}};
  double worst = 0;
  for (size_t b = 0; b < 4; ++b)
    for (const json& lobe : lobes)
      for (double w : {0.25, 0.8}) {
        const json layered = with_layers(kBases[b], {{{"model", "mix"}, {"weight", w}, {"lobe", lobe}}});
        const Reference alone(parse_material({{"specular", lobe}}, "test:lobe"));
        const double e = worst_error(layered, kBases[b], [&](const RGB& u, const Directions& d) {
          const RGB l = alone.reflectance(d.n, d.l, d.v, normalize(cross(d.n, Vec3(0.3, 0.5, 0.8))));
          RGB out;
          for (int c = 0; c < 3; ++c) out[c] = (1 - w) * u[c] + w * l[c];
          return out;
        });
        EXPECT_LE(e, 1e-12) << layered.dump();
        worst = std::max(worst, e);
      }
  std::printf("a mix with a lobe over 4 bases: worst relative error %.3g\n", worst);
  // A lobe that asks the material for its coat, emission weight or frame cannot be mixed in.
  const auto d = errors_of(with_layers(kBases[0], {{{"model", "mix"}, {"lobe", {{"model", "gltf_pbr"}}}}}));
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d[0].path, "layers[0].lobe.model");
  EXPECT_NE(d[0].message.find("gltf_pbr cannot be a layer's lobe"), std::string::npos) << d[0].message;
  // A textured parameter of the lobe is named by its key path.
  json textured = with_layers(kBases[0], {{{"model", "mix"},
                                           {"lobe", {{"model", "ward"},
                                                     {"alpha_x", {{"texture", "textures/checker.png"}, {"channel", "r"}}}, {"alpha_y", 0.3}}}}});
  const MaterialProgram p = compile(parse_material(textured, FACET_SOURCE_DIR "/examples/textured/test.json"));
  ASSERT_EQ(p.textured.size(), 1u);
  EXPECT_EQ(p.textured[0].key, "layers[0].lobe.alpha_x");
}

// The list is bottom first: [sheen, clearcoat] is the coat over the sheen (glTF's own order,
// KHR_materials_clearcoat: "the clearcoat layer is on top of … sheen"), and the other order is
// another material.
TEST(Layers, TheFirstLayerIsTheLowest) {
  const json base = kBases[1];
  const json sheen = {{"model", "sheen"}, {"color", {0.8, 0.7, 0.9}}, {"roughness", 0.4}};
  const json coat = {{"model", "clearcoat"}, {"weight", 0.8}, {"roughness", 0.25}};
  auto coat_over_sheen = [&](const RGB& u, const Directions& d) {
    return coated(sheened(u, d, {0.8, 0.7, 0.9}, 0.4), d, 0.8, 0.25);
  };
  EXPECT_LE(worst_error(with_layers(base, {sheen, coat}), base, coat_over_sheen), 1e-9);
  EXPECT_GT(worst_error(with_layers(base, {coat, sheen}), base, coat_over_sheen), 1e-2);
}

// gltf_pbr's own sheen and coat and the layers a file writes are one piece of code: gltf_pbr with
// KHR_materials_sheen and _clearcoat is gltf_pbr without them under [sheen, clearcoat] of the same
// values, to rounding.
TEST(Layers, GltfPbrsOwnSheenAndCoatAreTheseLayers) {
  const json own = {{"specular",
                     {{"model", "gltf_pbr"}, {"base_color", {0.3, 0.5, 0.7}}, {"metallic", 0.3}, {"roughness", 0.45},
                      {"sheen_color", {0.6, 0.9, 0.4}}, {"sheen_roughness", 0.35}, {"clearcoat", 0.9},
                      {"clearcoat_roughness", 0.15}}}};
  json bare = own;
  for (const char* k : {"sheen_color", "sheen_roughness", "clearcoat", "clearcoat_roughness"}) bare["specular"].erase(k);
  const json layered = with_layers(bare, {{{"model", "sheen"}, {"color", {0.6, 0.9, 0.4}}, {"roughness", 0.35}},
                                          {{"model", "clearcoat"}, {"weight", 0.9}, {"roughness", 0.15}}});
  const Reference a(parse_material(own, "test:own")), b(parse_material(layered, "test:layered"));
  double worst = 0;
  for (const auto& d : direction_sets(5, 2000)) {
    const RGB x = a.reflectance(d.n, d.l, d.v), y = b.reflectance(d.n, d.l, d.v);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(x[c] - y[c]) / std::max(std::fabs(x[c]), 1e-300));
  }
  EXPECT_LE(worst, 1e-12);
}

// The same with images: gltf_pbr's sheen colour and roughness and clearcoat from images equal the
// layers' (the layer's inputs named layer0_color, layer0_roughness, layer1_weight), sampled alike.
TEST(Layers, TexturedLayersAreGltfPbrsTexturedParts) {
  const json color = {{"texture", "textures/metal_roughness.png"}, {"colorspace", "srgb"}, {"factor", {0.6, 0.9, 0.7}}};
  const json roughness = {{"texture", "textures/leaf.png"}, {"channel", "a"}, {"factor", 0.8}};
  const json weight = {{"texture", "textures/metal_roughness.png"}, {"channel", "b"}};
  const json own = {{"specular",
                     {{"model", "gltf_pbr"}, {"base_color", {0.3, 0.5, 0.7}}, {"roughness", 0.45}, {"sheen_color", color},
                      {"sheen_roughness", roughness}, {"clearcoat", weight}, {"clearcoat_roughness", 0.3}}}};
  const json layered = {{"specular", {{"model", "gltf_pbr"}, {"base_color", {0.3, 0.5, 0.7}}, {"roughness", 0.45}}},
                        {"layers",
                         {{{"model", "sheen"}, {"color", color}, {"roughness", roughness}},
                          {{"model", "clearcoat"}, {"weight", weight}, {"roughness", 0.3}}}}};
  const std::string file = FACET_SOURCE_DIR "/examples/textured/test.json";  // its images in textures/
  const Reference a(parse_material(own, file)), b(parse_material(layered, file));
  // The textured inputs in each one's order, by what they are.
  auto order = [](const Reference& r) {
    std::vector<std::string> keys;
    for (const auto& t : r.program().textured) keys.push_back(t.key + (t.max_of.empty() ? "" : " max"));
    return keys;
  };
  const std::vector<std::string> ka = order(a), kb = order(b);
  const std::map<std::string, std::string> same = {{"specular.sheen_color", "layers[0].color"},
                                                    {"specular.sheen_color max", "layers[0].color max"},
                                                    {"specular.sheen_roughness", "layers[0].roughness"},
                                                    {"specular.clearcoat", "layers[1].weight"}};
  ASSERT_EQ(ka.size(), same.size());
  ASSERT_EQ(kb.size(), same.size());
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.05, 1.0);
  double worst = 0;
  for (const auto& d : direction_sets(23, 1000)) {
    ShadingInputs in = shading_inputs(d.n, d.l, d.v, normalize(cross(d.n, Vec3(0.3, 0.5, 0.8))));
    std::map<std::string, RGB> texel;  // one sample per meaning, given to both
    for (const auto& [k, v] : same) texel[k] = {u(rng), u(rng), u(rng)};
    const RGB& c = texel["specular.sheen_color"];
    texel["specular.sheen_color max"] = {std::max({c[0], c[1], c[2]}), 0, 0};
    ShadingInputs ia = in, ib = in;
    for (size_t i = 0; i < ka.size(); ++i) ia.textured[i] = texel.at(ka[i]);
    for (size_t i = 0; i < kb.size(); ++i) {
      const auto it = std::find_if(same.begin(), same.end(), [&](const auto& p) { return p.second == kb[i]; });
      ib.textured[i] = texel.at(it->first);
    }
    const RGB x = a.reflectance(ia), y = b.reflectance(ib);
    for (int k = 0; k < 3; ++k) worst = std::max(worst, std::fabs(x[k] - y[k]) / std::max(std::fabs(x[k]), 1e-300));
  }
  EXPECT_LE(worst, 1e-12);
}

// KHR_materials_clearcoat, "Emission": every coat over the emission dims it by its own 1 − w·fr(n·v);
// a sheen does not (its README says nothing of the emission). gltf_pbr's coat and a coat layer over
// it: the product.
TEST(Layers, EveryCoatOverTheEmissionDimsIt) {
  json m = with_layers(kBases[4], {{{"model", "sheen"}, {"color", {1, 1, 1}}, {"roughness", 0.5}},
                                   {{"model", "clearcoat"}, {"weight", 0.7}, {"roughness", 0.2}}});
  m["emission"] = {0.9, 0.35, 0.08};
  const Reference ref(parse_material(m, "test:emissive"));
  for (double NoV : {1.0, 0.6, 0.2, 1e-3}) {
    const double fr = 0.04 + 0.96 * std::pow(1 - NoV, 5);
    const RGB got = ref.emitted(ShadingInputs{}, {0, 0, 0}, NoV);
    for (int c = 0; c < 3; ++c) {
      const double want = m["emission"][c].get<double>() * (1 - 0.5 * fr) * (1 - 0.7 * fr);
      EXPECT_NEAR(got[c], want, 1e-12 * want) << "n·v " << NoV;
    }
  }
  json sheen_only = with_layers(kBases[0], {{{"model", "sheen"}}});
  sheen_only["emission"] = {1, 1, 1};
  EXPECT_FALSE(compile(parse_material(sheen_only, "test:sheen")).emission_weight) << "a sheen does not dim m_e";
}

TEST(Layers, MaterialFilesSayWhatIsWrongWithALayer) {
  auto first = [](const json& doc) {
    const auto d = errors_of(doc);
    return d.empty() ? std::string("(accepted)") : d[0].path + ": " + d[0].message;
  };
  EXPECT_EQ(first(with_layers(kBases[0], {{"model", "clearcoat"}})).substr(0, 8), "layers: ") << "an object, not a list";
  EXPECT_NE(first(with_layers(kBases[0], {{{"model", "clearcoat"}}, {{"model", "lacquer"}}})).find("layers[1].model: unknown layer model \"lacquer\""),
            std::string::npos);
  EXPECT_NE(first(with_layers(kBases[0], {{{"model", "sheen"}, {"roughness", 2}}})).find("layers[0].roughness"),
            std::string::npos);
  EXPECT_NE(first(with_layers(kBases[0], {{{"model", "sheen"}, {"weight", 1}}})).find("layers[0].weight"), std::string::npos)
      << "a clear coat's key on a sheen";
  // A coat normal map needs a coat: a clearcoat layer of weight 0 is none.
  json mapped = with_layers(kBases[0], {{{"model", "clearcoat"}, {"weight", 0}}});
  mapped["coat_normal_map"] = {{"texture", "textures/normals.png"}};
  EXPECT_NE(first(mapped).find("coat_normal_map: the material has no layer with a normal of its own"), std::string::npos);
  mapped["layers"][0]["weight"] = 0.5;
  EXPECT_EQ(first(mapped), "(accepted)");
  // A textured layer parameter is named by its key path.
  json textured = with_layers(kBases[0], {{{"model", "clearcoat"},
                                           {"weight", {{"texture", "textures/checker.png"},
                                                       {"channel", "r"}}}}});
  const MaterialProgram p = compile(parse_material(textured, FACET_SOURCE_DIR "/examples/textured/test.json"));
  ASSERT_EQ(p.textured.size(), 1u);
  EXPECT_EQ(p.textured[0].key, "layers[0].weight");
  EXPECT_EQ(p.textured[0].name, "layer0_weight");
}

// The canonical form keeps the layers, in order: it parses back to the same reflectance.
TEST(Layers, TheCanonicalFormKeepsThem) {
  const json layered = with_layers(kBases[1], {{{"model", "sheen"}, {"color", {0.5, 0.6, 0.7}}},
                                               {{"model", "clearcoat"}, {"roughness", 0.3}}});
  const Material m = parse_material(layered, "test:a");
  const json canonical = to_json(m);
  ASSERT_EQ(canonical["layers"].size(), 2u);
  EXPECT_EQ(canonical["layers"][0]["model"], "sheen");
  EXPECT_EQ(canonical["layers"][1]["weight"], 1.0) << "defaults written out";
  const Reference a(m), b(parse_material(canonical, "test:b"));
  for (const auto& d : direction_sets(3, 200)) EXPECT_EQ(a.reflectance(d.n, d.l, d.v), b.reflectance(d.n, d.l, d.v));
}

}  // namespace
}  // namespace facet
