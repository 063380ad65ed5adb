// Specular models (ρ_s) of MODELS.md: the classic lobes, the microfacet
// family, Blinn's Trowbridge–Reitz model and Ward's anisotropic model.
#include <algorithm>
#include <cmath>
#include <functional>

#include "catalog/catalog_internal.h"
#include "catalog/texture.h"
#include "core/vec.h"

namespace facet::catalog_detail {

namespace {

const std::vector<std::string> kGeometries = {"none", "v_cavity", "smith_ggx", "smith_ggx_correlated"};

ParamDef approximation_param() {
  return choice("approximation",
                "\"schlick\" replaces x^n by x / (n − n x + x) (Schlick 1994), which needs no pow()",
                {"none", "schlick"}, "none");
}

ParamDef geometry_param(const std::string& fallback) {
  return choice("geometry",
                "masking-shadowing term G; smith_ggx (separable) and smith_ggx_correlated (height-correlated, "
                "glTF's) use the lobe's roughness as α",
                kGeometries, fallback);
}

// x^n, or Schlick's rational approximation of it when the material asks.
ir::Expr power(LobeContext& c, const ir::FunctionPtr& exact_form, std::vector<ir::Expr> exact_args,
               const ir::Expr& x) {
  if (c.choice("approximation") == "schlick") return ir::call(terms::schlick_power(), {x, c.number("n")});
  return ir::call(exact_form, exact_args);
}

// π D G F / (4 n·v) with the lobe's D, its `geometry` choice and its `fresnel`.
// Smith GGX goes in as the visibility V = G / (4 (n·l)(n·v)), ρ = π D V F (n·l):
// the same product without the factors that cancel.
ir::Expr microfacet(LobeContext& c, const ir::Expr& D, const ir::Expr& alpha) {
  ir::Expr d = c.let("D", D);
  const std::string& geometry = c.choice("geometry");
  if (geometry == "smith_ggx" || geometry == "smith_ggx_correlated") {
    ir::Expr v = c.let("V", ir::call(geometry == "smith_ggx" ? terms::visibility_smith_ggx()
                                                      : terms::visibility_smith_ggx_correlated(),
                                     {c.NoL(), c.NoV(), alpha}));
    ir::Expr f = c.let("F", c.fresnel());
    return ir::call(terms::microfacet_visibility(f.type()), {d, v, f, c.NoL()});
  }
  ir::Expr g = c.let("G", c.geometry());
  ir::Expr f = c.let("F", c.fresnel());
  return ir::call(terms::microfacet(f.type()), {d, g, f, c.NoV()});
}

// KHR_materials_anisotropy, "Anisotropy": the direction of increased roughness is d = (x, y) in
// the tangent frame (t, b) — the mesh's tangent t (ModelDef::uv_tangent) and b = w·(n × t) —
// made unit and turned by anisotropy_rotation r counter-clockwise: d' = R(r) d (the README's
// "Implementation": mat2(cos r, sin r, −sin r, cos r) · normalize(direction)), so t' = d'_x t +
// d'_y b and b' = n × t' = d'_x b − d'_y t (up to the sign w, which D and V square away). d is
// 2·(anisotropy_direction_x, _y) − 1: anisotropyTexture's red and green as the README maps them,
// (1, 0) with the defaults (1, 0.5), the README's default texel. Along t' α_t = mix(α, 1,
// strength²) (strength times the texture's blue), across it α_b = α. D is the README's
// (Burley's anisotropic GGX), V the anisotropic height-correlated Smith term of its
// "Implementation" (without the sample's clamp at 1, as Appendix B's isotropic V has none).
ir::Expr gltf_anisotropic_layer(LobeContext& c, const ir::Expr& alpha) {
  const ModelSpec& s = c.spec();
  ir::Expr strength = c.number("anisotropy_strength");
  ir::Expr at = c.let("alpha_t", alpha + (1.0 - alpha) * ir::sq(strength));
  const double rotation = s.at("anisotropy_rotation").number;
  std::array<ir::Expr, 6> dots = {c.HoT(), c.HoB(), c.input(Input::LoT), c.input(Input::LoB), c.input(Input::VoT),
                                  c.input(Input::VoB)};
  std::optional<std::array<ir::Expr, 2>> turn;  // d', where it is not (1, 0)
  if (c.textured(s, "anisotropy_direction_x") || c.textured(s, "anisotropy_direction_y")) {
    // "red [0, 1] to X [−1, 1], green [0, 1] to Y [−1, 1]".
    ir::Expr x = c.let("direction_x", 2.0 * c.number("anisotropy_direction_x") - 1.0);
    ir::Expr y = c.let("direction_y", 2.0 * c.number("anisotropy_direction_y") - 1.0);
    // A zero direction (which normalize leaves undefined) is divided by ε instead: α_t and α_b still apply.
    ir::Expr len = c.let("direction_length", ir::max(ir::sqrt(x * x + y * y), kEpsilon));
    ir::Expr dx = c.let("direction_unit_x", x / len), dy = c.let("direction_unit_y", y / len);
    if (rotation != 0) {
      ir::Expr cr = ir::constant(c.lobe() + "_anisotropy_cos", std::cos(rotation));
      ir::Expr sr = ir::constant(c.lobe() + "_anisotropy_sin", std::sin(rotation));
      turn = {{c.let("direction_turned_x", cr * dx - sr * dy), c.let("direction_turned_y", sr * dx + cr * dy)}};
    } else {
      turn = {{dx, dy}};
    }
  } else {
    // A constant direction: decode, normalize and turn it here.
    const double x = 2 * s.at("anisotropy_direction_x").number - 1, y = 2 * s.at("anisotropy_direction_y").number - 1;
    const double angle = rotation + (x == 0 && y == 0 ? 0.0 : std::atan2(y, x));
    if (angle != 0)
      turn = {{ir::constant(c.lobe() + "_anisotropy_cos", std::cos(angle)),
               ir::constant(c.lobe() + "_anisotropy_sin", std::sin(angle))}};
  }
  if (turn) {
    const auto& [cr, sr] = *turn;
    const char* names[] = {"HoT_r", "HoB_r", "LoT_r", "LoB_r", "VoT_r", "VoB_r"};
    std::array<ir::Expr, 6> turned = dots;
    for (int k = 0; k < 6; k += 2) {
      turned[k] = c.let(names[k], cr * dots[k] + sr * dots[k + 1]);
      turned[k + 1] = c.let(names[k + 1], cr * dots[k + 1] - sr * dots[k]);
    }
    dots = turned;
  }
  ir::Expr D = c.let("D", ir::call(terms::distribution_ggx_anisotropic(), {c.NoH(), dots[0], dots[1], at, alpha}));
  ir::Expr V = c.let("V", ir::call(terms::visibility_smith_ggx_correlated_anisotropic(),
                                   {c.NoL(), c.NoV(), dots[2], dots[3], dots[4], dots[5], at, alpha}));
  return c.let("specular_brdf", kPi * D * V * c.NoL());
}

// Whether glTF's GGX core is anisotropic: anisotropy_strength above 0, or from an image.
bool gltf_anisotropic(const ModelSpec& s) {
  const Value& strength = s.at("anisotropy_strength");
  return strength.texture || strength.number > 0;
}

// The cosines a GGX layer reads of its normal: n·l, n·v and min(n·h, 1) (the lobes' n), or
// c·l, c·v and min(c·h, 1) (the coat's own normal c: Input::CoL …).
struct LayerCosines {
  ir::Expr l, v, h;
};
LayerCosines lobe_cosines(LobeContext& c) { return {c.NoL(), c.NoV(), c.NoH()}; }

// The GGX layer of glTF's specular_brdf(α) as ρ: π D V (n·l), Appendix B's D and height-correlated
// V, α = roughness² floored (a constant where `roughness` is a number, else computed where it
// shades), of the cosines `at`. `prefix` names its values ("" the core's, "coat_" the clear
// coat's). The core's is anisotropic where the material's anisotropy_strength is above 0
// (KHR_materials_anisotropy).
ir::Expr gltf_specular_layer(LobeContext& c, const std::string& roughness, const std::string& prefix,
                             const LayerCosines& at) {
  const double r = c.spec().at(roughness).number;
  ir::Expr alpha = c.textured(c.spec(), roughness)
                       ? c.let(prefix + "alpha", ir::max(ir::sq(c.number(roughness)), kRoughnessMin))
                       : ir::constant(c.lobe() + "_" + prefix + "alpha", std::max(r * r, kRoughnessMin));
  if (prefix.empty() && gltf_anisotropic(c.spec())) return gltf_anisotropic_layer(c, alpha);
  ir::Expr D = c.let(prefix + "D", ir::call(terms::distribution_ggx(), {at.h, alpha}));
  ir::Expr V = c.let(prefix + "V", ir::call(terms::visibility_smith_ggx_correlated(), {at.l, at.v, alpha}));
  return c.let(prefix + "specular_brdf", kPi * D * V * at.l);
}

// glTF 2.0 Appendix B, "Metal BRDF and Dielectric BRDF", with KHR_materials_specular's
// dielectric_f0 / f90 and KHR_materials_ior's f0 ("Interaction with other extensions").
ir::Expr gltf_core(LobeContext& c) {
  // A grey base colour (and specular_color) keeps the lobe one number until k_s ⊗ ρ.
  ir::Expr base = c.parameter(c.spec(), "base_color", c.lobe() + "_base_color", true);
  ir::Expr specular = c.number("specular");
  ir::Expr layer = gltf_specular_layer(c, "roughness", "", lobe_cosines(c));  // ρ of specular_brdf(α)
  // fresnel_w takes |v·h| itself (Appendix B): v·h unclamped.
  ir::Expr w = c.let("w", ir::call(terms::fresnel_weight(), {c.input(Input::VoH)}));
  // metallic 0 or 1 as a number (most materials): the other side of the mix is weighted 0
  // and left out of the code (it is finite, so (1 − t) a + t b is the one side exactly).
  const bool textured_metal = c.textured(c.spec(), "metallic");
  const double metallic = c.spec().at("metallic").number;
  ir::Expr metal = 0.0, dielectric = 0.0;
  if (textured_metal || metallic > 0)
    metal = c.let("metal_brdf", ir::call(terms::conductor_fresnel(base.type()), {base, w, layer}));
  if (!textured_metal && metallic == 1) return metal;
  ir::Expr ior = c.number("ior");
  ir::Expr f0_ior = c.let("f0_ior", ir::sq((ior - 1.0) / (ior + 1.0)));
  // A grey specular_color (the default) keeps F one number, its own max.
  const std::array<double, 3>& tint = c.spec().at("specular_color").rgb;
  const bool grey = !c.textured(c.spec(), "specular_color") && tint[0] == tint[1] && tint[1] == tint[2];
  ir::Expr color = c.parameter(c.spec(), "specular_color", c.lobe() + "_specular_color", true);
  ir::Expr f0 = c.let("dielectric_f0", ir::min(f0_ior * color, grey ? ir::Expr(1.0) : ir::color(1, 1, 1)) * specular);
  ir::Expr F = c.let("dielectric_fresnel", ir::call(terms::fresnel_schlick_f90(f0.type()), {f0, specular, w}));
  if (grey) {
    dielectric =
        c.let("dielectric_brdf", ir::call(terms::fresnel_mix(F.type(), base.type()), {F, layer, base * c.NoL()}));
  } else {
    // max(F) in closed form: F = f0 (1 − w) + f90 w with 1 − w ≥ 0 is largest where f0 is,
    // and max(min(a c, 1)) = min(a max(c), 1) for a ≥ 0: max₃ of specular_color, a constant, or
    // of specularColorTexture's sampled value (LobeContext::max_of).
    ir::Expr tint_max = c.max_of(c.spec(), "specular_color", c.lobe() + "_specular_color");
    ir::Expr F_max =
        c.let("dielectric_fresnel_max", ir::min(f0_ior * tint_max, 1.0) * specular * (1.0 - w) + specular * w);
    dielectric =
        c.let("dielectric_brdf",
              ir::call(terms::fresnel_mix(F.type(), base.type()), {F, F_max, layer, base * c.NoL()}));
  }
  if (!textured_metal && metallic == 0) return dielectric;
  // The two sides as one type: a grey one as a colour where the other is coloured.
  if (dielectric.type() != metal.type()) {
    if (dielectric.type() == ir::Type::Float) dielectric = dielectric * ir::color(1, 1, 1);
    else metal = metal * ir::color(1, 1, 1);
  }
  return ir::call(terms::mix_by(metal.type()), {dielectric, metal, c.number("metallic")});
}

// The parameters a sheen reads: gltf_pbr's (sheen_color, sheen_roughness) or the sheen layer's
// (color, roughness).
struct SheenParams {
  std::string color, roughness;
};
const SheenParams kGltfSheen{"sheen_color", "sheen_roughness"};
const SheenParams kLayerSheen{"color", "roughness"};

// What the sheen's terms take of its roughness r: α = max(r², 1e-3), the visibility's l()
// coefficients a … e and l(0.5), and E's series coefficients [μ piece][k].
struct SheenConstants {
  ir::Expr alpha = 0.0;
  std::vector<ir::Expr> l;
  std::vector<std::vector<ir::Expr>> e;
};

// r a number: every one a constant of the material, folded when the code is generated.
SheenConstants sheen_folded(LobeContext& c, const SheenParams& names) {
  const double r = c.spec().at(names.roughness).number;
  const double alpha = std::max(r * r, kRoughnessMin);
  SheenConstants k;
  k.alpha = ir::constant(c.lobe() + "_sheen_alpha", alpha);
  const std::array<double, 6> l = sheen_visibility_constants(alpha);
  const char* l_names[] = {"a", "b", "c", "d", "e", "l_half"};
  for (size_t i = 0; i < l.size(); ++i) k.l.push_back(ir::constant(c.lobe() + "_sheen_l_" + l_names[i], l[i]));
  const std::vector<SheenAlbedoPiece> pieces = sheen_albedo_pieces(r);
  for (size_t p = 0; p < pieces.size(); ++p) {
    k.e.emplace_back();
    for (size_t i = 0; i < pieces[p].coefficients.size(); ++i)
      k.e[p].push_back(ir::constant(c.lobe() + "_sheen_e" + std::to_string(p) + "_" + std::to_string(i),
                                    pieces[p].coefficients[i]));
  }
  return k;
}

// r from an image (sheenRoughnessTexture): the same quantities at every pixel, the README's mixes
// of l()'s coefficients and the fit's series in √r (sheen_albedo_r_pieces) summed as
// sheen_albedo_pieces sums them for a number: E is the same function of r either way.
SheenConstants sheen_per_pixel(LobeContext& c, const SheenParams& names) {
  SheenConstants k;
  ir::Expr r = c.let("sheen_r", ir::clamp(c.parameter(c.spec(), names.roughness, c.lobe() + "_" + names.roughness),
                                          sheen_albedo_r_min(), 1.0));
  k.alpha = c.let("sheen_alpha", ir::max(r * r, kRoughnessMin));
  ir::Expr t = c.let("sheen_t", (1.0 - k.alpha) * (1.0 - k.alpha));
  const char* l_names[] = {"a", "b", "c", "d", "e"};
  const auto pq = sheen_l_mix();
  for (size_t i = 0; i < pq.size(); ++i)
    k.l.push_back(c.let(std::string("sheen_l_") + l_names[i], pq[i].first + (pq[i].second - pq[i].first) * t));
  k.l.push_back(c.let("sheen_l_half", k.l[0] / (1.0 + k.l[1] * ir::pow(ir::Expr(0.5), k.l[2])) + k.l[3] * 0.5 + k.l[4]));
  const std::vector<SheenAlbedoRPiece>& pieces = sheen_albedo_r_pieces();
  auto pick = [&](const std::function<double(const SheenAlbedoRPiece&)>& of) {
    ir::Expr out = of(pieces.back());
    for (size_t p = pieces.size() - 1; p-- > 0;) out = ir::select(r < pieces[p].r_end, ir::Expr(of(pieces[p])), out);
    return out;
  };
  // T_j(y), y = √r mapped onto [−1, 1] on r's piece.
  ir::Expr y = c.let("sheen_r_y", ir::sqrt(r) * pick([](const SheenAlbedoRPiece& p) { return p.scale; }) +
                                      pick([](const SheenAlbedoRPiece& p) { return p.offset; }));
  std::vector<ir::Expr> T{1.0, y};
  for (size_t j = 2; j < pieces[0].c[0][0].size(); ++j)
    T.push_back(c.let("sheen_r_T" + std::to_string(j), 2.0 * y * T[j - 1] - T[j - 2]));
  for (size_t mu = 0; mu < pieces[0].c.size(); ++mu) {
    k.e.emplace_back();
    for (size_t i = 0; i < pieces[0].c[mu].size(); ++i) {
      // One sum per piece of r, the piece's chosen: two selects a coefficient, not one a term.
      auto sum = [&](const SheenAlbedoRPiece& p) {
        ir::Expr a = p.c[mu][i][0];
        for (size_t j = 1; j < T.size(); ++j) a = a + p.c[mu][i][j] * T[j];
        return a;
      };
      ir::Expr a = sum(pieces.back());
      for (size_t p = pieces.size() - 1; p-- > 0;) a = ir::select(r < pieces[p].r_end, sum(pieces[p]), a);
      k.e[mu].push_back(c.let("sheen_e" + std::to_string(mu) + "_" + std::to_string(i), a));
    }
  }
  return k;
}

// KHR_materials_sheen, "Sheen" and "Implementation Notes": sheen_material = sheenColor ⊗
// sheen_brdf + material · min(1 − max₃(sheenColor) E(n·v), 1 − max₃(sheenColor) E(n·l)), the
// sheen BRDF the "Charlie" D and visibility of α = sheenRoughness² (floored like the GGX α), the
// albedo scaling the reciprocal one the README writes first, not its view-only shortcut. E is
// the fit of catalog/sheen.cpp, its coefficients folded for a roughness of numbers (sheen_folded),
// summed at every pixel for sheenRoughnessTexture's (sheen_per_pixel). A
// sheen colour of 0 (every material without the extension) leaves the core as it is: "If
// sheenColorFactor is zero, the whole sheen layer is disabled."
ir::Expr sheen_over(LobeContext& c, ir::Expr core, const SheenParams& names) {
  const std::array<double, 3>& color = c.spec().at(names.color).rgb;  // the factor, where it is an image
  const double color_max = std::max({color[0], color[1], color[2]});
  if (color_max == 0) return core;
  const SheenConstants k =
      c.textured(c.spec(), names.roughness) ? sheen_per_pixel(c, names) : sheen_folded(c, names);
  ir::Expr D = c.let("sheen_D", ir::call(terms::distribution_charlie(), {c.NoH(), k.alpha}));
  std::vector<ir::Expr> v_args{c.NoL(), c.NoV()};
  v_args.insert(v_args.end(), k.l.begin(), k.l.end());
  ir::Expr V = c.let("sheen_V", ir::call(terms::visibility_charlie(), v_args));
  ir::Expr brdf = c.let("sheen_brdf", kPi * D * V * c.NoL());
  // E at n·v and at n·l: the piece of μ chooses its series' coefficients and argument, then one
  // series is summed.
  const std::vector<SheenAlbedoPiece> pieces = sheen_albedo_pieces(0);  // the μ pieces' bounds and maps
  std::vector<ir::Expr> scale, offset;
  for (size_t p = 0; p < pieces.size(); ++p) {
    const std::string piece = c.lobe() + "_sheen_e" + std::to_string(p);
    scale.push_back(ir::constant(piece + "_scale", pieces[p].scale));
    offset.push_back(ir::constant(piece + "_offset", pieces[p].offset));
  }
  auto albedo = [&](const ir::Expr& mu, const std::string& name) {
    // m = max(μ, mu_min); √m, and √√m for a piece in m^¼.
    ir::Expr u = c.let(name + "_u", ir::sqrt(ir::max(mu, sheen_albedo_mu_min())));
    ir::Expr u4 = c.let(name + "_u4", ir::sqrt(u));
    auto pick = [&](const std::function<ir::Expr(size_t)>& of) {
      ir::Expr out = of(pieces.size() - 1);
      for (size_t p = pieces.size() - 1; p-- > 0;) out = ir::select(mu < pieces[p].mu_end, of(p), out);
      return out;
    };
    std::vector<ir::Expr> args{c.let(name + "_x", pick([&](size_t p) {
      return (pieces[p].power == 0.25 ? u4 : u) * scale[p] + offset[p];
    }))};
    for (size_t i = 0; i < k.e[0].size(); ++i) args.push_back(pick([&](size_t p) { return k.e[p][i]; }));
    ir::Expr s = c.let(name + "_s", ir::call(terms::sheen_albedo_series(), args));
    return c.let(name, ir::clamp(ir::exp(s) - sheen_albedo_epsilon(), 0.0, 1.0));
  };
  ir::Expr e_v = albedo(c.NoV(), "sheen_E_v");
  ir::Expr e_l = albedo(c.NoL(), "sheen_E_l");
  // max₃(sheenColor): a constant, or of sheenColorTexture's sampled value (LobeContext::max_of).
  ir::Expr cmax = c.max_of(c.spec(), names.color, c.lobe() + "_" + names.color);
  ir::Expr scaling = c.let("sheen_scaling", ir::min(1.0 - cmax * e_v, 1.0 - cmax * e_l));
  ir::Expr sheen_color = c.parameter(c.spec(), names.color, c.lobe() + "_" + names.color, true);
  return sheen_color * brdf + core * scaling;
}

ir::Expr gltf_sheen(LobeContext& c, ir::Expr core) { return sheen_over(c, std::move(core), kGltfSheen); }

// The parameters a clear coat reads: gltf_pbr's (clearcoat, clearcoat_roughness) or the clearcoat
// layer's (weight, roughness).
struct CoatParams {
  std::string weight, roughness;
};
const CoatParams kGltfCoat{"clearcoat", "clearcoat_roughness"};
const CoatParams kLayerCoat{"weight", "roughness"};

// Whether `s` has a coat: its weight from an image, or a number other than 0 (every gltf_pbr
// without the extension has 0). Both the coat's layer and the emission under it ask.
bool has_coat(const ModelSpec& s, const CoatParams& names) {
  const Value& coat = s.at(names.weight);
  return coat.texture || coat.number != 0;
}
bool has_clearcoat(const ModelSpec& s) { return has_coat(s, kGltfCoat); }

// KHR_materials_clearcoat, "Clearcoat" and "Implementation": the coat is specular_brdf of
// α = clearcoatRoughness² over the whole material, mixed in by clearcoat · fresnel_coat, whose
// Schlick Fresnel (f0 = 0.04, ior 1.5) reads |c·v|, not v·h: coated = material (1 − c Fc) +
// c Fc clearcoat_brdf, all of it on the coat's normal c ("`normal` is a float3 vector that affects
// the top layer, but not the base"). Where c is n (no normal map under the coat) the lobe reads
// n's cosines; else c's (Input::CoL, CoV, CoH), and the coat's ρ takes c·l as its cosine, as the
// Khronos glTF Sample Viewer's getPunctualRadianceClearCoat does (punctual.glsl: NdotL of the
// clearcoat normal times BRDF_specularGGX), 0 where c·l or c·v is not above 0 (its clampedDot).
// A number clearcoat of 0 (every material without the extension) leaves the core as it is, in
// the code too.
ir::Expr coat_over(LobeContext& c, ir::Expr core, const CoatParams& names) {
  if (!has_coat(c.spec(), names)) return core;
  LayerCosines at = lobe_cosines(c);
  if (c.coat_normal())
    at = {c.input(Input::CoL), c.input(Input::CoV), c.let("CoH_1", ir::min(c.input(Input::CoH), 1.0))};
  // Its values are named coat_…: "clearcoat_alpha" would meet OSL's name for the alpha of the
  // clearcoat parameter's texel (<lobe>_clearcoat_alpha).
  ir::Expr coat = gltf_specular_layer(c, names.roughness, "coat_", at);
  if (c.coat_normal()) coat = c.let("coat_lit", ir::select(ir::min(at.l, at.v) <= 0.0, ir::Expr(0.0), coat));
  ir::Expr w = c.let("coat_w", ir::call(terms::fresnel_weight(), {at.v}));
  ir::Expr fc = c.let("coat_fresnel", ir::call(terms::fresnel_schlick_f90(ir::Type::Float), {0.04, 1.0, w}));
  if (core.type() != ir::Type::Float) coat = coat * ir::color(1, 1, 1);
  return ir::call(terms::mix_by(core.type()), {core, coat, c.number(names.weight) * fc});
}

ir::Expr gltf_clearcoat(LobeContext& c, ir::Expr core) { return coat_over(c, std::move(core), kGltfCoat); }

// KHR_materials_clearcoat, "Emission": coated_emission = emission (1 − clearcoat
// clearcoat_fresnel), clearcoat_fresnel = 0.04 + 0.96 (1 − n·v)^5 the coat's Fresnel of n·v as the
// coat lobe has it ("Layering"), n the coat's normal Nc: its own normal map's (the material's
// coat_normal_map, glTF's clearcoatNormalTexture), else the surface's own ("if
// clearcoatNormalTexture is not given, no normal mapping is applied to the clear coat layer"); every
// target passes n·v of that normal. A textured clearcoat is the same input the reflectance reads
// (`lobe`_clearcoat, its texel times its factor). Null without a coat.
ir::FunctionPtr coat_emission_weight(const ModelSpec& s, const std::string& lobe, const std::string& function,
                                     const CoatParams& names) {
  if (!has_coat(s, names)) return nullptr;
  const Value& coat = s.at(names.weight);
  ir::FunctionBuilder fb(function,
                         "KHR_materials_clearcoat, \"Emission\": the emission under the coat, 1 − clearcoat "
                         "clearcoat_fresnel(n·v)");
  ir::Expr NoV = fb.param("NoV");
  ir::Expr clearcoat = coat.texture ? fb.param(lobe + "_" + names.weight)
                                    : ir::constant(lobe + "_emission_" + names.weight, coat.number);
  ir::Expr w = fb.let("coat_w", ir::call(terms::fresnel_weight(), {NoV}));
  ir::Expr fc = fb.let("coat_fresnel", ir::call(terms::fresnel_schlick_f90(ir::Type::Float), {0.04, 1.0, w}));
  return fb.returns(1.0 - clearcoat * fc);
}

ir::FunctionPtr gltf_emission_weight(const ModelSpec& s, const std::string& lobe, const std::string& function) {
  return coat_emission_weight(s, lobe, function, kGltfCoat);
}

const char* kMicrofacetPov = "function pigment";

// The glTF equivalent of a lobe whose parameter `param` is a GGX-like roughness α.
std::function<double(const ModelSpec&)> alpha_is(std::string param) {
  return [param = std::move(param)](const ModelSpec& s) { return s.at(param).number; };
}

// The roughness α whose highlight is about as wide as Blinn–Phong's of exponent n,
// α = √(2 / (n + 2)): the relation Walter et al. 2007 give for Beckmann's m.
double blinn_phong_alpha(double n) { return std::sqrt(2 / (n + 2)); }

// A highlight POV-Ray's finish is exactly: `size` is how its keyword takes the
// exponent n; k_s must be grey, and neither Schlick's approximation nor toon.
PovFinish pov_highlight(const std::string& keyword, const std::string& size_keyword, PovFinishTerm::From size) {
  using Kind = PovFinishRequirement::Kind;
  PovFinish f;
  f.terms = {{keyword, PovFinishTerm::From::GreyColor, "color", 0}, {size_keyword, size, "n", 0}};
  f.requirements = {{Kind::Absent, "toon", "", "the toon modifier is not a POV-Ray finish"},
                    {Kind::Choice, "approximation", "none", "Schlick's approximation is not a POV-Ray finish"},
                    {Kind::Grey, "color", "", "POV-Ray highlights take a grey k_s only"}};
  return f;
}

}  // namespace

void add_specular(std::vector<ModelDef>& all) {
  {
    ModelDef m;
    m.section = "specular";
    m.name = "phong";
    m.title = "Phong";
    m.citation = "Phong 1975, \"Illumination for Computer Generated Pictures\", CACM 18(6)";
    m.formula = "ρ_s = [r·v]^n, r = 2(n·l)n − l";
    m.doc = "The classic highlight: a cosine lobe of exponent n around the mirror direction. Not "
            "energy-conserving and not reciprocal, but cheap and familiar.";
    m.params = {number("n", "exponent; larger is a tighter highlight", Range::exponent(1), 32),
                approximation_param()};
    m.cycles = none("Cycles registers no phong closure (phong_ramp is a different, ramped lobe)");
    m.pov = exact("finish { phong k_s phong_size n } for a grey k_s without approximation or toon");
    m.blender_nodes = nodes_none("no Blender node has a Phong lobe");
    m.pov_finish = pov_highlight("phong", "phong_size", PovFinishTerm::From::Number);
    m.build = [](LobeContext& c) {
      ir::Expr NoL = c.NoL(), NoV = c.NoV(), LoV = c.LoV();
      if (c.choice("approximation") == "schlick") {
        ir::Expr RoV = c.let("RoV", 2.0 * NoL * NoV - LoV);
        return ir::call(terms::schlick_power(), {RoV, c.number("n")});
      }
      return ir::call(terms::phong(), {NoL, NoV, LoV, c.number("n")});
    };
    m.physics_note = "ρ = [r·v]^n makes f = ρ/(π n·l) asymmetric; an unnormalized lobe, not a BRDF";
    // Phong's exponent n looks about like Blinn–Phong's 4n.
    m.ggx_alpha = [](const ModelSpec& s) { return blinn_phong_alpha(4 * s.at("n").number); };
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "specular";
    m.name = "blinn_phong";
    m.title = "Blinn–Phong";
    m.citation = "Blinn 1977, \"Models of Light Reflection for Computer Synthesized Pictures\", SIGGRAPH '77";
    m.formula = "ρ_s = [n·h]^n, h = normalize(l + v)";
    m.doc = "Phong's lobe measured around the normal with the half vector: the fixed-function "
            "OpenGL highlight. For the same look as Phong, use about four times the exponent.";
    m.params = {number("n", "exponent; larger is a tighter highlight", Range::exponent(1), 64),
                approximation_param()};
    m.cycles = none("Cycles has no Blinn–Phong closure");
    m.pov = exact("finish { specular k_s roughness 1/n } for a grey k_s without approximation or toon");
    m.blender_nodes = nodes_none("no Blender node has an unnormalized Blinn–Phong lobe");
    m.pov_finish = pov_highlight("specular", "roughness", PovFinishTerm::From::Reciprocal);
    m.build = [](LobeContext& c) {
      ir::Expr NoH = c.NoH();
      return power(c, terms::blinn_phong(), {NoH, c.number("n")}, NoH);
    };
    m.physics_note = "ρ = [n·h]^n makes f = ρ/(π n·l) asymmetric; an unnormalized lobe, not a BRDF";
    m.ggx_alpha = [](const ModelSpec& s) { return blinn_phong_alpha(s.at("n").number); };
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "specular";
    m.name = "gaussian";
    m.title = "Gaussian";
    m.citation = "Gaussian highlight, after Torrance & Sparrow 1967";
    m.formula = "ρ_s = exp(−m · acos([n·h])²)";
    m.doc = "A Gaussian in the angle between the normal and the half vector; larger m, tighter lobe.";
    m.params = {number("m", "sharpness; larger is a tighter lobe", Range::positive_exponent(), 50)};
    m.cycles = none("Cycles has no Gaussian-lobe closure");
    m.pov = none("function pigment");
    m.blender_nodes = nodes_none("no Blender node has a Gaussian lobe in the half-angle");
    m.build = [](LobeContext& c) { return ir::call(terms::gaussian(), {c.NoH(), c.number("m")}); };
    m.physics_note = "ρ itself is symmetric, so f = ρ/(π n·l) is not; an unnormalized lobe, not a BRDF";
    m.ggx_alpha = [](const ModelSpec& s) { return 1 / std::sqrt(s.at("m").number); };
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "specular";
    m.name = "heidrich_seidel";
    m.title = "Heidrich–Seidel anisotropic";
    m.citation = "Heidrich & Seidel 1998, \"Efficient Rendering of Anisotropic Surfaces Using Computer "
                 "Graphics Hardware\"";
    m.formula = "ρ_s = [√(1−(l·t)²)·√(1−(v·t)²) − (l·t)(v·t)]^n";
    m.doc = "Phong's lobe for fibres along the tangent t: brushed metal, hair, satin. The highlight is "
            "a band across the brushing direction.";
    m.params = {number("n", "exponent; larger is a thinner band", Range::exponent(1), 32)};
    m.cycles = none("Cycles has no such closure");
    m.pov = none("function pigment (POV-Ray has no tangent; facet builds it from the analytic normal)");
    m.blender_nodes = nodes_none("no Blender node has this tangent-only lobe");
    m.build = [](LobeContext& c) {
      return ir::call(terms::heidrich_seidel(), {c.input(Input::LoT), c.input(Input::VoT), c.number("n")});
    };
    m.physics_note = "Phong along fibres: ρ symmetric, f = ρ/(π n·l) not; unnormalized";
    m.ggx_alpha = [](const ModelSpec& s) { return blinn_phong_alpha(4 * s.at("n").number); };  // as phong's
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "specular";
    m.name = "beckmann";
    m.title = "Beckmann";
    m.citation = "Beckmann & Spizzichino 1963, \"The Scattering of Electromagnetic Waves from Rough Surfaces\"";
    m.formula = "ρ_s = π D G F / (4 n·v), D = exp(−tan²θ_h/m²)/(π m² cos⁴θ_h); G = 1 and F = 1 by default";
    m.doc = "The Beckmann microfacet distribution alone; add `geometry` and `fresnel` to make it "
            "Cook–Torrance. m is the RMS slope of the facets.";
    m.params = {number("m", "RMS facet slope", Range::roughness(), 0.3), geometry_param("none"),
                model("fresnel", "Fresnel term F", "fresnel", "none")};
    m.cycles = approximate("microfacet(\"beckmann\", …) uses Smith G and no Fresnel");
    m.pov = none(kMicrofacetPov);
    m.blender_nodes = nodes_approximate(
        "Glossy BSDF, Beckmann, Roughness √m, Color k_s × F(0) (Cycles: Smith G, no Fresnel)", 0.00147);
    m.build = [](LobeContext& c) {
      ir::Expr m_ = c.number("m");
      return microfacet(c, ir::call(terms::distribution_beckmann(), {c.NoH(), m_}), m_);
    };
    m.reciprocal = true;
    m.physics_note = "D F/(4 (n·l)(n·v)) is symmetric; without G nothing bounds the albedo as n·l → 0 (add "
                     "`geometry` for Cook–Torrance)";
    m.ggx_alpha = alpha_is("m");
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "specular";
    m.name = "cook_torrance";
    m.title = "Cook–Torrance";
    m.citation = "Cook & Torrance 1982, \"A Reflectance Model for Computer Graphics\", ACM TOG 1(1)";
    m.formula = "ρ_s = π D G F / (4 n·v), Beckmann D, V-cavity G, exact Fresnel (η = 1.5)";
    m.doc = "The first physically based model in graphics: Beckmann facets that mask and shadow each "
            "other (V-cavities) and reflect by Fresnel's law, so highlights brighten at grazing angles.";
    m.params = {number("m", "RMS facet slope", Range::roughness(), 0.3), geometry_param("v_cavity"),
                model("fresnel", "Fresnel term F", "fresnel", "exact", {{"ior", number_value(1.5)}})};
    m.cycles = approximate("microfacet(\"beckmann\", …) with F multiplied in; Cycles' G is Smith, not V-cavity");
    m.pov = none(kMicrofacetPov);
    m.blender_nodes = nodes_approximate(
        "Glossy BSDF, Beckmann, Roughness √m, Color k_s × F(0) (Cycles: Smith G, not V-cavity; no Fresnel)", 0.0638);
    m.build = [](LobeContext& c) {
      ir::Expr m_ = c.number("m");
      return microfacet(c, ir::call(terms::distribution_beckmann(), {c.NoH(), m_}), m_);
    };
    m.reciprocal = true;
    m.energy_conserving = true;
    m.physics_note = "symmetric; the V-cavity masking function is exact for its microsurface (Heitz 2014, "
                     "\"Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs\") and G ≤ G1(l), "
                     "so with F ≤ 1 the albedo is ≤ 1";
    m.ggx_alpha = alpha_is("m");
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "specular";
    m.name = "ggx";
    m.title = "GGX (Trowbridge–Reitz)";
    m.citation = "Walter et al. 2007, \"Microfacet Models for Refraction through Rough Surfaces\", EGSR";
    m.formula = "ρ_s = π D G F / (4 n·v), D = α²/(π((n·h)²(α²−1)+1)²), separable Smith G, Schlick F (f0 = 0.04)";
    m.doc = "The long-tailed distribution of real materials and of glTF's metallic–roughness model "
            "(α = roughness²).";
    m.params = {number("alpha", "roughness α", Range::roughness(), 0.2), geometry_param("smith_ggx"),
                model("fresnel", "Fresnel term F", "fresnel", "schlick", {{"f0", color_value(0.04)}})};
    m.cycles = approximate("microfacet(\"ggx\", …) uses height-correlated Smith G and no Fresnel");
    m.pov = none(kMicrofacetPov);
    m.blender_nodes = nodes_approximate(
        "Principled BSDF (Blender 4), GGX, Roughness √α, only its specular layer: Schlick's Fresnel a metal of Base "
        "Color k_s ⊗ f0, the exact one a dielectric of that IOR with Specular Tint k_s (without Fresnel, and before "
        "Blender 4: Glossy BSDF, GGX, Color k_s); Cycles' G is height-correlated Smith",
        0.00467);
    m.build = [](LobeContext& c) {
      ir::Expr a = c.number("alpha");
      return microfacet(c, ir::call(terms::distribution_ggx(), {c.NoH(), a}), a);
    };
    m.reciprocal = true;
    m.energy_conserving = true;
    m.physics_note = "symmetric; Smith G1 is exact for GGX facets and G = G1(l) G1(v) ≤ G1(l), so with F ≤ 1 the "
                     "albedo is ≤ 1 (Walter et al. 2007; Heitz 2014); energy of multiple scattering is lost";
    m.ggx_alpha = alpha_is("alpha");
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "specular";
    m.name = "gltf_pbr";
    m.title = "glTF metallic–roughness";
    m.citation = "The Khronos Group, \"glTF 2.0 Specification\", Appendix B \"BRDF Implementation\"; "
                 "KHR_materials_ior; KHR_materials_specular; KHR_materials_anisotropy; KHR_materials_sheen; "
                 "KHR_materials_clearcoat";
    // Short words: the add-on's panel wraps the formula at 27 characters (220 px) and keeps words whole.
    m.formula = "ρ = π f (n·l), f = (1 − metallic) dielectric + metallic metal, dielectric = F S + (1 − max F) "
                "base_color/π, metal = S (base_color + (1 − base_color) w), S = D V (GGX, height-correlated "
                "Smith, α = roughness²), F = f0 + (specular − f0) w, w = (1 − |v·h|)^5, f0 = min(F0(ior) "
                "specular_color, 1) specular, F0(ior) = ((ior − 1)/(ior + 1))²; with a sheen s: f' = s S_s + f min(1 − "
                "max(s) E(n·v), 1 − max(s) E(n·l)), S_s = D V (Charlie, α = sheen_roughness²), E its albedo; with a "
                "clear coat c over that: f'' = f' (1 − c Fc) + c Fc S_c, S_c = D V (α = clearcoat_roughness², on the "
                "coat's normal n_c), Fc = 0.04 + 0.96 (1 − |n_c·v|)^5";
    m.doc = "The whole BRDF a glTF file's material means, diffuse included, as its specification writes it: a "
            "dielectric (a Lambert base under a GGX layer, the base weighted by 1 − max(F)) and a metal (the GGX "
            "lobe tinted by the base colour's Schlick Fresnel), mixed by metallic. ior and specular / specular_color "
            "are KHR_materials_ior and KHR_materials_specular; their defaults (1.5, 1, white) give the core "
            "specification's f0 = 0.04. anisotropy_strength and anisotropy_rotation are KHR_materials_anisotropy: "
            "the GGX layer's α along the rotated tangent grows to mix(α, 1, strength²) (Burley's D, the "
            "anisotropic height-correlated V). sheen_color and sheen_roughness are KHR_materials_sheen: the \"Charlie\" "
            "sheen over the rest, which is scaled by one minus the sheen's directional albedo at n·v and at n·l (a "
            "fit, worst error stated in docs/gltf.md). clearcoat and clearcoat_roughness are KHR_materials_clearcoat: "
            "a GGX layer over all of it, weighted by its Fresnel at n·v, on a normal of its own: the material's "
            "coat_normal_map (glTF's clearcoatNormalTexture), else the surface's own, unmapped where the base has a "
            "normal_map. Write it as the material's specular lobe, alone.";
    // Defaults: Blender's Principled BSDF's (a grey dielectric, roughness 0.5), not glTF's white
    // rough metal (1, 1, 1), which a glTF import states for a file that leaves its factors out;
    // the extensions' defaults are their READMEs'.
    m.params = {
        color("base_color", "baseColorFactor: the diffuse colour of a dielectric, f0 of a metal (glTF's default 1)",
              Range::closed(0, 1), {0.8, 0.8, 0.8}),
        number("metallic", "metallicFactor: 0 a dielectric, 1 a metal, mixed between (glTF's default 1)",
               Range::closed(0, 1), 0, false),
        number("roughness",
               "roughnessFactor; α = roughness², at least 1e-3 (α = 0 is a delta the specification says to clamp; "
               "glTF's default 1)",
               Range::closed(0, 1), 0.5, false),
        number("ior", "KHR_materials_ior: f0 = ((ior − 1)/(ior + 1))² (0 gives f0 = 1, as the extension allows)",
               Range::closed(0, kScalarMax), 1.5, false),
        number("specular", "KHR_materials_specular specularFactor: f90 of the dielectric, and a factor of its f0",
               Range::closed(0, 1), 1, false),
        color("specular_color",
              "KHR_materials_specular specularColorFactor: the dielectric f0's colour; an image's: "
              "specularColorTexture's rgb (sRGB) times it",
              Range::color(), {1, 1, 1}),
        number("clearcoat", "KHR_materials_clearcoat clearcoatFactor: the clear coat's weight (0: none)",
               Range::closed(0, 1), 0, false),
        number("clearcoat_roughness",
               "KHR_materials_clearcoat clearcoatRoughnessFactor; the coat's α = clearcoat_roughness², at least 1e-3",
               Range::closed(0, 1), 0, false),
        number("anisotropy_strength",
               "KHR_materials_anisotropy anisotropyStrength: α along the anisotropy's direction is mix(α, 1, "
               "strength²) (0: isotropic); an image's: anisotropyTexture's blue times anisotropyStrength. Where it "
               "is above 0 the direction turns from the surface's tangent frame (a mesh's TANGENT or MikkTSpace "
               "tangents of the normal map's coordinates, else of this image's, else of TEXCOORD_0), not tangent_axis",
               Range::closed(0, 1), 0, false),
        number("anisotropy_rotation",
               "KHR_materials_anisotropy anisotropyRotation: the direction of increased roughness, radians "
               "counter-clockwise from the tangent t towards the bitangent b = w·(n × t)",
               Range::closed(-kScalarMax, kScalarMax), 0, false),
        number("anisotropy_direction_x",
               "KHR_materials_anisotropy anisotropyTexture's red: the direction's x in the tangent frame before the "
               "rotation, stored as the texture stores it, x = 2·value − 1 (1: x = 1), made unit with "
               "anisotropy_direction_y",
               Range::closed(0, 1), 1, false),
        number("anisotropy_direction_y",
               "KHR_materials_anisotropy anisotropyTexture's green: the direction's y (along b), y = 2·value − 1 "
               "(0.5: y = 0; the defaults give the README's (1, 0), the tangent)",
               Range::closed(0, 1), 0.5, false),
        color("sheen_color",
              "KHR_materials_sheen sheenColorFactor: the sheen's colour (0: none); an image's: sheenColorTexture's "
              "rgb (sRGB) times it",
              Range::closed(0, 1), {0, 0, 0}),
        number("sheen_roughness",
               "KHR_materials_sheen sheenRoughnessFactor; the sheen's α = sheen_roughness², at least 1e-3; an "
               "image's: sheenRoughnessTexture's alpha times it",
               Range::closed(0, 1), 0, false)};
    m.cycles = approximate("principled_bsdf: its dielectric is energy-compensated, not Appendix B's fresnel_mix");
    m.pov = none(kMicrofacetPov);
    m.blender_nodes = nodes_approximate(
        "Principled BSDF (Blender 4), GGX, as Blender's glTF importer builds it: Base Color, Metallic, Roughness, "
        "IOR, Specular IOR Level = specular/2, Specular Tint = specular_color; a GGX metal is glTF's exactly, a "
        "dielectric Cycles' energy-compensated layering (docs/blender.md, F)",
        0.106);
    m.build = [](LobeContext& c) { return gltf_clearcoat(c, gltf_sheen(c, gltf_core(c))); };
    // KHR_materials_anisotropy, "Anisotropy": the direction turns from the mesh's tangent frame
    // (TANGENT, else computed as the core specification says: MikkTSpace on the normal texture's
    // coordinates; facet takes the anisotropy texture's set where there is no normal texture, and
    // TEXCOORD_0 without either).
    m.uv_tangent = [](const ModelSpec& s) -> std::optional<int> {
      if (!gltf_anisotropic(s)) return std::nullopt;
      const Value& strength = s.at("anisotropy_strength");
      return strength.texture ? strength.texture->uv : 0;
    };
    m.uv_tangent_param = "anisotropy_strength";
    m.reciprocal = false;
    m.physics_note = "without a clear coat symmetric: D, V and F (of v·h = l·h) are, and so is the diffuse weight "
                     "1 − max(F); KHR_materials_clearcoat weights its layers by the Fresnel of n·v alone, which is "
                     "not (the README: \"we compute the microfacet Fresnel term with NdotV instead of VdotH\"). The "
                     "specification says fresnel_mix is not energy conserving (Appendix B, \"Coupling Diffuse and "
                     "Specular Reflection\"), and single-scattering GGX loses energy, so no bound is claimed";
    m.gltf_brdf = true;
    m.emission_weight = gltf_emission_weight;
    m.coated = has_clearcoat;
    m.ggx_alpha = [](const ModelSpec& s) {
      const double r = s.at("roughness").number;
      return std::max(r * r, kRoughnessMin);
    };
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "specular";
    m.name = "blinn";
    m.title = "Blinn (Trowbridge–Reitz)";
    m.citation = "Blinn 1977, \"Models of Light Reflection for Computer Synthesized Pictures\", SIGGRAPH '77";
    m.formula = "ρ_s = D G F / (n·v), D = (c²/((n·h)²(c²−1)+1))², V-cavity G, exact Fresnel (η = 1.5)";
    m.doc = "Blinn's model as printed: the Trowbridge–Reitz ellipsoid distribution with eccentricity "
            "c, unnormalized, with Cook–Torrance's G and Fresnel.";
    m.params = {number("c", "eccentricity of the facet ellipsoids", Range::left_open(0, 1), 0.3),
                model("fresnel", "Fresnel term F", "fresnel", "exact", {{"ior", number_value(1.5)}})};
    m.cycles = approximate("microfacet(\"ggx\", …) has the same distribution shape, normalized");
    m.pov = none(kMicrofacetPov);
    m.blender_nodes = nodes_approximate(
        "Glossy BSDF, GGX, Roughness √c, Color 4c² k_s × F(0) (D_TR = πc² D_GGX; Cycles: Smith G, no Fresnel)",
        0.0196);
    m.build = [](LobeContext& c) {
      ir::Expr D = c.let("D", ir::call(terms::distribution_trowbridge_reitz(), {c.NoH(), c.number("c")}));
      ir::Expr G = c.let("G", ir::call(terms::geometry_v_cavity(), {c.NoL(), c.NoV(), c.NoH(), c.VoH()}));
      ir::Expr F = c.let("F", c.fresnel());
      return ir::call(terms::blinn(F.type()), {D, G, F, c.NoV()});
    };
    m.reciprocal = true;
    m.physics_note = "D G F/(π (n·l)(n·v)) is symmetric; D is not normalized (its peak is 1), so no bound is claimed";
    m.ggx_alpha = alpha_is("c");
    add_lobe_params(m);
    all.push_back(m);
  }
  for (bool nvidia : {false, true}) {
    ModelDef m;
    m.section = "specular";
    m.name = nvidia ? "ward_nvidia" : "ward";
    m.title = nvidia ? "Ward (NVIDIA survey form)" : "Ward anisotropic";
    m.citation = nvidia ? "Losasso, \"Surface Reflection Models\", NVIDIA, after Ward 1992"
                        : "Ward 1992, \"Measuring and Modeling Anisotropic Reflection\", SIGGRAPH '92";
    m.formula = nvidia ? "as ward, with exponent −2((h·t/αx)² + (h·b/αy)²)/(1 + n·h)"
                       : "ρ_s = (n·l)/(4 αx αy √((n·l)(n·v))) · exp(−((h·t/αx)² + (h·b/αy)²)/(n·h)²)";
    m.doc = nvidia ? "The survey's rewriting of Ward's exponent; close to ward for small α, not equal."
                   : "An elliptical Gaussian of slopes with widths αx along the tangent and αy across it: "
                     "brushed metal. Fitted to measurements; αx = αy gives the isotropic model.";
    m.params = {number("alpha_x", "slope deviation along the tangent t", Range::roughness(), 0.1),
                number("alpha_y", "slope deviation along the bitangent b = n × t", Range::roughness(), 0.3)};
    m.cycles = approximate("microfacet(\"beckmann\", N, T, αx, αy, …): the same exponent, other normalization");
    m.pov = none("function pigment (POV-Ray has no tangent; facet builds it from the analytic normal)");
    m.blender_nodes = nodes_none(
        "none close: an anisotropic Beckmann Glossy BSDF with facet's tangent (Geometry, Vector Math) measured "
        "|Δ|/max(1, |ref|) 6.6 on ward.json with Anisotropy 0 and 15.6–23.2 with it (the mapping unverified), 0.63 "
        "for αx = αy = 0.15, where Ward's normalization alone differs; not built");
    m.build = [nvidia](LobeContext& c) {
      return ir::call(nvidia ? terms::ward_nvidia() : terms::ward(),
                      {c.NoL(), c.NoV(), c.NoH(), c.HoT(), c.HoB(), c.number("alpha_x"), c.number("alpha_y")});
    };
    m.reciprocal = true;
    m.physics_note = nvidia ? "symmetric in l and v; the rewritten exponent is not Ward's, so his normalization "
                              "does not carry over and no bound is claimed"
                            : "symmetric in l and v; Ward's normalization is approximate: narrow lobes lose energy "
                              "as cos θ_i (Dür 2006, \"An Improved Normalization for the Ward Reflectance Model\"), "
                              "and 1/√(n·l) makes the albedo grow without bound at grazing incidence";
    m.ggx_alpha = [](const ModelSpec& s) {
      return std::sqrt(s.at("alpha_x").number * s.at("alpha_y").number);
    };
    add_lobe_params(m);
    all.push_back(m);
  }
}

// The layers a material file writes over its lobes (Material::layers, bottom first): the clear
// coat and the sheen of glTF's BRDF, the same code as gltf_pbr's (coat_over, sheen_over), over
// whatever lies under them.
void add_layers(std::vector<ModelDef>& all) {
  const char* kLayerNodes = "a layer has no Blender node (no Add Shader weights one closure by what another reflects): "
                            "the add-on's Generate OSL (Cycles) and its facet POV-Ray engine draw it";
  {
    ModelDef m;
    m.section = "layer";
    m.name = "clearcoat";
    m.title = "Clear coat";
    m.citation = "KHR_materials_clearcoat, \"Clearcoat\", \"Layering\" and \"Emission\"";
    m.formula = "ρ' = ρ (1 − w Fc) + w Fc S_c, S_c = π D V (n_c·l) (GGX, height-correlated Smith, α = roughness²), "
                "Fc = 0.04 + 0.96 (1 − |n_c·v|)^5; the emission under it m_e (1 − w Fc)";
    m.doc = "A clear coat over everything under it (the lobes, and the layers listed before it): glTF's "
            "KHR_materials_clearcoat over any lobe. Its Fresnel reads n_c·v, not v·h, as the README writes it; n_c is "
            "the material's coat_normal_map, else the surface's own normal (unmapped where the lobes have a "
            "normal_map). The emission is dimmed by the coat as the README's \"Emission\" says.";
    m.params = {number("weight", "the coat's weight w (KHR_materials_clearcoat clearcoatFactor)", Range::closed(0, 1), 1,
                       false),
                number("roughness",
                       "the coat's roughness (clearcoatRoughnessFactor); α = roughness², at least 1e-3",
                       Range::closed(0, 1), 0, false)};
    m.cycles = approximate("principled_bsdf's Coat: Cycles layers its coat by the coat's albedo (and tints what lies "
                           "under it), not by w·Fc(n·v)");
    m.pov = none(kMicrofacetPov);
    m.blender_nodes = nodes_none(kLayerNodes);
    m.layer = [](LobeContext& c, const ir::Expr& base) { return coat_over(c, base, kLayerCoat); };
    m.emission_weight = [](const ModelSpec& s, const std::string& lobe, const std::string& function) {
      return coat_emission_weight(s, lobe, function, kLayerCoat);
    };
    m.coated = [](const ModelSpec& s) { return has_coat(s, kLayerCoat); };
    m.gltf_brdf_params = {{kLayerCoat.weight, kGltfCoat.weight}, {kLayerCoat.roughness, kGltfCoat.roughness}};
    m.gltf_brdf_stack = 2;
    m.reciprocal = false;
    m.physics_note = "the weight w Fc reads n·v alone, which is not symmetric in l and v (the README's "
                     "\"Discussion\": \"we compute the microfacet Fresnel term with NdotV instead of VdotH\"); for "
                     "the same reason the albedo at a light's incidence integrates Fc over the views, small where the "
                     "base reflects and near 1 at the grazing views a grazing light's coat highlight goes to: over a "
                     "white Lambert it exceeds 1 towards grazing light (the rows of weight 1 below), although the "
                     "Discussion calls the layering energy conserving, so no bound is claimed";
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "layer";
    m.name = "sheen";
    m.title = "Sheen";
    m.citation = "KHR_materials_sheen, \"Sheen\", \"Sheen distribution\", \"Sheen visibility\" and "
                 "\"Albedo-scaling technique\"";
    m.formula = "ρ' = s S_s + ρ min(1 − max(s) E(n·v), 1 − max(s) E(n·l)), S_s = π D V (n·l) (Charlie, the README's "
                "visibility, α = roughness²), E the sheen's directional albedo";
    m.doc = "A sheen (velvet, cloth, dust) over everything under it: glTF's KHR_materials_sheen over any lobe. What lies "
            "under it is scaled by one minus the sheen's directional albedo at n·v and at n·l, the reciprocal form the "
            "README writes first; E is the fit of docs/gltf.md, its worst error stated there.";
    m.params = {color("color", "the sheen's colour s (KHR_materials_sheen sheenColorFactor; 0: none)",
                      Range::closed(0, 1), {1, 1, 1}),
                number("roughness", "the sheen's roughness (sheenRoughnessFactor); α = roughness², at least 1e-3",
                       Range::closed(0, 1), 0.5, false)};
    m.cycles = approximate("principled_bsdf's Sheen: Cycles' microfiber sheen, another distribution and albedo");
    m.pov = none(kMicrofacetPov);
    m.blender_nodes = nodes_none(kLayerNodes);
    m.layer = [](LobeContext& c, const ir::Expr& base) { return sheen_over(c, base, kLayerSheen); };
    m.gltf_brdf_params = {{kLayerSheen.color, kGltfSheen.color}, {kLayerSheen.roughness, kGltfSheen.roughness}};
    m.gltf_brdf_stack = 1;
    m.reciprocal = true;
    m.physics_note = "over a reciprocal base symmetric: the sheen's D and V are, and so is the scaling min(1 − "
                     "max(s) E(n·v), 1 − max(s) E(n·l)), the README's reciprocal form; the README's visibility is "
                     "not derived from a microfacet model and E is a fit, so no bound on the albedo is claimed";
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "layer";
    m.name = "mix";
    m.title = "Mix with a lobe";
    m.citation = "glTF 2.0 Appendix B, \"General\": mix(a, b, t) = (1 − t) a + t b (MaterialX's mix node, OSL's "
                 "weighted closures)";
    m.formula = "ρ' = (1 − w) ρ + w k ⊗ ρ_lobe";
    m.doc = "Another specular lobe mixed with everything under it by a weight: (1 − w) of what lies under it and w of "
            "the lobe, its own colour k and toon included — two highlights of different shapes, a blend of two "
            "finishes. The lobe may be any specular model whose values read nothing the material holds apart (a "
            "coat, an emission weight, a texture-coordinate frame): gltf_pbr is the material's specular lobe instead.";
    m.params = {number("weight", "w, the lobe's share: 0 none of it, 1 the lobe alone", Range::closed(0, 1), 0.5, false),
                model("lobe", "the specular lobe mixed in: {\"model\": …, its parameters}", "specular", "ggx")};
    m.cycles = approximate("Mix Shader, Fac = weight: the mix exactly, each lobe as close as its own closure");
    m.pov = none(kMicrofacetPov);
    m.blender_nodes = nodes_none("not built: the add-on's panel holds no lobe inside a layer; Generate OSL (Cycles) and "
                                 "the facet POV-Ray engine draw it");
    m.layer = [](LobeContext& c, const ir::Expr& base) {
      const ModelSpec& spec = c.model("lobe");
      LobeContext lobe(spec, c.lobe() + "_lobe", c, c.key() + ".lobe");
      ir::Expr k = lobe.parameter(spec, "color", lobe.lobe() + "_color");
      ir::Expr mixed = c.let("mixed_lobe", k * lobe_rho(lobe));
      return ir::call(terms::mix_by(ir::Type::Color), {base, mixed, c.number("weight")});
    };
    m.reciprocal = true;
    m.energy_conserving = true;
    m.physics_note = "a weighted mean: symmetric where both sides are (here the default GGX lobe over Lambert), and its "
                     "albedo (1 − w) a + w k a_lobe is at most 1 where both albedos are and k ≤ 1";
    all.push_back(m);
  }
}

}  // namespace facet::catalog_detail
