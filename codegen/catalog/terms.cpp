// The terms of MODELS.md, one IR function each. Each is built once and shared,
// so a target prints it once however many models call it.
//
// Guards, all the same on every target (facet sweep checks them):
//  * A cosine that is a power's base is clamped into [0, 1] (ir::unit): GPUs return
//    NaN for pow(x < 0, y), a rounding error can push a cosine a few ulps below 0, and
//    on SwiftShader (WebGL2) a cosine overshoots 1 by at least 8.9e-5: x^n overflowed
//    there at n = 1e6 (docs/float32.md).
//  * sqrt() arguments of the form 1 − c² are clamped to ≥ 0 for the same reason,
//    and 1 − c² is computed as (1 − c)(1 + c), exact near c = 1 in float.
//  * Divisions by n·v, n·l or n·h are safe because the horizon rule
//    (reflectance(): n·l > 0 and n·v > 0, hence n·h > 0) guards every call.
//  * Denominators that are products of small powers (π m² cos⁴θ_h) are floored
//    at kTiny = 1e-30: float's smallest normal is 1.2e-38 and GPUs flush smaller
//    values to 0, which would turn 0/0 into NaN where the numerator underflowed
//    first. The floor only bites for roughness below about 1e-15.
#include <cmath>
#include <utility>

#include "catalog/catalog.h"
#include "core/vec.h"

namespace facet::terms {

using ir::Expr;
using ir::FunctionBuilder;
using ir::FunctionPtr;
using ir::Type;

namespace {
const double kTiny = 1e-30;  // see "Guards" above

// A term whose input may be grey or coloured: built once per type by `Form`.
template <FunctionPtr (*Form)(Type)>
FunctionPtr typed(Type type) {
  static const FunctionPtr f[2] = {Form(Type::Float), Form(Type::Color)};
  return f[type == Type::Color];
}
}  // namespace

// ---------------------------------------------------------------- diffuse

FunctionPtr lambert() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("rho_lambert", "Lambert 1760, \"Photometria\": ρ = n·l");
    Expr NoL = fb.param("NoL");
    return fb.returns(NoL);
  }();
  return f;
}

FunctionPtr minnaert() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("rho_minnaert",
                       "Minnaert 1941, \"The reciprocity principle in lunar photometry\": "
                       "ρ = (n·l)^k · max(n·v, ε)^(k−1)",
                       "max(n·v, ε) keeps (n·v)^(k−1) finite at the limb when k < 1 (MODELS.md); both\n"
                       "cosines are clamped at 1 too, as every power's base is.");
    Expr NoL = fb.param("NoL"), NoV = fb.param("NoV"), k = fb.param("k");
    return fb.returns(pow(unit(NoL), k) * pow(clamp(NoV, kEpsilon, 1.0), k - 1.0));
  }();
  return f;
}

FunctionPtr minnaert_velvet() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("rho_minnaert_velvet",
                       "Losasso, \"Surface Reflection Models\" (NVIDIA), velvet Minnaert: "
                       "ρ = (n·l)^(k+1) · (1 − n·v)^(1−k)",
                       "At k = 1 the limb factor is (1 − n·v)^0 = 1, written out because GPUs "
                       "disagree on pow(0, 0).");
    Expr NoL = fb.param("NoL"), NoV = fb.param("NoV"), k = fb.param("k");
    Expr limb = select(k >= 1.0, 1.0, pow(unit(1.0 - NoV), 1.0 - k));
    return fb.returns(pow(unit(NoL), k + 1.0) * limb);
  }();
  return f;
}

FunctionPtr oren_nayar() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb(
        "rho_oren_nayar",
        "Oren & Nayar 1994, \"Generalization of Lambert's Reflectance Model\": "
        "ρ = (n·l)(A + B [cos φ] sin α tan β)",
        "[cos φ] sin α tan β = max(0, l·v − (n·l)(n·v)) / max(n·l, n·v) exactly, which avoids\n"
        "normalizing the projected vectors; it is 0 where either projection is shorter than ε:\n"
        "|l − n(n·l)| = sin θ_i < ε where cos θ_i > √(1 − ε²), so where max(n·l, n·v) reaches it.");
    Expr NoL = fb.param("NoL"), NoV = fb.param("NoV"), LoV = fb.param("LoV");
    Expr sigma = fb.param("sigma"), q = fb.param("q");
    Expr s2 = fb.let("s2", sigma * sigma);
    Expr A = fb.let("A", 1.0 - 0.5 * s2 / (s2 + q));
    Expr B = fb.let("B", 0.45 * s2 / (s2 + 0.09));
    // cos β, β = min(θ_i, θ_r): the larger cosine, which also divides.
    Expr cos_beta = fb.let("cos_beta", max(NoL, NoV));
    Expr t = fb.let("t", select(cos_beta >= std::sqrt(1.0 - kEpsilon * kEpsilon), 0.0, pos(LoV - NoL * NoV) / cos_beta));
    return fb.returns(NoL * (A + B * t));
  }();
  return f;
}

// ---------------------------------------------------------------- classic lobes

FunctionPtr phong() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("rho_phong",
                       "Phong 1975, \"Illumination for Computer Generated Pictures\": ρ = [r·v]^n",
                       "r·v = 2(n·l)(n·v) − l·v for r = 2(n·l)n − l.");
    Expr NoL = fb.param("NoL"), NoV = fb.param("NoV"), LoV = fb.param("LoV"), n = fb.param("n");
    return fb.returns(pow(unit(2.0 * NoL * NoV - LoV), n));
  }();
  return f;
}

FunctionPtr blinn_phong() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("rho_blinn_phong",
                       "Blinn 1977, \"Models of Light Reflection for Computer Synthesized Pictures\": "
                       "ρ = [n·h]^n");
    Expr NoH = fb.param("NoH"), n = fb.param("n");
    return fb.returns(pow(unit(NoH), n));
  }();
  return f;
}

FunctionPtr schlick_power() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("schlick_power",
                       "Schlick 1994, \"An Inexpensive BRDF Model for Physically-based Rendering\": "
                       "x^n ≈ x / (n − n x + x)");
    Expr x = fb.param("x"), n = fb.param("n");
    Expr c = fb.let("c", unit(x));
    return fb.returns(c / (n - n * c + c));
  }();
  return f;
}

FunctionPtr gaussian() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("rho_gaussian",
                       "Gaussian highlight, as in the lecture notes: ρ = exp(−m · acos([n·h])²)",
                       "θ_h = acos(c) is computed as atan2(√(1 − c²), c): the same angle, but GPU acos\n"
                       "is a low-order polynomial (1.6e-4 absolute error on Mesa llvmpipe).");
    Expr NoH = fb.param("NoH"), m = fb.param("m");
    Expr c = fb.let("c", clamp(NoH, 0.0, 1.0));
    Expr theta = fb.let("theta_h", atan2(sqrt(pos(1.0 - c * c)), c));
    return fb.returns(exp(-m * theta * theta));
  }();
  return f;
}

FunctionPtr heidrich_seidel() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("rho_heidrich_seidel",
                       "Heidrich & Seidel 1998, \"Efficient Rendering of Anisotropic Surfaces Using "
                       "Computer Graphics Hardware\": ρ = [√(1−(l·t)²)√(1−(v·t)²) − (l·t)(v·t)]^n");
    Expr LoT = fb.param("LoT"), VoT = fb.param("VoT"), n = fb.param("n");
    // √a √b as √(a b): one root.
    Expr x = sqrt(pos(1.0 - LoT * LoT) * pos(1.0 - VoT * VoT)) - LoT * VoT;
    return fb.returns(pow(unit(x), n));
  }();
  return f;
}

// ---------------------------------------------------------------- microfacet terms

FunctionPtr distribution_beckmann() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("D_beckmann",
                       "Beckmann & Spizzichino 1963, \"The Scattering of Electromagnetic Waves from "
                       "Rough Surfaces\": D = exp(−tan²θ_h / m²) / (π m² cos⁴θ_h)");
    Expr NoH = fb.param("NoH"), m = fb.param("m");
    Expr c2 = fb.let("c2", NoH * NoH);
    Expr m2 = fb.let("m2", m * m);
    Expr tan2 = fb.let("tan2", pos((1.0 - NoH) * (1.0 + NoH)) / c2);
    // × (−1/m²) rather than −(…)/m²: with m a constant, one multiplication.
    return fb.returns(exp(tan2 * (-1.0 / m2)) / max(kPi * m2 * c2 * c2, kTiny));
  }();
  return f;
}

FunctionPtr distribution_ggx() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("D_ggx",
                       "Walter et al. 2007, \"Microfacet Models for Refraction through Rough Surfaces\" "
                       "(Trowbridge & Reitz 1975): D = α² / (π ((n·h)²(α²−1) + 1)²)");
    Expr NoH = fb.param("NoH"), alpha = fb.param("alpha");
    Expr a2 = fb.let("a2", alpha * alpha);
    // (n·h)²(α² − 1) + 1, without the cancellation of 1 − (n·h)² in float.
    Expr d = fb.let("d", (1.0 - NoH) * (1.0 + NoH) + a2 * NoH * NoH);
    return fb.returns(a2 / max(kPi * d * d, kTiny));
  }();
  return f;
}

FunctionPtr distribution_trowbridge_reitz() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("D_trowbridge_reitz",
                       "Blinn 1977, after Trowbridge & Reitz 1975, as printed (not normalized): "
                       "D = (c² / ((n·h)²(c²−1) + 1))²");
    Expr NoH = fb.param("NoH"), c = fb.param("c");
    Expr c2 = fb.let("c2", c * c);
    // (n·h)²(c² − 1) + 1, without the cancellation of 1 − (n·h)² in float.
    Expr r = fb.let("r", c2 / max((1.0 - NoH) * (1.0 + NoH) + c2 * NoH * NoH, kTiny));
    return fb.returns(r * r);
  }();
  return f;
}

FunctionPtr geometry_v_cavity() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("G_v_cavity",
                       "Cook & Torrance 1982, \"A Reflectance Model for Computer Graphics\": "
                       "G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h))");
    Expr NoL = fb.param("NoL"), NoV = fb.param("NoV"), NoH = fb.param("NoH"), VoH = fb.param("VoH");
    // 2(n·h)/(v·h) ≥ 0 scales both: min(k n·v, k n·l) = k min(n·v, n·l).
    return fb.returns(min(1.0, 2.0 * NoH * min(NoV, NoL) / VoH));
  }();
  return f;
}

namespace {
FunctionPtr fresnel_schlick_form(Type type) {
  FunctionBuilder fb(type == Type::Float ? "F_schlick" : "F_schlick_rgb",
                     "Schlick 1994, \"An Inexpensive BRDF Model for Physically-based Rendering\": "
                     "F = f0 + (1 − f0)(1 − v·h)^5",
                     "The base is clamped at 0 (v·h a hair above 1); v·h below 0 by rounding is harmless.");
  Expr f0 = fb.param("f0", type), VoH = fb.param("VoH");
  return fb.returns(f0 + (1.0 - f0) * pow(pos(1.0 - VoH), 5.0));
}

// Smith's s_l and s_v for GGX, s_x = √(α² + (1 − α²)x²), both visibility forms' lets: s_x² summed
// as α²·max(1 − x², 0) + x² (see V_smith_ggx's note).
std::pair<Expr, Expr> smith_roots(FunctionBuilder& fb, const Expr& NoL, const Expr& NoV, const Expr& alpha) {
  Expr a2 = fb.let("a2", alpha * alpha);
  Expr sl = fb.let("s_l", sqrt(a2 * max(1.0 - NoL * NoL, 0.0) + NoL * NoL));
  Expr sv = fb.let("s_v", sqrt(a2 * max(1.0 - NoV * NoV, 0.0) + NoV * NoV));
  return {sl, sv};
}
}  // namespace

FunctionPtr visibility_smith_ggx() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("V_smith_ggx",
                       "Smith 1967 for GGX (Walter et al. 2007), separable, as a visibility term: "
                       "V = G1(n·l) G1(n·v) / (4 (n·l)(n·v)) = 1 / ((n·l + s_l)(n·v + s_v)), "
                       "s_x = √(α² + (1−α²)x²) = √(α²(1 − x²) + x²)",
                       "The 2·2/4 of G1's numerators and n·l n·v cancel: no division by n·v, which the\n"
                       "form ρ = π D G F / (4 n·v) needs. s_x² is summed as α²·max(1 − x², 0) + x², two\n"
                       "terms ≥ 0: α² + (1 − α²)x² cancels at x ≈ 1 for large α (α = 1e4: 1e8 − 1e8 in\n"
                       "float32), and SwiftShader rounded it below 0, a NaN under the root.");
    Expr NoL = fb.param("NoL"), NoV = fb.param("NoV"), alpha = fb.param("alpha");
    const auto [sl, sv] = smith_roots(fb, NoL, NoV, alpha);
    return fb.returns(1.0 / ((NoL + sl) * (NoV + sv)));
  }();
  return f;
}

FunctionPtr fresnel_schlick(Type f0) { return typed<fresnel_schlick_form>(f0); }

FunctionPtr visibility_smith_ggx_correlated() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("V_smith_ggx_correlated",
                       "Heitz 2014, height-correlated Smith for GGX, as glTF 2.0 Appendix B \"Specular BRDF\" "
                       "writes it: V = G / (4 |n·l| |n·v|) = 1 / (2 (|n·v| s_l + |n·l| s_v)), "
                       "s_x = √(α² + (1−α²)x²)",
                       "χ⁺(h·l) χ⁺(h·v) is 1: h bisects l and v, so h·l = h·v > 0 wherever the horizon rule\n"
                       "lets the lobe be seen. s_x² is summed as α²·max(1 − x², 0) + x², as in V_smith_ggx.");
    Expr NoL = fb.param("NoL"), NoV = fb.param("NoV"), alpha = fb.param("alpha");
    const auto [sl, sv] = smith_roots(fb, NoL, NoV, alpha);
    return fb.returns(0.5 / (NoV * sl + NoL * sv));
  }();
  return f;
}

FunctionPtr distribution_ggx_anisotropic() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("D_ggx_anisotropic",
                       "KHR_materials_anisotropy, \"Anisotropy\" (Burley 2012): D = 1 / (π α_t α_b ((h·t)²/α_t² + "
                       "(h·b)²/α_b² + (h·n)²)²), as the README's D_GGX_anisotropic writes it",
                       "a2 = α_t α_b, f = (α_b h·t, α_t h·b, a2 n·h), w2 = a2 / |f|², D = a2 w2² / π: the same\n"
                       "value, without dividing by α_t² or α_b².");
    Expr NoH = fb.param("NoH"), HoT = fb.param("HoT"), HoB = fb.param("HoB");
    Expr at = fb.param("alpha_t"), ab = fb.param("alpha_b");
    Expr a2 = fb.let("a2", at * ab);
    Expr ft = ab * HoT, fb_ = at * HoB, fn = a2 * NoH;
    Expr w2 = fb.let("w2", a2 / max(ft * ft + fb_ * fb_ + fn * fn, kTiny));
    return fb.returns(a2 * w2 * w2 / kPi);
  }();
  return f;
}

FunctionPtr visibility_smith_ggx_correlated_anisotropic() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("V_smith_ggx_correlated_anisotropic",
                       "KHR_materials_anisotropy, \"Implementation\" (Heitz 2014, anisotropic height-correlated "
                       "Smith): V = 0.5 / (n·l |(α_t v·t, α_b v·b, n·v)| + n·v |(α_t l·t, α_b l·b, n·l)|)",
                       "The README's sample clamps V to [0, 1]; Appendix B's isotropic V, which this is at\n"
                       "α_t = α_b, has no clamp, and neither has this one.");
    Expr NoL = fb.param("NoL"), NoV = fb.param("NoV");
    Expr LoT = fb.param("LoT"), LoB = fb.param("LoB"), VoT = fb.param("VoT"), VoB = fb.param("VoB");
    Expr at = fb.param("alpha_t"), ab = fb.param("alpha_b");
    Expr gv = fb.let("ggx_v", NoL * sqrt(sq(at * VoT) + sq(ab * VoB) + NoV * NoV));
    Expr gl = fb.let("ggx_l", NoV * sqrt(sq(at * LoT) + sq(ab * LoB) + NoL * NoL));
    return fb.returns(0.5 / (gv + gl));
  }();
  return f;
}

FunctionPtr fresnel_weight() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("fresnel_w",
                       "glTF 2.0 Appendix B \"Fresnel\" (Schlick 1994): fresnel_w = (1 − |v·h|)^5, the weight "
                       "of f90 against f0",
                       "The base is clamped at 0 (v·h a hair above 1).");
    Expr VoH = fb.param("VoH");
    return fb.returns(pow(pos(1.0 - abs(VoH)), 5.0));
  }();
  return f;
}

namespace {
FunctionPtr fresnel_schlick_f90_form(Type type) {
  FunctionBuilder fb(type == Type::Float ? "F_schlick_f90" : "F_schlick_f90_rgb",
                     "KHR_materials_specular, \"Implementation\": F = f0 + (f90 − f0) fresnel_w, "
                     "mix(f0, f90, fresnel_w) (Schlick 1994 with f90 free)");
  Expr f0 = fb.param("f0", type), f90 = fb.param("f90"), w = fb.param("w");
  return fb.returns(f0 + (f90 - f0) * w);
}

// A grey F is its own max: F_max is then F. A grey base keeps the result one number.
FunctionPtr fresnel_mix_form(Type F_type, Type base_type) {
  const bool grey = F_type == Type::Float;
  FunctionBuilder fb(std::string("fresnel_mix") + (grey ? "" : "_rgb") + (base_type == Type::Float ? "" : "_base_rgb"),
                     "glTF 2.0 Appendix B \"Fresnel\" and KHR_materials_specular, \"Implementation\": "
                     "F ⊗ layer + (1 − max(F)) base, the base (diffuse) weighted by what the layer "
                     "(specular) does not reflect",
                     grey ? "F is grey: max(F) is F."
                          : "F_max is max(F.r, F.g, F.b), passed in: the material knows it in closed form.");
  Expr F = fb.param("F", F_type);
  Expr F_max = grey ? F : fb.param("F_max");
  Expr layer = fb.param("layer"), base = fb.param("base", base_type);
  return fb.returns(F * layer + (1.0 - F_max) * base);
}

FunctionPtr conductor_fresnel_form(Type type) {
  FunctionBuilder fb(type == Type::Float ? "conductor_fresnel" : "conductor_fresnel_rgb",
                     "glTF 2.0 Appendix B \"Fresnel\": bsdf ⊗ (f0 + (1 − f0) fresnel_w), a metal's tint");
  Expr f0 = fb.param("f0", type), w = fb.param("w"), bsdf = fb.param("bsdf");
  return fb.returns(bsdf * (f0 + (1.0 - f0) * w));
}

FunctionPtr mix_by_form(Type type) {
  FunctionBuilder fb(type == Type::Float ? "mix_by" : "mix_by_rgb",
                     "glTF 2.0 Appendix B \"General\": mix(a, b, t) = (1 − t) a + t b, the metallic blend "
                     "of the dielectric and the metal");
  Expr a = fb.param("a", type), b = fb.param("b", type), t = fb.param("t");
  return fb.returns((1.0 - t) * a + t * b);
}
}  // namespace

FunctionPtr fresnel_schlick_f90(Type f0) { return typed<fresnel_schlick_f90_form>(f0); }

FunctionPtr fresnel_mix(Type F, Type base) {
  static const FunctionPtr f[2][2] = {{fresnel_mix_form(Type::Float, Type::Float), fresnel_mix_form(Type::Float, Type::Color)},
                                      {fresnel_mix_form(Type::Color, Type::Float), fresnel_mix_form(Type::Color, Type::Color)}};
  return f[F == Type::Color][base == Type::Color];
}

FunctionPtr conductor_fresnel(Type f0) { return typed<conductor_fresnel_form>(f0); }

FunctionPtr mix_by(Type type) { return typed<mix_by_form>(type); }

FunctionPtr fresnel_exact() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("F_exact",
                       "Cook & Torrance 1982, unpolarized dielectric Fresnel: "
                       "F = ½ (g−c)²/(g+c)² (1 + ((c(g+c)−1)/(c(g−c)+1))²)",
                       "g = √((η² − 1) + c²), for η > 1: then g > 0, g + c > 0 and no total internal reflection.");
    Expr ior = fb.param("ior"), c = fb.param("VoH");
    Expr g = fb.let("g", sqrt((ior * ior - 1.0) + c * c));
    Expr a = fb.let("a", (g - c) / (g + c));
    Expr b = fb.let("b", (c * (g + c) - 1.0) / (c * (g - c) + 1.0));
    return fb.returns(0.5 * a * a * (1.0 + b * b));
  }();
  return f;
}

FunctionPtr fresnel_exact_tir() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("F_exact_tir",
                       "Cook & Torrance 1982, unpolarized dielectric Fresnel: "
                       "F = ½ (g−c)²/(g+c)² (1 + ((c(g+c)−1)/(c(g−c)+1))²)",
                       "g = √(η² + c² − 1), for η ≤ 1: total internal reflection (η² + c² − 1 < 0) gives F = 1.");
    Expr ior = fb.param("ior"), c = fb.param("VoH");
    Expr g2 = fb.let("g2", ior * ior + c * c - 1.0);
    Expr g = fb.let("g", sqrt(pos(g2)));
    // g + c = 0 only for η = 1 at c = 0 (l = −v): there a = 0/0; floored, a = 0.
    Expr a = fb.let("a", (g - c) / max(g + c, kTiny));
    Expr b = fb.let("b", (c * (g + c) - 1.0) / (c * (g - c) + 1.0));
    return fb.returns(select(g2 < 0.0, 1.0, 0.5 * a * a * (1.0 + b * b)));
  }();
  return f;
}

namespace {
// F is a Float where the Fresnel term is grey (or 1), a Color otherwise.
FunctionPtr microfacet_form(Type type) {
  FunctionBuilder fb(type == Type::Float ? "rho_microfacet" : "rho_microfacet_rgb",
                     "Cook & Torrance 1982, microfacet reflection: ρ = π f_r (n·l) = π D G F / (4 (n·v))");
  Expr D = fb.param("D"), G = fb.param("G"), F = fb.param("F", type), NoV = fb.param("NoV");
  // π/4 of two literals: a compiler folds it, and the 4 costs no multiplication.
  return fb.returns(Expr(kPi) / 4.0 * D * G * F / NoV);
}
FunctionPtr blinn_form(Type type) {
  FunctionBuilder fb(type == Type::Float ? "rho_blinn" : "rho_blinn_rgb",
                     "Blinn 1977, \"Models of Light Reflection for Computer Synthesized Pictures\", "
                     "as printed: ρ = D G F / (n·v)");
  Expr D = fb.param("D"), G = fb.param("G"), F = fb.param("F", type), NoV = fb.param("NoV");
  return fb.returns(D * G * F / NoV);
}
}  // namespace

namespace {
FunctionPtr microfacet_visibility_form(Type type) {
  FunctionBuilder fb(type == Type::Float ? "rho_microfacet_v" : "rho_microfacet_v_rgb",
                     "Cook & Torrance 1982 with the visibility V = G / (4 (n·l)(n·v)): ρ = π D V F (n·l)");
  Expr D = fb.param("D"), V = fb.param("V"), F = fb.param("F", type), NoL = fb.param("NoL");
  return fb.returns(kPi * D * V * F * NoL);
}
}  // namespace

FunctionPtr microfacet_visibility(Type F) { return typed<microfacet_visibility_form>(F); }

FunctionPtr microfacet(Type F) { return typed<microfacet_form>(F); }

FunctionPtr blinn(Type F) { return typed<blinn_form>(F); }

// ---------------------------------------------------------------- Ward

namespace {
FunctionPtr ward_form(const char* name, const char* citation, bool nvidia) {
  FunctionBuilder fb(name, citation);
  Expr NoL = fb.param("NoL"), NoV = fb.param("NoV"), NoH = fb.param("NoH");
  Expr HoT = fb.param("HoT"), HoB = fb.param("HoB");
  Expr ax = fb.param("alpha_x"), ay = fb.param("alpha_y");
  Expr tx = HoT / ax, ty = HoB / ay;
  Expr e = fb.let("e", tx * tx + ty * ty);
  Expr lobe = nvidia ? exp(-2.0 * e / (1.0 + NoH)) : exp(-e / (NoH * NoH));
  return fb.returns(NoL / (4.0 * ax * ay * sqrt(NoL * NoV)) * lobe);
}
}  // namespace

FunctionPtr ward() {
  static const FunctionPtr f =
      ward_form("rho_ward",
                "Ward 1992, \"Measuring and Modeling Anisotropic Reflection\": "
                "ρ = (n·l) / (4 αx αy √((n·l)(n·v))) · exp(−((h·t/αx)² + (h·b/αy)²) / (n·h)²)",
                false);
  return f;
}

FunctionPtr ward_nvidia() {
  static const FunctionPtr f =
      ward_form("rho_ward_nvidia",
                "Losasso, \"Surface Reflection Models\" (NVIDIA), Ward's model as printed: "
                "exponent −2((h·t/αx)² + (h·b/αy)²) / (1 + n·h)",
                true);
  return f;
}

// ---------------------------------------------------------------- modifiers and lights

namespace {
FunctionPtr toon_form(Type type) {
  FunctionBuilder fb(type == Type::Float ? "toon" : "toon_rgb",
                     "Toon shading (Lake et al. 2000, \"Stylized Rendering Techniques for Scalable "
                     "Real-Time 3D Animation\"): ρ' = smoothstep(cutoff − width/2, cutoff + width/2, ρ)");
  Expr rho = fb.param("rho", type), cutoff = fb.param("cutoff"), width = fb.param("width");
  Expr t = fb.let("s", clamp((rho - (cutoff - 0.5 * width)) / width, 0.0, 1.0));
  return fb.returns(t * t * (3.0 - 2.0 * t));
}
FunctionPtr toon_hard_form(Type type) {
  FunctionBuilder fb(type == Type::Float ? "toon_hard" : "toon_hard_rgb",
                     "Toon shading with width 0: ρ' = 1 where ρ ≥ cutoff, else 0");
  Expr rho = fb.param("rho", type), cutoff = fb.param("cutoff");
  return fb.returns(step(cutoff, rho));
}
}  // namespace

FunctionPtr toon(Type type) { return typed<toon_form>(type); }

FunctionPtr toon_hard(Type type) { return typed<toon_hard_form>(type); }

FunctionPtr attenuation_inverse_square() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("attenuation_inverse_square", "Inverse-square law: att(d) = 1/d²");
    Expr d = fb.param("d");
    return fb.returns(1.0 / (d * d));
  }();
  return f;
}

FunctionPtr attenuation_polynomial() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("attenuation_polynomial",
                       "Foley, van Dam, Feiner & Hughes 1990, eq. 16.8: att(d) = min(1, 1/(c1 + c2 d + c3 d²))",
                       "OpenGL's and Direct3D's fixed-function law is the same polynomial without the min(1, ·).");
    Expr d = fb.param("d"), c1 = fb.param("c1"), c2 = fb.param("c2"), c3 = fb.param("c3");
    return fb.returns(min(1.0, 1.0 / (c1 + c2 * d + c3 * d * d)));
  }();
  return f;
}

FunctionPtr attenuation_inverse_square_range() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("attenuation_inverse_square_range",
                       "KHR_lights_punctual (Khronos 2018), \"Range Property\": att(d) = clamp(1 − (d/r)⁴, 0, 1) / d²",
                       "The inverse-square law, windowed to 0 at the light's range r.");
    Expr d = fb.param("d"), r = fb.param("range");
    Expr x = fb.let("x", d / r);
    Expr x2 = fb.let("x2", x * x);
    return fb.returns(clamp(1.0 - x2 * x2, 0.0, 1.0) / (d * d));
  }();
  return f;
}

FunctionPtr spot_cone() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("spot_cone",
                       "OpenGL 1.0 spotlight: spot = [−l·s]^exponent inside the cutoff cone, 0 outside",
                       "SoL = −l·s, the cosine between the spot axis and the direction to the point.");
    Expr SoL = fb.param("SoL"), cos_cutoff = fb.param("cos_cutoff"), exponent = fb.param("exponent");
    return fb.returns(select(SoL >= cos_cutoff, pow(unit(SoL), exponent), 0.0));
  }();
  return f;
}

}  // namespace facet::terms
